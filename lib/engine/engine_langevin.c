/* engine_langevin.c — the Langevin-bridge detector of the engine
 * (SB_DETECT_LANGEVIN): exact conditional sampling of a pair's first
 * contact between the states the exact Langevin step produced
 * (<smolbridge/langevin_hit.h>), its neighbour reach, and the Langevin path
 * pieces that carry particles through collisions inside a step.
 *
 * Pieces.  Over a step particle k is known at the start (x0, u0) and the
 * end (x, u); its path in between is the Langevin bridge.  A collision at
 * step fraction t gives both partners' states at t (drawn by the
 * sampler); what happens after depends on the outcome: a partner the
 * outcome leaves unchanged continues on the bridge from its contact state
 * to its end (exact by the Markov property), a changed one (bounce,
 * merge, reinsertion) continues by a fresh exact Langevin step from its
 * new state (in the Lees-Edwards shear the exact step of the linear field
 * from the piece's start: mean correction and shear noise, engine_lees.c).
 * A record that starts inside the step (re-detection after a
 * collision) needs both states at its start: a partner that is not at the
 * start of its piece is drawn from its piece's bridge at that time.  Each
 * pair's interior path is drawn independently of the other pairs' (as for
 * every pairwise detector), which is exact for dilute suspensions, where
 * a particle rarely has two partners close at once.
 *
 * Pass-through (SB_OUTCOME_COUNT).  A collision changes nobody, so a pair
 * may leave contact and enter again inside the same step: its record
 * gets one event per entry of its path (sb_langevin_hitter_sample_all:
 * after an entry the walk looks for the exit, then for the next entry),
 * and a pair in contact at the start of the step is followed to its exit
 * first.  Every entry is then counted, at any dt, as the flux through
 * the contact sphere counts them.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_randist.h>

#include "common/internal.h"
#include "engine_internal.h"

void sb_engine_langevin_params_default(sb_engine_langevin_params *p)
{
  if (!p) {
    sbi_error(SB_EINVAL, __func__, "params is NULL");
    return;
  }
  p->eps = 1e-6;
  p->xtol = 1e-6;
  p->tol = 1e-9;
}

static sb_langevin_hitter *new_hitter(const sb_engine *e,
                                      const sb_engine_langevin_params *p)
{
  sb_langevin_hit_params hp;
  sb_langevin_hit_params_default(&hp);
  hp.dim = e->par.dim;
  hp.eps = p->eps;
  hp.xtol = p->xtol;
  return sb_langevin_hitter_alloc(&hp);
}

sb_langevin_hitter *sbi_engine_langevin_hitter(const sb_engine *e)
{
  return new_hitter(e, &e->lpar);
}

int sbi_engine_langevin_init(sb_engine *e)
{
  sb_engine_langevin_params_default(&e->lpar);
  e->lreach = NAN;
  e->lh = new_hitter(e, &e->lpar);
  e->lacc = calloc(1, sizeof *e->lacc);
  return e->lh && e->lacc ? SB_SUCCESS : SB_ENOMEM;
}

void sbi_engine_langevin_fold(sb_langevin_hit_stats *acc,
                              const sb_langevin_hit_stats *one,
                              int with_mass)
{
  acc->calls += one->calls;
  acc->hits += one->hits;
  acc->nodes += one->nodes;
  acc->pruned += one->pruned;
  acc->leaves += one->leaves;
  acc->grazing += one->grazing;
  acc->deep += one->deep;
  acc->audit_hits += one->audit_hits;
  if (one->depth_max > acc->depth_max)
    acc->depth_max = one->depth_max;
  if (with_mass)
    acc->pruned_mass += one->pruned_mass;
}

/* The counters of lh's calls since its reset, added to acc. */
static void hit_done(sb_langevin_hitter *lh, sb_langevin_hit_stats *acc)
{
  sb_langevin_hit_stats one;
  if (sb_langevin_hitter_stats(lh, &one) == SB_SUCCESS)
    sbi_engine_langevin_fold(acc, &one, 1);
}

void sbi_engine_langevin_done(const sb_engine *e, sb_langevin_hitter *lh)
{
  hit_done(lh, e->lacc);
}

