/* smolbridge/passage.h — first-passage laws (unit-free).
 *
 * 1. Brownian motion with drift,  X_s = x + mu s + sqrt(sigma2) W_s,
 *    T = inf{s >= 0 : X_s = a}  (level a above or below x; T = +inf if the
 *    level is never reached).  With d = |x - a| and nu = mu sign(a - x) the
 *    drift towards the level:
 *      density  f(t) = d / sqrt(2 pi sigma2 t^3) exp(-(d - nu t)^2/(2 sigma2 t))
 *               (valid for every nu);
 *      mass     P(T < inf) = 1 if nu >= 0, exp(-2 d |nu| / sigma2) if nu < 0;
 *      law      nu > 0: inverse Gaussian IG(mean d/nu, shape d^2/sigma2);
 *               nu = 0: Levy; nu < 0: defective, mass * IG(d/|nu|, d^2/sigma2).
 *    CDF (Schroedinger 1915; Chhikara & Folks 1989, eq. 2.5), with
 *    s = sqrt(sigma2 t), c = (nu t - d)/s, b = (nu t + d)/s:
 *      P(T <= t) = Phi(c) + exp(2 nu d / sigma2) Phi(-b).
 *    It is evaluated as sums of positive terms, in the scaled form
 *    exp(2 nu d/sigma2) Phi(-b) = exp(-c^2/2) M(b), M(z) = Q(z) exp(z^2/2),
 *    and the survival function P(T > t) = exp(-c^2/2) [M(c) - M(b)] uses a
 *    cancellation-free evaluation of the difference M(c) - M(b) (a positive
 *    series when b - c = 2 d/s is small); exp(-c^2/2) is formed from
 *    (nu t - d)^2 / (2 sigma2 t) in double-double arithmetic so that values
 *    near the underflow limit keep their relative accuracy.
 *    See docs/passage.md for the derivations.
 *
 * 2. Bessel-3 process (norm of 3-D Brownian motion, per-component rate
 *    sigma2) from x down to a level 0 <= a < x.  Doob's h-transform of BM
 *    killed at 0 with h(r) = r gives, with d = x - a,
 *      density (a/x) d / sqrt(2 pi sigma2 t^3) exp(-d^2/(2 sigma2 t)),
 *      P(T <= t) = (a/x) erfc(d / sqrt(2 sigma2 t)),   total mass a/x,
 *      P(T > t)  = (x - a)/x + (a/x) erf(d / sqrt(2 sigma2 t))  (direct).
 *
 * Domain (all functions): arguments finite except t, which may be +inf
 * (then cdf = mass); sigma2 > 0; t >= 0 (t < 0 is a domain error); for
 * Bessel-3, x >= 0 and a >= 0.  If the process starts on or beyond the level
 * (x == a for BM; x <= a for Bessel-3) then T = 0: cdf = 1, sf = 0 and the
 * pdf (of the absolutely continuous part) is 0.  Bessel-3 with a = 0 never
 * reaches the level: cdf = 0, sf = 1.  A domain error returns NaN (plain
 * form) or SB_EDOM with res = {NaN, NaN} (_e form) and records a message
 * (sb_last_error()) naming the function called (the plain form, not its _e
 * form).
 *
 * Extremes: pdf, cdf, sf and mass take any finite x, a, mu, sigma2, t
 * (sigma2 t, nu t or d^2 beyond DBL_MAX included; operands are scaled by
 * powers of two where a product would leave the double range, with the
 * same bits as before elsewhere) and return the value wherever it is a
 * normal double; a density above DBL_MAX is SB_ERANGE (NaN); values below
 * DBL_MIN are 0 or subnormal without error.  The quantile and the sampler
 * work in units scaled by powers of two where d, sigma2 or |mu| is far
 * from 1: a quantile or draw above DBL_MAX is SB_ERANGE with NaN (the
 * sampler records the status for sb_last_status()); +inf with status 0
 * only for the defective law (docs/passage.md).
 *
 * Accuracy (tested against mpmath values with at least 20 correct digits,
 * tests/data/passage_*.csv):
 * relative error below 1e-13 for pdf, cdf and sf over t/mean and
 * sigma2 t/d^2 from 1e-8 to 1e8, down to values of 1e-300; the _e err is an
 * honest absolute bound (tested).  Quantiles: |cdf(q) - p| <= 1e-13 and q to
 * a few ulps (safeguarded Newton iteration in log t on log cdf or log sf).
 * The sampler is exact in distribution (Michael, Schucany & Haas 1976 for
 * the inverse Gaussian: one Gaussian and one uniform variate).
 */
