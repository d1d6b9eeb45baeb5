/* test_bridge.c — crossing probabilities (bridge.c) and conditioned hitting
 * times (bridge_hit.c) of the Brownian and Bessel-3 bridges.
 *
 * Independent references:
 *  - the CSV files in tests/data, from tests/gen_refdata.py (mpmath at 60-200
 *    digits; densities from first principles, CDFs from the textbook forms
 *    with enough digits to absorb their cancellations; checked there
 *    against mp.quad);
 *  - GSL quadrature of first-passage decompositions built from *other*
 *    functions (the first-passage densities of passage.c and the transition
 *    densities written out here): crossing probabilities and hitting-time
 *    CDFs;
 *  - the two printed versions of the Bessel-3-bridge hitting-time CDF in
 *    Mohaupt (2011) (eq 5.21-5.22 and App. I eq I.60-I.61), coded here as
 *    printed, against the same quadrature: 5.21-5.22 is right, I.60-I.61
 *    is not;
 *  - Monte Carlo means of the samplers (fixed seeds, 5-sigma criteria; the
 *    KS / chi-square checks of the samplers live in test_bridge_mc.c).
 */
#include <float.h>
#include <math.h>
#include <string.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <gsl/gsl_rng.h>
#include <gsl/gsl_sf_erf.h>

#include <smolbridge/bridge.h>
#include <smolbridge/passage.h>
#include "refdata.h"
#include "sweep.h"
#include "testutil.h"

typedef int (*cross_e)(double, double, double, double, sb_result *);
typedef int (*hit_e)(double, double, double, double, double, double,
                     sb_result *);

/* N(0, v) density */
static double gv(double v, double z)
{
  return exp(-z * z / (2.0 * v)) / sqrt(2.0 * M_PI * v);
}

/* Bessel-3 transition density q_v(x, y) = (y/x)[g_v(y-x) - g_v(y+x)] */
static double q3(double v, double x, double y)
{
  return y / x * (gv(v, y - x) - gv(v, y + x));
}

/* --------------------------------------------------- crossing: values */

START_TEST(test_cross_reference)
{
  sbt_table t;
  sbt_table_load("bridge_cross.csv", &t);
  cross_e fn[2][3] = {
      {sb_bb_cross_prob_e, sb_bb_cross_logprob_e, sb_bb_nocross_prob_e},
      {sb_bes3b_cross_prob_e, sb_bes3b_cross_logprob_e,
       sb_bes3b_nocross_prob_e}};
  const char *nm[3] = {"p", "logp", "nocross"};
  double worst[2][3] = {{0}};
  for (int i = 0; i < t.nrow; i++) {
    int k = (int)sbt_at(&t, i, 0);
    double x = sbt_at(&t, i, 1), y = sbt_at(&t, i, 2), a = sbt_at(&t, i, 3),
           v = sbt_at(&t, i, 4);
    for (int j = 0; j < 3; j++) {
      double want = sbt_at(&t, i, 5 + j);
      if (j != 1 && want < 0) /* below 1e-300 */
        continue;
      sb_result r;
      ck_assert_int_eq(fn[k][j](x, y, a, v, &r), SB_SUCCESS);
      char what[120];
      snprintf(what, sizeof what, "%s %s(x=%g, y=%g, a=%g, v=%g)",
               k ? "bes3b" : "bb", nm[j], x, y, a, v);
      ck_assert_result(r, want, TOL_REF, what);
      worst[k][j] = fmax(worst[k][j], sbt_reldiff(r.val, want));
    }
  }
  printf("crossing vs mpmath (%d rows): bb p %.2g log %.2g no %.2g; "
         "bes3b p %.2g log %.2g no %.2g\n", t.nrow, worst[0][0],
         worst[0][1], worst[0][2], worst[1][0], worst[1][1], worst[1][2]);
  sbt_table_free(&t);
}
END_TEST

START_TEST(test_cross_special)
{
  /* overlap at an end point (Mohaupt 2011, eq 5.15): certain crossing */
  ck_assert(sb_bb_cross_prob(0.5, 2.0, 1.0, 1.0) == 1.0);
  ck_assert(sb_bb_cross_prob(2.0, 1.0, 1.0, 1.0) == 1.0);
  ck_assert(sb_bb_cross_logprob(2.0, -3.0, 1.0, 1.0) == 0.0);
  ck_assert(sb_bb_nocross_prob(2.0, -3.0, 1.0, 1.0) == 0.0);
  ck_assert(sb_bes3b_cross_prob(0.5, 2.0, 1.0, 1.0) == 1.0);
  ck_assert(sb_bes3b_cross_logprob(2.0, 1.0, 1.0, 1.0) == 0.0);
  ck_assert(sb_bes3b_nocross_prob(2.0, 0.3, 1.0, 1.0) == 0.0);
  /* Bessel-3 level 0: never crosses */
  ck_assert(sb_bes3b_cross_prob(2.0, 1.0, 0.0, 1.0) == 0.0);
  ck_assert(isinf(sb_bes3b_cross_logprob(2.0, 1.0, 0.0, 1.0)));
  ck_assert(sb_bes3b_nocross_prob(2.0, 1.0, 0.0, 1.0) == 1.0);
  /* v = 0: the straight line, no crossing */
  ck_assert(sb_bb_cross_prob(2.0, 1.5, 1.0, 0.0) == 0.0);
  ck_assert(sb_bes3b_nocross_prob(2.0, 1.5, 1.0, 0.0) == 1.0);
  /* p + nocross = 1; log p = log(p); bes3b <= bb: the Bessel-3 bridge is
   * the BB conditioned on min > 0, so P3 = (p - q)/(1 - q) <= p with
   * q = P_BB(min <= 0) (up to rounding when both are ~1);
   * a -> 0 limit of bes3b: P ~ a (x + y)/(x y) for v >> xy (small-v
   * exponentials expanded: expm1(A)/expm1(B) -> A/B) */
  for (double v = 1e-3; v < 1e3; v *= 4.3) {
    double pb = sb_bb_cross_prob(1.7, 1.2, 1.0, v);
    double p3 = sb_bes3b_cross_prob(1.7, 1.2, 1.0, v);
    ck_assert_abs(pb + sb_bb_nocross_prob(1.7, 1.2, 1.0, v), 1.0,
                  TOL_ULPS(4));
    ck_assert_abs(p3 + sb_bes3b_nocross_prob(1.7, 1.2, 1.0, v), 1.0,
                  TOL_ULPS(4));
    if (p3 > 1e-300)
      ck_assert_rel(sb_bes3b_cross_logprob(1.7, 1.2, 1.0, v), log(p3),
                    TOL_ULPS(8) + 1e-300);
    ck_assert(p3 <= pb * (1.0 + TOL_ULPS(4)));
  }
  double a = 1e-9, x = 2.0, y = 3.0, v = 1e9;
  ck_assert_rel(sb_bes3b_cross_prob(x, y, a, v), a * (x + y - a) / (x * y),
                1e-8);
}
END_TEST

/* ------------------------------------------- crossing vs quadrature */

/* One bridge: Brownian (bes3 = 0) or Bessel-3 (bes3 = 1). */
typedef struct {
  double x, y, a, s2, t;
  int bes3;
} hit_q;

/* first-passage decomposition: density of {T_a in ds, end at y}
 * BB:  f_{x->a}(s) g_{t-s}(y - a)       (BM first passage, no drift)
 * B3B: n_{x,a}(s) q_{t-s}(a, y)         (Bessel-3 first passage) */
static double cross_integrand(double s, void *vp)
{
  const hit_q *c = vp;
  if (s <= 0.0 || s >= c->t)
    return 0.0;
  double w = c->s2 * (c->t - s);
  if (c->bes3)
    return sb_bes3_fpt_pdf(s, c->x, c->a, c->s2) * q3(w, c->a, c->y);
  return sb_bm_fpt_pdf(s, c->x, c->a, 0.0, c->s2) * gv(w, c->y - c->a);
}

