/* test_passage.c — first-passage laws (passage.c) and the internal numerical
 * helpers they rest on (numutil.c).
 *
 * Independent references:
 *  - the CSV files in tests/data, from tests/gen_refdata.py (mpmath, 50-200 digits,
 *    textbook closed forms, themselves checked there against mp.quad);
 *  - GSL QAGS quadrature of the densities (every CDF here);
 *  - limits (t -> inf gives the mass; x == a), identities (cdf + sf = 1);
 *  - Monte Carlo for the sampler (fixed seeds, stated criteria).
 * Tolerances: TOL_REF (1e-12, the promised accuracy) against mpmath, and
 * the _e error estimate must cover the true error; TOL_QUAD against
 * quadrature.
 */
#include <float.h>
#include <math.h>
#include <string.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <gsl/gsl_rng.h>

#include <smolbridge/passage.h>
#include "common/numutil.h"
#include "refdata.h"
#include "sweep.h"
#include "testutil.h"

/* ------------------------------------------------------------ numutil */

START_TEST(test_mills)
{
  sbt_table t;
  sbt_table_load("mills.csv", &t);
  int cz = sbt_col(&t, "z"), cm = sbt_col(&t, "M");
  double worst = 0.0;
  for (int i = 0; i < t.nrow; i++) {
    double z = sbt_at(&t, i, cz), m = sbt_at(&t, i, cm);
    double e = sbt_reldiff(sbi_mills(z), m);
    ck_assert_msg(e <= TOL_ULPS(4), "M(%g): rel error %.3g", z, e);
    worst = fmax(worst, e);
  }
  printf("sbi_mills: max rel error %.2g (%d points)\n", worst, t.nrow);
  sbt_table_free(&t);
}
END_TEST

START_TEST(test_mills_diff)
{
  /* both branches: direct difference and the positive series with the
   * forward (z <= 3) and backward (z > 3) recurrences */
  sbt_table t;
  sbt_table_load("mdiff.csv", &t);
  int cz = sbt_col(&t, "z"), ch = sbt_col(&t, "h"), cl = sbt_col(&t, "lo"),
      cd = sbt_col(&t, "D");
  double worst = 0.0;
  for (int i = 0; i < t.nrow; i++) {
    double z = sbt_at(&t, i, cz), h = sbt_at(&t, i, ch);
    double lo = sbt_at(&t, i, cl), d = sbt_at(&t, i, cd), rel;
    double got = sbi_mills_diff(z, h, lo, &rel);
    double e = sbt_reldiff(got, d);
    ck_assert_msg(e <= TOL_ULPS(32) && e <= rel,
                  "D(%g, %g) = %.17g want %.17g: rel %.3g (bound %.3g)", z,
                  h, got, d, e, rel);
    worst = fmax(worst, e);
  }
  printf("sbi_mills_diff: max rel error %.2g (%d points)\n", worst, t.nrow);
  sbt_table_free(&t);
}
END_TEST

START_TEST(test_log1mexp)
{
  sbt_table t;
  sbt_table_load("log1mexp.csv", &t);
  for (int i = 0; i < t.nrow; i++) {
    double x = sbt_at(&t, i, 0), want = sbt_at(&t, i, 1);
    ck_assert_rel(sbi_log1mexp(x), want, TOL_ULPS(4));
  }
  sbt_table_free(&t);
  ck_assert(isinf(sbi_log1mexp(0.0)) && sbi_log1mexp(0.0) < 0);
}
END_TEST

START_TEST(test_dd)
{
  /* error-free transformations: (1 + 2^-30)^2 = 1 + 2^-29 + 2^-60 */
  double a = 1.0 + ldexp(1.0, -30);
  sbi_dd p = sbi_dd_prod(a, a);
  ck_assert(p.hi == 1.0 + ldexp(1.0, -29) && p.lo == ldexp(1.0, -60));
  sbi_dd s = sbi_dd_sum(1.0, ldexp(1.0, -70));
  ck_assert(s.hi == 1.0 && s.lo == ldexp(1.0, -70));
  /* 1/3 in double-double: 3 * (1/3) - 1 to ~1e-32 */
  sbi_dd q = sbi_dd_div((sbi_dd){1.0, 0.0}, (sbi_dd){3.0, 0.0});
  sbi_dd r = sbi_dd_add(sbi_dd_mul_d(q, 3.0), (sbi_dd){-1.0, 0.0});
  ck_assert(fabs(r.hi + r.lo) < 1e-31);
  /* exp(-E) of a double-double E */
  sbi_dd E = {700.0, 1e-14};
  ck_assert_rel(sbi_dd_expneg(E), exp(-700.0) * (1.0 - 1e-14), TOL_ULPS(2));
}
END_TEST

/* g(y) = y^3 + y - 2 (root 1) with both derivatives; and a g without the
 * second derivative and a flat start, to exercise the safeguards */
