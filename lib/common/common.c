/* common.c — status strings, the per-thread error record, version. */
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "internal.h"

/* The one piece of state the library keeps: each thread's last error. */
static _Thread_local struct {
  int status;
  char msg[512];
} last_error;

static const char *const status_text[SB_ENSTATUS] = {
    [SB_SUCCESS] = "success",
    [SB_EDOM] = "argument outside the domain",
    [SB_ERANGE] = "result out of range (overflow)",
    [SB_EINVAL] = "invalid argument",
    [SB_ENOMEM] = "out of memory",
    [SB_EMAXITER] = "iteration limit reached without convergence",
    [SB_EUNDRFLW] = "result underflows",
    [SB_ELOSS] = "loss of accuracy",
    [SB_ESOLVER] = "external solver failed",
    [SB_EIO] = "input/output error",
    [SB_EFORMAT] = "malformed input",
    [SB_EUNIMPL] = "not available in this build",
};

const char *sb_strerror(int status)
{
  if (status < 0 || status >= SB_ENSTATUS || status_text[status] == NULL)
    return "unknown status code";
  return status_text[status];
}

/* Formatted into a local buffer first: callers wrap the previous message
 * (sbi_error(st, func, "...: %s", sb_last_error())), an argument that
 * lies in last_error.msg itself, which vsnprintf may not overwrite while
 * it reads it. */
static void record(int status, const char *func, const char *fmt,
                   va_list ap)
{
  char buf[sizeof last_error.msg];
  int n = snprintf(buf, sizeof buf, "%s: ", func ? func : "smolbridge");
  if (n < 0)
    n = 0;
  if ((size_t)n < sizeof buf)
    vsnprintf(buf + n, sizeof buf - (size_t)n, fmt, ap);
  memcpy(last_error.msg, buf, sizeof buf);
  last_error.status = status;
}

int sbi_error(int status, const char *func, const char *fmt, ...)
{
  va_list ap;
  va_start(ap, fmt);
  record(status, func, fmt, ap);
  va_end(ap);
  return status;
}

int sbi_fail_res(sb_result *res, int status, const char *func,
                 const char *fmt, ...)
{
  va_list ap;
  if (res) {
    res->val = NAN;
    res->err = NAN;
  }
  va_start(ap, fmt);
  record(status, func, fmt, ap);
  va_end(ap);
  return status;
}

const char *sb_last_error(void) { return last_error.msg; }
int sb_last_status(void) { return last_error.status; }

void sb_clear_error(void)
{
  last_error.status = SB_SUCCESS;
  last_error.msg[0] = '\0';
}

const char *sb_version(void) { return SB_VERSION_STRING; }
int sb_version_major(void) { return SB_VERSION_MAJOR; }
int sb_version_minor(void) { return SB_VERSION_MINOR; }
int sb_version_patch(void) { return SB_VERSION_PATCH; }
