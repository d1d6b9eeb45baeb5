/* test_engine_neigh.c — the neighbour searches (linked cells, sort-and-
 * sweep) return a superset of the pairs that can collide during a step.
 *
 * Reference: for every one of the N(N-1)/2 pairs, the exact minimum
 * distance of the two straight segments x_i + s disp_i, s in [0,1]
 * (sb_engine_pair_can_meet, a closed form independent of both searches).
 * Every pair within r_i + r_j (+ reach) must be in each method's list, and
 * no list may hold a pair twice.  Configurations: random isotropic
 * (polydisperse, 2-D and 3-D, rectangular boxes), counter-flowing and
 * crossing jets (Thomine 2008, §5.1, §8), small boxes with fewer than three
 * cells per direction, particles straddling the periodic boundaries, and
 * an extra detector reach.
 */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>
#include <smolbridge/engine.h>

#include "testutil.h"

typedef struct {
  int dim;
  double L[3];
  size_t n;
  double r1, r2;       /* radii of the two species */
  int jets;            /* 0 isotropic, 1 counter-flow along x, 2 crossing */
  double vth, U;       /* thermal and jet speeds */
  double dt, reach;
  int edge;            /* put particles near the box faces */
} config;

/* Build the configuration, return the engine and the displacements. */
static sb_engine *build(const config *c, unsigned long seed, double **disp)
{
  sb_engine_params p;
  sb_engine_params_default(&p);
  p.dim = c->dim;
  memcpy(p.L, c->L, sizeof p.L);
  p.capacity = c->n;
  p.dt = c->dt;
  sb_engine *e = sb_engine_alloc(&p);
  ck_assert_ptr_nonnull(e);
  sb_engine_species s1 = {c->r1, 1.0, INFINITY, 0.0, 1.0};
  sb_engine_species s2 = {c->r2, 1.0, INFINITY, 0.0, 1.0};
  sb_engine_add_species(e, &s1, NULL);
  sb_engine_add_species(e, &s2, NULL);
  gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
  gsl_rng_set(r, seed);
  *disp = calloc(3 * c->n, sizeof(double));
  for (size_t i = 0; i < c->n; i++) {
    double x[3] = {0, 0, 0}, u[3] = {0, 0, 0};
    int fam = (int)(i % 2);
    for (int k = 0; k < c->dim; k++) {
      x[k] = c->L[k] * gsl_rng_uniform(r);
      if (c->edge && gsl_rng_uniform(r) < 0.5)
        x[k] = gsl_rng_uniform(r) < 0.5 ? c->L[k] * 1e-3 * gsl_rng_uniform(r)
                                        : c->L[k] * (1 - 1e-3 *
                                                     gsl_rng_uniform(r));
      u[k] = gsl_ran_gaussian(r, c->vth);
    }
    if (c->jets == 1) {
      /* two beams along x in the same band of y, opposite directions */
      x[1] = c->L[1] * (0.4 + 0.2 * gsl_rng_uniform(r));
      u[0] += fam ? -c->U : c->U;
    } else if (c->jets == 2) {
      /* crossing jets at +-50 degrees (Thomine 2008, §8) */
      double a = 50.0 * 3.14159265358979323846 / 180.0;
      u[0] += c->U * cos(a);
      u[1] += (fam ? -1 : 1) * c->U * sin(a);
    }
    ck_assert_int_eq(sb_engine_add_particle(e, (size_t)fam, fam, x, u),
                     SB_SUCCESS);
  }
  /* displacement of the trial step: u dt (sb_engine_add_particle wrapped
   * x; velocities are stored as given) */
  const double *u = sb_engine_velocities(e);
  for (size_t i = 0; i < 3 * c->n; i++)
    (*disp)[i] = u[i] * c->dt;
  gsl_rng_free(r);
  return e;
}

/* Bit sets over the n x n pair matrix. */
#define BIT_GET(b, k) (((b)[(k) >> 6] >> ((k)&63)) & 1u)
#define BIT_SET(b, k) ((b)[(k) >> 6] |= (uint64_t)1 << ((k)&63))

