/* refdata.h — tiny reader for the reference CSVs in tests/data (header
 * line of column names, then rows of numbers; see tests/data/README.md).
 *
 *   sbt_table tab;
 *   sbt_table_load("passage_bm.csv", &tab);      // fails the test if absent
 *   int ct = sbt_col(&tab, "t");
 *   for (int i = 0; i < tab.nrow; i++) use(sbt_at(&tab, i, ct));
 *   sbt_table_free(&tab);
 *
 * The file is $srcdir/tests/data/NAME (sbt_data_path in testutil.h; the
 * non-recursive build runs the tests with srcdir = top srcdir).  Comment
 * lines (starting with '#') and blank lines are skipped, also before the
 * header.
 */
#ifndef SB_REFDATA_H
#define SB_REFDATA_H

#include <check.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "testutil.h"

#define SBT_MAXCOL 64

typedef struct {
  int ncol, nrow;
  char name[SBT_MAXCOL][24];
  double *v; /* nrow * ncol values, row-major */
} sbt_table;

/* Skip comment and blank lines: the next data (or header) line in buf,
 * or NULL at the end of the file. */
static inline char *sbt_next_line(char *buf, int len, FILE *f)
{
  while (fgets(buf, len, f))
    if (buf[0] != '#' && buf[0] != '\n' && buf[0] != '\r')
      return buf;
  return NULL;
}

/* Load NAME; ck_abort (test failure) if missing or malformed. */
static inline void sbt_table_load(const char *name, sbt_table *t)
{
  char path[1024], line[4096];
  FILE *f = fopen(sbt_data_path(name, path, sizeof path), "r");
  ck_assert_msg(f != NULL, "reference file %s not found", path);
  memset(t, 0, sizeof *t);
  ck_assert_msg(sbt_next_line(line, sizeof line, f) != NULL, "%s: empty",
                path);
  for (char *tok = strtok(line, ",\r\n"); tok; tok = strtok(NULL, ",\r\n")) {
    ck_assert_msg(t->ncol < SBT_MAXCOL, "%s: too many columns", path);
    snprintf(t->name[t->ncol++], sizeof t->name[0], "%s", tok);
  }
  size_t cap = 256;
  t->v = malloc(cap * t->ncol * sizeof *t->v);
  ck_assert_msg(t->v != NULL, "out of memory");
  while (sbt_next_line(line, sizeof line, f)) {
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

/* Value in row `row` of the column called `name` (test failure if none). */
static inline double sbt_get(const sbt_table *t, int row, const char *name)
{
  return sbt_at(t, row, sbt_col(t, name));
}

static inline void sbt_table_free(sbt_table *t)
{
  free(t->v);
  t->v = NULL;
}

#endif /* SB_REFDATA_H */
