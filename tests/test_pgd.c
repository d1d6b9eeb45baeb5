/* test_pgd.c — the Eulerian pressureless-gas solver (lib/pgd): parameter
 * checks, conservation, positivity and the maximum principle on u, exact
 * drag relaxation, convergence orders against the exact smooth solution,
 * Riemann problems against the exact solutions, 2-D against 1-D, inflow,
 * outputs. */
#define _POSIX_C_SOURCE 200809L
#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <smolbridge/pgd.h>
#include "testutil.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

START_TEST(params_checked)
{
  sb_pgd_params p;
  sb_pgd_params_default(&p, 2);
  ck_assert_int_eq(sb_pgd_params_check(&p), SB_SUCCESS);
  p.scheme = SB_PGD_MUSCL;
  p.cfl = 0.6; /* MUSCL needs <= 1/2 */
  ck_assert_int_eq(sb_pgd_params_check(&p), SB_EINVAL);
  ck_assert(strstr(sb_last_error(), "cfl") != NULL);
  ck_assert_ptr_null(sb_pgd_alloc(&p));
  p.scheme = SB_PGD_UPWIND;
  ck_assert_int_eq(sb_pgd_params_check(&p), SB_SUCCESS);
  p.bc[SB_PGD_WEST] = SB_PGD_PERIODIC;
  ck_assert_int_eq(sb_pgd_params_check(&p), SB_EINVAL);
  p.bc[SB_PGD_EAST] = SB_PGD_PERIODIC;
  ck_assert_int_eq(sb_pgd_params_check(&p), SB_SUCCESS);
  ck_assert_int_eq(sb_pgd_params_add_inflow(&p, SB_PGD_WEST, 0, 3, 1, 1, 0),
                   SB_EINVAL); /* inflow on a periodic side */
  p.bc[SB_PGD_WEST] = p.bc[SB_PGD_EAST] = SB_PGD_OUTFLOW;
  ck_assert_int_eq(sb_pgd_params_add_inflow(&p, SB_PGD_WEST, 98, 3, 1, 1, 0),
                   SB_EINVAL); /* beyond the side */
  ck_assert_int_eq(sb_pgd_params_add_inflow(&p, SB_PGD_WEST, 10, 3, 1, 1, 0),
                   SB_SUCCESS);
  ck_assert_int_eq(sb_pgd_params_add_inflow(&p, SB_PGD_WEST, 12, 3, 1, 1, 0),
                   SB_EINVAL); /* overlaps */
  ck_assert_uint_eq(p.ninflow, 1);
  p.tau = 0;
  ck_assert_int_eq(sb_pgd_params_check(&p), SB_EINVAL);
  sb_pgd_scheme s;
  ck_assert_int_eq(sb_pgd_scheme_from_name("muscl", &s), SB_SUCCESS);
  ck_assert_int_eq(s, SB_PGD_MUSCL);
  ck_assert_int_eq(sb_pgd_scheme_from_name("weno", &s), SB_EINVAL);
  ck_assert_int_eq(sb_pgd_scheme_from_name("muscl", NULL), SB_SUCCESS);
  ck_assert_int_eq(sb_pgd_scheme_from_name("weno", NULL), SB_EINVAL);
}
END_TEST

/* Pseudo-random data (deterministic, no RNG needed): a smooth base with
 * vacuum patches and sign changes of u. */
static void rough(double x, double y, double *rho, double u[2], void *d)
{
  (void)d;
  double a = sin(12.9898 * x + 78.233 * y) * 43758.5453;
  a -= floor(a);
  double b = sin(39.3468 * x + 11.135 * y) * 24634.6345;
  b -= floor(b);
  *rho = a < 0.2 ? 0.0 : 0.3 + 2 * a;
  u[0] = 2 * b - 1;
  u[1] = cos(7 * x + 3 * y);
}

static sb_pgd *make(int dim, sb_pgd_scheme sc, size_t n, int periodic)
{
  sb_pgd_params p;
  sb_pgd_params_default(&p, dim);
  p.nx = n;
  p.ny = dim == 2 ? n / 2 + 3 : 1;
  p.scheme = sc;
  p.cfl = sc == SB_PGD_MUSCL ? 0.5 : 1.0; /* at the limit */
  if (periodic)
    for (int s = 0; s < 4; s++)
      p.bc[s] = SB_PGD_PERIODIC;
  return sb_pgd_alloc(&p);
}

