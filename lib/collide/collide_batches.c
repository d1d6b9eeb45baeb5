/* collide_batches.c — `[observe] batch_steps` and `region`: the
 * measurement cut into batches of a fixed number of steps, one row of
 * batches.csv per batch, and the batch means with t intervals in
 * summary.json.  Batch means are the standard estimator of the mean of a
 * time-correlated output and of its error: batches much longer than the
 * correlation time have nearly independent means (Law & Kelton 2000,
 * §9.5.3; Flyvbjerg & Petersen 1989, J. Chem. Phys. 91, 461).
 *
 * A row: the batch's start and end time, the particles at its start and
 * end, the drops injected by the inflows and leaving through open faces,
 * the mass leaving, the collisions; per open face the exiting mass of
 * each family, the exiting momentum per axis and the mass-weighted
 * coordinates of the exit points along the face (sums: their ratios are
 * the means); per region the mean mass inside over the samples of the
 * batch. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_cdf.h>

#include <smolbridge/engine.h>

#include "collide_internal.h"

#define NAME_LEN 24

struct sbi_col_batches {
  long per, nb, every;    /* steps per batch, batches, region period */
  long mk;                /* measured steps done */
  int dim, nface, nfam, nreg;
  int face[6];            /* the open faces, x_lo .. z_hi order */
  long fam[COL_MAXSPEC];  /* the species' families, increasing */
  double reg[COL_MAXREGION][6];
  int ncol;               /* columns; the offsets of the groups: */
  int c_m, c_p, c_x, c_r; /* exit mass, momentum, coordinates, regions */
  char (*names)[NAME_LEN];
  double *rows;           /* nb x ncol */
  double nsamp;           /* region samples of the open batch */
  double coll0, inj0, out0;
};

enum { C_BATCH, C_T0, C_T1, C_N0, C_N1, C_INJ, C_LEFT, C_MLEFT, C_COLL,
       C_SAMP, C_FIXED };

static const char *const FACE[6] = {"x_lo", "x_hi", "y_lo",
                                    "y_hi", "z_lo", "z_hi"};

int sbi_col_batches_check(sbi_col_config *c)
{
  if (c->batch_steps > 0 && c->nregions > 0 &&
      c->batch_steps % c->region_every)
    return sbi_col_fail(c, "%s: [observe] region_every = %ld does not "
                        "divide batch_steps = %ld: the batches would hold "
                        "unequal numbers of samples; valid: a divisor of "
                        "%ld", sbi_col_where(c, "observe", "region_every"),
                        c->region_every, c->batch_steps, c->batch_steps);
  if (c->batch_steps > 0) {
    if (!c->nregions && sbi_col_given(c, "observe", "region_every"))
      sbi_col_warn(c, "%s: [observe] region_every: no [observe] region to "
                   "sample; ignored",
                   sbi_col_where(c, "observe", "region_every"));
    return 0;
  }
  if (c->nregions > 0)
    return sbi_col_fail(c, "%s: [observe] region: its mass is reported per "
                        "batch; give [observe] batch_steps (steps per "
                        "batch, e.g. a tenth of the measured steps)",
                        c->region_where[0]);
  if (sbi_col_given(c, "observe", "region_every"))
    return sbi_col_fail(c, "%s: [observe] region_every without a region "
                        "and batch_steps; give [observe] region = x0 x1 y0 "
                        "y1 [z0 z1] and batch_steps",
                        sbi_col_where(c, "observe", "region_every"));
  return 0;
}

void sbi_col_batches_free(sbi_col_batches *b)
{
  if (!b)
    return;
  free(b->names);
  free(b->rows);
  free(b);
}

static double total_injected(const sb_engine *e)
{
  double s = 0.0;
  for (size_t q = 0; q < sb_engine_ninflows(e); q++)
    s += (double)sb_engine_inflow_injected(e, q);
  return s;
}

static double total_out(const sb_engine *e)
{
  double s = 0.0;
  for (int f = 0; f < 6; f++)
    s += (double)sb_engine_outflows(e, f);
  return s;
}

static double collisions(const sb_engine *e)
{
  sb_engine_stats s;
  sb_engine_get_stats(e, &s);
  return (double)s.ncoll;
}

/* The regions inside the box, with the numbers of the dimension. */
static int check_regions(sbi_col_config *c, const double *L)
{
  for (int q = 0; q < c->nregions; q++) {
    const double *g = c->regions[q];
    if (c->nregion_n[q] != 2 * (int)c->dim)
      return sbi_col_fail(c, "%s: [observe] region has %d numbers in %ld-D; "
                          "valid: %s", c->region_where[q], c->nregion_n[q],
                          c->dim, c->dim == 2 ? "x0 x1 y0 y1"
                                              : "x0 x1 y0 y1 z0 z1");
    for (int k = 0; k < c->dim; k++)
      if (!(g[2 * k] >= 0.0 && g[2 * k] < g[2 * k + 1] &&
            g[2 * k + 1] <= L[k]))
        return sbi_col_fail(c, "%s: [observe] region: %c0 = %g, %c1 = %g m; "
                            "valid: 0 <= %c0 < %c1 <= %g (the box)",
                            c->region_where[q], 'x' + k, g[2 * k], 'x' + k,
                            g[2 * k + 1], 'x' + k, 'x' + k, L[k]);
  }
  return 0;
}

