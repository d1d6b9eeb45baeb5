/* engine_open.c — open boundaries: inflows that inject a steady stream of
 * particles through part of a face, and the outflow of particles through
 * SB_WALL_OPEN faces (docs/engine_forces.md, "Open boundaries").
 *
 * Inflow.  A stream of rate R (particles per second) entering through an
 * inlet of area A with velocity u (normal component u_n > 0 inward) fills
 * the box as a spatial Poisson process of density R/(u_n A) when arrivals
 * are a Poisson process in time and uniform over the inlet.  A step of
 * length dt receives Poisson(R dt) particles; one that entered a fraction
 * s of the step before its end (s uniform) is placed where its flight
 * from the entry point took it over s dt (straight in free flight; with
 * drag the mean path of the exact Langevin step, see flight()).  The
 * engine's other particles are at the step's end then, so the stream
 * joins the box's state exactly in law for non-Brownian particles; the
 * arrivals' own flight over s dt has no collisions and, for Brownian
 * ones, no noise.
 *
 * Outflow.  engine_wall.c detects the particles whose centre reaches an
 * open face during the step (the absorbing walls' detector with the plane
 * at the face) and calls sbi_engine_outflow, which counts them, reports
 * them to the outflow callback and marks them for removal at the end of
 * the boundary pass. */
#include <math.h>
#include <string.h>

#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>

#include "common/internal.h"
#include "engine_internal.h"

int sb_engine_add_inflow(sb_engine *e, const sb_engine_inflow *in,
                         size_t *idx)
{
  if (!e || !in)
    return sbi_error(SB_EINVAL, __func__, "NULL argument");
  if (e->ninflow >= SB_ENGINE_MAXINFLOW)
    return sbi_error(SB_EINVAL, __func__, "at most %d inflows",
                     SB_ENGINE_MAXINFLOW);
  const int dim = e->par.dim, k = in->face / 2;
  if (in->face < 0 || k >= dim)
    return sbi_error(SB_EINVAL, __func__, "face = %d: must be 0..%d",
                     in->face, 2 * dim - 1);
  if (in->species >= e->nspec)
    return sbi_error(SB_EINVAL, __func__, "species %zu does not exist",
                     in->species);
  if (in->family < 0 || in->family >= SB_ENGINE_MAXFAM)
    return sbi_error(SB_EINVAL, __func__, "family = %d: must be in 0..%d",
                     in->family, SB_ENGINE_MAXFAM - 1);
  if (!(in->rate >= 0.0) || !isfinite(in->rate))
    return sbi_error(SB_EINVAL, __func__, "rate = %g: must be finite >= 0",
                     in->rate);
  for (int d = 0; d < dim; d++)
    if (!isfinite(in->u[d]))
      return sbi_error(SB_EINVAL, __func__, "u[%d] = %g: must be finite", d,
                       in->u[d]);
  const double un = (in->face % 2 ? -1.0 : 1.0) * in->u[k];
  if (!(un > 0.0))
    return sbi_error(SB_EINVAL, __func__, "face %d: the velocity's normal "
                     "component %g must point into the box", in->face,
                     in->u[k]);
  for (int d = 0, q = 0; d < dim; d++) {
    if (d == k)
      continue;
    if (!(in->lo[q] >= 0.0 && in->lo[q] < in->hi[q] &&
          in->hi[q] <= e->par.L[d]))
      return sbi_error(SB_EINVAL, __func__, "inlet [%g, %g] along %c: must "
                       "satisfy 0 <= lo < hi <= L = %g", in->lo[q],
                       in->hi[q], "xyz"[d], e->par.L[d]);
    q++;
  }
  if (un * e->par.dt >= e->par.L[k])
    return sbi_error(SB_EINVAL, __func__, "face %d: u_n dt = %g m crosses "
                     "the box (L = %g m)", in->face, un * e->par.dt,
                     e->par.L[k]);
  /* the slot's counters stay: 0 in a new engine, the saved ones in an
   * engine loaded from a checkpoint (its inflows added again in order) */
  e->inflow[e->ninflow] = *in;
  if (idx)
    *idx = e->ninflow;
  e->ninflow++;
  return SB_SUCCESS;
}

