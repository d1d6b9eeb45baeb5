/* test_langevin_mc.c — Monte Carlo checks of the langevin samplers against
 * the closed forms (which test_langevin.c checks against 150-digit
 * references):
 *   - exact step: KS on the X and U marginals, mean / variance / correlation
 *     inside stated intervals, for dt/tau from 1e-8 to 1e6;
 *   - one step of dt equals in law 64 steps of dt/64 (two-sample KS);
 *   - bridge sampler: against its closed-form law; against brute force
 *     (forward paths with fine exact steps, kept when they end in a small
 *     window around the conditioning state: two-sample KS); and the
 *     residual Z_s - E[Z_s | z0, Z_dt] of unconditioned forward paths,
 *     which must follow the conditional covariance whatever Z_dt is.
 *
 * Every test uses a fixed MT19937 seed and is deterministic.  Criteria:
 * KS p-values >= ALPHA = 1e-4; means within 4 standard errors (two-sided
 * p = 6.3e-5); variances inside the exact chi-square interval at 1 - 1e-4;
 * correlations inside the Fisher-z interval at 4 standard errors.  With
 * ~100 such comparisons the chance that a correct implementation fails one
 * for a new seed is ~1%; for the committed seeds they pass.  Each test
 * states its sample size.  Sensitivity (the break-the-code experiments are
 * listed in docs/langevin.md): a 5% error in one standard deviation, or a
 * correlation dropped, fails. */
#include <float.h>
#include <string.h>

#include <gsl/gsl_cdf.h>
#include <gsl/gsl_math.h>
#include <gsl/gsl_rng.h>
#include <smolbridge/langevin.h>
#include <smolbridge/simulate.h>
#include <smolbridge/stats.h>

#include "testutil.h"

#define ALPHA 1e-4
#define ZMAX 4.0 /* standard errors for means and Fisher z */

/* ------------------------------------------------------------ helpers */

typedef struct {
  double mean, sd;
} gpar;

static double gauss_cdf(double x, void *vp)
{
  const gpar *g = vp;
  return gsl_cdf_gaussian_P(x - g->mean, g->sd);
}

/* KS of x[0..n-1] (sorted in place) against N(mean, sd^2) */
static void ks_gauss(const char *what, double *x, size_t n, double mean,
                     double sd)
{
  gpar g = {mean, sd};
  double d, p;
  ck_assert_int_eq(sb_ks_test(x, n, gauss_cdf, &g, &d, &p), SB_SUCCESS);
  ck_assert_msg(p >= ALPHA, "%s: KS D = %.4g, p = %.3g < %g (n = %zu)", what,
                d, p, ALPHA, n);
}

static void ks2(const char *what, double *x, size_t nx, double *y, size_t ny)
{
  double d, p;
  ck_assert_int_eq(sb_ks2_test(x, nx, y, ny, &d, &p), SB_SUCCESS);
  ck_assert_msg(p >= ALPHA, "%s: two-sample KS D = %.4g, p = %.3g < %g "
                "(n = %zu, %zu)", what, d, p, ALPHA, nx, ny);
}

/* Sample moments of paired data: means, variances (n-1), correlation. */
typedef struct {
  double mx, my, vx, vy, r;
} smom;

static smom sample_moments(const double *x, const double *y, size_t n)
{
  smom s = {0, 0, 0, 0, 0};
  for (size_t i = 0; i < n; i++) {
    s.mx += x[i];
    s.my += y[i];
  }
  s.mx /= (double)n;
  s.my /= (double)n;
  double cxy = 0;
  for (size_t i = 0; i < n; i++) {
    double dx = x[i] - s.mx, dy = y[i] - s.my;
    s.vx += dx * dx;
    s.vy += dy * dy;
    cxy += dx * dy;
  }
  s.r = cxy / sqrt(s.vx * s.vy);
  s.vx /= (double)(n - 1);
  s.vy /= (double)(n - 1);
  return s;
}

/* true variance inside the exact chi-square interval of the sample
 * variance (Gaussian data): (n-1) s^2 / chi2_{1-a/2} <= var <= ... */
static void check_var(const char *what, double sv, double var, size_t n)
{
  double nu = (double)(n - 1);
  double lo = nu * sv / gsl_cdf_chisq_Qinv(ALPHA / 2, nu);
  double hi = nu * sv / gsl_cdf_chisq_Pinv(ALPHA / 2, nu);
  ck_assert_msg(var >= lo && var <= hi,
                "%s: variance %.6g outside [%.6g, %.6g] (sample %.6g, n = "
                "%zu)", what, var, lo, hi, sv, n);
}

