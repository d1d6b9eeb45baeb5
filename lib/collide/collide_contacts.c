/* collide_contacts.c — [observe] first_hit_velocities: the normal
 * relative velocity v_n = (u_i - u_j).(x_i - x_j)/|x_i - x_j| of the
 * first N counted first contacts (contacts.csv; v_n < 0: approach), the
 * law of the impact velocities (Mohaupt 2011, §7.2.1: in the
 * free-molecular limit |v_n| follows the flux-weighted Maxwellian of
 * variance k_B T/m_red).  The first-contact observer then wraps a
 * detector that also gives the velocities at the contact: `langevin`
 * (sb_engine_langevin_contact, the conditional law at the contact time:
 * the same draws as the built-in) or `ballistic` (the chord's contact
 * point, the velocities interpolated linearly over the step). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include <smolbridge/engine.h>
#include <smolbridge/engine_firsthit.h>
#include <smolbridge/langevin.h>

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

/* The detector the observer wraps: the built-in, with the velocity. */
static int detect(const sb_engine *e, const sb_engine_pair *p,
                  const gsl_rng *r, void *ctx, double *s)
{
  sbi_col_contacts *k = ctx;
  int h;
  k->vn = NAN;
  if (k->builtin == SB_DETECT_LANGEVIN) {
    sb_langevin_contact c;
    h = sb_engine_langevin_contact(e, p, r, s, &c);
    if (h == 1) {
      double vn = 0.0;
      for (int q = 0; q < 3; q++)
        vn += (c.ui[q] - c.uj[q]) * (c.xi[q] - c.xj[q]) / p->sigma;
      k->vn = vn;
    }
  } else {
    h = sb_engine_detect_ballistic(p, s);
    if (h == 1)
      k->vn = sb_engine_chord_vn(e, p, *s);
  }
  return h;
}

/* A counted first contact: keep its velocity (the first cap). */
static int on_hit(const sb_engine *e, const sb_engine_pair *p, double s,
                  void *ctx)
{
  sbi_col_contacts *k = ctx;
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
  fp->detect = detect;
  fp->detect_ctx = k;
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
