/* numutil.c — internal numerical helpers (see numutil.h). */
#include <float.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>

#include <gsl/gsl_cdf.h>
#include <gsl/gsl_integration.h>
#include <gsl/gsl_randist.h>
#include <gsl/gsl_roots.h>

#include <smolbridge/common.h>
#include "numutil.h"

#define RT2PI 2.5066282746310005024157652848110453 /* sqrt(2 pi) */
#define EPS DBL_EPSILON

int sbi_fail(sb_result *res, int status, const char *func, const char *fmt,
             ...)
{
  char buf[400];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(buf, sizeof buf, fmt, ap);
  va_end(ap);
  if (res) {
    res->val = NAN;
    res->err = NAN;
  }
  return sbi_error(status, func, "%s", buf);
}

/* ----------------------------------------------------------- log1mexp */

double sbi_log1mexp(double x)
{
  /* Maechler (2012), "Accurately computing log(1 - exp(-|a|))": expm1 below
   * log 2, log1p above. */
  return x <= 0.69314718055994530942 /* log 2 */ ? log(-expm1(-x)) : log1p(-exp(-x));
}

/* ----------------------------------------------------- Mills function */

/* Rational approximations of erfcx(y) = exp(y^2) erfc(y): Cody (1969),
 * Math. Comp. 23, 631-638, with the coefficients of his CALERF (SPECFUN,
 * 1990).  erf(y) = y A(y^2)/B(y^2) for y <= 0.46875; erfcx(y) = C(y)/D(y)
 * on [0.46875, 4]; erfcx(y) = (1/sqrt(pi) - P(1/y^2)/(y^2 Q(1/y^2)))/y
 * beyond.  The last two need no exponential at all. */
static const double CODY_A[5] = {
    3.16112374387056560e0, 1.13864154151050156e2, 3.77485237685302021e2,
    3.20937758913846947e3, 1.85777706184603153e-1};
static const double CODY_B[4] = {
    2.36012909523441209e1, 2.44024637934444173e2, 1.28261652607737228e3,
    2.84423683343917062e3};
static const double CODY_C[9] = {
    5.64188496988670089e-1, 8.88314979438837594e0, 6.61191906371416295e1,
    2.98635138197400131e2, 8.81952221241769090e2, 1.71204761263407058e3,
    2.05107837782607147e3, 1.23033935479799725e3, 2.15311535474403846e-8};
static const double CODY_D[8] = {
    1.57449261107098347e1, 1.17693950891312499e2, 5.37181101862009858e2,
    1.62138957456669019e3, 3.29079923573345963e3, 4.36261909014324716e3,
    3.43936767414372164e3, 1.23033935480374942e3};
static const double CODY_P[6] = {
    3.05326634961232344e-1, 3.60344899949804439e-1, 1.25781726111229246e-1,
    1.60837851487422766e-2, 6.58749161529837803e-4, 1.63153871373020978e-2};
static const double CODY_Q[5] = {
    2.56852019228982242e0, 1.87295284992346047e0, 5.27905102951428412e-1,
    6.05183413124413191e-2, 2.33520497626869185e-3};
#define INV_SQRTPI 0.56418958354775628694807945156077259 /* 1/sqrt(pi) */

/* erfcx(y) for y >= 0 */
static double erfcx_pos(double y)
{
  if (y <= 0.46875) {
    double q = y * y, num = CODY_A[4] * q, den = q;
    for (int i = 0; i < 3; i++) {
      num = (num + CODY_A[i]) * q;
      den = (den + CODY_B[i]) * q;
    }
    return exp(q) * (1.0 - y * (num + CODY_A[3]) / (den + CODY_B[3]));
  }
  if (y <= 4.0) {
    double num = CODY_C[8] * y, den = y;
    for (int i = 0; i < 7; i++) {
      num = (num + CODY_C[i]) * y;
      den = (den + CODY_D[i]) * y;
    }
    return (num + CODY_C[7]) / (den + CODY_D[7]);
  }
  if (y >= 6.71e7) /* the correction is below half an ulp */
    return INV_SQRTPI / y;
  double q = 1.0 / (y * y), num = CODY_P[5] * q, den = q;
  for (int i = 0; i < 4; i++) {
    num = (num + CODY_P[i]) * q;
    den = (den + CODY_Q[i]) * q;
  }
  return (INV_SQRTPI - q * (num + CODY_P[4]) / (den + CODY_Q[4])) / y;
}

