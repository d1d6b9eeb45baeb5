/* test_engine_reinsert.c — the free-position search of the reinsertion
 * outcome (lib/engine/engine_outcome.c: position_free).
 *
 * With the built-in outcome a trial position is tested inside a step only
 * against the particles the step's neighbour search puts near it
 * (sbi_engine_partners, here from the cells); a user outcome that calls
 * sb_engine_outcome_reinsert tests it against every particle, as outside
 * a step.  Both must accept and reject the same trial positions, so the
 * same seed gives the same run bit for bit.  The boxes are dense (phi = 0.2-0.3), where a uniform
 * trial point overlaps a sphere with probability 1 - exp(-8 phi) ~ 0.8-0.9
 * (excluded volume of radius 2r): most trials are rejected, so a search
 * that misses a neighbour changes the run at once.  Detectors: contact
 * time (3-D, the Verlet list's cells), overlap (2-D) and the Langevin
 * bridge at dt = tau_p (the partner sits at its sampled contact point).
 *
 * With Lees-Edwards images or walls the trial position is tested against
 * the nearest image as the detectors see it: the sliding image across y,
 * and none across a wall (whose direction is drawn within the accessible
 * volume, centres a radius from the walls).
 */
#include <math.h>
#include <stdlib.h>

#include <smolbridge/engine.h>

#include "engine/engine_internal.h"
#include "engine_same.h"
#include "testutil.h"

typedef struct {
  int dim;
  sb_engine_detect detect;
  double L;
  size_t n;
  double dt;
  int steps;
  double B;  /* velocity variance B^2 tau_p / 2 */
} setup;

/* the reference: the same outcome through the user callback */
static int reinsert_fn(sb_engine *e, const sb_engine_pair *p, double s,
                       void *ctx)
{
  (void)ctx;
  return sb_engine_outcome_reinsert(e, p, s);
}

static sb_engine *make(const setup *s, int reference)
{
  sb_engine_params p;
  sb_engine_params_default(&p);
  p.dim = s->dim;
  p.L[0] = p.L[1] = p.L[2] = s->L;
  p.dt = s->dt;
  p.capacity = s->n;
  p.seed = 21;
  p.neigh = SB_NEIGH_CELLS;
  p.detect = s->detect;
  p.outcome = SB_OUTCOME_REINSERT;
  p.sample_every = 10;
  p.threads = 2;
  sb_engine *e = sb_engine_alloc(&p);
  ck_assert_ptr_nonnull(e);
  if (reference)
    ck_assert_int_eq(sb_engine_set_outcome_fn(e, reinsert_fn, NULL),
                     SB_SUCCESS);
  /* r = 0.5, m = 1, tau_p = 1 */
  sb_engine_species sp = {0.5, 1.0, 1.0, s->B, 0.0};
  ck_assert_int_eq(sb_engine_add_species(e, &sp, NULL), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_fill_random(e, 0, 0, s->n), SB_SUCCESS);
  return e;
}

/* the partners from the cells against the scan of all (the same search
 * and candidate order otherwise: the Langevin detector draws along it);
 * returns the collisions */
static uint64_t same_run(const setup *s)
{
  sb_engine *a = make(s, 0), *b = make(s, 1);
  for (int k = 0; k < s->steps; k++) {
    ck_assert_int_eq(sb_engine_step(a), SB_SUCCESS);
    ck_assert_int_eq(sb_engine_step(b), SB_SUCCESS);
  }
  sbt_assert_same_run(a, b, 0);
  ck_assert(a->grid.valid || a->vl.valid);  /* the cells were used */
  sb_engine_stats st;
  sb_engine_get_stats(a, &st);
  sb_engine_free(a);
  sb_engine_free(b);
  return st.ncoll;
}

/* 3-D, 1000 spheres at phi = 0.30, velocity variance 1, contact time
 * (|disp| ~ 0.01 per step: the Verlet list serves the step) */
START_TEST(test_ballistic_3d)
{
  setup s = {3, SB_DETECT_BALLISTIC, 12.0, 1000, 0.005, 150, sqrt(2.0)};
  ck_assert_uint_gt(same_run(&s), 300);
}
END_TEST

/* 2-D, 230 disks at phi = 0.29, overlap detection */
START_TEST(test_overlap_2d)
{
  setup s = {2, SB_DETECT_OVERLAP, 25.0, 230, 0.005, 300, sqrt(2.0)};
  ck_assert_uint_gt(same_run(&s), 100);
}
END_TEST

/* 3-D, 700 spheres at phi = 0.21, the Langevin detector at dt = tau_p
 * (velocity variance 0.045: |disp| ~ 0.5 per step) */
START_TEST(test_langevin)
{
  setup s = {3, SB_DETECT_LANGEVIN, 12.0, 700, 1.0, 6, 0.3};
  ck_assert_uint_gt(same_run(&s), 300);
}
END_TEST

