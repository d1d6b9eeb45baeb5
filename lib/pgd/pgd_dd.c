/* pgd_dd.c — Euler-Lagrange coupling by domain decomposition (the
 * exercise "Couplage Euler-Lagrange" (2022), part 4: 3 x 3 subdomains,
 * each Eulerian or Lagrangian).
 *
 * One global step dt for every block.  Eulerian blocks exchange ghost
 * cells at every stage; towards a Lagrangian neighbour their ghost cells
 * are vacuum, so the flux through that face is purely outgoing, and the
 * mass and momentum it carries over the step (integrated with the stage
 * weights) are injected there as particles, as an inflow would be.
 * Particles that end a step inside an Eulerian block are absorbed by the
 * cell that contains them (mass and momentum added).  Both transfers move
 * exactly the same mass and momentum from one representation to the
 * other, so the coupling conserves both (up to the drag, a source).
 *
 * The blocks may be shared between parts (processes), each stepping its
 * own; what crosses between parts is in pgd_dd_msg.c.  Every sum whose
 * order could depend on the parts is done in one global order: particles
 * reach a block by (left a block | injected), then source block; budget
 * events are replayed by one part in (injection, left, injected) order,
 * then block.  A one-part run follows the same path without messages. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <smolbridge/pgd.h>
#include "common/internal.h"
#include "pgd_internal.h"
#include "pgd_dd_internal.h"

int sbi_dbuf_push(sbi_dbuf *b, const double *x, size_t k)
{
  if (b->n + k > b->cap) {
    size_t cap = b->cap ? 2 * b->cap : 256;
    while (cap < b->n + k)
      cap *= 2;
    double *v = realloc(b->v, cap * sizeof *v);
    if (!v)
      return SB_ENOMEM;
    b->v = v;
    b->cap = cap;
  }
  memcpy(b->v + b->n, x, k * sizeof *x);
  b->n += k;
  return SB_SUCCESS;
}

/* A budget event; nothing to record when it adds zeros: a sum that
 * starts at +0 is never -0 (round to nearest), and x + (+-0) = x for any
 * other x, so the replayed budget is the same bit for bit. */
static int event(sbi_dbuf *ev, int side, int out, double m, double px,
                 double py)
{
  if (m == 0 && px == 0 && py == 0)
    return SB_SUCCESS;
  const double e[SBI_DD_EVENT] = {side, out, m, px, py};
  return sbi_dbuf_push(ev, e, SBI_DD_EVENT);
}

void sb_pgd_dd_free(sb_pgd_dd *d)
{
  if (!d)
    return;
  for (size_t k = 0; d->b && k < d->nblocks; k++) {
    dd_block *b = &d->b[k];
    sb_pgd_free(b->e);
    sbi_parts_free(&b->parts);
    for (int s = 0; s < 4; s++)
      free(b->pend[s]);
    for (int m = 0; m < 2; m++)
      free(b->seg[m].v);
    for (int m = 0; m < 3; m++)
      free(b->ev[m].v);
  }
  free(d->b);
  sbi_parts_free(&d->moving);
  free(d);
}

/* Neighbour of block (bi, bj) across side s, or -1 at a physical side. */
static int neighbour(const sb_pgd_dd *d, size_t bi, size_t bj, int s)
{
  long i = (long)bi, j = (long)bj, nx = (long)d->px, ny = (long)d->py;
  int per = d->p.bc[s] == SB_PGD_PERIODIC;
  switch (s) {
  case SB_PGD_WEST: i--; break;
  case SB_PGD_EAST: i++; break;
  case SB_PGD_SOUTH: j--; break;
  default: j++; break;
  }
  if (i < 0 || i >= nx || j < 0 || j >= ny) {
    if (!per)
      return -1;
    i = (i + nx) % nx;
    j = (j + ny) % ny;
  }
  return (int)(i + nx * j);
}

