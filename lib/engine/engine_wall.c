/* engine_wall.c — walls beside periodic boundaries, deposition, the end
 * of the step (walls, then wrapping with the Lees-Edwards shift), and the
 * checkpoint block of forces, Lees-Edwards and walls
 * (docs/engine_forces.md).
 *
 * A particle of radius r touches the face at 0 when its centre reaches
 * the contact plane a = r (the face at L: a = L - r).  Over a step its
 * wall-normal coordinate goes from y0 (inside) to y1:
 *  - ballistic detector: contact iff y1 is beyond the plane (the straight
 *    chord crosses it; exact for straight paths);
 *  - bridge detector (Mohaupt 2011, §5.1): contact if y1 is beyond the
 *    plane, else with the probability that a Brownian bridge from y0 to
 *    y1 over the step, variance rate B_pos^2 = (B tau_p)^2, crosses it:
 *    P = exp(-2 (y0 - a)(y1 - a) / (B_pos^2 dt)) (sb_bb_cross_prob).
 *    Exact for Brownian motion, i.e. in the diffusive regime dt >> tau_p
 *    of the Langevin particles (there the position increments are those
 *    of a Brownian motion of diffusivity B_pos^2/2 = k_B T tau_p/m);
 *  - Langevin detector: the particle's path between its end states
 *    (x0, u0) and (x1, u1) is the exact conditional law of the Langevin
 *    model (each component an integrated OU bridge given both ends, fluid
 *    velocity plus settling velocity held over the step); its first
 *    passage through the contact plane is sampled by the pair sampler
 *    with the half-space in place of the ball
 *    (sb_langevin_hitter_sample_plane: midpoint refinement, Rice bound,
 *    chord leaves): exact at every dt/tau_p, the wall counterpart of the
 *    pair detector SB_DETECT_LANGEVIN.
 * A reflecting face folds the end state (y1 -> 2a - y1, u_y -> -u_y):
 * the dynamics without walls is symmetric under that reflection, so the
 * folded free path is the reflected path (exact in law).  Walls are
 * processed once per step, after the particle-particle events.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_rng.h>
#include <smolbridge/bridge.h>
#include <smolbridge/langevin_hit.h>

#include "common/internal.h"
#include "engine_internal.h"

int sb_engine_set_walls(sb_engine *e, int k, sb_engine_wall lo,
                        sb_engine_wall hi)
{
  if (!e || k < 0 || k >= e->par.dim)
    return sbi_error(SB_EINVAL, __func__, "bad engine or direction %d", k);
  if ((unsigned)lo > SB_WALL_OPEN || (unsigned)hi > SB_WALL_OPEN)
    return sbi_error(SB_EINVAL, __func__, "unknown wall type");
  if ((lo == SB_WALL_PERIODIC) != (hi == SB_WALL_PERIODIC))
    return sbi_error(SB_EINVAL, __func__, "direction %d: periodic on one "
                     "face only", k);
  if (e->lees && k <= 1 && lo != SB_WALL_PERIODIC)
    return sbi_error(SB_EINVAL, __func__, "Lees-Edwards boundaries need x "
                     "and y periodic");
  e->wall[2 * k] = lo;
  e->wall[2 * k + 1] = hi;
  e->walled = 0;
  for (int f = 0; f < 6; f++)
    if (e->wall[f] != SB_WALL_PERIODIC)
      e->walled = 1;
  e->norder = 0;
  return SB_SUCCESS;
}

int sb_engine_get_walls(const sb_engine *e, int k, sb_engine_wall *lo,
                        sb_engine_wall *hi)
{
  if (!e || k < 0 || k >= e->par.dim)
    return sbi_error(SB_EINVAL, __func__, "bad engine or direction %d", k);
  if (lo)
    *lo = e->wall[2 * k];
  if (hi)
    *hi = e->wall[2 * k + 1];
  return SB_SUCCESS;
}

int sb_engine_set_wall_mode(sb_engine *e, sb_engine_walldet det,
                            sb_engine_deposit dep)
{
  if (!e || (unsigned)det > SB_WALLDET_LANGEVIN ||
      (unsigned)dep > SB_DEPOSIT_REINSERT)
    return sbi_error(SB_EINVAL, __func__, "bad engine, detector or "
                     "deposition outcome");
  e->walldet = det;
  e->deposit = dep;
  return SB_SUCCESS;
}

int sb_engine_get_wall_mode(const sb_engine *e, sb_engine_walldet *det,
                            sb_engine_deposit *dep)
{
  if (!e)
    return sbi_error(SB_EINVAL, __func__, "engine is NULL");
  if (det)
    *det = e->walldet;
  if (dep)
    *dep = e->deposit;
  return SB_SUCCESS;
}

uint64_t sb_engine_deposits(const sb_engine *e, int face)
{
  if (!e) {
    sbi_error(SB_EINVAL, __func__, "engine is NULL");
    return 0;
  }
  return (face >= 0 && face < 6) ? e->ndep[face] : 0;
}

int sb_engine_periodic(const sb_engine *e, int k)
{
  if (!e) {
    sbi_error(SB_EINVAL, __func__, "engine is NULL");
    return 0;
  }
  return k >= 0 && k < 3 && e->wall[2 * k] == SB_WALL_PERIODIC;
}

/* Reinsert particle i uniformly in the accessible volume with an
 * equilibrium velocity (uniform volume source); one that is not finite is
 * SB_ERANGE, a fluid callback's failure SB_EINVAL: the step is then
 * undone, every particle back at its start (no half-made step). */
