/* collide_start.c — [species NAME] velocities = antipodal: a start far
 * from equilibrium for relaxation studies (Boltzmann's H theorem; the
 * approach to Maxwell's law, Bird 1994, §1.5): every placed particle of
 * the species gets the speed sqrt(3 k_B T/m) of the species' T (the
 * energy (3/2) k_B T each), directions uniform on the sphere
 * (gsl_ran_dir_3d) in antipodal pairs (particles 2k and 2k + 1 of the
 * species, in placement order), so that the species' momentum is exactly
 * zero.  The directions come from an MT19937 generator seeded with
 * [run] velocity_seed (default: the engine's generator), drawn after the
 * placement and thermalize.  [species NAME] velocity_scale = s_x s_y s_z
 * then multiplies each velocity component of the placed particles: an
 * anisotropic start with per-axis temperatures s_k^2 T (from a
 * thermalized gas; the relaxation of the anisotropy, Bird 1994, §1.5). */
#include <math.h>
#include <string.h>

#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>

#include <smolbridge/engine.h>
#include <smolbridge/langevin.h>

#include "collide_internal.h"

int sbi_col_start_check(sbi_col_config *c)
{
  int any = 0;
  for (int k = 0; k < c->nsp; k++) {
    const sbi_col_species *s = &c->sp[k];
    if (s->nvscale && s->nvscale != c->dim)
      return sbi_col_fail(c, "%s: [%s] velocity_scale: %d numbers; valid: "
                          "dim = %ld (one factor per axis)",
                          sbi_col_where(c, s->name, "velocity_scale"),
                          s->name, s->nvscale, c->dim);
    if (strcmp(s->velocities, "antipodal"))
      continue;
    any = 1;
    const char *w = sbi_col_where(c, s->name, "velocities");
    if (c->dim != 3)
      return sbi_col_fail(c, "%s: [%s] velocities = antipodal needs dim = 3 "
                          "(directions on the sphere)", w, s->name);
    if (isnan(s->T))
      return sbi_col_fail(c, "%s: [%s] velocities = antipodal needs the "
                          "species' T (K): the speed is sqrt(3 k_B T/m)", w,
                          s->name);
    if (s->inflow[0])
      return sbi_col_fail(c, "%s: [%s] velocities = antipodal with inflow: "
                          "only placed particles start in pairs", w, s->name);
  }
  if (!any && sbi_col_given(c, "run", "velocity_seed"))
    sbi_col_warn(c, "%s: [run] velocity_seed ignored: no species with "
                 "velocities = antipodal",
                 sbi_col_where(c, "run", "velocity_seed"));
  return 0;
}

/* velocity_scale: the components of the placed particles multiplied */
static int scale_velocities(sbi_col_config *c, sbi_col_run *r, int nexplicit)
{
  const size_t n = sb_engine_count(r->e);
  const size_t *sp = sb_engine_species_of(r->e);
  const double *x = sb_engine_positions(r->e);
  const double *u = sb_engine_velocities(r->e);
  for (size_t i = (size_t)nexplicit; i < n; i++) {
    const sbi_col_species *s = &c->sp[sp[i]];
    if (!s->nvscale)
      continue;
    double xi[3], ui[3];
    for (int a = 0; a < 3; a++) {
      xi[a] = x[3 * i + a];
      ui[a] = a < s->nvscale ? s->vscale[a] * u[3 * i + a] : u[3 * i + a];
    }
    if (sb_engine_set_particle(r->e, i, xi, ui))
      return sbi_col_fail(c, "%s: [%s] velocity_scale: %s",
                          sbi_col_where(c, s->name, "velocity_scale"),
                          s->name, sb_last_error());
  }
  return 0;
}

int sbi_col_start_velocities(sbi_col_config *c, sbi_col_run *r)
{
  int nexplicit = 0, any = 0, scale = 0;  /* explicit particles first */
  for (int k = 0; k < c->nsp; k++) {
    nexplicit += c->sp[k].npart;
    any |= !strcmp(c->sp[k].velocities, "antipodal");
    scale |= c->sp[k].nvscale > 0;
  }
  if (!any)
    return scale ? scale_velocities(c, r, nexplicit) : 0;
  gsl_rng *g = sb_engine_rng(r->e);
  if (c->velocity_seed >= 0) {
    g = gsl_rng_alloc(gsl_rng_mt19937);
    if (!g)
      return sbi_col_fail(c, "out of memory");
    gsl_rng_set(g, (unsigned long)c->velocity_seed);
  }
  const size_t n = sb_engine_count(r->e);
  const size_t *sp = sb_engine_species_of(r->e);
  const double *x = sb_engine_positions(r->e);
  int st = 0;
  for (int k = 0; k < c->nsp && !st; k++) {
    const sbi_col_species *s = &c->sp[k];
    if (strcmp(s->velocities, "antipodal"))
      continue;
    const sb_engine_species *q = sb_engine_get_species(r->e, (size_t)k);
    const double v = sqrt(3.0 * SB_BOLTZMANN * q->T / q->mass);
    size_t first = (size_t)-1, np = 0;
    for (size_t i = (size_t)nexplicit; i < n && !st; i++) {
      if (sp[i] != (size_t)k)
        continue;
      np++;
      if (first == (size_t)-1) {
        first = i;
        continue;
      }
      double d[3], u[3], xi[3];
      gsl_ran_dir_3d(g, &d[0], &d[1], &d[2]);
      for (int a = 0; a < 3; a++) {
        u[a] = v * d[a];
        xi[a] = x[3 * first + a];
      }
      st = sb_engine_set_particle(r->e, first, xi, u);
      for (int a = 0; a < 3; a++) {
        u[a] = -u[a];
        xi[a] = x[3 * i + a];
      }
      if (!st)
        st = sb_engine_set_particle(r->e, i, xi, u);
      first = (size_t)-1;
    }
    if (st)
      st = sbi_col_fail(c, "[%s] velocities = antipodal: %s", s->name,
                        sb_last_error());
    else if (np % 2)
      st = sbi_col_fail(c, "%s: [%s] velocities = antipodal: %zu placed "
                        "particles; valid: an even number (antipodal pairs)",
                        sbi_col_where(c, s->name, "velocities"), s->name, np);
  }
  if (g != sb_engine_rng(r->e))
    gsl_rng_free(g);
  if (!st && scale)
    st = scale_velocities(c, r, nexplicit);
  return st;
}
