/* smolbridge/engine.h — Lagrangian collision engine (SI units).
 *
 * Particles in a periodic box (2-D or 3-D, cube or rectangle) are moved by
 * the exact Langevin step of <smolbridge/langevin.h> (or by free flight,
 * tau = +inf, for molecules), pairs that can collide during a step are
 * found by an O(N) neighbour search (linked cells, or the sort-and-sweep of
 * Thomine 2008, §4.1, with the per-particle anisotropic reach of its
 * §5.1), a
 * detector decides whether and when each candidate pair touches (overlap at
 * step end, Sundaram & Collins 1996; or the exact contact time of the
 * straight-line relative motion, Thomine 2008, §4.2; Mohaupt 2011,
 * App. F), the
 * events are processed earliest-first, and an outcome is applied (elastic
 * with energy-loss factor eta, Thomine 2008, §4.3-4.4; or "reinsert", which
 * removes one partner and puts it back at random to keep the concentration
 * constant, Mohaupt 2011, §5.3.2).  Observers count collisions and estimate
 * the collision kernel with an exact Poisson interval.
 *
 * Theory, derivations, every parameter and its unit: docs/engine.md.
 *
 * One step of length dt (sb_engine_step):
 *  1. x0 <- x, u0 <- u; the fluid velocity U_s is evaluated at x0 (callback);
 *  2. transport: exact Langevin step per particle (sb_langevin_step3_coef,
 *     one coefficient set per species); x is the unwrapped end position and
 *     disp = x - x0 the displacement over the step (the "chord");
 *  3. neighbour search on (x0, disp): a superset of the pairs whose
 *     straight segments x0 + s disp (0 <= s <= 1) come within r_i + r_j
 *     (+ the detector's extra reach);
 *  4. the detector is called for every candidate pair and returns the
 *     contact fraction s in [0, 1] of the step (or "no collision"); the
 *     Langevin detector (SB_DETECT_LANGEVIN) samples it from the exact
 *     conditional law of both particles' paths between their states at
 *     the two ends of the step, with the states at contact;
 *  5. events are processed earliest first (ties by (i, j)); when an
 *     outcome changes the end of a particle's step (elastic bounce,
 *     reinsertion, merge), its path from the contact on is a new straight
 *     piece to its new end, its pending events are void, and every pair it
 *     forms is examined again over the rest of the step, so a particle can
 *     take part in several collisions in one step, in time order.  The
 *     built-in detectors always re-examine; a custom detector does when
 *     sb_engine_set_redetect allows it (its record then covers the rest of
 *     the step, see sb_engine_pair); otherwise the void events are dropped
 *     and counted in sb_engine_stats.dropped;
 *  6. positions are wrapped into the box, time advances by dt.
 * Given the seed and the same calls, a run is bit-identical (the engine
 * owns its generator, Philox4x32-10 by default, and the transport draws
 * from counter-based streams keyed by (seed, particle id, step); a
 * checkpoint stores the generator's state).
 *
 * Thread safety: an engine object must not be used by two threads at once;
 * distinct engines are independent (no global state).
 * Errors: functions return SB_SUCCESS or a status code with a message in
 * sb_last_error() that names the public function called; nothing is
 * printed; on error the state is unchanged unless stated.  A NULL engine
 * (or context, observer, field) or a NULL pointer argument that is not
 * documented as optional is SB_EINVAL: functions that return a value
 * instead of a status then return their failure value (NULL, NaN, 0, or
 * -1 for the detectors) and record SB_EINVAL; void functions record it.
 */
#ifndef SMOLBRIDGE_ENGINE_H
#define SMOLBRIDGE_ENGINE_H

#include <stddef.h>
#include <stdint.h>
#include <gsl/gsl_rng.h>
#include <smolbridge/common.h>
#include <smolbridge/langevin_hit.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Maximum number of family tags (0 .. SB_ENGINE_MAXFAM-1) for per-family
 *  collision counts. */
#define SB_ENGINE_MAXFAM 8

/** Species 0 .. SB_ENGINE_PAIR_SPECIES-1 get per-species-pair collision
 *  counts and kernels (sb_engine_pair_kernel). */
#define SB_ENGINE_PAIR_SPECIES 16

/** Neighbour-search method (all return a superset of the pairs that can
 *  collide during the step; docs/engine.md §neighbours). */
typedef enum {
  SB_NEIGH_CELLS = 0,  /**< linked cells, cell edge >= cut-off, O(N) */
  SB_NEIGH_SWEEP = 1,  /**< sort along x and sweep, anisotropic reach */
  SB_NEIGH_BRUTE = 2   /**< all N(N-1)/2 pairs (reference, O(N^2)) */
} sb_engine_neigh;

/** Built-in detectors. */
typedef enum {
  SB_DETECT_BALLISTIC = 0,  /**< exact contact time of the chords */
  SB_DETECT_OVERLAP = 1,    /**< overlap at step end (contact time then
                                 taken from the chords' entry root) */
  SB_DETECT_CUSTOM = 2,     /**< user callback, sb_engine_set_detector */
  SB_DETECT_LANGEVIN = 3    /**< first contact sampled from the exact
                                 conditional law of the pair's Langevin
                                 paths between the step's end states,
                                 valid at every dt/tau_p
                                 (sb_engine_set_langevin;
                                 docs/engine_langevin.md) */
} sb_engine_detect;

/** Built-in outcomes. */
typedef enum {
  SB_OUTCOME_ELASTIC = 0,   /**< elastic with energy-loss factor eta */
  SB_OUTCOME_REINSERT = 1,  /**< reinsert the partner of higher id at
                                 random (sb_engine_outcome_reinsert) */
  SB_OUTCOME_COUNT = 2,     /**< count only, particles pass through; with
                                 SB_DETECT_LANGEVIN every entry into
                                 contact counts, also re-entries inside
                                 a step (docs/engine.md §4) */
  SB_OUTCOME_CUSTOM = 3     /**< user callback, sb_engine_set_outcome */
} sb_engine_outcome;

/** Built-in fluid velocity fields U_s (seen by the particles). */
typedef enum {
  SB_FLUID_REST = 0,      /**< U_s = 0 */
  SB_FLUID_UNIFORM = 1,   /**< U_s = (p[0], p[1], p[2]) m/s */
  SB_FLUID_SHEAR = 2,     /**< U_s,x = p[0] (y - L_y/2), p[0] in 1/s; the box
                               is plainly periodic unless Lees-Edwards
                               images are on (sb_engine_set_lees_edwards) */
  SB_FLUID_CALLBACK = 3   /**< user callback */
} sb_engine_fluid;

/** Engine parameters (sb_engine_params_default fills the defaults). */
typedef struct {
  int dim;                   /**< 2 or 3 (default 3) */
  double L[3];               /**< box edge lengths, m, > 0 (L[2] unused in
                                  2-D); default 1e-4 */
  double dt;                 /**< time step, s, > 0 (default 1e-6) */
  unsigned long seed;        /**< generator seed (default 1) */
  const gsl_rng_type *rng_type; /**< generator type (default
                                  sb_rng_philox, smolbridge/rng.h; NULL
                                  means gsl_rng_mt19937, the generator of
                                  the validation cases).  Any gsl_rng type
                                  works; the choice changes the draws, not
                                  the law */
  size_t capacity;           /**< maximum number of particles (default
                                  1024) */
  sb_engine_neigh neigh;     /**< default SB_NEIGH_CELLS */
  sb_engine_detect detect;   /**< default SB_DETECT_BALLISTIC */
  sb_engine_outcome outcome; /**< default SB_OUTCOME_ELASTIC */
  double eta;                /**< energy-loss factor in [0, 1]: fraction of
                                  the normal relative kinetic energy kept
                                  (restitution e = sqrt(eta)); default 1 */
  size_t sample_every;       /**< time-series sample every this many steps
                                  (0: never); default 0 */
  size_t sort_every;         /**< reorder the particles in memory by cell
                                  every this many steps (0: never, the
                                  default).  Speeds up large systems
                                  (cache locality) but particle indices
                                  change: follow particles by id. */
  int streams;               /**< 1: the Langevin transport draws particle
                                  i's six normals at step k from the
                                  counter-based stream (seed, id_i, k)
                                  (smolbridge/rng.h, docs/rng.md) instead
                                  of the engine's generator: a particle's
                                  motion then depends on (seed, id, step)
                                  alone, not on the particle order, and
                                  transport runs on all threads (the
                                  default: 28 ns per 3-D particle-step
                                  against 62 ns with MT19937 draws,
                                  bench_langevin).  With it, the
                                  Langevin detector (SB_DETECT_LANGEVIN)
                                  draws each record's path from a stream
                                  of its own, keyed by (seed, step, pass,
                                  both particles' ids), and its first
                                  pass runs on all threads
                                  (docs/engine_langevin.md §5).  0: from
                                  the generator, in particle (record)
                                  order.  Everything else (placement,
                                  outcomes, custom detectors) uses the
                                  engine's generator in a fixed order. */
  int threads;               /**< threads of the parallel parts of a step
                                  (OpenMP builds: transport with streams,
                                  wrapping, the first detection pass of
                                  the deterministic detectors, and of
                                  the Langevin detector with streams);
                                  0 (the
                                  default): the OpenMP default
                                  (OMP_NUM_THREADS).  The results are
                                  bit-identical for any value. */
  int verlet_off;            /**< 0 (the default): with the cells search
                                  in a fully periodic box, the candidate
                                  pairs come from a Verlet list kept over
                                  several steps (skin = r_max, rebuilt
                                  when a particle has moved half of it;
                                  used when a step moves particles less
                                  than r_max/20); for the detectors that
                                  may draw in candidate order (langevin,
                                  bridges, custom) in the cell scan's
                                  order.  The candidates and the results
                                  are the same as without it, bit for bit
                                  (docs/engine.md, "Neighbour search").
                                  1: rebuild the cells at every step. */
  int lsearch_off;           /**< 0 (the default): with the cells search
                                  and the `langevin` detector in a fully
                                  periodic box, the candidates come from a
                                  search over the chord midpoints that
                                  drops most pairs the detector's chord
                                  test would skip; the detector examines
                                  the same pairs in the same order and the
                                  results are the same bit for bit, only
                                  the candidate count (ncand) is smaller
                                  (docs/engine.md, "Neighbour search").
                                  1: every pair of the linked cells. */
} sb_engine_params;

