/* testutil.h — assertions shared by the Check suites.
 *
 * Check's ck_assert_double_eq_tol is absolute-only.  Reference values span
 * hundreds of decades, so the suites compare with a relative tolerance given
 * as a named multiple of DBL_EPSILON (or an explicit bound from the
 * specification).
 */
#ifndef SB_TESTUTIL_H
#define SB_TESTUTIL_H

#include <check.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include <smolbridge/common.h>

/* Named tolerances.  TOL_REF is the accuracy promised against the
 * arbitrary-precision reference vectors. */
#define TOL_ULPS(n) ((n) * DBL_EPSILON)
#define TOL_TIGHT TOL_ULPS(16)  /* ~3.6e-15: simple closed forms */
#define TOL_REF 1e-12           /* promised accuracy of reference functions */
#define TOL_QUAD 1e-9           /* closed form vs adaptive quadrature */

/* Relative difference |a-b| / max(|b|, tiny); exact match (including both
 * infinite with the same sign, or both NaN) gives 0. */
static inline double sbt_reldiff(double a, double b)
{
  if (a == b || (isnan(a) && isnan(b)))
    return 0.0;
  if (isnan(a) || isnan(b) || isinf(a) || isinf(b))
    return INFINITY;
  double d = fabs(b);
  return fabs(a - b) / (d > DBL_MIN ? d : DBL_MIN);
}

