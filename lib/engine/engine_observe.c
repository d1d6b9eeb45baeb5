/* engine_observe.c — observers: collision counters (total and per family
 * pair), the kernel estimate with its exact Poisson interval, the time
 * series, snapshots and an overlap diagnostic.
 *
 * Kernel estimate.  With n particles in a volume V the expected number of
 * collisions per unit time is K n (n - 1) / (2 V) (K n_c^2 V / 2 with the
 * pair count n (n - 1)/2 in place of n^2/2), so
 *     K_e = 2 N_c V / (n (n - 1) t)                 (Mohaupt 2011, eq 2.16)
 * and, N_c being Poisson, K_e's exact interval is the Garwood interval of
 * N_c times the same scale (sb_poisson_rate_ci).  Successive collisions
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

void sbi_engine_count_collision(sb_engine *e, size_t i, size_t j)
{
  e->ncoll++;
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
  e->ncoll = e->ncand = e->dropped = 0;
  memset(e->fam, 0, sizeof e->fam);
  e->t_reset = e->t;
}

int sb_engine_get_stats(const sb_engine *e, sb_engine_stats *st)
{
  if (!e || !st)
    return sbi_error(SB_EINVAL, __func__, "NULL argument");
  st->steps = e->steps;
  st->ncoll = e->ncoll;
  st->ncand = e->ncand;
  st->dropped = e->dropped;
  memcpy(st->fam, e->fam, sizeof e->fam);
  st->t = e->t;
  st->t_reset = e->t_reset;
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
  double t = e->t - e->t_reset;
  if (!(t > 0.0) || e->n < 2)
    return sbi_error(SB_EDOM, __func__,
                     "no elapsed time (%g s) or fewer than 2 particles", t);
  double nn = (double)e->n;
  double scale = 2.0 * volume(e) / (nn * (nn - 1.0) * t);
  *K = scale * (double)e->ncoll;
  int st = sb_poisson_rate_ci((unsigned long)e->ncoll, scale, level, lo, hi);
  if (st)
    return sbi_error(st, __func__, "Poisson interval failed: %s",
                     sb_last_error());
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
  if (e->t > e->t_reset && e->n >= 2)
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
