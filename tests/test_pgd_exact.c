/* test_pgd_exact.c — the exact solutions of 1-D pressureless gas dynamics
 * (lib/pgd/pgd_exact.c) against independent computations: an
 * event-driven sticky-particle simulation (delta-shock speed and mass),
 * the generalised Rankine-Hugoniot balances differentiated numerically,
 * conservation over a window, limits, brute-force quadrature of the error
 * norms, and moving particles for the smooth solutions. */
#include <check.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <smolbridge/pgd.h>
#include "refdata.h"
#include "spray_extreme.h"
#include "sweep.h"
#include "testutil.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* Event-driven sticky particles: N particles of mass rho_l h left of x0
 * (velocity u_l) and of mass rho_r h right of x0 (velocity u_r), spaced h,
 * centred in their slots.  Colliding particles merge, conserving mass and
 * momentum.  Returns the cluster's mass, position and velocity at t. */
static void sticky(double x0, double rl, double ul, double rr, double ur,
                   double h, double t, double *M, double *X, double *V)
{
  /* the innermost pair meets first */
  double tc = h / (ul - ur);
  double m = (rl + rr) * h, x = x0 - 0.5 * h + ul * tc;
  double v = (rl * ul + rr * ur) / (rl + rr);
  long kl = 1, kr = 1; /* next particles: slot k on each side */
  for (;;) {
    /* times at which the next left/right particle meets the cluster */
    double xl = x0 - ((double)kl + 0.5) * h, xr = x0 + ((double)kr + 0.5) * h;
    /* cluster: x + v (s - tc); left: xl + ul s */
    double sl = (x - v * tc - xl) / (ul - v);
    double sr = (xr - x + v * tc) / (v - ur);
    double s = sl < sr ? sl : sr;
    if (s > t)
      break;
    double pos = x + v * (s - tc);
    double mi = sl < sr ? rl * h : rr * h, ui = sl < sr ? ul : ur;
    v = (m * v + mi * ui) / (m + mi);
    m += mi;
    x = pos;
    tc = s;
    if (sl < sr)
      kl++;
    else
      kr++;
  }
  *M = m;
  *X = x + v * (t - tc);
  *V = v;
}

START_TEST(delta_vs_sticky_particles)
{
  const double cases[][4] = {{1, 1, 1, -1}, {1, 2, 0.25, -1},
                             {0.3, 0.5, 4, -2}, {2, 3, 1, 2.5}};
  const double h = 2e-5, t = 0.3;
  for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
    const double *q = cases[c];
    sb_pgd_riemann rp = {0.1, q[0], q[1], q[2], q[3], INFINITY, 0};
    sb_pgd_riemann_sol w;
    ck_assert_int_eq(sb_pgd_riemann_solve(&rp, t, &w), SB_SUCCESS);
    ck_assert_int_eq(w.type, SB_PGD_WAVE_DELTA);
    double M, X, V;
    sticky(rp.x0, q[0], q[1], q[2], q[3], h, t, &M, &X, &V);
    /* discreteness: at most one particle per side, one spacing */
    double mtol = 2 * (q[0] + q[2]) * h;
    ck_assert_abs(w.mass, M, mtol);
    ck_assert_abs(w.xl, X, 4 * h);
    ck_assert_abs(w.vel, V, 1e-3);
    ck_assert_rel(sb_pgd_delta_speed(q[0], q[1], q[2], q[3]), w.vel,
                  TOL_TIGHT);
  }
}
END_TEST

/* The generalised Rankine-Hugoniot balances, from the solution at t +- e:
 * dw/dt = rho_l (u_l - sigma) + rho_r (sigma - u_r) and
 * d(w sigma)/dt = rho_l u_l (u_l - sigma) + rho_r u_r (sigma - u_r). */
