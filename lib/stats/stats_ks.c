/* stats_ks.c — Kolmogorov-Smirnov tests: statistics and p-values.
 *
 * One sample, P(D_n >= d) (strategy of Simard & L'Ecuyer 2011, J. Stat.
 * Softw. 39(11)):
 *  - closed forms (Ruben & Gambino 1982) for d <= 1/n and d >= 1 - 1/n;
 *  - d >= 1/2: exactly twice the one-sided tail P(D_n^+ >= d)
 *    (Smirnov 1944; Birnbaum & Tingey 1951), a sum of positive terms;
 *  - Durbin's matrix (Durbin 1973) evaluated as in Marsaglia, Tsang & Wang
 *    2003 (J. Stat. Softw. 8(18)) for small n d (cost O(m^3 log n),
 *    m = 2 ceil(n d) - 1);
 *  - Pelz & Good 1976 (JRSS B 38, 152) expansion of the CDF in powers of
 *    n^-1/2 through n^-3/2 otherwise;
 *  - for small p, 2 x one-sided tail whenever its error bound (the
 *    probability of crossing both bands) beats 1 - CDF's.
 * Two samples: Gnedenko-Korolyuk sum (equal sizes), lattice-path recursion
 * (Hodges 1957) for moderate nx*ny, Stephens' corrected limit otherwise.
 */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_blas.h>
#include <gsl/gsl_integration.h>
#include <gsl/gsl_math.h>
#include <gsl/gsl_sf_gamma.h>
#include <gsl/gsl_sf_log.h>
#include <gsl/gsl_sort.h>

#include "common/internal.h"
#include <smolbridge/stats.h>

#define KS_SMALL_N 140         /* exact methods everywhere up to this n */
#define KS_MTW_NMAX 100000     /* Durbin matrix used up to this n ... */
#define KS_MTW_ND15 1.4        /* ... when n d^1.5 <= this (S&L'E 2011) */
#define KS_MTW_NDD_SMALL 18.0  /* n <= 140: Durbin while n d^2 <= this */
#define KS_MTW_MMAX 64         /* ... or while the matrix is this small */
#define KS_SMIRNOV_NMAX 1000000 /* one-sided sum is O(n): beyond, its
                                   integral (smirnov_sf_large) */
#define KS_MTW_ERR 3e-14       /* abs. error bound of Durbin/MTW (measured
                                  <= 7.6e-15 vs long double, docs) */
#define KS_PG_C 0.08           /* |Pelz-Good - exact| <= KS_PG_C/n^2 */
#define KS2_DP_MAX 1e7         /* lattice recursion up to nx*ny */
#define KS2_EQ_LOOP 10000000   /* equal sizes: summed log ratios up to here */

/* ------------------------------------------------- one-sided (Smirnov) */

/* log Gamma*(x) = log Gamma(x) - [(x - 1/2) log x - x + log(2 pi)/2]:
 * Stirling's remainder ("stirlerr"), small and accurate. */
static double stirlerr(double x) { return log(gsl_sf_gammastar(x)); }

/* bd0(x, M) = x log(x/M) + M - x written as x lpmx(r) + M r^2 with
 * r = (x - M)/M given directly, lpmx(r) = log(1+r) - r (no cancellation
 * between the two large terms: Loader 2000's deviance). */
static double bd0(double x, double M, double r)
{
  return x * gsl_sf_log_1plusx_mx(r) + M * r * r;
}

/* log of the Birnbaum-Tingey term at j = x (below), continued to real
 * x in (0, n - n d) through the same saddle-point form: smooth in x. */
typedef struct {
  double nn, nd, stn, c0; /* n, n d, stirlerr(n), log(n / (2 pi)) / 2 */
  double lscale;          /* smirnov_term's scale: the log of the peak */
} smirnov_t;

static double smirnov_logterm(const smirnov_t *S, double x)
{
  const double nx = S->nn - x;
  const double M1 = S->nd + x, M2 = nx - S->nd; /* n pi_x, n (1 - pi_x) */
  const double r1 = -S->nd / M1, r2 = S->nd / M2;
  return log(S->nd / M1) + S->c0 - 0.5 * (log(x) + log(nx)) + S->stn -
         stirlerr(x) - stirlerr(nx) - bd0(x, M1, r1) - bd0(nx, M2, r2);
}

