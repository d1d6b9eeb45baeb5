/* langevin_step.c — exact transition of the Langevin model over one step:
 * scalar, and batched 3-D for the engine.
 *
 * Mohaupt (2011) eq 1.16 (Peirano, Chibbaro, Pozorski & Minier 2006)
 * writes the step as a Cholesky factorisation of the exact 2x2 covariance
 * of the noise (var_x, cov_xu, var_u; see langevin.h): U takes sqrt(var_u) z1,
 * X takes (cov_xu/sqrt(var_u)) z1 + sqrt(var_x|u) z2.  The coefficients are
 * written here without any difference of nearly equal terms:
 *   s_u  = B sqrt(tau)     sqrt(a (2-a)/2)
 *   s_xu = B tau sqrt(tau) sqrt(a^3 / (2 (2-a)))      (= cov_xu / s_u)
 *   s_xc = B tau sqrt(tau) sqrt(c(h)),  c(h) = h - 2 tanh(h/2),
 * with a = -expm1(-h), h = dt/tau; c(h) comes from
 * sb_langevin_var_x_cond (its small-h series).  None divides by var_u, so
 * the step stays well defined as dt -> 0 (all three -> 0). */
#include <math.h>

#include <gsl/gsl_randist.h>
#include <smolbridge/langevin.h>
#include <smolbridge/rng.h>

#include "common/internal.h"
#include "langevin_internal.h"

/* The coefficients in sbi_xd arithmetic (the same bits as the double
 * formulas wherever nothing over/underflows; langevin_internal.h for the
 * kernels at h = dt/tau below 1e-100 or above DBL_MAX): tau = 1e300 with
 * dt = 1 gave s_xu = 0 and s_xc = NaN before.  SB_ERANGE (for func), *c
 * NaN, where a coefficient exceeds DBL_MAX. */
static int coef_fill(sb_langevin_coef *c, double tau, double B, double dt,
                     const char *func)
{
  if (sbi_langevin_plain_ok(tau, B, dt)) { /* the formulas as they read */
    double h = dt / tau, a = -expm1(-h);
    double st = sqrt(tau), bt = B * st;  /* B sqrt(tau) */
    c->dt = dt;
    c->decay = exp(-h);
    c->gain = tau * a;
    c->s_u = bt * sqrt(0.5 * a * (2.0 - a));
    c->s_xu = bt * tau * sqrt(a * a * a / (2.0 * (2.0 - a)));
    c->s_xc = bt * tau * sqrt(sbi_langevin_cfun(h));
    return SB_SUCCESS;
  }
  const sbi_xd h = sbi_xd_div(sbi_xd_of(dt), sbi_xd_of(tau));
  const sbi_xd tx = sbi_xd_of(tau);
  const sbi_xd bt = sbi_xd_mul(sbi_xd_of(B), sbi_xd_sqrt(tx)); /* B sqrt(tau) */
  const sbi_xd btt = sbi_xd_mul(bt, tx);
  c->dt = dt;
  c->decay = exp(-sbi_xd_val(h));
  c->gain = sbi_xd_val(sbi_xd_mul(tx, sbi_langevin_kern(SBI_LK_A, h)));
  c->s_u = sbi_xd_val(
      sbi_xd_mul(bt, sbi_xd_sqrt(sbi_langevin_kern(SBI_LK_VU, h))));
  c->s_xu = sbi_xd_val(
      sbi_xd_mul(btt, sbi_xd_sqrt(sbi_langevin_kern(SBI_LK_XU2, h))));
  /* c(h) as in sb_langevin_var_x_cond (its small-h series) */
  c->s_xc = sbi_xd_val(
      sbi_xd_mul(btt, sbi_xd_sqrt(sbi_langevin_kern(SBI_LK_VXC, h))));
  if (!isfinite(c->gain) || !isfinite(c->s_u) || !isfinite(c->s_xu) ||
      !isfinite(c->s_xc)) {
    int st = sbi_error(SB_ERANGE, func,
                       "tau = %g, B = %g, dt = %g: a step coefficient "
                       "overflows a double", tau, B, dt);
    c->dt = c->decay = c->gain = c->s_u = c->s_xu = c->s_xc = NAN;
    return st;
  }
  return SB_SUCCESS;
}

/* tau, B, dt (valid) within 2^-300..2^300 (or B, dt zero): no
 * coefficient can overflow (B tau^1.5 sqrt(h) < 2^900) */
static int ordinary(double tau, double B, double dt)
{
  return tau > 0x1p-300 && tau < 0x1p300 && (B == 0 || (B > 0x1p-300 &&
         B < 0x1p300)) && (dt == 0 || (dt > 0x1p-300 && dt < 0x1p300));
}

static int bad_params(const char *func, double tau, double B, double dt)
{
  if (!(tau > 0) || !isfinite(tau))
    return sbi_error(SB_EDOM, func, "tau = %g must be positive and finite",
                     tau);
  if (!(B >= 0) || !isfinite(B))
    return sbi_error(SB_EDOM, func, "B = %g must be >= 0 and finite", B);
  if (!(dt >= 0) || !isfinite(dt))
    return sbi_error(SB_EDOM, func, "dt = %g must be >= 0 and finite", dt);
  return SB_SUCCESS;
}

