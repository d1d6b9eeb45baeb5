/* test_common.c — status strings, the per-thread error record, version,
 * and the wrappers that call GSL without its error handler. */
#include <math.h>
#include <pthread.h>
#include <string.h>

#include <gsl/gsl_errno.h>

#include "common/internal.h"
#include "common/numutil.h"
#include "testutil.h"

START_TEST(test_strerror_all_codes)
{
  /* Every status has its own non-empty text; out-of-range codes are named. */
  for (int s = 0; s < SB_ENSTATUS; s++) {
    const char *t = sb_strerror(s);
    ck_assert_ptr_nonnull(t);
    ck_assert_msg(strlen(t) > 0, "empty text for status %d", s);
    ck_assert_str_ne(t, "unknown status code");
    for (int q = 0; q < s; q++)
      ck_assert_str_ne(t, sb_strerror(q));
  }
  ck_assert_str_eq(sb_strerror(-1), "unknown status code");
  ck_assert_str_eq(sb_strerror(SB_ENSTATUS), "unknown status code");
}
END_TEST

START_TEST(test_error_record)
{
  sb_clear_error();
  ck_assert_int_eq(sb_last_status(), SB_SUCCESS);
  ck_assert_str_eq(sb_last_error(), "");
  int s = sbi_error(SB_EDOM, "sb_demo", "v = %g must be positive", -1.0);
  ck_assert_int_eq(s, SB_EDOM);
  ck_assert_int_eq(sb_last_status(), SB_EDOM);
  ck_assert_str_eq(sb_last_error(), "sb_demo: v = -1 must be positive");
  sb_clear_error();
  ck_assert_str_eq(sb_last_error(), "");
  /* an outer routine passing the inner message on */
  sbi_error(SB_EDOM, "sb_inner", "x = %d", 3);
  sbi_error(SB_EDOM, "sb_outer", "%s", sb_last_error());
  ck_assert_str_eq(sb_last_error(), "sb_outer: sb_inner: x = 3");
}
END_TEST

START_TEST(test_error_record_truncates)
{
  char big[2000];
  memset(big, 'x', sizeof big - 1);
  big[sizeof big - 1] = '\0';
  sbi_error(SB_EINVAL, "sb_demo", "%s", big);
  ck_assert_uint_lt(strlen(sb_last_error()), 512);
  ck_assert_int_eq(strncmp(sb_last_error(), "sb_demo: xxx", 12), 0);
}
END_TEST

/* A message that wraps the previous one (the library does this where a
 * public function reports a failure of a function it called) keeps the
 * inner text whole: the argument points into the record being written. */
START_TEST(test_error_record_wraps_previous)
{
  sbi_error(SB_EDOM, "sb_inner", "x = %g is negative", -2.0);
  sbi_error(SB_EINVAL, "sb_outer_function", "step failed: %s",
            sb_last_error());
  ck_assert_str_eq(sb_last_error(), "sb_outer_function: step failed: "
                   "sb_inner: x = -2 is negative");
  ck_assert_int_eq(sb_last_status(), SB_EINVAL);
}
END_TEST

START_TEST(test_fail_res_macro)
{
  sb_result r = {1.0, 0.0};
  int s = SBI_FAIL_RES(&r, SB_EINVAL, "bad %s", "thing");
  ck_assert_int_eq(s, SB_EINVAL);
  ck_assert(isnan(r.val) && isnan(r.err));
  ck_assert_int_eq(SBI_FAIL_RES((sb_result *)NULL, SB_EDOM, "x"), SB_EDOM);
}
END_TEST

/* Each thread sees only its own error record. */
static void *thread_sets_error(void *arg)
{
  int status = *(int *)arg;
  for (int i = 0; i < 1000; i++) {
    sbi_error(status, "sb_thread", "status %d", status);
    if (sb_last_status() != status)
      return (void *)1;
  }
  return NULL;
}

START_TEST(test_error_record_is_per_thread)
{
  pthread_t th[2];
  int st[2] = {SB_EDOM, SB_ERANGE};
  sb_clear_error();
  for (int i = 0; i < 2; i++)
    pthread_create(&th[i], NULL, thread_sets_error, &st[i]);
  for (int i = 0; i < 2; i++) {
    void *ret;
    pthread_join(th[i], &ret);
    ck_assert_ptr_null(ret);
  }
  ck_assert_int_eq(sb_last_status(), SB_SUCCESS); /* main thread untouched */
}
END_TEST

