/* collide_firsthit.c — [observe] first_hit: count the first detected
 * contact of every pair while the particles pass through each other
 * (outcome = count), so that the pairs are independent two-body problems
 * and the count has an exact reference (docs/engine_bridge.md §7):
 *   E[hits in (t1, t]] = P/(V - v_a) K [(t - t1) + 2 a (sqrt t - sqrt t1)
 *                                        / sqrt(pi D)],
 * P the pairs apart at the start, a the reference radius, D the relative
 * diffusivity.  The same protocol as the validation cases (its code in
 * lib/validate/firsthit.c), so a case's file reproduces its count. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <smolbridge/engine.h>
#include <smolbridge/engine_bridge.h>
#include <smolbridge/stats.h>

#include "collide.h"

#define PI 3.14159265358979323846

struct col_firsthit {
  sb_engine_bridge *b;   /* bridge detector, or NULL: built-in */
  sb_engine_detect builtin;
  uint64_t *set;         /* open addressing, 0 = empty */
  size_t cap, n;
  size_t n0;             /* pairs in contact at the start */
  size_t nwarm;          /* first contacts before t1 */
  double t1;
  double pairs_apart;
};

static size_t slot(uint64_t key, size_t cap)
{
  return (size_t)((key * 0x9E3779B97F4A7C15ULL) >> 17) & (cap - 1);
}

/* 1 if new, 0 if present, -1 out of memory (grows at half load). */
static int insert(struct col_firsthit *f, uint64_t key)
{
  if (2 * (f->n + 1) > f->cap) {
    size_t nc = f->cap ? 2 * f->cap : 1024;
    uint64_t *ns = calloc(nc, sizeof *ns);
    if (!ns)
      return -1;
    for (size_t i = 0; i < f->cap; i++)
      if (f->set[i]) {
        size_t h = slot(f->set[i], nc);
        while (ns[h])
          h = (h + 1) & (nc - 1);
        ns[h] = f->set[i];
      }
    free(f->set);
    f->set = ns;
    f->cap = nc;
  }
  for (size_t h = slot(key, f->cap);; h = (h + 1) & (f->cap - 1)) {
    if (f->set[h] == key)
      return 0;
    if (!f->set[h]) {
      f->set[h] = key;
      f->n++;
      return 1;
    }
  }
}

static uint64_t pair_key(uint64_t a, uint64_t b)
{
  return ((a < b ? a : b) << 32 | (a < b ? b : a)) + 1;
}

static int detect(const sb_engine *e, const sb_engine_pair *p,
                  const gsl_rng *r, void *ctx, double *s)
{
  struct col_firsthit *f = ctx;
  int h;
  if (f->b)
    h = sb_engine_detect_bridge(e, p, r, f->b, s);
  else if (f->builtin == SB_DETECT_OVERLAP)
    h = sb_engine_detect_overlap(p, s);
  else if (f->builtin == SB_DETECT_LANGEVIN)
    h = sb_engine_detect_langevin(e, p, r, NULL, s);
  else
    h = sb_engine_detect_ballistic(p, s);
  if (h <= 0)
    return h;
  const uint64_t *id = sb_engine_ids(e);
  int fresh = insert(f, pair_key(id[p->i], id[p->j]));
  if (fresh < 0)
    return -1;
  if (fresh && p->t0 + *s * p->dt < f->t1)
    f->nwarm++;
  return 0;  /* pass through */
}

void col_firsthit_start(col_run *r, double t1)
{
  if (r->fh)
    r->fh->t1 = t1;
}

/* Install the counting detector around the run's detector; the pairs in
 * contact now are not first contacts. */
int col_firsthit_attach(col_run *r, sb_engine_detect builtin, double reach)
{
  struct col_firsthit *f = calloc(1, sizeof *f);
  if (!f)
    return SB_ENOMEM;
  r->fh = f;
  f->b = r->bridge;
  f->builtin = builtin;
  const sb_engine *e = r->e;
  const sb_engine_params *p = sb_engine_get_params(e);
  const double *x = sb_engine_positions(e), *rad = sb_engine_radii(e);
  const uint64_t *id = sb_engine_ids(e);
  size_t N = sb_engine_count(e), nov = 0;
  for (size_t i = 0; i < N; i++)
    for (size_t j = i + 1; j < N; j++) {
      double d2 = 0.0;
      for (int k = 0; k < p->dim; k++) {
        double dx = x[3 * i + k] - x[3 * j + k];
        dx -= p->L[k] * floor(dx / p->L[k] + 0.5);
        d2 += dx * dx;
      }
      double a = rad[i] + rad[j];
      if (d2 <= a * a) {
        if (insert(f, pair_key(id[i], id[j])) < 0)
          return SB_ENOMEM;
        nov++;
      }
    }
  f->n0 = f->n;
  f->pairs_apart = 0.5 * (double)N * (double)(N - 1) - (double)nov;
  return sb_engine_set_detector(r->e, detect, f, reach);
}

void col_firsthit_free(struct col_firsthit *f)
{
  if (f)
    free(f->set);
  free(f);
}

int col_firsthit_result(const col_run *r, const col_config *c,
                        col_fh_result *o)
{
  memset(o, 0, sizeof *o);
  const struct col_firsthit *f = r->fh;
  if (!f)
    return -1;
  const sb_engine *e = r->e;
  const sb_engine_params *p = sb_engine_get_params(e);
  const sb_engine_species *s = sb_engine_get_species(e, 0);
  double b2 = isfinite(s->tau) ? c->b2_total[0] : NAN;
  sb_engine_stats es;
  sb_engine_get_stats(e, &es);
  double R = 2.0 * s->radius;  /* contact distance */
  double a = c->first_hit_radius > 0 ? c->first_hit_radius : R;
  double V = p->L[0] * p->L[1] * (p->dim == 3 ? p->L[2] : 1.0);
  double vb = 4.0 * PI * R * R * R / 3.0;
  double T = es.t, t1 = f->t1;
  double teff = (T - t1) + 2.0 * a * (sqrt(T) - sqrt(t1)) / sqrt(PI * b2);
  o->hits = (unsigned long)(f->n - f->n0 - f->nwarm);
  o->warm = (unsigned long)f->nwarm;
  o->pairs_apart = f->pairs_apart;
  o->radius = a;
  o->D = b2;
  o->t1 = t1;
  o->t = T;
  o->expected_per_K = f->pairs_apart * teff / (V - vb);
  double scale = 1.0 / o->expected_per_K;
  o->K = scale * (double)o->hits;
  sb_poisson_rate_ci(o->hits, scale, 0.95, &o->lo, &o->hi);
  return 0;
}
