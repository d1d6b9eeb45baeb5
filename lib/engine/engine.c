/* engine.c — the collision engine: parameters, allocation, species and
 * particles (structure of arrays), fluid velocity, transport (exact
 * Langevin step), run control and accessors.  Neighbour search, detection,
 * outcomes, observers and checkpoints live in the other lib/engine_*.c
 * files; docs/engine.md explains the algorithm. */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_randist.h>
#include <smolbridge/rng.h>

#include "common/internal.h"
#include "engine_internal.h"

/* ============================================================ parameters */

void sb_engine_params_default(sb_engine_params *p)
{
  if (!p) {
    sbi_error(SB_EINVAL, __func__, "params is NULL");
    return;
  }
  memset(p, 0, sizeof *p);
  p->dim = 3;
  p->L[0] = p->L[1] = p->L[2] = 1e-4;
  p->dt = 1e-6;
  p->seed = 1;
  /* the fast exact choice (docs/rng.md): keyed Philox streams for the
   * transport, Philox behind the gsl_rng interface for the rest */
  p->rng_type = sb_rng_philox;
  p->streams = 1;
  p->capacity = 1024;
  p->neigh = SB_NEIGH_CELLS;
  p->detect = SB_DETECT_BALLISTIC;
  p->outcome = SB_OUTCOME_ELASTIC;
  p->eta = 1.0;
  p->sample_every = 0;
}

static int check_params(const sb_engine_params *p, const char *func)
{
  if (!p)
    return sbi_error(SB_EINVAL, func, "params is NULL");
  if (p->dim != 2 && p->dim != 3)
    return sbi_error(SB_EINVAL, func, "dim = %d: must be 2 or 3", p->dim);
  for (int k = 0; k < p->dim; k++)
    if (!(p->L[k] > 0.0) || !isfinite(p->L[k]))
      return sbi_error(SB_EINVAL, func, "L[%d] = %g: must be finite > 0", k,
                       p->L[k]);
  if (!(p->dt > 0.0) || !isfinite(p->dt))
    return sbi_error(SB_EINVAL, func, "dt = %g: must be finite > 0", p->dt);
  if (p->streams != 0 && p->streams != 1)
    return sbi_error(SB_EINVAL, func, "streams = %d: must be 0 or 1",
                     p->streams);
  if (p->threads < 0 || p->threads > 4096)
    return sbi_error(SB_EINVAL, func, "threads = %d: must be in 0..4096",
                     p->threads);
  if (p->capacity == 0 || p->capacity > ((size_t)1 << 40))
    return sbi_error(SB_EINVAL, func, "capacity = %zu: must be in 1..2^40",
                     p->capacity);
  if ((unsigned)p->neigh > SB_NEIGH_BRUTE)
    return sbi_error(SB_EINVAL, func, "neigh = %d: unknown", (int)p->neigh);
  if ((unsigned)p->detect > SB_DETECT_LANGEVIN ||
      p->detect == SB_DETECT_CUSTOM)
    return sbi_error(SB_EINVAL, func,
                     "detect = %d: unknown or custom (use "
                     "sb_engine_set_detector)",
                     (int)p->detect);
  if ((unsigned)p->outcome > SB_OUTCOME_COUNT)
    return sbi_error(SB_EINVAL, func,
                     "outcome = %d: unknown or custom (use "
                     "sb_engine_set_outcome_fn)",
                     (int)p->outcome);
  if (!(p->eta >= 0.0 && p->eta <= 1.0))
    return sbi_error(SB_EINVAL, func, "eta = %g: must be in [0, 1]", p->eta);
  return SB_SUCCESS;
}

/* ============================================================ life cycle */

sb_engine *sb_engine_alloc(const sb_engine_params *p)
{
  if (check_params(p, __func__))
    return NULL;
  sb_engine *e = calloc(1, sizeof *e);
  if (!e) {
    sbi_error(SB_ENOMEM, __func__, "out of memory");
    return NULL;
  }
  e->par = *p;
  if (e->par.dim == 2)
    e->par.L[2] = 1.0;  /* unused; keeps the volume formula uniform */
  size_t c = p->capacity;
  e->x = calloc(3 * c, sizeof(double));
  e->u = calloc(3 * c, sizeof(double));
  e->x0 = calloc(3 * c, sizeof(double));
  e->u0 = calloc(3 * c, sizeof(double));
  e->disp = calloc(3 * c, sizeof(double));
  e->us = calloc(3 * c, sizeof(double));
  e->radius = calloc(c, sizeof(double));
  e->mass = calloc(c, sizeof(double));
  e->species = calloc(c, sizeof(size_t));
  e->family = calloc(c, sizeof(int));
  e->id = calloc(c, sizeof(uint64_t));
  e->hit = calloc(c, 1);
  e->dn = calloc(c, sizeof(double));
  e->xs = calloc(4 * c, sizeof(double));
  e->vl.xb = calloc(3 * c, sizeof(double));
  e->vl.rb = calloc(c, sizeof(double));
  e->vl.idb = calloc(c, sizeof(uint64_t));
  e->vl.isfloat = calloc(c, 1);
  e->vl.floats = calloc(c, sizeof(size_t));
  e->cell_of = calloc(c, sizeof(size_t));
  e->cell_list = calloc(c, sizeof(size_t));
  e->order = calloc(c, sizeof(size_t));
  e->key = calloc(c, sizeof(double));
  e->sub_p = calloc(3 * c, sizeof(double));
  e->sub_v = calloc(3 * c, sizeof(double));
  e->sub_t = calloc(c, sizeof(double));
  e->ver = calloc(c, sizeof(uint32_t));
  e->piece_at = calloc(c, sizeof(uint64_t));
  e->far = calloc(c, sizeof(size_t));
  e->isfar = calloc(c, 1);
  e->lp_x = calloc(3 * c, sizeof(double));
  e->lp_u = calloc(3 * c, sizeof(double));
  e->lp_t = calloc(c, sizeof(double));
  e->rng = gsl_rng_alloc(p->rng_type ? p->rng_type : gsl_rng_mt19937);
  if (!e->x || !e->u || !e->x0 || !e->u0 || !e->disp || !e->us ||
      !e->radius || !e->mass || !e->species || !e->family || !e->id ||
      !e->hit || !e->dn || !e->xs || !e->vl.xb || !e->vl.rb || !e->vl.idb ||
      !e->vl.isfloat || !e->vl.floats || !e->cell_of || !e->cell_list || !e->order ||
      !e->key || !e->sub_p || !e->sub_v || !e->sub_t || !e->ver ||
      !e->piece_at ||
      !e->far || !e->isfar || !e->lp_x || !e->lp_u || !e->lp_t ||
      !e->rng || sbi_engine_langevin_init(e)) {
    sb_engine_free(e);
    sbi_error(SB_ENOMEM, __func__, "out of memory (capacity %zu)", c);
    return NULL;
  }
  gsl_rng_set(e->rng, p->seed);
  e->detect_fn = NULL;
  e->fluid = SB_FLUID_REST;
  return e;
}

