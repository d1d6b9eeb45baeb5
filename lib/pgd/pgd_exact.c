/* pgd_exact.c — exact solutions of 1-D pressureless gas dynamics: the
 * Riemann problem (contact, vacuum, delta-shock) with optional uniform
 * drag, its error norms against a cell field, and smooth solutions by
 * characteristics.
 *
 * The delta-shock: mass w(t) at x(t) moving with sigma.  The generalised
 * Rankine-Hugoniot conditions (Bouchut 1994; Sheng & Zhang 1999) are the
 * mass and momentum balances of the point:
 *   dw/dt       = rho_l (u_l - sigma) + rho_r (sigma - u_r),
 *   d(w sigma)/dt = rho_l u_l (u_l - sigma) + rho_r u_r (sigma - u_r).
 * With w(0) = 0 and sigma constant, eliminating dw/dt gives
 *   rho_l (u_l - sigma)^2 = rho_r (sigma - u_r)^2,
 * whose root between u_r and u_l is the sqrt(rho)-weighted mean of u_l
 * and u_r; then w = sqrt(rho_l rho_r)(u_l - u_r) t.  docs/pgd.md has the
 * derivation; tests/test_pgd_exact.c checks it against an event-driven
 * sticky-particle simulation.
 *
 * Drag towards a uniform gas velocity U: in xi = x - U t, v = (u - U)
 * e^{t/tau} and the time s = tau (1 - e^{-t/tau}) the equations become the
 * drag-free system (the drag force is linear in the momentum, so it
 * commutes with sticky collisions); every solution maps back. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include <gsl/gsl_integration.h>
#include <gsl/gsl_errno.h>
#include <smolbridge/pgd.h>
#include "common/internal.h"
#include "common/numutil.h"

/* Drag time map: s(t), e(t) = e^{-t/tau} (s = t, e = 1 without drag). */
static void drag_map(double tau, double t, double *s, double *e)
{
  if (isinf(tau)) {
    *s = t;
    *e = 1.0;
  } else {
    *s = -tau * expm1(-t / tau);
    *e = exp(-t / tau);
  }
}

static int delta_dom(double rho_l, double u_l, double rho_r, double u_r)
{
  return rho_l > 0 && rho_r > 0 && u_l > u_r && isfinite(rho_l) &&
         isfinite(rho_r) && isfinite(u_l) && isfinite(u_r);
}

/* The sqrt(rho)-weighted mean of u_l and u_r (valid arguments): a mean,
 * so representable; through the weights where a u_l + b u_r overflows. */
static double delta_speed(double rho_l, double u_l, double rho_r, double u_r)
{
  double a = sqrt(rho_l), b = sqrt(rho_r);
  double sig = (a * u_l + b * u_r) / (a + b);
  if (!isfinite(sig)) {
    double wa = a / (a + b), wb = b / (a + b);
    sig = wa * u_l + wb * u_r;
  }
  return sig;
}

/* sqrt(rho_l rho_r)(u_l - u_r) (valid arguments) with an extended
 * exponent: the plain product where nothing leaves the range (same
 * bits), else formed as m 2^e. */
static sbi_xd delta_mass_rate_xd(double rho_l, double u_l, double rho_r,
                                 double u_r)
{
  double sa = sqrt(rho_l), sb = sqrt(rho_r), p = sa * sb, du = u_l - u_r;
  double m = p * du;
  if (p >= DBL_MIN && m >= DBL_MIN && m <= DBL_MAX)
    return sbi_xd_of(m);
  sbi_xd d = isinf(du) ? sbi_xd_mul(sbi_xd_of(0.5 * u_l - 0.5 * u_r),
                                    sbi_xd_of(2.0))
                       : sbi_xd_of(du);
  return sbi_xd_mul(sbi_xd_mul(sbi_xd_of(sa), sbi_xd_of(sb)), d);
}

/* The same as a double: inf if the rate exceeds DBL_MAX. */
static double delta_mass_rate(double rho_l, double u_l, double rho_r,
                              double u_r)
{
  return sbi_xd_val(delta_mass_rate_xd(rho_l, u_l, rho_r, u_r));
}

