/* smolbridge/engine_firsthit.h — first-contact observer: the collision
 * kernel measured by counting the first detected contact of every pair.
 *
 * With the pass-through outcome (SB_OUTCOME_COUNT) the particles do not
 * interact, so every pair is an independent two-body problem whatever the
 * volume fraction.  The observer wraps a detector: it records the first
 * contact the detector reports for each pair (a set of pair ids) and
 * answers "no collision", so a pair is counted once.  Pairs in contact
 * when the observer is attached are entered first (they are not first
 * contacts); first contacts before a warm-up time t1 are recorded but
 * counted apart.
 *
 * Reference (the estimator of sb_engine_firsthit_kernel).  For a pair
 * placed uniformly outside the contact ball of radius R = r_a + r_b in a
 * box of volume V, in the continuum (diffusion) limit the absorption rate
 * of a perfectly absorbing sphere of radius a is
 *   k(t) = K (1 + a / sqrt(pi D t)),   K = 4 pi D a
 * (Smoluchowski 1917, Z. phys. Chem. 92:129, the time-dependent solution
 * of the diffusion equation outside an absorbing sphere), D the relative
 * diffusivity.  Integrated over (t1, t], with P the pairs apart at the
 * start (the box large against the relative displacement, so that the
 * torus is infinite space for every pair):
 *   E[hits] = P / (V - 4 pi R^3 / 3) K [(t - t1)
 *             + 2 a (sqrt t - sqrt t1) / sqrt(pi D)].
 * K = hits / (E[hits] / K) then has the interval of the count times the
 * same scale.  The count is a sum of rare events over pairs, nearly
 * Poisson when each particle makes few contacts; but the pairs that share
 * a particle share its path, so when each makes many (tens, in a run sized
 * for 10^4 contacts with a box that cannot shrink) the variance exceeds
 * the mean: by 1.21-1.68 (mean 1.42 over seven seeds) for 3670 spheres of
 * 2 um with ~22 contacts each (V2 in --full).  The observer estimates the variance from each
 * particle's count (counts.hits_var) and widens the Garwood interval by
 * sqrt(var / mean) where it exceeds 1.  For
 * Langevin particles a is the radius that the outer diffusion field sees
 * (R minus the Milne extrapolation length of the Klein-Kramers equation,
 * Burschka & Titulaer 1981, J. Stat. Phys. 25:569; docs/engine_bridge.md
 * §7): the caller passes it, or asks for the capacitance radius of the
 * measured kernel itself, a = K / (4 pi D) (SB_ENGINE_FIRSTHIT_CAPACITANCE:
 * Langevin spheres at any Knudsen number, whose absorber the outer
 * diffusion field sees with that radius).  E[hits] is then the quadratic
 *   E[hits] = P / (V - 4 pi R^3 / 3) [K (t - t1)
 *             + K^2 2 (sqrt t - sqrt t1) / (4 pi D sqrt(pi D))],
 * solved exactly for K, and the Garwood interval of the count maps through
 * the same increasing function.  The remainder O(tau_p / t) of the rate
 * integrates to O(tau_p log(t / t1)): a warm-up t1 of many tau_p keeps it
 * small.  3-D only (the transient is the 3-D one).
 *
 * Positions should be independent and uniform (overlaps allowed) for every
 * counted pair to start uniform outside the contact ball; a
 * non-overlapping filling carries the hard-sphere pair correlation into
 * the transient.
 *
 * Thread safety: an observer belongs to one engine; distinct observers
 * are independent.  Errors: status codes with a message in
 * sb_last_error(); nothing is printed.
 */
#ifndef SMOLBRIDGE_ENGINE_FIRSTHIT_H
#define SMOLBRIDGE_ENGINE_FIRSTHIT_H

#include <stddef.h>
#include <stdint.h>
#include <gsl/gsl_rng.h>
#include <smolbridge/common.h>
#include <smolbridge/engine.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Called at every counted first contact (at or after the warm-up end):
 *  the pair record and the contact fraction s of the detector (the time
 *  p->t0 + s p->dt).  Around the built-in SB_DETECT_LANGEVIN the
 *  particles' states at the contact are readable inside the call with
 *  sb_engine_contact_state (sb_engine_contact_vn).  Return 0, or a negative value to fail the
 *  step. */
typedef int (*sb_engine_firsthit_fn)(const sb_engine *e,
                                     const sb_engine_pair *p, double s,
                                     void *ctx);

/** Parameters of the observer (sb_engine_firsthit_params_default). */
typedef struct {
  /** Wrapped detector and its context; NULL: the built-in detector
   *  `builtin`. */
  sb_engine_detect_fn detect;
  void *detect_ctx;
  /** Built-in detector used when detect is NULL: SB_DETECT_BALLISTIC
   *  (default), SB_DETECT_OVERLAP or SB_DETECT_LANGEVIN. */
  sb_engine_detect builtin;
  /** 1: a pair whose first contact is already recorded is not passed to
   *  the detector again (less work; a stochastic detector then draws
   *  fewer random numbers, so the run differs from one with 0).  0 (the
   *  default): every candidate pair is passed to the detector. */
  int skip_seen;
  /** Optional callback at every counted first contact, with its
   *  context. */
  sb_engine_firsthit_fn on_hit;
  void *hit_ctx;
} sb_engine_firsthit_params;

