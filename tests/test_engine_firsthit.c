#define _POSIX_C_SOURCE 200809L
/* test_engine_firsthit.c — the first-contact observer
 * (smolbridge/engine_firsthit.h): each pair counted once, pairs in contact
 * at the start excluded, warm-up, per species pair counts, skip_seen, the
 * callback, the estimator against its formula, bad arguments, a Monte
 * Carlo run of diffusive spheres against the Smoluchowski (1917)
 * absorbing-sphere count with its start-up transient, and the variance of
 * the counts (hits_var) by hand and against the spread over 200 runs, and
 * a count that goes on from a saved state as if it had not stopped. */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <stdlib.h>
#include <unistd.h>

#include <gsl/gsl_cdf.h>
#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>

#include <smolbridge/engine.h>
#include <smolbridge/engine_bridge.h>
#include <smolbridge/engine_firsthit.h>
#include <smolbridge/langevin.h>
#include <smolbridge/stats.h>

#include "testutil.h"

#define PI 3.14159265358979323846

/* Free-flight engine (molecules: straight lines), cube of edge L. */
static sb_engine *flight_engine(double L, double dt, double r)
{
  sb_engine_params p;
  sb_engine_params_default(&p);
  p.L[0] = p.L[1] = p.L[2] = L;
  p.dt = dt;
  p.outcome = SB_OUTCOME_COUNT;
  sb_engine *e = sb_engine_alloc(&p);
  ck_assert_ptr_nonnull(e);
  sb_engine_species s = {r, 1e-15, INFINITY, 0.0, 300.0};
  ck_assert_int_eq(sb_engine_add_species(e, &s, NULL), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_add_species(e, &s, NULL), SB_SUCCESS);
  return e;
}

typedef struct {
  unsigned long calls, hits;
  double s;
} counter;

static int counting_ballistic(const sb_engine *e, const sb_engine_pair *p,
                              const gsl_rng *r, void *ctx, double *s)
{
  (void)e;
  (void)r;
  counter *c = ctx;
  c->calls++;
  return sb_engine_detect_ballistic(p, s);
}

static int on_hit(const sb_engine *e, const sb_engine_pair *p, double s,
                  void *ctx)
{
  (void)e;
  (void)p;
  counter *c = ctx;
  c->hits++;
  c->s = s;
  return 0;
}

/* A (moving along x at v) passes through B (at rest): one contact at
 * t = (gap) / v, however long the particles overlap; run for less than a
 * box crossing. */
static sb_engine *passing_pair(void)
{
  const double L = 1e-4, r = 1e-6, v = 1e-2;
  sb_engine *e = flight_engine(L, 1e-5, r);
  double xa[3] = {0.2 * L, 0.5 * L, 0.5 * L}, ua[3] = {v, 0, 0};
  double xb[3] = {0.5 * L, 0.5 * L, 0.5 * L}, ub[3] = {0, 0, 0};
  ck_assert_int_eq(sb_engine_add_particle(e, 0, 0, xa, ua), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_add_particle(e, 0, 0, xb, ub), SB_SUCCESS);
  return e;
}

START_TEST(test_pass_through_once)
{
  /* contact at t = (0.3 L - 2 r)/v = 2.8e-3 s; the overlap lasts 4r/v =
   * 4e-4 s (40 steps), all re-detected as contacts by the chords */
  unsigned long calls[2];
  for (int skip = 0; skip <= 1; skip++) {
    sb_engine *e = passing_pair();
    counter c = {0, 0, NAN};
    sb_engine_firsthit_params fp;
    sb_engine_firsthit_params_default(&fp);
    fp.detect = counting_ballistic;
    fp.detect_ctx = &c;
    fp.skip_seen = skip;
    fp.on_hit = on_hit;
    fp.hit_ctx = &c;
    sb_engine_firsthit *f = sb_engine_firsthit_alloc(&fp);
    ck_assert_ptr_nonnull(f);
    ck_assert_int_eq(sb_engine_firsthit_attach(e, f, 0.0), SB_SUCCESS);
    ck_assert_int_eq(sb_engine_firsthit_attach(e, f, 0.0), SB_EINVAL);
    ck_assert_int_eq(sb_engine_run_until(e, 5e-3), SB_SUCCESS);
    sb_engine_firsthit_counts k;
    ck_assert_int_eq(sb_engine_firsthit_get(f, 0, 0, &k), SB_SUCCESS);
    ck_assert_uint_eq(k.hits, 1);
    ck_assert_uint_eq(k.warm, 0);
    ck_assert_uint_eq(k.contact0, 0);
    ck_assert_rel(k.pairs_apart, 1.0, 0.0);
    ck_assert_uint_eq(c.hits, 1);
    ck_assert(c.s >= 0.0 && c.s <= 1.0);
    calls[skip] = c.calls;
    /* the engine itself counts nothing (pass-through) */
    sb_engine_stats es;
    sb_engine_get_stats(e, &es);
    ck_assert_uint_eq(es.ncoll, 0);
    sb_engine_firsthit_free(f);
    sb_engine_free(e);
  }
  /* the overlapping pair is a candidate at each of the ~40 steps of the
   * overlap: without skip_seen the detector sees them all */
  ck_assert_uint_ge(calls[0], calls[1] + 30);
}
END_TEST

