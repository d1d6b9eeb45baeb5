/* test_langevin.c — closed forms of the langevin module against independent
 * computations: 150-digit mpmath vectors (tests/gen_langevin_ref.py ->
 * tests/data/langevin_*.csv), series and asymptotic limits, adaptive
 * quadrature of the Ito-isometry integrals, identities between the SI
 * helpers, and argument checking.  Monte Carlo checks are in
 * test_langevin_mc.c. */
#include <float.h>
#include <string.h>

#include <gsl/gsl_integration.h>
#include <gsl/gsl_rng.h>
#include <smolbridge/langevin.h>

#include "refdata.h"
#include "sweep.h"
#include "testutil.h"

/* Accuracy promised for the moments (the specification asks for 1e-12
 * at dt/tau = 1e-8 ... 1e8; the implementation reaches a few ulps). */
#define TOL_MOM 1e-13
/* Conditioned moments (information form; a few bits lost in det P). */
#define TOL_BRIDGE 1e-11

/* |got - want| <= tol |want| and the _e error bound covers the difference */
static void check_e(int (*fe)(double, double, double, sb_result *),
                    const char *what, double tau, double B, double t,
                    double want, double tol)
{
  sb_result r;
  char call[96];
  snprintf(call, sizeof call, "%s(tau=%g, B=%g, t=%g)", what, tau, B, t);
  ck_assert_int_eq(fe(tau, B, t, &r), SB_SUCCESS);
  ck_assert_result(r, want, tol, call);
}

/* ------------------------------------------------------ mpmath vectors */

START_TEST(test_var_vectors)
{
  sbt_table t;
  sbt_table_load("langevin_var.csv", &t);
  int (*fe[5])(double, double, double, sb_result *) = {
      sb_langevin_var_x_e, sb_langevin_var_u_e, sb_langevin_cov_xu_e,
      sb_langevin_var_x_cond_e, sb_langevin_msd_e};
  const char *nm[5] = {"var_x", "var_u", "cov_xu", "var_x_cond", "msd"};
  for (int i = 0; i < t.nrow; i++) {
    double tau = sbt_get(&t, i, "tau"), B = sbt_get(&t, i, "B");
    double tt = sbt_get(&t, i, "t");
    for (int k = 0; k < 5; k++)
      check_e(fe[k], nm[k], tau, B, tt, sbt_get(&t, i, nm[k]), TOL_MOM);
    /* plain forms agree with the _e forms */
    ck_assert_rel(sb_langevin_var_x(tau, B, tt), sbt_get(&t, i, "var_x"),
                  TOL_MOM);
    ck_assert_rel(sb_langevin_msd(tau, B, tt), sbt_get(&t, i, "msd"),
                  TOL_MOM);
    /* exp(-t/tau) has condition number t/tau: the rounding of the inputs
     * alone moves it by (t/tau) ulps */
    double kappa = 1 + tt / tau, vacf = sbt_get(&t, i, "vacf");
    ck_assert_rel(sb_langevin_vacf(tau, B, tt), vacf, TOL_TIGHT * kappa);
    ck_assert_rel(sb_langevin_vacf(tau, B, -tt), vacf, TOL_TIGHT * kappa);
  }
  sbt_table_free(&t);
}
END_TEST

/* Decade points dt/tau = 1e-8, 1e-4, 1, 1e4, 1e8 to relative 1e-12,
 * for the moment functions AND for the coefficients the exact step uses
 * (s_u^2 = var_u, s_u s_xu = cov, s_xu^2 + s_xc^2 = var_x). */
START_TEST(test_var_decade_points)
{
  sbt_table t;
  sbt_table_load("langevin_var.csv", &t);
  const double hs[] = {1e-8, 1e-4, 1.0, 1e4, 1e8};
  int found = 0;
  for (int i = 0; i < t.nrow; i++) {
    double tau = sbt_get(&t, i, "tau"), B = sbt_get(&t, i, "B");
    double tt = sbt_get(&t, i, "t");
    int hit = 0;
    for (size_t k = 0; k < sizeof hs / sizeof hs[0]; k++)
      hit |= fabs(tt / tau / hs[k] - 1) < 1e-12;
    if (!hit)
      continue;
    found++;
    double vx = sbt_get(&t, i, "var_x"), vu = sbt_get(&t, i, "var_u");
    double cv = sbt_get(&t, i, "cov_xu");
    double vxc = sbt_get(&t, i, "var_x_cond");
    ck_assert_rel(sb_langevin_var_x(tau, B, tt), vx, 1e-12);
    ck_assert_rel(sb_langevin_var_u(tau, B, tt), vu, 1e-12);
    ck_assert_rel(sb_langevin_cov_xu(tau, B, tt), cv, 1e-12);
    ck_assert_rel(sb_langevin_var_x_cond(tau, B, tt), vxc, 1e-12);
    sb_langevin_coef c;
    ck_assert_int_eq(sb_langevin_coef_init(&c, tau, B, tt), SB_SUCCESS);
    ck_assert_rel(c.s_u * c.s_u, vu, 1e-12);
    ck_assert_rel(c.s_u * c.s_xu, cv, 1e-12);
    ck_assert_rel(c.s_xu * c.s_xu + c.s_xc * c.s_xc, vx, 1e-12);
    ck_assert_rel(c.s_xc * c.s_xc, vxc, 1e-12);
    ck_assert_rel(c.decay, exp(-tt / tau), TOL_TIGHT);
    ck_assert_rel(c.gain, -tau * expm1(-tt / tau), TOL_TIGHT);
  }
  sbt_table_free(&t);
  ck_assert_int_eq(found, 15); /* 5 points x 3 parameter sets */
}
END_TEST

/* Parameters and start state of a row of langevin_moments.csv or
 * langevin_bridge.csv */
static sb_langevin row_par(const sbt_table *t, int i, double *x0, double *u0)
{
  *x0 = sbt_get(t, i, "x0");
  *u0 = sbt_get(t, i, "u0");
  sb_langevin p = {sbt_get(t, i, "tau"), sbt_get(t, i, "B"),
                   sbt_get(t, i, "us")};
  return p;
}

START_TEST(test_moments_vectors)
{
  sbt_table t;
  sbt_table_load("langevin_moments.csv", &t);
  for (int i = 0; i < t.nrow; i++) {
    double x0, u0, tt = sbt_get(&t, i, "t");
    sb_langevin p = row_par(&t, i, &x0, &u0);
    sb_langevin_mom m;
    ck_assert_int_eq(sb_langevin_moments(&p, tt, x0, u0, &m), SB_SUCCESS);
    /* means: a few ulps of the largest term of the sum */
    double a = -expm1(-tt / p.tau);
    double scale_x =
        fabs(x0) + fabs(p.us * tt) + fabs((u0 - p.us) * p.tau * a);
    double scale_u = fabs(p.us) + fabs(u0 - p.us);
    ck_assert_abs(m.mean_x, sbt_get(&t, i, "mean_x"),
                  8 * DBL_EPSILON * scale_x);
    ck_assert_abs(m.mean_u, sbt_get(&t, i, "mean_u"),
                  8 * DBL_EPSILON * scale_u);
    ck_assert_rel(m.var_x, sbt_get(&t, i, "var_x"), TOL_MOM);
    ck_assert_rel(m.var_u, sbt_get(&t, i, "var_u"), TOL_MOM);
    ck_assert_rel(m.cov_xu, sbt_get(&t, i, "cov_xu"), TOL_MOM);
  }
  sbt_table_free(&t);
}
END_TEST

