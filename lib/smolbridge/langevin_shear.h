/* langevin_shear.h — a Langevin particle in a linear shear flow: the exact
 * step and the exact bridge of its state in the plane of the flow
 * (docs/langevin.md, "Linear shear").
 *
 * Model (per unit mass).  The particle sees the fluid velocity
 * (G y + c_x, c_y) at its own position:
 *   du_x = (G y + c_x - u_x)/tau dt + B dW_x,   dx = u_x dt,
 *   du_y = (c_y - u_y)/tau dt + B dW_y,         dy = u_y dt,
 * W_x, W_y independent Wiener processes; the third component is a plain
 * Ornstein-Uhlenbeck process (<smolbridge/langevin.h>).  The system is
 * linear, so the in-plane state S = (u_y, y, u_x, x) — this order
 * throughout — is Gaussian at every time, and so is its bridge (the state
 * at an interior time given both ends of a step).  c_x, c_y are constant
 * velocities (the field's value at y = 0, a settling velocity, a
 * Lees-Edwards image's velocity offset); unlike a uniform flow they do
 * change the bridge when G != 0, because x's ends then carry information
 * on the integral of y over the step.
 *
 * Units.  The functions below work in units tau = B = 1: time t/tau,
 * velocity u/(B sqrt(tau)), position x/(B tau^{3/2}), shear g = G tau,
 * drift velocities c/(B sqrt(tau)); x = h/tau is the step.  Over a step
 *   S(h) = Phi(x) S(0) + a(x) (c_x, c_y)^T + N(0, Sigma(x)).
 */
#ifndef SMOLBRIDGE_LANGEVIN_SHEAR_H
#define SMOLBRIDGE_LANGEVIN_SHEAR_H

#include <gsl/gsl_rng.h>

