/* smolbridge/engine_bridge.h — collision engine II: detection of
 * collisions between diffusive particles by diffusion bridges (Mohaupt
 * 2011, ch. 5, App. H-J; turbulent pair diffusivity ch. 6).
 *
 * Over one step of length dt the relative position of a pair, r(t) =
 * x_i - x_j, is modelled as a 3-D Brownian motion with per-component
 * variance rate B_ij^2 = b2_i + b2_j (Mohaupt 2011, eq 5.9; b2 = B_pos^2 =
 * (B tau_p)^2 in the diffusive limit dt >> tau_p), conditioned on its end
 * points A = r(0), B = r(dt).  A pair collides during the step when |r|
 * reaches the contact distance a = r_i + r_j.  A and B are taken from the
 * unwrapped displacement over the step (A minimum image, B = A + change),
 * never from the minimum image of the end positions.
 *
 * Detection modes (sb_engine_bridge_params.mode):
 *  SB_BRIDGE_BESSEL  the thesis' criterion: |r| is a Bessel-3 bridge
 *      from x = |A| to y = |B|, it hits a with probability
 *      expm1(2a(x+y-a)/v)/expm1(2xy/v), v = B_ij^2 dt, and 1 if x <= a or
 *      y <= a (Mohaupt 2011, eqs 5.13-5.15; sb_bes3b_cross_prob).  The hit
 *      time T_a is drawn exactly from the conditioned first-passage law
 *      (eqs 5.20-5.22; sb_bes3b_hit_sample, no bisection).  This law ignores
 *      the angle between A and B: the collision *rate* is exact, but which
 *      pair collides, when and where is not (docs/engine_bridge.md).
 *  SB_BRIDGE_EXACT   the event is sampled from the full 3-D bridge
 *      (sb_bb3_hit_sample below): exact up to the stated tolerance, and the
 *      contact point comes with the hit time.
 *
 * End points (params.ends): SB_BRIDGE_ENDS_POSITION uses the positions X
 * (as the thesis does); SB_BRIDGE_ENDS_DIFFUSIVE uses Y = X + tau_p U,
 * which for the Langevin model at rest is *exactly* a Brownian motion with
 * B_pos = B tau_p at any dt/tau_p (dY = tau_p B dW); |X - Y| = tau_p |U| ~
 * B_pos sqrt(tau_p/2), negligible against the radii in the diffusive regime.
 *
 * Neighbour reach (tail bound).  A pair whose straight chords stay farther
 * apart than a + rho has |A| >= a + rho.  For a 3-D Brownian motion from
 * |A| = x, P(hit the ball of radius a within dt) = (a/x) erfc((x-a)/
 * sqrt(2v)) (Bessel-3 first passage), and the detector's probability
 * averaged over the end point is exactly this.  With n the number density
 * of the other particles, the expected number of collisions of one
 * particle that the search does not examine is at most
 *   E1(rho) = n int_{a+rho}^inf 4 pi x^2 (a/x) erfc((x-a)/sqrt(2v)) dx
 *          = 8 pi n a sqrt(v) [a (phi(z) - z Q(z))
 *                              + sqrt(v) ((1 - z^2) Q(z) + z phi(z))/2],
 * z = rho/sqrt(v), phi/Q the standard normal density/upper tail.  Also,
 * since both ends are beyond a + rho, the detector probability is at most
 * exp(-2(x-a)(y-a)/v) <= exp(-2(x-a) rho/v), whose integral is
 *   E2(rho) = 4 pi n exp(-2 rho^2/v) [(a+rho)^2 c + 2(a+rho) c^2 + 2 c^3],
 * c = v/(2 rho); the bound used is min(E1, E2).  The reach is the smallest
 * rho with that bound <= tol (default 1e-9 per particle per step), found
 * with GSL's Brent solver on its log.
 *
 * Collision place (Mohaupt 2011, §5.4.2, App. J): the barycentre
 * b = (m_i x_i + m_j x_j)/(m_i + m_j) is a Brownian bridge with
 * B_bary^2 = (m_i^2 b2_i + m_j^2 b2_j)/(m_i + m_j)^2 (eq 5.25); at T_a it
 * is N(b0 + (b1 - b0) T_a/dt, T_a (dt - T_a)/dt B_bary^2) per component
 * (eq 5.26).
 *
 * Outcomes (params.outcome):
 *  SB_BRIDGE_OUT_REINSERT  the partner of higher id is put back at random
 *      (kernel validation, Mohaupt 2011, §5.3.2; as SB_OUTCOME_REINSERT);
 *  SB_BRIDGE_OUT_CORRECT   correction step (Mohaupt 2011, §5.4.3): the pair is
 *      placed in contact at time T_a around the barycentre b(T_a), along a
 *      random unit vector e orthogonal to b1 - b0 (x_i = b + m_j a e/M,
 *      x_j = b - m_i a e/M; for equal masses each is one radius from b),
 *      i diffuses freely from there to dt (variance b2_i (dt - T_a)) and j
 *      is placed so that the barycentre keeps its end value b1;
 *  SB_BRIDGE_OUT_COUNT     count only.
 *
 * Collision split (Mohaupt 2011, §6.4): each species has a total b2 and a
 * Brownian part b2_brown (sb_engine_bridge_set_b2); a collision adds
 * f = (b2b_i + b2b_j)/(b2_i + b2_j) to the Brownian count and 1 - f to the
 * turbulent one (the expected share: the kernel 2 pi B_ij^2 a is linear in
 * B_ij^2, Mohaupt 2011, eq 6.18).
 *
 * Units: SI (m, s, m^2/s) for the engine functions; sb_bb3_* and
 * sb_bridge_miss_bound are unit-free.  3-D engines only.
 */
