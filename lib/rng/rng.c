/* rng.c — counter-based streams on Philox4x32-10 (smolbridge/rng.h,
 * docs/rng.md): uniforms, and standard normals by the ziggurat method of
 * Marsaglia & Tsang (2000), J. Stat. Softw. 5(8). */
#include <math.h>

#include <smolbridge/common.h>
#include <smolbridge/rng.h>

#include "common/internal.h"
#include "rng/rng_internal.h"

void sb_philox4x32_10(const uint32_t ctr[4], const uint32_t key[2],
                      uint32_t out[4])
{
  sbi_philox_block(ctr, key, out);
}

static int check_key(const char *fn, uint64_t id, uint64_t step)
{
  if (id > SB_STREAM_MAX_ID)
    return sbi_error(SB_EDOM, fn, "id = %llu exceeds SB_STREAM_MAX_ID = "
                     "2^47 - 1", (unsigned long long)id);
  if (step > SB_STREAM_MAX_STEP)
    return sbi_error(SB_EDOM, fn, "step = %llu exceeds SB_STREAM_MAX_STEP "
                     "= 2^48 - 1", (unsigned long long)step);
  return SB_SUCCESS;
}

int sb_stream_init(sb_stream *s, uint64_t seed, uint64_t id, uint64_t step)
{
  if (!s)
    return sbi_error(SB_EINVAL, __func__, "s is NULL");
  int st = check_key(__func__, id, step);
  sbi_stream_set(s, seed, st ? 0 : id, st ? 0 : step);
  return st;
}

/* The single-draw entry points check s (one predictable branch in a
 * non-inline call); the inline word source sbi_stream_u32 and the loops of
 * the _fill functions do not (checked once per call). */
uint32_t sb_stream_u32(sb_stream *s)
{
  if (!s) {
    sbi_error(SB_EINVAL, __func__, "s is NULL");
    return 0;
  }
  return sbi_stream_u32(s);
}

/* Word sources.  The ziggurat below is written once for a source type S
 * with S_next(S *) giving the next 32-bit word: the caller's sb_stream,
 * or (keyed batches) a particle's first blocks computed in advance for
 * many particles at once, then its sb_stream from the following block. */
typedef struct {
  const uint32_t *pre;  /* words computed in advance */
  uint32_t npre, ipre;  /* how many, next one */
  sb_stream s;          /* continues at block npre/4 */
} pre_src;

static inline uint32_t stream_next(sb_stream *s) { return sbi_stream_u32(s); }
static inline uint32_t pre_next(pre_src *p)
{
  return p->ipre < p->npre ? p->pre[p->ipre++] : sbi_stream_u32(&p->s);
}

/* +1 or -1 from bit 7 of a word, without a branch (a coin flip is a
 * mispredicted branch half of the time) */
static inline double sign_of(uint32_t w)
{
  return 1.0 - (double)((w >> 6) & 2u);
}

/* (2k + 1) 2^-53, k = the top 52 of 64 bits: exact in double, in (0, 1) */
#define SBI_DEF_UNIFORM(NAME, S, NEXT)                                       \
  static inline double NAME(S *src)                                          \
  {                                                                          \
    uint64_t hi = NEXT(src), lo = NEXT(src);                                 \
    uint64_t k = ((hi << 32) | lo) >> 12;                                    \
    return ((double)k + 0.5) * 0x1p-52;                                      \
  }
SBI_DEF_UNIFORM(uniform, sb_stream, stream_next)
SBI_DEF_UNIFORM(pre_uniform, pre_src, pre_next)

double sb_stream_uniform(sb_stream *s)
{
  if (!s) {
    sbi_error(SB_EINVAL, __func__, "s is NULL");
    return NAN;
  }
  return uniform(s);
}

