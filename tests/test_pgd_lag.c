/* test_pgd_lag.c — weighted Lagrangian particles and the Euler-Lagrange
 * domain decomposition of lib/pgd: exact drag motion, injection at the
 * inflow flux, mass and momentum budgets, and decompositions that must
 * reproduce the single-domain runs. */
#include <check.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <smolbridge/pgd.h>
#include "testutil.h"

/* The exercise's crossing jets on an n x n grid (n divisible by 3, odd
 * preferred): 5 central inflow cells on the west (velocity (1, 0)) and
 * south (velocity (0, 1)) sides, outflow elsewhere. */
static void jets(sb_pgd_params *p, size_t n, double tau, sb_pgd_scheme sc)
{
  sb_pgd_params_default(p, 2);
  p->nx = p->ny = n;
  p->scheme = sc;
  p->tau = tau;
  for (int s = 0; s < 4; s++)
    p->bc[s] = SB_PGD_OUTFLOW;
  sb_pgd_params_add_inflow(p, SB_PGD_WEST, n / 2 - 2, 5, 1, 1, 0);
  sb_pgd_params_add_inflow(p, SB_PGD_SOUTH, n / 2 - 2, 5, 1, 0, 1);
}

/* One particle in a uniform gas follows the closed form. */
START_TEST(particle_exact_drag)
{
  sb_pgd_params p;
  sb_pgd_params_default(&p, 2);
  p.L[0] = p.L[1] = 100;
  p.origin[0] = p.origin[1] = -50;
  p.tau = 0.7;
  p.ugas[0] = 0.3;
  p.ugas[1] = -0.2;
  sb_pgd_lag *l = sb_pgd_lag_alloc(&p);
  sb_pgd_particle q = {2.0, {0.1, 0.2}, {1.5, 0.5}};
  ck_assert_int_eq(sb_pgd_lag_add(l, &q), SB_SUCCESS);
  ck_assert_int_eq(sb_pgd_lag_advance(l, 3.0, NULL), SB_SUCCESS);
  const sb_pgd_particle *r = sb_pgd_lag_particles(l);
  double e = exp(-3.0 / 0.7), s = 0.7 * (1 - e);
  ck_assert_rel(r->x[0], 0.1 + 0.3 * 3 + (1.5 - 0.3) * s, 1e-13);
  ck_assert_rel(r->x[1], 0.2 - 0.2 * 3 + (0.5 + 0.2) * s, 1e-13);
  ck_assert_rel(r->v[0], 0.3 + 1.2 * e, 1e-13);
  ck_assert_rel(r->v[1], -0.2 + 0.7 * e, 1e-13);
  ck_assert(r->w == 2.0);
  q.x[0] = 60;
  ck_assert_int_eq(sb_pgd_lag_add(l, &q), SB_EDOM);
  sb_pgd_lag_free(l);
  p.dim = 1;
  p.ny = 1;
  ck_assert_ptr_null(sb_pgd_lag_alloc(&p));
}
END_TEST

/* A single jet: the particles carry exactly the injected mass; in the
 * steady state each jet cell holds rho = 1 (the injection lattice spaces
 * particles evenly) and the budget in = inside + out closes. */
