/* test_spray_mc.c — small Monte Carlo checks of the spray collision
 * operators against exact results.
 *
 * Every test uses fixed seeds and R independent replicas; it passes iff the
 * replica mean lies within 4 standard errors of the exact value (a false
 * alarm has probability ~1e-4 per check; the seeds are fixed, so the
 * outcome is reproducible).  Sample sizes are stated per test.  Each test
 * was checked to fail when the operator is broken (docs/spray.md,
 * "Tests").
 */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>

#include <smolbridge/kernel.h>
#include <smolbridge/langevin.h>
#include <smolbridge/pbe.h>
#include <smolbridge/spray.h>
#include <smolbridge/stats.h>

#include "testutil.h"

#define PI 3.14159265358979323846
#define NSE 4.0

/* |mean(x) - ref| <= NSE standard errors. */
static void check_replicas(const double *x, int R, double ref, const char *w)
{
  double m = 0, v = 0;
  for (int i = 0; i < R; i++)
    m += x[i] / R;
  for (int i = 0; i < R; i++)
    v += (x[i] - m) * (x[i] - m) / (R - 1);
  double se = sqrt(v / R);
  ck_assert_msg(fabs(m - ref) <= NSE * se,
                "%s: mean %.6g, reference %.6g, standard error %.3g (%.2f SE)",
                w, m, ref, se, (m - ref) / se);
}

static gsl_rng *rng_seeded(unsigned long seed)
{
  gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
  gsl_rng_set(r, seed);
  return r;
}

/* BKW: N = 4000 particles from the BKW state K0 = 0.6, Maxwell kernel with
 * n B0 = 1/s, 8 replicas per method; E|v|^4 at t = 3 s vs the exact
 * theta^2 K (30 - 15 K), K = 1 - 0.4 exp(-lambda t/6) (Bird: lambda =
 * N/(N-1)).  The speed of the relaxation is what is tested: the initial
 * E|v|^4 is 12.6 and the t = 3 value 13.8 (the standard error ~0.06). */
/* O'Rourke's Weber-number dependent coalescence (sb_spray_orourke_b2).
 * Deterministic: the formula against its definition at three pairs.
 * Monte Carlo: M = 20000 two-drop Bird systems with relative speed g;
 * the first collision merges with probability (b_cr/(r1 + r2))^2, since
 * sigma is isotropic; exact binomial test of the merge count, pass iff
 * p >= 1e-4 (seed 900 + case).  Equal 10 um water drops at 10 m/s (We =
 * 13.9, P = 3.12/We), a 2:1 radius pair (f(2) = 3.8), and 2 m/s (We < 3.12:
 * every collision merges). */
typedef struct {
  int seen, merged;
} first_event;

static void first_obs(const sb_spray_event *e, void *ctx)
{
  first_event *f = ctx;
  if (!f->seen++)
    f->merged = e->kind == SB_SPRAY_MERGE;
}

