/* test_dlvo.c — DLVO module: energies and forces against mpmath (60 digits,
 * tests/gen_dlvo_ref.py, forces there are numerical derivatives of the
 * energies), Derjaguin and far-field limits of the Hamaker form, LSA vs
 * HHF in their common range, force = -dW/dD by finite differences, sign
 * changes and barrier positions against the Lambert-W closed form of the
 * Derjaguin + LSA model, barrier vs mpmath and vs a fine scan, the
 * relative-kinetic-energy laws against mpmath, quadrature and Monte Carlo,
 * and bad input (no GSL error handler call, NaN + SB_EDOM). */
#include <string.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <gsl/gsl_math.h>
#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>
#include <gsl/gsl_sf_lambert.h>
#include <smolbridge/dlvo.h>

#include "sweep.h"
#include "testutil.h"

static const double kB = 1.380649e-23;
#define TW 298.15
#define EPSW 78.4

static sb_dlvo_pair mk(int vdw, int edl, double r1, double r2, double A,
                       double z, double kappa, double psi1, double psi2,
                       double d0)
{
  sb_dlvo_pair p = {r1, r2, A, TW, EPSW, z, kappa, psi1, psi2, d0,
                    (sb_dlvo_vdw_model)vdw, (sb_dlvo_edl_model)edl};
  return p;
}

/* ---------------------------------------------------------------- CSV */

#define MAXCOL 20
/* Read the next data row of f into v (returns the number of fields, 0 at
 * end of file). */
static int csv_row(FILE *f, double *v)
{
  char line[1024];
  if (!fgets(line, sizeof line, f))
    return 0;
  int n = 0;
  for (char *s = strtok(line, ",\n"); s && n < MAXCOL; s = strtok(NULL, ",\n"))
    v[n++] = strtod(s, NULL);
  return n;
}

static FILE *csv_open(const char *name)
{
  char path[1024], hdr[1024];
  FILE *f = fopen(sbt_data_path(name, path, sizeof path), "r");
  ck_assert_msg(f != NULL, "cannot open %s", path);
  ck_assert(fgets(hdr, sizeof hdr, f) != NULL);
  return f;
}

/* |got - want| <= err (honest bound) and relative error <= tol */
#define CHECK_ERR(res, want, tol)                                        \
  do {                                                                   \
    ck_assert_msg(fabs((res).val - (want)) <= (res).err,                 \
                  "line %d: val %.17g want %.17g: |diff| %.3g > err %.3g", \
                  __LINE__, (res).val, (double)(want),                   \
                  fabs((res).val - (want)), (res).err);                  \
    ck_assert_rel((res).val, (want), (tol));                             \
  } while (0)

/* ---------------------------------------------------------------- vdW */

START_TEST(test_vdw_ref)
{
  FILE *f = csv_open("dlvo_vdw.csv");
  double v[MAXCOL];
  int n = 0;
  double worst = 0.0;
  while (csv_row(f, v) == 6) {
    sb_result w, F;
    ck_assert_int_eq(sb_dlvo_vdw_hamaker_e(v[0], v[1], v[2], v[3], &w),
                     SB_SUCCESS);
    ck_assert_int_eq(
        sb_dlvo_vdw_hamaker_force_e(v[0], v[1], v[2], v[3], &F), SB_SUCCESS);
    CHECK_ERR(w, v[4], 2e-14);
    CHECK_ERR(F, v[5], 1e-14);
    ck_assert(sb_dlvo_vdw_hamaker(v[0], v[1], v[2], v[3]) == w.val);
    worst = fmax(worst, sbt_reldiff(w.val, v[4]));
    n++;
  }
  fclose(f);
  ck_assert_int_ge(n, 90);
  printf("vdw: %d Hamaker values, worst relative error %.2g\n", n, worst);
}
END_TEST

START_TEST(test_vdw_limits)
{
  const double A = 3e-20;
  /* D down to 1e-300 of r (t = r/D beyond 1e154, where t^2 overflowed and
   * the energy turned +inf): the Derjaguin limit to 1e-14; at D = 5e-324
   * (t = R/D beyond DBL_MAX) the energy is the documented -inf, not NaN,
   * and the force SB_ERANGE */
  for (int c = 0; c < 2; c++) {
    const double r2 = c ? INFINITY : 1e-6, D = c ? 1e-160 : 1e-300;
    ck_assert_rel(sb_dlvo_vdw_hamaker(A, 1e-6, r2, D),
                  sb_dlvo_vdw_derjaguin(A, 1e-6, r2, D), 1e-14);
    ck_assert(sb_dlvo_vdw_hamaker(A, 1e-6, r2, 5e-324) == -INFINITY);
    sb_clear_error(); /* the force overflows: SB_ERANGE, not -inf */
    ck_assert(isnan(sb_dlvo_vdw_hamaker_force(A, 1e-6, r2, 5e-324)));
    ck_assert_int_eq(sb_last_status(), SB_ERANGE);
  }
  const double rr[][2] = {{1e-7, 1e-7}, {2e-7, 5e-9}, {1e-6, INFINITY}};
  for (int c = 0; c < 3; c++) {
    double r1 = rr[c][0], r2 = rr[c][1];
    double R = isinf(r2) ? r1 : r1 * r2 / (r1 + r2), rmin = fmin(r1, r2);
    /* Derjaguin limit: W_ham/W_der = 1 + O((D/r) ln(r/D)), force ratio
     * 1 + O(D/r) */
    for (double x = 1e-9; x < 1e-2; x *= 3.1) {
      double D = x * rmin;
      double q = sb_dlvo_vdw_hamaker(A, r1, r2, D) /
                 sb_dlvo_vdw_derjaguin(A, r1, r2, D);
      ck_assert_msg(fabs(q - 1.0) <= 4.0 * x * (1.0 - log(x)) + 1e-14,
                    "Derjaguin limit: ratio %.17g at D/r = %g", q, x);
      q = sb_dlvo_vdw_hamaker_force(A, r1, r2, D) /
          sb_dlvo_vdw_derjaguin_force(A, r1, r2, D);
      ck_assert_msg(fabs(q - 1.0) <= 4.0 * x + 1e-14,
                    "Derjaguin force limit: ratio %.17g at D/r = %g", q, x);
    }
    ck_assert_rel(sb_dlvo_vdw_derjaguin(A, r1, r2, 1e-9), -A * R / 6e-9,
                  TOL_TIGHT);
    /* far field: spheres -(16/9) A r1^3 r2^3/r^6 (r = centre distance)
     * times 1 + 3 (r1^2 + r2^2)/r^2 + O(r^-4); sphere-plane
     * -(2/9) A r1^3/h^3 (h = D + r1) times 1 + (6/5)(r1/D)^2 + O(D^-3)
     * (from g(t) = (4/3) t^3 - 4 t^4 + (48/5) t^5 - ..., docs/dlvo.md) */
    for (double x = 1e2; x < 1e7; x *= 10) {
      double D = x * r1, W = sb_dlvo_vdw_hamaker(A, r1, r2, D), want;
      if (isinf(r2)) {
        double h = D + r1;
        want = -2.0 / 9.0 * A * pow(r1 / h, 3) * (1 + 1.2 / (x * x));
      } else {
        double r = D + r1 + r2;
        want = -16.0 / 9.0 * A * pow(r1 / r, 3) * pow(r2 / r, 3) *
               (1 + 3 * (r1 * r1 + r2 * r2) / (r * r));
      }
      ck_assert_msg(fabs(W / want - 1.0) <= 50.0 / (x * x * x) + 1e-14,
                    "far field: ratio %.17g at D/r1 = %g", W / want, x);
    }
    /* sphere-plane = limit of sphere-sphere as r2 -> inf */
    if (isinf(r2)) {
      double D = 3e-8;
      ck_assert_rel(sb_dlvo_vdw_hamaker(A, r1, 1e6, D),
                    sb_dlvo_vdw_hamaker(A, r1, INFINITY, D), 1e-11);
      ck_assert_rel(sb_dlvo_vdw_hamaker_force(A, r1, 1e6, D),
                    sb_dlvo_vdw_hamaker_force(A, r1, INFINITY, D), 1e-11);
    }
  }
}
END_TEST

