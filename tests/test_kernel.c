/* test_kernel.c — collision kernels: monodisperse limits, symmetry, SI spot
 * values (hand-computed with mpmath, 40 digits, constants in the comments),
 * transition-regime limits, Saffman–Turner from the pair diffusivity, the
 * Abrahamson flux against quadrature of the Maxwell speed density, the
 * pass-through kernel of Langevin spheres in shear against 30-digit
 * quadratures. */
#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <gsl/gsl_math.h>
#include <smolbridge/kernel.h>

#include "refdata.h"
#include "sweep.h"
#include "testutil.h"

static const double kB = 1.380649e-23;
#define T20 293.15
#define MUW 1.002e-3

/* kernels with the signature (r_i, r_j) fixed, for symmetry checks */
static double k_all(int which, double ri, double rj)
{
  switch (which) {
  case 0: return sb_kernel_brownian_co(ri, rj, T20, MUW);
  case 1: return sb_kernel_brownian_fm(ri, rj, T20, 2000.0);
  case 2: return sb_kernel_brownian_tr(ri, rj, T20, 1.8e-5, 2000.0, 6.7e-8);
  case 3: return sb_kernel_gravity(ri, rj, 2700.0, 998.2, MUW, 9.81);
  case 4: return sb_kernel_shear(ri, rj, 10.0);
  case 5: return sb_kernel_saffman_turner(ri, rj, 1e-4, 1e-6);
  case 6: return sb_kernel_abrahamson(ri, rj, 0.01, 0.01);
  case 7: return sb_kernel_diffusion(ri, rj, 1e-12, 1e-12);
  case 8: return sb_kernel_brownian_turb(ri, rj, T20, MUW, 1e-4, 1e-6);
  default: return sb_kernel_kinetic(2 * ri, 2 * rj, 1e-25, 2e-25, T20);
  }
}

START_TEST(test_monodisperse_limits)
{
  /* Mohaupt 2011, eq 2.11: 8kT/(3 mu); eq 2.12: 4 sqrt(6 kT d/rho_p) */
  for (double r = 1e-9; r < 1e-4; r *= 7.3) {
    ck_assert_rel(sb_kernel_brownian_co(r, r, T20, MUW),
                  8 * kB * T20 / (3 * MUW), TOL_TIGHT);
    ck_assert_rel(sb_kernel_brownian_fm(r, r, T20, 2000.0),
                  4 * sqrt(6 * kB * T20 * 2 * r / 2000.0), TOL_TIGHT);
    /* kinetic theory, monodisperse: pi d^2 sqrt(16 kT/(pi m)) */
    ck_assert_rel(sb_kernel_kinetic(2 * r, 2 * r, 3e-26, 3e-26, T20),
                  M_PI * 4 * r * r * sqrt(16 * kB * T20 / (M_PI * 3e-26)),
                  TOL_TIGHT);
    /* pure diffusion: 4 pi B_pos^2 d */
    ck_assert_rel(sb_kernel_diffusion(r, r, 2e-12, 2e-12),
                  4 * M_PI * 2e-12 * 2 * r, TOL_TIGHT);
  }
  /* equal radii: no differential settling */
  ck_assert(sb_kernel_gravity(1e-6, 1e-6, 2700, 1000, MUW, 9.81) == 0.0);
}
END_TEST

START_TEST(test_symmetry)
{
  for (int w = 0; w < 10; w++)
    for (double ri = 3e-9; ri < 1e-4; ri *= 5.1)
      for (double rj = 1e-9; rj < 1e-4; rj *= 3.7) {
        double a = k_all(w, ri, rj), b = k_all(w, rj, ri);
        ck_assert_msg(isfinite(a) && a >= 0, "kernel %d not finite", w);
        ck_assert_rel(a, b, TOL_TIGHT);
      }
}
END_TEST

START_TEST(test_spot_values)
{
  /* Values from mpmath at 40 digits (k_B = 1.380649e-23 exact). */
  ck_assert_rel(sb_kernel_brownian_co(1e-6, 1e-6, T20, MUW),
                1.0771450548236859614e-17, TOL_TIGHT);
  ck_assert_rel(sb_kernel_brownian_fm(5e-8, 5e-8, T20, 2000.0),
                4.4076510988053489532e-15, TOL_TIGHT);
  ck_assert_rel(sb_kernel_brownian_co(1e-6, 3e-6, T20, MUW),
                1.4361934064315812819e-17, TOL_TIGHT);
  ck_assert_rel(sb_kernel_saffman_turner(1e-6, 3e-6, 1e-4, 1e-6),
                8.2842705602376501506e-16, TOL_TIGHT);
  ck_assert_rel(sb_kernel_shear(1e-6, 3e-6, 10.0), 8.5333333333333333333e-16,
                TOL_TIGHT);
  ck_assert_rel(sb_kernel_gravity(1e-6, 3e-6, 2700.0, 998.2, MUW, 9.80665),
                1.4883627834259495342e-15, TOL_TIGHT);
  /* argon, d = 3.6e-10 m, m = 39.948 u (u = 1.66053906660e-27 kg) */
  double m = 39.948 * 1.66053906660e-27;
  ck_assert_rel(sb_kernel_kinetic(3.6e-10, 3.6e-10, m, m, T20),
                2.2696267971782225506e-16, TOL_TIGHT);
  ck_assert_rel(sb_kernel_abrahamson(1e-6, 3e-6, 0.01, 0.04),
                1.7935971892473371838e-11, TOL_TIGHT);
  /* test kernels */
  ck_assert(sb_kernel_constant(2, 5, 3) == 3);
  ck_assert(sb_kernel_additive(2, 5, 3) == 21);
  ck_assert(sb_kernel_multiplicative(2, 5, 3) == 30);
}
END_TEST

