/* cases_v16d.c — V16 cases of the detectors between step ends under the
 * new boundaries: Brownian + weak shear in the diffusive regime (bridge
 * detector across the Lees-Edwards images) against the small-Peclet
 * expansion of the absorbing-sphere flux (docs/engine_forces.md §8.3c),
 * and Langevin particles depositing on absorbing walls at dt = tau_p
 * (the Langevin wall detector) against the exact deposition law (§4).
 *
 * Reference.  Point particles diffuse (relative diffusivity D) and are
 * advected by the simple shear u = G y e_x relative to an absorbing
 * sphere of radius R, no hydrodynamic interaction.  For Pe = G R^2/D << 1
 * the matched expansion (inner region: pure diffusion; outer region,
 * lengths ~ sqrt(D/G): the linear flow around a point sink) gives the
 * steady flux 4 pi D R (1 + beta Pe^{1/2} + O(Pe)); the coefficient only
 * depends on the far field, which is the undisturbed linear flow, so it
 * is the same as for a freely rotating sphere in shear, Frankel & Acrivos
 * (1968), Phys. Fluids 11, 1913-1918, Nu = 1 + 0.257 Pe^{1/2} (see also
 * Batchelor 1979, J. Fluid Mech. 95, 369-400, for general linear flows).
 * Derived here: beta is the regular part at the origin of the Green
 * function of D lap - G y d/dx, the time integral of the transition
 * density of the relative motion (Gaussian, covariance of
 * dX = G Y dt + sqrt(2D) dW_x, dY = sqrt(2D) dW_y, dZ = sqrt(2D) dW_z
 * from 0: det = 8 D^3 t^3 (1 + (G t)^2/12)), so that
 *   p_t(0, 0) = (4 pi D t)^{-3/2} (1 + (G t)^2/12)^{-1/2},
 *   beta = J(inf)/sqrt(4 pi),  J(T) = int_0^T s^{-3/2} [1 - (1 +
 *   s^2/12)^{-1/2}] ds,  J(inf) = 12^{-1/4} B(3/4, 3/4),
 * beta = 0.256814 (0.257 printed by Frankel & Acrivos).  The same
 * matching in time, with the sink switched on at t = 0 (pairs uniform at
 * t = 0), gives to first order in R/sqrt(D t) and Pe^{1/2}
 *   K(t)/(4 pi D R) = 1 + R/sqrt(pi D t) + sqrt(Pe/(4 pi)) J(G t):
 * the first two terms are Smoluchowski's exact transient, the last one
 * the sheared part (its integrand is the free-minus-sheared transition
 * density at the origin).  The neglected terms are O(Pe) (second order
 * in R/sqrt(D/G)); the testing row sits at Pe = 0.1, an informational one
 * at Pe = 0.3. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include <gsl/gsl_cdf.h>
#include <gsl/gsl_integration.h>
#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>
#include <gsl/gsl_sf_gamma.h>

#include <smolbridge/engine.h>
#include <smolbridge/langevin.h>
#include <smolbridge/stats.h>

#include "common/numutil.h"
#include "cases.h"
#include "firsthit.h"
#include "v16.h"

#define PI 3.14159265358979323846

/* 1 - (1 + s^2/12)^{-1/2}, without cancellation at small s. */
static double shear_deficit(double s)
{
  return -expm1(-0.5 * log1p(s * s / 12.0));
}

static double j_integrand(double s, void *p)
{
  (void)p;
  return s > 0.0 ? shear_deficit(s) / (s * sqrt(s)) : 0.0;
}

static double jint_integrand(double s, void *p)
{
  (void)p;
  return s > 0.0 ? shear_deficit(s) / sqrt(s) : 0.0;
}

/* int_a^b f over (0, inf] (b = INFINITY) by CQUAD (sbi_integrate),
 * relative 1e-11; NaN on failure. */
static double quad(double (*f)(double, void *), double a, double b)
{
  gsl_function F = {f, NULL};
  double r, err;
  return sbi_integrate(&F, a, b, 0.0, 1e-11, 1000, &r, &err) ? NAN : r;
}