START_TEST(delta_rankine_hugoniot)
{
  const double cases[][4] = {{1, 2, 0.25, -1}, {3, 1, 0.5, 0.2},
                             {0.01, 10, 100, -1}};
  for (size_t c = 0; c < 3; c++) {
    const double *q = cases[c];
    sb_pgd_riemann rp = {0, q[0], q[1], q[2], q[3], INFINITY, 0};
    const double t = 0.7, e = 1e-4;
    sb_pgd_riemann_sol a, b, m;
    sb_pgd_riemann_solve(&rp, t - e, &a);
    sb_pgd_riemann_solve(&rp, t + e, &b);
    sb_pgd_riemann_solve(&rp, t, &m);
    double sig = (b.xl - a.xl) / (2 * e);
    double dw = (b.mass - a.mass) / (2 * e);
    double dp = (b.mass * b.vel - a.mass * a.vel) / (2 * e);
    ck_assert_rel(sig, m.vel, 1e-9);
    ck_assert_rel(dw, q[0] * (q[1] - sig) + q[2] * (sig - q[3]), 1e-9);
    ck_assert_rel(dp, q[0] * q[1] * (q[1] - sig) + q[2] * q[3] * (sig - q[3]),
                  1e-9);
  }
}
END_TEST

/* Mass and momentum in a window enclosing every wave change only by the
 * fluxes through its ends (and, with drag, by the drag impulse). */
START_TEST(riemann_conservation)
{
  const double cases[][4] = {{1, 2, 0.25, -1}, {1, -1, 2, 1.5},
                             {0.5, 0.3, 0.5, 0.3}, {1, 1, 0, 0},
                             {0, 0, 2, -1}};
  const double a = -3, b = 3, t = 0.8;
  for (size_t c = 0; c < 5; c++) {
    const double *q = cases[c];
    sb_pgd_riemann rp = {0.2, q[0], q[1], q[2], q[3], INFINITY, 0};
    double m0, p0, m1, p1;
    sb_pgd_riemann_integral(&rp, 0, a, b, &m0, &p0);
    sb_pgd_riemann_integral(&rp, t, a, b, &m1, &p1);
    ck_assert_rel(m1, m0 + t * (q[0] * q[1] - q[2] * q[3]), 1e-14);
    ck_assert_abs(p1, p0 + t * (q[0] * q[1] * q[1] - q[2] * q[3] * q[3]),
                  1e-13 * (1 + fabs(p1)));
  }
  /* with drag: d/dt (momentum) = end fluxes + (U M - P)/tau, checked by
   * central differences */
  sb_pgd_riemann rp = {0.2, 1, 2, 0.5, -1, 0.4, 0.3};
  const double e = 1e-5;
  double ma, pa, mb, pb, m, p;
  sb_pgd_riemann_integral(&rp, t - e, a, b, &ma, &pa);
  sb_pgd_riemann_integral(&rp, t + e, a, b, &mb, &pb);
  sb_pgd_riemann_integral(&rp, t, a, b, &m, &p);
  double ul, ur;
  sb_pgd_riemann_eval(&rp, a, t, NULL, &ul);
  sb_pgd_riemann_eval(&rp, b, t, NULL, &ur);
  double flux_m = rp.rho_l * ul - rp.rho_r * ur;
  double flux_p = rp.rho_l * ul * ul - rp.rho_r * ur * ur;
  ck_assert_rel((mb - ma) / (2 * e), flux_m, 1e-8);
  ck_assert_rel((pb - pa) / (2 * e), flux_p + (rp.ugas * m - p) / rp.tau,
                1e-7);
}
END_TEST

