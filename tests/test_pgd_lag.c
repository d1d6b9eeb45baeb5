/* test_pgd_lag.c — weighted Lagrangian particles and the Euler-Lagrange
 * domain decomposition of lib/pgd: exact drag motion, injection at the
 * inflow flux, mass and momentum budgets, decompositions that must
 * reproduce the single-domain runs, and decompositions shared between
 * parts (in-memory messages) that must reproduce the one-part run. */
#include <check.h>
#include <float.h>
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

/* A velocity relative to the gas beyond DBL_MAX: the particle at
 * 0.75 DBL_MAX against a gas at -0.75 DBL_MAX, in a square of side 1e10
 * (so that |v|/dx stays a double and sb_pgd_lag_dt is a positive step).
 * The drag move forms v - U_gas: the step is refused with SB_ERANGE and
 * changes nothing, where it used to move the particle to +inf and put
 * inf into the budget.  A relative velocity of DBL_MAX still steps. */
static void huge_gas(sb_pgd_params *p, double ug)
{
  sb_pgd_params_default(p, 2);
  p->nx = p->ny = 6;
  p->L[0] = p->L[1] = 1e10;
  p->tau = 1.0;
  p->ugas[0] = ug;
  for (int s = 0; s < 4; s++)
    p->bc[s] = SB_PGD_OUTFLOW;
}

START_TEST(relative_velocity_overflow)
{
  const double big = 0.75 * DBL_MAX;
  sb_pgd_params p;
  huge_gas(&p, -big);
  sb_pgd_lag *l = sb_pgd_lag_alloc(&p);
  ck_assert_ptr_nonnull(l);
  const sb_pgd_particle q = {1.0, {5e9, 5e9}, {big, 0.0}};
  ck_assert_int_eq(sb_pgd_lag_add(l, &q), SB_SUCCESS);
  const double dt = sb_pgd_lag_dt(l);
  ck_assert(dt > 0 && isfinite(dt));
  ck_assert_int_eq(sb_pgd_lag_step(l, dt), SB_ERANGE);
  ck_assert_ptr_nonnull(strstr(sb_last_error(), "sb_pgd_lag_step"));
  ck_assert_ptr_nonnull(strstr(sb_last_error(), "relative to the gas"));
  ck_assert_uint_eq(sb_pgd_lag_count(l), 1);
  ck_assert(memcmp(sb_pgd_lag_particles(l), &q, sizeof q) == 0);
  ck_assert(sb_pgd_lag_time(l) == 0.0 && sb_pgd_lag_steps(l) == 0);
  double in[3], out[3];
  sb_pgd_lag_boundary_totals(l, in, out);
  for (int k = 0; k < 3; k++)
    ck_assert(in[k] == 0.0 && out[k] == 0.0);
  ck_assert_int_eq(sb_pgd_lag_advance(l, 1.0, NULL), SB_ERANGE);
  sb_pgd_lag_free(l);

  /* relative velocity DBL_MAX (gas at -0.25 DBL_MAX): a double, the step
   * is taken; the new velocity lies between v and U_gas */
  huge_gas(&p, -DBL_MAX / 4);
  l = sb_pgd_lag_alloc(&p);
  ck_assert_int_eq(sb_pgd_lag_add(l, &q), SB_SUCCESS);
  ck_assert_int_eq(sb_pgd_lag_step(l, sb_pgd_lag_dt(l)), SB_SUCCESS);
  ck_assert_uint_eq(sb_pgd_lag_count(l), 1);
  const sb_pgd_particle *r = sb_pgd_lag_particles(l);
  ck_assert(r->v[0] <= big && r->v[0] >= -DBL_MAX / 4);
  ck_assert(isfinite(r->x[0]));
  sb_pgd_lag_free(l);

  /* the particles an inflow injects: rho = 1e-30 keeps their mass and
   * momentum doubles, their velocity minus the gas's is not */
  huge_gas(&p, -big);
  ck_assert_int_eq(sb_pgd_params_add_inflow(&p, SB_PGD_WEST, 2, 2, 1e-30,
                                            big, 0.0),
                   SB_SUCCESS);
  l = sb_pgd_lag_alloc(&p);
  ck_assert_int_eq(sb_pgd_lag_step(l, sb_pgd_lag_dt(l)), SB_ERANGE);
  ck_assert_uint_eq(sb_pgd_lag_count(l), 0);
  sb_pgd_lag_boundary_totals(l, in, out);
  ck_assert(in[0] == 0.0 && sb_pgd_lag_steps(l) == 0);
  sb_pgd_lag_free(l);

  /* the same inflow in a decomposition: its Lagrangian west blocks
   * inject it; the step is refused and no further step is taken */
  sb_pgd_dd *d = sb_pgd_dd_alloc(&p, 3, 3, "LLLLLLLLL");
  ck_assert_ptr_nonnull(d);
  ck_assert_int_eq(sb_pgd_dd_step(d, sb_pgd_dd_dt(d)), SB_ERANGE);
  ck_assert_ptr_nonnull(strstr(sb_last_error(), "relative to the gas"));
  ck_assert_int_eq(sb_pgd_dd_step(d, sb_pgd_dd_dt(d)), SB_EINVAL);
  sb_pgd_dd_free(d);
}
END_TEST

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

