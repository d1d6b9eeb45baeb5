/* records.c — the comparison rows validation cases make, each with its
 * rule and the interval that rule reads (<smolbridge/stats.h>, sb_rule):
 * exact tests where counts are involved, acceptance regions for
 * goodness-of-fit statistics, tolerance bands for deterministic numbers. */
#include <math.h>

#include <gsl/gsl_cdf.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_roots.h>

#include "cases.h"

/* Append c.  A record that sb_compare rejected (bad numbers, truncated
 * name) is still appended: its verdict is FAIL and the report shows it;
 * only running out of memory stops the case. */
static int add(sbv_report *rep, int st, const sb_comparison *c)
{
  (void)st;
  return sbv_add(rep, c);
}

int sbv_add_freq(sbv_report *rep, const char *name, unsigned long k,
                 unsigned long n, double P)
{
  sb_comparison c;
  int st = sb_compare_binomial(&c, name, k, n, P, SBV_ALPHA);
  return add(rep, st, &c);
}

int sbv_add_poisson(sbv_report *rep, const char *name, unsigned long k,
                    double scale, double reference)
{
  sb_comparison c;
  if (!(scale > 0.0 && isfinite(scale)))
    scale = 1.0; /* no event in no exposure: the row fails on the count */
  int st = sb_compare_poisson(&c, name, k, scale, reference, SBV_ALPHA);
  return add(rep, st, &c);
}

int sbv_add_poisson_dispersed(sbv_report *rep, const char *name,
                              unsigned long k, double dispersion,
                              double scale, double reference)
{
  sb_comparison c;
  if (!(scale > 0.0 && isfinite(scale)))
    scale = 1.0;
  int st = sb_compare_poisson_dispersed(&c, name, k, dispersion, scale,
                                        reference, SBV_ALPHA);
  return add(rep, st, &c);
}

int sbv_add_pair_kernel(sbv_report *rep, const char *name,
                        const sb_engine_pair_stats *ps, double Kth,
                        int info, const char *what)
{
  double scale = ps->ncoll ? ps->K / (double)ps->ncoll / Kth : 1.0;
  if (!ps->ncoll && ps->exposure > 0.0)
    scale = 1.0 / (Kth * ps->exposure);  /* V irrelevant: rate 0 */
  int st = info ? sbv_add_info(rep, name, ps->K / Kth, 1.0, ps->lo / Kth,
                               ps->hi / Kth, 0.95)
                : sbv_add_poisson_dispersed(rep, name,
                                            (unsigned long)ps->ncoll,
                                            ps->dispersion, scale, 1.0);
  sbv_note(rep, "- %s: %llu %s, K_e = %.4g m^3/s, K_th = %.4g, ratio "
           "%.4f [%.4f, %.4f] (95%%), var/mean of the count %.3f", name,
           (unsigned long long)ps->ncoll, what, ps->K, Kth, ps->K / Kth,
           ps->lo / Kth, ps->hi / Kth, ps->dispersion);
  return st;
}

int sbv_add_mean(sbv_report *rep, const char *name, const double *x,
                 size_t n, double reference)
{
  sb_comparison c;
  int st = sb_compare_mean(&c, name, x, n, reference, SBV_ALPHA);
  return add(rep, st, &c);
}

int sbv_add_chi2(sbv_report *rep, const char *name, int test_status,
                 double chi2, double dof, double p)
{
  sb_comparison c;
  double hi = NAN;
  if (test_status != SB_SUCCESS && test_status != SB_ELOSS)
    chi2 = p = NAN; /* the test did not run: the row fails */
  if (dof >= 1.0)
    hi = gsl_cdf_chisq_Qinv(SBV_ALPHA, dof);
  int st = sb_compare(&c, name, SB_RULE_ACCEPT, chi2, dof, 0.0, hi,
                      1.0 - SBV_ALPHA, p);
  return add(rep, st, &c);
}

/* Critical KS distance: P(D_n >= d) = alpha (Brent on log p). */
typedef struct {
  size_t n;
  double la;
} kspar;

static double ks_f(double d, void *vp)
{
  const kspar *k = vp;
  double p = sb_ks_pvalue(k->n, d);
  return log(p > 1e-300 ? p : 1e-300) - k->la;
}

static double ks_critical(size_t n, double alpha)
{
  kspar k = {n, log(alpha)};
  return sbv_brent(ks_f, &k, 1e-6, 1.0 - 1e-12, 1e-12);
}