/* ---------------------------------------------------------------- EDL */

START_TEST(test_edl_ref)
{
  FILE *f = csv_open("dlvo_edl.csv");
  double v[MAXCOL];
  int n = 0;
  while (csv_row(f, v) == 12) {
    sb_result w, F;
    if (v[0] == 0.0) {
      ck_assert_int_eq(sb_dlvo_edl_lsa_e(v[1], v[2], v[3], v[4], v[5], v[6],
                                         v[7], v[8], v[9], &w), SB_SUCCESS);
      ck_assert_int_eq(sb_dlvo_edl_lsa_force_e(v[1], v[2], v[3], v[4], v[5],
                                               v[6], v[7], v[8], v[9], &F),
                       SB_SUCCESS);
    } else {
      ck_assert_int_eq(sb_dlvo_edl_hhf_e(v[1], v[2], v[3], v[4], v[5], v[8],
                                         v[9], &w), SB_SUCCESS);
      ck_assert_int_eq(sb_dlvo_edl_hhf_force_e(v[1], v[2], v[3], v[4], v[5],
                                               v[8], v[9], &F), SB_SUCCESS);
    }
    CHECK_ERR(w, v[10], 2e-14);
    CHECK_ERR(F, v[11], 2e-14);
    n++;
  }
  fclose(f);
  ck_assert_int_eq(n, 80);
}
END_TEST

START_TEST(test_lsa_vs_hhf)
{
  /* Both reduce to 4 pi eps R psi1 psi2 exp(-kappa D) for small psi and
   * large kappa D (docs/dlvo.md): independent sources, same prefactor.
   * HHF to second order in e = exp(-kappa D):
   * pi eps R [4 psi1 psi2 e - (psi1^2 + psi2^2) e^2] + O(e^3). */
  const double kappa = 1e8, psi1 = 1e-3, psi2 = 1.5e-3;
  for (double x = 20; x < 60; x += 7) {
    double D = x / kappa;
    double a = sb_dlvo_edl_lsa(D, 1e-7, 3e-7, kappa, EPSW, TW, 1, psi1, psi2);
    double b = sb_dlvo_edl_hhf(D, 1e-7, 3e-7, kappa, EPSW, psi1, psi2);
    /* tanh(y) = y (1 - y^2/3 ...), y = e psi/4kT <= 0.0146 */
    ck_assert_msg(fabs(a / b - 1.0) < 2e-4, "LSA/HHF = %.17g", a / b);
    double R = 1e-7 * 3e-7 / 4e-7;
    double e = exp(-x);
    ck_assert_rel(b, M_PI * EPSW * SB_DLVO_EPS0 * R *
                         (4 * psi1 * psi2 * e - (psi1 * psi1 + psi2 * psi2) *
                                                    e * e), 1e-12);
  }
}
END_TEST

START_TEST(test_debye)
{
  /* Israelachvili (2011) ch. 14: 1/kappa = 0.304 nm/sqrt(M) for a 1:1
   * electrolyte in water at 25 C; 2:2 halves it. */
  const double NA = 6.02214076e23;
  for (double M = 1e-4; M < 0.2; M *= 10) {
    double k1 = sb_dlvo_debye_kappa(M * 1e3 * NA, 1, EPSW, TW);
    ck_assert_rel(1.0 / k1, 0.304e-9 / sqrt(M), 4e-3);
    ck_assert_rel(sb_dlvo_debye_kappa(M * 1e3 * NA, 2, EPSW, TW), 2 * k1,
                  TOL_TIGHT);
  }
}
END_TEST

/* ---------------------------------------------------------------- totals */

START_TEST(test_force_fd)
{
  /* F = -dW/dD: 4th-order central differences, step 1e-3 D, truncation
   * ~1e-12 relative, rounding ~1e-13 relative to max(|W_vdw|, |W_edl|). */
  for (int vdw = 0; vdw < 2; vdw++)
    for (int edl = 0; edl < 2; edl++) {
      sb_dlvo_pair p = mk(vdw, edl, 2e-7, vdw ? 6e-8 : INFINITY, 1e-20, 1,
                          1e8, 0.03, 0.02, 1e-10);
      for (double D = 1e-10; D < 1e-6; D *= 1.7) {
        double h = 1e-3 * D;
        double fd = -(8 * (sb_dlvo_energy(&p, D + h) -
                           sb_dlvo_energy(&p, D - h)) -
                      (sb_dlvo_energy(&p, D + 2 * h) -
                       sb_dlvo_energy(&p, D - 2 * h))) / (12 * h);
        sb_dlvo_pair pv = p;
        pv.psi1 = pv.psi2 = 0.0;
        double scale = fabs(sb_dlvo_force(&pv, D)) +
                       fabs(sb_dlvo_force(&p, D) - sb_dlvo_force(&pv, D));
        double F = sb_dlvo_force(&p, D);
        ck_assert_msg(fabs(F - fd) <= 1e-9 * scale,
                      "model %d/%d D = %g: F %.17g, -dW/dD %.17g", vdw, edl,
                      D, F, fd);
      }
    }
}
END_TEST

/* Derjaguin + LSA: W = R [C exp(-kappa D) - A/(6D)], so with x = kappa D
 * and a = A kappa/(6C): W = 0 at x e^-x = a, F = 0 at x^2 e^-x = a, i.e.
 * x = -W(-a) and x = -2 W(-sqrt(a)/2) on the branches 0 and -1. */
static double lsa_C(double z, double psi1, double psi2)
{
  double kt = kB * TW / (z * SB_DLVO_ECHARGE);
  return 64 * M_PI * EPSW * SB_DLVO_EPS0 * kt * kt * tanh(psi1 / (4 * kt)) *
         tanh(psi2 / (4 * kt));
}