/* ------------------------------------------------------------ parts */

/* What a run leaves: fields, totals, budget per side, particles, time. */
typedef struct {
  double f[3][27 * 27];
  double tot[3], in[4][3], out[4][3], t;
  size_t np;
} dd_result;

static void dd_collect(const sb_pgd_dd *d, size_t nn, dd_result *r)
{
  ck_assert_uint_le(nn, 27 * 27);
  ck_assert_int_eq(sb_pgd_dd_fields(d, r->f[0], r->f[1], r->f[2]),
                   SB_SUCCESS);
  sb_pgd_dd_totals(d, r->tot);
  for (int s = 0; s < 4; s++)
    sb_pgd_dd_side_totals(d, (sb_pgd_side)s, r->in[s], r->out[s]);
  r->np = sb_pgd_dd_particles(d);
  r->t = sb_pgd_dd_time(d);
}

/* Message m from every part to every other, as a transport would move
 * them: all packed first, then unpacked (in reverse order of the senders
 * when `rev`, which must not matter). */
static void dd_exchange(sb_pgd_dd **d, int np, sb_pgd_dd_msg m, int rev)
{
  double *buf[9][9] = {{NULL}};
  size_t len[9][9] = {{0}};
  for (int a = 0; a < np; a++)
    for (int b = 0; b < np; b++) {
      size_t n = 0;
      ck_assert_int_eq(sb_pgd_dd_pack(d[a], m, b, NULL, 0, &n), SB_SUCCESS);
      if (a == b)
        ck_assert_uint_eq(n, 0);
      buf[a][b] = malloc((n ? n : 1) * sizeof(double));
      ck_assert_int_eq(sb_pgd_dd_pack(d[a], m, b, buf[a][b], n, &len[a][b]),
                       SB_SUCCESS);
      ck_assert_uint_eq(len[a][b], n);
    }
  for (int k = 0; k < np; k++) {
    int a = rev ? np - 1 - k : k;
    for (int b = 0; b < np; b++)
      if (b != a)
        ck_assert_int_eq(sb_pgd_dd_unpack(d[b], m, a, buf[a][b], len[a][b]),
                         SB_SUCCESS);
  }
  for (int a = 0; a < np; a++)
    for (int b = 0; b < np; b++)
      free(buf[a][b]);
}

/* The run of p on np "virtual ranks" in this process, stepped phase by
 * phase with the exchanges of dd_exchange, then collected on part 0. */