START_TEST(jet_injection)
{
  sb_pgd_params p;
  sb_pgd_params_default(&p, 2);
  p.nx = p.ny = 30;
  for (int s = 0; s < 4; s++)
    p.bc[s] = SB_PGD_OUTFLOW;
  p.inject_time = 4;
  p.inject_face = 3;
  sb_pgd_params_add_inflow(&p, SB_PGD_WEST, 12, 5, 1, 1, 0);
  sb_pgd_lag *l = sb_pgd_lag_alloc(&p);
  ck_assert_int_eq(sb_pgd_lag_advance(l, 2.5, NULL), SB_SUCCESS);
  double in[3], out[3], tot[3];
  sb_pgd_lag_boundary_totals(l, in, out);
  sb_pgd_lag_totals(l, tot);
  ck_assert_rel(in[0], 2.5 * 5 / 30.0, 1e-13);
  ck_assert_rel(tot[0] + out[0], in[0], 1e-13);
  ck_assert_rel(tot[0], 5 / 30.0, 1e-13); /* one domain length of jet */
  double rho[900], qx[900];
  sb_pgd_lag_deposit(l, rho, qx, NULL);
  for (size_t j = 0; j < 30; j++)
    for (size_t i = 0; i < 30; i++) {
      int inj = j >= 12 && j < 17;
      ck_assert_abs(rho[i + 30 * j], inj ? 1.0 : 0.0, 1e-12);
      ck_assert_abs(qx[i + 30 * j], inj ? 1.0 : 0.0, 1e-12);
    }
  sb_pgd_lag_free(l);
}
END_TEST

/* Without drag: particles crossing jets conserve mass and momentum:
 * inside + out = in to round-off. */
START_TEST(lag_budget)
{
  sb_pgd_params p;
  jets(&p, 21, INFINITY, SB_PGD_UPWIND);
  sb_pgd_lag *l = sb_pgd_lag_alloc(&p);
  sb_pgd_lag_advance(l, 1.7, NULL);
  double in[3], out[3], tot[3];
  sb_pgd_lag_boundary_totals(l, in, out);
  sb_pgd_lag_totals(l, tot);
  for (int k = 0; k < 3; k++)
    ck_assert_abs(tot[k] + out[k], in[k], 1e-13);
  ck_assert(out[0] > 0);
  sb_pgd_lag_free(l);
}
END_TEST

static void fields_dd(const sb_pgd_dd *d, size_t n, double *r, double *x,
                      double *y)
{
  (void)n;
  sb_pgd_dd_fields(d, r, x, y);
}

/* All-Eulerian 3 x 3 decomposition = the single-domain solver, bit for
 * bit (the same fluxes from the same ghost values), both schemes, drag. */
START_TEST(dd_all_euler_bitwise)
{
  enum { N = 27 };
  for (int sc = 0; sc < 2; sc++) {
    sb_pgd_params p;
    jets(&p, N, 1.0, (sb_pgd_scheme)sc);
    p.ugas[0] = 0.2;
    sb_pgd *g = sb_pgd_alloc(&p);
    sb_pgd_dd *d = sb_pgd_dd_alloc(&p, 3, 3, "EEEEEEEEE");
    ck_assert_ptr_nonnull(d);
    ck_assert_int_eq(sb_pgd_advance(g, 1.2, NULL), SB_SUCCESS);
    ck_assert_int_eq(sb_pgd_dd_advance(d, 1.2, NULL), SB_SUCCESS);
    static double a[3][N * N], b[3][N * N];
    sb_pgd_fields(g, a[0], a[1], a[2]);
    fields_dd(d, N, b[0], b[1], b[2]);
    for (int f = 0; f < 3; f++)
      ck_assert(memcmp(a[f], b[f], sizeof a[f]) == 0);
    double ia[3], oa[3], ib[3], ob[3];
    sb_pgd_boundary_totals(g, ia, oa);
    sb_pgd_dd_boundary_totals(d, ib, ob);
    for (int k = 0; k < 3; k++) {
      ck_assert_rel(ib[k], ia[k], 1e-13);
      ck_assert_abs(ob[k], oa[k], 1e-13 * (1 + fabs(oa[k])));
    }
    sb_pgd_free(g);
    sb_pgd_dd_free(d);
  }
}
END_TEST

/* All-Lagrangian decomposition = the single-domain particles (the same
 * trajectories; only the order of summation in the deposit differs). */
