/* smolbridge/bridge.h — Brownian-bridge and Bessel-3-bridge crossing
 * probabilities and the conditioned hitting time of a level (unit-free).
 *
 * Brownian bridge (BB): 1-D, dX = sigma dW, X_0 = x, X_t = y.
 * Bessel-3 bridge (B3B): R = |3-D Brownian motion| with per-component rate
 * sigma2, R_0 = x, R_t = y (x, y >= 0 are radii).
 * v = sigma2 t; level a; alpha = x - a, beta = y - a.
 *
 * Crossing probabilities P(min over [0, t] <= a):
 *   BB   P = exp(-2 alpha beta / v)                         (reflection)
 *   B3B  P = expm1(2a(x+y-a)/v) / expm1(2xy/v)       (Mohaupt 2011, eq 5.13)
 *          = exp(-2 alpha beta/v) expm1(-2a(x+y-a)/v) / expm1(-2xy/v)
 *   and directly P(no crossing) = expm1(-2 alpha beta/v) / expm1(-2xy/v) for
 *   B3B, -expm1(-2 alpha beta/v) for BB.  The B3B form follows from the
 *   Bessel-3 transition density q_v(x,y) = (y/x)[g_v(y-x) - g_v(y+x)] and its
 *   version killed at a, (y/x)[g_v(y-x) - g_v(x+y-2a)], g_v the N(0, v)
 *   density.  Both are 1 when x <= a or y <= a (overlap at an end point;
 *   Mohaupt 2011, eq 5.15, writes min(1, P), which fails when both ends
 *   overlap: docs/errata.md): log 0, no-crossing 0.  B3B with a = 0 gives
 *   P = 0.
 * Domain: finite x, y, a; v >= 0 finite (v = 0 is the limit: P = 0 unless an
 * end point overlaps).  B3B: x >= 0, y >= 0 and a >= 0 (a < 0 is SB_EDOM).
 * Accuracy: relative error <= 1e-14 typically (tested <= 1e-13 against
 * mpmath at 50 digits for v/len^2 in [1e-8, 1e8]); the logs keep that
 * relative accuracy where P underflows (log P down to -1e300 and beyond).
 * The exponent 2 alpha beta / v is formed in double-double arithmetic.
 * Extremes: any finite magnitudes (products beyond the doubles are scaled
 * by powers of two; the B3B ratio expm1(-A)/expm1(-B) ~ a(x+y-a)/(xy),
 * where A = 2a(x+y-a)/v or B = 2xy/v is tiny, is formed with an extended
 * exponent, so P is right wherever it is a normal double, e.g. 1.16e-300
 * at x = v = DBL_MAX, y = 0.5, a = 1e-300, and 0 or subnormal only below
 * DBL_MIN); the log is SB_ERANGE (NaN) where log P < -DBL_MAX
 * (e.g. v = 1e-320) and -inf with status 0 only where P = 0 exactly (v = 0
 * with no end point overlapping, B3B a = 0).
 *
 * Conditioned hitting time T_a = inf{u : X_u = a} given T_a <= t, arguments
 * (u or p, x, y, a, sigma2, t), sigma2 > 0, t > 0:
 *   BB   (docs/bridge.md) the time change s = u t/(t - u) turns the bridge
 *        into BM with drift from alpha, and S = T t/(t - T) is inverse
 *        Gaussian IG(mean alpha t/|beta|, shape alpha^2/sigma2) (Levy when
 *        beta = 0), for either sign of beta.  So
 *        P(T <= u) = Phi(c) + exp(2 alpha |beta|/v) Phi(-b),
 *        c = (|beta| u - alpha (t-u))/r, b = (|beta| u + alpha (t-u))/r,
 *        r = sqrt(sigma2 u t (t-u)).
 *   B3B  density prop. to n_{x,a}(u) q_{t-u}(a, y) (n the Bessel-3
 *        first-passage density), i.e. the BB hitting density times
 *        -expm1(-2 a y/(sigma2 (t-u))); the CDF is
 *        [G(u; |beta|) - rho G(u; y + a)] / (1 - rho), G(u; L) the BB law
 *        above with |beta| replaced by L and
 *        rho = exp(-[(alpha + y + a)^2 - (alpha + |beta|)^2]/(2v)).  This
 *        agrees with Mohaupt (2011) eq 5.21-5.22 (and App. I eq I.62-I.63)
 *        but NOT with App. I eq I.60-I.61, which is misprinted
 *        (tests/test_bridge.c shows it against quadrature).  Where the
 *        difference cancels (rho G(u; y+a) > 0.95 G(u; |beta|), i.e.
 *        1 - rho small:
 *        a (x+y) << v) the CDF is computed from the equivalent positive
 *        mixture over the bridge minimum, by a Taylor expansion about its
 *        middle with a proven truncation and rounding bound, or by 3- and
 *        4-point Gauss-Legendre quadrature where the bound fails
 *        (docs/bridge.md §3).
 * Extremes: pdf, cdf and sf take any finite arguments, and u = +-inf
 * (outside [0, t]: pdf 0, cdf 0 at -inf and 1 at +inf, status 0); any
 * other infinite argument (x, y, a, sigma2, t, v, p) is SB_EDOM.  The pdf
 * is the right value wherever it is a normal double (extended exponents
 * where an intermediate leaves the doubles), 0 or subnormal below DBL_MIN,
 * and SB_ERANGE (NaN) where it exceeds DBL_MAX (docs/bridge.md); the B3B
 * 1 - rho and the factor 2ay/(sigma2 (t-u)) likewise keep full precision
 * where min(a, y) is tiny and v small (a = 1e-305, v = 1e-30), and where
 * k = 2 min(a, y)(x - a + max(a, y))/v < DBL_MIN the law is its limit as
 * min(a, y) -> 0 where min(a, y) < 2^-60 (x - a + max(a, y)) (right to
 * rounding there); where all positions are below ~1e-154 sqrt(v) with
 * min(a, y) comparable to the others, the mixture over the minimum with
 * its first-order weight, normalised by k with an extended exponent
 * (cdf/sf to ~4e-16 against mpmath; before: the limit law, off by up to
 * 48%).  There the early and late hits (u or t - u ~ position^2/sigma2)
 * can lie below DBL_MIN t or one ulp of t: the cdf then jumps at 0+ or t
 * in doubles, and quantiles beyond such a jump are not the best double
 * (docs/bridge.md §3).
 * Positions far beyond sqrt(v) follow the same rule as the other finite
 * arguments: x, y, a over sqrt(sigma2 t) beyond DBL_MAX (x = 1e300 with
 * sigma2 = 1e-200, t = 1e-100) are not SB_EDOM (only an infinite argument
 * is) but the limit law.  Beyond ~2^1000 sqrt(v) the law is a step at
 * u* = t alpha/(alpha + |beta|) on the scale of the doubles (relative
 * width ~ sqrt(v/(alpha |beta|))): cdf 0 below u* and 1 above (a law
 * conditioned on T_a <= t: sf = 1 - cdf, never defective), 1/2 where
 * |beta| u = alpha (t - u) exactly, pdf 0 off u* and SB_ERANGE where it
 * exceeds DBL_MAX; the value between 0 and 1 where the low-order parts of
 * the positions leave |beta| u - alpha (t - u) of order sqrt(sigma2 u t
 * (t - u)) (formed in double-double, as elsewhere).  For B3B with
 * sqrt(sigma2 u t (t - u)) < DBL_MIN the mixture over L in [|beta|, y + a]
 * is one of such steps (closed form; the BB law with |beta| where rho
 * underflows).  Known limitation: the rescaling
 * divides u by about t, so where u < 2^-1022 t with sigma2 t^3 outside
 * 2^(+-600) the cdf is that at u = 0 (0), wrong where the law sits below
 * u (t = 1e300, sigma2 = 1e-310, x = 1e-290, y = 1e300, a = 0, u =
 * 2e-290: 0, should be 1).  The
 * quantile falls back to bisection on the doubles of [0, t] where its
 * iteration fails or closes its bracket on a step (laws narrower than one
 * ulp, u ~ 1e-300 t; the step's best double).  The
 * samplers return a double in [0, t] for any valid arguments (t up to
 * DBL_MAX), or NaN with SB_EDOM/SB_EINVAL and a message naming them.
 * Special cases: x <= a: T_a = 0 (cdf = 1 for u >= 0, pdf 0, quantile 0,
 * sample 0).  y <= a < x: the bridge surely hits, same formulas.  For B3B
 * a = 0 with x, y > 0 is SB_EDOM (the bridge never hits 0); y = 0 < x with
 * a = 0 gives T_a = t.  cdf(u) is 0 for u < 0 and 1 for u > t (not an error).
 * Accuracy: pdf, cdf, sf relative error <= 1e-12 (tested against mpmath;
 * typically a few 1e-15), quantile to full double precision with
 * |cdf(q) - p| <= 1e-13, or, where one ulp of q moves the cdf by more
 * than that (a law concentrated near t), q the best double; samplers
 * exact in distribution:
 *   BB:  Michael-Schucany-Haas inverse-Gaussian draw of S, then T = St/(t+S);
 *   B3B: draw the bridge minimum m from its law restricted to (0, a]
 *        (closed-form inversion), then S from the mixture
 *        IG(alpha t/L, alpha^2/sigma2) with probability L/(alpha + L) or its
 *        size-biased version (IG + sigma2 t^2 Z^2 / L^2) otherwise,
 *        L = a + y - 2m; no rejection, any parameters.
 */
