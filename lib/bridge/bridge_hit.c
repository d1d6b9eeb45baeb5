/* bridge_hit.c — the hitting time T_a of a level a by a Brownian bridge or a
 * Bessel-3 bridge, conditioned on T_a <= t: density, CDF, survival
 * function, quantile and exact sampler (smolbridge/bridge.h,
 * docs/bridge.md).
 *
 * Notation: alpha = x - a > 0, v = sigma2 t, w = t - u,
 *   s(u) = u t / w (time change),  q(u) = sqrt(sigma2 u t w),
 *   for a "drift length" L >= 0:  eps = alpha w / q,  kap = L u / q,
 *   c = (L u - alpha w) / q = kap - eps.
 * BB: S = s(T) is IG(alpha t / L, alpha^2 / sigma2) with L = |y - a|, so
 *   P(T <= u) = F_IG(eps, kap).
 * B3B: with L1 = |y - a|, L2 = y + a, rho = exp(-min(a,y)(2 alpha +
 *   L1 + L2)/v):
 *   P(T <= u) = [F_IG(u; L1) - rho F_IG(u; L2)] / (1 - rho)        (1)
 *             = int_{L1}^{L2} (alpha + L)/v exp(-((alpha+L)^2 -
 *               (alpha+L1)^2)/(2v)) P_L(u) dL / (1 - rho),          (2)
 *   P_L(u) = [L F_IG(u; L) + alpha F_sb(u; L)] / (alpha + L), the law of T
 *   given the bridge minimum m (L = a + y - 2m).  (1) is used unless it
 *   cancels (rho F2 / F1 > 0.95, error amplification > 39; always when
 *   rho > 0.95), then (2) by a Taylor expansion about the mid L with a
 *   rigorous remainder bound (narrow), or where that bound fails by
 *   Gauss-Legendre quadrature (Gauss-Kronrod if needed).  Where all
 *   positions are below ~1e-154 sqrt(v), 1 - rho underflows (rho is 1 in
 *   doubles): (2) alone, divided by 1 - rho held with an extended exponent
 *   (h->tiny; docs/bridge.md §3).
 */
#include <float.h>
#include <limits.h>
#include <math.h>
#include <stdint.h>
#include <string.h>

#include <gsl/gsl_cdf.h>
#include <gsl/gsl_integration.h>
#include <gsl/gsl_rng.h>
#include <gsl/gsl_randist.h>

#include <smolbridge/bridge.h>
#include "common/internal.h"
#include "common/numutil.h"

#define EPS DBL_EPSILON
#define INV_RT2PI 0.39894228040143267793994605993438187 /* 1/sqrt(2 pi) */

enum { W_PDF, W_CDF, W_SF };
enum { T_NONE, T_ZERO, T_END }; /* trivial laws: T = 0 or T = t a.s. */

typedef struct {
  int b3;          /* 0: Brownian bridge, 1: Bessel-3 bridge */
  int trivial;
  double sigma2, t, v, a, y;
  sbi_dd al;       /* alpha = x - a > 0 */
  sbi_dd L1, L2;   /* |y - a|, y + a (L2 for B3B only) */
  double rho, omr; /* B3B: rho and 1 - rho */
  sbi_xd omrx;     /* B3B: 1 - rho with an extended exponent (below) */
  int tiny;        /* B3B: 1 - rho below DBL_MIN (only omrx holds it) */
  double rmax;     /* B3B: use (1) while rho G2 <= rmax G1 (0.95) */
  double rnx;      /* B3B: the expansion of (2) straight away if rho > rnx */
  double mn;       /* B3B: min(a, y); 0 means the single law P_a */
  double om1;      /* B3B: exp(-mn (2(alpha + L1) + mn)/(2v)), see narrow */
} hit_par;

/* One evaluation time u in (0, t), with w = t - u. */
typedef struct {
  double u;
  sbi_dd w, den; /* den 2^(-2k) = sigma2 u t w */
  int k;         /* 0 unless sigma2 u t w is below 2^-900 */
  double q;      /* sqrt(sigma2 u t w) (subnormal or 0 if it underflows) */
  sbi_xd qx;     /* the same with an extended exponent */
} hit_time;

/* ------------------------------------------------------------ set-up */

/* a b / c for a, b >= 0, c > 0: the plain expression where a b is a
 * normal double (same bits), else with extended exponents (u ~ 1e-300
 * with positions ~ 1e-149: L u underflows although L u / q is ~ 1e-299) */
static double prod_quot(double a, double b, double c)
{
  const double p = a * b;
  if ((p >= DBL_MIN && p <= DBL_MAX) || a == 0.0 || b == 0.0)
    return p / c;
  return sbi_xd_val(
      sbi_xd_div(sbi_xd_mul(sbi_xd_of(a), sbi_xd_of(b)), sbi_xd_of(c)));
}

/* a b / (c d) for a, b >= 0, c, d > 0, the same way: plain where a b
 * and c d are normal doubles (or a b = 0), else extended exponents */
static double prod_quot2(double a, double b, double c, double d)
{
  const double p = a * b, q = c * d;
  if (((p >= DBL_MIN && p <= DBL_MAX) || a == 0.0 || b == 0.0) &&
      q >= DBL_MIN && q <= DBL_MAX)
    return p / q;
  return sbi_xd_val(sbi_xd_div(sbi_xd_mul(sbi_xd_of(a), sbi_xd_of(b)),
                               sbi_xd_mul(sbi_xd_of(c), sbi_xd_of(d))));
}

/* num 2^-ks / (1 - rho): plain where 1 - rho is a normal double (the same
 * bits as ever), else with the extended 1 - rho (h->tiny) */
static double over_omr(const hit_par *h, double num, int ks)
{
  if (!h->tiny)
    return ldexp(num / h->omr, -ks);
  sbi_xd r = sbi_xd_div(sbi_xd_of(num), h->omrx);
  if (r.m != 0.0)
    r.e -= ks;
  return sbi_xd_val(r);
}

/* The density factor [1 - exp(-kw)] / (1 - rho), kw = 2ay/(sigma2 w),
 * where 1 - rho is below DBL_MIN (h->tiny): extended exponents; kw itself
 * then is usually below DBL_MIN too, and the factor is kw / (1 - rho) */
static sbi_xd tiny_factor(const hit_par *h, const hit_time *T, double kw)
{
  const sbi_xd num =
      kw >= DBL_MIN
          ? sbi_xd_of(-expm1(-kw))
          : sbi_xd_div(sbi_xd_mul(sbi_xd_of(2.0 * h->a), sbi_xd_of(h->y)),
                       sbi_xd_mul(sbi_xd_of(h->sigma2), sbi_xd_of(T->w.hi)));
  return sbi_xd_div(num, h->omrx);
}

/* e = -2 v log(1 - U (1 - rho)) / A^2, A = alpha + L1, in the inverse of
 * the law of L (sampler, quantile start); where 1 - rho is below DBL_MIN
 * its limit 2 U v k / A^2 = 4 U (min(a,y)/A)((alpha + max(a,y))/A) */
static double lmix_e(const hit_par *h, double U, double A)
{
  if (!h->tiny)
    return -2.0 * h->v * log1p(-U * h->omr) / (A * A);
  const double mx = h->a < h->y ? h->y : h->a;
  return 4.0 * U * (h->mn / A) * ((h->al.hi + mx) / A);
}

