/* cases_engine.c — `smolbridge validate` cases of the collision engine
 * (docs/engine.md §10): V1, V2, V9.
 *
 *  V1/kinetic-gases     MD hard-sphere gases He, Ne, Ar, Kr, Xe (Mohaupt
 *                       2011, Table 3.1: n = 250, L = 10 nm, T = 300 K, dt =
 *                       1e-14 s; He also at 1e-15 and 1e-13 s), elastic,
 *                       ballistic detection: K_e vs kinetic theory
 *                       K_th = pi d^2 sqrt(16 k_B T/(pi m)) g(sigma)
 *  V9/two-spheres-45    two equal spheres, 45° impact (Thomine 2008, §7):
 *                       post-collision velocities vs the analytic ones
 *  V9/crossing-jets     two 2-D beams crossing at +-50° (Thomine 2008,
 *                       §8-9, reduced): exit (end) distribution of the two
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
 * Garwood interval it inverts, widened by the count's dispersion above 1
 * (sb_engine_set_count_variance). */
static int add_kernel(sbv_report *rep, const char *name, double K,
                      unsigned long long ncoll, double dispersion,
                      double Kref)
{
  double scale = ncoll > 0 ? K / (double)ncoll : 1.0;
  return sbv_add_poisson_dispersed(rep, name, (unsigned long)ncoll,
                                   dispersion, scale, Kref);
}

/* --full: run on until each species pair (a <= b < nsp) has counted
 * `target` collisions times its count's dispersion (above 1), so that its
 * interval is as narrow as `target` Poisson collisions would make it:
 * the runs were sized for Poisson counts (+-0.98% at 40 000), and the
 * collisions of V1's gases measure var/mean 1.0-1.65.  At most three
 * extensions, each to the time the shortfall needs at the rate so far
 * (plus 2%). */
static int extend_for_dispersion(sb_engine *e, size_t nsp, double target)
{
  int st = SB_SUCCESS;
  for (int it = 0; it < 3 && !st; it++) {
    double more = 1.0;
    for (size_t a = 0; a < nsp; a++)
      for (size_t b = a; b < nsp; b++) {
        sb_engine_pair_stats ps;
        if (sb_engine_pair_kernel(e, a, b, 0.95, &ps) || !ps.ncoll)
          continue;
        const double need = target * (ps.dispersion > 1.0 ? ps.dispersion
                                                          : 1.0);
        if ((double)ps.ncoll < need && need / (double)ps.ncoll > more)
          more = need / (double)ps.ncoll;
      }
    if (more <= 1.0)
      break;
    sb_engine_stats es;
    sb_engine_get_stats(e, &es);
    st = sb_engine_run_until(e, es.t_reset +
                                    1.02 * more * (es.t - es.t_reset));
  }
  return st;
}

