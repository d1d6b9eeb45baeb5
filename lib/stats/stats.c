/* stats.c — confidence intervals (Garwood, Clopper-Pearson, Student t),
 * exact Poisson and binomial tests, z-scores, chi-square goodness of fit.
 * The Kolmogorov-Smirnov tests live in stats_ks.c, the comparison records
 * of validation reports in compare.c.  Theory: docs/stats.md.
 *
 * Why the intervals do not call gsl_cdf_gamma_Pinv / gsl_cdf_beta_Pinv:
 * GSL 2.7's gamma inverse fails to converge (error handler -> abort) for
 * shapes above a few hundred at small tail probabilities, and silently
 * returns wrong values for shapes >= 3e5 (e.g. Qinv(0.025, 316229) = 166360);
 * its incomplete gamma stops converging for shapes >= 1e6, and loses
 * accuracy well before (relative error 1e-13 at shape 1e3, 4e-10 at 1e5,
 * near the median); its incomplete beta returns NaN near the centre for
 * shapes >= 1e6 and has relative errors of 1e-12 - 1e-10 once a shape
 * exceeds ~1e3 (scans in docs/stats.md).  So the quantiles are found with
 * GSL's Brent solver on gsl_cdf_gamma_P/Q, gsl_cdf_beta_P/Q while every
 * shape is <= SHAPE_GSL_MAX (relative error <= 1e-13 there), and on a
 * Gauss-Legendre quadrature of the density, written around its mode with
 * gsl_sf_log_1plusx_mx (no cancellation), beyond.  Shape-1 cases have
 * closed forms.
 */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_cdf.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <gsl/gsl_math.h>
#include <gsl/gsl_roots.h>
#include <gsl/gsl_sf_gamma.h>
#include <gsl/gsl_sf_log.h>
#include <gsl/gsl_statistics_double.h>

#include "common/internal.h"
#include <smolbridge/stats.h>

/* Largest gamma/beta shape handed to GSL's CDFs. */
#define SHAPE_GSL_MAX 200.0
/* Quadrature: a tail is integrated from x outwards in scaled form
 * (law_scaled_tail); the beta law's normalisation over mode -+ QUAD_S
 * sigma, the distances doubled (up to the support's ends) until the log
 * density relative to the mode is below -QUAD_LOGCUT (the gamma law's is
 * a closed form).  Pieces of QUAD_H local scales, QUAD_N-point
 * Gauss-Legendre rules: with shapes >= 2 the integrand is smooth on the
 * support and varies on that scale, so each piece is exact to rounding
 * (checked against mpmath in the tests). */
#define QUAD_S 15.0
#define QUAD_LOGCUT 100.0
#define QUAD_H 2.0
#define QUAD_N 20
/* Scaled tail integrals (law_scaled_tail) stop where the integrand is
 * below e^-TAIL_LOGCUT of its start (the rest is < 4e-18 of the total);
 * they need about TAIL_LOGCUT/QUAD_H + 10 pieces, the cap only guards
 * against a loop that makes no progress. */
#define TAIL_LOGCUT 40.0
#define TAIL_MAXPIECES 4096
#define ROOT_MAXITER 400

/* ------------------------------------------------------------------ laws */

/* A gamma(a, scale 1) or beta(a, b) law whose tails we invert. */
typedef struct {
  int beta;      /* 0: gamma(a); 1: beta(a, b) */
  double a, b;
  int quad;      /* 1: tails by quadrature (large shapes) */
  double mode, om, sig; /* quadrature: mode, 1 - mode (beta), scale */
  double z;      /* integral of g (density / density at the mode) */
  gsl_integration_glfixed_table *gl;
  int bad;       /* set if a CDF returned NaN (never seen; defensive) */
} law_t;

/* (c - 1) [log(y) - (y - 1)] for y = t/m > 0, with d = t - m: written as
 * c' lpmx(d/m) near the mode (d exact there by Sterbenz's lemma) and
 * directly far from it, where nothing cancels. */
static double log_factor(double cm1, double d, double m, double y)
{
  if (!(y > 0.0))
    return -HUGE_VAL; /* at or beyond the support's end: density 0 */
  if (fabs(y - 1.0) < 0.5)
    return cm1 * gsl_sf_log_1plusx_mx(d / m);
  return cm1 * (log(y) - (y - 1.0));
}

/* log(g) with g = density / density(mode).  gamma: t^(a-1) e^-t;
 * beta: t^(a-1) (1-t)^(b-1); the linear terms cancel at the mode. */
static double law_logg(const law_t *L, double t)
{
  double m = L->mode;
  double e = log_factor(L->a - 1.0, t - m, m, t / m);
  if (L->beta)
    e += log_factor(L->b - 1.0, m - t, L->om, (1.0 - t) / L->om);
  return e;
}

static double law_g(double t, void *p) { return exp(law_logg(p, t)); }

/* Integral of g over [t0, t1] in pieces of QUAD_H sigma. */
static double law_int(const law_t *L, double t0, double t1)
{
  gsl_function F = {law_g, (void *)L};
  double w = t1 - t0;
  if (!(w > 0.0))
    return 0.0;
  double np = ceil(w / (QUAD_H * L->sig));
  double h = w / np, sum = 0.0;
  for (double i = 0; i < np; i++) {
    double a = t0 + i * h, b = (i == np - 1) ? t1 : t0 + (i + 1) * h;
    sum += gsl_integration_glfixed(&F, a, b, L->gl);
  }
  return sum;
}

/* End of the quadrature range on one side (dir = +-1): mode + dir QUAD_S
 * sigma, the distance doubled until the log density is below -QUAD_LOGCUT,
 * clipped to the support's end `lim`. */