int sb_langevin_coef_init(sb_langevin_coef *c, double tau, double B,
                          double dt)
{
  if (!c)
    return sbi_error(SB_EINVAL, __func__, "c is NULL");
  int st = bad_params(__func__, tau, B, dt);
  if (st) {
    c->dt = c->decay = c->gain = c->s_u = c->s_xu = c->s_xc = NAN;
    return st;
  }
  return coef_fill(c, tau, B, dt, __func__);
}

/* One component: the exact update with coefficients c, fluid velocity w.
 * Draw order z1 then z2 (documented in the header). */
static inline void step1(const sb_langevin_coef *c, double w,
                         const gsl_rng *r, double *x, double *u)
{
  double z1 = gsl_ran_gaussian_ziggurat(r, 1.0);
  double z2 = gsl_ran_gaussian_ziggurat(r, 1.0);
  double v = *u - w;
  *x += w * c->dt + v * c->gain + c->s_xu * z1 + c->s_xc * z2;
  *u = w + v * c->decay + c->s_u * z1;
}

/* The update of step1 for given normals z1, z2, into (*x, *u) only where
 * the new state is finite.  The plain sums first (the bits of step1); where
 * one of them leaves the doubles, the same sums with every term scaled by
 * 1/8 (exact above DBL_MIN; at most five terms of |.| <= DBL_MAX/8 cannot
 * overflow) and the result scaled back: an intermediate overflowed while
 * the new state is a double (u - us, or x + us dt + ... with terms of
 * opposite signs near DBL_MAX).  Returns 0, or SB_ERANGE (state unchanged,
 * nothing recorded) where the new state itself exceeds DBL_MAX. */
int sb_langevin_update(const sb_langevin_coef *c, double w, double z1,
                       double z2, double *x, double *u)
{
  double v = *u - w;
  double xn = *x + (w * c->dt + v * c->gain + c->s_xu * z1 + c->s_xc * z2);
  double un = w + v * c->decay + c->s_u * z1;
  if (!isfinite(xn) || !isfinite(un)) {
    const double q = 0.125;
    const double vq = q * *u - q * w, wq = q * w;
    xn = 8.0 * (q * *x + (wq * c->dt + vq * c->gain + (q * c->s_xu) * z1 +
                          (q * c->s_xc) * z2));
    un = 8.0 * (wq + vq * c->decay + (q * c->s_u) * z1);
    if (!isfinite(xn) || !isfinite(un))
      return SB_ERANGE;
  }
  *x = xn;
  *u = un;
  return SB_SUCCESS;
}

int sb_langevin_step(const sb_langevin *p, double dt, const gsl_rng *r,
                     double *x, double *u)
{
  if (!p || !r || !x || !u)
    return sbi_error(SB_EINVAL, __func__, "NULL argument");
  int st = bad_params(__func__, p->tau, p->B, dt);
  if (st)
    return st;
  if (!isfinite(p->us) || !isfinite(*x) || !isfinite(*u))
    return sbi_error(SB_EDOM, __func__,
                     "us = %g, x = %g, u = %g must be finite", p->us, *x,
                     *u);
  if (dt == 0)
    return SB_SUCCESS;
  sb_langevin_coef c;
  st = coef_fill(&c, p->tau, p->B, dt, __func__);
  if (st)
    return st;
  const double z1 = gsl_ran_gaussian_ziggurat(r, 1.0);
  const double z2 = gsl_ran_gaussian_ziggurat(r, 1.0);
  if (sb_langevin_update(&c, p->us, z1, z2, x, u))
    return sbi_error(SB_ERANGE, __func__,
                     "the new state (from x = %g, u = %g) overflows a "
                     "double", *x, *u);
  return SB_SUCCESS;
}

int sb_langevin_step3(size_t n, double dt, const double *tau,
                      const double *B, const double *us, double *x,
                      double *u, const gsl_rng *r)
{
  if (n == 0)
    return SB_SUCCESS;
  if (!tau || !B || !x || !u || !r)
    return sbi_error(SB_EINVAL, __func__, "NULL argument");
  /* validate everything first: either all particles move or none */
  for (size_t i = 0; i < n; i++) {
    int st = bad_params(__func__, tau[i], B[i], dt);
    if (st)
      return sbi_error(st, __func__,
                       "particle %zu: tau = %g, B = %g, dt = %g (need tau > "
                       "0, B >= 0, dt >= 0, finite)", i, tau[i], B[i], dt);
    for (int k = 0; k < 3; k++)
      if (!isfinite(x[3 * i + k]) || !isfinite(u[3 * i + k]) ||
          (us && !isfinite(us[3 * i + k])))
        return sbi_error(SB_EDOM, __func__, "particle %zu: x, u and us "
                         "must be finite", i);
    if (!ordinary(tau[i], B[i], dt)) {
      sb_langevin_coef c;
      st = coef_fill(&c, tau[i], B[i], dt, __func__);
      if (st)
        return sbi_error(st, __func__, "particle %zu: tau = %g, B = %g, "
                         "dt = %g: a coefficient overflows", i, tau[i],
                         B[i], dt);
    }
  }
  if (dt == 0)
    return SB_SUCCESS;
  for (size_t i = 0; i < n; i++) {
    sb_langevin_coef c;
    coef_fill(&c, tau[i], B[i], dt, __func__); /* checked above */
    for (int k = 0; k < 3; k++)
      step1(&c, us ? us[3 * i + k] : 0.0, r, &x[3 * i + k], &u[3 * i + k]);
  }
  return SB_SUCCESS;
}