/* J(T) (file comment). */
static double shear_J(double T)
{
  return T > 0.0 ? quad(j_integrand, 0.0, T) : 0.0;
}

/* int_a^b J(s) ds = b J(b) - a J(a) - int_a^b s^{-1/2} f(s) ds (by parts,
 * J' = s^{-3/2} f). */
static double shear_J_integral(double a, double b)
{
  return b * shear_J(b) - a * shear_J(a) - quad(jint_integrand, a, b);
}

static int case_shear_diffusive(const sbv_ctx *ctx, sbv_report *rep)
{
  const double Jinf = shear_J(INFINITY);
  const double Jbeta = pow(12.0, -0.25) * gsl_sf_beta(0.75, 0.75);
  const double beta = Jinf / sqrt(4.0 * PI);
  int st = sbv_add_relband(rep, "V16/combined-shear-diffusive/reference/"
                           "J(inf)", Jinf, Jbeta, 1e-9);
  if (!st)  /* Frankel & Acrivos (1968) print 0.257 */
    st = sbv_add_relband(rep, "V16/combined-shear-diffusive/reference/"
                         "Pe^1/2-coefficient", beta, 0.257, 2e-3);
  /* 1 um spheres (rho_p = 1000) in water at 293.15 K, diffusive regime,
   * exact 3-D Brownian-bridge contact, first-hit counting */
  const double T = 293.15, mu = 1e-3, rho_p = 1000.0, d = 1e-6;
  const double mass = rho_p * PI * d * d * d / 6.0;
  const double tau = mass / (3.0 * PI * mu * d);
  const double Dp = SB_BOLTZMANN * T * tau / mass;
  const double R = d, D = 2.0 * Dp, tD = R * R / D;
  const size_t N = ctx->full ? 12000 : 3000;
  const double hits = ctx->full ? 40000.0 : 2000.0;
  sbv_note(rep, "Brownian + simple shear, diffusive regime: d = 1 um "
           "spheres (rho_p = 1000 kg/m^3, water, 293.15 K; relative D = "
           "%.4g m^2/s, R = d, t_D = R^2/D = %.3g s), %zu particles, dt = "
           "0.25 t_D >> tau_p = %.3g s, U_x = G (y - L/2) with Lees-Edwards "
           "boundaries, exact 3-D Brownian-bridge contact (image-aware "
           "records), first-hit counting after t1 = 10 t_D until 210 t_D "
           "(G t up to 21 Pe/0.1).  Reference: the first-order small-Peclet "
           "kernel K(t) = 4 pi D R [1 + R/sqrt(pi D t) + sqrt(Pe/(4 pi)) "
           "J(G t)], Pe = G R^2/D, integrated over the run (steady limit 1 "
           "+ %.6f Pe^1/2; Frankel & Acrivos 1968: 0.257); neglected terms "
           "O(Pe).", D, tD, N, tau, beta);
  static const double pes[] = {0.1, 0.3};
  for (size_t k = 0; k < sizeof pes / sizeof pes[0] && !st; k++) {
    const double Pe = pes[k], G = Pe / tD;
    lv_run q;
    memset(&q, 0, sizeof q);
    q.nsp = 1;
    q.d[0] = d;
    q.tau[0] = tau;
    q.mass[0] = mass;
    q.N[0] = N;
    q.temp = T;
    q.dt = 0.25 * tD;
    q.t1 = 10.0 * tD;
    q.T = 210.0 * tD;
    q.det = LV_EXACT;
    q.G = G;
    /* expected count per unit c K_B: the bracket of the file comment */
    const double KB = 4.0 * PI * D * R;
    const double bd = (q.T - q.t1) +
                      2.0 * R * (sqrt(q.T) - sqrt(q.t1)) / sqrt(PI * D);
    const double bs = sqrt(Pe / (4.0 * PI)) *
                      shear_J_integral(G * q.t1, G * q.T) / G;
    const double V = KB * (bd + bs) * 0.5 * (double)N * (double)N / hits;
    q.L = cbrt(V);
    q.fh_radius = R;
    lv_out o;
    char fn[64];
    snprintf(fn, sizeof fn, "V16_combined_shear_diffusive_Pe%g", Pe);
    if (sbv_writing(ctx))
      fh_set_name(rep, fn);
    st = lv_firsthit(ctx, 1660 + k, &q, &o);
    if (st)
      break;
    if (sbv_writing(ctx)) {
      /* collide's first_hit.K with first_hit_radius = R is hits veff /
       * (pairs apart teff), teff = (t - t1) + 2 R (sqrt t - sqrt t1) /
       * sqrt(pi D) at its end time t: the records are hits veff / (pairs
       * apart K_B (bd [+ bs])), so each is K times teff / (K_B (bd
       * [+ bs])); t is the sum of the steps, as the engine adds them */
      double t = 0.0;
      while (t < q.T - 0.5 * q.dt)
        t += q.dt;
      const double teff = (t - q.t1) + 2.0 * R * (sqrt(t) - sqrt(q.t1)) /
                                           sqrt(PI * D);
      char name[160];
      sbv_ini_no_expect(rep);
      snprintf(name, sizeof name, "V16/combined-shear-diffusive/Pe=%g/"
               "K_e/K_ref", Pe);
      sbv_ini_expect(rep, name, "first_hit.K", teff / (KB * (bd + bs)));
      snprintf(name, sizeof name, "V16/combined-shear-diffusive/Pe=%g/"
               "K_e/K_B(no shear)", Pe);
      sbv_ini_expect(rep, name, "first_hit.K", teff / (KB * bd));
      continue;  /* the records need the run */
    }
    const double c = o.npairs[0] / o.veff[0];
    const double Eref = c * KB * (bd + bs), Ediff = c * KB * bd;
    char name[160];
    snprintf(name, sizeof name, "V16/combined-shear-diffusive/Pe=%g/"
             "K_e/K_ref", Pe);
    if (Pe <= 0.1)
      st = sbv_add_poisson(rep, name, o.hits[0], 1.0 / Eref, 1.0);
    else {  /* beyond the first order: informational */
      double lo = 0.0, hi = 0.0;
      sb_poisson_rate_ci(o.hits[0], 1.0 / Eref, 0.95, &lo, &hi);
      st = sbv_add_info(rep, name, (double)o.hits[0] / Eref, 1.0, lo, hi,
                        0.95);
    }
    if (!st) {
      double lo = 0.0, hi = 0.0;
      sb_poisson_rate_ci(o.hits[0], 1.0 / Ediff, 0.95, &lo, &hi);
      snprintf(name, sizeof name, "V16/combined-shear-diffusive/Pe=%g/"
               "K_e/K_B(no shear)", Pe);
      st = sbv_add_info(rep, name, (double)o.hits[0] / Ediff, 1.0, lo, hi,
                        0.95);
    }
    if (!st) {
      snprintf(name, sizeof name, "V16/combined-shear-diffusive/Pe=%g/"
               "K_ref/K_B(no shear)", Pe);
      st = sbv_add_info(rep, name, Eref / Ediff, 1.0, NAN, NAN, 0.95);
    }
    sbv_note(rep, "- Pe = %g (G = %.4g 1/s, box %.3g m, %.0f steps): %lu "
             "first contacts, expected %.1f (first-order shear theory) and "
             "%.1f (pure diffusion); K_e/K_ref = %.4f, enhancement over "
             "the run K_ref/K_B = %.4f, steady 1 + beta Pe^1/2 = %.4f", Pe,
             G, q.L, o.steps, o.hits[0], Eref, Ediff,
             (double)o.hits[0] / Eref, Eref / Ediff,
             1.0 + beta * sqrt(Pe));
    sbv_progress(ctx, "  V16 combined-shear-diffusive Pe=%g", Pe);
  }
  return st;
}

