/* collide_sweep.c — `smolbridge collide CONFIG.ini --sweep FILE`: one run
 * per line of FILE (overrides after the command line's --set), in
 * OUTPUT/point_NNN/, and OUTPUT/sweep.csv.  Under mpirun the points are
 * shared by the ranks (point k on rank k mod P) and rank 0 writes the
 * summary in point order: the same files as a single process, whatever
 * the number of ranks (docs/parallel.md). */
#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include <smolbridge/collide.h>

#include "collide.h"
#include "par.h"

#define SW_MAXSET 64 /* overrides per line */

typedef struct {
  char **line;   /* the overrides of each point, as written */
  size_t n, cap;
} sw_points;

static void points_free(sw_points *P)
{
  for (size_t i = 0; i < P->n; i++)
    free(P->line[i]);
  free(P->line);
}

/* Lines of the file without comments and blank lines; 0, or -1 with a
 * message in err. */
static int read_points(const char *file, sw_points *P, char *err,
                       size_t elen)
{
  FILE *f = fopen(file, "r");
  if (!f) {
    snprintf(err, elen, "--sweep %s: %s", file, strerror(errno));
    return -1;
  }
  char buf[8192];
  long ln = 0;
  while (fgets(buf, sizeof buf, f)) {
    ln++;
    size_t L = strlen(buf);
    if (L == sizeof buf - 1 && buf[L - 1] != '\n') {
      snprintf(err, elen, "%s:%ld: line longer than %zu characters", file,
               ln, sizeof buf - 2);
      fclose(f);
      return -1;
    }
    char *h = strchr(buf, '#');
    if (h)
      *h = '\0';
    char *b = buf;
    while (*b == ' ' || *b == '\t')
      b++;
    size_t e = strlen(b);
    while (e > 0 && strchr(" \t\r\n", b[e - 1]))
      b[--e] = '\0';
    if (!*b || *b == ';')
      continue;
    if (P->n == P->cap) {
      size_t nc = P->cap ? 2 * P->cap : 16;
      char **q = realloc(P->line, nc * sizeof *q);
      if (!q) {
        fclose(f);
        snprintf(err, elen, "out of memory");
        return -1;
      }
      P->line = q;
      P->cap = nc;
    }
    size_t blen = strlen(b) + 1;
    if (!(P->line[P->n] = malloc(blen))) {
      fclose(f);
      snprintf(err, elen, "out of memory");
      return -1;
    }
    memcpy(P->line[P->n++], b, blen);
  }
  fclose(f);
  if (P->n == 0) {
    snprintf(err, elen, "--sweep %s: no point (one line of "
             "SECTION.KEY=VALUE overrides per run)", file);
    return -1;
  }
  return 0;
}

/* The output directory and the checkpoint's file name (its last path
 * component, "" without one) of the base configuration (file + --set). */
static int base_output(const char *ini, const char *const *sets, int nsets,
                       char *out, size_t len, char *ck, size_t cklen,
                       char *err, size_t elen)
{
  sb_collide *c = sb_collide_alloc();
  if (!c) {
    snprintf(err, elen, "out of memory");
    return -1;
  }
  int st = sb_collide_read_file(c, ini);
  for (int i = 0; i < nsets && !st; i++)
    st = sb_collide_set(c, sets[i]);
  if (st)
    snprintf(err, elen, "%s", sb_collide_error(c));
  else {
    snprintf(out, len, "%s", sb_collide_output(c));
    const char *p = sb_collide_checkpoint(c), *slash = strrchr(p, '/');
    snprintf(ck, cklen, "%s", slash ? slash + 1 : p);
  }
  sb_collide_free(c);
  return st ? -1 : 0;
}

/* CSV field with quotes doubled */
static void csv_quoted(char *dst, size_t len, const char *s)
{
  size_t k = 0;
  if (len < 3)
    return;
  dst[k++] = '"';
  for (; *s && k + 3 < len; s++) {
    if (*s == '"')
      dst[k++] = '"';
    dst[k++] = *s;
  }
  dst[k++] = '"';
  dst[k] = '\0';
}

