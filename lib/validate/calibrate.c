/* calibrate.c — verdicts checked over many seeds: the records of the same
 * name from independent runs are pooled (mean estimate/reference with its
 * Student interval, fraction of p < 0.05, Kolmogorov-Smirnov test of the
 * p-values against the uniform law), so that a bias hidden by one seed's
 * wide interval shows.  DESIGN: a pooled bias beyond 3 standard errors or
 * non-uniform p-values is a bug in the code or in the reference. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_cdf.h>

#include <smolbridge/validate.h>
#include "common/internal.h"
#include "cases.h"
#include "report.h"

/* A pooled bias fails calibration below this t-test p-value: the
 * two-sided tail of a normal statistic beyond 3 standard errors
 * (DESIGN's rule), with Student's law for the few-seed case. */
#define SBV_BIAS_P 0.0026997960632601866

/* One seed's value of a record. */
typedef struct {
  double est, ref, p;
  sb_verdict verdict;
} obs;

typedef struct {
  char name[96];
  char case_name[96];
  sb_rule rule;
  obs *o;
  size_t n, cap;
} series;

struct sb_validate_calibration {
  series *s;
  size_t n, cap;
  size_t nseeds;
};

sb_validate_calibration *sb_validate_calibration_alloc(void)
{
  sb_validate_calibration *c = calloc(1, sizeof *c);
  if (!c)
    sbi_error(SB_ENOMEM, __func__, "out of memory");
  return c;
}

void sb_validate_calibration_free(sb_validate_calibration *c)
{
  if (!c)
    return;
  for (size_t i = 0; i < c->n; i++)
    free(c->s[i].o);
  free(c->s);
  free(c);
}

static series *find_or_add(sb_validate_calibration *c, const char *name,
                           const char *case_name, sb_rule rule)
{
  for (size_t i = 0; i < c->n; i++)
    if (strcmp(c->s[i].name, name) == 0)
      return &c->s[i];
  if (c->n == c->cap) {
    size_t nc = c->cap ? 2 * c->cap : 64;
    series *ns = realloc(c->s, nc * sizeof *ns);
    if (!ns)
      return NULL;
    c->s = ns;
    c->cap = nc;
  }
  series *s = &c->s[c->n++];
  memset(s, 0, sizeof *s);
  snprintf(s->name, sizeof s->name, "%s", name);
  snprintf(s->case_name, sizeof s->case_name, "%s", case_name);
  s->rule = rule;
  return s;
}

int sb_validate_calibration_add(sb_validate_calibration *c,
                                const sb_validate_report *rep)
{
  if (!c || !rep)
    return sbi_error(SB_EINVAL, __func__, "NULL calibration or report");
  for (size_t k = 0; k < rep->ncases; k++) {
    const struct sbv_case_log *cl = &rep->cases[k];
    for (size_t i = cl->first; i < cl->first + cl->count; i++) {
      const sb_comparison *r = &rep->recs[i];
      series *s = find_or_add(c, r->name, cl->case_name, r->rule);
      if (!s)
        return sbi_error(SB_ENOMEM, __func__, "out of memory");
      if (s->n == s->cap) {
        size_t nc = s->cap ? 2 * s->cap : 16;
        obs *no = realloc(s->o, nc * sizeof *no);
        if (!no)
          return sbi_error(SB_ENOMEM, __func__, "out of memory");
        s->o = no;
        s->cap = nc;
      }
      s->o[s->n++] = (obs){r->estimate, r->reference, r->p_value,
                           r->verdict};
    }
  }
  c->nseeds++;
  return SB_SUCCESS;
}

size_t sb_validate_calibration_nseeds(const sb_validate_calibration *c)
{
  return c ? c->nseeds : 0;
}

size_t sb_validate_calibration_nrows(const sb_validate_calibration *c)
{
  return c ? c->n : 0;
}