static double smirnov_term(double x, void *p)
{
  const smirnov_t *S = p;
  return exp(smirnov_logterm(S, x) - S->lscale);
}

/* P(D_n^+ >= d), 0 < d < 1: Birnbaum-Tingey
 *   d sum_{j=0}^{j < n(1-d)} C(n,j) (1-d-j/n)^(n-j) (d+j/n)^(j-1),
 * whose j-th term is (d/pi_j) b(j; n, pi_j), pi_j = d + j/n, with the
 * binomial probability b in Loader's saddle-point form (all terms > 0,
 * relative accuracy ~1e-13 per term). */
static double smirnov_sf(size_t n, double d)
{
  const double nn = (double)n;
  const smirnov_t S = {nn, nn * d, stirlerr(nn),
                       0.5 * (log(nn) - log(2.0 * M_PI)), 0.0};
  double sum = exp(nn * log1p(-d)); /* j = 0: (1 - d)^n */
  for (size_t j = 1; j < n; j++) {
    if (!((double)(n - j) - S.nd > 0.0))
      break; /* (1 - d - j/n)^(n-j) = 0 from here on */
    sum += exp(smirnov_logterm(&S, (double)j));
  }
  return sum;
}

/* The same sum for large n, where its terms vary on a scale of
 * ~n / sqrt(8 n d^2) >> 1 indices (they follow exp(-n d^2 / (2 pi (1-pi)))
 * in pi = d + j/n): sum_{j>=1} f(j) is the midpoint rule for the integral
 * of the continued term over [1/2, J + 1/2], whose error (Euler-Maclaurin:
 * f'/24 at the ends, where the terms are below e^-n d of the peak) is far
 * below the rounding.  The integral is taken over the indices where the
 * term is within e^-60 of its peak (found on a grid of SMIRNOV_GRID
 * points), in SMIRNOV_PANELS Gauss-Legendre panels of SMIRNOV_GL points;
 * relative error <= 1e-13 against an mpmath sum up to n = 1e7 (tests).
 * Only for n d >= 1000 and n d^2 >= 1 (the caller's range at n > 1e6):
 * there the j = 0 term and the ends are negligible. */
#define SMIRNOV_GRID 4096
#define SMIRNOV_PANELS 48
#define SMIRNOV_GL 20
static int smirnov_sf_large(size_t n, double d, double *p)
{
  const double nn = (double)n;
  smirnov_t S = {nn, nn * d, stirlerr(nn),
                 0.5 * (log(nn) - log(2.0 * M_PI)), 0.0};
  const double x0 = 0.5, x1 = floor(nn - S.nd) + 0.5;
  const double h = (x1 - x0) / SMIRNOV_GRID;
  /* the peak and the indices within e^-60 of it, on the grid (the log
   * term is unimodal in x: a binomial probability in its saddle form) */
  double lmax = -HUGE_VAL;
  size_t imax = 0;
  for (size_t i = 1; i < SMIRNOV_GRID; i++) {
    double l = smirnov_logterm(&S, x0 + (double)i * h);
    if (l > lmax)
      lmax = l, imax = i;
  }
  size_t ilo = imax, ihi = imax;
  while (ilo > 1 && smirnov_logterm(&S, x0 + (double)ilo * h) > lmax - 60)
    ilo--;
  while (ihi < SMIRNOV_GRID - 1 &&
         smirnov_logterm(&S, x0 + (double)ihi * h) > lmax - 60)
    ihi++;
  const double a = ilo > 1 ? x0 + (double)(ilo - 1) * h : x0;
  const double b = ihi < SMIRNOV_GRID - 1 ? x0 + (double)(ihi + 1) * h : x1;
  gsl_integration_glfixed_table *gl =
      gsl_integration_glfixed_table_alloc(SMIRNOV_GL);
  if (!gl)
    return SB_ENOMEM;
  S.lscale = lmax;
  gsl_function F = {smirnov_term, &S};
  const double w = (b - a) / SMIRNOV_PANELS;
  double sum = 0.0;
  for (int k = 0; k < SMIRNOV_PANELS; k++)
    sum += gsl_integration_glfixed(&F, a + k * w,
                                   k == SMIRNOV_PANELS - 1 ? b
                                                           : a + (k + 1) * w,
                                   gl);
  gsl_integration_glfixed_table_free(gl);
  *p = exp(nn * log1p(-d)) + sum * exp(lmax);
  return SB_SUCCESS;
}

