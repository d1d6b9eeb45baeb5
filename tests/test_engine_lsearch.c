/* test_engine_lsearch.c — the Langevin search of the cells
 * (lib/engine/engine_neigh.c: lsearch), used with the `langevin` detector
 * in a fully periodic box.
 *
 * Independent check: the same runs with the search switched off
 * (sb_engine_params.lsearch_off: every pair of the linked cells).  The
 * detector skips the pairs whose chords stay beyond sigma + rho before
 * drawing anything, so the runs must agree bit for bit — positions,
 * velocities, collisions, steps, time series; only the candidate count
 * differs, and must be smaller (the search is used) — at dt/tau_p = 1
 * and 30, for a bidisperse mixture, in 2-D, with elastic bounces
 * (re-detection through the cells of the search) and on 3 threads.
 * The search has two queries of its midpoint grid: the stencil
 * (lib/engine/engine_lstencil.c) and the cell-by-cell walk, used where the
 * stencil does not apply (fewer than three cells of the widest window on
 * an axis: the thin box).  A third run of every set-up takes the walk
 * and the stencil without AVX2 on alternate steps (engine->lstencil_off)
 * and must agree with the other two as well.
 * Direct check at every step of the pass-through runs: the candidate
 * list with the search, after the chord test, equals the list of the
 * cells after the same test, pair for pair and in order (the test is
 * the detector's, engine_langevin.c beyond_reach, written out here).
 * Fixed seeds; the criterion is equality.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <smolbridge/engine.h>
#include <smolbridge/engine_firsthit.h>

#include "engine/engine_internal.h"
#include "engine_same.h"
#include "testutil.h"

typedef struct {
  int dim;
  double dt;        /* in units of tau_p */
  double L;         /* box edge */
  size_t n;
  int bidisperse;   /* half the particles r = 1.5, tau = 4 */
  sb_engine_outcome outcome;
  int threads;
  int walls;        /* walls in z: the search must not be used */
  double Lz;        /* box edge in z, if not 0 (a thin box) */
  int walk;         /* the search walks cell by cell (few cells on an
                       axis), not the stencil */
} setup;

/* Spheres r = 0.5, m = 1, tau = 1, B = sqrt 2 (velocity variance 1). */
static sb_engine *make(const setup *s, int off)
{
  sb_engine_params p;
  sb_engine_params_default(&p);
  p.dim = s->dim;
  p.L[0] = p.L[1] = p.L[2] = s->L;
  if (s->Lz > 0.0)
    p.L[2] = s->Lz;
  p.dt = s->dt;
  p.capacity = s->n;
  p.seed = 13;
  p.detect = SB_DETECT_LANGEVIN;
  p.outcome = s->outcome;
  p.sample_every = 5;
  p.threads = s->threads;
  p.lsearch_off = off;
  sb_engine *e = sb_engine_alloc(&p);
  ck_assert_ptr_nonnull(e);
  sb_engine_species a = {0.5, 1.0, 1.0, sqrt(2.0), 0.0};
  sb_engine_species b = {1.5, 27.0, 4.0, 0.5, 0.0};
  ck_assert_int_eq(sb_engine_add_species(e, &a, NULL), SB_SUCCESS);
  if (!(s->Lz > 0.0))  /* the thin box: one species (r_max = 1.5 would
                         set a cut-off beyond half its height) */
    ck_assert_int_eq(sb_engine_add_species(e, &b, NULL), SB_SUCCESS);
  if (s->walls)
    ck_assert_int_eq(sb_engine_set_walls(e, 2, SB_WALL_REFLECT,
                                         SB_WALL_REFLECT), SB_SUCCESS);
  const size_t nb = s->bidisperse ? s->n / 2 : 0;
  ck_assert_int_eq(sb_engine_fill_random(e, 0, 0, s->n - nb), SB_SUCCESS);
  if (nb)
    ck_assert_int_eq(sb_engine_fill_random(e, 1, 0, nb), SB_SUCCESS);
  return e;
}

/* The detector's chord test at the start of the step: 1 if the chord
 * comes within sigma + rho (the pair is examined). */