/* Assert |got - want| <= tol * |want|, printing both values on failure. */
#define ck_assert_rel(got, want, tol)                                       \
  do {                                                                      \
    double sbt_g_ = (got), sbt_w_ = (want), sbt_t_ = (tol);                 \
    double sbt_r_ = sbt_reldiff(sbt_g_, sbt_w_);                            \
    ck_assert_msg(sbt_r_ <= sbt_t_,                                         \
                  "%s = %.17g, want %.17g: relative error %.3g > %.3g",     \
                  #got, sbt_g_, sbt_w_, sbt_r_, sbt_t_);                    \
  } while (0)

/* Assert |got - want| <= tol. */
#define ck_assert_abs(got, want, tol)                                       \
  do {                                                                      \
    double sbt_g_ = (got), sbt_w_ = (want), sbt_t_ = (tol);                 \
    ck_assert_msg(fabs(sbt_g_ - sbt_w_) <= sbt_t_,                          \
                  "%s = %.17g, want %.17g: |diff| %.3g > %.3g", #got,       \
                  sbt_g_, sbt_w_, fabs(sbt_g_ - sbt_w_), sbt_t_);           \
  } while (0)

/* An `_e` result against a reference value: relative error <= tol, and
 * the error estimate err covers the actual difference (an honest
 * err, docs/api.md).  `what` names the call in the failure message. */
#define ck_assert_result(res, want, tol, what)                              \
  do {                                                                      \
    double sbt_g_ = (res).val, sbt_e_ = (res).err, sbt_w_ = (want);         \
    ck_assert_msg(sbt_reldiff(sbt_g_, sbt_w_) <= (tol),                     \
                  "%s: got %.17g want %.17g (rel %.3g)", what, sbt_g_,      \
                  sbt_w_, sbt_reldiff(sbt_g_, sbt_w_));                     \
    ck_assert_msg(fabs(sbt_g_ - sbt_w_) <= sbt_e_,                          \
                  "%s: err %.3g does not cover |%.17g - %.17g| = %.3g",     \
                  what, sbt_e_, sbt_g_, sbt_w_, fabs(sbt_g_ - sbt_w_));     \
  } while (0)

/* Path of a file under tests/data: $srcdir/tests/data/NAME, valid in-tree
 * and in VPATH builds (the harness sets srcdir to the top source directory,
 * AM_TESTS_ENVIRONMENT in Makefile.am; "." when unset). */
static inline const char *sbt_data_path(const char *name, char *buf,
                                        size_t len)
{
  const char *dir = getenv("srcdir");
  snprintf(buf, len, "%s/tests/data/%s", dir ? dir : ".", name);
  return buf;
}

/* Write n bytes to path (the test fails if it cannot). */
static inline void sbt_write_file(const char *path, const void *data,
                                  size_t n)
{
  FILE *f = fopen(path, "wb");
  ck_assert_ptr_nonnull(f);
  ck_assert_uint_eq(fwrite(data, 1, n, f), n);
  fclose(f);
}

/* A loader of a saved-state file: its status for the file at path. */
typedef int (*sbt_load_fn)(const char *path, void *ctx);

/* Damaged copies of the saved-state file `good`, written to `bad`: cut
 * after its magic, after `head` bytes, three bytes short, with one byte
 * after the end, and a file of another kind's magic `other`; load must
 * give SB_EFORMAT for each, then SB_EIO once `bad` is gone. */
static inline void sbt_damaged_copies(const char *good, const char *bad,
                                      size_t head, const char *other,
                                      sbt_load_fn load, void *ctx)
{
  static char buf[1 << 20];
  FILE *in = fopen(good, "rb");
  ck_assert_ptr_nonnull(in);
  const size_t n = fread(buf, 1, sizeof buf - 1, in);
  fclose(in);
  ck_assert(n > head + 8 && n < sizeof buf - 1);
  buf[n] = 0;
  const size_t cut[4] = {8, head, n - 3, n + 1};
  for (int q = 0; q < 4; q++) {
    sbt_write_file(bad, buf, cut[q]);
    ck_assert_int_eq(load(bad, ctx), SB_EFORMAT);
  }
  sbt_write_file(bad, other, 8);
  ck_assert_int_eq(load(bad, ctx), SB_EFORMAT);
  remove(bad);
  ck_assert_int_eq(load(bad, ctx), SB_EIO);
}

/* A saved-state file that ends in the hash of its contents
 * (common/internal.h, sbi_hsave_finish): `good` with one byte flipped,
 * at spread positions from its magic to its hash, written to `bad`, must
 * not load (SB_EFORMAT; past the magic the message says "damaged" and
 * names the file); with its hash byte-swapped, it must be refused as
 * written on a machine of the other byte order; and `good` as version
 * `old` of the format wrote it
 * (the two version digits of the magic, bytes 6-7, set to `old`, and
 * without the hash) must load (SB_SUCCESS).  `bad` is removed. */
static inline void sbt_hash_checked(const char *good, const char *bad,
                                    const char old[2], sbt_load_fn load,
                                    void *ctx)
{
  static char buf[1 << 20];
  FILE *in = fopen(good, "rb");
  ck_assert_ptr_nonnull(in);
  const size_t n = fread(buf, 1, sizeof buf, in);
  fclose(in);
  ck_assert(n > 24 && n < sizeof buf);
  const size_t at[] = {0, 6, 7, 8, 9, n / 4, n / 2, 3 * n / 4, n - 9,
                       n - 8, n - 1};
  for (size_t q = 0; q < sizeof at / sizeof at[0]; q++)
    for (int bit = 0; bit < 8; bit += 7) {
      buf[at[q]] ^= (char)(1 << bit);
      sbt_write_file(bad, buf, n);
      buf[at[q]] ^= (char)(1 << bit);
      const int st = load(bad, ctx);
      ck_assert_msg(st == SB_EFORMAT, "byte %zu of %zu, bit %d flipped: "
                    "status %d (%s)", at[q], n, bit, st, sb_last_error());
      if (at[q] >= 8)
        ck_assert_msg(strstr(sb_last_error(), "damaged") &&
                          strstr(sb_last_error(), bad),
                      "byte %zu flipped: \"%s\"", at[q], sb_last_error());
    }
  /* the hash stored byte-swapped, as a machine of the other byte order
   * writes it: refused as such (SB_EFORMAT, "other byte order"), not as
   * damaged */
  for (int k = 0; k < 4; k++) {
    char t = buf[n - 8 + k];
    buf[n - 8 + k] = buf[n - 1 - k];
    buf[n - 1 - k] = t;
  }
  sbt_write_file(bad, buf, n);
  for (int k = 0; k < 4; k++) {
    char t = buf[n - 8 + k];
    buf[n - 8 + k] = buf[n - 1 - k];
    buf[n - 1 - k] = t;
  }
  {
    const int so = load(bad, ctx);
    ck_assert_msg(so == SB_EFORMAT && strstr(sb_last_error(),
                                             "other byte order"),
                  "hash byte-swapped: status %d (%s)", so, sb_last_error());
  }
  const char v[2] = {buf[6], buf[7]};
  buf[6] = old[0];
  buf[7] = old[1];
  sbt_write_file(bad, buf, n - 8);
  buf[6] = v[0];
  buf[7] = v[1];
  const int st = load(bad, ctx);
  ck_assert_msg(st == SB_SUCCESS, "version %c%c: status %d (%s)", old[0],
                old[1], st, sb_last_error());
  remove(bad);
}

/* Run a suite with CK_ENV-controlled forking; returns main()'s status. */
static inline int sbt_run_suite(Suite *s)
{
  SRunner *sr = srunner_create(s);
  srunner_run_all(sr, CK_NORMAL);
  int failed = srunner_ntests_failed(sr);
  srunner_free(sr);
  return failed == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}

#endif /* SB_TESTUTIL_H */
