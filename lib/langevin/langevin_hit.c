/* langevin_hit.c — first contact of two Langevin particles given their
 * states at both ends of a step, sampled from the exact conditional law
 * (method and error budget: <smolbridge/langevin_hit.h>,
 * docs/engine_langevin.md).
 *
 * Rice bound (Rice 1944, §3.3; 1945).  On a sub-interval [a, b] with
 * known end states, p(t) = n.r(t) - R is a Gaussian process with C^1
 * paths; at each time (p, p') has mean (mu, mu'), variances (s^2, s'^2)
 * and covariance c (the two particles' bridge moments: means subtract,
 * covariances add; every component has the same covariance).  With p(a),
 * p(b) > 0, a contact inside needs a down-crossing of 0, and
 *   E[# down-crossings] = int_a^b f_p(t)(0) E[(p')^- | p(t) = 0] dt,
 * where p' | p = 0 ~ N(m, v), m = mu' - c mu/s^2, v = s'^2 - c^2/s^2, and
 * E[(Z)^-] = sqrt(v) phi(m/sqrt(v)) - m Phi(-m/sqrt(v)).  The integrand
 * vanishes at both ends (s -> 0 with mu > 0).
 */
#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_integration.h>
#include <gsl/gsl_randist.h>

#include "common/internal.h"
#include <smolbridge/langevin.h>
#include <smolbridge/langevin_shear.h>

#include "langevin/langevin_shear_internal.h"
#include "langevin_hit_internal.h"

/* Multiplier on the quadrature value of the Rice integral (margin for the
 * quadrature error of a smooth, possibly peaked integrand). */
#define SAFETY 4.0
/* Nodes with mean/sd above this contribute < phi(12) ~ 5e-33 each. */
#define XFAR 12.0
/* A sub-interval whose chord clearance (less the mean path's largest
 * deviation) is below XNEAR times its largest conditional standard
 * deviation is subdivided without evaluating its Rice bound. */
#define XNEAR 4.0
/* Chords passing within GRAZE xtol R of the sphere count as grazing. */
#define GRAZE 6.0
/* Relative tolerance on R^2 within which a start counts as touching
 * (SB_ENGINE_TOUCH of the engine). */
#define TOUCH 1e-9
#define INV_SQRT_2PI 0.39894228040143267794
#define INV_SQRT_2 0.70710678118654752440
#define SQRT_2 1.41421356237309504880
#define LN_2 0.69314718055994530942

void sb_langevin_hit_params_default(sb_langevin_hit_params *p)
{
  if (!p)
    return;
  p->dim = 3;
  p->eps = 1e-6;
  p->xtol = 1e-6;
  p->audit = 0;
}

sb_langevin_hitter *sb_langevin_hitter_alloc(const sb_langevin_hit_params *p)
{
  sb_langevin_hit_params d;
  if (!p) {
    sb_langevin_hit_params_default(&d);
    p = &d;
  }
  if ((p->dim != 2 && p->dim != 3) || !(p->eps > 0.0 && p->eps <= 0.1) ||
      !(p->xtol > 0.0 && p->xtol <= 0.01)) {
    sbi_error(SB_EINVAL, __func__,
              "dim = %d (2 or 3), eps = %g (in (0, 0.1]), xtol = %g (in "
              "(0, 0.01])", p->dim, p->eps, p->xtol);
    return NULL;
  }
  sb_langevin_hitter *w = calloc(1, sizeof *w);
  gsl_integration_glfixed_table *t =
      gsl_integration_glfixed_table_alloc(SBI_LH_NQ);
  if (!w || !t) {
    free(w);
    if (t)
      gsl_integration_glfixed_table_free(t);
    sbi_error(SB_ENOMEM, __func__, "out of memory");
    return NULL;
  }
  w->par = *p;
  for (int k = 0; k < SBI_LH_NQ; k++)
    gsl_integration_glfixed_point(0.0, 1.0, (size_t)k, &w->xi[k], &w->wq[k],
                                  t);
  gsl_integration_glfixed_table_free(t);
  return w;
}

void sb_langevin_hitter_free(sb_langevin_hitter *w)
{
  if (!w)
    return;
  sbi_lh_slots_free(w);
  free(w->ent);
  free(w);
}

const sb_langevin_hit_params *
sb_langevin_hitter_params(const sb_langevin_hitter *w)
{
  return w ? &w->par : NULL;
}

int sb_langevin_hitter_stats(const sb_langevin_hitter *w,
                             sb_langevin_hit_stats *st)
{
  if (!w || !st)
    return sbi_error(SB_EINVAL, __func__, "NULL argument");
  *st = w->st;
  return SB_SUCCESS;
}

void sb_langevin_hitter_reset(sb_langevin_hitter *w)
{
  if (w)
    memset(&w->st, 0, sizeof w->st);
}

/* ------------------------------------------------------------ walk */

/* States of both particles (0 = i, 1 = j) at one time. */
typedef struct {
  double x[2][3], u[2][3];
} pstate;

typedef struct {
  sb_langevin_hitter *w;
  const gsl_rng *r;
  int dim;
  double R, htop, eps, delta;
  sbi_lh_slot *sl[2];
  double tau[2], B[2], mass[2], wv[2][3];
  /* linear shear: G, and each process's constant drift velocities
   * (c_x, c_y) (the fluid velocity is (G y + c_x, c_y)); shear = 1 when a
   * process's slot carries the in-plane shear bridge */
  double G, cs[2][2], csbar[2];
  int shear;
  int auditing;
  /* relative mode (relative_walk): the pair's relative state in slot 0
   * (slot 1 zero) and the barycentre's ends kept for the contact */
  int relm;
  pstate bary0, bary1;
  double wbar[3];
  /* plane mode (sb_langevin_hitter_sample_plane): j is a fixed point at
   * the origin and the contact set is the half-space n.r <= R (R the
   * level, any sign); scale sets the resolution */
  int plane;
  double n[3], scale;
  /* exit mode (sb_langevin_hitter_sample_exit): the target set is the
   * outside of the ball, |r| >= R, reached from inside */
  int exitm;
  /* every-entry walk (sb_langevin_hitter_sample_all): a leaf's crossing
   * is recorded (an entry) and the walk goes on in the other mode; the
   * barycentre's state last drawn, at time tb (relative mode) */
  int multi;
  double tb;
  /* result */
  double th;         /* contact time from the start of the step */
  pstate ca, cb;     /* the leaf's end states */
  double ta, hl;     /* the leaf's start and length */
} walk;

/* Moments of the relative motion at the quadrature nodes of [a, a + h]
 * (levels Li, Lj), by component (node index last). */
typedef struct {
  double mu[3][SBI_LH_NQ], mv[3][SBI_LH_NQ];
  double s2[SBI_LH_NQ], su2[SBI_LH_NQ], c[SBI_LH_NQ];
  double s2max, devmax;
  /* shear (not isotropic): the pair's covariances by component, of the
   * position (P: xx, xy, yy, zz), the velocity (V: the same) and between
   * them (X: (x, u_x), (x, u_y), (y, u_x), (y, u_y), (z, u_z)); s2 then
   * holds the largest position variance along any direction */
  int shear;
  double P[4][SBI_LH_NQ], V[4][SBI_LH_NQ], X[5][SBI_LH_NQ];
} nodes;

static void one_mean(const sbi_lh_coef *q, const pstate *A, const pstate *B,
                     int p, int k, double w, double *mx, double *mu)
{
  double dx = B->x[p][k] - A->x[p][k];
  *mx = A->x[p][k] + q->ax * dx + q->bx * A->u[p][k] + q->cx * B->u[p][k] +
        q->wx * w;
  *mu = q->au * dx + q->bu * A->u[p][k] + q->cu * B->u[p][k] + q->wu * w;
}