/* Check one method against the exact test; returns the list length. */
static size_t check_method(sb_engine *e, sb_engine_neigh m,
                           const double *disp, double reach,
                           const uint64_t *meet, size_t *nmeet)
{
  const size_t n = sb_engine_count(e);
  size_t np;
  const size_t *pairs;
  ck_assert_int_eq(sb_engine_neighbours(e, m, disp, reach, &np, &pairs),
                   SB_SUCCESS);
  uint64_t *seen = calloc(n * n / 64 + 1, sizeof *seen);
  for (size_t q = 0; q < np; q++) {
    size_t i = pairs[2 * q], j = pairs[2 * q + 1];
    /* plain tests first: Check logs every passing assertion to a file */
    if (!(i < j && j < n))
      ck_abort_msg("bad pair (%zu, %zu)", i, j);
    if (BIT_GET(seen, i * n + j))
      ck_abort_msg("method %d: pair (%zu, %zu) twice", (int)m, i, j);
    BIT_SET(seen, i * n + j);
  }
  size_t cnt = 0;
  for (size_t i = 0; i < n; i++)
    for (size_t j = i + 1; j < n; j++)
      if (BIT_GET(meet, i * n + j)) {
        cnt++;
        if (!BIT_GET(seen, i * n + j))
          ck_abort_msg("method %d misses pair (%zu, %zu) that can meet",
                       (int)m, i, j);
      }
  *nmeet = cnt;
  free(seen);
  return np;
}

static void run_config(const config *c, unsigned long seed, size_t min_meet)
{
  double *disp;
  sb_engine *e = build(c, seed, &disp);
  const size_t n = c->n;
  uint64_t *meet = calloc(n * n / 64 + 1, sizeof *meet);
  for (size_t i = 0; i < n; i++)
    for (size_t j = i + 1; j < n; j++)
      if (sb_engine_pair_can_meet(e, disp, c->reach, i, j))
        BIT_SET(meet, i * n + j);
  size_t nm, nc, ns, nb;
  nb = check_method(e, SB_NEIGH_BRUTE, disp, c->reach, meet, &nm);
  nc = check_method(e, SB_NEIGH_CELLS, disp, c->reach, meet, &nm);
  ns = check_method(e, SB_NEIGH_SWEEP, disp, c->reach, meet, &nm);
  ck_assert_msg(nm >= min_meet, "only %zu meeting pairs (test too easy)",
                nm);
  ck_assert(nc <= nb + 0);  /* cells filter with the same criterion */
  (void)ns;
  free(meet);
  free(disp);
  sb_engine_free(e);
}

START_TEST(test_random_3d)
{
  config c = {3, {20, 15, 12}, 2000, 0.3, 0.15, 0, 1.0, 0.0, 0.4, 0.0, 0};
  for (unsigned long s = 1; s <= 3; s++)
    run_config(&c, s, 50);
}
END_TEST

START_TEST(test_random_2d)
{
  config c = {2, {40, 25, 0}, 2000, 0.3, 0.1, 0, 1.0, 0.0, 0.3, 0.0, 0};
  for (unsigned long s = 1; s <= 3; s++)
    run_config(&c, s, 50);
}
END_TEST

START_TEST(test_counterflow_jets)
{
  config c2 = {2, {60, 20, 0}, 1500, 0.2, 0.1, 1, 0.05, 5.0, 0.4, 0.0, 0};
  config c3 = {3, {40, 10, 10}, 2000, 0.3, 0.2, 1, 0.05, 4.0, 0.5, 0.0, 0};
  for (unsigned long s = 1; s <= 2; s++) {
    run_config(&c2, s, 30);
    run_config(&c3, s, 30);
  }
}
END_TEST

START_TEST(test_crossing_jets)
{
  config c2 = {2, {40, 40, 0}, 2000, 0.25, 0.12, 2, 0.1, 3.0, 0.5, 0.0, 0};
  config c3 = {3, {20, 20, 10}, 2000, 0.25, 0.12, 2, 0.1, 3.0, 0.5, 0.0, 0};
  for (unsigned long s = 1; s <= 2; s++) {
    run_config(&c2, s, 30);
    run_config(&c3, s, 30);
  }
}
END_TEST

/* Periodic faces, a small box (fewer than 3 cells per direction) and an
 * extra reach (the custom-detector interface). */