START_TEST(test_bridge_vectors)
{
  sbt_table t;
  sbt_table_load("langevin_bridge.csv", &t);
  for (int i = 0; i < t.nrow; i++) {
    double x0, u0;
    sb_langevin p = row_par(&t, i, &x0, &u0);
    double dt = sbt_get(&t, i, "dt"), s = sbt_get(&t, i, "s");
    double x1 = sbt_get(&t, i, "x1"), u1 = sbt_get(&t, i, "u1");
    sb_langevin_mom m;
    ck_assert_int_eq(sb_langevin_bridge_moments(&p, dt, s, x0, u0, x1, u1,
                                                &m), SB_SUCCESS);
    double vx = sbt_get(&t, i, "var_x"), vu = sbt_get(&t, i, "var_u");
    double cv = sbt_get(&t, i, "cov_xu");
    ck_assert_msg(sbt_reldiff(m.var_x, vx) <= TOL_BRIDGE,
                  "row %d: var_x %.17g want %.17g (rel %.3g)", i, m.var_x, vx,
                  sbt_reldiff(m.var_x, vx));
    ck_assert_msg(sbt_reldiff(m.var_u, vu) <= TOL_BRIDGE,
                  "row %d: var_u %.17g want %.17g (rel %.3g)", i, m.var_u, vu,
                  sbt_reldiff(m.var_u, vu));
    /* the covariance can pass through 0: measure it on the scale
     * sqrt(var_x var_u) (i.e. the correlation to TOL_BRIDGE) */
    ck_assert_abs(m.cov_xu, cv, TOL_BRIDGE * sqrt(vx * vu));
    /* means: to TOL_BRIDGE conditional standard deviations, plus the
     * rounding of the inputs (x0, x1 are O(10) in some rows) */
    ck_assert_abs(m.mean_x, sbt_get(&t, i, "mean_x"),
                  TOL_BRIDGE * sqrt(vx) +
                      8 * DBL_EPSILON * (fabs(x0) + fabs(x1)));
    double mu = sbt_get(&t, i, "mean_u");
    ck_assert_msg(fabs(m.mean_u - mu) <=
                      TOL_BRIDGE * sqrt(vu) +
                          8 * DBL_EPSILON * (fabs(u0) + fabs(u1) + fabs(p.us)),
                  "row %d: mean_u %.17g want %.17g", i, m.mean_u, mu);
  }
  sbt_table_free(&t);
}
END_TEST

/* ------------------------------------------------------ series, limits */

START_TEST(test_small_time_series)
{
  /* h = t/tau -> 0, tau = 2, B = 0.7.  Series (docs/langevin.md):
   * var_x/(B^2 tau^3) = h^3/3 - h^4/4 + 7 h^5/60 - h^6/24 + ...,
   * var_x_cond/(B^2 tau^3) = h^3/12 - h^5/120 + ...,
   * var_u/(B^2 tau) = h - h^2 + 2h^3/3 - ..., cov/(B^2 tau^2) = h^2/2 - h^3/2
   * + 7h^4/24 - h^5/8.  Truncation <= 1e-14 relative at h = 1e-4 (and
   * below). */
  const double tau = 2.0, B = 0.7, B2 = B * B;
  for (double h = 1e-4; h >= 1e-12; h *= 0.01) {
    double t = h * tau, h2 = h * h, h3 = h2 * h;
    ck_assert_rel(sb_langevin_var_x(tau, B, t),
                  B2 * tau * tau * tau *
                      (h3 / 3 - h2 * h2 / 4 + 7 * h3 * h2 / 60 -
                       h3 * h3 / 24),
                  1e-14);
    ck_assert_rel(sb_langevin_var_x_cond(tau, B, t),
                  B2 * tau * tau * tau * (h3 / 12 - h3 * h2 / 120), 1e-14);
    ck_assert_rel(sb_langevin_var_u(tau, B, t),
                  B2 * tau * (h - h2 + 2 * h3 / 3 - h2 * h2 / 3), 1e-14);
    ck_assert_rel(sb_langevin_cov_xu(tau, B, t),
                  B2 * tau * tau *
                      (h2 / 2 - h3 / 2 + 7 * h2 * h2 / 24 - h3 * h2 / 8),
                  1e-14);
    /* MSD: (B^2 tau/2) t^2 (1 - h/3 + h^2/12 - h^3/60) */
    ck_assert_rel(sb_langevin_msd(tau, B, t) /
                      sb_langevin_msd_ballistic(tau, B, t),
                  1 - h / 3 + h2 / 12 - h3 / 60, 1e-14);
  }
  /* t = 0 exactly: everything vanishes, nothing is NaN */
  ck_assert(sb_langevin_var_x(tau, B, 0) == 0);
  ck_assert(sb_langevin_var_u(tau, B, 0) == 0);
  ck_assert(sb_langevin_msd(tau, B, 0) == 0);
}
END_TEST

START_TEST(test_large_time_limits)
{
  /* h >> 1: var_x = B^2 tau^3 (h - 3/2 + 2e^{-h} - e^{-2h}/2) exactly, so
   * for h >= 40 it is B^2 tau^3 (h - 1.5) to rounding; var_x_cond ->
   * B^2 tau^3 (h - 2); var_u -> B^2 tau/2; cov -> B^2 tau^2/2;
   * MSD -> B^2 tau^3 (h - 1) (diffusive limit 2 D t with offset). */
  const double tau = 3e-6, B = 2.27, B2 = B * B, T3 = tau * tau * tau;
  for (double h = 40; h <= 1e12; h *= 10) {
    double t = h * tau;
    ck_assert_rel(sb_langevin_var_x(tau, B, t), B2 * T3 * (h - 1.5),
                  TOL_TIGHT);
    ck_assert_rel(sb_langevin_var_x_cond(tau, B, t), B2 * T3 * (h - 2),
                  TOL_TIGHT);
    ck_assert_rel(sb_langevin_var_u(tau, B, t), sb_langevin_var_stat(tau, B),
                  TOL_TIGHT);
    ck_assert_rel(sb_langevin_cov_xu(tau, B, t), B2 * tau * tau / 2,
                  TOL_TIGHT);
    ck_assert_rel(sb_langevin_msd(tau, B, t), B2 * T3 * (h - 1), TOL_TIGHT);
    ck_assert_rel(sb_langevin_msd(tau, B, t) /
                      sb_langevin_msd_diffusive(tau, B, t),
                  1 - 1 / h, TOL_TIGHT);
  }
}
END_TEST

/* ----------------------------------------------------------- quadrature */

typedef struct {
  double tau, B, t;
  int which;
} qpar;

/* Ito isometry integrands over the lag r in [0, t]:
 * 0: var_x = B^2 tau^2 int (1 - e^{-r/tau})^2 dr
 * 1: var_u = B^2 int e^{-2r/tau} dr
 * 2: cov   = B^2 tau int (1 - e^{-r/tau}) e^{-r/tau} dr
 * 3: MSD   = 2 int (t - r) vacf(r) dr  (stationary velocity) */
static double integrand(double r, void *vp)
{
  const qpar *q = vp;
  double e = exp(-r / q->tau), B2 = q->B * q->B;
  switch (q->which) {
  case 0: return B2 * q->tau * q->tau * (1 - e) * (1 - e);
  case 1: return B2 * e * e;
  case 2: return B2 * q->tau * (1 - e) * e;
  default: return 2 * (q->t - r) * 0.5 * B2 * q->tau * e;
  }
}

