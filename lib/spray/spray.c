/* spray.c — the droplet system of the spray module: parameters,
 * allocation, parcels, accessors, totals and moments.  The operators live
 * in spray_collide.c (collisions, coalescence), spray_tab.c and
 * spray_reitz.c (breakup); the exact solutions in spray_exact.c. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_randist.h>

#include <smolbridge/langevin.h>
#include <smolbridge/spray.h>

#include "common/internal.h"
#include "spray_internal.h"

void sb_spray_params_default(sb_spray_params *p)
{
  if (!p)
    return;
  memset(p, 0, sizeof *p);
  p->method = SB_SPRAY_BIRD;
  p->cross = SB_SPRAY_HARD_SPHERE;
  p->select = SB_SPRAY_MAJORANT;
  p->volume = 1.0;
  p->rho_l = 1000.0;
  p->weight = 1.0;
  p->B0 = 1.0;
  p->theta_cr = 0.0;
  p->coal = SB_SPRAY_COAL_THETA;
  p->sigma = 0.072;
  p->capacity = 1024;
}

static int from_name(const char *name, const char *const *names, int n,
                     int *out, const char *func)
{
  if (!name)
    return sbi_error(SB_EINVAL, func, "NULL name");
  for (int k = 0; k < n; k++)
    if (!strcmp(name, names[k])) {
      *out = k;
      return SB_SUCCESS;
    }
  return sbi_error(SB_EINVAL, func, "unknown name '%s' (valid: %s, %s)",
                   name, names[0], names[1]);
}

int sb_spray_method_from_name(const char *name, sb_spray_method *m)
{
  static const char *const names[] = {"bird", "nanbu"};
  int k = 0, st = from_name(name, names, 2, &k, __func__);
  if (!st && m)
    *m = (sb_spray_method)k;
  return st;
}

int sb_spray_cross_from_name(const char *name, sb_spray_cross *c)
{
  static const char *const names[] = {"hard-sphere", "maxwell"};
  int k = 0, st = from_name(name, names, 2, &k, __func__);
  if (!st && c)
    *c = (sb_spray_cross)k;
  return st;
}

int sb_spray_select_from_name(const char *name, sb_spray_select *s)
{
  static const char *const names[] = {"majorant", "ntc"};
  int k = 0, st = from_name(name, names, 2, &k, __func__);
  if (!st && s)
    *s = (sb_spray_select)k;
  return st;
}

static int check_params(const sb_spray_params *p, const char *func)
{
  if (!p)
    return sbi_error(SB_EINVAL, func, "NULL params");
  if (p->method != SB_SPRAY_BIRD && p->method != SB_SPRAY_NANBU)
    return sbi_error(SB_EINVAL, func, "method %d unknown", (int)p->method);
  if (p->cross != SB_SPRAY_HARD_SPHERE && p->cross != SB_SPRAY_MAXWELL)
    return sbi_error(SB_EINVAL, func, "cross %d unknown", (int)p->cross);
  if (p->select != SB_SPRAY_MAJORANT && p->select != SB_SPRAY_NTC)
    return sbi_error(SB_EINVAL, func, "select %d unknown", (int)p->select);
  if (p->select == SB_SPRAY_NTC && p->method != SB_SPRAY_BIRD)
    return sbi_error(SB_EINVAL, func, "select = ntc needs method = bird");
  if (!(p->volume > 0) || !isfinite(p->volume))
    return sbi_error(SB_EINVAL, func, "volume = %g: must be finite > 0",
                     p->volume);
  if (!(p->rho_l > 0) || !isfinite(p->rho_l))
    return sbi_error(SB_EINVAL, func, "rho_l = %g: must be finite > 0",
                     p->rho_l);
  if (!(p->weight > 0) || !isfinite(p->weight))
    return sbi_error(SB_EINVAL, func, "weight = %g: must be finite > 0",
                     p->weight);
  if (p->cross == SB_SPRAY_MAXWELL && (!(p->B0 > 0) || !isfinite(p->B0)))
    return sbi_error(SB_EINVAL, func, "B0 = %g: must be finite > 0", p->B0);
  if (!(p->theta_cr >= 0 && p->theta_cr <= 0.5 * SBI_PI))
    return sbi_error(SB_EINVAL, func, "theta_cr = %g: must be in [0, pi/2]",
                     p->theta_cr);
  if (p->coal != SB_SPRAY_COAL_THETA && p->coal != SB_SPRAY_COAL_OROURKE)
    return sbi_error(SB_EINVAL, func, "coal = %d: unknown model", p->coal);
  if (p->coal == SB_SPRAY_COAL_OROURKE &&
      (!(p->sigma > 0) || !isfinite(p->sigma)))
    return sbi_error(SB_EINVAL, func, "sigma = %g: must be finite > 0 for "
                     "the O'Rourke coalescence boundary", p->sigma);
  return SB_SUCCESS;
}

sb_spray *sb_spray_alloc(const sb_spray_params *p)
{
  if (check_params(p, __func__))
    return NULL;
  sb_spray *s = calloc(1, sizeof *s);
  if (!s) {
    sbi_error(SB_ENOMEM, __func__, "out of memory");
    return NULL;
  }
  s->p = *p;
  if (sbi_spray_reserve(s, p->capacity > 0 ? p->capacity : 1, __func__)) {
    sb_spray_free(s);
    return NULL;
  }
  return s;
}

void sb_spray_free(sb_spray *s)
{
  if (!s)
    return;
  free(s->v);
  free(s->r);
  free(s->w);
  free(s->y);
  free(s->yd);
  free(s->shed);
  free(s->formed);
  free(s->tag);
  free(s);
}

const sb_spray_params *sb_spray_get_params(const sb_spray *s)
{
  return s ? &s->p : NULL;
}

/* realloc one array to `cap` elements of `size` bytes */
static int grow(void **a, size_t cap, size_t size)
{
  void *q = realloc(*a, cap * size);
  if (!q)
    return -1;
  *a = q;
  return 0;
}