void sb_engine_free(sb_engine *e)
{
  if (!e)
    return;
  free(e->x);
  free(e->u);
  free(e->x0);
  free(e->u0);
  free(e->disp);
  free(e->us);
  free(e->radius);
  free(e->mass);
  free(e->species);
  free(e->family);
  free(e->id);
  free(e->hit);
  free(e->spec);
  free(e->coef);
  free(e->vsd);
  free(e->series);
  sbi_idmap_free(&e->cvar_part);
  sbi_idmap_free(&e->cvar_pair);
  free(e->pairs);
  free(e->ev);
  for (int t = 0; t < e->ntb; t++)
    free(e->tb[t].p);
  free(e->tb);
  free(e->wst);
  free(e->dhit);
  free(e->ds);
  free(e->cell_of);
  free(e->cell_start);
  free(e->cell_list);
  free(e->dn);
  free(e->xs);
  free(e->vl.xb);
  free(e->vl.rb);
  free(e->vl.idb);
  free(e->vl.pairs);
  free(e->vl.isfloat);
  free(e->vl.floats);
  free(e->order);
  free(e->key);
  free(e->sub_p);
  free(e->sub_v);
  free(e->sub_t);
  free(e->ver);
  free(e->piece_at);
  free(e->far);
  free(e->isfar);
  free(e->lxm);   /* engine_neigh.c: the Langevin search */
  free(e->lfx);
  free(e->lfl);
  free(e->lcnt);
  free(e->lcc);
  free(e->lds);
  free(e->lfs);
  free(e->lpb.p);
  free(e->lpr2);
  for (int t = 0; t < e->nlpt; t++) {
    free(e->lpt[t].g);
    free(e->lpt[t].pr.p);
  }
  free(e->lpt);
  free(e->lp_x);
  free(e->lp_u);
  free(e->lp_t);
  free(e->sfl);   /* engine_force.c */
  free(e->lam);
  free(e->vset);
  free(e->shn);   /* engine_lees.c */
  sbi_engine_langevin_slots_free(e);
  sb_langevin_hitter_free(e->lh);
  free(e->lacc);
  free(e->lpm);
  if (e->rng)
    gsl_rng_free(e->rng);
  free(e);
}

const sb_engine_params *sb_engine_get_params(const sb_engine *e)
{
  if (!e) {
    sbi_error(SB_EINVAL, __func__, "engine is NULL");
    return NULL;
  }
  return &e->par;
}

/* ============================================================ species */

/* Step coefficients of one species.  Free flight (tau = inf) is the exact
 * limit of the Langevin step: decay 1, gain dt, no noise. */
static int species_coef(const sb_engine_species *s, double dt,
                        sb_langevin_coef *c)
{
  if (isinf(s->tau)) {
    *c = (sb_langevin_coef){dt, 1.0, dt, 0.0, 0.0, 0.0};
    return SB_SUCCESS;
  }
  return sb_langevin_coef_init(c, s->tau, s->B, dt);
}

/* Equilibrium velocity standard deviation per component: sqrt(k_B T / m),
 * or sqrt(B^2 tau / 2) for T = 0 (the stationary variance of the Langevin
 * model, Mohaupt 2011, eq A.4).  The variance as before wherever it is a
 * normal double (the same bits); where it overflows or underflows, the
 * square roots taken first (B sqrt(tau / 2), sqrt(k_B T) / sqrt(m)).
 * SB_ERANGE where the spread itself exceeds DBL_MAX, which only B sqrt(tau
 * / 2) can (sqrt(k_B DBL_MAX) / sqrt(4.9e-324) is 2.2e304). */
static int species_vsd(const sb_engine_species *s, double *vsd)
{
  const double var = s->T > 0.0 ? SB_BOLTZMANN * s->T / s->mass
                                : 0.5 * s->B * s->B * s->tau;
  if (var == 0.0 || (var >= DBL_MIN && var <= DBL_MAX))
    *vsd = sqrt(var);
  else
    *vsd = s->T > 0.0 ? sqrt(SB_BOLTZMANN * s->T) / sqrt(s->mass)
                      : s->B * sqrt(0.5 * s->tau);
  return isfinite(*vsd) ? SB_SUCCESS : SB_ERANGE;
}

int sbi_engine_update_coef(sb_engine *e, size_t *bad)
{
  for (size_t k = 0; k < e->nspec; k++) {
    int st = species_coef(&e->spec[k], e->par.dt, &e->coef[k]);
    if (st) {
      if (bad)
        *bad = k;
      return st;
    }
  }
  return SB_SUCCESS;
}

int sb_engine_add_species(sb_engine *e, const sb_engine_species *s,
                          size_t *idx)
{
  if (!e || !s)
    return sbi_error(SB_EINVAL, __func__, "NULL argument");
  if (!(s->radius > 0.0) || !isfinite(s->radius))
    return sbi_error(SB_EINVAL, __func__, "radius = %g: must be finite > 0",
                     s->radius);
  if (!(s->mass > 0.0) || !isfinite(s->mass))
    return sbi_error(SB_EINVAL, __func__, "mass = %g: must be finite > 0",
                     s->mass);
  if (!(s->tau > 0.0))
    return sbi_error(SB_EINVAL, __func__, "tau = %g: must be > 0 (or inf)",
                     s->tau);
  if (isfinite(s->tau) && (!(s->B >= 0.0) || !isfinite(s->B)))
    return sbi_error(SB_EINVAL, __func__, "B = %g: must be finite >= 0",
                     s->B);
  if (!(s->T >= 0.0) || !isfinite(s->T))
    return sbi_error(SB_EINVAL, __func__, "T = %g: must be finite >= 0",
                     s->T);
  if (isinf(s->tau) && s->T == 0.0)
    return sbi_error(SB_EINVAL, __func__,
                     "free-flight species (tau = inf) needs T > 0");
  sb_langevin_coef c;
  int cst = species_coef(s, e->par.dt, &c);
  if (cst == SB_ERANGE)
    return sbi_error(SB_ERANGE, __func__,
                     "tau = %g, B = %g, dt = %g: a step coefficient of "
                     "the species exceeds DBL_MAX", s->tau, s->B, e->par.dt);
  if (cst)
    return sbi_error(SB_EINVAL, __func__,
                     "tau = %g, B = %g, dt = %g: no Langevin step", s->tau,
                     s->B, e->par.dt);
  double vsd;
  if (species_vsd(s, &vsd))
    return sbi_error(SB_ERANGE, __func__,
                     "B = %g, tau = %g: the velocity spread B sqrt(tau / 2) "
                     "exceeds DBL_MAX", s->B, s->tau);
  if (e->nspec == e->capspec) {
    size_t nc = e->capspec ? 2 * e->capspec : 4;
    sb_engine_species *ns = realloc(e->spec, nc * sizeof *ns);
    if (!ns)
      return sbi_error(SB_ENOMEM, __func__, "out of memory");
    e->spec = ns;
    sb_langevin_coef *ncf = realloc(e->coef, nc * sizeof *ncf);
    if (!ncf)
      return sbi_error(SB_ENOMEM, __func__, "out of memory");
    e->coef = ncf;
    double *nv = realloc(e->vsd, nc * sizeof *nv);
    if (!nv)
      return sbi_error(SB_ENOMEM, __func__, "out of memory");
    e->vsd = nv;
    e->capspec = nc;
  }
  size_t k = e->nspec++;
  e->spec[k] = *s;
  e->coef[k] = c;
  e->vsd[k] = vsd;
  if (s->radius > e->rmax)
    e->rmax = s->radius;
  if (idx)
    *idx = k;
  return SB_SUCCESS;
}

const sb_engine_species *sb_engine_get_species(const sb_engine *e,
                                               size_t idx)
{
  if (!e) {
    sbi_error(SB_EINVAL, __func__, "engine is NULL");
    return NULL;
  }
  /* past the last species: NULL without an error (loops stop on it) */
  return idx < e->nspec ? &e->spec[idx] : NULL;
}

size_t sb_engine_species_count(const sb_engine *e)
{
  if (!e) {
    sbi_error(SB_EINVAL, __func__, "engine is NULL");
    return 0;
  }
  return e->nspec;
}

/* ============================================================ particles */

static void append_particle(sb_engine *e, size_t species, int family,
                            const double x[3], const double u[3]);

int sb_engine_add_particle(sb_engine *e, size_t species, int family,
                           const double x[3], const double u[3])
{
  if (!e || !x || !u)
    return sbi_error(SB_EINVAL, __func__, "NULL argument");
  SBI_NOT_IN_STEP(e, __func__);
  if (e->n >= e->par.capacity)
    return sbi_error(SB_EINVAL, __func__, "capacity %zu is full",
                     e->par.capacity);
  if (species >= e->nspec)
    return sbi_error(SB_EINVAL, __func__, "species %zu does not exist",
                     species);
  if (family < 0 || family >= SB_ENGINE_MAXFAM)
    return sbi_error(SB_EINVAL, __func__, "family = %d: must be in 0..%d",
                     family, SB_ENGINE_MAXFAM - 1);
  for (int k = 0; k < e->par.dim; k++)
    if (!isfinite(x[k]) || !isfinite(u[k]))
      return sbi_error(SB_EINVAL, __func__, "x[%d] = %g, u[%d] = %g: must "
                       "be finite", k, x[k], k, u[k]);
  int st = sbi_engine_check_position(e, x, SIZE_MAX, SB_EINVAL, __func__);
  if (st)
    return st;
  append_particle(e, species, family, x, u);
  return SB_SUCCESS;
}