int sb_langevin_step3_coef(size_t n, const sb_langevin_coef *coef,
                           const size_t *cidx, const double *us, double *x,
                           double *u, const gsl_rng *r)
{
  if (n == 0)
    return SB_SUCCESS;
  if (!coef || !x || !u || !r)
    return sbi_error(SB_EINVAL, __func__, "NULL argument");
  for (size_t i = 0; i < n; i++) {
    const sb_langevin_coef *c = &coef[cidx ? cidx[i] : i];
    double *xi = x + 3 * i, *ui = u + 3 * i;
    if (us) {
      const double *w = us + 3 * i;
      step1(c, w[0], r, &xi[0], &ui[0]);
      step1(c, w[1], r, &xi[1], &ui[1]);
      step1(c, w[2], r, &xi[2], &ui[2]);
    } else {
      step1(c, 0.0, r, &xi[0], &ui[0]);
      step1(c, 0.0, r, &xi[1], &ui[1]);
      step1(c, 0.0, r, &xi[2], &ui[2]);
    }
  }
  return SB_SUCCESS;
}

/* ------------------------------------------- counter-based streams */

/* one particle from its six normals z[0..5] = (z1, z2) per component */
static inline void step3_z(const sb_langevin_coef *c, const double *w,
                           const double *z, double *x, double *u)
{
  for (int k = 0; k < 3; k++) {
    double wk = w ? w[k] : 0.0;
    double v = u[k] - wk;
    x[k] += wk * c->dt + v * c->gain + c->s_xu * z[2 * k] +
            c->s_xc * z[2 * k + 1];
    u[k] = wk + v * c->decay + c->s_u * z[2 * k];
  }
}

int sb_langevin_step3_draw(const sb_langevin_coef *c, const double *us,
                           double *x, double *u, sb_stream *s)
{
  if (!c || !x || !u || !s)
    return sbi_error(SB_EINVAL, __func__, "NULL argument");
  double z[6];
  sb_stream_gaussian_fill(s, 6, z);
  step3_z(c, us, z, x, u);
  return SB_SUCCESS;
}

/* particles per call of sb_stream_gaussian_keyed: the normals of a chunk
 * (6 x 8 bytes each) stay in L1 */
#define CHUNK 128

int sb_langevin_step3_stream(size_t n, const sb_langevin_coef *coef,
                             const size_t *cidx, const double *us,
                             double *x, double *u, uint64_t seed,
                             uint64_t step, const uint64_t *ids,
                             uint64_t id0)
{
  if (n == 0)
    return SB_SUCCESS;
  if (!coef || !x || !u)
    return sbi_error(SB_EINVAL, __func__, "NULL argument");
  /* every key first: either all particles move or none */
  if (step > SB_STREAM_MAX_STEP)
    return sbi_error(SB_EDOM, __func__, "step = %llu exceeds "
                     "SB_STREAM_MAX_STEP", (unsigned long long)step);
  if (ids) {
    for (size_t i = 0; i < n; i++)
      if (ids[i] > SB_STREAM_MAX_ID)
        return sbi_error(SB_EDOM, __func__, "ids[%zu] = %llu exceeds "
                         "SB_STREAM_MAX_ID", i,
                         (unsigned long long)ids[i]);
  } else if (id0 > SB_STREAM_MAX_ID || n - 1 > SB_STREAM_MAX_ID - id0)
    return sbi_error(SB_EDOM, __func__, "ids %llu + [0, %zu) exceed "
                     "SB_STREAM_MAX_ID", (unsigned long long)id0, n);
  double z[6 * CHUNK];
  for (size_t i0 = 0; i0 < n; i0 += CHUNK) {
    size_t m = n - i0 < CHUNK ? n - i0 : CHUNK;
    sb_stream_gaussian_keyed(seed, step, m, ids ? ids + i0 : NULL, id0 + i0,
                             6, z);
    for (size_t j = 0; j < m; j++) {
      size_t i = i0 + j;
      const sb_langevin_coef *c = &coef[cidx ? cidx[i] : i];
      step3_z(c, us ? us + 3 * i : NULL, z + 6 * j, x + 3 * i, u + 3 * i);
    }
  }
  return SB_SUCCESS;
}
