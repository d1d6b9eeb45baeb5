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

/* Fail an _e function with SB_EDOM unless cond. */
#define REQ(cond, ...)                                       \
  do {                                                       \
    if (!(cond))                                             \
      return SBI_FAIL_RES(res, SB_EDOM, __VA_ARGS__);        \
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

/* Derjaguin radius r1 r2/(r1 + r2), = r1 for a plane. */
static double reff(double r1, double r2)
{
  return isinf(r2) ? r1 : r1 / (1.0 + r1 / r2);
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
  double ze = z * SB_DLVO_ECHARGE;
  return sqrt(2.0 * n0 * ze * ze / (eps_r * SB_DLVO_EPS0 * kB * T));
}

/* ------------------------------------------------------------ van der Waals */

/* g(t) = t + t/(1 + 2t) - ln(1 + 2t), t >= 0, with an absolute error bound.
 * Cancels as (4/3) t^3 for small t: the series (y = 2t)
 *   g = (1/2) sum_{k>=3} (-1)^(k-1) (k-2)/k y^k
 * (alternating, terms decreasing for y <= 1/2) for t < 1/4; above, the
 * form -(ln(1+y) - y) - y^2/(2(1+y)) with GSL's log_1plusx_mx loses at
 * most a factor 16 to cancellation. */
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
  if (isinf(y)) {  /* D below what t = R/D can hold: the energy overflows */
    *err = 0.0;
    return INFINITY;
  }
  /* y (y/(1 + y)), not y^2/(1 + y): y^2 overflows above 1.3e154 (contact
   * distances of R/1e154), and -A/6 g became +inf */
  double a = -gsl_sf_log_1plusx_mx(y), b = 0.5 * y * (y / (1.0 + y));
  *err = 4.0 * EPS * (fabs(a) + fabs(b));
  return a - b;
}

/* t = 2 r1 r2/(D (D + 2 r1 + 2 r2)) (r1/D for a plane) and the logarithmic
 * derivative -d ln t/dD = 1/D + 1/(D + 2 r1 + 2 r2). */
static double ham_t(double r1, double r2, double D, double *dlog)
{
  if (isinf(r2)) {
    *dlog = 1.0 / D;
    return r1 / D;
  }
  double s = D + 2.0 * (r1 + r2);
  *dlog = 1.0 / D + 1.0 / s;
  return (2.0 * r1 / D) * (r2 / s);
}

int sb_dlvo_vdw_hamaker_e(double A, double r1, double r2, double D,
                          sb_result *res)
{
  REQ_VDW(A, r1, r2, D);
  double dl, t = ham_t(r1, r2, D, &dl), eg;
  double g = ham_g(t, &eg);
  /* t carries ~4 ulp; g'(t) t <= 2 g for every t (g' = (2t/(1+2t))^2) is
   * not true near 0, so bound the propagated part by g'(t) t 4 eps. */
  double gp = 2.0 * t / (1.0 + 2.0 * t);
  eg += 4.0 * EPS * gp * gp * t;
  res->val = -A / 6.0 * g;
  res->err = fabs(A) / 6.0 * eg + 2.0 * EPS * fabs(res->val);
  return SB_SUCCESS;
}

double sb_dlvo_vdw_hamaker(double A, double r1, double r2, double D)
{
  VAL(sb_dlvo_vdw_hamaker_e(A, r1, r2, D, &r_));
}

int sb_dlvo_vdw_hamaker_force_e(double A, double r1, double r2, double D,
                                sb_result *res)
{
  REQ_VDW(A, r1, r2, D);
  /* F = (A/6) g'(t) dt/dD = -(A/6) (2t/(1+2t))^2 t (1/D + 1/(D+2r1+2r2)):
   * products of positive factors, no cancellation. */
  double dl, t = ham_t(r1, r2, D, &dl);
  double gp = isinf(t) ? 1.0 : 2.0 * t / (1.0 + 2.0 * t);
  res->val = -A / 6.0 * gp * gp * t * dl;
  res->err = 16.0 * EPS * fabs(res->val);
  return SB_SUCCESS;
}

