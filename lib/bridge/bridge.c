/* bridge.c — crossing probabilities of the Brownian bridge and the Bessel-3
 * bridge, with their logarithms and complements (smolbridge/bridge.h,
 * docs/bridge.md).  The conditioned hitting times are in bridge_hit.c. */
#include <float.h>
#include <math.h>

#include <smolbridge/bridge.h>
#include "common/internal.h"
#include "common/numutil.h"

#define EPS DBL_EPSILON

enum { K_P, K_LOG, K_NO };

/* An end point on or below the level: the crossing is certain. */
static sb_result certain(int kind)
{
  return (sb_result){kind == K_P ? 1.0 : 0.0, 0.0};
}

/* The crossing is impossible (v = 0, or a Bessel-3 level a = 0). */
static sb_result never(int kind)
{
  return (sb_result){kind == K_P ? 0.0 : kind == K_LOG ? -INFINITY : 1.0,
                     0.0};
}

/* C = 2 (x - a)(y - a) / v in double-double (x, y > a, v > 0). */
static sbi_dd cross_exponent(double x, double y, double a, double v)
{
  return sbi_dd_twice_ratio(sbi_dd_sum(x, -a), sbi_dd_sum(y, -a), v);
}

/* 2 p q / v (p, q, v > 0) in double, to a few ulp: the plain expression
 * where the product p q is a normal double, else from the operands scaled
 * by powers of two (same roundings), so that the value is right wherever
 * it is a double and +inf only where it exceeds DBL_MAX (the product
 * overflowed for x - a ~ 1e300 with C = 2 (x - a)(y - a)/v finite, or was
 * 0 below DBL_MIN). */
static double twice_ratio(double p, double q, double v)
{
  const double pr = p * q;
  if (pr >= DBL_MIN && pr <= DBL_MAX)
    return 2.0 * pr / v;
  if (isinf(p) || isinf(q))
    return INFINITY; /* |x - a| > DBL_MAX: C >= 2^972 / v, v <= DBL_MAX */
  if (p == 0.0 || q == 0.0)
    return 0.0;
  const int ep = ilogb(p), eq = ilogb(q), ev = ilogb(v);
  const double m = 2.0 * (ldexp(p, -ep) * ldexp(q, -eq)) / ldexp(v, -ev);
  const long e = (long)ep + eq - ev;
  return ldexp(m, e > 4000 ? 4000 : e < -4000 ? -4000 : (int)e);
}

/* p q / (r s) (all > 0, finite) with an extended exponent: (p q)/(r s)
 * where r s is a normal double, else (p / r)(q / s), each operation
 * rounded as on doubles (the same bits wherever the plain chain stays in
 * the normal range), and no intermediate over- or underflows (p q below
 * DBL_MIN with a 1e-304, x 1e-48; p / r below DBL_MIN with a 1e-300, x
 * 1e300). */
static sbi_xd prod_ratio(double p, double q, double r, double s)
{
  const sbi_xd P = sbi_xd_of(p), Q = sbi_xd_of(q), R = sbi_xd_of(r),
               S = sbi_xd_of(s);
  return r * s >= DBL_MIN ? sbi_xd_div(sbi_xd_mul(P, Q), sbi_xd_mul(R, S))
                          : sbi_xd_mul(sbi_xd_div(P, R), sbi_xd_div(Q, S));
}

/* P = exp(-C) r for a ratio r <= 1 given with an extended exponent: the
 * plain product where r is a normal double, else in extended exponents
 * with one final rounding (0 or subnormal below DBL_MIN). */
static double prob_times(sbi_dd C, sbi_xd r)
{
  const double rd = sbi_xd_val(r);
  if (rd >= DBL_MIN)
    return C.hi < 746.0 ? sbi_dd_expneg(C) * rd : 0.0;
  return C.hi < 746.0 ? sbi_xd_val(sbi_xd_mul(sbi_xd_of(sbi_dd_expneg(C)), r))
                      : 0.0;
}