/* Gopalakrishnan & Hogan (2011) transition kernel: H against a 40-digit
 * mpmath evaluation of the fit (including Kn = 1e60 and 1e120, where the
 * polynomials would overflow), both limits for unequal Langevin spheres,
 * the first-order continuum coefficient, symmetry and domain errors. */
START_TEST(test_gopalakrishnan_hogan)
{
  static const double kn[] = {1e-6, 0.01, 0.28, 0.55, 1, 3, 10, 1e3,
                              1e60, 1e120};
  static const double want[] = {
      1.2566352442958505224e-11, 0.001238747028610448409,
      0.67973136903989217568, 1.8992434090529458277,
      4.1269407515326935185, 14.147017131550644183,
      49.224843066346163804, 5012.3366534941810628,
      5.0132565492620010048e+60, 5.0132565492620010048e+120};
  for (size_t i = 0; i < sizeof kn / sizeof kn[0]; i++)
    ck_assert_rel(sb_kernel_gh_H(kn[i]), want[i], 32 * DBL_EPSILON);
  ck_assert(sb_kernel_gh_H(0.0) == 0.0);
  ck_assert(isnan(sb_kernel_gh_H(-1.0)));

  /* unequal spheres: 20 nm and 200 nm-like parameters, scaled so that
   * Kn_D sweeps the limits by the temperature */
  const double ri = 1e-8, rj = 1e-7, mi = 4e-21, mj = 4e-18;
  const double ti = 4e-9, tj = 3e-7;
  double fi = mi / ti, fj = mj / tj, fr = fi * fj / (fi + fj);
  double mr = mi * mj / (mi + mj), R = ri + rj;
  /* continuum: 4 pi (D_i + D_j) R with D = kT/f; relative deviation
   * -1.446 Kn_D to first order */
  double T = 1e-12;  /* tiny kT: tiny Kn_D */
  double k0 = sb_kernel_brownian_gh_kn(ri, rj, mi, mj, ti, tj, T);
  ck_assert_rel(k0, sqrt(kB * T * mr) / (fr * R), 1e-15);
  double kco = 4 * M_PI * R * (kB * T / fi + kB * T / fj);
  ck_assert_rel(sb_kernel_brownian_gh(ri, rj, mi, mj, ti, tj, T), kco,
                2.0 * k0);
  /* first-order coefficient: 25.836/(4 pi) - 3.502 = -1.4460 */
  double T2 = 1e-5;
  double k2 = sb_kernel_brownian_gh_kn(ri, rj, mi, mj, ti, tj, T2);
  double kco2 = 4 * M_PI * R * (kB * T2 / fi + kB * T2 / fj);
  double slope = (sb_kernel_brownian_gh(ri, rj, mi, mj, ti, tj, T2) / kco2 -
                  1.0) / k2;
  ck_assert_msg(k2 < 1e-3 && fabs(slope + 1.44607) < 0.01,
                "Kn = %g, slope %g", k2, slope);
  /* free molecular: pi R^2 sqrt(8 kT/(pi m_red)), deviation ~ 1/Kn_D */
  double T3 = 1e20;
  double k3 = sb_kernel_brownian_gh_kn(ri, rj, mi, mj, ti, tj, T3);
  ck_assert(k3 > 1e6);
  ck_assert_rel(sb_kernel_brownian_gh(ri, rj, mi, mj, ti, tj, T3),
                M_PI * R * R * sqrt(8 * kB * T3 / (M_PI * mr)), 2.0 / k3);
  /* symmetric in the two particles */
  ck_assert(sb_kernel_brownian_gh(ri, rj, mi, mj, ti, tj, 300) ==
            sb_kernel_brownian_gh(rj, ri, mj, mi, tj, ti, 300));
  ck_assert(isnan(sb_kernel_brownian_gh(ri, rj, mi, mj, 0.0, tj, 300)));
  ck_assert(isnan(sb_kernel_brownian_gh(ri, rj, mi, NAN, ti, tj, 300)));
}
END_TEST

