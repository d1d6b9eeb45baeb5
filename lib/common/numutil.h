/* numutil.h — internal numerical helpers shared by passage.c, bridge.c and
 * bridge_hit.c (prefix sbi_, not exported, not installed).
 *
 * Contents
 *  - double-double ("dd") arithmetic, inline: error-free sums/products used
 *    to form Gaussian exponents such as (nu t - d)^2 / (2 sigma2 t) to about
 *    one ulp, so exp(-E) keeps full relative accuracy even when E ~ 700.
 *  - log1mexp, the scaled normal tail M(z) = Q(z) exp(z^2/2) and the
 *    cancellation-free difference M(z - h) - M(z + h).
 *  - the inverse-Gaussian kernel in normalised variables (one evaluation
 *    point = eps, kap, c = kap - eps, exp(-c^2/2)) giving the CDF, survival
 *    function and their size-biased versions as sums of positive terms.
 *  - a safeguarded Newton iteration for monotone equations (quantiles), and
 *    the Michael–Schucany–Haas inverse-Gaussian sampler.
 * See docs/passage.md for the derivations.
 */
#ifndef SB_NUMUTIL_H
#define SB_NUMUTIL_H

#include <math.h>
#include <gsl/gsl_math.h>
#include <gsl/gsl_rng.h>
#include <smolbridge/common.h>
#include "internal.h"

/* Record an error for the public function `func` (sbi_error), set *res (if
 * not NULL) to {NaN, NaN} and return `status`. */
int sbi_fail(sb_result *res, int status, const char *func, const char *fmt,
             ...) SBI_PRINTF(4, 5);

/* ------------------------------------------------- double-double kernels */

/* A value hi + lo with |lo| <= ulp(hi)/2. */
typedef struct {
  double hi, lo;
} sbi_dd;

/* Knuth's TwoSum: a + b = s.hi + s.lo exactly. */
static inline sbi_dd sbi_dd_sum(double a, double b)
{
  double s = a + b, bb = s - a;
  sbi_dd r = {s, (a - (s - bb)) + (b - bb)};
  return r;
}

/* a * b = p.hi + p.lo exactly: fma where the hardware has it, otherwise
 * Dekker's product with Veltkamp splitting (a software fma costs ~9 ns on
 * x86-64 without -mfma, this ~3 ns).  Exact unless |a| or |b| > 2^995. */
static inline sbi_dd sbi_dd_prod(double a, double b)
{
  double p = a * b;
#ifdef FP_FAST_FMA
  sbi_dd r = {p, fma(a, b, -p)};
#else
  const double split = 134217729.0; /* 2^27 + 1 */
  double ca = split * a, cb = split * b;
  double ah = ca - (ca - a), al = a - ah;
  double bh = cb - (cb - b), bl = b - bh;
  sbi_dd r = {p, ((ah * bh - p) + ah * bl + al * bh) + al * bl};
#endif
  return r;
}

/* Renormalise hi + lo (requires |hi| >= |lo| or hi == 0). */
static inline sbi_dd sbi_dd_fast(double hi, double lo)
{
  double s = hi + lo;
  sbi_dd r = {s, lo - (s - hi)};
  return r;
}

static inline sbi_dd sbi_dd_add(sbi_dd a, sbi_dd b)
{
  sbi_dd s = sbi_dd_sum(a.hi, b.hi);
  return sbi_dd_fast(s.hi, s.lo + a.lo + b.lo);
}

static inline sbi_dd sbi_dd_neg(sbi_dd a)
{
  sbi_dd r = {-a.hi, -a.lo};
  return r;
}

static inline sbi_dd sbi_dd_mul(sbi_dd a, sbi_dd b)
{
  sbi_dd p = sbi_dd_prod(a.hi, b.hi);
  return sbi_dd_fast(p.hi, p.lo + (a.hi * b.lo + a.lo * b.hi));
}

static inline sbi_dd sbi_dd_mul_d(sbi_dd a, double b)
{
  sbi_dd p = sbi_dd_prod(a.hi, b);
  return sbi_dd_fast(p.hi, p.lo + a.lo * b);
}

static inline sbi_dd sbi_dd_div(sbi_dd a, sbi_dd b)
{
  double q = a.hi / b.hi;
  /* remainder a - q b (q b.hi exactly), to first order in the lo parts */
  sbi_dd qb = sbi_dd_prod(q, b.hi);
  double r = ((a.hi - qb.hi) - qb.lo) + a.lo - q * b.lo;
  return sbi_dd_fast(q, r / b.hi);
}