double sbi_mills(double z)
{
  /* M(z) = erfcx(z/sqrt 2)/2; for z < 0, M(z) = exp(z^2/2) - M(-z) (as
   * Q(z) = 1 - Q(-z)), with exp(z^2/2) split so that the rounding of z*z
   * does not enter: z^2 = h + l exactly (overflow below z ~ -37.6). */
  double m = 0.5 * erfcx_pos(fabs(z) * 0.70710678118654752440084436210484904);
  if (z >= 0.0)
    return m;
  sbi_dd z2 = sbi_dd_prod(z, z);
  return exp(0.5 * z2.hi) * (1.0 + 0.5 * z2.lo) - m;
}

/* ------------------------------------------ difference of Mills values */

#define JMAX 27 /* highest J_j used by the series (odd j up to JMAX) */

double sbi_mills_diff(double z, double h, double lo, double *rel_err)
{
  if (h <= 0.0) {
    if (rel_err)
      *rel_err = 0.0;
    return 0.0;
  }
  return sbi_mills_diff_m(z, h, sbi_mills(lo), sbi_mills(z + h), rel_err);
}

double sbi_mills_diff_m(double z, double h, double mlo, double mhi,
                        double *rel_err)
{
  if (h <= 0.0) {
    if (rel_err)
      *rel_err = 0.0;
    return 0.0;
  }
  if (mhi <= 0.8 * mlo) {
    /* no serious cancellation: each M is within 4 ulp */
    if (rel_err)
      *rel_err = EPS * (1.0 + 4.0 * (mlo + mhi) / (mlo - mhi));
    return mlo - mhi;
  }
  /* Series.  M(z -+ h) = (1/sqrt(2 pi)) int_0^inf exp(-w^2/2 - (z -+ h) w)dw,
   * so M(z-h) - M(z+h) = (2/sqrt(2 pi)) sum_{j odd} J_j(z) h^j / j!, a sum of
   * positive terms.  Only reached when h/max(z,1) < 0.2, where it converges
   * in at most ~12 odd terms. */
  double J[JMAX + 1];
  double mz = sbi_mills(z);
  J[0] = RT2PI * mz;
  /* number of odd terms: they fall at least like (h/z)^2 for z > 3 */
  int jn = JMAX;
  if (z > 3.0) {
    double n = 20.8 / log(z / h); /* (h/z)^(2n) < 1e-18 */
    if (n > 0.0 && n < 12.0)
      jn = 2 * (int)n + 3;
  }
  if (!(z > 3.0)) { /* NaN z too: (int) of NaN below is undefined */
    /* forward recurrence J_{k+1} = k J_{k-1} - z J_k (integration by parts);
     * it loses accuracy as z grows (J_1 = 1 - z J_0 cancels), measured
     * <= 9 ulp for D up to z = 3 (tests/data/mdiff.csv) */
    J[1] = 1.0 - z * J[0];
    for (int k = 1; k < JMAX; k++)
      J[k + 1] = k * J[k - 1] - z * J[k];
  } else {
    /* backward (Miller) recurrence for the ratios R_k = J_k / J_{k-1} =
     * k / (z + R_{k+1}), started at N where R_{N+1} solves
     * R^2 + (z + dR) R = N + 1 with dR = 1/(z + 2R) ~ R_{k+1} - R_k; the
     * depth N - jn >= (110 + 2 jn)/z + 7 was measured (against N = 5000)
     * to give R_1..R_jn to 1 ulp with a margin of 4 or more levels. */
    int N = jn + 7 + (int)((110.0 + 2.0 * jn) / z);
    double k1 = N + 1.0;
    double R = 0.5 * (sqrt(z * z + 4.0 * k1) - z);
    double zd = z + 1.0 / (z + 2.0 * R);
    R = 0.5 * (sqrt(zd * zd + 4.0 * k1) - zd);
    double Rk[JMAX + 1];
    for (int k = N; k >= 1; k--) {
      R = k / (z + R);
      if (k <= jn)
        Rk[k] = R;
    }
    for (int k = 1; k <= jn; k++)
      J[k] = J[k - 1] * Rk[k];
  }
  double term = J[1] * h, sum = term, h2 = h * h, pw = h;
  int converged = 0;
  for (int j = 3; j <= jn; j += 2) {
    pw *= h2 / ((double)(j - 1) * j);
    term = J[j] * pw;
    sum += term;
    if (term < 1e-18 * sum) {
      converged = 1;
      break;
    }
  }
  double d = 2.0 * sum / RT2PI;
  if (!converged) {
    /* cannot happen for the documented domain; fall back to the direct
     * difference with its honest (large) error */
    if (rel_err)
      *rel_err = EPS * (1.0 + 4.0 * (mlo + mhi) / (mlo - mhi));
    return mlo - mhi;
  }
  if (rel_err)
    *rel_err = 24.0 * EPS;
  return d;
}

