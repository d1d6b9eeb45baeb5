/* cases_engine.c — `smolbridge validate` cases of the collision engine
 * (issue 5): V1, V2, V9 of DESIGN.md.
 *
 *  V1/kinetic-gases     MD hard-sphere gases He, Ne, Ar, Kr, Xe (seed 003
 *                       Table 3.1: n = 250, L = 10 nm, T = 300 K, dt =
 *                       1e-14 s; He also at 1e-15 and 1e-13 s), elastic,
 *                       ballistic detection: K_e vs kinetic theory
 *                       K_th = pi d^2 sqrt(16 k_B T/(pi m)) g(sigma)
 *  V9/two-spheres-45    two equal spheres, 45° impact (seed 000 §7):
 *                       post-collision velocities vs the analytic ones
 *  V9/crossing-jets     two 2-D beams crossing at +-50° (seed 000 §8-9,
 *                       reduced): exit (end) distribution of the two
 *                       families with and without collisions
 *
 * V2 (Brownian spheres, contact time) lives in cases_v2.c.
 *
 * Verdicts: kernels pass iff the reference lies in the exact Garwood
 * interval of K_e at 1 - SBV_ALPHA (the exact Poisson test); the 45° case
 * iff |computed - analytic| <= 1e-12 (a tolerance band); jets: see
 * case_jets.
 *
 * Reductions (quick mode): V1 stops at ~1000 collisions per run (400 for
 * dt = 1e-15 s) instead of running as long as Mohaupt (2011) Figs 3.6-3.7;
 * --full runs 40 000 (+-1% at 95%).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_rng.h>

#include <smolbridge/engine.h>
#include <smolbridge/kernel.h>
#include <smolbridge/langevin.h>
#include <smolbridge/stats.h>

#include "cases.h"

#define PI 3.14159265358979323846
#define NSAMP 50   /* points of the K_e/K_th time series */

/* Carnahan-Starling contact value of the hard-sphere radial distribution
 * function: the equilibrium collision frequency of a dense gas is the
 * dilute one times g(sigma) (Enskog). */
static double g_cs(double phi)
{
  return (1.0 - 0.5 * phi) / ((1.0 - phi) * (1.0 - phi) * (1.0 - phi));
}

/* Record a kernel estimate K = scale * ncoll against Kref: exact
 * two-sided Poisson test of the collision count at SBV_ALPHA and the
 * Garwood interval it inverts. */
static int add_kernel(sbv_report *rep, const char *name, double K,
                      unsigned long long ncoll, double Kref)
{
  double scale = ncoll > 0 ? K / (double)ncoll : 1.0;
  return sbv_add_poisson(rep, name, (unsigned long)ncoll, scale, Kref);
}

/* ====================================================== V1 kinetic gases */

typedef struct {
  const char *name;
  double M;     /* molar mass, g/mol */
  double rvdw;  /* van der Waals radius, m */
} gas;

static const gas GASES[] = {{"He", 4.0, 140e-12},
                            {"Ne", 20.0, 154e-12},
                            {"Ar", 40.0, 188e-12},
                            {"Kr", 83.3, 202e-12},
                            {"Xe", 131.3, 216e-12}};

#define AVOGADRO 6.02214076e23

