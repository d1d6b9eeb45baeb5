/* engine_firsthit.c — first-contact observer (smolbridge/engine_firsthit.h):
 * a set of pair ids (engine_idmap.c) around a detector, counts per
 * species pair, each particle's counted contacts (a map of the same kind)
 * for the variance of the counts, and the Smoluchowski (1917)
 * first-contact estimator of the kernel with its Garwood interval. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <smolbridge/engine_firsthit.h>
#include <smolbridge/stats.h>

#include "common/internal.h"
#include "engine_internal.h"
#include "engine_firsthit_state.h"

#define PI 3.14159265358979323846

/* 1 if new, 0 if present, -1 out of memory. */
static int set_insert(sb_engine_firsthit *f, uint64_t key)
{
  const long h = sbi_idmap_add(&f->set, key, 0);
  return h < 0 ? -1 : h == 0;
}

static int set_has(const sb_engine_firsthit *f, uint64_t key)
{
  return sbi_idmap_has(&f->set, key);
}

/* Add one to a particle's count under key; the count before, or -1. */
static long count_add(sb_engine_firsthit *f, uint64_t key)
{
  return sbi_idmap_add(&f->counts, key, 1);
}

/* A counted first contact of particles i, j: their counts and the sums of
 * squares ((h + 1)^2 - h^2 = 2 h + 1).  -1 out of memory. */
static int tally(sb_engine_firsthit *f, const sb_engine *e, size_t i,
                 size_t j, long t)
{
  const size_t si = e->species[i], sj = e->species[j];
  const uint64_t S = SB_ENGINE_PAIR_SPECIES;
  const size_t q[2] = {i, j};
  for (int side = 0; side < 2; side++) {
    const uint64_t id = e->id[q[side]] << 5;
    const size_t other = side ? si : sj, own = side ? sj : si;
    const long h = count_add(f, (id | S) + 1);
    if (h < 0)
      return -1;
    f->sq_all += 2.0 * (double)h + 1.0;
    if (t < 0)
      continue;
    const long g = count_add(f, (id | other) + 1);
    if (g < 0)
      return -1;
    /* the side of the species pair (a, b), a <= b, the particle is on */
    f->sq[t][own > other] += 2.0 * (double)g + 1.0;
  }
  return 0;
}

/* Index of the species pair of particles i, j, or -1 beyond the table. */
static long type_of(const sb_engine *e, size_t i, size_t j)
{
  size_t a = e->species[i], b = e->species[j];
  if (a >= SB_ENGINE_PAIR_SPECIES || b >= SB_ENGINE_PAIR_SPECIES)
    return -1;
  return (long)sbi_pair_index(a, b);
}

/* 1 if the observer leaves record p alone (a pair seen before, with
 * skip_seen). */
static int skip(const sb_engine *e, const sb_engine_pair *p, void *ctx)
{
  const sb_engine_firsthit *f = ctx;
  return f->par.skip_seen &&
         set_has(f, sbi_pair_key(e->id[p->i], e->id[p->j]));
}

/* A contact of record p at fraction s of its interval: counted if it is
 * the pair's first; 0, or -1 (out of memory, or on_hit failed). */
static int count(sb_engine_firsthit *f, const sb_engine *e,
                 const sb_engine_pair *p, double s)
{
  int fresh = set_insert(f, sbi_pair_key(e->id[p->i], e->id[p->j]));
  if (fresh <= 0)
    return fresh;  /* known pair (0), or out of memory (-1) */
  const long t = type_of(e, p->i, p->j);
  /* the record covers [t0, t0 + dt] */
  if (p->t0 + s * p->dt < f->t1) {
    f->warm_all++;
    if (t >= 0)
      f->warm[t]++;
    return 0;
  }
  f->hits_all++;
  if (t >= 0)
    f->hits[t]++;
  if (tally(f, e, p->i, p->j, t))
    return -1;
  if (f->par.on_hit && f->par.on_hit(e, p, s, f->par.hit_ctx) < 0)
    return -1;
  return 0;
}

/* The counting detector around a custom one: records the pair's first
 * detected contact and answers "no collision", so the particles pass
 * through each other. */
static int detect(const sb_engine *e, const sb_engine_pair *p,
                  const gsl_rng *r, void *ctx, double *s)
{
  sb_engine_firsthit *f = ctx;
  if (skip(e, p, f))
    return 0;
  const int h = f->par.detect(e, p, r, f->par.detect_ctx, s);
  if (h <= 0)
    return h;
  return count(f, e, p, *s);
}