START_TEST(riemann_limits)
{
  sb_pgd_riemann_sol w;
  /* equal densities: the mean velocity; one side nearly empty: that side
   * stops mattering; equal velocities: no delta */
  ck_assert_rel(sb_pgd_delta_speed(2, 3, 2, -1), 1.0, TOL_TIGHT);
  ck_assert_rel(sb_pgd_delta_speed(1, 3, 1e-20, -1), 3.0, 1e-9);
  ck_assert_abs(sb_pgd_delta_mass_rate(1, 3, 1e-20, -1), 0.0, 1e-9);
  ck_assert(isnan(sb_pgd_delta_speed(1, 1, 1, 1)));
  ck_assert(isnan(sb_pgd_delta_mass_rate(1, -1, 1, 1)));
  sb_pgd_riemann rp = {0, 1, 0.5, 2, 0.5, INFINITY, 0};
  sb_pgd_riemann_solve(&rp, 2, &w);
  ck_assert_int_eq(w.type, SB_PGD_WAVE_CONTACT);
  ck_assert_rel(w.xl, 1.0, TOL_TIGHT);
  /* vacuum between diverging states */
  rp = (sb_pgd_riemann){0, 1, -1, 2, 0.5, INFINITY, 0};
  sb_pgd_riemann_solve(&rp, 2, &w);
  ck_assert_int_eq(w.type, SB_PGD_WAVE_VACUUM);
  ck_assert_rel(w.xl, -2.0, TOL_TIGHT);
  ck_assert_rel(w.xr, 1.0, TOL_TIGHT);
  double r, u;
  sb_pgd_riemann_eval(&rp, 0, 2, &r, &u);
  ck_assert(r == 0 && u == 0);
  sb_pgd_riemann_eval(&rp, 1.5, 2, &r, &u);
  ck_assert(r == 2 && u == 0.5);
  /* right side vacuum: the left state advances as a contact */
  rp = (sb_pgd_riemann){0, 1, 1, 0, -5, INFINITY, 0};
  sb_pgd_riemann_solve(&rp, 2, &w);
  ck_assert_int_eq(w.type, SB_PGD_WAVE_CONTACT);
  ck_assert_rel(w.xl, 2.0, TOL_TIGHT);
  /* drag: tau -> 0 leaves every velocity at ugas (the delta too), and
   * tau -> infinity is the drag-free solution */
  rp = (sb_pgd_riemann){0, 1, 2, 0.25, -1, 1e-6, 0.3};
  sb_pgd_riemann_solve(&rp, 1, &w);
  ck_assert_rel(w.vel, 0.3, 1e-12);
  ck_assert_rel(w.ul, 0.3, 1e-12);
  ck_assert_rel(w.xl, 0.3 + 0.7e-6, 1e-9); /* sigma' = 0.7, s = tau */
  rp.tau = 1e12;
  sb_pgd_riemann_sol f;
  sb_pgd_riemann rf = rp;
  rf.tau = INFINITY;
  sb_pgd_riemann_solve(&rp, 1, &w);
  sb_pgd_riemann_solve(&rf, 1, &f);
  ck_assert_rel(w.xl, f.xl, 1e-9);
  ck_assert_rel(w.mass, f.mass, 1e-9);
  /* errors */
  rp.rho_l = -1;
  ck_assert_int_eq(sb_pgd_riemann_solve(&rp, 1, &w), SB_EDOM);
  rp.rho_l = 1;
  rp.tau = 0;
  ck_assert_int_eq(sb_pgd_riemann_solve(&rp, 1, &w), SB_EDOM);
  rp.tau = INFINITY;
  ck_assert_int_eq(sb_pgd_riemann_solve(&rp, -1, &w), SB_EDOM);
}
END_TEST

/* The exact L1 and W1 of sb_pgd_riemann_error against brute force. */
START_TEST(riemann_error_norms)
{
  sb_pgd_riemann rps[2] = {{0.43, 1, 2, 0.25, -1, INFINITY, 0},
                           {0.43, 1, -1, 0.5, 1, INFINITY, 0}};
  const size_t n = 37;
  const double a = 0.01, h = 1.0 / n, t = 0.13;
  double rho[37];
  for (int c = 0; c < 2; c++) {
    for (size_t i = 0; i < n; i++)
      rho[i] = 0.8 + 0.5 * sin(3.0 * (double)i) * sin(3.0 * (double)i);
    double l1, w1;
    ck_assert_int_eq(sb_pgd_riemann_error(&rps[c], t, a, h, n, rho, &l1, &w1),
                     SB_SUCCESS);
    /* brute force from point values (midpoint rule) plus the delta */
    sb_pgd_riemann_sol w;
    sb_pgd_riemann_solve(&rps[c], t, &w);
    const size_t k = 2000000;
    double dx = (double)n * h / (double)k, sw = 0, Me = 0, cell[37] = {0};
    int added = w.type != SB_PGD_WAVE_DELTA;
    for (size_t j = 0; j < k; j++) {
      double x = a + ((double)j + 0.5) * dx, r;
      size_t i = (size_t)((x - a) / h);
      if (!added && x - 0.5 * dx >= w.xl) {
        Me += w.mass;
        cell[i] += w.mass;
        added = 1;
      }
      sb_pgd_riemann_eval(&rps[c], x, t, &r, NULL);
      Me += r * dx;
      cell[i] += r * dx;
      double Mn = 0;
      for (size_t m = 0; m < i; m++)
        Mn += rho[m] * h;
      Mn += rho[i] * (x + 0.5 * dx - a - (double)i * h);
      sw += fabs(Mn - Me) * dx;
    }
    double sl = 0;
    for (size_t i = 0; i < n; i++)
      sl += fabs(rho[i] * h - cell[i]);
    ck_assert_rel(w1, sw, 1e-5);
    ck_assert_rel(l1, sl, 1e-5);
  }
}
END_TEST

