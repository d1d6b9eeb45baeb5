/* collide_setup.c — build the engine of a `smolbridge collide` run from
 * its configuration: species (with the alternative keys resolved and
 * checked against the box), particles (explicit, random, lattice or
 * uniform placement), fluid, bridge detector, turbulence, agglomeration
 * and first-hit counting.  Errors name the section and key at fault. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>

#include <smolbridge/engine.h>
#include <smolbridge/engine_bridge.h>
#include <smolbridge/engine_field.h>
#include <smolbridge/kernel.h>
#include <smolbridge/langevin.h>
#include <smolbridge/rng.h>

#include "collide_internal.h"

#define PI 3.14159265358979323846

/* Random placement (no overlaps) is used up to this total volume fraction;
 * random sequential addition jams near 0.38 in 3-D. */
#define RANDOM_PHI_MAX 0.3

void sbi_col_run_free(sbi_col_run *r)
{
  sbi_col_firsthit_free(r->fh);
  sbi_col_msd_free(r->msd);
  sbi_col_contacts_free(r->contacts);
  sbi_col_batches_free(r->batches);
  sb_agglo_free(r->agglo);
  sb_engine_bridge_free(r->bridge);
  sb_engine_free(r->e);
  sb_field_ou_free(r->ou);
  sb_field_kraichnan_free(r->kr);
  if (r->field_rng)
    gsl_rng_free(r->field_rng);
  free(r->dep);
  free(r->pairs.rows);
  if (r->grid_f)  /* a run that did not reach its outputs */
    fclose(r->grid_f);
  if (r->exits_f)
    fclose(r->exits_f);
  memset(r, 0, sizeof *r);
}

static double volume_of(const sbi_col_config *c)
{
  return c->Lx * c->Ly * (c->dim == 3 ? c->Lz : 1.0);
}

static double particle_volume(const sbi_col_config *c, double r)
{
  return c->dim == 3 ? 4.0 / 3.0 * PI * r * r * r : PI * r * r;
}

/* Species k from its keys; messages name the key at fault. */
static int species_build(sbi_col_config *c, int k, sb_engine_species *o)
{
  sbi_col_species *s = &c->sp[k];
  const char *n = s->name;
  double Lmin = fmin(c->Lx, c->Ly);
  if (c->dim == 3)
    Lmin = fmin(Lmin, c->Lz);
  const char *rk = sbi_col_given(c, n, "diameter") ? "diameter" : "radius";
  if (!(4.0 * s->radius < Lmin))
    return sbi_col_fail(c, "%s: [%s] %s = %g m: the particle does not fit the "
                        "box (a diameter must stay below half the smallest "
                        "edge, %g m)", sbi_col_where(c, n, rk), n, rk,
                        sbi_col_given(c, n, "diameter") ? s->diameter
                                                        : s->radius,
                        0.5 * Lmin);
  double d = 2.0 * s->radius, m = s->mass;
  if (isnan(m)) {
    m = sb_sphere_mass(s->density, d);  /* spheres, also in 2-D */
    if (!(m > 0) || !isfinite(m))
      return sbi_col_fail(c, "%s: [%s] density = %g kg/m^3 with radius %g m "
                          "gives the mass %g kg: not a finite positive number",
                          sbi_col_where(c, n, "density"), n, s->density,
                          s->radius, m);
  }
  double tau = s->tau;
  if (isnan(tau)) {
    tau = sb_stokes_tau(s->density, d, s->mu, s->cc);
    if (!(tau > 0) || !isfinite(tau))
      return sbi_col_fail(c, "%s: [%s] mu = %g Pa s gives the Stokes tau = %g "
                          "s: not a finite positive number",
                          sbi_col_where(c, n, "mu"), n, s->mu, tau);
  }
  double T = isnan(s->T) ? 0.0 : s->T, B = s->B;
  if (isinf(tau)) {
    if (!(T > 0))
      return sbi_col_fail(c, "%s: [%s]: free flight (tau = inf) needs T > 0 "
                          "(K): the velocities of placed and reinserted "
                          "particles, the kinetic reference",
                          sbi_col_given(c, n, "T") ? sbi_col_where(c, n, "T")
                                               : s->where, n);
    if (!isnan(s->b2))
      return sbi_col_fail(c, "%s: [%s] b2: a free-flight species (tau = inf) "
                          "has no diffusion", sbi_col_where(c, n, "b2"), n);
    B = 0.0;
  } else if (!isnan(s->b2)) {
    B = sqrt(s->b2) / tau;
  } else if (isnan(B)) {
    if (!sbi_col_given(c, n, "T"))
      return sbi_col_fail(c, "%s: [%s]: a Langevin species (finite tau) needs "
                          "T (K, B = sqrt(2 k_B T/(m tau))), b2 (m^2/s) or B "
                          "(m s^-3/2)", s->where, n);
    if (!(T > 0))
      return sbi_col_fail(c, "%s: [%s] T = 0 K gives no Brownian motion (B = "
                          "sqrt(2 k_B T/(m tau)) = 0); give T > 0, or b2 "
                          "(m^2/s) or B (m s^-3/2) with T = 0",
                          sbi_col_where(c, n, "T"), n);
    B = sb_brownian_B(T, m, tau);
  }
  if (!isfinite(B))
    return sbi_col_fail(c, "%s: [%s]: B = %g m s^-3/2 from these keys is not "
                        "finite", s->where, n, B);
  /* the bridge's position variance rate; with turbulence each particle
   * moves with the virtual diffusion b2_Brown + B_turb^2(d)/2 (Mohaupt
   * 2011, eqs 6.20-6.23, monodisperse form) */
  if (isfinite(tau)) {
    double b2 = !isnan(s->b2) ? s->b2 : (B * tau) * (B * tau);
    c->b2_brown[k] = c->b2_total[k] = b2;
    if (c->eps > 0) {
      c->b2_total[k] =
          b2 + 0.5 * sb_turb_pair_b2(2.0 * s->radius, c->eps, c->nu);
      B = sqrt(c->b2_total[k]) / tau;
    }
  }
  *o = (sb_engine_species){s->radius, m, tau, B, T};
  return 0;
}

/* The particles section s places in a box of volume vol (m^3, 2-D m^2),
 * those of phi with the particle volume pvol. */
static long placed_count(const sbi_col_species *s, double vol, double pvol)
{
  if (s->count >= 0)
    return s->count + s->npart;
  if (!isnan(s->phi))
    return lround(s->phi * vol / pvol) + s->npart;
  return s->npart;
}

static long species_count(const sbi_col_config *c, const sbi_col_species *s)
{
  return placed_count(s, volume_of(c), particle_volume(c, s->radius));
}

/* The end time up to which the inflows get room: t_end, or with steps
 * the run's steps in all times dt, done + steps with `done` the steps
 * before the measured ones (a new run's warm-up, a restart's checkpoint).
 * A restart thus computes what the run in one go computes, to the bit:
 * its time after the checkpoint, summed step by step, can differ from
 * steps times dt in the last place, and the room is truncated. */