/* Transition density from x to y over [0, t] (the bridge's normaliser). */
static double end_density(const hit_q *c)
{
  double v = c->s2 * c->t;
  return c->bes3 ? q3(v, c->x, c->y) : gv(v, c->y - c->x);
}

/* The closed-form crossing probability under test. */
static double cross_prob(const hit_q *c)
{
  double v = c->s2 * c->t;
  return c->bes3 ? sb_bes3b_cross_prob(c->x, c->y, c->a, v)
                 : sb_bb_cross_prob(c->x, c->y, c->a, v);
}

START_TEST(test_cross_vs_quadrature)
{
  gsl_integration_workspace *w = gsl_integration_workspace_alloc(1000);
  const hit_q cases[] = {{1.5, 1.3, 1.0, 1.0, 1.0, 0},
                         {2.0, 3.0, 1.0, 0.5, 2.0, 0},
                         {1.1, 1.05, 1.0, 0.01, 1.0, 0},
                         {1.5, 1.3, 1.0, 1.0, 1.0, 1},
                         {2.0, 3.0, 0.5, 0.5, 2.0, 1},
                         {1.1, 1.05, 1.0, 0.01, 1.0, 1},
                         {3.0, 2.0, 0.1, 4.0, 1.5, 1}};
  for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
    hit_q c = cases[k];
    gsl_function F = {cross_integrand, &c};
    double res, err;
    int st = gsl_integration_qags(&F, 0.0, c.t, 0.0, 1e-11, 1000, w, &res,
                                  &err);
    ck_assert_int_eq(st, GSL_SUCCESS);
    double ref = res / end_density(&c), p = cross_prob(&c);
    ck_assert_msg(fabs(p - ref) <= TOL_QUAD * ref,
                  "case %zu: closed form %.17g, quadrature %.17g", k, p, ref);
  }
  gsl_integration_workspace_free(w);
}
END_TEST

/* ------------------------------------------------ hitting times: values */

/* pdf, cdf and sf of both bridges against a table of mpmath values
 * (gen_refdata.py): relative error <= TOL_REF, err covering it */
static void hit_table(const char *file)
{
  sbt_table t;
  sbt_table_load(file, &t);
  hit_e fn[2][3] = {{sb_bb_hit_pdf_e, sb_bb_hit_cdf_e, sb_bb_hit_sf_e},
                    {sb_bes3b_hit_pdf_e, sb_bes3b_hit_cdf_e,
                     sb_bes3b_hit_sf_e}};
  const char *nm[3] = {"pdf", "cdf", "sf"};
  double worst[2][3] = {{0}};
  int n = 0;
  for (int i = 0; i < t.nrow; i++) {
    int k = (int)sbt_at(&t, i, 0);
    double u = sbt_at(&t, i, 1), x = sbt_at(&t, i, 2), y = sbt_at(&t, i, 3),
           a = sbt_at(&t, i, 4), s2 = sbt_at(&t, i, 5), tt = sbt_at(&t, i, 6);
    for (int j = 0; j < 3; j++) {
      double want = sbt_at(&t, i, 7 + j);
      if (want < 0)
        continue;
      sb_result r;
      if (isinf(want)) { /* a density above DBL_MAX */
        ck_assert_int_eq(fn[k][j](u, x, y, a, s2, tt, &r), SB_ERANGE);
        ck_assert(isnan(r.val));
        continue;
      }
      ck_assert_int_eq(fn[k][j](u, x, y, a, s2, tt, &r), SB_SUCCESS);
      char what[160];
      snprintf(what, sizeof what, "%s hit %s(u=%g; x=%g y=%g a=%g s2=%g "
               "t=%g)", k ? "bes3b" : "bb", nm[j], u, x, y, a, s2, tt);
      ck_assert_result(r, want, TOL_REF, what);
      worst[k][j] = fmax(worst[k][j], sbt_reldiff(r.val, want));
      n++;
    }
  }
  printf("hitting times vs mpmath, %s (%d values): bb pdf %.2g cdf %.2g "
         "sf %.2g; bes3b pdf %.2g cdf %.2g sf %.2g\n", file, n, worst[0][0],
         worst[0][1], worst[0][2], worst[1][0], worst[1][1], worst[1][2]);
  sbt_table_free(&t);
}

START_TEST(test_hit_reference)
{
  hit_table("bridge_hit.csv");
}
END_TEST

/* The hitting density from independent pieces: the first-passage density
 * (passage.c) times the transition density from the level to y, divided by
 * P(cross) times the transition density from x to y (bridge.c's crossing
 * probability). */
static double hit_density_indep(double s, void *vp)
{
  hit_q h = *(const hit_q *)vp;
  /* y = 0 is the continuous limit; y = 1e-9 stands for it (error ~1e-7) */
  if (h.bes3 && !(h.y > 0.0))
    h.y = 1e-9;
  return cross_integrand(s, &h) / (cross_prob(&h) * end_density(&h));
}

/* The hitting-time functions under test, for either bridge. */
typedef double (*hit_fn)(double, double, double, double, double, double);
enum { H_PDF, H_CDF, H_SF, H_QUANTILE };

static double hit_f(const hit_q *h, int which, double u)
{
  static const hit_fn fn[2][4] = {
      {sb_bb_hit_pdf, sb_bb_hit_cdf, sb_bb_hit_sf, sb_bb_hit_quantile},
      {sb_bes3b_hit_pdf, sb_bes3b_hit_cdf, sb_bes3b_hit_sf,
       sb_bes3b_hit_quantile}};
  return fn[h->bes3 != 0][which](u, h->x, h->y, h->a, h->s2, h->t);
}
static int hit_quantile_e(const hit_q *h, double p, sb_result *r)
{
  return h->bes3
             ? sb_bes3b_hit_quantile_e(p, h->x, h->y, h->a, h->s2, h->t, r)
             : sb_bb_hit_quantile_e(p, h->x, h->y, h->a, h->s2, h->t, r);
}
static double hit_sample(const hit_q *h, const gsl_rng *r)
{
  return h->bes3 ? sb_bes3b_hit_sample(r, h->x, h->y, h->a, h->s2, h->t)
                 : sb_bb_hit_sample(r, h->x, h->y, h->a, h->s2, h->t);
}

static const hit_q HITQ[] = {
    {1.5, 1.3, 1.0, 1.0, 1.0, 0},   {2.0, 3.0, 1.0, 0.5, 2.0, 0},
    {1.5, 0.4, 1.0, 0.7, 2.0, 0},   {1.5, 1.0, 1.0, 1.0, 1.0, 0},
    {1.5, 1.3, 1.0, 1.0, 1.0, 1},   {1.5, 0.4, 1.0, 0.7, 2.0, 1},
    {3.0, 2.0, 0.1, 1.3, 0.5, 1},   {1.1, 1.05, 1.0, 5.0, 3.0, 1},
    {2.0, 2.5, 0.01, 100.0, 1.0, 1} /* 1 - rho ~ 1e-3: quadrature branch */};

