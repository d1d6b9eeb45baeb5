/* passage.c — first-passage laws: Brownian motion with drift (inverse
 * Gaussian, Levy, defective) and Bessel-3 down to a level.  Formulas and
 * derivations: smolbridge/passage.h and docs/passage.md. */
#include <float.h>
#include <math.h>

#include <gsl/gsl_cdf.h>
#include <gsl/gsl_rng.h>
#include <gsl/gsl_sf_erf.h>

#include <smolbridge/passage.h>
#include "common/internal.h"
#include "common/numutil.h"

#define EPS DBL_EPSILON
#define INV_RT2PI 0.39894228040143267793994605993438187 /* 1/sqrt(2 pi) */

/* --------------------------------------------------- BM with drift */

enum { W_PDF, W_CDF, W_SF };

typedef struct {
  sbi_dd d;      /* |x - a| exactly (x - a as a double-double) */
  double nu;     /* drift towards the level, mu sign(a - x) */
  double nua;    /* |nu| */
  double sigma2;
  double mass;   /* P(T < inf) */
  double kmass;  /* -log(mass) = 2 |nu| d / sigma2 (0 if nu >= 0) */
} fpt_par;

/* 1 - mass, computed directly */
static double cmass(const fpt_par *q) { return -expm1(-q->kmass); }

static int is_bad(double v) { return !isfinite(v); }

/* Validate (x, a, mu, sigma2) and fill *q.  Returns a status. */
static int fpt_setup(const char *fn, double x, double a, double mu,
                     double sigma2, fpt_par *q, sb_result *res)
{
  if (is_bad(x) || is_bad(a) || is_bad(mu))
    return sbi_fail(res, SB_EDOM, fn, "x = %g, a = %g, mu = %g must be finite",
                    x, a, mu);
  if (!(sigma2 > 0.0) || is_bad(sigma2))
    return sbi_fail(res, SB_EDOM, fn,
                    "sigma2 = %g must be positive and finite", sigma2);
  sbi_dd d = sbi_dd_sum(x, -a);
  if (d.hi < 0.0)
    d = sbi_dd_neg(d);
  q->d = d;
  q->nu = x < a ? mu : -mu;
  q->nua = fabs(mu);
  q->sigma2 = sigma2;
  if (q->nu >= 0.0 || d.hi == 0.0) {
    q->mass = 1.0;
    q->kmass = 0.0;
  } else {
    /* mass = exp(-2 |nu| d / sigma2), exponent in double-double */
    sbi_dd k = sbi_dd_twice_ratio(d, (sbi_dd){q->nua, 0.0}, sigma2);
    q->mass = k.hi < 746.0 ? sbi_dd_expneg(k) : 0.0;
    q->kmass = k.hi + k.lo;
  }
  return SB_SUCCESS;
}

/* Plain double-double arithmetic is exact for these operands: their
 * products stay far from overflow (and from the 2^995 where Veltkamp's
 * split overflows) and from the subnormals. */
static int in_window(double v)
{
  return v < 0x1p400 && v > 0x1p-400;
}

/* sigma2 t = den 2^(2k), den in [1, 4) exact (0 < sigma2, t < inf):
 * formed from the mantissas so that nothing over/underflows. */
static sbi_dd scaled_var(double sigma2, double t, int *k)
{
  const int es = ilogb(sigma2), et = ilogb(t), e2 = es + et;
  sbi_dd den = sbi_dd_prod(ldexp(sigma2, -es), ldexp(t, -et));
  *k = (e2 - (e2 & 1)) / 2;
  if (e2 & 1) {
    den.hi *= 2.0;
    den.lo *= 2.0;
  }
  return den;
}