static void check_mean(const char *what, double sm, double mean, double var,
                       size_t n)
{
  double se = sqrt(var / (double)n);
  ck_assert_msg(fabs(sm - mean) <= ZMAX * se,
                "%s: sample mean %.10g, want %.10g +- %g (%.2f se)", what, sm,
                mean, ZMAX * se, (sm - mean) / se);
}

static void check_corr(const char *what, double r, double rho, size_t n)
{
  double z = (atanh(r) - atanh(rho)) * sqrt((double)n - 3);
  ck_assert_msg(fabs(z) <= ZMAX, "%s: correlation %.5f, want %.5f (%.2f se)",
                what, r, rho, z);
}

/* Check n draws (x, u) against a Gaussian law with moments m. */
static void check_law(const char *what, double *x, double *u, size_t n,
                      const sb_langevin_mom *m)
{
  char buf[160];
  smom s = sample_moments(x, u, n);
  snprintf(buf, sizeof buf, "%s X", what);
  check_mean(buf, s.mx, m->mean_x, m->var_x, n);
  check_var(buf, s.vx, m->var_x, n);
  snprintf(buf, sizeof buf, "%s U", what);
  check_mean(buf, s.my, m->mean_u, m->var_u, n);
  check_var(buf, s.vy, m->var_u, n);
  snprintf(buf, sizeof buf, "%s corr", what);
  check_corr(buf, s.r, m->cov_xu / sqrt(m->var_x * m->var_u), n);
  /* KS last: it sorts the arrays */
  snprintf(buf, sizeof buf, "%s X", what);
  ks_gauss(buf, x, n, m->mean_x, sqrt(m->var_x));
  snprintf(buf, sizeof buf, "%s U", what);
  ks_gauss(buf, u, n, m->mean_u, sqrt(m->var_u));
}

/* ------------------------------------------------------- exact step */

/* N = 20000 one-step draws from a fixed start, for each dt/tau. */
START_TEST(test_step_marginals)
{
  const double hs[] = {1e-8, 1e-4, 0.05, 1.0, 30.0, 1e6};
  const size_t N = 20000;
  double *x = malloc(N * sizeof *x), *u = malloc(N * sizeof *u);
  gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
  sb_langevin p = {2.0, 0.7, 0.5};
  for (size_t k = 0; k < sizeof hs / sizeof hs[0]; k++) {
    gsl_rng_set(r, 1000 + k);
    double dt = hs[k] * p.tau, x0 = 0.3, u0 = -1.2;
    for (size_t i = 0; i < N; i++) {
      x[i] = x0;
      u[i] = u0;
      ck_assert_int_eq(sb_langevin_step(&p, dt, r, &x[i], &u[i]), SB_SUCCESS);
    }
    sb_langevin_mom m;
    ck_assert_int_eq(sb_langevin_moments(&p, dt, x0, u0, &m), SB_SUCCESS);
    char what[64];
    snprintf(what, sizeof what, "step dt/tau=%g", hs[k]);
    check_law(what, x, u, N, &m);
  }
  gsl_rng_free(r);
  free(x);
  free(u);
}
END_TEST

/* The batched 3-D step: N = 10000 particles of two classes (different tau,
 * B, fluid velocity), each component checked against its own law. */
START_TEST(test_step3_marginals)
{
  const size_t N = 10000;
  double *tau = malloc(N * sizeof *tau), *B = malloc(N * sizeof *B);
  double *us = malloc(3 * N * sizeof *us), *x = malloc(3 * N * sizeof *x);
  double *u = malloc(3 * N * sizeof *u);
  double *cx = malloc(N * sizeof *cx), *cu = malloc(N * sizeof *cu);
  const double cls_tau[2] = {1e-3, 5.0}, cls_B[2] = {3.0, 0.2};
  const double cls_us[2][3] = {{0.1, -0.2, 0.0}, {1.0, 0.0, -1.0}};
  const double dt = 0.01, x0 = -0.4, u0 = 0.25;
  for (size_t i = 0; i < N; i++) {
    int c = (int)(i & 1);
    tau[i] = cls_tau[c];
    B[i] = cls_B[c];
    for (int k = 0; k < 3; k++) {
      us[3 * i + k] = cls_us[c][k];
      x[3 * i + k] = x0;
      u[3 * i + k] = u0;
    }
  }
  gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
  gsl_rng_set(r, 2024);
  ck_assert_int_eq(sb_langevin_step3(N, dt, tau, B, us, x, u, r), SB_SUCCESS);
  for (int c = 0; c < 2; c++)
    for (int k = 0; k < 3; k++) {
      size_t n = 0;
      for (size_t i = (size_t)c; i < N; i += 2, n++) {
        cx[n] = x[3 * i + k];
        cu[n] = u[3 * i + k];
      }
      sb_langevin p = {cls_tau[c], cls_B[c], cls_us[c][k]};
      sb_langevin_mom m;
      sb_langevin_moments(&p, dt, x0, u0, &m);
      char what[64];
      snprintf(what, sizeof what, "step3 class %d comp %d", c, k);
      check_law(what, cx, cu, n, &m);
    }
  gsl_rng_free(r);
  free(tau); free(B); free(us); free(x); free(u); free(cx); free(cu);
}
END_TEST

