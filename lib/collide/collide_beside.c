/* collide_beside.c — the state a run keeps beside its engine checkpoint:
 * the first-contact observer's counts ([observe] first_hit:
 * CHECKPOINT.firsthit, sb_engine_firsthit_save) or the agglomeration
 * context's sizes and series (outcome = merge | dlvo: CHECKPOINT.agglo,
 * sb_agglo_save), so that a restart goes on as if the run had not
 * stopped. */
#include <stdio.h>

#include <smolbridge/engine.h>
#include <smolbridge/engine_firsthit.h>

#include "collide_internal.h"
#include "common/internal.h"

int sbi_col_beside(const sbi_col_config *c, const char *checkpoint,
                   char *buf, size_t len)
{
  const char *suffix = c->first_hit       ? "firsthit"
                       : sbi_col_agglo(c) ? "agglo"
                                          : NULL;
  if (!suffix)
    return 1;
  snprintf(buf, len, "%s.%s", checkpoint, suffix);
  return 0;
}

int sbi_col_restart_beside(const sbi_col_config *c, const char *lost,
                           char *buf, size_t len)
{
  if (sbi_col_beside(c, c->restart, buf, len))
    return SB_SUCCESS;
  FILE *f = fopen(buf, "rb");
  if (!f)
    return sbi_error(SB_EIO, "restart", "no %s beside the checkpoint (it "
                     "is written with the checkpoint of a run with %s): "
                     "%s is unknown", buf,
                     c->first_hit ? "first_hit" : "merging", lost);
  fclose(f);
  return SB_SUCCESS;
}

int sbi_col_save_beside(const sbi_col_config *c, const sbi_col_run *r)
{
  char path[600];
  if (!c->checkpoint[0] || sbi_col_beside(c, c->checkpoint, path,
                                          sizeof path))
    return SB_SUCCESS;
  return r->fh ? sb_engine_firsthit_save(r->fh, r->e, path)
               : sb_agglo_save(r->agglo, r->e, path);
}
