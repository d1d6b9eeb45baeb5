/* pbe_check.c — comparisons of population-balance solutions with the
 * analytic ones (pbe_analytic.c), written once for the tests
 * (tests/test_pbe.c), `smolbridge validate` (lib/validate/cases_pbe.c) and the
 * benches. */
#include <math.h>

#include <smolbridge/pbe.h>

#include "common/internal.h"

int sb_pbe_config_sectional(sb_pbe_config *cfg, size_t nsections,
                            double decades)
{
  if (!cfg)
    return sbi_error(SB_EINVAL, __func__, "cfg is NULL");
  if (nsections < 2)
    return sbi_error(SB_EINVAL, __func__, "nsections must be >= 2 (got %zu)",
                     nsections);
  if (!(decades > 0 && isfinite(decades)))
    return sbi_error(SB_EINVAL, __func__,
                     "decades must be finite and > 0 (got %g)", decades);
  const double ratio = pow(10.0, decades / (double)(nsections - 1));
  if (!(ratio > 1.0 && isfinite(ratio)))
    return sbi_error(SB_EINVAL, __func__, "%g decades over %zu sections: "
                     "pivot ratio %g (need finite > 1)", decades, nsections,
                     ratio);
  cfg->method = SB_PBE_SECTIONAL;
  cfg->nsizes = nsections;
  cfg->ratio = ratio;
  return SB_SUCCESS;
}

int sb_pbe_config_sectional_ratio(sb_pbe_config *cfg, double ratio,
                                  double decades)
{
  if (!cfg)
    return sbi_error(SB_EINVAL, __func__, "cfg is NULL");
  if (!(ratio > 1 && isfinite(ratio)))
    return sbi_error(SB_EINVAL, __func__,
                     "ratio must be finite and > 1 (got %g)", ratio);
  if (!(decades > 0 && isfinite(decades)))
    return sbi_error(SB_EINVAL, __func__,
                     "decades must be finite and > 0 (got %g)", decades);
  /* the count as a double first: beyond SIZE_MAX (or +inf) the conversion
   * was undefined (it wrapped to 1 on x86-64) */
  const double cnt = ceil(decades * log(10.0) / log(ratio)) + 1;
  if (!(cnt <= 1e6))
    return sbi_error(SB_EINVAL, __func__, "ratio %g over %g decades needs "
                     "%g sections (sb_pbe_alloc allows at most 1e6)", ratio,
                     decades, cnt);
  cfg->method = SB_PBE_SECTIONAL;
  cfg->ratio = ratio;
  cfg->nsizes = (size_t)cnt;
  return SB_SUCCESS;
}

/* Output callback of sb_pbe_solve_moments: copies the moments to the next
 * row. */
static int mom_out(double t, const double *v, const double *n, size_t nb,
                   const double mom[3], void *data)
{
  double(**row)[3] = data;
  (void)t;
  (void)v;
  (void)n;
  (void)nb;
  for (int j = 0; j < 3; j++)
    (**row)[j] = mom[j];
  (*row)++;
  return 0;
}

int sb_pbe_solve_moments(sb_pbe *p, const double *times, size_t ntimes,
                         double m[][3], sb_pbe_report *rep)
{
  if (!m)
    return sbi_error(SB_EINVAL, __func__, "m is NULL");
  double(*row)[3] = m;
  int st = sb_pbe_solve(p, times, ntimes, mom_out, &row, rep);
  if (st) /* the message names this function, then sb_pbe_solve's */
    return sbi_error(st, __func__, "%s", sb_last_error());
  return st;
}

/* sum of w_i and of w_i (l_i - mu)^j, l = ln(v)/3, weights w_i = n_i 2^-e
 * (j = 1 with mu = 0: the mean's sum; j = 2: the variance's) */
static void sigma_sums(const double *v, const double *n, size_t nbins, int e,
                       double mu, int j, double s[2])
{
  s[0] = s[1] = 0;
  for (size_t i = 0; i < nbins; i++)
    if (n[i] > 0) {
      double d = log(v[i]) / 3 - mu, w = ldexp(n[i], -e);
      s[0] += w;
      s[1] += j == 1 ? w * d : w * d * d;
    }
}