START_TEST(test_sign_changes)
{
  const double kappa = 1e8, psi = 0.04, C = lsa_C(1, psi, psi);
  for (double a = 1e-4; a < 1 / M_E; a *= 1.9) {
    double A = 6 * C * a / kappa;
    sb_dlvo_pair p = mk(0, 0, 1e-6, 3e-7, A, 1, kappa, psi, psi, 1e-12);
    double z0 = -gsl_sf_lambert_W0(-a) / kappa;
    double z1 = -gsl_sf_lambert_Wm1(-a) / kappa;
    double b0 = -2 * gsl_sf_lambert_W0(-sqrt(a) / 2) / kappa;
    double b1 = -2 * gsl_sf_lambert_Wm1(-sqrt(a) / 2) / kappa;
    const double e = 1e-9;
    ck_assert(sb_dlvo_energy(&p, z0 * (1 - e)) < 0);
    ck_assert(sb_dlvo_energy(&p, z0 * (1 + e)) > 0);
    ck_assert(sb_dlvo_energy(&p, z1 * (1 - e)) > 0);
    ck_assert(sb_dlvo_energy(&p, z1 * (1 + e)) < 0);
    ck_assert(sb_dlvo_force(&p, b0 * (1 - e)) < 0);
    ck_assert(sb_dlvo_force(&p, b0 * (1 + e)) > 0);
    ck_assert(sb_dlvo_force(&p, b1 * (1 - e)) > 0);
    ck_assert(sb_dlvo_force(&p, b1 * (1 + e)) < 0);
  }
  /* HHF: opposite potentials attract at every D, equal ones repel */
  for (double D = 1e-10; D < 1e-6; D *= 2.3) {
    ck_assert(sb_dlvo_edl_hhf(D, 1e-7, 1e-7, 1e8, EPSW, 0.02, -0.01) < 0);
    ck_assert(sb_dlvo_edl_hhf_force(D, 1e-7, 1e-7, 1e8, EPSW, 0.02, -0.01) <
              0);
    ck_assert(sb_dlvo_edl_hhf(D, 1e-7, 1e-7, 1e8, EPSW, 0.02, 0.02) > 0);
    ck_assert(sb_dlvo_edl_lsa(D, 1e-7, 1e-7, 1e8, EPSW, TW, 1, 0.02, -0.01) <
              0);
  }
}
END_TEST

START_TEST(test_barrier_lambert)
{
  const double kappa = 1e8;
  const double geo[][2] = {{5e-7, 5e-7}, {1e-6, INFINITY}, {3e-8, 2e-6}};
  int nb = 0, nn = 0;
  for (int g = 0; g < 3; g++)
    for (double a = 1e-6; a < 0.6; a *= 1.37) {
      double psi = 0.03, C = lsa_C(1, psi, psi), A = 6 * C * a / kappa;
      double r1 = geo[g][0], r2 = geo[g][1];
      double R = isinf(r2) ? r1 : r1 * r2 / (r1 + r2);
      sb_dlvo_pair p = mk(0, 0, r1, r2, A, 1, kappa, psi, psi, 1e-13);
      sb_dlvo_barrier_t b;
      ck_assert_int_eq(sb_dlvo_barrier(&p, &b), SB_SUCCESS);
      if (a > 4 / (M_E * M_E)) { /* no stationary point at all */
        ck_assert_int_eq(b.kind, SB_DLVO_NO_BARRIER);
        ck_assert(isnan(b.D_min2));
        nn++;
        continue;
      }
      double x1 = -2 * gsl_sf_lambert_W0(-sqrt(a) / 2);
      double x2 = -2 * gsl_sf_lambert_Wm1(-sqrt(a) / 2);
      /* secondary minimum in every case */
      ck_assert_rel(b.D_min2, x2 / kappa, 1e-11);
      ck_assert_rel(b.W_min2, R * C * (exp(-x2) - a / x2), 1e-11);
      if (x1 >= 1.0) { /* the maximum is <= 0: nothing to overcome */
        ck_assert_int_eq(b.kind, SB_DLVO_NO_BARRIER);
        ck_assert(b.W_max == 0.0 && isinf(b.D_max));
        nn++;
        continue;
      }
      ck_assert_int_eq(b.kind, SB_DLVO_BARRIER);
      double Wm = R * C * (exp(-x1) - a / x1);
      ck_assert_rel(b.D_max, x1 / kappa, 1e-12);
      ck_assert(fabs(b.D_max - x1 / kappa) <= b.D_max_err);
      /* the reference cancels as 1 - x1 near x1 = 1 */
      ck_assert_rel(b.W_max, Wm, 1e-14 * R * C * exp(-x1) / Wm + 4e-16);
      ck_assert(fabs(b.W_max - Wm) <= b.W_max_err + 4e-16 * R * C);
      nb++;
    }
  ck_assert_int_ge(nb, 100);
  ck_assert_int_ge(nn, 6);
}
END_TEST

START_TEST(test_barrier_ref)
{
  FILE *f = csv_open("dlvo_barrier.csv");
  double v[MAXCOL];
  int n = 0;
  while (csv_row(f, v) == 17) {
    sb_dlvo_pair p = {v[2], v[3], v[4], v[5], v[6], v[7], v[8], v[9], v[10],
                      v[11], (sb_dlvo_vdw_model)v[0],
                      (sb_dlvo_edl_model)v[1]};
    sb_dlvo_barrier_t b;
    ck_assert_int_eq(sb_dlvo_barrier(&p, &b), SB_SUCCESS);
    ck_assert_int_eq(b.kind, (int)v[12]);
    if (b.kind == SB_DLVO_NO_BARRIER) {
      ck_assert(b.W_max == 0.0 && isinf(b.D_max));
    } else {
      ck_assert(fabs(b.D_max - v[13]) <= b.D_max_err + 0.0);
      ck_assert_rel(b.D_max, v[13], 1e-12);
      ck_assert(fabs(b.W_max - v[14]) <= b.W_max_err);
      ck_assert_rel(b.W_max, v[14], 1e-13);
    }
    if (isnan(v[15])) {
      ck_assert(isnan(b.D_min2));
    } else {
      ck_assert_rel(b.D_min2, v[15], 1e-10);
      ck_assert_rel(b.W_min2, v[16], 1e-11);
    }
    n++;
  }
  fclose(f);
  ck_assert_int_eq(n, 7);
}
END_TEST

START_TEST(test_barrier_scan)
{
  /* The maximum of W on a fine grid (2e5 points, log-spaced from
   * d_contact to 50/kappa) is attained within one grid step of D_max
   * and does not exceed W_max. */
  for (int vdw = 0; vdw < 2; vdw++)
    for (int edl = 0; edl < 2; edl++) {
      sb_dlvo_pair p = mk(vdw, edl, 1e-7, vdw ? 4e-7 : INFINITY, 1e-20, 1,
                          2e8, 0.025, 0.03, 2e-10);
      sb_dlvo_barrier_t b;
      ck_assert_int_eq(sb_dlvo_barrier(&p, &b), SB_SUCCESS);
      ck_assert_int_eq(b.kind, SB_DLVO_BARRIER);
      const int n = 200000;
      double lo = p.d_contact, hi = 50 / p.kappa, q = pow(hi / lo, 1.0 / n);
      double best = -INFINITY, at = 0;
      for (int i = 0; i <= n; i++) {
        double D = lo * pow(q, i), W = sb_dlvo_energy(&p, D);
        if (W > best)
          best = W, at = D;
      }
      ck_assert(best <= b.W_max + b.W_max_err);
      ck_assert_rel(best, b.W_max, 1e-9);
      ck_assert_msg(fabs(at - b.D_max) <= (q - 1) * at,
                    "scan max at %g, D_max %g", at, b.D_max);
    }
}
END_TEST