/* 2 a b / v for dd a, b > 0 and v > 0, at any magnitude: the operands are
 * scaled by powers of two (exact) into [1, 2) before the dd operations,
 * whose splitting overflows above 2^995, and the result scaled back
 * (inf or 0 where it overflows or underflows). */
static inline sbi_dd sbi_dd_twice_ratio(sbi_dd a, sbi_dd b, double v)
{
  if (a.hi == 0.0 || b.hi == 0.0) {
    sbi_dd z = {0.0, 0.0};
    return z;
  }
  const double big = 0x1p240, small = 0x1p-240;  /* quotient < 2^721 */
  if (a.hi < big && b.hi < big && v < big && a.hi > small && b.hi > small &&
      v > small)  /* the usual case: no scaling needed */
    return sbi_dd_div(sbi_dd_mul_d(sbi_dd_mul(a, b), 2.0),
                      (sbi_dd){v, 0.0});
  const int ea = ilogb(a.hi), eb = ilogb(b.hi), ev = ilogb(v);
  sbi_dd as = {ldexp(a.hi, -ea), ldexp(a.lo, -ea)};
  sbi_dd bs = {ldexp(b.hi, -eb), ldexp(b.lo, -eb)};
  sbi_dd vs = {ldexp(v, -ev), 0.0};
  sbi_dd r = sbi_dd_div(sbi_dd_mul_d(sbi_dd_mul(as, bs), 2.0), vs);
  const int e = ea + eb - ev;
  sbi_dd out = {ldexp(r.hi, e), ldexp(r.lo, e)};
  if (!isfinite(out.hi))
    out.lo = 0.0;
  return out;
}

/* exp(-(e.hi + e.lo)) for e >= 0 to about one ulp. */
static inline double sbi_dd_expneg(sbi_dd e)
{
  return exp(-e.hi) * (1.0 - e.lo);
}

/* ------------------------------------------------ elementary functions */

/* log(1 - exp(-x)) for x >= 0 (Maechler 2012): -inf at x = 0. */
double sbi_log1mexp(double x);

/* M(z) = Q(z) exp(z^2/2) = erfcx(z/sqrt 2)/2, the scaled upper normal tail
 * (M(0) = 1/2, M(z) ~ 1/(z sqrt(2 pi)) for large z).  Cody's (1969)
 * rational approximations of erfcx (no exponential for z >= 0.663, one
 * exp below), and M(z) = exp(z^2/2) - M(-z) with an exactly split z^2 for
 * z < 0.  Relative error <= 4 ulp for z >= -37 (3.7 ulp in 11 000 points
 * against mpmath); overflows (+inf) below about -37.6. */
double sbi_mills(double z);

/* M(lo) - M(z + h) where lo = z - h is passed accurately by the caller;
 * requires h >= 0, z >= 0, lo >= -2.  Direct difference when it does not
 * cancel (ratio <= 0.8); otherwise the positive series
 *   2 M(z) sum_{j odd} (J_j(z)/J_0(z)) h^j / j!,
 *   J_j(z) = int_0^inf w^j exp(-z w - w^2/2) dw,
 * with J_j/J_{j-1} from the forward recurrence (z <= 2) or the backward
 * (Miller) recurrence J_j/J_{j-1} = j / (z + J_{j+1}/J_j) (z > 2).
 * Relative error <= ~20 ulp in both branches.  *rel_err (if not NULL)
 * receives a bound on the relative error. */
double sbi_mills_diff(double z, double h, double lo, double *rel_err);
/* The same with mlo = sbi_mills(z - h) and mhi = sbi_mills(z + h) already
 * computed by the caller (they are its first step). */
double sbi_mills_diff_m(double z, double h, double mlo, double mhi,
                        double *rel_err);

/* ------------------------------------------- extended-exponent products */

/* A value m 2^e with m in [1/2, 1) (or m = 0, e = 0), for products and
 * quotients whose intermediates over- or underflow a double (a mass of
 * 1e-320 inverted, kT/m with m tiny, a prefactor of 1e300 times
 * exp(-800)).  Each operation rounds its mantissa once, exactly as the
 * same operation on doubles rounds when nothing over/underflows: a chain
 * of sbi_xd operations gives the same bits as the plain chain in the
 * normal range, and the right value (up to the final rounding) wherever
 * that is a double.  Arguments must be finite. */
typedef struct {
  double m;
  int e;
} sbi_xd;

static inline sbi_xd sbi_xd_of(double x)
{
  sbi_xd r;
  r.m = frexp(x, &r.e);
  return r;
}

