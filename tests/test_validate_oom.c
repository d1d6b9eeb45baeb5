/* test_validate_oom.c — running out of memory inside a validation case.
 *
 * A case stops with SB_ENOMEM when an allocation it needs fails
 * (lib/validate/records.c: only running out of memory stops a case); it
 * must never go on to compare the totals of a run that did not happen.
 * malloc, calloc and realloc are replaced here (glibc's __libc_* do the
 * work) so that the k-th allocation made during sb_validate_run fails;
 * every k is tried, and the case must return SB_ENOMEM or, for an
 * allocation it can do without (a note of the report), succeed with the
 * records of the run without failure.  Allocations that GSL makes are
 * left alone: GSL's own recovery is not under test
 * (gsl_ran_discrete_preproc of GSL 2.7 does not survive one).  Cases too
 * long for that sweep have their parts called directly (v12.h) with a
 * report whose next growth of its records fails.
 * Linux/glibc only, and not under AddressSanitizer: elsewhere the test
 * does nothing. */
#define _GNU_SOURCE /* dladdr */
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_errno.h>

#include <smolbridge/validate.h>
#include "testutil.h"
#include "validate/v12.h"

/* AddressSanitizer has its own allocator: blocks from glibc's would
 * reach its free() (GCC defines __SANITIZE_ADDRESS__, clang
 * __has_feature(address_sanitizer)). */
#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#define SBT_ASAN 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__)
#define SBT_ASAN 1
#endif

#if defined(__GLIBC__) && !defined(SBT_ASAN)
#include <dlfcn.h>
#define SBT_OOM 1
extern void *__libc_malloc(size_t n);
extern void *__libc_calloc(size_t m, size_t n);
extern void *__libc_realloc(void *p, size_t n);

static long fail_at = -1; /* index of the allocation that fails (-1: none) */
static long nalloc = -1;  /* allocations since arming (-1: not counting) */
static void *fail_grow;   /* a block whose next realloc fails (once) */

static int fail_now(void *caller)
{
  if (nalloc < 0)
    return 0;
  Dl_info di;
  if (dladdr(caller, &di) && di.dli_fname && strstr(di.dli_fname, "libgsl"))
    return 0;
  return nalloc++ == fail_at;
}

#define CALLER __builtin_return_address(0)
void *malloc(size_t n)
{
  return fail_now(CALLER) ? NULL : __libc_malloc(n);
}
void *calloc(size_t m, size_t n)
{
  return fail_now(CALLER) ? NULL : __libc_calloc(m, n);
}
void *realloc(void *p, size_t n)
{
  if (p && p == fail_grow) {
    fail_grow = NULL;
    return NULL;
  }
  return fail_now(CALLER) ? NULL : __libc_realloc(p, n);
}
#else
#define SBT_OOM 0
#endif

#if SBT_OOM
/* Run case idx with allocation k failing (k < 0: none); *count gets the
 * number of allocations the run made, *rec (if rec) a copy of its
 * records and *nrec their number. */
static int run_case(size_t idx, long k, long *count, sb_comparison **rec,
                    size_t *nrec)
{
  sb_validate_options o;
  sb_validate_options_init(&o);
  sb_validate_report *rep = sb_validate_report_alloc();
  ck_assert_ptr_nonnull(rep);
  fail_at = k;
  nalloc = 0;
  int st = sb_validate_run(idx, &o, rep);
  *count = nalloc;
  nalloc = fail_at = -1;
  *nrec = sb_validate_report_nrecords(rep);
  if (rec) {
    *rec = malloc((*nrec + 1) * sizeof **rec);
    ck_assert_ptr_nonnull(*rec);
    for (size_t i = 0; i < *nrec; i++)
      (*rec)[i] = *sb_validate_report_record(rep, i);
  }
  sb_validate_report_free(rep);
  return st;
}

static int same_double(double a, double b)
{
  return !memcmp(&a, &b, sizeof a);
}

static int same_record(const sb_comparison *a, const sb_comparison *b)
{
  return !strcmp(a->name, b->name) && same_double(a->estimate, b->estimate) &&
         same_double(a->reference, b->reference) &&
         same_double(a->ci_low, b->ci_low) &&
         same_double(a->ci_high, b->ci_high) &&
         same_double(a->p_value, b->p_value) &&
         same_double(a->level, b->level) && a->rule == b->rule &&
         a->verdict == b->verdict;
}