START_TEST(test_transition_limits)
{
  /* Air at 20 C: mu = 1.81e-5, lambda = 67.3 nm (Mohaupt 2011,
   * §2.2.4). */
  const double mu = 1.81e-5, rho = 1000.0, lam = 6.73e-8;
  for (int slip = 0; slip < 2; slip++) {
    double l = slip ? lam : 0.0;
    /* small particles: free-molecular limit (Kn_D ~ r^-1/2 without slip,
     * ~ r^-3/2 with it); relative deviation ~ 1/(2 Kn_D^2) */
    double rs = slip ? 1e-11 : 1e-16;
    ck_assert_rel(sb_kernel_brownian_tr(rs, 1.3 * rs, T20, mu, rho, l),
                  sb_kernel_brownian_fm(rs, 1.3 * rs, T20, rho), 1e-3);
    /* large particles: continuum limit */
    double rl = 1e-2;
    double kco = slip ? NAN : sb_kernel_brownian_co(rl, 2 * rl, T20, mu);
    if (!slip)
      ck_assert_rel(sb_kernel_brownian_tr(rl, 2 * rl, T20, mu, rho, l), kco,
                    1e-3);
    /* everywhere below both limits (harmonic-like interpolation) */
    for (double r = 1e-10; r < 1e-4; r *= 1.9) {
      double tr = sb_kernel_brownian_tr(r, 2 * r, T20, mu, rho, l);
      ck_assert(tr <= sb_kernel_brownian_fm(r, 2 * r, T20, rho) * (1 + 1e-15));
      if (!slip)
        ck_assert(tr <= sb_kernel_brownian_co(r, 2 * r, T20, mu) * (1 + 1e-15));
    }
  }
  /* With slip the continuum limit still holds for r >> lambda. */
  ck_assert_rel(sb_kernel_brownian_tr(1e-3, 1e-3, T20, mu, rho, lam),
                8 * kB * T20 / (3 * mu), 1e-3);
  /* The deviation shrinks as the limits are approached (the test above
   * must not pass by accident): at Kn_D ~ 1 it is large. */
  double mid = sb_kernel_brownian_tr(5e-8, 5e-8, T20, mu, rho, 0.0);
  ck_assert(fabs(mid / sb_kernel_brownian_fm(5e-8, 5e-8, T20, rho) - 1) > 0.05);
}
END_TEST

START_TEST(test_pair_diffusivity)
{
  /* Mohaupt 2011, eqs 6.17–6.19: K = 2 pi B_ij^2(r) r, r = r_i + r_j, is
   * exactly Saffman–Turner; eq 6.16 total strain sqrt(270/pi) gives
   * B^2 = (1/3)(tau_S Gamma) Gamma r^2/15. */
  for (double ri = 1e-8; ri < 1e-4; ri *= 4.3) {
    double rj = 0.37 * ri, r = ri + rj, eps = 1e-3, nu = 1e-6;
    double b2 = sb_turb_pair_b2(r, eps, nu);
    ck_assert_rel(b2, sqrt(270 / M_PI) * sqrt(eps / nu) * r * r / 45.0,
                  TOL_TIGHT);
    ck_assert_rel(2 * M_PI * b2 * r, sb_kernel_saffman_turner(ri, rj, eps, nu),
                  TOL_TIGHT);
    /* Brownian diffusion in the same form gives the continuum kernel */
    double bi = sb_brownian_b2(ri, T20, MUW), bj = sb_brownian_b2(rj, T20, MUW);
    ck_assert_rel(sb_kernel_diffusion(ri, rj, bi, bj),
                  sb_kernel_brownian_co(ri, rj, T20, MUW), TOL_TIGHT);
    /* combined = sum of kernels (Mohaupt 2011, §6.4) */
    ck_assert_rel(sb_kernel_brownian_turb(ri, rj, T20, MUW, eps, nu),
                  sb_kernel_brownian_co(ri, rj, T20, MUW) +
                      sb_kernel_saffman_turner(ri, rj, eps, nu),
                  TOL_TIGHT);
  }
  /* Mohaupt 2011, eq 6.22: per-particle turbulent term sqrt(eps/(30 pi nu))
   * d^2 is half the pair value at r = d */
  double d = 1e-6;
  ck_assert_rel(0.5 * sb_turb_pair_b2(d, 1e-4, 1e-6),
                sqrt(1e-4 / (30 * M_PI * 1e-6)) * d * d, TOL_TIGHT);
}
END_TEST

/* Maxwell speed density with per-component variance s2, times w */
static double w_maxwell(double w, void *p)
{
  double s2 = *(double *)p;
  return w * 4 * M_PI * w * w * pow(2 * M_PI * s2, -1.5) *
         exp(-w * w / (2 * s2));
}