/* ------------------------------------------- inverse-Gaussian kernel */

sbi_igpt sbi_igpt_make_x(sbi_dd num, sbi_dd den, int e, double eps,
                         double kap)
{
  sbi_igpt p;
  p.eps = eps;
  p.kap = kap;
  const double big = 0x1p400, small = 0x1p-400;
  if ((e == 0 && den.hi < big && den.hi > small &&
       fabs(num.hi) < 0x1p200) ||
      !(den.hi > 0.0 && den.hi <= DBL_MAX && fabs(num.hi) <= DBL_MAX)) {
    /* the usual case (and the degenerate den = 0 or inf, num inf):
     * E = num^2 / (2 den) in double-double, exp(-E) to ~1 ulp */
    double q = sqrt(den.hi);
    p.c = (num.hi + num.lo) / q;
    sbi_dd n2 = sbi_dd_mul(num, num);
    p.E = sbi_dd_div(n2, sbi_dd_mul_d(den, 2.0));
  } else if (num.hi == 0.0) {
    p.c = 0.0;
    p.E = (sbi_dd){0.0, 0.0};
  } else {
    /* c = 2^(e + kn - kd) ns / sqrt(ds), E = c^2/2, with ns = num 2^-kn
     * and ds = den 2^(-2 kd) in [1, 4): each operation rounds as the
     * plain one does where that stays in range (same bits), and only
     * the final ldexp can overflow (c = +-inf, E = inf) or underflow */
    const int kn = ilogb(num.hi), kd = ilogb(den.hi) / 2, ec = e + kn - kd;
    sbi_dd ns = {ldexp(num.hi, -kn), ldexp(num.lo, -kn)};
    sbi_dd ds = {ldexp(den.hi, -2 * kd), ldexp(den.lo, -2 * kd)};
    double c = (ns.hi + ns.lo) / sqrt(ds.hi);
    sbi_dd E = sbi_dd_div(sbi_dd_mul(ns, ns), sbi_dd_mul_d(ds, 2.0));
    /* |ec| can exceed the range of ldexp's useful exponents: clamp */
    const int ecl = ec > 4000 ? 4000 : ec < -4000 ? -4000 : ec;
    p.c = ldexp(c, ecl);
    p.E.hi = ldexp(E.hi, 2 * ecl);
    p.E.lo = isfinite(p.E.hi) ? ldexp(E.lo, 2 * ecl) : 0.0;
  }
  p.ex = (p.E.hi < 746.0) ? sbi_dd_expneg(p.E) : 0.0;
  return p;
}

sbi_igpt sbi_igpt_make(sbi_dd num, sbi_dd den, double eps, double kap)
{
  return sbi_igpt_make_x(num, den, 0, eps, kap);
}

/* exp(-c^2/2) M(kap + eps) = exp(2 kap eps) Q(kap + eps) */
static double second_term(const sbi_igpt *p)
{
  return p->ex > 0.0 ? p->ex * sbi_mills(p->kap + p->eps) : 0.0;
}

double sbi_ig_cdf(const sbi_igpt *p, double *rel)
{
  double c = p->c, t2 = second_term(p), f, r;
  if (c >= -3.0) {
    /* Phi(c) >= 0.0013: the rounding of c costs at most (1 + c^2) ulp */
    double ph = gsl_cdf_ugaussian_P(c);
    f = ph + t2;
    r = (ph * (2.0 + (c < 0 ? 2.0 * c * c : 0.0)) + 6.0 * t2) * EPS;
  } else {
    /* Phi(c) = exp(-c^2/2) M(-c): insensitive to the rounding of c */
    double t1 = p->ex > 0.0 ? p->ex * sbi_mills(-c) : 0.0;
    f = t1 + t2;
    r = 6.0 * f * EPS;
  }
  if (rel)
    *rel = f > 0.0 ? r / f + EPS : 0.0;
  return f;
}

