/* engine_detect.c — collision detection over a step and earliest-first
 * processing of the events.
 *
 * Relative motion over the step: particle k follows its chord
 * x0_k + s disp_k, s in [0, 1] (s = time / dt).  The separation
 * r(s) = dx0 + s dd (dd = disp_i - disp_j) touches the contact sphere
 * |r| = sigma where
 *     a s^2 + 2 b s + c = 0,  a = dd.dd,  b = dx0.dd,  c = dx0.dx0 - sigma^2
 * (Thomine 2008, eq 2 with beta = 2b; Mohaupt 2011, eq F.4 with
 * t = s dt).  For
 * c > 0 (apart at the start) a contact in the step needs b < 0
 * (approaching, Mohaupt 2011, Fig 3.3) and b^2 - a c >= 0; the first root is
 *     s = (-b - sqrt(b^2 - a c)) / a = c / (-b + sqrt(b^2 - a c)),
 * the second form free of cancellation (-b > 0).  The second root is the
 * time the spheres would separate again (Thomine 2008, §4.2).  Its §4.4
 * writes the 3-D root with +sqrt: a misprint (it is the exit time;
 * docs/errata.md).
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "common/internal.h"
#include "engine_internal.h"

void sbi_engine_make_pair(const sb_engine *e, size_t i, size_t j,
                          sb_engine_pair *p)
{
  p->i = i;
  p->j = j;
  for (int k = 0; k < 3; k++) {
    p->dx0[k] = k < e->par.dim
                    ? sbi_minimg(e->x0[3 * i + k] - e->x0[3 * j + k],
                                 e->par.L[k])
                    : 0.0;
    p->dd[k] = e->disp[3 * i + k] - e->disp[3 * j + k];
  }
  p->sigma = e->radius[i] + e->radius[j];
  p->dt = e->par.dt;
  p->t0 = e->t;
  if (e->lees || e->walled)  /* engine_lees.c */
    sbi_engine_boundary_fix_pair(e, &e->x0[3 * i], &e->x0[3 * j], 0.0, p);
}

static void quad(const sb_engine_pair *p, double *a, double *b, double *c)
{
  const double *x = p->dx0, *d = p->dd;
  *a = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
  *b = x[0] * d[0] + x[1] * d[1] + x[2] * d[2];
  *c = (x[0] * x[0] + x[1] * x[1] + x[2] * x[2]) - p->sigma * p->sigma;
}

int sb_engine_detect_ballistic(const sb_engine_pair *p, double *s)
{
  if (!p || !s) {
    sbi_error(SB_EINVAL, __func__, "NULL argument");
    return -1;
  }
  double a, b, c;
  quad(p, &a, &b, &c);
  if (c <= 0.0) {
    /* touching or overlapping at the start: a collision now if they
     * approach (a pair that just bounced has b >= 0).  Overlaps arise only
     * from events dropped in an earlier step (or an overlapping initial
     * state); this catches them up.  The pass-through outcome filters
     * such pairs out first (see sbi_engine_detect_and_process). */
    if (b < 0.0) {
      *s = 0.0;
      return 1;
    }
    return 0;
  }
  if (b >= 0.0 || a == 0.0)
    return 0;
  double disc = b * b - a * c;
  if (disc < 0.0)
    return 0;
  double r = c / (-b + sqrt(disc));
  if (r > 1.0)
    return 0;
  *s = r;
  return 1;
}

int sb_engine_detect_overlap(const sb_engine_pair *p, double *s)
{
  if (!p || !s) {
    sbi_error(SB_EINVAL, __func__, "NULL argument");
    return -1;
  }
  double e2 = 0.0;
  for (int k = 0; k < 3; k++) {
    double v = p->dx0[k] + p->dd[k];
    e2 += v * v;
  }
  if (!(e2 < p->sigma * p->sigma))
    return 0;
  /* overlapping at the end: contact time from the chords (Mohaupt
   * 2011, §3.1.1: the overlap test is completed by the exact collision
   * time of App. F); s = 0 if the pair already overlapped at the start */
  double a, b, c;
  quad(p, &a, &b, &c);
  if (c <= 0.0) {
    *s = 0.0;
    return 1;
  }
  double disc = b * b - a * c;
  double r = (b < 0.0 && disc >= 0.0) ? c / (-b + sqrt(disc)) : 1.0;
  *s = r > 1.0 ? 1.0 : r;
  return 1;
}