/* The block's parameters: its grid, physical sides and inflow parts. */
static void block_params(const sb_pgd_dd *d, dd_block *b, size_t bi,
                         size_t bj)
{
  sb_pgd_params *q = &b->p;
  *q = d->p;
  q->nx = d->nbx;
  q->ny = d->nby;
  q->L[0] = (double)d->nbx * d->dx;
  q->L[1] = (double)d->nby * d->dy;
  q->origin[0] = d->p.origin[0] + (double)b->i0 * d->dx;
  q->origin[1] = d->p.origin[1] + (double)b->j0 * d->dy;
  for (int s = 0; s < 4; s++) {
    b->nbr[s] = neighbour(d, bi, bj, s);
    int self = b->nbr[s] == (int)(bi + d->px * bj);
    if (b->nbr[s] >= 0 && !self)
      q->bc[s] = SB_PGD_OUTFLOW;  /* placeholder: ghosts set here */
    if (self)                     /* one block across a periodic direction */
      b->nbr[s] = -1;
  }
  q->ninflow = 0;
  for (size_t m = 0; m < d->p.ninflow; m++) {
    const sb_pgd_inflow *in = &d->p.inflow[m];
    if (b->nbr[in->side] >= 0)
      continue;
    int along_y = in->side < SB_PGD_SOUTH;
    size_t lo = along_y ? b->j0 : b->i0, n = along_y ? d->nby : d->nbx;
    size_t a = in->first > lo ? in->first : lo;
    size_t e = in->first + in->count < lo + n ? in->first + in->count
                                              : lo + n;
    if (a >= e)
      continue;
    sb_pgd_inflow *o = &q->inflow[q->ninflow++];
    *o = *in;
    o->first = a - lo;
    o->count = e - a;
  }
}

int sbi_dd_block_alloc(sb_pgd_dd *d, dd_block *b)
{
  int ext[4];
  for (int s = 0; s < 4; s++)
    ext[s] = b->nbr[s] >= 0;
  if (!(b->e = sbi_pgd_alloc(&b->p, ext)))
    return SB_ENOMEM;
  sbi_pgd_geometry(b->e, d->dx, d->dy, d->p.origin, b->i0, b->j0);
  for (int s = 0; s < 4; s++)
    if (b->nbr[s] >= 0 && d->b[b->nbr[s]].kind == 'L' &&
        !(b->pend[s] = calloc(3 * b->e->nb[s], sizeof(double))))
      return sbi_error(SB_ENOMEM, "sb_pgd_dd_alloc", "out of memory");
  return SB_SUCCESS;
}

sb_pgd_dd *sb_pgd_dd_alloc_part(const sb_pgd_params *p, size_t px,
                                size_t py, const char *kinds,
                                const int *owner, int nparts, int part)
{
  if (sb_pgd_params_check(p)) {
    sbi_error(SB_EINVAL, __func__, "%s", sb_last_error());
    return NULL;
  }
  if (p->dim != 2 || px < 1 || py < 1 || p->nx % px || p->ny % py ||
      p->nx / px < 2 || p->ny / py < 2) {
    sbi_error(SB_EINVAL, __func__, "need dim = 2 and %zu x %zu blocks of "
              "at least 2 x 2 cells dividing the %zu x %zu grid", px, py,
              p->nx, p->ny);
    return NULL;
  }
  if (!kinds || strlen(kinds) != px * py ||
      strspn(kinds, "EL") != px * py) {
    sbi_error(SB_EINVAL, __func__, "kinds '%s': need %zu letters E or L",
              kinds ? kinds : "(null)", px * py);
    return NULL;
  }
  if (nparts < 1 || part < 0 || part >= nparts || (!owner && nparts > 1)) {
    sbi_error(SB_EINVAL, __func__, "part %d of %d parts%s", part, nparts,
              owner ? "" : " without an owner map");
    return NULL;
  }
  for (size_t k = 0; owner && k < px * py; k++)
    if (owner[k] < 0 || owner[k] >= nparts) {
      sbi_error(SB_EINVAL, __func__, "owner[%zu] = %d: must be in [0, %d)",
                k, owner[k], nparts);
      return NULL;
    }
  sb_pgd_dd *d = calloc(1, sizeof *d);
  if (!d || !(d->b = calloc(px * py, sizeof *d->b))) {
    free(d);
    sbi_error(SB_ENOMEM, __func__, "out of memory");
    return NULL;
  }
  d->p = *p;
  d->px = px;
  d->py = py;
  d->nblocks = px * py;
  d->nparts = nparts;
  d->part = part;
  d->nbx = p->nx / px;
  d->nby = p->ny / py;
  d->dx = p->L[0] / (double)p->nx;
  d->dy = p->L[1] / (double)p->ny;
  d->pspeed = sbi_pgd_param_speed(p);
  sbi_locator_init(&d->loc, p);
  for (size_t k = 0; k < d->nblocks; k++) {
    dd_block *b = &d->b[k];
    b->kind = kinds[k];
    b->owner = owner ? owner[k] : part;
    b->present = b->owner == part;
  }
  for (size_t bj = 0; bj < py; bj++)
    for (size_t bi = 0; bi < px; bi++) {
      dd_block *b = &d->b[bi + px * bj];
      b->i0 = bi * d->nbx;
      b->j0 = bj * d->nby;
      block_params(d, b, bi, bj);
    }
  for (size_t k = 0; k < d->nblocks; k++)
    if (d->b[k].present && d->b[k].kind == 'E' &&
        sbi_dd_block_alloc(d, &d->b[k])) {
      sb_pgd_dd_free(d);
      return NULL;
    }
  return d;
}

