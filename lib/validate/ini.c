/* ini.c — write mode of the validation cases: instead of running an
 * engine run, a case writes it as a `smolbridge collide` configuration,
 * with comment lines that say which summary.json field gives each record
 * of the case (sb_validate_write_ini; docs/validation.md). */
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include <smolbridge/validate.h>
#include "common/internal.h"
#include "cases.h"
#include "report.h"

int sbv_writing(const sbv_ctx *ctx) { return ctx->ini_dir != NULL; }

FILE *sbv_ini_begin(const sbv_ctx *ctx, sbv_report *rep, const char *run,
                    const char *what)
{
  char name[128];
  snprintf(name, sizeof name, "%s", run);
  for (char *p = name; *p; p++)  /* a file name */
    if (!((*p >= 'a' && *p <= 'z') || (*p >= 'A' && *p <= 'Z') ||
          (*p >= '0' && *p <= '9') || *p == '.' || *p == '-' || *p == '_'))
      *p = '_';
  snprintf(rep->ini_path, sizeof rep->ini_path, "%s/%s.ini", ctx->ini_dir,
           name);
  rep->ini_field[0] = 0;
  FILE *f = fopen(rep->ini_path, "w");
  if (!f) {
    sbi_error(SB_EIO, "sb_validate_write_ini", "cannot write '%s'",
              rep->ini_path);
    rep->ini_path[0] = 0;
    return NULL;
  }
  fprintf(f, "; %s\n; written by: smolbridge validate --case %s "
          "--write-ini (%s, seed %lu)\n; run: smolbridge collide %s.ini\n"
          "; the same seed gives the same estimate: each 'expect' line "
          "names a\n; record of the case and the summary.json field (times "
          "a factor) that gives it\n", what,
          rep->ncases ? rep->cases[rep->ncases - 1].case_name : "?",
          ctx->full ? "--full" : "--quick", ctx->seed, name);
  fprintf(f, "[run]\noutput = %s-out\n", name);
  rep->nini++;
  return f;
}

int sbv_ini_end(sbv_report *rep, FILE *f, const char *field)
{
  snprintf(rep->ini_field, sizeof rep->ini_field, "%s", field ? field : "");
  if (fclose(f))
    return sbi_error(SB_EIO, "sb_validate_write_ini", "write error on '%s'",
                     rep->ini_path);
  return SB_SUCCESS;
}

void sbv_ini_no_expect(sbv_report *rep) { rep->ini_field[0] = 0; }

static void expect_line(sbv_report *rep, const char *kind,
                        const char *record, const char *field, double factor)
{
  if (!rep->ini_path[0])
    return;
  FILE *f = fopen(rep->ini_path, "a");
  if (!f)
    return;
  if (factor == 1.0)
    fprintf(f, "; %s %s = %s\n", kind, record, field);
  else
    fprintf(f, "; %s %s = %s * %.17g\n", kind, record, field, factor);
  fclose(f);
}

void sbv_ini_expect(sbv_report *rep, const char *record, const char *field,
                    double factor)
{
  expect_line(rep, "expect", record, field, factor);
}

void sbv_ini_expect_mean(sbv_report *rep, const char *record,
                         const char *field, double factor)
{
  expect_line(rep, "expect-mean", record, field, factor);
}

void sbv_ini_expect_grid(sbv_report *rep, const char *record,
                         const char *stat, int frame, const char *ref,
                         double factor)
{
  char field[400];
  snprintf(field, sizeof field, "grid.csv %s %d %s", stat, frame, ref);
  expect_line(rep, "expect-grid", record, field, factor);
}

void sbv_ini_expect_sweep_mean(sbv_report *rep, const char *record,
                               const char *field, double factor)
{
  expect_line(rep, "expect-sweep-mean", record, field, factor);
}

/* Point k of the ensemble of the file begun last: a line of overrides in
 * NAME.sweep.txt (created at k = 0, with a line in NAME.ini saying how to
 * run it). */
int sbv_ini_sweep_point(sbv_report *rep, size_t k, const char *fmt, ...)
{
  char path[1100];
  size_t n = strlen(rep->ini_path);
  if (n < 4 || strcmp(rep->ini_path + n - 4, ".ini"))
    return sbi_error(SB_EINVAL, "sb_validate_write_ini", "no file begun");
  snprintf(path, sizeof path, "%.*s.sweep.txt", (int)(n - 4), rep->ini_path);
  const char *base = strrchr(path, '/') ? strrchr(path, '/') + 1 : path;
  if (k == 0) {
    FILE *g = fopen(rep->ini_path, "a");
    int bad = !g || fprintf(g, "; an ensemble: smolbridge collide %.*s.ini "
                            "--sweep %s (one run per line);\n; "
                            "'expect-sweep-mean': the record is the mean "
                            "over the runs (OUTPUT/point_NNN/summary.json)"
                            "\n", (int)(strlen(base) - 10), base,
                            base) < 0;
    if (g)
      bad |= fclose(g) != 0;
    if (bad)
      return sbi_error(SB_EIO, "sb_validate_write_ini", "cannot write '%s'",
                       rep->ini_path);
  }
  FILE *f = fopen(path, k == 0 ? "w" : "a");
  if (!f)
    return sbi_error(SB_EIO, "sb_validate_write_ini", "cannot write '%s'",
                     path);
  int bad = k == 0 && fprintf(f, "# overrides of the runs of %.*s.ini, "
                              "one run per line\n",
                              (int)(strlen(base) - 10), base) < 0;
  va_list ap;
  va_start(ap, fmt);
  bad |= vfprintf(f, fmt, ap) < 0;
  va_end(ap);
  bad |= fputc('\n', f) == EOF;
  bad |= fclose(f) != 0;
  return bad ? sbi_error(SB_EIO, "sb_validate_write_ini", "write error on "
                         "'%s'", path)
             : SB_SUCCESS;
}

void sbv_ini_expect_stat(sbv_report *rep, const char *kind,
                         const char *record, const char *spec)
{
  expect_line(rep, kind, record, spec, 1.0);
}

void sbv_ini_skip(sbv_report *rep, const char *fmt, ...)
{
  char line[400];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(line, sizeof line, fmt, ap);
  va_end(ap);
  size_t n = strlen(rep->ini_skipped);
  snprintf(rep->ini_skipped + n, sizeof rep->ini_skipped - n, "%s\n", line);
}
