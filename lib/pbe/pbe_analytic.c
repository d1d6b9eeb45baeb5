/* pbe_analytic.c — analytic solutions of the Smoluchowski equation for the
 * constant, additive and multiplicative kernels, evaluated in log space.
 *
 * Sources (each re-derived and checked in tests/test_pbe.c against the
 * moments, 40-digit mpmath vectors and the CVODE solution):
 *  - constant kernel, monodisperse: Smoluchowski (1917);
 *  - additive, monodisperse: Golovin (1963); the factor is 1/k!;
 *  - multiplicative, monodisperse, pre-gel: McLeod (1962), Ziff (1980);
 *    the factor is 1/(k-1)! with k^(k-3) (versions dividing by k! are
 *    wrong by a factor k: they violate mass conservation);
 *  - exponential start, constant and additive: Scott (1968, J. Atmos. Sci.
 *    25:54), Golovin (1963).
 */
#include <math.h>

#include <gsl/gsl_math.h>
#include <gsl/gsl_sf_bessel.h>
#include <gsl/gsl_sf_gamma.h>
#include <gsl/gsl_sf_log.h>
#include <smolbridge/pbe.h>

#include "common/internal.h"

/* k must be an integer >= 1; tau finite >= 0 */
static int bad_k(double k) { return !(k >= 1.0 && k == floor(k) && isfinite(k)); }
static int bad_tau(double tau) { return !(tau >= 0.0 && isfinite(tau)); }

/* the functions below take the public name fn for their messages (the
 * _logn and _n forms share them) */
#define DOMAIN(cond, ...)                       \
  do {                                          \
    if (cond) {                                 \
      sbi_error(SB_EDOM, fn, __VA_ARGS__);      \
      return NAN;                               \
    }                                           \
  } while (0)

static double const_mono_logn(const char *fn, double k, double tau)
{
  DOMAIN(bad_k(k), "k must be an integer >= 1 (got %g)", k);
  DOMAIN(bad_tau(tau), "tau must be finite and >= 0 (got %g)", tau);
  if (k == 1.0)
    return -2.0 * log1p(0.5 * tau);
  if (tau == 0.0)
    return -INFINITY;
  /* (k-1) log(t/(1+t)) - 2 log1p(t), t = tau/2: no terms of size k log
   * tau that cancel */
  const double r = 2.0 / tau;
  /* tau < 2/DBL_MAX (subnormal): log1p(2/tau) = log(2 + tau) - log tau,
   * log(2 + tau) = log 2 to the last bit (it was log1p(inf) = inf) */
  const double l = isinf(r) ? M_LN2 - log(tau) : log1p(r);
  return -(k - 1.0) * l - 2.0 * log1p(0.5 * tau);
}

/* rest(k) = log Gamma(k) - [(k - 1/2) log k - k] = log(2 pi)/2 +
 * log gamma*(k) (GSL's gammastar, -> 0 as k grows): the part of log Gamma
 * that does not cancel against the k log k - k of the solutions. */
static double lgamma_rest(double k)
{
  return 0.5 * log(2.0 * M_PI) + log(gsl_sf_gammastar(k));
}

static double add_mono_logn(const char *fn, double k, double tau)
{
  DOMAIN(bad_k(k), "k must be an integer >= 1 (got %g)", k);
  DOMAIN(bad_tau(tau), "tau must be finite and >= 0 (got %g)", tau);
  double phi = -expm1(-tau);
  if (k == 1.0)
    return -tau - phi;
  if (tau == 0.0)
    return -INFINITY;
  /* with lgamma(k+1) = (k + 1/2) log k - k + rest(k):
   * log n = -tau + (k-1) log phi + k q - 3/2 log k - rest(k), q = e^-tau;
   * (k-1) log phi + k q = (k-1)(log1p(-q) + q) + q (no cancellation of
   * terms ~ k q when phi ~ 1) */
  const double q = exp(-tau);
  double lk = q < 0.5 ? (k - 1.0) * gsl_sf_log_1plusx_mx(-q) + q
                      : (k - 1.0) * log(phi) + k * q;
  if (isinf(lk)) /* (k-1) log phi beyond -DBL_MAX, k q not: k ~ 1e308 at
                  * tau in ~[0.1, 0.7], log n ~ -0.2 k ... -1.5 k */
    lk = (k - 1.0) * (log(phi) + q) + q;
  return -tau + lk - 1.5 * log(k) - lgamma_rest(k);
}

static double mult_mono_logn(const char *fn, double k, double tau)
{
  DOMAIN(bad_k(k), "k must be an integer >= 1 (got %g)", k);
  DOMAIN(bad_tau(tau) || tau >= 1.0,
         "tau must be in [0, 1) (before gelation; got %g)", tau);
  if (k == 1.0)
    return -tau;
  if (tau == 0.0)
    return -INFINITY;
  /* with lgamma(k) = (k - 1/2) log k - k + rest(k):
   * log n = -5/2 log k - rest(k) + (k-1)(log tau + 1 - tau) + 1 - tau,
   * log tau + 1 - tau = log1p(x) - x at x = tau - 1 (near gelation the
   * terms ~ k cancel).  For tau < 1/16 it is formed directly: x = tau - 1
   * rounds away tau's low bits (relative error 1e-16/tau: 1e-6 at tau =
   * 1e-10), and for tau < 2^-54 it is -1, outside GSL's domain (its
   * error handler, which aborts by default) */
  const double lt = tau < 0.0625 ? log(tau) + (1.0 - tau)
                                 : gsl_sf_log_1plusx_mx(tau - 1.0);
  return -2.5 * log(k) - lgamma_rest(k) + (k - 1.0) * lt + (1.0 - tau);
}