int sbi_engine_check_position(const sb_engine *e, const double x[3],
                              size_t k, int status, const char *who)
{
  for (int c = 0; c < e->par.dim; c++) {
    if (sbi_wrappable(x[c], e->par.L[c]))
      continue;
    char what[48];
    if (k == SIZE_MAX)
      snprintf(what, sizeof what, "a new particle");
    else
      snprintf(what, sizeof what, "particle %zu", k);
    if (!isfinite(x[c]))
      return sbi_error(status, who, "%s: position x[%d] = %g is not "
                       "finite", what, c, x[c]);
    return sbi_error(status, who, "%s: position x[%d] = %g is more than "
                     "2^26 box lengths (L[%d] = %g m) from the box: it "
                     "cannot be wrapped into the box with its digits",
                     what, c, x[c], c, e->par.L[c]);
  }
  return SB_SUCCESS;
}

/* Append particle n with the next id (arguments checked by the caller). */
static void append_particle(sb_engine *e, size_t species, int family,
                            const double x[3], const double u[3])
{
  size_t i = e->n++;
  for (int k = 0; k < 3; k++) {
    int on = k < e->par.dim;
    e->x[3 * i + k] = on ? sbi_wrap(x[k], e->par.L[k]) : 0.0;
    e->u[3 * i + k] = on ? u[k] : 0.0;
  }
  e->radius[i] = e->spec[species].radius;
  e->mass[i] = e->spec[species].mass;
  e->species[i] = species;
  e->family[i] = family;
  e->id[i] = e->next_id++;
  e->hit[i] = 0;
  e->norder = 0;  /* sweep order must be rebuilt */
}

int sb_engine_set_particle(sb_engine *e, size_t i, const double x[3],
                           const double u[3])
{
  if (!e || !x || !u || i >= e->n)
    return sbi_error(SB_EINVAL, __func__, "bad particle index or NULL");
  for (int k = 0; k < e->par.dim; k++) {
    if (!isfinite(x[k]) || !isfinite(u[k]))
      return sbi_error(SB_EINVAL, __func__, "non-finite state");
  }
  int st = sbi_engine_check_position(e, x, i, SB_EINVAL, __func__);
  if (st)
    return st;
  for (int k = 0; k < e->par.dim; k++) {
    e->x[3 * i + k] = sbi_wrap(x[k], e->par.L[k]);
    e->u[3 * i + k] = u[k];
  }
  return SB_SUCCESS;
}

/* The first component of the n velocities us that is not finite (in 2-D
 * the first two of each), as particle index p and component c; 0 if
 * there is none. */
static int fluid_nonfinite(const sb_engine *e, size_t n, const double *us,
                           size_t *p, int *c)
{
  const int dim = e->par.dim;
  int bad = 0;
  for (size_t i = 0; i < n; i++)  /* y - y is 0, or NaN for inf or NaN */
    bad |= !isfinite((us[3 * i] - us[3 * i]) +
                     (us[3 * i + 1] - us[3 * i + 1]) +
                     (dim == 3 ? us[3 * i + 2] - us[3 * i + 2] : 0.0));
  if (!bad)
    return 0;
  for (size_t i = 0; i < n; i++)
    for (int k = 0; k < dim; k++)
      if (!isfinite(us[3 * i + k])) {
        *p = i;
        *c = k;
        return 1;
      }
  return 0;
}

int sbi_engine_fluid_eval(sb_engine *e, size_t n, const double *x,
                          double *us, size_t first, const char *who)
{
  switch (e->fluid) {
  case SB_FLUID_REST:
    memset(us, 0, 3 * n * sizeof *us);
    return SB_SUCCESS;
  case SB_FLUID_UNIFORM:
    for (size_t i = 0; i < n; i++)
      for (int k = 0; k < 3; k++)
        us[3 * i + k] = k < e->par.dim ? e->fluid_p[k] : 0.0;
    return SB_SUCCESS;
  case SB_FLUID_SHEAR:
    for (size_t i = 0; i < n; i++) {
      us[3 * i] = e->fluid_p[0] * (x[3 * i + 1] - 0.5 * e->par.L[1]);
      us[3 * i + 1] = us[3 * i + 2] = 0.0;
    }
    return SB_SUCCESS;
  case SB_FLUID_CALLBACK: {
    int st = e->fluid_fn(n, x, us, e->fluid_ctx);
    if (st)
      return sbi_error(SB_EINVAL, who, "fluid callback failed (status %d)",
                       st);
    size_t p;
    int c;
    if (fluid_nonfinite(e, n, us, &p, &c)) {
      char what[48];
      if (first == SIZE_MAX)
        snprintf(what, sizeof what, "a new particle");
      else
        snprintf(what, sizeof what, "particle %zu", first + p);
      return sbi_error(SB_EINVAL, who, "the fluid callback returned the "
                       "velocity us[%d] = %g for %s at (%g, %g, %g): not "
                       "finite", c, us[3 * p + c], what, x[3 * p],
                       x[3 * p + 1], x[3 * p + 2]);
    }
    if (e->par.dim == 2)
      for (size_t i = 0; i < n; i++)
        us[3 * i + 2] = 0.0;
    return SB_SUCCESS;
  }
  }
  return sbi_error(SB_EINVAL, who, "unknown fluid field %d", (int)e->fluid);
}

int sbi_engine_equilibrium_velocity(sb_engine *e, size_t sp,
                                    const double x[3], double u[3],
                                    size_t who_k, const char *who)
{
  double us[3], th[3] = {0, 0, 0};
  int st = sbi_engine_fluid_eval(e, 1, x, us, who_k, who);
  if (st)
    return st;
  for (int k = 0; k < 3; k++) {
    if (k < e->par.dim)
      th[k] = gsl_ran_gaussian_ziggurat(e->rng, e->vsd[sp]);
    u[k] = k < e->par.dim ? us[k] + th[k] : 0.0;
  }
  /* with gravity: plus the species' settling velocity (engine_force.c) */
  const double *vs;
  if ((st = sbi_engine_settling(e, sp, &vs, who)))
    return st;
  if (vs)
    for (int k = 0; k < e->par.dim; k++)
      u[k] += vs[k];
  for (int k = 0; k < e->par.dim; k++) {
    if (isfinite(u[k]))
      continue;
    /* the part that is not finite, or the sum that overflowed */
    const double v = vs ? vs[k] : 0.0;
    char why[160];
    if (!isfinite(us[k]))
      snprintf(why, sizeof why, "the fluid field's velocity %g there", us[k]);
    else if (!isfinite(th[k]))
      snprintf(why, sizeof why, "the thermal draw %g from the species' "
               "velocity spread %g m/s", th[k], e->vsd[sp]);
    else if (!isfinite(v))
      snprintf(why, sizeof why, "the species' settling velocity %g", v);
    else
      snprintf(why, sizeof why, "the sum of the fluid field's velocity %g, "
               "the thermal draw %g (spread %g m/s) and the settling "
               "velocity %g", us[k], th[k], e->vsd[sp], v);
    return sbi_error(SB_ERANGE, who, "velocity u[%d] = %g of a new particle of "
                     "species %zu at (%g, %g, %g): not finite (%s)", k, u[k],
                     sp, x[0], x[1], x[2], why);
  }
  return SB_SUCCESS;
}

/* Cell grid for the overlap checks of sb_engine_fill_random. */
typedef struct {
  int nc[3];
  double cs[3];
  size_t *head, *next;
} fill_grid;

static size_t fill_cell(const fill_grid *g, const double *x)
{
  size_t c = 0;
  for (int k = 2; k >= 0; k--) {
    int ck = (int)(x[k] / g->cs[k]);
    if (ck >= g->nc[k])
      ck = g->nc[k] - 1;
    c = c * (size_t)g->nc[k] + (size_t)ck;
  }
  return c;
}

