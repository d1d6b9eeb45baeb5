/* smolbridge/pgd.h — pressureless gas dynamics (the T = 0 moment system of
 * a monokinetic spray) on a regular 1-D or 2-D grid, its exact solutions,
 * weighted Lagrangian particles with the same inflow, and their coupling by
 * domain decomposition.
 *
 * Equations (d = 1 or 2 space dimensions):
 *
 *   d_t rho      + div(rho u)      = 0
 *   d_t (rho u)  + div(rho u (x) u) = rho (U_gas(x) - u) / tau
 *
 * rho the particle mass per unit length (1-D) or area (2-D), u their
 * velocity, tau the Stokes relaxation time (INFINITY: no drag), U_gas a
 * steady gas velocity (uniform, or a callback sampled at cell centres).
 * The module is unit-free: use any consistent units (the validation runs
 * in the exercise's dimensionless units: unit square, jet speed 1).
 *
 * Schemes (docs/pgd.md):
 *  - SB_PGD_UPWIND: the first-order kinetic flux splitting
 *    F(UL, UR) = F+(UL) + F-(UR), F+-(rho, u) = rho max/min(u_n, 0) (1, u)
 *    (the upwind fluxes of the exercise "Couplage Euler-Lagrange" (2022),
 *    eq. 6, completed by the momentum flux; Bouchut, Jin & Li 2003).
 *    Positive and velocity-bounded (maximum principle on u) for
 *    dt (max|ux|/dx + max|uy|/dy) <= 1.
 *  - SB_PGD_MUSCL: the same kinetic flux on a piecewise-linear
 *    reconstruction of rho and u (minmod slopes, the u slope weighted so
 *    that the reconstruction conserves rho u), SSP-RK2 (Heun) in time;
 *    first order in cells where the flow converges onto a density jump
 *    larger than a factor 2 (delta-shocks).  Second order for smooth
 *    solutions with monotone velocity (measured 1.5 at velocity extrema,
 *    where the limiter clips), positive and velocity-bounded for
 *    dt (max|ux|/dx + max|uy|/dy) <= 1/2.
 *  Drag: Strang splitting D(dt/2) T(dt) D(dt/2) with the exact relaxation
 *  u <- U + (u - U) exp(-t/tau) in each cell (second order overall).
 *
 * Layout of field arrays: cell (i, j), i = 0..nx-1 along x, j = 0..ny-1
 * along y, stored at index i + nx j; centres at origin + ((i+1/2) dx,
 * (j+1/2) dy).  Sides: SB_PGD_WEST (x = x0), SB_PGD_EAST, SB_PGD_SOUTH
 * (y = y0), SB_PGD_NORTH; boundary cell k of a side counts along the side
 * (j for west/east, i for south/north).
 */
#ifndef SMOLBRIDGE_PGD_H
#define SMOLBRIDGE_PGD_H

#include <stddef.h>
#include <stdio.h>
#include <smolbridge/common.h>

