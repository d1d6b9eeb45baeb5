/* smolbridge/common.h — status codes, results with error estimates, errors,
 * version.
 *
 * Conventions used by every module (see docs/api.md):
 *  - `double sb_f(args)` returns the value, or NaN on a domain error;
 *  - `int sb_f_e(args, sb_result *res)` returns a status code and fills
 *    res->val and res->err (an honest absolute error estimate);
 *  - the library never prints, aborts or exits.  A failing call returns a
 *    status code and records a message that the calling thread can read with
 *    sb_last_error().  That per-thread record is the only state the library
 *    keeps; it is thread-local, so every routine is thread-safe.
 *
 * GSL note: GSL's default error handler aborts.  smolbridge checks arguments
 * before it calls GSL and uses solvers and quadratures in ways that report
 * failures by status, so GSL's handler is not reached for valid or invalid
 * smolbridge input.  The library never changes the handler (it is process-
 * wide: switching it would race with other threads); applications may
 * still call gsl_set_error_handler_off().
 */
#ifndef SMOLBRIDGE_COMMON_H
#define SMOLBRIDGE_COMMON_H

#include <smolbridge/version.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Status codes.  0 is success; every error is positive. */
enum {
  SB_SUCCESS = 0,
  SB_EDOM = 1,      /**< argument outside the function's domain */
  SB_ERANGE = 2,    /**< result not representable (overflow) */
  SB_EINVAL = 3,    /**< invalid argument or parameter combination */
  SB_ENOMEM = 4,    /**< allocation failed */
  SB_EMAXITER = 5,  /**< iterative method did not converge in its budget */
  SB_EUNDRFLW = 6,  /**< result underflows; value set to 0 (see _log form) */
  SB_ELOSS = 7,     /**< result computed with reduced accuracy (see err) */
  SB_ESOLVER = 8,   /**< an external solver (GSL, CVODE) failed */
  SB_EIO = 9,       /**< file input/output failed */
  SB_EFORMAT = 10,  /**< malformed input file or string */
  SB_EUNIMPL = 11,  /**< feature not available in this build */
  SB_ENSTATUS       /**< number of status codes (not a status) */
};

/** A value with an absolute error estimate: |val - exact| <= err. */
typedef struct {
  double val;
  double err;
} sb_result;

/** Short constant English description of a status code (never NULL). */
const char *sb_strerror(int status);

/** Message of the last error recorded in the calling thread ("" if none).
 *  The text names the function and the offending argument.  It stays valid
 *  until the next smolbridge call that fails in the same thread. */
const char *sb_last_error(void);

/** Status of the last error recorded in the calling thread (SB_SUCCESS if
 *  none since the last sb_clear_error()). */
int sb_last_status(void);

/** Forget the calling thread's last error. */
void sb_clear_error(void);

/** Create the directory `path` and its missing parents (as mkdir -p);
 *  an existing directory is fine.  SB_SUCCESS, SB_EINVAL (empty path) or
 *  SB_EIO with the reason in sb_last_error() (errno kept: ENOTDIR when
 *  the path names a file). */
int sb_mkdir_p(const char *path);

/** Version of the library actually linked (compare with SB_VERSION_STRING,
 *  the version of the headers compiled against). */
const char *sb_version(void);
int sb_version_major(void);
int sb_version_minor(void);
int sb_version_patch(void);

#ifdef __cplusplus
}
#endif

#endif /* SMOLBRIDGE_COMMON_H */
