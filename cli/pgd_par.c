/* pgd_par.c — the decomposition of `smolbridge pgd` over MPI ranks
 * (pgd_par.h).  The library does the physics and says what to send; this
 * file moves the messages (sbc_par_exchange) in the order of
 * <smolbridge/pgd.h>: a minimum over the ranks for dt, ghost cells before
 * every stage, migrating particles and budget events after the moves.  A
 * rank whose library call fails keeps taking part in the exchanges (with
 * empty messages) until the next minimum, which carries the failure to
 * all; out of memory inside an exchange stops the job (sbc_par_abort). */
#include <math.h>
#include <stdlib.h>

#include <smolbridge/pgd.h>

#include "par.h"
#include "pgd_par.h"

sb_pgd_dd *sbc_pgd_dd_alloc(const sb_pgd_params *p, size_t px, size_t py,
                            const char *kinds)
{
  const int P = sbc_par_size();
  if (P == 1)
    return sb_pgd_dd_alloc(p, px, py, kinds);
  int *owner = malloc(px * py * sizeof *owner);
  sb_pgd_dd *d = NULL;
  if (owner && sb_pgd_dd_split(px * py, P, owner) == SB_SUCCESS)
    d = sb_pgd_dd_alloc_part(p, px, py, kinds, owner, P, sbc_par_rank());
  free(owner);
  if (sbc_par_max_int(d == NULL)) {
    sb_pgd_dd_free(d);
    return NULL;
  }
  return d;
}

/* Message m from this rank to every other, and theirs to it.  Once
 * *st is set, only empty messages go out. */
static void exchange(sb_pgd_dd *d, sb_pgd_dd_msg m, int only_to, int *st)
{
  const int P = sbc_par_size(), me = sbc_par_rank();
  double **send = calloc(2 * (size_t)P, sizeof *send);
  size_t *n = calloc(2 * (size_t)P, sizeof *n);
  if (!send || !n) /* the others would wait for this rank */
    sbc_par_abort("pgd: out of memory for the message lists");
  double **recv = send + P;
  size_t *nr = n + P;
  for (int q = 0; !*st && q < P; q++) {
    if (q == me || (only_to >= 0 && q != only_to))
      continue;
    *st = sb_pgd_dd_pack(d, m, q, NULL, 0, &n[q]);
    if (!*st && n[q] && !(send[q] = malloc(n[q] * sizeof(double))))
      *st = SB_ENOMEM;
    if (!*st)
      *st = sb_pgd_dd_pack(d, m, q, send[q], n[q], &n[q]);
  }
  if (*st)
    for (int q = 0; q < P; q++)
      n[q] = 0;
  /* everyone takes part, failed or not */
  sbc_par_exchange(send, n, recv, nr);
  for (int q = 0; !*st && q < P; q++)
    if (q != me)
      *st = sb_pgd_dd_unpack(d, m, q, recv[q], nr[q]);
  for (int q = 0; q < 2 * P; q++)
    free(send[q]);
  free(send);
  free(n);
}

/* The smallest dt over the ranks; a rank that failed sends -1. */
static double global_dt(const sb_pgd_dd *d, int st)
{
  return sbc_par_min_double(st ? -1.0 : sb_pgd_dd_dt(d));
}

int sbc_pgd_dd_advance(sb_pgd_dd *d, double t_end, size_t *nsteps)
{
  if (sbc_par_size() == 1)
    return sb_pgd_dd_advance(d, t_end, nsteps);
  int st = SB_SUCCESS;
  size_t k = 0;
  for (;;) {
    /* every rank is at the same time unless one failed, and then every
     * rank leaves here */
    double dt = global_dt(d, st);
    if (dt < 0) {
      if (!st)
        st = SBC_PGD_OTHER_RANK;
      break;
    }
    if (sb_pgd_dd_time(d) >= t_end)
      break;
    st = sb_pgd_dd_begin(d, dt, t_end);
    for (int s = 0; s < sb_pgd_dd_nstages(d); s++) {
      exchange(d, SB_PGD_DD_HALO, -1, &st);
      if (!st)
        st = sb_pgd_dd_stage(d);
    }
    if (!st)
      st = sb_pgd_dd_move(d);
    exchange(d, SB_PGD_DD_MIGRATE, -1, &st);
    if (!st)
      st = sb_pgd_dd_end(d);
    k++;
  }
  if (nsteps)
    *nsteps = k;
  return st;
}

int sbc_pgd_dd_gather(sb_pgd_dd *d)
{
  if (sbc_par_size() == 1)
    return SB_SUCCESS;
  int st = SB_SUCCESS;
  exchange(d, SB_PGD_DD_STATE, 0, &st);
  return sbc_par_max_int(st != SB_SUCCESS) && !st ? SBC_PGD_OTHER_RANK : st;
}