/* Around a built-in (sbi_engine_set_observer): the built-in's first
 * contact of record p, serially in record order. */
static int take(sb_engine *e, const sb_engine_pair *p, double s, void *ctx)
{
  if (count(ctx, e, p, s))
    return sbi_error(SB_ENOMEM, "sb_engine_step", "first-contact "
                     "observer: out of memory, or its on_hit failed");
  return SB_SUCCESS;
}

/* Install f's detector on e (sb_engine_firsthit_attach). */
static int install(sb_engine *e, sb_engine_firsthit *f, double reach)
{
  int st;
  if (!f->par.detect) {
    /* the built-in itself, observed: its own reach, search (the Verlet
     * list of the chord detectors, the Langevin search) and first pass on
     * the threads (for `langevin` with the engine's streams); skip only
     * reads the set of pairs seen, which changes in take, serially */
    st = sb_engine_set_detect(e, f->par.builtin);
    if (!st)
      sbi_engine_set_observer(e, skip, take, f);
  } else
    st = sb_engine_set_detector(e, detect, f, reach);
  if (!st)
    f->attached = 1;
  return st;
}

void sb_engine_firsthit_params_default(sb_engine_firsthit_params *p)
{
  if (!p) {
    sbi_error(SB_EINVAL, __func__, "params is NULL");
    return;
  }
  memset(p, 0, sizeof *p);
  p->builtin = SB_DETECT_BALLISTIC;
}

sb_engine_firsthit *sb_engine_firsthit_alloc(
    const sb_engine_firsthit_params *p)
{
  if (!p) {
    sbi_error(SB_EINVAL, __func__, "params is NULL");
    return NULL;
  }
  if (!p->detect && p->builtin != SB_DETECT_BALLISTIC &&
      p->builtin != SB_DETECT_OVERLAP && p->builtin != SB_DETECT_LANGEVIN) {
    sbi_error(SB_EINVAL, __func__, "builtin = %d: not a built-in detector "
              "(ballistic, overlap or langevin)", (int)p->builtin);
    return NULL;
  }
  sb_engine_firsthit *f = calloc(1, sizeof *f);
  if (!f) {
    sbi_error(SB_ENOMEM, __func__, "out of memory");
    return NULL;
  }
  f->par = *p;
  f->par.skip_seen = p->skip_seen != 0;
  return f;
}

void sb_engine_firsthit_free(sb_engine_firsthit *f)
{
  if (f) {
    sbi_idmap_free(&f->set);
    sbi_idmap_free(&f->counts);
  }
  free(f);
}

int sb_engine_firsthit_attach(sb_engine *e, sb_engine_firsthit *f,
                              double reach)
{
  if (!e || !f)
    return sbi_error(SB_EINVAL, __func__, "engine or observer is NULL");
  if (f->attached)
    return sbi_error(SB_EINVAL, __func__, "the observer is attached "
                     "already");
  if (!(reach >= 0.0) || !isfinite(reach))
    return sbi_error(SB_EINVAL, __func__, "reach = %g: must be finite and "
                     ">= 0", reach);
  if (f->restored) {  /* sb_engine_firsthit_load: the saved counts */
    const int st = sbi_engine_check_saved(e, f->saved_steps,
                                          f->saved_print, __func__,
                                          "the observer");
    return st ? st : install(e, f, reach);
  }
  /* particles per species */
  double ns[SB_ENGINE_PAIR_SPECIES] = {0};
  for (size_t i = 0; i < e->n; i++)
    if (e->species[i] < SB_ENGINE_PAIR_SPECIES)
      ns[e->species[i]] += 1.0;
  /* pairs in contact now: candidates of the neighbour search without
   * displacement, checked exactly (minimum image) */
  int st = sbi_engine_find_pairs(e, SB_NEIGH_CELLS, e->x, NULL, 0.0,
                                 __func__);
  if (st)
    return st;
  double nov[NPT] = {0}, novall = 0.0;
  for (size_t k = 0; k < e->npairs; k++) {
    size_t i = e->pairs[2 * k], j = e->pairs[2 * k + 1];
    double d2 = 0.0;
    for (int c = 0; c < e->par.dim; c++) {
      double L = e->par.L[c], dx = e->x[3 * i + c] - e->x[3 * j + c];
      dx -= L * floor(dx / L + 0.5);
      d2 += dx * dx;
    }
    const double a = e->radius[i] + e->radius[j];
    if (d2 <= a * a) {
      int fresh = set_insert(f, sbi_pair_key(e->id[i], e->id[j]));
      if (fresh < 0)
        return sbi_error(SB_ENOMEM, __func__, "out of memory");
      if (fresh) {
        const long t = type_of(e, i, j);
        if (t >= 0)
          nov[t] += 1.0;
        novall += 1.0;
      }
    }
  }
  e->npairs = 0;
  for (size_t a = 0; a < SB_ENGINE_PAIR_SPECIES; a++)
    for (size_t b = a; b < SB_ENGINE_PAIR_SPECIES; b++) {
      const size_t t = sbi_pair_index(a, b);
      const double tot = a == b ? 0.5 * ns[a] * (ns[a] - 1.0) : ns[a] * ns[b];
      f->contact0[t] = (uint64_t)nov[t];
      f->pairs_apart[t] = tot - nov[t];
    }
  const double N = (double)e->n;
  memcpy(f->ns, ns, sizeof ns);
  f->n_all = N;
  f->contact0_all = (uint64_t)novall;
  f->pairs_apart_all = 0.5 * N * (N - 1.0) - novall;
  return install(e, f, reach);
}

