/* collide.c — `smolbridge collide CONFIG.ini [--set SECTION.KEY=VALUE]...`:
 * the library's run description (<smolbridge/collide.h>) reads the
 * configuration, builds the engine, runs it and writes the outputs; the
 * command prints its progress, warnings and messages on stderr.  Exit
 * status: 0 done, 1 run or write error, 2 usage or input error (the
 * configuration, an unwritable output). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <smolbridge/collide.h>
#include <smolbridge/engine.h>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "cli.h"
#include "collide.h"
#include "par.h"

/* The library's key table, one section after the other. */
static void print_keys(FILE *f)
{
  const size_t n = sb_collide_nkeys();
  sb_collide_keyinfo k;
  int w = 16;  /* the longest key sets the name column */
  for (size_t i = 0; i < n; i++)
    if (!sb_collide_key(i, &k) && (int)strlen(k.key) > w)
      w = (int)strlen(k.key);
  const char *sec = "";
  for (size_t i = 0; i < n && !sb_collide_key(i, &k); i++) {
    if (strcmp(sec, k.section)) {
      sec = k.section;
      fprintf(f, "\n[%s%s]\n", sec, strcmp(sec, "species") ? "" : " NAME");
    }
    fprintf(f, "  %-*s %-9s default %s; %s\n  %-*s %-9s valid: %s\n", w,
            k.key, k.unit, k.def, k.help, w, "", "", k.valid);
  }
}

static void usage(FILE *f)
{
  fprintf(f,
"Usage: smolbridge collide CONFIG.ini [--set SECTION.KEY=VALUE]...\n"
"                         [--threads N] [--sweep FILE]\n"
"       smolbridge collide --help\n"
"(also written --set=SECTION.KEY=VALUE, --threads=N, --sweep=FILE)\n"
"\n"
"Run the Lagrangian collision engine described by CONFIG.ini (INI: [section]\n"
"headers, key = value lines, comments start a line with ';' or '#', or\n"
"follow a value after ' ;').  --set overrides or adds one key after the\n"
"file is read (species.NAME.KEY for [species NAME]); summary.json records\n"
"the overrides.  Writes into the directory `output` (files of an earlier\n"
"run there are removed first): series.csv (t, collisions, kernel and its\n"
"95%% interval, energy, momentum, per-pair kernels), summary.json, and as\n"
"asked snap_NNNNNN.csv, sizes.csv (merge | dlvo), hits.csv (hit_times),\n"
"grid.csv (grid), exits.csv (exits), contacts.csv (first_hit_velocities),\n"
"msd.csv (msd_every), batches.csv (batch_steps), manifest.txt (the files\n"
"of the run).  Progress and warnings go to stderr.\n"
"--sweep FILE runs one point per line of FILE (whitespace-separated\n"
"SECTION.KEY=VALUE overrides after the --set ones; '#' starts a comment)\n"
"into OUTPUT/point_NNN/ and writes OUTPUT/sweep.csv (one row per point:\n"
"point,status,particles,steps,collisions,kind,K,K_lo,K_hi,pairs,overrides,\n"
"message: the kernel and its 95%% interval, per species pair of a\n"
"mixture, the overrides, why a point failed); under\n"
"mpirun (a build with --with-mpi) the points are shared by the ranks\n"
"(docs/parallel.md).\n"
"--threads N (1 to 4096; or OMP_NUM_THREADS=N) sets the threads of the\n"
"engine's parallel parts; the outputs do not depend on it ([run] rng =\n"
"philox also moves the particles in parallel; docs/engine.md).\n"
"Exit status: 0 done, 1 run or write error, 2 usage or input error.\n"
"Theory and every key: docs/engine.md §9; examples: examples/*.ini.\n"
"\n"
"Sections and keys (unit, default, valid values):\n");
  print_keys(f);
}

/* Progress on stderr (verbose), the particle count for a sweep. */
typedef struct {
  const sb_collide *c;
  int verbose;
  col_point *res;
} progress_ctx;