static double room_end(const sbi_col_config *c, uint64_t done, double dt)
{
  if (isfinite(c->t_end))
    return c->t_end;
  return (double)(done + (uint64_t)(c->steps > 0 ? c->steps : 0)) * dt;
}

/* The steps the warm-up of a new run takes: as collide_run.c runs it,
 * from t = 0 in steps of dt summed while t < warmup - dt/2. */
static uint64_t warmup_steps(const sbi_col_config *c)
{
  uint64_t n = 0;
  if (!(c->warmup > 0) || !isfinite(c->warmup))
    return 0;
  for (double t = 0.0; t < c->warmup - 0.5 * c->dt; t += c->dt)
    n++;
  return n;
}

/* Room for the particles the inflows can bring in by time T (s, from
 * t = 0; none leaving), at most 2e6. */
static long inflow_room(const sbi_col_config *c, double T)
{
  double inflow = 0.0;
  for (int k = 0; k < c->nsp; k++)
    if (c->sp[k].inflow[0])
      inflow += c->sp[k].inflow_rate * T * 1.1 + 100.0;
  return (long)fmin(inflow, 2e6);
}

/* Fluid velocity at x (as the engine's built-in fields; the Kraichnan
 * field at the engine's time; 0 for the OU field, see start_law). */
static void fluid_at(const sbi_col_config *c, const sbi_col_run *r,
                     const double x[3], double u[3])
{
  u[0] = u[1] = u[2] = 0.0;
  if (r->kr)
    sb_field_kraichnan_eval(r->kr, sb_engine_time(r->e), 1, x, u);
  else if (!strcmp(c->fluid, "uniform"))
    for (int k = 0; k < c->nU; k++)
      u[k] = c->U[k];
  else if (!strcmp(c->fluid, "shear"))
    u[0] = c->G * (x[1] - 0.5 * c->Ly);
}

/* Standard deviation of a placed particle's velocity components. */
static double velocity_sd(const sbi_col_config *c, int k,
                          const sb_engine_species *q)
{
  const sbi_col_species *s = &c->sp[k];
  if ((!isnan(s->b2) || c->eps > 0) && isfinite(q->tau) && !(q->T > 0))
    return sqrt(0.5 * c->b2_total[k] / q->tau);
  if (q->T > 0)
    return sqrt(SB_BOLTZMANN * q->T / q->mass);
  return sqrt(q->B * q->B * q->tau / 2.0);
}

int sbi_col_md(const sbi_col_config *c) { return !strcmp(c->detect, "md"); }

/* The run's gravity: [fluid] g (the components it gives, 0 for the
 * others), or on restart without it the checkpoint's (setup_physics
 * leaves the engine's then). */
static void run_gravity(const sbi_col_config *c, const sb_engine *e,
                        double g[3])
{
  g[0] = g[1] = g[2] = 0.0;
  if (c->ng)
    memcpy(g, c->g, (size_t)c->ng * sizeof(double));
  else if (c->restart[0])
    sb_engine_get_gravity(e, g);
}

/* Reach of detect = md: the pairs whose start velocities bring them
 * together within the step, |u_i - u_j| dt, beyond the chords: 7 sd of
 * the relative thermal velocity (sqrt(2) vsd of the widest species; as
 * V3/diffusive-fail, which sizes its box by it) plus twice the largest
 * mean speed (drifts, explicit particles, inflows, settling tau g, with
 * the run's g: on restart without [fluid] g the checkpoint's). */
double sbi_col_md_reach(const sbi_col_config *c, const sb_engine *e)
{
  double vsd = 0.0, umax = 0.0, gv[3];
  run_gravity(c, e, gv);
  const double g = sqrt(gv[0] * gv[0] + gv[1] * gv[1] + gv[2] * gv[2]);
  for (int k = 0; k < c->nsp; k++) {
    const sb_engine_species *q = sb_engine_get_species(e, (size_t)k);
    const sbi_col_species *s = &c->sp[k];
    if (!q)
      continue;
    vsd = fmax(vsd, velocity_sd(c, k, q));
    umax = fmax(umax, sqrt(s->drift[0] * s->drift[0] +
                           s->drift[1] * s->drift[1] +
                           s->drift[2] * s->drift[2]));
    umax = fmax(umax, sqrt(s->inflow_u[0] * s->inflow_u[0] +
                           s->inflow_u[1] * s->inflow_u[1] +
                           s->inflow_u[2] * s->inflow_u[2]));
    for (int i = 0; i < s->npart; i++)
      umax = fmax(umax, sqrt(s->part[i][3] * s->part[i][3] +
                             s->part[i][4] * s->part[i][4] +
                             s->part[i][5] * s->part[i][5]));
    if (isfinite(q->tau))
      umax = fmax(umax, q->tau * g);
  }
  const double dt = sb_engine_get_params(e)->dt;
  return 7.0 * sqrt(2.0) * vsd * dt + 2.0 * umax * dt;
}

/* Start law of the next placed particle (engine index sb_engine_count):
 * velocity sd per component *sd from the species' vsd, and with the OU
 * field and stationary_start the stationary joint law with its seen
 * velocity, mean[] + N(0, vsd^2 + var) (sb_field_ou_start). */
static int start_law(sbi_col_config *c, sbi_col_run *r,
                     const sbi_col_species *s, const sb_engine_species *q,
                     double vsd, double mean[3], double *sd)
{
  mean[0] = mean[1] = mean[2] = 0.0;
  *sd = vsd;
  if (!r->ou || !c->ou_stationary)
    return 0;
  double var;
  if (sb_field_ou_start(r->ou, sb_engine_count(r->e), q->tau, mean, &var))
    return sbi_col_fail(c, "%s: [%s] with [fluid] type = ou-field: %s",
                        s->where, s->name, sb_last_error());
  *sd = sqrt(vsd * vsd + var);
  return 0;
}

/* Explicit particles: inside the box, no two overlapping. */
static int check_explicit(sbi_col_config *c)
{
  const double L[3] = {c->Lx, c->Ly, c->Lz};
  for (int a = 0; a < c->nsp; a++)
    for (int p = 0; p < c->sp[a].npart; p++) {
      const double *x = c->sp[a].part[p];
      for (int k = 0; k < c->dim; k++)
        if (!(x[k] >= 0.0 && x[k] < L[k]))
          return sbi_col_fail(c, "%s: [%s] particle: %c = %g m is outside "
                              "the box [0, %g)", c->sp[a].part_where[p],
                              c->sp[a].name, 'x' + k, x[k], L[k]);
      for (int b = a; b < c->nsp; b++)
        for (int q = (b == a ? p + 1 : 0); q < c->sp[b].npart; q++) {
          const double *y = c->sp[b].part[q];
          double d2 = 0.0;
          for (int k = 0; k < c->dim; k++) {
            double dx = x[k] - y[k];
            dx -= L[k] * floor(dx / L[k] + 0.5);
            d2 += dx * dx;
          }
          double s = c->sp[a].radius + c->sp[b].radius;
          if (d2 < s * s && strcmp(c->placement, "uniform"))
            return sbi_col_fail(c, "%s: [%s] particle overlaps the particle "
                                "at %s (centres %g m apart, radii sum %g m)",
                                c->sp[b].part_where[q], c->sp[b].name,
                                c->sp[a].part_where[p], sqrt(d2), s);
        }
    }
  return 0;
}

