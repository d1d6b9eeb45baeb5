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
 *  - ctx->full selects the sample sizes of the source studies (Mohaupt
 *    2011, Thomine 2008); quick mode must keep the
 *    whole quick suite under two minutes (aim for a few seconds per case);
 *  - state sample size and criterion in the record name or in the notes;
 *  - optionally write a plot with sbv_plot() (data file + gnuplot script in
 *    ctx->outdir, rendered by the caller's render callback).
 */
#ifndef SB_VALIDATE_CASES_H
#define SB_VALIDATE_CASES_H

#include <stdio.h>
#include <gsl/gsl_rng.h>
#include <smolbridge/engine.h>
#include <smolbridge/stats.h>
#include <smolbridge/pgd.h>
#include <smolbridge/validate.h>

/* Growing list of comparison records, plus free-text notes per case. */
typedef struct sb_validate_report sbv_report;

typedef struct {
  int full;                 /* 0: quick (default), 1: full */
  unsigned long seed;       /* base seed */
  const char *outdir;       /* plot directory (exists), or NULL */
  const sb_validate_options *opt;  /* callbacks */
  const char *ini_dir;      /* write mode (ini.c), or NULL */
  sbv_report *ini_rep;      /* write mode: the report of the case */
} sbv_ctx;


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

/* ------------------------------------------------------ rows (records.c)
 * Each helper appends one comparison row with its rule (sb_rule) and the
 * interval that rule reads.  Tests are at level SBV_ALPHA: a quick run
 * makes ~250 rows, so a correct code fails a given run with probability
 * about 250 SBV_ALPHA = 2.5% (family-wise). */
#define SBV_ALPHA 1e-4

/* k successes in n trials vs probability P: exact binomial test and the
 * Clopper-Pearson interval at 1 - SBV_ALPHA (rule cover). */
int sbv_add_freq(sbv_report *rep, const char *name, unsigned long k,
                 unsigned long n, double P);
/* Rate scale * k from a Poisson count vs reference: exact test, Garwood
 * interval (rule cover). */
int sbv_add_poisson(sbv_report *rep, const char *name, unsigned long k,
                    double scale, double reference);
/* The same for a count whose variance is `dispersion` times its mean
 * (first contacts: fh_out.dispersion): the Garwood interval widened by
 * sqrt(dispersion) above 1, approximate (sb_compare_poisson_dispersed). */
int sbv_add_poisson_dispersed(sbv_report *rep, const char *name,
                              unsigned long k, double dispersion,
                              double scale, double reference);
/* A pair kernel's row K_e/K_th (sb_engine_pair_kernel): its count's
 * Poisson test, widened by the count's dispersion where the engine tallied
 * the collisions (sb_engine_set_count_variance), or, with info, an
 * informational row of the same interval; and a note with the count
 * (`what`: "collisions", "contacts"), the estimates and the dispersion. */
int sbv_add_pair_kernel(sbv_report *rep, const char *name,
                        const sb_engine_pair_stats *ps, double Kth,
                        int info, const char *what);
/* Mean of n >= 2 independent replicas vs reference: t interval and test. */
int sbv_add_mean(sbv_report *rep, const char *name, const double *x,
                 size_t n, double reference);
/* Chi-square statistic (reference: its dof) in the acceptance region
 * [0, chi2_{1-SBV_ALPHA}(dof)]; test_status from sb_chi2_test (a failed
 * test fails the row; SB_ELOSS, small expected counts, does not). */
int sbv_add_chi2(sbv_report *rep, const char *name, int test_status,
                 double chi2, double dof, double p);
/* KS distance of n samples in [0, D_crit(n, SBV_ALPHA)] (reference: the
 * mean of D_n under H0, 0.8687/sqrt(n)); p the KS p-value. */
int sbv_add_ks(sbv_report *rep, const char *name, size_t n, double d,
               double p);
/* Median of m sorted samples xs vs the reference median: exact
 * order-statistic interval at 1 - SBV_ALPHA and the sign test. */
int sbv_add_median(sbv_report *rep, const char *name, const double *xs,
                   size_t m, double med_ref);
/* Deterministic comparison: reference inside [lo, hi] (rule band), a
 * tolerance around est, which must lie in it (else the row fails); the
 * relative form uses est (1 -+ tol). */
int sbv_add_band(sbv_report *rep, const char *name, double est, double ref,
                 double lo, double hi);
int sbv_add_relband(sbv_report *rep, const char *name, double est,
                    double ref, double tol);
/* Demonstration of an expected failure: the interval [lo, hi] at `level`
 * lies entirely above (above = 1) or below the reference. */
int sbv_add_side(sbv_report *rep, const char *name, int above, double est,
                 double ref, double lo, double hi, double level, double p);
/* Descriptive row (never fails). */
int sbv_add_info(sbv_report *rep, const char *name, double est, double ref,
                 double lo, double hi, double level);

/* Root of f in the bracket [lo, hi] (signs must differ at the ends) by
 * GSL's Brent solver to relative tolerance rtol; NaN if not bracketed. */
double sbv_brent(double (*f)(double, void *), void *par, double lo,
                 double hi, double rtol);

/* The engine of V2's thesis-protocol run id (0, 1, 2: d_p = 0.75, 1,
 * 2 um; base seed 12345, one thread, reinsert outcome) at its start, its
 * particles *n and the steps of the whole run *nsteps (cases_v2.c), for
 * bench/bench_v2_thesis's cost per step.  Free with sb_engine_free. */
int sbv_v2_thesis_engine(int id, size_t *n, double *nsteps, sb_engine **e);

/* A fresh Mersenne-Twister generator seeded from (ctx->seed, stream):
 * give every independent part of a case its own stream.  Streams are not
 * unique across cases (several cases use 100+, 200+ or 300+); a new case
 * should take a range no case uses, so that it is independent of the
 * others (changing an existing case's streams changes its records and
 * needs its calibration again). */
gsl_rng *sbv_rng_alloc(const sbv_ctx *ctx, unsigned long stream);
/* Its seed (MT19937 seeds modulo 2^32): a collide file's placement_seed
 * for a placement drawn from sbv_rng_alloc(ctx, stream). */
unsigned long sbv_rng_seed(const sbv_ctx *ctx, unsigned long stream);

/* sb_engine_params_default with the engine's generator pinned to MT19937
 * and the transport drawing from it (streams = 0): the set-up the cases
 * were calibrated with (docs/validation.md), whatever the library's
 * default generator.  A case's collide file says `rng = mt19937`. */
void sbv_engine_params(sb_engine_params *p);

/* A plot: columns of `data` (nrows x ncols, row-major) are written to
 * OUTDIR/NAME.dat with `header` as a comment; `gnuplot_body` is the plot
 * command(s) reading '$DATA' (replaced by the file name), written to
 * OUTDIR/NAME.gp; rendered to OUTDIR/NAME.png by the caller's render
 * callback, if any.  The plot is recorded in the report.  Returns
 * SB_SUCCESS (nothing written when there is no outdir) or SB_EIO. */
int sbv_plot(const sbv_ctx *ctx, sbv_report *rep, const char *name,
             const char *title, const char *header, const double *data,
             size_t nrows, size_t ncols, const char *gnuplot_body);

/* ------------------------------------------------- write mode (ini.c)
 * sb_validate_write_ini runs a case with ctx->ini_dir set: each engine run
 * that `smolbridge collide` can reproduce is written as DIR/RUN.ini
 * instead of being run, and returns unit values (K = 1, one hit), so that
 * the record the case then adds has as its estimate the factor between a
 * summary.json field and the record ("; expect" lines).  Runs that collide
 * cannot reproduce are listed with sbv_ini_skip. */
int sbv_writing(const sbv_ctx *ctx);
/* Open DIR/RUN.ini with its header and "[run]\noutput = RUN-out"; the
 * caller writes the other [run] keys, then the sections. */
FILE *sbv_ini_begin(const sbv_ctx *ctx, sbv_report *rep, const char *run,
                    const char *what);
/* Close it; `field` (may be NULL) is the summary.json field of the next
 * record added (sbv_add appends its expect line). */
int sbv_ini_end(sbv_report *rep, FILE *f, const char *field);
/* Append "; expect RECORD = FIELD * FACTOR" to the last file. */
/* The current run's file gets no expect line from the next record (a
 * record that compares several runs). */
void sbv_ini_no_expect(sbv_report *rep);
void sbv_ini_expect(sbv_report *rep, const char *record, const char *field,
                    double factor);
/* Append "; expect-mean RECORD = FIELD * FACTOR": the record is the mean
 * of FIELD * FACTOR over every file of the case with this line (a record
 * that is a mean over independent runs, e.g. field realizations). */
void sbv_ini_expect_mean(sbv_report *rep, const char *record,
                         const char *field, double factor);
/* An ensemble of runs of one file (realizations that differ only in
 * their seeds): point k's overrides ("run.seed=... fluid.seed=...",
 * printf-style) as line k of DIR/RUN.sweep.txt, run with `smolbridge
 * collide RUN.ini --sweep RUN.sweep.txt` (point k in
 * OUTPUT/point_NNN/); "; expect-sweep-mean RECORD = FIELD * FACTOR":
 * the record is the mean of FIELD * FACTOR over the points. */
int sbv_ini_sweep_point(sbv_report *rep, size_t k, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;
void sbv_ini_expect_sweep_mean(sbv_report *rep, const char *record,
                               const char *field, double factor);
/* Append "; expect-grid RECORD = grid.csv STAT FRAME REF * FACTOR": the
 * record is a statistic of the counts k = nearbyint(rho * FACTOR) of grid
 * frame FRAME (from 1; collide's [observe] grid) against REF (a CSV
 * beside the file, "i,j,lambda,outside", one row per cell in grid.csv's
 * order): STAT chi2 = sum over lambda > 0 of (k - lambda)^2 / lambda,
 * ratio = (1 / sum lambda) * sum k over lambda > 0, outside = sum k over
 * the cells with outside = 1 (docs/validation.md). */
void sbv_ini_expect_grid(sbv_report *rep, const char *record,
                         const char *stat, int frame, const char *ref,
                         double factor);
/* Append "; KIND RECORD = SPEC": a record recomputed from collide's
 * output tables, pooled over every file of the case with this line
 * (docs/validation.md lists the kinds: expect-ks, expect-chi2,
 * expect-max, expect-h-rises, expect-diff-mean, expect-batches). */
void sbv_ini_expect_stat(sbv_report *rep, const char *kind,
                         const char *record, const char *spec);
/* A run left out, and why (printf-style). */
void sbv_ini_skip(sbv_report *rep, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

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
extern const sbv_case sbv_cases_v2[];
extern const size_t sbv_ncases_v2;
extern const sbv_case sbv_cases_engine2[];
extern const size_t sbv_ncases_engine2;
extern const sbv_case sbv_cases_agglo[];
extern const size_t sbv_ncases_agglo;
extern const sbv_case sbv_cases_pgd[];
extern const size_t sbv_ncases_pgd;
extern const sbv_case sbv_cases_pgd_jets[];
extern const size_t sbv_ncases_pgd_jets;
extern const sbv_case sbv_cases_pgd_dense[];
extern const size_t sbv_ncases_pgd_dense;
extern const sbv_case sbv_cases_pgd_engine[];
extern const size_t sbv_ncases_pgd_engine;
/* The crossing jets of the exercise "Couplage Euler-Lagrange" (2022) on an
 * n x n grid of the unit square, n a multiple of 45 (cases_pgd_jets.c):
 * inflow rho = 1 on the central ninth of the west side with velocity
 * (1, 0) and of the south side with (0, 1), outflow elsewhere, gas
 * velocity (ugx, ugy), relaxation time tau. */
void sbv_pgd_jets_params(sb_pgd_params *p, size_t n, double tau,
                         sb_pgd_scheme sc, double ugx, double ugy);
extern const sbv_case sbv_cases_spray[];
extern const size_t sbv_ncases_spray;
extern const sbv_case sbv_cases_v12[];
extern const size_t sbv_ncases_v12;
extern const sbv_case sbv_cases_pair[];
extern const size_t sbv_ncases_pair;
extern const sbv_case sbv_cases_transport[];
extern const size_t sbv_ncases_transport;
extern const sbv_case sbv_cases_v16[];
extern const size_t sbv_ncases_v16;
extern const sbv_case sbv_cases_v16c[];
extern const size_t sbv_ncases_v16c;
extern const sbv_case sbv_cases_v16d[];
extern const size_t sbv_ncases_v16d;

#endif /* SB_VALIDATE_CASES_H */