/* --------------------------------------------- Durbin / Marsaglia-Tsang-Wang */

/* P(D_n < d) = n!/n^n (H^n)_{kk}, k = ceil-ish(n d), h = k - n d, with the
 * m x m matrix H of Durbin 1973 (MTW 2003 eq. for H).  Powers by squaring
 * with GSL's dgemm; the (k,k) entry is kept below 2^300 by exact power-of-
 * two rescaling whose exponents are tracked. */
static int mtw_cdf(size_t n, double d, double *cdf)
{
  const double nd = (double)n * d;
  const size_t k = (size_t)nd + 1, m = 2 * k - 1;
  const double h = (double)k - nd;
  const int ESC = 300;
  double *w = malloc((3 * m * m + m + 1) * sizeof *w);
  if (!w)
    return SB_ENOMEM;
  double *H = w, *R = w + m * m, *T = w + 2 * m * m, *fi = w + 3 * m * m;
  fi[0] = 1.0; /* fi[r] = 1/r! (may underflow to 0: harmless) */
  for (size_t r = 1; r <= m; r++)
    fi[r] = fi[r - 1] / (double)r;
  for (size_t i = 0; i < m; i++)
    for (size_t j = 0; j < m; j++)
      H[i * m + j] = (i + 1 >= j) ? fi[i + 1 - j] : 0.0;
  for (size_t i = 0; i < m; i++) {
    H[i * m] -= pow(h, (double)(i + 1)) * fi[i + 1];
    H[(m - 1) * m + i] -= pow(h, (double)(m - i)) * fi[m - i];
  }
  if (2.0 * h - 1.0 > 0.0)
    H[(m - 1) * m] += pow(2.0 * h - 1.0, (double)m) * fi[m];

  for (size_t i = 0; i < m * m; i++)
    R[i] = 0.0;
  for (size_t i = 0; i < m; i++)
    R[i * m + i] = 1.0;
  long eR = 0, eH = 0;
  const size_t kk = (k - 1) * m + (k - 1);
  gsl_matrix_view vH = gsl_matrix_view_array(H, m, m);
  gsl_matrix_view vR = gsl_matrix_view_array(R, m, m);
  gsl_matrix_view vT = gsl_matrix_view_array(T, m, m);
  for (size_t e = n;;) {
    if (e & 1) {
      gsl_blas_dgemm(CblasNoTrans, CblasNoTrans, 1.0, &vR.matrix,
                     &vH.matrix, 0.0, &vT.matrix);
      memcpy(R, T, m * m * sizeof *R);
      eR += eH;
      if (fabs(R[kk]) > ldexp(1.0, ESC)) {
        for (size_t i = 0; i < m * m; i++)
          R[i] = ldexp(R[i], -ESC);
        eR += ESC;
      }
    }
    e >>= 1;
    if (!e)
      break;
    gsl_blas_dgemm(CblasNoTrans, CblasNoTrans, 1.0, &vH.matrix, &vH.matrix,
                   0.0, &vT.matrix);
    memcpy(H, T, m * m * sizeof *H);
    eH *= 2;
    if (fabs(H[kk]) > ldexp(1.0, ESC)) {
      for (size_t i = 0; i < m * m; i++)
        H[i] = ldexp(H[i], -ESC);
      eH += ESC;
    }
  }
  /* times n!/n^n, rescaled the same way; long double keeps the n
   * roundings of this product below 1e-15 for n <= 1e5. */
  long double s = R[kk];
  for (size_t i = 1; i <= n; i++) {
    s *= (long double)i / (long double)n;
    if (fabsl(s) < 0x1p-300L) {
      s *= 0x1p300L;
      eR -= ESC;
    }
  }
  free(w);
  *cdf = ldexp((double)s, (int)eR);
  return SB_SUCCESS;
}

/* ------------------------------------------------------------ Pelz-Good */