static int restart_fluid(sbi_col_config *c, sbi_col_run *r);

/* Lees-Edwards images, gravity, per-species fluid properties and drag
 * laws, walls (docs/engine_forces.md); before the placement, whose
 * velocities include the settling velocities. */
static int setup_physics(sbi_col_config *c, sbi_col_run *r)
{
  static const char *const faces[] = {"x_lo", "x_hi", "y_lo", "y_hi",
                                      "z_lo", "z_hi"};
  /* Lees-Edwards images: a new run has them with type = shear unless
   * lees_edwards = no; a restart keeps the checkpoint's unless the file
   * gives lees_edwards (which then applies to the checkpoint's field) or
   * [fluid] type (the fluid set afresh, as for a new run: off with any
   * other type than shear) */
  const int fluid_given = sbi_col_given(c, "fluid", "type");
  if (!c->restart[0] || fluid_given ||
      sbi_col_given(c, "fluid", "lees_edwards")) {
    const int on = c->lees && (!strcmp(c->fluid, "shear") ||
                               (c->restart[0] && !fluid_given));
    if (sb_engine_set_lees_edwards(r->e, on))
      return sbi_col_fail(c, "%s: [fluid] lees_edwards = %s: %s",
                          sbi_col_given(c, "fluid", "lees_edwards")
                              ? sbi_col_where(c, "fluid", "lees_edwards")
                              : sbi_col_where(c, "fluid", "type"),
                          on ? "yes" : "no", sb_last_error());
  }
  /* on restart without [fluid] type, the checkpoint's field and images
   * as the walls below meet them: refused as a new run refuses them */
  if (restart_fluid(c, r))
    return -1;
  if (c->ng) {
    double g[3] = {0, 0, 0};
    memcpy(g, c->g, (size_t)c->ng * sizeof(double));
    if (sb_engine_set_gravity(r->e, g))
      return sbi_col_fail(c, "%s: [fluid] g: %s",
                          sbi_col_where(c, "fluid", "g"), sb_last_error());
  }
  for (int k = 0; k < c->nsp && !c->restart[0]; k++) {
    const sbi_col_species *s = &c->sp[k];
    sb_engine_species_fluid fl = {SB_DRAG_STOKES, c->rho_f,
                                  isnan(s->mu) ? c->mu_f : s->mu};
    if (!strcmp(s->drag, "schiller-naumann"))
      fl.drag = SB_DRAG_SCHILLER_NAUMANN;
    if (isnan(fl.mu))
      fl.mu = 0.0;
    if (sb_engine_set_species_fluid(r->e, (size_t)k, &fl))
      return sbi_col_fail(c, "%s: [%s] drag / [fluid] rho, mu: %s", s->where,
                          s->name, sb_last_error());
  }
  for (int k = 0; k < c->dim; k++) {
    sb_engine_wall w[2];
    for (int q = 0; q < 2; q++)
      w[q] = !strcmp(c->wall[2 * k + q], "reflect")  ? SB_WALL_REFLECT
             : !strcmp(c->wall[2 * k + q], "absorb") ? SB_WALL_ABSORB
             : !strcmp(c->wall[2 * k + q], "open")   ? SB_WALL_OPEN
                                                     : SB_WALL_PERIODIC;
    /* a restart keeps the checkpoint's walls of a direction whose faces
     * the file does not give */
    const int given = sbi_col_given(c, "walls", faces[2 * k]) ||
                      sbi_col_given(c, "walls", faces[2 * k + 1]);
    if ((w[0] != SB_WALL_PERIODIC || w[1] != SB_WALL_PERIODIC ||
         (c->restart[0] && given)) &&
        sb_engine_set_walls(r->e, k, w[0], w[1])) {
      /* sbi_col_check and restart_fluid refuse what they can see */
      const char *f = faces[2 * k + !sbi_col_given(c, "walls", faces[2 * k])];
      return sbi_col_fail(c, "%s: [walls] %s = %s, %s = %s: %s",
                          sbi_col_where(c, "walls", f), faces[2 * k],
                          c->wall[2 * k], faces[2 * k + 1],
                          c->wall[2 * k + 1], sb_last_error());
    }
  }
  /* a restart keeps the checkpoint's wall detector and deposition
   * outcome unless the file gives them (each on its own) */
  sb_engine_walldet wdet = !strcmp(c->wall_detect, "ballistic")
                               ? SB_WALLDET_BALLISTIC
                           : !strcmp(c->wall_detect, "langevin")
                               ? SB_WALLDET_LANGEVIN
                               : SB_WALLDET_BRIDGE;
  sb_engine_deposit wdep = strcmp(c->deposit, "reinsert")
                               ? SB_DEPOSIT_REMOVE
                               : SB_DEPOSIT_REINSERT;
  if (c->restart[0])
    sb_engine_get_wall_mode(r->e,
                            sbi_col_given(c, "walls", "detect") ? NULL : &wdet,
                            sbi_col_given(c, "walls", "deposit") ? NULL
                                                                 : &wdep);
  if (sb_engine_set_wall_mode(r->e, wdet, wdep))
    return sbi_col_fail(c, "[walls]: %s", sb_last_error());
  /* open boundaries: one inflow per species that has one */
  for (int k = 0; k < c->nsp; k++) {
    const sbi_col_species *s = &c->sp[k];
    if (!s->inflow[0])
      continue;
    sb_engine_inflow in;
    memset(&in, 0, sizeof in);
    for (int f = 0; f < 6; f++)
      if (!strcmp(s->inflow, faces[f]))
        in.face = f;
    in.species = (size_t)k;
    in.family = (int)s->family;
    in.rate = s->inflow_rate;
    const double *L = sb_engine_get_params(r->e)->L;
    for (int d = 0, q = 0; d < c->dim; d++) {
      if (d == in.face / 2)
        continue;
      in.lo[q] = s->ninflow_region ? s->inflow_region[2 * q] : 0.0;
      in.hi[q] = s->ninflow_region ? s->inflow_region[2 * q + 1] : L[d];
      q++;
    }
    for (int d = 0; d < c->dim; d++)
      in.u[d] = s->inflow_u[d];
    in.no_overlap = (int)s->inflow_no_overlap;
    if (sb_engine_add_inflow(r->e, &in, NULL))
      return sbi_col_fail(c, "%s: [%s] inflow: %s", sbi_col_where(c, s->name,
                                                              "inflow"),
                          s->name, sb_last_error());
  }
  return 0;
}

