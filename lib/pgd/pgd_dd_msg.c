/* pgd_dd_msg.c — what the parts of a decomposition send each other
 * (sb_pgd_dd_pack, sb_pgd_dd_unpack): ghost cells at every stage, the
 * step's migrating particles and budget events, and block states for the
 * output.  Messages are flat arrays of doubles (indices and counts are
 * exact integers in them); the caller moves them (MPI in the command,
 * memcpy in the tests) and never reads them. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <smolbridge/pgd.h>
#include "common/internal.h"
#include "pgd_internal.h"
#include "pgd_dd_internal.h"

/* A writer that counts (buf NULL) or writes. */
typedef struct {
  double *buf;
  size_t n;
} writer;

static void put(writer *w, double x)
{
  if (w->buf)
    w->buf[w->n] = x;
  w->n++;
}

static void put_n(writer *w, const double *x, size_t k)
{
  if (w->buf)
    memcpy(w->buf + w->n, x, k * sizeof *x);
  w->n += k;
}

static size_t side_len(const sb_pgd_dd *d, int s)
{
  return s < 2 ? d->nby : d->nbx;
}

/* Ghost cells of part `to`'s Eulerian blocks from this part's blocks: by
 * receiving block, side, position along the side, layer. */
static void halo(const sb_pgd_dd *d, int to, writer *w)
{
  const long nx = (long)d->nbx, ny = (long)d->nby;
  for (size_t k = 0; k < d->nblocks; k++) {
    const dd_block *b = &d->b[k];
    if (b->owner != to)
      continue;
    for (int s = 0; s < 4; s++) {
      int n = sbi_dd_euler_nbr(d, b, s);
      if (n < 0 || d->b[n].owner != d->part)
        continue;
      const struct sb_pgd *o = d->b[n].e;
      for (long c = 0; c < (long)side_len(d, s); c++)
        for (long l = 1; l <= SBI_PGD_G; l++) {
          size_t gh, src;
          sbi_dd_halo_idx(o, nx, ny, s, c, l, &gh, &src);
          const double v[3] = {o->rho[src], o->qx[src], o->qy[src]};
          put_n(w, v, 3);
        }
    }
  }
}

/* The step's items bound for part `to` by (left, injected), source block;
 * for the keeper also every budget event: records tag, block, count. */
static void migrate(const sb_pgd_dd *d, int to, writer *w)
{
  for (int ph = 0; ph < 2; ph++)
    for (size_t k = 0; k < d->nblocks; k++) {
      const sbi_dbuf *sg = &d->b[k].seg[ph];
      if (d->b[k].owner != d->part)
        continue;
      size_t cnt = 0;
      for (size_t m = 0; m < sg->n; m += SBI_DD_ITEM)
        cnt += d->b[(size_t)sg->v[m]].owner == to;
      if (!cnt)
        continue;
      put(w, ph);
      put(w, (double)k);
      put(w, (double)cnt);
      for (size_t m = 0; m < sg->n; m += SBI_DD_ITEM)
        if (d->b[(size_t)sg->v[m]].owner == to)
          put_n(w, sg->v + m, SBI_DD_ITEM);
    }
  if (to != SBI_DD_KEEPER)
    return;
  for (int e = 0; e < 3; e++)
    for (size_t k = 0; k < d->nblocks; k++) {
      const sbi_dbuf *ev = &d->b[k].ev[e];
      if (d->b[k].owner != d->part || !ev->n)
        continue;
      put(w, 2 + e);
      put(w, (double)k);
      put(w, (double)(ev->n / SBI_DD_EVENT));
      put_n(w, ev->v, ev->n);
    }
}

/* This part's blocks: index, then the interior cells (rho, qx, qy) and
 * pending fluxes of an Eulerian block, or the count and particles (w, x,
 * y, vx, vy) of a Lagrangian one. */
static void state(const sb_pgd_dd *d, writer *w)
{
  for (size_t k = 0; k < d->nblocks; k++) {
    const dd_block *b = &d->b[k];
    if (b->owner != d->part)
      continue;
    put(w, (double)k);
    if (b->kind == 'E') {
      for (size_t j = 0; j < d->nby; j++)
        for (size_t i = 0; i < d->nbx; i++) {
          size_t c = sbi_pgd_idx(b->e, (long)i, (long)j);
          const double v[3] = {b->e->rho[c], b->e->qx[c], b->e->qy[c]};
          put_n(w, v, 3);
        }
      for (int s = 0; s < 4; s++)
        if (b->pend[s])
          put_n(w, b->pend[s], 3 * b->e->nb[s]);
      continue;
    }
    put(w, (double)b->parts.n);
    for (size_t m = 0; m < b->parts.n; m++) {
      const sb_pgd_particle *q = &b->parts.q[m];
      const double v[5] = {q->w, q->x[0], q->x[1], q->v[0], q->v[1]};
      put_n(w, v, 5);
    }
  }
}