/* Inverse-Gaussian point (drift |nu|) at time t, 0 < t < inf. */
static sbi_igpt fpt_point(const fpt_par *q, double t)
{
  if (in_window(t) && in_window(q->sigma2) && in_window(q->d.hi) &&
      (q->nua == 0.0 || in_window(q->nua))) {
    sbi_dd den = sbi_dd_prod(q->sigma2, t);
    sbi_dd num = sbi_dd_add(sbi_dd_prod(q->nua, t), sbi_dd_neg(q->d));
    double s = sqrt(den.hi);
    return sbi_igpt_make(num, den, q->d.hi / s, q->nua * t / s);
  }
  /* extreme magnitudes (sigma2 t or nu t beyond DBL_MAX, a product above
   * 2^995, ...): the same operations on mantissas scaled by powers of two,
   * i.e. the same roundings wherever the plain path stays in range.
   * sigma2 t = den 2^(2k), s = rs 2^k, nu t - d = num 2^m. */
  int k;
  const sbi_dd den = scaled_var(q->sigma2, t, &k);
  const double rs = sqrt(den.hi);
  const int et = ilogb(t), ed = ilogb(q->d.hi);
  double kap = 0.0;
  int m = ed;
  sbi_dd pt = {0.0, 0.0};
  if (q->nua > 0.0) {
    const int en = ilogb(q->nua), ep = en + et;
    pt = sbi_dd_prod(ldexp(q->nua, -en), ldexp(t, -et)); /* nu t 2^-ep */
    kap = ldexp(pt.hi / rs, ep - k);
    m = ep > ed ? ep : ed;
    pt.hi = ldexp(pt.hi, ep - m);
    pt.lo = ldexp(pt.lo, ep - m);
  }
  const sbi_dd dm = {ldexp(q->d.hi, -m), ldexp(q->d.lo, -m)};
  const sbi_dd num = sbi_dd_add(pt, sbi_dd_neg(dm));
  const double eps = ldexp(ldexp(q->d.hi, -ed) / rs, ed - k);
  return sbi_igpt_make_x(num, den, m - k, eps, kap);
}

/* w d exp(-E) / (t sqrt(2 pi sigma2 t)) with an extended exponent range,
 * for densities whose plain product over- or underflows in an
 * intermediate (eps / t or exp(-E) beyond the doubles): +inf if the
 * density itself exceeds DBL_MAX. */
static double pdf_xd(double w, double d, double t, double sigma2, sbi_dd E)
{
  if (!(E.hi < 1e6) || w == 0.0)
    return 0.0;
  sbi_xd ex = sbi_xd_expneg(E.hi);
  ex.m *= 1.0 - E.lo;
  sbi_xd st = sbi_xd_sqrt(sbi_xd_mul(sbi_xd_of(sigma2), sbi_xd_of(t)));
  sbi_xd f = sbi_xd_div(sbi_xd_mul(sbi_xd_of(w), sbi_xd_of(d)),
                        sbi_xd_mul(sbi_xd_of(t), st));
  f = sbi_xd_mul(sbi_xd_mul(f, ex), sbi_xd_of(INV_RT2PI));
  return sbi_xd_val(f);
}

/* Core of pdf/cdf/sf: validated parameters, t >= 0.  Returns SB_ERANGE
 * (nothing recorded) if the density exceeds DBL_MAX. */
static int fpt_eval(const fpt_par *q, int what, double t, sb_result *res)
{
  double val, err;
  if (q->d.hi == 0.0) {
    /* starts on the level: T = 0 */
    res->val = what == W_CDF ? 1.0 : 0.0;
    res->err = 0.0;
    return SB_SUCCESS;
  }
  if (t == 0.0 || isinf(t)) {
    int at0 = t == 0.0;
    if (what == W_PDF)
      val = 0.0;
    else if (what == W_CDF)
      val = at0 ? 0.0 : q->mass;
    else
      val = at0 ? 1.0 : cmass(q);
    res->val = val;
    res->err = 2.0 * EPS * val;
    return SB_SUCCESS;
  }
  if (q->mass == 0.0) {
    /* drift away so strong that the level is never reached (to double
     * precision): the inverse-Gaussian point may not even be finite */
    res->val = what == W_SF ? 1.0 : 0.0;
    res->err = 0.0;
    return SB_SUCCESS;
  }
  sbi_igpt p = fpt_point(q, t);
  double rel = 0.0;
  if (what == W_PDF) {
    /* f = mass (eps / t) phi(c): for nu < 0 the exponent (d + |nu| t)^2
     * equals (d - |nu| t)^2 + 4 |nu| t d, i.e. the defective factor */
    val = q->mass * (p.eps / t) * p.ex * INV_RT2PI;
    rel = 8.0 * EPS;
    if (!(val >= DBL_MIN && val <= DBL_MAX)) {
      /* eps / t or exp(-E) out of range (or a subnormal density) */
      val = pdf_xd(q->mass, q->d.hi, t, q->sigma2, p.E);
      if (isinf(val))
        return SB_ERANGE;
    }
  } else if (what == W_CDF) {
    val = q->mass * sbi_ig_cdf(&p, &rel);
    rel += 2.0 * EPS;
  } else {
    double s = sbi_ig_sf(&p, &rel);
    if (q->mass < 1.0) {
      /* P(T > t) = (1 - mass) + mass P_IG(S > t): positive terms */
      double m = q->mass * s, cm = cmass(q);
      val = cm + m;
      rel = (4.0 * EPS * cm + (rel + 2.0 * EPS) * m) / val;
    } else {
      val = s;
    }
  }
  err = rel * val;
  res->val = val;
  res->err = err;
  return SB_SUCCESS;
}

