/* pgd_dd_internal.h — the state of a domain decomposition (pgd_dd.c) and
 * what its messages between parts (pgd_dd_msg.c) read and write.  Private
 * to lib/pgd. */
#ifndef SB_PGD_DD_INTERNAL_H
#define SB_PGD_DD_INTERNAL_H

#include <stddef.h>
#include <smolbridge/pgd.h>
#include "pgd_internal.h"

/* A growable array of doubles: the records of a step's migrations and
 * budget events, kept as flat arrays so that they travel as messages. */
typedef struct {
  double *v;
  size_t n, cap;
} sbi_dbuf;

int sbi_dbuf_push(sbi_dbuf *b, const double *x, size_t k);

/* A migrating particle: destination block, w, x, y, vx, vy. */
#define SBI_DD_ITEM 6
/* A budget event: side, out (0/1), mass, momentum x, momentum y. */
#define SBI_DD_EVENT 5
/* The part that keeps the boundary budget (and replays its events). */
#define SBI_DD_KEEPER 0

typedef enum { SBI_DD_IDLE, SBI_DD_STAGES, SBI_DD_MOVED } sbi_dd_phase;

typedef struct {
  char kind;             /* 'E' or 'L' */
  int owner;             /* the part that steps it */
  int present;           /* its state is here: owned, or a collected copy */
  size_t i0, j0;         /* first global cell */
  sb_pgd_params p;       /* the block's own grid */
  struct sb_pgd *e;      /* Eulerian block */
  sbi_parts parts;       /* Lagrangian block */
  int nbr[4];            /* neighbour block per side, -1: physical side */
  double *pend[4];       /* Eulerian block: mass and momentum sent towards
                            a Lagrangian neighbour and not yet injected
                            (3 per boundary cell) */
  /* this step's particles that left the block [0] or were injected from
   * it [1], as items (all of them on the owner; on another part those
   * bound for its blocks) */
  sbi_dbuf seg[2];
  /* this step's budget events: [0] injection (inflows, physical faces of
   * an Eulerian block), [1] and [2] particles of seg[0] and seg[1] that
   * left the domain (on the owner and on the keeper) */
  sbi_dbuf ev[3];
} dd_block;

struct sb_pgd_dd {
  sb_pgd_params p;
  sbi_locator loc;
  size_t px, py, nbx, nby;
  double dx, dy, pspeed;
  dd_block *b;
  size_t nblocks;
  int nparts, part;      /* the parts of the run and this one */
  sbi_parts moving;      /* scratch: particles injected by one face */
  sbi_dd_phase phase;
  int stage, nst;        /* next Runge-Kutta stage, their number */
  double dt, t_end;      /* the step under way, and where it stops */
  double t;
  size_t steps;
  sbi_budget bud;
};

/* Ghost cell l (1..SBI_PGD_G) at position k along side s of an Eulerian
 * block, and the cell of the neighbour across s that it copies.  Padded
 * indices: every block has the layout of g. */
static inline void sbi_dd_halo_idx(const struct sb_pgd *g, long nx, long ny,
                                   int s, long k, long l, size_t *gh,
                                   size_t *src)
{
  switch (s) {
  case SB_PGD_WEST:
    *gh = sbi_pgd_idx(g, -l, k);
    *src = sbi_pgd_idx(g, nx - l, k);
    break;
  case SB_PGD_EAST:
    *gh = sbi_pgd_idx(g, nx - 1 + l, k);
    *src = sbi_pgd_idx(g, l - 1, k);
    break;
  case SB_PGD_SOUTH:
    *gh = sbi_pgd_idx(g, k, -l);
    *src = sbi_pgd_idx(g, k, ny - l);
    break;
  default:
    *gh = sbi_pgd_idx(g, k, ny - 1 + l);
    *src = sbi_pgd_idx(g, k, l - 1);
    break;
  }
}

/* Whether Eulerian block b takes the ghost cells of side s from an
 * Eulerian neighbour (and which), else -1. */
static inline int sbi_dd_euler_nbr(const struct sb_pgd_dd *d,
                                   const dd_block *b, int s)
{
  int n = b->nbr[s];
  return b->kind == 'E' && n >= 0 && d->b[n].kind == 'E' ? n : -1;
}

/* The solver and pending-flux arrays of Eulerian block b (owned, or a
 * copy being collected).  SB_ENOMEM with a message. */
int sbi_dd_block_alloc(struct sb_pgd_dd *d, dd_block *b);

#endif /* SB_PGD_DD_INTERNAL_H */
