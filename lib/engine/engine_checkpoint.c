#define _POSIX_C_SOURCE 200809L /* open_memstream, fmemopen */
/* engine_checkpoint.c — save and restore the whole engine state so that a
 * restarted run continues bit-identically (same positions, velocities,
 * counters and random stream: the MT19937 state is written with
 * the bytes of gsl_rng_fwrite).
 *
 * Format (little-endian on every machine: each number is reversed on a
 * big-endian one, common/byteorder.c, the bytes on a little-endian one
 * are those of the builds before; portable between builds with the same
 * type sizes; a big-endian file, an older build's, is recognised by its
 * hash, which then matches byte-swapped, or by its first number, the
 * dimension, and refused as such): the 8-byte magic "SBENGCK6" (versions 2
 * to 5 still load: MAGIC below), then the fields in the order written by
 * sb_engine_checkpoint_save, then (version 6) the FNV-1a hash of all the
 * bytes before it: a file that was cut, flipped or mixed up is refused
 * before any of it is used.  Callbacks cannot be
 * saved: a custom detector / outcome / fluid callback is replaced on load
 * by the defaults (ballistic, elastic, fluid at rest); set them again.
 */
#include <stdio.h>
#include <stdlib.h>
#include <stddef.h>
#include <string.h>


#include <smolbridge/rng.h>

#include "common/internal.h"
#include "engine_internal.h"

/* version 3 appends the block of forces, Lees-Edwards and walls
 * (engine_wall.c) after the generator state; version 4 puts the
 * streams flag (sb_engine_params.streams) between the two; version 5
 * appends the Langevin detector's parameters, the open boundaries'
 * counters and the collision tally
 * (sb_engine_set_count_variance: whether it is on and whole, its sums
 * and both tables).  The parameter block keeps
 * the layout of version 2 (the fields before streams), so version 2 to
 * 4 files still load (no such settings; streams and tally off, the
 * counters 0).  Version 6 appends the hash of the file. */
static const char MAGIC[8] = {'S', 'B', 'E', 'N', 'G', 'C', 'K', '6'};
#define PAR_BYTES offsetof(sb_engine_params, streams)

/* count numbers of `width` bytes each, in the file's byte order (swap:
 * the reverse of this machine's, common/internal.h sbi_write_ord) */
#define W(ptr, width, count)                                \
  do {                                                      \
    if (!sbi_write_ord(f, (ptr), (width), (count), swap))   \
      goto fail;                                            \
  } while (0)

/* The numbers of the structures written whole: the parameters (the block
 * before `streams`; the generator-type pointer is written as 0), a
 * species, a time-series sample. */
static const sbi_field PAR_FIELDS[] = {
    SBI_FIELD(sb_engine_params, dim),
    SBI_FIELDS(sb_engine_params, L, 3),
    SBI_FIELD(sb_engine_params, dt),
    SBI_FIELD(sb_engine_params, seed),
    SBI_FIELD(sb_engine_params, rng_type),
    SBI_FIELD(sb_engine_params, capacity),
    SBI_FIELD(sb_engine_params, neigh),
    SBI_FIELD(sb_engine_params, detect),
    SBI_FIELD(sb_engine_params, outcome),
    SBI_FIELD(sb_engine_params, eta),
    SBI_FIELD(sb_engine_params, sample_every),
    SBI_FIELD(sb_engine_params, sort_every)};
static const sbi_field SPEC_FIELDS[] = {
    SBI_FIELD(sb_engine_species, radius), SBI_FIELD(sb_engine_species, mass),
    SBI_FIELD(sb_engine_species, tau), SBI_FIELD(sb_engine_species, B),
    SBI_FIELD(sb_engine_species, T)};
static const sbi_field SAMPLE_FIELDS[] = {
    SBI_FIELD(sb_engine_sample, t), SBI_FIELD(sb_engine_sample, ncoll),
    SBI_FIELD(sb_engine_sample, K), SBI_FIELD(sb_engine_sample, K_lo),
    SBI_FIELD(sb_engine_sample, K_hi), SBI_FIELD(sb_engine_sample, ekin),
    SBI_FIELDS(sb_engine_sample, p, 3)};