/* Periodic: mass and momentum exact to round-off; rho >= 0 and each
 * velocity component within its initial range at the CFL limit. */
START_TEST(conservation_positivity)
{
  for (int dim = 1; dim <= 2; dim++)
    for (int sc = 0; sc < 2; sc++) {
      sb_pgd *g = make(dim, (sb_pgd_scheme)sc, 64, 1);
      ck_assert_ptr_nonnull(g);
      ck_assert_int_eq(sb_pgd_init(g, rough, NULL), SB_SUCCESS);
      const sb_pgd_params *p = sb_pgd_get_params(g);
      size_t n = p->nx * p->ny;
      double t0[3], t1[3], lo[2] = {INFINITY, INFINITY},
             hi[2] = {-INFINITY, -INFINITY};
      sb_pgd_totals(g, t0);
      for (size_t j = 0; j < p->ny; j++)
        for (size_t i = 0; i < p->nx; i++) {
          double r, u[2];
          sb_pgd_get_cell(g, i, j, &r, u);
          for (int d = 0; d < 2; d++)
            if (r > p->rho_floor) {
              lo[d] = fmin(lo[d], u[d]);
              hi[d] = fmax(hi[d], u[d]);
            }
        }
      for (int k = 0; k < 60; k++)
        ck_assert_int_eq(sb_pgd_step(g, sb_pgd_dt(g)), SB_SUCCESS);
      sb_pgd_totals(g, t1);
      ck_assert_rel(t1[0], t0[0], 1e-13);
      ck_assert_abs(t1[1], t0[1], 1e-13 * t0[0]);
      ck_assert_abs(t1[2], t0[2], 1e-13 * t0[0]);
      double *rho = malloc(n * sizeof *rho);
      sb_pgd_fields(g, rho, NULL, NULL);
      for (size_t j = 0; j < p->ny; j++)
        for (size_t i = 0; i < p->nx; i++) {
          double r, u[2];
          sb_pgd_get_cell(g, i, j, &r, u);
          ck_assert(r >= 0);
          for (int d = 0; d < dim; d++)
            if (r > p->rho_floor)
              ck_assert_msg(u[d] >= lo[d] - 1e-12 && u[d] <= hi[d] + 1e-12,
                            "dim %d scheme %d: u[%d] = %g outside [%g, %g]",
                            dim, sc, d, u[d], lo[d], hi[d]);
        }
      free(rho);
      sb_pgd_free(g);
    }
}
END_TEST

/* A step longer than the CFL bound is refused. */
START_TEST(cfl_enforced)
{
  sb_pgd *g = make(1, SB_PGD_UPWIND, 50, 1);
  sb_pgd_init(g, rough, NULL);
  double dt = sb_pgd_dt(g);
  ck_assert(dt > 0 && isfinite(dt));
  ck_assert_int_eq(sb_pgd_step(g, 1.01 * dt), SB_EINVAL);
  ck_assert_int_eq(sb_pgd_step(g, dt), SB_SUCCESS);
  ck_assert_int_eq(sb_pgd_advance(g, 0.3, NULL), SB_SUCCESS);
  ck_assert(sb_pgd_time(g) == 0.3);
  sb_pgd_free(g);
}
END_TEST

static void uniform(double x, double y, double *rho, double u[2], void *d)
{
  (void)x, (void)y, (void)d;
  *rho = 1.7;
  u[0] = 0.9;
  u[1] = -0.4;
}

/* Uniform state, uniform gas: u(t) = U + (u0 - U) e^{-t/tau} exactly in
 * every cell, rho unchanged (both schemes, 1-D and 2-D). */