START_TEST(test_hit_vs_quadrature)
{
  /* pdf against the independent density; cdf and sf against QAGS of it */
  gsl_integration_workspace *w = gsl_integration_workspace_alloc(1000);
  for (size_t k = 0; k < sizeof HITQ / sizeof HITQ[0]; k++) {
    hit_q h = HITQ[k];
    gsl_function F = {hit_density_indep, &h};
    for (double f = 0.1; f < 0.95; f += 0.2) {
      double u = f * h.t, res, err, res2, err2;
      double pdf = hit_f(&h, H_PDF, u);
      ck_assert_msg(sbt_reldiff(pdf, hit_density_indep(u, &h)) < 1e-12,
                    "case %zu u=%g: pdf %.17g independent %.17g", k, u, pdf,
                    hit_density_indep(u, &h));
      ck_assert_int_eq(gsl_integration_qags(&F, 0.0, u, 1e-300, 1e-11, 1000,
                                            w, &res, &err), GSL_SUCCESS);
      ck_assert_int_eq(gsl_integration_qags(&F, u, h.t, 1e-300, 1e-11, 1000,
                                            w, &res2, &err2), GSL_SUCCESS);
      double c = hit_f(&h, H_CDF, u);
      double s = hit_f(&h, H_SF, u);
      ck_assert_msg(fabs(c - res) <= TOL_QUAD * res + 1e-300,
                    "case %zu u=%g: cdf %.17g quadrature %.17g", k, u, c,
                    res);
      ck_assert_msg(fabs(s - res2) <= TOL_QUAD * res2 + 1e-300,
                    "case %zu u=%g: sf %.17g quadrature %.17g", k, u, s,
                    res2);
    }
  }
  gsl_integration_workspace_free(w);
}
END_TEST

/* ------------------- the two printed versions in Mohaupt (2011) */

/* Mohaupt 2011, eq 5.21-5.22 (= App. I eq I.62-I.63 with K = B), B_ij = B the
 * per-component diffusion coefficient (sigma2 = B^2), Delta t = dt. */
static double thesis_522(double u, double x, double y, double a, double B,
                       double dt)
{
  double k = sqrt(1.0 / u - 1.0 / dt), B2 = B * B;
#define E(z) exp(-(z) * (z) / (2.0 * B2 * dt))
  double c1 = (x - a) / (B * M_SQRT2) * k;
  double i1 = E(x + y - 2 * a) *
              gsl_sf_erf(c1 - (y - a) / (B * M_SQRT2 * dt * k));
  double i2 = E(x - y) * gsl_sf_erfc(c1 + (y - a) / (B * M_SQRT2 * dt * k));
  double i3 = E(x + y) * gsl_sf_erf(c1 - (y + a) / (B * M_SQRT2 * dt * k));
  double i4 = E(x - y - 2 * a) *
              gsl_sf_erfc(c1 + (y + a) / (B * M_SQRT2 * dt * k));
  double den = E(x + y - 2 * a) - E(x + y);
#undef E
  return 0.5 * (1.0 - (i1 - i2 - i3 + i4) / den);
}

/* Mohaupt 2011, App. I eq I.60-I.61 as printed (standard Bessel-3,
 * sigma2 = 1): I2 and I4 carry exp(-(x+y)^2/2t) and exp(-(x+y-2a)^2/2t)
 * and the second erf argument has sqrt(2t) where 5.22 has sqrt(2) t. */
static double thesis_I61(double u, double x, double y, double a, double t)
{
  double k = sqrt(1.0 / u - 1.0 / t);
#define E(z) exp(-(z) * (z) / (2.0 * t))
  double c1 = (x - a) / M_SQRT2 * k;
  double i1 = E(x + y - 2 * a) * gsl_sf_erf(c1 - (y - a) / (sqrt(2 * t) * k));
  double i2 = E(x + y) * gsl_sf_erfc(c1 + (y - a) / (sqrt(2 * t) * k));
  double i3 = E(x + y) * gsl_sf_erf(c1 - (y + a) / (sqrt(2 * t) * k));
  double i4 = E(x + y - 2 * a) *
              gsl_sf_erfc(c1 + (y + a) / (sqrt(2 * t) * k));
  double den = E(x + y - 2 * a) - E(x + y);
#undef E
  return 0.5 * (1.0 - (i1 - i2 - i3 + i4) / den);
}

START_TEST(test_thesis_versions)
{
  /* Quadrature of the density n_{x,a}(s) q_{t-s}(a, y) (independent
   * pieces) decides: 5.21-5.22 agrees to 1e-9, I.60-I.61 is off by 1e-3 or
   * more in every case (sigma2 = 1 so that I.61 applies; t = 1 and t != 1).
   * The finding is recorded in docs/bridge.md. */
  gsl_integration_workspace *w = gsl_integration_workspace_alloc(1000);
  const hit_q cases[] = {{1.5, 1.3, 1.0, 1.0, 2.0, 1},
                         {2.0, 1.5, 1.0, 1.0, 0.5, 1},
                         {1.2, 1.4, 1.0, 1.0, 1.0, 1},
                         {3.0, 2.0, 0.5, 1.0, 3.0, 1}};
  double worst522 = 0.0, best61 = INFINITY;
  for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
    hit_q h = cases[k];
    gsl_function F = {hit_density_indep, &h};
    for (double f = 0.15; f < 0.9; f += 0.25) {
      double u = f * h.t, res, err;
      ck_assert_int_eq(gsl_integration_qags(&F, 0.0, u, 1e-300, 1e-11, 1000,
                                            w, &res, &err), GSL_SUCCESS);
      double s522 = thesis_522(u, h.x, h.y, h.a, sqrt(h.s2), h.t);
      double s61 = thesis_I61(u, h.x, h.y, h.a, h.t);
      ck_assert_msg(fabs(s522 - res) <= TOL_QUAD * res,
                    "eq 5.22, case %zu u=%g: %.17g vs quadrature %.17g", k, u,
                    s522, res);
      ck_assert_msg(fabs(s61 - res) > 1e-3 * res,
                    "eq I.61 unexpectedly agrees: case %zu u=%g", k, u);
      /* and the library agrees with 5.22 */
      ck_assert_rel(sb_bes3b_hit_cdf(u, h.x, h.y, h.a, h.s2, h.t), s522,
                    1e-12);
      worst522 = fmax(worst522, fabs(s522 - res) / res);
      best61 = fmin(best61, fabs(s61 - res) / res);
    }
  }
  printf("Mohaupt 2011 eq 5.21-5.22 vs quadrature: max rel diff %.2g; "
         "eq I.60-I.61: min rel diff %.2g (misprint)\n", worst522, best61);
  gsl_integration_workspace_free(w);
}
END_TEST

/* ----------------------------------------------------------- quantiles */

/* g(u) = cdf(u) - p (or its complement form) for the best-double check */
static double hit_gap(int b3, double u, double p, const double *a6)
{
  double x = a6[0], y = a6[1], a = a6[2], s2 = a6[3], t = a6[4];
  if (p <= 0.5)
    return (b3 ? sb_bes3b_hit_cdf(u, x, y, a, s2, t)
               : sb_bb_hit_cdf(u, x, y, a, s2, t)) - p;
  return (1.0 - p) - (b3 ? sb_bes3b_hit_sf(u, x, y, a, s2, t)
                         : sb_bb_hit_sf(u, x, y, a, s2, t));
}

/* quantiles against a table of mpmath roots: full double precision (a
 * few ulp) and err covering it; with `roundtrip`, also |cdf(q) - p| <=
 * 1e-13 (cdf(q) as 1 - sf(q) for p > 1/2) */