START_TEST(test_abrahamson_flux)
{
  /* K = pi r^2 E|w| with E|w| from quadrature of the Maxwell density of the
   * relative velocity (per-component variance u2_i + u2_j). */
  double u2i = 0.013, u2j = 0.029, s2 = u2i + u2j, ri = 2e-6, rj = 5e-6;
  gsl_integration_workspace *w = gsl_integration_workspace_alloc(200);
  gsl_function f = {w_maxwell, &s2};
  double mean, err;
  gsl_integration_qagiu(&f, 0.0, 0.0, 1e-13, 200, w, &mean, &err);
  gsl_integration_workspace_free(w);
  double r = ri + rj;
  ck_assert_rel(sb_kernel_abrahamson(ri, rj, u2i, u2j), M_PI * r * r * mean,
                1e-12);
  /* the energy form of Mohaupt (2011) eq 2.7 with the square root
   * restored */
  double Ei = 1.5 * u2i, Ej = 1.5 * u2j;
  ck_assert_rel(sb_kernel_abrahamson(ri, rj, u2i, u2j),
                sqrt(32 * M_PI / 3) * sqrt((Ei + Ej) / 2) * r * r, TOL_TIGHT);
  /* with u2 = kT/m it is the kinetic-theory kernel */
  double mi = 3e-25, mj = 7e-25;
  ck_assert_rel(sb_kernel_abrahamson(ri, rj, kB * T20 / mi, kB * T20 / mj),
                sb_kernel_kinetic(2 * ri, 2 * rj, mi, mj, T20), TOL_TIGHT);
}
END_TEST

/* |v| times the 2-D Gaussian density of the relative velocity (variance
 * 1 per component), on a line vy = const: the inner integral */
static double speed_x(double vx, void *p)
{
  const double vy = *(const double *)p;
  return hypot(vx, vy) * exp(-0.5 * (vx * vx + vy * vy)) / (2 * M_PI);
}

static double speed_xy(double vy, void *p)
{
  gsl_integration_workspace *w = p;
  gsl_function f = {speed_x, &vy};
  double r, err;
  gsl_integration_qagi(&f, 1e-14, 1e-12, 200, w, &r, &err);
  return r;
}

START_TEST(test_kinetic_2d)
{
  /* K = (d_i + d_j) E|v_rel|: the mean speed of the 2-D Gaussian by a
   * double quadrature over both Cartesian components (in units of its
   * standard deviation sqrt(kT/m_red)), not the Rayleigh mean */
  gsl_integration_workspace *wi = gsl_integration_workspace_alloc(200);
  gsl_integration_workspace *wo = gsl_integration_workspace_alloc(200);
  gsl_function f = {speed_xy, wi};
  double mean, err;
  gsl_integration_qagi(&f, 1e-13, 1e-11, 200, wo, &mean, &err);
  gsl_integration_workspace_free(wi);
  gsl_integration_workspace_free(wo);
  const double mi = 6.646e-27, mj = 2.18e-25, di = 2.8e-10, dj = 4.3e-10;
  const double sd = sqrt(kB * T20 * (1 / mi + 1 / mj));
  ck_assert_rel(sb_kernel_kinetic_2d(di, dj, mi, mj, T20), (di + dj) * sd * mean,
                1e-10);
  /* monodisperse: 2 d sqrt(pi kT/m) */
  ck_assert_rel(sb_kernel_kinetic_2d(di, di, mi, mi, T20),
                2 * di * sqrt(M_PI * kB * T20 / mi), TOL_TIGHT);
  sb_clear_error();
  ck_assert(isnan(sb_kernel_kinetic_2d(di, dj, mi, mj, 0)));
  ck_assert_int_eq(sb_last_status(), SB_EDOM);
  ck_assert(isnan(sb_kernel_kinetic_2d(-di, dj, mi, mj, T20)));
  ck_assert(isnan(sb_kernel_kinetic_2d(di, dj, NAN, mj, T20)));
}
END_TEST