static double cubic(double y, void *ctx, double *d, double *d2)
{
  int *n = ctx;
  (*n)++;
  *d = 3.0 * y * y + 1.0;
  *d2 = 6.0 * y;
  return y * y * y + y - 2.0;
}

static double atan_shift(double y, void *ctx, double *d, double *d2)
{
  int *n = ctx;
  (*n)++;
  *d = 1.0 / (1.0 + (y - 30.0) * (y - 30.0));
  *d2 = NAN;
  return atan(y - 30.0); /* flat far from the root: Newton overshoots */
}

START_TEST(test_solver)
{
  int n = 0;
  double root, dy;
  ck_assert_int_eq(sbi_solve_increasing(cubic, &n, 10.0, 1.0, 1e-13, &root,
                                        &dy), SB_SUCCESS);
  ck_assert_rel(root, 1.0, TOL_ULPS(2));
  ck_assert_int_le(n, 12);
  n = 0;
  ck_assert_int_eq(sbi_solve_increasing(atan_shift, &n, 0.0, 1.0, 1e-13,
                                        &root, &dy), SB_SUCCESS);
  ck_assert_rel(root, 30.0, TOL_ULPS(2));
  ck_assert_int_le(n, 60);
}
END_TEST

START_TEST(test_ig_sampler_moments)
{
  /* MSH draws of IG(m, lambda): mean m, variance m^3/lambda.  n = 200000,
   * seed 7; pass if the sample mean is within 5 standard errors and the
   * sample variance within 5 of its standard errors (4th cumulant of IG:
   * 15 m^7/lambda^3).  A wrong root choice in MSH shifts the mean by O(1). */
  gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
  gsl_rng_set(r, 7);
  const double par[][2] = {{1.0, 3.0}, {2.0, 0.2}, {0.5, 40.0}};
  for (int k = 0; k < 3; k++) {
    double m = par[k][0], lam = par[k][1];
    const int n = 200000;
    double s = 0.0, s2 = 0.0;
    for (int i = 0; i < n; i++) {
      double x = sbi_ig_sample(r, m, lam);
      s += x;
      s2 += x * x;
    }
    double mean = s / n, var = s2 / n - mean * mean;
    double v = m * m * m / lam, k4 = 15.0 * pow(m, 7) / pow(lam, 3);
    ck_assert_msg(fabs(mean - m) < 5.0 * sqrt(v / n), "IG(%g,%g) mean %g", m,
                  lam, mean);
    ck_assert_msg(fabs(var - v) < 5.0 * sqrt((k4 + 2.0 * v * v) / n),
                  "IG(%g,%g) variance %g want %g", m, lam, var, v);
  }
  gsl_rng_free(r);
}
END_TEST

/* ------------------------------------------------- BM with drift: values */

START_TEST(test_bm_reference)
{
  sbt_table t;
  sbt_table_load("passage_bm.csv", &t);
  int ct = sbt_col(&t, "t"), cx = sbt_col(&t, "x"), ca = sbt_col(&t, "a"),
      cm = sbt_col(&t, "mu"), cs = sbt_col(&t, "sigma2"),
      cp = sbt_col(&t, "pdf"), cc = sbt_col(&t, "cdf"),
      cf = sbt_col(&t, "sf"), cma = sbt_col(&t, "mass"),
      clm = sbt_col(&t, "logmass");
  double worst[3] = {0, 0, 0};
  int n = 0;
  for (int i = 0; i < t.nrow; i++) {
    double tt = sbt_at(&t, i, ct), x = sbt_at(&t, i, cx),
           a = sbt_at(&t, i, ca), mu = sbt_at(&t, i, cm),
           s2 = sbt_at(&t, i, cs);
    double want[3] = {sbt_at(&t, i, cp), sbt_at(&t, i, cc),
                      sbt_at(&t, i, cf)};
    sb_result r[3];
    ck_assert_int_eq(sb_bm_fpt_pdf_e(tt, x, a, mu, s2, &r[0]), SB_SUCCESS);
    ck_assert_int_eq(sb_bm_fpt_cdf_e(tt, x, a, mu, s2, &r[1]), SB_SUCCESS);
    ck_assert_int_eq(sb_bm_fpt_sf_e(tt, x, a, mu, s2, &r[2]), SB_SUCCESS);
    const char *nm[3] = {"pdf", "cdf", "sf"};
    for (int k = 0; k < 3; k++) {
      if (want[k] < 0) /* reference below 1e-300: not a normal double */
        continue;
      char what[160];
      snprintf(what, sizeof what, "fpt %s(t=%g, x=%g, a=%g, mu=%g, s2=%g)",
               nm[k], tt, x, a, mu, s2);
      ck_assert_result(r[k], want[k], TOL_REF, what);
      worst[k] = fmax(worst[k], sbt_reldiff(r[k].val, want[k]));
      n++;
    }
    /* the plain form returns the same value */
    ck_assert(sb_bm_fpt_cdf(tt, x, a, mu, s2) == r[1].val);
    /* mass -1: below 1e-300, where only logmass = log(mass) shows its
     * exponent (the mass exp(-2e300) of a 60-digit computation once had a
     * wrong one); sb_bm_fpt_logmass has it also there */
    double mass = sb_bm_fpt_mass(x, a, mu, s2), want_m = sbt_at(&t, i, cma),
           want_lm = sbt_at(&t, i, clm);
    if (want_m < 0)
      ck_assert_msg(mass < 1e-300 && want_lm < log(1e-300),
                    "mass(x=%g, a=%g, mu=%g, s2=%g) = %g, log %g: want "
                    "below 1e-300", x, a, mu, s2, mass, want_lm);
    else
      ck_assert_rel(mass, want_m, TOL_ULPS(4));
    sb_result lm;
    ck_assert_int_eq(sb_bm_fpt_logmass_e(x, a, mu, s2, &lm), SB_SUCCESS);
    ck_assert(sb_bm_fpt_logmass(x, a, mu, s2) == lm.val);
    if (want_lm < 0.0) { /* nu < 0 */
      ck_assert_rel(lm.val, want_lm, TOL_ULPS(2));
      ck_assert_msg(fabs(lm.val - want_lm) <= lm.err,
                    "logmass err %g does not cover %g", lm.err,
                    fabs(lm.val - want_lm));
    } else {
      ck_assert(want_lm == 0.0 && mass == 1.0 && lm.val == 0.0);
    }
  }
  printf("bm_fpt vs mpmath (%d values): max rel error pdf %.2g cdf %.2g "
         "sf %.2g\n", n, worst[0], worst[1], worst[2]);
  sbt_table_free(&t);
}
END_TEST

