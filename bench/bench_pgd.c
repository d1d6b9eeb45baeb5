/* bench_pgd.c — speed of the pressureless-gas module (lib/pgd).
 *
 *  1. Eulerian solver: nanoseconds per cell-update (one Strang step of one
 *     cell, drag included) and cell-updates per second, 1-D (1e5 cells)
 *     and 2-D (256^2, 1024^2; quick: 256^2), both schemes, periodic smooth
 *     data with drag towards a uniform gas.
 *  2. Lagrangian particles: nanoseconds per particle-update (exact drag
 *     move, periodic wrap) for 1e5 and 1e6 particles in a periodic box.
 *  3. The crossing jets (tau = 200) to t = 2 on 135^2 cells (quick 45^2),
 *     with 2 x 2 and 4 x 4 particles per inflow face and step: wall time
 *     all-Euler, all-Lagrange and the coupled decomposition with the
 *     Lagrangian centre block, and their ratios.
 * Median of --reps repetitions (default 5; --quick 3); single thread.
 */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <smolbridge/pgd.h>

#include "benchutil.h"

#define PI 3.14159265358979323846

static void smooth2(double x, double y, double *rho, double u[2], void *d)
{
  (void)d;
  *rho = 1 + 0.5 * sin(2 * PI * x) * cos(2 * PI * y);
  u[0] = 0.5 + 0.2 * sin(2 * PI * y);
  u[1] = -0.3 + 0.2 * cos(2 * PI * x);
}

/* ns per cell-update of `steps` steps on an n x m grid (m = 1: 1-D). */
static double bench_grid(int dim, size_t n, sb_pgd_scheme sc, int steps,
                         int reps)
{
  double v[32];
  for (int r = 0; r < reps && r < 32; r++) {
    sb_pgd_params p;
    sb_pgd_params_default(&p, dim);
    p.nx = n;
    p.ny = dim == 2 ? n : 1;
    p.scheme = sc;
    p.tau = 0.5;
    p.ugas[0] = 0.3;
    p.ugas[1] = 0.1;
    for (int s = 0; s < 4; s++)
      p.bc[s] = SB_PGD_PERIODIC;
    sb_pgd *g = sb_pgd_alloc(&p);
    if (!g)
      return NAN;
    sb_pgd_init(g, smooth2, NULL);
    double dt = 0.9 * sb_pgd_dt(g);
    sb_pgd_step(g, dt); /* warm-up */
    double t0 = sbb_now_ns();
    for (int k = 0; k < steps; k++)
      sb_pgd_step(g, dt);
    v[r] = (sbb_now_ns() - t0) / ((double)steps * (double)(n * p.ny));
    sb_pgd_free(g);
  }
  return sbb_median(v, (size_t)reps);
}

/* ns per particle-update, N particles in a periodic unit box. */
static double bench_particles(size_t N, int steps, int reps)
{
  double v[32];
  for (int r = 0; r < reps && r < 32; r++) {
    sb_pgd_params p;
    sb_pgd_params_default(&p, 2);
    p.tau = 0.5;
    p.ugas[0] = 0.3;
    for (int s = 0; s < 4; s++)
      p.bc[s] = SB_PGD_PERIODIC;
    sb_pgd_lag *l = sb_pgd_lag_alloc(&p);
    if (!l)
      return NAN;
    for (size_t k = 0; k < N; k++) {
      double a = (double)k * 0.6180339887498949, b = (double)k * 0.7548776662;
      sb_pgd_particle q = {1.0 / (double)N,
                           {a - floor(a), b - floor(b)},
                           {cos(6.2831853 * a), sin(6.2831853 * a)}};
      sb_pgd_lag_add(l, &q);
    }
    double dt = sb_pgd_lag_dt(l);
    sb_pgd_lag_step(l, dt);
    double t0 = sbb_now_ns();
    for (int k = 0; k < steps; k++)
      sb_pgd_lag_step(l, dt);
    v[r] = (sbb_now_ns() - t0) / ((double)steps * (double)N);
    sb_pgd_lag_free(l);
  }
  return sbb_median(v, (size_t)reps);
}

static void jets(sb_pgd_params *p, size_t n, size_t inj)
{
  sb_pgd_params_default(p, 2);
  p->nx = p->ny = n;
  p->tau = 200;
  p->inject_time = p->inject_face = inj;
  for (int s = 0; s < 4; s++)
    p->bc[s] = SB_PGD_OUTFLOW;
  size_t w = 5 * n / 45;
  sb_pgd_params_add_inflow(p, SB_PGD_WEST, (n - w) / 2, w, 1, 1, 0);
  sb_pgd_params_add_inflow(p, SB_PGD_SOUTH, (n - w) / 2, w, 1, 0, 1);
}

