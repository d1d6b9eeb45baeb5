/* engine_field_io.c — save and restore the random fluid fields
 * (<smolbridge/engine_field.h>) beside an engine checkpoint, so that a
 * run in a random field goes on from the checkpoint as if it had not
 * stopped: the OU field's seen velocities (and the state of its own
 * generator, when it has one apart from the engine's), the Kraichnan
 * field's modes (drawn once: a field drawn again from the engine's
 * generator would be another realization).
 *
 * Formats (native binary, like the engine's checkpoint):
 *   "SBFOU002", n, u2, T_L, dt, whether a generator follows (its name,
 *   32 bytes, its state size and bytes), the 3 n seen velocities;
 *   "SBFKR002", L, s2, eps_nu, omega, M, the number of modes, their
 *   lattice vectors, a, b and w;
 * each followed by the FNV-1a hash of every byte before it
 * (common/internal.h, sbi_hsave_finish), checked before anything is
 * read.  Version 001 of either, the same without the hash, still loads. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "common/internal.h"
#include "engine_field_state.h"
#include "engine_internal.h"

static const char OU_MAGIC[8] = {'S', 'B', 'F', 'O', 'U', '0', '0', '2'};
static const char KR_MAGIC[8] = {'S', 'B', 'F', 'K', 'R', '0', '0', '2'};

#define W(x) (fwrite(&(x), sizeof(x), 1, f) == 1)
#define R(x) (fread(&(x), sizeof(x), 1, f) == 1)

int sb_field_ou_save(const sb_field_ou *fd, int with_rng, const char *path)
{
  if (!fd || !path)
    return sbi_error(SB_EINVAL, __func__, "NULL argument");
  sbi_hsave hs;
  FILE *f = sbi_hsave_begin(&hs, __func__);
  if (!f)
    return SB_ENOMEM;
  const uint64_t n = fd->n;
  const int32_t g = with_rng != 0;
  int ok = fwrite(OU_MAGIC, 1, 8, f) == 8 && W(n) && W(fd->u2) &&
           W(fd->TL) && W(fd->dt) && W(g);
  if (ok && g) {
    char name[32] = {0};
    strncpy(name, gsl_rng_name(fd->r), sizeof name - 1);
    const uint64_t size = gsl_rng_size(fd->r);
    ok = fwrite(name, 1, sizeof name, f) == sizeof name && W(size) &&
         fwrite(gsl_rng_state(fd->r), 1, size, f) == size;
  }
  ok = ok && fwrite(fd->U, sizeof *fd->U, 3 * n, f) == 3 * n;
  return sbi_hsave_finish(&hs, ok, path, __func__);
}

/* Read f's OU field into a new field with generator r (its state
 * replaced by a saved one, only if the whole file is good); NULL with a
 * status and its reason. */
static sb_field_ou *ou_read(FILE *f, double u2, double TL, double dt,
                            gsl_rng *r, int *st, const char **why)
{
  char mg[8];
  uint64_t n;
  double fu2, fTL, fdt;
  int32_t g;
  *st = SB_EFORMAT;
  *why = "truncated, or data after the end";
  if (fread(mg, 1, 8, f) != 8) {
    *why = "not an OU field file";
    return NULL;
  }
  if (!R(n) || !R(fu2) || !R(fTL) || !R(fdt) || !R(g))
    return NULL;
  if (n == 0 || n > ((uint64_t)1 << 34) || (g != 0 && g != 1)) {
    *why = "malformed";
    return NULL;
  }
  if (fu2 != u2 || fTL != TL || fdt != dt) {
    *st = SB_EINVAL;
    *why = "saved with other parameters (u2, T_L or dt)";
    return NULL;
  }
  gsl_rng *t = NULL;  /* the saved generator state, read into a copy */
  if (g) {
    char name[32];
    uint64_t size;
    if (fread(name, 1, sizeof name, f) != sizeof name || !R(size))
      return NULL;
    name[sizeof name - 1] = 0;
    if (strcmp(name, gsl_rng_name(r)) || size != gsl_rng_size(r)) {
      *st = SB_EINVAL;
      *why = "its generator is of another type than the one given";
      return NULL;
    }
    if (!(t = gsl_rng_clone(r))) {
      *st = SB_ENOMEM, *why = "out of memory";
      return NULL;
    }
    if (fread(gsl_rng_state(t), 1, size, f) != size) {
      gsl_rng_free(t);
      return NULL;
    }
  }
  sb_field_ou *fd = calloc(1, sizeof *fd);
  double *U = fd ? malloc(3 * n * sizeof *U) : NULL;
  if (!U)
    *st = SB_ENOMEM, *why = "out of memory";
  else if (fread(U, sizeof *U, 3 * n, f) == 3 * n && fgetc(f) == EOF)
    *st = SB_SUCCESS;
  if (*st) {
    free(U);
    free(fd);
    gsl_rng_free(t);
    return NULL;
  }
  if (t) {
    memcpy(gsl_rng_state(r), gsl_rng_state(t), gsl_rng_size(r));
    gsl_rng_free(t);
  }
  fd->U = U;
  sbi_field_ou_set(fd, (size_t)n, u2, TL, dt, r);
  return fd;
}

