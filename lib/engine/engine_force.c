/* engine_force.c — external acceleration (gravity with buoyancy),
 * per-species fluid properties and drag laws (docs/engine_forces.md).
 *
 * Gravity.  A particle of species s (density rho_p = m / (4 pi r^3 / 3))
 * in a fluid of density rho_f feels g' = g (1 - rho_f / rho_p).  With
 * Stokes drag the Langevin equation du = (U_s - u)/tau dt + g' dt + B dW
 * is the one without gravity with the fluid velocity U_s + tau g', so the
 * exact step of Mohaupt (2011, eq 1.16) stays exact: the transport adds
 * the settling velocity v_s = tau g' to U_s.
 *
 * Nonlinear drag.  du/dt = -lambda(|u - U_s|) (u - U_s) + g', lambda(v) =
 * f(Re(v)) / tau, Re = rho_f v d / mu, non-Brownian particles, fluid
 * velocity frozen at the start position over the step.  For a constant
 * rate lambda the step is exact (terminal slip v_t = g'/lambda):
 *   u(h) = U_s + v_t + (u0 - U_s - v_t) e^{-lambda h},
 *   x(h) = x0 + (U_s + v_t) h + (u0 - U_s - v_t)(1 - e^{-lambda h})/lambda.
 * The scheme: lambda0 = lambda(u0); a predictor with lambda0 gives u*;
 * lambda1 = lambda(u*); the step is the exact linear one with the mean
 * (lambda0 + lambda1)/2.  The rate along the true path is lambda0 +
 * lambda' t + O(t^2), whose integral over the step the trapezoid gets to
 * O(h^3): local error O(h^3), so the scheme is of second order
 * (tests/test_engine_physics.c measures the error ratio 4 per halving), it
 * is exact for Stokes drag (f = 1), keeps the terminal velocity exactly
 * (a steady slip is a fixed point) and is stable at every dt/tau (an
 * exponential integrator).
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_math.h>

#include "common/internal.h"
#include "common/numutil.h"
#include "engine_internal.h"

/* ============================================================ drag laws */

double sb_drag_factor(sb_engine_drag law, double Re)
{
  if (!(Re >= 0.0) || !isfinite(Re)) {
    sbi_error(SB_EDOM, __func__, "Re = %g: must be finite >= 0", Re);
    return NAN;
  }
  switch (law) {
  case SB_DRAG_STOKES:
    return 1.0;
  case SB_DRAG_SCHILLER_NAUMANN:
    /* Schiller & Naumann (1933) up to Re = 1000, then C_D = 0.44 */
    return Re <= 1000.0 ? 1.0 + 0.15 * pow(Re, 0.687) : 0.44 * Re / 24.0;
  }
  sbi_error(SB_EDOM, __func__, "unknown drag law %d", (int)law);
  return NAN;
}

static const sb_engine_species_fluid FLUID_DEFAULT = {SB_DRAG_STOKES, 0.0,
                                                      0.0};

static const sb_engine_species_fluid *sfl_of(const sb_engine *e, size_t sp)
{
  return sp < e->nsfl ? &e->sfl[sp] : &FLUID_DEFAULT;
}

static double rho_p(const sb_engine *e, size_t sp)
{
  const double r = e->spec[sp].radius;
  return e->spec[sp].mass / (4.0 / 3.0 * M_PI * r * r * r);
}

int sb_engine_set_species_fluid(sb_engine *e, size_t sp,
                                const sb_engine_species_fluid *f)
{
  if (!e || !f)
    return sbi_error(SB_EINVAL, __func__, "NULL argument");
  if (sp >= e->nspec)
    return sbi_error(SB_EINVAL, __func__, "species %zu does not exist", sp);
  if ((unsigned)f->drag > SB_DRAG_SCHILLER_NAUMANN)
    return sbi_error(SB_EINVAL, __func__, "drag law %d: unknown",
                     (int)f->drag);
  if (!(f->rho_f >= 0.0) || !isfinite(f->rho_f))
    return sbi_error(SB_EINVAL, __func__, "rho_f = %g: must be finite >= 0",
                     f->rho_f);
  if (!(f->mu >= 0.0) || !isfinite(f->mu))
    return sbi_error(SB_EINVAL, __func__, "mu = %g: must be finite >= 0",
                     f->mu);
  if (f->drag != SB_DRAG_STOKES) {
    const sb_engine_species *s = &e->spec[sp];
    if (!(f->mu > 0.0))
      return sbi_error(SB_EINVAL, __func__,
                       "a nonlinear drag law needs the viscosity mu > 0");
    if (isinf(s->tau) || s->B != 0.0)
      return sbi_error(SB_EINVAL, __func__,
                       "species %zu: a nonlinear drag law needs a finite "
                       "tau_p and B = 0 (non-Brownian)", sp);
  }
  if (sp >= e->nsfl) {
    sb_engine_species_fluid *n = realloc(e->sfl, e->nspec * sizeof *n);
    if (!n)
      return sbi_error(SB_ENOMEM, __func__, "out of memory");
    for (size_t k = e->nsfl; k < e->nspec; k++)
      n[k] = FLUID_DEFAULT;
    e->sfl = n;
    e->nsfl = e->nspec;
  }
  e->sfl[sp] = *f;
  e->nonlin = 0;
  for (size_t k = 0; k < e->nsfl; k++)
    if (e->sfl[k].drag != SB_DRAG_STOKES)
      e->nonlin = 1;
  e->nvset = 0;  /* settling velocities are stale */
  return SB_SUCCESS;
}

