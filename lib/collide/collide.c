/* collide.c — the run description of <smolbridge/collide.h>: the
 * configuration read from files, strings and overrides, checked and set
 * up, with the first failure and the warnings kept for the caller (the
 * library prints nothing). */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "common/internal.h"

#include "collide_internal.h"

sb_collide *sb_collide_alloc(void)
{
  sb_collide *cl = calloc(1, sizeof *cl);
  if (!cl) {
    sbi_error(SB_ENOMEM, "sb_collide_alloc", "out of memory");
    return NULL;
  }
  sbi_col_defaults(&cl->c);
  return cl;
}

void sb_collide_free(sb_collide *cl)
{
  if (!cl)
    return;
  sbi_col_run_free(&cl->r);
  free(cl);
}

int sbi_col_failure(sb_collide *cl, sb_collide_failure kind, int status,
                    const char *msg)
{
  if (cl->failed)
    return cl->status;
  cl->failed = kind;
  cl->status = status;
  snprintf(cl->msg, sizeof cl->msg, "%s", msg);
  return status;
}

void sbi_col_more(sb_collide *cl, const char *fmt, ...)
{
  size_t n = strlen(cl->msg);
  if (n + 2 >= sizeof cl->msg)
    return;
  if (n)
    cl->msg[n++] = '\n';
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(cl->msg + n, sizeof cl->msg - n, fmt, ap);
  va_end(ap);
}

/* An input error found by the configuration code (c.err), or the earlier
 * failure. */
static int input_error(sb_collide *cl)
{
  return sbi_col_failure(cl, SB_COLLIDE_EINPUT, SB_EINVAL, cl->c.err);
}

/* Keys are added before the checks only: SB_SUCCESS, or the failure. */
static int reading(sb_collide *cl, const char *func)
{
  if (cl->failed)
    return cl->status;
  if (!cl->checked)
    return SB_SUCCESS;
  char msg[120];
  snprintf(msg, sizeof msg, "%s: the configuration is already checked",
           func);
  return sbi_col_failure(cl, SB_COLLIDE_EINPUT, SB_EINVAL, msg);
}

int sb_collide_read_file(sb_collide *cl, const char *path)
{
  int st = reading(cl, "sb_collide_read_file");
  if (st)
    return st;
  return sbi_col_read_file(&cl->c, path) ? input_error(cl) : SB_SUCCESS;
}

int sb_collide_read_string(sb_collide *cl, const char *text,
                           const char *name)
{
  int st = reading(cl, "sb_collide_read_string");
  if (st)
    return st;
  return sbi_col_read_string(&cl->c, text ? text : "",
                             name ? name : "string")
             ? input_error(cl)
             : SB_SUCCESS;
}

int sb_collide_set(sb_collide *cl, const char *assignment)
{
  int st = reading(cl, "sb_collide_set");
  if (st)
    return st;
  return sbi_col_override(&cl->c, assignment ? assignment : "")
             ? input_error(cl)
             : SB_SUCCESS;
}

int sb_collide_check(sb_collide *cl)
{
  if (cl->failed)
    return cl->status;
  if (cl->checked)
    return SB_SUCCESS;
  cl->checked = 1;
  return sbi_col_check(&cl->c) ? input_error(cl) : SB_SUCCESS;
}

int sb_collide_setup(sb_collide *cl)
{
  int st = sb_collide_check(cl);
  if (st || cl->set_up)
    return st;
  cl->set_up = 1;
  if (sbi_col_setup(&cl->c, &cl->r)) {
    sbi_col_run_free(&cl->r);
    return input_error(cl);
  }
  return SB_SUCCESS;
}

sb_collide_failure sb_collide_failed(const sb_collide *cl)
{
  return cl->failed;
}

const char *sb_collide_error(const sb_collide *cl)
{
  return cl->failed ? cl->msg : "";
}

size_t sb_collide_nwarnings(const sb_collide *cl)
{
  return (size_t)cl->c.nwarn;
}

const char *sb_collide_warning(const sb_collide *cl, size_t i)
{
  return i < (size_t)cl->c.nwarn ? cl->c.warn[i] : NULL;
}

const char *sb_collide_output(const sb_collide *cl) { return cl->c.output; }

const char *sb_collide_checkpoint(const sb_collide *cl)
{
  return cl->c.checkpoint;
}

const sb_engine *sb_collide_engine(const sb_collide *cl) { return cl->r.e; }

const sb_agglo *sb_collide_agglo(const sb_collide *cl)
{
  return cl->r.agglo;
}

int sb_collide_has_firsthit(const sb_collide *cl) { return cl->r.fh != NULL; }

const char *sb_collide_species_name(const sb_collide *cl, size_t k)
{
  return cl && (int)k < cl->c.nsp ? sbi_col_short_name(&cl->c, k) : NULL;
}

int sb_collide_firsthit(const sb_collide *cl,
                        sb_engine_firsthit_kernel_result *o)
{
  int st = sbi_col_firsthit_result(&cl->r, &cl->c, o);
  if (st < 0)
    return sbi_error(SB_EINVAL, "sb_collide_firsthit", "no first-hit "
                     "observer: [observe] first_hit = yes and "
                     "sb_collide_setup are needed");
  if (st == SB_EDOM && cl->c.nsp > 1)
    return sbi_error(SB_EDOM, "sb_collide_firsthit", "%d species: one kernel "
                     "per species pair (sb_collide_firsthit_pair); the "
                     "counts are those of all pairs", cl->c.nsp);
  return st;
}

int sb_collide_firsthit_pair(const sb_collide *cl, size_t a, size_t b,
                             sb_engine_firsthit_kernel_result *o)
{
  if (!cl || !o)
    return sbi_error(SB_EINVAL, __func__, "NULL argument");
  if (!cl->r.fh)
    return sbi_error(SB_EINVAL, __func__, "no first-hit observer: [observe] "
                     "first_hit = yes and sb_collide_setup are needed");
  if (a >= (size_t)cl->c.nsp || b >= (size_t)cl->c.nsp)
    return sbi_error(SB_EINVAL, __func__, "species pair (%zu, %zu): the run "
                     "has %d species (0 .. %d, in the order of their "
                     "sections)", a, b, cl->c.nsp, cl->c.nsp - 1);
  return sbi_col_firsthit_pair(&cl->r, &cl->c, a < b ? a : b, a < b ? b : a,
                               o);
}
