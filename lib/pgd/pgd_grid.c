/* pgd_grid.c — the Eulerian grid of sb_pgd: allocation, initial data,
 * ghost cells from the boundary conditions, access to the fields and
 * their output (CSV, legacy VTK). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_integration.h>
#include <smolbridge/pgd.h>
#include "common/internal.h"
#include "pgd_internal.h"

struct sb_pgd *sbi_pgd_alloc(const sb_pgd_params *p, const int external[4])
{
  if (sb_pgd_params_check(p)) {
    sbi_error(SB_EINVAL, "sb_pgd_alloc", "%s", sb_last_error());
    return NULL;
  }
  struct sb_pgd *g = calloc(1, sizeof *g);
  if (!g) {
    sbi_error(SB_ENOMEM, "sb_pgd_alloc", "out of memory");
    return NULL;
  }
  g->p = *p;
  if (p->dim == 1)
    g->p.ny = 1;
  g->nx = g->p.nx;
  g->ny = g->p.ny;
  g->gx = SBI_PGD_G;
  g->gy = p->dim == 2 ? SBI_PGD_G : 0;
  g->sx = g->nx + 2 * g->gx;
  g->sy = g->ny + 2 * g->gy;
  g->dx = p->L[0] / (double)g->nx;
  g->dy = p->dim == 2 ? p->L[1] / (double)g->ny : 1.0;
  size_t n = g->sx * g->sy, nmax = g->sx > g->sy ? g->sx : g->sy;
  double **arr[] = {&g->rho, &g->qx, &g->qy, &g->r0, &g->qx0, &g->qy0,
                    &g->dr, &g->dqx, &g->dqy, &g->ugx, &g->ugy,
                    &g->ux, &g->uy};
  int ok = 1;
  for (size_t k = 0; k < sizeof arr / sizeof arr[0]; k++)
    ok &= (*arr[k] = calloc(n, sizeof(double))) != NULL;
  ok &= (g->line = calloc(12 * nmax, sizeof(double))) != NULL;
  for (int s = 0; s < 4; s++) {
    g->nb[s] = s < 2 ? g->ny : (p->dim == 2 ? g->nx : 0);
    g->external[s] = external ? external[s] != 0 : 0;
    if (g->nb[s] == 0)
      continue;
    ok &= (g->inflow_at[s] = malloc(g->nb[s] * sizeof(int))) != NULL;
    ok &= (g->bflux[s] = calloc(3 * g->nb[s], sizeof(double))) != NULL;
  }
  if (!ok) {
    sb_pgd_free(g);
    sbi_error(SB_ENOMEM, "sb_pgd_alloc", "out of memory (%zu cells)", n);
    return NULL;
  }
  for (int s = 0; s < 4; s++)
    for (size_t k = 0; k < g->nb[s]; k++)
      g->inflow_at[s][k] = -1;
  for (size_t m = 0; m < p->ninflow; m++) {
    const sb_pgd_inflow *in = &p->inflow[m];
    for (size_t k = in->first; k < in->first + in->count; k++)
      g->inflow_at[in->side][k] = (int)m;
  }
  sbi_pgd_geometry(g, g->dx, g->dy, p->origin, 0, 0);
  return g;
}

/* Store one gas sample in the solver's cache. */
static void cache_visit(void *ctx, size_t i, size_t j, const double ug[2])
{
  struct sb_pgd *g = ctx;
  const size_t c = sbi_pgd_idx(g, (long)i, (long)j);
  g->ugx[c] = ug[0];
  g->ugy[c] = ug[1];
}

void sbi_pgd_geometry(struct sb_pgd *g, double dx, double dy,
                      const double origin[2], size_t i0, size_t j0)
{
  g->dx = dx;
  g->dy = dy;
  /* the gas is steady: sample it once at the cell centres */
  const sbi_pgd_cells cells = {{origin[0], origin[1]}, dx, dy,
                               i0, j0, g->nx, g->ny};
  sbi_pgd_gas_at_centres(&g->p, &cells, cache_visit, g);
}

sb_pgd *sb_pgd_alloc(const sb_pgd_params *p)
{
  return sbi_pgd_alloc(p, NULL);
}