/* The kernel of the engine's one species with the count's dispersion. */
static int one_species_kernel(const sb_engine *e, double *K, double *lo,
                              double *hi, double *dispersion)
{
  sb_engine_pair_stats ps;
  int st = sb_engine_pair_kernel(e, 0, 0, 0.95, &ps);
  *K = ps.K, *lo = ps.lo, *hi = ps.hi, *dispersion = ps.dispersion;
  return st;
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
           "Stops at %d collisions per run (%d for dt = 1e-15 s)%s.",
           ctx->full ? 40000 : 1000, ctx->full ? 40000 : 400,
           ctx->full ? ", times the count's var/mean where above 1" : "");
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
    if (sbv_writing(ctx)) {
      char fn[64], rec[96];
      snprintf(fn, sizeof fn, "V1_%s_dt%.0e", g->name, dt);
      snprintf(rec, sizeof rec, "V1/%s/dt=%.0e", g->name, dt);
      FILE *f = sbv_ini_begin(ctx, rep, fn, "V1: MD hard-sphere gas");
      if (!f) {
        st = SB_EIO;
        break;
      }
      fprintf(f, "seed = %lu\nrng = mt19937\n"
            "L = %.17g\ndt = %.17g\nt_end = %.17g\n"
              "thermalize = %.17g\ndetect = ballistic\noutcome = elastic\n"
              "\n[species %s]\nradius = %.17g\nmass = %.17g\ntau = inf\n"
              "T = %.17g\ncount = %zu\n", ctx->seed * 1000 + 100 +
              (unsigned long)run, L, dt, t_end, T, g->name, g->rvdw, m, T, n);
      st = sbv_ini_end(rep, f, NULL);
      sbv_ini_expect(rep, rec, "kernel.K", 1.0);
      continue;
    }
    sb_engine_params p;
    sbv_engine_params(&p);
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
    if (!st)
      st = sb_engine_set_count_variance(e, 1);
    for (int k = 1; k <= NSAMP && !st; k++) {
      st = sb_engine_run_until(e, t_end * k / NSAMP);
      double K = NAN;
      if (!st)
        sb_engine_kernel(e, 0.95, &K, NULL, NULL);
      plot[(size_t)(k - 1) * (nrun + 1)] = (double)k / NSAMP;
      plot[(size_t)(k - 1) * (nrun + 1) + 1 + run] = K / Kth;
    }
    if (!st && ctx->full)
      st = extend_for_dispersion(e, 1, target);
    if (!st) {
      double K, lo, hi, disp;
      sb_engine_stats stt;
      sb_engine_get_stats(e, &stt);
      st = one_species_kernel(e, &K, &lo, &hi, &disp);
      char name[96];
      snprintf(name, sizeof name, "V1/%s/dt=%.0e", g->name, dt);
      if (!st)
        st = add_kernel(rep, name, K, stt.ncoll, disp, Kth);
      sbv_note(rep, "- %s, dt = %.0e s: %llu collisions in %.3g s (%llu "
               "steps, %llu dropped), K_e/K_th = %.4f [%.4f, %.4f], "
               "var/mean of the count %.3f", g->name, dt,
               (unsigned long long)stt.ncoll, stt.t,
               (unsigned long long)stt.steps,
               (unsigned long long)stt.dropped, K / Kth, lo / Kth,
               hi / Kth, disp);
      sbv_progress(ctx, "  V1 %s dt=%.0e: K_e/K_th = %.4f", g->name,
                   dt, K / Kth);
    }
    sb_engine_free(e);
  }
  if (!st)
    sbv_plot(ctx, rep, "V1_kinetic_gases",
             "V1: K_e/K_th over time, MD hard-sphere gases (Mohaupt 2011, "
             "Figs 3.6-3.7)",
             "t/t_end He Ne Ar Kr Xe He_dt1e-15 He_dt1e-13", plot, NSAMP,
             (size_t)nrun + 1,
             "set xlabel 't / t_end'\nset ylabel 'K_e / K_th'\n"
             "set yrange [0.7:1.3]\n"
             "plot for [c=2:8] $DATA u 1:c w lp t columnhead(c), 1 lc "
             "rgb 'black' notitle");
  free(plot);
  return st;
}

/* ======================================= V1 dense gas, long steps */

/* Helium at phi = 0.05 (Enskog factor g = 1.137) with dt = 0.3 mean free
 * times: a molecule often meets two partners in one step, which the
 * engine processes in time order, re-detecting after each bounce.  With
 * one collision per particle per step this run would lose ~10% of its
 * contacts; here K_e must equal the Enskog rate. */
