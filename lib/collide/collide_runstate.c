/* collide_runstate.c — CHECKPOINT.run: what the outputs of a restarted
 * run need from its part before the checkpoint, so that series.csv and
 * summary.json are those of the run in one go: the kinetic energy at the
 * start of the measurement (summary.json kinetic_energy.start) and the
 * rows sampled with the series (the per-pair kernel columns and the
 * deposits per face).
 *
 * Format (native binary): "SBCRUN02", the energy (double), the species
 * of the pair columns (int32), the pair rows (uint64 count, then
 * 1 + 3 npairs doubles each), the deposit rows (uint64 count, then 7
 * doubles each), then the FNV-1a hash of every byte before it
 * (common/internal.h, sbi_hsave_finish), checked before anything is
 * read.  Version 01, the same without the hash, still loads. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "collide_internal.h"
#include "common/internal.h"

static const char MAGIC[8] = {'S', 'B', 'C', 'R', 'U', 'N', '0', '2'};

static size_t pair_width(int nsp)
{
  return nsp > 1 ? 1 + 3 * (size_t)(nsp * (nsp + 1) / 2) : 1;
}

int sbi_col_runstate_save(const sbi_col_config *c, const sbi_col_run *r)
{
  char path[600];
  sbi_col_beside(c, SBI_BESIDE_RUN, c->checkpoint, path, sizeof path);
  sbi_hsave hs;
  FILE *f = sbi_hsave_begin(&hs, "checkpoint");
  if (!f)
    return SB_ENOMEM;
  const int32_t nsp = r->pairs.nsp;
  const uint64_t np = r->pairs.nrows, nd = r->ndep;
  const size_t w = pair_width(nsp);
  int ok = fwrite(MAGIC, 1, 8, f) == 8 &&
           fwrite(&r->ekin0, sizeof r->ekin0, 1, f) == 1 &&
           fwrite(&nsp, sizeof nsp, 1, f) == 1 &&
           fwrite(&np, sizeof np, 1, f) == 1 &&
           (np == 0 || fwrite(r->pairs.rows, sizeof(double), w * np, f) ==
                           w * np) &&
           fwrite(&nd, sizeof nd, 1, f) == 1 &&
           (nd == 0 || fwrite(r->dep, sizeof(double), 7 * nd, f) == 7 * nd);
  return sbi_hsave_finish(&hs, ok, path, "checkpoint");
}

/* n rows of w doubles from f into a new array *rows (NULL for none). */
static int read_rows(FILE *f, size_t w, uint64_t n, double **rows)
{
  *rows = NULL;
  if (n == 0)
    return 0;
  if (n > ((uint64_t)1 << 32))
    return -1;
  *rows = malloc((size_t)n * w * sizeof **rows);
  return !*rows || fread(*rows, sizeof **rows, (size_t)n * w, f) !=
                       (size_t)n * w ? -1 : 0;
}

int sbi_col_runstate_load(sbi_col_config *c, sbi_col_run *r)
{
  char path[600];
  sbi_col_beside(c, SBI_BESIDE_RUN, c->restart, path, sizeof path);
  FILE *f = fopen(path, "rb");
  if (!f) {
    sbi_col_warn(c, "no %s beside the checkpoint (written by a checkpoint "
                 "of an older version): summary.json kinetic_energy.start is "
                 "the restart's, and series.csv has no pair kernels or "
                 "deposits before it", path);
    return 0;
  }
  fclose(f);
  int ver, st;
  char *mem;
  f = sbi_hload_open(path, MAGIC, 2, "run state beside a checkpoint", &ver,
                     &mem, "restart", &st);
  if (!f)
    return sbi_col_fail(c, "[run] %s", sb_last_error());
  char mg[8];
  double ekin0;
  int32_t nsp;
  uint64_t np, nd;
  double *pr = NULL, *dr = NULL;
  int bad = fread(mg, 1, 8, f) != 8 ||
            fread(&ekin0, sizeof ekin0, 1, f) != 1 ||
            fread(&nsp, sizeof nsp, 1, f) != 1 ||
            fread(&np, sizeof np, 1, f) != 1;
  if (!bad && nsp != r->pairs.nsp) {
    fclose(f);
    free(mem);
    return sbi_col_fail(c, "[run] restart: %s: its series has pair columns "
                        "for %d species, this run %d", path, (int)nsp,
                        r->pairs.nsp);
  }
  bad = bad || read_rows(f, pair_width(nsp), np, &pr) ||
        fread(&nd, sizeof nd, 1, f) != 1 || read_rows(f, 7, nd, &dr) ||
        fgetc(f) != EOF;
  fclose(f);
  free(mem);
  if (bad) {
    free(pr);
    free(dr);
    return sbi_col_fail(c, "[run] restart: %s: not the run's state beside "
                        "a checkpoint (truncated, or data after the end)",
                        path);
  }
  r->ekin0 = ekin0;
  r->ekin0_saved = 1;
  free(r->pairs.rows);
  r->pairs.rows = pr;
  r->pairs.nrows = r->pairs.cap = (size_t)np;
  free(r->dep);
  r->dep = dr;
  r->ndep = r->capdep = (size_t)nd;
  return 0;
}
