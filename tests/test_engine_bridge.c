/* test_engine_bridge.c — Bessel-3 bridge detection for the engine
 * (lib/engine/engine_bridge.c): tail bound and reach, detector probabilities and
 * hit times, periodic end points, barycentre place, correction step. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <check.h>
#include <gsl/gsl_integration.h>
#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>
#include <gsl/gsl_sf_erf.h>

#include <smolbridge/bridge.h>
#include <smolbridge/engine.h>
#include <smolbridge/engine_bridge.h>
#include <smolbridge/langevin.h>
#include <smolbridge/stats.h>

#include "engine_same.h"
#include "testutil.h"

#define PI 3.14159265358979323846

/* ------------------------------------------------ tail bound vs quadrature */

typedef struct {
  double n, a, v, rho;
} bq;

/* In z = (x - a)/sqrt(v): n 4 pi x^2 (a/x) erfc((x - a)/sqrt(2 v)) dx */
static double bound1_integrand(double z, void *p)
{
  const bq *q = p;
  double sv = sqrt(q->v), x = q->a + z * sv;
  return q->n * 4.0 * PI * x * q->a * gsl_sf_erfc(z / sqrt(2.0)) * sv;
}

/* second bound, n 4 pi x^2 exp(-2 (x - a) rho/v) dx, same variable */
static double bound2_integrand(double z, void *p)
{
  const bq *q = p;
  double sv = sqrt(q->v), x = q->a + z * sv;
  return q->n * 4.0 * PI * x * x * exp(-2.0 * z * q->rho / sv) * sv;
}

START_TEST(test_bound_quadrature)
{
  const double cfg[][4] = {{1e15, 1e-6, 1e-13, 2e-6}, {1.0, 1.0, 1.0, 0.0},
                           {1.0, 1.0, 0.01, 0.5}, {3.0, 2.0, 5.0, 7.0},
                           {1e-3, 1.0, 1e-4, 0.05}};
  gsl_integration_workspace *w = gsl_integration_workspace_alloc(1000);
  for (size_t k = 0; k < sizeof cfg / sizeof cfg[0]; k++) {
    bq q = {cfg[k][0], cfg[k][1], cfg[k][2], cfg[k][3]};
    double rho = cfg[k][3], z0 = rho / sqrt(q.v);
    gsl_function F1 = {bound1_integrand, &q}, F2 = {bound2_integrand, &q};
    double v1, v2 = INFINITY, err;
    gsl_integration_qagiu(&F1, z0, 0.0, 1e-12, 1000, w, &v1, &err);
    if (rho > 0.0)
      gsl_integration_qagiu(&F2, z0, 0.0, 1e-12, 1000, w, &v2, &err);
    ck_assert_rel(sb_bridge_miss_bound(q.n, q.a, q.v, rho), fmin(v1, v2),
                  1e-9);
  }
  gsl_integration_workspace_free(w);
  ck_assert(isnan(sb_bridge_miss_bound(-1.0, 1.0, 1.0, 0.0)));
  ck_assert(isnan(sb_bridge_reach(1.0, 1.0, 1.0, 1.5)));
}
END_TEST

START_TEST(test_reach_solves_bound)
{
  const double tols[] = {1e-3, 1e-9, 1e-15};
  for (int k = 0; k < 3; k++) {
    double n = 1e16, a = 1e-6, v = 3e-13;
    double rho = sb_bridge_reach(n, a, v, tols[k]);
    ck_assert(rho > 0.0);
    ck_assert_rel(sb_bridge_miss_bound(n, a, v, rho), tols[k], 1e-8);
    ck_assert(sb_bridge_miss_bound(n, a, v, 0.999 * rho) > tols[k]);
  }
  /* a bound already below tol at rho = 0 gives 0 */
  ck_assert(sb_bridge_reach(1.0, 1e-6, 1e-14, 1e-3) == 0.0);
}
END_TEST

/* Brute force: N particles, random Gaussian displacements of variance b2 dt
 * per component; the detector probability summed over the pairs the
 * neighbour search would NOT examine (sb_engine_pair_can_meet with the
 * reach) must stay below the bound.  tol = 1e-2 makes the sum measurable.
 * 20 trials of N = 1500, pass: mean per particle <= bound and >= bound/50
 * (the bound drops the end-point condition, so it is loose by a bounded
 * factor; measured ratio ~0.1-0.3). */