#ifdef __cplusplus
extern "C" {
#endif

/* ================================================== problem description */

typedef enum {
  SB_PGD_UPWIND = 0,  /**< first-order kinetic upwind, cfl <= 1 */
  SB_PGD_MUSCL = 1    /**< second-order kinetic MUSCL + SSP-RK2, cfl <= 1/2 */
} sb_pgd_scheme;

typedef enum {
  SB_PGD_WEST = 0,
  SB_PGD_EAST = 1,
  SB_PGD_SOUTH = 2,
  SB_PGD_NORTH = 3
} sb_pgd_side;

typedef enum {
  SB_PGD_TRANSMISSIVE = 0, /**< zero-gradient ghost cells (default) */
  SB_PGD_OUTFLOW = 1,      /**< vacuum ghost cells: mass may leave, none
                                enters (particles leaving are removed) */
  SB_PGD_PERIODIC = 2      /**< both sides of the direction must be set */
} sb_pgd_bc;

/** Inflow on `count` consecutive boundary cells of one side, starting at
 *  boundary cell `first`: the ghost state (rho, u); mass enters at the rate
 *  rho max(u.n_in, 0) per unit face length. */
typedef struct {
  sb_pgd_side side;
  size_t first, count;
  double rho;
  double u[2];
} sb_pgd_inflow;

#define SB_PGD_MAXINFLOW 8

/** Gas velocity at (x, y) (y = 0 in 1-D): fill ug[0..1]. */
typedef void (*sb_pgd_gas_fn)(double x, double y, double ug[2], void *data);

typedef struct {
  int dim;               /**< 1 or 2 */
  size_t nx, ny;         /**< cells; ny is forced to 1 in 1-D */
  double L[2];           /**< domain lengths (> 0) */
  double origin[2];      /**< lower-left corner */
  sb_pgd_scheme scheme;
  double cfl;            /**< Courant number dt max(|ux|/dx + |uy|/dy), in
                              (0, 1] (upwind) or (0, 1/2] (muscl); 0.5 */
  double dt_max;         /**< cap on the step (INFINITY: none, default) */
  double tau;            /**< relaxation time > 0; INFINITY: no drag */
  double ugas[2];        /**< uniform gas velocity (default 0) */
  sb_pgd_gas_fn gas;     /**< if not NULL, overrides ugas */
  void *gas_data;
  sb_pgd_bc bc[4];       /**< per side, default transmissive */
  sb_pgd_inflow inflow[SB_PGD_MAXINFLOW];
  size_t ninflow;
  double rho_floor;      /**< cells with rho <= floor have u = 0 (1e-14) */
  /* Lagrangian particles (sb_pgd_lag, sb_pgd_dd): each inflow face injects
   * inject_time x inject_face particles per step, on a lattice in (time of
   * entry, position along the face); weights share the entering mass. */
  size_t inject_time;    /**< default 2 */
  size_t inject_face;    /**< default 2 */
} sb_pgd_params;

/** Defaults for dimension dim (1 or 2): unit domain, 100 (x 100) cells,
 *  upwind, cfl 0.5, no drag, gas at rest, transmissive sides. */
void sb_pgd_params_default(sb_pgd_params *p, int dim);

/** Check p; SB_EINVAL with a message naming the field. */
int sb_pgd_params_check(const sb_pgd_params *p);

/** Add an inflow segment to p (SB_EINVAL if full or out of range). */
int sb_pgd_params_add_inflow(sb_pgd_params *p, sb_pgd_side side,
                             size_t first, size_t count, double rho,
                             double ux, double uy);

/** "upwind" | "muscl" -> scheme; SB_EINVAL otherwise.  s may be NULL
 *  (the name is only checked). */
int sb_pgd_scheme_from_name(const char *name, sb_pgd_scheme *s);
const char *sb_pgd_scheme_name(sb_pgd_scheme s);

/* ================================================== Eulerian solver */

typedef struct sb_pgd sb_pgd;

/** Allocate a solver for p (copied) with vacuum everywhere at t = 0.
 *  NULL on error (message recorded). */
sb_pgd *sb_pgd_alloc(const sb_pgd_params *p);
void sb_pgd_free(sb_pgd *g);

const sb_pgd_params *sb_pgd_get_params(const sb_pgd *g);

/** Initial state from point values: each cell gets the average of rho and
 *  rho u over the cell (3-point Gauss-Legendre per direction, exact for
 *  polynomials of degree 5).  f fills rho, u[0..1] at (x, y). */
typedef void (*sb_pgd_init_fn)(double x, double y, double *rho, double u[2],
                               void *data);
int sb_pgd_init(sb_pgd *g, sb_pgd_init_fn f, void *data);

/** Set one cell (rho >= 0). */
int sb_pgd_set_cell(sb_pgd *g, size_t i, size_t j, double rho, double ux,
                    double uy);

/** Read one cell: rho and u (u = 0 where rho <= rho_floor). */
int sb_pgd_get_cell(const sb_pgd *g, size_t i, size_t j, double *rho,
                    double u[2]);

/** Copy the fields to caller arrays of nx ny values (any may be NULL):
 *  rho, momentum rho ux, rho uy. */
int sb_pgd_fields(const sb_pgd *g, double *rho, double *qx, double *qy);

/** Largest stable step at the current state (cfl, dt_max, and the gas
 *  velocity, towards which the drag relaxes u, are accounted for);
 *  INFINITY if nothing moves. */
double sb_pgd_dt(const sb_pgd *g);

/** One Strang step of length dt (0 < dt <= sb_pgd_dt(g) (1 + 1e-12));
 *  SB_EINVAL otherwise, state unchanged. */
int sb_pgd_step(sb_pgd *g, double dt);

/** Steps of length sb_pgd_dt() (the last one shortened) until t_end. */
int sb_pgd_advance(sb_pgd *g, double t_end, size_t *nsteps);

double sb_pgd_time(const sb_pgd *g);
size_t sb_pgd_steps(const sb_pgd *g);

/** Totals over the domain: tot[0] = mass, tot[1..2] = momentum. */
void sb_pgd_totals(const sb_pgd *g, double tot[3]);

/** Mass and momentum that entered (in) and left (out) through the sides
 *  since t = 0, so that totals(t) = totals(0) + in - out + drag impulse. */
void sb_pgd_boundary_totals(const sb_pgd *g, double in[3], double out[3]);
/** The same through one side. */
void sb_pgd_side_totals(const sb_pgd *g, sb_pgd_side s, double in[3],
                        double out[3]);

/** Cell-centred fields as CSV with a header: "x,rho,u" (1-D) or
 *  "x,y,rho,ux,uy" (2-D), 17 significant digits. */
int sb_pgd_write_csv(const sb_pgd *g, const char *path);

/** 2-D fields as a legacy VTK file (STRUCTURED_POINTS, CELL_DATA rho and
 *  the vector u) for ParaView; SB_EINVAL in 1-D. */
int sb_pgd_write_vtk(const sb_pgd *g, const char *path);

/** Checkpoint: save the whole state of g to path so that the solver
 *  loaded from it continues bit for bit as g would (the fields with their
 *  ghost cells, time, step count, the boundary budget of
 *  sb_pgd_boundary_totals / _side_totals, and every parameter: scheme,
 *  cfl, dt_max, drag, sides, inflows, rho_floor).  The file is
 *  little-endian on every machine (docs/pgd.md, "Checkpoints"): the magic "SBPGDE01", the type
 *  sizes of the build, the parameters and state, and a 64-bit FNV-1a hash
 *  of all of it; it is written from memory in one piece, and a failed
 *  write leaves no file (the engine's convention, sb_engine_checkpoint_save).
 *  SB_EINVAL (NULL argument), SB_EIO (cannot write), SB_ENOMEM.
 *
 *  The gas velocity callback (p.gas, p.gas_data) cannot be saved: only a
 *  fingerprint of its velocities at the cell centres is.  A solver loaded
 *  from a checkpoint saved with a callback refuses to step (SB_EINVAL)
 *  until the caller attaches one again with sb_pgd_set_gas. */
int sb_pgd_checkpoint_save(const sb_pgd *g, const char *path);

/** A new solver from a checkpoint of sb_pgd_checkpoint_save, or NULL with
 *  *status (status may be NULL) and the message: SB_EINVAL (NULL path),
 *  SB_EIO (cannot open or read), SB_EFORMAT (not a solver checkpoint,
 *  e.g. a particle checkpoint; a newer version of the format; damaged:
 *  cut short or changed, the hash does not match; in big-endian order, an
 *  older build's on a big-endian machine: the hash matches byte-swapped;
 *  written by a
 *  build with other type sizes; parameters or state that do not fit),
 *  SB_ENOMEM.  Nothing is returned in part. */
sb_pgd *sb_pgd_checkpoint_load(const char *path, int *status);

/** Attach the gas velocity callback (NULL: the uniform ugas) and sample
 *  it again at the cell centres.  On a solver loaded from a checkpoint
 *  saved with a callback, gas must give the same velocities at the cell
 *  centres as that one (SB_EINVAL otherwise, nothing changed). */
int sb_pgd_set_gas(sb_pgd *g, sb_pgd_gas_fn gas, void *data);

/* ================================================== exact solutions */

/** The 1-D Riemann problem of pressureless gas dynamics with the
 *  discontinuity at x0 at t = 0, optional drag towards a uniform gas
 *  velocity ugas (tau = INFINITY: none).  Admissible solution (Bouchut
 *  1994; Sheng & Zhang 1999; derivation in docs/pgd.md):
 *   - u_l < u_r: the two states separate; vacuum between
 *     x0 + u_l s and x0 + u_r s;
 *   - u_l = u_r: a contact moving with the states;
 *   - u_l > u_r (rho_l, rho_r > 0): a delta-shock at
 *     x0 + sigma s, carrying the mass w = sqrt(rho_l rho_r)(u_l - u_r) s,
 *     sigma = (sqrt(rho_l) u_l + sqrt(rho_r) u_r)/(sqrt(rho_l) + sqrt(rho_r))
 *     (generalised Rankine-Hugoniot conditions).
 *  With drag, velocities are measured from ugas and s = tau (1 - e^-t/tau)
 *  replaces t (the sticky dynamics commutes with the linear drag); every
 *  velocity v then reads ugas + (v - ugas) e^{-t/tau}, positions shift by
 *  ugas t. */
typedef struct {
  double x0;
  double rho_l, u_l, rho_r, u_r;  /**< rho >= 0, finite */
  double tau;                     /**< > 0 or INFINITY */
  double ugas;
} sb_pgd_riemann;

typedef enum {
  SB_PGD_WAVE_CONTACT = 0,  /**< u_l = u_r, or one side vacuum */
  SB_PGD_WAVE_VACUUM = 1,   /**< u_l < u_r: vacuum between the states */
  SB_PGD_WAVE_DELTA = 2,    /**< u_l > u_r: delta-shock */
  SB_PGD_WAVE_NONE = 3      /**< both sides vacuum */
} sb_pgd_wave;

/** The waves at time t >= 0: the left state occupies x < xl, the right
 *  state x > xr (xl = xr for a contact or a delta), vacuum between; a
 *  delta-shock sits at xl = xr with mass `mass` and velocity `vel`. */
typedef struct {
  sb_pgd_wave type;
  double xl, xr;
  double mass, vel;   /**< delta-shock (0, NaN otherwise) */
  double ul, ur;      /**< velocities of the two states at t */
} sb_pgd_riemann_sol;

/** SB_EDOM for arguments outside the ranges above (t finite >= 0);
 *  SB_ERANGE when a wave position, a velocity or the delta's mass is not
 *  a finite double (e.g. u_l - u_r or sqrt(rho_l rho_r)(u_l - u_r) s
 *  beyond DBL_MAX).  The delta speed is formed through its weights where
 *  sqrt(rho_l) u_l overflows, the mass rate with an extended exponent
 *  where sqrt(rho_l rho_r) or the product leaves the range.  The same
 *  statuses, named after the function called, hold for _eval (x not
 *  NaN), _integral (SB_ERANGE when the mass or momentum in [a, b]
 *  overflows, e.g. an infinite a or b on a side of density > 0; the
 *  sums are formed with an extended exponent where b - a, rho u or
 *  rho u (b - a) leaves the double range, so the result is right
 *  wherever it is a double) and _error.  Wave positions and the delta's
 *  mass are formed with an extended exponent too, so x0 + u t is right
 *  where u t overflows and the position does not.  _eval, _integral and
 *  _error need only finite velocities (ul, ur and the delta's; SB_ERANGE
 *  otherwise): a wave position beyond DBL_MAX lies outside every finite
 *  [a, b] or cell and only bounds the states there (exactly), a delta
 *  outside [a, b] or the cells adds nothing whatever its mass, _eval
 *  compares x with the exact positions (x = +inf is right of a wave
 *  beyond DBL_MAX, -inf left of one beyond -DBL_MAX), and over an
 *  infinite a or b the true position is used (a state of density > 0
 *  against vacuum up to x = 1e310 holds a finite mass); SB_ERANGE there
 *  only where the mass or momentum in [a, b], or a norm of _error, itself
 *  overflows (a delta inside [a, b] or the cells whose mass exceeds
 *  DBL_MAX, say). */
int sb_pgd_riemann_solve(const sb_pgd_riemann *rp, double t,
                         sb_pgd_riemann_sol *sol);

/** Point value at (x, t): rho and u (u = 0 in vacuum; at a discontinuity
 *  the right-hand value; the delta's mass is not a point value, see
 *  sb_pgd_riemann_integral). */
int sb_pgd_riemann_eval(const sb_pgd_riemann *rp, double x, double t,
                        double *rho, double *u);

/** Exact mass and momentum in [a, b] at time t, the delta's included when
 *  a <= x_delta < b. */
int sb_pgd_riemann_integral(const sb_pgd_riemann *rp, double t, double a,
                            double b, double *mass, double *mom);

/** Speed and mass growth rate of the delta-shock of (rho_l, u_l) against
 *  (rho_r, u_r) without drag (u_l > u_r, rho_l, rho_r > 0, all finite;
 *  NaN with SB_EDOM otherwise).  The speed, a weighted mean of u_l and
 *  u_r, is representable for every valid argument; the mass rate is NaN
 *  with SB_ERANGE where it exceeds DBL_MAX. */
double sb_pgd_delta_speed(double rho_l, double u_l, double rho_r,
                          double u_r);
double sb_pgd_delta_mass_rate(double rho_l, double u_l, double rho_r,
                              double u_r);

/** L1 distance between a 1-D cell field rho[0..n-1] on cells
 *  [a + i h, a + (i+1) h] and the exact Riemann solution at t:
 *  l1 = sum_i |rho_i h - exact mass of cell i| (the L1 distance of the
 *  cell averages); w1 = integral over [a, a + n h] of |M_num - M_exact|,
 *  M the cumulative mass from a (the Wasserstein-1 distance when both
 *  masses agree), computed exactly for the piecewise-constant numerical
 *  density.  Either pointer may be NULL.  SB_EINVAL for a NULL rho or
 *  n = 0; SB_EDOM unless a, h > 0, a + n h and every rho[i] are finite;
 *  SB_ERANGE where the cells are not resolved in double precision
 *  (max(|a|, |a + n h|) DBL_EPSILON > 1e-6 h) or a norm overflows. */
int sb_pgd_riemann_error(const sb_pgd_riemann *rp, double t, double a,
                         double h, size_t n, const double *rho, double *l1,
                         double *w1);

/** A smooth 1-D solution from smooth initial data (rho0, u0) before
 *  characteristics cross, with drag towards a uniform ugas: a particle
 *  from xi is at X(xi, t) = xi + ugas t + (u0(xi) - ugas) s(t),
 *  s = tau (1 - e^-t/tau) (s = t without drag), with velocity
 *  ugas + (u0(xi) - ugas) e^{-t/tau}.  Mass in [a, b] is M0(xi_b) -
 *  M0(xi_a) with M0 a primitive of rho0 and xi_a, xi_b the feet of the
 *  characteristics (GSL Brent root finding); momentum by GSL quadrature
 *  over [xi_a, xi_b]. */
typedef struct {
  double (*rho0)(double xi, void *data);
  double (*mass0)(double xi, void *data);  /**< a primitive of rho0 */
  double (*u0)(double xi, void *data);
  void *data;
  double tau;   /**< > 0 or INFINITY */
  double ugas;
} sb_pgd_smooth;

/** Foot xi of the characteristic through (x, t): the root of
 *  X(xi, t) = x, bracketed by expansion from x - ugas t and refined by
 *  GSL's Brent solver to 4 DBL_EPSILON.  Valid while X is increasing in
 *  xi (1 + u0'(xi) s(t) > 0 everywhere: the caller's responsibility);
 *  SB_EMAXITER if no bracket is found.  u0 must be finite (SB_EDOM where
 *  it is not, e.g. a periodic u0 of |x| near DBL_MAX); SB_EDOM for a
 *  non-finite x, SB_EINVAL for NULL pointers. */
int sb_pgd_smooth_foot(const sb_pgd_smooth *s, double x, double t,
                       double *xi);

/** Exact mass and momentum in [a, b] at t.  Errors of the feet as
 *  sb_pgd_smooth_foot (named after this function); SB_EMAXITER when the
 *  momentum quadrature does not converge, e.g. over ~1e300 periods of an
 *  oscillating rho0 u0 (the mass, from mass0, is then still set). */
int sb_pgd_smooth_integral(const sb_pgd_smooth *s, double t, double a,
                           double b, double *mass, double *mom);

/* ================================================== Lagrangian particles */

/** A weighted particle: w the mass it carries, position and velocity. */
typedef struct {
  double w;
  double x[2];
  double v[2];
} sb_pgd_particle;

/** Drag-only weighted particles on the grid of p (2-D only): inflow faces
 *  of p inject particles (p->inject_time x p->inject_face per face and
 *  step), particles leaving through a transmissive or outflow side are
 *  removed, periodic sides wrap.  Each step moves every particle by the
 *  exact solution of dx/dt = v, dv/dt = (U_gas(x) - v)/tau with U_gas
 *  frozen at the particle's start position (exact for uniform gas). */
typedef struct sb_pgd_lag sb_pgd_lag;

sb_pgd_lag *sb_pgd_lag_alloc(const sb_pgd_params *p);
void sb_pgd_lag_free(sb_pgd_lag *l);

int sb_pgd_lag_add(sb_pgd_lag *l, const sb_pgd_particle *q);
size_t sb_pgd_lag_count(const sb_pgd_lag *l);
const sb_pgd_particle *sb_pgd_lag_particles(const sb_pgd_lag *l);

/** Step bound: the same CFL rule as the Eulerian solver, over particle,
 *  inflow and gas velocities. */
double sb_pgd_lag_dt(const sb_pgd_lag *l);
/** One step of dt > 0 (SB_EINVAL otherwise).  The exact drag move is
 *  formed from each particle's velocity relative to the gas, v - U_gas
 *  (also for the particles the inflows inject): where a component
 *  overflows (|v| and |U_gas| near DBL_MAX with opposite signs) the step
 *  is refused with SB_ERANGE, naming the particle, and changes nothing;
 *  SB_ENOMEM likewise.  _advance stops at the first refused step. */
int sb_pgd_lag_step(sb_pgd_lag *l, double dt);
int sb_pgd_lag_advance(sb_pgd_lag *l, double t_end, size_t *nsteps);
double sb_pgd_lag_time(const sb_pgd_lag *l);

/** Deposit on the grid (nearest grid point: a particle's mass counts in
 *  the cell that contains it): arrays of nx ny values, any may be NULL. */
int sb_pgd_lag_deposit(const sb_pgd_lag *l, double *rho, double *qx,
                       double *qy);
void sb_pgd_lag_totals(const sb_pgd_lag *l, double tot[3]);
void sb_pgd_lag_boundary_totals(const sb_pgd_lag *l, double in[3],
                                double out[3]);
void sb_pgd_lag_side_totals(const sb_pgd_lag *l, sb_pgd_side s, double in[3],
                            double out[3]);
const sb_pgd_params *sb_pgd_lag_get_params(const sb_pgd_lag *l);
/** Steps taken since the particles were allocated (0 for NULL). */
size_t sb_pgd_lag_steps(const sb_pgd_lag *l);

/** Checkpoints of the particles, as sb_pgd_checkpoint_save / _load (magic
 *  "SBPGDL01"): parameters, time, steps, budget and every particle in
 *  order, so that the run goes on bit for bit.  A solver checkpoint is
 *  refused here and a particle checkpoint by sb_pgd_checkpoint_load
 *  (SB_EFORMAT).  The gas callback is attached again with
 *  sb_pgd_lag_set_gas (steps are refused until then). */
int sb_pgd_lag_checkpoint_save(const sb_pgd_lag *l, const char *path);
sb_pgd_lag *sb_pgd_lag_checkpoint_load(const char *path, int *status);
int sb_pgd_lag_set_gas(sb_pgd_lag *l, sb_pgd_gas_fn gas, void *data);

/* ================================================== domain decomposition */

/** The grid of p cut into px x py blocks (nx, ny divisible by px, py),
 *  each block Eulerian ('E') or Lagrangian ('L'): kinds[bi + px bj], bi
 *  along x from the west, bj along y from the south.  Eulerian blocks
 *  exchange ghost cells; the mass and momentum an Eulerian block sends
 *  through a face shared with a Lagrangian block become particles there
 *  (injected like an inflow); particles entering an Eulerian block give
 *  their mass and momentum to the cell they land in.  Both transfers
 *  conserve mass and momentum exactly.  All blocks advance with one
 *  global step (the CFL rule over the whole domain), so an all-Eulerian
 *  decomposition reproduces the single-domain solver to round-off. */
typedef struct sb_pgd_dd sb_pgd_dd;

sb_pgd_dd *sb_pgd_dd_alloc(const sb_pgd_params *p, size_t px, size_t py,
                           const char *kinds);
void sb_pgd_dd_free(sb_pgd_dd *d);

/** Largest stable step (the CFL rule over cells, particles and inflow
 *  states); on a part (below), over its own blocks only. */
double sb_pgd_dd_dt(const sb_pgd_dd *d);
/** One step; SB_ERANGE (message naming the particle) where a particle's
 *  velocity relative to the gas overflows, as in sb_pgd_lag_step, and
 *  SB_ENOMEM: the Eulerian blocks have then taken their part of the step
 *  already, and the decomposition refuses further steps (SB_EINVAL, a
 *  step is under way); sb_pgd_dd_move reports the same. */
int sb_pgd_dd_step(sb_pgd_dd *d, double dt);
int sb_pgd_dd_advance(sb_pgd_dd *d, double t_end, size_t *nsteps);
double sb_pgd_dd_time(const sb_pgd_dd *d);

/** Global fields: Eulerian blocks copy their cells, Lagrangian blocks
 *  deposit their particles (nearest grid point). */
int sb_pgd_dd_fields(const sb_pgd_dd *d, double *rho, double *qx,
                     double *qy);
void sb_pgd_dd_totals(const sb_pgd_dd *d, double tot[3]);
void sb_pgd_dd_boundary_totals(const sb_pgd_dd *d, double in[3],
                               double out[3]);
void sb_pgd_dd_side_totals(const sb_pgd_dd *d, sb_pgd_side s, double in[3],
                           double out[3]);
size_t sb_pgd_dd_particles(const sb_pgd_dd *d);

/** Checkpoints of a one-part decomposition, as sb_pgd_checkpoint_save /
 *  _load (magic "SBPGDD01"): the parameters, blocks and kinds, time,
 *  steps and budget, and every block's state (an Eulerian block's fields
 *  and the fluxes it has not yet turned into particles, a Lagrangian
 *  block's particles in order), so that the run goes on bit for bit.
 *  Save: SB_EINVAL for a part of a run on several parts (nparts > 1),
 *  during a step, or with a gas velocity callback (not done yet).  The
 *  loaded decomposition is a one-part one. */
int sb_pgd_dd_checkpoint_save(const sb_pgd_dd *d, const char *path);
sb_pgd_dd *sb_pgd_dd_checkpoint_load(const char *path, int *status);
/** Its time in steps, and the blocks' layout (px, py; kinds: px py
 *  letters and a 0, in a buffer of at least px py + 1 chars; any pointer
 *  may be NULL). */
size_t sb_pgd_dd_steps(const sb_pgd_dd *d);
int sb_pgd_dd_layout(const sb_pgd_dd *d, size_t *px, size_t *py,
                     char *kinds);
const sb_pgd_params *sb_pgd_dd_get_params(const sb_pgd_dd *d);

/* ---- the blocks shared between processes (parts)
 *
 * For several processes (MPI ranks in the command), each process holds one
 * *part*: the same decomposition, of which it owns and steps some blocks.
 * The library does no communication; the caller moves opaque messages
 * (arrays of doubles) between the parts at three points of each step:
 *
 *   dt = min over the parts of sb_pgd_dd_dt(d)     (an all-reduce)
 *   sb_pgd_dd_begin(d, dt, t_end)
 *   repeat sb_pgd_dd_nstages(d) times:
 *     exchange(SB_PGD_DD_HALO)        ghost cells of Eulerian neighbours
 *     sb_pgd_dd_stage(d)
 *   sb_pgd_dd_move(d)
 *   exchange(SB_PGD_DD_MIGRATE)       particles changing part, budget
 *   sb_pgd_dd_end(d)
 *
 * exchange(m): every part p calls sb_pgd_dd_pack(d, m, q, ...) for every
 * other part q and hands the message to q, which calls
 * sb_pgd_dd_unpack(d, m, p, ...) with it (in any order of p).  Messages
 * may be empty (length 0: nothing to say, but still allowed to be sent).
 * Particles are delivered, and their mass summed into Eulerian cells, in
 * a fixed global order (particles that left a block, then injected ones;
 * by source block), and the boundary budget is summed by part 0 in the
 * order of a one-part run, so the fields, totals and budget do not depend
 * on the number of parts or on the owner map: a run on P parts gives the
 * one-part run's numbers bit for bit.  Between steps,
 * exchange(SB_PGD_DD_STATE) towards one part (the others send it their
 * blocks) lets it hold copies of every block, so that its
 * sb_pgd_dd_fields, _totals and _particles describe the whole domain.
 *
 * Results per part: sb_pgd_dd_fields, _totals and _particles cover the
 * blocks the part holds (owned, or copied by the last STATE message);
 * fields of other blocks are 0.  sb_pgd_dd_boundary_totals and
 * _side_totals are kept by part 0 only (zero on the others).
 * sb_pgd_dd_step and sb_pgd_dd_advance are for one part (SB_EINVAL
 * otherwise). */

/** Part `part` of `nparts`: block k (numbered as kinds) is stepped by
 *  part owner[k] in [0, nparts); owner may be NULL when nparts = 1 (then
 *  this is sb_pgd_dd_alloc).  Every part must be allocated with the same
 *  arguments but `part`.  A part may own no block (it then only takes
 *  part in the exchanges).  NULL on error (message recorded). */
sb_pgd_dd *sb_pgd_dd_alloc_part(const sb_pgd_params *p, size_t px,
                                size_t py, const char *kinds,
                                const int *owner, int nparts, int part);

/** A balanced owner map of contiguous runs of blocks (in the order of
 *  kinds, row by row from the south-west): owner[k] = floor(k nparts /
 *  nblocks), so that every part has at least one block and neighbouring
 *  blocks of a row tend to share a part.  SB_EINVAL unless
 *  1 <= nparts <= nblocks. */
int sb_pgd_dd_split(size_t nblocks, int nparts, int *owner);

/** The phases of a step (see above).  begin: dt must not exceed this
 *  part's sb_pgd_dd_dt (the caller passes the smallest over the parts;
 *  INFINITY when nothing moves); the step is shortened to end exactly at
 *  t_end (> current time; INFINITY for none, then dt must be finite)
 *  when dt reaches it, as sb_pgd_dd_advance does.
 *  SB_EINVAL when called out of order; SB_ENOMEM. */
int sb_pgd_dd_begin(sb_pgd_dd *d, double dt, double t_end);
/** Runge-Kutta stages per step: 1 (upwind) or 2 (muscl). */
int sb_pgd_dd_nstages(const sb_pgd_dd *d);
int sb_pgd_dd_stage(sb_pgd_dd *d);
int sb_pgd_dd_move(sb_pgd_dd *d);
int sb_pgd_dd_end(sb_pgd_dd *d);

typedef enum {
  SB_PGD_DD_HALO = 0,     /**< before each stage: ghost cells */
  SB_PGD_DD_MIGRATE = 1,  /**< between move and end: particles, budget */
  SB_PGD_DD_STATE = 2     /**< between steps: blocks, for output */
} sb_pgd_dd_msg;

/** Pack message m for part `to` into buf[0..cap-1], its length in *n;
 *  with buf = NULL only *n is set.  A message to oneself is empty.
 *  SB_EINVAL for a message out of its phase, a bad part or cap < *n. */
int sb_pgd_dd_pack(const sb_pgd_dd *d, sb_pgd_dd_msg m, int to,
                   double *buf, size_t cap, size_t *n);

/** Unpack message m of n values that part `from` packed for this part.
 *  SB_EFORMAT for a message that does not fit this part (wrong length,
 *  blocks of a part other than `from`, particles outside their block),
 *  SB_EINVAL out of phase, SB_ENOMEM. */
int sb_pgd_dd_unpack(sb_pgd_dd *d, sb_pgd_dd_msg m, int from,
                     const double *buf, size_t n);

/* ================================================== comparison */

/** L1 distances between two 2-D (or 1-D) fields on the grid of p:
 *  drho = sum |rho_a - rho_b| dA, dq = sum (|qx_a - qx_b| + |qy_a - qy_b|)
 *  dA (dA = dx dy, or dx in 1-D).  qy may be NULL in 1-D. */
void sb_pgd_l1(const sb_pgd_params *p, const double *rho_a,
               const double *qx_a, const double *qy_a, const double *rho_b,
               const double *qx_b, const double *qy_b, double *drho,
               double *dq);

#ifdef __cplusplus
}
#endif

#endif /* SMOLBRIDGE_PGD_H */
