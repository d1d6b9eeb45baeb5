/* langevin.c — exact moments of the Langevin / Ornstein–Uhlenbeck model:
 * variances and covariance of (X_t, U_t), means, mean-square displacement,
 * velocity autocorrelation.  Formulas and their derivation: header and
 * docs/langevin.md.  Everything is written as sums of non-negative terms
 * so that t << tau does not cancel. */
#include <float.h>
#include <math.h>

#include <smolbridge/langevin.h>

#include "common/internal.h"
#include "common/numutil.h"
#include "langevin_internal.h"

/* Error bounds, in units of |val|, for the closed forms below: a few
 * roundings each (see the accuracy note in each helper); the tests check
 * these bounds against 150-digit references. */
#define ERR_VU (8 * DBL_EPSILON)
#define ERR_CXU (8 * DBL_EPSILON)
#define ERR_VX (24 * DBL_EPSILON)
#define ERR_VXC (24 * DBL_EPSILON)

/* c(h) = h - 2 tanh(h/2), the scaled conditional variance of X given U.
 * For h <= 2 the difference cancels (c ~ h^3/12), so use
 *   y - tanh y = (y cosh y - sinh y) / cosh y,
 *   y cosh y - sinh y = sum_{n>=1} [1/(2n)! - 1/(2n+1)!] y^{2n+1}
 *                     = sum_{n>=1} 2n y^{2n+1} / (2n+1)!,
 * a series of positive terms, summed by Horner in y^2 with the
 * coefficients 2n/(2n+1)! below (n = 1..11; for y = h/2 <= 1 the first
 * omitted term is < 1e-23 of the sum), so it is accurate to a few ulps.
 * For h > 2 the direct form loses at most log2(h/c(h)) <= 3 bits. */
static const double cser[11] = {
    0.33333333333333333,    0.033333333333333333,   0.0011904761904761905,
    2.2045855379188713e-5,  2.5052108385441719e-7,  1.9270852604185938e-9,
    1.0706029224547743e-11, 4.4983316069528332e-14, 1.4797143443923793e-16,
    3.9145882126782522e-19, 8.5099743753875049e-22};

static double cfun(double h)
{
  if (h > 2.0)
    return h - 2.0 * tanh(0.5 * h);
  double y = 0.5 * h, y2 = y * y, sum = cser[10];
  for (int n = 9; n >= 0; n--)
    sum = sum * y2 + cser[n];
  return 2.0 * y * y2 * sum / cosh(y);
}

/* Scaled moments (tau = B = 1) at h = t/tau:
 *   vu = a (2 - a)/2,  cxu = a^2/2,  vxc = c(h),
 *   vx = c(h) + a^3 / (2 (2 - a))   [= vxc + cxu^2/vu, both terms >= 0],
 * a = -expm1(-h).  The last identity is var_x = var_x|u + cov^2/var_u. */
static double sc_vu(double h)
{
  double a = -expm1(-h);
  return 0.5 * a * (2.0 - a);
}

static double sc_cxu(double h)
{
  double a = -expm1(-h);
  return 0.5 * a * a;
}

static double sc_vx(double h)
{
  double a = -expm1(-h);
  return cfun(h) + a * a * a / (2.0 * (2.0 - a));
}

static double sc_xu2(double h)
{
  double a = -expm1(-h);
  return a * a * a / (2.0 * (2.0 - a));
}

static double sc_msd(double h);

#define X(x) sbi_xd_of(x)
#define MUL(a, b) sbi_xd_mul((a), (b))

/* Extreme arguments.  The values are products B^2 tau^k K(h) whose
 * factors can each leave the double range while the value is a double:
 * tau = 1e300 with t = 1 has h = 1e-300 and K(h) ~ h^3 = 0, times
 * tau^3 = inf (a NaN before); tau = 1e-300 with t = 1e300 has h = inf.
 * The products are taken in sbi_xd arithmetic (numutil.h: the same bits
 * as the double chain wherever nothing over/underflows), h = t/tau too,
 * and K(h) comes from sbi_langevin_kern: below DBL_MIN the leading term
 * k0 h^j of its Taylor series at 0 (K(h) = k0 h^j (1 + O(h)) with
 * h < 1e-100 there), above h = DBL_MAX its limit (h for the kernels
 * growing like h - const, relative error const/h < 1e-307). */