/* Process p's in-plane state (u_y, y, u_x, x) (sb_langevin_shear_bridge
 * order) in and out of a pstate. */
static void plane_get(const pstate *S, int p, double v[4])
{
  v[0] = S->u[p][1];
  v[1] = S->x[p][1];
  v[2] = S->u[p][0];
  v[3] = S->x[p][0];
}

static void plane_set(pstate *S, int p, const double v[4])
{
  S->u[p][1] = v[0];
  S->x[p][1] = v[1];
  S->u[p][0] = v[2];
  S->x[p][0] = v[3];
}

/* m = ka S_a + kb S_b + kc c (the in-plane bridge mean) */
static void plane_mean(const double ka[4][4], const double kb[4][4],
                       const double kc[4][2], const double *sa,
                       const double *sb, const double *c, double m[4])
{
  for (int i = 0; i < 4; i++) {
    double t = kc[i][0] * c[0] + kc[i][1] * c[1];
    for (int j = 0; j < 4; j++)
      t += ka[i][j] * sa[j] + kb[i][j] * sb[j];
    m[i] = t;
  }
}

/* One component of the node moments (the loop over the nodes vectorises:
 * the outputs alias no input; 4 lanes on AVX2, chosen at load time.  The
 * lanes do what the scalar code does, operation for operation: AVX2
 * without FMA contracts nothing, so every value is the same). */
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
__attribute__((target_clones("avx2", "default")))
#endif
static void node_row(const sbi_lh_level *restrict Li,
                     const sbi_lh_level *restrict Lj,
                     const double *restrict xi, double dX0, double dX1,
                     double ua0, double ub0, double w0, double ua1,
                     double ub1, double w1, double ra, double dr,
                     double *restrict mu, double *restrict mv,
                     double *restrict dev2)
{
  for (int q = 0; q < SBI_LH_NQ; q++) {
    /* deviation of the mean from the chord ra + xi dr */
    const double d = Li->axr[q] * dX0 + Li->bx[q] * ua0 + Li->cx[q] * ub0 +
                     Li->wx[q] * w0 -
                     (Lj->axr[q] * dX1 + Lj->bx[q] * ua1 + Lj->cx[q] * ub1 +
                      Lj->wx[q] * w1);
    mu[q] = ra + xi[q] * dr + d;
    mv[q] = Li->au[q] * dX0 + Li->bu[q] * ua0 + Li->cu[q] * ub0 +
            Li->wu[q] * w0 -
            (Lj->au[q] * dX1 + Lj->bu[q] * ua1 + Lj->cu[q] * ub1 +
             Lj->wu[q] * w1);
    dev2[q] += d * d;
  }
}

/* eval_nodes with a shear process: each process's node means and
 * covariances by component (in-plane from the shear bridge, the third
 * component and non-shear processes from the level's coefficients), then
 * the pair's. */
static void eval_nodes_shear(const walk *W, const sbi_lh_level *Li,
                             const sbi_lh_level *Lj, const pstate *A,
                             const pstate *Bs, nodes *N)
{
  const sbi_lh_level *L[2] = {Li, Lj};
  const double *xi = W->w->xi;
  double sa[2][4], sb[2][4];
  for (int p = 0; p < 2; p++) {
    plane_get(A, p, sa[p]);
    plane_get(Bs, p, sb[p]);
  }
  N->shear = 1;
  N->s2max = N->devmax = 0.0;
  for (int q = 0; q < SBI_LH_NQ; q++) {
    double mx[3] = {0, 0, 0}, mu[3] = {0, 0, 0};
    double P[4] = {0}, V[4] = {0}, X[5] = {0};
    for (int p = 0; p < 2; p++) {
      const double sg = p ? -1.0 : 1.0;
      const sbi_lh_coef *c = &L[p]->q[q];
      for (int k = 0; k < 3; k++) {
        if (k < 2 && L[p]->sh)
          continue;
        double x, u;
        one_mean(c, A, Bs, p, k, W->wv[p][k], &x, &u);
        mx[k] += sg * x;
        mu[k] += sg * u;
      }
      if (L[p]->sh) {
        const sbi_lh_shear *S = L[p]->sh;
        double m[4];
        plane_mean(S->ka[q], S->kb[q], S->kc[q], sa[p], sb[p], W->cs[p], m);
        mx[0] += sg * m[3];
        mx[1] += sg * m[1];
        mu[0] += sg * m[2];
        mu[1] += sg * m[0];
        const double (*C)[4] = S->cov[q];
        P[0] += C[3][3];
        P[1] += C[3][1];
        P[2] += C[1][1];
        V[0] += C[2][2];
        V[1] += C[2][0];
        V[2] += C[0][0];
        X[0] += C[3][2];
        X[1] += C[3][0];
        X[2] += C[1][2];
        X[3] += C[1][0];
      } else {
        P[0] += c->vx;
        P[2] += c->vx;
        V[0] += c->vu;
        V[2] += c->vu;
        X[0] += c->cxu;
        X[3] += c->cxu;
      }
      P[3] += c->vx;
      V[3] += c->vu;
      X[4] += c->cxu;
    }
    double dev2 = 0.0;
    for (int k = 0; k < 3; k++) {
      const double ra = A->x[0][k] - A->x[1][k];
      const double rb = Bs->x[0][k] - Bs->x[1][k];
      const double d = mx[k] - (ra + xi[q] * (rb - ra));
      N->mu[k][q] = mx[k];
      N->mv[k][q] = mu[k];
      dev2 += d * d;
    }
    for (int k = 0; k < 4; k++) {
      N->P[k][q] = P[k];
      N->V[k][q] = V[k];
    }
    for (int k = 0; k < 5; k++)
      N->X[k][q] = X[k];
    /* the largest position variance along a direction */
    const double m = 0.5 * (P[0] + P[2]), h = 0.5 * (P[0] - P[2]);
    N->s2[q] = fmax(m + sqrt(h * h + P[1] * P[1]), P[3]);
    N->su2[q] = N->c[q] = NAN;
    if (N->s2[q] > N->s2max)
      N->s2max = N->s2[q];
    if (dev2 > N->devmax)
      N->devmax = dev2;
  }
  N->devmax = sqrt(N->devmax);
}

static void eval_nodes(const walk *W, const sbi_lh_level *Li,
                       const sbi_lh_level *Lj, const pstate *A,
                       const pstate *Bs, nodes *N)
{
  if (W->shear) {
    eval_nodes_shear(W, Li, Lj, A, Bs, N);
    return;
  }
  N->shear = 0;
  const double *xi = W->w->xi;
  double dev2[SBI_LH_NQ];
  for (int q = 0; q < SBI_LH_NQ; q++) {
    N->s2[q] = Li->vx[q] + Lj->vx[q];
    N->su2[q] = Li->vu[q] + Lj->vu[q];
    N->c[q] = Li->cxu[q] + Lj->cxu[q];
    dev2[q] = 0.0;
  }
  for (int k = 0; k < 3; k++) {
    /* per particle: x_b - x_a, u_a, u_b, w; relative start and chord */
    const double dX0 = Bs->x[0][k] - A->x[0][k];
    const double dX1 = Bs->x[1][k] - A->x[1][k];
    const double ra = A->x[0][k] - A->x[1][k], dr = dX0 - dX1;
    const double ua0 = A->u[0][k], ub0 = Bs->u[0][k], w0 = W->wv[0][k];
    const double ua1 = A->u[1][k], ub1 = Bs->u[1][k], w1 = W->wv[1][k];
    node_row(Li, Lj, xi, dX0, dX1, ua0, ub0, w0, ua1, ub1, w1, ra, dr,
             N->mu[k], N->mv[k], dev2);
  }
  N->s2max = 0.0;
  N->devmax = 0.0;
  for (int q = 0; q < SBI_LH_NQ; q++) {
    if (N->s2[q] > N->s2max)
      N->s2max = N->s2[q];
    if (dev2[q] > N->devmax)
      N->devmax = dev2[q];
  }
  N->devmax = sqrt(N->devmax);
}