START_TEST(test_quadrature)
{
  gsl_integration_workspace *w = gsl_integration_workspace_alloc(1000);
  double (*f[4])(double, double, double) = {
      sb_langevin_var_x, sb_langevin_var_u, sb_langevin_cov_xu,
      sb_langevin_msd};
  const double hs[] = {0.01, 0.7, 1.0, 5.0, 30.0};
  for (size_t k = 0; k < sizeof hs / sizeof hs[0]; k++)
    for (int which = 0; which < 4; which++) {
      qpar q = {1.3, 0.45, hs[k] * 1.3, which};
      gsl_function F = {integrand, &q};
      double val, err;
      ck_assert_int_eq(gsl_integration_qag(&F, 0, q.t, 0, 1e-13, 1000,
                                           GSL_INTEG_GAUSS61, w, &val, &err),
                       0);
      ck_assert_rel(f[which](q.tau, q.B, q.t), val, TOL_QUAD);
    }
  gsl_integration_workspace_free(w);
}
END_TEST

/* ---------------------------------------------------- bridge: limits */

START_TEST(test_bridge_limits)
{
  /* Diffusive limit (dt/tau = 1e6): X_s is a Brownian bridge with
   * B_pos = B tau (Mohaupt 2011, eq J.5): variance B^2 tau^2 s (dt - s)/dt.
   * The mean: Y = X + tau U is exactly a Brownian motion with B_pos
   * (integrate dU = -U/tau dt + B dW), started at x0 + tau u0.  The OU
   * velocity is time-reversible with U -> -U, so seen from the end the
   * same argument starts Y at x1 - tau u1.  Far from both ends (U_s mean
   * ~0) X_s is the Brownian bridge between these two points.  Both up to
   * relative corrections of order tau / min(s, dt - s). */
  sb_langevin p = {1e-3, 2.0, 0.0};
  double dt = 1e3, x0 = 0.1, x1 = 0.1 + 3 * p.B * p.tau * sqrt(dt);
  for (double f = 0.1; f < 0.95; f += 0.2) {
    double s = f * dt;
    sb_langevin_mom m;
    ck_assert_int_eq(sb_langevin_bridge_moments(&p, dt, s, x0, 0.3, x1, -0.2,
                                                &m), SB_SUCCESS);
    double vbb = p.B * p.B * p.tau * p.tau * s * (dt - s) / dt;
    double corr = 3 * p.tau / fmin(s, dt - s);
    ck_assert_rel(m.var_x, vbb, corr);
    double y0 = x0 + p.tau * 0.3, y1 = x1 - p.tau * (-0.2);
    ck_assert_abs(m.mean_x, y0 + (y1 - y0) * s / dt, corr * sqrt(vbb));
    /* the velocity forgets both end velocities: stationary variance, and
     * mean the bridge's drift (y1 - y0)/dt (same order of corrections) */
    double vs = sb_langevin_var_stat(p.tau, p.B);
    ck_assert_rel(m.var_u, vs, corr);
    ck_assert_abs(m.mean_u, (y1 - y0) / dt, corr * sqrt(vs));
  }
  /* End points: zero variance and the given states, bit-exactly */
  sb_langevin_mom m;
  ck_assert_int_eq(sb_langevin_bridge_moments(&p, dt, 0.0, 1, 2, 3, 4, &m),
                   SB_SUCCESS);
  ck_assert(m.mean_x == 1 && m.mean_u == 2 && m.var_x == 0 && m.var_u == 0);
  ck_assert_int_eq(sb_langevin_bridge_moments(&p, dt, dt, 1, 2, 3, 4, &m),
                   SB_SUCCESS);
  ck_assert(m.mean_x == 3 && m.mean_u == 4 && m.cov_xu == 0);
  /* Near the ends the law collapses continuously onto the end state */
  ck_assert_int_eq(sb_langevin_bridge_moments(&p, dt, dt * (1 - 1e-9), 1, 2,
                                              3, 4, &m), SB_SUCCESS);
  /* ... moving back from x1 = 3 with the end velocity u1 = 4 */
  ck_assert_abs(m.mean_x, 3 - 4 * (dt * 1e-9), 1e-8); /* + drag O(r^2/tau) */
  ck_assert_abs(m.mean_u, 4, 1e-2);
  ck_assert(m.var_x >= 0 && m.var_x < 1e-9);
  /* Sampler draws with one generator state reproduce bit-exactly */
  gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
  double xa, ua, xb, ub;
  gsl_rng_set(r, 7);
  sb_langevin_bridge_sample(&p, dt, 0.4 * dt, x0, 0.3, x1, -0.2, r, &xa, &ua);
  gsl_rng_set(r, 7);
  sb_langevin_bridge_sample(&p, dt, 0.4 * dt, x0, 0.3, x1, -0.2, r, &xb, &ub);
  ck_assert(xa == xb && ua == ub);
  gsl_rng_free(r);
}
END_TEST

/* Law of total variance, a reference-free check of the bridge:
 *   Var(Z_s | z0) = E[Var(Z_s | z0, Z_dt)] + Var(E[Z_s | z0, Z_dt]).
 * The conditional covariance does not depend on Z_dt and the conditional
 * mean is linear in Z_dt, so three end states give the gain, and the
 * identity ties the bridge moments to the unconditioned ones.  Also: at the
 * unconditioned end mean the conditioned mean is the unconditioned mean. */
START_TEST(test_bridge_total_variance)
{
  const double hs[] = {1e-6, 0.1, 1.0, 10.0, 1e4};
  for (size_t k = 0; k < sizeof hs / sizeof hs[0]; k++) {
    sb_langevin p = {0.8, 1.3, 0.25};
    double dt = hs[k] * p.tau, s = 0.37 * dt, x0 = 0.0, u0 = -1.0;
    sb_langevin_mom prior_s, prior_t, c0, cx, cu;
    sb_langevin_moments(&p, s, x0, u0, &prior_s);
    sb_langevin_moments(&p, dt, x0, u0, &prior_t);
    double sx = sqrt(prior_t.var_x), su = sqrt(prior_t.var_u);
    double xm = prior_t.mean_x, um = prior_t.mean_u;
    sb_langevin_bridge_moments(&p, dt, s, x0, u0, xm, um, &c0);
    sb_langevin_bridge_moments(&p, dt, s, x0, u0, xm + sx, um, &cx);
    sb_langevin_bridge_moments(&p, dt, s, x0, u0, xm, um + su, &cu);
    /* mean at the unconditioned end mean = unconditioned mean at s */
    ck_assert_abs(c0.mean_x, prior_s.mean_x, 1e-10 * sqrt(prior_s.var_x));
    ck_assert_abs(c0.mean_u, prior_s.mean_u, 1e-10 * sqrt(prior_s.var_u));
    /* gain K (per unit of the end-state standard deviations) */
    double kxx = (cx.mean_x - c0.mean_x), kxu = (cu.mean_x - c0.mean_x);
    double kux = (cx.mean_u - c0.mean_u), kuu = (cu.mean_u - c0.mean_u);
    double rho = prior_t.cov_xu / (sx * su);
    /* Var(K d), d ~ N(0, [[1, rho], [rho, 1]]) in standardised units */
    double vmx = kxx * kxx + kxu * kxu + 2 * rho * kxx * kxu;
    double vmu = kux * kux + kuu * kuu + 2 * rho * kux * kuu;
    double cmxu = kxx * kux + kxu * kuu + rho * (kxx * kuu + kxu * kux);
    ck_assert_rel(c0.var_x + vmx, prior_s.var_x, 1e-9);
    ck_assert_rel(c0.var_u + vmu, prior_s.var_u, 1e-9);
    ck_assert_abs(c0.cov_xu + cmxu, prior_s.cov_xu,
                  1e-9 * sqrt(prior_s.var_x * prior_s.var_u));
  }
}
END_TEST