static int chord_in(const sb_engine *e, size_t i, size_t j)
{
  sb_engine_pair p;
  sbi_engine_make_pair(e, i, j, &p);
  const double lim = p.sigma + e->lreach;
  return sbi_pair_chord_min2(&p) <= lim * lim;
}

/* The candidates of the last search that pass the chord test, and how
 * many there are, into out (2 per pair). */
static size_t chord_list(const sb_engine *e, size_t *out)
{
  size_t m = 0;
  for (size_t q = 0; q < e->npairs; q++) {
    const size_t i = e->pairs[2 * q], j = e->pairs[2 * q + 1];
    if (chord_in(e, i, j)) {
      out[2 * m] = i;
      out[2 * m + 1] = j;
      m++;
    }
  }
  return m;
}

/* Run with the search on (a) and off (b) side by side for `steps` steps;
 * returns a's collisions.  check_lists: compare the chord-filtered
 * candidate lists at every step (pass-through runs: the displacements
 * are those the search saw). */
static uint64_t run_pair(const setup *s, int steps, int check_lists)
{
  sb_engine *a = make(s, 0), *b = make(s, 1), *w = make(s, 0);
  size_t *la = NULL, *lb = NULL, cap = 0, kept = 0;
  for (int k = 0; k < steps; k++) {
    int st = sb_engine_step(a);
    ck_assert_msg(st == SB_SUCCESS, "%s", sb_last_error());
    st = sb_engine_step(b);
    ck_assert_msg(st == SB_SUCCESS, "%s", sb_last_error());
    w->lstencil_off = 1 + (k % 2 && !s->walk);  /* walk, scalar stencil */
    st = sb_engine_step(w);
    ck_assert_msg(st == SB_SUCCESS, "%s", sb_last_error());
    if (!check_lists)
      continue;
    if (b->npairs > cap) {
      cap = b->npairs;
      la = realloc(la, 2 * cap * sizeof *la);
      lb = realloc(lb, 2 * cap * sizeof *lb);
      ck_assert(la && lb);
    }
    ck_assert_uint_le(a->npairs, b->npairs);
    const size_t ma = chord_list(a, la), mb = chord_list(b, lb);
    ck_assert_uint_eq(ma, mb);
    ck_assert(!mb || !memcmp(la, lb, 2 * mb * sizeof *la));
    const size_t mw = chord_list(w, la);
    ck_assert_uint_eq(mw, mb);
    ck_assert(!mb || !memcmp(la, lb, 2 * mb * sizeof *la));
    kept += mb;
  }
  if (check_lists)
    ck_assert_uint_gt(kept, 20 * (size_t)steps);  /* not vacuous */
  free(la);
  free(lb);
  sbt_assert_same_run(a, b, SBT_SAME_REDETECTED);
  sbt_assert_same_run(w, b, SBT_SAME_REDETECTED);
  /* the query used: the stencil, or the walk where it does not apply;
   * w took the other one, or the stencil without AVX2, every other step */
  if (!s->walls) {
    ck_assert_uint_gt(s->walk ? a->lsearch_walk_n : a->lsearch_stencil_n,
                      0);
    ck_assert_uint_eq(s->walk ? a->lsearch_stencil_n : a->lsearch_walk_n,
                      0);
    ck_assert_uint_eq(w->lsearch_walk_n + w->lsearch_stencil_n,
                      a->lsearch_walk_n + a->lsearch_stencil_n);
    if (!s->walk)
      ck_assert(w->lsearch_walk_n > 0 && w->lsearch_stencil_n > 0);
  }
  sb_engine_stats sa, sb;
  sb_engine_get_stats(a, &sa);
  sb_engine_get_stats(b, &sb);
  if (s->walls)  /* not used: the cells' candidates */
    ck_assert_uint_eq(sa.ncand, sb.ncand);
  else  /* used: fewer candidates */
    ck_assert_uint_lt(sa.ncand, sb.ncand);
  sb_engine_free(a);
  sb_engine_free(b);
  sb_engine_free(w);
  return sa.ncoll;
}

