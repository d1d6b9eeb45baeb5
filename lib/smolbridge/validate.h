/* smolbridge/validate.h — the validation suite as a library.
 *
 * A validation case runs a Monte Carlo (or numerical) experiment and
 * compares its estimates with the library's theoretical references; each
 * comparison is a record (sb_comparison, <smolbridge/stats.h>) with its
 * estimate, reference, interval, p-value and verdict.  This header lists
 * the registered cases, runs them into a report, and writes the report as
 * a table, CSV or Markdown.  `smolbridge validate` is a thin front end to
 * it (docs/validation.md describes every case and its verdict rule).
 *
 * Typical use:
 *
 *   sb_validate_options opt;
 *   sb_validate_options_init(&opt);            // quick mode, seed 12345
 *   sb_validate_report *rep = sb_validate_report_alloc();
 *   size_t i;
 *   if (sb_validate_case_index("V9/two-spheres-45", &i) == SB_SUCCESS)
 *     sb_validate_run(i, &opt, rep);
 *   for (size_t k = 0; k < sb_validate_report_nrecords(rep); k++) {
 *     const sb_comparison *c = sb_validate_report_record(rep, k);
 *     ...
 *   }
 *   sb_validate_report_free(rep);
 *
 * Determinism: a case draws only from generators seeded by the base seed
 * and stream numbers fixed in the case, so the same options give
 * bit-identical records whatever the order or selection of cases.  The
 * stream numbers are distinct within a case, not across cases (V2's and
 * V5's engine runs and a V13 spray case all use streams from 200 on): two
 * cases of one run are not independent samples of each other, while each
 * case's verdicts, and their calibration over seeds, are unaffected.
 * Cases are thread-safe as long as two threads do not share a report;
 * plot files of two concurrent runs must go to different directories.
 *
 * The library never prints.  Progress lines go to the optional progress
 * callback; plots are written as data (.dat) and gnuplot scripts (.gp) into
 * `outdir`, and rendered only through the optional render callback (the
 * command-line tool passes one that runs gnuplot).
 */
#ifndef SMOLBRIDGE_VALIDATE_H
#define SMOLBRIDGE_VALIDATE_H

#include <stddef.h>
#include <stdio.h>
#include <smolbridge/common.h>
#include <smolbridge/stats.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Receives one progress line (no trailing newline). */
typedef void (*sb_validate_progress_fn)(const char *line, void *data);

/** Renders the gnuplot script `script` (a file name relative to `dir`);
 *  returns 0 when a picture was made.  `dir` is the options' outdir. */
typedef int (*sb_validate_render_fn)(const char *dir, const char *script,
                                     void *data);

/** How to run cases. */
typedef struct {
  int full;                /**< 0: quick sample sizes; 1: the full ones */
  unsigned long seed;      /**< base seed: same seed, same records */
  const char *outdir;      /**< existing directory for plot data and
                                scripts; NULL writes no plot files */
  sb_validate_progress_fn progress; /**< NULL: no progress lines */
  void *progress_data;
  sb_validate_render_fn render;     /**< NULL: plots are not rendered */
  void *render_data;
  const char *run_dir;     /**< directory where each finished engine run
                                of a case is saved (one small file
                                per run; created if missing; today the
                                first-hit kernel runs of V2-V5, V7, VX,
                                V12 and V16's Langevin cases, V2's thesis
                                runs); NULL: runs are not saved */
  int resume;              /**< 1: a run saved in run_dir with exactly the
                                same inputs (seed, stream, every parameter,
                                library version) is read back instead of
                                run again, bit for bit: a long --full run
                                that was stopped resumes where it was.  A
                                file that does not match the hash at its
                                end (cut short or changed) is refused,
                                said so on a progress line, and the run
                                made again; files without a hash (written
                                before it) are still read.  The
                                inputs do not include the code: empty
                                run_dir after changing the library */
} sb_validate_options;

/** Defaults: quick mode, seed 12345, no outdir, no callbacks, runs not
 *  saved. */
void sb_validate_options_init(sb_validate_options *opt);

/* ------------------------------------------------------------- registry */

/** Number of registered cases. */
size_t sb_validate_ncases(void);

/** Name ("V4/bridge-brownian") and one-line description of case i, in
 *  run order; NULL (SB_EINVAL recorded) when i >= sb_validate_ncases(). */
