/* smolbridge/stats.h — Monte Carlo versus reference: confidence intervals,
 * z-scores, goodness-of-fit tests and the comparison record printed by
 * `smolbridge validate`.
 *
 * All intervals are two-sided with coverage `level` in (0, 1) (0.95 for a
 * 95% interval).  Probabilities come from GSL's CDFs (gsl_cdf_*).
 */
#ifndef SMOLBRIDGE_STATS_H
#define SMOLBRIDGE_STATS_H

#include <stddef.h>
#include <smolbridge/common.h>

#ifdef __cplusplus
extern "C" {
#endif

/* ---------------------------------------------------------- intervals */

/** Exact (Garwood) interval for the mean of a Poisson count k:
 *  lo = chi2_{(1-level)/2}(2k)/2 (0 if k = 0), hi = chi2_{(1+level)/2}(2k+2)/2.
 *  Returns SB_EINVAL for level outside (0,1). */
int sb_poisson_ci(unsigned long k, double level, double *lo, double *hi);

/** Exact (Clopper–Pearson) interval for a binomial proportion, k successes
 *  in n trials (k <= n, n >= 1), from Beta quantiles. */
int sb_binomial_ci(unsigned long k, unsigned long n, double level,
                   double *lo, double *hi);

/** z-score (estimate - reference) / stderr; NaN if stderr <= 0. */
double sb_zscore(double estimate, double reference, double stderr_);

/** Two-sided p-value of a standard normal z-score: 2 Q(|z|). */
double sb_zscore_pvalue(double z);

/* ------------------------------------------------- goodness of fit */

/** A CDF callback: F(x; params). Must be non-decreasing, in [0, 1]. */
typedef double (*sb_cdf_fn)(double x, void *params);

/** One-sample Kolmogorov–Smirnov test of n samples against a continuous
 *  CDF.  `x` is sorted in place.  *d receives D_n = sup |F_n - F|, *p the
 *  p-value P(D_n >= d) (exact Marsaglia–Tsang–Wang for n <= 10^5... see
 *  docs/stats.md for the method and accuracy). Either pointer may be NULL. */
int sb_ks_test(double *x, size_t n, sb_cdf_fn cdf, void *params,
               double *d, double *p);

/** Two-sample Kolmogorov–Smirnov test (asymptotic p-value with the
 *  Stephens small-sample correction).  Both arrays are sorted in place. */
int sb_ks2_test(double *x, size_t nx, double *y, size_t ny, double *d,
                double *p);

/** Chi-square goodness of fit of samples against a CDF on `nbins` bins with
 *  edges edges[0] < ... < edges[nbins] (samples outside are counted in the
 *  first/last bin only if the edges are infinite, otherwise ignored and the
 *  expected counts are conditioned on [edges[0], edges[nbins]]).
 *  *chi2 the statistic, *dof = nbins - 1, *p = Q_chi2(chi2; dof).  Bins with
 *  expected count < 5 are reported through SB_ELOSS (the test still runs). */
int sb_chi2_test(const double *x, size_t n, const double *edges,
                 size_t nbins, sb_cdf_fn cdf, void *params, double *chi2,
                 double *dof, double *p);

/* ------------------------------------------------- comparison record */

typedef enum { SB_PASS = 0, SB_FAIL = 1 } sb_verdict;

/** One line of a validation report.  NaN marks a field that does not apply
 *  (for example no p-value for an interval-only comparison). */
typedef struct {
  char name[96];     /**< "V11/bes3b_hit/ks": V-number/what/how */
  double estimate;   /**< Monte Carlo (or numerical) estimate */
  double reference;  /**< theoretical reference value */
  double ci_low;     /**< interval for the estimate (coverage in docs) */
  double ci_high;
  double p_value;    /**< p-value of the test, NaN if none */
  sb_verdict verdict;
} sb_comparison;

/** Record whose verdict is PASS iff ci_low <= reference <= ci_high. */
int sb_compare_interval(sb_comparison *c, const char *name, double estimate,
                        double reference, double ci_low, double ci_high);

/** Record whose verdict is PASS iff p_value >= alpha. ci_* may be NaN. */
int sb_compare_pvalue(sb_comparison *c, const char *name, double estimate,
                      double reference, double ci_low, double ci_high,
                      double p_value, double alpha);

/** Write the record as one CSV line (no newline) matching the header
 *  SB_COMPARISON_CSV_HEADER into buf; returns the snprintf count. */
#define SB_COMPARISON_CSV_HEADER \
  "case,estimate,reference,ci_low,ci_high,p_value,verdict"
int sb_comparison_csv(const sb_comparison *c, char *buf, size_t len);

#ifdef __cplusplus
}
#endif

#endif /* SMOLBRIDGE_STATS_H */
