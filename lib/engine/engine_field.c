/* engine_field.c — random fluid velocity fields for the collision engine
 * (<smolbridge/engine_field.h>: the models, their parameters and
 * sources; docs/engine_forces.md §8): a per-particle Ornstein-Uhlenbeck
 * seen velocity and Kraichnan's (1970) random Fourier modes. */
#include <complex.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_randist.h>

#include <smolbridge/engine_field.h>
#include "common/internal.h"
#include "common/numutil.h"
#include "engine_field_state.h"

#define PI 3.14159265358979323846

/* ------------------------------------------------------------- OU */


void sbi_field_ou_set(sb_field_ou *f, size_t n, double u2, double TL,
                      double dt, const gsl_rng *r)
{
  f->n = n;
  f->u2 = u2;
  f->TL = TL;
  f->dt = dt;
  f->b = exp(-dt / TL);
  f->q = sqrt(u2 * -expm1(-2.0 * dt / TL));
  f->r = r;
}

sb_field_ou *sb_field_ou_alloc(size_t n, double u2, double TL, double dt,
                               const gsl_rng *r)
{
  if (!(u2 >= 0.0 && isfinite(u2) && TL > 0.0 && dt > 0.0) || n == 0 ||
      !r) {
    sbi_error(SB_EINVAL, __func__, "n = %zu, u2 = %g, T_L = %g, dt = %g "
              "(need n >= 1, u2 >= 0, T_L > 0, dt > 0, a generator)", n, u2,
              TL, dt);
    return NULL;
  }
  if (n > SIZE_MAX / (3 * sizeof(double))) {
    sbi_error(SB_EINVAL, __func__, "n = %zu: too many particles", n);
    return NULL;
  }
  sb_field_ou *f = calloc(1, sizeof *f);
  if (f)
    f->U = malloc(3 * n * sizeof *f->U);
  if (!f || !f->U) {
    free(f);
    sbi_error(SB_ENOMEM, __func__, "out of memory");
    return NULL;
  }
  sbi_field_ou_set(f, n, u2, TL, dt, r);
  const double sd = sqrt(u2);
  for (size_t i = 0; i < 3 * n; i++)
    f->U[i] = gsl_ran_gaussian_ziggurat(r, sd);
  return f;
}

void sb_field_ou_free(sb_field_ou *f)
{
  if (!f)
    return;
  free(f->U);
  free(f);
}

const double *sb_field_ou_seen(const sb_field_ou *f)
{
  if (!f) {
    sbi_error(SB_EINVAL, __func__, "field is NULL");
    return NULL;
  }
  return f->U;
}

int sb_field_ou_fluid(size_t n, const double *x, double *us, void *ctx)
{
  sb_field_ou *f = ctx;
  (void)x;
  if (!f || n != f->n)
    return sbi_error(SB_EINVAL, __func__, "called with %zu positions, the "
                     "field has %zu particles (it serves the engine's "
                     "per-step call only)", n, f ? f->n : 0);
  memcpy(us, f->U, 3 * n * sizeof *us);
  for (size_t i = 0; i < 3 * n; i++)
    f->U[i] = f->b * f->U[i] + gsl_ran_gaussian_ziggurat(f->r, f->q);
  return SB_SUCCESS;
}

int sb_field_ou_attach(sb_engine *e, sb_field_ou *f)
{
  if (!e || !f)
    return sbi_error(SB_EINVAL, __func__, "NULL engine or field");
  if (sb_engine_count(e) != f->n)
    return sbi_error(SB_EINVAL, __func__, "the engine holds %zu particles, "
                     "the field %zu", sb_engine_count(e), f->n);
  return sb_engine_set_fluid_fn(e, sb_field_ou_fluid, f);
}

double sb_field_ou_particle_var(double u2, double TL, double tau, double dt)
{
  const double a = exp(-dt / tau), b = exp(-dt / TL);
  const double oma = -expm1(-dt / tau), omab = -expm1(-dt / tau - dt / TL);
  const double c = b * oma * u2 / omab;
  return (2.0 * a * c + oma * u2) / (1.0 + a);
}

double sb_field_ou_particle_cov(double u2, double TL, double tau, double dt)
{
  const double b = exp(-dt / TL);
  return b * -expm1(-dt / tau) * u2 / -expm1(-dt / tau - dt / TL);
}

int sb_field_ou_start(const sb_field_ou *f, size_t i, double tau,
                      double mean[3], double *var)
{
  if (!f || i >= f->n || !(tau > 0.0) || !mean || !var)
    return sbi_error(SB_EINVAL, __func__, "particle %zu of %zu, tau = %g",
                     i, f ? f->n : 0, tau);
  if (!(f->u2 > 0.0) || isinf(tau)) {  /* free flight ignores the fluid */
    mean[0] = mean[1] = mean[2] = 0.0;
    *var = 0.0;
    return SB_SUCCESS;
  }
  const double v = sb_field_ou_particle_var(f->u2, f->TL, tau, f->dt);
  const double c = sb_field_ou_particle_cov(f->u2, f->TL, tau, f->dt);
  for (int k = 0; k < 3; k++)
    mean[k] = c / f->u2 * f->U[3 * i + k];
  *var = fmax(0.0, v - c * c / f->u2);
  return SB_SUCCESS;
}

