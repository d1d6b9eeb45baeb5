/* test_engine_verlet.c — the Verlet list of the cells search
 * (lib/engine/engine_neigh.c: list_holds, list_build, listed).
 *
 * Independent check: the same runs with the list switched off
 * (sb_engine_params.verlet_off, cells rebuilt at every step) and with the
 * O(N^2) brute-force search.  The list must give the same candidate pairs
 * and therefore the same run, bit for bit: positions, velocities,
 * counters (candidates included) and the time series — through elastic
 * bounces (re-detection inside a step with the cells of an older build),
 * reinsertions (jumps: the list must be rebuilt), merges (particles
 * removed, radii changed), overlap detection, 2-D boxes, memory reordering
 * (sort_every) and a foreign search between steps (sb_engine_neighbours
 * overwrites the cells).  Each run also checks that the list was used and
 * rebuilt, so that the comparison is not vacuous.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_rng.h>
#include <smolbridge/engine.h>

#include "engine/engine_internal.h"
#include "engine_same.h"
#include "testutil.h"

typedef struct {
  int dim;
  sb_engine_outcome outcome;
  sb_engine_detect detect;
  size_t sort_every;
  int foreign;  /* call sb_engine_neighbours every 50 steps */
  int merge;    /* agglomeration: every contact merges (sb_agglo) */
} setup;

/* 400 Brownian spheres (r = 0.5, velocity variance 1) in a 30 x 25 x 20
 * box (phi ~ 1.4%): |disp| ~ 0.01 per step, below r/20, so the list
 * applies; 3000 steps give a few hundred contacts. */
static sb_engine *make(const setup *s, sb_engine_neigh m, int verlet_off)
{
  sb_engine_params p;
  sb_engine_params_default(&p);
  p.dim = s->dim;
  p.L[0] = 30.0;
  p.L[1] = 25.0;
  p.L[2] = 20.0;
  p.dt = 0.005;
  p.capacity = 400;
  p.seed = 7;
  p.neigh = m;
  p.detect = s->detect;
  p.outcome = s->outcome;
  p.sample_every = 100;
  p.sort_every = s->sort_every;
  p.verlet_off = verlet_off;
  /* the list against the cells' own scan, candidate for candidate (the
   * Langevin search, where the list is not used, returns fewer: the same
   * run, tests/test_engine_lsearch.c) */
  p.lsearch_off = 1;
  sb_engine *e = sb_engine_alloc(&p);
  ck_assert_ptr_nonnull(e);
  sb_engine_species sp = {0.5, 1.0, 1.0, sqrt(2.0), 0.0};
  ck_assert_int_eq(sb_engine_add_species(e, &sp, NULL), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_fill_random(e, 0, 0, s->dim == 2 ? 150 : 400),
                   SB_SUCCESS);
  return e;
}

/* Every contact merges the pair (sizes grow, particles go). */
static sb_agglo *merging(sb_engine *e)
{
  sb_agglo_params ap;
  sb_agglo_params_default(&ap);
  sb_agglo *a = sb_agglo_alloc(&ap);
  ck_assert_ptr_nonnull(a);
  ck_assert_int_eq(sb_agglo_attach(e, a), SB_SUCCESS);
  return a;
}


/* Run the three searches side by side; returns the list engine's
 * collisions. */
static uint64_t run_three(const setup *s)
{
  sb_engine *a = make(s, SB_NEIGH_CELLS, 0);
  sb_engine *b = make(s, SB_NEIGH_CELLS, 1);
  sb_engine *c = make(s, SB_NEIGH_BRUTE, 0);
  sb_agglo *ga = s->merge ? merging(a) : NULL,
           *gb = s->merge ? merging(b) : NULL,
           *gc = s->merge ? merging(c) : NULL;
  for (int k = 0; k < 3000; k++) {
    ck_assert_int_eq(sb_engine_step(a), SB_SUCCESS);
    ck_assert_int_eq(sb_engine_step(b), SB_SUCCESS);
    ck_assert_int_eq(sb_engine_step(c), SB_SUCCESS);
    if (s->foreign && k % 50 == 49) {
      size_t np;
      const size_t *pp;
      ck_assert_int_eq(sb_engine_neighbours(a, SB_NEIGH_CELLS, NULL, 0.3,
                                            &np, &pp), SB_SUCCESS);
    }
  }
  sbt_assert_same_run(a, b, SBT_SAME_CANDIDATES | SBT_SAME_REDETECTED);
  sbt_assert_same_run(a, c, SBT_SAME_CANDIDATES);
  /* the list was used, and rebuilt as particles moved or changed */
  ck_assert_uint_ge(a->vl.builds, 2);
  ck_assert_uint_gt(a->vl.uses, 500);
  ck_assert_uint_eq(b->vl.uses, 0);
  /* a reinsertion is a jump: the list goes on with a floater */
  if (s->outcome == SB_OUTCOME_REINSERT)
    ck_assert_uint_gt(a->vl.floated, 100);
  sb_engine_stats st;
  sb_engine_get_stats(a, &st);
  sb_engine_free(a);
  sb_engine_free(b);
  sb_engine_free(c);
  sb_agglo_free(ga);
  sb_agglo_free(gb);
  sb_agglo_free(gc);
  return st.ncoll;
}