START_TEST(test_barrier_tail)
{
  /* Very long Debye length (pure water, 1/kappa = 960 nm) and weak vdW:
   * the secondary minimum lies far out; big particles. */
  sb_dlvo_pair p = mk(1, 0, 5e-6, 5e-6, 1e-21, 1, 1 / 960e-9, 0.05, 0.05,
                      3e-10);
  sb_dlvo_barrier_t b;
  ck_assert_int_eq(sb_dlvo_barrier(&p, &b), SB_SUCCESS);
  ck_assert_int_eq(b.kind, SB_DLVO_BARRIER);
  ck_assert(b.D_min2 > b.D_max);
  ck_assert(fabs(sb_dlvo_force(&p, b.D_min2)) <=
            1e-9 * fabs(sb_dlvo_vdw_hamaker_force(p.A, p.r1, p.r2, b.D_min2)));
  /* A = 0: pure repulsion, the sup is at contact */
  p.A = 0.0;
  ck_assert_int_eq(sb_dlvo_barrier(&p, &b), SB_SUCCESS);
  ck_assert_int_eq(b.kind, SB_DLVO_BARRIER_CONTACT);
  ck_assert(b.W_max == sb_dlvo_energy(&p, p.d_contact));
}
END_TEST

/* ---------------------------------------------------------------- E_rel */

START_TEST(test_erel_values)
{
  const double v1[3] = {1.5, -2.0, 0.25}, v2[3] = {-0.5, 1.0, 3.0};
  double m1 = 2e-15, m2 = 5e-16, mu = m1 * m2 / (m1 + m2);
  double w2 = 4.0 + 9.0 + 2.75 * 2.75;
  ck_assert_rel(sb_dlvo_erel(m1, m2, v1, v2), 0.5 * mu * w2, TOL_TIGHT);
  /* total = centre-of-mass + relative (eq C.11) */
  double vc[3], ec = 0, e1 = 0, e2 = 0;
  for (int k = 0; k < 3; k++) {
    vc[k] = (m1 * v1[k] + m2 * v2[k]) / (m1 + m2);
    ec += 0.5 * (m1 + m2) * vc[k] * vc[k];
    e1 += 0.5 * m1 * v1[k] * v1[k];
    e2 += 0.5 * m2 * v2[k] * v2[k];
  }
  ck_assert_rel(ec + sb_dlvo_erel(m1, m2, v1, v2), e1 + e2, TOL_TIGHT);
  /* normal part: along w it is everything, across w nothing */
  double w[3] = {2.0, -3.0, -2.75}, t[3] = {3.0, 2.0, 0.0};
  ck_assert_rel(sb_dlvo_erel_normal(m1, m2, v1, v2, w),
                sb_dlvo_erel(m1, m2, v1, v2), TOL_TIGHT);
  ck_assert_abs(sb_dlvo_erel_normal(m1, m2, v1, v2, t), 0.0,
                1e-15 * sb_dlvo_erel(m1, m2, v1, v2));
  ck_assert_int_eq(sb_dlvo_sticks(2.0, 1.0), 1);
  ck_assert_int_eq(sb_dlvo_sticks(1.0, 1.0), 0);
  ck_assert_int_eq(sb_dlvo_sticks(0.5, 1.0), 0);
  ck_assert_int_eq(sb_dlvo_sticks(NAN, 1.0), 0);
}
END_TEST

/* Extreme arguments: the limits where they are representable (no error
 * recorded), NaN and SB_ERANGE where the result overflows. */
START_TEST(test_erel_extreme)
{
  for (int l = 0; l < 4; l++) {
    sb_dlvo_erel_law law = (sb_dlvo_erel_law)l;
    sb_clear_error();
    ck_assert(sb_dlvo_erel_P(INFINITY, 1, law, 3) == 1.0);
    ck_assert(sb_dlvo_erel_Q(INFINITY, 1, law, 3) == 0.0);
    ck_assert(sb_dlvo_erel_pdf(INFINITY, 1, law, 3) == 0.0);
    ck_assert(sb_dlvo_erel_logQ(INFINITY, 1, law, 3) == -INFINITY);
    /* E/theta = 1e300 (GSL's erf is NaN beyond ~1e124) and E/theta
     * overflowing (theta subnormal): P = 1, Q = 0, density 0 */
    const double Es[2] = {1e300, 1.0}, ths[2] = {1.0, 1e-320};
    for (int c = 0; c < 2; c++) {
      ck_assert(sb_dlvo_erel_P(Es[c], ths[c], law, 3) == 1.0);
      ck_assert(sb_dlvo_erel_Q(Es[c], ths[c], law, 3) == 0.0);
      ck_assert(sb_dlvo_erel_pdf(Es[c], ths[c], law, 3) == 0.0);
    }
    ck_assert_int_eq(sb_last_status(), SB_SUCCESS);
    /* log Q = -x + log(prefactor), x = 1e300: -1e300 to rounding */
    ck_assert_rel(sb_dlvo_erel_logQ(1e300, 1, law, 3), -1e300, TOL_TIGHT);
    ck_assert(isnan(sb_dlvo_erel_logQ(1.0, 1e-320, law, 3)));
    ck_assert_int_eq(sb_last_status(), SB_ERANGE);
  }
  /* the density at E = 0 for k = 1 is 1/theta: overflows for theta 1e-320;
   * for k = 1/2 it is +inf (documented), not an error */
  sb_clear_error();
  ck_assert(sb_dlvo_erel_pdf(0, 1e-320, SB_DLVO_EREL_STATIONARY_NORMAL, 3) ==
            INFINITY);
  ck_assert_int_eq(sb_last_status(), SB_SUCCESS);
  ck_assert(isnan(sb_dlvo_erel_pdf(0, 1e-320, SB_DLVO_EREL_COLLISION_NORMAL,
                                   3)));
  ck_assert_int_eq(sb_last_status(), SB_ERANGE);
  ck_assert_rel(sb_dlvo_erel_pdf(0, 1e-300, SB_DLVO_EREL_COLLISION_NORMAL, 3),
                1e300, TOL_TIGHT);

  /* E_rel at extreme scales, against hand values: |w| = 5 x scale */
  const double z[3] = {0, 0, 0};
  const double big[3] = {3e200, 4e200, 0}, tiny[3] = {3e-200, 4e-200, 0};
  sb_clear_error();
  /* mu = 1e-250: E = 0.5e-250 * 25e400 */
  ck_assert_rel(sb_dlvo_erel(2e-250, 2e-250, big, z), 1.25e151, TOL_TIGHT);
  /* mu = 1e250: E = 0.5e250 * 25e-400 */
  ck_assert_rel(sb_dlvo_erel(2e250, 2e250, tiny, z), 1.25e-149, TOL_TIGHT);
  /* m1/m2 overflows: mu = m2 */
  const double one[3] = {1, 0, 0};
  ck_assert_rel(sb_dlvo_erel(1e300, 1e-10, one, z), 0.5e-10, TOL_TIGHT);
  ck_assert_rel(sb_dlvo_erel(1e-10, 1e300, one, z), 0.5e-10, TOL_TIGHT);
  /* velocities of opposite sign whose difference overflows, small mu:
   * w = 2^1024, mu = 2^-1030, E = 2^1017 exactly */
  const double vp[3] = {0x1p1023, 0, 0}, vm[3] = {-0x1p1023, 0, 0};
  ck_assert_rel(sb_dlvo_erel(0x1p-1029, 0x1p-1029, vp, vm), 0x1p1017,
                TOL_TIGHT);
  /* normal part with |n| tiny or huge: n along x and along (1, 1, 0) */
  const double v34[3] = {3, 4, 0};
  const double nt[3] = {1e-200, 0, 0}, nh[3] = {1e200, 1e200, 0};
  ck_assert_rel(sb_dlvo_erel_normal(2, 2, v34, z, nt), 0.5 * 9.0, TOL_TIGHT);
  ck_assert_rel(sb_dlvo_erel_normal(2, 2, v34, z, nh), 0.5 * 24.5,
                TOL_TIGHT);
  ck_assert_rel(sb_dlvo_erel_normal(2e-250, 2e-250, big, z, nh),
                1.225e151, TOL_TIGHT);
  /* underflow is 0, not an error */
  ck_assert(sb_dlvo_erel(1, 2, tiny, z) == 0.0);
  ck_assert_int_eq(sb_last_status(), SB_SUCCESS);
  /* overflow */
  const double v300[3] = {1e300, 0, 0};
  ck_assert(isnan(sb_dlvo_erel(1, 2, v300, z)));
  ck_assert_int_eq(sb_last_status(), SB_ERANGE);
  sb_clear_error();
  ck_assert(isnan(sb_dlvo_erel_normal(1, 2, v300, z, one)));
  ck_assert_int_eq(sb_last_status(), SB_ERANGE);
}
END_TEST

