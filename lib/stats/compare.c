/* compare.c — comparison records of validation reports: one estimate
 * against its reference, the interval the verdict uses, the rule that
 * turns them into a verdict, and CSV output.  docs/stats.md. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_cdf.h>
#include <gsl/gsl_statistics_double.h>
#include <gsl/gsl_math.h>

#include "common/internal.h"
#include <smolbridge/stats.h>

/* Copy name into c->name; 1 if truncated. */
static int set_name(sb_comparison *c, const char *name)
{
  size_t cap = sizeof c->name;
  size_t len = strlen(name);
  size_t k = len < cap - 1 ? len : cap - 1;
  memcpy(c->name, name, k);
  c->name[k] = '\0';
  return len > k;
}

static int valid_rule(int r)
{
  return r >= SB_RULE_COVER && r <= SB_RULE_INFO;
}

/* The verdict of a filled record (NaN in a field the rule reads fails). */
static sb_verdict judge(const sb_comparison *c)
{
  double e = c->estimate, r = c->reference, lo = c->ci_low, hi = c->ci_high;
  switch (c->rule) {
  case SB_RULE_COVER:
  case SB_RULE_BAND:
    return (lo <= r && r <= hi) ? SB_PASS : SB_FAIL;
  case SB_RULE_ACCEPT:
    return (lo <= e && e <= hi) ? SB_PASS : SB_FAIL;
  case SB_RULE_ABOVE:
    return r < lo ? SB_PASS : SB_FAIL;
  case SB_RULE_BELOW:
    return hi < r ? SB_PASS : SB_FAIL;
  case SB_RULE_INFO:
  default:
    return SB_INFO;
  }
}

int sb_compare(sb_comparison *c, const char *name, sb_rule rule,
               double estimate, double reference, double ci_low,
               double ci_high, double level, double p_value)
{
  if (!c)
    return sbi_error(SB_EINVAL, __func__, "NULL record");
  c->estimate = estimate;
  c->reference = reference;
  c->ci_low = ci_low;
  c->ci_high = ci_high;
  c->level = level;
  c->p_value = p_value;
  c->rule = valid_rule((int)rule) ? rule : SB_RULE_INFO;
  c->verdict = SB_FAIL;
  c->name[0] = '\0';
  if (!name)
    return sbi_error(SB_EINVAL, __func__, "NULL name");
  int trunc = set_name(c, name);
  if (!valid_rule((int)rule))
    return sbi_error(SB_EINVAL, __func__, "unknown rule %d", (int)rule);
  if (ci_low > ci_high)
    return sbi_error(SB_EINVAL, __func__, "ci_low %g > ci_high %g", ci_low,
                     ci_high);
  int needs_level = rule == SB_RULE_COVER || rule == SB_RULE_ACCEPT ||
                    rule == SB_RULE_ABOVE || rule == SB_RULE_BELOW;
  if (needs_level && !(level > 0.0 && level < 1.0))
    return sbi_error(SB_EINVAL, __func__,
                     "level = %g not in (0,1) for this rule", level);
  if (!isnan(p_value) && !(p_value >= 0.0 && p_value <= 1.0))
    return sbi_error(SB_EINVAL, __func__, "p_value = %g not in [0,1]",
                     p_value);
  c->verdict = judge(c);
  if (trunc)
    return sbi_error(SB_ELOSS, __func__, "name truncated to %zu bytes",
                     sizeof c->name - 1);
  return SB_SUCCESS;
}

int sb_compare_poisson(sb_comparison *c, const char *name, unsigned long k,
                       double scale, double reference, double alpha)
{
  if (!c)
    return sbi_error(SB_EINVAL, __func__, "NULL record");
  if (!(scale > 0.0 && isfinite(scale)) || !(reference >= 0.0) ||
      !isfinite(reference) || !(alpha > 0.0 && alpha < 1.0)) {
    sb_compare(c, name ? name : "", SB_RULE_COVER, NAN, reference, NAN, NAN,
               0.95, NAN);
    return sbi_error(SB_EINVAL, __func__,
                     "need scale = %g > 0, reference = %g >= 0 and "
                     "0 < alpha = %g < 1", scale, reference, alpha);
  }
  double lo, hi, mu = reference / scale;
  int st = sb_poisson_rate_ci(k, scale, 1.0 - alpha, &lo, &hi);
  /* a mean beyond DBL_MAX puts any count in the far lower tail: p = 0 */
  double p = isinf(mu) ? 0.0 : sb_poisson_pvalue(k, mu);
  if (st != SB_SUCCESS || isnan(p)) {
    int why = st != SB_SUCCESS ? st : sb_last_status();
    sb_compare(c, name ? name : "", SB_RULE_COVER, scale * (double)k,
               reference, NAN, NAN, 1.0 - alpha, NAN);
    return why;
  }
  /* p >= alpha <=> reference inside the Garwood (1 - alpha) interval (the
   * interval inverts the same equal-tailed test): verdict and interval
   * agree by construction. */
  return sb_compare(c, name, SB_RULE_COVER, scale * (double)k, reference,
                    lo, hi, 1.0 - alpha, p);
}