sb_pgd_dd *sb_pgd_dd_alloc(const sb_pgd_params *p, size_t px, size_t py,
                           const char *kinds)
{
  return sb_pgd_dd_alloc_part(p, px, py, kinds, NULL, 1, 0);
}

int sb_pgd_dd_split(size_t nblocks, int nparts, int *owner)
{
  if (nparts < 1 || (size_t)nparts > nblocks || !owner)
    return sbi_error(SB_EINVAL, __func__, "%d parts for %zu blocks: need "
                     "1 to %zu", nparts, nblocks, nblocks);
  for (size_t k = 0; k < nblocks; k++)
    owner[k] = (int)(k * (size_t)nparts / nblocks);
  return SB_SUCCESS;
}

double sb_pgd_dd_time(const sb_pgd_dd *d) { return d ? d->t : NAN; }

size_t sb_pgd_dd_particles(const sb_pgd_dd *d)
{
  size_t n = 0;
  for (size_t k = 0; d && k < d->nblocks; k++)
    if (d->b[k].present)
      n += d->b[k].parts.n;
  return n;
}

double sb_pgd_dd_dt(const sb_pgd_dd *d)
{
  if (!d)
    return NAN;
  double s = d->pspeed;
  for (size_t k = 0; k < d->nblocks; k++) {
    const dd_block *b = &d->b[k];
    if (b->owner != d->part)
      continue;
    double v = b->kind == 'E' ? sbi_pgd_speed(b->e)
                              : sbi_lag_speed(&d->p, b->parts.q, b->parts.n);
    if (v > s)
      s = v;
  }
  return sbi_pgd_dt_from_speed(&d->p, s);
}

/* Ghost cells of Eulerian block b across its interfaces with blocks of
 * this part (the other parts' cells were unpacked into them). */
static void exchange(sb_pgd_dd *d, dd_block *b)
{
  struct sb_pgd *g = b->e;
  const long nx = (long)d->nbx, ny = (long)d->nby;
  for (int s = 0; s < 4; s++) {
    if (b->nbr[s] < 0)
      continue;
    const dd_block *o = &d->b[b->nbr[s]];
    if (o->kind == 'E' && o->owner != d->part)
      continue;
    long n = s < 2 ? ny : nx;
    for (long k = 0; k < n; k++)
      for (long l = 1; l <= SBI_PGD_G; l++) {
        size_t gh, src;
        sbi_dd_halo_idx(g, nx, ny, s, k, l, &gh, &src);
        if (o->kind == 'E') {
          g->rho[gh] = o->e->rho[src];
          g->qx[gh] = o->e->qx[src];
          g->qy[gh] = o->e->qy[src];
        } else { /* towards particles: only outgoing flux */
          g->rho[gh] = g->qx[gh] = g->qy[gh] = 0.0;
        }
      }
  }
}

