/* engine_outcome.c — collision outcomes: elastic with energy-loss factor
 * eta (Thomine 2008, §4.3-4.4), reinsertion (Mohaupt 2011, §5.3.2),
 * count-only, and the dispatcher to a user outcome.
 *
 * Elastic collision.  With n the unit normal at contact (from j to i) and
 * w the chord velocities (disp/dt), the tangential components are kept
 * and the normal components change so that
 *   m_i w_i.n + m_j w_j.n is conserved             (Thomine 2008, eqs 4, 6)
 *   (w_i - w_j).n  ->  -e (w_i - w_j).n,  e = sqrt(eta).
 * With eta = 1 this is Thomine's solution (2008, eqs 7-9: the normal
 * kinetic energy conserved).  For eta < 1 his eq 5 multiplies the *total*
 * normal kinetic energy by eta, which depends on the frame (it is not
 * Galilean invariant, and its square root can be negative when the centre
 * of mass moves fast); we apply eta to the kinetic energy of the relative
 * normal motion, mu w_n^2 / 2 (mu the reduced mass), i.e. a restitution
 * coefficient e = sqrt(eta).  His sign choice in eq 9 also depends
 * on the orientation of i (its test case has R moving away from S along
 * i); writing the rule on w_n avoids the ambiguity.  In impulse form:
 *   J = (1 + e) mu w_n,  dw_i = -J n / m_i,  dw_j = +J n / m_j.
 * The same impulse is applied to the particle velocities u (for free
 * flight u = w, exact), and the end positions are re-advanced from the
 * contact: x += (1 - s) dt dw (Thomine 2008, §4.3, last
 * equation).
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_rng.h>

#include "common/internal.h"
#include "engine_internal.h"

/* Elastic collision at a Langevin contact: the same impulse rule on the
 * velocities at contact (e->u holds them), normal from the contact
 * separation; positions stay (the engine continues both partners from
 * their new states by a fresh Langevin step).  Across a Lees-Edwards
 * boundary j's image moves c->cdu faster along x: the relative velocity
 * is taken to it (the impulse itself is the same in every frame). */
static int elastic_contact(sb_engine *e, const sb_engine_pair *p)
{
  const sbi_event *c = e->contact;
  const size_t i = p->i, j = p->j;
  double nv[3], nn = 0.0, wn = 0.0;
  for (int k = 0; k < 3; k++) {
    nv[k] = c->crel[k];
    nn += nv[k] * nv[k];
  }
  nn = sqrt(nn);
  if (!(nn > 0.0))
    return SB_SUCCESS;
  for (int k = 0; k < 3; k++) {
    nv[k] /= nn;
    wn += (e->u[3 * i + k] - e->u[3 * j + k] - (k == 0 ? c->cdu : 0.0)) *
          nv[k];
  }
  if (!(wn < 0.0))
    return SB_SUCCESS;
  const double mi = e->mass[i], mj = e->mass[j];
  const double J = (1.0 + sqrt(e->par.eta)) * mi * mj / (mi + mj) * wn;
  for (int k = 0; k < e->par.dim; k++) {
    e->u[3 * i + k] -= J * nv[k] / mi;
    e->u[3 * j + k] += J * nv[k] / mj;
  }
  return SB_SUCCESS;
}

int sb_engine_outcome_elastic(sb_engine *e, const sb_engine_pair *p,
                              double s)
{
  if (!e || !p || p->i >= e->n || p->j >= e->n || p->i == p->j ||
      !(s >= 0.0 && s <= 1.0))
    return sbi_error(SB_EINVAL, __func__, "bad argument");
  if (e->contact)
    return elastic_contact(e, p);
  const double dt = p->dt;  /* the interval the record covers */
  double nv[3], nn = 0.0;
  for (int k = 0; k < 3; k++) {
    nv[k] = p->dx0[k] + s * p->dd[k];
    nn += nv[k] * nv[k];
  }
  nn = sqrt(nn);
  if (!(nn > 0.0))
    return SB_SUCCESS;  /* coincident centres: no normal, nothing to do */
  double wn = 0.0;
  for (int k = 0; k < 3; k++) {
    nv[k] /= nn;
    wn += (p->dd[k] / dt) * nv[k];
  }
  if (!(wn < 0.0))
    return SB_SUCCESS;  /* separating */
  const size_t i = p->i, j = p->j;
  const double mi = e->mass[i], mj = e->mass[j];
  const double mu = mi * mj / (mi + mj);
  const double J = (1.0 + sqrt(e->par.eta)) * mu * wn;
  const double rest = (1.0 - s) * dt;
  for (int k = 0; k < e->par.dim; k++) {
    double dwi = -J * nv[k] / mi, dwj = J * nv[k] / mj;
    e->u[3 * i + k] += dwi;
    e->u[3 * j + k] += dwj;
    e->x[3 * i + k] += rest * dwi;
    e->x[3 * j + k] += rest * dwj;
    e->disp[3 * i + k] += rest * dwi;
    e->disp[3 * j + k] += rest * dwj;
  }
  return SB_SUCCESS;
}