void sb_pgd_free(sb_pgd *g)
{
  if (!g)
    return;
  double *arr[] = {g->rho, g->qx, g->qy, g->r0, g->qx0, g->qy0,
                   g->dr, g->dqx, g->dqy, g->ugx, g->ugy, g->line,
                   g->ux, g->uy};
  for (size_t k = 0; k < sizeof arr / sizeof arr[0]; k++)
    free(arr[k]);
  for (int s = 0; s < 4; s++) {
    free(g->inflow_at[s]);
    free(g->bflux[s]);
  }
  free(g);
}

const sb_pgd_params *sb_pgd_get_params(const sb_pgd *g)
{
  return g ? &g->p : NULL;
}

double sb_pgd_time(const sb_pgd *g) { return g ? g->t : NAN; }
size_t sb_pgd_steps(const sb_pgd *g) { return g ? g->steps : 0; }

int sb_pgd_init(sb_pgd *g, sb_pgd_init_fn f, void *data)
{
  if (!g || !f)
    return sbi_error(SB_EINVAL, __func__, "NULL solver or function");
  gsl_integration_glfixed_table *tab = gsl_integration_glfixed_table_alloc(3);
  if (!tab)
    return sbi_error(SB_ENOMEM, __func__, "out of memory");
  const int dim = g->p.dim, ny = dim == 2 ? 3 : 1;
  for (size_t j = 0; j < g->ny; j++)
    for (size_t i = 0; i < g->nx; i++) {
      double xa = g->p.origin[0] + (double)i * g->dx;
      double ya = g->p.origin[1] + (double)j * g->dy;
      double m = 0, mx = 0, my = 0;
      for (int b = 0; b < ny; b++) {
        double y = 0, wy = 1;
        if (dim == 2)
          gsl_integration_glfixed_point(ya, ya + g->dy, (size_t)b, &y, &wy,
                                        tab);
        for (int a = 0; a < 3; a++) {
          double x, wx, rho = 0, u[2] = {0, 0};
          gsl_integration_glfixed_point(xa, xa + g->dx, (size_t)a, &x, &wx,
                                        tab);
          f(x, y, &rho, u, data);
          if (!(rho >= 0) || !isfinite(rho) || !isfinite(u[0]) ||
              !isfinite(u[1])) {
            gsl_integration_glfixed_table_free(tab);
            return sbi_error(SB_EDOM, __func__, "initial data at (%g, %g): "
                             "rho = %g, u = (%g, %g)", x, y, rho, u[0], u[1]);
          }
          m += wx * wy * rho;
          mx += wx * wy * rho * u[0];
          my += wx * wy * rho * u[1];
        }
      }
      double area = g->dx * (dim == 2 ? g->dy : 1.0);
      size_t c = sbi_pgd_idx(g, (long)i, (long)j);
      g->rho[c] = m / area;
      g->qx[c] = mx / area;
      g->qy[c] = dim == 2 ? my / area : 0.0;
    }
  gsl_integration_glfixed_table_free(tab);
  g->speed_ok = 0;
  g->empty = 0;
  return SB_SUCCESS;
}

int sb_pgd_set_cell(sb_pgd *g, size_t i, size_t j, double rho, double ux,
                    double uy)
{
  if (!g || i >= g->nx || j >= g->ny)
    return sbi_error(SB_EINVAL, __func__, "cell (%zu, %zu) outside the "
                     "grid", i, j);
  if (!(rho >= 0) || !isfinite(rho) || !isfinite(ux) || !isfinite(uy))
    return sbi_error(SB_EDOM, __func__, "rho = %g (>= 0), u = (%g, %g) "
                     "(finite)", rho, ux, uy);
  size_t c = sbi_pgd_idx(g, (long)i, (long)j);
  g->rho[c] = rho;
  g->qx[c] = rho * ux;
  g->qy[c] = g->p.dim == 2 ? rho * uy : 0.0;
  g->speed_ok = 0;
  g->empty = 0;
  return SB_SUCCESS;
}

