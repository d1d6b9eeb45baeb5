/* validate.c — `smolbridge validate`: run the registered validation cases,
 * print the comparison table, write validate.csv, report.md and plots. */
#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <getopt.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include <smolbridge/common.h>
#include <smolbridge/validate.h>

#include "cli.h"
#include "par.h"

/* Progress lines go to stderr. */
static void progress_to_stderr(const char *line, void *data)
{
  (void)data;
  fprintf(stderr, "%s\n", line);
}

/* Is there an executable `name` on PATH? */
static int on_path(const char *name)
{
  const char *path = getenv("PATH");
  if (!path)
    return 0;
  char buf[4096];
  while (*path) {
    size_t n = strcspn(path, ":");
    if (n > 0 && n + strlen(name) + 2 < sizeof buf) {
      memcpy(buf, path, n);
      buf[n] = '/';
      strcpy(buf + n + 1, name);
      if (access(buf, X_OK) == 0)
        return 1;
    }
    path += n;
    if (*path == ':')
      path++;
  }
  return 0;
}

/* Render a plot script with gnuplot, when it is installed (it is optional:
 * the data and the script are always written). */
static int render_with_gnuplot(const char *dir, const char *script,
                               void *data)
{
  const int *have_gnuplot = data;
  if (!*have_gnuplot)
    return -1;
  return sbc_gnuplot(dir, script);
}

static void usage(FILE *out)
{
  fprintf(out,
"Usage: smolbridge validate [--quick|--full] [--out DIR] [--resume]\n"
"                           [--seed N] [--seeds N] [--case PREFIX]...\n"
"                           [--list] [--write-ini DIR]\n"
"\n"
"Run the validation cases: each compares a Monte Carlo (or numerical)\n"
"estimate with its theoretical reference and gives a verdict by a rule\n"
"stated in its row.\n"
"\n"
"  --quick         reduced sample sizes, whole suite in about two minutes\n"
"                  (default)\n"
"  --full          the sample sizes of the source studies, or enough for\n"
"                  +-1%% (95%%) on the engine kernels (slow: hours; the\n"
"                  run time of each case is in docs/validation.md)\n"
"  --out DIR       output directory (default: validate-out; also -o DIR);\n"
"                  receives validate.csv, report.md and one .dat/.gp/.png\n"
"                  per plot (--full: also DIR/runs/, one file per\n"
"                  finished engine run, for --resume)\n"
"  --resume        read back the engine runs saved in DIR/runs/ by an\n"
"                  earlier invocation with the same options, instead of\n"
"                  running them again (same records, bit for bit); runs\n"
"                  not found are made and saved.  Empty DIR/runs/ after\n"
"                  changing the library: the saved runs know its version,\n"
"                  not its code\n"
"  --seed N        base random seed (default 12345); same seed, same output\n"
"  --seeds N       calibration: run the selected cases with the N seeds\n"
"                  (2 <= N <= 100000) SEED, SEED+1, ..., SEED+N-1 and pool\n"
"                  each record over them (mean estimate/reference and its\n"
"                  95%% interval, bias in standard errors, fraction of\n"
"                  p < 0.05, KS test of the p-values); writes\n"
"                  calibration.csv, calibration.md, all_seeds.csv and the\n"
"                  p-value QQ plot calibration_qq\n"
"  --case PREFIX   run only cases whose name starts with PREFIX (e.g. V11;\n"
"                  V16/combined also selects V16/combined-shear); NAME$\n"
"                  selects that one case only; may be repeated\n"
"  --list          list the cases and exit\n"
"  --write-ini DIR write the engine runs of the selected cases as\n"
"                  smolbridge collide configurations (same mode and seed:\n"
"                  the same estimates; 'expect' comment lines name the\n"
"                  summary.json field of each record, and expect-mean,\n"
"                  expect-sweep-mean, expect-grid, expect-ks, expect-chi2,\n"
"                  expect-max, expect-diff-mean, expect-h-rises and\n"
"                  expect-batches lines how it follows from the outputs,\n"
"                  docs/validation.md) instead of running them; engine\n"
"                  runs collide cannot reproduce are listed, with the\n"
"                  reason, in DIR/NOT-WRITTEN.txt (cases without an\n"
"                  engine run: 'no files' on stderr)\n"
"  -h, --help      this help\n"
"\n"
"Table columns: case, estimate, reference, interval, p-value (of the test\n"
"behind the row), rule, verdict (pass, FAIL, or info for descriptive\n"
"rows).  The interval is the one the rule reads.  Exit status: 0 if no\n"
"comparison (or, with --seeds, no pooled record) fails, 1 if one does, 2\n"
"on a usage or output error.\n");
}

