/* langevin_bridge.c — the Langevin state at an intermediate time given the
 * states at both ends of a step ("Langevin bridge"), by exact Gaussian
 * conditioning.
 *
 * Reduction.  In the frame moving with the fluid, x~ = x - x0 - us t and
 * u~ = u - us follow the same model with us = 0 and x~_0 = 0.  Scaling
 * time by tau, x~ by B tau^{3/2} and u~ by B tau^{1/2} removes tau and B:
 * Z = (X, U) with dX = U dh, dU = -U dh + dW.  For that process over a lag
 * h, Z_h = Phi(h) Z_0 + noise, Phi(h) = [[1, a], [0, e]] (a = 1 - e,
 * e = exp(-h)), noise ~ N(0, Sigma(h)), Sigma = [[vx, cxu], [cxu, vu]]
 * (the unit-free moments of langevin.c; det Sigma = vu * vxc with vxc the
 * conditional variance, a product of two accurate factors).
 *
 * Conditioning.  Prior of Z_s given Z_0: N(m_s, Sigma_s), m_s = Phi_s Z_0.
 * Observation Z_dt = Phi_r Z_s + noise(Sigma_r), r = dt - s.  Posterior
 * (standard Gaussian linear update):
 *   covariance S = P^{-1},  P = Sigma_s^{-1} + Phi_r^T Sigma_r^{-1} Phi_r,
 *   mean m_s + K (Z_dt - Phi_dt Z_0),  K = Sigma_s Phi_r^T Sigma_dt^{-1}
 * (K = P^{-1} Phi_r^T Sigma_r^{-1}, the same gain).  The covariance uses the
 * information form: P is a sum of two positive-definite matrices, so it does
 * not cancel as s -> dt like Sigma_s - K Sigma_dt K^T does; det P loses at
 * most ~2 bits.  The mean uses the gain form: K has O(1) entries, whereas
 * P^{-1} (Phi_r^T Sigma_r^{-1} d) multiplies O(r^-3) by O(r^3) and lost
 * ~10 bits near s = dt in tests.  Accuracy against a 150-digit
 * covariance-form computation: variances and covariance to a few ulps,
 * means to ~1e-11 conditional standard deviations or one ulp of the value.
 * Sampling: Cholesky of S, with S11 = P22/det P, S12 = -P12/det P and the
 * Schur complement S22 - S12^2/S11 = 1/P22.
 */
#include <float.h>
#include <math.h>

#include <gsl/gsl_randist.h>
#include <smolbridge/langevin.h>

#include "common/internal.h"
#include "common/numutil.h"
#include "langevin_hit_internal.h"

#define X(x) sbi_xd_of(x)
#define MUL(a, b) sbi_xd_mul((a), (b))

/* Smallest s/tau or (dt-s)/tau accepted: det P ~ (tau/s)^4 must not
 * overflow (1e-60 leaves a margin of ~10^60). */
#define HMIN 1e-60
/* Largest dt/tau accepted (the scaled lag moments are ~h there). */
#define HMAX 1e300

/* Unit-free transition over lag h: Phi = [[1, a], [0, e]] and the inverse
 * covariance M = Sigma^{-1} = [[vu, -cxu], [-cxu, vx]] / (vu * vxc). */
typedef struct {
  double a, e;
  double m11, m12, m22;
} lag;

static void lag_init(lag *L, double h)
{
  L->a = -expm1(-h);
  L->e = exp(-h);
  double vu = sb_langevin_var_u(1.0, 1.0, h);
  double cxu = sb_langevin_cov_xu(1.0, 1.0, h);
  double vx = sb_langevin_var_x(1.0, 1.0, h);
  double vxc = sb_langevin_var_x_cond(1.0, 1.0, h);
  /* M = adj(Sigma)/det: scale 1/vxc and 1/vu separately so that the
   * product vu * vxc cannot underflow before the division. */
  L->m11 = 1.0 / vxc;
  L->m12 = -(cxu / vu) / vxc;
  L->m22 = (vx / vu) / vxc;
}

/* The scaled bridge at hs = s/tau into a lag h = dt/tau (hr = h - hs):
 * its posterior precision P (det), the gain K = Sigma_s Phi_r^T
 * Sigma_dt^{-1} and the prior transitions (a, e) over hs and h. */
typedef struct {
  double as, es, ah, eh;
  double k11, k12, k21, k22;
  double p11, p12, p22, det;
} gain;

