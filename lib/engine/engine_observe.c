/* engine_observe.c — observers: collision counters (total and per family
 * pair), the kernel estimate with its exact Poisson interval, the time
 * series, snapshots and an overlap diagnostic.
 *
 * Kernel estimate.  With n particles in a volume V the expected number of
 * collisions per unit time is K n (n - 1) / (2 V) (K n_c^2 V / 2 with the
 * pair count n (n - 1)/2 in place of n^2/2), so over the measurement
 *     K_e = N_c V / int n (n - 1)/2 dt    (= 2 N_c V / (n (n - 1) t) for a
 * constant n; Mohaupt 2011, eq 2.16), the integral (the pair exposure)
 * accumulated step by step (trapezoid) so that removals and merges are
 * accounted for; and per species pair (a, b) K_ab = N_ab V / int P_ab dt,
 * P_ab = n_a n_b for a != b, n_a (n_a - 1)/2 for a = b.  N_c being
 * Poisson, K_e's exact interval is the Garwood interval of N_c times the
 * same scale (sb_poisson_rate_ci).  Successive collisions
 * are not strictly independent (re-collisions of a pair), so the interval
 * is exact for a Poisson process and approximate otherwise.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <stdlib.h>

#include <smolbridge/stats.h>

#include "common/internal.h"
#include "engine_internal.h"

/* Tally collision (i, j) of species pair type t for the counts'
 * variance: each particle's collisions with the other's species and the
 * pair's, and the sums of their squares ((h + 1)^2 - h^2 = 2 h + 1).  Out
 * of memory: the tally is incomplete until the next reset. */
static void tally_collision(sb_engine *e, size_t i, size_t j, size_t t)
{
  const size_t s[2] = {e->species[i], e->species[j]}, q[2] = {i, j};
  for (int side = 0; side < 2; side++) {
    const size_t own = s[side], other = s[1 - side];
    const long h = sbi_idmap_add(&e->cvar_part,
                                 (e->id[q[side]] << 5 | other) + 1, 1);
    if (h < 0) {
      e->cvar_lost = 1;
      return;
    }
    e->cvar_sq[t][own > other] += 2.0 * (double)h + 1.0;
  }
  const long g = sbi_idmap_add(&e->cvar_pair,
                               sbi_pair_key(e->id[i], e->id[j]), 1);
  if (g < 0) {
    e->cvar_lost = 1;
    return;
  }
  e->cvar_s2[t] += 2.0 * (double)g + 1.0;
}

void sbi_engine_count_collision(sb_engine *e, size_t i, size_t j)
{
  e->ncoll++;
  size_t si = e->species[i], sj = e->species[j];
  if (si < SB_ENGINE_PAIR_SPECIES && sj < SB_ENGINE_PAIR_SPECIES) {
    const size_t t = sbi_pair_index(si, sj);
    e->pcoll[t]++;
    if (e->cvar_on && !e->cvar_lost)
      tally_collision(e, i, j, t);
  }
  int a = e->family[i], b = e->family[j];
  if (a > b) {
    int t = a;
    a = b;
    b = t;
  }
  e->fam[a][b]++;
}

/* Empty the collision tally (its tables kept). */
static void clear_tally(sb_engine *e)
{
  sbi_idmap *m[2] = {&e->cvar_part, &e->cvar_pair};
  for (int k = 0; k < 2; k++) {
    if (m[k]->cap) {
      memset(m[k]->key, 0, m[k]->cap * sizeof *m[k]->key);
      memset(m[k]->val, 0, m[k]->cap * sizeof *m[k]->val);
    }
    m[k]->n = 0;
  }
  memset(e->cvar_sq, 0, sizeof e->cvar_sq);
  memset(e->cvar_s2, 0, sizeof e->cvar_s2);
}

void sb_engine_reset_counters(sb_engine *e)
{
  if (!e) {
    sbi_error(SB_EINVAL, __func__, "engine is NULL");
    return;
  }
  e->ncoll = e->ncand = e->dropped = e->nredetect = 0;
  sbi_engine_langevin_reset_stats(e);
  memset(e->fam, 0, sizeof e->fam);
  e->expo = 0.0;
  memset(e->pexpo, 0, sizeof e->pexpo);
  memset(e->pcoll, 0, sizeof e->pcoll);
  memset(e->ndep, 0, sizeof e->ndep);  /* wall depositions */
  memset(e->nout, 0, sizeof e->nout);  /* open boundaries */
  memset(e->ninj, 0, sizeof e->ninj);
  memset(e->nskip, 0, sizeof e->nskip);
  clear_tally(e);
  e->cvar_lost = 0;
  e->t_reset = e->t;
}