int sb_engine_firsthit_set_warmup(sb_engine_firsthit *f, double t1)
{
  if (!f || !(t1 >= 0.0) || !isfinite(t1))
    return sbi_error(SB_EINVAL, __func__, "t1 = %g: must be finite and "
                     ">= 0", f ? t1 : NAN);
  f->t1 = t1;
  return SB_SUCCESS;
}

double sb_engine_firsthit_warmup(const sb_engine_firsthit *f)
{
  if (!f) {
    sbi_error(SB_EINVAL, __func__, "observer is NULL");
    return NAN;
  }
  return f->t1;
}

/* The U-statistic estimate of var(hits) (engine_firsthit.h, hits_var):
 * sb_pair_count_variance with one first contact per pair (S2 = hits). */
static double hits_variance(uint64_t hits, double sq, double na, double sq2,
                            double nb, double P)
{
  const double H = (double)hits;
  return sb_pair_count_variance(H, H, sq, na, sq2, nb, P);
}

/* sb_engine_firsthit_get for the public function who */
static int get_counts(const sb_engine_firsthit *f, size_t a, size_t b,
                      sb_engine_firsthit_counts *c, const char *who)
{
  if (!f || !c)
    return sbi_error(SB_EINVAL, who, "observer or result is NULL");
  if (!f->attached)
    return sbi_error(SB_EINVAL, who, "the observer is not attached");
  if (a == SB_ENGINE_FIRSTHIT_ALL && b == SB_ENGINE_FIRSTHIT_ALL) {
    c->hits = f->hits_all;
    c->warm = f->warm_all;
    c->contact0 = f->contact0_all;
    c->pairs_apart = f->pairs_apart_all;
    /* one population of exchangeable pairs only: one species (all of
     * them within the table) */
    int one = 0;
    for (size_t q = 0; q < SB_ENGINE_PAIR_SPECIES; q++)
      one += f->ns[q] == f->n_all;
    c->hits_var = one ? hits_variance(c->hits, f->sq_all, f->n_all, 0.0,
                                      0.0, c->pairs_apart)
                      : NAN;
    return SB_SUCCESS;
  }
  if (a >= SB_ENGINE_PAIR_SPECIES || b >= SB_ENGINE_PAIR_SPECIES)
    return sbi_error(SB_EINVAL, who, "species pair (%zu, %zu): each "
                     "must be below %d (or both SB_ENGINE_FIRSTHIT_ALL)", a,
                     b, SB_ENGINE_PAIR_SPECIES);
  const size_t t = sbi_pair_index(a, b);
  c->hits = f->hits[t];
  c->warm = f->warm[t];
  c->contact0 = f->contact0[t];
  c->pairs_apart = f->pairs_apart[t];
  const size_t lo = a < b ? a : b, hi = a < b ? b : a;
  c->hits_var = lo == hi ? hits_variance(c->hits, f->sq[t][0], f->ns[lo],
                                         0.0, 0.0, c->pairs_apart)
                         : hits_variance(c->hits, f->sq[t][0], f->ns[lo],
                                         f->sq[t][1], f->ns[hi],
                                         c->pairs_apart);
  return SB_SUCCESS;
}