/* ------------------------------------------------------- SI helpers */

START_TEST(test_si_helpers)
{
  /* Mohaupt 2011, Table D.1: d_p = 1 um, rho_p/rho_f = 1000, tau_p = 3e-6 s
   * corresponds to a gas with nu_f = rho_p d^2/(18 rho_f tau_p)
   * = 1.85e-5 m^2/s; tau_p then comes back exactly. */
  double rho_f = 1.2, rho_p = 1000 * rho_f, d = 1e-6;
  double nu = 1000 * d * d / (18 * 3e-6);
  ck_assert_rel(sb_stokes_tau(rho_p, d, rho_f * nu, 1.0), 3e-6, TOL_TIGHT);
  /* Einstein: D = k T Cc/(3 pi mu d) equals B^2 tau^2/2 with
   * B^2 = 2kT/(m tau), for any Cc (tau scales with Cc) */
  double T = 293.15, mu = 1.81e-5, cc = sb_cunningham(sb_knudsen(66e-9, d));
  double tau = sb_stokes_tau(rho_p, d, mu, cc);
  double m = sb_sphere_mass(rho_p, d);
  double B = sb_brownian_B(T, m, tau);
  ck_assert_rel(sb_einstein_D(T, mu, d, cc), 0.5 * B * B * tau * tau,
                TOL_TIGHT);
  /* equipartition: stationary velocity variance = kT/m */
  ck_assert_rel(sb_langevin_var_stat(tau, B), SB_BOLTZMANN * T / m,
                TOL_TIGHT);
  ck_assert_rel(m, rho_p * 4.0 / 3.0 * M_PI * 0.125 * d * d * d, TOL_TIGHT);
  /* Knudsen number: mean free path over radius */
  ck_assert_rel(sb_knudsen(66e-9, 1e-6), 0.132, TOL_TIGHT);
  /* Cunningham (Davies 1945): continuum limit 1 with slope A1 + A2 e^{-A3/Kn}
   * -> 1 + 1.257 Kn; free-molecular limit Kn (A1 + A2) = 1.657 Kn. */
  ck_assert(sb_cunningham(0) == 1.0);
  ck_assert_rel(sb_cunningham(1e-3), 1 + 1.257e-3, 1e-12);
  ck_assert_rel(sb_cunningham(1e4) / 1e4, 1.657, 1e-4);
  /* d = 0.1 um in air (lambda = 0.066 um): Kn = 1.32,
   * Cc = 1 + 1.32 (1.257 + 0.4 exp(-1.1/1.32)) = 2.8887078540917... */
  ck_assert_rel(sb_cunningham(1.32), 2.888707854091737, TOL_TIGHT);
  ck_assert_rel(sb_cunningham_gen(1.32, 1.257, 0.4, 1.1),
                sb_cunningham(1.32), TOL_TIGHT);
  /* domain errors */
  ck_assert(isnan(sb_stokes_tau(-1, d, mu, 1)));
  ck_assert_int_eq(sb_last_status(), SB_EDOM);
  ck_assert(isnan(sb_stokes_tau(rho_p, d, mu, 0.5)));
  ck_assert(isnan(sb_brownian_B(0, m, tau)));
  ck_assert(isnan(sb_einstein_D(T, mu, NAN, 1)));
  ck_assert(isnan(sb_knudsen(66e-9, 0)));
  ck_assert(isnan(sb_cunningham(-1)));
  ck_assert(isnan(sb_cunningham_gen(1, 1, 1, -1)));
  ck_assert(isnan(sb_sphere_mass(INFINITY, d)));
}
END_TEST


/* -------------------------------------------- dimensionless numbers */

/* integrand w^k exp(-w^2/(2 s2)) for the Maxwell relative speed */
typedef struct { double s2; int k; } speed_mom;
static double speed_mom_f(double w, void *p)
{
  const speed_mom *m = p;
  return pow(w, m->k) * exp(-w * w / (2.0 * m->s2));
}

static double speed_moment(double s2, int k)
{
  gsl_integration_workspace *ws = gsl_integration_workspace_alloc(200);
  speed_mom m = {s2, k};
  gsl_function F = {speed_mom_f, &m};
  double v = NAN, err;
  gsl_integration_qagiu(&F, 0.0, 0.0, 1e-13, 200, ws, &v, &err);
  gsl_integration_workspace_free(ws);
  return v;
}

START_TEST(test_dimensionless)
{
  /* Mohaupt 2011, eq 6.3: water (nu = 1e-6), eps = 1e-5 and 1e-2 give
   * eta = 560 um and 100 um */
  ck_assert_rel(sb_kolmogorov_length(1e-5, 1e-6), 5.6234e-4, 1e-4);
  ck_assert_rel(sb_kolmogorov_length(1e-2, 1e-6), 1e-4, TOL_TIGHT);
  ck_assert_rel(sb_kolmogorov_time(1e-4, 1e-6), 0.1, TOL_TIGHT);
  /* Mohaupt 2011, eq 6.4: tau_k = 0.316 s and 0.01 s at the same eps */
  ck_assert(fabs(sb_kolmogorov_time(1e-5, 1e-6) - 0.316) < 0.0005);
  ck_assert_rel(sb_kolmogorov_time(1e-2, 1e-6), 0.01, TOL_TIGHT);
  /* eta = sqrt(nu tau_eta) by definition of both */
  ck_assert_rel(sb_kolmogorov_length(3e-3, 1.5e-5),
                sqrt(1.5e-5 * sb_kolmogorov_time(3e-3, 1.5e-5)), TOL_TIGHT);
  ck_assert_rel(sb_stokes_number(3e-6, 0.1), 3e-5, TOL_TIGHT);
  ck_assert_rel(sb_particle_reynolds(1e-5, 0.01, 1e-6), 0.1, TOL_TIGHT);
  ck_assert(sb_particle_reynolds(1e-5, 0.0, 1e-6) == 0.0);
  /* collision-weighted mean relative speed E|w|^2/E|w| against GSL
   * quadrature of the Maxwell law of the relative speed (per-component
   * variance 2 u2), for three u2 */
  const double u2s[3] = {7.9e-3, 1.0, 2.5e4};
  for (int i = 0; i < 3; i++) {
    double s2 = 2.0 * u2s[i];
    double ratio = speed_moment(s2, 4) / speed_moment(s2, 3);
    ck_assert_rel(sb_collision_speed(u2s[i]), ratio, 1e-11);
  }
  /* Mohaupt 2011, eq 3.2, and its worked values: Brownian agitation
   * T_p = k_B T/m_p of a sphere of density 1000 kg/m^3 at 300 K (no
   * fluid property enters), frac = 13%: 5.5e-8 s at 0.1 um and 5.5e-3 s
   * at 10 um, given to two figures (computed: 5.4976e-8, 5.4976e-3 s) */
  double t1 = sb_wunsch_dt_brownian(1e-7, 1000.0, 300.0, 0.13);
  double t2 = sb_wunsch_dt_brownian(1e-5, 1000.0, 300.0, 0.13);
  ck_assert(fabs(t1 - 5.5e-8) <= 0.05e-8);
  ck_assert(fabs(t2 - 5.5e-3) <= 0.05e-3);
  ck_assert(fabs(t1 - 5.4976e-8) <= 0.0001e-8);
  /* dt_lim ~ d^(5/2): "five orders of magnitude" between the two */
  ck_assert_rel(t2 / t1, 1e5, TOL_TIGHT);
  /* the definition: frac d / ((3/2) sqrt(pi k T / m)) */
  double m = sb_sphere_mass(1000.0, 1e-7);
  ck_assert_rel(t1, 0.13 * 1e-7 /
                (1.5 * sqrt(M_PI * SB_BOLTZMANN * 300.0 / m)), TOL_TIGHT);
  ck_assert_rel(sb_wunsch_dt(1e-7, SB_BOLTZMANN * 300.0 / m, 0.13), t1,
                TOL_TIGHT);
  /* domain errors */
  ck_assert(isnan(sb_kolmogorov_time(0, 1e-6)));
  ck_assert_int_eq(sb_last_status(), SB_EDOM);
  ck_assert(isnan(sb_kolmogorov_length(1e-4, -1)));
  ck_assert(isnan(sb_stokes_number(1, INFINITY)));
  ck_assert(isnan(sb_particle_reynolds(1e-5, -0.1, 1e-6)));
  ck_assert(isnan(sb_collision_speed(0)));
  ck_assert(isnan(sb_wunsch_dt(1e-7, 1.0, 0.0)));
  ck_assert(isnan(sb_wunsch_dt_brownian(1e-7, 1000.0, NAN, 0.13)));
}
END_TEST