static int case_gases(const sbv_ctx *ctx, sbv_report *rep)
{
  const size_t n = 250;
  const double L = 10e-9, T = 300.0;
  /* runs: 5 gases at 1e-14 s, then He at 1e-15 and 1e-13 s */
  const int nrun = 7;
  double *plot = calloc((size_t)NSAMP * (nrun + 1), sizeof(double));
  if (!plot)
    return SB_ENOMEM;
  int st = SB_SUCCESS;
  sbv_note(rep, "n = %zu molecules, L = 10 nm, T = 300 K, elastic hard "
           "spheres of the van der Waals radius, free flight, velocities "
           "thermalised to T with zero momentum.", n);
  sbv_note(rep, "K_th = pi d^2 sqrt(16 k_B T/(pi m)) (sb_kernel_kinetic) "
           "times the Carnahan-Starling contact value g = (1-phi/2)/"
           "(1-phi)^3 (Enskog; phi = 0.003-0.011, g = 1.007-1.027).  "
           "Stops at %d collisions per run (%d for dt = 1e-15 s).",
           ctx->full ? 40000 : 1000, ctx->full ? 40000 : 400);
  for (int run = 0; run < nrun && !st; run++) {
    const gas *g = &GASES[run < 5 ? run : 0];
    double dt = run < 5 ? 1e-14 : (run == 5 ? 1e-15 : 1e-13);
    double m = g->M * 1e-3 / AVOGADRO, d = 2.0 * g->rvdw;
    double phi = (double)n * PI * d * d * d / 6.0 / (L * L * L);
    double Kth = sb_kernel_kinetic(d, d, m, m, T) * g_cs(phi);
    double target = ctx->full ? 40000.0
                              : (run == 5 ? 400 : 1000);
    double rate = Kth * (double)n * (double)(n - 1) / (2.0 * L * L * L);
    double t_end = target / rate;
    sb_engine_params p;
    sb_engine_params_default(&p);
    p.L[0] = p.L[1] = p.L[2] = L;
    p.dt = dt;
    p.capacity = n;
    p.seed = ctx->seed * 1000 + 100 + (unsigned long)run;
    sb_engine *e = sb_engine_alloc(&p);
    if (!e) {
      st = SB_ENOMEM;
      break;
    }
    sb_engine_species s = {g->rvdw, m, INFINITY, 0.0, T};
    st = sb_engine_add_species(e, &s, NULL);
    if (!st)
      st = sb_engine_fill_random(e, 0, 0, n);
    if (!st)
      st = sb_engine_thermalize(e, T);
    for (int k = 1; k <= NSAMP && !st; k++) {
      st = sb_engine_run_until(e, t_end * k / NSAMP);
      double K = NAN;
      if (!st)
        sb_engine_kernel(e, 0.95, &K, NULL, NULL);
      plot[(size_t)(k - 1) * (nrun + 1)] = (double)k / NSAMP;
      plot[(size_t)(k - 1) * (nrun + 1) + 1 + run] = K / Kth;
    }
    if (!st) {
      double K, lo, hi;
      sb_engine_stats stt;
      sb_engine_get_stats(e, &stt);
      sb_engine_kernel(e, 0.95, &K, &lo, &hi);
      char name[96];
      snprintf(name, sizeof name, "V1/%s/dt=%.0e", g->name, dt);
      st = add_kernel(rep, name, K, stt.ncoll, Kth);
      sbv_note(rep, "- %s, dt = %.0e s: %llu collisions in %.3g s (%llu "
               "steps, %llu dropped), K_e/K_th = %.4f [%.4f, %.4f]",
               g->name, dt, (unsigned long long)stt.ncoll, stt.t,
               (unsigned long long)stt.steps,
               (unsigned long long)stt.dropped, K / Kth, lo / Kth,
               hi / Kth);
      sbv_progress(ctx, "  V1 %s dt=%.0e: K_e/K_th = %.4f", g->name,
                   dt, K / Kth);
    }
    sb_engine_free(e);
  }
  if (!st)
    sbv_plot(ctx, rep, "V1_kinetic_gases",
             "V1: K_e/K_th over time, MD hard-sphere gases (seed 003 Figs "
             "3.6-3.7)",
             "t/t_end He Ne Ar Kr Xe He_dt1e-15 He_dt1e-13", plot, NSAMP,
             (size_t)nrun + 1,
             "set xlabel 't / t_end'\nset ylabel 'K_e / K_th'\n"
             "set yrange [0.7:1.3]\n"
             "plot for [c=2:8] $DATA u 1:c w lp t columnhead(c), 1 lc "
             "rgb 'black' notitle");
  free(plot);
  return st;
}

/* ============================================== V9 two spheres at 45° */

/* Equal spheres (radius 1e-6 m, mass 1e-15 kg, free flight), A moving at
 * v along x, B at rest, line of centres at 45° at contact.  Analytic:
 * A' = (v/2, v/2, 0), B' = (v/2, -v/2, 0) (normal components exchanged). */
