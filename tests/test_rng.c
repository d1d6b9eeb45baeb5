/* test_rng.c — counter-based streams (smolbridge/rng.h).
 *
 *  - Philox4x32-10 known answers: the three "philox4x32 10" lines of
 *    Random123's tests/kat_vectors (D. E. Shaw Research, Random123
 *    1.14; Salmon et al. 2011);
 *  - the counter layout of a stream, rebuilt here from the header's
 *    description, and the gsl_rng wrapper's words;
 *  - the ziggurat tables recomputed from r with GSL (erfc, the layer
 *    recurrence of Marsaglia & Tsang 2000, §2);
 *  - Monte Carlo checks with fixed seeds, each with its sample size and
 *    criterion: uniforms and normals by KS (n = 2e5, p >= 1e-3), moments
 *    (|z| <= 4.5, two-sided p ~ 7e-6 each), a 100-bin chi-square of 2e6
 *    normals (p >= 1e-3: sensitive to the wedges and the tail, which carry
 *    1.2% of the mass), the tail beyond r (binomial p >= 1e-3);
 *    independence across ids, steps and seeds and within a stream by
 *    correlation coefficients of 1e5 pairs (|r| sqrt(n) <= 4.5);
 *  - the same uniformity and normality checks through sb_rng_philox with
 *    GSL's own gsl_rng_uniform and gsl_ran_gaussian_ziggurat. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_cdf.h>
#include <gsl/gsl_math.h>
#include <gsl/gsl_randist.h>
#include <gsl/gsl_sf_erf.h>
#include <smolbridge/common.h>
#include <smolbridge/rng.h>
#include <smolbridge/stats.h>

#include "testutil.h"

/* the ziggurat tables are internal: declared here to check them */
extern const double sbi_zig_r, sbi_zig_v;
extern const double sbi_zig_w[128];
extern const uint32_t sbi_zig_k[128];
extern const double sbi_zig_f[129];

#define ZMAX 4.5 /* |z| bound of the moment and correlation checks */

START_TEST(test_kat)
{
  /* counter (4 words), key (2 words), expected (4 words) */
  static const uint32_t kat[3][10] = {
      {0, 0, 0, 0, 0, 0, 0x6627e8d5, 0xe169c58d, 0xbc57ac4c, 0x9b00dbd8},
      {0xffffffff, 0xffffffff, 0xffffffff, 0xffffffff, 0xffffffff,
       0xffffffff, 0x408f276d, 0x41c83b0e, 0xa20bc7c6, 0x6d5451fd},
      {0x243f6a88, 0x85a308d3, 0x13198a2e, 0x03707344, 0xa4093822,
       0x299f31d0, 0xd16cfe09, 0x94fdcceb, 0x5001e420, 0x24126ea1}};
  for (int i = 0; i < 3; i++) {
    uint32_t out[4];
    sb_philox4x32_10(kat[i], kat[i] + 4, out);
    for (int k = 0; k < 4; k++)
      ck_assert_msg(out[k] == kat[i][6 + k], "vector %d word %d: %08x, want "
                    "%08x", i, k, out[k], kat[i][6 + k]);
  }
}
END_TEST

/* the words of (seed, id, step) are philox(ctr, key) with the documented
 * layout, block after block */