/** A species: shared physical properties of a class of particles. */
typedef struct {
  double radius;  /**< m, > 0 */
  double mass;    /**< kg, > 0 */
  double tau;     /**< relaxation time tau_p, s, > 0; +INFINITY = free
                       flight (molecules: x += u dt, no noise) */
  double B;       /**< velocity-diffusion coefficient, m s^-3/2, >= 0
                       (ignored if tau = inf) */
  double T;       /**< temperature, K, >= 0: equilibrium velocity variance
                       k_B T / m per component for initial and reinserted
                       velocities; T = 0 uses B^2 tau / 2 instead */
} sb_engine_species;

/** State of a candidate pair handed to a detector / outcome.  The record
 *  covers the interval [t0, t0 + dt]: the whole step, or, after a
 *  collision inside the step changed the path of i or j, the rest of the
 *  step from that collision on (the detector's contact fraction s is then
 *  a fraction of this interval: the contact happens at t0 + s dt). */
typedef struct {
  size_t i, j;     /**< particle indices, i < j */
  double dx0[3];   /**< x_i - x_j at t0 (minimum image), m */
  double dd[3];    /**< change of x_i - x_j over the interval, m */
  double sigma;    /**< contact distance r_i + r_j, m */
  double dt;       /**< length of the interval, s (the step, or less) */
  double t0;       /**< time at its start, s */
} sb_engine_pair;

typedef struct sb_engine sb_engine;

/** Detector callback: decide whether the pair collides during the step.
 *  Return 1 and set *s (contact fraction of the step, in [0, 1]) for a
 *  collision, 0 for none, or a negative value for an error (the step then
 *  fails with SB_EINVAL).  r is the engine's generator (stochastic
 *  detectors draw from it; candidates come in a deterministic order).
 *  The detector may read the engine through the accessors below
 *  (sb_engine_start_velocities, sb_engine_velocities, ...). */
typedef int (*sb_engine_detect_fn)(const sb_engine *e,
                                   const sb_engine_pair *p, const gsl_rng *r,
                                   void *ctx, double *s);

/** Outcome callback: apply the collision of pair p at fraction s.  It may
 *  call sb_engine_outcome_elastic / sb_engine_outcome_reinsert (and the
 *  other sb_engine_outcome_* functions); sb_engine_step, _run_until,
 *  _set_dt, _add_particle, _fill_*, _flush_removals and _sort return
 *  SB_EINVAL inside a step.  Return a status (non-zero aborts the step
 *  with that status). */
typedef int (*sb_engine_outcome_fn)(sb_engine *e, const sb_engine_pair *p,
                                    double s, void *ctx);

/** Fluid callback: fill us[3i..3i+2] (m/s) for the n positions
 *  x[3i..3i+2] (m, inside the box); return a status.  A non-zero status,
 *  or a velocity component that is not finite (of the dim components),
 *  is SB_EINVAL from the function that called it, the message naming the
 *  callback, the particle (or "a new particle": fills, arrivals) and the
 *  component; a step that fails so is undone (every particle back at its
 *  start of step), a fill adds nothing. */
typedef int (*sb_engine_fluid_fn)(size_t n, const double *x, double *us,
                                  void *ctx);

/* ============================================================ life cycle */

/** Fill *p with the defaults listed in sb_engine_params. */
void sb_engine_params_default(sb_engine_params *p);

/** New engine (no particle, no species; time 0).  NULL on a bad parameter
 *  (SB_EINVAL) or allocation failure (SB_ENOMEM), see sb_last_error(). */
sb_engine *sb_engine_alloc(const sb_engine_params *p);

/** Free the engine (NULL is allowed). */
void sb_engine_free(sb_engine *e);

/** The parameters the engine runs with. */
const sb_engine_params *sb_engine_get_params(const sb_engine *e);

/** Add a species; *idx (may be NULL) receives its index.  SB_EINVAL on a
 *  bad field; SB_ERANGE where a step coefficient (sb_langevin_coef_init
 *  at the engine's dt) or the stationary velocity spread B sqrt(tau / 2)
 *  (T = 0) exceeds DBL_MAX (the spread is taken as sqrt(B^2 tau / 2) or
 *  sqrt(k_B T / mass) where that variance is a normal double, otherwise
 *  with the square roots first).  Species are kept for the life of the
 *  engine. */
int sb_engine_add_species(sb_engine *e, const sb_engine_species *s,
                          size_t *idx);

/** Add one particle of species `species` with family tag `family` (0 ..
 *  SB_ENGINE_MAXFAM-1) at position x (m, wrapped into the box) with velocity
 *  u (m/s); in 2-D x[2], u[2] are ignored (set to 0).  No overlap check
 *  (see sb_engine_check_overlaps).  SB_EINVAL when the capacity is full or
 *  an argument is bad: x or u not finite, or a coordinate more than 2^26
 *  box lengths from the box (|x_k| >= 2^26 L_k, where the wrapped
 *  coordinate would keep fewer than half of a double's digits; x = 1.7e308
 *  m in a box of 1e-4 m was stored as -inf).  The wrapped coordinate is
 *  in [0, L_k), within about ulp(x_k) of x_k mod L_k. */
int sb_engine_add_particle(sb_engine *e, size_t species, int family,
                           const double x[3], const double u[3]);

/** Add n particles of a species at uniformly random positions that do not
 *  overlap any particle, with equilibrium (Maxwellian) velocities
 *  U_s(x) + N(0, vvar) per component, plus the species' settling velocity
 *  under gravity (sb_engine_set_gravity); ids follow on from the last one.
 *  All or nothing: SB_EMAXITER if a position cannot be found in 10000
 *  tries (box too full) or a settling velocity cannot be found,
 *  SB_EINVAL for a bad argument, a failing fluid callback or one that
 *  returns a velocity that is not finite, SB_ERANGE (as a reinsertion's
 *  draw in sb_engine_step; it was SB_EINVAL) for a drawn velocity that is
 *  not finite (the message names the cause: the species' velocity
 *  spread, the settling velocity, their sum, or the drift of
 *  sb_engine_fill_box), SB_EINVAL for settings
 *  sb_engine_step would refuse that the settling velocities depend on
 *  (gravity with a free-flight species, Lees-Edwards boundaries without
 *  the shear field), SB_ENOMEM; on any failure the engine holds exactly the
 *  particles it had (same order, states and id counter) and only its
 *  generator has advanced. */
int sb_engine_fill_random(sb_engine *e, size_t species, int family,
                          size_t n);

/** As sb_engine_fill_random (all or nothing), inside the region
 *  lo[k] <= x_k < hi[k] (m, 0 <= lo < hi <= L), with `drift` (m/s, may be
 *  NULL) added to the equilibrium velocities (jets, beams). */
int sb_engine_fill_box(sb_engine *e, size_t species, int family, size_t n,
                       const double lo[3], const double hi[3],
                       const double drift[3]);

/** Remove the mean velocity (globally) and
 *  rescale velocities so that the total kinetic energy in the
 *  centre-of-mass frame equals dim (N - 1) k_B T / 2 for the given T [K]
 *  (T <= 0: no rescaling).  For molecular-dynamics (free-flight) runs. */