/* P(sqrt(n) D_n <= z) ~ K0 + K1/n^1/2 + K2/n + K3/n^3/2 (Pelz & Good 1976,
 * in the theta-function form given by Simard & L'Ecuyer 2011).
 * Sums over odd m = 2k-1 of polynomials in m^2 times q^(m^2),
 * q = exp(-pi^2/(8 z^2)), plus sums over k of k^2 (...) exp(-pi^2 k^2 /
 * (2 z^2)). */
static double pelz_good_cdf(size_t n, double d)
{
  const double z = sqrt((double)n) * d;
  const double z2 = z * z, z4 = z2 * z2, z6 = z4 * z2, z8 = z4 * z4;
  const double pi2 = M_PI * M_PI, pi4 = pi2 * pi2, pi6 = pi4 * pi2;
  const double lq = -pi2 / (8.0 * z2);
  if (lq < -745.0)
    return 0.0;
  double s0 = 0, s1 = 0, s2 = 0, s3 = 0;
  for (int k = 1; k < 1000; k++) {
    double mo = 2.0 * k - 1.0, m2 = mo * mo, m4 = m2 * m2, m6 = m4 * m2;
    double e = exp(lq * m2);
    if (e == 0.0)
      break;
    s0 += e;
    s1 += (pi2 * m2 / 4.0 - z2) * e;
    s2 += (6.0 * z6 + 2.0 * z4 + pi2 * (2.0 * z4 - 5.0 * z2) * m2 / 4.0 +
           pi4 * (1.0 - 2.0 * z2) * m4 / 16.0) * e;
    s3 += (-30.0 * z6 - 90.0 * z8 + pi2 * (135.0 * z4 - 96.0 * z6) * m2 / 4.0 +
           pi4 * (212.0 * z4 - 60.0 * z2) * m4 / 16.0 +
           pi6 * (5.0 - 30.0 * z2) * m6 / 64.0) * e;
    if (e < 1e-17 * s0)
      break;
  }
  double t2 = 0, t3 = 0;
  for (int k = 1; k < 1000; k++) {
    double kk = (double)k * k;
    double e = exp(-pi2 * kk / (2.0 * z2));
    if (e == 0.0)
      break;
    t2 += kk * e;
    t3 += (3.0 * z2 - pi2 * kk) * kk * e;
    if (kk * e < 1e-17 * t2)
      break;
  }
  const double r2p = sqrt(2.0 * M_PI), rn = sqrt((double)n);
  double K0 = r2p / z * s0;
  double K1 = r2p / (6.0 * z4) * s1;
  double K2 = r2p / (72.0 * z4 * z2 * z) * s2 - r2p * pi2 / (36.0 * z2 * z) * t2;
  double K3 = r2p / (6480.0 * z8 * z2) * s3 + r2p * pi2 / (216.0 * z6) * t3;
  return K0 + K1 / rn + K2 / (double)n + K3 / ((double)n * rn);
}

/* ------------------------------------------------------------- p-value */