START_TEST(test_domain_errors)
{
  sb_clear_error();
  ck_assert(isnan(sb_kernel_brownian_co(-1e-6, 1e-6, T20, MUW)));
  ck_assert_int_eq(sb_last_status(), SB_EDOM);
  sb_clear_error();
  ck_assert(isnan(sb_kernel_brownian_fm(1e-6, NAN, T20, 1000)));
  ck_assert_int_eq(sb_last_status(), SB_EDOM);
  ck_assert(isnan(sb_kernel_brownian_tr(1e-6, 1e-6, T20, MUW, 1e3, -1)));
  ck_assert(isnan(sb_kernel_saffman_turner(1e-6, 1e-6, 1e-4, 0)));
  ck_assert(isnan(sb_kernel_gravity(1e-6, 1e-6, 0, 1000, MUW, 9.81)));
  ck_assert(isnan(sb_kernel_shear(1e-6, INFINITY, 1)));
  ck_assert(isnan(sb_kernel_abrahamson(1e-6, 1e-6, -1, 1)));
  ck_assert(isnan(sb_kernel_diffusion(1e-6, 1e-6, 1, NAN)));
  ck_assert(isnan(sb_kernel_kinetic(1e-10, 1e-10, 0, 1e-26, T20)));
  ck_assert(isnan(sb_turb_pair_b2(0, 1e-4, 1e-6)));
  ck_assert(isnan(sb_brownian_b2(1e-6, -T20, MUW)));
  ck_assert(isnan(sb_kernel_brownian_turb(1e-6, 1e-6, T20, MUW, -1, 1e-6)));
  ck_assert(strlen(sb_last_error()) > 0);
  /* the test kernels: volumes finite and > 0, K finite and >= 0 */
  const double bad[4] = {NAN, -1.0, 0.0, INFINITY};
  for (int b = 0; b < 4; b++)
    for (int w = 0; w < 3; w++)
      for (int arg = 0; arg < 3; arg++) {
        double a[3] = {1.0, 2.0, 3.0};
        if (arg == 2 && b == 2)
          continue; /* K = 0 is allowed */
        a[arg] = bad[b];
        sb_clear_error();
        const double v = w == 0   ? sb_kernel_constant(a[0], a[1], a[2])
                         : w == 1 ? sb_kernel_additive(a[0], a[1], a[2])
                                  : sb_kernel_multiplicative(a[0], a[1], a[2]);
        ck_assert_msg(isnan(v) && sb_last_status() == SB_EDOM,
                      "test kernel %d, argument %d = %g: %g", w, arg,
                      a[arg], v);
      }
  ck_assert(sb_kernel_multiplicative(1, 2, 0) == 0.0);
  sb_clear_error();
  ck_assert(isnan(sb_kernel_multiplicative(1e200, 1e200, 1)));
  ck_assert_int_eq(sb_last_status(), SB_ERANGE);
  ck_assert_ptr_nonnull(strstr(sb_last_error(), "sb_kernel_multiplicative"));
}
END_TEST

/* Extreme arguments (sbt_sweep_ext with +-inf: +-1e-320 ... +-DBL_MAX,
 * +-inf, NaN, 0, 2^+-995, 1e+-154, each argument in turn, the others
 * ordinary; the test kernels and the steady rates with separation-
 * dependent diffusivity too): a kernel is finite with no error
 * recorded, or NaN with the error (SB_ERANGE where the value overflows,
 * SB_EDOM outside the domain) and a message naming the kernel -- never a
 * silent inf or NaN; at the finite
 * extremes the value against mpmath.  And the
 * Gopalakrishnan-Hogan kernel at tau = 1e300 (f_red underflowing) is the
 * free-molecular pi R^2 sqrt(8 kT/(pi m_red)) (it was NaN). */
typedef double (*kfn)(const double *a);
static double k_co(const double *a)
{ return sb_kernel_brownian_co(a[0], a[1], a[2], a[3]); }
static double k_fm(const double *a)
{ return sb_kernel_brownian_fm(a[0], a[1], a[2], a[3]); }
static double k_tr(const double *a)
{ return sb_kernel_brownian_tr(a[0], a[1], a[2], a[3], a[4], a[5]); }
static double k_gh(const double *a)
{ return sb_kernel_brownian_gh(a[0], a[1], a[2], a[3], a[4], a[5], a[6]); }
static double k_ghkn(const double *a)
{ return sb_kernel_brownian_gh_kn(a[0], a[1], a[2], a[3], a[4], a[5], a[6]); }
static double k_kin(const double *a)
{ return sb_kernel_kinetic(a[0], a[1], a[2], a[3], a[4]); }
static double k_kin2(const double *a)
{ return sb_kernel_kinetic_2d(a[0], a[1], a[2], a[3], a[4]); }
static double k_grav(const double *a)
{ return sb_kernel_gravity(a[0], a[1], a[2], a[3], a[4], a[5]); }
static double k_sh(const double *a)
{ return sb_kernel_shear(a[0], a[1], a[2]); }
static double k_st(const double *a)
{ return sb_kernel_saffman_turner(a[0], a[1], a[2], a[3]); }
static double k_ab(const double *a)
{ return sb_kernel_abrahamson(a[0], a[1], a[2], a[3]); }
static double k_shl(const double *a)
{ return sb_kernel_shear_langevin(a[0], a[1], a[2], a[3], a[4]); }
static double k_dif(const double *a)
{ return sb_kernel_diffusion(a[0], a[1], a[2], a[3]); }
static double k_b2(const double *a) { return sb_brownian_b2(a[0], a[1], a[2]); }
static double k_tb2(const double *a)
{ return sb_turb_pair_b2(a[0], a[1], a[2]); }
static double k_bt(const double *a)
{ return sb_kernel_brownian_turb(a[0], a[1], a[2], a[3], a[4], a[5]); }
static double k_const(const double *a)
{ return sb_kernel_constant(a[0], a[1], a[2]); }
static double k_add(const double *a)
{ return sb_kernel_additive(a[0], a[1], a[2]); }
static double k_mult(const double *a)
{ return sb_kernel_multiplicative(a[0], a[1], a[2]); }
static double k_dr2(const double *a)
{ return sb_kernel_diffusion_r2(a[0], a[1], a[2]); }
static double k_btr2(const double *a)
{ return sb_kernel_brownian_turb_r2(a[0], a[1], a[2], a[3], a[4], a[5]); }