int sb_engine_thermalize(sb_engine *e, double T);

/* ============================================================ settings */

int sb_engine_set_neigh(sb_engine *e, sb_engine_neigh m);
/** Built-in detector (not SB_DETECT_CUSTOM). */
int sb_engine_set_detect(sb_engine *e, sb_engine_detect d);
/** Custom detector; `reach` (m, >= 0) widens the neighbour search by this
 *  much beyond the straight segments (a stochastic detector can detect
 *  pairs whose chords stay apart). */
int sb_engine_set_detector(sb_engine *e, sb_engine_detect_fn fn, void *ctx,
                           double reach);
/** Declare (on = 1) that the custom detector set last leaves every record
 *  at the start of a step whose chord stays beyond sigma + rho
 *  (rho = sb_engine_langevin_reach) alone: it returns 0 without drawing
 *  or changing anything, as sb_engine_detect_langevin and
 *  sb_engine_langevin_contact do (wrappers around them; the
 *  first-contact observer with the `langevin` built-in declares it
 *  itself).  The
 *  Langevin search of the cells (sb_engine_params.lsearch_off) then
 *  serves it as it serves `langevin`: the same run, fewer candidates.
 *  Off again whenever a detector is set. */
int sb_engine_set_detector_chord(sb_engine *e, int on);
/** Whether a custom detector is called again, on the rest of the step,
 *  for the pairs of a particle whose path an outcome changed (on = 1).
 *  Off by default: allow it when the detector decides from the pair
 *  record alone (dx0, dd, dt: chord-type and position-end bridge
 *  detectors; the partner's position at the collision time is then its
 *  chord point).  Built-in detectors always re-detect. */
int sb_engine_set_redetect(sb_engine *e, int on);
/** Built-in outcome (not SB_OUTCOME_CUSTOM); eta in [0, 1]. */
int sb_engine_set_outcome(sb_engine *e, sb_engine_outcome o, double eta);
int sb_engine_set_outcome_fn(sb_engine *e, sb_engine_outcome_fn fn,
                             void *ctx);
/** Built-in fluid field with parameters p[3] (see sb_engine_fluid). */
int sb_engine_set_fluid(sb_engine *e, sb_engine_fluid f, const double p[3]);
int sb_engine_set_fluid_fn(sb_engine *e, sb_engine_fluid_fn fn, void *ctx);
/** The fluid the engine runs with (as set, or as a checkpoint restored
 *  it): the field f, its parameters p[3] (zeros for SB_FLUID_REST and
 *  SB_FLUID_CALLBACK) and whether the Lees-Edwards images are on (*lees =
 *  1, sb_engine_set_lees_edwards).  A checkpoint keeps the built-in
 *  fields; one saved with a callback loads as SB_FLUID_REST.  Any output
 *  may be NULL.  SB_EINVAL for a NULL engine. */
int sb_engine_get_fluid(const sb_engine *e, sb_engine_fluid *f, double p[3],
                        int *lees);
/** Time-series sampling period in steps (0: off). */
int sb_engine_set_sample_every(sb_engine *e, size_t every);
/** Threads of the parallel parts (see sb_engine_params.threads; 0: the
 *  OpenMP default).  SB_EINVAL outside 0..4096. */
int sb_engine_set_threads(sb_engine *e, int threads);
/** Change the time step (s, > 0) and every species' step coefficients.
 *  SB_EINVAL for dt not finite > 0 (or a species with no Langevin step at
 *  dt); SB_ERANGE, naming the species, where a step coefficient
 *  (sb_langevin_coef_init at dt) exceeds DBL_MAX (as sb_engine_add_species
 *  refuses such a species).  On failure dt and the coefficients are
 *  unchanged. */
int sb_engine_set_dt(sb_engine *e, double dt);

/* ============================================================ run */

/** One step (see the file comment).  Errors: SB_EINVAL if a particle's
 *  reach (displacement + radii) is not below half the box (step too large,
 *  also where the displacement's length overflows a double; "non-finite
 *  displacement" only where a component is not finite), checked for a
 *  single particle as for more (it is not wrapped into the box), a
 *  callback failed, the fluid callback returned a velocity that is not
 *  finite (naming the particle), or the detector returned an error;
 *  SB_ERANGE if the transport, the nonlinear drag step (also a particle's
 *  after a collision of the Langevin detector) or the exact shear step
 *  (Lees-Edwards) gave a particle an infinite or NaN position or velocity
 *  (B sqrt(tau), the state or the fluid velocity near DBL_MAX), naming
 *  the particle; SB_ERANGE also if a reinsertion (SB_OUTCOME_REINSERT,
 *  SB_DEPOSIT_REINSERT) drew an infinite or NaN velocity, or its flight
 *  over the rest of the step or an inflow arrival's flight left the
 *  doubles or landed too far out to be wrapped into the box (2^26 box
 *  lengths, as sb_engine_add_particle) (the message names the cause: the
 *  species' velocity spread, the settling velocity, or their sum): that
 *  particle is not placed; SB_ENOMEM; SB_EMAXITER if a reinsertion found
 *  no free place.  After these SB_ERANGE, after the fluid callback's
 *  SB_EINVAL and after a built-in outcome's (reinsertion) or a wall
 *  reinsertion's error every particle keeps its position and velocity
 *  from before the step (the collision tallies of the events already
 *  processed are kept, the generator has advanced); an arrival's error
 *  comes after the step (the particles before it are placed).  After any
 *  other error the state is undefined (restore a checkpoint). */
int sb_engine_step(sb_engine *e);

/** Reorder the particles in memory along the cells of a grid (cell
 *  edge ~ mean spacing), for cache locality; indices change, ids do not.
 *  Called automatically every params.sort_every steps. */
int sb_engine_sort(sb_engine *e);

/** Step until the time reaches t_end (s): while t < t_end - dt/2.  A
 *  failing step's status is returned, its message recorded after this
 *  function's name and the time the step started from. */
int sb_engine_run_until(sb_engine *e, double t_end);

/* ======================================================= outcomes (API) */

/** Elastic collision of pair p at contact fraction s with the engine's
 *  eta: along the contact normal n (from x_j to x_i at contact) the
 *  relative chord velocity w_n = (w_i - w_j).n becomes -sqrt(eta) w_n,
 *  momentum conserved (impulses m_i dw_i = -m_j dw_j); the same impulse is
 *  applied to the particle velocities u; end positions re-advanced after
 *  the contact: x += (1 - s) dt dw.  Pairs that separate (w_n >= 0) are
 *  left unchanged. */
int sb_engine_outcome_elastic(sb_engine *e, const sb_engine_pair *p,
                              double s);

/** Reinsert particle p->j at a uniformly random non-overlapping position
 *  with an equilibrium velocity (the partner i is untouched).  j stays at
 *  that place for the rest of the step. */
int sb_engine_outcome_reinsert(sb_engine *e, const sb_engine_pair *p,
                               double s);

/** For an outcome callback that changes where partner k (p->i or p->j)
 *  ends the step: declare its position x (m, any image) at the collision
 *  time; the engine then takes its path for the rest of the step as the
 *  straight line from x to its new end, and examines its pairs again
 *  from there.  Without a declaration a custom outcome's change is taken
 *  as a jump: the particle is at its new end from the collision on. */
int sb_engine_outcome_path(sb_engine *e, size_t k, const double x[3]);

/** Inside a detector or outcome callback: the position (m, unwrapped
 *  frame of the particle's start of step) of particle k at time t on its
 *  current straight piece of the step (the chord, or the piece it got
 *  after a collision earlier in the step).  SB_EINVAL outside a step or
 *  for a t before that piece. */
int sb_engine_position_at(const sb_engine *e, size_t k, double t,
                          double x[3]);

/* ======================================================= neighbours */

/** Candidate pairs for the trial straight-line step x -> x + disp from
 *  the current positions (disp: 3n values in m, NULL for zero), with
 *  `reach` (m) of extra distance, by method m.  *pairs receives 2*npairs
 *  indices (i < j for each pair; the array belongs to the engine and
 *  stays valid until the next call or step).  Used by the tests and the
 *  benchmarks; sb_engine_step calls the same code. */
int sb_engine_neighbours(sb_engine *e, sb_engine_neigh m, const double *disp,
                         double reach, size_t *npairs, const size_t **pairs);

/** Exact test used by the tests: 1 if the segments x_i + s disp_i and
 *  x_j + s disp_j (s in [0,1], minimum image at the start; disp: 3n
 *  values in m, NULL for zero) come within r_i + r_j + reach, else 0.
 *  -SB_EINVAL (negative, message in sb_last_error()) for a NULL engine, i
 *  or j not a particle, i == j, or reach not finite >= 0. */
