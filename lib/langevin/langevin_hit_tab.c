/* langevin_hit_tab.c — bridge coefficients of the pair sampler, cached per
 * (tau, B, dt) and refinement level.
 *
 * The conditional mean of a Langevin bridge is affine in the end states
 * and the fluid velocity, with coefficients that depend on (tau, h, s)
 * only (the gain K = Sigma_s Phi^T Sigma_h^{-1} does not depend on B);
 * the conditional covariance depends on (tau, B, h, s).  Both come from
 * the gain of sb_langevin_bridge_moments, in one pass (sbi_lh_bridge_coef:
 * its coefficients are that function's mean at unit end states).  A sub-interval at depth d of a step dt has length
 * dt / 2^d wherever it lies (time-homogeneous Markov process), so one
 * table per level serves every sub-interval of that level.
 *
 * Processes without noise (tau = inf: free flight; B = 0: deterministic
 * relaxation to us) have the unconditioned mean from the start state and
 * zero covariance. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_sf_exp.h>
#include <smolbridge/langevin.h>

#include "common/internal.h"
#include "langevin_hit_internal.h"

static int det_coef(double tau, double s, sbi_lh_coef *c)
{
  memset(c, 0, sizeof *c);
  if (isinf(tau)) {
    c->bx = s;
    c->bu = 1.0;
    return SB_SUCCESS;
  }
  double x = s / tau, e = exp(-x);
  c->bx = -tau * expm1(-x);
  /* s - tau (1 - e) = tau (x + expm1(-x)) = tau x^2 exprel_2(-x) / 2,
   * free of cancellation for small x */
  c->wx = 0.5 * tau * x * x * gsl_sf_exprel_2(-x);
  c->bu = e;
  c->wu = -expm1(-x);
  return SB_SUCCESS;
}

int sbi_lh_coef_at(double tau, double B, double h, double s, sbi_lh_coef *c)
{
  if (isinf(tau) || B == 0.0)
    return det_coef(tau, s, c);
  memset(c, 0, sizeof *c);
  if (s <= 0.0 || s >= h) {  /* an end: its state, no spread */
    if (s >= h) {
      c->ax = 1.0;
      c->cu = 1.0;
    } else
      c->bu = 1.0;
    return SB_SUCCESS;
  }
  return sbi_lh_bridge_coef(tau, B, h, s, c);
}

sbi_lh_slot *sbi_lh_slot_get(sb_langevin_hitter *w, double tau, double B,
                             double htop)
{
  if (isinf(tau))
    B = 0.0;
  w->clock++;
  sbi_lh_slot *old = &w->slot[0];
  for (int k = 0; k < SBI_LH_NSLOT; k++) {
    sbi_lh_slot *s = &w->slot[k];
    if (s->used && s->tau == tau && s->B == B && s->htop == htop) {
      s->stamp = w->clock;
      return s;
    }
    if (!s->used || s->stamp < old->stamp)
      old = s;
  }
  /* recycle the least recently used slot: keep its memory, drop its
   * contents */
  old->used = 1;
  old->tau = tau;
  old->B = B;
  old->htop = htop;
  old->det = isinf(tau) || B == 0.0;
  old->stamp = w->clock;
  for (int d = 0; d <= SBI_LH_MAXDEPTH; d++)
    if (old->lev[d])
      old->lev[d]->valid = 0;
  return old;
}

const sbi_lh_level *sbi_lh_level_get(sb_langevin_hitter *w, sbi_lh_slot *s,
                                     unsigned d)
{
  if (d > SBI_LH_MAXDEPTH)
    return NULL;
  sbi_lh_level *L = s->lev[d];
  if (L && L->valid)
    return L;
  if (!L) {
    L = malloc(sizeof *L);
    if (!L) {
      sbi_error(SB_ENOMEM, "sb_langevin_hitter_sample", "out of memory");
      return NULL;
    }
    s->lev[d] = L;
  }
  const double h = ldexp(s->htop, -(int)d);
  L->h = h;
  for (int k = 0; k < SBI_LH_NQ; k++)
    if (sbi_lh_coef_at(s->tau, s->B, h, w->xi[k] * h, &L->q[k]))
      return NULL;
  if (sbi_lh_coef_at(s->tau, s->B, h, 0.5 * h, &L->mid))
    return NULL;
  L->ka = L->kb = L->kc = L->kw = L->vxmax = 0.0;
  L->kau = L->kbu = L->kcu = L->kwu = L->vumax = 0.0;
  for (int k = 0; k < SBI_LH_NQ; k++) {
    const sbi_lh_coef *q = &L->q[k];
    L->axr[k] = q->ax - w->xi[k];
    L->bx[k] = q->bx;
    L->cx[k] = q->cx;
    L->wx[k] = q->wx;
    L->au[k] = q->au;
    L->bu[k] = q->bu;
    L->cu[k] = q->cu;
    L->wu[k] = q->wu;
    L->vx[k] = q->vx;
    L->vu[k] = q->vu;
    L->cxu[k] = q->cxu;
    L->ka = fmax(L->ka, fabs(q->ax - w->xi[k]));
    L->kb = fmax(L->kb, fabs(q->bx));
    L->kc = fmax(L->kc, fabs(q->cx));
    L->kw = fmax(L->kw, fabs(q->wx));
    L->vxmax = fmax(L->vxmax, q->vx);
    L->kau = fmax(L->kau, fabs(q->au));
    L->kbu = fmax(L->kbu, fabs(q->bu));
    L->kcu = fmax(L->kcu, fabs(q->cu));
    L->kwu = fmax(L->kwu, fabs(q->wu));
    L->vumax = fmax(L->vumax, q->vu);
  }
  /* the largest values also bound the stretches between the nodes, up to
   * the margins the caller applies */
  /* Cholesky of [[vx, cxu], [cxu, vu]]; the Schur complement vu - cxu^2/vx
   * is the variance of U given X (positive, no cancellation beyond a
   * factor ~4 for any h/tau) */
  const sbi_lh_coef *m = &L->mid;
  if (m->vx > 0.0) {
    L->l11 = sqrt(m->vx);
    L->l21 = m->cxu / L->l11;
    double sch = m->vu - L->l21 * L->l21;
    L->l22 = sch > 0.0 ? sqrt(sch) : 0.0;
  } else
    L->l11 = L->l21 = L->l22 = 0.0;
  L->valid = 1;
  return L;
}

void sbi_lh_slots_free(sb_langevin_hitter *w)
{
  for (int k = 0; k < SBI_LH_NSLOT; k++)
    for (int d = 0; d <= SBI_LH_MAXDEPTH; d++) {
      free(w->slot[k].lev[d]);
      w->slot[k].lev[d] = NULL;
    }
}