START_TEST(test_orourke_coalescence)
{
  const double rho = 1000, sig = 0.072;
  const double cases[3][3] = {{10e-6, 10e-6, 10}, {10e-6, 20e-6, 10},
                              {10e-6, 10e-6, 2}};
  for (int c = 0; c < 3; c++) {
    double r1 = cases[c][0], r2 = cases[c][1], g = cases[c][2];
    double gam = r2 / r1, We = rho * g * g * r1 / sig;
    double P = fmin(1.0, 2.4 * (gam * gam * gam - 2.4 * gam * gam +
                                2.7 * gam) / We);
    ck_assert_rel(sb_spray_orourke_b2(r1, r2, g, rho, sig), P, 8 * DBL_EPSILON);
    ck_assert_rel(sb_spray_orourke_b2(r2, r1, g, rho, sig), P, 8 * DBL_EPSILON);
    sb_spray_params p;
    sb_spray_params_default(&p);
    p.coal = SB_SPRAY_COAL_OROURKE;
    p.sigma = sig;
    p.rho_l = rho;
    p.volume = 2 * PI * (r1 + r2) * (r1 + r2) * g; /* pair rate 1/s */
    sb_spray *s = sb_spray_alloc(&p);
    gsl_rng *rng = rng_seeded(900 + c);
    first_event fe;
    sb_spray_set_observer(s, first_obs, &fe);
    const unsigned long M = 20000;
    unsigned long k = 0;
    double v1[3] = {g, 0, 0}, v2[3] = {0, 0, 0};
    for (unsigned long m = 0; m < M; m++) {
      sb_spray_clear(s);
      sb_spray_add(s, v1, r1, 1, 0, NULL);
      sb_spray_add(s, v2, r2, 1, 0, NULL);
      fe.seen = fe.merged = 0;
      sb_spray_collide(s, 40.0, rng); /* P(no event) = e^-40 */
      ck_assert(fe.seen > 0);
      k += (unsigned long)fe.merged;
    }
    double pv = sb_binomial_pvalue(k, M, P);
    ck_assert_msg(pv >= 1e-4, "case %d: %lu of %lu merged, P = %.6f (p = %.3g)",
                  c, k, M, P, pv);
    gsl_rng_free(rng);
    sb_spray_free(s);
  }
  /* sigma is required by the model */
  sb_spray_params p;
  sb_spray_params_default(&p);
  p.coal = SB_SPRAY_COAL_OROURKE;
  p.sigma = 0;
  ck_assert_ptr_null(sb_spray_alloc(&p));
  ck_assert(isnan(sb_spray_orourke_b2(0, 1e-5, 1, rho, sig)));
  ck_assert(sb_spray_orourke_b2(1e-5, 1e-5, 0, rho, sig) == 1.0);
}
END_TEST

START_TEST(test_bkw_m4)
{
  const int R = 8, N = 4000;
  for (int meth = 0; meth < 2; meth++) {
    gsl_rng *rng = rng_seeded(100 + meth);
    double x[8];
    for (int rr = 0; rr < R; rr++) {
      sb_spray_params p;
      sb_spray_params_default(&p);
      p.method = (sb_spray_method)meth;
      p.cross = SB_SPRAY_MAXWELL;
      p.volume = N;
      sb_spray *s = sb_spray_alloc(&p);
      for (int i = 0; i < N; i++) {
        double v[3];
        sb_spray_bkw_sample(0.6, 1.0, rng, v);
        sb_spray_add(s, v, 1e-3, 1.0, 0, NULL);
      }
      ck_assert_int_eq(sb_spray_collide(s, 3.0, rng), SB_SUCCESS);
      double lam = meth == 0 ? (double)N / (N - 1) : 1.0;
      x[rr] = sb_spray_velocity_moment(s, 4, NULL, -1) /
              sb_spray_bkw_m4(sb_spray_bkw_K(0.6, lam, 3.0), 1.0);
      sb_spray_free(s);
    }
    check_replicas(x, R, 1.0, meth ? "Nanbu BKW M4" : "Bird BKW M4");
    gsl_rng_free(rng);
  }
}
END_TEST

/* BKW sampler: 2e5 draws at K = 0.7, mean of |v|^4 and |v|^6 vs the
 * moments (20 batches). */
START_TEST(test_bkw_sampler)
{
  gsl_rng *rng = rng_seeded(3);
  double x4[20], x6[20];
  for (int b = 0; b < 20; b++) {
    double s4 = 0, s6 = 0;
    for (int i = 0; i < 10000; i++) {
      double v[3];
      sb_spray_bkw_sample(0.7, 2.0, rng, v);
      double v2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
      s4 += v2 * v2;
      s6 += v2 * v2 * v2;
    }
    x4[b] = s4 / 1e4 / sb_spray_bkw_m4(0.7, 2.0);
    x6[b] = s6 / 1e4 / sb_spray_bkw_m6(0.7, 2.0);
  }
  check_replicas(x4, 20, 1.0, "BKW sampler E|v|^4");
  check_replicas(x6, 20, 1.0, "BKW sampler E|v|^6");
  gsl_rng_free(rng);
}
END_TEST

