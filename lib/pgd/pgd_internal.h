/* pgd_internal.h — the Eulerian grid behind sb_pgd, the particle arrays
 * behind sb_pgd_lag, and the pieces the domain-decomposition driver
 * (pgd_dd.c) calls one by one.  Private to lib/pgd. */
#ifndef SB_PGD_INTERNAL_H
#define SB_PGD_INTERNAL_H

#include <stddef.h>
#include <stdint.h>
#include <smolbridge/pgd.h>

#define SBI_PGD_G 2  /* ghost layers (the MUSCL slopes need two) */

/* Mass and momentum that crossed each side, in and out. */
typedef struct {
  double in[4][3], out[4][3];
} sbi_budget;

static inline void sbi_budget_add(sbi_budget *b, int side, int out,
                                  double m, double px, double py)
{
  double *v = out ? b->out[side] : b->in[side];
  v[0] += m;
  v[1] += px;
  v[2] += py;
}

/* Sums over one side (0..3) or all (-1); in/out may be NULL. */
static inline void sbi_budget_get(const sbi_budget *b, int side,
                                  double in[3], double out[3])
{
  for (int k = 0; k < 3; k++) {
    double a = 0, c = 0;
    for (int s = 0; s < 4; s++)
      if (side < 0 || s == side) {
        a += b->in[s][k];
        c += b->out[s][k];
      }
    if (in)
      in[k] = a;
    if (out)
      out[k] = c;
  }
}

struct sb_pgd {
  sb_pgd_params p;
  size_t nx, ny;       /* interior cells */
  size_t gx, gy;       /* ghost layers in x and y (gy = 0 in 1-D) */
  size_t sx, sy;       /* padded sizes: nx + 2 gx, ny + 2 gy */
  double dx, dy;       /* cell sizes (dy = 1 in 1-D: per unit length) */
  double *rho, *qx, *qy;     /* padded state */
  double *r0, *qx0, *qy0;    /* state at the start of an RK2 step */
  double *dr, *dqx, *dqy;    /* accumulated flux divergence of a stage */
  double *ux, *uy;           /* velocities of a stage (0 in vacuum) */
  double *ugx, *ugy;         /* gas velocity at cell centres (padded) */
  int *inflow_at[4];         /* per side and boundary cell: inflow index
                                or -1 */
  size_t nb[4];              /* boundary cells per side */
  int external[4];           /* ghosts of this side are set by the caller */
  double *bflux[4];          /* outward flux integrated over the current
                                step: 3 per boundary cell (mass, qx, qy) */
  sbi_budget bud;
  double t;
  size_t steps;
  double speed;              /* max (|ux|/dx + |uy|/dy) of the cells, */
  int speed_ok;              /* kept up to date by the step's last pass */
  int empty;                 /* every cell is vacuum (skip the work) */
  double *line;              /* work buffers for one line of cells */
  int gas_missing;           /* loaded from a checkpoint saved with a gas
                                callback not yet attached again
                                (sb_pgd_set_gas): steps refused */
  uint64_t gas_print;        /* then: sbi_pgd_gas_print of that callback */
};

/* Padded index of cell (i, j); i, j may be -G .. n-1+G. */
static inline size_t sbi_pgd_idx(const struct sb_pgd *g, long i, long j)
{
  return (size_t)(i + (long)g->gx) +
         g->sx * (size_t)(j + (long)g->gy);
}

/* Velocity of a cell from its moments (0 in vacuum). */
static inline double sbi_pgd_vel(double rho, double q, double floor_)
{
  return rho > floor_ ? q / rho : 0.0;
}

/* Allocate the solver; if `external` is not NULL, sides with a nonzero
 * flag get their ghost cells from the caller (domain decomposition). */
struct sb_pgd *sbi_pgd_alloc(const sb_pgd_params *p, const int external[4]);

/* Cell sizes and gas samples of a block whose first cell is (i0, j0) of
 * a grid with lower-left corner `origin` (the same arithmetic as the
 * whole grid, so that a decomposition reproduces it bit for bit). */
void sbi_pgd_geometry(struct sb_pgd *g, double dx, double dy,
                      const double origin[2], size_t i0, size_t j0);

