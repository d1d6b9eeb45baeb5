/* engine_firsthit_io.c — save and restore a first-contact observer
 * (smolbridge/engine_firsthit.h), so that a first-contact count goes on
 * from an engine checkpoint (engine_checkpoint.c) as if it had not
 * stopped.
 *
 * Format (native binary, like the engine's checkpoint: portable only
 * between builds with the same type sizes and endianness): the 8-byte
 * magic "SBFHIT02"; the engine's step count, a fingerprint of its
 * particles (ids and positions) and its time at the save; the
 * detector's kind (custom or which built-in) and skip_seen; the size of
 * the species-pair table; the warm-up end; the counts and sums of every
 * species pair and of all pairs; the particles per species at the
 * attachment; the set of pairs seen and each particle's counted contacts
 * (engine_idmap.c); then the FNV-1a hash of every byte before it
 * (common/internal.h, sbi_hsave_finish), checked before anything is read.
 * Version 01, the same without the hash, still loads. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <smolbridge/engine_firsthit.h>

#include "common/internal.h"
#include "engine_firsthit_state.h"

static const char MAGIC[8] = {'S', 'B', 'F', 'H', 'I', 'T', '0', '2'};

/* The fixed-size part, in file order. */
typedef struct {
  uint64_t steps, print;
  double t;
  int32_t custom, builtin, skip_seen;
  uint32_t npt, nspec;
  double t1;
  uint64_t hits[NPT], warm[NPT], contact0[NPT];
  double pairs_apart[NPT];
  uint64_t hits_all, warm_all, contact0_all;
  double pairs_apart_all;
  double sq[NPT][2], sq_all;
  double ns[SB_ENGINE_PAIR_SPECIES], n_all;
} head;

/* Write every field on its own: the struct's padding is never written,
 * so two identical runs give identical files. */
static int head_write(const head *h, FILE *f)
{
#define W(x) (fwrite(&(x), sizeof(x), 1, f) == 1)
  return W(h->steps) && W(h->print) && W(h->t) && W(h->custom) && W(h->builtin) &&
                 W(h->skip_seen) && W(h->npt) && W(h->nspec) && W(h->t1) &&
                 W(h->hits) && W(h->warm) && W(h->contact0) &&
                 W(h->pairs_apart) && W(h->hits_all) && W(h->warm_all) &&
                 W(h->contact0_all) && W(h->pairs_apart_all) && W(h->sq) &&
                 W(h->sq_all) && W(h->ns) && W(h->n_all)
             ? 0
             : -1;
#undef W
}

static int head_read(head *h, FILE *f)
{
#define R(x) (fread(&(x), sizeof(x), 1, f) == 1)
  return R(h->steps) && R(h->print) && R(h->t) && R(h->custom) && R(h->builtin) &&
                 R(h->skip_seen) && R(h->npt) && R(h->nspec) && R(h->t1) &&
                 R(h->hits) && R(h->warm) && R(h->contact0) &&
                 R(h->pairs_apart) && R(h->hits_all) && R(h->warm_all) &&
                 R(h->contact0_all) && R(h->pairs_apart_all) && R(h->sq) &&
                 R(h->sq_all) && R(h->ns) && R(h->n_all)
             ? 0
             : -1;
#undef R
}

int sb_engine_firsthit_save(const sb_engine_firsthit *f, const sb_engine *e,
                            const char *path)
{
  if (!f || !e || !path)
    return sbi_error(SB_EINVAL, __func__, "NULL argument");
  if (!f->attached)
    return sbi_error(SB_EINVAL, __func__, "the observer is not attached: "
                     "nothing to save");
  head h;
  memset(&h, 0, sizeof h);
  h.steps = e->steps;
  h.print = sbi_engine_fingerprint(e);
  h.t = e->t;
  h.custom = f->par.detect != NULL;
  h.builtin = (int32_t)f->par.builtin;
  h.skip_seen = f->par.skip_seen;
  h.npt = NPT;
  h.nspec = SB_ENGINE_PAIR_SPECIES;
  h.t1 = f->t1;
  memcpy(h.hits, f->hits, sizeof h.hits);
  memcpy(h.warm, f->warm, sizeof h.warm);
  memcpy(h.contact0, f->contact0, sizeof h.contact0);
  memcpy(h.pairs_apart, f->pairs_apart, sizeof h.pairs_apart);
  h.hits_all = f->hits_all;
  h.warm_all = f->warm_all;
  h.contact0_all = f->contact0_all;
  h.pairs_apart_all = f->pairs_apart_all;
  memcpy(h.sq, f->sq, sizeof h.sq);
  h.sq_all = f->sq_all;
  memcpy(h.ns, f->ns, sizeof h.ns);
  h.n_all = f->n_all;
  sbi_hsave hs;
  FILE *out = sbi_hsave_begin(&hs, __func__);
  if (!out)
    return SB_ENOMEM;
  const int bad = fwrite(MAGIC, 1, 8, out) != 8 || head_write(&h, out) ||
                  sbi_idmap_write(&f->set, out, 0, 0) ||
                  sbi_idmap_write(&f->counts, out, 1, 0);
  return sbi_hsave_finish(&hs, !bad, path, __func__);
}