double sb_pgd_delta_speed(double rho_l, double u_l, double rho_r, double u_r)
{
  if (!delta_dom(rho_l, u_l, rho_r, u_r)) {
    sbi_error(SB_EDOM, __func__, "need finite rho_l, rho_r > 0 and u_l > "
              "u_r (rho_l = %g, u_l = %g, rho_r = %g, u_r = %g)", rho_l, u_l,
              rho_r, u_r);
    return NAN;
  }
  return delta_speed(rho_l, u_l, rho_r, u_r);
}

double sb_pgd_delta_mass_rate(double rho_l, double u_l, double rho_r,
                              double u_r)
{
  if (!delta_dom(rho_l, u_l, rho_r, u_r)) {
    sbi_error(SB_EDOM, __func__, "need finite rho_l, rho_r > 0 and u_l > "
              "u_r (rho_l = %g, u_l = %g, rho_r = %g, u_r = %g)", rho_l, u_l,
              rho_r, u_r);
    return NAN;
  }
  double m = delta_mass_rate(rho_l, u_l, rho_r, u_r);
  if (isinf(m)) {
    sbi_error(SB_ERANGE, __func__, "sqrt(rho_l rho_r)(u_l - u_r) overflows "
              "(rho_l = %g, u_l = %g, rho_r = %g, u_r = %g)", rho_l, u_l,
              rho_r, u_r);
    return NAN;
  }
  return m;
}

/* Every output of a solved pattern finite, else SB_ERANGE. */
static int sol_ok(const sb_pgd_riemann_sol *w, const char *f)
{
  if (!isfinite(w->xl) || !isfinite(w->xr) || !isfinite(w->mass) ||
      !isfinite(w->ul) || !isfinite(w->ur) ||
      (w->type == SB_PGD_WAVE_DELTA && !isfinite(w->vel)))
    return sbi_error(SB_ERANGE, f, "the wave positions, velocities or the "
                     "delta's mass leave the double range (xl = %g, xr = %g, "
                     "mass = %g)", w->xl, w->xr, w->mass);
  return SB_SUCCESS;
}

static int check_rp(const sb_pgd_riemann *rp, double t, const char *f)
{
  if (!rp)
    return sbi_error(SB_EINVAL, f, "NULL problem");
  if (!(rp->rho_l >= 0) || !(rp->rho_r >= 0) || !isfinite(rp->rho_l) ||
      !isfinite(rp->rho_r))
    return sbi_error(SB_EDOM, f, "rho_l = %g, rho_r = %g: must be >= 0 and "
                     "finite", rp->rho_l, rp->rho_r);
  if (!isfinite(rp->u_l) || !isfinite(rp->u_r) || !isfinite(rp->x0) ||
      !isfinite(rp->ugas))
    return sbi_error(SB_EDOM, f, "x0, u_l, u_r, ugas must be finite");
  if (!(rp->tau > 0))
    return sbi_error(SB_EDOM, f, "tau = %g: must be > 0 (INFINITY: no "
                     "drag)", rp->tau);
  if (!(t >= 0) || !isfinite(t))
    return sbi_error(SB_EDOM, f, "t = %g: must be >= 0 and finite", t);
  return SB_SUCCESS;
}

/* A wave position x0 + U t + v s with an extended exponent: right
 * (one rounding per operation) also where U t or v s overflows while the
 * sum may not; v must be finite. */
static sbi_xd wave_pos(double x0, double U, double t, double v, double s)
{
  return sbi_xd_add(sbi_xd_add(sbi_xd_of(x0),
                               sbi_xd_mul(sbi_xd_of(U), sbi_xd_of(t))),
                    sbi_xd_mul(sbi_xd_of(v), sbi_xd_of(s)));
}

/* The wave pattern (arguments checked), without range checks: the
 * positions and the delta's mass also with an extended exponent in *px
 * (xl, xr, mass; sol's doubles are their nearest doubles, +-inf beyond
 * DBL_MAX).  Returns 0 (px unset, sol's positions inf or NaN) where
 * u_l - ugas or u_r - ugas overflows. */