int sb_engine_set_count_variance(sb_engine *e, int on)
{
  if (!e)
    return sbi_error(SB_EINVAL, __func__, "engine is NULL");
  e->cvar_on = on != 0;
  clear_tally(e);
  e->cvar_lost = e->ncoll > 0;  /* complete only from a reset */
  if (!e->cvar_on) {
    sbi_idmap_free(&e->cvar_part);
    sbi_idmap_free(&e->cvar_pair);
  }
  return SB_SUCCESS;
}

int sb_engine_get_count_variance(const sb_engine *e)
{
  if (!e) {
    sbi_error(SB_EINVAL, __func__, "engine is NULL");
    return 0;
  }
  return e->cvar_on;
}

/* The variance of the count H of species pair (a, b), type t, from the
 * tally (sb_pair_count_variance, with the particles of each species now);
 * NaN without a complete tally since the reset. */
static double count_variance(const sb_engine *e, size_t a, size_t b,
                             size_t t, uint64_t H)
{
  if (!e->cvar_on || e->cvar_lost)
    return NAN;
  double na = 0.0, nb = 0.0;
  for (size_t i = 0; i < e->n; i++) {
    na += e->species[i] == a;
    nb += e->species[i] == b;
  }
  const double *sq = e->cvar_sq[t];
  if (a == b)
    return sb_pair_count_variance((double)H, e->cvar_s2[t], sq[0], na, 0.0,
                                  0.0, 0.5 * na * (na - 1.0));
  /* sq[0]: the particles of the lower species */
  const double nlo = a < b ? na : nb, nhi = a < b ? nb : na;
  return sb_pair_count_variance((double)H, e->cvar_s2[t], sq[0], nlo,
                                sq[1], nhi, na * nb);
}

int sb_engine_get_stats(const sb_engine *e, sb_engine_stats *st)
{
  if (!e || !st)
    return sbi_error(SB_EINVAL, __func__, "NULL argument");
  st->steps = e->steps;
  st->ncoll = e->ncoll;
  st->ncand = e->ncand;
  st->dropped = e->dropped;
  st->redetected = e->nredetect;
  memcpy(st->fam, e->fam, sizeof e->fam);
  st->t = e->t;
  st->t_reset = e->t_reset;
  st->exposure = e->expo;
  return SB_SUCCESS;
}

static double volume(const sb_engine *e)
{
  double v = 1.0;
  for (int k = 0; k < e->par.dim; k++)
    v *= e->par.L[k];
  return v;
}

int sb_engine_kernel(const sb_engine *e, double level, double *K,
                     double *lo, double *hi)
{
  double dummy;
  if (!lo)
    lo = &dummy;
  if (!hi)
    hi = &dummy;
  if (K)
    *K = NAN;
  *lo = *hi = NAN;
  if (!e || !K)
    return sbi_error(SB_EINVAL, __func__, "NULL argument");
  if (!(level > 0.0 && level < 1.0))
    return sbi_error(SB_EINVAL, __func__, "level = %g: must be in (0, 1)",
                     level);
  if (!(e->expo > 0.0))
    return sbi_error(SB_EDOM, __func__,
                     "no pair exposure since the reset (no step taken, or "
                     "fewer than 2 particles)");
  double scale = volume(e) / e->expo;
  *K = scale * (double)e->ncoll;
  int st = sb_poisson_rate_ci((unsigned long)e->ncoll, scale, level, lo, hi);
  if (st)
    return sbi_error(st, __func__, "Poisson interval failed: %s",
                     sb_last_error());
  return SB_SUCCESS;
}

void sbi_engine_pair_counts(const sb_engine *e, double *out)
{
  double nsp[SB_ENGINE_PAIR_SPECIES] = {0};
  if (e->nspec == 1 && !e->nremove)
    nsp[0] = (double)e->n;  /* one species, nothing marked for removal */
  else {
    size_t cnt[SB_ENGINE_PAIR_SPECIES] = {0};
    for (size_t i = 0; i < e->n; i++)
      if (e->species[i] < SB_ENGINE_PAIR_SPECIES && e->hit[i] != 2)
        cnt[e->species[i]]++;
    for (size_t a = 0; a < SB_ENGINE_PAIR_SPECIES; a++)
      nsp[a] = (double)cnt[a];
  }
  for (size_t a = 0; a < SB_ENGINE_PAIR_SPECIES; a++)
    for (size_t b = a; b < SB_ENGINE_PAIR_SPECIES; b++)
      out[sbi_pair_index(a, b)] =
          a == b ? 0.5 * nsp[a] * (nsp[a] - 1.0) : nsp[a] * nsp[b];
  double n = (double)e->n;
  out[SBI_NPAIRSP] = 0.5 * n * (n - 1.0);
}

void sbi_engine_add_exposure(sb_engine *e, double dt)
{
  double now[SBI_NPAIRSP + 1];
  sbi_engine_pair_counts(e, now);
  for (size_t q = 0; q < SBI_NPAIRSP; q++)
    e->pexpo[q] += 0.5 * (e->pairs0[q] + now[q]) * dt;
  e->expo += 0.5 * (e->pairs0[SBI_NPAIRSP] + now[SBI_NPAIRSP]) * dt;
}