START_TEST(test_layout)
{
  const uint64_t seed = UINT64_C(0x0123456789abcdef);
  const uint64_t id = UINT64_C(0x00007654deadbeef);  /* 47 bits */
  const uint64_t step = UINT64_C(0x0000abcd12345678); /* 48 bits */
  sb_stream s;
  ck_assert_int_eq(sb_stream_init(&s, seed, id, step), SB_SUCCESS);
  uint32_t key[2] = {0x89abcdef, 0x01234567};
  for (uint32_t blk = 0; blk < 3; blk++) {
    uint32_t ctr[4] = {blk, 0x12345678, 0xdeadbeef,
                       0xabcdu | (0x7654u << 16)}, want[4];
    sb_philox4x32_10(ctr, key, want);
    for (int k = 0; k < 4; k++)
      ck_assert_uint_eq(sb_stream_u32(&s), want[k]);
  }
  /* a copy continues the same sequence */
  sb_stream c = s;
  ck_assert_uint_eq(sb_stream_u32(&c), sb_stream_u32(&s));
  /* domain */
  ck_assert_int_eq(sb_stream_init(&s, 1, SB_STREAM_MAX_ID, 0), SB_SUCCESS);
  ck_assert_int_eq(sb_stream_init(&s, 1, 0, SB_STREAM_MAX_STEP),
                   SB_SUCCESS);
  ck_assert_int_eq(sb_stream_init(&s, 1, SB_STREAM_MAX_ID + 1, 0), SB_EDOM);
  ck_assert_int_eq(sb_stream_init(&s, 1, 0, SB_STREAM_MAX_STEP + 1),
                   SB_EDOM);
  ck_assert_int_eq(sb_stream_init(NULL, 1, 0, 0), SB_EINVAL);
  ck_assert_int_eq(sb_stream_gaussian_fill(NULL, 1, NULL), SB_EINVAL);
  ck_assert_int_eq(sb_stream_uniform_fill(&s, 0, NULL), SB_SUCCESS);
  double z[4];
  ck_assert_int_eq(sb_stream_gaussian_keyed(1, 0, 2, NULL,
                                            SB_STREAM_MAX_ID, 2, z),
                   SB_EDOM);
  uint64_t bad = SB_STREAM_MAX_ID + 1;
  ck_assert_int_eq(sb_stream_gaussian_keyed(1, 0, 1, &bad, 0, 2, z),
                   SB_EDOM);
}
END_TEST

/* uniform = (2k+1)/2^53 from the top 52 bits of (w0 << 32 | w1) */
START_TEST(test_uniform_bits)
{
  sb_stream a, b;
  sb_stream_init(&a, 7, 3, 5);
  sb_stream_init(&b, 7, 3, 5);
  for (int i = 0; i < 1000; i++) {
    uint64_t hi = sb_stream_u32(&b), lo = sb_stream_u32(&b);
    uint64_t k = ((hi << 32) | lo) >> 12;
    double want = (2.0 * (double)k + 1.0) * 0x1p-53;
    double u = sb_stream_uniform(&a);
    ck_assert(u == want);
    ck_assert(u > 0.0 && u < 1.0);
  }
}
END_TEST

/* fill and keyed batch give what single calls give */
START_TEST(test_batch_equal)
{
  enum { N = 37, M = 6 };
  double z[N * M], zb[N * M];
  uint64_t ids[N];
  for (int j = 0; j < N; j++)
    ids[j] = (uint64_t)(1000 + 3 * j);
  ck_assert_int_eq(sb_stream_gaussian_keyed(99, 12, N, ids, 0, M, z),
                   SB_SUCCESS);
  ck_assert_int_eq(sb_stream_gaussian_keyed(99, 12, N, NULL, 500, M, zb),
                   SB_SUCCESS);
  for (int j = 0; j < N; j++) {
    sb_stream s, t;
    sb_stream_init(&s, 99, ids[j], 12);
    sb_stream_init(&t, 99, 500 + (uint64_t)j, 12);
    double f[M];
    sb_stream_gaussian_fill(&t, M, f);
    for (int k = 0; k < M; k++) {
      ck_assert(z[j * M + k] == sb_stream_gaussian(&s));
      ck_assert(zb[j * M + k] == f[k]);
    }
  }
  sb_stream s, t;
  sb_stream_init(&s, 4, 4, 4);
  sb_stream_init(&t, 4, 4, 4);
  double u[9];
  sb_stream_uniform_fill(&s, 9, u);
  for (int k = 0; k < 9; k++)
    ck_assert(u[k] == sb_stream_uniform(&t));
}
END_TEST