static inline sbi_xd sbi_xd_norm(double m, int e)
{
  sbi_xd r;
  r.m = frexp(m, &r.e);
  r.e = r.m == 0.0 ? 0 : r.e + e;
  return r;
}

static inline sbi_xd sbi_xd_mul(sbi_xd a, sbi_xd b)
{
  return sbi_xd_norm(a.m * b.m, a.e + b.e);
}

static inline sbi_xd sbi_xd_div(sbi_xd a, sbi_xd b)
{
  return sbi_xd_norm(a.m / b.m, a.e - b.e);
}

/* sqrt(a), a >= 0 */
static inline sbi_xd sbi_xd_sqrt(sbi_xd a)
{
  const int odd = a.e & 1;
  return sbi_xd_norm(sqrt(odd ? 2.0 * a.m : a.m), (a.e - odd) / 2);
}

/* a + b: aligned to the larger exponent, one rounding */
static inline sbi_xd sbi_xd_add(sbi_xd a, sbi_xd b)
{
  if (a.m == 0.0)
    return b;
  if (b.m == 0.0)
    return a;
  const int E = a.e > b.e ? a.e : b.e;
  return sbi_xd_norm(ldexp(a.m, a.e - E) + ldexp(b.m, b.e - E), E);
}

/* The double nearest a: +-inf above DBL_MAX, subnormal or 0 below
 * DBL_MIN. */
static inline double sbi_xd_val(sbi_xd a)
{
  const int e = a.e > 4000 ? 4000 : a.e < -4000 ? -4000 : a.e;
  return ldexp(a.m, e);
}

/* The double nearest a as a public function's value: NaN and SB_ERANGE
 * (recorded for func) where it exceeds DBL_MAX; 0 or a subnormal, without
 * error, where it is below DBL_MIN. */
static inline double sbi_xd_checked(sbi_xd a, const char *func)
{
  const double d = sbi_xd_val(a);
  if (isfinite(d))
    return d;
  sbi_error(SB_ERANGE, func, "the value overflows a double at these "
            "arguments");
  return NAN;
}

/* log(a), a > 0 */
static inline double sbi_xd_log(sbi_xd a)
{
  return log(a.m) + a.e * M_LN2;
}

/* exp(-x) for x >= 0 (+inf allowed: 0), without underflow: Cody-Waite
 * reduction x = k ln 2 + r with ln 2 split so that k ln2_hi is exact. */
static inline sbi_xd sbi_xd_expneg(double x)
{
  if (!(x < 1e6))
    return sbi_xd_of(0.0);
  if (x < 700.0)
    return sbi_xd_of(exp(-x));
  const double ln2_hi = 6.93147180369123816490e-01,
               ln2_lo = 1.90821492927058770002e-10;
  const double k = floor(x / M_LN2);
  const double r = (x - k * ln2_hi) - k * ln2_lo;
  return sbi_xd_norm(exp(-r), -(int)k);
}

/* --------------------------------------------- inverse-Gaussian kernel */

/* One evaluation point of the law of S = first passage to 0 of
 * d + nu s' + sqrt(sigma2) W_{s'} (nu >= 0, d > 0), at time s:
 *   eps = d / sqrt(sigma2 s), kap = nu s / sqrt(sigma2 s) >= 0,
 *   c = kap - eps (accurate), ex = exp(-c^2/2) (accurate).
 * Then
 *   F    = P(S <= s)      = Phi(c) + exp(2 kap eps) Q(kap + eps)
 *   SF   = P(S > s)       = ex [M(c) - M(kap + eps)]
 *   SBF  = size-biased CDF = Phi(c) - exp(2 kap eps) Q(kap + eps)
 *        = int_0^s s' f(s') ds' / E[S]
 *   SBSF = 1 - SBF        = ex [M(c) + M(kap + eps)]
 *   pdf  = (eps / s) phi(c).
 * All are evaluated as positive sums or through sbi_mills_diff; relative
 * error bounds are returned through *rel (may be NULL). */
typedef struct {
  double eps, kap, c, ex;
  sbi_dd E; /* c^2/2 in double-double (+inf where it overflows) */
} sbi_igpt;

/* Build a point from the exact numerator num = nu s - d (as dd), the
 * variance den = sigma2 s (as dd, 0 < den < inf), eps and kap; any
 * magnitudes (see sbi_igpt_make_x). */
