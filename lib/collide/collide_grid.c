/* collide_grid.c — `[observe] grid`: the particles' mass and momentum
 * densities deposited on a regular grid (sb_engine_grid_fields) at every
 * stop of `[run] stop_every` and at the end, written to grid.csv: the
 * Eulerian view of the Lagrangian run, for comparison with an Eulerian
 * solver on the same grid (`smolbridge pgd`; validation case
 * V15/engine-jets). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <smolbridge/engine.h>

#include "common/internal.h"
#include "collide_internal.h"

#define GRID_COLS 8  /* t, i, j, k, rho, rho_ux, rho_uy, rho_uz */

int sbi_col_grid_on(const sbi_col_config *c) { return c->ngrid > 0; }

/* Cells along each axis (n[2] = 1 in 2-D). */
static void grid_cells(const sbi_col_config *c, size_t n[3])
{
  for (int k = 0; k < 3; k++)
    n[k] = k < c->ngrid && (k < 2 || c->dim == 3) ? (size_t)c->grid[k] : 1;
}

int sbi_col_grid_sample(const sbi_col_config *c, sbi_col_run *r)
{
  if (!sbi_col_grid_on(c))
    return SB_SUCCESS;
  const double t = sb_engine_time(r->e);
  if (r->grid_n && r->grid_rows[(r->grid_n - 1) * GRID_COLS] == t)
    return SB_SUCCESS;  /* this time has its frame */
  size_t n[3];
  grid_cells(c, n);
  const size_t nc = n[0] * n[1] * n[2];
  if (r->grid_n + nc > r->grid_cap) {
    size_t cap = r->grid_cap ? 2 * r->grid_cap : nc;
    while (cap < r->grid_n + nc)
      cap *= 2;
    double *q = realloc(r->grid_rows, cap * GRID_COLS * sizeof *q);
    if (!q)
      return sbi_error(SB_ENOMEM, "[observe] grid", "out of memory");
    r->grid_rows = q;
    r->grid_cap = cap;
  }
  double *rho = malloc(nc * sizeof *rho), *mom = malloc(3 * nc * sizeof *mom);
  int st = rho && mom ? SB_SUCCESS : SB_ENOMEM;
  if (!st)
    st = sb_engine_grid_fields(r->e, n, !strcmp(c->grid_scheme, "cic")
                                            ? SB_GRID_CIC
                                            : SB_GRID_NGP, -1, rho, mom);
  for (size_t q = 0; q < nc && !st; q++) {
    double *row = r->grid_rows + (r->grid_n + q) * GRID_COLS;
    row[0] = t;
    row[1] = (double)(q % n[0]);
    row[2] = (double)(q / n[0] % n[1]);
    row[3] = (double)(q / (n[0] * n[1]));
    row[4] = rho[q];
    memcpy(row + 5, mom + 3 * q, 3 * sizeof *row);
  }
  if (!st)
    r->grid_n += nc;
  free(rho);
  free(mom);
  return st;
}

int sbi_col_grid_csv(const sbi_col_config *c, const sbi_col_run *r,
                     const char *path)
{
  FILE *f = fopen(path, "w");
  if (!f)
    return -1;
  fprintf(f, "t,i,j,k,rho,rho_ux,rho_uy,rho_uz\n");
  for (size_t q = 0; q < r->grid_n; q++) {
    const double *row = r->grid_rows + q * GRID_COLS;
    fprintf(f, "%.17g,%.0f,%.0f,%.0f,%.17g,%.17g,%.17g,%.17g\n", row[0],
            row[1], row[2], row[3], row[4], row[5], row[6], row[7]);
  }
  (void)c;
  return fclose(f) ? -1 : 0;
}

void sbi_col_grid_json(FILE *f, const sbi_col_config *c,
                       const sbi_col_run *r)
{
  size_t n[3];
  grid_cells(c, n);
  const size_t nc = n[0] * n[1] * n[2];
  fprintf(f, "  \"grid\": {\"n\": [%zu, %zu, %zu], \"scheme\": \"%s\", "
          "\"frames\": %zu, \"file\": \"grid.csv\"},\n", n[0], n[1], n[2],
          c->grid_scheme, nc ? r->grid_n / nc : 0);
}
