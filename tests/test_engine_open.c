#define _POSIX_C_SOURCE 200809L
/* test_engine_open.c — open boundaries of the engine (lib/engine/
 * engine_open.c): inflows and outflow through SB_WALL_OPEN faces.
 *
 * Independent checks: the stream's particle number in the box against
 * its Poisson law (mean rate x transit time, by the exact Poisson test on
 * the pooled count of well separated snapshots); the balance injected =
 * left + inside, exactly; the outflow callback's crossing time against
 * the straight chord computed by hand; the arrivals' positions uniform
 * over the inlet (KS); argument checks; open faces through a checkpoint;
 * a run with inflows continued from a checkpoint against the run in one
 * go, bit for bit.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <gsl/gsl_cdf.h>

#include <smolbridge/engine.h>
#include <smolbridge/langevin.h>
#include <smolbridge/stats.h>

#include "engine_same.h"
#include "testutil.h"

/* A 2-D box of edge L with one non-Brownian species of radius r and
 * relaxation time tau (inf: free flight), open in x (and in y when
 * open_y), periodic otherwise, count outcome. */
static sb_engine *box2_tau(double L, double dt, double r, double tau,
                           size_t cap, int open_y, unsigned long seed)
{
  sb_engine_params p;
  sb_engine_params_default(&p);
  p.dim = 2;
  p.L[0] = p.L[1] = L;
  p.dt = dt;
  p.capacity = cap;
  p.seed = seed;
  p.outcome = SB_OUTCOME_COUNT;
  sb_engine *e = sb_engine_alloc(&p);
  ck_assert_ptr_nonnull(e);
  const double m = 1e-15;
  sb_engine_species s = {r, m, tau, 0.0, m * 1e-8 / SB_BOLTZMANN};
  ck_assert_int_eq(sb_engine_add_species(e, &s, NULL), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_set_walls(e, 0, SB_WALL_OPEN, SB_WALL_OPEN),
                   SB_SUCCESS);
  if (open_y)
    ck_assert_int_eq(sb_engine_set_walls(e, 1, SB_WALL_OPEN, SB_WALL_OPEN),
                     SB_SUCCESS);
  ck_assert_int_eq(sb_engine_set_wall_mode(e, SB_WALLDET_BALLISTIC,
                                           SB_DEPOSIT_REMOVE),
                   SB_SUCCESS);
  return e;
}

/* The same box with free-flight particles. */
static sb_engine *box2(double L, double dt, double r, size_t cap,
                       int open_y, unsigned long seed)
{
  return box2_tau(L, dt, r, INFINITY, cap, open_y, seed);
}

/* The number of particles of a stream in the box is Poisson with mean
 * rate x L/u once the stream fills it; snapshots one transit apart are
 * independent (each holds only the arrivals of its own transit).  Sample:
 * 200 snapshots of mean 50; exact Poisson test at 1e-4 on their sum. */
START_TEST(test_inflow_density)
{
  const double L = 1e-3, u = 1.0, dt = 2e-6, rate = 5e4;
  sb_engine *e = box2(L, dt, 1e-6, 4096, 0, 11);
  sb_engine_inflow in = {0, 0, 0, rate, {0, 0}, {L, 0}, {u, 0, 0}, 0};
  ck_assert_int_eq(sb_engine_add_inflow(e, &in, NULL), SB_SUCCESS);
  const long transit = lround(L / u / dt);
  unsigned long sum = 0;
  for (long k = 0; k < 201 * transit; k++) {
    ck_assert_int_eq(sb_engine_step(e), SB_SUCCESS);
    if (k >= transit && (k + 1) % transit == 0)
      sum += sb_engine_count(e);
  }
  const double mean = 200.0 * rate * L / u;
  double lo, hi;
  ck_assert_int_eq(sb_poisson_ci(sum, 1.0 - 1e-4, &lo, &hi), SB_SUCCESS);
  ck_assert_msg(lo <= mean && mean <= hi, "count %lu, expected %g, "
                "interval [%g, %g]", sum, mean, lo, hi);
  /* every particle is accounted for, exactly */
  ck_assert_uint_eq(sb_engine_inflow_injected(e, 0),
                    sb_engine_outflows(e, 0) + sb_engine_outflows(e, 1) +
                        sb_engine_count(e));
  ck_assert_uint_eq(sb_engine_outflows(e, 0), 0);  /* none goes back */
  sb_engine_free(e);
}
END_TEST

typedef struct {
  double t_exit[8];
  int face[8];
  double y[8];
  int n;
} exits;

static int record(const sb_engine *e, size_t i, int face, double t_exit,
                  void *ctx)
{
  exits *x = ctx;
  if (x->n < 8) {
    x->t_exit[x->n] = t_exit;
    x->face[x->n] = face;
    x->y[x->n] = sb_engine_positions(e)[3 * i + 1];
    x->n++;
  }
  return 0;
}