int sbi_col_batches_setup(sbi_col_config *c, sbi_col_run *r, long nsteps)
{
  if (c->batch_steps <= 0)
    return 0;
  const sb_engine_params *p = sb_engine_get_params(r->e);
  const char *where = sbi_col_where(c, "observe", "batch_steps");
  if (check_regions(c, p->L))
    return -1;
  if (c->batch_steps > nsteps || nsteps % c->batch_steps)
    return sbi_col_fail(c, "%s: [observe] batch_steps = %ld: the run "
                        "measures %ld steps, not a whole number of batches; "
                        "valid: a divisor of %ld (or steps = a multiple of "
                        "%ld)", where, c->batch_steps, nsteps, nsteps,
                        c->batch_steps);
  sbi_col_batches *b = calloc(1, sizeof *b);
  if (!b)
    return sbi_col_fail(c, "out of memory");
  r->batches = b;
  b->per = c->batch_steps;
  b->nb = nsteps / c->batch_steps;
  b->every = c->region_every;
  b->dim = p->dim;
  for (int f = 0; f < 2 * p->dim; f++)
    if (!strcmp(c->wall[f], "open"))
      b->face[b->nface++] = f;
  /* the families of the species, increasing (family 0 without any) */
  for (int k = 0; k < c->nsp || (k == 0 && c->nsp == 0); k++) {
    long f = c->nsp ? c->sp[k].family : 0;
    int i = 0;
    while (i < b->nfam && b->fam[i] < f)
      i++;
    if (i < b->nfam && b->fam[i] == f)
      continue;
    memmove(b->fam + i + 1, b->fam + i, (size_t)(b->nfam - i) * sizeof(long));
    b->fam[i] = f;
    b->nfam++;
  }
  b->nreg = c->nregions;
  memcpy(b->reg, c->regions, sizeof b->reg);
  b->c_m = C_FIXED;
  b->c_p = b->c_m + b->nface * b->nfam;
  b->c_x = b->c_p + b->nface * b->dim;
  b->c_r = b->c_x + b->nface * (b->dim - 1);
  b->ncol = b->c_r + b->nreg;
  b->names = calloc((size_t)b->ncol, sizeof *b->names);
  b->rows = calloc((size_t)(b->nb * b->ncol), sizeof *b->rows);
  if (!b->names || !b->rows)
    return sbi_col_fail(c, "out of memory");
  static const char *const fixed[C_FIXED] = {
      "batch", "t_start", "t_end", "n_start", "n_end", "injected", "left",
      "m_left", "collisions", "region_samples"};
  for (int k = 0; k < C_FIXED; k++)
    snprintf(b->names[k], NAME_LEN, "%s", fixed[k]);
  for (int q = 0; q < b->nface; q++) {
    const int f = b->face[q];
    for (int i = 0; i < b->nfam; i++)
      snprintf(b->names[b->c_m + q * b->nfam + i], NAME_LEN, "m_%s_f%ld",
               FACE[f], b->fam[i]);
    for (int k = 0; k < b->dim; k++)
      snprintf(b->names[b->c_p + q * b->dim + k], NAME_LEN, "p%c_%s",
               'x' + k, FACE[f]);
    for (int k = 0, j = 0; k < b->dim; k++)
      if (k != f / 2)
        snprintf(b->names[b->c_x + q * (b->dim - 1) + j++], NAME_LEN,
                 "m%c_%s", 'x' + k, FACE[f]);
  }
  for (int q = 0; q < b->nreg; q++)
    snprintf(b->names[b->c_r + q], NAME_LEN, "region%d", q + 1);
  return 0;
}

/* Open batch k: its start values. */
static void open_batch(sbi_col_batches *b, const sb_engine *e, long k)
{
  double *row = b->rows + k * b->ncol;
  row[C_BATCH] = (double)k;
  row[C_T0] = sb_engine_time(e);
  row[C_N0] = (double)sb_engine_count(e);
  b->coll0 = collisions(e);
  b->inj0 = total_injected(e);
  b->out0 = total_out(e);
  b->nsamp = 0.0;
}

static void close_batch(sbi_col_batches *b, const sb_engine *e, long k)
{
  double *row = b->rows + k * b->ncol;
  row[C_T1] = sb_engine_time(e);
  row[C_N1] = (double)sb_engine_count(e);
  row[C_INJ] = total_injected(e) - b->inj0;
  row[C_LEFT] = total_out(e) - b->out0;
  row[C_COLL] = collisions(e) - b->coll0;
  row[C_SAMP] = b->nsamp;
  for (int q = 0; q < b->nreg; q++)  /* the sums of the samples: means */
    row[b->c_r + q] = b->nsamp > 0 ? row[b->c_r + q] / b->nsamp : NAN;
}

