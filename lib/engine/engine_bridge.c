/* engine_bridge.c — diffusive-bridge collision detection for the engine:
 * Bessel-3 bridge criterion, tail-bound neighbour reach, conditioned hit
 * time, barycentre place, correction step and reinsert outcomes, collision
 * split.  Theory and derivations: smolbridge/engine_bridge.h and
 * docs/engine_bridge.md.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_math.h>
#include <gsl/gsl_randist.h>
#include <gsl/gsl_sf_erf.h>

#include <smolbridge/bridge.h>
#include <smolbridge/engine_bridge.h>

#include "common/internal.h"
#include "common/numutil.h"
#include "engine_bridge_state.h"
#include "engine_internal.h"


void sb_engine_bridge_params_default(sb_engine_bridge_params *p)
{
  if (!p) {
    sbi_error(SB_EINVAL, __func__, "params is NULL");
    return;
  }
  p->mode = SB_BRIDGE_BESSEL;
  p->ends = SB_BRIDGE_ENDS_POSITION;
  p->outcome = SB_BRIDGE_OUT_REINSERT;
  p->tol = 1e-9;
  p->exact_tol = 1e-3;
  p->record_cap = 0;
}

sb_engine_bridge *sb_engine_bridge_alloc(const sb_engine_bridge_params *p)
{
  sb_engine_bridge_params d;
  if (!p) {
    sb_engine_bridge_params_default(&d);
    p = &d;
  }
  if ((p->mode != SB_BRIDGE_BESSEL && p->mode != SB_BRIDGE_EXACT) ||
      (p->ends != SB_BRIDGE_ENDS_POSITION &&
       p->ends != SB_BRIDGE_ENDS_DIFFUSIVE) ||
      (p->outcome != SB_BRIDGE_OUT_REINSERT &&
       p->outcome != SB_BRIDGE_OUT_CORRECT &&
       p->outcome != SB_BRIDGE_OUT_COUNT) ||
      !(p->tol > 0.0 && p->tol < 1.0) ||
      !(p->exact_tol > 0.0 && p->exact_tol <= 0.1) ||
      p->record_cap > SIZE_MAX / sizeof *((sb_engine_bridge *)0)->hits) {
    sbi_error(SB_EINVAL, __func__, "bad parameter (mode %d, ends %d, "
              "outcome %d, tol %g, exact_tol %g, record_cap %zu)",
              (int)p->mode, (int)p->ends, (int)p->outcome, p->tol,
              p->exact_tol, p->record_cap);
    return NULL;
  }
  sb_engine_bridge *b = calloc(1, sizeof *b);
  if (!b) {
    sbi_error(SB_ENOMEM, __func__, "out of memory");
    return NULL;
  }
  b->par = *p;
  if (p->record_cap) {
    b->hits = malloc(p->record_cap * sizeof *b->hits);
    if (!b->hits) {
      free(b);
      sbi_error(SB_ENOMEM, __func__, "out of memory");
      return NULL;
    }
  }
  return b;
}

void sb_engine_bridge_free(sb_engine_bridge *b)
{
  if (!b)
    return;
  free(b->b2);
  free(b->b2b);
  free(b->b2set);
  free(b->hits);
  free(b);
}

int sb_engine_bridge_set_b2(sb_engine_bridge *b, size_t species, double b2,
                            double b2_brown)
{
  if (!b || !(b2 > 0.0) || !isfinite(b2) || !(b2_brown >= 0.0) ||
      !(b2_brown <= b2))
    return sbi_error(SB_EINVAL, __func__, "b2 = %g, b2_brown = %g: need "
                     "0 <= b2_brown <= b2, b2 > 0 finite", b2, b2_brown);
  if (species >= ((size_t)1 << 20))
    return sbi_error(SB_EINVAL, __func__, "species %zu: beyond 2^20",
                     species);
  if (species >= b->nb2) {
    size_t nn = species + 1;
    double *n1 = realloc(b->b2, nn * sizeof *n1);
    if (!n1)
      return sbi_error(SB_ENOMEM, __func__, "out of memory");
    b->b2 = n1;
    double *n2 = realloc(b->b2b, nn * sizeof *n2);
    if (!n2)
      return sbi_error(SB_ENOMEM, __func__, "out of memory");
    b->b2b = n2;
    unsigned char *n3 = realloc(b->b2set, nn);
    if (!n3)
      return sbi_error(SB_ENOMEM, __func__, "out of memory");
    b->b2set = n3;
    for (size_t k = b->nb2; k < nn; k++)
      b->b2set[k] = 0;
    b->nb2 = nn;
  }
  b->b2[species] = b2;
  b->b2b[species] = b2_brown;
  b->b2set[species] = 1;
  return SB_SUCCESS;
}

/* Position variance rate of species sp (total and Brownian part). */
static void species_b2(const sb_engine *e, const sb_engine_bridge *b,
                       size_t sp, double *b2, double *b2b)
{
  if (sp < b->nb2 && b->b2set[sp]) {
    *b2 = b->b2[sp];
    *b2b = b->b2b[sp];
    return;
  }
  const sb_engine_species *s = &e->spec[sp];
  double bp = s->B * s->tau;  /* B_pos = B tau_p: Mohaupt 2011, eqs 5.7, J.2 */
  *b2 = *b2b = bp * bp;
}