/* Overlapping (beyond touching) at the start of the step. */
static int overlapping(const sb_engine_pair *p)
{
  const double *x = p->dx0;
  double d2 = x[0] * x[0] + x[1] * x[1] + x[2] * x[2];
  return d2 < p->sigma * p->sigma * (1.0 - SB_ENGINE_TOUCH);
}

/* ------------------------------------------------------- event heap */

static int ev_less(const sbi_event *p, const sbi_event *q)
{
  if (p->s != q->s)
    return p->s < q->s;
  if (p->p.i != q->p.i)
    return p->p.i < q->p.i;
  return p->p.j < q->p.j;
}

static int heap_push(sb_engine *e, const sbi_event *ev)
{
  if (e->nev == e->capev) {
    size_t nc = e->capev ? 2 * e->capev : 64;
    sbi_event *ne = realloc(e->ev, nc * sizeof *ne);
    if (!ne)
      return sbi_error(SB_ENOMEM, "sb_engine_step", "out of memory");
    e->ev = ne;
    e->capev = nc;
  }
  size_t c = e->nev++;
  e->ev[c] = *ev;
  while (c > 0) {
    size_t up = (c - 1) / 2;
    if (!ev_less(&e->ev[c], &e->ev[up]))
      break;
    sbi_event t = e->ev[c];
    e->ev[c] = e->ev[up];
    e->ev[up] = t;
    c = up;
  }
  return SB_SUCCESS;
}

static sbi_event heap_pop(sb_engine *e)
{
  sbi_event top = e->ev[0];
  e->ev[0] = e->ev[--e->nev];
  size_t c = 0;
  for (;;) {
    size_t l = 2 * c + 1, r = l + 1, m = c;
    if (l < e->nev && ev_less(&e->ev[l], &e->ev[m]))
      m = l;
    if (r < e->nev && ev_less(&e->ev[r], &e->ev[m]))
      m = r;
    if (m == c)
      break;
    sbi_event t = e->ev[c];
    e->ev[c] = e->ev[m];
    e->ev[m] = t;
    c = m;
  }
  return top;
}

/* ------------------------------------------------------- detection */

/* The deterministic built-in detectors (no generator, no engine state
 * written): what detect_push runs for them, callable from any thread. */
static int detect_pure(const sb_engine *e, const sb_engine_pair *p,
                       double *s)
{
  if (e->obs_skip && e->obs_skip(e, p, e->obs_ctx))
    return 0;
  if (e->par.outcome == SB_OUTCOME_COUNT && !e->obs_take && overlapping(p))
    return 0;  /* pass-through: an overlap is not a new contact */
  return e->par.detect == SB_DETECT_BALLISTIC
             ? sb_engine_detect_ballistic(p, s)
             : sb_engine_detect_overlap(p, s);
}

static int push_hit(sb_engine *e, const sb_engine_pair *p, double t,
                    int hit, double s, sbi_event *ev);

/* Run the engine's detector on pair record p (interval [t, 1] of the
 * step, t = the record's start fraction); push an event if it hits. */
