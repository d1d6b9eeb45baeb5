/* validate.c — `smolbridge validate`: run the registered validation cases,
 * print the comparison table, write validate.csv, report.md and plots. */
#include <errno.h>
#include <getopt.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#include <gsl/gsl_rng.h>
#include <smolbridge/common.h>

#include "cases.h"
#include "cli.h"
#include "report.h"

/* The case tables of all modules, in the order they run. */
static const struct {
  const sbv_case *cases;
  const size_t *n;
} tables[] = {
    {sbv_cases_bridge, &sbv_ncases_bridge},
    {sbv_cases_langevin, &sbv_ncases_langevin},
    {sbv_cases_pbe, &sbv_ncases_pbe},
    {sbv_cases_engine, &sbv_ncases_engine},
    {sbv_cases_engine2, &sbv_ncases_engine2},
    {sbv_cases_agglo, &sbv_ncases_agglo},
};

gsl_rng *sbv_rng_alloc(const sbv_ctx *ctx, unsigned long stream)
{
  gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
  if (r) /* distinct, reproducible seeds per (base seed, stream) */
    gsl_rng_set(r, ctx->seed * 1000003UL + stream * 7919UL + 1UL);
  return r;
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
"Table columns: case, estimate, reference, 95%% interval of the estimate,\n"
"p-value (when the comparison is a test), verdict. Exit status: 0 if every\n"
"comparison passes, 1 if any fails, 2 on a usage or output error.\n");
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
  sbv_ctx ctx = {0, 12345UL, "validate-out", stderr};
  char *prefixes[64];
  int nprefixes = 0, list = 0, opt;
  optind = 1;
  while ((opt = getopt_long(argc, argv, "ho:", opts, NULL)) != -1) {
    switch (opt) {
    case 'q': ctx.full = 0; break;
    case 'f': ctx.full = 1; break;
    case 'o': ctx.outdir = optarg; break;
    case 's': {
      char *end;
      errno = 0;
      unsigned long s = strtoul(optarg, &end, 10);
      if (errno || *end || optarg[0] == '-') {
        fprintf(stderr, "smolbridge validate: --seed needs a non-negative "
                        "integer, got '%s'\n", optarg);
        return 2;
      }
      ctx.seed = s;
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

  size_t nsel = 0;
  for (size_t t = 0; t < sizeof tables / sizeof tables[0]; t++)
    for (size_t i = 0; i < *tables[t].n; i++) {
      const sbv_case *c = &tables[t].cases[i];
      if (!selected(c->name, prefixes, nprefixes))
        continue;
      nsel++;
      if (list)
        printf("%-32s %s\n", c->name, c->description);
    }
  if (list)
    return 0;
  if (nsel == 0) {
    fprintf(stderr, "smolbridge validate: no case matches\n");
    return 2;
  }
  if (make_dirs(ctx.outdir) != 0) {
    fprintf(stderr, "smolbridge validate: cannot create '%s': %s\n",
            ctx.outdir, strerror(errno));
    return 2;
  }

  sbv_report *rep = sbv_report_alloc();
  if (!rep) {
    fprintf(stderr, "smolbridge validate: out of memory\n");
    return 2;
  }
  const char *mode = ctx.full ? "full" : "quick";
  fprintf(stderr, "smolbridge validate (%s, seed %lu): %zu cases -> %s/\n",
          mode, ctx.seed, nsel, ctx.outdir);
  double t_all = now_seconds();
  size_t k = 0;
  for (size_t t = 0; t < sizeof tables / sizeof tables[0]; t++)
    for (size_t i = 0; i < *tables[t].n; i++) {
      const sbv_case *c = &tables[t].cases[i];
      if (!selected(c->name, prefixes, nprefixes))
        continue;
      fprintf(stderr, "[%zu/%zu] %s: %s ...\n", ++k, nsel, c->name,
              c->description);
      if (sbv_report_begin_case(rep, c->name) != SB_SUCCESS) {
        sbv_report_free(rep);
        fprintf(stderr, "smolbridge validate: out of memory\n");
        return 2;
      }
      double t0 = now_seconds();
      int st = c->run(&ctx, rep);
      double dt = now_seconds() - t0;
      sbv_report_end_case(rep, st, dt);
      fprintf(stderr, "[%zu/%zu] %s done in %.1f s%s%s\n", k, nsel, c->name,
              dt, st ? ": " : "", st ? sb_strerror(st) : "");
    }

  printf("\n");
  sbv_report_print_table(rep, stdout);
  char path[1100];
  int io = 0;
  snprintf(path, sizeof path, "%s/validate.csv", ctx.outdir);
  io |= sbv_report_write_csv(rep, path);
  snprintf(path, sizeof path, "%s/report.md", ctx.outdir);
  io |= sbv_report_write_markdown(rep, path, mode, ctx.seed);
  size_t nfail = sbv_report_nfail(rep);
  printf("\n%zu comparisons, %zu passed, %zu failed (%.1f s); report in "
         "%s/report.md\n",
         rep->nrecs, rep->nrecs - (nfail > rep->nrecs ? rep->nrecs : nfail),
         nfail, now_seconds() - t_all, ctx.outdir);
  sbv_report_free(rep);
  if (io) {
    fprintf(stderr, "smolbridge validate: could not write the report in "
                    "'%s'\n", ctx.outdir);
    return 2;
  }
  return nfail ? 1 : 0;
}
