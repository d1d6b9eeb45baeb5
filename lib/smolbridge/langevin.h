/* smolbridge/langevin.h — Langevin / Ornstein–Uhlenbeck references: exact
 * moments, exact transition (scalar and batched 3-D), conditioned ("bridge")
 * sampling, and SI helpers for Brownian particles.
 *
 * Model, per Cartesian component (Mohaupt 2011, eq 1.15, with U_s held
 * constant over the step):
 *
 *     dX = U dt,     dU = (us - U)/tau dt + B dW,
 *
 * tau > 0 the relaxation time, B >= 0 the velocity-diffusion coefficient,
 * us the (constant) fluid velocity seen, W a standard Wiener process.
 * The core routines are unit-free: use any consistent units (tau and t in
 * the same time unit, B in velocity / sqrt(time)).  The SI helpers at the
 * end take and return SI units.
 *
 * Notation used below: h = t/tau, e = exp(-h), a = 1 - e = -expm1(-h).
 *
 * Exact moments from (x0, u0) at time 0 (Ito isometry; see docs/langevin.md
 * for the derivation; Mohaupt 2011, App. D, eqs D.1–D.6, is the case us = 0):
 *   mean_u = us + (u0 - us) e
 *   mean_x = x0 + us t + (u0 - us) tau a
 *   var_u  = B^2 tau/2 (1 - e^2)                   (-> B^2 tau/2, stationary)
 *   cov_xu = B^2 tau^2 a^2 / 2
 *   var_x  = B^2 tau^2 [t - 2 tau a + tau/2 (1 - e^2)]
 *          = B^2 tau^3 [c(h) + a^3 / (2 (2 - a))]     (the stable form used)
 *   var_x|u = var_x - cov_xu^2/var_u = B^2 tau^2 [t - 2 tau a/(1+e)]
 *          = B^2 tau^3 c(h),    c(h) = h - 2 tanh(h/2)
 * The textbook form of var_x loses all digits for t << tau (it is a
 * difference of O(h) terms with an O(h^3) result); the forms above are sums
 * of non-negative terms, and c(h) is evaluated for h <= 2 by the positive
 * series 2 (y cosh y - sinh y)/cosh y = 2 sum_{n>=1} 2n y^{2n+1}/(2n+1)! /
 * cosh y, y = h/2.  Accuracy: every moment here is within a few ulps
 * (tested <= 1e-13 relative, against mpmath at 150 digits) for
 * t/tau in [1e-10, 1e10]; below 1e-10 the results stay accurate until
 * var_x underflows (t/tau ~ 1e-100 for tau = B = 1).
 *
 * Extreme arguments (docs/langevin.md §6): every function returns the
 * right value wherever it is a double, for any tau, B, t in the double
 * range (tau = 1e300 with t = 1: var_x = B^2 t^3/3; tau = 1e-300 with
 * t = 1e300: B^2 tau^2 t; B^2 or tau^3 beyond DBL_MAX): the products are
 * formed with the exponents set aside (the same bits as the formulas
 * above wherever nothing over/underflows) and the unit-free kernels by
 * their leading term where t/tau is below ~1e-100 or above DBL_MAX.  A
 * value above DBL_MAX is SB_ERANGE (NaN for the plain forms); one below
 * DBL_MIN is 0 or a subnormal, without error.
 *
 * Thread safety: no global state; generators are passed in by the caller.
 * Randomness: Gaussian variates come from gsl_ran_gaussian_ziggurat, drawn
 * in a documented order, so the same generator state gives bit-identical
 * output.
 */
#ifndef SMOLBRIDGE_LANGEVIN_H
#define SMOLBRIDGE_LANGEVIN_H

#include <stddef.h>
#include <stdint.h>
#include <gsl/gsl_rng.h>
#include <smolbridge/common.h>
#include <smolbridge/rng.h>

