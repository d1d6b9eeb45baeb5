/* test_langevin_shear.c — the exact bridge of a Langevin particle in a
 * linear shear (<smolbridge/langevin_shear.h>, lib/langevin/langevin_shear.c).
 *
 *  (a) the coefficients against a 200-digit direct conditioning of the
 *      joint Gaussian law (tests/gen_shear_bridge_ref.py: gain form, Van
 *      Loan's covariance, mpmath's matrix exponential), h/tau in
 *      [1e-6, 1000], G tau up to 3 (G h <= 100), s/h from the first
 *      16-point Gauss-Legendre node to 0.9: ka, kb, kc within 1e-10
 *      conditional standard deviations per unit of the step's noise scale,
 *      the covariance within 1e-10 of sqrt(cov_ii cov_jj);
 *  (b) without shear (g = 0) each in-plane pair (u_y, y), (u_x, x) is the
 *      Ornstein-Uhlenbeck bridge of sb_langevin_bridge_moments (an
 *      independent implementation) for h/tau in [1e-9, 1e9] and s/h in
 *      [1e-3, 0.999] (within 1e-9 sd), and the drift velocities drop out
 *      (kc = 0);
 *  (b') Monte Carlo: 20 000 paths from random starts, exact forward steps
 *      to s and on to h, with drift velocities: the residuals of S(s)
 *      about the bridge mean, whitened by the bridge covariance, are
 *      N(0, I) and uncorrelated with S(h) (chi-square, p >= 1e-4);
 *  (b'') sb_langevin_shear_bridge_sample against the exact law inside
 *      the coefficients' domain, near both ends (the halving) and in a
 *      step below 1e-9 tau;
 *  (c) sb_langevin_shear_bridge_moments in SI units: translating the whole
 *      path by d along y while lowering c_x by G d (the same dynamics)
 *      translates the mean by d, and translating along x does the same;
 *  (d) the domain;
 *  (e) the mean path (sb_langevin_shear_mean, the exact path without
 *      noise) against a Runge-Kutta integration.
 * Broken on purpose: dropping the constant drift terms of the bridge
 * (kc = 0) fails (a) at g != 0, (b') (p(mean) = 1e-15) and (c) (231 sd:
 * the drift does change the bridge in a shear); dropping the x-y
 * correlation of the covariance fails (a) and (b') (p(cov) = 1e-5);
 * dropping u_x's response to u_y(0) from the propagator fails (a); a
 * halving that loses track of s fails (b'') near the end (p = 0). */
#include <check.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include <gsl/gsl_cdf.h>
#include <gsl/gsl_linalg.h>
#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>

#include <smolbridge/common.h>
#include <smolbridge/langevin.h>
#include <smolbridge/langevin_shear.h>

#include "refdata.h"
#include "testutil.h"

/* ------------------------------------------------- (a) reference */

START_TEST(test_reference)
{
  sbt_table t;
  sbt_table_load("shear_bridge.csv", &t);
  const int cx = sbt_col(&t, "x"), cg = sbt_col(&t, "g"),
            cs = sbt_col(&t, "s"), c0 = sbt_col(&t, "ka00");
  double worst_m = 0.0, worst_c = 0.0;
  for (int r = 0; r < t.nrow; r++) {
    const double x = sbt_at(&t, r, cx), g = sbt_at(&t, r, cg),
                 s = sbt_at(&t, r, cs);
    const double *v = &t.v[r * t.ncol + c0];
    const double *ka = v, *kb = v + 16, *kc = v + 32, *cv = v + 40;
    sb_langevin_shear_bridge b;
    ck_assert_int_eq(sb_langevin_shear_bridge_coefs(x, g, s, &b), 0);
    /* scales: the conditional standard deviations (reference) and the
     * step's own noise scale for the end states */
    double sd[4], n[4], C[4][4], S[4][4];
    for (int i = 0, q = 0; i < 4; i++)
      for (int j = 0; j <= i; j++, q++)
        C[i][j] = C[j][i] = cv[q];
    sb_langevin_shear_noise_cov(x, g, S);
    for (int i = 0; i < 4; i++) {
      sd[i] = sqrt(C[i][i]);
      n[i] = sqrt(S[i][i]);
    }
    for (int i = 0; i < 4; i++) {
      for (int j = 0; j < 4; j++) {
        const double ea = fabs(b.ka[i][j] - ka[4 * i + j]) * n[j] / sd[i];
        const double eb = fabs(b.kb[i][j] - kb[4 * i + j]) * n[j] / sd[i];
        const double ec = fabs(b.cov[i][j] - C[i][j]) / (sd[i] * sd[j]);
        worst_m = fmax(worst_m, fmax(ea, eb));
        worst_c = fmax(worst_c, ec);
        ck_assert_msg(ea <= 1e-10 && eb <= 1e-10 && ec <= 1e-10,
                      "x %g g %g s %g (%d,%d): ka %.17g/%.17g kb %.17g/%.17g "
                      "cov %.17g/%.17g", x, g, s, i, j, b.ka[i][j],
                      ka[4 * i + j], b.kb[i][j], kb[4 * i + j], b.cov[i][j],
                      C[i][j]);
      }
      for (int j = 0; j < 2; j++) {
        const double ec = fabs(b.kc[i][j] - kc[2 * i + j]) / sd[i];
        worst_m = fmax(worst_m, ec);
        ck_assert_msg(ec <= 1e-10, "x %g g %g s %g kc(%d,%d): %.17g vs %.17g",
                      x, g, s, i, j, b.kc[i][j], kc[2 * i + j]);
      }
    }
  }
  printf("shear bridge: %d rows, worst mean coefficient error %.2g sd, "
         "covariance %.2g\n", t.nrow, worst_m, worst_c);
  sbt_table_free(&t);
}
END_TEST

