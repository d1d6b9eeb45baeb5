/* pbe.c — Smoluchowski population balance: solver object, discrete
 * right-hand side and analytic Jacobian, CVODE driver, moments.
 *
 * CVODE (SUNDIALS 6.x and 7.x): BDF with Newton iteration.  Linear solver
 * (default): GMRES right-preconditioned by the diagonal of I - gamma J with
 * an M1-conserving rank-one correction; dense LU with the analytic
 * Jacobian and plain GMRES on request (docs/pbe.md has the measurements).
 * All keep the linear invariant
 * M1 exactly: v^T f(y) = 0 for pure coagulation gives v^T J = 0, so the
 * Newton residual, every Krylov vector and the dense correction all have
 * zero M1 and the corrected iterate has the predictor's M1.  M1 drifts only
 * by rounding and by collisions leaving the grid.
 */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_config.h>
#include <sundials/sundials_types.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunlinsol/sunlinsol_spgmr.h>
#include <sunmatrix/sunmatrix_dense.h>

#include "common/internal.h"
#include "pbe_internal.h"

/* Kernel matrices above this many entries are not stored (the kernel is
 * then evaluated on the fly: slower, but K = 10^4 sizes fit in memory). */
#define KMAT_MAX ((size_t)1 << 24)

static const sb_kernel_spec default_kernel = {SB_KERNEL_CONSTANT, 1.0,
                                              293.15, 1.002e-3, 1000.0,
                                              998.2, 0.0, 9.80665, 1.0,
                                              1e-4, 1.004e-6, 1.0, 1e-12};

void sb_pbe_config_init(sb_pbe_config *cfg)
{
  if (!cfg)
    return;
  memset(cfg, 0, sizeof *cfg);
  cfg->method = SB_PBE_DISCRETE;
  cfg->nsizes = 100;
  cfg->v1 = 1.0;
  cfg->ratio = 2.0;
  cfg->kernel = sb_kernel_spec_fn;
  cfg->kparams = &default_kernel;
  cfg->rtol = 1e-8;
  cfg->atol = 0.0;
  cfg->linsol = SB_PBE_LS_AUTO;
  cfg->max_steps = 100000;
  cfg->tail = 1;
}

void sb_pbe_free(sb_pbe *p)
{
  if (!p)
    return;
  free(p->v);
  free(p->kmat);
  free(p->y0);
  free(p->y);
  free(p->work);
  free(p->src);
  free(p->gbuf);
  free(p->diags);
  free(p->kdiag);
  sbi_pbe_fft_free(p);
  free(p->fa);
  free(p->fb);
  free(p->ktail);
  free(p->dktail);
  free(p->pdiag);
  free(p->jtmp);
  free(p);
}

static double kval(const sb_pbe *p, size_t i, size_t j)
{
  if (p->kmat)
    return p->kmat[i * p->n + j];
  return p->cfg.kernel(p->v[i], p->v[j], p->cfg.kparams);
}