/* ============================================ V16/deposition-langevin */

/* Deposition of Langevin particles (stationary velocities) started
 * uniform between two absorbing contact planes W apart, dt = tau_p.
 *
 * Reference (exact).  A particle starting at distance x0 from the lower
 * plane has reached it by t iff x0 <= M_t = max_{s<=t} (X_0 - X_s), its
 * largest displacement towards the plane, which does not depend on x0:
 * per unit area the number deposited by t is n E[M_t] (uniform density
 * n), so the fraction of the slab deposited on both walls is
 * 2 E[M_t]/W as long as no particle can reach both (W is 10 times the
 * displacement spread of the run).  Brownian limit: E[M_t] = sqrt(4 D t
 * /pi), the flux n sqrt(D/(pi t)) of Smoluchowski; ballistic limit t <<
 * tau_p: t E[U^+] = t sqrt(k_B T/(2 pi m)) (effusion).  E[M_t] of the
 * stationary integrated OU process has no closed form; it is estimated
 * here by an independent Monte Carlo of the exact OU transition
 * (Mohaupt 2011, eq 1.16; sb_langevin_coef_init) on a grid of tau_p/64,
 * NREF paths, the running maximum read on the grid (its bias, the
 * overshoot between grid points, is O((h/tau)^{3/2}) of sqrt(k_B T/m)
 * tau_p: < 1e-3 relative here).  The engine's window counts are binomial;
 * the rows' intervals combine both errors (normal approximation). */
