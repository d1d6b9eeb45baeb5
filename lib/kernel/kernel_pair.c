/* kernel_pair.c — steady collision rate of a pair whose relative
 * diffusivity grows with separation (SI units).
 *
 * Derivation (docs/kernel.md, "Separation-dependent pair diffusivity"):
 * the relative position diffuses isotropically with per-component
 * variance rate b2(r), i.e. diffusion coefficient kappa = b2/2 in
 * dc/dt = div(kappa grad c) (uniform pairs are stationary without
 * collisions).  With c(R) = 0 and c -> n far away the steady radial flux
 * 4 pi r^2 kappa c' is the same through every sphere, so
 *   K = 4 pi / int_R^inf ds / (s^2 kappa(s)).
 * For b2(s) = b2_0 + b2_2 (s/R)^2, with t^2 = b2_0/b2_2,
 *   int_R^inf 2 ds/(s^2 (b2_0 + b2_2 s^2/R^2)) = 2 g(t)/(b2_2 R),
 *   g(t) = (t - atan t)/t^3,
 * and K = 2 pi b2_2 R / g(t).  g(0) = 1/3 (pure r^2: K = 6 pi b2_2 R,
 * three times the rate at the contact value 2 pi b2_2 R) and g ~ 1/t^2
 * for t -> inf (Smoluchowski, 2 pi b2_0 R).
 */
#include <math.h>

#include <gsl/gsl_math.h> /* M_PI under -std=c11 */

#include <smolbridge/kernel.h>

#include "common/internal.h"

static int pos(double x) { return isfinite(x) && x > 0.0; }
static int nonneg(double x) { return isfinite(x) && x >= 0.0; }

/* g(t) = (t - atan t)/t^3 for t >= 0, without the cancellation of the
 * difference at small t (series 1/3 - t^2/5 + t^4/7 - ..., |t| <= 0.4:
 * 40 terms reach 1e-17) */
static double g_of_t(double t)
{
  if (t <= 0.4) {
    double t2 = t * t, term = 1.0, sum = 0.0;
    for (int k = 0; k < 40; k++) {
      sum += term / (2.0 * k + 3.0);
      term *= -t2;
    }
    return sum;
  }
  return (t - atan(t)) / (t * t * t);
}

double sb_kernel_diffusion_r2(double R, double b2_0, double b2_2)
{
  if (!pos(R) || !nonneg(b2_0) || !nonneg(b2_2) ||
      !(b2_0 > 0.0 || b2_2 > 0.0)) {
    sbi_error(SB_EDOM, __func__,
              "need R > 0, b2_0 >= 0, b2_2 >= 0, not both 0 (got %g, %g, "
              "%g)", R, b2_0, b2_2);
    return NAN;
  }
  if (b2_2 == 0.0)
    return 2.0 * M_PI * b2_0 * R;
  double t = sqrt(b2_0 / b2_2);
  if (t > 1e6) /* g = 1/t^2 - pi/(2 t^3) + O(t^-4): Brownian limit */
    return 2.0 * M_PI * b2_0 * R / (1.0 - M_PI / (2.0 * t) + 1.0 / (t * t));
  return 2.0 * M_PI * b2_2 * R / g_of_t(t);
}

double sb_kernel_brownian_turb_r2(double r_i, double r_j, double T,
                                  double mu, double eps, double nu)
{
  if (!pos(r_i) || !pos(r_j) || !pos(T) || !pos(mu) || !nonneg(eps) ||
      !pos(nu)) {
    sbi_error(SB_EDOM, __func__,
              "need radii, T, mu, nu > 0 and eps >= 0 (got %g, %g, %g, %g, "
              "%g, %g)", r_i, r_j, T, mu, eps, nu);
    return NAN;
  }
  double R = r_i + r_j;
  return sb_kernel_diffusion_r2(R, sb_brownian_b2(r_i, T, mu) +
                                       sb_brownian_b2(r_j, T, mu),
                                sb_turb_pair_b2(R, eps, nu));
}
