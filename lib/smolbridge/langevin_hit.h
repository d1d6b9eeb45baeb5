/* smolbridge/langevin_hit.h — first contact of two Langevin particles
 * between two known states: exact sampling from the pair's conditional
 * (bridge) law, and the neighbour reach that goes with it.
 *
 * Problem.  Particles i and j follow the Langevin model of
 * <smolbridge/langevin.h> (per Cartesian component dX = U dt,
 * dU = (us - U)/tau dt + B dW, us held constant over the step).  Their
 * states (x, u) at both ends of a step of length dt are known.  Given
 * them, the two paths are independent Gaussian bridges
 * (sb_langevin_bridge_moments), so the relative position
 * r(t) = x_i(t) - x_j(t) is a Gaussian process whose law is known at every
 * time.  The sampler decides whether |r(t)| <= R (R = r_i + r_j) for some
 * t in [0, dt] and returns the first such time, the contact point and both
 * particles' velocities at contact, drawn from that conditional law.
 * In a linear shear (sb_langevin_path.G != 0) the fluid velocity seen
 * along x is G y(t): x and y couple, and each particle's in-plane state
 * follows the exact bridge of <smolbridge/langevin_shear.h> instead (the
 * bounds below then take their variances along a direction from the
 * covariances by component).
 *
 * Method (docs/engine_langevin.md):
 *  - recursive midpoint refinement in time order: on a sub-interval
 *    [a, b] with both particles' states known at a and b, the midpoint
 *    states are drawn exactly (Markov property of (X, U)), then [a, m] is
 *    examined before [m, b].  Two particles with the same tau and B (one
 *    species) walk their relative state alone: their bridges have the same
 *    covariance, so r and the barycentre are independent bridges (twice
 *    and half that covariance) and the barycentre is drawn once, at the
 *    contact;
 *  - pruning by Rice's formula (Rice 1944, 1945): for a unit vector n the
 *    ball |r| <= R lies in the half-space n.r <= R, so the probability of
 *    a contact in (a, b) is at most the expected number of down-crossings
 *    of p(t) = n.r(t) - R through 0, the integral over (a, b) of
 *    f_p(0) E[(p')^- | p = 0]; (p, p') is jointly Gaussian given the end
 *    states.  n points at the conditional mean path's closest approach.
 *    The integral is evaluated by 16-point Gauss-Legendre quadrature (GSL)
 *    and a sub-interval is pruned when SAFETY times it, plus the largest
 *    node probability P(p(t_k) <= 0), is below eps (b - a)/dt: the pruned
 *    sub-intervals are disjoint, so the probability that a contact is
 *    missed is at most eps per call (up to the quadrature, see below);
 *  - leaves: once the conditional position spread on a sub-interval plus
 *    the distance of its mean path from the straight chord is below
 *    xtol R, the sub-interval is decided on its chord (the path lies
 *    within that distance of it): the entry root is the contact time, and
 *    both particles' states at that time are drawn from their bridges,
 *    then moved along the line of centres (barycentre kept) to be exactly
 *    in contact.  Leaves whose chord passes within 6 xtol R of the sphere
 *    without entering are counted as grazing (decided "no contact").
 *
 * Error budget.  Per call: P(the sampled outcome differs from an exact
 * draw) <= eps (pruning, Rice) + P(grazing leaf) (O(xtol), counted), and
 * the contact time and place are exact up to a position error xtol R.
 * The Rice integral is a quadrature, not a proven bound: the tests measure
 * the realised error by auditing pruned sub-intervals
 * (sb_langevin_hit_params.audit) and compare the whole law with a
 * brute-force fine-step simulation of the same bridge.
 *
 * Periodic images: pass positions in one frame (unwrapped, minimum image
 * at the start).  Units: any consistent set (SI in the engine).
 * Thread safety: a workspace (sb_langevin_hitter) belongs to one thread;
 * distinct workspaces are independent.
 */
#ifndef SMOLBRIDGE_LANGEVIN_HIT_H
#define SMOLBRIDGE_LANGEVIN_HIT_H

#include <stddef.h>
#include <stdint.h>
#include <gsl/gsl_rng.h>
#include <smolbridge/common.h>