START_TEST(drag_relaxation_exact)
{
  for (int dim = 1; dim <= 2; dim++)
    for (int sc = 0; sc < 2; sc++) {
      sb_pgd_params p;
      sb_pgd_params_default(&p, dim);
      p.nx = 20;
      p.ny = dim == 2 ? 12 : 1;
      p.scheme = (sb_pgd_scheme)sc;
      p.tau = 0.3;
      p.ugas[0] = -0.25;
      p.ugas[1] = 0.6;
      for (int s = 0; s < 4; s++)
        p.bc[s] = SB_PGD_PERIODIC;
      sb_pgd *g = sb_pgd_alloc(&p);
      sb_pgd_init(g, uniform, NULL);
      ck_assert_int_eq(sb_pgd_advance(g, 1.3, NULL), SB_SUCCESS);
      double e = exp(-1.3 / 0.3);
      double ux = -0.25 + (0.9 + 0.25) * e, uy = 0.6 + (-0.4 - 0.6) * e;
      for (size_t j = 0; j < p.ny; j += 5)
        for (size_t i = 0; i < p.nx; i += 3) {
          double r, u[2];
          sb_pgd_get_cell(g, i, j, &r, u);
          ck_assert_rel(r, 1.7, 1e-14);
          ck_assert_rel(u[0], ux, 1e-13);
          if (dim == 2)
            ck_assert_rel(u[1], uy, 1e-13);
        }
      sb_pgd_free(g);
    }
}
END_TEST

/* ------------------------------------------------------------ orders */

static double s_r0(double x, void *d) { (void)d; return 1 + 0.5 * sin(2 * M_PI * x); }
static double s_m0(double x, void *d)
{
  (void)d;
  return x - 0.5 * cos(2 * M_PI * x) / (2 * M_PI);
}
static double s_u0(double x, void *d) { (void)d; return 0.5 + 0.5 * x; }
static void s_init(double x, double y, double *rho, double u[2], void *d)
{
  (void)y, (void)d;
  *rho = s_r0(x, NULL);
  u[0] = s_u0(x, NULL);
  u[1] = 0;
}

/* L1 error on [0, 1] of a run on [-1, 1] (the inflow boundary's influence
 * stays left of 0) to t = 0.5: expanding flow with density extrema. */
static double smooth_l1(sb_pgd_scheme sc, size_t n, double tau)
{
  sb_pgd_smooth s = {s_r0, s_m0, s_u0, NULL, tau, 1.5};
  sb_pgd_params p;
  sb_pgd_params_default(&p, 1);
  p.nx = 2 * n;
  p.L[0] = 2;
  p.origin[0] = -1;
  p.scheme = sc;
  p.cfl = 0.45;
  p.tau = tau;
  p.ugas[0] = 1.5;
  sb_pgd *g = sb_pgd_alloc(&p);
  sb_pgd_init(g, s_init, NULL);
  sb_pgd_advance(g, 0.5, NULL);
  double *rho = malloc(2 * n * sizeof *rho), l1 = 0;
  sb_pgd_fields(g, rho, NULL, NULL);
  for (size_t i = 0; i < n; i++) {
    double m;
    sb_pgd_smooth_integral(&s, 0.5, (double)i / (double)n,
                           (double)(i + 1) / (double)n, &m, NULL);
    l1 += fabs(rho[n + i] / (double)n - m);
  }
  free(rho);
  sb_pgd_free(g);
  return l1;
}

START_TEST(convergence_orders)
{
  for (int drag = 0; drag < 2; drag++) {
    double tau = drag ? 0.3 : INFINITY;
    double u1 = smooth_l1(SB_PGD_UPWIND, 200, tau);
    double u2 = smooth_l1(SB_PGD_UPWIND, 400, tau);
    double m1 = smooth_l1(SB_PGD_MUSCL, 200, tau);
    double m2 = smooth_l1(SB_PGD_MUSCL, 400, tau);
    double ou = log2(u1 / u2), om = log2(m1 / m2);
    ck_assert_msg(ou > 0.9 && ou < 1.1, "upwind order %g (drag %d)", ou, drag);
    ck_assert_msg(om > 1.8 && om < 2.1, "MUSCL order %g (drag %d)", om, drag);
  }
}
END_TEST

/* ------------------------------------------------------------ Riemann */

static void rp_init(double x, double y, double *rho, double u[2], void *d)
{
  (void)y;
  double r, v;
  sb_pgd_riemann_eval(d, x, 0, &r, &v);
  *rho = r;
  u[0] = v;
  u[1] = 0;
}

/* Delta-shock: the scheme conserves the mass that the generalised
 * Rankine-Hugoniot conditions put in the delta; its centroid is within a
 * few cells of x0 + sigma t; both schemes, with and without drag. */
