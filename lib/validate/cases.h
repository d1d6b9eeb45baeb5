/* cases.h — what a validation case sees (private to lib/validate).
 *
 * A case runs a Monte Carlo (or numerical) experiment and appends one or
 * more comparison records (see <smolbridge/stats.h>) to a report.  Each
 * module's cases live in lib/validate/cases_MODULE.c and are listed in the
 * table of lib/validate/registry.c; the public interface is
 * <smolbridge/validate.h>.
 *
 * Rules for a case:
 *  - deterministic: use only the gsl_rng seeded from ctx->seed (create your
 *    own with sbv_rng_alloc(ctx, stream) so cases are independent of order);
 *  - ctx->full selects the seeds' sample sizes; quick mode must keep the
 *    whole quick suite under two minutes (aim for a few seconds per case);
 *  - state sample size and criterion in the record name or in the notes;
 *  - optionally write a plot with sbv_plot() (data file + gnuplot script in
 *    ctx->outdir, rendered by the caller's render callback).
 */
#ifndef SB_VALIDATE_CASES_H
#define SB_VALIDATE_CASES_H

#include <stdio.h>
#include <gsl/gsl_rng.h>
#include <smolbridge/stats.h>
#include <smolbridge/validate.h>

typedef struct {
  int full;                 /* 0: quick (default), 1: full */
  unsigned long seed;       /* base seed */
  const char *outdir;       /* plot directory (exists), or NULL */
  const sb_validate_options *opt;  /* callbacks */
} sbv_ctx;

/* Growing list of comparison records, plus free-text notes per case. */
typedef struct sb_validate_report sbv_report;

/* One progress line (printf-style, no newline) to the caller's progress
 * callback, if any. */
void sbv_progress(const sbv_ctx *ctx, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

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
 * OUTDIR/NAME.gp; rendered to OUTDIR/NAME.png by the caller's render
 * callback, if any.  The plot is recorded in the report.  Returns
 * SB_SUCCESS (nothing written when there is no outdir) or SB_EIO. */
int sbv_plot(const sbv_ctx *ctx, sbv_report *rep, const char *name,
             const char *title, const char *header, const double *data,
             size_t nrows, size_t ncols, const char *gnuplot_body);

typedef int (*sbv_case_fn)(const sbv_ctx *ctx, sbv_report *rep);

typedef struct {
  const char *name;         /* "V11/bridge-hit-times" */
  const char *description;  /* one line */
  sbv_case_fn run;
} sbv_case;

/* Cases provided by each module's file (lib/validate/cases_MODULE.c). */
extern const sbv_case sbv_cases_bridge[];
extern const size_t sbv_ncases_bridge;
extern const sbv_case sbv_cases_langevin[];
extern const size_t sbv_ncases_langevin;
extern const sbv_case sbv_cases_pbe[];
extern const size_t sbv_ncases_pbe;
extern const sbv_case sbv_cases_engine[];
extern const size_t sbv_ncases_engine;
extern const sbv_case sbv_cases_engine2[];
extern const size_t sbv_ncases_engine2;
extern const sbv_case sbv_cases_agglo[];
extern const size_t sbv_ncases_agglo;
extern const sbv_case sbv_cases_spray[];
extern const size_t sbv_ncases_spray;

#endif /* SB_VALIDATE_CASES_H */