START_TEST(dd_all_lagrange)
{
  enum { N = 27 };
  sb_pgd_params p;
  jets(&p, N, 3.0, SB_PGD_UPWIND);
  p.ugas[1] = 0.1;
  sb_pgd_lag *l = sb_pgd_lag_alloc(&p);
  sb_pgd_dd *d = sb_pgd_dd_alloc(&p, 3, 3, "LLLLLLLLL");
  sb_pgd_lag_advance(l, 1.3, NULL);
  sb_pgd_dd_advance(d, 1.3, NULL);
  ck_assert_uint_eq(sb_pgd_lag_count(l), sb_pgd_dd_particles(d));
  static double a[3][N * N], b[3][N * N];
  sb_pgd_lag_deposit(l, a[0], a[1], a[2]);
  fields_dd(d, N, b[0], b[1], b[2]);
  for (int f = 0; f < 3; f++)
    for (size_t k = 0; k < N * N; k++)
      ck_assert_abs(b[f][k], a[f][k], 1e-13 * (1 + fabs(a[f][k])));
  sb_pgd_lag_free(l);
  sb_pgd_dd_free(d);
}
END_TEST

/* Mixed decompositions move mass and momentum between representations
 * without loss: inside + out = in (no drag), both schemes, and periodic
 * directions across blocks. */
START_TEST(dd_mixed_conserves)
{
  const char *kinds[] = {"EEEELEEEE", "LELELELEL", "ELLLELLLE"};
  for (int sc = 0; sc < 2; sc++)
    for (int k = 0; k < 3; k++) {
      sb_pgd_params p;
      jets(&p, 27, INFINITY, (sb_pgd_scheme)sc);
      sb_pgd_dd *d = sb_pgd_dd_alloc(&p, 3, 3, kinds[k]);
      ck_assert_int_eq(sb_pgd_dd_advance(d, 1.6, NULL), SB_SUCCESS);
      double in[3], out[3], tot[3];
      sb_pgd_dd_boundary_totals(d, in, out);
      sb_pgd_dd_totals(d, tot);
      for (int m = 0; m < 3; m++)
        ck_assert_msg(fabs(tot[m] + out[m] - in[m]) <= 1e-13,
                      "%s scheme %d: component %d: %.17g + %.17g vs %.17g",
                      kinds[k], sc, m, tot[m], out[m], in[m]);
      ck_assert(out[0] > 0 && sb_pgd_dd_particles(d) > 0);
      sb_pgd_dd_free(d);
    }
  /* periodic in x, blocks 3 x 1: a drifting uniform state stays uniform
   * in mass and momentum through Eulerian and Lagrangian blocks */
  sb_pgd_params p;
  sb_pgd_params_default(&p, 2);
  p.nx = 12;
  p.ny = 4;
  p.bc[0] = p.bc[1] = p.bc[2] = p.bc[3] = SB_PGD_PERIODIC;
  sb_pgd_dd *d = sb_pgd_dd_alloc(&p, 3, 1, "ELE");
  ck_assert_ptr_nonnull(d);
  sb_pgd_dd_free(d);
  ck_assert_ptr_null(sb_pgd_dd_alloc(&p, 5, 1, "EEEEE")); /* 12 % 5 */
  ck_assert_ptr_null(sb_pgd_dd_alloc(&p, 3, 1, "EXE"));
}
END_TEST

Suite *suite(void)
{
  Suite *s = suite_create("pgd_lag");
  TCase *tc = tcase_create("particles");
  tcase_set_timeout(tc, 20);
  tcase_add_test(tc, particle_exact_drag);
  tcase_add_test(tc, jet_injection);
  tcase_add_test(tc, lag_budget);
  suite_add_tcase(s, tc);
  tc = tcase_create("decomposition");
  tcase_set_timeout(tc, 30);
  tcase_add_test(tc, dd_all_euler_bitwise);
  tcase_add_test(tc, dd_all_lagrange);
  tcase_add_test(tc, dd_mixed_conserves);
  suite_add_tcase(s, tc);
  return s;
}

int main(void) { return sbt_run_suite(suite()); }