/* ------------------------------------------------------------ smooth */

static double r0(double x, void *d) { (void)d; return 1 + 0.5 * sin(2 * M_PI * x); }
static double m0(double x, void *d)
{
  (void)d;
  return x - 0.5 * cos(2 * M_PI * x) / (2 * M_PI);
}
static double u0(double x, void *d) { (void)d; return 1 + 0.2 * sin(2 * M_PI * x); }

/* Mass in [a, b] by exact particle motion: N particles of mass rho0 dxi
 * (midpoint rule over [a - 2, b + 2]) counted where they are at t. */
static double particle_mass(const sb_pgd_smooth *s, double t, double a,
                            double b, double *mom)
{
  const size_t N = 400000;
  double lo = a - 2, hi = b + 2, dxi = (hi - lo) / (double)N, m = 0, p = 0;
  double sf = isinf(s->tau) ? t : -s->tau * expm1(-t / s->tau);
  double e = isinf(s->tau) ? 1 : exp(-t / s->tau);
  double U = isinf(s->tau) ? 0 : s->ugas;
  for (size_t k = 0; k < N; k++) {
    double xi = lo + ((double)k + 0.5) * dxi;
    double v = s->u0(xi, NULL);
    double x = xi + U * t + (v - U) * sf;
    if (x >= a && x < b) {
      m += s->rho0(xi, NULL) * dxi;
      p += s->rho0(xi, NULL) * dxi * (U + (v - U) * e);
    }
  }
  *mom = p;
  return m;
}

START_TEST(smooth_vs_particles)
{
  sb_pgd_smooth s = {r0, m0, u0, NULL, INFINITY, 0};
  for (int drag = 0; drag < 2; drag++) {
    s.tau = drag ? 0.4 : INFINITY;
    s.ugas = drag ? -0.5 : 0;
    const double t = 0.5;
    double xi;
    ck_assert_int_eq(sb_pgd_smooth_foot(&s, 0.3, 0, &xi), SB_SUCCESS);
    ck_assert_rel(xi, 0.3, TOL_TIGHT);
    double m, p, mp, pp;
    ck_assert_int_eq(sb_pgd_smooth_integral(&s, t, 0.2, 0.45, &m, &p),
                     SB_SUCCESS);
    mp = particle_mass(&s, t, 0.2, 0.45, &pp);
    /* particle discreteness: one particle (mass <= 1.5 dxi) per edge */
    ck_assert_abs(m, mp, 2 * 1.5 * 4.25 / 400000);
    ck_assert_abs(p, pp, 2 * 1.5 * 1.2 * 4.25 / 400000);
    /* one period holds the mass of one period */
    ck_assert_int_eq(sb_pgd_smooth_integral(&s, t, -0.37, 0.63, &m, NULL),
                     SB_SUCCESS);
    ck_assert_rel(m, 1.0, 1e-13);
  }
}
END_TEST

/* ------------------------------------------------- extreme arguments */

typedef sbt_xfn xfn;

/* a = x0, rho_l, u_l, rho_r, u_r, tau, ugas, t; outputs xl, xr, mass, ul,
 * ur, vel (delta only) */
static int x_solve(const double *a, double *out, int *n, const char **nm)
{
  sb_pgd_riemann rp = {a[0], a[1], a[2], a[3], a[4], a[5], a[6]};
  sb_pgd_riemann_sol w;
  *nm = "sb_pgd_riemann_solve";
  int st = sb_pgd_riemann_solve(&rp, a[7], &w);
  *n = 6;
  if (st) /* w is not written on an error */
    return st;
  out[0] = w.xl, out[1] = w.xr, out[2] = w.mass, out[3] = w.ul;
  out[4] = w.ur, out[5] = w.type == SB_PGD_WAVE_DELTA ? w.vel : 0.0;
  return st;
}

/* a = x0, rho_l, u_l, rho_r, u_r, tau, ugas, t, x */
static int x_eval(const double *a, double *out, int *n, const char **nm)
{
  sb_pgd_riemann rp = {a[0], a[1], a[2], a[3], a[4], a[5], a[6]};
  *nm = "sb_pgd_riemann_eval";
  *n = 2;
  return sb_pgd_riemann_eval(&rp, a[8], a[7], &out[0], &out[1]);
}