static int detect_push(sb_engine *e, const sb_engine_pair *p, double t)
{
  const sb_engine_detect det = e->par.detect;
  const int count_only = e->par.outcome == SB_OUTCOME_COUNT;
  double s = 0.0;
  int hit;
  sbi_event ev;
  ev.hasc = 0;
  if (det == SB_DETECT_LANGEVIN)  /* first contact, or every entry */
    return sbi_engine_langevin_record(e, p, t);
  if (det != SB_DETECT_CUSTOM) {
    if (e->obs_skip && e->obs_skip(e, p, e->obs_ctx))
      return SB_SUCCESS;
    if (count_only && !e->obs_take && overlapping(p))
      return SB_SUCCESS;  /* pass-through: an overlap is not a new contact */
  }
  if (det == SB_DETECT_BALLISTIC)
    hit = sb_engine_detect_ballistic(p, &s);
  else if (det == SB_DETECT_OVERLAP)
    hit = sb_engine_detect_overlap(p, &s);
  else
    hit = e->detect_fn(e, p, e->rng, e->detect_ctx, &s);
  if (hit == 1 && det != SB_DETECT_CUSTOM)  /* to the observer, if any */
    return sbi_engine_deliver(e, p, t, s, &ev);
  return push_hit(e, p, t, hit, s, &ev);
}

int sbi_engine_push_event(sb_engine *e, const sb_engine_pair *p, double t,
                          double s, sbi_event *ev)
{
  return push_hit(e, p, t, 1, s, ev);
}

void sbi_engine_set_observer(
    sb_engine *e,
    int (*skip)(const sb_engine *e, const sb_engine_pair *p, void *ctx),
    int (*take)(sb_engine *e, const sb_engine_pair *p, double s, void *ctx),
    void *ctx)
{
  e->obs_skip = skip;
  e->obs_take = take;
  e->obs_ctx = ctx;
}

int sbi_engine_deliver(sb_engine *e, const sb_engine_pair *p, double t,
                       double s, sbi_event *ev)
{
  if (!e->obs_take)
    return sbi_engine_push_event(e, p, t, s, ev);
  if (!(s >= 0.0 && s <= 1.0))
    return sbi_error(SB_EINVAL, "sb_engine_step",
                     "detector returned s = %g outside [0, 1]", s);
  e->contact = ev->hasc ? ev : NULL;
  const int st = e->obs_take(e, p, s, e->obs_ctx);
  e->contact = NULL;
  return st;
}

/* The detector's answer (hit, s) on p: push the event (ev: the
 * detector's contact states if ev->hasc). */
static int push_hit(sb_engine *e, const sb_engine_pair *p, double t,
                    int hit, double s, sbi_event *ev)
{
  if (hit < 0)
    return sbi_error(SB_EINVAL, "sb_engine_step",
                     "detector failed on pair (%zu, %zu)", p->i, p->j);
  if (!hit)
    return SB_SUCCESS;
  if (!(s >= 0.0 && s <= 1.0))
    return sbi_error(SB_EINVAL, "sb_engine_step",
                     "detector returned s = %g outside [0, 1]", s);
  if (!ev->hasc)
    ev->p = *p;
  ev->s_rec = s;
  ev->s = t + s * (1.0 - t);
  ev->vi = e->ver[p->i];
  ev->vj = e->ver[p->j];
  return heap_push(e, ev);
}

/* Particle k's current path piece: start point, velocity (per step
 * fraction) and start fraction; until an outcome stores one, the whole
 * step from x0 (the same numbers the stored piece would hold). */
static inline int piece_stored(const sb_engine *e, size_t k)
{
  return e->piece_at[k] == e->epoch;
}
static inline const double *piece_p(const sb_engine *e, size_t k)
{
  return piece_stored(e, k) ? &e->sub_p[3 * k] : &e->x0[3 * k];
}
static inline const double *piece_v(const sb_engine *e, size_t k)
{
  return piece_stored(e, k) ? &e->sub_v[3 * k] : &e->disp[3 * k];
}
static inline double piece_t(const sb_engine *e, size_t k)
{
  return piece_stored(e, k) ? e->sub_t[k] : 0.0;
}

/* Store k's piece before an outcome may change what the lazy piece reads
 * (the elastic outcome updates disp in place). */
static void keep_piece(sb_engine *e, size_t k)
{
  if (piece_stored(e, k))
    return;
  memcpy(&e->sub_p[3 * k], &e->x0[3 * k], 3 * sizeof(double));
  memcpy(&e->sub_v[3 * k], &e->disp[3 * k], 3 * sizeof(double));
  e->sub_t[k] = 0.0;
  e->piece_at[k] = e->epoch;
}