START_TEST(test_warmup)
{
  sb_engine *e = passing_pair();
  sb_engine_firsthit_params fp;
  sb_engine_firsthit_params_default(&fp);
  sb_engine_firsthit *f = sb_engine_firsthit_alloc(&fp);
  ck_assert_int_eq(sb_engine_firsthit_set_warmup(f, 3e-3), SB_SUCCESS);
  ck_assert_rel(sb_engine_firsthit_warmup(f), 3e-3, 0.0);
  ck_assert_int_eq(sb_engine_firsthit_set_warmup(f, -1.0), SB_EINVAL);
  ck_assert_int_eq(sb_engine_firsthit_attach(e, f, 0.0), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_run_until(e, 5e-3), SB_SUCCESS);
  sb_engine_firsthit_counts k;
  ck_assert_int_eq(sb_engine_firsthit_get(f, SB_ENGINE_FIRSTHIT_ALL,
                                          SB_ENGINE_FIRSTHIT_ALL, &k),
                   SB_SUCCESS);
  ck_assert_uint_eq(k.hits, 0);
  ck_assert_uint_eq(k.warm, 1);
  sb_engine_firsthit_free(f);
  sb_engine_free(e);
}
END_TEST

/* Species pairs and pairs in contact at the start: one 0-0 pair and one
 * 0-1 pair overlap, the 1-1 pair is apart. */
START_TEST(test_species_and_contact0)
{
  const double L = 1e-4, r = 1e-6;
  sb_engine *e = flight_engine(L, 1e-5, r);
  double u[3] = {0, 0, 0};
  double x[5][3] = {{0.5 * L, 0.5 * L, 0.5 * L},
                    {0.5 * L + r, 0.5 * L, 0.5 * L},     /* 0: overlaps */
                    {0.5 * L - 1.5 * r, 0.5 * L, 0.5 * L}, /* 1: on 0 */
                    {0.1 * L, 0.1 * L, 0.1 * L},         /* 1: apart */
                    {0.999 * L, 0.5 * L, 0.5 * L}};      /* 0: periodic */
  const size_t sp[5] = {0, 0, 1, 1, 0};
  for (int i = 0; i < 5; i++)
    ck_assert_int_eq(sb_engine_add_particle(e, sp[i], 0, x[i], u),
                     SB_SUCCESS);
  /* particle 4 overlaps none (0.499 L from 0 across the boundary) */
  sb_engine_firsthit_params fp;
  sb_engine_firsthit_params_default(&fp);
  sb_engine_firsthit *f = sb_engine_firsthit_alloc(&fp);
  sb_engine_firsthit_counts k;
  ck_assert_int_eq(sb_engine_firsthit_get(f, 0, 0, &k), SB_EINVAL);
  ck_assert_int_eq(sb_engine_firsthit_attach(e, f, 0.0), SB_SUCCESS);
  /* 0-0: pairs (0,1) (0,4) (1,4), one in contact */
  ck_assert_int_eq(sb_engine_firsthit_get(f, 0, 0, &k), SB_SUCCESS);
  ck_assert_uint_eq(k.contact0, 1);
  ck_assert_rel(k.pairs_apart, 2.0, 0.0);
  /* 0-1: 3 x 2 pairs, (0,2) overlapping */
  ck_assert_int_eq(sb_engine_firsthit_get(f, 1, 0, &k), SB_SUCCESS);
  ck_assert_uint_eq(k.contact0, 1);
  ck_assert_rel(k.pairs_apart, 5.0, 0.0);
  ck_assert_int_eq(sb_engine_firsthit_get(f, 1, 1, &k), SB_SUCCESS);
  ck_assert_uint_eq(k.contact0, 0);
  ck_assert_rel(k.pairs_apart, 1.0, 0.0);
  /* a species without particles, and all pairs */
  ck_assert_int_eq(sb_engine_firsthit_get(f, 2, 5, &k), SB_SUCCESS);
  ck_assert_rel(k.pairs_apart, 0.0, 0.0);
  ck_assert_int_eq(sb_engine_firsthit_get(f, SB_ENGINE_FIRSTHIT_ALL,
                                          SB_ENGINE_FIRSTHIT_ALL, &k),
                   SB_SUCCESS);
  ck_assert_uint_eq(k.contact0, 2);
  ck_assert_rel(k.pairs_apart, 8.0, 0.0);
  ck_assert_int_eq(sb_engine_firsthit_get(f, SB_ENGINE_PAIR_SPECIES, 0, &k),
                   SB_EINVAL);
  sb_engine_firsthit_free(f);
  sb_engine_free(e);
}
END_TEST