#ifndef SMOLBRIDGE_ENGINE_BRIDGE_H
#define SMOLBRIDGE_ENGINE_BRIDGE_H

#include <stddef.h>
#include <stdint.h>
#include <gsl/gsl_rng.h>
#include <smolbridge/common.h>
#include <smolbridge/engine.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef enum {
  SB_BRIDGE_BESSEL = 0,   /**< Bessel-3 bridge criterion
                               (Mohaupt 2011, §5.3) */
  SB_BRIDGE_EXACT = 1     /**< full 3-D bridge (sb_bb3_hit_sample) */
} sb_bridge_mode;

typedef enum {
  SB_BRIDGE_ENDS_POSITION = 0,  /**< X (as Mohaupt 2011) */
  SB_BRIDGE_ENDS_DIFFUSIVE = 1  /**< Y = X + tau_p U (exact BM) */
} sb_bridge_ends;

typedef enum {
  SB_BRIDGE_OUT_REINSERT = 0,
  SB_BRIDGE_OUT_CORRECT = 1,
  SB_BRIDGE_OUT_COUNT = 2
} sb_bridge_outcome;

/** Parameters (sb_engine_bridge_params_default fills the defaults). */
typedef struct {
  sb_bridge_mode mode;        /**< default SB_BRIDGE_BESSEL */
  sb_bridge_ends ends;        /**< default SB_BRIDGE_ENDS_POSITION */
  sb_bridge_outcome outcome;  /**< default SB_BRIDGE_OUT_REINSERT */
  double tol;                 /**< reach tail tolerance, expected missed
                                   collisions per particle per step, in
                                   (0, 1); default 1e-9 */
  double exact_tol;           /**< exact mode tolerance (see
                                   sb_bb3_hit_sample); default 1e-3 */
  size_t record_cap;          /**< keep up to this many hit records
                                   (sb_engine_bridge_hits); default 0 */
} sb_engine_bridge_params;

/** One detected hit (for hit-time histograms): Bessel-3 bridge from x to
 *  y (m), level a (m), rate sigma2 = B_ij^2 (m^2/s), step dt (s), sampled
 *  hit time ta (s). */
typedef struct {
  double x, y, a, sigma2, dt, ta;
} sb_engine_bridge_hit;

/** Counters since the allocation or sb_engine_bridge_reset. */
typedef struct {
  uint64_t ndetect;    /**< detections (before the one-per-step rule) */
  uint64_t ncoll;      /**< collisions processed by the outcome */
  uint64_t noverlap;   /**< detections of pairs overlapping at the start */
  double coll_brown;   /**< Brownian share of ncoll (sum of f) */
  double coll_turb;    /**< turbulent share (sum of 1 - f) */
} sb_engine_bridge_stats;

typedef struct sb_engine_bridge sb_engine_bridge;

void sb_engine_bridge_params_default(sb_engine_bridge_params *p);

/** New detector context; p NULL: the defaults (NULL and SB_EINVAL /
 *  SB_ENOMEM on failure). */
sb_engine_bridge *sb_engine_bridge_alloc(const sb_engine_bridge_params *p);
void sb_engine_bridge_free(sb_engine_bridge *b);

/** Per-species position variance rate b2 = B_pos^2 (m^2/s, > 0) and its
 *  Brownian part b2_brown in [0, b2] (for the collision split).  Species
 *  not set use b2 = b2_brown = (B tau_p)^2 of the engine species. */
int sb_engine_bridge_set_b2(sb_engine_bridge *b, size_t species, double b2,
                            double b2_brown);

/** Save the detector's counters and hit records beside a checkpoint of
 *  engine e at the same step (sb_engine_checkpoint_save), with the
 *  engine's step and a fingerprint of its particles.  Native binary.
 *  SB_EINVAL, SB_EIO (cannot write; no file is left). */
int sb_engine_bridge_save(const sb_engine_bridge *b, const sb_engine *e,
                          const char *path);
/** Restore them into a new detector (its parameters and b2 given again),
 *  before sb_engine_bridge_attach, which then checks that the engine is
 *  the one restored from the same checkpoint (SB_EINVAL otherwise).
 *  SB_EINVAL (more records than record_cap), SB_EIO (cannot open),
 *  SB_EFORMAT (not such a file, truncated, or damaged: the file ends in
 *  a hash of its contents, format SBBRID02, checked before anything is
 *  read; SBBRID01 files, without it, still load); on failure the
 *  counters are unchanged and no record is kept. */