sb_field_ou *sb_field_ou_load(const char *path, double u2, double TL,
                              double dt, gsl_rng *r, int *status)
{
  int dummy;
  if (!status)
    status = &dummy;
  int ver;
  char *mem = NULL;
  FILE *f = r ? sbi_hload_open(path, OU_MAGIC, 2, "OU field file", &ver,
                               &mem, __func__, status)
              : NULL;
  if (!r)
    *status = sbi_error(SB_EINVAL, __func__, "NULL generator");
  if (!f)
    return NULL;
  const char *why;
  sb_field_ou *fd = ou_read(f, u2, TL, dt, r, status, &why);
  fclose(f);
  free(mem);
  if (!fd)
    sbi_error(*status, __func__, "'%s': %s", path, why);
  return fd;
}

int sb_field_kraichnan_save(const sb_field_kraichnan *fd, const char *path)
{
  if (!fd || !path)
    return sbi_error(SB_EINVAL, __func__, "NULL argument");
  sbi_hsave hs;
  FILE *f = sbi_hsave_begin(&hs, __func__);
  if (!f)
    return SB_ENOMEM;
  const int32_t M = fd->M;
  const uint64_t nm = fd->nm;
  const int ok =
      fwrite(KR_MAGIC, 1, 8, f) == 8 && W(fd->L) && W(fd->s2) &&
      W(fd->eps_nu) && W(fd->omega) && W(M) && W(nm) &&
      fwrite(fd->m, sizeof fd->m[0], nm, f) == nm &&
      fwrite(fd->a, sizeof fd->a[0], nm, f) == nm &&
      fwrite(fd->b, sizeof fd->b[0], nm, f) == nm &&
      fwrite(fd->w, sizeof fd->w[0], nm, f) == nm;
  return sbi_hsave_finish(&hs, ok, path, __func__);
}

sb_field_kraichnan *sb_field_kraichnan_load(const char *path, double L,
                                            int M, double eps_nu,
                                            double omega, int *status)
{
  int dummy;
  if (!status)
    status = &dummy;
  int ver;
  char *mem;
  FILE *f = sbi_hload_open(path, KR_MAGIC, 2, "Kraichnan field file", &ver,
                           &mem, __func__, status);
  if (!f)
    return NULL;
  sb_field_kraichnan *fd = calloc(1, sizeof *fd);
  if (!fd) {
    fclose(f);
    free(mem);
    *status = sbi_error(SB_ENOMEM, __func__, "out of memory");
    return NULL;
  }
  char mg[8];
  int32_t fM;
  uint64_t nm;
  const char *why = "truncated, or data after the end";
  int st = SB_EFORMAT;
  if (fread(mg, 1, 8, f) != 8)
    why = "not a Kraichnan field file";
  else if (R(fd->L) && R(fd->s2) && R(fd->eps_nu) && R(fd->omega) &&
           R(fM) && R(nm)) {
    if (nm > SB_FIELD_KRAICHNAN_MAXMODES || fM < 1 ||
        fM > SB_FIELD_KRAICHNAN_MAXM)
      why = "malformed";
    else if (fd->L != L || fM != M || fd->eps_nu != eps_nu ||
             fd->omega != omega)
      st = SB_EINVAL, why = "saved with other parameters (L, shell, eps_nu "
                            "or omega)";
    else if (fread(fd->m, sizeof fd->m[0], nm, f) == nm &&
             fread(fd->a, sizeof fd->a[0], nm, f) == nm &&
             fread(fd->b, sizeof fd->b[0], nm, f) == nm &&
             fread(fd->w, sizeof fd->w[0], nm, f) == nm && fgetc(f) == EOF)
      st = SB_SUCCESS;
  }
  fclose(f);
  free(mem);
  if (st) {
    free(fd);
    *status = sbi_error(st, __func__, "'%s': %s", path, why);
    return NULL;
  }
  fd->M = fM;
  fd->nm = (size_t)nm;
  *status = SB_SUCCESS;
  return fd;
}