sbi_igpt sbi_igpt_make(sbi_dd num, sbi_dd den, double eps, double kap);
/* The same for the numerator num 2^e and the variance den 2^(2e'), with
 * c = 2^e num / sqrt(den) (e = e' absorbed: only the ratio matters), so
 * that a caller whose num or den would over/underflow passes scaled
 * parts.  c and c^2/2 are formed from num and den scaled by powers of two
 * into [1, 4) (exact) wherever the plain double-double operations (whose
 * Veltkamp splitting overflows above 2^995) could leave their range; they
 * are +-inf / +inf where c overflows, the value where it is a double. */
sbi_igpt sbi_igpt_make_x(sbi_dd num, sbi_dd den, int e, double eps,
                         double kap);

double sbi_ig_cdf(const sbi_igpt *p, double *rel);
/* wl F + wa SBF (upper = 0) or wl SF + wa SBSF (upper = 1) for wl, wa >= 0,
 * sharing the Mills evaluations (the integrand of the Bessel-3-bridge
 * mixture); relative error bound in *rel. */
double sbi_ig_mix(const sbi_igpt *p, double wl, double wa, int upper,
                  double *rel);
double sbi_ig_sf(const sbi_igpt *p, double *rel);
double sbi_ig_sbcdf(const sbi_igpt *p, double *rel);
double sbi_ig_sbsf(const sbi_igpt *p, double *rel);

/* One exact draw from IG(mean, shape) (Michael, Schucany & Haas 1976):
 * one gsl_ran_gaussian_ziggurat (redrawn if exactly 0, probability 2^-24)
 * and one gsl_rng_uniform.  mean = +inf gives the Levy law shape / Z^2
 * (no uniform). */
double sbi_ig_sample(const gsl_rng *r, double mean, double shape);

/* Rough quantile of IG(1, phi) (mean 1, shape phi; phi = +inf not allowed,
 * phi = 0 not allowed) used as a Newton starting point; lower tail if
 * upper == 0 (P(S <= s) = p), else upper tail (P(S > s) = p).  Within a
 * factor of a few of the truth. */
double sbi_ig_quantile_guess(double p, int upper, double phi);

/* Starting point for the quantile (x = s/mean) of the mixture (1 - pi)
 * IG(1, phi) + pi SB, SB its size-biased law (0 <= pi <= 1), sharper than
 * sbi_ig_quantile_guess (used by the bridge quantiles).  From the
 * Michael-Schucany-Haas representation: Y = phi (S - 1)^2 / S is
 * chi-square(1), and S = 1/D or D with probabilities D/(1 + D), 1/(1 + D)
 * (swapped for SB, whose density is s f(s)), D = 1 + w + sqrt(w (w + 2)),
 * w = Y/(2 phi).  So P(S <= 1/D(y)) and P(S > D(y)) are integrals over
 * (y, inf) of chi2(1) with slowly varying weights; each is approximated by
 * its weight at the mean excess y + delta(y) of chi2(1) beyond y (delta
 * from 1 at y = 0 to 2 as y -> inf) times 2 Q(sqrt y), and solved for y by
 * two fixed-point passes (3 Qinv, 1 Mills call).  Tails as in
 * sbi_ig_quantile_guess. */
double sbi_ig_quantile_start(double p, int upper, double phi, double pi);

/* --------------------------------------------------- monotone solver */

/* g(y), dg/dy and d2g/dy2 (set *d2g = NAN if not available) for an
 * increasing function; g may return -inf / +inf where the underlying
 * probability under/overflows (then the derivatives are ignored). */
typedef double (*sbi_fdf)(double y, void *ctx, double *dg, double *d2g);

/* Solve g(y) = 0 for an increasing g by Halley's method (Newton's when no
 * second derivative is given), safeguarded with a bracket: bisection when
 * the step leaves the bracket or stalls, capped steps while unbracketed,
 * bracket found by stepping from y0 by `step`, doubling.  GSL's
 * derivative-based solvers (gsl_root_fdfsolver_*) are unbracketed and its
 * bracketed ones do not use the derivative; this keeps fast convergence
 * with a guaranteed bracket.  Converged when the correction is below tol
 * (absolute, in y) or |g| <= 1e-10 (the final correction is then applied:
 * for the log-probabilities solved here g''/g'^2 = O(1), so the result is
 * good to ~1e-20 in g).  Returns SB_SUCCESS or SB_EMAXITER; *root receives
 * the result and *dy (may be NULL) the size of the last correction. */
int sbi_solve_increasing(sbi_fdf g, void *ctx, double y0, double step,
                         double tol, double *root, double *dy);