sb_pbe *sb_pbe_alloc(const sb_pbe_config *cfg)
{
  if (!cfg) {
    sbi_error(SB_EINVAL, __func__, "cfg is NULL");
    return NULL;
  }
  if (cfg->method != SB_PBE_DISCRETE && cfg->method != SB_PBE_SECTIONAL) {
    sbi_error(SB_EINVAL, __func__, "unknown method %d", (int)cfg->method);
    return NULL;
  }
  if (cfg->nsizes < 2 || cfg->nsizes > 1000000) {
    sbi_error(SB_EINVAL, __func__, "nsizes = %zu outside [2, 1e6]",
              cfg->nsizes);
    return NULL;
  }
  if (!(cfg->v1 > 0 && isfinite(cfg->v1))) {
    sbi_error(SB_EDOM, __func__, "v1 must be finite and > 0 (got %g)",
              cfg->v1);
    return NULL;
  }
  if (cfg->method == SB_PBE_DISCRETE &&
      !isfinite((double)cfg->nsizes * cfg->v1)) {
    sbi_error(SB_EDOM, __func__, "the largest size %zu v1 = %zu x %g "
              "overflows", cfg->nsizes, cfg->nsizes, cfg->v1);
    return NULL;
  }
  if (cfg->method == SB_PBE_SECTIONAL &&
      !(cfg->ratio > 1.0 && isfinite(cfg->ratio) &&
        isfinite(cfg->v1 * pow(cfg->ratio, (double)cfg->nsizes)))) {
    sbi_error(SB_EDOM, __func__,
              "ratio must be > 1 with a finite last pivot (got %g)",
              cfg->ratio);
    return NULL;
  }
  if (!cfg->kernel) {
    sbi_error(SB_EINVAL, __func__, "no kernel");
    return NULL;
  }
  if (!(cfg->rtol > 0 && cfg->rtol < 1) || !(cfg->atol >= 0) ||
      !isfinite(cfg->atol)) {
    sbi_error(SB_EINVAL, __func__, "need 0 < rtol < 1, finite atol >= 0 "
              "(got %g, %g)", cfg->rtol, cfg->atol);
    return NULL;
  }
  if (cfg->linsol != SB_PBE_LS_DENSE && cfg->linsol != SB_PBE_LS_GMRES &&
      cfg->linsol != SB_PBE_LS_GMRES_DIAG && cfg->linsol != SB_PBE_LS_AUTO) {
    sbi_error(SB_EINVAL, __func__, "unknown linear solver %d",
              (int)cfg->linsol);
    return NULL;
  }
  if (cfg->gain != SB_PBE_GAIN_AUTO && cfg->gain != SB_PBE_GAIN_DIRECT &&
      cfg->gain != SB_PBE_GAIN_FFT) {
    sbi_error(SB_EINVAL, __func__, "unknown gain evaluation %d",
              (int)cfg->gain);
    return NULL;
  }
  if (cfg->linsol == SB_PBE_LS_DENSE && cfg->nsizes > 20000) {
    sbi_error(SB_EINVAL, __func__, "dense Jacobian with %zu sizes: use GMRES",
              cfg->nsizes);
    return NULL;
  }
  sb_pbe *p = calloc(1, sizeof *p);
  if (!p) {
    sbi_error(SB_ENOMEM, __func__, "out of memory");
    return NULL;
  }
  p->cfg = *cfg;
  if (p->cfg.max_steps <= 0)
    p->cfg.max_steps = 100000;
  size_t n = p->n = cfg->nsizes;
  p->tail = cfg->method == SB_PBE_DISCRETE && cfg->tail;
  p->ny = n + (p->tail ? 2 : 0);
  p->v = malloc(n * sizeof *p->v);
  p->y0 = calloc(p->ny, sizeof *p->y0);
  p->y = calloc(p->ny, sizeof *p->y);
  p->work = malloc(n * sizeof *p->work);
  p->src = calloc(n, sizeof *p->src);
  p->ktail = calloc(n, sizeof *p->ktail);
  p->dktail = calloc(n, sizeof *p->dktail);
  p->gbuf = calloc(2 * n, sizeof *p->gbuf);
  p->pdiag = calloc(p->ny, sizeof *p->pdiag);
  p->jtmp = calloc(p->ny, sizeof *p->jtmp);
  if (!p->jtmp || !p->v || !p->y0 || !p->y || !p->work || !p->src || !p->ktail ||
      !p->dktail || !p->gbuf || !p->pdiag)
    goto nomem;
  sbi_pbe_sep_detect(p);
  /* AUTO: FFT only where measured harmless (constant kernel, GMRES): for
   * the additive and multiplicative kernels its rounding noise costs
   * GMRES 5-20x more steps at K >= 1000 (docs/pbe.md) */
  p->use_fft = p->sep && (cfg->gain == SB_PBE_GAIN_FFT ||
                          (cfg->gain == SB_PBE_GAIN_AUTO && n >= 4096 &&
                           p->sep - 1 == SB_PBE_CONSTANT));
  p->fft_auto = p->use_fft && cfg->gain == SB_PBE_GAIN_AUTO;
  if (sbi_pbe_sep_setup(p))
    goto nomem;
  for (size_t i = 0; i < n; i++)
    p->v[i] = cfg->method == SB_PBE_DISCRETE
                  ? (double)(i + 1) * cfg->v1
                  : cfg->v1 * pow(cfg->ratio, (double)i);
  /* Tabulate and check the kernel (symmetric, finite, >= 0).  Separable
   * kernels need no table except for the dense Jacobian. */
  int dense = cfg->linsol == SB_PBE_LS_DENSE;
  if (n * n <= KMAT_MAX && (!p->sep || dense)) {
    p->kmat = malloc(n * n * sizeof *p->kmat);
    if (!p->kmat)
      goto nomem;
  }
  for (size_t i = 0; i < n; i++)
    for (size_t j = i; j < n; j++) {
      double k = cfg->kernel(p->v[i], p->v[j], cfg->kparams);
      if (!(k >= 0 && isfinite(k))) {
        sbi_error(SB_EDOM, __func__, "kernel(%g, %g) = %g: must be finite "
                  "and >= 0", p->v[i], p->v[j], k);
        sb_pbe_free(p);
        return NULL;
      }
      if (p->kmat)
        p->kmat[i * n + j] = p->kmat[j * n + i] = k;
      else if (j > i + 64) /* spot checks only when not tabulated */
        break;
    }
  if (cfg->method == SB_PBE_SECTIONAL) {
    int st = sbi_pbe_sect_setup(p);
    if (st) {
      sb_pbe_free(p);
      sbi_error(st, __func__, "sectional setup failed");
      return NULL;
    }
  }
  return p;
nomem:
  sb_pbe_free(p);
  sbi_error(SB_ENOMEM, __func__, "out of memory (%zu bins)", n);
  return NULL;
}

size_t sb_pbe_nbins(const sb_pbe *p) { return p ? p->n : 0; }
const double *sb_pbe_volumes(const sb_pbe *p) { return p ? p->v : NULL; }
const double *sb_pbe_state(const sb_pbe *p) { return p ? p->y : NULL; }

void sb_pbe_tail(const sb_pbe *p, double *number, double *mass)
{
  double a = 0.0, b = 0.0;
  if (p && p->tail) {
    a = p->y[p->n];
    b = p->y[p->n + 1];
  }
  if (number)
    *number = a;
  if (mass)
    *mass = b;
}

/* Moments of a full ODE vector y (grid plus tail). */
static void moments_y(const sb_pbe *p, const double *y, double m[3])
{
  sb_pbe_moments(p->v, y, p->n, m);
  if (p->tail) {
    double nt = y[p->n], mt = y[p->n + 1];
    m[0] += nt;
    m[1] += mt;
    if (nt > 0)
      m[2] += mt * (mt / nt);
  }
}

void sb_pbe_state_moments(const sb_pbe *p, double m[3])
{
  if (p && m)
    moments_y(p, p->y, m);
}

