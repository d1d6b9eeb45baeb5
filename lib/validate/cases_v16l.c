/* cases_v16l.c — V16/combined-shear's rows for the Langevin detector:
 * pass-through counting of Langevin spheres in a Lees-Edwards shear at
 * dt = tau_p, against the Rice flux through the contact sphere
 * (sb_kernel_shear_langevin; docs/engine_forces.md §8).
 *
 * At dt = tau_p a pair near grazing contact leaves and enters again
 * inside a step; contact-time chords cannot (a line meets the ball once),
 * while the Langevin detector follows the pair's bridge through every
 * exit and entry (sb_langevin_hitter_sample_all), so it counts the flux
 * at any dt.  The count is over-dispersed (a grazing pair re-crosses many
 * times), so the verdict is the t interval of independent replicas, each
 * with its own engine seed and placement.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include <gsl/gsl_rng.h>

#include <smolbridge/engine.h>
#include <smolbridge/kernel.h>
#include <smolbridge/stats.h>

#include "cases.h"
#include "v16.h"

#define PI 3.14159265358979323846

/* Replica streams: 1780 + k. */
#define LV_STREAM 1780UL
#define LV_MAXREP 32

/* One replica: n spheres placed uniformly at their stationary peculiar
 * velocities plus the shear flow, 5 steps of warm-up (5 tau_p), then
 * `steps` steps; K_e/K_ref into *ratio. */
static int replica(const sbv_ctx *ctx, unsigned long k,
                   sb_engine_detect det, double dt, size_t steps, size_t n,
                   const double L[3], const sb_engine_species *sp, double G,
                   double Kref, double *ratio)
{
  sb_engine_params p;
  sbv_engine_params(&p);
  p.dim = 3;
  memcpy(p.L, L, sizeof p.L);
  p.dt = dt;
  p.seed = ctx->seed * 1000 + LV_STREAM + k;
  p.outcome = SB_OUTCOME_COUNT;
  p.detect = det;
  p.capacity = n + 1;
  p.neigh = SB_NEIGH_CELLS;
  gsl_rng *r = sbv_rng_alloc(ctx, LV_STREAM + k);
  sb_engine *e = r ? sb_engine_alloc(&p) : NULL;
  int st = e ? v16_shear_fill(e, r, sp, n, L, G) : SB_ENOMEM;
  const size_t warm = (size_t)ceil(5.0 * sp->tau / dt);
  for (size_t q = 0; q < warm && !st; q++)
    st = sb_engine_step(e);
  if (!st)
    sb_engine_reset_counters(e);
  for (size_t q = 0; q < steps && !st; q++)
    st = sb_engine_step(e);
  sb_engine_pair_stats ps;
  if (!st)
    st = sb_engine_pair_kernel(e, 0, 0, 0.95, &ps);
  if (!st)
    *ratio = ps.K / Kref;
  sb_engine_free(e);
  gsl_rng_free(r);
  return st;
}

/* Write mode: detector d's replicas as one collide file with a sweep
 * point per replica (its engine seed and placement stream); the record
 * is the mean of kernel.K / K_ref over the points. */
static int write_replicas(const sbv_ctx *ctx, sbv_report *rep,
                          const char *det, const char *record, size_t nrep,
                          double dt, size_t steps, size_t n,
                          const double L[3], const sb_engine_species *sp,
                          double G, double Kref)
{
  char fn[64], what[96];
  snprintf(fn, sizeof fn, "V16_combined_shear_dt_tau_%s", det);
  snprintf(what, sizeof what, "V16/combined-shear: %s detection at dt = "
           "tau_p, Pe_k = 1", det);
  FILE *f = sbv_ini_begin(ctx, rep, fn, what);
  if (!f)
    return SB_EIO;
  fprintf(f, "warmup = %.17g\n", ceil(5.0 * sp->tau / dt) * dt);
  v16_ini_run_detect(f, ctx->seed * 1000 + LV_STREAM, L, dt, steps,
                     sbv_rng_seed(ctx, LV_STREAM), det);
  fprintf(f, "\n[fluid]\ntype = shear\nG = %.17g\nlees_edwards = yes\n"
          "\n[species a]\nradius = %.17g\nmass = %.17g\ntau = %.17g\n"
          "B = %.17g\ncount = %zu\n", G, sp->radius, sp->mass, sp->tau,
          sp->B, n);
  int st = sbv_ini_end(rep, f, NULL);
  sbv_ini_expect_sweep_mean(rep, record, "pair_kernels[a,a].K", 1.0 / Kref);
  for (size_t k = 0; k < nrep && !st; k++)
    st = sbv_ini_sweep_point(rep, k, "run.seed=%lu run.placement_seed=%lu",
                             ctx->seed * 1000 + LV_STREAM + k,
                             sbv_rng_seed(ctx, LV_STREAM + k));
  return st;
}

