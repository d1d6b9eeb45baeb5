/* spray_extreme.h — the reader of tests/data/spray_extreme.csv shared by
 * test_spray (kinds 0-6, 9-12, 15-24) and test_pgd_exact (kinds 7, 8, 13,
 * 14): corners of the closed forms where a double intermediate over- or
 * underflows but the value is a normal double, against mpmath
 * (tests/gen_spray_ref.py; columns kind, a1 .. a8, value).
 *
 * Each suite gives the value of a row by its function:
 *
 *   static double row(int kind, const double *a, double *got)
 *   {  ... *got = f(a[0], a[1]); return 1e-13;  (0: kind not handled) }
 *   ck_assert_int_ge(sbt_spray_extreme(row), 8);
 */
#ifndef SB_SPRAY_EXTREME_H
#define SB_SPRAY_EXTREME_H

#include <math.h>

#include "refdata.h"

/* The value of one row: a[0 .. 7] are its a1 .. a8; stores the suite's
 * value in *got and returns the relative tolerance, or returns 0 where the
 * suite does not handle kind (the row is skipped). */
typedef double (*sbt_spray_row)(int kind, const double *a, double *got);

/* Every row of spray_extreme.csv that row() handles, in file order:
 * |got - value| <= tol |value| (ck_assert_msg, labelled with the row and
 * kind).  Returns the number of rows checked. */
static inline int sbt_spray_extreme(sbt_spray_row row)
{
  sbt_table t;
  sbt_table_load("spray_extreme.csv", &t);
  const int ck = sbt_col(&t, "kind"), cv = sbt_col(&t, "value"),
            ca = sbt_col(&t, "a1");
  int nrow = 0;
  for (int i = 0; i < t.nrow; i++) {
    const int kind = (int)sbt_at(&t, i, ck);
    const double want = sbt_at(&t, i, cv);
    double a[8], got = NAN;
    for (int j = 0; j < 8; j++)
      a[j] = sbt_at(&t, i, ca + j);
    const double tol = row(kind, a, &got);
    if (tol == 0.0)
      continue;
    ck_assert_msg(fabs(got - want) <= tol * fabs(want),
                  "row %d (kind %d): %.17g, mpmath %.17g", i, kind, got,
                  want);
    nrow++;
  }
  sbt_table_free(&t);
  return nrow;
}

#endif /* SB_SPRAY_EXTREME_H */
