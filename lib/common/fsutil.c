/* fsutil.c — file-system helpers of the library and the command line
 * (output directories of collide, pgd, spray and validate runs). */
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