int sb_ks_pvalue_e(size_t n, double d, sb_result *res)
{
  if (n == 0 || isnan(d))
    return SBI_FAIL_RES(res, SB_EINVAL, "need n >= 1 and d not NaN "
                                        "(n = %zu, d = %g)", n, d);
  sb_result r = {1.0, 0.0};
  const double nn = (double)n, nd = nn * d, ndd = nd * d;
  if (nd <= 0.5) { /* D_n >= 1/(2n) always */
    r.val = 1.0;
  } else if (d >= 1.0) {
    r.val = 0.0;
  } else if (nd >= nn - 1.0) { /* Ruben-Gambino: 2 (1 - d)^n */
    r.val = 2.0 * exp(nn * log1p(-d));
    r.err = 4.0 * DBL_EPSILON * (1.0 + fabs(nn * log1p(-d))) * r.val;
  } else if (nd <= 1.0) { /* Ruben-Gambino: CDF = n!/n^n (2 n d - 1)^n */
    double lc = gsl_sf_lngamma(nn + 1.0) - nn * log(nn) +
                nn * log(2.0 * nd - 1.0);
    r.val = -expm1(lc);
    r.err = 8.0 * DBL_EPSILON * (1.0 + nn * log(nn)) * exp(lc) +
            2.0 * DBL_EPSILON * r.val;
  } else if (d >= 0.5 || ndd >= 370.0) {
    /* exact 2 x one-sided for d >= 1/2; for n d^2 >= 370, p < 1e-321. */
    if (ndd >= 370.0 && n > KS_SMIRNOV_NMAX) {
      r.val = 0.0;
      r.err = 1e-320;
    } else {
      r.val = 2.0 * smirnov_sf(n, d);
      r.err = 1e-13 * r.val + 1e-320;
    }
  } else {
    /* A: complement of the CDF (Durbin matrix or Pelz-Good). */
    double cdf, errA;
    size_t m = 2 * ((size_t)nd + 1) - 1;
    int use_mtw = (n <= KS_SMALL_N)
                      ? (ndd <= KS_MTW_NDD_SMALL)
                      : (n <= KS_MTW_NMAX &&
                         (nn * d * sqrt(d) <= KS_MTW_ND15 || m <= KS_MTW_MMAX));
    if (use_mtw) {
      int st = mtw_cdf(n, d, &cdf);
      if (st != SB_SUCCESS)
        return SBI_FAIL_RES(res, st, "no memory for the Durbin matrix");
      errA = KS_MTW_ERR;
    } else if (n > KS_SMALL_N) {
      cdf = pelz_good_cdf(n, d);
      errA = KS_PG_C / (nn * nn) + 1e-15;
    } else {
      cdf = 1.0; /* n <= 140 and n d^2 > 18 (p < 1e-15): use B */
      errA = HUGE_VAL;
    }
    double pA = 1.0 - cdf;
    if (pA < 0.0)
      pA = 0.0;
    if (pA > 1.0)
      pA = 1.0;
    /* B: twice the one-sided tail; the neglected term is the probability
     * of crossing both bands, below p+^2/2 (checked in the tests). */
    double pB = NAN, errB = HUGE_VAL;
    /* B can only win if (pA/2)^2/2 < errA (up to B's own rounding). */
    if ((ndd >= 1.0 || errA == HUGE_VAL) &&
        (errA == HUGE_VAL || pA * pA < 16.0 * errA)) {
      double pp;
      if (n <= KS_SMIRNOV_NMAX) {
        pp = smirnov_sf(n, d);
      } else {
        int st = smirnov_sf_large(n, d, &pp);
        if (st != SB_SUCCESS)
          return SBI_FAIL_RES(res, st, "no memory for the quadrature table");
      }
      pB = 2.0 * pp;
      errB = 0.5 * pp * pp + 1e-13 * pB;
    }
    if (errB < errA) {
      r.val = pB;
      r.err = errB;
    } else {
      r.val = pA;
      r.err = errA;
    }
  }
  if (res)
    *res = r;
  return SB_SUCCESS;
}

double sb_ks_pvalue(size_t n, double d)
{
  sb_result r;
  return sb_ks_pvalue_e(n, d, &r) == SB_SUCCESS ? r.val : NAN;
}

double sb_kolmogorov_sf(double t)
{
  if (isnan(t)) {
    sbi_error(SB_EDOM, __func__, "t is NaN");
    return NAN;
  }
  if (t <= 0.0)
    return 1.0;
  if (t < 1.0) {
    /* CDF = sqrt(2 pi)/t sum_k exp(-(2k-1)^2 pi^2 / (8 t^2)) <= 0.73 here,
     * so 1 - CDF loses nothing. */
    double a = -M_PI * M_PI / (8.0 * t * t), s = 0.0;
    for (int k = 1; k < 100; k++) {
      double mo = 2.0 * k - 1.0, e = exp(a * mo * mo);
      s += e;
      if (e < 1e-17 * s || e == 0.0)
        break;
    }
    if (s == 0.0) /* t < ~0.04: the CDF underflows (and sqrt(2 pi)/t may
                   * overflow): Q = 1 to double precision */
      return 1.0;
    return 1.0 - sqrt(2.0 * M_PI) / t * s;
  }
  double s = 0.0, a = -2.0 * t * t;
  for (int j = 1; j < 100; j++) {
    double e = exp(a * j * j);
    s += (j & 1) ? e : -e;
    if (e < 1e-17 * s || e == 0.0)
      break;
  }
  return 2.0 * s;
}

/* ------------------------------------------------------- one-sample test */