#define NFIELDS(t) (sizeof(t) / sizeof(t)[0])

/* The generator state's numbers, to byte-reverse it: 0 fields if its
 * layout is not known.  MT19937 (GSL's mt.c: unsigned long mt[624], int
 * mti; also its 1998 and 1999 seedings) and sb_rng_philox (rng_gsl.c:
 * a sb_stream, 15 uint32, and an int) are; the sizes are checked against
 * the generator's. */
static size_t rng_layout(const gsl_rng *r, sbi_field fl[2])
{
  typedef struct {
    unsigned long mt[624];
    int mti;
  } mt_state;
  typedef struct {
    sb_stream s;
    int own;
  } philox_state;
  const char *name = gsl_rng_name(r);
  const size_t size = gsl_rng_size(r);
  if (!strncmp(name, "mt19937", 7) && size == sizeof(mt_state)) {
    fl[0] = (sbi_field)SBI_FIELDS(mt_state, mt, 624);
    fl[1] = (sbi_field)SBI_FIELD(mt_state, mti);
    return 2;
  }
  if (!strcmp(name, sb_rng_philox->name) && size == sizeof(philox_state) &&
      sizeof(int) == sizeof(uint32_t)) {
    fl[0] = (sbi_field){0, sizeof(uint32_t), size / sizeof(uint32_t)};
    return 1;
  }
  return 0;
}

/* What version 5 adds: the Langevin detector's parameters
 * (sb_engine_set_langevin), the open boundaries' counters (engine_open.c:
 * outflows per face, each inflow slot's injected and skipped particles;
 * the inflows themselves are added again after loading, in the same
 * order) and the collision tally (engine_observe.c: on, whole, the sums,
 * and with it on both tables, engine_idmap.c).  -1 on a write error. */
static int counters_save(const sb_engine *e, FILE *f, int swap)
{
  const int32_t slots = SB_ENGINE_MAXINFLOW;
  const int32_t on = e->cvar_on, lost = e->cvar_lost;
  const double lp[3] = {e->lpar.eps, e->lpar.xtol, e->lpar.tol};
  W(lp, sizeof lp[0], 3);
  W(e->nout, sizeof e->nout[0], 6);
  W(&slots, sizeof slots, 1);
  W(e->ninj, sizeof e->ninj[0], SB_ENGINE_MAXINFLOW);
  W(e->nskip, sizeof e->nskip[0], SB_ENGINE_MAXINFLOW);
  W(&on, sizeof on, 1);
  W(&lost, sizeof lost, 1);
  W(e->cvar_sq, sizeof e->cvar_sq[0][0], 2 * SBI_NPAIRSP);
  W(e->cvar_s2, sizeof e->cvar_s2[0], SBI_NPAIRSP);
  return on ? (sbi_idmap_write(&e->cvar_part, f, 1, swap) ||
               sbi_idmap_write(&e->cvar_pair, f, 1, swap)) ? -1 : 0
            : 0;
fail:
  return -1;
}

