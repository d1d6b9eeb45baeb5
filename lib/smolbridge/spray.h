/* smolbridge/spray.h — homogeneous spray kinetics: stochastic particle
 * solutions of  d_t f = Q(f)  for droplets with velocity v and radius r
 * (collision, coalescence), and the TAB and Reitz-wave breakup models,
 * with the exact solutions they are checked against.
 *
 * Model (C. Baranger, "Modélisation, étude mathématique et simulation des
 * collisions dans les fluides complexes", PhD thesis, ENS Cachan / CEA-DIF):
 *   Q(f) = int [f(v') f(v_*') - f(v) f(v_*)] B dsigma dv* dr*,
 *   hard spheres  B = |v - v_*| pi (r + r_*)^2 / (4 pi)  per unit solid angle
 *   (isotropic scattering in the centre-of-mass frame), or a Maxwell-type
 *   kernel B = B0 / (4 pi) independent of |v - v_*| (Bobylev 1975, Krook &
 *   Wu 1976 give an exact solution).  Post-collision velocities for masses
 *   m, m_* (m = rho_l 4/3 pi r^3):
 *     v' = G + m_* /(m + m_*) |g| sigma,  v_*' = G - m/(m + m_*) |g| sigma,
 *     G = (m v + m_* v_*)/(m + m_*), g = v - v_*, sigma uniform on the sphere.
 *   Coalescence by impact parameter b (hard-sphere geometry:
 *   b = (r + r_*) cos(chi/2), chi the deflection angle): the pair merges iff
 *   b <= (r + r_*) sin(theta_cr), i.e. a fraction sin^2(theta_cr) of the
 *   collisions; theta_cr = pi/2 is coalescence efficiency 1, theta_cr = 0
 *   pure bouncing.
 *
 * Two stochastic particle methods, both exact in time (the collision times
 * are those of the N-particle jump process, sampled by thinning a Poisson
 * process whose rate bounds every pair's rate; see docs/spray.md):
 *  - Bird type (Bird 1994, "Molecular Gas Dynamics and the Direct
 *    Simulation of Gas Flows", §11.1): every simulation particle stands for
 *    the same number W of droplets; a pair (i, j) collides at rate
 *    W B_ij N/((N-1) V) (Bird's N N-bar convention: each particle's rate is
 *    exactly n B); both velocities change, so momentum and energy are
 *    conserved at every collision to round-off.  Coalescence merges the
 *    pair into one particle.  Candidate pairs: Poisson majorant (default)
 *    or Bird's no-time-counter count per step.
 *  - Nanbu type (Nanbu 1980, J. Phys. Soc. Japan 49:2042): variable weights
 *    w_i; particle i collides with j at rate w_j B_ij / V (j over all
 *    parcels, i included: two droplets of one parcel) and only particle
 *    i changes.  Momentum and energy are martingales (conserved on average;
 *    their random walk is the variance the method adds, docs/spray.md).
 *    Coalescence uses the mass-flow rule (Eibeck & Wagner 2001, Ann. Appl.
 *    Probab. 11:1137): i becomes the merged droplet and its weight becomes
 *    w_i m_i/(m_i + m_j), so the liquid mass is conserved exactly.
 *
 * Units: SI (m, s, kg, K); velocities m/s; B0 m^3/s; V m^3.
 * Errors: status codes of <smolbridge/common.h>, message in sb_last_error().
 * Thread safety: a sb_spray object is used by one thread at a time; the
 * caller passes the gsl_rng.  Theory, derivations, accuracy and
 * validation: docs/spray.md.
 */
#ifndef SMOLBRIDGE_SPRAY_H
#define SMOLBRIDGE_SPRAY_H

#include <stddef.h>
#include <gsl/gsl_rng.h>
#include <smolbridge/common.h>