int sb_engine_set_langevin(sb_engine *e, const sb_engine_langevin_params *p)
{
  if (!e || !p || !(p->eps > 0.0 && p->eps <= 0.1) ||
      !(p->xtol > 0.0 && p->xtol <= 0.01) || !(p->tol > 0.0 && p->tol < 1.0))
    return sbi_error(SB_EINVAL, __func__,
                     "eps in (0, 0.1], xtol in (0, 0.01], tol in (0, 1)");
  sb_langevin_hitter *h = new_hitter(e, p);
  if (!h)
    return sbi_error(SB_ENOMEM, __func__, "out of memory");
  sbi_engine_langevin_slots_free(e);  /* their hitters had the old ones */
  sb_langevin_hitter_free(e->lh);
  e->lh = h;
  e->lpar = *p;
  e->lreach = NAN;
  return SB_SUCCESS;
}

int sb_engine_get_langevin(const sb_engine *e, sb_engine_langevin_params *p)
{
  if (!e || !p)
    return sbi_error(SB_EINVAL, __func__, "NULL argument");
  *p = e->lpar;
  return SB_SUCCESS;
}

int sb_engine_langevin_stats(const sb_engine *e, sb_langevin_hit_stats *st)
{
  if (!e || !st || !e->lacc)
    return sbi_error(SB_EINVAL, __func__, "NULL argument");
  /* every call's counters, the parallel pass's included, were added in
   * a fixed order (sbi_engine_langevin_fold) */
  *st = *e->lacc;
  return SB_SUCCESS;
}

void sbi_engine_langevin_reset_stats(sb_engine *e)
{
  memset(e->lacc, 0, sizeof *e->lacc);
}

/* ------------------------------------------------------------ reach */

/* Per-step position variance of species sp (0 for free flight). */
static double spread(const sb_engine_species *s, double dt)
{
  return isinf(s->tau) ? 0.0 : sb_langevin_var_x(s->tau, s->B, dt);
}

double sb_engine_langevin_reach(sb_engine *e)
{
  if (!e) {
    sbi_error(SB_EINVAL, __func__, "engine is NULL");
    return NAN;
  }
  if (e->n < 2 || e->nspec == 0)
    return 0.0;
  if (!isnan(e->lreach) && e->lreach_dt == e->par.dt &&
      e->lreach_nspec == e->nspec && e->n <= e->lreach_n)
    return e->lreach;
  /* the (at most) 8 species that spread most in a step */
  size_t pick[8], np = 0;
  for (size_t sp = 0; sp < e->nspec; sp++) {
    double v = spread(&e->spec[sp], e->par.dt);
    if (np < 8)
      pick[np++] = sp;
    else {
      size_t lo = 0;
      for (size_t q = 1; q < np; q++)
        if (spread(&e->spec[pick[q]], e->par.dt) <
            spread(&e->spec[pick[lo]], e->par.dt))
          lo = q;
      if (v > spread(&e->spec[pick[lo]], e->par.dt))
        pick[lo] = sp;
    }
  }
  double V = e->par.L[0] * e->par.L[1] * (e->par.dim == 3 ? e->par.L[2] : 1.0);
  double n = (double)(e->n - 1) / V, R = 2.0 * e->rmax, rho = 0.0;
  for (size_t a = 0; a < np; a++)
    for (size_t b = a; b < np; b++) {
      const sb_engine_species *sa = &e->spec[pick[a]], *sb = &e->spec[pick[b]];
      double r = sb_langevin_reach(e->par.dim, n, R, sa->tau,
                                   isinf(sa->tau) ? 0.0 : sa->B, sb->tau,
                                   isinf(sb->tau) ? 0.0 : sb->B, e->par.dt,
                                   e->lpar.tol);
      if (isnan(r))
        return NAN;
      if (r > rho)
        rho = r;
    }
  e->lreach = rho;
  e->lreach_dt = e->par.dt;
  e->lreach_n = e->n;
  e->lreach_nspec = e->nspec;
  return rho;
}

/* ------------------------------------------------------------ pieces */

void sbi_engine_langevin_begin(sb_engine *e)
{
  memcpy(e->lp_x, e->x0, 3 * e->n * sizeof(double));
  memcpy(e->lp_u, e->u0, 3 * e->n * sizeof(double));
  for (size_t k = 0; k < e->n; k++)
    e->lp_t[k] = 0.0;
}