static int reinsert(sb_engine *e, size_t i)
{
  double x[3] = {0, 0, 0}, u[3];
  const double r = e->radius[i];
  for (int k = 0; k < e->par.dim; k++) {
    double lo = 0.0, L = e->par.L[k];
    if (e->wall[2 * k] != SB_WALL_PERIODIC) {
      lo = r;
      L -= 2.0 * r;
    }
    x[k] = lo + L * gsl_rng_uniform(e->rng);
  }
  int st = sbi_engine_equilibrium_velocity(e, e->species[i], x, u, i,
                                           "sb_engine_step");
  if (st) {
    sbi_engine_step_undo(e);
    return st;
  }
  memcpy(&e->x[3 * i], x, sizeof x);
  memcpy(&e->u[3 * i], u, sizeof u);
  return SB_SUCCESS;
}

/* The Langevin detector of touches(): the plane n.x = level with n = e_k
 * (face at 0) or -e_k (face at L), approached from inside.  Status < 0 on
 * error, else 0 / 1. */
static int touches_langevin(sb_engine *e, size_t i, int k, int s, double a)
{
  const sb_engine_species *sp = &e->spec[e->species[i]];
  sb_langevin_path q;
  double w[3];  /* a nonlinear drag: its step's rate and terminal slip */
  sbi_engine_relax(e, i, &q.tau, w);
  q.B = sp->B;
  q.mass = e->mass[i];
  q.G = 0.0;
  for (int c = 0; c < 3; c++) {
    q.us[c] = w[c];
    q.x0[c] = e->x0[3 * i + c];
    q.u0[c] = e->u0[3 * i + c];
    q.x1[c] = e->x[3 * i + c];
    q.u1[c] = e->u[3 * i + c];
  }
  double n[3] = {0, 0, 0};
  n[k] = s ? -1.0 : 1.0;
  const double level = s ? -(e->par.L[k] - a) : a;
  /* resolution: the particle radius, or the step's spread for a point */
  const double scale = e->radius[i] > 0.0
                           ? e->radius[i]
                           : sqrt(sb_langevin_var_x(sp->tau, sp->B,
                                                    e->par.dt)) + 1e-300;
  sb_langevin_hitter_reset(e->lh);
  int h = sb_langevin_hitter_sample_plane(e->lh, &q, n, level, scale,
                                          e->par.dt, e->rng, NULL);
  sbi_engine_langevin_done(e, e->lh);
  return h < 0 ? h : h == 1;
}

/* Does particle i reach the plane at distance a from face f (direction
 * k, side s) during the step?  a = r: contact with an absorbing wall;
 * a = 0: the centre leaves through an open face. */
