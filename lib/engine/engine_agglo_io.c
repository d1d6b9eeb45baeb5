/* engine_agglo_io.c — save and restore an agglomeration context
 * (sb_agglo, engine_merge.c) beside an engine checkpoint, so that a
 * merging run goes on from the checkpoint as if it had not stopped: the
 * engine's checkpoint holds the particles and every cluster species, this
 * file which species is which cluster size, the counters and the size
 * time series.
 *
 * Format (native binary, like the engine's checkpoint): the 8-byte magic
 * "SBAGGL02"; the engine's step count and a fingerprint of its particles
 * at the save; the parameters that shape the run (primary species,
 * growth law, sticking rule, E_rel mode, barrier, largest and observed
 * sizes, and whether the two callbacks were set); the counters; the
 * sizes with a species, as (k, species) pairs; the series (rows and
 * columns, then the values); then the FNV-1a hash of every byte before
 * it (common/internal.h, sbi_hsave_finish), checked before anything is
 * read.  Version 01, the same without the hash, still loads. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "common/internal.h"
#include "engine_agglo_state.h"
#include "engine_internal.h"

static const char MAGIC[8] = {'S', 'B', 'A', 'G', 'G', 'L', '0', '2'};

/* The parameters a restored run must share with the saved one. */
typedef struct {
  uint64_t primary, kmax, kobs;
  int32_t growth, rule, erel, erel_normal, species_fn, wmax_fn;
  double wmax;
} shape;

static shape shape_of(const sb_agglo_params *p)
{
  shape s;
  memset(&s, 0, sizeof s);
  s.primary = p->primary;
  s.kmax = p->kmax;
  s.kobs = p->kobs;
  s.growth = (int32_t)p->growth;
  s.rule = (int32_t)p->rule;
  s.erel = (int32_t)p->erel;
  s.erel_normal = p->erel_normal;
  s.species_fn = p->species_fn != NULL;
  s.wmax_fn = p->wmax_fn != NULL;
  s.wmax = p->wmax;
  return s;
}

#define W(x) (fwrite(&(x), sizeof(x), 1, f) == 1)
#define R(x) (fread(&(x), sizeof(x), 1, f) == 1)

static int shape_write(const shape *s, FILE *f)
{
  return W(s->primary) && W(s->kmax) && W(s->kobs) && W(s->growth) &&
                 W(s->rule) && W(s->erel) && W(s->erel_normal) &&
                 W(s->species_fn) && W(s->wmax_fn) && W(s->wmax)
             ? 0
             : -1;
}

static int shape_read(shape *s, FILE *f)
{
  return R(s->primary) && R(s->kmax) && R(s->kobs) && R(s->growth) &&
                 R(s->rule) && R(s->erel) && R(s->erel_normal) &&
                 R(s->species_fn) && R(s->wmax_fn) && R(s->wmax)
             ? 0
             : -1;
}

int sb_agglo_save(const sb_agglo *a, const sb_engine *e, const char *path)
{
  if (!a || !e || !path)
    return sbi_error(SB_EINVAL, __func__, "NULL argument");
  if (!a->ncap_k)
    return sbi_error(SB_EINVAL, __func__, "the context is not attached: "
                     "nothing to save");
  sbi_hsave hs;
  FILE *f = sbi_hsave_begin(&hs, __func__);
  if (!f)
    return SB_ENOMEM;
  const uint64_t steps = e->steps, print = sbi_engine_fingerprint(e);
  const shape s = shape_of(&a->par);
  uint64_t nmap = 0;
  for (size_t k = 0; k < a->ncap_k; k++)
    nmap += a->sp_of_k[k] != SIZE_MAX;
  const uint64_t nrows = a->nrows, ncols = 4 + a->par.kobs;
  int ok = fwrite(MAGIC, 1, 8, f) == 8 && W(steps) && W(print) &&
           !shape_write(&s, f) && W(a->st.nmerge) && W(a->st.nrebound) &&
           W(a->st.erel_sum) && W(nmap);
  for (size_t k = 0; ok && k < a->ncap_k; k++)
    if (a->sp_of_k[k] != SIZE_MAX) {
      const uint64_t kk = k, sp = a->sp_of_k[k];
      ok = W(kk) && W(sp);
    }
  ok = ok && W(nrows) && W(ncols) &&
       (nrows == 0 ||
        fwrite(a->rows, sizeof *a->rows, nrows * ncols, f) == nrows * ncols);
  return sbi_hsave_finish(&hs, ok, path, __func__);
}

/* The file's contents. */
typedef struct {
  uint64_t steps, print;
  shape s;
  sb_agglo_stats st;
  uint64_t nmap, *map;  /* (k, species) pairs */
  uint64_t nrows, ncols;
  double *rows;
} saved;

/* Read path into *v: 0, or a status with its reason in *why (NULL: the
 * message is recorded already, from func). */