/* The shear rate of particle k's exact bridge: G for a Stokes species
 * in the Lees-Edwards shear (its transport is exact in the linear field,
 * engine_lees.c; without noise its path is the exact deterministic map),
 * else 0 (the uniform-flow bridge). */
static double shear_rate(const sb_engine *e, size_t k)
{
  const sb_engine_species *sp = &e->spec[e->species[k]];
  const double G = e->fluid_p[0];
  if (e->lees && e->fluid == SB_FLUID_SHEAR && G != 0.0 &&
      !isinf(sp->tau) &&
      !(e->species[k] < e->nsfl &&
        e->sfl[e->species[k]].drag != SB_DRAG_STOKES))
    return G;
  return 0.0;
}

/* The constant part c_x of the fluid velocity (G y + c_x) that particle k
 * sees in the shear (the field G (y - L_y/2) plus its settling
 * velocity). */
static double shear_cx(const sb_engine *e, size_t k, double G)
{
  return (sbi_engine_w(e, k, 0) - e->us[3 * k]) - G * 0.5 * e->par.L[1];
}

int sbi_engine_det_bulge_on(const sb_engine *e)
{
  if (e->par.detect != SB_DETECT_LANGEVIN &&
      e->par.detect != SB_DETECT_CUSTOM)
    return 0;
  for (size_t sp = 0; sp < e->nspec; sp++)
    if (!isinf(e->spec[sp].tau) && e->spec[sp].B == 0.0)
      return 1;
  return 0;
}

/* The path's deviation from its chord over [0, h] is
 * F(s) = int_0^s (u - mean u) = s (1 - s/h) (mean of u before s - mean
 * after), at most (h/4) times the range of u over the piece, taken per
 * component: u relaxes monotonically to the fluid velocity w, a range
 * |u_a - w| (1 - e^{-h/tau}); in the shear u_x also follows G y(t), whose
 * response adds |G| tau (|u_y - w_y| Bv + |w_y| C) (engine_lees.c). */
double sbi_engine_det_bulge(const sb_engine *e, size_t k, const double *ua,
                            double ya, double h)
{
  const sb_engine_species *sp = &e->spec[e->species[k]];
  if (isinf(sp->tau) || sp->B > 0.0 || !(h > 0.0))
    return 0.0;
  double tau, rw[3];  /* a nonlinear drag: its step's rate */
  sbi_engine_relax(e, k, &tau, rw);
  const double a = -expm1(-h / tau);
  const double G = shear_rate(e, k);
  double r2 = 0.0;
  for (int c = 0; c < e->par.dim; c++) {
    double w = rw[c], r;
    if (c == 0 && G != 0.0) {
      double cs[4];
      sb_langevin_shear_mean_coefs(h / tau, cs);
      const double wy = sbi_engine_w(e, k, 1);
      w = shear_cx(e, k, G) + G * ya;
      r = fabs(ua[0] - w) * a +
          fabs(G) * tau * (fabs(ua[1] - wy) * cs[1] + fabs(wy) * cs[2]);
    } else
      r = fabs(ua[c] - w) * a;
    r2 += r * r;
  }
  return 0.25 * h * sqrt(r2);
}

/* State of particle k at step fraction t on its current piece (position
 * in its frame); draws from r inside a stochastic piece. */
