/* collide_contacts.c — [observe] first_hit_velocities: the normal
 * relative velocity v_n = (u_i - u_j).(x_i - x_j)/|x_i - x_j| of the
 * first N counted first contacts (contacts.csv; v_n < 0: approach), the
 * law of the impact velocities (Mohaupt 2011, §7.2.1: in the
 * free-molecular limit |v_n| follows the flux-weighted Maxwellian of
 * variance k_B T/m_red).  The observer's on_hit reads them from the
 * built-in it watches: with `langevin` the states at the contact the
 * built-in drew (sb_engine_contact_state: the conditional law at the
 * contact time), with `ballistic` the chord's contact point and the
 * velocities interpolated linearly over the step (sb_engine_chord_vn). */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <smolbridge/engine.h>
#include <smolbridge/engine_firsthit.h>

#include "collide_internal.h"
#include "common/internal.h"

struct sbi_col_contacts {
  sb_engine_detect builtin;   /* SB_DETECT_LANGEVIN or _BALLISTIC */
  size_t cap, n;
  double *t, *v;              /* contact time, v_n */
  size_t *a, *b;              /* species */
};

void sbi_col_contacts_free(sbi_col_contacts *k)
{
  if (!k)
    return;
  free(k->t);
  free(k->v);
  free(k->a);
  free(k->b);
  free(k);
}

/* A counted first contact: keep its velocity (the first cap). */
static int on_hit(const sb_engine *e, const sb_engine_pair *p, double s,
                  void *ctx)
{
  sbi_col_contacts *k = ctx;
  if (k->n >= k->cap)
    return 0;
  const double vn = k->builtin == SB_DETECT_LANGEVIN
                        ? sb_engine_contact_vn(e)  /* the built-in's draw */
                        : sb_engine_chord_vn(e, p, s);
  if (isnan(vn))
    return -1;
  const size_t *sp = sb_engine_species_of(e);
  k->t[k->n] = p->t0 + s * p->dt;
  k->v[k->n] = vn;
  /* the pair's species in increasing order (not the slots', which
   * follow the order in memory) */
  const size_t a = sp[p->i], b = sp[p->j];
  k->a[k->n] = a < b ? a : b;
  k->b[k->n] = a < b ? b : a;
  k->n++;
  return 0;
}

int sbi_col_contacts_setup(const sbi_col_config *c, sbi_col_run *r,
                           sb_engine_detect builtin,
                           sb_engine_firsthit_params *fp)
{
  if (c->first_hit_vn <= 0)
    return SB_SUCCESS;
  sbi_col_contacts *k = calloc(1, sizeof *k);
  if (!k)
    return SB_ENOMEM;
  r->contacts = k;
  k->builtin = builtin;
  k->cap = (size_t)c->first_hit_vn;
  k->t = malloc(k->cap * sizeof *k->t);
  k->v = malloc(k->cap * sizeof *k->v);
  k->a = malloc(k->cap * sizeof *k->a);
  k->b = malloc(k->cap * sizeof *k->b);
  if (!k->t || !k->v || !k->a || !k->b)
    return SB_ENOMEM;
  fp->on_hit = on_hit;
  fp->hit_ctx = k;
  return SB_SUCCESS;
}

int sbi_col_contacts_write(FILE *js, const sbi_col_config *c,
                           const sbi_col_run *r, const char *path)
{
  const sbi_col_contacts *k = r->contacts;
  if (!k)
    return 0;
  FILE *f = fopen(path, "w");
  if (!f)
    return -1;
  fprintf(f, "t,a,b,vn\n");
  for (size_t i = 0; i < k->n; i++)
    fprintf(f, "%.17g,%s,%s,%.17g\n", k->t[i],
            sbi_col_short_name(c, k->a[i]), sbi_col_short_name(c, k->b[i]),
            k->v[i]);
  fprintf(js, "  \"contacts\": {\"recorded\": %zu, \"cap\": %zu, "
          "\"file\": \"contacts.csv\"},\n", k->n, k->cap);
  return fclose(f) ? -1 : 0;
}

/* Beside a checkpoint (collide_beside.c): "SBCCON01", the recorded count,
 * then the times, velocities and both species of each (native binary;
 * nothing after). */
static const char MAGIC[8] = {'S', 'B', 'C', 'C', 'O', 'N', '0', '1'};

int sbi_col_contacts_save(const sbi_col_run *r, const char *path)
{
  const sbi_col_contacts *k = r->contacts;
  FILE *f = fopen(path, "wb");
  if (!f)
    return sbi_error(SB_EIO, "checkpoint", "cannot open '%s' for writing",
                     path);
  const uint64_t n = k->n;
  int ok = fwrite(MAGIC, 1, 8, f) == 8 && fwrite(&n, sizeof n, 1, f) == 1 &&
           fwrite(k->t, sizeof *k->t, n, f) == n &&
           fwrite(k->v, sizeof *k->v, n, f) == n &&
           fwrite(k->a, sizeof *k->a, n, f) == n &&
           fwrite(k->b, sizeof *k->b, n, f) == n;
  ok &= fclose(f) == 0;
  if (ok)
    return SB_SUCCESS;
  remove(path);
  return sbi_error(SB_EIO, "checkpoint", "write error on '%s'", path);
}

int sbi_col_contacts_load(sbi_col_run *r, const char *path)
{
  sbi_col_contacts *k = r->contacts;
  FILE *f = fopen(path, "rb");
  if (!f)
    return sbi_error(SB_EIO, "restart", "cannot open '%s'", path);
  char mg[8];
  uint64_t n;
  const char *why = "truncated, or data after the end";
  int st = SB_EFORMAT;
  if (fread(mg, 1, 8, f) != 8 || memcmp(mg, MAGIC, 8))
    why = "not a file of contacts";
  else if (fread(&n, sizeof n, 1, f) == 1) {
    if (n > k->cap)
      st = SB_EINVAL, why = "it holds more contacts than "
                            "first_hit_velocities allows";
    else if (fread(k->t, sizeof *k->t, n, f) == n &&
             fread(k->v, sizeof *k->v, n, f) == n &&
             fread(k->a, sizeof *k->a, n, f) == n &&
             fread(k->b, sizeof *k->b, n, f) == n && fgetc(f) == EOF) {
      k->n = (size_t)n;
      st = SB_SUCCESS;
    }
  }
  fclose(f);
  return st ? sbi_error(st, "restart", "'%s': %s", path, why) : SB_SUCCESS;
}