/* ex (M(lo) - M(z + h)), lo = z - h (see sbi_mills_diff), or 0 when ex
 * underflowed; *rel (if rel) gets its relative error bound. */
static double ex_mills_diff(const sbi_igpt *p, double z, double h, double lo,
                            double *rel)
{
  if (p->ex == 0.0) {
    if (rel)
      *rel = 0.0;
    return 0.0;
  }
  double rd;
  double d = sbi_mills_diff(z, h, lo, &rd);
  if (rel)
    *rel = rd + 3.0 * EPS;
  return p->ex * d;
}

double sbi_ig_sf(const sbi_igpt *p, double *rel)
{
  double c = p->c;
  if (c < -2.0) {
    /* Q(c) > 0.977 and the subtracted term is below 0.025 of it */
    double t2 = second_term(p), q = gsl_cdf_ugaussian_Q(c);
    double s = q - t2;
    if (rel)
      *rel = ((2.0 + 2.0 * c * c) * q + 6.0 * t2) * EPS / s + EPS;
    return s;
  }
  return ex_mills_diff(p, p->kap, p->eps, c, rel);
}

double sbi_ig_sbcdf(const sbi_igpt *p, double *rel)
{
  double c = p->c;
  if (c > 2.0) {
    double t2 = second_term(p), ph = gsl_cdf_ugaussian_P(c);
    double s = ph - t2;
    if (rel)
      *rel = (2.0 * ph + 6.0 * t2) * EPS / s + EPS;
    return s;
  }
  return ex_mills_diff(p, p->eps, p->kap, -c, rel);
}

double sbi_ig_sbsf(const sbi_igpt *p, double *rel)
{
  double c = p->c, s, r;
  if (c < -3.0) {
    double q = gsl_cdf_ugaussian_Q(c), t2 = second_term(p);
    s = q + t2;
    r = (2.0 * q + 6.0 * t2) * EPS;
  } else {
    s = p->ex > 0.0 ? p->ex * (sbi_mills(c) + sbi_mills(p->kap + p->eps))
                    : 0.0;
    r = 7.0 * s * EPS;
  }
  if (rel)
    *rel = s > 0.0 ? r / s + EPS : 0.0;
  return s;
}

double sbi_ig_mix(const sbi_igpt *p, double wl, double wa, int upper,
                  double *rel)
{
  double c = p->c;
  if (p->ex == 0.0 || c < -3.0 || c > 2.0) {
    /* far tails: the separate routines (no shared work to speak of) */
    double r1, r2, f, g;
    f = upper ? sbi_ig_sf(p, &r1) : sbi_ig_cdf(p, &r1);
    g = upper ? sbi_ig_sbsf(p, &r2) : sbi_ig_sbcdf(p, &r2);
    double v = wl * f + wa * g;
    if (rel)
      *rel = v > 0.0 ? (wl * f * r1 + wa * g * r2) / v + EPS : 0.0;
    return v;
  }
  /* -3 <= c <= 2: with Mb = M(kap + eps),
   *   F = ex (M(-c) + Mb), SBF = ex (M(-c) - Mb),
   *   SF = ex (M(c) - Mb), SBSF = ex (M(c) + Mb),
   * the differences by sbi_mills_diff when they cancel. */
  double b = p->kap + p->eps, mb = sbi_mills(b);
  double lo = upper ? c : -c, mlo = sbi_mills(lo);
  double dif, rd;
  if (mb <= 0.8 * mlo) {
    dif = mlo - mb;
    rd = EPS * (1.0 + 4.0 * (mlo + mb) / dif);
  } else {
    /* M(lo) - M(b) with midpoint z and half-width h */
    double z = upper ? p->kap : p->eps, h = upper ? p->eps : p->kap;
    dif = sbi_mills_diff_m(z, h, mlo, mb, &rd);
  }
  double sum = mlo + mb;
  /* upper: wl (M(c) - Mb) + wa (M(c) + Mb); lower: wl sum + wa dif */
  double v = upper ? wl * dif + wa * sum : wl * sum + wa * dif;
  double e = upper ? wl * dif * rd + wa * sum * 5.0 * EPS
                   : wl * sum * 5.0 * EPS + wa * dif * rd;
  if (rel)
    *rel = v > 0.0 ? e / v + 3.0 * EPS : 0.0;
  return p->ex * v;
}