/* Region of species s (the whole box by default). */
static void region_of(const sbi_col_config *c, const sbi_col_species *s,
                      double lo[3], double hi[3])
{
  const double L[3] = {c->Lx, c->Ly, c->Lz};
  for (int k = 0; k < 3; k++) {
    lo[k] = 0.0;
    hi[k] = k < c->dim ? L[k] : 0.0;
  }
  for (int k = 0; k < c->dim && s->nregion; k++) {
    lo[k] = s->region[2 * k];
    hi[k] = s->region[2 * k + 1];
  }
  /* walls: centres between the contact planes (engine_wall.c) */
  const double r = isnan(s->radius) ? 0.5 * s->diameter : s->radius;
  for (int k = 0; k < c->dim; k++)
    if (strcmp(c->wall[2 * k], "periodic") && isfinite(r)) {
      if (lo[k] < r)
        lo[k] = r;
      if (hi[k] > L[k] - r)
        hi[k] = L[k] - r;
    }
}

/* Independent uniform positions (overlaps allowed) and Gaussian
 * velocities, x and u drawn per component in turn: the placement of the
 * first-hit validation cases. */
static int place_uniform(sbi_col_config *c, sbi_col_run *r, size_t sp,
                         size_t n, gsl_rng *g, const sb_engine_species *q)
{
  const sbi_col_species *s = &c->sp[sp];
  double lo[3], hi[3];
  region_of(c, s, lo, hi);
  const double vsd = velocity_sd(c, (int)sp, q);
  for (size_t i = 0; i < n; i++) {
    double x[3] = {0, 0, 0}, u[3] = {0, 0, 0}, us[3], m[3], sd;
    if (start_law(c, r, s, q, vsd, m, &sd))
      return -1;
    for (int k = 0; k < c->dim; k++) {
      x[k] = sbi_col_place_coord(c, s, k, lo[k], hi[k], g);
      u[k] = gsl_ran_gaussian_ziggurat(g, sd);
    }
    fluid_at(c, r, x, us);
    for (int k = 0; k < 3; k++)
      us[k] += m[k];
    double vs[3] = {0, 0, 0};  /* settling velocity under [fluid] g */
    sb_engine_settling_velocity(r->e, sp, vs);
    for (int k = 0; k < c->dim; k++)
      u[k] += us[k] + vs[k] + (s->ndrift ? s->drift[k] : 0.0);
    if (sb_engine_add_particle(r->e, sp, (int)s->family, x, u))
      return sbi_col_fail(c, "%s: [%s]: %s", s->where, s->name,
                          sb_last_error());
  }
  return 0;
}

/* Lattice sites for every placed particle (FCC in 3-D, square in 2-D) at
 * a spacing of at least the largest diameter, sites chosen at random:
 * reaches volume fractions where random addition jams. */
static int place_lattice(sbi_col_config *c, sbi_col_run *r, const long *nplace,
                         const sb_engine_species *q)
{
  double dmax = 0.0;
  long total = 0;
  for (int k = 0; k < c->nsp; k++) {
    if (nplace[k] > 0 && 2.0 * c->sp[k].radius > dmax)
      dmax = 2.0 * c->sp[k].radius;
    total += nplace[k];
    if (c->sp[k].nregion && nplace[k] > 0)
      return sbi_col_fail(c, "%s: [%s] region: not with placement = lattice",
                          sbi_col_where(c, c->sp[k].name, "region"),
                          c->sp[k].name);
  }
  const double L[3] = {c->Lx, c->Ly, c->Lz};
  const int nb = c->dim == 3 ? 4 : 1;   /* sites per cell */
  const double cell = c->dim == 3 ? sqrt(2.0) * dmax : dmax;
  long m[3] = {1, 1, 1}, nsites = nb;
  for (int k = 0; k < c->dim; k++) {
    m[k] = (long)floor(L[k] / cell);
    nsites *= m[k];
  }
  if (nsites < total)
    return sbi_col_fail(c, "[run] placement = lattice: %ld particles but only "
                        "%ld lattice sites fit the box (spacing %g m): lower "
                        "count/phi or enlarge the box", total, nsites, cell);
  static const double basis[4][3] = {
      {0, 0, 0}, {0.5, 0.5, 0}, {0.5, 0, 0.5}, {0, 0.5, 0.5}};
  long *site = malloc((size_t)nsites * sizeof *site);
  if (!site)
    return sbi_col_fail(c, "out of memory");
  for (long i = 0; i < nsites; i++)
    site[i] = i;
  gsl_rng *g = sb_engine_rng(r->e);
  /* partial Fisher-Yates: the first `total` sites in random order */
  for (long i = 0; i < total; i++) {
    long j = i + (long)gsl_rng_uniform_int(g, (unsigned long)(nsites - i));
    long t = site[i];
    site[i] = site[j];
    site[j] = t;
  }
  long next = 0;
  int st = 0;
  for (int sp = 0; sp < c->nsp && !st; sp++) {
    const sbi_col_species *s = &c->sp[sp];
    const double vsd = velocity_sd(c, sp, &q[sp]);
    for (long i = 0; i < nplace[sp] && !st; i++) {
      long id = site[next++], b = id % nb, cidx = id / nb;
      double x[3] = {0, 0, 0}, u[3] = {0, 0, 0}, us[3];
      long ix[3] = {cidx % m[0], (cidx / m[0]) % m[1],
                    cidx / (m[0] * m[1])};
      for (int k = 0; k < c->dim; k++)
        x[k] = (ix[k] + basis[b][k] + 0.25) * (L[k] / (double)m[k]);
      double m[3], sd;
      if (start_law(c, r, s, &q[sp], vsd, m, &sd)) {
        st = -1;
        break;
      }
      fluid_at(c, r, x, us);
      for (int k = 0; k < c->dim; k++)
        u[k] = us[k] + m[k] + gsl_ran_gaussian_ziggurat(g, sd) +
               (s->ndrift ? s->drift[k] : 0.0);
      if (sb_engine_add_particle(r->e, (size_t)sp, (int)s->family, x, u))
        st = sbi_col_fail(c, "%s: [%s]: %s", s->where, s->name,
                          sb_last_error());
    }
  }
  free(site);
  return st;
}