static void quantile_table(const char *file, int roundtrip)
{
  sbt_table t;
  sbt_table_load(file, &t);
  double worst[2] = {0, 0}, gap = 0.0;
  int nbest = 0;
  for (int i = 0; i < t.nrow; i++) {
    int k = (int)sbt_at(&t, i, 0);
    double p = sbt_at(&t, i, 1), x = sbt_at(&t, i, 2), y = sbt_at(&t, i, 3),
           a = sbt_at(&t, i, 4), s2 = sbt_at(&t, i, 5), tt = sbt_at(&t, i, 6),
           q = sbt_at(&t, i, 7);
    sb_result r;
    int st = k ? sb_bes3b_hit_quantile_e(p, x, y, a, s2, tt, &r)
               : sb_bb_hit_quantile_e(p, x, y, a, s2, tt, &r);
    ck_assert_int_eq(st, SB_SUCCESS);
    char what[160];
    snprintf(what, sizeof what, "%s quantile(p=%g; x=%g y=%g a=%g s2=%g "
             "t=%g)", k ? "bes3b" : "bb", p, x, y, a, s2, tt);
    /* full double precision: a few ulp */
    ck_assert_msg(sbt_reldiff(r.val, q) <= TOL_ULPS(32),
                  "%s = %.17g want %.17g", what, r.val, q);
    ck_assert_result(r, q, TOL_REF, what);
    worst[k] = fmax(worst[k], sbt_reldiff(r.val, q));
    if (roundtrip) {
      /* where one ulp of q moves the cdf by more than 1e-13 (a law
       * concentrated near t), q must be the best double instead */
      const double a6[5] = {x, y, a, s2, tt};
      double g = fabs(hit_gap(k, r.val, p, a6));
      if (g > 1e-13) {
        double gl = fabs(hit_gap(k, nextafter(r.val, 0.0), p, a6));
        double gh = fabs(hit_gap(k, nextafter(r.val, INFINITY), p, a6));
        ck_assert_msg(g <= gl && g <= gh, "%s: |cdf(q) - p| = %.3g, at the "
                      "neighbours %.3g %.3g", what, g, gl, gh);
        nbest++;
      } else
        gap = fmax(gap, g);
    }
  }
  printf("hit quantiles vs mpmath, %s: max rel error bb %.2g bes3b %.2g",
         file, worst[0], worst[1]);
  if (roundtrip)
    printf("; max |cdf(q) - p| = %.2g (%d best doubles instead)", gap, nbest);
  printf("\n");
  sbt_table_free(&t);
}

START_TEST(test_quantile_reference)
{
  quantile_table("bridge_quantile.csv", 0);
}
END_TEST

/* Short mixture ranges (1 - rho from 5e-2 to 1e-9, u up to t(1 - 1e-4)),
 * where bridge_hit.c expands the mixture (2) about its mid L */
START_TEST(test_narrow_reference)
{
  hit_table("bridge_narrow.csv");
  quantile_table("bridge_narrow_quantile.csv", 1);
}
END_TEST

START_TEST(test_quantile_roundtrip)
{
  /* |cdf(q) - p| <= 1e-13 for p in [1e-12, 1 - 1e-12], both bridges,
   * several parameter sets (both branches of the Bessel-3 CDF) */
  double grid[40];
  int ng = 0;
  for (int e = -12; e <= -1; e++)
    grid[ng++] = pow(10.0, e);
  for (double p = 0.2; p < 0.85; p += 0.1)
    grid[ng++] = p;
  for (int e = -1; e >= -12; e--)
    grid[ng++] = 1.0 - pow(10.0, e);
  const hit_q sets[] = {
      {1.5, 1.3, 1.0, 1.0, 1.0, 0},  {2.0, 3.0, 1.0, 0.5, 2.0, 0},
      {1.5, 0.4, 1.0, 0.7, 2.0, 0},  {30.0, 20.0, 1.0, 1.0, 10.0, 0},
      {1.5, 1.3, 1.0, 1.0, 1.0, 1},  {1.5, 0.4, 1.0, 0.7, 2.0, 1},
      {3.0, 2.0, 0.1, 1.3, 0.5, 1},  {2.0, 2.5, 0.01, 100.0, 1.0, 1},
      {2.0, 3.0, 1e-6, 1.0, 1.0, 1}, {1.5, 0.0, 1.0, 1.0, 1.0, 1}};
  double worst = 0.0;
  for (size_t k = 0; k < sizeof sets / sizeof sets[0]; k++) {
    hit_q h = sets[k];
    for (int i = 0; i < ng; i++) {
      double p = grid[i];
      sb_result r;
      int st = hit_quantile_e(&h, p, &r);
      ck_assert_int_eq(st, SB_SUCCESS);
      double c;
      if (p <= 0.5)
        c = hit_f(&h, H_CDF, r.val);
      else
        c = 1.0 - hit_f(&h, H_SF, r.val);
      ck_assert_msg(fabs(c - p) <= 1e-13,
                    "set %zu p=%.17g: q=%.17g cdf(q)=%.17g", k, p, r.val, c);
      ck_assert(r.val > 0.0 && r.val < h.t);
      worst = fmax(worst, fabs(c - p));
    }
    ck_assert(sb_bb_hit_quantile(0.0, h.x, h.y, h.a, h.s2, h.t) == 0.0);
    ck_assert(sb_bb_hit_quantile(1.0, h.x, h.y, h.a, h.s2, h.t) == h.t);
  }
  printf("hit quantile round trip: max |cdf(q) - p| = %.2g\n", worst);
}
END_TEST

START_TEST(test_quantile_best_double)
{
  /* Very concentrated laws (found by fuzzing): where one ulp of u moves
   * the CDF by more than 1e-13 (here 2e-12 .. 2e-8), |cdf(q) - p| <= 1e-13
   * is not attainable and the quantile must be the best double: no
   * neighbour is closer.  Elsewhere (the Brownian bridge of the third set:
   * one ulp of u moves the CDF by about one ulp of the CDF) the contract is
   * |cdf(q) - p| <= 1e-13 (smolbridge/bridge.h). */
  int nconc = 0;
  const double sets[][6] = {
      /* p, x, y, a, sigma2, t */
      {0.29334219312295318, 0.3648306275883072, 0.31773942453417769,
       0.052752477402825793, 2.1009533479184924e-16, 809628.84517146694},
      {0.031515424838289618, 0.13492042479768029, 0.00019172374409305142,
       0.00019161056419294699, 3.4461372203630029e-12, 0.0018201388294060981},
      {0.72675649751909077, 0.68114497898894211, 0.0028598758996340769,
       0.0028598335345009023, 11248.090597362514, 0.0071488657442242559}};
  for (int k = 0; k < 3; k++)
    for (int b3 = 0; b3 < 2; b3++) {
      double p = sets[k][0];
      const double *a6 = sets[k] + 1;
      double q = b3 ? sb_bes3b_hit_quantile(p, a6[0], a6[1], a6[2], a6[3],
                                            a6[4])
                    : sb_bb_hit_quantile(p, a6[0], a6[1], a6[2], a6[3],
                                         a6[4]);
      double g = fabs(hit_gap(b3, q, p, a6));
      double gl = fabs(hit_gap(b3, nextafter(q, 0.0), p, a6));
      double gh = fabs(hit_gap(b3, nextafter(q, INFINITY), p, a6));
      printf("best double, set %d %s: |gap| %.3g at q, %.3g and %.3g at "
             "the neighbours\n", k, b3 ? "bes3b" : "bb", g, gl, gh);
      if (gl > 1e-13 || gh > 1e-13) {
        ck_assert_msg(g <= gl && g <= gh,
                      "set %d %s: |gap| %.3g at q, %.3g and %.3g at the "
                      "neighbours", k, b3 ? "bes3b" : "bb", g, gl, gh);
        nconc++;
      } else
        ck_assert_msg(g <= 1e-13, "set %d %s: |gap| %.3g", k,
                      b3 ? "bes3b" : "bb", g);
    }
  ck_assert_int_ge(nconc, 5); /* the sets do exercise the best double */
}
END_TEST

/* ----------------------------------------------------------- samplers */

static double u_density(double s, void *vp)
{
  return s * hit_density_indep(s, vp);
}