sbi_xd sbi_langevin_kern(int kind, sbi_xd h)
{
  const double hv = sbi_xd_val(h);
  if (isinf(hv)) {
    if (kind == SBI_LK_A)
      return X(1.0);
    if (kind == SBI_LK_VX || kind == SBI_LK_VXC || kind == SBI_LK_MSD)
      return h;
    return X(0.5);
  }
  double K;
  switch (kind) {
  case SBI_LK_A: K = -expm1(-hv); break;
  case SBI_LK_VU: K = sc_vu(hv); break;
  case SBI_LK_CXU: K = sc_cxu(hv); break;
  case SBI_LK_XU2: K = sc_xu2(hv); break;
  case SBI_LK_VX: K = sc_vx(hv); break;
  case SBI_LK_VXC: K = cfun(hv); break;
  default: K = sc_msd(hv); break;
  }
  if (K >= DBL_MIN)
    return X(K);
  /* small h: K ~ k0 h^j */
  static const double k0[] = {1.0, 1.0, 0.5, 0.25, 1.0 / 3.0, 1.0 / 12.0,
                              0.5};
  static const int j[] = {1, 1, 2, 3, 3, 3, 2};
  sbi_xd v = X(k0[kind]);
  for (int i = 0; i < j[kind]; i++)
    v = MUL(v, h);
  return v;
}

/* h = t/tau as an sbi_xd */
static sbi_xd xd_h(double t, double tau)
{
  return sbi_xd_div(X(t), X(tau));
}

int sbi_langevin_plain_ok(double tau, double B, double t)
{
  const double at = fabs(t);
  return tau >= 0x1p-100 && tau <= 0x1p100 &&
         (B == 0.0 || (B >= 0x1p-100 && B <= 0x1p100)) &&
         (at == 0.0 || (at >= 0x1p-100 && at <= 0x1p100));
}

double sbi_langevin_cfun(double h) { return cfun(h); }

/* Argument checks shared by the (tau, B, t) functions; returns a status and
 * records the message under the public function's name. */
static int check_tbt(const char *func, double tau, double B, double t,
                     int t_any_sign)
{
  if (!(tau > 0) || !isfinite(tau))
    return sbi_error(SB_EDOM, func, "tau = %g must be positive and finite",
                     tau);
  if (!(B >= 0) || !isfinite(B))
    return sbi_error(SB_EDOM, func, "B = %g must be >= 0 and finite", B);
  if (!isfinite(t) || (!t_any_sign && !(t >= 0)))
    return sbi_error(SB_EDOM, func, "t = %g must be %s", t,
                     t_any_sign ? "finite" : ">= 0 and finite");
  return SB_SUCCESS;
}

/* Define `double sb_NAME(tau, B, t)` and `int sb_NAME_e(..., res)` from a
 * scaled kernel KIND (value = B^2 tau^k K(t/tau), TAUK the sbi_xd
 * expression tau^k) and a relative error bound; SB_ERANGE where the value
 * exceeds DBL_MAX. */
#define SB_LANGEVIN_TBT(NAME, KIND, KERN, TAUKP, TAUK, RELERR)             \
  static double NAME##_val(double tau, double B, double t, const char *fn)  \
  {                                                                         \
    if (sbi_langevin_plain_ok(tau, B, t))                                   \
      return B * B * (TAUKP) * KERN(t / tau);                               \
    return sbi_xd_checked(MUL(MUL(MUL(X(B), X(B)), TAUK),                   \
                              sbi_langevin_kern(KIND, xd_h(t, tau))),       \
                          fn);                                              \
  }                                                                         \
  int sb_langevin_##NAME##_e(double tau, double B, double t,                \
                             sb_result *res)                                \
  {                                                                         \
    int st = check_tbt(__func__, tau, B, t, 0);                             \
    if (st) {                                                               \
      if (res)                                                              \
        res->val = res->err = NAN;                                          \
      return st;                                                            \
    }                                                                       \
    if (!res)                                                               \
      return sbi_error(SB_EINVAL, __func__, "res is NULL");                 \
    double v = NAME##_val(tau, B, t, __func__);                             \
    res->val = v;                                                           \
    res->err = (RELERR) * fabs(v);                                          \
    return isnan(v) ? SB_ERANGE : SB_SUCCESS;                               \
  }                                                                         \
  double sb_langevin_##NAME(double tau, double B, double t)                 \
  {                                                                         \
    if (check_tbt(__func__, tau, B, t, 0))                                  \
      return NAN;                                                           \
    return NAME##_val(tau, B, t, __func__);                                 \
  }

