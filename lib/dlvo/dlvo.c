/* dlvo.c — DLVO energies, forces, energy barrier, relative kinetic energy.
 * Formulas and sources: lib/smolbridge/dlvo.h; derivations: docs/dlvo.md.
 */
#include <float.h>
#include <math.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_math.h>
#include <gsl/gsl_randist.h>
#include <gsl/gsl_roots.h>
#include <gsl/gsl_sf_erf.h>
#include <gsl/gsl_sf_log.h>

#include <smolbridge/dlvo.h>

#include "common/internal.h"
#include "common/numutil.h"

static const double kB = 1.380649e-23; /* J/K, exact (SI 2019) */
static const double EPS = DBL_EPSILON;

/* ------------------------------------------------------------ validation */

static int fin(double x) { return isfinite(x); }
static int pos(double x) { return isfinite(x) && x > 0.0; }
/* r2 may be +inf (plane) */
static int radius2(double x) { return x > 0.0 && !isnan(x); }

/* Fail an _e function with SB_EDOM unless cond; the message names the
 * public function `who` (in scope wherever REQ is used). */
#define REQ(cond, ...)                                       \
  do {                                                       \
    if (!(cond))                                             \
      return sbi_fail_res(res, SB_EDOM, who, __VA_ARGS__);   \
  } while (0)

#define REQ_GEOM(r1, r2, D)                                                \
  REQ(pos(r1) && radius2(r2),                                             \
      "radii must be > 0 (r2 may be +inf) (got r1 = %g, r2 = %g)", r1, r2); \
  REQ(pos(D), "separation D must be finite and > 0 (got %g)", D)

#define REQ_VDW(A, r1, r2, D)                                     \
  REQ(fin(A), "Hamaker constant A must be finite (got %g)", A);  \
  REQ_GEOM(r1, r2, D)

/* Plain double wrapper around an _e call. */
#define VAL(call)                                                          \
  do {                                                                     \
    sb_result r_;                                                          \
    int s_ = call;                                                         \
    return s_ == SB_SUCCESS ? r_.val : NAN;                                \
  } while (0)

/* The potentials are formed in sbi_xd arithmetic (common/numutil.h):
 * the same operations in the same order as the plain formulas, so the
 * same bits where nothing over/underflows, but a prefactor such as
 * eps_r = 1e300, (psi1 + psi2)^2 with psi = 1e300, (kT/ze)^2 with
 * z = 1e-320 or exp(-kappa D) below DBL_MIN no longer turns a
 * representable value into inf, 0 or NaN. */
#define X(x) sbi_xd_of(x)
#define MUL(a, b) sbi_xd_mul((a), (b))
#define DIV(a, b) sbi_xd_div((a), (b))
#define ADD(a, b) sbi_xd_add((a), (b))

static sbi_xd xabs(sbi_xd a)
{
  a.m = fabs(a.m);
  return a;
}

static sbi_xd xneg(sbi_xd a)
{
  a.m = -a.m;
  return a;
}

/* Store the value and error bound val, err in *res: SB_SUCCESS, or NaN
 * and SB_ERANGE (for the public function who) where either exceeds
 * DBL_MAX.  A value that underflows gets the half-ulp of the subnormals
 * added to its bound. */
static int finish(sbi_xd val, sbi_xd err, sb_result *res, const char *who)
{
  const double v = sbi_xd_val(val), e = sbi_xd_val(err);
  if (!isfinite(v))
    return sbi_fail_res(res, SB_ERANGE, who, "the value overflows (|value| "
                        "~ 2^%d > DBL_MAX)", val.e);
  if (!isfinite(e))
    return sbi_fail_res(res, SB_ERANGE, who, "the error bound of the value "
                        "%g overflows", v);
  res->val = v;
  res->err = fabs(v) < DBL_MIN ? e + 0x1p-1074 : e;
  return SB_SUCCESS;
}

/* Derjaguin radius r1 r2/(r1 + r2), = r1 for a plane; the ratio the other
 * way round where r1/r2 overflows. */
static double reff(double r1, double r2)
{
  if (isinf(r2))
    return r1;
  const double q = r1 / r2;
  return isinf(q) ? r2 / (1.0 + r2 / r1) : r1 / (1.0 + q);
}

/* ------------------------------------------------------------ Debye */

double sb_dlvo_debye_kappa(double n0, double z, double eps_r, double T)
{
  if (!(pos(n0) && pos(z) && pos(eps_r) && pos(T))) {
    sbi_error(SB_EDOM, __func__,
              "n0, z, eps_r, T must be finite and > 0 (got %g, %g, %g, %g)",
              n0, z, eps_r, T);
    return NAN;
  }
  const sbi_xd ze = MUL(X(z), X(SB_DLVO_ECHARGE));
  const double k = sbi_xd_val(sbi_xd_sqrt(
      DIV(MUL(MUL(MUL(X(2.0), X(n0)), ze), ze),
          MUL(MUL(MUL(X(eps_r), X(SB_DLVO_EPS0)), X(kB)), X(T)))));
  if (isinf(k)) {
    sbi_error(SB_ERANGE, __func__, "kappa overflows (n0 = %g, z = %g, eps_r "
              "= %g, T = %g)", n0, z, eps_r, T);
    return NAN;
  }
  return k;
}

/* ------------------------------------------------------------ van der Waals */

/* g(t) = t + t/(1 + 2t) - ln(1 + 2t), t >= 0, with an absolute error bound.
 * Cancels as (4/3) t^3 for small t: the series (y = 2t)
 *   g = (1/2) sum_{k>=3} (-1)^(k-1) (k-2)/k y^k
 * (alternating, terms decreasing for y <= 1/2) for t < 1/4; above, the
 * form -(ln(1+y) - y) - y^2/(2(1+y)) with GSL's log_1plusx_mx loses at
 * most a factor 16 to cancellation.  Beyond t = DBL_MAX/2 (y overflows)
 * g = t - (ln 2t - 1/2) + O(1/t). */