/* Two particles leave through x_hi and y_lo; the callback gets the face
 * and the time the straight chord crossed it. */
START_TEST(test_outflow_callback)
{
  const double L = 1e-3, dt = 1e-5;
  sb_engine *e = box2(L, dt, 1e-6, 16, 1, 3);
  exits x = {{0}, {0}, {0}, 0};
  ck_assert_int_eq(sb_engine_set_outflow_fn(e, record, &x), SB_SUCCESS);
  double p0[3] = {0.95e-3, 0.3e-3, 0}, u0[3] = {2.0, 0.5, 0};
  double p1[3] = {0.5e-3, 0.07e-3, 0}, u1[3] = {0.0, -3.0, 0};
  ck_assert_int_eq(sb_engine_add_particle(e, 0, 0, p0, u0), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_add_particle(e, 0, 1, p1, u1), SB_SUCCESS);
  for (int k = 0; k < 5; k++)
    ck_assert_int_eq(sb_engine_step(e), SB_SUCCESS);
  ck_assert_int_eq(x.n, 2);
  ck_assert_uint_eq(sb_engine_count(e), 0);
  /* by hand: x = 0.95e-3 + 2 t reaches 1e-3 at t = 2.5e-5 (step 3);
   * y = 0.07e-3 - 3 t reaches 0 at t = 2.333e-5 (step 3) */
  for (int q = 0; q < 2; q++) {
    if (x.face[q] == 1)
      ck_assert_double_eq_tol(x.t_exit[q], 2.5e-5, 1e-15);
    else {
      ck_assert_int_eq(x.face[q], 2);
      ck_assert_double_eq_tol(x.t_exit[q], 0.07e-3 / 3.0, 1e-15);
    }
  }
  ck_assert_uint_eq(sb_engine_outflows(e, 1), 1);
  ck_assert_uint_eq(sb_engine_outflows(e, 2), 1);
  sb_engine_free(e);
}
END_TEST

static double unif_cdf(double v, void *ctx)
{
  (void)ctx;
  return v < 0 ? 0 : (v > 1 ? 1 : v);
}

/* Arrivals are uniform across the inlet (KS on 2000 positions at their
 * first step, p >= 1e-4) and none lands outside it. */
START_TEST(test_inflow_uniform)
{
  const double L = 1e-3, dt = 1e-6, lo = 0.2e-3, hi = 0.7e-3;
  sb_engine *e = box2(L, dt, 1e-7, 4096, 1, 5);
  sb_engine_inflow in = {0, 0, 0, 2e8, {lo, 0}, {hi, 0}, {1.0, 0, 0}, 0};
  ck_assert_int_eq(sb_engine_add_inflow(e, &in, NULL), SB_SUCCESS);
  double v[2400];
  size_t n = 0;
  while (n < 2000) {
    size_t before = sb_engine_count(e);
    ck_assert_int_eq(sb_engine_step(e), SB_SUCCESS);
    const double *x = sb_engine_positions(e);
    for (size_t i = before; i < sb_engine_count(e) && n < 2400; i++) {
      ck_assert(x[3 * i] >= 0.0 && x[3 * i] <= dt * 1.0);
      ck_assert(x[3 * i + 1] >= lo && x[3 * i + 1] < hi);
      v[n++] = (x[3 * i + 1] - lo) / (hi - lo);
    }
  }
  double d, p;
  ck_assert_int_eq(sb_ks_test(v, n, unif_cdf, NULL, &d, &p), SB_SUCCESS);
  ck_assert_msg(p >= 1e-4, "KS p = %g", p);
  sb_engine_free(e);
}
END_TEST

START_TEST(test_inflow_errors)
{
  sb_engine *e = box2(1e-3, 1e-6, 1e-6, 16, 0, 1);
  sb_engine_inflow in = {0, 0, 0, 1e3, {0, 0}, {1e-3, 0}, {1.0, 0, 0}, 0};
  sb_engine_inflow b = in;
  b.u[0] = -1.0;  /* outward */
  ck_assert_int_eq(sb_engine_add_inflow(e, &b, NULL), SB_EINVAL);
  b = in;
  b.face = 4;  /* z in 2-D */
  ck_assert_int_eq(sb_engine_add_inflow(e, &b, NULL), SB_EINVAL);
  b = in;
  b.hi[0] = 2e-3;  /* inlet beyond the box */
  ck_assert_int_eq(sb_engine_add_inflow(e, &b, NULL), SB_EINVAL);
  b = in;
  b.rate = -1.0;
  ck_assert_int_eq(sb_engine_add_inflow(e, &b, NULL), SB_EINVAL);
  b = in;
  b.species = 3;
  ck_assert_int_eq(sb_engine_add_inflow(e, &b, NULL), SB_EINVAL);
  b = in;
  b.u[0] = 2e3;  /* crosses the box in one step */
  ck_assert_int_eq(sb_engine_add_inflow(e, &b, NULL), SB_EINVAL);
  size_t idx = 99;
  ck_assert_int_eq(sb_engine_add_inflow(e, &in, &idx), SB_SUCCESS);
  ck_assert_uint_eq(idx, 0);
  ck_assert_uint_eq(sb_engine_ninflows(e), 1);
  ck_assert_int_eq(sb_engine_set_walls(e, 1, SB_WALL_OPEN, 7), SB_EINVAL);
  sb_engine_free(e);
}
END_TEST

