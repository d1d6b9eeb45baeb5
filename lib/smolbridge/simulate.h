/* smolbridge/simulate.h — reference simulators: brute-force Monte Carlo of
 * the processes, for validating the closed forms (tests/test_bridge_mc.c,
 * tests/test_langevin_mc.c, `smolbridge validate` V10-V11) and users' own
 * codes.  Unit-free (the Langevin simulator takes whatever units the
 * sb_langevin parameters are in).
 *
 * These routines are deliberately slow and simple: they simulate the path
 * itself on a grid and do not use the closed forms of the bridge or passage
 * modules, so comparing the two is an independent check.
 *
 * Bridges on a grid (sb_sim_bb_*, sb_sim_bes3b_*, sb_sim_bes3_*).  The
 * interval [0, t] is cut into n equal sub-steps of dt = t/n.
 *  - What is EXACT.  The grid values have exactly the law of the process
 *    (sequential Gaussian bridge sampling, no time-discretisation error),
 *    and whether the continuous path crosses the level a inside a sub-step
 *    is drawn as a Bernoulli with the exact crossing probability of the
 *    bridge between the two grid values.  So the event "the path reaches a
 *    in [0, t]" and the index of the sub-step holding the FIRST crossing
 *    have exactly their true law, whatever n (grid-independence is tested).
 *  - What is DISCRETISED.  Only the crossing time: it is known to the
 *    sub-step, i.e. to within dt (use the sub-step midpoint, or a histogram
 *    whose bin edges are grid points).
 *  - The per-sub-step crossing probabilities are written out in simulate.c
 *    independently of sb_bb_cross_prob / sb_bes3b_cross_prob (reflection
 *    principle; Bessel-3 bridge h-transform, docs/simulate.md).
 *
 *   sb_sim_bb_path      1-D Brownian bridge X_0 = x, X_t = y, dX = sigma dW
 *                       (sigma2 = sigma^2).  Grid: X_{k+1} ~ N(X_k + (y -
 *                       X_k) dt/T, sigma2 dt (T - dt)/T), T = t - k dt the
 *                       remaining time.  Sub-step crossing of a (both ends
 *                       above a): exp(-2 (X_k - a)(X_{k+1} - a)/(sigma2 dt)).
 *                       Cost per path: n - 1 Gaussian and <= n uniform draws.
 *   sb_sim_bes3b_path   Bessel-3 bridge R_0 = x, R_t = y, simulated as a 3-D
 *                       Brownian motion B (per-component rate sigma2) from
 *                       (x, 0, 0) conditioned on |B_t| = y: the end point is
 *                       drawn on the sphere of radius y from the von
 *                       Mises-Fisher law prop. to exp(kappa cos theta),
 *                       kappa = x y/(sigma2 t) (exact inversion of cos
 *                       theta, uniform azimuth), then B is a 3-D Brownian
 *                       bridge.  Sub-step crossing drawn from the Bessel-3
 *                       bridge formula given the two NORMS (exact for the
 *                       event: the norm of B is Markov, see docs/simulate.md;
 *                       it is not the crossing probability given the full
 *                       3-D points).  Cost per path: 3(n - 1) Gaussian and
 *                       <= n + 2 uniform draws.
 *   sb_sim_bes3_path    Bessel-3 process from R_0 = x (norm of 3-D BM from
 *                       (x, 0, 0)), unconditioned, first passage down to
 *                       a < x; same sub-step correction.  Cost per path: 3n
 *                       Gaussian and <= n uniform draws.
 * Arguments: finite x, y, a; sigma2 > 0 and t > 0 finite; n >= 1; r and the
 * outputs not NULL.  Bessel-3: a >= 0, x >= 0, y >= 0 (a = 0: never
 * crosses).  Where sigma2 t^2 is outside 2^(+-600), t is first scaled
 * by a power of two into [1, 2) and sigma2 by its inverse (the law is
 * unchanged; elsewhere the draws are bit-identical).  Where sigma2 t
 * exceeds 2^998, or is below 2^-900 with the positions (Brownian bridge:
 * x - a and y - a) within 2^400 of its root, or x - a, y - a or y - x
 * overflows, the positions are also scaled by 2^-m and sigma2 by 2^-2m
 * (the law is unchanged; docs/simulate.md); Bessel-3 norms and the
 * sub-step probability are formed without over- or underflow.  SB_ERANGE
 * (outputs untouched) where no such scale keeps the positions and sigma2 t
 * in range (the positions and sqrt(sigma2 t) more than the doubles apart,
 * e.g. x = 1e-300 with sigma2 t = 1e600).  x <= a is a crossing in
 * sub-step 0 (no draws are made).  The
 * _path functions set *k to the sub-step index in [0, n) of the first
 * crossing, or -1 if the path stays above a; the _hits functions simulate
 * npaths independent paths and set hits[k] (n entries, zeroed first) to the
 * number of first crossings in sub-step k and *ncross to their sum.  Draws
 * use gsl_ran_gaussian_ziggurat and gsl_rng_uniform in a fixed order: same
 * generator state, same result.  Status: SB_SUCCESS, SB_EDOM (bad number),
 * SB_ERANGE (above), SB_EINVAL (NULL pointer, n < 1).
 *
 * Langevin (sb_sim_langevin): np particles with 3 velocity/position
 * components each, all with the parameters p (tau, B, fluid velocity us in
 * every component), advanced in place by nsteps exact steps of dt (Mohaupt
 * 2011, eq 1.16; sb_langevin_step3_coef): exact in law at the grid times,
 * nothing is discretised.  Draw order: step, particle, component, as
 * sb_langevin_step3_coef.  Cost: 6 Gaussian draws per particle and step.
 * Arguments as sb_langevin_coef_init (tau > 0, B >= 0, dt >= 0 finite),
 * finite us and start states x, u, nsteps >= 0; else SB_EDOM (SB_EINVAL
 * for NULL or nsteps < 0), nothing moved.  Every new x and u is checked:
 * where one exceeds DBL_MAX (B sqrt(tau) or the state near DBL_MAX: B =
 * DBL_MAX, tau = dt = 1 gave +-inf with status 0) the run stops with
 * SB_ERANGE, that particle keeps its state before the step (particles
 * before it in the step order have taken it); where only an intermediate
 * overflows (u - us, or sums of terms near DBL_MAX) the update is
 * recomputed with its terms scaled by 1/8 (same draws), so the state is
 * right wherever it is a double.  Otherwise the same bits as
 * sb_langevin_step3_coef.
 */
