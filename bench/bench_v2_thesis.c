/* bench_v2_thesis.c — run time of V2's `--full` thesis-protocol runs
 * (Mohaupt 2011, Table 3.2: phi = 1e-4, L = 100 um, dt = tau_p/10, reinsert
 * outcome, ~500 expected collisions) without making them: each run's CPU
 * time per step, measured over a few thousand steps on one thread after
 * the first list builds, times its exact step count.  The particles stay
 * uniform (random start, uniform reinsertion), so the cost per step is
 * that of the whole run.  docs/validation.md quotes these figures.
 * Options: --quick (fewer steps).
 */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

#include <smolbridge/engine.h>

#include "validate/cases.h"

static double now(void)
{
  struct timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

/* CPU seconds per step of run id over `steps` steps (NAN on failure). */
static double per_step(int id, int steps, size_t *n, double *nsteps)
{
  sb_engine *e;
  if (sbv_v2_thesis_engine(id, n, nsteps, &e))
    return NAN;
  int st = 0;
  for (int k = 0; k < 30 && !st; k++)  /* past the first list builds */
    st = sb_engine_step(e);
  double t0 = now();
  for (int k = 0; k < steps && !st; k++)
    st = sb_engine_step(e);
  const double per = (now() - t0) / steps;
  sb_engine_free(e);
  return st ? NAN : per;
}

int main(int argc, char **argv)
{
  const int quick = argc > 1 && !strcmp(argv[1], "--quick");
  static const double dps[3] = {0.75, 1.0, 2.0};
  printf("bench_v2_thesis: V2 --full thesis runs, single thread, CPU "
         "time\n");
  printf("   %-6s %8s %12s %12s %16s %12s\n", "d_p um", "n", "steps",
         "us/step", "ns/particle-step", "run CPU s");
  double total = 0.0;
  for (int id = 0; id < 3; id++) {
    size_t n;
    double nsteps;
    /* ~0.5-1 s of steps each (the small run's steps are the cheapest) */
    const double per =
        per_step(id, (quick ? 1 : 10) * (id == 2 ? 3000 : 600), &n, &nsteps);
    if (isnan(per)) {
      fprintf(stderr, "bench: %s\n", sb_last_error());
      return 1;
    }
    printf("   %-6.2f %8zu %12.3g %12.2f %16.1f %12.0f\n", dps[id], n,
           nsteps, 1e6 * per, 1e9 * per / (double)n, per * nsteps);
    total += per * nsteps;
  }
  printf("   the three runs: %.0f s of CPU (they run at once on the OpenMP "
         "threads: the wall time is about the largest)\n", total);
  return 0;
}