int sb_pbe_set_initial(sb_pbe *p, const double *n)
{
  if (!p || !n)
    return sbi_error(SB_EINVAL, __func__, "NULL argument");
  for (size_t i = 0; i < p->n; i++)
    if (!(n[i] >= 0 && isfinite(n[i])))
      return sbi_error(SB_EDOM, __func__, "n[%zu] = %g: must be finite and "
                       ">= 0", i, n[i]);
  memset(p->y0, 0, p->ny * sizeof *p->y0);
  memcpy(p->y0, n, p->n * sizeof *n);
  memcpy(p->y, p->y0, p->ny * sizeof *p->y);
  p->have_init = 1;
  return SB_SUCCESS;
}

int sb_pbe_init_mono(sb_pbe *p, double n0)
{
  if (!p)
    return sbi_error(SB_EINVAL, __func__, "p is NULL");
  if (!(n0 > 0 && isfinite(n0)))
    return sbi_error(SB_EDOM, __func__, "n0 must be finite and > 0 (got %g)",
                     n0);
  memset(p->y0, 0, p->ny * sizeof *p->y0);
  p->y0[0] = n0;
  memcpy(p->y, p->y0, p->ny * sizeof *p->y);
  p->have_init = 1;
  return SB_SUCCESS;
}

int sb_pbe_init_exp(sb_pbe *p, double n0, double v0)
{
  if (!p)
    return sbi_error(SB_EINVAL, __func__, "p is NULL");
  if (!(n0 > 0 && isfinite(n0)) || !(v0 > 0 && isfinite(v0)))
    return sbi_error(SB_EDOM, __func__, "n0, v0 must be finite and > 0 "
                     "(got %g, %g)", n0, v0);
  if (p->cfg.method == SB_PBE_SECTIONAL) {
    int st = sbi_pbe_sect_init_exp(p, n0, v0);
    if (st)
      return st;
  } else {
    if (!(v0 > p->cfg.v1))
      return sbi_error(SB_EDOM, __func__, "discrete exponential start needs "
                       "v0 > v1 (got %g, %g)", v0, p->cfg.v1);
    /* geometric: n_k = N0 (1-q) q^(k-1), mean size v1/(1-q) = v0 */
    double lq = log1p(-p->cfg.v1 / v0);
    for (size_t k = 0; k < p->n; k++)
      p->y0[k] = n0 * (p->cfg.v1 / v0) * exp((double)k * lq);
    if (p->tail) { /* sizes above K: number q^K N0, mass N0 q^K (K v1 + v0) */
      double qK = exp((double)p->n * lq);
      p->y0[p->n] = n0 * qK;
      p->y0[p->n + 1] = n0 * qK * ((double)p->n * p->cfg.v1 + v0);
    }
  }
  for (size_t i = 0; i < p->ny; i++)
    if (!isfinite(p->y0[i])) {
      /* n0 v0 (the mass concentration) beyond DBL_MAX: the initial state
       * is cleared rather than left half-written */
      memset(p->y0, 0, p->ny * sizeof *p->y0);
      p->have_init = 0;
      return sbi_error(SB_ERANGE, __func__, "n0 = %g, v0 = %g: the initial "
                       "state overflows (scale n by 1/N0 and the kernel by "
                       "N0)", n0, v0);
    }
  memcpy(p->y, p->y0, p->ny * sizeof *p->y);
  p->have_init = 1;
  return SB_SUCCESS;
}

/* ------------------------------------------------------------ RHS */

/* Loss rates L_i = sum_j K_ij n_j into p->work.  Four accumulators: one
 * dependency chain would be latency-bound (measured 2-3x slower). */
static void loss_rates(const sb_pbe *p, const double *n)
{
  size_t N = p->n;
  for (size_t i = 0; i < N; i++) {
    double s0 = 0.0, s1 = 0.0, s2 = 0.0, s3 = 0.0;
    size_t j = 0;
    if (p->kmat) {
      const double *row = p->kmat + i * N;
      for (; j + 4 <= N; j += 4) {
        s0 += row[j] * n[j];
        s1 += row[j + 1] * n[j + 1];
        s2 += row[j + 2] * n[j + 2];
        s3 += row[j + 3] * n[j + 3];
      }
      for (; j < N; j++)
        s0 += row[j] * n[j];
    } else {
      for (; j < N; j++)
        s0 += kval(p, i, j) * n[j];
    }
    p->work[i] = (s0 + s1) + (s2 + s3);
  }
}

/* Discrete gain by total index s = i0 + j0 (size s + 2), s = 0..2N-2:
 * g[s] = sum_{i0<j0} K n_i0 n_j0 + K_ii n_i^2/2 [s = 2 i0], and the loss
 * rates, in one pass over the upper triangle of the kernel matrix, row by
 * row (contiguous inner loops; the symmetric half of the loss is added as
 * L_j += K_ij n_i).  Without a stored matrix the kernel is called per
 * pair. */
