/* bench_engine.c — speed of the collision engine.
 *
 *  1. Particle-steps per second vs N = 1e3 ... 1e7 (1e6 with --quick;
 *     N = 1e7 needs ~6 GB) for a dilute Brownian suspension (Mohaupt 2011,
 *     Table 3.2 physics: d_p = 1 um, rho_p = 1000 kg/m^3, T = 296.15 K,
 *     mu = 1.83245e-5 Pa s, dt/tau_p = 0.1, phi = 1e-4, fluid at rest)
 *     with everything on, as smolbridge collide runs it: exact Langevin
 *     step on the keyed streams, linked cells through the Verlet list,
 *     contact-time detection, reinsert outcome.  Goals: >= 2e7
 *     particle-steps/s (<= 50 ns) at N = 1e6 on one core, and the
 *     per-particle cost flat within 1.3x (max/min) from 1e4 to 1e7.
 * 1b. At N = 1e6 (1e5 with --quick), interleaved: the cells rebuilt at
 *     every step (params.verlet_off), the Verlet list (the default), both
 *     on taus2, and the list with the keyed streams (smolbridge collide's
 *     default generator).
 *  3. Threads (OpenMP build): the same suspension at N = 1e6 on the keyed
 *     per-particle streams (params.streams) with 1, 2 and 3 threads, the
 *     thread counts in turns; the median ratio of the rates (goal >= 1.8x
 *     at 2 threads on a 2-core machine).
 *  2. Linked cells vs sort-and-sweep (the neighbour search alone, on the
 *     trial step x -> x + u dt): isotropic Brownian configuration and two
 *     counter-flowing jets along x (Thomine 2008, §5.1), N = 1e5; ratio
 *     sweep/cells of the median times.
 *
 * Figures are medians over repetitions (--reps, default 5; --quick: 3 and
 * smaller N); --threads-only runs section 3 alone.  Pin with `taskset -c 0` for stable numbers.
 */
#define _POSIX_C_SOURCE 200809L
#include "benchutil.h"

#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>

#include <smolbridge/engine.h>
#include <smolbridge/langevin.h>
#include <smolbridge/rng.h>

#define PI 3.14159265358979323846

static sb_engine *brownian_x(size_t n, double phi, unsigned long seed,
                             int streams, int threads, int verlet_off);
static sb_engine *brownian(size_t n, double phi, unsigned long seed)
{
  return brownian_x(n, phi, seed, 0, 0, 0);
}

static sb_engine *brownian_x(size_t n, double phi, unsigned long seed,
                             int streams, int threads, int verlet_off)
{
  const double T = 296.15, mu = 1.83245e-5, rho = 1000.0, d = 1e-6;
  double tau = sb_stokes_tau(rho, d, mu, 1.0), m = sb_sphere_mass(rho, d);
  sb_engine_params p;
  sb_engine_params_default(&p);
  double L = cbrt((double)n * PI * d * d * d / 6.0 / phi);
  p.L[0] = p.L[1] = p.L[2] = L;
  p.dt = 0.1 * tau;
  p.capacity = n;
  p.seed = seed;
  p.outcome = SB_OUTCOME_REINSERT;
  p.sort_every = 20;  /* cache locality (indices change, ids do not) */
  p.rng_type = gsl_rng_taus2;  /* faster Gaussian draws than MT19937 */
  p.streams = streams;
  p.threads = threads;
  p.verlet_off = verlet_off;
  sb_engine *e = sb_engine_alloc(&p);
  if (!e)
    return NULL;
  sb_engine_species s = {0.5 * d, m, tau, sb_brownian_B(T, m, tau), T};
  if (sb_engine_add_species(e, &s, NULL) ||
      sb_engine_fill_random(e, 0, 0, n) || sb_engine_sort(e)) {
    sb_engine_free(e);
    return NULL;
  }
  return e;
}

