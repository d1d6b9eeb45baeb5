/* v16_field.c — random fluid velocity fields for the V16 kernel cases
 * (lib/validate/cases_v16c.c, docs/engine_forces.md §8), handed to the
 * engine through its fluid callback (sb_engine_set_fluid_fn).
 *
 * 1. Per-particle Ornstein-Uhlenbeck "fluid velocity seen": particle i
 *    sees U_i(t), independent between particles and components, a
 *    stationary OU process of variance u'^2 and correlation time T_L,
 *    advanced exactly over each step (Gardiner 2009, §3.8.4) and held
 *    constant during the step (the engine evaluates U_s at the start of
 *    the step).  No spatial structure: the model of a particle whose
 *    relaxation time is long against the time it takes to cross an eddy
 *    (the seen velocity decorrelates faster than the particle responds).
 *
 * 2. Kraichnan (1970, Phys. Fluids 13:22, eqs 2-4) random Fourier modes:
 *      U(x, t) = sum_n [a_n cos(k_n.x + w_n t) + b_n sin(k_n.x + w_n t)],
 *    a_n = zeta_n x khat_n, b_n = xi_n x khat_n with zeta, xi independent
 *    N(0, s2 I_3) vectors (divergence-free: a_n.k_n = b_n.k_n = 0),
 *    w_n = 0 (frozen) or N(0, w0^2) (Kraichnan's time-dependent field).
 *    Wave vectors: every lattice vector k = 2 pi m / L (m integer, one of
 *    each pair +-m) with M - 1/2 < |m| < M + 1/2, so the field is periodic
 *    in the cubic box of edge L.  At every point the velocity is Gaussian
 *    over realizations with per-component variance 2 N s2 / 3, and
 *    <A_ij A_ij> = 2 s2 sum |k_n|^2 (A = grad U), which is eps/nu; s2 is
 *    set from the prescribed eps/nu.
 */
#include <complex.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_integration.h>
#include <gsl/gsl_randist.h>

#include <smolbridge/common.h>

#include "v16c.h"

#define PI 3.14159265358979323846

/* ------------------------------------------------------------- OU */

int v16_ou_init(v16_ou_field *f, size_t n, double u2, double TL, double dt,
                gsl_rng *r)
{
  if (!(u2 >= 0.0 && TL > 0.0 && dt > 0.0) || n == 0)
    return SB_EINVAL;
  f->U = malloc(3 * n * sizeof *f->U);
  if (!f->U)
    return SB_ENOMEM;
  f->n = n;
  f->b = exp(-dt / TL);
  f->q = sqrt(u2 * -expm1(-2.0 * dt / TL));
  f->r = r;
  const double sd = sqrt(u2);
  for (size_t i = 0; i < 3 * n; i++)
    f->U[i] = gsl_ran_gaussian_ziggurat(r, sd);
  return SB_SUCCESS;
}

void v16_ou_free(v16_ou_field *f)
{
  free(f->U);
  f->U = NULL;
}

/* Hands out U_i at the start of the step, then advances it by dt.  The
 * engine calls it once per step with all particles in index order (no
 * reordering, count outcome); any other call is refused. */
int v16_ou_fluid(size_t n, const double *x, double *us, void *ctx)
{
  v16_ou_field *f = ctx;
  (void)x;
  if (n != f->n)
    return SB_EINVAL;
  memcpy(us, f->U, 3 * n * sizeof *us);
  for (size_t i = 0; i < 3 * n; i++)
    f->U[i] = f->b * f->U[i] + gsl_ran_gaussian_ziggurat(f->r, f->q);
  return SB_SUCCESS;
}

double v16_ou_particle_var(double u2, double TL, double tau, double dt)
{
  /* u_{k+1} = a u_k + (1 - a) U_k, U_{k+1} = b U_k + noise:
   * c = Cov(u, U) = b (1 - a) u2/(1 - a b),
   * v = Var u = (2 a c + (1 - a) u2)/(1 + a). */
  const double a = exp(-dt / tau), b = exp(-dt / TL);
  const double oma = -expm1(-dt / tau), omab = -expm1(-dt / tau - dt / TL);
  const double c = b * oma * u2 / omab;
  return (2.0 * a * c + oma * u2) / (1.0 + a);
}