/* Where a particle that left block src (ph = 0) or was injected from it
 * (ph = 1) now is: out of the domain (a budget event), or an item for the
 * block that contains it (wrapped across periodic sides). */
static int classify(sb_pgd_dd *d, dd_block *src, int ph, sb_pgd_particle q)
{
  int side = sbi_lag_place(&d->p, &q);
  if (side)
    return event(&src->ev[1 + ph], side - 1, 1, q.w, q.w * q.v[0],
                 q.w * q.v[1]);
  size_t i = sbi_locate1(&d->loc, 0, q.x[0]);
  size_t j = sbi_locate1(&d->loc, 1, q.x[1]);
  const double it[SBI_DD_ITEM] = {
      (double)(i / d->nbx + d->px * (j / d->nby)), q.w, q.x[0], q.x[1],
      q.v[0], q.v[1]};
  return sbi_dbuf_push(&src->seg[ph], it, SBI_DD_ITEM);
}

/* Classify the particles in d->moving as injected from b. */
static int classify_moving(sb_pgd_dd *d, dd_block *b)
{
  for (size_t m = 0; m < d->moving.n; m++)
    if (classify(d, b, 1, d->moving.q[m]))
      return SB_ENOMEM;
  d->moving.n = 0;
  return SB_SUCCESS;
}

/* Particles for the step from block b: its physical inflow faces
 * (Lagrangian) or its outgoing fluxes towards Lagrangian blocks
 * (Eulerian), and the budget of its physical faces.  SB_ENOMEM (no
 * message) or SB_ERANGE (message: an injected velocity minus the gas's
 * overflows, named after func). */
static int inject(sb_pgd_dd *d, dd_block *b, double dt,
                  const char *func)
{
  int st;
  const sb_pgd_params *q = &b->p;
  sbi_dbuf *ev = &b->ev[0];
  if (b->kind == 'L') {
    for (size_t m = 0; m < q->ninflow; m++) {
      const sb_pgd_inflow *in = &q->inflow[m];
      int dir = in->side >= SB_PGD_SOUTH;
      double sgn = in->side == SB_PGD_WEST || in->side == SB_PGD_SOUTH
                       ? 1.0 : -1.0;
      double un = sgn * in->u[dir], len = dir ? d->dx : d->dy;
      if (!(un > 0) || !(in->rho > 0))
        continue;
      /* global arithmetic, as the single-domain particles */
      double xn = d->p.origin[dir] + (sgn > 0 ? 0.0 : d->p.L[dir]);
      size_t off = dir ? b->i0 : b->j0;
      for (size_t c = in->first; c < in->first + in->count; c++) {
        double M = in->rho * un * len * dt;
        double P[2] = {M * in->u[0], M * in->u[1]};
        if ((st = sbi_lag_inject(&d->p, dir, xn, d->p.origin[1 - dir] +
                                 (double)(off + c) * len, len, M, P, dt,
                                 &d->moving, func)))
          return st;
        if (event(ev, in->side, 0, M, P[0], P[1]) || classify_moving(d, b))
          return SB_ENOMEM;
      }
    }
    return SB_SUCCESS;
  }
  for (int s = 0; s < 4; s++) {
    const double *f = b->e->bflux[s];
    if (b->nbr[s] < 0) { /* physical side: count what crossed it */
      for (size_t c = 0; c < b->e->nb[s]; c++) {
        const double *v = f + 3 * c;
        if (v[0] > 0 ? event(ev, s, 1, v[0], v[1], v[2])
                     : event(ev, s, 0, -v[0], -v[1], -v[2]))
          return SB_ENOMEM;
      }
      continue;
    }
    if (d->b[b->nbr[s]].kind != 'L')
      continue;
    int dir = s >= SB_PGD_SOUTH, hi = s == SB_PGD_EAST || s == SB_PGD_NORTH;
    size_t face = dir ? b->j0 + (hi ? d->nby : 0) : b->i0 + (hi ? d->nbx : 0);
    double xn = d->p.origin[dir] + (double)face * (dir ? d->dy : d->dx);
    double len = dir ? d->dx : d->dy;
    size_t off = dir ? b->i0 : b->j0;
    /* a face's outflow becomes particles once it carries at least the
     * mass of a cell at the vacuum threshold; smaller amounts wait (the
     * diffuse fringe of a jet would otherwise make many particles of
     * negligible weight), so nothing is lost */
    const double mmin = d->p.rho_floor * d->dx * d->dy;
    double *pe = b->pend[s];
    for (size_t c = 0; c < b->e->nb[s]; c++) {
      for (int m = 0; m < 3; m++)
        pe[3 * c + m] += f[3 * c + m];
      if (!(pe[3 * c] > mmin))
        continue;
      double P[2] = {pe[3 * c + 1], pe[3 * c + 2]};
      if ((st = sbi_lag_inject(&d->p, dir, xn, d->p.origin[1 - dir] +
                               (double)(off + c) * len, len, pe[3 * c], P,
                               dt, &d->moving, func)))
        return st;
      if (classify_moving(d, b))
        return SB_ENOMEM;
      pe[3 * c] = pe[3 * c + 1] = pe[3 * c + 2] = 0.0;
    }
  }
  return SB_SUCCESS;
}

