/* engine_bridge_io.c — save and restore a bridge detector's counters and
 * hit records (smolbridge/engine_bridge.h) beside an engine checkpoint, so
 * that they go on from the checkpoint as if the run had not stopped (its
 * parameters and per-species b2 are given again).
 *
 * Format (native binary, like the checkpoint): the 8-byte magic
 * "SBBRID02", the engine's step and particle fingerprint at the save, the
 * counters, the number of hit records and the records, then the FNV-1a
 * hash of every byte before it (common/internal.h, sbi_hsave_finish),
 * checked before anything is read.  Version 01, the same without the
 * hash, still loads. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "common/internal.h"
#include "engine_bridge_state.h"
#include "engine_internal.h"

static const char MAGIC[8] = {'S', 'B', 'B', 'R', 'I', 'D', '0', '2'};

#define W(x) (fwrite(&(x), sizeof(x), 1, f) == 1)
#define R(x) (fread(&(x), sizeof(x), 1, f) == 1)

int sb_engine_bridge_save(const sb_engine_bridge *b, const sb_engine *e,
                          const char *path)
{
  if (!b || !e || !path)
    return sbi_error(SB_EINVAL, __func__, "NULL argument");
  sbi_hsave hs;
  FILE *f = sbi_hsave_begin(&hs, __func__);
  if (!f)
    return SB_ENOMEM;
  const uint64_t steps = e->steps, print = sbi_engine_fingerprint(e),
                 nh = b->nhits;
  int ok = fwrite(MAGIC, 1, 8, f) == 8 && W(steps) && W(print) &&
           W(b->st.ndetect) && W(b->st.ncoll) && W(b->st.noverlap) &&
           W(b->st.coll_brown) && W(b->st.coll_turb) && W(nh) &&
           (nh == 0 || fwrite(b->hits, sizeof *b->hits, nh, f) == nh);
  return sbi_hsave_finish(&hs, ok, path, __func__);
}

int sb_engine_bridge_load(sb_engine_bridge *b, const char *path)
{
  if (!b || !path)
    return sbi_error(SB_EINVAL, __func__, "NULL argument");
  int ver, status;
  char *mem;
  FILE *f = sbi_hload_open(path, MAGIC, 2, "bridge detector file", &ver,
                           &mem, __func__, &status);
  if (!f)
    return status;
  char mg[8];
  uint64_t steps, print, nh;
  sb_engine_bridge_stats st;
  const char *why = "truncated, or data after the end";
  status = SB_EFORMAT;
  if (fread(mg, 1, 8, f) != 8)
    why = "not a bridge detector file";
  else if (R(steps) && R(print) && R(st.ndetect) && R(st.ncoll) &&
           R(st.noverlap) && R(st.coll_brown) && R(st.coll_turb) && R(nh)) {
    if (nh > b->par.record_cap)
      status = SB_EINVAL, why = "it holds more hit records than this "
                                "detector's record_cap";
    else if ((nh == 0 || fread(b->hits, sizeof *b->hits, nh, f) == nh) &&
             fgetc(f) == EOF)
      status = SB_SUCCESS;
  }
  fclose(f);
  free(mem);
  if (status) {
    b->nhits = 0;  /* the records may be partly overwritten */
    return sbi_error(status, __func__, "'%s': %s", path, why);
  }
  b->st = st;
  b->nhits = (size_t)nh;
  b->restored = 1;
  b->saved_steps = steps;
  b->saved_print = print;
  return SB_SUCCESS;
}