static int solve_raw(const sb_pgd_riemann *rp, double t,
                     sb_pgd_riemann_sol *sol, sbi_xd px[3])
{
  double s, e;
  drag_map(rp->tau, t, &s, &e);
  const double U = isinf(rp->tau) ? 0.0 : rp->ugas;
  const double vl = rp->u_l - U, vr = rp->u_r - U;
  const int ok = isfinite(vl) && isfinite(vr);
  sbi_xd pl = sbi_xd_of(0.0), pr = pl, pm = pl;
  sol->mass = 0.0;
  sol->vel = NAN;
  sol->ul = U + vl * e;
  sol->ur = U + vr * e;
  if (rp->rho_l == 0 && rp->rho_r == 0) {
    sol->type = SB_PGD_WAVE_NONE;
    if (ok)
      pl = pr = wave_pos(rp->x0, U, t, 0.0, s);
  } else if (rp->rho_r == 0 || rp->rho_l == 0 || vl == vr) {
    /* one state against vacuum, or both with the same velocity */
    sol->type = SB_PGD_WAVE_CONTACT;
    if (ok)
      pl = pr = wave_pos(rp->x0, U, t, rp->rho_l > 0 ? vl : vr, s);
  } else if (vl < vr) {
    sol->type = SB_PGD_WAVE_VACUUM;
    if (ok) {
      pl = wave_pos(rp->x0, U, t, vl, s);
      pr = wave_pos(rp->x0, U, t, vr, s);
    }
  } else {
    sol->type = SB_PGD_WAVE_DELTA;
    if (ok) {
      double sig = delta_speed(rp->rho_l, vl, rp->rho_r, vr);
      pl = pr = wave_pos(rp->x0, U, t, sig, s);
      pm = sbi_xd_mul(delta_mass_rate_xd(rp->rho_l, vl, rp->rho_r, vr),
                      sbi_xd_of(s));
      sol->vel = U + sig * e;
    }
  }
  if (!ok) {
    sol->xl = sol->xr = sol->mass = INFINITY;
    return 0;
  }
  sol->xl = sbi_xd_val(pl);
  sol->xr = sbi_xd_val(pr);
  sol->mass = sbi_xd_val(pm);
  px[0] = pl;
  px[1] = pr;
  px[2] = pm;
  return 1;
}

int sb_pgd_riemann_solve(const sb_pgd_riemann *rp, double t,
                         sb_pgd_riemann_sol *sol)
{
  int st = check_rp(rp, t, __func__);
  if (st)
    return st;
  if (!sol)
    return sbi_error(SB_EINVAL, __func__, "NULL solution");
  sbi_xd px[3];
  solve_raw(rp, t, sol, px);
  return sol_ok(sol, __func__);
}

/* The wave pattern for _eval, _integral and _error, errors named after
 * func: wave positions and the delta's mass may lie beyond DBL_MAX (px
 * holds them exactly, w's doubles are +-inf there: a finite x or cell
 * end compares right with them), the velocities must be doubles. */
static int solve_wide(const sb_pgd_riemann *rp, double t,
                      sb_pgd_riemann_sol *w, sbi_xd px[3], const char *func)
{
  int st = check_rp(rp, t, func);
  if (st)
    return st;
  if (!solve_raw(rp, t, w, px) || !isfinite(w->ul) || !isfinite(w->ur) ||
      (w->type == SB_PGD_WAVE_DELTA && !isfinite(w->vel)))
    return sbi_error(SB_ERANGE, func, "the velocities leave the double "
                     "range (ul = %g, ur = %g)", w->ul, w->ur);
  return SB_SUCCESS;
}

/* A point of sb_pgd_riemann_eval or an end of a segment for
 * integral_sol_x: its nearest double d (+-inf also for a wave position
 * beyond DBL_MAX) and, where fin, its exact value x with an extended
 * exponent (every wave position; a point or an end of [a, b] when
 * finite). */
typedef struct {
  double d;
  sbi_xd x;
  int fin;
} xend;

static xend end_wave(sbi_xd x, double d)
{
  xend r = {d, x, 1};
  return r;
}

static xend end_dbl(double d)
{
  xend r = {d, sbi_xd_of(isfinite(d) ? d : 0.0), isfinite(d)};
  return r;
}

/* -1, 0, 1 as u <, =, > v: by the extended values where both are finite
 * reals, else by rank (+-inf ends outside every finite real). */