static int touches(sb_engine *e, size_t i, int k, int s, double a)
{
  const double r = a, L = e->par.L[k];
  /* distances to the plane, positive inside */
  double h0 = s ? (L - r) - e->x0[3 * i + k] : e->x0[3 * i + k] - r;
  double h1 = s ? (L - r) - e->x[3 * i + k] : e->x[3 * i + k] - r;
  if (h0 <= 0.0 || h1 <= 0.0)
    return 1;
  if (e->walldet == SB_WALLDET_BALLISTIC)
    return 0;
  const sb_engine_species *sp = &e->spec[e->species[i]];
  if (isinf(sp->tau))
    return 0;  /* free flight: the chord is the path */
  if (e->walldet == SB_WALLDET_LANGEVIN)
    return touches_langevin(e, i, k, s, a);
  if (sp->B == 0.0)
    return 0;
  const double bpos = sp->B * sp->tau;
  double P = sb_bb_cross_prob(h0, h1, 0.0, bpos * bpos * e->par.dt);
  if (!(P > 1e-300))
    return 0;
  return gsl_rng_uniform(e->rng) < P;
}

static int walls(sb_engine *e)
{
  const int dim = e->par.dim;
  for (size_t i = 0; i < e->n; i++) {
    if (e->hit[i] == 2)
      continue;
    for (int k = 0; k < dim; k++) {
      if (e->wall[2 * k] == SB_WALL_PERIODIC)
        continue;
      const double r = e->radius[i], L = e->par.L[k];
      int dep = -1, out = -1;
      for (int s = 0; s < 2 && dep < 0 && out < 0; s++) {
        const sb_engine_wall wt = e->wall[2 * k + s];
        if (wt != SB_WALL_ABSORB && wt != SB_WALL_OPEN)
          continue;
        int t = touches(e, i, k, s, wt == SB_WALL_ABSORB ? r : 0.0);
        if (t < 0)
          return sbi_error(SB_EINVAL, "sb_engine_step", "particle %zu: "
                           "wall contact failed: %s", i, sb_last_error());
        if (t && wt == SB_WALL_ABSORB)
          dep = s;
        else if (t)
          out = s;
      }
      if (out >= 0) {  /* leaves through an open face (engine_open.c) */
        int st = sbi_engine_outflow(e, i, 2 * k + out);
        if (st)
          return st;
        break;
      }
      if (dep >= 0) {
        e->ndep[2 * k + dep]++;
        if (e->deposit == SB_DEPOSIT_REMOVE) {
          e->hit[i] = 2;
          e->nremove++;
        } else {
          int st = reinsert(e, i);
          if (st)
            return st;
        }
        break;
      }
      /* reflecting faces: fold until inside (a step longer than the
       * width folds several times) */
      for (int it = 0; it < 64; it++) {
        double *y = &e->x[3 * i + k], *u = &e->u[3 * i + k];
        if (e->wall[2 * k] == SB_WALL_REFLECT && *y < r) {
          *y = 2.0 * r - *y;
          *u = -*u;
        } else if (e->wall[2 * k + 1] == SB_WALL_REFLECT && *y > L - r) {
          *y = 2.0 * (L - r) - *y;
          *u = -*u;
        } else
          break;
      }
    }
  }
  return e->nremove ? sbi_engine_purge(e) : SB_SUCCESS;
}

/* Wrap the periodic coordinates of one position that left the box
 * (writing only those: most do not move out in a step, and their cache
 * lines stay clean). */
static inline void wrap_periodic(double *x, const double *L, const int *per,
                                 int dim)
{
  for (int k = 0; k < dim; k++)
    if (per[k] && (x[k] >= L[k] || x[k] < 0.0))
      x[k] = sbi_wrap(x[k], L[k]);
}

void sbi_engine_wrap_one(sb_engine *e, size_t i)
{
  const double *L = e->par.L;
  double *x = &e->x[3 * i];
  if (e->lees) {  /* as the pass below, without advancing the offset */
    const double n = floor(x[1] / L[1]);
    if (n != 0.0) {
      x[1] -= n * L[1];
      x[0] -= n * e->le_off;
      e->u[3 * i] -= n * e->fluid_p[0] * L[1];
      if (x[1] >= L[1])
        x[1] = 0.0;
    }
  }
  int per[3] = {0, 0, 0};
  for (int k = 0; k < e->par.dim; k++)
    per[k] = e->wall[2 * k] == SB_WALL_PERIODIC;
  wrap_periodic(x, L, per, e->par.dim);
}