/* Open faces survive a checkpoint (the inflows are given again). */
START_TEST(test_open_checkpoint)
{
  sb_engine *e = box2(1e-3, 1e-6, 1e-6, 64, 1, 2);
  char path[] = "/tmp/sb_open_XXXXXX";
  int fd = mkstemp(path);
  ck_assert_int_ge(fd, 0);
  close(fd);
  ck_assert_int_eq(sb_engine_checkpoint_save(e, path), SB_SUCCESS);
  int st = 0;
  sb_engine *f = sb_engine_checkpoint_load(path, &st);
  ck_assert_ptr_nonnull(f);
  ck_assert_int_eq(sb_engine_periodic(f, 0), 0);
  ck_assert_int_eq(sb_engine_periodic(f, 1), 0);
  ck_assert_uint_eq(sb_engine_ninflows(f), 0);
  unlink(path);
  sb_engine_free(f);
  sb_engine_free(e);
}
END_TEST

/* The engine of test_inflow_restart: a 2-D box open in x, periodic in y,
 * Brownian spheres under gravity with elastic collisions, two opposed
 * inflows (the second one redrawing overlapping arrivals). */
static sb_engine *jets(unsigned long seed)
{
  const double L = 1e-3;
  sb_engine_params p;
  sb_engine_params_default(&p);
  p.dim = 2;
  p.L[0] = p.L[1] = L;
  p.dt = 1e-5;
  p.capacity = 4096;
  p.seed = seed;
  p.outcome = SB_OUTCOME_ELASTIC;
  sb_engine *e = sb_engine_alloc(&p);
  ck_assert_ptr_nonnull(e);
  const double tau = 1e-4, vsd = 0.1;
  sb_engine_species s = {1e-5, 1e-12, tau, sqrt(2.0 * vsd * vsd / tau), 0.0};
  ck_assert_int_eq(sb_engine_add_species(e, &s, NULL), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_set_walls(e, 0, SB_WALL_OPEN, SB_WALL_OPEN),
                   SB_SUCCESS);
  const double g[3] = {0.0, -9.81, 0.0};
  ck_assert_int_eq(sb_engine_set_gravity(e, g), SB_SUCCESS);
  return e;
}

static void jets_inflows(sb_engine *e)
{
  const double L = 1e-3;
  sb_engine_inflow a = {0, 0, 0, 4e5, {0.2 * L, 0}, {0.8 * L, 0},
                        {1.0, 0.1, 0}, 0};
  sb_engine_inflow b = {1, 0, 1, 3e5, {0.1 * L, 0}, {0.6 * L, 0},
                        {-0.8, 0, 0}, 1};
  ck_assert_int_eq(sb_engine_add_inflow(e, &a, NULL), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_add_inflow(e, &b, NULL), SB_SUCCESS);
}

/* A run with inflows continued from a checkpoint, its inflows added again
 * as documented, is the run without the stop, bit for bit: the particles
 * (ids, positions, velocities), the collisions, the injected, skipped and
 * outflow counters.  Inflows are settings (like the callbacks), and
 * everything they draw from, the engine's generator, and their counters
 * are in the checkpoint.  120 + 120 steps, a few hundred particles,
 * thousands of collisions. */