/* Marsaglia & Tsang (2000) layers from r: v = r f(r) + sqrt(pi/2)
 * erfc(r/sqrt 2), X[i+1] = f^-1(f(X[i]) + v/X[i]); the top layer closes
 * at f(0) = 1 */
START_TEST(test_zig_tables)
{
  const double r = sbi_zig_r;
  double f_r = exp(-0.5 * r * r);
  double v = r * f_r + sqrt(M_PI / 2) * gsl_sf_erfc(r / M_SQRT2);
  ck_assert_rel(sbi_zig_v, v, 1e-14);
  double X[129];
  X[0] = v / f_r;
  X[1] = r;
  for (int i = 1; i < 127; i++)
    X[i + 1] = sqrt(-2.0 * log(exp(-0.5 * X[i] * X[i]) + v / X[i]));
  X[128] = 0.0;
  /* closure: the top layer's area is v (error growth along the
   * recurrence keeps this to ~1e-11) */
  ck_assert_rel(X[127] * (1.0 - exp(-0.5 * X[127] * X[127])), v, 1e-9);
  for (int i = 0; i < 128; i++) {
    ck_assert_rel(sbi_zig_w[i], X[i] * 0x1p-24, 1e-9);
    double kk = floor(0x1p24 * X[i + 1] / X[i]);
    ck_assert_msg(fabs((double)sbi_zig_k[i] - kk) <= 1.0,
                  "k[%d] = %u, want %.0f", i, sbi_zig_k[i], kk);
    if (i > 0)
      ck_assert_rel(sbi_zig_f[i], exp(-0.5 * X[i] * X[i]), 1e-9);
  }
  ck_assert(sbi_zig_f[128] == 1.0);
  /* every layer has area v: X[i] (f[i+1] - f[i]) for i >= 1 */
  for (int i = 1; i < 127; i++)
    ck_assert_rel(X[i] * (exp(-0.5 * X[i + 1] * X[i + 1]) -
                          exp(-0.5 * X[i] * X[i])), v, 1e-9);
}
END_TEST

static double cdf_unif(double x, void *p)
{
  (void)p;
  return x <= 0 ? 0 : x >= 1 ? 1 : x;
}
static double cdf_norm(double x, void *p)
{
  (void)p;
  return gsl_cdf_ugaussian_P(x);
}

static double cdf_tail(double x, void *p)
{
  (void)p;
  if (x <= sbi_zig_r)
    return 0.0;
  return 1.0 - gsl_sf_erfc(x / M_SQRT2) / gsl_sf_erfc(sbi_zig_r / M_SQRT2);
}

/* mean, variance, skewness, excess kurtosis z-scores of n draws against
 * the law's (standard errors from the law's moments) */
static void check_moments(const double *x, size_t n, double mean,
                          double var, double m3, double m4, double m6,
                          double m8, const char *what)
{
  double s1 = 0, s2 = 0, s3 = 0, s4 = 0;
  for (size_t i = 0; i < n; i++) {
    double d = x[i] - mean, d2 = d * d;
    s1 += d;
    s2 += d2;
    s3 += d2 * d;
    s4 += d2 * d2;
  }
  double nn = (double)n;
  /* each central sample moment around the known mean: se^2 =
   * (E d^{2k} - (E d^k)^2)/n */
  double z1 = s1 / nn / sqrt(var / nn);
  double z2 = (s2 / nn - var) / sqrt((m4 - var * var) / nn);
  double z3 = (s3 / nn - m3) / sqrt((m6 - m3 * m3) / nn);
  double z4 = (s4 / nn - m4) / sqrt((m8 - m4 * m4) / nn);
  ck_assert_msg(fabs(z1) <= ZMAX && fabs(z2) <= ZMAX && fabs(z3) <= ZMAX &&
                fabs(z4) <= ZMAX, "%s: moment z-scores %.2f %.2f %.2f "
                "%.2f (bound %.1f)", what, z1, z2, z3, z4, ZMAX);
}