/* a = x0, rho_l, u_l, rho_r, u_r, tau, ugas, t, a, b */
static int x_integral(const double *a, double *out, int *n, const char **nm)
{
  sb_pgd_riemann rp = {a[0], a[1], a[2], a[3], a[4], a[5], a[6]};
  *nm = "sb_pgd_riemann_integral";
  *n = 2;
  return sb_pgd_riemann_integral(&rp, a[7], a[8], a[9], &out[0], &out[1]);
}

/* a = x0, rho_l, u_l, rho_r, u_r, tau, ugas, t, a, h, rho[0..1] */
static int x_error(const double *a, double *out, int *n, const char **nm)
{
  sb_pgd_riemann rp = {a[0], a[1], a[2], a[3], a[4], a[5], a[6]};
  *nm = "sb_pgd_riemann_error";
  *n = 2;
  return sb_pgd_riemann_error(&rp, a[7], a[8], a[9], 2, &a[10], &out[0],
                              &out[1]);
}

#define XPLAIN(NAME, FN)                                                    \
  static int NAME(const double *a, double *out, int *n, const char **nm)   \
  {                                                                         \
    *nm = #FN;                                                              \
    sb_clear_error();                                                       \
    out[0] = FN(a[0], a[1], a[2], a[3]);                                    \
    *n = 1;                                                                 \
    return sb_last_status();                                                \
  }
XPLAIN(x_dspeed, sb_pgd_delta_speed)
XPLAIN(x_dmass, sb_pgd_delta_mass_rate)

/* a = tau, ugas, t, x */
static int x_foot(const double *a, double *out, int *n, const char **nm)
{
  sb_pgd_smooth s = {r0, m0, u0, NULL, a[0], a[1]};
  *nm = "sb_pgd_smooth_foot";
  *n = 1;
  out[0] = 0.0;
  return sb_pgd_smooth_foot(&s, a[3], a[2], &out[0]);
}

/* a = tau, ugas, t, a, b */
static int x_smooth_int(const double *a, double *out, int *n,
                        const char **nm)
{
  sb_pgd_smooth s = {r0, m0, u0, NULL, a[0], a[1]};
  *nm = "sb_pgd_smooth_integral";
  *n = 2;
  return sb_pgd_smooth_integral(&s, a[2], a[3], a[4], &out[0], &out[1]);
}

/* A row of tests/data/spray_extreme.csv (spray_extreme.h) of the delta
 * (kinds 7, 8) or of sb_pgd_riemann_integral (13, 14): its value, to
 * 1e-13 relative; 0 for the spray kinds (test_spray.c). */
static double pgd_row(int kind, const double *a, double *got)
{
  if (kind != 7 && kind != 8 && kind != 13 && kind != 14)
    return 0.0;
  if (kind >= 13) {
    double mq[2] = {NAN, NAN};
    sb_pgd_riemann rp = {0.0, a[0], a[1], a[2], a[3], INFINITY, 0.0};
    ck_assert_int_eq(sb_pgd_riemann_integral(&rp, a[4], a[5], a[6], &mq[0],
                                             &mq[1]),
                     SB_SUCCESS);
    *got = mq[kind - 13];
  } else {
    *got = kind == 7 ? sb_pgd_delta_mass_rate(a[0], a[1], a[2], a[3])
                     : sb_pgd_delta_speed(a[0], a[1], a[2], a[3]);
  }
  return 1e-13;
}

/* Each argument of each exact-solution function in turn over +-1e-320,
 * +-1e-300, 0, +-1e300, +-DBL_MAX, +-inf, NaN (the others ordinary): the
 * outputs are finite (masses and norms >= 0) with status 0, or the
 * status is SB_EDOM/SB_ERANGE, a plain value NaN and the message names
 * the public function. */