static int end_cmp(xend u, xend v)
{
  if (isfinite(u.d) && isfinite(v.d))
    return (u.d > v.d) - (u.d < v.d);
  if (u.fin && v.fin) {
    sbi_xd nv = v.x;
    nv.m = -nv.m;
    const double dm = sbi_xd_add(u.x, nv).m;
    return (dm > 0) - (dm < 0);
  }
  const int su = u.d > 0 ? 1 : -1, sv = v.d > 0 ? 1 : -1;
  const int ru = !u.fin ? 2 * su : isinf(u.d) ? su : 0,
            rv = !v.fin ? 2 * sv : isinf(v.d) ? sv : 0;
  return (ru > rv) - (ru < rv);
}

int sb_pgd_riemann_eval(const sb_pgd_riemann *rp, double x, double t,
                        double *rho, double *u)
{
  sb_pgd_riemann_sol w;
  sbi_xd px[3];
  int st = solve_wide(rp, t, &w, px, __func__);
  if (st)
    return st;
  if (isnan(x))
    return sbi_error(SB_EDOM, __func__, "x is NaN");
  /* compared with the exact positions: x = -inf lies left of a wave
   * beyond -DBL_MAX, x = +inf right of one beyond DBL_MAX */
  const xend X = end_dbl(x);
  double r = 0, v = 0;
  if (end_cmp(X, end_wave(px[0], w.xl)) < 0) {
    r = rp->rho_l;
    v = r > 0 ? w.ul : 0.0;
  } else if (end_cmp(X, end_wave(px[1], w.xr)) >= 0) {
    r = rp->rho_r;
    v = r > 0 ? w.ur : 0.0;
  }
  if (rho)
    *rho = r;
  if (u)
    *u = v;
  return SB_SUCCESS;
}

/* Mass and momentum in [a, b] from a solved wave pattern. */
static void integral_sol(const sb_pgd_riemann *rp,
                         const sb_pgd_riemann_sol *w, double a, double b,
                         double *mass, double *mom)
{
  double ll = fmin(b, w->xl) - a, lr = b - fmax(a, w->xr);
  ll = ll > 0 ? ll : 0.0;
  lr = lr > 0 ? lr : 0.0;
  double m = rp->rho_l * ll + rp->rho_r * lr;
  double q = rp->rho_l * w->ul * ll + rp->rho_r * w->ur * lr;
  if (w->type == SB_PGD_WAVE_DELTA && a <= w->xl && w->xl < b) {
    m += w->mass;
    q += w->mass * w->vel;
  }
  *mass = m;
  *mom = q;
}

/* Is the product x y free of overflow and underflow (or exactly 0)? */
static int prod_ok(double x, double y)
{
  const double p = fabs(x * y);
  return x == 0 || y == 0 || (p >= DBL_MIN && p <= DBL_MAX);
}

/* rho (hi - lo) as m 2^e: 0 unless hi > lo, 0 for rho = 0 (vacuum, of
 * any extent); *inf set where the mass is infinite (an infinite end). */
static sbi_xd xd_mass(double rho, xend hi, xend lo, int *inf)
{
  if (rho == 0 || end_cmp(hi, lo) <= 0)
    return sbi_xd_of(0.0);
  if (!hi.fin || !lo.fin) {
    *inf = 1;
    return sbi_xd_of(0.0);
  }
  sbi_xd nl = lo.x;
  nl.m = -nl.m;
  return sbi_xd_mul(sbi_xd_of(rho), sbi_xd_add(hi.x, nl));
}

/* integral_sol's sums with an extended exponent, for where a length
 * (b - a beyond DBL_MAX), a product rho u length or a partial sum leaves
 * the double range while the mass and momentum may not, and with the
 * exact wave positions and delta mass px (solve_raw) where they are
 * beyond DBL_MAX: a position beyond an end of [a, b] then only clamps the
 * states to it, and the delta's mass counts only if a <= x_delta < b.  A
 * vacuum side of infinite extent adds nothing.  +inf / NaN where the
 * mass is infinite. */