/** Counts of one species pair (or of all pairs). */
typedef struct {
  uint64_t hits;        /**< first contacts at or after the warm-up end */
  uint64_t warm;        /**< first contacts before the warm-up end */
  uint64_t contact0;    /**< pairs in contact at attachment */
  double pairs_apart;   /**< pairs not in contact at attachment */
  /** Estimated variance of `hits` (m^0), from each particle's number of
   *  counted first contacts: hits is a sum over pairs, and two pairs that
   *  share a particle are correlated through its path (a particle that
   *  wanders far meets more partners), so var(hits) exceeds the Poisson
   *  value hits when particles make many contacts each.  The unbiased
   *  U-statistic estimate (Hoeffding 1948) for pairs of one species pair:
   *  sum over both sides of sum_i (h_i - mean h)^2 - hits (1 - p), with
   *  h_i particle i's contacts with the other side and p = hits / pairs
   *  (independent particles: disjoint pairs are independent), divided by
   *  the factor that removes its bias (sb_pair_count_variance, with one
   *  contact per pair).  Variances of
   *  independent runs add.  NaN where unknown (several species pooled in
   *  SB_ENGINE_FIRSTHIT_ALL); 0 in counts assembled by hand: the
   *  estimator then takes the Poisson value. */
  double hits_var;
} sb_engine_firsthit_counts;

/** Reference radius for the capacitance radius K / (4 pi D) of the
 *  measured kernel (sb_engine_firsthit_kernel). */
#define SB_ENGINE_FIRSTHIT_CAPACITANCE 0.0

/** Kernel estimate (sb_engine_firsthit_kernel, sb_engine_firsthit_estimate).
 *  The inputs are c, radius, D, t1, t and veff. */
typedef struct {
  sb_engine_firsthit_counts c;
  double radius;          /**< reference radius given, m, or
                               SB_ENGINE_FIRSTHIT_CAPACITANCE */
  double a;               /**< radius used: `radius`, or K / (4 pi D) */
  double D;               /**< relative diffusivity, m^2/s */
  double t1, t;           /**< counting interval, s */
  double veff;            /**< V - 4 pi R^3 / 3, m^3 */
  double expected_per_K;  /**< E[hits] / K at the estimate, s/m^3 */
  double K;               /**< hits / expected_per_K, m^3/s */
  double dispersion;      /**< c.hits_var / c.hits (1: Poisson), or NaN
                               where unknown (no hits, hits_var 0 or NaN) */
  double lo, hi;          /**< interval at `level`: the exact (Garwood)
                               interval of the count, widened about it by
                               sqrt(dispersion) where dispersion > 1 (then
                               approximate: quasi-Poisson), mapped through
                               the estimator */
} sb_engine_firsthit_kernel_result;

typedef struct sb_engine_firsthit sb_engine_firsthit;

/** Any species pair (sb_engine_firsthit_get). */
#define SB_ENGINE_FIRSTHIT_ALL ((size_t)-1)

/** Defaults: the built-in ballistic detector, every candidate detected,
 *  no callback. */
void sb_engine_firsthit_params_default(sb_engine_firsthit_params *p);

/** New observer (not attached).  NULL on a bad parameter (SB_EINVAL) or
 *  allocation failure (SB_ENOMEM), see sb_last_error(). */
sb_engine_firsthit *sb_engine_firsthit_alloc(
    const sb_engine_firsthit_params *p);

/** Free the observer (NULL is allowed).  Detach it first (install another
 *  detector) if the engine runs on. */
void sb_engine_firsthit_free(sb_engine_firsthit *f);

/** Attach to engine e with the detector's neighbour reach (m, >= 0; the
 *  bridge detectors and a wrapped Langevin detector need theirs,
 *  sb_engine_bridge_reach, sb_engine_langevin_reach): record the pairs in
 *  contact now (|x_i - x_j| <= r_i + r_j, minimum image), count the
 *  particles of each species, and install the counting detector
 *  (sb_engine_set_detector).  Around a built-in (detect NULL) the
 *  engine's detector becomes that built-in itself, observed (reach is
 *  then unused: the built-in has its own): it hands the observer each
 *  record's first contact, with its own neighbour search (the Verlet
 *  list of the chord detectors, the Langevin search) and its first pass
 *  on all of the engine's threads (`langevin`: with the engine's
 *  counter-based streams, sb_engine_params.streams, the default), the
 *  same counts and contacts in the same order on any number of them (the
 *  observer counts serially, in record order); with `langevin`, on_hit
 *  may read the particles' states at the contact with
 *  sb_engine_contact_state or sb_engine_contact_vn.  The engine's outcome should be
 *  SB_OUTCOME_COUNT.  An observer attaches once (SB_EINVAL otherwise);
 *  the observer must outlive the engine's use of it. */
int sb_engine_firsthit_attach(sb_engine *e, sb_engine_firsthit *f,
                              double reach);

