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

/* One recorded contact; lo, hi (the pair's ids) order a step's contacts. */
typedef struct {
  double t, v;       /* contact time, v_n */
  size_t a, b;       /* species, a <= b */
  uint64_t lo, hi;   /* the pair's ids, lo < hi */
} contact;

struct sbi_col_contacts {
  sb_engine_detect builtin;   /* SB_DETECT_LANGEVIN or _BALLISTIC */
  size_t cap;                 /* first_hit_velocities */
  size_t kept;                /* contacts of the steps before, <= cap */
  size_t n, alloc;            /* kept + this step's so far; allocated */
  contact *c;
};

void sbi_col_contacts_free(sbi_col_contacts *k)
{
  if (!k)
    return;
  free(k->c);
  free(k);
}

/* A counted first contact: kept while the steps before hold fewer than
 * cap (the step that reaches cap keeps all of its own until its end). */
static int on_hit(const sb_engine *e, const sb_engine_pair *p, double s,
                  void *ctx)
{
  sbi_col_contacts *k = ctx;
  if (k->kept >= k->cap)
    return 0;
  const double vn = k->builtin == SB_DETECT_LANGEVIN
                        ? sb_engine_contact_vn(e)  /* the built-in's draw */
                        : sb_engine_chord_vn(e, p, s);
  if (isnan(vn))
    return -1;
  if (k->n == k->alloc) {
    const size_t na = 2 * k->alloc;
    contact *c = realloc(k->c, na * sizeof *c);
    if (!c) {
      sbi_error(SB_ENOMEM, "first_hit_velocities",
                "out of memory for %zu contacts", na);
      return -1;
    }
    k->c = c;
    k->alloc = na;
  }
  const size_t *sp = sb_engine_species_of(e);
  const uint64_t *id = sb_engine_ids(e);
  /* the pair's species and ids in increasing order (not the slots',
   * which follow the order in memory) */
  const size_t a = sp[p->i], b = sp[p->j];
  const uint64_t u = id[p->i], w = id[p->j];
  k->c[k->n++] = (contact){.t = p->t0 + s * p->dt, .v = vn,
                           .a = a < b ? a : b, .b = a < b ? b : a,
                           .lo = u < w ? u : w, .hi = u < w ? w : u};
  return 0;
}

/* Contact time first, then the ids: an order that does not depend on the
 * order of the particles in memory or on the threads. */
static int by_time_ids(const void *x, const void *y)
{
  const contact *c = x, *d = y;
  if (c->t != d->t)
    return c->t < d->t ? -1 : 1;
  if (c->lo != d->lo)
    return c->lo < d->lo ? -1 : 1;
  return (c->hi > d->hi) - (c->hi < d->hi);
}

void sbi_col_contacts_step_end(sbi_col_run *r)
{
  sbi_col_contacts *k = r->contacts;
  if (!k || k->n == k->kept)
    return;
  qsort(k->c + k->kept, k->n - k->kept, sizeof *k->c, by_time_ids);
  if (k->n > k->cap)
    k->n = k->cap;
  k->kept = k->n;
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
  k->alloc = k->cap < 1024 ? k->cap : 1024;  /* grows as contacts come */
  k->c = malloc(k->alloc * sizeof *k->c);
  if (!k->c)
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
  char na[32], nb[32];
  for (size_t i = 0; i < k->n; i++)
    fprintf(f, "%.17g,%s,%s,%.17g\n", k->c[i].t,
            sbi_col_species_label(c, r->agglo, k->c[i].a, na, sizeof na),
            sbi_col_species_label(c, r->agglo, k->c[i].b, nb, sizeof nb),
            k->c[i].v);
  fprintf(js, "  \"contacts\": {\"recorded\": %zu, \"cap\": %zu, "
          "\"file\": \"contacts.csv\"},\n", k->n, k->cap);
  return fclose(f) ? -1 : 0;
}

/* Beside a checkpoint (collide_beside.c), at the end of a step: "SBCCON02",
 * the recorded count n, then the n times, the n velocities and the n
 * species of each side (native binary: doubles and size_t), then the
 * FNV-1a hash of every byte before it (common/internal.h,
 * sbi_hsave_finish), checked before anything is read.  Version 01, the
 * same without the hash, still loads. */
static const char MAGIC[8] = {'S', 'B', 'C', 'C', 'O', 'N', '0', '2'};

int sbi_col_contacts_save(const sbi_col_run *r, const char *path)
{
  const sbi_col_contacts *k = r->contacts;
  sbi_hsave hs;
  FILE *f = sbi_hsave_begin(&hs, "checkpoint");
  if (!f)
    return SB_ENOMEM;
  const uint64_t n = k->n;
  int ok = fwrite(MAGIC, 1, 8, f) == 8 && fwrite(&n, sizeof n, 1, f) == 1;
  for (size_t i = 0; ok && i < k->n; i++)
    ok = fwrite(&k->c[i].t, sizeof k->c[i].t, 1, f) == 1;
  for (size_t i = 0; ok && i < k->n; i++)
    ok = fwrite(&k->c[i].v, sizeof k->c[i].v, 1, f) == 1;
  for (size_t i = 0; ok && i < k->n; i++)
    ok = fwrite(&k->c[i].a, sizeof k->c[i].a, 1, f) == 1;
  for (size_t i = 0; ok && i < k->n; i++)
    ok = fwrite(&k->c[i].b, sizeof k->c[i].b, 1, f) == 1;
  return sbi_hsave_finish(&hs, ok, path, "checkpoint");
}

int sbi_col_contacts_load(sbi_col_run *r, const char *path)
{
  sbi_col_contacts *k = r->contacts;
  int st, ver;
  char *mem;
  FILE *f = sbi_hload_open(path, MAGIC, 2, "file of contacts", &ver, &mem,
                           "restart", &st);
  if (!f)
    return st;
  char mg[8];
  uint64_t n;
  const char *why = "truncated, or data after the end";
  st = SB_EFORMAT;
  if (fread(mg, 1, 8, f) != 8)
    why = "not a file of contacts";
  else if (fread(&n, sizeof n, 1, f) == 1) {
    contact *c = NULL;
    if (n > k->cap)
      st = SB_EINVAL, why = "it holds more contacts than "
                            "first_hit_velocities allows";
    else if (!(c = n > k->alloc ? realloc(k->c, n * sizeof *c) : k->c))
      st = SB_ENOMEM, why = "out of memory";
    else {
      k->c = c;
      k->alloc = n > k->alloc ? n : k->alloc;
      int ok = 1;
      for (size_t i = 0; ok && i < n; i++)
        ok = fread(&c[i].t, sizeof c[i].t, 1, f) == 1;
      for (size_t i = 0; ok && i < n; i++)
        ok = fread(&c[i].v, sizeof c[i].v, 1, f) == 1;
      for (size_t i = 0; ok && i < n; i++)
        ok = fread(&c[i].a, sizeof c[i].a, 1, f) == 1;
      for (size_t i = 0; ok && i < n; i++)
        ok = fread(&c[i].b, sizeof c[i].b, 1, f) == 1;
      if (ok && fgetc(f) == EOF) {
        k->n = k->kept = (size_t)n;
        st = SB_SUCCESS;
      }
    }
  }
  fclose(f);
  free(mem);
  return st ? sbi_error(st, "restart", "'%s': %s", path, why) : SB_SUCCESS;
}