const char *sb_validate_case_name(size_t i);
const char *sb_validate_case_description(size_t i);

/** Index of the case called exactly `name`; SB_EINVAL if there is none. */
int sb_validate_case_index(const char *name, size_t *index);

/** Write the engine runs of case `index` as `smolbridge collide`
 *  configurations DIR/RUN.ini (DIR must exist) instead of running them:
 *  the same options (mode, seed) give files whose runs reproduce the
 *  case's estimates; "; expect RECORD = FIELD [* FACTOR]" comment lines
 *  say which summary.json field gives each record.  Runs collide cannot
 *  reproduce are listed in DIR/NOT-WRITTEN.txt.  *nfiles (may be NULL)
 *  receives the number of files.  SB_EINVAL for a case without engine runs
 *  collide reproduces (the message lists those that have), SB_EIO. */
int sb_validate_write_ini(size_t index, const sb_validate_options *opt,
                          const char *dir, size_t *nfiles);

/* ------------------------------------------------------------- reports */

/** Records, notes and timings of the cases run into it. */
typedef struct sb_validate_report sb_validate_report;

/** A new empty report (NULL and SB_ENOMEM recorded on failure). */
sb_validate_report *sb_validate_report_alloc(void);
void sb_validate_report_free(sb_validate_report *rep);

/** Run case `index` and append its records, notes and timing to `rep`.
 *  Returns the case's status: SB_SUCCESS when it ran to the end (its
 *  records may still have failing verdicts), otherwise the error that
 *  stopped it (the records made before stay in the report and the case
 *  counts as failed).  SB_EINVAL for a bad index, NULL options or report. */
int sb_validate_run(size_t index, const sb_validate_options *opt,
                    sb_validate_report *rep);

/** Comparison records, in the order the cases made them. */
size_t sb_validate_report_nrecords(const sb_validate_report *rep);
const sb_comparison *sb_validate_report_record(const sb_validate_report *rep,
                                               size_t i);

/** Cases run into the report: name, status returned by the case, wall
 *  time in seconds, Markdown notes ("" if none) and their records
 *  (first, count).  Out-of-range k gives NULL / SB_EINVAL / NaN / 0. */
size_t sb_validate_report_ncases(const sb_validate_report *rep);
const char *sb_validate_report_case_name(const sb_validate_report *rep,
                                         size_t k);
int sb_validate_report_case_status(const sb_validate_report *rep, size_t k);
double sb_validate_report_case_seconds(const sb_validate_report *rep,
                                       size_t k);
const char *sb_validate_report_case_notes(const sb_validate_report *rep,
                                          size_t k);
size_t sb_validate_report_case_records(const sb_validate_report *rep,
                                       size_t k, size_t *first);

/** Failed records plus cases that did not complete. */
size_t sb_validate_report_nfailed(const sb_validate_report *rep);

/** The cases of rep (records, notes, status, seconds) as a malloc'd byte
 *  buffer *buf of *len bytes (free() it), for sending to another process
 *  of the same program (an MPI rank: `mpirun smolbridge validate`).  The
 *  buffer is a memory image: read it back with the same build only.
 *  SB_EINVAL (NULL argument), SB_ENOMEM. */
int sb_validate_report_pack(const sb_validate_report *rep, void **buf,
                            size_t *len);

/** Append the cases of a buffer from sb_validate_report_pack to rep, as
 *  if they had been run into it (in their order).  Case names are matched
 *  to the registry.  SB_EFORMAT for a malformed buffer or an unknown case
 *  (rep may then hold the cases read before the error), SB_ENOMEM. */
int sb_validate_report_append_packed(sb_validate_report *rep,
                                     const void *buf, size_t len);

/** The comparison table, one line per record (and one per case that did
 *  not complete).  SB_EIO if writing fails. */
int sb_validate_report_fprint(const sb_validate_report *rep, FILE *out);

/** validate.csv: SB_COMPARISON_CSV_HEADER and one line per record. */
int sb_validate_report_write_csv(const sb_validate_report *rep,
                                 const char *path);

/** report.md: verdict rules, then per case its notes, plots and table.
 *  `opt` gives the mode and seed printed in the heading. */