static double law_cut(const law_t *L, double dir, double lim)
{
  double w = QUAD_S * L->sig, t = L->mode;
  /* 64 doublings reach 2^64 sigma: far beyond any log density of -100 for
   * shapes >= 2; the cap only guards against a non-terminating loop. */
  for (int i = 0; i < 64; i++, w *= 2.0) {
    t = L->mode + dir * w;
    if (dir * (t - lim) >= 0.0)
      return lim;
    if (law_logg(L, t) < -QUAD_LOGCUT)
      return t;
  }
  return t;
}

/* Set up L; returns SB_ENOMEM if the quadrature table cannot be made. */
static int law_init(law_t *L, int beta, double a, double b)
{
  memset(L, 0, sizeof *L);
  L->beta = beta;
  L->a = a;
  L->b = b;
  /* quad mode requires shapes >= 2 (callers use closed forms for 1) */
  L->quad = beta ? (a > SHAPE_GSL_MAX || b > SHAPE_GSL_MAX)
                 : (a > SHAPE_GSL_MAX);
  if (!L->quad)
    return SB_SUCCESS;
  if (!beta) {
    L->mode = a - 1.0;
    L->sig = sqrt(L->mode);
  } else {
    double c = a + b - 2.0;
    L->mode = (a - 1.0) / c;
    L->om = (b - 1.0) / c;
    L->sig = sqrt(L->mode * L->om / c);
  }
  L->gl = gsl_integration_glfixed_table_alloc(QUAD_N);
  if (!L->gl)
    return SB_ENOMEM;
  if (!beta) {
    /* z = Gamma(a) e^m / m^m with m = a - 1, from GSL's
     * gamma*(a) = Gamma(a) / (sqrt(2 pi) a^(a-1/2) e^-a):
     * z = sqrt(2 pi a) gamma*(a) e^(-1 - (a-1) log(1 - 1/a)).  Exact to
     * rounding at every shape, unlike a quadrature whose nodes are rounded
     * to the grid of doubles near m (relative error ~1e-16 z sqrt(a) at
     * z sigma) or lgamma(a) - m log(m) + m (cancels). */
    L->z = sqrt(2.0 * M_PI) * sqrt(a) * gsl_sf_gammastar(a) *
           exp(-1.0 - (a - 1.0) * log1p(-1.0 / a));
  } else {
    double tlo = law_cut(L, -1.0, 0.0), thi = law_cut(L, 1.0, 1.0);
    L->z = law_int(L, tlo, L->mode) + law_int(L, L->mode, thi);
    /* a law narrower than the grid of doubles at its mode (callers flip
     * those, beta_flip); never go on with a zero or NaN normalisation */
    if (!(L->z > 0.0 && isfinite(L->z)))
      return SB_ESOLVER;
  }
  return SB_SUCCESS;
}

/* Beta(a, b) with its mass crowded against 1 (1 - mode < 2^-26): its tails
 * and quantiles are taken from the mirror law Beta(b, a) at 1 - x, where
 * doubles are dense (near 1 their spacing, 1.1e-16, can exceed the width
 * of the law: n > 2^53 trials with k near n).  The threshold leaves every
 * law with both shapes <= SHAPE_GSL_MAX, and all but such crowded ones,
 * as they were. */
static int beta_flip(double a, double b)
{
  return a > b && (b - 1.0) / (a + b - 2.0) < 0x1p-26;
}

static void law_free(law_t *L)
{
  if (L->gl)
    gsl_integration_glfixed_table_free(L->gl);
  L->gl = NULL;
}

/* log g(x + s) - log g(x), written without cancellation: with
 * lpmx(u) = log(1 + u) - u and the slope phi1 = (log g)'(x),
 *   gamma: (a-1) lpmx(s/x) + s phi1,
 *   beta:  (a-1) lpmx(s/x) + (b-1) lpmx(-s/(1-x)) + s phi1;
 * every term has the sign of the whole for s pointing away from the mode,
 * so the relative error is a few ulp however far x is from the mode.
 * -inf at or beyond the support's end. */
static double law_dlogg(const law_t *L, double x, double phi1, double s)
{
  double u = s / x;
  if (!(u > -1.0))
    return -HUGE_VAL;
  double e = (L->a - 1.0) * gsl_sf_log_1plusx_mx(u) + s * phi1;
  if (L->beta) {
    double v = -s / (1.0 - x);
    if (!(v > -1.0))
      return -HUGE_VAL;
    e += (L->b - 1.0) * gsl_sf_log_1plusx_mx(v);
  }
  return e;
}

/* (log g)'(t) and sqrt(-(log g)''(t)) at 0 < t (< 1 for beta), written
 * so that neither overflows before the true value does; the numerator of
 * the slope has one rounding (fma), so its sign is right near the mode. */
static void law_slope(const law_t *L, double t, double *phi1, double *root2)
{
  double a1 = L->a - 1.0;
  if (!L->beta) {
    *phi1 = (a1 - t) / t;
    *root2 = sqrt(a1) / t;
  } else {
    double b1 = L->b - 1.0, w = 1.0 - t;
    *phi1 = fma(-(a1 + b1), t, a1) / t / w;
    *root2 = hypot(sqrt(a1) / t, sqrt(b1) / w);
  }
}

typedef struct {
  const law_t *L;
  double x, phi1;
} dlogg_par;

/* g(x + s)/g(x) as a function of the offset s: nodes placed in s, not in
 * t = x + s, keep their full relative precision (a node rounded to the
 * grid of doubles near x would move g by |phi'| ulp(x), ~1e-12 at
 * shapes ~1e6). */