static void every_allocation_stops_the_case(const char *name)
{
  gsl_set_error_handler_off();
  size_t idx, n0;
  ck_assert_int_eq(sb_validate_case_index(name, &idx), SB_SUCCESS);
  long total;
  sb_comparison *r0;
  ck_assert_int_eq(run_case(idx, -1, &total, &r0, &n0), SB_SUCCESS);
  ck_assert_int_gt(total, 0);
  for (long k = 0; k < total; k++) {
    long c;
    size_t n;
    sb_comparison *r;
    int st = run_case(idx, k, &c, &r, &n);
    if (st == SB_SUCCESS) {
      ck_assert_msg(n == n0, "%s: allocation %ld of %ld failed, the case "
                    "succeeded with %zu records, not %zu", name, k, total, n,
                    n0);
      for (size_t i = 0; i < n; i++)
        ck_assert_msg(same_record(&r[i], &r0[i]), "%s: allocation %ld of "
                      "%ld failed, the case succeeded with record %s = %g "
                      "(%g without the failure)", name, k, total, r[i].name,
                      r[i].estimate, r0[i].estimate);
    } else
      ck_assert_msg(st == SB_ENOMEM, "%s: allocation %ld of %ld failed, "
                    "the case returned %d (%s), not SB_ENOMEM", name, k,
                    total, st, sb_strerror(st));
    free(r);
  }
  free(r0);
}
#endif

/* The Bird and Nanbu conservation case: a failed sb_spray_collide (the
 * Nanbu partner weights, its alias table) was overwritten by the next
 * row's status, and the case compared the totals of a run that had not
 * collided. */
START_TEST(test_spray_conservation_stops)
{
#if SBT_OOM
  every_allocation_stops_the_case("V13/spray-conservation");
#endif
}
END_TEST

#if SBT_OOM
/* A report of n rows (the next one grows its records, see report.c)
 * whose next growth fails. */
static sbv_report *full_report(size_t n)
{
  sbv_report *rep = sb_validate_report_alloc();
  ck_assert_ptr_nonnull(rep);
  for (size_t i = 0; i < n; i++)
    ck_assert_int_eq(sbv_add_info(rep, "V0/filler", 1.0, 1.0, 0.0, 2.0,
                                  0.95), SB_SUCCESS);
  fail_grow = (void *)sb_validate_report_record(rep, 0);
  return rep;
}
#endif

/* V12 mixture: the status of its last two rows (the contact-place slope)
 * was dropped, so a row lost for want of memory went unnoticed.  The
 * report is filled so that the first of them grows the records. */
START_TEST(test_v12_mixture_last_rows)
{
#if SBT_OOM
  gsl_set_error_handler_off();
  sb_validate_options o;
  sb_validate_options_init(&o);
  const sbv_ctx ctx = {0, o.seed, NULL, &o, NULL, NULL};
  sbv_report *rep = full_report(13); /* + 3 kernel rows = 16 */
  ck_assert_int_eq(v12_mixture(&ctx, rep), SB_ENOMEM);
  ck_assert_ptr_null(fail_grow);
  sb_validate_report_free(rep);
#endif
}
END_TEST

/* V12 velocities: a failed sticking-fraction row was overwritten by the
 * next row's status. */
START_TEST(test_v12_velocities_stick_rows)
{
#if SBT_OOM
  gsl_set_error_handler_off();
  sb_validate_options o;
  sb_validate_options_init(&o);
  const sbv_ctx ctx = {0, o.seed, NULL, &o, NULL, NULL};
  enum { N = 500 };
  static double vref[N], vl[N];
  for (int i = 0; i < N; i++) {
    vref[i] = 0.5 * (i + 0.5) / N;
    vl[i] = 0.5 * (i + 0.25) / N;
  }
  v12_vel vel = {0.05, vref, {vl, NULL}, N, {N, 0}};
  sbv_report *rep = full_report(16);
  ck_assert_int_eq(v12_velocities(&ctx, rep, &vel, 1), SB_ENOMEM);
  ck_assert_ptr_null(fail_grow);
  sb_validate_report_free(rep);
#endif
}
END_TEST

static Suite *suite(void)
{
  Suite *s = suite_create("validate_oom");
  TCase *tc = tcase_create("oom");
  tcase_set_timeout(tc, 300);
  tcase_add_test(tc, test_spray_conservation_stops);
  tcase_add_test(tc, test_v12_mixture_last_rows);
  tcase_add_test(tc, test_v12_velocities_stick_rows);
  suite_add_tcase(s, tc);
  return s;
}

int main(void) { return sbt_run_suite(suite()); }
