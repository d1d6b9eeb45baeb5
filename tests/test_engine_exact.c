/* test_engine_exact.c — exact endpoint-conditioned 3-D bridge detection
 * (sb_bb3_hit_sample, lib/engine/engine_exact.c) against a brute-force fine-step
 * simulation, a closed form, and the Bessel-3 criterion. */
#include <math.h>
#include <stdlib.h>

#include <check.h>
#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>
#include <gsl/gsl_sf_erf.h>

#include <smolbridge/bridge.h>
#include <smolbridge/engine_bridge.h>
#include <smolbridge/stats.h>

#include "testutil.h"

/* Brute force: the bridge A -> B on [0, t] in n equal sub-steps, each new
 * point drawn from the exact bridge law given the previous point and B;
 * a contact within a sub-step is decided by the Bessel-3 formula on that
 * sub-step (variance sigma2 t/n, i.e. sqrt(v)/a = 0.03 for n = 1024 in the
 * configurations below).  Returns 1 and the hit time at the sub-step
 * start plus the Bessel-3 conditioned time within it, or 0. */
static int brute(const gsl_rng *r, const double *A, const double *B,
                 double a, double s2, double t, int n, double *ta)
{
  double P[3] = {A[0], A[1], A[2]};
  const double h = t / n;
  for (int k = 0; k < n; k++) {
    double rem = t - k * h, Q[3];
    for (int c = 0; c < 3; c++) {
      double mean = P[c] + (B[c] - P[c]) * h / rem;
      double var = s2 * h * (rem - h) / rem;
      Q[c] = mean + gsl_ran_gaussian_ziggurat(r, sqrt(var));
    }
    double x = sqrt(P[0] * P[0] + P[1] * P[1] + P[2] * P[2]);
    double y = sqrt(Q[0] * Q[0] + Q[1] * Q[1] + Q[2] * Q[2]);
    if (y <= a || gsl_rng_uniform(r) < sb_bes3b_cross_prob(x, y, a, s2 * h)) {
      *ta = k * h + sb_bes3b_hit_sample(r, x, y, a, s2, h);
      return 1;
    }
    for (int c = 0; c < 3; c++)
      P[c] = Q[c];
  }
  return 0;
}

/* Configurations (a = 1, sigma2 = 1, t = 1 so v = a^2): |A| = |B| = 2 on
 * the same side (~0.08), opposite (~0.99), perpendicular, and an
 * asymmetric pair.  Exact: 40000 draws; brute force: 4000 paths of 1024
 * steps.  Pass: |p_exact - p_brute| <= 3.5 combined standard errors plus
 * 0.01 (the brute force's own sub-step bias, measured <= 0.006 between
 * n = 1024 and 4096).  The Bessel-3 value 0.135 differs from both in the
 * first two configurations. */
START_TEST(test_exact_vs_brute)
{
  const double cfg[][6] = {{2, 0, 0, 2, 0, 0},
                           {2, 0, 0, -2, 0, 0},
                           {2, 0, 0, 0, 2, 0},
                           {1.5, 0.5, 0, -0.5, 2.5, 1}};
  gsl_rng *r = gsl_rng_alloc(gsl_rng_taus2);
  gsl_rng_set(r, 21);
  for (size_t c = 0; c < sizeof cfg / sizeof cfg[0]; c++) {
    const double *A = cfg[c], *B = cfg[c] + 3;
    const long ne = 40000, nb = 4000;
    long he = 0, hb = 0;
    for (long k = 0; k < ne; k++) {
      double ta, xa[3];
      int h = sb_bb3_hit_sample(r, A, B, 1.0, 1.0, 1.0, 1e-3, &ta, xa, NULL);
      ck_assert(h == 0 || h == 1);
      if (h) {
        ck_assert(ta >= 0.0 && ta <= 1.0);
        double nx = sqrt(xa[0] * xa[0] + xa[1] * xa[1] + xa[2] * xa[2]);
        ck_assert_rel(nx, 1.0, 1e-12);
      }
      he += h;
    }
    for (long k = 0; k < nb; k++) {
      double ta;
      hb += brute(r, A, B, 1.0, 1.0, 1.0, 1024, &ta);
    }
    double pe = (double)he / ne, pb = (double)hb / nb;
    double se = sqrt(pe * (1 - pe) / ne + pb * (1 - pb) / nb);
    ck_assert_msg(fabs(pe - pb) <= 3.5 * se + 0.01,
                  "config %zu: exact %g, brute %g (se %g)", c, pe, pb, se);
    if (c == 0)
      ck_assert(pe < 0.1);
    if (c == 1)
      ck_assert(pe > 0.97);
  }
  gsl_rng_free(r);
}
END_TEST

/* Hit times of the opposite configuration: exact (4000 hits) vs brute
 * force (2000 hits): two-sample KS, p >= 1e-3. */