double sbv_brent(double (*f)(double, void *), void *par, double lo,
                 double hi, double rtol)
{
  gsl_function F = {f, par};
  double flo = f(lo, par), fhi = f(hi, par);
  if (!((flo < 0 && fhi > 0) || (flo > 0 && fhi < 0)))
    return NAN;
  gsl_root_fsolver *s = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
  if (!s)
    return NAN;
  double x = NAN;
  if (gsl_root_fsolver_set(s, &F, lo, hi) == GSL_SUCCESS)
    for (int i = 0; i < 200; i++) {
      if (gsl_root_fsolver_iterate(s) != GSL_SUCCESS)
        break;
      x = gsl_root_fsolver_root(s);
      if (gsl_root_test_interval(gsl_root_fsolver_x_lower(s),
                                 gsl_root_fsolver_x_upper(s), 0,
                                 rtol) == GSL_SUCCESS)
        break;
    }
  gsl_root_fsolver_free(s);
  return x;
}

int sbv_add_ks(sbv_report *rep, const char *name, size_t n, double d,
               double p)
{
  sb_comparison c;
  double hi = n > 0 ? ks_critical(n, SBV_ALPHA) : NAN;
  /* expected D_n under H0 ~ 0.8687/sqrt(n) (mean of the Kolmogorov law
   * sqrt(pi/2) ln 2) */
  double ref = n > 0 ? 0.868731160636 / sqrt((double)n) : NAN;
  int st = sb_compare(&c, name, SB_RULE_ACCEPT, d, ref, 0.0, hi,
                      1.0 - SBV_ALPHA, p);
  return add(rep, st, &c);
}

int sbv_add_band(sbv_report *rep, const char *name, double est, double ref,
                 double lo, double hi)
{
  sb_comparison c;
  int st = sb_compare(&c, name, SB_RULE_BAND, est, ref, lo, hi, NAN, NAN);
  /* the band is a tolerance around the estimate: one that does not hold
   * it is a case's mistake (a fixed [0, 0] passes whatever est is) */
  if (!(lo <= est && est <= hi))
    c.verdict = SB_FAIL;
  return add(rep, st, &c);
}

int sbv_add_relband(sbv_report *rep, const char *name, double est,
                    double ref, double tol)
{
  double h = tol * fabs(est);
  return sbv_add_band(rep, name, est, ref, est - h, est + h);
}

int sbv_add_side(sbv_report *rep, const char *name, int above, double est,
                 double ref, double lo, double hi, double level, double p)
{
  sb_comparison c;
  int st = sb_compare(&c, name, above ? SB_RULE_ABOVE : SB_RULE_BELOW, est,
                      ref, lo, hi, level, p);
  return add(rep, st, &c);
}

int sbv_add_info(sbv_report *rep, const char *name, double est, double ref,
                 double lo, double hi, double level)
{
  sb_comparison c;
  int st = sb_compare(&c, name, SB_RULE_INFO, est, ref, lo, hi, level, NAN);
  return add(rep, st, &c);
}

int sbv_add_median(sbv_report *rep, const char *name, const double *xs,
                   size_t m, double med_ref)
{
  sb_comparison c;
  if (m < 2 || isnan(med_ref)) {
    int st = sb_compare(&c, name, SB_RULE_COVER, NAN, med_ref, NAN, NAN,
                        1.0 - SBV_ALPHA, NAN);
    return add(rep, st, &c);
  }
  /* Distribution-free interval [x_(j), x_(m-1-j)] (0-based order
   * statistics): the median lies below x_(j) iff at most j samples are
   * below it, probability P(Bin(m, 1/2) <= j); take the largest j with
   * that tail <= alpha/2 on each side (exact coverage >= 1 - alpha). */
  double half = 0.5 * SBV_ALPHA;
  long j = (long)floor(0.5 * (double)m -
                       0.5 * gsl_cdf_ugaussian_Qinv(half) *
                           sqrt((double)m)) + 3;
  if (j > (long)m / 2)
    j = (long)m / 2;
  while (j >= 0 && gsl_cdf_binomial_P((unsigned)j, 0.5, (unsigned)m) > half)
    j--;
  /* j = -1: no order statistic gives the level (tiny m) */
  double lo = j >= 0 ? xs[j] : -INFINITY;
  double hi = j >= 0 ? xs[m - 1 - (size_t)j] : INFINITY;
  double med = m % 2 ? xs[m / 2] : 0.5 * (xs[m / 2 - 1] + xs[m / 2]);
  /* sign test: samples below the reference median ~ Bin(m, 1/2) */
  unsigned long below = 0;
  for (size_t i = 0; i < m; i++)
    below += xs[i] < med_ref;
  double p = sb_binomial_pvalue(below, (unsigned long)m, 0.5);
  int st = sb_compare(&c, name, SB_RULE_COVER, med, med_ref, lo, hi,
                      1.0 - SBV_ALPHA, p);
  return add(rep, st, &c);
}