double v16_ou_particle_cov(double u2, double TL, double tau, double dt)
{
  const double b = exp(-dt / TL);
  return b * -expm1(-dt / tau) * u2 / -expm1(-dt / tau - dt / TL);
}

/* -------------------------------------------------------- Kraichnan */

int v16_kr_init(v16_kr_field *f, double L, int M, double eps_nu, double w0,
                double dt, size_t np, gsl_rng *r)
{
  if (!(L > 0.0 && eps_nu > 0.0 && w0 >= 0.0 && dt > 0.0) || M < 1 ||
      M > V16_KR_MAXM)
    return SB_EINVAL;
  memset(f, 0, sizeof *f);
  f->L = L;
  f->M = M;
  f->dt = dt;
  f->np = np;
  const double lo = (M - 0.5) * (M - 0.5), hi = (M + 0.5) * (M + 0.5);
  double sk2 = 0.0;
  for (int i = -M; i <= M; i++)
    for (int j = -M; j <= M; j++)
      for (int k = -M; k <= M; k++) {
        const double m2 = (double)(i * i + j * j + k * k);
        if (m2 <= lo || m2 >= hi)
          continue;
        /* one of +-m: first non-zero component positive */
        if (i < 0 || (i == 0 && (j < 0 || (j == 0 && k < 0))))
          continue;
        if (f->nm >= V16_KR_MAXMODES)
          return SB_EINVAL;
        f->m[f->nm][0] = i;
        f->m[f->nm][1] = j;
        f->m[f->nm][2] = k;
        sk2 += m2;
        f->nm++;
      }
  const double kk = 2.0 * PI / L;
  f->s2 = eps_nu / (2.0 * sk2 * kk * kk);
  const double s = sqrt(f->s2);
  for (size_t n = 0; n < f->nm; n++) {
    double kh[3], nrm = 0.0;
    for (int c = 0; c < 3; c++)
      nrm += (double)(f->m[n][c] * f->m[n][c]);
    for (int c = 0; c < 3; c++)
      kh[c] = f->m[n][c] / sqrt(nrm);
    double z[3], xi[3];
    for (int c = 0; c < 3; c++) {
      z[c] = gsl_ran_gaussian_ziggurat(r, s);
      xi[c] = gsl_ran_gaussian_ziggurat(r, s);
    }
    f->a[n][0] = z[1] * kh[2] - z[2] * kh[1];
    f->a[n][1] = z[2] * kh[0] - z[0] * kh[2];
    f->a[n][2] = z[0] * kh[1] - z[1] * kh[0];
    f->b[n][0] = xi[1] * kh[2] - xi[2] * kh[1];
    f->b[n][1] = xi[2] * kh[0] - xi[0] * kh[2];
    f->b[n][2] = xi[0] * kh[1] - xi[1] * kh[0];
    f->w[n] = w0 > 0.0 ? gsl_ran_gaussian_ziggurat(r, w0) : 0.0;
  }
  return SB_SUCCESS;
}