enum { DL_NW = 5, DL_SUB = 64 };

/* E[M_t] at t = 2^k tau, k = 0..DL_NW-1, in units of sqrt(kT/m) tau, and
 * the standard errors of its window increments. */
static int dl_reference(gsl_rng *r, size_t npath, double em[DL_NW],
                        double se[DL_NW])
{
  sb_langevin_coef c;
  /* units tau = 1, k_B T/m = 1: B = sqrt(2) */
  if (sb_langevin_coef_init(&c, 1.0, sqrt(2.0), 1.0 / DL_SUB))
    return SB_EDOM;
  double s1[DL_NW] = {0}, s2[DL_NW] = {0};
  for (size_t p = 0; p < npath; p++) {
    double x = 0.0, u = gsl_ran_gaussian_ziggurat(r, 1.0), m = 0.0;
    double prev = 0.0;
    size_t step = 0;
    for (int k = 0; k < DL_NW; k++) {
      const size_t end = (size_t)DL_SUB << k;
      for (; step < end; step++) {
        const double z1 = gsl_ran_gaussian_ziggurat(r, 1.0);
        const double z2 = gsl_ran_gaussian_ziggurat(r, 1.0);
        x += u * c.gain + c.s_xu * z1 + c.s_xc * z2;
        u = u * c.decay + c.s_u * z1;
        if (-x > m)
          m = -x;
      }
      const double inc = m - prev;  /* the window's increment */
      s1[k] += inc;
      s2[k] += inc * inc;
      prev = m;
    }
  }
  double cum = 0.0;
  for (int k = 0; k < DL_NW; k++) {
    const double mean = s1[k] / (double)npath;
    cum += mean;
    em[k] = cum;
    se[k] = sqrt(fmax(0.0, s2[k] / (double)npath - mean * mean) /
                 (double)(npath - 1));
  }
  return SB_SUCCESS;
}

/* Each detector run's placement from its own stream (a collide file's
 * placement_seed); the reference Monte Carlo draws from DL_REF_STREAM. */
#define DL_REF_STREAM 1670UL
#define DL_PLACE_STREAM 1671UL  /* + detector */