static int case_dense(const sbv_ctx *ctx, sbv_report *rep)
{
  const gas *g = &GASES[0];
  const size_t n = 2000;
  const double T = 300.0, phi = 0.05;
  const double m = g->M * 1e-3 / AVOGADRO, d = 2.0 * g->rvdw;
  const double V = (double)n * PI * d * d * d / 6.0 / phi, L = cbrt(V);
  const double Kth = sb_kernel_kinetic(d, d, m, m, T) * g_cs(phi);
  const double nu = (double)n / V * Kth;  /* collisions per molecule, 1/s */
  const double dt = 0.3 / nu;
  const double target = ctx->full ? 400000.0 : 20000.0;
  if (sbv_writing(ctx)) {
    double t1 = 0.0;  /* the time the warm-up reaches, step by step */
    while (t1 < 20.0 / nu - 0.5 * dt)
      t1 += dt;
    FILE *f = sbv_ini_begin(ctx, rep, "V1_dense_He_phi0.05",
                            "V1: dense helium, long steps");
    if (!f)
      return SB_EIO;
    fprintf(f, "seed = %lu\nrng = mt19937\n"
            "L = %.17g\ndt = %.17g\nwarmup = %.17g\n"
            "t_end = %.17g\nthermalize = %.17g\ndetect = ballistic\n"
            "outcome = elastic\n\n[species He]\nradius = %.17g\n"
            "mass = %.17g\ntau = inf\nT = %.17g\ncount = %zu\n",
            ctx->seed * 1000 + 160, L, dt, 20.0 / nu,
            t1 + 2.0 * target / (nu * (double)n), T, g->rvdw, m, T, n);
    int st = sbv_ini_end(rep, f, NULL);
    sbv_ini_expect(rep, "V1/dense/He/phi=0.05/dt=0.3t_free", "kernel.K",
                   1.0);
    return st;
  }
  sb_engine_params p;
  sbv_engine_params(&p);
  p.L[0] = p.L[1] = p.L[2] = L;
  p.dt = dt;
  p.capacity = n;
  p.seed = ctx->seed * 1000 + 160;
  sb_engine *e = sb_engine_alloc(&p);
  if (!e)
    return SB_ENOMEM;
  sb_engine_species s = {g->rvdw, m, INFINITY, 0.0, T};
  int st = sb_engine_add_species(e, &s, NULL);
  if (!st)
    st = sb_engine_fill_random(e, 0, 0, n);
  if (!st)
    st = sb_engine_thermalize(e, T);
  /* warm-up: 20 mean free times relax the random (non-overlapping)
   * placement to the equilibrium pair structure */
  if (!st)
    st = sb_engine_run_until(e, 20.0 / nu);
  if (!st)
    st = sb_engine_set_count_variance(e, 1);
  sb_engine_reset_counters(e);
  double t1 = sb_engine_time(e);
  if (!st)
    st = sb_engine_run_until(e, t1 + 2.0 * target / (nu * (double)n));
  if (!st) {
    double K, lo, hi, disp;
    sb_engine_stats es;
    sb_engine_get_stats(e, &es);
    st = one_species_kernel(e, &K, &lo, &hi, &disp);
    if (!st)
      st = add_kernel(rep, "V1/dense/He/phi=0.05/dt=0.3t_free", K, es.ncoll,
                      disp, Kth);
    sbv_note(rep, "Helium, %zu molecules at phi = %.2f (L = %.3g m), 300 "
             "K, dt = 0.3 mean free times (%.3g s); %llu collisions in "
             "%llu steps (%.2f per molecule and step), %llu re-examined "
             "pairs, %llu dropped; K_e/K_th = %.4f [%.4f, %.4f] (95%%), "
             "var/mean of the count %.3f, "
             "K_th = kinetic x Carnahan-Starling g = %.4f.", n, phi, L, dt,
             (unsigned long long)es.ncoll,
             (unsigned long long)(es.steps),
             2.0 * (double)es.ncoll / (double)n /
                 ((es.t - es.t_reset) / dt),
             (unsigned long long)es.redetected,
             (unsigned long long)es.dropped, K / Kth, lo / Kth, hi / Kth,
             disp, g_cs(phi));
  }
  sb_engine_free(e);
  return st;
}

/* ================================================= V1 binary mixture */

/* Contact values of the radial distribution functions of a hard-sphere
 * mixture, Boublik (1970) / Mansoori, Carnahan, Starling & Leland (1971):
 *   g_ij = 1/(1 - x3) + 3 h x2/(1 - x3)^2 + 2 (h x2)^2/(1 - x3)^3,
 *   h = d_i d_j/(d_i + d_j),  x_k = (pi/6) sum_l n_l d_l^k,
 * which reduces to Carnahan-Starling for one species.  The equilibrium
 * collision rate of a pair type is the kinetic one times g_ij (Enskog). */