static double law_gratio(double s, void *vp)
{
  const dlogg_par *p = vp;
  return exp(law_dlogg(p->L, p->x, p->phi1, s));
}

/* Tail mass of the law beyond x, away from the mode (dir = +1: above x,
 * up to the support's end lim; dir = -1: below x, down to lim = 0), in
 * scaled form: Q = g(x)/z * I with I = integral of g(x + s)/g(x) over s
 * from 0 outwards, an O(1/|slope|) to O(sigma) integral whatever the size
 * of Q.  I is integrated in pieces of QUAD_H local scales
 * (1/max(|phi'|, sqrt(-phi''))), on which g falls by ~e^-2 at most, with
 * QUAD_N-point Gauss-Legendre rules, until g(x + s)/g(x) < e^-TAIL_LOGCUT
 * (the rest is below e^-TAIL_LOGCUT of I, log g being concave).  The
 * product is formed in log space, so Q is right down to the smallest
 * subnormal and 0 below it. */
static double law_scaled_tail(const law_t *L, double x, double dir,
                              double lim)
{
  double lg = law_logg(L, x), phi1, root2;
  if (!(lg > -HUGE_VAL))
    return 0.0;
  double lq = lg - log(L->z); /* log of the density at x, normalised */
  law_slope(L, x, &phi1, &root2);
  /* I <= 1/|phi'(x)| (log g is concave): below this bound Q is under
   * half the smallest subnormal and rounds to 0. */
  if (dir * phi1 < 0.0 && lq - log(fabs(phi1)) < log(DBL_TRUE_MIN) - 1.0)
    return 0.0;
  dlogg_par par = {L, x, phi1};
  gsl_function F = {law_gratio, &par};
  double slim = lim - x, s = 0.0, sum = 0.0;
  for (int i = 0; i < TAIL_MAXPIECES; i++) {
    double p1, r2;
    law_slope(L, x + s, &p1, &r2);
    double s1 = s + dir * QUAD_H / fmax(fabs(p1), r2);
    if (dir * (s1 - slim) >= 0.0)
      s1 = slim;
    if (s1 == s) /* no room left in double precision */
      break;
    sum += dir * gsl_integration_glfixed(&F, s, s1, L->gl);
    s = s1;
    if (s == slim || law_dlogg(L, x, phi1, s) < -TAIL_LOGCUT)
      break;
  }
  return sum > 0.0 ? exp(lq + log(sum)) : 0.0;
}

/* Lower (upper = 0) or upper tail probability at x.  The tail away from
 * the mode is integrated directly (scaled form); the other is its
 * complement (>= ~1/2, no loss). */
static double law_tail(law_t *L, double x, int upper)
{
  double v;
  if (!L->quad) {
    if (!L->beta)
      v = upper ? gsl_cdf_gamma_Q(x, L->a, 1.0) : gsl_cdf_gamma_P(x, L->a, 1.0);
    else
      v = upper ? gsl_cdf_beta_Q(x, L->a, L->b) : gsl_cdf_beta_P(x, L->a, L->b);
    if (!isfinite(v)) {
      L->bad = 1;
      v = 0.5;
    }
    return v;
  }
  if (x <= L->mode) {
    double lt = law_scaled_tail(L, x, -1.0, 0.0);
    return upper ? 1.0 - lt : lt;
  }
  double ut = law_scaled_tail(L, x, 1.0, L->beta ? 1.0 : HUGE_VAL);
  return upper ? ut : 1.0 - ut;
}

typedef struct {
  law_t *L;
  int upper;
  double target;
} root_par;

/* Increasing in x: P(x) - target, or target - Q(x). */
static double root_fn(double x, void *vp)
{
  root_par *rp = vp;
  double t = law_tail(rp->L, x, rp->upper);
  return rp->upper ? rp->target - t : t - rp->target;
}

/* x with lower tail P(x) = target (upper = 0) or upper tail Q(x) = target,
 * 0 < target < 1.  Brackets by doubling steps from the mean (the function is
 * finite everywhere and has the right sign at the support's ends), then
 * refines with GSL's Brent solver to 4 ulp. */
static int law_quantile(law_t *L, int upper, double target, double *x)
{
  root_par rp = {L, upper, target};
  gsl_function F = {root_fn, &rp};
  double mean, sd, xmax;
  if (!L->beta) {
    mean = L->a;
    sd = sqrt(L->a);
    xmax = HUGE_VAL;
  } else {
    double c = L->a + L->b;
    mean = L->a / c;
    sd = sqrt(L->a * L->b / (c * c * (c + 1.0)));
    xmax = 1.0;
  }
  double lo = mean, hi = mean, flo, fhi;
  double f0 = root_fn(mean, &rp);
  if (f0 == 0.0) {
    *x = mean;
    return SB_SUCCESS;
  }
  if (f0 < 0.0) { /* root above the mean */
    flo = f0;
    for (double step = sd;; step *= 2.0) {
      hi = mean + step;
      if (hi >= xmax) {
        hi = xmax;
        fhi = upper ? target : 1.0 - target; /* tails at the support end */
        break;
      }
      fhi = root_fn(hi, &rp);
      if (fhi >= 0.0)
        break;
      lo = hi;
      flo = fhi;
    }
  } else { /* root below the mean */
    fhi = f0;
    for (double step = sd;; step *= 2.0) {
      lo = mean - step;
      if (lo <= 0.0) {
        lo = 0.0;
        flo = upper ? target - 1.0 : -target;
        break;
      }
      flo = root_fn(lo, &rp);
      if (flo <= 0.0)
        break;
      hi = lo;
      fhi = flo;
    }
  }
  if (L->bad)
    return SB_ESOLVER;
  if (flo == 0.0 || fhi == 0.0) {
    *x = flo == 0.0 ? lo : hi;
    return SB_SUCCESS;
  }
  if (isinf(hi)) /* unreachable: the doubling stops before overflow */
    return SB_ESOLVER;

  /* GSL's handler would abort on a bracket without a sign change (only
   * NaN tails could give one; defensive) */
  if (!(flo < 0.0 && fhi > 0.0))
    return SB_ESOLVER;
  gsl_root_fsolver *s = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
  if (!s)
    return SB_ENOMEM;
  gsl_root_fsolver_set(s, &F, lo, hi); /* signs checked above */
  int status = SB_EMAXITER;
  for (int it = 0; it < ROOT_MAXITER; it++) {
    gsl_root_fsolver_iterate(s);
    if (L->bad)
      break;
    double a = gsl_root_fsolver_x_lower(s), b = gsl_root_fsolver_x_upper(s);
    if (gsl_root_test_interval(a, b, DBL_MIN, 4 * DBL_EPSILON) == GSL_SUCCESS) {
      status = SB_SUCCESS;
      break;
    }
  }
  *x = gsl_root_fsolver_root(s);
  gsl_root_fsolver_free(s);
  return L->bad ? SB_ESOLVER : status;
}