int sb_engine_get_species_fluid(const sb_engine *e, size_t sp,
                                sb_engine_species_fluid *f)
{
  if (!e || !f || sp >= e->nspec)
    return sbi_error(SB_EINVAL, __func__, "bad engine, species or NULL");
  *f = *sfl_of(e, sp);
  return SB_SUCCESS;
}

int sb_engine_set_gravity(sb_engine *e, const double g[3])
{
  if (!e || !g)
    return sbi_error(SB_EINVAL, __func__, "NULL argument");
  for (int k = 0; k < 3; k++)
    if (!isfinite(g[k]))
      return sbi_error(SB_EINVAL, __func__, "g[%d] = %g: not finite", k,
                       g[k]);
  e->has_grav = 0;
  for (int k = 0; k < 3; k++) {
    e->grav[k] = k < e->par.dim ? g[k] : 0.0;
    if (e->grav[k] != 0.0)
      e->has_grav = 1;
  }
  e->nvset = 0;
  return SB_SUCCESS;
}

int sb_engine_get_gravity(const sb_engine *e, double g[3])
{
  if (!e || !g)
    return sbi_error(SB_EINVAL, __func__, "NULL argument");
  memcpy(g, e->grav, 3 * sizeof(double));
  return SB_SUCCESS;
}

/* Buoyant acceleration of species sp. */
static void gprime(const sb_engine *e, size_t sp, double a[3])
{
  const double f = 1.0 - sfl_of(e, sp)->rho_f / rho_p(e, sp);
  for (int k = 0; k < 3; k++)
    a[k] = e->grav[k] * f;
}

typedef struct {
  const sb_engine_species_fluid *fl;
  double d, tau, vst;  /* diameter, tau_p, Stokes terminal speed */
} term_par;

static double term_fn(double v, void *vp)
{
  const term_par *q = vp;
  double Re = q->fl->rho_f * v * q->d / q->fl->mu;
  return v * sb_drag_factor(q->fl->drag, Re) - q->vst;
}

/* Speed v >= 0 with f(Re(v)) v = vst (Brent; f >= 1 so v <= vst). */
static int terminal_speed(const sb_engine *e, size_t sp, double vst,
                          double *v, const char *who)
{
  const sb_engine_species_fluid *fl = sfl_of(e, sp);
  if (fl->drag == SB_DRAG_STOKES || vst == 0.0 || fl->rho_f == 0.0) {
    *v = vst;
    return SB_SUCCESS;
  }
  term_par q = {fl, 2.0 * e->spec[sp].radius, e->spec[sp].tau, vst};
  gsl_function F = {term_fn, &q};
  double r;
  int st = sbi_brent(&F, 0.0, vst, 0.0, 1e-14, 200, &r);
  if (st == SB_ENOMEM)
    return sbi_error(SB_ENOMEM, who, "out of memory");
  if (st || !isfinite(r))
    return sbi_error(SB_EMAXITER, who,
                     "no terminal velocity for species %zu", sp);
  *v = r;
  return SB_SUCCESS;
}