/* Position of particle k at step fraction s on its current path piece
 * (unwrapped, in the frame of x0_k). */
static void path_at(const sb_engine *e, size_t k, double s, double x[3])
{
  const double *p = piece_p(e, k), *v = piece_v(e, k), t = piece_t(e, k);
  for (int c = 0; c < 3; c++)
    x[c] = p[c] + (s - t) * v[c];
}

int sb_engine_position_at(const sb_engine *e, size_t k, double t,
                          double x[3])
{
  if (!e || !x || k >= e->n)
    return sbi_error(SB_EINVAL, __func__, "bad engine, particle or NULL");
  double f = (t - e->t) / e->par.dt;
  if (!e->in_step || !(f >= piece_t(e, k) - 1e-12 && f <= 1.0 + 1e-12))
    return sbi_error(SB_EINVAL, __func__,
                     "t = %g is not in the current piece of particle %zu's "
                     "step", t, k);
  path_at(e, k, f, x);
  return SB_SUCCESS;
}

/* Pair record of (a, b) over the rest [t, 1] of the step, from their
 * current path pieces (i = min(a, b)). */
static void make_subpair(const sb_engine *e, size_t a, size_t b, double t,
                         sb_engine_pair *p)
{
  size_t i = a < b ? a : b, j = a < b ? b : a;
  double xi[3], xj[3];
  path_at(e, i, t, xi);
  path_at(e, j, t, xj);
  const double f = 1.0 - t;
  p->i = i;
  p->j = j;
  const double *vi = piece_v(e, i), *vj = piece_v(e, j);
  for (int k = 0; k < 3; k++) {
    p->dx0[k] = k < e->par.dim ? sbi_minimg(xi[k] - xj[k], e->par.L[k])
                               : 0.0;
    p->dd[k] = (vi[k] - vj[k]) * f;
  }
  p->sigma = e->radius[i] + e->radius[j];
  p->dt = e->par.dt * f;
  p->t0 = e->t + t * e->par.dt;
  /* no image across a wall; across the sliding boundary the image
   * shifted by delta(t) and its velocity jump over the rest of the step,
   * as for the first detection (engine_lees.c) */
  if (e->walled || e->lees)
    sbi_engine_boundary_fix_pair(e, xi, xj, t, p);
}

double sbi_engine_pair_du(const sb_engine *e, const sb_engine_pair *p)
{
  if (!e->lees)
    return 0.0;
  if (e->contact)
    return e->contact->cdu;
  double yi, yj;
  if (e->in_step) {
    /* the record's pieces are current while its outcome runs */
    double xi[3], xj[3];
    path_at(e, p->i, e->in_outcome_t, xi);
    path_at(e, p->j, e->in_outcome_t, xj);
    yi = xi[1];
    yj = xj[1];
  } else {
    yi = e->x[3 * p->i + 1];
    yj = e->x[3 * p->j + 1];
  }
  return sbi_lees_n(e, yi - yj) * e->fluid_p[0] * e->par.L[1];
}

double sb_engine_pair_image_velocity(const sb_engine *e,
                                     const sb_engine_pair *p)
{
  if (!e || !p || p->i >= e->n || p->j >= e->n) {
    sbi_error(SB_EINVAL, __func__, "bad engine or pair");
    return NAN;
  }
  return sbi_engine_pair_du(e, p);
}

typedef struct {
  double t;     /* step fraction of the collision that changed a */
  size_t skip;  /* partner already re-examined from the other side */
} redetect_ctx;

static int redetect_one(sb_engine *e, size_t a, size_t k, void *vctx)
{
  const redetect_ctx *c = vctx;
  if (e->hit[k] == 2 || k == c->skip)
    return SB_SUCCESS;  /* removed in this step, or done */
  sb_engine_pair p;
  make_subpair(e, a, k, c->t, &p);
  e->nredetect++;
  return detect_push(e, &p, c->t);
}

/* Snapshot of a particle's end state, to see whether an outcome changed
 * it. */