START_TEST(test_kernel_formula_and_errors)
{
  sb_engine *e = passing_pair();
  sb_engine_firsthit_params fp;
  sb_engine_firsthit_params_default(&fp);
  fp.builtin = SB_DETECT_CUSTOM;
  ck_assert_ptr_null(sb_engine_firsthit_alloc(&fp));
  ck_assert_ptr_null(sb_engine_firsthit_alloc(NULL));
  fp.builtin = SB_DETECT_OVERLAP;
  sb_engine_firsthit *f = sb_engine_firsthit_alloc(&fp);
  ck_assert_int_eq(sb_engine_firsthit_set_warmup(f, 1e-3), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_firsthit_attach(e, f, 0.0), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_run_until(e, 5e-3), SB_SUCCESS);
  const double a = 1.5e-6, D = 2e-12, L = 1e-4, R = 2e-6;
  sb_engine_firsthit_kernel_result k;
  ck_assert_int_eq(sb_engine_firsthit_kernel(f, e, 0, 0, a, D, 0.95, &k),
                   SB_SUCCESS);
  const double T = sb_engine_time(e), t1 = 1e-3;
  const double teff = (T - t1) + 2 * a * (sqrt(T) - sqrt(t1)) / sqrt(PI * D);
  const double want = 1.0 * teff / (L * L * L - 4 * PI * R * R * R / 3);
  ck_assert_uint_eq(k.c.hits, 1);
  ck_assert_rel(k.expected_per_K, want, TOL_TIGHT);
  ck_assert_rel(k.K, 1.0 / want, TOL_TIGHT);
  ck_assert(k.lo < k.K && k.K < k.hi);
  ck_assert_rel(k.t, T, 0.0);
  double c1, c2;
  ck_assert_int_eq(sb_engine_firsthit_coefs(&k, &c1, &c2), SB_SUCCESS);
  ck_assert_rel(c1, want, TOL_TIGHT);
  ck_assert_rel(c2, 0.0, 0.0);
  /* the capacitance radius: E[hits] = c (K (T - t1) + K^2 2 (sqrt T -
   * sqrt t1) / (4 pi D sqrt(pi D))) = 1 solved for K */
  ck_assert_int_eq(sb_engine_firsthit_kernel(f, e, 0, 0,
                                             SB_ENGINE_FIRSTHIT_CAPACITANCE,
                                             D, 0.95, &k),
                   SB_SUCCESS);
  const double cc = 1.0 / (L * L * L - 4 * PI * R * R * R / 3);
  const double q1 = cc * (T - t1);
  const double q2 = cc * 2 * (sqrt(T) - sqrt(t1)) / (4 * PI * D * sqrt(PI * D));
  const double Kq = (-q1 + sqrt(q1 * q1 + 4 * q2)) / (2 * q2);
  ck_assert_rel(k.K, Kq, 1e-9);  /* the textbook root cancels */
  ck_assert_rel(q1 * k.K + q2 * k.K * k.K, 1.0, 1e-12);
  ck_assert_rel(k.a, k.K / (4 * PI * D), TOL_TIGHT);
  ck_assert(k.lo < k.K && k.K < k.hi);
  ck_assert_int_eq(sb_engine_firsthit_coefs(&k, &c1, &c2), SB_SUCCESS);
  ck_assert_rel(c1, q1, TOL_TIGHT);
  ck_assert_rel(c2, q2, TOL_TIGHT);
  /* the estimator alone, from kept inputs, gives the same */
  sb_engine_firsthit_kernel_result k2 = k;
  k2.K = k2.lo = k2.hi = 0.0;
  ck_assert_int_eq(sb_engine_firsthit_estimate(&k2, 0.95), SB_SUCCESS);
  ck_assert_rel(k2.K, k.K, 0.0);
  ck_assert_rel(k2.hi, k.hi, 0.0);
  /* bad arguments: the counts are still set, K is NaN */
  ck_assert_int_eq(sb_engine_firsthit_kernel(f, e, 0, 0, -1.0, D, 0.95, &k),
                   SB_EINVAL);
  ck_assert(isnan(k.K));
  ck_assert_uint_eq(k.c.hits, 1);
  ck_assert_int_eq(sb_engine_firsthit_kernel(f, e, 0, 0, a, NAN, 0.95, &k),
                   SB_EINVAL);
  ck_assert_int_eq(sb_engine_firsthit_kernel(f, e, 0, 0, a, D, 1.0, &k),
                   SB_EINVAL);
  ck_assert_int_eq(sb_engine_firsthit_kernel(f, e, 0, 2, a, D, 0.95, &k),
                   SB_EINVAL);
  /* species pair 1-1 has no pair: no exposure */
  ck_assert_int_eq(sb_engine_firsthit_kernel(f, e, 1, 1, a, D, 0.95, &k),
                   SB_EDOM);
  ck_assert(isnan(k.K));
  sb_engine_firsthit_free(f);
  sb_engine_free(e);

  /* 2-D: no reference */
  sb_engine_params p;
  sb_engine_params_default(&p);
  p.dim = 2;
  p.outcome = SB_OUTCOME_COUNT;
  e = sb_engine_alloc(&p);
  sb_engine_species s = {1e-6, 1e-15, INFINITY, 0.0, 300.0};
  ck_assert_int_eq(sb_engine_add_species(e, &s, NULL), SB_SUCCESS);
  f = sb_engine_firsthit_alloc(&fp);
  ck_assert_int_eq(sb_engine_firsthit_attach(e, f, 0.0), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_firsthit_kernel(f, e, 0, 0, a, D, 0.95, &k),
                   SB_EINVAL);
  sb_engine_firsthit_free(f);
  sb_engine_free(e);
}
END_TEST

/* Diffusive spheres (dt = 1000 tau_p, b2 = B_pos^2 per particle: the
 * relative diffusivity is D = b2) placed independently and uniformly,
 * detected by the Bessel-3 bridge (Mohaupt 2011, ch. 5): the first-contact
 * kernel is K = 4 pi D d with radius a = d.  N = 600, 300 steps, seed 7,
 * box edge 10 relative displacement standard deviations; about 4500
 * counted contacts (the start-up transient makes 2/3 of them); pass: K in
 * the exact 99.9% Garwood interval of the count.  Without the transient
 * term the estimate would be ~3 K. */