static double ham_g(double t, double *err)
{
  if (t < 0.25) {
    double y = 2.0 * t, yk = y * y * y, sum = 0.0, asum = 0.0, term = 0.0;
    for (int k = 3; k < 200; k++) {
      term = ((k & 1) ? 1.0 : -1.0) * (double)(k - 2) / k * yk;
      sum += term;
      asum += fabs(term);
      if (fabs(term) < 0.25 * EPS * fabs(sum))
        break;
      yk *= y;
    }
    *err = 0.5 * (4.0 * EPS * asum + fabs(term));
    return 0.5 * sum;
  }
  double y = 2.0 * t;
  if (isinf(y)) {
    *err = 4.0 * EPS * t;
    return t - (log(t) + M_LN2 - 0.5);
  }
  /* y (y/(1 + y)), not y^2/(1 + y): y^2 overflows above 1.3e154 (contact
   * distances of R/1e154), and -A/6 g became +inf */
  double a = -gsl_sf_log_1plusx_mx(y), b = 0.5 * y * (y / (1.0 + y));
  *err = 4.0 * EPS * (fabs(a) + fabs(b));
  return a - b;
}

/* t = 2 r1 r2/(D (D + 2 r1 + 2 r2)) (r1/D for a plane) and, if dlog is not
 * NULL, the logarithmic derivative -d ln t/dD = 1/D + 1/(D + 2 r1 + 2 r2),
 * both in sbi_xd form (t may exceed DBL_MAX, 1/D too). */
static sbi_xd ham_t(double r1, double r2, double D, sbi_xd *dlog)
{
  if (isinf(r2)) {
    if (dlog)
      *dlog = DIV(X(1.0), X(D));
    return DIV(X(r1), X(D));
  }
  const sbi_xd s = ADD(X(D), MUL(X(2.0), ADD(X(r1), X(r2))));
  if (dlog)
    *dlog = ADD(DIV(X(1.0), X(D)), DIV(X(1.0), s));
  return MUL(DIV(MUL(X(2.0), X(r1)), X(D)), DIV(X(r2), s));
}

static int hamaker(double A, double r1, double r2, double D, sb_result *res,
                   const char *who)
{
  REQ_VDW(A, r1, r2, D);
  const sbi_xd tx = ham_t(r1, r2, D, NULL);
  const double t = sbi_xd_val(tx);
  if (A == 0.0) {
    res->val = res->err = 0.0;
    return SB_SUCCESS;
  }
  if (isinf(t)) {
    /* D below ~R/DBL_MAX: t = R/D is not a double; the energy is -inf
     * for A > 0 by convention (documented; the contact singularity) */
    res->val = A > 0.0 ? -INFINITY : INFINITY;
    res->err = 0.0;
    return SB_SUCCESS;
  }
  sbi_xd g, eg;
  if (t < 0x1p-60) {
    /* g = (1/2)(1/3) y^3 (1 + O(y)), y = 2t: the series' first term,
     * formed without the underflow of y^3 */
    const sbi_xd y = MUL(X(2.0), tx);
    g = MUL(X(0.5), MUL(X(1.0 / 3.0), MUL(MUL(y, y), y)));
    eg = MUL(X(4.0 * EPS), g);
  } else {
    double e;
    g = X(ham_g(t, &e));
    /* t carries ~4 ulp; g'(t) t <= 2 g for every t (g' = (2t/(1+2t))^2)
     * is not true near 0, so bound the propagated part by
     * g'(t) t 4 eps. */
    const double gp = t > 1e300 ? 1.0 : 2.0 * t / (1.0 + 2.0 * t);
    eg = X(e + 4.0 * EPS * gp * gp * t);
  }
  const sbi_xd W = MUL(DIV(X(-A), X(6.0)), g);
  return finish(W, ADD(MUL(DIV(X(fabs(A)), X(6.0)), eg),
                       MUL(X(2.0 * EPS), xabs(W))),
                res, who);
}

int sb_dlvo_vdw_hamaker_e(double A, double r1, double r2, double D,
                          sb_result *res)
{
  return hamaker(A, r1, r2, D, res, __func__);
}

double sb_dlvo_vdw_hamaker(double A, double r1, double r2, double D)
{
  VAL(hamaker(A, r1, r2, D, &r_, __func__));
}

static int hamaker_force(double A, double r1, double r2, double D,
                         sb_result *res, const char *who)
{
  REQ_VDW(A, r1, r2, D);
  /* F = (A/6) g'(t) dt/dD = -(A/6) (2t/(1+2t))^2 t (1/D + 1/(D+2r1+2r2)):
   * products of positive factors, no cancellation. */
  sbi_xd dl;
  const sbi_xd tx = ham_t(r1, r2, D, &dl);
  const double t = sbi_xd_val(tx);
  const sbi_xd gp =
      t > 1e300 ? X(1.0) : DIV(MUL(X(2.0), tx), X(1.0 + 2.0 * t));
  const sbi_xd F = MUL(MUL(MUL(MUL(DIV(X(-A), X(6.0)), gp), gp), tx), dl);
  return finish(F, MUL(X(16.0 * EPS), xabs(F)), res, who);
}

int sb_dlvo_vdw_hamaker_force_e(double A, double r1, double r2, double D,
                                sb_result *res)
{
  return hamaker_force(A, r1, r2, D, res, __func__);
}

double sb_dlvo_vdw_hamaker_force(double A, double r1, double r2, double D)
{
  VAL(hamaker_force(A, r1, r2, D, &r_, __func__));
}

/* Derjaguin energy (force = 0) or force (force = 1). */
static int derjaguin(double A, double r1, double r2, double D, sb_result *res,
                     int force, const char *who)
{
  REQ_VDW(A, r1, r2, D);
  sbi_xd den = MUL(X(6.0), X(D));
  if (force)
    den = MUL(den, X(D));
  const sbi_xd W = DIV(MUL(X(-A), X(reff(r1, r2))), den);
  return finish(W, MUL(X((force ? 5.0 : 4.0) * EPS), xabs(W)), res, who);
}

