/* langevin_reach.c — neighbour reach for the Langevin pair sampler: the
 * expected number of contacts missed by examining only the pairs whose
 * straight chords come within R + rho (derivation in
 * <smolbridge/langevin_hit.h>).
 *
 * Deviation from the chord.  For one particle at equilibrium (velocity a
 * stationary OU process of variance sigma^2 = B^2 tau/2 per component,
 * autocorrelation sigma^2 exp(-|s|/tau)), the displacement D(t) = x(t) -
 * x(0) has (Ornstein 1919; Uhlenbeck & Ornstein 1930)
 *   Var D(t)        = 2 sigma^2 tau^2 g(t/tau),  g(x) = x - 1 + e^{-x},
 *   Cov(D(t), u(t)) = sigma^2 tau (1 - e^{-t/tau}),
 *   Cov(u(t), D(T)) = sigma^2 tau (2 - e^{-t/tau} - e^{-(T-t)/tau}),
 *   Cov(D(t), D(T)) = [Var D(t) + Var D(T) - Var D(T-t)]/2,
 * so Z(t) = D(t) - (t/T) D(T) and Z'(t) = u(t) - D(T)/T have closed-form
 * variances and covariance; the two particles are independent, so the
 * pair's moments are sums.  g(x) = x^2 exprel_2(-x)/2 (no cancellation);
 * Var Z still cancels like T/tau for T << tau (digits lost ~ log10(tau/T),
 * harmless down to T/tau ~ 1e-10 for a reach).
 *
 * Huge B.  The moments scale like B^2 and every length like B, so they
 * are computed in the length unit 2^k, k = ilogb(max B) where max B >
 * 2^64 (the B's and R are divided by 2^k, exactly; lengths are read back
 * with ldexp).  Otherwise B^2 tau overflows at B ~ 1e155 (the clamps then
 * turn inf - inf into "no deviation", a bound of 0), c^2 in upcross at
 * B ~ 1e100, and the integrand, of order sc^2, passes 1e154, beyond which
 * GSL's CQUAD (it squares the values for its norms) never converges:
 * minutes per call.  Where the unit is scaled, n sc^dim > e^50 or a
 * length (sc, R, L) passes 1e50, the bound is evaluated in logarithms
 * ("scaled"): the shell is in units of h = max(sc, R), the factor
 * P(z0) = min(1, U(z0)) (z0 = rho/sc) is taken out of the integrand, so
 * that it stays of order one, and the tail is cut where a node's term is
 * below e^{-722} of that factor, not at 38 sd: a reach where n sc^dim >>
 * 1e300 needs probabilities far below DBL_MIN.  Elsewhere the evaluation
 * is the plain one (h = 1, no factor, cut at 38 sd), bit for bit.
 */
#include <math.h>

#include <gsl/gsl_integration.h>
#include <gsl/gsl_sf_exp.h>

#include "common/internal.h"
#include "common/numutil.h"
#include "langevin_hit_internal.h"

#define NZ 64
#define PI 3.14159265358979323846
#define INV_SQRT_2PI 0.39894228040143267794
#define INV_SQRT_2 0.70710678118654752440

typedef struct {
  int dim;
  double n, R, T, L;
  double sc;                    /* length unit of the integral: max sd */
  double w[NZ];                 /* weights on [0, 1] */
  double s2[NZ], sp2[NZ], c[NZ];  /* pair moments of Z, Z' at the nodes */
  double ltol;
  int k;                        /* lengths above are in units of 2^k */
  int scaled;                   /* log-domain evaluation (see top) */
} zstats;

/* One evaluation of the bound: the integrand is multiplied by
 * e^E / h^(dim-1) (P(y) capped at e^E), node terms below e^{-722} of
 * e^{-E} are dropped (x > xc); E = 0, xc = 38, h = 1 is the plain
 * evaluation. */
typedef struct {
  const zstats *Z;
  double E, cap, xc, h;
} mctx;

static double gfun(double x)
{
  return 0.5 * x * x * gsl_sf_exprel_2(-x);
}

/* Add one particle's moments (tau, B) at the nodes; returns Var D(T). */
static double add_particle(zstats *Z, const double *xi, double tau,
                           double B)
{
  if (isinf(tau) || B == 0.0)
    return 0.0;
  const double T = Z->T, s2 = 0.5 * B * B * tau;
  const double vD = 2.0 * s2 * tau * tau * gfun(T / tau);
  for (int q = 0; q < NZ; q++) {
    const double t = xi[q] * T, f = xi[q];
    const double vt = 2.0 * s2 * tau * tau * gfun(t / tau);
    const double vr = 2.0 * s2 * tau * tau * gfun((T - t) / tau);
    const double C = 0.5 * (vt + vD - vr);
    const double cuD = s2 * tau * (-expm1(-t / tau) - expm1(-(T - t) / tau));
    const double cDu = -s2 * tau * expm1(-t / tau);
    double vz = vt - 2.0 * f * C + f * f * vD;
    double vzp = s2 - 2.0 * cuD / T + vD / (T * T);
    Z->s2[q] += vz > 0.0 ? vz : 0.0;
    Z->sp2[q] += vzp > 0.0 ? vzp : 0.0;
    Z->c[q] += cDu - C / T - f * cuD + f * vD / T;
  }
  return vD;
}