static int hit_setup(const char *fn, int b3, double x, double y, double a,
                     double sigma2, double t, hit_par *h, sb_result *res)
{
  if (!isfinite(x) || !isfinite(y) || !isfinite(a))
    return sbi_fail(res, SB_EDOM, fn, "x = %g, y = %g, a = %g must be finite",
                    x, y, a);
  if (!(sigma2 > 0.0) || !isfinite(sigma2))
    return sbi_fail(res, SB_EDOM, fn,
                    "sigma2 = %g must be positive and finite", sigma2);
  if (!(t > 0.0) || !isfinite(t))
    return sbi_fail(res, SB_EDOM, fn, "t = %g must be positive and finite",
                    t);
  if (b3 && (a < 0.0 || x < 0.0 || y < 0.0))
    return sbi_fail(res, SB_EDOM, fn, "x = %g, y = %g, a = %g: Bessel-3 "
                    "radii and level must be >= 0", x, y, a);
  h->b3 = b3;
  h->sigma2 = sigma2;
  h->t = t;
  h->v = sigma2 * t;
  h->a = a;
  h->y = y;
  h->trivial = T_NONE;
  h->tiny = 0;
  h->rmax = 0.95;
  h->rnx = 0.95;
  if (x <= a) {
    h->trivial = T_ZERO; /* starts on or below the level */
    return SB_SUCCESS;
  }
  if (b3 && a == 0.0) {
    if (y > 0.0)
      return sbi_fail(res, SB_EDOM, fn, "a = 0: a Bessel-3 bridge with y = "
                      "%g > 0 never hits 0", y);
    h->trivial = T_END; /* ends at the origin: T_0 = t */
    return SB_SUCCESS;
  }
  h->al = sbi_dd_sum(x, -a);
  sbi_dd be = sbi_dd_sum(y, -a);
  h->L1 = be.hi < 0.0 ? sbi_dd_neg(be) : be;
  if (b3) {
    h->L2 = sbi_dd_sum(y, a);
    h->mn = a < y ? a : y;
    double mx = a < y ? y : a;
    /* (L2 - L1)(2 alpha + L1 + L2)/(2v) = min(a,y) (2 alpha + 2 max(a,y))/v;
     * this and om1 by prod_quot: the products underflow where a ~ 1e-305
     * although k is a normal double (v = 1e-30: k ~ 1e-289, 1 - rho had
     * 13 bits and the cdf 5 digits) */
    double k = prod_quot(h->mn, 2.0 * (h->al.hi + mx), h->v);
    h->omrx = sbi_xd_of(-expm1(-k));
    if (!(k >= DBL_MIN)) {
      /* all positions below ~1e-154 sqrt(v): 1 - rho = k to rounding, kept
       * with an extended exponent, and (2) is the mixture with the weight
       * (alpha + L) (its exponential is 1 to rounding), normalised by
       * omrx.  Where min(a, y) is negligible against alpha + max(a, y)
       * (or subnormal) the mixture range is, and the limit law P_L1 is
       * right to rounding (docs/bridge.md) */
      if (h->mn >= DBL_MIN && h->mn > 0x1p-60 * (h->al.hi + mx)) {
        h->tiny = 1;
        h->omrx = sbi_xd_div(sbi_xd_mul(sbi_xd_of(h->mn),
                                        sbi_xd_of(2.0 * (h->al.hi + mx))),
                             sbi_xd_of(h->v));
      } else
        h->mn = 0.0;
    }
    h->rho = exp(-k);
    h->omr = -expm1(-k);
    h->om1 = exp(-prod_quot(h->mn, 2.0 * (h->al.hi + h->L1.hi) + h->mn,
                            2.0 * h->v));
  }
  return SB_SUCCESS;
}

/* The variance sigma2 u t w in double-double where it is within
 * [2^-900, DBL_MAX] (same bits as ever); else its factors are scaled by
 * powers of two (exact) to [1, 2) and den carries 2^(2k) (scaled
 * positions up to 2^990 make sigma2 t tiny, and sigma2 u t w underflowed
 * where the law still had its mass: the cdf read 0 for a law that is
 * concentrated near u = 0) */
static hit_time make_time(const hit_par *h, double u, sbi_dd w)
{
  hit_time T;
  T.u = u;
  T.w = w;
  T.k = 0;
  T.den = sbi_dd_mul(sbi_dd_mul_d(sbi_dd_prod(h->sigma2, u), h->t), w);
  if (T.den.hi >= 0x1p-900 && isfinite(T.den.hi)) {
    T.q = sqrt(T.den.hi);
    T.qx = sbi_xd_of(T.q);
    return T;
  }
  int i1 = -ilogb(h->sigma2), i2 = -ilogb(u), i3 = -ilogb(h->t),
      i4 = -ilogb(w.hi);
  if ((i1 + i2 + i3 + i4) & 1)
    i1++;
  const sbi_dd ws = {ldexp(w.hi, i4), ldexp(w.lo, i4)};
  T.den = sbi_dd_mul(sbi_dd_mul_d(sbi_dd_prod(ldexp(h->sigma2, i1),
                                              ldexp(u, i2)),
                                  ldexp(h->t, i3)),
                     ws);
  T.k = (i1 + i2 + i3 + i4) / 2;
  const double qs = sqrt(T.den.hi);
  T.qx = sbi_xd_norm(qs, -T.k);
  T.q = sbi_xd_val(T.qx);
  return T;
}

/* a b / q (a, b >= 0) with q = T->qx: +inf above 1e300 (the IG kernel
 * then sees a negligible second term; its values need no more) */
static double over_q(const hit_time *T, double a, double b)
{
  if (T->k == 0)
    return prod_quot(a, b, T->q);
  const double r = sbi_xd_val(
      sbi_xd_div(sbi_xd_mul(sbi_xd_of(a), sbi_xd_of(b)), T->qx));
  return r > 1e300 ? 1e300 : r;
}

/* IG point of the drift length L at time T. */
static sbi_igpt point(const hit_par *h, const hit_time *T, sbi_dd L)
{
  sbi_dd num = sbi_dd_add(sbi_dd_mul_d(L, T->u),
                          sbi_dd_neg(sbi_dd_mul(h->al, T->w)));
  if (T->k == 0)
    return sbi_igpt_make(num, T->den, prod_quot(h->al.hi, T->w.hi, T->q),
                         prod_quot(L.hi, T->u, T->q));
  return sbi_igpt_make_x(num, T->den, T->k, over_q(T, h->al.hi, T->w.hi),
                         over_q(T, L.hi, T->u));
}

/* ------------------------------------------------ B3B: the mixture (2) */

typedef struct {
  const hit_par *h;
  const hit_time *T;
  int sf;
  double scale; /* h->tiny: alpha + max(a, y) */
} mix_ctx;

/* integrand of (2) in l = L - L1 in [0, 2 min(a, y)] (exact end points;
 * L = L1 + l is formed in double-double) */
static double mix_integrand(double l, void *vc)
{
  const mix_ctx *m = vc;
  const hit_par *h = m->h;
  double al = h->al.hi;
  sbi_dd Ld = sbi_dd_add(h->L1, (sbi_dd){l, 0.0});
  sbi_igpt p = point(h, m->T, Ld);
  /* weight (alpha + L)/v exp(-((alpha+L)^2 - (alpha+L1)^2)/(2v)) / (alpha+L)
   * times (alpha + L) P_L = L F + alpha F_sb (or the complements) */
  double wgt = exp(-l * (2.0 * (al + h->L1.hi) + l) / (2.0 * h->v));
  if (h->tiny) /* times 2 mn (alpha + max(a, y)) / (v (1 - rho)) = 1: the
                * integral stays a normal double */
    return wgt * (sbi_ig_mix(&p, Ld.hi, al, m->sf, NULL) / m->scale) /
           (2.0 * h->mn);
  return wgt / h->v * sbi_ig_mix(&p, Ld.hi, al, m->sf, NULL);
}

/* (2) by quadrature over l in [0, 2 min(a, y)].  Where (2) is used the
 * integrand varies little over the interval (the direct form (1) would
 * cancel otherwise), so 3- and 4-point Gauss-Legendre (GSL's fixed tables,
 * 7 evaluations) agree to ~1e-16; |I4 - I3| bounds the error of I4.  If
 * they disagree by more than 1e-13 relative, 21-point Gauss-Kronrod
 * (gsl_integration_qk21, which never calls the GSL error handler) on 1, 2,
 * 4, ... 64 equal panels until GSL's error estimate is below 1e-13.
 * Returns the probability, *err its absolute error bound. */
static double mixture(const hit_par *h, const hit_time *T, int sf,
                      double *err)
{
  mix_ctx m = {h, T, sf, h->al.hi + (h->a < h->y ? h->y : h->a)};
  gsl_function F = {mix_integrand, &m};
  double hi = 2.0 * h->mn, tot = 0.0, e = 0.0;
  gsl_integration_glfixed_table *g3 = gsl_integration_glfixed_table_alloc(3);
  gsl_integration_glfixed_table *g4 = gsl_integration_glfixed_table_alloc(4);
  int done = 0;
  if (g3 && g4) {
    double i3 = gsl_integration_glfixed(&F, 0.0, hi, g3);
    tot = gsl_integration_glfixed(&F, 0.0, hi, g4);
    e = fabs(tot - i3) + 8.0 * EPS * fabs(tot);
    done = e <= 1e-13 * fabs(tot);
  }
  if (g3)
    gsl_integration_glfixed_table_free(g3);
  if (g4)
    gsl_integration_glfixed_table_free(g4);
  for (int n = 1; !done && n <= 64; n *= 2) {
    tot = 0.0;
    e = 0.0;
    double step = hi / n;
    for (int i = 0; i < n; i++) {
      double r, ae, ra, rc;
      double b = i == n - 1 ? hi : (i + 1) * step;
      gsl_integration_qk21(&F, i * step, b, &r, &ae, &ra, &rc);
      tot += r;
      e += ae;
    }
    done = e <= 1e-13 * fabs(tot);
  }
  if (h->tiny) { /* normalised in the integrand */
    *err = e + 4.0 * EPS * fabs(tot);
    return tot;
  }
  *err = (e + 4.0 * EPS * fabs(tot)) / h->omr;
  return tot / h->omr;
}