#define NMC 200000
static double buf[NMC];

static void check_uniform(const char *what)
{
  check_moments(buf, NMC, 0.5, 1.0 / 12, 0.0, 1.0 / 80, 1.0 / 448,
                1.0 / 2304, what);
  double d, p;
  ck_assert_int_eq(sb_ks_test(buf, NMC, cdf_unif, NULL, &d, &p),
                   SB_SUCCESS);
  ck_assert_msg(p >= 1e-3, "%s: KS D = %.3g, p = %.3g < 1e-3", what, d, p);
}

static void check_normal(const char *what)
{
  check_moments(buf, NMC, 0.0, 1.0, 0.0, 3.0, 15.0, 105.0, what);
  double d, p;
  ck_assert_int_eq(sb_ks_test(buf, NMC, cdf_norm, NULL, &d, &p),
                   SB_SUCCESS);
  ck_assert_msg(p >= 1e-3, "%s: KS D = %.3g, p = %.3g < 1e-3", what, d, p);
}

START_TEST(test_uniform_law)
{
  sb_stream s;
  sb_stream_init(&s, 2011, 0, 0);
  sb_stream_uniform_fill(&s, NMC, buf);
  check_uniform("sb_stream_uniform, seed 2011");
}
END_TEST

START_TEST(test_normal_law)
{
  sb_stream s;
  sb_stream_init(&s, 2011, 1, 0);
  sb_stream_gaussian_fill(&s, NMC, buf);
  check_normal("sb_stream_gaussian, seed 2011");
  /* keyed: the first of 6 normals of 2e5/6 particles, all 6 pooled */
  sb_stream_gaussian_keyed(2011, 17, NMC / 6, NULL, 0, 6, buf);
  for (size_t i = 6 * (NMC / 6); i < NMC; i++)
    buf[i] = sb_stream_gaussian(&s);
  check_normal("sb_stream_gaussian_keyed, seed 2011, step 17");
}
END_TEST

/* 2e6 normals in 100 equiprobable bins (expected 2e4 each): a wedge or
 * tail error of 1e-3 of the mass in a few bins shows as chi2 >> 99 */
START_TEST(test_normal_chi2)
{
  enum { NB = 100 };
  const size_t n = 2000000;
  double *z = malloc(n * sizeof *z), edges[NB + 1];
  ck_assert_ptr_nonnull(z);
  sb_stream s;
  sb_stream_init(&s, 1964, 2, 3);
  sb_stream_gaussian_fill(&s, n, z);
  edges[0] = -INFINITY;
  edges[NB] = INFINITY;
  for (int i = 1; i < NB; i++)
    edges[i] = gsl_cdf_ugaussian_Pinv((double)i / NB);
  double chi2, dof, p;
  ck_assert_int_eq(sb_chi2_test(z, n, edges, NB, cdf_norm, NULL, &chi2,
                                &dof, &p), SB_SUCCESS);
  ck_assert_msg(p >= 1e-3, "chi2 = %.1f on %.0f dof, p = %.3g", chi2, dof,
                p);
  /* the tail beyond r (the ziggurat's tail method), both signs:
   * P(|Z| > r) = erfc(r/sqrt 2) */
  unsigned long k = 0;
  for (size_t i = 0; i < n; i++)
    k += fabs(z[i]) > sbi_zig_r;
  double pt = gsl_sf_erfc(sbi_zig_r / M_SQRT2);
  double pb = sb_binomial_pvalue(k, n, pt);
  ck_assert_msg(pb >= 1e-3, "tail beyond r: %lu of %zu, expected %.1f, p = "
                "%.3g", k, n, pt * (double)n, pb);
  /* the shape of the tail: KS of the ~1150 values of |Z| > r against
   * P(|Z| <= x | |Z| > r) = 1 - erfc(x/sqrt 2)/erfc(r/sqrt 2) */
  size_t m = 0;
  for (size_t i = 0; i < n; i++)
    if (fabs(z[i]) > sbi_zig_r)
      z[m++] = fabs(z[i]);
  double d;
  ck_assert_int_eq(sb_ks_test(z, m, cdf_tail, NULL, &d, &p), SB_SUCCESS);
  ck_assert_msg(p >= 1e-3, "tail shape: KS D = %.3g on %zu values, p = "
                "%.3g", d, m, p);
  free(z);
}
END_TEST

