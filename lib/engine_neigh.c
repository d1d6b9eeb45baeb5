/* engine_neigh.c — neighbour search: linked cells (O(N)) and brute force
 * (O(N^2) reference), the dispatcher, and the exact segment test.
 *
 * Candidate criterion.  Over a step particle i moves on the segment
 * x0_i + s disp_i, s in [0, 1] (the straight "chord" the ballistic
 * detector uses).  Two segments can come within sigma_ij + reach only if
 *     |dx0_ij| <= r_i + r_j + |disp_i| + |disp_j| + reach      (*)
 * (triangle inequality).  Both methods return every pair satisfying (*)
 * (cells: with cell edge >= cut = 2 r_max + 2 max|disp| + reach, every such
 * pair lies in neighbouring cells), hence a superset of the pairs that can
 * collide.  Periodic images: the minimum image is used, which is exact as
 * long as cut < L/2 in every direction (checked; otherwise SB_EINVAL,
 * "step too large for the box").
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "internal.h"
#include "engine_internal.h"

int sbi_engine_push_pair(sb_engine *e, size_t i, size_t j)
{
  if (e->npairs == e->cappairs) {
    size_t nc = e->cappairs ? 2 * e->cappairs : 1024;
    size_t *np = realloc(e->pairs, 2 * nc * sizeof *np);
    if (!np)
      return sbi_error(SB_ENOMEM, "sb_engine_step",
                       "out of memory (%zu candidate pairs)", nc);
    e->pairs = np;
    e->cappairs = nc;
  }
  e->pairs[2 * e->npairs] = i < j ? i : j;
  e->pairs[2 * e->npairs + 1] = i < j ? j : i;
  e->npairs++;
  return SB_SUCCESS;
}

double sbi_engine_max_disp(const sb_engine *e, const double *disp)
{
  double m = 0.0;
  if (!disp)
    return 0.0;
  for (size_t i = 0; i < e->n; i++) {
    const double *d = &disp[3 * i];
    double v = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    if (v > m)
      m = v;
  }
  return sqrt(m);
}

/* |disp_i| into e->dn; returns the cut-off 2 rmax + 2 max|disp| + reach
 * and checks it against half the box. */
static int cutoff(sb_engine *e, const double *disp, double reach,
                  double *cut, const char *func)
{
  double m = 0.0;
  for (size_t i = 0; i < e->n; i++) {
    double v = 0.0;
    if (disp) {
      const double *d = &disp[3 * i];
      v = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    }
    if (!isfinite(v))
      return sbi_error(SB_EINVAL, func, "particle %zu: non-finite "
                       "displacement", i);
    e->dn[i] = v;
    if (v > m)
      m = v;
  }
  *cut = 2.0 * e->rmax + 2.0 * m + reach;
  for (int k = 0; k < e->par.dim; k++)
    if (!(*cut < 0.5 * e->par.L[k]))
      return sbi_error(SB_EINVAL, func,
                       "step too large for the box: reach 2 r_max + 2 "
                       "max|disp| + extra = %g m is not below L[%d]/2 = %g m",
                       *cut, k, 0.5 * e->par.L[k]);
  return SB_SUCCESS;
}

/* Criterion (*) for one pair. */
static inline int near(const sb_engine *e, const double *x0, size_t i,
                       size_t j, double reach)
{
  double d2 = 0.0;
  for (int k = 0; k < e->par.dim; k++) {
    double d = sbi_minimg(x0[3 * i + k] - x0[3 * j + k], e->par.L[k]);
    d2 += d * d;
  }
  double lim = e->radius[i] + e->radius[j] + e->dn[i] + e->dn[j] + reach;
  return d2 <= lim * lim;
}

static int brute(sb_engine *e, const double *x0, double reach)
{
  for (size_t i = 0; i < e->n; i++)
    for (size_t j = i + 1; j < e->n; j++)
      if (near(e, x0, i, j, reach)) {
        int st = sbi_engine_push_pair(e, i, j);
        if (st)
          return st;
      }
  return SB_SUCCESS;
}