/** Save the state of an attached observer to `path` (native binary,
 *  portable between builds of the same type sizes and endianness): the
 *  pairs seen, the counts and sums, the warm-up end, the particles per
 *  species at the attachment, and the step engine e is at.  Save it
 *  beside a checkpoint of the same engine at the same step
 *  (sb_engine_checkpoint_save): the pair ids of both must match.
 *  SB_EINVAL (not attached), SB_EIO (cannot write; no file is left). */
int sb_engine_firsthit_save(const sb_engine_firsthit *f, const sb_engine *e,
                            const char *path);

/** Restore a saved state into a new observer f, before it is attached
 *  (then sb_engine_firsthit_attach keeps these counts instead of starting
 *  afresh, and fails with SB_EINVAL unless the engine is at the saved
 *  step: load both from the same checkpoint).  f's parameters must watch
 *  the same detector (custom, or the same built-in) with the same
 *  skip_seen; set detect, on_hit and their contexts again (callbacks are
 *  not saved).  With the engine restored from its checkpoint, the run
 *  then goes on bit for bit as if it had not stopped (the same draws: the
 *  engine's generator state is in its checkpoint).  SB_EINVAL (attached,
 *  another detector or skip_seen), SB_EIO (cannot open), SB_EFORMAT (not
 *  an observer file, truncated, from another build, or damaged: the file
 *  ends in a hash of its contents, format SBFHIT02, checked before
 *  anything is read; SBFHIT01 files, without it, still load); f is
 *  unchanged on failure. */
int sb_engine_firsthit_load(sb_engine_firsthit *f, const char *path);

/** End of the warm-up, s (default 0): first contacts before t1 are
 *  counted in `warm`, not in `hits`. */
int sb_engine_firsthit_set_warmup(sb_engine_firsthit *f, double t1);
double sb_engine_firsthit_warmup(const sb_engine_firsthit *f);

/** Counts of species pair (a, b) (a, b < SB_ENGINE_PAIR_SPECIES, in any
 *  order; species without particles give zeros), or of all pairs with
 *  a = b = SB_ENGINE_FIRSTHIT_ALL (particles of species beyond
 *  SB_ENGINE_PAIR_SPECIES count there only).  SB_EINVAL otherwise or if the observer
 *  is not attached. */
int sb_engine_firsthit_get(const sb_engine_firsthit *f, size_t a, size_t b,
                           sb_engine_firsthit_counts *c);

/** The kernel of species pair (a, b) from the counts up to the engine's
 *  time, by the estimator of the file comment: reference radius `radius`
 *  (m, > 0; the contact distance r_a + r_b for pure diffusion; or
 *  SB_ENGINE_FIRSTHIT_CAPACITANCE), relative diffusivity D (m^2/s, > 0),
 *  interval level in (0, 1).  3-D engines only (SB_EINVAL in 2-D).
 *  SB_EDOM (the counts still set, K = lo = hi = NaN) when the exposure is
 *  not positive (no pair apart, or no time after the warm-up). */
int sb_engine_firsthit_kernel(const sb_engine_firsthit *f,
                              const sb_engine *e, size_t a, size_t b,
                              double radius, double D, double level,
                              sb_engine_firsthit_kernel_result *k);

/** The estimator alone, from the inputs in *k (c.hits, c.hits_var,
 *  c.pairs_apart, radius, D, t1, t, veff; e.g. the counts of a run kept
 *  after its engine is freed, or of independent runs added up): sets a,
 *  expected_per_K, K, dispersion, lo, hi.  Status as
 *  sb_engine_firsthit_kernel. */
int sb_engine_firsthit_estimate(sb_engine_firsthit_kernel_result *k,
                                double level);

/** The forward map of the estimator: E[hits] = c1 K + c2 K^2 for a kernel
 *  K (c2 = 0 for a given radius), from the inputs in *k.  SB_EDOM when the
 *  inputs give no exposure. */
int sb_engine_firsthit_coefs(const sb_engine_firsthit_kernel_result *k,
                             double *c1, double *c2);

/** Normal relative velocity (m/s; < 0: approach) of pair p at a contact
 *  on its straight chord at fraction s of the record's interval: the
 *  direction dx0 + s dd, the velocities interpolated linearly between the
 *  step's start and end (sb_engine_start_velocities, sb_engine_velocities;
 *  right where dt << tau_p).  For a detector's hit callback (contact-time
 *  detection); the `langevin` detector's contact velocities come from
 *  sb_engine_contact_vn. */
double sb_engine_chord_vn(const sb_engine *e, const sb_engine_pair *p,
                          double s);

/** Normal relative velocity (m/s; < 0: approach) at the contact the
 *  `langevin` built-in drew, inside the on_hit callback of an observer
 *  around it (or inside an outcome): (u_i - u_j).(x_i - x_j)/|x_i - x_j|
 *  with the states of sb_engine_contact_state (|x_i - x_j| = r_i + r_j).
 *  NaN (and sb_last_error set) where no contact state is available. */
double sb_engine_contact_vn(const sb_engine *e);

#ifdef __cplusplus
}
#endif

#endif /* SMOLBRIDGE_ENGINE_FIRSTHIT_H */