/* Back into a loaded engine: 0, -1 on a read error or malformed data. */
static int counters_load(sb_engine *e, FILE *f, int swap)
{
  int32_t slots, on, lost;
  double lp[3];
  if (!sbi_read_ord(f, lp, sizeof lp[0], 3, swap))
    return -1;
  const sb_engine_langevin_params q = {lp[0], lp[1], lp[2]};
  if (sb_engine_set_langevin(e, &q))
    return -1;
  if (!sbi_read_ord(f, e->nout, sizeof e->nout[0], 6, swap) ||
      !sbi_read_ord(f, &slots, sizeof slots, 1, swap) ||
      slots != SB_ENGINE_MAXINFLOW ||
      !sbi_read_ord(f, e->ninj, sizeof e->ninj[0], SB_ENGINE_MAXINFLOW,
                    swap) ||
      !sbi_read_ord(f, e->nskip, sizeof e->nskip[0], SB_ENGINE_MAXINFLOW,
                    swap) ||
      !sbi_read_ord(f, &on, sizeof on, 1, swap) ||
      !sbi_read_ord(f, &lost, sizeof lost, 1, swap) ||
      (on != 0 && on != 1) || (lost != 0 && lost != 1) ||
      !sbi_read_ord(f, e->cvar_sq, sizeof e->cvar_sq[0][0],
                    2 * SBI_NPAIRSP, swap) ||
      !sbi_read_ord(f, e->cvar_s2, sizeof e->cvar_s2[0], SBI_NPAIRSP, swap))
    return -1;
  e->cvar_on = on;
  e->cvar_lost = lost;
  return on ? (sbi_idmap_read(&e->cvar_part, f, 1, swap) ||
               sbi_idmap_read(&e->cvar_pair, f, 1, swap)) ? -1 : 0
            : 0;
}

/* The state in the order of the format, into f: 0 or -1. */
static int write_state(const sb_engine *e, FILE *f, int swap)
{
  const size_t n = e->n;
  sbi_field rfl[2];
  const size_t nrfl = rng_layout(e->rng, rfl);
  W(MAGIC, 1, 8);
  {
    /* field by field into zeroed storage: the generator-type pointer and
     * the struct's padding would make two identical runs' files differ
     * (the type is stored by name below) */
    sb_engine_params par;
    memset(&par, 0, sizeof par);
    par.dim = e->par.dim;
    memcpy(par.L, e->par.L, sizeof par.L);
    par.dt = e->par.dt;
    par.seed = e->par.seed;
    par.capacity = e->par.capacity;
    par.neigh = e->par.neigh;
    par.detect = e->par.detect;
    par.outcome = e->par.outcome;
    par.eta = e->par.eta;
    par.sample_every = e->par.sample_every;
    par.sort_every = e->par.sort_every;
    /* streams: below; threads: not state */
    if (!sbi_write_fields(f, &par, PAR_BYTES, 1, PAR_FIELDS,
                          NFIELDS(PAR_FIELDS), swap))
      goto fail;
  }
  W(&n, sizeof n, 1);
  W(&e->next_id, sizeof e->next_id, 1);
  W(&e->nspec, sizeof e->nspec, 1);
  if (!sbi_write_fields(f, e->spec, sizeof *e->spec, e->nspec, SPEC_FIELDS,
                        NFIELDS(SPEC_FIELDS), swap))
    goto fail;
  W(e->x, sizeof(double), 3 * n);
  W(e->u, sizeof(double), 3 * n);
  W(e->species, sizeof(size_t), n);
  W(e->family, sizeof(int), n);
  W(e->id, sizeof(uint64_t), n);
  W(&e->fluid, sizeof e->fluid, 1);
  W(e->fluid_p, sizeof(double), 3);
  W(&e->steps, sizeof e->steps, 1);
  W(&e->t, sizeof e->t, 1);
  W(&e->t_reset, sizeof e->t_reset, 1);
  W(&e->ncoll, sizeof e->ncoll, 1);
  W(&e->ncand, sizeof e->ncand, 1);
  W(&e->dropped, sizeof e->dropped, 1);
  W(&e->nredetect, sizeof e->nredetect, 1);
  W(&e->redetect, sizeof e->redetect, 1);
  W(&e->expo, sizeof e->expo, 1);
  W(e->pexpo, sizeof e->pexpo[0], SBI_NPAIRSP);
  W(e->pcoll, sizeof e->pcoll[0], SBI_NPAIRSP);
  W(e->fam, sizeof e->fam[0][0], SB_ENGINE_MAXFAM * SB_ENGINE_MAXFAM);
  W(&e->nseries, sizeof e->nseries, 1);
  if (!sbi_write_fields(f, e->series, sizeof *e->series, e->nseries,
                        SAMPLE_FIELDS, NFIELDS(SAMPLE_FIELDS), swap))
    goto fail;
  {
    char name[32] = {0};
    strncpy(name, gsl_rng_name(e->rng), sizeof name - 1);
    W(name, 1, sizeof name);
  }
  /* the bytes gsl_rng_fwrite writes (fwrite of gsl_rng_state), written
   * directly: GSL's error handler would abort on an I/O error */
  if ((swap && !nrfl) ||
      !sbi_write_fields(f, gsl_rng_state(e->rng), gsl_rng_size(e->rng), 1,
                        rfl, nrfl, swap))
    goto fail;
  {
    int32_t streams = e->par.streams;
    W(&streams, sizeof streams, 1);
  }
  if (sbi_engine_physics_save(e, f, swap) || counters_save(e, f, swap))
    goto fail;
  return 0;
fail:
  return -1;
}

