/* smolbridge/stats.h — Monte Carlo versus reference: confidence intervals,
 * z-scores, goodness-of-fit tests and the comparison record printed by
 * `smolbridge validate`.
 *
 * All intervals are two-sided, equal-tailed, with coverage `level` in
 * (0, 1) (0.95 for a 95% interval): each tail has probability at most
 * alpha/2 = (1 - level)/2.  Theory, methods, measured accuracy and
 * references: docs/stats.md.
 *
 * Errors: every function validates its arguments before any GSL call (GSL's
 * default handler aborts); a bad argument gives SB_EINVAL (or SB_EDOM) and a
 * message readable with sb_last_error(), and the outputs are set to NaN.
 * Everything here is thread-safe (no state besides the per-thread error).
 */
#ifndef SMOLBRIDGE_STATS_H
#define SMOLBRIDGE_STATS_H

#include <stddef.h>
#include <smolbridge/common.h>

#ifdef __cplusplus
extern "C" {
#endif

/* ---------------------------------------------------------- intervals */

/** Exact (Garwood 1936) interval for the mean mu of a Poisson count k:
 *    lo = Gamma^{-1}_P(alpha/2; k)        (0 if k = 0),
 *    hi = Gamma^{-1}_Q(alpha/2; k + 1)    (= chi2_{1-alpha/2}(2k+2)/2),
 *  i.e. P(X >= k | lo) = alpha/2 = P(X <= k | hi).  Coverage >= level for
 *  every mu.  Accuracy: relative error <= 1e-13 on lo and hi (measured
 *  <= 2e-15 against mpmath, k = 0 ... 1e12).  Method: Brent's root finder
 *  on GSL's incomplete gamma for k <= 200, on a Gauss-Legendre quadrature
 *  of the gamma density beyond (GSL's gamma inverse aborts or is wrong, and
 *  its incomplete gamma loses accuracy, for large shapes: docs/stats.md).
 *  0.003-0.02 ms for k <= 200, ~0.05-0.3 ms beyond.  k > 2^53 is rounded
 *  to a double.  Returns SB_EINVAL for level outside (0,1) or NULL
 *  outputs. */
int sb_poisson_ci(unsigned long k, double level, double *lo, double *hi);

/** Exact (Clopper-Pearson 1934) interval for a binomial proportion, k
 *  successes in n trials (k <= n, n >= 1), from Beta quantiles:
 *    lo = Beta^{-1}_P(alpha/2; k, n-k+1)   (0 if k = 0),
 *    hi = Beta^{-1}_Q(alpha/2; k+1, n-k)   (1 if k = n),
 *  i.e. P(X >= k | lo) = alpha/2 = P(X <= k | hi).  Coverage >= level.
 *  Accuracy: relative error <= 1e-13 on lo and hi (measured <= 1e-14
 *  against mpmath, n up to 1e15); 1 - hi is only as accurate as a double
 *  near 1.  Method as for sb_poisson_ci (GSL's incomplete beta while both
 *  shapes are <= 200, quadrature beyond; closed forms for k = 0, 1, n-1,
 *  n; laws crowded against 1 (k near n > 2^53) through the mirror law at
 *  1 - p, so lo and hi are right to rounding, often exactly 1, there).
 *  SB_EINVAL for n = 0, k > n, level outside (0,1). */
int sb_binomial_ci(unsigned long k, unsigned long n, double level,
                   double *lo, double *hi);

/** Interval for a rate estimated as scale * k with k Poisson (for example a
 *  collision kernel K = c N_c): scale times the Garwood interval.
 *  scale must be finite and > 0 (SB_EINVAL otherwise); SB_ERANGE, with lo
 *  and hi NaN, where scale * hi overflows (e.g. scale = 1e308); lo may
 *  underflow to 0. */
int sb_poisson_rate_ci(unsigned long k, double scale, double level,
                       double *lo, double *hi);

/** The Garwood interval of k (sb_poisson_ci) for a count whose variance
 *  is `dispersion` times its mean: widened about k by sqrt(dispersion)
 *  where that is above 1 (the lower end clipped at 0); dispersion <= 1 or
 *  NaN gives sb_poisson_ci exactly; dispersion = +inf is SB_EINVAL.
 *  Approximate (quasi-Poisson), as sb_compare_poisson_dispersed, whose
 *  interval it is. */
int sb_poisson_ci_dispersed(unsigned long k, double dispersion, double level,
                            double *lo, double *hi);

/** Estimated variance of a count H of events between pairs of particles
 *  (collisions, first contacts) from how the events share particles: a
 *  U-statistic (Hoeffding 1948), unbiased when the pairs are exchangeable
 *  and their counts correlate only through a shared particle.  One population
 *  (nb = 0): sqa = sum over its na particles of the squared number of
 *  events each took part in (those add up to 2H); two populations (the
 *  events between them): sqa over the na particles of one side and sqb
 *  over the nb of the other (each side adds up to H).  S2 = sum over the
 *  pairs of their squared event counts (= H when no pair has more than one
 *  event, as for first contacts); P the pairs.
 *    var(H) ~ [sqa - 4 H^2/na - S2 + H^2/P] / (1 - 4/na + 1/P)   (one)
 *    var(H) ~ [(sqa - H^2/na) + (sqb - H^2/nb) - S2 + H^2/P]
 *             / (1 - 1/na - 1/nb + 1/P)                        (two);
 *  the divisor removes the bias of the H^2 terms (whose mean holds
 *  var(H) too).  For Poisson pair counts it is ~H; particles that take
 *  part in more events than others (a persistent speed, a longer
 *  exposure) raise it.  Not below 0; NaN if na or P is not positive or
 *  the divisor is not (fewer than ~5 particles; 0 if H = 0), without an
 *  error status.  NaN with SB_EDOM for NaN arguments or infinite H, S2,
 *  sqa (sqb if nb > 0); NaN with SB_ERANGE where var(H) exceeds DBL_MAX
 *  (or H^2/P and 1/P both overflow); H^2 itself may overflow. */
double sb_pair_count_variance(double H, double S2, double sqa, double na,
                              double sqb, double nb, double P);

/** Ratio of two Poisson rates R = lambda1 / lambda2 from counts k1 over
 *  exposure t1 and k2 over exposure t2 (t1, t2 > 0): conditional method
 *  (given k1 + k2 = N, k1 is binomial with p = R t1 / (R t1 + t2)), with the
 *  Clopper-Pearson interval for p, so coverage >= level.  *ratio receives
 *  (k1/t1)/(k2/t2) (+inf if k2 = 0, NaN if k1 = k2 = 0); hi is +inf if
 *  k2 = 0; N = 0 gives the uninformative [0, +inf].  ratio may be NULL.
 *  t2/t1 may lie beyond the doubles; SB_ERANGE (all outputs NaN) where
 *  lo, a finite hi or the ratio exceed DBL_MAX; they may underflow. */
int sb_poisson_ratio_ci(unsigned long k1, double t1, unsigned long k2,
                        double t2, double level, double *ratio, double *lo,
                        double *hi);

/** Mean of n >= 2 finite samples and its Student-t interval from the
 *  sample variance: mean -+ t_{(1+level)/2}(n-1) s / sqrt(n) (exact for
 *  normal samples, asymptotically right for any finite-variance law).
 *  Samples up to +-DBL_MAX (sums scaled where they overflow); SB_ERANGE,
 *  lo and hi NaN, *mean set, where an end exceeds DBL_MAX.  level < 1e-8:
 *  t = level / (2 f(0)), f the t density.  mean may be NULL. */
int sb_mean_ci(const double *x, size_t n, double level, double *mean,
               double *lo, double *hi);

/** Exact two-sided p-value of a Poisson count k when its mean is mu:
 *  min(1, 2 min(P(X <= k), P(X >= k))).  mu = 0 gives 1 if k = 0, else 0.
 *  NaN (SB_EDOM) for mu < 0, NaN or infinite.  Accuracy: relative 1e-11
 *  (tested against direct summation) for p >= 1e-30; smaller p come from
 *  the same scaled tail integrals as sb_chi2_sf (large counts) but are not
 *  tested here. */
double sb_poisson_pvalue(unsigned long k, double mu);

/** Exact two-sided p-value of a binomial count k of n trials when the
 *  success probability is p: min(1, 2 min(P(X <= k), P(X >= k))), from
 *  the incomplete beta function (the Clopper-Pearson machinery; closed
 *  forms where a shape is 1).  NaN (SB_EDOM) for n = 0, k > n or p
 *  outside [0, 1].  Accuracy: relative 1e-10 (tested against direct
 *  summation) for p >= 1e-30; smaller p come from the same scaled tail
 *  integrals as sb_chi2_sf (shapes above 200) but are not tested here.
 *  k near n > 2^53 (laws crowded against 1) through the mirror law at
 *  1 - p (tested against mpmath for n = 2^64 - 1, p = 1 - 2^-53). */
double sb_binomial_pvalue(unsigned long k, unsigned long n, double p);

/** z-score (estimate - reference) / stderr_; NaN (SB_EDOM recorded) if
 *  stderr_ <= 0 or any argument is NaN.  +-inf for an infinite estimate or
 *  reference (not both); for finite arguments, NaN and SB_ERANGE where z
 *  overflows (e.g. stderr_ = 1e-320), and no overflow of the difference
 *  (1e308 - -1e308) where z itself is finite. */
double sb_zscore(double estimate, double reference, double stderr_);

/** Two-sided p-value of a standard normal z-score: 2 Q(|z|), computed
 *  without cancellation (relative accuracy ~1e-15 down to 1e-300).
 *  NaN for NaN z; 0 for |z| = inf. */
double sb_zscore_pvalue(double z);

/* ------------------------------------------------- goodness of fit */

/** Chi-square survival function Q(x; dof) = P(chi2_dof >= x), dof >= 1
 *  (not necessarily an integer); Q = 1 for x <= 0, 0 for x = inf.
 *  GSL's gsl_cdf_chisq_Q for dof <= 400; beyond (where GSL's incomplete
 *  gamma loses accuracy or fails) the smaller tail is integrated from x
 *  outwards in scaled form, Q = f(x) * integral of f(t)/f(x), the density
 *  at x taken in log space and normalised in closed form (Stirling with
 *  GSL's gamma*), so Q is right however small.  Relative error <= 1e-12
 *  over the whole representable range, down to Q ~ 1e-308 (measured:
 *  <= 3e-13 against mpmath for dof = 1 ... 1e12 and Q from 1 to 1e-308;
 *  subnormal Q to 1e-12 or one DBL_TRUE_MIN; Q below DBL_TRUE_MIN/2 is 0).
 *  Cost: < 1 us for dof <= 400, ~25 us beyond.
 *  NaN (SB_EDOM) for NaN arguments or dof < 1. */
double sb_chi2_sf(double x, double dof);

/** A CDF callback: F(x; params). Must be non-decreasing, in [0, 1]. */
typedef double (*sb_cdf_fn)(double x, void *params);

/** One-sample Kolmogorov-Smirnov test of n samples against a continuous
 *  CDF.  `x` is sorted in place.  *d receives D_n = sup |F_n - F|, *p the
 *  p-value P(D_n >= d) from sb_ks_pvalue_e (exact for n <= 140 and for
 *  small D_n up to n = 1e5, Pelz-Good asymptotic otherwise; see that
 *  function).  Either pointer may be NULL.  SB_EINVAL for n = 0, NaN
 *  samples, or F values that are NaN, outside [0,1] or decreasing (by more
 *  than 1e-12; smaller decreases are treated as rounding and ignored). */
int sb_ks_test(double *x, size_t n, sb_cdf_fn cdf, void *params,
               double *d, double *p);

/** P(D_n >= d) for the two-sided one-sample KS statistic of n samples from
 *  a continuous law.  Methods (Simard & L'Ecuyer 2011 strategy):
 *   - exact closed forms for d <= 1/n and d >= 1 - 1/n (Ruben-Gambino),
 *     and for d >= 1/2 (twice the one-sided Birnbaum-Tingey sum);
 *   - Durbin's matrix (Marsaglia-Tsang-Wang 2003 algorithm, exponent
 *     scaling) when n <= 140 and n d^2 <= 18, or n <= 1e5 and (n d^1.5 <=
 *     1.4 or matrix order <= 64): absolute error <= 3e-14 (measured
 *     <= 8e-15);
 *   - otherwise the Pelz-Good 1976 expansion through n^-3/2: absolute
 *     error <= 0.08/n^2 (measured: 0.066/n^2 worst, near sqrt(n) d = 0.55);
 *   - for small p, twice the one-sided tail P+ (its sum for n <= 1e6, the
 *     sum's integral beyond: relative error <= 1e-13), neglecting the
 *     probability of crossing both bands (bounded by P+^2/2, verified on
 *     the reference cases), whenever that bound is the smaller error.
 *  _e: res->err bounds |res->val - exact| (checked against 60-digit
 *  Durbin values in the tests).  Cost: <= 1 ms except the one-sided sum,
 *  O(n) for n <= 1e6.  SB_EINVAL for n = 0 or NaN d. */
double sb_ks_pvalue(size_t n, double d);
int sb_ks_pvalue_e(size_t n, double d, sb_result *res);

/** Survival function of the Kolmogorov limit law,
 *  Q(t) = P(sup|B| >= t) = 2 sum_{j>=1} (-1)^(j-1) exp(-2 j^2 t^2) (for the
 *  Brownian bridge B), via its theta-function dual for t < 1.  Relative
 *  accuracy ~1e-15 for Q >= 1e-300.  Q(t) = 1 for t < 0.1 (to double
 *  precision) and t <= 0; NaN (SB_EDOM) for NaN. */
double sb_kolmogorov_sf(double t);

/** Two-sample Kolmogorov-Smirnov test: *d = sup |F_x - F_y| (ties handled
 *  by stepping over equal values in both samples; the p-value assumes
 *  continuous laws and is conservative with ties), *p = P(D >= d) under H0
 *  from sb_ks2_pvalue.  Both arrays are sorted in place.  Either output may
 *  be NULL.  SB_EINVAL for empty or NaN samples. */
int sb_ks2_test(double *x, size_t nx, double *y, size_t ny, double *d,
                double *p);

/** P(D >= d) for the two-sample KS statistic of continuous samples:
 *   - nx = ny = n: exact (Gnedenko-Korolyuk alternating sum), any n (log
 *     ratios in closed form beyond 1e7; 1 for n > 1e12 and n d^2 <
 *     1/325 where the sum would be long, the neglected mass < e^-750);
 *   - nx * ny <= 1e7: exact lattice-path recursion (Hodges 1957) summing
 *     only positive terms, relative accuracy ~1e-13, ~15 ns per cell;
 *   - otherwise asymptotic, Stephens' small-sample correction:
 *     Q((sqrt(ne) + 0.12 + 0.11/sqrt(ne)) d), ne = nx ny / (nx + ny):
 *     absolute error <= 0.3/sqrt(ne), relative <= 1.4/sqrt(ne) for p in
 *     [1e-5, 0.05] (measured, docs/stats.md).  Use equal sizes when an
 *     exact p-value matters for large samples.
 *  D takes the values c/(nx ny), c integer: d is mapped to c (nearest
 *  integer if within 1e-9 relative, else the next one up).  NaN
 *  (SB_EINVAL) for nx or ny = 0 or NaN d. */
double sb_ks2_pvalue(size_t nx, size_t ny, double d);

/** Chi-square goodness of fit of samples against a CDF on `nbins` >= 2 bins
 *  with edges edges[0] < ... < edges[nbins] (bin i is [e_i, e_{i+1}), the
 *  last bin also holds e_nbins; edges may be -inf/+inf at the ends).
 *  Samples outside [edges[0], edges[nbins]] are ignored and the expected
 *  counts are conditioned on that range:
 *    E_i = n_in (F(e_{i+1}) - F(e_i)) / (F(e_nbins) - F(e_0)).
 *  *chi2 the statistic, *dof = (number of bins with E_i > 0) - 1, *p =
 *  Q_chi2(chi2; dof).  Outputs may be NULL.  A bin with E_i = 0 but samples
 *  in it gives chi2 = inf, p = 0.  Bins with expected count < 5 are
 *  reported through SB_ELOSS (the outputs are still set).  SB_EINVAL for
 *  n = 0, NaN samples, unsorted or NaN edges, no sample in range, or F
 *  values outside [0,1] / decreasing at the edges. */
int sb_chi2_test(const double *x, size_t n, const double *edges,
                 size_t nbins, sb_cdf_fn cdf, void *params, double *chi2,
                 double *dof, double *p);

/* ------------------------------------------------- comparison record */

/** Verdict of a comparison.  SB_INFO marks a descriptive row that cannot
 *  fail (and does not count as a pass). */
typedef enum { SB_PASS = 0, SB_FAIL = 1, SB_INFO = 2 } sb_verdict;

/** How a comparison record turns into a verdict.  The interval stored in
 *  the record is always the one the rule reads, so a reader can check
 *  every verdict from the printed numbers. */
typedef enum {
  /** PASS iff ci_low <= reference <= ci_high, where [ci_low, ci_high] is
   *  a confidence interval of the estimate with coverage `level`
   *  (stochastic estimates: kernels, probabilities, means). */
  SB_RULE_COVER = 0,
  /** PASS iff ci_low <= estimate <= ci_high, where [ci_low, ci_high] is
   *  the region holding the statistic with probability `level` when the
   *  reference law is true (goodness-of-fit statistics: KS distance,
   *  chi-square; p_value >= 1 - level is then the same rule). */
  SB_RULE_ACCEPT = 1,
  /** Deterministic comparison: PASS iff ci_low <= reference <= ci_high,
   *  a tolerance band around the (numerical) estimate; level is NaN. */
  SB_RULE_BAND = 2,
  /** Demonstration that the estimate lies significantly above the
   *  reference (an expected failure of an approximate method): PASS iff
   *  reference < ci_low, ci at `level`. */
  SB_RULE_ABOVE = 3,
  /** ... significantly below: PASS iff ci_high < reference. */
  SB_RULE_BELOW = 4,
  /** Descriptive only: verdict SB_INFO whatever the numbers. */
  SB_RULE_INFO = 5
} sb_rule;

/** One line of a validation report.  NaN marks a field that does not apply
 *  (no p-value for a tolerance band, no level for SB_RULE_BAND). */
typedef struct {
  char name[96];     /**< "V11/bes3b_hit/ks": V-number/what/how */
  double estimate;   /**< Monte Carlo (or numerical) estimate */
  double reference;  /**< theoretical reference value */
  double ci_low;     /**< the interval the rule reads (see sb_rule) */
  double ci_high;
  double p_value;    /**< p-value of the test behind the row, NaN if none;
                          for SB_RULE_COVER rows built by the helpers below
                          p_value >= 1 - level iff the row passes */
  double level;      /**< coverage of the interval (NaN for bands) */
  sb_rule rule;
  sb_verdict verdict;
} sb_comparison;

/** Fill a record and set its verdict by `rule`.  A NaN in a field the
 *  rule reads fails the row (except SB_RULE_INFO).  SB_EINVAL (record
 *  filled, verdict FAIL) for NULL c/name, an unknown rule, ci_low >
 *  ci_high, a level outside (0,1) where the rule needs one, or a p_value
 *  outside [0,1] (NaN allowed); SB_ELOSS if the name was truncated to 95
 *  bytes. */
int sb_compare(sb_comparison *c, const char *name, sb_rule rule,
               double estimate, double reference, double ci_low,
               double ci_high, double level, double p_value);

/** Rate estimated from a Poisson count: estimate = scale k, interval = the
 *  exact Garwood interval at level 1 - alpha times scale, p-value = the
 *  exact two-sided Poisson test of k against the mean reference/scale
 *  (sb_poisson_pvalue); rule SB_RULE_COVER.  The test and the interval are
 *  inversions of each other: PASS iff p >= alpha iff the reference lies in
 *  the printed interval (p = 0 where reference/scale exceeds DBL_MAX).
 *  Use it for collision kernels K_e = scale N_c. */
int sb_compare_poisson(sb_comparison *c, const char *name, unsigned long k,
                       double scale, double reference, double alpha);

/** sb_compare_poisson for a count whose variance is `dispersion` times
 *  its mean (> 1: a sum of correlated rare events, e.g. first contacts of
 *  pairs that share particles, sb_engine_firsthit_counts.hits_var / hits):
 *  the Garwood interval widened about k by sqrt(dispersion), and the exact
 *  test at the mean k + (reference/scale - k) / sqrt(dispersion), so that
 *  again PASS iff p >= alpha iff the reference lies in the interval (the
 *  lower end clipped at 0).  Approximate (quasi-Poisson: right to first
 *  order in the spread, as the normal approximation); dispersion <= 1 or
 *  NaN gives sb_compare_poisson exactly. */
int sb_compare_poisson_dispersed(sb_comparison *c, const char *name,
                                 unsigned long k, double dispersion,
                                 double scale, double reference,
                                 double alpha);

/** Proportion k/n against the probability `reference`: Clopper-Pearson
 *  interval at 1 - alpha, exact two-sided binomial test
 *  (sb_binomial_pvalue); rule SB_RULE_COVER, verdict as above. */
int sb_compare_binomial(sb_comparison *c, const char *name, unsigned long k,
                        unsigned long n, double reference, double alpha);

/** Mean of n >= 2 independent replicas x[] against `reference`: Student-t
 *  interval at 1 - alpha (sb_mean_ci) and the two-sided one-sample t test
 *  (exact for normal replicas, asymptotically right otherwise); rule
 *  SB_RULE_COVER.  SB_ERANGE where the interval overflows (sb_mean_ci);
 *  for alpha > 1 - 1e-8 the test statistic comes from the standard error
 *  directly (the interval is then narrower than the rounding of the
 *  mean). */
int sb_compare_mean(sb_comparison *c, const char *name, const double *x,
                    size_t n, double reference, double alpha);

/** Short names of rules ("cover", "accept", "band", "above", "below",
 *  "info") and verdicts ("pass", "fail", "info"), as in the CSV. */
const char *sb_rule_name(sb_rule rule);
const char *sb_verdict_name(sb_verdict v);

/** The rule in words for a table ("ref in 99.9% CI", "est in 99.9%
 *  acceptance", "ref in tolerance band", "95% CI above ref", "95% CI
 *  below ref", "informational"); snprintf semantics; -1 for NULL c.
 *  The level is the shortest percentage keeping level and 1 - level to 3
 *  digits ("99.9999999%" for 0.999999999, up to 17 digits). */
int sb_comparison_rule_text(const sb_comparison *c, char *buf, size_t len);

/** Write the record as one CSV line (no newline) matching the header
 *  SB_COMPARISON_CSV_HEADER into buf; returns the snprintf count (the
 *  length the full line needs; the line is complete iff count < len;
 *  buf may be NULL when len is 0), or -1 (SB_EINVAL recorded) for a NULL
 *  record.  Numbers use the shortest "%.{15,16,17}g" form that reads back
 *  exactly; NaN is written "nan", infinities "inf"/"-inf"; rule and
 *  verdict by their short names; a name holding a comma, quote or newline
 *  is quoted RFC 4180 style. */
#define SB_COMPARISON_CSV_HEADER \
  "case,estimate,reference,ci_low,ci_high,p_value,rule,level,verdict"
int sb_comparison_csv(const sb_comparison *c, char *buf, size_t len);

#ifdef __cplusplus
}
#endif

#endif /* SMOLBRIDGE_STATS_H */