START_TEST(test_elastic)
{
  setup s = {3, SB_OUTCOME_ELASTIC, SB_DETECT_BALLISTIC, 0, 0, 0};
  ck_assert_uint_gt(run_three(&s), 50);
}
END_TEST

START_TEST(test_reinsert)
{
  setup s = {3, SB_OUTCOME_REINSERT, SB_DETECT_BALLISTIC, 0, 0, 0};
  ck_assert_uint_gt(run_three(&s), 50);
}
END_TEST

START_TEST(test_merge)
{
  setup s = {3, SB_OUTCOME_ELASTIC, SB_DETECT_BALLISTIC, 0, 0, 1};
  ck_assert_uint_gt(run_three(&s), 50);
}
END_TEST

START_TEST(test_overlap_2d)
{
  setup s = {2, SB_OUTCOME_ELASTIC, SB_DETECT_OVERLAP, 0, 0, 0};
  ck_assert_uint_gt(run_three(&s), 50);
  setup t = {2, SB_OUTCOME_REINSERT, SB_DETECT_BALLISTIC, 0, 0, 0};
  ck_assert_uint_gt(run_three(&t), 50);
}
END_TEST

START_TEST(test_sort_and_foreign_search)
{
  setup s = {3, SB_OUTCOME_ELASTIC, SB_DETECT_BALLISTIC, 37, 0, 0};
  ck_assert_uint_gt(run_three(&s), 50);
  setup t = {3, SB_OUTCOME_REINSERT, SB_DETECT_BALLISTIC, 0, 1, 0};
  ck_assert_uint_gt(run_three(&t), 50);
}
END_TEST

/* Threads: 6000 particles in a 30^3 box (phi ~ 12%, ~6000 listed
 * pairs), so that the displacement check and the filter of the list run
 * on 3 threads; the same run as one thread and as the cells at every
 * step. */
static sb_engine *big(int threads, int verlet_off)
{
  sb_engine_params p;
  sb_engine_params_default(&p);
  p.L[0] = p.L[1] = p.L[2] = 30.0;
  p.dt = 0.005;
  p.capacity = 6000;
  p.seed = 11;
  p.outcome = SB_OUTCOME_REINSERT;
  p.threads = threads;
  p.verlet_off = verlet_off;
  /* the list against the cells' own scan, candidate for candidate (the
   * Langevin search, where the list is not used, returns fewer: the same
   * run, tests/test_engine_lsearch.c) */
  p.lsearch_off = 1;
  sb_engine *e = sb_engine_alloc(&p);
  ck_assert_ptr_nonnull(e);
  sb_engine_species sp = {0.5, 1.0, 1.0, sqrt(2.0), 0.0};
  ck_assert_int_eq(sb_engine_add_species(e, &sp, NULL), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_fill_random(e, 0, 0, 6000), SB_SUCCESS);
  return e;
}

START_TEST(test_threads)
{
  sb_engine *a = big(3, 0), *b = big(1, 0), *c = big(1, 1);
  for (int k = 0; k < 300; k++) {
    ck_assert_int_eq(sb_engine_step(a), SB_SUCCESS);
    ck_assert_int_eq(sb_engine_step(b), SB_SUCCESS);
    ck_assert_int_eq(sb_engine_step(c), SB_SUCCESS);
  }
  sbt_assert_same_run(a, b, SBT_SAME_CANDIDATES | SBT_SAME_REDETECTED);
  sbt_assert_same_run(a, c, SBT_SAME_CANDIDATES | SBT_SAME_REDETECTED);
  ck_assert_uint_gt(a->vl.npairs, 4096);
  ck_assert_uint_gt(a->vl.uses, 100);
  ck_assert_uint_gt(a->vl.floated, 10);
  sb_engine_stats st;
  sb_engine_get_stats(a, &st);
  ck_assert_uint_gt(st.ncoll, 100);
  sb_engine_free(a);
  sb_engine_free(b);
  sb_engine_free(c);
}
END_TEST