static void discrete_gain_loss(sb_pbe *p, const double *restrict n,
                               double *restrict g)
{
  size_t N = p->n;
  double *restrict L = p->work;
  memset(g, 0, (2 * N - 1) * sizeof *g);
  memset(L, 0, N * sizeof *L);
  for (size_t i = 0; i < N; i++) {
    double ni = n[i], *restrict gi = g + i;
    double a0, a1 = 0.0, a2 = 0.0, a3 = 0.0;
    size_t j = i + 1;
    if (p->kmat) {
      const double *restrict row = p->kmat + i * N;
      a0 = row[i] * ni;
      gi[i] += 0.5 * a0 * ni;
      for (; j + 4 <= N; j += 4) {
        double t0 = row[j] * n[j], t1 = row[j + 1] * n[j + 1];
        double t2 = row[j + 2] * n[j + 2], t3 = row[j + 3] * n[j + 3];
        a0 += t0;
        a1 += t1;
        a2 += t2;
        a3 += t3;
        L[j] += row[j] * ni;
        L[j + 1] += row[j + 1] * ni;
        L[j + 2] += row[j + 2] * ni;
        L[j + 3] += row[j + 3] * ni;
        gi[j] += ni * t0;
        gi[j + 1] += ni * t1;
        gi[j + 2] += ni * t2;
        gi[j + 3] += ni * t3;
      }
      for (; j < N; j++) {
        double t = row[j] * n[j];
        a0 += t;
        L[j] += row[j] * ni;
        gi[j] += ni * t;
      }
    } else {
      double k = kval(p, i, i);
      a0 = k * ni;
      gi[i] += 0.5 * a0 * ni;
      for (; j < N; j++) {
        k = kval(p, i, j);
        double t = k * n[j];
        a0 += t;
        L[j] += k * ni;
        gi[j] += ni * t;
      }
    }
    L[i] += (a0 + a1) + (a2 + a3);
  }
}

/* Mean volume of the tail (clamped to the smallest size it can hold) and
 * the kernel against it: ktail[a] = K(v_a, vbar) and, if `deriv`,
 * dktail[a] = dK/dvbar by central differences (Jacobian only). */
static double tail_kernel(sb_pbe *p, const double *y, int deriv)
{
  size_t N = p->n;
  double vmin = (double)(N + 1) * p->cfg.v1, nt = y[N], mt = y[N + 1];
  double vbar = (nt > 0 && mt > 0) ? fmax(mt / nt, vmin) : vmin;
  double h = 1e-6 * vbar;
  for (size_t a = 0; a < N; a++) {
    p->ktail[a] = p->cfg.kernel(p->v[a], vbar, p->cfg.kparams);
    if (deriv)
      p->dktail[a] = (p->cfg.kernel(p->v[a], vbar + h, p->cfg.kparams) -
                      p->cfg.kernel(p->v[a], vbar - h, p->cfg.kparams)) /
                     (2 * h);
  }
  return vbar;
}

/* Tail equations: number and mass of the particles larger than K.  The
 * grid pairs of total size > K are g[s], s >= N - 1 (size s + 2). */
static void tail_rhs(sb_pbe *p, double t, const double *y, const double *g,
                     double *ydot)
{
  size_t N = p->n;
  double nt = y[N], mt = y[N + 1];
  double vbar = tail_kernel(p, y, 0);
  double dn = 0.0, dm = 0.0;
  if (p->sep) {
    /* exact bilinear forms in (nt, mt), no clamped vbar: f stays a
     * quadratic polynomial in y (used by the FFT path's jtimes) */
    double K = p->sepK;
    for (size_t a = 0; a < N; a++)
      p->ktail[a] = p->sep - 1 == SB_PBE_CONSTANT   ? K * nt
                    : p->sep - 1 == SB_PBE_ADDITIVE ? K * (p->v[a] * nt + mt)
                                                    : K * p->v[a] * mt;
    dn -= p->sep - 1 == SB_PBE_CONSTANT   ? 0.5 * K * nt * nt
          : p->sep - 1 == SB_PBE_ADDITIVE ? K * nt * mt
                                          : 0.5 * K * mt * mt;
  }
  if (p->use_fft) {
    dn += p->of_dn;
    dm += p->of_dm;
  } else {
    for (size_t s = N - 1; s + 1 < 2 * N; s++) {
      dn += g[s];
      dm += g[s] * ((double)(s + 2) * p->cfg.v1);
    }
  }
  /* grid particles absorbed by the tail, and their loss */
  for (size_t a = 0; a < N; a++) {
    double r = p->ktail[a] * y[a] * (p->sep ? 1.0 : nt);
    dm += p->v[a] * r;
    ydot[a] -= r;
  }
  /* tail-tail collisions: one tail particle less, mass unchanged */
  if (!p->sep)
    dn -= 0.5 * p->cfg.kernel(vbar, vbar, p->cfg.kparams) * nt * nt;
  if (p->cfg.removal) {
    double rr = p->cfg.removal(t, vbar, p->cfg.rparams);
    dn -= rr * nt;
    dm -= rr * mt;
  }
  ydot[N] = dn;
  ydot[N + 1] = dm;
}

static void full_rhs(sb_pbe *p, double t, const double *n, double *dndt)
{
  size_t N = p->n;
  if (p->cfg.method == SB_PBE_DISCRETE) {
    double *g = p->gbuf;
    if (p->sep)
      sbi_pbe_sep_gain_loss(p, n, g);
    else
      discrete_gain_loss(p, n, g);
    dndt[0] = 0.0;
    for (size_t a = 1; a < N; a++)
      dndt[a] = g[a - 1];
  } else {
    sbi_pbe_sect_gain(p, n, dndt);
    loss_rates(p, n);
  }
  for (size_t i = 0; i < N; i++)
    dndt[i] -= n[i] * p->work[i];
  if (p->cfg.source) {
    memset(p->src, 0, N * sizeof *p->src);
    p->cfg.source(t, p->v, p->src, N, p->cfg.sparams);
    for (size_t i = 0; i < N; i++)
      dndt[i] += p->src[i];
  }
  if (p->cfg.removal)
    for (size_t i = 0; i < N; i++)
      dndt[i] -= p->cfg.removal(t, p->v[i], p->cfg.rparams) * n[i];
  if (p->tail)
    tail_rhs(p, t, n, p->gbuf, dndt);
}