#define SWEEP_HEADER "point,status,particles,steps,collisions,kind,K,K_lo," \
                     "K_hi,pairs,overrides,message"

/* K, K_lo, K_hi of a row: empty for a first-contact mixture, which has
 * one kernel per species pair (the pairs column) and no single one. */
static void kernel_cells(const col_point *res, char *buf, size_t len)
{
  if (res->mixture && !strcmp(res->kind, "first-hit"))
    snprintf(buf, len, ",,");
  else
    snprintf(buf, len, "%.10g,%.10g,%.10g", res->K, res->lo, res->hi);
}

/* One point: run it and format its summary row.  A checkpoint of the
 * base configuration (file name ck) is written into the point's
 * directory, unless the line gives the point's own: every point would
 * write the same file otherwise. */
static int run_point(const char *ini, const char *const *sets, int nsets,
                     const char *base, const char *ck, size_t k,
                     const char *line, char *row, size_t rlen,
                     col_point *res)
{
  char *words = malloc(strlen(line) + 1);
  const char *all[2 * SW_MAXSET + 3];
  char outset[1200], ckset[1800];
  int n = 0, rc;
  if (!words)
    return -1;
  strcpy(words, line);
  for (int i = 0; i < nsets; i++)
    all[n++] = sets[i];
  int nline = 0;
  for (char *tok = strtok(words, " \t"); tok; tok = strtok(NULL, " \t")) {
    if (++nline > SW_MAXSET)
      break;
    all[n++] = tok;
  }
  snprintf(outset, sizeof outset, "run.output=%s/point_%03zu", base, k);
  all[n++] = outset;
  if (ck[0] && !strstr(line, "run.checkpoint=")) {
    snprintf(ckset, sizeof ckset, "run.checkpoint=%s/point_%03zu/%s", base,
             k, ck);
    all[n++] = ckset;
  }
  if (nline > SW_MAXSET) {
    memset(res, 0, sizeof *res);
    res->K = res->lo = res->hi = NAN;
    snprintf(res->status, sizeof res->status, "input error");
    snprintf(res->why, sizeof res->why, "more than %d overrides on one "
             "line", SW_MAXSET);
    rc = 2;
  } else
    rc = col_run_point(ini, all, n, 0, res);
  free(words);
  char ov[2400], why[2300], pairs[1600], kc[80];
  csv_quoted(ov, sizeof ov, line);
  csv_quoted(why, sizeof why, strcmp(res->status, "ok") ? res->why : "");
  csv_quoted(pairs, sizeof pairs, res->mixture ? res->pairs : "");
  kernel_cells(res, kc, sizeof kc);
  snprintf(row, rlen, "%zu,%s,%zu,%llu,%llu,%s,%s,%s,%s,%s", k,
           res->status, res->particles, res->steps, res->ncoll,
           res->kind[0] ? res->kind : "none", kc, pairs, ov, why);
  return rc;
}