int sbi_engine_boundaries(sb_engine *e)
{
  if (e->walled) {
    int st = walls(e);
    if (st)
      return st;
  }
  const int dim = e->par.dim;
  const double *L = e->par.L;
  if (e->lees) {
    const double G = e->fluid_p[0];
    double d = fmod(e->le_off + G * L[1] * e->par.dt, L[0]);
    e->le_off = d < 0.0 ? d + L[0] : (d >= L[0] ? 0.0 : d);
    for (size_t i = 0; i < e->n; i++) {
      double *x = &e->x[3 * i];
      double n = floor(x[1] / L[1]);
      if (n != 0.0) {
        x[1] -= n * L[1];
        x[0] -= n * e->le_off;
        e->u[3 * i] -= n * G * L[1];
        if (x[1] >= L[1])  /* rounding */
          x[1] = 0.0;
      }
    }
  }
  /* periodic faces */
  int per[3] = {0, 0, 0};
  for (int k = 0; k < dim; k++)
    per[k] = e->wall[2 * k] == SB_WALL_PERIODIC;
  const size_t n = e->n;
  double *x = e->x;
  const int nt = n >= 4096 ? sbi_engine_threads(&e->par) : 1;
  if (nt > 1) {
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 4096) num_threads(nt)
#endif
    for (size_t i = 0; i < n; i++)
      wrap_periodic(&x[3 * i], L, per, dim);
  } else {  /* no parallel region: entering one costs ~0.3 us */
    for (size_t i = 0; i < n; i++)
      wrap_periodic(&x[3 * i], L, per, dim);
  }
  return SB_SUCCESS;
}

/* ------------------------------------------------------- checkpoint */

/* numbers of `size` bytes, in the checkpoint's byte order (swap) */
#define W(ptr, size, count)                                       \
  do {                                                            \
    if (!sbi_write_ord(f, (ptr), (size), (count), swap))          \
      return SB_EIO;                                              \
  } while (0)
#define R(ptr, size, count)                                       \
  do {                                                            \
    if (!sbi_read_ord(f, (ptr), (size), (count), swap))           \
      return SB_EFORMAT;                                          \
  } while (0)

int sbi_engine_physics_save(const sb_engine *e, FILE *f, int swap)
{
  int32_t iv[11] = {e->has_grav, e->lees, e->walled, (int32_t)e->walldet,
                    (int32_t)e->deposit};
  for (int q = 0; q < 6; q++)
    iv[5 + q] = (int32_t)e->wall[q];
  W(iv, sizeof iv[0], 11);
  W(e->grav, sizeof(double), 3);
  W(&e->le_off, sizeof e->le_off, 1);
  W(e->ndep, sizeof e->ndep[0], 6);
  uint64_t ns = e->nsfl;
  W(&ns, sizeof ns, 1);
  for (size_t k = 0; k < e->nsfl; k++) {
    int32_t d = (int32_t)e->sfl[k].drag;
    W(&d, sizeof d, 1);
    W(&e->sfl[k].rho_f, sizeof(double), 1);
    W(&e->sfl[k].mu, sizeof(double), 1);
  }
  return SB_SUCCESS;
}

int sbi_engine_physics_load(sb_engine *e, FILE *f, int swap)
{
  int32_t iv[11];
  R(iv, sizeof iv[0], 11);
  double g[3];
  R(g, sizeof(double), 3);
  R(&e->le_off, sizeof e->le_off, 1);
  R(e->ndep, sizeof e->ndep[0], 6);
  uint64_t ns;
  R(&ns, sizeof ns, 1);
  if (ns > e->nspec || (unsigned)iv[3] > SB_WALLDET_BALLISTIC ||
      (unsigned)iv[4] > SB_DEPOSIT_REINSERT)
    return SB_EFORMAT;
  if (sb_engine_set_gravity(e, g))
    return SB_EFORMAT;
  for (size_t k = 0; k < ns; k++) {
    int32_t d;
    sb_engine_species_fluid fl;
    R(&d, sizeof d, 1);
    R(&fl.rho_f, sizeof(double), 1);
    R(&fl.mu, sizeof(double), 1);
    fl.drag = (sb_engine_drag)d;
    if (sb_engine_set_species_fluid(e, k, &fl))
      return SB_EFORMAT;
  }
  for (int q = 0; q < 6; q++) {
    int32_t v = iv[5 + q];
    if ((unsigned)v > SB_WALL_OPEN)
      return SB_EFORMAT;
    e->wall[q] = (sb_engine_wall)v;
  }
  e->walled = iv[2] != 0;
  e->walldet = (sb_engine_walldet)iv[3];
  e->deposit = (sb_engine_deposit)iv[4];
  e->lees = iv[1] != 0;  /* the shear field itself was loaded before */
  return SB_SUCCESS;
}