double sb_dlvo_vdw_hamaker_force(double A, double r1, double r2, double D)
{
  VAL(sb_dlvo_vdw_hamaker_force_e(A, r1, r2, D, &r_));
}

/* Derjaguin energy (force = 0) or force (force = 1). */
static int derjaguin(double A, double r1, double r2, double D, sb_result *res,
                     int force)
{
  REQ_VDW(A, r1, r2, D);
  if (force) {
    res->val = -A * reff(r1, r2) / (6.0 * D * D);
    res->err = 5.0 * EPS * fabs(res->val);
  } else {
    res->val = -A * reff(r1, r2) / (6.0 * D);
    res->err = 4.0 * EPS * fabs(res->val);
  }
  return SB_SUCCESS;
}

int sb_dlvo_vdw_derjaguin_e(double A, double r1, double r2, double D,
                            sb_result *res)
{
  return derjaguin(A, r1, r2, D, res, 0);
}

double sb_dlvo_vdw_derjaguin(double A, double r1, double r2, double D)
{
  VAL(derjaguin(A, r1, r2, D, &r_, 0));
}

int sb_dlvo_vdw_derjaguin_force_e(double A, double r1, double r2, double D,
                                  sb_result *res)
{
  return derjaguin(A, r1, r2, D, res, 1);
}

double sb_dlvo_vdw_derjaguin_force(double A, double r1, double r2, double D)
{
  VAL(derjaguin(A, r1, r2, D, &r_, 1));
}

/* ------------------------------------------------------------ double layer */

#define REQ_EDL(kappa, eps_r, psi1, psi2)                                  \
  REQ(pos(kappa) && pos(eps_r),                                            \
      "kappa and eps_r must be finite and > 0 (got %g, %g)", kappa, eps_r); \
  REQ(fin(psi1) && fin(psi2), "surface potentials must be finite (got %g, " \
      "%g)", psi1, psi2)

/* LSA energy; *force gets kappa W (same relative error). */
static int lsa(double D, double r1, double r2, double kappa, double eps_r,
               double T, double z, double psi1, double psi2, sb_result *res,
               int force)
{
  REQ_GEOM(r1, r2, D);
  REQ_EDL(kappa, eps_r, psi1, psi2);
  REQ(pos(T) && pos(z), "T and z must be finite and > 0 (got %g, %g)", T, z);
  double kt_ze = kB * T / (z * SB_DLVO_ECHARGE);
  double g1 = tanh(psi1 / (4.0 * kt_ze)), g2 = tanh(psi2 / (4.0 * kt_ze));
  double w = 64.0 * M_PI * eps_r * SB_DLVO_EPS0 * reff(r1, r2) * kt_ze *
             kt_ze * g1 * g2 * exp(-kappa * D);
  if (force)
    w *= kappa;
  res->val = w;
  /* ~12 roundings; exp(-x) turns x's relative rounding (the product
   * kappa D, ~2 ulp with that of its inputs) into x times as much */
  res->err = (16.0 + 3.0 * kappa * D) * EPS * fabs(w);
  return SB_SUCCESS;
}

int sb_dlvo_edl_lsa_e(double D, double r1, double r2, double kappa,
                      double eps_r, double T, double z, double psi1,
                      double psi2, sb_result *res)
{
  return lsa(D, r1, r2, kappa, eps_r, T, z, psi1, psi2, res, 0);
}

double sb_dlvo_edl_lsa(double D, double r1, double r2, double kappa,
                       double eps_r, double T, double z, double psi1,
                       double psi2)
{
  VAL(lsa(D, r1, r2, kappa, eps_r, T, z, psi1, psi2, &r_, 0));
}

int sb_dlvo_edl_lsa_force_e(double D, double r1, double r2, double kappa,
                            double eps_r, double T, double z, double psi1,
                            double psi2, sb_result *res)
{
  return lsa(D, r1, r2, kappa, eps_r, T, z, psi1, psi2, res, 1);
}