START_TEST(test_reach_brute_force)
{
  const size_t N = 1500;
  const double d = 1e-6, L = 2e-5, b2 = 1e-10, dt = 5e-3, tol = 1e-2;
  sb_engine_params p;
  sb_engine_params_default(&p);
  p.L[0] = p.L[1] = p.L[2] = L;
  p.dt = dt;
  p.capacity = N;
  p.seed = 11;
  sb_engine *e = sb_engine_alloc(&p);
  ck_assert_ptr_nonnull(e);
  double tau = dt / 1000.0;
  sb_engine_species s = {0.5 * d, 1e-15, tau, sqrt(b2) / tau, 0.0};
  ck_assert_int_eq(sb_engine_add_species(e, &s, NULL), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_fill_random(e, 0, 0, N), SB_SUCCESS);
  sb_engine_bridge_params bp;
  sb_engine_bridge_params_default(&bp);
  bp.tol = tol;
  sb_engine_bridge *b = sb_engine_bridge_alloc(&bp);
  double reach = sb_engine_bridge_reach(e, b);
  double V = L * L * L, v = 2.0 * b2 * dt;
  double bound = sb_bridge_miss_bound((double)(N - 1) / V, d, v, reach);
  ck_assert_rel(bound, tol, 1e-8);
  gsl_rng *r = gsl_rng_alloc(gsl_rng_taus2);
  gsl_rng_set(r, 5);
  double *disp = malloc(3 * N * sizeof *disp);
  const double *x = sb_engine_positions(e);
  double sum = 0.0;
  const int trials = 20;
  for (int t = 0; t < trials; t++) {
    for (size_t k = 0; k < 3 * N; k++)
      disp[k] = gsl_ran_gaussian_ziggurat(r, sqrt(b2 * dt));
    for (size_t i = 0; i < N; i++)
      for (size_t j = i + 1; j < N; j++) {
        if (sb_engine_pair_can_meet(e, disp, reach, i, j))
          continue;
        double A2 = 0, B2 = 0;
        for (int k = 0; k < 3; k++) {
          double A = x[3 * i + k] - x[3 * j + k];
          A -= L * floor(A / L + 0.5);
          double B = A + disp[3 * i + k] - disp[3 * j + k];
          A2 += A * A;
          B2 += B * B;
        }
        sum += sb_bes3b_cross_prob(sqrt(A2), sqrt(B2), d, v);
      }
  }
  double per = 2.0 * sum / ((double)N * trials);
  ck_assert_msg(per <= bound && per >= bound / 50.0,
                "missed per particle %g, bound %g", per, bound);
  free(disp);
  gsl_rng_free(r);
  sb_engine_bridge_free(b);
  sb_engine_free(e);
}
END_TEST

/* ------------------------------------------------ detector on one pair */

static sb_engine *two_particles(double d, double b2, double dt, double L)
{
  sb_engine_params p;
  sb_engine_params_default(&p);
  p.L[0] = p.L[1] = p.L[2] = L;
  p.dt = dt;
  p.capacity = 2;
  sb_engine *e = sb_engine_alloc(&p);
  double tau = dt / 1000.0;
  sb_engine_species s = {0.5 * d, 1e-15, tau, sqrt(b2) / tau, 0.0};
  sb_engine_add_species(e, &s, NULL);
  double x0[3] = {0.25 * L, 0.5 * L, 0.5 * L}, u[3] = {0, 0, 0};
  double x1[3] = {0.75 * L, 0.5 * L, 0.5 * L};
  sb_engine_add_particle(e, 0, 0, x0, u);
  sb_engine_add_particle(e, 0, 0, x1, u);
  return e;
}

static double cdf_pit(double u, void *p)
{
  (void)p;
  return u < 0 ? 0 : (u > 1 ? 1 : u);
}

/* 2e5 draws on fixed end points: hit frequency within 4.4 standard errors
 * of sb_bes3b_cross_prob, and the hit times' PIT through sb_bes3b_hit_cdf
 * uniform (KS p >= 1e-3).  Seed 3. */
