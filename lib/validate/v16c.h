/* v16c.h — random fluid velocity fields of the V16 Abrahamson and
 * Saffman-Turner cases (lib/validate/v16_field.c; theory in
 * docs/engine_forces.md §8).  SI units.  Private to lib/validate. */
#ifndef SB_VALIDATE_V16C_H
#define SB_VALIDATE_V16C_H

#include <stddef.h>
#include <gsl/gsl_rng.h>

/* Per-particle OU fluid velocity seen (variance u2 per component,
 * correlation time TL), exact OU update of length dt per engine step. */
typedef struct {
  size_t n;      /* particles */
  double *U;     /* 3 n, the velocities handed out at the next step */
  double b, q;   /* exp(-dt/TL), sd of the update noise */
  gsl_rng *r;    /* generator (owned by the caller) */
} v16_ou_field;

/* Stationary start; SB_EINVAL (bad argument) or SB_ENOMEM. */
int v16_ou_init(v16_ou_field *f, size_t n, double u2, double TL, double dt,
                gsl_rng *r);
void v16_ou_free(v16_ou_field *f);
/* sb_engine_fluid_fn: refuses n != f->n (SB_EINVAL). */
int v16_ou_fluid(size_t n, const double *x, double *us, void *ctx);
/* Stationary per-component velocity variance of a Stokes particle
 * (relaxation time tau) driven by that field held constant over steps of
 * dt with the exact step: -> u2 TL/(TL + tau) as dt -> 0 (relative
 * deviation O(dt/TL)).  Exact for the engine's scheme. */
double v16_ou_particle_var(double u2, double TL, double tau, double dt);
/* Its stationary covariance with the seen velocity handed out at the same
 * step, Cov(u_k, U_k) (-> the same limit). */
double v16_ou_particle_cov(double u2, double TL, double tau, double dt);

#define V16_KR_MAXM 3
#define V16_KR_MAXMODES 64

/* Kraichnan (1970) random Fourier modes on the lattice shell
 * M - 1/2 < |m| < M + 1/2 of the cube of edge L (periodic field). */
typedef struct {
  double L, dt, t, s2;
  int M;
  size_t nm, np;   /* modes; particles (time advances on a call with np) */
  int m[V16_KR_MAXMODES][3];
  double a[V16_KR_MAXMODES][3], b[V16_KR_MAXMODES][3], w[V16_KR_MAXMODES];
} v16_kr_field;

/* One realization with <A_ij A_ij> = eps_nu (1/s^2), frequencies
 * N(0, w0^2) (w0 = 0: frozen); time starts at 0 and advances by dt at
 * each callback with np positions.  M in 1..V16_KR_MAXM (M = 2: 31
 * modes, M = 3: 49). */
int v16_kr_init(v16_kr_field *f, double L, int M, double eps_nu, double w0,
                double dt, size_t np, gsl_rng *r);
void v16_kr_eval(const v16_kr_field *f, double t, size_t n, const double *x,
                 double *us);
int v16_kr_fluid(size_t n, const double *x, double *us, void *ctx);
/* Ensemble per-component velocity variance 2 N s2/3 (m^2/s^2) and
 * <(dU_x/dx)^2> = s2 sum |k|^2 khat_x^2 (1 - khat_x^2) (1/s^2). */
double v16_kr_u2(const v16_kr_field *f);
double v16_kr_a11(const v16_kr_field *f);
/* Exact collision rate of pass-through tracer pairs at contact distance
 * R in this field (the ensemble inward flux through the contact sphere,
 * velocities Gaussian over realizations): R^2/sqrt(2 pi) int sd(w.n)
 * dOmega, by product quadrature (64 Gauss-Legendre nodes in cos theta,
 * 128 in phi; the integrand is smooth for R k <= 2).  -> Saffman &
 * Turner (1956) as R k -> 0 for an isotropic field (0.99976 of it at
 * R k = 0.1 on the M = 2 shell: its cubic anisotropy). */
double v16_kr_flux_kernel(const v16_kr_field *f, double R);

#endif /* SB_VALIDATE_V16C_H */