/* -------------------------------------------------------- Kraichnan */

#define MAXM SB_FIELD_KRAICHNAN_MAXM
#define MAXMODES SB_FIELD_KRAICHNAN_MAXMODES


sb_field_kraichnan *sb_field_kraichnan_alloc(double L, int M, double eps_nu,
                                             double omega,
                                             const gsl_rng *r)
{
  if (!(L > 0.0 && isfinite(L) && eps_nu > 0.0 && isfinite(eps_nu) &&
        omega >= 0.0 && isfinite(omega)) || M < 1 || M > MAXM || !r) {
    sbi_error(SB_EINVAL, __func__, "L = %g, M = %d, eps/nu = %g, omega = %g "
              "(need L > 0, M in 1..%d, eps/nu > 0, omega >= 0, a "
              "generator)", L, M, eps_nu, omega, MAXM);
    return NULL;
  }
  sb_field_kraichnan *f = calloc(1, sizeof *f);
  if (!f) {
    sbi_error(SB_ENOMEM, __func__, "out of memory");
    return NULL;
  }
  f->L = L;
  f->M = M;
  f->eps_nu = eps_nu;
  f->omega = omega;
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
        f->m[f->nm][0] = i;  /* at most 49 modes for M <= 3 */
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
    f->w[n] = omega > 0.0 ? gsl_ran_gaussian_ziggurat(r, omega) : 0.0;
  }
  return f;
}

void sb_field_kraichnan_free(sb_field_kraichnan *f) { free(f); }

size_t sb_field_kraichnan_modes(const sb_field_kraichnan *f)
{
  if (!f) {
    sbi_error(SB_EINVAL, __func__, "field is NULL");
    return 0;
  }
  return f->nm;
}

void sb_field_kraichnan_eval(const sb_field_kraichnan *f, double t,
                             size_t n, const double *x, double *us)
{
  if (!f || (n && (!x || !us))) {
    sbi_error(SB_EINVAL, __func__, "NULL argument");
    return;
  }
  const int M = f->M;
  double complex rot[MAXMODES];
  for (size_t q = 0; q < f->nm; q++)
    rot[q] = f->w[q] != 0.0 ? cexp(I * f->w[q] * t) : 1.0;
  for (size_t i = 0; i < n; i++) {
    /* exp(i 2 pi m x_c / L) for m = -M..M, by powers */
    double complex pw[3][2 * MAXM + 1];
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

/* sb_engine_fluid_fn: the field at the engine's time. */
static int kraichnan_fluid(size_t n, const double *x, double *us, void *ctx)
{
  const sb_field_kraichnan *f = ctx;
  sb_field_kraichnan_eval(f, sb_engine_time(f->e), n, x, us);
  return SB_SUCCESS;
}

int sb_field_kraichnan_attach(sb_engine *e, sb_field_kraichnan *f)
{
  if (!e || !f)
    return sbi_error(SB_EINVAL, __func__, "NULL engine or field");
  const sb_engine_params *p = sb_engine_get_params(e);
  if (p->dim != 3)
    return sbi_error(SB_EINVAL, __func__, "the field is 3-D (dim = %d)",
                     p->dim);
  for (int k = 0; k < 3; k++)
    if (!(fabs(p->L[k] - f->L) <= 1e-12 * f->L))
      return sbi_error(SB_EINVAL, __func__, "box edge L[%d] = %g m: the "
                       "field is periodic in the cube of edge %g m", k,
                       p->L[k], f->L);
  f->e = e;
  return sb_engine_set_fluid_fn(e, kraichnan_fluid, f);
}

double sb_field_kraichnan_u2(const sb_field_kraichnan *f)
{
  if (!f) {
    sbi_error(SB_EINVAL, __func__, "field is NULL");
    return NAN;
  }
  return 2.0 * (double)f->nm * f->s2 / 3.0;
}

double sb_field_kraichnan_a11(const sb_field_kraichnan *f)
{
  if (!f) {
    sbi_error(SB_EINVAL, __func__, "field is NULL");
    return NAN;
  }
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
static double kr_var_wn(const sb_field_kraichnan *f, double R,
                        const double n3[3])
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

typedef struct {
  const sb_field_kraichnan *f;
  double R;
} kr_flux_ctx;

static double kr_sd_wn(const double n[3], void *ctx)
{
  const kr_flux_ctx *k = ctx;
  return sqrt(kr_var_wn(k->f, k->R, n));
}

double sb_field_kraichnan_flux_kernel(const sb_field_kraichnan *f, double R)
{
  if (!f) {
    sbi_error(SB_EINVAL, __func__, "field is NULL");
    return NAN;
  }
  /* K = R^2 int dOmega E[(w.n)^-] = R^2/sqrt(2 pi) int dOmega sd(n):
   * 64 Gauss-Legendre nodes in cos(theta), 128 trapezoid points in phi */
  kr_flux_ctx k = {f, R};
  return R * R * sbi_sphere_integral(kr_sd_wn, &k, 64, 128, 0.0) /
         sqrt(2.0 * PI);
}
