/* smolbridge/engine_field.h — random fluid velocity fields for the
 * collision engine, handed to it through its fluid callback
 * (sb_engine_set_fluid_fn); docs/engine_forces.md §8.  SI units.
 *
 * 1. Per-particle Ornstein-Uhlenbeck "fluid velocity seen" (sb_field_ou):
 *    particle i sees U_i(t), independent between particles and
 *    components, a stationary OU process of per-component variance u'^2
 *    (m^2/s^2) and Lagrangian correlation time T_L (s), advanced exactly
 *    over each engine step h (Gardiner 2009, Stochastic Methods, §3.8.4:
 *    U <- b U + sqrt(u'^2 (1 - b^2)) Z, b = exp(-h/T_L)) and held
 *    constant during the step (the engine evaluates U_s at the start of
 *    the step).  No spatial structure: the model of a particle that
 *    forgets the eddy it is in before it responds to it, so that two
 *    particles' velocities are independent (Abrahamson 1975, Chem. Eng.
 *    Sci. 30:1371; the kernel is sb_kernel_abrahamson).
 *
 * 2. Kraichnan (1970, Phys. Fluids 13:22, eqs 2-4) random Fourier modes
 *    (sb_field_kraichnan):
 *      U(x, t) = sum_n [a_n cos(k_n.x + w_n t) + b_n sin(k_n.x + w_n t)],
 *    a_n = zeta_n x khat_n, b_n = xi_n x khat_n with zeta, xi independent
 *    N(0, s2 I_3) vectors (divergence-free: a_n.k_n = b_n.k_n = 0),
 *    w_n = 0 (frozen) or N(0, omega^2) (Kraichnan's time-dependent
 *    field).  Wave vectors: every lattice vector k = 2 pi m / L (m
 *    integer, one of each pair +-m) with M - 1/2 < |m| < M + 1/2 (the
 *    "shell" M), so the field is periodic in the cube of edge L.  At every
 *    point the velocity is Gaussian over realizations with per-component
 *    variance 2 N s2 / 3 (N modes) and <A_ij A_ij> = 2 s2 sum |k_n|^2
 *    (A = grad U), which is eps/nu: s2 is set from the prescribed eps/nu.
 *    In a linear, isotropic Gaussian flow the pass-through collision rate
 *    is Saffman & Turner's (1956) kernel (sb_kernel_saffman_turner).
 *
 * Generators: each field draws from the gsl_rng given at allocation (not
 * owned; it must outlive the field).  Thread safety: a field belongs to
 * one engine; distinct fields are independent.  Errors: status codes with
 * a message in sb_last_error(); nothing is printed. */
#ifndef SMOLBRIDGE_ENGINE_FIELD_H
#define SMOLBRIDGE_ENGINE_FIELD_H

#include <stddef.h>
#include <gsl/gsl_rng.h>
#include <smolbridge/common.h>
#include <smolbridge/engine.h>