START_TEST(test_dt1)
{
  setup s = {3, 1.0, 60.0, 3000, 0, SB_OUTCOME_COUNT, 1, 0, 0.0, 0};
  ck_assert_uint_gt(run_pair(&s, 30, 1), 100);
}
END_TEST

START_TEST(test_dt30)
{
  setup s = {3, 30.0, 280.0, 4000, 0, SB_OUTCOME_COUNT, 1, 0, 0.0, 0};
  ck_assert_uint_gt(run_pair(&s, 6, 1), 100);
}
END_TEST

START_TEST(test_bidisperse)
{
  setup s = {3, 1.0, 60.0, 3000, 1, SB_OUTCOME_COUNT, 1, 0, 0.0, 0};
  ck_assert_uint_gt(run_pair(&s, 30, 1), 100);
  setup t = {3, 10.0, 150.0, 3000, 1, SB_OUTCOME_COUNT, 1, 0, 0.0, 0};
  ck_assert_uint_gt(run_pair(&t, 10, 1), 100);
}
END_TEST

START_TEST(test_2d)
{
  setup s = {2, 1.0, 120.0, 2000, 0, SB_OUTCOME_COUNT, 1, 0, 0.0, 0};
  ck_assert_uint_gt(run_pair(&s, 30, 1), 100);
  setup t = {2, 30.0, 300.0, 2000, 1, SB_OUTCOME_COUNT, 1, 0, 0.0, 0};
  ck_assert_uint_gt(run_pair(&t, 10, 1), 100);
}
END_TEST

/* Dense (phi ~ 10% and 6%): a particle has several partners within
 * reach, in several neighbouring cells, so the order of the cells
 * matters. */
START_TEST(test_dense)
{
  setup s = {3, 0.1, 20.0, 1500, 0, SB_OUTCOME_COUNT, 1, 0, 0.0, 0};
  ck_assert_uint_gt(run_pair(&s, 20, 1), 100);
  setup t = {3, 0.3, 40.0, 1500, 1, SB_OUTCOME_COUNT, 1, 0, 0.0, 0};
  ck_assert_uint_gt(run_pair(&t, 20, 1), 100);
}
END_TEST

/* Bounces: the particles leave their chords inside the step and are
 * re-detected through the cells of the search. */
START_TEST(test_elastic)
{
  setup s = {3, 1.0, 40.0, 3000, 0, SB_OUTCOME_ELASTIC, 1, 0, 0.0, 0};
  ck_assert_uint_gt(run_pair(&s, 40, 0), 100);
  setup t = {3, 10.0, 150.0, 3000, 1, SB_OUTCOME_ELASTIC, 1, 0, 0.0, 0};
  ck_assert_uint_gt(run_pair(&t, 10, 0), 100);
}
END_TEST

/* 6000 particles: the cells scan in parallel without the search. */
START_TEST(test_threads)
{
  setup s = {3, 1.0, 70.0, 6000, 1, SB_OUTCOME_COUNT, 3, 0, 0.0, 0};
  ck_assert_uint_gt(run_pair(&s, 15, 1), 100);
  setup t = s;
  t.threads = 1;
  sb_engine *a = make(&s, 0), *b = make(&t, 0);
  for (int k = 0; k < 15; k++) {
    ck_assert_int_eq(sb_engine_step(a), SB_SUCCESS);
    ck_assert_int_eq(sb_engine_step(b), SB_SUCCESS);
  }
  sbt_assert_same_run(a, b, SBT_SAME_CANDIDATES | SBT_SAME_REDETECTED);
  sb_engine_free(a);
  sb_engine_free(b);
}
END_TEST

/* The first-contact observer around the `langevin` built-in (the
 * built-in itself, observed: engine_firsthit.c), and around a wrapped
 * Langevin detector declared to leave the pairs beyond the chord test
 * alone (sb_engine_set_detector_chord, as V12's harness does): with the
 * search and without it, the same counts and run. */