/* ------------------------------------------------------- domain errors */

START_TEST(test_domain)
{
  sb_result r;
  sb_clear_error();
  ck_assert(isnan(sb_langevin_var_x(0, 1, 1)));
  ck_assert_int_eq(sb_last_status(), SB_EDOM);
  ck_assert_ptr_nonnull(strstr(sb_last_error(), "sb_langevin_var_x"));
  ck_assert(isnan(sb_langevin_var_u(1, -1, 1)));
  ck_assert(isnan(sb_langevin_cov_xu(1, 1, -1)));
  ck_assert(isnan(sb_langevin_msd(1, 1, NAN)));
  ck_assert(isnan(sb_langevin_var_x_cond(INFINITY, 1, 1)));
  ck_assert(isnan(sb_langevin_vacf(1, 1, INFINITY)));
  ck_assert(!isnan(sb_langevin_vacf(1, 1, -2)));
  ck_assert_int_eq(sb_langevin_var_x_e(1, 1, -1, &r), SB_EDOM);
  ck_assert(isnan(r.val) && isnan(r.err));
  ck_assert_int_eq(sb_langevin_msd_e(1, 1, 1, NULL), SB_EINVAL);

  sb_langevin p = {1, 1, 0}, bad = {-1, 1, 0};
  sb_langevin_mom m;
  ck_assert_int_eq(sb_langevin_moments(&bad, 1, 0, 0, &m), SB_EDOM);
  ck_assert(isnan(m.var_x) && isnan(m.mean_x));
  ck_assert_int_eq(sb_langevin_moments(&p, 1, NAN, 0, &m), SB_EDOM);
  ck_assert_int_eq(sb_langevin_moments(NULL, 1, 0, 0, &m), SB_EINVAL);
  ck_assert_int_eq(sb_langevin_moments(&p, 1, 0, 0, NULL), SB_EINVAL);

  gsl_rng *g = gsl_rng_alloc(gsl_rng_mt19937);
  double x = 1, u = 2;
  ck_assert_int_eq(sb_langevin_step(&p, -1, g, &x, &u), SB_EDOM);
  ck_assert_int_eq(sb_langevin_step(&bad, 1, g, &x, &u), SB_EDOM);
  ck_assert_int_eq(sb_langevin_step(&p, 1, NULL, &x, &u), SB_EINVAL);
  ck_assert(x == 1 && u == 2); /* unchanged on error */
  ck_assert_int_eq(sb_langevin_step(&p, 0, g, &x, &u), SB_SUCCESS);
  ck_assert(x == 1 && u == 2); /* dt = 0: identity */

  double tau[2] = {1, -1}, B[2] = {1, 1}, xs[6] = {0}, us[6] = {0};
  ck_assert_int_eq(sb_langevin_step3(2, 0.1, tau, B, NULL, xs, us, g),
                   SB_EDOM);
  for (int k = 0; k < 6; k++)
    ck_assert(xs[k] == 0 && us[k] == 0); /* nothing moved */
  ck_assert_int_eq(sb_langevin_step3(0, 0.1, NULL, NULL, NULL, NULL, NULL,
                                     NULL), SB_SUCCESS);

  sb_langevin_coef c;
  ck_assert_int_eq(sb_langevin_coef_init(&c, 1, 1, -1), SB_EDOM);
  ck_assert(isnan(c.s_u));
  ck_assert_int_eq(sb_langevin_coef_init(NULL, 1, 1, 1), SB_EINVAL);

  double a, b;
  sb_langevin zeroB = {1, 0, 0};
  ck_assert_int_eq(sb_langevin_bridge_sample(&zeroB, 1, 0.5, 0, 0, 0, 0, g,
                                             &a, &b), SB_EDOM);
  ck_assert(isnan(a) && isnan(b));
  ck_assert_int_eq(sb_langevin_bridge_sample(&p, 1, 1.5, 0, 0, 0, 0, g, &a,
                                             &b), SB_EDOM);
  ck_assert_int_eq(sb_langevin_bridge_sample(&p, 1, 1e-70, 0, 0, 0, 0, g,
                                             &a, &b), SB_EDOM);
  ck_assert_int_eq(sb_langevin_bridge_sample(&p, 0, 0, 0, 0, 0, 0, g, &a,
                                             &b), SB_EDOM);
  ck_assert_int_eq(sb_langevin_bridge_sample(&p, 1, 0.5, 0, 0, 0, 0, NULL,
                                             &a, &b), SB_EINVAL);
  ck_assert_int_eq(sb_langevin_bridge_moments(&p, 1, 0.5, 0, INFINITY, 0, 0,
                                              &m), SB_EDOM);
  ck_assert(isnan(m.var_u));
  gsl_rng_free(g);
}
END_TEST

/* Extreme ratios: dt/tau from 1e-10 to 1e10 give finite, positive step
 * coefficients and bridge variances (no NaN from 0/0 or negative sqrt). */
START_TEST(test_extremes_finite)
{
  for (double h = 1e-10; h <= 1e10; h *= 10) {
    sb_langevin_coef c;
    ck_assert_int_eq(sb_langevin_coef_init(&c, 1.0, 1.0, h), SB_SUCCESS);
    ck_assert(c.s_u > 0 && c.s_xu > 0 && c.s_xc > 0 && isfinite(c.s_xc));
    sb_langevin p = {1.0, 1.0, 0.0};
    sb_langevin_mom m;
    for (double f = 1e-6; f < 1; f *= 100) {
      ck_assert_int_eq(sb_langevin_bridge_moments(&p, h, f * h, 0, 0, 0, 0,
                                                  &m), SB_SUCCESS);
      ck_assert(m.var_x > 0 && m.var_u > 0 && isfinite(m.var_x));
      ck_assert(m.cov_xu * m.cov_xu < m.var_x * m.var_u);
    }
  }
}
END_TEST

/* ------------------------------------------------- extreme arguments */

/* One public function of langevin.h on an argument vector a: its status
 * (sb_last_status for the plain forms, after sb_clear_error), its
 * outputs in out[0..n-1] (n returned in *n) and the name that its error
 * messages must carry. */
typedef sbt_xfn xfn;