START_TEST(test_version)
{
  char buf[64];
  snprintf(buf, sizeof buf, "%d.%d.%d", sb_version_major(),
           sb_version_minor(), sb_version_patch());
  ck_assert_str_eq(buf, sb_version());
  ck_assert_str_eq(sb_version(), SB_VERSION_STRING);
  ck_assert_int_eq(sb_version_major(), SB_VERSION_MAJOR);
}
END_TEST

/* GSL's handler must never be reached from the wrappers: this one fails
 * the test (the library must not switch the handler either). */
static void fail_handler(const char *reason, const char *file, int line,
                         int gsl_errno)
{
  ck_abort_msg("GSL error handler reached: %s (%s:%d, %d)", reason, file,
               line, gsl_errno);
}

static double cubic(double x, void *p) { (void)p; return x * x * x - 2.0; }
static double nan_inside(double x, void *p)
{
  (void)p;
  return x > 0.3 && x < 0.7 ? NAN : x * x * x - 0.125;
}
static double gauss(double x, void *p) { (void)p; return exp(-x * x); }
static double inv_sqrt(double x, void *p) { (void)p; return 1.0 / sqrt(x); }

START_TEST(test_gsl_wrappers)
{
  gsl_error_handler_t *old = gsl_set_error_handler(fail_handler);
  double r, res, err;
  gsl_function F = {cubic, NULL};
  ck_assert_int_eq(sbi_brent(&F, 0.0, 2.0, 0.0, 1e-15, 100, &r), SB_SUCCESS);
  ck_assert_double_eq_tol(r, cbrt(2.0), 4e-15);
  ck_assert_int_eq(sbi_brent(&F, 0.0, 1.0, 0.0, 1e-15, 100, &r), SB_EINVAL);
  ck_assert_int_eq(sbi_brent(&F, 2.0, 3.0, 0.0, 1e-15, 100, &r), SB_EINVAL);
  /* a NaN met inside the bracket ends the search (GSL's Brent would call
   * its handler: "function value is not finite") */
  gsl_function N = {nan_inside, NULL};
  ck_assert_int_eq(sbi_brent(&N, 0.0, 1.0, 0.0, 1e-15, 100, &r), SB_EDOM);
  ck_assert(isnan(r));
  ck_assert_int_eq(sbi_brent(&N, 0.0, 0.3, 0.0, 1e-15, 100, &r), SB_EINVAL);
  ck_assert_int_eq(sbi_brent(&N, 0.5, 1.0, 0.0, 1e-15, 100, &r), SB_EDOM);
  gsl_function G = {gauss, NULL};
  ck_assert_int_eq(sbi_integrate(&G, 0.0, INFINITY, 0.0, 1e-12, 100, &res,
                                 &err), SB_SUCCESS);
  ck_assert_double_eq_tol(res, 0.5 * sqrt(M_PI), 1e-13);
  ck_assert_int_eq(sbi_integrate(&G, -1.0, 1.0, 0.0, 1e-12, 100, &res,
                                 &err), SB_SUCCESS);
  ck_assert_double_eq_tol(res, sqrt(M_PI) * erf(1.0), 1e-13);
  /* an integrable singularity at an end */
  gsl_function S = {inv_sqrt, NULL};
  int st = sbi_integrate(&S, 0.0, 1.0, 0.0, 1e-10, 200, &res, &err);
  ck_assert(st == SB_SUCCESS || st == SB_EMAXITER);
  ck_assert_double_eq_tol(res, 2.0, 1e-6);
  ck_assert_ptr_eq(gsl_set_error_handler(old), fail_handler);
}
END_TEST

int main(void)
{
  Suite *s = suite_create("common");
  TCase *tc = tcase_create("core");
  tcase_add_test(tc, test_strerror_all_codes);
  tcase_add_test(tc, test_error_record);
  tcase_add_test(tc, test_error_record_truncates);
  tcase_add_test(tc, test_error_record_wraps_previous);
  tcase_add_test(tc, test_fail_res_macro);
  tcase_add_test(tc, test_error_record_is_per_thread);
  tcase_add_test(tc, test_version);
  tcase_add_test(tc, test_gsl_wrappers);
  suite_add_tcase(s, tc);
  return sbt_run_suite(s);
}