START_TEST(extreme_arguments)
{
  static const struct {
    xfn f;
    int n;     /* arguments */
    int nn[6]; /* which outputs are >= 0 */
    double a[12];
  } k[] = {
      {x_solve, 8, {0, 0, 1, 0, 0, 0},
       {0.1, 1.0, 1.5, 2.0, -0.5, 0.7, 0.3, 0.4}},
      {x_solve, 8, {0, 0, 1, 0, 0, 0},
       {0.1, 1.0, -0.5, 2.0, 1.5, INFINITY, 0.3, 0.4}},
      {x_eval, 9, {1, 0, 0, 0, 0, 0},
       {0.1, 1.0, 1.5, 2.0, -0.5, 0.7, 0.3, 0.4, 0.2}},
      {x_integral, 10, {1, 0, 0, 0, 0, 0},
       {0.1, 1.0, 1.5, 2.0, -0.5, 0.7, 0.3, 0.4, -0.3, 0.9}},
      {x_error, 12, {1, 1, 0, 0, 0, 0},
       {0.1, 1.0, 1.5, 2.0, -0.5, 0.7, 0.3, 0.4, -0.3, 0.5, 1.1, 1.9}},
      {x_dspeed, 4, {0, 0, 0, 0, 0, 0}, {1.0, 1.5, 2.0, -0.5}},
      {x_dmass, 4, {1, 0, 0, 0, 0, 0}, {1.0, 1.5, 2.0, -0.5}},
      {x_foot, 4, {0, 0, 0, 0, 0, 0}, {0.4, -0.5, 0.5, 0.3}},
      {x_smooth_int, 5, {1, 0, 0, 0, 0, 0}, {0.4, -0.5, 0.5, 0.2, 0.45}},
  };
  int nbad = 0; /* every failure is printed, then counted */
  const int na = (int)(sizeof k[0].a / sizeof k[0].a[0]);
  for (size_t f = 0; f < sizeof k / sizeof k[0]; f++) {
    unsigned nonneg = 0;
    for (size_t j = 0; j < sizeof k[f].nn / sizeof k[f].nn[0]; j++)
      nonneg |= k[f].nn[j] ? 1u << j : 0u;
    /* (the momentum quadrature of sb_pgd_smooth_integral over ~1e300
     * periods of rho0 u0: SB_EMAXITER, documented; only the delta's speed
     * and mass rate have a plain value) */
    nbad += sbt_sweep_vec(k[f].f, k[f].a, na, k[f].n, nonneg,
                          k[f].f == x_smooth_int ? SB_EMAXITER : 0,
                          k[f].f == x_dspeed || k[f].f == x_dmass
                              ? SBT_SWEEP_NAN
                              : 0,
                          f);
  }
  ck_assert_int_eq(nbad, 0);

  /* The delta at corners where sqrt(rho) u or the mass-rate product
   * leaves the double range: kinds 7 (mass rate) and 8 (speed) of
   * tests/data/spray_extreme.csv (gen_spray_ref.py, mpmath); the mass
   * (13) and momentum (14) of sb_pgd_riemann_integral where rho u, rho u
   * length or b - a over/underflows (SB_ERANGE or a momentum of 0
   * before), or a wave position or the delta's mass beyond DBL_MAX lies
   * outside [a, b] (SB_ERANGE before). */
  ck_assert_int_ge(sbt_spray_extreme(pgd_row), 8 + 11);

  /* vacuum of infinite extent holds no mass: an infinite a or b is
   * SB_ERANGE only where the density there is > 0 */
  sb_pgd_riemann vac = {0.0, 0.0, 1.0, 2.0, 1.0, INFINITY, 0.0};
  double m = NAN, q = NAN;
  ck_assert_int_eq(sb_pgd_riemann_integral(&vac, 0.5, -INFINITY, 1.5, &m, &q),
                   SB_SUCCESS);
  ck_assert_rel(m, 2.0, 4 * DBL_EPSILON);  /* 2 (1.5 - 0.5) */
  ck_assert_rel(q, 2.0, 4 * DBL_EPSILON);
  ck_assert_int_eq(sb_pgd_riemann_integral(&vac, 0.5, -1.0, INFINITY, &m, &q),
                   SB_ERANGE);

  /* wave positions beyond DBL_MAX (rows above, and here): a contact at
   * x = 1e200 1e110 = 1e310 against vacuum on its right holds the mass
   * 1e-300 (1e310 - 0) = 1e10 and momentum 1e10 1e200 in [0, +inf) */
  sb_pgd_riemann far = {0.0, 1e-300, 1e200, 0.0, 0.0, INFINITY, 0.0};
  ck_assert_int_eq(sb_pgd_riemann_integral(&far, 1e110, 0.0, INFINITY, &m,
                                           &q),
                   SB_SUCCESS);
  ck_assert_rel(m, 1e10, 8 * DBL_EPSILON);
  ck_assert_rel(q, 1e210, 8 * DBL_EPSILON);
  /* the mirror image: rho_r over (-1e310, 0] */
  sb_pgd_riemann farl = {0.0, 0.0, 0.0, 1e-300, -1e200, INFINITY, 0.0};
  ck_assert_int_eq(sb_pgd_riemann_integral(&farl, 1e110, -INFINITY, 0.0, &m,
                                           &q),
                   SB_SUCCESS);
  ck_assert_rel(m, 1e10, 8 * DBL_EPSILON);
  ck_assert_rel(q, -1e210, 8 * DBL_EPSILON);
  /* ... but a delta inside [a, b] whose mass exceeds DBL_MAX is still
   * SB_ERANGE: at (1e10 - 1)/2 with mass 1e300 (1e10 + 1) */
  sb_pgd_riemann big = {0.0, 1e300, 1e10, 1e300, -1.0, INFINITY, 0.0};
  ck_assert_int_eq(sb_pgd_riemann_integral(&big, 1.0, 4e9, 6e9, &m, &q),
                   SB_ERANGE);
  /* x0 + u t where u t = 1.5e308 overflows but the position 5e307 does
   * not (the solve itself) */
  sb_pgd_riemann cancel = {-1e308, 1.0, 1e300, 0.0, 0.0, INFINITY, 0.0};
  sb_pgd_riemann_sol sol;
  ck_assert_int_eq(sb_pgd_riemann_solve(&cancel, 1.5e8, &sol), SB_SUCCESS);
  ck_assert_rel(sol.xl, 5e307, 8 * DBL_EPSILON);
}
END_TEST