START_TEST(test_samplers)
{
  /* Sample mean of T vs the mean by QAGS of u f(u); n = 100000 per set,
   * seed 2024; pass if within 5 standard errors (sample sd).  Also the
   * fraction below the median (quantile(0.5)) within 5 binomial sd.  Sets
   * cover the BB (beta > 0, < 0, = 0) and the Bessel-3 sampler with
   * 1 - rho ~ 1, ~ 1e-3 and 2e-6, y < a and y = 0. */
  gsl_integration_workspace *w = gsl_integration_workspace_alloc(1000);
  gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
  gsl_rng_set(r, 2024);
  const hit_q sets[] = {
      {1.5, 1.3, 1.0, 1.0, 1.0, 0},   {1.5, 0.4, 1.0, 0.7, 2.0, 0},
      {1.5, 1.0, 1.0, 1.0, 1.0, 0},   {1.5, 1.3, 1.0, 1.0, 1.0, 1},
      {1.5, 0.4, 1.0, 0.7, 2.0, 1},   {2.0, 2.5, 0.01, 100.0, 1.0, 1},
      {2.0, 3.0, 1e-6, 1.0, 1.0, 1},  {1.5, 0.0, 1.0, 1.0, 1.0, 1},
      {1.1, 1.05, 1.0, 5.0, 3.0, 1}};
  const int n = 100000;
  for (size_t k = 0; k < sizeof sets / sizeof sets[0]; k++) {
    hit_q h = sets[k];
    gsl_function F = {u_density, &h};
    double mean, err;
    ck_assert_int_eq(gsl_integration_qags(&F, 0.0, h.t, 1e-300, 1e-8, 1000,
                                          w, &mean, &err), GSL_SUCCESS);
    double med = hit_f(&h, H_QUANTILE, 0.5);
    double s = 0.0, s2 = 0.0;
    int below = 0;
    for (int i = 0; i < n; i++) {
      double u = hit_sample(&h, r);
      ck_assert(u >= 0.0 && u <= h.t);
      s += u;
      s2 += u * u;
      below += u <= med;
    }
    double m = s / n, sd = sqrt((s2 / n - m * m) / n);
    ck_assert_msg(fabs(m - mean) < 5.0 * sd,
                  "set %zu: sample mean %.6g, exact %.6g (se %.3g)", k, m,
                  mean, sd);
    ck_assert_msg(fabs((double)below / n - 0.5) < 5.0 * sqrt(0.25 / n),
                  "set %zu: P(T <= median) = %.4f", k, (double)below / n);
  }
  gsl_rng_free(r);
  gsl_integration_workspace_free(w);
}
END_TEST

/* ------------------------------------------------ special cases, errors */

/* Scale: the law of T/t depends only on x, y, a over sqrt(sigma2 t).
 * Positions times 2^k, times 2^(2k) (sigma2 = 1) for k = -200 and 200,
 * where sigma2 u t (t - u) leaves the doubles (the functions returned
 * cdf 1 and pdf 0): the same cdf, sf and quantile/t, the pdf times
 * 2^(-2k), the same draws scaled, bit for bit (powers of two). */
START_TEST(test_hit_scale)
{
  typedef double (*hfn)(double, double, double, double, double, double);
  const hfn cdf[2] = {sb_bb_hit_cdf, sb_bes3b_hit_cdf};
  const hfn sf[2] = {sb_bb_hit_sf, sb_bes3b_hit_sf};
  const hfn pdf[2] = {sb_bb_hit_pdf, sb_bes3b_hit_pdf};
  const hfn qf[2] = {sb_bb_hit_quantile, sb_bes3b_hit_quantile};
  double (*const smp[2])(const gsl_rng *, double, double, double, double,
                         double) = {sb_bb_hit_sample, sb_bes3b_hit_sample};
  const double x = 1.0, y = 1.3, a = 0.5, t = 1.0;
  gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
  for (int b3 = 0; b3 < 2; b3++)
    for (int k = -200; k <= 200; k += 400) {
      const double sx = ldexp(1.0, k), st = ldexp(1.0, 2 * k);
      for (double u = 0.1; u < 1.0; u += 0.2) {
        ck_assert(cdf[b3](u, x, y, a, 1.0, t) > 0.0);
        ck_assert(cdf[b3](u * st, x * sx, y * sx, a * sx, 1.0, t * st) ==
                  cdf[b3](u, x, y, a, 1.0, t));
        ck_assert(sf[b3](u * st, x * sx, y * sx, a * sx, 1.0, t * st) ==
                  sf[b3](u, x, y, a, 1.0, t));
        ck_assert(pdf[b3](u * st, x * sx, y * sx, a * sx, 1.0, t * st) ==
                  pdf[b3](u, x, y, a, 1.0, t) / st);
        ck_assert(qf[b3](u, x * sx, y * sx, a * sx, 1.0, t * st) ==
                  qf[b3](u, x, y, a, 1.0, t) * st);
      }
      gsl_rng_set(r, 5);
      double d1 = smp[b3](r, x, y, a, 1.0, t);
      gsl_rng_set(r, 5);
      double d2 = smp[b3](r, x * sx, y * sx, a * sx, 1.0, t * st);
      ck_assert(d2 == d1 * st);
    }
  gsl_rng_free(r);
}
END_TEST

/* Positions beyond ~2^990 sqrt(sigma2 t).  The rescaling to sigma2 t of
 * order one overflowed them (SB_EDOM for every function), and sigma2 u t
 * (t - u) below DBL_MIN was read as "no mass below u" (cdf 0 where the
 * law sits at u ~ 1e-600).  The law of T is then a step at
 * u* = t alpha/(alpha + |beta|) on the scale of the doubles (relative
 * width ~ sqrt(v/(alpha |beta|)) < 1e-150 here), so by the definitions
 * (conditioned on T <= t, not defective) cdf = 0 below u* and 1 above,
 * sf = 1 - cdf, pdf 0 off u*; where u = u* exactly (c = 0) the cdf is
 * Phi(0) = 1/2 up to exp(2 alpha |beta|/v) Phi(-2 sqrt(alpha |beta|/v))
 * < 1e-400, and the density ~1e550 is SB_ERANGE.  Non-trivial values
 * (mpmath at 1000 digits) are in bridge_hit.csv. */