START_TEST(test_mc_smoluchowski)
{
  const double d = 1e-6, b2 = 1e-12, tau = 1e-6, dt = 1e-3;
  const size_t N = 600;
  const double T = 300 * dt, L = 10.0 * sqrt(2.0 * b2 * T);
  sb_engine_params p;
  sb_engine_params_default(&p);
  p.L[0] = p.L[1] = p.L[2] = L;
  p.dt = dt;
  p.capacity = N;
  p.seed = 7;
  p.outcome = SB_OUTCOME_COUNT;
  sb_engine *e = sb_engine_alloc(&p);
  sb_engine_species s = {0.5 * d, 1e-15, tau, sqrt(b2) / tau, 0.0};
  ck_assert_int_eq(sb_engine_add_species(e, &s, NULL), SB_SUCCESS);
  gsl_rng *g = gsl_rng_alloc(gsl_rng_taus2);
  gsl_rng_set(g, 7);
  for (size_t i = 0; i < N; i++) {
    double x[3], u[3] = {0, 0, 0};
    for (int k = 0; k < 3; k++)
      x[k] = L * gsl_rng_uniform(g);
    ck_assert_int_eq(sb_engine_add_particle(e, 0, 0, x, u), SB_SUCCESS);
  }
  gsl_rng_free(g);
  sb_engine_bridge_params bp;
  sb_engine_bridge_params_default(&bp);
  bp.outcome = SB_BRIDGE_OUT_COUNT;
  sb_engine_bridge *b = sb_engine_bridge_alloc(&bp);
  ck_assert_int_eq(sb_engine_bridge_set_b2(b, 0, b2, b2), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_bridge_attach(e, b), SB_SUCCESS);
  sb_engine_firsthit_params fp;
  sb_engine_firsthit_params_default(&fp);
  fp.detect = sb_engine_detect_bridge;
  fp.detect_ctx = b;
  sb_engine_firsthit *f = sb_engine_firsthit_alloc(&fp);
  ck_assert_int_eq(
      sb_engine_firsthit_attach(e, f, sb_engine_bridge_reach(e, b)),
      SB_SUCCESS);
  ck_assert_int_eq(sb_engine_run_until(e, T), SB_SUCCESS);
  sb_engine_firsthit_kernel_result k;
  ck_assert_int_eq(sb_engine_firsthit_kernel(f, e, 0, 0, d, b2, 0.999, &k),
                   SB_SUCCESS);
  const double Kth = 4.0 * PI * b2 * d;
  ck_assert_uint_gt(k.c.hits, 2000);
  ck_assert_msg(k.lo <= Kth && Kth <= k.hi,
                "K = %g [%g, %g] (%llu hits), K_th = %g", k.K, k.lo, k.hi,
                (unsigned long long)k.c.hits, Kth);
  sb_engine_firsthit_free(f);
  sb_engine_bridge_free(b);
  sb_engine_free(e);
}
END_TEST


/* One free-flight first-contact run (ballistic detector) of N molecules
 * of radius r with Maxwellian velocities (unit variance), in a cube of
 * edge L for `steps` steps of dt; its counts. */
static sb_engine_firsthit_counts flight_run(size_t N, double L, double r,
                                            double dt, int steps,
                                            unsigned long seed)
{
  sb_engine *e = flight_engine(L, dt, r);
  gsl_rng *g = gsl_rng_alloc(gsl_rng_taus2);
  gsl_rng_set(g, seed);
  for (size_t i = 0; i < N; i++) {
    double x[3], u[3];
    for (int k = 0; k < 3; k++) {
      x[k] = L * gsl_rng_uniform(g);
      u[k] = gsl_ran_gaussian_ziggurat(g, 1.0);
    }
    ck_assert_int_eq(sb_engine_add_particle(e, 0, 0, x, u), SB_SUCCESS);
  }
  gsl_rng_free(g);
  sb_engine_firsthit_params fp;
  sb_engine_firsthit_params_default(&fp);
  sb_engine_firsthit *f = sb_engine_firsthit_alloc(&fp);
  ck_assert_int_eq(sb_engine_firsthit_attach(e, f, 0.0), SB_SUCCESS);
  for (int k = 0; k < steps; k++)
    ck_assert_int_eq(sb_engine_step(e), SB_SUCCESS);
  sb_engine_firsthit_counts c;
  ck_assert_int_eq(sb_engine_firsthit_get(f, 0, 0, &c), SB_SUCCESS);
  sb_engine_firsthit_free(f);
  sb_engine_free(e);
  return c;
}

/* hits_var by hand: molecule A (species 0) runs along x through three
 * resting molecules of species 1; molecule C (species 0) and a fourth of
 * species 1 rest off the line.  Species pair (0, 1): 3 hits; counts 3 and
 * 0 on one side, 1, 1, 1, 0 on the other; 8 pairs:
 * [(9 - 9/2) + (3 - 9/4) - 3 + 9/8] / (1 - 1/2 - 1/4 + 1/8)
 * = 3.375 / 0.375 = 9 (sb_pair_count_variance). */
START_TEST(test_variance_by_hand)
{
  const double L = 1e-4, r = 1e-6, v = 1e-2;
  sb_engine *e = flight_engine(L, 1e-5, r);
  const double y = 0.5 * L, z = 0.5 * L;
  double xa[3] = {0.1 * L, y, z}, ua[3] = {v, 0, 0}, u0[3] = {0, 0, 0};
  double xc[3] = {0.5 * L, 0.1 * L, z};
  ck_assert_int_eq(sb_engine_add_particle(e, 0, 0, xa, ua), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_add_particle(e, 0, 0, xc, u0), SB_SUCCESS);
  for (int k = 0; k < 4; k++) {
    double xb[3] = {(0.3 + 0.2 * k) * L, k < 3 ? y : 0.8 * L, z};
    ck_assert_int_eq(sb_engine_add_particle(e, 1, 0, xb, u0), SB_SUCCESS);
  }
  sb_engine_firsthit_params fp;
  sb_engine_firsthit_params_default(&fp);
  sb_engine_firsthit *f = sb_engine_firsthit_alloc(&fp);
  ck_assert_int_eq(sb_engine_firsthit_attach(e, f, 0.0), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_run_until(e, 0.7 * L / v), SB_SUCCESS);
  sb_engine_firsthit_counts c;
  ck_assert_int_eq(sb_engine_firsthit_get(f, 1, 0, &c), SB_SUCCESS);
  ck_assert_uint_eq(c.hits, 3);
  ck_assert_rel(c.hits_var, 9.0, 1e-14);
  ck_assert_int_eq(sb_engine_firsthit_get(f, 0, 0, &c), SB_SUCCESS);
  ck_assert_uint_eq(c.hits, 0);
  ck_assert_rel(c.hits_var, 0.0, 0.0);
  /* two species pooled: not one population of pairs */
  ck_assert_int_eq(sb_engine_firsthit_get(f, SB_ENGINE_FIRSTHIT_ALL,
                                          SB_ENGINE_FIRSTHIT_ALL, &c),
                   SB_SUCCESS);
  ck_assert(isnan(c.hits_var));
  /* the estimator: the Garwood interval widened by sqrt(9 / 3) */
  sb_engine_firsthit_kernel_result k;
  ck_assert_int_eq(sb_engine_firsthit_kernel(f, e, 0, 1, 2 * r, 1e-9, 0.95,
                                             &k), SB_SUCCESS);
  ck_assert_rel(k.dispersion, 3.0, 1e-14);
  double lo, hi;
  ck_assert_int_eq(sb_poisson_ci(3, 0.95, &lo, &hi), SB_SUCCESS);
  const double w = sqrt(3.0);
  /* (3 - w (3 - lo) < 0: the lower end clipped at 0) */
  ck_assert(3.0 - w * (3.0 - lo) < 0.0 && k.lo == 0.0);
  ck_assert_rel(k.hi * k.expected_per_K, 3.0 + w * (hi - 3.0), 1e-14);
  sb_engine_firsthit_free(f);
  sb_engine_free(e);
}
END_TEST