#define TAU1 X(tau)
#define TAU2 MUL(X(tau), X(tau))
#define TAU3 MUL(MUL(X(tau), X(tau)), X(tau))
SB_LANGEVIN_TBT(var_u, SBI_LK_VU, sc_vu, tau, TAU1, ERR_VU)
SB_LANGEVIN_TBT(cov_xu, SBI_LK_CXU, sc_cxu, tau * tau, TAU2, ERR_CXU)
SB_LANGEVIN_TBT(var_x, SBI_LK_VX, sc_vx, tau * tau * tau, TAU3, ERR_VX)
SB_LANGEVIN_TBT(var_x_cond, SBI_LK_VXC, cfun, tau * tau * tau, TAU3, ERR_VXC)

double sb_langevin_var_stat(double tau, double B)
{
  if (check_tbt(__func__, tau, B, 0.0, 0))
    return NAN;
  return sbi_xd_checked(MUL(MUL(MUL(X(0.5), X(B)), X(B)), X(tau)), __func__);
}

/* MSD = B^2 tau^3 (h - a), a = 1 - e^{-h}.  h - a cancels for small h
 * (GSL's exprel_2 loses ~1e-12 relative near h = 0.01), so use the identity
 * MSD = var_x + tau^2 a^2 <U_0^2>, <U_0^2> = B^2 tau/2, i.e.
 *   h - a = vx(h) + a^2/2,
 * a sum of two non-negative accurate terms. */
static double sc_msd(double h)
{
  double a = -expm1(-h);
  return sc_vx(h) + 0.5 * a * a;
}

static double msd_val(double tau, double B, double t, const char *fn)
{
  if (sbi_langevin_plain_ok(tau, B, t))
    return B * B * tau * tau * tau * sc_msd(t / tau);
  return sbi_xd_checked(MUL(MUL(MUL(MUL(MUL(X(B), X(B)), X(tau)), X(tau)),
                                X(tau)),
                            sbi_langevin_kern(SBI_LK_MSD, xd_h(t, tau))),
                        fn);
}

int sb_langevin_msd_e(double tau, double B, double t, sb_result *res)
{
  int st = check_tbt(__func__, tau, B, t, 0);
  if (st) {
    if (res)
      res->val = res->err = NAN;
    return st;
  }
  if (!res)
    return sbi_error(SB_EINVAL, __func__, "res is NULL");
  double v = msd_val(tau, B, t, __func__);
  res->val = v;
  res->err = ERR_VX * fabs(v);
  return isnan(v) ? SB_ERANGE : SB_SUCCESS;
}

double sb_langevin_msd(double tau, double B, double t)
{
  if (check_tbt(__func__, tau, B, t, 0))
    return NAN;
  return msd_val(tau, B, t, __func__);
}

double sb_langevin_msd_ballistic(double tau, double B, double t)
{
  if (check_tbt(__func__, tau, B, t, 0))
    return NAN;
  return sbi_xd_checked(MUL(MUL(MUL(MUL(MUL(X(0.5), X(B)), X(B)), X(tau)),
                                X(t)),
                            X(t)),
                        __func__);
}

double sb_langevin_msd_diffusive(double tau, double B, double t)
{
  if (check_tbt(__func__, tau, B, t, 0))
    return NAN;
  return sbi_xd_checked(MUL(MUL(MUL(MUL(X(B), X(B)), X(tau)), X(tau)), X(t)),
                        __func__);
}

