/* engine_same.h — "the same run, bit for bit" for the engine suites:
 * particle count, positions, velocities, counters and the time series of
 * two engines.  Searches that differ in how they find candidates (brute
 * force, cells, sweep, a Verlet list) must still give the same run; the
 * candidate and re-detection counters are compared only where the two
 * searches are meant to produce the same candidates (flags below). */
#ifndef SB_ENGINE_SAME_H
#define SB_ENGINE_SAME_H

#include <string.h>

#include <check.h>
#include <smolbridge/engine.h>

enum {
  SBT_SAME_CANDIDATES = 1,  /* also ncand and dropped */
  SBT_SAME_REDETECTED = 2   /* also the re-detection count */
};

static inline void sbt_assert_same_run(const sb_engine *a, const sb_engine *b,
                                       int flags)
{
  size_t n = sb_engine_count(a);
  ck_assert_uint_eq(n, sb_engine_count(b));
  ck_assert(!memcmp(sb_engine_positions(a), sb_engine_positions(b),
                    3 * n * sizeof(double)));
  ck_assert(!memcmp(sb_engine_velocities(a), sb_engine_velocities(b),
                    3 * n * sizeof(double)));
  sb_engine_stats sa, sb;
  sb_engine_get_stats(a, &sa);
  sb_engine_get_stats(b, &sb);
  ck_assert_uint_eq(sa.ncoll, sb.ncoll);
  ck_assert_uint_eq(sa.steps, sb.steps);
  ck_assert(sa.t == sb.t);
  if (flags & SBT_SAME_CANDIDATES) {
    ck_assert_uint_eq(sa.ncand, sb.ncand);
    ck_assert_uint_eq(sa.dropped, sb.dropped);
  }
  if (flags & SBT_SAME_REDETECTED)
    ck_assert_uint_eq(sa.redetected, sb.redetected);
  size_t na, nb;
  const sb_engine_sample *ta = sb_engine_series(a, &na);
  const sb_engine_sample *tb = sb_engine_series(b, &nb);
  ck_assert_uint_eq(na, nb);
  for (size_t k = 0; k < na; k++) {
    ck_assert(ta[k].t == tb[k].t);
    ck_assert_uint_eq(ta[k].ncoll, tb[k].ncoll);
    ck_assert(ta[k].ekin == tb[k].ekin);
  }
}

#endif
