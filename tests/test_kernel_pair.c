/* test_kernel_pair.c — the steady rate of a pair whose diffusivity grows
 * with separation (sb_kernel_diffusion_r2, sb_kernel_brownian_turb_r2):
 * GSL quadrature of the flux integral 4 pi / int ds/(s^2 kappa(s)), the
 * Smoluchowski and pure-r^2 limits, continuity across the series switch,
 * Brownian + turbulent composition, domain errors.  The Monte Carlo check
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

static Suite *kernel_pair_suite(void)
{
  Suite *s = suite_create("kernel_pair");
  TCase *tc = tcase_create("core");
  tcase_add_test(tc, test_quadrature);
  tcase_add_test(tc, test_limits);
  tcase_add_test(tc, test_brownian_turb);
  tcase_add_test(tc, test_domain);
  suite_add_tcase(s, tc);
  return s;
}

int main(void)
{
  gsl_set_error_handler_off();
  return sbt_run_suite(kernel_pair_suite());
}