static void integral_sol_x(const sb_pgd_riemann *rp,
                           const sb_pgd_riemann_sol *w, const sbi_xd px[3],
                           double a, double b, double *mass, double *mom)
{
  int inf = 0;
  const xend A = end_dbl(a), B = end_dbl(b), L = end_wave(px[0], w->xl),
             R = end_wave(px[1], w->xr);
  const sbi_xd ml = xd_mass(rp->rho_l, end_cmp(L, B) < 0 ? L : B, A, &inf),
               mr = xd_mass(rp->rho_r, B, end_cmp(R, A) > 0 ? R : A, &inf);
  if (w->type == SB_PGD_WAVE_DELTA && end_cmp(A, L) <= 0 &&
      end_cmp(L, B) < 0 && isinf(w->mass))
    inf = 1;  /* the delta's mass alone exceeds DBL_MAX */
  if (inf) {
    *mass = INFINITY;
    *mom = NAN;
    return;
  }
  sbi_xd m = sbi_xd_add(ml, mr);
  sbi_xd q = sbi_xd_add(sbi_xd_mul(ml, sbi_xd_of(w->ul)),
                        sbi_xd_mul(mr, sbi_xd_of(w->ur)));
  if (w->type == SB_PGD_WAVE_DELTA && end_cmp(A, L) <= 0 &&
      end_cmp(L, B) < 0) {
    m = sbi_xd_add(m, px[2]);
    q = sbi_xd_add(q, sbi_xd_mul(px[2], sbi_xd_of(w->vel)));
  }
  *mass = sbi_xd_val(m);
  *mom = sbi_xd_val(q);
}

int sb_pgd_riemann_integral(const sb_pgd_riemann *rp, double t, double a,
                            double b, double *mass, double *mom)
{
  sb_pgd_riemann_sol w;
  sbi_xd px[3];
  int st = solve_wide(rp, t, &w, px, __func__);
  if (st)
    return st;
  if (!(a <= b))
    return sbi_error(SB_EDOM, __func__, "interval [%g, %g] is empty", a, b);
  double m, q;
  /* with finite a and b, a position of +-inf (beyond DBL_MAX) clamps
   * exactly: fmin(b, +inf) = b, fmax(a, -inf) = a, and it is never in
   * [a, b) */
  integral_sol(rp, &w, a, b, &m, &q);
  /* plain sums unless a length, rho_l u_l, rho_r u_r (their order in
   * integral_sol), a product with a length or with the delta's mass, or
   * a sum over/underflowed */
  const double ll = fmin(b, w.xl) - a, lr = b - fmax(a, w.xr);
  if (!isfinite(m) || !isfinite(q) || !isfinite(ll) || !isfinite(lr) ||
      !prod_ok(rp->rho_l, w.ul) || !prod_ok(rp->rho_r, w.ur) ||
      (ll > 0 && (!prod_ok(rp->rho_l, ll) ||
                  !prod_ok(rp->rho_l * w.ul, ll))) ||
      (lr > 0 && (!prod_ok(rp->rho_r, lr) ||
                  !prod_ok(rp->rho_r * w.ur, lr))) ||
      (w.type == SB_PGD_WAVE_DELTA && !prod_ok(w.mass, w.vel)))
    integral_sol_x(rp, &w, px, a, b, &m, &q);
  if (!isfinite(m) || !isfinite(q))
    return sbi_error(SB_ERANGE, __func__, "mass = %g, momentum = %g in "
                     "[%g, %g] leave the double range", m, q, a, b);
  if (mass)
    *mass = m;
  if (mom)
    *mom = q;
  return SB_SUCCESS;
}

/* Integral over a segment of |d| for d linear from d0 to d1. */
static double abs_linear(double d0, double d1, double len)
{
  if ((d0 >= 0) == (d1 >= 0))
    return 0.5 * (fabs(d0) + fabs(d1)) * len;
  return 0.5 * (d0 * d0 + d1 * d1) / fabs(d0 - d1) * len;
}