#ifdef __cplusplus
extern "C" {
#endif

/* ------------------------------------------------------------ options */

typedef enum {
  SB_SPRAY_BIRD = 0,  /**< constant weight, pair updates, exact conservation */
  SB_SPRAY_NANBU = 1  /**< variable weights, one-sided updates */
} sb_spray_method;

typedef enum {
  SB_SPRAY_HARD_SPHERE = 0, /**< B = pi (r + r_*)^2 |v - v_*| */
  SB_SPRAY_MAXWELL = 1      /**< B = B0, independent of velocities and radii */
} sb_spray_cross;

typedef enum {
  SB_SPRAY_MAJORANT = 0, /**< candidate pairs from a Poisson process whose
                              rate bounds all pair rates: exact in time */
  SB_SPRAY_NTC = 1       /**< Bird's no-time-counter: a fixed number of
                              candidates per call (remainder carried);
                              Bird method only */
} sb_spray_select;

/** Coalescence boundary in impact parameter. */
typedef enum {
  SB_SPRAY_COAL_THETA = 0,  /**< fixed critical angle theta_cr (the thesis):
                                 b_cr = (r + r_*) sin(theta_cr) */
  SB_SPRAY_COAL_OROURKE = 1 /**< Weber-number dependent (O'Rourke 1981;
                                 Amsden, O'Rourke & Butler 1989):
                                 sb_spray_orourke_b2; needs sigma */
} sb_spray_coal;

/** Optional velocity rule for a droplet formed by coalescence (radius r, in
 *  m): set v (on entry the momentum-conserving velocity).  For example the
 *  settling velocity of the new size (sb_spray_stokes_settling).  Must be
 *  thread-safe if the ctx is shared. */
typedef void (*sb_spray_merge_fn)(double r, double v[3], void *ctx);

typedef struct {
  sb_spray_method method;
  sb_spray_cross cross;
  sb_spray_select select;
  double volume;    /**< V of the homogeneous cell, m^3 (> 0) */
  double rho_l;     /**< droplet (liquid) density, kg/m^3 (> 0) */
  double weight;    /**< Bird: droplets per simulation particle W (> 0) */
  double B0;        /**< Maxwell-type rate coefficient, m^3/s (> 0) */
  double theta_cr;  /**< critical impact angle in [0, pi/2]: coalescence
                         iff b <= (r + r_*) sin(theta_cr) (0: none) */
  sb_spray_coal coal; /**< coalescence boundary (default: theta_cr) */
  double sigma;     /**< surface tension, N/m (> 0 for COAL_OROURKE) */
  sb_spray_merge_fn merge_velocity; /**< NULL: momentum conserved */
  void *merge_ctx;
  size_t capacity;  /**< initial capacity (grows when needed) */
} sb_spray_params;

/** Defaults: Bird, hard spheres, majorant, V = 1, rho_l = 1000, W = 1,
 *  B0 = 1, theta_cr = 0 (elastic only), coal = COAL_THETA, sigma = 0.072,
 *  momentum rule, capacity 1024. */
void sb_spray_params_default(sb_spray_params *p);

/** Names for configuration files: "bird"/"nanbu", "hard-sphere"/"maxwell",
 *  "majorant"/"ntc".  SB_EINVAL for an unknown name.  The output may be
 *  NULL (the name is only checked). */
int sb_spray_method_from_name(const char *name, sb_spray_method *m);
int sb_spray_cross_from_name(const char *name, sb_spray_cross *c);
int sb_spray_select_from_name(const char *name, sb_spray_select *s);

/* ------------------------------------------------------------ the system */

typedef struct sb_spray sb_spray;

/** NULL on error (SB_EINVAL: bad parameter, named in sb_last_error();
 *  SB_ENOMEM). */
sb_spray *sb_spray_alloc(const sb_spray_params *p);
void sb_spray_free(sb_spray *s);
const sb_spray_params *sb_spray_get_params(const sb_spray *s);

/** Add one parcel: velocity v (m/s), radius r (m, > 0), weight w (> 0;
 *  ignored by the Bird method, which uses params.weight), tag (free
 *  label kept through collisions and inherited by children).  *index (may
 *  be NULL) receives its index. */
int sb_spray_add(sb_spray *s, const double v[3], double r, double w, int tag,
                 size_t *index);

/** Add n parcels of radius r, weight w and tag, velocities Maxwellian at
 *  temperature T (K) for the droplet mass m = rho_l 4/3 pi r^3 (variance
 *  k_B T/m per component) around the mean u (may be NULL: 0). */
int sb_spray_add_maxwellian(sb_spray *s, size_t n, double r, double w,
                            int tag, double T, const double u[3],
                            gsl_rng *rng);

/** Remove every parcel (the clock and counters are kept). */
void sb_spray_clear(sb_spray *s);

size_t sb_spray_count(const sb_spray *s);
double sb_spray_time(const sb_spray *s);
/** Arrays of the current parcels (valid until the next call that adds,
 *  removes or merges parcels): v[3 i + k], r[i], w[i], tag[i]. */
const double *sb_spray_velocities(const sb_spray *s);
const double *sb_spray_radii(const sb_spray *s);
const double *sb_spray_weights(const sb_spray *s);
const int *sb_spray_tags(const sb_spray *s);
/** TAB deformation y and dy/dt (1/s) of each parcel. */
const double *sb_spray_tab_y(const sb_spray *s);
const double *sb_spray_tab_ydot(const sb_spray *s);
/** Reitz breakup: liquid volume shed by each parcel and not yet emitted
 *  as children, summed over the parcel's droplets (m^3). */
const double *sb_spray_shed_volume(const sb_spray *s);

/** Set parcel i's velocity / TAB state (SB_EINVAL if i is out of range). */
int sb_spray_set_velocity(sb_spray *s, size_t i, const double v[3]);
int sb_spray_set_tab(sb_spray *s, size_t i, double y, double ydot);

/** Totals over the parcels (weights included):
 *  number = sum w, mass = sum w m, momentum = sum w m v, energy =
 *  sum w m |v|^2 / 2, volume = liquid volume sum w 4/3 pi r^3 plus the shed
 *  volume not yet emitted (conserved by coalescence and breakup).  All sums
 *  are compensated (Neumaier). */
typedef struct {
  double number, mass, momentum[3], energy, volume;
} sb_spray_totals;
int sb_spray_get_totals(const sb_spray *s, sb_spray_totals *t);

/** Weighted moment sum_i w_i |v_i - u|^k / sum_i w_i over the parcels
 *  with tag == tag (tag < 0: all), u may be NULL (0).  NaN if none. */
double sb_spray_velocity_moment(const sb_spray *s, int k, const double u[3],
                                int tag);

/** Weighted temperature of the parcels with tag (tag < 0: all):
 *  sum w m |v - u_tag|^2 / (3 k_B sum w), u_tag their mass-weighted mean
 *  velocity.  NaN if none. */
double sb_spray_temperature(const sb_spray *s, int tag);

/* ------------------------------------------------------------ collisions */

/** Counters since the allocation (or sb_spray_reset_stats). */
typedef struct {
  unsigned long long candidates; /**< candidate pairs drawn */
  unsigned long long bounces;    /**< accepted, elastic outcome */
  unsigned long long merges;     /**< accepted, coalescence */
  unsigned long long tab_breakups, reitz_children;
  unsigned long long reitz_blobs; /**< Reitz second branch applied */
} sb_spray_stats;
int sb_spray_get_stats(const sb_spray *s, sb_spray_stats *st);
void sb_spray_reset_stats(sb_spray *s);

/** What happened in one accepted collision (for observers). */
typedef enum { SB_SPRAY_BOUNCE = 0, SB_SPRAY_MERGE = 1 } sb_spray_event_kind;
typedef struct {
  sb_spray_event_kind kind;
  double t;                 /**< event time, s */
  size_t i, j;              /**< parcel indices before the event */
  int tag_i, tag_j;
  double r_i, r_j, w_i, w_j;  /**< before */
  double vi[3], vj[3];        /**< velocities before */
  double vi_new[3], vj_new[3];/**< after (Nanbu: vj_new = vj; merge: the
                                   merged droplet's velocity in vi_new) */
} sb_spray_event;
typedef void (*sb_spray_event_fn)(const sb_spray_event *ev, void *ctx);
/** Call fn for every accepted collision (NULL to stop). */
void sb_spray_set_observer(sb_spray *s, sb_spray_event_fn fn, void *ctx);

/** Advance the collision (and coalescence) operator by dt > 0 seconds.
 *  The Bird method needs N >= 2 to do anything (fewer parcels: time just
 *  advances).  Returns SB_SUCCESS, SB_EINVAL, SB_ENOMEM. */
int sb_spray_collide(sb_spray *s, double dt, gsl_rng *rng);

/** Post-collision velocities of masses m1, m2 (> 0, or any positive
 *  numbers proportional to them, e.g. r^3) for the unit vector sigma:
 *  v1' = G + m2/(m1+m2)|g| sigma, v2' = G - m1/(m1+m2)|g| sigma.
 *  Momentum and energy are conserved (to round-off).  Outputs may alias
 *  the inputs. */
void sb_spray_post_collision(const double v1[3], const double v2[3],
                             double m1, double m2, const double sigma[3],
                             double v1p[3], double v2p[3]);

/** Does a collision with deflection cosine cos_chi = sigma . g/|g|
 *  coalesce for the critical angle theta_cr?  Returns 1 iff
 *  b^2/(r+r_*)^2 = (1 + cos_chi)/2 <= sin^2(theta_cr) (0 for
 *  theta_cr <= 0).  The int result has no NaN: when cos_chi or theta_cr
 *  is NaN, or theta_cr is infinite, it returns 0 and records SB_EDOM
 *  naming this function (sb_last_status, sb_last_error); a caller that
 *  must tell this from "does not coalesce" calls sb_clear_error() first
 *  and checks sb_last_status().  Infinite cos_chi is compared as given. */
int sb_spray_coalesces(double cos_chi, double theta_cr);

/** Weber-number dependent coalescence boundary of O'Rourke (1981, PhD
 *  thesis, Princeton; as used in KIVA-II, Amsden, O'Rourke & Butler 1989,
 *  Los Alamos report LA-11560-MS), from the energy argument of
 *  Brazier-Smith, Jennings & Latham (1972, Proc. R. Soc. A 326:393):
 *  a collision coalesces iff b <= b_cr with
 *    (b_cr/(r1 + r2))^2 = min(1, 2.4 f(gamma)/We),
 *    f(gamma) = gamma^3 - 2.4 gamma^2 + 2.7 gamma,
 *    gamma = r_large/r_small >= 1,  We = rho_l |g|^2 r_small/sigma;
 *  grazing collisions beyond b_cr separate.  Returns (b_cr/(r1+r2))^2, the
 *  fraction of collisions that merge for this pair (1 when g = 0); NaN
 *  (SB_EDOM) unless r1, r2, rho_l, sigma > 0 and g >= 0 (all finite).
 *  gamma^3 and rho_l g^2 r_small may leave the double range: the ratio is
 *  then formed with an extended exponent (the same value, or its
 *  underflow to a subnormal or 0).  For equal drops every collision
 *  merges iff We <= 3.12. */
double sb_spray_orourke_b2(double r1, double r2, double g, double rho_l,
                           double sigma);

/** Pair rate coefficient B (m^3/s) of the cross-section model:
 *  hard spheres pi (r1 + r2)^2 |g| (r1, r2, g finite >= 0; B0 unused),
 *  Maxwell B0 (finite > 0; r1, r2, g unused).  NaN (SB_EDOM) outside
 *  these domains; where (r1 + r2)^2 over/underflows the product is formed
 *  with an extended exponent; NaN (SB_ERANGE) when B exceeds DBL_MAX. */
double sb_spray_pair_rate(sb_spray_cross c, double B0, double r1, double r2,
                          double g);

/** Stokes settling velocity 2 (rho_l - rho_g) g r^2/(9 mu_g) along the unit
 *  vector of `gvec` (m/s^2, its norm is g) as an sb_spray_merge_fn: ctx is
 *  a const sb_spray_settling *.  Valid for droplet Reynolds numbers << 1. */
typedef struct {
  double rho_l, rho_g, mu_g; /**< kg/m^3, kg/m^3, Pa s */
  double gvec[3];            /**< gravity, m/s^2 */
} sb_spray_settling;
void sb_spray_stokes_settling(double r, double v[3], void *ctx);

/* ------------------------------------------------------------ breakup */

/* The breakup steps do not advance the clock (sb_spray_collide does); a
 * time step of a full model is collide(dt) then tab_step / reitz_step(dt)
 * (first-order splitting, as in the thesis's four-step splitting). */

/** Gas seen by the droplets (constant over a call). */
typedef struct {
  double u[3];    /**< gas velocity, m/s */
  double rho_g;   /**< gas density, kg/m^3 */
  double mu_g;    /**< gas viscosity, Pa s (Reitz stripping test; 0: off) */
} sb_spray_gas;

/** Liquid properties for breakup (rho_l comes from the spray params). */
typedef struct {
  double sigma;   /**< surface tension, N/m */
  double mu_l;    /**< liquid viscosity, Pa s */
} sb_spray_liquid;

/** How children are represented.  PARCEL: the parcel takes a child radius
 *  and its weight is scaled to conserve mass (one parcel; variable
 *  weights; Nanbu method only).  PARTICLES: children of the parcel's weight are added until
 *  the parent volume is used (the last child takes the remainder), so
 *  every parcel keeps the same weight (Bird method).  AUTO: PARTICLES for
 *  Bird, PARCEL for Nanbu. */
typedef enum {
  SB_SPRAY_CHILDREN_AUTO = 0,
  SB_SPRAY_CHILDREN_PARCEL = 1,
  SB_SPRAY_CHILDREN_PARTICLES = 2
} sb_spray_children;

/* TAB (O'Rourke & Amsden 1987, SAE 872089): deformation y of the equator
 * (in units of C_b r, C_b = 1/2) obeys
 *   y'' = (2/3)(rho_g/rho_l) |u - v|^2/r^2 - 8 sigma/(rho_l r^3) y
 *         - C_d mu_l/(rho_l r^2) y'
 * (the forcing is quadratic in |u - v|: the thesis slides print |u - v|);
 * C_d = 5 in O'Rourke & Amsden; Lamb's (1932, §355) damping of the n = 2
 * mode gives C_d = 10 (the slides' value).  Breakup when |y| reaches 1.
 * At constant relative velocity, with We = rho_g |u - v|^2 r/sigma,
 * 1/t_d = C_d mu_l/(2 rho_l r^2), omega^2 = 8 sigma/(rho_l r^3) - 1/t_d^2:
 *   y(t) = We/12 + e^{-t/t_d} [(y0 - We/12) cos wt
 *          + (y0'/w + (y0 - We/12)/(w t_d)) sin wt]. */
typedef struct {
  double Cd;      /**< damping constant (default 5) */
  sb_spray_children children;
  int child_tag;  /**< >= 0: tag of the children; < 0: the parent's */
  size_t max_children; /**< PARTICLES: cap per breakup (default 10000);
                            beyond it the last child takes the rest */
} sb_spray_tab_params;
void sb_spray_tab_params_default(sb_spray_tab_params *p);

/** Closed-form TAB state at time t for constant relative speed urel (m/s),
 *  radius r, from (y0, ydot0).  Underdamped case (omega^2 > 0) exact;
 *  overdamped and critical cases use the matching closed forms.  Returns
 *  SB_EDOM for non-positive r, sigma, rho_l, negative rho_g, mu, Cd, t or
 *  any argument not finite; SB_ERANGE where We/12 exceeds DBL_MAX (urel
 *  near 1e150 m/s for ordinary drops), where y or y' overflows, and where
 *  the phase omega t exceeds 2^52 while e^{-t/t_d} > 0 (the oscillation
 *  is not resolved in double precision; the phase error is
 *  ~ omega t DBL_EPSILON radians).  Where w0^2, 1/t_d, 1/t_d^2, We/12 or
 *  the initial state's products (y0/t_d, w0^2 y0, y0'/t_d) leave the
 *  normal range (r near 1e-100 or 1e100 m, y0 or y0' near DBL_MAX) the
 *  oscillator is solved in units scaled by powers of two (time by
 *  1/max(w0, 1/t_d), y by up to 2^-1020), its scales formed with an
 *  extended exponent; other arguments give the same bits as the plain
 *  formulas.  Overdamped, the slow rate k - 1/t_d (k = sqrt(1/t_d^2 -
 *  w0^2)) is formed as -w0^2/(k + 1/t_d) for every argument: relative
 *  error a few DBL_EPSILON (the difference had ~ DBL_EPSILON/(w0 t_d)^2,
 *  y wrong in the ninth digit at 1/(w0 t_d) = 1e4); heavily overdamped
 *  y, y' are within ~10 ulp of mpmath for 1/(w0 t_d)^2 from 1e4 to 1e16
 *  and t up to a few times the slow time.  y is formed as y_eq g(t) +
 *  e^{-t/t_d}[y0 C + (y0' + y0/t_d) S] with the step response g = 1 -
 *  e^{-t/t_d}(C + S/t_d) summed from non-negative terms (series where t
 *  is small against t_d or 1/w0), not as y_eq + (y - y_eq), which
 *  cancelled where |y| << y_eq = We/12 (t << 1/w0 from y0 ~ 0: 6e3 ulp,
 *  1e13 ulp at y0 ~ 1e-13).  What remains is inherent: where y is a
 *  small difference of those three terms (y0 or y0' of the opposite
 *  sign to y_eq) the error is up to ~ (sum of |terms|)/|y| ulp, and a
 *  phase w t of many radians carries the rounding of w0^2 and 1/t_d
 *  from the data.  y' is formed as y0' h'(t) - w0^2 (y0 - y_eq) h(t),
 *  h = e^{-t/t_d} S the impulse response and h' = e^{-t/t_d}(C - S/t_d)
 *  its rate (overdamped: from the two exponentials' rates, and e^{-t/t_d}
 *  S with expm1 at small k t), not as e^{-t/t_d}[y0' C - (y0'/t_d +
 *  w0^2 z0) S], which lost ~ (w0 t_d)^-2 ulp in C - S/t_d when
 *  overdamped and up to 1.4e4 ulp at small k t.  Its error is up to a
 *  few times (|y0' h'| + w0^2 (|y_eq| + |y0|) |h|)/|y'| ulp, plus the
 *  phase's share as for y.  The same SB_EDOM/SB_ERANGE domain
 *  holds for sb_spray_tab_breakup_time (SB_ERANGE also when y' at
 *  breakup overflows) and sb_spray_tab_we_crit. */
int sb_spray_tab_state(double t, double r, double urel, double rho_g,
                       double rho_l, const sb_spray_liquid *liq, double Cd,
                       double y0, double ydot0, double *y, double *ydot);

/** First time in (0, tmax] at which |y| = 1 for the motion above; +inf if
 *  none (found by bracketing between extrema and GSL Brent; absolute
 *  accuracy 1e-12 of the oscillation period).  *ydot_b (may be NULL)
 *  receives y' at breakup. */
int sb_spray_tab_breakup_time(double r, double urel, double rho_g,
                              double rho_l, const sb_spray_liquid *liq,
                              double Cd, double y0, double ydot0,
                              double tmax, double *tb, double *ydot_b);

/** Critical Weber number of a droplet starting at rest (y0 = y0' = 0):
 *  12/(1 + exp(-pi/(omega t_d))) — 6 without damping (the first maximum
 *  We/12 (1 + e^{-pi/(omega t_d)}) is the largest).  It depends on
 *  r, rho_l and the liquid only (omega, t_d); NaN (SB_EDOM) when
 *  overdamped. */
double sb_spray_tab_we_crit(double r, double rho_l,
                            const sb_spray_liquid *liq, double Cd);

/** Sauter mean radius of the children, from energy conservation
 *  (O'Rourke & Amsden 1987): parent surface + oscillation energy (K = 10/3)
 *  at y = 1 equals children surface + normal kinetic energy:
 *    r/r32 = 7/3 + rho_l r^3 ydot^2/(8 sigma).
 *  NaN (SB_EDOM) unless r, rho_l, sigma are finite > 0 and ydot finite;
 *  r^3 ydot^2 is formed with an extended exponent where it over/underflows
 *  (r32 then underflows to a subnormal or 0 only if it is that small). */
double sb_spray_tab_r32(double r, double ydot, double rho_l, double sigma);

/** Advance every parcel's TAB state by dt in the gas (relative velocity
 *  u - v held constant over the call), break up the parcels that reach
 *  |y| = 1: the children's number law is exponential with mean r32/3 (so
 *  their Sauter radius is r32; truncated at the parent radius), they get
 *  the normal velocity r ydot/2 in a random direction perpendicular to
 *  u - v, and y = y' = 0.  A PARCEL draws its radius from the mass-weighted
 *  law (Gamma, shape 4, scale r32/3) since it stands for w r^3/r_c^3
 *  droplets. */
int sb_spray_tab_step(sb_spray *s, const sb_spray_gas *gas,
                      const sb_spray_liquid *liq,
                      const sb_spray_tab_params *tp, double dt,
                      gsl_rng *rng);

/* Reitz wave breakup (Reitz 1987, Atomisation Spray Technol. 3:309): for a
 * droplet of radius a at relative speed U, We_g = rho_g U^2 a/sigma,
 * We_l = rho_l U^2 a/sigma, Re_l = rho_l U a/mu_l, Z = sqrt(We_l)/Re_l,
 * T = Z sqrt(We_g):
 *   Lambda/a = 9.02 (1 + 0.45 Z^0.5)(1 + 0.4 T^0.7)/(1 + 0.87 We_g^1.67)^0.6
 *   Omega sqrt(rho_l a^3/sigma) = (0.34 + 0.38 We_g^1.5)/((1+Z)(1+1.4 T^0.6))
 * stable radius R = B0 Lambda, breakup time tau = 3.726 B1 a/(Lambda Omega),
 * and (the thesis slides: chi = -nu (r - R), nu = 1/tau; the slides print
 * nu = C r/(Lambda Omega), which is tau, not its inverse)
 *   da/dt = -(a - R)/tau  while a > R  (and We_g > sqrt(Re_g)/2 when the
 *   stripping test is on, Re_g = rho_g U a/mu_g);
 * the shed liquid forms children of radius R (the same velocity). */
typedef struct {
  double B0;       /**< 0.61 */
  double B1;       /**< 10 */
  double emit_fraction; /**< PARCEL children: emit a child parcel when the
                             shed volume exceeds this fraction of the
                             parcel's volume (default 0.03) */
  sb_spray_children children;
  int child_tag;   /**< >= 0: tag of the children; < 0: the parent's */
  int stripping;   /**< 1: no breakup unless We_g > sqrt(Re_g)/2 */
  int blob;        /**< 1: Reitz's second branch (default 0): a parcel
                        with B0 Lambda >= a (low We_g) forms its drops
                        once, radius sb_spray_reitz_blob_radius, weight
                        w a^3/r^3 (volume kept; PARCEL children only) */
} sb_spray_reitz_params;
void sb_spray_reitz_params_default(sb_spray_reitz_params *p);

/** Radius of the drops formed once when B0 Lambda >= a (Reitz 1987, the
 *  second case of the drop-size law, meant for the injected liquid
 *  "blobs" at low relative speed):
 *    r = min( (3 pi a^2 U/(2 Omega))^(1/3), (3 a^2 Lambda/4)^(1/3) ),
 *  i.e. 4/3 pi r^3 is the liquid volume of a cylinder of radius a and
 *  length U 2 pi/Omega (one wave period) or Lambda (one wavelength),
 *  whichever is smaller.  r > a whenever Lambda > 4a/3 (always when
 *  B0 Lambda >= a with B0 = 0.61) and U 2 pi/Omega > 4a/3: the drops then
 *  grow.  NaN (SB_EDOM) unless a, U, Lambda, Omega are finite > 0; a^2 U
 *  and a^2 Lambda are formed with an extended exponent where they
 *  over/underflow (the result, a cube root, is then representable for
 *  every finite argument).  Applied by
 *  sb_spray_reitz_step when params.blob = 1, once per parcel added with
 *  sb_spray_add (drops born by TAB or Reitz breakup are formed drops). */
double sb_spray_reitz_blob_radius(double a, double U, double Lambda,
                                  double Omega);

/** Wavelength Lambda (m) and growth rate Omega (1/s) of the fastest
 *  Kelvin-Helmholtz wave (Reitz 1987 fits above).  SB_EDOM for
 *  non-positive a, rho_g, rho_l, sigma, negative U, mu_l or any argument
 *  not finite.  mu_l = 0 gives Z = T = 0 (inviscid).  Where We, a^3 or a
 *  power of the fits leaves the double range the fits are evaluated
 *  through logarithms (relative error ~ |ln Lambda| DBL_EPSILON, resp.
 *  Omega); SB_ERANGE when Lambda or Omega is outside the normal double
 *  range (e.g. a < 1e-200 m: Omega ~ a^-1.5). */
int sb_spray_reitz_wave(double a, double U, double rho_g, double rho_l,
                        const sb_spray_liquid *liq, double *Lambda,
                        double *Omega);

/** Closed form of da/dt = -(a - R)/tau with tau = a/c, R and c = Lambda
 *  Omega/(3.726 B1) held constant (a0 > R > 0, c > 0, t >= 0):
 *    (a - a0) + R ln((a - R)/(a0 - R)) = -c t, i.e.
 *    a(t) = R + R W0( (a0 - R)/R exp((a0 - R - c t)/R) )
 *  (W0: Lambert's function, GSL; evaluated through its logarithm when the
 *  argument overflows).  a0 <= R returns a0 (no breakup). */
double sb_spray_reitz_radius_frozen(double a0, double R, double c, double t);

/** Radius a(t) of the full model (Lambda, Omega re-evaluated at the current
 *  radius) at constant U: t(a) = int_a^a0 tau(x)/(x - R(x)) dx by GSL
 *  adaptive quadrature (CQUAD, each t(a) to 1e-12 relative or to
 *  1e-13 a dt/da, whichever is looser: next to the stable radius x - R(x)
 *  cancels, t(a) cannot be had to 1e-12 but a(t) can), inverted with GSL
 *  Brent; relative accuracy ~1e-10 (~1e-12 against mpmath's ODE solution
 *  in tests/data/spray_reitz.csv).  About 0.1-2 ms per call
 *  (bench/bench_spray).
 *  Stops at the stable radius (a_inf with a_inf = R(a_inf)).  SB_EDOM as
 *  sb_spray_reitz_wave (message naming this function) or for t < 0.
 *  Where the plain fits leave the normal double range at a0 or near the
 *  stable radius (We^1.67, a^3 over/underflowing: a0 ~ 1e-150 or 1e120 m,
 *  U ~ 1e100 m/s) the quadrature uses the fits through logarithms and an
 *  integrand scaled by a power of two (relative accuracy ~1e-10 still).
 *  The result lies in [a_inf, a0]; SB_ERANGE only where a(t) is below
 *  DBL_MIN (a_inf there: U ~ 1e300 m/s). */
int sb_spray_reitz_radius(double a0, double t, double U, double rho_g,
                          double rho_l, const sb_spray_liquid *liq,
                          const sb_spray_reitz_params *rp, double *a);

/** Advance every parcel by dt: radius relaxation with Lambda, Omega of the
 *  parcel's radius at the start of the call (exact closed form within the
 *  step), shed volume accumulated per parcel and emitted as children of
 *  radius R (PARTICLES: whenever one child's worth W 4/3 pi R^3 is
 *  available; PARCEL: a child parcel when the shed volume exceeds
 *  emit_fraction of the parcel's volume).  Liquid volume (parcels + shed)
 *  is conserved to round-off. */
int sb_spray_reitz_step(sb_spray *s, const sb_spray_gas *gas,
                        const sb_spray_liquid *liq,
                        const sb_spray_reitz_params *rp, double dt);

/* ------------------------------------------------------------ exact results */

/** BKW solution (Bobylev 1975; Krook & Wu 1976) of the homogeneous
 *  Boltzmann equation with a Maxwell-type kernel, equal masses, per-
 *  component variance theta = k_B T/m (m^2/s^2), per-particle collision
 *  rate lambda = n B0 (1/s):
 *    f(v) = (2 pi K theta)^{-3/2} exp(-v^2/(2 K theta))
 *           [(5K - 3)/(2K) + (1 - K) v^2/(2 K^2 theta)],
 *    K(t) = 1 - (1 - K0) exp(-lambda t/6),  3/5 <= K0 <= 1.
 *  f is a probability density in R^3 (integral 1).  Domains: K in
 *  [3/5, 1], theta finite > 0, lambda and t finite >= 0, v and s not NaN
 *  (v, s = +-inf allowed: f = 0, cdf = 1); else NaN (SB_EDOM).  Where
 *  (2 pi K theta)^{-3/2}, e^{-x}, theta^2 or theta^3 leave the double
 *  range the values are formed with an extended exponent (the result, or
 *  its underflow to a subnormal or 0); NaN (SB_ERANGE) when f, E|v|^4 or
 *  E|v|^6 exceeds DBL_MAX (theta > ~1e154 for the fourth moment). */
double sb_spray_bkw_K(double K0, double lambda, double t);
double sb_spray_bkw_pdf(double v, double K, double theta);
/** P(|v| <= s) = (5K-3)/(2K) P(3/2, x) + 3(1-K)/(2K) P(5/2, x),
 *  x = s^2/(2 K theta), P the regularized lower incomplete gamma (GSL). */
double sb_spray_bkw_speed_cdf(double s, double K, double theta);
/** E|v|^4 = theta^2 (30 K - 15 K^2);  E|v|^6 = theta^3 K^2 (315 - 210 K). */
double sb_spray_bkw_m4(double K, double theta);
double sb_spray_bkw_m6(double K, double theta);
/** One velocity from the BKW density (the speed is sqrt(K theta) times a
 *  chi with 3 degrees of freedom with probability (5K - 3)/(2K), else with
 *  5; the direction is isotropic).  SB_EDOM outside the domain. */
int sb_spray_bkw_sample(double K, double theta, gsl_rng *rng, double v[3]);

/** Two-temperature relaxation of a binary mixture (number densities n_a,
 *  n_b in 1/m^3, masses m_a, m_b in kg, zero mean velocities) from T_a0,
 *  T_b0 (K); the mixture temperature (n_a T_a + n_b T_b)/(n_a + n_b) is
 *  constant and Delta = T_a - T_b obeys:
 *   Maxwell kernel (exact for any distributions):
 *     dDelta/dt = -2 B0 (n_a + n_b) m_a m_b/(m_a + m_b)^2 Delta;
 *   hard spheres with both species Maxwellian (exact at t = 0, a closure
 *   afterwards; d = r_a + r_b, s^2 = k_B (T_a/m_a + T_b/m_b)):
 *     dDelta/dt = -(16/3) sqrt(2/pi) pi d^2 (n_a + n_b)
 *                  m_a m_b/(m_a + m_b)^2 s Delta,
 *   solved in closed form (s^2 is linear in Delta).  Outputs T_a, T_b at t
 *  (either pointer may be NULL).  SB_EDOM for non-positive or non-finite
 *  arguments (T may be any finite positive values).  Products of the
 *  rate constants that over/underflow (n near DBL_MAX, m or r near
 *  1e-300) are formed with an extended exponent, and n_a T_a0 + n_b T_b0
 *  through the fractions n_a/n, n_b/n where it overflows (with an
 *  extended exponent where n_a T_a0 or n_b T_b0 is below DBL_MIN, n T
 *  below 1e-300: also where T_m is normal, for the hard-sphere law's
 *  alpha = k_B T_m (1/m_a + 1/m_b) as for T_a, T_b).  A Maxwell rate
 *  below DBL_MIN (n B0 near 1e-300; rate t is then below 4) enters
 *  exp(-rate t) and 1 - exp(-rate t) (expm1) with an extended exponent,
 *  not as a subnormal double with fewer bits.  The
 *  hard-sphere T_a, T_b lie between T_a0 and T_b0, and
 *  sb_spray_two_temp_hs returns them for every argument in the domain:
 *  where an intermediate of its closed form (n T, k T/m, their square
 *  roots, C sqrt(alpha) t) leaves the normal range it is evaluated in a
 *  scaled form with an extended exponent (docs/spray.md, "Extreme
 *  arguments"); never SB_ERANGE.  Both laws give the hotter species as
 *  T_m + f |Delta| and the colder as T_0 + f' |Delta0 - Delta(t)| (T_0
 *  its initial temperature, f, f' the other species' number fraction,
 *  Delta0 - Delta(t) in a form without cancellation, 1 - exp(-x) by
 *  expm1): sums of non-negative terms, so both are positive and neither
 *  loses digits where T_m is far above the colder species (a rare, much
 *  hotter species).  Accuracy: a few ulp against mpmath for both
 *  species (at most 12 ulp over the random ordinary and extreme draws of
 *  tests/ulp_spray.py), also at such corners (m = 1e-320 or 1e300, n or T near
 *  DBL_MAX, T_hot0/T_cold0 = 1e18 with n_hot/n_cold = 1e-9 or 1e-3,
 *  m_a/m_b = 1e10, n T near 1e-318 with T_m normal, a Maxwell rate of
 *  1e-316). */
typedef struct {
  double n_a, n_b, m_a, m_b, r_a, r_b, T_a0, T_b0;
} sb_spray_mixture;
int sb_spray_two_temp_maxwell(const sb_spray_mixture *mx, double B0,
                              double t, double *T_a, double *T_b);
int sb_spray_two_temp_hs(const sb_spray_mixture *mx, double t, double *T_a,
                         double *T_b);
/** The hard-sphere rate dT_a/dt (K/s) for Maxwellian species at T_a, T_b
 *  (finite > 0): NaN with SB_EDOM outside the domain, SB_ERANGE when the
 *  rate overflows.  C, s and n_b/n are formed with an extended exponent
 *  where a plain product leaves the normal range, so the rate is
 *  returned wherever it is a double (m = 1e-320: k T/m overflows,
 *  the rate is 1e-141). */
double sb_spray_two_temp_hs_rate(const sb_spray_mixture *mx, double T_a,
                                 double T_b);

#ifdef __cplusplus
}
#endif

#endif /* SMOLBRIDGE_SPRAY_H */