/* The ziggurat (Marsaglia & Tsang 2000, §2) on one 32-bit word: layer i
 * (bits 0-6), sign (bit 7), j (bits 8-31), x = j W[i], accepted at once
 * when j < K[i] (under the next layer).  Otherwise: the base layer's tail
 * beyond r (Marsaglia 1964: x = -log(U1)/r, accept if -2 log(U2) > x^2),
 * or the wedge test y < f(x) with y uniform between the layer's heights;
 * a rejected wedge point starts again with a new word. */
#define SBI_DEF_GAUSSIAN(NAME, S, NEXT, UNIF)                                \
  static double NAME##_slow(S *src, uint32_t i, double x)                    \
  {                                                                          \
    if (i == 0) {                                                            \
      const double r = sbi_zig_r;                                            \
      double e, y;                                                           \
      do {                                                                   \
        e = -log(UNIF(src)) / r;                                             \
        y = -log(UNIF(src));                                                 \
      } while (2.0 * y <= e * e);                                            \
      return r + e;                                                          \
    }                                                                        \
    double y = sbi_zig_f[i] + UNIF(src) * (sbi_zig_f[i + 1] - sbi_zig_f[i]); \
    return y < exp(-0.5 * x * x) ? x : -1.0;                                 \
  }                                                                          \
  static inline double NAME(S *src)                                          \
  {                                                                          \
    for (;;) {                                                               \
      uint32_t w = NEXT(src);                                                \
      uint32_t i = w & 0x7fu, j = w >> 8;                                    \
      double x = (double)j * sbi_zig_w[i];                                   \
      if (j >= sbi_zig_k[i]) {                                               \
        x = NAME##_slow(src, i, x);                                          \
        if (x < 0.0)                                                         \
          continue;                                                          \
      }                                                                      \
      return x * sign_of(w);                                                 \
    }                                                                        \
  }
SBI_DEF_GAUSSIAN(gaussian, sb_stream, stream_next, uniform)
SBI_DEF_GAUSSIAN(pre_gaussian, pre_src, pre_next, pre_uniform)

double sb_stream_gaussian(sb_stream *s)
{
  if (!s) {
    sbi_error(SB_EINVAL, __func__, "s is NULL");
    return NAN;
  }
  return gaussian(s);
}

/* Philox4x32-10 on LANES counters at once, structure of arrays, the round
 * loop outside: the lanes are independent, so their multiplications
 * overlap (one block alone is a chain of 10 dependent rounds).  Round and
 * key schedule of Salmon et al. (2011), §4.2: (x0, x1, x2, x3) ->
 * (hi(M1 x2) ^ x1 ^ k0, lo(M1 x2), hi(M0 x0) ^ x3 ^ k1, lo(M0 x0)), the
 * key bumped by the Weyl constants between rounds.  The test suite checks
 * it against Random123 (keyed batches equal single streams). */
#define LANES 64
static void philox_lanes(uint32_t *restrict x0, uint32_t *restrict x1,
                         uint32_t *restrict x2, uint32_t *restrict x3,
                         uint32_t k0, uint32_t k1)
{
  for (int r = 0; r < 10; r++) {
    for (int l = 0; l < LANES; l++) {
      uint64_t p0 = (uint64_t)UINT32_C(0xD2511F53) * x0[l];
      uint64_t p1 = (uint64_t)UINT32_C(0xCD9E8D57) * x2[l];
      uint32_t y0 = (uint32_t)(p1 >> 32) ^ x1[l] ^ k0;
      uint32_t y2 = (uint32_t)(p0 >> 32) ^ x3[l] ^ k1;
      x0[l] = y0;
      x1[l] = (uint32_t)p1;
      x2[l] = y2;
      x3[l] = (uint32_t)p0;
    }
    k0 += UINT32_C(0x9E3779B9);
    k1 += UINT32_C(0xBB67AE85);
  }
}

#if defined(__GNUC__) && defined(__x86_64__)
#include <immintrin.h>
/* The same rounds on 8 lanes per AVX2 register, 4 registers at once (a
 * round is a chain of dependent multiplications: several chains hide
 * their latency); chosen at run time where the processor has AVX2.
 * Integer arithmetic: the words are those of philox_lanes, bit for bit
 * (the suite compares keyed batches with single streams). */