int sb_pgd_get_cell(const sb_pgd *g, size_t i, size_t j, double *rho,
                    double u[2])
{
  if (!g || i >= g->nx || j >= g->ny)
    return sbi_error(SB_EINVAL, __func__, "cell (%zu, %zu) outside the "
                     "grid", i, j);
  size_t c = sbi_pgd_idx(g, (long)i, (long)j);
  double fl = g->p.rho_floor;
  if (rho)
    *rho = g->rho[c];
  if (u) {
    u[0] = sbi_pgd_vel(g->rho[c], g->qx[c], fl);
    u[1] = sbi_pgd_vel(g->rho[c], g->qy[c], fl);
  }
  return SB_SUCCESS;
}

int sb_pgd_fields(const sb_pgd *g, double *rho, double *qx, double *qy)
{
  if (!g)
    return sbi_error(SB_EINVAL, __func__, "NULL solver");
  for (size_t j = 0; j < g->ny; j++)
    for (size_t i = 0; i < g->nx; i++) {
      size_t c = sbi_pgd_idx(g, (long)i, (long)j), k = i + g->nx * j;
      if (rho)
        rho[k] = g->rho[c];
      if (qx)
        qx[k] = g->qx[c];
      if (qy)
        qy[k] = g->qy[c];
    }
  return SB_SUCCESS;
}

void sb_pgd_totals(const sb_pgd *g, double tot[3])
{
  double m = 0, mx = 0, my = 0;
  for (size_t j = 0; j < g->ny; j++)
    for (size_t i = 0; i < g->nx; i++) {
      size_t c = sbi_pgd_idx(g, (long)i, (long)j);
      m += g->rho[c];
      mx += g->qx[c];
      my += g->qy[c];
    }
  double dA = g->dx * g->dy;
  tot[0] = m * dA;
  tot[1] = mx * dA;
  tot[2] = my * dA;
}

void sb_pgd_boundary_totals(const sb_pgd *g, double in[3], double out[3])
{
  sbi_budget_get(&g->bud, -1, in, out);
}

void sb_pgd_side_totals(const sb_pgd *g, sb_pgd_side s, double in[3],
                        double out[3])
{
  sbi_budget_get(&g->bud, (int)s & 3, in, out);
}

/* ------------------------------------------------------------ ghosts */

/* Ghost layer `l` (1 .. G) of boundary cell k of side s: its padded index
 * and the index of the interior cell it mirrors (transmissive) or wraps
 * to (periodic). */
static void ghost_pair(const struct sb_pgd *g, int s, size_t k, long l,
                       size_t *ghost, size_t *copy, size_t *wrap)
{
  long n;
  switch (s) {
  case SB_PGD_WEST:
    n = (long)g->nx;
    *ghost = sbi_pgd_idx(g, -l, (long)k);
    *copy = sbi_pgd_idx(g, 0, (long)k);
    *wrap = sbi_pgd_idx(g, n - l, (long)k);
    break;
  case SB_PGD_EAST:
    n = (long)g->nx;
    *ghost = sbi_pgd_idx(g, n - 1 + l, (long)k);
    *copy = sbi_pgd_idx(g, n - 1, (long)k);
    *wrap = sbi_pgd_idx(g, l - 1, (long)k);
    break;
  case SB_PGD_SOUTH:
    n = (long)g->ny;
    *ghost = sbi_pgd_idx(g, (long)k, -l);
    *copy = sbi_pgd_idx(g, (long)k, 0);
    *wrap = sbi_pgd_idx(g, (long)k, n - l);
    break;
  default:
    n = (long)g->ny;
    *ghost = sbi_pgd_idx(g, (long)k, n - 1 + l);
    *copy = sbi_pgd_idx(g, (long)k, n - 1);
    *wrap = sbi_pgd_idx(g, (long)k, l - 1);
    break;
  }
}