int sb_engine_pair_can_meet(const sb_engine *e, const double *disp,
                            double reach, size_t i, size_t j);

/* ======================================================= detectors (API) */

/** Relative tolerance on sigma^2 below which a pair counts as touching
 *  (not overlapping) at the start of a step. */
#define SB_ENGINE_TOUCH 1e-9

/** Ballistic detector: smallest root s in [0, 1] of |dx0 + s dd| = sigma
 *  (approaching pairs only); a pair touching or overlapping at the start
 *  and approaching collides at s = 0.  With the pass-through outcome
 *  (SB_OUTCOME_COUNT) the engine skips pairs overlapping at the start
 *  (|dx0|^2 < sigma^2 (1 - SB_ENGINE_TOUCH)) before calling this
 *  detector or the overlap one, so each contact is counted once (the
 *  Langevin detector instead follows such a pair to its exit and counts
 *  its next entries).  Returns 1/0 as sb_engine_detect_fn. */
int sb_engine_detect_ballistic(const sb_engine_pair *p, double *s);

/** MD-type detector (Mohaupt 2011, §3.1.2, App. F), a custom detector
 *  (sb_engine_set_detector, or the first-contact observer's detect): the
 *  ballistic contact time of the straight motion x + u dt with the
 *  velocities at the start of the step (sb_engine_start_velocities)
 *  instead of the displacement chords.  Right when dt << tau_p; in the
 *  diffusive regime it overestimates the kernel (the thesis' finding,
 *  validation case V3/diffusive-fail).  Its neighbour reach must cover
 *  |u_i - u_j| dt (the chords do not).  ctx unused; -1 without start
 *  velocities. */
int sb_engine_detect_md(const sb_engine *e, const sb_engine_pair *p,
                        const gsl_rng *r, void *ctx, double *s);

/** A custom detector that never reports a contact (returns 0): particles
 *  pass through each other while the walls still act (deposition without
 *  particle-particle detection; `smolbridge collide` [run] detect =
 *  none).  Set it with reach 0. */
int sb_engine_detect_none(const sb_engine *e, const sb_engine_pair *p,
                          const gsl_rng *r, void *ctx, double *s);

/** Overlap detector: collision iff |dx0 + dd| < sigma; *s is then the
 *  entry root of the chords (0 if they overlapped at the start). */
int sb_engine_detect_overlap(const sb_engine_pair *p, double *s);

/* ================================================ Langevin detector */

/** Parameters of SB_DETECT_LANGEVIN (sb_engine_langevin_params_default). */
typedef struct {
  double eps;   /**< probability budget per pair and step of the pruning
                     (sb_langevin_hit_params.eps), in (0, 0.1]; default
                     1e-6 */
  double xtol;  /**< position resolution of the contact relative to
                     r_i + r_j, in (0, 0.01]; default 1e-6 */
  double tol;   /**< neighbour reach: expected contacts missed per
                     particle per step (sb_langevin_reach), in (0, 1);
                     default 1e-9 */
} sb_engine_langevin_params;

void sb_engine_langevin_params_default(sb_engine_langevin_params *p);

/** Set the parameters of the Langevin detector (whether or not it is the
 *  engine's detector now); checkpoints keep them.  SB_EINVAL on a bad
 *  value. */
int sb_engine_set_langevin(sb_engine *e, const sb_engine_langevin_params *p);
/** The parameters in use (the defaults, those set, or a checkpoint's). */
int sb_engine_get_langevin(const sb_engine *e, sb_engine_langevin_params *p);

/** The neighbour reach (m) of the Langevin detector for the current
 *  particle number, species, box and dt: the largest sb_langevin_reach
 *  over species pairs (with r_i + r_j = 2 r_max and n = (N - 1)/V; beyond
 *  8 species, over the 8 whose positions spread most in a step).  Cached;
 *  recomputed when dt, the species or the particle number grow.  NaN on
 *  error. */
double sb_engine_langevin_reach(sb_engine *e);

/** The Langevin detector as a detector callback (for wrappers, e.g.
 *  first-contact counting): samples the first contact of the record's
 *  pair from the exact conditional law (ctx unused, r the generator to
 *  draw from).  The states at the record's start are the step's start
 *  states, or, for a record that starts inside the step, the particles'
 *  states on their current Langevin path pieces (drawn from their
 *  bridges).  3-D or 2-D, every species (free flight and B = 0 are
 *  deterministic paths).  Once the reach is known (sb_engine_langevin_reach
 *  called for the current dt and species, as the engine does every step),
 *  a record at the step's start whose relative chord stays beyond
 *  r_i + r_j + reach returns 0 without a draw (both particles with noise,
 *  periodic or open box): such pairs hold at most `tol` contacts per
 *  particle and step.  Returns 1/0/-1 as sb_engine_detect_fn. */
int sb_engine_detect_langevin(const sb_engine *e, const sb_engine_pair *p,
                              const gsl_rng *r, void *ctx, double *s);

/** As sb_engine_detect_langevin, also returning both particles' states at
 *  the contact in *c (c may be NULL): time c->t from the record's start
 *  t0 (s), positions x_i in i's unwrapped frame and x_j in the image next
 *  to it (|x_i - x_j| = r_i + r_j), velocities. */
int sb_engine_langevin_contact(const sb_engine *e, const sb_engine_pair *p,
                               const gsl_rng *r, double *s,
                               sb_langevin_contact *c);

/** Counters of the Langevin detector since the engine's allocation (or
 *  sb_engine_reset_counters), the wall detector's included; the same on
 *  any number of threads, pruned_mass bit for bit (each sampler call's
 *  counters are added in record order).  SB_EINVAL for NULL. */
int sb_engine_langevin_stats(const sb_engine *e, sb_langevin_hit_stats *st);

/** Inside an outcome callback with SB_DETECT_LANGEVIN, or inside the
 *  on_hit callback of a first-contact observer around that built-in
 *  (smolbridge/engine_firsthit.h): the states of p->i and p->j at the
 *  contact (positions in m with x_i - x_j the contact
 *  separation, |x_i - x_j| = r_i + r_j; velocities in m/s, drawn from
 *  the conditional law at the contact time).  Any argument may be NULL.
 *  SB_EINVAL when no contact state is available (another detector, or
 *  outside an outcome).
 *
 *  With this detector an outcome sees each partner's state at the contact
 *  in sb_engine_positions / sb_engine_velocities (position in the
 *  particle's unwrapped frame of the step).  A partner whose state the
 *  outcome changes (velocity, position, species) continues from its new
 *  state by a fresh exact Langevin step over the rest of the step; an
 *  unchanged one continues on its bridge to its end state. */
int sb_engine_contact_state(const sb_engine *e, double xi[3], double ui[3],
                            double xj[3], double uj[3]);

/* ======================================================= observers */

/** Counters since the start (or the last sb_engine_reset_counters). */
typedef struct {
  uint64_t steps;      /**< steps taken in total */
  uint64_t ncoll;      /**< collisions since the counter reset */
  uint64_t ncand;      /**< candidate pairs examined since the reset
                            (fewer with the Langevin search of the
                            cells, sb_engine_params.lsearch_off: the
                            pairs it leaves out are those the detector
                            would skip) */
  uint64_t dropped;    /**< events dropped since the reset: a custom
                            detector without re-detection saw a partner's
                            path change earlier in the step (0 with the
                            built-in detectors) */
  uint64_t redetected; /**< pair records examined again after a
                            collision changed a path, since the reset */
  uint64_t fam[SB_ENGINE_MAXFAM][SB_ENGINE_MAXFAM]; /**< collisions by
                            family pair (a <= b in fam[a][b]) */
  double t;            /**< time, s (steps * dt, summed per dt change) */
  double t_reset;      /**< time of the last counter reset: the kernel is
                            measured over [t_reset, t], s */
  double exposure;     /**< pair exposure int n (n - 1)/2 dt over that
                            interval, s (what sb_engine_kernel divides
                            by) */
} sb_engine_stats;

int sb_engine_get_stats(const sb_engine *e, sb_engine_stats *st);

/** Zero the collision counters and start the kernel measurement now. */
void sb_engine_reset_counters(sb_engine *e);

/** Kernel estimate K_e = N_c V / int n (n - 1)/2 dt over [t_reset, t]
 *  (= 2 N_c V / (n (n - 1) (t - t_reset)) for a constant n; m^3/s in
 *  3-D, m^2/s in 2-D; V the box volume/area, N_c collisions since the
 *  reset) with the exact (Garwood) Poisson interval at `level` (e.g.
 *  0.95) of the same scale times N_c.  The kernel of one species pair in a
 *  mixture is sb_engine_pair_kernel.  SB_EDOM if there is no exposure yet
 *  (no step since the reset, or n < 2).  lo/hi may be NULL. */