int sb_engine_pair_kernel(const sb_engine *e, size_t a, size_t b,
                          double level, sb_engine_pair_stats *ps)
{
  if (!e || !ps)
    return sbi_error(SB_EINVAL, __func__, "NULL argument");
  ps->ncoll = 0;
  ps->exposure = ps->K = ps->lo = ps->hi = NAN;
  ps->ncoll_var = ps->dispersion = NAN;
  if (a >= SB_ENGINE_PAIR_SPECIES || b >= SB_ENGINE_PAIR_SPECIES)
    return sbi_error(SB_EINVAL, __func__,
                     "species %zu, %zu: only the first %d species are "
                     "tracked", a, b, SB_ENGINE_PAIR_SPECIES);
  if (!(level > 0.0 && level < 1.0))
    return sbi_error(SB_EINVAL, __func__, "level = %g: must be in (0, 1)",
                     level);
  size_t q = sbi_pair_index(a, b);
  ps->ncoll = e->pcoll[q];
  ps->exposure = e->pexpo[q];
  if (!(e->pexpo[q] > 0.0))
    return sbi_error(SB_EDOM, __func__,
                     "no exposure of species pair (%zu, %zu) since the "
                     "reset", a, b);
  double scale = volume(e) / e->pexpo[q];
  ps->K = scale * (double)e->pcoll[q];
  ps->ncoll_var = count_variance(e, a, b, q, e->pcoll[q]);
  ps->dispersion = e->pcoll[q] > 0 ? ps->ncoll_var / (double)e->pcoll[q]
                                   : NAN;
  int st = sb_poisson_ci_dispersed((unsigned long)e->pcoll[q],
                                   ps->dispersion, level, &ps->lo, &ps->hi);
  if (st)
    return sbi_error(st, __func__, "Poisson interval failed: %s",
                     sb_last_error());
  ps->lo *= scale;
  ps->hi *= scale;
  return SB_SUCCESS;
}

int sbi_engine_sample(sb_engine *e)
{
  if (e->nseries == e->capseries) {
    size_t nc = e->capseries ? 2 * e->capseries : 256;
    sb_engine_sample *ns = realloc(e->series, nc * sizeof *ns);
    if (!ns)
      return sbi_error(SB_ENOMEM, "sb_engine_step", "out of memory");
    e->series = ns;
    e->capseries = nc;
  }
  sb_engine_sample *s = &e->series[e->nseries++];
  s->t = e->t;
  s->ncoll = e->ncoll;
  s->K = s->K_lo = s->K_hi = NAN;
  if (e->expo > 0.0)
    sb_engine_kernel(e, 0.95, &s->K, &s->K_lo, &s->K_hi);
  s->ekin = sb_engine_kinetic_energy(e, s->p);
  return SB_SUCCESS;
}

const sb_engine_sample *sb_engine_series(const sb_engine *e, size_t *n)
{
  if (n)
    *n = e ? e->nseries : 0;
  if (!e) {
    sbi_error(SB_EINVAL, __func__, "engine is NULL");
    return NULL;
  }
  return e->series;
}

size_t sb_engine_check_overlaps(const sb_engine *e, double rel_tol)
{
  size_t bad = 0;
  if (!e) {
    sbi_error(SB_EINVAL, __func__, "engine is NULL");
    return 0;
  }
  for (size_t i = 0; i < e->n; i++)
    for (size_t j = i + 1; j < e->n; j++) {
      double d2 = 0.0;
      for (int k = 0; k < e->par.dim; k++) {
        double d = sbi_minimg(e->x[3 * i + k] - e->x[3 * j + k],
                              e->par.L[k]);
        d2 += d * d;
      }
      double sg = (e->radius[i] + e->radius[j]) * (1.0 - rel_tol);
      if (d2 < sg * sg)
        bad++;
    }
  return bad;
}

int sb_engine_snapshot_csv(const sb_engine *e, const char *path)
{
  if (!e || !path)
    return sbi_error(SB_EINVAL, __func__, "NULL argument");
  FILE *f = fopen(path, "w");
  if (!f)
    return sbi_error(SB_EIO, __func__, "cannot open '%s' for writing", path);
  fprintf(f, "id,species,family,x,y,z,ux,uy,uz\n");
  for (size_t i = 0; i < e->n; i++) {
    const double *x = &e->x[3 * i], *u = &e->u[3 * i];
    fprintf(f, "%llu,%zu,%d,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n",
            (unsigned long long)e->id[i], e->species[i], e->family[i], x[0],
            x[1], x[2], u[0], u[1], u[2]);
  }
  if (fclose(f))
    return sbi_error(SB_EIO, __func__, "write error on '%s'", path);
  return SB_SUCCESS;
}