/* Squared distance from x to particle j's current position (positions may
 * be unwrapped during a step by less than L/2: one shift; a full
 * reduction only beyond).  With walls or Lees-Edwards images the nearest
 * image is sbi_engine_image's: none across a wall, the sliding image
 * across y shifted by its offset at the positions' time (the step's end
 * inside a step, as every current position is an end of a path piece). */
static double free_d2(const sb_engine *e, const double x[3], size_t j)
{
  const double *L = e->par.L;
  double d2 = 0.0;
  if (e->lees || e->walled) {
    double sh[3], du;
    sbi_engine_image(e, x, &e->x[3 * j], e->in_step ? 1.0 : 0.0, sh, &du);
    for (int c = 0; c < e->par.dim; c++) {
      const double d = x[c] - e->x[3 * j + c] - sh[c];
      d2 += d * d;
    }
    return d2;
  }
  for (int c = 0; c < e->par.dim; c++) {
    double d = x[c] - e->x[3 * j + c];
    if (d > 0.5 * L[c] || d < -0.5 * L[c]) {
      d += d > 0.0 ? -L[c] : L[c];
      if (d > 0.5 * L[c] || d < -0.5 * L[c])
        d -= L[c] * floor(d / L[c] + 0.5);
    }
    d2 += d * d;
  }
  return d2;
}

typedef struct {
  const double *x;
  double r;
} free_q;

/* 1 (stop the search) when k overlaps the trial position */
static int overlaps(sb_engine *e, size_t a, size_t k, void *ctx)
{
  (void)a;
  const free_q *q = ctx;
  const double sg = q->r + e->radius[k];
  return free_d2(e, q->x, k) < sg * sg;
}

/* Is the trial position x free for particle k?  Inside a step's event loop
 * (reinsertion outcome, no Lees-Edwards) only the particles the step's
 * search puts near x can overlap it: each one's current position lies on
 * its path, within r_j + dn_j of x0_j, or on its far piece
 * (sbi_engine_partners); the partner of the collision may sit at a
 * Langevin contact point off its chord and is tested by itself.  The
 * answer is the same as the scan of all particles, which serves every
 * other case. */
static int position_free(sb_engine *e, size_t k, size_t partner,
                         const double x[3])
{
  const double rk = e->radius[k];
  free_q q = {x, rk};
  if (e->in_step && !e->lees && e->par.outcome == SB_OUTCOME_REINSERT) {
    if (partner < e->n && partner != k && overlaps(e, k, partner, &q))
      return 0;
    return !sbi_engine_partners(e, k, x, rk, e->in_outcome_t, overlaps, &q);
  }
  for (size_t j = 0; j < e->n; j++)
    if (j != k && overlaps(e, k, j, &q))
      return 0;
  return 1;
}

int sbi_engine_random_free_position(sb_engine *e, size_t k, size_t partner,
                                    double x[3], size_t tries,
                                    const char *who)
{
  const int dim = e->par.dim;
  const double *L = e->par.L;
  const double r = e->radius[k];
  for (size_t t = 0; t < tries; t++) {
    x[0] = x[1] = x[2] = 0.0;
    for (int c = 0; c < dim; c++) {
      /* a walled direction: the accessible volume, centres >= r from the
       * walls (as the placements and the deposit source) */
      if (e->wall[2 * c] != SB_WALL_PERIODIC)
        x[c] = r + (L[c] - 2.0 * r) * gsl_rng_uniform(e->rng);
      else
        x[c] = L[c] * gsl_rng_uniform(e->rng);
    }
    if (position_free(e, k, partner, x))
      return SB_SUCCESS;
  }
  return sbi_error(SB_EMAXITER, who,
                   "no free position for a reinserted particle after %zu "
                   "tries",
                   tries);
}

/* In a flow (or settling) a reinserted particle j moves on over the rest
 * of the step with its mean velocity w at the new place x, the fluid's
 * plus the settling velocity (the mean of the exact step from an
 * equilibrium velocity), as the particles around it do: standing still it
 * would meet those streaming past (in a shear, at a relative velocity up
 * to G L_y/2).  x becomes the position at the step's end; a flight that
 * is not finite, or lands too far out to be wrapped into the box, is
 * SB_ERANGE. */
