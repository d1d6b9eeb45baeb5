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
  if (!p || !s)
    return -1;
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
  if (!p || !s)
    return -1;
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

static int ev_cmp(const void *a, const void *b)
{
  const sbi_event *p = a, *q = b;
  if (p->s != q->s)
    return p->s < q->s ? -1 : 1;
  if (p->p.i != q->p.i)
    return p->p.i < q->p.i ? -1 : 1;
  return (p->p.j > q->p.j) - (p->p.j < q->p.j);
}

static int push_event(sb_engine *e, const sb_engine_pair *p, double s)
{
  if (e->nev == e->capev) {
    size_t nc = e->capev ? 2 * e->capev : 64;
    sbi_event *ne = realloc(e->ev, nc * sizeof *ne);
    if (!ne)
      return sbi_error(SB_ENOMEM, "sb_engine_step", "out of memory");
    e->ev = ne;
    e->capev = nc;
  }
  e->ev[e->nev].s = s;
  e->ev[e->nev].p = *p;
  e->nev++;
  return SB_SUCCESS;
}

int sbi_engine_detect_and_process(sb_engine *e)
{
  e->nev = 0;
  e->ncand += e->npairs;
  const sb_engine_detect det = e->par.detect;
  const int count_only = e->par.outcome == SB_OUTCOME_COUNT;
  for (size_t q = 0; q < e->npairs; q++) {
    sb_engine_pair p;
    sbi_engine_make_pair(e, e->pairs[2 * q], e->pairs[2 * q + 1], &p);
    double s = 0.0;
    int hit;
    if (count_only && det != SB_DETECT_CUSTOM && overlapping(&p))
      continue;  /* pass-through: an overlap is not a new contact */
    if (det == SB_DETECT_BALLISTIC)
      hit = sb_engine_detect_ballistic(&p, &s);
    else if (det == SB_DETECT_OVERLAP)
      hit = sb_engine_detect_overlap(&p, &s);
    else
      hit = e->detect_fn(e, &p, e->rng, e->detect_ctx, &s);
    if (hit < 0)
      return sbi_error(SB_EINVAL, "sb_engine_step",
                       "detector failed on pair (%zu, %zu)", p.i, p.j);
    if (hit) {
      if (!(s >= 0.0 && s <= 1.0))
        return sbi_error(SB_EINVAL, "sb_engine_step",
                         "detector returned s = %g outside [0, 1]", s);
      int st = push_event(e, &p, s);
      if (st)
        return st;
    }
  }
  if (e->nev > 1)
    qsort(e->ev, e->nev, sizeof *e->ev, ev_cmp);
  /* earliest first; one collision per particle per step */
  for (size_t k = 0; k < e->nev; k++) {
    const sb_engine_pair *p = &e->ev[k].p;
    if (e->hit[p->i] || e->hit[p->j]) {
      e->dropped++;
      continue;
    }
    e->hit[p->i] = e->hit[p->j] = 1;
    sbi_engine_count_collision(e, p->i, p->j);
    int st = sbi_engine_apply_outcome(e, p, e->ev[k].s);
    if (st)
      return st;
  }
  return SB_SUCCESS;
}