static int state_at(const sb_engine *e, size_t k, double t, const gsl_rng *r,
                    double x[3], double u[3])
{
  const double t0 = e->lp_t[k];
  if (t <= t0 || t >= 1.0) {
    const double *xs = t >= 1.0 ? &e->x[3 * k] : &e->lp_x[3 * k];
    const double *us = t >= 1.0 ? &e->u[3 * k] : &e->lp_u[3 * k];
    memcpy(x, xs, 3 * sizeof(double));
    memcpy(u, us, 3 * sizeof(double));
    return SB_SUCCESS;
  }
  const sb_engine_species *sp = &e->spec[e->species[k]];
  const double h = (1.0 - t0) * e->par.dt, s = (t - t0) * e->par.dt;
  x[0] = x[1] = x[2] = u[0] = u[1] = u[2] = 0.0;
  int c0 = 0;
  const double G = shear_rate(e, k);
  if (G != 0.0) {  /* the in-plane state from the exact shear bridge */
    const double *xa = &e->lp_x[3 * k], *ua = &e->lp_u[3 * k],
                 *xb = &e->x[3 * k], *ub = &e->u[3 * k];
    const double sa[4] = {ua[1], xa[1], ua[0], xa[0]},
                 sb[4] = {ub[1], xb[1], ub[0], xb[0]};
    double o[4];
    if (sp->B == 0.0) {  /* no noise: the exact path from the piece's
                            start */
      int st = sb_langevin_shear_mean(sp->tau, G, shear_cx(e, k, G),
                                      sbi_engine_w(e, k, 1), s, sa, o);
      if (st)
        return st;
    } else {
      int st = sb_langevin_shear_bridge_sample(
          sp->tau, sp->B, G, shear_cx(e, k, G), sbi_engine_w(e, k, 1), h, s,
          sa, sb, r, o);
      if (st)
        return st;
    }
    u[1] = o[0], x[1] = o[1], u[0] = o[2], x[0] = o[3];
    c0 = 2;
  }
  /* the relaxation without noise (a nonlinear drag: its step's rate) */
  double rt, rw[3];
  sbi_engine_relax(e, k, &rt, rw);
  for (int c = c0; c < e->par.dim; c++) {
    const double xa = e->lp_x[3 * k + c], ua = e->lp_u[3 * k + c];
    const double w = rw[c];
    if (isinf(sp->tau)) {
      x[c] = xa + ua * s;
      u[c] = ua;
    } else if (sp->B == 0.0) {
      double a = -expm1(-s / rt);
      x[c] = xa + w * s + (ua - w) * rt * a;
      u[c] = w + (ua - w) * (1.0 - a);
    } else {
      sb_langevin p = {sp->tau, sp->B, w};
      double ss = s < 1e-50 * sp->tau ? 0.0 : (h - s < 1e-50 * sp->tau ? h : s);
      int st = sb_langevin_bridge_sample(&p, h, ss, xa, ua, e->x[3 * k + c],
                                         e->u[3 * k + c], r, &x[c], &u[c]);
      if (st)
        return st;
    }
  }
  return SB_SUCCESS;
}

/* Path of particle k from (xa, ua) to its end, seen in the frame shifted
 * by sh (position at the piece's start) and moving at du along x relative
 * to it (a Lees-Edwards image: its fluid velocity and both velocities gain
 * du, its end position du h more; docs/engine_forces.md §3). */
static void fill_path(const sb_engine *e, size_t k, const double *xa,
                      const double *ua, const double *sh, double du,
                      double h, sb_langevin_path *q)
{
  const sb_engine_species *sp = &e->spec[e->species[k]];
  double w[3];  /* a nonlinear drag: its step's rate and terminal slip */
  sbi_engine_relax(e, k, &q->tau, w);
  q->B = isinf(sp->tau) ? 0.0 : sp->B;
  q->mass = e->mass[k];
  for (int c = 0; c < 3; c++) {
    const double v = c == 0 ? du : 0.0;
    q->us[c] = w[c] + v;
    q->x0[c] = xa[c] + sh[c];
    q->u0[c] = ua[c] + v;
    q->x1[c] = e->x[3 * k + c] + sh[c] + v * h;
    q->u1[c] = e->u[3 * k + c] + v;
  }
  /* in the shear: the fluid velocity at x0, the field continued linearly
   * through the images (their velocity offset du is G times their y
   * shift) */
  q->G = shear_rate(e, k);
  if (q->G != 0.0)
    q->us[0] = shear_cx(e, k, q->G) + q->G * q->x0[1];
}

double sbi_pair_chord_min2(const sb_engine_pair *p)
{
  return sbi_chord_min2(p->dx0, p->dd);
}

/* 1 if the pair's record at the start of the step is not examined: its
 * relative chord (the engine pair's, both particles on their first piece)
 * stays more than sigma + rho away, rho the cached neighbour reach (valid
 * for this dt, these species and at most lreach_n particles)
 * (docs/engine_langevin.md §4: the expected number of contacts such pairs
 * hold is <= tol per particle and step).  The neighbour search returns a
 * superset of these pairs (its criterion bounds the chords by the
 * displacements' lengths); this exact chord test drops the rest before any
 * state is drawn.  Only for particles with noise (the reach bounds the
 * noise's deviation from the chord; a deterministic curved path is not
 * covered) and plain periodic or open boxes (the engine pair's image is
 * the one the sampler uses). */