static void count_ab(const sb_spray_event *e, void *ctx)
{
  double *n = ctx;
  if (e->tag_i != e->tag_j)
    *n += 1.0;
}

/* Hard spheres, Bird: N_a = N_b = 1500 (r = 10 and 20 um) at a common
 * temperature (k_B T/m_a = 1 m^2/s^2), 6 replicas of 2 collision times:
 * a-b collision count / (pairs N/((N-1) V) t) vs sb_kernel_kinetic.  The
 * i.i.d. Maxwellian start is stationary, so the expectation is exact. */
START_TEST(test_hs_frequency)
{
  const int R = 6, Na = 1500;
  const double ra = 1e-5, rb = 2e-5, V = 1e-6;
  const double ma = 1000 * 4.0 / 3.0 * PI * ra * ra * ra, mb = 8 * ma;
  const double T = ma / SB_BOLTZMANN;
  const double K = sb_kernel_kinetic(2 * ra, 2 * rb, ma, mb, T);
  const double t = 2.0 / (Na / V * K);
  gsl_rng *rng = rng_seeded(21);
  double x[6];
  for (int rr = 0; rr < R; rr++) {
    sb_spray_params p;
    sb_spray_params_default(&p);
    p.volume = V;
    sb_spray *s = sb_spray_alloc(&p);
    sb_spray_add_maxwellian(s, Na, ra, 1, 0, T, NULL, rng);
    sb_spray_add_maxwellian(s, Na, rb, 1, 1, T, NULL, rng);
    double nab = 0; /* a-b collisions, counted by an observer */
    sb_spray_set_observer(s, count_ab, &nab);
    sb_spray_collide(s, t, rng);
    double N = 2.0 * Na;
    x[rr] = nab / ((double)Na * Na * N / (N - 1) / V * t) / K;
    sb_spray_free(s);
  }
  check_replicas(x, R, 1.0, "Bird a-b collision frequency");
  gsl_rng_free(rng);
}
END_TEST

/* Nanbu, variable weights: the energy drift over 5 collision times of
 * 5000 parcels divided by sqrt(sum of squared event increments) is
 * N(0,1) (energy is a martingale); |z| <= 4 for each of 4 seeds, and the
 * mean square of the 4 is below 4.  Bird: the drift is round-off. */
typedef struct {
  double dE2;
} qv;

static void qv_obs(const sb_spray_event *e, void *ctx)
{
  qv *q = ctx;
  double m = 1000 * 4.0 / 3.0 * PI * e->r_i * e->r_i * e->r_i * e->w_i;
  double d = 0.5 * m * (e->vi_new[0] * e->vi_new[0] + e->vi_new[1] * e->vi_new[1] +
                        e->vi_new[2] * e->vi_new[2] - e->vi[0] * e->vi[0] -
                        e->vi[1] * e->vi[1] - e->vi[2] * e->vi[2]);
  q->dE2 += d * d;
}

START_TEST(test_nanbu_martingale)
{
  double zz = 0;
  for (int seed = 0; seed < 4; seed++) {
    gsl_rng *rng = rng_seeded(40 + seed);
    sb_spray_params p;
    sb_spray_params_default(&p);
    p.method = SB_SPRAY_NANBU;
    p.volume = 1e-6;
    sb_spray *s = sb_spray_alloc(&p);
    double T = 1000 * 4.0 / 3.0 * PI * 1e-15 / SB_BOLTZMANN;
    for (int i = 0; i < 5000; i++) {
      double r = i % 2 ? 1.5e-5 : 1e-5;
      sb_spray_add_maxwellian(s, 1, r, 0.5 + 1.5 * gsl_rng_uniform(rng), 0, T,
                              NULL, rng);
    }
    qv q = {0};
    sb_spray_set_observer(s, qv_obs, &q);
    sb_spray_totals a, b;
    sb_spray_get_totals(s, &a);
    for (int k = 0; k < 5; k++)
      sb_spray_collide(s, 0.2, rng);
    sb_spray_get_totals(s, &b);
    sb_spray_stats st;
    sb_spray_get_stats(s, &st);
    ck_assert(st.bounces > 5000);
    double z = (b.energy - a.energy) / sqrt(q.dE2);
    ck_assert_msg(fabs(z) <= 4, "seed %d: energy drift z = %.3f", seed, z);
    zz += z * z / 4;
    sb_spray_free(s);
    gsl_rng_free(rng);
  }
  ck_assert_msg(zz < 4, "mean z^2 = %.3f", zz);
}
END_TEST

