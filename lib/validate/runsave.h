/* runsave.h — finished engine runs of a validation case kept on disk
 * (private to lib/validate).
 *
 * A --full validation runs for hours; a run that stops (killed, machine
 * reset) must not lose the engine runs it finished.  With
 * sb_validate_options.run_dir set, each first-hit run saves its results in
 * run_dir as one small file (text and a hash) named by a hash of its key; with
 * .resume also set, a run whose key is found there is read back instead
 * of being run again.  The key is the text of every input that decides
 * the result (kind of run, library version, base seed, stream and each
 * numeric input written exactly in C99 hexadecimal), and the file keeps
 * the whole key: a file is used only when its key equals the run's, so
 * a hash collision or a changed input can never hand a run another's
 * results.  What the key cannot see is a change of the code itself: a
 * developer who changes the engine between two invocations must empty
 * run_dir (docs/validation.md, "Resuming a long run").
 *
 * Values are written in hexadecimal floating point: a resumed run gives
 * the records bit for bit.  The file ends with the hash of its text
 * (runsave.c): one that does not match is refused, with a progress line,
 * and the run made again.  Files are written under a temporary name and
 * renamed, so a run killed while saving leaves no partial file; two
 * processes (MPI ranks, calibration seeds) may share run_dir.
 */
#ifndef SB_VALIDATE_RUNSAVE_H
#define SB_VALIDATE_RUNSAVE_H

#include <stddef.h>
#include "cases.h"

#define SBV_KEY_MAX 2048

typedef struct {
  char s[SBV_KEY_MAX];
  size_t n;
  int overflow;  /* the key did not fit: the run is neither read nor saved */
} sbv_runkey;

/* Start the key of a run of kind `kind` ("firsthit-lv") drawn from
 * `stream` of the context's base seed. */
void sbv_runkey_init(sbv_runkey *k, const sbv_ctx *ctx, const char *kind,
                     unsigned long stream);
/* Append the input `name` = v (exactly, %a). */
void sbv_runkey_num(sbv_runkey *k, const char *name, double v);

/* Read the results of the run with key k: 1 when found (vals[0..nvals)
 * filled; *extra a malloc'd array of *nextra values, NULL when none: the
 * caller frees it), 0 when the run must be made (no run_dir, no .resume,
 * no file with this key, or an unreadable one), SB_ENOMEM.  A run read
 * back says so on the progress line. */
int sbv_run_load(const sbv_ctx *ctx, const sbv_runkey *k, double *vals,
                 size_t nvals, double **extra, size_t *nextra);

/* sbv_run_load for a run saved without extra values (any are dropped). */
int sbv_run_load_vals(const sbv_ctx *ctx, const sbv_runkey *k,
                      double *vals, size_t nvals);

/* Save the results of the run with key k (no-op without run_dir).  A
 * failure to save does not stop the case: it is reported on the progress
 * line, and the run is simply made again by the next invocation. */
void sbv_run_save(const sbv_ctx *ctx, const sbv_runkey *k,
                  const double *vals, size_t nvals, const double *extra,
                  size_t nextra);

#endif /* SB_VALIDATE_RUNSAVE_H */
