/* pbe_fft.c — discrete Smoluchowski gain and loss for the separable test
 * kernels (constant K, additive K(v+v'), multiplicative K v v'), sizes
 * v_k = k v1.  The kernel is a sum of products K(v_i, v_j) =
 * K sum_r f_r(v_i) g_r(v_j), so
 *   loss  L_i = K sum_r f_r(v_i) <g_r, n>                      O(N),
 *   gain  G_s = 1/2 sum_{i0+j0=s} K(v_i0, v_j0) n_i0 n_j0     (s = i0 + j0)
 *             = (K/2) sum_r (f_r n * g_r n)_s                  a convolution,
 * evaluated either directly (O(N^2/2), no kernel matrix) or by a
 * zero-padded FFT linear convolution (O(N log N), GSL mixed-radix real FFT
 * with precomputed trigonometric tables).  Constant: (K/2) n*n;
 * multiplicative: (K/2) (vn)*(vn); additive (symmetric): K (vn)*n.
 *
 * Accuracy: the direct sums are sums of non-negative terms (relative
 * error ~ N eps in the worst case, typically sqrt(N) eps).  The FFT
 * convolution has an ABSOLUTE error ~ eps log2(nfft) max_s G_s: entries
 * much smaller than the largest (the far tail of the distribution) lose
 * their relative accuracy.  That is harmless when CVODE's absolute
 * tolerance is above ~1e-13 of the peak gain rate, and wrong for the
 * 1e-40 tolerances used to resolve n_50 ~ 1e-64 (then use the direct sum,
 * the default).  Measurements: docs/pbe.md.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_fft_halfcomplex.h>
#include <gsl/gsl_fft_real.h>

#include "common/internal.h"
#include "pbe_internal.h"

/* FFT tables live here rather than in pbe_internal.h (GSL types). */
typedef struct {
  gsl_fft_real_wavetable *rw;
  gsl_fft_halfcomplex_wavetable *hw;
  gsl_fft_real_workspace *ws;
} fft_tabs;

void sbi_pbe_sep_detect(sb_pbe *p)
{
  p->sep = 0;
  if (p->cfg.method != SB_PBE_DISCRETE || p->cfg.kernel != sb_kernel_spec_fn)
    return;
  const sb_kernel_spec *s = p->cfg.kparams;
  switch (s->type) {
  case SB_KERNEL_CONSTANT:
    p->sep = 1 + SB_PBE_CONSTANT;
    break;
  case SB_KERNEL_ADDITIVE:
    p->sep = 1 + SB_PBE_ADDITIVE;
    break;
  case SB_KERNEL_MULTIPLICATIVE:
    p->sep = 1 + SB_PBE_MULTIPLICATIVE;
    break;
  default:
    return;
  }
  p->sepK = s->K;
}

void sbi_pbe_fft_free(sb_pbe *p)
{
  fft_tabs *t = p->fft;
  if (t) {
    if (t->rw)
      gsl_fft_real_wavetable_free(t->rw);
    if (t->hw)
      gsl_fft_halfcomplex_wavetable_free(t->hw);
    if (t->ws)
      gsl_fft_real_workspace_free(t->ws);
    free(t);
  }
  p->fft = NULL;
}

int sbi_pbe_sep_setup(sb_pbe *p)
{
  if (!p->use_fft)
    return SB_SUCCESS;
  size_t m = 1;
  while (m < 2 * p->n - 1)
    m *= 2;
  p->nfft = m;
  p->fa = calloc(m, sizeof *p->fa);
  p->fb = calloc(m, sizeof *p->fb);
  fft_tabs *t = calloc(1, sizeof *t);
  p->fft = t;
  if (!p->fa || !p->fb || !t)
    return SB_ENOMEM;
  /* GSL allocators only fail on memory (n = 2^k > 0 is valid) */
  t->rw = gsl_fft_real_wavetable_alloc(m);
  t->hw = gsl_fft_halfcomplex_wavetable_alloc(m);
  t->ws = gsl_fft_real_workspace_alloc(m);
  if (!t->rw || !t->hw || !t->ws)
    return SB_ENOMEM;
  return SB_SUCCESS;
}

/* Multiply halfcomplex arrays a *= b (GSL mixed-radix layout: a[0] real,
 * then (re, im) pairs at 2k-1, 2k, and a[m-1] real for even m). */
static void hc_mul(double *a, const double *b, size_t m)
{
  a[0] *= b[0];
  for (size_t k = 1; 2 * k < m; k++) {
    double ar = a[2 * k - 1], ai = a[2 * k];
    double br = b[2 * k - 1], bi = b[2 * k];
    a[2 * k - 1] = ar * br - ai * bi;
    a[2 * k] = ar * bi + ai * br;
  }
  if (m % 2 == 0)
    a[m - 1] *= b[m - 1];
}