static double g_mix(double di, double dj, const double *n, const double *d,
                    int ns)
{
  double x2 = 0.0, x3 = 0.0;
  for (int l = 0; l < ns; l++) {
    x2 += PI / 6.0 * n[l] * d[l] * d[l];
    x3 += PI / 6.0 * n[l] * d[l] * d[l] * d[l];
  }
  double h = di * dj / (di + dj), om = 1.0 - x3;
  return 1.0 / om + 3.0 * h * x2 / (om * om) +
         2.0 * h * h * x2 * x2 / (om * om * om);
}

static int case_mixture(const sbv_ctx *ctx, sbv_report *rep)
{
  /* He and Xe (Mohaupt 2011, Table 3.1 values) at 300 K, one box */
  const gas *g[2] = {&GASES[0], &GASES[4]};
  const size_t nsp[2] = {150, 150};
  const double L = 12e-9, T = 300.0, dt = 1e-14;
  const double target = ctx->full ? 40000.0 : 600.0; /* Xe-Xe contacts */
  double m[2], d[2], nd[2];
  for (int k = 0; k < 2; k++) {
    m[k] = g[k]->M * 1e-3 / AVOGADRO;
    d[k] = 2.0 * g[k]->rvdw;
    nd[k] = (double)nsp[k] / (L * L * L);
  }
  sb_engine_params p;
  sbv_engine_params(&p);
  p.L[0] = p.L[1] = p.L[2] = L;
  p.dt = dt;
  p.capacity = nsp[0] + nsp[1];
  p.seed = ctx->seed * 1000 + 150;
  sb_engine *e = sb_engine_alloc(&p);
  if (!e)
    return SB_ENOMEM;
  int st = SB_SUCCESS;
  for (int k = 0; k < 2 && !st; k++) {
    sb_engine_species s = {g[k]->rvdw, m[k], INFINITY, 0.0, T};
    st = sb_engine_add_species(e, &s, NULL);
    if (!st)
      st = sb_engine_fill_random(e, (size_t)k, k, nsp[k]);
  }
  if (!st)
    st = sb_engine_thermalize(e, T);
  /* run length from the rarest pair (Xe-Xe) */
  double Kxx = sb_kernel_kinetic(d[1], d[1], m[1], m[1], T) *
               g_mix(d[1], d[1], nd, d, 2);
  double Pxx = 0.5 * (double)nsp[1] * (double)(nsp[1] - 1);
  double t_end = target * L * L * L / (Kxx * Pxx);
  if (sbv_writing(ctx)) {
    sb_engine_free(e);
    if (st)
      return st;
    FILE *f = sbv_ini_begin(ctx, rep, "V1_mixture_He_Xe",
                            "V1: binary He + Xe gas");
    if (!f)
      return SB_EIO;
    fprintf(f, "seed = %lu\nrng = mt19937\n"
            "L = %.17g\ndt = %.17g\nwarmup = %.17g\n"
            "t_end = %.17g\nthermalize = %.17g\ndetect = ballistic\n"
            "outcome = elastic\n", ctx->seed * 1000 + 150, L, dt,
            0.1 * t_end, 1.1 * t_end, T);
    for (int k = 0; k < 2; k++)
      fprintf(f, "\n[species %s]\nradius = %.17g\nmass = %.17g\n"
              "tau = inf\nT = %.17g\nfamily = %d\ncount = %zu\n",
              k ? "Xe" : "He", g[k]->rvdw, m[k], T, k, nsp[k]);
    st = sbv_ini_end(rep, f, NULL);
    static const char *lb[2] = {"He", "Xe"};
    for (int a = 0; a < 2; a++)
      for (int b = a; b < 2; b++) {
        char rec[96], fld[96];
        double Kth = sb_kernel_kinetic(d[a], d[b], m[a], m[b], T) *
                     g_mix(d[a], d[b], nd, d, 2);
        snprintf(rec, sizeof rec, "V1/mixture/%s-%s/K_e/K_th", lb[a], lb[b]);
        snprintf(fld, sizeof fld, "pair_kernels[%s,%s].K", lb[a], lb[b]);
        sbv_ini_expect(rep, rec, fld, 1.0 / Kth);
      }
    return st;
  }
  if (!st)
    st = sb_engine_run_until(e, 0.1 * t_end);  /* warm-up */
  if (!st)
    st = sb_engine_set_count_variance(e, 1);
  sb_engine_reset_counters(e);
  if (!st)
    st = sb_engine_run_until(e, 1.1 * t_end);
  if (!st && ctx->full)
    st = extend_for_dispersion(e, 2, target);
  sbv_note(rep, "Binary hard-sphere gas, %zu He + %zu Xe in (12 nm)^3 at "
           "300 K, free flight, elastic, contact time, dt = 1e-14 s; after "
           "a warm-up of 10%% of the run, the kernel of each pair type "
           "(sb_engine_pair_kernel: its collisions over its pair exposure) "
           "vs kinetic theory times the Boublik-Mansoori contact value "
           "g_ij; exact Poisson test, its interval widened by the "
           "count's dispersion (each particle's and each pair's "
           "collisions: sb_engine_set_count_variance).", nsp[0], nsp[1]);
  static const char *lab[2] = {"He", "Xe"};
  for (size_t a = 0; a < 2 && !st; a++)
    for (size_t b = a; b < 2 && !st; b++) {
      sb_engine_pair_stats ps;
      st = sb_engine_pair_kernel(e, a, b, 0.95, &ps);
      if (st)
        break;
      double gab = g_mix(d[a], d[b], nd, d, 2);
      double Kth = sb_kernel_kinetic(d[a], d[b], m[a], m[b], T) * gab;
      char name[96];
      snprintf(name, sizeof name, "V1/mixture/%s-%s/K_e/K_th", lab[a],
               lab[b]);
      double scale = ps.ncoll ? ps.K / (double)ps.ncoll / Kth : 1.0;
      st = sbv_add_poisson_dispersed(rep, name, (unsigned long)ps.ncoll,
                                     ps.dispersion, scale, 1.0);
      sbv_note(rep, "- %s-%s: %llu collisions, K_e = %.4g m^3/s, K_th = "
               "%.4g (g = %.4f), K_e/K_th = %.4f [%.4f, %.4f] (95%%), "
               "var/mean of the count %.3f", lab[a], lab[b],
               (unsigned long long)ps.ncoll, ps.K, Kth, gab, ps.K / Kth,
               ps.lo / Kth, ps.hi / Kth, ps.dispersion);
    }
  sb_engine_free(e);
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
  sbv_engine_params(&p);
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
  if (sbv_writing(ctx)) {
    sb_engine_free(e);
    FILE *f = sbv_ini_begin(ctx, rep, "V9_two_spheres_45",
                            "V9: two spheres, impact at 45 degrees");
    if (!f)
      return SB_EIO;
    fprintf(f, "L = 1e-4\ndt = %.17g\nsteps = 1\nsnapshot_every = 1\n"
            "outcome = elastic\n\n[species sphere]\nradius = %.17g\n"
            "mass = 1e-15\ntau = inf\nT = 300\n"
            "particle = %.17g %.17g %.17g %.17g %.17g %.17g\n"
            "particle = %.17g %.17g %.17g %.17g %.17g %.17g\n", dt, r,
            xa[0], xa[1], xa[2], ua[0], ua[1], ua[2], xb[0], xb[1], xb[2],
            ub[0], ub[1], ub[2]);
    st = sbv_ini_end(rep, f, NULL);
    static const char *const lab[4] = {"A_ux", "A_uy", "B_ux", "B_uy"};
    static const char *const col[4] = {"id 0 ux", "id 0 uy", "id 1 ux",
                                       "id 1 uy"};
    for (int k = 0; k < 4; k++) {
      char rec[96], fld[96];
      snprintf(rec, sizeof rec, "V9/two-spheres-45/%s", lab[k]);
      snprintf(fld, sizeof fld, "snap_000000.csv %s", col[k]);
      sbv_ini_expect(rep, rec, fld, 1.0);
    }
    return st;
  }
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
 * with speed 1 m/s and a thermal spread of 2% (Thomine 2008, §8:
 * injection angle 50°).  Family 0 starts high and moves down, family 1 low and
 * up; the run stops when the beams' centres have exchanged heights.  Without
 * collisions every particle of family 0 ends in the lower half (the
 * families stay grouped, no mixing: Thomine 2008, §9.1); with elastic
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
  sbv_engine_params(&p);
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
  if (sbv_writing(ctx)) {
    sb_engine_free(e);
    double t_end = 0.4 * L / (U * sin(a)), t = 0.0;
    long nst = 0;
    while (t < t_end - 0.5 * p.dt) {
      t += p.dt;
      nst++;
    }
    FILE *f = sbv_ini_begin(ctx, ctx->ini_rep, collide ? "V9_jets_collisions"
                                              : "V9_jets_no_collision",
                            "V9: crossing jets in 2-D");
    if (!f)
      return SB_EIO;
    fprintf(f, "seed = %lu\nrng = mt19937\n"
            "dim = 2\nL = %.17g\ndt = %.17g\n"
            "t_end = %.17g\nsnapshot_every = %ld\noutcome = %s\n",
            p.seed, L, p.dt, t_end, nst, collide ? "elastic" : "count");
    for (int k = 0; k < 2; k++) {
      const double *lo = k ? lo1 : lo0, *hi = k ? hi1 : hi0;
      const double *u = k ? u1 : u0;
      fprintf(f, "\n[species jet%d]\nradius = %.17g\nmass = %.17g\n"
              "tau = inf\nT = %.17g\nfamily = %d\ncount = %zu\n"
              "region = %.17g %.17g %.17g %.17g\ndrift = %.17g %.17g\n", k,
              r, m, s.T, k, nb, lo[0], hi[0], lo[1], hi[1], u[0], u[1]);
    }
    memset(crossed, 0, 2 * sizeof *crossed);
    nfam[0] = nfam[1] = 1;  /* unit values */
    *n01 = 0;
    return sbv_ini_end(ctx->ini_rep, f, NULL);
  }
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
  if (sbv_writing(ctx)) {
    for (int c = 0; c < 2; c++)
      for (int f = 0; f < 2; f++) {
        char rec[96], fld[160];
        snprintf(rec, sizeof rec, "V9/crossing-jets/%s/fam%d-%s",
                 c ? "collisions" : "no-collision", f,
                 c ? "mixed" : "crossed");
        snprintf(fld, sizeof fld, "%s: last snapshot, fraction of family "
                 "%d with y %s L/2", c ? "V9_jets_collisions"
                                       : "V9_jets_no_collision", f,
                 (f == 0) != (c == 1) ? "<" : ">=");
        sbv_ini_expect(rep, rec, fld, 1.0);
      }
    return st;
  }
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
           "(Thomine 2008, Figs 22-24)",
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
     "MD hard-sphere gases He..Xe vs kinetic theory (Mohaupt 2011, "
     "Table 3.1)",
     case_gases},
    {"V1/dense-long-steps",
     "hard-sphere helium at phi = 0.05 with dt = 0.3 mean free times: "
     "several collisions per molecule and step",
     case_dense},
    {"V1/kinetic-mixture",
     "binary He + Xe gas: the kernel of each pair type vs kinetic theory "
     "(Mohaupt 2011, Table 3.1 values)",
     case_mixture},
    {"V9/two-spheres-45",
     "two equal spheres at 45°: velocities vs analytic (Thomine 2008, §7)",
     case_45},
    {"V9/crossing-jets",
     "2-D crossing jets with/without collisions (Thomine 2008, §8-9)",
     case_jets},
};

const size_t sbv_ncases_engine =
    sizeof sbv_cases_engine / sizeof sbv_cases_engine[0];
