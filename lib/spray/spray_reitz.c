/* spray_reitz.c — Reitz wave breakup (Reitz 1987, Atomisation and Spray
 * Technology 3:309–337): Kelvin–Helmholtz wavelength and growth-rate fits,
 * relaxation of the parent radius to R = B0 Lambda, children carrying the
 * shed liquid, and Reitz's second case (B0 Lambda >= a: the drops form
 * once at min((3 pi a^2 U/(2 Omega))^(1/3), (3 a^2 Lambda/4)^(1/3))).
 * Derivations and accuracy: docs/spray.md, "Reitz". */
#include <float.h>
#include <math.h>
#include <string.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <gsl/gsl_roots.h>
#include <gsl/gsl_sf_lambert.h>

#include <smolbridge/spray.h>

#include "common/internal.h"
#include "common/numutil.h"
#include "spray_internal.h"

void sb_spray_reitz_params_default(sb_spray_reitz_params *p)
{
  if (!p)
    return;
  p->B0 = 0.61;
  p->B1 = 10.0;
  p->emit_fraction = 0.03;
  p->children = SB_SPRAY_CHILDREN_AUTO;
  p->child_tag = -1;
  p->stripping = 0;
  p->blob = 0;
}

/* Reitz (1987): when B0 Lambda > a the drops form once, with the volume
 * of the liquid under one wavelength, pi a^2 Lambda, or passing in one
 * wave period 2 pi/Omega, pi a^2 U 2 pi/Omega, whichever is smaller:
 * 4/3 pi r^3 = min(...). */
double sb_spray_reitz_blob_radius(double a, double U, double Lambda,
                                  double Omega)
{
  if (!(a > 0) || !(U > 0) || !(Lambda > 0) || !(Omega > 0) ||
      !isfinite(a) || !isfinite(U) || !isfinite(Lambda) ||
      !isfinite(Omega)) {
    sbi_error(SB_EDOM, __func__, "need a, U, Lambda, Omega > 0 (a = %g, "
              "U = %g, Lambda = %g, Omega = %g)", a, U, Lambda, Omega);
    return NAN;
  }
  double v1 = 3.0 * SBI_PI * a * a * U / (2.0 * Omega);
  double v2 = 0.75 * a * a * Lambda;
  if (!(v1 >= DBL_MIN && v1 <= DBL_MAX && v2 >= DBL_MIN && v2 <= DBL_MAX)) {
    /* a^2 U or a^2 Lambda over/underflows: the same chains with an
     * extended exponent, then the cube root of m 2^e */
    sbi_xd A = sbi_xd_of(a);
    sbi_xd x1 = sbi_xd_mul(sbi_xd_mul(sbi_xd_of(3.0 * SBI_PI), A), A);
    x1 = sbi_xd_div(sbi_xd_mul(x1, sbi_xd_of(U)),
                    sbi_xd_mul(sbi_xd_of(2.0), sbi_xd_of(Omega)));
    sbi_xd x2 = sbi_xd_mul(sbi_xd_mul(sbi_xd_mul(sbi_xd_of(0.75), A), A),
                           sbi_xd_of(Lambda));
    sbi_xd x = (x1.e < x2.e || (x1.e == x2.e && x1.m < x2.m)) ? x1 : x2;
    int q = x.e >= 0 ? x.e / 3 : -((-x.e + 2) / 3);
    return ldexp(cbrt(ldexp(x.m, x.e - 3 * q)), q);
  }
  return fmin(cbrt(v1), cbrt(v2));
}

/* The fits, for valid arguments (U >= 0).  Z = sqrt(We_l)/Re_l =
 * mu_l/sqrt(rho_l a sigma) is written without U so that U -> 0 is safe. */
static void wave(double a, double U, double rho_g, double rho_l,
                 const sb_spray_liquid *liq, double *L, double *O)
{
  double We = rho_g * U * U * a / liq->sigma;
  double Z = liq->mu_l / sqrt(rho_l * a * liq->sigma);
  double T = Z * sqrt(We);
  *L = a * 9.02 * (1.0 + 0.45 * sqrt(Z)) * (1.0 + 0.4 * pow(T, 0.7)) /
       pow(1.0 + 0.87 * pow(We, 1.67), 0.6);
  *O = (0.34 + 0.38 * pow(We, 1.5)) /
       ((1.0 + Z) * (1.0 + 1.4 * pow(T, 0.6))) *
       sqrt(liq->sigma / (rho_l * a * a * a));
}