#ifndef SMOLBRIDGE_BRIDGE_H
#define SMOLBRIDGE_BRIDGE_H

#include <gsl/gsl_rng.h>
#include <smolbridge/common.h>

#ifdef __cplusplus
extern "C" {
#endif

/* --------------------------------------------------- crossing probability */

/** Brownian bridge: P(min_{[0,t]} X <= a) given X_0 = x, X_t = y, v = sigma2 t. */
double sb_bb_cross_prob(double x, double y, double a, double v);
/** log of sb_bb_cross_prob (= -2 (x-a)(y-a)/v when no end point overlaps). */
double sb_bb_cross_logprob(double x, double y, double a, double v);
/** 1 - sb_bb_cross_prob, computed directly. */
double sb_bb_nocross_prob(double x, double y, double a, double v);

/** Bessel-3 bridge: P(min_{[0,t]} R <= a) given R_0 = x, R_t = y. */
double sb_bes3b_cross_prob(double x, double y, double a, double v);
double sb_bes3b_cross_logprob(double x, double y, double a, double v);
double sb_bes3b_nocross_prob(double x, double y, double a, double v);

int sb_bb_cross_prob_e(double x, double y, double a, double v, sb_result *res);
int sb_bb_cross_logprob_e(double x, double y, double a, double v,
                          sb_result *res);
int sb_bb_nocross_prob_e(double x, double y, double a, double v,
                         sb_result *res);
int sb_bes3b_cross_prob_e(double x, double y, double a, double v,
                          sb_result *res);
int sb_bes3b_cross_logprob_e(double x, double y, double a, double v,
                             sb_result *res);
int sb_bes3b_nocross_prob_e(double x, double y, double a, double v,
                            sb_result *res);

/* --------------------------- hitting time T_a conditioned on T_a <= t */

/** Brownian bridge: density of T_a at u given T_a <= t. */
double sb_bb_hit_pdf(double u, double x, double y, double a, double sigma2,
                     double t);
/** Brownian bridge: P(T_a <= u | T_a <= t). */
double sb_bb_hit_cdf(double u, double x, double y, double a, double sigma2,
                     double t);
/** Brownian bridge: P(T_a > u | T_a <= t), computed directly. */
double sb_bb_hit_sf(double u, double x, double y, double a, double sigma2,
                    double t);
/** Brownian bridge: quantile of T_a | T_a <= t for p in [0, 1]. */
double sb_bb_hit_quantile(double p, double x, double y, double a,
                          double sigma2, double t);
/** Brownian bridge: one exact draw of T_a | T_a <= t (one Gaussian, one
 *  uniform). */
double sb_bb_hit_sample(const gsl_rng *r, double x, double y, double a,
                        double sigma2, double t);

int sb_bb_hit_pdf_e(double u, double x, double y, double a, double sigma2,
                    double t, sb_result *res);
int sb_bb_hit_cdf_e(double u, double x, double y, double a, double sigma2,
                    double t, sb_result *res);
int sb_bb_hit_sf_e(double u, double x, double y, double a, double sigma2,
                   double t, sb_result *res);
int sb_bb_hit_quantile_e(double p, double x, double y, double a,
                         double sigma2, double t, sb_result *res);

/** Bessel-3 bridge: density of T_a at u given T_a <= t. */
double sb_bes3b_hit_pdf(double u, double x, double y, double a, double sigma2,
                        double t);
/** Bessel-3 bridge: P(T_a <= u | T_a <= t). */
double sb_bes3b_hit_cdf(double u, double x, double y, double a, double sigma2,
                        double t);
/** Bessel-3 bridge: P(T_a > u | T_a <= t), computed directly. */
double sb_bes3b_hit_sf(double u, double x, double y, double a, double sigma2,
                       double t);
/** Bessel-3 bridge: quantile of T_a | T_a <= t for p in [0, 1]. */
double sb_bes3b_hit_quantile(double p, double x, double y, double a,
                             double sigma2, double t);
/** Bessel-3 bridge: one exact draw of T_a | T_a <= t (no rejection; two to
 *  three uniforms and one or two Gaussians). */
double sb_bes3b_hit_sample(const gsl_rng *r, double x, double y, double a,
                           double sigma2, double t);

int sb_bes3b_hit_pdf_e(double u, double x, double y, double a, double sigma2,
                       double t, sb_result *res);
int sb_bes3b_hit_cdf_e(double u, double x, double y, double a, double sigma2,
                       double t, sb_result *res);
int sb_bes3b_hit_sf_e(double u, double x, double y, double a, double sigma2,
                      double t, sb_result *res);
int sb_bes3b_hit_quantile_e(double p, double x, double y, double a,
                            double sigma2, double t, sb_result *res);

#ifdef __cplusplus
}
#endif

#endif /* SMOLBRIDGE_BRIDGE_H */