static double rep_mean(const double *x, size_t n)
{
  double m = 0.0;
  for (size_t k = 0; k < n; k++)
    m += x[k] / (double)n;
  return m;
}

int v16_shear_langevin_rows(const sbv_ctx *ctx, sbv_report *rep)
{
  const double rad = 5e-6, R = 2.0 * rad, G = 1000.0, tau = 1e-5;
  const double pk = 1.0, v2 = 0.5 * (G * R / pk) * (G * R / pk);
  const size_t n = 2000, nrep = ctx->full ? LV_MAXREP : 16;
  const size_t steps = 200;  /* 200 tau_p at dt = tau_p */
  const double V = (double)n * 4.0 / 3.0 * PI * rad * rad * rad / 0.5;
  const double l = cbrt(V / 0.4);
  const double L[3] = {l, 0.4 * l, l};
  const double Kref = sb_kernel_shear_langevin(rad, rad, v2, tau, G);
  const sb_engine_species sp = {rad, 1000.0 * 4.0 / 3.0 * PI * rad * rad *
                                         rad,
                                tau, sqrt(2.0 * v2 / tau), 0.0};
  static const char *const rec[2] = {
      "V16/combined-shear/langevin+shear/Pe_k=1/dt=tau_p/langevin/K_e/K_ref",
      "V16/combined-shear/langevin+shear/Pe_k=1/dt=tau_p/contact-time/"
      "K_e/K_ref"};
  static const sb_engine_detect det[2] = {SB_DETECT_LANGEVIN,
                                          SB_DETECT_BALLISTIC};
  static const char *const detname[2] = {"langevin", "ballistic"};
  int st = SB_SUCCESS;
  if (sbv_writing(ctx)) {
    for (int d = 0; d < 2 && !st; d++)
      st = write_replicas(ctx, rep, detname[d], rec[d], nrep, tau, steps, n,
                          L, &sp, G, Kref);
    return st;
  }
  double x[2][LV_MAXREP];
  for (int d = 0; d < 2 && !st; d++)
    for (size_t k = 0; k < nrep && !st; k++)
      st = replica(ctx, k, det[d], tau, steps, n, L, &sp, G, Kref,
                   &x[d][k]);
  if (st)
    return st;
  sbv_note(rep, "Langevin detector, dt = tau_p (Pe_k = %g, G tau_p = %.2g, "
           "%zu spheres, %zu steps after 5 tau_p of warm-up; %zu "
           "independent replicas, each its own seed and placement): the "
           "mean of the replicas' K_e/K_ref with its t interval (the count "
           "is over-dispersed: a grazing pair re-crosses the contact sphere "
           "several times).  Contact time on the same replicas misses the "
           "re-entries inside a step (expected failure).", pk, G * tau, n,
           steps, nrep);
  st = sbv_add_mean(rep, rec[0], x[0], nrep, 1.0);
  sb_comparison c;
  if (!st)  /* contact time: its replicas' t interval lies below 1 */
    st = sb_compare_mean(&c, "ct", x[1], nrep, 1.0, SBV_ALPHA);
  if (!st)
    st = sbv_add_side(rep, rec[1], 0, c.estimate, 1.0, c.ci_low, c.ci_high,
                      c.level, c.p_value);
  if (!st)
    sbv_note(rep, "- dt = tau_p, %zu replicas: langevin K_e/K_ref = %.4f, "
             "contact time %.4f", nrep, rep_mean(x[0], nrep),
             rep_mean(x[1], nrep));
  sbv_progress(ctx, "  V16 combined-shear langevin dt=tau_p");
  return st;
}
