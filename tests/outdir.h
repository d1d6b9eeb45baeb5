/* outdir.h — temporary output directories of the tests that run
 * `smolbridge collide` configurations (test_collide_lib.c,
 * test_collide_walls.c): create one, read a file of it, remove it with
 * everything the run wrote.  Needs _POSIX_C_SOURCE 200809L (mkdtemp). */
#ifndef SB_TESTS_OUTDIR_H
#define SB_TESTS_OUTDIR_H

#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <check.h>

/* A fresh directory $TMPDIR/PREFIXXXXXXX (or under /tmp), in dir. */
static inline void sbt_tmp_dir(char *dir, size_t len, const char *prefix)
{
  const char *t = getenv("TMPDIR");
  snprintf(dir, len, "%s/%sXXXXXX", t && *t ? t : "/tmp", prefix);
  ck_assert_ptr_nonnull(mkdtemp(dir));
}

/* Remove every file of dir (a run writes no subdirectories here), then
 * dir itself. */
static inline void sbt_rm_dir(const char *dir)
{
  DIR *d = opendir(dir);
  if (d) {
    struct dirent *de;
    char p[1200];
    while ((de = readdir(d)) != NULL) {
      if (!strcmp(de->d_name, ".") || !strcmp(de->d_name, ".."))
        continue;
      snprintf(p, sizeof p, "%s/%s", dir, de->d_name);
      remove(p);
    }
    closedir(d);
  }
  rmdir(dir);
}

/* The whole text of a file, up to 64 KiB ("" if it cannot be read); free
 * it. */
static inline char *sbt_slurp(const char *path)
{
  FILE *f = fopen(path, "r");
  char *s = calloc(1, 1 << 16);
  ck_assert_ptr_nonnull(s);
  if (f) {
    size_t n = fread(s, 1, (1 << 16) - 1, f);
    s[n] = 0;
    fclose(f);
  }
  return s;
}

#endif