__attribute__((target("avx2"))) static inline void
mulhilo8(__m256i a, __m256i m, __m256i *hi, __m256i *lo)
{
  const __m256i pe = _mm256_mul_epu32(a, m);  /* lanes 0, 2, 4, 6 */
  const __m256i po = _mm256_mul_epu32(_mm256_srli_epi64(a, 32), m);
  *lo = _mm256_blend_epi32(pe, _mm256_slli_epi64(po, 32), 0xAA);
  *hi = _mm256_blend_epi32(_mm256_srli_epi64(pe, 32), po, 0xAA);
}

__attribute__((target("avx2"))) static void
philox_lanes_avx2(uint32_t *restrict x0, uint32_t *restrict x1,
                  uint32_t *restrict x2, uint32_t *restrict x3, uint32_t k0,
                  uint32_t k1)
{
  enum { VW = 4 };
  const __m256i m0 = _mm256_set1_epi64x(0xD2511F53), m1 =
      _mm256_set1_epi64x(0xCD9E8D57);
  for (int l = 0; l < LANES; l += 8 * VW) {
    __m256i a0[VW], a1[VW], a2[VW], a3[VW];
    for (int v = 0; v < VW; v++) {
      a0[v] = _mm256_loadu_si256((const __m256i *)(x0 + l + 8 * v));
      a1[v] = _mm256_loadu_si256((const __m256i *)(x1 + l + 8 * v));
      a2[v] = _mm256_loadu_si256((const __m256i *)(x2 + l + 8 * v));
      a3[v] = _mm256_loadu_si256((const __m256i *)(x3 + l + 8 * v));
    }
    uint32_t q0 = k0, q1 = k1;
    for (int r = 0; r < 10; r++) {
      const __m256i c0 = _mm256_set1_epi32((int)q0),
                    c1 = _mm256_set1_epi32((int)q1);
      for (int v = 0; v < VW; v++) {
        __m256i h0, l0, h1, l1;
        mulhilo8(a0[v], m0, &h0, &l0);
        mulhilo8(a2[v], m1, &h1, &l1);
        a0[v] = _mm256_xor_si256(_mm256_xor_si256(h1, a1[v]), c0);
        a2[v] = _mm256_xor_si256(_mm256_xor_si256(h0, a3[v]), c1);
        a1[v] = l1;
        a3[v] = l0;
      }
      q0 += UINT32_C(0x9E3779B9);
      q1 += UINT32_C(0xBB67AE85);
    }
    for (int v = 0; v < VW; v++) {
      _mm256_storeu_si256((__m256i *)(x0 + l + 8 * v), a0[v]);
      _mm256_storeu_si256((__m256i *)(x1 + l + 8 * v), a1[v]);
      _mm256_storeu_si256((__m256i *)(x2 + l + 8 * v), a2[v]);
      _mm256_storeu_si256((__m256i *)(x3 + l + 8 * v), a3[v]);
    }
  }
}
#define SBI_HAVE_AVX2_PATH 1
#endif

/* philox_lanes, on AVX2 where the processor has it */
static void philox_batch(uint32_t *restrict x0, uint32_t *restrict x1,
                         uint32_t *restrict x2, uint32_t *restrict x3,
                         uint32_t k0, uint32_t k1)
{
#ifdef SBI_HAVE_AVX2_PATH
  if (__builtin_cpu_supports("avx2")) {
    philox_lanes_avx2(x0, x1, x2, x3, k0, k1);
    return;
  }
#endif
  philox_lanes(x0, x1, x2, x3, k0, k1);
}

int sb_stream_uniform_fill(sb_stream *s, size_t n, double *u)
{
  if (n > 0 && (!s || !u))
    return sbi_error(SB_EINVAL, __func__, "NULL argument");
  for (size_t k = 0; k < n; k++)
    u[k] = uniform(s);
  return SB_SUCCESS;
}

