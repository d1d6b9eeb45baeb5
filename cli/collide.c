/* collide.c — `smolbridge collide CONFIG.ini [--set SECTION.KEY=VALUE]...`:
 * read the configuration (collide_ini.c), build the engine
 * (collide_setup.c), run it with progress on stderr, write the outputs
 * (collide_out.c).  Exit status: 0 done, 1 run or write error, 2 usage or
 * input error (the configuration, an unwritable output). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <smolbridge/engine.h>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "cli.h"
#include "collide.h"
#include "par.h"

static void usage(FILE *f)
{
  fprintf(f,
"Usage: smolbridge collide CONFIG.ini [--set SECTION.KEY=VALUE]...\n"
"                         [--threads N] [--sweep FILE]\n"
"       smolbridge collide --help\n"
"\n"
"Run the Lagrangian collision engine described by CONFIG.ini (INI: [section]\n"
"headers, key = value lines, comments start a line with ';' or '#', or\n"
"follow a value after ' ;').  --set overrides or adds one key after the\n"
"file is read (species.NAME.KEY for [species NAME]); summary.json records\n"
"the overrides.  Writes into the directory `output` (files of an earlier\n"
"run there are removed first): series.csv (t, collisions, kernel and its\n"
"95%% interval, energy, momentum, per-pair kernels), summary.json, and as\n"
"asked snap_NNNNNN.csv, sizes.csv (merge | dlvo), hits.csv (hit_times),\n"
"manifest.txt (the files of the run).  Progress and warnings go to stderr.\n"
"--sweep FILE runs one point per line of FILE (whitespace-separated\n"
"SECTION.KEY=VALUE overrides after the --set ones; '#' starts a comment)\n"
"into OUTPUT/point_NNN/ and writes OUTPUT/sweep.csv (one row per point:\n"
"status, particles, collisions, kernel and its 95%% interval); under\n"
"mpirun (a build with --with-mpi) the points are shared by the ranks\n"
"(docs/parallel.md).\n"
"--threads N (or OMP_NUM_THREADS=N) sets the threads of the engine's\n"
"parallel parts; the outputs do not depend on it ([run] rng = philox\n"
"also moves the particles in parallel; docs/engine.md).\n"
"Exit status: 0 done, 1 run or write error, 2 usage or input error.\n"
"Theory and every key: docs/engine.md §9; examples: examples/*.ini.\n"
"\n"
"Sections and keys (unit, default, valid values):\n");
  col_print_keys(f);
}

static int progress_step(col_run *r, const col_config *c, double t_stop,
                         col_pairs *ps, int verbose)
{
  sb_engine *e = r->e;
  const double dt = sb_engine_get_params(e)->dt, t0 = sb_engine_time(e);
  double last = -1;
  while (sb_engine_time(e) < t_stop - 0.5 * dt) {
    int st = sb_engine_step(e);
    if (st)
      return st;
    size_t every = sb_engine_get_params(e)->sample_every;
    if (every) {
      sb_engine_stats s0;
      sb_engine_get_stats(e, &s0);
      if (s0.steps % every == 0) {
        if (ps && col_pairs_sample(ps, e))
          return SB_ENOMEM;
        if (r->agglo && (st = sb_agglo_sample(r->agglo, e)))
          return st;
      }
    }
    double frac = (sb_engine_time(e) - t0) / (t_stop - t0);
    if (verbose && (frac - last >= 0.1 || frac >= 1.0 - 1e-12)) {
      sb_engine_stats s;
      sb_engine_get_stats(e, &s);
      fprintf(stderr, "collide: t = %.4g s (%3.0f%%), %llu collisions\n",
              sb_engine_time(e), 100 * frac, (unsigned long long)s.ncoll);
      last = frac;
    }
  }
  (void)c;
  return SB_SUCCESS;
}

static void print_warnings(const col_config *c, int *shown)
{
  for (; *shown < c->nwarn; (*shown)++)
    fprintf(stderr, "collide: warning: %s\n", c->warn[*shown]);
}

int sbc_collide_main(int argc, char **argv)
{
  const char *ini = NULL;
  const char *sets[64];
  const char *sweep = NULL;
  int nsets = 0;
  for (int i = 1; i < argc; i++) {
    if (!strcmp(argv[i], "-h") || !strcmp(argv[i], "--help")) {
      usage(stdout);
      return 0;
    }
    if (!strcmp(argv[i], "--set") || !strncmp(argv[i], "--set=", 6)) {
      const char *v = argv[i][5] == '=' ? argv[i] + 6
                                        : (i + 1 < argc ? argv[++i] : NULL);
      if (!v) {
        fprintf(stderr, "collide: --set needs SECTION.KEY=VALUE\n");
        return 2;
      }
      if (nsets == 64) {
        fprintf(stderr, "collide: more than 64 --set options\n");
        return 2;
      }
      sets[nsets++] = v;
    } else if (!strcmp(argv[i], "--threads") ||
               !strncmp(argv[i], "--threads=", 10)) {
      const char *v = argv[i][9] == '=' ? argv[i] + 10
                                        : (i + 1 < argc ? argv[++i] : NULL);
      char *end = NULL;
      long nt = v ? strtol(v, &end, 10) : -1;
      if (!v || end == v || *end || nt < 1 || nt > 4096) {
        fprintf(stderr, "collide: --threads needs a count in 1..4096\n");
        return 2;
      }
#ifdef _OPENMP
      omp_set_num_threads((int)nt);  /* as OMP_NUM_THREADS */