int sb_dlvo_vdw_derjaguin_e(double A, double r1, double r2, double D,
                            sb_result *res)
{
  return derjaguin(A, r1, r2, D, res, 0, __func__);
}

double sb_dlvo_vdw_derjaguin(double A, double r1, double r2, double D)
{
  VAL(derjaguin(A, r1, r2, D, &r_, 0, __func__));
}

int sb_dlvo_vdw_derjaguin_force_e(double A, double r1, double r2, double D,
                                  sb_result *res)
{
  return derjaguin(A, r1, r2, D, res, 1, __func__);
}

double sb_dlvo_vdw_derjaguin_force(double A, double r1, double r2, double D)
{
  VAL(derjaguin(A, r1, r2, D, &r_, 1, __func__));
}

/* ------------------------------------------------------------ double layer */

#define REQ_EDL(kappa, eps_r, psi1, psi2)                                  \
  REQ(pos(kappa) && pos(eps_r),                                            \
      "kappa and eps_r must be finite and > 0 (got %g, %g)", kappa, eps_r); \
  REQ(fin(psi1) && fin(psi2), "surface potentials must be finite (got %g, " \
      "%g)", psi1, psi2)

/* The error factor (c0 + 3x) eps times |terms| (0 where the terms are 0,
 * whatever x: kappa D may be inf there). */
static sbi_xd xerr(double c0, double x, sbi_xd terms)
{
  return terms.m == 0.0 ? terms : MUL(X((c0 + 3.0 * x) * EPS), terms);
}

/* tanh(psi/(4 kT/ze)) with kT/ze in sbi_xd form: the argument itself
 * where it is below 2^-27 (tanh u = u (1 - u^2/3)), so that a tiny
 * argument keeps its digits */
static sbi_xd lsa_gamma(double psi, sbi_xd kt_ze)
{
  const sbi_xd u = DIV(X(psi), MUL(X(4.0), kt_ze));
  const double uv = sbi_xd_val(u);
  return fabs(uv) < 0x1p-27 ? u : X(tanh(uv));
}

/* LSA energy; *force gets kappa W (same relative error). */
static int lsa(double D, double r1, double r2, double kappa, double eps_r,
               double T, double z, double psi1, double psi2, sb_result *res,
               int force, const char *who)
{
  REQ_GEOM(r1, r2, D);
  REQ_EDL(kappa, eps_r, psi1, psi2);
  REQ(pos(T) && pos(z), "T and z must be finite and > 0 (got %g, %g)", T, z);
  const sbi_xd kt_ze = DIV(MUL(X(kB), X(T)), MUL(X(z), X(SB_DLVO_ECHARGE)));
  const sbi_xd g1 = lsa_gamma(psi1, kt_ze), g2 = lsa_gamma(psi2, kt_ze);
  const double x = kappa * D;
  sbi_xd w = MUL(MUL(MUL(MUL(MUL(MUL(MUL(MUL(X(64.0 * M_PI), X(eps_r)),
                                             X(SB_DLVO_EPS0)),
                                         X(reff(r1, r2))),
                                     kt_ze),
                                 kt_ze),
                             g1),
                         g2),
                     sbi_xd_expneg(x));
  if (force)
    w = MUL(w, X(kappa));
  /* ~12 roundings; exp(-x) turns x's relative rounding (the product
   * kappa D, ~2 ulp with that of its inputs) into x times as much */
  return finish(w, xerr(16.0, x, xabs(w)), res, who);
}

int sb_dlvo_edl_lsa_e(double D, double r1, double r2, double kappa,
                      double eps_r, double T, double z, double psi1,
                      double psi2, sb_result *res)
{
  return lsa(D, r1, r2, kappa, eps_r, T, z, psi1, psi2, res, 0, __func__);
}

double sb_dlvo_edl_lsa(double D, double r1, double r2, double kappa,
                       double eps_r, double T, double z, double psi1,
                       double psi2)
{
  VAL(lsa(D, r1, r2, kappa, eps_r, T, z, psi1, psi2, &r_, 0, __func__));
}

int sb_dlvo_edl_lsa_force_e(double D, double r1, double r2, double kappa,
                            double eps_r, double T, double z, double psi1,
                            double psi2, sb_result *res)
{
  return lsa(D, r1, r2, kappa, eps_r, T, z, psi1, psi2, res, 1, __func__);
}

double sb_dlvo_edl_lsa_force(double D, double r1, double r2, double kappa,
                             double eps_r, double T, double z, double psi1,
                             double psi2)
{
  VAL(lsa(D, r1, r2, kappa, eps_r, T, z, psi1, psi2, &r_, 1, __func__));
}

/* HHF energy or force, x = kappa D.  For x <= 1 the printed form: with
 * ln(1 + e^-x) = log1p(exp(-x)), ln(1 - e^-x) = sbi_log1mexp(x) (Maechler
 * 2012), = ln x where kappa D underflows; the force terms 1/(e^x + 1) and
 * 1/expm1(x) (= 1/x where kappa D underflows).  For x > 1, where the two
 * printed terms ~ (psi1 +- psi2)^2 e^-x cancel unless psi1 psi2 is large,
 * the equivalent form with q = psi1^2 + psi2^2, p = psi1 psi2:
 *   W = pi eps R [q ln(1 - e^{-2x}) + 4 p atanh(e^{-x})],
 *   F = pi eps R kappa [2 p/sinh x - 2 q/expm1(2x)]
 * (ln(1 - u^2) = -u^2 and atanh u = u, 1/sinh x = 2e^-x, 1/expm1(2x) =
 * e^{-2x} to double precision where e^-x < 1e-300). */