/* log(1 + c x^p) from lx = log x (lx = -inf: x = 0). */
static double log1p_pow(double c, double lx, double p)
{
  double y = log(c) + p * lx;
  return y > 0 ? y + log1p(exp(-y)) : log1p(exp(y));
}

/* The fits through logarithms, for arguments whose We, Z, T or powers
 * leave the double range (relative error ~ |log| DBL_EPSILON). */
static void wave_log(double a, double U, double rho_g, double rho_l,
                     const sb_spray_liquid *liq, double *lL, double *lO)
{
  double la = log(a), ls = log(liq->sigma), lrl = log(rho_l);
  double lWe = log(rho_g) + 2.0 * log(U) + la - ls;
  double lZ = log(liq->mu_l) - 0.5 * (lrl + la + ls);
  double lT = lZ + 0.5 * lWe;
  *lL = la + log(9.02) + log1p_pow(0.45, lZ, 0.5) +
        log1p_pow(0.4, lT, 0.7) - 0.6 * log1p_pow(0.87, lWe, 1.67);
  *lO = log(0.34) + log1p_pow(0.38 / 0.34, lWe, 1.5) -
        log1p_pow(1.0, lZ, 1.0) - log1p_pow(1.4, lT, 0.6) +
        0.5 * (ls - lrl) - 1.5 * la;
}

static int wave_check(double a, double U, double rho_g, double rho_l,
                      const sb_spray_liquid *liq, const char *func)
{
  if (!liq)
    return sbi_error(SB_EDOM, func, "NULL liquid");
  if (!(a > 0) || !(U >= 0) || !(rho_g > 0) || !(rho_l > 0) ||
      !(liq->sigma > 0) || !(liq->mu_l >= 0) || !isfinite(a) ||
      !isfinite(U) || !isfinite(rho_g) || !isfinite(rho_l) ||
      !isfinite(liq->sigma) || !isfinite(liq->mu_l))
    return sbi_error(SB_EDOM, func, "need finite a, rho_g, rho_l, sigma > "
                     "0, U, mu_l >= 0 (a = %g, U = %g)", a, U);
  return SB_SUCCESS;
}

/* Is a plain value in the normal double range? */
static int normal_pos(double x)
{
  return x >= DBL_MIN && x <= DBL_MAX;
}

int sb_spray_reitz_wave(double a, double U, double rho_g, double rho_l,
                        const sb_spray_liquid *liq, double *Lambda,
                        double *Omega)
{
  int st = wave_check(a, U, rho_g, rho_l, liq, __func__);
  if (st)
    return st;
  if (!Lambda || !Omega)
    return sbi_error(SB_EDOM, __func__, "NULL argument");
  double L, O;
  wave(a, U, rho_g, rho_l, liq, &L, &O);
  if (!normal_pos(L) || !normal_pos(O)) {
    /* an intermediate (We, a^3, a power) over/underflowed */
    double lL, lO;
    wave_log(a, U, rho_g, rho_l, liq, &lL, &lO);
    L = exp(lL);
    O = exp(lO);
    if (!normal_pos(L) || !normal_pos(O))
      return sbi_error(SB_ERANGE, __func__, "Lambda = exp(%g), Omega = "
                       "exp(%g) outside the normal double range", lL, lO);
  }
  *Lambda = L;
  *Omega = O;
  return SB_SUCCESS;
}

/* w + ln w = L for w > 0 (Lambert W0 of e^L) when e^L overflows. */
static double w_of_log(double L)
{
  if (L < 700.0)
    return gsl_sf_lambert_W0(exp(L));
  double w = L - log(L);
  for (int k = 0; k < 50; k++) {
    double f = w + log(w) - L, d = f / (1.0 + 1.0 / w);
    w -= d;
    if (fabs(d) <= 4 * DBL_EPSILON * w)
      break;
  }
  return w;
}