static int beyond_reach(const sb_engine *e, const sb_engine_pair *p)
{
  const double rho = e->lreach;
  if (!(rho >= 0.0) || e->lreach_dt != e->par.dt ||
      e->lreach_nspec != e->nspec || e->n > e->lreach_n || e->lees ||
      e->walled || e->lp_t[p->i] > 0.0 || e->lp_t[p->j] > 0.0)
    return 0;
  const sb_engine_species *si = &e->spec[e->species[p->i]],
                          *sj = &e->spec[e->species[p->j]];
  if (isinf(si->tau) || isinf(sj->tau) || !(si->B > 0.0) || !(sj->B > 0.0))
    return 0;
  const double lim = p->sigma + rho;
  return sbi_pair_chord_min2(p) > lim * lim;
}

int sbi_engine_langevin_chord_gate(const sb_engine *e, double reach)
{
  /* beyond_reach's conditions that do not depend on the pair (at the
   * start of a step every particle is on its first piece) */
  const double rho = e->lreach;
  if (!(rho >= 0.0) || reach != rho || e->lreach_dt != e->par.dt ||
      e->lreach_nspec != e->nspec || e->n > e->lreach_n || e->lees ||
      e->walled)
    return 0;
  for (size_t sp = 0; sp < e->nspec; sp++)
    if (isinf(e->spec[sp].tau) || !(e->spec[sp].B > 0.0))
      return 0;
  return 1;
}

/* A record ready for the sampler: both paths over the rest of the step
 * (dtr), j seen in the image next to i (shift shj, velocity offset du). */
typedef struct {
  sb_langevin_path pi, pj;
  double shj[3], du, dtr;
} lrec;

/* Both paths of record p from step fraction t; 1 (ready), 0 (nothing to
 * look for: beyond reach, or no time left) or -1 (error). */
static int lrec_make(const sb_engine *e, const sb_engine_pair *p, double t,
                     const gsl_rng *r, lrec *q)
{
  const size_t i = p->i, j = p->j;
  if (t <= 0.0 && beyond_reach(e, p))
    return 0;
  double xi[3], ui[3], xj[3], uj[3];
  double shi[3] = {0, 0, 0};
  memset(q->shj, 0, sizeof q->shj);
  q->du = 0.0;
  /* Inside the step a partner's state at t is drawn from its own bridge,
   * independently of the other particle, so the draw ignores that the
   * pair has not touched before t; the draw is repeated while the pair
   * overlaps at t (conditioning on no overlap at t, the part of that
   * condition that matters most; docs/engine_langevin.md). */
  const int drawn = t > e->lp_t[i] || t > e->lp_t[j];
  for (int tries = 0;; tries++) {
    if (state_at(e, i, t, r, xi, ui) || state_at(e, j, t, r, xj, uj))
      return -1;
    /* j in the image next to i at t: shift shj (a multiple of the box,
     * with the Lees-Edwards offset across the sliding boundary) */
    sbi_engine_image(e, xi, xj, t, q->shj, &q->du);
    double d2 = 0.0;
    for (int c = 0; c < e->par.dim; c++) {
      double d = xi[c] - xj[c] - q->shj[c];
      d2 += d * d;
    }
    if (!drawn || t <= 0.0 || tries >= 1000 ||
        d2 >= p->sigma * p->sigma * (1.0 + SB_ENGINE_TOUCH))
      break;
  }
  q->dtr = (1.0 - t) * e->par.dt;
  fill_path(e, i, xi, ui, shi, 0.0, q->dtr, &q->pi);
  fill_path(e, j, xj, uj, q->shj, q->du, q->dtr, &q->pj);
  return q->dtr > 0.0;
}