int sb_compare_poisson_dispersed(sb_comparison *c, const char *name,
                                 unsigned long k, double dispersion,
                                 double scale, double reference,
                                 double alpha)
{
  if (dispersion == HUGE_VAL) {
    if (c)
      sb_compare(c, name ? name : "", SB_RULE_COVER, NAN, reference, NAN,
                 NAN, 0.95, NAN);
    return sbi_error(SB_EINVAL, __func__, "dispersion = inf");
  }
  if (!(dispersion > 1.0))
    return sb_compare_poisson(c, name, k, scale, reference, alpha);
  int st = sb_compare_poisson(c, name, k, scale, reference, alpha);
  if (st != SB_SUCCESS && st != SB_ELOSS)
    return st;
  /* the Garwood interval of k widened about k by w; the p-value of the
   * exact test at the reference brought back towards k by the same factor,
   * so that p >= alpha <=> the reference lies in the widened interval */
  const double w = sqrt(dispersion), K = (double)k;
  double l, u, lo, hi;
  st = sb_poisson_ci(k, 1.0 - alpha, &l, &u);
  if (!st)
    st = sb_poisson_ci_dispersed(k, dispersion, 1.0 - alpha, &lo, &hi);
  if (st)
    return st;
  double mu = K + (reference / scale - K) / w;
  if (lo == 0.0 && mu < l)  /* clipped: every rate down to 0 is inside */
    mu = l;
  const double p = isinf(mu) ? 0.0 : sb_poisson_pvalue(k, mu);
  return sb_compare(c, name, SB_RULE_COVER, scale * K, reference,
                    scale * lo, scale * hi, 1.0 - alpha, isnan(p) ? NAN : p);
}

int sb_compare_binomial(sb_comparison *c, const char *name, unsigned long k,
                        unsigned long n, double reference, double alpha)
{
  if (!c)
    return sbi_error(SB_EINVAL, __func__, "NULL record");
  if (n == 0 || k > n || !(reference >= 0.0 && reference <= 1.0) ||
      !(alpha > 0.0 && alpha < 1.0)) {
    sb_compare(c, name ? name : "", SB_RULE_COVER, NAN, reference, NAN, NAN,
               0.95, NAN);
    return sbi_error(SB_EINVAL, __func__,
                     "need 0 <= k <= n, n >= 1, reference in [0,1], "
                     "0 < alpha < 1 (k = %lu, n = %lu, reference = %g, "
                     "alpha = %g)", k, n, reference, alpha);
  }
  double lo, hi;
  int st = sb_binomial_ci(k, n, 1.0 - alpha, &lo, &hi);
  double p = sb_binomial_pvalue(k, n, reference);
  double est = (double)k / (double)n;
  if (st != SB_SUCCESS || isnan(p)) {
    int why = st != SB_SUCCESS ? st : sb_last_status();
    sb_compare(c, name ? name : "", SB_RULE_COVER, est, reference, NAN, NAN,
               1.0 - alpha, NAN);
    return why;
  }
  /* Clopper-Pearson inverts the same equal-tailed test: p >= alpha <=>
   * reference in [lo, hi]. */
  return sb_compare(c, name, SB_RULE_COVER, est, reference, lo, hi,
                    1.0 - alpha, p);
}

int sb_compare_mean(sb_comparison *c, const char *name, const double *x,
                    size_t n, double reference, double alpha)
{
  if (!c)
    return sbi_error(SB_EINVAL, __func__, "NULL record");
  double m = NAN, lo = NAN, hi = NAN;
  int st = SB_EINVAL;
  if (x && n >= 2 && alpha > 0.0 && alpha < 1.0 && isfinite(reference))
    st = sb_mean_ci(x, n, 1.0 - alpha, &m, &lo, &hi);
  if (st != SB_SUCCESS) {
    sb_compare(c, name ? name : "", SB_RULE_COVER, m, reference, NAN, NAN,
               0.95, NAN);
    if (st == SB_ERANGE)
      return sbi_error(st, __func__, "%s", sb_last_error());
    return sbi_error(SB_EINVAL, __func__,
                     "need n >= 2 finite samples, a finite reference and "
                     "0 < alpha < 1 (n = %zu, alpha = %g)", n, alpha);
  }
  /* Two-sided one-sample t test; consistent with the t interval. */
  double half = hi - m, p;
  if (alpha > 1.0 - 1e-8) {
    /* level < 1e-8: the interval is narrower than the rounding of m (and
     * its quantile is not GSL's): t from the standard error itself */
    double se = gsl_stats_sd_m(x, 1, n, m) / sqrt((double)n);
    double t = fabs(m - reference) / se;
    p = se > 0.0 ? 2.0 * gsl_cdf_tdist_Q(t, (double)(n - 1))
                 : (m == reference ? 1.0 : 0.0);
    if (p > 1.0)
      p = 1.0;
  } else if (half > 0.0) {
    double nu = (double)(n - 1);
    double tq = n == 2 ? 1.0 / tan(M_PI * 0.5 * alpha)
                       : gsl_cdf_tdist_Qinv(0.5 * alpha, nu);
    double t = fabs(m - reference) * tq / half;
    p = 2.0 * gsl_cdf_tdist_Q(t, nu);
    if (p > 1.0)
      p = 1.0;
  } else {
    p = m == reference ? 1.0 : 0.0;
  }
  return sb_compare(c, name, SB_RULE_COVER, m, reference, lo, hi,
                    1.0 - alpha, p);
}