/* Linked cells: counting sort of the particles by cell, then every
 * particle i is compared with the particles j > i of the (up to 27)
 * neighbouring cells.  Cell edge >= cut, and no more than ~2 cells per
 * particle (larger cells are still correct, only slower per cell). */
static int cells(sb_engine *e, const double *x0, double cut, double reach)
{
  const int dim = e->par.dim;
  const size_t n = e->n;
  double vol = 1.0;
  for (int k = 0; k < dim; k++)
    vol *= e->par.L[k];
  double cs = cut, csmin = pow(vol / (2.0 * (double)n + 8.0), 1.0 / dim);
  if (cs < csmin)
    cs = csmin;
  int nc[3] = {1, 1, 1};
  double inv[3] = {0, 0, 0};
  size_t ncell = 1;
  for (int k = 0; k < dim; k++) {
    double m = floor(e->par.L[k] / cs);
    nc[k] = m < 1 ? 1 : (m > 1e6 ? 1000000 : (int)m);
    inv[k] = nc[k] / e->par.L[k];
    ncell *= (size_t)nc[k];
  }
  if (ncell + 1 > e->capcells) {
    size_t *p = realloc(e->cell_start, (ncell + 1) * sizeof *p);
    if (!p)
      return sbi_error(SB_ENOMEM, "sb_engine_step", "out of memory");
    e->cell_start = p;
    e->capcells = ncell + 1;
  }
  size_t *start = e->cell_start, *list = e->cell_list, *cof = e->cell_of;
  memset(start, 0, (ncell + 1) * sizeof *start);
  for (size_t i = 0; i < n; i++) {
    size_t c = 0;
    for (int k = dim - 1; k >= 0; k--) {
      int ck = (int)(x0[3 * i + k] * inv[k]);
      if (ck >= nc[k])
        ck = nc[k] - 1;
      if (ck < 0)
        ck = 0;
      c = c * (size_t)nc[k] + (size_t)ck;
    }
    cof[i] = c;
    start[c + 1]++;
  }
  for (size_t c = 0; c < ncell; c++)
    start[c + 1] += start[c];
  /* stable fill: particles in increasing index within a cell */
  for (size_t i = 0; i < n; i++)
    list[start[cof[i]]++] = i;
  for (size_t c = ncell; c > 0; c--)
    start[c] = start[c - 1];
  start[0] = 0;

  /* Copy positions and reach radii r + |disp| in cell order, so that the
   * inner loop reads contiguous memory. */
  double *xs = e->xs;
  for (size_t a = 0; a < n; a++) {
    size_t i = list[a];
    xs[4 * a] = x0[3 * i];
    xs[4 * a + 1] = x0[3 * i + 1];
    xs[4 * a + 2] = x0[3 * i + 2];
    xs[4 * a + 3] = e->radius[i] + e->dn[i];
  }
  /* For each particle only the neighbouring cells within `cut` of it are
   * visited (one to eight cells when cells are larger than the cut-off,
   * as in dilute systems); with fewer than 3 cells along a direction all
   * of them are visited once.  A pair within the cut-off is seen from
   * both sides; it is reported once (j > i). */
  const double *L = e->par.L;
  for (size_t a = 0; a < n; a++) {
    const size_t i = list[a];
    const double *xa = &xs[4 * a];
    int off[3][3], noff[3];
    int ci[3] = {0, 0, 0};
    for (int k = 0; k < 3; k++) {
      noff[k] = 1;
      off[k][0] = 0;
      if (k >= dim)
        continue;
      double xk = xa[k];
      int ck = (int)(xk * inv[k]);
      ck = ck >= nc[k] ? nc[k] - 1 : (ck < 0 ? 0 : ck);
      ci[k] = ck;
      if (nc[k] <= 2) {
        if (nc[k] == 2)
          off[k][noff[k]++] = 1;
        continue;
      }
      double lo = xk - ck * (L[k] / nc[k]), hi = L[k] / nc[k] - lo;
      if (lo < cut)
        off[k][noff[k]++] = -1;
      if (hi < cut)
        off[k][noff[k]++] = 1;
    }
    const double ra = xa[3] + reach;
    for (int q2 = 0; q2 < noff[2]; q2++)
      for (int q1 = 0; q1 < noff[1]; q1++)
        for (int q0 = 0; q0 < noff[0]; q0++) {
          int q[3] = {ci[0] + off[0][q0], ci[1] + off[1][q1],
                      ci[2] + off[2][q2]};
          size_t c2 = 0;
          for (int k = dim - 1; k >= 0; k--) {
            int v = q[k] < 0 ? q[k] + nc[k]
                             : (q[k] >= nc[k] ? q[k] - nc[k] : q[k]);
            c2 = c2 * (size_t)nc[k] + (size_t)v;
          }
          for (size_t b = start[c2]; b < start[c2 + 1]; b++) {
            const double *xb = &xs[4 * b];
            double d2 = 0.0;
            for (int k = 0; k < dim; k++) {
              double d = sbi_minimg(xa[k] - xb[k], L[k]);
              d2 += d * d;
            }
            double lim = ra + xb[3];
            if (d2 > lim * lim)
              continue;
            size_t j = list[b];
            if (j <= i)
              continue;
            int st = sbi_engine_push_pair(e, i, j);
            if (st)
              return st;
          }
        }
  }
  return SB_SUCCESS;
}