START_TEST(test_bm_identities)
{
  /* cdf + sf = 1; t -> inf gives the mass; x == a gives T = 0; t = 0 */
  const double par[][4] = {{1, 0, 1, 1}, {1, 0, -1, 1}, {0, 2, -0.3, 0.5},
                           {3, 1, 0, 2}};
  for (int k = 0; k < 4; k++) {
    double x = par[k][0], a = par[k][1], mu = par[k][2], s2 = par[k][3];
    for (double t = 1e-3; t < 1e4; t *= 3.7) {
      double c = sb_bm_fpt_cdf(t, x, a, mu, s2), s = sb_bm_fpt_sf(t, x, a,
                                                                  mu, s2);
      ck_assert_abs(c + s, 1.0, TOL_ULPS(4));
    }
    double mass = sb_bm_fpt_mass(x, a, mu, s2);
    ck_assert_rel(sb_bm_fpt_cdf(INFINITY, x, a, mu, s2), mass, TOL_ULPS(1));
    ck_assert_rel(sb_bm_fpt_cdf(1e12, x, a, mu, s2), mass, 1e-5);
    ck_assert(sb_bm_fpt_cdf(0.0, x, a, mu, s2) == 0.0);
    ck_assert(sb_bm_fpt_sf(0.0, x, a, mu, s2) == 1.0);
    ck_assert(sb_bm_fpt_cdf(0.7, a, a, mu, s2) == 1.0);
    ck_assert(sb_bm_fpt_quantile(0.3, a, a, mu, s2) == 0.0);
  }
  /* mass = exp(-2 d |mu| / sigma2) when the drift points away */
  ck_assert_rel(sb_bm_fpt_mass(1.0, 0.0, 1.0, 1.0), exp(-2.0), TOL_ULPS(2));
  ck_assert_rel(sb_bm_fpt_mass(0.0, 1.0, -0.5, 2.0), exp(-0.5), TOL_ULPS(2));
  ck_assert(sb_bm_fpt_mass(0.0, 1.0, 0.5, 2.0) == 1.0);
}
END_TEST

/* ------------------------------------------------- quadrature checks */

typedef struct {
  double x, a, mu, s2;
  int bes3;
} fpt_q;

static double fpt_density(double t, void *vp)
{
  const fpt_q *q = vp;
  if (t <= 0.0)
    return 0.0;
  return q->bes3 ? sb_bes3_fpt_pdf(t, q->x, q->a, q->s2)
                 : sb_bm_fpt_pdf(t, q->x, q->a, q->mu, q->s2);
}