START_TEST(test_extreme_arguments)
{
  static const struct {
    kfn f;
    const char *nm;
    int n;
    double a[7];
  } k[] = {
      {k_co, "sb_kernel_brownian_co", 4, {1e-6, 2e-6, 300, 1e-3}},
      {k_fm, "sb_kernel_brownian_fm", 4, {1e-8, 2e-8, 300, 1000}},
      {k_tr, "sb_kernel_brownian_tr", 6,
       {1e-7, 2e-7, 300, 1.8e-5, 1000, 6.8e-8}},
      {k_gh, "sb_kernel_brownian_gh", 7,
       {1e-7, 2e-7, 4e-18, 3e-17, 1e-7, 3e-7, 300}},
      {k_ghkn, "sb_kernel_brownian_gh_kn", 7,
       {1e-7, 2e-7, 4e-18, 3e-17, 1e-7, 3e-7, 300}},
      {k_kin, "sb_kernel_kinetic", 5, {1e-9, 2e-9, 1e-25, 2e-25, 300}},
      {k_kin2, "sb_kernel_kinetic_2d", 5, {1e-9, 2e-9, 1e-25, 2e-25, 300}},
      {k_grav, "sb_kernel_gravity", 6, {1e-6, 2e-6, 2000, 1000, 1e-3, 9.81}},
      {k_sh, "sb_kernel_shear", 3, {1e-6, 2e-6, 10}},
      {k_st, "sb_kernel_saffman_turner", 4, {1e-6, 2e-6, 1e-3, 1e-6}},
      {k_ab, "sb_kernel_abrahamson", 4, {1e-6, 2e-6, 1e-4, 2e-4}},
      {k_shl, "sb_kernel_shear_langevin", 5, {1e-6, 1e-6, 1e-6, 1e-3, 100}},
      {k_dif, "sb_kernel_diffusion", 4, {1e-6, 2e-6, 1e-12, 2e-12}},
      {k_b2, "sb_brownian_b2", 3, {1e-6, 300, 1e-3}},
      {k_tb2, "sb_turb_pair_b2", 3, {1e-6, 1e-3, 1e-6}},
      {k_bt, "sb_kernel_brownian_turb", 6,
       {1e-6, 2e-6, 300, 1e-3, 1e-3, 1e-6}},
      {k_const, "sb_kernel_constant", 3, {1e-18, 2e-18, 1e-9}},
      {k_add, "sb_kernel_additive", 3, {1e-18, 2e-18, 1e-9}},
      {k_mult, "sb_kernel_multiplicative", 3, {1e-18, 2e-18, 1e-9}},
      {k_dr2, "sb_kernel_diffusion_r2", 3, {2e-6, 1e-12, 2e-12}},
      {k_btr2, "sb_kernel_brownian_turb_r2", 6,
       {1e-6, 2e-6, 300, 1e-3, 1e-3, 1e-6}},
  };
  /* sbt_sweep_ext with +-inf; the message names the kernel */
  for (size_t f = 0; f < sizeof k / sizeof k[0]; f++)
    sbt_sweep_scalar(k[f].f, k[f].a, k[f].n, 0, f, k[f].nm);
  /* the finite extremes against mpmath (tests/gen_kernel_corner_ref.py,
   * same table): the value wherever it is a normal double (also where
   * an intermediate such as 1/m, k_B T or 3 pi mu r over/underflows:
   * these were SB_ERANGE, 0 or a subnormal with lost digits), SB_ERANGE
   * where it exceeds DBL_MAX, no error where it underflows */
  sbt_table t;
  sbt_table_load("kernel_corners.csv", &t);
  const int cf = sbt_col(&t, "f"), ca = sbt_col(&t, "arg"),
            cx = sbt_col(&t, "x"), cK = sbt_col(&t, "K");
  ck_assert_int_ge(t.nrow, 280);
  for (int row = 0; row < t.nrow; row++) {
    const int f = (int)sbt_at(&t, row, cf), i = (int)sbt_at(&t, row, ca);
    const double want = sbt_at(&t, row, cK);
    double a[7];
    memcpy(a, k[f].a, sizeof a);
    a[i] = sbt_at(&t, row, cx);
    sb_clear_error();
    const double v = k[f].f(a);
    const int st = sb_last_status();
    if (isinf(want))
      ck_assert_msg(isnan(v) && st == SB_ERANGE, "kernel %d, argument %d "
                    "= %g: %g (status %d), want SB_ERANGE", f, i, a[i], v,
                    st);
    else if (want == 0.0)
      ck_assert_msg(st == SB_SUCCESS && v >= 0.0 && v <= DBL_MIN,
                    "kernel %d, argument %d = %g: %g (status %d), want "
                    "below DBL_MIN", f, i, a[i], v, st);
    else
      ck_assert_msg(st == SB_SUCCESS && fabs(v / want - 1.0) <= 1e-14,
                    "kernel %d, argument %d = %g: %.17g (status %d), want "
                    "%.17g", f, i, a[i], v, st, want);
  }
  sbt_table_free(&t);
  const double ri = 1e-7, rj = 2e-7, mi = 4e-18, mj = 3e-17, R = ri + rj;
  const double mr = mi * mj / (mi + mj);
  ck_assert_rel(sb_kernel_brownian_gh(ri, rj, mi, mj, 1e300, 3e-7, 300),
                M_PI * R * R * sqrt(8 * kB * 300 / (M_PI * mr)), 1e-14);
  ck_assert_rel(sb_kernel_brownian_gh(ri, rj, mi, mj, 1e300, 1e300, 300),
                M_PI * R * R * sqrt(8 * kB * 300 / (M_PI * mr)), 1e-14);
}
END_TEST