static double const_exp_logn(const char *fn, double x, double tau)
{
  DOMAIN(!(x >= 0.0 && isfinite(x)), "x must be finite and >= 0 (got %g)", x);
  DOMAIN(bad_tau(tau), "tau must be finite and >= 0 (got %g)", tau);
  return -x / (1.0 + 0.5 * tau) - 2.0 * log1p(0.5 * tau);
}

static double add_exp_logn(const char *fn, double x, double tau)
{
  DOMAIN(!(x > 0.0 && isfinite(x)), "x must be finite and > 0 (got %g)", x);
  DOMAIN(bad_tau(tau), "tau must be finite and >= 0 (got %g)", tau);
  /* z = x (2 sqrt T): the same bits as (2 x) sqrt T, which overflowed for
   * x > DBL_MAX/2 (inf * 0 = NaN at tau = 0) */
  double T = -expm1(-tau), sT = sqrt(T), z = x * (2.0 * sT);
  /* n = e^-tau e^{-(1+T)x} I1(z)/(x sqrt T); with I1(z) = e^z I1s(z):
   * exponent -(1+T)x + z = -x (1 - sqrt T)^2, no cancellation. */
  double e = -tau - x * (1.0 - sT) * (1.0 - sT);
  if (isinf(z)) /* I1s(z) = (2 pi z)^(-1/2) (1 + O(1/z)) (Abramowitz &
                 * Stegun 1964, 9.7.1); GSL's scaled I1 gives 0 at inf */
    return e - 0.5 * (log(2.0 * M_PI) + log(x) + log(2.0 * sT)) -
           log(x * sT);
  if (z < 0.1) {
    /* I1(z)/(z/2) = sum_m (z^2/4)^m/(m!(m+1)!): 6 terms reach 1e-19 for
     * z < 0.1 (GSL's scaled I1 drops the e^-z factor at tiny z). */
    double q = 0.25 * z * z, term = 1.0, sum = 0.0;
    for (int m = 1; m <= 6; m++) {
      term *= q / ((double)m * (double)(m + 1));
      sum += term;
    }
    return e - z + log1p(sum); /* e - z = -tau - (1+T)x */
  }
  return e + log(gsl_sf_bessel_I1_scaled(z)) - log(x * sT);
}

/* log n = -inf is the value only where n = 0 (tau = 0, k > 1: all the
 * forms are finite at tau = 0 otherwise); for tau > 0 it means that log
 * n < -DBL_MAX (k or x ~ 1e308), which a double cannot hold: NaN and
 * SB_ERANGE.  n itself is then 0 (underflow, no error). */
#define EXPFORM(name)                                  \
  double sb_pbe_##name##_logn(double a, double tau)    \
  {                                                    \
    const double v = name##_logn(__func__, a, tau);    \
    if (v == -INFINITY && tau > 0.0) {                 \
      sbi_error(SB_ERANGE, __func__, "(%g, tau = %g): "  \
                "log n < -DBL_MAX", a, tau);           \
      return NAN;                                      \
    }                                                  \
    return v;                                          \
  }                                                    \
  double sb_pbe_##name##_n(double a, double tau)       \
  {                                                    \
    return exp(name##_logn(__func__, a, tau));         \
  }
EXPFORM(const_mono)
EXPFORM(add_mono)
EXPFORM(mult_mono)
EXPFORM(const_exp)
EXPFORM(add_exp)

int sb_pbe_analytic_moments(sb_pbe_kernel_kind kind, int exp_start,
                            double tau, double m[3])
{
  if (!m)
    return sbi_error(SB_EINVAL, __func__, "m is NULL");
  if (bad_tau(tau))
    return sbi_error(SB_EDOM, __func__, "tau must be finite and >= 0 (got %g)",
                     tau);
  double m20 = exp_start ? 2.0 : 1.0;
  m[1] = 1.0;
  switch (kind) {
  case SB_PBE_CONSTANT: /* dM0/dt = -K M0^2/2, dM2/dt = K M1^2 */
    m[0] = 1.0 / (1.0 + 0.5 * tau);
    m[2] = m20 + tau;
    return SB_SUCCESS;
  case SB_PBE_ADDITIVE: /* dM0/dt = -K M0 M1, dM2/dt = 2 K M1 M2 */
    m[0] = exp(-tau);
    m[2] = m20 * exp(2.0 * tau);
    if (isinf(m[2])) /* tau > ~354.9 */
      return sbi_error(SB_ERANGE, __func__, "additive kernel: M2 = %g "
                       "exp(2 tau) exceeds DBL_MAX at tau = %g", m20, tau);
    return SB_SUCCESS;
  case SB_PBE_MULTIPLICATIVE: /* dM0/dt = -K M1^2/2, dM2/dt = K M2^2 */
    if (exp_start)
      return sbi_error(SB_EINVAL, __func__,
                       "multiplicative kernel: monodisperse start only");
    if (tau >= 1.0)
      return sbi_error(SB_EDOM, __func__,
                       "multiplicative kernel: tau = %g >= 1 (gelation)", tau);
    m[0] = 1.0 - 0.5 * tau;
    m[2] = 1.0 / (1.0 - tau);
    return SB_SUCCESS;
  default:
    return sbi_error(SB_EINVAL, __func__, "unknown kernel kind %d", (int)kind);
  }
}