START_TEST(test_hit_overflow)
{
  typedef int (*hfe)(double, double, double, double, double, double,
                     sb_result *);
  static const hfe F[2][3] = {
      {sb_bb_hit_pdf_e, sb_bb_hit_cdf_e, sb_bb_hit_sf_e},
      {sb_bes3b_hit_pdf_e, sb_bes3b_hit_cdf_e, sb_bes3b_hit_sf_e}};
  const double s2 = 1e-200, t = 1e-100; /* sqrt(v) = 1e-150, rescaled */
  /* (u, x, y, a, pdf, cdf); pdf NaN: SB_ERANGE */
  static const double rows[][6] = {
      /* x far: u* = t (1 - 2.5e-451) */
      {0.5e-100, 1e300, 0.5, 0.25, 0.0, 0.0},
      {0.999999e-100, 1e300, 0.5, 0.25, 0.0, 0.0},
      /* y far: u* = 7.5e-401 (sigma2 u t w underflows at u = 1e-300) */
      {1e-300, 1.0, 1e300, 0.25, 0.0, 1.0},
      {0.5e-100, 1.0, 1e300, 0.25, 0.0, 1.0},
      /* both far: u* = t/2 */
      {0.49e-100, 1e300, 1e300, 0.25, 0.0, 0.0},
      {0.5e-100, 1e300, 1e300, 0.25, NAN, 0.5},
      {0.51e-100, 1e300, 1e300, 0.25, 0.0, 1.0},
      /* a above x: T = 0 */
      {0.5e-100, 1e300, 1.0, 2e300, 0.0, 1.0}};
  for (int b3 = 0; b3 < 2; b3++)
    for (size_t i = 0; i < sizeof rows / sizeof rows[0]; i++) {
      const double *r = rows[i];
      sb_result res;
      for (int j = 0; j < 3; j++) {
        const double want = j == 0 ? r[4] : j == 1 ? r[5] : 1.0 - r[5];
        const int st = F[b3][j](r[0], r[1], r[2], r[3], s2, t, &res);
        if (isnan(want))
          ck_assert_msg(st == SB_ERANGE && isnan(res.val),
                        "b3 %d row %zu fn %d: %g status %d, want "
                        "SB_ERANGE", b3, i, j, res.val, st);
        else
          ck_assert_msg(st == SB_SUCCESS && res.val == want,
                        "b3 %d row %zu fn %d: %g status %d, want %g", b3, i,
                        j, res.val, st, want);
      }
    }
  /* BB with a level far below: u* = t/2 */
  ck_assert(sb_bb_hit_cdf(0.5e-100, 1.0, 1.0, -1e300, s2, t) == 0.5);
  ck_assert(sb_bb_hit_cdf(0.49e-100, 1.0, 1.0, -1e300, s2, t) == 0.0);
  /* quantiles: the best doubles of the steps (u* = t: either neighbour of
   * the step is as good for p = 0.5) */
  typedef double (*qf)(double, double, double, double, double, double);
  typedef double (*sf)(const gsl_rng *, double, double, double, double,
                       double);
  const qf Q[2] = {sb_bb_hit_quantile, sb_bes3b_hit_quantile};
  const sf S[2] = {sb_bb_hit_sample, sb_bes3b_hit_sample};
  gsl_rng *g = gsl_rng_alloc(gsl_rng_mt19937);
  for (int b3 = 0; b3 < 2; b3++) {
    double q = Q[b3](0.5, 1e300, 0.5, 0.25, s2, t);
    ck_assert_msg(q == t || q == nextafter(t, 0.0), "b3 %d: q = %.17g", b3,
                  q);
    ck_assert(Q[b3](0.5, 1.0, 1e300, 0.25, s2, t) == 0.0);
    ck_assert(Q[b3](0.5, 1e300, 1e300, 0.25, s2, t) == 0.5e-100);
    ck_assert(Q[b3](0.5, 1e-300, 1e300, 1e-301, s2, t) == 0.0);
    /* samples: the step's double (NaN with status 0 before where alpha t/L
     * and alpha^2/sigma2 both underflowed: 0/0) */
    for (int k = 0; k < 20; k++) {
      sb_clear_error();
      double d = S[b3](g, 1e300, 0.5, 0.25, s2, t);
      ck_assert(d <= t && d >= nextafter(nextafter(t, 0.0), 0.0));
      ck_assert(S[b3](g, 1.0, 1e300, 0.25, s2, t) == 0.0);
      ck_assert(S[b3](g, 1e-300, 1e300, 1e-301, 1.0, 1.0) == 0.0);
      d = S[b3](g, 1e300, 1e300, 0.25, s2, t);
      ck_assert(fabs(d - 0.5e-100) <= 2e-116);
      ck_assert_int_eq(sb_last_status(), SB_SUCCESS);
    }
  }
  gsl_rng_free(g);
  /* the B3B density where 2ay/(sigma2 (t - u)) underflows (min(a, y)
   * ~1e-300 against x = 1e298, not rescaled): 0, was NaN (0 * inf) with
   * status 0 */
  sb_result res;
  ck_assert_int_eq(sb_bes3b_hit_pdf_e(0.5, 1e298, 1e-300, 1e-301, 1e-180,
                                      1.0, &res),
                   SB_SUCCESS);
  ck_assert(res.val == 0.0);
}
END_TEST

START_TEST(test_hit_special)
{
  gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
  /* x <= a: T = 0 */
  ck_assert(sb_bb_hit_cdf(0.0, 0.9, 2.0, 1.0, 1.0, 1.0) == 1.0);
  ck_assert(sb_bb_hit_cdf(-0.1, 0.9, 2.0, 1.0, 1.0, 1.0) == 0.0);
  ck_assert(sb_bes3b_hit_sf(0.5, 1.0, 2.0, 1.0, 1.0, 1.0) == 0.0);
  ck_assert(sb_bes3b_hit_quantile(0.7, 0.5, 2.0, 1.0, 1.0, 1.0) == 0.0);
  ck_assert(sb_bes3b_hit_sample(r, 0.5, 2.0, 1.0, 1.0, 1.0) == 0.0);
  ck_assert(sb_bb_hit_sample(r, 0.5, 2.0, 1.0, 1.0, 1.0) == 0.0);
  ck_assert(sb_bb_hit_pdf(0.5, 0.5, 2.0, 1.0, 1.0, 1.0) == 0.0);
  /* u outside [0, t] */
  ck_assert(sb_bb_hit_cdf(-1.0, 2.0, 2.0, 1.0, 1.0, 1.0) == 0.0);
  ck_assert(sb_bb_hit_cdf(2.0, 2.0, 2.0, 1.0, 1.0, 1.0) == 1.0);
  ck_assert(sb_bes3b_hit_sf(2.0, 2.0, 2.0, 1.0, 1.0, 1.0) == 0.0);
  ck_assert(sb_bes3b_hit_pdf(-1.0, 2.0, 2.0, 1.0, 1.0, 1.0) == 0.0);
  /* Bessel-3 level 0: only y = 0 makes sense (T = t) */
  ck_assert(sb_bes3b_hit_cdf(0.5, 2.0, 0.0, 0.0, 1.0, 1.0) == 0.0);
  ck_assert(sb_bes3b_hit_cdf(1.0, 2.0, 0.0, 0.0, 1.0, 1.0) == 1.0);
  ck_assert(sb_bes3b_hit_sample(r, 2.0, 0.0, 0.0, 1.0, 1.0) == 1.0);
  ck_assert(isnan(sb_bes3b_hit_cdf(0.5, 2.0, 1.0, 0.0, 1.0, 1.0)));
  ck_assert_int_eq(sb_last_status(), SB_EDOM);
  /* y = 0 is the continuous limit y -> 0 */
  ck_assert_rel(sb_bes3b_hit_cdf(0.4, 1.5, 0.0, 1.0, 1.0, 1.0),
                sb_bes3b_hit_cdf(0.4, 1.5, 1e-12, 1.0, 1.0, 1.0), 1e-10);
  /* cdf + sf = 1 */
  for (double u = 0.05; u < 1.0; u += 0.1) {
    ck_assert_abs(sb_bes3b_hit_cdf(u, 1.5, 1.3, 1.0, 1.0, 1.0) +
                      sb_bes3b_hit_sf(u, 1.5, 1.3, 1.0, 1.0, 1.0),
                  1.0, TOL_ULPS(8));
    ck_assert_abs(sb_bb_hit_cdf(u, 1.5, 1.3, 1.0, 1.0, 1.0) +
                      sb_bb_hit_sf(u, 1.5, 1.3, 1.0, 1.0, 1.0),
                  1.0, TOL_ULPS(8));
  }
  gsl_rng_free(r);
}
END_TEST