#ifdef __cplusplus
extern "C" {
#endif

/* ============================================ OU seen velocity (1.) */

typedef struct sb_field_ou sb_field_ou;

/** Field for n particles (n >= 1), u2 >= 0 (m^2/s^2), T_L > 0 (s), engine
 *  step dt > 0 (s).  Stationary start: the 3 n seen velocities are drawn
 *  N(0, u2) from r (in index order, components in turn).  NULL on a bad
 *  argument (SB_EINVAL) or allocation failure (SB_ENOMEM). */
sb_field_ou *sb_field_ou_alloc(size_t n, double u2, double TL, double dt,
                               const gsl_rng *r);
void sb_field_ou_free(sb_field_ou *f);

/** The seen velocities the next step hands out, 3 n (m/s). */
const double *sb_field_ou_seen(const sb_field_ou *f);

/** sb_engine_fluid_fn (ctx: the field): hands out U_i (particle i at
 *  index i) and advances the field by dt (3 n draws from its generator).
 *  The engine calls it once per step with all its particles; any other
 *  call (n differing from the field's: an outcome or inflow that
 *  evaluates the fluid at one place, a particle added or removed) is
 *  refused (SB_EINVAL), as the field does not know which particle is
 *  asking.  Particles must not be reordered (sort_every = 0). */
int sb_field_ou_fluid(size_t n, const double *x, double *us, void *ctx);

/** Install the field as e's fluid; SB_EINVAL unless e holds exactly the
 *  field's n particles. */
int sb_field_ou_attach(sb_engine *e, sb_field_ou *f);

/** Save the field (its parameters and seen velocities) to path, beside an
 *  engine checkpoint of the same step; with_rng = 1 also the state of its
 *  generator (one of its own, apart from the engine's, whose state the
 *  checkpoint keeps).  Native binary, like the checkpoint.  SB_EINVAL,
 *  SB_EIO (cannot write; no file is left). */
int sb_field_ou_save(const sb_field_ou *f, int with_rng, const char *path);
/** The saved field, drawing from r from now on (no draws here: the
 *  engine's generator, as restored by its checkpoint, or a generator of
 *  the saved one's type, whose state the file then replaces): u2, T_L
 *  and dt must be the saved ones (SB_EINVAL), as must r's type when the
 *  file holds a generator.  Attach it to the engine restored from the
 *  same checkpoint: the run goes on bit for bit as if it had not
 *  stopped.  NULL with *status (may be NULL) SB_EINVAL, SB_EIO (cannot
 *  open), SB_EFORMAT (not such a file, truncated, or damaged: the file
 *  ends in a hash of its contents, format SBFOU002, checked before
 *  anything is read; SBFOU001 files, without it, still load) or
 *  SB_ENOMEM; r is unchanged on failure. */
sb_field_ou *sb_field_ou_load(const char *path, double u2, double TL,
                              double dt, gsl_rng *r, int *status);

/** Stationary per-component velocity variance of a Stokes particle
 *  (relaxation time tau, s) driven by the field held constant over steps
 *  of dt with the exact step: -> u2 T_L/(T_L + tau) as dt -> 0 (relative
 *  deviation O(dt/T_L)).  With u_{k+1} = a u_k + (1 - a) U_k,
 *  U_{k+1} = b U_k + noise (a = exp(-dt/tau), b = exp(-dt/T_L)):
 *  c = Cov(u, U) = b (1 - a) u2/(1 - a b), Var u = (2 a c + (1 - a) u2)/
 *  (1 + a).  A Brownian part (B) adds its own B^2 tau/2, independent. */
double sb_field_ou_particle_var(double u2, double TL, double tau, double dt);
/** Its stationary covariance with the seen velocity handed out at the same
 *  step, Cov(u_k, U_k) (-> the same limit). */
double sb_field_ou_particle_cov(double u2, double TL, double tau, double dt);

/** Stationary start of particle i (species relaxation time tau) jointly
 *  with its seen velocity: u = mean + N(0, var) per component with
 *  mean[k] = (c/u2) U_ik and var = Var u - c^2/u2 (the Gaussian
 *  conditional law; c, Var u as above; u2 = 0 or tau = inf: mean 0,
 *  var 0).  Add the
 *  Brownian variance B^2 tau/2 to var for a Langevin species.  SB_EINVAL
 *  for i >= n or tau <= 0. */
int sb_field_ou_start(const sb_field_ou *f, size_t i, double tau,
                      double mean[3], double *var);

/* ================================================ Kraichnan (2.) */

/** Largest shell M, and the modes it can hold. */
#define SB_FIELD_KRAICHNAN_MAXM 3
#define SB_FIELD_KRAICHNAN_MAXMODES 64

typedef struct sb_field_kraichnan sb_field_kraichnan;

/** One realization on the shell M (1 .. SB_FIELD_KRAICHNAN_MAXM; M = 1: 9
 *  modes, 2: 31, 3: 49) of the cube of edge L (m), <A_ij A_ij> = eps_nu
 *  (1/s^2, > 0), frequencies N(0, omega^2) (1/s; 0: frozen).  Draws from
 *  r, mode by mode in lattice order: zeta (3), xi (3), then w if
 *  omega > 0.  NULL on a bad argument (SB_EINVAL) or SB_ENOMEM. */
sb_field_kraichnan *sb_field_kraichnan_alloc(double L, int M, double eps_nu,
                                             double omega,
                                             const gsl_rng *r);
void sb_field_kraichnan_free(sb_field_kraichnan *f);

/** Save the realization (its parameters and modes) to path: drawn once,
 *  it cannot be drawn again from a generator that has moved on.  Native
 *  binary.  SB_EINVAL, SB_EIO (cannot write; no file is left). */
int sb_field_kraichnan_save(const sb_field_kraichnan *f, const char *path);
/** The saved realization; L, M, eps_nu and omega must be the saved ones
 *  (SB_EINVAL).  NULL with *status (may be NULL) SB_EINVAL, SB_EIO,
 *  SB_EFORMAT (not such a file, truncated, or damaged: hash as in
 *  sb_field_ou_load, format SBFKR002; SBFKR001 still loads) or
 *  SB_ENOMEM. */
sb_field_kraichnan *sb_field_kraichnan_load(const char *path, double L,
                                            int M, double eps_nu,
                                            double omega, int *status);

/** Number of modes N. */
size_t sb_field_kraichnan_modes(const sb_field_kraichnan *f);

/** Velocities us[3i..3i+2] (m/s) at the n positions x[3i..3i+2] (m) at
 *  time t (s).  A NULL argument: nothing written, sb_last_error set. */
void sb_field_kraichnan_eval(const sb_field_kraichnan *f, double t,
                             size_t n, const double *x, double *us);

/** Install the field as e's fluid, evaluated at the engine's time
 *  (sb_engine_time: the start of the step, or of the run at placement).
 *  SB_EINVAL unless e is 3-D with every box edge equal to the field's L
 *  (relative 1e-12: the field is periodic in that cube). */
int sb_field_kraichnan_attach(sb_engine *e, sb_field_kraichnan *f);

/** Ensemble per-component velocity variance 2 N s2/3 (m^2/s^2). */
double sb_field_kraichnan_u2(const sb_field_kraichnan *f);
/** Ensemble <(dU_x/dx)^2> = s2 sum |k|^2 khat_x^2 (1 - khat_x^2) (1/s^2)
 *  (eps/(15 nu) for an isotropic field; the lattice shell is cubic). */
double sb_field_kraichnan_a11(const sb_field_kraichnan *f);
/** Exact collision rate (m^3/s) of pass-through tracer pairs at contact
 *  distance R (m) in this field: the ensemble inward flux through the
 *  contact sphere, velocities Gaussian over realizations,
 *  R^2/sqrt(2 pi) int sd(w.n) dOmega with Var(w.n) = sum_n s2 (1 -
 *  (khat.n)^2) 2 (1 - cos(R k.n)); product quadrature (64 Gauss-Legendre
 *  nodes in cos theta, 128 in phi; the integrand is smooth for R k <= 2).
 *  -> Saffman & Turner (1956) as R k -> 0 for an isotropic field. NaN if
 *  the quadrature table cannot be allocated. */
double sb_field_kraichnan_flux_kernel(const sb_field_kraichnan *f, double R);

#ifdef __cplusplus
}
#endif

#endif /* SMOLBRIDGE_ENGINE_FIELD_H */