/* The event of contact c on record p (the record's step fraction *s). */
static void lrec_event(const lrec *q, const sb_engine_pair *p,
                       const sb_langevin_contact *c, double *s,
                       sbi_event *ev)
{
  double f = c->t / q->dtr;
  *s = f < 0.0 ? 0.0 : (f > 1.0 ? 1.0 : f);
  if (!ev)
    return;
  ev->hasc = 1;
  ev->p = *p;
  ev->cdu = q->du;
  for (int k = 0; k < 3; k++) {
    /* j back in its own frame: the image moved du c.t further */
    const double v = k == 0 ? q->du : 0.0;
    ev->cx[0][k] = c->xi[k];
    ev->cu[0][k] = c->ui[k];
    ev->cx[1][k] = c->xj[k] - q->shj[k] - v * c->t;
    ev->cu[1][k] = c->uj[k] - v;
    ev->crel[k] = c->xi[k] - c->xj[k];
    /* the record's chord from the Langevin states it was built on */
    ev->p.dx0[k] = q->pi.x0[k] - q->pj.x0[k];
    ev->p.dd[k] = (q->pi.x1[k] - q->pj.x1[k]) - ev->p.dx0[k];
  }
}

/* The record's orientation.  The sampler walks x_i - x_j and draws i's
 * state before j's, so a record is built with the particle of lower id
 * first: its draws then depend on the two particles and not on their
 * order in memory (sb_engine_sort).  *o is p, turned around if needed;
 * returns 1 if it was. */
static int pair_by_id(const sb_engine *e, const sb_engine_pair *p,
                      sb_engine_pair *o)
{
  *o = *p;
  if (e->id[p->i] < e->id[p->j])
    return 0;
  o->i = p->j;
  o->j = p->i;
  for (int k = 0; k < 3; k++) {
    o->dx0[k] = -p->dx0[k];
    o->dd[k] = -p->dd[k];
  }
  return 1;
}

/* An event of the turned-around record back in p's orientation. */
static void event_turn_back(const sb_engine_pair *p, sbi_event *ev)
{
  for (int k = 0; k < 3; k++) {
    double w = ev->cx[0][k];
    ev->cx[0][k] = ev->cx[1][k];
    ev->cx[1][k] = w;
    w = ev->cu[0][k];
    ev->cu[0][k] = ev->cu[1][k];
    ev->cu[1][k] = w;
    ev->crel[k] = -ev->crel[k];
    ev->p.dx0[k] = -ev->p.dx0[k];
    ev->p.dd[k] = -ev->p.dd[k];
  }
  ev->cdu = -ev->cdu;  /* i's image moves du along x relative to j */
  ev->p.i = p->i;
  ev->p.j = p->j;
}

/* The first contact of record p from step fraction t, with hitter lh and
 * generator r. */
static int detect_with(const sb_engine *e, sb_langevin_hitter *lh,
                       const sb_engine_pair *p, double t, const gsl_rng *r,
                       double *s, sbi_event *ev, sb_langevin_hit_stats *acc)
{
  sb_engine_pair o;
  const int turned = pair_by_id(e, p, &o);
  lrec q;
  int h = lrec_make(e, &o, t, r, &q);
  if (h <= 0)
    return h;
  sb_langevin_contact c;
  sb_langevin_hitter_reset(lh);
  h = sb_langevin_hitter_sample(lh, &q.pi, &q.pj, o.sigma, q.dtr, r, &c);
  hit_done(lh, acc);
  if (h <= 0)
    return h < 0 ? -1 : 0;
  lrec_event(&q, &o, &c, s, ev);
  if (turned && ev)
    event_turn_back(p, ev);
  return 1;
}

int sbi_engine_langevin_detect(const sb_engine *e, const sb_engine_pair *p,
                               double t, const gsl_rng *r, double *s,
                               sbi_event *ev)
{
  return detect_with(e, e->lh, p, t, r, s, ev, e->lacc);
}