START_TEST(test_bad_input)
{
  sb_result r;
  gsl_rng *g = gsl_rng_alloc(gsl_rng_mt19937);
  sb_clear_error();
  /* crossing: NaN, negative or infinite v, Bessel a < 0, x < 0 */
  ck_assert(isnan(sb_bb_cross_prob(NAN, 1, 0, 1)));
  ck_assert_int_eq(sb_last_status(), SB_EDOM);
  ck_assert(strstr(sb_last_error(), "sb_bb_cross_prob") != NULL);
  ck_assert_int_eq(sb_bb_cross_prob_e(2, 2, 1, -1.0, &r), SB_EDOM);
  ck_assert(isnan(r.val) && isnan(r.err));
  ck_assert_int_eq(sb_bb_cross_logprob_e(2, 2, 1, INFINITY, &r), SB_EDOM);
  ck_assert_int_eq(sb_bb_nocross_prob_e(2, 2, NAN, 1, &r), SB_EDOM);
  ck_assert_int_eq(sb_bes3b_cross_prob_e(2, 2, -1.0, 1, &r), SB_EDOM);
  ck_assert(strstr(sb_last_error(), "a = -1") != NULL);
  ck_assert_int_eq(sb_bes3b_cross_logprob_e(-2, 2, 1.0, 1, &r), SB_EDOM);
  ck_assert_int_eq(sb_bes3b_nocross_prob_e(2, 2, 1.0, NAN, &r), SB_EDOM);
  /* hitting times */
  hit_e fn[6] = {sb_bb_hit_pdf_e,    sb_bb_hit_cdf_e,
                 sb_bb_hit_sf_e,     sb_bes3b_hit_pdf_e,
                 sb_bes3b_hit_cdf_e, sb_bes3b_hit_sf_e};
  for (int k = 0; k < 6; k++) {
    ck_assert_int_eq(fn[k](NAN, 2, 2, 1, 1, 1, &r), SB_EDOM);
    ck_assert_int_eq(fn[k](0.5, 2, 2, 1, -1.0, 1, &r), SB_EDOM);
    ck_assert_int_eq(fn[k](0.5, 2, 2, 1, 0.0, 1, &r), SB_EDOM);
    ck_assert_int_eq(fn[k](0.5, 2, 2, 1, 1, -1.0, &r), SB_EDOM);
    ck_assert_int_eq(fn[k](0.5, 2, 2, 1, 1, 0.0, &r), SB_EDOM);
    ck_assert_int_eq(fn[k](0.5, 2, INFINITY, 1, 1, 1, &r), SB_EDOM);
    ck_assert(isnan(r.val));
  }
  ck_assert_int_eq(sb_bes3b_hit_cdf_e(0.5, 2, 2, -1, 1, 1, &r), SB_EDOM);
  ck_assert_int_eq(sb_bes3b_hit_cdf_e(0.5, -2, 2, 1, 1, 1, &r), SB_EDOM);
  ck_assert_int_eq(sb_bb_hit_quantile_e(-0.5, 2, 2, 1, 1, 1, &r), SB_EDOM);
  ck_assert_int_eq(sb_bb_hit_quantile_e(1.5, 2, 2, 1, 1, 1, &r), SB_EDOM);
  ck_assert_int_eq(sb_bes3b_hit_quantile_e(NAN, 2, 2, 1, 1, 1, &r), SB_EDOM);
  ck_assert(isnan(sb_bes3b_hit_quantile(0.5, 2, 2, 1, 1, NAN)));
  ck_assert(isnan(sb_bb_hit_sample(NULL, 2, 2, 1, 1, 1)));
  ck_assert_int_eq(sb_last_status(), SB_EINVAL);
  ck_assert(isnan(sb_bes3b_hit_sample(g, 2, 2, -1, 1, 1)));
  ck_assert(isnan(sb_bb_hit_sample(g, 2, 2, 1, -1, 1)));
  ck_assert_int_eq(sb_bb_hit_cdf_e(0.5, 2, 2, 1, 1, 1, NULL), SB_SUCCESS);
  gsl_rng_free(g);
}
END_TEST

/* Every argument in turn over +-1e-320 ... +-DBL_MAX, +-inf, NaN, 0 and a
 * few magnitudes where double-double products (2^995) or squares (1e154)
 * overflow, the others ordinary: the value is finite with status 0, or NaN
 * with an error status and a message naming the public function (never
 * NaN, or +-inf with status 0).  At +-inf the
 * rule of bridge.h: u = +-inf is outside [0, t] (pdf 0, cdf 0 at -inf and
 * 1 at +inf, sf 1 - cdf, status 0), the crossings do not read a[0] and
 * a[5], and
 * every other infinite argument (x, y, a, v, sigma2, t, p) is NaN with
 * SB_EDOM.  The values at
 * the extreme corners are checked against mpmath in bridge_hit.csv,
 * bridge_cross.csv and bridge_quantile.csv (the rows after the "extreme"
 * comments of tests/gen_refdata.py). */
typedef sbt_sfn xfn;
static double x_bbpdf(const double *a)
{
  return sb_bb_hit_pdf(a[0], a[1], a[2], a[3], a[4], a[5]);
}
static double x_bbcdf(const double *a)
{
  return sb_bb_hit_cdf(a[0], a[1], a[2], a[3], a[4], a[5]);
}
static double x_bbsf(const double *a)
{
  return sb_bb_hit_sf(a[0], a[1], a[2], a[3], a[4], a[5]);
}
static double x_b3pdf(const double *a)
{
  return sb_bes3b_hit_pdf(a[0], a[1], a[2], a[3], a[4], a[5]);
}
static double x_b3cdf(const double *a)
{
  return sb_bes3b_hit_cdf(a[0], a[1], a[2], a[3], a[4], a[5]);
}
static double x_b3sf(const double *a)
{
  return sb_bes3b_hit_sf(a[0], a[1], a[2], a[3], a[4], a[5]);
}

static double x_bbq(const double *a)
{
  return sb_bb_hit_quantile(a[0], a[1], a[2], a[3], a[4], a[5]);
}
static double x_b3q(const double *a)
{
  return sb_bes3b_hit_quantile(a[0], a[1], a[2], a[3], a[4], a[5]);
}

/* crossing functions: (x, y, a, v) in a[1..4]; log P = -inf with status
 * 0 only where P = 0 exactly (v = 0, or a Bessel-3 level a = 0) */
static double x_bblog(const double *a)
{
  double v = sb_bb_cross_logprob(a[1], a[2], a[3], a[4]);
  return isinf(v) && v < 0.0 && a[4] == 0.0 ? 0.0 : v;
}
static double x_b3log(const double *a)
{
  double v = sb_bes3b_cross_logprob(a[1], a[2], a[3], a[4]);
  return isinf(v) && v < 0.0 && (a[4] == 0.0 || a[3] == 0.0) ? 0.0 : v;
}
static double x_bbp(const double *a)
{
  return sb_bb_cross_prob(a[1], a[2], a[3], a[4]);
}
static double x_b3p(const double *a)
{
  return sb_bes3b_cross_prob(a[1], a[2], a[3], a[4]);
}
static double x_bbnp(const double *a)
{
  return sb_bb_nocross_prob(a[1], a[2], a[3], a[4]);
}
static double x_b3np(const double *a)
{
  return sb_bes3b_nocross_prob(a[1], a[2], a[3], a[4]);
}