/* The counter-based stepper (sb_langevin_step3_stream): N = 20000
 * particles in two classes (coefficient table, cidx) from a fixed start,
 * one step keyed (seed 2024, step 7, ids 0..N-1): marginals of every
 * class and component against sb_langevin_moments (check_law); then 64
 * steps of dt/64 (step keys 0..63) against the law of one step of dt, so
 * that normals reused across steps or ids would show. */
START_TEST(test_step3_stream_law)
{
  const size_t N = 20000;
  double *us = malloc(3 * N * sizeof *us), *x = malloc(3 * N * sizeof *x);
  double *u = malloc(3 * N * sizeof *u);
  double *cx = malloc(N * sizeof *cx), *cu = malloc(N * sizeof *cu);
  size_t *cidx = malloc(N * sizeof *cidx);
  const double cls_tau[2] = {1e-3, 5.0}, cls_B[2] = {3.0, 0.2};
  const double cls_us[2][3] = {{0.1, -0.2, 0.0}, {1.0, 0.0, -1.0}};
  const double dt = 0.01, x0 = -0.4, u0 = 0.25;
  for (int pass = 0; pass < 2; pass++) {
    const size_t nsub = pass ? 64 : 1;
    sb_langevin_coef coef[2];
    for (int c = 0; c < 2; c++)
      sb_langevin_coef_init(&coef[c], cls_tau[c], cls_B[c],
                            dt / (double)nsub);
    for (size_t i = 0; i < N; i++) {
      cidx[i] = i & 1;
      for (int k = 0; k < 3; k++) {
        us[3 * i + k] = cls_us[i & 1][k];
        x[3 * i + k] = x0;
        u[3 * i + k] = u0;
      }
    }
    for (size_t j = 0; j < nsub; j++)
      ck_assert_int_eq(sb_langevin_step3_stream(N, coef, cidx, us, x, u,
                                                2024, pass ? j : 7, NULL,
                                                0), SB_SUCCESS);
    for (int c = 0; c < 2; c++)
      for (int k = 0; k < 3; k++) {
        size_t n = 0;
        for (size_t i = (size_t)c; i < N; i += 2, n++) {
          cx[n] = x[3 * i + k];
          cu[n] = u[3 * i + k];
        }
        sb_langevin p = {cls_tau[c], cls_B[c], cls_us[c][k]};
        sb_langevin_mom m;
        sb_langevin_moments(&p, dt, x0, u0, &m);
        char what[80];
        snprintf(what, sizeof what, "step3_stream %zu step(s) class %d "
                 "comp %d", nsub, c, k);
        check_law(what, cx, cu, n, &m);
      }
  }
  free(us); free(x); free(u); free(cx); free(cu); free(cidx);
}
END_TEST

/* The state of a particle depends on (seed, id, step) and its own state
 * only: the whole batch, the batch in reverse in pieces of 7 with
 * explicit ids, and sb_stream_init + sb_langevin_step3_draw one by one
 * give bit-identical states; a bad id moves nothing. */