/* Large steps (|disp| > r/20): the list does not pay and is not used. */
START_TEST(test_not_used_for_long_steps)
{
  setup s = {3, SB_OUTCOME_ELASTIC, SB_DETECT_BALLISTIC, 0, 0, 0};
  sb_engine *a = make(&s, SB_NEIGH_CELLS, 0);
  sb_engine_params p = *sb_engine_get_params(a);
  sb_engine_free(a);
  p.dt = 0.1;
  a = sb_engine_alloc(&p);
  ck_assert_ptr_nonnull(a);
  sb_engine_species sp = {0.5, 1.0, 1.0, sqrt(2.0), 0.0};
  ck_assert_int_eq(sb_engine_add_species(a, &sp, NULL), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_fill_random(a, 0, 0, 400), SB_SUCCESS);
  for (int k = 0; k < 20; k++)
    ck_assert_int_eq(sb_engine_step(a), SB_SUCCESS);
  ck_assert_uint_eq(a->vl.uses, 0);
  ck_assert_uint_eq(a->vl.builds, 0);
  sb_engine_free(a);
}
END_TEST

/* e[0] (list on) and e[1] (list off) made the same run, e[0] collided
 * more than ncoll times, and its list served more than uses steps with
 * at least builds builds. */
static void assert_list_served(sb_engine *const e[2], uint64_t ncoll,
                               uint64_t uses, uint64_t builds)
{
  sbt_assert_same_run(e[0], e[1], SBT_SAME_CANDIDATES | SBT_SAME_REDETECTED);
  sb_engine_stats st;
  sb_engine_get_stats(e[0], &st);
  ck_assert_uint_gt(st.ncoll, ncoll);
  ck_assert_uint_gt(e[0]->vl.uses, uses);
  ck_assert_uint_ge(e[0]->vl.builds, builds);
}

/* A small system (24 particles, fewer than SBI_VERLET_FLOATERS): every
 * particle in turn moves beyond the skin.  The list must be rebuilt once
 * the floater searches outnumber the particles, so the floaters stay few
 * (before, it was never rebuilt and all 24 ended as floaters, each
 * searched at every step); the run is the same as with the list off. */
START_TEST(test_small_system_rebuilds)
{
  setup s = {3, SB_OUTCOME_REINSERT, SB_DETECT_BALLISTIC, 0, 0, 0};
  sb_engine *a = make(&s, SB_NEIGH_CELLS, 0);
  sb_engine_params p = *sb_engine_get_params(a);
  sb_engine_free(a);
  p.L[0] = p.L[1] = p.L[2] = 8.0;  /* phi ~ 2.5% */
  p.capacity = 24;
  sb_engine *e[2];
  for (int v = 0; v < 2; v++) {
    p.verlet_off = v;
    e[v] = sb_engine_alloc(&p);
    ck_assert_ptr_nonnull(e[v]);
    sb_engine_species sp = {0.5, 1.0, 1.0, sqrt(2.0), 0.0};
    ck_assert_int_eq(sb_engine_add_species(e[v], &sp, NULL), SB_SUCCESS);
    ck_assert_int_eq(sb_engine_fill_random(e[v], 0, 0, 24), SB_SUCCESS);
  }
  double floaters = 0.0;
  const int steps = 6000;
  for (int k = 0; k < steps; k++) {
    ck_assert_int_eq(sb_engine_step(e[0]), SB_SUCCESS);
    ck_assert_int_eq(sb_engine_step(e[1]), SB_SUCCESS);
    floaters += (double)e[0]->vl.nfloat;
  }
  assert_list_served(e, 50, 3000, 10);
  ck_assert_double_lt(floaters / steps, 2.0);
  sb_engine_free(e[0]);
  sb_engine_free(e[1]);
}
END_TEST

/* A detector whose answer depends on the draws' order: the contact time
 * of the chords, kept with probability 1/2 (one uniform per candidate
 * pair, in candidate order). */
static int coin_detect(const sb_engine *e, const sb_engine_pair *p,
                       const gsl_rng *r, void *ctx, double *s)
{
  (void)e;
  (void)ctx;
  const double u = gsl_rng_uniform(r);
  const int h = sb_engine_detect_ballistic(p, s);
  return h == 1 && u < 0.5 ? 0 : h;
}

/* The detectors that draw in candidate order (langevin, a custom one)
 * get the list in the cells' order: the same run as with the list off,
 * candidates and re-detections included, through bounces, reinsertions
 * (floaters) and in 2-D; the list is used and rebuilt. */