/* The checkpoint in the order swap; messages from func. */
static int save(const sb_engine *e, const char *path, int swap,
                const char *func)
{
  if (!e || !path)
    return sbi_error(SB_EINVAL, func, "NULL argument");
  sbi_field rfl[2];
  if (swap && !rng_layout(e->rng, rfl))
    return sbi_error(SB_EINVAL, func, "the state of generator '%s' cannot "
                     "be written in the other byte order (checkpoints are "
                     "little-endian): use sb_rng_philox or "
                     "gsl_rng_mt19937", gsl_rng_name(e->rng));
  /* in memory first: the hash covers every byte, and the file is then
   * written in one piece (also to a pipe) */
  sbi_hsave h;
  FILE *m = sbi_hsave_begin(&h, func);
  if (!m)
    return SB_ENOMEM;
  return sbi_hsave_finish_ord(&h, write_state(e, m, swap) == 0, swap, path,
                              func);
}

int sb_engine_checkpoint_save(const sb_engine *e, const char *path)
{
  return save(e, path, !sbi_host_le(), __func__);
}

int sbi_engine_checkpoint_save_ord(const sb_engine *e, const char *path,
                                   int swap)
{
  return save(e, path, swap, __func__);
}

static int id_cmp(const void *a, const void *b)
{
  const uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
  return (x > y) - (x < y);
}

/* The particles' ids are distinct and below the id counter (the next
 * particle's): SB_SUCCESS, or SB_EINVAL naming the first id at fault
 * (SB_ENOMEM). */
static int check_ids(const uint64_t *id, size_t n, uint64_t next_id,
                     const char *path, const char *func)
{
  for (size_t i = 0; i < n; i++)
    if (id[i] >= next_id)
      return sbi_error(SB_EINVAL, func, "'%s': particle %zu has id %llu, "
                       "not below the id counter %llu", path, i,
                       (unsigned long long)id[i],
                       (unsigned long long)next_id);
  if (n < 2)
    return SB_SUCCESS;
  uint64_t *s = malloc(n * sizeof *s);
  if (!s)
    return sbi_error(SB_ENOMEM, func, "out of memory");
  memcpy(s, id, n * sizeof *s);
  qsort(s, n, sizeof *s, id_cmp);
  int st = SB_SUCCESS;
  for (size_t k = 1; k < n && !st; k++)
    if (s[k] == s[k - 1])
      st = sbi_error(SB_EINVAL, func, "'%s': two particles have id %llu "
                     "(ids must be distinct)", path,
                     (unsigned long long)s[k]);
  free(s);
  return st;
}

#define R(ptr, width, count)                                \
  do {                                                      \
    if (!sbi_read_ord(f, (ptr), (width), (count), swap))    \
      goto bad;                                             \
  } while (0)

/* The n saved particle states of e: a position inside the box (0 <= x_k
 * < L_k, which every entry point and step keeps) and finite velocities
 * (and third components in 2-D): SB_SUCCESS, or SB_EINVAL naming the
 * first particle at fault. */