/* hits_var against the spread of hits over 200 independent free-flight
 * runs (200 Maxwellian molecules, ~2100 first contacts, ~21 per
 * molecule): a fast molecule meets more partners, so var(hits) is ~2.4
 * times the mean.  Criterion: (R - 1) s^2 / v, with v the mean of the
 * runs' hits_var (its own spread is small: 200 runs), inside the central
 * 99.9% of chi^2 with R - 1 degrees of freedom; and the Poisson value (the
 * mean) outside it, so the test sees the difference (it fails with
 * hits_var = hits).  Then the estimator's interval: its half-width is
 * sqrt(dispersion) times the Garwood one. */
START_TEST(test_mc_variance)
{
  const int R = 200;
  double sh = 0.0, sh2 = 0.0, sv = 0.0;
  for (int r = 0; r < R; r++) {
    sb_engine_firsthit_counts c =
        flight_run(200, 1e-4, 2e-6, 1e-6, 1000, 1000 + (unsigned long)r);
    const double h = (double)c.hits;
    sh += h;
    sh2 += h * h;
    sv += c.hits_var;
  }
  const double mean = sh / R, s2 = (sh2 - R * mean * mean) / (R - 1),
               v = sv / R;
  const double qlo = gsl_cdf_chisq_Pinv(0.0005, R - 1),
               qhi = gsl_cdf_chisq_Qinv(0.0005, R - 1);
  const double x = (R - 1) * s2 / v, xp = (R - 1) * s2 / mean;
  ck_assert_msg(qlo <= x && x <= qhi, "var %g, estimate %g (mean %g)", s2,
                v, mean);
  ck_assert_msg(xp > qhi, "var %g: not above the Poisson value %g", s2,
                mean);
  /* one run's interval */
  sb_engine_firsthit_counts c = flight_run(200, 1e-4, 2e-6, 1e-6, 1000, 7);
  sb_engine_firsthit_kernel_result k;
  memset(&k, 0, sizeof k);
  k.c = c;
  k.radius = 4e-6;
  k.D = 1e-6;
  k.t1 = 0.0;
  k.t = 1e-3;
  k.veff = 1e-12;
  ck_assert_int_eq(sb_engine_firsthit_estimate(&k, 0.95), SB_SUCCESS);
  ck_assert(k.dispersion > 1.5);
  double lo, hi;
  ck_assert_int_eq(sb_poisson_ci(c.hits, 0.95, &lo, &hi), SB_SUCCESS);
  const double H = (double)c.hits, w = sqrt(k.dispersion);
  ck_assert_rel(k.lo * k.expected_per_K, H - w * (H - lo), 1e-12);
  ck_assert_rel(k.hi * k.expected_per_K, H + w * (hi - H), 1e-12);
}
END_TEST

/* Around the built-in `langevin` the observer watches the built-in itself
 * (sbi_engine_set_observer): its first pass runs on the threads
 * with the engine's streams, and on_hit reads the contact state.  1500
 * Langevin spheres (r = 0.5, tau = 0.35, dt = 0.7: several hundred
 * records per step), 12 steps, warm-up 3 steps, skip_seen on.
 * (1) On 1 and 2 threads: the same counts, warm-ups and variance
 * estimate, and the same sequence of contacts bit for bit (a running
 * hash of the on_hit calls in order: their times, normal velocities and
 * separations; an observer fed out of record order fails it).
 * (2) The contact state in on_hit: |x_i - x_j| = r_i + r_j.
 * (3) With the streams off (the engine's generator in record order) the
 * observed built-in is the wrapped one (fp.detect =
 * sb_engine_detect_langevin, the search declared with
 * sb_engine_set_detector_chord, as V12's harness does): the same counts
 * and the same contact times in the same order.  Criterion: equality. */
typedef struct {
  int states;     /* read the contact state */
  size_t n;
  double hash;    /* running combination of the calls, order-sensitive */
  double maxsep;  /* largest | |x_i - x_j| / (r_i + r_j) - 1 | */
} observed;

static int observe_hit(const sb_engine *e, const sb_engine_pair *p,
                       double s, void *ctx)
{
  observed *o = ctx;
  double v = p->t0 + s * p->dt;
  if (o->states) {
    double xi[3], ui[3], xj[3], uj[3], d2 = 0.0, vn = 0.0;
    if (sb_engine_contact_state(e, xi, ui, xj, uj))
      return -1;
    for (int k = 0; k < 3; k++) {
      d2 += (xi[k] - xj[k]) * (xi[k] - xj[k]);
      vn += (ui[k] - uj[k]) * (xi[k] - xj[k]);
    }
    const double dev = fabs(sqrt(d2) / p->sigma - 1.0);
    o->maxsep = dev > o->maxsep ? dev : o->maxsep;
    v += 1e-3 * vn;
  }
  o->hash = 1.000001 * o->hash + v + 1e-9 * (double)(p->i + 7 * p->j);
  o->n++;
  return 0;
}