START_TEST(riemann_delta)
{
  sb_pgd_riemann rps[2] = {{0.5, 1, 2, 0.25, -1, INFINITY, 0},
                           {0.5, 1, 1, 1, -1, 0.5, 0.2}};
  for (int c = 0; c < 2; c++)
    for (int sc = 0; sc < 2; sc++) {
      const size_t n = 800;
      const double h = 1.0 / n, T = 0.2;
      sb_pgd_params p;
      sb_pgd_params_default(&p, 1);
      p.nx = n;
      p.scheme = (sb_pgd_scheme)sc;
      p.cfl = 0.45;
      p.tau = rps[c].tau;
      p.ugas[0] = rps[c].ugas;
      sb_pgd *g = sb_pgd_alloc(&p);
      sb_pgd_init(g, rp_init, &rps[c]);
      sb_pgd_advance(g, T, NULL);
      double rho[800], q[800];
      sb_pgd_fields(g, rho, q, NULL);
      sb_pgd_riemann_sol w;
      sb_pgd_riemann_solve(&rps[c], T, &w);
      double M = 0, X = 0;
      for (size_t i = 0; i < n; i++) {
        double x = ((double)i + 0.5) * h;
        if (fabs(x - w.xl) > 0.05)
          continue;
        double bg = x < w.xl ? rps[c].rho_l : rps[c].rho_r;
        M += (rho[i] - bg) * h;
        X += (rho[i] - bg) * h * x;
      }
      X /= M;
      ck_assert_rel(M, w.mass, 1e-6);
      ck_assert_abs(X, w.xl, 3 * h);
      double w1;
      sb_pgd_riemann_error(&rps[c], T, 0, h, n, rho, NULL, &w1);
      ck_assert_msg(w1 < 1e-3, "W1 %g", w1);
      sb_pgd_free(g);
    }
}
END_TEST

/* Vacuum and contact: L1 error shrinks like h^(1/2) (upwind) and
 * h^(2/3) (MUSCL), the rates of linear discontinuities. */
START_TEST(riemann_vacuum_contact)
{
  sb_pgd_riemann rps[2] = {{0.5, 1, -1, 1, 1, INFINITY, 0},
                           {0.5, 1, 0.5, 0.5, 0.5, INFINITY, 0}};
  for (int c = 0; c < 2; c++)
    for (int sc = 0; sc < 2; sc++) {
      double e[2];
      for (int k = 0; k < 2; k++) {
        size_t n = k ? 1600 : 400;
        sb_pgd_params p;
        sb_pgd_params_default(&p, 1);
        p.nx = n;
        p.scheme = (sb_pgd_scheme)sc;
        p.cfl = 0.45;
        sb_pgd *g = sb_pgd_alloc(&p);
        sb_pgd_init(g, rp_init, &rps[c]);
        sb_pgd_advance(g, 0.2, NULL);
        double *rho = malloc(n * sizeof *rho);
        sb_pgd_fields(g, rho, NULL, NULL);
        sb_pgd_riemann_error(&rps[c], 0.2, 0, 1.0 / (double)n, n, rho, &e[k],
                             NULL);
        free(rho);
        sb_pgd_free(g);
      }
      double order = log2(e[0] / e[1]) / 2, want = sc ? 2.0 / 3 : 0.5;
      ck_assert_msg(fabs(order - want) < 0.05, "case %d scheme %d: order %g",
                    c, sc, order);
    }
}
END_TEST

