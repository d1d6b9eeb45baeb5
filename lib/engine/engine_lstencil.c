/* engine_lstencil.c — the stencil query of the Langevin search's midpoint
 * grid (engine_neigh.c, lsearch).
 *
 * The grid holds the chord midpoints m_k and extents f_k of the
 * particles, cell by cell (x fastest).  A pair must be found when
 * |m_a - m_b| <= (f_a + f_b + rho)(1 + tol) + eabs.  When every cell edge
 * is at least the widest such bound (2 f_max + rho, with the margins) and
 * each axis has >= 3 cells, the two members of such a pair lie in the same
 * or in neighbouring cells, and the image through the neighbouring
 * cell's wrap is the nearest one (|m_a - m_b| <= h <= L/3 on each axis).
 * Each cell is then visited once: the members of the half of its
 * neighbouring cells that follow it (13 in 3-D, 4 in 2-D, 1 in 1-D) are
 * gathered into one block, shifted into the cell's frame, and every
 * member of the cell is tested against the block and against the later
 * members of its own cell.  Every pair is tested exactly once.  A call
 * visits a range of cells with a gather block of its own, so the ranges
 * of one grid may be queried on several threads at once (engine_neigh.c,
 * stencil_search).
 *
 * Why a block: at the densities of a first-hit run a cell holds ~2
 * particles, so a query that walks cell by cell spends its time on loop
 * exits, not on distance tests.  Away from the box's faces the half
 * stencil is five runs of consecutive cells (the next cell, the row
 * above, the three rows of the layer above), copied whole; the block is
 * tested in one loop per member, four members per AVX2 instruction where
 * the processor has it.  A hit is rare (~1 in 100 tests): the count comes
 * first, the pairs are then found by the scalar test, which does the same
 * operations (no FMA contraction: AVX2 without FMA), so both agree. */
#include <string.h>

#include "common/internal.h"
#include "engine_internal.h"

/* Grow the gather block to hold m members (and four sentinels). */
static int block_grow(sbi_lpart *blk, size_t m)
{
  m += 4;
  if (m <= blk->gcap)
    return 0;
  const size_t c = 2 * m + 64;
  double *x = realloc(blk->g, 4 * c * sizeof *x);
  if (!x)
    return -1;
  blk->g = x;
  blk->gcap = c;
  return 0;
}

/* How many of the G members of block g (x, y, z, f each) are within
 * Ba + f_b tol1 of ma; the members from G to the next multiple of 4 are
 * sentinels far away. */
static size_t count_near_scalar(const double *g, size_t G, const double *ma,
                                double Ba, double tol1)
{
  size_t hits = 0;
  for (size_t q = 0; q < G; q++) {
    const double *mb = &g[4 * q];
    const double d0 = ma[0] - mb[0], d1 = ma[1] - mb[1], d2 = ma[2] - mb[2],
                 B = Ba + mb[3] * tol1;
    hits += d0 * d0 + d1 * d1 + d2 * d2 <= B * B;
  }
  return hits;
}

#if defined(__GNUC__) && defined(__x86_64__)
#include <immintrin.h>
/* count_near_scalar, four members at a time (a 4x4 transpose of the
 * block's rows; the same operations in the same order). */