int sb_engine_bridge_load(sb_engine_bridge *b, const char *path);

/** Install the detector and outcome in engine e (3-D, every species with
 *  finite tau_p): computes the reach (sb_engine_bridge_reach) from the
 *  current particle number, box, species and dt.  Call again after a
 *  change of dt, of the particle number or of b2.  The context must
 *  outlive its use by the engine. */
int sb_engine_bridge_attach(sb_engine *e, sb_engine_bridge *b);

/** The reach (m) the attach computes: smallest rho >= 0 with
 *  min(E1, E2)(rho) <= tol for n = (N - 1)/V, a = the largest contact distance and
 *  v = the largest B_ij^2 dt over species pairs.  NaN on error. */
double sb_engine_bridge_reach(const sb_engine *e, const sb_engine_bridge *b);

/** Tail bound min(E1, E2)(rho) of the file comment (unit-free): bounds
 *  the expected number of particles of density n (> 0) that a particle
 *  would be found to hit within a step of variance v (> 0) while both end
 *  separations exceed a + rho (a > 0, rho >= 0).  Relative accuracy ~1e-12
 *  (tested 1e-9 against quadrature; the cancellation in phi - z Q is
 *  bounded by 1/z^2 ~ 1e-2 at the reaches of interest). */
double sb_bridge_miss_bound(double n, double a, double v, double rho);
/** Smallest rho >= 0 with sb_bridge_miss_bound(n, a, v, rho) <= tol
 *  (0 < tol < 1); relative accuracy 1e-10 in rho. */
double sb_bridge_reach(double n, double a, double v, double tol);

/** Detector (sb_engine_detect_fn; ctx is the sb_engine_bridge). */
int sb_engine_detect_bridge(const sb_engine *e, const sb_engine_pair *p,
                            const gsl_rng *r, void *ctx, double *s);
/** Outcome (sb_engine_outcome_fn; ctx is the sb_engine_bridge). */
int sb_engine_outcome_bridge(sb_engine *e, const sb_engine_pair *p, double s,
                             void *ctx);

/** Barycentre of pair p at T_a = s dt (eq 5.26), relative to the start
 *  position of particle p->i (m; add x0_i to get a position).  Draws 3
 *  Gaussians from r. */
int sb_engine_bridge_place(const sb_engine *e, const sb_engine_bridge *b,
                           const sb_engine_pair *p, double s,
                           const gsl_rng *r, double bary[3]);

int sb_engine_bridge_get_stats(const sb_engine_bridge *b,
                               sb_engine_bridge_stats *st);
void sb_engine_bridge_reset(sb_engine_bridge *b);
/** The recorded hits (array owned by the context). */
const sb_engine_bridge_hit *sb_engine_bridge_hits(const sb_engine_bridge *b,
                                                  size_t *n);

/* ================================= exact 3-D bridge detection (unit-free) */

/** Statistics of one sb_bb3_hit_sample call (may be NULL). */
typedef struct {
  size_t nodes;   /**< sub-bridges examined */
  size_t depth;   /**< deepest refinement level */
} sb_bb3_info;

/** One draw of the first contact of the 3-D Brownian bridge r(u),
 *  r(0) = A, r(t) = B, per-component variance rate sigma2 (> 0), with the
 *  sphere |r| = a (a > 0), t > 0.  Returns 1 (hit; *ta in [0, t] the hit
 *  time, xa[3] the contact point, |xa| = a), 0 (no hit) or minus the
 *  status code (-SB_EINVAL, -SB_EDOM) on bad input.  |A| <= a: hit at
 *  0; |B| <= a: surely hits.
 *
 *  Method: recursive midpoint refinement of the Gaussian bridge in time
 *  order.  A sub-bridge P -> Q of variance w = sigma2 h is discarded when
 *  the half-space bound exp(-2 (p - a)(q - a)/w) (p, q the distances of
 *  P, Q to the tangent plane of the sphere normal to the direction of the
 *  closest chord point; the ball lies in that half-space, so this bounds
 *  the hit probability from above) is below tol * 1e-3; once sqrt(w) <=
 *  tol * a the sphere is flat at that scale and the sub-bridge is decided
 *  by the Bessel-3 formula with its conditioned hit time (error O(tol) in
 *  the probability and the place, relative); otherwise its midpoint is
 *  drawn, N((P + Q)/2, w/4) per component, and both halves are examined,
 *  earlier first.  tol in (0, 0.1].  Exactness is tested against a
 *  brute-force fine-step simulation (tests/test_engine_exact.c). */
int sb_bb3_hit_sample(const gsl_rng *r, const double A[3], const double B[3],
                      double a, double sigma2, double t, double tol,
                      double *ta, double xa[3], sb_bb3_info *info);

#ifdef __cplusplus
}
#endif

#endif /* SMOLBRIDGE_ENGINE_BRIDGE_H */
