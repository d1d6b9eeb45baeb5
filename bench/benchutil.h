/* benchutil.h — timing helpers shared by the benchmarks in bench/.
 *
 * Header-only (static functions), no dependency beyond POSIX clock_gettime.
 * Every figure is "ns per call": a kernel runs a batch of `ncalls` calls,
 * the batch is timed with CLOCK_MONOTONIC, and the batch is repeated `reps`
 * times; the reported figure is the MEDIAN over repetitions (robust to the
 * odd interruption), with the min and max shown alongside.
 *
 * Usage (the including file must request POSIX before any #include, since
 * the build uses -std=c11, which hides clock_gettime otherwise):
 *
 *   #define _POSIX_C_SOURCE 200809L
 *   #include "benchutil.h"
 *
 *   static void k_exp(void *ctx, size_t n)        // one batch of n calls
 *   {
 *     const sbb_args *a = ctx;
 *     double acc = 0;
 *     for (size_t i = 0; i < n; i++)
 *       acc += exp(a->x[i & a->mask]);            // arguments from an array
 *     sbb_consume(acc);                          // defeat dead-code removal
 *   }
 *   ...
 *   sbb_opts o = sbb_opts_parse(argc, argv);
 *   sbb_table_header(stdout);
 *   sbb_timing t = sbb_run(k_exp, &args, &o);
 *   sbb_table_row(stdout, "exp", &t, NAN);       // NAN goal: no verdict
 *
 * Kernels take their arguments from a pre-generated array (sbb_args), so the
 * compiler cannot hoist the call out of the loop, and feed every result into
 * sbb_consume() (a volatile sink), so it cannot drop the call.
 * Options: --reps N (default 9), --ms T (target milliseconds per batch,
 * default 20), --quick (reps 3, 5 ms), --cpu (time the thread's CPU time
 * instead of the wall clock: for a loaded, shared machine).  Single core: the benchmarks are
 * single-threaded; pin them with `taskset -c 0` for stable figures.
 */
#ifndef SB_BENCHUTIL_H
#define SB_BENCHUTIL_H

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#ifndef CLOCK_MONOTONIC
#error "benchutil.h: define _POSIX_C_SOURCE 200809L before any #include"
#endif

#if defined(__GNUC__)
#define SBB_UNUSED __attribute__((unused))
#else
#define SBB_UNUSED
#endif

/* Results go here so that the optimiser must compute them. */
static volatile double sbb_sink SBB_UNUSED;

static inline void sbb_consume(double v) { sbb_sink += v; }

/* The clock of the timings: CLOCK_MONOTONIC (wall), or with --cpu the
 * calling thread's CPU time, which leaves out the time other processes
 * hold the core on a shared machine (caches they evict still count). */
static clockid_t sbb_clock SBB_UNUSED = CLOCK_MONOTONIC;

/* Nanoseconds on the benchmark clock. */
static inline double sbb_now_ns(void)
{
  struct timespec ts;
  clock_gettime(sbb_clock, &ts);
  return (double)ts.tv_sec * 1e9 + (double)ts.tv_nsec;
}

/* A batch of `ncalls` calls of the code under test. */
typedef void (*sbb_kernel)(void *ctx, size_t ncalls);

typedef struct {
  int reps;          /* timed repetitions (median over them) */
  double target_ms;  /* batch length aimed at by sbb_calibrate */
} sbb_opts;

typedef struct {
  double median, min, max;  /* ns per call */
  size_t ncalls;            /* calls per batch */
  int reps;
} sbb_timing;

static inline sbb_opts sbb_opts_parse(int argc, char **argv)
{
  sbb_opts o = {9, 20.0};
  for (int i = 1; i < argc; i++) {
    if (!strcmp(argv[i], "--reps") && i + 1 < argc)
      o.reps = atoi(argv[++i]);
    else if (!strcmp(argv[i], "--ms") && i + 1 < argc)
      o.target_ms = atof(argv[++i]);
    else if (!strcmp(argv[i], "--cpu"))
      sbb_clock = CLOCK_THREAD_CPUTIME_ID;
    else if (!strcmp(argv[i], "--quick")) {
      o.reps = 3;
      o.target_ms = 5.0;
    }
  }
  if (o.reps < 1)
    o.reps = 1;
  if (!(o.target_ms > 0))
    o.target_ms = 20.0;
  return o;
}