double sbi_ig_sample(const gsl_rng *r, double mean, double shape)
{
  /* GSL's ziggurat returns exactly 0 with probability 2^-24 (its atom for
   * a sliver of width ~1e-7 around 0); shape/0 would be +inf although the
   * passage happens a.s.  Redraw: the conditional law is the right one. */
  double z;
  do
    z = gsl_ran_gaussian_ziggurat(r, 1.0);
  while (z == 0.0);
  if (isinf(mean))
    return shape / (z * z); /* Levy */
  /* Michael, Schucany & Haas (1976): the two roots of
   * lambda (x - mean)^2 / (mean^2 x) = z^2 are x1 = mean / D and
   * x2 = mean D with D = 1 + w + sqrt(w (w + 2)), w = mean z^2/(2 shape)
   * (this form avoids the cancellation of the textbook expression); pick x1
   * with probability mean / (mean + x1) = 1 / (1 + 1/D). */
  double w = mean * z * z / (2.0 * shape);
  double root = w > 1.0 ? w * sqrt(1.0 + 2.0 / w) : sqrt(w * (w + 2.0));
  double D = 1.0 + w + root;
  double u = gsl_rng_uniform(r);
  return u * (1.0 + 1.0 / D) <= 1.0 ? mean / D : mean * D;
}

double sbi_ig_quantile_guess(double p, int upper, double phi)
{
  /* (a) First term only: Phi(c) = p (lower) or Q(c) = p (upper), with
   *     c = sqrt(phi/s)(s - 1): sqrt(s) solves u^2 - k u - 1 = 0,
   *     k = z / sqrt(phi).
   * (b) Levy approximation (drift neglected): P(S <= s) = 2 Q(sqrt(phi/s)).
   * The smaller of the two is within a small factor over the whole range
   * of phi and p (checked in tests/test_passage.c by iteration counts). */
  if (p <= 0.0)
    return upper ? INFINITY : 0.0;
  double z = upper ? gsl_cdf_ugaussian_Qinv(p) : gsl_cdf_ugaussian_Pinv(p);
  double k = z / sqrt(phi), r = sqrt(k * k + 4.0);
  double su = k >= 0.0 ? 0.5 * (k + r) : 2.0 / (r - k);
  double sn = su * su;
  double zl;
  if (!upper)
    zl = gsl_cdf_ugaussian_Qinv(0.5 * p);
  else
    zl = p < 1e-8 ? p * 1.2533141373155002512 /* sqrt(pi/2) */
                  : gsl_cdf_ugaussian_Pinv(0.5 + 0.5 * p);
  double sl = phi / (zl * zl);
  return sn < sl ? sn : sl;
}

double sbi_ig_quantile_start(double p, int upper, double phi, double pi)
{
  if (p <= 0.0)
    return upper ? INFINITY : 0.0;
  /* P(S <= 1) = 1/2 + (1 - 2 pi) M(2 sqrt phi) (F_IG(1) = 1/2 + M, SBF(1)
   * = 1/2 - M) decides the branch (S < 1: the root 1/D, else D) */
  double f1 = 0.5 + (1.0 - 2.0 * pi) * sbi_mills(2.0 * sqrt(phi));
  int low;
  double P;
  if (!upper) {
    low = p <= f1;
    P = low ? p : 1.0 - p;
  } else {
    low = p > 1.0 - f1;
    P = low ? 1.0 - p : p;
  }
  /* branch weights: IG lower D/(1+D), upper 1/(1+D); size-biased swapped */
  double W = 0.5, z = 0.0, D = 1.0;
  for (int it = 0; it < 3; it++) {
    double q = 0.5 * P / W;
    z = q < 0.5 ? gsl_cdf_ugaussian_Qinv(q) : 0.0;
    if (it == 2)
      break;
    /* mean excess of chi2(1) beyond z^2, fitted to 1e-2 */
    double y = z * z + 2.0 - 1.0 / (1.0 + z * (0.8 + 0.6 * z));
    double w = y / (2.0 * phi);
    D = 1.0 + w + sqrt(w * (w + 2.0));
    W = (low ? (1.0 - pi) * D + pi : (1.0 - pi) + pi * D) / (1.0 + D);
  }
  double w = z * z / (2.0 * phi);
  D = 1.0 + w + (w > 1.0 ? w * sqrt(1.0 + 2.0 / w) : sqrt(w * (w + 2.0)));
  return low ? 1.0 / D : D;
}