static int check_args(const char *fn, double x, double y, double a, double v,
                      int bessel, sb_result *res)
{
  if (!isfinite(x) || !isfinite(y) || !isfinite(a))
    return sbi_fail(res, SB_EDOM, fn, "x = %g, y = %g, a = %g must be finite",
                    x, y, a);
  if (!(v >= 0.0) || !isfinite(v))
    return sbi_fail(res, SB_EDOM, fn, "v = %g must be >= 0 and finite", v);
  if (bessel && a < 0.0)
    return sbi_fail(res, SB_EDOM, fn, "a = %g < 0: a Bessel-3 level must be "
                    ">= 0", a);
  if (bessel && (x < 0.0 || y < 0.0))
    return sbi_fail(res, SB_EDOM, fn, "x = %g, y = %g: a Bessel-3 radius must "
                    "be >= 0", x, y);
  return SB_SUCCESS;
}

/* --------------------------------------------------------------- BB */

static sb_result bb_cross(int kind, double x, double y, double a, double v)
{
  if (x <= a || y <= a)
    return certain(kind);
  if (v == 0.0)
    return never(kind);
  /* P = exp(-C): exp of the double-double C is within ~1 ulp even when C
   * is close to the underflow limit 745.  log P and 1 - P need C only to
   * a few ulp (condition number <= 1). */
  if (kind == K_P) {
    sbi_dd C = cross_exponent(x, y, a, v);
    double p = C.hi < 746.0 ? sbi_dd_expneg(C) : 0.0;
    return (sb_result){p, 3.0 * EPS * p};
  }
  double c = twice_ratio(x - a, y - a, v);
  if (kind == K_LOG)
    return (sb_result){-c, 4.0 * EPS * c}; /* -inf: SB_ERANGE (entry) */
  double nc = -expm1(-c);
  return (sb_result){nc, 5.0 * EPS * nc};
}

/* -------------------------------------------------------------- B3B */