/* g[s] = c (a * b)_s, s = 0..2N-2, by zero-padded FFT (b == NULL: a*a). */
static void fft_conv(sb_pbe *p, const double *a, const double *b, double c,
                     double *g)
{
  fft_tabs *t = p->fft;
  size_t N = p->n, m = p->nfft;
  memcpy(p->fa, a, N * sizeof *a);
  memset(p->fa + N, 0, (m - N) * sizeof *a);
  /* GSL returns an error only for bad lengths (m is fixed and valid) */
  gsl_fft_real_transform(p->fa, 1, m, t->rw, t->ws);
  if (b) {
    memcpy(p->fb, b, N * sizeof *b);
    memset(p->fb + N, 0, (m - N) * sizeof *b);
    gsl_fft_real_transform(p->fb, 1, m, t->rw, t->ws);
    hc_mul(p->fa, p->fb, m);
  } else {
    hc_mul(p->fa, p->fa, m);
  }
  gsl_fft_halfcomplex_inverse(p->fa, 1, m, t->hw, t->ws);
  for (size_t s = 0; s + 1 < 2 * N; s++)
    g[s] = c * p->fa[s];
}

/* Direct symmetric self-convolution g[s] = c sum_{i+j=s} a_i a_j. */
static void direct_self(size_t N, const double *restrict a, double c,
                        double *restrict g)
{
  if (N == 0)
    return;
  memset(g, 0, (2 * N - 1) * sizeof *g);
  for (size_t i = 0; i < N; i++) {
    double ai = a[i], t = 2.0 * c * ai;
    double *restrict gi = g + i;
    gi[i] += c * ai * ai;
    for (size_t j = i + 1; j < N; j++)
      gi[j] += t * a[j];
  }
}

/* Direct additive-kernel gain g[s] = c sum_{i+j=s} v_i n_i n_j (i.e.
 * (c/2) sum (v_i + v_j) n_i n_j over ordered pairs), by unordered pairs. */
static void direct_add(size_t N, const double *restrict v,
                       const double *restrict n, double c, double *restrict g)
{
  if (N == 0)
    return;
  memset(g, 0, (2 * N - 1) * sizeof *g);
  for (size_t i = 0; i < N; i++) {
    double ni = c * n[i], vi = v[i];
    double *restrict gi = g + i;
    gi[i] += ni * vi * n[i];
    for (size_t j = i + 1; j < N; j++)
      gi[j] += ni * (vi + v[j]) * n[j];
  }
}

/* Overflow of a convolution gain c (a * b)_s beyond the grid, s >= N - 1
 * (total size s + 2 > N): number c sum_i a_i B(N-1-i) and volume
 * c v1 sum_i a_i [(i+1) B(N-1-i) + C(N-1-i)], with the suffix sums
 * B(m) = sum_{j>=m} b_j and C(m) = sum_{j>=m} (j+1) b_j.  O(N), sums of
 * non-negative terms: accurate even where the FFT values are noise (the
 * FFT gain would give the tail an absolute error ~ N^2 eps max G). */
/* FFT path only. */
static void overflow(sb_pbe *p, const double *a, const double *b, double c)
{
  size_t N = p->n;
  double *B = p->fa, *C = p->fb; /* scratch: the FFT buffers */
  double sb = 0.0, sc = 0.0, dn = 0.0, dm = 0.0;
  for (size_t m = N; m-- > 0;) {
    sb += b[m];
    sc += (double)(m + 1) * b[m];
    B[m] = sb;
    C[m] = sc;
  }
  for (size_t i = 0; i < N; i++) {
    size_t m = N - 1 - i;
    dn += a[i] * B[m];
    dm += a[i] * ((double)(i + 1) * B[m] + C[m]);
  }
  p->of_dn = c * dn;
  p->of_dm = c * p->cfg.v1 * dm;
}

void sbi_pbe_sep_gain_loss(sb_pbe *p, const double *n, double *g)
{
  size_t N = p->n;
  const double *v = p->v;
  double K = p->sepK, m0 = 0.0, m1 = 0.0;
  double *vn = p->src; /* scratch: the source is added after the gain */
  for (size_t i = 0; i < N; i++) {
    m0 += n[i];
    vn[i] = v[i] * n[i];
    m1 += vn[i];
  }
  switch (p->sep - 1) {
  case SB_PBE_CONSTANT:
    for (size_t i = 0; i < N; i++)
      p->work[i] = K * m0;
    if (!g)
      break;
    if (p->use_fft) {
      fft_conv(p, n, NULL, 0.5 * K, g);
      overflow(p, n, n, 0.5 * K);
    } else
      direct_self(N, n, 0.5 * K, g);
    break;
  case SB_PBE_ADDITIVE:
    for (size_t i = 0; i < N; i++)
      p->work[i] = K * (v[i] * m0 + m1);
    if (!g)
      break;
    if (p->use_fft) {
      fft_conv(p, vn, n, K, g);
      overflow(p, vn, n, K);
    } else
      direct_add(N, v, n, K, g);
    break;
  default: /* multiplicative */
    for (size_t i = 0; i < N; i++)
      p->work[i] = K * v[i] * m1;
    if (!g)
      break;
    if (p->use_fft) {
      fft_conv(p, vn, NULL, 0.5 * K, g);
      overflow(p, vn, vn, 0.5 * K);
    } else
      direct_self(N, vn, 0.5 * K, g);
    break;
  }
}
