/* simulate.c — reference simulators (brute-force Monte Carlo of the
 * processes).  What is exact and why: smolbridge/simulate.h and
 * docs/simulate.md.
 *
 * The per-sub-step crossing probabilities below are written out here on
 * purpose, independently of lib/bridge/bridge.c: the simulators exist to check
 * sb_bb_cross_prob / sb_bes3b_cross_prob and the hitting-time laws, so
 * they must not call them. */
#include <float.h>
#include <limits.h>
#include <math.h>
#include <stddef.h>
#include <stdlib.h>

#include <gsl/gsl_math.h>
#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>

#include <smolbridge/langevin.h>
#include <smolbridge/simulate.h>
#include "common/internal.h"

/* ------------------------------------------ per-sub-step crossing laws */

/* 1-D Brownian bridge from x0 > a to x1 > a with variance v over the
 * sub-step: P(min <= a) = exp(-2 (x0 - a)(x1 - a)/v) (reflection
 * principle: the density of paths ending at x1 that touch a equals that
 * of paths ending at the mirror image 2a - x1). */
static double step_bb(double x0, double x1, double a, double v)
{
  return exp(-2.0 * (x0 - a) * (x1 - a) / v);
}

/* Bessel-3 bridge from r0 > a to r1 > a, variance v per component:
 * P(min <= a) = q^a_v(r0, r1)/q_v(r0, r1) complemented, with the Bessel-3
 * transition density q_v(x, y) = (y/x)[g_v(y - x) - g_v(y + x)] and its
 * version killed at a, (y/x)[g_v(y - x) - g_v(x + y - 2a)] (the Bessel-3
 * process is BM on (0, inf) h-transformed by h(x) = x).  The ratio
 * [g(x+y-2a) - g(x+y)] / [g(y-x) - g(y+x)] is written with all exponents
 * <= 0 so that it cannot overflow:
 *   exp(-2 (r0-a)(r1-a)/v) expm1(-2a(r0+r1-a)/v) / expm1(-2 r0 r1/v).
 * Level a = 0 is never reached. */
static double step_bes3b(double r0, double r1, double a, double v)
{
  if (a <= 0.0)
    return 0.0;
  const double den = expm1(-2.0 * r0 * r1 / v);
  if (den > -0x1p-1000) { /* 2 r0 r1/v below 2^-1000 (or 0 by underflow,
                           * 0/0 before): the ratio of the expm1 is that
                           * of their arguments, and the exp factor 1 */
    const double rl = r0 < r1 ? r0 : r1, rh = r0 < r1 ? r1 : r0;
    return (a / rl) * ((rl + rh - a) / rh);
  }
  return exp(-2.0 * (r0 - a) * (r1 - a) / v) *
         expm1(-2.0 * a * (r0 + r1 - a) / v) / den;
}

/* |X|: sqrt of the sum of squares (the bits as written) where that lies
 * in 2^(+-500); beyond, the components are scaled by a power of two first
 * (the squares over- or underflowed: positions ~ 1e300 gave +inf, ~
 * 1e-300 gave 0) */
static double norm3(const double *X)
{
  const double r = sqrt(X[0] * X[0] + X[1] * X[1] + X[2] * X[2]);
  if (r >= 0x1p-500 && r <= 0x1p500)
    return r;
  double mx = fmax(fabs(X[0]), fmax(fabs(X[1]), fabs(X[2])));
  if (mx == 0.0 || !isfinite(mx))
    return mx;
  const int e = ilogb(mx);
  double s = 0.0;
  for (int j = 0; j < 3; j++) {
    const double c = ldexp(X[j], -e);
    s += c * c;
  }
  return ldexp(sqrt(s), e);
}

/* ------------------------------------------------------ path kernels */

/* The kernels assume validated arguments. */

static int path_bb(const gsl_rng *r, double x, double y, double a,
                   double s2, double t, int n)
{
  if (x <= a)
    return 0;
  const double dt = t / n;
  double X = x;
  for (int k = 0; k < n; k++) {
    double Xn;
    if (k == n - 1) {
      Xn = y;
    } else {
      /* exact sequential bridge sampling: given X_k with T left */
      double T = t - k * dt;
      const double sd = sqrt(s2 * dt * (T - dt) / T);
      const double z = gsl_ran_gaussian_ziggurat(r, 1.0);
      Xn = X + (y - X) * dt / T + sd * z;
      if (!isfinite(Xn)) /* (y - X) dt overflowed (t ~ 1e300) */
        Xn = X + (y - X) * (dt / T) + sd * z;
    }
    if (Xn <= a || gsl_rng_uniform(r) < step_bb(X, Xn, a, s2 * dt))
      return k;
    X = Xn;
  }
  return -1;
}