/* ------------------------------------------------- (b) g = 0 */

START_TEST(test_no_shear)
{
  static const double X[] = {1e-9, 1e-4, 0.3, 2.0, 50.0, 1e3, 1e6, 1e9};
  static const double F[] = {1e-3, 0.0053, 0.5, 0.97, 0.999};
  const sb_langevin p = {1.0, 1.0, 0.0};
  double worst = 0.0;
  for (size_t a = 0; a < sizeof X / sizeof *X; a++)
    for (size_t f = 0; f < sizeof F / sizeof *F; f++) {
      const double x = X[a], s = F[f] * x;
      sb_langevin_shear_bridge b;
      ck_assert_int_eq(sb_langevin_shear_bridge_coefs(x, 0.0, s, &b), 0);
      /* the OU bridge's coefficients from its moments at unit ends */
      for (int blk = 0; blk < 2; blk++) {
        const int iu = 2 * blk, ix = 2 * blk + 1; /* (u, x) of the block */
        sb_langevin_mom m0, m;
        ck_assert_int_eq(
            sb_langevin_bridge_moments(&p, x, s, 0, 0, 0, 0, &m0), 0);
        const double sdx = sqrt(m0.var_x), sdu = sqrt(m0.var_u);
        ck_assert(fabs(b.cov[ix][ix] / m0.var_x - 1.0) <= 1e-10);
        ck_assert(fabs(b.cov[iu][iu] / m0.var_u - 1.0) <= 1e-10);
        ck_assert(fabs(b.cov[ix][iu] - m0.cov_xu) <= 1e-10 * sdx * sdu);
        /* no coupling across the blocks */
        const int o = 2 - 2 * blk;
        for (int k = 0; k < 2; k++)
          for (int l = 0; l < 2; l++) {
            const double vv = b.cov[iu + k][iu + k] * b.cov[o + l][o + l];
            ck_assert(fabs(b.cov[iu + k][o + l]) <= 1e-12 * sqrt(vv));
            ck_assert(b.ka[iu + k][o + l] == 0.0);
            ck_assert(b.kb[iu + k][o + l] == 0.0);
          }
        /* ends one noise unit off in each coordinate */
        double S[4][4];
        sb_langevin_shear_noise_cov(x, 0.0, S);
        const double nu = sqrt(S[iu][iu]), nx = sqrt(S[ix][ix]);
        const double ends[4][4] = {{nx, 0, 0, 0}, {0, nu, 0, 0},
                                   {0, 0, nx, 0}, {0, 0, 0, nu}};
        for (int q = 0; q < 4; q++) {
          const double *z = ends[q]; /* x0 u0 x1 u1 */
          ck_assert_int_eq(sb_langevin_bridge_moments(&p, x, s, z[0], z[1],
                                                      z[2], z[3], &m), 0);
          const double mx = b.ka[ix][ix] * z[0] + b.ka[ix][iu] * z[1] +
                            b.kb[ix][ix] * z[2] + b.kb[ix][iu] * z[3];
          const double mu = b.ka[iu][ix] * z[0] + b.ka[iu][iu] * z[1] +
                            b.kb[iu][ix] * z[2] + b.kb[iu][iu] * z[3];
          const double e = fmax(fabs(mx - m.mean_x) / sdx,
                                fabs(mu - m.mean_u) / sdu);
          worst = fmax(worst, e);
          ck_assert_msg(e <= 1e-9, "x %g s %g block %d end %d: %.3g sd", x,
                        s, blk, q, e);
        }
        for (int k = 0; k < 2; k++)
          ck_assert_msg(fabs(b.kc[iu][k]) <= 1e-10 * sdu &&
                            fabs(b.kc[ix][k]) <= 1e-10 * sdx,
                        "x %g s %g: drift coefficient %.3g %.3g", x, s,
                        b.kc[iu][k], b.kc[ix][k]);
      }
    }
  printf("shear bridge at g = 0 against the OU bridge: worst %.2g sd\n",
         worst);
}
END_TEST

/* ------------------------------------------------- (b') Monte Carlo */