__attribute__((target("avx2"))) static size_t
count_near_avx2(const double *g, size_t G, const double *ma, double Ba,
                double tol1)
{
  const __m256d x = _mm256_set1_pd(ma[0]), y = _mm256_set1_pd(ma[1]),
                z = _mm256_set1_pd(ma[2]), ba = _mm256_set1_pd(Ba),
                t1 = _mm256_set1_pd(tol1);
  size_t hits = 0;
  for (size_t q = 0; q < G; q += 4) {
    const __m256d r0 = _mm256_loadu_pd(&g[4 * q]),
                  r1 = _mm256_loadu_pd(&g[4 * q + 4]),
                  r2 = _mm256_loadu_pd(&g[4 * q + 8]),
                  r3 = _mm256_loadu_pd(&g[4 * q + 12]);
    const __m256d a = _mm256_unpacklo_pd(r0, r1),   /* x0 x1 z0 z1 */
        b = _mm256_unpackhi_pd(r0, r1),             /* y0 y1 f0 f1 */
        c = _mm256_unpacklo_pd(r2, r3),             /* x2 x3 z2 z3 */
        d = _mm256_unpackhi_pd(r2, r3);             /* y2 y3 f2 f3 */
    const __m256d X = _mm256_permute2f128_pd(a, c, 0x20),
                  Z = _mm256_permute2f128_pd(a, c, 0x31),
                  Y = _mm256_permute2f128_pd(b, d, 0x20),
                  F = _mm256_permute2f128_pd(b, d, 0x31);
    const __m256d d0 = _mm256_sub_pd(x, X), d1 = _mm256_sub_pd(y, Y),
                  d2 = _mm256_sub_pd(z, Z);
    const __m256d s = _mm256_add_pd(
        _mm256_add_pd(_mm256_mul_pd(d0, d0), _mm256_mul_pd(d1, d1)),
        _mm256_mul_pd(d2, d2));
    const __m256d B = _mm256_add_pd(ba, _mm256_mul_pd(F, t1));
    const int m = _mm256_movemask_pd(
        _mm256_cmp_pd(s, _mm256_mul_pd(B, B), _CMP_LE_OQ));
    hits += (size_t)__builtin_popcount((unsigned)m);
  }
  return hits;
}
#define SBI_LSTENCIL_AVX2 1
#endif

/* A member of the block: its slot in the grid order (which run it came
 * from: runs t hold the grid's members r0[t]..r1[t]-1, at block offsets
 * off[t]). */
typedef struct {
  size_t r0[13], r1[13], off[14];
  int nr;
} runs;

static size_t run_member(const runs *R, size_t q)
{
  int t = 0;
  while (q >= R->off[t + 1])
    t++;
  return R->r0[t] + (q - R->off[t]);
}