void v16_kr_eval(const v16_kr_field *f, double t, size_t n, const double *x,
                 double *us)
{
  const int M = f->M;
  double complex rot[V16_KR_MAXMODES];
  for (size_t q = 0; q < f->nm; q++)
    rot[q] = f->w[q] != 0.0 ? cexp(I * f->w[q] * t) : 1.0;
  for (size_t i = 0; i < n; i++) {
    /* exp(i 2 pi m x_c / L) for m = -M..M, by powers */
    double complex pw[3][2 * V16_KR_MAXM + 1];
    for (int c = 0; c < 3; c++) {
      const double th = 2.0 * PI * x[3 * i + c] / f->L;
      const double complex e1 = cos(th) + I * sin(th);
      pw[c][M] = 1.0;
      for (int m = 1; m <= M; m++) {
        pw[c][M + m] = pw[c][M + m - 1] * e1;
        pw[c][M - m] = conj(pw[c][M + m]);
      }
    }
    double u[3] = {0.0, 0.0, 0.0};
    for (size_t q = 0; q < f->nm; q++) {
      const double complex ph = pw[0][M + f->m[q][0]] *
                                pw[1][M + f->m[q][1]] *
                                pw[2][M + f->m[q][2]] * rot[q];
      const double co = creal(ph), si = cimag(ph);
      for (int c = 0; c < 3; c++)
        u[c] += f->a[q][c] * co + f->b[q][c] * si;
    }
    memcpy(&us[3 * i], u, sizeof u);
  }
}

int v16_kr_fluid(size_t n, const double *x, double *us, void *ctx)
{
  v16_kr_field *f = ctx;
  v16_kr_eval(f, f->t, n, x, us);
  if (n == f->np)  /* the per-step call for all particles */
    f->t += f->dt;
  return SB_SUCCESS;
}

double v16_kr_u2(const v16_kr_field *f)
{
  return 2.0 * (double)f->nm * f->s2 / 3.0;
}

double v16_kr_a11(const v16_kr_field *f)
{
  const double kk = 2.0 * PI / f->L;
  double s = 0.0;
  for (size_t q = 0; q < f->nm; q++) {
    double m2 = 0.0;
    for (int c = 0; c < 3; c++)
      m2 += (double)(f->m[q][c] * f->m[q][c]);
    const double c1 = f->m[q][0] * f->m[q][0] / m2;
    s += m2 * kk * kk * c1 * (1.0 - c1);
  }
  return f->s2 * s;
}

/* Var(w.n) at separation R n over realizations (any point, any time):
 * sum_q s2 (1 - (khat.n)^2) 2 (1 - cos(R k.n)). */
static double kr_var_wn(const v16_kr_field *f, double R, const double n3[3])
{
  const double kk = 2.0 * PI / f->L;
  double v = 0.0;
  for (size_t q = 0; q < f->nm; q++) {
    double kn = 0.0, m2 = 0.0;
    for (int c = 0; c < 3; c++) {
      kn += f->m[q][c] * n3[c];
      m2 += (double)(f->m[q][c] * f->m[q][c]);
    }
    const double ch2 = kn * kn / m2;
    const double x = R * kk * kn;
    /* 1 - cos x = 2 sin^2(x/2) */
    const double omc = 2.0 * sin(0.5 * x) * sin(0.5 * x);
    v += f->s2 * (1.0 - ch2) * 2.0 * omc;
  }
  return v;
}

double v16_kr_flux_kernel(const v16_kr_field *f, double R)
{
  /* K = R^2 int dOmega E[(w.n)^-] = R^2/sqrt(2 pi) int dOmega sd(n):
   * Gauss-Legendre (64) in cos(theta), 128-point trapezoid in phi
   * (periodic: spectral) */
  gsl_integration_glfixed_table *tb = gsl_integration_glfixed_table_alloc(64);
  if (!tb)
    return NAN;
  double sum = 0.0;
  const int nphi = 128;
  for (size_t i = 0; i < 64; i++) {
    double mu, wmu;
    gsl_integration_glfixed_point(-1.0, 1.0, i, &mu, &wmu, tb);
    const double st = sqrt(1.0 - mu * mu);
    double sp = 0.0;
    for (int j = 0; j < nphi; j++) {
      const double ph = 2.0 * PI * j / nphi;
      const double n3[3] = {st * cos(ph), st * sin(ph), mu};
      sp += sqrt(kr_var_wn(f, R, n3));
    }
    sum += wmu * sp * 2.0 * PI / nphi;
  }
  gsl_integration_glfixed_table_free(tb);
  return R * R * sum / sqrt(2.0 * PI);
}