static int fill_free(const sb_engine *e, const fill_grid *g, const double *x,
                     double r)
{
  int c0[3], off[3][3], noff[3];
  for (int k = 0; k < 3; k++) {
    c0[k] = (int)(x[k] / g->cs[k]);
    if (c0[k] >= g->nc[k])
      c0[k] = g->nc[k] - 1;
    /* neighbour offsets, without repeats when there are < 3 cells */
    noff[k] = g->nc[k] >= 3 ? 3 : g->nc[k];
    for (int o = 0; o < noff[k]; o++)
      off[k][o] = g->nc[k] >= 3 ? o - 1 : o;
  }
  for (int a = 0; a < noff[0]; a++)
    for (int b = 0; b < noff[1]; b++)
      for (int d = 0; d < noff[2]; d++) {
        int cc[3] = {c0[0] + off[0][a], c0[1] + off[1][b],
                     c0[2] + off[2][d]};
        size_t c = 0;
        for (int k = 2; k >= 0; k--) {
          int v = ((cc[k] % g->nc[k]) + g->nc[k]) % g->nc[k];
          c = c * (size_t)g->nc[k] + (size_t)v;
        }
        for (size_t j = g->head[c]; j != SIZE_MAX; j = g->next[j]) {
          double d2 = 0.0;
          for (int k = 0; k < e->par.dim; k++) {
            double dk = sbi_minimg(x[k] - e->x[3 * j + k], e->par.L[k]);
            d2 += dk * dk;
          }
          double sg = r + e->radius[j];
          if (d2 < sg * sg)
            return 0;
        }
      }
  return 1;
}

/* sb_engine_fill_box for the public function who.  All or nothing: the
 * particles are appended as they are placed (each new one is an obstacle
 * for the next), and on any failure the engine is put back as it was,
 * its particle number, id counter and sweep order (the arrays below the
 * old number were not touched); the generator has advanced. */
static int fill_region(sb_engine *e, size_t species, int family, size_t n,
                       const double lo[3], const double hi[3],
                       const double drift[3], const char *who)
{
  if (!e || !lo || !hi)
    return sbi_error(SB_EINVAL, who, "NULL argument");
  SBI_NOT_IN_STEP(e, who);
  for (int k = 0; k < e->par.dim; k++) {
    if (!(lo[k] >= 0.0 && lo[k] < hi[k] && hi[k] <= e->par.L[k]))
      return sbi_error(SB_EINVAL, who,
                       "region [%g, %g] in direction %d: need 0 <= lo < hi "
                       "<= L = %g", lo[k], hi[k], k, e->par.L[k]);
    if (drift && !isfinite(drift[k]))
      return sbi_error(SB_EINVAL, who, "drift[%d] = %g: not finite", k,
                       drift[k]);
  }
  if (species >= e->nspec)
    return sbi_error(SB_EINVAL, who, "species %zu does not exist",
                     species);
  if (family < 0 || family >= SB_ENGINE_MAXFAM)
    return sbi_error(SB_EINVAL, who, "family = %d: must be in 0..%d",
                     family, SB_ENGINE_MAXFAM - 1);
  if (n > e->par.capacity - e->n)
    return sbi_error(SB_EINVAL, who, "%zu particles exceed the "
                     "capacity %zu (holding %zu)", n, e->par.capacity, e->n);
  if (n == 0)
    return SB_SUCCESS;
  const size_t n0 = e->n, norder0 = e->norder;
  const uint64_t next_id0 = e->next_id;
  const int dim = e->par.dim;
  const double r = e->spec[species].radius;
  fill_grid g = {{1, 1, 1}, {1, 1, 1}, NULL, NULL};
  /* cells of edge >= 2 rmax, at most ~2 cells per particle */
  double cs = 2.0 * (e->rmax > r ? e->rmax : r);
  double vol = 1.0;
  for (int k = 0; k < dim; k++)
    vol *= e->par.L[k];
  double ntot = (double)(e->n + n) + 1.0;
  double csmin = pow(vol / (2.0 * ntot), 1.0 / dim);
  if (cs < csmin)
    cs = csmin;
  size_t ncell = 1;
  for (int k = 0; k < 3; k++) {
    if (k < dim) {
      double m = floor(e->par.L[k] / cs);
      g.nc[k] = m < 1 ? 1 : (m > 1e6 ? 1000000 : (int)m);
      g.cs[k] = e->par.L[k] / g.nc[k];
    } else {
      g.nc[k] = 1;
      g.cs[k] = 1e300;
    }
    ncell *= (size_t)g.nc[k];
  }
  g.head = malloc(ncell * sizeof(size_t));
  g.next = malloc((e->n + n) * sizeof(size_t));
  if (!g.head || !g.next) {
    free(g.head);
    free(g.next);
    return sbi_error(SB_ENOMEM, who, "out of memory");
  }
  for (size_t c = 0; c < ncell; c++)
    g.head[c] = SIZE_MAX;
  for (size_t j = 0; j < e->n; j++) {
    size_t c = fill_cell(&g, &e->x[3 * j]);
    g.next[j] = g.head[c];
    g.head[c] = j;
  }
  int st = SB_SUCCESS;
  for (size_t a = 0; a < n && !st; a++) {
    double x[3] = {0, 0, 0}, u[3];
    size_t tries = 0;
    for (;;) {
      for (int k = 0; k < dim; k++)
        x[k] = lo[k] + (hi[k] - lo[k]) * gsl_rng_uniform(e->rng);
      if (fill_free(e, &g, x, r))
        break;
      if (++tries >= 10000) {
        st = sbi_error(SB_EMAXITER, who,
                       "no free position after 10000 tries (box too full)");
        break;
      }
    }
    if (st)
      break;
    st = sbi_engine_equilibrium_velocity(e, species, x, u, SIZE_MAX, who);
    if (st)
      break;
    for (int k = 0; k < dim && drift; k++) {
      const double ue = u[k];
      u[k] += drift[k];
      if (!isfinite(u[k])) {
        st = sbi_error(SB_ERANGE, who, "velocity u[%d] = %g of a new "
                       "particle: not finite (the equilibrium velocity %g "
                       "plus the drift %g)", k, u[k], ue, drift[k]);
        break;
      }
    }
    if (st)
      break;
    append_particle(e, species, family, x, u);
    size_t j = e->n - 1, c = fill_cell(&g, &e->x[3 * j]);
    g.next[j] = g.head[c];
    g.head[c] = j;
  }
  free(g.head);
  free(g.next);
  if (st) {  /* all or nothing */
    e->n = n0;
    e->next_id = next_id0;
    e->norder = norder0;
  }
  return st;
}

int sb_engine_fill_random(sb_engine *e, size_t species, int family, size_t n)
{
  if (!e)
    return sbi_error(SB_EINVAL, __func__, "engine is NULL");
  double lo[3] = {0, 0, 0};
  return fill_region(e, species, family, n, lo, e->par.L, NULL, __func__);
}

int sb_engine_fill_box(sb_engine *e, size_t species, int family, size_t n,
                       const double lo[3], const double hi[3],
                       const double drift[3])
{
  return fill_region(e, species, family, n, lo, hi, drift, __func__);
}

