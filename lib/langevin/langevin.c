/* langevin.c — exact moments of the Langevin / Ornstein–Uhlenbeck model:
 * variances and covariance of (X_t, U_t), means, mean-square displacement,
 * velocity autocorrelation.  Formulas and their derivation: header and
 * docs/langevin.md.  Everything is written as sums of non-negative terms
 * so that t << tau does not cancel. */
#include <float.h>
#include <math.h>

#include <smolbridge/langevin.h>

#include "common/internal.h"

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
 * scaled kernel KERN(h) (value = B^2 tau^k KERN(t/tau), TAUK the
 * expression tau^k) and a relative error bound. */
#define SB_LANGEVIN_TBT(NAME, KERN, TAUK, RELERR)                           \
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
    double v = B * B * (TAUK) * KERN(t / tau);                              \
    res->val = v;                                                           \
    res->err = (RELERR) * fabs(v);                                          \
    return SB_SUCCESS;                                                      \
  }                                                                         \
  double sb_langevin_##NAME(double tau, double B, double t)                 \
  {                                                                         \
    if (check_tbt(__func__, tau, B, t, 0))                                  \
      return NAN;                                                           \
    return B * B * (TAUK) * KERN(t / tau);                                  \
  }

SB_LANGEVIN_TBT(var_u, sc_vu, tau, ERR_VU)
SB_LANGEVIN_TBT(cov_xu, sc_cxu, tau * tau, ERR_CXU)
SB_LANGEVIN_TBT(var_x, sc_vx, tau * tau * tau, ERR_VX)
SB_LANGEVIN_TBT(var_x_cond, cfun, tau * tau * tau, ERR_VXC)

double sb_langevin_var_stat(double tau, double B)
{
  if (check_tbt(__func__, tau, B, 0.0, 0))
    return NAN;
  return 0.5 * B * B * tau;
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
  double v = B * B * tau * tau * tau * sc_msd(t / tau);
  res->val = v;
  res->err = ERR_VX * fabs(v);
  return SB_SUCCESS;
}

double sb_langevin_msd(double tau, double B, double t)
{
  if (check_tbt(__func__, tau, B, t, 0))
    return NAN;
  sb_result r;
  sb_langevin_msd_e(tau, B, t, &r);
  return r.val;
}

double sb_langevin_msd_ballistic(double tau, double B, double t)
{
  if (check_tbt(__func__, tau, B, t, 0))
    return NAN;
  return 0.5 * B * B * tau * t * t;
}

double sb_langevin_msd_diffusive(double tau, double B, double t)
{
  if (check_tbt(__func__, tau, B, t, 0))
    return NAN;
  return B * B * tau * tau * t;
}

double sb_langevin_vacf(double tau, double B, double t)
{
  if (check_tbt(__func__, tau, B, t, 1))
    return NAN;
  return 0.5 * B * B * tau * exp(-fabs(t) / tau);
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
  double tau = p->tau, B2 = p->B * p->B, h = t / tau;
  double a = -expm1(-h), w = u0 - p->us;
  m->mean_u = p->us + w * exp(-h);
  m->mean_x = x0 + p->us * t + w * tau * a;
  m->var_u = B2 * tau * sc_vu(h);
  m->cov_xu = B2 * tau * tau * sc_cxu(h);
  m->var_x = B2 * tau * tau * tau * sc_vx(h);
  return SB_SUCCESS;
}