/* _eval and _error where the waves lie beyond +-DBL_MAX or the delta's
 * mass exceeds DBL_MAX while the states are doubles (SB_ERANGE before,
 * as for _integral until it was extended).  A delta-shock in a uniform
 * gas: U = 1e300, u_l = 3e300, u_r = -1e300, rho_l = 2, rho_r = 1/2,
 * tau = t = 1e10.  In the gas frame v_l = -v_r = 2e300, so the delta
 * moves at 2e300/3 from x = U t = 1e310 and carries the mass
 * 4e300 s = 2.5e310 (s = tau (1 - 1/e)): both beyond DBL_MAX.  The
 * states' velocities U + v e^{-1}, mpmath (40 digits) from the double
 * inputs:
 *   ul = 1.7357588823428847343e300, ur = 2.6424111765711537068e299.
 * The mirror image (U, u_l, u_r negated, rho_l and rho_r swapped) puts
 * the delta beyond -DBL_MAX. */
START_TEST(waves_beyond_dbl_max)
{
  const double ul = 1.7357588823428847343e300, ur = 2.6424111765711537068e299;
  const double tol = 8 * DBL_EPSILON;
  sb_pgd_riemann rp = {0.0, 2.0, 3e300, 0.5, -1e300, 1e10, 1e300};
  sb_pgd_riemann mir = {0.0, 0.5, 1e300, 2.0, -3e300, 1e10, -1e300};
  const double t = 1e10;
  double r = NAN, u = NAN;
  sb_pgd_riemann_sol sol;
  ck_assert_int_eq(sb_pgd_riemann_solve(&rp, t, &sol), SB_ERANGE);

  /* point values: left of the delta everywhere up to +DBL_MAX, right of
   * it only at x = +inf (and the mirror image) */
  const double xs[] = {-INFINITY, -DBL_MAX, 0.0, DBL_MAX};
  for (size_t k = 0; k < sizeof xs / sizeof xs[0]; k++) {
    ck_assert_int_eq(sb_pgd_riemann_eval(&rp, xs[k], t, &r, &u), SB_SUCCESS);
    ck_assert(r == 2.0);
    ck_assert_rel(u, ul, tol);
    ck_assert_int_eq(sb_pgd_riemann_eval(&mir, -xs[k], t, &r, &u),
                     SB_SUCCESS);
    ck_assert(r == 2.0);
    ck_assert_rel(u, -ul, tol);
  }
  ck_assert_int_eq(sb_pgd_riemann_eval(&rp, INFINITY, t, &r, &u), SB_SUCCESS);
  ck_assert(r == 0.5);
  ck_assert_rel(u, ur, tol);
  ck_assert_int_eq(sb_pgd_riemann_eval(&mir, -INFINITY, t, &r, &u),
                   SB_SUCCESS);
  ck_assert(r == 0.5);
  ck_assert_rel(u, -ur, tol);

  /* norms on [0, 1] where the exact density is 2: cells of densities 1
   * and 3 (h = 1/2) hold the masses 1/2 and 3/2 against 1 and 1, so
   * l1 = 1; M_num - M_exact = -x on the first cell and x - 1 on the
   * second, so w1 = 2 (1/2)^2/2 = 1/4 (by hand) */
  const double cells[2] = {1.0, 3.0};
  double l1 = NAN, w1 = NAN;
  ck_assert_int_eq(sb_pgd_riemann_error(&rp, t, 0.0, 0.5, 2, cells, &l1,
                                        &w1),
                   SB_SUCCESS);
  ck_assert_rel(l1, 1.0, 4 * DBL_EPSILON);
  ck_assert_rel(w1, 0.25, 4 * DBL_EPSILON);
  l1 = w1 = NAN;
  ck_assert_int_eq(sb_pgd_riemann_error(&mir, t, 0.0, 0.5, 2, cells, &l1,
                                        &w1),
                   SB_SUCCESS);
  ck_assert_rel(l1, 1.0, 4 * DBL_EPSILON);
  ck_assert_rel(w1, 0.25, 4 * DBL_EPSILON);

  /* a delta at a finite place whose mass exceeds DBL_MAX: at
   * (1e10 - 1)/2 with mass 1e300 (1e10 + 1) at t = 1 (no drag).  Point
   * values either side are the states; the norms over cells holding it
   * overflow (SB_ERANGE), over cells beside it they are exact */
  sb_pgd_riemann big = {0.0, 1e300, 1e10, 1e300, -1.0, INFINITY, 0.0};
  ck_assert_int_eq(sb_pgd_riemann_eval(&big, 0.0, 1.0, &r, &u), SB_SUCCESS);
  ck_assert(r == 1e300 && u == 1e10);
  ck_assert_int_eq(sb_pgd_riemann_eval(&big, 6e9, 1.0, &r, &u), SB_SUCCESS);
  ck_assert(r == 1e300 && u == -1.0);
  const double dense[2] = {1e300, 1e300};
  ck_assert_int_eq(sb_pgd_riemann_error(&big, 1.0, 4e9, 1e9, 2, dense, &l1,
                                        &w1),
                   SB_ERANGE);
  ck_assert_int_eq(sb_pgd_riemann_error(&big, 1.0, -1.0, 0.5, 2, dense, &l1,
                                        &w1),
                   SB_SUCCESS);
  ck_assert(l1 == 0.0 && w1 == 0.0);

  /* the states' velocities themselves out of range stay SB_ERANGE:
   * u_l - ugas = 2 DBL_MAX */
  sb_pgd_riemann fast = {0.0, 1.0, DBL_MAX, 1.0, DBL_MAX, 1.0, -DBL_MAX};
  ck_assert_int_eq(sb_pgd_riemann_eval(&fast, 0.0, 1.0, &r, &u), SB_ERANGE);
  ck_assert_int_eq(sb_pgd_riemann_error(&fast, 1.0, 0.0, 0.5, 2, cells, &l1,
                                        &w1),
                   SB_ERANGE);
}
END_TEST

Suite *suite(void)
{
  Suite *s = suite_create("pgd_exact");
  TCase *tc = tcase_create("riemann");
  tcase_add_test(tc, delta_vs_sticky_particles);
  tcase_add_test(tc, delta_rankine_hugoniot);
  tcase_add_test(tc, riemann_conservation);
  tcase_add_test(tc, riemann_limits);
  suite_add_tcase(s, tc);
  tc = tcase_create("norms");
  tcase_set_timeout(tc, 30);
  tcase_add_test(tc, riemann_error_norms);
  tcase_add_test(tc, smooth_vs_particles);
  tcase_add_test(tc, extreme_arguments);
  tcase_add_test(tc, waves_beyond_dbl_max);
  suite_add_tcase(s, tc);
  return s;
}

int main(void) { return sbt_run_suite(suite()); }