START_TEST(test_step3_stream_keys)
{
  enum { N = 300 };
  static double xa[3 * N], ua[3 * N], xb[3 * N], ub[3 * N], xc[3 * N],
      uc[3 * N];
  sb_langevin_coef c;
  sb_langevin_coef_init(&c, 0.5, 1.5, 0.2);
  size_t cidx[N];
  uint64_t ids[N];
  for (size_t i = 0; i < N; i++) {
    cidx[i] = 0;
    ids[i] = 1000 + i;
    for (int k = 0; k < 3; k++)
      xa[3 * i + k] = xb[3 * i + k] = xc[3 * i + k] = ua[3 * i + k] =
          ub[3 * i + k] = uc[3 * i + k] = 0.1 * (double)k;
  }
  ck_assert_int_eq(sb_langevin_step3_stream(N, &c, cidx, NULL, xa, ua, 9,
                                            3, NULL, 1000), SB_SUCCESS);
  for (size_t end = N; end > 0;) {
    size_t beg = end >= 7 ? end - 7 : 0;
    ck_assert_int_eq(sb_langevin_step3_stream(end - beg, &c, cidx + beg,
                                              NULL, xb + 3 * beg,
                                              ub + 3 * beg, 9, 3, ids + beg,
                                              0), SB_SUCCESS);
    end = beg;
  }
  for (size_t i = 0; i < N; i++) {
    sb_stream s;
    sb_stream_init(&s, 9, 1000 + i, 3);
    ck_assert_int_eq(sb_langevin_step3_draw(&c, NULL, xc + 3 * i,
                                            uc + 3 * i, &s), SB_SUCCESS);
  }
  ck_assert(memcmp(xa, xb, sizeof xa) == 0 && memcmp(ua, ub, sizeof ua) == 0);
  ck_assert(memcmp(xa, xc, sizeof xa) == 0 && memcmp(ua, uc, sizeof ua) == 0);
  ids[N - 1] = SB_STREAM_MAX_ID + 1;
  ck_assert_int_eq(sb_langevin_step3_stream(N, &c, cidx, NULL, xb, ub, 9, 4,
                                            ids, 0), SB_EDOM);
  ck_assert(memcmp(xa, xb, sizeof xa) == 0);
  ck_assert_int_eq(sb_langevin_step3_stream(N, &c, cidx, NULL, xb, ub, 9,
                                            SB_STREAM_MAX_STEP + 1, NULL, 0),
                   SB_EDOM);
  ck_assert_int_eq(sb_langevin_step3_stream(1, NULL, NULL, NULL, xb, ub, 9,
                                            0, NULL, 0), SB_EINVAL);
  ck_assert_int_eq(sb_langevin_step3_draw(&c, NULL, xb, ub, NULL),
                   SB_EINVAL);
}
END_TEST

/* One step of dt against 64 steps of dt/64 (N = 20000 paths each), and
 * the 64-step sample against the closed-form law, for dt/tau = 0.05, 1,
 * 20.  A wrong variance term that happens to compose (or not) shows up. */
START_TEST(test_step_composition)
{
  const double hs[] = {0.05, 1.0, 20.0};
  const size_t N = 20000, NSUB = 64;
  double *x1 = malloc(N * sizeof *x1), *u1 = malloc(N * sizeof *u1);
  double *xn = malloc(N * sizeof *xn), *un = malloc(N * sizeof *un);
  gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
  sb_langevin p = {0.5, 1.5, -0.3};
  for (size_t k = 0; k < sizeof hs / sizeof hs[0]; k++) {
    double dt = hs[k] * p.tau, x0 = 1.0, u0 = 2.0;
    gsl_rng_set(r, 3000 + k);
    for (size_t i = 0; i < N; i++) {
      x1[i] = x0;
      u1[i] = u0;
      sb_langevin_step(&p, dt, r, &x1[i], &u1[i]);
      xn[i] = x0;
      un[i] = u0;
      for (size_t j = 0; j < NSUB; j++)
        sb_langevin_step(&p, dt / NSUB, r, &xn[i], &un[i]);
    }
    sb_langevin_mom m;
    sb_langevin_moments(&p, dt, x0, u0, &m);
    char what[64];
    snprintf(what, sizeof what, "64 steps dt/tau=%g", hs[k]);
    check_law(what, xn, un, N, &m); /* sorts xn, un */
    snprintf(what, sizeof what, "1 vs 64 steps X dt/tau=%g", hs[k]);
    ks2(what, x1, N, xn, N);
    snprintf(what, sizeof what, "1 vs 64 steps U dt/tau=%g", hs[k]);
    ks2(what, u1, N, un, N);
  }
  gsl_rng_free(r);
  free(x1); free(u1); free(xn); free(un);
}
END_TEST

/* --------------------------------------------------------------- bridge */