#else
      if (nt > 1)
        fprintf(stderr, "collide: built without OpenMP: --threads %ld "
                "ignored (one thread)\n", nt);
#endif
    } else if (!strcmp(argv[i], "--sweep") ||
               !strncmp(argv[i], "--sweep=", 8)) {
      sweep = argv[i][7] == '=' ? argv[i] + 8
                                : (i + 1 < argc ? argv[++i] : NULL);
      if (!sweep) {
        fprintf(stderr, "collide: --sweep needs a FILE\n");
        return 2;
      }
    } else if (argv[i][0] == '-' && argv[i][1]) {
      fprintf(stderr, "collide: unknown option '%s' (see smolbridge "
              "collide --help)\n", argv[i]);
      return 2;
    } else if (ini) {
      fprintf(stderr, "collide: one CONFIG.ini expected, got '%s' and "
              "'%s'\n", ini, argv[i]);
      return 2;
    } else
      ini = argv[i];
  }
  if (!ini) {
    fprintf(stderr, "collide: no CONFIG.ini given\n"
            "Usage: smolbridge collide CONFIG.ini [--set "
            "SECTION.KEY=VALUE]... (--help lists the keys)\n");
    return 2;
  }
  if (sweep)
    return col_sweep(ini, sets, nsets, sweep);
  if (sbc_par_size() > 1) {
    if (sbc_par_rank() == 0)
      fprintf(stderr, "collide: one run on rank 0 (%d ranks; --sweep "
              "shares points between them)\n", sbc_par_size());
    else
      return 0;
  }
  return col_run_point(ini, sets, nsets, 1, NULL);
}