int sb_engine_kernel(const sb_engine *e, double level, double *K,
                     double *lo, double *hi);

/** Collisions, exposure and kernel of one species pair (a, b) since the
 *  reset. */
typedef struct {
  uint64_t ncoll;   /**< collisions between a and b */
  double exposure;  /**< int P_ab dt, s; P_ab = n_a n_b (a != b) or
                         n_a (n_a - 1)/2 (a = b) */
  double K;         /**< N_ab V / exposure, m^3/s (3-D) */
  double lo, hi;    /**< exact Poisson (Garwood) interval at `level`,
                         widened by sqrt(dispersion) where that is above 1
                         (sb_poisson_ci_dispersed) */
  double ncoll_var; /**< estimated variance of ncoll from the collision
                         tally (sb_engine_set_count_variance; NaN without
                         it): sb_pair_count_variance of each particle's and
                         each pair's collisions since the reset */
  double dispersion;/**< ncoll_var / ncoll (NaN without the tally) */
} sb_engine_pair_stats;

/** Tally the collisions since the counter reset (on = 1): each
 *  particle's with each partner species and each pair's, in hash tables
 *  (about 24 bytes per particle and partner species and per pair that
 *  collided), so that sb_engine_pair_kernel can estimate the variance of
 *  its count: collisions are not independent
 *  events when particles differ persistently (a light molecule keeps its
 *  speed over many collisions with heavy ones: He-Xe in V1 measures
 *  var/mean ~1.5) or when pairs collide again.  Turn it on before the
 *  reset that starts the measurement (or before the first step): a
 *  count the tally does not hold whole (turned on after collisions, out
 *  of memory) gives NaN until the next reset.  The estimate assumes a
 *  fixed population (no merging, reinsertion or removal).  O(1) per
 *  collision and per sb_engine_pair_kernel call (plus a pass over the
 *  particles).  on = 0 frees the tables.  Checkpoints keep the tally
 *  (sb_engine_checkpoint_save): a restored engine goes on with it, so do
 *  not call this again after loading one, which would start it afresh. */
int sb_engine_set_count_variance(sb_engine *e, int on);
/** 1 if the engine tallies its collisions (sb_engine_set_count_variance,
 *  or a checkpoint of an engine that did), 0 otherwise or for NULL. */
int sb_engine_get_count_variance(const sb_engine *e);

/** The kernel of species pair (a, b), a and b < SB_ENGINE_PAIR_SPECIES
 *  (SB_EINVAL otherwise); SB_EDOM (ncoll and exposure still set) if the
 *  pair had no exposure. */
int sb_engine_pair_kernel(const sb_engine *e, size_t a, size_t b,
                          double level, sb_engine_pair_stats *ps);

/** One time-series sample (every params.sample_every steps). */
typedef struct {
  double t;        /**< s */
  uint64_t ncoll;  /**< collisions since the reset */
  double K;        /**< kernel estimate (NaN before the first collision
                        time has elapsed), see sb_engine_kernel */
  double K_lo, K_hi;  /**< its 95% interval */
  double ekin;     /**< total kinetic energy sum m u^2/2, J */
  double p[3];     /**< total momentum, kg m/s */
} sb_engine_sample;

/** The recorded time series (array owned by the engine). */
const sb_engine_sample *sb_engine_series(const sb_engine *e, size_t *n);

/** Total kinetic energy (J) and momentum (kg m/s, p may be NULL); NaN
 *  (p NaN too) for a NULL engine. */
double sb_engine_kinetic_energy(const sb_engine *e, double p[3]);

/** Number of pairs overlapping by more than rel_tol * (r_i + r_j) now
 *  (brute force, O(N^2): a diagnostic for tests). */
size_t sb_engine_check_overlaps(const sb_engine *e, double rel_tol);

/** Write a snapshot CSV (header; one line per particle: id, species,
 *  family, x, y, z [m], ux, uy, uz [m/s]).  SB_EIO on failure. */
int sb_engine_snapshot_csv(const sb_engine *e, const char *path);

/** Particle-to-grid assignment (lib/engine/engine_grid.c). */
typedef enum {
  SB_GRID_NGP = 0,  /**< nearest grid point: the cell holding the centre */
  SB_GRID_CIC = 1   /**< cloud in cell: linear weights over the 2^dim
                         nearest cell centres (Hockney & Eastwood 1988) */
} sb_engine_grid_scheme;

/** Mass and momentum densities of the particles now, on a regular grid of
 *  n[0] x n[1] (x n[2] in 3-D; n[2] is ignored in 2-D) cells covering the
 *  box, cell (i, j, k) = [i h_x, (i + 1) h_x) x ..., h = L/n, stored at
 *  index i + n[0] (j + n[1] k).  rho receives the mass per cell volume
 *  (kg/m^3; 2-D: per cell area, kg/m^2), mom (may be NULL) three values
 *  per cell, the momentum density (rho u).  family >= 0: only that
 *  family's particles; -1: all.  Along periodic directions CIC weights
 *  wrap round; along walled or open ones the share beyond the box is
 *  folded into the edge cell, so the totals (sum rho h^dim) equal the
 *  particles' mass and momentum to rounding with either scheme.  O(N +
 *  cells).  SB_EINVAL for NULL, n[k] = 0 or > 2^24, or a bad scheme. */
int sb_engine_grid_fields(const sb_engine *e, const size_t n[3],
                          sb_engine_grid_scheme scheme, int family,
                          double *rho, double *mom);

/* ======================================================= accessors */

size_t sb_engine_count(const sb_engine *e);
double sb_engine_time(const sb_engine *e);
/** Arrays of 3n values (x[3i+k]); positions in [0, L_k). */
const double *sb_engine_positions(const sb_engine *e);
const double *sb_engine_velocities(const sb_engine *e);
/** Positions / velocities at the start of the current step (valid inside
 *  detector and outcome callbacks). */
const double *sb_engine_start_positions(const sb_engine *e);
const double *sb_engine_start_velocities(const sb_engine *e);
const double *sb_engine_radii(const sb_engine *e);
const double *sb_engine_masses(const sb_engine *e);
const size_t *sb_engine_species_of(const sb_engine *e);
const int *sb_engine_families(const sb_engine *e);
const uint64_t *sb_engine_ids(const sb_engine *e);
/** Species idx (0 .. sb_engine_species_count(e) - 1), or NULL for idx at
 *  or past the count: an end-of-list sentinel, not an error (nothing is
 *  recorded; loops may stop on it).  NULL and SB_EINVAL for e NULL. */
const sb_engine_species *sb_engine_get_species(const sb_engine *e,
                                               size_t idx);
/** Number of species of the engine (those added, and the cluster species
 *  an agglomeration context creates as sizes appear); 0 and SB_EINVAL for
 *  e NULL. */
size_t sb_engine_species_count(const sb_engine *e);
/** The engine's generator (for callbacks; do not free). */
gsl_rng *sb_engine_rng(sb_engine *e);
/** Set the state of particle i (m, m/s), e.g. in tests; x is wrapped into
 *  the box and refused (SB_EINVAL, the particle unchanged) as by
 *  sb_engine_add_particle. */
int sb_engine_set_particle(sb_engine *e, size_t i, const double x[3],
                           const double u[3]);

/* ======================================================= checkpoint */

/** Write the whole state (parameters, species, particles, counters, time
 *  series, built-in fluid field, generator state via gsl_rng_fwrite) to a
 *  binary file, little-endian on every machine (docs/engine.md).  On a
 *  big-endian machine, SB_EINVAL for a generator other than
 *  sb_rng_philox and gsl_rng_mt19937 (its state cannot be converted).
 *  Callbacks (custom detector/outcome/fluid) are not saved:
 *  set them again after loading.  SB_EIO on failure (a file that could
 *  not be written whole is removed, as by every save of the library). */
int sb_engine_checkpoint_save(const sb_engine *e, const char *path);

/** Load a checkpoint: a new engine that continues bit-identically.  NULL
 *  and *status (may be NULL) = SB_EIO / SB_EFORMAT / SB_ENOMEM on
 *  failure; SB_EFORMAT also for a file whose contents do not match the
 *  hash it ends with (damaged; format SBENGCK6, docs/engine.md), and
 *  for a file in big-endian order (an older build's on a big-endian
 *  machine: checkpoints are little-endian; the message says so);
 *  SB_EINVAL, naming the id, for particles that share an id or hold one
 *  not below the file's id counter, and, naming the particle, for a
 *  position outside the box [0, L_k) or a state that is not finite. */