START_TEST(test_spec)
{
  sb_kernel_spec s;
  sb_kernel_type t;
  ck_assert_int_eq(sb_kernel_type_from_name("bogus", &t), SB_EINVAL);
  ck_assert_int_eq(sb_kernel_type_from_name("shear", NULL), SB_SUCCESS);
  ck_assert_int_eq(sb_kernel_spec_init(&s, SB_KERNEL_NTYPES), SB_EINVAL);
  for (int k = 0; k < SB_KERNEL_NTYPES; k++) {
    const char *name = sb_kernel_type_name((sb_kernel_type)k);
    ck_assert_ptr_nonnull(name);
    ck_assert_int_eq(sb_kernel_type_from_name(name, &t), SB_SUCCESS);
    ck_assert_int_eq((int)t, k);
    ck_assert_int_eq(sb_kernel_spec_init(&s, t), SB_SUCCESS);
    ck_assert_int_eq(sb_kernel_spec_check(&s), SB_SUCCESS);
  }
  ck_assert_int_eq(sb_kernel_spec_set(&s, "nope", 1), SB_EINVAL);
  ck_assert_int_eq(sb_kernel_spec_set(&s, "mu", -1), SB_SUCCESS);
  sb_kernel_spec_init(&s, SB_KERNEL_BROWNIAN_CO);
  sb_kernel_spec_set(&s, "mu", -1);
  ck_assert_int_eq(sb_kernel_spec_check(&s), SB_EDOM);

  /* the volume form matches the radius form */
  double vi = 4.0 / 3.0 * M_PI * 1e-18, vj = 4.0 / 3.0 * M_PI * 27e-18;
  ck_assert_rel(sb_radius_from_volume(vi), 1e-6, TOL_TIGHT);
  sb_kernel_spec_init(&s, SB_KERNEL_SAFFMAN_TURNER);
  sb_kernel_spec_set(&s, "eps", 1e-4);
  sb_kernel_spec_set(&s, "nu", 1e-6);
  ck_assert_rel(sb_kernel_spec_fn(vi, vj, &s),
                8.2842705602376501506e-16, TOL_ULPS(32));
  sb_kernel_spec_init(&s, SB_KERNEL_BROWNIAN_CO);
  ck_assert_rel(sb_kernel_spec_fn(vi, vj, &s),
                sb_kernel_brownian_co(1e-6, 3e-6, s.T, s.mu), TOL_ULPS(32));
  sb_kernel_spec_init(&s, SB_KERNEL_ADDITIVE);
  sb_kernel_spec_set(&s, "K", 2.5);
  ck_assert(sb_kernel_spec_fn(3, 4, &s) == 17.5);
  sb_kernel_spec_init(&s, SB_KERNEL_MULTIPLICATIVE);
  ck_assert(sb_kernel_spec_fn(3, 4, &s) == 12);
}
END_TEST