START_TEST(test_cdf_vs_quadrature)
{
  /* every CDF closed form against GSL QAGS of its density */
  gsl_integration_workspace *w = gsl_integration_workspace_alloc(1000);
  const fpt_q cases[] = {
      {1, 0, 1, 1, 0},     {1, 0, -1, 1, 0},   {0, 1, 0, 1, 0},
      {2, 1.5, 3, 0.3, 0}, {3, 1, -0.2, 2, 0}, {2, 1, 0, 1, 1},
      {5, 0.5, 0, 3, 1},   {1, 0.999, 0, 1, 1}};
  const double ts[] = {0.01, 0.3, 1.0, 2.5, 10.0};
  for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
    fpt_q q = cases[k];
    gsl_function F = {fpt_density, &q};
    double d = fabs(q.x - q.a), td = d * d / q.s2; /* diffusive time */
    for (int j = 0; j < 5; j++) {
      /* QAGP with break points at 0.1, 1, 10 diffusive times (the density
       * can be a narrow peak there) */
      double pts[5];
      size_t np = 0;
      pts[np++] = 0.0;
      for (double f = 0.1; f < 11.0; f *= 10.0)
        if (f * td < ts[j])
          pts[np++] = f * td;
      pts[np++] = ts[j];
      double res, err;
      int st = gsl_integration_qagp(&F, pts, np, 0.0, 1e-11, 1000, w, &res,
                                    &err);
      ck_assert_msg(st == GSL_SUCCESS, "case %zu t=%g: QAGS status %d", k,
                    ts[j], st);
      double c = q.bes3 ? sb_bes3_fpt_cdf(ts[j], q.x, q.a, q.s2)
                        : sb_bm_fpt_cdf(ts[j], q.x, q.a, q.mu, q.s2);
      ck_assert_msg(fabs(c - res) <= TOL_QUAD * res + 1e-300,
                    "case %zu t=%g: cdf %.17g quadrature %.17g", k, ts[j], c,
                    res);
    }
  }
  gsl_integration_workspace_free(w);
}
END_TEST

/* ---------------------------------------------------------- quantiles */

START_TEST(test_quantile_reference)
{
  sbt_table t;
  sbt_table_load("passage_quantile.csv", &t);
  double worst = 0.0;
  for (int i = 0; i < t.nrow; i++) {
    double p = sbt_at(&t, i, 0), x = sbt_at(&t, i, 1), a = sbt_at(&t, i, 2),
           mu = sbt_at(&t, i, 3), s2 = sbt_at(&t, i, 4), q = sbt_at(&t, i, 5);
    sb_result r;
    ck_assert_int_eq(sb_bm_fpt_quantile_e(p, x, a, mu, s2, &r), SB_SUCCESS);
    char what[120];
    snprintf(what, sizeof what, "quantile(p=%g, x=%g, a=%g, mu=%g)", p, x, a,
             mu);
    /* full double precision: a few ulp */
    ck_assert_msg(sbt_reldiff(r.val, q) <= TOL_ULPS(16),
                  "%s = %.17g want %.17g", what, r.val, q);
    ck_assert_result(r, q, TOL_REF, what);
    worst = fmax(worst, sbt_reldiff(r.val, q));
  }
  printf("bm_fpt_quantile vs mpmath: max rel error %.2g\n", worst);
  sbt_table_free(&t);
}
END_TEST

START_TEST(test_quantile_roundtrip)
{
  /* |cdf(quantile(p)) - p| <= 1e-13 on a grid including the ends, several
   * laws: IG concentrated and dispersed, Levy, defective */
  const double par[][4] = {{1, 0, 1, 1},     {0, 1, 1e3, 1},
                           {0, 1, 1e-3, 1},  {1, 0, 0, 1},
                           {1, 0, -1, 1},    {2, -1, 0.05, 0.01},
                           {1e4, 0, 1, 1e4}, {0, 1e-6, 1, 1}};
  double grid[40];
  int ng = 0;
  for (int e = -12; e <= -1; e++)
    grid[ng++] = pow(10.0, e);
  for (double p = 0.2; p < 0.85; p += 0.1)
    grid[ng++] = p;
  for (int e = -1; e >= -12; e--)
    grid[ng++] = 1.0 - pow(10.0, e);
  double worst = 0.0;
  for (int k = 0; k < 8; k++) {
    double x = par[k][0], a = par[k][1], mu = par[k][2], s2 = par[k][3];
    double mass = sb_bm_fpt_mass(x, a, mu, s2);
    for (int i = 0; i < ng; i++) {
      double p = grid[i] * (mass < 1.0 ? mass : 1.0);
      sb_result r;
      ck_assert_int_eq(sb_bm_fpt_quantile_e(p, x, a, mu, s2, &r),
                       SB_SUCCESS);
      double c = p <= 0.5 ? sb_bm_fpt_cdf(r.val, x, a, mu, s2)
                          : 1.0 - sb_bm_fpt_sf(r.val, x, a, mu, s2);
      ck_assert_msg(fabs(c - p) <= 1e-13,
                    "set %d p=%.17g: q=%.17g cdf(q)=%.17g", k, p, r.val, c);
      worst = fmax(worst, fabs(c - p));
    }
    /* ends */
    ck_assert(sb_bm_fpt_quantile(0.0, x, a, mu, s2) == 0.0);
    ck_assert(isinf(sb_bm_fpt_quantile(1.0, x, a, mu, s2)));
    if (mass < 1.0)
      ck_assert(isinf(sb_bm_fpt_quantile(mass, x, a, mu, s2)));
  }
  printf("bm_fpt_quantile round trip: max |cdf(q) - p| = %.2g\n", worst);
}
END_TEST

