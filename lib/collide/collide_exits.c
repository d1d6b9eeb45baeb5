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

static const char *const faces[6] = {"x_lo", "x_hi", "y_lo",
                                     "y_hi", "z_lo", "z_hi"};

/* exits.csv (again) with its header; SB_EIO with the path. */
static int exits_open(const sbi_col_config *c, sbi_col_run *r)
{
  char path[1100];
  snprintf(path, sizeof path, "%s/exits.csv", c->output);
  if (r->exits_f)
    fclose(r->exits_f);
  r->exits_f = fopen(path, "w");
  if (!r->exits_f)
    return sbi_error(SB_EIO, "[observe] exits", "cannot write %s", path);
  fprintf(r->exits_f, "t,face,species,family,mass,x,y,z,ux,uy,uz\n");
  return SB_SUCCESS;
}

/* sb_engine_outflow_fn: the state is the step's end, outside the box by
 * at most one step's flight; back along the chord to the face.  The row
 * goes straight to exits.csv: a long run with open faces sees millions
 * of exits, none is kept in memory, and a run that stops keeps the rows
 * written. */
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
  const sbi_col_config *c = r->exits_c;
  if (!r->exits_f && exits_open(c, r))
    return SB_EIO;
  FILE *f = r->exits_f;
  char name[32];
  fprintf(f, "%.17g,%s,%s,%d,%.17g", t_exit,
          face >= 0 && face < 6 ? faces[face] : "?",
          sbi_col_species_label(c, r->agglo, sb_engine_species_of(e)[i],
                                name, sizeof name),
          fam, m);
  for (int k = 0; k < 3; k++)
    fprintf(f, ",%.17g", x[k]);
  for (int k = 0; k < 3; k++)
    fprintf(f, ",%.17g", u[k]);
  return fputc('\n', f) == EOF
             ? sbi_error(SB_EIO, "[observe] exits", "cannot write exits.csv")
             : SB_SUCCESS;
}

int sbi_col_exits_attach(const sbi_col_config *c, sbi_col_run *r)
{
  r->record_exits = c->exits > 0;
  r->exits_c = c;
  return c->exits > 0 || c->batch_steps > 0
             ? sb_engine_set_outflow_fn(r->e, on_exit, r)
             : SB_SUCCESS;
}

int sbi_col_exits_reset(sbi_col_run *r)
{
  /* the warm-up's rows go: the file starts again */
  return r->exits_f ? exits_open(r->exits_c, r) : SB_SUCCESS;
}

int sbi_col_exits_close(const sbi_col_config *c, sbi_col_run *r)
{
  if (!r->exits_f && exits_open(c, r))  /* no exit: the header alone */
    return -1;
  int bad = ferror(r->exits_f);
  bad |= fclose(r->exits_f) != 0;
  r->exits_f = NULL;
  return bad ? -1 : 0;
}