size_t sb_engine_ninflows(const sb_engine *e)
{
  if (!e) {
    sbi_error(SB_EINVAL, __func__, "engine is NULL");
    return 0;
  }
  return e->ninflow;
}

uint64_t sb_engine_inflow_injected(const sb_engine *e, size_t k)
{
  if (!e) {
    sbi_error(SB_EINVAL, __func__, "engine is NULL");
    return 0;
  }
  return k < e->ninflow ? e->ninj[k] : 0;
}

uint64_t sb_engine_inflow_skipped(const sb_engine *e, size_t k)
{
  if (!e) {
    sbi_error(SB_EINVAL, __func__, "engine is NULL");
    return 0;
  }
  return k < e->ninflow ? e->nskip[k] : 0;
}

uint64_t sb_engine_outflows(const sb_engine *e, int face)
{
  if (!e) {
    sbi_error(SB_EINVAL, __func__, "engine is NULL");
    return 0;
  }
  return (face >= 0 && face < 6) ? e->nout[face] : 0;
}

int sb_engine_set_outflow_fn(sb_engine *e, sb_engine_outflow_fn fn,
                             void *ctx)
{
  if (!e)
    return sbi_error(SB_EINVAL, __func__, "engine is NULL");
  e->outflow_fn = fn;
  e->outflow_ctx = fn ? ctx : NULL;
  return SB_SUCCESS;
}

int sbi_engine_outflow(sb_engine *e, size_t i, int face)
{
  const int k = face / 2;
  e->nout[face]++;
  if (e->outflow_fn) {
    /* when the straight chord crossed the face (the end if it did not:
     * a bridge-detected excursion) */
    const double L = face % 2 ? e->par.L[k] : 0.0;
    const double y0 = e->x0[3 * i + k], y1 = e->x[3 * i + k];
    double s = 1.0;
    if ((face % 2 && y1 >= L) || (!(face % 2) && y1 <= L))
      s = y1 != y0 ? (L - y0) / (y1 - y0) : 1.0;
    s = s < 0.0 ? 0.0 : (s > 1.0 ? 1.0 : s);
    int st = e->outflow_fn(e, i, face, e->t + s * e->par.dt, e->outflow_ctx);
    if (st)
      return sbi_error(st, "sb_engine_step", "outflow callback returned %d",
                       st);
  }
  e->hit[i] = 2;  /* removed with the others at the end of the pass */
  e->nremove++;
  return SB_SUCCESS;
}

/* Does a particle of radius r at x overlap one of the box's particles? */
static int overlaps(const sb_engine *e, const double x[3], double r)
{
  const int dim = e->par.dim;
  for (size_t j = 0; j < e->n; j++) {
    double d2 = 0.0;
    for (int d = 0; d < dim; d++) {
      double v = x[d] - e->x[3 * j + d];
      if (e->wall[2 * d] == SB_WALL_PERIODIC)
        v = sbi_minimg(v, e->par.L[d]);
      d2 += v * v;
    }
    const double s = r + e->radius[j];
    if (d2 < s * s)
      return 1;
  }
  return 0;
}

/* An arrival's flight over the h = s dt since its entry from x (on the face)
 * with the inflow velocity: straight for free flight (tau = inf), else the
 * mean path of the exact Langevin step with linear drag towards the fluid
 * velocity U at the entry point (plus the settling velocity),
 *   u = U + (u0 - U) e^{-h/tau},  x += U h + (u0 - U) tau (1 - e^{-h/tau}),
 * exact for a non-Brownian particle under Stokes drag in a uniform field;
 * the noise over h is left out (it is O(sqrt(h)) against a step's). */
