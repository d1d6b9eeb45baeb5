#define _POSIX_C_SOURCE 200809L /* mkdtemp */
/* test_validate_resume.c — saved engine runs (sb_validate_options.run_dir,
 * .resume): a resumed case gives the records of a fresh one bit for bit,
 * really reads the saved runs (a doctored file changes the records), and
 * ignores files that are not for the run: resume off, another key, a
 * truncated file.  Two cases: V16/combined (Langevin first-hit runs) and
 * V7/brownian-turb (bridge first-hit runs). */
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <smolbridge/validate.h>
#include "testutil.h"

/* Records of case `name` run with opt. */
static sb_comparison *run_case(const char *name,
                               const sb_validate_options *opt, size_t *n)
{
  size_t idx;
  ck_assert_int_eq(sb_validate_case_index(name, &idx), SB_SUCCESS);
  sb_validate_report *rep = sb_validate_report_alloc();
  ck_assert_ptr_nonnull(rep);
  ck_assert_int_eq(sb_validate_run(idx, opt, rep), SB_SUCCESS);
  *n = sb_validate_report_nrecords(rep);
  sb_comparison *c = malloc(*n * sizeof *c);
  ck_assert_ptr_nonnull(c);
  for (size_t i = 0; i < *n; i++)
    c[i] = *sb_validate_report_record(rep, i);
  sb_validate_report_free(rep);
  return c;
}

/* Records whose estimates, intervals or p-values differ, bit for bit
 * (same names required; the intervals of first-contact rows also read
 * the counts' variances). */
static size_t ndiffer(const sb_comparison *a, const sb_comparison *b,
                      size_t n)
{
  size_t d = 0;
  for (size_t i = 0; i < n; i++) {
    ck_assert_str_eq(a[i].name, b[i].name);
    d += memcmp(&a[i].estimate, &b[i].estimate, sizeof(double)) != 0 ||
         memcmp(&a[i].ci_low, &b[i].ci_low, sizeof(double)) != 0 ||
         memcmp(&a[i].ci_high, &b[i].ci_high, sizeof(double)) != 0 ||
         memcmp(&a[i].p_value, &b[i].p_value, sizeof(double)) != 0;
  }
  return d;
}

enum { DOUBLE_VALUES, CHANGE_KEY, TRUNCATE };

/* Edit every saved run in dir; returns the number of files. */
static size_t edit_saved(const char *dir, int how)
{
  DIR *d = opendir(dir);
  ck_assert_ptr_nonnull(d);
  size_t nfiles = 0;
  struct dirent *de;
  while ((de = readdir(d))) {
    size_t len = strlen(de->d_name);
    if (len < 5 || strcmp(de->d_name + len - 4, ".run"))
      continue;
    char path[1024], line[4096];
    snprintf(path, sizeof path, "%s/%s", dir, de->d_name);
    FILE *f = fopen(path, "r");
    ck_assert_ptr_nonnull(f);
    char *text = calloc(1, 1 << 22);
    ck_assert_ptr_nonnull(text);
    size_t n = 0;
    int row = -1;  /* value lines after "vals=" */
    while (fgets(line, sizeof line, f)) {
      if (how == TRUNCATE && strcmp(line, "end\n") == 0)
        continue;
      if (how == CHANGE_KEY && strncmp(line, "key=", 4) == 0)
        line[4] = 'X';
      if (row >= 0 && row < 3 && how == DOUBLE_VALUES) {
        /* the first values are counts and kernels: doubling them
         * changes every estimate made from the run */
        double v = strtod(line, NULL);
        snprintf(line, sizeof line, "%a\n", 2.0 * v + 1.0);
      }
      if (row >= 0)
        row++;
      if (strncmp(line, "vals=", 5) == 0)
        row = 0;
      size_t l = strlen(line);
      ck_assert_uint_lt(n + l, 1 << 22);
      memcpy(text + n, line, l);
      n += l;
    }
    fclose(f);
    f = fopen(path, "w");
    ck_assert_ptr_nonnull(f);
    ck_assert_uint_eq(fwrite(text, 1, n, f), n);
    fclose(f);
    free(text);
    nfiles++;
  }
  closedir(d);
  return nfiles;
}

static void check_case(const char *name)
{
  char dir[] = "/tmp/sbresumeXXXXXX";
  ck_assert_ptr_nonnull(mkdtemp(dir));
  char runs[64];
  snprintf(runs, sizeof runs, "%s/runs", dir);  /* made by the library */
  sb_validate_options opt;
  sb_validate_options_init(&opt);
  ck_assert_ptr_null(opt.run_dir);
  ck_assert_int_eq(opt.resume, 0);
  size_t n0, n;
  sb_comparison *fresh = run_case(name, &opt, &n0);  /* nothing saved */
  ck_assert_uint_gt(n0, 0);

  opt.run_dir = runs;  /* saved, not read */
  sb_comparison *saved = run_case(name, &opt, &n);
  ck_assert_uint_eq(n, n0);
  ck_assert_uint_eq(ndiffer(fresh, saved, n), 0);
  opt.resume = 1;  /* read back: the same records */
  sb_comparison *resumed = run_case(name, &opt, &n);
  ck_assert_uint_eq(n, n0);
  ck_assert_uint_eq(ndiffer(fresh, resumed, n), 0);

  /* doctored values are read back (the records change)... */
  ck_assert_uint_gt(edit_saved(runs, DOUBLE_VALUES), 0);
  sb_comparison *doctored = run_case(name, &opt, &n);
  ck_assert_msg(ndiffer(fresh, doctored, n) > 0,
                "%s: the saved runs were not read", name);
  /* ... but not without resume (the runs are made and saved again) */
  opt.resume = 0;
  sb_comparison *again = run_case(name, &opt, &n);
  ck_assert_uint_eq(ndiffer(fresh, again, n), 0);
  opt.resume = 1;
  free(again);
  again = run_case(name, &opt, &n);  /* the files are right again */
  ck_assert_uint_eq(ndiffer(fresh, again, n), 0);

  /* files for another key, or cut short, are not used: doctor the
   * values too, so that a file wrongly read would show */
  for (int how = CHANGE_KEY; how <= TRUNCATE; how++) {
    edit_saved(runs, DOUBLE_VALUES);
    edit_saved(runs, how);
    free(again);
    again = run_case(name, &opt, &n);
    ck_assert_msg(ndiffer(fresh, again, n) == 0,
                  "%s: a %s file was read", name,
                  how == TRUNCATE ? "truncated" : "foreign");
  }
  free(fresh);
  free(saved);
  free(resumed);
  free(doctored);
  free(again);
  char cmd[128];
  snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
  ck_assert_int_eq(system(cmd), 0);
}

START_TEST(test_resume_langevin_runs) { check_case("V16/combined"); }
END_TEST

START_TEST(test_resume_bridge_runs) { check_case("V7/brownian-turb"); }
END_TEST

static Suite *suite(void)
{
  Suite *s = suite_create("validate_resume");
  TCase *tc = tcase_create("saved runs");
  tcase_set_timeout(tc, 120);
  tcase_add_test(tc, test_resume_langevin_runs);
  tcase_add_test(tc, test_resume_bridge_runs);
  suite_add_tcase(s, tc);
  return s;
}

int main(void) { return sbt_run_suite(suite()); }