static int path_bes3b(const gsl_rng *r, double x, double y, double a,
                      double s2, double t, int n)
{
  if (x <= a)
    return 0;
  const double dt = t / n;
  /* End point on the sphere of radius y: density prop. to the Gaussian
   * kernel exp(-|y w - B_0|^2/(2 s2 t)) prop. to exp(kappa c), c the cosine
   * of the angle to B_0.  The area element of S^2 is uniform in c, so c
   * has density prop. to exp(kappa c) on [-1, 1]; inversion:
   * c = 1 + log1p((1 - U) expm1(-2 kappa))/kappa (stable for all kappa > 0;
   * kappa = 0, i.e. y = 0 or x = 0, is the uniform law). */
  const double kappa = x * y / (s2 * t);
  double U = gsl_rng_uniform(r);
  double c = kappa > 0.0
                 ? 1.0 + log1p((1.0 - U) * expm1(-2.0 * kappa)) / kappa
                 : 2.0 * U - 1.0;
  c = c > 1.0 ? 1.0 : (c < -1.0 ? -1.0 : c);
  double sn = sqrt(fmax(0.0, 1.0 - c * c));
  double phi = 2.0 * M_PI * gsl_rng_uniform(r);
  const double Y[3] = {y * c, y * sn * cos(phi), y * sn * sin(phi)};
  double X[3] = {x, 0.0, 0.0};
  double R = x;
  for (int k = 0; k < n; k++) {
    double Rn;
    if (k == n - 1) {
      Rn = y;
    } else {
      /* three independent 1-D bridges towards Y */
      double T = t - k * dt;
      double sd = sqrt(s2 * dt * (T - dt) / T);
      for (int j = 0; j < 3; j++) {
        const double z = gsl_ran_gaussian_ziggurat(r, 1.0);
        const double Xj = X[j] + ((Y[j] - X[j]) * dt / T + sd * z);
        /* (Y - X) dt overflowed (t ~ 1e300): the same with dt/T first */
        X[j] = isfinite(Xj) ? Xj
                            : X[j] + ((Y[j] - X[j]) * (dt / T) + sd * z);
      }
      Rn = norm3(X);
    }
    /* Given the norms at the grid times, the pieces of R between them are
     * independent Bessel-3 bridges (R is Markov; conditioning on R_t is an
     * h-transform), so this Bernoulli reproduces P(hit) exactly. */
    if (Rn <= a || gsl_rng_uniform(r) < step_bes3b(R, Rn, a, s2 * dt))
      return k;
    R = Rn;
  }
  return -1;
}

static int path_bes3(const gsl_rng *r, double x, double a, double s2,
                     double t, int n)
{
  if (x <= a)
    return 0;
  const double dt = t / n, sd = sqrt(s2 * dt);
  double X[3] = {x, 0.0, 0.0}, R = x;
  for (int k = 0; k < n; k++) {
    for (int j = 0; j < 3; j++)
      X[j] += sd * gsl_ran_gaussian_ziggurat(r, 1.0);
    double Rn = norm3(X);
    /* same Markov argument: sub-step pieces are Bessel-3 bridges */
    if (Rn <= a || gsl_rng_uniform(r) < step_bes3b(R, Rn, a, s2 * dt))
      return k;
    R = Rn;
  }
  return -1;
}

/* ---------------------------------------------------------- validation */

enum { K_BB, K_BES3B, K_BES3 };