int sbi_engine_langevin_events(const sb_engine *e, sb_langevin_hitter *lh,
                               const gsl_rng *r, const sb_engine_pair *p,
                               double t, sbi_lsink sink, void *ctx,
                               sb_langevin_hit_stats *acc)
{
  if (e->obs_skip && e->obs_skip(e, p, e->obs_ctx))
    return SB_SUCCESS;
  if (e->par.outcome != SB_OUTCOME_COUNT || e->obs_take) {
    double s = 0.0;
    sbi_event ev;
    ev.hasc = 0;
    const int h = detect_with(e, lh, p, t, r, &s, &ev, acc);
    if (h < 0)
      return sbi_error(SB_EINVAL, "sb_engine_step",
                       "detector failed on pair (%zu, %zu)", p->i, p->j);
    return h ? sink(ctx, s, &ev) : SB_SUCCESS;
  }
  /* pass-through: every entry */
  sb_engine_pair o;
  const int turned = pair_by_id(e, p, &o);
  lrec q;
  int n = lrec_make(e, &o, t, r, &q);
  if (n > 0) {
    sb_langevin_hitter_reset(lh);
    n = sb_langevin_hitter_sample_all(lh, &q.pi, &q.pj, o.sigma, q.dtr, r);
    hit_done(lh, acc);
  }
  if (n < 0)
    return sbi_error(SB_EINVAL, "sb_engine_step",
                     "detector failed on pair (%zu, %zu)", p->i, p->j);
  const sb_langevin_contact *c = sb_langevin_hitter_entries(lh);
  for (int k = 0; k < n; k++) {
    double s;
    sbi_event ev;
    lrec_event(&q, &o, &c[k], &s, &ev);
    if (turned)
      event_turn_back(p, &ev);
    int st = sink(ctx, s, &ev);
    if (st)
      return st;
  }
  return SB_SUCCESS;
}

/* sb_engine_langevin_contact for the public function who. */
static int langevin_contact(const sb_engine *e, const sb_engine_pair *p,
                            const gsl_rng *r, double *s,
                            sb_langevin_contact *c, const char *who)
{
  if (!e || !p || !r || !s) {
    sbi_error(SB_EINVAL, who, "NULL argument");
    return -1;
  }
  if (p->i >= e->n || p->j >= e->n) {
    sbi_error(SB_EINVAL, who, "pair (%zu, %zu): no such particle (%zu)",
              p->i, p->j, e->n);
    return -1;
  }
  double t = (p->t0 - e->t) / e->par.dt;
  t = t < 0.0 ? 0.0 : (t > 1.0 ? 1.0 : t);
  sbi_event ev;
  int h = sbi_engine_langevin_detect(e, p, t, r, s, c ? &ev : NULL);
  if (h == 1 && c) {
    c->t = *s * p->dt;
    for (int k = 0; k < 3; k++) {
      c->xi[k] = ev.cx[0][k];
      c->ui[k] = ev.cu[0][k];
      c->xj[k] = ev.cx[0][k] - ev.crel[k];
      c->uj[k] = ev.cu[1][k] + (k == 0 ? ev.cdu : 0.0);
    }
  }
  return h;
}

int sb_engine_langevin_contact(const sb_engine *e, const sb_engine_pair *p,
                               const gsl_rng *r, double *s,
                               sb_langevin_contact *c)
{
  return langevin_contact(e, p, r, s, c, __func__);
}

int sb_engine_detect_langevin(const sb_engine *e, const sb_engine_pair *p,
                              const gsl_rng *r, void *ctx, double *s)
{
  (void)ctx;
  return langevin_contact(e, p, r, s, NULL, __func__);
}

/* ------------------------------------------------------------ after */