/* The pass-through kernel of Langevin spheres in shear against 30-digit
 * quadratures (tests/gen_kernel_shear_langevin_ref.py: Pe_k = 0.3-3,
 * G tau = 0.01-0.5, G = 0, unequal radii: 1e-14; G tau = 1e3, 1e6, where
 * the integrand's kink at n_x = 0 limits the fixed quadrature: 5e-5), its
 * limits (G = 0 is Abrahamson's kernel; u2 -> 0 the laminar (4/3) G R^3,
 * exactly at u2 = 0; G tau -> inf, R^2 sqrt(2 pi u2) G tau (1 + O(1/G tau)),
 * at G tau = 1e160 and 1e200, where (G tau)^2 overflows), SB_ERANGE where
 * K overflows, and domain. */
START_TEST(test_shear_langevin)
{
  sbt_table t;
  sbt_table_load("kernel_shear_langevin.csv", &t);
  const int c[6] = {sbt_col(&t, "r_i"), sbt_col(&t, "r_j"),
                    sbt_col(&t, "u2"), sbt_col(&t, "tau"), sbt_col(&t, "G"),
                    sbt_col(&t, "K")};
  ck_assert_int_ge(t.nrow, 8);
  for (int i = 0; i < t.nrow; i++) {
    const double K = sb_kernel_shear_langevin(
        sbt_at(&t, i, c[0]), sbt_at(&t, i, c[1]), sbt_at(&t, i, c[2]),
        sbt_at(&t, i, c[3]), sbt_at(&t, i, c[4]));
    const double ref = sbt_at(&t, i, c[5]);
    const double gt = sbt_at(&t, i, c[4]) * sbt_at(&t, i, c[3]);
    ck_assert_msg(fabs(K / ref - 1.0) <= (gt <= 1.0 ? 1e-14 : 5e-5),
                  "row %d: %.17g against %.17g", i, K, ref);
  }
  sbt_table_free(&t);
  const double Rr = 2e-6, u2 = 1e-6, gts[2][2] = {{1e160, 1.0},
                                                  {1e100, 1e100}};
  for (int k = 0; k < 2; k++) {
    const double tau = gts[k][0], G = gts[k][1];
    ck_assert_rel(sb_kernel_shear_langevin(1e-6, 1e-6, u2, tau, G),
                  Rr * Rr * sqrt(2.0 * M_PI * u2) * G * tau, 5e-5);
  }
  sb_clear_error();
  ck_assert(isnan(sb_kernel_shear_langevin(1e-6, 1e-6, u2, 1e200, 1e200)));
  ck_assert_int_eq(sb_last_status(), SB_ERANGE);
  ck_assert_rel(sb_kernel_shear_langevin(1e-6, 3e-6, 0.02, 1e-4, 0.0),
                sb_kernel_abrahamson(1e-6, 3e-6, 0.02, 0.02), 1e-14);
  ck_assert(sb_kernel_shear_langevin(1e-6, 3e-6, 0.0, 1e-4, 50.0) ==
            sb_kernel_shear(1e-6, 3e-6, 50.0));
  const double lam = sb_kernel_shear(1e-6, 3e-6, 50.0);
  ck_assert_rel(sb_kernel_shear_langevin(1e-6, 3e-6, 1e-20, 1e-4, 50.0), lam,
                1e-3);
  ck_assert(sb_kernel_shear_langevin(1e-6, 3e-6, 0.02, 1e-4, 50.0) > lam);
  ck_assert(isnan(sb_kernel_shear_langevin(1e-6, 3e-6, -1.0, 1e-4, 50.0)));
  ck_assert(isnan(sb_kernel_shear_langevin(0.0, 3e-6, 1.0, 1e-4, 50.0)));
  ck_assert(isnan(sb_kernel_shear_langevin(1e-6, 3e-6, 1.0, NAN, 50.0)));
  ck_assert(isnan(sb_kernel_shear_langevin(1e-6, 3e-6, 1.0, 1e-4, -1.0)));
}
END_TEST

static Suite *kernel_suite(void)
{
  Suite *s = suite_create("kernel");
  TCase *tc = tcase_create("core");
  tcase_add_test(tc, test_monodisperse_limits);
  tcase_add_test(tc, test_symmetry);
  tcase_add_test(tc, test_spot_values);
  tcase_add_test(tc, test_transition_limits);
  tcase_add_test(tc, test_gopalakrishnan_hogan);
  tcase_add_test(tc, test_pair_diffusivity);
  tcase_add_test(tc, test_abrahamson_flux);
  tcase_add_test(tc, test_shear_langevin);
  tcase_add_test(tc, test_kinetic_2d);
  tcase_add_test(tc, test_domain_errors);
  tcase_add_test(tc, test_spec);
  tcase_add_test(tc, test_extreme_arguments);
  suite_add_tcase(s, tc);
  return s;
}

int main(void)
{
  gsl_set_error_handler_off();
  return sbt_run_suite(kernel_suite());
}