#ifdef __cplusplus
extern "C" {
#endif

/** The step's shear coefficients for x = h/tau >= 0:
 *  c = (A, Bv, C, D), A = x(1 + e^-x) - 2(1 - e^-x), Bv = 1 - e^-x(1 + x),
 *  C = x - (1 - e^-x), D = x^2/2 - x + (1 - e^-x) (series below x = 1:
 *  relative accuracy a few ulps at every x).  In Phi: the response of u_x
 *  and x to u_y(0) is g Bv and g A. */
void sb_langevin_shear_mean_coefs(double x, double c[4]);

/** The mean transition over x = h/tau >= 0: Phi (4 x 4) and the response
 *  a (4 x 2, columns c_x then c_y) to the drift velocities, from
 *  sb_langevin_shear_mean_coefs (u_x and x respond to u_y(0) with g Bv and
 *  g A, to y(0) with g (1 - e^-x) and g C; to c_y with g A and g (D - A),
 *  the last a difference that loses relative accuracy as x -> 0 but
 *  stays within ~1e-16 x^3 absolute).  Checked against mpmath's matrix
 *  exponential through the bridge's reference vectors. */
void sb_langevin_shear_propagator(double x, double g, double Phi[4][4],
                                  double a[4][2]);

/** The mean of S(s) = (u_y, y, u_x, x) after a time s >= 0 from S(0) = s0,
 *  SI units (tau in s, G in 1/s, drift velocities cx, cy in m/s): the
 *  mean transition Phi s0 + a (c_x, c_y) of sb_langevin_shear_propagator
 *  taken to physical units; it does not depend on B, and for a particle
 *  without noise (B = 0) it is the exact path in the linear field (the
 *  Langevin detector's and the engine's; tested against a Runge-Kutta
 *  integration, tests/test_langevin_shear.c).  Domain: tau > 0, s >= 0,
 *  all finite; SB_EDOM (out set to NaN) or SB_EINVAL (NULL) otherwise.
 *  Computed in physical units without the scales sqrt(tau), tau^1.5, so
 *  tau may be anything from subnormal (the particle follows the fluid) to
 *  1e300 (it keeps its velocity); SB_ERANGE (out set to NaN) where a
 *  component overflows (e.g. x ~ G cy s^2/2 at s = 1e300). */
int sb_langevin_shear_mean(double tau, double G, double cx, double cy,
                           double s, const double s0[4], double out[4]);

/** The noise covariance Sigma(x) of S over a step x = h/tau >= 0 with
 *  shear g = G tau (the integral of Phi Q Phi^T, Q = diag(1, 0, 1, 0)),
 *  from closed-form integrals of the response kernels (series below
 *  x = 1.5).  Tested against Van Loan's (1978) matrix exponential at 80
 *  digits for x in [1e-3, 100], g in [1e-3, 10]: 1e-12 relative. */
void sb_langevin_shear_noise_cov(double x, double g, double S[4][4]);

/** The x rows of the lower Cholesky factor of Sigma(x) against the
 *  normals (z1_y, z2_y, z1_x, z2_x), whose y rows are the plain
 *  Ornstein-Uhlenbeck step's (s_u 0; s_xu s_xc) (sb_langevin_coef):
 *  L = (L31, L32, L33, L41, L42, L43, L44); the Schur complement in long
 *  double (it cancels by up to 5 digits at small x). */
void sb_langevin_shear_noise_chol(double x, double g, double L[7]);

/** The bridge of S at time s inside a step x (both in units of tau), given
 *  the ends S(0) and S(x):
 *    E[S(s)] = ka S(0) + kb S(x) + kc (c_x, c_y)^T,   Cov = cov. */
typedef struct {
  double ka[4][4];  /**< coefficients of the start state */
  double kb[4][4];  /**< of the end state */
  double kc[4][2];  /**< of the drift velocities (c_x, c_y) */
  double cov[4][4]; /**< conditional covariance (symmetric) */
} sb_langevin_shear_bridge;

/** The bridge coefficients above.  The covariance in information form
 *  (a sum of positive definite matrices: no difference of large terms),
 *  cov = (Sigma(s)^-1 + Phi(r)^T Sigma(r)^-1 Phi(r))^-1, r = x - s; the
 *  mean coefficients for s <= x/2 in gain form, K = Sigma(s) Phi(r)^T
 *  Sigma(x)^-1, ka = Phi(s) - K Phi(x), kb = K, kc = a(s) - K a(x), and
 *  beyond in information form, ka = cov Sigma(s)^-1 Phi(s),
 *  kb = cov Phi(r)^T Sigma(r)^-1, kc = cov (Sigma(s)^-1 a(s) - Phi(r)^T
 *  Sigma(r)^-1 a(r)) (each form cancels near one end of the step); each
 *  inverse by the Cholesky factor of the matrix scaled to unit diagonal.
 *  At g = 0 the (u_y, y) and (u_x, x) blocks are the Ornstein-Uhlenbeck
 *  bridge of sb_langevin_bridge_moments and kc = 0.  Domain: x in
 *  [1e-9, 1e9], s/x in [1e-3, 0.999], |g| x <= 100, all finite; else
 *  SB_EDOM (SB_EINVAL for NULL b), with b filled with NaN.  Accuracy
 *  (tests/test_langevin_shear.c against a 100-digit direct conditioning,
 *  tests/gen_shear_bridge_ref.py): ka, kb, kc to 1e-10 of the
 *  conditional standard deviation per unit of the step's own noise
 *  scale, cov to 1e-10 of sqrt(cov_ii cov_jj) (measured: 2e-13 and
 *  1e-14; at g = 0 within 5e-11 sd of the OU bridge over the whole
 *  domain). */
int sb_langevin_shear_bridge_coefs(double x, double g, double s,
                                   sb_langevin_shear_bridge *b);

/** The same in SI units: the law of S(s) = (u_y, y, u_x, x) at time s in
 *  [0, h] (s, h in seconds) given S(0) = s0 and S(h) = s1, for a
 *  particle of relaxation time tau > 0 and B > 0 in the shear G (1/s) with
 *  drift velocities cx, cy (m/s).  Domain as sb_langevin_shear_bridge_coefs
 *  with x = h/tau and s/h; mean and cov set to NaN on error.  The mean
 *  does not depend on B and is formed without the scales B sqrt(tau),
 *  B tau^1.5 (any B, tau down to subnormal); the covariance B^2 tau
 *  r_i r_j cov_ij (r = 1 or tau) with the exponents set aside, so it is
 *  right wherever representable, 0 where it underflows; SB_ERANGE (all
 *  outputs NaN) where an output overflows (e.g. B = 1e200). */
int sb_langevin_shear_bridge_moments(double tau, double B, double G,
                                     double cx, double cy, double h,
                                     double s, const double s0[4],
                                     const double s1[4], double mean[4],
                                     double cov[4][4]);

/** One draw of S(s) from that law (SI units as above), for any s in
 *  [0, h]: s = 0 and s = h return the ends; inside [1e-3, 0.999] h it is
 *  the mean plus the Cholesky factor of cov times four normals
 *  (gsl_ran_gaussian_ziggurat, in the order of S); nearer an end the
 *  interval is halved by exact draws at its midpoint (the bridge of a
 *  Markov process restricted to a sub-interval is the bridge between its
 *  ends) until s lies inside; an interval below 1e-9 tau takes each
 *  in-plane pair (u, position) from its Ornstein-Uhlenbeck bridge (the
 *  shear changes the law by O(G h) there).  Domain: tau, B, h > 0,
 *  |G| h <= 100, all finite; SB_EDOM / SB_EINVAL otherwise, out set to
 *  NaN.  Where B sqrt(tau) or B tau^1.5 is below DBL_MIN (B subnormal,
 *  e.g. 1e-320) the draw is formed in SI units instead (the mean as in
 *  sb_langevin_shear_bridge_moments, the noise scaled with the exponents
 *  set aside; within 1e-9 tau of an end, with B and the states scaled by
 *  a power of 2), so it is finite; elsewhere the computation, and the
 *  output for a given generator state, are unchanged.  SB_ERANGE (out
 *  NaN) if the draw is still not finite (states ~1e300 standard
 *  deviations apart). */
int sb_langevin_shear_bridge_sample(double tau, double B, double G,
                                    double cx, double cy, double h,
                                    double s, const double s0[4],
                                    const double s1[4], const gsl_rng *r,
                                    double out[4]);

#ifdef __cplusplus
}
#endif

#endif /* SMOLBRIDGE_LANGEVIN_SHEAR_H */
