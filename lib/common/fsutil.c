#define _POSIX_C_SOURCE 200809L /* open_memstream, fmemopen */
/* fsutil.c — file-system helpers of the library and the command line
 * (output directories of collide, pgd, spray and validate runs; the files
 * of saved states). */
#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>

#include "internal.h"

/* SB_EIO naming the path, errno kept for the caller's message. */
static int io_fail(const char *path)
{
  const int e = errno;
  sbi_error(SB_EIO, "sb_mkdir_p", "'%s': %s", path, strerror(e));
  errno = e;
  return SB_EIO;
}

int sb_mkdir_p(const char *path)
{
  char buf[1024];
  if (!path || !path[0])
    return sbi_error(SB_EINVAL, __func__, "empty directory name");
  if (snprintf(buf, sizeof buf, "%s", path) >= (int)sizeof buf) {
    errno = ENAMETOOLONG;
    return io_fail(path);
  }
  for (char *p = buf + 1; *p; p++)
    if (*p == '/') {
      *p = 0;
      if (mkdir(buf, 0777) && errno != EEXIST)
        return io_fail(buf);
      *p = '/';
    }
  if (mkdir(buf, 0777) && errno != EEXIST)
    return io_fail(buf);
  struct stat st;
  if (stat(buf, &st) || !S_ISDIR(st.st_mode)) {
    errno = ENOTDIR;
    return io_fail(buf);
  }
  return SB_SUCCESS;
}

/* The saves of states beside checkpoints (engine, collide). */
FILE *sbi_open_for_save(const char *path, const char *func)
{
  FILE *f = fopen(path, "wb");
  if (!f)
    sbi_error(SB_EIO, func, "cannot open '%s' for writing", path);
  return f;
}

int sbi_finish_save(FILE *f, int ok, const char *path, const char *func)
{
  ok &= fclose(f) == 0;
  if (ok)
    return SB_SUCCESS;
  struct stat sb;  /* a regular file only: not a device or a pipe */
  if (stat(path, &sb) == 0 && S_ISREG(sb.st_mode))
    remove(path);
  return sbi_error(SB_EIO, func, "write error on '%s'", path);
}

FILE *sbi_open_saved(const char *path, const char *func, int *status)
{
  *status = SB_SUCCESS;
  if (!path) {
    *status = sbi_error(SB_EINVAL, func, "path is NULL");
    return NULL;
  }
  FILE *f = fopen(path, "rb");
  if (!f)
    *status = sbi_error(SB_EIO, func, "cannot open '%s'", path);
  return f;
}

/* ------------------------------------------------ saves with a hash */

uint64_t sbi_fnv1a(uint64_t h, const void *p, size_t n)
{
  const unsigned char *c = p;
  for (size_t k = 0; k < n; k++)
    h = (h ^ c[k]) * 0x100000001b3ULL;
  return h;
}

FILE *sbi_hsave_begin(sbi_hsave *h, const char *func)
{
  h->buf = NULL;
  h->len = 0;
  h->f = open_memstream(&h->buf, &h->len);
  if (!h->f)
    sbi_error(SB_ENOMEM, func, "out of memory");
  return h->f;
}

int sbi_hsave_finish(sbi_hsave *h, int ok, const char *path,
                     const char *func)
{
  return sbi_hsave_finish_ord(h, ok, 0, path, func);
}

int sbi_hsave_finish_ord(sbi_hsave *h, int ok, int swap, const char *path,
                         const char *func)
{
  ok &= fclose(h->f) == 0;
  h->f = NULL;
  if (!ok) {
    free(h->buf);
    h->buf = NULL;
    return sbi_error(SB_ENOMEM, func, "out of memory for the state");
  }
  const uint64_t hash = sbi_fnv1a(SBI_FNV_BASIS, h->buf, h->len);
  FILE *f = sbi_open_for_save(path, func);
  if (f)
    ok = fwrite(h->buf, 1, h->len, f) == h->len &&
         sbi_write_ord(f, &hash, sizeof hash, 1, swap);
  free(h->buf);
  h->buf = NULL;
  return f ? sbi_finish_save(f, ok, path, func) : SB_EIO;
}

uint32_t sbi_bswap32(uint32_t v)
{
  return (v >> 24) | ((v >> 8) & 0xff00u) | ((v << 8) & 0xff0000u) |
         (v << 24);
}

