/* collide.h — `smolbridge collide`: one run (collide.c) and sweeps of
 * runs over the MPI ranks (collide_sweep.c), over the library's run
 * description <smolbridge/collide.h>. */
#ifndef SB_CLI_COLLIDE_H
#define SB_CLI_COLLIDE_H

#include <stddef.h>

/* What one run gives a sweep's summary. */
typedef struct {
  char status[16];      /* ok, input error, run error, write error */
  char why[1100];       /* the message when not ok */
  char kind[16];        /* K_e (collision kernel) or first-hit */
  size_t particles;
  unsigned long long ncoll, steps;
  double K, lo, hi;     /* m^3/s and its 95% interval, NaN if none */
  int mixture;          /* several species: K is no single kernel */
  char pairs[1536];     /* then one kernel per species pair:
                           "a-b K [lo, hi]; ..." (col_pair_kernels) */
} col_point;

/* One run of CONFIG.ini with the overrides; progress on stderr when
 * verbose; *res (may be NULL) receives the summary.  Exit status as the
 * command's. */
int col_run_point(const char *ini, const char *const *sets, int nsets,
                  int verbose, col_point *res);
/* --sweep FILE: the points over the ranks (collide_sweep.c). */
int col_sweep(const char *ini, const char *const *sets, int nsets,
              const char *file);

#endif /* SB_CLI_COLLIDE_H */