/* dn/dt finite, else SB_ERANGE (K n^2 beyond DBL_MAX) */
static int rhs_check(const char *fn, const double *dndt, size_t n)
{
  for (size_t i = 0; i < n; i++)
    if (!isfinite(dndt[i]))
      return sbi_error(SB_ERANGE, fn, "dn/dt[%zu] = %g: the rates overflow",
                       i, dndt[i]);
  return SB_SUCCESS;
}

int sb_pbe_rhs(sb_pbe *p, double t, const double *n, double *dndt)
{
  if (!p || !n || !dndt)
    return sbi_error(SB_EINVAL, __func__, "NULL argument");
  if (!isfinite(t))
    return sbi_error(SB_EDOM, __func__, "t = %g must be finite", t);
  for (size_t i = 0; i < p->n; i++)
    if (!isfinite(n[i]))
      return sbi_error(SB_EDOM, __func__, "n[%zu] = %g must be finite", i,
                       n[i]);
  if (!p->tail) {
    full_rhs(p, t, n, dndt);
    return rhs_check(__func__, dndt, p->n);
  }
  /* grid only: evaluate with an empty tail */
  double *y = malloc(p->ny * sizeof *y), *yd = malloc(p->ny * sizeof *yd);
  if (!y || !yd) {
    free(y);
    free(yd);
    return sbi_error(SB_ENOMEM, __func__, "out of memory");
  }
  memcpy(y, n, p->n * sizeof *n);
  y[p->n] = y[p->n + 1] = 0.0;
  full_rhs(p, t, y, yd);
  memcpy(dndt, yd, p->n * sizeof *dndt);
  free(y);
  free(yd);
  return rhs_check(__func__, dndt, p->n);
}

static int cv_rhs(sunrealtype t, N_Vector y, N_Vector ydot, void *data)
{
  full_rhs(data, t, N_VGetArrayPointer(y), N_VGetArrayPointer(ydot));
  return 0;
}

/* Tail rows and columns of the Jacobian (column-major, leading dim ld).
 * Columns N (tail number) and N+1 (tail mass) follow from vbar = M/N:
 * d(K(v_a,vbar) N)/dN = K - K' vbar and d/dM = K', with K' = dK/dvbar.
 * The M1 weights (v_a on the grid, 1 on the tail mass) annihilate every
 * column, so the Newton iteration conserves M1 exactly. */
static void tail_jac(sb_pbe *p, double t, const double *y, double *J,
                     size_t ld)
{
  size_t N = p->n;
  double nt = y[N], mt = y[N + 1];
  double vbar = tail_kernel(p, y, 1);
  double *cN = J + N * ld, *cM = J + (N + 1) * ld;
  double sN = 0.0, sM = 0.0;
  for (size_t m = 0; m < N; m++) {
    double *col = J + m * ld;
    /* grid particle m absorbed by the tail */
    col[m] -= p->ktail[m] * nt;
    /* overflow pairs (m, j0) with m + j0 >= N - 1 */
    double a = 0.0, b = 0.0;
    for (size_t j0 = (m >= N - 1 ? 0 : N - 1 - m); j0 < N; j0++) {
      double r = kval(p, m, j0) * y[j0];
      a += r;
      b += r * (p->v[m] + p->v[j0]);
    }
    col[N] += a;
    col[N + 1] += b + p->v[m] * p->ktail[m] * nt;
    double dN = p->ktail[m] - p->dktail[m] * vbar, dM = p->dktail[m];
    cN[m] -= y[m] * dN;
    cM[m] -= y[m] * dM;
    sN += p->v[m] * y[m] * dN;
    sM += p->v[m] * y[m] * dM;
  }
  cN[N + 1] += sN;
  cM[N + 1] += sM;
  /* tail-tail: h = G(vbar) N^2/2, dh/dN = G N - G' M/2, dh/dM = G' N/2 */
  double hv = 1e-6 * vbar;
  double G = p->cfg.kernel(vbar, vbar, p->cfg.kparams);
  double Gp = (p->cfg.kernel(vbar + hv, vbar + hv, p->cfg.kparams) -
               p->cfg.kernel(vbar - hv, vbar - hv, p->cfg.kparams)) /
              (2 * hv);
  cN[N] -= G * nt - 0.5 * Gp * mt;
  cM[N] -= 0.5 * Gp * nt;
  if (p->cfg.removal) {
    double rr = p->cfg.removal(t, vbar, p->cfg.rparams);
    cN[N] -= rr;
    cM[N + 1] -= rr;
  }
}