/* node q's mean relative position (or velocity) as a 3-vector */
static void node3(const double v[3][SBI_LH_NQ], int q, double r[3])
{
  r[0] = v[0][q];
  r[1] = v[1][q];
  r[2] = v[2][q];
}

static double dot3(const double *a, const double *b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void rel(const pstate *S, double r[3])
{
  for (int k = 0; k < 3; k++)
    r[k] = S->x[0][k] - S->x[1][k];
}

/* The unit normal n of the half-space bound: the plane's (plane mode),
 * or along the mean path's closest approach (nodes and both ends); 0 if
 * that approach is inside the ball (no bound). */
static int bound_normal(const walk *W, const nodes *N, const double *ra,
                        const double *rb, double n[3])
{
  if (W->plane) {
    memcpy(n, W->n, 3 * sizeof *n);
    return 1;
  }
  double best[3], m[3];
  memcpy(best, ra, sizeof best);
  double bd = dot3(ra, ra);
  if (dot3(rb, rb) < bd) {
    memcpy(best, rb, sizeof best);
    bd = dot3(rb, rb);
  }
  for (int q = 0; q < SBI_LH_NQ; q++) {
    node3(N->mu, q, m);
    double d = dot3(m, m);
    if (d < bd) {
      bd = d;
      memcpy(best, m, sizeof best);
    }
  }
  if (!(bd > W->R * W->R * (1.0 - TOUCH)))
    return 0;
  const double nn = sqrt(bd);
  for (int k = 0; k < 3; k++)
    n[k] = best[k] / nn;
  return 1;
}

/* The pruning bound on [a, a + h] (file comment); 1 when it does not
 * apply. */
static double rice_bound(const walk *W, const nodes *N, const pstate *A,
                         const pstate *Bs, double h)
{
  double ra[3], rb[3], n[3];
  if (W->exitm)
    return 1.0;  /* exit mode: the closed-form bound only (exit_tail) */
  rel(A, ra);
  rel(Bs, rb);
  if (!bound_normal(W, N, ra, rb, n))
    return 1.0;
  /* both ends outside the half-space; a start on its boundary is allowed
   * when the pair separates there (the integrand then vanishes at a) */
  double va[3];
  for (int k = 0; k < 3; k++)
    va[k] = A->u[0][k] - A->u[1][k];
  const double pa = dot3(n, ra) - W->R, tiny = 0.5 * TOUCH * W->scale;
  if (!(dot3(n, rb) > W->R) ||
      !(pa > 0.0 || (pa > -tiny && dot3(n, va) > 0.0)))
    return 1.0;
  /* the variances along n: the same in every direction, or (shear) from
   * the covariances by component */
  const double *s2v = N->s2, *su2v = N->su2, *cv = N->c;
  double S2[SBI_LH_NQ], SU2[SBI_LH_NQ], CV[SBI_LH_NQ];
  if (N->shear) {
    const double a = n[0] * n[0], b = 2.0 * n[0] * n[1], c = n[1] * n[1],
                 z = n[2] * n[2];
    for (int q = 0; q < SBI_LH_NQ; q++) {
      S2[q] = a * N->P[0][q] + b * N->P[1][q] + c * N->P[2][q] +
              z * N->P[3][q];
      SU2[q] = a * N->V[0][q] + b * N->V[1][q] + c * N->V[2][q] +
               z * N->V[3][q];
      CV[q] = a * N->X[0][q] + 0.5 * b * (N->X[1][q] + N->X[2][q]) +
              c * N->X[3][q] + z * N->X[4][q];
    }
    s2v = S2, su2v = SU2, cv = CV;
  }
  double x[SBI_LH_NQ], p[SBI_LH_NQ], xmin = INFINITY;
  for (int q = 0; q < SBI_LH_NQ; q++) {
    double m[3];
    node3(N->mu, q, m);
    p[q] = dot3(n, m) - W->R;
    x[q] = s2v[q] > 0.0 ? p[q] / sqrt(s2v[q])
                        : (p[q] > 0.0 ? INFINITY : -INFINITY);
    if (x[q] < xmin)
      xmin = x[q];
  }
  if (xmin > XFAR)
    return 0.0;
  if (!(xmin > -XFAR))
    return 1.0;
  /* the largest node probability P(p(t_k) <= 0) is at the smallest x */
  double rice = 0.0, ptmax = 0.5 * erfc(xmin * INV_SQRT_2);
  for (int q = 0; q < SBI_LH_NQ; q++) {
    if (!(x[q] < XFAR))
      continue;
    const double s2 = s2v[q], s = sqrt(s2);
    double mq[3];
    node3(N->mv, q, mq);
    const double qv = dot3(n, mq);
    const double m = qv - cv[q] * p[q] / s2;
    const double v = su2v[q] - cv[q] * cv[q] / s2;
    double g;
    if (!(v > 0.0))
      g = m < 0.0 ? -m : 0.0;
    else if (x[q] > 5.0)  /* small term: E[Z^-] <= sd/sqrt(2 pi) + m^- */
      g = sqrt(v) * INV_SQRT_2PI + (m < 0.0 ? -m : 0.0);
    else {
      double sv = sqrt(v), z = m / sv;
      g = sv * INV_SQRT_2PI * exp(-0.5 * z * z) -
          m * 0.5 * erfc(z * INV_SQRT_2);
    }
    rice += W->w->wq[q] * INV_SQRT_2PI * exp(-0.5 * x[q] * x[q]) / s * g;
  }
  double b = SAFETY * h * rice + ptmax;
  return b < 1.0 ? b : 1.0;
}

/* Entry fraction of the chord ra -> rb into the ball of radius R, or -1;
 * *gap receives the chord's closest distance minus R. */
static double chord_entry(const double *ra, const double *rb, double R,
                          double *gap)
{
  double d[3] = {rb[0] - ra[0], rb[1] - ra[1], rb[2] - ra[2]};
  double a = dot3(d, d), b = dot3(ra, d), c = dot3(ra, ra) - R * R;
  double lam = a > 0.0 ? -b / a : 0.0;
  lam = lam < 0.0 ? 0.0 : (lam > 1.0 ? 1.0 : lam);
  double m[3] = {ra[0] + lam * d[0], ra[1] + lam * d[1], ra[2] + lam * d[2]};
  *gap = sqrt(dot3(m, m)) - R;
  if (c < -TOUCH * R * R)
    return 0.0;
  if (c <= TOUCH * R * R)  /* touching: in now if approaching */
    return b < 0.0 ? 0.0 : -1.0;
  if (b >= 0.0 || a == 0.0)
    return -1.0;
  double disc = b * b - a * c;
  if (disc < 0.0)
    return -1.0;
  double s = c / (-b + sqrt(disc));
  return s <= 1.0 ? s : -1.0;
}

/* Exit mode: fraction at which the chord ra -> rb leaves the ball of
 * radius R (ra inside it), or -1; *gap receives the chord's clearance
 * inside, R less its largest distance from the centre (at an end: the
 * ball is convex). */
static double chord_exit(const double *ra, const double *rb, double R,
                         double *gap)
{
  double d[3] = {rb[0] - ra[0], rb[1] - ra[1], rb[2] - ra[2]};
  double a = dot3(d, d), b = dot3(ra, d), c = dot3(ra, ra) - R * R;
  const double fa = dot3(ra, ra), fb = dot3(rb, rb);
  *gap = R - sqrt(fa > fb ? fa : fb);
  if (c > TOUCH * R * R)
    return 0.0;
  if (c >= -TOUCH * R * R && b >= 0.0)  /* touching: out now if leaving */
    return 0.0;
  if (fb <= R * R || a == 0.0)
    return -1.0;
  /* the positive root of a s^2 + 2 b s + c = 0 (c <= ~0) */
  const double disc = b * b - a * c, q = sqrt(disc > 0.0 ? disc : 0.0);
  const double s = b > 0.0 ? -c / (b + q) : (q - b) / a;
  return s < 0.0 ? 0.0 : (s > 1.0 ? 1.0 : s);
}

/* Plane mode: entry fraction of the chord ra -> rb into the half-space
 * n.r <= R, or -1; *gap receives the chord's smallest clearance. */
static double plane_entry(const walk *W, const double *ra, const double *rb,
                          double *gap)
{
  const double pa = dot3(W->n, ra) - W->R, pb = dot3(W->n, rb) - W->R;
  const double tol = 0.5 * TOUCH * W->scale;
  *gap = pa < pb ? pa : pb;
  if (pa < -tol)
    return 0.0;
  if (pa <= tol)  /* touching: in now if approaching */
    return pb < pa ? 0.0 : -1.0;
  if (pb > 0.0)
    return -1.0;
  return pa / (pa - pb);
}

/* The contact set's entry along the chord (ball or half-space). */
static double entry(const walk *W, const double *ra, const double *rb,
                    double *gap)
{
  if (W->exitm)
    return chord_exit(ra, rb, W->R, gap);
  return W->plane ? plane_entry(W, ra, rb, gap)
                  : chord_entry(ra, rb, W->R, gap);
}

/* End of a sub-interval inside the target set (the contact set; exit
 * mode: the outside of the ball). */
static int inside(const walk *W, const double *r)
{
  if (W->exitm)
    return dot3(r, r) >= W->R * W->R;
  return W->plane ? dot3(W->n, r) <= W->R : dot3(r, r) <= W->R * W->R;
}

static int contact_states(walk *W, sb_langevin_contact *c);

/* Every-entry walk: the leaf W->ta.. holds a crossing at W->th.  An entry
 * is recorded (its states drawn) and the walk then looks for the exit; an
 * exit sends it back to entries.  A chord that enters and ends outside
 * the ball has left it again inside the leaf (a line meets the ball in
 * one segment).  Returns 0 (go on) or a negative status. */
static int multi_leaf(walk *W, const double *rb)
{
  if (W->exitm) {
    W->exitm = 0;
    return 0;
  }
  sb_langevin_hitter *w = W->w;
  if (w->nent == w->capent) {
    size_t cap = w->capent ? 2 * w->capent : 8;
    sb_langevin_contact *e = realloc(w->ent, cap * sizeof *e);
    if (!e)
      return -SB_ENOMEM;
    w->ent = e;
    w->capent = cap;
  }
  int st = contact_states(W, &w->ent[w->nent]);
  if (st < 0)
    return st;
  w->nent++;
  W->exitm = !(dot3(rb, rb) > W->R * W->R);
  return 0;
}

/* Leaf [a, a + h]: decide on the chord (file comment of the header). */
static int leaf(walk *W, const pstate *A, const pstate *Bs, double a,
                double h)
{
  double ra[3], rb[3], gap;
  rel(A, ra);
  rel(Bs, rb);
  double s = entry(W, ra, rb, &gap);
  if (!W->auditing)
    W->w->st.leaves++;
  if (s < 0.0) {
    if (W->exitm && dot3(ra, ra) >= W->R * W->R * (1.0 - TOUCH)) {
      /* exit mode, a start touching the sphere on the way in (the walk's
       * start after an entry): only the end's clearance can graze */
      gap = W->R - sqrt(dot3(rb, rb));
    }
    if (gap < GRAZE * W->delta && !W->auditing)
      W->w->st.grazing++;
    return 0;
  }
  W->th = a + s * h;
  W->ca = *A;
  W->cb = *Bs;
  W->ta = a;
  W->hl = h;
  return W->multi ? multi_leaf(W, rb) : 1;
}

/* The largest standard deviation of the pair's relative position along
 * any direction on a level (shear: from the in-plane bridge). */
static double walk_sd(const walk *W, const sbi_lh_level *Li,
                      const sbi_lh_level *Lj)
{
  if (!W->shear)
    return sqrt(Li->vxmax + Lj->vxmax);
  return sqrt((Li->sh ? Li->sh->vmax : Li->vxmax) +
              (Lj->sh ? Lj->sh->vmax : Lj->vxmax));
}

/* quick_bound from the chord's clearance gap, the bounds dev and vel on
 * the mean's deviation from the chord and on the mean relative velocity,
 * and the largest standard deviations smax, spmax of the relative
 * position and velocity along any direction (the comment below). */
static double quick_tail(double gap, double dev, double vel, double smax,
                         double spmax, double h, double *x0out)
{
  const double G = gap - 1.25 * dev;
  if (smax > 0.0)
    *x0out = G / smax;
  if (!(smax > 0.0) || !(G > 1.5 * smax))
    return 1.0;
  const double x0 = G / smax;
  if (x0 > 38.0)
    return 0.0;
  const double ph = INV_SQRT_2PI * exp(-0.5 * x0 * x0);
  const double f = ph / smax * (spmax * INV_SQRT_2PI + 1.25 * vel) +
                   spmax * x0 * ph / smax;
  double b = SAFETY * h * f;
  return b < 1.0 ? b : 1.0;
}

/* Exit mode: the same closed form for leaving the ball.  The mean path
 * stays within 1.25 dev of the chord, whose clearance inside is gap, so
 * an exit needs |Z(t)| >= G = gap - 1.25 dev, Z the deviation from the
 * conditional mean, which vanishes at both ends.  P(sup |Z| >= G) is at
 * most the expected number of up-crossings of G by |Z| (Rice), the
 * integral of f_|Z|(G) E[(d|Z|/dt)^+ | |Z| = G].  For Z isotropic in k
 * dimensions (variances s^2, s'^2 per component, covariance c):
 * f_|Z|(G) = chi_k(G/s)/s, and given Z = G e the radial derivative e.Z'
 * is N(c G/s^2, s'^2 - c^2/s^2), so E[(.)^+] <= s' (x + 1/sqrt(2 pi)),
 * x = G/s (|c| <= s s').  The integrand is then at most
 * (s'/G) x chi_k(x) (x + 1/sqrt(2 pi)), which decreases in x >= 3:
 * evaluate it at smax, spmax.  In the shear (Z not isotropic) smax and
 * spmax are the largest along any direction, and the bound is not proven
 * (measured by the audit, as the quadrature is). */
static double exit_tail(int k, double gap, double dev, double smax,
                        double spmax, double h, double *x0out)
{
  const double G = gap - 1.25 * dev;
  if (smax > 0.0)
    *x0out = G / smax;
  if (!(smax > 0.0) || !(G >= 3.0 * smax))
    return 1.0;
  const double x = G / smax;
  if (x > 40.0)
    return 0.0;
  /* chi_k(x) = x^(k-1) exp(-x^2/2) / (2^(k/2-1) Gamma(k/2)) */
  const double chi =
      exp((k - 1) * log(x) - 0.5 * x * x - (0.5 * k - 1.0) * LN_2 -
          lgamma(0.5 * k));
  double b = SAFETY * h * spmax / G * x * chi * (x + INV_SQRT_2PI);
  return b < 1.0 ? b : 1.0;
}

/* The exit mode's tail, or the entry's. */
static double tail(const walk *W, double gap, double dev, double vel,
                   double smax, double spmax, double h, double *x0out)
{
  if (W->exitm)
    return exit_tail(W->dim, gap, dev, smax, spmax, h, x0out);
  return quick_tail(gap, dev, vel, smax, spmax, h, x0out);
}

/* Closed-form bound on the Rice integral of [a, a + h], from the chord
 * and the level's coefficient maxima, without evaluating the nodes.
 * With n the normal of the chord's closest approach (gap g beyond R),
 * the mean path stays within dev of the chord, so p(t) has mean
 * mu >= G = g - 1.25 dev (1.25: margin for the stretches between the
 * nodes).  With s, s' the standard deviations of p and p', |c| <= s s',
 * E[(p')^- | p = 0] <= s'/sqrt(2 pi) + |mu'| + s' x (x = mu/s), so the
 * integrand is at most phi(x)/s (s'/sqrt(2 pi) + |mu'|) + s' x phi(x)/s.
 * Both terms grow with s while s <= G/sqrt(2) (x phi(x) and phi(x)
 * decrease in x >= G/s > 1): evaluate them at s_max, s'_max and the bound
 * on |mu'|.  Returns the bound, or 1 if it does not apply (x0 < 1.5). */
static double quick_bound(const walk *W, const sbi_lh_level *Li,
                          const sbi_lh_level *Lj, const pstate *A,
                          const pstate *Bs, const double *ra,
                          const double *rb, double h, double *x0out)
{
  double gap;
  *x0out = 0.0;
  if (entry(W, ra, rb, &gap) >= 0.0)
    return 1.0;
  const sbi_lh_level *L[2] = {Li, Lj};
  if (W->shear) {
    /* each process's deviation and velocity bound by component: the
     * shear bridge's in the plane (sbi_lh_shear.km), the level's
     * per-component maxima elsewhere; the relative walk's j is zero */
    double dev = 0.0, vel = 0.0;
    for (int p = 0; p < (W->relm ? 1 : 2); p++) {
      double dv[3] = {0, 0, 0}, vv[3] = {0, 0, 0};
      int k0 = 0;
      if (L[p]->sh) {
        const double in[8] = {
            fabs(Bs->x[p][0] - A->x[p][0]), fabs(Bs->x[p][1] - A->x[p][1]),
            fabs(A->u[p][0]), fabs(A->u[p][1]), fabs(Bs->u[p][0]),
            fabs(Bs->u[p][1]), fabs(W->cs[p][0] + W->G * A->x[p][1]),
            fabs(W->cs[p][1])};
        const double(*km)[8] = L[p]->sh->km;
        for (int m = 0; m < 8; m++) {
          dv[0] += km[0][m] * in[m];
          dv[1] += km[1][m] * in[m];
          vv[0] += km[2][m] * in[m];
          vv[1] += km[3][m] * in[m];
        }
        k0 = 2;
      }
      for (int k = k0; k < W->dim; k++) {
        const double d = fabs(Bs->x[p][k] - A->x[p][k]);
        const double va = fabs(A->u[p][k]), vb = fabs(Bs->u[p][k]),
                     wk = fabs(W->wv[p][k]);
        dv[k] = L[p]->ka * d + L[p]->kb * va + L[p]->kc * vb + L[p]->kw * wk;
        vv[k] = L[p]->kau * d + L[p]->kbu * va + L[p]->kcu * vb +
                L[p]->kwu * wk;
      }
      dev += sqrt(dot3(dv, dv));
      vel += sqrt(dot3(vv, vv));
    }
    const double smax = walk_sd(W, Li, Lj);
    const double spmax = sqrt((Li->sh ? Li->sh->umax : Li->vumax) +
                              (Lj->sh ? Lj->sh->umax : Lj->vumax));
    return tail(W, gap, dev, vel, smax, spmax, h, x0out);
  }
  double dev = 0.0, vel = 0.0;
  /* same coefficients (one species): the deviations depend on the
   * relative end states only; otherwise bound each particle's */
  const int same = Li == Lj;
  for (int p = 0; p < (same ? 1 : 2); p++) {
    double dx = 0.0, ua = 0.0, ub = 0.0, ww = 0.0;
    for (int k = 0; k < W->dim; k++) {
      double d = Bs->x[p][k] - A->x[p][k];
      double va = A->u[p][k], vb = Bs->u[p][k], wk = W->wv[p][k];
      if (same) {
        d -= Bs->x[1][k] - A->x[1][k];
        va -= A->u[1][k];
        vb -= Bs->u[1][k];
        wk -= W->wv[1][k];
      }
      dx += d * d;
      ua += va * va;
      ub += vb * vb;
      ww += wk * wk;
    }
    dx = sqrt(dx), ua = sqrt(ua), ub = sqrt(ub), ww = sqrt(ww);
    dev += L[p]->ka * dx + L[p]->kb * ua + L[p]->kc * ub + L[p]->kw * ww;
    vel += L[p]->kau * dx + L[p]->kbu * ua + L[p]->kcu * ub + L[p]->kwu * ww;
  }
  const double smax = sqrt(Li->vxmax + Lj->vxmax);
  const double spmax = sqrt(Li->vumax + Lj->vumax);
  return tail(W, gap, dev, vel, smax, spmax, h, x0out);
}

/* Examine [a, a + h] at depth d, with end states A and Bs; 1 if the first
 * contact lies in it (stored in W), 0 if not, < 0 on error. */
static int examine(walk *W, const pstate *A, const pstate *Bs, double a,
                   unsigned d);

/* Audit a pruned sub-interval: did it hold a contact? (the draws are
 * discarded; the statistics other than audit_hits are restored) */
static int audit(walk *W, const pstate *A, const pstate *Bs, double a,
                 unsigned d)
{
  walk V = *W;
  V.auditing = 1;
  V.multi = 0;  /* did it hold a crossing (of the walk's current mode)? */
  V.eps = W->eps * 1e-3;
  sb_langevin_hit_stats keep = W->w->st;
  int h = examine(&V, A, Bs, a, d);
  uint64_t ah = keep.audit_hits + (h > 0);
  W->w->st = keep;
  W->w->st.audit_hits = ah;
  return h < 0 ? h : 0;
}

static int examine(walk *W, const pstate *A, const pstate *Bs, double a,
                   unsigned d)
{
  sb_langevin_hitter *w = W->w;
  w->st.nodes++;
  if (d > w->st.depth_max)
    w->st.depth_max = d;
  const sbi_lh_level *Li = sbi_lh_level_get(w, W->sl[0], d);
  const sbi_lh_level *Lj = sbi_lh_level_get(w, W->sl[1], d);
  if (!Li || !Lj)
    return -SB_ENOMEM;
  const double h = Li->h;
  double ra[3], rb[3];
  rel(A, ra);
  rel(Bs, rb);
  const int sure = inside(W, rb);
  double x0 = 0.0;
  if (!sure) {
    double b = quick_bound(W, Li, Lj, A, Bs, ra, rb, h, &x0);
    if (b < W->eps * h / W->htop) {
      w->st.pruned++;
      w->st.pruned_mass += b;
      if (w->par.audit && !W->auditing)
        return audit(W, A, Bs, a, d);
      return 0;
    }
  }
  /* the chord within XNEAR largest standard deviations of the plane: the
   * quadrature would hardly ever prune (its bound includes the largest
   * node probability P(p <= 0)); subdividing is always valid, so skip it
   * (not a leaf: the spread exceeds smax > 4 delta) */
  const double smax = walk_sd(W, Li, Lj);
  if (x0 < XNEAR && smax > 4.0 * W->delta && d < SBI_LH_MAXDEPTH &&
      (sure || smax > 0.0))
    goto subdivide;
  nodes N;
  eval_nodes(W, Li, Lj, A, Bs, &N);
  const double spread = sqrt(N.s2max) + N.devmax;
  if (!sure) {
    double share = W->eps * h / W->htop;
    if (N.s2max > 0.0) {
      double b = rice_bound(W, &N, A, Bs, h);
      if (b < share) {
        w->st.pruned++;
        w->st.pruned_mass += b;
        if (w->par.audit && !W->auditing)
          return audit(W, A, Bs, a, d);
        return 0;
      }
    } else {
      /* no noise: the path is its mean, within devmax of the chord
       * (checked at the nodes; at least twice that margin) */
      double gap;
      entry(W, ra, rb, &gap);
      if (gap > 2.0 * N.devmax + W->delta)
        return 0;
    }
  }
  if (spread <= W->delta)
    return leaf(W, A, Bs, a, h);
  if (d >= SBI_LH_MAXDEPTH) {
    if (!W->auditing)
      w->st.deep++;
    return leaf(W, A, Bs, a, h);
  }
  /* exact midpoint states, particle i then j (relative mode: the
   * relative state), component by component, z1 then z2 */
subdivide:;
  pstate M;
  const sbi_lh_level *L[2] = {Li, Lj};
  memset(&M, 0, sizeof M);
  /* relative mode: one process whose covariance is twice a particle's */
  const double sc = W->relm ? SQRT_2 : 1.0;
  for (int p = 0; p < (W->relm ? 1 : 2); p++) {
    int k0 = 0;
    if (L[p]->sh) {  /* the in-plane state from the shear bridge */
      const sbi_lh_shear *S = L[p]->sh;
      double sa[4], sb[4], m[4], z[4];
      plane_get(A, p, sa);
      plane_get(Bs, p, sb);
      plane_mean(S->mka, S->mkb, S->mkc, sa, sb, W->cs[p], m);
      for (int i = 0; i < 4; i++)
        z[i] = gsl_ran_gaussian_ziggurat(W->r, 1.0);
      for (int i = 0; i < 4; i++)
        for (int j = 0; j <= i; j++)
          m[i] += sc * S->ml[i][j] * z[j];
      plane_set(&M, p, m);
      k0 = 2;
    }
    for (int k = k0; k < W->dim; k++) {
      double mx, mu;
      one_mean(&L[p]->mid, A, Bs, p, k, W->wv[p][k], &mx, &mu);
      if (L[p]->l11 > 0.0) {
        double z1 = gsl_ran_gaussian_ziggurat(W->r, 1.0);
        double z2 = gsl_ran_gaussian_ziggurat(W->r, 1.0);
        mx += sc * L[p]->l11 * z1;
        mu += sc * (L[p]->l21 * z1 + L[p]->l22 * z2);
      }
      M.x[p][k] = mx;
      M.u[p][k] = mu;
    }
  }
  int st = examine(W, A, &M, a, d + 1);
  if (st)
    return st;
  return examine(W, &M, Bs, a + 0.5 * h, d + 1);
}

/* ------------------------------------------------------------ public */

static int check_path(const sb_langevin_path *q, int dim)
{
  if (!(q->tau > 0.0) || !(q->B >= 0.0) || !isfinite(q->B) ||
      !(q->mass >= 0.0) || !isfinite(q->mass))
    return 0;
  for (int k = 0; k < dim; k++)
    if (!isfinite(q->x0[k]) || !isfinite(q->u0[k]) || !isfinite(q->x1[k]) ||
        !isfinite(q->u1[k]) || !isfinite(q->us[k]))
      return 0;
  return 1;
}

/* Largest length of the problem, relative to the scale and absolute
 * (setup). */
#define LMAX_REL 1e100
#define LMAX_ABS 1e150

/* Set up a walk; returns 0, 1 (in the target set at the start) or a
 * negative status.  plane: NULL (ball |r| <= R, scale = R), or the unit
 * normal of the half-space n.r <= R (any R; resolution xtol scale);
 * exitm: the target is the outside of the ball (plane NULL). */
static int setup(walk *W, sb_langevin_hitter *w, const sb_langevin_path *pi,
                 const sb_langevin_path *pj, double R, const double *plane,
                 int exitm, double scale, double dt, const gsl_rng *r,
                 pstate *A, pstate *Bs, const char *func)
{
  if (!w || !pi || !pj)
    return -sbi_error(SB_EINVAL, func, "NULL argument");
  const int dim = w->par.dim;
  if (!plane)
    scale = R;
  if (!(scale > 0.0) || !isfinite(scale) || !isfinite(R) ||
      !(dt > 0.0) || !isfinite(dt) ||
      !check_path(pi, dim) || !check_path(pj, dim))
    return -sbi_error(SB_EDOM, func,
                      "R = %g, dt = %g, or a particle's tau, B, mass or "
                      "state is out of its domain", R, dt);
  const sb_langevin_path *P[2] = {pi, pj};
  /* Lengths of the problem (positions, u dt, us dt, the noise's position
   * spread) beyond 1e100 R or 1e150: the bounds' squares and the bridge
   * coefficients would overflow, nothing would be pruned and the walk
   * would refine to its depth limit everywhere (B = 1e300 or x0 = 1e300
   * took minutes).  SB_EDOM. */
  for (int p = 0; p < 2; p++) {
    const sb_langevin_path *q = P[p];
    double L = 0.0;
    if (isfinite(q->tau) && q->B > 0.0)
      L = sqrt(sb_langevin_var_x(q->tau, q->B, dt)); /* NaN: overflow */
    for (int k = 0; k < dim; k++) {
      const double l[5] = {fabs(q->x0[k]), fabs(q->x1[k]),
                           fabs(q->u0[k]) * dt, fabs(q->u1[k]) * dt,
                           fabs(q->us[k]) * dt};
      for (int i = 0; i < 5; i++)
        L = l[i] > L ? l[i] : L;
    }
    if (!(L <= LMAX_ABS) || !(L <= LMAX_REL * scale))
      return -sbi_error(SB_EDOM, func,
                        "particle %d: a length of the problem (position, "
                        "velocity times dt or noise spread) of %g exceeds "
                        "1e100 times the scale %g or 1e150", p, L, scale);
  }
  memset(W, 0, sizeof *W);
  memset(A, 0, sizeof *A);
  memset(Bs, 0, sizeof *Bs);
  W->w = w;
  W->r = r;
  W->dim = dim;
  W->R = R;
  W->htop = dt;
  W->eps = w->par.eps;
  W->delta = w->par.xtol * scale;
  W->scale = scale;
  W->exitm = exitm;
  if (plane) {
    W->plane = 1;
    memcpy(W->n, plane, sizeof W->n);
  }
  /* linear shear: one rate for the pair (Stokes particles; free flight
   * does not see the fluid) */
  double G = 0.0;
  for (int p = 0; p < 2; p++) {
    const sb_langevin_path *q = P[p];
    if (isinf(q->tau) || q->G == 0.0)
      continue;
    if (!isfinite(q->G) || (G != 0.0 && q->G != G) ||
        !(fabs(q->G) * dt <= 100.0))
      return -sbi_error(SB_EDOM, func, "shear rates %g and %g: one finite "
                        "rate for the pair, |G| dt <= 100", pi->G, pj->G);
    G = q->G;
  }
  W->G = G;
  for (int p = 0; p < 2; p++) {
    const sb_langevin_path *q = P[p];
    int det = isinf(q->tau) || q->B == 0.0;
    if (!det && !(dt / q->tau >= 1e-9 && dt / q->tau <= 1e9))
      return -sbi_error(SB_EDOM, func, "dt/tau = %g outside [1e-9, 1e9]",
                        dt / q->tau);
    /* the shear field is (G y + c_x, c_y): us is its value at x0 */
    W->cs[p][0] = q->us[0] - G * q->x0[1];
    W->cs[p][1] = q->us[1];
    W->tau[p] = q->tau;
    W->B[p] = q->B;
    W->mass[p] = q->mass;
    for (int k = 0; k < dim; k++) {
      W->wv[p][k] = isinf(q->tau) ? 0.0 : q->us[k];
      A->x[p][k] = q->x0[k];
      A->u[p][k] = q->u0[k];
      /* without noise the end is where the start state leads (in the
       * shear, in-plane, below) */
      if (det) {
        sbi_lh_coef c;
        sbi_lh_coef_at(q->tau, 0.0, dt, dt, &c);
        Bs->x[p][k] = q->x0[k] + c.bx * q->u0[k] + c.wx * W->wv[p][k];
        Bs->u[p][k] = c.bu * q->u0[k] + c.wu * W->wv[p][k];
      } else {
        Bs->x[p][k] = q->x1[k];
        Bs->u[p][k] = q->u1[k];
      }
    }
    W->sl[p] = sbi_lh_slot_get(w, q->tau, q->B, dt, G);
    W->shear |= W->sl[p] && W->sl[p]->shear;
    if (det && G != 0.0 && !isinf(q->tau)) {
      double sa[4], sb[4];
      plane_get(A, p, sa);
      sbi_shear_det_state(q->tau, G, W->cs[p][0], W->cs[p][1], dt, sa, sb);
      plane_set(Bs, p, sb);
    }
  }
  /* overlapping, or touching and approaching: a contact now; touching
   * and separating (a pair that has just bounced): no contact now */
  double ra[3], va[3];
  rel(A, ra);
  for (int k = 0; k < 3; k++)
    va[k] = A->u[0][k] - A->u[1][k];
  if (plane) {
    const double pa = dot3(W->n, ra) - R, tol = 0.5 * TOUCH * scale;
    if (pa < -tol)
      return 1;
    return pa <= tol && dot3(W->n, va) < 0.0;
  }
  double r2 = dot3(ra, ra), R2 = R * R;
  if (exitm) {
    /* apart, or touching and separating: out now; touching and
     * approaching (the state of a contact): in */
    if (r2 > R2 * (1.0 + TOUCH))
      return 1;
    return r2 >= R2 * (1.0 - TOUCH) && dot3(ra, va) >= 0.0;
  }
  if (r2 < R2 * (1.0 - TOUCH))
    return 1;
  return r2 <= R2 * (1.0 + TOUCH) && dot3(ra, va) < 0.0;
}

/* State of process p (a particle, or in relative mode the relative
 * state or the barycentre) at time s into [0, h] between end states A and
 * Bs, drawn from its bridge with the covariance scaled by sc^2. */
/* Shear: process p's in-plane state (u_y, y, u_x, x) at time s into
 * [0, h] between A and Bs from the exact shear bridge
 * (sb_langevin_shear_bridge_sample; the covariance scaled by sc^2 is that
 * of a particle with B sc; drifts cs). */
static int shear_plane_draw(const walk *W, int p, const pstate *A,
                            const pstate *Bs, double h, double s, double sc,
                            const double *cs, double out[4])
{
  double sa[4], sb[4];
  plane_get(A, p, sa);
  plane_get(Bs, p, sb);
  return sb_langevin_shear_bridge_sample(W->tau[p], W->B[p] * sc, W->G,
                                         cs[0], cs[1], h, s, sa, sb, W->r,
                                         out)
             ? -SB_EDOM
             : 0;
}

static int bridge_draw(const walk *W, int p, const pstate *A,
                       const pstate *Bs, double h, double s, double sc,
                       const double *wv, const double *cs, double x[3],
                       double v[3])
{
  int k0 = 0;
  if (W->sl[p]->shear) {
    double pl[4];
    if (W->sl[p]->det) {  /* no noise: the exact map from A */
      double sa[4];
      plane_get(A, p, sa);
      sbi_shear_det_state(W->tau[p], W->G, cs[0], cs[1], s, sa, pl);
    } else {
      int st = shear_plane_draw(W, p, A, Bs, h, s, sc, cs, pl);
      if (st < 0)
        return -st;
    }
    v[1] = pl[0];
    x[1] = pl[1];
    v[0] = pl[2];
    x[0] = pl[3];
    k0 = 2;
  }
  sbi_lh_coef q;
  if (!isinf(W->tau[p]) && W->B[p] > 0.0) {
    /* the bridge needs s and h - s >= 1e-60 tau, or exactly an end */
    if (s < 1e-50 * W->tau[p])
      s = 0.0;
    else if (h - s < 1e-50 * W->tau[p])
      s = h;
  }
  int st = sbi_lh_coef_at(W->tau[p], W->B[p], h, s, &q);
  if (st)
    return st;
  double l11 = 0.0, l21 = 0.0, l22 = 0.0;
  if (q.vx > 0.0) {
    l11 = sqrt(q.vx);
    l21 = q.cxu / l11;
    double sch = q.vu - l21 * l21;
    l22 = sch > 0.0 ? sqrt(sch) : 0.0;
  }
  for (int k = k0; k < W->dim; k++) {
    one_mean(&q, A, Bs, p, k, wv[k], &x[k], &v[k]);
    if (l11 > 0.0) {
      double z1 = gsl_ran_gaussian_ziggurat(W->r, 1.0);
      double z2 = gsl_ran_gaussian_ziggurat(W->r, 1.0);
      x[k] += sc * l11 * z1;
      v[k] += sc * (l21 * z1 + l22 * z2);
    }
  }
  return SB_SUCCESS;
}

/* Both particles' states at the contact time inside the leaf, drawn from
 * their bridges, then moved along the line of centres to touch.  In
 * relative mode the relative state comes from the leaf's bridge and the
 * barycentre, independent of the relative path, from its own over the
 * whole step. */
static int contact_states(walk *W, sb_langevin_contact *c)
{
  const double s = W->th - W->ta, h = W->hl;
  double xs[2][3] = {{0}}, vs[2][3] = {{0}};
  int st;
  if (W->relm) {
    double r[3] = {0}, v[3] = {0}, xc[3] = {0}, vc[3] = {0};
    if ((st = bridge_draw(W, 0, &W->ca, &W->cb, h, s, SQRT_2, W->wv[0],
                          W->cs[0], r, v)) ||
        (st = bridge_draw(W, 0, &W->bary0, &W->bary1, W->htop - W->tb,
                          W->th - W->tb, INV_SQRT_2, W->wbar, W->csbar, xc,
                          vc)))
      return -st;
    if (W->multi) {  /* the next entry's barycentre from this one's */
      memcpy(W->bary0.x[0], xc, sizeof xc);
      memcpy(W->bary0.u[0], vc, sizeof vc);
      W->tb = W->th;
    }
    for (int k = 0; k < W->dim; k++) {
      xs[0][k] = xc[k] + 0.5 * r[k];
      xs[1][k] = xc[k] - 0.5 * r[k];
      vs[0][k] = vc[k] + 0.5 * v[k];
      vs[1][k] = vc[k] - 0.5 * v[k];
    }
  } else
    for (int p = 0; p < 2; p++)
      if ((st = bridge_draw(W, p, &W->ca, &W->cb, h, s, 1.0, W->wv[p],
                            W->cs[p], xs[p], vs[p])))
        return -st;
  double r[3] = {xs[0][0] - xs[1][0], xs[0][1] - xs[1][1],
                 xs[0][2] - xs[1][2]};
  double rn = sqrt(dot3(r, r));
  if (W->plane) {  /* onto the plane along its normal */
    const double g = W->R - dot3(W->n, r);
    for (int k = 0; k < W->dim; k++)
      xs[0][k] += g * W->n[k];
  } else if (rn > 0.0) {
    double M = W->mass[0] + W->mass[1];
    double fi = M > 0.0 ? W->mass[1] / M : 0.5, fj = 1.0 - fi;
    double g = W->R / rn - 1.0;
    for (int k = 0; k < W->dim; k++) {
      xs[0][k] += fi * g * r[k];
      xs[1][k] -= fj * g * r[k];
    }
  }
  if (c) {
    c->t = W->th;
    for (int k = 0; k < 3; k++) {
      c->xi[k] = xs[0][k];
      c->ui[k] = vs[0][k];
      c->xj[k] = xs[1][k];
      c->uj[k] = vs[1][k];
    }
  }
  return 1;
}

/* Relative mode, for two particles with the same noisy slot (tau, B and
 * dt): their bridges are independent with the same covariance, so the
 * relative state r = x_i - x_j and the barycentre (x_i + x_j)/2 are
 * independent bridges with twice and half that covariance, and the
 * contact depends on r alone.  The walk then draws r's midpoints only
 * (half the draws of the two particles'); the barycentre is drawn once,
 * at the contact (contact_states).  The relative state takes slot 0 and
 * slot 1 is zero: the nodes' moments (variances add: Li == Lj), the
 * bounds and the chords are unchanged. */
static void relative_walk(walk *W, pstate *A, pstate *Bs)
{
  if (W->plane || W->sl[0] != W->sl[1] || W->sl[0]->det)
    return;
  W->relm = 1;
  pstate *S[2] = {A, Bs}, *C[2] = {&W->bary0, &W->bary1};
  memset(C[0], 0, sizeof *C[0]);
  memset(C[1], 0, sizeof *C[1]);
  for (int e = 0; e < 2; e++)
    for (int k = 0; k < 3; k++) {
      C[e]->x[0][k] = 0.5 * (S[e]->x[0][k] + S[e]->x[1][k]);
      C[e]->u[0][k] = 0.5 * (S[e]->u[0][k] + S[e]->u[1][k]);
      S[e]->x[0][k] -= S[e]->x[1][k];
      S[e]->u[0][k] -= S[e]->u[1][k];
      S[e]->x[1][k] = S[e]->u[1][k] = 0.0;
    }
  for (int k = 0; k < 3; k++) {
    W->wbar[k] = 0.5 * (W->wv[0][k] + W->wv[1][k]);
    W->wv[0][k] -= W->wv[1][k];
    W->wv[1][k] = 0.0;
  }
  for (int k = 0; k < 2; k++) {  /* the shear's drifts likewise (linear) */
    W->csbar[k] = 0.5 * (W->cs[0][k] + W->cs[1][k]);
    W->cs[0][k] -= W->cs[1][k];
    W->cs[1][k] = 0.0;
  }
}

/* The sampler for a ball (plane NULL), a half-space or the outside of
 * the ball (exitm) (setup). */

static int sample(sb_langevin_hitter *w, const sb_langevin_path *pi,
                  const sb_langevin_path *pj, double R, const double *plane,
                  int exitm, double scale, double dt, const gsl_rng *r,
                  sb_langevin_contact *c, const char *func)
{
  if (!r)
    return -sbi_error(SB_EINVAL, func, "r is NULL");
  walk W;
  pstate A, Bs;
  int st = setup(&W, w, pi, pj, R, plane, exitm, scale, dt, r, &A, &Bs,
                 func);
  if (st < 0)
    return st;
  w->st.calls++;
  if (st == 1) {  /* in the target set at the start: contact (exit) now */
    w->st.hits++;
    if (c) {
      memset(c, 0, sizeof *c);
      for (int k = 0; k < W.dim; k++) {
        c->xi[k] = A.x[0][k];
        c->ui[k] = A.u[0][k];
        c->xj[k] = A.x[1][k];
        c->uj[k] = A.u[1][k];
      }
    }
    return 1;
  }
  if (!W.sl[0] || !W.sl[1])
    return -sbi_error(SB_ENOMEM, func, "out of memory");
  relative_walk(&W, &A, &Bs);
  st = examine(&W, &A, &Bs, 0.0, 0);
  if (st < 0)
    return -sbi_error(-st, func, "coefficients failed");
  if (!st)
    return 0;
  w->st.hits++;
  st = contact_states(&W, c);
  if (st < 0)
    return -sbi_error(-st, func, "contact state failed");
  return 1;
}

int sb_langevin_hitter_sample(sb_langevin_hitter *w,
                              const sb_langevin_path *pi,
                              const sb_langevin_path *pj, double R,
                              double dt, const gsl_rng *r,
                              sb_langevin_contact *c)
{
  return sample(w, pi, pj, R, NULL, 0, R, dt, r, c, __func__);
}

int sb_langevin_hitter_sample_all(sb_langevin_hitter *w,
                                  const sb_langevin_path *pi,
                                  const sb_langevin_path *pj, double R,
                                  double dt, const gsl_rng *r)
{
  static const char *func = "sb_langevin_hitter_sample_all";
  if (!r)
    return -sbi_error(SB_EINVAL, func, "r is NULL");
  walk W;
  pstate A, Bs;
  int st = setup(&W, w, pi, pj, R, NULL, 0, R, dt, r, &A, &Bs, func);
  if (st < 0)
    return st;
  if (!W.sl[0] || !W.sl[1])
    return -sbi_error(SB_ENOMEM, func, "out of memory");
  w->st.calls++;
  w->nent = 0;
  W.multi = 1;
  W.exitm = st == 1;  /* in contact at the start: its exit first */
  relative_walk(&W, &A, &Bs);
  st = examine(&W, &A, &Bs, 0.0, 0);
  if (st < 0)
    return -sbi_error(-st, func, st == -SB_ENOMEM ? "out of memory"
                                                   : "coefficients failed");
  if (w->nent > (size_t)INT_MAX)
    return -sbi_error(SB_EMAXITER, func, "too many entries");
  w->st.hits += w->nent > 0;
  return (int)w->nent;
}

const sb_langevin_contact *
sb_langevin_hitter_entries(const sb_langevin_hitter *w)
{
  return w ? w->ent : NULL;
}

int sb_langevin_hitter_sample_exit(sb_langevin_hitter *w,
                                   const sb_langevin_path *pi,
                                   const sb_langevin_path *pj, double R,
                                   double dt, const gsl_rng *r,
                                   sb_langevin_contact *c)
{
  return sample(w, pi, pj, R, NULL, 1, R, dt, r, c, __func__);
}

int sb_langevin_hitter_sample_plane(sb_langevin_hitter *w,
                                    const sb_langevin_path *p,
                                    const double n[3], double level,
                                    double scale, double dt,
                                    const gsl_rng *r,
                                    sb_langevin_contact *c)
{
  if (!n)
    return -sbi_error(SB_EINVAL, __func__, "n is NULL");
  const double nn = sqrt(dot3(n, n));
  if (!(nn > 0.0) || !isfinite(nn))
    return -sbi_error(SB_EDOM, __func__, "n is not a direction");
  const double u[3] = {n[0] / nn, n[1] / nn, n[2] / nn};
  /* the other "particle": a fixed point at the origin */
  sb_langevin_path o;
  memset(&o, 0, sizeof o);
  o.tau = INFINITY;
  return sample(w, p, &o, level / nn, u, 0, scale, dt, r, c, __func__);
}

double sb_langevin_hitter_bound(sb_langevin_hitter *w,
                                const sb_langevin_path *pi,
                                const sb_langevin_path *pj, double R,
                                double dt)
{
  walk W;
  pstate A, Bs;
  int st = setup(&W, w, pi, pj, R, NULL, 0, R, dt, NULL, &A, &Bs,
                 __func__);
  if (st < 0)
    return NAN;
  if (st == 1)
    return 1.0;
  double rb[3];
  rel(&Bs, rb);
  if (dot3(rb, rb) <= R * R)
    return 1.0;
  const sbi_lh_level *Li = sbi_lh_level_get(w, W.sl[0], 0);
  const sbi_lh_level *Lj = sbi_lh_level_get(w, W.sl[1], 0);
  if (!Li || !Lj)
    return NAN;
  nodes N;
  eval_nodes(&W, Li, Lj, &A, &Bs, &N);
  if (!(N.s2max > 0.0))
    return NAN;
  return rice_bound(&W, &N, &A, &Bs, dt);
}