/* --------------------------------------------------- monotone solver */

/* Bracket and fallback steps of the two monotone solvers below. */
typedef struct {
  double lo, hi;      /* g(lo) < 0, g(hi) > 0 (infinite: not found yet) */
  double up, dn, cap; /* expansion steps up and down, unbracketed cap */
} guard;

/* Replace the Newton-type step y -> *yn (newton: it is usable) when it is
 * unusable, out of the bracket or not converging fast enough (step not
 * halving every two iterations: |*yn - y| > before / 2): bisect, or expand
 * toward the sign change; an unbracketed long step from a flat region is
 * capped.  Returns 1 when *yn was replaced. */
static int safeguard(guard *s, int newton, double y, double gy,
                     double before, double *yn)
{
  int bracketed = isfinite(s->lo) && isfinite(s->hi);
  if (!newton || !(*yn > s->lo && *yn < s->hi) ||
      (bracketed && fabs(*yn - y) > 0.5 * before)) {
    if (bracketed)
      *yn = 0.5 * (s->lo + s->hi);
    else if (gy < 0.0) {
      *yn = y + s->up;
      s->up *= 2.0;
    } else {
      *yn = y - s->dn;
      s->dn *= 2.0;
    }
    return 1;
  }
  if (!bracketed && fabs(*yn - y) > s->cap) {
    *yn = *yn > y ? y + s->cap : y - s->cap;
    s->cap *= 2.0;
    return 1;
  }
  return 0;
}

/* Store the solver's result: *root = r, *dy = d (if dy), return status. */
static int solved(double *root, double *dy, double r, double d, int status)
{
  *root = r;
  if (dy)
    *dy = d;
  return status;
}

int sbi_solve_increasing(sbi_fdf g, void *ctx, double y0, double step,
                         double tol, double *root, double *dy)
{
  const int maxit = 100;
  const double gacc = 1e-10;
  guard s = {-INFINITY, INFINITY, step, step, 4.0 * step};
  double y = y0, d = 0.0, d2 = NAN;
  double gy = g(y, ctx, &d, &d2);
  double last = INFINITY, before = INFINITY;
  double best = y, gbest = fabs(gy);

  for (int it = 0; it < maxit; it++) {
    if (gy == 0.0)
      return solved(root, dy, y, 0.0, SB_SUCCESS);
    if (fabs(gy) < gbest) {
      gbest = fabs(gy);
      best = y;
    }
    if (gy < 0.0)
      s.lo = y;
    else
      s.hi = y;
    int newton = isfinite(gy) && isfinite(d) && d > 0.0;
    double yn = NAN;
    if (newton) {
      yn = y - gy / d;
      if (isfinite(d2)) {
        /* Halley: y - 2 g g' / (2 g'^2 - g g''), if the denominator is
         * safely positive (else plain Newton) */
        double den = 2.0 * d * d - gy * d2;
        if (den > d * d)
          yn = y - 2.0 * gy * d / den;
      }
    }
    /* converged: the correction is below tol or g is small enough that
     * the correction is final (checked before the bracket test: a sub-ulp
     * correction may land on the bracket end) */
    if (newton && (fabs(yn - y) <= tol || fabs(gy) <= gacc))
      return solved(root, dy, yn, fabs(yn - y), SB_SUCCESS);
    int bracketed = isfinite(s.lo) && isfinite(s.hi);
    safeguard(&s, newton, y, gy, before, &yn);
    if (bracketed && s.hi - s.lo <= tol)
      return solved(root, dy, best, s.hi - s.lo, SB_SUCCESS);
    before = last;
    last = fabs(yn - y);
    y = yn;
    d2 = NAN;
    gy = g(y, ctx, &d, &d2);
  }
  return solved(root, dy, best, last, SB_EMAXITER);
}