/* ------------------------------- B3B: (2) expanded about its midpoint */

#define NX_KMAX 15     /* highest (odd) order of the expansion */
#define NX_NPAN 4      /* at most this many panels */
#define NX_TOL (2.0 * EPS)  /* truncation bound accepted (relative) */
#define NX_RTOL (8.0 * EPS) /* rounding bound of the corrections accepted */

/* G(L1) - rho G(L2), the numerator of (1), for a short range of L: on
 * panels of the range, a Taylor expansion about the panel's middle with a
 * rigorous bound of its truncation error (the caller falls back to the
 * quadrature when no order up to NX_KMAX on up to NX_NPAN panels meets
 * NX_TOL).
 *
 * In kap = L u/q (z = eps = alpha w/q, r = t/u) the IG laws are
 *   F(u; L) = ex(L) H(kap),  H = M(z - kap) + M(z + kap)      (CDF),
 *   SF(u; L) = ex(L) H(kap), H = M(kap - z) - M(kap + z)      (SF),
 * and exp(-(alpha+L)^2/(2v)) ex(L) = exp(-alpha^2/(2 sigma2 u)) exp(-r
 * kap^2/2) (the exponents add up to alpha^2/(2 sigma2 u) + L^2/(2 sigma2
 * w)).  So the panel l = L - L1 in [lc - hw, lc + hw], with kap = km + tau,
 * km at Lc = L1 + lc, tau in [-dl, dl], dl = hw u/q, contributes
 *   ex(Lc) om [Ft(-dl) - Ft(dl)],  om = exp(-lc (2(alpha + L1) + lc)/(2v)),
 *   Ft(tau) = P(tau) H(km + tau),  P(tau) = exp(-r km tau - r tau^2/2).
 * As M' = xM - 1/sqrt(2 pi), g = -Ft' = P(tau) [(r-1) kap SA + z SB] with
 * SA = M(z-kap) + M(z+kap), SB = M(z-kap) - M(z+kap) for the CDF (for the
 * SF the two swapped, of M(kap-z), M(kap+z)): g(0) > 0 is the integrand of
 * (2) at Lc.  Ft(-dl) - Ft(dl) = 2 dl g(0) - 2 sum_{k odd >= 3} f_k dl^k,
 * f_k = sum_i p_{k-i} h_i (Leibniz), p_j the Taylor coefficients of P
 * ((j+1) p_{j+1} = -r km p_j - r p_{j-1}) and h_i those of H, from
 * M^(i)(x) = (-1)^i j_i(x), j_0 = M, j_1 = 1/sqrt(2 pi) - x M,
 * j_{k+1} = k j_{k-1} - x j_k (by parts in j_k = int_0^inf s^k phi(s)
 * e^{-xs} ds).  The leading term takes SB (resp. SA) from sbi_mills_diff:
 * no cancellation.  The corrections are small (relative size about
 * (r km dl)^2 ~ (hw L/(sigma2 w))^2); their rounding errors are bounded by
 * running the recurrences on absolute values (the forward recurrence
 * loses accuracy for x > 0, but only relative to that majorant).
 *
 * Truncation (Cauchy's estimate; Ft is entire): on |tau| = R,
 * |P| <= exp(r R (km + R/2)); from M(x) = int_0^inf phi(s) e^{-xs} ds,
 * |M(x + iy)| <= M(x), |cosh(ks)| <= e^{|Re k| s}, |sinh(ks)| <= sinh(|k|
 * s) and sinh(a + b) <= (1 + b/a) e^b sinh(a), so |(r-1) kap SA + z SB| <=
 * 2 (1 + R/km) E[e^{R S}] g(0), S with a density proportional to
 * exp(-(s + lo)^2/2) times sinh(.) or 1 on s > 0 (lo = -c for the CDF, c
 * for the SF).  Both are strongly log-concave (V'' >= 1), hence E[e^{R S}]
 * <= exp(R E[S] + R^2/2) (Bakry & Emery 1985; Ledoux 2001, ch. 5), and by
 * likelihood ratios E[S] <= the mean of s exp(-(s + lo)^2/2), at most its
 * mode (sqrt(lo^2 + 4) - lo)/2 plus sqrt 3 (a unimodal law with variance
 * <= 1: Johnson & Rogers 1951; Brascamp & Lieb 1976).  So the Taylor
 * coefficients of g satisfy |g_k| <= Mg/R^k, Mg = 2 (1 + R/km) e^{E(R)}
 * g(0), E(R) = r R (km + R/2) + R mbar + R^2/2, and the terms left out
 * after order K sum to at most 2 dl g(0) C eta^(K+1)/(K+2), eta = dl/R,
 * C = 2 (1 + R/km) e^{E(R)}/(1 - eta^2). */

/* The order K (odd, <= NX_KMAX) that makes the truncation bound of a panel
 * <= NX_TOL relative (*tail: the bound), or 0 if none does.  R minimises
 * the bound for K = 9 (all K then follow from one exponential). */
static int nx_order(double r, double km, double lo, double dl, double *tail)
{
  double mbar = 0.5 * (sqrt(lo * lo + 4.0) - lo) + 1.7320508075688772935;
  double A2 = 2.0 * (r + 1.0), B = r * km + mbar;
  double R = (-B + sqrt(B * B + 20.0 * A2)) / A2, eta = dl / R;
  if (!(eta < 0.5) || !(km > 0.0))
    return 0;
  double E = r * R * (km + 0.5 * R) + R * mbar + 0.5 * R * R;
  double cst = 2.0 * (1.0 + R / km) * exp(E) / (1.0 - eta * eta);
  /* the smallest odd K with cst eta^(K+1)/(K+2) <= NX_TOL (no logs: at
   * most NX_KMAX/2 + 1 products) */
  double e2 = eta * eta, p = e2;
  int K = 1;
  while (!(cst * p <= NX_TOL * (K + 2))) {
    K += 2;
    p *= e2;
    if (K > NX_KMAX)
      return 0;
  }
  *tail = cst * p / (K + 2);
  return K;
}

/* One panel: ex(Lc) [Ft(-dl) - Ft(dl)] at the point pc (L = Lc) to order
 * K, times dls/dl (a power of two: see narrow); *err its absolute error
 * bound (the truncation bound `tail` relative included), scaled alike.
 * Returns 0 if rounding could exceed NX_RTOL relative. */