double sb_engine_kinetic_energy(const sb_engine *e, double p[3])
{
  double ek = 0.0, pm[3] = {0, 0, 0};
  if (!e) {
    if (p)
      p[0] = p[1] = p[2] = NAN;
    sbi_error(SB_EINVAL, __func__, "engine is NULL");
    return NAN;
  }
  for (size_t i = 0; i < e->n; i++) {
    const double *u = &e->u[3 * i];
    ek += 0.5 * e->mass[i] * (u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    for (int k = 0; k < 3; k++)
      pm[k] += e->mass[i] * u[k];
  }
  if (p)
    for (int k = 0; k < 3; k++)
      p[k] = pm[k];
  return ek;
}

int sb_engine_thermalize(sb_engine *e, double T)
{
  if (!e || !isfinite(T))
    return sbi_error(SB_EINVAL, __func__, "NULL engine or non-finite T");
  if (e->n < 2)
    return sbi_error(SB_EINVAL, __func__, "needs at least 2 particles");
  double M = 0.0, p[3];
  sb_engine_kinetic_energy(e, p);
  for (size_t i = 0; i < e->n; i++)
    M += e->mass[i];
  for (size_t i = 0; i < e->n; i++)
    for (int k = 0; k < e->par.dim; k++)
      e->u[3 * i + k] -= p[k] / M;
  if (T > 0.0) {
    double ek = sb_engine_kinetic_energy(e, NULL);
    if (!(ek > 0.0))
      return sbi_error(SB_EINVAL, __func__, "all particles at rest");
    /* equipartition over dim (N - 1) degrees of freedom (total momentum
     * fixed at 0) */
    double want = 0.5 * e->par.dim * (double)(e->n - 1) * SB_BOLTZMANN * T;
    double f = sqrt(want / ek);
    for (size_t i = 0; i < 3 * e->n; i++)
      e->u[i] *= f;
  }
  return SB_SUCCESS;
}

/* ============================================================ settings */

int sb_engine_set_neigh(sb_engine *e, sb_engine_neigh m)
{
  if (!e || (unsigned)m > SB_NEIGH_BRUTE)
    return sbi_error(SB_EINVAL, __func__, "bad engine or method %d", (int)m);
  e->par.neigh = m;
  return SB_SUCCESS;
}

int sb_engine_set_detect(sb_engine *e, sb_engine_detect d)
{
  if (!e || (unsigned)d > SB_DETECT_LANGEVIN || d == SB_DETECT_CUSTOM)
    return sbi_error(SB_EINVAL, __func__, "bad engine or detector %d",
                     (int)d);
  e->par.detect = d;
  e->detect_fn = NULL;
  e->detect_reach = 0.0;
  e->detect_chord = 0;
  sbi_engine_set_observer(e, NULL, NULL, NULL);
  return SB_SUCCESS;
}

int sb_engine_set_detector_chord(sb_engine *e, int on)
{
  if (!e || e->par.detect != SB_DETECT_CUSTOM)
    return sbi_error(SB_EINVAL, __func__, "no custom detector");
  e->detect_chord = on != 0;
  return SB_SUCCESS;
}

int sb_engine_set_redetect(sb_engine *e, int on)
{
  if (!e)
    return sbi_error(SB_EINVAL, __func__, "engine is NULL");
  e->redetect = on != 0;
  return SB_SUCCESS;
}

int sb_engine_set_detector(sb_engine *e, sb_engine_detect_fn fn, void *ctx,
                           double reach)
{
  if (!e || !fn || !(reach >= 0.0) || !isfinite(reach))
    return sbi_error(SB_EINVAL, __func__, "bad engine, callback or reach");
  e->par.detect = SB_DETECT_CUSTOM;
  e->detect_fn = fn;
  e->detect_chord = 0;
  e->detect_ctx = ctx;
  e->detect_reach = reach;
  sbi_engine_set_observer(e, NULL, NULL, NULL);
  return SB_SUCCESS;
}

int sb_engine_set_outcome(sb_engine *e, sb_engine_outcome o, double eta)
{
  if (!e || (unsigned)o > SB_OUTCOME_COUNT)
    return sbi_error(SB_EINVAL, __func__, "bad engine or outcome %d",
                     (int)o);
  if (!(eta >= 0.0 && eta <= 1.0))
    return sbi_error(SB_EINVAL, __func__, "eta = %g: must be in [0, 1]",
                     eta);
  e->par.outcome = o;
  e->par.eta = eta;
  e->outcome_fn = NULL;
  return SB_SUCCESS;
}

int sb_engine_set_outcome_fn(sb_engine *e, sb_engine_outcome_fn fn,
                             void *ctx)
{
  if (!e || !fn)
    return sbi_error(SB_EINVAL, __func__, "NULL engine or callback");
  e->par.outcome = SB_OUTCOME_CUSTOM;
  e->outcome_fn = fn;
  e->outcome_ctx = ctx;
  return SB_SUCCESS;
}

int sb_engine_set_fluid(sb_engine *e, sb_engine_fluid f, const double p[3])
{
  if (!e || f == SB_FLUID_CALLBACK || (unsigned)f > SB_FLUID_CALLBACK)
    return sbi_error(SB_EINVAL, __func__,
                     "bad engine or field %d (callbacks: "
                     "sb_engine_set_fluid_fn)",
                     (int)f);
  double q[3] = {0, 0, 0};
  if (p)
    for (int k = 0; k < 3; k++) {
      if (!isfinite(p[k]))
        return sbi_error(SB_EINVAL, __func__, "p[%d] = %g: not finite", k,
                         p[k]);
      q[k] = p[k];
    }
  e->fluid = f;
  memcpy(e->fluid_p, q, sizeof q);
  e->fluid_fn = NULL;
  return SB_SUCCESS;
}

int sb_engine_get_fluid(const sb_engine *e, sb_engine_fluid *f, double p[3],
                        int *lees)
{
  if (!e)
    return sbi_error(SB_EINVAL, __func__, "engine is NULL");
  if (f)
    *f = e->fluid;
  if (p)
    for (int k = 0; k < 3; k++)
      p[k] = e->fluid == SB_FLUID_UNIFORM || e->fluid == SB_FLUID_SHEAR
                 ? e->fluid_p[k]
                 : 0.0;
  if (lees)
    *lees = e->lees;
  return SB_SUCCESS;
}

int sb_engine_set_fluid_fn(sb_engine *e, sb_engine_fluid_fn fn, void *ctx)
{
  if (!e || !fn)
    return sbi_error(SB_EINVAL, __func__, "NULL engine or callback");
  e->fluid = SB_FLUID_CALLBACK;
  e->fluid_fn = fn;
  e->fluid_ctx = ctx;
  return SB_SUCCESS;
}

int sb_engine_set_sample_every(sb_engine *e, size_t every)
{
  if (!e)
    return sbi_error(SB_EINVAL, __func__, "engine is NULL");
  e->par.sample_every = every;
  return SB_SUCCESS;
}

int sb_engine_set_threads(sb_engine *e, int threads)
{
  if (!e || threads < 0 || threads > 4096)
    return sbi_error(SB_EINVAL, __func__, "threads = %d: must be in 0..4096 "
                     "(or NULL engine)", threads);
  e->par.threads = threads;
  return SB_SUCCESS;
}

int sb_engine_set_dt(sb_engine *e, double dt)
{
  if (!e)
    return sbi_error(SB_EINVAL, __func__, "engine is NULL");
  if (!(dt > 0.0) || !isfinite(dt))
    return sbi_error(SB_EINVAL, __func__, "dt = %g: must be finite > 0", dt);
  SBI_NOT_IN_STEP(e, __func__);
  double old = e->par.dt;
  size_t k = 0;
  e->par.dt = dt;
  int st = sbi_engine_update_coef(e, &k);
  if (st) {
    e->par.dt = old;
    sbi_engine_update_coef(e, NULL);
    const sb_engine_species *s = &e->spec[k];
    /* as sb_engine_add_species: a coefficient beyond the doubles is a
     * range error, not a bad argument */
    if (st == SB_ERANGE)
      return sbi_error(SB_ERANGE, __func__,
                       "dt = %g: a step coefficient of species %zu (tau = "
                       "%g, B = %g) exceeds DBL_MAX; dt stays %g", dt, k,
                       s->tau, s->B, old);
    return sbi_error(SB_EINVAL, __func__, "dt = %g: no Langevin step for "
                     "species %zu (tau = %g, B = %g); dt stays %g", dt, k,
                     s->tau, s->B, old);
  }
  return SB_SUCCESS;
}

/* ============================================================ run */

/* Transport: x0 <- x, u0 <- u, U_s at x0, exact Langevin step of every
 * particle with its species' coefficients (langevin_step.c; Mohaupt
 * 2011, eq 1.16):
 *   x += w dt + (u - w) gain + s_xu z1 + s_xc z2,  u = w + (u - w) decay
 *   + s_u z1,
 * disp = x - x0.  The same update as sb_langevin_step3_coef, fused with
 * the copies and the displacement so that the particle data are read and
 * written once; the Gaussians are drawn first for a block of particles
 * (GSL ziggurat, in the documented order: particle, component, z1 then z2,
 * so a run does not depend on the block size) and the arithmetic loop
 * then runs without calls.  In 2-D the third component is stepped too
 * (keeping the draw order independent of dim) and reset.  With the
 * Lees-Edwards shear (G != 0) the x component of a Stokes species takes
 * the exact shear noise from the same normals: its rows of the Cholesky
 * factor of the (u_y, y, u_x, x) covariance (engine_lees.c). */
#define SBI_TRANSPORT_BLOCK 256

/* Transport on the counter-based streams (par.streams): particle i takes
 * the first six normals of the stream (seed, id_i, step) through
 * sb_langevin_step3_stream (the same update and draw order as above), so
 * blocks of particles are independent and run on all threads with
 * bit-identical results.  With the shear noise the same normals go
 * through shear_step_z instead. */
#define SBI_STREAM_BLOCK 1024
/* The sheared step of one particle from its six normals z (the order of
 * sb_langevin_step3_stream): y and z as step3_z, the x component with the
 * exact shear noise (engine_lees.c) when sh is on. */
static inline void shear_step_z(const sb_langevin_coef *c,
                                const sbi_shear_noise *sh, const double *w,
                                const double *z, double *x, double *u)
{
  for (int k = 0; k < 3; k++) {
    const double wk = w ? w[k] : 0.0, v = u[k] - wk;
    if (k == 0 && sh && sh->on) {
      const double *L = sh->L;
      x[0] += wk * c->dt + v * c->gain + L[5] * z[0] + L[6] * z[1] +
              L[3] * z[2] + L[4] * z[3];
      u[0] = wk + v * c->decay + (L[2] * z[0] + L[0] * z[2] + L[1] * z[3]);
      continue;
    }
    x[k] += wk * c->dt + v * c->gain + c->s_xu * z[2 * k] +
            c->s_xc * z[2 * k + 1];
    u[k] = wk + v * c->decay + c->s_u * z[2 * k];
  }
}

/* What the blocks of transport_streams share. */
typedef struct {
  sb_engine *e;
  const double *us, *vset;
  double *ws;
  const sbi_shear_noise *shn;
} stream_step;

/* Block b of transport_streams (particles b * SBI_STREAM_BLOCK on): one
 * pass over the particle data: the start state is kept, the step taken
 * (the update and normals of sb_langevin_step3_stream, or with the shear
 * noise), the displacement and its length (for the search's cut-off)
 * written while the particle is in cache.  Returns bit 1 for a stream out
 * of range, bit 2 for a non-finite |disp|, bit 4 for a non-finite new x
 * or u; *dmax: the block's largest |disp|. */
static int stream_block(const stream_step *S, size_t b, double *dmax)
{
  sb_engine *e = S->e;
  enum { CH = 128 };
  double z[6 * CH];
  double *restrict x = e->x, *restrict u = e->u;
  double *restrict x0 = e->x0, *restrict u0 = e->u0, *restrict dp = e->disp;
  double *restrict dn = e->dn;
  const size_t n = e->n, i0 = b * SBI_STREAM_BLOCK;
  const size_t m = n - i0 < SBI_STREAM_BLOCK ? n - i0 : SBI_STREAM_BLOCK;
  const double *us = S->us, *wb = us ? us + 3 * i0 : NULL;
  if (S->ws) {
    for (size_t i = i0; i < i0 + m; i++)
      for (int k = 0; k < 3; k++)
        S->ws[3 * i + k] = (us ? us[3 * i + k] : 0.0) +
                           S->vset[3 * e->species[i] + k];
    wb = S->ws + 3 * i0;
  }
  int bad = 0;
  double dm = 0.0;
  for (size_t j0 = 0; j0 < m; j0 += CH) {
    const size_t mc = m - j0 < CH ? m - j0 : CH;
    if (sb_stream_gaussian_keyed(e->par.seed, e->steps, mc, e->id + i0 + j0,
                                 0, 6, z)) {
      bad |= 1;
      break;
    }
    for (size_t j = 0; j < mc; j++) {
      const size_t i = i0 + j0 + j, sp = e->species[i];
      double *xi = x + 3 * i, *ui = u + 3 * i, *d = dp + 3 * i;
      const double xo[3] = {xi[0], xi[1], xi[2]};
      memcpy(x0 + 3 * i, xo, sizeof xo);
      memcpy(u0 + 3 * i, ui, 3 * sizeof *ui);
      shear_step_z(&e->coef[sp], S->shn ? &S->shn[sp] : NULL,
                   wb ? wb + 3 * (j0 + j) : NULL, z + 6 * j, xi, ui);
      for (int k = 0; k < 3; k++)
        d[k] = xi[k] - xo[k];
      /* as the search's cut-off computes it (engine_neigh.c) */
      const double v = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
      dn[i] = v;
      bad |= 2 * !isfinite(v);
      /* y - y is 0, or NaN for an infinite or NaN y */
      bad |= 4 * !isfinite((xi[0] - xi[0]) + (xi[1] - xi[1]) +
                           (xi[2] - xi[2]) + (ui[0] - ui[0]) +
                           (ui[1] - ui[1]) + (ui[2] - ui[2]));
      dm = v > dm ? v : dm;
    }
  }
  *dmax = dm;
  return bad;
}

/* After a transport whose new state has an infinite or NaN component
 * (B sqrt(tau), the state or the fluid velocity near DBL_MAX): if one of
 * the box's dim components is (in 2-D the third is reset after the step),
 * every particle back to its start of step (x0, u0) and SB_ERANGE naming
 * the first such particle and its species' parameters; else 0.  `after`
 * (NULL for the transport itself) names the part of the step after the
 * transport that gave the state (engine_force.c). */
void sbi_engine_step_undo(sb_engine *e)
{
  memcpy(e->x, e->x0, 3 * e->n * sizeof *e->x);
  memcpy(e->u, e->u0, 3 * e->n * sizeof *e->u);
  memset(e->disp, 0, 3 * e->n * sizeof *e->disp);
}

int sbi_engine_step_overflow(sb_engine *e, const char *after)
{
  const int dim = e->par.dim;
  size_t bad = e->n;
  for (size_t i = 0; i < e->n && bad == e->n; i++)
    for (int k = 0; k < dim; k++)
      if (!isfinite(e->x[3 * i + k]) || !isfinite(e->u[3 * i + k]))
        bad = i;
  if (bad == e->n)
    return SB_SUCCESS;
  sbi_engine_step_undo(e);
  const sb_engine_species *s = &e->spec[e->species[bad]];
  return sbi_error(SB_ERANGE, "sb_engine_step",
                   "particle %zu (species %zu, tau = %g, B = %g): the new "
                   "position or velocity exceeds DBL_MAX%s%s (from x = (%g, "
                   "%g, %g), u = (%g, %g, %g)); the step is not taken",
                   bad, e->species[bad], s->tau, s->B, after ? " after " : "",
                   after ? after : "", e->x[3 * bad],
                   e->x[3 * bad + 1], e->x[3 * bad + 2], e->u[3 * bad],
                   e->u[3 * bad + 1], e->u[3 * bad + 2]);
}

static int transport_streams(sb_engine *e, const double *us)
{
  const size_t n = e->n, nb = (n + SBI_STREAM_BLOCK - 1) / SBI_STREAM_BLOCK;
  if (e->steps > SB_STREAM_MAX_STEP || e->next_id > SB_STREAM_MAX_ID + 1)
    return sbi_error(SB_EDOM, "sb_engine_step", "streams: step %llu or "
                     "particle id %llu beyond the streams' range",
                     (unsigned long long)e->steps,
                     (unsigned long long)e->next_id);
  stream_step S = {e, us, NULL, NULL, NULL};
  /* gravity: each species' settling velocity adds to U_s, as in the
   * sequential path; the sum goes to a scratch array (e->us keeps the
   * fluid velocity for the detectors) */
  if (e->has_grav && e->vset) {
    if (!e->wst && !(e->wst = malloc(3 * e->par.capacity * sizeof *e->wst)))
      return sbi_error(SB_ENOMEM, "sb_engine_step", "out of memory");
    S.ws = e->wst;
    S.vset = e->vset;
  }
  int st = sbi_engine_shear_noise(e, &S.shn);
  if (st)
    return st;
  int bad = 0;
  double dmax = 0.0;
  const int nt = sbi_engine_threads(&e->par);
  if (nb > 1 && nt > 1) {
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic) num_threads(nt) \
    reduction(| : bad) reduction(max : dmax)
#endif
    for (size_t b = 0; b < nb; b++) {
      double m;
      bad |= stream_block(&S, b, &m);
      dmax = m > dmax ? m : dmax;
    }
  } else {  /* no parallel region: entering one costs ~0.3 us */
    for (size_t b = 0; b < nb; b++) {
      double m;
      bad |= stream_block(&S, b, &m);
      dmax = m > dmax ? m : dmax;
    }
  }
  if (bad & 1)
    return sbi_error(SB_EDOM, "sb_engine_step",
                     "streams: a particle id or the step is out of range");
  if ((bad & 4) && (st = sbi_engine_step_overflow(e, NULL)))
    return st;
  e->dn_ready = 1;
  e->dn_bad = (bad & 2) != 0;
  e->dn_max = dmax;
  return SB_SUCCESS;
}