int sbi_spray_reserve(sb_spray *s, size_t extra, const char *func)
{
  if (s->n + extra <= s->cap && s->v)
    return SB_SUCCESS;
  size_t cap = s->cap ? s->cap : 16;
  while (cap < s->n + extra) {
    if (cap > ((size_t)-1) / 48)
      return sbi_error(SB_ENOMEM, func, "too many parcels");
    cap *= 2;
  }
  if (grow((void **)&s->v, cap, 3 * sizeof(double)) ||
      grow((void **)&s->r, cap, sizeof(double)) ||
      grow((void **)&s->w, cap, sizeof(double)) ||
      grow((void **)&s->y, cap, sizeof(double)) ||
      grow((void **)&s->yd, cap, sizeof(double)) ||
      grow((void **)&s->shed, cap, sizeof(double)) ||
      grow((void **)&s->formed, cap, sizeof(unsigned char)) ||
      grow((void **)&s->tag, cap, sizeof(int)))
    return sbi_error(SB_ENOMEM, func, "out of memory (%zu parcels)", cap);
  s->cap = cap;
  return SB_SUCCESS;
}

size_t sbi_spray_push(sb_spray *s, const double v[3], double r, double w,
                      int tag)
{
  size_t i = s->n++;
  memcpy(s->v + 3 * i, v, 3 * sizeof(double));
  s->r[i] = r;
  s->w[i] = s->p.method == SB_SPRAY_BIRD ? s->p.weight : w;
  s->y[i] = s->yd[i] = s->shed[i] = 0.0;
  s->formed[i] = 0;
  s->tag[i] = tag;
  return i;
}

void sbi_spray_remove(sb_spray *s, size_t i)
{
  size_t last = --s->n;
  if (i == last)
    return;
  memcpy(s->v + 3 * i, s->v + 3 * last, 3 * sizeof(double));
  s->r[i] = s->r[last];
  s->w[i] = s->w[last];
  s->y[i] = s->y[last];
  s->yd[i] = s->yd[last];
  s->shed[i] = s->shed[last];
  s->formed[i] = s->formed[last];
  s->tag[i] = s->tag[last];
}

int sb_spray_add(sb_spray *s, const double v[3], double r, double w, int tag,
                 size_t *index)
{
  if (!s || !v)
    return sbi_error(SB_EINVAL, __func__, "NULL spray or velocity");
  if (!(r > 0) || !isfinite(r))
    return sbi_error(SB_EINVAL, __func__, "r = %g: must be finite > 0", r);
  if (s->p.method == SB_SPRAY_NANBU && (!(w > 0) || !isfinite(w)))
    return sbi_error(SB_EINVAL, __func__, "w = %g: must be finite > 0", w);
  for (int k = 0; k < 3; k++)
    if (!isfinite(v[k]))
      return sbi_error(SB_EINVAL, __func__, "v[%d] = %g: not finite", k,
                       v[k]);
  int st = sbi_spray_reserve(s, 1, __func__);
  if (st)
    return st;
  size_t i = sbi_spray_push(s, v, r, w, tag);
  if (index)
    *index = i;
  return SB_SUCCESS;
}