/* Give a particle item to its block (of this part): a Lagrangian block's
 * list, or the Eulerian cell that contains it (absorbed). */
static int deliver(sb_pgd_dd *d, const double *it)
{
  dd_block *b = &d->b[(size_t)it[0]];
  const sb_pgd_particle q = {it[1], {it[2], it[3]}, {it[4], it[5]}};
  if (b->kind == 'L')
    return sbi_parts_push(&b->parts, &q);
  size_t i = sbi_locate1(&d->loc, 0, q.x[0]);
  size_t j = sbi_locate1(&d->loc, 1, q.x[1]);
  size_t c = sbi_pgd_idx(b->e, (long)(i - b->i0), (long)(j - b->j0));
  double iA = 1.0 / (d->dx * d->dy);
  b->e->rho[c] += q.w * iA;
  b->e->qx[c] += q.w * q.v[0] * iA;
  b->e->qy[c] += q.w * q.v[1] * iA;
  b->e->speed_ok = 0;
  b->e->empty = 0;
  return SB_SUCCESS;
}

/* ------------------------------------------------------ step phases */

/* Start a step of at most dt (already checked) that stops at t_end. */
static void begin(sb_pgd_dd *d, double dt, double t_end)
{
  double left = t_end - d->t;
  d->t_end = dt >= left * (1 - 1e-12) ? t_end : NAN;
  d->dt = isnan(d->t_end) ? dt : left;
  d->nst = sbi_pgd_nstages(d->p.scheme);
  for (size_t k = 0; k < d->nblocks; k++) {
    dd_block *b = &d->b[k];
    if (b->owner == d->part && b->kind == 'E') {
      sbi_pgd_drag(b->e, 0.5 * d->dt, 0);
      sbi_pgd_transport_begin(b->e);
    }
  }
  d->stage = 0;
  d->phase = SBI_DD_STAGES;
}

/* Stage d->stage, every other part's ghost cells already unpacked. */
static void stage(sb_pgd_dd *d)
{
  for (size_t k = 0; k < d->nblocks; k++)
    if (d->b[k].owner == d->part && d->b[k].kind == 'E') {
      sbi_pgd_fill_ghosts(d->b[k].e);
      exchange(d, &d->b[k]);
    }
  for (size_t k = 0; k < d->nblocks; k++)
    if (d->b[k].owner == d->part && d->b[k].kind == 'E')
      sbi_pgd_stage(d->b[k].e, d->dt, d->stage);
  d->stage++;
}