int sbi_solve_increasing4(sbi_fdf4 g, void *ctx, double y0, double step,
                          double *root, double *dy)
{
  const int maxit = 100;
  const double tol = 1e-14; /* bracket width at which bisection stops */
  guard s = {-INFINITY, INFINITY, step, step, 4.0 * step};
  double y = y0, d[4] = {NAN, NAN, NAN, 0.0};
  double gy = g(y, INFINITY, ctx, d);
  double last = INFINITY, before = INFINITY;
  double best = y, gbest = INFINITY;

  for (int it = 0; it < maxit; it++) {
    int final = d[3] != 0.0;
    if (gy == 0.0 && final)
      return solved(root, dy, y, 0.0, SB_SUCCESS);
    if (final && fabs(gy) < gbest) {
      gbest = fabs(gy);
      best = y;
    }
    if (gy < 0.0)
      s.lo = y;
    else if (gy > 0.0)
      s.hi = y;
    int newton = isfinite(gy) && isfinite(d[0]) && d[0] > 0.0;
    double yn = NAN, k = INFINITY;
    if (newton) {
      double r = gy / d[0], a2 = d[1] / d[0], a3 = d[2] / d[0];
      yn = y - r;
      if (isfinite(a2)) {
        double sc = fmax(1.0, fabs(a2)), c2 = 0.5 * a2 * r, c3 = NAN;
        if (isfinite(a3)) {
          sc = fmax(sc, sqrt(fabs(a3)));
          c3 = (3.0 * a2 * a2 - a3) * r * r / 6.0;
        }
        k = fabs(r) * sc;
        if (isfinite(c3) && fabs(c2) + fabs(c3) <= 0.25) {
          yn = y - r * (1.0 + c2 + c3);
          if (fabs(r) * k * k * k <= 1e-18) {
            if (final)
              return solved(root, dy, yn, 4.0 * fabs(r) * k * k * k,
                            SB_SUCCESS);
            /* close enough: one final-accuracy value at yn decides */
            y = yn;
            gy = g(y, 0.0, ctx, d);
            continue;
          }
        } else if (2.0 - a2 * r > 1.0) {
          yn = y - 2.0 * r / (2.0 - a2 * r); /* Halley */
        }
      }
    }
    int bracketed = isfinite(s.lo) && isfinite(s.hi);
    if (safeguard(&s, newton, y, gy, before, &yn))
      k = INFINITY;
    if (bracketed && s.hi - s.lo <= tol * fmax(1.0, fabs(y)))
      return solved(root, dy, isfinite(gbest) ? best : 0.5 * (s.lo + s.hi),
                    s.hi - s.lo, SB_SUCCESS);
    before = last;
    last = fabs(yn - y);
    y = yn;
    gy = g(y, k, ctx, d);
  }
  return solved(root, dy, best, last, SB_EMAXITER);
}

/* f behind a guard: a non-finite value is remembered and replaced by 0
 * (Brent then stops at once: the caller reports SB_EDOM), so GSL's
 * SAFE_FUNC_CALL never reaches the error handler. */
typedef struct {
  const gsl_function *f;
  int bad;
} guarded_fn;

static double guarded(double x, void *p)
{
  guarded_fn *g = p;
  double y = GSL_FN_EVAL(g->f, x);
  if (isfinite(y))
    return y;
  g->bad = 1;
  return 0.0;
}

int sbi_brent(const gsl_function *f, double lo, double hi, double epsabs,
              double epsrel, int maxit, double *root)
{
  *root = NAN;
  const double flo = GSL_FN_EVAL(f, lo), fhi = GSL_FN_EVAL(f, hi);
  if (!isfinite(flo) || !isfinite(fhi))
    return SB_EDOM;
  if (flo == 0.0 || fhi == 0.0) {
    *root = flo == 0.0 ? lo : hi;
    return SB_SUCCESS;
  }
  if ((flo > 0.0) == (fhi > 0.0) || !(lo < hi))
    return SB_EINVAL;
  gsl_root_fsolver *s = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
  if (!s)
    return SB_ENOMEM;
  guarded_fn g = {f, 0};
  gsl_function G = {guarded, &g};
  /* a finite bracket of opposite signs: set() raises no error */
  gsl_root_fsolver_set(s, &G, lo, hi);
  int st = SB_EMAXITER;
  for (int it = 0; it < maxit; it++) {
    gsl_root_fsolver_iterate(s);
    *root = gsl_root_fsolver_root(s);
    if (g.bad) {
      st = SB_EDOM;
      *root = NAN;
      break;
    }
    if (gsl_root_test_interval(gsl_root_fsolver_x_lower(s),
                               gsl_root_fsolver_x_upper(s), epsabs,
                               epsrel) == GSL_SUCCESS) {
      st = SB_SUCCESS;
      break;
    }
  }
  gsl_root_fsolver_free(s);
  return st;
}