/* Ghost cells of the non-external sides from the boundary conditions. */
void sbi_pgd_fill_ghosts(struct sb_pgd *g);

/* Exact drag relaxation over h in every interior cell; with `track`,
 * the cells' speed bound is recomputed on the way. */
void sbi_pgd_drag(struct sb_pgd *g, double h, int track);

/* Transport: number of stages of the scheme (1 upwind, 2 MUSCL/RK2);
 * begin() saves the state and clears the step's boundary fluxes; stage(s)
 * advances stage s with the ghost cells as they are. */
int sbi_pgd_nstages(sb_pgd_scheme s);
void sbi_pgd_transport_begin(struct sb_pgd *g);
void sbi_pgd_stage(struct sb_pgd *g, double dt, int stage);

/* Largest |ux|/dx + |uy|/dy over interior cells (gas velocity included
 * where there is drag) and inflow states; the cells' part is cached by
 * the last pass of a step, and must be invalidated (speed_ok = 0) by
 * anything else that changes cells. */
double sbi_pgd_speed(const struct sb_pgd *g);

/* Courant bound of the scheme (1 or 1/2). */
double sbi_pgd_cfl_limit(sb_pgd_scheme s);

/* Gas velocity at (x, y) from the parameters. */
void sbi_pgd_gas_at(const sb_pgd_params *p, double x, double y,
                    double ug[2]);

/* Cells whose centres sample the gas: the block of nx x ny cells whose
 * first cell is (i0, j0) of a grid with lower-left corner `origin` and
 * cells dx x dy (ny = 1 and dy unused in 1-D). */
typedef struct {
  double origin[2], dx, dy;
  size_t i0, j0, nx, ny;
} sbi_pgd_cells;

/* The cells of the whole grid of p. */
sbi_pgd_cells sbi_pgd_grid_cells(const sb_pgd_params *p);

/* Calls visit(ctx, i, j, ug) with the gas velocity ug at the centre of
 * every cell (i, j) of c (i < c->nx, j < c->ny, counted from the block's
 * first cell), row by row from the south-west.  The one place where the
 * cell centres are computed (x = origin + (i0 + i + 1/2) dx; y = 0 in
 * 1-D): the solver's cache, a block's, the speed bound and a
 * checkpoint's fingerprint sample the same points bit for bit. */
typedef void (*sbi_pgd_gas_visit)(void *ctx, size_t i, size_t j,
                                  const double ug[2]);
void sbi_pgd_gas_at_centres(const sb_pgd_params *p, const sbi_pgd_cells *c,
                            sbi_pgd_gas_visit visit, void *ctx);

/* ------------------------------------------------------------ particles */

typedef struct {
  sb_pgd_particle *q;
  size_t n, cap;
} sbi_parts;

int sbi_parts_push(sbi_parts *a, const sb_pgd_particle *q);
/* Room for at least n particles (pushes up to n cannot fail). */
int sbi_parts_reserve(sbi_parts *a, size_t n);
void sbi_parts_free(sbi_parts *a);

/* Decay e^{-h/tau} and position gain tau (1 - e^{-h/tau}) of a move h
 * (1 and h without drag). */
void sbi_lag_coef(const sb_pgd_params *p, double h, double *e, double *g);

/* Exact drag-and-transport move of one particle over h (gas frozen at its
 * start position), with the coefficients of sbi_lag_coef(h).  The move
 * is formed from the velocity relative to the gas, v - U_gas: the
 * caller checks first that it is a double (sbi_lag_rel_ok). */
void sbi_lag_move_coef(const sb_pgd_params *p, sb_pgd_particle *q, double h,
                       double e, double gain);
/* The same for n particles. */
void sbi_lag_move_all(const sb_pgd_params *p, sb_pgd_particle *q, size_t n,
                      double h, double e, double gain);

/* Whether both components of q's velocity relative to the gas that drags
 * it (v - U_gas, the gas at q's position; 0 without drag) are doubles:
 * |v| and |U_gas| near DBL_MAX with opposite signs overflow it. */
int sbi_lag_rel_ok(const sb_pgd_params *p, const sb_pgd_particle *q);