static int flight(sb_engine *e, const sb_engine_inflow *in, double tau,
                  double s, double dt, double x[3], double u[3])
{
  const int dim = e->par.dim;
  if (!isfinite(tau)) {
    for (int d = 0; d < dim; d++)
      x[d] += in->u[d] * s * dt;
    return SB_SUCCESS;
  }
  const double h = s * dt;
  double U[3];
  int st = sbi_engine_fluid_eval(e, 1, x, U, SIZE_MAX, "sb_engine_step");
  if (st)
    return st;
  const double *vs;
  if ((st = sbi_engine_settling(e, in->species, &vs, "sb_engine_step")))
    return st;
  const double decay = exp(-h / tau), grow = -tau * expm1(-h / tau);
  for (int d = 0; d < dim; d++) {
    const double Ud = U[d] + (vs ? vs[d] : 0.0);
    x[d] += Ud * h + (in->u[d] - Ud) * grow;
    u[d] = Ud + (in->u[d] - Ud) * decay;
  }
  return SB_SUCCESS;
}

int sbi_engine_inject(sb_engine *e)
{
  const int dim = e->par.dim;
  const double dt = e->par.dt;
  for (size_t q = 0; q < e->ninflow; q++) {
    const sb_engine_inflow *in = &e->inflow[q];
    const int k = in->face / 2, hi = in->face % 2;
    const double r = e->spec[in->species].radius;
    /* a mean far beyond the room left cannot fit (and GSL's Poisson draw
     * takes minutes at 1e24): the capacity error at once */
    const double mean = in->rate * dt,
                 room = (double)(e->par.capacity - e->n);
    if (mean > room + 100.0 * sqrt(room + 1.0) + 100.0)
      return sbi_error(SB_EINVAL, "sb_engine_step", "inflow %zu brings "
                       "%g particles a step on average: capacity %zu is "
                       "full", q, mean, e->par.capacity);
    unsigned int m = in->rate > 0.0 ? gsl_ran_poisson(e->rng, mean) : 0;
    const double tau = e->spec[in->species].tau;
    for (unsigned int a = 0; a < m; a++) {
      double x[3] = {0, 0, 0}, u[3] = {in->u[0], in->u[1], in->u[2]};
      int placed = 0;
      for (int tries = 0; tries < 100 && !placed; tries++) {
        const double s = gsl_rng_uniform(e->rng);  /* since entry, / dt */
        for (int d = 0, c = 0; d < dim; d++) {
          if (d == k) {
            x[d] = hi ? e->par.L[d] : 0.0;
            continue;
          }
          x[d] = in->lo[c] + (in->hi[c] - in->lo[c]) * gsl_rng_uniform(e->rng);
          c++;
        }
        int st = flight(e, in, tau, s, dt, x, u);
        if (st)
          return st;
        for (int d = 0; d < dim; d++)
          if (d != k && e->wall[2 * d] == SB_WALL_PERIODIC)
            x[d] = sbi_wrap(x[d], e->par.L[d]);
        placed = 1;
        /* beyond a wall across the stream: not placed */
        for (int d = 0; d < dim; d++)
          if (d != k && e->wall[2 * d] != SB_WALL_PERIODIC &&
              (x[d] < 0.0 || x[d] >= e->par.L[d]))
            placed = 0;
        if (placed && in->no_overlap && overlaps(e, x, r))
          placed = 0;
        if (!in->no_overlap)
          break;
      }
      if (!placed) {
        e->nskip[q]++;
        continue;
      }
      /* an arrival's flight that leaves the doubles, or lands too far
       * out to be wrapped into the box (a fluid velocity near DBL_MAX):
       * not placed, SB_ERANGE as an overflowing step */
      for (int d = 0; d < dim; d++)
        if (!sbi_wrappable(x[d], e->par.L[d]) || !isfinite(u[d]))
          return sbi_error(SB_ERANGE, "sb_engine_step", "inflow %zu: an "
                           "arrival's flight from its entry point gave x[%d] "
                           "= %g, u[%d] = %g (%s)", q, d, x[d], d, u[d],
                           isfinite(x[d]) && isfinite(u[d])
                               ? "too far out to be wrapped into the box"
                               : "not finite");
      int st = sb_engine_add_particle(e, in->species, in->family, x, u);
      if (st)
        return st;
      e->ninj[q]++;
    }
  }
  return SB_SUCCESS;
}