void sbi_pgd_fill_ghosts(struct sb_pgd *g)
{
  for (int s = 0; s < 4; s++) {
    if (g->nb[s] == 0 || g->external[s])
      continue;
    for (size_t k = 0; k < g->nb[s]; k++) {
      int m = g->inflow_at[s][k];
      for (long l = 1; l <= SBI_PGD_G; l++) {
        size_t gh, cp, wr;
        ghost_pair(g, s, k, l, &gh, &cp, &wr);
        if (m >= 0) {
          const sb_pgd_inflow *in = &g->p.inflow[m];
          g->rho[gh] = in->rho;
          g->qx[gh] = in->rho * in->u[0];
          g->qy[gh] = g->p.dim == 2 ? in->rho * in->u[1] : 0.0;
          continue;
        }
        size_t src = cp;
        switch (g->p.bc[s]) {
        case SB_PGD_PERIODIC:
          src = wr;
          break;
        case SB_PGD_OUTFLOW:
          g->rho[gh] = g->qx[gh] = g->qy[gh] = 0.0;
          continue;
        default:
          break;
        }
        g->rho[gh] = g->rho[src];
        g->qx[gh] = g->qx[src];
        g->qy[gh] = g->qy[src];
      }
    }
  }
}

/* ------------------------------------------------------------ output */

int sb_pgd_write_csv(const sb_pgd *g, const char *path)
{
  if (!g || !path)
    return sbi_error(SB_EINVAL, __func__, "NULL solver or path");
  FILE *f = fopen(path, "w");
  if (!f)
    return sbi_error(SB_EIO, __func__, "cannot write '%s'", path);
  const double fl = g->p.rho_floor;
  if (g->p.dim == 1)
    fprintf(f, "x,rho,u\n");
  else
    fprintf(f, "x,y,rho,ux,uy\n");
  for (size_t j = 0; j < g->ny; j++)
    for (size_t i = 0; i < g->nx; i++) {
      size_t c = sbi_pgd_idx(g, (long)i, (long)j);
      double x = g->p.origin[0] + ((double)i + 0.5) * g->dx;
      double ux = sbi_pgd_vel(g->rho[c], g->qx[c], fl);
      if (g->p.dim == 1) {
        fprintf(f, "%.17g,%.17g,%.17g\n", x, g->rho[c], ux);
      } else {
        double y = g->p.origin[1] + ((double)j + 0.5) * g->dy;
        fprintf(f, "%.17g,%.17g,%.17g,%.17g,%.17g\n", x, y, g->rho[c], ux,
                sbi_pgd_vel(g->rho[c], g->qy[c], fl));
      }
    }
  if (fclose(f) != 0)
    return sbi_error(SB_EIO, __func__, "cannot write '%s'", path);
  return SB_SUCCESS;
}

int sb_pgd_write_vtk(const sb_pgd *g, const char *path)
{
  if (!g || !path)
    return sbi_error(SB_EINVAL, __func__, "NULL solver or path");
  if (g->p.dim != 2)
    return sbi_error(SB_EINVAL, __func__, "VTK output is for 2-D grids");
  FILE *f = fopen(path, "w");
  if (!f)
    return sbi_error(SB_EIO, __func__, "cannot write '%s'", path);
  const double fl = g->p.rho_floor;
  fprintf(f, "# vtk DataFile Version 3.0\nsmolbridge pgd t = %.17g\nASCII\n"
          "DATASET STRUCTURED_POINTS\nDIMENSIONS %zu %zu 1\n"
          "ORIGIN %.17g %.17g 0\nSPACING %.17g %.17g 1\nCELL_DATA %zu\n"
          "SCALARS rho double 1\nLOOKUP_TABLE default\n",
          g->t, g->nx + 1, g->ny + 1, g->p.origin[0], g->p.origin[1], g->dx,
          g->dy, g->nx * g->ny);
  for (size_t j = 0; j < g->ny; j++)
    for (size_t i = 0; i < g->nx; i++)
      fprintf(f, "%.17g\n", g->rho[sbi_pgd_idx(g, (long)i, (long)j)]);
  fprintf(f, "VECTORS u double\n");
  for (size_t j = 0; j < g->ny; j++)
    for (size_t i = 0; i < g->nx; i++) {
      size_t c = sbi_pgd_idx(g, (long)i, (long)j);
      fprintf(f, "%.17g %.17g 0\n", sbi_pgd_vel(g->rho[c], g->qx[c], fl),
              sbi_pgd_vel(g->rho[c], g->qy[c], fl));
    }
  if (fclose(f) != 0)
    return sbi_error(SB_EIO, __func__, "cannot write '%s'", path);
  return SB_SUCCESS;
}