static int fpt_entry(const char *fn, int what, double t, double x, double a,
                     double mu, double sigma2, sb_result *res)
{
  fpt_par q;
  int st = fpt_setup(fn, x, a, mu, sigma2, &q, res);
  if (st)
    return st;
  if (isnan(t) || t < 0.0)
    return sbi_fail(res, SB_EDOM, fn, "t = %g must be >= 0", t);
  if (fpt_eval(&q, what, t, res))
    return sbi_fail(res, SB_ERANGE, fn,
                    "the density at t = %g exceeds DBL_MAX", t);
  return SB_SUCCESS;
}

#define FPT_PAIR(name, what)                                                \
  int sb_bm_fpt_##name##_e(double t, double x, double a, double mu,         \
                           double sigma2, sb_result *res)                   \
  {                                                                         \
    sb_result r;                                                            \
    int st = fpt_entry(__func__, what, t, x, a, mu, sigma2, &r);            \
    if (res)                                                                \
      *res = r;                                                             \
    return st;                                                              \
  }                                                                         \
  double sb_bm_fpt_##name(double t, double x, double a, double mu,          \
                          double sigma2)                                    \
  {                                                                         \
    sb_result r;                                                            \
    fpt_entry(__func__, what, t, x, a, mu, sigma2, &r);                     \
    return r.val;                                                           \
  }

FPT_PAIR(pdf, W_PDF)
FPT_PAIR(cdf, W_CDF)
FPT_PAIR(sf, W_SF)

/* the mass, its errors naming func (the public function called) */
static int fpt_mass(const char *func, double x, double a, double mu,
                    double sigma2, sb_result *res)
{
  fpt_par q;
  sb_result r;
  int st = fpt_setup(func, x, a, mu, sigma2, &q, &r);
  if (!st) {
    r.val = q.mass;
    r.err = 2.0 * EPS * q.mass;
  }
  if (res)
    *res = r;
  return st;
}

int sb_bm_fpt_mass_e(double x, double a, double mu, double sigma2,
                     sb_result *res)
{
  return fpt_mass(__func__, x, a, mu, sigma2, res);
}

double sb_bm_fpt_mass(double x, double a, double mu, double sigma2)
{
  sb_result r;
  fpt_mass(__func__, x, a, mu, sigma2, &r);
  return r.val;
}

/* log of the mass, -2 d |nu| / sigma2 (0 if nu >= 0): fpt_setup's
 * double-double exponent rounded once; SB_ERANGE where it is below
 * -DBL_MAX.  Errors name func. */
static int fpt_logmass(const char *func, double x, double a, double mu,
                       double sigma2, sb_result *res)
{
  fpt_par q;
  sb_result r;
  int st = fpt_setup(func, x, a, mu, sigma2, &q, &r);
  if (!st) {
    if (isinf(q.kmass))
      st = sbi_fail(&r, SB_ERANGE, func, "log mass = -2 |x - a| |mu| / "
                    "sigma2 is below -DBL_MAX (x = %g, a = %g, mu = %g, "
                    "sigma2 = %g)", x, a, mu, sigma2);
    else {
      r.val = 0.0 - q.kmass; /* +0, not -0, for nu >= 0 */
      r.err = 2.0 * EPS * q.kmass;
    }
  }
  if (res)
    *res = r;
  return st;
}

int sb_bm_fpt_logmass_e(double x, double a, double mu, double sigma2,
                        sb_result *res)
{
  return fpt_logmass(__func__, x, a, mu, sigma2, res);
}

double sb_bm_fpt_logmass(double x, double a, double mu, double sigma2)
{
  sb_result r;
  fpt_logmass(__func__, x, a, mu, sigma2, &r);
  return r.val;
}