static sb_result b3_cross(int kind, double x, double y, double a, double v)
{
  if (x <= a || y <= a)
    return certain(kind);
  if (a == 0.0 || v == 0.0)
    return never(kind);
  /* P = exp(-C) r,  r = expm1(-A) / expm1(-B),  1 - P = expm1(-C)/expm1(-B)
   * with A = 2a(x+y-a)/v, B = 2xy/v = A + C.  Both ratios are quotients of
   * two negative numbers computed to ~1 ulp (expm1 has condition number
   * <= 1 here), so nothing cancels. */
  double c = twice_ratio(x - a, y - a, v); /* C to a few ulp */
  double sxa = (x - a) + y; /* x + y - a, a sum of positives */
  double A = twice_ratio(a, sxa, v), B = twice_ratio(x, y, v);
  int tiny = B < 1e-280; /* v huge: the ratios are their limits */
  if (tiny) {
    /* nc and r in extended exponents: a(x + y - a) or a/x may leave the
     * doubles where r does not (a = 1e-304, x = 1e-48: r ~ 1e-105) */
    const sbi_xd rx = prod_ratio(a, sxa, x, y);
    double nc = sbi_xd_val(prod_ratio(x - a, y - a, x, y)),
           r = sbi_xd_val(rx);
    if (kind == K_NO)
      return (sb_result){nc, 6.0 * EPS * nc};
    if (kind == K_P) {
      double p = prob_times(cross_exponent(x, y, a, v), rx);
      return (sb_result){p, 8.0 * EPS * p};
    }
    /* 1 - r = nc: log1p where r is near 1 (a near min(x, y)) */
    double logr = nc < 0.5   ? log1p(-nc)
                  : r >= DBL_MIN ? log(r)
                                 : sbi_xd_log(rx);
    return (sb_result){-c + logr, 4.0 * EPS * c + 6.0 * EPS * fabs(logr)};
  }
  double eb = expm1(-B);
  if (kind == K_NO) {
    double nc = expm1(-c) / eb;
    return (sb_result){nc, 6.0 * EPS * nc};
  }
  double ea = expm1(-A), r = ea / eb;
  sbi_xd rx = sbi_xd_of(r);
  if (A < 1e-290) { /* A near or below the subnormals: r = (A/B)/g(B), */
    /* g(z) = (1 - e^-z)/z; in extended exponents, since a/x may underflow
     * and (x + y - a)/y overflow where r is a double (x = DBL_MAX,
     * y = 0.5, a = 1e-300: r ~ 1e-300) */
    rx = sbi_xd_mul(sbi_xd_mul(sbi_xd_div(sbi_xd_of(a), sbi_xd_of(x)),
                               sbi_xd_div(sbi_xd_of(sxa), sbi_xd_of(y))),
                    sbi_xd_of(B / -eb));
    r = sbi_xd_val(rx);
  }
  if (kind == K_P) {
    double p = prob_times(cross_exponent(x, y, a, v), rx);
    return (sb_result){p, 8.0 * EPS * p};
  }
  /* log P = -C + log r.  Near r = 1 use 1 - r = exp(-A) (1 - P) exactly
   * (because B = A + C): log r = log1p(-(1 + ea) nc).  (1 + ea has a large
   * relative error only when exp(-A) is tiny, where it is a negligible
   * correction.)  Elsewhere log r directly, or in log space if r is
   * subnormal. */
  double logr;
  if (r >= 0.5) {
    double nc = expm1(-c) / eb;
    logr = log1p(-(1.0 + ea) * nc);
  } else if (r > 1e-300) {
    logr = log(r);
  } else {
    double la = A > 1e-300 ? sbi_log1mexp(A)
                           : log(2.0 * a) + log(sxa) - log(v);
    logr = la - sbi_log1mexp(B);
  }
  return (sb_result){-c + logr, 4.0 * EPS * c + 6.0 * EPS * fabs(logr)};
}

/* --------------------------------------------------------- wrappers */

static int cross_entry(const char *fn, int bessel, int kind, double x,
                       double y, double a, double v, sb_result *res)
{
  int st = check_args(fn, x, y, a, v, bessel, res);
  if (st)
    return st;
  *res = bessel ? b3_cross(kind, x, y, a, v) : bb_cross(kind, x, y, a, v);
  if (kind == K_LOG && isinf(res->val) && v > 0.0 &&
      !(bessel && a == 0.0) && x > a && y > a)
    /* log P = -C below -DBL_MAX (not the exact -inf of P = 0) */
    return sbi_fail(res, SB_ERANGE, fn,
                    "log P = -2 (x - a)(y - a)/v < -DBL_MAX (x = %g, y = %g, "
                    "a = %g, v = %g)", x, y, a, v);
  return SB_SUCCESS;
}

#define CROSS_PAIR(name, bessel, kind)                                      \
  int sb_##name##_e(double x, double y, double a, double v, sb_result *res) \
  {                                                                         \
    sb_result r;                                                            \
    int st = cross_entry(__func__, bessel, kind, x, y, a, v, &r);           \
    if (res)                                                                \
      *res = r;                                                             \
    return st;                                                              \
  }                                                                         \
  double sb_##name(double x, double y, double a, double v)                  \
  {                                                                         \
    sb_result r;                                                            \
    cross_entry(__func__, bessel, kind, x, y, a, v, &r);                    \
    return r.val;                                                           \
  }

CROSS_PAIR(bb_cross_prob, 0, K_P)
CROSS_PAIR(bb_cross_logprob, 0, K_LOG)
CROSS_PAIR(bb_nocross_prob, 0, K_NO)
CROSS_PAIR(bes3b_cross_prob, 1, K_P)
CROSS_PAIR(bes3b_cross_logprob, 1, K_LOG)
CROSS_PAIR(bes3b_nocross_prob, 1, K_NO)
