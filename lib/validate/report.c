/* report.c — collects comparison records, notes and plots of validation
 * cases, and writes the table, validate.csv and report.md. */
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include <smolbridge/common.h>
#include <smolbridge/validate.h>
#include "common/internal.h"
#include "cases.h"
#include "report.h"

sbv_report *sb_validate_report_alloc(void)
{
  sbv_report *rep = calloc(1, sizeof(sbv_report));
  if (!rep)
    sbi_error(SB_ENOMEM, __func__, "out of memory");
  return rep;
}

void sb_validate_report_free(sbv_report *rep)
{
  if (!rep)
    return;
  for (size_t i = 0; i < rep->ncases; i++)
    free(rep->cases[i].notes);
  free(rep->cases);
  free(rep->recs);
  free(rep);
}

static int grow(void **p, size_t *cap, size_t need, size_t size)
{
  if (need <= *cap)
    return SB_SUCCESS;
  size_t ncap = *cap ? 2 * *cap : 16;
  while (ncap < need)
    ncap *= 2;
  void *q = realloc(*p, ncap * size);
  if (!q)
    return SB_ENOMEM;
  *p = q;
  *cap = ncap;
  return SB_SUCCESS;
}

int sbv_report_begin_case(sbv_report *rep, const char *name)
{
  if (grow((void **)&rep->cases, &rep->capcases, rep->ncases + 1,
           sizeof *rep->cases))
    return SB_ENOMEM;
  struct sbv_case_log *c = &rep->cases[rep->ncases++];
  memset(c, 0, sizeof *c);
  c->case_name = name;
  c->first = rep->nrecs;
  return SB_SUCCESS;
}

void sbv_report_end_case(sbv_report *rep, int status, double seconds)
{
  if (rep->ncases == 0)
    return;
  struct sbv_case_log *c = &rep->cases[rep->ncases - 1];
  c->count = rep->nrecs - c->first;
  c->status = status;
  c->seconds = seconds;
  snprintf(c->message, sizeof c->message, "%s",
           status != SB_SUCCESS ? sb_last_error() : "");
}

int sbv_add(sbv_report *rep, const sb_comparison *c)
{
  if (grow((void **)&rep->recs, &rep->caprecs, rep->nrecs + 1,
           sizeof *rep->recs))
    return SB_ENOMEM;
  rep->recs[rep->nrecs++] = *c;
  if (rep->ini_path[0] && rep->ini_field[0]) {
    /* write mode: the run returned unit values, so the estimate is the
     * factor between the summary field and the record */
    sbv_ini_expect(rep, c->name, rep->ini_field, c->estimate);
    rep->ini_field[0] = 0;
  }
  return SB_SUCCESS;
}

void sbv_note(sbv_report *rep, const char *fmt, ...)
{
  if (rep->ncases == 0)
    return;
  struct sbv_case_log *c = &rep->cases[rep->ncases - 1];
  char line[1024];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(line, sizeof line, fmt, ap);
  va_end(ap);
  size_t old = c->notes ? strlen(c->notes) : 0;
  char *n = realloc(c->notes, old + strlen(line) + 2);
  if (!n)
    return; /* a lost note is not worth failing the run */
  memcpy(n + old, line, strlen(line));
  n[old + strlen(line)] = '\n';
  n[old + strlen(line) + 1] = '\0';
  c->notes = n;
}

size_t sb_validate_report_nrecords(const sbv_report *rep)
{
  return rep ? rep->nrecs : 0;
}

const sb_comparison *sb_validate_report_record(const sbv_report *rep,
                                               size_t i)
{
  if (!rep || i >= rep->nrecs) {
    sbi_error(SB_EINVAL, __func__, "record %zu out of range", i);
    return NULL;
  }
  return &rep->recs[i];
}

size_t sb_validate_report_ncases(const sbv_report *rep)
{
  return rep ? rep->ncases : 0;
}