/* A 1-D problem along x or along y of a 2-D grid gives the 1-D answer. */
START_TEST(two_d_matches_one_d)
{
  sb_pgd_riemann rp = {0.37, 1, 2, 0.25, -1, INFINITY, 0};
  for (int sc = 0; sc < 2; sc++) {
    const size_t n = 60;
    sb_pgd_params p;
    sb_pgd_params_default(&p, 1);
    p.nx = n;
    p.scheme = (sb_pgd_scheme)sc;
    sb_pgd *g1 = sb_pgd_alloc(&p);
    sb_pgd_init(g1, rp_init, &rp);
    /* the same step sequence for all three runs */
    double dts[40];
    for (int k = 0; k < 40; k++) {
      dts[k] = sb_pgd_dt(g1);
      sb_pgd_step(g1, dts[k]);
    }
    sb_pgd_params q;
    sb_pgd_params_default(&q, 2);
    q.scheme = p.scheme;
    for (int dir = 0; dir < 2; dir++) {
      q.nx = dir ? 4 : n;
      q.ny = dir ? n : 4;
      sb_pgd *g2 = sb_pgd_alloc(&q);
      for (size_t j = 0; j < q.ny; j++)
        for (size_t i = 0; i < q.nx; i++) {
          double x = ((double)(dir ? j : i) + 0.5) / (double)n, r, u;
          sb_pgd_riemann_integral(&rp, 0, x - 0.5 / n, x + 0.5 / n, &r, NULL);
          sb_pgd_riemann_eval(&rp, x, 0, NULL, &u);
          sb_pgd_set_cell(g2, i, j, r * (double)n, dir ? 0 : u, dir ? u : 0);
        }
      sb_pgd *g1b = sb_pgd_alloc(&p);
      for (size_t i = 0; i < n; i++) {
        double x = ((double)i + 0.5) / (double)n, r, u;
        sb_pgd_riemann_integral(&rp, 0, x - 0.5 / n, x + 0.5 / n, &r, NULL);
        sb_pgd_riemann_eval(&rp, x, 0, NULL, &u);
        sb_pgd_set_cell(g1b, i, 0, r * (double)n, u, 0);
      }
      for (int k = 0; k < 40; k++) {
        ck_assert_int_eq(sb_pgd_step(g1b, dts[k]), SB_SUCCESS);
        ck_assert_int_eq(sb_pgd_step(g2, dts[k]), SB_SUCCESS);
      }
      for (size_t i = 0; i < n; i++) {
        double r1, r2, u1[2], u2[2];
        sb_pgd_get_cell(g1b, i, 0, &r1, u1);
        sb_pgd_get_cell(g2, dir ? 2 : i, dir ? i : 1, &r2, u2);
        ck_assert_rel(r2, r1, 1e-14);
        ck_assert_abs(u2[dir], u1[0], 1e-14);
        ck_assert_abs(u2[1 - dir], 0.0, 0.0);
      }
      sb_pgd_free(g1b);
      sb_pgd_free(g2);
    }
    sb_pgd_free(g1);
  }
}
END_TEST

/* ------------------------------------------------------------ inflow */

/* A jet along x: steady after it crossed the domain; inside rho = 1, u =
 * (1, 0) exactly, outside vacuum; the mass budget in - out balances. */
START_TEST(inflow_jet)
{
  for (int sc = 0; sc < 2; sc++) {
    sb_pgd_params p;
    sb_pgd_params_default(&p, 2);
    p.nx = p.ny = 30;
    p.scheme = (sb_pgd_scheme)sc;
    for (int s = 0; s < 4; s++)
      p.bc[s] = SB_PGD_OUTFLOW;
    ck_assert_int_eq(sb_pgd_params_add_inflow(&p, SB_PGD_WEST, 12, 5, 1, 1, 0),
                     SB_SUCCESS);
    sb_pgd *g = sb_pgd_alloc(&p);
    ck_assert_int_eq(sb_pgd_advance(g, 3.0, NULL), SB_SUCCESS);
    for (size_t j = 0; j < p.ny; j++)
      for (size_t i = 0; i < p.nx; i++) {
        double r, u[2];
        sb_pgd_get_cell(g, i, j, &r, u);
        int in = j >= 12 && j < 17;
        ck_assert_abs(r, in ? 1.0 : 0.0, 1e-12);
        if (in)
          ck_assert_abs(u[0], 1.0, 1e-12);
      }
    double tot[3], in[3], out[3];
    sb_pgd_totals(g, tot);
    sb_pgd_boundary_totals(g, in, out);
    ck_assert_rel(in[0], 3.0 * 5.0 / 30.0, 1e-13);
    ck_assert_rel(tot[0] + out[0], in[0], 1e-13);
    ck_assert_rel(tot[1] + out[1], in[1], 1e-13);
    sb_pgd_free(g);
  }
}
END_TEST