static int read_saved(const char *path, saved *v, const char **why,
                      const char *func)
{
  memset(v, 0, sizeof *v);
  int ver, st;
  char *mem;
  FILE *f = sbi_hload_open(path, MAGIC, 2, "agglomeration file", &ver,
                           &mem, func, &st);
  if (!f) {
    *why = NULL;
    return st;
  }
  char mg[8];
  st = SB_EFORMAT;
  *why = "truncated";
  if (fread(mg, 1, 8, f) != 8) {
    *why = "not an agglomeration file";
    goto out;
  }
  if (!R(v->steps) || !R(v->print) || shape_read(&v->s, f) ||
      !R(v->st.nmerge) || !R(v->st.nrebound) || !R(v->st.erel_sum) ||
      !R(v->nmap))
    goto out;
  if (v->nmap > ((uint64_t)1 << 30)) {
    *why = "malformed table of sizes";
    goto out;
  }
  v->map = malloc((2 * v->nmap + 1) * sizeof *v->map);
  if (!v->map) {
    st = SB_ENOMEM, *why = "out of memory";
    goto out;
  }
  if (fread(v->map, sizeof *v->map, 2 * v->nmap, f) != 2 * v->nmap ||
      !R(v->nrows) || !R(v->ncols))
    goto out;
  if (v->ncols != 4 + v->s.kobs || v->nrows > ((uint64_t)1 << 32)) {
    *why = "malformed series";
    goto out;
  }
  v->rows = malloc((v->nrows * v->ncols + 1) * sizeof *v->rows);
  if (!v->rows) {
    st = SB_ENOMEM, *why = "out of memory";
    goto out;
  }
  if (fread(v->rows, sizeof *v->rows, v->nrows * v->ncols, f) !=
      v->nrows * v->ncols)
    goto out;
  if (fgetc(f) != EOF) {
    *why = "trailing data";
    goto out;
  }
  st = SB_SUCCESS;
out:
  fclose(f);
  free(mem);
  if (st) {
    free(v->map);
    free(v->rows);
    v->map = NULL;
    v->rows = NULL;
  }
  return st;
}

int sb_agglo_load(sb_agglo *a, const char *path)
{
  if (!a || !path)
    return sbi_error(SB_EINVAL, __func__, "NULL argument");
  if (a->ncap_k)
    return sbi_error(SB_EINVAL, __func__, "the context is attached already: "
                     "load the saved state before attaching");
  saved v;
  const char *why;
  int st = read_saved(path, &v, &why, __func__);
  if (st)
    return why ? sbi_error(st, __func__, "'%s': %s", path, why) : st;
  const shape mine = shape_of(&a->par);
  if (memcmp(&mine, &v.s, sizeof mine)) {
    free(v.map);
    free(v.rows);
    return sbi_error(SB_EINVAL, __func__, "'%s' was saved with other "
                     "agglomeration parameters (primary, growth, rule, "
                     "erel, erel_normal, wmax, kmax, kobs or a callback): "
                     "the run would not go on as it was", path);
  }
  for (uint64_t q = 0; q < v.nmap; q++) {
    const uint64_t k = v.map[2 * q], sp = v.map[2 * q + 1];
    if (k == 0 || k > a->par.kmax || sp >= ((uint64_t)1 << 30) ||
        (st = sbi_agglo_set_map(a, (size_t)k, (size_t)sp, __func__))) {
      free(v.map);
      free(v.rows);
      /* undo: the context stays as it was (never attached) */
      free(a->sp_of_k);
      free(a->k_of_sp);
      a->sp_of_k = a->k_of_sp = NULL;
      a->ncap_k = a->ncap_sp = 0;
      return st ? st
                : sbi_error(SB_EFORMAT, __func__, "'%s': malformed table "
                            "of sizes", path);
    }
  }
  free(v.map);
  free(a->rows);
  a->rows = v.rows;
  a->nrows = a->caprows = v.nrows;
  a->st = v.st;
  a->restored = 1;
  a->saved_steps = v.steps;
  a->saved_print = v.print;
  return SB_SUCCESS;
}

int sbi_agglo_check_restored(sb_agglo *a, const sb_engine *e)
{
  const int st = sbi_engine_check_saved(e, a->saved_steps, a->saved_print,
                                        "sb_agglo_attach", "the context");
  if (st)
    return st;
  const double m1 = e->spec[a->par.primary].mass;
  for (size_t k = 2; k < a->ncap_k; k++) {
    const size_t sp = a->sp_of_k[k];
    if (sp == SIZE_MAX)
      continue;
    if (sp >= e->nspec ||
        !(fabs(e->spec[sp].mass - (double)k * m1) <= 1e-9 * (double)k * m1))
      return sbi_error(SB_EINVAL, "sb_agglo_attach", "saved size %zu is "
                       "species %zu, which the engine %s", k, sp,
                       sp >= e->nspec ? "does not have"
                                      : "has with another mass");
  }
  a->restored = 0;  /* checked: later re-attachments are ordinary */
  return SB_SUCCESS;
}