static int nx_panel(const hit_par *h, const hit_time *T, const sbi_igpt *pc,
                    double dl, double dls, int K, double tail, int sf,
                    double *val, double *err)
{
  double u = T->u, z = pc->eps, km = pc->kap, c = pc->c;
  double lo = sf ? c : -c, b = km + z;
  double mlo = sbi_mills(lo), mb = sbi_mills(b);
  if (!isfinite(mlo) || !(pc->ex > 0.0))
    return 0;
  double rd;
  double dif = sbi_mills_diff_m(sf ? km : z, sf ? z : km, mlo, mb, &rd);
  double sum = mlo + mb;
  double r = h->t / u;
  double SA = sf ? dif : sum, SB = sf ? sum : dif;
  double rA = sf ? rd : 5.0 * EPS, rB = sf ? 5.0 * EPS : rd;
  double tA = (T->w.hi / u) * km * SA, tB = z * SB, g0 = tA + tB;
  /* Taylor coefficients of g = P Q, Q = (r-1) kap SA + z SB, scaled by
   * dl^k: P_k; s_i = j_i dl^i / i! at lo (a_i) and b (b_i), so that the
   * coefficients of M(lo -+ tau) and M(b + tau) are (+-1)^i a_i and
   * (-1)^i b_i.  Rounding: the same recurrences on |.| (with x = max(|lo|,
   * b) for both points) give majorants of the coefficients; the error of
   * the g_k (k >= 2) is below (6K + 16) EPS times the majorant of their
   * sum, at most sum(Pm) sum(Qm) less the parts of order 0 and 1. */
  double rm1 = T->w.hi / u, ad = r * km * dl, rd2 = r * dl * dl;
  double d2 = dl * dl, xm = fmax(fabs(lo), b);
  double P[NX_KMAX], Q[NX_KMAX];
  P[0] = 1.0;
  P[1] = -ad;
  double pm0 = 1.0, pm1 = ad, psum = 1.0 + ad;
  for (int k = 2; k < K; k++) {
    double pmk = (ad * pm1 + rd2 * pm0) / k;
    P[k] = (-ad * P[k - 1] - rd2 * P[k - 2]) / k;
    psum += pmk;
    pm0 = pm1;
    pm1 = pmk;
  }
  /* CDF: SA = M(lo - tau) + M(b + tau), SB = M(lo - tau) - M(b + tau);
   * SF: SA = M(lo + tau) - M(b + tau), SB = M(lo + tau) + M(b + tau) */
  double a0 = mlo, a1 = dl * (INV_RT2PI - lo * mlo);
  double b0 = mb, b1 = dl * (INV_RT2PI - b * mb);
  double m0 = sum, m1 = dl * (2.0 * INV_RT2PI + xm * sum);
  double cq = rm1 * km + z, qm0 = cq * m0, qm1 = cq * m1 + rm1 * dl * m0;
  double qsum = qm0 + qm1, SAp = SA;
  Q[0] = g0;
  for (int k = 1; k < K; k++) {
    if (k >= 2) {
      double ik = 1.0 / k;
      double a2 = (d2 * a0 - lo * dl * a1) * ik;
      double b2 = (d2 * b0 - b * dl * b1) * ik;
      double m2 = (d2 * m0 + xm * dl * m1) * ik;
      qsum += cq * m2 + rm1 * dl * m1;
      a0 = a1;
      a1 = a2;
      b0 = b1;
      b1 = b2;
      m0 = m1;
      m1 = m2;
    }
    double sg = (k & 1) ? -1.0 : 1.0, SAk, SBk;
    if (sf) {
      SAk = sg * (a1 - b1);
      SBk = sg * (a1 + b1);
    } else {
      SAk = a1 + sg * b1;
      SBk = a1 - sg * b1;
    }
    Q[k] = rm1 * (km * SAk + dl * SAp) + z * SBk;
    SAp = SAk;
  }
  /* the integral of tau^k over [-dl, dl] is 2 dl^(k+1)/(k+1) */
  double corr = 0.0;
  for (int k = 2; k < K; k += 2) {
    double gk = 0.0;
    for (int i = 0; i <= k; i++)
      gk += P[k - i] * Q[i];
    corr += 2.0 * dls * gk / (k + 1);
  }
  double ecorr = K < 3 ? 0.0
                       : 2.0 * dls * (6.0 * K + 16.0) * EPS *
                             (psum * qsum - qm0 - qm1 - ad * qm0);
  double tot = 2.0 * dls * g0 + corr;
  if (!(tot > 0.0) || ecorr > NX_RTOL * tot)
    return 0;
  *val = pc->ex * tot;
  *err = pc->ex * (2.0 * dls * (tA * (rA + 3.0 * EPS) + tB * (rB + 3.0 * EPS) +
                               tail * g0) + ecorr) + 4.0 * EPS * *val;
  return 1;
}

/* (2) by the expansion: 1 and the probability in *val (*err: its absolute
 * error bound), or 0 if the bounds do not hold.  pm: the point at the mid
 * L (one panel). */
static int narrow(const hit_par *h, const hit_time *T, const sbi_igpt *pm,
                  int sf, double *val, double *err)
{
  double r = h->t / T->u, uq = T->u / T->q, A = h->al.hi + h->L1.hi;
  for (int n = 1; n <= NX_NPAN; n *= 2) {
    double hw = h->mn / n, dl = hw * uq;
    /* the panels' values are proportional to dl, as is 1 - rho: where dl
     * is tiny (u ~ 1e-300 with min(a, y) ~ 1e-149: 2 dl ex g0 underflows
     * although the ratio is a normal probability) they are formed scaled
     * by 2^ks (exact: the same bits once scaled back wherever nothing
     * underflowed; ks <= 900 keeps them below 2^900 since the numerator
     * of (1) is at most 1 - rho <= 1) */
    const int ks = dl < 0x1p-300 ? (ilogb(dl) < -900 ? 900 : -ilogb(dl)) : 0;
    const double dls = ldexp(dl, ks);
    sbi_igpt pc[NX_NPAN];
    int K[NX_NPAN];
    double tail[NX_NPAN];
    int ok = 1;
    for (int j = 0; j < n && ok; j++) {
      pc[j] = n == 1 ? *pm
                     : point(h, T, sbi_dd_add(h->L1, (sbi_dd){(2 * j + 1) *
                                                                  hw, 0.0}));
      K[j] = nx_order(r, pc[j].kap, sf ? pc[j].c : -pc[j].c, dl, &tail[j]);
      ok = K[j] > 0;
    }
    if (!ok)
      continue;
    double tot = 0.0, e = 0.0;
    for (int j = 0; j < n && ok; j++) {
      double vj = 0.0, ej = 0.0, lc = (2 * j + 1) * hw;
      ok = nx_panel(h, T, &pc[j], dl, dls, K[j], tail[j], sf, &vj, &ej);
      double om =
          n == 1 ? h->om1 : exp(-prod_quot(lc, 2.0 * A + lc, 2.0 * h->v));
      tot += om * vj;
      e += om * ej;
    }
    if (!ok)
      return 0; /* rounding, not truncation: more panels would not help */
    *val = over_omr(h, tot, ks);
    *err = over_omr(h, e + 4.0 * EPS * tot, ks);
    return 1;
  }
  return 0;
}

/* ---------------------------------------------------- core evaluation */

/* cdf and sf of the conditioned law at T (0 < u < t), both computed
 * directly (the smaller one never as 1 - the other).  err: absolute. */
typedef struct {
  double cdf, sf, ecdf, esf; /* values and their absolute error bounds */
  double dens; /* dG/dy, y = log s (the density of log S) */
  double sfl;  /* d log(dens)/dy (quantile iteration) */
  double sfl2; /* d^2 log(dens)/dy^2 */
  double rused; /* B3B: rho G2/G1 of the value returned by (1), else 0 */
} hit_prob;

/* the complement of a value with absolute error e: add the rounding of
 * 1 - x */
static double comp_err(double e, double c) { return e + EPS * c; }

/* d^2 log(dens)/dy^2 of the IG part: dens = eps phi(c) with
 * d eps/dy = -eps/2, d kap/dy = kap/2, so dc/dy = b/2 and db/dy = c/2
 * (b = kap + eps): d/dy (-1/2 - c b/2) = -(b^2 + c^2)/4 */
static double ig_sfl2(const sbi_igpt *p)
{
  double b = p->kap + p->eps;
  return -0.25 * (b * b + p->c * p->c);
}

/* BB: only the requested tail is evaluated (the other is 1 - it) */
static hit_prob bb_prob(const hit_par *h, const hit_time *T, int want)
{
  hit_prob r;
  r.rused = 0.0;
  sbi_igpt p = point(h, T, h->L1);
  double rel;
  r.dens = p.eps * p.ex * INV_RT2PI;
  r.sfl = -0.5 - 0.5 * p.c * (p.kap + p.eps);
  r.sfl2 = ig_sfl2(&p);
  if (want == W_CDF) {
    r.cdf = sbi_ig_cdf(&p, &rel);
    r.sf = 1.0 - r.cdf;
    r.ecdf = (rel + 2.0 * EPS) * r.cdf;
    r.esf = comp_err(r.ecdf, r.sf);
  } else {
    r.sf = sbi_ig_sf(&p, &rel);
    r.cdf = 1.0 - r.sf;
    r.esf = (rel + 2.0 * EPS) * r.sf;
    r.ecdf = comp_err(r.esf, r.cdf);
  }
  return r;
}