static void dd_run_parts(const sb_pgd_params *p, size_t px, size_t py,
                         const char *kinds, const int *owner, int np,
                         double t_end, int rev, dd_result *r)
{
  sb_pgd_dd *d[9];
  ck_assert_int_le(np, 9);
  for (int k = 0; k < np; k++)
    ck_assert_ptr_nonnull(
        d[k] = sb_pgd_dd_alloc_part(p, px, py, kinds, owner, np, k));
  while (sb_pgd_dd_time(d[0]) < t_end) {
    double dt = INFINITY;
    for (int k = 0; k < np; k++)
      dt = fmin(dt, sb_pgd_dd_dt(d[k]));
    for (int k = 0; k < np; k++)
      ck_assert_int_eq(sb_pgd_dd_begin(d[k], dt, t_end), SB_SUCCESS);
    for (int s = 0; s < sb_pgd_dd_nstages(d[0]); s++) {
      dd_exchange(d, np, SB_PGD_DD_HALO, rev);
      for (int k = 0; k < np; k++)
        ck_assert_int_eq(sb_pgd_dd_stage(d[k]), SB_SUCCESS);
    }
    for (int k = 0; k < np; k++)
      ck_assert_int_eq(sb_pgd_dd_move(d[k]), SB_SUCCESS);
    dd_exchange(d, np, SB_PGD_DD_MIGRATE, rev);
    for (int k = 0; k < np; k++)
      ck_assert_int_eq(sb_pgd_dd_end(d[k]), SB_SUCCESS);
  }
  /* every part at the same time; then part 0 gathers the blocks */
  for (int k = 1; k < np; k++)
    ck_assert(sb_pgd_dd_time(d[k]) == sb_pgd_dd_time(d[0]));
  for (int k = 1; k < np; k++) {
    size_t n = 0;
    ck_assert_int_eq(sb_pgd_dd_pack(d[k], SB_PGD_DD_STATE, 0, NULL, 0, &n),
                     SB_SUCCESS);
    double *b = malloc((n ? n : 1) * sizeof *b);
    ck_assert_int_eq(sb_pgd_dd_pack(d[k], SB_PGD_DD_STATE, 0, b, n, &n),
                     SB_SUCCESS);
    ck_assert_int_eq(sb_pgd_dd_unpack(d[0], SB_PGD_DD_STATE, k, b, n),
                     SB_SUCCESS);
    free(b);
  }
  dd_collect(d[0], p->nx * p->ny, r);
  for (int k = 0; k < np; k++)
    sb_pgd_dd_free(d[k]);
}

static void dd_assert_same(const dd_result *a, const dd_result *b,
                           size_t nn, const char *what)
{
  for (int f = 0; f < 3; f++)
    ck_assert_msg(memcmp(a->f[f], b->f[f], nn * sizeof(double)) == 0,
                  "%s: field %d differs", what, f);
  ck_assert_msg(memcmp(a->tot, b->tot, sizeof a->tot) == 0 &&
                    memcmp(a->in, b->in, sizeof a->in) == 0 &&
                    memcmp(a->out, b->out, sizeof a->out) == 0,
                "%s: totals or budget differ (mass %.17g vs %.17g, out "
                "east %.17g vs %.17g)", what, a->tot[0], b->tot[0],
                a->out[SB_PGD_EAST][0], b->out[SB_PGD_EAST][0]);
  ck_assert_msg(a->np == b->np && a->t == b->t, "%s: %zu vs %zu particles",
                what, a->np, b->np);
}

/* The blocks shared between 2, 3 or 9 parts (contiguous runs, a
 * checkerboard, a part with no block) give the one-part run bit for bit:
 * fields, totals, budget per side, particle count, for all-Eulerian,
 * all-Lagrangian and mixed decompositions whose particles cross block
 * boundaries in both directions (jets at tau = 3 bend towards the gas). */
START_TEST(dd_parts_bitwise)
{
  enum { N = 27 };
  static const char *kinds[] = {"EEEEEEEEE", "LLLLLLLLL", "LELELELEL",
                                "ELLLELLLE", "EEEELEEEE"};
  static const int check2[9] = {0, 1, 0, 1, 0, 1, 0, 1, 0};
  static const int idle[9] = {2, 2, 0, 0, 2, 0, 2, 2, 0}; /* part 1 idle */
  static const int nine[9] = {8, 7, 6, 5, 4, 3, 2, 1, 0};
  static dd_result one, many;
  for (int sc = 0; sc < 2; sc++)
    for (size_t k = 0; k < sizeof kinds / sizeof *kinds; k++) {
      sb_pgd_params p;
      jets(&p, N, 3.0, (sb_pgd_scheme)sc);
      p.ugas[0] = 0.2;
      p.ugas[1] = -0.3;
      sb_pgd_dd *d = sb_pgd_dd_alloc(&p, 3, 3, kinds[k]);
      ck_assert_int_eq(sb_pgd_dd_advance(d, 1.6, NULL), SB_SUCCESS);
      dd_collect(d, N * N, &one);
      sb_pgd_dd_free(d);
      ck_assert_msg(one.tot[0] > 0 && one.out[SB_PGD_EAST][0] > 0 && one.out[SB_PGD_NORTH][0] > 0, "%s: mass %g, out east %g north %g", kinds[k], one.tot[0], one.out[SB_PGD_EAST][0], one.out[SB_PGD_NORTH][0]);
      if (strchr(kinds[k], 'L'))
        ck_assert(one.np > 0);
      int split[9];
      char what[64];
      for (int np = 2; np <= 3; np++) {
        ck_assert_int_eq(sb_pgd_dd_split(9, np, split), SB_SUCCESS);
        dd_run_parts(&p, 3, 3, kinds[k], split, np, 1.6, np == 3, &many);
        snprintf(what, sizeof what, "%s scheme %d, %d parts", kinds[k], sc,
                 np);
        dd_assert_same(&many, &one, N * N, what);
      }
      const int *maps[] = {check2, idle, nine};
      const int nps[] = {2, 3, 9};
      for (int m = 0; m < 3; m++) {
        if (sc == 1 && m == 2)
          continue; /* one part per block: upwind is enough */
        dd_run_parts(&p, 3, 3, kinds[k], maps[m], nps[m], 1.6, 0, &many);
        snprintf(what, sizeof what, "%s scheme %d, map %d", kinds[k], sc, m);
        dd_assert_same(&many, &one, N * N, what);
      }
    }
}
END_TEST