typedef struct {
  double x[3], u[3];
  size_t sp;
} pstate;

static void snap(const sb_engine *e, size_t k, pstate *q)
{
  memcpy(q->x, &e->x[3 * k], sizeof q->x);
  memcpy(q->u, &e->u[3 * k], sizeof q->u);
  q->sp = e->species[k];
}

static int changed(const sb_engine *e, size_t k, const pstate *q)
{
  return memcmp(q->x, &e->x[3 * k], sizeof q->x) != 0 ||
         memcmp(q->u, &e->u[3 * k], sizeof q->u) != 0 ||
         q->sp != e->species[k];
}

/* Particle k's end changed by an outcome at step fraction t: a new path
 * piece from `from` (its position at t after the outcome) to its new end;
 * returns the new bound on the distance of its path from x0_k plus its
 * radius. */
static double new_piece(sb_engine *e, size_t k, double t,
                        const double *from)
{
  const double f = 1.0 - t;
  double len2 = 0.0, r0 = 0.0, r1 = 0.0;
  double pt[3], pe[3];  /* the piece's start and end */
  if (e->lees) {
    /* across the sliding boundary the nearest image is shifted along x
     * by delta at the time of the point: the start (at t) next to x0_k,
     * the end (at 1) next to the start (engine_lees.c) */
    sbi_engine_lees_near(e, &e->x0[3 * k], from, t, pt);
    sbi_engine_lees_near(e, pt, &e->x[3 * k], 1.0, pe);
  }
  for (int c = 0; c < 3; c++) {
    /* positions in the frame of x0_k (outcomes keep the end unwrapped; a
     * reinsertion or a declared position may be anywhere in the box) */
    double xe = e->x0[3 * k + c], xt = e->x0[3 * k + c];
    if (e->lees) {
      xt = pt[c];
      xe = pe[c];
    } else if (c < e->par.dim) {
      xe += sbi_minimg(e->x[3 * k + c] - e->x0[3 * k + c], e->par.L[c]);
      xt += sbi_minimg(from[c] - e->x0[3 * k + c], e->par.L[c]);
    }
    e->sub_v[3 * k + c] = f > 0.0 ? (xe - xt) / f : 0.0;
    e->sub_p[3 * k + c] = xt;
    len2 += (xe - xt) * (xe - xt);
    r0 += (xt - e->x0[3 * k + c]) * (xt - e->x0[3 * k + c]);
    r1 += (xe - e->x0[3 * k + c]) * (xe - e->x0[3 * k + c]);
  }
  e->sub_t[k] = t;
  e->piece_at[k] = e->epoch;
  e->ver[k]++;
  /* a noise-free Stokes path on a Langevin piece (started at t by
   * sbi_engine_langevin_continue) curves away from its chord */
  double bulge = 0.0;
  if (sbi_engine_det_bulge_on(e) && e->lp_t[k] == t)
    bulge = sbi_engine_det_bulge(e, k, &e->lp_u[3 * k],
                                 e->lp_x[3 * k + 1], f * e->par.dt);
  /* still inside the region the search covered around x0_k?  then widen
   * its reach (others' searches see it from the cells); else it goes to
   * the far list, checked against its piece directly */
  double r = sqrt(r0 > r1 ? r0 : r1) + bulge;
  if (!e->isfar[k]) {
    if (e->radius[k] + r <= e->grid.ext_max || !e->grid.valid) {
      if (r > e->dn[k])
        e->dn[k] = r;
    } else {
      e->isfar[k] = 1;
      e->far[e->nfar++] = k;
    }
  }
  return e->radius[k] + sqrt(len2) + bulge;  /* from the piece's start */
}

/* Where particle k is at step fraction t after the outcome: the position
 * the outcome declared (sb_engine_outcome_path), else for the elastic
 * outcome its old path at t (a bounce changes the velocity, not the
 * place), else its new end (a jump: reinsertion, or a custom outcome that
 * declared nothing). */