static const char *msg_name(sb_pgd_dd_msg m)
{
  return m == SB_PGD_DD_HALO ? "halo" : m == SB_PGD_DD_MIGRATE ? "migrate"
                                                               : "state";
}

/* Whether message m may be packed or unpacked now. */
static int msg_ready(const sb_pgd_dd *d, sb_pgd_dd_msg m, int peer,
                     const char *func)
{
  if (!d)
    return sbi_error(SB_EINVAL, func, "NULL decomposition");
  if (peer < 0 || peer >= d->nparts)
    return sbi_error(SB_EINVAL, func, "part %d: must be in [0, %d)", peer,
                     d->nparts);
  int ok = m == SB_PGD_DD_HALO
               ? d->phase == SBI_DD_STAGES && d->stage < d->nst
           : m == SB_PGD_DD_MIGRATE ? d->phase == SBI_DD_MOVED
           : m == SB_PGD_DD_STATE   ? d->phase == SBI_DD_IDLE
                                    : -1;
  if (ok < 0)
    return sbi_error(SB_EINVAL, func, "message kind %d", (int)m);
  if (!ok)
    return sbi_error(SB_EINVAL, func, "no %s message at this point of the "
                     "step (halo: before each sb_pgd_dd_stage; migrate: "
                     "between sb_pgd_dd_move and sb_pgd_dd_end; state: "
                     "between steps)", msg_name(m));
  return SB_SUCCESS;
}

int sb_pgd_dd_pack(const sb_pgd_dd *d, sb_pgd_dd_msg m, int to, double *buf,
                   size_t cap, size_t *n)
{
  int st = msg_ready(d, m, to, __func__);
  if (st)
    return st;
  writer w = {NULL, 0};
  for (int pass = buf ? 0 : 1; pass < 2; pass++) {
    w.n = 0;
    if (to == d->part)
      ; /* nothing to send to oneself */
    else if (m == SB_PGD_DD_HALO)
      halo(d, to, &w);
    else if (m == SB_PGD_DD_MIGRATE)
      migrate(d, to, &w);
    else
      state(d, &w);
    if (pass == 0) {
      if (w.n > cap)
        return sbi_error(SB_EINVAL, __func__, "%s message of %zu values: "
                         "buffer of %zu", msg_name(m), w.n, cap);
      w.buf = buf;
    }
  }
  if (n)
    *n = w.n;
  return SB_SUCCESS;
}

/* ------------------------------------------------------ unpacking */

static int malformed(sb_pgd_dd_msg m, int from, const char *why)
{
  return sbi_error(SB_EFORMAT, "sb_pgd_dd_unpack", "%s message from part "
                   "%d: %s", msg_name(m), from, why);
}

/* x is an integer in [0, lim) */
static int index_ok(double x, size_t lim)
{
  return x >= 0 && x < (double)lim && x == floor(x);
}

static int unpack_halo(sb_pgd_dd *d, int from, const double *v, size_t n)
{
  const long nx = (long)d->nbx, ny = (long)d->nby;
  size_t want = 0;
  for (int pass = 0; pass < 2; pass++) {
    size_t pos = 0;
    for (size_t k = 0; k < d->nblocks; k++) {
      dd_block *b = &d->b[k];
      if (b->owner != d->part)
        continue;
      for (int s = 0; s < 4; s++) {
        int o = sbi_dd_euler_nbr(d, b, s);
        if (o < 0 || d->b[o].owner != from)
          continue;
        if (pass == 0) {
          want += 3 * SBI_PGD_G * side_len(d, s);
          continue;
        }
        struct sb_pgd *g = b->e;
        for (long c = 0; c < (long)side_len(d, s); c++)
          for (long l = 1; l <= SBI_PGD_G; l++, pos += 3) {
            size_t gh, src;
            sbi_dd_halo_idx(g, nx, ny, s, c, l, &gh, &src);
            g->rho[gh] = v[pos];
            g->qx[gh] = v[pos + 1];
            g->qy[gh] = v[pos + 2];
          }
      }
    }
    if (pass == 0 && want != n)
      return malformed(SB_PGD_DD_HALO, from, "wrong length");
  }
  return SB_SUCCESS;
}

/* An item must name a block of this part that contains its position. */
static int item_ok(const sb_pgd_dd *d, const double *it)
{
  if (!index_ok(it[0], d->nblocks))
    return 0;
  const dd_block *b = &d->b[(size_t)it[0]];
  for (int m = 1; m < SBI_DD_ITEM; m++)
    if (!isfinite(it[m]))
      return 0;
  size_t i = sbi_locate1(&d->loc, 0, it[2]);
  size_t j = sbi_locate1(&d->loc, 1, it[3]);
  return b->owner == d->part && i - b->i0 < d->nbx && j - b->j0 < d->nby;
}