/* Dense Jacobian, column-major J[col * ny + row]. */
static int cv_jac(sunrealtype t, N_Vector y, N_Vector fy, SUNMatrix Jm,
                  void *data, N_Vector t1, N_Vector t2, N_Vector t3)
{
  (void)fy;
  (void)t1;
  (void)t2;
  (void)t3;
  sb_pbe *p = data;
  size_t N = p->n, ld = p->ny;
  const double *n = N_VGetArrayPointer(y);
  double *J = SUNDenseMatrix_Data(Jm);
  SUNMatZero(Jm);
  loss_rates(p, n);
  /* loss: d(-n_a L_a)/dn_m = -delta_am L_a - n_a K_am */
  for (size_t m = 0; m < N; m++) {
    double *col = J + m * ld;
    for (size_t a = 0; a < N; a++)
      col[a] = -n[a] * kval(p, a, m);
    col[m] -= p->work[m];
  }
  if (p->cfg.method == SB_PBE_DISCRETE) {
    /* gain_a = sum_{i0 + j0 = a-1} K n_i0 n_j0 / 2: d/dn_m = K_{m,a-1-m}
     * n_{a-1-m} for m <= a - 1 */
    for (size_t a = 1; a < N; a++)
      for (size_t m = 0; m <= a - 1; m++)
        J[m * ld + a] += kval(p, m, a - 1 - m) * n[a - 1 - m];
  } else {
    sbi_pbe_sect_gain_jac(p, n, J, ld);
  }
  if (p->cfg.removal)
    for (size_t a = 0; a < N; a++)
      J[a * ld + a] -= p->cfg.removal(t, p->v[a], p->cfg.rparams);
  if (p->tail)
    tail_jac(p, t, n, J, ld);
  return 0;
}

/* Jacobian-vector product for the FFT gain path.  CVODE's one-sided
 * difference quotient divides the FFT's absolute rounding noise by a tiny
 * increment (measured: 20x more steps, additive kernel).  For the
 * separable kernels the coagulation RHS is a quadratic polynomial in y
 * (the tail in its bilinear form), so the central difference
 * (f(y + s v) - f(y - s v))/(2 s) is exact for ANY s: take s = |y|/|v|,
 * which keeps the noise at the level of f itself.  (Removal evaluated at
 * the tail's mean volume is the only non-polynomial term; there this is
 * a second-order difference.) */
static int cv_jtimes(N_Vector v, N_Vector Jv, sunrealtype t, N_Vector y,
                     N_Vector fy, void *data, N_Vector tmp)
{
  (void)fy;
  sb_pbe *p = data;
  double ny = sqrt(N_VDotProd(y, y)), nv = sqrt(N_VDotProd(v, v));
  if (!(nv > 0.0)) {
    N_VConst(0.0, Jv);
    return 0;
  }
  double s = ny > 0.0 ? ny / nv : 1.0 / nv;
  N_VLinearSum(1.0, y, s, v, tmp);
  full_rhs(p, t, N_VGetArrayPointer(tmp), N_VGetArrayPointer(Jv));
  N_VLinearSum(1.0, y, -s, v, tmp);
  double *a = N_VGetArrayPointer(Jv);
  /* second evaluation into p->jtmp, then the difference */
  full_rhs(p, t, N_VGetArrayPointer(tmp), p->jtmp);
  for (size_t i = 0; i < p->ny; i++)
    a[i] = (a[i] - p->jtmp[i]) / (2.0 * s);
  return 0;
}

/* Diagonal preconditioner P = diag(1 - gamma J_aa) for GMRES, applied on
 * the right (so GMRES controls the true residual), with a rank-one
 * correction making w^T P^-1 r = w^T r for the M1 weights w (v_a on the
 * grid, 1 on the tail mass).  Since w^T (I - gamma J) = w^T for pure
 * coagulation, every Krylov vector and the Newton correction then have
 * zero M1, as without preconditioning (measured drift ~1e-15; a plain
 * diagonal drifts by 1e-10..1e-6).  The defect is put back where the mass
 * is (along D^-1 |y|).  J_aa = -L_a - n_a K_aa (+ the sectional gain's
 * diagonal, - removal): the stiff modes are the loss of the large
 * particles, which this captures.  Tail rows are left unscaled. */
static int cv_psetup(sunrealtype t, N_Vector y, N_Vector fy,
                     sunbooleantype jok, sunbooleantype *jcur,
                     sunrealtype gamma, void *data)
{
  (void)fy;
  (void)jok;
  (void)gamma;
  sb_pbe *p = data;
  size_t N = p->n;
  const double *n = N_VGetArrayPointer(y);
  double *d = p->pdiag;
  if (p->cfg.method == SB_PBE_DISCRETE && p->sep)
    sbi_pbe_sep_gain_loss(p, n, NULL); /* loss rates into p->work */
  else
    loss_rates(p, n);
  for (size_t a = 0; a < N; a++)
    d[a] = -p->work[a] - n[a] * kval(p, a, a);
  if (p->cfg.method == SB_PBE_SECTIONAL)
    sbi_pbe_sect_gain_jac_diag(p, n, d);
  if (p->cfg.removal)
    for (size_t a = 0; a < N; a++)
      d[a] -= p->cfg.removal(t, p->v[a], p->cfg.rparams);
  for (size_t a = N; a < p->ny; a++)
    d[a] = 0.0;
  *jcur = 1;
  return 0;
}