/* ------------------------------------------------------- tail bound */

/* log E(rho) (see the header): with M = Q(z)/phi(z) the Mills ratio,
 * E = 8 pi n a sqrt(v) phi(z) [a (1 - z M) + sqrt(v) (z - (z^2 - 1) M)/2].
 * Both brackets are positive for z >= 0 (tail integrals of positive
 * functions). */
static double log_miss(double n, double a, double v, double rho)
{
  double sv = sqrt(v), z = rho / sv;
  double M = 1.0 / gsl_sf_hazard(z);
  double t1 = 1.0 - z * M, t2 = 0.5 * (z - (z * z - 1.0) * M);
  double br = a * t1 + sv * t2;
  if (!(br > 0.0))
    br = a / (z * z + 2.0);  /* rounding at huge z: 1 - zM ~ 1/(z^2+2) */
  double l1 = log(8.0 * M_PI * n * a * sv * br) - 0.5 * z * z -
              0.5 * log(2.0 * M_PI);
  if (!(rho > 0.0))
    return l1;
  /* second bound: both ends beyond a + rho, so the detector probability
   * is <= exp(-2 (x-a)(y-a)/v) <= exp(-2 (x-a) rho/v); integrated over
   * x >= a + rho with c = v/(2 rho):
   * 4 pi n exp(-2 rho^2/v) [(a+rho)^2 c + 2 (a+rho) c^2 + 2 c^3] */
  double c = v / (2.0 * rho), ar = a + rho;
  double l2 = log(4.0 * M_PI * n * (ar * ar * c + 2.0 * ar * c * c +
                                    2.0 * c * c * c)) - 2.0 * z * z;
  return l1 < l2 ? l1 : l2;
}

double sb_bridge_miss_bound(double n, double a, double v, double rho)
{
  if (!(n > 0.0) || !(a > 0.0) || !(v > 0.0) || !(rho >= 0.0) ||
      !isfinite(n) || !isfinite(a) || !isfinite(v) || !isfinite(rho)) {
    sbi_error(SB_EDOM, __func__, "n = %g, a = %g, v = %g, rho = %g", n, a,
              v, rho);
    return NAN;
  }
  return exp(log_miss(n, a, v, rho));
}

typedef struct {
  double n, a, v, ltol;
} reach_par;

static double reach_fn(double z, void *vp)
{
  const reach_par *q = vp;
  return log_miss(q->n, q->a, q->v, z * sqrt(q->v)) - q->ltol;
}