/* Expected up-crossings of level y by one component of Z over [0, T],
 * times e^E. */
static double upcross(const mctx *M, double y)
{
  const zstats *Z = M->Z;
  double u = 0.0;
  for (int q = 0; q < NZ; q++) {
    const double s2 = Z->s2[q];
    if (!(s2 > 0.0))
      continue;
    const double s = sqrt(s2), x = y / s;
    if (x > M->xc)
      continue;
    const double m = Z->c[q] * y / s2;
    double v = Z->sp2[q] - Z->c[q] * Z->c[q] / s2, g;
    if (v > 0.0) {
      double sv = sqrt(v), z = m / sv;
      g = sv * INV_SQRT_2PI * exp(-0.5 * z * z) +
          m * 0.5 * erfc(-z * INV_SQRT_2);
    } else
      g = m > 0.0 ? m : 0.0;
    u += Z->w[q] * INV_SQRT_2PI * exp(M->E - 0.5 * x * x) / s * g;
  }
  return Z->T * u;
}

/* P(a contact of a pair whose chord passes at distance R + y): with n
 * the unit normal of the chord's closest approach, every chord point has
 * n.chord >= R + y, so a contact needs n.Z(t) <= -y, a one-component
 * excursion (Z isotropic; n is a function of the chord, independent of
 * Z for Brownian motion, whose bridge is independent of its ends). */
static double psup(const mctx *M, double y)
{
  double p = upcross(M, y);
  return p < M->cap ? p : M->cap;
}

/* Integrand in the scaled variable z = y / sc (sc the largest standard
 * deviation of Z): the integrand then varies on a scale of order one,
 * whatever the units (in metres it would live within ~1e-7 of the lower
 * limit, where the adaptive routine cannot find it). */
static double miss_integrand(double z, void *vp)
{
  const mctx *M = vp;
  const zstats *Z = M->Z;
  const double y = z * Z->sc, d = Z->R / M->h + z * (Z->sc / M->h);
  const double L = Z->L / M->h;
  double shell = Z->dim == 3 ? 4.0 * PI * d * d + 2.0 * PI * d * L
                             : 2.0 * PI * d + 2.0 * L;
  return shell * psup(M, y);
}

/* The bound at rho (in the unit 2^k): returns it (inf beyond DBL_MAX) and
 * its log in *lm (-745 where it is 0), or NaN if the quadrature fails. */
static double miss(const zstats *Z, double rho, double *lm)
{
  *lm = -745.0;
  if (!(Z->sc > 0.0))
    return 0.0;  /* no deviation from the chords: nothing is missed */
  const double z0 = rho / Z->sc;
  mctx M = {Z, 0.0, 1.0, 38.0, 1.0};
  if (Z->scaled) {
    /* an integrand of order one (top of the file): the shell in units of
     * h, and E = -log P(z0), from U at z0 times e^{z0^2/2} (no underflow:
     * x >= z0 at every node) */
    M.h = fmax(Z->sc, Z->R);
    if (z0 > 0.0) {
      const double E0 = 0.5 * z0 * z0;
      const mctx M0 = {Z, E0, INFINITY, sqrt(1444.0 + 2.0 * E0), 1.0};
      const double u0 = upcross(&M0, rho);
      M.E = !(u0 > 0.0) ? E0 : isinf(u0) ? 0.0 : fmax(0.0, E0 - log(u0));
      M.cap = exp(M.E);
      M.xc = sqrt(1444.0 + 2.0 * M.E);
    }
  }
  /* the integrand is 0 beyond z = xc (upcross skips every component
   * beyond xc standard deviations, and sc is the largest) */
  const double z1 = M.xc;
  if (!(z0 < z1))
    return 0.0;
  gsl_function F = {miss_integrand, &M};
  double res, err;
  if (sbi_integrate(&F, z0, z1, 0.0, 1e-7, 200, &res, &err) != SB_SUCCESS)
    return NAN;
  if (!Z->scaled) {
    const double m = Z->n * Z->sc * res;
    if (m > 0.0)
      *lm = log(m);
    return m;
  }
  if (!(res > 0.0))
    return 0.0;
  *lm = log(Z->n) + log(Z->sc) + (Z->dim - 1) * log(M.h) + log(res) +
        Z->dim * (Z->k * 0.69314718055994530942) - M.E;
  return exp(*lm);
}