static int validate_selection(sb_validate_options *vo, const size_t *sel,
                              size_t nsel, unsigned long nseeds, int list,
                              const char *ini_dir, char **prefixes,
                              int nprefixes);

/* A selector is a name prefix (V16/combined also selects
 * V16/combined-shear), or with a trailing '$' one exact name. */
static int selected(const char *name, char **prefixes, int nprefixes)
{
  if (nprefixes == 0)
    return 1;
  for (int i = 0; i < nprefixes; i++) {
    size_t n = strlen(prefixes[i]);
    int exact = n > 0 && prefixes[i][n - 1] == '$';
    if (exact ? strlen(name) == n - 1 && strncmp(name, prefixes[i], n - 1) == 0
              : strncmp(name, prefixes[i], n) == 0)
      return 1;
  }
  return 0;
}

static double now_seconds(void)
{
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static void count_verdicts(const sb_validate_report *rep, size_t *npass,
                           size_t *nfail, size_t *ninfo)
{
  *npass = *nfail = *ninfo = 0;
  for (size_t i = 0; i < sb_validate_report_nrecords(rep); i++) {
    sb_verdict v = sb_validate_report_record(rep, i)->verdict;
    *npass += v == SB_PASS;
    *nfail += v == SB_FAIL;
    *ninfo += v == SB_INFO;
  }
}

/* Append one seed's records to all_seeds.csv (seed as first column). */
static int append_seed_csv(FILE *f, const sb_validate_report *rep,
                           unsigned long seed)
{
  char line[1024];
  for (size_t i = 0; i < sb_validate_report_nrecords(rep); i++) {
    sb_comparison_csv(sb_validate_report_record(rep, i), line, sizeof line);
    fprintf(f, "%lu,%s\n", seed, line);
  }
  return ferror(f) ? SB_EIO : SB_SUCCESS;
}

/* calibration.md: per-case summary, then every pooled record. */
static int write_calibration_md(const sb_validate_calibration *cal,
                                const sb_validate_options *vo,
                                unsigned long base, unsigned long nseeds,
                                const char *path)
{
  FILE *f = fopen(path, "w");
  if (!f)
    return SB_EIO;
  fprintf(f, "# smolbridge calibration\n\nsmolbridge %s, mode `%s`, seeds "
             "%lu..%lu (%lu runs).\n\n", sb_version(),
          vo->full ? "full" : "quick", base, base + nseeds - 1, nseeds);
  fprintf(f, "Per record: mean over the seeds of estimate/reference (or of "
             "estimate - reference, `d`, when the reference is 0) with its "
             "Student 95%% interval; bias z = (mean - target)/standard error; "
             "fraction of p-values below 0.05 (about 0.05 when calibrated); "
             "Kolmogorov-Smirnov p-value of the p-values against the uniform "
             "law (not computed for discrete p-values: fewer than 80%% "
             "distinct).  A record fails calibration when the t test of no bias "
             "gives p < 0.0027 (|z| > 3 for many seeds) or KS p < "
             "1e-3 (tests and intervals), or when it failed on any seed "
             "(tolerance bands and demonstrations of expected failures, "
             "which must hold on every seed).\n\n");
  fprintf(f, "| case | records | failing | record-seeds failed | max |z| | "
             "p < 0.05 | KS p (all p-values) | verdict |\n"
             "|---|---|---|---|---|---|---|---|\n");
  for (size_t k = 0; k < sb_validate_calibration_ncases(cal); k++) {
    sb_validate_calibration_case_summary s;
    sb_validate_calibration_case(cal,
                                 sb_validate_calibration_case_name(cal, k),
                                 &s);
    fprintf(f, "| %s | %zu | %zu | %zu/%zu | %.2f | %.3f | %.3g | %s |\n",
            s.case_name, s.nrows, s.nrows_failed, s.nrecords_failed,
            s.nrecords, s.max_abs_bias_z, s.frac_p05, s.ks_p,
            sb_verdict_name(s.verdict));
  }
  fprintf(f, "\n![p-value QQ plot](calibration_qq.png)\n\n```\n");
  sb_validate_calibration_fprint(cal, f);
  fprintf(f, "```\n");
  return fclose(f) == 0 ? SB_SUCCESS : SB_EIO;
}

/* --write-ini DIR: the selected cases' engine runs as collide files. */
static int write_ini(const sb_validate_options *vo, const char *dir,
                     char **prefixes, int nprefixes)
{
  if (sb_mkdir_p(dir) != 0) {
    fprintf(stderr, "smolbridge validate: cannot create '%s': %s\n", dir,
            strerror(errno));
    return 2;
  }
  char path[1100];
  snprintf(path, sizeof path, "%s/NOT-WRITTEN.txt", dir);
  remove(path);
  size_t total = 0;
  for (size_t i = 0; i < sb_validate_ncases(); i++) {
    const char *name = sb_validate_case_name(i);
    if (!selected(name, prefixes, nprefixes))
      continue;
    size_t n = 0;
    int st = sb_validate_write_ini(i, vo, dir, &n);
    if (st == SB_EINVAL && n == 0)
      fprintf(stderr, "%s: no files: %s\n", name, sb_last_error());
    else if (st) {
      fprintf(stderr, "%s: %s\n", name, sb_last_error());
      return 2;
    } else
      fprintf(stderr, "%s: %zu files\n", name, n);
    total += n;
  }
  fprintf(stderr, "smolbridge validate: %zu configurations in %s/ (%s, "
          "seed %lu); run each with smolbridge collide FILE; the 'expect' "
          "lines say which summary.json field gives which record\n", total,
          dir, vo->full ? "full" : "quick", vo->seed);
  return total ? 0 : 2;
}

/* ------------------------------------------------ runs over the ranks
 *
 * The work is a list of tasks t = k * nsel + c: case sel[c] with seed
 * base + k (one seed without --seeds).  Rank r runs the tasks t = r
 * (mod P); each task's report is packed (sb_validate_report_pack) behind
 * a header {t, length}; rank 0 gathers them and appends them in task
 * order, so its reports are the serial run's (the cases draw from
 * generators keyed by the seed and the case: docs/validation.md).  A
 * single process takes the same path. */

typedef struct {
  const sb_validate_options *vo;
  const size_t *sel;
  size_t nsel;
  unsigned long nseeds; /* 0: one seed, progress and plots as usual */
} tasks;

static int put_task(unsigned char **buf, size_t *len, size_t *cap,
                    uint64_t t, const void *p, size_t n)
{
  uint64_t hdr[2] = {t, n};
  size_t need = *len + sizeof hdr + n;
  if (need > *cap) {
    size_t nc = *cap ? 2 * *cap : 4096;
    while (nc < need)
      nc *= 2;
    unsigned char *q = realloc(*buf, nc);
    if (!q)
      return -1;
    *buf = q;
    *cap = nc;
  }
  memcpy(*buf + *len, hdr, sizeof hdr);
  memcpy(*buf + *len + sizeof hdr, p, n);
  *len = need;
  return 0;
}

/* This rank's tasks, packed; progress on stderr from rank 0. */
static int run_my_tasks(const tasks *T, unsigned char **out, size_t *outlen)
{
  const int rank = sbc_par_rank(), P = sbc_par_size();
  const size_t nt = T->nsel * (T->nseeds ? T->nseeds : 1);
  size_t cap = 0, mine = 0, done = 0;
  *out = NULL;
  *outlen = 0;
  for (size_t t = (size_t)rank; t < nt; t += (size_t)P)
    mine++;
  double t_all = now_seconds(), t_seed = t_all;
  size_t seed_rows = 0, seed_fail = 0;
  for (size_t t = (size_t)rank; t < nt; t += (size_t)P) {
    size_t k = t / T->nsel, c = t % T->nsel, i = T->sel[c];
    sb_validate_options o = *T->vo;
    if (T->nseeds) {
      o.seed = T->vo->seed + k;
      o.outdir = NULL; /* per-seed plots would overwrite each other */
      o.progress = NULL;
    } else if (rank != 0)
      o.progress = NULL;
    sb_validate_report *rep = sb_validate_report_alloc();
    if (!rep)
      return -1;
    const char *name = sb_validate_case_name(i);
    if (!T->nseeds && rank == 0)
      fprintf(stderr, "[%zu/%zu] %s: %s ...%s\n", c + 1, T->nsel, name,
              sb_validate_case_description(i), sbc_par_tag());
    double t0 = now_seconds();
    int st = sb_validate_run(i, &o, rep);
    if (!T->nseeds && rank == 0)
      fprintf(stderr, "[%zu/%zu] %s done in %.1f s%s%s\n", c + 1, T->nsel,
              name, now_seconds() - t0, st ? ": " : "",
              !st ? "" : (*sb_last_error() ? sb_last_error()
                                           : sb_strerror(st)));
    size_t np_, nf_, ni_;
    count_verdicts(rep, &np_, &nf_, &ni_);
    seed_rows += sb_validate_report_nrecords(rep);
    seed_fail += nf_;
    void *pk = NULL;
    size_t n;
    int bad = sb_validate_report_pack(rep, &pk, &n) ||
              put_task(out, outlen, &cap, t, pk, n);
    free(pk);  /* put_task copied it (or failed) */
    sb_validate_report_free(rep);
    if (bad)
      return -1;
    done++;
    /* --seeds: a line per seed's worth of tasks done by rank 0 */
    if (T->nseeds && rank == 0 && (done % T->nsel == 0 || done == mine)) {
      double el = now_seconds() - t_all;
      if (P == 1)  /* a whole seed: its rows */
        fprintf(stderr, "[seed %lu, %zu/%lu] %zu rows, %zu failed (%.1f s; "
                "about %.0f s to go)\n", o.seed, k + 1, T->nseeds,
                seed_rows, seed_fail, now_seconds() - t_seed,
                el / (double)done * (double)(mine - done));
      else
        fprintf(stderr, "[%zu/%zu runs of rank 0] seed %lu done; about "
                "%.0f s to go\n", done, mine, o.seed,
                el / (double)done * (double)(mine - done));
      seed_rows = seed_fail = 0;
      t_seed = now_seconds();
    }
  }
  return 0;
}

/* Run the tasks on every rank; on rank 0, *reps[k] gets seed k's report
 * (nseeds of them, or one).  0, or 2 on a failure (every rank). */
static int run_tasks(const tasks *T, sb_validate_report ***reps)
{
  unsigned char *mine, *all = NULL;
  size_t nmine, *lens = NULL;
  int bad = run_my_tasks(T, &mine, &nmine) ? 1 : 0;
  bad = sbc_par_max_int(bad);
  if (!bad && sbc_par_gather(mine, nmine, &all, &lens))
    bad = 1;
  free(mine);
  *reps = NULL;
  if (bad || sbc_par_rank() != 0) {
    free(all);
    free(lens);
    if (bad && sbc_par_rank() == 0)
      fprintf(stderr, "smolbridge validate: out of memory or MPI failure\n");
    return bad ? 2 : 0;
  }
  const size_t ns = T->nseeds ? T->nseeds : 1, nt = ns * T->nsel;
  size_t total = 0;
  for (int r = 0; r < sbc_par_size(); r++)
    total += lens[r];
  free(lens);
  const unsigned char **blob = calloc(nt, sizeof *blob);
  size_t *blen = calloc(nt, sizeof *blen);
  sb_validate_report **R = calloc(ns, sizeof *R);
  int rc = blob && blen && R ? 0 : 2;
  for (size_t off = 0; !rc && off < total;) {
    uint64_t hdr[2];
    memcpy(hdr, all + off, sizeof hdr);
    if (hdr[0] >= nt || hdr[1] > total - off - sizeof hdr)
      rc = 2;
    else {
      blob[hdr[0]] = all + off + sizeof hdr;
      blen[hdr[0]] = (size_t)hdr[1];
      off += sizeof hdr + (size_t)hdr[1];
    }
  }
  for (size_t k = 0; !rc && k < ns; k++) {
    if (!(R[k] = sb_validate_report_alloc()))
      rc = 2;
    for (size_t c = 0; !rc && c < T->nsel; c++) {
      size_t t = k * T->nsel + c;
      if (!blob[t] ||
          sb_validate_report_append_packed(R[k], blob[t], blen[t]))
        rc = 2;
    }
  }
  free(all);
  free(blob);
  free(blen);
  if (rc) {
    fprintf(stderr, "smolbridge validate: gathering the reports failed: "
            "%s\n", sb_last_error());
    for (size_t k = 0; R && k < ns; k++)
      sb_validate_report_free(R[k]);
    free(R);
    return rc;
  }
  *reps = R;
  return 0;
}

/* --seeds N: run the selection with N seeds and pool. */
static int calibrate(sb_validate_options *vo, const size_t *sel,
                     size_t nsel, unsigned long nseeds)
{
  const unsigned long base = vo->seed;
  const char *outdir = vo->outdir;
  const int root = sbc_par_rank() == 0;
  if (root)
    fprintf(stderr, "smolbridge validate --seeds %lu (%s, seeds %lu..%lu): "
                    "%zu case%s -> %s/%s\n", nseeds,
            vo->full ? "full" : "quick", base, base + nseeds - 1, nsel,
            nsel == 1 ? "" : "s", outdir,
            sbc_par_size() > 1 ? " (runs shared by the ranks; progress of "
                                 "rank 0)" : "");
  double t_all = now_seconds();
  tasks T = {vo, sel, nsel, nseeds};
  sb_validate_report **reps;
  int rc = run_tasks(&T, &reps);
  if (rc || !root)
    return rc;
  char path[1100];
  snprintf(path, sizeof path, "%s/all_seeds.csv", outdir);
  FILE *all = fopen(path, "w");
  sb_validate_calibration *cal = sb_validate_calibration_alloc();
  if (!all || !cal) {
    fprintf(stderr, "smolbridge validate: cannot write '%s'\n", path);
    rc = 2;
  } else
    fprintf(all, "seed,%s\n", SB_COMPARISON_CSV_HEADER);
  for (unsigned long k = 0; k < nseeds; k++) {
    const sb_validate_report *rep = reps[k];
    if (!rc && (sb_validate_calibration_add(cal, rep) != SB_SUCCESS ||
                append_seed_csv(all, rep, base + k) != SB_SUCCESS))
      rc = 2;
    sb_validate_report_free(reps[k]);
  }
  free(reps);
  if (all && fclose(all) != 0)
    rc = 2;
  if (rc) {
    sb_validate_calibration_free(cal);
    fprintf(stderr, "smolbridge validate: calibration failed (out of memory "
                    "or write error)\n");
    return rc;
  }
  /* per-case summary on stdout, records failing calibration below it */
  printf("\n%-28s %7s %7s %9s %8s %8s %8s %s\n", "case", "records",
         "failing", "max |z|", "p<0.05", "KS p", "seeds", "verdict");
  size_t nbad = 0;
  for (size_t k = 0; k < sb_validate_calibration_ncases(cal); k++) {
    sb_validate_calibration_case_summary s;
    sb_validate_calibration_case(cal,
                                 sb_validate_calibration_case_name(cal, k),
                                 &s);
    printf("%-28s %7zu %7zu %9.2f %8.3f %8.3g %8lu %s\n", s.case_name,
           s.nrows, s.nrows_failed, s.max_abs_bias_z, s.frac_p05, s.ks_p,
           nseeds, s.verdict == SB_FAIL ? "FAIL" : "pass");
    nbad += s.nrows_failed;
  }
  if (nbad) {
    printf("\nRecords failing calibration:\n");
    for (size_t i = 0; i < sb_validate_calibration_nrows(cal); i++) {
      sb_validate_calibration_row r;
      sb_validate_calibration_get_row(cal, i, &r);
      if (r.verdict == SB_FAIL)
        printf("  %-44s pooled %.4f [%.4f, %.4f], z = %.2f, KS p = %.3g, "
               "failed on %zu/%zu seeds\n", r.name, r.mean, r.mean_lo,
               r.mean_hi, r.bias_z, r.ks_p, r.nfail, r.nseeds);
    }
  }
  int io = 0;
  snprintf(path, sizeof path, "%s/calibration.csv", outdir);
  io |= sb_validate_calibration_write_csv(cal, path);
  snprintf(path, sizeof path, "%s/calibration.md", outdir);
  io |= write_calibration_md(cal, vo, base, nseeds, path);
  io |= sb_validate_calibration_qq_plot(cal, vo, "calibration_qq");
  /* a correct code still fails some records by chance: at most
   * 0.0027 per bias test and 1e-3 per KS test (the union bound) */
  double chance = 0.0;
  for (size_t i = 0; i < sb_validate_calibration_nrows(cal); i++) {
    sb_validate_calibration_row r;
    sb_validate_calibration_get_row(cal, i, &r);
    chance += (isnan(r.bias_p) ? 0.0 : 0.0027) + (isnan(r.ks_p) ? 0.0 : 1e-3);
  }
  printf("\n%zu records pooled over %lu seeds, %zu failing calibration "
         "(a correct code: about %.2g by chance) (%.1f s); "
         "%s/calibration.md\n", sb_validate_calibration_nrows(cal), nseeds,
         nbad, chance, now_seconds() - t_all, outdir);
  sb_validate_calibration_free(cal);
  if (io) {
    fprintf(stderr, "smolbridge validate: could not write the calibration "
                    "in '%s'\n", outdir);
    return 2;
  }
  return nbad ? 1 : 0;
}

int sbc_validate_main(int argc, char **argv)
{
  static const struct option opts[] = {
      {"quick", no_argument, NULL, 'q'}, {"full", no_argument, NULL, 'f'},
      {"out", required_argument, NULL, 'o'},
      {"seed", required_argument, NULL, 's'},
      {"seeds", required_argument, NULL, 'n'},
      {"case", required_argument, NULL, 'c'},
      {"list", no_argument, NULL, 'l'}, {"help", no_argument, NULL, 'h'},
      {"write-ini", required_argument, NULL, 'w'},
      {"resume", no_argument, NULL, 'r'},
      {NULL, 0, NULL, 0}};
  const char *ini_dir = NULL;
  sb_validate_options vo;
  sb_validate_options_init(&vo);
  vo.outdir = "validate-out";
  char *prefixes[64];
  int nprefixes = 0, list = 0, opt, mode_given = 0;
  unsigned long nseeds = 0;
  optind = 1;
  while ((opt = getopt_long(argc, argv, "ho:", opts, NULL)) != -1) {
    switch (opt) {
    case 'q':
    case 'f':
      if (mode_given && vo.full != (opt == 'f')) {
        fprintf(stderr, "smolbridge validate: --quick and --full: give "
                        "one of them\n");
        return 2;
      }
      vo.full = opt == 'f';
      mode_given = 1;
      break;
    case 'o': vo.outdir = optarg; break;
    case 's': {
      char *end;
      errno = 0;
      unsigned long s = strtoul(optarg, &end, 10);
      if (errno || *end || optarg[0] == '-') {
        fprintf(stderr, "smolbridge validate: --seed needs a non-negative "
                        "integer, got '%s'\n", optarg);
        return 2;
      }
      vo.seed = s;
      break;
    }
    case 'n': {
      char *end;
      errno = 0;
      unsigned long v = strtoul(optarg, &end, 10);
      if (errno || *end || optarg[0] == '-' || v < 2 || v > 100000) {
        fprintf(stderr, "smolbridge validate: --seeds needs an integer from "
                        "2 to 100000, got '%s'\n", optarg);
        return 2;
      }
      nseeds = v;
      break;
    }
    case 'c':
      if (nprefixes == 64) {
        fprintf(stderr, "smolbridge validate: too many --case options\n");
        return 2;
      }
      prefixes[nprefixes++] = optarg;
      break;
    case 'l': list = 1; break;
    case 'r': vo.resume = 1; break;
    case 'w': ini_dir = optarg; break;
    case 'h': usage(stdout); return 0;
    default: usage(stderr); return 2;
    }
  }
  if (optind < argc) {
    fprintf(stderr, "smolbridge validate: unexpected argument '%s'\n",
            argv[optind]);
    usage(stderr);
    return 2;
  }

  size_t ncases = sb_validate_ncases(), nsel = 0;
  size_t *sel = malloc((ncases ? ncases : 1) * sizeof *sel);
  if (!sel) {
    fprintf(stderr, "smolbridge validate: out of memory\n");
    return 2;
  }
  for (size_t i = 0; i < ncases; i++) {
    const char *name = sb_validate_case_name(i);
    if (!selected(name, prefixes, nprefixes))
      continue;
    sel[nsel++] = i;
    if (list && sbc_par_rank() == 0)
      printf("%-32s %s\n", name, sb_validate_case_description(i));
  }
  int rc = validate_selection(&vo, sel, nsel, nseeds, list, ini_dir,
                              prefixes, nprefixes);
  free(sel);
  return rc;
}

static int validate_selection(sb_validate_options *vo_, const size_t *sel,
                              size_t nsel, unsigned long nseeds, int list,
                              const char *ini_dir, char **prefixes,
                              int nprefixes)
{
  sb_validate_options vo = *vo_;
  const int root = sbc_par_rank() == 0;
  if (list)
    return 0;
  if (nsel == 0) {
    fprintf(stderr, "smolbridge validate: no case matches\n");
    return 2;
  }
  if (ini_dir)  /* quick: rank 0 writes them */
    return root ? write_ini(&vo, ini_dir, prefixes, nprefixes) : 0;
  if (sb_mkdir_p(vo.outdir) != 0) {
    fprintf(stderr, "smolbridge validate: cannot create '%s': %s\n",
            vo.outdir, strerror(errno));
    return 2;
  }

  /* --full (hours) saves every finished engine run; --resume reads them */
  char runs[1100];
  if (vo.full || vo.resume) {
    snprintf(runs, sizeof runs, "%s/runs", vo.outdir);
    if (sb_mkdir_p(runs) != 0) {
      fprintf(stderr, "smolbridge validate: cannot create '%s': %s\n", runs,
              strerror(errno));
      return 2;
    }
    vo.run_dir = runs;
  }

  int have_gnuplot = on_path("gnuplot");
  vo.render = render_with_gnuplot;
  vo.render_data = &have_gnuplot;
  if (nseeds)
    return calibrate(&vo, sel, nsel, nseeds);
  vo.progress = progress_to_stderr;

  const char *mode = vo.full ? "full" : "quick";
  if (root)
    fprintf(stderr,
            "smolbridge validate (%s, seed %lu): %zu case%s -> %s/%s\n", mode,
            vo.seed, nsel, nsel == 1 ? "" : "s", vo.outdir,
            sbc_par_size() > 1 ? " (cases shared by the ranks; progress of "
                                 "rank 0)" : "");
  double t_all = now_seconds();
  tasks T = {&vo, sel, nsel, 0};
  sb_validate_report **reps;
  int rc = run_tasks(&T, &reps);
  if (rc || !root)
    return rc;
  sb_validate_report *rep = reps[0];
  free(reps);
  printf("\n");
  sb_validate_report_fprint(rep, stdout);
  char path[1100];
  int io = 0;
  snprintf(path, sizeof path, "%s/validate.csv", vo.outdir);
  io |= sb_validate_report_write_csv(rep, path);
  snprintf(path, sizeof path, "%s/report.md", vo.outdir);
  io |= sb_validate_report_write_markdown(rep, path, &vo);
  size_t npass, nfail, ninfo;
  count_verdicts(rep, &npass, &nfail, &ninfo);
  printf("\n%zu comparisons: %zu passed, %zu failed, %zu informational "
         "(%.1f s); report in %s/report.md\n",
         sb_validate_report_nrecords(rep), npass, nfail, ninfo,
         now_seconds() - t_all, vo.outdir);
  nfail = sb_validate_report_nfailed(rep);  /* + cases not completed */
  sb_validate_report_free(rep);
  if (io) {
    fprintf(stderr, "smolbridge validate: could not write the report in "
                    "'%s'\n", vo.outdir);
    return 2;
  }
  return nfail ? 1 : 0;
}