#define PLAIN(NAME, EXPR)                                                   \
  static int NAME(const double *a, double *out, int *n, const char **nm)   \
  {                                                                         \
    *nm = #EXPR;                                                            \
    sb_clear_error();                                                       \
    out[0] = EXPR(a[0], a[1], a[2]);                                        \
    *n = 1;                                                                 \
    return sb_last_status();                                                \
  }
#define WITH_E(NAME, EXPR)                                                  \
  static int NAME(const double *a, double *out, int *n, const char **nm)   \
  {                                                                         \
    sb_result r;                                                            \
    *nm = #EXPR;                                                            \
    int st = EXPR(a[0], a[1], a[2], &r);                                    \
    out[0] = r.val;                                                         \
    out[1] = r.err;                                                         \
    *n = 2;                                                                 \
    return st;                                                              \
  }
PLAIN(x_var_u, sb_langevin_var_u)
PLAIN(x_var_x, sb_langevin_var_x)
PLAIN(x_cov_xu, sb_langevin_cov_xu)
PLAIN(x_var_x_cond, sb_langevin_var_x_cond)
PLAIN(x_msd, sb_langevin_msd)
PLAIN(x_msd_bal, sb_langevin_msd_ballistic)
PLAIN(x_msd_dif, sb_langevin_msd_diffusive)
PLAIN(x_vacf, sb_langevin_vacf)
WITH_E(x_var_u_e, sb_langevin_var_u_e)
WITH_E(x_var_x_e, sb_langevin_var_x_e)
WITH_E(x_cov_xu_e, sb_langevin_cov_xu_e)
WITH_E(x_var_x_cond_e, sb_langevin_var_x_cond_e)
WITH_E(x_msd_e, sb_langevin_msd_e)

static int x_var_stat(const double *a, double *out, int *n, const char **nm)
{
  *nm = "sb_langevin_var_stat";
  sb_clear_error();
  out[0] = sb_langevin_var_stat(a[0], a[1]);
  *n = 1;
  return sb_last_status();
}

/* a = tau, B, us, t, x0, u0 */
static int x_moments(const double *a, double *out, int *n, const char **nm)
{
  sb_langevin p = {a[0], a[1], a[2]};
  sb_langevin_mom m;
  *nm = "sb_langevin_moments";
  int st = sb_langevin_moments(&p, a[3], a[4], a[5], &m);
  out[0] = m.var_x, out[1] = m.var_u, out[2] = m.cov_xu;
  out[3] = m.mean_x, out[4] = m.mean_u;
  *n = 5;
  return st;
}

/* a = tau, B, dt */
static int x_coef(const double *a, double *out, int *n, const char **nm)
{
  sb_langevin_coef c;
  *nm = "sb_langevin_coef_init";
  int st = sb_langevin_coef_init(&c, a[0], a[1], a[2]);
  out[0] = c.s_u, out[1] = c.s_xu, out[2] = c.s_xc, out[3] = c.gain;
  out[4] = c.decay;
  *n = 5;
  return st;
}

static gsl_rng *xrng; /* test_extreme_arguments's generator */

/* a = tau, B, us, dt, x, u: the new state (or the old one on error) */
static int x_step(const double *a, double *out, int *n, const char **nm)
{
  sb_langevin p = {a[0], a[1], a[2]};
  *nm = "sb_langevin_step";
  out[3] = a[4], out[4] = a[5];
  int st = sb_langevin_step(&p, a[3], xrng, &out[3], &out[4]);
  out[0] = out[1] = out[2] = 0.0; /* (variances: none) */
  *n = 5;
  if (st) /* unchanged */
    ck_assert(memcmp(&out[3], &a[4], sizeof(double)) == 0 &&
              memcmp(&out[4], &a[5], sizeof(double)) == 0);
  return st;
}

/* a = tau, B, us, dt, x, u: one particle of the batched step */
static int x_step3(const double *a, double *out, int *n, const char **nm)
{
  double x[3] = {a[4], a[4], a[4]}, u[3] = {a[5], a[5], a[5]};
  double us[3] = {a[2], a[2], a[2]};
  *nm = "sb_langevin_step3";
  int st = sb_langevin_step3(1, a[3], &a[0], &a[1], us, x, u, xrng);
  out[0] = out[1] = out[2] = 0.0;
  out[3] = x[1], out[4] = u[2];
  *n = 5;
  return st;
}

/* a = tau, B, us, dt, s/dt, x0, u0, x1, u1 */
static int x_bridge(const double *a, double *out, int *n, const char **nm)
{
  sb_langevin p = {a[0], a[1], a[2]};
  sb_langevin_mom m;
  *nm = "sb_langevin_bridge_moments";
  int st = sb_langevin_bridge_moments(&p, a[3], a[4] * a[3], a[5], a[6],
                                      a[7], a[8], &m);
  out[0] = m.var_x, out[1] = m.var_u, out[2] = 0.0;
  out[3] = m.mean_x, out[4] = m.mean_u;
  *n = 5;
  return st;
}

static int x_bridge_sample(const double *a, double *out, int *n,
                           const char **nm)
{
  sb_langevin p = {a[0], a[1], a[2]};
  *nm = "sb_langevin_bridge_sample";
  int st = sb_langevin_bridge_sample(&p, a[3], a[4] * a[3], a[5], a[6],
                                     a[7], a[8], xrng, &out[3], &out[4]);
  out[0] = out[1] = out[2] = 0.0;
  *n = 5;
  return st;
}

#define SI(NAME, EXPR, NARG, ...)                                           \
  static int NAME(const double *a, double *out, int *n, const char **nm)   \
  {                                                                         \
    *nm = #EXPR;                                                            \
    sb_clear_error();                                                       \
    out[0] = EXPR(__VA_ARGS__);                                             \
    *n = 1;                                                                 \
    return sb_last_status();                                                \
  }
SI(x_stokes_tau, sb_stokes_tau, 4, a[0], a[1], a[2], a[3])
SI(x_sphere_mass, sb_sphere_mass, 2, a[0], a[1])
SI(x_brownian_B, sb_brownian_B, 3, a[0], a[1], a[2])
SI(x_einstein_D, sb_einstein_D, 4, a[0], a[1], a[2], a[3])
SI(x_knudsen, sb_knudsen, 2, a[0], a[1])
SI(x_cunningham, sb_cunningham, 1, a[0])
SI(x_cunningham_gen, sb_cunningham_gen, 4, a[0], a[1], a[2], a[3])
SI(x_kolmogorov_time, sb_kolmogorov_time, 2, a[0], a[1])
SI(x_kolmogorov_length, sb_kolmogorov_length, 2, a[0], a[1])
SI(x_stokes_number, sb_stokes_number, 2, a[0], a[1])
SI(x_particle_reynolds, sb_particle_reynolds, 3, a[0], a[1], a[2])
SI(x_collision_speed, sb_collision_speed, 1, a[0])
SI(x_wunsch_dt, sb_wunsch_dt, 3, a[0], a[1], a[2])
SI(x_wunsch_dt_brownian, sb_wunsch_dt_brownian, 4, a[0], a[1], a[2], a[3])

/* Each argument of each public function of langevin.h in turn over
 * +-1e-320, +-1e-300, 0, +-1e300, +-DBL_MAX, +-inf, NaN (the others
 * ordinary): the outputs are finite (variances and the SI quantities
 * >= 0; a mean between the extremes of its inputs' scales is not
 * checked) with status 0, or the status is an error, the plain value
 * NaN and the message names the public function.  Then the corners of
 * tests/data/langevin_extreme.csv (gen_langevin_ref.py, mpmath) where
 * t/tau, B^2 or tau^3 leave the double range: the value wherever it is a
 * normal double (these gave NaN, inf or 0 before), 0 or a subnormal
 * where it underflows. */