/* Coalescence, Maxwell-type kernel B0 = 1 m^3/s, every collision merges,
 * N0 = 5000 monomers in V = N0 m^3: M0 (1 + tau/2) = 1 and n_2/n_2,exact
 * = 1 at tau = 2 (constant-kernel Smoluchowski), 8 replicas per method. */
START_TEST(test_coalescence_constant)
{
  const int R = 8, N0 = 5000;
  const double tau = 2.0, r1 = 1e-5;
  for (int meth = 0; meth < 2; meth++) {
    gsl_rng *rng = rng_seeded(60 + meth);
    double x0[8], x2[8];
    for (int rr = 0; rr < R; rr++) {
      sb_spray_params p;
      sb_spray_params_default(&p);
      p.method = (sb_spray_method)meth;
      p.cross = SB_SPRAY_MAXWELL;
      p.volume = N0;
      p.theta_cr = 0.5 * PI;
      sb_spray *s = sb_spray_alloc(&p);
      sb_spray_add_maxwellian(s, N0, r1, 1.0, 0, 300, NULL, rng);
      sb_spray_collide(s, tau, rng);
      const double *r = sb_spray_radii(s), *w = sb_spray_weights(s);
      double n = 0, n2 = 0;
      for (size_t i = 0; i < sb_spray_count(s); i++) {
        n += w[i];
        double k = r[i] / r1;
        if (llround(k * k * k) == 2)
          n2 += w[i];
      }
      x0[rr] = n / N0 * (1 + tau / 2);
      x2[rr] = n2 / N0 / sb_pbe_const_mono_n(2, tau);
      sb_spray_free(s);
    }
    check_replicas(x0, R, 1.0, meth ? "Nanbu M0" : "Bird M0");
    check_replicas(x2, R, 1.0, meth ? "Nanbu n_2" : "Bird n_2");
    gsl_rng_free(rng);
  }
}
END_TEST

/* Two temperatures, Maxwell kernel: N_a = N_b = 3000 (m_b = 2 m_a),
 * T_a = 2 T_b, zero momentum per species; T_a(t) at t = 1.5 s vs the exact
 * exponential with rate 2 B0 (n_a + n_b) m_a m_b/M^2 = 4/9 /s, 6
 * replicas, Bird and Nanbu. */