/* correlation coefficient of n pairs (known mean 0, variance 1) */
static double corr_z(const double *a, const double *b, size_t n)
{
  double s = 0;
  for (size_t i = 0; i < n; i++)
    s += a[i] * b[i];
  return s / sqrt((double)n); /* ~ N(0, 1) for independent N(0,1) pairs */
}

START_TEST(test_independence)
{
  enum { N = 100000 };
  static double a[N], b[N];
  /* neighbouring ids, same step: the first normal of each */
  sb_stream_gaussian_keyed(5, 0, N, NULL, 0, 1, a);
  sb_stream_gaussian_keyed(5, 0, N, NULL, 1, 1, b);
  double z = corr_z(a, b, N);
  ck_assert_msg(fabs(z) <= ZMAX, "ids i, i+1: z = %.2f", z);
  /* same id, neighbouring steps */
  for (int i = 0; i < N; i++) {
    sb_stream s;
    sb_stream_init(&s, 5, 42, (uint64_t)i);
    a[i] = sb_stream_gaussian(&s);
    sb_stream_init(&s, 5, 42, (uint64_t)i + 1);
    b[i] = sb_stream_gaussian(&s);
  }
  z = corr_z(a, b, N);
  ck_assert_msg(fabs(z) <= ZMAX, "steps k, k+1: z = %.2f", z);
  /* neighbouring seeds */
  sb_stream_gaussian_keyed(6, 0, N, NULL, 0, 1, b);
  sb_stream_gaussian_keyed(5, 0, N, NULL, 0, 1, a);
  z = corr_z(a, b, N);
  ck_assert_msg(fabs(z) <= ZMAX, "seeds 5, 6: z = %.2f", z);
  /* within a stream: lag 1 to 6 of consecutive draws of one particle */
  sb_stream_gaussian_keyed(5, 9, N / 6, NULL, 0, 6, a);
  for (int lag = 1; lag <= 5; lag++) {
    double s = 0;
    size_t m = 0;
    for (size_t j = 0; j < N / 6; j++)
      for (int k = 0; k + lag < 6; k++, m++)
        s += a[6 * j + k] * a[6 * j + k + lag];
    z = s / sqrt((double)m);
    ck_assert_msg(fabs(z) <= ZMAX, "lag %d within a particle: z = %.2f",
                  lag, z);
  }
}
END_TEST

/* ------------------------------------------------- gsl_rng wrapper */

