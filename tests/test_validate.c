#define _POSIX_C_SOURCE 200809L /* mkdtemp, access */
/* test_validate.c — the validation module from C: list the registered
 * cases, run two of them into a report, and check the report's records,
 * accessors, determinism, callbacks and files. */
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <smolbridge/validate.h>
#include "testutil.h"

START_TEST(test_registry_lists_cases)
{
  size_t n = sb_validate_ncases();
  ck_assert_uint_ge(n, 20);
  for (size_t i = 0; i < n; i++) {
    const char *name = sb_validate_case_name(i);
    const char *desc = sb_validate_case_description(i);
    ck_assert_ptr_nonnull(name);
    ck_assert_ptr_nonnull(desc);
    ck_assert_msg(name[0] == 'V', "case name '%s' does not start with V",
                  name);
    ck_assert_msg(strlen(desc) > 0, "case '%s' has no description", name);
    size_t j = n;
    ck_assert_int_eq(sb_validate_case_index(name, &j), SB_SUCCESS);
    ck_assert_msg(j == i, "case '%s' is not unique (%zu and %zu)", name, i,
                  j);
  }
  ck_assert_ptr_null(sb_validate_case_name(n));
  ck_assert_int_eq(sb_last_status(), SB_EINVAL);
  ck_assert_ptr_null(sb_validate_case_description(n));
  size_t k;
  ck_assert_int_eq(sb_validate_case_index("V99/no-such-case", &k), SB_EINVAL);
  ck_assert_int_eq(sb_validate_case_index(NULL, &k), SB_EINVAL);
}
END_TEST

/* Copy of every record of a report (to compare two runs). */
static sb_comparison *records(const sb_validate_report *rep, size_t *n)
{
  *n = sb_validate_report_nrecords(rep);
  sb_comparison *c = malloc(*n * sizeof *c);
  ck_assert_ptr_nonnull(c);
  for (size_t i = 0; i < *n; i++)
    c[i] = *sb_validate_report_record(rep, i);
  return c;
}

START_TEST(test_run_case_records_and_determinism)
{
  sb_validate_options opt;
  sb_validate_options_init(&opt);
  ck_assert_int_eq(opt.full, 0);
  ck_assert_uint_eq(opt.seed, 12345UL);
  ck_assert_ptr_null(opt.outdir);

  size_t idx;
  ck_assert_int_eq(sb_validate_case_index("V9/two-spheres-45", &idx),
                   SB_SUCCESS);
  sb_validate_report *rep = sb_validate_report_alloc();
  ck_assert_ptr_nonnull(rep);
  ck_assert_int_eq(sb_validate_run(idx, &opt, rep), SB_SUCCESS);
  ck_assert_uint_eq(sb_validate_report_ncases(rep), 1);
  ck_assert_str_eq(sb_validate_report_case_name(rep, 0), "V9/two-spheres-45");
  ck_assert_int_eq(sb_validate_report_case_status(rep, 0), SB_SUCCESS);
  ck_assert(sb_validate_report_case_seconds(rep, 0) >= 0.0);
  size_t first = 99;
  size_t count = sb_validate_report_case_records(rep, 0, &first);
  ck_assert_uint_eq(first, 0);
  ck_assert_uint_eq(count, sb_validate_report_nrecords(rep));
  ck_assert_uint_ge(count, 4);
  for (size_t i = 0; i < count; i++) {
    const sb_comparison *c = sb_validate_report_record(rep, i);
    ck_assert_msg(strncmp(c->name, "V9/two-spheres-45/", 18) == 0,
                  "record '%s' not named after its case", c->name);
    ck_assert_msg(c->verdict == SB_PASS, "%s fails: %g vs %g", c->name,
                  c->estimate, c->reference);
  }
  ck_assert_uint_eq(sb_validate_report_nfailed(rep), 0);
  ck_assert_ptr_null(sb_validate_report_record(rep, count));
  ck_assert_ptr_null(sb_validate_report_case_name(rep, 1));
  ck_assert_int_eq(sb_validate_report_case_status(rep, 1), SB_EINVAL);

  /* A Monte Carlo case twice with the same seed: identical records. */
  ck_assert_int_eq(sb_validate_case_index("V11/bb-hit-ks", &idx),
                   SB_SUCCESS);
  sb_validate_report *a = sb_validate_report_alloc();
  sb_validate_report *b = sb_validate_report_alloc();
  ck_assert_int_eq(sb_validate_run(idx, &opt, a), SB_SUCCESS);
  ck_assert_int_eq(sb_validate_run(idx, &opt, b), SB_SUCCESS);
  size_t na, nb;
  sb_comparison *ra = records(a, &na), *rb = records(b, &nb);
  ck_assert_uint_eq(na, nb);
  ck_assert_uint_gt(na, 0);
  for (size_t i = 0; i < na; i++) {
    ck_assert_str_eq(ra[i].name, rb[i].name);
    ck_assert_msg(ra[i].estimate == rb[i].estimate,
                  "%s not reproducible", ra[i].name);
  }
  /* ... and a different seed gives different estimates. */
  opt.seed = 777;
  sb_validate_report *c = sb_validate_report_alloc();
  ck_assert_int_eq(sb_validate_run(idx, &opt, c), SB_SUCCESS);
  size_t nc, ndiff = 0;
  sb_comparison *rc = records(c, &nc);
  ck_assert_uint_eq(nc, na);
  for (size_t i = 0; i < na; i++)
    ndiff += rc[i].estimate != ra[i].estimate;
  ck_assert_uint_gt(ndiff, 0);
  free(ra);
  free(rb);
  free(rc);
  sb_validate_report_free(a);
  sb_validate_report_free(b);
  sb_validate_report_free(c);
  sb_validate_report_free(rep);
}
END_TEST