static int hhf(double D, double r1, double r2, double kappa, double eps_r,
               double psi1, double psi2, sb_result *res, int force,
               const char *who)
{
  REQ_GEOM(r1, r2, D);
  REQ_EDL(kappa, eps_r, psi1, psi2);
  const double x = kappa * D;
  const sbi_xd kd = MUL(X(kappa), X(D)); /* x without underflow */
  sbi_xd pre = MUL(MUL(MUL(X(M_PI), X(eps_r)), X(SB_DLVO_EPS0)),
                   X(reff(r1, r2)));
  sbi_xd a, b;
  if (x <= 1.0) {
    const sbi_xd s1 = ADD(X(psi1), X(psi2)), s2 = ADD(X(psi1), X(-psi2));
    const sbi_xd sp = MUL(s1, s1), sm = MUL(s2, s2);
    const int tiny = !(x >= 1e-300);
    if (force) {
      pre = MUL(pre, X(kappa));
      a = DIV(sp, X(exp(x) + 1.0));
      b = sm.m == 0.0 ? X(0.0)
          : tiny      ? xneg(DIV(sm, kd))
                      : DIV(xneg(sm), X(expm1(x)));
    } else {
      a = MUL(sp, X(log1p(exp(-x))));
      b = sm.m == 0.0 ? X(0.0)
                      : MUL(sm, X(tiny ? sbi_xd_log(kd) : sbi_log1mexp(x)));
    }
  } else {
    const sbi_xd q = ADD(MUL(X(psi1), X(psi1)), MUL(X(psi2), X(psi2)));
    const sbi_xd p = MUL(X(psi1), X(psi2));
    const int far = x >= 700.0; /* e^-x below 1e-300 */
    if (force) {
      pre = MUL(pre, X(kappa));
      a = far ? MUL(MUL(X(4.0), p), sbi_xd_expneg(x))
              : DIV(MUL(X(2.0), p), X(sinh(x)));
      b = far ? MUL(MUL(X(-2.0), q), sbi_xd_expneg(2.0 * x))
              : DIV(MUL(X(-2.0), q), X(expm1(2.0 * x)));
    } else {
      a = MUL(q, far ? xneg(sbi_xd_expneg(2.0 * x))
                     : X(sbi_log1mexp(2.0 * x)));
      b = MUL(MUL(X(4.0), p), far ? sbi_xd_expneg(x) : X(atanh(exp(-x))));
    }
  }
  const sbi_xd W = MUL(pre, ADD(a, b));
  /* each term ~8 roundings plus the x-sensitivity (<= x relative for the
   * exponentials; <= 1 for the logarithms near 0 since x d/dx ln(1-e^-x)
   * = x/expm1(x) <= 1) */
  return finish(W, ADD(MUL(pre, xerr(10.0, x, ADD(xabs(a), xabs(b)))),
                       MUL(X(2.0 * EPS), xabs(W))),
                res, who);
}

int sb_dlvo_edl_hhf_e(double D, double r1, double r2, double kappa,
                      double eps_r, double psi1, double psi2, sb_result *res)
{
  return hhf(D, r1, r2, kappa, eps_r, psi1, psi2, res, 0, __func__);
}

double sb_dlvo_edl_hhf(double D, double r1, double r2, double kappa,
                       double eps_r, double psi1, double psi2)
{
  VAL(hhf(D, r1, r2, kappa, eps_r, psi1, psi2, &r_, 0, __func__));
}

int sb_dlvo_edl_hhf_force_e(double D, double r1, double r2, double kappa,
                            double eps_r, double psi1, double psi2,
                            sb_result *res)
{
  return hhf(D, r1, r2, kappa, eps_r, psi1, psi2, res, 1, __func__);
}

double sb_dlvo_edl_hhf_force(double D, double r1, double r2, double kappa,
                             double eps_r, double psi1, double psi2)
{
  VAL(hhf(D, r1, r2, kappa, eps_r, psi1, psi2, &r_, 1, __func__));
}

/* ------------------------------------------------------------ pair */

static int pair_check(const sb_dlvo_pair *p, const char *who)
{
  sb_result *res = NULL;
  REQ(p != NULL, "pair is NULL");
  REQ(pos(p->r1) && radius2(p->r2),
      "radii must be > 0 (r2 may be +inf) (got r1 = %g, r2 = %g)", p->r1,
      p->r2);
  REQ(fin(p->A), "Hamaker constant A must be finite (got %g)", p->A);
  REQ(pos(p->T) && pos(p->eps_r) && pos(p->kappa),
      "T, eps_r, kappa must be finite and > 0 (got %g, %g, %g)", p->T,
      p->eps_r, p->kappa);
  REQ(fin(p->psi1) && fin(p->psi2),
      "surface potentials must be finite (got %g, %g)", p->psi1, p->psi2);
  REQ(p->edl != SB_DLVO_EDL_LSA || pos(p->z),
      "valence z must be finite and > 0 (got %g)", p->z);
  REQ(p->vdw == SB_DLVO_VDW_DERJAGUIN || p->vdw == SB_DLVO_VDW_HAMAKER,
      "unknown van der Waals model %d", (int)p->vdw);
  REQ(p->edl == SB_DLVO_EDL_LSA || p->edl == SB_DLVO_EDL_HHF,
      "unknown double-layer model %d", (int)p->edl);
  REQ(pos(p->d_contact), "d_contact must be finite and > 0 (got %g)",
      p->d_contact);
  return SB_SUCCESS;
}

int sb_dlvo_pair_check(const sb_dlvo_pair *p)
{
  return pair_check(p, __func__);
}

/* The two parts of the energy (force = 0) or of the force (force = 1) of
 * a checked pair; the first failing status (messages for who). */