sb_engine *sb_engine_checkpoint_load(const char *path, int *status);
/** As sb_engine_checkpoint_load, with room for at least `capacity`
 *  particles (sb_engine_params.capacity; the checkpoint's own if that is
 *  larger, so 0 gives it): for a run that goes on with more particles
 *  than the one that wrote the file had room for (inflows over a longer
 *  time).  The capacity holds no state: the engine continues
 *  bit-identically, and a checkpoint it writes records the capacity it
 *  has.  SB_EINVAL for capacity > 2^40; otherwise as
 *  sb_engine_checkpoint_load (SB_ENOMEM when the room does not fit in
 *  memory). */
sb_engine *sb_engine_checkpoint_load_capacity(const char *path,
                                              size_t capacity, int *status);

/* ======================================================= names */

/** Names used by the CLI ("cells", "sweep", "brute"; "ballistic",
 *  "overlap", "langevin"; "elastic", "reinsert", "count"); return
 *  SB_EINVAL for an unknown name, with the valid names in the message.
 *  The output may be NULL (the name is only checked). */
int sb_engine_neigh_from_name(const char *name, sb_engine_neigh *m);
int sb_engine_detect_from_name(const char *name, sb_engine_detect *d);
int sb_engine_outcome_from_name(const char *name, sb_engine_outcome *o);
/** The names the _from_name functions accept, NULL-terminated, in enum
 *  order (detectors: SB_DETECT_CUSTOM has no name) (static storage; for
 *  help texts and error messages). */
const char *const *sb_engine_neigh_names(void);
const char *const *sb_engine_detect_names(void);
const char *const *sb_engine_outcome_names(void);


/* ============================================================
 * Agglomeration: particle removal, merge and DLVO outcomes,
 * cluster sizes and size-distribution observers (lib/engine/engine_merge.c);
 * theory and validation: docs/agglomeration.md.
 *
 * A cluster of k primaries is a particle of the engine species registered
 * for size k (one species per size, created on the first merge that makes
 * that size), so that its radius, mass, tau_p and B follow from k through
 * a growth law while the Langevin coefficients stay per species.  All
 * primaries must belong to one species (monodisperse primaries).
 * ============================================================ */

/** Mark particle i for removal.  The removal is deferred: the particle
 *  takes no further part in the current step (it counts as having
 *  collided) and sb_engine_step removes all marked particles at the end
 *  of the step.  Outside a step, call sb_engine_flush_removals before the
 *  next step (a step clears the marks when it starts).  The survivors
 *  keep their relative order (indices shift down, ids do not change). */
int sb_engine_remove_particle(sb_engine *e, size_t i);
/** Remove the marked particles now (done by sb_engine_step). */
int sb_engine_flush_removals(sb_engine *e);
/** Change the species of particle i; its radius and mass become the
 *  species' (position and velocity unchanged; no overlap check). */
int sb_engine_set_particle_species(sb_engine *e, size_t i, size_t species);

/** How the species of a cluster of k primaries follows from the primary
 *  species (radius r1, mass m1, tau1, B1, T1). */
typedef enum {
  /** radius r1, tau1, B1, T1 kept, mass k m1: every cluster has the
   *  primaries' diffusivity and contact radius, so the kernel is
   *  constant (V8).  The summed volume is tracked as k only. */
  SB_AGGLO_CONSTANT = 0,
  /** compact sphere in the Stokes (continuum) regime: r = r1 k^(1/3),
   *  m = k m1, tau = tau1 k^(2/3) (tau = m/(6 pi mu r)), and B from the
   *  fluctuation-dissipation relation B^2 tau/2 = k_B T/m, i.e.
   *  B = B1 k^(-5/6); hence D = (B tau)^2/2 = D1 k^(-1/3) (Stokes-
   *  Einstein).  Free-flight primaries (tau1 = inf) keep tau = inf. */
  SB_AGGLO_STOKES = 1,
  /** user callback (sb_agglo_params.species_fn) */
  SB_AGGLO_CUSTOM = 2
} sb_agglo_growth;

/** Sticking rule. */
typedef enum {
  SB_AGGLO_MERGE = 0,  /**< every collision merges */
  SB_AGGLO_DLVO = 1    /**< merge iff E_rel > W_max, else rebound */
} sb_agglo_rule;

/** Where E_rel comes from (rule SB_AGGLO_DLVO). */
typedef enum {
  /** relative chord velocity w = dd/dt at contact, E = mu |w|^2/2
   *  (ballistic regime: free flight, or dt << tau_p); a rebound is the
   *  engine's elastic outcome (sb_engine_outcome_elastic, its eta) */
  SB_AGGLO_EREL_CONTACT = 0,
  /** drawn from the stationary law of two independent equilibrium
   *  velocities, Gamma(dim/2, theta), theta = mu (s_i^2 + s_j^2) with s^2
   *  the species' equilibrium velocity variance (diffusive regime: with
   *  dt >> tau_p the chord velocity is not a velocity); a rebound leaves
   *  the pair as the step moved it */
  SB_AGGLO_EREL_STATIONARY = 1
} sb_agglo_erel;

/** Growth-law callback: fill *out with the species of a cluster of k >= 2
 *  primaries; return a status. */
typedef int (*sb_agglo_species_fn)(size_t k,
                                   const sb_engine_species *primary,
                                   sb_engine_species *out, void *ctx);
/** Size-dependent barrier callback: W_max (J, >= 0) for radii r_i, r_j
 *  (e.g. from sb_dlvo_barrier); NaN aborts the step (SB_EDOM). */
typedef double (*sb_agglo_wmax_fn)(double r_i, double r_j, void *ctx);

/** Agglomeration parameters (sb_agglo_params_default fills them). */
typedef struct {
  size_t primary;             /**< species of the primaries (default 0) */
  sb_agglo_growth growth;     /**< default SB_AGGLO_STOKES */
  sb_agglo_species_fn species_fn; /**< SB_AGGLO_CUSTOM only */
  void *species_ctx;
  sb_agglo_rule rule;         /**< default SB_AGGLO_MERGE */
  double wmax;                /**< barrier W_max, J, >= 0 (default 0) */
  sb_agglo_wmax_fn wmax_fn;   /**< NULL (default): constant wmax */
  void *wmax_ctx;
  sb_agglo_erel erel;         /**< default SB_AGGLO_EREL_CONTACT */
  int erel_normal;            /**< 0 (default): the full E_rel of
                                   Mohaupt 2011, App. C; 1: its part
                                   along the line of centres (what works
                                   against a central force) */
  size_t kmax;                /**< largest cluster size allowed (a merge
                                   beyond it fails with SB_EINVAL);
                                   default 2^20 */
  size_t kobs;                /**< n_k columns kept by sb_agglo_sample,
                                   k = 1..kobs (default 10) */
} sb_agglo_params;

/** Counters since sb_agglo_attach or sb_agglo_reset_stats. */
typedef struct {
  uint64_t nmerge;      /**< merges */
  uint64_t nrebound;    /**< DLVO rebounds */
  double erel_sum;      /**< sum of E_rel over DLVO decisions, J */
} sb_agglo_stats;

typedef struct sb_agglo sb_agglo;

void sb_agglo_params_default(sb_agglo_params *p);
/** New context (NULL and SB_EINVAL / SB_ENOMEM on failure). */
sb_agglo *sb_agglo_alloc(const sb_agglo_params *p);
void sb_agglo_free(sb_agglo *a);

/** Register the primary species as size 1 and install the outcome
 *  (sb_engine_outcome_agglo) in e.  Every particle present must be a
 *  primary or a cluster species of this context (re-attaching during a
 *  run is allowed, e.g. after sb_engine_bridge_attach updated the
 *  reach).  With a custom detector (e.g. sb_engine_bridge_attach), attach
 *  the detector first: this call replaces the outcome.  The context must
 *  outlive its use by the engine; it belongs to one engine. */
int sb_agglo_attach(sb_engine *e, sb_agglo *a);

/** Save an attached context beside a checkpoint of engine e at the same
 *  step (sb_engine_checkpoint_save): which species is which cluster size,
 *  the counters, the size series (sb_agglo_sample's rows), the parameters
 *  that shape the run, and the engine's step with a fingerprint of its
 *  particles.  Native binary, like the checkpoint.  SB_EINVAL (not
 *  attached), SB_EIO (cannot write; no file is left). */
int sb_agglo_save(const sb_agglo *a, const sb_engine *e, const char *path);

/** Restore a saved state into a new context a (same parameters; set the
 *  callbacks again: they are not saved), before sb_agglo_attach, which
 *  then checks that the engine is the one restored from the same
 *  checkpoint (its step, its particles, the masses of the saved cluster
 *  species) and fails with SB_EINVAL otherwise.  The run then goes on bit
 *  for bit as if it had not stopped.  SB_EINVAL (attached already, other
 *  parameters), SB_EIO (cannot open), SB_EFORMAT (not such a file,
 *  truncated, malformed, or damaged: the file ends in a hash of its
 *  contents, format SBAGGL02, checked before anything is read; SBAGGL01
 *  files, without it, still load); a is unchanged on failure. */
