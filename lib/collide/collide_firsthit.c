/* collide_firsthit.c — [observe] first_hit: the first-contact observer of
 * the library (<smolbridge/engine_firsthit.h>) around the run's detector,
 * with outcome = count, so that the pairs are independent two-body
 * problems and the count has the Smoluchowski (1917) reference
 * (docs/engine_bridge.md §7).  The validation cases use the same
 * observer, so a case's file reproduces its count.  With a checkpoint the
 * observer's state is saved beside it (CHECKPOINT.firsthit), and a
 * restart loads it, so the count goes on as if the run had not stopped. */
#include <math.h>
#include <string.h>

#include <smolbridge/engine.h>
#include <smolbridge/engine_bridge.h>
#include <smolbridge/engine_firsthit.h>

#include "collide_internal.h"

/* every species pair of a run has its counts in the observer */
_Static_assert(COL_MAXSPEC <= SB_ENGINE_PAIR_SPECIES,
               "more collide species than the observer's pair table");

void sbi_col_firsthit_start(sbi_col_run *r, double t1)
{
  if (r->fh)
    sb_engine_firsthit_set_warmup(r->fh, t1);
}

/* Install the counting observer around the run's detector (the bridge
 * context r->bridge, or the built-in one). */
int sbi_col_firsthit_attach(const sbi_col_config *c, sbi_col_run *r,
                            sb_engine_detect builtin, double reach)
{
  sb_engine_firsthit_params fp;
  sb_engine_firsthit_params_default(&fp);
  if (r->bridge) {
    fp.detect = sb_engine_detect_bridge;
    fp.detect_ctx = r->bridge;
  } else if (sbi_col_md(c))
    fp.detect = sb_engine_detect_md;
  else
    fp.builtin = builtin == SB_DETECT_OVERLAP || builtin == SB_DETECT_LANGEVIN
                     ? builtin
                     : SB_DETECT_BALLISTIC;
  fp.skip_seen = c->first_hit_skip_seen > 0;
  /* [observe] first_hit_velocities: the built-in with the velocities */
  if (!r->bridge && sbi_col_contacts_setup(c, r, fp.builtin, &fp))
    return SB_ENOMEM;
  r->fh = sb_engine_firsthit_alloc(&fp);
  if (!r->fh)
    return SB_ENOMEM;
  if (c->restart[0]) {  /* the count goes on from the checkpoint's */
    char path[600];
    int st = sbi_col_restart_beside(c, SBI_BESIDE_COUNTS,
                                    "the pairs counted before it",
                                    path, sizeof path);
    if (!st)
      st = sb_engine_firsthit_load(r->fh, path);
    if (!st && r->contacts) {
      st = sbi_col_restart_beside(c, SBI_BESIDE_CONTACTS,
                                  "the contacts recorded before it", path,
                                  sizeof path);
      if (!st)
        st = sbi_col_contacts_load(r, path);
    }
    if (st)
      return st;
  }
  return sb_engine_firsthit_attach(r->e, r->fh, reach);
}

void sbi_col_firsthit_free(sb_engine_firsthit *f)
{
  sb_engine_firsthit_free(f);
}

/* The kernel of species pair (a, b) with the reference radius
 * first_hit_radius (one species only), the contact distance r_a + r_b
 * (default) or the capacitance radius, and the relative diffusivity
 * D_ab = D_a + D_b = (b2_a + b2_b) / 2, b2 the per-particle position
 * variance rate 2 D (NaN with a species in free flight: no estimate). */
int sbi_col_firsthit_pair(const sbi_col_run *r, const sbi_col_config *c,
                          size_t a, size_t b,
                          sb_engine_firsthit_kernel_result *o)
{
  memset(o, 0, sizeof *o);
  o->K = o->lo = o->hi = o->a = o->D = NAN;
  if (!r->fh)
    return -1;
  const sb_engine_species *sa = sb_engine_get_species(r->e, a);
  const sb_engine_species *sb = sb_engine_get_species(r->e, b);
  if (!sa || !sb)
    return SB_EINVAL;
  double D = NAN;
  if (isfinite(sa->tau) && isfinite(sb->tau))
    D = a == b ? c->b2_total[a] : 0.5 * (c->b2_total[a] + c->b2_total[b]);
  double rad = c->first_hit_capacitance > 0 ? SB_ENGINE_FIRSTHIT_CAPACITANCE
               : c->first_hit_radius > 0    ? c->first_hit_radius
                                            : sa->radius + sb->radius;
  return sb_engine_firsthit_kernel(r->fh, r->e, a, b, rad, D, 0.95, o);
}

/* One species: the kernel of its pair.  Several: the counts over all
 * pairs (K, its interval, radius and D NaN: one kernel per pair type,
 * sbi_col_firsthit_pair), SB_EDOM. */
int sbi_col_firsthit_result(const sbi_col_run *r, const sbi_col_config *c,
                            sb_engine_firsthit_kernel_result *o)
{
  memset(o, 0, sizeof *o);
  if (!r->fh)
    return -1;
  if (c->nsp == 1)
    return sbi_col_firsthit_pair(r, c, 0, 0, o);
  o->K = o->lo = o->hi = o->a = o->D = o->expected_per_K = NAN;
  o->radius = NAN;
  o->t1 = sb_engine_firsthit_warmup(r->fh);
  o->t = sb_engine_time(r->e);
  int st = sb_engine_firsthit_get(r->fh, SB_ENGINE_FIRSTHIT_ALL,
                                  SB_ENGINE_FIRSTHIT_ALL, &o->c);
  return st ? st : SB_EDOM;
}
