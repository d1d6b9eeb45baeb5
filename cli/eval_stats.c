/* eval_stats.c — `smolbridge eval` entries of the stats module: exact
 * Poisson and binomial intervals and tests, z-scores, Kolmogorov-Smirnov
 * and chi-square distributions.  Counts are checked to be integers >= 0
 * before the call (the C arguments are unsigned). */
#include <math.h>

#include <smolbridge/common.h>
#include <smolbridge/stats.h>

#include "cli.h"

/* A count argument: integer in [0, 2^53]; SB_EDOM otherwise. */
static int count_ok(double x) { return x >= 0 && x <= 9007199254740992.0 &&
                                       x == floor(x); }

static int sbe_w_poisson_ci(const double *i, double *o)
{
  if (!count_ok(i[0]))
    return SB_EDOM;
  return sb_poisson_ci((unsigned long)i[0], i[1], &o[0], &o[1]);
}
static int sbe_w_poisson_rate_ci(const double *i, double *o)
{
  if (!count_ok(i[0]))
    return SB_EDOM;
  return sb_poisson_rate_ci((unsigned long)i[0], i[1], i[2], &o[0], &o[1]);
}
static int sbe_w_binomial_ci(const double *i, double *o)
{
  if (!count_ok(i[0]) || !count_ok(i[1]))
    return SB_EDOM;
  return sb_binomial_ci((unsigned long)i[0], (unsigned long)i[1], i[2],
                        &o[0], &o[1]);
}
static int sbe_w_poisson_pvalue(const double *i, double *o)
{
  if (!count_ok(i[0]))
    return SB_EDOM;
  o[0] = sb_poisson_pvalue((unsigned long)i[0], i[1]);
  return 0;
}
static int sbe_w_binomial_pvalue(const double *i, double *o)
{
  if (!count_ok(i[0]) || !count_ok(i[1]))
    return SB_EDOM;
  o[0] = sb_binomial_pvalue((unsigned long)i[0], (unsigned long)i[1], i[2]);
  return 0;
}
static int sbe_w_ks_pvalue(const double *i, double *o)
{
  if (!count_ok(i[0]) || i[0] < 1)
    return SB_EDOM;
  o[0] = sb_ks_pvalue((size_t)i[0], i[1]);
  return 0;
}
static int sbe_w_ks2_pvalue(const double *i, double *o)
{
  if (!count_ok(i[0]) || !count_ok(i[1]) || i[0] < 1 || i[1] < 1)
    return SB_EDOM;
  o[0] = sb_ks2_pvalue((size_t)i[0], (size_t)i[1], i[2]);
  return 0;
}
SBE_WRAP3(zscore)
SBE_WRAP1(zscore_pvalue)
SBE_WRAP2(chi2_sf)
SBE_WRAP1(kolmogorov_sf)

#define E(n, args, outs, text) {#n, args, outs, sbe_w_##n, text}
#define ONE {NULL}
#define LOHI {"lo", "hi", NULL}
#define A_KL {"k", "level", NULL}
#define A_KSL {"k", "scale", "level", NULL}
#define A_KNL {"k", "n", "level", NULL}
#define A_KMU {"k", "mu", NULL}
#define A_KNP {"k", "n", "p", NULL}
#define A_Z3 {"estimate", "reference", "stderr", NULL}
#define A_Z {"z", NULL}
#define A_XD {"x", "dof", NULL}
#define A_ND {"n", "d", NULL}
#define A_NND {"nx", "ny", "d", NULL}
#define A_T {"t", NULL}

static const sbe_func funcs[] = {
    E(poisson_ci, A_KL, LOHI,
      "exact (Garwood) interval of a Poisson mean from count k"),
    E(poisson_rate_ci, A_KSL, LOHI, "Garwood interval of the rate scale * k"),
    E(binomial_ci, A_KNL, LOHI,
      "exact (Clopper-Pearson) interval of a proportion k/n"),
    E(poisson_pvalue, A_KMU, ONE,
      "exact two-sided Poisson test of count k against mean mu"),
    E(binomial_pvalue, A_KNP, ONE,
      "exact two-sided binomial test of k in n against p"),
    E(zscore, A_Z3, ONE, "(estimate - reference)/stderr"),
    E(zscore_pvalue, A_Z, ONE, "two-sided normal p-value of z"),
    E(chi2_sf, A_XD, ONE, "chi-square upper tail P(X > x)"),
    E(ks_pvalue, A_ND, ONE, "one-sample KS: P(D_n >= d) for n samples"),
    E(ks2_pvalue, A_NND, ONE, "two-sample KS p-value"),
    E(kolmogorov_sf, A_T, ONE,
      "Kolmogorov distribution P(K > t) (asymptotic KS)"),
};

const sbe_table sbe_table_stats = {funcs, sizeof funcs / sizeof funcs[0]};