int sb_ks_test(double *x, size_t n, sb_cdf_fn cdf, void *params, double *d,
               double *p)
{
  if (d)
    *d = NAN;
  if (p)
    *p = NAN;
  if (!x || n == 0 || !cdf)
    return sbi_error(SB_EINVAL, __func__, "need samples (n = %zu) and a cdf",
                     n);
  for (size_t i = 0; i < n; i++)
    if (isnan(x[i]))
      return sbi_error(SB_EINVAL, __func__, "x[%zu] is NaN", i);
  gsl_sort(x, 1, n);
  const double nn = (double)n;
  double dmax = 0.0, prev = 0.0;
  for (size_t i = 0; i < n; i++) {
    double f = cdf(x[i], params);
    if (!(f >= 0.0 && f <= 1.0) || f < prev - 1e-12)
      return sbi_error(SB_EINVAL, __func__,
                       "F(%g) = %g is NaN, outside [0,1] or decreasing",
                       x[i], f);
    if (f < prev)
      f = prev; /* rounding-level non-monotonicity */
    prev = f;
    /* D+ = max (i+1)/n - F(x_(i)),  D- = max F(x_(i)) - i/n. */
    double dp = (double)(i + 1) / nn - f, dm = f - (double)i / nn;
    if (dp > dmax)
      dmax = dp;
    if (dm > dmax)
      dmax = dm;
  }
  if (d)
    *d = dmax;
  if (p) {
    sb_result r;
    int st = sb_ks_pvalue_e(n, dmax, &r);
    if (st != SB_SUCCESS)
      return st;
    *p = r.val;
  }
  return SB_SUCCESS;
}

/* ------------------------------------------------------------ two-sample */

/* log[C(2n, n - T) / C(2n, n)] = log[n!^2 / ((n-T)! (n+T)!)] for
 * 1 <= T < n in closed form (Stirling with the exact remainders
 * stirlerr, the log terms as n [(1+u) lpmx(u) + (1-u) lpmx(-u) + 2u^2]
 * with u = T/n, lpmx(u) = log(1+u) - u: no cancellation). */
static double ks2_logratio(size_t nn, size_t TT)
{
  double n = (double)nn, T = (double)TT, u = T / n;
  return 2.0 * stirlerr(n) - stirlerr((double)(nn - TT)) - stirlerr(n + T) -
         n * ((1.0 + u) * gsl_sf_log_1plusx_mx(u) +
              (1.0 - u) * gsl_sf_log_1plusx_mx(-u) + 2.0 * u * u) -
         0.5 * log1p(-u * u);
}

/* Equal sizes, integer threshold h (D >= h/n): Gnedenko & Korolyuk 1951,
 *   P = 2 sum_{j>=1} (-1)^(j+1) C(2n, n - j h) / C(2n, n),
 * the ratios as products prod_{i<t} (n - i)/(n + 1 + i) summed in logs. */
static double ks2_equal(size_t n, size_t h)
{
  /* h^2 < n/325: the paths with |i - j| < h number at most (2h - 1)
   * (2 cos(pi/(2h)))^(2n) (the largest eigenvalue of a path graph on 2h - 1
   * vertices), so P(D < h/n) <= 4 h sqrt(n) exp(-pi^2 n/(4 h^2)) < e^-750
   * and p = 1.  Used only where the sum below would need more than ~1e7
   * terms (n > 1e12). */
  if ((double)n > 1e12 && (double)h * (double)h * 325.0 < (double)n)
    return 1.0;
  double lr = 0.0, s = 0.0;
  size_t t = 0;
  for (size_t j = 1; j <= n / h; j++) { /* j h <= n, without overflow */
    if (j * h > KS2_EQ_LOOP) { /* closed form: O(1) however large n */
      if (j * h > n / 2) /* the ratio is below exp(-0.26 n) (u > 1/2), */
        break;           /* with n > 1e7 far below the smallest double */
      lr = ks2_logratio(n, j * h);
    } else {
      for (; t < j * h; t++)
        lr += log1p(-(2.0 * t + 1.0) / ((double)n + 1.0 + (double)t));
    }
    double term = exp(lr);
    s += (j & 1) ? term : -term;
    if (term < 1e-17 * s || term == 0.0)
      break;
  }
  return 2.0 * s;
}

/* P(max |i ny - j nx| >= c) over uniformly random lattice paths from (0,0)
 * to (nx,ny): B(i,j) = share of the paths to (i,j) that already touched the
 * boundary; B = 1 on it, else (i B(i-1,j) + j B(i,j-1))/(i+j).  Only sums
 * of positive terms: no cancellation even for tiny p. */