/* Lower Cholesky factor of a 4 x 4 covariance (GSL), row-major. */
static void chol4(const double S[4][4], double L[16])
{
  gsl_matrix_view m = gsl_matrix_view_array(L, 4, 4);
  for (int i = 0; i < 4; i++)
    for (int j = 0; j < 4; j++)
      L[4 * i + j] = j <= i ? S[i][j] : 0.0;
  for (int i = 0; i < 4; i++)
    for (int j = i + 1; j < 4; j++)
      L[4 * i + j] = S[j][i];
  ck_assert_int_eq(gsl_linalg_cholesky_decomp1(&m.matrix), 0);
  for (int i = 0; i < 4; i++)
    for (int j = i + 1; j < 4; j++)
      L[4 * i + j] = 0.0;
}

/* One exact forward piece: S <- Phi(t) S + a(t) c + L z. */
static void forward(double t, double g, const double c[2], const double *L,
                    const gsl_rng *r, double S[4])
{
  double P[4][4], a[4][2], z[4], o[4];
  sb_langevin_shear_propagator(t, g, P, a);
  for (int i = 0; i < 4; i++)
    z[i] = gsl_ran_gaussian_ziggurat(r, 1.0);
  for (int i = 0; i < 4; i++) {
    o[i] = a[i][0] * c[0] + a[i][1] * c[1];
    for (int j = 0; j < 4; j++)
      o[i] += P[i][j] * S[j] + L[4 * i + j] * z[j];
  }
  memcpy(S, o, sizeof o);
}

/* Paths from random starts forward to s and on to x (exact steps); the
 * residuals S(s) - E[S(s) | S(0), S(x)], whitened by the bridge's
 * covariance, must be N(0, I) and uncorrelated with S(x) (which needs
 * both the gain and the covariance right, and kc with drifts).
 * Chi-square p-values: mean (4 dof), covariance (10), cross-covariance
 * with the standardised end (16). */
START_TEST(test_residuals)
{
  static const double CASES[][5] = {/* x, g, s/x, c_x, c_y */
                                    {2.0, 0.4, 0.3, 0.7, -0.4},
                                    {0.05, 3.0, 0.6, 1.5, 0.2},
                                    {30.0, 0.2, 0.5, -0.3, 0.5}};
  const size_t N = 20000;
  gsl_rng *r = gsl_rng_alloc(gsl_rng_taus2);
  gsl_rng_set(r, 2026);
  for (size_t k = 0; k < sizeof CASES / sizeof *CASES; k++) {
    const double x = CASES[k][0], g = CASES[k][1], s = CASES[k][2] * x;
    const double c[2] = {CASES[k][3], CASES[k][4]};
    sb_langevin_shear_bridge b;
    ck_assert_int_eq(sb_langevin_shear_bridge_coefs(x, g, s, &b), 0);
    double Ss[4][4], Sr[4][4], Sx[4][4], Ls[16], Lr[16], Lc[16];
    sb_langevin_shear_noise_cov(s, g, Ss);
    sb_langevin_shear_noise_cov(x - s, g, Sr);
    sb_langevin_shear_noise_cov(x, g, Sx);
    chol4(Ss, Ls);
    chol4(Sr, Lr);
    chol4(b.cov, Lc);
    double m[4] = {0}, M[4][4] = {{0}}, X[4][4] = {{0}}, sd[4];
    {  /* E[S(x)_i^2]: S(0) ~ N(0, I), so Phi Phi^T + Sigma + (a c)^2 */
      double P[4][4], a[4][2];
      sb_langevin_shear_propagator(x, g, P, a);
      for (int i = 0; i < 4; i++) {
        const double mu = a[i][0] * c[0] + a[i][1] * c[1];
        double v = Sx[i][i] + mu * mu;
        for (int j = 0; j < 4; j++)
          v += P[i][j] * P[i][j];
        sd[i] = sqrt(v);
      }
    }
    for (size_t q = 0; q < N; q++) {
      double S0[4], S[4], w[4], R[4];
      for (int i = 0; i < 4; i++)
        S0[i] = gsl_ran_gaussian_ziggurat(r, 1.0);
      memcpy(S, S0, sizeof S);
      forward(s, g, c, Ls, r, S);
      double Sm[4];
      memcpy(Sm, S, sizeof S);
      forward(x - s, g, c, Lr, r, S);
      for (int i = 0; i < 4; i++) {
        R[i] = Sm[i] - (b.kc[i][0] * c[0] + b.kc[i][1] * c[1]);
        for (int j = 0; j < 4; j++)
          R[i] -= b.ka[i][j] * S0[j] + b.kb[i][j] * S[j];
      }
      for (int i = 0; i < 4; i++) { /* w = Lc^-1 R */
        double t = R[i];
        for (int j = 0; j < i; j++)
          t -= Lc[4 * i + j] * w[j];
        w[i] = t / Lc[4 * i + i];
      }
      for (int i = 0; i < 4; i++) {
        m[i] += w[i];
        for (int j = 0; j < 4; j++) {
          M[i][j] += w[i] * w[j];
          X[i][j] += w[i] * S[j] / sd[j];
        }
      }
    }
    double chim = 0.0, chic = 0.0, chix = 0.0;
    const double n = (double)N;
    for (int i = 0; i < 4; i++) {
      chim += m[i] * m[i] / n;
      for (int j = 0; j <= i; j++) {
        const double d = M[i][j] / n - (i == j);
        chic += d * d * n / (i == j ? 2.0 : 1.0);
      }
      for (int j = 0; j < 4; j++)
        chix += X[i][j] * X[i][j] / n;
    }
    const double pm = gsl_cdf_chisq_Q(chim, 4.0),
                 pc = gsl_cdf_chisq_Q(chic, 10.0),
                 px = gsl_cdf_chisq_Q(chix, 16.0);
    printf("shear bridge residuals x %g g %g s/x %g: p(mean) %.3g p(cov) "
           "%.3g p(cross) %.3g\n", x, g, CASES[k][2], pm, pc, px);
    ck_assert_msg(pm >= 1e-4 && pc >= 1e-4 && px >= 1e-4,
                  "x %g g %g: p %.3g %.3g %.3g", x, g, pm, pc, px);
  }
  gsl_rng_free(r);
}
END_TEST