int sb_engine_firsthit_get(const sb_engine_firsthit *f, size_t a, size_t b,
                           sb_engine_firsthit_counts *c)
{
  return get_counts(f, a, b, c, __func__);
}

static int estimate(sb_engine_firsthit_kernel_result *k, double level,
                    const char *who);

int sb_engine_firsthit_kernel(const sb_engine_firsthit *f,
                              const sb_engine *e, size_t a, size_t b,
                              double radius, double D, double level,
                              sb_engine_firsthit_kernel_result *k)
{
  if (!k)
    return sbi_error(SB_EINVAL, __func__, "result is NULL");
  memset(k, 0, sizeof *k);
  k->K = k->lo = k->hi = k->dispersion = NAN;
  if (!e)
    return sbi_error(SB_EINVAL, __func__, "engine is NULL");
  if (a >= SB_ENGINE_PAIR_SPECIES || b >= SB_ENGINE_PAIR_SPECIES ||
      a >= e->nspec || b >= e->nspec)
    return sbi_error(SB_EINVAL, __func__, "species pair (%zu, %zu): no "
                     "such species", a, b);
  int st = get_counts(f, a, b, &k->c, __func__);
  if (st)
    return st;
  const double R = e->spec[a].radius + e->spec[b].radius;
  const double V = e->par.L[0] * e->par.L[1] * e->par.L[2];
  const double T = e->t, t1 = f->t1;
  k->radius = radius;
  k->D = D;
  k->t1 = t1;
  k->t = T;
  k->veff = V - 4.0 * PI * R * R * R / 3.0;
  if (e->par.dim != 3)
    return sbi_error(SB_EINVAL, __func__, "dim = %d: the first-contact "
                     "reference is 3-D", e->par.dim);
  return estimate(k, level, __func__);
}

/* Inputs valid: SB_SUCCESS, or the status with a message from `func`. */
static int check_inputs(const sb_engine_firsthit_kernel_result *k,
                        const char *func)
{
  if (!(k->radius >= 0.0) || !isfinite(k->radius))
    return sbi_error(SB_EINVAL, func, "radius = %g: must be > 0 (or "
                     "SB_ENGINE_FIRSTHIT_CAPACITANCE)", k->radius);
  if (!(k->D > 0.0) || !isfinite(k->D))
    return sbi_error(SB_EINVAL, func, "D = %g: must be > 0 (relative "
                     "diffusivity)", k->D);
  if (!(k->t1 >= 0.0) || !(k->t >= 0.0) || !(k->veff > 0.0))
    return sbi_error(SB_EINVAL, func, "t1 = %g s, t = %g s, veff = %g m^3: "
                     "must be >= 0, >= 0, > 0", k->t1, k->t, k->veff);
  return SB_SUCCESS;
}

/* Forward map without checks; the fixed-radius c1 is computed as
 * P teff / veff, the capacitance form as (P / veff) (t - t1). */
static void coefs(const sb_engine_firsthit_kernel_result *k, double *c1,
                  double *c2)
{
  const double T = k->t, t1 = k->t1, D = k->D;
  if (k->radius > 0.0) {
    const double teff =
        (T - t1) + 2.0 * k->radius * (sqrt(T) - sqrt(t1)) / sqrt(PI * D);
    *c1 = k->c.pairs_apart * teff / k->veff;
    *c2 = 0.0;
  } else {
    const double c = k->c.pairs_apart / k->veff;
    *c1 = c * (T - t1);
    *c2 = c * 2.0 * (sqrt(T) - sqrt(t1)) / (4.0 * PI * D * sqrt(PI * D));
  }
}

int sb_engine_firsthit_coefs(const sb_engine_firsthit_kernel_result *k,
                             double *c1, double *c2)
{
  if (!k || !c1 || !c2)
    return sbi_error(SB_EINVAL, __func__, "NULL argument");
  int st = check_inputs(k, __func__);
  if (st)
    return st;
  coefs(k, c1, c2);
  if (!(*c1 > 0.0))
    return sbi_error(SB_EDOM, __func__, "no exposure (%g pairs apart, "
                     "counting from t1 = %g s to t = %g s)",
                     k->c.pairs_apart, k->t1, k->t);
  return SB_SUCCESS;
}