static int progress(const sb_collide_progress *p, void *user)
{
  const progress_ctx *pc = user;
  if (p->event == SB_COLLIDE_BEGIN) {
    if (pc->verbose)
      fprintf(stderr, "collide: %zu particles, dt = %g s, t = %g -> %g s, "
              "seed %lu, output %s/\n", p->particles, p->dt, p->t_begin,
              p->t_end, sb_engine_get_params(sb_collide_engine(pc->c))->seed,
              sb_collide_output(pc->c));
    if (pc->res)
      pc->res->particles = p->particles;
  } else if (pc->verbose) {
    const char *warm = p->t <= p->t_measure ? " of the warm-up" : "";
    if (p->first_contacts >= 0)  /* [observe] first_hit: the kernel's count */
      fprintf(stderr, "collide: t = %.4g s (%3.0f%%%s), %lld first contacts "
              "counted\n", p->t, 100 * p->fraction, warm, p->first_contacts);
    else
      fprintf(stderr, "collide: t = %.4g s (%3.0f%%%s), %llu collisions\n",
              p->t, 100 * p->fraction, warm, p->collisions);
  }
  return 0;
}

static void print_warnings(const sb_collide *c, size_t *shown)
{
  for (; *shown < sb_collide_nwarnings(c); (*shown)++)
    fprintf(stderr, "collide: warning: %s\n", sb_collide_warning(c, *shown));
}