/* ns per particle-step, median over reps runs of `steps` steps */
static sbb_timing time_steps(sb_engine *e, int steps, int reps)
{
  sbb_timing t = {NAN, NAN, NAN, 0, reps};
  double v[64];
  size_t n = sb_engine_count(e);
  if (reps > 64)
    reps = 64;
  for (int k = 0; k < 2; k++)  /* warm-up */
    sb_engine_step(e);
  for (int r = 0; r < reps; r++) {
    double t0 = sbb_now_ns();
    for (int k = 0; k < steps; k++)
      if (sb_engine_step(e))
        return t;
    v[r] = (sbb_now_ns() - t0) / ((double)n * steps);
  }
  t.median = sbb_median(v, (size_t)reps);
  t.min = v[0];
  t.max = v[reps - 1];
  t.ncalls = n * (size_t)steps;
  return t;
}

/* The machine's own ceiling for the thread speed-up: a loop with no
 * shared data and no memory traffic (keyed normals, six per particle, into
 * a per-thread buffer that stays in L1), in ns per particle on `threads`
 * threads.  On a virtual machine two vCPUs need not be two free cores;
 * this says what two threads can gain here at all. */
static double time_ceiling(size_t n, int threads)
{
  enum { CH = 256 };
  double t0 = sbb_now_ns(), sum = 0.0;
#ifdef _OPENMP
#pragma omp parallel num_threads(threads) reduction(+ : sum)
#endif
  {
    double z[6 * CH];
#ifdef _OPENMP
#pragma omp for schedule(static)
#endif
    for (size_t b = 0; b < n / CH; b++) {
      sb_stream_gaussian_keyed(7, 0, CH, NULL, (uint64_t)(b * CH), 6, z);
      sum += z[b % (6 * CH)];
    }
  }
  (void)threads;
  sbb_consume(sum);
  return (sbb_now_ns() - t0) / (double)n;
}

/* neighbour search alone */
static sbb_timing time_neigh(sb_engine *e, sb_engine_neigh m,
                             const double *disp, int reps, size_t *np)
{
  sbb_timing t = {NAN, NAN, NAN, 0, reps};
  double v[64];
  const size_t *pairs;
  size_t n = sb_engine_count(e);
  if (reps > 64)
    reps = 64;
  sb_engine_neighbours(e, m, disp, 0.0, np, &pairs);
  for (int r = 0; r < reps; r++) {
    double t0 = sbb_now_ns();
    sb_engine_neighbours(e, m, disp, 0.0, np, &pairs);
    v[r] = (sbb_now_ns() - t0) / (double)n;
  }
  t.median = sbb_median(v, (size_t)reps);
  t.min = v[0];
  t.max = v[reps - 1];
  t.ncalls = n;
  return t;
}