/* Inverse of the forward map for a count h (the positive root). */
static double kernel_of(double c1, double c2, double h)
{
  if (!(c2 > 0.0))
    return h / c1;
  /* (-c1 + sqrt(c1^2 + 4 c2 h)) / (2 c2), written without cancellation */
  return 2.0 * h / (c1 + sqrt(c1 * c1 + 4.0 * c2 * h));
}

/* sb_engine_firsthit_estimate for the public function who */
static int estimate(sb_engine_firsthit_kernel_result *k, double level,
                    const char *who)
{
  if (!k)
    return sbi_error(SB_EINVAL, who, "result is NULL");
  k->K = k->lo = k->hi = k->a = k->expected_per_K = k->dispersion = NAN;
  int st = check_inputs(k, who);
  if (st)
    return st;
  if (!(level > 0.0 && level < 1.0))
    return sbi_error(SB_EINVAL, who, "level = %g: must be in (0, 1)",
                     level);
  double c1, c2;
  coefs(k, &c1, &c2);
  if (!(c1 > 0.0)) {
    k->expected_per_K = c1;
    return sbi_error(SB_EDOM, who, "no exposure (%g pairs apart, "
                     "counting from t1 = %g s to t = %g s)",
                     k->c.pairs_apart, k->t1, k->t);
  }
  /* the count's Garwood interval, widened about it by sqrt(var / mean)
   * where the per-particle counts show more variance than Poisson */
  const double H = (double)k->c.hits, v = k->c.hits_var;
  k->dispersion = H > 0.0 && v > 0.0 && isfinite(v) ? v / H : NAN;
  double l, u;
  st = sb_poisson_ci_dispersed(k->c.hits, k->dispersion, level, &l, &u);
  if (st)
    return sbi_error(st, who, "interval: %s", sb_last_error());
  if (k->radius > 0.0) {
    /* linear: the interval is the count's interval times the scale */
    k->a = k->radius;
    k->expected_per_K = c1;
    const double scale = 1.0 / c1;
    k->K = scale * H;
    k->lo = l * scale;
    k->hi = u * scale;
    return SB_SUCCESS;
  }
  k->K = kernel_of(c1, c2, (double)k->c.hits);
  k->lo = kernel_of(c1, c2, l);
  k->hi = kernel_of(c1, c2, u);
  k->a = k->K / (4.0 * PI * k->D);
  k->expected_per_K = c1 + c2 * k->K;
  return SB_SUCCESS;
}

int sb_engine_firsthit_estimate(sb_engine_firsthit_kernel_result *k,
                                double level)
{
  return estimate(k, level, __func__);
}

double sb_engine_chord_vn(const sb_engine *e, const sb_engine_pair *p,
                          double s)
{
  if (!e || !p) {
    sbi_error(SB_EINVAL, __func__, "NULL argument");
    return NAN;
  }
  if (p->i >= e->n || p->j >= e->n) {
    sbi_error(SB_EINVAL, __func__, "pair (%zu, %zu): no such particle",
              p->i, p->j);
    return NAN;
  }
  const double *u0 = sb_engine_start_velocities(e);
  const double *u1 = sb_engine_velocities(e);
  double n[3], nn = 0.0, vn = 0.0;
  for (int k = 0; k < 3; k++) {
    n[k] = p->dx0[k] + s * p->dd[k];
    nn += n[k] * n[k];
  }
  nn = sqrt(nn);
  for (int k = 0; k < 3; k++) {
    double ui = u0[3 * p->i + k] + s * (u1[3 * p->i + k] - u0[3 * p->i + k]);
    double uj = u0[3 * p->j + k] + s * (u1[3 * p->j + k] - u0[3 * p->j + k]);
    vn += (ui - uj) * n[k] / nn;
  }
  return vn;
}

double sb_engine_contact_vn(const sb_engine *e)
{
  if (!e || !e->contact) {
    sbi_error(SB_EINVAL, __func__, "no contact state (Langevin detector, "
              "inside an outcome or an on_hit callback only)");
    return NAN;
  }
  /* from the relative vector and velocity themselves, (u_i - u_j) - du
   * (j's Lees-Edwards image) and x_i - x_j, not from the states: the same
   * bits whichever particle of the pair comes first in memory */
  const sbi_event *c = e->contact;
  const double sigma = c->p.sigma;  /* |x_i - x_j| */
  double vn = 0.0;
  for (int k = 0; k < 3; k++)
    vn += (c->cu[0][k] - c->cu[1][k] - (k == 0 ? c->cdu : 0.0)) *
          c->crel[k] / sigma;
  return vn;
}