static int place(sbi_col_config *c, sbi_col_run *r, const sb_engine_species *q)
{
  if (check_explicit(c))
    return -1;
  long nplace[COL_MAXSPEC];
  double phi = 0.0;
  for (int k = 0; k < c->nsp; k++) {
    const sbi_col_species *s = &c->sp[k];
    nplace[k] = species_count(c, s) - s->npart;
    phi += (double)species_count(c, s) * particle_volume(c, s->radius) /
           volume_of(c);
    for (int p = 0; p < s->npart; p++)
      if (sb_engine_add_particle(r->e, (size_t)k, (int)s->family, s->part[p],
                                 s->part[p] + 3))
        return sbi_col_fail(c, "%s: [%s] particle: %s", s->part_where[p],
                            s->name, sb_last_error());
  }
  if (!c->placement[0]) {
    strcpy(c->placement, phi > RANDOM_PHI_MAX ? "lattice" : "random");
    if (phi > RANDOM_PHI_MAX)
      sbi_col_warn(c, "total volume fraction %.3g > %g: particles start on a "
                   "lattice (placement = lattice); use warmup to let the "
                   "structure relax", phi, RANDOM_PHI_MAX);
  } else if (!strcmp(c->placement, "random") && phi > RANDOM_PHI_MAX)
    return sbi_col_fail(c, "%s: [run] placement = random at a total volume "
                        "fraction %.3g: random addition jams near 0.38; above "
                        "%g use placement = lattice (or uniform: overlaps "
                        "allowed)", sbi_col_where(c, "run", "placement"), phi,
                        RANDOM_PHI_MAX);
  if (!strcmp(c->placement, "lattice"))
    return place_lattice(c, r, nplace, q);
  gsl_rng *g = NULL;
  if (!strcmp(c->placement, "uniform")) {
    if (c->placement_seed >= 0) {
      g = gsl_rng_alloc(gsl_rng_mt19937);
      if (!g)
        return sbi_col_fail(c, "out of memory");
      gsl_rng_set(g, (unsigned long)c->placement_seed);
    } else
      g = sb_engine_rng(r->e);
  }
  int st = 0;
  for (int k = 0; k < c->nsp && !st; k++) {
    sbi_col_species *s = &c->sp[k];
    if (nplace[k] <= 0)
      continue;
    if (g)
      st = place_uniform(c, r, (size_t)k, (size_t)nplace[k], g, &q[k]);
    else {
      double lo[3], hi[3];
      region_of(c, s, lo, hi);
      if (sb_engine_fill_box(r->e, (size_t)k, (int)s->family,
                             (size_t)nplace[k], lo, hi,
                             s->ndrift ? s->drift : NULL)) {
        /* the key that asked for it: too full, the number placed;
         * otherwise the region (sbi_col_check refuses what it can see) */
        const int full = sb_last_status() == SB_EMAXITER;
        const char *key = !full && s->nregion                ? "region"
                          : sbi_col_given(c, s->name, "phi") ? "phi"
                                                             : "count";
        st = sbi_col_fail(c, "%s: [%s] %s: %s%s",
                          sbi_col_given(c, s->name, key)
                              ? sbi_col_where(c, s->name, key)
                              : s->where,
                          s->name, key, sb_last_error(),
                          !full ? ""
                          : s->nregion
                              ? " (the region is too full for random "
                                "placement: a larger region or fewer "
                                "particles)"
                              : " (the box is too full for random "
                                "placement: placement = lattice reaches "
                                "higher volume fractions)");
      }
    }
  }
  if (g && g != sb_engine_rng(r->e))
    gsl_rng_free(g);
  return st;
}

/* x and y equal to rounding (the same keys give the same doubles; a
 * diameter halved or a mass from the density may differ in the last
 * bits). */
static int same_value(double x, double y)
{
  return x == y || fabs(x - y) <= 1e-12 * fmax(fabs(x), fabs(y));
}

/* On restart the [species] sections name the checkpoint's species, in
 * order, and the output's references and first-contact radii follow
 * them: they must be the first run's.  Each must give the saved
 * species' radius, mass, tau and T (merging adds cluster species after
 * them). */
static int restart_species(sbi_col_config *c, const sb_engine *e)
{
  size_t ns = 0;
  while (sb_engine_get_species(e, ns))
    ns++;
  if (c->nsp == 0)
    return sbi_col_fail(c, "[run] restart: give the first run's [species] "
                        "sections (the checkpoint has %zu species): they "
                        "name the saved species, in order; the particles "
                        "come from the checkpoint", ns);
  if ((size_t)c->nsp > ns || (!sbi_col_agglo(c) && (size_t)c->nsp != ns))
    return sbi_col_fail(c, "[run] restart: %d [species] sections for the "
                        "checkpoint's %zu species: give the first run's, in "
                        "the same order", c->nsp, ns);
  for (int k = 0; k < c->nsp; k++) {
    const sbi_col_species *s = &c->sp[k];
    const sb_engine_species *q = sb_engine_get_species(e, (size_t)k);
    const double r = isnan(s->diameter) ? s->radius : 0.5 * s->diameter;
    const double m = isnan(s->mass) ? sb_sphere_mass(s->density, 2.0 * r)
                                    : s->mass;
    const double tau = isnan(s->tau) ? sb_stokes_tau(s->density, 2.0 * r,
                                                     s->mu, s->cc)
                                     : s->tau;
    const double T = isnan(s->T) ? 0.0 : s->T;
    const char *what = !same_value(r, q->radius) ? "radius"
                       : !same_value(m, q->mass) ? "mass"
                       : !same_value(tau, q->tau) ? "tau"
                       : !same_value(T, q->T)     ? "T"
                                                  : NULL;
    if (what)
      return sbi_col_fail(c, "%s: [%s] is not the checkpoint's species %d "
                          "(its %s differs: radius %g m, mass %g kg, tau %g "
                          "s, T %g K saved): give the first run's [species] "
                          "sections, in the same order", s->where, s->name,
                          k + 1, what, q->radius, q->mass, q->tau, q->T);
  }
  return SB_SUCCESS;
}

/* A restart whose state beside the checkpoint ([run] key = val keeps
 * one) is missing or does not load. */
static int restart_failed(sbi_col_config *c, const char *key,
                          const char *val)
{
  return sbi_col_fail(c, "%s: [run] %s = %s with %s",
                      sbi_col_where(c, "run", "restart"), key, val,
                      sb_last_error());
}

/* Bridge detector (bridge | exact) with turbulence and hit records. */
static int attach_bridge(sbi_col_config *c, sbi_col_run *r)
{
  sb_engine_bridge_params bp;
  sb_engine_bridge_params_default(&bp);
  bp.mode = !strcmp(c->detect, "exact") ? SB_BRIDGE_EXACT : SB_BRIDGE_BESSEL;
  bp.ends = !strcmp(c->ends, "diffusive") ? SB_BRIDGE_ENDS_DIFFUSIVE
                                           : SB_BRIDGE_ENDS_POSITION;
  bp.outcome = !strcmp(c->outcome, "reinsert")     ? SB_BRIDGE_OUT_REINSERT
               : !strcmp(c->outcome, "correction") ? SB_BRIDGE_OUT_CORRECT
                                                   : SB_BRIDGE_OUT_COUNT;
  bp.tol = c->tol;
  bp.exact_tol = c->exact_tol;
  bp.record_cap = (size_t)c->hit_times;
  r->bridge = sb_engine_bridge_alloc(&bp);
  if (!r->bridge)
    return sbi_col_fail(c, "[bridge]: %s", sb_last_error());
  /* on restart the saved species: with turbulence their Brownian share
   * (the collision split) from the b2 set in sbi_col_setup */
  for (int k = 0; c->restart[0] && c->eps > 0 && k < COL_MAXSPEC; k++) {
    const sb_engine_species *s = sb_engine_get_species(r->e, (size_t)k);
    if (s && isfinite(s->tau) &&
        sb_engine_bridge_set_b2(r->bridge, (size_t)k, c->b2_total[k],
                                c->b2_brown[k]))
      return sbi_col_fail(c, "[turbulence] with restart: %s",
                          sb_last_error());
  }
  for (int k = 0; k < c->nsp && !c->restart[0]; k++) {
    const sb_engine_species *s = sb_engine_get_species(r->e, (size_t)k);
    if (isinf(s->tau))
      return sbi_col_fail(c, "%s: [%s] tau = inf with detect = %s: the bridge "
                          "detectors need Langevin (finite tau) species",
                          c->sp[k].where, c->sp[k].name, c->detect);
    if (!isnan(c->sp[k].b2) || c->eps > 0)
      if (sb_engine_bridge_set_b2(r->bridge, (size_t)k, c->b2_total[k],
                                  c->b2_brown[k]))
        return sbi_col_fail(c, "%s: [%s]: %s", c->sp[k].where, c->sp[k].name,
                            sb_last_error());
  }
  char path[600];
  if (c->restart[0] &&  /* its counters and records go on */
      (sbi_col_restart_beside(c, SBI_BESIDE_BRIDGE, "what it counted before",
                              path, sizeof path) ||
       sb_engine_bridge_load(r->bridge, path)))
    return restart_failed(c, "detect", c->detect);
  if (sb_engine_bridge_attach(r->e, r->bridge))
    return sbi_col_fail(c, "[run] detect = %s: %s", c->detect,
                        sb_last_error());
  return 0;
}