/* A box of side 1 with a big sphere (radius 0.3) near the top face and a
 * small one (radius 0.05) reinserted 3000 times by the outcome, outside a
 * step: the small one lands at least 0.35 from every image of the big one
 * the engine knows, and where the plain periodic image would be (below
 * the bottom face, unshifted) the new rule differs from the old one. */
static sb_engine *pair_box(int lees, int walls)
{
  sb_engine_params p;
  sb_engine_params_default(&p);
  p.L[0] = p.L[1] = p.L[2] = 1.0;
  p.dt = 1e-3;
  p.capacity = 2;
  p.seed = 5;
  p.outcome = SB_OUTCOME_REINSERT;
  sb_engine *e = sb_engine_alloc(&p);
  ck_assert_ptr_nonnull(e);
  if (lees) {
    const double G[3] = {0.5, 0.0, 0.0};
    ck_assert_int_eq(sb_engine_set_fluid(e, SB_FLUID_SHEAR, G), SB_SUCCESS);
    ck_assert_int_eq(sb_engine_set_lees_edwards(e, 1), SB_SUCCESS);
  }
  if (walls)
    ck_assert_int_eq(sb_engine_set_walls(e, 1, SB_WALL_REFLECT,
                                         SB_WALL_REFLECT), SB_SUCCESS);
  sb_engine_species big = {0.3, 1.0, 1.0, 0.0, 0.0};
  sb_engine_species small = {0.05, 1.0, 1.0, 0.0, 0.0};
  ck_assert_int_eq(sb_engine_add_species(e, &big, NULL), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_add_species(e, &small, NULL), SB_SUCCESS);
  /* the big sphere's excluded ball (radius 0.35) crosses the top face
   * with the images on; with walls it stays a radius from them */
  const double xb[3] = {0.5, walls ? 0.65 : 0.85, 0.5};
  const double xs[3] = {0.1, 0.3, 0.1};
  const double u0[3] = {0.0, 0.0, 0.0};
  ck_assert_int_eq(sb_engine_add_particle(e, 0, 0, xb, u0), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_add_particle(e, 1, 0, xs, u0), SB_SUCCESS);
  if (lees)
    e->le_off = 0.37;  /* the image above/below slid by 0.37 along x */
  return e;
}

/* the distance from the small sphere (1) to the big one (0): the sliding
 * image (Lees-Edwards) or no image (walls) across y, periodic otherwise;
 * *plain: the same with plain periodic images */
static double image_dist(const sb_engine *e, int lees, int walls,
                         double *plain)
{
  double d[3], q[3];
  for (int c = 0; c < 3; c++)
    d[c] = q[c] = e->x[3 + c] - e->x[c];
  int n = d[1] > 0.5 ? 1 : (d[1] < -0.5 ? -1 : 0);
  if (walls)
    n = 0;
  if (lees)
    d[0] -= n * e->le_off;
  if (!walls)
    d[1] -= n;
  for (int c = 0; c < 3; c++) {
    if (c != 1)
      d[c] -= floor(d[c] + 0.5);
    q[c] -= floor(q[c] + 0.5);
  }
  *plain = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
  return sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
}

static void reinsert_images(int lees, int walls)
{
  sb_engine *e = pair_box(lees, walls);
  sb_engine_pair pr = {0};
  pr.i = 0;
  pr.j = 1;
  int differ = 0;
  for (int k = 0; k < 3000; k++) {
    ck_assert_int_eq(sb_engine_outcome_reinsert(e, &pr, 0.0), SB_SUCCESS);
    double plain, d = image_dist(e, lees, walls, &plain);
    ck_assert_msg(d >= 0.35, "reinserted at %g from the big sphere's image "
                  "(x = %g %g %g)", d, e->x[3], e->x[4], e->x[5]);
    if (walls)
      ck_assert(e->x[4] >= 0.05 && e->x[4] <= 0.95);
    differ += plain < 0.35;
  }
  /* Lees-Edwards: the plain periodic image (unshifted) would have
   * rejected these, the shadow of the big sphere below the bottom face (a
   * cap of ~0.02 of the box); walls: no image can reach a centre placed a
   * radius from them, so only the accessible volume matters */
  if (lees)
    ck_assert_int_gt(differ, 20);
  sb_engine_free(e);
}

START_TEST(test_images_lees_edwards)
{
  reinsert_images(1, 0);
}
END_TEST

START_TEST(test_images_walls)
{
  reinsert_images(0, 1);
}
END_TEST

int main(void)
{
  Suite *s = suite_create("engine_reinsert");
  TCase *t = tcase_create("same run");
  tcase_set_timeout(t, 300);
  tcase_add_test(t, test_ballistic_3d);
  tcase_add_test(t, test_overlap_2d);
  tcase_add_test(t, test_langevin);
  tcase_add_test(t, test_images_lees_edwards);
  tcase_add_test(t, test_images_walls);
  suite_add_tcase(s, t);
  return sbt_run_suite(s);
}