/* The first of n particles whose relative velocity overflows, or n. */
size_t sbi_lag_rel_first_bad(const sb_pgd_params *p,
                             const sb_pgd_particle *q, size_t n);

/* SB_ERANGE with a message, named after func, on q's relative velocity. */
int sbi_lag_rel_error(const sb_pgd_params *p, const sb_pgd_particle *q,
                      const char *func);

/* Inject the mass M with momentum P[2] that crossed one face during a
 * step of length dt: p->inject_time x p->inject_face particles entering
 * at the face (normal direction `dir` 0 = x, 1 = y, at coordinate xn,
 * along [s0, s0 + len] in the other direction), each moved over the part
 * of the step left after its entry.  Appends to out.  SB_ENOMEM (no
 * message), or SB_ERANGE with a message named after func where P/M - U_gas
 * overflows (sbi_lag_rel_ok). */
int sbi_lag_inject(const sb_pgd_params *p, int dir, double xn, double s0,
                   double len, double M, const double P[2], double dt,
                   sbi_parts *out, const char *func);

/* Where a particle is after a move: wraps periodic directions in place;
 * returns 0 inside the domain, 1 + the side it left through otherwise. */
int sbi_lag_place(const sb_pgd_params *p, sb_pgd_particle *q);

/* Largest |vx|/dx + |vy|/dy over particles. */
double sbi_lag_speed(const sb_pgd_params *p, const sb_pgd_particle *q,
                     size_t n);

/* Cell (i, j) containing a point of the domain (clamped), with the
 * grid's inverse spacings precomputed: one rule everywhere, so that a
 * particle's cell (and block) is decided the same way by every caller. */
typedef struct {
  double o[2], inv[2];
  size_t n[2];
} sbi_locator;

static inline void sbi_locator_init(sbi_locator *L, const sb_pgd_params *p)
{
  for (int d = 0; d < 2; d++) {
    L->o[d] = p->origin[d];
    L->n[d] = d ? p->ny : p->nx;
    L->inv[d] = (double)L->n[d] / p->L[d];
  }
}

static inline size_t sbi_locate1(const sbi_locator *L, int d, double x)
{
  double f = (x - L->o[d]) * L->inv[d]; /* truncation = floor for f >= 0 */
  return !(f > 0) ? 0 : f >= (double)L->n[d] ? L->n[d] - 1 : (size_t)f;
}

/* The particles behind sb_pgd_lag (pgd_lag.c; saved by pgd_checkpoint.c). */
struct sb_pgd_lag {
  sb_pgd_params p;
  sbi_locator loc;
  sbi_parts a;
  sbi_parts fresh;  /* the step's injected particles, before they join a */
  double pspeed;  /* speed bound of inflow states and gas */
  double t;
  size_t steps;
  sbi_budget bud;
  int gas_missing;     /* as in struct sb_pgd */
  uint64_t gas_print;
};

/* Step bound from a speed (|ux|/dx + |uy|/dy), p->cfl and p->dt_max. */
double sbi_pgd_dt_from_speed(const sb_pgd_params *p, double speed);

/* Inflow speed bound of p (|ux|/dx + |uy|/dy over inflow states) and of
 * the gas where there is drag (sampled at cell centres for a callback). */
double sbi_pgd_param_speed(const sb_pgd_params *p);

/* A fingerprint of the gas velocity of p at the cell centres (FNV-1a of
 * the samples; 0 without a callback): what a checkpoint keeps of a gas
 * callback, to refuse another one when it is attached again. */
uint64_t sbi_pgd_gas_print(const sb_pgd_params *p);

/* sb_pgd_checkpoint_save and _load with the file's byte order the
 * reverse of this machine's when swap = 1 (pgd_checkpoint.c; the files
 * are little-endian, swap = 0 here): what a big-endian machine does, for
 * the tests. */
int sbi_pgd_checkpoint_save_ord(const sb_pgd *g, const char *path, int swap);
sb_pgd *sbi_pgd_checkpoint_load_ord(const char *path, int swap, int *status);

#endif /* SB_PGD_INTERNAL_H */
