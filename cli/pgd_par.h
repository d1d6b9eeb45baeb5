/* pgd_par.h — `smolbridge pgd` with method = decomposition over the MPI
 * ranks of the command (cli/par.h): each rank steps its blocks and the
 * blocks' messages (<smolbridge/pgd.h>, sb_pgd_dd_pack) travel through
 * sbc_par_exchange.  In one process these are the library's one-part
 * calls.  docs/pgd.md §6. */
#ifndef SB_CLI_PGD_PAR_H
#define SB_CLI_PGD_PAR_H

#include <stddef.h>
#include <smolbridge/pgd.h>

/* This rank's part of the decomposition: blocks split over the ranks by
 * sb_pgd_dd_split.  NULL on every rank if any failed (message recorded
 * on the ranks that did). */
sb_pgd_dd *sbc_pgd_dd_alloc(const sb_pgd_params *p, size_t px, size_t py,
                            const char *kinds);

/* Status of a rank whose part is fine when another rank failed. */
#define SBC_PGD_OTHER_RANK (-1)

/* Advance every rank's part to t_end (as sb_pgd_dd_advance).  Every rank
 * fails if one does: its own status (message recorded) on that rank,
 * SBC_PGD_OTHER_RANK on the others. */
int sbc_pgd_dd_advance(sb_pgd_dd *d, double t_end, size_t *nsteps);

/* Copies of every block on rank 0, so that its sb_pgd_dd_fields, _totals
 * and _particles cover the domain.  Collective; fails as the above. */
int sbc_pgd_dd_gather(sb_pgd_dd *d);

#endif /* SB_CLI_PGD_PAR_H */