double sb_bridge_reach(double n, double a, double v, double tol)
{
  if (!(n > 0.0) || !(a > 0.0) || !(v > 0.0) || !(tol > 0.0 && tol < 1.0) ||
      !isfinite(n) || !isfinite(a) || !isfinite(v)) {
    sbi_error(SB_EDOM, __func__, "n = %g, a = %g, v = %g, tol = %g", n, a,
              v, tol);
    return NAN;
  }
  reach_par q = {n, a, v, log(tol)};
  if (reach_fn(0.0, &q) <= 0.0)
    return 0.0;
  /* bracket in z = rho/sqrt(v): log E decreases at least like -z^2/2 */
  gsl_function F = {reach_fn, &q};
  double z;
  int st = sbi_reach_root(&F, 1.0, 1e8, 1e-12, &z);
  if (st) {
    if (st == SB_ENOMEM)
      sbi_error(st, __func__, "out of memory");
    else
      sbi_error(st, __func__, "no bracket (n a^3 = %g)", n * a * a * a);
    return NAN;
  }
  return z * sqrt(v);
}

double sb_engine_bridge_reach(const sb_engine *e, const sb_engine_bridge *b)
{
  if (!e || !b) {
    sbi_error(SB_EINVAL, __func__, "NULL argument");
    return NAN;
  }
  if (e->n < 2 || e->nspec == 0)
    return 0.0;
  double b2max = 0.0;
  for (size_t sp = 0; sp < e->nspec; sp++) {
    double b2, b2b;
    species_b2(e, b, sp, &b2, &b2b);
    if (b2 > b2max)
      b2max = b2;
  }
  double V = e->par.L[0] * e->par.L[1] * e->par.L[2];
  double n = (double)(e->n - 1) / V;
  return sb_bridge_reach(n, 2.0 * e->rmax, 2.0 * b2max * e->par.dt,
                         b->par.tol);
}

int sb_engine_bridge_attach(sb_engine *e, sb_engine_bridge *b)
{
  if (!e || !b)
    return sbi_error(SB_EINVAL, __func__, "NULL argument");
  if (e->par.dim != 3)
    return sbi_error(SB_EINVAL, __func__, "bridge detection needs dim 3");
  for (size_t sp = 0; sp < e->nspec; sp++)
    if (!isfinite(e->spec[sp].tau) && !(sp < b->nb2 && b->b2set[sp]))
      return sbi_error(SB_EINVAL, __func__,
                       "species %zu: free flight has no diffusivity", sp);
  if (b->restored) {  /* sb_engine_bridge_load: its counters go on */
    const int st = sbi_engine_check_saved(e, b->saved_steps, b->saved_print,
                                          __func__, "the bridge detector");
    if (st)
      return st;
    b->restored = 0;
  }
  double reach = sb_engine_bridge_reach(e, b);
  if (!(reach >= 0.0))
    return sbi_error(SB_EINVAL, __func__, "no reach: %s", sb_last_error());
  int st = sb_engine_set_detector(e, sb_engine_detect_bridge, b, reach);
  if (st)
    return st;
  return sb_engine_set_outcome_fn(e, sb_engine_outcome_bridge, b);
}

/* ------------------------------------------------------- detector */

/* End-point separations A (start) and B (end) of the pair, from the
 * unwrapped change over the step; diffusive ends add tau (u_i - u_j). */
static void pair_ends(const sb_engine *e, const sb_engine_bridge *b,
                      const sb_engine_pair *p, double A[3], double B[3])
{
  for (int k = 0; k < 3; k++) {
    A[k] = p->dx0[k];
    B[k] = p->dx0[k] + p->dd[k];
  }
  if (b->par.ends == SB_BRIDGE_ENDS_DIFFUSIVE) {
    const size_t i = p->i, j = p->j;
    double ti = e->spec[e->species[i]].tau, tj = e->spec[e->species[j]].tau;
    /* across a Lees-Edwards boundary j's image moves du faster along x */
    double sh[3], du = 0.0;
    sbi_engine_image(e, &e->x0[3 * i], &e->x0[3 * j], 0.0, sh, &du);
    if (isfinite(ti) && isfinite(tj))
      for (int k = 0; k < 3; k++) {
        const double v = k == 0 ? du : 0.0;
        A[k] += ti * e->u0[3 * i + k] - tj * (e->u0[3 * j + k] + v);
        B[k] += ti * e->u[3 * i + k] - tj * (e->u[3 * j + k] + v);
      }
  }
}