START_TEST(test_gsl_words)
{
  gsl_rng *r = gsl_rng_alloc(sb_rng_philox);
  ck_assert_ptr_nonnull(r);
  ck_assert_str_eq(gsl_rng_name(r), "sb_philox4x32_10");
  ck_assert_uint_eq(gsl_rng_max(r), 0xffffffffUL);
  ck_assert_uint_eq(gsl_rng_min(r), 0);
  /* gsl_rng_set: key = seed, counter (block, 0, 0, 2^31) */
  unsigned long seed = 0x0123456789abcdefUL;
  gsl_rng_set(r, seed);
  uint32_t key[2] = {0x89abcdef, 0x01234567};
  for (uint32_t blk = 0; blk < 2; blk++) {
    uint32_t ctr[4] = {blk, 0, 0, 0x80000000u}, want[4];
    sb_philox4x32_10(ctr, key, want);
    for (int k = 0; k < 4; k++)
      ck_assert_uint_eq(gsl_rng_get(r), want[k]);
  }
  /* the stream of (seed, id, step) */
  ck_assert_int_eq(sb_rng_philox_set_stream(r, 11, 22, 33), SB_SUCCESS);
  sb_stream s;
  sb_stream_init(&s, 11, 22, 33);
  for (int i = 0; i < 10; i++)
    ck_assert_uint_eq(gsl_rng_get(r), sb_stream_u32(&s));
  ck_assert_int_eq(sb_rng_philox_set_stream(r, 1, SB_STREAM_MAX_ID + 1, 0),
                   SB_EDOM);
  gsl_rng *m = gsl_rng_alloc(gsl_rng_mt19937);
  ck_assert_int_eq(sb_rng_philox_set_stream(m, 1, 1, 1), SB_EINVAL);
  ck_assert_int_eq(sb_rng_philox_set_stream(NULL, 1, 1, 1), SB_EINVAL);
  /* gsl_rng_clone copies the state (buffer and counter) */
  gsl_rng_set(r, 3);
  gsl_rng_get(r);
  gsl_rng *c = gsl_rng_clone(r);
  for (int i = 0; i < 9; i++)
    ck_assert_uint_eq(gsl_rng_get(c), gsl_rng_get(r));
  gsl_rng_free(c);
  gsl_rng_free(m);
  gsl_rng_free(r);
}
END_TEST

/* Integer arguments 0, 1, the largest valid and the first invalid values
 * and UINT64_MAX for id and step: sb_stream_init, sb_rng_philox_set_stream
 * and sb_stream_gaussian_keyed succeed exactly where id <= 2^47 - 1 and
 * step <= 2^48 - 1, and otherwise return SB_EDOM with a message naming
 * themselves (set_stream's named sb_stream_init); an invalid key leaves
 * the stream at (seed, 0, 0) as documented. */
START_TEST(test_key_extremes)
{
  const uint64_t ids[] = {0, 1, SB_STREAM_MAX_ID, SB_STREAM_MAX_ID + 1,
                          SB_STREAM_MAX_STEP, SB_STREAM_MAX_STEP + 1,
                          UINT64_MAX};
  const size_t ni = sizeof ids / sizeof ids[0];
  gsl_rng *r = gsl_rng_alloc(sb_rng_philox);
  for (size_t i = 0; i < ni; i++)
    for (size_t j = 0; j < ni; j++) {
      const uint64_t id = ids[i], step = ids[j];
      const int ok = id <= SB_STREAM_MAX_ID && step <= SB_STREAM_MAX_STEP;
      sb_stream s, s0;
      sb_clear_error();
      int st = sb_stream_init(&s, UINT64_MAX, id, step);
      ck_assert_int_eq(st, ok ? SB_SUCCESS : SB_EDOM);
      if (!ok) {
        ck_assert(strstr(sb_last_error(), "sb_stream_init") != NULL);
        sb_stream_init(&s0, UINT64_MAX, 0, 0);
        ck_assert_uint_eq(sb_stream_u32(&s), sb_stream_u32(&s0));
      }
      sb_clear_error();
      st = sb_rng_philox_set_stream(r, UINT64_MAX, id, step);
      ck_assert_int_eq(st, ok ? SB_SUCCESS : SB_EDOM);
      if (!ok)
        ck_assert_msg(strstr(sb_last_error(), "sb_rng_philox_set_stream"),
                      "%s", sb_last_error());
      double z[3] = {0.0, 0.0, 0.0};
      sb_clear_error();
      st = sb_stream_gaussian_keyed(UINT64_MAX, step, 1, &id, 0, 3, z);
      ck_assert_int_eq(st, ok ? SB_SUCCESS : SB_EDOM);
      if (!ok)
        ck_assert(strstr(sb_last_error(), "sb_stream_gaussian_keyed"));
      else
        ck_assert(isfinite(z[0]) && isfinite(z[1]) && isfinite(z[2]));
    }
  gsl_rng_free(r);
}
END_TEST