/* 1500 Kn_D ~ 0.5 spheres (r = 0.5, m = 1, tau = 0.35, k_B T = 1) in a
 * cube of 30 at dt = 2 tau, `langevin`, pass-through, on `threads`
 * threads (0: the default) with the streams on or off. */
static sb_engine *kn_engine(unsigned long seed, int threads, int streams)
{
  sb_engine_params p;
  sb_engine_params_default(&p);
  p.L[0] = p.L[1] = p.L[2] = 30.0;
  p.dt = 0.7;
  p.capacity = 1500;
  p.seed = seed;
  if (threads)
    p.threads = threads;
  p.streams = streams;
  p.detect = SB_DETECT_LANGEVIN;
  p.outcome = SB_OUTCOME_COUNT;
  sb_engine *e = sb_engine_alloc(&p);
  ck_assert_ptr_nonnull(e);
  sb_engine_species sp = {0.5, 1.0, 0.35, sqrt(2.0 / 0.35),
                          1.0 / SB_BOLTZMANN};
  ck_assert_int_eq(sb_engine_add_species(e, &sp, NULL), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_fill_random(e, 0, 0, 1500), SB_SUCCESS);
  return e;
}

static sb_engine_firsthit_counts observed_run(sb_engine_detect builtin,
                                              int threads, int streams,
                                              int wrapped, observed *o)
{
  sb_engine *e = kn_engine(41, threads, streams);
  sb_engine_firsthit_params fp;
  sb_engine_firsthit_params_default(&fp);
  counter calls = {0, 0, 0.0};
  fp.builtin = builtin;
  if (wrapped && builtin == SB_DETECT_LANGEVIN)
    fp.detect = sb_engine_detect_langevin;
  else if (wrapped) {
    fp.detect = counting_ballistic;
    fp.detect_ctx = &calls;
  }
  fp.skip_seen = 1;
  fp.on_hit = observe_hit;
  fp.hit_ctx = o;
  sb_engine_firsthit *f = sb_engine_firsthit_alloc(&fp);
  ck_assert_ptr_nonnull(f);
  const double rho =
      builtin == SB_DETECT_LANGEVIN ? sb_engine_langevin_reach(e) : 0.0;
  ck_assert(rho > 0.0 || builtin != SB_DETECT_LANGEVIN);
  ck_assert_int_eq(sb_engine_firsthit_set_warmup(f, 3 * 0.7), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_firsthit_attach(e, f, rho), SB_SUCCESS);
  if (wrapped && builtin == SB_DETECT_LANGEVIN)
    ck_assert_int_eq(sb_engine_set_detector_chord(e, 1), SB_SUCCESS);
  else if (!wrapped)  /* the built-in itself, observed */
    ck_assert_int_eq(sb_engine_get_params(e)->detect, builtin);
  for (int k = 0; k < 12; k++)
    ck_assert_msg(sb_engine_step(e) == SB_SUCCESS, "%s", sb_last_error());
  sb_engine_firsthit_counts c;
  ck_assert_int_eq(sb_engine_firsthit_get(f, SB_ENGINE_FIRSTHIT_ALL,
                                          SB_ENGINE_FIRSTHIT_ALL, &c),
                   SB_SUCCESS);
  sb_engine_stats st;
  sb_engine_get_stats(e, &st);
  ck_assert_uint_eq(st.ncoll, 0);  /* the particles pass through */
  if (builtin != SB_DETECT_LANGEVIN)  /* enough for the parallel pass */
    ck_assert_uint_gt(st.ncand, 12 * 256);
  sb_engine_free(e);
  sb_engine_firsthit_free(f);
  return c;
}

START_TEST(test_langevin_observed)
{
  observed o[2] = {{1, 0, 0.0, 0.0}, {1, 0, 0.0, 0.0}};
  sb_engine_firsthit_counts c[2];
  for (int t = 0; t < 2; t++)
    c[t] = observed_run(SB_DETECT_LANGEVIN, t + 1, 1, 0, &o[t]);
  printf("observed langevin, 1 / 2 threads: %llu / %llu first contacts "
         "(%llu / %llu in the warm-up), largest |d/sigma - 1| %.1e\n",
         (unsigned long long)c[0].hits, (unsigned long long)c[1].hits,
         (unsigned long long)c[0].warm, (unsigned long long)c[1].warm,
         o[0].maxsep);
  ck_assert_uint_gt(c[0].hits, 300);
  ck_assert_uint_gt(c[0].warm, 100);
  ck_assert_uint_eq(c[0].hits, c[1].hits);
  ck_assert_uint_eq(c[0].warm, c[1].warm);
  ck_assert(c[0].hits_var == c[1].hits_var);
  ck_assert_uint_eq(o[0].n, c[0].hits);
  ck_assert(o[0].hash == o[1].hash);
  ck_assert(o[0].maxsep < 1e-9 && o[1].maxsep < 1e-9);
  /* streams off: observed = wrapped (times only: the wrapped detector
   * has no contact state to read) */
  observed w[2] = {{0, 0, 0.0, 0.0}, {0, 0, 0.0, 0.0}};
  for (int t = 0; t < 2; t++)
    c[t] = observed_run(SB_DETECT_LANGEVIN, 1, 0, t, &w[t]);
  ck_assert_uint_gt(c[0].hits, 300);
  ck_assert_uint_eq(c[0].hits, c[1].hits);
  ck_assert_uint_eq(c[0].warm, c[1].warm);
  ck_assert(w[0].hash == w[1].hash);
}
END_TEST

/* The same for the built-in contact-time detector (`ballistic`, no
 * draws): observed, on 1 and 2 threads (its parallel first pass), the
 * same counts and contacts in the same order; observed and wrapped (a
 * custom detector around sb_engine_detect_ballistic, searched by the
 * cells where the built-in takes its Verlet list, so in another order)
 * the same counts and variance estimate. */