START_TEST(test_inflow_restart)
{
  const int n1 = 120, n2 = 120;
  sb_engine *a = jets(23), *b = jets(23);
  jets_inflows(a);
  jets_inflows(b);
  for (int k = 0; k < n1 + n2; k++)
    ck_assert_msg(sb_engine_step(a) == SB_SUCCESS, "%s", sb_last_error());
  for (int k = 0; k < n1; k++)
    ck_assert_msg(sb_engine_step(b) == SB_SUCCESS, "%s", sb_last_error());
  char path[] = "/tmp/sb_open_restart_XXXXXX";
  int fd = mkstemp(path);
  ck_assert_int_ge(fd, 0);
  close(fd);
  ck_assert_int_eq(sb_engine_checkpoint_save(b, path), SB_SUCCESS);
  sb_engine_free(b);
  int st = 0;
  b = sb_engine_checkpoint_load(path, &st);
  ck_assert_msg(b != NULL, "%s", sb_last_error());
  unlink(path);
  ck_assert_uint_eq(sb_engine_ninflows(b), 0);  /* not in the file */
  jets_inflows(b);
  for (int k = 0; k < n2; k++)
    ck_assert_msg(sb_engine_step(b) == SB_SUCCESS, "%s", sb_last_error());
  sbt_assert_same_run(a, b, SBT_SAME_CANDIDATES | SBT_SAME_REDETECTED);
  const size_t n = sb_engine_count(a);
  ck_assert(!memcmp(sb_engine_ids(a), sb_engine_ids(b), n * sizeof(uint64_t)));
  ck_assert(!memcmp(sb_engine_families(a), sb_engine_families(b),
                    n * sizeof(int)));
  for (size_t q = 0; q < 2; q++) {
    ck_assert_uint_eq(sb_engine_inflow_injected(a, q),
                      sb_engine_inflow_injected(b, q));
    ck_assert_uint_eq(sb_engine_inflow_skipped(a, q),
                      sb_engine_inflow_skipped(b, q));
  }
  for (int f = 0; f < 4; f++)
    ck_assert_uint_eq(sb_engine_outflows(a, f), sb_engine_outflows(b, f));
  sb_engine_stats sa;
  sb_engine_get_stats(a, &sa);
  printf("inflow restart: %zu particles, %llu + %llu injected, %llu "
         "skipped, %llu + %llu out, %llu collisions\n", n,
         (unsigned long long)sb_engine_inflow_injected(a, 0),
         (unsigned long long)sb_engine_inflow_injected(a, 1),
         (unsigned long long)sb_engine_inflow_skipped(a, 1),
         (unsigned long long)sb_engine_outflows(a, 0),
         (unsigned long long)sb_engine_outflows(a, 1),
         (unsigned long long)sa.ncoll);
  ck_assert_uint_gt(n, 100);
  ck_assert_uint_gt(sa.ncoll, 100);
  ck_assert_uint_gt(sb_engine_outflows(a, 0) + sb_engine_outflows(a, 1), 50);
  sb_engine_free(a);
  sb_engine_free(b);
}
END_TEST

/* With drag, an arrival's partial step follows the exact path: after
 * h since entry, u = u0 e^{-h/tau} and x = u0 tau (1 - e^{-h/tau}) (fluid
 * at rest), so x = tau (u0 - u) for every arrival of the first step, with
 * u in [u0 e^{-dt/tau}, u0].  (A straight flight would keep u = u0.) */
START_TEST(test_inflow_drag_flight)
{
  const double L = 1e-3, dt = 1e-4, tau = 2e-4, u0 = 1.0;
  sb_engine *e = box2_tau(L, dt, 1e-9, tau, 256, 0, 11);
  sb_engine_inflow in;
  memset(&in, 0, sizeof in);
  in.face = 0;
  in.rate = 1e6;  /* ~100 arrivals per step */
  in.lo[0] = 0.25 * L;
  in.hi[0] = 0.75 * L;
  in.u[0] = u0;
  ck_assert_int_eq(sb_engine_add_inflow(e, &in, NULL), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_step(e), SB_SUCCESS);
  const size_t n = sb_engine_count(e);
  ck_assert_uint_gt(n, 50);
  const double *x = sb_engine_positions(e), *u = sb_engine_velocities(e);
  for (size_t i = 0; i < n; i++) {
    ck_assert_double_le(u[3 * i], u0);
    ck_assert_double_ge(u[3 * i], u0 * exp(-dt / tau) * (1 - 1e-12));
    ck_assert_double_eq_tol(x[3 * i], tau * (u0 - u[3 * i]), 1e-12 * L);
    ck_assert_double_eq(u[3 * i + 1], 0.0);
  }
  sb_engine_free(e);
}
END_TEST

static Suite *suite(void)
{
  Suite *s = suite_create("engine_open");
  TCase *tc = tcase_create("open");
  tcase_set_timeout(tc, 300);
  tcase_add_test(tc, test_inflow_density);
  tcase_add_test(tc, test_outflow_callback);
  tcase_add_test(tc, test_inflow_uniform);
  tcase_add_test(tc, test_inflow_errors);
  tcase_add_test(tc, test_open_checkpoint);
  tcase_add_test(tc, test_inflow_restart);
  tcase_add_test(tc, test_inflow_drag_flight);
  suite_add_tcase(s, tc);
  return s;
}

int main(void) { return sbt_run_suite(suite()); }