#ifndef SMOLBRIDGE_SIMULATE_H
#define SMOLBRIDGE_SIMULATE_H

#include <stddef.h>

#include <gsl/gsl_rng.h>
#include <smolbridge/common.h>
#include <smolbridge/langevin.h>

#ifdef __cplusplus
extern "C" {
#endif

/* ----------------------------------------------------- one path */

/** 1-D Brownian bridge x -> y on n sub-steps: *k = first-crossing sub-step
 * of the level a, or -1. */
int sb_sim_bb_path(const gsl_rng *r, double x, double y, double a,
                   double sigma2, double t, int n, int *k);
/** Bessel-3 bridge x -> y (3-D BM conditioned on its end norm). */
int sb_sim_bes3b_path(const gsl_rng *r, double x, double y, double a,
                      double sigma2, double t, int n, int *k);
/** Bessel-3 process from x, first passage down to a within [0, t]. */
int sb_sim_bes3_path(const gsl_rng *r, double x, double a, double sigma2,
                     double t, int n, int *k);

/* ------------------------------------ npaths paths, first-crossing counts */

int sb_sim_bb_hits(const gsl_rng *r, double x, double y, double a,
                   double sigma2, double t, int n, unsigned long npaths,
                   unsigned long *hits, unsigned long *ncross);
int sb_sim_bes3b_hits(const gsl_rng *r, double x, double y, double a,
                      double sigma2, double t, int n, unsigned long npaths,
                      unsigned long *hits, unsigned long *ncross);
int sb_sim_bes3_hits(const gsl_rng *r, double x, double a, double sigma2,
                     double t, int n, unsigned long npaths,
                     unsigned long *hits, unsigned long *ncross);

/* ------------------------------------------------------------ Langevin */

/** Advance np 3-D particles (x, u: 3 np values each, particle-major) by
 * nsteps exact Langevin steps of dt with parameters p. */
int sb_sim_langevin(const sb_langevin *p, double dt, long nsteps,
                    const gsl_rng *r, size_t np, double *x, double *u);

#ifdef __cplusplus
}
#endif

#endif /* SMOLBRIDGE_SIMULATE_H */
