/* test_kernel_pair.c — the steady rate of a pair whose diffusivity grows
 * with separation (sb_kernel_diffusion_r2, sb_kernel_brownian_turb_r2):
 * GSL quadrature of the flux integral 4 pi / int ds/(s^2 kappa(s)), the
 * Smoluchowski and pure-r^2 limits, continuity across the series switch,
 * Brownian + turbulent composition, domain errors, corners with two
 * extreme arguments against mpmath.  The Monte Carlo check
 * (fine-step integration of the 3-D SDE) is validation case
 * V17/pair-diffusivity. */
#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <gsl/gsl_math.h>
#include <smolbridge/kernel.h>

#include "testutil.h"

typedef struct { double R, b0, b2; } kpar;

/* b2_2/(x^2 kappa(R x)), kappa = b2/2: the integrand in x = s/R, scaled
 * by b2_2 (or b2_0) so that it is O(1) */
static double inv_flux(double x, void *vp)
{
  const kpar *p = vp;
  double sc = p->b2 > 0 ? p->b2 : p->b0;
  return 2.0 * sc / (x * x * (p->b0 + p->b2 * x * x));
}

/* 4 pi / int_R^inf ds/(s^2 kappa) by GSL qagiu (in x = s/R), independent
 * of the closed form */
static double k_quad(double R, double b0, double b2)
{
  gsl_integration_workspace *w = gsl_integration_workspace_alloc(500);
  kpar p = {R, b0, b2};
  gsl_function F = {inv_flux, &p};
  double I = NAN, err;
  gsl_integration_qagiu(&F, 1.0, 0.0, 1e-13, 500, w, &I, &err);
  gsl_integration_workspace_free(w);
  double sc = b2 > 0 ? b2 : b0;
  return 4.0 * M_PI * R * sc / I;
}

START_TEST(test_quadrature)
{
  const double R[3] = {1.0, 2e-6, 3.7e-3};
  const double t[9] = {0.0, 1e-3, 0.1, 0.39, 0.4, 0.41, 1.0, 7.0, 300.0};
  for (int i = 0; i < 3; i++)
    for (int k = 0; k < 9; k++) {
      double b2 = 1.3e-12, b0 = t[k] * t[k] * b2;
      ck_assert_rel(sb_kernel_diffusion_r2(R[i], b0, b2),
                    k_quad(R[i], b0, b2), TOL_QUAD);
    }
}
END_TEST

START_TEST(test_limits)
{
  /* constant diffusivity: Smoluchowski 2 pi b2 R = 4 pi kappa R */
  ck_assert_rel(sb_kernel_diffusion_r2(2e-6, 3e-12, 0.0),
                2.0 * M_PI * 3e-12 * 2e-6, TOL_TIGHT);
  ck_assert_rel(sb_kernel_diffusion_r2(2e-6, 3e-12, 0.0),
                sb_kernel_diffusion(1e-6, 1e-6, 1.5e-12, 1.5e-12),
                TOL_TIGHT);
  /* pure r^2: three times the contact value */
  ck_assert_rel(sb_kernel_diffusion_r2(2e-6, 0.0, 3e-12),
                3.0 * 2.0 * M_PI * 3e-12 * 2e-6, TOL_TIGHT);
  /* Brownian dominated: K -> 2 pi b0 R (1 + pi/(2t)), t = sqrt(b0/b2) */
  double b0 = 1.0, b2 = 1e-10, tt = sqrt(b0 / b2);
  ck_assert_rel(sb_kernel_diffusion_r2(1.0, b0, b2),
                2.0 * M_PI * (1.0 + M_PI / (2.0 * tt)), 1e-9);
  ck_assert_rel(sb_kernel_diffusion_r2(1.0, 1.0, 1e-14),
                2.0 * M_PI / (1.0 - M_PI / 2e7 + 1e-14), TOL_TIGHT);
  /* continuity at the series switch t = 0.4 */
  double lo = sb_kernel_diffusion_r2(1.0, 0.16 * (1 - 1e-12), 1.0);
  double hi = sb_kernel_diffusion_r2(1.0, 0.16 * (1 + 1e-12), 1.0);
  ck_assert_rel(lo, hi, 1e-11);
  /* monotone in b0 and b2, and at least the contact value:
   * K(b0, b2) >= 2 pi (b0 + b2) R (diffusivity >= its contact value) */
  double prev = 0.0;
  for (int k = 0; k <= 20; k++) {
    double a = pow(10.0, -5.0 + 0.5 * k);
    double K = sb_kernel_diffusion_r2(1.0, 1.0, a);
    ck_assert(K > prev);
    ck_assert(K >= 2.0 * M_PI * (1.0 + a) * (1.0 - 1e-14));
    ck_assert(K <= 3.0 * 2.0 * M_PI * (1.0 + a));
    prev = K;
  }
}
END_TEST

