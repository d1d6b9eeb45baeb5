/* engine_sweep.c — sort-and-sweep neighbour search with the per-particle
 * anisotropic reach of Thomine (2008) §4.1 and §5.1 (eqs 13-16), in 3-D
 * and with periodic images.
 *
 * The particles are sorted by their start abscissa x0.  For a particle R,
 * a partner S to its right (0 <= dx = x_S - x_R, minimum image) can only
 * meet R during the step if
 *     dx <= (d_R,x - d_min,x) + r_R + r_max + reach           (eq 14)
 * where d = displacement over the step (Thomine writes V dt; here the
 * chord of the exact Langevin step) and d_min,x = min_i d_i,x (eq 13): the
 * x-gap closes at most at the rate of R against the fastest left-mover.
 * Across x (k = y, z), a partner above (dy >= 0) or below must satisfy
 *     dy <= (d_R,k - d_min,k) + r_R + r_max + reach            (eq 15)
 *    -dy <= (d_max,k - d_R,k) + r_R + r_max + reach            (eq 16)
 * These are necessary conditions for |x0_RS + s (d_S - d_R)| <= sigma +
 * reach at some s in [0, 1] (each component must close the gap), so the
 * sweep returns a superset of the colliding pairs.  Thomine uses the
 * velocities and 2-D; the z bounds are the same as the y bounds (its
 * §4.4 uses the isotropic D_max in z).
 *
 * Sorting: the order of the previous step is reused and repaired by
 * insertion sort (nearly sorted input, O(N + inversions)), with a budget of
 * 8N shifts after which a full qsort is done (Thomine 2008, §4.5.1,
 * discusses quicksort's bad cases on nearly sorted input).
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "common/internal.h"
#include "engine_internal.h"

typedef struct {
  double k;
  size_t i;
} kv;

static int kv_cmp(const void *a, const void *b)
{
  const kv *p = a, *q = b;
  if (p->k < q->k)
    return -1;
  if (p->k > q->k)
    return 1;
  return (p->i > q->i) - (p->i < q->i);
}

static int sort_x(sb_engine *e, const double *x0, const char *who)
{
  const size_t n = e->n;
  size_t *ord = e->order;
  double *key = e->key;
  if (e->norder == n) {
    for (size_t m = 0; m < n; m++)
      key[m] = x0[3 * ord[m]];
    size_t budget = 8 * n + 64, shifts = 0;
    int ok = 1;
    for (size_t m = 1; m < n && ok; m++) {
      double kk = key[m];
      size_t ii = ord[m], q = m;
      while (q > 0 && key[q - 1] > kk) {
        key[q] = key[q - 1];
        ord[q] = ord[q - 1];
        q--;
        if (++shifts > budget) {
          ok = 0;
          break;
        }
      }
      key[q] = kk;
      ord[q] = ii;
    }
    if (ok)
      return SB_SUCCESS;
  }
  kv *t = malloc(n * sizeof *t);
  if (!t)
    return sbi_error(SB_ENOMEM, who, "out of memory");
  for (size_t i = 0; i < n; i++) {
    t[i].k = x0[3 * i];
    t[i].i = i;
  }
  qsort(t, n, sizeof *t, kv_cmp);
  for (size_t m = 0; m < n; m++) {
    ord[m] = t[m].i;
    key[m] = t[m].k;
  }
  free(t);
  e->norder = n;
  return SB_SUCCESS;
}

int sbi_engine_sweep(sb_engine *e, const double *x0, const double *disp,
                     double reach, const char *who)
{
  const size_t n = e->n;
  const int dim = e->par.dim;
  const double *L = e->par.L;
  int st = sort_x(e, x0, who);
  if (st)
    return st;
  double dmin[3] = {0, 0, 0}, dmax[3] = {0, 0, 0};
  if (disp) {
    for (int k = 0; k < 3; k++)
      dmin[k] = dmax[k] = disp[k];
    for (size_t i = 0; i < n; i++)
      for (int k = 0; k < dim; k++) {
        double v = disp[3 * i + k];
        if (v < dmin[k])
          dmin[k] = v;
        if (v > dmax[k])
          dmax[k] = v;
      }
  }
  const size_t *ord = e->order;
  const double *key = e->key;
  for (size_t m = 0; m < n; m++) {
    const size_t R = ord[m];
    const double base = e->radius[R] + e->rmax + reach;
    double dR[3] = {0, 0, 0};
    if (disp)
      for (int k = 0; k < dim; k++)
        dR[k] = disp[3 * R + k];
    const double reach_x = dR[0] - dmin[0] + base;  /* eq 14 */
    double up[3], down[3];
    for (int k = 1; k < dim; k++) {
      up[k] = dR[k] - dmin[k] + base;    /* eq 15 */
      down[k] = dmax[k] - dR[k] + base;  /* eq 16 */
    }
    const double xr = key[m];
    for (size_t q = m + 1; q < m + n; q++) {
      size_t idx = q < n ? q : q - n;
      double dx = key[idx] - xr + (q < n ? 0.0 : L[0]);
      if (dx > reach_x)
        break;
      size_t S = ord[idx];
      int ok = 1;
      for (int k = 1; k < dim && ok; k++) {
        double d = sbi_minimg(x0[3 * S + k] - x0[3 * R + k], L[k]);
        ok = d >= 0.0 ? d <= up[k] : -d <= down[k];
      }
      if (ok) {
        st = sbi_engine_push_pair(e, R, S, who);
        if (st)
          return st;
      }
    }
  }
  return SB_SUCCESS;
}
