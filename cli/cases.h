/* cases.h — the registry of `smolbridge validate` cases.
 *
 * A case runs a Monte Carlo (or numerical) experiment and appends one or
 * more comparison records (see <smolbridge/stats.h>) to a report.  Each
 * module's cases live in cli/cases_MODULE.c and are listed in the table in
 * cli/validate.c.
 *
 * Rules for a case:
 *  - deterministic: use only the gsl_rng seeded from ctx->seed (create your
 *    own with sbv_rng_alloc(ctx, stream) so cases are independent of order);
 *  - ctx->full selects the seeds' sample sizes; quick mode must keep the
 *    whole quick suite under two minutes (aim for a few seconds per case);
 *  - state sample size and criterion in the record name or in the notes;
 *  - optionally write a plot with sbv_plot() (data file + gnuplot script in
 *    ctx->outdir, rendered to PNG when gnuplot is available).
 */
#ifndef SB_CLI_CASES_H
#define SB_CLI_CASES_H

#include <stdio.h>
#include <gsl/gsl_rng.h>
#include <smolbridge/stats.h>

typedef struct {
  int full;                 /* 0: --quick (default), 1: --full */
  unsigned long seed;       /* base seed (--seed) */
  const char *outdir;       /* output directory (exists) */
  FILE *progress;           /* progress messages (stderr), never NULL */
} sbv_ctx;

/* Growing list of comparison records, plus free-text notes per case. */
typedef struct sbv_report sbv_report;

/* Append a record; returns SB_SUCCESS or SB_ENOMEM. */
int sbv_add(sbv_report *rep, const sb_comparison *c);

/* Append a line of Markdown to the report's notes for the current case
 * (sample sizes, criteria, plot names).  printf-style. */
void sbv_note(sbv_report *rep, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

/* A fresh Mersenne-Twister generator seeded from (ctx->seed, stream):
 * give every case (and every independent part of a case) its own stream. */
gsl_rng *sbv_rng_alloc(const sbv_ctx *ctx, unsigned long stream);

/* A plot: columns of `data` (nrows x ncols, row-major) are written to
 * OUTDIR/NAME.dat with `header` as a comment; `gnuplot_body` is the plot
 * command(s) reading '$DATA' (replaced by the file name), written to
 * OUTDIR/NAME.gp; rendered to OUTDIR/NAME.png if gnuplot is found.  The
 * plot is recorded in the report.  Returns SB_SUCCESS or SB_EIO. */
int sbv_plot(const sbv_ctx *ctx, sbv_report *rep, const char *name,
             const char *title, const char *header, const double *data,
             size_t nrows, size_t ncols, const char *gnuplot_body);

typedef int (*sbv_case_fn)(const sbv_ctx *ctx, sbv_report *rep);

typedef struct {
  const char *name;         /* "V11/bridge-hit-times" */
  const char *description;  /* one line */
  sbv_case_fn run;
} sbv_case;

/* Cases provided by each module's file. */
extern const sbv_case sbv_cases_bridge[];   /* cli/cases_bridge.c */
extern const size_t sbv_ncases_bridge;
extern const sbv_case sbv_cases_langevin[]; /* cli/cases_langevin.c */
extern const size_t sbv_ncases_langevin;
extern const sbv_case sbv_cases_pbe[];      /* cli/cases_pbe.c */
extern const size_t sbv_ncases_pbe;
extern const sbv_case sbv_cases_engine[];   /* cli/cases_engine.c */
extern const size_t sbv_ncases_engine;
extern const sbv_case sbv_cases_engine2[];  /* cli/cases_engine2.c */
extern const size_t sbv_ncases_engine2;
extern const sbv_case sbv_cases_agglo[];   /* cli/cases_agglo.c */
extern const size_t sbv_ncases_agglo;

#endif /* SB_CLI_CASES_H */
