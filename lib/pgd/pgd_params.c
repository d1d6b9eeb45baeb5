/* pgd_params.c — problem description of the pressureless-gas module:
 * defaults, checks, inflow segments, scheme names, the CFL rule and the
 * L1 distance between fields. */
#include <math.h>
#include <string.h>

#include <smolbridge/pgd.h>
#include "common/internal.h"
#include "pgd_internal.h"

void sb_pgd_params_default(sb_pgd_params *p, int dim)
{
  if (!p)
    return;
  memset(p, 0, sizeof *p);
  p->dim = dim == 1 ? 1 : 2;
  p->nx = 100;
  p->ny = p->dim == 2 ? 100 : 1;
  p->L[0] = p->L[1] = 1.0;
  p->scheme = SB_PGD_UPWIND;
  p->cfl = 0.5;
  p->dt_max = INFINITY;
  p->tau = INFINITY;
  p->rho_floor = 1e-14;
  p->inject_time = 2;
  p->inject_face = 2;
  for (int s = 0; s < 4; s++)
    p->bc[s] = SB_PGD_TRANSMISSIVE;
}

double sbi_pgd_cfl_limit(sb_pgd_scheme s)
{
  return s == SB_PGD_MUSCL ? 0.5 : 1.0;
}

/* Boundary cells along a side. */
static size_t side_cells(const sb_pgd_params *p, sb_pgd_side s)
{
  if (s == SB_PGD_WEST || s == SB_PGD_EAST)
    return p->dim == 1 ? 1 : p->ny;
  return p->nx;
}