static const struct sbv_case_log *case_log(const sbv_report *rep, size_t k,
                                           const char *func)
{
  if (!rep || k >= rep->ncases) {
    sbi_error(SB_EINVAL, func, "case %zu out of range", k);
    return NULL;
  }
  return &rep->cases[k];
}

const char *sb_validate_report_case_name(const sbv_report *rep, size_t k)
{
  const struct sbv_case_log *c = case_log(rep, k, __func__);
  return c ? c->case_name : NULL;
}

int sb_validate_report_case_status(const sbv_report *rep, size_t k)
{
  const struct sbv_case_log *c = case_log(rep, k, __func__);
  return c ? c->status : SB_EINVAL;
}

double sb_validate_report_case_seconds(const sbv_report *rep, size_t k)
{
  const struct sbv_case_log *c = case_log(rep, k, __func__);
  return c ? c->seconds : NAN;
}

const char *sb_validate_report_case_notes(const sbv_report *rep, size_t k)
{
  const struct sbv_case_log *c = case_log(rep, k, __func__);
  return c ? (c->notes ? c->notes : "") : NULL;
}

size_t sb_validate_report_case_records(const sbv_report *rep, size_t k,
                                       size_t *first)
{
  const struct sbv_case_log *c = case_log(rep, k, __func__);
  if (first)
    *first = c ? c->first : 0;
  return c ? c->count : 0;
}

size_t sb_validate_report_nfailed(const sbv_report *rep)
{
  if (!rep)
    return 0;
  size_t nfail = 0;
  for (size_t i = 0; i < rep->nrecs; i++)
    nfail += rep->recs[i].verdict == SB_FAIL;
  for (size_t i = 0; i < rep->ncases; i++)
    nfail += rep->cases[i].status != SB_SUCCESS;
  return nfail;
}

static const char *verdict_text(sb_verdict v)
{
  return v == SB_PASS ? "pass" : v == SB_INFO ? "info" : "FAIL";
}

static void fmt_num(char *buf, size_t len, double x)
{
  if (isnan(x))
    snprintf(buf, len, "-");
  else
    snprintf(buf, len, "%.6g", x);
}

int sb_validate_report_fprint(const sbv_report *rep, FILE *out)
{
  if (!rep || !out)
    return sbi_error(SB_EINVAL, __func__, "NULL report or stream");
  fprintf(out, "%-44s %12s %12s %27s %9s %-22s %s\n", "case", "estimate",
          "reference", "interval", "p-value", "rule", "verdict");
  for (size_t i = 0; i < rep->nrecs; i++) {
    const sb_comparison *c = &rep->recs[i];
    char e[32], r[32], lo[32], hi[32], p[32], iv[72], rule[48];
    fmt_num(e, sizeof e, c->estimate);
    fmt_num(r, sizeof r, c->reference);
    fmt_num(lo, sizeof lo, c->ci_low);
    fmt_num(hi, sizeof hi, c->ci_high);
    fmt_num(p, sizeof p, c->p_value);
    if (isnan(c->ci_low) && isnan(c->ci_high))
      snprintf(iv, sizeof iv, "-");
    else
      snprintf(iv, sizeof iv, "[%s, %s]", lo, hi);
    sb_comparison_rule_text(c, rule, sizeof rule);
    fprintf(out, "%-44s %12s %12s %27s %9s %-22s %s\n", c->name, e, r, iv, p,
            rule, verdict_text(c->verdict));
  }
  for (size_t i = 0; i < rep->ncases; i++)
    if (rep->cases[i].status != SB_SUCCESS)
      fprintf(out, "%-44s did not complete: %s%s%s\n",
              rep->cases[i].case_name, sb_strerror(rep->cases[i].status),
              rep->cases[i].message[0] ? ": " : "", rep->cases[i].message);
  if (ferror(out))
    return sbi_error(SB_EIO, __func__, "write error");
  return SB_SUCCESS;
}