static uint64_t bswap64(uint64_t v)
{
  return ((uint64_t)sbi_bswap32((uint32_t)v) << 32) |
         sbi_bswap32((uint32_t)(v >> 32));
}

int sbi_hash_check(const char *buf, size_t len)
{
  uint64_t h;
  memcpy(&h, buf + len - 8, 8);
  const uint64_t want = sbi_fnv1a(SBI_FNV_BASIS, buf, len - 8);
  if (h == want)
    return 0;
  return bswap64(h) == want ? 1 : -1;
}

char *sbi_slurp(FILE *f, size_t *len)
{
  size_t cap = 1 << 12, n = 0;
  char *b = malloc(cap);
  while (b) {
    n += fread(b + n, 1, cap - n, f);
    if (n < cap)
      break;
    char *nb = cap < ((size_t)1 << 62) ? realloc(b, 2 * cap) : NULL;
    if (!nb) {
      free(b);
      return NULL;
    }
    b = nb;
    cap *= 2;
  }
  if (b && ferror(f)) {
    free(b);
    return NULL;
  }
  *len = n;
  return b;
}

/* sbi_hload_open (swap = -1: native binary) and sbi_hload_open_ord
 * (swap 0 or 1: a fixed byte order). */
static FILE *hload_open(const char *path, const char magic[8],
                        int hashed_from, const char *what, int *ver,
                        char **mem, int swap, const char *func,
                        int *status)
{
  *mem = NULL;
  *ver = 0;
  FILE *file = sbi_open_saved(path, func, status);
  if (!file)
    return NULL;
  size_t len = 0;
  char *buf = sbi_slurp(file, &len);
  fclose(file);
  if (!buf) {
    *status = sbi_error(SB_EIO, func, "cannot read '%s'", path);
    return NULL;
  }
  const int cur = (magic[6] - '0') * 10 + (magic[7] - '0');
  int v = 0;
  if (len >= 8 && !memcmp(buf, magic, 6) && buf[6] >= '0' &&
      buf[6] <= '9' && buf[7] >= '0' && buf[7] <= '9')
    v = (buf[6] - '0') * 10 + (buf[7] - '0');
  if (v < 1 || v > cur) {
    free(buf);
    *status = sbi_error(SB_EFORMAT, func, "'%s': not a %s%s", path, what,
                        v > cur ? " of this version (written by a newer "
                                  "build)" : "");
    return NULL;
  }
  if (v >= hashed_from) {
    int c = len >= 16 ? sbi_hash_check(buf, len) : -1;
    if (c >= 0 && swap == 1)  /* 0: the hash in the file's order */
      c = !c;
    if (c) {
      free(buf);
      *status = c > 0 && swap < 0
          ? sbi_error(SB_EFORMAT, func, "'%s' was written on a machine of "
                      "the other byte order: a %s is native binary, load "
                      "it where it was written", path, what)
          : c > 0
          ? sbi_error(SB_EFORMAT, func, "'%s' is in the other byte order, "
                      "big-endian: a %s of an older build on a big-endian "
                      "machine (they are little-endian now); load it with "
                      "that build", path, what)
          : sbi_error(SB_EFORMAT, func, "'%s' is damaged: its contents "
                      "do not match the hash at its end (cut short or "
                      "changed)", path);
      return NULL;
    }
    len -= 8;
  }
  FILE *f = fmemopen(buf, len, "rb");
  if (!f) {
    free(buf);
    *status = sbi_error(SB_ENOMEM, func, "out of memory");
    return NULL;
  }
  *ver = v;
  *mem = buf;
  *status = SB_SUCCESS;
  return f;
}

FILE *sbi_hload_open(const char *path, const char magic[8], int hashed_from,
                     const char *what, int *ver, char **mem,
                     const char *func, int *status)
{
  return hload_open(path, magic, hashed_from, what, ver, mem, -1, func,
                    status);
}

FILE *sbi_hload_open_ord(const char *path, const char magic[8],
                         int hashed_from, const char *what, int *ver,
                         char **mem, int swap, const char *func,
                         int *status)
{
  return hload_open(path, magic, hashed_from, what, ver, mem, swap != 0,
                    func, status);
}