int sb_pgd_params_check(const sb_pgd_params *p)
{
  const char *f = "sb_pgd_params_check";
  if (!p)
    return sbi_error(SB_EINVAL, f, "NULL parameters");
  if (p->dim != 1 && p->dim != 2)
    return sbi_error(SB_EINVAL, f, "dim = %d: must be 1 or 2", p->dim);
  if (p->nx < 2 || p->nx > 100000000 ||
      (p->dim == 2 && (p->ny < 2 || p->ny > 100000000)))
    return sbi_error(SB_EINVAL, f, "nx = %zu, ny = %zu: need 2 .. 1e8 cells "
                     "per direction", p->nx, p->ny);
  if (p->dim == 2 && p->nx * p->ny > 400000000)
    return sbi_error(SB_EINVAL, f, "nx ny = %zu: more than 4e8 cells",
                     p->nx * p->ny);
  for (int d = 0; d < p->dim; d++) {
    if (!(p->L[d] > 0) || !isfinite(p->L[d]))
      return sbi_error(SB_EINVAL, f, "L[%d] = %g: must be finite and > 0",
                       d, p->L[d]);
    if (!isfinite(p->origin[d]))
      return sbi_error(SB_EINVAL, f, "origin[%d] is not finite", d);
  }
  if (p->scheme != SB_PGD_UPWIND && p->scheme != SB_PGD_MUSCL)
    return sbi_error(SB_EINVAL, f, "scheme = %d: upwind or muscl",
                     (int)p->scheme);
  double lim = sbi_pgd_cfl_limit(p->scheme);
  if (!(p->cfl > 0 && p->cfl <= lim))
    return sbi_error(SB_EINVAL, f, "cfl = %g: must be in (0, %g] for the "
                     "%s scheme", p->cfl, lim, sb_pgd_scheme_name(p->scheme));
  if (!(p->dt_max > 0))
    return sbi_error(SB_EINVAL, f, "dt_max = %g: must be > 0 (INFINITY: "
                     "no cap)", p->dt_max);
  if (!(p->tau > 0))
    return sbi_error(SB_EINVAL, f, "tau = %g: must be > 0 (INFINITY: no "
                     "drag)", p->tau);
  if (!isfinite(p->ugas[0]) || !isfinite(p->ugas[1]))
    return sbi_error(SB_EINVAL, f, "ugas is not finite");
  if (!(p->rho_floor >= 0) || !isfinite(p->rho_floor))
    return sbi_error(SB_EINVAL, f, "rho_floor = %g: must be >= 0",
                     p->rho_floor);
  if (p->inject_time < 1 || p->inject_face < 1 || p->inject_time > 1000 ||
      p->inject_face > 1000)
    return sbi_error(SB_EINVAL, f, "inject_time = %zu, inject_face = %zu: "
                     "must be 1 .. 1000", p->inject_time, p->inject_face);
  for (int s = 0; s < 4; s++) {
    if (p->bc[s] != SB_PGD_TRANSMISSIVE && p->bc[s] != SB_PGD_OUTFLOW &&
        p->bc[s] != SB_PGD_PERIODIC)
      return sbi_error(SB_EINVAL, f, "bc[%d] = %d: transmissive, outflow "
                       "or periodic", s, (int)p->bc[s]);
  }
  int ndir = p->dim;
  for (int d = 0; d < ndir; d++)
    if ((p->bc[2 * d] == SB_PGD_PERIODIC) !=
        (p->bc[2 * d + 1] == SB_PGD_PERIODIC))
      return sbi_error(SB_EINVAL, f, "periodic boundary on one %s side "
                       "only: set both", d ? "y" : "x");
  if (p->ninflow > SB_PGD_MAXINFLOW)
    return sbi_error(SB_EINVAL, f, "ninflow = %zu > %d", p->ninflow,
                     SB_PGD_MAXINFLOW);
  for (size_t k = 0; k < p->ninflow; k++) {
    const sb_pgd_inflow *in = &p->inflow[k];
    if ((int)in->side < 0 || (int)in->side > 3 ||
        (p->dim == 1 && in->side > SB_PGD_EAST))
      return sbi_error(SB_EINVAL, f, "inflow %zu: side %d invalid", k,
                       (int)in->side);
    size_t nb = side_cells(p, in->side);
    if (in->count < 1 || in->first >= nb || in->count > nb - in->first)
      return sbi_error(SB_EINVAL, f, "inflow %zu: cells %zu .. %zu outside "
                       "the side's 0 .. %zu", k, in->first,
                       in->first + in->count - 1, nb - 1);
    if (p->bc[in->side] == SB_PGD_PERIODIC)
      return sbi_error(SB_EINVAL, f, "inflow %zu on a periodic side", k);
    if (!(in->rho >= 0) || !isfinite(in->rho) || !isfinite(in->u[0]) ||
        !isfinite(in->u[1]))
      return sbi_error(SB_EINVAL, f, "inflow %zu: rho must be >= 0 and "
                       "finite, u finite", k);
    for (size_t m = 0; m < k; m++) {
      const sb_pgd_inflow *o = &p->inflow[m];
      if (o->side == in->side && in->first < o->first + o->count &&
          o->first < in->first + in->count)
        return sbi_error(SB_EINVAL, f, "inflows %zu and %zu overlap", m, k);
    }
  }
  return SB_SUCCESS;
}

int sb_pgd_params_add_inflow(sb_pgd_params *p, sb_pgd_side side,
                             size_t first, size_t count, double rho,
                             double ux, double uy)
{
  if (!p)
    return sbi_error(SB_EINVAL, __func__, "NULL parameters");
  if (p->ninflow >= SB_PGD_MAXINFLOW)
    return sbi_error(SB_EINVAL, __func__, "more than %d inflow segments",
                     SB_PGD_MAXINFLOW);
  sb_pgd_inflow *in = &p->inflow[p->ninflow];
  in->side = side;
  in->first = first;
  in->count = count;
  in->rho = rho;
  in->u[0] = ux;
  in->u[1] = uy;
  p->ninflow++;
  int st = sb_pgd_params_check(p);
  if (st)
    p->ninflow--;
  return st;
}

int sb_pgd_scheme_from_name(const char *name, sb_pgd_scheme *s)
{
  if (name && (!strcmp(name, "upwind") || !strcmp(name, "muscl"))) {
    if (s)
      *s = !strcmp(name, "muscl") ? SB_PGD_MUSCL : SB_PGD_UPWIND;
    return SB_SUCCESS;
  }
  return sbi_error(SB_EINVAL, __func__, "scheme '%s': must be upwind or "
                   "muscl", name ? name : "(null)");
}

const char *sb_pgd_scheme_name(sb_pgd_scheme s)
{
  return s == SB_PGD_MUSCL ? "muscl" : s == SB_PGD_UPWIND ? "upwind" : "?";
}