START_TEST(test_quantile_best_double)
{
  /* Very concentrated laws (found by fuzzing; the plain log-t iteration
   * lands 1-2 ulp off there): one ulp of t moves the CDF by more than
   * 1e-13, so the quantile must be the best double (no neighbour closer) */
  const double sets[][5] = {
      /* p, x, a, mu, sigma2 */
      {0.72629019105806947, 1.8083472429744382e-05, 1.8063995204005285e-05,
       -9426.4808441151345, 1.3835404501589568e-12},
      {0.86234734975732863, 11936.453507620898, 150.75035211552517,
       -8.9795261943828368, 2.4603726049569515e-06},
      {0.27650007815100253, 5.2889127002261578, 4.9386493284340975,
       -2.1476104231738602, 6.0622093454584052e-11}};
  for (int k = 0; k < 3; k++) {
    double p = sets[k][0], x = sets[k][1], a = sets[k][2], mu = sets[k][3],
           s2 = sets[k][4];
    double q = sb_bm_fpt_quantile(p, x, a, mu, s2);
#define GAP(tt)                                                             \
  fabs(p <= 0.5 ? sb_bm_fpt_cdf(tt, x, a, mu, s2) - p                        \
                : (1.0 - p) - sb_bm_fpt_sf(tt, x, a, mu, s2))
    double g = GAP(q), gl = GAP(nextafter(q, 0.0)),
           gh = GAP(nextafter(q, INFINITY));
#undef GAP
    ck_assert_msg(g <= gl && g <= gh, "set %d: |gap| %.3g, neighbours %.3g "
                  "%.3g", k, g, gl, gh);
  }
}
END_TEST

START_TEST(test_quantile_narrower_than_ulp)
{
  /* x = 0, a = 1, sigma2 = 1, drift mu: IG(mean 1/mu, shape 1), relative
   * width sqrt(mean/shape) = mu^(-1/2) = 1e-17 .. 1e-75: every quantile
   * with |z| < 5 is the mean to within 1e-16, i.e. two ulp (the log-t
   * iteration returned mean*e or mean/e beyond mu ~ 1e37) */
  const double mus[] = {1e34, 1e38, 1e40, 1e150};
  const double ps[] = {1e-6, 0.5, 1 - 1e-6};
  for (int i = 0; i < 4; i++)
    for (int j = 0; j < 3; j++) {
      double q = sb_bm_fpt_quantile(ps[j], 0.0, 1.0, mus[i], 1.0);
      ck_assert_msg(fabs(q * mus[i] - 1.0) <= 4.5e-16,
                    "mu %g p %g: quantile %.17g, mean %.17g", mus[i], ps[j],
                    q, 1.0 / mus[i]);
    }
}
END_TEST

/* ------------------------------------------------------------ sampler */

START_TEST(test_sampler)
{
  /* (a) drift towards the level: sample mean vs d/nu; n = 100000, seed 11,
   *     5 standard errors (sd = sqrt(m^3/lambda)).
   * (b) defective law: fraction of +inf vs 1 - mass, 5 binomial sd.
   * (c) Levy (mu = 0): P(T <= 1) vs cdf(1), 5 binomial sd.
   * The detailed KS / chi-square checks are in test_bridge_mc.c. */
  gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
  gsl_rng_set(r, 11);
  const int n = 100000;
  double s = 0.0;
  for (int i = 0; i < n; i++)
    s += sb_bm_fpt_sample(r, 1.0, 0.0, -2.0, 0.5); /* d 1, nu 2: mean 0.5 */
  double m = 0.5, lam = 1.0 / 0.5;
  ck_assert_msg(fabs(s / n - m) < 5.0 * sqrt(m * m * m / lam / n),
                "mean %g", s / n);
  int ninf = 0;
  double mass = sb_bm_fpt_mass(0.0, 1.0, -0.4, 1.0);
  for (int i = 0; i < n; i++)
    ninf += isinf(sb_bm_fpt_sample(r, 0.0, 1.0, -0.4, 1.0));
  ck_assert_msg(fabs((double)ninf / n - (1.0 - mass)) <
                    5.0 * sqrt(mass * (1.0 - mass) / n),
                "P(inf) %g want %g", (double)ninf / n, 1.0 - mass);
  int nb = 0;
  double c = sb_bm_fpt_cdf(1.0, 2.0, 1.0, 0.0, 1.0);
  for (int i = 0; i < n; i++)
    nb += sb_bm_fpt_sample(r, 2.0, 1.0, 0.0, 1.0) <= 1.0;
  ck_assert_msg(fabs((double)nb / n - c) < 5.0 * sqrt(c * (1.0 - c) / n),
                "Levy P(T<=1) %g want %g", (double)nb / n, c);
  ck_assert(sb_bm_fpt_sample(r, 1.0, 1.0, 1.0, 1.0) == 0.0);
  gsl_rng_free(r);
}
END_TEST

