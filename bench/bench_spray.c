/* bench_spray.c — speed of the spray collision operators: collisions per
 * second for the Bird and Nanbu methods (hard spheres and the Maxwell-type
 * kernel) at N = 1e6 particles, and the cost of one time step against N
 * (1e4 ... 1e6; it must grow as O(N): the per-particle cost is printed,
 * and the ratio of the largest to the smallest per-particle cost).
 *
 * Set-up: monodisperse droplets r = 10 um, rho = 1000 kg/m^3, Maxwellian
 * with k_B T/m = 1 m^2/s^2, number density n = 1e9 m^-3 (V = N/n), time
 * step dt such that each particle collides 0.1 times per step on average.
 * CPU time of the thread (CLOCK_THREAD_CPUTIME_ID, robust to other
 * processes on a shared machine) of one sb_spray_collide(dt) call, median
 * of `reps` steps after 3 warm-up steps.  Options: --quick (fewer steps,
 * N up to 2e5).  Single thread.
 *
 * Last section: the cost of one sb_spray_reitz_radius call (the full
 * Reitz model's radius by quadrature and root finding) for a 50 um drop
 * at U = 100 m/s, rho_g = 10 kg/m^3 (V14's set-up), at t = 0.1 ... 20
 * relaxation times tau(a0), the later ones next to the stable radius,
 * where the integrand's rounding is largest. */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_rng.h>

#include <smolbridge/kernel.h>
#include <smolbridge/langevin.h>
#include <smolbridge/spray.h>

#include "benchutil.h"

#define PI 3.14159265358979323846

typedef struct {
  double ns_step, coll_per_s, cand_per_coll;
} result;

static double cpu_ns(void)
{
  struct timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return (double)ts.tv_sec * 1e9 + (double)ts.tv_nsec;
}

static result run(sb_spray_method m, sb_spray_cross c, size_t N, int reps)
{
  result res = {NAN, NAN, NAN};
  const double r = 1e-5, rho = 1000, n = 1e9;
  const double mass = rho * 4.0 / 3.0 * PI * r * r * r;
  const double T = mass / SB_BOLTZMANN;
  const double K = sb_kernel_kinetic(2 * r, 2 * r, mass, mass, T);
  sb_spray_params p;
  sb_spray_params_default(&p);
  p.method = m;
  p.cross = c;
  p.volume = (double)N / n;
  p.rho_l = rho;
  p.B0 = K; /* same mean rate as the hard spheres */
  p.capacity = N;
  sb_spray *s = sb_spray_alloc(&p);
  gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
  if (!s || !rng) {
    sb_spray_free(s);
    gsl_rng_free(rng);
    return res;
  }
  gsl_rng_set(rng, 1);
  sb_spray_add_maxwellian(s, N, r, 1.0, 0, T, NULL, rng);
  const double dt = 0.1 / (n * K);
  for (int k = 0; k < 3; k++)
    sb_spray_collide(s, dt, rng);
  double *t = malloc((size_t)reps * sizeof *t);
  sb_spray_stats a, b;
  sb_spray_get_stats(s, &a);
  double total = 0;
  for (int k = 0; k < reps && t; k++) {
    double t0 = cpu_ns();
    sb_spray_collide(s, dt, rng);
    t[k] = cpu_ns() - t0;
    total += t[k];
  }
  sb_spray_get_stats(s, &b);
  if (t) {
    double coll = (double)(b.bounces - a.bounces);
    res.ns_step = sbb_median(t, (size_t)reps);
    res.coll_per_s = coll / (total * 1e-9);
    res.cand_per_coll = (double)(b.candidates - a.candidates) / coll;
  }
  free(t);
  sb_spray_free(s);
  gsl_rng_free(rng);
  return res;
}

/* CPU time of one sb_spray_reitz_radius call, mean of `reps`, at
 * t = f tau(a0) (section comment at the top). */
static void reitz_radius_cost(int reps)
{
  const double a0 = 50e-6, U = 100.0, rho_g = 10.0, rho_l = 1000.0;
  const sb_spray_liquid liq = {0.072, 1e-3};
  sb_spray_reitz_params rp;
  sb_spray_reitz_params_default(&rp);
  double L0, O0;
  sb_spray_reitz_wave(a0, U, rho_g, rho_l, &liq, &L0, &O0);
  const double tau0 = 3.726 * rp.B1 * a0 / (L0 * O0);
  static const double fs[] = {0.1, 1.0, 2.0, 5.0, 20.0};
  printf("\nsb_spray_reitz_radius, a0 = 50 um, U = 100 m/s: ms per call "
         "(a(t)/a0)\n");
  for (int k = 0; k < 5; k++) {
    double a = NAN, t0 = cpu_ns();
    int st = 0;
    for (int r = 0; r < reps && !st; r++)
      st = sb_spray_reitz_radius(a0, fs[k] * tau0, U, rho_g, rho_l, &liq,
                                 &rp, &a);
    const double ms = (cpu_ns() - t0) / reps * 1e-6;
    printf("  t = %4.1f tau(a0): %10.3f ms (%.6f)%s\n", fs[k], ms, a / a0,
           st ? "  FAILED" : "");
  }
}

int main(int argc, char **argv)
{
  int quick = 0;
  for (int i = 1; i < argc; i++)
    quick |= !strcmp(argv[i], "--quick");
  sbb_print_machine(stdout);
  printf("# times are CPU time of the thread\n");
  printf("# dt: 0.1 collisions per particle per step; n = 1e9 m^-3, r = 10 "
         "um, k_B T/m = 1 m^2/s^2\n");
  static const char *mn[2] = {"bird", "nanbu"}, *cn[2] = {"hard-sphere",
                                                          "maxwell"};
  const size_t Nbig = quick ? 200000 : 1000000;
  printf("\n%-24s %10s %14s %14s %12s\n", "method/kernel", "N",
         "collisions/s", "ns/step", "cand/coll");
  for (int m = 0; m < 2; m++)
    for (int c = 0; c < 2; c++) {
      result r = run((sb_spray_method)m, (sb_spray_cross)c, Nbig,
                     quick ? 3 : 7);
      char name[48];
      snprintf(name, sizeof name, "%s/%s", mn[m], cn[c]);
      printf("%-24s %10zu %14.4g %14.4g %12.2f\n", name, Nbig, r.coll_per_s,
             r.ns_step, r.cand_per_coll);
    }
  printf("\nCost of one step against N (hard spheres): ns per particle per "
         "step\n%-24s", "method");
  const size_t Ns[] = {10000, 100000, 1000000};
  const int nN = quick ? 2 : 3;
  for (int k = 0; k < nN; k++)
    printf(" %12zu", Ns[k]);
  printf(" %10s\n", "max/min");
  for (int m = 0; m < 2; m++) {
    double lo = INFINITY, hi = 0;
    printf("%-24s", mn[m]);
    for (int k = 0; k < nN; k++) {
      result r = run((sb_spray_method)m, SB_SPRAY_HARD_SPHERE, Ns[k],
                     quick ? 3 : 9);
      double per = r.ns_step / (double)Ns[k];
      lo = per < lo ? per : lo;
      hi = per > hi ? per : hi;
      printf(" %12.1f", per);
    }
    printf(" %10.2f\n", hi / lo);
  }
  printf("# O(N) per step: the number of candidates per particle is fixed; "
         "the per-particle cost grows\n# only when the arrays outgrow the "
         "caches (random pair access into ~40 MB at 1e6)\n");
  reitz_radius_cost(quick ? 3 : 10);
  return 0;
}