static int case_deposition_langevin(const sbv_ctx *ctx, sbv_report *rep)
{
  gsl_rng *r = sbv_rng_alloc(ctx, DL_REF_STREAM);
  if (!r)
    return SB_ENOMEM;
  /* 50 nm spheres (rho_p = 1000) in air at 300 K, Stokes drag as
   * modelled (no slip correction: a model test, not an aerosol) */
  const double T = 300.0, mu = 1.8e-5, rho = 1000.0, rad = 25e-9;
  const double m = rho * 4.0 / 3.0 * PI * rad * rad * rad;
  const double tau = rho * 4.0 * rad * rad / (18.0 * mu);
  const double vth = sqrt(SB_BOLTZMANN * T / m), lam = vth * tau;
  const double D = SB_BOLTZMANN * T * tau / m;
  const double Tend = (double)(1 << (DL_NW - 1)) * tau;
  /* W: at least 10 displacement spreads (no particle reaches both
   * walls), and room for the neighbour search (L_y/2 above 2 r + 2 max
   * |disp|, which runs although nothing is detected) */
  const double W = fmax(10.0 * sqrt(2.0 * D * Tend), 3.0 * rad);
  const size_t N = ctx->full ? 2000000 : 200000;
  const size_t NREF = ctx->full ? 400000 : 20000;
  double em[DL_NW], se[DL_NW];
  int st = dl_reference(r, NREF, em, se);
  v16_setup s;
  memset(&s, 0, sizeof s);
  s.L[0] = s.L[2] = 300.0 * W;  /* dilute: the (unused) pair search is cheap */
  s.L[1] = W + 2.0 * rad;
  s.dt = tau;
  s.nsp = 1;
  s.sp[0] = (v16_species){rad, rho, tau, sqrt(2.0 * SB_BOLTZMANN * T /
                                               (m * tau)),
                          N, SB_DRAG_STOKES, 0.0, 0.0};
  s.walls[1] = SB_WALL_ABSORB;
  s.deposit = SB_DEPOSIT_REMOVE;
  s.nodetect = 1;
  s.steps = (size_t)1 << (DL_NW - 1);
  s.nmark = DL_NW;
  for (size_t k = 0; k < DL_NW; k++)
    s.mark[k] = (size_t)1 << k;
  static const sb_engine_walldet dets[3] = {
      SB_WALLDET_LANGEVIN, SB_WALLDET_BRIDGE, SB_WALLDET_BALLISTIC};
  static const char *dname[3] = {"langevin", "brownian-bridge", "chord"};
  v16_result res[3];
  for (int d = 0; d < 3 && !st; d++) {
    s.walldet = dets[d];
    s.seed = ctx->seed * 1000 + 1670 + (unsigned long)d;
    if (sbv_writing(ctx)) {
      /* the records: window counts (rows of series.csv, one per step)
       * over N times the reference fraction of the window */
      char fn[64], what[96];
      snprintf(fn, sizeof fn, "V16_deposition_langevin_%s", dname[d]);
      snprintf(what, sizeof what, "V16/deposition-langevin: dt = tau_p, "
               "%s wall detection", dname[d]);
      st = v16_write_walls(ctx, rep, &s,
                           sbv_rng_seed(ctx, DL_PLACE_STREAM +
                                                 (unsigned long)d),
                           1, fn, what);
      double eprev = 0.0;
      for (int k = 0; k < DL_NW && !st; k++) {
        const double P = 2.0 * (em[k] - eprev) * lam / W;
        char name[128];
        snprintf(name, sizeof name, "V16/deposition-langevin/dt=tau_p/%s/"
                 "t=%ddt/window-count", dname[d], 1 << k);
        v16_expect_window(rep, name, k ? (size_t)1 << (k - 1) : 0,
                          (size_t)1 << k, 1.0 / ((double)N * P));
        eprev = em[k];
      }
      continue;
    }
    gsl_rng *g = sbv_rng_alloc(ctx, DL_PLACE_STREAM + (unsigned long)d);
    st = g ? v16_run(&s, g, &res[d]) : SB_ENOMEM;
    gsl_rng_free(g);
  }
  if (sbv_writing(ctx)) {
    gsl_rng_free(r);
    return st;
  }
  sbv_note(rep, "Langevin deposition: %zu spheres (d = 50 nm, rho_p = 1000 "
           "kg/m^3, air, 300 K: tau_p = %.3g s, sqrt(kT/m) tau_p = %.3g m, "
           "D = %.4g m^2/s) uniform with stationary velocities between two "
           "absorbing contact planes W = %.3g m apart (%.0f x the spread "
           "sqrt(2 D t) of the run), dt = tau_p, particle-particle detection "
           "off; counts in the windows (0, 1], (1, 2], ..., (8, 16] dt.  "
           "Reference: fraction 2 E[M_t]/W deposited by t (M_t the largest "
           "displacement towards a wall; exact identity), E[M_t] by an "
           "independent Monte Carlo of the exact OU step on a grid of "
           "tau_p/64 (%zu paths); rows: window count / reference, interval "
           "and p-value from the binomial and Monte Carlo errors (normal "
           "approximation) at 99.99%%.  The Brownian-bridge and chord "
           "detectors at the same dt are informational.", N, tau, lam, D, W,
           W / sqrt(2.0 * D * Tend), NREF);
  const double zq = gsl_cdf_ugaussian_Qinv(0.5 * SBV_ALPHA);
  unsigned long long prev[3] = {0, 0, 0};
  double eprev = 0.0;
  for (int k = 0; k < DL_NW && !st; k++) {
    const double P = 2.0 * (em[k] - eprev) * lam / W;  /* window */
    const double sP = 2.0 * se[k] * lam / W;
    for (int d = 0; d < 3 && !st; d++) {
      const unsigned long long c = res[d].dep[k] - prev[d];
      prev[d] = res[d].dep[k];
      const double f = (double)c / (double)N, est = f / P;
      /* var(f/P) ~ P(1-P)/N / P^2 + (f/P)^2 (sP/P)^2 */
      const double sd = sqrt((1.0 - P) / ((double)N * P) +
                             est * est * (sP / P) * (sP / P));
      char name[128];
      snprintf(name, sizeof name, "V16/deposition-langevin/dt=tau_p/%s/"
               "t=%ddt/window-count", dname[d], 1 << k);
      if (d == 0) {
        sb_comparison cmp;
        const double z = (est - 1.0) / sd;
        sb_compare(&cmp, name, SB_RULE_COVER, est, 1.0, est - zq * sd,
                   est + zq * sd, 1.0 - SBV_ALPHA,
                   2.0 * gsl_cdf_ugaussian_Q(fabs(z)));
        st = sbv_add(rep, &cmp);
      } else
        st = sbv_add_info(rep, name, est, 1.0, est - 1.96 * sd,
                          est + 1.96 * sd, 0.95);
    }
    sbv_note(rep, "- window (%g, %d] dt: E[M_t] = %.5f sqrt(kT/m) tau_p "
             "(Brownian sqrt(4 D t/pi) = %.5f), reference fraction %.5f; "
             "Langevin %.5f, Brownian bridge %.5f, chord %.5f",
             k ? (double)(1 << (k - 1)) : 0.0, 1 << k, em[k],
             sqrt(4.0 * (double)(1 << k) / PI), P,
             (double)(res[0].dep[k] - (k ? res[0].dep[k - 1] : 0)) /
                 (double)N,
             (double)(res[1].dep[k] - (k ? res[1].dep[k - 1] : 0)) /
                 (double)N,
             (double)(res[2].dep[k] - (k ? res[2].dep[k - 1] : 0)) /
                 (double)N);
    eprev = em[k];
  }
  gsl_rng_free(r);
  return st;
}

const sbv_case sbv_cases_v16d[] = {
    {"V16/combined-shear-diffusive",
     "Brownian + weak simple shear, diffusive regime (Lees-Edwards images, "
     "exact Brownian-bridge detector, first-hit counting) against the "
     "small-Peclet flux 1 + 0.2568 Pe^1/2 (Frankel & Acrivos 1968) with "
     "its transient",
     case_shear_diffusive},
    {"V16/deposition-langevin",
     "Langevin particles between absorbing walls at dt = tau_p (the "
     "Langevin wall detector) against the exact deposition law 2 E[M_t]/W",
     case_deposition_langevin},
};
const size_t sbv_ncases_v16d = sizeof sbv_cases_v16d / sizeof sbv_cases_v16d[0];