double sb_langevin_vacf(double tau, double B, double t)
{
  if (check_tbt(__func__, tau, B, t, 1))
    return NAN;
  /* |t|/tau = inf gives exp(-inf) = 0, the right value */
  return sbi_xd_checked(MUL(MUL(MUL(MUL(X(0.5), X(B)), X(B)), X(tau)),
                            sbi_xd_expneg(fabs(t) / tau)),
                        __func__);
}

int sb_langevin_moments(const sb_langevin *p, double t, double x0, double u0,
                        sb_langevin_mom *m)
{
  if (!m)
    return sbi_error(SB_EINVAL, __func__, "m is NULL");
  m->mean_x = m->mean_u = m->var_x = m->var_u = m->cov_xu = NAN;
  if (!p)
    return sbi_error(SB_EINVAL, __func__, "p is NULL");
  int st = check_tbt(__func__, p->tau, p->B, t, 0);
  if (st)
    return st;
  if (!isfinite(p->us) || !isfinite(x0) || !isfinite(u0))
    return sbi_error(SB_EDOM, __func__,
                     "us = %g, x0 = %g, u0 = %g must be finite", p->us, x0,
                     u0);
  const double tau = p->tau, B = p->B;
  if (sbi_langevin_plain_ok(tau, B, t)) { /* the formulas as they read */
    double B2 = B * B, h = t / tau;
    double a = -expm1(-h), w = u0 - p->us;
    double mu = p->us + w * exp(-h);
    double mx = x0 + p->us * t + w * tau * a;
    if (isfinite(mu) && isfinite(mx)) {
      m->mean_u = mu;
      m->mean_x = mx;
      m->var_u = B2 * tau * sc_vu(h);
      m->cov_xu = B2 * tau * tau * sc_cxu(h);
      m->var_x = B2 * tau * tau * tau * sc_vx(h);
      return SB_SUCCESS;
    }
  }
  const sbi_xd hx = xd_h(t, tau), ax = sbi_langevin_kern(SBI_LK_A, hx);
  const sbi_xd B2 = MUL(X(B), X(B));
  const double h = sbi_xd_val(hx); /* t/tau: inf gives e = 0 */
  double w = u0 - p->us, e = exp(-h), mx, mu;
  /* (the same operations as the plain formulas of the header) */
  if (isfinite(w)) {
    mu = p->us + w * e;
    mx = x0 + p->us * t + sbi_xd_val(MUL(MUL(X(w), X(tau)), ax));
  } else { /* u0 - us overflows: halve it, mean_u lies between us and u0 */
    w = 0.5 * u0 - 0.5 * p->us;
    mu = 2.0 * (0.5 * p->us + w * e);
    mx = x0 + p->us * t + 2.0 * sbi_xd_val(MUL(MUL(X(w), X(tau)), ax));
  }
  const double vu = sbi_xd_val(
      MUL(MUL(B2, X(tau)), sbi_langevin_kern(SBI_LK_VU, hx)));
  const double cxu = sbi_xd_val(
      MUL(MUL(MUL(B2, X(tau)), X(tau)), sbi_langevin_kern(SBI_LK_CXU, hx)));
  const double vx = sbi_xd_val(
      MUL(MUL(MUL(MUL(B2, X(tau)), X(tau)), X(tau)),
          sbi_langevin_kern(SBI_LK_VX, hx)));
  if (!isfinite(mx) || !isfinite(mu) || !isfinite(vx) || !isfinite(vu) ||
      !isfinite(cxu))
    return sbi_error(SB_ERANGE, __func__,
                     "a moment overflows a double (mean_x = %g, mean_u = "
                     "%g, var_x = %g, var_u = %g, cov_xu = %g)", mx, mu, vx,
                     vu, cxu);
  m->mean_u = mu;
  m->mean_x = mx;
  m->var_u = vu;
  m->cov_xu = cxu;
  m->var_x = vx;
  return SB_SUCCESS;
}