static int case_45(const sbv_ctx *ctx, sbv_report *rep)
{
  (void)ctx;
  const double r = 1e-6, v = 0.1, dt = 1e-5, s2 = sqrt(2.0);
  sb_engine_params p;
  sb_engine_params_default(&p);
  p.L[0] = p.L[1] = p.L[2] = 1e-4;
  p.dt = dt;
  p.capacity = 2;
  sb_engine *e = sb_engine_alloc(&p);
  if (!e)
    return SB_ENOMEM;
  sb_engine_species s = {r, 1e-15, INFINITY, 0.0, 300.0};
  int st = sb_engine_add_species(e, &s, NULL);
  const double c = 5e-5;
  double xa[3] = {c - s2 * r - 0.5 * v * dt, c, c}, ua[3] = {v, 0, 0};
  double xb[3] = {c, c - s2 * r, c}, ub[3] = {0, 0, 0};
  if (!st)
    st = sb_engine_add_particle(e, 0, 0, xa, ua);
  if (!st)
    st = sb_engine_add_particle(e, 0, 1, xb, ub);
  if (!st)
    st = sb_engine_step(e);
  if (!st) {
    const double *u = sb_engine_velocities(e);
    const double want[4] = {v / 2, v / 2, v / 2, -v / 2};
    const double got[4] = {u[0], u[1], u[3], u[4]};
    const char *lab[4] = {"A_ux", "A_uy", "B_ux", "B_uy"};
    for (int k = 0; k < 4 && !st; k++) {
      char name[96];
      snprintf(name, sizeof name, "V9/two-spheres-45/%s", lab[k]);
      st = sbv_add_band(rep, name, got[k], want[k], got[k] - 1e-12 * v,
                        got[k] + 1e-12 * v);
    }
    sbv_note(rep, "Equal spheres r = 1 um, v = 0.1 m/s, impact at 45°: "
             "analytic A' = (v/2, v/2), B' = (v/2, -v/2); pass iff "
             "|computed - analytic| <= 1e-12 v.");
  }
  sb_engine_free(e);
  return st;
}

/* ============================================== V9 crossing jets (2-D) */

/* Two 2-D beams of free-flying discs (radius 2 um, 400 each, area
 * fraction 0.13 in their 0.2 mm x 0.2 mm source squares) cross at +-50°
 * with speed 1 m/s and a thermal spread of 2% (seed 000 §8: injection
 * angle 50°).  Family 0 starts high and moves down, family 1 low and up;
 * the run stops when the beams' centres have exchanged heights.  Without
 * collisions every particle of family 0 ends in the lower half ("no
 * mixing, the families stay grouped", seed 000 §9.1); with elastic
 * collisions part of it is deflected back (mixing, §9.2-9.3).  The "exit
 * distribution" is the final y-histogram of each family (plot). */
static int run_jets(const sbv_ctx *ctx, int collide, size_t *crossed,
                    size_t *nfam, double *hist, int nbin,
                    unsigned long long *n01)
{
  const double L = 1e-3, r = 2e-6, U = 1.0, a = 50.0 * PI / 180.0;
  const double m = 1e-12, vth = 0.02 * U;
  const size_t nb = 400;
  sb_engine_params p;
  sb_engine_params_default(&p);
  p.dim = 2;
  p.L[0] = p.L[1] = L;
  p.dt = 1e-6;
  p.capacity = 2 * nb;
  p.seed = ctx->seed * 1000 + 900;
  p.outcome = collide ? SB_OUTCOME_ELASTIC : SB_OUTCOME_COUNT;
  sb_engine *e = sb_engine_alloc(&p);
  if (!e)
    return SB_ENOMEM;
  sb_engine_species s = {r, m, INFINITY, 0.0, m * vth * vth / SB_BOLTZMANN};
  int st = sb_engine_add_species(e, &s, NULL);
  double lo0[3] = {0.1 * L, 0.6 * L, 0}, hi0[3] = {0.3 * L, 0.8 * L, 0};
  double lo1[3] = {0.1 * L, 0.2 * L, 0}, hi1[3] = {0.3 * L, 0.4 * L, 0};
  double u0[3] = {U * cos(a), -U * sin(a), 0}, u1[3] = {U * cos(a),
                                                       U * sin(a), 0};
  if (!st)
    st = sb_engine_fill_box(e, 0, 0, nb, lo0, hi0, u0);
  if (!st)
    st = sb_engine_fill_box(e, 0, 1, nb, lo1, hi1, u1);
  if (!st)
    st = sb_engine_run_until(e, 0.4 * L / (U * sin(a)));
  if (!st) {
    const double *x = sb_engine_positions(e);
    const int *f = sb_engine_families(e);
    crossed[0] = crossed[1] = nfam[0] = nfam[1] = 0;
    for (size_t i = 0; i < sb_engine_count(e); i++) {
      double y = x[3 * i + 1] / L;
      nfam[f[i]]++;
      if ((f[i] == 0 && y < 0.5) || (f[i] == 1 && y >= 0.5))
        crossed[f[i]]++;
      int b = (int)(y * nbin);
      b = b < 0 ? 0 : (b >= nbin ? nbin - 1 : b);
      hist[b * 2 + f[i]] += 1.0;
    }
    sb_engine_stats stt;
    sb_engine_get_stats(e, &stt);
    *n01 = (unsigned long long)stt.fam[0][1];
  }
  sb_engine_free(e);
  return st;
}