#ifdef __cplusplus
extern "C" {
#endif

/* ============================================================ parameters */

/** Parameters of one component of the Langevin model.
 *  tau > 0 and finite; B >= 0 and finite; us finite. */
typedef struct {
  double tau;  /**< relaxation time */
  double B;    /**< velocity-diffusion coefficient (dU noise amplitude) */
  double us;   /**< fluid velocity seen, constant over the time considered */
} sb_langevin;

/** Mean and covariance of the state (X, U) at one time. */
typedef struct {
  double mean_x, mean_u;
  double var_x, var_u, cov_xu;
} sb_langevin_mom;

/* ====================================================== exact moments */

/** Exact moments of (X_t, U_t) given X_0 = x0, U_0 = u0 (formulas above).
 *  Domain: valid *p, t >= 0 finite, x0 and u0 finite; else SB_EDOM (and
 *  SB_EINVAL for NULL pointers), with *m set to NaN; SB_ERANGE, *m NaN,
 *  where a moment exceeds DBL_MAX.  Accuracy: variances
 *  and covariance to a few ulps; the means to a few ulps of the largest of
 *  |x0|, |us t|, |(u0 - us) tau a|. */
int sb_langevin_moments(const sb_langevin *p, double t, double x0, double u0,
                        sb_langevin_mom *m);

/* The next functions depend on (tau, B, t) only.  Domain: tau > 0, B >= 0,
 * t >= 0, all finite (t may be negative for the autocorrelation).  The plain
 * form returns NaN on a domain error (SB_EDOM) or where the value exceeds
 * DBL_MAX (SB_ERANGE, recorded for sb_last_error); the _e form returns the
 * status and an error estimate err (a bound, a few ulps of val). */

/** Velocity variance B^2 tau/2 (1 - e^{-2t/tau}) = B^2 tau/2 a (2 - a). */
double sb_langevin_var_u(double tau, double B, double t);
int sb_langevin_var_u_e(double tau, double B, double t, sb_result *res);

/** Position variance (formula above), stable for all t/tau. */
double sb_langevin_var_x(double tau, double B, double t);
int sb_langevin_var_x_e(double tau, double B, double t, sb_result *res);

/** Position–velocity covariance B^2 tau^2 (1 - e^{-t/tau})^2 / 2. */
double sb_langevin_cov_xu(double tau, double B, double t);
int sb_langevin_cov_xu_e(double tau, double B, double t, sb_result *res);

/** Variance of X_t given U_t (and the start state): B^2 tau^2
 *  [t - 2 tau (1-e)/(1+e)] = B^2 tau^3 (h - 2 tanh(h/2)).  It is the
 *  variance of the zeta_x term of Mohaupt (2011) eq 1.16.  Small t:
 *  B^2 t^3/12. */
double sb_langevin_var_x_cond(double tau, double B, double t);
int sb_langevin_var_x_cond_e(double tau, double B, double t, sb_result *res);

/** Stationary (equilibrium) velocity variance B^2 tau / 2 (= k_B T / m_p
 *  for Brownian particles; Mohaupt 2011, eq A.4). */
double sb_langevin_var_stat(double tau, double B);

/** Mean-square displacement <(X_t - X_0)^2> with a stationary (Maxwellian)
 *  initial velocity U_0 ~ N(us, B^2 tau/2), measured in the frame moving
 *  with us (Ornstein 1919; Uhlenbeck & Ornstein 1930):
 *      MSD(t) = B^2 tau^2 [t - tau (1 - e^{-t/tau})]
 *             = var_x(t) + B^2 tau^3 a^2/2      (no cancellation).
 *  Limits: ballistic B^2 tau t^2/2 (t << tau), diffusive B^2 tau^2 t =
 *  2 D t (t >> tau), see the two functions below. */
double sb_langevin_msd(double tau, double B, double t);
int sb_langevin_msd_e(double tau, double B, double t, sb_result *res);

/** Ballistic limit of the MSD: (B^2 tau/2) t^2 = <U^2>_eq t^2. */
double sb_langevin_msd_ballistic(double tau, double B, double t);

/** Diffusive limit of the MSD: B^2 tau^2 t (= 2 D t, D = B^2 tau^2/2). */
double sb_langevin_msd_diffusive(double tau, double B, double t);

/** Stationary velocity autocorrelation <(U_0 - us)(U_t - us)> =
 *  B^2 tau/2 exp(-|t|/tau); t may be any finite real. */
double sb_langevin_vacf(double tau, double B, double t);

/* ================================================== exact transition */

/** Exact one-step transition (Peirano, Chibbaro, Pozorski &
 *  Minier 2006; Mohaupt 2011, eq 1.16):
 *  replaces (*x, *u) by a draw of (X_dt, U_dt) given (X_0, U_0) = (*x, *u),
 *
 *    U_dt = us + (u - us) e + s_u z1
 *    X_dt = x + us dt + (u - us) tau a + s_xu z1 + s_xc z2
 *
 *  z1, z2 independent N(0,1) drawn in that order with
 *  gsl_ran_gaussian_ziggurat; s_u^2 = var_u, s_xu = cov_xu / s_u,
 *  s_xc^2 = var_x|u (a Cholesky factor of the exact covariance, written
 *  without dividing by var_u so that dt -> 0 is not degenerate).
 *  Domain: valid *p, dt >= 0 finite (dt = 0 leaves the state unchanged),
 *  valid for dt/tau in [1e-10, 1e10] and beyond; *x, *u finite.
 *  Errors: SB_EDOM / SB_EINVAL, state unchanged; SB_ERANGE, state
 *  unchanged, where a coefficient (sb_langevin_coef_init) or the new
 *  state exceeds DBL_MAX (where only an intermediate such as u - us
 *  overflows, the update is recomputed with its terms scaled by 1/8:
 *  the new state is right wherever it is a double). */
int sb_langevin_step(const sb_langevin *p, double dt, const gsl_rng *r,
                     double *x, double *u);

/** Precomputed coefficients of the exact step for one (tau, B, dt): the
 *  batched stepper reuses them across steps and particles.
 *  Fill with sb_langevin_coef_init(); the fields are read-only to callers. */
typedef struct {
  double dt;     /**< the step */
  double decay;  /**< e = exp(-dt/tau) */
  double gain;   /**< tau a = tau (1 - e): X gain per unit (u - us) */
  double s_u;    /**< sqrt(var_u) */
  double s_xu;   /**< cov_xu / sqrt(var_u): X noise correlated with U */
  double s_xc;   /**< sqrt(var_x|u): X noise independent of U */
} sb_langevin_coef;

/** Coefficients of the exact step of length dt for (tau, B).
 *  Domain: tau > 0, B >= 0, dt >= 0, all finite; else SB_EDOM, *c NaN.
 *  Right at any such arguments (tau = 1e300 with dt = 1: s_xu = B/2,
 *  s_xc = B/sqrt(12)); SB_ERANGE, *c NaN, where one exceeds DBL_MAX
 *  (B tau^1.5 ~ 1e450). */
int sb_langevin_coef_init(sb_langevin_coef *c, double tau, double B,
                          double dt);

/** Batched 3-D exact step, each particle with its own tau, B and fluid
 *  velocity (the engine's interface).
 *
 *  Layout ("array of 3-vectors"): particle i has position
 *  x[3i], x[3i+1], x[3i+2], velocity u[3i..3i+2] and fluid velocity
 *  us[3i..3i+2]; tau[i], B[i].  us may be NULL (fluid at rest).
 *  The three components are independent copies of the 1-D model.
 *  Draw order: for i = 0..n-1, for k = 0..2: z1, z2 (as sb_langevin_step),
 *  so a batch of n particles equals n*3 scalar steps in that order.
 *  All tau[i], B[i] and the states x, u, us (finite) are validated before
 *  anything moves (SB_EDOM and no change on a bad one; SB_ERANGE and no
 *  change where a coefficient overflows, as sb_langevin_coef_init).  Coefficients are computed per particle; use
 *  sb_langevin_step3_coef to reuse precomputed ones. */
int sb_langevin_step3(size_t n, double dt, const double *tau,
                      const double *B, const double *us, double *x,
                      double *u, const gsl_rng *r);

/** Batched 3-D exact step with precomputed coefficients: particle i uses
 *  coef[cidx[i]] (a table per particle class), or coef[i] if cidx is NULL.
 *  Layout and draw order as sb_langevin_step3; us may be NULL.  The
 *  coefficients are trusted (built by sb_langevin_coef_init), and neither
 *  the states nor us are checked: this is the fast path (see
 *  bench/bench_langevin.c for its cost). */
int sb_langevin_step3_coef(size_t n, const sb_langevin_coef *coef,
                           const size_t *cidx, const double *us, double *x,
                           double *u, const gsl_rng *r);

/** One component of the exact step for given standard normals z1, z2
 *  (the draws of sb_langevin_step, in that order) and fluid velocity w:
 *  the bits of sb_langevin_step3_coef wherever nothing overflows; where
 *  only an intermediate does (u - w, or terms of opposite signs near
 *  DBL_MAX), the same sums scaled by 1/8.  Updates *x, *u and returns
 *  SB_SUCCESS, or returns SB_ERANGE with *x, *u unchanged and no error
 *  recorded where the new x or u exceeds DBL_MAX (the caller names
 *  itself).  c from sb_langevin_coef_init (trusted); for callers that
 *  draw their own normals, such as sb_sim_langevin. */
int sb_langevin_update(const sb_langevin_coef *c, double w, double z1,
                       double z2, double *x, double *u);

/** Batched 3-D exact step drawing from counter-based streams
 *  (smolbridge/rng.h): particle i takes the first six normals of the
 *  stream (seed, id_i, step), id_i = ids[i] (or id0 + i if ids is NULL),
 *  as (z1, z2) for x, then y, then z, with the update of sb_langevin_step.
 *  The result for a particle depends only on (seed, id_i, step) and its
 *  own state: any split of the particles over calls or threads, in any
 *  order, gives bit-identical states (the engine's per-particle stream).
 *  coef, cidx, us and the layout as sb_langevin_step3_coef.  SB_EDOM (and
 *  nothing moves) if an id exceeds SB_STREAM_MAX_ID or step
 *  SB_STREAM_MAX_STEP; SB_EINVAL for NULL coef, x or u with n > 0.
 *  The normals are Philox4x32-10 ziggurat draws (sb_stream_gaussian);
 *  cost in bench/bench_langevin.c. */
int sb_langevin_step3_stream(size_t n, const sb_langevin_coef *coef,
                             const size_t *cidx, const double *us,
                             double *x, double *u, uint64_t seed,
                             uint64_t step, const uint64_t *ids,
                             uint64_t id0);

/** One particle's 3-D exact step with the next six normals of *s:
 *  x[0..2], u[0..2], us[0..2] (us may be NULL); the same numbers as
 *  sb_langevin_step3_stream when *s was just set by sb_stream_init(s,
 *  seed, id, step).  SB_EINVAL for a NULL pointer (other than us). */
int sb_langevin_step3_draw(const sb_langevin_coef *c, const double *us,
                           double *x, double *u, sb_stream *s);

/* ======================================= conditioned ("bridge") sampling */

/** Law of (X_s, U_s) given (X_0, U_0) = (x0, u0) and (X_dt, U_dt) =
 *  (x1, u1), 0 <= s <= dt: Gaussian, with mean and covariance returned in
 *  *m.  Covariance in information form, P^{-1} with P = Sigma_s^{-1} +
 *  Phi^T Sigma_r^{-1} Phi (r = dt - s, Phi the mean-transition matrix over
 *  r); mean m_s + K (z1 - m_dt) with the gain K = Sigma_s Phi^T
 *  Sigma_dt^{-1}; each Sigma^{-1} uses the analytic determinant
 *  var_u * var_x|u.  Accuracy (against a 150-digit direct conditioning of
 *  the joint law, dt/tau in [1e-8, 1e6], s/dt in [1e-3, 0.999]): variances
 *  and covariance to a few ulps; means to 1e-11 conditional standard
 *  deviations or one ulp of the value.
 *  Diffusive limit (dt >> tau): X_s tends to the Brownian bridge with
 *  B_pos = B tau (variance B^2 tau^2 s(dt-s)/dt, Mohaupt 2011, eq J.5) between
 *  x0 + tau u0 and x1 - tau u1 (Y = X + tau U is exactly a Brownian
 *  motion).  Domain: valid *p with B > 0, dt > 0, s in [0, dt],
 *  all finite, and s, dt - s each either 0 or >= 1e-60 tau, and
 *  dt <= 1e300 tau (SB_EDOM otherwise: the scaled precision would
 *  overflow).  s = 0 and s = dt return the end states with zero variance.
 *  Any B, tau in the double range: where B sqrt(tau) or B tau^1.5 leaves
 *  the normal range the mean is formed without those scales.  SB_ERANGE
 *  (outputs NaN) where u0 - us, u1 - us, x1 - x0 - us dt or a moment
 *  exceeds DBL_MAX. */
int sb_langevin_bridge_moments(const sb_langevin *p, double dt, double s,
                               double x0, double u0, double x1, double u1,
                               sb_langevin_mom *m);

/** One draw of (X_s, U_s) from the conditioned law above (exact):
 *  X_s = mean_x + L11 z1, U_s = mean_u + L21 z1 + L22 z2 with L the
 *  Cholesky factor of the conditional covariance; z1, z2 drawn in that
 *  order with gsl_ran_gaussian_ziggurat.  Domain as above; on error
 *  (SB_ERANGE also where the draw exceeds DBL_MAX) *xs, *us are set to
 *  NaN. */
int sb_langevin_bridge_sample(const sb_langevin *p, double dt, double s,
                              double x0, double u0, double x1, double u1,
                              const gsl_rng *r, double *xs, double *us);

/* ================================================= SI helpers (SI units)
 * Products and quotients of the arguments, right wherever the value is a
 * double (an intermediate such as d_p^3 or nu/eps may over/underflow);
 * NaN and SB_ERANGE where it exceeds DBL_MAX, 0 or a subnormal without
 * error below DBL_MIN.  Domain errors: NaN and SB_EDOM. */

/** Boltzmann constant, J/K (exact since the 2019 SI redefinition). */
#define SB_BOLTZMANN 1.380649e-23

/** Stokes relaxation time tau_p = rho_p d_p^2 Cc / (18 mu_f), s
 *  (Mohaupt 2011, eq 1.4, with mu_f = rho_f nu_f; Cc the Cunningham slip
 *  correction, 1 for none).  rho_p [kg/m^3] > 0, d_p [m] > 0,
 *  mu_f [Pa s] > 0, cc >= 1.  NaN and SB_EDOM otherwise. */
double sb_stokes_tau(double rho_p, double d_p, double mu_f, double cc);

/** Mass of a sphere rho_p pi d_p^3 / 6, kg. */
double sb_sphere_mass(double rho_p, double d_p);

/** Brownian velocity-diffusion coefficient B = sqrt(2 k_B T / (m_p tau_p)),
 *  m/s^{3/2} (Mohaupt 2011, eqs 1.5, A.5: it makes the stationary velocity
 *  variance B^2 tau_p/2 equal k_B T/m_p).  T [K] > 0, m_p [kg] > 0,
 *  tau_p [s] > 0. */
double sb_brownian_B(double T, double m_p, double tau_p);

/** Stokes–Einstein diffusion coefficient D = k_B T Cc / (3 pi mu_f d_p)
 *  = k_B T Cc / (6 pi mu_f r_p), m^2/s.  It equals B^2 tau_p^2 / 2 with
 *  tau_p and B from the two functions above (for the same Cc and
 *  rho_p = m_p / (pi d_p^3/6)).  T > 0, mu_f > 0, d_p > 0, cc >= 1. */
double sb_einstein_D(double T, double mu_f, double d_p, double cc);

/** Knudsen number of a particle, Kn = 2 lambda / d_p (mean free path of
 *  the gas over the particle radius: the convention of the Cunningham
 *  fits below).  lambda [m] > 0, d_p [m] > 0. */
double sb_knudsen(double lambda, double d_p);

/** Cunningham slip correction with the classic coefficients of Davies
 *  (1945), Proc. Phys. Soc. 57, 259:
 *      Cc = 1 + Kn [1.257 + 0.400 exp(-1.10 / Kn)],  Kn = 2 lambda/d_p
 *  (fitted for air with lambda = 0.066 um at NTP; use the mean free path
 *  of the same convention).  Kn >= 0; Cc(0) = 1. */
double sb_cunningham(double kn);

/** Cunningham correction with user coefficients (another published fit of
 *  the same form, with Kn = 2 lambda / d_p):
 *  Cc = 1 + Kn [A1 + A2 exp(-A3 / Kn)].  Kn >= 0, A1, A2, A3 finite and
 *  A3 >= 0. */
double sb_cunningham_gen(double kn, double A1, double A2, double A3);


/* ------------------------------------------------ dimensionless numbers
 * For choosing a regime and a time step (docs/langevin.md §5).  SI units;
 * NaN and SB_EDOM when an argument is not finite and positive (w >= 0 is
 * allowed).  Accuracy: a few ulps (plain products, quotients and roots). */

/** Kolmogorov time scale tau_eta = sqrt(nu/eps), s (Pope 2000, §6.1):
 *  eps [m^2/s^3] > 0, nu [m^2/s] > 0. */
double sb_kolmogorov_time(double eps, double nu);

/** Kolmogorov length scale eta = (nu^3/eps)^(1/4), m (Pope 2000, §6.1). */
double sb_kolmogorov_length(double eps, double nu);

/** Stokes number St = tau_p / tau_f, the particle relaxation time over a
 *  time scale of the flow (tau_f = sb_kolmogorov_time for the
 *  dissipative range of turbulence: St << 1 means the particle follows
 *  the sub-Kolmogorov shear, the premise of Saffman & Turner 1956). */
double sb_stokes_number(double tau_p, double tau_f);

/** Particle Reynolds number Re_p = w d_p / nu_f, w >= 0 the slip speed
 *  |u_p - u_f| (m/s), d_p [m] > 0, nu_f [m^2/s] > 0.  Stokes drag (and
 *  sb_stokes_tau) assumes Re_p << 1. */
double sb_particle_reynolds(double d_p, double w, double nu_f);

/** Mean relative speed of colliding pairs of identical particles whose
 *  velocities are independent isotropic Gaussians of per-component
 *  variance u2 (m^2/s^2): the collision-weighted mean
 *  E|w|^2 / E|w| = (3/2) sqrt(pi u2) (m/s).  For Brownian particles
 *  u2 = k_B T/m_p. */
double sb_collision_speed(double u2);

/** Wunsch's time-step limit for overlap (and contact-time) detection
 *  (Wunsch 2009; Mohaupt 2011, eq 3.2): the thesis writes
 *    (3/2) sqrt(pi T_p) dt_lim / d_p = 13%,
 *  calling (3/2) sqrt(pi T_p) dt the mean displacement per step; the
 *  factor is exactly sb_collision_speed(T_p), the mean relative speed of
 *  colliding pairs, so dt_lim is the step over which a colliding pair
 *  approaches by frac d_p:
 *    dt_lim = frac d_p / ((3/2) sqrt(pi u2)),
 *  frac = 0.13 the value Wunsch found to detect all collisions.
 *  u2 [m^2/s^2] the per-component velocity variance (T_p, the agitation
 *  per unit mass), d_p [m].  Mohaupt's worked values assume Brownian
 *  agitation u2 = k_B T/m_p with rho_p = 1000 kg/m^3 and T = 300 K (no
 *  fluid property enters): 5.5e-8 s at 0.1 um, 5.5e-3 s at 10 um (computed
 *  5.4976e-8 and 5.4976e-3 s; dt_lim ~ d_p^(5/2)). */
double sb_wunsch_dt(double d_p, double u2, double frac);

/** The same for a Brownian sphere of density rho_p [kg/m^3] at
 *  temperature T [K]: u2 = k_B T / (rho_p pi d_p^3/6). */
double sb_wunsch_dt_brownian(double d_p, double rho_p, double T,
                             double frac);

#ifdef __cplusplus
}
#endif

#endif /* SMOLBRIDGE_LANGEVIN_H */