int sb_pgd_riemann_error(const sb_pgd_riemann *rp, double t, double a,
                         double h, size_t n, const double *rho, double *l1,
                         double *w1)
{
  /* the cells are finite: a wave position beyond DBL_MAX (+-inf in w)
   * only clamps the states to them, and a delta outside them (its mass
   * whatever it is) adds nothing, as in sb_pgd_riemann_integral */
  sb_pgd_riemann_sol w;
  sbi_xd px[3];
  int st = solve_wide(rp, t, &w, px, __func__);
  if (st)
    return st;
  if (!rho || n == 0)
    return sbi_error(SB_EINVAL, __func__, "need rho, n > 0");
  if (!(h > 0) || !isfinite(h) || !isfinite(a) ||
      !isfinite(a + (double)n * h))
    return sbi_error(SB_EDOM, __func__, "need finite a, h > 0 and a + n h "
                     "(a = %g, h = %g)", a, h);
  if (fmax(fabs(a), fabs(a + (double)n * h)) * DBL_EPSILON > 1e-6 * h)
    return sbi_error(SB_ERANGE, __func__, "cells of width h = %g at |x| = "
                     "%g are not resolved in double precision", h,
                     fmax(fabs(a), fabs(a + (double)n * h)));
  for (size_t i = 0; i < n; i++)
    if (!isfinite(rho[i]))
      return sbi_error(SB_EDOM, __func__, "rho[%zu] = %g: must be finite",
                       i, rho[i]);
  double sl1 = 0, sw1 = 0, Mnum = 0;
  const int has_delta = w.type == SB_PGD_WAVE_DELTA;
  for (size_t i = 0; i < n; i++) {
    double ca = a + (double)i * h, cb = a + (double)(i + 1) * h;
    double m, q;
    integral_sol(rp, &w, ca, cb, &m, &q);
    sl1 += fabs(rho[i] * h - m);
    if (w1) {
      /* breakpoints of the exact cumulative mass inside the cell */
      double bp[4] = {ca, 0, 0, cb};
      int nb = 1;
      if (w.xl > ca && w.xl < cb)
        bp[nb++] = w.xl;
      if (w.xr > ca && w.xr < cb && w.xr != w.xl)
        bp[nb++] = w.xr;
      bp[nb] = cb;
      for (int k = 0; k < nb; k++) {
        double p = bp[k], r = bp[k + 1], Mp, Mr;
        integral_sol(rp, &w, a, p, &Mp, &q); /* mass in [a, p) */
        integral_sol(rp, &w, a, r, &Mr, &q);
        if (has_delta && p == w.xl)
          Mp += w.mass;  /* right limit at the delta */
        double np = Mnum + rho[i] * (p - ca), nr = Mnum + rho[i] * (r - ca);
        sw1 += abs_linear(np - Mp, nr - Mr, r - p);
      }
      Mnum += rho[i] * h;
    }
  }
  if (!isfinite(sl1) || (w1 && !isfinite(sw1)))
    return sbi_error(SB_ERANGE, __func__, "l1 = %g, w1 = %g leave the double "
                     "range", sl1, sw1);
  if (l1)
    *l1 = sl1;
  if (w1)
    *w1 = sw1;
  return SB_SUCCESS;
}

/* ------------------------------------------------------------ smooth */

typedef struct {
  const sb_pgd_smooth *s;
  double x, Ut, sf;
} foot_par;

static double foot_f(double xi, void *v)
{
  const foot_par *fp = v;
  double U = isinf(fp->s->tau) ? 0.0 : fp->s->ugas;
  return xi + fp->Ut + (fp->s->u0(xi, fp->s->data) - U) * fp->sf - fp->x;
}

static int check_smooth(const sb_pgd_smooth *s, double t, const char *f)
{
  if (!s || !s->rho0 || !s->u0)
    return sbi_error(SB_EINVAL, f, "NULL problem or functions");
  if (!(s->tau > 0) || !isfinite(s->ugas))
    return sbi_error(SB_EDOM, f, "tau = %g (> 0 or INFINITY), ugas finite",
                     s->tau);
  if (!(t >= 0) || !isfinite(t))
    return sbi_error(SB_EDOM, f, "t = %g: must be >= 0", t);
  return SB_SUCCESS;
}

