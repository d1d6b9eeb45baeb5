/* refdata.h — tiny reader for the reference CSVs in tests/data (header
 * line of column names, then rows of numbers; see tests/data/README.md).
 *
 *   sbt_table tab;
 *   sbt_table_load("passage_bm.csv", &tab);      // fails the test if absent
 *   int ct = sbt_col(&tab, "t");
 *   for (int i = 0; i < tab.nrow; i++) use(sbt_at(&tab, i, ct));
 *   sbt_table_free(&tab);
 *
 * The file is looked up as $srcdir/tests/data/NAME (the non-recursive build
 * runs the tests from the top build directory with srcdir = top srcdir),
 * then $srcdir/data/NAME, then tests/data/NAME and data/NAME.
 */
#ifndef SB_REFDATA_H
#define SB_REFDATA_H

#include <check.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define SBT_MAXCOL 16

typedef struct {
  int ncol, nrow;
  char name[SBT_MAXCOL][24];
  double *v; /* nrow * ncol values, row-major */
} sbt_table;

static inline FILE *sbt_open_data(const char *name, char *path, size_t len)
{
  const char *dir = getenv("srcdir");
  const char *fmt[] = {"%s/tests/data/%s", "%s/data/%s"};
  for (int k = 0; k < 2; k++) {
    snprintf(path, len, fmt[k], dir ? dir : ".", name);
    FILE *f = fopen(path, "r");
    if (f)
      return f;
  }
  return NULL;
}

/* Load NAME; ck_abort (test failure) if missing or malformed. */
static inline void sbt_table_load(const char *name, sbt_table *t)
{
  char path[1024], line[4096];
  FILE *f = sbt_open_data(name, path, sizeof path);
  ck_assert_msg(f != NULL, "reference file %s not found (srcdir=%s)", name,
                getenv("srcdir") ? getenv("srcdir") : "(unset)");
  memset(t, 0, sizeof *t);
  ck_assert_msg(fgets(line, sizeof line, f) != NULL, "%s: empty", path);
  for (char *tok = strtok(line, ",\r\n"); tok; tok = strtok(NULL, ",\r\n")) {
    ck_assert_msg(t->ncol < SBT_MAXCOL, "%s: too many columns", path);
    snprintf(t->name[t->ncol++], sizeof t->name[0], "%s", tok);
  }
  size_t cap = 256;
  t->v = malloc(cap * t->ncol * sizeof *t->v);
  ck_assert_msg(t->v != NULL, "out of memory");
  while (fgets(line, sizeof line, f)) {
    if (line[0] == '\n' || line[0] == '#')
      continue;
    if ((size_t)t->nrow == cap) {
      cap *= 2;
      double *nv = realloc(t->v, cap * t->ncol * sizeof *t->v);
      ck_assert_msg(nv != NULL, "out of memory");
      t->v = nv;
    }
    char *p = line;
    for (int c = 0; c < t->ncol; c++) {
      char *end;
      double x = strtod(p, &end);
      ck_assert_msg(end != p, "%s: row %d column %d is not a number", path,
                    t->nrow + 2, c + 1);
      t->v[(size_t)t->nrow * t->ncol + c] = x;
      p = end;
      if (*p == ',')
        p++;
    }
    t->nrow++;
  }
  fclose(f);
  ck_assert_msg(t->nrow > 0, "%s: no data rows", path);
}

static inline int sbt_col(const sbt_table *t, const char *name)
{
  for (int c = 0; c < t->ncol; c++)
    if (strcmp(t->name[c], name) == 0)
      return c;
  ck_abort_msg("column %s not found", name);
  return -1;
}

static inline double sbt_at(const sbt_table *t, int row, int col)
{
  return t->v[(size_t)row * t->ncol + col];
}

static inline void sbt_table_free(sbt_table *t)
{
  free(t->v);
  t->v = NULL;
}

#endif /* SB_REFDATA_H */
