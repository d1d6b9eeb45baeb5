/* collide_exits.c — `[observe] exits`: every particle leaving through an
 * open face during the measurement (the engine's outflow callback,
 * engine_open.c) as a row of exits.csv: when and where its straight chord
 * crossed the face, its face, species, family, mass and velocity (the
 * outflow profiles and momentum fluxes of Thomine 2008, §9); the same
 * callback adds each exit to its batch ([observe] batch_steps,
 * collide_batches.c). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <smolbridge/engine.h>

#include "common/internal.h"
#include "collide_internal.h"

#define EXIT_COLS 11  /* t, face, species, family, mass, x, y, z, ux, uy, uz */

/* sb_engine_outflow_fn: the state is the step's end, outside the box by
 * at most one step's flight; back along the chord to the face. */
static int on_exit(const sb_engine *e, size_t i, int face, double t_exit,
                   void *vr)
{
  sbi_col_run *r = vr;
  const double *p = &sb_engine_positions(e)[3 * i];
  const double *u = &sb_engine_velocities(e)[3 * i];
  const double back = sb_engine_time(e) + sb_engine_get_params(e)->dt -
                      t_exit;
  double x[3];
  for (int k = 0; k < 3; k++)
    x[k] = p[k] - u[k] * back;
  const int fam = sb_engine_families(e)[i];
  const double m = sb_engine_masses(e)[i];
  sbi_col_batches_exit(r, face, fam, m, x, u);  /* [observe] batch_steps */
  if (!r->record_exits)
    return SB_SUCCESS;
  if (r->exit_n + 1 > r->exit_cap) {
    size_t cap = r->exit_cap ? 2 * r->exit_cap : 1024;
    double *q = realloc(r->exit_rows, cap * EXIT_COLS * sizeof *q);
    if (!q)
      return SB_ENOMEM;
    r->exit_rows = q;
    r->exit_cap = cap;
  }
  double *row = r->exit_rows + r->exit_n * EXIT_COLS;
  row[0] = t_exit;
  row[1] = face;
  row[2] = (double)sb_engine_species_of(e)[i];
  row[3] = fam;
  row[4] = m;
  for (int k = 0; k < 3; k++) {
    row[5 + k] = x[k];
    row[8 + k] = u[k];
  }
  r->exit_n++;
  return SB_SUCCESS;
}

int sbi_col_exits_attach(const sbi_col_config *c, sbi_col_run *r)
{
  r->record_exits = c->exits > 0;
  return c->exits > 0 || c->batch_steps > 0
             ? sb_engine_set_outflow_fn(r->e, on_exit, r)
             : SB_SUCCESS;
}

void sbi_col_exits_reset(sbi_col_run *r) { r->exit_n = 0; }

int sbi_col_exits_csv(const sbi_col_config *c, const sbi_col_run *r,
                      const char *path)
{
  static const char *const faces[6] = {"x_lo", "x_hi", "y_lo",
                                       "y_hi", "z_lo", "z_hi"};
  FILE *f = fopen(path, "w");
  if (!f)
    return -1;
  fprintf(f, "t,face,species,family,mass,x,y,z,ux,uy,uz\n");
  for (size_t q = 0; q < r->exit_n; q++) {
    const double *row = r->exit_rows + q * EXIT_COLS;
    const int face = (int)row[1];
    fprintf(f, "%.17g,%s,%s,%.0f", row[0],
            face >= 0 && face < 6 ? faces[face] : "?",
            sbi_col_short_name(c, (size_t)row[2]), row[3]);
    for (int k = 4; k < EXIT_COLS; k++)
      fprintf(f, ",%.17g", row[k]);
    fputc('\n', f);
  }
  return fclose(f) ? -1 : 0;
}
