/* validate.c — `smolbridge validate`: run the registered validation cases,
 * print the comparison table, write validate.csv, report.md and plots. */
#include <errno.h>
#include <getopt.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include <smolbridge/common.h>
#include <smolbridge/validate.h>

#include "cli.h"

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
  char cmd[2300];
  snprintf(cmd, sizeof cmd, "cd '%s' && gnuplot '%s' 2>/dev/null", dir,
           script);
  return system(cmd) == 0 ? 0 : -1;
}

static void usage(FILE *out)
{
  fprintf(out,
"Usage: smolbridge validate [--quick|--full] [--out DIR] [--seed N]\n"
"                           [--seeds N] [--case PREFIX]... [--list]\n"
"                           [--write-ini DIR]\n"
"\n"
"Run the validation cases: each compares a Monte Carlo (or numerical)\n"
"estimate with its theoretical reference and gives a verdict by a rule\n"
"stated in its row.\n"
"\n"
"  --quick         reduced sample sizes, whole suite in about a minute\n"
"                  (default)\n"
"  --full          the sample sizes of the source studies, or enough for\n"
"                  +-1%% (95%%) on the engine kernels (slow: hours; the\n"
"                  run time of each case is in docs/validation.md)\n"
"  --out DIR       output directory (default: validate-out); receives\n"
"                  validate.csv, report.md and one .dat/.gp/.png per plot\n"
"  --seed N        base random seed (default 12345); same seed, same output\n"
"  --seeds N       calibration: run the selected cases with the N seeds\n"
"                  SEED, SEED+1, ..., SEED+N-1 and pool each record over\n"
"                  them (mean estimate/reference and its 95%% interval,\n"
"                  bias in standard errors, fraction of p < 0.05, KS test\n"
"                  of the p-values); writes calibration.csv, calibration.md,\n"
"                  all_seeds.csv and the p-value QQ plot calibration_qq\n"
"  --case PREFIX   run only cases whose name starts with PREFIX (e.g. V11);\n"
"                  may be repeated\n"
"  --list          list the cases and exit\n"
"  --write-ini DIR write the engine runs of the selected cases as\n"
"                  smolbridge collide configurations (same mode and seed:\n"
"                  the same estimates; 'expect' comment lines name the\n"
"                  summary.json field of each record) instead of running\n"
"                  them; runs collide cannot reproduce are listed in\n"
"                  DIR/NOT-WRITTEN.txt\n"
"  -h, --help      this help\n"
"\n"
"Table columns: case, estimate, reference, interval, p-value (of the test\n"
"behind the row), rule, verdict (pass, FAIL, or info for descriptive\n"
"rows).  The interval is the one the rule reads.  Exit status: 0 if no\n"
"comparison (or, with --seeds, no pooled record) fails, 1 if one does, 2\n"
"on a usage or output error.\n");
}

/* mkdir -p */
static int make_dirs(const char *path)
{
  char buf[1024];
  size_t n = strlen(path);
  if (n == 0 || n >= sizeof buf)
    return -1;
  memcpy(buf, path, n + 1);
  for (char *p = buf + 1; *p; p++) {
    if (*p == '/') {
      *p = '\0';
      if (mkdir(buf, 0777) != 0 && errno != EEXIST)
        return -1;
      *p = '/';
    }
  }
  if (mkdir(buf, 0777) != 0 && errno != EEXIST)
    return -1;
  return 0;
}