/* sb_langevin_shear_bridge_sample: 20 000 draws, whitened by the exact
 * law, N(0, I) (chi-square p >= 1e-4 on the mean, 4 dof, and the
 * covariance, 10 dof): inside the coefficients' domain against
 * sb_langevin_shear_bridge_moments (G h = 0.5, with drifts); near both
 * ends (s/h = 1e-4, 1 - 1e-4: the interval halved by midpoint draws)
 * and below h = 1e-9 tau (each in-plane pair from its OU bridge) at
 * G = 0 against sb_langevin_bridge_moments, whose domain reaches there. */
START_TEST(test_sample)
{
  static const double CASES[][4] = {/* h/tau, s/h, G tau, drifts on */
                                    {2.0, 0.3, 0.25, 1},
                                    {2.0, 1e-4, 0.0, 0},
                                    {2.0, 1.0 - 1e-4, 0.0, 0},
                                    {5e-10, 0.4, 0.0, 0}};
  const double tau = 2e-6, B = 0.7;
  gsl_rng *r = gsl_rng_alloc(gsl_rng_taus2);
  gsl_rng_set(r, 99);
  for (size_t k = 0; k < sizeof CASES / sizeof *CASES; k++) {
    const double h = CASES[k][0] * tau, s = CASES[k][1] * h,
                 G = CASES[k][2] / tau;
    const double vu = B * sqrt(tau), vx = vu * tau;
    /* ends a typical step apart: the mean motion plus a noise-sized
     * offset (ballistic h^1.5, diffusive h^0.5); positions near 0 in the
     * tiny step (its spread is far below an ulp of 1e-6) */
    const double hn = h / tau, sn = hn < 1.0 ? pow(hn, 1.5) : sqrt(hn),
                 o0 = hn < 1e-6 ? 0.0 : 1e-6;
    const double cx = CASES[k][3] * 0.4 * vu, cy = CASES[k][3] * -0.2 * vu;
    const double s0[4] = {0.3 * vu, o0, -0.5 * vu, 2.0 * o0};
    const double s1[4] = {0.1 * vu, o0 + 0.2 * vu * h + 0.4 * vx * sn,
                          0.2 * vu, 2.0 * o0 - 0.15 * vu * h - 0.7 * vx * sn};
    double m[4], C[4][4];
    if (G != 0.0)
      ck_assert_int_eq(sb_langevin_shear_bridge_moments(tau, B, G, cx, cy, h,
                                                        s, s0, s1, m, C),
                       0);
    else {  /* two independent OU bridges */
      const sb_langevin p = {tau, B, 0.0};
      memset(C, 0, sizeof C);
      for (int c = 0; c < 2; c++) {
        sb_langevin_mom o;
        const int iu = 2 * c, ix = 2 * c + 1;
        ck_assert_int_eq(sb_langevin_bridge_moments(&p, h, s, s0[ix], s0[iu],
                                                    s1[ix], s1[iu], &o), 0);
        m[iu] = o.mean_u, m[ix] = o.mean_x;
        C[iu][iu] = o.var_u, C[ix][ix] = o.var_x;
        C[iu][ix] = C[ix][iu] = o.cov_xu;
      }
    }
    double L[16];
    chol4(C, L);
    const size_t N = 20000;
    double mm[4] = {0}, M[4][4] = {{0}};
    for (size_t q = 0; q < N; q++) {
      double o[4], w[4];
      ck_assert_int_eq(sb_langevin_shear_bridge_sample(tau, B, G, cx, cy, h,
                                                       s, s0, s1, r, o), 0);
      for (int i = 0; i < 4; i++) {
        double t = o[i] - m[i];
        for (int j = 0; j < i; j++)
          t -= L[4 * i + j] * w[j];
        w[i] = t / L[4 * i + i];
      }
      for (int i = 0; i < 4; i++) {
        mm[i] += w[i];
        for (int j = 0; j <= i; j++)
          M[i][j] += w[i] * w[j];
      }
    }
    double chim = 0.0, chic = 0.0;
    for (int i = 0; i < 4; i++) {
      chim += mm[i] * mm[i] / (double)N;
      for (int j = 0; j <= i; j++) {
        const double d = M[i][j] / (double)N - (i == j);
        chic += d * d * (double)N / (i == j ? 2.0 : 1.0);
      }
    }
    const double pm = gsl_cdf_chisq_Q(chim, 4.0),
                 pc = gsl_cdf_chisq_Q(chic, 10.0);
    printf("shear bridge sample h/tau %g s/h %g: p(mean) %.3g p(cov) %.3g\n",
           CASES[k][0], CASES[k][1], pm, pc);
    ck_assert_msg(pm >= 1e-4 && pc >= 1e-4, "case %zu: p %.3g %.3g", k, pm,
                  pc);
  }
  double o[4];
  const double z[4] = {0, 0, 0, 0};
  ck_assert_int_eq(sb_langevin_shear_bridge_sample(1, 1, 0, 0, 0, 1, 1.5, z,
                                                   z, r, o), SB_EDOM);
  ck_assert(isnan(o[0]));
  ck_assert_int_eq(sb_langevin_shear_bridge_sample(1, 1, 0, 0, 0, 1, 0.5, z,
                                                   z, NULL, o), SB_EINVAL);
  gsl_rng_free(r);
}
END_TEST