static int check_states(const sb_engine *e, size_t n, const char *path,
                        const char *func)
{
  for (size_t i = 0; i < n; i++)
    for (int k = 0; k < 3; k++) {
      const double x = e->x[3 * i + k], u = e->u[3 * i + k];
      const int in = k < e->par.dim ? x >= 0.0 && x < e->par.L[k]
                                    : isfinite(x);
      if (!in || !isfinite(u))
        return sbi_error(SB_EINVAL, func, "'%s': particle %zu has x[%d] = "
                         "%g, u[%d] = %g: the position must lie in the box "
                         "[0, %g) and both be finite", path, i, k, x, k, u,
                         e->par.L[k]);
    }
  return SB_SUCCESS;
}

/* The engine of checkpoint `path` in the order swap, with room for at
 * least `capacity` particles (its own capacity if that is larger);
 * messages name func. */
static sb_engine *load(const char *path, size_t capacity, int swap,
                       int *status, const char *func)
{
  int dummy;
  if (!status)
    status = &dummy;
  FILE *file = sbi_open_saved(path, func, status);
  if (!file)
    return NULL;
  /* the whole file, its hash checked before anything is read from it
   * (version 6) */
  size_t len = 0;
  char *buf = sbi_slurp(file, &len);
  fclose(file);
  if (!buf) {
    *status = sbi_error(SB_EIO, func, "cannot read '%s'", path);
    return NULL;
  }
  sb_engine *e = NULL;
  sb_engine_species *spec = NULL;
  FILE *f = NULL;
  const int ver = len >= 8 && !memcmp(buf, MAGIC, 7) ? buf[7] - '0' : 0;
  if (ver < 2 || ver > 6)
    goto bad;
  if (ver >= 6) {
    if (len < 16)
      goto bad;
    int c = sbi_hash_check(buf, len);
    if (c >= 0 && swap)  /* 0: the hash in the file's order */
      c = !c;
    if (c > 0)
      goto foreign;
    if (c) {
      *status = sbi_error(SB_EFORMAT, func, "'%s' is damaged: its "
                          "contents do not match the hash at its end "
                          "(cut short, changed or not a checkpoint)", path);
      goto out;
    }
    len -= 8;
  }
  /* the magic and version are text, the same in either byte order; the
   * first number, the dimension (2 or 3), tells the order of a file
   * without the hash (versions 2 to 5) */
  if (len >= 12) {
    uint32_t dim, other;
    memcpy(&dim, buf + 8, 4);
    other = sbi_bswap32(dim);
    if (swap) {
      other = dim;
      dim = sbi_bswap32(dim);
    }
    if (!(dim >= 1 && dim <= 3) && other >= 1 && other <= 3)
      goto foreign;
  }
  f = fmemopen(buf, len, "rb");
  if (!f) {
    *status = sbi_error(SB_ENOMEM, func, "out of memory");
    goto out;
  }
  char magic[8];
  sb_engine_params par;
  size_t n, nspec;
  uint64_t next_id;
  R(magic, 1, 8);
  const int v2 = ver == 2;
  memset(&par, 0, sizeof par);
  if (!sbi_read_fields(f, &par, PAR_BYTES, 1, PAR_FIELDS,
                       NFIELDS(PAR_FIELDS), swap))
    goto bad;
  R(&n, sizeof n, 1);
  R(&next_id, sizeof next_id, 1);
  R(&nspec, sizeof nspec, 1);
  if (n > par.capacity || nspec > ((size_t)1 << 20))
    goto bad;
  if (capacity > par.capacity)
    par.capacity = capacity;  /* room only: no state depends on it */
  par.rng_type = NULL;  /* the pointer is meaningless in a file: the
                          * generator's name is stored below */
  if (par.detect == SB_DETECT_CUSTOM)
    par.detect = SB_DETECT_BALLISTIC;
  if (par.outcome == SB_OUTCOME_CUSTOM)
    par.outcome = SB_OUTCOME_ELASTIC;
  e = sb_engine_alloc(&par);
  if (!e && sb_last_status() == SB_ENOMEM) {
    *status = sbi_error(SB_ENOMEM, func, "out of memory for the "
                        "engine of '%s' (capacity %zu)", path, par.capacity);
    goto out;
  }
  if (!e)
    goto bad; /* parameters the engine refuses: not a valid file */
  spec = malloc((nspec ? nspec : 1) * sizeof *spec);
  if (!spec) {
    *status = sbi_error(SB_ENOMEM, func, "out of memory");
    goto out;
  }
  if (!sbi_read_fields(f, spec, sizeof *spec, nspec, SPEC_FIELDS,
                       NFIELDS(SPEC_FIELDS), swap))
    goto bad;
  for (size_t k = 0; k < nspec; k++)
    if (sb_engine_add_species(e, &spec[k], NULL))
      goto bad;
  R(e->x, sizeof(double), 3 * n);
  R(e->u, sizeof(double), 3 * n);
  R(e->species, sizeof(size_t), n);
  R(e->family, sizeof(int), n);
  R(e->id, sizeof(uint64_t), n);
  for (size_t i = 0; i < n; i++) {
    if (e->species[i] >= nspec || e->family[i] < 0 ||
        e->family[i] >= SB_ENGINE_MAXFAM)
      goto bad;
    e->radius[i] = e->spec[e->species[i]].radius;
    e->mass[i] = e->spec[e->species[i]].mass;
  }
  {
    int st = check_ids(e->id, n, next_id, path, func);
    if (!st)
      st = check_states(e, n, path, func);
    if (st) {
      *status = st;
      goto out;
    }
  }
  e->n = n;
  e->next_id = next_id;
  R(&e->fluid, sizeof e->fluid, 1);
  R(e->fluid_p, sizeof(double), 3);
  if ((unsigned)e->fluid > SB_FLUID_CALLBACK)
    goto bad;
  if (e->fluid == SB_FLUID_CALLBACK)
    e->fluid = SB_FLUID_REST;
  R(&e->steps, sizeof e->steps, 1);
  R(&e->t, sizeof e->t, 1);
  R(&e->t_reset, sizeof e->t_reset, 1);
  R(&e->ncoll, sizeof e->ncoll, 1);
  R(&e->ncand, sizeof e->ncand, 1);
  R(&e->dropped, sizeof e->dropped, 1);
  R(&e->nredetect, sizeof e->nredetect, 1);
  R(&e->redetect, sizeof e->redetect, 1);
  R(&e->expo, sizeof e->expo, 1);
  R(e->pexpo, sizeof e->pexpo[0], SBI_NPAIRSP);
  R(e->pcoll, sizeof e->pcoll[0], SBI_NPAIRSP);
  R(e->fam, sizeof e->fam[0][0], SB_ENGINE_MAXFAM * SB_ENGINE_MAXFAM);
  {
    size_t ns;
    R(&ns, sizeof ns, 1);
    if (ns > ((size_t)1 << 32))
      goto bad;
    if (ns) {
      e->series = malloc(ns * sizeof *e->series);
      if (!e->series) {
        *status = sbi_error(SB_ENOMEM, func, "out of memory");
        goto out;
      }
      e->capseries = ns;
      if (!sbi_read_fields(f, e->series, sizeof *e->series, ns,
                           SAMPLE_FIELDS, NFIELDS(SAMPLE_FIELDS), swap))
        goto bad;
      e->nseries = ns;
    }
  }
  {
    char name[32];
    R(name, 1, sizeof name);
    name[sizeof name - 1] = 0;
    if (strcmp(name, gsl_rng_name(e->rng))) {
      const gsl_rng_type **t = gsl_rng_types_setup();
      const gsl_rng_type *found = NULL;
      for (; *t; t++)
        if (!strcmp((*t)->name, name))
          found = *t;
      if (!strcmp(sb_rng_philox->name, name))
        found = sb_rng_philox;
      if (!found)
        goto bad;
      gsl_rng *r = gsl_rng_alloc(found);
      if (!r) {
        *status = sbi_error(SB_ENOMEM, func, "out of memory");
        goto out;
      }
      gsl_rng_free(e->rng);
      e->rng = r;
      e->par.rng_type = found;
    }
  }
  /* counterpart of gsl_rng_fread, without GSL's aborting handler */
  {
    sbi_field rfl[2];
    const size_t nrfl = rng_layout(e->rng, rfl);
    if (swap && !nrfl) {
      *status = sbi_error(SB_EFORMAT, func, "'%s': the state of its "
                          "generator '%s' cannot be read on a big-endian "
                          "machine (checkpoints are little-endian): load it "
                          "on a little-endian one", path,
                          gsl_rng_name(e->rng));
      goto out;
    }
    if (!sbi_read_fields(f, gsl_rng_state(e->rng), gsl_rng_size(e->rng), 1,
                         rfl, nrfl, swap))
      goto bad;
  }
  if (ver >= 4) {
    int32_t streams;
    R(&streams, sizeof streams, 1);
    if (streams != 0 && streams != 1)
      goto bad;
    e->par.streams = streams;
  }
  if (!v2 && sbi_engine_physics_load(e, f, swap))
    goto bad;
  if ((ver >= 5 && counters_load(e, f, swap)) || fgetc(f) != EOF)
    goto bad;  /* nothing may follow */
  free(spec);
  fclose(f);
  free(buf);
  return e;
bad:
  *status = sbi_error(SB_EFORMAT, func,
                      "'%s' is not a valid engine checkpoint", path);
  goto out;
foreign:
  *status = sbi_error(SB_EFORMAT, func, "'%s' is in the other byte order, "
                      "big-endian: a checkpoint of an older build on a "
                      "big-endian machine (they are little-endian now); "
                      "load it with that build", path);
out:
  free(spec);
  sb_engine_free(e);
  if (f)
    fclose(f);
  free(buf);
  return NULL;
}