START_TEST(test_ballistic_observed)
{
  observed o[3] = {{0, 0, 0.0, 0.0}, {0, 0, 0.0, 0.0}, {0, 0, 0.0, 0.0}};
  sb_engine_firsthit_counts c[3];
  for (int t = 0; t < 2; t++)
    c[t] = observed_run(SB_DETECT_BALLISTIC, t + 1, 1, 0, &o[t]);
  c[2] = observed_run(SB_DETECT_BALLISTIC, 1, 1, 1, &o[2]);
  printf("observed ballistic, 1 / 2 threads / wrapped: %llu / %llu / %llu "
         "first contacts\n", (unsigned long long)c[0].hits,
         (unsigned long long)c[1].hits, (unsigned long long)c[2].hits);
  ck_assert_uint_gt(c[0].hits, 300);
  for (int t = 1; t < 3; t++) {
    ck_assert_uint_eq(c[0].hits, c[t].hits);
    ck_assert_uint_eq(c[0].warm, c[t].warm);
    ck_assert(c[0].hits_var == c[t].hits_var);
  }
  ck_assert(o[0].hash == o[1].hash);
}
END_TEST

/* An observer (skip_seen, on_hit into o) around the built-in `langevin`
 * of kn_engine, loaded from `saved` unless that is NULL. */
static sb_engine_firsthit *restart_observer(observed *o, int skip_seen,
                                            const char *saved, int *st)
{
  sb_engine_firsthit_params fp;
  sb_engine_firsthit_params_default(&fp);
  fp.builtin = SB_DETECT_LANGEVIN;
  fp.skip_seen = skip_seen;
  fp.on_hit = observe_hit;
  fp.hit_ctx = o;
  sb_engine_firsthit *f = sb_engine_firsthit_alloc(&fp);
  ck_assert_ptr_nonnull(f);
  *st = saved ? sb_engine_firsthit_load(f, saved) : SB_SUCCESS;
  return f;
}

static void steps(sb_engine *e, int n)
{
  for (int k = 0; k < n; k++)
    ck_assert_msg(sb_engine_step(e) == SB_SUCCESS, "%s", sb_last_error());
}

/* sbt_load_fn: a state loaded into a new observer around `langevin`
 * (skip_seen *ctx, 0 for NULL). */
static int load_observer(const char *path, void *ctx)
{
  observed z = {0, 0, 0.0, 0.0};
  int st;
  sb_engine_firsthit *f =
      restart_observer(&z, ctx ? *(const int *)ctx : 0, path, &st);
  if (st == SB_EFORMAT)
    ck_assert_ptr_nonnull(strstr(sb_last_error(), path));
  sb_engine_firsthit_free(f);
  return st;
}

/* A run stopped after 6 steps, saved (engine checkpoint and observer),
 * restored and run 6 more is the 12-step run: the same counts, warm-up
 * counts, variance estimate, kernel estimate, and the same contacts in
 * the same order (the order-sensitive hash of on_hit goes on across the
 * restart).  Then the errors: a state loaded into an attached observer,
 * or into one around another detector or skip_seen; an engine at another
 * step, or at the same step of another run; files that are not observer files, truncated or with data after
 * the end; saving an observer not attached. */