static int nrender;
static int count_render(const char *dir, const char *script, void *data)
{
  (void)data;
  char path[2048];
  snprintf(path, sizeof path, "%s/%s", dir, script);
  ck_assert_msg(access(path, R_OK) == 0, "script %s not written", path);
  nrender++;
  return -1; /* "not rendered": the note must say how to render it */
}

static int nprogress;
static void count_progress(const char *line, void *data)
{
  (void)line;
  (void)data;
  nprogress++;
}

START_TEST(test_plots_and_report_files)
{
  char dir[] = "/tmp/sbvalXXXXXX";
  ck_assert_ptr_nonnull(mkdtemp(dir));
  sb_validate_options opt;
  sb_validate_options_init(&opt);
  opt.outdir = dir;
  opt.render = count_render;
  opt.progress = count_progress;
  size_t idx;
  ck_assert_int_eq(sb_validate_case_index("V8/pbe-discrete", &idx),
                   SB_SUCCESS);
  sb_validate_report *rep = sb_validate_report_alloc();
  nrender = 0;
  ck_assert_int_eq(sb_validate_run(idx, &opt, rep), SB_SUCCESS);
  ck_assert_int_ge(nrender, 1);
  ck_assert_msg(strstr(sb_validate_report_case_notes(rep, 0), "gnuplot ") !=
                    NULL,
                "notes do not say how to render: %s",
                sb_validate_report_case_notes(rep, 0));
  ck_assert_uint_eq(sb_validate_report_nfailed(rep), 0);

  char csv[512], md[512];
  snprintf(csv, sizeof csv, "%s/validate.csv", dir);
  snprintf(md, sizeof md, "%s/report.md", dir);
  ck_assert_int_eq(sb_validate_report_write_csv(rep, csv), SB_SUCCESS);
  ck_assert_int_eq(sb_validate_report_write_markdown(rep, md, &opt),
                   SB_SUCCESS);
  FILE *f = fopen(csv, "r");
  ck_assert_ptr_nonnull(f);
  char line[1024];
  ck_assert_ptr_nonnull(fgets(line, sizeof line, f));
  line[strcspn(line, "\n")] = '\0';
  ck_assert_str_eq(line, SB_COMPARISON_CSV_HEADER);
  size_t nlines = 0;
  while (fgets(line, sizeof line, f))
    nlines++;
  fclose(f);
  ck_assert_uint_eq(nlines, sb_validate_report_nrecords(rep));
  ck_assert_int_eq(sb_validate_report_write_csv(rep, "/nonexistent/x.csv"),
                   SB_EIO);
  ck_assert_int_eq(sb_validate_report_fprint(rep, NULL), SB_EINVAL);

  /* A case with progress lines reports them through the callback. */
  ck_assert_int_eq(sb_validate_case_index("V1/kinetic-gases", &idx),
                   SB_SUCCESS);
  nprogress = 0;
  opt.outdir = NULL; /* no plot files */
  ck_assert_int_eq(sb_validate_run(idx, &opt, rep), SB_SUCCESS);
  ck_assert_int_gt(nprogress, 0);
  ck_assert_uint_eq(sb_validate_report_ncases(rep), 2);
  sb_validate_report_free(rep);
  char cmd[600];
  snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
  ck_assert_int_eq(system(cmd), 0);
}
END_TEST

/* A report through a byte buffer (what MPI ranks send to rank 0): the
 * cases appended from it equal the originals, record for record, notes and
 * status included, and appending two buffers keeps their order. */