int sb_spray_add_maxwellian(sb_spray *s, size_t n, double r, double w,
                            int tag, double T, const double u[3],
                            gsl_rng *rng)
{
  if (!s || !rng)
    return sbi_error(SB_EINVAL, __func__, "NULL spray or rng");
  if (!(r > 0) || !isfinite(r))
    return sbi_error(SB_EINVAL, __func__, "r = %g: must be finite > 0", r);
  if (!(T >= 0) || !isfinite(T))
    return sbi_error(SB_EINVAL, __func__, "T = %g: must be finite >= 0", T);
  if (s->p.method == SB_SPRAY_NANBU && (!(w > 0) || !isfinite(w)))
    return sbi_error(SB_EINVAL, __func__, "w = %g: must be finite > 0", w);
  int st = sbi_spray_reserve(s, n, __func__);
  if (st)
    return st;
  double sd = sqrt(SB_BOLTZMANN * T / sbi_spray_mass(s->p.rho_l, r));
  for (size_t k = 0; k < n; k++) {
    double v[3];
    for (int d = 0; d < 3; d++)
      v[d] = (u ? u[d] : 0.0) + gsl_ran_gaussian_ziggurat(rng, sd);
    sbi_spray_push(s, v, r, w, tag);
  }
  return SB_SUCCESS;
}

void sb_spray_clear(sb_spray *s)
{
  if (s)
    s->n = 0;
}

size_t sb_spray_count(const sb_spray *s) { return s ? s->n : 0; }
double sb_spray_time(const sb_spray *s) { return s ? s->t : NAN; }
const double *sb_spray_velocities(const sb_spray *s) { return s ? s->v : NULL; }
const double *sb_spray_radii(const sb_spray *s) { return s ? s->r : NULL; }
const double *sb_spray_weights(const sb_spray *s) { return s ? s->w : NULL; }
const int *sb_spray_tags(const sb_spray *s) { return s ? s->tag : NULL; }
const double *sb_spray_tab_y(const sb_spray *s) { return s ? s->y : NULL; }
const double *sb_spray_tab_ydot(const sb_spray *s) { return s ? s->yd : NULL; }
const double *sb_spray_shed_volume(const sb_spray *s)
{
  return s ? s->shed : NULL;
}

int sb_spray_set_velocity(sb_spray *s, size_t i, const double v[3])
{
  if (!s || !v || i >= s->n)
    return sbi_error(SB_EINVAL, __func__, "NULL argument or index %zu out "
                     "of range", i);
  for (int k = 0; k < 3; k++)
    if (!isfinite(v[k]))
      return sbi_error(SB_EINVAL, __func__, "v[%d] not finite", k);
  memcpy(s->v + 3 * i, v, 3 * sizeof(double));
  return SB_SUCCESS;
}

int sb_spray_set_tab(sb_spray *s, size_t i, double y, double ydot)
{
  if (!s || i >= s->n || !isfinite(y) || !isfinite(ydot))
    return sbi_error(SB_EINVAL, __func__, "NULL spray, index %zu out of "
                     "range or non-finite state", i);
  s->y[i] = y;
  s->yd[i] = ydot;
  return SB_SUCCESS;
}

int sb_spray_get_totals(const sb_spray *s, sb_spray_totals *t)
{
  if (!s || !t)
    return sbi_error(SB_EINVAL, __func__, "NULL argument");
  sbi_ksum num = {0, 0}, mass = {0, 0}, en = {0, 0}, vol = {0, 0};
  sbi_ksum mom[3] = {{0, 0}, {0, 0}, {0, 0}};
  const double c = (4.0 / 3.0) * SBI_PI;
  for (size_t i = 0; i < s->n; i++) {
    double w = s->w[i], r3 = s->r[i] * s->r[i] * s->r[i];
    double m = s->p.rho_l * c * r3;
    const double *v = s->v + 3 * i;
    sbi_ksum_add(&num, w);
    sbi_ksum_add(&mass, w * m);
    sbi_ksum_add(&vol, w * c * r3);
    sbi_ksum_add(&vol, s->shed[i]);
    sbi_ksum_add(&en, 0.5 * w * m * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]));
    for (int k = 0; k < 3; k++)
      sbi_ksum_add(&mom[k], w * m * v[k]);
  }
  t->number = sbi_ksum_get(&num);
  t->mass = sbi_ksum_get(&mass);
  t->energy = sbi_ksum_get(&en);
  t->volume = sbi_ksum_get(&vol);
  for (int k = 0; k < 3; k++)
    t->momentum[k] = sbi_ksum_get(&mom[k]);
  return SB_SUCCESS;
}

