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
 * relaxation to us, or in a linear shear to the field along the path) have
 * the unconditioned mean from the start state and zero covariance. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_sf_exp.h>
#include <smolbridge/langevin.h>
#include <smolbridge/langevin_shear.h>

#include "common/internal.h"
#include "langevin/langevin_shear_internal.h"
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
                             double htop, double G)
{
  if (isinf(tau))
    B = G = 0.0;  /* free flight does not see the fluid */
  w->clock++;
  sbi_lh_slot *old = &w->slot[0];
  for (int k = 0; k < SBI_LH_NSLOT; k++) {
    sbi_lh_slot *s = &w->slot[k];
    if (s->used && s->tau == tau && s->B == B && s->htop == htop &&
        s->G == G) {
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
  old->G = G;
  old->det = isinf(tau) || B == 0.0;
  old->shear = G != 0.0;
  old->stamp = w->clock;
  for (int d = 0; d <= SBI_LH_MAXDEPTH; d++)
    if (old->lev[d])
      old->lev[d]->valid = 0;
  return old;
}

/* Largest eigenvalue of the symmetric 2 x 2 [[a, b], [b, c]]. */
static double eig2(double a, double b, double c)
{
  const double m = 0.5 * (a + c), d = 0.5 * (a - c);
  return m + sqrt(d * d + b * b);
}

/* The in-plane bridge of a shear slot's level (its other fields filled):
 * sb_langevin_shear_bridge_coefs in units tau = B = 1, taken to the
 * caller's by S = D S~, D = diag(vu, vx, vu, vx), vu = B sqrt(tau),
 * vx = vu tau.  Below h/tau = 1e-9 (that function's domain) the shear
 * changes the law by O(G h) < 1e-9 relative: the Ornstein-Uhlenbeck
 * coefficients of the level are used.  A slot without noise (B = 0, a
 * Stokes particle) takes the exact deterministic map from each
 * sub-interval's start (sbi_shear_det_map), no spread.  Status. */
static int shear_fill(sb_langevin_hitter *w, const sbi_lh_slot *s,
                      sbi_lh_level *L)
{
  if (!L->sh && !(L->sh = malloc(sizeof *L->sh)))
    return sbi_error(SB_ENOMEM, "sb_langevin_hitter_sample",
                     "out of memory");
  sbi_lh_shear *S = L->sh;
  const double tau = s->tau, x = L->h / tau, g = s->G * tau;
  const double vu = s->B * sqrt(tau), vx = vu * tau;
  const double D[4] = {vu, vx, vu, vx};
  S->vmax = S->umax = 0.0;
  for (int k = 0; k <= SBI_LH_NQ; k++) {  /* the nodes, then the midpoint */
    const double xi = k < SBI_LH_NQ ? w->xi[k] : 0.5;
    double (*ka)[4] = k < SBI_LH_NQ ? S->ka[k] : S->mka;
    double (*kb)[4] = k < SBI_LH_NQ ? S->kb[k] : S->mkb;
    double (*kc)[2] = k < SBI_LH_NQ ? S->kc[k] : S->mkc;
    double cov[4][4];
    sb_langevin_shear_bridge b;
    if (s->det) {  /* no noise: the exact map from the sub-interval's
                      start, whatever its end */
      sbi_shear_det_map(tau, s->G, xi * L->h, ka, kc);
      memset(kb, 0, 16 * sizeof(double));
      memset(cov, 0, sizeof cov);
    } else if (x >= 1e-9) {
      if (sb_langevin_shear_bridge_coefs(x, g, xi * x, &b))
        return sbi_error(SB_EDOM, "sb_langevin_hitter_sample",
                         "no shear bridge (h/tau = %g, G tau = %g): %s", x,
                         g, sb_last_error());
      for (int i = 0; i < 4; i++) {
        for (int j = 0; j < 4; j++) {
          ka[i][j] = D[i] * b.ka[i][j] / D[j];
          kb[i][j] = D[i] * b.kb[i][j] / D[j];
          cov[i][j] = D[i] * D[j] * b.cov[i][j];
        }
        kc[i][0] = D[i] * b.kc[i][0] / vu;
        kc[i][1] = D[i] * b.kc[i][1] / vu;
      }
    } else {  /* the level's own (u, x) coefficients, per component */
      const sbi_lh_coef *q = k < SBI_LH_NQ ? &L->q[k] : &L->mid;
      memset(ka, 0, 16 * sizeof(double));
      memset(kb, 0, 16 * sizeof(double));
      memset(kc, 0, 8 * sizeof(double));
      memset(cov, 0, sizeof cov);
      for (int c = 0; c < 2; c++) {  /* (u_y, y), then (u_x, x) */
        const int iu = 2 * c, ix = 2 * c + 1;
        ka[ix][ix] = 1.0 - q->ax;
        ka[ix][iu] = q->bx;
        kb[ix][ix] = q->ax;
        kb[ix][iu] = q->cx;
        ka[iu][ix] = -q->au;
        ka[iu][iu] = q->bu;
        kb[iu][ix] = q->au;
        kb[iu][iu] = q->cu;
        cov[ix][ix] = q->vx;
        cov[iu][iu] = q->vu;
        cov[ix][iu] = cov[iu][ix] = q->cxu;
      }
    }
    if (k < SBI_LH_NQ) {
      /* the bound's coefficients (sbi_lh_shear.km): output rows x, y,
       * u_x, u_y are S rows 3, 1, 2, 0; inputs dx, dy from kb's position
       * columns less the chord's xi, the velocities from ka and kb, the
       * drifts from kc */
      static const int row[4] = {3, 1, 2, 0};
      for (int o = 0; o < 4; o++) {
        const int i = row[o];
        const double in[8] = {kb[i][3] - (o == 0 ? xi : 0.0),
                              kb[i][1] - (o == 1 ? xi : 0.0),
                              ka[i][2], ka[i][0], kb[i][2], kb[i][0],
                              kc[i][0], kc[i][1]};
        for (int m = 0; m < 8; m++)
          S->km[o][m] = k ? fmax(S->km[o][m], fabs(in[m])) : fabs(in[m]);
      }
      memcpy(S->cov[k], cov, sizeof cov);
      const double vz = L->q[k].vx, uz = L->q[k].vu;
      const double ve = eig2(cov[3][3], cov[3][1], cov[1][1]);
      const double ue = eig2(cov[2][2], cov[2][0], cov[0][0]);
      S->vmax = fmax(S->vmax, fmax(ve, vz));
      S->umax = fmax(S->umax, fmax(ue, uz));
    } else if (s->det)
      memset(S->ml, 0, sizeof S->ml);
    else if (sbi_shear_chol4(cov, S->ml))
      return sbi_error(SB_EDOM, "sb_langevin_hitter_sample",
                       "shear bridge covariance not positive definite "
                       "(h/tau = %g, G tau = %g)", x, g);
  }
  return SB_SUCCESS;
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
    L = calloc(1, sizeof *L);
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
  if (s->shear && shear_fill(w, s, L))
    return NULL;
  L->valid = 1;
  return L;
}

void sbi_lh_slots_free(sb_langevin_hitter *w)
{
  for (int k = 0; k < SBI_LH_NSLOT; k++)
    for (int d = 0; d <= SBI_LH_MAXDEPTH; d++) {
      if (w->slot[k].lev[d])
        free(w->slot[k].lev[d]->sh);
      free(w->slot[k].lev[d]);
      w->slot[k].lev[d] = NULL;
    }
}