static int parts(const sb_dlvo_pair *p, double D, int force, sb_result *v,
                 sb_result *e, const char *who)
{
  int s;
  if (p->vdw == SB_DLVO_VDW_HAMAKER)
    s = force ? hamaker_force(p->A, p->r1, p->r2, D, v, who)
              : hamaker(p->A, p->r1, p->r2, D, v, who);
  else
    s = derjaguin(p->A, p->r1, p->r2, D, v, force, who);
  int s2 = p->edl == SB_DLVO_EDL_LSA
               ? lsa(D, p->r1, p->r2, p->kappa, p->eps_r, p->T, p->z, p->psi1,
                     p->psi2, e, force, who)
               : hhf(D, p->r1, p->r2, p->kappa, p->eps_r, p->psi1, p->psi2, e,
                     force, who);
  return s ? s : s2;
}

static int total(const sb_dlvo_pair *p, double D, int force, sb_result *res,
                 const char *who)
{
  int s = pair_check(p, who); /* records the message */
  if (s != SB_SUCCESS) {
    res->val = res->err = NAN;
    return s;
  }
  REQ(pos(D), "separation D must be finite and > 0 (got %g)", D);
  sb_result v, e;
  s = parts(p, D, force, &v, &e, who);
  if (s != SB_SUCCESS) {
    res->val = res->err = NAN;
    return s;
  }
  res->val = v.val + e.val;
  if (isinf(v.val) && !force) { /* the Hamaker energy's documented -inf */
    res->err = 0.0;
    return SB_SUCCESS;
  }
  res->err = v.err + e.err + EPS * fabs(res->val);
  if (!isfinite(res->val) || !isfinite(res->err))
    return sbi_fail_res(res, SB_ERANGE, who, "the %s overflows (%g + %g)",
                        force ? "force" : "energy", v.val, e.val);
  return SB_SUCCESS;
}

int sb_dlvo_energy_e(const sb_dlvo_pair *p, double D, sb_result *res)
{
  return total(p, D, 0, res, __func__);
}
double sb_dlvo_energy(const sb_dlvo_pair *p, double D)
{
  VAL(total(p, D, 0, &r_, __func__));
}
int sb_dlvo_force_e(const sb_dlvo_pair *p, double D, sb_result *res)
{
  return total(p, D, 1, res, __func__);
}
double sb_dlvo_force(const sb_dlvo_pair *p, double D)
{
  VAL(total(p, D, 1, &r_, __func__));
}

/* ------------------------------------------------------------ barrier */

/* Unchecked evaluations for the search. */
static double fW(const sb_dlvo_pair *p, double D, double *err)
{
  sb_result v, e;
  parts(p, D, 0, &v, &e, "sb_dlvo_barrier");
  if (err)
    *err = v.err + e.err + EPS * fabs(v.val + e.val);
  return v.val + e.val;
}

static double fF(double D, void *ctx)
{
  sb_result v, e;
  parts((const sb_dlvo_pair *)ctx, D, 1, &v, &e, "sb_dlvo_barrier");
  return v.val + e.val;
}

/* Refine the root of F in [lo, hi] (F(lo), F(hi) of opposite signs) with
 * GSL's Brent solver; *err gets the final bracket width plus the effect
 * of F's rounding (err_F / |F'|). */
static int refine(const sb_dlvo_pair *p, double lo, double hi, double *root,
                  double *err)
{
  gsl_function fn = {fF, (void *)p};
  gsl_root_fsolver *s = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
  if (!s)
    return sbi_error(SB_ENOMEM, "sb_dlvo_barrier", "no memory for solver");
  /* the bracket is valid (signs checked by the caller), F is finite on
   * it, so GSL's handler is never reached */
  gsl_root_fsolver_set(s, &fn, lo, hi);
  int status = GSL_CONTINUE, it;
  for (it = 0; it < 200 && status == GSL_CONTINUE; it++) {
    gsl_root_fsolver_iterate(s);
    lo = gsl_root_fsolver_x_lower(s);
    hi = gsl_root_fsolver_x_upper(s);
    status = gsl_root_test_interval(lo, hi, 0.0, 1e-14);
  }
  *root = gsl_root_fsolver_root(s);
  gsl_root_fsolver_free(s);
  if (status != GSL_SUCCESS)
    return sbi_error(SB_EMAXITER, "sb_dlvo_barrier",
                     "root finder did not converge near D = %g", *root);
  sb_result v, e;
  parts(p, *root, 1, &v, &e, "sb_dlvo_barrier");
  double h = 1e-4 * *root;
  double dF = fabs(fF(*root + h, (void *)p) - fF(*root - h, (void *)p)) /
              (2.0 * h);
  *err = (hi - lo) + (dF > 0.0 ? (v.err + e.err + fabs(v.val + e.val)) / dF
                               : 0.0);
  return SB_SUCCESS;
}

#define PER_DECADE 40