void sbi_col_batches_start(sbi_col_run *r)
{
  if (r->batches) {
    r->batches->mk = 0;
    open_batch(r->batches, r->e, 0);
  }
}

/* Add the mass inside each region to the batch's sums. */
static void sample_regions(sbi_col_batches *b, const sb_engine *e,
                           double *row)
{
  const double *x = sb_engine_positions(e), *m = sb_engine_masses(e);
  const size_t n = sb_engine_count(e);
  for (int q = 0; q < b->nreg; q++) {
    const double *g = b->reg[q];
    double s = row[b->c_r + q];
    for (size_t i = 0; i < n; i++) {
      int in = 1;
      for (int k = 0; k < b->dim && in; k++)
        in = x[3 * i + k] >= g[2 * k] && x[3 * i + k] < g[2 * k + 1];
      if (in)
        s += m[i];
    }
    row[b->c_r + q] = s;
  }
  b->nsamp += 1.0;
}

void sbi_col_batches_step(sbi_col_run *r)
{
  sbi_col_batches *b = r->batches;
  if (!b || b->mk >= b->per * b->nb)
    return;
  b->mk++;
  const long k = (b->mk - 1) / b->per;  /* the batch of this step */
  if (b->nreg && b->mk % b->every == 0)
    sample_regions(b, r->e, b->rows + k * b->ncol);
  if (b->mk % b->per == 0) {
    close_batch(b, r->e, k);
    if (k + 1 < b->nb)
      open_batch(b, r->e, k + 1);
  }
}

void sbi_col_batches_exit(sbi_col_run *r, int face, int family, double m,
                          const double x[3], const double u[3])
{
  sbi_col_batches *b = r->batches;
  if (!b || !r->measuring || b->mk >= b->per * b->nb)
    return;
  double *row = b->rows + (b->mk / b->per) * b->ncol;
  int q = 0;
  while (q < b->nface && b->face[q] != face)
    q++;
  if (q == b->nface)
    return;
  row[C_MLEFT] += m;
  for (int i = 0; i < b->nfam; i++)
    if (b->fam[i] == family)
      row[b->c_m + q * b->nfam + i] += m;
  for (int k = 0; k < b->dim; k++)
    row[b->c_p + q * b->dim + k] += m * u[k];
  for (int k = 0, j = 0; k < b->dim; k++)
    if (k != face / 2)
      row[b->c_x + q * (b->dim - 1) + j++] += m * x[k];
}

int sbi_col_batches_write(FILE *js, const sbi_col_config *c,
                          const sbi_col_run *r, const char *path)
{
  const sbi_col_batches *b = r->batches;
  if (!b)
    return 0;
  /* the batches completed (all of them unless the run failed) */
  const long nb = b->mk / b->per;
  FILE *f = fopen(path, "w");
  if (!f)
    return -1;
  for (int k = 0; k < b->ncol; k++)
    fprintf(f, "%s%s", k ? "," : "", b->names[k]);
  fputc('\n', f);
  for (long q = 0; q < nb; q++) {
    const double *row = b->rows + q * b->ncol;
    for (int k = 0; k < b->ncol; k++)
      fprintf(f, k < C_T0 ? "%.0f" : ",%.17g", row[k]);
    fputc('\n', f);
  }
  int err = fclose(f) != 0;
  fprintf(js, "  \"batches\": {\"file\": \"batches.csv\", \"steps\": %ld, "
          "\"n\": %ld, \"region_every\": %ld, \"regions\": [", b->per, nb,
          c->region_every);
  for (int q = 0; q < b->nreg; q++) {
    fprintf(js, "%s[", q ? ", " : "");
    for (int k = 0; k < 2 * b->dim; k++)
      fprintf(js, "%s%.17g", k ? ", " : "", b->reg[q][k]);
    fprintf(js, "]");
  }
  /* each column's batch mean with its t interval (95%) */
  fprintf(js, "],\n    \"means\": {");
  const double tq = nb > 1 ? gsl_cdf_tdist_Pinv(0.975, (double)(nb - 1))
                           : NAN;
  for (int k = C_N0; k < b->ncol; k++) {
    double s = 0.0, s2 = 0.0;
    for (long q = 0; q < nb; q++)
      s += b->rows[q * b->ncol + k];
    const double mean = nb > 0 ? s / (double)nb : NAN;
    for (long q = 0; q < nb; q++) {
      const double d = b->rows[q * b->ncol + k] - mean;
      s2 += d * d;
    }
    const double se = nb > 1 ? sqrt(s2 / (double)(nb - 1) / (double)nb)
                             : NAN;
    fprintf(js, "%s\n      \"%s\": {\"mean\": ", k > C_N0 ? "," : "",
            b->names[k]);
    sbi_col_jnum(js, mean);
    fprintf(js, ", \"ci95\": [");
    sbi_col_jnum(js, mean - tq * se);
    fprintf(js, ", ");
    sbi_col_jnum(js, mean + tq * se);
    fprintf(js, "]}");
  }
  fprintf(js, "}},\n");
  return err ? -1 : 0;
}