START_TEST(test_detector_probability)
{
  const double d = 1e-6, b2 = 1e-10, dt = 1e-2;
  sb_engine *e = two_particles(d, b2, dt, 1e-4);
  sb_engine_bridge_params bp;
  sb_engine_bridge_params_default(&bp);
  bp.record_cap = 200000;
  sb_engine_bridge *b = sb_engine_bridge_alloc(&bp);
  sb_engine_pair p = {0, 1, {1.6e-6, 0.3e-6, 0}, {0.1e-6, -0.5e-6, 0.8e-6},
                      d, dt, 0.0};
  gsl_rng *r = gsl_rng_alloc(gsl_rng_taus2);
  gsl_rng_set(r, 3);
  const long n = 200000;
  long hits = 0;
  for (long k = 0; k < n; k++) {
    double s;
    int h = sb_engine_detect_bridge(e, &p, r, b, &s);
    ck_assert(h == 0 || h == 1);
    hits += h;
    if (h)
      ck_assert(s >= 0.0 && s <= 1.0);
  }
  double x = sqrt(1.6e-6 * 1.6e-6 + 0.3e-6 * 0.3e-6);
  double B[3] = {1.7e-6, -0.2e-6, 0.8e-6};
  double y = sqrt(B[0] * B[0] + B[1] * B[1] + B[2] * B[2]);
  double P = sb_bes3b_cross_prob(x, y, d, 2.0 * b2 * dt);
  double se = sqrt(P * (1 - P) / n);
  ck_assert_msg(fabs((double)hits / n - P) < 4.4 * se, "freq %g, P %g",
                (double)hits / n, P);
  size_t nh;
  const sb_engine_bridge_hit *rec = sb_engine_bridge_hits(b, &nh);
  ck_assert_uint_eq(nh, (size_t)hits);
  double *u = malloc(nh * sizeof *u);
  for (size_t k = 0; k < nh; k++)
    u[k] = sb_bes3b_hit_cdf(rec[k].ta, rec[k].x, rec[k].y, rec[k].a,
                            rec[k].sigma2, rec[k].dt);
  double D, pv;
  ck_assert_int_eq(sb_ks_test(u, nh, cdf_pit, NULL, &D, &pv), SB_SUCCESS);
  ck_assert_msg(pv >= 1e-3, "KS p = %g", pv);
  free(u);
  gsl_rng_free(r);
  sb_engine_bridge_free(b);
  sb_engine_free(e);
}
END_TEST

/* Periodic boundary: the end separation is dx0 + dd (unwrapped), not the
 * minimum image of the end positions.  dx0 = 2a along x, dd = L - 4a:
 * unwrapped end L - 2a (far: P = 0), minimum image -2a (P = 0.135 for
 * v = a^2).  No hit in 2000 draws. */
START_TEST(test_periodic_unwrapped)
{
  const double d = 1e-6, L = 2e-5, dt = 1.0;
  const double b2 = 0.5 * d * d / dt;  /* v = B_ij^2 dt = a^2 */
  sb_engine *e = two_particles(d, b2, dt, L);
  sb_engine_bridge *b = sb_engine_bridge_alloc(NULL);
  sb_engine_pair p = {0, 1, {2 * d, 0, 0}, {L - 4 * d, 0, 0}, d, dt, 0.0};
  gsl_rng *r = gsl_rng_alloc(gsl_rng_taus2);
  int hits = 0;
  for (int k = 0; k < 2000; k++) {
    double s;
    hits += sb_engine_detect_bridge(e, &p, r, b, &s);
  }
  ck_assert_int_eq(hits, 0);
  /* and the same pair without the wrap does hit (~13.5%) */
  p.dd[0] = -4 * d;
  for (int k = 0; k < 2000; k++) {
    double s;
    hits += sb_engine_detect_bridge(e, &p, r, b, &s);
  }
  ck_assert(hits > 200 && hits < 350);
  gsl_rng_free(r);
  sb_engine_bridge_free(b);
  sb_engine_free(e);
}
END_TEST

/* Barycentre place (eq 5.26): mean b0 + s (b1 - b0), variance
 * s (1 - s) dt B_bary^2 per component; 1e5 draws, mean within 4.4
 * standard errors, variance within 2% (its relative sd is 0.45%). */