START_TEST(test_firsthit)
{
  setup s = {3, 1.0, 60.0, 3000, 1, SB_OUTCOME_COUNT, 1, 0, 0.0, 0};
  for (int wrapped = 0; wrapped < 2; wrapped++) {
    sb_engine *e[2];
    sb_engine_firsthit *f[2];
    for (int q = 0; q < 2; q++) {
      e[q] = make(&s, q);
      sb_engine_firsthit_params fp;
      sb_engine_firsthit_params_default(&fp);
      fp.builtin = SB_DETECT_LANGEVIN;
      if (wrapped)
        fp.detect = sb_engine_detect_langevin;
      fp.skip_seen = 1;
      f[q] = sb_engine_firsthit_alloc(&fp);
      ck_assert_ptr_nonnull(f[q]);
      const double rho = sb_engine_langevin_reach(e[q]);
      ck_assert(rho > 0.0);
      ck_assert_int_eq(sb_engine_firsthit_attach(e[q], f[q], rho),
                       SB_SUCCESS);
      if (wrapped)
        ck_assert_int_eq(sb_engine_set_detector_chord(e[q], 1), SB_SUCCESS);
      else
        ck_assert_int_eq(e[q]->par.detect, SB_DETECT_LANGEVIN);
    }
    for (int k = 0; k < 30; k++)
      for (int q = 0; q < 2; q++)
        ck_assert_int_eq(sb_engine_step(e[q]), SB_SUCCESS);
    sbt_assert_same_run(e[0], e[1], SBT_SAME_REDETECTED);
    sb_engine_firsthit_counts c0, c1;
    ck_assert_int_eq(sb_engine_firsthit_get(f[0], SB_ENGINE_FIRSTHIT_ALL,
                                            SB_ENGINE_FIRSTHIT_ALL, &c0),
                     SB_SUCCESS);
    ck_assert_int_eq(sb_engine_firsthit_get(f[1], SB_ENGINE_FIRSTHIT_ALL,
                                            SB_ENGINE_FIRSTHIT_ALL, &c1),
                     SB_SUCCESS);
    ck_assert_uint_gt(c0.hits, 100);
    ck_assert_uint_eq(c0.hits, c1.hits);
    ck_assert_uint_eq(c0.warm, c1.warm);
    sb_engine_stats s0, s1;
    sb_engine_get_stats(e[0], &s0);
    sb_engine_get_stats(e[1], &s1);
    ck_assert_uint_lt(s0.ncand, s1.ncand);  /* used */
    if (wrapped) {  /* only for a custom detector */
      ck_assert_int_eq(sb_engine_set_detect(e[0], SB_DETECT_LANGEVIN),
                       SB_SUCCESS);
      ck_assert_int_ne(sb_engine_set_detector_chord(e[0], 1), SB_SUCCESS);
    }
    for (int q = 0; q < 2; q++) {
      sb_engine_free(e[q]);
      sb_engine_firsthit_free(f[q]);
    }
  }
}
END_TEST

/* A thin box (16 radii high, dt = 0.3 tau_p): under three of the widest
 * windows fit in its height, so the search walks cell by cell. */
START_TEST(test_thin_box)
{
  setup s = {3, 0.3, 40.0, 1000, 0, SB_OUTCOME_COUNT, 1, 0, 8.0, 1};
  ck_assert_uint_gt(run_pair(&s, 10, 1), 100);
}
END_TEST

/* Walls: the chord test does not apply; every pair of the cells. */
START_TEST(test_walls_fall_back)
{
  setup s = {3, 1.0, 60.0, 3000, 0, SB_OUTCOME_COUNT, 1, 1, 0.0, 0};
  ck_assert_uint_gt(run_pair(&s, 10, 0), 10);
}
END_TEST

int main(void)
{
  Suite *s = suite_create("engine_lsearch");
  TCase *t = tcase_create("same run");
  tcase_set_timeout(t, 300);
  tcase_add_test(t, test_dt1);
  tcase_add_test(t, test_dt30);
  tcase_add_test(t, test_bidisperse);
  tcase_add_test(t, test_2d);
  tcase_add_test(t, test_dense);
  tcase_add_test(t, test_elastic);
  tcase_add_test(t, test_threads);
  tcase_add_test(t, test_firsthit);
  tcase_add_test(t, test_thin_box);
  tcase_add_test(t, test_walls_fall_back);
  suite_add_tcase(s, t);
  return sbt_run_suite(s);
}