START_TEST(test_erel_ref)
{
  FILE *f = csv_open("dlvo_erel.csv");
  double v[MAXCOL];
  int n = 0;
  /* (law, dim) giving each shape k2/2 */
  const int law_of[5][2] = {{0, 0}, {1, 3}, {3, 3}, {0, 3}, {2, 3}};
  const double theta = 0x1p-70; /* ~kT; a power of 2: E/theta exact */
  while (csv_row(f, v) == 6) {
    int k2 = (int)v[0];
    sb_dlvo_erel_law law = (sb_dlvo_erel_law)law_of[k2][0];
    int dim = law_of[k2][1];
    ck_assert(sb_dlvo_erel_shape(law, dim) == 0.5 * k2);
    double E = v[1] * theta;
    sb_result P, Q;
    ck_assert_int_eq(sb_dlvo_erel_P_e(E, theta, law, dim, &P), SB_SUCCESS);
    ck_assert_int_eq(sb_dlvo_erel_Q_e(E, theta, law, dim, &Q), SB_SUCCESS);
    CHECK_ERR(P, v[2], 1e-14);
    CHECK_ERR(Q, v[3], 1e-14);
    ck_assert_rel(sb_dlvo_erel_pdf(E, theta, law, dim) * theta, v[4],
                  TOL_TIGHT);
    ck_assert_abs(sb_dlvo_erel_logQ(E, theta, law, dim), v[5],
                  2e-16 + 1e-14 * fabs(v[5]));
    n++;
  }
  fclose(f);
  ck_assert_int_eq(n, 60);
  /* logQ beyond underflow: k = 2 is log1p(x) - x */
  ck_assert_rel(sb_dlvo_erel_logQ(1000, 1, SB_DLVO_EREL_COLLISION, 3),
                log1p(1000.0) - 1000.0, TOL_TIGHT);
  ck_assert(isfinite(sb_dlvo_erel_logQ(1e4, 1, SB_DLVO_EREL_STATIONARY, 3)));
}
END_TEST

typedef struct {
  sb_dlvo_erel_law law;
  int dim;
} lawdim;

static double pdf_fn(double E, void *c)
{
  const lawdim *l = c;
  return sb_dlvo_erel_pdf(E, 1.0, l->law, l->dim);
}

START_TEST(test_erel_quad)
{
  /* P and Q against GSL adaptive quadrature of the density (QAGS, which
   * handles the E^-1/2 end point; QAGIU for the tail). */
  gsl_integration_workspace *w = gsl_integration_workspace_alloc(200);
  for (int law = 0; law < 4; law++)
    for (int dim = 1; dim <= 3; dim++) {
      lawdim l = {(sb_dlvo_erel_law)law, dim};
      gsl_function fn = {pdf_fn, &l};
      for (double x = 0.05; x < 40; x *= 2.3) {
        double P, Q, eP, eQ;
        gsl_integration_qags(&fn, 0, x, 0, 1e-12, 200, w, &P, &eP);
        gsl_integration_qagiu(&fn, x, 0, 1e-12, 200, w, &Q, &eQ);
        ck_assert_rel(sb_dlvo_erel_P(x, 1, l.law, dim), P, TOL_QUAD);
        ck_assert_rel(sb_dlvo_erel_Q(x, 1, l.law, dim), Q, TOL_QUAD);
      }
    }
  gsl_integration_workspace_free(w);
}
END_TEST

START_TEST(test_erel_mc)
{
  /* Two particles with independent Maxwellian velocities (v_i ~ N(0, kT/m_i)
   * per component), N = 200000 pairs, seed 20240607.  For the COLLISION
   * laws each pair gets a random isotropic line of centres n and the
   * approach-flux weight max(0, -w.n) (ratio estimator).  The fraction of
   * E_rel > W must match Q(W) with |z| < 4.5 (delta-method standard error)
   * for W/kT in {0.3, 1.5, 4}, for all four laws in 3-D. */
  gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
  gsl_rng_set(r, 20240607);
  const double T = 300, m1 = 3e-17, m2 = 7e-18, kT = kB * T;
  const int N = 200000;
  const double Ws[3] = {0.3 * kT, 1.5 * kT, 4 * kT};
  double sw[4][3] = {{0}}, sw2[4][3] = {{0}}, wsum[4] = {0}, w2sum[4] = {0};
  double cross[4][3] = {{0}};
  for (int i = 0; i < N; i++) {
    double v1[3], v2[3], n[3], wn = 0;
    for (int k = 0; k < 3; k++) {
      v1[k] = gsl_ran_gaussian(r, sqrt(kT / m1));
      v2[k] = gsl_ran_gaussian(r, sqrt(kT / m2));
    }
    gsl_ran_dir_3d(r, &n[0], &n[1], &n[2]);
    for (int k = 0; k < 3; k++)
      wn += (v1[k] - v2[k]) * n[k];
    double E = sb_dlvo_erel(m1, m2, v1, v2);
    double En = sb_dlvo_erel_normal(m1, m2, v1, v2, n);
    double flux = wn < 0 ? -wn : 0; /* approaching along n */
    const double e[4] = {E, En, E, En}, wt[4] = {1, 1, flux, flux};
    for (int l = 0; l < 4; l++) {
      wsum[l] += wt[l];
      w2sum[l] += wt[l] * wt[l];
      for (int j = 0; j < 3; j++) {
        double y = wt[l] * (e[l] > Ws[j]);
        sw[l][j] += y;
        sw2[l][j] += y * y;
        cross[l][j] += y * wt[l];
      }
    }
  }
  for (int l = 0; l < 4; l++)
    for (int j = 0; j < 3; j++) {
      double q = sb_dlvo_erel_Q(Ws[j], kT, (sb_dlvo_erel_law)l, 3);
      double ybar = sw[l][j] / N, wbar = wsum[l] / N, est = ybar / wbar;
      /* Var(ratio) ~ Var(y - est w)/(N wbar^2) */
      double var = (sw2[l][j] / N - 2 * est * cross[l][j] / N +
                    est * est * w2sum[l] / N) / (N * wbar * wbar);
      double zz = (est - q) / sqrt(var);
      ck_assert_msg(fabs(zz) < 4.5, "law %d W/kT = %g: MC %.5f, Q %.5f, "
                    "z = %.2f", l, Ws[j] / kT, est, q, zz);
    }
  gsl_rng_free(r);
}
END_TEST