/* ------------------------------------------------- (c) SI, invariances */

START_TEST(test_translations)
{
  const double tau = 4e-7, B = 3.1e-2, G = 2.5e5, h = 3.0 * tau,
               s = 0.37 * h, cx = 0.2, cy = -0.05;
  const double vu = B * sqrt(tau), vx = vu * tau;
  const double s0[4] = {0.3 * vu, 1e-6, -0.7 * vu, 2e-6};
  const double s1[4] = {-0.2 * vu, 1e-6 + 0.8 * vx, 0.5 * vu,
                        2e-6 + 1.5 * vx};
  double m[4], c[4][4], m2[4], c2[4][4];
  ck_assert_int_eq(sb_langevin_shear_bridge_moments(tau, B, G, cx, cy, h, s,
                                                    s0, s1, m, c), 0);
  for (int i = 0; i < 4; i++)
    ck_assert(isfinite(m[i]) && c[i][i] > 0.0);
  /* y -> y + d with c_x -> c_x - G d: the same x dynamics */
  const double d = 7.3e-7;
  double t0[4], t1[4];
  for (int i = 0; i < 4; i++) {
    t0[i] = s0[i] + (i == 1 ? d : 0.0);
    t1[i] = s1[i] + (i == 1 ? d : 0.0);
  }
  ck_assert_int_eq(sb_langevin_shear_bridge_moments(tau, B, G, cx - G * d, cy,
                                                    h, s, t0, t1, m2, c2), 0);
  for (int i = 0; i < 4; i++) {
    const double want = m[i] + (i == 1 ? d : 0.0);
    ck_assert_msg(fabs(m2[i] - want) <= 1e-9 * sqrt(c[i][i]),
                  "y shift: component %d off by %.3g sd", i,
                  (m2[i] - want) / sqrt(c[i][i]));
    for (int j = 0; j < 4; j++)
      ck_assert(fabs(c2[i][j] - c[i][j]) <= 1e-12 * sqrt(c[i][i] * c[j][j]));
  }
  /* x -> x + d */
  for (int i = 0; i < 4; i++) {
    t0[i] = s0[i] + (i == 3 ? d : 0.0);
    t1[i] = s1[i] + (i == 3 ? d : 0.0);
  }
  ck_assert_int_eq(sb_langevin_shear_bridge_moments(tau, B, G, cx, cy, h, s,
                                                    t0, t1, m2, c2), 0);
  for (int i = 0; i < 4; i++) {
    const double want = m[i] + (i == 3 ? d : 0.0);
    ck_assert_msg(fabs(m2[i] - want) <= 1e-9 * sqrt(c[i][i]),
                  "x shift: component %d off by %.3g sd", i,
                  (m2[i] - want) / sqrt(c[i][i]));
  }
  /* the drift matters in a shear: c_x shifts the mean of y */
  ck_assert_int_eq(sb_langevin_shear_bridge_moments(tau, B, G, cx + 0.1, cy,
                                                    h, s, s0, s1, m2, c2), 0);
  ck_assert(fabs(m2[1] - m[1]) > 1e-3 * sqrt(c[1][1]));
}
END_TEST

/* ------------------------------------------------- (e) the mean path */

/* dS/dt of (u_y, y, u_x, x) in the field (G y + cx, cy), per unit mass */
static void shear_rhs(double tau, double G, double cx, double cy,
                      const double *S, double *d)
{
  d[0] = (cy - S[0]) / tau;
  d[1] = S[0];
  d[2] = (G * S[1] + cx - S[2]) / tau;
  d[3] = S[2];
}

/* (e) sb_langevin_shear_mean against classical Runge-Kutta on the
 * equation of motion without noise (steps of at most 0.002 tau: error
 * below 1e-12 of the increment), for tau from 1e-7 to 30 s, G tau from 0
 * to 3 (either sign), s/tau from 1e-8 to 50, drifts of both signs: each
 * component's increment S(s) - S(0) within 1e-9 of itself plus the
 * rounding of the states.  Broken on purpose: dropping u_x's response to
 * u_y(0) (g Bv) fails it (3e-3 of the increment of u_x at s = 1e-3 tau). */
