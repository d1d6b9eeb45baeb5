/* spray_collide.c — the stochastic collision–coalescence operator:
 * Bird-type (constant weight, pair updates) and Nanbu-type (variable
 * weights, one-sided updates) particle methods.
 *
 * Time integration.  Both methods simulate the N-particle jump process
 * exactly: candidate events form a Poisson process of rate Lambda >= the
 * total event rate, and a candidate (i, j) is accepted with probability
 * rate_ij / bound (thinning; Lewis & Shedler 1979).  When an event raises
 * the bound (a faster particle, a larger droplet) the next waiting time is
 * drawn with the new Lambda, which keeps the thinning exact because waiting
 * times are memoryless.  Bird's no-time-counter (Bird 1994, §11.1) instead
 * draws a fixed number Lambda dt of candidates per call, carrying the
 * fractional part to the next call.
 *
 * Bound on the hard-sphere rate pi (r_i + r_j)^2 |v_i - v_j|: with c the
 * mean velocity at the start of the call, |v_i - v_j| <= 2 max_k |v_k - c|
 * and r_i + r_j <= 2 max_k r_k; both maxima are updated after every event.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_randist.h>

#include <smolbridge/spray.h>

#include "common/internal.h"
#include "spray_internal.h"

typedef struct {
  double c[3];  /* reference velocity */
  double smax;  /* max |v - c| */
  double rmax;  /* max r */
  double Bmax;  /* bound on every pair's B */
} bound;

static double bound_B(const sb_spray *s, const bound *b)
{
  if (s->p.cross == SB_SPRAY_MAXWELL)
    return s->p.B0;
  double d = 2.0 * b->rmax;
  return SBI_PI * d * d * 2.0 * b->smax;
}

static void bound_init(const sb_spray *s, bound *b)
{
  double c[3] = {0, 0, 0}, wt = 0;
  for (size_t i = 0; i < s->n; i++) {
    wt += s->w[i];
    for (int k = 0; k < 3; k++)
      c[k] += s->w[i] * s->v[3 * i + k];
  }
  for (int k = 0; k < 3; k++)
    b->c[k] = wt > 0 ? c[k] / wt : 0.0;
  b->smax = 0;
  b->rmax = 0;
  for (size_t i = 0; i < s->n; i++) {
    const double *v = s->v + 3 * i;
    double d0 = v[0] - b->c[0], d1 = v[1] - b->c[1], d2 = v[2] - b->c[2];
    double sp = sqrt(d0 * d0 + d1 * d1 + d2 * d2);
    if (sp > b->smax)
      b->smax = sp;
    if (s->r[i] > b->rmax)
      b->rmax = s->r[i];
  }
  /* a relative margin so that rounding in |g| never exceeds the bound */
  b->smax *= 1.0 + 1e-12;
  b->Bmax = bound_B(s, b);
}

/* Widen the bound for parcel i after an event; returns the new Bmax. */
static double bound_update(const sb_spray *s, bound *b, size_t i)
{
  const double *v = s->v + 3 * i;
  double d0 = v[0] - b->c[0], d1 = v[1] - b->c[1], d2 = v[2] - b->c[2];
  double sp = sqrt(d0 * d0 + d1 * d1 + d2 * d2) * (1.0 + 1e-12);
  if (sp > b->smax)
    b->smax = sp;
  if (s->r[i] > b->rmax)
    b->rmax = s->r[i];
  b->Bmax = bound_B(s, b);
  return b->Bmax;
}

/* Pair rate of (i, j) and the relative velocity g = v_i - v_j. */
static double pair_B(const sb_spray *s, size_t i, size_t j, double g[3],
                     double *gmod)
{
  const double *vi = s->v + 3 * i, *vj = s->v + 3 * j;
  g[0] = vi[0] - vj[0];
  g[1] = vi[1] - vj[1];
  g[2] = vi[2] - vj[2];
  *gmod = sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
  return sb_spray_pair_rate(s->p.cross, s->p.B0, s->r[i], s->r[j], *gmod);
}

static void event_begin(const sb_spray *s, sb_spray_event *e, size_t i,
                        size_t j, double t)
{
  e->t = t;
  e->i = i;
  e->j = j;
  e->tag_i = s->tag[i];
  e->tag_j = s->tag[j];
  e->r_i = s->r[i];
  e->r_j = s->r[j];
  e->w_i = s->w[i];
  e->w_j = s->w[j];
  memcpy(e->vi, s->v + 3 * i, sizeof e->vi);
  memcpy(e->vj, s->v + 3 * j, sizeof e->vj);
}

