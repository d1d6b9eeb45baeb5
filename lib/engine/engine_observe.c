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

/* Log collision (i, j) for the counts' variance; an entry that cannot be
 * stored marks the log lost until the next reset. */
static void log_collision(sb_engine *e, size_t i, size_t j)
{
  if (e->clog_lost)
    return;
  if (e->nclog == e->capclog) {
    const size_t nc = e->capclog ? 2 * e->capclog : 1024;
    sbi_collision *c = realloc(e->clog, nc * sizeof *c);
    if (!c) {
      e->clog_lost = 1;
      return;
    }
    e->clog = c;
    e->capclog = nc;
  }
  sbi_collision *c = &e->clog[e->nclog++];
  c->id[0] = e->id[i];
  c->id[1] = e->id[j];
  c->sp[0] = (uint32_t)e->species[i];
  c->sp[1] = (uint32_t)e->species[j];
}

void sbi_engine_count_collision(sb_engine *e, size_t i, size_t j)
{
  e->ncoll++;
  if (e->clog_on)
    log_collision(e, i, j);
  size_t si = e->species[i], sj = e->species[j];
  if (si < SB_ENGINE_PAIR_SPECIES && sj < SB_ENGINE_PAIR_SPECIES)
    e->pcoll[sbi_pair_index(si, sj)]++;
  int a = e->family[i], b = e->family[j];
  if (a > b) {
    int t = a;
    a = b;
    b = t;
  }
  e->fam[a][b]++;
}

void sb_engine_reset_counters(sb_engine *e)
{
  if (!e)
    return;
  e->ncoll = e->ncand = e->dropped = e->nredetect = 0;
  sb_langevin_hitter_reset(e->lh);
  memset(e->fam, 0, sizeof e->fam);
  e->expo = 0.0;
  memset(e->pexpo, 0, sizeof e->pexpo);
  memset(e->pcoll, 0, sizeof e->pcoll);
  memset(e->ndep, 0, sizeof e->ndep);  /* wall depositions */
  memset(e->nout, 0, sizeof e->nout);  /* open boundaries */
  memset(e->ninj, 0, sizeof e->ninj);
  memset(e->nskip, 0, sizeof e->nskip);
  e->nclog = 0;
  e->clog_lost = 0;
  e->t_reset = e->t;
}

int sb_engine_set_count_variance(sb_engine *e, int on)
{
  if (!e)
    return sbi_error(SB_EINVAL, __func__, "engine is NULL");
  e->clog_on = on != 0;
  e->nclog = 0;
  e->clog_lost = !e->clog_on || e->ncoll > 0;  /* complete from a reset */
  if (!e->clog_on) {
    free(e->clog);
    e->clog = NULL;
    e->capclog = 0;
  }
  return SB_SUCCESS;
}

/* Keys: a particle id, or a pair of ids (lo < hi; single ids: hi 0). */
typedef struct {
  uint64_t lo, hi;
} ckey;

static int cmp_key(const void *a, const void *b)
{
  const ckey *x = a, *y = b;
  if (x->lo != y->lo)
    return x->lo < y->lo ? -1 : 1;
  return x->hi < y->hi ? -1 : x->hi > y->hi;
}

/* Sum of the squared multiplicities of the n keys (sorted in place). */
static double sum_sq_runs(ckey *k, size_t n)
{
  qsort(k, n, sizeof *k, cmp_key);
  double s = 0.0;
  for (size_t a = 0; a < n;) {
    size_t b = a + 1;
    while (b < n && !cmp_key(&k[b], &k[a]))
      b++;
    s += (double)(b - a) * (double)(b - a);
    a = b;
  }
  return s;
}

/* The variance of the count H of species pair (a, b) from the collision
 * log (sb_pair_count_variance): each particle's collisions on each side,
 * each pair's, and the particles of each species now.  NaN when the log
 * does not hold exactly the count (off, lost, or not complete since the
 * reset), or out of memory. */
static double count_variance(const sb_engine *e, size_t a, size_t b,
                             uint64_t H)
{
  if (!e->clog_on || e->clog_lost)
    return NAN;
  size_t m = 0;
  for (size_t q = 0; q < e->nclog; q++) {
    const sbi_collision *c = &e->clog[q];
    m += (c->sp[0] == a && c->sp[1] == b) || (c->sp[0] == b && c->sp[1] == a);
  }
  if (m != H)
    return NAN;
  if (!H)
    return 0.0;
  /* the pairs, side a's ends and side b's (one species: both ends) */
  ckey *k = malloc(3 * m * sizeof *k);
  if (!k)
    return NAN;
  ckey *pk = k, *ka = k + m, *kb = k + 2 * m;
  size_t np = 0, na_k = 0, nb_k = 0;
  for (size_t q = 0; q < e->nclog; q++) {
    const sbi_collision *c = &e->clog[q];
    int f;  /* the end of species a */
    if (c->sp[0] == a && c->sp[1] == b)
      f = 0;
    else if (c->sp[0] == b && c->sp[1] == a)
      f = 1;
    else
      continue;
    const int o = c->id[0] < c->id[1] ? 0 : 1;
    pk[np++] = (ckey){c->id[o], c->id[1 - o]};
    ka[na_k++] = (ckey){c->id[f], 0};
    if (a == b)
      ka[na_k++] = (ckey){c->id[1 - f], 0};
    else
      kb[nb_k++] = (ckey){c->id[1 - f], 0};
  }
  const double S2 = sum_sq_runs(pk, np), sqa = sum_sq_runs(ka, na_k);
  const double sqb = a == b ? 0.0 : sum_sq_runs(kb, nb_k);
  free(k);
  double na = 0.0, nb = 0.0;
  for (size_t i = 0; i < e->n; i++) {
    na += e->species[i] == a;
    nb += e->species[i] == b;
  }
  if (a == b)
    return sb_pair_count_variance((double)H, S2, sqa, na, 0.0, 0.0,
                                  0.5 * na * (na - 1.0));
  return sb_pair_count_variance((double)H, S2, sqa, na, sqb, nb, na * nb);
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
  ps->ncoll_var = count_variance(e, a, b, e->pcoll[q]);
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
  return e ? e->series : NULL;
}

size_t sb_engine_check_overlaps(const sb_engine *e, double rel_tol)
{
  size_t bad = 0;
  if (!e)
    return 0;
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