int sb_dlvo_barrier(const sb_dlvo_pair *p, sb_dlvo_barrier_t *b)
{
  sb_result *res = NULL;
  const char *const who = __func__;
  int s = pair_check(p, who);
  if (s != SB_SUCCESS)
    return s;
  REQ(b != NULL, "result pointer is NULL");
  b->kind = SB_DLVO_NO_BARRIER;
  b->W_max = b->W_max_err = b->D_max_err = 0.0;
  b->D_max = INFINITY;
  b->W_min2 = b->D_min2 = NAN;
  REQ(p->A >= 0.0, "the barrier needs A >= 0 (got %g)", p->A);

  /* Tail: beyond D_hi the power-law attraction dominates the exponential
   * double layer and keeps F < 0, so no stationary point lies there.
   * D_hi >= d0 + 40/kappa makes kappa exceed the log-slope (<= 7/D) of
   * F_vdw, so |F_edl/F_vdw| keeps decreasing past D_hi. */
  const double d0 = p->d_contact;
  double Dhi = d0 + 40.0 / p->kappa;
  if (p->A > 0.0) {
    int k;
    for (k = 0; k < 80; k++, Dhi *= 2.0) {
      sb_result v, e;
      parts(p, Dhi, 1, &v, &e, __func__);
      if (v.val + e.val < 0.0 && fabs(e.val) <= 1e-3 * fabs(v.val))
        break;
    }
    if (k == 80)
      return sbi_error(SB_EMAXITER, __func__,
                       "no attractive tail found up to D = %g", Dhi);
  }

  /* Scan the sign of F on a log grid; refine each change. */
  int n = (int)ceil(PER_DECADE * log10(Dhi / d0)) + 1;
  if (n < 2)
    n = 2;
  double q = pow(Dhi / d0, 1.0 / (n - 1));
  double Werr0, W0 = fW(p, d0, &Werr0);
  if (W0 > 0.0) {
    b->kind = SB_DLVO_BARRIER_CONTACT;
    b->W_max = W0;
    b->W_max_err = Werr0;
    b->D_max = d0;
  }
  double Dp = d0, Fp = fF(d0, (void *)p);
  /* minima found, to pick the secondary one after the barrier is known */
  enum { NMIN = 16 };
  double mins_D[NMIN], mins_W[NMIN];
  int nmin = 0;
  for (int i = 1; i < n; i++) {
    double D = i == n - 1 ? Dhi : d0 * pow(q, i);
    double F = fF(D, (void *)p);
    int up = Fp < 0.0 && F >= 0.0, down = Fp >= 0.0 && F < 0.0;
    if (up || down) {
      double r = NAN, rerr = NAN;
      int st = refine(p, Dp, D, &r, &rerr);
      if (st != SB_SUCCESS)
        return st;
      double werr, w = fW(p, r, &werr);
      if (up) { /* W increases then decreases: a maximum */
        if (w > b->W_max) {
          b->kind = SB_DLVO_BARRIER;
          b->W_max = w;
          /* W is stationary at the true root: the position error enters
           * at second order; bound it by |F(r)| rerr */
          b->W_max_err = werr + fabs(fF(r, (void *)p)) * rerr;
          b->D_max = r;
          b->D_max_err = rerr;
        }
      } else if (nmin < NMIN) {
        mins_D[nmin] = r;
        mins_W[nmin++] = w;
      }
    }
    Dp = D;
    Fp = F;
  }
  for (int i = 0; i < nmin; i++)
    if ((b->kind == SB_DLVO_NO_BARRIER || mins_D[i] > b->D_max) &&
        !(mins_W[i] >= b->W_min2))
      b->W_min2 = mins_W[i], b->D_min2 = mins_D[i];
  return SB_SUCCESS;
}

/* ------------------------------------------------------------ kinetic energy */

static int vec_ok(const double *v)
{
  return v && fin(v[0]) && fin(v[1]) && fin(v[2]);
}

/* mu = m1 m2/(m1 + m2) without overflow of m1 m2, nor of m1/m2 (the
 * ratio is taken the other way round where it would overflow). */
static double reduced_mass(double m1, double m2)
{
  double r = m1 / m2;
  return isinf(r) ? m2 / (1.0 + m2 / m1) : m1 / (1.0 + r);
}

/* Half the velocity difference d = (v1 - v2)/2 (exact for normal
 * velocities, and no overflow of the difference) and its largest
 * component in magnitude. */
static double half_diff(const double *v1, const double *v2, double d[3])
{
  double dm = 0.0;
  for (int k = 0; k < 3; k++) {
    d[k] = 0.5 * v1[k] - 0.5 * v2[k];
    dm = fmax(dm, fabs(d[k]));
  }
  return dm;
}

/* A velocity scale (m/s) inside which the plain formulas for E_rel can
 * neither overflow nor underflow in their sums of squares; outside it
 * they are evaluated in scaled form. */
#define EREL_VMIN 1e-100
#define EREL_VMAX 1e100

/* (1/2) mu |w|^2 c with |w| = 2 dm: 2 (sqrt(mu) dm)^2 c, the factors
 * ordered so that an intermediate over/underflows only where E does;
 * NaN and SB_ERANGE recorded (for func) if E overflows. */
static double erel_scaled(double mu, double dm, double c, const char *func)
{
  double u = sqrt(mu) * dm;
  double E = (2.0 * c * u) * u;
  if (isinf(E)) {
    sbi_error(SB_ERANGE, func, "the energy overflows (mu = %g, |v1 - v2| "
              "~ %g)", mu, 2.0 * dm);
    return NAN;
  }
  return E;
}

double sb_dlvo_erel(double m1, double m2, const double v1[3],
                    const double v2[3])
{
  if (!(pos(m1) && pos(m2) && vec_ok(v1) && vec_ok(v2))) {
    sbi_error(SB_EDOM, __func__,
              "masses must be finite and > 0, velocities finite (m1 = %g, "
              "m2 = %g)", m1, m2);
    return NAN;
  }
  const double mu = reduced_mass(m1, m2);
  double d[3], dm = half_diff(v1, v2, d);
  if (dm == 0.0 || (dm >= EREL_VMIN && dm <= EREL_VMAX)) {
    double w2 = 0.0;
    for (int k = 0; k < 3; k++)
      w2 += (v1[k] - v2[k]) * (v1[k] - v2[k]);
    double E = 0.5 * mu * w2;
    if (isinf(E)) {
      sbi_error(SB_ERANGE, __func__, "the energy overflows (mu = %g, "
                "|v1 - v2|^2 = %g)", mu, w2);
      return NAN;
    }
    return E;
  }
  double c = 0.0;
  for (int k = 0; k < 3; k++)
    c += (d[k] / dm) * (d[k] / dm);
  return erel_scaled(mu, dm, c, __func__);
}