int sb_validate_report_write_markdown(const sb_validate_report *rep,
                                      const char *path,
                                      const sb_validate_options *opt);

/* ---------------------------------------------------------- calibration
 * One seed's "pass" is weak evidence.  A calibration pools the reports of
 * the same cases run with independent seeds: per record the mean of
 * estimate/reference (or estimate - reference when the reference is 0)
 * with its Student 95% interval and the bias in standard errors, the
 * fraction of p-values below 0.05 and a Kolmogorov-Smirnov test of the
 * p-values against the uniform law.  `smolbridge validate --seeds N`. */

typedef struct sb_validate_calibration sb_validate_calibration;

/** One record pooled over seeds. */
typedef struct {
  char name[96];        /**< record name */
  char case_name[96];   /**< the case that made it */
  sb_rule rule;         /**< its verdict rule */
  size_t nseeds;        /**< seeds in which the record appeared */
  size_t nfail;         /**< seeds in which it failed */
  int deterministic;    /**< the same estimate in every seed */
  int is_ratio;         /**< 1: mean of estimate/reference (target 1);
                             0: of estimate - reference (target 0) */
  double mean, mean_lo, mean_hi; /**< pooled value, Student 95% interval */
  double bias_z;        /**< (mean - target) / standard error */
  double bias_p;        /**< two-sided Student t test p-value of it */
  size_t npvalues;      /**< p-values pooled */
  double frac_p05;      /**< fraction of them below 0.05 */
  double ks_d, ks_p;    /**< KS of the p-values vs U(0,1); NaN when fewer
                             than 5 or fewer than 80% distinct (discrete
                             tests on small counts) */
  /** FAIL: bias_p < 0.0027 (|z| > 3 for a normal statistic; Student's
   *  law with few seeds) or ks_p < 1e-3 (cover/accept rows), or any failed
   *  seed (demonstrations and tolerance bands, which must hold on every
   *  seed); PASS otherwise; INFO for informational and deterministic rows
   *  that never failed. */
  sb_verdict verdict;
} sb_validate_calibration_row;

/** All rows of one case pooled. */
typedef struct {
  char case_name[96];
  size_t nrows, nrows_failed;       /**< records, and failing ones */
  size_t nrecords, nrecords_failed; /**< record-seeds, failing ones */
  double max_abs_bias_z;            /**< over cover/accept rows */
  size_t npvalues;
  double frac_p05, ks_d, ks_p;      /**< over all p-values of the case */
  sb_verdict verdict;               /**< FAIL iff a row fails */
} sb_validate_calibration_case_summary;

sb_validate_calibration *sb_validate_calibration_alloc(void);
void sb_validate_calibration_free(sb_validate_calibration *c);

/** Pool the records of one seed's report (call once per seed). */
int sb_validate_calibration_add(sb_validate_calibration *c,
                                const sb_validate_report *rep);

size_t sb_validate_calibration_nseeds(const sb_validate_calibration *c);
size_t sb_validate_calibration_nrows(const sb_validate_calibration *c);
/** Row i (in first-seen order); SB_EINVAL out of range. */
int sb_validate_calibration_get_row(const sb_validate_calibration *c,
                                    size_t i,
                                    sb_validate_calibration_row *row);
/** The cases pooled, in first-seen order, and the summary of one. */
size_t sb_validate_calibration_ncases(const sb_validate_calibration *c);
const char *sb_validate_calibration_case_name(
    const sb_validate_calibration *c, size_t k);
int sb_validate_calibration_case(const sb_validate_calibration *c,
                                 const char *case_name,
                                 sb_validate_calibration_case_summary *sum);

/** calibration.csv: one line per record (header first). */
int sb_validate_calibration_write_csv(const sb_validate_calibration *c,
                                      const char *path);
/** The per-record table. */
int sb_validate_calibration_fprint(const sb_validate_calibration *c,
                                   FILE *out);
/** p-value QQ plot, one curve per case: OUTDIR/NAME.dat and NAME.gp,
 *  rendered through opt->render (nothing when opt->outdir is NULL). */
int sb_validate_calibration_qq_plot(const sb_validate_calibration *c,
                                    const sb_validate_options *opt,
                                    const char *name);

#ifdef __cplusplus
}
#endif

#endif /* SMOLBRIDGE_VALIDATE_H */
