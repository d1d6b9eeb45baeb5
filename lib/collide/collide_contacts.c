/* collide_contacts.c — [observe] first_hit_velocities: the normal
 * relative velocity v_n = (u_i - u_j).(x_i - x_j)/|x_i - x_j| of the
 * first N counted first contacts (contacts.csv; v_n < 0: approach), the
 * law of the impact velocities (Mohaupt 2011, §7.2.1: in the
 * free-molecular limit |v_n| follows the flux-weighted Maxwellian of
 * variance k_B T/m_red).  With `langevin` the observer's on_hit reads the
 * states at the contact the built-in drew (sb_engine_contact_state: the
 * conditional law at the contact time); with `ballistic` the observer
 * wraps a detector that also gives the velocities at the contact (the
 * chord's contact point, the velocities interpolated linearly over the
 * step). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include <smolbridge/engine.h>
#include <smolbridge/engine_firsthit.h>

#include "collide_internal.h"

struct sbi_col_contacts {
  sb_engine_detect builtin;   /* SB_DETECT_LANGEVIN or _BALLISTIC */
  double vn;                  /* of the contact just detected (NaN: none) */
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

/* The detector the observer wraps (`ballistic`): the built-in, with the
 * velocity. */
static int detect(const sb_engine *e, const sb_engine_pair *p,
                  const gsl_rng *r, void *ctx, double *s)
{
  (void)r;
  sbi_col_contacts *k = ctx;
  k->vn = NAN;
  const int h = sb_engine_detect_ballistic(p, s);
  if (h == 1)
    k->vn = sb_engine_chord_vn(e, p, *s);
  return h;
}

/* A counted first contact: keep its velocity (the first cap). */
static int on_hit(const sb_engine *e, const sb_engine_pair *p, double s,
                  void *ctx)
{
  sbi_col_contacts *k = ctx;
  if (k->builtin == SB_DETECT_LANGEVIN) {  /* the built-in's draw */
    double xi[3], ui[3], xj[3], uj[3];
    if (sb_engine_contact_state(e, xi, ui, xj, uj))
      return -1;
    double vn = 0.0;
    for (int q = 0; q < 3; q++)
      vn += (ui[q] - uj[q]) * (xi[q] - xj[q]) / p->sigma;
    k->vn = vn;
  }
  if (isnan(k->vn) || k->n >= k->cap)
    return 0;
  const size_t *sp = sb_engine_species_of(e);
  k->t[k->n] = p->t0 + s * p->dt;
  k->v[k->n] = k->vn;
  k->a[k->n] = sp[p->i];
  k->b[k->n] = sp[p->j];
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
  if (builtin != SB_DETECT_LANGEVIN) {
    fp->detect = detect;
    fp->detect_ctx = k;
  }
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