int sb_stream_gaussian_fill(sb_stream *s, size_t n, double *z)
{
  if (n > 0 && (!s || !z))
    return sbi_error(SB_EINVAL, __func__, "NULL argument");
  for (size_t k = 0; k < n; k++)
    z[k] = gaussian(s);
  return SB_SUCCESS;
}

int sb_stream_gaussian_keyed(uint64_t seed, uint64_t step, size_t n,
                             const uint64_t *ids, uint64_t id0, size_t m,
                             double *z)
{
  if (n == 0 || m == 0)
    return SB_SUCCESS;
  if (!z)
    return sbi_error(SB_EINVAL, __func__, "z is NULL");
  if (step > SB_STREAM_MAX_STEP)
    return check_key(__func__, 0, step);
  if (ids) {
    for (size_t j = 0; j < n; j++)
      if (ids[j] > SB_STREAM_MAX_ID)
        return sbi_error(SB_EDOM, __func__, "ids[%zu] = %llu exceeds "
                         "SB_STREAM_MAX_ID = 2^47 - 1", j,
                         (unsigned long long)ids[j]);
  } else if (id0 > SB_STREAM_MAX_ID || n - 1 > SB_STREAM_MAX_ID - id0)
    return sbi_error(SB_EDOM, __func__, "ids %llu + [0, %zu) exceed "
                     "SB_STREAM_MAX_ID = 2^47 - 1", (unsigned long long)id0,
                     n);
  /* the first nb blocks of every particle of a group, LANES blocks at a
   * time; the particle's later blocks (slow paths, m > 4 nb) from its
   * sb_stream */
  const uint32_t nb = m <= 4 ? 1 : 2;
  const uint32_t per = LANES / nb; /* particles per group */
  uint32_t x0[LANES], x1[LANES], x2[LANES], x3[LANES], words[4 * LANES];
  const uint32_t key0 = (uint32_t)seed, key1 = (uint32_t)(seed >> 32);
  for (size_t g = 0; g < n; g += per) {
    size_t np = n - g < per ? n - g : per;
    for (uint32_t l = 0; l < LANES; l++) {
      size_t j = g + (l / nb < np ? l / nb : 0);
      uint64_t id = ids ? ids[j] : id0 + j;
      x0[l] = l % nb;
      x1[l] = (uint32_t)step;
      x2[l] = (uint32_t)id;
      x3[l] = (uint32_t)((step >> 32) & 0xffffu) |
              (uint32_t)(((id >> 32) & 0x7fffu) << 16);
    }
    philox_batch(x0, x1, x2, x3, key0, key1);
    for (uint32_t l = 0; l < LANES; l++) {
      words[4 * l] = x0[l];
      words[4 * l + 1] = x1[l];
      words[4 * l + 2] = x2[l];
      words[4 * l + 3] = x3[l];
    }
    for (size_t q = 0; q < np; q++) {
      size_t j = g + q;
      const uint32_t *wp = words + 4 * nb * q, nw = 4 * nb;
      double *zj = z + j * m;
      /* fast path in registers while the draws stay under the next layer;
       * the first draw that does not (or runs out of computed words) and
       * the rest go through the general source, from that same word */
      uint32_t iw = 0;
      size_t k = 0;
      for (; k < m && iw < nw; k++) {
        uint32_t w = wp[iw], i = w & 0x7fu, jj = w >> 8;
        if (jj >= sbi_zig_k[i])
          break;
        iw++;
        zj[k] = (double)jj * sbi_zig_w[i] * sign_of(w);
      }
      if (k < m) {
        pre_src p;
        p.pre = wp;
        p.npre = nw;
        p.ipre = iw;
        sbi_stream_set(&p.s, seed, ids ? ids[j] : id0 + j, step);
        p.s.ctr[0] = nb;
        for (; k < m; k++)
          zj[k] = pre_gaussian(&p);
      }
    }
  }
  return SB_SUCCESS;
}