int col_run_point(const char *ini, const char *const *sets, int nsets,
                  int verbose, col_point *res)
{
  static col_config c;  /* large: not on the stack */
  col_defaults(&c);
  if (res) {
    memset(res, 0, sizeof *res);
    res->K = res->lo = res->hi = NAN;
    snprintf(res->status, sizeof res->status, "input error");
  }
  int shown = 0;
  if (col_read_file(&c, ini)) {
    fprintf(stderr, "collide: %s\n", c.err);
    if (res)
      snprintf(res->why, sizeof res->why, "%s", c.err);
    return 2;
  }
  for (int i = 0; i < nsets; i++)
    if (col_override(&c, sets[i])) {
      fprintf(stderr, "collide: %s\n", c.err);
      if (res)
        snprintf(res->why, sizeof res->why, "%s", c.err);
      return 2;
    }
  if (col_check(&c)) {
    print_warnings(&c, &shown);
    fprintf(stderr, "collide: %s\n", c.err);
    if (res)
      snprintf(res->why, sizeof res->why, "%s", c.err);
    return 2;
  }
  col_run r;
  if (col_setup(&c, &r)) {
    print_warnings(&c, &shown);
    fprintf(stderr, "collide: %s\n", c.err);
    if (res)
      snprintf(res->why, sizeof res->why, "%s", c.err);
    col_run_free(&r);
    return 2;
  }
  print_warnings(&c, &shown);
  sb_engine *e = r.e;
  const double dt = sb_engine_get_params(e)->dt;
  const double t0 = sb_engine_time(e);
  /* t_end is the absolute end time (warm-up inside it); steps counts the
   * measured steps after the warm-up */
  r.warm = c.restart[0] ? 0.0 : c.warmup;
  r.t_end = !isnan(c.t_end) ? c.t_end : t0 + r.warm + (double)c.steps * dt;
  if (!(r.t_end - t0 - r.warm >= 0.5 * dt)) {
    fprintf(stderr, "collide: %s: nothing to measure: the warm-up (%g s) "
            "does not end before t_end (%g s from t = %g s)\n",
            col_given(&c, "run", "warmup") ? col_where(&c, "run", "warmup")
                                           : col_where(&c, "run", "t_end"),
            r.warm, r.t_end - t0, t0);
    col_run_free(&r);
    return 2;
  }
  if (col_out_prepare(&c)) {
    fprintf(stderr, "collide: %s\n", c.err);
    if (res)
      snprintf(res->why, sizeof res->why, "%s", c.err);
    col_run_free(&r);
    return 2;
  }
  {
    long nst = lround((r.t_end - t0) / dt);
    sb_engine_set_sample_every(e, c.sample_every > 0
                                      ? (size_t)c.sample_every
                                      : (size_t)(nst / 200 > 0 ? nst / 200
                                                               : 1));
  }
  col_firsthit_start(&r, t0 + r.warm);
  if (verbose)
    fprintf(stderr, "collide: %zu particles, dt = %g s, t = %g -> %g s, "
            "seed %lu, output %s/\n", sb_engine_count(e), dt, t0, r.t_end,
            c.restart[0] ? sb_engine_get_params(e)->seed : c.seed,
            c.output);
  if (res)
    res->particles = sb_engine_count(e);
  /* per-pair columns for 2 to 4 species (clusters: sizes.csv) */
  col_pairs pser = {c.nsp <= 4 && !r.agglo ? c.nsp : 0, NULL, 0, 0};
  double cpu0 = (double)clock() / CLOCKS_PER_SEC;
  int st = SB_SUCCESS;
  if (r.warm > 0) {
    st = progress_step(&r, &c, t0 + r.warm, NULL, verbose);
    sb_engine_reset_counters(e);
    if (r.bridge)
      sb_engine_bridge_reset(r.bridge);
    if (r.agglo)
      sb_agglo_reset_stats(r.agglo);
  }
  char path[1100];
  long nsnap = 0;
  while (!st && sb_engine_time(e) < r.t_end - 0.5 * dt) {
    double t_next = r.t_end;
    if (c.snapshot_every > 0) {
      double ts = sb_engine_time(e) + (double)c.snapshot_every * dt;
      if (ts < t_next)
        t_next = ts;
    }
    st = progress_step(&r, &c, t_next, &pser, verbose);
    if (!st && c.snapshot_every > 0) {
      col_snap_path(&c, nsnap, path, sizeof path);
      st = sb_engine_snapshot_csv(e, path);
      if (!st)
        nsnap++;
    }
  }
  double secs = (double)clock() / CLOCKS_PER_SEC - cpu0;
  if (!st && r.agglo) {  /* the last size row at the end time */
    size_t nr, nc;
    const double *rows = sb_agglo_series(r.agglo, &nr, &nc);
    if (!(nr > 0 && rows[(nr - 1) * nc] == sb_engine_time(e)))
      st = sb_agglo_sample(r.agglo, e);
  }
  if (st) {
    char why[600];
    snprintf(why, sizeof why, "step failed at t = %g s: %s",
             sb_engine_time(e), sb_last_error());
    fprintf(stderr, "collide: %s\n", why);
    if (res) {
      snprintf(res->status, sizeof res->status, "run error");
      snprintf(res->why, sizeof res->why, "%s", why);
    }
    if (col_out_write(&c, &r, &pser, secs, "failed", why, nsnap))
      fprintf(stderr, "collide: could not write the outputs in %s/\n",
              c.output);
    free(pser.rows);
    col_run_free(&r);
    return 1;
  }
  int rc = 0;
  if (col_out_write(&c, &r, &pser, secs, "ok", NULL, nsnap)) {
    fprintf(stderr, "collide: could not write the outputs in %s/\n",
            c.output);
    rc = 1;
  }
  free(pser.rows);
  if (c.checkpoint[0] && sb_engine_checkpoint_save(e, c.checkpoint)) {
    fprintf(stderr, "collide: checkpoint: %s\n", sb_last_error());
    rc = 1;
  }
  if (r.agglo) {
    sb_agglo_stats as;
    sb_agglo_get_stats(r.agglo, &as);
    fprintf(stderr, "collide: %llu merges, %llu rebounds, %zu clusters; "
            "sizes in %s/sizes.csv\n", (unsigned long long)as.nmerge,
            (unsigned long long)as.nrebound, sb_engine_count(e), c.output);
  }
  sb_engine_stats fs;
  sb_engine_get_stats(e, &fs);
  if (res) {
    res->ncoll = fs.ncoll;
    res->steps = fs.steps;
    res->cpu_seconds = secs;
    snprintf(res->status, sizeof res->status, rc ? "write error" : "ok");
  }
  if (r.fh) {
    sb_engine_firsthit_kernel_result o;
    col_firsthit_result(&r, &c, &o);
    if (verbose)
      fprintf(stderr, "collide: done; %llu first contacts after t = %g s, "
              "K = %.6g [%.6g, %.6g] (95%%, reference radius %g m)\n",
              (unsigned long long)o.c.hits, o.t1, o.K, o.lo, o.hi, o.a);
    if (res) {
      res->K = o.K;
      res->lo = o.lo;
      res->hi = o.hi;
      res->ncoll = o.c.hits;
      snprintf(res->kind, sizeof res->kind, "first-hit");
    }
  } else {
    double K, lo, hi;
    if (!sb_engine_kernel(e, 0.95, &K, &lo, &hi)) {
      if (verbose)
        fprintf(stderr, "collide: done; K_e = %.6g [%.6g, %.6g] (95%%) over "
                "[%g, %g] s\n", K, lo, hi, fs.t_reset, fs.t);
      if (res) {
        res->K = K;
        res->lo = lo;
        res->hi = hi;
        snprintf(res->kind, sizeof res->kind, "K_e");
      }
    } else if (verbose)
      fprintf(stderr, "collide: done; no kernel: %s\n",
              sb_engine_count(e) < 2 ? "fewer than 2 particles"
                                     : sb_last_error());
  }
  if (fs.dropped)
    fprintf(stderr, "collide: warning: %llu collision events were dropped "
            "(the custom detector does not re-examine pairs after an "
            "outcome within a step); the kernel is low by about that many "
            "collisions of %llu: shorten dt\n",
            (unsigned long long)fs.dropped, (unsigned long long)fs.ncoll);
  col_run_free(&r);
  return rc;
}