START_TEST(test_extreme_arguments)
{
  static const struct {
    xfn f;
    int n;       /* arguments */
    int nonneg;  /* outputs 0..nonneg-1 are >= 0 */
    double a[9];
  } k[] = {
      {x_var_u, 3, 1, {0.7, 1.3, 0.4}},
      {x_var_x, 3, 1, {0.7, 1.3, 0.4}},
      {x_cov_xu, 3, 1, {0.7, 1.3, 0.4}},
      {x_var_x_cond, 3, 1, {0.7, 1.3, 0.4}},
      {x_msd, 3, 1, {0.7, 1.3, 0.4}},
      {x_msd_bal, 3, 1, {0.7, 1.3, 0.4}},
      {x_msd_dif, 3, 1, {0.7, 1.3, 0.4}},
      {x_vacf, 3, 1, {0.7, 1.3, -0.4}},
      {x_var_u_e, 3, 2, {0.7, 1.3, 0.4}},
      {x_var_x_e, 3, 2, {0.7, 1.3, 0.4}},
      {x_cov_xu_e, 3, 2, {0.7, 1.3, 0.4}},
      {x_var_x_cond_e, 3, 2, {0.7, 1.3, 0.4}},
      {x_msd_e, 3, 2, {0.7, 1.3, 0.4}},
      {x_var_stat, 2, 1, {0.7, 1.3}},
      {x_moments, 6, 3, {0.7, 1.3, 0.2, 0.4, 1.5, -0.8}},
      {x_coef, 3, 5, {0.7, 1.3, 0.4}},
      {x_step, 6, 3, {0.7, 1.3, 0.2, 0.4, 1.5, -0.8}},
      {x_step3, 6, 3, {0.7, 1.3, 0.2, 0.4, 1.5, -0.8}},
      {x_bridge, 9, 2, {0.7, 1.3, 0.2, 0.4, 0.3, 1.5, -0.8, 1.6, 0.1}},
      {x_bridge_sample, 9, 3, {0.7, 1.3, 0.2, 0.4, 0.3, 1.5, -0.8, 1.6,
                               0.1}},
      {x_stokes_tau, 4, 1, {1000, 1e-6, 1.8e-5, 1.1}},
      {x_sphere_mass, 2, 1, {1000, 1e-6}},
      {x_brownian_B, 3, 1, {300, 1e-15, 1e-6}},
      {x_einstein_D, 4, 1, {300, 1.8e-5, 1e-6, 1.1}},
      {x_knudsen, 2, 1, {6.6e-8, 1e-6}},
      {x_cunningham, 1, 1, {0.13}},
      /* (A1, A2 may be any finite reals: Cc is the formula's value) */
      {x_cunningham_gen, 4, 0, {0.13, 1.2, 0.4, 1.1}},
      {x_kolmogorov_time, 2, 1, {0.01, 1.5e-5}},
      {x_kolmogorov_length, 2, 1, {0.01, 1.5e-5}},
      {x_stokes_number, 2, 1, {1e-3, 0.03}},
      {x_particle_reynolds, 3, 1, {1e-6, 0.01, 1.5e-5}},
      {x_collision_speed, 1, 1, {1e-4}},
      {x_wunsch_dt, 3, 1, {1e-6, 1e-4, 0.13}},
      {x_wunsch_dt_brownian, 4, 1, {1e-6, 1000, 300, 0.13}},
  };
  int nbad = 0; /* every failure is printed, then counted */
  xrng = gsl_rng_alloc(gsl_rng_mt19937);
  gsl_rng_set(xrng, 20261129);
  const int na = (int)(sizeof k[0].a / sizeof k[0].a[0]);
  for (size_t f = 0; f < sizeof k / sizeof k[0]; f++)
    nbad += sbt_sweep_vec(k[f].f, k[f].a, na, k[f].n,
                          SBT_SWEEP_FIRST(k[f].nonneg), 0, SBT_SWEEP_NAN, f);
  gsl_rng_free(xrng);
  /* The bridge mean does not depend on B (the gain is unit-free): at
   * B = 1e-320 and 1e300 (the scales B sqrt(tau), B tau^1.5 outside the
   * normal range: the mean formed without them) it is the one at B = 1,
   * and the variances scale as B^2 (here to 1e-20 and 1e300 times). */
  {
    sb_langevin_mom m1, me;
    for (int k = 0; k < 3; k++) {
      const double Bk[3] = {1e-320, 1e-10, 1e150};
      sb_langevin p1 = {0.7, 1.0, 0.2}, pe = {0.7, Bk[k], 0.2};
      ck_assert_int_eq(sb_langevin_bridge_moments(&p1, 0.4, 0.12, 1.5, -0.8,
                                                  1.6, 0.1, &m1),
                       SB_SUCCESS);
      ck_assert_int_eq(sb_langevin_bridge_moments(&pe, 0.4, 0.12, 1.5, -0.8,
                                                  1.6, 0.1, &me),
                       SB_SUCCESS);
      ck_assert_rel(me.mean_x, m1.mean_x, 1e-14);
      ck_assert_rel(me.mean_u, m1.mean_u, 1e-13);
      if (k > 0) {
        const double B2 = Bk[k] * Bk[k];
        ck_assert_rel(me.var_x, B2 * m1.var_x, 1e-14);
        ck_assert_rel(me.var_u, B2 * m1.var_u, 1e-14);
        ck_assert_rel(me.cov_xu, B2 * m1.cov_xu, 1e-14);
      }
    }
  }
  /* SI helpers whose intermediates over/underflow (nu/eps = 1e310,
   * m_p tau_p = 1e-330, mu_f = 1e-320): the value (mpmath, 40 digits) */
  ck_assert_rel(sb_kolmogorov_time(1e-320, 1e-10), 1.0000055664551363047e155,
                TOL_TIGHT);
  ck_assert_rel(sb_brownian_B(300, 1e-320, 1e-10), 9.1016406345808276821e154,
                TOL_TIGHT);
  ck_assert_rel(sb_stokes_tau(1e-300, 1e-8, 1e-320, 1.0),
                555.56174052292114595, TOL_TIGHT);
  ck_assert_int_eq(nbad, 0);

  sbt_table t;
  sbt_table_load("langevin_extreme.csv", &t);
  ck_assert_int_ge(t.nrow, 10);
  int (*fe[5])(double, double, double, sb_result *) = {
      sb_langevin_var_x_e, sb_langevin_var_u_e, sb_langevin_cov_xu_e,
      sb_langevin_var_x_cond_e, sb_langevin_msd_e};
  double (*fp[6])(double, double, double) = {
      sb_langevin_var_x, sb_langevin_var_u, sb_langevin_cov_xu,
      sb_langevin_var_x_cond, sb_langevin_msd, sb_langevin_vacf};
  const char *nm[6] = {"var_x", "var_u", "cov_xu", "var_x_cond", "msd",
                       "vacf"};
  for (int i = 0; i < t.nrow; i++) {
    const double tau = sbt_get(&t, i, "tau"), B = sbt_get(&t, i, "B");
    const double tt = sbt_get(&t, i, "t");
    for (int j = 0; j < 6; j++) {
      const double want = sbt_get(&t, i, nm[j]);
      char call[96];
      snprintf(call, sizeof call, "%s(tau=%g, B=%g, t=%g)", nm[j], tau, B,
               tt);
      if (j < 5)
        check_e(fe[j], nm[j], tau, B, tt, want, TOL_MOM);
      ck_assert_msg(sbt_reldiff(fp[j](tau, B, tt), want) <= TOL_MOM,
                    "%s: %.17g, want %.17g", call, fp[j](tau, B, tt), want);
    }
    sb_langevin p = {tau, B, 0.37};
    sb_langevin_mom m;
    ck_assert_int_eq(sb_langevin_moments(&p, tt, 1.5, -0.8, &m), SB_SUCCESS);
    /* means: to a few ulps of their largest term (1.5 or us t) */
    const double mscale = fmax(1.5, 0.37 * tt);
    ck_assert_abs(m.mean_x, sbt_get(&t, i, "mean_x"), 4e-16 * mscale);
    ck_assert_abs(m.mean_u, sbt_get(&t, i, "mean_u"), 4e-16);
    ck_assert_rel(m.var_x, sbt_get(&t, i, "var_x"), TOL_MOM);
    ck_assert_rel(m.var_u, sbt_get(&t, i, "var_u"), TOL_MOM);
    ck_assert_rel(m.cov_xu, sbt_get(&t, i, "cov_xu"), TOL_MOM);
    sb_langevin_coef c;
    ck_assert_int_eq(sb_langevin_coef_init(&c, tau, B, tt), SB_SUCCESS);
    const double g = sbt_get(&t, i, "gain");
    if (g >= DBL_MIN)
      ck_assert_rel(c.gain, g, TOL_MOM);
    else /* subnormal: to its last place */
      ck_assert_abs(c.gain, g, 0x1p-1074);
    ck_assert_rel(c.s_u, sbt_get(&t, i, "s_u"), TOL_MOM);
    ck_assert_rel(c.s_xu, sbt_get(&t, i, "s_xu"), TOL_MOM);
    ck_assert_rel(c.s_xc, sbt_get(&t, i, "s_xc"), TOL_MOM);
  }
  sbt_table_free(&t);
}
END_TEST