static void gain_init(gain *g, double hs, double hr, double h)
{
  lag Ls, Lr, Lt;
  lag_init(&Ls, hs);
  lag_init(&Lr, hr);
  lag_init(&Lt, h);
  g->as = Ls.a, g->es = Ls.e, g->ah = Lt.a, g->eh = Lt.e;
  /* Posterior precision P = M_s + Phi_r^T M_r Phi_r, with
   * G = Phi_r^T M_r = [[m11, m12], [a m11 + e m12, a m12 + e m22]]. */
  double g11 = Lr.m11, g12 = Lr.m12;
  double g21 = Lr.a * Lr.m11 + Lr.e * Lr.m12;
  double g22 = Lr.a * Lr.m12 + Lr.e * Lr.m22;
  g->p11 = Ls.m11 + g11;
  g->p12 = Ls.m12 + g11 * Lr.a + g12 * Lr.e;
  g->p22 = Ls.m22 + g21 * Lr.a + g22 * Lr.e;
  g->det = g->p11 * g->p22 - g->p12 * g->p12;
  /* the gain (see the top of the file); C = Sigma_s Phi_r^T has
   * non-negative entries */
  double vx = sb_langevin_var_x(1.0, 1.0, hs);
  double vu = sb_langevin_var_u(1.0, 1.0, hs);
  double cxu = sb_langevin_cov_xu(1.0, 1.0, hs);
  double c11 = vx + Lr.a * cxu, c12 = Lr.e * cxu;
  double c21 = cxu + Lr.a * vu, c22 = Lr.e * vu;
  g->k11 = c11 * Lt.m11 + c12 * Lt.m12;
  g->k12 = c11 * Lt.m12 + c12 * Lt.m22;
  g->k21 = c21 * Lt.m11 + c22 * Lt.m12;
  g->k22 = c21 * Lt.m12 + c22 * Lt.m22;
}

typedef struct {
  double mx, mu;           /* posterior mean, scaled frame (origin x0) */
  double p11, p12, p22;    /* posterior precision */
  double det;              /* det P */
  /* Extreme B or tau: the scales sx = B tau^1.5 or su = B tau^0.5 (or
   * the scaled end states) leave the normal range, and the mean is taken
   * unscaled instead (scaled = 0): mean_x = x0 + us s + ox, mean_u =
   * us + ou, with sbi_xd products for tau times a velocity. */
  int scaled;
  double ox, ou;
  sbi_xd sx, su;           /* the scales */
} post;

/* Validate, reduce to the scaled frame and compute the posterior.
 * Returns a status; *endpoint = 0/1/2 for interior / s == 0 / s == dt. */