START_TEST(test_two_temperature_maxwell)
{
  const int R = 6, Na = 3000;
  const double ra = 1e-5, rb = ra * cbrt(2.0), t = 1.5;
  const double ma = 1000 * 4.0 / 3.0 * PI * ra * ra * ra, T = ma / SB_BOLTZMANN;
  for (int meth = 0; meth < 2; meth++) {
    gsl_rng *rng = rng_seeded(80 + meth);
    double x[6];
    for (int rr = 0; rr < R; rr++) {
      sb_spray_params p;
      sb_spray_params_default(&p);
      p.method = (sb_spray_method)meth;
      p.cross = SB_SPRAY_MAXWELL;
      p.B0 = 1.0 / (2.0 * Na);
      p.volume = 1.0;
      sb_spray *s = sb_spray_alloc(&p);
      sb_spray_add_maxwellian(s, Na, ra, 1, 0, 2 * T, NULL, rng);
      sb_spray_add_maxwellian(s, Na, rb, 1, 1, T, NULL, rng);
      for (int sp = 0; sp < 2; sp++) {
        double u[3] = {0, 0, 0};
        const double *v = sb_spray_velocities(s);
        for (int i = sp * Na; i < (sp + 1) * Na; i++)
          for (int k = 0; k < 3; k++)
            u[k] += v[3 * i + k] / Na;
        for (int i = sp * Na; i < (sp + 1) * Na; i++) {
          double w[3] = {v[3 * i] - u[0], v[3 * i + 1] - u[1], v[3 * i + 2] - u[2]};
          sb_spray_set_velocity(s, (size_t)i, w);
        }
      }
      sb_spray_mixture mx = {Na, Na, ma, 2 * ma, ra, rb, sb_spray_temperature(s, 0),
                             sb_spray_temperature(s, 1)};
      double B = meth == 0 ? p.B0 * 2.0 * Na / (2.0 * Na - 1) : p.B0, Ta, Tb;
      sb_spray_two_temp_maxwell(&mx, B, t, &Ta, &Tb);
      sb_spray_collide(s, t, rng);
      x[rr] = sb_spray_temperature(s, 0) / Ta;
      sb_spray_free(s);
    }
    check_replicas(x, R, 1.0, meth ? "Nanbu T_a" : "Bird T_a");
    gsl_rng_free(rng);
  }
}
END_TEST

/* The hard-sphere two-temperature rate at t = 0 (closed form) vs a Monte
 * Carlo average of B (-mu G.g) over 10 x 1e5 independent Maxwellian
 * pairs (T_a = 3 T_b, m_b = 5 m_a). */
START_TEST(test_two_temperature_hs_rate)
{
  const double ra = 1e-5, rb = 2e-5, ma = 1e-12, mb = 5e-12;
  const double Ta = 3e11, Tb = 1e11, nb = 1e9;
  sb_spray_mixture mx = {1e9, nb, ma, mb, ra, rb, Ta, Tb};
  double rate = sb_spray_two_temp_hs_rate(&mx, Ta, Tb);
  gsl_rng *rng = rng_seeded(99);
  double x[10], sa = sqrt(SB_BOLTZMANN * Ta / ma), sb = sqrt(SB_BOLTZMANN * Tb / mb);
  double M = ma + mb, mu = ma * mb / M, d = ra + rb;
  for (int b = 0; b < 10; b++) {
    double sum = 0;
    for (int k = 0; k < 100000; k++) {
      double va[3], vb[3], gg = 0, Gg = 0;
      for (int q = 0; q < 3; q++) {
        va[q] = gsl_ran_gaussian(rng, sa);
        vb[q] = gsl_ran_gaussian(rng, sb);
        double g = va[q] - vb[q];
        gg += g * g;
        Gg += (ma * va[q] + mb * vb[q]) / M * g;
      }
      sum += PI * d * d * sqrt(gg) * (-mu * Gg);
    }
    x[b] = nb * sum / 1e5 / (1.5 * SB_BOLTZMANN) / rate;
  }
  check_replicas(x, 10, 1.0, "hard-sphere two-temperature rate");
  gsl_rng_free(rng);
}
END_TEST

static Suite *suite(void)
{
  Suite *s = suite_create("spray_mc");
  TCase *tc = tcase_create("mc");
  tcase_set_timeout(tc, 60);
  tcase_add_test(tc, test_bkw_m4);
  tcase_add_test(tc, test_orourke_coalescence);
  tcase_add_test(tc, test_bkw_sampler);
  tcase_add_test(tc, test_hs_frequency);
  tcase_add_test(tc, test_nanbu_martingale);
  tcase_add_test(tc, test_coalescence_constant);
  tcase_add_test(tc, test_two_temperature_maxwell);
  tcase_add_test(tc, test_two_temperature_hs_rate);
  suite_add_tcase(s, tc);
  return s;
}

int main(void) { return sbt_run_suite(suite()); }