/* ------------------------------------------------------- quantile */

typedef struct {
  const fpt_par *q;
  double sref;   /* s = sref exp(y) */
  double logtg;  /* log of the target probability of the IG part */
  int upper;     /* 0: solve F_IG = target, 1: solve SF_IG = target */
  double rel, dlog; /* last relative error of F/SF and d log/dy */
} fpt_qctx;

/* g(y) = log F_IG(s) - log target (lower) or log target - log SF_IG(s)
 * (upper); increasing in y = log(s/sref).  With D1 = s pdf / F (or / SF)
 * and s f'(s)/f(s) = -3/2 - c b/2 for the inverse Gaussian (b = kap + eps):
 *   g' = D1,  g'' = D1 (-1/2 - c b/2 -+ D1)   (- lower, + upper). */
static double fpt_qfun(double y, void *vctx, double *dg, double *d2g)
{
  fpt_qctx *c = vctx;
  double s = c->sref * exp(y);
  /* g is increasing in both tails: -inf at s = 0, +inf at s = inf */
  if (!(s > 0.0))
    return -INFINITY;
  if (isinf(s))
    return INFINITY;
  sbi_igpt p = fpt_point(c->q, s);
  double pr = c->upper ? sbi_ig_sf(&p, &c->rel) : sbi_ig_cdf(&p, &c->rel);
  double spdf = p.eps * p.ex * INV_RT2PI; /* s times the IG density */
  if (!(pr > 0.0)) {
    *dg = 0.0;
    return c->upper ? INFINITY : -INFINITY;
  }
  double D1 = spdf / pr;
  double sfl = -0.5 - 0.5 * p.c * (p.kap + p.eps);
  *dg = D1;
  *d2g = D1 * (sfl + (c->upper ? D1 : -D1));
  c->dlog = D1;
  double lp = log(pr);
  return c->upper ? c->logtg - lp : lp - c->logtg;
}

/* g(t) = F_IG(t) - tg (lower) or tg - SF_IG(t) (upper), *f = IG density */
static double fpt_g_at(const fpt_par *q, double t, double tg, int upper,
                       double *f)
{
  sbi_igpt p = fpt_point(q, t);
  *f = p.eps * p.ex * INV_RT2PI / t;
  return upper ? tg - sbi_ig_sf(&p, NULL) : sbi_ig_cdf(&p, NULL) - tg;
}

/* Final polish in t when the law is so concentrated that the rounding of
 * t = sref exp(y) (a couple of ulp) matters: Newton on g(t), then the
 * better of t and its neighbour towards the root (the best double). */
static double polish_t(const fpt_par *q, double t, double tg, int upper)
{
  double f, g = fpt_g_at(q, t, tg, upper, &f);
  for (int it = 0; it < 3 && f > 0.0; it++) {
    double tn = t - g / f;
    if (!(tn > 0.0) || isinf(tn) || tn == t)
      break;
    double fn, gn = fpt_g_at(q, tn, tg, upper, &fn);
    if (!(fabs(gn) < fabs(g)))
      break;
    t = tn;
    g = gn;
    f = fn;
  }
  double nb = nextafter(t, g > 0.0 ? 0.0 : INFINITY), fnb;
  if (nb > 0.0) {
    double gnb = fpt_g_at(q, nb, tg, upper, &fnb);
    if (fabs(gnb) < fabs(g))
      t = nb;
  }
  return t;
}

/* A law narrower than one ulp of t: from t (the mean), step one double at
 * a time towards the root of g (at most 64) until g changes sign, and
 * return the better of the two doubles around it.  Newton is useless
 * there (the density at a double can be exp(-50) of its peak). */
static double walk_doubles(const fpt_par *q, double t, double tg, int upper)
{
  double f, g = fpt_g_at(q, t, tg, upper, &f);
  for (int k = 0; k < 64 && g != 0.0; k++) {
    double tn = nextafter(t, g > 0.0 ? 0.0 : INFINITY), gn;
    if (!(tn > 0.0) || isinf(tn))
      break;
    gn = fpt_g_at(q, tn, tg, upper, &f);
    if ((gn > 0.0) != (g > 0.0))
      return fabs(gn) < fabs(g) ? tn : t;
    t = tn;
    g = gn;
  }
  return t;
}