static hit_prob b3_prob(const hit_par *h, const hit_time *T, int want)
{
  hit_prob r;
  double rel1, rel2;
  r.rused = 0.0;
  if (h->mn == 0.0) {
    /* y = 0: the mixture collapses to the single law P_a (L1 = L2 = a);
     * likewise a -> 0 (L1 = L2 = y).  The density factor
     * [1 - exp(-2ay/(sigma2 w))]/(1 - rho) tends to M t/((alpha + M) w),
     * M = max(a, y) (it was a t/((alpha + a) w) also where a -> 0: ~1e-320
     * times the density at a = 1e-320) */
    const double mx = h->a < h->y ? h->y : h->a;
    sbi_igpt p = point(h, T, h->L1);
    r.dens = p.eps * p.ex * INV_RT2PI * mx * h->t /
             ((h->al.hi + mx) * T->w.hi);
    /* d log(1/w)/dy = u/t */
    r.sfl = -0.5 - 0.5 * p.c * (p.kap + p.eps) + T->u / h->t;
    r.sfl2 = ig_sfl2(&p) + (T->u / h->t) * (T->w.hi / h->t);
    double al = h->al.hi, L = h->L1.hi, w = al + L;
    double f = sbi_ig_cdf(&p, &rel1), g = sbi_ig_sbcdf(&p, &rel2);
    r.cdf = (L * f + al * g) / w;
    r.ecdf = (L * f * rel1 + al * g * rel2) / w + 4.0 * EPS * r.cdf;
    f = sbi_ig_sf(&p, &rel1);
    g = sbi_ig_sbsf(&p, &rel2);
    r.sf = (L * f + al * g) / w;
    r.esf = (L * f * rel1 + al * g * rel2) / w + 4.0 * EPS * r.sf;
    return r;
  }
  /* rho G2/G1 >= rho (docs/bridge.md), so for rho > 0.95 (1) cancels:
   * straight to the expansion of (2) about its mid L, which also tells
   * which tail is the smaller one (c at the mid L: about the median); the
   * point at L1 (for the density and its derivatives, which only steer the
   * quantile) then follows from the mid one: kap and c smaller by dl */
  int nx = h->rho > h->rnx;
  sbi_igpt p1, pm = {0.0, 0.0, 0.0, 0.0, {0.0, 0.0}}, p2 = pm;
  if (nx) {
    pm = point(h, T, sbi_dd_add(h->L1, (sbi_dd){h->mn, 0.0}));
    double dl = prod_quot(h->mn, T->u, T->q);
    p1 = pm;
    p1.kap -= dl;
    p1.c -= dl;
    p1.ex = exp(-0.5 * p1.c * p1.c);
  } else {
    p1 = point(h, T, h->L1);
    p2 = point(h, T, h->L2);
  }
  /* density: the BB one times hw / (1 - rho), hw = 1 - exp(-k/w),
   * k = 2ay/sigma2; d log(hw)/dy = (1 - hw)(k/w)(u/t)/hw as dw/dy = -wu/t */
  double kw = prod_quot2(2.0 * h->a, h->y, h->sigma2, T->w.hi);
  double hw = -expm1(-kw);
  r.dens = p1.eps * p1.ex * INV_RT2PI *
           (h->tiny ? sbi_xd_val(tiny_factor(h, T, kw)) : hw / h->omr);
  /* with ph = (1 - hw)/hw = 1/(e^{k/w} - 1) and z1 = d(k/w)/dy =
   * (k/w)(u/t) = d^2(k/w)/dy^2: d^2 log hw/dy^2 = ph z1 (1 - z1/hw) */
  double z1 = kw * (T->u / h->t), ph = (1.0 - hw) / hw;
  r.sfl = -0.5 - 0.5 * p1.c * (p1.kap + p1.eps) + ph * z1;
  r.sfl2 = ig_sfl2(&p1) + ph * z1 * (1.0 - z1 / hw);
  if (h->tiny && !(hw >= DBL_MIN)) { /* their limits as kw -> 0 */
    r.sfl = -0.5 - 0.5 * p1.c * (p1.kap + p1.eps) + T->u / h->t;
    r.sfl2 = ig_sfl2(&p1) + (T->u / h->t) * (T->w.hi / h->t);
  }
  int first = nx ? pm.c > 0.0 : want == W_SF;
  int failed = 0; /* bit sf: the expansion's bounds failed for that tail */
  /* the requested (or likely smaller) tail first; if it is the larger one
   * (> 1/2) the other is computed directly and this one is its
   * complement */
  for (int pass = 0; pass < 2; pass++) {
    int sf = first != (pass == 1);
    double val, err;
    int got = nx && narrow(h, T, &pm, sf, &val, &err);
    if (!got && h->tiny) /* rho is 1 in doubles: (1) is 0/0, only (2) */
      val = mixture(h, T, sf, &err);
    if (got || h->tiny) {
      r.rused = 0.0; /* accurate: not (1) */
      if (pass == 0 && val > 0.5)
        continue;
    } else {
      if (nx) {
        nx = 0;
        failed = 1 << sf;
        p1 = point(h, T, h->L1);
        p2 = point(h, T, h->L2);
      }
      double g1 = sf ? sbi_ig_sf(&p1, &rel1) : sbi_ig_cdf(&p1, &rel1);
      double g2 = sf ? sbi_ig_sf(&p2, &rel2) : sbi_ig_cdf(&p2, &rel2);
      g2 *= h->rho;
      double num = g1 - g2;
      if (pass == 0 && num > 0.5 * h->omr)
        continue; /* the larger tail: compute the other one */
      r.rused = g1 > 0.0 ? g2 / g1 : 0.0;
      if (g2 <= h->rmax * g1) {
        val = num / h->omr;
        err = (g1 * rel1 + g2 * rel2 + 2.0 * EPS * (g1 + g2)) / h->omr +
              2.0 * EPS * val;
      } else {
        /* (1) cancels although rho <= 0.95: the expansion if its bounds
         * hold (on up to NX_NPAN panels), else the quadrature */
        if (!(pm.kap > 0.0)) /* not yet computed */
          pm = point(h, T, sbi_dd_add(h->L1, (sbi_dd){h->mn, 0.0}));
        if ((failed & (1 << sf)) || !narrow(h, T, &pm, sf, &val, &err))
          val = mixture(h, T, sf, &err);
      }
    }
    if (sf) {
      r.sf = val;
      r.esf = err;
      r.cdf = 1.0 - val;
      r.ecdf = comp_err(err, r.cdf);
    } else {
      r.cdf = val;
      r.ecdf = err;
      r.sf = 1.0 - val;
      r.esf = comp_err(err, r.sf);
    }
    break;
  }
  return r;
}

/* B3B where sqrt(sigma2 u t w) < DBL_MIN (positions beyond ~2^1000
 * sqrt(v) after the rescaling): each law P_L of the mixture (2) is a step
 * at u_L = t alpha/(alpha + L) on the scale of the doubles, so the cdf is
 * the mass of the L >= alpha w/u = Lu: (exp(-d) - rho)/(1 - rho),
 * d = (Lu - L1)(2 alpha + L1 + Lu)/(2v) (the law of L, see the sampler);
 * 0 or 1 where Lu is outside (L1, L2).  Where rho underflows, (1) is
 * G(u; L1) itself (1/2 where c = 0, as for BB) */