double sb_dlvo_erel_normal(double m1, double m2, const double v1[3],
                           const double v2[3], const double n[3])
{
  if (!(pos(m1) && pos(m2) && vec_ok(v1) && vec_ok(v2) && vec_ok(n) &&
        (n[0] != 0.0 || n[1] != 0.0 || n[2] != 0.0))) {
    sbi_error(SB_EDOM, __func__,
              "masses must be > 0, vectors finite, n non-zero (m1 = %g, "
              "m2 = %g)", m1, m2);
    return NAN;
  }
  const double mu = reduced_mass(m1, m2);
  double d[3], dm = half_diff(v1, v2, d);
  double nm = fmax(fabs(n[0]), fmax(fabs(n[1]), fabs(n[2])));
  if ((dm == 0.0 || (dm >= EREL_VMIN && dm <= EREL_VMAX)) &&
      nm >= EREL_VMIN && nm <= EREL_VMAX) {
    double wn = 0.0, nn = 0.0;
    for (int k = 0; k < 3; k++) {
      wn += (v1[k] - v2[k]) * n[k];
      nn += n[k] * n[k];
    }
    double E = 0.5 * mu * (wn * wn / nn);
    if (isinf(E)) {
      sbi_error(SB_ERANGE, __func__, "the energy overflows (mu = %g, "
                "w.n/|n| = %g)", mu, wn / sqrt(nn));
      return NAN;
    }
    return E;
  }
  if (dm == 0.0)
    return 0.0;
  /* scaled: c = ((d/dm).(n/nm))^2 / |n/nm|^2 <= 3 */
  double dn = 0.0, nn = 0.0;
  for (int k = 0; k < 3; k++) {
    dn += (d[k] / dm) * (n[k] / nm);
    nn += (n[k] / nm) * (n[k] / nm);
  }
  return erel_scaled(mu, dm, dn * dn / nn, __func__);
}

int sb_dlvo_sticks(double E_rel, double W_max) { return E_rel > W_max; }

double sb_dlvo_erel_shape(sb_dlvo_erel_law law, int dim)
{
  if (dim < 1 || dim > 3)
    return NAN;
  switch (law) {
  case SB_DLVO_EREL_STATIONARY: return 0.5 * dim;
  case SB_DLVO_EREL_STATIONARY_NORMAL: return 0.5;
  case SB_DLVO_EREL_COLLISION: return 0.5 * (dim + 1);
  case SB_DLVO_EREL_COLLISION_NORMAL: return 1.0;
  default: return NAN;
  }
}

/* Shape k (twice: 1..4) from law and dim, or SB_EDOM (for the public
 * function who). */
static int law_k2(double E, double theta, sb_dlvo_erel_law law, int dim,
                  sb_result *res, int *k2, const char *who)
{
  double k = sb_dlvo_erel_shape(law, dim);
  REQ(!isnan(k), "invalid law %d or dimension %d", (int)law, dim);
  REQ(pos(theta), "theta must be finite and > 0 (got %g)", theta);
  REQ(E >= 0.0 && !isnan(E), "E must be >= 0 (got %g)", E);
  *k2 = (int)(2.0 * k);
  return SB_SUCCESS;
}

/* P(k, x) = x^k e^-x sum_n x^n/Gamma(k+n+1): positive series, used for
 * k = 3/2, 2 and x < 2 (terms ratio x/(k+n+1) < 2/3). */
static double p_series(int k2, double x, double *rel)
{
  double k = 0.5 * k2;
  /* 1/Gamma(k+1): Gamma(5/2) = 3 sqrt(pi)/4, Gamma(3) = 2 */
  double term = (k2 == 3 ? 4.0 / (3.0 * sqrt(M_PI)) : 0.5);
  double sum = 0.0;
  for (int j = 1; j < 100; j++) {
    sum += term;
    if (term < 0.25 * EPS * sum)
      break;
    term *= x / (k + j);
  }
  *rel = 8.0 * EPS + 2.0 * x * EPS; /* e^-x amplifies x's rounding */
  return pow(x, k) * exp(-x) * sum;
}

/* erf(sqrt x) (upper = 0) or erfc(sqrt x) (upper = 1) from GSL, with the
 * rounding of y = sqrt(x) corrected to first order: y^2 - x is exact by
 * fma, and d erfc(y)/dy = -(2/sqrt pi) e^{-y^2}.  (Used for the lower
 * tail; the upper one goes through sbi_mills, see gam_pq.) */
static double erf_sqrt(double x, int upper, gsl_sf_result *ef)
{
  double y = sqrt(x);
  if (y > 1e10) { /* GSL's erf and erfc return NaN from y ~ 1e62 on;
                   * erfc(y) < e^-1e20 underflows here */
    ef->val = upper ? 0.0 : 1.0;
    ef->err = upper ? 0.0 : EPS;
    return ef->val;
  }
  double h = y > 0.0 ? -fma(y, y, -x) / (2.0 * y) : 0.0; /* sqrt(x) - y */
  double d = h * M_2_SQRTPI * exp(-y * y);
  if (upper) {
    gsl_sf_erfc_e(y, ef);
    return ef->val - d;
  }
  gsl_sf_erf_e(y, ef);
  return ef->val + d;
}