START_TEST(test_extreme_arguments)
{
  /* (u or p, x, y, a, sigma2, t); crossings (-, x, y, a, v) */
  static const double base[4][6] = {{0.3, 1.0, 0.5, 0.0, 1.0, 1.0},
                                    {0.3, 2.0, 1.0, 0.5, 1.0, 1.0},
                                    {0.0, 1.0, 0.5, 0.0, 1.0, 0.0},
                                    {0.0, 2.0, 1.0, 0.5, 1.0, 0.0}};
  static const struct {
    xfn f;
    int b;
    const char *nm;
  } k[] = {{x_bbpdf, 0, "sb_bb_hit_pdf"},
           {x_bbcdf, 0, "sb_bb_hit_cdf"},
           {x_bbsf, 0, "sb_bb_hit_sf"},
           {x_b3pdf, 1, "sb_bes3b_hit_pdf"},
           {x_b3cdf, 1, "sb_bes3b_hit_cdf"},
           {x_b3sf, 1, "sb_bes3b_hit_sf"},
           {x_bblog, 2, "sb_bb_cross_logprob"},
           {x_b3log, 3, "sb_bes3b_cross_logprob"},
           {x_bbp, 2, "sb_bb_cross_prob"},
           {x_b3p, 3, "sb_bes3b_cross_prob"},
           {x_bbnp, 2, "sb_bb_nocross_prob"},
           {x_b3np, 3, "sb_bes3b_nocross_prob"},
           {x_bbq, 0, "sb_bb_hit_quantile"},
           {x_b3q, 1, "sb_bes3b_hit_quantile"}};
  /* sbt_sweep_ext with +-inf; an error names the function */
  for (size_t f = 0; f < sizeof k / sizeof k[0]; f++)
    sbt_sweep_scalar(k[f].f, base[k[f].b], 6, 0, f, k[f].nm);
  /* the values at +-inf: k[0 .. 5] pdf, cdf, sf; 6 .. 11 crossings; 12,
   * 13 quantiles */
  for (size_t f = 0; f < sizeof k / sizeof k[0]; f++)
    for (int i = 0; i < 6; i++)
      for (int sg = -1; sg <= 1; sg += 2) {
        double a[6];
        memcpy(a, base[k[f].b], sizeof a);
        a[i] = sg * INFINITY;
        sb_clear_error();
        const double v = k[f].f(a);
        const int st = sb_last_status();
        if (i == 0 && f < 6) { /* u */
          const double cdf = sg > 0 ? 1.0 : 0.0;
          const double want = f % 3 == 0 ? 0.0 : f % 3 == 1 ? cdf : 1 - cdf;
          ck_assert_msg(v == want && st == SB_SUCCESS,
                        "function %zu, u = %g: %g with status %d, want %g",
                        f, a[0], v, st, want);
        } else if ((i == 0 || i == 5) && f >= 6 && f < 12) { /* unused */
          const double want = k[f].f(base[k[f].b]);
          ck_assert_msg(v == want && st == SB_SUCCESS,
                        "function %zu, unused argument %d = %g: %g with "
                        "status %d, want %g", f, i, a[i], v, st, want);
        } else
          ck_assert_msg(isnan(v) && st == SB_EDOM,
                        "function %zu, argument %d = %g: %g with status %d, "
                        "want SB_EDOM", f, i, a[i], v, st);
      }
  /* a density above DBL_MAX is SB_ERANGE naming the function */
  sb_result r;
  ck_assert_int_eq(sb_bb_hit_pdf_e(1e-310, 1e-155, 1e-155, 0.0, 1.0, 1e-300,
                                   &r),
                   SB_ERANGE);
  ck_assert(isnan(r.val));
  ck_assert(strstr(sb_last_error(), "sb_bb_hit_pdf") != NULL);
  ck_assert(strstr(sb_last_error(), "u = 1e-310") != NULL);
  /* log P below -DBL_MAX is SB_ERANGE; P = 0 exactly gives -inf */
  ck_assert_int_eq(sb_bb_cross_logprob_e(1.0, 0.5, 0.0, 1e-320, &r),
                   SB_ERANGE);
  ck_assert(strstr(sb_last_error(), "sb_bb_cross_logprob") != NULL);
  ck_assert_int_eq(sb_bes3b_cross_logprob_e(DBL_MAX, 2.0, 0.5, 1.0, &r),
                   SB_ERANGE);
  ck_assert_int_eq(sb_bb_cross_logprob_e(1.0, 0.5, 0.0, 0.0, &r),
                   SB_SUCCESS);
  ck_assert(r.val == -INFINITY);
  ck_assert_int_eq(sb_bes3b_cross_logprob_e(1.0, 0.5, 0.0, 1.0, &r),
                   SB_SUCCESS);
  ck_assert(r.val == -INFINITY);
}
END_TEST

/* The samplers, every argument in turn over sbt_sweep_ext and +-1e-150,
 * +-1, +-1e150, the others ordinary: each of 20 draws (MT19937, seed 7) is
 * in [0, t] with status 0, or NaN with SB_EDOM or SB_ERANGE and a message
 * naming the public function (the errors used to name an internal
 * helper).  Draws used to exceed t by an ulp where s >> t (t = 1e150: ~1%
 * of the draws; t = DBL_MAX: +inf). */
static gsl_rng *sx_rng; /* test_sampler_extreme's generator */
/* up to 20 draws of sampler b3 at (x, y, a, sigma2, t) = a[0 .. 4]: the
 * first out of [0, t] (a NaN with its status ends the draws), else the
 * last; out = {v, t - v}, both >= 0 where v is in [0, t] */
static int sx_draws(int b3, const double *a, double *out, int *n,
                    const char **nm)
{
  *nm = b3 ? "sb_bes3b_hit_sample" : "sb_bb_hit_sample";
  for (int k = 0; k < 20; k++) {
    sb_clear_error();
    const double v =
        b3 ? sb_bes3b_hit_sample(sx_rng, a[0], a[1], a[2], a[3], a[4])
           : sb_bb_hit_sample(sx_rng, a[0], a[1], a[2], a[3], a[4]);
    const int st = sb_last_status();
    out[0] = v;
    *n = 1;
    if (isnan(v) || st != SB_SUCCESS)
      return st;
    out[1] = !(v <= a[4]) ? -1.0 : isinf(a[4]) ? 0.0 : a[4] - v;
    *n = 2;
    if (!(v >= 0.0 && v <= a[4]))
      break;
  }
  return SB_SUCCESS;
}
static int sx_bb(const double *a, double *out, int *n, const char **nm)
{
  return sx_draws(0, a, out, n, nm);
}
static int sx_b3(const double *a, double *out, int *n, const char **nm)
{
  return sx_draws(1, a, out, n, nm);
}

START_TEST(test_sampler_extreme)
{
  static const double base[2][5] = {{1.0, 0.5, 0.0, 1.0, 1.0},
                                    {2.0, 1.0, 0.5, 1.0, 1.0}};
  double ext[SBT_SWEEP_NEXT + 6];
  memcpy(ext, sbt_sweep_ext, sizeof sbt_sweep_ext);
  const double more[6] = {1e-150, -1e-150, 1.0, -1.0, 1e150, -1e150};
  memcpy(ext + SBT_SWEEP_NEXT, more, sizeof more);
  gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
  gsl_rng_set(r, 7);
  sx_rng = r;
  int nbad = sbt_sweep_vec_over(sx_bb, base[0], 5, 5, 3u, 0, SBT_SWEEP_NAN,
                                0, ext, SBT_SWEEP_NEXT + 6);
  nbad += sbt_sweep_vec_over(sx_b3, base[1], 5, 5, 3u, 0, SBT_SWEEP_NAN, 1,
                             ext, SBT_SWEEP_NEXT + 6);
  ck_assert_int_eq(nbad, 0);
  /* t = 1e150: 2000 draws, none above t */
  for (int k = 0; k < 2000; k++)
    ck_assert(sb_bes3b_hit_sample(r, 2.0, 1.0, 0.5, 1.0, 1e150) <= 1e150);
  sb_clear_error();
  ck_assert(isnan(sb_bb_hit_sample(NULL, 1.0, 0.5, 0.0, 1.0, 1.0)));
  ck_assert_int_eq(sb_last_status(), SB_EINVAL);
  ck_assert(strstr(sb_last_error(), "sb_bb_hit_sample") != NULL);
  gsl_rng_free(r);
}
END_TEST

static Suite *bridge_suite(void)
{
  Suite *s = suite_create("bridge");
  TCase *tc = tcase_create("crossing");
  tcase_add_test(tc, test_cross_reference);
  tcase_add_test(tc, test_cross_special);
  tcase_add_test(tc, test_cross_vs_quadrature);
  suite_add_tcase(s, tc);
  tc = tcase_create("hitting");
  tcase_add_test(tc, test_hit_reference);
  tcase_add_test(tc, test_hit_vs_quadrature);
  tcase_add_test(tc, test_thesis_versions);
  tcase_add_test(tc, test_quantile_reference);
  tcase_add_test(tc, test_narrow_reference);
  tcase_add_test(tc, test_quantile_roundtrip);
  tcase_add_test(tc, test_quantile_best_double);
  tcase_add_test(tc, test_hit_scale);
  tcase_add_test(tc, test_hit_special);
  tcase_add_test(tc, test_hit_overflow);
  tcase_add_test(tc, test_extreme_arguments);
  tcase_add_test(tc, test_bad_input);
  tcase_set_timeout(tc, 30);
  suite_add_tcase(s, tc);
  tc = tcase_create("samplers");
  tcase_add_test(tc, test_samplers);
  tcase_add_test(tc, test_sampler_extreme);
  tcase_set_timeout(tc, 60);
  suite_add_tcase(s, tc);
  return s;
}

int main(void)
{
  gsl_set_error_handler_off(); /* the test's own QAGS calls report status */
  return sbt_run_suite(bridge_suite());
}