/* Quantile of gamma(a) or beta(a, b); quad tables freed before return. */
static int quantile(int beta, double a, double b, int upper, double target,
                    double *x)
{
  if (beta && beta_flip(a, b)) { /* X ~ Beta(a, b) iff 1 - X ~ Beta(b, a) */
    double y = NAN;
    int st = quantile(1, b, a, !upper, target, &y);
    *x = 1.0 - y;
    return st;
  }
  law_t L;
  int st = law_init(&L, beta, a, b);
  if (st == SB_SUCCESS)
    st = law_quantile(&L, upper, target, x);
  law_free(&L);
  return st;
}

static int bad_level(double level) { return !(level > 0.0 && level < 1.0); }

static void set_nan2(double *a, double *b)
{
  if (a)
    *a = NAN;
  if (b)
    *b = NAN;
}

/* -------------------------------------------------------------- Poisson */

int sb_poisson_ci(unsigned long k, double level, double *lo, double *hi)
{
  if (!lo || !hi) {
    set_nan2(lo, hi);
    return sbi_error(SB_EINVAL, __func__, "NULL output pointer");
  }
  if (bad_level(level)) {
    set_nan2(lo, hi);
    return sbi_error(SB_EINVAL, __func__, "level = %g not in (0,1)", level);
  }
  double t = 0.5 * (1.0 - level), kd = (double)k;
  int st = SB_SUCCESS, st2;
  if (k == 0) {
    *lo = 0.0;
    *hi = -log(t); /* P(X = 0 | mu) = exp(-mu) = t */
    return SB_SUCCESS;
  }
  /* P(X >= k | mu) = P_gamma(k; mu),  P(X <= k | mu) = Q_gamma(k+1; mu). */
  if (k == 1)
    *lo = -log1p(-t); /* 1 - exp(-mu) = t */
  else
    st = quantile(0, kd, 0.0, 0, t, lo);
  st2 = quantile(0, kd + 1.0, 0.0, 1, t, hi);
  if (st == SB_SUCCESS)
    st = st2;
  if (st != SB_SUCCESS) {
    set_nan2(lo, hi);
    return sbi_error(st, __func__, "root finding failed for k = %lu", k);
  }
  return SB_SUCCESS;
}

int sb_poisson_rate_ci(unsigned long k, double scale, double level,
                       double *lo, double *hi)
{
  if (!(scale > 0.0 && isfinite(scale))) {
    set_nan2(lo, hi);
    return sbi_error(SB_EINVAL, __func__, "scale = %g must be finite > 0",
                     scale);
  }
  int st = sb_poisson_ci(k, level, lo, hi);
  if (st == SB_SUCCESS) {
    *lo *= scale;
    *hi *= scale;
    if (isinf(*hi)) { /* underflow of lo (to 0 at worst) is no error */
      set_nan2(lo, hi);
      return sbi_error(SB_ERANGE, __func__, "scale * hi overflows (k = %lu, "
                       "scale = %g)", k, scale);
    }
  }
  return st;
}

int sb_poisson_ci_dispersed(unsigned long k, double dispersion, double level,
                            double *lo, double *hi)
{
  if (dispersion == HUGE_VAL) {
    set_nan2(lo, hi);
    return sbi_error(SB_EINVAL, __func__, "dispersion = inf (k = %lu)", k);
  }
  int st = sb_poisson_ci(k, level, lo, hi);
  if (st || !(dispersion > 1.0))
    return st;
  const double w = sqrt(dispersion), K = (double)k;
  *lo = K - w * (K - *lo);
  *hi = K + w * (*hi - K);
  if (*lo < 0.0)
    *lo = 0.0;
  return SB_SUCCESS;
}