/* ------------------------------------------------------------ Bessel-3 */

START_TEST(test_bes3_reference)
{
  sbt_table t;
  sbt_table_load("passage_bes3.csv", &t);
  double worst = 0.0;
  for (int i = 0; i < t.nrow; i++) {
    double tt = sbt_at(&t, i, 0), x = sbt_at(&t, i, 1), a = sbt_at(&t, i, 2),
           s2 = sbt_at(&t, i, 3);
    double want[3] = {sbt_at(&t, i, 4), sbt_at(&t, i, 5), sbt_at(&t, i, 6)};
    sb_result r[3];
    ck_assert_int_eq(sb_bes3_fpt_pdf_e(tt, x, a, s2, &r[0]), SB_SUCCESS);
    ck_assert_int_eq(sb_bes3_fpt_cdf_e(tt, x, a, s2, &r[1]), SB_SUCCESS);
    ck_assert_int_eq(sb_bes3_fpt_sf_e(tt, x, a, s2, &r[2]), SB_SUCCESS);
    for (int k = 0; k < 3; k++) {
      if (want[k] < 0)
        continue;
      char what[120];
      snprintf(what, sizeof what, "bes3 %d (t=%g, x=%g, a=%g)", k, tt, x, a);
      ck_assert_result(r[k], want[k], TOL_REF, what);
      worst = fmax(worst, sbt_reldiff(r[k].val, want[k]));
    }
  }
  printf("bes3_fpt vs mpmath: max rel error %.2g\n", worst);
  sbt_table_free(&t);
  /* limits: mass a/x at t = inf; inside (x <= a) T = 0; a = 0 never */
  ck_assert_rel(sb_bes3_fpt_cdf(INFINITY, 4.0, 1.0, 1.0), 0.25, TOL_ULPS(1));
  ck_assert_rel(sb_bes3_fpt_sf(INFINITY, 4.0, 1.0, 1.0), 0.75, TOL_ULPS(1));
  ck_assert(sb_bes3_fpt_cdf(1.0, 0.5, 1.0, 1.0) == 1.0);
  ck_assert(sb_bes3_fpt_cdf(1.0, 2.0, 0.0, 1.0) == 0.0);
  ck_assert(sb_bes3_fpt_sf(1.0, 2.0, 0.0, 1.0) == 1.0);
  /* t far below d^2/sigma2 (eps = 1e65): nothing has happened yet */
  ck_assert(sb_bes3_fpt_sf(1e-130, 2.0, 1.0, 1.0) == 1.0);
  ck_assert(sb_bes3_fpt_cdf(1e-130, 2.0, 1.0, 1.0) == 0.0);
  ck_assert(sb_bes3_fpt_pdf(1e-130, 2.0, 1.0, 1.0) == 0.0);
}
END_TEST

/* ---------------------------------------------------------- bad input */

START_TEST(test_bad_input)
{
  sb_result r;
  sb_clear_error();
  ck_assert(isnan(sb_bm_fpt_cdf(NAN, 1, 0, 1, 1)));
  ck_assert_int_eq(sb_last_status(), SB_EDOM);
  ck_assert(strstr(sb_last_error(), "sb_bm_fpt_cdf") != NULL);
  ck_assert_int_eq(sb_bm_fpt_cdf_e(-1.0, 1, 0, 1, 1, &r), SB_EDOM);
  ck_assert(isnan(r.val) && isnan(r.err));
  ck_assert_int_eq(sb_bm_fpt_pdf_e(1.0, 1, 0, 1, -1.0, &r), SB_EDOM);
  ck_assert_int_eq(sb_bm_fpt_sf_e(1.0, 1, 0, 1, 0.0, &r), SB_EDOM);
  ck_assert_int_eq(sb_bm_fpt_sf_e(1.0, NAN, 0, 1, 1, &r), SB_EDOM);
  ck_assert_int_eq(sb_bm_fpt_sf_e(1.0, 1, INFINITY, 1, 1, &r), SB_EDOM);
  ck_assert_int_eq(sb_bm_fpt_mass_e(1, 0, NAN, 1, &r), SB_EDOM);
  ck_assert_int_eq(sb_bm_fpt_quantile_e(-0.1, 1, 0, 1, 1, &r), SB_EDOM);
  ck_assert_int_eq(sb_bm_fpt_quantile_e(1.5, 1, 0, 1, 1, &r), SB_EDOM);
  ck_assert_int_eq(sb_bm_fpt_quantile_e(NAN, 1, 0, 1, 1, &r), SB_EDOM);
  ck_assert(isnan(sb_bm_fpt_quantile(0.5, 1, 0, 1, -2.0)));
  ck_assert(isnan(sb_bm_fpt_sample(NULL, 1, 0, 1, 1)));
  ck_assert_int_eq(sb_last_status(), SB_EINVAL);
  gsl_rng *g = gsl_rng_alloc(gsl_rng_mt19937);
  ck_assert(isnan(sb_bm_fpt_sample(g, 1, 0, 1, NAN)));
  gsl_rng_free(g);
  ck_assert_int_eq(sb_bes3_fpt_cdf_e(1.0, 2.0, -1.0, 1.0, &r), SB_EDOM);
  ck_assert_int_eq(sb_bes3_fpt_cdf_e(1.0, -2.0, 1.0, 1.0, &r), SB_EDOM);
  ck_assert_int_eq(sb_bes3_fpt_pdf_e(-1.0, 2.0, 1.0, 1.0, &r), SB_EDOM);
  ck_assert_int_eq(sb_bes3_fpt_sf_e(1.0, 2.0, 1.0, NAN, &r), SB_EDOM);
  ck_assert(isnan(sb_bes3_fpt_sf(1.0, 2.0, 1.0, -1.0)));
  /* NULL result pointers are allowed */
  ck_assert_int_eq(sb_bm_fpt_cdf_e(1.0, 1, 0, 1, 1, NULL), SB_SUCCESS);
  ck_assert_int_eq(sb_bm_fpt_cdf_e(-1.0, 1, 0, 1, 1, NULL), SB_EDOM);
}
END_TEST