START_TEST(test_pack_and_append)
{
  sb_validate_options opt;
  sb_validate_options_init(&opt);
  size_t i1, i2;
  ck_assert_int_eq(sb_validate_case_index("V9/two-spheres-45", &i1),
                   SB_SUCCESS);
  ck_assert_int_eq(sb_validate_case_index("V11/bb-hit-ks", &i2),
                   SB_SUCCESS);
  sb_validate_report *a = sb_validate_report_alloc(),
                     *b = sb_validate_report_alloc(),
                     *all = sb_validate_report_alloc(),
                     *g = sb_validate_report_alloc();
  ck_assert_int_eq(sb_validate_run(i1, &opt, a), SB_SUCCESS);
  ck_assert_int_eq(sb_validate_run(i2, &opt, b), SB_SUCCESS);
  ck_assert_int_eq(sb_validate_run(i1, &opt, all), SB_SUCCESS);
  ck_assert_int_eq(sb_validate_run(i2, &opt, all), SB_SUCCESS);
  void *pa, *pb;
  size_t la, lb;
  ck_assert_int_eq(sb_validate_report_pack(a, &pa, &la), SB_SUCCESS);
  ck_assert_int_eq(sb_validate_report_pack(b, &pb, &lb), SB_SUCCESS);
  ck_assert_uint_gt(la, 8);
  ck_assert_int_eq(sb_validate_report_append_packed(g, pa, la), SB_SUCCESS);
  ck_assert_int_eq(sb_validate_report_append_packed(g, pb, lb), SB_SUCCESS);
  ck_assert_uint_eq(sb_validate_report_ncases(g), 2);
  ck_assert_uint_eq(sb_validate_report_nrecords(g),
                    sb_validate_report_nrecords(all));
  for (size_t k = 0; k < 2; k++) {
    ck_assert_str_eq(sb_validate_report_case_name(g, k),
                     sb_validate_report_case_name(all, k));
    ck_assert_int_eq(sb_validate_report_case_status(g, k),
                     sb_validate_report_case_status(all, k));
    const char *n1 = sb_validate_report_case_notes(g, k),
               *n2 = sb_validate_report_case_notes(all, k);
    ck_assert_str_eq(n1 ? n1 : "", n2 ? n2 : "");
    size_t f1, f2;
    ck_assert_uint_eq(sb_validate_report_case_records(g, k, &f1),
                      sb_validate_report_case_records(all, k, &f2));
    ck_assert_uint_eq(f1, f2);
  }
  for (size_t i = 0; i < sb_validate_report_nrecords(g); i++) {
    const sb_comparison *x = sb_validate_report_record(g, i),
                        *y = sb_validate_report_record(all, i);
    /* bit for bit (NaN fields included) */
    const double *dx[] = {&x->estimate, &x->reference, &x->ci_low,
                          &x->ci_high, &x->p_value, &x->level},
                 *dy[] = {&y->estimate, &y->reference, &y->ci_low,
                          &y->ci_high, &y->p_value, &y->level};
    ck_assert_str_eq(x->name, y->name);
    for (int j = 0; j < 6; j++)
      ck_assert_msg(!memcmp(dx[j], dy[j], sizeof(double)),
                    "record %s, field %d differs after the round trip",
                    x->name, j);
    ck_assert_int_eq(x->rule, y->rule);
    ck_assert_int_eq(x->verdict, y->verdict);
  }
  /* malformed buffers: a truncated one, a wrong magic, a renamed case */
  sb_validate_report *bad = sb_validate_report_alloc();
  ck_assert_int_eq(sb_validate_report_append_packed(bad, pa, la - 1),
                   SB_EFORMAT);
  unsigned char *q = malloc(la);
  memcpy(q, pa, la);
  q[0] ^= 1;
  ck_assert_int_eq(sb_validate_report_append_packed(bad, q, la), SB_EFORMAT);
  memcpy(q, pa, la);
  /* the case name follows the magic (8) and the count (8) and its length */
  ck_assert(q[24] == 'V');
  q[24] = 'W';
  ck_assert_int_eq(sb_validate_report_append_packed(bad, q, la), SB_EFORMAT);
  ck_assert_int_eq(sb_validate_report_pack(NULL, &pa, &la), SB_EINVAL);
  ck_assert_int_eq(sb_validate_report_append_packed(NULL, pb, lb),
                   SB_EINVAL);
  free(q);
  free(pa);
  free(pb);
  sb_validate_report_free(a);
  sb_validate_report_free(b);
  sb_validate_report_free(all);
  sb_validate_report_free(g);
  sb_validate_report_free(bad);
}
END_TEST

START_TEST(test_bad_arguments)
{
  sb_validate_options opt;
  sb_validate_options_init(&opt);
  sb_validate_report *rep = sb_validate_report_alloc();
  ck_assert_int_eq(sb_validate_run(sb_validate_ncases(), &opt, rep),
                   SB_EINVAL);
  ck_assert_int_eq(sb_validate_run(0, NULL, rep), SB_EINVAL);
  ck_assert_int_eq(sb_validate_run(0, &opt, NULL), SB_EINVAL);
  ck_assert_uint_eq(sb_validate_report_ncases(rep), 0);
  ck_assert_uint_eq(sb_validate_report_nrecords(NULL), 0);
  sb_validate_report_free(rep);
  sb_validate_report_free(NULL);
}
END_TEST

static Suite *suite(void)
{
  Suite *s = suite_create("validate");
  TCase *tc = tcase_create("registry");
  tcase_set_timeout(tc, 60);
  tcase_add_test(tc, test_registry_lists_cases);
  tcase_add_test(tc, test_run_case_records_and_determinism);
  tcase_add_test(tc, test_plots_and_report_files);
  tcase_add_test(tc, test_pack_and_append);
  tcase_add_test(tc, test_bad_arguments);
  suite_add_tcase(s, tc);
  return s;
}

int main(void) { return sbt_run_suite(suite()); }