double sb_dlvo_edl_lsa_force(double D, double r1, double r2, double kappa,
                             double eps_r, double T, double z, double psi1,
                             double psi2)
{
  VAL(lsa(D, r1, r2, kappa, eps_r, T, z, psi1, psi2, &r_, 1));
}

/* HHF energy or force.  ln(1 + e^-x) = log1p(exp(-x)),
 * ln(1 - e^-x) = sbi_log1mexp(x) (Maechler 2012); the force terms 1/(e^x + 1) and
 * 1/expm1(x) are accurate for every x > 0 (1/inf = 0 for large x). */
static int hhf(double D, double r1, double r2, double kappa, double eps_r,
               double psi1, double psi2, sb_result *res, int force)
{
  REQ_GEOM(r1, r2, D);
  REQ_EDL(kappa, eps_r, psi1, psi2);
  double x = kappa * D;
  double sp = (psi1 + psi2) * (psi1 + psi2), sm = (psi1 - psi2) * (psi1 - psi2);
  double pre = M_PI * eps_r * SB_DLVO_EPS0 * reff(r1, r2);
  double a, b;
  if (force) {
    pre *= kappa;
    a = sp / (exp(x) + 1.0);
    b = sm == 0.0 ? 0.0 : -sm / expm1(x);
  } else {
    a = sp * log1p(exp(-x));
    b = sm == 0.0 ? 0.0 : sm * sbi_log1mexp(x);
  }
  res->val = pre * (a + b);
  /* each term ~8 roundings plus the x-sensitivity (<= x relative for the
   * exponentials; <= 1 for the logarithms near 0 since x d/dx ln(1-e^-x)
   * = x/expm1(x) <= 1) */
  res->err = pre * (10.0 + 3.0 * x) * EPS * (fabs(a) + fabs(b)) +
             2.0 * EPS * fabs(res->val);
  return SB_SUCCESS;
}

int sb_dlvo_edl_hhf_e(double D, double r1, double r2, double kappa,
                      double eps_r, double psi1, double psi2, sb_result *res)
{
  return hhf(D, r1, r2, kappa, eps_r, psi1, psi2, res, 0);
}

double sb_dlvo_edl_hhf(double D, double r1, double r2, double kappa,
                       double eps_r, double psi1, double psi2)
{
  VAL(hhf(D, r1, r2, kappa, eps_r, psi1, psi2, &r_, 0));
}

int sb_dlvo_edl_hhf_force_e(double D, double r1, double r2, double kappa,
                            double eps_r, double psi1, double psi2,
                            sb_result *res)
{
  return hhf(D, r1, r2, kappa, eps_r, psi1, psi2, res, 1);
}

double sb_dlvo_edl_hhf_force(double D, double r1, double r2, double kappa,
                             double eps_r, double psi1, double psi2)
{
  VAL(hhf(D, r1, r2, kappa, eps_r, psi1, psi2, &r_, 1));
}

/* ------------------------------------------------------------ pair */

int sb_dlvo_pair_check(const sb_dlvo_pair *p)
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

/* The two parts of the energy (force = 0) or of the force (force = 1) of
 * a checked pair. */
static void parts(const sb_dlvo_pair *p, double D, int force, sb_result *v,
                  sb_result *e)
{
  if (p->vdw == SB_DLVO_VDW_HAMAKER) {
    if (force)
      sb_dlvo_vdw_hamaker_force_e(p->A, p->r1, p->r2, D, v);
    else
      sb_dlvo_vdw_hamaker_e(p->A, p->r1, p->r2, D, v);
  } else {
    if (force)
      sb_dlvo_vdw_derjaguin_force_e(p->A, p->r1, p->r2, D, v);
    else
      sb_dlvo_vdw_derjaguin_e(p->A, p->r1, p->r2, D, v);
  }
  if (p->edl == SB_DLVO_EDL_LSA)
    lsa(D, p->r1, p->r2, p->kappa, p->eps_r, p->T, p->z, p->psi1, p->psi2, e,
        force);
  else
    hhf(D, p->r1, p->r2, p->kappa, p->eps_r, p->psi1, p->psi2, e, force);
}

