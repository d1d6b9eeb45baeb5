/* internal.h — helpers shared by the library's modules.  Not installed.
 * Internal symbols use the prefix `sbi_`; the shared library exports only
 * `sb_*`, so these are reachable from the tests (which link the convenience
 * library libsbcore.la) but not from applications. */
#ifndef SB_INTERNAL_H
#define SB_INTERNAL_H

#include <math.h>
#include <stdio.h>
#include <smolbridge/common.h>

#if defined(__GNUC__)
#define SBI_PRINTF(f, a) __attribute__((format(printf, f, a)))
#else
#define SBI_PRINTF(f, a)
#endif

/* Record an error for the calling thread and return `status`.
 * `func` is the public function's name; the message should name the
 * offending argument and its value. */
int sbi_error(int status, const char *func, const char *fmt, ...)
    SBI_PRINTF(3, 4);

/* For `_e` functions: set *res (if not NULL) to NaN, record the message,
 * return status. */
int sbi_fail_res(sb_result *res, int status, const char *func,
                 const char *fmt, ...) SBI_PRINTF(4, 5);
#define SBI_FAIL_RES(res, status, ...) \
  sbi_fail_res((res), (status), __func__, __VA_ARGS__)

/* Saved states (fsutil.c). */
/* A saved state's file opened for reading (*status SB_SUCCESS), or NULL
 * with *status SB_EINVAL (path NULL) or SB_EIO and the message from
 * func. */
FILE *sbi_open_saved(const char *path, const char *func, int *status);
/* A file opened to save a state to path, or NULL with the message from
 * func (SB_EIO). */
FILE *sbi_open_for_save(const char *path, const char *func);
/* Close the save's file f: SB_SUCCESS if every write succeeded (ok) and
 * so did the close, else SB_EIO with the message from func and the
 * partial file removed (a failed save leaves no file behind). */
int sbi_finish_save(FILE *f, int ok, const char *path, const char *func);

#endif /* SB_INTERNAL_H */