/* Periodic in x with two blocks across it (each block's east and west
 * neighbours are the same block of the other part), a jet entering
 * obliquely from the south so that mass wraps around. */
START_TEST(dd_parts_periodic)
{
  enum { N = 12 };
  static const char *kinds[] = {"ELLE", "EEEE", "LLLL"};
  static const int owner[4] = {0, 1, 1, 0};
  static dd_result one, many;
  for (int sc = 0; sc < 2; sc++)
    for (int k = 0; k < 3; k++) {
      sb_pgd_params p;
      sb_pgd_params_default(&p, 2);
      p.nx = p.ny = N;
      p.scheme = (sb_pgd_scheme)sc;
      p.bc[SB_PGD_WEST] = p.bc[SB_PGD_EAST] = SB_PGD_PERIODIC;
      p.bc[SB_PGD_SOUTH] = p.bc[SB_PGD_NORTH] = SB_PGD_OUTFLOW;
      sb_pgd_params_add_inflow(&p, SB_PGD_SOUTH, 7, 4, 1, 1.5, 1.0);
      sb_pgd_dd *d = sb_pgd_dd_alloc(&p, 2, 2, kinds[k]);
      ck_assert_int_eq(sb_pgd_dd_advance(d, 1.5, NULL), SB_SUCCESS);
      dd_collect(d, N * N, &one);
      sb_pgd_dd_free(d);
      ck_assert(one.out[SB_PGD_NORTH][0] > 0);
      dd_run_parts(&p, 2, 2, kinds[k], owner, 2, 1.5, 0, &many);
      dd_assert_same(&many, &one, N * N, kinds[k]);
    }
}
END_TEST

/* Misuse: phases out of order, a multi-part object stepped as one,
 * malformed messages, bad owner maps. */