/* Units for the quantile and the sampler where d = |x - a|, sigma2 or
 * |mu| is outside 2^(+-300) (d^2/sigma2 or d/|nu| then over/underflowed:
 * a start point of 0 or +inf).  Lengths are scaled by 2^-m (d in [1, 2)),
 * times by 2^-n with n the smaller of the diffusion and drift time scales
 * (d^2/sigma2, d/|mu|), so that sigma2 and |mu| become at most ~2 (all
 * exact: powers of two; the law of T 2^-n is that of the scaled
 * arguments).  sigma2 is kept >= 2^-1000, which only narrows a law whose
 * relative width is below 2^-490 already.  Returns n (0: unchanged;
 * invalid arguments are left to fpt_setup's messages). */
static int fpt_units(double *x, double *a, double *mu, double *sigma2)
{
  if (is_bad(*x) || is_bad(*a) || is_bad(*mu) || !(*sigma2 > 0.0) ||
      is_bad(*sigma2))
    return 0;
  const double d = fabs(*x - *a), mua = fabs(*mu);
  const double lo = 0x1p-300, hi = 0x1p300;
  if (d == 0.0 || (d > lo && d < hi && *sigma2 > lo && *sigma2 < hi &&
                   (mua == 0.0 || (mua > lo && mua < hi))))
    return 0;
  const int m = isinf(d) ? 1024 : ilogb(d), es = ilogb(*sigma2);
  int n = 2 * m - es;
  if (mua > 0.0 && m - ilogb(mua) < n)
    n = m - ilogb(mua);
  int e2 = n - 2 * m; /* sigma2 2^e2, e2 + es <= 0 */
  if (e2 + es < -1000)
    e2 = -1000 - es;
  *x = ldexp(*x, -m);
  *a = ldexp(*a, -m);
  *mu = ldexp(*mu, n - m);
  *sigma2 = ldexp(*sigma2, e2);
  return n;
}

static int fpt_quantile_unit(const char *fn, double p, double x, double a,
                             double mu, double sigma2, sb_result *res);

/* the quantile, its errors naming func (the public function called) */
static int fpt_quantile(const char *func, double p, double x, double a,
                        double mu, double sigma2, sb_result *res)
{
  const double x0 = x, a0 = a;
  const int n = fpt_units(&x, &a, &mu, &sigma2);
  sb_result r;
  int st = fpt_quantile_unit(func, p, x, a, mu, sigma2, &r);
  if (n && !isnan(r.val)) {
    const double v = r.val;
    r.val = ldexp(r.val, n);
    r.err = ldexp(r.err, n);
    if (isinf(r.val) && isfinite(v))
      st = sbi_fail(&r, SB_ERANGE, func, "the quantile for p = %g, "
                    "x = %g, a = %g exceeds DBL_MAX", p, x0, a0);
  }
  if (res)
    *res = r;
  return st;
}

int sb_bm_fpt_quantile_e(double p, double x, double a, double mu,
                         double sigma2, sb_result *res)
{
  return fpt_quantile(__func__, p, x, a, mu, sigma2, res);
}

