/* test_engine_grid.c — particle mass and momentum densities on a grid
 * (lib/engine/engine_grid.c, sb_engine_grid_fields).
 *
 * Independent checks: hand-computed CIC and NGP weights of single
 * particles (cell centre, cell face, across a periodic face, against a
 * wall); the totals sum rho h^dim and sum mom h^dim against the particles'
 * mass and momentum summed directly, 2-D and 3-D, periodic and walled;
 * the family filter; a linear momentum profile u_x = a y reproduced by CIC
 * at the cell centres (the scheme's defining property, for particles on a
 * regular lattice); argument checks.
 */
#include <math.h>
#include <stdlib.h>

#include <smolbridge/engine.h>

#include "testutil.h"

static sb_engine *box(int dim, double L, size_t cap, int walled)
{
  sb_engine_params p;
  sb_engine_params_default(&p);
  p.dim = dim;
  p.L[0] = p.L[1] = p.L[2] = L;
  p.dt = 1e-6;
  p.capacity = cap;
  p.seed = 3;
  p.outcome = SB_OUTCOME_COUNT;
  sb_engine *e = sb_engine_alloc(&p);
  ck_assert_ptr_nonnull(e);
  const double m = 2e-15;
  sb_engine_species s = {1e-7, m, INFINITY, 0.0, 300.0};
  ck_assert_int_eq(sb_engine_add_species(e, &s, NULL), SB_SUCCESS);
  if (walled)
    ck_assert_int_eq(sb_engine_set_walls(e, 0, SB_WALL_REFLECT,
                                         SB_WALL_REFLECT),
                     SB_SUCCESS);
  return e;
}

/* 2-D, 4 x 4 cells of h = 1e-4 m; one particle, CIC weights by hand. */
START_TEST(test_single_particle_weights)
{
  const double L = 4e-4, h = 1e-4, m = 2e-15, A = h * h;
  const size_t n[3] = {4, 4, 1};
  double rho[16], mom[48];
  /* at the centre of cell (1, 2): all of it there, both schemes */
  sb_engine *e = box(2, L, 4, 0);
  const double x1[3] = {1.5 * h, 2.5 * h, 0}, u1[3] = {3.0, -1.0, 0};
  ck_assert_int_eq(sb_engine_add_particle(e, 0, 0, x1, u1), SB_SUCCESS);
  for (int sc = 0; sc < 2; sc++) {
    ck_assert_int_eq(sb_engine_grid_fields(e, n, (sb_engine_grid_scheme)sc,
                                           -1, rho, mom),
                     SB_SUCCESS);
    for (size_t c = 0; c < 16; c++) {
      double want = c == 1 + 4 * 2 ? m / A : 0.0;
      ck_assert_double_eq_tol(rho[c], want, 1e-12 * m / A);
    }
    ck_assert_double_eq_tol(mom[3 * 9], 3.0 * m / A, 1e-12 * m / A);
    ck_assert_double_eq_tol(mom[3 * 9 + 1], -m / A, 1e-12 * m / A);
  }
  sb_engine_free(e);
  /* a quarter of a cell past the centre of (3, 0) in x and y, periodic:
   * x shares 3/4 with column 3 and 1/4 with column 0 (wrapped), y 3/4
   * with row 0 and 1/4 with row 1 */
  e = box(2, L, 4, 0);
  const double x2[3] = {3.75 * h, 0.75 * h, 0}, u0[3] = {0, 0, 0};
  ck_assert_int_eq(sb_engine_add_particle(e, 0, 0, x2, u0), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_grid_fields(e, n, SB_GRID_CIC, -1, rho, NULL),
                   SB_SUCCESS);
  ck_assert_double_eq_tol(rho[3 + 4 * 0], 0.5625 * m / A, 1e-12 * m / A);
  ck_assert_double_eq_tol(rho[0 + 4 * 0], 0.1875 * m / A, 1e-12 * m / A);
  ck_assert_double_eq_tol(rho[3 + 4 * 1], 0.1875 * m / A, 1e-12 * m / A);
  ck_assert_double_eq_tol(rho[0 + 4 * 1], 0.0625 * m / A, 1e-12 * m / A);
  /* NGP: all in cell (3, 0) */
  ck_assert_int_eq(sb_engine_grid_fields(e, n, SB_GRID_NGP, -1, rho, NULL),
                   SB_SUCCESS);
  ck_assert_double_eq_tol(rho[3], m / A, 1e-12 * m / A);
  sb_engine_free(e);
  /* walls in x: the same particle's share beyond x = L folds into
   * column 3 (3/4 + 1/4) */
  e = box(2, L, 4, 1);
  ck_assert_int_eq(sb_engine_add_particle(e, 0, 0, x2, u0), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_grid_fields(e, n, SB_GRID_CIC, -1, rho, NULL),
                   SB_SUCCESS);
  ck_assert_double_eq_tol(rho[3 + 4 * 0], 0.75 * m / A, 1e-12 * m / A);
  ck_assert_double_eq_tol(rho[3 + 4 * 1], 0.25 * m / A, 1e-12 * m / A);
  ck_assert_double_eq_tol(rho[0], 0.0, 1e-12 * m / A);
  sb_engine_free(e);
}
END_TEST

/* Totals equal the direct sums: 1000 random particles with random
 * velocities, 2-D and 3-D, periodic and walled, both schemes, odd grid
 * sizes; and the family filter splits them exactly. */