double sb_pbe_sigma_g(const double *v, const double *n, size_t nbins)
{
  double nmax = 0;
  for (size_t i = 0; v && n && i < nbins; i++) {
    if (isnan(n[i]) ||
        (n[i] > 0 && (isinf(n[i]) || !(v[i] > 0 && isfinite(v[i]))))) {
      sbi_error(SB_EDOM, __func__, "bin %zu: n = %g, v = %g (need n not NaN, "
                "and finite n, finite v > 0 where n > 0)", i, n[i], v[i]);
      return NAN;
    }
    if (n[i] > nmax)
      nmax = n[i];
  }
  if (!(nmax > 0)) {
    sbi_error(SB_EINVAL, __func__, "no bin with n > 0 (or v, n NULL)");
    return NAN;
  }
  /* two passes (mean, then squared deviations): the one-pass s2/s0 -
   * (s1/s0)^2 rounded to slightly below 0 or above where one bin dominates
   * (a monodisperse distribution gave NaN, or 1 + 3e-9); weights scaled by
   * 2^-e, e = ilogb(max n), where the sums would overflow */
  const int e = nmax > 0x1p900 ? ilogb(nmax) : 0;
  double s[2];
  sigma_sums(v, n, nbins, e, 0.0, 1, s);
  const double mu = s[1] / s[0];
  sigma_sums(v, n, nbins, e, mu, 2, s);
  return exp(sqrt(s[1] / s[0]));
}

double sb_pbe_mono_n(sb_pbe_kernel_kind kind, double k, double tau)
{
  double n;
  switch (kind) {
  case SB_PBE_CONSTANT:
    n = sb_pbe_const_mono_n(k, tau);
    break;
  case SB_PBE_ADDITIVE:
    n = sb_pbe_add_mono_n(k, tau);
    break;
  case SB_PBE_MULTIPLICATIVE:
    n = sb_pbe_mult_mono_n(k, tau);
    break;
  default:
    sbi_error(SB_EINVAL, __func__, "unknown kernel kind %d", (int)kind);
    return NAN;
  }
  if (isnan(n)) /* the message names this function, then the solution */
    sbi_error(sb_last_status(), __func__, "%s", sb_last_error());
  return n;
}

int sb_pbe_compare_analytic(const double *n, size_t kmax,
                            sb_pbe_kernel_kind kind, double tau, double nmin,
                            sb_pbe_analytic_cmp *res)
{
  if (!res)
    return sbi_error(SB_EINVAL, __func__, "res is NULL");
  *res = (sb_pbe_analytic_cmp){0, 0, 0, 0, 0};
  if (!n || kmax == 0)
    return sbi_error(SB_EINVAL, __func__, "n is NULL or kmax = 0");
  for (size_t k = 1; k <= kmax; k++) {
    double a = sb_pbe_mono_n(kind, (double)k, tau);
    if (isnan(a)) { /* error recorded by the analytic solution */
      *res = (sb_pbe_analytic_cmp){0, 0, 0, 0, 0};
      return sbi_error(sb_last_status(), __func__, "%s", sb_last_error());
    }
    if (!(a >= nmin))
      continue;
    double e = fabs(n[k - 1] / a - 1);
    if (isnan(e))
      e = INFINITY;
    res->nchecked++;
    if (e >= res->maxrel) {
      res->maxrel = e;
      res->kworst = k;
      res->nworst = n[k - 1];
      res->exact_worst = a;
    }
  }
  return SB_SUCCESS;
}

/* Output callback of sb_pbe_gelation_time: keeps the previous output and
 * stops at the one after the first M2 > m2_cross. */
typedef struct {
  double cross, tprev, m2prev, tgel;
  int n;
} gel_state;

static int gel_out(double t, const double *v, const double *n, size_t nb,
                   const double mom[3], void *data)
{
  gel_state *g = data;
  (void)v;
  (void)n;
  (void)nb;
  if (g->n++ > 0 && g->m2prev > g->cross) {
    double a = 1 / g->m2prev, b = 1 / mom[2];
    g->tgel = g->tprev + a * (t - g->tprev) / (a - b);
    return 1;
  }
  g->tprev = t;
  g->m2prev = mom[2];
  return 0;
}

int sb_pbe_gelation_time(sb_pbe *p, const double *times, size_t ntimes,
                         double m2_cross, double *tgel)
{
  if (!tgel)
    return sbi_error(SB_EINVAL, __func__, "tgel is NULL");
  *tgel = NAN;
  if (!(m2_cross > 0 && isfinite(m2_cross)))
    return sbi_error(SB_EINVAL, __func__,
                     "m2_cross must be finite and > 0 (got %g)", m2_cross);
  gel_state g = {m2_cross, 0, 0, NAN, 0};
  int st = sb_pbe_solve(p, times, ntimes, gel_out, &g, NULL);
  if (!isnan(g.tgel)) { /* the solve was stopped by gel_out */
    *tgel = g.tgel;
    return SB_SUCCESS;
  }
  if (st) /* the message names this function, then sb_pbe_solve's */
    return sbi_error(st, __func__, "%s", sb_last_error());
  return sbi_error(SB_EINVAL, __func__,
                   "M2 did not exceed %g before the last time", m2_cross);
}