/* Every argument in turn over sbt_sweep_ext (+-1e-320 ... +-DBL_MAX,
 * +-inf, NaN, 0, 2^+-995, 1e+-154), the others ordinary: the value is finite with status 0, or NaN with an
 * error status and a message naming the public function (never NaN, or
 * inf with status 0); the values themselves at
 * the extreme corners are checked against mpmath in passage_bm.csv,
 * passage_bes3.csv and passage_quantile.csv (the rows after the "extreme"
 * comments of tests/gen_refdata.py). */
typedef sbt_sfn pfn;
static double e_pdf(const double *a)
{
  return sb_bm_fpt_pdf(a[0], a[1], a[2], a[3], a[4]);
}
static double e_cdf(const double *a)
{
  return sb_bm_fpt_cdf(a[0], a[1], a[2], a[3], a[4]);
}
static double e_sf(const double *a)
{
  return sb_bm_fpt_sf(a[0], a[1], a[2], a[3], a[4]);
}
static double e_mass(const double *a)
{
  return sb_bm_fpt_mass(a[1], a[2], a[3], a[4]);
}
static double e_logmass(const double *a)
{
  return sb_bm_fpt_logmass(a[1], a[2], a[3], a[4]);
}
static double e_b3pdf(const double *a)
{
  return sb_bes3_fpt_pdf(a[0], a[1], a[2], a[4]);
}
static double e_b3cdf(const double *a)
{
  return sb_bes3_fpt_cdf(a[0], a[1], a[2], a[4]);
}
static double e_b3sf(const double *a)
{
  return sb_bes3_fpt_sf(a[0], a[1], a[2], a[4]);
}

/* quantile and sampler: +inf (the level is never reached) is right only
 * where p >= mass (quantile) or mass < 1 (sampler); mapped to 0 there */
static double e_quant(const double *a)
{
  double v = sb_bm_fpt_quantile(a[0], a[1], a[2], a[3], a[4]);
  if (isinf(v) && v > 0.0 && a[0] >= sb_bm_fpt_mass(a[1], a[2], a[3], a[4]))
    return 0.0;
  return v;
}
static gsl_rng *e_rng; /* test_extreme_arguments' generator */
static double e_sample(const double *a)
{
  gsl_rng *r = e_rng;
  double m = 0.0;
  for (int i = 0; i < 8; i++) {
    double v = sb_bm_fpt_sample(r, a[1], a[2], a[3], a[4]);
    if (isinf(v) && v > 0.0 && sb_bm_fpt_mass(a[1], a[2], a[3], a[4]) < 1.0)
      v = 0.0;
    if (!isfinite(v))
      return v;
    m += v;
  }
  return m / 8.0;
}