/* y is ignored for K_BES3 (pass 0). */
static int check_args(const char *fn, int kind, const gsl_rng *r, double x,
                      double y, double a, double s2, double t, int n,
                      const void *out)
{
  if (!r || !out)
    return sbi_error(SB_EINVAL, fn, "NULL argument");
  if (n < 1)
    return sbi_error(SB_EINVAL, fn, "n = %d < 1", n);
  if (!isfinite(x) || !isfinite(y) || !isfinite(a))
    return sbi_error(SB_EDOM, fn, "x = %g, y = %g, a = %g: not finite", x,
                     y, a);
  if (!(s2 > 0.0) || !isfinite(s2))
    return sbi_error(SB_EDOM, fn, "sigma2 = %g: need 0 < sigma2 < inf", s2);
  if (!(t > 0.0) || !isfinite(t))
    return sbi_error(SB_EDOM, fn, "t = %g: need 0 < t < inf", t);
  if (kind != K_BB && (a < 0.0 || x < 0.0 || y < 0.0))
    return sbi_error(SB_EDOM, fn, "x = %g, y = %g, a = %g: Bessel-3 radii "
                     "must be >= 0", x, y, a);
  return SB_SUCCESS;
}

/* The law of the first-crossing sub-step is unchanged when t is scaled by
 * 2^-e and sigma2 by 2^e (sigma2 t is kept).  The kernels form sigma2 dt
 * (T - dt) ~ sigma2 t^2: outside 2^(+-600) (t = 1e300 with sigma2 = 1:
 * +inf, then NaN positions that never cross) t is scaled (exactly) into
 * [1, 2) if sigma2 2^e stays a normal double; elsewhere nothing changes
 * (same draws, same bits).  The positions are left as they are here;
 * sigma2 t itself beyond the normal doubles is fit_scales' (below), which
 * runs first. */
static void rescale(double *s2, double *t)
{
  if (*s2 == 0.0) /* fit_scales underflowed it (a far-off bridge) */
    return;
  const int et = ilogb(*t), ev = ilogb(*s2) + et;
  if (abs(ev + et) < 600)
    return;
  const double s2n = ldexp(*s2, et);
  if (!(s2n >= DBL_MIN && s2n <= DBL_MAX))
    return;
  *s2 = s2n;
  *t = ldexp(*t, -et);
}

/* floor(v/2) and ceil(v/2) for any int v */
static int floor2(int v) { return v >= 0 ? v / 2 : -((1 - v) / 2); }
static int ceil2(int v) { return -floor2(-v); }

/* Positions and sigma2 t far from the normal doubles.  The law of the
 * first-crossing sub-step is also unchanged when the positions are scaled
 * by 2^-m and sigma2 by 2^-2m (Brownian scaling).  The kernels are at risk
 *  - where sigma2 t exceeds 2^998 (the sub-step variance, the Brownian
 *    bridge's (X - a)(X' - a) and the sums overflow at positions on the
 *    scale of its root);
 *  - where sigma2 t is below 2^-900 (the variance underflows, 0/0 in the
 *    sub-step probability) with the positions (Brownian bridge: x - a and
 *    y - a) all within 2^400 of its root;
 *  - Brownian bridge: where x - a, y - a or y - x overflows.
 * Farther from the root the kernels give the certain outcome through
 * exp(-inf) = 0 (|a| = 1e300 with sigma2 t = 1e-320; a path leaving for y
 * far away), and elsewhere nothing changes (same draws, same bits; the
 * Bessel-3 norms and small ratios are handled by norm3 and step_bes3b).
 * At risk, m is the one nearest 0 with
 *  - sigma2 t 2^-2m < 2^1000, and >= 2^-898 where the variance was at risk
 *    of underflowing;
 *  - |x|, |y|, |a| 2^-m <= 2^1020 (x - a and the norms cannot overflow);
 *  - Bessel-3: the nonzero positions stay normal doubles (their ratios set
 *    the law);
 * and t is scaled into [1, 2) as by rescale().  Where no m meets them (the
 * positions and the root of sigma2 t more than the doubles apart),
 * SB_ERANGE.  Inputs: validated, y = 0 for K_BES3. */