static int attach_agglo(sbi_col_config *c, sbi_col_run *r)
{
  if (c->nsp > 1)
    return sbi_col_fail(c, "%s: [run] outcome = %s: one primary species (the "
                        "clusters are species of their own); %d given",
                        sbi_col_where(c, "run", "outcome"), c->outcome,
                        c->nsp);
  sb_agglo_params ap;
  sb_agglo_params_default(&ap);
  ap.rule = strcmp(c->outcome, "dlvo") ? SB_AGGLO_MERGE : SB_AGGLO_DLVO;
  ap.growth = !strcmp(c->growth, "constant") ? SB_AGGLO_CONSTANT
                                              : SB_AGGLO_STOKES;
  ap.erel = !strcmp(c->erel, "stationary") ? SB_AGGLO_EREL_STATIONARY
                                           : SB_AGGLO_EREL_CONTACT;
  ap.erel_normal = (int)c->erel_normal;
  ap.kobs = (size_t)c->kobs;
  const sb_engine_species *s0 = sb_engine_get_species(r->e, 0);
  if (!isnan(c->wmax_kT) && !(s0->T > 0))
    return sbi_col_fail(c, "%s: [agglo] wmax_kT: the first species has T = 0; "
                        "give wmax in J",
                        sbi_col_where(c, "agglo", "wmax_kT"));
  ap.wmax = !isnan(c->wmax_kT) ? c->wmax_kT * SB_BOLTZMANN * s0->T : c->wmax;
  r->agglo = sb_agglo_alloc(&ap);
  if (!r->agglo)
    return sbi_col_fail(c, "[run] outcome = %s: %s", c->outcome,
                        sb_last_error());
  char path[600];
  if (c->restart[0] &&  /* the sizes and series go on from the checkpoint's */
      (sbi_col_restart_beside(c, SBI_BESIDE_COUNTS,
                              "which species is which cluster size", path,
                              sizeof path) ||
       sb_agglo_load(r->agglo, path)))
    return restart_failed(c, "outcome", c->outcome);
  if (sb_agglo_attach(r->e, r->agglo))
    return sbi_col_fail(c, "[run] outcome = %s: %s", c->outcome,
                        sb_last_error());
  return 0;
}

/* [fluid] type = ou-field | kraichnan: the field, drawn from its own
 * generator ([fluid] seed) or the engine's.  The Kraichnan field is
 * attached at once (placement reads it at time 0); the OU field after
 * the placement (it serves the engine's per-step call for all the
 * particles, and the placement starts them from its seen velocities). */
static int setup_field(sbi_col_config *c, sbi_col_run *r)
{
  const int ou = !strcmp(c->fluid, "ou-field");
  if (!ou && strcmp(c->fluid, "kraichnan"))
    return 0;
  const char *type = sbi_col_where(c, "fluid", "type");
  gsl_rng *g = sb_engine_rng(r->e);
  if (c->field_seed >= 0) {
    if (!(r->field_rng = gsl_rng_alloc(gsl_rng_mt19937)))
      return sbi_col_fail(c, "out of memory");
    gsl_rng_set(r->field_rng, (unsigned long)c->field_seed);
    g = r->field_rng;
  }
  if (ou) {
    long n = 0;
    for (int k = 0; k < c->nsp; k++)
      n += species_count(c, &c->sp[k]);
    if (!(r->ou = sb_field_ou_alloc((size_t)n, c->ou_u2, c->ou_TL, c->dt, g)))
      return sbi_col_fail(c, "%s: [fluid] type = ou-field: %s", type,
                          sb_last_error());
    return 0;
  }
  if (!(r->kr = sb_field_kraichnan_alloc(c->Lx, (int)c->kr_shell,
                                         c->kr_eps_nu, c->kr_omega, g)) ||
      sb_field_kraichnan_attach(r->e, r->kr))
    return sbi_col_fail(c, "%s: [fluid] type = kraichnan: %s", type,
                        sb_last_error());
  return 0;
}

/* On restart: the random field saved beside the checkpoint, drawing from
 * the engine's generator or from its own ([fluid] seed: its state from
 * the file), attached. */
static int restart_field(sbi_col_config *c, sbi_col_run *r)
{
  const int ou = !strcmp(c->fluid, "ou-field");
  if (!ou && strcmp(c->fluid, "kraichnan"))
    return 0;
  const char *type = sbi_col_where(c, "fluid", "type");
  const sb_engine_params *p = sb_engine_get_params(r->e);
  char path[600];
  int st = sbi_col_restart_beside(c, SBI_BESIDE_FIELD, "the field's state",
                                  path, sizeof path);
  if (!st && ou) {
    gsl_rng *g = sb_engine_rng(r->e);
    if (c->field_seed >= 0) {
      if (!(r->field_rng = gsl_rng_alloc(gsl_rng_mt19937)))
        return sbi_col_fail(c, "out of memory");
      g = r->field_rng;
    }
    r->ou = sb_field_ou_load(path, c->ou_u2, c->ou_TL, p->dt, g, &st);
    if (!st)
      st = sb_field_ou_attach(r->e, r->ou);
  } else if (!st) {
    r->kr = sb_field_kraichnan_load(path, p->L[0], (int)c->kr_shell,
                                    c->kr_eps_nu, c->kr_omega, &st);
    if (!st)
      st = sb_field_kraichnan_attach(r->e, r->kr);
  }
  return st ? sbi_col_fail(c, "%s: [fluid] type = %s with %s", type,
                           c->fluid, sb_last_error())
            : 0;
}

/* The capacity of the run in one go, as a new run computes it: the
 * particles the [species] sections place (in the checkpoint's box, with
 * its species' radii) and the inflows' room up to the end time (t_end,
 * or the checkpoint's steps and steps more times dt, room_end; with
 * another dt than the checkpoint's, or a checkpoint whose time is not
 * its steps times its dt, the checkpoint's time and steps more: there
 * is no run in one go).
 * The checkpoint holds the capacity of the run that wrote it, whose end
 * time was the checkpoint's: with inflows, too little for the rest.
 * Called before [run] dt is applied. */