static double pair_b2(const sb_engine *e, const sb_engine_bridge *b,
                      size_t i, size_t j, double *b2brown)
{
  double bi, bbi, bj, bbj;
  species_b2(e, b, e->species[i], &bi, &bbi);
  species_b2(e, b, e->species[j], &bj, &bbj);
  if (b2brown)
    *b2brown = bbi + bbj;
  return bi + bj;
}

static void record(sb_engine_bridge *b, double x, double y, double a,
                   double s2, double dt, double ta)
{
  if (b->nhits < b->par.record_cap) {
    sb_engine_bridge_hit *h = &b->hits[b->nhits++];
    h->x = x;
    h->y = y;
    h->a = a;
    h->sigma2 = s2;
    h->dt = dt;
    h->ta = ta;
  }
}

int sb_engine_detect_bridge(const sb_engine *e, const sb_engine_pair *p,
                            const gsl_rng *r, void *ctx, double *s)
{
  sb_engine_bridge *b = ctx;
  if (!e || !p || !r || !b || !s) {
    sbi_error(SB_EINVAL, __func__, "NULL argument");
    return -1;
  }
  if (p->i >= e->n || p->j >= e->n) {
    sbi_error(SB_EINVAL, __func__, "pair (%zu, %zu): no such particle",
              p->i, p->j);
    return -1;
  }
  double A[3], B[3];
  pair_ends(e, b, p, A, B);
  const double s2 = pair_b2(e, b, p->i, p->j, NULL);
  const double dt = p->dt, a = p->sigma, v = s2 * dt;
  const double x = sqrt(A[0] * A[0] + A[1] * A[1] + A[2] * A[2]);
  const double y = sqrt(B[0] * B[0] + B[1] * B[1] + B[2] * B[2]);
  if (x <= a) {  /* overlap at the start: P = 1 (eq 5.15), T_a = 0 */
    b->st.ndetect++;
    b->st.noverlap++;
    *s = 0.0;
    return 1;
  }
  if (b->par.mode == SB_BRIDGE_EXACT) {
    double ta, xa[3];
    int h = sb_bb3_hit_sample(r, A, B, a, s2, dt, b->par.exact_tol, &ta, xa,
                              NULL);
    if (h < 0)
      return -1;
    if (!h)
      return 0;
    b->st.ndetect++;
    record(b, x, y, a, s2, dt, ta);
    *s = fmin(1.0, fmax(0.0, ta / dt));
    return 1;
  }
  if (y > a) {
    /* P(hit) = expm1(2a(x+y-a)/v)/expm1(2xy/v) (eq 5.13) is at most the
     * half-space value exp(-2(x-a)(y-a)/v) (the ratio of the expm1 terms
     * is <= 1): decide most candidates with that one exp, the same uniform
     * then against the exact P (identical decisions, faster) */
    double lbb = -2.0 * (x - a) * (y - a) / v;
    if (!(lbb > -745.0))
      return 0;
    double u = gsl_rng_uniform(r);
    if (!(u < exp(lbb)))
      return 0;
    double lp = sb_bes3b_cross_logprob(x, y, a, v);
    if (isnan(lp))
      return -1;
    if (!(u < exp(lp)))
      return 0;
  }
  double ta = sb_bes3b_hit_sample(r, x, y, a, s2, dt);
  if (!(ta >= 0.0 && ta <= dt))
    return -1;
  b->st.ndetect++;
  record(b, x, y, a, s2, dt, ta);
  *s = ta / dt;
  return 1;
}