static int zinit(zstats *Z, int dim, double n, double R, double tau_i,
                 double B_i, double tau_j, double B_j, double dt)
{
  if ((dim != 2 && dim != 3) || !(n > 0.0) || !isfinite(n) || !(R > 0.0) ||
      !isfinite(R) || !(dt > 0.0) || !isfinite(dt) || !(tau_i > 0.0) ||
      !(tau_j > 0.0) || !(B_i >= 0.0) || !(B_j >= 0.0) || !isfinite(B_i) ||
      !isfinite(B_j))
    return SB_EDOM;
  gsl_integration_glfixed_table *t = gsl_integration_glfixed_table_alloc(NZ);
  if (!t)
    return SB_ENOMEM;
  double xi[NZ];
  for (int q = 0; q < NZ; q++)
    gsl_integration_glfixed_point(0.0, 1.0, (size_t)q, &xi[q], &Z->w[q], t);
  gsl_integration_glfixed_table_free(t);
  /* the length unit 2^k (top of the file): B_i, B_j and R exactly scaled
   * (a particle without noise contributes nothing, whatever its B) */
  const double Bm = fmax(isinf(tau_i) ? 0.0 : B_i, isinf(tau_j) ? 0.0 : B_j);
  Z->k = Bm > 0x1p64 ? ilogb(Bm) : 0;
  Z->dim = dim;
  Z->n = n;
  Z->R = ldexp(R, -Z->k);
  Z->T = dt;
  for (int q = 0; q < NZ; q++)
    Z->s2[q] = Z->sp2[q] = Z->c[q] = 0.0;
  double vD = add_particle(Z, xi, tau_i, ldexp(B_i, -Z->k)) +
              add_particle(Z, xi, tau_j, ldexp(B_j, -Z->k));
  Z->L = sqrt(dim * vD);
  double s2 = 0.0;
  for (int q = 0; q < NZ; q++)
    s2 = Z->s2[q] > s2 ? Z->s2[q] : s2;
  Z->sc = sqrt(s2);
  /* log(n sc^dim) in the real unit: beyond 50 the plain 38-sd cut and
   * the bound near a reach's tol are not resolved in doubles; lengths
   * beyond 1e50 take the plain integrand's squares near overflow (top) */
  Z->scaled = Z->k > 0 || !(Z->sc < 1e50 && Z->R < 1e50 && Z->L < 1e50) ||
              log(n) + dim * (log(Z->sc) + Z->k * 0.69314718055994530942) >
                  50.0;
  return SB_SUCCESS;
}

double sb_langevin_miss_bound(int dim, double n, double R, double tau_i,
                              double B_i, double tau_j, double B_j,
                              double dt, double rho)
{
  zstats Z;
  int st = zinit(&Z, dim, n, R, tau_i, B_i, tau_j, B_j, dt);
  if (st || !(rho >= 0.0) || !isfinite(rho)) {
    sbi_error(st ? st : SB_EDOM, __func__, "bad argument (dim %d, n %g, R "
              "%g, dt %g, rho %g)", dim, n, R, dt, rho);
    return NAN;
  }
  double lm, m = miss(&Z, ldexp(rho, -Z.k), &lm);
  if (isnan(m))
    sbi_error(SB_EMAXITER, __func__, "quadrature failed (rho = %g)", rho);
  else if (isinf(m)) { /* n sc (R + y)^2 (times 2^(dim k)) beyond DBL_MAX */
    sbi_error(SB_ERANGE, __func__, "the bound exceeds DBL_MAX (rho = %g)",
              rho);
    return NAN;
  }
  return m;
}

/* log(miss) - log(tol); NaN propagates (a failed quadrature is an
 * error, never "nothing missed"). */
static double reach_fn(double rho, void *vp)
{
  const zstats *Z = vp;
  double lm, m = miss(Z, rho, &lm);
  if (isnan(m))
    return NAN;
  return lm - Z->ltol;
}

double sb_langevin_reach(int dim, double n, double R, double tau_i,
                         double B_i, double tau_j, double B_j, double dt,
                         double tol)
{
  zstats Z;
  int st = zinit(&Z, dim, n, R, tau_i, B_i, tau_j, B_j, dt);
  if (st || !(tol > 0.0 && tol < 1.0)) {
    sbi_error(st ? st : SB_EDOM, __func__, "bad argument (dim %d, n %g, R "
              "%g, dt %g, tol %g)", dim, n, R, dt, tol);
    return NAN;
  }
  Z.ltol = log(tol);
  double smax = 0.0;
  for (int q = 0; q < NZ; q++)
    if (Z.s2[q] > smax)
      smax = Z.s2[q];
  if (!(smax > 0.0))
    return 0.0;  /* no deviation from the chords */
  smax = sqrt(smax);
  double f0 = reach_fn(0.0, &Z);
  if (isnan(f0)) {
    sbi_error(SB_EMAXITER, __func__, "miss-bound quadrature failed");
    return NAN;
  }
  if (!(f0 > 0.0))
    return 0.0;
  gsl_function F = {reach_fn, &Z};
  double rho; /* in the unit 2^k */
  st = sbi_reach_root(&F, smax, 1e6 * (smax + Z.R), 1e-6, &rho);
  if (st) {
    sbi_error(st, __func__, st == SB_ENOMEM ? "out of memory"
                                            : "no bracket");
    return rho;
  }
  rho = ldexp(rho, Z.k);
  if (isinf(rho)) {
    sbi_error(SB_ERANGE, __func__, "the reach exceeds DBL_MAX");
    return NAN;
  }
  return rho;
}