static void position_after(const sb_engine *e, size_t k, double t,
                           double x[3])
{
  for (int q = 0; q < e->ndeclared; q++)
    if (e->declared[q].k == k) {
      memcpy(x, e->declared[q].x, 3 * sizeof(double));
      return;
    }
  if (e->par.outcome == SB_OUTCOME_ELASTIC) {
    path_at(e, k, t, x);
    return;
  }
  memcpy(x, &e->x[3 * k], 3 * sizeof(double));
}

int sbi_engine_detect_and_process(sb_engine *e)
{
  e->nev = 0;
  e->ncand += e->npairs;
  const size_t n = e->n;
  for (size_t q = 0; q < e->nfar; q++)
    e->isfar[e->far[q]] = 0;
  e->nfar = 0;
  e->epoch++;  /* every path piece is the whole step (none stored) */
  if (e->par.detect == SB_DETECT_LANGEVIN || e->par.detect == SB_DETECT_CUSTOM)
    sbi_engine_langevin_begin(e);  /* a custom detector may call it */
  const size_t np = e->npairs;
  const int nt = sbi_engine_threads(&e->par);
  e->lredet = 0;
  if (e->par.detect == SB_DETECT_LANGEVIN && e->par.streams && nt > 1 &&
      np >= 256) {
    /* every record on its own stream: in parallel, pushed in order */
    int st = sbi_engine_langevin_first_pass(e, nt);
    if (st)
      return st;
  } else if ((e->par.detect == SB_DETECT_BALLISTIC ||
              e->par.detect == SB_DETECT_OVERLAP) && nt > 1 && np >= 256) {
    /* first pass of a deterministic detector on every thread; the events
     * are then pushed in pair order, as the serial loop below does */
    if (np > e->capdet) {
      signed char *h = realloc(e->dhit, np);
      if (h)
        e->dhit = h;
      double *sv = realloc(e->ds, np * sizeof *sv);
      if (sv)
        e->ds = sv;
      if (!h || !sv)
        return sbi_error(SB_ENOMEM, "sb_engine_step", "out of memory");
      e->capdet = np;
    }
    const sb_engine *ce = e;
    signed char *dh = e->dhit;
    double *ds = e->ds;
#ifdef _OPENMP
#pragma omp parallel for schedule(static) num_threads(nt)
#endif
    for (size_t q = 0; q < np; q++) {
      sb_engine_pair p;
      double s = 0.0;
      sbi_engine_make_pair(ce, ce->pairs[2 * q], ce->pairs[2 * q + 1], &p);
      dh[q] = (signed char)detect_pure(ce, &p, &s);
      ds[q] = s;
    }
    for (size_t q = 0; q < np; q++) {
      if (!dh[q])
        continue;
      sb_engine_pair p;
      sbi_event ev;
      ev.hasc = 0;
      sbi_engine_make_pair(e, e->pairs[2 * q], e->pairs[2 * q + 1], &p);
      int st = dh[q] == 1 ? sbi_engine_deliver(e, &p, 0.0, ds[q], &ev)
                          : push_hit(e, &p, 0.0, dh[q], ds[q], &ev);
      if (st)
        return st;
    }
  } else
    for (size_t q = 0; q < np; q++) {
      sb_engine_pair p;
      sbi_engine_make_pair(e, e->pairs[2 * q], e->pairs[2 * q + 1], &p);
      int st = detect_push(e, &p, 0.0);
      if (st)
        return st;
    }
  const int redetect = e->par.detect != SB_DETECT_CUSTOM || e->redetect;
  e->in_step = 1;
  /* a dense inelastic system can chatter (inelastic collapse): bound the
   * work of one step */
  uint64_t budget = 1000 * (uint64_t)(n + 1) + 16 * (uint64_t)e->npairs,
           used = 0;
  /* earliest first; an event whose particle changed its path since it was
   * detected is stale: with re-detection its pair was examined again on
   * the new path, otherwise it is dropped (and counted) */
  while (e->nev > 0) {
    sbi_event ev = heap_pop(e);
    const sb_engine_pair *p = &ev.p;
    const size_t i = p->i, j = p->j;
    if (e->hit[i] == 2 || e->hit[j] == 2)
      continue;  /* a partner was removed (merged) earlier in the step */
    if (ev.vi != e->ver[i] || ev.vj != e->ver[j]) {
      if (!redetect)
        e->dropped++;
      continue;
    }
    if (++used > budget) {
      e->in_step = 0;
      return sbi_error(SB_EMAXITER, "sb_engine_step",
                       "more than %llu collisions in one step (inelastic "
                       "collapse, or a step far too long for the density)",
                       (unsigned long long)budget);
    }
    pstate si, sj;
    snap(e, i, &si);
    snap(e, j, &sj);
    keep_piece(e, i);
    keep_piece(e, j);
    e->ndeclared = 0;
    e->in_outcome_t = ev.s;
    e->hit[i] = e->hit[i] ? e->hit[i] : 1;
    e->hit[j] = e->hit[j] ? e->hit[j] : 1;
    sbi_engine_count_collision(e, i, j);
    const size_t who[2] = {i, j};
    pstate sc[2];  /* Langevin: the states at contact the outcome sees */
    if (ev.hasc) {
      for (int q = 0; q < 2; q++) {
        memcpy(&e->x[3 * who[q]], ev.cx[q], 3 * sizeof(double));
        memcpy(&e->u[3 * who[q]], ev.cu[q], 3 * sizeof(double));
        snap(e, who[q], &sc[q]);
      }
      e->contact = &ev;
    }
    /* the re-detections' streams, from the ids before the outcome (a
     * reinsertion may give a particle a new id) */
    sbi_engine_langevin_redetect_key(e, &ev);
    /* the particle of lower id continues first (its new piece's draws):
     * the order in memory does not matter */
    const int first = e->id[i] < e->id[j] ? 0 : 1;
    int st = sbi_engine_apply_outcome(e, p, ev.s_rec);
    e->contact = NULL;
    if (st) {
      /* a built-in outcome's failure (a reinsertion's draw or flight, the
       * fluid callback): no half-made step, every particle back at its
       * start (a custom outcome's is left to its caller, as before) */
      if (e->par.outcome != SB_OUTCOME_CUSTOM) {
        sbi_engine_step_undo(e);
        e->in_step = 0;
      }
      return st;
    }
    const pstate *ref[2] = {ev.hasc ? &sc[0] : &si, ev.hasc ? &sc[1] : &sj};
    const int ch[2] = {e->hit[i] != 2 && changed(e, i, ref[0]),
                       e->hit[j] != 2 && changed(e, j, ref[1])};
    double ext[2] = {0.0, 0.0};
    for (int r = 0; r < 2; r++) {
      const int q = r ^ first;
      if (e->hit[who[q]] == 2) {
        e->ver[who[q]]++;  /* removed: its events are stale */
        continue;
      }
      double from[3];
      if (ev.hasc) {
        /* the state now is the one after the collision; continue from it
         * (then the chord piece runs from there to the new end) */
        memcpy(from, &e->x[3 * who[q]], sizeof from);
        const pstate *end = q ? &sj : &si;
        st = sbi_engine_langevin_continue(e, who[q], &ev, ch[q], end->x,
                                          end->u);
        if (st) {  /* the step undone (engine_langevin.c): not in it */
          e->in_step = 0;
          return st;
        }
      } else if (ch[q])
        position_after(e, who[q], ev.s, from);
      if (ch[q])
        ext[q] = new_piece(e, who[q], ev.s, from);
    }
    if (!redetect)
      continue;
    for (int q = 0; q < 2; q++) {
      if (!ch[q])
        continue;
      redetect_ctx rc = {ev.s, (q == 1 && ch[0]) ? who[0] : (size_t)-1};
      st = sbi_engine_partners(e, who[q], &e->sub_p[3 * who[q]], ext[q],
                               ev.s, redetect_one, &rc);
      if (st) {
        e->in_step = 0;
        return st;
      }
    }
  }
  e->in_step = 0;
  return SB_SUCCESS;
}
