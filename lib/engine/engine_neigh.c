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
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "common/internal.h"
#include "engine_internal.h"

int sbi_engine_push_pair(sb_engine *e, size_t i, size_t j, const char *who)
{
  if (e->npairs == e->cappairs) {
    size_t nc = e->cappairs ? 2 * e->cappairs : 1024;
    size_t *np = realloc(e->pairs, 2 * nc * sizeof *np);
    if (!np)
      return sbi_error(SB_ENOMEM, who,
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

/* |disp_i| (0 without displacements). */
static inline double disp_len(const double *disp, size_t i)
{
  if (!disp)
    return 0.0;
  const double *d = &disp[3 * i];
  return sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
}

/* SB_EINVAL for particle i whose |disp_i| (as disp_len) is not finite:
 * a component that is not finite, or finite components whose squares
 * overflow, a step far too large for the box (its length then from
 * hypot, which does not overflow). */
static int disp_refused(const double *disp, size_t i, const char *func)
{
  const double *d = &disp[3 * i];
  if (!isfinite(d[0]) || !isfinite(d[1]) || !isfinite(d[2]))
    return sbi_error(SB_EINVAL, func, "particle %zu: non-finite "
                     "displacement (%g, %g, %g)", i, d[0], d[1], d[2]);
  const double len = hypot(hypot(d[0], d[1]), d[2]);
  return sbi_error(SB_EINVAL, func, "step too large for the box: particle "
                   "%zu moves by (%g, %g, %g) m, a length of %g m (whose "
                   "square overflows a double), far beyond half the box",
                   i, d[0], d[1], d[2], len);
}

/* |disp_i| into e->dn; returns the cut-off 2 rmax + 2 max|disp| + reach
 * and checks it against half the box. */
static int cutoff(sb_engine *e, const double *disp, double reach,
                  double *cut, double *dmax, const char *func)
{
  const size_t n = e->n;
  const int nt = n >= 4096 ? sbi_engine_threads(&e->par) : 1;
  double m = 0.0;
  int bad = 0;
  double *dn = e->dn;
  if (disp == e->disp && e->dn_ready) {
    /* the step's own displacements: the transport measured them */
    m = e->dn_max;
    bad = e->dn_bad;
  } else if (nt > 1) {
    /* a maximum: the same for any split between threads */
#ifdef _OPENMP
#pragma omp parallel for schedule(static) num_threads(nt) \
    reduction(max : m) reduction(| : bad)
#endif
    for (size_t i = 0; i < n; i++) {
      const double v = disp_len(disp, i);
      bad |= !isfinite(v);
      dn[i] = v;
      m = v > m ? v : m;
    }
  } else {  /* no parallel region: entering one costs ~0.3 us */
    for (size_t i = 0; i < n; i++) {
      const double v = disp_len(disp, i);
      bad |= !isfinite(v);
      dn[i] = v;
      m = v > m ? v : m;
    }
  }
  e->dn_ready = 0;  /* dn is overwritten by later searches and outcomes */
  if (bad)
    for (size_t i = 0; i < n; i++)
      if (!isfinite(dn[i]))
        return disp_refused(disp, i, func);
  if (disp == e->disp && sbi_engine_det_bulge_on(e))
    /* noise-free Stokes paths curve away from their chords: each path
     * stays within |disp| + bulge of its start */
    for (size_t i = 0; i < n; i++) {
      dn[i] += sbi_engine_det_bulge(e, i, &e->u0[3 * i], e->x0[3 * i + 1],
                                    e->par.dt);
      m = dn[i] > m ? dn[i] : m;
    }
  *cut = 2.0 * e->rmax + 2.0 * m + reach;
  *dmax = m;
  for (int k = 0; k < e->par.dim; k++)
    if (!(*cut < 0.5 * e->par.L[k]))
      return sbi_error(SB_EINVAL, func,
                       "step too large for the box: reach 2 r_max + 2 "
                       "max|disp| + extra = %g m is not below L[%d]/2 = %g m",
                       *cut, k, 0.5 * e->par.L[k]);
  return SB_SUCCESS;
}

/* Forget the floaters (their flags must be clear whenever the cells are
 * not the list's). */
static void float_clear(sbi_verlet *v)
{
  for (size_t q = 0; q < v->nfloat; q++)
    v->isfloat[v->floats[q]] = 0;
  v->nfloat = 0;
}

/* The block of the grid's cells within m[k] cells of the one holding
 * point pt (wrapped into the box: cw): that cell ca and the offsets
 * lo[k]..hi[k] (every cell once where the block would wrap onto itself).
 */
static void cell_block(const sb_engine *e, const double *pt, const int m[3],
                       double cw[3], int ca[3], int lo[3], int hi[3])
{
  const sbi_grid *g = &e->grid;
  for (int k = 0; k < 3; k++) {
    cw[k] = 0.0;
    ca[k] = lo[k] = hi[k] = 0;
    if (k >= e->par.dim)
      continue;
    cw[k] = sbi_wrap(pt[k], e->par.L[k]);
    int v = (int)(cw[k] * g->inv[k]);
    ca[k] = v >= g->nc[k] ? g->nc[k] - 1 : (v < 0 ? 0 : v);
    if (2 * m[k] + 1 >= g->nc[k])
      hi[k] = g->nc[k] - 1;
    else
      lo[k] = -m[k], hi[k] = m[k];
  }
}

/* Index of the cell ca + q (periodic). */
static size_t cell_at(const sbi_grid *g, int dim, const int ca[3],
                      const int q[3])
{
  size_t c2 = 0;
  for (int k = 0; k < dim; k++) {
    int v = ca[k] + q[k];  /* |q[k]| < nc (cell_block): one wrap */
    v = v < 0 ? v + g->nc[k] : (v >= g->nc[k] ? v - g->nc[k] : v);
    c2 += (size_t)v * g->stride[k];
  }
  return c2;
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

static int brute(sb_engine *e, const double *x0, double reach,
                 const char *who)
{
  for (size_t i = 0; i < e->n; i++)
    for (size_t j = i + 1; j < e->n; j++)
      if (near(e, x0, i, j, reach)) {
        int st = sbi_engine_push_pair(e, i, j, who);
        if (st)
          return st;
      }
  return SB_SUCCESS;
}

/* What cells() scans: the grid and the particles in cell order. */
typedef struct {
  int dim, own_wrap;
  int nc[3];
  size_t stride[3];
  double edge[3], L[3];
  double cut, reach;
  double ext;  /* reach + the largest r + |disp| of the scan,
                  (cut + reach)/2, plus 1e-12 cut against rounding */
  const size_t *start, *list;
  const double *xs;
  /* the Langevin search's slot-ordered copies (lsearch; NULL elsewhere):
   * displacement and radius (4 per slot), cell coordinates (3 per slot) */
  const double *ds;
  const int *cc;
} cell_scan;

/* Append (i, j), i < j, to b; 0, or -1 out of memory. */
static int pb_push(sbi_pairbuf *b, size_t i, size_t j)
{
  if (b->n == b->cap) {
    size_t nc = b->cap ? 2 * b->cap : 1024;
    size_t *np = realloc(b->p, 2 * nc * sizeof *np);
    if (!np)
      return -1;
    b->p = np;
    b->cap = nc;
  }
  b->p[2 * b->n] = i < j ? i : j;
  b->p[2 * b->n + 1] = i < j ? j : i;
  b->n++;
  return 0;
}

/* The engine's per-thread candidate buffers, at least nt of them; NULL
 * out of memory. */
static sbi_pairbuf *thread_buffers(sb_engine *e, int nt)
{
  if (nt > e->ntb) {
    sbi_pairbuf *tb = realloc(e->tb, (size_t)nt * sizeof *tb);
    if (!tb)
      return NULL;
    for (int t = e->ntb; t < nt; t++)
      tb[t] = (sbi_pairbuf){NULL, 0, 0};
    e->tb = tb;
    e->ntb = nt;
  }
  return e->tb;
}

/* Append the per-thread buffers tb[0..nt-1], in thread order, to
 * e->pairs; 0, or 1 out of memory. */
static int join_buffers(sb_engine *e, const sbi_pairbuf *tb, int nt)
{
  size_t total = e->npairs;
  for (int t = 0; t < nt; t++)
    total += tb[t].n;
  if (total > e->cappairs) {
    size_t *np = realloc(e->pairs, 2 * total * sizeof *np);
    if (!np)
      return 1;
    e->pairs = np;
    e->cappairs = total;
  }
  for (int t = 0; t < nt; t++) {
    if (!tb[t].n)
      continue;  /* (its list may be NULL) */
    memcpy(e->pairs + 2 * e->npairs, tb[t].p, 2 * tb[t].n * sizeof *tb[t].p);
    e->npairs += tb[t].n;
  }
  return 0;
}

/* The candidate pairs whose first member (in cell order) lies in cell c,
 * in the order of the serial scan; 0, or -1 out of memory. */
static int scan_cell(const cell_scan *K, size_t c, sbi_pairbuf *out)
{
  const int dim = K->dim;
  const double *L = K->L, *xs = K->xs;
  const size_t *start = K->start, *list = K->list;
  const double reach = K->reach;
  int ci[3] = {0, 0, 0};
  for (int k = 0; k < dim; k++)
    ci[k] = (int)((c / K->stride[k]) % (size_t)K->nc[k]);
  const size_t end = start[c + 1];
  for (size_t a = start[c]; a < end; a++) {
    const double *xa = &xs[4 * a];
    const double ra = xa[3] + reach;
    const size_t i = list[a];
    for (size_t b = a + 1; b < end; b++) {
      const double *xb = &xs[4 * b];
      double d0 = xa[0] - xb[0], d1 = xa[1] - xb[1], d2 = xa[2] - xb[2];
      if (K->own_wrap) {
        d0 = sbi_minimg(d0, L[0]);
        d1 = sbi_minimg(d1, L[1]);
        d2 = dim == 3 ? sbi_minimg(d2, L[2]) : 0.0;
      }
      double lim = ra + xb[3];
      if (d0 * d0 + d1 * d1 + d2 * d2 <= lim * lim && pb_push(out, i, list[b]))
        return -1;
    }
    /* neighbouring cells within a's own reach of it: a partner b across
     * a face is within r_a + |disp_a| + reach + r_b + |disp_b| <= wa of
     * a, so a lies within wa of that face (and of both faces of a
     * corner); wa <= cut spares the particles with small displacements
     * the visits the largest one needs.  The candidates and their order
     * are those of the whole cut-off. */
    const double wa = xa[3] + K->ext;
    int off[3][3], noff[3], any = 0;
    for (int k = 0; k < 3; k++) {
      noff[k] = 1;
      off[k][0] = 0;
      if (k >= dim || K->nc[k] == 1)
        continue;
      if (K->nc[k] == 2) {  /* the other cell is adjacent on both sides */
        off[k][noff[k]++] = 1;
        any = 1;
        continue;
      }
      double lo = xa[k] - ci[k] * K->edge[k];
      if (lo < wa)
        off[k][noff[k]++] = -1;
      if (K->edge[k] - lo < wa)
        off[k][noff[k]++] = 1;
      any |= noff[k] > 1;
    }
    if (!any)
      continue;
    for (int q2 = 0; q2 < noff[2]; q2++)
      for (int q1 = 0; q1 < noff[1]; q1++)
        for (int q0 = 0; q0 < noff[0]; q0++) {
          if (!q0 && !q1 && !q2)
            continue;  /* own cell: done above */
          const int q[3] = {off[0][q0], off[1][q1], off[2][q2]};
          size_t c2 = 0;
          for (int k = 0; k < dim; k++) {
            int v = ci[k] + q[k];
            v = v < 0 ? v + K->nc[k] : (v >= K->nc[k] ? v - K->nc[k] : v);
            c2 += (size_t)v * K->stride[k];
          }
          for (size_t b = start[c2]; b < start[c2 + 1]; b++) {
            if (b <= a)
              continue;  /* reported from its first member */
            const double *xb = &xs[4 * b];
            double d2 = 0.0;
            for (int k = 0; k < dim; k++) {
              double d = sbi_minimg(xa[k] - xb[k], L[k]);
              d2 += d * d;
            }
            double lim = ra + xb[3];
            if (d2 <= lim * lim && pb_push(out, i, list[b]))
              return -1;
          }
        }
  }
  return 0;
}

/* Linked cells: counting sort of the particles by cell (positions and
 * reach radii r + |disp| are scattered into e->xs in cell order, so the
 * pair loop reads contiguous memory), then for every particle a:
 *  - its own cell: the particles after it in cell order (plain
 *    differences: two points of one cell are less than L/2 apart when the
 *    direction has >= 2 cells);
 *  - a neighbouring cell only when a lies within `cut` of the shared face
 *    (edge, corner), i.e. rarely in dilute systems where the cells are much
 *    larger than the cut-off; a pair in neighbouring cells is within the
 *    cut-off of the face from both sides, so it is seen twice and reported
 *    from its first member in cell order.
 * Cell edge >= cut, about SBI_CELL_PPC particles per cell (larger cells
 * are still correct, only slower per cell).  Directions with 1 or 2 cells use the
 * minimum image.  for_list: the pairs within r_i + r_j + reach of a
 * Verlet list (no displacements).  keep_list: the Verlet list stays valid
 * (its pairs and floaters are its own; only its cells are gone). */
static int cell_sort(sb_engine *e, const double *x0, double cut,
                     double reach, int for_list, int keep_list, cell_scan *K,
                     const char *who)
{
  if (!keep_list) {  /* its cells are overwritten (a list build sets it) */
    e->vl.valid = 0;
    float_clear(&e->vl);
  }
  const int dim = e->par.dim;
  const size_t n = e->n;
  const double *L = e->par.L;
  double vol = 1.0;
  for (int k = 0; k < dim; k++)
    vol *= L[k];
  double cs = cut, csmin = sbi_cell_edge_min(vol, n, dim);
  if (cs < csmin)
    cs = csmin;
  int nc[3] = {1, 1, 1};
  double inv[3] = {0, 0, 0}, edge[3] = {1e300, 1e300, 1e300};
  size_t ncell = 1, stride[3] = {1, 1, 1};
  for (int k = 0; k < dim; k++) {
    double m = floor(L[k] / cs);
    nc[k] = m < 1 ? 1 : (m > 1e6 ? 1000000 : (int)m);
    inv[k] = nc[k] / L[k];
    edge[k] = L[k] / nc[k];
    stride[k] = ncell;
    ncell *= (size_t)nc[k];
  }
  if (ncell + 1 > e->capcells) {
    size_t *p = realloc(e->cell_start, (ncell + 1) * sizeof *p);
    if (!p)
      return sbi_error(SB_ENOMEM, who, "out of memory");
    e->cell_start = p;
    e->capcells = ncell + 1;
  }
  size_t *start = e->cell_start, *list = e->cell_list, *cof = e->cell_of;
  memset(start, 0, (ncell + 1) * sizeof *start);
  const int nt = n >= 4096 ? sbi_engine_threads(&e->par) : 1;
#ifdef _OPENMP
#pragma omp parallel for schedule(static) num_threads(nt)
#endif
  for (size_t i = 0; i < n; i++) {
    size_t c = 0;
    for (int k = 0; k < dim; k++) {
      int ck = (int)(x0[3 * i + k] * inv[k]);
      ck = ck >= nc[k] ? nc[k] - 1 : (ck < 0 ? 0 : ck);
      c += (size_t)ck * stride[k];
    }
    cof[i] = c;
  }
  for (size_t i = 0; i < n; i++)
    start[cof[i] + 1]++;
  for (size_t c = 0; c < ncell; c++)
    start[c + 1] += start[c];
  /* stable scatter (increasing index within a cell); start[c] becomes the
   * end of cell c, shifted back below */
  double *xs = e->xs;
  for (size_t i = 0; i < n; i++) {
    size_t a = start[cof[i]]++;
    list[a] = i;
    xs[4 * a] = x0[3 * i];
    xs[4 * a + 1] = x0[3 * i + 1];
    xs[4 * a + 2] = x0[3 * i + 2];
    xs[4 * a + 3] = e->radius[i] + (for_list ? 0.0 : e->dn[i]);
  }
  for (size_t c = ncell; c > 0; c--)
    start[c] = start[c - 1];
  start[0] = 0;
  /* keep the grid for re-detection after collisions in this step */
  sbi_grid *g = &e->grid;
  g->valid = 1;
  for (int k = 0; k < 3; k++) {
    g->nc[k] = nc[k];
    g->stride[k] = stride[k];
    g->inv[k] = inv[k];
  }
  g->cut = cut;
  g->reach = reach;

  int own_wrap = 0;  /* a direction with a single cell: minimum image */
  for (int k = 0; k < dim; k++)
    own_wrap |= nc[k] == 1;
  *K = (cell_scan){dim, own_wrap, {nc[0], nc[1], nc[2]},
                   {stride[0], stride[1], stride[2]},
                   {edge[0], edge[1], edge[2]}, {L[0], L[1], L[2]},
                   cut, reach, 0.5 * (cut + reach) + 1e-12 * cut, start,
                   list, xs, NULL, NULL};
  return SB_SUCCESS;
}

static int cells(sb_engine *e, const double *x0, double cut, double reach,
                 int for_list, const char *who)
{
  cell_scan K;
  int st0 = cell_sort(e, x0, cut, reach, for_list, 0, &K, who);
  if (st0)
    return st0;
  const size_t n = e->n, ncell = (size_t)K.nc[0] * K.nc[1] * K.nc[2];
  const int nt = sbi_engine_threads(&e->par);
  if (nt <= 1 || n < 4096 || ncell < (size_t)(4 * nt)) {
    sbi_pairbuf pb = {e->pairs, e->npairs, e->cappairs};
    int st = 0;
    for (size_t c = 0; c < ncell && !st; c++)
      st = scan_cell(&K, c, &pb);
    e->pairs = pb.p;
    e->npairs = pb.n;
    e->cappairs = pb.cap;
    return st ? sbi_error(SB_ENOMEM, who, "out of memory "
                          "(%zu candidate pairs)", pb.n) : SB_SUCCESS;
  }
  /* in parallel: thread t scans the t-th of nt contiguous ranges of cells
   * into its own buffer; the buffers concatenated in thread order are the
   * serial list, pair for pair */
  sbi_pairbuf *tb = thread_buffers(e, nt);
  if (!tb)
    return sbi_error(SB_ENOMEM, who, "out of memory");
  int bad = 0;
#ifdef _OPENMP
#pragma omp parallel for schedule(static, 1) num_threads(nt) reduction(| : bad)
#endif
  for (int t = 0; t < nt; t++) {
    const size_t c0 = ncell * (size_t)t / (size_t)nt,
                 c1 = ncell * (size_t)(t + 1) / (size_t)nt;
    tb[t].n = 0;
    for (size_t c = c0; c < c1 && !bad; c++)
      bad |= scan_cell(&K, c, &tb[t]);
  }
  if (!bad)
    bad = join_buffers(e, tb, nt);
  if (bad)
    return sbi_error(SB_ENOMEM, who, "out of memory "
                     "(candidate pairs)");
  return SB_SUCCESS;
}

/* ------------------------------------------------ the Langevin search
 *
 * With the `langevin` detector the first pass over the candidates skips,
 * before drawing anything, every pair whose relative chord
 * dx0 + s dd, s in [0, 1], stays beyond sigma + rho (rho = the neighbour
 * reach; engine_langevin.c, beyond_reach), and draws its random numbers
 * in candidate order.  A search that returns
 *  (a) every pair of cells() that passes the chord test,
 *  (b) perhaps some that do not,
 *  (c) no pair cells() does not return,
 *  (d) in cells()' relative order
 * therefore gives the same run bit for bit (only the candidate count
 * differs).  lsearch() keeps cells()' counting sort (its grid serves
 * re-detection) and finds the pairs through the chord midpoints
 * m_k = x0_k + disp_k / 2 with extents f_k = r_k + |disp_k| / 2:
 *  (a) |dx0 + s dd - (dx0 + dd/2)| = |s - 1/2| |dd| <= (|d_i| + |d_j|)/2,
 *      so a pair within sigma + rho of its chord has
 *      |m_i - m_j| <= f_i + f_j + rho (minimum image: no larger).  The
 *      test is taken with a relative margin of 1e-8 and an absolute one
 *      of 64 L eps, far above the rounding of either side (a few eps of
 *      the lengths involved, a few ulp(L) for positions).  The stencil
 *      query (engine_lstencil.c) tests every pair of the same or
 *      neighbouring cells once, where the cells are at least the widest
 *      bound and three or more per axis.  Elsewhere the walk: each pair is
 *      looked for from its member of larger extent (ties: the lower
 *      slot), in the cells of a grid over the midpoints within
 *      2 f + rho (+ the margins, which also cover a cell index rounded
 *      across a face) of it: every pair passing the test is found once.  A
 *      window of at most one cell on either side on each axis of a grid
 *      of >= 4 cells sees each member through its cell's wrap, which is
 *      its nearest image (within 2 h <= L/2); wider windows take the
 *      minimum image member by member.
 *  (c) a pair found is kept only if scan_cell() would report it: the same
 *      first member (lower slot), the same face-zone decision and
 *      criterion (*) with the same operands and operations
 *      (cells_sees).
 *  (d) scan_cell() reports the pairs by the slot a of their first
 *      member, then its own cell (b > a), then the neighbouring cells in
 *      the loop order q2, q1, q0 over offsets listed as {0, -1, +1}
 *      ({0, +1} with two cells), then the slot b ascending; the kept
 *      pairs are sorted by (a, rank of b's cell offset in that loop, b).
 */

/* Would scan_cell() report the slots lo < hi, whose cells have the
 * coordinates ia, ib?  Sets the rank of b's cell offset from a's in
 * scan_cell's loop over the neighbouring cells (0: own cell). */
static int cells_sees_at(const cell_scan *K, size_t lo, size_t hi,
                         const int ia[3], const int ib[3], unsigned *g)
{
  const double *xa = &K->xs[4 * lo], *xb = &K->xs[4 * hi];
  const double *L = K->L;
  const double ra = xa[3] + K->reach, lim = ra + xb[3];
  /* the distance first (most pairs of a Verlet list fail it), with
   * scan_cell's operations: plain differences within a cell (the minimum
   * image where a direction has one cell), the minimum image across */
  const int own = ia[0] == ib[0] && ia[1] == ib[1] && ia[2] == ib[2];
  if (own) {
    double d0 = xa[0] - xb[0], d1 = xa[1] - xb[1], d2 = xa[2] - xb[2];
    if (K->own_wrap) {
      d0 = sbi_minimg(d0, L[0]);
      d1 = sbi_minimg(d1, L[1]);
      d2 = K->dim == 3 ? sbi_minimg(d2, L[2]) : 0.0;
    }
    *g = 0;
    return d0 * d0 + d1 * d1 + d2 * d2 <= lim * lim;
  }
  double d2 = 0.0;
  for (int k = 0; k < K->dim; k++) {
    double d = sbi_minimg(xa[k] - xb[k], L[k]);
    d2 += d * d;
  }
  if (!(d2 <= lim * lim))
    return 0;
  /* then whether a's scan looks into b's cell (its face zones) */
  const double wa = xa[3] + K->ext;
  unsigned r = 0, w = 1;
  for (int k = 0; k < K->dim; k++, w *= 3) {
    const int nck = K->nc[k];
    int v = ib[k] - ia[k];
    v = v < 0 ? v + nck : v;
    if (v == 0)
      continue;
    if (nck == 2) {  /* scan_cell: {0, +1}, always visited */
      r += 2 * w;
      continue;
    }
    const double dlo = xa[k] - ia[k] * K->edge[k];
    if (v == nck - 1) {  /* -1 */
      if (!(dlo < wa))
        return 0;
      r += w;
    } else if (v == 1) {  /* +1 */
      if (!(K->edge[k] - dlo < wa))
        return 0;
      r += 2 * w;
    } else
      return 0;  /* not a neighbouring cell */
  }
  *g = r;
  return 1;
}

/* Each slot's cell coordinates, cc[3 a + k] (no divisions). */
static void slot_cells(const cell_scan *K, int *cc)
{
  int ci[3] = {0, 0, 0};
  const size_t ncell = (size_t)K->nc[0] * K->nc[1] * K->nc[2];
  for (size_t c = 0; c < ncell; c++) {
    if (c)
      for (int k = 0; k < 3 && ++ci[k] == K->nc[k]; k++)
        ci[k] = 0;
    for (size_t a = K->start[c]; a < K->start[c + 1]; a++)
      memcpy(&cc[3 * a], ci, sizeof ci);
  }
}

/* Blocks of the midpoint loop (its sums do not depend on the threads). */
#define SBI_LSEARCH_BLOCKS 32

/* Particles per cell of the midpoint grid, at least (memory: one cell
 * per 2 particles at most; with the walk 0.5 per cell was no faster, with
 * the stencil 1, 3 and 5 were not, in V12's Kn_D = 0.5 runs). */
#define SBI_LSEARCH_PPC 2.0

static int lsearch_grow(sb_engine *e, size_t n)
{
  if (n > e->lcapn) {
    double *xm = realloc(e->lxm, 4 * n * sizeof *xm);
    if (xm)
      e->lxm = xm;
    double *fx = realloc(e->lfx, 4 * n * sizeof *fx);
    if (fx)
      e->lfx = fx;
    size_t *fl = realloc(e->lfl, n * sizeof *fl);
    if (fl)
      e->lfl = fl;
    size_t *cn = realloc(e->lcnt, (n + 1) * sizeof *cn);
    if (cn)
      e->lcnt = cn;
    int *cc = realloc(e->lcc, 3 * n * sizeof *cc);
    if (cc)
      e->lcc = cc;
    double *ds = realloc(e->lds, 4 * n * sizeof *ds);
    if (ds)
      e->lds = ds;
    if (!xm || !fx || !fl || !cn || !cc || !ds)
      return -1;
    e->lcapn = n;
  }
  return 0;
}

static int lpair_push(sbi_lpairbuf *b, size_t sa, size_t sb, unsigned g)
{
  if (b->n == b->cap) {
    size_t nc = b->cap ? 2 * b->cap : 1024;
    sbi_lpair *p = realloc(b->p, nc * sizeof *p);
    if (!p)
      return -1;
    b->p = p;
    b->cap = nc;
  }
  b->p[b->n++] = (sbi_lpair){sa, sb, g};
  return 0;
}

/* At least nt shares of the Langevin search (their buffers kept). */
static int lparts(sb_engine *e, int nt)
{
  if (nt <= e->nlpt)
    return 0;
  sbi_lpart *p = realloc(e->lpt, (size_t)nt * sizeof *p);
  if (!p)
    return -1;
  for (int t = e->nlpt; t < nt; t++)
    p[t] = (sbi_lpart){NULL, 0, {NULL, 0, 0}};
  e->lpt = p;
  e->nlpt = nt;
  return 0;
}

/* Append the pairs the first nb shares found (slots a < b, rank g of b's
 * cell) to the candidates in cells()' order: by first slot (counting
 * sort), then (rank, b); the candidates are the particles list[a],
 * list[b].  How the pairs are spread over the shares and ordered in them
 * does not matter (each pair once: the order out is a total order), so
 * the shares may come from threads. */
static int emit_in_cell_order(sb_engine *e, int nb, const size_t *list,
                              const char *who)
{
  const sbi_lpart *in = e->lpt;
  const size_t n = e->n;
  size_t np = 0;
  for (int t = 0; t < nb; t++)
    np += in[t].pr.n;
  if (np > e->lcap2) {
    sbi_lpair *q = realloc(e->lpr2, np * sizeof *q);
    if (!q)
      return sbi_error(SB_ENOMEM, who, "out of memory "
                       "(%zu candidate pairs)", np);
    e->lpr2 = q;
    e->lcap2 = np;
  }
  size_t *cnt = e->lcnt;
  memset(cnt, 0, (n + 1) * sizeof *cnt);
  for (int t = 0; t < nb; t++)
    for (size_t q = 0; q < in[t].pr.n; q++)
      cnt[in[t].pr.p[q].a + 1]++;
  for (size_t a = 0; a < n; a++)
    cnt[a + 1] += cnt[a];
  sbi_lpair *sp = e->lpr2;
  for (int t = 0; t < nb; t++)
    for (size_t q = 0; q < in[t].pr.n; q++)
      sp[cnt[in[t].pr.p[q].a]++] = in[t].pr.p[q];
  sbi_pairbuf pb = {e->pairs, e->npairs, e->cappairs};
  int bad = 0;
  for (size_t q0 = 0; q0 < np && !bad;) {
    size_t q1 = q0 + 1;
    while (q1 < np && sp[q1].a == sp[q0].a)
      q1++;
    for (size_t q = q0 + 1; q < q1; q++) {  /* insertion sort: few */
      sbi_lpair t = sp[q];
      size_t r = q;
      while (r > q0 && (sp[r - 1].g > t.g ||
                        (sp[r - 1].g == t.g && sp[r - 1].b > t.b))) {
        sp[r] = sp[r - 1];
        r--;
      }
      sp[r] = t;
    }
    for (size_t q = q0; q < q1 && !bad; q++)
      bad = pb_push(&pb, list[sp[q].a], list[sp[q].b]);
    q0 = q1;
  }
  e->pairs = pb.p;
  e->npairs = pb.n;
  e->cappairs = pb.cap;
  return bad ? sbi_error(SB_ENOMEM, who, "out of memory "
                         "(%zu candidate pairs)", pb.n) : SB_SUCCESS;
}

/* What a query of the midpoint grid keeps fixed: the grid (fx: midpoint
 * and extent, fl: slot, in grid order), the querying midpoint ma of slot
 * a and extent fa, its part of the bound, (fa + rho)(1 + tol) + eabs, and
 * 1 + tol. */
typedef struct {
  const double *fx;
  const size_t *fl;
  const double *ma;
  size_t a;
  double fa, Ba, tol1;
} lprobe;

/* Push the pair of slots a, b (either order) when scan_cell() would
 * report it and the detector's chord test would examine it, with the rank
 * of the later slot's cell.  The chord test (engine_langevin.c,
 * beyond_reach: the relative chord stays beyond sigma + rho) is the
 * detector's own, with the operations of the pair the step makes
 * (sbi_engine_make_pair, sbi_pair_chord_min2), so a pair dropped here is
 * one the detector skips at the step's start (lsearch runs only where
 * that test applies to every pair: sbi_engine_langevin_chord_gate); half
 * of the midpoint grid's pairs in V12's Kn_D = 0.5 runs at dt = 2 tau_p.
 * -1 out of memory. */
static inline int lprobe_emit(const sb_engine *e, const cell_scan *K,
                              size_t a, size_t b, sbi_lpairbuf *out)
{
  const size_t s0 = a < b ? a : b, s1 = a < b ? b : a;
  /* the particles' x0, disp and radius through their slot-ordered copies
   * (the same values; slots of near pairs are near in memory) */
  const double *xa = &K->xs[4 * s0], *xb = &K->xs[4 * s1];
  const double *da = &K->ds[4 * s0], *db = &K->ds[4 * s1];
  double dx0[3], dd[3];  /* sbi_engine_make_pair's chord (periodic box) */
  for (int k = 0; k < 3; k++) {
    dx0[k] = k < e->par.dim ? sbi_minimg(xa[k] - xb[k], e->par.L[k]) : 0.0;
    dd[k] = da[k] - db[k];
  }
  const double lim = (da[3] + db[3]) + e->lreach;
  if (sbi_chord_min2(dx0, dd) > lim * lim)
    return 0;
  unsigned g;
  if (cells_sees_at(K, s0, s1, &K->cc[3 * s0], &K->cc[3 * s1], &g) &&
      lpair_push(out, s0, s1, g))
    return -1;
  return 0;
}

/* The members pb0..pb1-1 of one grid cell, seen through the periodic
 * image that shifts them by sh: push the pairs with slot a that a looks
 * for (b of smaller extent; ties: the lower slot) within
 * f_a + f_b + rho (with the margins) and that scan_cell() would report.
 * The test only has to keep every pair scan_cell() reports (cells_sees
 * decides), and its margins (1e-8 relative) dwarf the rounding of the
 * shifted differences.  -1 out of memory. */
static inline int lprobe_cell(const sb_engine *e, const cell_scan *K,
                              const lprobe *P, const double sh[3],
                              size_t pb0, size_t pb1, sbi_lpairbuf *out)
{
  const double *ma = P->ma, fa = P->fa, Ba = P->Ba, tol1 = P->tol1;
  const double m0 = ma[0] - sh[0], m1 = ma[1] - sh[1], m2 = ma[2] - sh[2];
  const size_t a = P->a;
  for (size_t pb = pb0; pb < pb1; pb++) {
    /* most members fail: one branch-free test (which member looks for
     * the pair, and the distance), rarely taken */
    const double *mb = &P->fx[4 * pb];
    const double fb = mb[3];
    const double d0 = m0 - mb[0], d1 = m1 - mb[1], d2 = m2 - mb[2];
    const double B = Ba + fb * tol1;
    const int mine = (fb < fa) | ((fb == fa) & (a < P->fl[pb]));
    if (!(mine & (d0 * d0 + d1 * d1 + d2 * d2 <= B * B)))
      continue;  /* too far, or looked for from b */
    if (lprobe_emit(e, K, a, P->fl[pb], out))
      return -1;
  }
  return 0;
}

/* lprobe_cell with each member's nearest image (minimum image per axis;
 * a 2-D box has third coordinates 0, whose image is 0 for any L2 >= 0). */
static int lprobe_wide(const sb_engine *e, const cell_scan *K,
                       const lprobe *P, double L0, double L1, double L2,
                       size_t pb0, size_t pb1, sbi_lpairbuf *out)
{
  const double *ma = P->ma;
  const size_t a = P->a;
  for (size_t pb = pb0; pb < pb1; pb++) {
    const double *mb = &P->fx[4 * pb];
    const double fb = mb[3];
    const double d0 = sbi_minimg(ma[0] - mb[0], L0),
                 d1 = sbi_minimg(ma[1] - mb[1], L1),
                 d2 = sbi_minimg(ma[2] - mb[2], L2);
    const double B = P->Ba + fb * P->tol1;
    const size_t b = P->fl[pb];
    if (!(fb < P->fa || (fb == P->fa && a < b)) ||
        d0 * d0 + d1 * d1 + d2 * d2 > B * B)
      continue;
    if (lprobe_emit(e, K, a, b, out))
      return -1;
  }
  return 0;
}


/* sbi_lsearch_stencil's report of a pair: lprobe_emit. */
typedef struct {
  const cell_scan *K;
  sbi_lpairbuf *out;
} lstencil_ctx;

static int lstencil_emit(const sb_engine *e, void *vctx, size_t a,
                         size_t b)
{
  const lstencil_ctx *c = vctx;
  return lprobe_emit(e, c->K, a, b, c->out);
}

/* The first cell of share t of nt: the shares hold about equal numbers
 * of the grid's n members (fs: the cells' starts, nfc cells). */
static size_t share_start(const size_t *fs, size_t nfc, size_t n, int t,
                          int nt)
{
  if (t >= nt)
    return nfc;
  const size_t want = (size_t)((double)n * t / nt);
  size_t lo = 0, hi = nfc;  /* the first c with fs[c] >= want */
  while (lo < hi) {
    const size_t mid = lo + (hi - lo) / 2;
    if (fs[mid] < want)
      lo = mid + 1;
    else
      hi = mid;
  }
  return lo;
}

/* The stencil query of grid M (nfc cells) on the engine's threads, each
 * over a range of cells, then every pair in the cells' order (the same
 * candidates in the same order for any number of threads). */
static int stencil_search(sb_engine *e, const cell_scan *K,
                          const sbi_mgrid *M, size_t nfc, const char *who)
{
  const size_t n = e->n;
  const int nt = n >= 4096 ? sbi_engine_threads(&e->par) : 1;
  if (lparts(e, nt))
    return sbi_error(SB_ENOMEM, who, "out of memory");
  int bad = 0;
#ifdef _OPENMP
#pragma omp parallel for schedule(static, 1) num_threads(nt) reduction(| : bad)
#endif
  for (int t = 0; t < nt; t++) {
    sbi_lpart *part = &e->lpt[t];
    part->pr.n = 0;
    lstencil_ctx lc = {K, &part->pr};
    bad |= sbi_lsearch_stencil(e, M, share_start(M->fs, nfc, n, t, nt),
                               share_start(M->fs, nfc, n, t + 1, nt), part,
                               lstencil_emit, &lc) != 0;
  }
  if (bad)
    return sbi_error(SB_ENOMEM, who, "out of memory "
                     "(candidate pairs)");
  return emit_in_cell_order(e, nt, K->list, who);
}

static int lsearch(sb_engine *e, const double *x0, const double *disp,
                   double cut, double reach, const char *who)
{
  cell_scan K;
  int st = cell_sort(e, x0, cut, reach, 0, 0, &K, who);
  if (st)
    return st;
  const size_t n = e->n;
  const int dim = K.dim;
  if (lsearch_grow(e, n))
    return sbi_error(SB_ENOMEM, who, "out of memory");
  double Lmax = 0.0, vol = 1.0;
  for (int k = 0; k < dim; k++) {
    Lmax = K.L[k] > Lmax ? K.L[k] : Lmax;
    vol *= K.L[k];
  }
  const double tol = 1e-8, eabs = 64.0 * Lmax * DBL_EPSILON;
  /* midpoints (in the box) and extents, in cell order; on the threads
   * in SBI_LSEARCH_BLOCKS blocks whose sums are added in order (the same
   * sum for any number of threads) */
  double *xm = e->lxm;
  const int nt = n >= 4096 ? sbi_engine_threads(&e->par) : 1;
  double *ds = e->lds;  /* K.ds: disp and radius in cell order */
  K.ds = ds;
  K.cc = e->lcc;
  slot_cells(&K, e->lcc);
  double bsum[SBI_LSEARCH_BLOCKS], bmax[SBI_LSEARCH_BLOCKS];
#ifdef _OPENMP
#pragma omp parallel for schedule(static) num_threads(nt)
#endif
  for (int blk = 0; blk < SBI_LSEARCH_BLOCKS; blk++) {
    const size_t a0 = n * (size_t)blk / SBI_LSEARCH_BLOCKS,
                 a1 = n * (size_t)(blk + 1) / SBI_LSEARCH_BLOCKS;
    double sum = 0.0, max = 0.0;
    for (size_t a = a0; a < a1; a++) {
      const size_t i = K.list[a];
      for (int k = 0; k < 3; k++)
        xm[4 * a + k] =
            k < dim ? sbi_wrap(x0[3 * i + k] + 0.5 * disp[3 * i + k], K.L[k])
                    : 0.0;
      xm[4 * a + 3] = e->radius[i] + 0.5 * e->dn[i];
      for (int k = 0; k < 3; k++)
        ds[4 * a + k] = disp[3 * i + k];
      ds[4 * a + 3] = e->radius[i];
      sum += xm[4 * a + 3];
      max = xm[4 * a + 3] > max ? xm[4 * a + 3] : max;
    }
    bsum[blk] = sum;
    bmax[blk] = max;
  }
  double fsum = 0.0, fmax = 0.0;
  for (int blk = 0; blk < SBI_LSEARCH_BLOCKS; blk++) {
    fsum += bsum[blk];
    fmax = bmax[blk] > fmax ? bmax[blk] : fmax;
  }
  /* their grid: for the stencil query (engine_lstencil.c) cells of at
   * least the widest bound 2 f_max + rho with the margins, three or more
   * on each axis; else, for the walk, cells of at least the mean query
   * 2 f + rho (most particles then look at most one cell away, and only
   * near a face) */
  const double h0 = pow(vol * SBI_LSEARCH_PPC / ((double)n + 8.0), 1.0 / dim);
  const double wmean = 2.0 * fsum / (double)n + reach;
  const double wmax = (2.0 * fmax + reach) * (1.0 + tol) + 4.0 * eabs;
  double h = h0 < wmax ? wmax : h0;
  int stencil = e->lstencil_off != 1;
  for (int k = 0; k < dim; k++)
    stencil &= floor(K.L[k] / h) >= 3.0;
  if (!stencil)
    h = h0 < wmean ? wmean : h0;
  int nf[3] = {1, 1, 1};
  double inv[3] = {0, 0, 0}, hk[3] = {1e300, 1e300, 1e300};
  size_t fst[3] = {1, 1, 1}, nfc = 1;
  for (int k = 0; k < dim; k++) {
    double m = floor(K.L[k] / h);
    nf[k] = m < 1 ? 1 : (m > 1e6 ? 1000000 : (int)m);
    inv[k] = nf[k] / K.L[k];
    hk[k] = K.L[k] / nf[k];
    fst[k] = nfc;
    nfc *= (size_t)nf[k];
  }
  if (nfc + 1 > e->lcapc) {
    size_t *p = realloc(e->lfs, (nfc + 1) * sizeof *p);
    if (!p)
      return sbi_error(SB_ENOMEM, who, "out of memory");
    e->lfs = p;
    e->lcapc = nfc + 1;
  }
  size_t *fs = e->lfs, *fl = e->lfl, *cnt = e->lcnt;
  double *fx = e->lfx;
  memset(fs, 0, (nfc + 1) * sizeof *fs);
#ifdef _OPENMP
#pragma omp parallel for schedule(static) num_threads(nt)
#endif
  for (size_t a = 0; a < n; a++) {  /* cnt: the midpoint's cell */
    size_t c = 0;
    for (int k = 0; k < dim; k++) {
      int v = (int)(xm[4 * a + k] * inv[k]);
      v = v >= nf[k] ? nf[k] - 1 : (v < 0 ? 0 : v);
      c += (size_t)v * fst[k];
    }
    cnt[a] = c;
  }
  for (size_t a = 0; a < n; a++)
    fs[cnt[a] + 1]++;
  for (size_t c = 0; c < nfc; c++)
    fs[c + 1] += fs[c];
  for (size_t a = 0; a < n; a++) {
    size_t p = fs[cnt[a]]++;
    fl[p] = a;
    memcpy(&fx[4 * p], &xm[4 * a], 4 * sizeof *fx);
  }
  for (size_t c = nfc; c > 0; c--)
    fs[c] = fs[c - 1];
  fs[0] = 0;
  if (stencil) {  /* every pair once, then in the cells' order */
    const sbi_mgrid M = {dim, {nf[0], nf[1], nf[2]}, {fst[0], fst[1], fst[2]},
                         {K.L[0], K.L[1], K.L[2]}, fs, fl, fx, reach, tol,
                         eabs};
    e->lsearch_stencil_n++;
    return stencil_search(e, &K, &M, nfc, who);
  }
  /* every pair from its member of larger extent */
  e->lsearch_walk_n++;
  const double L0 = K.L[0], L1 = dim > 1 ? K.L[1] : 0.0,
               L2 = dim > 2 ? K.L[2] : 0.0;
  const size_t *list = K.list;
  if (lparts(e, 1))
    return sbi_error(SB_ENOMEM, who, "out of memory");
  sbi_lpairbuf *out = &e->lpt[0].pr;
  out->n = 0;
  int ci[3] = {0, 0, 0};
  for (size_t c = 0; c < nfc; c++) {
    if (c) {  /* the coordinates of cell c (no divisions) */
      for (int k = 0; k < 3 && ++ci[k] == nf[k]; k++)
        ci[k] = 0;
    }
    for (size_t p = fs[c]; p < fs[c + 1]; p++) {
      const double *ma = &fx[4 * p];
      const size_t a = fl[p];
      const double fa = ma[3];
      const double W = (2.0 * fa + reach) * (1.0 + tol) + 2.0 * eabs;
      int lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0}, wide = 0;
      for (int k = 0; k < dim; k++) {
        /* the cells that [m - W, m + W] meets: ceil((W - dlo)/h) below,
         * ceil((W - (h - dlo))/h) above (the margins in W cover a cell
         * index rounded across a face); ceil(t) = 1 for t in (0, 1]
         * needs no call (most windows are narrower than a cell) */
        const double dlo = ma[k] - ci[k] * hk[k], dhi = hk[k] - dlo;
        const double tm = W * inv[k];
        const int m = tm <= 1.0 ? 1 : (int)ceil(tm);
        if (2 * m + 1 >= nf[k]) {
          hi[k] = nf[k] - 1;  /* every cell once */
          wide = 1;
          continue;
        }
        const double tl = (W - dlo) * inv[k], th = (W - dhi) * inv[k];
        lo[k] = dlo < W ? (tl <= 1.0 ? -1 : -(int)ceil(tl)) : 0;
        hi[k] = dhi < W ? (th <= 1.0 ? 1 : (int)ceil(th)) : 0;
        wide |= lo[k] < -1 || hi[k] > 1;
      }
      const lprobe P = {fx, fl, ma, a, fa,
                        (fa + reach) * (1.0 + tol) + eabs, 1.0 + tol};
      if (!wide) {
        /* at most the cells -1, 0, +1 on each axis of a grid of >= 4:
         * each member is within 2 h <= L/2 of ma on every axis through
         * the image of its cell's wrap, its nearest image.  Each axis'
         * cell index contribution and shift once. */
        size_t off[3][3] = {{0}, {0}, {0}};
        double shf[3][3] = {{0}, {0}, {0}};
        for (int k = 0; k < dim; k++)
          for (int q = lo[k]; q <= hi[k]; q++) {
            int v = ci[k] + q;
            double w = 0.0;
            if (v < 0)
              v += nf[k], w = -K.L[k];
            else if (v >= nf[k])
              v -= nf[k], w = K.L[k];
            off[k][q - lo[k]] = (size_t)v * fst[k];
            shf[k][q - lo[k]] = w;
          }
        for (int q2 = 0; q2 <= hi[2] - lo[2]; q2++)
          for (int q1 = 0; q1 <= hi[1] - lo[1]; q1++)
            for (int q0 = 0; q0 <= hi[0] - lo[0]; q0++) {
              const size_t c2 = off[0][q0] + off[1][q1] + off[2][q2];
              const double sh[3] = {shf[0][q0], shf[1][q1], shf[2][q2]};
              if (lprobe_cell(e, &K, &P, sh, fs[c2], fs[c2 + 1], out))
                return sbi_error(SB_ENOMEM, who, "out of "
                                 "memory (%zu candidate pairs)", out->n);
            }
        continue;
      }
      for (int q2 = lo[2]; q2 <= hi[2]; q2++)
        for (int q1 = lo[1]; q1 <= hi[1]; q1++)
          for (int q0 = lo[0]; q0 <= hi[0]; q0++) {
            /* a wide window (large extents, or few cells) may meet a
             * cell through two images: each member's nearest image */
            const int q[3] = {q0, q1, q2};
            size_t c2 = 0;
            for (int k = 0; k < dim; k++) {  /* |q| < nf: one wrap */
              int v = ci[k] + q[k];
              v = v < 0 ? v + nf[k] : (v >= nf[k] ? v - nf[k] : v);
              c2 += (size_t)v * fst[k];
            }
            if (lprobe_wide(e, &K, &P, L0, L1, L2, fs[c2], fs[c2 + 1], out))
              return sbi_error(SB_ENOMEM, who, "out of "
                               "memory (%zu candidate pairs)", out->n);
          }
    }
  }
  return emit_in_cell_order(e, 1, list, who);
}

/* Where the cut-off is well below the density's cell edge (dt << tau_p),
 * cells() returns few candidates and its scan is cheaper than building
 * the midpoint grid; as the cut-off grows, its face zones cover most of
 * each cell and most of its candidates fail the chord test.  V12's
 * first-hit runs at Kn_D = 0.5 (the same run either way), CPU time with
 * the stencil query / the cells: cut/edge ~0.2 (dt = 0.3 tau_p)
 * 1.02-1.06, ~0.3 (0.5 tau_p) 0.88-0.93, 0.42 (tau_p) 0.72-0.74: the grid
 * from SBI_LSEARCH_CUT on (it was 0.6 with the walk alone, which cost
 * 1.09-1.13 at tau_p). */
#define SBI_LSEARCH_CUT 0.25
static int lsearch_pays(const sb_engine *e, double cut)
{
  double vol = 1.0;
  for (int k = 0; k < e->par.dim; k++)
    vol *= e->par.L[k];
  return cut > SBI_LSEARCH_CUT * sbi_cell_edge_min(vol, e->n, e->par.dim);
}

/* 1 if x moved more than lim (minimum image) from where the list saw it
 * (xb). */
static inline unsigned char moved_beyond(const double *x, const double *xb,
                                         const double *L, int dim,
                                         double lim)
{
  double d2 = 0.0;
  for (int k = 0; k < dim; k++) {
    double d = sbi_minimg(x[k] - xb[k], L[k]);
    d2 += d * d;
  }
  return d2 > lim * lim;
}

/* Does the Verlet list still cover this step (D = max|disp|)?  A particle
 * that moved more than skin/2 - D from where the list saw it (a
 * reinsertion, a fast one) becomes a floater: its pairs are searched
 * afresh at every step (float_pairs) until the next build, which comes
 * when there are more than SBI_VERLET_FLOATERS of them, or when the
 * floater searches since the build outnumber the particles. */
static int list_holds(sb_engine *e, const double *x0, double D, double reach)
{
  sbi_verlet *v = &e->vl;
  const int dim = e->par.dim;
  float_clear(v);
  if (!v->valid || v->n != e->n || reach > v->reach || e->rmax != v->rmax)
    return 0;
  for (int k = 0; k < dim; k++)
    if (v->L[k] != e->par.L[k])
      return 0;
  const double lim = 0.5 * v->skin - D;
  if (!(lim > 0.0))
    return 0;
  const size_t n = e->n, maxf = SBI_VERLET_FLOATERS(n);
  const double *xb = v->xb, *L = e->par.L, *rb = v->rb, *r = e->radius;
  const uint64_t *idb = v->idb, *id = e->id;
  unsigned char *fl = v->isfloat;
  size_t nf = 0;
  int other = 0;
  const int nt = n >= 4096 ? sbi_engine_threads(&e->par) : 1;
  /* the same particles (ids and radii bit for bit: nothing added,
   * removed, merged or reordered)?  Mark the floaters (any thread order:
   * each flag is its own), then collect them in index order */
  if (nt > 1) {
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 4096) num_threads(nt) \
    reduction(+ : nf) reduction(| : other)
#endif
    for (size_t i = 0; i < n; i++) {
      other |= idb[i] != id[i] || memcmp(&rb[i], &r[i], sizeof r[i]) != 0;
      nf += fl[i] = moved_beyond(&x0[3 * i], &xb[3 * i], L, dim, lim);
    }
  } else {  /* no parallel region: entering one costs ~0.3 us */
    for (size_t i = 0; i < n; i++) {
      other |= idb[i] != id[i] || memcmp(&rb[i], &r[i], sizeof r[i]) != 0;
      nf += fl[i] = moved_beyond(&x0[3 * i], &xb[3 * i], L, dim, lim);
    }
  }
  if (other || nf > maxf || v->fsum + nf > n) {
    memset(fl, 0, n);
    return 0;
  }
  v->fsum += nf;
  for (size_t i = 0; nf && i < n; i++)
    if (fl[i]) {
      v->floats[v->nfloat++] = i;
      nf--;
    }
  return 1;
}

/* The candidate pairs of the floaters: with every listed particle in the
 * 27 cells of the build around the floater's start (a listed particle is
 * within skin/2 - D of where it was binned, and 2 (r_max + D) + reach +
 * skin/2 - D <= the cell edge), and with each other. */
static int float_pairs(sb_engine *e, const double *x0, double reach,
                       sbi_pairbuf *pb)
{
  const sbi_verlet *v = &e->vl;
  const sbi_grid *g = &e->grid;
  const int dim = e->par.dim;
  const int m1[3] = {1, 1, 1};
  for (size_t q = 0; q < v->nfloat; q++) {
    const size_t f = v->floats[q];
    double cw[3];
    int ca[3], lo[3], hi[3];
    cell_block(e, &x0[3 * f], m1, cw, ca, lo, hi);
    for (int q2 = lo[2]; q2 <= hi[2]; q2++)
      for (int q1 = lo[1]; q1 <= hi[1]; q1++)
        for (int q0 = lo[0]; q0 <= hi[0]; q0++) {
          const int o[3] = {q0, q1, q2};
          const size_t c2 = cell_at(g, dim, ca, o);
          for (size_t b = e->cell_start[c2]; b < e->cell_start[c2 + 1];
               b++) {
            const size_t k = e->cell_list[b];
            if (!v->isfloat[k] && near(e, x0, f, k, reach) &&
                pb_push(pb, f, k))
              return -1;
          }
        }
    for (size_t r = q + 1; r < v->nfloat; r++)
      if (near(e, x0, f, v->floats[r], reach) &&
          pb_push(pb, f, v->floats[r]))
        return -1;
  }
  return 0;
}

/* Rebuild the list around x0: pairs within r_i + r_j + reach + skin.
 * SB_SUCCESS with v->valid = 0 when a list does not pay (displacements
 * above skin / SBI_VERLET_STEPS) or does not fit the box. */
static int list_build(sb_engine *e, const double *x0, double D, double reach,
                      const char *who)
{
  sbi_verlet *v = &e->vl;
  const int dim = e->par.dim;
  v->valid = 0;
  const double skin = SBI_VERLET_SKIN * e->rmax,
               cut = 2.0 * e->rmax + reach + skin;
  if (!(D <= skin / SBI_VERLET_STEPS))
    return SB_SUCCESS;
  for (int k = 0; k < dim; k++)
    if (!(cut < 0.5 * e->par.L[k]))
      return SB_SUCCESS;
  int st = cells(e, x0, cut, reach + skin, 1, who);
  if (st)
    return st;
  if (e->npairs > v->cappairs) {
    size_t *p = realloc(v->pairs, 2 * e->npairs * sizeof *p);
    if (!p)
      return sbi_error(SB_ENOMEM, who, "out of memory "
                       "(%zu listed pairs)", e->npairs);
    v->pairs = p;
    v->cappairs = e->npairs;
  }
  if (e->npairs)  /* (both lists may still be NULL) */
    memcpy(v->pairs, e->pairs, 2 * e->npairs * sizeof *v->pairs);
  v->npairs = e->npairs;
  e->npairs = 0;
  memcpy(v->xb, x0, 3 * e->n * sizeof *x0);
  memcpy(v->rb, e->radius, e->n * sizeof *e->radius);
  memcpy(v->idb, e->id, e->n * sizeof *e->id);
  v->n = e->n;
  v->skin = skin;
  v->reach = reach;
  v->rmax = e->rmax;
  for (int k = 0; k < 3; k++)
    v->L[k] = e->par.L[k];
  v->valid = 1;
  v->fsum = 0;
  v->builds++;
  return SB_SUCCESS;
}

/* Cells through a Verlet list: the listed pairs of listed particles that
 * meet criterion (*) now, and the floaters' pairs — exactly the pairs
 * cells() would return, in another order (the detectors that use it
 * order their events by (s, i, j)).  Between rebuilds the cells of the
 * last build serve re-detection: their edge is >= 2 r_max + reach +
 * skin, and a listed particle is within skin/2 - max|disp| of where it
 * was binned, so the 27 cells around a point still hold every listed
 * start position within 2 (r_max + max|disp|) + reach of it; the
 * floaters are checked one by one (sbi_engine_partners). */
static int listed(sb_engine *e, const double *x0, double cut, double D,
                  double reach, const char *who)
{
  sbi_verlet *v = &e->vl;
  if (list_holds(e, x0, D, reach)) {
    v->uses++;
    v->floated += v->nfloat > 0;
  }
  else {
    int st = list_build(e, x0, D, reach, who);
    if (st)
      return st;
    if (!v->valid)
      return cells(e, x0, cut, reach, 0, who);
  }
  const unsigned char *fl = v->isfloat;
  const size_t np = v->npairs;
  const int nt = np >= 4096 ? sbi_engine_threads(&e->par) : 1;
  int bad = 0;
  e->npairs = 0;
  if (nt <= 1) {
    sbi_pairbuf pb = {e->pairs, 0, e->cappairs};
    for (size_t q = 0; q < np && !bad; q++) {
      const size_t i = v->pairs[2 * q], j = v->pairs[2 * q + 1];
      if (!fl[i] && !fl[j] && near(e, x0, i, j, reach))
        bad = pb_push(&pb, i, j);
    }
    e->pairs = pb.p;
    e->npairs = pb.n;
    e->cappairs = pb.cap;
  } else {
    /* thread t filters the t-th of nt contiguous ranges of the list into
     * its own buffer; joined in thread order they are the serial list */
    sbi_pairbuf *tb = thread_buffers(e, nt);
    if (!tb)
      return sbi_error(SB_ENOMEM, who, "out of memory");
    const sb_engine *ce = e;
#ifdef _OPENMP
#pragma omp parallel for schedule(static, 1) num_threads(nt) reduction(| : bad)
#endif
    for (int t = 0; t < nt; t++) {
      const size_t q0 = np * (size_t)t / (size_t)nt,
                   q1 = np * (size_t)(t + 1) / (size_t)nt;
      tb[t].n = 0;
      for (size_t q = q0; q < q1 && !bad; q++) {
        const size_t i = v->pairs[2 * q], j = v->pairs[2 * q + 1];
        if (!fl[i] && !fl[j] && near(ce, x0, i, j, reach))
          bad |= pb_push(&tb[t], i, j);
      }
    }
    if (!bad)
      bad = join_buffers(e, tb, nt);
  }
  if (!bad) {
    sbi_pairbuf pb = {e->pairs, e->npairs, e->cappairs};
    bad = float_pairs(e, x0, reach, &pb);
    e->pairs = pb.p;
    e->npairs = pb.n;
    e->cappairs = pb.cap;
  }
  if (bad)
    return sbi_error(SB_ENOMEM, who, "out of memory "
                     "(candidate pairs)");
  e->grid.valid = 1;  /* the cells of the build */
  e->grid.cut = cut;
  e->grid.reach = reach;
  return SB_SUCCESS;
}

/* Keep the pair of slots sa, sb (any order; cc: each slot's cell
 * coordinates) if scan_cell() would report it: push it with its rank in
 * scan_cell's loop (cells_sees_at).  0, or -1 out of memory. */
static int keep_if_seen(const cell_scan *K, const int *cc, size_t sa,
                        size_t sb, sbi_lpairbuf *out)
{
  const size_t s0 = sa < sb ? sa : sb, s1 = sa < sb ? sb : sa;
  unsigned g;
  if (!cells_sees_at(K, s0, s1, &cc[3 * s0], &cc[3 * s1], &g))
    return 0;
  return lpair_push(out, s0, s1, g);
}

/* The Verlet list in the cells' order, for the detectors whose draws
 * follow the candidate order (langevin, bridges, custom ones): the
 * candidates of the listed path (listed pairs of listed particles, and
 * each floater with every particle of the 27 cells around it), kept when
 * scan_cell() would report them and sorted as it does (cells_sees and
 * emit_in_cell_order, as lsearch): exactly cells()' list, pair for pair
 * and in order, so the run is the same bit for bit with the list on or
 * off.  The cells of this step (this step's cut) are sorted as cells()
 * sorts them and serve the ranks and re-detection, as with cells(); the
 * floaters are then forgotten (re-detection finds them in those cells).
 * Without a list that holds or pays: *used = 0, nothing done. */
static int listed_ordered(sb_engine *e, const double *x0, double cut,
                          double D, double reach, int *used, const char *who)
{
  sbi_verlet *v = &e->vl;
  *used = 0;
  if (list_holds(e, x0, D, reach)) {
    v->uses++;
    v->floated += v->nfloat > 0;
  } else {
    int st = list_build(e, x0, D, reach, who);
    if (st || !v->valid)
      return st;
  }
  *used = 1;
  const size_t n = e->n;
  if (lsearch_grow(e, n))
    return sbi_error(SB_ENOMEM, who, "out of memory");
  cell_scan K;
  int st = cell_sort(e, x0, cut, reach, 0, 1, &K, who);
  if (st)
    return st;
  size_t *slot = e->lfl;  /* particle -> its slot in cell order */
  for (size_t a = 0; a < n; a++)
    slot[K.list[a]] = a;
  int *cc = e->lcc;
  slot_cells(&K, cc);
  const unsigned char *fl = v->isfloat;
  if (lparts(e, 1))
    return sbi_error(SB_ENOMEM, who, "out of memory");
  sbi_lpairbuf *out = &e->lpt[0].pr;
  out->n = 0;
  int bad = 0;
  for (size_t q = 0; q < v->npairs && !bad; q++) {
    const size_t i = v->pairs[2 * q], j = v->pairs[2 * q + 1];
    if (!fl[i] && !fl[j])
      bad = keep_if_seen(&K, cc, slot[i], slot[j], out);
  }
  /* a floater's partners: in its own or a neighbouring cell (scan_cell
   * looks no further), each neighbouring cell once; two floaters from
   * the lower index */
  for (size_t q = 0; q < v->nfloat && !bad; q++) {
    const size_t f = v->floats[q], sf = slot[f];
    const int *ca = &cc[3 * sf];
    int lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
    for (int k = 0; k < K.dim; k++) {
      lo[k] = K.nc[k] >= 3 ? -1 : 0;
      hi[k] = K.nc[k] >= 2 ? 1 : 0;
    }
    for (int q2 = lo[2]; q2 <= hi[2] && !bad; q2++)
      for (int q1 = lo[1]; q1 <= hi[1] && !bad; q1++)
        for (int q0 = lo[0]; q0 <= hi[0] && !bad; q0++) {
          const int o[3] = {q0, q1, q2};
          size_t c2 = 0;
          for (int k = 0; k < K.dim; k++) {
            int w = ca[k] + o[k];
            w = w < 0 ? w + K.nc[k] : (w >= K.nc[k] ? w - K.nc[k] : w);
            c2 += (size_t)w * K.stride[k];
          }
          for (size_t b = K.start[c2]; b < K.start[c2 + 1] && !bad; b++) {
            const size_t k = K.list[b];
            if (k != f && !(fl[k] && k < f))
              bad = keep_if_seen(&K, cc, sf, b, out);
          }
        }
  }
  float_clear(v);
  if (bad)
    return sbi_error(SB_ENOMEM, who, "out of memory "
                     "(%zu candidate pairs)", out->n);
  return emit_in_cell_order(e, 1, K.list, who);
}

/* The search of sbi_engine_find_pairs; with_list: linked cells may go
 * through the Verlet list (a step's search with a deterministic
 * detector). */
static int find_pairs(sb_engine *e, sb_engine_neigh m, const double *x0,
                      const double *disp, double reach, int with_list,
                      int ordered, int lang, const char *who)
{
  e->npairs = 0;
  e->grid.valid = 0;
  if (e->n < 2)
    return SB_SUCCESS;
  double cut = 0.0, D = 0.0;
  int st = cutoff(e, disp, reach, &cut, &D, who);
  if (st)
    return st;
  e->grid.ext_max = 0.5 * (cut - reach);  /* r_max + max |disp| */
  switch (m) {
  case SB_NEIGH_CELLS: {
    int used = 0;
    if (with_list)
      st = listed(e, x0, cut, D, reach, who);
    else if (ordered)
      st = listed_ordered(e, x0, cut, D, reach, &used, who);
    if (!with_list && !st && !used)
      st = lang && lsearch_pays(e, cut)
               ? lsearch(e, x0, disp, cut, reach, who)
               : cells(e, x0, cut, reach, 0, who);
    break;
  }
  case SB_NEIGH_SWEEP:
    st = sbi_engine_sweep(e, x0, disp, reach, who);
    break;
  case SB_NEIGH_BRUTE:
    st = brute(e, x0, reach, who);
    break;
  default:
    return sbi_error(SB_EINVAL, who, "unknown method %d",
                     (int)m);
  }
  /* walls and Lees-Edwards images (engine_lees.c) */
  if (!st)
    st = sbi_engine_boundary_pairs(e, x0, disp, reach, cut, who);
  return st;
}

int sbi_engine_find_pairs(sb_engine *e, sb_engine_neigh m, const double *x0,
                          const double *disp, double reach, const char *who)
{
  return find_pairs(e, m, x0, disp, reach, 0, 0, 0, who);
}

int sbi_engine_find_step_pairs(sb_engine *e, double reach)
{
  /* the list's pairs come in another order than the cells': only for the
   * detectors whose result does not depend on it, and only in a fully
   * periodic box (walls, open faces and Lees-Edwards images add pairs of
   * their own each step) */
  const int periodic_list = !e->walled && !e->lees && !e->ninflow &&
                            !e->par.verlet_off;
  const int with_list = (e->par.detect == SB_DETECT_BALLISTIC ||
                         e->par.detect == SB_DETECT_OVERLAP) &&
                        !e->walled && !e->lees && !e->par.verlet_off;
  /* the other detectors may draw in candidate order: the list in the
   * cells' order (listed_ordered) */
  const int ordered = !with_list && periodic_list;
  if (!with_list && !ordered)
    e->vl.valid = 0;
  /* the Langevin search: only where the detector's chord test drops
   * every pair it leaves out (fully periodic box, noise on every
   * species, this step's reach) */
  const int lang = (e->par.detect == SB_DETECT_LANGEVIN ||
                    (e->par.detect == SB_DETECT_CUSTOM && e->detect_chord)) &&
                   !e->par.lsearch_off && !e->walled && !e->lees &&
                   !e->ninflow && sbi_engine_langevin_chord_gate(e, reach);
  if (e->n == 1) {
    /* no pairs to search, but the displacement is checked as for more
     * particles: a non-finite one or one beyond half the box is refused,
     * not wrapped into the box */
    double cut, D;
    int st = cutoff(e, e->disp, reach, &cut, &D, "sb_engine_step");
    if (st)
      return st;
  }
  return find_pairs(e, e->par.neigh, e->x0, e->disp, reach, with_list,
                    ordered, lang, "sb_engine_step");
}

int sb_engine_neighbours(sb_engine *e, sb_engine_neigh m, const double *disp,
                         double reach, size_t *npairs, const size_t **pairs)
{
  if (!e || !npairs || !pairs || (unsigned)m > SB_NEIGH_BRUTE ||
      !(reach >= 0.0) || !isfinite(reach))
    return sbi_error(SB_EINVAL, __func__, "bad argument");
  int st = sbi_engine_find_pairs(e, m, e->x, disp, reach, __func__);
  *npairs = st ? 0 : e->npairs;
  *pairs = e->pairs;
  return st;
}

int sb_engine_pair_can_meet(const sb_engine *e, const double *disp,
                            double reach, size_t i, size_t j)
{
  if (!e)
    return -sbi_error(SB_EINVAL, __func__, "engine is NULL");
  if (i >= e->n || j >= e->n || i == j)
    return -sbi_error(SB_EINVAL, __func__, "pair (%zu, %zu): need two "
                      "distinct particles below %zu", i, j, e->n);
  if (!(reach >= 0.0) || !isfinite(reach))
    return -sbi_error(SB_EINVAL, __func__, "reach = %g: must be finite "
                      ">= 0", reach);
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

/* Partners of particle a for re-detection, whose new path piece starts
 * at step fraction t and stays within ext_a (its radius included) of the
 * point c (same frame as x0): every k != a whose path can come within
 * reach of it.  Particles that kept a piece near their start (within the
 * r + |disp| the search was built for, e->dn updated) are found from the
 * cells of this step's search around c when they cover ext_a (else by a
 * scan of all); the few whose piece left that region (reinsertions, long
 * bounces) are in e->far and are checked against their current piece.
 * With Lees-Edwards k is taken in its image nearest to c (shifted by
 * delta(t) across the sliding boundary), and the bound widens by the
 * image's extra flight |G| L_y dt (1 - t) over the rest of the step; the
 * partners across the boundary come from the cells around c's image in
 * the box (c - n (delta(t), L_y, 0)), scanned as wide as that bound.
 * Calls fn(e, a, k, ctx) for each candidate once; stops on a non-zero
 * return. */
static double dist2_min(const sb_engine *e, const double *p, const double *q)
{
  double d2 = 0.0;
  for (int c = 0; c < e->par.dim; c++) {
    double d = sbi_minimg(p[c] - q[c], e->par.L[c]);
    d2 += d * d;
  }
  return d2;
}

/* Squared distance from p (at step fraction t) to the image of q nearest
 * to it; *n its Lees-Edwards image index (0 without). */
static double pdist2(const sb_engine *e, const double *p, const double *q,
                     double t, int *n)
{
  if (e->lees)
    return sbi_engine_lees_dist2(e, p, q, t, n);
  *n = 0;
  return dist2_min(e, p, q);
}

typedef struct {
  size_t a;
  const double *c;  /* a's piece start (frame of x0_a) */
  double ext_a, t, reach;
  double extra;     /* Lees-Edwards: |G| L_y dt (1 - t) */
  int (*fn)(sb_engine *, size_t, size_t, void *);
  void *ctx;
} partner_q;

/* The cells within m[k] cells of the one holding point pt (wrapped):
 * candidates k of image index `want` (Lees-Edwards; 0 otherwise). */
static int cell_pass(sb_engine *e, const partner_q *Q, const double *pt,
                     const int m[3], int want)
{
  const int dim = e->par.dim;
  const sbi_grid *g = &e->grid;
  const double *x0 = e->x0;
  double cw[3];
  int ca[3], lo[3], hi[3];
  cell_block(e, pt, m, cw, ca, lo, hi);
  for (int q2 = lo[2]; q2 <= hi[2]; q2++)
    for (int q1 = lo[1]; q1 <= hi[1]; q1++)
      for (int q0 = lo[0]; q0 <= hi[0]; q0++) {
        const int q[3] = {q0, q1, q2};
        const size_t c2 = cell_at(g, dim, ca, q);
        for (size_t b = e->cell_start[c2]; b < e->cell_start[c2 + 1]; b++) {
          size_t k = e->cell_list[b];
          if (k == Q->a || e->isfar[k] || e->vl.isfloat[k])
            continue;  /* far, floaters: checked one by one */
          double lim = Q->ext_a + e->radius[k] + e->dn[k] + Q->reach;
          double d2;
          if (e->lees) {
            int n;
            d2 = sbi_engine_lees_dist2(e, Q->c, &x0[3 * k], Q->t, &n);
            if (n != want)
              continue;  /* the other pass has it */
            if (n)
              lim += Q->extra;
          } else
            d2 = dist2_min(e, cw, &x0[3 * k]);
          int st;
          if (d2 <= lim * lim && (st = Q->fn(e, Q->a, k, Q->ctx)))
            return st;
        }
      }
  return SB_SUCCESS;
}

int sbi_engine_partners(sb_engine *e, size_t a, const double c[3],
                        double ext_a, double t,
                        int (*fn)(sb_engine *, size_t, size_t, void *),
                        void *ctx)
{
  const int dim = e->par.dim;
  const double *x0 = e->x0;
  const double reach = e->grid.valid ? e->grid.reach : e->detect_reach;
  const sbi_grid *g = &e->grid;
  const double extra =
      e->lees ? fabs(e->fluid_p[0]) * e->par.L[1] * e->par.dt * (1.0 - t)
              : 0.0;
  int st, n;
  /* the far list first: their pieces, not their starts */
  for (size_t q = 0; q < e->nfar; q++) {
    size_t k = e->far[q];
    if (k == a)
      continue;
    double len2 = 0.0;
    for (int d = 0; d < dim; d++)
      len2 += e->sub_v[3 * k + d] * e->sub_v[3 * k + d];
    double ext_k = e->radius[k] + sqrt(len2) * (1.0 - e->sub_t[k]);
    double d2 = pdist2(e, c, &e->sub_p[3 * k], t, &n);
    double lim = ext_a + ext_k + reach + (n ? extra : 0.0);
    if (d2 <= lim * lim && (st = fn(e, a, k, ctx)))
      return st;
  }
  if (g->valid && ext_a <= g->ext_max) {
    /* the floaters of a Verlet list: not where the cells have them */
    for (size_t q = 0; q < e->vl.nfloat; q++) {
      size_t k = e->vl.floats[q];
      if (k == a || e->isfar[k])
        continue;
      double d2 = pdist2(e, c, &x0[3 * k], t, &n);
      double lim = ext_a + e->radius[k] + e->dn[k] + reach +
                   (n ? extra : 0.0);
      if (d2 <= lim * lim && (st = fn(e, a, k, ctx)))
        return st;
    }
    const partner_q Q = {a, c, ext_a, t, reach, extra, fn, ctx};
    const int m1[3] = {1, 1, 1};
    st = cell_pass(e, &Q, c, m1, 0);
    if (st || !e->lees)
      return st;
    /* across the sliding boundary: around c's image in the box, as wide
     * as the largest bound (non-far k have r_k + dn_k <= ext_max) */
    const double Ly = e->par.L[1];
    const int nc = c[1] > 0.5 * Ly ? 1 : -1;
    const double lmax = ext_a + g->ext_max + reach + extra;
    if (nc > 0 ? c[1] < Ly - lmax : c[1] > lmax)
      return SB_SUCCESS;  /* too far from the face */
    double ci[3] = {c[0] - nc * sbi_lees_delta(e, t), c[1] - nc * Ly, c[2]};
    int m[3] = {0, 0, 0};
    for (int k = 0; k < dim; k++)
      m[k] = (int)ceil(lmax * g->inv[k]);
    return cell_pass(e, &Q, ci, m, nc);
  }
  for (size_t k = 0; k < e->n; k++) {
    if (k == a || e->isfar[k])
      continue;
    double d2 = pdist2(e, c, &x0[3 * k], t, &n);
    double lim = ext_a + e->radius[k] + e->dn[k] + reach + (n ? extra : 0.0);
    if (d2 <= lim * lim && (st = fn(e, a, k, ctx)))
      return st;
  }
  return SB_SUCCESS;
}