int sbi_engine_find_pairs(sb_engine *e, sb_engine_neigh m, const double *x0,
                          const double *disp, double reach)
{
  e->npairs = 0;
  if (e->n < 2)
    return SB_SUCCESS;
  double cut = 0.0;
  int st = cutoff(e, disp, reach, &cut, "sb_engine_step");
  if (st)
    return st;
  switch (m) {
  case SB_NEIGH_CELLS:
    return cells(e, x0, cut, reach);
  case SB_NEIGH_SWEEP:
    return sbi_engine_sweep(e, x0, disp, reach);
  case SB_NEIGH_BRUTE:
    return brute(e, x0, reach);
  }
  return sbi_error(SB_EINVAL, "sb_engine_step", "unknown method %d", (int)m);
}

int sb_engine_neighbours(sb_engine *e, sb_engine_neigh m, const double *disp,
                         double reach, size_t *npairs, const size_t **pairs)
{
  if (!e || !npairs || !pairs || (unsigned)m > SB_NEIGH_BRUTE ||
      !(reach >= 0.0) || !isfinite(reach))
    return sbi_error(SB_EINVAL, __func__, "bad argument");
  int st = sbi_engine_find_pairs(e, m, e->x, disp, reach);
  *npairs = st ? 0 : e->npairs;
  *pairs = e->pairs;
  return st;
}

int sb_engine_pair_can_meet(const sb_engine *e, const double *disp,
                            double reach, size_t i, size_t j)
{
  if (!e || i >= e->n || j >= e->n || i == j)
    return 0;
  double a[3] = {0, 0, 0}, d[3] = {0, 0, 0};
  for (int k = 0; k < e->par.dim; k++) {
    a[k] = sbi_minimg(e->x[3 * i + k] - e->x[3 * j + k], e->par.L[k]);
    if (disp)
      d[k] = disp[3 * i + k] - disp[3 * j + k];
  }
  double dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
  double ad = a[0] * d[0] + a[1] * d[1] + a[2] * d[2];
  double s = dd > 0.0 ? -ad / dd : 0.0;
  s = s < 0.0 ? 0.0 : (s > 1.0 ? 1.0 : s);
  double m2 = 0.0;
  for (int k = 0; k < 3; k++) {
    double v = a[k] + s * d[k];
    m2 += v * v;
  }
  double lim = e->radius[i] + e->radius[j] + reach;
  return m2 <= lim * lim;
}