static int transport(sb_engine *e)
{
  const size_t n = e->n;
  e->dn_ready = 0;
  const double *us = NULL;
  if (e->fluid != SB_FLUID_REST) {
    /* x is the start position x0 here */
    int st = sbi_engine_fluid_eval(e, n, e->x, e->us, 0, "sb_engine_step");
    if (st)
      return st;
    us = e->us;
  }
  if (e->par.streams) {
    int st = transport_streams(e, us);
    if (st)
      return st;
    if (e->par.dim == 2) {
      e->dn_ready = 0;  /* |disp| had the third component */
      for (size_t i = 0; i < n; i++)
        e->x[3 * i + 2] = e->u[3 * i + 2] = e->disp[3 * i + 2] = 0.0;
    }
    return SB_SUCCESS;
  }
  double z[6 * SBI_TRANSPORT_BLOCK];
  double *restrict x = e->x, *restrict u = e->u;
  double *restrict x0 = e->x0, *restrict u0 = e->u0, *restrict dp = e->disp;
  const sb_langevin_coef *coef = e->coef;
  const size_t *sp = e->species;
  /* gravity: each species' settling velocity adds to U_s (engine_force.c) */
  const double *vset = e->has_grav ? e->vset : NULL;
  /* Lees-Edwards shear: the x rows of the exact noise (engine_lees.c) */
  const sbi_shear_noise *shn;
  int st = sbi_engine_shear_noise(e, &shn);
  if (st)
    return st;
  int bad = 0;
  for (size_t i0 = 0; i0 < n; i0 += SBI_TRANSPORT_BLOCK) {
    const size_t m = n - i0 < SBI_TRANSPORT_BLOCK ? n - i0
                                                   : SBI_TRANSPORT_BLOCK;
    for (size_t q = 0; q < 6 * m; q++)
      z[q] = gsl_ran_gaussian_ziggurat(e->rng, 1.0);
    for (size_t a = 0; a < m; a++) {
      const size_t i = i0 + a;
      const sb_langevin_coef *c = &coef[sp[i]];
      for (int k = 0; k < 3; k++) {
        const size_t q = 3 * i + k;
        const double w = (us ? us[q] : 0.0) +
                         (vset ? vset[3 * sp[i] + k] : 0.0),
                     z1 = z[6 * a + 2 * k],
                     z2 = z[6 * a + 2 * k + 1];
        const double xo = x[q], uo = u[q], v = uo - w;
        double xn, un;
        if (k == 0 && shn && shn[sp[i]].on) {
          const double *L = shn[sp[i]].L, z3 = z[6 * a + 2],
                       z4 = z[6 * a + 3];
          xn = xo + (w * c->dt + v * c->gain + L[5] * z1 + L[6] * z2 +
                     L[3] * z3 + L[4] * z4);
          un = w + v * c->decay + (L[2] * z1 + L[0] * z3 + L[1] * z4);
        } else {
          xn = xo + (w * c->dt + v * c->gain + c->s_xu * z1 + c->s_xc * z2);
          un = w + v * c->decay + c->s_u * z1;
        }
        x0[q] = xo;
        u0[q] = uo;
        x[q] = xn;
        u[q] = un;
        dp[q] = xn - xo;
        bad |= !isfinite(xn - xn + un - un);
      }
    }
  }
  if (bad && (st = sbi_engine_step_overflow(e, NULL)))
    return st;
  if (e->par.dim == 2)
    for (size_t i = 0; i < n; i++)
      x[3 * i + 2] = u[3 * i + 2] = dp[3 * i + 2] = 0.0;
  return SB_SUCCESS;
}