START_TEST(test_totals)
{
  for (int dim = 2; dim <= 3; dim++)
    for (int walled = 0; walled < 2; walled++) {
      const double L = 1e-3;
      sb_engine *e = box(dim, L, 1000, walled);
      ck_assert_int_eq(sb_engine_fill_random(e, 0, 0, 600), SB_SUCCESS);
      ck_assert_int_eq(sb_engine_fill_random(e, 0, 1, 400), SB_SUCCESS);
      double P[3];
      const double M = 1000 * 2e-15;
      sb_engine_kinetic_energy(e, P);
      const size_t n[3] = {7, 5, 3};
      const size_t nc = dim == 3 ? 105 : 35;
      double *rho = malloc(nc * sizeof *rho), *mom = malloc(3 * nc * sizeof
                                                           *mom);
      double *r1 = malloc(nc * sizeof *r1);
      const double vc = (L / 7) * (L / 5) * (dim == 3 ? L / 3 : 1.0);
      for (int sc = 0; sc < 2; sc++) {
        ck_assert_int_eq(sb_engine_grid_fields(e, n,
                                               (sb_engine_grid_scheme)sc, -1,
                                               rho, mom),
                         SB_SUCCESS);
        double tm = 0, tp[3] = {0, 0, 0};
        for (size_t c = 0; c < nc; c++) {
          ck_assert(rho[c] >= 0.0);
          tm += rho[c] * vc;
          for (int k = 0; k < 3; k++)
            tp[k] += mom[3 * c + k] * vc;
        }
        ck_assert_double_eq_tol(tm, M, 1e-12 * M);
        const double *u = sb_engine_velocities(e);
        double pscale = 0;
        for (size_t i = 0; i < 1000; i++)
          pscale += 2e-15 * fabs(u[3 * i]);
        for (int k = 0; k < dim; k++)
          ck_assert_double_eq_tol(tp[k], P[k], 1e-12 * pscale);
        /* family 1 alone holds 400 of the 1000 masses */
        ck_assert_int_eq(sb_engine_grid_fields(e, n,
                                               (sb_engine_grid_scheme)sc, 1,
                                               r1, NULL),
                         SB_SUCCESS);
        double t1 = 0;
        for (size_t c = 0; c < nc; c++) {
          ck_assert(r1[c] <= rho[c] * (1 + 1e-12));
          t1 += r1[c] * vc;
        }
        ck_assert_double_eq_tol(t1, 0.4 * M, 1e-12 * M);
      }
      free(rho);
      free(mom);
      free(r1);
      sb_engine_free(e);
    }
}
END_TEST

/* CIC reproduces a linear field: particles on a regular lattice offset
 * from the cell centres (4 per cell and direction, 2-D periodic... in y
 * the profile u_x = a (y - L/2) is linear inside the box; compared in the
 * interior rows, where no wrap mixes the two ends), uniform density. */
START_TEST(test_cic_linear_profile)
{
  const double L = 1e-3, a = 1e3;
  const size_t nc = 10, per = 4, np = nc * per;
  sb_engine *e = box(2, L, np * np, 0);
  const double hp = L / (double)np;
  for (size_t i = 0; i < np; i++)
    for (size_t j = 0; j < np; j++) {
      double x[3] = {(i + 0.3) * hp, (j + 0.3) * hp, 0};
      double u[3] = {a * (x[1] - 0.5 * L), 0, 0};
      ck_assert_int_eq(sb_engine_add_particle(e, 0, 0, x, u), SB_SUCCESS);
    }
  const size_t n[3] = {nc, nc, 1};
  double rho[100], mom[300];
  ck_assert_int_eq(sb_engine_grid_fields(e, n, SB_GRID_CIC, -1, rho, mom),
                   SB_SUCCESS);
  const double h = L / (double)nc, rho0 = (double)(np * np) * 2e-15 /
                                           (L * L);
  for (size_t j = 1; j + 1 < nc; j++)
    for (size_t i = 0; i < nc; i++) {
      size_t c = i + nc * j;
      ck_assert_double_eq_tol(rho[c], rho0, 1e-12 * rho0);
      double yc = (j + 0.5) * h;
      /* the lattice's mean y in the CIC window is the cell centre */
      ck_assert_double_eq_tol(mom[3 * c] / rho[c], a * (yc - 0.5 * L),
                              1e-9 * a * L);
    }
  sb_engine_free(e);
}
END_TEST

START_TEST(test_errors)
{
  sb_engine *e = box(3, 1e-3, 4, 0);
  double rho[8];
  size_t n[3] = {2, 2, 2}, bad[3] = {2, 0, 2};
  ck_assert_int_eq(sb_engine_grid_fields(NULL, n, SB_GRID_CIC, -1, rho,
                                         NULL),
                   SB_EINVAL);
  ck_assert_int_eq(sb_engine_grid_fields(e, n, SB_GRID_CIC, -1, NULL, NULL),
                   SB_EINVAL);
  ck_assert_int_eq(sb_engine_grid_fields(e, bad, SB_GRID_CIC, -1, rho, NULL),
                   SB_EINVAL);
  ck_assert_int_eq(sb_engine_grid_fields(e, n, (sb_engine_grid_scheme)7, -1,
                                         rho, NULL),
                   SB_EINVAL);
  /* empty engine: zero fields */
  ck_assert_int_eq(sb_engine_grid_fields(e, n, SB_GRID_NGP, -1, rho, NULL),
                   SB_SUCCESS);
  for (int c = 0; c < 8; c++)
    ck_assert_double_eq(rho[c], 0.0);
  sb_engine_free(e);
}
END_TEST

static Suite *suite(void)
{
  Suite *s = suite_create("engine_grid");
  TCase *tc = tcase_create("grid");
  tcase_add_test(tc, test_single_particle_weights);
  tcase_add_test(tc, test_totals);
  tcase_add_test(tc, test_cic_linear_profile);
  tcase_add_test(tc, test_errors);
  suite_add_tcase(s, tc);
  return s;
}

int main(void) { return sbt_run_suite(suite()); }