START_TEST(test_place_moments)
{
  const double d = 1e-6, b2 = 1e-10, dt = 1e-2, L = 1e-4;
  sb_engine *e = two_particles(d, b2, dt, L);
  ck_assert_int_eq(sb_engine_step(e), SB_SUCCESS);  /* x0, disp set */
  sb_engine_bridge *b = sb_engine_bridge_alloc(NULL);
  const double *x0 = sb_engine_start_positions(e);
  const double *x = sb_engine_positions(e);
  sb_engine_pair p;
  p.i = 0;
  p.j = 1;
  p.sigma = d;
  p.dt = dt;
  for (int k = 0; k < 3; k++) {
    p.dx0[k] = x0[k] - x0[3 + k];
    p.dd[k] = 0;
  }
  double want[3];
  const double s = 0.3;
  for (int k = 0; k < 3; k++) {
    /* equal masses: b0 = -dx0/2 relative to x0_0; b1 from the wrapped
     * end positions (no particle crossed a face in one step here) */
    double b0 = -0.5 * p.dx0[k];
    double b1 = 0.5 * ((x[k] - x0[k]) + (x[3 + k] - x0[3 + k]) - p.dx0[k]);
    want[k] = b0 + s * (b1 - b0);
  }
  gsl_rng *r = gsl_rng_alloc(gsl_rng_taus2);
  const int n = 100000;
  double m[3] = {0, 0, 0}, q[3] = {0, 0, 0};
  for (int t = 0; t < n; t++) {
    double bb[3];
    ck_assert_int_eq(sb_engine_bridge_place(e, b, &p, s, r, bb), 0);
    for (int k = 0; k < 3; k++) {
      m[k] += bb[k];
      q[k] += bb[k] * bb[k];
    }
  }
  double var = s * (1 - s) * dt * 0.5 * b2;  /* B_bary^2 = b2/2 */
  for (int k = 0; k < 3; k++) {
    m[k] /= n;
    double vk = q[k] / n - m[k] * m[k];
    ck_assert_msg(fabs(m[k] - want[k]) < 4.4 * sqrt(var / n),
                  "mean %g want %g", m[k], want[k]);
    ck_assert_rel(vk, var, 0.02);
  }
  gsl_rng_free(r);
  sb_engine_bridge_free(b);
  sb_engine_free(e);
}
END_TEST

/* Correction step in a run: the barycentre of every colliding pair keeps
 * its end value; checked on a dense small system through the kinetic
 * observable sum of positions (unwrapped by the displacements):
 * the sum of all end positions equals that of the uncorrected ends.  We
 * use the sum over particles of x0 + disp, which the correction changes
 * only through the pairs (i, j) and there preserves m_i x_i + m_j x_j. */
typedef struct {
  sb_engine_bridge *b;
  double dsum[3];
  int ncorr;
} corr_ctx;

static int corr_outcome(sb_engine *e, const sb_engine_pair *p, double s,
                        void *ctx)
{
  corr_ctx *c = ctx;
  const double *x = sb_engine_positions(e);
  double before[3], after[3];
  for (int k = 0; k < 3; k++)
    before[k] = x[3 * p->i + k] + x[3 * p->j + k];
  int st = sb_engine_outcome_bridge(e, p, s, c->b);
  x = sb_engine_positions(e);
  for (int k = 0; k < 3; k++) {
    after[k] = x[3 * p->i + k] + x[3 * p->j + k];
    double dd = fabs(after[k] - before[k]);
    if (dd > c->dsum[k])
      c->dsum[k] = dd;
  }
  c->ncorr++;
  return st;
}