/* sb_engine_settling_velocity for the public function who */
static int settling_velocity(const sb_engine *e, size_t sp, double v[3],
                             const char *who)
{
  if (!e || !v || sp >= e->nspec)
    return sbi_error(SB_EINVAL, who, "bad engine, species or NULL");
  const sb_engine_species *s = &e->spec[sp];
  memset(v, 0, 3 * sizeof(double));
  if (!e->has_grav)
    return SB_SUCCESS;
  if (isinf(s->tau))
    return sbi_error(SB_EINVAL, who,
                     "species %zu is in free flight: no settling velocity",
                     sp);
  double a[3];
  gprime(e, sp, a);
  double na = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
  if (na == 0.0)
    return SB_SUCCESS;
  double sp_ = 0.0;
  int st = terminal_speed(e, sp, s->tau * na, &sp_, who);
  if (st)
    return st;
  for (int k = 0; k < 3; k++)
    v[k] = sp_ * a[k] / na;
  return SB_SUCCESS;
}

int sb_engine_settling_velocity(const sb_engine *e, size_t sp, double v[3])
{
  return settling_velocity(e, sp, v, __func__);
}

/* ============================================================ step hooks */

int sbi_engine_physics_prepare(sb_engine *e, const char *fn)
{
  if (e->lees) {
    if (e->fluid != SB_FLUID_SHEAR)
      return sbi_error(SB_EINVAL, fn, "Lees-Edwards boundaries need the "
                       "built-in shear field");
    if (e->wall[2] != SB_WALL_PERIODIC || e->wall[3] != SB_WALL_PERIODIC ||
        e->wall[0] != SB_WALL_PERIODIC || e->wall[1] != SB_WALL_PERIODIC)
      return sbi_error(SB_EINVAL, fn, "Lees-Edwards boundaries need x and "
                       "y periodic");
    /* every detector sees image-aware pair records (and the Langevin
     * detector image-aware states), the first detection and the
     * re-detection after an outcome alike, and the outcomes take j's
     * image velocity (engine_lees.c): every outcome works */
  }
  if (e->has_grav)
    for (size_t k = 0; k < e->nspec; k++)
      if (isinf(e->spec[k].tau))
        return sbi_error(SB_EINVAL, fn, "gravity with a free-flight species "
                         "(%zu, tau = inf) is not supported", k);
  if (e->has_grav && e->nvset != e->nspec) {
    double *v = realloc(e->vset, 3 * (e->nspec ? e->nspec : 1) * sizeof *v);
    if (!v)
      return sbi_error(SB_ENOMEM, fn, "out of memory");
    e->vset = v;
    for (size_t k = 0; k < e->nspec; k++) {
      int st = settling_velocity(e, k, &v[3 * k], fn);
      if (st)
        return st;
    }
    e->nvset = e->nspec;
  }
  return SB_SUCCESS;
}

int sbi_engine_settling(sb_engine *e, size_t sp, const double **vs,
                        const char *who)
{
  *vs = NULL;
  if (!e->has_grav)
    return SB_SUCCESS;
  int st = sbi_engine_physics_prepare(e, who);
  if (st)
    return st;
  if (sp >= e->nvset)
    return sbi_error(SB_EINVAL, who, "species %zu does not exist", sp);
  *vs = &e->vset[3 * sp];
  return SB_SUCCESS;
}

/* Exact step of du/dt = -lam (u - w) + a from (x0, u0) over h. */
static void linear_step(double lam, double h, const double *w,
                        const double *a, const double *x0, const double *u0,
                        double *x, double *u)
{
  const double em = expm1(-lam * h);  /* e^{-lam h} - 1 */
  for (int k = 0; k < 3; k++) {
    const double vt = a[k] / lam, s0 = u0[k] - w[k] - vt;
    u[k] = w[k] + vt + s0 * (1.0 + em);
    x[k] = x0[k] + (w[k] + vt) * h - s0 * em / lam;
  }
}

static double rate(const sb_engine_species_fluid *fl, double tau, double d,
                   const double *u, const double *w)
{
  double v2 = 0.0;
  for (int k = 0; k < 3; k++)
    v2 += (u[k] - w[k]) * (u[k] - w[k]);
  return sb_drag_factor(fl->drag, fl->rho_f * sqrt(v2) * d / fl->mu) / tau;
}

/* Particle i's second-order exponential step over h from (x0, u0) (file
 * comment) into (x, u); returns its rate. */