/* With x = (a - R)/R: x + ln x = x0 + ln x0 - c t/R. */
double sb_spray_reitz_radius_frozen(double a0, double R, double c, double t)
{
  if (!(a0 > 0) || !(R > 0) || !(c > 0) || !(t >= 0) || !isfinite(a0) ||
      !isfinite(R) || !isfinite(c)) {
    sbi_error(SB_EDOM, __func__, "need a0, R, c > 0 and t >= 0 (a0 = %g, "
              "R = %g, c = %g, t = %g)", a0, R, c, t);
    return NAN;
  }
  if (a0 <= R)
    return a0;
  if (t == 0)
    return a0;
  double x0 = (a0 - R) / R;
  double L = log(x0) + x0 - c * t / R;
  double x = L < -700.0 ? exp(L) : w_of_log(L);
  double a = R * (1.0 + x);
  return a < a0 ? a : a0;
}

/* ------------------------------------------------ full model at constant U */

/* The quadrature uses the plain fits (lg = 0) unless they leave the
 * normal range at a0 or near the stable radius; then (lg = 1) the fits
 * through logarithms, the variable u = x 2^-ex (a0 2^-ex in [1, 2): the
 * interval's width stays finite) and the integrand scaled by 2^-sc (the
 * time by the same power of two) so that CQUAD sees values of order
 * one. */
typedef struct {
  double U, rho_g, rho_l;
  const sb_spray_liquid *liq;
  const sb_spray_reitz_params *rp;
  double target;
  double a0;
  int lg, sc, ex;
} full_ctx;

/* log of tau(x) = 3.726 B1 x/(Lambda Omega) and R(x) = B0 Lambda(x) in
 * the log mode */
static double log_tau_R(const full_ctx *c, double x, double *R)
{
  double lL, lO;
  wave_log(x, c->U, c->rho_g, c->rho_l, c->liq, &lL, &lO);
  *R = c->rp->B0 * exp(lL);
  return log(3.726 * c->rp->B1) + log(x) - lL - lO;
}

static double rate_gap(double x, void *p) /* x - R(x) */
{
  const full_ctx *c = p;
  double L, O;
  if (c->lg) {
    double R;
    log_tau_R(c, x, &R);
    return x - R;
  }
  wave(x, c->U, c->rho_g, c->rho_l, c->liq, &L, &O);
  return x - c->rp->B0 * L;
}

static double integrand(double x, void *p) /* tau(x)/(x - R(x)) */
{
  const full_ctx *c = p;
  double L, O;
  if (c->lg) { /* x is u: tau(x)/(x - R) dx/du 2^-sc */
    x = ldexp(x, c->ex);
    double R, lt = log_tau_R(c, x, &R);
    return exp(lt + (c->ex - c->sc) * M_LN2 - log(x - R));
  }
  wave(x, c->U, c->rho_g, c->rho_l, c->liq, &L, &O);
  double tau = 3.726 * c->rp->B1 * x / (L * O);
  return tau / (x - c->rp->B0 * L);
}

static double time_to(double a, void *p) /* t(a) - target */
{
  full_ctx *c = p;
  const double target = ldexp(c->target, -c->sc);
  if (a >= c->a0)
    return -target;
  gsl_function F = {integrand, c};
  double res, err;
  /* The root a needs t(a) only to 1e-13 a |dt/da|: near a_inf, x - R(x)
   * cancels and the integrand carries a relative rounding ~eps a/(a -
   * a_inf), which puts a relative 1e-12 on t(a) out of reach (CQUAD then
   * fills its 1000 intervals: ~600 000 evaluations, 0.2 s per call), while
   * that rounding moves the root by only ~eps a (da/dt -> 0 there). */
  const double u = ldexp(a, -c->ex), dtda = fabs(integrand(u, c));
  const double epsabs = isfinite(dtda) ? 1e-13 * u * dtda : 0.0;
  int st = sbi_integrate(&F, u, ldexp(c->a0, -c->ex), epsabs, 1e-12, 1000,
                         &res, &err);
  /* Brent needs the sign: the estimate is kept (as it was with QAGS)
   * when CQUAD's error estimate is above the 1e-12 asked for */
  return (st && st != SB_EMAXITER) ? NAN : res - target;
}

/* Root in [lo, hi] to rtol (relative); NaN if Brent fails. */
static double brent(gsl_function *F, double lo, double hi, double rtol)
{
  double x;
  return sbi_brent(F, lo, hi, 0.0, rtol, 300, &x) ? NAN : x;
}

