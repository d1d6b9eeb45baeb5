/* pbe_sectional.c — fixed-pivot sectional method (Kumar & Ramkrishna 1996,
 * Chem. Eng. Sci. 51:1311, eqs 22–25) on the geometric grid
 * x_i = v1 ratio^i:
 *   dN_i/dt = sum_{j>=k, x_{i-1} <= x_j+x_k <= x_{i+1}} (1 - delta_jk/2)
 *               eta_i(x_j + x_k) beta_jk N_j N_k  -  N_i sum_k beta_ik N_k,
 *   eta_i(v) = (x_{i+1} - v)/(x_{i+1} - x_i)  for x_i <= v <= x_{i+1},
 *            = (v - x_{i-1})/(x_i - x_{i-1})  for x_{i-1} <= v <= x_i.
 * The two fractions of a new particle sum to 1 (number) and their
 * pivot-weighted sum is v (mass).  Particles formed above the last pivot
 * leave the grid (reported as M1 drift).  The loss term and the driver are
 * in pbe.c.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_sf_gamma.h>

#include "common/internal.h"
#include "pbe_internal.h"

/* Coalescence channels by diagonal d = k - j (pairs j <= k): on the
 * geometric grid the volume x_j + x_k = x_k w, w = 1 + r^-d, lies in
 * [x_k r^off, x_k r^(off+1)) with off and the split fraction
 * eta = (r^(off+1) - w)/(r^(off+1) - r^off) independent of k.  The pair
 * stays on the grid iff x_j + x_k <= x_{N-1}, i.e. i = j + d + off <= N-2
 * (or i = N-1 with eta = 1). */
int sbi_pbe_sect_setup(sb_pbe *p)
{
  size_t n = p->n;
  double r = p->cfg.ratio, lr = log(r);
  p->diags = calloc(n, sizeof *p->diags);
  if (!p->diags)
    return SB_ENOMEM;
  size_t tot = 0;
  for (size_t d = 0; d < n; d++) {
    double w = 1.0 + pow(r, -(double)d);
    long off = (long)floor(log(w) / lr);
    if (off < 0)
      off = 0;
    while (off > 0 && pow(r, (double)off) > w)
      off--;
    while (pow(r, (double)(off + 1)) <= w)
      off++;
    double lo = pow(r, (double)off), hi = lo * r;
    sbi_pbe_diag *q = &p->diags[d];
    q->off = (unsigned)off;
    q->eta = (hi - w) / (hi - lo);
    long last = (long)n - 2 + (q->eta == 1.0); /* largest target pivot */
    long cnt = last - (long)d - off + 1;
    q->cnt = cnt > 0 ? (unsigned)cnt : 0;
    q->start = tot;
    tot += q->cnt;
    if (q->cnt)
      p->ndiag = d + 1;
  }
  if (!p->kmat)
    return SB_SUCCESS; /* kernel evaluated on the fly */
  p->kdiag = malloc((tot ? tot : 1) * sizeof *p->kdiag);
  if (!p->kdiag)
    return SB_ENOMEM;
  for (size_t d = 0; d < p->ndiag; d++) {
    const sbi_pbe_diag *q = &p->diags[d];
    double c = d == 0 ? 0.5 : 1.0;
    for (size_t j = 0; j < q->cnt; j++)
      p->kdiag[q->start + j] = c * p->kmat[j * n + j + d];
  }
  return SB_SUCCESS;
}

static double cbeta(const sb_pbe *p, size_t d, size_t j)
{
  if (p->kdiag)
    return p->kdiag[p->diags[d].start + j];
  return (d == 0 ? 0.5 : 1.0) *
         p->cfg.kernel(p->v[j], p->v[j + d], p->cfg.kparams);
}