static double drag_one(const sb_engine *e, size_t i, double h,
                       const double *x0, const double *u0, double *x,
                       double *u)
{
  const size_t sp = e->species[i];
  const sb_engine_species_fluid *fl = sfl_of(e, sp);
  const double tau = e->spec[sp].tau, d = 2.0 * e->radius[i];
  double w[3] = {0, 0, 0}, a[3] = {0, 0, 0}, xs[3], us_[3];
  if (e->fluid != SB_FLUID_REST)
    memcpy(w, &e->us[3 * i], sizeof w);
  if (e->has_grav)
    gprime(e, sp, a);
  double l0 = rate(fl, tau, d, u0, w);
  linear_step(l0, h, w, a, x0, u0, xs, us_);
  double l1 = rate(fl, tau, d, us_, w);
  const double lam = 0.5 * (l0 + l1);
  linear_step(lam, h, w, a, x0, u0, x, u);
  for (int k = e->par.dim; k < 3; k++)
    x[k] = u[k] = 0.0;
  return lam;
}

int sbi_engine_nonlinear(const sb_engine *e, size_t k)
{
  return e->nonlin && sfl_of(e, e->species[k])->drag != SB_DRAG_STOKES;
}

/* The nonlinear-drag species' step (file comment); overwrites their end
 * states and chords, and keeps their rates.  A new x or u that is not
 * finite (a state or fluid velocity near DBL_MAX, a rate that overflows)
 * undoes the step: SB_ERANGE (sbi_engine_step_overflow). */
static int drag_step(sb_engine *e)
{
  if (e->par.capacity > e->caplam) {
    double *l = realloc(e->lam, e->par.capacity * sizeof *l);
    if (!l)
      return sbi_error(SB_ENOMEM, "sb_engine_step", "out of memory");
    e->lam = l;
    e->caplam = e->par.capacity;
  }
  int bad = 0;
  for (size_t i = 0; i < e->n; i++) {
    if (!sbi_engine_nonlinear(e, i))
      continue;
    const double *x0 = &e->x0[3 * i];
    double *x = &e->x[3 * i], *u = &e->u[3 * i];
    e->lam[i] = drag_one(e, i, e->par.dt, x0, &e->u0[3 * i], x, u);
    for (int k = 0; k < 3; k++)
      e->disp[3 * i + k] = x[k] - x0[k];
    /* y - y is 0, or NaN for an infinite or NaN y */
    bad |= !isfinite((x[0] - x[0]) + (x[1] - x[1]) + (x[2] - x[2]) +
                     (u[0] - u[0]) + (u[1] - u[1]) + (u[2] - u[2]));
  }
  return bad ? sbi_engine_step_overflow(e, "the nonlinear drag step")
             : SB_SUCCESS;
}

int sbi_engine_drag_piece(sb_engine *e, size_t k, double h)
{
  const double xa[3] = {e->x[3 * k], e->x[3 * k + 1], e->x[3 * k + 2]},
               ua[3] = {e->u[3 * k], e->u[3 * k + 1], e->u[3 * k + 2]};
  e->lam[k] = drag_one(e, k, h, xa, ua, &e->x[3 * k], &e->u[3 * k]);
  const double *x = &e->x[3 * k], *u = &e->u[3 * k];
  /* y - y is 0, or NaN for an infinite or NaN y (as drag_step) */
  if (isfinite((x[0] - x[0]) + (x[1] - x[1]) + (x[2] - x[2]) +
               (u[0] - u[0]) + (u[1] - u[1]) + (u[2] - u[2])))
    return SB_SUCCESS;
  return sbi_engine_step_overflow(e, "the nonlinear drag step after a "
                                     "collision");
}

void sbi_engine_relax(const sb_engine *e, size_t k, double *tau,
                      double w[3])
{
  const size_t sp = e->species[k];
  if (!sbi_engine_nonlinear(e, k) || !e->lam) {
    *tau = e->spec[sp].tau;
    for (int c = 0; c < 3; c++)
      w[c] = sbi_engine_w(e, k, c);
    return;
  }
  double a[3] = {0, 0, 0};
  if (e->has_grav)
    gprime(e, sp, a);
  *tau = 1.0 / e->lam[k];
  for (int c = 0; c < 3; c++)
    w[c] = (e->fluid != SB_FLUID_REST ? e->us[3 * k + c] : 0.0) +
           a[c] * *tau;
}

int sbi_engine_after_transport(sb_engine *e)
{
  if (e->nonlin) {
    int st = drag_step(e);
    if (st)
      return st;
    e->dn_ready = 0;  /* new displacements */
  }
  if (e->lees && e->fluid == SB_FLUID_SHEAR) {
    e->dn_ready = 0;
    if (sbi_engine_shear_correct(e))
      return sbi_engine_step_overflow(e, "the exact shear step");
  }
  return SB_SUCCESS;
}