/* Are the plain fits at x in the normal range (as the quadrature needs
 * them)? */
static int plain_fits_ok(const full_ctx *c, double x)
{
  double L, O;
  wave(x, c->U, c->rho_g, c->rho_l, c->liq, &L, &O);
  return normal_pos(L) && normal_pos(O) && normal_pos(L * O);
}

/* Stable radius a_inf: x - B0 Lambda(x) changes sign below a0 (Lambda/x
 * grows without bound as x -> 0 through the Ohnesorge number); 0 if no
 * sign change is found within `halvings` halvings of a0 (or above
 * DBL_MIN). */
static double stable_radius(full_ctx *c, int halvings)
{
  double lo = c->a0;
  for (int k = 0; k < halvings && 0.5 * lo >= DBL_MIN && rate_gap(lo, c) > 0;
       k++)
    lo *= 0.5;
  gsl_function G = {rate_gap, c};
  return rate_gap(lo, c) > 0 ? 0.0 : brent(&G, lo, c->a0, 1e-15);
}

int sb_spray_reitz_radius(double a0, double t, double U, double rho_g,
                          double rho_l, const sb_spray_liquid *liq,
                          const sb_spray_reitz_params *rp, double *a)
{
  if (!rp || !a)
    return sbi_error(SB_EDOM, __func__, "NULL argument");
  int st = wave_check(a0, U, rho_g, rho_l, liq, __func__);
  if (st)
    return st;
  if (!(t >= 0) || !(rp->B0 > 0) || !(rp->B1 > 0))
    return sbi_error(SB_EDOM, __func__, "need t >= 0, B0, B1 > 0");
  full_ctx c = {U, rho_g, rho_l, liq, rp, t, a0, 0, 0, 0};
  c.lg = !plain_fits_ok(&c, a0);
  if (rate_gap(a0, &c) <= 0 || t == 0) {
    *a = a0;
    return SB_SUCCESS;
  }
  double ainf = stable_radius(&c, 60);
  double hi = a0, low = ainf + (a0 - ainf) * 1e-14;
  if (!c.lg && !plain_fits_ok(&c, low)) {
    /* the plain fits leave the range on the way to a_inf */
    c.lg = 1;
    ainf = stable_radius(&c, 60);
    low = ainf + (a0 - ainf) * 1e-14;
  }
  if (c.lg) {
    /* halve down to the smallest normal radii (a_inf may be many orders
     * below a0, or below DBL_MIN: then 0); bracket within 1e-12 of
     * a_inf; scale by the integrand at a0 */
    ainf = stable_radius(&c, 2200);
    low = ainf > 0 ? fmin(ainf * (1.0 + 0x1p-40), ainf + (a0 - ainf) * 1e-14)
                   : DBL_MIN;
    double R, lt = log_tau_R(&c, a0, &R);
    c.ex = ilogb(a0);
    c.sc = (int)floor((lt - log(a0 - R)) / M_LN2) + c.ex;
  }
  /* t(a) decreases from +inf at a_inf to 0 at a0 */
  gsl_function F = {time_to, &c};
  double fl = time_to(low, &c);
  if (fl <= 0 && c.lg && ainf == 0)
    return sbi_error(SB_ERANGE, __func__, "a(t) < DBL_MIN: the radius "
                     "relaxes below the normal double range (a0 = %g, "
                     "U = %g)", a0, U);
  if (fl <= 0)
    *a = low; /* closer to a_inf than the bracket can resolve */
  else
    *a = brent(&F, low, hi, 1e-13);
  return isnan(*a) ? sbi_error(SB_ESOLVER, __func__, "root finding failed")
                   : SB_SUCCESS;
}

/* ------------------------------------------------------------ stepping */