void sbi_pbe_sect_gain(const sb_pbe *p, const double *restrict n,
                       double *restrict dndt)
{
  size_t N = p->n;
  memset(dndt, 0, N * sizeof *dndt);
  for (size_t d = 0; d < p->ndiag; d++) {
    const sbi_pbe_diag *q = &p->diags[d];
    double eta = q->eta, eta1 = 1.0 - eta;
    const double *restrict nd = n + d;
    double *restrict lo = dndt + d + q->off, *restrict hi = lo + 1;
    size_t cnt = q->cnt;
    if (p->kdiag) {
      const double *restrict kd = p->kdiag + q->start;
      if (eta == 1.0) {
        for (size_t j = 0; j < cnt; j++)
          lo[j] += kd[j] * n[j] * nd[j];
      } else {
        for (size_t j = 0; j < cnt; j++) {
          double t = kd[j] * n[j] * nd[j];
          lo[j] += eta * t;
          hi[j] += eta1 * t;
        }
      }
    } else {
      for (size_t j = 0; j < cnt; j++) {
        double t = cbeta(p, d, j) * n[j] * nd[j];
        lo[j] += eta * t;
        if (eta1 != 0.0)
          hi[j] += eta1 * t;
      }
    }
  }
}

void sbi_pbe_sect_gain_jac(const sb_pbe *p, const double *n, double *J,
                           size_t ld)
{
  for (size_t d = 0; d < p->ndiag; d++) {
    const sbi_pbe_diag *q = &p->diags[d];
    double eta = q->eta, eta1 = 1.0 - eta;
    for (size_t j = 0; j < q->cnt; j++) {
      size_t k = j + d, i = k + q->off;
      double cb = cbeta(p, d, j), dj = cb * n[k], dk = cb * n[j];
      double *cj = J + j * ld, *ck = J + k * ld;
      cj[i] += eta * dj;
      ck[i] += eta * dk;
      if (eta1 != 0.0) {
        cj[i + 1] += eta1 * dj;
        ck[i + 1] += eta1 * dk;
      }
    }
  }
}

/* 1 - (1 + d) e^-d = P(2, d), the regularised incomplete gamma: positive,
 * computed without cancellation. */
/* P(2, d) = 1 - (1 + d) e^-d; 1 at d = +inf (v0 ~ 1e-320 below x_0:
 * GSL gives NaN there) */
static double p2(double d)
{
  return d > 0 ? (isinf(d) ? 1.0 : gsl_sf_gamma_inc_P(2.0, d)) : 0.0;
}

int sbi_pbe_sect_init_exp(sb_pbe *p, double n0, double v0)
{
  size_t N = p->n;
  const double *x = p->v;
  double *y = p->y0;
  for (size_t i = 0; i < N; i++)
    y[i] = 0.0;
  /* below x_0: the mass, N0 v0 P(2, x0/v0), goes to pivot 0 */
  y[0] += n0 * v0 * p2(x[0] / v0) / x[0];
  for (size_t i = 0; i + 1 < N; i++) {
    double a = x[i] / v0, b = x[i + 1] / v0, d = b - a;
    if (a > 700.0)
      break; /* e^-a underflows: nothing left */
    double ea = exp(-a), om = -expm1(-d);
    /* number A = N0 (e^-a - e^-b); first moment
     * B = N0 v0 [(1+a) e^-a - (1+b) e^-b] = N0 v0 e^-a [a om + P(2,d)] */
    double A = n0 * ea * om;
    double B = n0 * v0 * ea * (a * om + p2(d));
    double w = x[i + 1] - x[i];
    /* split conserving number and mass; both parts are integrals of
     * non-negative functions, clip rounding below 0 */
    double lo = (x[i + 1] * A - B) / w, hi = (B - x[i] * A) / w;
    y[i] += lo > 0 ? lo : 0.0;
    y[i + 1] += hi > 0 ? hi : 0.0;
  }
  return SB_SUCCESS;
}

/* Only pairs whose lower target is their own larger pivot (off = 0) feed
 * the diagonal: d/dn_k of eta cb n_j n_k (twice that for j = k). */
void sbi_pbe_sect_gain_jac_diag(const sb_pbe *p, const double *n,
                                double *diag)
{
  for (size_t d = 0; d < p->ndiag; d++) {
    const sbi_pbe_diag *q = &p->diags[d];
    if (q->off != 0)
      continue;
    double c = q->eta * (d == 0 ? 2.0 : 1.0);
    for (size_t j = 0; j < q->cnt; j++)
      diag[j + d] += c * cbeta(p, d, j) * n[j];
  }
}