/* The quantile for arguments in fpt_units' range. */
static int fpt_quantile_unit(const char *fn, double p, double x, double a,
                             double mu, double sigma2, sb_result *res)
{
  fpt_par q;
  sb_result r = {NAN, NAN};
  int st = fpt_setup(fn, x, a, mu, sigma2, &q, &r);
  if (st) {
    *res = r;
    return st;
  }
  if (!(p >= 0.0 && p <= 1.0)) {
    st = sbi_fail(&r, SB_EDOM, fn, "p = %g must be in [0, 1]", p);
    *res = r;
    return st;
  }
  if (q.d.hi == 0.0 || p == 0.0) {
    r.val = 0.0;
    r.err = 0.0;
  } else if (p >= q.mass) {
    r.val = INFINITY;
    r.err = 0.0;
  } else {
    /* target for the inverse-Gaussian part (drift |nu|) */
    double pl = q.mass < 1.0 ? p / q.mass : p;
    int upper = pl > 0.5;
    double tg = upper ? (q.mass < 1.0 ? (q.mass - p) / q.mass : 1.0 - p) : pl;
    double dist = q.d.hi, shape = dist * dist / sigma2, sref;
    if (q.nua > 0.0) {
      double mean = dist / q.nua;
      sref = mean * sbi_ig_quantile_guess(tg, upper, shape / mean);
    } else {
      /* Levy: P(T <= s) = 2 Q(dist / sqrt(sigma2 s)) exactly */
      double z = upper ? (tg < 1e-8 ? tg * 1.2533141373155002512
                                    : gsl_cdf_ugaussian_Pinv(0.5 + 0.5 * tg))
                       : gsl_cdf_ugaussian_Qinv(0.5 * tg);
      sref = shape / (z * z);
    }
    if (!(sref > 0.0) || isinf(sref))
      sref = shape;
    if (q.nua > 0.0 && shape * q.nua > 1e32 * dist) {
      /* relative width sqrt(mean/shape) below 1e-16: every quantile is
       * within a few ulp of the mean, where the root in y = log(s/sref)
       * is narrower than one ulp of y (the solver then stopped a bracket
       * step away: off by e).  Newton in t and the best double. */
      r.val = walk_doubles(&q, dist / q.nua, tg, upper);
      r.err = 4.0 * EPS * r.val;
      *res = r;
      return SB_SUCCESS;
    }
    fpt_qctx c = {&q, sref, log(tg), upper, 0.0, 1.0};
    double y, dy;
    st = sbi_solve_increasing(fpt_qfun, &c, 0.0, 1.0, 1e-11, &y, &dy);
    r.val = sref * exp(y);
    if (st == SB_SUCCESS && c.dlog > 100.0 && r.val > 0.0 && isfinite(r.val))
      r.val = polish_t(&q, r.val, tg, upper);
    /* last step, rounding of exp and of the target, noise of F or SF */
    r.err = r.val * (2.0 * dy + 8.0 * EPS + (c.rel + 4.0 * EPS) / c.dlog);
    if (st)
      sbi_error(st, fn, "no convergence for p = %g", p);
  }
  *res = r;
  return st;
}

double sb_bm_fpt_quantile(double p, double x, double a, double mu,
                          double sigma2)
{
  sb_result r;
  fpt_quantile(__func__, p, x, a, mu, sigma2, &r);
  return r.val;
}

/* -------------------------------------------------------- sampler */

static double fpt_sample_unit(const char *fn, const gsl_rng *r, double x,
                              double a, double mu, double sigma2);

double sb_bm_fpt_sample(const gsl_rng *r, double x, double a, double mu,
                        double sigma2)
{
  const double x0 = x, a0 = a;
  const int n = fpt_units(&x, &a, &mu, &sigma2);
  const double v = fpt_sample_unit(__func__, r, x, a, mu, sigma2);
  if (n == 0 || !isfinite(v))
    return v;
  const double t = ldexp(v, n);
  if (isinf(t)) {
    sbi_error(SB_ERANGE, __func__, "the draw for x = %g, a = %g exceeds "
              "DBL_MAX", x0, a0);
    return NAN;
  }
  return t;
}

/* One draw for arguments in fpt_units' range. */
static double fpt_sample_unit(const char *fn, const gsl_rng *r, double x,
                              double a, double mu, double sigma2)
{
  fpt_par q;
  if (fpt_setup(fn, x, a, mu, sigma2, &q, NULL))
    return NAN;
  if (r == NULL) {
    sbi_fail(NULL, SB_EINVAL, fn, "r is NULL");
    return NAN;
  }
  if (q.d.hi == 0.0)
    return 0.0;
  double shape = q.d.hi * q.d.hi / sigma2;
  if (q.nu == 0.0)
    return sbi_ig_sample(r, INFINITY, shape);
  if (q.nu < 0.0 && gsl_rng_uniform(r) >= q.mass)
    return INFINITY; /* never reaches the level */
  return sbi_ig_sample(r, q.d.hi / q.nua, shape);
}

/* ---------------------------------------------- Bessel-3 down to a */