static int case_jets(const sbv_ctx *ctx, sbv_report *rep)
{
  enum { NB = 40 };
  double h[2][NB * 2];
  size_t cr[2][2], nf[2][2];
  unsigned long long n01[2];
  memset(h, 0, sizeof h);
  int st = SB_SUCCESS;
  for (int c = 0; c < 2 && !st; c++)
    st = run_jets(ctx, c, cr[c], nf[c], h[c], NB, &n01[c]);
  if (st)
    return st;
  /* no collisions: every particle crosses (reference 1 inside the
   * Clopper-Pearson interval of the crossed fraction) */
  for (int f = 0; f < 2 && !st; f++) {
    char name[96];
    snprintf(name, sizeof name, "V9/crossing-jets/no-collision/fam%d-crossed",
             f);
    st = sbv_add_freq(rep, name, cr[0][f], nf[0][f], 1.0);
  }
  /* collisions: the fraction that does not cross (mixing) must be
   * significantly above 0, its value without collisions */
  for (int f = 0; f < 2 && !st; f++) {
    size_t k = nf[1][f] - cr[1][f];
    double lo, hi;
    sb_binomial_ci(k, nf[1][f], 1.0 - SBV_ALPHA, &lo, &hi);
    char name[96];
    snprintf(name, sizeof name, "V9/crossing-jets/collisions/fam%d-mixed",
             f);
    /* PASS iff mixing is significant: the interval lies above 0 */
    st = sbv_add_side(rep, name, 1, (double)k / nf[1][f], 0.0, lo, hi,
                      1.0 - SBV_ALPHA, NAN);
  }
  sbv_note(rep, "2-D, L = 1 mm, 2 x 400 discs r = 2 um, speed 1 m/s at "
           "+-50°, spread 2%%, dt = 1 us, free flight.  No collisions: "
           "crossed fractions %zu/%zu and %zu/%zu (pass iff 1 is in the "
           "95%% interval).  Elastic collisions (%llu between families): "
           "%zu/%zu and %zu/%zu cross; the 'mixed' records pass iff the "
           "non-crossing fraction is significantly > 0 (the reference "
           "column is its no-collision value).",
           cr[0][0], nf[0][0], cr[0][1], nf[0][1], n01[1], cr[1][0],
           nf[1][0], cr[1][1], nf[1][1]);
  double plot[NB * 5];
  for (int b = 0; b < NB; b++) {
    plot[b * 5] = (b + 0.5) / NB;
    plot[b * 5 + 1] = h[0][b * 2];
    plot[b * 5 + 2] = h[0][b * 2 + 1];
    plot[b * 5 + 3] = h[1][b * 2];
    plot[b * 5 + 4] = h[1][b * 2 + 1];
  }
  sbv_plot(ctx, rep, "V9_crossing_jets",
           "V9: final y-distribution of the two families, crossing jets "
           "(seed 000 Figs 22-23)",
           "y/L fam0_nocoll fam1_nocoll fam0_coll fam1_coll", plot, NB, 5,
           "set xlabel 'y / L'\nset ylabel 'particles per bin'\n"
           "plot $DATA u 1:2 w histeps lc rgb 'red' t 'family 0, no "
           "collisions', $DATA u 1:3 w histeps lc rgb 'blue' t 'family 1, "
           "no collisions', $DATA u 1:4 w lp lc rgb 'red' t 'family 0, "
           "collisions', $DATA u 1:5 w lp lc rgb 'blue' t 'family 1, "
           "collisions'");
  return st;
}

/* ========================================================== table */

const sbv_case sbv_cases_engine[] = {
    {"V1/kinetic-gases",
     "MD hard-sphere gases He..Xe vs kinetic theory (seed 003 Table 3.1)",
     case_gases},
    {"V9/two-spheres-45",
     "two equal spheres at 45°: velocities vs analytic (seed 000 §7)",
     case_45},
    {"V9/crossing-jets",
     "2-D crossing jets with/without collisions (seed 000 §8-9)",
     case_jets},
};

const size_t sbv_ncases_engine =
    sizeof sbv_cases_engine / sizeof sbv_cases_engine[0];