static void run_ordered(int dim, sb_engine_detect det,
                        sb_engine_outcome outcome, double shrink,
                        double reach, size_t min_pairs)
{
  setup s = {dim, outcome, det == SB_DETECT_CUSTOM ? SB_DETECT_BALLISTIC : det,
             0, 0, 0};
  sb_engine *e[2];
  for (int v = 0; v < 2; v++) {
    e[v] = make(&s, SB_NEIGH_CELLS, v);
    if (shrink != 1.0) {  /* the same particles in a smaller box */
      sb_engine_params p = *sb_engine_get_params(e[v]);
      sb_engine_free(e[v]);
      for (int k = 0; k < 3; k++)
        p.L[k] *= shrink;
      e[v] = sb_engine_alloc(&p);
      ck_assert_ptr_nonnull(e[v]);
      sb_engine_species sp = {0.5, 1.0, 1.0, sqrt(2.0), 0.0};
      ck_assert_int_eq(sb_engine_add_species(e[v], &sp, NULL), SB_SUCCESS);
      ck_assert_int_eq(sb_engine_fill_random(e[v], 0, 0, dim == 2 ? 150 : 400),
                       SB_SUCCESS);
    }
    if (det == SB_DETECT_CUSTOM)
      ck_assert_int_eq(sb_engine_set_detector(e[v], coin_detect, NULL,
                                              reach), SB_SUCCESS);
  }
  uint64_t floated = 0;
  size_t kept = 0;
  for (int k = 0; k < 1500; k++) {
    for (int v = 0; v < 2; v++) {
      const int st = sb_engine_step(e[v]);
      ck_assert_msg(st == SB_SUCCESS, "%s", sb_last_error());
    }
    /* the step's candidates, pair for pair and in order */
    ck_assert_uint_eq(e[0]->npairs, e[1]->npairs);
    ck_assert(!e[0]->npairs ||
              !memcmp(e[0]->pairs, e[1]->pairs,
                      2 * e[0]->npairs * sizeof *e[0]->pairs));
    kept += e[0]->npairs;
  }
  ck_assert_uint_gt(kept, min_pairs);  /* not vacuous */
  floated = e[0]->vl.floated;
  assert_list_served(e, 20, 1000, 2);
  ck_assert_uint_eq(e[1]->vl.uses, 0);
  if (outcome == SB_OUTCOME_REINSERT)
    ck_assert_uint_gt(floated, 20);
  sb_engine_free(e[0]);
  sb_engine_free(e[1]);
}

START_TEST(test_ordered_langevin)
{
  run_ordered(3, SB_DETECT_LANGEVIN, SB_OUTCOME_ELASTIC, 1.0, 0.0, 500);
  run_ordered(3, SB_DETECT_LANGEVIN, SB_OUTCOME_REINSERT, 1.0, 0.0, 500);
  run_ordered(2, SB_DETECT_LANGEVIN, SB_OUTCOME_ELASTIC, 0.6, 0.0, 500);
}
END_TEST

/* With a reach of 1.5 (3 radii) at phi ~ 11% a particle has ~14
 * candidates, in several neighbouring cells: the order of the cells
 * matters (the test fails when the rank of the cell is left out). */
START_TEST(test_ordered_custom)
{
  run_ordered(3, SB_DETECT_CUSTOM, SB_OUTCOME_ELASTIC, 1.0, 0.0, 1000);
  run_ordered(3, SB_DETECT_CUSTOM, SB_OUTCOME_REINSERT, 0.5, 1.5, 1000000);
  run_ordered(3, SB_DETECT_CUSTOM, SB_OUTCOME_ELASTIC, 0.5, 1.5, 1000000);
  run_ordered(2, SB_DETECT_CUSTOM, SB_OUTCOME_REINSERT, 0.6, 1.5, 100000);
}
END_TEST

int main(void)
{
  Suite *s = suite_create("engine_verlet");
  TCase *t = tcase_create("same run");
  tcase_set_timeout(t, 300);
  tcase_add_test(t, test_elastic);
  tcase_add_test(t, test_reinsert);
  tcase_add_test(t, test_merge);
  tcase_add_test(t, test_overlap_2d);
  tcase_add_test(t, test_sort_and_foreign_search);
  tcase_add_test(t, test_not_used_for_long_steps);
  tcase_add_test(t, test_threads);
  tcase_add_test(t, test_small_system_rebuilds);
  tcase_add_test(t, test_ordered_langevin);
  tcase_add_test(t, test_ordered_custom);
  suite_add_tcase(s, t);
  return sbt_run_suite(s);
}