static int ks2_paths(size_t nx, size_t ny, long long c, double *p)
{
  double *B = malloc((ny + 1) * sizeof *B);
  if (!B)
    return SB_ENOMEM;
  for (size_t i = 0; i <= nx; i++) {
    for (size_t j = 0; j <= ny; j++) {
      long long dev = (long long)i * (long long)ny - (long long)j * (long long)nx;
      if (dev < 0)
        dev = -dev;
      if (dev >= c)
        B[j] = 1.0;
      else if (i == 0 && j == 0)
        B[j] = 0.0;
      else {
        double up = i ? (double)i * B[j] : 0.0;
        double left = j ? (double)j * B[j - 1] : 0.0;
        B[j] = (up + left) / (double)(i + j);
      }
    }
  }
  *p = B[ny];
  free(B);
  return SB_SUCCESS;
}

double sb_ks2_pvalue(size_t nx, size_t ny, double d)
{
  if (nx == 0 || ny == 0 || isnan(d)) {
    sbi_error(SB_EINVAL, __func__, "need nx, ny >= 1 and d not NaN "
                                   "(nx = %zu, ny = %zu)", nx, ny);
    return NAN;
  }
  if (d <= 0.0)
    return 1.0;
  if (d > 1.0)
    return 0.0;
  const double L = (double)nx * (double)ny;
  /* D takes values |i ny - j nx| / (nx ny): recover the integer. */
  double c = d * L, cr = nearbyint(c);
  double ci = fabs(c - cr) <= 1e-9 * c ? cr : ceil(c);
  if (nx == ny) {
    double hd = ceil(ci / (double)nx); /* |i - j| >= h */
    /* h >= n: P = 2/C(2n, n) (h = n) or 0, and 2/C(2n, n) underflows for
     * n > 540 (also keeps h representable when n is near SIZE_MAX) */
    if (hd >= (double)nx && nx > 1000)
      return 0.0;
    return fmin(1.0, ks2_equal(nx, (size_t)hd)); /* sum may round above 1 */
  }
  if (L <= KS2_DP_MAX) {
    double p;
    if (ks2_paths(nx, ny, (long long)ci, &p) != SB_SUCCESS) {
      sbi_error(SB_ENOMEM, __func__, "no memory");
      return NAN;
    }
    return p;
  }
  double ne = L / ((double)nx + (double)ny), rne = sqrt(ne);
  return sb_kolmogorov_sf((rne + 0.12 + 0.11 / rne) * d);
}

int sb_ks2_test(double *x, size_t nx, double *y, size_t ny, double *d,
                double *p)
{
  if (d)
    *d = NAN;
  if (p)
    *p = NAN;
  if (!x || !y || nx == 0 || ny == 0)
    return sbi_error(SB_EINVAL, __func__, "empty sample (nx = %zu, "
                                          "ny = %zu)", nx, ny);
  for (size_t i = 0; i < nx; i++)
    if (isnan(x[i]))
      return sbi_error(SB_EINVAL, __func__, "x[%zu] is NaN", i);
  for (size_t j = 0; j < ny; j++)
    if (isnan(y[j]))
      return sbi_error(SB_EINVAL, __func__, "y[%zu] is NaN", j);
  gsl_sort(x, 1, nx);
  gsl_sort(y, 1, ny);
  /* Step through the merged order; equal values in both samples move
   * together, so ties never create a spurious jump. */
  size_t i = 0, j = 0;
  double dmax = 0.0;
  const double fx = 1.0 / (double)nx, fy = 1.0 / (double)ny;
  while (i < nx && j < ny) {
    double v = x[i] < y[j] ? x[i] : y[j];
    while (i < nx && x[i] == v)
      i++;
    while (j < ny && y[j] == v)
      j++;
    double dev = fabs((double)i * fx - (double)j * fy);
    if (dev > dmax)
      dmax = dev;
  }
  if (d)
    *d = dmax;
  if (p) {
    double pv = sb_ks2_pvalue(nx, ny, dmax);
    if (isnan(pv))
      return sb_last_status();
    *p = pv;
  }
  return SB_SUCCESS;
}
