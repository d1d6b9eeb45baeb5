/* engine_detect_md.c — two fixed custom detectors: the MD-type detector
 * of molecular dynamics
 * (Mohaupt 2011, §3.1.2, §3.2, App. F): the contact time of the straight
 * motion x + u dt with the velocities at the start of the step, instead
 * of the actual displacement.  Right in the ballistic regime (dt << tau_p,
 * where the path is straight); the thesis shows it overestimating the
 * kernel in the diffusive regime (validation case V3/diffusive-fail);
 * and the detector that never reports a contact. */
#include <smolbridge/engine.h>

#include "common/internal.h"

int sb_engine_detect_md(const sb_engine *e, const sb_engine_pair *p,
                        const gsl_rng *r, void *ctx, double *s)
{
  (void)r;
  (void)ctx;
  if (!e || !p || !s) {
    sbi_error(SB_EINVAL, __func__, "NULL argument");
    return -1;
  }
  const double *u0 = sb_engine_start_velocities(e);
  if (!u0 || p->i >= sb_engine_count(e) || p->j >= sb_engine_count(e)) {
    sbi_error(SB_EINVAL, __func__, "no start velocities or pair (%zu, %zu) "
              "out of range", p->i, p->j);
    return -1;
  }
  sb_engine_pair q = *p;
  for (int k = 0; k < 3; k++)
    q.dd[k] = (u0[3 * p->i + k] - u0[3 * p->j + k]) * p->dt;
  return sb_engine_detect_ballistic(&q, s);
}

int sb_engine_detect_none(const sb_engine *e, const sb_engine_pair *p,
                          const gsl_rng *r, void *ctx, double *s)
{
  (void)r;
  (void)ctx;
  if (!e || !p || !s) {
    sbi_error(SB_EINVAL, __func__, "NULL argument");
    return -1;
  }
  return 0;
}