static size_t restart_capacity(const sbi_col_config *c, const sb_engine *e)
{
  const sb_engine_params *p = sb_engine_get_params(e);
  const int dim = p->dim;
  const double vol = p->L[0] * p->L[1] * (dim == 3 ? p->L[2] : 1.0);
  long total = 0;
  for (int k = 0; k < c->nsp; k++) {
    const sb_engine_species *q = sb_engine_get_species(e, (size_t)k);
    if (!q)
      return 0;  /* not the checkpoint's species: restart_species says */
    const double r = q->radius;
    total += placed_count(&c->sp[k], vol,
                          dim == 3 ? 4.0 / 3.0 * PI * r * r * r
                                   : PI * r * r);
  }
  const double dt = sbi_col_given(c, "run", "dt") ? c->dt : p->dt;
  sb_engine_stats st;
  sb_engine_get_stats(e, &st);
  const int one_go = dt == p->dt && fabs((double)st.steps * dt - st.t) <=
                                        0.5 * dt;
  const double T = one_go || isfinite(c->t_end)
                       ? room_end(c, st.steps, dt)
                       : st.t + (double)c->steps * dt;
  total += inflow_room(c, T);
  return total > 0 ? (size_t)total : 0;
}

/* On restart: the checkpoint's dim and box (the file's are ignored),
 * and its walls of the directions whose faces the file does not give
 * (setup_physics keeps them), into the configuration. */
static void restart_box(sbi_col_config *c, const sb_engine *e)
{
  static const char *const faces[] = {"x_lo", "x_hi", "y_lo", "y_hi",
                                      "z_lo", "z_hi"};
  static const char *const names[] = {"periodic", "reflect", "absorb",
                                      "open"};
  const sb_engine_params *p = sb_engine_get_params(e);
  c->dim = p->dim;
  c->Lx = p->L[0];
  c->Ly = p->L[1];
  c->Lz = p->L[2];
  for (int k = 0; k < c->dim; k++) {
    sb_engine_wall w[2];
    if (sbi_col_given(c, "walls", faces[2 * k]) ||
        sbi_col_given(c, "walls", faces[2 * k + 1]) ||
        sb_engine_get_walls(e, k, &w[0], &w[1]))
      continue;
    for (int q = 0; q < 2; q++)
      snprintf(c->wall[2 * k + q], sizeof c->wall[0], "%s",
               (unsigned)w[q] <= SB_WALL_OPEN ? names[w[q]] : "periodic");
  }
}

/* Gravity ([fluid] g, or on restart without it the checkpoint's) with a
 * free-flight species (tau = inf): the engine has no settling velocity
 * for it and refuses the first step (sbi_engine_physics_prepare); here
 * at set-up, before any output, naming the species. */
static int gravity_check(sbi_col_config *c, const sb_engine *e)
{
  double g[3];
  run_gravity(c, e, g);
  int on = 0;
  for (int k = 0; k < c->dim && k < 3; k++)
    on |= g[k] != 0.0;
  for (size_t k = 0; on; k++) {
    const sb_engine_species *q = sb_engine_get_species(e, k);
    if (!q)
      break;
    if (!isinf(q->tau))
      continue;
    char sp[80];
    if (k < (size_t)c->nsp)
      snprintf(sp, sizeof sp, "[%s] tau = inf%s", c->sp[k].name,
               c->restart[0] ? " (the restart checkpoint's)" : "");
    else
      snprintf(sp, sizeof sp, "the restart checkpoint's species %zu "
               "(tau = inf)", k + 1);
    return sbi_col_fail(c, "%s: [fluid] g = %g %g %g%s with %s: a "
                        "free-flight species has no drag and no settling "
                        "velocity; give it a finite tau (or mu), or g = 0",
                        c->ng ? sbi_col_where(c, "fluid", "g")
                              : sbi_col_where(c, "run", "restart"),
                        g[0], g[1], g[2], c->ng ? ""
                        : " (the restart checkpoint's)", sp);
  }
  return 0;
}

/* A restart without [fluid] type runs in the checkpoint's field, with
 * the Lees-Edwards images as setup_physics set them (before the walls):
 * the configuration takes them over (summary.json names the field, the
 * references are those of its fluid) and the checks that depend on them
 * run now (sbi_col_check ran before the checkpoint was read). */
static int restart_fluid(sbi_col_config *c, sbi_col_run *r)
{
  if (!c->restart[0] || sbi_col_given(c, "fluid", "type"))
    return 0;
  sb_engine_fluid f;
  double p[3];
  int lees;
  sb_engine_get_fluid(r->e, &f, p, &lees);
  snprintf(c->fluid, sizeof c->fluid, "%s",
           f == SB_FLUID_UNIFORM ? "uniform"
           : f == SB_FLUID_SHEAR ? "shear"
                                 : "rest");
  if (f == SB_FLUID_UNIFORM) {
    memcpy(c->U, p, sizeof c->U);
    c->nU = (int)c->dim;
  }
  if (f == SB_FLUID_SHEAR)
    c->G = p[0];
  c->lees = lees;
  return sbi_col_fluid_check(c);
}