static int fit_scales(const char *fn, int kind, double *x, double *y,
                      double *a, double *s2, double *t)
{
  if (*x <= *a || (kind != K_BB && *a == 0.0)) /* sub-step 0, no draws;
                                                 * Bessel-3 never at 0 */
    return SB_SUCCESS;
  const int q = ilogb(*s2) + ilogb(*t); /* log2(sigma2 t) in [q, q + 2) */
  const int half = floor2(q);           /* log2 of its root, about */
  const double p[3] = {*x, *y, *a};
  int hi = INT_MIN, lo = INT_MAX;
  for (int i = 0; i < 3; i++)
    if (p[i] != 0.0) {
      const int e = ilogb(p[i]);
      hi = e > hi ? e : hi;
      lo = e < lo ? e : lo;
    }
  int mmin = ceil2(q - 998), mmax = INT_MAX;
  int risk = q > 998, low = 0;
  if (kind == K_BB) {
    const double d0 = fabs(*x - *a), d1 = fabs(*y - *a);
    if (!isfinite(d0) || !isfinite(d1) || !isfinite(*y - *x))
      risk = 1;
    low = q < -900 && d0 > 0.0 && d1 > 0.0 && ilogb(fmax(d0, d1)) <
                                                   half + 400;
    if (hi - 1020 > mmin)
      mmin = hi - 1020;
  } else if (hi != INT_MIN) {
    low = q < -900 && hi < half + 400;
    if (hi - 1020 > mmin)
      mmin = hi - 1020;
    mmax = lo + 1022; /* the positions stay normal doubles */
  }
  if (low) {
    risk = 1;
    if (floor2(q + 898) < mmax)
      mmax = floor2(q + 898);
  }
  /* Bessel-3, wherever it scales: sigma2 t 2^-2m >= 2^-898 too (the end
   * point's kappa and the norms need a variance that is not 0) */
  if (kind != K_BB && risk && floor2(q + 898) < mmax)
    mmax = floor2(q + 898);
  if (!risk)
    return SB_SUCCESS;
  if (mmin > mmax)
    return sbi_error(SB_ERANGE, fn, "x = %g, y = %g, a = %g, sigma2 = %g, "
                     "t = %g: the positions and sqrt(sigma2 t) span more "
                     "than the doubles", *x, *y, *a, *s2, *t);
  const int m = mmin > 0 ? mmin : (mmax < 0 ? mmax : 0);
  const int et = ilogb(*t);
  *x = ldexp(*x, -m);
  *y = ldexp(*y, -m);
  *a = ldexp(*a, -m);
  *s2 = ldexp(*s2, et - 2 * m); /* sigma2 t 2^-2m / t' */
  *t = ldexp(*t, -et);          /* t' in [1, 2) */
  return SB_SUCCESS;
}

static int run_path(const char *fn, int kind, const gsl_rng *r, double x,
                    double y, double a, double s2, double t, int n, int *k)
{
  int st = check_args(fn, kind, r, x, y, a, s2, t, n, k);
  if (st != SB_SUCCESS)
    return st;
  st = fit_scales(fn, kind, &x, &y, &a, &s2, &t);
  if (st != SB_SUCCESS)
    return st;
  rescale(&s2, &t);
  *k = kind == K_BB      ? path_bb(r, x, y, a, s2, t, n)
       : kind == K_BES3B ? path_bes3b(r, x, y, a, s2, t, n)
                         : path_bes3(r, x, a, s2, t, n);
  return SB_SUCCESS;
}

static int run_hits(const char *fn, int kind, const gsl_rng *r, double x,
                    double y, double a, double s2, double t, int n,
                    unsigned long npaths, unsigned long *hits,
                    unsigned long *ncross)
{
  int st = check_args(fn, kind, r, x, y, a, s2, t, n, hits);
  if (st != SB_SUCCESS)
    return st;
  if (!ncross)
    return sbi_error(SB_EINVAL, fn, "NULL argument");
  st = fit_scales(fn, kind, &x, &y, &a, &s2, &t);
  if (st != SB_SUCCESS)
    return st;
  rescale(&s2, &t);
  for (int k = 0; k < n; k++)
    hits[k] = 0;
  unsigned long nh = 0;
  for (unsigned long i = 0; i < npaths; i++) {
    int k = kind == K_BB      ? path_bb(r, x, y, a, s2, t, n)
            : kind == K_BES3B ? path_bes3b(r, x, y, a, s2, t, n)
                              : path_bes3(r, x, a, s2, t, n);
    if (k >= 0) {
      hits[k]++;
      nh++;
    }
  }
  *ncross = nh;
  return SB_SUCCESS;
}

/* ---------------------------------------------------------- public API */

int sb_sim_bb_path(const gsl_rng *r, double x, double y, double a,
                   double sigma2, double t, int n, int *k)
{
  return run_path(__func__, K_BB, r, x, y, a, sigma2, t, n, k);
}