START_TEST(test_save_load)
{
  char dir[] = "/tmp/sb_firsthit_XXXXXX";
  ck_assert_ptr_nonnull(mkdtemp(dir));
  char ck[64], fh[64], bad[64];
  snprintf(ck, sizeof ck, "%s/engine.ck", dir);
  snprintf(fh, sizeof fh, "%s/engine.ck.firsthit", dir);
  snprintf(bad, sizeof bad, "%s/bad", dir);
  for (int skip_seen = 0; skip_seen < 2; skip_seen++) {
    observed o[2] = {{1, 0, 0.0, 0.0}, {1, 0, 0.0, 0.0}};
    int st;
    /* straight */
    sb_engine *e = kn_engine(43, 0, 1);
    sb_engine_firsthit *f = restart_observer(&o[0], skip_seen, NULL, &st);
    ck_assert_int_eq(sb_engine_firsthit_save(f, e, fh), SB_EINVAL);
    ck_assert_int_eq(sb_engine_firsthit_set_warmup(f, 3 * 0.7), SB_SUCCESS);
    ck_assert_int_eq(sb_engine_firsthit_attach(e, f, 0.0), SB_SUCCESS);
    steps(e, 12);
    sb_engine_firsthit_kernel_result k[2];
    ck_assert_int_eq(sb_engine_firsthit_kernel(
                         f, e, 0, 0, SB_ENGINE_FIRSTHIT_CAPACITANCE,
                         2.0 * 1.0 * 0.35, 0.95, &k[0]),
                     SB_SUCCESS);
    sb_engine_firsthit_counts all[2];
    ck_assert_int_eq(sb_engine_firsthit_get(f, SB_ENGINE_FIRSTHIT_ALL,
                                            SB_ENGINE_FIRSTHIT_ALL, &all[0]),
                     SB_SUCCESS);
    sb_engine_free(e);
    sb_engine_firsthit_free(f);
    /* stopped at step 6, saved, restored */
    e = kn_engine(43, 0, 1);
    f = restart_observer(&o[1], skip_seen, NULL, &st);
    ck_assert_int_eq(sb_engine_firsthit_set_warmup(f, 3 * 0.7), SB_SUCCESS);
    ck_assert_int_eq(sb_engine_firsthit_attach(e, f, 0.0), SB_SUCCESS);
    /* saved before any counted contact (empty tables): it loads */
    ck_assert_int_eq(sb_engine_firsthit_save(f, e, fh), SB_SUCCESS);
    observed y = {0, 0, 0.0, 0.0};
    sb_engine_firsthit *g = restart_observer(&y, skip_seen, fh, &st);
    ck_assert_msg(st == SB_SUCCESS, "%s", sb_last_error());
    sb_engine_firsthit_free(g);
    steps(e, 6);
    ck_assert_int_eq(sb_engine_checkpoint_save(e, ck), SB_SUCCESS);
    ck_assert_int_eq(sb_engine_firsthit_save(f, e, fh), SB_SUCCESS);
    ck_assert_int_eq(sb_engine_firsthit_load(f, fh), SB_EINVAL);  /* attached */
    sb_engine_free(e);
    sb_engine_firsthit_free(f);
    e = sb_engine_checkpoint_load(ck, &st);
    ck_assert_int_eq(st, SB_SUCCESS);
    f = restart_observer(&o[1], skip_seen, fh, &st);
    ck_assert_msg(st == SB_SUCCESS, "%s", sb_last_error());
    ck_assert_int_eq(sb_engine_firsthit_attach(e, f, 0.0), SB_SUCCESS);
    steps(e, 6);
    ck_assert_int_eq(sb_engine_firsthit_kernel(
                         f, e, 0, 0, SB_ENGINE_FIRSTHIT_CAPACITANCE,
                         2.0 * 1.0 * 0.35, 0.95, &k[1]),
                     SB_SUCCESS);
    ck_assert_int_eq(sb_engine_firsthit_get(f, SB_ENGINE_FIRSTHIT_ALL,
                                            SB_ENGINE_FIRSTHIT_ALL, &all[1]),
                     SB_SUCCESS);
    ck_assert(all[0].hits == all[1].hits && all[0].hits_var == all[1].hits_var);
    ck_assert(all[0].hits_var > 0.0);
    printf("save/load, skip_seen = %d: %llu / %llu first contacts "
           "(%llu / %llu in the warm-up), K %.6g / %.6g\n", skip_seen,
           (unsigned long long)k[0].c.hits, (unsigned long long)k[1].c.hits,
           (unsigned long long)k[0].c.warm, (unsigned long long)k[1].c.warm,
           k[0].K, k[1].K);
    ck_assert_uint_gt(k[0].c.hits, 300);
    ck_assert_uint_eq(k[0].c.hits, k[1].c.hits);
    ck_assert_uint_eq(k[0].c.warm, k[1].c.warm);
    ck_assert_uint_eq(k[0].c.contact0, k[1].c.contact0);
    ck_assert(k[0].c.pairs_apart == k[1].c.pairs_apart);
    ck_assert(k[0].c.hits_var == k[1].c.hits_var);
    ck_assert(k[0].K == k[1].K && k[0].lo == k[1].lo && k[0].hi == k[1].hi);
    ck_assert_uint_eq(o[0].n, o[1].n);
    ck_assert(o[0].hash == o[1].hash);
    /* the errors */
    sb_engine_firsthit_free(f);
    observed z = {0, 0, 0.0, 0.0};
    f = restart_observer(&z, !skip_seen, fh, &st);
    ck_assert_int_eq(st, SB_EINVAL);
    ck_assert_ptr_nonnull(strstr(sb_last_error(), "skip_seen"));
    sb_engine_firsthit_free(f);
    f = restart_observer(&z, skip_seen, fh, &st);
    ck_assert_int_eq(st, SB_SUCCESS);
    ck_assert_int_eq(sb_engine_firsthit_attach(e, f, 0.0), SB_EINVAL);
    ck_assert_ptr_nonnull(strstr(sb_last_error(), "step 6"));
    sb_engine_firsthit_free(f);
    sb_engine_free(e);
    e = kn_engine(44, 0, 1);  /* another run at the same step */
    steps(e, 6);
    f = restart_observer(&z, skip_seen, fh, &st);
    ck_assert_int_eq(st, SB_SUCCESS);
    ck_assert_int_eq(sb_engine_firsthit_attach(e, f, 0.0), SB_EINVAL);
    ck_assert_ptr_nonnull(strstr(sb_last_error(), "other particles"));
    sb_engine_firsthit_free(f);
    sb_engine_free(e);
  }
  sb_engine_firsthit_params fp;
  sb_engine_firsthit_params_default(&fp);  /* ballistic */
  sb_engine_firsthit *f = sb_engine_firsthit_alloc(&fp);
  ck_assert_int_eq(sb_engine_firsthit_load(f, fh), SB_EINVAL);
  ck_assert_ptr_nonnull(strstr(sb_last_error(), "langevin"));
  sb_engine_firsthit_free(f);
  /* not observer files, truncated, trailing data, missing */
  sbt_damaged_copies(fh, bad, 100, "SBENGCK5", load_observer, NULL);
  /* a flipped byte; the format without the hash (version 01) */
  int skip_seen = 1;  /* the last save's */
  sbt_hash_checked(fh, bad, "01", load_observer, &skip_seen);
  remove(ck);
  remove(fh);
  rmdir(dir);
}
END_TEST

static Suite *suite(void)
{
  Suite *s = suite_create("engine_firsthit");
  TCase *tc = tcase_create("core");
  tcase_set_timeout(tc, 60);
  tcase_add_test(tc, test_pass_through_once);
  tcase_add_test(tc, test_warmup);
  tcase_add_test(tc, test_species_and_contact0);
  tcase_add_test(tc, test_kernel_formula_and_errors);
  tcase_add_test(tc, test_mc_smoluchowski);
  tcase_add_test(tc, test_variance_by_hand);
  tcase_add_test(tc, test_mc_variance);
  tcase_add_test(tc, test_langevin_observed);
  tcase_add_test(tc, test_ballistic_observed);
  tcase_add_test(tc, test_save_load);
  suite_add_tcase(s, tc);
  return s;
}

int main(void) { return sbt_run_suite(suite()); }