const char *sb_rule_name(sb_rule rule)
{
  switch (rule) {
  case SB_RULE_COVER: return "cover";
  case SB_RULE_ACCEPT: return "accept";
  case SB_RULE_BAND: return "band";
  case SB_RULE_ABOVE: return "above";
  case SB_RULE_BELOW: return "below";
  case SB_RULE_INFO: return "info";
  }
  return "unknown";
}

const char *sb_verdict_name(sb_verdict v)
{
  switch (v) {
  case SB_PASS: return "pass";
  case SB_FAIL: return "fail";
  case SB_INFO: return "info";
  }
  return "unknown";
}

/* "99.9%" or "95%": the level as the shortest percentage that keeps both
 * the level and 1 - level to 3 digits (0.999999999 is "99.9999999%", not
 * "1e+02%"; 1e-300 is "1e-298%"). */
static void fmt_level(char *buf, size_t len, double level)
{
  char tmp[32];
  double tol = fmin(1e-9 * 100.0, fabs(1e-3 * 100.0 * fmin(level, 1.0 -
                                                            level)));
  for (int prec = 1; prec <= 17; prec++) {
    snprintf(tmp, sizeof tmp, "%.*g", prec, 100.0 * level);
    if (fabs(strtod(tmp, NULL) - 100.0 * level) <= tol)
      break;
  }
  snprintf(buf, len, "%s%%", tmp);
}

int sb_comparison_rule_text(const sb_comparison *c, char *buf, size_t len)
{
  if (!c) {
    sbi_error(SB_EINVAL, __func__, "NULL record");
    return -1;
  }
  char lv[40];
  fmt_level(lv, sizeof lv, c->level);
  switch (c->rule) {
  case SB_RULE_COVER:
    return snprintf(buf, len, "ref in %s CI", lv);
  case SB_RULE_ACCEPT:
    return snprintf(buf, len, "est in %s acceptance", lv);
  case SB_RULE_BAND:
    return snprintf(buf, len, "ref in tolerance band");
  case SB_RULE_ABOVE:
    return snprintf(buf, len, "%s CI above ref", lv);
  case SB_RULE_BELOW:
    return snprintf(buf, len, "%s CI below ref", lv);
  case SB_RULE_INFO:
    return snprintf(buf, len, "informational");
  }
  return snprintf(buf, len, "unknown");
}

/* Shortest of %.15g, %.16g, %.17g that reads back to v; "nan", "inf". */
static void fmt_num(char *out, size_t len, double v)
{
  if (isnan(v)) {
    snprintf(out, len, "nan");
    return;
  }
  if (isinf(v)) {
    snprintf(out, len, v > 0 ? "inf" : "-inf");
    return;
  }
  for (int prec = 15; prec <= 17; prec++) {
    snprintf(out, len, "%.*g", prec, v);
    if (strtod(out, NULL) == v)
      break;
  }
  /* A locale with a decimal comma must not split the CSV field. */
  for (char *q = out; *q; q++)
    if (*q == ',')
      *q = '.';
}

int sb_comparison_csv(const sb_comparison *c, char *buf, size_t len)
{
  if (!c) {
    sbi_error(SB_EINVAL, __func__, "NULL record");
    return -1;
  }
  char line[2 * sizeof c->name + 7 * 32 + 32];
  size_t pos = 0;
  const char *nul = memchr(c->name, '\0', sizeof c->name);
  size_t nlen = nul ? (size_t)(nul - c->name) : sizeof c->name;
  int quote = 0;
  for (size_t i = 0; i < nlen; i++)
    if (strchr(",\"\r\n", c->name[i]))
      quote = 1;
  if (quote)
    line[pos++] = '"';
  for (size_t i = 0; i < nlen; i++) {
    if (c->name[i] == '"')
      line[pos++] = '"';
    line[pos++] = c->name[i];
  }
  if (quote)
    line[pos++] = '"';
  const double v[5] = {c->estimate, c->reference, c->ci_low, c->ci_high,
                       c->p_value};
  for (int i = 0; i < 5; i++) {
    char num[32];
    fmt_num(num, sizeof num, v[i]);
    pos += (size_t)snprintf(line + pos, sizeof line - pos, ",%s", num);
  }
  char lv[32];
  fmt_num(lv, sizeof lv, c->level);
  snprintf(line + pos, sizeof line - pos, ",%s,%s,%s", sb_rule_name(c->rule),
           lv, sb_verdict_name(c->verdict));
  return snprintf(buf, len, "%s", line);
}
