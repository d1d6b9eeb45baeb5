/* collide_beside.c — the state a run keeps beside its engine checkpoint,
 * so that a restart goes on as if the run had not stopped:
 *  - the counts: the first-contact observer's ([observe] first_hit:
 *    CHECKPOINT.firsthit, sb_engine_firsthit_save) or the agglomeration
 *    context's sizes and series (outcome = merge | dlvo: CHECKPOINT.agglo,
 *    sb_agglo_save);
 *  - the random field ([fluid] type = ou-field | kraichnan:
 *    CHECKPOINT.field, sb_field_ou_save, sb_field_kraichnan_save);
 *  - the recorded contacts ([observe] first_hit_velocities:
 *    CHECKPOINT.contacts, collide_contacts.c);
 *  - a bridge detector's counters and hit records (detect = bridge |
 *    exact: CHECKPOINT.bridge, sb_engine_bridge_save);
 *  - the outputs' part before the checkpoint (CHECKPOINT.run,
 *    collide_runstate.c). */
#include <stdio.h>
#include <string.h>

#include <smolbridge/engine.h>
#include <smolbridge/engine_bridge.h>
#include <smolbridge/engine_field.h>
#include <smolbridge/engine_firsthit.h>

#include "collide_internal.h"
#include "common/internal.h"

/* The file name's suffix of state `which` of the run, or NULL. */
static const char *suffix_of(const sbi_col_config *c, int which)
{
  if (which == SBI_BESIDE_RUN)
    return "run";
  if (which == SBI_BESIDE_BRIDGE)
    return sbi_col_bridge(c) ? "bridge" : NULL;
  if (which == SBI_BESIDE_CONTACTS)
    return c->first_hit && c->first_hit_vn > 0 ? "contacts" : NULL;
  if (which == SBI_BESIDE_FIELD)
    return !strcmp(c->fluid, "ou-field") || !strcmp(c->fluid, "kraichnan")
               ? "field"
               : NULL;
  return c->first_hit ? "firsthit" : sbi_col_agglo(c) ? "agglo" : NULL;
}

int sbi_col_beside(const sbi_col_config *c, int which,
                   const char *checkpoint, char *buf, size_t len)
{
  const char *suffix = suffix_of(c, which);
  if (!suffix)
    return 1;
  snprintf(buf, len, "%s.%s", checkpoint, suffix);
  return 0;
}

int sbi_col_restart_beside(const sbi_col_config *c, int which,
                           const char *lost, char *buf, size_t len)
{
  if (sbi_col_beside(c, which, c->restart, buf, len))
    return SB_SUCCESS;
  FILE *f = fopen(buf, "rb");
  if (!f)
    return sbi_error(SB_EIO, "restart", "no %s beside the checkpoint (it "
                     "is written with the checkpoint of a run with %s): "
                     "%s is unknown", buf,
                     which == SBI_BESIDE_FIELD      ? "that field"
                     : which == SBI_BESIDE_BRIDGE   ? "a bridge detector"
                     : which == SBI_BESIDE_CONTACTS ? "first_hit_velocities"
                     : c->first_hit                 ? "first_hit"
                                                    : "merging", lost);
  fclose(f);
  return SB_SUCCESS;
}

int sbi_col_save_beside(const sbi_col_config *c, const sbi_col_run *r)
{
  char path[600];
  int st = SB_SUCCESS;
  if (!c->checkpoint[0])
    return st;
  if (!sbi_col_beside(c, SBI_BESIDE_COUNTS, c->checkpoint, path,
                      sizeof path))
    st = r->fh ? sb_engine_firsthit_save(r->fh, r->e, path)
               : sb_agglo_save(r->agglo, r->e, path);
  if (!st && !sbi_col_beside(c, SBI_BESIDE_FIELD, c->checkpoint, path,
                             sizeof path))
    st = r->ou ? sb_field_ou_save(r->ou, r->field_rng != NULL, path)
               : sb_field_kraichnan_save(r->kr, path);
  if (!st && !sbi_col_beside(c, SBI_BESIDE_CONTACTS, c->checkpoint, path,
                             sizeof path))
    st = sbi_col_contacts_save(r, path);
  if (!st && !sbi_col_beside(c, SBI_BESIDE_BRIDGE, c->checkpoint, path,
                             sizeof path))
    st = sb_engine_bridge_save(r->bridge, r->e, path);
  if (!st)
    st = sbi_col_runstate_save(c, r);
  return st;
}