/* The message of a failure, one "collide: " line per problem. */
static void print_error(const sb_collide *c)
{
  const char *m = sb_collide_error(c);
  do {
    const char *nl = strchr(m, '\n');
    int n = nl ? (int)(nl - m) : (int)strlen(m);
    fprintf(stderr, "collide: %.*s\n", n, m);
    m = nl ? nl + 1 : NULL;
  } while (m);
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

/* A mixture's kernels, one per species pair ("a-b K [lo, hi]; ..."): the
 * first-contact kernels (summary.json first_hit.pairs), or the collision
 * kernels of the pairs with exposure (summary.json pair_kernels). */
static void pair_kernels(const sb_collide *c, char *buf, size_t len)
{
  const sb_engine *e = sb_collide_engine(c);
  const int fh = sb_collide_has_firsthit(c);
  size_t n = 0;
  buf[0] = '\0';
  for (size_t a = 0; sb_engine_get_species(e, a); a++)
    for (size_t b = a; sb_engine_get_species(e, b); b++) {
      double K, lo, hi;
      if (fh) {
        sb_engine_firsthit_kernel_result p;
        sb_collide_firsthit_pair(c, a, b, &p);
        K = p.K, lo = p.lo, hi = p.hi;
      } else {
        sb_engine_pair_stats ps;
        if (a >= SB_ENGINE_PAIR_SPECIES || b >= SB_ENGINE_PAIR_SPECIES ||
            sb_engine_pair_kernel(e, a, b, 0.95, &ps) || !(ps.exposure > 0))
          continue;
        K = ps.K, lo = ps.lo, hi = ps.hi;
      }
      int w = snprintf(buf + n, len - n, "%s%s-%s %.6g [%.6g, %.6g]",
                       n ? "; " : "", sb_collide_species_name(c, a),
                       sb_collide_species_name(c, b), K, lo, hi);
      if (w < 0 || (size_t)w >= len - n)
        return;  /* truncated: the rest is in summary.json */
      n += (size_t)w;
    }
}

/* The kernel estimate after a completed run, in *res; the done message
 * when verbose. */
static void report_result(const sb_collide *c, int verbose, col_point *res)
{
  const sb_engine *e = sb_collide_engine(c);
  sb_engine_stats fs;
  sb_engine_get_stats(e, &fs);
  if (res) {
    res->ncoll = fs.ncoll;
    res->steps = fs.steps;
    res->mixture = sb_engine_get_species(e, 1) != NULL;
    if (res->mixture)
      pair_kernels(c, res->pairs, sizeof res->pairs);
  }
  if (sb_collide_has_firsthit(c)) {
    sb_engine_firsthit_kernel_result o;
    sb_collide_firsthit(c, &o);
    const int mix = sb_engine_get_species(e, 1) != NULL;
    if (verbose && !mix)
      fprintf(stderr, "collide: done; %llu first contacts after t = %g s, "
              "K = %.6g [%.6g, %.6g] (95%%, reference radius %g m)\n",
              (unsigned long long)o.c.hits, o.t1, o.K, o.lo, o.hi, o.a);
    else if (verbose)
      fprintf(stderr, "collide: done; %llu first contacts after t = %g s; "
              "per species pair (95%%):\n", (unsigned long long)o.c.hits,
              o.t1);
    /* a mixture: one kernel per species pair (summary.json
     * first_hit.pairs) */
    for (size_t a = 0; verbose && mix && sb_engine_get_species(e, a); a++)
      for (size_t b = a; sb_engine_get_species(e, b); b++) {
        sb_engine_firsthit_kernel_result p;
        sb_collide_firsthit_pair(c, a, b, &p);
        fprintf(stderr, "collide:   species %zu-%zu: %llu first contacts, "
                "K = %.6g [%.6g, %.6g] (reference radius %g m)\n", a, b,
                (unsigned long long)p.c.hits, p.K, p.lo, p.hi, p.a);
      }
    if (res) {
      res->K = o.K;
      res->lo = o.lo;
      res->hi = o.hi;
      res->ncoll = o.c.hits;
      snprintf(res->kind, sizeof res->kind, "first-hit");
    }
    return;
  }
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

int col_run_point(const char *ini, const char *const *sets, int nsets,
                  int verbose, col_point *res)
{
  if (res) {
    memset(res, 0, sizeof *res);
    res->K = res->lo = res->hi = NAN;
    snprintf(res->status, sizeof res->status, "input error");
  }
  sb_collide *c = sb_collide_alloc();
  if (!c) {
    fprintf(stderr, "collide: out of memory\n");
    return 2;
  }
  size_t shown = 0;
  int st = sb_collide_read_file(c, ini);
  for (int i = 0; i < nsets && !st; i++)
    st = sb_collide_set(c, sets[i]);
  if (!st) {  /* warnings of the checks before their error */
    st = sb_collide_setup(c);
    print_warnings(c, &shown);
  }
  progress_ctx pc = {c, verbose, res};
  if (!st)
    st = sb_collide_run(c, progress, &pc);
  const sb_collide_failure kind = sb_collide_failed(c);
  if (kind != SB_COLLIDE_OK) {
    print_error(c);
    if (res) {
      static const char *const status[] = {"ok", "run error", "input error",
                                           "write error"};
      snprintf(res->status, sizeof res->status, "%s", status[kind]);
      snprintf(res->why, sizeof res->why, "%.*s",
               (int)strcspn(sb_collide_error(c), "\n"), sb_collide_error(c));
    }
  }
  if (kind == SB_COLLIDE_OK || kind == SB_COLLIDE_EWRITE) {
    const sb_agglo *ag = sb_collide_agglo(c);
    if (ag) {
      sb_agglo_stats as;
      sb_agglo_get_stats(ag, &as);
      fprintf(stderr, "collide: %llu merges, %llu rebounds, %zu clusters; "
              "sizes in %s/sizes.csv\n", (unsigned long long)as.nmerge,
              (unsigned long long)as.nrebound,
              sb_engine_count(sb_collide_engine(c)), sb_collide_output(c));
    }
    report_result(c, verbose, res);
    if (res)
      snprintf(res->status, sizeof res->status, kind ? "write error" : "ok");
    print_warnings(c, &shown);  /* those of the run */
  }
  sb_collide_free(c);
  return kind == SB_COLLIDE_EWRITE ? 1 : (int)kind;
}