#ifdef __cplusplus
extern "C" {
#endif

/** One particle over a step: Langevin parameters and both end states.
 *  tau > 0 (INFINITY: free flight, x1 = x0 + u0 dt), B >= 0 (0: no noise,
 *  the path is the deterministic relaxation from the start state and the
 *  end state is ignored), mass > 0 (only used to share the final contact
 *  adjustment; 0 shares it equally). */
typedef struct {
  double tau, B, mass;
  double us[3];          /**< fluid velocity seen at x0, constant over the
                              step when G = 0 */
  double x0[3], u0[3];   /**< state at t = 0 */
  double x1[3], u1[3];   /**< state at t = dt */
  double G;              /**< linear shear: the fluid velocity at x is
                              us + (G (x[1] - x0[1]), 0, 0) (units 1/time;
                              0: uniform flow).  Used for Stokes
                              particles (finite tau): with noise their
                              in-plane bridge is then the exact one of
                              <smolbridge/langevin_shear.h>, without
                              (B = 0) their path the exact one in the
                              linear field; free flight ignores it; both
                              particles of a pair must have the same G
                              (one may give 0: the pair's rate is the
                              other's) */
} sb_langevin_path;

/** Sampler parameters (sb_langevin_hit_params_default). */
typedef struct {
  int dim;        /**< 2 or 3 (default 3); in 2-D the third components
                       are ignored and returned as 0 */
  double eps;     /**< probability budget of pruning per call, in
                       (0, 0.1]; default 1e-6 */
  double xtol;    /**< leaf resolution relative to R, in (0, 0.01];
                       default 1e-6 */
  int audit;      /**< 1: explore every pruned sub-interval (with budget
                       eps 1e-3) and count in the statistics those that
                       held a contact; the law of the output is unchanged
                       (tests only: slow); default 0 */
} sb_langevin_hit_params;

/** First contact: time t in [0, dt], both particles' positions (|x_i -
 *  x_j| = R to rounding) and velocities at t. */
typedef struct {
  double t;
  double xi[3], ui[3];
  double xj[3], uj[3];
} sb_langevin_contact;

/** Counters since the allocation or sb_langevin_hitter_reset. */
typedef struct {
  uint64_t calls;     /**< sampler calls (contact, plane and exit) */
  uint64_t hits;      /**< calls that returned a contact (or exit) */
  uint64_t nodes;     /**< sub-intervals examined */
  uint64_t pruned;    /**< sub-intervals pruned by the bound */
  uint64_t leaves;    /**< sub-intervals decided on their chord */
  uint64_t grazing;   /**< leaves whose chord grazed the sphere */
  uint64_t deep;      /**< sub-intervals cut at the depth limit */
  uint64_t audit_hits;/**< audit: pruned sub-intervals that held a contact */
  unsigned depth_max; /**< deepest refinement level reached */
  double pruned_mass; /**< sum of the bounds of the pruned sub-intervals:
                           its mean per call bounds the pruning error */
} sb_langevin_hit_stats;

typedef struct sb_langevin_hitter sb_langevin_hitter;

void sb_langevin_hit_params_default(sb_langevin_hit_params *p);

/** Workspace (caches the bridge coefficients per (tau, B, dt) and
 *  refinement level).  NULL and SB_EINVAL / SB_ENOMEM on failure. */
sb_langevin_hitter *sb_langevin_hitter_alloc(const sb_langevin_hit_params *p);
void sb_langevin_hitter_free(sb_langevin_hitter *w);
const sb_langevin_hit_params *
sb_langevin_hitter_params(const sb_langevin_hitter *w);

/** Sample the first contact of i and j over [0, dt] (see the file
 *  comment).  Returns 1 (contact, *c filled; c may be NULL), 0 (none) or a
 *  negative status (-SB_EINVAL, -SB_EDOM) on bad input.  A pair that
 *  overlaps at t = 0 (|x0_i - x0_j| <= R) is in contact at t = 0.
 *  Draws Gaussians and uniforms from r.  Domain: R > 0, dt > 0 finite,
 *  finite states, tau > 0, B >= 0, and dt/tau in [1e-9, 1e9] for the
 *  particles with noise; every length of the problem (a position
 *  component, |u| dt, |us| dt at either end, the noise's position spread
 *  sqrt(var_x(tau, B, dt))) at most 1e100 R and 1e150 (-SB_EDOM
 *  otherwise: the bounds would overflow and nothing would be pruned;
 *  docs/engine_langevin.md §2). */
int sb_langevin_hitter_sample(sb_langevin_hitter *w,
                              const sb_langevin_path *pi,
                              const sb_langevin_path *pj, double R,
                              double dt, const gsl_rng *r,
                              sb_langevin_contact *c);

/** First exit: the first time in [0, dt] at which i and j are R apart,
 *  for a pair that starts in contact (|x0_i - x0_j| < R, or = R and
 *  approaching, as the states sb_langevin_hitter_sample returns at a
 *  contact), from the same conditional law with the same method and
 *  error budget.  The target set is the outside of the ball; the closed-
 *  form bound then takes the expected number of up-crossings, by the norm
 *  of the relative path's deviation from its conditional mean, of the
 *  chord's clearance inside the ball (Rice's formula for the chi process;
 *  docs/engine_langevin.md §2), and leaves decide on the chord's exit
 *  root.  A leaf whose chord comes within 6 xtol R of the sphere from
 *  inside counts as grazing (except at a start touching on the way in).
 *  With the entry sampler from the exit state it gives every entry of a
 *  pair that passes through contact (the engine's count outcome).
 *  Returns 1 (exit: c->t, both states, |x_i - x_j| = R to rounding), 0
 *  (the pair stays within R over [0, dt]) or a negative status.  A pair
 *  apart at 0 (|x0_i - x0_j| > R, or = R and separating) exits at 0.
 *  Domain as sb_langevin_hitter_sample. */
int sb_langevin_hitter_sample_exit(sb_langevin_hitter *w,
                                   const sb_langevin_path *pi,
                                   const sb_langevin_path *pj, double R,
                                   double dt, const gsl_rng *r,
                                   sb_langevin_contact *c);

/** Every entry into contact over (0, dt]: for a pair that passes
 *  through contact (nothing happens at a contact: the engine's count
 *  outcome), the same walk goes on after an entry, looking for the exit
 *  (as sb_langevin_hitter_sample_exit), then for the next entry, over the
 *  same refinement levels.  Each entry's states are drawn at its leaf as
 *  for sb_langevin_hitter_sample (for equal particles the barycentre's
 *  from its bridge between the previous entry's and the end).  A pair in
 *  contact at t = 0 (overlapping, or touching and approaching) is not
 *  entering: its exit is looked for first.  Per entry and exit, the same
 *  error budget.  Returns the number n >= 0 of entries, whose states are
 *  at sb_langevin_hitter_entries(w) in time order until the next call on
 *  w, or a negative status (-SB_ENOMEM as well). */
int sb_langevin_hitter_sample_all(sb_langevin_hitter *w,
                                  const sb_langevin_path *pi,
                                  const sb_langevin_path *pj, double R,
                                  double dt, const gsl_rng *r);

/** The entries of the last sb_langevin_hitter_sample_all call on w. */
const sb_langevin_contact *
sb_langevin_hitter_entries(const sb_langevin_hitter *w);

/** First contact of one Langevin particle with the plane n.x = level
 *  (n need not be normalised), approached from the side n.x > level,
 *  over [0, dt] given its states at both ends: the same sampler, with the
 *  half-space n.x <= level in place of the ball (the Rice bound is then
 *  taken along n itself, and a leaf's chord enters the half-space at a
 *  linear root).  The particle's path is the exact conditional (bridge)
 *  law of the integrated OU process given both end states, so the
 *  contact probability and time are exact at every dt/tau up to eps and
 *  the leaf resolution xtol * scale (scale > 0: a length of the problem,
 *  e.g. the particle radius).  Used for particle-wall contact
 *  (SB_WALLDET_LANGEVIN of the engine; Mohaupt 2011, §5.1 for the
 *  Brownian-bridge version).  Returns 1 (contact: c->t, c->xi on the
 *  plane, c->ui; c->xj, c->uj zero), 0, or a negative status; a start at
 *  or beyond the plane (touching and approaching) is a contact at t = 0.
 *  Domain as sb_langevin_hitter_sample (lengths at most 1e100 scale);
 *  level finite. */
int sb_langevin_hitter_sample_plane(sb_langevin_hitter *w,
                                    const sb_langevin_path *p,
                                    const double n[3], double level,
                                    double scale, double dt,
                                    const gsl_rng *r,
                                    sb_langevin_contact *c);

/** The top-level pruning bound of the sampler for this configuration
 *  (SAFETY x Rice integral + largest node probability, capped at 1; 1
 *  when the bound does not apply: an end inside the half-space, or
 *  overlap).  For tests and diagnostics; NaN on bad input. */
double sb_langevin_hitter_bound(sb_langevin_hitter *w,
                                const sb_langevin_path *pi,
                                const sb_langevin_path *pj, double R,
                                double dt);

int sb_langevin_hitter_stats(const sb_langevin_hitter *w,
                             sb_langevin_hit_stats *st);
void sb_langevin_hitter_reset(sb_langevin_hitter *w);

/* ==================================================== neighbour reach */

/** Expected number of contacts, per particle and step, of pairs whose
 *  straight chords stay more than R + rho apart, for particles of density
 *  n (> 0) in dimension dim with species (tau_i, B_i) and (tau_j, B_j) at
 *  equilibrium (tau may be INFINITY: no deviation from the chord).
 *
 *  Let Z(t) = r(t) - r(0) - (t/dt)(r(dt) - r(0)) be the deviation of the
 *  relative path from its chord, and n the unit normal of the chord's
 *  closest approach c to the origin: every chord point has n.chord >= |c|,
 *  so a contact needs n.Z(t) <= R - |c|, an excursion of one component.
 *  Z is a stationary-start Gaussian process vanishing at both ends
 *  (closed-form covariance from the velocity autocorrelation), isotropic;
 *  the probability that one component exceeds y is at most its expected
 *  number of up-crossings U(y) (Rice), computed by quadrature.  The pairs
 *  whose chord passes at distance in [d, d + dd] number n (4 pi d^2 +
 *  2 pi d L) dd in 3-D (2 pi d + 2 L in 2-D), L the chord length (rms).
 *  Z is taken as independent of the chord (exact for Brownian motion,
 *  whose bridge is independent of its end point; an approximation at
 *  dt <~ tau), so
 *     E(rho) = n int_{R + rho}^inf (4 pi d^2 + 2 pi d L) P(d - R) dd,
 *     P(y) = min(1, U(y)).
 *  Accuracy ~1e-6 relative (quadrature).  NaN on bad input (SB_EDOM), NaN
 *  with SB_ERANGE where the bound exceeds DBL_MAX (e.g. B_i = 1e154 with
 *  n = R = tau = dt = 1), NaN with SB_EMAXITER where the quadrature fails.
 *
 *  Huge B: every finite B_i, B_j >= 0 is in the domain (up to DBL_MAX).
 *  The lengths of the problem scale like B (E(n, R, lambda B, lambda rho)
 *  = lambda^dim E(n, R / lambda, B, rho)); above max(B_i, B_j) = 2^64 the
 *  moments are computed in a length unit scaled by a power of two, and
 *  where n sc^dim > e^50 (sc the largest sd of the deviation), sc, R or L
 *  exceed 1e50 or the unit is scaled, the bound is evaluated in
 *  logarithms with an integrand of order one, so the result is a
 *  finite value, or NaN with SB_ERANGE where it exceeds DBL_MAX, never 0
 *  for lack of range.  Elsewhere the results are those of the plain
 *  evaluation, bit for bit. */
double sb_langevin_miss_bound(int dim, double n, double R, double tau_i,
                              double B_i, double tau_j, double B_j,
                              double dt, double rho);

/** Smallest rho >= 0 with sb_langevin_miss_bound(...) <= tol, 0 < tol < 1;
 *  relative accuracy 1e-6 in rho.  NaN on bad input (SB_EDOM).  At huge B
 *  (above) the reach is about sc sqrt(2 log(n sc^dim / tol)), sc
 *  proportional to B; it is found wherever it is below DBL_MAX (to B_i =
 *  DBL_MAX with tau, dt in 1e-8 .. 1e-6), NaN with SB_ERANGE beyond. */
double sb_langevin_reach(int dim, double n, double R, double tau_i,
                         double B_i, double tau_j, double B_j, double dt,
                         double tol);

#ifdef __cplusplus
}
#endif

#endif /* SMOLBRIDGE_LANGEVIN_HIT_H */