static int cv_psolve(sunrealtype t, N_Vector y, N_Vector fy, N_Vector rv,
                     N_Vector zv, sunrealtype gamma, sunrealtype delta,
                     int lr, void *data)
{
  (void)t;
  (void)fy;
  (void)delta;
  (void)lr;
  sb_pbe *p = data;
  size_t N = p->n, NY = p->ny;
  const double *r = N_VGetArrayPointer(rv), *d = p->pdiag;
  const double *yc = N_VGetArrayPointer(y);
  double *z = N_VGetArrayPointer(zv);
  double wr = 0.0, wz = 0.0, wu = 0.0;
  /* r and z may be the same vector: read r before writing z.  The mass
   * defect is put back along u = D^-1 |y|, i.e. in proportion to the
   * mass w_a |y_a| of each component (u = D^-1 w would move it to the
   * empty largest sizes: unstable).  Not D^-1 (w |y|): the weights have
   * units (volume on the grid, 1 on the tail mass), and that form gave
   * the tail mass a share scaled by 1/v1, its noise swamping a tail of
   * small particles (v1 = 1e-20 m^3: M2 off by 1e49). */
  for (size_t a = 0; a < NY; a++) {
    double w = a < N ? p->v[a] : (a == N + 1 ? 1.0 : 0.0);
    double q = 1.0 - gamma * d[a]; /* >= 1: d <= 0 up to the gain term */
    if (!(q > 0.0))
      q = 1.0;
    wr += w * r[a];
    z[a] = r[a] / q;
    wz += w * z[a];
    wu += w * fabs(yc[a]) / q;
  }
  if (wu > 0.0) { /* z += u (w^T r - w^T z)/(w^T u) */
    double c = (wr - wz) / wu;
    for (size_t a = 0; a < NY; a++) {
      double w = a < N ? p->v[a] : (a == N + 1 ? 1.0 : 0.0);
      if (w != 0.0) {
        double q = 1.0 - gamma * d[a];
        z[a] += c * fabs(yc[a]) / (q > 0.0 ? q : 1.0);
      }
    }
  }
  return 0;
}

/* ------------------------------------------------------------ moments */

void sb_pbe_moments(const double *v, const double *n, size_t nbins,
                    double m[3])
{
  /* Kahan–Babuska (Neumaier) summation: the M1 drift test looks at 1e-14 */
  for (int j = 0; j < 3; j++) {
    double s = 0.0, c = 0.0;
    for (size_t i = 0; i < nbins; i++) {
      double x = n[i];
      for (int q = 0; q < j; q++)
        x *= v[i];
      double t = s + x;
      c += fabs(s) >= fabs(x) ? (s - t) + x : (x - t) + s;
      s = t;
    }
    /* past DBL_MAX the correction is inf - inf: the moment is +-inf */
    m[j] = isinf(s) ? s : s + c;
  }
}

/* ------------------------------------------------------------ driver */

#if SUNDIALS_VERSION_MAJOR >= 7
static void err_handler(int line, const char *func, const char *file,
                        const char *msg, SUNErrCode code, void *data,
                        SUNContext ctx)
{
  (void)line;
  (void)file;
  (void)ctx;
  sb_pbe *p = data;
  snprintf(p->cvmsg, sizeof p->cvmsg, "%s (code %d): %s", func, (int)code,
           msg);
}
#else
static void err_handler(int code, const char *module, const char *function,
                        char *msg, void *data)
{
  sb_pbe *p = data;
  if (code > 0 && p->cvmsg[0]) /* keep an error rather than a warning */
    return;
  snprintf(p->cvmsg, sizeof p->cvmsg, "%s %s (flag %d): %s", module,
           function, code, msg);
}
#endif