double sb_pair_count_variance(double H, double S2, double sqa, double na,
                              double sqb, double nb, double P)
{
  if (!isfinite(H) || !isfinite(S2) || !isfinite(sqa) || isnan(na) ||
      isnan(P) || isnan(nb) || (nb > 0.0 && !isfinite(sqb))) {
    sbi_error(SB_EDOM, __func__, "need finite H, S2, sqa (and sqb if nb > "
              "0), na, nb, P not NaN (H = %g, S2 = %g, sqa = %g, na = %g, "
              "sqb = %g, nb = %g, P = %g)", H, S2, sqa, na, sqb, nb, P);
    return NAN;
  }
  if (!(na > 0.0) || !(P > 0.0))
    return H > 0.0 ? NAN : 0.0;
  /* the raw sum has mean f var(H): its H^2 terms also hold var(H) */
  double v, f;
  if (!(nb > 0.0)) {  /* sum_i (h_i - 2H/n)^2 */
    v = sqa - 4.0 * H * H / na;
    f = 1.0 - 4.0 / na + 1.0 / P;
  } else {
    v = (sqa - H * H / na) + (sqb - H * H / nb);
    f = 1.0 - 1.0 / na - 1.0 / nb + 1.0 / P;
  }
  v += -S2 + H * H / P;
  if (!(f > 0.0))
    return H > 0.0 ? NAN : 0.0;
  if (!isfinite(v)) {
    /* H^2 (or a sum of squares) overflowed: the same sums with H scaled by
     * 2^-e and the squares by 2^-2e (exact), the result scaled back */
    int e;
    double big = fmax(fmax(fabs(H), sqrt(fabs(sqa))), fmax(sqrt(fabs(S2)),
                      nb > 0.0 ? sqrt(fabs(sqb)) : 0.0));
    frexp(big, &e);
    double Hs = ldexp(H, -e), as = ldexp(sqa, -2 * e), Ss = ldexp(S2, -2 * e);
    if (!(nb > 0.0))
      v = as - 4.0 * Hs * Hs / na;
    else
      v = (as - Hs * Hs / na) + (ldexp(sqb, -2 * e) - Hs * Hs / nb);
    v += -Ss + Hs * Hs / P;
    v = v > 0.0 ? ldexp(v / f, 2 * e) : 0.0;
    if (!isfinite(v)) { /* var(H) overflows, or H^2/P and 1/P both do */
      sbi_error(SB_ERANGE, __func__, "var(H) or an intermediate overflows "
                "(H = %g, sqa = %g, P = %g, divisor %g)", H, sqa, P, f);
      return NAN;
    }
    return v;
  }
  v = v > 0.0 ? v / f : 0.0;
  if (isinf(v)) { /* v finite, f tiny */
    sbi_error(SB_ERANGE, __func__, "var(H) overflows (H = %g, sqa = %g, "
              "divisor %g)", H, sqa, f);
    return NAN;
  }
  return v;
}

/* Exact two-sided Poisson test: p = min(1, 2 min(P(X <= k), P(X >= k)))
 * for X ~ Poisson(mu), from the gamma-Poisson duality
 * P(X <= k) = Q_gamma(k+1; mu), P(X >= k) = P_gamma(k; mu). */
double sb_poisson_pvalue(unsigned long k, double mu)
{
  if (!(mu >= 0.0 && isfinite(mu))) {
    sbi_error(SB_EDOM, __func__, "mu = %g must be finite and >= 0", mu);
    return NAN;
  }
  if (mu == 0.0)
    return k == 0 ? 1.0 : 0.0;
  law_t L;
  double le, ge = 1.0;
  if (law_init(&L, 0, (double)k + 1.0, 0.0) != SB_SUCCESS) {
    law_free(&L);
    sbi_error(SB_ENOMEM, __func__, "no memory for the quadrature table");
    return NAN;
  }
  le = law_tail(&L, mu, 1);
  int bad = L.bad;
  law_free(&L);
  if (k > 0) {
    if (law_init(&L, 0, (double)k, 0.0) != SB_SUCCESS) {
      law_free(&L);
      sbi_error(SB_ENOMEM, __func__, "no memory for the quadrature table");
      return NAN;
    }
    ge = law_tail(&L, mu, 0);
    bad |= L.bad;
    law_free(&L);
  }
  if (bad) {
    sbi_error(SB_ELOSS, __func__, "tail probability failed (k = %lu, mu = %g)",
              k, mu);
    return NAN;
  }
  double p = 2.0 * (le < ge ? le : ge);
  return p < 1.0 ? p : 1.0;
}

/* ------------------------------------------------------------- binomial */

/* Clopper-Pearson bounds, arguments already validated (1 <= n, k <= n). */
static int cp_bounds(unsigned long k, unsigned long n, double t, double *lo,
                     double *hi)
{
  double kd = (double)k, nd = (double)n, md = (double)(n - k);
  int st = SB_SUCCESS, st2 = SB_SUCCESS;
  /* Closed forms where a Beta shape is 1: k = 0: (1 - hi)^n = t;
   * k = 1: 1 - (1 - lo)^n = t;  k = n: lo^n = t;  k = n-1: 1 - hi^n = t. */
  if (k == 0)
    *lo = 0.0;
  else if (k == n)
    *lo = exp(log(t) / nd);
  else if (k == 1)
    *lo = -expm1(log1p(-t) / nd);
  else /* P(X >= k | p) = I_p(k, n-k+1) */
    st = quantile(1, kd, md + 1.0, 0, t, lo);
  if (k == n)
    *hi = 1.0;
  else if (k == 0)
    *hi = -expm1(log(t) / nd);
  else if (k == n - 1)
    *hi = exp(log1p(-t) / nd);
  else /* P(X <= k | p) = 1 - I_p(k+1, n-k) */
    st2 = quantile(1, kd + 1.0, md, 1, t, hi);
  return st != SB_SUCCESS ? st : st2;
}