START_TEST(test_correction_barycentre)
{
  const size_t N = 200;
  const double d = 1e-6, L = 2e-5, b2 = 1e-10, dt = 2.5e-1 * d * d / b2;
  sb_engine_params p;
  sb_engine_params_default(&p);
  p.L[0] = p.L[1] = p.L[2] = L;
  p.dt = dt;
  p.capacity = N;
  p.seed = 9;
  sb_engine *e = sb_engine_alloc(&p);
  double tau = dt / 1000.0;
  sb_engine_species s = {0.5 * d, 1e-15, tau, sqrt(b2) / tau, 0.0};
  sb_engine_add_species(e, &s, NULL);
  ck_assert_int_eq(sb_engine_fill_random(e, 0, 0, N), SB_SUCCESS);
  sb_engine_bridge_params bp;
  sb_engine_bridge_params_default(&bp);
  bp.outcome = SB_BRIDGE_OUT_CORRECT;
  corr_ctx c = {sb_engine_bridge_alloc(&bp), {0, 0, 0}, 0};
  ck_assert_int_eq(sb_engine_bridge_attach(e, c.b), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_set_outcome_fn(e, corr_outcome, &c), 0);
  for (int t = 0; t < 200; t++) {
    int st = sb_engine_step(e);
    ck_assert_msg(st == SB_SUCCESS, "step %d: %s", t, sb_last_error());
  }
  ck_assert(c.ncorr > 20);
  for (int k = 0; k < 3; k++)
    ck_assert_msg(c.dsum[k] < 1e-12 * L, "barycentre moved by %g",
                  c.dsum[k]);
  sb_engine_bridge_free(c.b);
  sb_engine_free(e);
}
END_TEST

START_TEST(test_bad_arguments)
{
  sb_engine_bridge_params bp;
  sb_engine_bridge_params_default(&bp);
  bp.tol = 0.0;
  ck_assert_ptr_null(sb_engine_bridge_alloc(&bp));
  sb_engine_bridge *b = sb_engine_bridge_alloc(NULL);
  ck_assert_int_eq(sb_engine_bridge_set_b2(b, 0, 1.0, 2.0), SB_EINVAL);
  ck_assert_int_eq(sb_engine_bridge_set_b2(b, 3, 1.0, 0.5), SB_SUCCESS);
  sb_engine_params p;
  sb_engine_params_default(&p);
  p.dim = 2;
  sb_engine *e = sb_engine_alloc(&p);
  ck_assert_int_eq(sb_engine_bridge_attach(e, b), SB_EINVAL);
  sb_engine_free(e);
  sb_engine_bridge_free(b);
}
END_TEST

/* 1500 Brownian spheres (r = 0.5, tau = 0.05, k_B T/m = 1) in a cube of
 * 30 at dt = 0.5, the Bessel-3 bridge counting (pass-through) with up to
 * 4000 hit records. */
static sb_engine *bridge_gas(sb_engine_bridge **b, size_t cap,
                             const char *saved, int *st)
{
  sb_engine_params p;
  sb_engine_params_default(&p);
  p.L[0] = p.L[1] = p.L[2] = 30.0;
  p.dt = 0.5;
  p.capacity = 1500;
  p.seed = 29;
  sb_engine *e = sb_engine_alloc(&p);
  ck_assert_ptr_nonnull(e);
  sb_engine_species sp = {0.5, 1.0, 0.05, sqrt(2.0 / 0.05),
                          1.0 / SB_BOLTZMANN};
  ck_assert_int_eq(sb_engine_add_species(e, &sp, NULL), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_fill_random(e, 0, 0, 1500), SB_SUCCESS);
  sb_engine_bridge_params bp;
  sb_engine_bridge_params_default(&bp);
  bp.outcome = SB_BRIDGE_OUT_COUNT;
  bp.record_cap = cap;
  *b = sb_engine_bridge_alloc(&bp);
  ck_assert_ptr_nonnull(*b);
  *st = saved ? sb_engine_bridge_load(*b, saved) : SB_SUCCESS;
  return e;
}

static void bridge_steps(sb_engine *e, int n)
{
  for (int k = 0; k < n; k++)
    ck_assert_msg(sb_engine_step(e) == SB_SUCCESS, "%s", sb_last_error());
}

/* sbt_load_fn: the saved counters into a new detector. */
static int load_bridge(const char *path, void *ctx)
{
  (void)ctx;
  int st;
  sb_engine_bridge *b;
  sb_engine *e = bridge_gas(&b, 4000, path, &st);
  sb_engine_bridge_free(b);
  sb_engine_free(e);
  return st;
}

/* The counters and hit records go on from a checkpoint: a run stopped
 * after 10 steps, saved (engine and detector) and restored is the 20-step
 * run, its counters and records bit for bit.  Then the errors: more
 * records than record_cap, an engine at another step, damaged files. */