static int selected(const char *name, char **prefixes, int nprefixes)
{
  if (nprefixes == 0)
    return 1;
  for (int i = 0; i < nprefixes; i++)
    if (strncmp(name, prefixes[i], strlen(prefixes[i])) == 0)
      return 1;
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
  if (make_dirs(dir) != 0) {
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

/* --seeds N: run the selection with N seeds and pool. */
static int calibrate(sb_validate_options *vo, char **prefixes,
                     int nprefixes, size_t nsel, unsigned long nseeds)
{
  const unsigned long base = vo->seed;
  const char *outdir = vo->outdir;
  char path[1100];
  snprintf(path, sizeof path, "%s/all_seeds.csv", outdir);
  FILE *all = fopen(path, "w");
  sb_validate_calibration *cal = sb_validate_calibration_alloc();
  if (!all || !cal) {
    fprintf(stderr, "smolbridge validate: cannot write '%s'\n", path);
    if (all)
      fclose(all);
    sb_validate_calibration_free(cal);
    return 2;
  }
  fprintf(all, "seed,%s\n", SB_COMPARISON_CSV_HEADER);
  fprintf(stderr, "smolbridge validate --seeds %lu (%s, seeds %lu..%lu): "
                  "%zu cases -> %s/\n", nseeds, vo->full ? "full" : "quick",
          base, base + nseeds - 1, nsel, outdir);
  double t_all = now_seconds();
  int rc = 0;
  size_t ncases = sb_validate_ncases();
  for (unsigned long k = 0; k < nseeds && !rc; k++) {
    sb_validate_options o = *vo;
    o.seed = base + k;
    o.outdir = NULL;  /* per-seed plots would overwrite each other */
    o.progress = NULL;
    sb_validate_report *rep = sb_validate_report_alloc();
    if (!rep) {
      rc = 2;
      break;
    }
    double t0 = now_seconds();
    for (size_t i = 0; i < ncases; i++)
      if (selected(sb_validate_case_name(i), prefixes, nprefixes))
        sb_validate_run(i, &o, rep);
    size_t npass, nfail, ninfo;
    count_verdicts(rep, &npass, &nfail, &ninfo);
    double el = now_seconds() - t_all;
    fprintf(stderr, "[seed %lu, %lu/%lu] %zu rows, %zu failed (%.1f s; "
                    "about %.0f s to go)\n", o.seed, k + 1, nseeds,
            sb_validate_report_nrecords(rep), nfail, now_seconds() - t0,
            el / (double)(k + 1) * (double)(nseeds - k - 1));
    if (sb_validate_calibration_add(cal, rep) != SB_SUCCESS ||
        append_seed_csv(all, rep, o.seed) != SB_SUCCESS)
      rc = 2;
    sb_validate_report_free(rep);
  }
  if (fclose(all) != 0)
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
  printf("\n%zu records pooled over %lu seeds, %zu failing calibration "
         "(%.1f s); %s/calibration.md\n", sb_validate_calibration_nrows(cal),
         nseeds, nbad, now_seconds() - t_all, outdir);
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
      {NULL, 0, NULL, 0}};
  const char *ini_dir = NULL;
  sb_validate_options vo;
  sb_validate_options_init(&vo);
  vo.outdir = "validate-out";
  char *prefixes[64];
  int nprefixes = 0, list = 0, opt;
  unsigned long nseeds = 0;
  optind = 1;
  while ((opt = getopt_long(argc, argv, "ho:", opts, NULL)) != -1) {
    switch (opt) {
    case 'q': vo.full = 0; break;
    case 'f': vo.full = 1; break;
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
  for (size_t i = 0; i < ncases; i++) {
    const char *name = sb_validate_case_name(i);
    if (!selected(name, prefixes, nprefixes))
      continue;
    nsel++;
    if (list)
      printf("%-32s %s\n", name, sb_validate_case_description(i));
  }
  if (list)
    return 0;
  if (nsel == 0) {
    fprintf(stderr, "smolbridge validate: no case matches\n");
    return 2;
  }
  if (ini_dir)
    return write_ini(&vo, ini_dir, prefixes, nprefixes);
  if (make_dirs(vo.outdir) != 0) {
    fprintf(stderr, "smolbridge validate: cannot create '%s': %s\n",
            vo.outdir, strerror(errno));
    return 2;
  }

  int have_gnuplot = on_path("gnuplot");
  vo.render = render_with_gnuplot;
  vo.render_data = &have_gnuplot;
  if (nseeds)
    return calibrate(&vo, prefixes, nprefixes, nsel, nseeds);
  vo.progress = progress_to_stderr;

  sb_validate_report *rep = sb_validate_report_alloc();
  if (!rep) {
    fprintf(stderr, "smolbridge validate: out of memory\n");
    return 2;
  }
  const char *mode = vo.full ? "full" : "quick";
  fprintf(stderr, "smolbridge validate (%s, seed %lu): %zu cases -> %s/\n",
          mode, vo.seed, nsel, vo.outdir);
  double t_all = now_seconds();
  size_t k = 0;
  for (size_t i = 0; i < ncases; i++) {
    const char *name = sb_validate_case_name(i);
    if (!selected(name, prefixes, nprefixes))
      continue;
    fprintf(stderr, "[%zu/%zu] %s: %s ...\n", ++k, nsel, name,
            sb_validate_case_description(i));
    double t0 = now_seconds();
    int st = sb_validate_run(i, &vo, rep);
    fprintf(stderr, "[%zu/%zu] %s done in %.1f s%s%s\n", k, nsel, name,
            now_seconds() - t0, st ? ": " : "",
            !st ? "" : (*sb_last_error() ? sb_last_error() : sb_strerror(st)));
  }

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