static int reinsert_flight(sb_engine *e, const sb_engine_pair *p, double s,
                           size_t j, double x[3], const char *who)
{
  double w[3] = {0.0, 0.0, 0.0};
  int st;
  if (e->fluid != SB_FLUID_REST &&
      (st = sbi_engine_fluid_eval(e, 1, x, w, j, who)))
    return st;
  const double *vs;
  if ((st = sbi_engine_settling(e, e->species[j], &vs, who)))
    return st;
  double tc = (p->t0 + s * p->dt - e->t) / e->par.dt;
  tc = tc < 0.0 ? 0.0 : (tc > 1.0 ? 1.0 : tc);
  const double rest = (1.0 - tc) * e->par.dt;
  if ((st = sb_engine_outcome_path(e, j, x)))
    return st;
  double xm[3] = {x[0], x[1], x[2]};
  for (int k = 0; k < e->par.dim; k++) {
    xm[k] += rest * (w[k] + (vs ? vs[k] : 0.0));
    if (!sbi_wrappable(xm[k], e->par.L[k]))
      return sbi_error(SB_ERANGE, who, "reinserted particle %zu: its "
                       "flight over the rest of the step from x[%d] = %g "
                       "(velocity %g) ends at %g, %s", j, k, x[k],
                       w[k] + (vs ? vs[k] : 0.0), xm[k],
                       isfinite(xm[k]) ? "too far out to be wrapped into "
                                         "the box"
                                       : "not finite");
  }
  memcpy(x, xm, sizeof xm);
  return SB_SUCCESS;
}

/* sb_engine_outcome_reinsert for the public function who (the step for
 * the built-in outcome) */
static int outcome_reinsert(sb_engine *e, const sb_engine_pair *p, double s,
                            const char *who)
{
  if (!e || !p || p->i >= e->n || p->j >= e->n || p->i == p->j)
    return sbi_error(SB_EINVAL, who, "bad argument");
  const size_t j = p->j;
  double x[3], u[3];
  int st = sbi_engine_random_free_position(e, j, p->i, x, 10000, who);
  if (st)
    return st;
  /* a velocity that is not finite: SB_ERANGE, j left as it was */
  st = sbi_engine_equilibrium_velocity(e, e->species[j], x, u, j, who);
  if (st)
    return st;
  const int flies = e->in_step && !e->contact &&
                    (e->fluid != SB_FLUID_REST || e->has_grav);
  /* (Langevin: continued by a fresh exact step) */
  if (flies && (st = reinsert_flight(e, p, s, j, x, who)))
    return st;  /* j left as it was */
  for (int k = 0; k < 3; k++) {
    e->x[3 * j + k] = x[k];
    e->u[3 * j + k] = u[k];
    e->disp[3 * j + k] = 0.0;
  }
  return SB_SUCCESS;
}

int sb_engine_outcome_reinsert(sb_engine *e, const sb_engine_pair *p,
                               double s)
{
  return outcome_reinsert(e, p, s, __func__);
}

int sb_engine_outcome_path(sb_engine *e, size_t k, const double x[3])
{
  if (!e || !x || k >= e->n)
    return sbi_error(SB_EINVAL, __func__, "bad engine, particle or NULL");
  if (!isfinite(x[0]) || !isfinite(x[1]) || !isfinite(x[2]) ||
      fabs(x[0]) > 1e3 * e->par.L[0] || fabs(x[1]) > 1e3 * e->par.L[1] ||
      fabs(x[2]) > 1e3 * e->par.L[2])
    return sbi_error(SB_EINVAL, __func__, "position (%g, %g, %g) of "
                     "particle %zu: not finite, or far outside the box",
                     x[0], x[1], x[2], k);
  for (int q = 0; q < e->ndeclared; q++)
    if (e->declared[q].k == k) {
      memcpy(e->declared[q].x, x, 3 * sizeof(double));
      return SB_SUCCESS;
    }
  if (e->ndeclared == 2)
    return sbi_error(SB_EINVAL, __func__,
                     "only the two partners of the collision (particle %zu)",
                     k);
  e->declared[e->ndeclared].k = k;
  memcpy(e->declared[e->ndeclared].x, x, 3 * sizeof(double));
  e->ndeclared++;
  return SB_SUCCESS;
}

int sbi_engine_reinsert_higher_id(sb_engine *e, const sb_engine_pair *p,
                                  double s, const char *who)
{
  if (e->id[p->i] < e->id[p->j])
    return outcome_reinsert(e, p, s, who);
  sb_engine_pair q = *p;
  q.i = p->j;
  q.j = p->i;
  for (int k = 0; k < 3; k++) {
    q.dx0[k] = -p->dx0[k];
    q.dd[k] = -p->dd[k];
  }
  return outcome_reinsert(e, &q, s, who);
}

int sbi_engine_apply_outcome(sb_engine *e, const sb_engine_pair *p,
                             double s)
{
  switch (e->par.outcome) {
  case SB_OUTCOME_ELASTIC:
    return sb_engine_outcome_elastic(e, p, s);
  case SB_OUTCOME_REINSERT:
    return sbi_engine_reinsert_higher_id(e, p, s, "sb_engine_step");
  case SB_OUTCOME_COUNT:
    return SB_SUCCESS;
  case SB_OUTCOME_CUSTOM: {
    int st = e->outcome_fn(e, p, s, e->outcome_ctx);
    if (st)
      return sbi_error(st, "sb_engine_step",
                       "outcome callback failed on pair (%zu, %zu)", p->i,
                       p->j);
    return SB_SUCCESS;
  }
  }
  return sbi_error(SB_EINVAL, "sb_engine_step", "unknown outcome");
}