/* Outcome of an accepted pair (i, j).  pairwise = 1 (Bird): both change,
 * a merge removes j.  pairwise = 0 (Nanbu): only i changes; a merge turns
 * i into the merged droplet with weight w_i m_i/(m_i + m_j) (mass flow).
 * Returns 1 if j was removed (Bird merge). */
static int outcome(sb_spray *s, size_t i, size_t j, const double g[3],
                   double gmod, int pairwise, double t, gsl_rng *rng,
                   bound *b)
{
  double sig[3];
  gsl_ran_dir_3d(rng, &sig[0], &sig[1], &sig[2]);
  double cchi = gmod > 0 ? (sig[0] * g[0] + sig[1] * g[1] + sig[2] * g[2]) /
                               gmod
                         : sig[2]; /* g = 0: any axis (sigma isotropic) */
  sb_spray_event e;
  if (s->ev)
    event_begin(s, &e, i, j, t);
  double *vi = s->v + 3 * i, *vj = s->v + 3 * j;
  double ri3 = s->r[i] * s->r[i] * s->r[i], rj3 = s->r[j] * s->r[j] * s->r[j];
  int merge = s->p.coal == SB_SPRAY_COAL_OROURKE
                  ? 0.5 * (1.0 + cchi) <=
                        sb_spray_orourke_b2(s->r[i], s->r[j], gmod,
                                            s->p.rho_l, s->p.sigma)
                  : sb_spray_coalesces(cchi, s->p.theta_cr);
  if (merge) {
    double m = ri3 + rj3, vn[3];
    for (int k = 0; k < 3; k++)
      vn[k] = (ri3 * vi[k] + rj3 * vj[k]) / m;
    double rn = cbrt(m);
    if (s->p.merge_velocity)
      s->p.merge_velocity(rn, vn, s->p.merge_ctx);
    if (!pairwise)
      s->w[i] *= ri3 / m;
    s->r[i] = rn;
    memcpy(vi, vn, sizeof vn);
    s->y[i] = s->yd[i] = 0.0;
    if (pairwise)
      s->shed[i] += s->shed[j];
    s->st.merges++;
    if (s->ev) {
      e.kind = SB_SPRAY_MERGE;
      memcpy(e.vi_new, vn, sizeof vn);
      memcpy(e.vj_new, pairwise ? vn : e.vj, sizeof vn);
      s->ev(&e, s->evctx);
    }
    bound_update(s, b, i);
    if (pairwise) {
      sbi_spray_remove(s, j);
      return 1;
    }
    return 0;
  }
  double vip[3], vjp[3];
  sb_spray_post_collision(vi, vj, ri3, rj3, sig, vip, vjp);
  memcpy(vi, vip, sizeof vip);
  if (pairwise)
    memcpy(vj, vjp, sizeof vjp);
  s->st.bounces++;
  if (s->ev) {
    e.kind = SB_SPRAY_BOUNCE;
    memcpy(e.vi_new, vip, sizeof vip);
    memcpy(e.vj_new, pairwise ? vjp : e.vj, sizeof vjp);
    s->ev(&e, s->evctx);
  }
  bound_update(s, b, i);
  if (pairwise)
    bound_update(s, b, j);
  return 0;
}

/* Candidate rate of the Bird method: N^2 W Bmax/(2V) (Bird's N N-bar:
 * pairs among the N(N-1)/2 distinct ones, so each pair's rate is
 * W B N/((N-1) V) and each particle's n B). */
static double bird_rate(const sb_spray *s, const bound *b)
{
  double N = (double)s->n;
  return N * N * s->p.weight * b->Bmax / (2.0 * s->p.volume);
}

static void bird_pick(const sb_spray *s, gsl_rng *rng, size_t *i, size_t *j)
{
  size_t n = s->n;
  *i = (size_t)gsl_rng_uniform_int(rng, n);
  *j = (size_t)gsl_rng_uniform_int(rng, n - 1);
  if (*j >= *i)
    (*j)++;
}

