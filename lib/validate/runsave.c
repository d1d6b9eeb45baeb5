/* runsave.c — finished engine runs kept on disk (runsave.h). */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <smolbridge/common.h>
#include <smolbridge/validate.h>

#include "common/internal.h"
#include "runsave.h"

/* Format (text): the magic line, "key=KEY", "vals=N" and N values, one
 * a line in C99 hexadecimal, "extra=M" and M values, "end"; then (version
 * 2) the FNV-1a hash of every byte before it, 8 bytes in native order
 * (common/internal.h, sbi_hsave_finish): a file that was cut, flipped or
 * mixed up is refused before any of it is used.  Version 1 files
 * (magic line "smolbridge-run 1", no hash) still load. */
static const char MAGIC[8] = {'S', 'B', 'V', 'R', 'U', 'N', '0', '2'};
#define MAGIC_V1 "smolbridge-run 1\n"

static void key_add(sbv_runkey *k, const char *fmt, ...)
{
  if (k->overflow)
    return;
  va_list ap;
  va_start(ap, fmt);
  int w = vsnprintf(k->s + k->n, sizeof k->s - k->n, fmt, ap);
  va_end(ap);
  if (w < 0 || (size_t)w >= sizeof k->s - k->n)
    k->overflow = 1;
  else
    k->n += (size_t)w;
}

void sbv_runkey_init(sbv_runkey *k, const sbv_ctx *ctx, const char *kind,
                     unsigned long stream)
{
  k->n = 0;
  k->overflow = 0;
  k->s[0] = 0;
  key_add(k, "%s v%s seed=%lu stream=%lu", kind, sb_version(), ctx->seed,
          stream);
}

void sbv_runkey_num(sbv_runkey *k, const char *name, double v)
{
  key_add(k, " %s=%a", name, v);
}

/* The directory of saved runs, or NULL when runs are not saved. */
static const char *run_dir(const sbv_ctx *ctx)
{
  const sb_validate_options *o = ctx->opt;
  return o && o->run_dir && o->run_dir[0] ? o->run_dir : NULL;
}

/* run_dir/HASH.run, HASH the 64-bit FNV-1a hash of the key. */
static int run_path(const char *dir, const sbv_runkey *k, char *path,
                    size_t n)
{
  uint64_t h = 14695981039346656037ULL;
  for (size_t i = 0; i < k->n; i++) {
    h ^= (unsigned char)k->s[i];
    h *= 1099511628211ULL;
  }
  int w = snprintf(path, n, "%s/%016llx.run", dir, (unsigned long long)h);
  return w > 0 && (size_t)w < n ? 0 : -1;
}

/* One value line; 0 on success. */
static int read_value(FILE *f, double *v)
{
  char line[64], *end;
  if (!fgets(line, sizeof line, f))
    return -1;
  errno = 0;
  *v = strtod(line, &end);
  return errno || end == line || (*end != '\n' && *end != 0) ? -1 : 0;
}

/* "NAME=COUNT\n"; 0 on success. */
static int read_count(FILE *f, const char *name, size_t *n)
{
  char line[64];
  size_t len = strlen(name);
  if (!fgets(line, sizeof line, f) || strncmp(line, name, len) ||
      line[len] != '=')
    return -1;
  char *end;
  errno = 0;
  unsigned long long c = strtoull(line + len + 1, &end, 10);
  if (errno || *end != '\n' || c > 100000000ULL)
    return -1;
  *n = (size_t)c;
  return 0;
}