static const char *detector_name(int custom, int builtin)
{
  if (custom)
    return "a custom detector";
  return builtin == SB_DETECT_LANGEVIN  ? "the built-in langevin"
         : builtin == SB_DETECT_OVERLAP ? "the built-in overlap"
                                        : "the built-in ballistic";
}

int sb_engine_firsthit_load(sb_engine_firsthit *f, const char *path)
{
  if (!f || !path)
    return sbi_error(SB_EINVAL, __func__, "NULL argument");
  if (f->attached)
    return sbi_error(SB_EINVAL, __func__, "the observer is attached "
                     "already: load the saved state before attaching");
  int ver, st;
  char *mem;
  FILE *in = sbi_hload_open(path, MAGIC, 2, "first-contact observer file",
                            &ver, &mem, __func__, &st);
  if (!in)
    return st;
  char mg[8];
  head h;
  sbi_idmap set = {NULL, NULL, 0, 0}, counts = {NULL, NULL, 0, 0};
  const char *why = NULL;
  if (fread(mg, 1, 8, in) != 8)
    st = SB_EFORMAT, why = "not a first-contact observer file";
  else if (head_read(&h, in))
    st = SB_EFORMAT, why = "truncated";
  else if (h.npt != NPT || h.nspec != SB_ENGINE_PAIR_SPECIES)
    st = SB_EFORMAT, why = "written by a build with another species-pair "
                           "table";
  if (!st) {
    const int a = sbi_idmap_read(&set, in, 0, 0);
    const int b = a ? a : sbi_idmap_read(&counts, in, 1, 0);
    if (a == -2 || b == -2)
      st = SB_EFORMAT, why = "malformed set of pairs";
    else if (a || b)
      st = SB_EFORMAT, why = "truncated (or out of memory)";
    else if (fgetc(in) != EOF)
      st = SB_EFORMAT, why = "trailing data";
  }
  fclose(in);
  free(mem);
  if (st) {
    sbi_idmap_free(&set);
    sbi_idmap_free(&counts);
    return sbi_error(st, __func__, "'%s': %s", path, why);
  }
  const int custom = f->par.detect != NULL;
  if (h.custom != custom || (!custom && h.builtin != (int)f->par.builtin) ||
      h.skip_seen != f->par.skip_seen) {
    sbi_idmap_free(&set);
    sbi_idmap_free(&counts);
    return sbi_error(SB_EINVAL, __func__, "'%s' was saved around %s with "
                     "skip_seen = %d; this observer watches %s with "
                     "skip_seen = %d: the count would not go on as it "
                     "was", path, detector_name(h.custom, h.builtin),
                     (int)h.skip_seen, detector_name(custom,
                                                     (int)f->par.builtin),
                     f->par.skip_seen);
  }
  sbi_idmap_free(&f->set);
  sbi_idmap_free(&f->counts);
  f->set = set;
  f->counts = counts;
  f->restored = 1;
  f->saved_steps = h.steps;
  f->saved_print = h.print;
  f->t1 = h.t1;
  memcpy(f->hits, h.hits, sizeof h.hits);
  memcpy(f->warm, h.warm, sizeof h.warm);
  memcpy(f->contact0, h.contact0, sizeof h.contact0);
  memcpy(f->pairs_apart, h.pairs_apart, sizeof h.pairs_apart);
  f->hits_all = h.hits_all;
  f->warm_all = h.warm_all;
  f->contact0_all = h.contact0_all;
  f->pairs_apart_all = h.pairs_apart_all;
  memcpy(f->sq, h.sq, sizeof h.sq);
  f->sq_all = h.sq_all;
  memcpy(f->ns, h.ns, sizeof h.ns);
  f->n_all = h.n_all;
  return SB_SUCCESS;
}