int sbi_col_setup(sbi_col_config *c, sbi_col_run *r)
{
  memset(r, 0, sizeof *r);
  sb_engine_neigh nm;
  sb_engine_detect dm = SB_DETECT_BALLISTIC;
  sb_engine_outcome om = SB_OUTCOME_ELASTIC;
  sb_engine_neigh_from_name(c->neigh, &nm);
  if (!sbi_col_bridge(c) && !sbi_col_detect_none(c))
    sb_engine_detect_from_name(c->detect, &dm);
  if (!sbi_col_bridge(c) && !sbi_col_agglo(c))
    sb_engine_outcome_from_name(c->outcome, &om);
  if (sbi_col_bridge(c) || sbi_col_detect_none(c))
    om = SB_OUTCOME_COUNT;  /* replaced by the bridge's outcome; none:
                               never called */
  sb_engine_species q[COL_MAXSPEC];
  if (c->restart[0]) {
    int st;
    r->e = sb_engine_checkpoint_load(c->restart, &st);
    /* the checks of a new run that depend on dim, the box and the
     * walls, with the checkpoint's (the inflows' room below reads their
     * keys) */
    if (r->e) {
      restart_box(c, r->e);
      if (sbi_col_dim_check(c))
        return -1;
    }
    size_t cap;
    if (r->e && (cap = restart_capacity(c, r->e)) >
                    sb_engine_get_params(r->e)->capacity) {
      sb_engine_free(r->e);
      r->e = sb_engine_checkpoint_load_capacity(c->restart, cap, &st);
    }
    if (!r->e)
      return sbi_col_fail(c, "%s: [run] restart = %s: %s",
                          sbi_col_where(c, "run", "restart"), c->restart,
                          sb_last_error());
    if ((sbi_col_given(c, "run", "dt") && sb_engine_set_dt(r->e, c->dt)) ||
        sb_engine_set_neigh(r->e, nm) ||
        sb_engine_set_threads(r->e, (int)c->threads) ||
        (!sbi_col_bridge(c) && (sb_engine_set_detect(r->e, dm) ||
                                sb_engine_set_outcome(r->e, om, c->eta))))
      return sbi_col_fail(c, "[run] restart: %s", sb_last_error());
    if (restart_species(c, r->e) || gravity_check(c, r->e))
      return -1;
    /* the position variance rates of the saved species, (B tau)^2: with
     * turbulence B holds its part (species_build), taken out again for
     * the Brownian one */
    for (int k = 0; k < COL_MAXSPEC; k++) {
      const sb_engine_species *s = sb_engine_get_species(r->e, (size_t)k);
      if (!s || !isfinite(s->tau))
        continue;
      c->b2_brown[k] = c->b2_total[k] = (s->B * s->tau) * (s->B * s->tau);
      if (c->eps > 0)
        c->b2_brown[k] = fmax(0.0, c->b2_total[k] -
                                       0.5 * sb_turb_pair_b2(2.0 * s->radius,
                                                             c->eps, c->nu));
    }
  } else {
    sb_engine_params p;
    sb_engine_params_default(&p);
    p.dim = (int)c->dim;
    p.L[0] = c->Lx;
    p.L[1] = c->Ly;
    p.L[2] = c->dim == 3 ? c->Lz : 1.0;
    p.dt = c->dt;
    p.seed = c->seed;
    p.neigh = nm;
    p.detect = dm;
    p.outcome = om;
    p.eta = c->eta;
    p.sort_every = (size_t)c->sort_every;
    p.rng_type = !strcmp(c->rng, "taus2")    ? gsl_rng_taus2
                 : !strcmp(c->rng, "philox") ? sb_rng_philox
                                             : gsl_rng_mt19937;
    p.streams = !strcmp(c->rng, "philox");
    p.threads = (int)c->threads;
    long total = 0;
    for (int k = 0; k < c->nsp; k++) {
      if (species_build(c, k, &q[k]))
        return -1;
      total += species_count(c, &c->sp[k]);
    }
    /* inflows: room for every particle that can enter in the run (none
     * leaving), at most 2e6 more (a restart asks for the same:
     * restart_capacity) */
    total += inflow_room(c, room_end(c, warmup_steps(c), c->dt));
    p.capacity = total > 0 ? (size_t)total : 1;
    r->e = sb_engine_alloc(&p);
    if (!r->e)
      return sbi_col_fail(c, "[run]: %s", sb_last_error());
    for (int k = 0; k < c->nsp; k++)
      if (sb_engine_add_species(r->e, &q[k], NULL))
        return sbi_col_fail(c, "%s: [%s]: %s", c->sp[k].where, c->sp[k].name,
                            sb_last_error());
    if (gravity_check(c, r->e))
      return -1;
  }
  /* fluid (on restart the saved field is kept unless [fluid] is given) */
  if (!c->restart[0] || sbi_col_given(c, "fluid", "type")) {
    double fp[3] = {0, 0, 0};
    sb_engine_fluid f = SB_FLUID_REST;
    if (!strcmp(c->fluid, "uniform")) {
      f = SB_FLUID_UNIFORM;
      memcpy(fp, c->U, sizeof fp);
    } else if (!strcmp(c->fluid, "shear")) {
      f = SB_FLUID_SHEAR;
      fp[0] = c->G;
    }
    if (sb_engine_set_fluid(r->e, f, fp))
      return sbi_col_fail(c, "[fluid]: %s", sb_last_error());
  }
  if (c->restart[0] ? restart_field(c, r) : setup_field(c, r))
    return -1;
  if (setup_physics(c, r))
    return -1;
  if (!c->restart[0]) {
    if (place(c, r, q))
      return -1;
    if (r->ou && sb_field_ou_attach(r->e, r->ou))
      return sbi_col_fail(c, "%s: [fluid] type = ou-field: %s",
                          sbi_col_where(c, "fluid", "type"), sb_last_error());
    if (c->thermalize > 0 && sb_engine_thermalize(r->e, c->thermalize))
      return sbi_col_fail(c, "%s: [run] thermalize: %s",
                          sbi_col_where(c, "run", "thermalize"),
                          sb_last_error());
    if (sbi_col_start_velocities(c, r))
      return -1;
  }
  if (sbi_col_bridge(c) && attach_bridge(c, r))
    return -1;
  if (sbi_col_agglo(c) && attach_agglo(c, r))
    return -1;
  if (!isnan(c->lv_eps) || !isnan(c->lv_xtol) || !isnan(c->lv_tol)) {
    /* over the defaults, or on restart over the checkpoint's */
    sb_engine_langevin_params lp;
    sb_engine_get_langevin(r->e, &lp);
    if (!isnan(c->lv_eps))
      lp.eps = c->lv_eps;
    if (!isnan(c->lv_xtol))
      lp.xtol = c->lv_xtol;
    if (!isnan(c->lv_tol))
      lp.tol = c->lv_tol;
    if (sb_engine_set_langevin(r->e, &lp))
      return sbi_col_fail(c, "[run] langevin_*: %s", sb_last_error());
  }
  r->dep_on = sbi_col_walls_absorb(c);
  if (sbi_col_detect_none(c) && sbi_col_none_attach(r))
    return sbi_col_fail(c, "[run] detect = none: %s", sb_last_error());
  if (sbi_col_exits_attach(c, r))
    return sbi_col_fail(c, "[observe] exits: %s", sb_last_error());
  /* a restart goes on with the checkpoint's tally (whole since its
   * reset), or starts one that gives NaN until the next reset */
  const int tally = sb_engine_get_count_variance(r->e);
  if (c->count_variance > 0 ? !tally && sb_engine_set_count_variance(r->e, 1)
                            : tally && sb_engine_set_count_variance(r->e, 0))
    return sbi_col_fail(c, "[observe] count_variance: %s", sb_last_error());
  if (sbi_col_md(c) && !c->first_hit &&
      sb_engine_set_detector(r->e, sb_engine_detect_md, NULL,
                             sbi_col_md_reach(c, r->e)))
    return sbi_col_fail(c, "[run] detect = md: %s", sb_last_error());
  if (c->first_hit) {
    double reach = r->bridge ? sb_engine_bridge_reach(r->e, r->bridge)
                   : dm == SB_DETECT_LANGEVIN ? sb_engine_langevin_reach(r->e)
                   : sbi_col_md(c)            ? sbi_col_md_reach(c, r->e)
                                              : 0.0;
    if (sbi_col_firsthit_attach(c, r, dm, reach))
      return sbi_col_fail(c, "[observe] first_hit: %s", sb_last_error());
  }
  /* per-pair columns of series.csv for 2 to 4 species (clusters:
   * sizes.csv); a restart goes on from the first run's rows */
  r->pairs.nsp = c->nsp <= 4 && !r->agglo ? c->nsp : 0;
  if (c->restart[0] && sbi_col_runstate_load(c, r))
    return -1;
  return 0;
}