int sb_binomial_ci(unsigned long k, unsigned long n, double level,
                   double *lo, double *hi)
{
  if (!lo || !hi) {
    set_nan2(lo, hi);
    return sbi_error(SB_EINVAL, __func__, "NULL output pointer");
  }
  if (n == 0 || k > n || bad_level(level)) {
    set_nan2(lo, hi);
    return sbi_error(SB_EINVAL, __func__,
                     "need 0 <= k <= n, n >= 1, 0 < level < 1 "
                     "(k = %lu, n = %lu, level = %g)", k, n, level);
  }
  int st = cp_bounds(k, n, 0.5 * (1.0 - level), lo, hi);
  if (st != SB_SUCCESS) {
    set_nan2(lo, hi);
    return sbi_error(st, __func__, "root finding failed (k = %lu, n = %lu)",
                     k, n);
  }
  return SB_SUCCESS;
}

/* Lower (upper = 0) or upper tail of Beta(a, b) at x in (0, 1); crowded
 * laws (beta_flip) through the mirror law at 1 - x, exact for x >= 1/2
 * (below 1/2 their lower tail is far below the smallest double: 0). */
static int beta_tail(double a, double b, double x, int upper, double *v)
{
  law_t L;
  int flip = beta_flip(a, b);
  if (flip && x < 0.5) { /* log density at 1/2 < -0.69 (a - 1) < -4e7 */
    *v = upper ? 1.0 : 0.0;
    return SB_SUCCESS;
  }
  int st = flip ? law_init(&L, 1, b, a) : law_init(&L, 1, a, b);
  if (st == SB_SUCCESS) {
    *v = flip ? law_tail(&L, 1.0 - x, !upper) : law_tail(&L, x, upper);
    if (L.bad)
      st = SB_ELOSS;
  }
  law_free(&L);
  return st;
}

/* Exact binomial tails at p, 0 < p < 1, 0 <= k <= n (n >= 1):
 * P(X >= k) = I_p(k, n-k+1) and P(X <= k) = I_{1-p}(n-k, k+1), with the
 * closed forms where a Beta shape is 1 (or the tail is the whole law). */
static int binomial_tails(unsigned long k, unsigned long n, double p,
                          double *ge, double *le)
{
  double kd = (double)k, nd = (double)n, md = (double)(n - k);
  int st;
  if (k == 0)
    *ge = 1.0;
  else if (k == 1)
    *ge = -expm1(nd * log1p(-p));
  else if (k == n)
    *ge = exp(nd * log(p));
  else if ((st = beta_tail(kd, md + 1.0, p, 0, ge)) != SB_SUCCESS)
    return st;
  if (k == n)
    *le = 1.0;
  else if (k == 0)
    *le = exp(nd * log1p(-p));
  else if (k == n - 1)
    *le = -expm1(nd * log(p));
  else if ((st = beta_tail(kd + 1.0, md, p, 1, le)) != SB_SUCCESS)
    return st;
  return SB_SUCCESS;
}

double sb_binomial_pvalue(unsigned long k, unsigned long n, double p)
{
  if (n == 0 || k > n || !(p >= 0.0 && p <= 1.0)) {
    sbi_error(SB_EDOM, __func__,
              "need n >= 1, k <= n, 0 <= p <= 1 (k = %lu, n = %lu, p = %g)",
              k, n, p);
    return NAN;
  }
  if (p == 0.0)
    return k == 0 ? 1.0 : 0.0;
  if (p == 1.0)
    return k == n ? 1.0 : 0.0;
  double ge, le;
  int st = binomial_tails(k, n, p, &ge, &le);
  if (st != SB_SUCCESS) {
    sbi_error(st, __func__, "tail probability failed (k = %lu, n = %lu, "
              "p = %g)", k, n, p);
    return NAN;
  }
  double q = 2.0 * (le < ge ? le : ge);
  return q < 1.0 ? q : 1.0;
}

/* (t2 / t1) x / y (y > 0), given f = t2 / t1 as rounded: f x / y where f
 * is a normal double (the usual case); else (t2/t1 overflowed or
 * underflowed) with the exponents apart, so that the result is right
 * wherever it is representable (and overflows or underflows otherwise). */
static double times_ratio(double x, double y, double t2, double t1, double f)
{
  if (isfinite(f) && f >= DBL_MIN)
    return f * x / y;
  if (x == 0.0)
    return 0.0;
  int e1, e2;
  double m2 = frexp(t2, &e2), m1 = frexp(t1, &e1);
  return ldexp(m2 / m1 * (x / y), e2 - e1);
}

int sb_poisson_ratio_ci(unsigned long k1, double t1, unsigned long k2,
                        double t2, double level, double *ratio, double *lo,
                        double *hi)
{
  if (ratio)
    *ratio = NAN;
  if (!lo || !hi) {
    set_nan2(lo, hi);
    return sbi_error(SB_EINVAL, __func__, "NULL output pointer");
  }
  if (!(t1 > 0.0 && isfinite(t1) && t2 > 0.0 && isfinite(t2)) ||
      bad_level(level) || k1 > (unsigned long)-1 - k2) {
    set_nan2(lo, hi);
    return sbi_error(SB_EINVAL, __func__,
                     "need finite t1, t2 > 0, 0 < level < 1, k1 + k2 "
                     "representable (t1 = %g, t2 = %g, level = %g)",
                     t1, t2, level);
  }
  unsigned long n = k1 + k2;
  double f = t2 / t1;
  if (n == 0) {
    *lo = 0.0;
    *hi = HUGE_VAL;
    return SB_SUCCESS;
  }
  if (ratio)
    *ratio = k2 == 0 ? HUGE_VAL : times_ratio((double)k1 / (double)k2, 1.0,
                                              t2, t1, f);
  /* p = R t1/(R t1 + t2), so R = f p/(1-p).  By symmetry of the
   * Clopper-Pearson interval, 1 - p_lo(k1) = p_hi(k2) and
   * 1 - p_hi(k1) = p_lo(k2): use those so 1 - p never cancels. */
  double t = 0.5 * (1.0 - level), lo1, hi1, lo2, hi2;
  int st = cp_bounds(k1, n, t, &lo1, &hi1);
  if (st == SB_SUCCESS)
    st = cp_bounds(k2, n, t, &lo2, &hi2);
  if (st != SB_SUCCESS) {
    set_nan2(lo, hi);
    return sbi_error(st, __func__, "root finding failed");
  }
  *lo = times_ratio(lo1, hi2, t2, t1, f);
  *hi = lo2 > 0.0 ? times_ratio(hi1, lo2, t2, t1, f) : HUGE_VAL;
  if (isinf(*lo) || (lo2 > 0.0 && isinf(*hi)) ||
      (ratio && k2 > 0 && isinf(*ratio))) {
    set_nan2(lo, hi);
    if (ratio)
      *ratio = NAN;
    return sbi_error(SB_ERANGE, __func__, "the ratio overflows (k1 = %lu, "
                     "t1 = %g, k2 = %lu, t2 = %g)", k1, t1, k2, t2);
  }
  return SB_SUCCESS;
}