int main(int argc, char **argv)
{
  int quick = 0, reps = 5, threads_only = 0;
  for (int i = 1; i < argc; i++) {
    if (!strcmp(argv[i], "--quick"))
      quick = 1;
    else if (!strcmp(argv[i], "--threads-only"))
      threads_only = 1;
    else if (!strcmp(argv[i], "--reps") && i + 1 < argc)
      reps = atoi(argv[++i]);
  }
  if (quick)
    reps = 3;
  if (reps < 1)
    reps = 1;
  sbb_print_machine(stdout);
  int miss = 0;
  if (threads_only)  /* section 3 alone: repeated scaling measurements */
    goto threads;
  printf("# 1. dilute Brownian suspension, phi = 1e-4, dt/tau_p = 0.1, "
         "keyed streams + Verlet list + contact time + reinsert, one "
         "thread (ns per particle-step)\n");
  sbb_table_header(stdout);
  const size_t Ns[5] = {1000, 10000, 100000, 1000000, 10000000};
  int nN = quick ? 3 : 5;
  double per[5] = {NAN, NAN, NAN, NAN, NAN};
  for (int k = 0; k < nN; k++) {
    sb_engine *e = brownian_x(Ns[k], 1e-4, 1 + (unsigned long)k, 1, 1, 0);
    if (!e) {
      fprintf(stderr, "bench_engine: setup failed: %s\n", sb_last_error());
      return 1;
    }
    int steps = (int)(2e6 / (double)Ns[k]);
    if (steps < 2)
      steps = 2;
    sbb_timing t = time_steps(e, steps, reps);
    per[k] = t.median;
    char name[64];
    snprintf(name, sizeof name, "engine step, N = %zu", Ns[k]);
    miss += sbb_table_row(stdout, name, &t, Ns[k] == 1000000 ? 50.0 : NAN);
    sb_engine_free(e);
  }
  double lo = INFINITY, hi = 0;
  for (int k = 1; k < nN; k++) {
    lo = per[k] < lo ? per[k] : lo;
    hi = per[k] > hi ? per[k] : hi;
  }
  printf("# per-particle cost from N = 1e4 to %.0e: max/min = %.2f "
         "(goal <= 1.3); %.3g particle-steps/s at N = 1e6 (goal 2e7)\n",
         (double)Ns[nN - 1], hi / lo, nN > 3 ? 1e9 / per[3] : NAN);

  /* 1b. the same suspension at N = 1e6 (1e5 quick), side by side (A B A B):
   * the Verlet list off (cells at every step) and on, and the keyed
   * streams of smolbridge collide's default (rng = philox) */
  {
    const size_t nb = Ns[quick ? 2 : 3];
    printf("\n# 1b. N = %zu: cells at every step / Verlet list (the "
           "default) / list + keyed streams (collide's default); "
           "interleaved\n", nb);
    sbb_table_header(stdout);
    sb_engine *v[3] = {brownian_x(nb, 1e-4, 5, 0, 1, 1),
                       brownian_x(nb, 1e-4, 5, 0, 1, 0),
                       brownian_x(nb, 1e-4, 5, 1, 1, 0)};
    if (!v[0] || !v[1] || !v[2])
      return 1;
    const char *lab[3] = {"cells every step, taus2", "Verlet list, taus2",
                          "Verlet list, keyed streams"};
    double acc[3][16];
    const int rb = reps < 16 ? reps : 16;
    int steps = (int)(2e6 / (double)nb);
    steps = steps < 2 ? 2 : steps;
    for (int r = 0; r < rb; r++)
      for (int c = 0; c < 3; c++) {
        sbb_timing t = time_steps(v[c], steps, 1);
        acc[c][r] = t.median;
      }
    double med[3];
    for (int c = 0; c < 3; c++) {
      sbb_timing t = {NAN, NAN, NAN, nb * (size_t)steps, rb};
      t.median = med[c] = sbb_median(acc[c], (size_t)rb);
      t.min = acc[c][0];
      t.max = acc[c][rb - 1];
      sbb_table_row(stdout, lab[c], &t, NAN);
      sb_engine_free(v[c]);
    }
    printf("# list speed-up %.2fx; with keyed streams %.2fx (%.3g "
           "particle-steps/s; goal 2e7)\n", med[0] / med[1],
           med[0] / med[2], 1e9 / med[2]);
  }

  printf("\n# 2. neighbour search alone, N = %d (ns per particle)\n",
         quick ? 20000 : 100000);
  sbb_table_header(stdout);
  size_t n = quick ? 20000 : 100000;
  for (int cfg = 0; cfg < 2; cfg++) {
    sb_engine *e = brownian(n, 1e-4, 7);
    if (!e)
      return 1;
    const double *u = sb_engine_velocities(e);
    double dt = sb_engine_get_params(e)->dt;
    double *disp = malloc(3 * n * sizeof *disp);
    gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
    double Lx = sb_engine_get_params(e)->L[0];
    for (size_t i = 0; i < n; i++) {
      double x[3];
      memcpy(x, &sb_engine_positions(e)[3 * i], sizeof x);
      double v[3] = {u[3 * i], u[3 * i + 1], u[3 * i + 2]};
      if (cfg) {
        /* counter-flowing jets along x: two beams in a slab (1% of the
         * box section), |U| = 1 m/s (U dt = 0.3 d), thermal spread kept */
        double U = 1.0;
        v[0] += (i % 2) ? -U : U;
        x[1] = Lx * (0.45 + 0.1 * gsl_rng_uniform(r));
        x[2] = Lx * (0.45 + 0.1 * gsl_rng_uniform(r));
        sb_engine_set_particle(e, i, x, v);
      }
      for (int k = 0; k < 3; k++)
        disp[3 * i + k] = v[k] * dt;
    }
    size_t npc, nps;
    sbb_timing tc = time_neigh(e, SB_NEIGH_CELLS, disp, reps, &npc);
    sbb_timing ts = time_neigh(e, SB_NEIGH_SWEEP, disp, reps, &nps);
    const char *lab = cfg ? "counter-jets" : "isotropic";
    char name[80];
    snprintf(name, sizeof name, "cells, %s (%zu pairs)", lab, npc);
    sbb_table_row(stdout, name, &tc, NAN);
    snprintf(name, sizeof name, "sweep, %s (%zu pairs)", lab, nps);
    sbb_table_row(stdout, name, &ts, NAN);
    printf("# %s: sweep/cells time ratio = %.2f\n", lab,
           ts.median / tc.median);
    free(disp);
    gsl_rng_free(r);
    sb_engine_free(e);
  }
  /* 3. threads: the keyed streams move the particles on every thread
   * (and the results do not depend on the thread count); N = 1e6.  The
   * thread counts take turns (A B C A B C): another process taking a core
   * then spoils one round, not one thread count, and the speed-up is the
   * median of the rounds' ratios */
threads:;
  size_t nt = quick ? 100000 : 1000000;
  printf("\n# 3. threads, N = %zu, phi = 1e-4, keyed streams (ns per "
         "particle-step, wall clock); rounds interleaved\n", nt);
  sbb_table_header(stdout);
  {
    enum { NTH = 3 };
    sb_engine *th[NTH];
    for (int c = 0; c < NTH; c++)
      if (!(th[c] = brownian_x(nt, 1e-4, 11, 1, c + 1, 0)))
        return 1;
    const int rb = reps < 16 ? reps : 16;
    double acc[NTH][16], ratio[NTH][16], ceil1[16], ceil2[16];
    for (int r = 0; r < rb; r++) {
      for (int c = 0; c < NTH; c++)
        acc[c][r] = time_steps(th[c], quick ? 5 : 4, 1).median;
      ceil1[r] = time_ceiling(nt, 1);
      ceil2[r] = time_ceiling(nt, 2);
      ceil1[r] /= ceil2[r];  /* the round's ceiling ratio */
    }
    const double ceiling = sbb_median(ceil1, (size_t)rb);
    for (int c = 0; c < NTH; c++)
      for (int r = 0; r < rb; r++)
        ratio[c][r] = acc[0][r] / acc[c][r];
    for (int c = 0; c < NTH; c++) {
      sbb_timing t = {NAN, NAN, NAN, nt * (size_t)(quick ? 5 : 4), rb};
      double sorted[16];
      memcpy(sorted, acc[c], (size_t)rb * sizeof *sorted);
      t.median = sbb_median(sorted, (size_t)rb);
      t.min = sorted[0];
      t.max = sorted[rb - 1];
      char name[80];
      snprintf(name, sizeof name, "keyed streams, %d thread%s", c + 1,
               c ? "s" : "");
      sbb_table_row(stdout, name, &t, NAN);
      if (c)
        printf("# %d threads: %.2fx the 1-thread rate (median of %d "
               "rounds; %.3g particle-steps/s)%s\n", c + 1,
               sbb_median(ratio[c], (size_t)rb), rb, 1e9 / t.median,
               c == 1 ? "; goal >= 1.8x" : "");
      if (c == 1)
        printf("# machine ceiling: a compute-bound loop with no shared "
               "memory (keyed normals) runs %.2fx its 1-thread rate on 2 "
               "threads in the same rounds; the engine's speed-up is %.0f%% "
               "of it\n", ceiling,
               100.0 * sbb_median(ratio[c], (size_t)rb) / ceiling);
      sb_engine_free(th[c]);
    }
  }
  return miss ? 0 : 0;  /* figures, not a pass/fail test */
}