/* Drag, particle moves, injections: the step's items and events.
 * SB_ENOMEM (no message) or SB_ERANGE (message) where a particle's
 * velocity relative to the gas overflows: the particles are checked
 * before this phase changes anything, the injected ones as they are
 * made; messages named after func. */
static int move(sb_pgd_dd *d, const char *func)
{
  const double dt = d->dt;
  for (size_t k = 0; k < d->nblocks; k++) {
    const dd_block *b = &d->b[k];
    if (b->owner != d->part || b->kind != 'L')
      continue;
    const size_t bad = sbi_lag_rel_first_bad(&d->p, b->parts.q, b->parts.n);
    if (bad < b->parts.n)
      return sbi_lag_rel_error(&d->p, &b->parts.q[bad], func);
  }
  for (size_t k = 0; k < d->nblocks; k++) {
    dd_block *b = &d->b[k];
    if (b->owner == d->part && b->kind == 'E') {
      sbi_pgd_drag(b->e, 0.5 * dt, 1);
      b->e->t += dt;
      b->e->steps++;
    }
  }
  /* particles: move, keep those still in their block */
  double pe, pg;
  sbi_lag_coef(&d->p, dt, &pe, &pg);
  for (size_t k = 0; k < d->nblocks; k++) {
    dd_block *b = &d->b[k];
    if (b->owner != d->part || b->kind != 'L')
      continue;
    size_t w = 0;
    sbi_lag_move_all(&d->p, b->parts.q, b->parts.n, dt, pe, pg);
    for (size_t m = 0; m < b->parts.n; m++) {
      const sb_pgd_particle q = b->parts.q[m];
      /* still in the block: the cell rule decides, as in classify() */
      size_t i = sbi_locate1(&d->loc, 0, q.x[0]);
      size_t j = sbi_locate1(&d->loc, 1, q.x[1]);
      int stay = q.x[0] >= d->p.origin[0] && q.x[1] >= d->p.origin[1] &&
                 q.x[0] < d->p.origin[0] + d->p.L[0] &&
                 q.x[1] < d->p.origin[1] + d->p.L[1] &&
                 i - b->i0 < d->nbx && j - b->j0 < d->nby; /* unsigned */
      if (stay)
        b->parts.q[w++] = q;
      else if (classify(d, b, 0, q))
        return SB_ENOMEM;
    }
    b->parts.n = w;
  }
  for (size_t k = 0; k < d->nblocks; k++) {
    const int st = d->b[k].owner == d->part ? inject(d, &d->b[k], dt, func)
                                            : SB_SUCCESS;
    if (st)
      return st;
  }
  d->phase = SBI_DD_MOVED;
  return SB_SUCCESS;
}

/* Deliver the items bound for this part's blocks and replay the budget
 * events (the keeper), in the global order; close the step. */
static int end(sb_pgd_dd *d)
{
  int st = SB_SUCCESS;
  if (d->part == SBI_DD_KEEPER)
    for (int m = 0; m < 3; m++)
      for (size_t k = 0; k < d->nblocks; k++) {
        const sbi_dbuf *ev = &d->b[k].ev[m];
        for (size_t e = 0; e < ev->n; e += SBI_DD_EVENT) {
          const double *v = ev->v + e;
          sbi_budget_add(&d->bud, (int)v[0], (int)v[1], v[2], v[3], v[4]);
        }
      }
  for (int ph = 0; ph < 2; ph++)
    for (size_t k = 0; k < d->nblocks; k++) {
      const sbi_dbuf *sg = &d->b[k].seg[ph];
      for (size_t m = 0; !st && m < sg->n; m += SBI_DD_ITEM)
        if (d->b[(size_t)sg->v[m]].owner == d->part)
          st = deliver(d, sg->v + m);
    }
  for (size_t k = 0; k < d->nblocks; k++) {
    for (int m = 0; m < 2; m++)
      d->b[k].seg[m].n = 0;
    for (int m = 0; m < 3; m++)
      d->b[k].ev[m].n = 0;
  }
  d->t += d->dt;
  d->steps++;
  if (!isnan(d->t_end))
    d->t = d->t_end;
  d->phase = SBI_DD_IDLE;
  return st;
}