START_TEST(test_edges_small_reach)
{
  config ce = {3, {12, 12, 12}, 1500, 0.3, 0.2, 0, 1.0, 0.0, 0.4, 0.0, 1};
  run_config(&ce, 4, 30);
  config cs = {3, {5, 6, 7}, 300, 0.4, 0.3, 0, 1.0, 0.0, 0.15, 0.0, 1};
  run_config(&cs, 5, 10);
  config cr = {3, {20, 20, 20}, 1500, 0.2, 0.1, 0, 1.0, 0.0, 0.3, 0.8, 0};
  run_config(&cr, 6, 50);
  config c2 = {2, {6, 5, 0}, 200, 0.3, 0.2, 2, 0.5, 1.0, 0.2, 0.2, 1};
  run_config(&c2, 7, 10);
}
END_TEST

/* Very few particles: one cell per direction, so pairs across the
 * periodic faces lie in the same cell and need the minimum image. */
START_TEST(test_single_cell_periodic)
{
  sb_engine_params p;
  sb_engine_params_default(&p);
  p.L[0] = p.L[1] = p.L[2] = 10.0;
  p.capacity = 8;
  sb_engine *e = sb_engine_alloc(&p);
  ck_assert_ptr_nonnull(e);
  sb_engine_species s = {0.5, 1.0, INFINITY, 0.0, 1.0};
  ck_assert_int_eq(sb_engine_add_species(e, &s, NULL), SB_SUCCESS);
  /* three touching pairs across the x, y and z faces, two loners */
  const double x[8][3] = {{0.1, 5, 5}, {9.5, 5, 5}, {3, 0.2, 3},
                          {3, 9.3, 3}, {7, 7, 0.05}, {7, 7.2, 9.2},
                          {5, 5, 5},   {2, 7, 8}};
  const double u[3] = {0, 0, 0};
  for (int i = 0; i < 8; i++)
    ck_assert_int_eq(sb_engine_add_particle(e, 0, 0, x[i], u), SB_SUCCESS);
  size_t nb, nc;
  const size_t *pb, *pc;
  ck_assert_int_eq(sb_engine_neighbours(e, SB_NEIGH_BRUTE, NULL, 0.0, &nb,
                                        &pb), SB_SUCCESS);
  ck_assert_uint_eq(nb, 3);
  size_t want[6];
  memcpy(want, pb, sizeof want);
  ck_assert_int_eq(sb_engine_neighbours(e, SB_NEIGH_CELLS, NULL, 0.0, &nc,
                                        &pc), SB_SUCCESS);
  ck_assert_uint_eq(nc, 3);
  for (int q = 0; q < 3; q++) {
    int found = 0;
    for (size_t r = 0; r < nc; r++)
      found |= pc[2 * r] == want[2 * q] && pc[2 * r + 1] == want[2 * q + 1];
    ck_assert_msg(found, "cells miss pair (%zu, %zu)", want[2 * q],
                  want[2 * q + 1]);
  }
  sb_engine_free(e);
}
END_TEST

/* Displacements too large for the box are refused. */
START_TEST(test_refuse_large)
{
  config c = {3, {10, 10, 10}, 50, 0.3, 0.2, 0, 1.0, 0.0, 4.0, 0.0, 0};
  double *disp;
  sb_engine *e = build(&c, 1, &disp);
  size_t np;
  const size_t *pairs;
  ck_assert_int_eq(
      sb_engine_neighbours(e, SB_NEIGH_CELLS, disp, 0.0, &np, &pairs),
      SB_EINVAL);
  ck_assert_int_eq(
      sb_engine_neighbours(e, SB_NEIGH_SWEEP, disp, 0.0, &np, &pairs),
      SB_EINVAL);
  free(disp);
  sb_engine_free(e);
}
END_TEST

static Suite *suite(void)
{
  Suite *s = suite_create("engine_neigh");
  TCase *tc = tcase_create("superset");
  tcase_set_timeout(tc, 60);
  tcase_add_test(tc, test_random_3d);
  tcase_add_test(tc, test_random_2d);
  tcase_add_test(tc, test_counterflow_jets);
  tcase_add_test(tc, test_crossing_jets);
  tcase_add_test(tc, test_edges_small_reach);
  tcase_add_test(tc, test_refuse_large);
  tcase_add_test(tc, test_single_cell_periodic);
  suite_add_tcase(s, tc);
  return s;
}

int main(void) { return sbt_run_suite(suite()); }