static int bridge_core(const char *func, const sb_langevin *p, double dt,
                       double s, double x0, double u0, double x1, double u1,
                       post *q, int *endpoint)
{
  if (!p)
    return sbi_error(SB_EINVAL, func, "p is NULL");
  double tau = p->tau, B = p->B, us = p->us;
  if (!(tau > 0) || !isfinite(tau))
    return sbi_error(SB_EDOM, func, "tau = %g must be positive and finite",
                     tau);
  if (!(B > 0) || !isfinite(B))
    return sbi_error(SB_EDOM, func,
                     "B = %g must be positive and finite (the bridge of a "
                     "deterministic motion is undefined)", B);
  if (!(dt > 0) || !isfinite(dt))
    return sbi_error(SB_EDOM, func, "dt = %g must be positive and finite",
                     dt);
  if (!(s >= 0 && s <= dt))
    return sbi_error(SB_EDOM, func, "s = %g must lie in [0, dt = %g]", s,
                     dt);
  if (!isfinite(us) || !isfinite(x0) || !isfinite(u0) || !isfinite(x1) ||
      !isfinite(u1))
    return sbi_error(SB_EDOM, func, "us, x0, u0, x1, u1 must be finite");
  *endpoint = s == 0 ? 1 : (s == dt ? 2 : 0);
  if (*endpoint)
    return SB_SUCCESS;
  double hs = s / tau, hr = (dt - s) / tau, h = dt / tau;
  if (hs < HMIN || hr < HMIN)
    return sbi_error(SB_EDOM, func,
                     "s = %g is closer than 1e-60 tau to 0 or dt = %g", s,
                     dt);

  if (!(h <= HMAX))
    return sbi_error(SB_EDOM, func, "dt/tau = %g exceeds 1e300", h);

  /* scaled end states in the moving frame (origin at x0) */
  const double w0 = u0 - us, w1 = u1 - us, d1 = (x1 - x0) - us * dt;
  if (!isfinite(w0) || !isfinite(w1) || !isfinite(d1))
    return sbi_error(SB_ERANGE, func, "u0 - us = %g, u1 - us = %g or "
                     "x1 - x0 - us dt = %g overflows", w0, w1, d1);
  const sbi_xd sx = MUL(MUL(X(B), X(tau)), sbi_xd_sqrt(X(tau)));
  const sbi_xd su = MUL(X(B), sbi_xd_sqrt(X(tau)));
  q->sx = sx, q->su = su;
  double U0 = sbi_xd_val(sbi_xd_div(X(w0), su));
  double X1 = sbi_xd_val(sbi_xd_div(X(d1), sx));
  double U1 = sbi_xd_val(sbi_xd_div(X(w1), su));

  gain g;
  gain_init(&g, hs, hr, h);
  q->p11 = g.p11, q->p12 = g.p12, q->p22 = g.p22, q->det = g.det;
  const double sxv = sbi_xd_val(sx), suv = sbi_xd_val(su);
  q->scaled = sxv >= DBL_MIN && suv >= DBL_MIN && isfinite(sxv) &&
              isfinite(suv) && isfinite(U0) && isfinite(X1) &&
              isfinite(U1);
  if (q->scaled) {
    /* prior mean at s and innovation at dt (unconditioned mean
     * Phi_dt Z0) */
    double msx = U0 * g.as, msu = U0 * g.es;
    double dx = X1 - U0 * g.ah, du = U1 - U0 * g.eh;
    q->mx = msx + g.k11 * dx + g.k12 * du;
    q->mu = msu + g.k21 * dx + g.k22 * du;
    q->ox = sxv * q->mx;
    q->ou = suv * q->mu;
  } else {
    /* the same mean times (sx, su), with sx U0 = tau w0, sx X1 = d1,
     * sx U1 = tau w1, su U0 = w0, su X1 = d1/tau, su U1 = w1 */
    const sbi_xd T0 = MUL(X(tau), X(w0));
    const double dx = d1 - sbi_xd_val(MUL(T0, X(g.ah)));
    const double du = w1 - w0 * g.eh;
    q->mx = q->mu = NAN;
    q->ox = sbi_xd_val(MUL(T0, X(g.as))) + g.k11 * dx +
            g.k12 * sbi_xd_val(MUL(X(tau), X(du)));
    q->ou = w0 * g.es + sbi_xd_val(sbi_xd_div(X(g.k21), X(tau))) * dx +
            g.k22 * du;
  }
  return SB_SUCCESS;
}

static void set_nan(sb_langevin_mom *m)
{
  m->mean_x = m->mean_u = m->var_x = m->var_u = m->cov_xu = NAN;
}

int sb_langevin_bridge_moments(const sb_langevin *p, double dt, double s,
                               double x0, double u0, double x1, double u1,
                               sb_langevin_mom *m)
{
  if (!m)
    return sbi_error(SB_EINVAL, __func__, "m is NULL");
  set_nan(m);
  post q;
  int end;
  int st = bridge_core(__func__, p, dt, s, x0, u0, x1, u1, &q, &end);
  if (st)
    return st;
  if (end) {
    m->mean_x = end == 1 ? x0 : x1;
    m->mean_u = end == 1 ? u0 : u1;
    m->var_x = m->var_u = m->cov_xu = 0.0;
    return SB_SUCCESS;
  }
  const double tau = p->tau;
  const sbi_xd B2 = MUL(X(p->B), X(p->B));
  const double mx = x0 + p->us * s + q.ox, mu = p->us + q.ou;
  const double vx = sbi_xd_val(MUL(MUL(MUL(MUL(B2, X(tau)), X(tau)), X(tau)),
                                   X(q.p22 / q.det)));
  const double vu = sbi_xd_val(MUL(MUL(B2, X(tau)), X(q.p11 / q.det)));
  const double cxu = sbi_xd_val(MUL(MUL(MUL(B2, X(tau)), X(tau)),
                                    X(-q.p12 / q.det)));
  if (!isfinite(mx) || !isfinite(mu) || !isfinite(vx) || !isfinite(vu) ||
      !isfinite(cxu))
    return sbi_error(SB_ERANGE, __func__,
                     "a moment overflows a double (mean_x = %g, mean_u = "
                     "%g, var_x = %g, var_u = %g, cov_xu = %g)", mx, mu, vx,
                     vu, cxu);
  m->mean_x = mx;
  m->mean_u = mu;
  m->var_x = vx;
  m->var_u = vu;
  m->cov_xu = cxu;
  return SB_SUCCESS;
}