/* One step of a one-part run, dt checked. */
static int dd_step(sb_pgd_dd *d, double dt, double t_end)
{
  begin(d, dt, t_end);
  while (d->stage < d->nst)
    stage(d);
  int st = move(d, "sb_pgd_dd_step");
  if (st == SB_ERANGE)
    return st;
  if (st || end(d))
    return sbi_error(SB_ENOMEM, "sb_pgd_dd_step", "out of memory");
  return SB_SUCCESS;
}

static int one_part(const sb_pgd_dd *d, const char *func)
{
  if (!d)
    return sbi_error(SB_EINVAL, func, "NULL decomposition");
  if (d->nparts > 1)
    return sbi_error(SB_EINVAL, func, "part %d of %d: step with "
                     "sb_pgd_dd_begin ... sb_pgd_dd_end", d->part,
                     d->nparts);
  if (d->phase != SBI_DD_IDLE)
    return sbi_error(SB_EINVAL, func, "a step is under way");
  return SB_SUCCESS;
}

int sb_pgd_dd_step(sb_pgd_dd *d, double dt)
{
  int st = one_part(d, __func__);
  if (st)
    return st;
  double lim = sb_pgd_dd_dt(d);
  if (!(dt > 0) || !isfinite(dt) || dt > lim * (1 + 1e-12))
    return sbi_error(SB_EINVAL, __func__, "dt = %g: must be in (0, %g]", dt,
                     lim);
  return dd_step(d, dt, INFINITY);
}

int sb_pgd_dd_advance(sb_pgd_dd *d, double t_end, size_t *nsteps)
{
  int st = one_part(d, __func__);
  if (st)
    return st;
  if (!(t_end >= d->t) || !isfinite(t_end))
    return sbi_error(SB_EINVAL, __func__, "t_end = %g before t = %g", t_end,
                     d->t);
  size_t k = 0;
  while (d->t < t_end) {
    if ((st = dd_step(d, sb_pgd_dd_dt(d), t_end)))
      return st;
    k++;
  }
  if (nsteps)
    *nsteps = k;
  return SB_SUCCESS;
}

/* The public phases: checked, then the same functions. */
static int phase_is(const sb_pgd_dd *d, sbi_dd_phase ph, const char *func)
{
  static const char *names[] = {"sb_pgd_dd_begin", "sb_pgd_dd_stage",
                                "sb_pgd_dd_move"};
  if (!d)
    return sbi_error(SB_EINVAL, func, "NULL decomposition");
  if (d->phase != ph)
    return sbi_error(SB_EINVAL, func, "out of order: %s is next",
                     names[d->phase]);
  return SB_SUCCESS;
}

int sb_pgd_dd_begin(sb_pgd_dd *d, double dt, double t_end)
{
  int st = phase_is(d, SBI_DD_IDLE, __func__);
  if (st)
    return st;
  double lim = sb_pgd_dd_dt(d);
  if (!(dt > 0) || dt > lim * (1 + 1e-12) || (isinf(dt) && isinf(t_end)))
    return sbi_error(SB_EINVAL, __func__, "dt = %g: must be in (0, %g] "
                     "(the smallest sb_pgd_dd_dt of the parts; infinite "
                     "only with a finite t_end)", dt, lim);
  if (!(t_end > d->t))
    return sbi_error(SB_EINVAL, __func__, "t_end = %g: must be after t = "
                     "%g", t_end, d->t);
  begin(d, dt, t_end);
  return SB_SUCCESS;
}

int sb_pgd_dd_nstages(const sb_pgd_dd *d)
{
  return d ? sbi_pgd_nstages(d->p.scheme) : 0;
}

int sb_pgd_dd_stage(sb_pgd_dd *d)
{
  int st = phase_is(d, SBI_DD_STAGES, __func__);
  if (st)
    return st;
  if (d->stage >= d->nst)
    return sbi_error(SB_EINVAL, __func__, "all %d stages done: "
                     "sb_pgd_dd_move is next", d->nst);
  stage(d);
  return SB_SUCCESS;
}