START_TEST(test_erel_sample)
{
  /* N = 100000 draws per law (seed 7): the mean (k theta) within 4.5
   * standard errors (sqrt(k) theta/sqrt(N)) and the fraction above
   * 2 theta within 4.5 binomial standard errors of Q(2 theta). */
  gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
  gsl_rng_set(r, 7);
  const int N = 100000;
  for (int law = 0; law < 4; law++) {
    double k = sb_dlvo_erel_shape((sb_dlvo_erel_law)law, 3), s = 0, c = 0;
    for (int i = 0; i < N; i++) {
      double e = sb_dlvo_erel_sample(r, 2.0, (sb_dlvo_erel_law)law, 3);
      s += e;
      c += e > 4.0;
    }
    ck_assert(fabs(s / N - 2 * k) < 4.5 * sqrt(k) * 2 / sqrt(N));
    double q = sb_dlvo_erel_Q(4.0, 2.0, (sb_dlvo_erel_law)law, 3);
    ck_assert(fabs(c / N - q) < 4.5 * sqrt(q * (1 - q) / N));
  }
  gsl_rng_free(r);
}
END_TEST

/* ---------------------------------------------------------------- errors */

/* Extreme arguments (each argument in turn over sbt_sweep_ext: 1e-320 ...
 * DBL_MAX, inf, NaN, 2^+-995, 1e+-154, negative values; the others
 * ordinary): a function returns a finite
 * value and SB_SUCCESS, or NaN and an error (SB_EDOM outside the domain,
 * SB_ERANGE where the value exceeds DBL_MAX) -- never a silent inf or
 * NaN, except the documented -inf of the Hamaker energy where t = R/D
 * exceeds DBL_MAX.  At the finite extremes the value against mpmath at
 * 1000 digits (tests/gen_dlvo_ref.py, dlvo_sweep.csv: the same table),
 * with an honest error bound: where an intermediate over/underflowed
 * (psi = 1e300 gave NaN, A = 1e300 a force of -inf, eps_r = DBL_MAX or
 * kappa D = 1e308 an inf or NaN energy or bound) the value is now right
 * wherever it is a double. */
/* The sweep's form (sweep.h, sbt_xfn): value and error bound of the
 * sb_result of NAME, called as CALL with the result in r. */
#define D_XFN(w, NAME, CALL)                                                \
  static int w(const double *a, double *out, int *n, const char **nm)     \
  {                                                                         \
    sb_result r = {0.0, 0.0};                                               \
    const int st = (CALL);                                                  \
    out[0] = r.val;                                                         \
    out[1] = r.err;                                                         \
    *n = 2;                                                                 \
    *nm = NAME;                                                             \
    return st;                                                              \
  }
D_XFN(d_ham, "sb_dlvo_vdw_hamaker_e",
      sb_dlvo_vdw_hamaker_e(a[0], a[1], a[2], a[3], &r))
D_XFN(d_hamf, "sb_dlvo_vdw_hamaker_force_e",
      sb_dlvo_vdw_hamaker_force_e(a[0], a[1], a[2], a[3], &r))
D_XFN(d_der, "sb_dlvo_vdw_derjaguin_e",
      sb_dlvo_vdw_derjaguin_e(a[0], a[1], a[2], a[3], &r))
D_XFN(d_derf, "sb_dlvo_vdw_derjaguin_force_e",
      sb_dlvo_vdw_derjaguin_force_e(a[0], a[1], a[2], a[3], &r))
D_XFN(d_lsa, "sb_dlvo_edl_lsa_e",
      sb_dlvo_edl_lsa_e(a[0], a[1], a[2], a[3], a[4], a[5], a[6], a[7],
                        a[8], &r))
D_XFN(d_lsaf, "sb_dlvo_edl_lsa_force_e",
      sb_dlvo_edl_lsa_force_e(a[0], a[1], a[2], a[3], a[4], a[5], a[6],
                              a[7], a[8], &r))
D_XFN(d_hhf, "sb_dlvo_edl_hhf_e",
      sb_dlvo_edl_hhf_e(a[0], a[1], a[2], a[3], a[4], a[5], a[6], &r))
D_XFN(d_hhff, "sb_dlvo_edl_hhf_force_e",
      sb_dlvo_edl_hhf_force_e(a[0], a[1], a[2], a[3], a[4], a[5], a[6],
                              &r))
static int kappa_e(const double *a, sb_result *r)
{
  sb_clear_error();
  r->val = sb_dlvo_debye_kappa(a[0], a[1], a[2], a[3]);
  r->err = 4.0 * DBL_EPSILON * fabs(r->val);
  return sb_last_status();
}
D_XFN(d_kappa, "sb_dlvo_debye_kappa", kappa_e(a, &r))
static sb_dlvo_pair d_pair(const double *a)
{
  sb_dlvo_pair p = mk((int)a[11], (int)a[12], a[0], a[1], a[2], a[5], a[6],
                      a[7], a[8], a[9]);
  p.T = a[3];
  p.eps_r = a[4];
  return p;
}
static int energy_e(const double *a, sb_result *r)
{
  sb_dlvo_pair p = d_pair(a);
  return sb_dlvo_energy_e(&p, a[10], r);
}
static int force_e(const double *a, sb_result *r)
{
  sb_dlvo_pair p = d_pair(a);
  return sb_dlvo_force_e(&p, a[10], r);
}
D_XFN(d_energy, "sb_dlvo_energy_e", energy_e(a, &r))
D_XFN(d_force, "sb_dlvo_force_e", force_e(a, &r))
/* The sweep's view of the documented -inf (status 0) of the Hamaker
 * energy, and of the total energy with the Hamaker model: 0. */
static int d_ham_sweep(const double *a, double *out, int *n,
                       const char **nm)
{
  const int st = d_ham(a, out, n, nm);
  if (st == SB_SUCCESS && out[0] == -INFINITY)
    out[0] = 0.0;
  return st;
}
static int d_energy_sweep(const double *a, double *out, int *n,
                          const char **nm)
{
  const int st = d_energy(a, out, n, nm);
  if (st == SB_SUCCESS && out[0] == -INFINITY &&
      (int)a[11] == SB_DLVO_VDW_HAMAKER)
    out[0] = 0.0;
  return st;
}