int sbv_run_load(const sbv_ctx *ctx, const sbv_runkey *k, double *vals,
                 size_t nvals, double **extra, size_t *nextra)
{
  *extra = NULL;
  *nextra = 0;
  const char *dir = run_dir(ctx);
  char path[4096];
  if (!dir || !ctx->opt->resume || k->overflow ||
      run_path(dir, k, path, sizeof path))
    return 0;
  FILE *f = fopen(path, "r");
  if (!f)
    return 0;
  static const size_t cap = SBV_KEY_MAX + 8;
  char *line = malloc(cap), *mem = NULL;
  if (!line) {
    fclose(f);
    return SB_ENOMEM;
  }
  int ok = fgets(line, (int)cap, f) != NULL;
  if (ok && strcmp(line, MAGIC_V1)) {  /* version 2: its hash checked */
    fclose(f);
    int ver, st;
    f = sbi_hload_open(path, MAGIC, 2, "saved run", &ver, &mem, __func__,
                       &st);
    if (!f) {
      free(line);
      if (st == SB_ENOMEM)
        return st;
      /* damaged, or not a saved run: made again (and saved over) */
      sbv_progress(ctx, "  (saved run refused, made again: %s)",
                   sb_last_error());
      return 0;
    }
    ok = fgets(line, (int)cap, f) && !memcmp(line, MAGIC, 8) &&
         line[8] == '\n' && line[9] == 0;
  }
  ok = ok && fgets(line, (int)cap, f) && strncmp(line, "key=", 4) == 0 &&
           strlen(line + 4) == k->n + 1 &&
           memcmp(line + 4, k->s, k->n) == 0 && line[4 + k->n] == '\n';
  free(line);
  size_t nv = 0, ne = 0;
  ok = ok && !read_count(f, "vals", &nv) && nv == nvals;
  for (size_t i = 0; ok && i < nv; i++)
    ok = !read_value(f, vals + i);
  ok = ok && !read_count(f, "extra", &ne);
  double *x = NULL;
  if (ok && ne) {
    x = malloc(ne * sizeof *x);
    if (!x) {
      fclose(f);
      free(mem);
      return SB_ENOMEM;
    }
  }
  for (size_t i = 0; ok && i < ne; i++)
    ok = !read_value(f, x + i);
  char tail[8];
  ok = ok && fgets(tail, sizeof tail, f) && strcmp(tail, "end\n") == 0;
  fclose(f);
  free(mem);
  if (!ok) {  /* another key, or damaged: make the run again */
    free(x);
    return 0;
  }
  *extra = x;
  *nextra = ne;
  sbv_progress(ctx, "  (read back from the saved runs)");
  return 1;
}

int sbv_run_load_vals(const sbv_ctx *ctx, const sbv_runkey *k,
                      double *vals, size_t nvals)
{
  double *extra;
  size_t nextra;
  int got = sbv_run_load(ctx, k, vals, nvals, &extra, &nextra);
  free(extra);
  return got;
}

void sbv_run_save(const sbv_ctx *ctx, const sbv_runkey *k,
                  const double *vals, size_t nvals, const double *extra,
                  size_t nextra)
{
  const char *dir = run_dir(ctx);
  if (!dir || k->overflow)
    return;
  char path[4096], tmp[4200];
  if (run_path(dir, k, path, sizeof path))
    return;
  /* a name of this process and call: concurrent savers never share it */
  snprintf(tmp, sizeof tmp, "%s.%ld.%p.tmp", path, (long)getpid(),
           (const void *)k);
  sbi_hsave hs;  /* the text, then its hash (sbi_hsave_finish) */
  FILE *f = sb_mkdir_p(dir) == SB_SUCCESS ? sbi_hsave_begin(&hs, __func__)
                                          : NULL;
  int ok = f != NULL;
  if (ok) {
    fprintf(f, "%.8s\nkey=%s\nvals=%zu\n", MAGIC, k->s, nvals);
    for (size_t i = 0; i < nvals; i++)
      fprintf(f, "%a\n", vals[i]);
    fprintf(f, "extra=%zu\n", nextra);
    for (size_t i = 0; i < nextra; i++)
      fprintf(f, "%a\n", extra[i]);
    fprintf(f, "end\n");
    ok = sbi_hsave_finish(&hs, !ferror(f), tmp, __func__) == SB_SUCCESS;
  }  /* (a failed finish leaves no file) */
  if (ok && rename(tmp, path)) {
    ok = 0;
    remove(tmp);
  }
  if (!ok) {
    sbv_progress(ctx, "  (could not save the run as %s; a resumed run "
                 "will make it again)", path);
  }
}