sb_engine *sb_engine_checkpoint_load(const char *path, int *status)
{
  return load(path, 0, !sbi_host_le(), status, __func__);
}

sb_engine *sbi_engine_checkpoint_load_ord(const char *path, int swap,
                                          int *status)
{
  return load(path, 0, swap, status, __func__);
}

sb_engine *sb_engine_checkpoint_load_capacity(const char *path,
                                              size_t capacity, int *status)
{
  int dummy;
  if (!status)
    status = &dummy;
  if (capacity > ((size_t)1 << 40)) {
    *status = sbi_error(SB_EINVAL, __func__, "capacity = %zu: must be at "
                        "most 2^40", capacity);
    return NULL;
  }
  return load(path, capacity, !sbi_host_le(), status, __func__);
}

uint64_t sbi_engine_fingerprint(const sb_engine *e)
{
  uint64_t h = sbi_fnv1a(SBI_FNV_BASIS, &e->n, sizeof e->n);
  h = sbi_fnv1a(h, e->id, e->n * sizeof *e->id);
  return sbi_fnv1a(h, e->x, 3 * e->n * sizeof *e->x);
}

int sbi_engine_check_saved(const sb_engine *e, uint64_t steps,
                           uint64_t print, const char *func,
                           const char *what)
{
  if (e->steps != steps)
    return sbi_error(SB_EINVAL, func, "%s was saved at step %llu, the "
                     "engine is at step %llu: restore both from the same "
                     "checkpoint", what, (unsigned long long)steps,
                     (unsigned long long)e->steps);
  if (sbi_engine_fingerprint(e) != print)
    return sbi_error(SB_EINVAL, func, "%s was saved with other particles "
                     "than the engine has (another checkpoint at the same "
                     "step): restore both from the same checkpoint", what);
  return SB_SUCCESS;
}