int sb_spray_reitz_step(sb_spray *s, const sb_spray_gas *gas,
                        const sb_spray_liquid *liq,
                        const sb_spray_reitz_params *rp, double dt)
{
  if (!s || !gas || !liq || !rp)
    return sbi_error(SB_EINVAL, __func__, "NULL argument");
  if (!(dt > 0) || !isfinite(dt))
    return sbi_error(SB_EINVAL, __func__, "dt = %g: must be finite > 0", dt);
  if (!(gas->rho_g > 0) || !(liq->sigma > 0) || !(liq->mu_l >= 0) ||
      !(rp->B0 > 0) || !(rp->B1 > 0) || !(rp->emit_fraction >= 0) ||
      (rp->stripping && !(gas->mu_g > 0)))
    return sbi_error(SB_EINVAL, __func__, "need rho_g, sigma, B0, B1 > 0, "
                     "mu_l, emit_fraction >= 0 (and mu_g > 0 for the "
                     "stripping test)");
  sb_spray_children mode = rp->children;
  if (mode == SB_SPRAY_CHILDREN_AUTO)
    mode = s->p.method == SB_SPRAY_BIRD ? SB_SPRAY_CHILDREN_PARTICLES
                                        : SB_SPRAY_CHILDREN_PARCEL;
  if (mode == SB_SPRAY_CHILDREN_PARCEL && s->p.method == SB_SPRAY_BIRD)
    return sbi_error(SB_EINVAL, __func__, "children = parcel changes "
                     "weights: not with the Bird method");
  if (rp->blob && mode != SB_SPRAY_CHILDREN_PARCEL)
    return sbi_error(SB_EINVAL, __func__, "blob = 1 changes the parcel's "
                     "weight: parcel children (Nanbu method) only");
  const double c43 = (4.0 / 3.0) * SBI_PI, rho_l = s->p.rho_l;
  size_t n0 = s->n;
  for (size_t i = 0; i < n0; i++) {
    double *v = s->v + 3 * i, U2 = 0;
    for (int k = 0; k < 3; k++) {
      double d = gas->u[k] - v[k];
      U2 += d * d;
    }
    double U = sqrt(U2), a = s->r[i], L, O;
    wave(a, U, gas->rho_g, rho_l, liq, &L, &O);
    double R = rp->B0 * L;
    int breaks = U > 0;
    if (breaks && rp->stripping) {
      double We = gas->rho_g * U2 * a / liq->sigma;
      double Re = gas->rho_g * U * a / gas->mu_g;
      breaks = We > 0.5 * sqrt(Re);
    }
    int active = breaks && a > R;
    if (breaks && !active && rp->blob && !s->formed[i]) {
      /* second branch (B0 Lambda >= a): the drops form once at the
       * blob radius; the parcel keeps its liquid volume */
      double rn = sb_spray_reitz_blob_radius(a, U, L, O), q = a / rn;
      s->w[i] *= q * q * q;
      s->r[i] = rn;
      s->formed[i] = 1;
      s->st.reitz_blobs++;
      continue;
    }
    if (active) {
      double c = L * O / (3.726 * rp->B1);
      double an = sb_spray_reitz_radius_frozen(a, R, c, dt);
      s->shed[i] += s->w[i] * c43 * (a * a * a - an * an * an);
      s->r[i] = an;
    }
    if (!(s->shed[i] > 0))
      continue;
    double vc = c43 * R * R * R; /* one child's volume */
    int tag = rp->child_tag >= 0 ? rp->child_tag : s->tag[i];
    double vel[3];
    memcpy(vel, s->v + 3 * i, sizeof vel);
    if (mode == SB_SPRAY_CHILDREN_PARTICLES) {
      double unit = s->w[i] * vc;
      double k = floor(s->shed[i] / unit);
      if (k < 1)
        continue;
      int st = sbi_spray_reserve(s, (size_t)k, __func__);
      if (st)
        return st;
      for (double q = 0; q < k; q++)
        s->formed[sbi_spray_push(s, vel, R, s->w[i], tag)] = 1;
      s->shed[i] -= k * unit;
      s->st.reitz_children += (unsigned long long)k;
    } else if (s->shed[i] >= rp->emit_fraction * s->w[i] * c43 *
                                 s->r[i] * s->r[i] * s->r[i]) {
      int st = sbi_spray_reserve(s, 1, __func__);
      if (st)
        return st;
      double wc = s->shed[i] / vc;
      s->shed[i] = 0.0;
      s->formed[sbi_spray_push(s, vel, R, wc, tag)] = 1;
      s->st.reitz_children++;
    }
  }
  return SB_SUCCESS;
}