int sb_pbe_solve(sb_pbe *p, const double *times, size_t ntimes,
                 sb_pbe_output_fn out, void *data, sb_pbe_report *rep)
{
  if (!p || (!times && ntimes))
    return sbi_error(SB_EINVAL, __func__, "NULL argument");
  if (!p->have_init)
    return sbi_error(SB_EINVAL, __func__, "no initial state");
  for (size_t i = 0; i < ntimes; i++)
    if (!(times[i] >= 0 && isfinite(times[i])) ||
        (i > 0 && !(times[i] > times[i - 1])))
      return sbi_error(SB_EINVAL, __func__, "times must be finite, >= 0 and "
                       "increasing (times[%zu] = %g)", i, times[i]);
  size_t N = p->n, NY = p->ny;
  double m[3], m10;
  moments_y(p, p->y0, m);
  m10 = m[1];
  if (rep)
    memset(rep, 0, sizeof *rep);
  memcpy(p->y, p->y0, NY * sizeof *p->y);
  p->cvmsg[0] = '\0';

  int status = SB_SUCCESS;
  SUNContext ctx = NULL;
  N_Vector y = NULL, atolv = NULL;
  SUNMatrix A = NULL;
  SUNLinearSolver LS = NULL;
  void *mem = NULL;
  double drift = 0.0;
#if SUNDIALS_VERSION_MAJOR >= 7
  if (SUNContext_Create(SUN_COMM_NULL, &ctx) != 0)
#else
  if (SUNContext_Create(NULL, &ctx) != 0)
#endif
    return sbi_error(SB_ENOMEM, __func__, "SUNContext_Create failed");
#if SUNDIALS_VERSION_MAJOR >= 7
  SUNContext_ClearErrHandlers(ctx);
  SUNContext_PushErrHandler(ctx, err_handler, p);
#endif
  y = N_VNew_Serial((sunindextype)NY, ctx);
  mem = CVodeCreate(CV_BDF, ctx);
  if (!y || !mem) {
    status = sbi_error(SB_ENOMEM, __func__, "CVODE allocation failed");
    goto done;
  }
#if SUNDIALS_VERSION_MAJOR < 7
  CVodeSetErrHandlerFn(mem, err_handler, p);
#endif
  memcpy(N_VGetArrayPointer(y), p->y0, NY * sizeof(double));
  double atol = p->cfg.atol, mx = 0.0;
  for (size_t i = 0; i < NY; i++)
    mx = fmax(mx, p->y0[i]);
  if (!(atol > 0))
    atol = 1e-14 * (mx > 0 ? mx : 1.0);
  /* AUTO: the FFT's rounding (absolute, ~1e-16 of the largest gain) must
   * stay below atol, or CVODE chases it (at atol = 1e-30 it stopped at
   * its step limit): below the default atol, direct sums */
  if (p->fft_auto)
    p->use_fft = atol >= 1e-14 * (mx > 0 ? mx : 1.0);
  /* atol is on number concentrations; the tail's mass (a number times a
   * volume) gets atol times the mean volume at the start, so that it is
   * resolved whatever the unit of volume (with the number's atol a tail
   * of 1e-20 m^3 particles was pure noise, and M2 with it) */
  atolv = N_VNew_Serial((sunindextype)NY, ctx);
  if (!atolv) {
    status = sbi_error(SB_ENOMEM, __func__, "CVODE allocation failed");
    goto done;
  }
  {
    double m0[3];
    sb_pbe_moments(p->v, p->y0, p->n, m0);
    const double vmean = m0[0] > 0 && m0[1] > 0 ? m0[1] / m0[0] : 1.0;
    double *av = N_VGetArrayPointer(atolv);
    for (size_t i = 0; i < NY; i++)
      av[i] = atol;
    if (p->tail)
      av[p->n + 1] = atol * vmean;
    /* CVODE weighs errors by 1/(rtol |y| + atol): an atol that is not a
     * normal double (concentrations near 1e-300, or a tail mass out of
     * range) makes the weights infinite and the first step fail */
    if (!(atol >= DBL_MIN) || (p->tail && !(av[p->n + 1] >= DBL_MIN &&
                                            isfinite(av[p->n + 1])))) {
      status = sbi_error(SB_EDOM, __func__, "absolute tolerance %g (tail "
                         "mass %g) out of the range of doubles: initial "
                         "concentrations up to %g are too small for the "
                         "unit of number; solve for n/N0 with the kernel "
                         "N0 K instead", atol, p->tail ? atol * vmean : 0.0,
                         mx);
      goto done;
    }
  }
  int flag = CVodeInit(mem, cv_rhs, 0.0, y);
  if (flag >= 0)
    flag = CVodeSVtolerances(mem, p->cfg.rtol, atolv);
  if (flag >= 0)
    flag = CVodeSetUserData(mem, p);
  if (flag >= 0)
    flag = CVodeSetMaxNumSteps(mem, p->cfg.max_steps);
  if (flag >= 0) {
    int dense = p->cfg.linsol == SB_PBE_LS_DENSE;
    int prec = p->cfg.linsol == SB_PBE_LS_GMRES_DIAG ||
               p->cfg.linsol == SB_PBE_LS_AUTO;
    if (dense) {
      A = SUNDenseMatrix((sunindextype)NY, (sunindextype)NY, ctx);
      LS = A ? SUNLinSol_Dense(y, A, ctx) : NULL;
    } else {
      LS = SUNLinSol_SPGMR(y, prec ? SUN_PREC_RIGHT : SUN_PREC_NONE, 0, ctx);
    }
    if (!LS) {
      status = sbi_error(SB_ENOMEM, __func__, "linear solver allocation "
                         "failed (%zu bins)", N);
      goto done;
    }
    flag = CVodeSetLinearSolver(mem, LS, A);
    if (flag >= 0 && A)
      flag = CVodeSetJacFn(mem, cv_jac);
    if (flag >= 0 && prec)
      flag = CVodeSetPreconditioner(mem, cv_psetup, cv_psolve);
    if (flag >= 0 && !A && p->use_fft)
      flag = CVodeSetJacTimes(mem, NULL, cv_jtimes);
  }
  if (flag < 0) {
    status = sbi_error(SB_ESOLVER, __func__, "CVODE setup failed: %s",
                       p->cvmsg[0] ? p->cvmsg : "(no message)");
    goto done;
  }

  double t = 0.0;
  for (size_t it = 0; it < ntimes; it++) {
    if (times[it] > 0.0) {
      flag = CVode(mem, times[it], y, &t, CV_NORMAL);
      if (flag < 0) {
        status = sbi_error(SB_ESOLVER, __func__, "CVODE failed at t = %g "
                           "(target %g): %s", t, times[it],
                           p->cvmsg[0] ? p->cvmsg
                                       : CVodeGetReturnFlagName(flag));
        memcpy(p->y, N_VGetArrayPointer(y), NY * sizeof(double));
        goto done;
      }
    }
    memcpy(p->y, N_VGetArrayPointer(y), NY * sizeof(double));
    moments_y(p, p->y, m);
    if (m10 > 0)
      drift = fmax(drift, fabs(m[1] - m10) / m10);
    if (out && out(times[it], p->v, p->y, N, m, data)) {
      status = sbi_error(SB_EINVAL, __func__, "stopped by the output "
                         "callback at t = %g", times[it]);
      goto done;
    }
  }

done:
  if (rep) {
    rep->m1_drift = drift;
    if (mem) {
      long nfe = 0, nfels = 0;
      CVodeGetNumSteps(mem, &rep->nsteps);
      CVodeGetNumRhsEvals(mem, &nfe);
      CVodeGetNumErrTestFails(mem, &rep->nerrfails);
      if (LS) {
        CVodeGetNumLinRhsEvals(mem, &nfels);
        CVodeGetNumJacEvals(mem, &rep->njac);
        CVodeGetNumLinIters(mem, &rep->nliniters);
      }
      rep->nrhs = nfe + nfels;
    }
  }
  if (mem)
    CVodeFree(&mem);
  if (LS)
    SUNLinSolFree(LS);
  if (A)
    SUNMatDestroy(A);
  if (y)
    N_VDestroy(y);
  if (atolv)
    N_VDestroy(atolv);
  if (ctx)
    SUNContext_Free(&ctx);
  return status;
}
