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

uint32_t sb_stream_u32(sb_stream *s) { return sbi_stream_u32(s); }

/* (2k + 1) 2^-53, k = the top 52 of 64 bits: exact in double, in (0, 1) */
static inline double uniform(sb_stream *s)
{
  uint64_t hi = sbi_stream_u32(s), lo = sbi_stream_u32(s);
  uint64_t k = ((hi << 32) | lo) >> 12;
  return ((double)k + 0.5) * 0x1p-52;
}

double sb_stream_uniform(sb_stream *s) { return uniform(s); }

/* The slow path of the ziggurat for layer i and draw x = j W[i] that was
 * not under the next layer: the base layer's tail beyond r (Marsaglia
 * 1964: x = -log(U1)/r, accept if -2 log(U2) > x^2), or the wedge test
 * y < f(x) with y uniform between the layer's heights.  Returns |z| or a
 * negative value to start again with a new word. */
static double zig_slow(sb_stream *s, uint32_t i, double x)
{
  if (i == 0) {
    const double r = sbi_zig_r;
    double e, y;
    do {
      e = -log(uniform(s)) / r;
      y = -log(uniform(s));
    } while (2.0 * y <= e * e);
    return r + e;
  }
  double y = sbi_zig_f[i] + uniform(s) * (sbi_zig_f[i + 1] - sbi_zig_f[i]);
  return y < exp(-0.5 * x * x) ? x : -1.0;
}

/* one 32-bit word: layer i (bits 0-6), sign (bit 7), j (bits 8-31) */
static inline double gaussian(sb_stream *s)
{
  for (;;) {
    uint32_t w = sbi_stream_u32(s);
    uint32_t i = w & 0x7fu, j = w >> 8;
    double x = (double)j * sbi_zig_w[i];
    if (j >= sbi_zig_k[i]) {
      x = zig_slow(s, i, x);
      if (x < 0.0)
        continue;
    }
    return (w & 0x80u) ? -x : x;
  }
}

double sb_stream_gaussian(sb_stream *s) { return gaussian(s); }

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
  sb_stream s;
  for (size_t j = 0; j < n; j++) {
    sbi_stream_set(&s, seed, ids ? ids[j] : id0 + j, step);
    double *zj = z + j * m;
    for (size_t k = 0; k < m; k++)
      zj[k] = gaussian(&s);
  }
  return SB_SUCCESS;
}