static hit_prob b3_prob_step(const hit_par *h, const hit_time *T)
{
  hit_prob r = {0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
  const sbi_igpt p1 = point(h, T, h->L1), p2 = point(h, T, h->L2);
  double rel;
  if (h->rho < DBL_MIN) { /* (1) is the BB law with L1 */
    r.cdf = sbi_ig_cdf(&p1, &rel);
    r.ecdf = (rel + 2.0 * EPS) * r.cdf;
    r.sf = sbi_ig_sf(&p1, &rel);
    r.esf = (rel + 2.0 * EPS) * r.sf;
  } else if (p1.c >= 0.0) {
    r.cdf = 1.0;
    r.sf = 0.0;
  } else if (p2.c > 0.0) {
    const double Lu = prod_quot(h->al.hi, T->w.hi, T->u);
    const double d = prod_quot(Lu - h->L1.hi, 2.0 * h->al.hi + h->L1.hi + Lu,
                               2.0 * h->v);
    r.cdf = (exp(-d) - h->rho) / h->omr;
    r.sf = -expm1(-d) / h->omr;
    r.ecdf = 4.0 * EPS * r.cdf;
    r.esf = 4.0 * EPS * r.sf;
  }
  return r;
}

/* want: W_CDF or W_SF, the value whose relative accuracy matters (B3B
 * computes the smaller tail directly and the other as its complement) */
static hit_prob prob_at(const hit_par *h, const hit_time *T, int want)
{
  if (h->b3 && h->mn > 0.0 && !(T->q >= DBL_MIN))
    return b3_prob_step(h, T);
  return h->b3 ? b3_prob(h, T, want) : bb_prob(h, T, want);
}

/* The density alpha t / (q u) phi(c) ratio where the plain product leaves
 * the normal doubles: the prefactor can overflow while exp(-c^2/2)
 * underflows (u ~ 1e-300: NaN from inf * 0), or c^2/2 be NaN (alpha or
 * |beta| near DBL_MAX overflow the double-double products).  Extended
 * exponents; c^2/2 from the point where it is finite, else from plain
 * doubles (|c| > 1e154 there, exp(-c^2/2) = 0).  +inf if the density
 * exceeds DBL_MAX, 0 or subnormal below DBL_MIN. */
static double pdf_extreme(const hit_par *h, const hit_time *T,
                          const sbi_igpt *p, sbi_xd ratio, int e)
{
  sbi_dd E = p->E;
  if (!(E.hi >= 0.0)) {
    double c = sbi_xd_val(sbi_xd_div(sbi_xd_of(h->L1.hi * T->u), T->qx)) -
               sbi_xd_val(sbi_xd_div(sbi_xd_of(h->al.hi * T->w.hi), T->qx));
    E = (sbi_dd){fabs(c) < 1e154 ? 0.5 * c * c : INFINITY, 0.0};
  }
  if (!(E.hi < 1e6))
    return 0.0;
  sbi_xd ex = sbi_xd_expneg(E.hi);
  ex.m *= 1.0 - E.lo;
  sbi_xd f = sbi_xd_div(sbi_xd_mul(sbi_xd_of(h->al.hi), sbi_xd_of(h->t)),
                        sbi_xd_mul(T->qx, sbi_xd_of(T->u)));
  f = sbi_xd_mul(sbi_xd_mul(f, ex), sbi_xd_mul(sbi_xd_of(INV_RT2PI), ratio));
  if (f.m != 0.0)
    f.e += e;
  return sbi_xd_val(f);
}

/* density at T (0 < u < t) times 2^e (e: minus the binary exponent of a
 * time scale, so that a density that leaves the doubles only in the
 * scaled units is still right, t = 2^200 with positions 2^1000: +inf
 * before), with relative error bound *rel (+inf if it exceeds DBL_MAX) */
static double pdf_at(const hit_par *h, const hit_time *T, int e,
                     double *rel)
{
  /* BB hitting density given T <= t: f_alpha(u) g_{t-u}(L1)/g_t(alpha+L1)
   * = alpha t / (q u) phi(c) */
  sbi_igpt p = point(h, T, h->L1);
  double f = h->al.hi * h->t / (T->q * T->u) * p.ex * INV_RT2PI;
  *rel = 8.0 * EPS;
  double ratio = 1.0;
  sbi_xd rx = sbi_xd_of(1.0);
  if (h->b3) {
    /* B3B: times [1 - exp(-2ay/(sigma2 w))] / (1 - rho); for min(a, y)
     * -> 0 the limit M t / ((alpha + M) w), M = max(a, y) */
    if (h->mn == 0.0) {
      const double mx = h->a < h->y ? h->y : h->a;
      ratio = mx * h->t / ((h->al.hi + mx) * T->w.hi);
      rx = sbi_xd_of(ratio);
    } else {
      const double kw = prod_quot2(2.0 * h->a, h->y, h->sigma2, T->w.hi);
      ratio = h->tiny ? sbi_xd_val(tiny_factor(h, T, kw))
                      : -expm1(-kw) / h->omr;
      /* 2ay/(sigma2 w) below DBL_MIN (a, y tiny against sqrt(v) at
       * x ~ 1e298: the ratio underflowed and the density was 0 * inf =
       * NaN with status 0): the factor is 2ay/(sigma2 w) itself, with an
       * extended exponent */
      rx = h->tiny ? tiny_factor(h, T, kw)
           : kw < DBL_MIN
               ? sbi_xd_div(sbi_xd_div(sbi_xd_mul(sbi_xd_of(2.0 * h->a),
                                                  sbi_xd_of(h->y)),
                                       sbi_xd_mul(sbi_xd_of(h->sigma2),
                                                  sbi_xd_of(T->w.hi))),
                            h->omrx)
               : sbi_xd_of(ratio);
    }
    *rel += 6.0 * EPS;
    f *= ratio;
  }
  if (f >= DBL_MIN && f <= DBL_MAX) {
    const double g = ldexp(f, e);
    if (g >= DBL_MIN && g <= DBL_MAX)
      return g;
  }
  return rx.m > 0.0 ? pdf_extreme(h, T, &p, rx, e) : 0.0;
}

/* --------------------------------------------------- pdf, cdf, sf */

/* Arguments far from unit scale.  The law of T/t depends on x, y, a only
 * through them over sqrt(sigma2 t), so positions, sigma2 and times are
 * scaled by powers of two (exactly) to sigma2 t in [1, 4) and t in
 * [1, 2) when sigma2 t^3 is outside 2^(+-600) (the products sigma2 u t w
 * of the evaluation under- or overflowed: cdf 1 for every u) or a
 * position is above 2^990; positions are kept below 2^990 (sigma2 t then
 * ends below 1: positions beyond DBL_MAX sqrt(sigma2 t) overflowed to
 * +-inf, SB_EDOM).  Returns
 * the binary exponent of the time scale (0: nothing done; invalid
 * arguments are left to hit_setup's messages). */
#define POS_EMAX 989 /* scaled positions below 2^990 */

static int rescale(int b3, double *x, double *y, double *a, double *sigma2,
                   double *t, double *u)
{
  if (!isfinite(*x) || !isfinite(*y) || !isfinite(*a) ||
      !(*sigma2 > 0.0) || !isfinite(*sigma2) || !(*t > 0.0) ||
      !isfinite(*t) || (b3 && (*a < 0.0 || *x < 0.0 || *y < 0.0)))
    return 0;
  const int et = ilogb(*t), ev = ilogb(*sigma2) + et;
  /* the largest position's exponent (the double-double products of the
   * evaluation overflow above ~2^995: positions are kept below 2^990) */
  int pe = INT_MIN;
  const double pos[3] = {*x, *y, *a};
  for (int i = 0; i < 3; i++)
    if (pos[i] != 0.0 && ilogb(pos[i]) > pe)
      pe = ilogb(pos[i]);
  if (abs(ev + 2 * et) < 600 && pe <= POS_EMAX)
    return 0;
  /* sigma2 t in [1, 4) where the positions allow it; else the positions
   * scaled to below 2^(POS_EMAX + 1) and sigma2 t below 1 (positions
   * beyond DBL_MAX sqrt(sigma2 t) overflowed here: SB_EDOM) */
  const int es = pe != INT_MIN && pe - ev / 2 > POS_EMAX ? pe - POS_EMAX
                                                        : ev / 2;
  *x = ldexp(*x, -es);
  *y = ldexp(*y, -es);
  *a = ldexp(*a, -es);
  *sigma2 = ldexp(*sigma2, et - 2 * es);
  *t = ldexp(*t, -et);
  if (u)
    *u = ldexp(*u, -et);
  return et;
}

static int hit_entry_unit(const char *fn, int b3, int what, double u,
                          double x, double y, double a, double sigma2,
                          double t, int et, sb_result *res);

static int hit_entry(const char *fn, int b3, int what, double u, double x,
                     double y, double a, double sigma2, double t,
                     sb_result *res)
{
  const double u0 = u;
  const int et = rescale(b3, &x, &y, &a, &sigma2, &t, &u);
  int st = hit_entry_unit(fn, b3, what, u, x, y, a, sigma2, t, et, res);
  if (what == W_PDF && st == SB_SUCCESS && isinf(res->val))
    return sbi_fail(res, SB_ERANGE, fn,
                    "the density at u = %g exceeds DBL_MAX", u0);
  return st;
}

/* et: the binary exponent of the time scale (rescale); a density is per
 * unit of the caller's time */
static int hit_entry_unit(const char *fn, int b3, int what, double u,
                          double x, double y, double a, double sigma2,
                          double t, int et, sb_result *res)
{
  hit_par h;
  int st = hit_setup(fn, b3, x, y, a, sigma2, t, &h, res);
  if (st)
    return st;
  if (isnan(u))
    return sbi_fail(res, SB_EDOM, fn, "u = %g is not a number", u);
  double val;
  /* outside (0, t), and the trivial laws */
  double t0 = h.trivial == T_ZERO ? 0.0 : t; /* the atom if trivial */
  if (h.trivial != T_NONE || u <= 0.0 || u >= t) {
    if (what == W_PDF)
      val = 0.0;
    else {
      int below = h.trivial != T_NONE ? u < t0 : u <= 0.0;
      double c = below ? 0.0 : 1.0;
      val = what == W_CDF ? c : 1.0 - c;
    }
    *res = (sb_result){val, 0.0};
    return SB_SUCCESS;
  }
  /* sigma2 u t w below the doubles is carried with an extended exponent
   * (make_time): it was read as "u or t - u negligible", cdf 0 for
   * u < t/2, also where the law has all its mass below u */
  hit_time T = make_time(&h, u, sbi_dd_sum(t, -u));
  if (what == W_PDF) {
    double rel;
    val = pdf_at(&h, &T, -et, &rel); /* +inf above DBL_MAX: hit_entry */
    *res = (sb_result){val, rel * val};
    return SB_SUCCESS;
  }
  hit_prob p = prob_at(&h, &T, what);
  val = what == W_CDF ? p.cdf : p.sf;
  *res = (sb_result){val, what == W_CDF ? p.ecdf : p.esf};
  return SB_SUCCESS;
}

#define HIT_PAIR(pfx, b3, name, what)                                       \
  int sb_##pfx##_hit_##name##_e(double u, double x, double y, double a,     \
                                double sigma2, double t, sb_result *res)    \
  {                                                                         \
    sb_result r;                                                            \
    int st = hit_entry(__func__, b3, what, u, x, y, a, sigma2, t, &r);      \
    if (res)                                                                \
      *res = r;                                                             \
    return st;                                                              \
  }                                                                         \
  double sb_##pfx##_hit_##name(double u, double x, double y, double a,      \
                               double sigma2, double t)                     \
  {                                                                         \
    sb_result r;                                                            \
    hit_entry(__func__, b3, what, u, x, y, a, sigma2, t, &r);               \
    return r.val;                                                           \
  }

