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
#include "common/numutil.h"
#include "kernel_internal.h"

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

/* 2 pi b R / d for b, R > 0 and d = O(1) (a ratio of g or of the Brownian
 * asymptote): the plain double operations where b, R and the products
 * 2 pi b, 2 pi b R are normal doubles (ordinary arguments: the bits are
 * those of the plain formula), else the same operations with an extended
 * exponent (numutil.h), so that a product that over/underflows (b2 near
 * DBL_MAX, R near 1e-320) does not matter where K itself is a double.
 * NaN and SB_ERANGE (for func) where K exceeds DBL_MAX. */
static double two_pi_bR_over(sbi_xd b, sbi_xd R, double d, const char *func)
{
  const double bd = sbi_xd_val(b), Rd = sbi_xd_val(R);
  const double p = 2.0 * M_PI * bd, q = p * Rd, K = q / d;
  if (isnormal(bd) && isnormal(Rd) && isnormal(p) && isnormal(q) &&
      isfinite(K))
    return K;
  const double Kx = sbi_xd_val(sbi_xd_div(
      sbi_xd_mul(sbi_xd_mul(sbi_xd_of(2.0 * M_PI), b), R), sbi_xd_of(d)));
  if (!isfinite(Kx)) {
    sbi_error(SB_ERANGE, func, "the rate overflows (R = %g, b2 = %g)", Rd,
              bd);
    return NAN;
  }
  return Kx;
}

/* The closed form for R > 0, b2_0, b2_2 >= 0 not both 0, given with an
 * extended exponent.  t = sqrt(b2_0/b2_2) is formed in sbi_xd too (the
 * same bits as the plain quotient and root where it is normal); as a
 * double it may overflow (t = inf: the Brownian branch, exact there) or
 * underflow (the series, g = 1/3). */
static double dr2(sbi_xd R, sbi_xd b2_0, sbi_xd b2_2, const char *func)
{
  if (b2_2.m == 0.0)
    return two_pi_bR_over(b2_0, R, 1.0, func);
  const double t = sbi_xd_val(sbi_xd_sqrt(sbi_xd_div(b2_0, b2_2)));
  if (t > 1e6) /* g = 1/t^2 - pi/(2 t^3) + O(t^-4): Brownian limit */
    return two_pi_bR_over(b2_0, R, 1.0 - M_PI / (2.0 * t) + 1.0 / (t * t),
                          func);
  return two_pi_bR_over(b2_2, R, g_of_t(t), func);
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
  return dr2(sbi_xd_of(R), sbi_xd_of(b2_0), sbi_xd_of(b2_2), __func__);
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
  /* b2_0 and b2_2 with an extended exponent (the bits of sb_brownian_b2
   * and sb_turb_pair_b2 where those are normal): one of them may leave
   * the double range where K does not (T = 1e300 with r = 1e-300), and
   * an error is reported for this function, not for a helper. */
  const sbi_xd R = sbi_xd_add(sbi_xd_of(r_i), sbi_xd_of(r_j));
  return dr2(R, sbi_xd_add(sbi_kernel_b2_brownian(r_i, T, mu),
                           sbi_kernel_b2_brownian(r_j, T, mu)),
             sbi_kernel_b2_turb(R, eps, nu), __func__);
}