/* Fourth-order variant for quantiles whose g has cheap closed-form
 * derivatives.  The callback fills d[0] = g', d[1] = g'', d[2] = g''' (NAN
 * if not available) and d[3] = 1 if the value is of final accuracy, 0 if
 * it is only a cheaper approximation (good enough to steer the iteration).
 * `kprev` is the solver's last dimensionless step k (below; +inf at the
 * start, 0 when the solver requires a final-accuracy value): a callback
 * may evaluate cheaply while kprev is large.
 * Step: the inverse-function (Lagrange) series to third order,
 *   dy = -r (1 + a2 r/2 + (3 a2^2 - a3) r^2/6),  r = g/g', a2 = g''/g',
 *   a3 = g'''/g',
 * whose truncation error is about |r| k^3 with k = |r| max(1, |a2|,
 * sqrt|a3|) (quartic convergence); Halley's step when the series terms are
 * not small, bisection under the same bracket safeguards as
 * sbi_solve_increasing.  Accepted (with the final step applied) when
 * |r| k^3 <= 1e-18 (about 1 % of an ulp in y) on a final-accuracy value; an
 * acceptable cheap value triggers one final-accuracy evaluation at the
 * corrected point.  *dy receives a bound on the remaining error in y. */
typedef double (*sbi_fdf4)(double y, double kprev, void *ctx, double d[4]);
int sbi_solve_increasing4(sbi_fdf4 g, void *ctx, double y0, double step,
                          double *root, double *dy);

/* ---------------------------------- GSL without its error handler */

/* GSL reports failures through a process-wide error handler (by default
 * it aborts); switching it off inside the library would race with other
 * threads and with the application.  These wrappers call only GSL
 * routines that cannot reach the handler with the arguments they pass. */

/* Root of f in [lo, hi] by GSL's Brent solver.  f(lo) and f(hi) must be
 * finite and of opposite signs (or zero: that end is the root).  Stops
 * when the bracket is within epsabs + epsrel |x| (gsl_root_test_interval)
 * or after maxit iterations.  A non-finite value of f met during the
 * search ends it (SB_EDOM) instead of reaching GSL's handler.  Returns
 * SB_SUCCESS (*root the solver's estimate), SB_EINVAL (no bracket),
 * SB_EDOM (f not finite), SB_EMAXITER (*root the last estimate) or
 * SB_ENOMEM.  Records no error message: the caller names the cause. */
int sbi_brent(const gsl_function *f, double lo, double hi, double epsabs,
              double epsrel, int maxit, double *root);

/* Integral of f over [a, b], b finite or +inf (then over [a, a + 1] and
 * over u in (0, 1] with x = a + 1/u^2: the variable should be scaled to
 * order one), by GSL's doubly adaptive CQUAD (Gonnet 2010), which reports
 * no failure through GSL's handler and skips non-finite values.
 * `n` intervals of workspace (>= 3).  Returns SB_SUCCESS when the error
 * estimate *err is within max(epsabs, epsrel |*res|), SB_EMAXITER when it
 * is not (*res and *err still set), SB_ERANGE if the integral diverges,
 * SB_ENOMEM.  Records no error message. */
int sbi_integrate(const gsl_function *f, double a, double b, double epsabs,
                  double epsrel, size_t n, double *res, double *err);

/* ------------------------------------------------- reach (last zero) */

/* Zero of f where f(0) > 0 turns <= 0 for good (a reach: the distance
 * beyond which a tail bound stays below its tolerance).  Brackets [0, hi]
 * by doubling hi from hi0 while f(hi) > 0, then runs GSL's Brent solver
 * until the bracket's width is below xtol relative to its
 * ends (gsl_root_test_interval with epsabs 0, epsrel xtol).  *root
 * receives the bracket's upper end, where f <= 0 (a conservative reach).
 * Returns SB_SUCCESS, SB_EMAXITER (f NaN, or still > 0 beyond hi_max;
 * *root NaN), SB_EDOM (f NaN inside the bracket; *root NaN) or
 * SB_ENOMEM.  Records no error message: the caller names the cause. */
int sbi_reach_root(gsl_function *f, double hi0, double hi_max, double xtol,
                   double *root);

/* Integral of fn(n) over the unit sphere (dOmega): nmu Gauss-Legendre
 * nodes in cos(theta) times nphi trapezoid points in phi at
 * 2 pi (j + phase)/nphi (periodic: spectral for smooth fn).  NaN if the
 * node table cannot be allocated. */
double sbi_sphere_integral(double (*fn)(const double n[3], void *ctx),
                           void *ctx, size_t nmu, int nphi, double phase);

#endif /* SB_NUMUTIL_H */