START_TEST(test_save_load)
{
  char dir[] = "/tmp/sb_bridge_XXXXXX";
  ck_assert_ptr_nonnull(mkdtemp(dir));
  char ck[64], bf[64], bad[64];
  snprintf(ck, sizeof ck, "%s/run.ck", dir);
  snprintf(bf, sizeof bf, "%s/run.ck.bridge", dir);
  snprintf(bad, sizeof bad, "%s/bad", dir);
  int st;
  sb_engine_bridge *a, *b;
  sb_engine *ea = bridge_gas(&a, 4000, NULL, &st);
  sb_engine *eb = bridge_gas(&b, 4000, NULL, &st);
  ck_assert_int_eq(sb_engine_bridge_attach(ea, a), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_bridge_attach(eb, b), SB_SUCCESS);
  bridge_steps(ea, 20);
  bridge_steps(eb, 10);
  ck_assert_int_eq(sb_engine_checkpoint_save(eb, ck), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_bridge_save(b, eb, bf), SB_SUCCESS);
  sb_engine_bridge_free(b);
  sb_engine_free(eb);
  eb = sb_engine_checkpoint_load(ck, &st);
  ck_assert_int_eq(st, SB_SUCCESS);
  sb_engine *unused = bridge_gas(&b, 4000, bf, &st);
  sb_engine_free(unused);
  ck_assert_msg(st == SB_SUCCESS, "%s", sb_last_error());
  ck_assert_int_eq(sb_engine_bridge_attach(eb, b), SB_SUCCESS);
  bridge_steps(eb, 10);
  sbt_assert_same_run(ea, eb, SBT_SAME_CANDIDATES);
  sb_engine_bridge_stats sa, sb;
  sb_engine_bridge_get_stats(a, &sa);
  sb_engine_bridge_get_stats(b, &sb);
  ck_assert_uint_gt(sa.ncoll, 100);
  ck_assert(!memcmp(&sa, &sb, sizeof sa));
  size_t na, nb;
  const sb_engine_bridge_hit *ha = sb_engine_bridge_hits(a, &na);
  const sb_engine_bridge_hit *hb = sb_engine_bridge_hits(b, &nb);
  ck_assert_uint_eq(na, nb);
  ck_assert(na > 100 && !memcmp(ha, hb, na * sizeof *ha));
  sb_engine_bridge_free(b);
  /* the errors: too few records allowed; the engine at another step */
  unused = bridge_gas(&b, 10, bf, &st);
  ck_assert_int_eq(st, SB_EINVAL);
  sb_engine_bridge_free(b);
  sb_engine_free(unused);
  unused = bridge_gas(&b, 4000, bf, &st);
  ck_assert_int_eq(st, SB_SUCCESS);
  ck_assert_int_eq(sb_engine_bridge_attach(eb, b), SB_EINVAL);  /* at 20 */
  ck_assert_ptr_nonnull(strstr(sb_last_error(), "step 10"));
  sb_engine_bridge_free(b);
  sb_engine_free(unused);
  sbt_damaged_copies(bf, bad, 30, "SBFHIT01", load_bridge, NULL);
  /* a flipped byte; the format without the hash (version 01) */
  sbt_hash_checked(bf, bad, "01", load_bridge, NULL);
  sb_engine_bridge_free(a);
  sb_engine_free(ea);
  sb_engine_free(eb);
  remove(ck);
  remove(bf);
  rmdir(dir);
}
END_TEST

static Suite *suite(void)
{
  Suite *s = suite_create("engine_bridge");
  TCase *tc = tcase_create("core");
  tcase_set_timeout(tc, 60);
  tcase_add_test(tc, test_bound_quadrature);
  tcase_add_test(tc, test_reach_solves_bound);
  tcase_add_test(tc, test_reach_brute_force);
  tcase_add_test(tc, test_detector_probability);
  tcase_add_test(tc, test_periodic_unwrapped);
  tcase_add_test(tc, test_place_moments);
  tcase_add_test(tc, test_correction_barycentre);
  tcase_add_test(tc, test_bad_arguments);
  tcase_add_test(tc, test_save_load);
  suite_add_tcase(s, tc);
  return s;
}

int main(void) { return sbt_run_suite(suite()); }