int sb_pgd_dd_move(sb_pgd_dd *d)
{
  int st = phase_is(d, SBI_DD_STAGES, __func__);
  if (st)
    return st;
  if (d->stage < d->nst)
    return sbi_error(SB_EINVAL, __func__, "stage %d of %d not done",
                     d->stage, d->nst);
  st = move(d, __func__);
  if (st == SB_ERANGE)
    return st;
  if (st)
    return sbi_error(SB_ENOMEM, __func__, "out of memory");
  return SB_SUCCESS;
}

int sb_pgd_dd_end(sb_pgd_dd *d)
{
  int st = phase_is(d, SBI_DD_MOVED, __func__);
  if (st)
    return st;
  if (end(d))
    return sbi_error(SB_ENOMEM, __func__, "out of memory");
  return SB_SUCCESS;
}

/* ------------------------------------------------------ results */

int sb_pgd_dd_fields(const sb_pgd_dd *d, double *rho, double *qx, double *qy)
{
  if (!d)
    return sbi_error(SB_EINVAL, __func__, "NULL decomposition");
  const size_t nx = d->p.nx, n = nx * d->p.ny;
  const double iA = 1.0 / (d->dx * d->dy);
  double *f[3] = {rho, qx, qy};
  for (int m = 0; m < 3; m++)
    if (f[m])
      memset(f[m], 0, n * sizeof(double));
  for (size_t k = 0; k < d->nblocks; k++) {
    const dd_block *b = &d->b[k];
    if (!b->present)
      continue;
    if (b->kind == 'E') {
      for (size_t j = 0; j < d->nby; j++)
        for (size_t i = 0; i < d->nbx; i++) {
          size_t c = sbi_pgd_idx(b->e, (long)i, (long)j);
          size_t o = b->i0 + i + nx * (b->j0 + j);
          if (rho)
            rho[o] = b->e->rho[c];
          if (qx)
            qx[o] = b->e->qx[c];
          if (qy)
            qy[o] = b->e->qy[c];
        }
      continue;
    }
    for (size_t m = 0; m < b->parts.n; m++) {
      const sb_pgd_particle *q = &b->parts.q[m];
      size_t o = sbi_locate1(&d->loc, 0, q->x[0]) +
                 nx * sbi_locate1(&d->loc, 1, q->x[1]);
      if (rho)
        rho[o] += q->w * iA;
      if (qx)
        qx[o] += q->w * q->v[0] * iA;
      if (qy)
        qy[o] += q->w * q->v[1] * iA;
    }
  }
  return SB_SUCCESS;
}

void sb_pgd_dd_totals(const sb_pgd_dd *d, double tot[3])
{
  tot[0] = tot[1] = tot[2] = 0;
  for (size_t k = 0; k < d->nblocks; k++) {
    const dd_block *b = &d->b[k];
    if (!b->present)
      continue;
    if (b->kind == 'E') {
      double t[3];
      sb_pgd_totals(b->e, t);
      for (int m = 0; m < 3; m++)
        tot[m] += t[m];
      for (int s = 0; s < 4; s++)
        for (size_t c = 0; b->pend[s] && c < b->e->nb[s]; c++)
          for (int m = 0; m < 3; m++)
            tot[m] += b->pend[s][3 * c + m];
      continue;
    }
    for (size_t m = 0; m < b->parts.n; m++) {
      tot[0] += b->parts.q[m].w;
      tot[1] += b->parts.q[m].w * b->parts.q[m].v[0];
      tot[2] += b->parts.q[m].w * b->parts.q[m].v[1];
    }
  }
}

void sb_pgd_dd_boundary_totals(const sb_pgd_dd *d, double in[3],
                               double out[3])
{
  sbi_budget_get(&d->bud, -1, in, out);
}

void sb_pgd_dd_side_totals(const sb_pgd_dd *d, sb_pgd_side s, double in[3],
                           double out[3])
{
  sbi_budget_get(&d->bud, (int)s & 3, in, out);
}