/* Crossing jets are symmetric under x <-> y. */
START_TEST(jets_symmetric)
{
  for (int sc = 0; sc < 2; sc++) {
    sb_pgd_params p;
    sb_pgd_params_default(&p, 2);
    p.nx = p.ny = 21;
    p.scheme = (sb_pgd_scheme)sc;
    p.tau = 1;
    for (int s = 0; s < 4; s++)
      p.bc[s] = SB_PGD_OUTFLOW;
    sb_pgd_params_add_inflow(&p, SB_PGD_WEST, 8, 5, 1, 1, 0);
    sb_pgd_params_add_inflow(&p, SB_PGD_SOUTH, 8, 5, 1, 0, 1);
    sb_pgd *g = sb_pgd_alloc(&p);
    sb_pgd_advance(g, 1.5, NULL);
    for (size_t j = 0; j < p.ny; j++)
      for (size_t i = 0; i < p.nx; i++) {
        double r1, r2, u1[2], u2[2];
        sb_pgd_get_cell(g, i, j, &r1, u1);
        sb_pgd_get_cell(g, j, i, &r2, u2);
        /* the x and y sweeps add in a fixed order: round-off only */
        ck_assert_abs(r1, r2, 1e-13);
        ck_assert_abs(u1[0], u2[1], 1e-12);
      }
    sb_pgd_free(g);
  }
}
END_TEST

START_TEST(outputs)
{
  char path[] = "/tmp/sb_pgd_testXXXXXX";
  int fd = mkstemp(path);
  ck_assert(fd >= 0);
  close(fd);
  sb_pgd_riemann rp = {0.5, 1, 1, 0.5, -1, INFINITY, 0};
  sb_pgd_params p;
  sb_pgd_params_default(&p, 1);
  p.nx = 10;
  sb_pgd *g = sb_pgd_alloc(&p);
  sb_pgd_init(g, rp_init, &rp);
  ck_assert_int_eq(sb_pgd_write_csv(g, path), SB_SUCCESS);
  FILE *f = fopen(path, "r");
  char line[256];
  ck_assert_ptr_nonnull(fgets(line, sizeof line, f));
  ck_assert_str_eq(line, "x,rho,u\n");
  double x, r, u;
  ck_assert_int_eq(fscanf(f, "%lf,%lf,%lf", &x, &r, &u), 3);
  ck_assert_rel(x, 0.05, TOL_TIGHT);
  ck_assert_rel(r, 1.0, TOL_TIGHT);
  ck_assert_rel(u, 1.0, TOL_TIGHT);
  fclose(f);
  ck_assert_int_eq(sb_pgd_write_vtk(g, path), SB_EINVAL); /* 1-D */
  sb_pgd_free(g);
  sb_pgd_params_default(&p, 2);
  p.nx = 3;
  p.ny = 2;
  g = sb_pgd_alloc(&p);
  sb_pgd_set_cell(g, 2, 1, 2.5, 1, -1);
  ck_assert_int_eq(sb_pgd_write_vtk(g, path), SB_SUCCESS);
  f = fopen(path, "r");
  int found = 0;
  while (fgets(line, sizeof line, f))
    found += !strcmp(line, "DIMENSIONS 4 3 1\n") ||
             !strcmp(line, "2.5\n") || !strcmp(line, "1 -1 0\n");
  fclose(f);
  ck_assert_int_eq(found, 3);
  ck_assert_int_eq(sb_pgd_write_csv(g, "/nonexistent/dir/f.csv"), SB_EIO);
  sb_pgd_free(g);
  remove(path);
}
END_TEST

Suite *suite(void)
{
  Suite *s = suite_create("pgd");
  TCase *tc = tcase_create("solver");
  tcase_set_timeout(tc, 20);
  tcase_add_test(tc, params_checked);
  tcase_add_test(tc, conservation_positivity);
  tcase_add_test(tc, cfl_enforced);
  tcase_add_test(tc, drag_relaxation_exact);
  tcase_add_test(tc, two_d_matches_one_d);
  tcase_add_test(tc, inflow_jet);
  tcase_add_test(tc, jets_symmetric);
  tcase_add_test(tc, outputs);
  suite_add_tcase(s, tc);
  tc = tcase_create("accuracy");
  tcase_set_timeout(tc, 30);
  tcase_add_test(tc, convergence_orders);
  tcase_add_test(tc, riemann_delta);
  tcase_add_test(tc, riemann_vacuum_contact);
  suite_add_tcase(s, tc);
  return s;
}

int main(void) { return sbt_run_suite(suite()); }