static int cmp_double(const void *a, const void *b)
{
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

static double cdf_uniform(double x, void *p)
{
  (void)p;
  return x <= 0.0 ? 0.0 : x >= 1.0 ? 1.0 : x;
}

/* KS of p-values against U(0,1), when they are continuous enough: with
 * fewer than 80% distinct values (discrete tests on small counts, or
 * p = 1 everywhere) the KS p-value would flag the discreteness itself, so
 * it is not computed (NaN). */
static void ks_uniform(double *p, size_t n, double *d, double *pv)
{
  *d = *pv = NAN;
  if (n < 5)
    return;
  qsort(p, n, sizeof *p, cmp_double);
  size_t distinct = 1;
  for (size_t i = 1; i < n; i++)
    distinct += p[i] != p[i - 1];
  if ((double)distinct < 0.8 * (double)n)
    return;
  sb_ks_test(p, n, cdf_uniform, NULL, d, pv);
}

int sb_validate_calibration_get_row(const sb_validate_calibration *c,
                                    size_t i,
                                    sb_validate_calibration_row *row)
{
  if (!c || !row || i >= c->n)
    return sbi_error(SB_EINVAL, __func__, "row %zu out of range", i);
  const series *s = &c->s[i];
  memset(row, 0, sizeof *row);
  snprintf(row->name, sizeof row->name, "%s", s->name);
  snprintf(row->case_name, sizeof row->case_name, "%s", s->case_name);
  row->rule = s->rule;
  row->nseeds = s->n;
  double *x = malloc((s->n ? s->n : 1) * sizeof *x);
  double *p = malloc((s->n ? s->n : 1) * sizeof *p);
  if (!x || !p) {
    free(x);
    free(p);
    return sbi_error(SB_ENOMEM, __func__, "out of memory");
  }
  /* estimate/reference where the reference is a non-zero number,
   * otherwise the plain estimate (pooled as a difference from 0) */
  size_t nx = 0, np = 0;
  int ratio = 1, same = 1;
  for (size_t k = 0; k < s->n; k++) {
    const obs *o = &s->o[k];
    row->nfail += o->verdict == SB_FAIL;
    if (!(isfinite(o->ref) && o->ref != 0.0))
      ratio = 0;
    if (o->est != s->o[0].est)
      same = 0;
    if (!isnan(o->p))
      p[np++] = o->p;
  }
  for (size_t k = 0; k < s->n; k++) {
    const obs *o = &s->o[k];
    double v = ratio ? o->est / o->ref : o->est - o->ref;
    if (isfinite(v))
      x[nx++] = v;
  }
  row->is_ratio = ratio;
  row->deterministic = same && s->n > 1;
  row->mean = row->mean_lo = row->mean_hi = row->bias_z = NAN;
  row->bias_p = NAN;
  if (nx >= 2) {
    double m, lo, hi;
    if (sb_mean_ci(x, nx, 0.95, &m, &lo, &hi) == SB_SUCCESS) {
      row->mean = m;
      row->mean_lo = lo;
      row->mean_hi = hi;
      double nu = (double)(nx - 1);
      double se = (hi - m) / gsl_cdf_tdist_Qinv(0.025, nu);
      double target = ratio ? 1.0 : 0.0;
      row->bias_z = se > 0.0 ? (m - target) / se : (m == target ? 0 : NAN);
      /* two-sided t test of "no bias": with few seeds the t tails are
       * heavier than the normal ones, so the verdict uses this p-value
       * (the level of |z| > 3 for a normal statistic) */
      row->bias_p = isfinite(row->bias_z)
                        ? fmin(1.0, 2.0 * gsl_cdf_tdist_Q(fabs(row->bias_z),
                                                          nu))
                        : NAN;
    }
  } else if (nx == 1) {
    row->mean = x[0];
  }
  row->npvalues = np;
  size_t small = 0;
  for (size_t k = 0; k < np; k++)
    small += p[k] < 0.05;
  row->frac_p05 = np ? (double)small / (double)np : NAN;
  ks_uniform(p, np, &row->ks_d, &row->ks_p);
  free(x);
  free(p);

  /* calibration verdict */
  if (s->rule == SB_RULE_INFO || (row->deterministic && s->rule ==
                                                            SB_RULE_BAND))
    row->verdict = row->nfail ? SB_FAIL : SB_INFO;
  else if (s->rule == SB_RULE_ABOVE || s->rule == SB_RULE_BELOW ||
           s->rule == SB_RULE_BAND)
    row->verdict = row->nfail ? SB_FAIL : SB_PASS;  /* every seed */
  else if (row->deterministic)
    row->verdict = row->nfail ? SB_FAIL : SB_INFO;
  else {
    int biased = !isnan(row->bias_p) && row->bias_p < SBV_BIAS_P;
    int skewed = !isnan(row->ks_p) && row->ks_p < 1e-3;
    row->verdict = (biased || skewed) ? SB_FAIL : SB_PASS;
  }
  return SB_SUCCESS;
}

/* Per case: all p-values of its rows pooled. */
int sb_validate_calibration_case(const sb_validate_calibration *c,
                                 const char *case_name,
                                 sb_validate_calibration_case_summary *sum)
{
  if (!c || !case_name || !sum)
    return sbi_error(SB_EINVAL, __func__, "NULL argument");
  memset(sum, 0, sizeof *sum);
  snprintf(sum->case_name, sizeof sum->case_name, "%s", case_name);
  size_t np = 0;
  for (size_t i = 0; i < c->n; i++)
    if (strcmp(c->s[i].case_name, case_name) == 0)
      np += c->s[i].n;
  double *p = malloc((np ? np : 1) * sizeof *p);
  if (!p)
    return sbi_error(SB_ENOMEM, __func__, "out of memory");
  np = 0;
  size_t small = 0;
  for (size_t i = 0; i < c->n; i++) {
    if (strcmp(c->s[i].case_name, case_name) != 0)
      continue;
    sum->nrows++;
    sb_validate_calibration_row row;
    if (sb_validate_calibration_get_row(c, i, &row) == SB_SUCCESS) {
      sum->nrows_failed += row.verdict == SB_FAIL;
      sum->nrecords_failed += row.nfail;
      sum->nrecords += row.nseeds;
      int stochastic = (row.rule == SB_RULE_COVER ||
                        row.rule == SB_RULE_ACCEPT) && !row.deterministic;
      if (stochastic && isfinite(row.bias_z) &&
          fabs(row.bias_z) > sum->max_abs_bias_z)
        sum->max_abs_bias_z = fabs(row.bias_z);
    }
    for (size_t k = 0; k < c->s[i].n; k++)
      if (!isnan(c->s[i].o[k].p)) {
        small += c->s[i].o[k].p < 0.05;
        p[np++] = c->s[i].o[k].p;
      }
  }
  sum->npvalues = np;
  sum->frac_p05 = np ? (double)small / (double)np : NAN;
  ks_uniform(p, np, &sum->ks_d, &sum->ks_p);
  free(p);
  sum->verdict = sum->nrows_failed ? SB_FAIL : SB_PASS;
  return SB_SUCCESS;
}

static void fmt(char *b, size_t n, double v)
{
  if (isnan(v))
    snprintf(b, n, "nan");
  else
    snprintf(b, n, "%.6g", v);
}

int sb_validate_calibration_write_csv(const sb_validate_calibration *c,
                                      const char *path)
{
  if (!c || !path)
    return sbi_error(SB_EINVAL, __func__, "NULL calibration or path");
  FILE *f = fopen(path, "w");
  if (!f)
    return sbi_error(SB_EIO, __func__, "cannot write '%s'", path);
  fprintf(f, "case,record,rule,seeds,pooled,pooled_lo,pooled_hi,kind,"
             "bias_z,bias_p,npvalues,frac_p05,ks_d,ks_p,nfail,verdict\n");
  for (size_t i = 0; i < c->n; i++) {
    sb_validate_calibration_row r;
    if (sb_validate_calibration_get_row(c, i, &r) != SB_SUCCESS)
      continue;
    char m[32], lo[32], hi[32], z[32], zp[32], f5[32], kd[32], kp[32];
    fmt(zp, sizeof zp, r.bias_p);
    fmt(m, sizeof m, r.mean);
    fmt(lo, sizeof lo, r.mean_lo);
    fmt(hi, sizeof hi, r.mean_hi);
    fmt(z, sizeof z, r.bias_z);
    fmt(f5, sizeof f5, r.frac_p05);
    fmt(kd, sizeof kd, r.ks_d);
    fmt(kp, sizeof kp, r.ks_p);
    int q = strchr(r.name, ',') != NULL;
    fprintf(f, "%s,%s%s%s,%s,%zu,%s,%s,%s,%s,%s,%s,%zu,%s,%s,%s,%zu,%s\n",
            r.case_name, q ? "\"" : "", r.name, q ? "\"" : "",
            sb_rule_name(r.rule), r.nseeds, m, lo, hi,
            r.deterministic ? "deterministic"
                            : (r.is_ratio ? "est/ref" : "est-ref"),
            z, zp, r.npvalues, f5, kd, kp, r.nfail,
            sb_verdict_name(r.verdict));
  }
  if (fclose(f) != 0)
    return sbi_error(SB_EIO, __func__, "cannot write '%s'", path);
  return SB_SUCCESS;
}

int sb_validate_calibration_fprint(const sb_validate_calibration *c,
                                   FILE *out)
{
  if (!c || !out)
    return sbi_error(SB_EINVAL, __func__, "NULL calibration or stream");
  fprintf(out, "%-44s %5s %25s %7s %6s %8s %5s %s\n", "record", "seeds",
          "pooled est/ref [95%]", "bias z", "p<.05", "KS p", "fails",
          "verdict");
  for (size_t i = 0; i < c->n; i++) {
    sb_validate_calibration_row r;
    if (sb_validate_calibration_get_row(c, i, &r) != SB_SUCCESS)
      continue;
    char pooled[64], z[32], f5[32], kp[32];
    if (r.deterministic)
      snprintf(pooled, sizeof pooled, "deterministic");
    else if (isnan(r.mean_lo))
      snprintf(pooled, sizeof pooled, "-");
    else
      snprintf(pooled, sizeof pooled, "%s%.4f [%.4f, %.4f]",
               r.is_ratio ? "" : "d ", r.mean, r.mean_lo, r.mean_hi);
    fmt(z, sizeof z, r.bias_z);
    fmt(f5, sizeof f5, r.frac_p05);
    fmt(kp, sizeof kp, r.ks_p);
    fprintf(out, "%-44s %5zu %25s %7.7s %6.6s %8.8s %5zu %s\n", r.name,
            r.nseeds, pooled, z, f5, kp, r.nfail,
            r.verdict == SB_FAIL ? "FAIL" : sb_verdict_name(r.verdict));
  }
  return ferror(out) ? sbi_error(SB_EIO, __func__, "write error")
                     : SB_SUCCESS;
}

/* Names of the cases present, in first-seen order; returns the count. */
static size_t case_names(const sb_validate_calibration *c,
                         const char **names, size_t cap)
{
  size_t n = 0;
  for (size_t i = 0; i < c->n; i++) {
    size_t k = 0;
    while (k < n && strcmp(names[k], c->s[i].case_name) != 0)
      k++;
    if (k == n && n < cap)
      names[n++] = c->s[i].case_name;
  }
  return n;
}

size_t sb_validate_calibration_ncases(const sb_validate_calibration *c)
{
  if (!c)
    return 0;
  const char *names[256];
  return case_names(c, names, 256);
}

const char *sb_validate_calibration_case_name(
    const sb_validate_calibration *c, size_t k)
{
  if (!c)
    return NULL;
  const char *names[256];
  size_t n = case_names(c, names, 256);
  return k < n ? names[k] : NULL;
}

int sb_validate_calibration_qq_plot(const sb_validate_calibration *c,
                                    const sb_validate_options *opt,
                                    const char *name)
{
  if (!c || !opt || !name)
    return sbi_error(SB_EINVAL, __func__, "NULL argument");
  if (!opt->outdir)
    return SB_SUCCESS;
  char path[1100];
  snprintf(path, sizeof path, "%s/%s.dat", opt->outdir, name);
  FILE *f = fopen(path, "w");
  if (!f)
    return sbi_error(SB_EIO, __func__, "cannot write '%s'", path);
  const char *names[256];
  size_t nc = case_names(c, names, 256), nblocks = 0;
  fprintf(f, "# p-value QQ data: per case (one block each), the sorted "
             "p-values of all its records over %zu seeds against the "
             "uniform quantiles (i - 1/2)/n\n", c->nseeds);
  char titles[4096] = "";
  for (size_t k = 0; k < nc; k++) {
    size_t np = 0;
    for (size_t i = 0; i < c->n; i++)
      if (strcmp(c->s[i].case_name, names[k]) == 0)
        np += c->s[i].n;
    double *p = malloc((np ? np : 1) * sizeof *p);
    if (!p) {
      fclose(f);
      return sbi_error(SB_ENOMEM, __func__, "out of memory");
    }
    np = 0;
    for (size_t i = 0; i < c->n; i++)
      if (strcmp(c->s[i].case_name, names[k]) == 0)
        for (size_t q = 0; q < c->s[i].n; q++)
          if (!isnan(c->s[i].o[q].p))
            p[np++] = c->s[i].o[q].p;
    if (np > 0) {
      qsort(p, np, sizeof *p, cmp_double);
      fprintf(f, "# %s\n", names[k]);
      for (size_t q = 0; q < np; q++)
        fprintf(f, "%.6g %.6g\n", ((double)q + 0.5) / (double)np, p[q]);
      fprintf(f, "\n\n");
      size_t len = strlen(titles);
      snprintf(titles + len, sizeof titles - len, "%s%s", nblocks ? " " : "",
               names[k]);
      nblocks++;
    }
    free(p);
  }
  if (fclose(f) != 0)
    return sbi_error(SB_EIO, __func__, "cannot write '%s'", path);
  snprintf(path, sizeof path, "%s/%s.gp", opt->outdir, name);
  f = fopen(path, "w");
  if (!f)
    return sbi_error(SB_EIO, __func__, "cannot write '%s'", path);
  fprintf(f, "# gnuplot script written by smolbridge validate --seeds; run "
             "it in this directory.\n"
             "set terminal pngcairo size 960,720 noenhanced\n"
             "set output '%s.png'\n"
             "set title 'p-values over %zu seeds: uniform quantile vs "
             "observed (on the diagonal when calibrated)'\n"
             "set xlabel 'uniform quantile'\nset ylabel 'p-value'\n"
             "set key outside right\nset grid\nset size ratio -1\n"
             "cases = '%s'\n"
             "plot for [i=0:%zu] '%s.dat' index i u 1:2 w l "
             "t word(cases, i+1), x lc rgb 'black' dt 2 t 'uniform'\n",
          name, c->nseeds, titles, nblocks ? nblocks - 1 : 0, name);
  if (fclose(f) != 0)
    return sbi_error(SB_EIO, __func__, "cannot write '%s'", path);
  if (opt->render && nblocks > 0) {
    char script[1040];
    snprintf(script, sizeof script, "%s.gp", name);
    opt->render(opt->outdir, script, opt->render_data);
  }
  return SB_SUCCESS;
}