START_TEST(test_mean)
{
  static const double taus[3] = {1e-7, 1.0, 30.0};
  static const double gts[4] = {0.0, 0.4, -1.3, 3.0};
  static const double sts[5] = {1e-8, 1e-3, 0.7, 5.0, 50.0};
  double worst = 0.0;
  for (int a = 0; a < 3; a++)
    for (int b = 0; b < 4; b++)
      for (int c = 0; c < 5; c++) {
        const double tau = taus[a], G = gts[b] / tau, s = sts[c] * tau;
        const double v = 1.7, cx = 0.6 * v, cy = -0.4 * v;
        const double s0[4] = {-1.1 * v, 0.3 * v * tau, 0.8 * v,
                              -2.0 * v * tau};
        double out[4];
        ck_assert_int_eq(sb_langevin_shear_mean(tau, G, cx, cy, s, s0, out),
                         SB_SUCCESS);
        int n = (int)ceil(sts[c] / 0.002);
        if (n < 1)
          n = 1;
        const double h = s / n;
        double S[4];
        memcpy(S, s0, sizeof S);
        for (int k = 0; k < n; k++) {
          double k1[4], k2[4], k3[4], k4[4], T[4];
          shear_rhs(tau, G, cx, cy, S, k1);
          for (int i = 0; i < 4; i++)
            T[i] = S[i] + 0.5 * h * k1[i];
          shear_rhs(tau, G, cx, cy, T, k2);
          for (int i = 0; i < 4; i++)
            T[i] = S[i] + 0.5 * h * k2[i];
          shear_rhs(tau, G, cx, cy, T, k3);
          for (int i = 0; i < 4; i++)
            T[i] = S[i] + h * k3[i];
          shear_rhs(tau, G, cx, cy, T, k4);
          for (int i = 0; i < 4; i++)
            S[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
        }
        for (int i = 0; i < 4; i++) {
          const double dr = S[i] - s0[i], dm = out[i] - s0[i];
          const double tol = 1e-9 * fabs(dr) +
                             1e-15 * sqrt(n) * (fabs(s0[i]) + fabs(S[i]));
          ck_assert_msg(fabs(dm - dr) <= tol,
                        "tau %g, G tau %g, s/tau %g, component %d: "
                        "increment %.15g, Runge-Kutta %.15g", tau, gts[b],
                        sts[c], i, dm, dr);
          if (dr != 0.0)
            worst = fmax(worst, fabs(dm - dr) / fabs(dr));
        }
      }
  printf("shear mean path against Runge-Kutta: largest relative error of "
         "an increment %.1e\n", worst);
  double out[4];
  const double z[4] = {0, 0, 0, 0};
  ck_assert_int_eq(sb_langevin_shear_mean(0.0, 1, 0, 0, 1, z, out), SB_EDOM);
  ck_assert(isnan(out[0]) && isnan(out[3]));
  ck_assert_int_eq(sb_langevin_shear_mean(1, 1, 0, 0, -1, z, out), SB_EDOM);
  ck_assert_int_eq(sb_langevin_shear_mean(1, NAN, 0, 0, 1, z, out), SB_EDOM);
  ck_assert_int_eq(sb_langevin_shear_mean(1, 1, 0, 0, 1, NULL, out),
                   SB_EINVAL);
  /* s = 0: the start */
  const double s0[4] = {1, 2, 3, 4};
  ck_assert_int_eq(sb_langevin_shear_mean(1, 1, 5, 6, 0, s0, out), 0);
  for (int i = 0; i < 4; i++)
    ck_assert(out[i] == s0[i]);
}
END_TEST

/* (e') the mean path at extreme time scales, against its limits: tau
 * -> 0, the particle follows the fluid (u_y = cy, y = y0 + cy s,
 * u_x = G y + cx, x = x0 + (G y0 + cx) s + G cy s^2/2); tau -> inf, it
 * keeps its velocity; s -> inf with cy = 0, u_x relaxed to G y + cx and
 * x ~ (G y + cx) s.  The O(tau) and O(1/tau) corrections are below the
 * rounding.  Where x overflows (cy != 0, s = 1e300): SB_ERANGE. */
START_TEST(test_mean_extreme)
{
  const double s0[4] = {1, 1, 1, 1};
  const double G = 1.0, cx = 0.1, cy = 0.2, s = 0.5;
  double out[4];
  const double taus[3] = {1e-300, 1e-320, 1e300};
  const double want[3][4] = {{0.2, 1.1, 1.2, 1.575},
                             {0.2, 1.1, 1.2, 1.575},
                             {1.0, 1.5, 1.0, 1.5}};
  for (int t = 0; t < 3; t++) {
    ck_assert_int_eq(sb_langevin_shear_mean(taus[t], G, cx, cy, s, s0, out),
                     SB_SUCCESS);
    for (int i = 0; i < 4; i++)
      ck_assert_rel(out[i], want[t][i], TOL_TIGHT);
  }
  ck_assert_int_eq(sb_langevin_shear_mean(1.0, G, cx, 0.0, 1e300, s0, out),
                   SB_SUCCESS);
  const double w2[4] = {0.0, 2.0, 2.1, 2.1e300};
  for (int i = 0; i < 4; i++)
    ck_assert_rel(out[i], w2[i], TOL_TIGHT);
  ck_assert_int_eq(sb_langevin_shear_mean(1.0, G, cx, cy, 1e300, s0, out),
                   SB_ERANGE);
  ck_assert(isnan(out[0]) && isnan(out[3]));
}
END_TEST

/* (e'') the bridge moments in SI units at extreme scales: the mean does
 * not depend on B (B = 1e-320 as B = 1), the covariance is B^2 times
 * B = 1's (B = 1e150), an overflowing covariance (B = 1e200) is SB_ERANGE;
 * and at tau = 2^-1000 (tau^1.5 underflows) the law is the tau = 1 law
 * with time scaled by tau = 2^-1000 exactly: positions unchanged,
 * velocities and drifts times 2^1000, Var u times 2^-1000 (B fixed),
 * Var x ~ 2^-3000 = 0. */
START_TEST(test_bridge_moments_extreme)
{
  const double s0[4] = {0.3, -0.2, 0.1, 0.4}, s1[4] = {1.0, 1.1, 0.9, 1.2};
  double m1[4], c1[4][4], m[4], c[4][4];
  ck_assert_int_eq(sb_langevin_shear_bridge_moments(1, 1, 1, 0.1, 0.2, 1,
                                                    0.5, s0, s1, m1, c1),
                   SB_SUCCESS);
  ck_assert_int_eq(sb_langevin_shear_bridge_moments(1, 1e-320, 1, 0.1, 0.2, 1,
                                                    0.5, s0, s1, m, c),
                   SB_SUCCESS);
  for (int i = 0; i < 4; i++)
    ck_assert_rel(m[i], m1[i], TOL_TIGHT);
  ck_assert_int_eq(sb_langevin_shear_bridge_moments(1, 1e150, 1, 0.1, 0.2, 1,
                                                    0.5, s0, s1, m, c),
                   SB_SUCCESS);
  for (int i = 0; i < 4; i++) {
    ck_assert_rel(m[i], m1[i], TOL_TIGHT);
    for (int j = 0; j < 4; j++)
      ck_assert_rel(c[i][j], 1e300 * c1[i][j], TOL_TIGHT);
  }
  ck_assert_int_eq(sb_langevin_shear_bridge_moments(1, 1e200, 1, 0.1, 0.2, 1,
                                                    0.5, s0, s1, m, c),
                   SB_ERANGE);
  ck_assert(isnan(m[0]) && isnan(c[3][3]));
  const double l = 0x1p-1000, il = 0x1p1000;
  const double t0[4] = {il * s0[0], s0[1], il * s0[2], s0[3]};
  const double t1[4] = {il * s1[0], s1[1], il * s1[2], s1[3]};
  ck_assert_int_eq(sb_langevin_shear_bridge_moments(l, 1, il, il * 0.1,
                                                    il * 0.2, l, 0.5 * l, t0,
                                                    t1, m, c),
                   SB_SUCCESS);
  for (int i = 0; i < 4; i++)
    ck_assert_rel(m[i], (i % 2 ? 1.0 : il) * m1[i], 1e-14);
  ck_assert_rel(c[0][0], l * c1[0][0], 1e-14);
  ck_assert_rel(c[2][0], l * c1[2][0], 1e-14);
  ck_assert_rel(c[2][2], l * c1[2][2], 1e-14);
  ck_assert(c[3][3] == 0.0 && c[1][1] == 0.0);
}
END_TEST

/* ------------------------------------------------- (d) domain */

START_TEST(test_domain)
{
  sb_langevin_shear_bridge b;
  ck_assert_int_eq(sb_langevin_shear_bridge_coefs(1.0, 0.1, 0.5, NULL),
                   SB_EINVAL);
  ck_assert_int_eq(sb_langevin_shear_bridge_coefs(1e-10, 0.1, 5e-11, &b),
                   SB_EDOM);
  ck_assert(isnan(b.ka[0][0]) && isnan(b.cov[3][3]) && isnan(b.kc[2][1]));
  ck_assert_int_eq(sb_langevin_shear_bridge_coefs(1.0, 0.1, 0.0, &b),
                   SB_EDOM);
  ck_assert_int_eq(sb_langevin_shear_bridge_coefs(1.0, 0.1, 1e-4, &b),
                   SB_EDOM);
  ck_assert_int_eq(sb_langevin_shear_bridge_coefs(1.0, 0.1, 1.0, &b),
                   SB_EDOM);
  ck_assert_int_eq(sb_langevin_shear_bridge_coefs(10.0, 11.0, 5.0, &b),
                   SB_EDOM);
  ck_assert_int_eq(sb_langevin_shear_bridge_coefs(1.0, NAN, 0.5, &b),
                   SB_EDOM);
  ck_assert_int_eq(sb_langevin_shear_bridge_coefs(1.0, 0.1, 0.5, &b), 0);
  double m[4], c[4][4];
  const double z[4] = {0, 0, 0, 0};
  ck_assert_int_eq(sb_langevin_shear_bridge_moments(0.0, 1, 1, 0, 0, 1, 0.5,
                                                    z, z, m, c), SB_EDOM);
  ck_assert(isnan(m[0]) && isnan(c[1][1]));
  ck_assert_int_eq(sb_langevin_shear_bridge_moments(1, 1, 1, 0, 0, 1, 0.5,
                                                    NULL, z, m, c), SB_EINVAL);
}
END_TEST

/* (e''') one draw at a subnormal B (the scales B sqrt(tau), B tau^1.5
 * subnormal: the states divided by them overflowed and the draw was
 * NaN).  The law is linear: B = 2^-1060 with states and drifts times
 * 2^-1000 is the B = 2^-60 draw of the same seed times 2^-1000 (to
 * rounding: the two are formed differently), at s inside [1e-3, 0.999] h
 * and near an end (the halving branch); at B = 1e-320 with ordinary
 * states the draw is the bridge mean (the noise, ~1e-320, is below its
 * rounding); and at s within 1e-9 tau of an end (the Ornstein-Uhlenbeck
 * branch) with B = 2^-1060 the draw is the B = 1 draw times 2^-1060
 * exactly (dyadic states). */
START_TEST(test_sample_subnormal_B)
{
  const double l = 0x1p-1000, d0[4] = {0.3, -0.2, 0.1, 0.4},
               d1[4] = {1.0, 1.1, -0.9, 1.2};
  const double t0[4] = {l * d0[0], l * d0[1], l * d0[2], l * d0[3]};
  const double t1[4] = {l * d1[0], l * d1[1], l * d1[2], l * d1[3]};
  const double ss[2] = {0.5, 1e-5};
  gsl_rng *r = gsl_rng_alloc(gsl_rng_taus2);
  for (int k = 0; k < 2; k++) {
    double ref[4], out[4];
    gsl_rng_set(r, 17);
    ck_assert_int_eq(sb_langevin_shear_bridge_sample(1, 0x1p-60, 0.5, 0.25,
                                                     -0.125, 1, ss[k], d0,
                                                     d1, r, ref),
                     SB_SUCCESS);
    gsl_rng_set(r, 17);
    ck_assert_int_eq(sb_langevin_shear_bridge_sample(1, 0x1p-1060, 0.5,
                                                     0.25 * l, -0.125 * l, 1,
                                                     ss[k], t0, t1, r, out),
                     SB_SUCCESS);
    for (int i = 0; i < 4; i++)
      ck_assert_rel(out[i], l * ref[i], 1e-13);
  }
  double m[4], c[4][4], out[4];
  ck_assert_int_eq(sb_langevin_shear_bridge_moments(1, 1e-320, 1, 0.1, 0.2,
                                                    1, 0.5, d0, d1, m, c),
                   SB_SUCCESS);
  ck_assert_int_eq(sb_langevin_shear_bridge_sample(1, 1e-320, 1, 0.1, 0.2, 1,
                                                   0.5, d0, d1, r, out),
                   SB_SUCCESS);
  for (int i = 0; i < 4; i++)
    ck_assert_rel(out[i], m[i], 1e-13);
  const double e = 0x1p-1060, q0[4] = {0.25, -0.5, 0.125, 0.75},
               q1[4] = {1.0, 1.125, -0.875, 1.25};
  const double u0[4] = {e * q0[0], e * q0[1], e * q0[2], e * q0[3]};
  const double u1[4] = {e * q1[0], e * q1[1], e * q1[2], e * q1[3]};
  double ref[4];
  gsl_rng_set(r, 5);
  ck_assert_int_eq(sb_langevin_shear_bridge_sample(1, 1, 0.5, 0.25, -0.125, 1,
                                                   1e-12, q0, q1, r, ref),
                   SB_SUCCESS);
  gsl_rng_set(r, 5);
  ck_assert_int_eq(sb_langevin_shear_bridge_sample(1, e, 0.5, 0.25 * e,
                                                   -0.125 * e, 1, 1e-12, u0,
                                                   u1, r, out),
                   SB_SUCCESS);
  for (int i = 0; i < 4; i++)
    ck_assert_msg(out[i] == ldexp(ref[i], -1060), "component %d: %g, want "
                  "%g", i, out[i], ldexp(ref[i], -1060));
  gsl_rng_free(r);
}
END_TEST

int main(void)
{
  Suite *s = suite_create("langevin_shear");
  TCase *tc = tcase_create("core");
  tcase_set_timeout(tc, 60);
  tcase_add_test(tc, test_reference);
  tcase_add_test(tc, test_no_shear);
  tcase_add_test(tc, test_residuals);
  tcase_add_test(tc, test_sample);
  tcase_add_test(tc, test_translations);
  tcase_add_test(tc, test_domain);
  tcase_add_test(tc, test_mean);
  tcase_add_test(tc, test_mean_extreme);
  tcase_add_test(tc, test_bridge_moments_extreme);
  tcase_add_test(tc, test_sample_subnormal_B);
  suite_add_tcase(s, tc);
  return sbt_run_suite(s);
}
