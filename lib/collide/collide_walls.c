/* collide_walls.c — what a `smolbridge collide` run measures and places
 * at walls: the deposits per absorbing face through the run (series.csv
 * columns, sampled with the series), the parabolic placement profile
 * between walls ([species] profile), and runs without particle-particle
 * detection ([run] detect = none: particles only meet the walls). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_randist.h>

#include "collide_internal.h"

static const char *const FACE[6] = {"x_lo", "x_hi", "y_lo", "y_hi",
                                    "z_lo", "z_hi"};

int sbi_col_walls_absorb(const sbi_col_config *c)
{
  for (int f = 0; f < 6; f++)
    if (!strcmp(c->wall[f], "absorb"))
      return 1;
  return 0;
}

int sbi_col_walls_sample(sbi_col_run *r)
{
  if (r->ndep == r->capdep) {
    size_t nc = r->capdep ? 2 * r->capdep : 256;
    double *nr = realloc(r->dep, nc * 7 * sizeof *nr);
    if (!nr)
      return SB_ENOMEM;
    r->dep = nr;
    r->capdep = nc;
  }
  double *row = r->dep + 7 * r->ndep++;
  row[0] = sb_engine_time(r->e);
  for (int f = 0; f < 6; f++)
    row[1 + f] = (double)sb_engine_deposits(r->e, f);
  return SB_SUCCESS;
}

void sbi_col_walls_header(FILE *f, const sbi_col_config *c)
{
  if (!sbi_col_walls_absorb(c))
    return;
  fprintf(f, ",deposits");
  for (int q = 0; q < 6; q++)
    if (!strcmp(c->wall[q], "absorb"))
      fprintf(f, ",deposits_%s", FACE[q]);
}

void sbi_col_walls_row(FILE *f, const sbi_col_config *c,
                       const sbi_col_run *r, double t, size_t *next)
{
  if (!sbi_col_walls_absorb(c))
    return;
  /* the row sampled at the same time (the measured part); both series
   * are in time order */
  while (*next < r->ndep && r->dep[7 * *next] < t)
    (*next)++;
  const double *row = *next < r->ndep && r->dep[7 * *next] == t
                          ? r->dep + 7 * *next
                          : NULL;
  double tot = 0.0;
  for (int q = 0; q < 6 && row; q++)
    tot += row[1 + q];
  if (row)
    fprintf(f, ",%.0f", tot);
  else
    fprintf(f, ",nan");
  for (int q = 0; q < 6; q++)
    if (!strcmp(c->wall[q], "absorb")) {
      if (row)
        fprintf(f, ",%.0f", row[1 + q]);
      else
        fprintf(f, ",nan");
    }
}

double sbi_col_place_coord(const sbi_col_config *c,
                           const sbi_col_species *s, int k, double lo,
                           double hi, gsl_rng *g)
{
  /* density (x - lo)(hi - x) on [lo, hi]: the Beta(2, 2) law */
  if (!strcmp(s->profile, "parabolic") && strcmp(c->wall[2 * k], "periodic"))
    return lo + (hi - lo) * gsl_ran_beta(g, 2.0, 2.0);
  return lo + (hi - lo) * gsl_rng_uniform(g);
}

int sbi_col_detect_none(const sbi_col_config *c)
{
  return !strcmp(c->detect, "none");
}

int sbi_col_none_attach(sbi_col_run *r)
{
  /* no extra reach: the neighbour search keeps its contact distance */
  return sb_engine_set_detector(r->e, sb_engine_detect_none, NULL, 0.0);
}
