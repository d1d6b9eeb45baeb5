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
"                           [--case PREFIX]... [--list]\n"
"\n"
"Run the validation cases: each compares a Monte Carlo (or numerical)\n"
"estimate with its theoretical reference and gives a verdict.\n"
"\n"
"  --quick         reduced sample sizes, whole suite in under 2 minutes\n"
"                  (default)\n"
"  --full          the sample sizes of the source studies (slow)\n"
"  --out DIR       output directory (default: validate-out); receives\n"
"                  validate.csv, report.md and one .dat/.gp/.png per plot\n"
"  --seed N        base random seed (default 12345); same seed, same output\n"
"  --case PREFIX   run only cases whose name starts with PREFIX (e.g. V11);\n"
"                  may be repeated\n"
"  --list          list the cases and exit\n"
"  -h, --help      this help\n"
"\n"
"Table columns: case, estimate, reference, interval of the estimate (95%%\n"
"unless the case notes say otherwise), p-value (when the comparison is a\n"
"test), verdict; the rules are in docs/validation.md. Exit status: 0 if\n"
"every comparison passes, 1 if any fails, 2 on a usage or output error.\n");
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

int sbc_validate_main(int argc, char **argv)
{
  static const struct option opts[] = {
      {"quick", no_argument, NULL, 'q'}, {"full", no_argument, NULL, 'f'},
      {"out", required_argument, NULL, 'o'},
      {"seed", required_argument, NULL, 's'},
      {"case", required_argument, NULL, 'c'},
      {"list", no_argument, NULL, 'l'}, {"help", no_argument, NULL, 'h'},
      {NULL, 0, NULL, 0}};
  sb_validate_options vo;
  sb_validate_options_init(&vo);
  vo.outdir = "validate-out";
  char *prefixes[64];
  int nprefixes = 0, list = 0, opt;
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
    case 'c':
      if (nprefixes == 64) {
        fprintf(stderr, "smolbridge validate: too many --case options\n");
        return 2;
      }
      prefixes[nprefixes++] = optarg;
      break;
    case 'l': list = 1; break;
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
  if (make_dirs(vo.outdir) != 0) {
    fprintf(stderr, "smolbridge validate: cannot create '%s': %s\n",
            vo.outdir, strerror(errno));
    return 2;
  }

  sb_validate_report *rep = sb_validate_report_alloc();
  if (!rep) {
    fprintf(stderr, "smolbridge validate: out of memory\n");
    return 2;
  }
  int have_gnuplot = on_path("gnuplot");
  vo.progress = progress_to_stderr;
  vo.render = render_with_gnuplot;
  vo.render_data = &have_gnuplot;
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
            now_seconds() - t0, st ? ": " : "", st ? sb_strerror(st) : "");
  }

  printf("\n");
  sb_validate_report_fprint(rep, stdout);
  char path[1100];
  int io = 0;
  snprintf(path, sizeof path, "%s/validate.csv", vo.outdir);
  io |= sb_validate_report_write_csv(rep, path);
  snprintf(path, sizeof path, "%s/report.md", vo.outdir);
  io |= sb_validate_report_write_markdown(rep, path, &vo);
  size_t nrecs = sb_validate_report_nrecords(rep);
  size_t nfail = sb_validate_report_nfailed(rep);
  printf("\n%zu comparisons, %zu passed, %zu failed (%.1f s); report in "
         "%s/report.md\n",
         nrecs, nrecs - (nfail > nrecs ? nrecs : nfail), nfail,
         now_seconds() - t_all, vo.outdir);
  sb_validate_report_free(rep);
  if (io) {
    fprintf(stderr, "smolbridge validate: could not write the report in "
                    "'%s'\n", vo.outdir);
    return 2;
  }
  return nfail ? 1 : 0;
}