/* The sampler against its closed-form law: N = 20000 draws at fixed end
 * states ~1 sd from the unconditioned mean, for dt/tau = 1e-4, 1, 1e3 and
 * s/dt = 0.1, 0.5, 0.9. */
START_TEST(test_bridge_sampler_law)
{
  const double hs[] = {1e-4, 1.0, 1e3}, fr[] = {0.1, 0.5, 0.9};
  const size_t N = 20000;
  double *x = malloc(N * sizeof *x), *u = malloc(N * sizeof *u);
  gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
  sb_langevin p = {1.5, 0.8, 0.3};
  unsigned long seed = 4000;
  for (size_t k = 0; k < 3; k++)
    for (size_t j = 0; j < 3; j++) {
      double dt = hs[k] * p.tau, s = fr[j] * dt, x0 = -2.0, u0 = 0.6;
      sb_langevin_mom mt, m;
      sb_langevin_moments(&p, dt, x0, u0, &mt);
      double x1 = mt.mean_x + 0.9 * sqrt(mt.var_x);
      double u1 = mt.mean_u - 1.2 * sqrt(mt.var_u);
      ck_assert_int_eq(sb_langevin_bridge_moments(&p, dt, s, x0, u0, x1, u1,
                                                  &m), SB_SUCCESS);
      gsl_rng_set(r, seed++);
      for (size_t i = 0; i < N; i++)
        ck_assert_int_eq(sb_langevin_bridge_sample(&p, dt, s, x0, u0, x1, u1,
                                                   r, &x[i], &u[i]),
                         SB_SUCCESS);
      char what[64];
      snprintf(what, sizeof what, "bridge dt/tau=%g s/dt=%g", hs[k], fr[j]);
      check_law(what, x, u, N, &m);
    }
  gsl_rng_free(r);
  free(x);
  free(u);
}
END_TEST

/* Brute force.  tau = 1, B = 1, us = 0.2, dt = 1, s = 0.4, z0 = (0, 0.5).
 * M = 1.2e6 forward paths with 8 + 12 exact sub-steps; a path is kept when
 * its end state lies within +-0.05 standard deviations (each coordinate)
 * of z1 = mean + 0.7 sd in both coordinates (z1 off the mean, so the gain
 * of the conditioning matters; acceptance ~2e-3, ~2300 kept).  The window
 * widens the end law by (0.05)^2/3 of its variance: negligible for KS at
 * that size.  Kept X_s, U_s vs N = 20000 sampler draws: two-sample KS, and
 * kept draws vs the closed-form law. */
START_TEST(test_bridge_bruteforce)
{
  sb_langevin p = {1.0, 1.0, 0.2};
  const double dt = 1.0, s = 0.4, x0 = 0.0, u0 = 0.5;
  const size_t M = 1200000, N = 20000, N1 = 8, N2 = 12;
  sb_langevin_mom mt, m;
  sb_langevin_moments(&p, dt, x0, u0, &mt);
  double sx = sqrt(mt.var_x), su = sqrt(mt.var_u);
  double x1 = mt.mean_x + 0.7 * sx, u1 = mt.mean_u + 0.7 * su;
  sb_langevin_bridge_moments(&p, dt, s, x0, u0, x1, u1, &m);

  size_t cap = 20000, nk = 0;
  double *kx = malloc(cap * sizeof *kx), *ku = malloc(cap * sizeof *ku);
  gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
  gsl_rng_set(r, 5001);
  int st = SB_SUCCESS;
  for (size_t i = 0; i < M; i += 3) {
    /* three independent paths: the components of one 3-D particle of the
     * reference simulator (exact steps, lib/simulate/simulate.c) */
    double x[3] = {x0, x0, x0}, u[3] = {u0, u0, u0};
    st |= sb_sim_langevin(&p, s / N1, N1, r, 1, x, u);
    double xs[3] = {x[0], x[1], x[2]}, uss[3] = {u[0], u[1], u[2]};
    st |= sb_sim_langevin(&p, (dt - s) / N2, N2, r, 1, x, u);
    for (int k = 0; k < 3; k++)
      if (fabs(x[k] - x1) < 0.05 * sx && fabs(u[k] - u1) < 0.05 * su &&
          nk < cap) {
        kx[nk] = xs[k];
        ku[nk++] = uss[k];
      }
  }
  ck_assert_int_eq(st, SB_SUCCESS);
  ck_assert_msg(nk >= 1500, "only %zu paths kept", nk);

  double *bx = malloc(N * sizeof *bx), *bu = malloc(N * sizeof *bu);
  gsl_rng_set(r, 5002);
  for (size_t i = 0; i < N; i++)
    sb_langevin_bridge_sample(&p, dt, s, x0, u0, x1, u1, r, &bx[i], &bu[i]);
  /* kept paths against the closed form: means and variances (the window
   * adds <0.1% to the variances), then KS against the sampler */
  smom sm = sample_moments(kx, ku, nk);
  check_mean("brute force X_s", sm.mx, m.mean_x, m.var_x, nk);
  check_mean("brute force U_s", sm.my, m.mean_u, m.var_u, nk);
  check_var("brute force X_s", sm.vx, m.var_x, nk);
  check_var("brute force U_s", sm.vy, m.var_u, nk);
  check_corr("brute force corr", sm.r, m.cov_xu / sqrt(m.var_x * m.var_u),
             nk);
  ks2("brute force vs sampler X_s", kx, nk, bx, N);
  ks2("brute force vs sampler U_s", ku, nk, bu, N);
  gsl_rng_free(r);
  free(kx); free(ku); free(bx); free(bu);
}
END_TEST