static int sort_particles(sb_engine *e, const char *who);

int sb_engine_step(sb_engine *e)
{
  if (!e)
    return sbi_error(SB_EINVAL, __func__, "engine is NULL");
  SBI_NOT_IN_STEP(e, __func__);
  memset(e->hit, 0, e->n);
  sbi_engine_pair_counts(e, e->pairs0);
  /* forces, Lees-Edwards, walls: checks and settling (engine_force.c) */
  int st = sbi_engine_physics_prepare(e, __func__);
  if (st)
    return st;
  st = transport(e);
  if (!st)  /* nonlinear drag, exact shear step (engine_force.c) */
    st = sbi_engine_after_transport(e);
  if (st)
    return st;
  double reach = 0.0;
  if (e->par.detect == SB_DETECT_CUSTOM)
    reach = e->detect_reach;
  else if (e->par.detect == SB_DETECT_LANGEVIN) {
    reach = sb_engine_langevin_reach(e);
    if (!(reach >= 0.0))
      return sbi_error(SB_EINVAL, __func__, "no Langevin reach: %s",
                       sb_last_error());
  }
  st = sbi_engine_find_step_pairs(e, reach);
  if (st)
    return st;
  st = sbi_engine_detect_and_process(e);
  if (st)
    return st;
  if (e->nremove) {  /* merged partners (engine_merge.c) */
    st = sbi_engine_purge(e);
    if (st)
      return st;
  }
  /* walls and deposition, then wrapping (with the Lees-Edwards shift):
   * engine_wall.c */
  st = sbi_engine_boundaries(e);
  if (st)
    return st;
  sbi_engine_add_exposure(e, e->par.dt);
  e->steps++;
  e->t += e->par.dt;
  if (e->ninflow) {  /* open boundaries: this step's arrivals */
    st = sbi_engine_inject(e);
    if (st)
      return st;
  }
  if (e->par.sort_every && e->steps % e->par.sort_every == 0) {
    st = sort_particles(e, __func__);
    if (st)
      return st;
  }
  if (e->par.sample_every && e->steps % e->par.sample_every == 0) {
    st = sbi_engine_sample(e);
    if (st)
      return st;
  }
  return SB_SUCCESS;
}

/* Copy one element of b bytes: the common element sizes get a fixed-size
 * copy the compiler inlines. */
static inline void copy_elem(char *d, const char *s, size_t b)
{
  if (b == 24)
    memcpy(d, s, 24);
  else if (b == 8)
    memcpy(d, s, 8);
  else if (b == 4)
    memcpy(d, s, 4);
  else
    memcpy(d, s, b);
}

/* Permute a per-particle array of `w` elements of `size` bytes by perm
 * (new[k] = old[perm[k]]) through the scratch buffer tmp, on nt threads
 * (each k is written once: any split gives the same array). */
