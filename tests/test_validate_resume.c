#define _POSIX_C_SOURCE 200809L /* mkdtemp */
/* test_validate_resume.c — saved engine runs (sb_validate_options.run_dir,
 * .resume): a resumed case gives the records of a fresh one bit for bit,
 * really reads the saved runs (a doctored file changes the records), and
 * ignores files that are not for the run: resume off, another key, a
 * truncated file; refuses a file that does not match the hash at its
 * end, saying so, and still reads the files of version 1 (no hash).  Two cases: V16/combined (Langevin first-hit runs) and
 * V7/brownian-turb (bridge first-hit runs). */
#include <dirent.h>
#include <stdint.h>
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

enum { DOUBLE_VALUES, CHANGE_KEY, TRUNCATE, FLIP, OLD_FORMAT };

/* FNV-1a, 64 bits (Fowler, Noll & Vo), written here again: the hash the
 * saved runs end with (version 2). */
static uint64_t fnv1a(const char *p, size_t n)
{
  uint64_t h = 0xcbf29ce484222325ULL;
  for (size_t i = 0; i < n; i++) {
    h ^= (unsigned char)p[i];
    h *= 0x100000001b3ULL;
  }
  return h;
}

/* Edit every saved run in dir; returns the number of files.  The files
 * end with the hash of the text before it, which the edits write again
 * (the edited file is whole), except FLIP: the text of DOUBLE_VALUES with
 * the old hash (a damaged file); OLD_FORMAT: the text of DOUBLE_VALUES as
 * version 1 wrote it (its magic line, no hash). */
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
    char path[1024], line[4096], *text = calloc(1, 1 << 22),
                                 *in = calloc(1, 1 << 22);
    ck_assert_ptr_nonnull(text);
    ck_assert_ptr_nonnull(in);
    snprintf(path, sizeof path, "%s/%s", dir, de->d_name);
    FILE *f = fopen(path, "rb");
    ck_assert_ptr_nonnull(f);
    size_t nin = fread(in, 1, (1 << 22) - 1, f);
    fclose(f);
    ck_assert_uint_gt(nin, 17);
    ck_assert_mem_eq(in, "SBVRUN02\n", 9);  /* the format written now */
    uint64_t hash;
    memcpy(&hash, in + nin - 8, 8);
    ck_assert(hash == fnv1a(in, nin - 8));  /* a whole file */
    in[nin - 8] = 0;
    size_t n = 0;
    int row = -1;  /* value lines after "vals=" */
    for (char *p = in, *q; *p; p = q) {
      q = strchr(p, '\n');
      ck_assert_ptr_nonnull(q);
      q++;
      ck_assert_uint_lt((size_t)(q - p), sizeof line);
      memcpy(line, p, (size_t)(q - p));
      line[q - p] = 0;
      if (how == TRUNCATE && strcmp(line, "end\n") == 0)
        continue;
      if (how == CHANGE_KEY && strncmp(line, "key=", 4) == 0)
        line[4] = 'X';
      if (how == OLD_FORMAT && p == in)
        strcpy(line, "smolbridge-run 1\n");
      if (row >= 0 && row < 3 &&
          (how == DOUBLE_VALUES || how == FLIP || how == OLD_FORMAT)) {
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
    if (how != FLIP)
      hash = fnv1a(text, n);
    f = fopen(path, "wb");
    ck_assert_ptr_nonnull(f);
    ck_assert_uint_eq(fwrite(text, 1, n, f), n);
    if (how != OLD_FORMAT)
      ck_assert_uint_eq(fwrite(&hash, 8, 1, f), 1);
    fclose(f);
    free(text);
    free(in);
    nfiles++;
  }
  closedir(d);
  return nfiles;
}

/* Progress lines that say a saved run was refused as damaged. */
static void count_damaged(const char *line, void *data)
{
  if (strstr(line, "saved run refused, made again") &&
      strstr(line, "is damaged"))
    ++*(int *)data;
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
  /* a file whose contents do not match its hash is refused, saying so,
   * and the run made again */
  int ndamaged = 0;
  opt.progress = count_damaged;
  opt.progress_data = &ndamaged;
  const size_t nfiles = edit_saved(runs, FLIP);
  free(again);
  again = run_case(name, &opt, &n);
  ck_assert_msg(ndiffer(fresh, again, n) == 0,
                "%s: a file that does not match its hash was read", name);
  ck_assert_int_eq(ndamaged, (int)nfiles);
  /* a file of version 1 (no hash) is still read */
  ck_assert_uint_eq(edit_saved(runs, OLD_FORMAT), nfiles);
  free(again);
  again = run_case(name, &opt, &n);
  ck_assert_msg(ndiffer(fresh, again, n) > 0,
                "%s: the saved runs of version 1 were not read", name);
  ck_assert_int_eq(ndamaged, (int)nfiles);
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