HIT_PAIR(bb, 0, pdf, W_PDF)
HIT_PAIR(bb, 0, cdf, W_CDF)
HIT_PAIR(bb, 0, sf, W_SF)
HIT_PAIR(bes3b, 1, pdf, W_PDF)
HIT_PAIR(bes3b, 1, cdf, W_CDF)
HIT_PAIR(bes3b, 1, sf, W_SF)

/* ---------------------------------------------------------- quantile */

typedef struct {
  hit_par *h;    /* h->rmax is switched by the iteration */
  double sref;   /* s = sref exp(y), u = t s/(t + s), w = t^2/(t + s) */
  double logtg;  /* log p (lower) or log (1 - p) (upper) */
  int upper;
  double err, dlog; /* last absolute error of the probability, dg/dy */
} hit_qctx;

/* g(y) = log G - log p (lower) or log(1 - p) - log SF (upper), y =
 * log(s/sref); with D1 = dens / G (or / SF), sfl = d log(dens)/dy and
 * sfl2 = d sfl/dy (closed forms in hit_prob), the upper sign for SF:
 *   g' = D1,  g'' = D1 (sfl -+ D1),  g''' = g'' (sfl -+ 2 D1) + D1 sfl2.
 * B3B: (1) is used while kprev (the solver's last dimensionless step) is
 * large, even where it cancels moderately (rho G2/G1 <= 1 - 1e-6: relative
 * noise <= ~1e-9, ample to steer); near the root the accurate form gives
 * the final value.  For rho > 0.95 the values are the accurate expansion of
 * (2), except the first one (at the starting guess, which the solver
 * almost never takes as final) while rho <= RNX_FIRST: (1), noise <=
 * ~1e-11 relative, costs about a third of the expansion. */
#define RNX_FIRST (1.0 - 1e-5)

static double hit_qfun(double y, double kprev, void *vc, double d[4])
{
  hit_qctx *c = vc;
  hit_par *h = c->h;
  double s = c->sref * exp(y), t = h->t;
  d[3] = 1.0;
  /* g is increasing in both tails: -inf at u = 0, +inf at u = t */
  if (!(s > 0.0))
    return -INFINITY;
  if (isinf(s))
    return INFINITY;
  double u = t * s / (t + s), w = t * t / (t + s);
  /* t s overflows for s > DBL_MAX/t (+inf, not t) */
  if (!(u > 0.0) || !(w > 0.0) || !(u < t))
    return u < 0.5 * t ? -INFINITY : INFINITY;
  hit_time T = make_time(h, u, (sbi_dd){w, 0.0});
  /* kprev < 0.05: the next error ~ kprev^4 is acceptable, so this value is
   * likely the last one */
  int cheap = kprev >= 0.05;
  h->rmax = cheap ? 1.0 - 1e-6 : 0.95;
  h->rnx = isinf(kprev) ? RNX_FIRST : 0.95;
  hit_prob p = prob_at(h, &T, c->upper ? W_SF : W_CDF);
  h->rmax = 0.95;
  h->rnx = 0.95;
  /* (1) was accurate anyway unless it entered the cancelling range */
  if (cheap && p.rused > 0.95 && p.rused <= 1.0 - 1e-6)
    d[3] = 0.0;
  double pr = c->upper ? p.sf : p.cdf;
  /* no density here (a law narrower than the doubles resolve, e.g. a
   * step at u = 0 or t): the value is 0 or 1 on either side of the
   * jump, never the best root, which is where the bracket closes */
  if (!(p.dens > 0.0))
    d[3] = 0.0;
  if (!(pr > 0.0)) {
    d[0] = 0.0;
    return c->upper ? INFINITY : -INFINITY;
  }
  double D1 = p.dens / pr, sg = c->upper ? 1.0 : -1.0;
  d[0] = D1;
  d[1] = D1 * (p.sfl + sg * D1);
  d[2] = d[1] * (p.sfl + 2.0 * sg * D1) + D1 * p.sfl2;
  c->dlog = D1;
  c->err = (c->upper ? p.esf : p.ecdf) / pr;
  double lp = log(pr);
  return c->upper ? c->logtg - lp : lp - c->logtg;
}

/* Starting guess for S = s(T): the law (1 - pi) IG + pi SB (size-biased)
 * with drift length L (sbi_ig_quantile_start); Levy if L = 0 */
static double s_guess(const hit_par *h, double L, double pi, double p,
                      int upper)
{
  double al = h->al.hi, shape = al * al / h->sigma2;
  if (L > 0.0) {
    double mean = al * h->t / L;
    double g = mean * sbi_ig_quantile_start(p, upper, shape / mean, pi);
    if (g > 0.0 && isfinite(g))
      return g;
  }
  double z = upper ? (p < 1e-8 ? p * 1.2533141373155002512
                               : gsl_cdf_ugaussian_Pinv(0.5 + 0.5 * p))
                   : gsl_cdf_ugaussian_Qinv(0.5 * p);
  return shape / (z * z);
}

/* g(u) = G(u) - p (lower) or (1 - p) - SF(u) (upper), increasing, on the
 * same path as the public cdf/sf (w = t - u); *f = pdf(u) = g'(u) */
static double hit_g_at(const hit_par *h, double u, double p, int upper,
                       double *f)
{
  hit_time T = make_time(h, u, sbi_dd_sum(h->t, -u));
  hit_prob pr = prob_at(h, &T, upper ? W_SF : W_CDF);
  double rel;
  *f = pdf_at(h, &T, 0, &rel);
  return upper ? (1.0 - p) - pr.sf : pr.cdf - p;
}

/* Final polish in u: where the law is very concentrated one ulp of u moves
 * G by more than the probabilities' own error, and the rounding of
 * u = t s/(t + s) (a couple of ulp) matters.  Newton steps on g(u), then
 * the better of u and its neighbour towards the root (the best double). */
static double polish_u(const hit_par *h, double u, double p, int upper)
{
  double f, g = hit_g_at(h, u, p, upper, &f);
  if (!isfinite(g))
    return u;
  for (int it = 0; it < 3 && f > 0.0; it++) {
    double un = u - g / f;
    if (!(un > 0.0 && un < h->t) || un == u)
      break;
    double fn, gn = hit_g_at(h, un, p, upper, &fn);
    if (!(fabs(gn) < fabs(g)))
      break;
    u = un;
    g = gn;
    f = fn;
  }
  double nb = nextafter(u, g > 0.0 ? 0.0 : h->t), fnb;
  if (nb > 0.0 && nb < h->t) {
    double gnb = hit_g_at(h, nb, p, upper, &fnb);
    if (fabs(gnb) < fabs(g))
      u = nb;
  }
  return u;
}

/* Fallback where the iteration in log s fails (laws narrower than one
 * ulp of u, sigma2 t ~ 1e300 or 1e-300 relative to alpha^2, u near the
 * underflow): bisection on the binary representation of u in [0, t] (the
 * order of non-negative doubles is that of their bit patterns, so at most
 * 64 steps) on the public evaluation path, then the better of the two
 * adjacent doubles.  Where sigma2 u t w underflows the public cdf is 0 (u
 * < t/2) or 1, and so is the sign used here.  *err: two ulp plus the cdf
 * noise (1e-13 relative) over the density. */
static double bisect_u(const hit_par *h, double p, int upper, double *err)
{
  uint64_t lo, hi;
  double ulo = 0.0, uhi = h->t, glo = -p, ghi = 1.0 - p, f = 0.0;
  memcpy(&lo, &ulo, sizeof lo);
  memcpy(&hi, &uhi, sizeof hi);
  while (hi - lo > 1) {
    uint64_t mid = lo + (hi - lo) / 2;
    double um, fm;
    memcpy(&um, &mid, sizeof um);
    double g = hit_g_at(h, um, p, upper, &fm);
    if (isnan(g))
      g = um < 0.5 * h->t ? -1.0 : 1.0;
    if (g < 0.0) {
      lo = mid;
      ulo = um;
      glo = g;
    } else {
      hi = mid;
      uhi = um;
      ghi = g;
      f = fm;
    }
  }
  const int up = fabs(ghi) <= fabs(glo);
  const double u = up ? uhi : ulo;
  *err = 2.0 * (uhi - ulo) +
         (f > 0.0 ? 1e-13 * (upper ? 1.0 - p : p) / f : 0.0);
  return u;
}

static int hit_quantile_unit(const char *fn, int b3, double p, double x,
                             double y, double a, double sigma2, double t,
                             sb_result *res);

static int hit_quantile(const char *fn, int b3, double p, double x, double y,
                        double a, double sigma2, double t, sb_result *res)
{
  const int et = rescale(b3, &x, &y, &a, &sigma2, &t, NULL);
  int st = hit_quantile_unit(fn, b3, p, x, y, a, sigma2, t, res);
  res->val = ldexp(res->val, et);
  res->err = ldexp(res->err, et);
  return st;
}