int sbi_lsearch_stencil(const sb_engine *e, const sbi_mgrid *M, size_t c0,
                        size_t c1, sbi_lpart *blk, sbi_lpair_fn emit,
                        void *ctx)
{
  const int dim = M->dim;
  const int *nf = M->nf;
  const size_t *fst = M->fst, *fs = M->fs, *fl = M->fl;
  const double *fx = M->fx;
  const double tol1 = 1.0 + M->tol, reach = M->reach, eabs = M->eabs;
#ifdef SBI_LSTENCIL_AVX2
  const int avx2 = __builtin_cpu_supports("avx2") && e->lstencil_off != 2;
#endif
  /* the half stencil: the offsets after (0, 0, 0), z slowest */
  int so[13][3], ns = 0;
  for (int o2 = dim > 2 ? -1 : 0; o2 <= (dim > 2 ? 1 : 0); o2++)
    for (int o1 = dim > 1 ? -1 : 0; o1 <= (dim > 1 ? 1 : 0); o1++)
      for (int o0 = -1; o0 <= 1; o0++)
        if (o2 > 0 || (o2 == 0 && (o1 > 0 || (o1 == 0 && o0 > 0)))) {
          so[ns][0] = o0, so[ns][1] = o1, so[ns][2] = o2;
          ns++;
        }
  int ci[3] = {0, 0, 0};  /* the coordinates of cell c0 */
  for (int k = 0; k < dim; k++)
    ci[k] = (int)((c0 / fst[k]) % (size_t)nf[k]);
  for (size_t c = c0; c < c1; c++) {
    if (c > c0)
      for (int k = 0; k < 3 && ++ci[k] == nf[k]; k++)
        ci[k] = 0;
    const size_t p0 = fs[c], p1 = fs[c + 1];
    if (p0 == p1)
      continue;
    /* the runs of the block, and the image shift of each */
    runs R;
    double sh[13][3];
    const int inner = ci[0] >= 1 && ci[0] + 1 < nf[0] &&
                      (dim < 2 || (ci[1] >= 1 && ci[1] + 1 < nf[1])) &&
                      (dim < 3 || ci[2] + 1 < nf[2]);
    if (inner) {  /* consecutive cells, no image */
      R.r0[0] = fs[c + 1], R.r1[0] = fs[c + 2];
      R.nr = 1;
      if (dim > 1) {
        const size_t cy = c + fst[1];
        R.r0[1] = fs[cy - 1], R.r1[1] = fs[cy + 2];
        R.nr = 2;
      }
      if (dim > 2)
        for (int o1 = -1; o1 <= 1; o1++) {
          const size_t cz = c + fst[2] + fst[1] - (size_t)(1 - o1) * fst[1];
          R.r0[R.nr] = fs[cz - 1], R.r1[R.nr] = fs[cz + 2];
          R.nr++;
        }
    } else {  /* cell by cell, through the wraps */
      size_t off[3][3] = {{0}, {0}, {0}};
      double shf[3][3] = {{0}, {0}, {0}};
      for (int k = 0; k < dim; k++)
        for (int q = -1; q <= 1; q++) {
          int v = ci[k] + q;
          double w = 0.0;
          if (v < 0)
            v += nf[k], w = -M->L[k];
          else if (v >= nf[k])
            v -= nf[k], w = M->L[k];
          off[k][q + 1] = (size_t)v * fst[k];
          shf[k][q + 1] = w;
        }
      for (int t = 0; t < ns; t++) {
        const size_t c2 = off[0][so[t][0] + 1] + off[1][so[t][1] + 1] +
                          off[2][so[t][2] + 1];
        R.r0[t] = fs[c2], R.r1[t] = fs[c2 + 1];
        for (int k = 0; k < 3; k++)
          sh[t][k] = shf[k][so[t][k] + 1];
      }
      R.nr = ns;
    }
    size_t G = 0;
    for (int t = 0; t < R.nr; t++) {
      R.off[t] = G;
      G += R.r1[t] - R.r0[t];
    }
    R.off[R.nr] = G;
    if (block_grow(blk, G))
      return -1;
    double *g = blk->g;
    for (int t = 0; t < R.nr; t++) {
      double *b = &g[4 * R.off[t]];
      const size_t m = 4 * (R.r1[t] - R.r0[t]);
      memcpy(b, &fx[4 * R.r0[t]], m * sizeof *g);
      if (!inner && (sh[t][0] != 0.0 || sh[t][1] != 0.0 || sh[t][2] != 0.0))
        for (size_t q = 0; q < m; q += 4) {
          b[q] += sh[t][0];
          b[q + 1] += sh[t][1];
          b[q + 2] += sh[t][2];
        }
    }
    for (size_t q = G; q < G + 4; q++) {  /* sentinels: never near */
      g[4 * q] = g[4 * q + 1] = g[4 * q + 2] = 1e300;
      g[4 * q + 3] = 0.0;
    }
    for (size_t pa = p0; pa < p1; pa++) {
      const double *ma = &fx[4 * pa];
      const double Ba = (ma[3] + reach) * tol1 + eabs;
      /* the later members of the own cell */
      for (size_t pb = pa + 1; pb < p1; pb++) {
        const double *mb = &fx[4 * pb];
        const double d0 = ma[0] - mb[0], d1 = ma[1] - mb[1],
                     d2 = ma[2] - mb[2], B = Ba + mb[3] * tol1;
        if (d0 * d0 + d1 * d1 + d2 * d2 <= B * B &&
            emit(e, ctx, fl[pa], fl[pb]))
          return -1;
      }
      size_t hits;
#ifdef SBI_LSTENCIL_AVX2
      if (avx2)
        hits = count_near_avx2(g, G, ma, Ba, tol1);
      else
#endif
        hits = count_near_scalar(g, G, ma, Ba, tol1);
      for (size_t q = 0; hits && q < G; q++) {
        const double *mb = &g[4 * q];
        const double d0 = ma[0] - mb[0], d1 = ma[1] - mb[1],
                     d2 = ma[2] - mb[2], B = Ba + mb[3] * tol1;
        if (d0 * d0 + d1 * d1 + d2 * d2 <= B * B) {
          hits--;
          if (emit(e, ctx, fl[pa], fl[run_member(&R, q)]))
            return -1;
        }
      }
    }
  }
  return 0;
}
