/* engine_exact.c — exact endpoint-conditioned detection of the first
 * contact of a 3-D Brownian bridge with a sphere (beyond Mohaupt 2011,
 * whose Bessel-3 criterion sees only |A| and |B|).
 *
 * The relative position r(u) of a diffusive pair over a step, given r(0) =
 * A and r(t) = B, is a 3-D Brownian bridge with per-component variance
 * rate sigma2.  Its law is built by midpoint refinement (Levy's
 * construction): given the values at the ends of a sub-interval of length
 * h, the midpoint is N((P + Q)/2, sigma2 h/4) per component, independent of
 * everything outside.  We explore the sub-intervals in time order,
 * depth-first, so the first sub-interval found to contain a contact holds
 * the first contact.
 *
 * Discarding.  For a unit vector n the ball |r| <= a lies in the half
 * space r.n <= a, and r.n is a 1-D Brownian bridge from P.n to Q.n, which
 * enters the half space with probability exp(-2 (P.n - a)(Q.n - a)/w), w =
 * sigma2 h (reflection principle; sb_bb_cross_prob).  This upper-bounds the
 * probability of touching the ball; we take n along the point of the chord
 * PQ closest to the centre and discard the sub-bridge when the bound is
 * below tol/1000.
 *
 * Leaves.  When sqrt(w) <= tol a, the sphere is flat to relative order tol
 * over the region the sub-bridge explores: there the Bessel-3 bridge
 * formula (which is exact for the radial part when A and B are aligned and
 * tends to the half-space formula as w/a^2 -> 0) decides the contact, and
 * the conditioned hit time comes from sb_bes3b_hit_sample.  The contact
 * point is the chord point at that time projected radially on the sphere
 * (off by O(sqrt(w)) <= tol a).
 */
#include <math.h>

#include <gsl/gsl_randist.h>

#include <smolbridge/bridge.h>
#include <smolbridge/engine_bridge.h>

#include "common/internal.h"

#define MAXDEPTH 80

typedef struct {
  const gsl_rng *r;
  double a, sigma2, tol, skip;
  double ta, xa[3];
  sb_bb3_info info;
} bb3_work;

static double norm3(const double *v)
{
  return sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

/* Upper bound on P(sub-bridge P -> Q of variance w touches the ball);
 * 1 when the half-space bound does not apply (an end inside the plane). */
static double half_space_bound(const double *P, const double *Q, double a,
                               double w)
{
  double d[3] = {Q[0] - P[0], Q[1] - P[1], Q[2] - P[2]};
  double dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
  double lam = dd > 0.0 ? -(P[0] * d[0] + P[1] * d[1] + P[2] * d[2]) / dd
                        : 0.0;
  lam = lam < 0.0 ? 0.0 : (lam > 1.0 ? 1.0 : lam);
  double c[3] = {P[0] + lam * d[0], P[1] + lam * d[1], P[2] + lam * d[2]};
  double cn = norm3(c);
  if (!(cn > a))
    return 1.0;
  double p = (P[0] * c[0] + P[1] * c[1] + P[2] * c[2]) / cn - a;
  double q = (Q[0] * c[0] + Q[1] * c[1] + Q[2] * c[2]) / cn - a;
  if (!(p > 0.0 && q > 0.0))
    return 1.0;
  return exp(-2.0 * p * q / w);
}

/* Examine the sub-bridge P -> Q on [t0, t0 + h]; 1 if the first contact
 * is found in it (stored in W), 0 if not, -1 on error. */
static int examine(bb3_work *W, const double *P, const double *Q, double t0,
                   double h, size_t depth)
{
  W->info.nodes++;
  if (depth > W->info.depth)
    W->info.depth = depth;
  const double a = W->a, w = W->sigma2 * h;
  if (half_space_bound(P, Q, a, w) < W->skip)
    return 0;
  if (sqrt(w) <= W->tol * a || depth >= MAXDEPTH) {
    double x = norm3(P), y = norm3(Q);
    if (x <= a) {  /* only reachable at depth 0 (caller handles it) */
      W->ta = t0;
      for (int k = 0; k < 3; k++)
        W->xa[k] = a * P[k] / x;
      return 1;
    }
    if (y > a) {
      double pr = sb_bes3b_cross_prob(x, y, a, w);
      if (isnan(pr))
        return -1;
      if (!(gsl_rng_uniform(W->r) < pr))
        return 0;
    }
    double u = sb_bes3b_hit_sample(W->r, x, y, a, W->sigma2, h);
    if (!(u >= 0.0 && u <= h))
      return -1;
    double c[3];
    for (int k = 0; k < 3; k++)
      c[k] = P[k] + (Q[k] - P[k]) * (u / h);
    double cn = norm3(c);
    for (int k = 0; k < 3; k++)
      W->xa[k] = cn > 0.0 ? a * c[k] / cn : (k == 2 ? a : 0.0);
    W->ta = t0 + u;
    return 1;
  }
  double M[3], sd = 0.5 * sqrt(w);
  for (int k = 0; k < 3; k++)
    M[k] = 0.5 * (P[k] + Q[k]) + gsl_ran_gaussian_ziggurat(W->r, sd);
  int st = examine(W, P, M, t0, 0.5 * h, depth + 1);
  if (st)
    return st;
  return examine(W, M, Q, t0 + 0.5 * h, 0.5 * h, depth + 1);
}

int sb_bb3_hit_sample(const gsl_rng *r, const double A[3], const double B[3],
                      double a, double sigma2, double t, double tol,
                      double *ta, double xa[3], sb_bb3_info *info)
{
  if (info)
    info->nodes = info->depth = 0;
  if (!r || !A || !B || !ta || !xa)
    return -sbi_error(SB_EINVAL, __func__, "NULL argument");
  if (!(a > 0.0) || !(sigma2 > 0.0) || !(t > 0.0) ||
      !(tol > 0.0 && tol <= 0.1) || !isfinite(a) || !isfinite(sigma2) ||
      !isfinite(t))
    return -sbi_error(SB_EDOM, __func__, "a = %g, sigma2 = %g, t = %g, "
                     "tol = %g", a, sigma2, t, tol);
  for (int k = 0; k < 3; k++)
    if (!isfinite(A[k]) || !isfinite(B[k]))
      return -sbi_error(SB_EDOM, __func__, "non-finite end point");
  double x = norm3(A);
  if (x <= a) {
    *ta = 0.0;
    for (int k = 0; k < 3; k++)
      xa[k] = x > 0.0 ? a * A[k] / x : (k == 2 ? a : 0.0);
    return 1;
  }
  bb3_work W = {r, a, sigma2, tol, tol * 1e-3, 0.0, {0, 0, 0}, {0, 0}};
  int st = examine(&W, A, B, 0.0, t, 0);
  if (info)
    *info = W.info;
  if (st < 0)
    return -sbi_error(SB_EDOM, __func__, "hit-time draw failed");
  if (st) {
    *ta = W.ta;
    for (int k = 0; k < 3; k++)
      xa[k] = W.xa[k];
  }
  return st;
}