/* Seconds for the jets to t = 2: kind "euler", "lagrange" or DD kinds. */
static double bench_jets(size_t n, size_t inj, const char *kind, int reps,
                         size_t *nparticles)
{
  double v[32];
  for (int r = 0; r < reps && r < 32; r++) {
    sb_pgd_params p;
    jets(&p, n, inj);
    double t0 = sbb_now_ns();
    if (!strcmp(kind, "euler")) {
      sb_pgd *g = sb_pgd_alloc(&p);
      sb_pgd_advance(g, 2.0, NULL);
      sb_pgd_free(g);
      *nparticles = 0;
    } else if (!strcmp(kind, "lagrange")) {
      sb_pgd_lag *l = sb_pgd_lag_alloc(&p);
      sb_pgd_lag_advance(l, 2.0, NULL);
      *nparticles = sb_pgd_lag_count(l);
      sb_pgd_lag_free(l);
    } else {
      sb_pgd_dd *d = sb_pgd_dd_alloc(&p, 3, 3, kind);
      sb_pgd_dd_advance(d, 2.0, NULL);
      *nparticles = sb_pgd_dd_particles(d);
      sb_pgd_dd_free(d);
    }
    v[r] = (sbb_now_ns() - t0) * 1e-9;
  }
  return sbb_median(v, (size_t)reps);
}

int main(int argc, char **argv)
{
  int quick = 0, reps = 5;
  for (int i = 1; i < argc; i++) {
    if (!strcmp(argv[i], "--quick"))
      quick = 1;
    else if (!strcmp(argv[i], "--reps") && i + 1 < argc)
      reps = atoi(argv[++i]);
  }
  if (quick)
    reps = 3;
  if (reps < 1 || reps > 31)
    reps = 5;
  sbb_print_machine(stdout);
  printf("# pressureless gas dynamics; median of %d repetitions\n\n", reps);
  printf("%-44s %12s %16s\n", "Eulerian solver (drag on, periodic)",
         "ns/update", "cell-updates/s");
  static const char *sn[2] = {"upwind", "muscl"};
  for (int sc = 0; sc < 2; sc++) {
    double t = bench_grid(1, 100000, (sb_pgd_scheme)sc, quick ? 20 : 100,
                          reps);
    char row[64];
    snprintf(row, sizeof row, "1-D, 1e5 cells, %s", sn[sc]);
    printf("%-44s %12.2f %16.3g\n", row, t, 1e9 / t);
  }
  size_t sizes[2] = {256, 1024};
  for (int k = 0; k < (quick ? 1 : 2); k++)
    for (int sc = 0; sc < 2; sc++) {
      double t = bench_grid(2, sizes[k], (sb_pgd_scheme)sc,
                            sizes[k] > 500 ? 5 : 30, reps);
      char row[64];
      snprintf(row, sizeof row, "2-D, %zu^2 cells, %s", sizes[k], sn[sc]);
      printf("%-44s %12.2f %16.3g\n", row, t, 1e9 / t);
    }
  printf("\n%-44s %12s %16s\n", "Lagrangian particles (drag, periodic)",
         "ns/update", "particle-upd./s");
  size_t np[2] = {100000, 1000000};
  for (int k = 0; k < (quick ? 1 : 2); k++) {
    double t = bench_particles(np[k], np[k] > 500000 ? 5 : 20, reps);
    char row[64];
    snprintf(row, sizeof row, "%zu particles", np[k]);
    printf("%-44s %12.2f %16.3g\n", row, t, 1e9 / t);
  }
  size_t n = quick ? 45 : 135;
  const char *kinds[5] = {"euler", "lagrange", "EEEEEEEEE", "LLLLLLLLL",
                          "EEEELEEEE"};
  for (size_t inj = 2; inj <= 4; inj += 2) {
    printf("\ncrossing jets, tau = 200, t = 2, %zu^2 cells, 3 x 3 blocks, "
           "%zu x %zu particles per inflow face and step\n", n, inj, inj);
    printf("%-44s %12s %16s\n", "run", "seconds", "particles at t");
    double secs[5];
    for (int k = 0; k < 5; k++) {
      size_t npart = 0;
      secs[k] = bench_jets(n, inj, kinds[k], quick ? 1 : 3, &npart);
      char row[64];
      snprintf(row, sizeof row, "%s%s", k >= 2 ? "decomposition " : "",
               kinds[k]);
      printf("%-44s %12.3f %16zu\n", row, secs[k], npart);
    }
    printf("coupled EEEELEEEE / all-Lagrange: %.2f (decomposed), %.2f "
           "(single domain)\n", secs[4] / secs[3], secs[4] / secs[1]);
  }
  return 0;
}