int sb_validate_report_write_csv(const sbv_report *rep, const char *path)
{
  if (!rep || !path)
    return sbi_error(SB_EINVAL, __func__, "NULL report or path");
  FILE *f = fopen(path, "w");
  if (!f)
    return sbi_error(SB_EIO, __func__, "cannot write '%s'", path);
  fprintf(f, "%s\n", SB_COMPARISON_CSV_HEADER);
  char line[512];
  for (size_t i = 0; i < rep->nrecs; i++) {
    sb_comparison_csv(&rep->recs[i], line, sizeof line);
    fprintf(f, "%s\n", line);
  }
  if (fclose(f) != 0)
    return sbi_error(SB_EIO, __func__, "cannot write '%s'", path);
  return SB_SUCCESS;
}

int sb_validate_report_write_markdown(const sbv_report *rep, const char *path,
                                      const sb_validate_options *opt)
{
  if (!rep || !path || !opt)
    return sbi_error(SB_EINVAL, __func__, "NULL report, path or options");
  FILE *f = fopen(path, "w");
  if (!f)
    return sbi_error(SB_EIO, __func__, "cannot write '%s'", path);
  const char *mode = opt->full ? "full" : "quick";
  unsigned long seed = opt->seed;
  size_t nfail = sb_validate_report_nfailed(rep);
  fprintf(f, "# smolbridge validation report\n\n");
  fprintf(f, "smolbridge %s, mode `%s`, seed %lu: %zu comparisons, %zu "
             "failed.\n\n",
          sb_version(), mode, seed, rep->nrecs, nfail);
  fprintf(f,
          "Each row states the rule that gives its verdict, and the "
          "interval printed is the one that rule reads:\n\n"
          "- `ref in X%% CI`: pass iff the reference lies in the confidence "
          "interval of the estimate at level X (exact Poisson, binomial or "
          "Student intervals; the p-value is that of the test the interval "
          "inverts, so p >= 1 - X iff pass);\n"
          "- `est in X%% acceptance`: a goodness-of-fit statistic (KS "
          "distance, chi-square) must lie in the region that holds it with "
          "probability X when the reference law is true;\n"
          "- `ref in tolerance band`: a deterministic number within the "
          "stated numerical tolerance;\n"
          "- `X%% CI above ref` / `below ref`: the demonstration of an "
          "expected failure of an approximate method;\n"
          "- `informational`: a descriptive row, no verdict.\n\n"
          "Tests run at alpha = 1e-4 per row unless a case says otherwise, "
          "so a correct code fails a quick run (~250 rows) with probability "
          "about 2.5%%.\n\n");
  for (size_t k = 0; k < rep->ncases; k++) {
    const struct sbv_case_log *c = &rep->cases[k];
    fprintf(f, "## %s\n\n", c->case_name);
    if (c->status != SB_SUCCESS)
      fprintf(f, "**Did not complete:** %s%s%s.\n\n", sb_strerror(c->status),
              c->message[0] ? ": " : "", c->message);
    if (c->notes)
      fprintf(f, "%s\n", c->notes);
    fprintf(f, "| case | estimate | reference | interval | p-value | rule | "
               "verdict |\n|---|---|---|---|---|---|---|\n");
    for (size_t i = c->first; i < c->first + c->count; i++) {
      const sb_comparison *r = &rep->recs[i];
      char e[32], ref[32], lo[32], hi[32], p[32], rule[48];
      fmt_num(e, sizeof e, r->estimate);
      fmt_num(ref, sizeof ref, r->reference);
      fmt_num(lo, sizeof lo, r->ci_low);
      fmt_num(hi, sizeof hi, r->ci_high);
      fmt_num(p, sizeof p, r->p_value);
      sb_comparison_rule_text(r, rule, sizeof rule);
      fprintf(f, "| %s | %s | %s | [%s, %s] | %s | %s | %s |\n", r->name, e,
              ref, lo, hi, p, rule, verdict_text(r->verdict));
    }
    fprintf(f, "\n_%.1f s_\n\n", c->seconds);
  }
  if (fclose(f) != 0)
    return sbi_error(SB_EIO, __func__, "cannot write '%s'", path);
  return SB_SUCCESS;
}