/* ------------------------------------------------------- place, outcomes */

/* Start and end of the barycentre relative to x0_i (positions of j taken
 * as x0_i - dx0 (+ disp_j): the unwrapped pair; across a Lees-Edwards
 * boundary j's image, whose chord is du dt longer along x). */
static void bary_ends(const sb_engine *e, const sb_engine_pair *p,
                      double b0[3], double b1[3])
{
  const size_t i = p->i, j = p->j;
  const double mi = e->mass[i], mj = e->mass[j], M = mi + mj;
  const double du = sbi_engine_pair_du(e, p);
  for (int k = 0; k < 3; k++) {
    const double dj = e->disp[3 * j + k] + (k == 0 ? du * e->par.dt : 0.0);
    b0[k] = -mj * p->dx0[k] / M;
    b1[k] = (mi * e->disp[3 * i + k] + mj * (dj - p->dx0[k])) / M;
  }
}

static double bary_b2(const sb_engine *e, const sb_engine_bridge *b,
                      size_t i, size_t j)
{
  double bi, bbi, bj, bbj;
  species_b2(e, b, e->species[i], &bi, &bbi);
  species_b2(e, b, e->species[j], &bj, &bbj);
  const double mi = e->mass[i], mj = e->mass[j], M = mi + mj;
  return (mi * mi * bi + mj * mj * bj) / (M * M);  /* eq 5.25 */
}

int sb_engine_bridge_place(const sb_engine *e, const sb_engine_bridge *b,
                           const sb_engine_pair *p, double s,
                           const gsl_rng *r, double bary[3])
{
  if (!e || !b || !p || !r || !bary || p->i >= e->n || p->j >= e->n ||
      !(s >= 0.0 && s <= 1.0))
    return sbi_error(SB_EINVAL, __func__, "bad argument");
  double b0[3], b1[3];
  bary_ends(e, p, b0, b1);
  /* eq 5.26: variance T_a (dt - T_a)/dt B_bary^2 = s (1 - s) dt B_bary^2 */
  double sd = sqrt(s * (1.0 - s) * e->par.dt * bary_b2(e, b, p->i, p->j));
  for (int k = 0; k < 3; k++)
    bary[k] = b0[k] + s * (b1[k] - b0[k]) + gsl_ran_gaussian_ziggurat(r, sd);
  return SB_SUCCESS;
}

/* Random unit vector orthogonal to w (uniform angle in that plane); any
 * plane if w = 0. */
static void unit_orthogonal(const gsl_rng *r, const double w[3], double e[3])
{
  double ww = sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
  double n[3] = {0.0, 0.0, 1.0};
  if (ww > 0.0)
    for (int k = 0; k < 3; k++)
      n[k] = w[k] / ww;
  /* basis (p, q) of the plane orthogonal to n */
  double t[3] = {1.0, 0.0, 0.0};
  if (fabs(n[0]) > 0.6) {
    t[0] = 0.0;
    t[1] = 1.0;
  }
  double pv[3] = {n[1] * t[2] - n[2] * t[1], n[2] * t[0] - n[0] * t[2],
                  n[0] * t[1] - n[1] * t[0]};
  double pn = sqrt(pv[0] * pv[0] + pv[1] * pv[1] + pv[2] * pv[2]);
  for (int k = 0; k < 3; k++)
    pv[k] /= pn;
  double qv[3] = {n[1] * pv[2] - n[2] * pv[1], n[2] * pv[0] - n[0] * pv[2],
                  n[0] * pv[1] - n[1] * pv[0]};
  double c, sn;
  gsl_ran_dir_2d(r, &c, &sn);
  for (int k = 0; k < 3; k++)
    e[k] = c * pv[k] + sn * qv[k];
}