double sb_spray_velocity_moment(const sb_spray *s, int k, const double u[3],
                                int tag)
{
  if (!s || k < 0) {
    sbi_error(SB_EINVAL, __func__, "NULL spray or k < 0");
    return NAN;
  }
  sbi_ksum num = {0, 0}, sum = {0, 0};
  for (size_t i = 0; i < s->n; i++) {
    if (tag >= 0 && s->tag[i] != tag)
      continue;
    const double *v = s->v + 3 * i;
    double d2 = 0;
    for (int q = 0; q < 3; q++) {
      double d = v[q] - (u ? u[q] : 0.0);
      d2 += d * d;
    }
    double p = k % 2 ? sqrt(d2) : 1.0;
    for (int q = 0; q < k / 2; q++)
      p *= d2;
    sbi_ksum_add(&num, s->w[i]);
    sbi_ksum_add(&sum, s->w[i] * p);
  }
  double nn = sbi_ksum_get(&num);
  return nn > 0 ? sbi_ksum_get(&sum) / nn : NAN;
}

double sb_spray_temperature(const sb_spray *s, int tag)
{
  if (!s) {
    sbi_error(SB_EINVAL, __func__, "NULL spray");
    return NAN;
  }
  sbi_ksum num = {0, 0}, mass = {0, 0}, e2 = {0, 0};
  sbi_ksum p[3] = {{0, 0}, {0, 0}, {0, 0}};
  for (size_t i = 0; i < s->n; i++) {
    if (tag >= 0 && s->tag[i] != tag)
      continue;
    double wm = s->w[i] * sbi_spray_mass(s->p.rho_l, s->r[i]);
    const double *v = s->v + 3 * i;
    sbi_ksum_add(&num, s->w[i]);
    sbi_ksum_add(&mass, wm);
    sbi_ksum_add(&e2, wm * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]));
    for (int q = 0; q < 3; q++)
      sbi_ksum_add(&p[q], wm * v[q]);
  }
  double nn = sbi_ksum_get(&num), mm = sbi_ksum_get(&mass);
  if (!(nn > 0))
    return NAN;
  /* sum w m |v - u|^2 = sum w m |v|^2 - |P|^2 / M */
  double p2 = 0;
  for (int q = 0; q < 3; q++) {
    double pq = sbi_ksum_get(&p[q]);
    p2 += pq * pq;
  }
  return (sbi_ksum_get(&e2) - p2 / mm) / (3.0 * SB_BOLTZMANN * nn);
}

int sb_spray_get_stats(const sb_spray *s, sb_spray_stats *st)
{
  if (!s || !st)
    return sbi_error(SB_EINVAL, __func__, "NULL argument");
  *st = s->st;
  return SB_SUCCESS;
}

void sb_spray_reset_stats(sb_spray *s)
{
  if (s)
    memset(&s->st, 0, sizeof s->st);
}

void sb_spray_set_observer(sb_spray *s, sb_spray_event_fn fn, void *ctx)
{
  if (!s)
    return;
  s->ev = fn;
  s->evctx = ctx;
}

void sbi_spray_perp_dir(const double e[3], gsl_rng *rng, double n[3])
{
  /* orthonormal pair (a, b) perpendicular to e, then a random angle */
  double a[3];
  if (fabs(e[0]) < 0.9) {
    a[0] = 0;
    a[1] = e[2];
    a[2] = -e[1];
  } else {
    a[0] = -e[2];
    a[1] = 0;
    a[2] = e[0];
  }
  double na = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
  for (int k = 0; k < 3; k++)
    a[k] /= na;
  double b[3] = {e[1] * a[2] - e[2] * a[1], e[2] * a[0] - e[0] * a[2],
                 e[0] * a[1] - e[1] * a[0]};
  double x, y;
  gsl_ran_dir_2d(rng, &x, &y);
  for (int k = 0; k < 3; k++)
    n[k] = x * a[k] + y * b[k];
}