int sbi_engine_langevin_continue(sb_engine *e, size_t k, const sbi_event *ev,
                                 int changed, const double xe[3],
                                 const double ue[3])
{
  const double t = ev->s;
  memcpy(&e->lp_x[3 * k], &e->x[3 * k], 3 * sizeof(double));
  memcpy(&e->lp_u[3 * k], &e->u[3 * k], 3 * sizeof(double));
  e->lp_t[k] = t;
  if (!changed) {
    memcpy(&e->x[3 * k], xe, 3 * sizeof(double));
    memcpy(&e->u[3 * k], ue, 3 * sizeof(double));
    return SB_SUCCESS;
  }
  /* a jump (reinsertion, declared position) sees the fluid at its new
   * place */
  const int q = ev->p.i == k ? 0 : 1;
  int moved = 0;
  for (int c = 0; c < 3; c++)
    moved |= e->x[3 * k + c] != ev->cx[q][c];
  if (moved && e->fluid != SB_FLUID_REST) {
    double xw[3];
    for (int c = 0; c < 3; c++)
      xw[c] = c < e->par.dim ? sbi_wrap(e->x[3 * k + c], e->par.L[c]) : 0.0;
    int st = sbi_engine_fluid_eval(e, 1, xw, &e->us[3 * k], k,
                                   "sb_engine_step");
    if (st) {  /* no half-made step: every particle back at its start */
      sbi_engine_step_undo(e);
      return st;
    }
  }
  const sb_engine_species *sp = &e->spec[e->species[k]];
  const double h = (1.0 - t) * e->par.dt;
  if (sbi_engine_nonlinear(e, k)) {  /* its own step (engine_force.c) */
    int st = sbi_engine_drag_piece(e, k, h);
    if (st)
      return st;
    for (int c = 0; c < 3; c++)
      e->disp[3 * k + c] = e->x[3 * k + c] - e->x0[3 * k + c];
    return SB_SUCCESS;
  }
  sb_langevin_coef cf;
  if (isinf(sp->tau))
    cf = (sb_langevin_coef){h, 1.0, h, 0.0, 0.0, 0.0};
  else if (sb_langevin_coef_init(&cf, sp->tau, sp->B, h))
    return sbi_error(SB_EINVAL, "sb_engine_step", "no Langevin step");
  double z[6];
  for (int c = 0; c < 6; c++)
    z[c] = gsl_ran_gaussian_ziggurat(e->rng, 1.0);
  /* Lees-Edwards shear, Stokes species: the exact step in the linear
   * field over h (engine_lees.c: mean correction and shear noise, the
   * x rows of the Cholesky factor against the same normals) */
  const double G = e->fluid_p[0];
  const int shear = e->lees && e->fluid == SB_FLUID_SHEAR && G != 0.0 &&
                    !isinf(sp->tau) && h > 0.0 &&
                    !(e->species[k] < e->nsfl &&
                      e->sfl[e->species[k]].drag != SB_DRAG_STOKES);
  double dux = 0.0, dxx = 0.0, L[7];
  if (shear) {
    const double tau = sp->tau, bt = sp->B * sqrt(tau);
    const double wy = sbi_engine_w(e, k, 1);
    double cs[4];
    sb_langevin_shear_mean_coefs(h / tau, cs);
    const double vr = e->u[3 * k + 1] - wy;
    dux = G * tau * (cs[1] * vr + cs[2] * wy);
    dxx = G * tau * tau * (cs[0] * vr + cs[3] * wy);
    sb_langevin_shear_noise_chol(h / tau, G * tau, L);
    for (int q = 0; q < 7; q++)
      L[q] *= q < 3 ? bt : bt * tau;
  }
  for (int c = 0; c < 3; c++) {
    const double z1 = z[2 * c], z2 = z[2 * c + 1];
    if (c >= e->par.dim)
      continue;
    double w = sbi_engine_w(e, k, c);
    if (c == 0 && shear)  /* the field at the piece's start (the linear
                             continuation in the particle's frame) */
      w += G * (e->x[3 * k + 1] - 0.5 * e->par.L[1]) - e->us[3 * k];
    const double v = e->u[3 * k + c] - w;
    if (c == 0 && shear) {
      e->x[3 * k] += w * cf.dt + v * cf.gain + L[5] * z1 + L[6] * z2 +
                     L[3] * z[2] + L[4] * z[3] + dxx;
      e->u[3 * k] = w + v * cf.decay + (L[2] * z1 + L[0] * z[2] +
                                        L[1] * z[3]) + dux;
      continue;
    }
    e->x[3 * k + c] += w * cf.dt + v * cf.gain + cf.s_xu * z1 + cf.s_xc * z2;
    e->u[3 * k + c] = w + v * cf.decay + cf.s_u * z1;
  }
  for (int c = 0; c < 3; c++)
    e->disp[3 * k + c] = e->x[3 * k + c] - e->x0[3 * k + c];
  return SB_SUCCESS;
}

int sb_engine_contact_state(const sb_engine *e, double xi[3], double ui[3],
                            double xj[3], double uj[3])
{
  if (!e || !e->contact)
    return sbi_error(SB_EINVAL, __func__,
                     "no contact state (Langevin detector, inside an "
                     "outcome only)");
  const sbi_event *ev = e->contact;
  for (int k = 0; k < 3; k++) {
    if (xi)
      xi[k] = ev->cx[0][k];
    if (ui)
      ui[k] = ev->cu[0][k];
    if (xj)
      xj[k] = ev->cx[0][k] - ev->crel[k];
    if (uj)  /* in i's frame (j's Lees-Edwards image), as xj */
      uj[k] = ev->cu[1][k] + (k == 0 ? ev->cdu : 0.0);
  }
  return SB_SUCCESS;
}