START_TEST(dd_parts_errors)
{
  sb_pgd_params p;
  jets(&p, 9, INFINITY, SB_PGD_UPWIND);
  static const int owner[9] = {0, 0, 0, 0, 1, 1, 1, 1, 1};
  static const int bad[9] = {0, 0, 0, 0, 2, 1, 1, 1, 1};
  int split[9];
  ck_assert_ptr_null(sb_pgd_dd_alloc_part(&p, 3, 3, "EEEELEEEE", bad, 2, 0));
  ck_assert_ptr_null(sb_pgd_dd_alloc_part(&p, 3, 3, "EEEELEEEE", NULL, 2, 0));
  ck_assert_ptr_null(sb_pgd_dd_alloc_part(&p, 3, 3, "EEEELEEEE", owner, 2, 2));
  ck_assert_int_eq(sb_pgd_dd_split(9, 10, split), SB_EINVAL);
  ck_assert_int_eq(sb_pgd_dd_split(9, 0, split), SB_EINVAL);
  ck_assert_int_eq(sb_pgd_dd_split(9, 9, split), SB_SUCCESS);
  for (int k = 0; k < 9; k++)
    ck_assert_int_eq(split[k], k);
  sb_pgd_dd *d = sb_pgd_dd_alloc_part(&p, 3, 3, "EEEELEEEE", owner, 2, 1);
  ck_assert_ptr_nonnull(d);
  ck_assert_int_eq(sb_pgd_dd_advance(d, 1, NULL), SB_EINVAL);
  ck_assert_int_eq(sb_pgd_dd_step(d, 1e-3), SB_EINVAL);
  ck_assert_int_eq(sb_pgd_dd_stage(d), SB_EINVAL);
  ck_assert_int_eq(sb_pgd_dd_move(d), SB_EINVAL);
  ck_assert_int_eq(sb_pgd_dd_end(d), SB_EINVAL);
  double dt = sb_pgd_dd_dt(d);
  ck_assert_int_eq(sb_pgd_dd_begin(d, 2 * dt, 1), SB_EINVAL);
  ck_assert_int_eq(sb_pgd_dd_begin(d, dt, 0), SB_EINVAL);
  ck_assert_int_eq(sb_pgd_dd_begin(d, dt, 1), SB_SUCCESS);
  ck_assert_int_eq(sb_pgd_dd_begin(d, dt, 1), SB_EINVAL);
  ck_assert_int_eq(sb_pgd_dd_move(d), SB_EINVAL); /* stage not done */
  size_t n = 0;
  ck_assert_int_eq(sb_pgd_dd_pack(d, SB_PGD_DD_MIGRATE, 0, NULL, 0, &n),
                   SB_EINVAL);
  ck_assert_int_eq(sb_pgd_dd_pack(d, SB_PGD_DD_HALO, 2, NULL, 0, &n),
                   SB_EINVAL);
  ck_assert_int_eq(sb_pgd_dd_pack(d, SB_PGD_DD_HALO, 0, NULL, 0, &n),
                   SB_SUCCESS);
  ck_assert_uint_gt(n, 0); /* block 3 of part 0 borders part 1's 4, 5 */
  double buf[64] = {0};
  ck_assert_int_eq(sb_pgd_dd_pack(d, SB_PGD_DD_HALO, 0, buf, 1, &n),
                   SB_EINVAL);
  ck_assert_int_eq(sb_pgd_dd_unpack(d, SB_PGD_DD_HALO, 0, buf, 3),
                   SB_EFORMAT);
  ck_assert_int_eq(sb_pgd_dd_stage(d), SB_SUCCESS);
  ck_assert_int_eq(sb_pgd_dd_move(d), SB_SUCCESS);
  /* a particle record for a block of part 1 sent as if from part 0 */
  const double rec[3 + 6] = {0, 5, 1, 5, 1.0, 0.5, 0.5, 0, 0};
  ck_assert_int_eq(sb_pgd_dd_unpack(d, SB_PGD_DD_MIGRATE, 0, rec, 9),
                   SB_EFORMAT);
  const double rec2[3 + 6] = {0, 0, 1, 0, 1.0, 0.5, 0.5, 0, 0};
  ck_assert_int_eq(sb_pgd_dd_unpack(d, SB_PGD_DD_MIGRATE, 0, rec2, 9),
                   SB_EFORMAT); /* block 0 is not ours; position outside */
  ck_assert_int_eq(sb_pgd_dd_unpack(d, SB_PGD_DD_MIGRATE, 0, rec2, 5),
                   SB_EFORMAT); /* truncated */
  ck_assert_int_eq(sb_pgd_dd_end(d), SB_SUCCESS);
  ck_assert_int_eq(sb_pgd_dd_pack(d, SB_PGD_DD_STATE, 0, NULL, 0, &n),
                   SB_SUCCESS);
  ck_assert_uint_gt(n, 0);
  sb_pgd_dd_free(d);
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
  tcase_add_test(tc, relative_velocity_overflow);
  suite_add_tcase(s, tc);
  tc = tcase_create("decomposition");
  tcase_set_timeout(tc, 30);
  tcase_add_test(tc, dd_all_euler_bitwise);
  tcase_add_test(tc, dd_all_lagrange);
  tcase_add_test(tc, dd_mixed_conserves);
  suite_add_tcase(s, tc);
  tc = tcase_create("parts");
  tcase_set_timeout(tc, 30);
  tcase_add_test(tc, dd_parts_bitwise);
  tcase_add_test(tc, dd_parts_periodic);
  tcase_add_test(tc, dd_parts_errors);
  suite_add_tcase(s, tc);
  return s;
}

int main(void) { return sbt_run_suite(suite()); }
