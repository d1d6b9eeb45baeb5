/* collide_firsthit.c — [observe] first_hit: the first-contact observer of
 * the library (<smolbridge/engine_firsthit.h>) around the run's detector,
 * with outcome = count, so that the pairs are independent two-body
 * problems and the count has the Smoluchowski (1917) reference
 * (docs/engine_bridge.md §7).  The validation cases use the same
 * observer, so a case's file reproduces its count. */
#include <math.h>
#include <string.h>

#include <smolbridge/engine.h>
#include <smolbridge/engine_bridge.h>
#include <smolbridge/engine_firsthit.h>

#include "collide_internal.h"

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
  } else
    fp.builtin = builtin == SB_DETECT_OVERLAP || builtin == SB_DETECT_LANGEVIN
                     ? builtin
                     : SB_DETECT_BALLISTIC;
  fp.skip_seen = c->first_hit_skip_seen > 0;
  r->fh = sb_engine_firsthit_alloc(&fp);
  if (!r->fh)
    return SB_ENOMEM;
  return sb_engine_firsthit_attach(r->e, r->fh, reach);
}

void sbi_col_firsthit_free(sb_engine_firsthit *f)
{
  sb_engine_firsthit_free(f);
}

/* The kernel with the reference radius first_hit_radius (default: the
 * contact distance) or the capacitance radius, and D = b2 (NaN for free
 * flight: no estimate). */
int sbi_col_firsthit_result(const sbi_col_run *r, const sbi_col_config *c,
                            sb_engine_firsthit_kernel_result *o)
{
  memset(o, 0, sizeof *o);
  if (!r->fh)
    return -1;
  const sb_engine_species *s = sb_engine_get_species(r->e, 0);
  double b2 = isfinite(s->tau) ? c->b2_total[0] : NAN;
  double a = c->first_hit_capacitance > 0 ? SB_ENGINE_FIRSTHIT_CAPACITANCE
             : c->first_hit_radius > 0    ? c->first_hit_radius
                                          : 2.0 * s->radius;
  return sb_engine_firsthit_kernel(r->fh, r->e, 0, 0, a, b2, 0.95, o);
}