/* The foot, errors named after func (s and t checked by the caller). */
static int foot(const sb_pgd_smooth *s, double x, double t, double *xi,
                const char *func)
{
  int st;
  if (!xi)
    return sbi_error(SB_EINVAL, func, "NULL xi");
  if (!isfinite(x))
    return sbi_error(SB_EDOM, func, "x = %g: must be finite", x);
  double sf, e;
  drag_map(s->tau, t, &sf, &e);
  double U = isinf(s->tau) ? 0.0 : s->ugas;
  foot_par fp = {s, x, U * t, sf};
  gsl_function F = {foot_f, &fp};
  double g0 = x - U * t, f0 = foot_f(g0, &fp);
  if (!isfinite(f0))
    return sbi_error(SB_EDOM, func, "u0 not finite near %g", g0);
  if (f0 == 0) {
    *xi = g0;
    return SB_SUCCESS;
  }
  /* bracket by expanding away from the guess (f increases with xi while
   * the characteristics have not crossed) */
  double d = fabs(f0) + 1e-12 * (1 + fabs(g0)), lo = g0, hi = g0;
  int k;
  for (k = 0; k < 200; k++) {
    if (f0 > 0)
      lo = g0 - d;
    else
      hi = g0 + d;
    double fl = foot_f(lo, &fp), fh = foot_f(hi, &fp);
    if (!isfinite(fl) || !isfinite(fh))
      return sbi_error(SB_EDOM, func, "u0 not finite in [%g, %g]", lo,
                       hi);
    if (fl <= 0 && fh >= 0)
      break;
    d *= 2;
  }
  if (k == 200)
    return sbi_error(SB_EMAXITER, func, "no foot found for x = %g at "
                     "t = %g (characteristics crossed?)", x, t);
  st = sbi_brent(&F, lo, hi, DBL_MIN, 4 * DBL_EPSILON, 300, xi);
  if (st == SB_ENOMEM)
    return sbi_error(SB_ENOMEM, func, "out of memory");
  if (st)
    return sbi_error(SB_EMAXITER, func, "root finding did not converge "
                     "for x = %g", x);
  return SB_SUCCESS;
}

int sb_pgd_smooth_foot(const sb_pgd_smooth *s, double x, double t,
                       double *xi)
{
  int st = check_smooth(s, t, __func__);
  if (st)
    return st;
  return foot(s, x, t, xi, __func__);
}

typedef struct {
  const sb_pgd_smooth *s;
  double U;
} mom_par;

static double mom_f(double xi, void *v)
{
  const mom_par *m = v;
  return m->s->rho0(xi, m->s->data) * (m->s->u0(xi, m->s->data) - m->U);
}

/* Composite 10-point Gauss-Legendre on k panels, k doubled until two
 * successive sums agree to 1e-14 relative (smooth integrand). */
static int quad_smooth(gsl_function *F, double a, double b, double *res)
{
  gsl_integration_glfixed_table *tab = gsl_integration_glfixed_table_alloc(10);
  if (!tab)
    return SB_ENOMEM;
  double prev = NAN;
  int st = SB_EMAXITER;
  for (size_t k = 1; k <= 4096; k *= 2) {
    double sum = 0, h = (b - a) / (double)k;
    for (size_t i = 0; i < k; i++)
      sum += gsl_integration_glfixed(F, a + (double)i * h,
                                     a + (double)(i + 1) * h, tab);
    if (k > 1 && fabs(sum - prev) <= 1e-14 * fabs(sum) + 1e-300) {
      *res = sum;
      st = SB_SUCCESS;
      break;
    }
    prev = sum;
    *res = sum;
  }
  gsl_integration_glfixed_table_free(tab);
  return st;
}

int sb_pgd_smooth_integral(const sb_pgd_smooth *s, double t, double a,
                           double b, double *mass, double *mom)
{
  int st = check_smooth(s, t, __func__);
  if (st)
    return st;
  if (!s->mass0)
    return sbi_error(SB_EINVAL, __func__, "mass0 (primitive of rho0) is "
                     "required");
  if (!(a <= b))
    return sbi_error(SB_EDOM, __func__, "interval [%g, %g] is empty", a, b);
  double xa, xb;
  if ((st = foot(s, a, t, &xa, __func__)) ||
      (st = foot(s, b, t, &xb, __func__)))
    return st;
  double m = s->mass0(xb, s->data) - s->mass0(xa, s->data);
  if (mass)
    *mass = m;
  if (mom) {
    double sf, e, q = 0;
    drag_map(s->tau, t, &sf, &e);
    double U = isinf(s->tau) ? 0.0 : s->ugas;
    mom_par mp = {s, U};
    gsl_function F = {mom_f, &mp};
    if (xb > xa && (st = quad_smooth(&F, xa, xb, &q)))
      return sbi_error(st, __func__, "quadrature of the momentum over "
                       "[%g, %g] did not converge", xa, xb);
    *mom = U * m + e * q;
  }
  return SB_SUCCESS;
}