START_TEST(test_extreme_arguments)
{
  /* (t, x, a, mu, sigma2); Bessel-3 ignores mu */
  static const double base[3][5] = {{1.3, 0.0, 1.0, 0.4, 0.8},
                                    {1.3, 0.0, 1.0, -0.4, 0.8},
                                    {1.3, 2.0, 0.5, 0.0, 0.8}};
  static const struct {
    pfn f;
    int b;
    const char *nm;
  } k[] = {{e_pdf, 0, "sb_bm_fpt_pdf"},
           {e_cdf, 0, "sb_bm_fpt_cdf"},
           {e_sf, 0, "sb_bm_fpt_sf"},
           {e_mass, 0, "sb_bm_fpt_mass"},
           {e_pdf, 1, "sb_bm_fpt_pdf"},
           {e_cdf, 1, "sb_bm_fpt_cdf"},
           {e_sf, 1, "sb_bm_fpt_sf"},
           {e_mass, 1, "sb_bm_fpt_mass"},
           {e_b3pdf, 2, "sb_bes3_fpt_pdf"},
           {e_b3cdf, 2, "sb_bes3_fpt_cdf"},
           {e_b3sf, 2, "sb_bes3_fpt_sf"},
           {e_quant, 0, "sb_bm_fpt_quantile"},
           {e_quant, 1, "sb_bm_fpt_quantile"},
           {e_sample, 0, "sb_bm_fpt_sample"},
           {e_sample, 1, "sb_bm_fpt_sample"}};
  e_rng = gsl_rng_alloc(gsl_rng_mt19937);
  /* sbt_sweep_ext with +-inf; every value is >= 0; an error names the
   * function */
  for (size_t f = 0; f < sizeof k / sizeof k[0]; f++)
    sbt_sweep_scalar(k[f].f, base[k[f].b], 5, 1, f, k[f].nm);
  /* the log mass (<= 0): finite, or NaN with an error */
  for (int b = 0; b < 2; b++)
    sbt_sweep_scalar(e_logmass, base[b], 5, 0, 100 + (size_t)b,
                     "sb_bm_fpt_logmass");
  /* log mass below -DBL_MAX: SB_ERANGE (-2 1e300 1e300 / 1e-300) */
  sb_result lr;
  ck_assert_int_eq(sb_bm_fpt_logmass_e(0.0, 1e300, -1e300, 1e-300, &lr),
                   SB_ERANGE);
  ck_assert(isnan(lr.val));
  ck_assert(strstr(sb_last_error(), "sb_bm_fpt_logmass") != NULL);
  /* where the mass underflows its log is finite: -2 1e200 1e100 / 1 */
  ck_assert(sb_bm_fpt_mass(0.0, 1e200, -1e100, 1.0) == 0.0);
  ck_assert_rel(sb_bm_fpt_logmass(0.0, 1e200, -1e100, 1.0),
                -2.0 * (1e200 * 1e100), TOL_ULPS(2));
  /* a density above DBL_MAX (t = 1e-310 at the mean of a narrow law) is
   * SB_ERANGE, not inf */
  sb_result r;
  ck_assert_int_eq(sb_bm_fpt_pdf_e(1e-310, 0.0, 1e-155, 0.0, 1.0, &r),
                   SB_ERANGE);
  ck_assert(isnan(r.val));
  ck_assert_int_eq(sb_bes3_fpt_pdf_e(1e-310, 2e-155, 1e-155, 1.0, &r),
                   SB_ERANGE);
  /* a quantile or draw above DBL_MAX is SB_ERANGE (NaN), not +inf */
  ck_assert_int_eq(sb_bm_fpt_quantile_e(0.3, 0.0, 1e300, 1e-10, 1.0, &r),
                   SB_ERANGE);
  ck_assert(isnan(r.val));
  ck_assert(strstr(sb_last_error(), "sb_bm_fpt_quantile") != NULL);
  sb_clear_error();
  ck_assert(isnan(sb_bm_fpt_sample(e_rng, 0.0, 1e300, 1e-10, 1.0)));
  ck_assert_int_eq(sb_last_status(), SB_ERANGE);
  gsl_rng_free(e_rng);
}
END_TEST

static Suite *passage_suite(void)
{
  Suite *s = suite_create("passage");
  TCase *tc = tcase_create("numutil");
  tcase_add_test(tc, test_mills);
  tcase_add_test(tc, test_mills_diff);
  tcase_add_test(tc, test_log1mexp);
  tcase_add_test(tc, test_dd);
  tcase_add_test(tc, test_solver);
  tcase_add_test(tc, test_ig_sampler_moments);
  tcase_set_timeout(tc, 30);
  suite_add_tcase(s, tc);
  tc = tcase_create("bm");
  tcase_add_test(tc, test_bm_reference);
  tcase_add_test(tc, test_bm_identities);
  tcase_add_test(tc, test_cdf_vs_quadrature);
  tcase_add_test(tc, test_quantile_reference);
  tcase_add_test(tc, test_quantile_roundtrip);
  tcase_add_test(tc, test_quantile_best_double);
  tcase_add_test(tc, test_quantile_narrower_than_ulp);
  tcase_add_test(tc, test_sampler);
  tcase_set_timeout(tc, 30);
  suite_add_tcase(s, tc);
  tc = tcase_create("bes3");
  tcase_add_test(tc, test_bes3_reference);
  tcase_add_test(tc, test_extreme_arguments);
  tcase_add_test(tc, test_bad_input);
  suite_add_tcase(s, tc);
  return s;
}

int main(void)
{
  gsl_set_error_handler_off(); /* the test's own QAGS calls report status */
  return sbt_run_suite(passage_suite());
}