static void permute(void *a, size_t w, size_t size, const size_t *perm,
                    size_t n, void *tmp, int nt)
{
  char *src = a, *dst = tmp;
  const size_t b = w * size;
  if (nt > 1) {
#ifdef _OPENMP
#pragma omp parallel for schedule(static) num_threads(nt)
#endif
    for (size_t k = 0; k < n; k++)
      copy_elem(dst + k * b, src + perm[k] * b, b);
  } else {  /* no parallel region: entering one costs ~0.3 us */
    for (size_t k = 0; k < n; k++)
      copy_elem(dst + k * b, src + perm[k] * b, b);
  }
  memcpy(a, tmp, n * b);
}

/* sb_engine_sort for the public function who (the step sorts every
 * sort_every steps) */
static int sort_particles(sb_engine *e, const char *who)
{
  const size_t n = e->n;
  if (n < 2)
    return SB_SUCCESS;
  const int dim = e->par.dim;
  double vol = 1.0;
  for (int k = 0; k < dim; k++)
    vol *= e->par.L[k];
  /* the grid of the linked cells when the cut-off is below the mean
   * spacing (dilute): their counting sort then scatters sequentially */
  double cs = sbi_cell_edge_min(vol, n, dim);
  int nc[3] = {1, 1, 1};
  size_t ncell = 1;
  for (int k = 0; k < dim; k++) {
    double m = floor(e->par.L[k] / cs);
    nc[k] = m < 1 ? 1 : (m > 1e6 ? 1000000 : (int)m);
    ncell *= (size_t)nc[k];
  }
  size_t *cnt = calloc(ncell + 1, sizeof *cnt);
  size_t *perm = malloc(n * sizeof *perm);
  if (!cnt || !perm) {
    free(cnt);
    free(perm);
    return sbi_error(SB_ENOMEM, who, "out of memory");
  }
  size_t *cof = e->cell_of;
  for (size_t i = 0; i < n; i++) {
    size_t c = 0;
    for (int k = dim - 1; k >= 0; k--) {
      int ck = (int)(e->x[3 * i + k] / e->par.L[k] * nc[k]);
      ck = ck >= nc[k] ? nc[k] - 1 : (ck < 0 ? 0 : ck);
      c = c * (size_t)nc[k] + (size_t)ck;
    }
    cof[i] = c;
    cnt[c + 1]++;
  }
  for (size_t c = 0; c < ncell; c++)
    cnt[c + 1] += cnt[c];
  for (size_t i = 0; i < n; i++)
    perm[cnt[cof[i]]++] = i;
  free(cnt);
  /* scratch: x0 (3 cap doubles) holds any array of <= 24 bytes per
   * particle */
  void *tmp = e->x0;
  const int nt = n >= 4096 ? sbi_engine_threads(&e->par) : 1;
  permute(e->x, 3, sizeof(double), perm, n, tmp, nt);
  permute(e->u, 3, sizeof(double), perm, n, tmp, nt);
  permute(e->radius, 1, sizeof(double), perm, n, tmp, nt);
  permute(e->mass, 1, sizeof(double), perm, n, tmp, nt);
  permute(e->species, 1, sizeof(size_t), perm, n, tmp, nt);
  permute(e->family, 1, sizeof(int), perm, n, tmp, nt);
  permute(e->id, 1, sizeof(uint64_t), perm, n, tmp, nt);
  free(perm);
  e->norder = 0;
  return SB_SUCCESS;
}

int sb_engine_sort(sb_engine *e)
{
  if (!e)
    return sbi_error(SB_EINVAL, __func__, "engine is NULL");
  SBI_NOT_IN_STEP(e, __func__);
  return sort_particles(e, __func__);
}

int sb_engine_run_until(sb_engine *e, double t_end)
{
  if (!e || !isfinite(t_end))
    return sbi_error(SB_EINVAL, __func__, "NULL engine or non-finite t_end");
  while (e->t < t_end - 0.5 * e->par.dt) {
    const double t = e->t;
    int st = sb_engine_step(e);
    if (st)  /* the step's message, under this function's name */
      return sbi_error(st, __func__, "step from t = %g s: %s", t,
                       sb_last_error());
  }
  return SB_SUCCESS;
}

/* ============================================================ accessors */

/* The accessors return 0, NaN or NULL for a NULL engine and record
 * SB_EINVAL (engine.h, file comment). */
size_t sb_engine_count(const sb_engine *e)
{
  if (!e) {
    sbi_error(SB_EINVAL, __func__, "engine is NULL");
    return 0;
  }
  return e->n;
}

double sb_engine_time(const sb_engine *e)
{
  if (!e) {
    sbi_error(SB_EINVAL, __func__, "engine is NULL");
    return NAN;
  }
  return e->t;
}

/* Read-only view of a particle array. */
#define ARRAY_VIEW(type, fn, field)                        \
  const type *fn(const sb_engine *e)                       \
  {                                                        \
    if (!e) {                                              \
      sbi_error(SB_EINVAL, __func__, "engine is NULL");    \
      return NULL;                                         \
    }                                                      \
    return e->field;                                       \
  }
ARRAY_VIEW(double, sb_engine_positions, x)
ARRAY_VIEW(double, sb_engine_velocities, u)
ARRAY_VIEW(double, sb_engine_start_positions, x0)
ARRAY_VIEW(double, sb_engine_start_velocities, u0)
ARRAY_VIEW(double, sb_engine_radii, radius)
ARRAY_VIEW(double, sb_engine_masses, mass)
ARRAY_VIEW(size_t, sb_engine_species_of, species)
ARRAY_VIEW(int, sb_engine_families, family)
ARRAY_VIEW(uint64_t, sb_engine_ids, id)
#undef ARRAY_VIEW
gsl_rng *sb_engine_rng(sb_engine *e)
{
  if (!e) {
    sbi_error(SB_EINVAL, __func__, "engine is NULL");
    return NULL;
  }
  return e->rng;
}

/* ============================================================ names */

/* One list per setting, NULL-terminated; the index is the enum value.  A
 * new built-in (e.g. a detector) is one more name here and in the enum. */
static const char *const NEIGH_NAMES[] = {"cells", "sweep", "brute", NULL};
/* SB_DETECT_CUSTOM has no name: it is set with sb_engine_set_detector */
static const char *const DETECT_NAMES[] = {"ballistic", "overlap",
                                           "langevin", NULL};
static const int DETECT_VALUES[] = {SB_DETECT_BALLISTIC, SB_DETECT_OVERLAP,
                                    SB_DETECT_LANGEVIN};
static const char *const OUTCOME_NAMES[] = {"elastic", "reinsert", "count",
                                            NULL};

const char *const *sb_engine_neigh_names(void) { return NEIGH_NAMES; }
const char *const *sb_engine_detect_names(void) { return DETECT_NAMES; }
const char *const *sb_engine_outcome_names(void) { return OUTCOME_NAMES; }

static int lookup(const char *name, const char *const *names, int *out,
                  const char *func)
{
  if (name)
    for (int k = 0; names[k]; k++)
      if (!strcmp(name, names[k])) {
        *out = k;
        return SB_SUCCESS;
      }
  char valid[256] = "";
  for (int k = 0; names[k]; k++) {
    size_t len = strlen(valid);
    snprintf(valid + len, sizeof valid - len, "%s%s", k ? ", " : "",
             names[k]);
  }
  return sbi_error(SB_EINVAL, func, "unknown name '%s'; valid: %s",
                   name ? name : "(null)", valid);
}

int sb_engine_neigh_from_name(const char *name, sb_engine_neigh *m)
{
  int k = 0, st = lookup(name, NEIGH_NAMES, &k, __func__);
  if (!st && m)
    *m = (sb_engine_neigh)k;
  return st;
}

int sb_engine_detect_from_name(const char *name, sb_engine_detect *d)
{
  int k = 0, st = lookup(name, DETECT_NAMES, &k, __func__);
  if (!st)
    k = DETECT_VALUES[k];
  if (!st && d)
    *d = (sb_engine_detect)k;
  return st;
}

int sb_engine_outcome_from_name(const char *name, sb_engine_outcome *o)
{
  int k = 0, st = lookup(name, OUTCOME_NAMES, &k, __func__);
  if (!st && o)
    *o = (sb_engine_outcome)k;
  return st;
}