/* ----------------------------------------------------------------- mean */

int sb_mean_ci(const double *x, size_t n, double level, double *mean,
               double *lo, double *hi)
{
  if (mean)
    *mean = NAN;
  if (!x || !lo || !hi || n < 2 || bad_level(level)) {
    set_nan2(lo, hi);
    return sbi_error(SB_EINVAL, __func__,
                     "need x, lo, hi non-NULL, n >= 2 and 0 < level < 1 "
                     "(n = %zu, level = %g)", n, level);
  }
  for (size_t i = 0; i < n; i++)
    if (!isfinite(x[i])) {
      set_nan2(lo, hi);
      return sbi_error(SB_EINVAL, __func__, "x[%zu] = %g is not finite", i,
                       x[i]);
    }
  double m = gsl_stats_mean(x, 1, n);
  double var = gsl_stats_variance_m(x, 1, n, m);
  double q = 0.5 * (1.0 - level), nu = (double)(n - 1), tq;
  /* Upper quantile from Q, not P((1+level)/2), to keep q's digits.  GSL's
   * Cauchy (nu = 1) inverse is inaccurate for q < 1e-15: use cot(pi q). */
  if (level < 1e-8) /* q rounds to 1/2: t = level / (2 f_nu(0)), the
                     * next term O(level^3) below rounding */
    tq = 0.5 * level * exp(gsl_sf_lngamma(0.5 * nu) -
                           gsl_sf_lngamma(0.5 * (nu + 1.0))) * sqrt(nu * M_PI);
  else if (n == 2)
    tq = 1.0 / tan(M_PI * q);
  else
    tq = gsl_cdf_tdist_Qinv(q, nu);
  double sd = sqrt(var / (double)n);
  if (!isfinite(m) || !isfinite(sd)) {
    /* x - m or the squares overflowed (|x| near DBL_MAX): the same sums on
     * x 2^-e, exact, with 2^e > max |x|; the results scaled back */
    double big = 0.0, ms = 0.0, ss = 0.0;
    int e;
    for (size_t i = 0; i < n; i++)
      big = fmax(big, fabs(x[i]));
    frexp(big, &e);
    for (size_t i = 0; i < n; i++)
      ms += (ldexp(x[i], -e) - ms) / (double)(i + 1);
    for (size_t i = 0; i < n; i++) {
      double dd = ldexp(x[i], -e) - ms;
      ss += dd * dd;
    }
    m = ldexp(ms, e); /* |m| <= max |x|: finite */
    sd = ldexp(sqrt(ss / nu / (double)n), e);
  }
  double half = tq * sd;
  if (mean)
    *mean = m;
  *lo = m - half;
  *hi = m + half;
  if (!isfinite(*lo) || !isfinite(*hi)) {
    set_nan2(lo, hi);
    return sbi_error(SB_ERANGE, __func__, "the interval overflows (mean %g, "
                     "half width %g, n = %zu)", m, half, n);
  }
  return SB_SUCCESS;
}

/* -------------------------------------------------------------- z-score */

double sb_zscore(double estimate, double reference, double stderr_)
{
  if (isnan(estimate) || isnan(reference) || !(stderr_ > 0.0)) {
    sbi_error(SB_EDOM, __func__,
              "need stderr > 0 and no NaN (estimate %g, reference %g, "
              "stderr %g)", estimate, reference, stderr_);
    return NAN;
  }
  double z = (estimate - reference) / stderr_;
  if (isnan(z))  /* inf - inf, or inf / inf */
    sbi_error(SB_EDOM, __func__, "estimate %g, reference %g, stderr %g: "
              "z is undefined", estimate, reference, stderr_);
  else if (isinf(z) && isfinite(estimate) && isfinite(reference) &&
           isfinite(stderr_)) {
    /* the difference may overflow where z does not (1e308 - -1e308) */
    z = 2.0 * ((0.5 * estimate - 0.5 * reference) / stderr_);
    if (isinf(z)) {
      sbi_error(SB_ERANGE, __func__, "estimate %g, reference %g, stderr %g: "
                "z overflows", estimate, reference, stderr_);
      return NAN;
    }
  }
  return z;
}

double sb_zscore_pvalue(double z)
{
  if (isnan(z)) {
    sbi_error(SB_EDOM, __func__, "z is NaN");
    return NAN;
  }
  if (isinf(z))
    return 0.0;
  return 2.0 * gsl_cdf_ugaussian_Q(fabs(z));
}