/* Residuals.  For Gaussian (Z_s, Z_dt) the residual Z_s - E[Z_s | z0, Z_dt]
 * is independent of Z_dt with the conditional covariance; it is N(0, S)
 * only if both the gain and S are right.  N = 20000 unconditioned forward
 * paths (4 + 4 exact sub-steps) per regime, dt/tau = 1e-3, 1, 100, s = 0.3
 * dt; KS of each residual coordinate against N(0, S_kk), variance and
 * correlation intervals, and the residual must be uncorrelated with the end
 * state (Fisher z). */
START_TEST(test_bridge_residuals)
{
  const double hs[] = {1e-3, 1.0, 100.0};
  const size_t N = 20000;
  double *rx = malloc(N * sizeof *rx), *ru = malloc(N * sizeof *ru);
  double *ex = malloc(N * sizeof *ex), *eu = malloc(N * sizeof *eu);
  gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
  sb_langevin p = {0.7, 1.1, -0.4};
  for (size_t k = 0; k < 3; k++) {
    double dt = hs[k] * p.tau, s = 0.3 * dt, x0 = 0.2, u0 = -0.9;
    gsl_rng_set(r, 6000 + k);
    sb_langevin_mom m = {0};
    for (size_t i = 0; i < N; i++) {
      double x = x0, u = u0;
      for (int j = 0; j < 4; j++)
        sb_langevin_step(&p, s / 4, r, &x, &u);
      double xs = x, us = u;
      for (int j = 0; j < 4; j++)
        sb_langevin_step(&p, (dt - s) / 4, r, &x, &u);
      sb_langevin_bridge_moments(&p, dt, s, x0, u0, x, u, &m);
      rx[i] = xs - m.mean_x;
      ru[i] = us - m.mean_u;
      ex[i] = x;
      eu[i] = u;
    }
    /* S does not depend on the end state: m holds it */
    char what[64];
    snprintf(what, sizeof what, "residual dt/tau=%g", hs[k]);
    sb_langevin_mom m0 = {0, 0, m.var_x, m.var_u, m.cov_xu};
    smom sx = sample_moments(rx, ex, N), su = sample_moments(ru, eu, N);
    check_corr("residual X vs end X", sx.r, 0.0, N);
    check_corr("residual U vs end U", su.r, 0.0, N);
    check_law(what, rx, ru, N, &m0);
  }
  gsl_rng_free(r);
  free(rx); free(ru); free(ex); free(eu);
}
END_TEST

static Suite *langevin_mc_suite(void)
{
  Suite *s = suite_create("langevin_mc");
  TCase *tc = tcase_create("step");
  tcase_set_timeout(tc, 60);
  tcase_add_test(tc, test_step_marginals);
  tcase_add_test(tc, test_step3_marginals);
  tcase_add_test(tc, test_step3_stream_law);
  tcase_add_test(tc, test_step3_stream_keys);
  tcase_add_test(tc, test_step_composition);
  suite_add_tcase(s, tc);
  tc = tcase_create("bridge");
  tcase_set_timeout(tc, 60);
  tcase_add_test(tc, test_bridge_sampler_law);
  tcase_add_test(tc, test_bridge_bruteforce);
  tcase_add_test(tc, test_bridge_residuals);
  suite_add_tcase(s, tc);
  return s;
}

int main(void) { return sbt_run_suite(langevin_mc_suite()); }