enum { S3N = 5 }; /* particles in test_step3_order */

/* Restart a run: states from (x0, u0), generator seeded with seed. */
static void restart(double *x, double *u, const double *x0,
                    const double *u0, gsl_rng *r, unsigned long seed)
{
  memcpy(x, x0, 3 * S3N * sizeof *x);
  memcpy(u, u0, 3 * S3N * sizeof *u);
  gsl_rng_set(r, seed);
}

/* Bit-exact agreement of two runs. */
static void assert_same_states(const double *x, const double *u,
                               const double *xr, const double *ur)
{
  for (int i = 0; i < 3 * S3N; i++)
    ck_assert(x[i] == xr[i] && u[i] == ur[i]);
}

/* The batched steppers reproduce the scalar step bit-exactly, in the
 * documented draw order (particle, component, z1 then z2), and the
 * coefficient-table form (with and without a class index) matches the
 * per-particle form. */
START_TEST(test_step3_order)
{
  enum { N = S3N };
  const double tau[N] = {1e-3, 2.0, 0.5, 2.0, 1e-3};
  const double B[N] = {3.0, 0.1, 1.0, 0.1, 3.0};
  const size_t cls[N] = {0, 1, 2, 1, 0};
  double us[3 * N], x0[3 * N], u0[3 * N];
  for (int i = 0; i < 3 * N; i++) {
    us[i] = 0.1 * i - 0.5;
    x0[i] = 0.01 * i * i;
    u0[i] = 1.0 - 0.2 * i;
  }
  const double dt = 0.02;
  gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
  /* reference: scalar steps in the documented order */
  double xr[3 * N], ur[3 * N];
  restart(xr, ur, x0, u0, r, 99);
  for (int i = 0; i < N; i++)
    for (int k = 0; k < 3; k++) {
      sb_langevin p = {tau[i], B[i], us[3 * i + k]};
      ck_assert_int_eq(sb_langevin_step(&p, dt, r, &xr[3 * i + k],
                                        &ur[3 * i + k]), SB_SUCCESS);
    }
  /* per-particle arrays */
  double x[3 * N], u[3 * N];
  restart(x, u, x0, u0, r, 99);
  ck_assert_int_eq(sb_langevin_step3(N, dt, tau, B, us, x, u, r), SB_SUCCESS);
  assert_same_states(x, u, xr, ur);
  /* coefficient table, one entry per particle */
  sb_langevin_coef c[N], ct[3];
  for (int i = 0; i < N; i++)
    ck_assert_int_eq(sb_langevin_coef_init(&c[i], tau[i], B[i], dt),
                     SB_SUCCESS);
  restart(x, u, x0, u0, r, 99);
  ck_assert_int_eq(sb_langevin_step3_coef(N, c, NULL, us, x, u, r),
                   SB_SUCCESS);
  assert_same_states(x, u, xr, ur);
  /* class table indexed by cidx */
  sb_langevin_coef_init(&ct[0], 1e-3, 3.0, dt);
  sb_langevin_coef_init(&ct[1], 2.0, 0.1, dt);
  sb_langevin_coef_init(&ct[2], 0.5, 1.0, dt);
  restart(x, u, x0, u0, r, 99);
  ck_assert_int_eq(sb_langevin_step3_coef(N, ct, cls, us, x, u, r),
                   SB_SUCCESS);
  assert_same_states(x, u, xr, ur);
  /* us = NULL means a fluid at rest */
  double zero[3 * N] = {0};
  restart(xr, ur, x0, u0, r, 5);
  sb_langevin_step3(N, dt, tau, B, zero, xr, ur, r);
  restart(x, u, x0, u0, r, 5);
  sb_langevin_step3_coef(N, c, NULL, NULL, x, u, r);
  assert_same_states(x, u, xr, ur);
  /* B = 0: the deterministic relaxation, exactly the mean */
  sb_langevin p0 = {0.5, 0.0, 0.3};
  double xx = 1.0, uu = -2.0;
  sb_langevin_mom m;
  sb_langevin_moments(&p0, 0.7, xx, uu, &m);
  sb_langevin_step(&p0, 0.7, r, &xx, &uu);
  ck_assert_rel(xx, m.mean_x, TOL_TIGHT);
  ck_assert_rel(uu, m.mean_u, TOL_TIGHT);
  gsl_rng_free(r);
}
END_TEST

static Suite *langevin_suite(void)
{
  Suite *s = suite_create("langevin");
  TCase *tc = tcase_create("reference");
  tcase_add_test(tc, test_var_vectors);
  tcase_add_test(tc, test_var_decade_points);
  tcase_add_test(tc, test_moments_vectors);
  tcase_add_test(tc, test_bridge_vectors);
  suite_add_tcase(s, tc);
  tc = tcase_create("limits");
  tcase_add_test(tc, test_small_time_series);
  tcase_add_test(tc, test_large_time_limits);
  tcase_add_test(tc, test_quadrature);
  tcase_add_test(tc, test_bridge_limits);
  tcase_add_test(tc, test_bridge_total_variance);
  suite_add_tcase(s, tc);
  tc = tcase_create("api");
  tcase_add_test(tc, test_si_helpers);
  tcase_add_test(tc, test_dimensionless);
  tcase_add_test(tc, test_domain);
  tcase_add_test(tc, test_extremes_finite);
  tcase_add_test(tc, test_step3_order);
  tcase_add_test(tc, test_extreme_arguments);
  suite_add_tcase(s, tc);
  return s;
}

int main(void) { return sbt_run_suite(langevin_suite()); }
