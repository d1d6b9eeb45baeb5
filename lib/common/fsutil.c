/* fsutil.c — file-system helpers of the library and the command line
 * (output directories of collide, pgd, spray and validate runs; the files
 * of saved states). */
#include <errno.h>
#include <stdio.h>
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
