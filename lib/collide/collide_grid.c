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

int sbi_col_grid_on(const sbi_col_config *c) { return c->ngrid > 0; }

/* Cells along each axis (n[2] = 1 in 2-D). */
static void grid_cells(const sbi_col_config *c, size_t n[3])
{
  for (int k = 0; k < 3; k++)
    n[k] = k < c->ngrid && (k < 2 || c->dim == 3) ? (size_t)c->grid[k] : 1;
}

/* grid.csv with its header; SB_EIO with the path. */
static int grid_open(const sbi_col_config *c, sbi_col_run *r)
{
  char path[1100];
  snprintf(path, sizeof path, "%s/grid.csv", c->output);
  r->grid_f = fopen(path, "w");
  if (!r->grid_f)
    return sbi_error(SB_EIO, "[observe] grid", "cannot write %s", path);
  fprintf(r->grid_f, "t,i,j,k,rho,rho_ux,rho_uy,rho_uz\n");
  return SB_SUCCESS;
}

/* Each frame goes straight to grid.csv (a long run has many frames of
 * many cells: none is kept in memory, and a run that stops keeps the
 * frames written). */
int sbi_col_grid_sample(const sbi_col_config *c, sbi_col_run *r)
{
  if (!sbi_col_grid_on(c))
    return SB_SUCCESS;
  const double t = sb_engine_time(r->e);
  if (r->grid_frames && r->grid_last_t == t)
    return SB_SUCCESS;  /* this time has its frame */
  if (!r->grid_f && grid_open(c, r))
    return SB_EIO;
  size_t n[3];
  grid_cells(c, n);
  const size_t nc = n[0] * n[1] * n[2];
  double *rho = malloc(nc * sizeof *rho), *mom = malloc(3 * nc * sizeof *mom);
  int st = rho && mom ? SB_SUCCESS : SB_ENOMEM;
  if (!st)
    st = sb_engine_grid_fields(r->e, n, !strcmp(c->grid_scheme, "cic")
                                            ? SB_GRID_CIC
                                            : SB_GRID_NGP, -1, rho, mom);
  for (size_t q = 0; q < nc && !st; q++)
    fprintf(r->grid_f, "%.17g,%zu,%zu,%zu,%.17g,%.17g,%.17g,%.17g\n", t,
            q % n[0], q / n[0] % n[1], q / (n[0] * n[1]), rho[q],
            mom[3 * q], mom[3 * q + 1], mom[3 * q + 2]);
  if (!st && ferror(r->grid_f))
    st = sbi_error(SB_EIO, "[observe] grid", "cannot write grid.csv");
  if (!st) {
    r->grid_frames++;
    r->grid_last_t = t;
  }
  free(rho);
  free(mom);
  return st;
}

int sbi_col_grid_close(const sbi_col_config *c, sbi_col_run *r)
{
  if (!r->grid_f && grid_open(c, r))  /* no frame: the header alone */
    return -1;
  int bad = ferror(r->grid_f);
  bad |= fclose(r->grid_f) != 0;
  r->grid_f = NULL;
  return bad ? -1 : 0;
}

void sbi_col_grid_json(FILE *f, const sbi_col_config *c,
                       const sbi_col_run *r)
{
  size_t n[3];
  grid_cells(c, n);
  const size_t nc = n[0] * n[1] * n[2];
  fprintf(f, "  \"grid\": {\"n\": [%zu, %zu, %zu], \"scheme\": \"%s\", "
          "\"frames\": %zu, \"file\": \"grid.csv\"},\n", n[0], n[1], n[2],
          c->grid_scheme, nc ? r->grid_frames : 0);
}