static inline int sbb_cmp_double_(const void *a, const void *b)
{
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

/* Median of v[0..n-1] (sorts v in place). */
static inline double sbb_median(double *v, size_t n)
{
  qsort(v, n, sizeof *v, sbb_cmp_double_);
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/* Smallest power-of-two batch (>= 1024 calls) lasting >= target_ms. */
static inline size_t sbb_calibrate(sbb_kernel k, void *ctx, double target_ms)
{
  size_t n = 1024;
  for (;;) {
    double t0 = sbb_now_ns();
    k(ctx, n);
    double dt = sbb_now_ns() - t0;
    if (dt >= target_ms * 1e6 || n >= ((size_t)1 << 34))
      return n;
    /* jump close to the target, at most x16 at a time */
    double f = dt > 0 ? target_ms * 1e6 / dt : 16.0;
    n *= f > 16.0 ? 16 : (f > 2.0 ? (size_t)f + 1 : 2);
  }
}

/* Time `reps` batches of `ncalls` calls (after one warm-up batch). */
static inline sbb_timing sbb_time(sbb_kernel k, void *ctx, size_t ncalls,
                                  int reps)
{
  sbb_timing t = {NAN, NAN, NAN, ncalls, reps};
  double *v = malloc((size_t)reps * sizeof *v);
  if (!v)
    return t;
  k(ctx, ncalls);  /* warm-up: caches, branch predictors, frequency */
  for (int r = 0; r < reps; r++) {
    double t0 = sbb_now_ns();
    k(ctx, ncalls);
    v[r] = (sbb_now_ns() - t0) / (double)ncalls;
  }
  t.median = sbb_median(v, (size_t)reps);
  t.min = v[0];
  t.max = v[reps - 1];
  free(v);
  return t;
}

/* Calibrate the batch size, then time it. */
static inline sbb_timing sbb_run(sbb_kernel k, void *ctx, const sbb_opts *o)
{
  return sbb_time(k, ctx, sbb_calibrate(k, ctx, o->target_ms), o->reps);
}

/* Pre-generated arguments: `n` (a power of two) values per column, so a
 * kernel indexes them with i & mask.  Columns are filled by the caller. */
#define SBB_MAXCOLS 8
typedef struct {
  size_t n, mask;
  double *col[SBB_MAXCOLS];
} sbb_args;

static inline int sbb_args_alloc(sbb_args *a, size_t log2n, int ncols)
{
  memset(a, 0, sizeof *a);
  a->n = (size_t)1 << log2n;
  a->mask = a->n - 1;
  for (int c = 0; c < ncols && c < SBB_MAXCOLS; c++)
    if (!(a->col[c] = malloc(a->n * sizeof(double))))
      return -1;
  return 0;
}

static inline void sbb_args_free(sbb_args *a)
{
  for (int c = 0; c < SBB_MAXCOLS; c++)
    free(a->col[c]);
  memset(a, 0, sizeof *a);
}

/* ------------------------------------------------------------ printing */

/* First "model name" line of /proc/cpuinfo (or "unknown CPU"). */
static inline void sbb_print_machine(FILE *f)
{
  char line[256], model[256] = "unknown CPU";
  FILE *c = fopen("/proc/cpuinfo", "r");
  if (c) {
    while (fgets(line, sizeof line, c))
      if (!strncmp(line, "model name", 10)) {
        const char *p = strchr(line, ':');
        if (p) {
          snprintf(model, sizeof model, "%s", p + 2);
          model[strcspn(model, "\n")] = 0;
        }
        break;
      }
    fclose(c);
  }
  fprintf(f, "# machine: %s; single thread; median of repeated batches"
             " (%s)\n", model, sbb_clock == CLOCK_MONOTONIC
                                   ? "wall clock" : "thread CPU time");
}

static inline void sbb_table_header(FILE *f)
{
  fprintf(f, "%-40s %10s %21s %9s %s\n", "function", "ns/call",
          "(min .. max)", "goal ns", "verdict");
  fprintf(f, "%-40s %10s %21s %9s %s\n",
          "----------------------------------------", "----------",
          "---------------------", "---------", "-------");
}

/* One row; goal_ns NaN means "for scale" (no verdict).  Returns 1 if the
 * goal is missed, 0 otherwise (so callers can count misses).  A row whose
 * slowest batch took more than 1.5 times its fastest is marked "noisy":
 * another process probably took the core; rerun on a quiet machine (or
 * read the min column). */
static inline int sbb_table_row(FILE *f, const char *name,
                                const sbb_timing *t, double goal_ns)
{
  char mm[64];
  snprintf(mm, sizeof mm, "(%.1f .. %.1f)", t->min, t->max);
  int miss = !isnan(goal_ns) && !(t->median <= goal_ns);
  const char *noisy = t->max > 1.5 * t->min ? " noisy" : "";
  if (isnan(goal_ns))
    fprintf(f, "%-40s %10.1f %21s %9s %s%s\n", name, t->median, mm, "-",
            "(scale)", noisy);
  else
    fprintf(f, "%-40s %10.1f %21s %9.0f %s%s\n", name, t->median, mm,
            goal_ns, miss ? "MISS" : "PASS", noisy);
  return miss;
}

#endif /* SB_BENCHUTIL_H */