/* ----------------------------------------------------------- chi-square */

/* Q_chi2(x; nu) = Q_gamma(nu/2; x/2); nu >= 1 checked by the callers. */
static int chi2_q(double x, double nu, double *q)
{
  if (!(x > 0.0)) {
    *q = 1.0;
    return SB_SUCCESS;
  }
  if (isinf(x)) {
    *q = 0.0;
    return SB_SUCCESS;
  }
  if (0.5 * nu <= SHAPE_GSL_MAX) {
    *q = gsl_cdf_chisq_Q(x, nu);
    return SB_SUCCESS;
  }
  law_t L;
  int st = law_init(&L, 0, 0.5 * nu, 0.0);
  if (st == SB_SUCCESS)
    *q = law_tail(&L, 0.5 * x, 1);
  law_free(&L);
  return st;
}

double sb_chi2_sf(double x, double dof)
{
  if (isnan(x) || !(dof >= 1.0 && isfinite(dof))) {
    sbi_error(SB_EDOM, __func__, "need x not NaN, finite dof >= 1 "
                                 "(x = %g, dof = %g)", x, dof);
    return NAN;
  }
  double q;
  int st = chi2_q(x, dof, &q);
  if (st != SB_SUCCESS) {
    sbi_error(st, __func__, "no memory for the quadrature table");
    return NAN;
  }
  return q;
}

/* F at an edge: infinite edges are 0 / 1 without calling the callback. */
static double cdf_at(double e, sb_cdf_fn cdf, void *params)
{
  if (e == -HUGE_VAL)
    return 0.0;
  if (e == HUGE_VAL)
    return 1.0;
  return cdf(e, params);
}

int sb_chi2_test(const double *x, size_t n, const double *edges,
                 size_t nbins, sb_cdf_fn cdf, void *params, double *chi2,
                 double *dof, double *p)
{
  if (chi2)
    *chi2 = NAN;
  if (dof)
    *dof = NAN;
  if (p)
    *p = NAN;
  if (!x || n == 0 || !edges || nbins < 2 || !cdf)
    return sbi_error(SB_EINVAL, __func__,
                     "need samples (n = %zu), edges, nbins >= 2 (%zu), cdf",
                     n, nbins);
  for (size_t i = 0; i < nbins; i++)
    if (!(edges[i] < edges[i + 1]))
      return sbi_error(SB_EINVAL, __func__,
                       "edges not strictly increasing at %zu (%g, %g)", i,
                       edges[i], edges[i + 1]);
  for (size_t i = 0; i < n; i++)
    if (isnan(x[i]))
      return sbi_error(SB_EINVAL, __func__, "x[%zu] is NaN", i);

  double *w = malloc((2 * nbins + 1) * sizeof *w);
  if (!w)
    return sbi_error(SB_ENOMEM, __func__, "no memory for %zu bins", nbins);
  double *F = w, *obs = w + nbins + 1;
  int st = SB_SUCCESS;
  for (size_t i = 0; i <= nbins; i++) {
    F[i] = cdf_at(edges[i], cdf, params);
    if (!(F[i] >= 0.0 && F[i] <= 1.0) || (i > 0 && F[i] < F[i - 1])) {
      st = sbi_error(SB_EINVAL, __func__,
                     "F(edges[%zu] = %g) = %g not in [0,1] or decreasing", i,
                     edges[i], F[i]);
      goto out;
    }
  }
  double mass = F[nbins] - F[0];
  if (!(mass > 0.0)) {
    st = sbi_error(SB_EINVAL, __func__, "F has no mass in [%g, %g]",
                   edges[0], edges[nbins]);
    goto out;
  }
  for (size_t i = 0; i < nbins; i++)
    obs[i] = 0.0;
  size_t nin = 0;
  for (size_t i = 0; i < n; i++) {
    double v = x[i];
    if (v < edges[0] || v > edges[nbins])
      continue;
    size_t l = 0, h = nbins; /* find l with edges[l] <= v < edges[l+1] */
    while (h - l > 1) {
      size_t mid = l + (h - l) / 2;
      if (v >= edges[mid])
        l = mid;
      else
        h = mid;
    }
    obs[l] += 1.0;
    nin++;
  }
  if (nin == 0) {
    st = sbi_error(SB_EINVAL, __func__, "no sample inside [%g, %g]",
                   edges[0], edges[nbins]);
    goto out;
  }
  double c2 = 0.0, used = 0.0;
  size_t nsmall = 0;
  for (size_t i = 0; i < nbins; i++) {
    double e = (double)nin * (F[i + 1] - F[i]) / mass;
    if (e < 5.0)
      nsmall++;
    if (e > 0.0) {
      double dd = obs[i] - e;
      c2 += dd * dd / e;
      used += 1.0;
    } else if (obs[i] > 0.0) {
      c2 = HUGE_VAL; /* samples where the law puts no mass */
    }
  }
  double nu = used - 1.0, q = 0.0;
  if (nu < 1.0) {
    st = sbi_error(SB_EINVAL, __func__, "fewer than two bins with mass");
    goto out;
  }
  st = chi2_q(c2, nu, &q);
  if (st != SB_SUCCESS) {
    st = sbi_error(st, __func__, "p-value failed");
    goto out;
  }
  if (chi2)
    *chi2 = c2;
  if (dof)
    *dof = nu;
  if (p)
    *p = q;
  if (nsmall)
    st = sbi_error(SB_ELOSS, __func__,
                   "%zu bin(s) with expected count < 5: chi-square "
                   "approximation unreliable", nsmall);
out:
  free(w);
  return st;
}