/* Correction step, Mohaupt 2011, §5.4.3 (see the header). */
static int correct(sb_engine *e, const sb_engine_bridge *b,
                   const sb_engine_pair *p, double s)
{
  const size_t i = p->i, j = p->j;
  const double mi = e->mass[i], mj = e->mass[j], M = mi + mj;
  const double dt = e->par.dt;
  double b0[3], b1[3], bt[3], w[3], u[3];
  bary_ends(e, p, b0, b1);
  int st = sb_engine_bridge_place(e, b, p, s, e->rng, bt);
  if (st)
    return st;
  for (int k = 0; k < 3; k++)
    w[k] = b1[k] - b0[k];
  unit_orthogonal(e->rng, w, u);
  double bi, bbi;
  species_b2(e, b, e->species[i], &bi, &bbi);
  const double sd = sqrt(bi * (1.0 - s) * dt);
  const double du = sbi_engine_pair_du(e, p);
  for (int k = 0; k < 3; k++) {
    double xi_t = bt[k] + mj * p->sigma * u[k] / M;  /* contact, i */
    double xi_1 = xi_t + gsl_ran_gaussian_ziggurat(e->rng, sd);
    double xj_1 = (M * b1[k] - mi * xi_1) / mj;  /* barycentre kept */
    /* back to absolute unwrapped positions: i relative to x0_i; j's frame
     * differs from x0_j by the minimum-image shift, x0_j = x0_i - dx0
     * (across a Lees-Edwards boundary its image has moved du dt further
     * along x by the end of the step) */
    double xi_abs = e->x0[3 * i + k] + xi_1;
    double xj_abs = e->x0[3 * j + k] + (xj_1 + p->dx0[k]) -
                    (k == 0 ? du * dt : 0.0);
    e->disp[3 * i + k] = xi_abs - e->x0[3 * i + k];
    e->disp[3 * j + k] = xj_abs - e->x0[3 * j + k];
    e->x[3 * i + k] = xi_abs;
    e->x[3 * j + k] = xj_abs;
  }
  return SB_SUCCESS;
}

int sb_engine_outcome_bridge(sb_engine *e, const sb_engine_pair *p, double s,
                             void *ctx)
{
  sb_engine_bridge *b = ctx;
  if (!e || !p || !b)
    return sbi_error(SB_EINVAL, __func__, "NULL argument");
  if (p->i >= e->n || p->j >= e->n || p->i == p->j)
    return sbi_error(SB_EINVAL, __func__, "pair (%zu, %zu): not two "
                     "particles", p->i, p->j);
  double bb, b2 = pair_b2(e, b, p->i, p->j, &bb);
  double f = bb / b2;
  b->st.ncoll++;
  b->st.coll_brown += f;
  b->st.coll_turb += 1.0 - f;
  switch (b->par.outcome) {
  case SB_BRIDGE_OUT_REINSERT:
    return sbi_engine_reinsert_higher_id(e, p, s, __func__);
  case SB_BRIDGE_OUT_CORRECT:
    return correct(e, b, p, s);
  case SB_BRIDGE_OUT_COUNT:
    return SB_SUCCESS;
  }
  return sbi_error(SB_EINVAL, __func__, "unknown outcome %d",
                   (int)b->par.outcome);
}

int sb_engine_bridge_get_stats(const sb_engine_bridge *b,
                               sb_engine_bridge_stats *st)
{
  if (!b || !st)
    return sbi_error(SB_EINVAL, __func__, "NULL argument");
  *st = b->st;
  return SB_SUCCESS;
}

void sb_engine_bridge_reset(sb_engine_bridge *b)
{
  if (!b) {
    sbi_error(SB_EINVAL, __func__, "bridge is NULL");
    return;
  }
  memset(&b->st, 0, sizeof b->st);
  b->nhits = 0;
}

const sb_engine_bridge_hit *sb_engine_bridge_hits(const sb_engine_bridge *b,
                                                  size_t *n)
{
  if (n)
    *n = b ? b->nhits : 0;
  if (!b) {
    sbi_error(SB_EINVAL, __func__, "bridge is NULL");
    return NULL;
  }
  return b->hits;
}