int sb_langevin_bridge_sample(const sb_langevin *p, double dt, double s,
                              double x0, double u0, double x1, double u1,
                              const gsl_rng *r, double *xs, double *us)
{
  if (!xs || !us)
    return sbi_error(SB_EINVAL, __func__, "xs or us is NULL");
  *xs = *us = NAN;
  if (!r)
    return sbi_error(SB_EINVAL, __func__, "r is NULL");
  post q;
  int end;
  int st = bridge_core(__func__, p, dt, s, x0, u0, x1, u1, &q, &end);
  if (st)
    return st;
  if (end) {
    *xs = end == 1 ? x0 : x1;
    *us = end == 1 ? u0 : u1;
    return SB_SUCCESS;
  }
  /* Cholesky of S = P^{-1}: L11 = sqrt(P22/det), L21 = -P12/sqrt(P22 det),
   * L22 = 1/sqrt(P22) (scaled frame). */
  double l11 = sqrt(q.p22 / q.det);
  double l21 = -q.p12 / (sqrt(q.p22) * sqrt(q.det)); /* no overflow */
  double l22 = 1.0 / sqrt(q.p22);
  double z1 = gsl_ran_gaussian_ziggurat(r, 1.0);
  double z2 = gsl_ran_gaussian_ziggurat(r, 1.0);
  double x, u;
  if (q.scaled) {
    const double sx = sbi_xd_val(q.sx), su = sbi_xd_val(q.su);
    x = x0 + p->us * s + sx * (q.mx + l11 * z1);
    u = p->us + su * (q.mu + l21 * z1 + l22 * z2);
  } else {
    x = x0 + p->us * s + q.ox + sbi_xd_val(MUL(q.sx, X(l11 * z1)));
    u = p->us + q.ou + sbi_xd_val(MUL(q.su, X(l21 * z1 + l22 * z2)));
  }
  if (!isfinite(x) || !isfinite(u))
    return sbi_error(SB_ERANGE, __func__, "the draw (x = %g, u = %g) "
                     "overflows a double", x, u);
  *xs = x;
  *us = u;
  return SB_SUCCESS;
}

/* The mean's coefficients and the covariance in one pass (one gain, three
 * lags, where sb_langevin_bridge_moments at unit end states takes four).
 * From bridge_core's mean, with sx/su = tau:
 *   ax = k11, bx = tau (a_s - k11 a_h - k12 e_h), cx = tau k12,
 *   au = k21/tau, bu = e_s - k21 a_h - k22 e_h, cu = k22,
 * and the fluid velocity's from translation in time-independent drift
 * (x_s = x_0 + w s and u_s = w when the ends are the drift's):
 *   wx = s - ax dt - bx - cx, wu = 1 - au dt - bu - cu. */
int sbi_lh_bridge_coef(double tau, double B, double dt, double s,
                       sbi_lh_coef *c)
{
  const double hs = s / tau, hr = (dt - s) / tau, h = dt / tau;
  if (!(tau > 0.0) || !isfinite(tau) || !(B > 0.0) || !isfinite(B) ||
      !(hs >= HMIN) || !(hr >= HMIN) || !isfinite(h))
    return SB_EDOM;
  gain g;
  gain_init(&g, hs, hr, h);
  c->ax = g.k11;
  c->bx = tau * (g.as - g.k11 * g.ah - g.k12 * g.eh);
  c->cx = tau * g.k12;
  c->wx = s - c->ax * dt - c->bx - c->cx;
  c->au = g.k21 / tau;
  c->bu = g.es - g.k21 * g.ah - g.k22 * g.eh;
  c->cu = g.k22;
  c->wu = 1.0 - c->au * dt - c->bu - c->cu;
  const double B2 = B * B;
  c->vx = B2 * tau * tau * tau * (g.p22 / g.det);
  c->vu = B2 * tau * (g.p11 / g.det);
  c->cxu = B2 * tau * tau * (-g.p12 / g.det);
  return SB_SUCCESS;
}