/* f(a + 1/u^2) 2/u^3: [a + 1, inf) onto (0, 1].  A tail x^-p becomes
 * u^(2p - 3), smooth for p = 3/2 and 2 (the tails of the library's
 * integrands), integrable for p > 1; exponential tails vanish at u = 0. */
typedef struct {
  const gsl_function *f;
  double a;
} semi_inf;

static double semi_inf_fn(double u, void *p)
{
  const semi_inf *q = p;
  if (!(u > 0.0))
    return 0.0;
  const double x = q->a + 1.0 / (u * u);
  if (isinf(x))
    return 0.0;
  return GSL_FN_EVAL(q->f, x) * 2.0 / (u * u * u);
}

int sbi_integrate(const gsl_function *f, double a, double b, double epsabs,
                  double epsrel, size_t n, double *res, double *err)
{
  *res = *err = NAN;
  gsl_integration_cquad_workspace *ws =
      gsl_integration_cquad_workspace_alloc(n < 3 ? 3 : n);
  if (!ws)
    return SB_ENOMEM;
  int st;
  if (isinf(b)) { /* [a, a + 1] and the mapped tail */
    semi_inf q = {f, a};
    gsl_function S = {semi_inf_fn, &q};
    double r1, e1, r2, e2;
    st = gsl_integration_cquad(f, a, a + 1.0, epsabs, epsrel, ws, &r1, &e1,
                               NULL);
    if (!st)
      st = gsl_integration_cquad(&S, 0.0, 1.0, epsabs, epsrel, ws, &r2, &e2,
                                 NULL);
    if (!st)
      *res = r1 + r2, *err = e1 + e2;
  } else {
    st = gsl_integration_cquad(f, a, b, epsabs, epsrel, ws, res, err, NULL);
  }
  gsl_integration_cquad_workspace_free(ws);
  if (st)
    return SB_ERANGE; /* GSL_EDIVERGE: the only status left */
  return *err <= fmax(epsabs, epsrel * fabs(*res)) ? SB_SUCCESS
                                                    : SB_EMAXITER;
}

int sbi_reach_root(gsl_function *f, double hi0, double hi_max, double xtol,
                   double *root)
{
  *root = NAN;
  double hi = hi0, fh;
  while ((fh = GSL_FN_EVAL(f, hi)) > 0.0 || isnan(fh)) {
    hi *= 2.0;
    if (isnan(fh) || hi > hi_max)
      return SB_EMAXITER;
  }
  /* the bracket's upper end, where f <= 0, is the conservative reach:
   * run Brent by hand to read it */
  gsl_root_fsolver *s = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
  if (!s)
    return SB_ENOMEM;
  guarded_fn g = {f, 0};
  gsl_function G = {guarded, &g};
  /* f(0) > 0 >= f(hi) (a non-finite f(0) reads 0 and is reported below):
   * set() raises no error */
  gsl_root_fsolver_set(s, &G, 0.0, hi);
  double up = hi;
  for (int it = 0; it < 200 && !g.bad; it++) {
    gsl_root_fsolver_iterate(s);
    double lo = gsl_root_fsolver_x_lower(s);
    up = gsl_root_fsolver_x_upper(s);
    if (gsl_root_test_interval(lo, up, 0.0, xtol) == GSL_SUCCESS)
      break;
  }
  gsl_root_fsolver_free(s);
  if (g.bad)
    return SB_EDOM;
  *root = up;
  return SB_SUCCESS;
}

double sbi_sphere_integral(double (*fn)(const double n[3], void *ctx),
                           void *ctx, size_t nmu, int nphi, double phase)
{
  gsl_integration_glfixed_table *tb =
      gsl_integration_glfixed_table_alloc(nmu);
  if (!tb)
    return NAN;
  const double pi = 3.14159265358979323846;
  double sum = 0.0;
  for (size_t i = 0; i < nmu; i++) {
    double mu, wmu;
    gsl_integration_glfixed_point(-1.0, 1.0, i, &mu, &wmu, tb);
    const double st = sqrt(1.0 - mu * mu);
    double sp = 0.0;
    for (int j = 0; j < nphi; j++) {
      const double ph = 2.0 * pi * (j + phase) / nphi;
      const double n[3] = {st * cos(ph), st * sin(ph), mu};
      sp += fn(n, ctx);
    }
    sum += wmu * sp * 2.0 * pi / nphi;
  }
  gsl_integration_glfixed_table_free(tb);
  return sum;
}