static int total(const sb_dlvo_pair *p, double D, int force, sb_result *res)
{
  int s = sb_dlvo_pair_check(p); /* records the message */
  if (s != SB_SUCCESS) {
    res->val = res->err = NAN;
    return s;
  }
  REQ(pos(D), "separation D must be finite and > 0 (got %g)", D);
  sb_result v, e;
  parts(p, D, force, &v, &e);
  res->val = v.val + e.val;
  res->err = v.err + e.err + EPS * fabs(res->val);
  return SB_SUCCESS;
}

int sb_dlvo_energy_e(const sb_dlvo_pair *p, double D, sb_result *res)
{
  return total(p, D, 0, res);
}
double sb_dlvo_energy(const sb_dlvo_pair *p, double D)
{
  VAL(total(p, D, 0, &r_));
}
int sb_dlvo_force_e(const sb_dlvo_pair *p, double D, sb_result *res)
{
  return total(p, D, 1, res);
}
double sb_dlvo_force(const sb_dlvo_pair *p, double D)
{
  VAL(total(p, D, 1, &r_));
}

/* ------------------------------------------------------------ barrier */

/* Unchecked evaluations for the search. */
static double fW(const sb_dlvo_pair *p, double D, double *err)
{
  sb_result v, e;
  parts(p, D, 0, &v, &e);
  if (err)
    *err = v.err + e.err + EPS * fabs(v.val + e.val);
  return v.val + e.val;
}

static double fF(double D, void *ctx)
{
  sb_result v, e;
  parts((const sb_dlvo_pair *)ctx, D, 1, &v, &e);
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
  parts(p, *root, 1, &v, &e);
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
  int s = sb_dlvo_pair_check(p);
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
      parts(p, Dhi, 1, &v, &e);
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

/* Shape k (twice: 1..4) from law and dim, or SB_EDOM. */
static int law_k2(double E, double theta, sb_dlvo_erel_law law, int dim,
                  sb_result *res, int *k2)
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
    v = upper ? exp(-x) : -expm1(-x);
    *err = rel * v;
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
    v = upper ? (1.0 + x) * exp(-x) : -expm1(-x) - x * exp(-x);
    /* (4 + 2x) EPS, written so that it cannot overflow */
    *err = (4.0 * EPS + 2.0 * EPS * x) * (upper ? v : 1.0 + x * exp(-x));
    return v;
  }
}

/* P (upper = 0) or Q (upper = 1) of the law at E. */
static int erel_pq(double E, double theta, sb_dlvo_erel_law law, int dim,
                   int upper, sb_result *res)
{
  int k2;
  int s = law_k2(E, theta, law, dim, res, &k2);
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
  return erel_pq(E, theta, law, dim, 0, res);
}

double sb_dlvo_erel_P(double E, double theta, sb_dlvo_erel_law law, int dim)
{
  VAL(erel_pq(E, theta, law, dim, 0, &r_));
}

int sb_dlvo_erel_Q_e(double E, double theta, sb_dlvo_erel_law law, int dim,
                     sb_result *res)
{
  return erel_pq(E, theta, law, dim, 1, res);
}

double sb_dlvo_erel_Q(double E, double theta, sb_dlvo_erel_law law, int dim)
{
  VAL(erel_pq(E, theta, law, dim, 1, &r_));
}

double sb_dlvo_erel_logQ(double E, double theta, sb_dlvo_erel_law law,
                         int dim)
{
  sb_result rr, *res = &rr;
  int k2;
  if (law_k2(E, theta, law, dim, res, &k2) != SB_SUCCESS)
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
  if (law_k2(E, theta, law, dim, res, &k2) != SB_SUCCESS)
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