#ifndef SMOLBRIDGE_PASSAGE_H
#define SMOLBRIDGE_PASSAGE_H

#include <gsl/gsl_rng.h>
#include <smolbridge/common.h>

#ifdef __cplusplus
extern "C" {
#endif

/* ------------------------------------------- Brownian motion with drift */

/** First-passage density of BM with drift at time t (see header comment). */
double sb_bm_fpt_pdf(double t, double x, double a, double mu, double sigma2);
/** P(T <= t). */
double sb_bm_fpt_cdf(double t, double x, double a, double mu, double sigma2);
/** P(T > t), T = +inf counted: 1 - cdf computed directly. */
double sb_bm_fpt_sf(double t, double x, double a, double mu, double sigma2);
/** P(T < inf): 1 if the drift points towards the level (or is 0), else
 *  exp(-2 |x - a| |mu| / sigma2). */
double sb_bm_fpt_mass(double x, double a, double mu, double sigma2);
/** log P(T < inf) = -2 |x - a| |mu| / sigma2 if the drift points away
 *  from the level, else 0: finite where the mass underflows (below
 *  ~1e-308, mass 0).  Same domain as sb_bm_fpt_mass (SB_EDOM, NaN);
 *  to about 1 ulp (the exponent is formed in double-double, scaled by
 *  powers of two where d |mu| or the quotient would leave the range,
 *  and rounded once); 0 or subnormal without error where |log mass| is
 *  below DBL_MIN; NaN with SB_ERANGE where it exceeds DBL_MAX. */
double sb_bm_fpt_logmass(double x, double a, double mu, double sigma2);
/** Smallest t with P(T <= t) >= p, for p in [0, 1]: 0 for p = 0 and +inf
 *  for p >= mass (defective law) or p = 1.  Full double precision; NaN
 *  (SB_ERANGE) where the quantile exceeds DBL_MAX. */
double sb_bm_fpt_quantile(double p, double x, double a, double mu,
                          double sigma2);
/** One exact draw of T; +inf when the path never reaches the level; NaN
 *  (SB_ERANGE recorded) if the draw exceeds DBL_MAX.
 *  Uses one Gaussian (gsl_ran_gaussian_ziggurat) and one or two uniforms
 *  (gsl_rng_uniform) per call. */
double sb_bm_fpt_sample(const gsl_rng *r, double x, double a, double mu,
                        double sigma2);

int sb_bm_fpt_pdf_e(double t, double x, double a, double mu, double sigma2,
                    sb_result *res);
int sb_bm_fpt_cdf_e(double t, double x, double a, double mu, double sigma2,
                    sb_result *res);
int sb_bm_fpt_sf_e(double t, double x, double a, double mu, double sigma2,
                   sb_result *res);
int sb_bm_fpt_mass_e(double x, double a, double mu, double sigma2,
                     sb_result *res);
int sb_bm_fpt_logmass_e(double x, double a, double mu, double sigma2,
                        sb_result *res);
/** err bounds |val - exact quantile|; returns SB_EMAXITER (with the best
 *  value found) if the iteration did not converge. */
int sb_bm_fpt_quantile_e(double p, double x, double a, double mu,
                         double sigma2, sb_result *res);

/* ----------------------------------------- Bessel-3 down to a level a < x */

/** Density of the first passage of a Bessel-3 process from x down to a
 *  (defective, total mass a/x). */
double sb_bes3_fpt_pdf(double t, double x, double a, double sigma2);
/** P(T <= t) = (a/x) erfc((x - a)/sqrt(2 sigma2 t)). */
double sb_bes3_fpt_cdf(double t, double x, double a, double sigma2);
/** P(T > t) (T = +inf counted) = 1 - cdf, computed directly. */
double sb_bes3_fpt_sf(double t, double x, double a, double sigma2);

int sb_bes3_fpt_pdf_e(double t, double x, double a, double sigma2,
                      sb_result *res);
int sb_bes3_fpt_cdf_e(double t, double x, double a, double sigma2,
                      sb_result *res);
int sb_bes3_fpt_sf_e(double t, double x, double a, double sigma2,
                     sb_result *res);

#ifdef __cplusplus
}
#endif

#endif /* SMOLBRIDGE_PASSAGE_H */