static int hit_quantile_unit(const char *fn, int b3, double p, double x,
                             double y, double a, double sigma2, double t,
                             sb_result *res)
{
  hit_par h;
  int st = hit_setup(fn, b3, x, y, a, sigma2, t, &h, res);
  if (st)
    return st;
  if (!(p >= 0.0 && p <= 1.0))
    return sbi_fail(res, SB_EDOM, fn, "p = %g must be in [0, 1]", p);
  if (h.trivial != T_NONE) {
    *res = (sb_result){h.trivial == T_ZERO ? 0.0 : t, 0.0};
    return SB_SUCCESS;
  }
  if (p == 0.0 || p == 1.0) {
    *res = (sb_result){p == 0.0 ? 0.0 : t, 0.0};
    return SB_SUCCESS;
  }
  int upper = p > 0.5;
  double tg = upper ? 1.0 - p : p;
  /* Start.  BB: the IG law of S.  B3B: for rho <= 1/2, (1) is dominated
   * by its first term, the IG law with L1 (exact as rho -> 0); for rho
   * near 1 the mixture (2) spans a short range of L, so its law is close to
   * P_L at the median of L = a + y - 2m (see the sampler), the mixture of
   * the IG and its size-biased version with weight alpha/(alpha + L) on
   * the latter (y = 0: exactly P_a). */
  double Lg = h.L1.hi, pi = 0.0;
  if (b3 && h.mn == 0.0)
    pi = h.al.hi / (h.al.hi + Lg);
  else if (b3 && h.rho > 0.5) {
    double A = h.al.hi + Lg;
    double e = lmix_e(&h, 0.5, A);
    Lg += A * e / (1.0 + sqrt(1.0 + e));
    pi = h.al.hi / (h.al.hi + Lg);
  }
  double sref = s_guess(&h, Lg, pi, tg, upper);
  if (!(sref > 0.0) || isinf(sref))
    sref = t;
  hit_qctx c = {&h, sref, log(tg), upper, 0.0, 1.0};
  double yy, dy;
  st = sbi_solve_increasing4(hit_qfun, &c, 0.0, 1.0, &yy, &dy);
  double s = sref * exp(yy);
  double u = isinf(s) ? t : t * s / (t + s);
  double w = isinf(s) ? 0.0 : t * t / (t + s);
  if (u > t) /* t s overflowed (s > DBL_MAX/t): +inf, not t */
    u = t;
  /* d log G / d log u = dlog t / w: polish if a few ulp of u matter */
  if (st == SB_SUCCESS && u > 0.0 && u < t && c.dlog * t / w > 100.0) {
    u = polish_u(&h, u, p, upper);
    w = t - u;
  }
  /* du = (u w / t) dy; plus the noise of the probability */
  res->val = u;
  res->err = u * w / t * (2.0 * dy + 8.0 * EPS + c.err / c.dlog) +
             2.0 * EPS * u;
  /* no density at the last point or no finite error bound: the
   * iteration closed its bracket on a step of the law (a law narrower
   * than the doubles resolve, positions beyond ~2^1000 sqrt(v)), where
   * its point need not be the best double: bisection */
  if (st == SB_EMAXITER ||
      (st == SB_SUCCESS && !(c.dlog > 0.0 && res->err < INFINITY))) {
    res->val = bisect_u(&h, p, upper, &res->err);
    st = SB_SUCCESS;
  }
  if (st)
    sbi_error(st, fn, "no convergence for p = %g", p);
  return st;
}

#define HIT_QUANT(pfx, b3)                                                  \
  int sb_##pfx##_hit_quantile_e(double p, double x, double y, double a,     \
                                double sigma2, double t, sb_result *res)    \
  {                                                                         \
    sb_result r;                                                            \
    int st = hit_quantile(__func__, b3, p, x, y, a, sigma2, t, &r);         \
    if (res)                                                                \
      *res = r;                                                             \
    return st;                                                              \
  }                                                                         \
  double sb_##pfx##_hit_quantile(double p, double x, double y, double a,    \
                                 double sigma2, double t)                   \
  {                                                                         \
    sb_result r;                                                            \
    hit_quantile(__func__, b3, p, x, y, a, sigma2, t, &r);                  \
    return r.val;                                                           \
  }

HIT_QUANT(bb, 0)
HIT_QUANT(bes3b, 1)

/* ---------------------------------------------------------- samplers */

/* u = t s/(t + s) <= t: the rounding can exceed t by an ulp (s >> t,
 * e.g. t = 1e150 with x ~ 1: ~1% of the draws; t = DBL_MAX gave +inf
 * after the rescaling), so it is clipped to t */
static double s_to_u(double s, double t)
{
  const double u = isinf(s) ? t : t * s / (t + s);
  return u > t ? t : u;
}

static double bb_hit_sample_unit(const char *fn, const gsl_rng *r, double x,
                                 double y, double a, double sigma2, double t)
{
  hit_par h;
  if (hit_setup(fn, 0, x, y, a, sigma2, t, &h, NULL))
    return NAN;
  if (r == NULL) {
    sbi_fail(NULL, SB_EINVAL, fn, "r is NULL");
    return NAN;
  }
  if (h.trivial == T_ZERO)
    return 0.0;
  double al = h.al.hi, L = h.L1.hi;
  /* S = T t/(t - T) ~ IG(alpha t / L, alpha^2 / sigma2) (Levy if L = 0);
   * a mean below the doubles (alpha ~ 1e-300 against L ~ 1e300) is the
   * point mass S = 0 (it was 0/0 = NaN with status 0 where the shape
   * underflowed too) */
  const double mean = L > 0.0 ? al * t / L : INFINITY;
  double S = mean > 0.0 ? sbi_ig_sample(r, mean, al * al / sigma2) : 0.0;
  return s_to_u(S, t);
}

double sb_bb_hit_sample(const gsl_rng *r, double x, double y, double a,
                        double sigma2, double t)
{
  const int et = rescale(0, &x, &y, &a, &sigma2, &t, NULL);
  return ldexp(bb_hit_sample_unit(__func__, r, x, y, a, sigma2, t), et);
}

static double bes3b_hit_sample_unit(const char *fn, const gsl_rng *r,
                                    double x, double y, double a,
                                    double sigma2, double t)
{
  hit_par h;
  if (hit_setup(fn, 1, x, y, a, sigma2, t, &h, NULL))
    return NAN;
  if (r == NULL) {
    sbi_fail(NULL, SB_EINVAL, fn, "r is NULL");
    return NAN;
  }
  if (h.trivial != T_NONE)
    return h.trivial == T_ZERO ? 0.0 : t;
  double al = h.al.hi, L1 = h.L1.hi, L;
  /* 1. L = a + y - 2m from the law of the minimum m of the 1-D bridge
   *    restricted to (0, a] (the Bessel-3 bridge is the 1-D bridge
   *    conditioned on m > 0): P(L <= l) = [1 - exp(-((alpha+l)^2 -
   *    (alpha+L1)^2)/(2v))] / (1 - rho), inverted in closed form with
   *    l = L1 + (alpha + L1) e / (1 + sqrt(1 + e)), e = dlt/(alpha+L1)^2,
   *    dlt = -2 v log(1 - U (1 - rho)) (no cancellation). */
  if (h.mn == 0.0)
    L = L1;
  else {
    double U = gsl_rng_uniform(r);
    double A = al + L1;
    double e = lmix_e(&h, U, A);
    L = L1 + A * e / (1.0 + sqrt(1.0 + e));
    if (L > h.L2.hi)
      L = h.L2.hi;
  }
  /* 2. Given m, S = s(T) is IG(alpha t/L, alpha^2/sigma2) with probability
   *    L/(alpha + L), else its size-biased version IG + sigma2 t^2 Z^2/L^2
   *    (Laplace transforms; docs/bridge.md). */
  double U2 = gsl_rng_uniform(r);
  double mean = L > 0.0 ? al * t / L : INFINITY;
  double S = mean > 0.0 ? sbi_ig_sample(r, mean, al * al / sigma2) : 0.0;
  if (U2 * (al + L) >= L) {
    double z = gsl_ran_gaussian_ziggurat(r, 1.0);
    S += L > 0.0 ? sigma2 * (t * t) * (z * z) / (L * L) : INFINITY;
  }
  return s_to_u(S, t);
}

double sb_bes3b_hit_sample(const gsl_rng *r, double x, double y, double a,
                           double sigma2, double t)
{
  const int et = rescale(1, &x, &y, &a, &sigma2, &t, NULL);
  return ldexp(bes3b_hit_sample_unit(__func__, r, x, y, a, sigma2, t), et);
}