START_TEST(test_extreme_arguments)
{
  static const struct {
    sbt_xfn f;
    int n;
    double a[13];
  } k[] = {
      {d_ham, 4, {1e-20, 1e-6, 2e-6, 1e-8}},
      {d_hamf, 4, {1e-20, 1e-6, 2e-6, 1e-8}},
      {d_der, 4, {1e-20, 1e-6, 2e-6, 1e-8}},
      {d_derf, 4, {1e-20, 1e-6, 2e-6, 1e-8}},
      {d_lsa, 9, {1e-8, 1e-6, 2e-6, 1e8, 78.4, 298, 1, 0.03, 0.02}},
      {d_lsaf, 9, {1e-8, 1e-6, 2e-6, 1e8, 78.4, 298, 1, 0.03, 0.02}},
      {d_hhf, 7, {1e-8, 1e-6, 2e-6, 1e8, 78.4, 0.03, 0.02}},
      {d_hhff, 7, {1e-8, 1e-6, 2e-6, 1e8, 78.4, 0.03, 0.02}},
      {d_kappa, 4, {6e23, 1, 78.4, 298}},
      {d_energy, 11,
       {1e-6, 2e-6, 1e-20, 298, 78.4, 1, 1e8, 0.03, 0.02, 4e-10, 1e-8, 1, 1}},
      {d_energy, 11,
       {1e-6, 2e-6, 1e-20, 298, 78.4, 1, 1e8, 0.03, 0.02, 4e-10, 1e-8, 0, 0}},
      {d_force, 11,
       {1e-6, 2e-6, 1e-20, 298, 78.4, 1, 1e8, 0.03, 0.02, 4e-10, 1e-8, 1, 1}},
      {d_force, 11,
       {1e-6, 2e-6, 1e-20, 298, 78.4, 1, 1e8, 0.03, 0.02, 4e-10, 1e-8, 0, 0}},
  };
  /* sbt_sweep_ext; value and bound finite with status 0, or SB_EDOM or
   * SB_ERANGE with a NaN value and a message naming the function */
  int nbad = 0; /* every failure is printed, then counted */
  for (size_t f = 0; f < sizeof k / sizeof k[0]; f++) {
    const sbt_xfn g = k[f].f == d_ham      ? d_ham_sweep
                      : k[f].f == d_energy ? d_energy_sweep
                                           : k[f].f;
    nbad += sbt_sweep_vec(g, k[f].a, 13, k[f].n, 0, 0, SBT_SWEEP_NAN0, f);
  }
  ck_assert_int_eq(nbad, 0);
  FILE *fh = csv_open("dlvo_sweep.csv");
  double v[MAXCOL];
  int rows = 0;
  while (csv_row(fh, v) == 4) {
    const int f = (int)v[0], i = (int)v[1];
    const double want = v[3];
    double a[13];
    memcpy(a, k[f].a, sizeof a);
    a[i] = v[2];
    double out[SBT_SWEEP_MAXOUT];
    int n;
    const char *nm;
    sb_clear_error();
    const int st = k[f].f(a, out, &n, &nm);
    const sb_result r = {out[0], out[1]};
    if (want == -INFINITY) /* Hamaker energy, t = R/D beyond DBL_MAX */
      ck_assert_msg(r.val == -INFINITY && st == SB_SUCCESS,
                    "function %d, argument %d = %g: %g (status %d), want "
                    "-inf", f, i, a[i], r.val, st);
    else if (isinf(want))
      ck_assert_msg(isnan(r.val) && st == SB_ERANGE,
                    "function %d, argument %d = %g: %g (status %d), want "
                    "SB_ERANGE", f, i, a[i], r.val, st);
    else if (want == 0.0)
      ck_assert_msg(st == SB_SUCCESS && fabs(r.val) <= DBL_MIN &&
                        fabs(r.val) <= r.err + DBL_MIN,
                    "function %d, argument %d = %g: %g +- %g (status %d), "
                    "want below DBL_MIN", f, i, a[i], r.val, r.err, st);
    else
      ck_assert_msg(st == SB_SUCCESS && fabs(r.val / want - 1.0) <= 1e-13 &&
                        fabs(r.val - want) <= r.err,
                    "function %d, argument %d = %g: %.17g +- %.3g (status "
                    "%d), want %.17g", f, i, a[i], r.val, r.err, st, want);
    rows++;
  }
  fclose(fh);
  ck_assert_int_ge(rows, 400);
}
END_TEST

/* The error bound of P for k = 1 and k = 2 at large x stays a few ulp
 * (P -> 1 to full precision): it was (1 + x) 2 eps and (4 + 2x) eps,
 * 4e-10 at x = 1e6.  The bound is still honest against the exact
 * 1 - (1 + x) e^-x at x = 3, 30 (mpmath: 0.80085172652854422808,
 * 0.99999999999709913688). */
START_TEST(test_erel_P_err)
{
  const double xs[3] = {100.0, 1e3, 1e6};
  for (int k = 0; k < 3; k++) {
    sb_result r;
    ck_assert_int_eq(sb_dlvo_erel_P_e(xs[k], 1, SB_DLVO_EREL_COLLISION_NORMAL,
                                      3, &r), SB_SUCCESS);
    ck_assert(r.val == 1.0 && r.err <= 4 * DBL_EPSILON);
    ck_assert_int_eq(sb_dlvo_erel_P_e(xs[k], 1, SB_DLVO_EREL_COLLISION, 3,
                                      &r), SB_SUCCESS);
    ck_assert(r.val == 1.0 && r.err <= 4 * DBL_EPSILON);
  }
  sb_result r;
  ck_assert_int_eq(sb_dlvo_erel_P_e(3, 1, SB_DLVO_EREL_COLLISION, 3, &r),
                   SB_SUCCESS);
  CHECK_ERR(r, 0.80085172652854422808, 1e-15);
  ck_assert_int_eq(sb_dlvo_erel_P_e(30, 1, SB_DLVO_EREL_COLLISION, 3, &r),
                   SB_SUCCESS);
  CHECK_ERR(r, 0.99999999999709913688, 1e-15);
}
END_TEST

/* Errors name the public function that was called (the shared check of
 * law, theta and E reported its own name, law_k2). */
START_TEST(test_error_names)
{
  const sb_dlvo_erel_law bad = (sb_dlvo_erel_law)99;
  sb_result r;
  const char *names[6] = {"sb_dlvo_erel_P:", "sb_dlvo_erel_Q:",
                          "sb_dlvo_erel_Q_e:", "sb_dlvo_erel_logQ:",
                          "sb_dlvo_erel_pdf:", "sb_dlvo_erel_P_e:"};
  for (int k = 0; k < 6; k++) {
    sb_clear_error();
    switch (k) {
    case 0: ck_assert(isnan(sb_dlvo_erel_P(1, 1, bad, 3))); break;
    case 1: ck_assert(isnan(sb_dlvo_erel_Q(-1, 1, SB_DLVO_EREL_STATIONARY,
                                           3))); break;
    case 2:
      ck_assert_int_eq(sb_dlvo_erel_Q_e(1, 1, SB_DLVO_EREL_STATIONARY, 7,
                                        &r), SB_EDOM);
      break;
    case 3: ck_assert(isnan(sb_dlvo_erel_logQ(1, NAN, bad, 3))); break;
    case 4: ck_assert(isnan(sb_dlvo_erel_pdf(1, 0, SB_DLVO_EREL_STATIONARY,
                                             3))); break;
    default:
      ck_assert_int_eq(sb_dlvo_erel_P_e(NAN, 1, SB_DLVO_EREL_STATIONARY, 3,
                                        &r), SB_EDOM);
    }
    ck_assert_msg(!strncmp(sb_last_error(), names[k], strlen(names[k])),
                  "call %d: %s", k, sb_last_error());
  }
  /* and the potentials' shared helpers (derjaguin, lsa, hhf, total) */
  sb_clear_error();
  ck_assert(isnan(sb_dlvo_edl_hhf(-1, 1e-6, 1e-6, 1e8, 78, 0.01, 0.01)));
  ck_assert_msg(!strncmp(sb_last_error(), "sb_dlvo_edl_hhf:", 16), "%s",
                sb_last_error());
  sb_dlvo_pair p = mk(0, 0, 1e-6, 1e-6, 1e-20, 1, 1e8, 0.01, 0.01, 4e-10);
  sb_clear_error();
  ck_assert(isnan(sb_dlvo_force(&p, -1)));
  ck_assert_msg(!strncmp(sb_last_error(), "sb_dlvo_force:", 14), "%s",
                sb_last_error());
}
END_TEST