int sb_agglo_load(sb_agglo *a, const char *path);

/** The outcome (sb_engine_outcome_fn; ctx is the sb_agglo): the rule of
 *  the context, then merge or rebound. */
int sb_engine_outcome_agglo(sb_engine *e, const sb_engine_pair *p, double s,
                            void *ctx);
/** Merge pair p now (see the file comment of lib/engine/engine_merge.c): slot
 *  p->i receives the cluster of k_i + k_j primaries at the mass
 *  barycentre with the total momentum; p->j is marked for removal.
 *  Inside a step (from an outcome callback) p is the detector's record
 *  and s the contact fraction; p->j goes at the end of the step.  Outside
 *  a step (e.g. to build clusters before a run) it is not an error: the
 *  merge is at the current positions, with x_i - x_j = p->dx0 + p->dd
 *  (the image of j next to i; s is not used), the cluster wrapped into
 *  the box, and p->j stays marked
 *  until sb_engine_flush_removals, which must be called before the next
 *  step.  SB_EINVAL for a bad argument (p->i == p->j, an index out of
 *  range, a particle not of a cluster species of a) or a size above
 *  kmax. */
int sb_agglo_merge(sb_engine *e, sb_agglo *a, const sb_engine_pair *p,
                   double s);
/** E_rel (J) the rule uses for pair p in contact at fraction s of the
 *  step (CONTACT: from the chords, the normal part along dx0 + s dd;
 *  STATIONARY: one draw from r).  NaN and SB_EINVAL on a bad argument. */
double sb_agglo_erel_of(const sb_engine *e, const sb_agglo *a,
                        const sb_engine_pair *p, double s, const gsl_rng *r);

/** Cluster size (number of primaries) of species sp; 0 if sp is not a
 *  cluster species of the context. */
size_t sb_agglo_size_of_species(const sb_agglo *a, size_t sp);
/** Species of size k (created in e if needed); SB_EINVAL if k > kmax. */
int sb_agglo_species_of_size(sb_agglo *a, sb_engine *e, size_t k,
                             size_t *sp);
int sb_agglo_get_stats(const sb_agglo *a, sb_agglo_stats *st);
void sb_agglo_reset_stats(sb_agglo *a);

/* ----------------------------------------------------- size observers */

/** Cluster counts now: nk[k-1] = number of clusters of size k for
 *  k = 1..kmax (nk may be NULL if kmax = 0), *tail (may be NULL) = number
 *  of clusters larger than kmax.  Divide by the box volume for
 *  concentrations.  SB_EINVAL if a particle is not a cluster species. */
int sb_agglo_count_sizes(const sb_agglo *a, const sb_engine *e, size_t kmax,
                         double *nk, double *tail);
/** Moments now: m[j] = sum over clusters of k^j, j = 0, 1, 2 (M0 the
 *  number of clusters, M1 the number of primaries, conserved by merges,
 *  M2 in primaries^2); divide by the box volume for concentrations (and
 *  multiply M_j by v1^j for volume moments). */
int sb_agglo_moments(const sb_agglo *a, const sb_engine *e, double m[3]);
/** Append one row (t, M0, M1, M2, n_1 .. n_kobs) to the context's time
 *  series (counts, as above). */
int sb_agglo_sample(sb_agglo *a, const sb_engine *e);
/** The time series: *nrows rows of *ncols = 4 + kobs values, row-major
 *  (array owned by the context). */
const double *sb_agglo_series(const sb_agglo *a, size_t *nrows,
                              size_t *ncols);
/** Write the time series as CSV (header t,M0,M1,M2,n1,...).  SB_EIO on
 *  failure. */
int sb_agglo_series_csv(const sb_agglo *a, const char *path);

/* ====================================================================
 * Forces, Lees-Edwards sliding boundaries and walls (engine_force.c,
 * engine_lees.c, engine_wall.c; docs/engine_forces.md).  All SI units.
 * ==================================================================== */

/** Drag law of a species.  The drag force is F = (m / tau_p) f(Re_p)
 *  (U_s - u), Re_p = rho_f |U_s - u| d / mu, where tau_p is the species'
 *  Stokes relaxation time and f = C_D Re_p / 24. */
typedef enum {
  SB_DRAG_STOKES = 0,          /**< f = 1 (linear: the exact Langevin step) */
  SB_DRAG_SCHILLER_NAUMANN = 1 /**< f = 1 + 0.15 Re_p^0.687 for Re_p <=
                                    1000 (Schiller & Naumann 1933), then
                                    Newton's C_D = 0.44, f = 0.44 Re_p/24
                                    (Clift, Grace & Weber 1978); non-
                                    Brownian species only (B = 0) */
} sb_engine_drag;

/** Fluid properties of a species (defaults: Stokes drag, rho_f = 0, mu =
 *  0).  rho_f enters the buoyancy factor (1 - rho_f/rho_p) of gravity and
 *  Re_p; mu enters Re_p (needed by the nonlinear law only).  rho_p is the
 *  species' mass over its sphere volume 4 pi r^3 / 3. */
typedef struct {
  sb_engine_drag drag;
  double rho_f;   /**< fluid density, kg/m^3, >= 0 */
  double mu;      /**< fluid dynamic viscosity, Pa s, > 0 for a nonlinear
                       drag law (ignored by Stokes drag) */
} sb_engine_species_fluid;

/** Drag factor f(Re) = C_D Re / 24 of a law, Re >= 0 (NaN and SB_EDOM
 *  otherwise).  Stokes: 1.  Schiller-Naumann: 1 + 0.15 Re^0.687 (Re <=
 *  1000), 0.44 Re / 24 above (continuous within 0.4% at Re = 1000). */
double sb_drag_factor(sb_engine_drag law, double Re);

/** Set the fluid properties of species sp (before or after particles are
 *  added).  SB_EINVAL for a bad value, a nonlinear law on a Brownian
 *  (B > 0) or free-flight species, or mu <= 0 with a nonlinear law. */
int sb_engine_set_species_fluid(sb_engine *e, size_t sp,
                                const sb_engine_species_fluid *f);
/** The fluid properties of species sp (defaults if never set); SB_EINVAL
 *  for a bad index. */
int sb_engine_get_species_fluid(const sb_engine *e, size_t sp,
                                sb_engine_species_fluid *f);

/** Constant external acceleration g (m/s^2; e.g. gravity (0, -9.81, 0)).
 *  A particle of species s feels g (1 - rho_f/rho_p) (buoyancy), so with
 *  Stokes drag it settles at v_s = tau_p g (1 - rho_f/rho_p) relative to
 *  the fluid: the exact Langevin step with the fluid velocity U_s + v_s
 *  (exact at every dt).  Free-flight species (tau = inf) have no
 *  settling velocity: with g != 0 the step (and a placement that draws
 *  settling velocities, sb_engine_fill_box) refuses them (SB_EINVAL);
 *  this call does not. */
int sb_engine_set_gravity(sb_engine *e, const double g[3]);
/** The engine's acceleration into g. */
int sb_engine_get_gravity(const sb_engine *e, double g[3]);

/** Terminal (settling) velocity of species sp relative to the fluid under
 *  the engine's gravity: Stokes tau_p g' (g' = g (1 - rho_f/rho_p)); with
 *  a nonlinear law the root of f(Re(v)) v = tau_p |g'| along g' (GSL
 *  Brent, relative accuracy 1e-13).  SB_EINVAL on a bad index. */
int sb_engine_settling_velocity(const sb_engine *e, size_t sp, double v[3]);

/** Lees-Edwards sliding boundaries for the built-in shear field
 *  (SB_FLUID_SHEAR, U_x = G (y - L_y/2)): the periodic image of the box at
 *  y + n L_y is shifted by n delta(t) along x and moves at n G L_y, with
 *  delta(t) = G L_y t (mod L_x) (Lees & Edwards 1972), so the fluid
 *  velocity is continuous across the y boundary.  A particle leaving
 *  through y = L_y (y = 0) re-enters at y - L_y (y + L_y) with x -= delta
 *  (+= delta) and u_x -= G L_y (+= G L_y); pair separations and relative
 *  chords across the boundary use the shifted image, for the first
 *  detection of a step and for the re-detection after an outcome alike,
 *  with every detector and every outcome: an elastic collision takes the
 *  relative velocity to j's image, a merge conserves momentum in the
 *  frame of i (where the cluster stays).  With the images on, the
 *  Langevin step of a Stokes species is the exact transition in the
 *  linear field, mean and noise (the y noise the shear carries into x
 *  within a step, drawn from the same six normals; docs/engine_forces.md
 *  section 3); nonlinear-drag species keep the field frozen over a step.
 *  on = 1 requires SB_FLUID_SHEAR and x and y periodic (otherwise
 *  SB_EINVAL here or at the step).  Off by default. */