int col_sweep(const char *ini, const char *const *sets, int nsets,
              const char *file)
{
  const int rank = sbc_par_rank(), P = sbc_par_size();
  sw_points pts = {NULL, 0, 0};
  char err[1200] = "", base[600], ck[600] = "";
  /* every rank reads the same files: the same error on each */
  if (read_points(file, &pts, err, sizeof err) ||
      base_output(ini, sets, nsets, base, sizeof base, ck, sizeof ck, err,
                  sizeof err)) {
    if (rank == 0)
      fprintf(stderr, "collide: %s\n", err);
    points_free(&pts);
    return 2;
  }
  if (rank == 0) {
    if (mkdir(base, 0777) != 0 && errno != EEXIST)
      fprintf(stderr, "collide: warning: cannot create %s/: %s\n", base,
              strerror(errno));
    fprintf(stderr, "collide --sweep %s: %zu points -> %s/point_NNN/, "
            "summary %s/sweep.csv%s\n", file, pts.n, base, base,
            P > 1 ? " (points shared by the ranks; progress of rank 0)"
                  : "");
  }
  /* this rank's rows, each behind {point, length} */
  unsigned char *mine = NULL;
  size_t nmine = 0, cap = 0;
  int bad = 0, worst = 0;
  for (size_t k = (size_t)rank; k < pts.n && !bad; k += (size_t)P) {
    char row[8192];
    col_point res;
    int rc = run_point(ini, sets, nsets, base, ck, k, pts.line[k], row,
                       sizeof row, &res);
    if (rc < 0) {
      bad = 1;
      break;
    }
    if (rc > worst)
      worst = rc;
    if (rank == 0 && res.mixture && !strcmp(res.kind, "first-hit"))
      fprintf(stderr, "[point %zu/%zu] %s: %s, per species pair K = %s%s\n",
              k + 1, pts.n, pts.line[k], res.status, res.pairs,
              sbc_par_tag());
    else if (rank == 0)
      fprintf(stderr, "[point %zu/%zu] %s: %s, K = %.6g [%.6g, %.6g]%s%s%s\n",
              k + 1, pts.n, pts.line[k], res.status, res.K, res.lo, res.hi,
              res.mixture ? "; per species pair " : "",
              res.mixture ? res.pairs : "", sbc_par_tag());
    uint64_t hdr[2] = {k, strlen(row)};
    size_t need = nmine + sizeof hdr + hdr[1];
    if (need > cap) {
      size_t nc = cap ? 2 * cap : 8192;
      while (nc < need)
        nc *= 2;
      unsigned char *q = realloc(mine, nc);
      if (!q) {
        bad = 1;
        break;
      }
      mine = q;
      cap = nc;
    }
    memcpy(mine + nmine, hdr, sizeof hdr);
    memcpy(mine + nmine + sizeof hdr, row, hdr[1]);
    nmine = need;
  }
  bad = sbc_par_max_int(bad);
  worst = sbc_par_max_int(worst);
  unsigned char *all = NULL;
  size_t *lens = NULL;
  if (!bad && sbc_par_gather(mine, nmine, &all, &lens))
    bad = 1;
  free(mine);
  int rc = bad ? 2 : (worst ? 1 : 0);
  if (rank == 0 && !bad) {
    size_t total = 0;
    for (int r = 0; r < P; r++)
      total += lens[r];
    const char **row = calloc(pts.n, sizeof *row);
    size_t *rl = calloc(pts.n, sizeof *rl);
    for (size_t off = 0; row && rl && off < total;) {
      uint64_t hdr[2];
      memcpy(hdr, all + off, sizeof hdr);
      if (hdr[0] >= pts.n || hdr[1] > total - off - sizeof hdr)
        break;
      row[hdr[0]] = (const char *)all + off + sizeof hdr;
      rl[hdr[0]] = (size_t)hdr[1];
      off += sizeof hdr + (size_t)hdr[1];
    }
    char path[700];
    snprintf(path, sizeof path, "%s/sweep.csv", base);
    FILE *f = fopen(path, "w");
    if (!f || !row || !rl)
      rc = 1;
    else {
      fprintf(f, "%s\n", SWEEP_HEADER);
      printf("%s\n", SWEEP_HEADER);
      for (size_t k = 0; k < pts.n; k++) {
        if (!row[k]) {
          rc = 1;
          continue;
        }
        fprintf(f, "%.*s\n", (int)rl[k], row[k]);
        printf("%.*s\n", (int)rl[k], row[k]);
      }
      if (fclose(f) != 0)
        rc = 1;
    }
    if (rc == 1 && (!row || !rl || !f))
      fprintf(stderr, "collide: could not write %s\n", path);
    free(row);
    free(rl);
    fprintf(stderr, "collide --sweep: %zu points, summary in %s\n", pts.n,
            path);
  } else if (bad && rank == 0)
    fprintf(stderr, "collide --sweep: out of memory or MPI failure\n");
  free(all);
  free(lens);
  points_free(&pts);
  return rc;
}