static int collide_bird(sb_spray *s, double dt, gsl_rng *rng)
{
  bound b;
  bound_init(s, &b);
  const double t0 = s->t;
  if (s->p.select == SB_SPRAY_MAJORANT) {
    double tt = 0.0;
    while (s->n >= 2) {
      double lam = bird_rate(s, &b);
      if (!(lam > 0))
        break;
      tt += gsl_ran_exponential(rng, 1.0 / lam);
      if (tt > dt)
        break;
      size_t i, j;
      bird_pick(s, rng, &i, &j);
      s->st.candidates++;
      double g[3], gm, B = pair_B(s, i, j, g, &gm);
      if (gsl_rng_uniform(rng) * b.Bmax >= B)
        continue;
      outcome(s, i, j, g, gm, 1, t0 + tt, rng, &b);
    }
    return SB_SUCCESS;
  }
  /* NTC: a candidate budget; rescaled when N or Bmax change mid-call so
   * that the expected number of collisions stays right */
  double budget = s->n >= 2 ? bird_rate(s, &b) * dt + s->ntc_rem
                            : s->ntc_rem;
  double k = 0;
  while (budget >= 1.0 && s->n >= 2) {
    budget -= 1.0;
    k += 1.0;
    size_t i, j;
    bird_pick(s, rng, &i, &j);
    s->st.candidates++;
    double g[3], gm, B = pair_B(s, i, j, g, &gm);
    if (gsl_rng_uniform(rng) * b.Bmax >= B)
      continue;
    double lam0 = bird_rate(s, &b);
    /* the event time is not resolved by NTC: spread over the call */
    double te = t0 + dt * k / (k + budget + 1.0);
    outcome(s, i, j, g, gm, 1, te, rng, &b);
    double lam1 = s->n >= 2 ? bird_rate(s, &b) : 0.0;
    if (lam1 != lam0 && lam0 > 0)
      budget *= lam1 / lam0;
  }
  s->ntc_rem = budget < 1.0 ? budget : 0.0;
  return SB_SUCCESS;
}

static int collide_nanbu(sb_spray *s, double dt, gsl_rng *rng)
{
  const size_t n = s->n;
  if (n == 0)
    return SB_SUCCESS;
  bound b;
  bound_init(s, &b);
  /* partner law: weights at the start of the call (they only decrease:
   * a merge multiplies w_i by m_i/(m_i + m_j) < 1), then accept
   * w_j / w0_j */
  double *w0 = malloc(n * sizeof *w0);
  if (!w0)
    return sbi_error(SB_ENOMEM, "sb_spray_collide", "out of memory");
  memcpy(w0, s->w, n * sizeof *w0);
  double wtot = 0, wmin = INFINITY, wmax = 0;
  for (size_t i = 0; i < n; i++) {
    wtot += w0[i];
    if (w0[i] < wmin)
      wmin = w0[i];
    if (w0[i] > wmax)
      wmax = w0[i];
  }
  gsl_ran_discrete_t *alias = NULL;
  if (wmax > wmin) {
    alias = gsl_ran_discrete_preproc(n, w0);
    if (!alias) {
      free(w0);
      return sbi_error(SB_ENOMEM, "sb_spray_collide", "out of memory");
    }
  }
  const double t0 = s->t;
  double tt = 0.0;
  for (;;) {
    /* each parcel's clock: rate wtot Bmax / V */
    double lam = (double)n * wtot * b.Bmax / s->p.volume;
    if (!(lam > 0))
      break;
    tt += gsl_ran_exponential(rng, 1.0 / lam);
    if (tt > dt)
      break;
    size_t i = (size_t)gsl_rng_uniform_int(rng, n);
    size_t j = alias ? gsl_ran_discrete(rng, alias)
                     : (size_t)gsl_rng_uniform_int(rng, n);
    s->st.candidates++;
    double g[3], gm, B = pair_B(s, i, j, g, &gm);
    double acc = (s->w[j] / w0[j]) * (B / b.Bmax);
    if (gsl_rng_uniform(rng) >= acc)
      continue;
    outcome(s, i, j, g, gm, 0, t0 + tt, rng, &b);
  }
  gsl_ran_discrete_free(alias);
  free(w0);
  return SB_SUCCESS;
}

int sb_spray_collide(sb_spray *s, double dt, gsl_rng *rng)
{
  if (!s || !rng)
    return sbi_error(SB_EINVAL, __func__, "NULL spray or rng");
  if (!(dt > 0) || !isfinite(dt))
    return sbi_error(SB_EINVAL, __func__, "dt = %g: must be finite > 0", dt);
  int st = s->p.method == SB_SPRAY_BIRD ? collide_bird(s, dt, rng)
                                        : collide_nanbu(s, dt, rng);
  s->t += dt;
  return st;
}