void sbi_pgd_gas_at(const sb_pgd_params *p, double x, double y,
                    double ug[2])
{
  if (p->gas) {
    p->gas(x, y, ug, p->gas_data);
  } else {
    ug[0] = p->ugas[0];
    ug[1] = p->ugas[1];
  }
  if (p->dim == 1)
    ug[1] = 0.0;
}

sbi_pgd_cells sbi_pgd_grid_cells(const sb_pgd_params *p)
{
  sbi_pgd_cells c = {{p->origin[0], p->origin[1]},
                     p->L[0] / (double)p->nx,
                     p->dim == 2 ? p->L[1] / (double)p->ny : 0.0,
                     0, 0, p->nx, p->dim == 2 ? p->ny : 1};
  return c;
}

void sbi_pgd_gas_at_centres(const sb_pgd_params *p, const sbi_pgd_cells *c,
                            sbi_pgd_gas_visit visit, void *ctx)
{
  for (size_t j = 0; j < c->ny; j++)
    for (size_t i = 0; i < c->nx; i++) {
      double ug[2];
      sbi_pgd_gas_at(p, c->origin[0] + ((double)(c->i0 + i) + 0.5) * c->dx,
                     p->dim == 2
                         ? c->origin[1] + ((double)(c->j0 + j) + 0.5) * c->dy
                         : 0.0,
                     ug);
      visit(ctx, i, j, ug);
    }
}

double sbi_pgd_dt_from_speed(const sb_pgd_params *p, double speed)
{
  double dt = speed > 0 ? p->cfl / speed : INFINITY;
  return dt < p->dt_max ? dt : p->dt_max;
}

/* The running maximum of |ux|/dx + |uy|/dy over gas samples. */
typedef struct {
  int dim;
  double dx, dy, s;
} gas_speed_acc;

static void gas_speed_visit(void *ctx, size_t i, size_t j,
                            const double ug[2])
{
  gas_speed_acc *a = ctx;
  (void)i, (void)j;
  double v = fabs(ug[0]) / a->dx + (a->dim == 2 ? fabs(ug[1]) / a->dy : 0.0);
  if (v > a->s)
    a->s = v;
}

double sbi_pgd_param_speed(const sb_pgd_params *p)
{
  double dx = p->L[0] / (double)p->nx;
  double dy = p->dim == 2 ? p->L[1] / (double)p->ny : INFINITY;
  double s = 0;
  for (size_t k = 0; k < p->ninflow; k++) {
    double v = fabs(p->inflow[k].u[0]) / dx +
               (p->dim == 2 ? fabs(p->inflow[k].u[1]) / dy : 0.0);
    if (v > s)
      s = v;
  }
  if (isinf(p->tau))
    return s;
  if (!p->gas)
    return fmax(s, fabs(p->ugas[0]) / dx +
                       (p->dim == 2 ? fabs(p->ugas[1]) / dy : 0.0));
  gas_speed_acc acc = {p->dim, dx, dy, s};
  const sbi_pgd_cells cells = sbi_pgd_grid_cells(p);
  sbi_pgd_gas_at_centres(p, &cells, gas_speed_visit, &acc);
  return acc.s;
}

void sb_pgd_l1(const sb_pgd_params *p, const double *rho_a,
               const double *qx_a, const double *qy_a, const double *rho_b,
               const double *qx_b, const double *qy_b, double *drho,
               double *dq)
{
  size_t ny = p->dim == 2 ? p->ny : 1, n = p->nx * ny;
  double dA = p->L[0] / (double)p->nx *
              (p->dim == 2 ? p->L[1] / (double)p->ny : 1.0);
  double sr = 0, sq = 0;
  for (size_t k = 0; k < n; k++) {
    if (rho_a && rho_b)
      sr += fabs(rho_a[k] - rho_b[k]);
    if (qx_a && qx_b)
      sq += fabs(qx_a[k] - qx_b[k]);
    if (qy_a && qy_b)
      sq += fabs(qy_a[k] - qy_b[k]);
  }
  if (drho)
    *drho = sr * dA;
  if (dq)
    *dq = sq * dA;
}