START_TEST(test_brownian_turb)
{
  const double T = 296.15, mu = 1e-3, nu = 1e-6;
  double ri = 0.5e-6, rj = 0.8e-6, eps = 1e-4;
  double b0 = sb_brownian_b2(ri, T, mu) + sb_brownian_b2(rj, T, mu);
  double b2 = sb_turb_pair_b2(ri + rj, eps, nu);
  ck_assert_rel(sb_kernel_brownian_turb_r2(ri, rj, T, mu, eps, nu),
                k_quad(ri + rj, b0, b2), TOL_QUAD);
  /* no turbulence: the continuum Brownian kernel */
  ck_assert_rel(sb_kernel_brownian_turb_r2(ri, rj, T, mu, 0.0, nu),
                sb_kernel_brownian_co(ri, rj, T, mu), TOL_TIGHT);
  /* turbulence dominated: three times Saffman-Turner */
  double big = sb_kernel_brownian_turb_r2(5e-5, 5e-5, 1e-6, mu, 1.0, nu);
  ck_assert_rel(big, 3.0 * sb_kernel_saffman_turner(5e-5, 5e-5, 1.0, nu),
                1e-4);
  /* never below the frozen-contact kernel of Mohaupt 2011, eq 6.23 */
  ck_assert(sb_kernel_brownian_turb_r2(ri, rj, T, mu, eps, nu) >
            sb_kernel_brownian_turb(ri, rj, T, mu, eps, nu));
}
END_TEST

START_TEST(test_domain)
{
  ck_assert(isnan(sb_kernel_diffusion_r2(0.0, 1.0, 1.0)));
  ck_assert_int_eq(sb_last_status(), SB_EDOM);
  ck_assert(isnan(sb_kernel_diffusion_r2(1.0, 0.0, 0.0)));
  ck_assert(isnan(sb_kernel_diffusion_r2(1.0, -1.0, 1.0)));
  ck_assert(isnan(sb_kernel_diffusion_r2(1.0, 1.0, NAN)));
  ck_assert(isnan(sb_kernel_brownian_turb_r2(1e-6, 1e-6, 300, 1e-3, -1,
                                             1e-6)));
  ck_assert(isnan(sb_kernel_brownian_turb_r2(1e-6, 0, 300, 1e-3, 1, 1e-6)));
}
END_TEST

/* Corners where a product of the closed form leaves the double range but
 * K is a double (values: mpmath at 50 digits, the formulas of
 * tests/gen_kernel_corner_ref.py; single extreme arguments are in
 * tests/test_kernel.c, test_extreme_arguments): b2_0 = 1e-315 (2 pi b2_0
 * subnormal) with R = 1e300 was a wrong value, T = 1e300 with radii of
 * 1e-300 (b2_Brown ~ 1e579) NaN, R = 1e-320 with b2 = 1e300 the rounding
 * of a subnormal. */
START_TEST(test_extreme)
{
  static const struct { double a[6]; int turb; double K; } c[] = {
      {{1e300, 1e-315, 0.0}, 0, 6.283185297639724822e-15},
      {{1e-320, 1e300, 3e299}, 0, 1.517296543654084908e-19},
      {{1e-320, 1e300, 0.0}, 0, 6.283115357625393152e-20},
      {{1e-300, 1e-300, 1e300, 1e-3, 1e-3, 1e-6}, 1,
       3.6817306666666667833e+280},
      {{1e-300, 2e-300, 1e300, 1e-3, 0.0, 1e-6}, 1,
       4.1419470000000001313e+280},
  };
  for (size_t i = 0; i < sizeof c / sizeof c[0]; i++) {
    const double *a = c[i].a;
    sb_clear_error();
    const double K =
        c[i].turb ? sb_kernel_brownian_turb_r2(a[0], a[1], a[2], a[3], a[4],
                                               a[5])
                  : sb_kernel_diffusion_r2(a[0], a[1], a[2]);
    ck_assert_msg(sb_last_status() == SB_SUCCESS &&
                      fabs(K / c[i].K - 1.0) <= 1e-14,
                  "case %zu: %.17g (status %d), want %.17g", i, K,
                  sb_last_status(), c[i].K);
  }
  /* where K overflows: SB_ERANGE naming the function (this was SB_EDOM
   * from sb_kernel_diffusion_r2 after sb_turb_pair_b2 overflowed) */
  sb_clear_error();
  ck_assert(isnan(sb_kernel_brownian_turb_r2(1e300, 1e-6, 300, 1e-3, 1e-3,
                                             1e-6)));
  ck_assert_int_eq(sb_last_status(), SB_ERANGE);
  ck_assert_ptr_nonnull(strstr(sb_last_error(), "sb_kernel_brownian_turb_r2"));
  sb_clear_error();
  ck_assert(isnan(sb_kernel_diffusion_r2(1e300, 1e300, 1e-12)));
  ck_assert_int_eq(sb_last_status(), SB_ERANGE);
  ck_assert_ptr_nonnull(strstr(sb_last_error(), "sb_kernel_diffusion_r2"));
}
END_TEST

static Suite *kernel_pair_suite(void)
{
  Suite *s = suite_create("kernel_pair");
  TCase *tc = tcase_create("core");
  tcase_add_test(tc, test_quadrature);
  tcase_add_test(tc, test_limits);
  tcase_add_test(tc, test_brownian_turb);
  tcase_add_test(tc, test_domain);
  tcase_add_test(tc, test_extreme);
  suite_add_tcase(s, tc);
  return s;
}

int main(void)
{
  gsl_set_error_handler_off();
  return sbt_run_suite(kernel_pair_suite());
}