int sb_sim_bes3b_path(const gsl_rng *r, double x, double y, double a,
                      double sigma2, double t, int n, int *k)
{
  return run_path(__func__, K_BES3B, r, x, y, a, sigma2, t, n, k);
}

int sb_sim_bes3_path(const gsl_rng *r, double x, double a, double sigma2,
                     double t, int n, int *k)
{
  return run_path(__func__, K_BES3, r, x, 0.0, a, sigma2, t, n, k);
}

int sb_sim_bb_hits(const gsl_rng *r, double x, double y, double a,
                   double sigma2, double t, int n, unsigned long npaths,
                   unsigned long *hits, unsigned long *ncross)
{
  return run_hits(__func__, K_BB, r, x, y, a, sigma2, t, n, npaths, hits,
                  ncross);
}

int sb_sim_bes3b_hits(const gsl_rng *r, double x, double y, double a,
                      double sigma2, double t, int n, unsigned long npaths,
                      unsigned long *hits, unsigned long *ncross)
{
  return run_hits(__func__, K_BES3B, r, x, y, a, sigma2, t, n, npaths, hits,
                  ncross);
}

int sb_sim_bes3_hits(const gsl_rng *r, double x, double a, double sigma2,
                     double t, int n, unsigned long npaths,
                     unsigned long *hits, unsigned long *ncross)
{
  return run_hits(__func__, K_BES3, r, x, 0.0, a, sigma2, t, n, npaths,
                  hits, ncross);
}

int sb_sim_langevin(const sb_langevin *p, double dt, long nsteps,
                    const gsl_rng *r, size_t np, double *x, double *u)
{
  if (!p || !r || (np > 0 && (!x || !u)))
    return sbi_error(SB_EINVAL, __func__, "NULL argument");
  if (nsteps < 0)
    return sbi_error(SB_EINVAL, __func__, "nsteps = %ld < 0", nsteps);
  if (!isfinite(p->us))
    return sbi_error(SB_EDOM, __func__, "us = %g: not finite", p->us);
  sb_langevin_coef c;
  int st = sb_langevin_coef_init(&c, p->tau, p->B, dt);
  if (st != SB_SUCCESS) /* named here (its message names coef_init) */
    return sbi_error(st, __func__, "tau = %g, B = %g, dt = %g: %s", p->tau,
                     p->B, dt, st == SB_ERANGE
                                   ? "a step coefficient exceeds DBL_MAX"
                                   : "need tau > 0, B >= 0, dt >= 0, "
                                     "all finite");
  /* one coefficient set for all, particle by particle: the draws and the
   * update of one sb_langevin_step3_coef call over all particles (the same
   * bits), but checked: with B sqrt(tau) or the state near DBL_MAX a new
   * x or u can exceed DBL_MAX (B = DBL_MAX, tau = dt = 1 gave +-inf with
   * status 0); an intermediate that overflows alone is recomputed scaled
   * (sb_langevin_update) */
  for (size_t i = 0; i < 3 * np; i++)
    if (!isfinite(x[i]) || !isfinite(u[i]))
      return sbi_error(SB_EDOM, __func__, "x[%zu] = %g, u[%zu] = %g: not "
                       "finite", i, x[i], i, u[i]);
  const double w = p->us != 0.0 ? p->us : 0.0; /* -0: the bits of us NULL */
  for (long k = 0; k < nsteps; k++)
    for (size_t i = 0; i < np; i++) {
      double z[6], xi[3], ui[3];
      for (int j = 0; j < 6; j++)
        z[j] = gsl_ran_gaussian_ziggurat(r, 1.0);
      for (int j = 0; j < 3; j++) {
        xi[j] = x[3 * i + j];
        ui[j] = u[3 * i + j];
        if (sb_langevin_update(&c, w, z[2 * j], z[2 * j + 1], &xi[j],
                               &ui[j]))
          return sbi_error(SB_ERANGE, __func__,
                           "step %ld, particle %zu: the new state (from x "
                           "= %g, u = %g) exceeds DBL_MAX (tau = %g, B = "
                           "%g, dt = %g)", k, i, x[3 * i + j],
                           u[3 * i + j], p->tau, p->B, dt);
      }
      for (int j = 0; j < 3; j++) {
        x[3 * i + j] = xi[j];
        u[3 * i + j] = ui[j];
      }
    }
  return SB_SUCCESS;
}