/* P (upper = 0) or Q (upper = 1) of Gamma(k2/2) at x = E/theta. */
static double gam_pq(int k2, double x, int upper, double *err)
{
  gsl_sf_result ef;
  if (x == 0.0) {
    *err = 0.0;
    return upper ? 1.0 : 0.0;
  }
  double v, rel = 2.0 * EPS * (1.0 + x);
  if (k2 >= 3 && !upper && x < 2.0) { /* k = 3/2, 2: the positive series */
    v = p_series(k2, x, &rel);
    *err = rel * v;
    return v;
  }
  switch (k2) {
  case 1:
    if (upper) { /* erfc(sqrt x) = 2 M(sqrt(2x)) e^-x: no x eps loss */
      v = 2.0 * sbi_mills(sqrt(2.0 * x)) * exp(-x);
      *err = 8.0 * EPS * v;
      return v;
    }
    v = erf_sqrt(x, 0, &ef);
    *err = ef.err + 4.0 * EPS * fabs(v);
    return v;
  case 2:
    if (upper) {
      v = exp(-x);
      *err = rel * v;
      return v;
    }
    /* P = -expm1(-x): one rounding, plus x's rounding (<= x eps/2, from
     * E/theta) times dP/dx = e^-x -- not (1 + x) eps relative, which
     * grew without bound although P -> 1 */
    v = -expm1(-x);
    *err = 2.0 * EPS * v + EPS * x * exp(-x);
    return v;
  case 3:
    if (upper) { /* e^-x (2 M(sqrt(2x)) + 2 sqrt(x/pi)) */
      v = (2.0 * sbi_mills(sqrt(2.0 * x)) + 2.0 * sqrt(x / M_PI)) * exp(-x);
      *err = 10.0 * EPS * v;
      return v;
    }
    {
      double t = 2.0 * sqrt(x / M_PI) * exp(-x);
      double e = erf_sqrt(x, 0, &ef);
      v = e - t;
      *err = ef.err + 8.0 * EPS * (fabs(e) + t);
      return v;
    }
  default: /* 4: k = 2 */
    if (upper) {
      v = (1.0 + x) * exp(-x);
      /* (4 + 2x) EPS, written so that it cannot overflow */
      *err = (4.0 * EPS + 2.0 * EPS * x) * v;
      return v;
    }
    {
      /* P = a - b, a = -expm1(-x), b = x e^-x (x >= 2 here, P >= 0.59):
       * a to 1 ulp; b to 3 ulp plus x eps/2 relative through e^-x; the
       * difference 1 ulp; x's own rounding moves P by dP/dx = b times
       * x eps/2.  The bound tends to ~3 eps, not (4 + 2x) eps. */
      const double a = -expm1(-x), b = x * exp(-x);
      v = a - b;
      *err = EPS * (2.0 * a + (3.0 + x) * b + v);
      return v;
    }
  }
}

/* P (upper = 0) or Q (upper = 1) of the law at E. */
static int erel_pq(double E, double theta, sb_dlvo_erel_law law, int dim,
                   int upper, sb_result *res, const char *who)
{
  int k2;
  int s = law_k2(E, theta, law, dim, res, &k2, who);
  if (s != SB_SUCCESS)
    return s;
  /* E = inf, or E/theta beyond DBL_MAX: Q < e^-DBL_MAX is 0 and P rounds
   * to 1 */
  if (isinf(E / theta)) {
    res->val = upper ? 0.0 : 1.0, res->err = 0.0;
    return SB_SUCCESS;
  }
  res->val = gam_pq(k2, E / theta, upper, &res->err);
  return SB_SUCCESS;
}

int sb_dlvo_erel_P_e(double E, double theta, sb_dlvo_erel_law law, int dim,
                     sb_result *res)
{
  return erel_pq(E, theta, law, dim, 0, res, __func__);
}

double sb_dlvo_erel_P(double E, double theta, sb_dlvo_erel_law law, int dim)
{
  VAL(erel_pq(E, theta, law, dim, 0, &r_, __func__));
}

int sb_dlvo_erel_Q_e(double E, double theta, sb_dlvo_erel_law law, int dim,
                     sb_result *res)
{
  return erel_pq(E, theta, law, dim, 1, res, __func__);
}

double sb_dlvo_erel_Q(double E, double theta, sb_dlvo_erel_law law, int dim)
{
  VAL(erel_pq(E, theta, law, dim, 1, &r_, __func__));
}

double sb_dlvo_erel_logQ(double E, double theta, sb_dlvo_erel_law law,
                         int dim)
{
  sb_result rr, *res = &rr;
  int k2;
  if (law_k2(E, theta, law, dim, res, &k2, __func__) != SB_SUCCESS)
    return NAN;
  double x = E / theta;
  if (isinf(x)) {
    if (isinf(E))
      return -HUGE_VAL; /* Q = 0 exactly */
    sbi_error(SB_ERANGE, __func__, "log Q ~ -E/theta overflows (E = %g, "
              "theta = %g)", E, theta);
    return NAN;
  }
  if (x < 1.0) { /* log1p(-P) keeps the relative accuracy when Q ~ 1 */
    double P = gam_pq(k2, x, 0, &rr.err);
    return P < 0.25 ? log1p(-P) : log(gam_pq(k2, x, 1, &rr.err));
  }
  /* Q = e^-x times a factor that neither underflows nor overflows */
  switch (k2) {
  case 1: return -x + log(2.0 * sbi_mills(sqrt(2.0 * x)));
  case 2: return -x;
  case 3: return -x + log(2.0 * sbi_mills(sqrt(2.0 * x)) +
                          2.0 * sqrt(x / M_PI));
  default: return log1p(x) - x;
  }
}

double sb_dlvo_erel_pdf(double E, double theta, sb_dlvo_erel_law law,
                        int dim)
{
  sb_result rr, *res = &rr;
  int k2;
  if (law_k2(E, theta, law, dim, res, &k2, __func__) != SB_SUCCESS)
    return NAN;
  double x = E / theta, f;
  if (isinf(x))
    return 0.0; /* e^-x underflows whatever the prefactor */
  /* x^(k-1) e^-x / (Gamma(k) theta) */
  switch (k2) {
  case 1: f = exp(-x) / (sqrt(M_PI * x) * theta); break;
  case 2: f = exp(-x) / theta; break;
  case 3: f = 2.0 * sqrt(x / M_PI) * exp(-x) / theta; break;
  default: f = x * exp(-x) / theta; break;
  }
  if (isinf(f) && !(k2 == 1 && E == 0.0)) { /* theta below ~1e-308 */
    sbi_error(SB_ERANGE, __func__, "the density overflows (E = %g, "
              "theta = %g)", E, theta);
    return NAN;
  }
  return f;
}

double sb_dlvo_erel_sample(const gsl_rng *r, double theta,
                           sb_dlvo_erel_law law, int dim)
{
  double k = sb_dlvo_erel_shape(law, dim);
  if (!r || isnan(k) || !pos(theta)) {
    sbi_error(SB_EDOM, __func__, "invalid rng, law %d, dim %d or theta %g",
              (int)law, dim, theta);
    return NAN;
  }
  return gsl_ran_gamma(r, k, theta);
}