/* Every public sb_stream_* function on a NULL stream: a status, or the
 * documented value (0 word, NaN draw) with SB_EINVAL and a message naming
 * the function; no crash (the single draws dereferenced s). */
START_TEST(test_null_stream)
{
  sb_clear_error();
  ck_assert_uint_eq(sb_stream_u32(NULL), 0);
  ck_assert_int_eq(sb_last_status(), SB_EINVAL);
  ck_assert(strstr(sb_last_error(), "sb_stream_u32") != NULL);
  sb_clear_error();
  ck_assert(isnan(sb_stream_uniform(NULL)));
  ck_assert_int_eq(sb_last_status(), SB_EINVAL);
  ck_assert(strstr(sb_last_error(), "sb_stream_uniform") != NULL);
  sb_clear_error();
  ck_assert(isnan(sb_stream_gaussian(NULL)));
  ck_assert_int_eq(sb_last_status(), SB_EINVAL);
  ck_assert(strstr(sb_last_error(), "sb_stream_gaussian") != NULL);
  double z[2];
  ck_assert_int_eq(sb_stream_init(NULL, 1, 0, 0), SB_EINVAL);
  ck_assert_int_eq(sb_stream_uniform_fill(NULL, 2, z), SB_EINVAL);
  ck_assert_int_eq(sb_stream_gaussian_fill(NULL, 2, z), SB_EINVAL);
  ck_assert_int_eq(sb_stream_uniform_fill(NULL, 0, z), SB_SUCCESS);
  ck_assert_int_eq(sb_stream_gaussian_fill(NULL, 0, NULL), SB_SUCCESS);
  ck_assert_int_eq(sb_stream_gaussian_keyed(1, 0, 2, NULL, 0, 1, NULL),
                   SB_EINVAL);
  /* a valid stream after the errors draws as ever */
  sb_stream s, s0;
  sb_stream_init(&s, 3, 4, 5);
  sb_stream_init(&s0, 3, 4, 5);
  ck_assert_uint_eq(sb_stream_u32(&s), sb_stream_u32(&s0));
}
END_TEST

START_TEST(test_gsl_laws)
{
  gsl_rng *r = gsl_rng_alloc(sb_rng_philox);
  gsl_rng_set(r, 2011);
  for (size_t i = 0; i < NMC; i++)
    buf[i] = gsl_rng_uniform_pos(r);
  check_uniform("gsl_rng_uniform_pos with sb_rng_philox, seed 2011");
  for (size_t i = 0; i < NMC; i++)
    buf[i] = gsl_ran_gaussian_ziggurat(r, 1.0);
  check_normal("gsl_ran_gaussian_ziggurat with sb_rng_philox, seed 2011");
  gsl_rng_free(r);
}
END_TEST

static Suite *rng_suite(void)
{
  Suite *s = suite_create("rng");
  TCase *tc = tcase_create("philox");
  tcase_add_test(tc, test_kat);
  tcase_add_test(tc, test_layout);
  tcase_add_test(tc, test_uniform_bits);
  tcase_add_test(tc, test_batch_equal);
  tcase_add_test(tc, test_zig_tables);
  tcase_add_test(tc, test_gsl_words);
  tcase_add_test(tc, test_key_extremes);
  tcase_add_test(tc, test_null_stream);
  suite_add_tcase(s, tc);
  TCase *mc = tcase_create("monte-carlo");
  tcase_set_timeout(mc, 60);
  tcase_add_test(mc, test_uniform_law);
  tcase_add_test(mc, test_normal_law);
  tcase_add_test(mc, test_normal_chi2);
  tcase_add_test(mc, test_independence);
  tcase_add_test(mc, test_gsl_laws);
  suite_add_tcase(s, mc);
  return s;
}

int main(void) { return sbt_run_suite(rng_suite()); }