static int unpack_migrate(sb_pgd_dd *d, int from, const double *v,
                          size_t n)
{
  const sb_pgd_dd_msg M = SB_PGD_DD_MIGRATE;
  for (size_t pos = 0; pos < n;) {
    if (n - pos < 3 || !index_ok(v[pos], 5) ||
        !index_ok(v[pos + 1], d->nblocks) || !(v[pos + 2] >= 1) ||
        v[pos + 2] != floor(v[pos + 2]))
      return malformed(M, from, "bad record header");
    int tag = (int)v[pos];
    dd_block *b = &d->b[(size_t)v[pos + 1]];
    size_t wid = tag < 2 ? SBI_DD_ITEM : SBI_DD_EVENT;
    if (b->owner != from)
      return malformed(M, from, "a block of another part");
    if (v[pos + 2] > (double)((n - pos - 3) / wid))
      return malformed(M, from, "truncated");
    size_t len = (size_t)v[pos + 2] * wid;
    const double *r = v + pos + 3;
    if (tag >= 2 && d->part != SBI_DD_KEEPER)
      return malformed(M, from, "budget events for a part that does not "
                       "keep the budget");
    for (size_t m = 0; m < len; m += wid)
      if (tag < 2 ? !item_ok(d, r + m)
                  : !index_ok(r[m], 4) || !index_ok(r[m + 1], 2))
        return malformed(M, from, tag < 2 ? "a particle outside its block"
                                          : "bad budget event");
    if (sbi_dbuf_push(tag < 2 ? &b->seg[tag] : &b->ev[tag - 2], r, len))
      return sbi_error(SB_ENOMEM, "sb_pgd_dd_unpack", "out of memory");
    pos += 3 + len;
  }
  return SB_SUCCESS;
}

static int unpack_state(sb_pgd_dd *d, int from, const double *v, size_t n)
{
  const sb_pgd_dd_msg M = SB_PGD_DD_STATE;
  const size_t cells = d->nbx * d->nby;
  for (size_t pos = 0; pos < n;) {
    if (!index_ok(v[pos], d->nblocks))
      return malformed(M, from, "bad block index");
    dd_block *b = &d->b[(size_t)v[pos++]];
    if (b->owner != from)
      return malformed(M, from, "a block of another part");
    if (b->kind == 'L') {
      if (pos == n || !(v[pos] >= 0) || v[pos] != floor(v[pos]) ||
          v[pos] > (double)((n - pos - 1) / 5))
        return malformed(M, from, "bad particle count");
      size_t cnt = (size_t)v[pos++];
      b->parts.n = 0;
      for (size_t m = 0; m < cnt; m++, pos += 5) {
        const sb_pgd_particle q = {v[pos], {v[pos + 1], v[pos + 2]},
                                   {v[pos + 3], v[pos + 4]}};
        if (sbi_parts_push(&b->parts, &q))
          return sbi_error(SB_ENOMEM, "sb_pgd_dd_unpack", "out of memory");
      }
      b->present = 1;
      continue;
    }
    if (!b->e && sbi_dd_block_alloc(d, b))
      return SB_ENOMEM;
    size_t len = 3 * cells;
    for (int s = 0; s < 4; s++)
      if (b->pend[s])
        len += 3 * b->e->nb[s];
    if (n - pos < len)
      return malformed(M, from, "truncated");
    for (size_t j = 0; j < d->nby; j++)
      for (size_t i = 0; i < d->nbx; i++, pos += 3) {
        size_t c = sbi_pgd_idx(b->e, (long)i, (long)j);
        b->e->rho[c] = v[pos];
        b->e->qx[c] = v[pos + 1];
        b->e->qy[c] = v[pos + 2];
      }
    for (int s = 0; s < 4; s++)
      if (b->pend[s]) {
        memcpy(b->pend[s], v + pos, 3 * b->e->nb[s] * sizeof *v);
        pos += 3 * b->e->nb[s];
      }
    b->present = 1;
  }
  return SB_SUCCESS;
}

int sb_pgd_dd_unpack(sb_pgd_dd *d, sb_pgd_dd_msg m, int from,
                     const double *buf, size_t n)
{
  int st = msg_ready(d, m, from, __func__);
  if (st)
    return st;
  if (n && !buf)
    return sbi_error(SB_EINVAL, __func__, "NULL buffer of %zu values", n);
  if (from == d->part)
    return n ? malformed(m, from, "a message to oneself") : SB_SUCCESS;
  return m == SB_PGD_DD_HALO      ? unpack_halo(d, from, buf, n)
         : m == SB_PGD_DD_MIGRATE ? unpack_migrate(d, from, buf, n)
                                  : unpack_state(d, from, buf, n);
}