START_TEST(test_exact_hit_times)
{
  const double A[3] = {2, 0, 0}, B[3] = {-2, 0, 0};
  gsl_rng *r = gsl_rng_alloc(gsl_rng_taus2);
  gsl_rng_set(r, 22);
  double *te = malloc(4000 * sizeof *te), *tb = malloc(2000 * sizeof *tb);
  size_t ne = 0, nb = 0;
  while (ne < 4000) {
    double ta, xa[3];
    if (sb_bb3_hit_sample(r, A, B, 1.0, 1.0, 1.0, 1e-3, &ta, xa, NULL) == 1)
      te[ne++] = ta;
  }
  while (nb < 2000) {
    double ta;
    if (brute(r, A, B, 1.0, 1.0, 1.0, 1024, &ta))
      tb[nb++] = ta;
  }
  double D, p;
  ck_assert_int_eq(sb_ks2_test(te, ne, tb, nb, &D, &p), SB_SUCCESS);
  ck_assert_msg(p >= 1e-3, "KS2 D = %g, p = %g", D, p);
  free(te);
  free(tb);
  gsl_rng_free(r);
}
END_TEST

/* Averaged over a free end point B ~ N(A, v I), the contact probability
 * is the Bessel-3 first-passage probability (a/x) erfc((x - a)/sqrt(2v))
 * (closed form, independent of the bridge machinery).  x = 1.5, a = 1,
 * v = 0.5: 40000 draws, within 4 standard errors.  The same average of
 * the Bessel-3 criterion is checked too (it is unbiased on average). */
START_TEST(test_exact_free_end)
{
  const double a = 1.0, v = 0.5, A[3] = {1.5, 0, 0};
  const double want = (a / 1.5) * gsl_sf_erfc((1.5 - a) / sqrt(2 * v));
  gsl_rng *r = gsl_rng_alloc(gsl_rng_taus2);
  gsl_rng_set(r, 23);
  const long n = 40000;
  long he = 0;
  double sb = 0.0;
  for (long k = 0; k < n; k++) {
    double B[3], ta, xa[3];
    for (int c = 0; c < 3; c++)
      B[c] = A[c] + gsl_ran_gaussian_ziggurat(r, sqrt(v));
    he += sb_bb3_hit_sample(r, A, B, a, v, 1.0, 1e-3, &ta, xa, NULL);
    double y = sqrt(B[0] * B[0] + B[1] * B[1] + B[2] * B[2]);
    sb += sb_bes3b_cross_prob(1.5, y, a, v);
  }
  double se = sqrt(want * (1 - want) / n);
  ck_assert_msg(fabs((double)he / n - want) < 4 * se, "exact %g want %g",
                (double)he / n, want);
  ck_assert_msg(fabs(sb / n - want) < 4 * se, "bessel %g want %g", sb / n,
                want);
  gsl_rng_free(r);
}
END_TEST

START_TEST(test_exact_edges)
{
  gsl_rng *r = gsl_rng_alloc(gsl_rng_taus2);
  double ta, xa[3];
  const double in[3] = {0.5, 0, 0}, out[3] = {3, 0, 0}, far[3] = {50, 0, 0};
  ck_assert_int_eq(sb_bb3_hit_sample(r, in, out, 1, 1, 1, 1e-3, &ta, xa,
                                     NULL), 1);
  ck_assert(ta == 0.0 && xa[0] == 1.0);
  for (int k = 0; k < 100; k++)  /* end inside: always hits */
    ck_assert_int_eq(sb_bb3_hit_sample(r, out, in, 1, 1, 1, 1e-3, &ta, xa,
                                       NULL), 1);
  sb_bb3_info info;
  ck_assert_int_eq(sb_bb3_hit_sample(r, far, far, 1, 1, 1, 1e-3, &ta, xa,
                                     &info), 0);
  ck_assert_uint_eq(info.nodes, 1);  /* discarded at once */
  ck_assert_int_eq(sb_bb3_hit_sample(r, out, out, -1, 1, 1, 1e-3, &ta, xa,
                                     NULL), -SB_EDOM);
  ck_assert_int_eq(sb_bb3_hit_sample(r, out, out, 1, 1, 1, 0.5, &ta, xa,
                                     NULL), -SB_EDOM);
  gsl_rng_free(r);
}
END_TEST

static Suite *suite(void)
{
  Suite *s = suite_create("engine_exact");
  TCase *tc = tcase_create("core");
  tcase_set_timeout(tc, 60);
  tcase_add_test(tc, test_exact_vs_brute);
  tcase_add_test(tc, test_exact_hit_times);
  tcase_add_test(tc, test_exact_free_end);
  tcase_add_test(tc, test_exact_edges);
  suite_add_tcase(s, tc);
  return s;
}

int main(void) { return sbt_run_suite(suite()); }