START_TEST(test_bad_input)
{
  sb_result res;
  const double v[3] = {0, 0, 0};
  ck_assert(isnan(sb_dlvo_vdw_hamaker(1e-20, -1e-7, 1e-7, 1e-9)));
  ck_assert_int_eq(sb_last_status(), SB_EDOM);
  ck_assert(strlen(sb_last_error()) > 0);
  ck_assert(isnan(sb_dlvo_vdw_hamaker(1e-20, 1e-7, 1e-7, 0)));
  ck_assert(isnan(sb_dlvo_vdw_hamaker(NAN, 1e-7, 1e-7, 1e-9)));
  ck_assert(isnan(sb_dlvo_vdw_derjaguin_force(1e-20, 1e-7, NAN, 1e-9)));
  ck_assert(isnan(sb_dlvo_vdw_hamaker_force(1e-20, INFINITY, 1e-7, 1e-9)));
  ck_assert_int_eq(sb_dlvo_vdw_hamaker_e(1e-20, 1e-7, 1e-7, -1, &res),
                   SB_EDOM);
  ck_assert(isnan(res.val));
  ck_assert(isnan(sb_dlvo_edl_lsa(1e-9, 1e-7, 1e-7, 0, 78, 300, 1, .1, .1)));
  ck_assert(isnan(sb_dlvo_edl_lsa(1e-9, 1e-7, 1e-7, 1e8, 78, 300, 0, .1, .1)));
  ck_assert(isnan(sb_dlvo_edl_hhf(1e-9, 1e-7, 1e-7, 1e8, 78, NAN, .1)));
  ck_assert(isnan(sb_dlvo_edl_hhf_force(INFINITY, 1e-7, 1e-7, 1e8, 78, .1,
                                        .1)));
  ck_assert(isnan(sb_dlvo_debye_kappa(0, 1, 78, 300)));
  sb_dlvo_pair p = mk(0, 0, 1e-7, 1e-7, 1e-20, 1, 1e8, .03, .03, 2e-10);
  sb_dlvo_barrier_t b;
  ck_assert(isnan(sb_dlvo_energy(NULL, 1e-9)));
  ck_assert(isnan(sb_dlvo_energy(&p, -1e-9)));
  p.vdw = (sb_dlvo_vdw_model)7;
  ck_assert_int_eq(sb_dlvo_energy_e(&p, 1e-9, &res), SB_EDOM);
  ck_assert(isnan(res.val));
  p.vdw = SB_DLVO_VDW_DERJAGUIN;
  p.d_contact = 0;
  ck_assert_int_eq(sb_dlvo_barrier(&p, &b), SB_EDOM);
  p.d_contact = 2e-10;
  p.A = -1e-20;
  ck_assert_int_eq(sb_dlvo_barrier(&p, &b), SB_EDOM);
  ck_assert_int_eq(sb_dlvo_barrier(NULL, &b), SB_EDOM);
  p.A = 1e-20;
  ck_assert_int_eq(sb_dlvo_barrier(&p, NULL), SB_EDOM);
  ck_assert(isnan(sb_dlvo_erel(0, 1, v, v)));
  ck_assert(isnan(sb_dlvo_erel(1, 1, v, NULL)));
  ck_assert(isnan(sb_dlvo_erel_normal(1, 1, v, v, v)));
  ck_assert(isnan(sb_dlvo_erel_Q(-1, 1, SB_DLVO_EREL_STATIONARY, 3)));
  ck_assert(isnan(sb_dlvo_erel_P(1, 0, SB_DLVO_EREL_STATIONARY, 3)));
  ck_assert(isnan(sb_dlvo_erel_P(1, 1, SB_DLVO_EREL_STATIONARY, 4)));
  ck_assert(isnan(sb_dlvo_erel_pdf(1, 1, (sb_dlvo_erel_law)9, 3)));
  ck_assert(isnan(sb_dlvo_erel_logQ(NAN, 1, SB_DLVO_EREL_STATIONARY, 3)));
  ck_assert(isnan(sb_dlvo_erel_sample(NULL, 1, SB_DLVO_EREL_STATIONARY, 3)));
  ck_assert_int_eq(sb_last_status(), SB_EDOM);
  /* limits that are not errors */
  ck_assert(sb_dlvo_erel_Q(INFINITY, 1, SB_DLVO_EREL_COLLISION, 3) == 0);
  ck_assert(sb_dlvo_erel_P(0, 1, SB_DLVO_EREL_COLLISION, 3) == 0);
  ck_assert(sb_dlvo_erel_Q(0, 1, SB_DLVO_EREL_COLLISION, 3) == 1);
  ck_assert(isfinite(sb_dlvo_vdw_hamaker(1e-20, 1e-7, 1e-7, 1e300)));
  ck_assert(isfinite(sb_dlvo_edl_hhf(1e300, 1e-7, 1e-7, 1e8, 78, .1, .2)));
  ck_assert(sb_dlvo_erel_Q(1e6, 1, SB_DLVO_EREL_STATIONARY, 3) == 0);
}
END_TEST

static void gsl_handler(const char *reason, const char *file, int line,
                        int gsl_errno)
{
  ck_abort_msg("GSL error handler called: %s (%s:%d, %d)", reason, file,
               line, gsl_errno);
}

static Suite *suite(void)
{
  Suite *s = suite_create("dlvo");
  TCase *t = tcase_create("potentials");
  tcase_add_test(t, test_vdw_ref);
  tcase_add_test(t, test_vdw_limits);
  tcase_add_test(t, test_edl_ref);
  tcase_add_test(t, test_lsa_vs_hhf);
  tcase_add_test(t, test_debye);
  tcase_add_test(t, test_force_fd);
  tcase_add_test(t, test_sign_changes);
  tcase_add_test(t, test_bad_input);
  tcase_add_test(t, test_extreme_arguments);
  tcase_add_test(t, test_error_names);
  suite_add_tcase(s, t);
  t = tcase_create("barrier");
  tcase_set_timeout(t, 30);
  tcase_add_test(t, test_barrier_lambert);
  tcase_add_test(t, test_barrier_ref);
  tcase_add_test(t, test_barrier_scan);
  tcase_add_test(t, test_barrier_tail);
  suite_add_tcase(s, t);
  t = tcase_create("erel");
  tcase_set_timeout(t, 30);
  tcase_add_test(t, test_erel_values);
  tcase_add_test(t, test_erel_P_err);
  tcase_add_test(t, test_erel_ref);
  tcase_add_test(t, test_erel_extreme);
  tcase_add_test(t, test_erel_quad);
  tcase_add_test(t, test_erel_mc);
  tcase_add_test(t, test_erel_sample);
  suite_add_tcase(s, t);
  return s;
}

int main(void)
{
  gsl_set_error_handler(gsl_handler);
  return sbt_run_suite(suite());
}