static int bes3_entry(const char *fn, int what, double t, double x, double a,
                      double sigma2, sb_result *res)
{
  if (isnan(t) || is_bad(x) || is_bad(a))
    return sbi_fail(res, SB_EDOM, fn,
                    "t = %g, x = %g, a = %g: t must be a number, x and a "
                    "finite", t, x, a);
  if (x < 0.0 || a < 0.0)
    return sbi_fail(res, SB_EDOM, fn,
                    "x = %g, a = %g: a Bessel-3 radius must be >= 0", x, a);
  if (!(sigma2 > 0.0) || is_bad(sigma2))
    return sbi_fail(res, SB_EDOM, fn,
                    "sigma2 = %g must be positive and finite", sigma2);
  if (t < 0.0)
    return sbi_fail(res, SB_EDOM, fn, "t = %g must be >= 0", t);
  double val, rel;
  if (x <= a) {
    /* starts inside: T = 0 */
    res->val = what == W_CDF ? 1.0 : 0.0;
    res->err = 0.0;
    return SB_SUCCESS;
  }
  sbi_dd d = sbi_dd_sum(x, -a);
  double h = a / x;         /* P(T < inf) */
  double ch = d.hi / x;     /* 1 - a/x */
  if (a == 0.0 || t == 0.0 || isinf(t)) {
    if (what == W_PDF)
      val = 0.0;
    else if (what == W_CDF)
      val = t == 0.0 ? 0.0 : h;
    else
      val = t == 0.0 ? 1.0 : ch;
    res->val = val;
    res->err = 2.0 * EPS * val;
    return SB_SUCCESS;
  }
  /* eps = d / sqrt(sigma2 t); exp(-eps^2/2) from the exact d^2/(2 sigma2 t) */
  double eps, ex;
  sbi_dd E;
  if (in_window(sigma2) && in_window(t) && in_window(d.hi)) {
    sbi_dd den = sbi_dd_prod(sigma2, t);
    eps = d.hi / sqrt(den.hi);
    E = sbi_dd_div(sbi_dd_mul(d, d), sbi_dd_mul_d(den, 2.0));
    ex = E.hi < 746.0 ? sbi_dd_expneg(E) : 0.0;
  } else {
    /* scaled by powers of two (see fpt_point): sigma2 t = den 2^(2k) */
    int k;
    const sbi_dd den = scaled_var(sigma2, t, &k);
    const int ed = ilogb(d.hi);
    const sbi_dd dm = {ldexp(d.hi, -ed), ldexp(d.lo, -ed)};
    eps = ldexp(dm.hi / sqrt(den.hi), ed - k);
    sbi_igpt p = sbi_igpt_make_x(dm, den, ed - k, eps, 0.0);
    E = p.E;
    ex = p.ex;
  }
  if (what == W_PDF) {
    val = h * (eps / t) * ex * INV_RT2PI;
    rel = 8.0 * EPS;
    if (!(val >= DBL_MIN && val <= DBL_MAX)) {
      val = pdf_xd(h, d.hi, t, sigma2, E);
      if (isinf(val))
        return sbi_fail(res, SB_ERANGE, fn,
                        "the density at t = %g exceeds DBL_MAX", t);
    }
  } else if (what == W_CDF) {
    /* (a/x) erfc(eps/sqrt 2) = (a/x) 2 Q(eps) = (a/x) 2 exp(-eps^2/2) M(eps) */
    double tail = eps <= 3.0 ? gsl_cdf_ugaussian_Q(eps)
                             : ex * sbi_mills(eps);
    val = 2.0 * h * tail;
    rel = eps <= 3.0 ? (4.0 + 2.0 * eps * eps) * EPS : 8.0 * EPS;
  } else {
    /* (1 - a/x) + (a/x) erf(eps/sqrt 2): positive terms */
    /* erf is 1 in double from eps ~ 8.3 on; GSL's erf is NaN from an
     * argument of ~1e62 (t tiny against d^2/sigma2) */
    double e = eps > 10.0 ? 1.0 : gsl_sf_erf(eps * 0.70710678118654752440);
    val = ch + h * e;
    rel = 4.0 * EPS;
  }
  res->val = val;
  res->err = rel * val;
  return SB_SUCCESS;
}

#define BES3_PAIR(name, what)                                               \
  int sb_bes3_fpt_##name##_e(double t, double x, double a, double sigma2,   \
                             sb_result *res)                                \
  {                                                                         \
    sb_result r;                                                            \
    int st = bes3_entry(__func__, what, t, x, a, sigma2, &r);               \
    if (res)                                                                \
      *res = r;                                                             \
    return st;                                                              \
  }                                                                         \
  double sb_bes3_fpt_##name(double t, double x, double a, double sigma2)    \
  {                                                                         \
    sb_result r;                                                            \
    bes3_entry(__func__, what, t, x, a, sigma2, &r);                        \
    return r.val;                                                           \
  }

BES3_PAIR(pdf, W_PDF)
BES3_PAIR(cdf, W_CDF)
BES3_PAIR(sf, W_SF)