int sb_engine_set_lees_edwards(sb_engine *e, int on);
/** Current image shift delta in [0, L_x) (m); 0 when off. */
double sb_engine_lees_edwards_offset(const sb_engine *e);
/** Inside an outcome callback: the x velocity (m/s) of the image of p->j
 *  that collides with p->i, relative to p->j itself: n G L_y with n = 1
 *  (-1) when that image lies above (below) the box, 0 in the box or
 *  without Lees-Edwards.  A custom outcome that uses both velocities
 *  (sb_engine_velocities, each in its particle's own frame) takes j's as
 *  u_j + du e_x.  Outside a step, from the current positions.  NaN and
 *  SB_EINVAL for a bad argument. */
double sb_engine_pair_image_velocity(const sb_engine *e,
                                     const sb_engine_pair *p);

/** Boundary of one face of the box. */
typedef enum {
  SB_WALL_PERIODIC = 0,  /**< periodic (both faces of a direction) */
  SB_WALL_REFLECT = 1,   /**< specular wall: y -> 2a - y, u_y -> -u_y
                              (exact fold of the free step) */
  SB_WALL_ABSORB = 2,    /**< deposition: the particle touching the
                              contact plane (centre at a radius from the
                              face) is counted and removed or reinserted */
  SB_WALL_OPEN = 3       /**< outflow: the particle whose centre crosses
                              the face (same detector as the absorbing
                              walls, plane at the face) leaves the box:
                              counted, passed to the outflow callback,
                              removed (sb_engine_add_inflow for inflow) */
} sb_engine_wall;

/** How contact with an absorbing wall is detected over a step. */
typedef enum {
  SB_WALLDET_BRIDGE = 0,    /**< 1-D Brownian bridge of the wall-normal
                                 coordinate between the step's end points,
                                 variance rate B_pos^2 = (B tau_p)^2:
                                 P = exp(-2 h0 h1 / (B_pos^2 dt)) (h the
                                 distances to the contact plane; Mohaupt
                                 2011, §5.1): exact for Brownian motion,
                                 the diffusive regime dt >> tau_p */
  SB_WALLDET_BALLISTIC = 1, /**< the straight chord crosses the contact
                                 plane (exact for straight paths: dt <<
                                 tau_p, free flight, non-Brownian) */
  SB_WALLDET_LANGEVIN = 2   /**< the exact conditional (bridge) law of the
                                 Langevin path between the step's end
                                 states, position and velocity
                                 (sb_langevin_hitter_sample_plane): exact
                                 at every dt/tau_p (free flight: the
                                 chord) */
} sb_engine_walldet;

/** What a deposited particle does. */
typedef enum {
  SB_DEPOSIT_REMOVE = 0,    /**< removed (counted) */
  SB_DEPOSIT_REINSERT = 1   /**< reinserted at a uniform position of the
                                 accessible volume (overlaps allowed),
                                 with an equilibrium velocity: a uniform
                                 volume source keeping N constant */
} sb_engine_deposit;

/** Set direction k (0 = x, 1 = y, 2 = z) to walls lo (face at 0) and hi
 *  (face at L[k]); both SB_WALL_PERIODIC restores periodicity; one
 *  periodic face and one wall is SB_EINVAL.  Pairs are not searched
 *  across a wall.  Walls are processed at the end of each step, after
 *  the particle-particle events of the step. */
int sb_engine_set_walls(sb_engine *e, int k, sb_engine_wall lo,
                        sb_engine_wall hi);
/** The walls of direction k (0 = x, 1 = y, 2 = z) into lo and hi (as
 *  set, or as a checkpoint restored them); either output may be NULL.
 *  SB_EINVAL for a NULL engine or k outside 0 .. dim - 1. */
int sb_engine_get_walls(const sb_engine *e, int k, sb_engine_wall *lo,
                        sb_engine_wall *hi);
/** Detector and outcome of the absorbing walls (defaults: bridge,
 *  remove). */
int sb_engine_set_wall_mode(sb_engine *e, sb_engine_walldet det,
                            sb_engine_deposit dep);
/** The detector and outcome of the absorbing walls (as set, or as a
 *  checkpoint restored them); either output may be NULL.  SB_EINVAL for
 *  a NULL engine. */
int sb_engine_get_wall_mode(const sb_engine *e, sb_engine_walldet *det,
                            sb_engine_deposit *dep);
/** Depositions since the counter reset on face 2k (lo) or 2k + 1 (hi) of
 *  direction k; 0 for a bad face. */
uint64_t sb_engine_deposits(const sb_engine *e, int face);
/** Whether direction k is periodic (1) or walled (0). */
int sb_engine_periodic(const sb_engine *e, int k);

/* ============================================================
 * Open boundaries: inflow of particles through a face at a given rate,
 * outflow through SB_WALL_OPEN faces (lib/engine/engine_open.c;
 * docs/engine_forces.md).  With them a box holds a steady stream: jets,
 * sprays crossing a domain (Thomine 2008, §8-9).
 * ============================================================ */

#define SB_ENGINE_MAXINFLOW 16

/** A stream entering the box through part of a face.  Particles arrive as
 *  a Poisson process of the given rate, at uniform points of the inlet
 *  and uniform times: each one injected at the end of a step is placed
 *  where its straight path from its entry point and time leads (its
 *  normal distance from the face is u_n s dt, s the fraction of the step
 *  since its entry), so that the stream is a spatial Poisson process of
 *  number density rate/(|u_n| inlet area).  Its flight over the entry
 *  fraction of the step is straight and without collisions (an O(dt)
 *  approximation at the inlet only).  The face need not be open: the
 *  stream may enter through a periodic face as well. */
typedef struct {
  int face;          /**< 2k (lo face of direction k, at 0) or 2k + 1 (hi
                          face, at L[k]) */
  size_t species;    /**< species of the entering particles */
  int family;        /**< their family tag */
  double rate;       /**< particles per second over the whole inlet, >= 0 */
  double lo[2], hi[2]; /**< inlet: the face's other coordinates in
                          increasing direction order (x, y, z without k;
                          2-D: one), lo < hi within the box, m */
  double u[3];       /**< velocity of the entering particles, m/s; its
                          component normal to the face points inward */
  int no_overlap;    /**< 1: redraw (up to 100 times, then skip and
                          count) a particle that would overlap another;
                          costs O(N) per particle */
} sb_engine_inflow;

/** Add an inflow (at most SB_ENGINE_MAXINFLOW); *idx (may be NULL) gets
 *  its index.  SB_EINVAL on a bad field.  Inflows are not stored in
 *  checkpoints: add them again after sb_engine_checkpoint_load, in the
 *  same order (the checkpoint keeps each index's injected and skipped
 *  counts, which the inflow added there goes on from).  An inflow has no
 *  other state (its arrivals draw from the engine's generator, which the
 *  checkpoint keeps), so the same inflows added again continue the run
 *  bit for bit, as if it had not stopped (docs/engine_forces.md §4). */
int sb_engine_add_inflow(sb_engine *e, const sb_engine_inflow *in,
                         size_t *idx);
/** Number of inflows. */
size_t sb_engine_ninflows(const sb_engine *e);
/** Particles injected by inflow k, and draws skipped because every
 *  position tried overlapped a particle, since the counter reset. */
uint64_t sb_engine_inflow_injected(const sb_engine *e, size_t k);
uint64_t sb_engine_inflow_skipped(const sb_engine *e, size_t k);
/** Particles that left through face f (an SB_WALL_OPEN face) since the
 *  counter reset; 0 for a bad face. */
uint64_t sb_engine_outflows(const sb_engine *e, int face);

/** Called for each particle leaving through an open face, before its
 *  removal: its index i (positions, velocities, masses, families readable
 *  through the accessors: the end-of-step state, outside the box by at
 *  most one step's flight), the face, and the time t_exit (s) at which
 *  its straight chord crossed the face.  A non-zero return stops the step
 *  with that status. */
typedef int (*sb_engine_outflow_fn)(const sb_engine *e, size_t i, int face,
                                    double t_exit, void *ctx);
/** Set (fn != NULL) or clear the outflow callback (not in checkpoints). */
int sb_engine_set_outflow_fn(sb_engine *e, sb_engine_outflow_fn fn,
                             void *ctx);

#ifdef __cplusplus
}
#endif

#endif /* SMOLBRIDGE_ENGINE_H */
