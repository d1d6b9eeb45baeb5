/* spray_tab.c — TAB breakup (O'Rourke & Amsden 1987, SAE 872089): the
 * damped, forced oscillator of the droplet's deformation solved in closed
 * form at constant relative velocity, the breakup time (|y| = 1), the
 * critical Weber number and the children's Sauter radius from energy
 * conservation.  Derivations: docs/spray.md, "TAB". */
#include <float.h>
#include <limits.h>
#include <math.h>
#include <string.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_randist.h>

#include <smolbridge/spray.h>

#include "common/internal.h"
#include "common/numutil.h"
#include "spray_internal.h"

void sb_spray_tab_params_default(sb_spray_tab_params *p)
{
  if (!p)
    return;
  p->Cd = 5.0;
  p->children = SB_SPRAY_CHILDREN_AUTO;
  p->child_tag = -1;
  p->max_children = 10000;
}

/* Oscillator z'' + 2 beta z' + w0^2 z = 0 for z = y - y_eq, with
 * y_eq = F/w0^2 = We/12, F = (2/3)(rho_g/rho_l) U^2/r^2,
 * w0^2 = 8 sigma/(rho_l r^3), beta = 1/t_d = Cd mu_l/(2 rho_l r^2).
 * Where these scales or the initial state leave the plain double range
 * the oscillator is kept in scaled units: time t = 2^ks tau and
 * z = 2^ms Z (powers of two, exact), so beta, w0^2, w2, z0, zd0 below
 * are 2^ks beta, 2^(2 ks) w0^2, ..., z0 2^-ms, ydot0 2^(ks - ms); ks =
 * ms = 0 in the plain case, which thereby keeps its bits. */
typedef struct {
  double yeq, beta, w02, w2; /* w2 = w0^2 - beta^2 */
  double z0, zd0;
  double km, kp; /* overdamped: k - beta, k + beta, k = sqrt(-w2) */
  double ys;     /* yeq 2^-ms */
  double y0s;    /* y0 2^-ms */
  int ks, ms;
} osc;

/* x in the normal range (or 0 where zero is exact: zero_ok) */
static int nrm(double x, int zero_ok)
{
  const double a = fabs(x);
  return (zero_ok && x == 0) || (a >= DBL_MIN && a <= DBL_MAX);
}

/* The scaled oscillator (see osc) with extended-exponent scales. */
static int osc_scaled(osc *o, double r, double urel, double rho_g,
                      double rho_l, const sb_spray_liquid *liq, double Cd,
                      double y0, double ydot0, const char *func)
{
  const sbi_xd R = sbi_xd_of(r), Rl = sbi_xd_of(rho_l);
  const sbi_xd r2 = sbi_xd_mul(R, R), r3 = sbi_xd_mul(r2, R);
  const sbi_xd w02 = sbi_xd_div(sbi_xd_mul(sbi_xd_of(8.0),
                                           sbi_xd_of(liq->sigma)),
                                sbi_xd_mul(Rl, r3));
  const sbi_xd b = sbi_xd_div(sbi_xd_mul(sbi_xd_of(Cd),
                                         sbi_xd_of(liq->mu_l)),
                              sbi_xd_mul(sbi_xd_of(2.0), sbi_xd_mul(Rl, r2)));
  /* the faster rate max(beta, w0) = m 2^e becomes m: ks = -e */
  const sbi_xd w0 = sbi_xd_sqrt(w02);
  const int e = (b.m != 0.0 && (b.e > w0.e || (b.e == w0.e && b.m > w0.m)))
                    ? b.e : w0.e;
  o->ks = -e;
  o->beta = sbi_xd_val(sbi_xd_norm(b.m, b.e + o->ks));
  o->w02 = sbi_xd_val(sbi_xd_norm(w02.m, w02.e + 2 * o->ks));
  o->w2 = o->w02 - o->beta * o->beta;
  /* y_eq = We/12 = rho_g U^2 r/(12 sigma) */
  const sbi_xd U = sbi_xd_of(urel);
  const sbi_xd yq = sbi_xd_div(
      sbi_xd_mul(sbi_xd_mul(sbi_xd_of(rho_g), sbi_xd_mul(U, U)), R),
      sbi_xd_mul(sbi_xd_of(12.0), sbi_xd_of(liq->sigma)));
  o->yeq = sbi_xd_val(yq);
  if (!isfinite(o->yeq))
    return sbi_error(SB_ERANGE, func, "We/12 = 2^%d leaves the double "
                     "range", yq.e);
  const sbi_xd z0 = sbi_xd_add(sbi_xd_of(y0), sbi_xd_of(-o->yeq));
  const sbi_xd zd0 = sbi_xd_norm(sbi_xd_of(ydot0).m,
                                 sbi_xd_of(ydot0).e + o->ks);
  /* |Z0|, |Zd0|, |y0| 2^-ms < 2^1020: the sums of osc_eval stay
   * finite */
  int em = z0.m != 0.0 ? z0.e : INT_MIN;
  if (zd0.m != 0.0 && zd0.e > em)
    em = zd0.e;
  if (y0 != 0.0 && sbi_xd_of(y0).e > em)
    em = sbi_xd_of(y0).e;
  o->ms = em > 1020 ? em - 1020 : 0;
  o->z0 = sbi_xd_val(sbi_xd_norm(z0.m, z0.e - o->ms));
  o->zd0 = sbi_xd_val(sbi_xd_norm(zd0.m, zd0.e - o->ms));
  o->ys = ldexp(o->yeq, -o->ms);
  o->y0s = ldexp(y0, -o->ms);
  if (o->w2 < 0) { /* k - beta = -w0^2/(k + beta) without cancellation */
    o->kp = sqrt(-o->w2) + o->beta;
    o->km = -o->w02 / o->kp;
  }
  return SB_SUCCESS;
}

static int osc_init(osc *o, double r, double urel, double rho_g,
                    double rho_l, const sb_spray_liquid *liq, double Cd,
                    double y0, double ydot0, const char *func)
{
  if (!liq)
    return sbi_error(SB_EDOM, func, "NULL liquid");
  if (!(r > 0) || !(rho_g >= 0) || !(rho_l > 0) || !(liq->sigma > 0) ||
      !(liq->mu_l >= 0) || !(Cd >= 0) || !isfinite(urel) || !isfinite(r) ||
      !isfinite(y0) || !isfinite(ydot0) || !isfinite(rho_g) ||
      !isfinite(rho_l) || !isfinite(liq->sigma) || !isfinite(liq->mu_l) ||
      !isfinite(Cd))
    return sbi_error(SB_EDOM, func, "need r, rho_l, sigma > 0 and rho_g, "
                     "mu_l, Cd >= 0, finite (r = %g, rho_l = %g, sigma = %g)",
                     r, rho_l, liq->sigma);
  o->w02 = 8.0 * liq->sigma / (rho_l * r * r * r);
  o->beta = Cd * liq->mu_l / (2.0 * rho_l * r * r);
  o->w2 = o->w02 - o->beta * o->beta;
  const double f = (2.0 / 3.0) * (rho_g / rho_l) * urel,
               fu = f * urel, fr = fu / (r * r);
  o->yeq = fr / o->w02;
  o->z0 = y0 - o->yeq;
  o->zd0 = ydot0;
  o->ks = o->ms = 0;
  o->ys = o->yeq;
  o->y0s = y0;
  const double cm = Cd * liq->mu_l, bz = o->beta * o->z0,
               bzd = o->beta * o->zd0, wz = o->w02 * o->z0,
               by = o->beta * y0;
  /* plain: every scale and product in the normal range (or exactly 0) */
  const int plain =
      nrm(rho_l * r * r * r, 0) && nrm(o->w02, 0) &&
      (cm == 0 || (nrm(cm, 0) && nrm(2.0 * rho_l * r * r, 0) &&
                   nrm(o->beta, 0))) &&
      isfinite(o->w2) &&
      (rho_g == 0 || urel == 0 ||
       (nrm(rho_g / rho_l, 0) && nrm(f, 0) && nrm(fu, 0) &&
        nrm(r * r, 0) && nrm(fr, 0) && nrm(o->yeq, 0))) &&
      isfinite(o->z0) && isfinite(bz) && isfinite(wz) && isfinite(bzd) &&
      isfinite(o->zd0 + bz) && isfinite(bzd + wz) && isfinite(by) &&
      isfinite(o->zd0 + by);
  if (!plain) {
    int st = osc_scaled(o, r, urel, rho_g, rho_l, liq, Cd, y0, ydot0, func);
    if (st)
      return st;
  } else if (o->w2 < 0) {
    /* k - beta = -w0^2/(k + beta): the difference cancels (relative
     * error ~ DBL_EPSILON beta^2/w0^2) when heavily overdamped */
    o->kp = sqrt(-o->w2) + o->beta;
    o->km = -o->w02 / o->kp;
  }
  if (!isfinite(o->w02) || !isfinite(o->beta) || !isfinite(o->w2) ||
      !isfinite(o->z0) || !isfinite(o->zd0))
    return sbi_error(SB_ERANGE, func, "the oscillator's scales leave the "
                     "double range (w0^2 = %g, 1/t_d = %g, We/12 = %g)",
                     o->w02, o->beta, o->yeq);
  return SB_SUCCESS;
}

/* e^{-beta t} C(t), e^{-beta t} S(t) and their rate h'(t) = e^{-beta t}
 * (C - beta S) of h = e^{-beta t} S, C'' = -w2 C, S'' = -w2 S, C(0) = 1,
 * C'(0) = 0, S(0) = 0, S'(0) = 1, without overflow (t in the
 * oscillator's units).  h is the impulse response of z'' + 2 beta z' +
 * w0^2 z = 0 (z(0) = 0, z'(0) = 1) and h' its rate (osc_eval).  None
 * cancels beyond its condition number in t, beta and w0 (h' is
 * ill-conditioned only near its zero). */
static void osc_cs(const osc *o, double t, double *ec, double *es,
                   double *ed)
{
  double w2 = o->w2, b = o->beta;
  if (fabs(w2) * t * t < 1e-10) {
    double e = exp(-b * t);
    *ec = e * (1.0 - 0.5 * w2 * t * t);
    *es = e * t * (1.0 - w2 * t * t / 6.0);
    *ed = *ec - b * *es; /* e (1 - bt) + O(w2 t^2): cancels at its zero */
  } else if (w2 > 0) {
    double w = sqrt(w2), e = exp(-b * t), wt = w * t;
    /* wt = inf: the oscillation has died out (e = 0: tab_state refuses
     * an unresolved phase with e > 0) */
    *ec = isinf(wt) ? 0.0 : e * cos(wt);
    *es = isinf(wt) ? 0.0 : e * sin(wt) / w;
    /* e (cos wt - (b/w) sin wt), b < w: the two cancel only near the
     * zero of h' (tan wt = w/b), where its phase already costs as much */
    *ed = *ec - b * *es;
  } else {
    /* e^{-bt} (cosh kt, sinh(kt)/k) = ((ep + em)/2, (ep - em)/(2k)) with
     * ep = e^{(k - b)t}, em = e^{-(k + b)t}, and h' = e^{-bt} (cosh kt -
     * (b/k) sinh kt) = (kp em + km ep)/(2k): the two exponentials'
     * rates kept apart, for cosh kt - (b/k) sinh kt ~ (k - b)/(2k) e^{kt}
     * cancelled by ~ (b/w0)^2 when heavily overdamped */
    const double k = sqrt(-w2), em = exp(-o->kp * t), ep = exp(o->km * t);
    *ec = 0.5 * (ep + em);
    if (2 * k * t <= 1) {
      /* ep - em = em (e^{2kt} - 1) cancels as kt -> 0; with x =
       * e^{2kt} - 1 and kp + km = 2k, kp em + km ep = em (2k + km x) */
      const double x = expm1(2 * k * t);
      *es = 0.5 * em * x / k;
      *ed = em * (1 + o->km * x / (2 * k));
    } else {
      *es = 0.5 * (ep - em) / k;
      *ed = (o->kp * em + o->km * ep) / (2 * k);
    }
  }
}

/* The step response g(t) = 1 - e^{-bt}(C + b S) (z'' + 2 b z' + w0^2 z =
 * w0^2, z(0) = z'(0) = 0), 0 <= g, without the cancellation of 1 - P
 * where P = e^{-bt}(C + b S) is near 1 (t small against 1/b, 1/w0;
 * slow decay when heavily overdamped).  ec, es: e^{-bt} C, e^{-bt} S
 * (osc_cs). */
static double osc_step(const osc *o, double t, double ec, double es)
{
  const double b = o->beta, bt = b * t, e = exp(-bt);
  const double eps = 0.25 * DBL_EPSILON;
  if (o->w2 > 0) {
    /* 1 - e C - e b S = e [(e^{bt} - 1 - bt) + (b/w)(wt - sin wt)
     * + 2 sin^2(wt/2)], every term >= 0 */
    const double w = sqrt(o->w2), th = w * t;
    double eE, ts;
    if (bt <= 1) { /* e^x - 1 - x = sum_{m >= 2} x^m/m! */
      double term = 0.5 * bt * bt, sum = 0;
      for (int m = 2; m < 40 && term > eps * sum; m++) {
        sum += term;
        term *= bt / (m + 1);
      }
      eE = e * sum;
    } else {
      eE = -expm1(-bt) - bt * e;
    }
    if (isinf(th)) {
      ts = 0.0;  /* e = 0 here (tab_state refuses an unresolved phase) */
    } else if (th <= 1.5) { /* th - sin th = sum (-1)^(n+1) th^(2n+1)/(2n+1)! */
      double term = th * th * th / 6, sum = 0;
      for (int n = 1; n < 40 && fabs(term) > eps * fabs(sum); n++) {
        sum += term;
        term *= -th * th / ((2 * n + 2) * (2 * n + 3));
      }
      ts = e * (b / w) * sum;
    } else {
      ts = e * (b / w) * (th - sin(th));
    }
    const double sh = isinf(th) ? 0.0 : sin(0.5 * th);
    return eE + ts + 2 * e * sh * sh;
  }
  if (bt <= 30) {
    /* overdamped or critical, B = (bt)^2 >= K = (kt)^2 = B - W, W =
     * (w0 t)^2: g = e sum_{n >= 1} D_n (1/(2n)! + bt/(2n+1)!) with D_n =
     * B^n - K^n >= 0, D_{n+1} = B D_n + W K^n: every term >= 0 */
    const double B = bt * bt, W = o->w02 * t * t, K = -o->w2 * t * t;
    double D = W, Kn = K, f = 0.5, sum = 0; /* f = 1/(2n)! */
    for (int n = 1; n < 200; n++) {
      const double term = D * (f + bt * f / (2 * n + 1));
      sum += term;
      if (term <= eps * sum)
        break;
      D = B * D + W * Kn;
      Kn *= K;
      f /= (double)((2 * n + 1) * (2 * n + 2));
    }
    return e * sum;
  }
  const double P = ec + b * es;
  if (P <= 0.5)
    return 1 - P;
  /* slow decay: [kp (1 - e^{km t}) - |km| (1 - e^{-kp t})]/(2k); P > 1/2
   * at bt > 30 needs k > 0.97 b, and then the second term is below ~1/20
   * of the first */
  const double k = sqrt(-o->w2);
  return (-o->kp * expm1(o->km * t) + o->km * -expm1(-o->kp * t)) / (2 * k);
}

/* y = y_eq g + e^{-bt}[y0 C + (y0' + b y0) S] (the forced response plus
 * the free one: no y_eq + z cancellation where y << y_eq) and its rate
 * y' = y0' h' - w0^2 z0 h, at t in the oscillator's units; y, y' in SI
 * units.  h = e^{-bt} S is the impulse response (g' = w0^2 h), so y' =
 * w0^2 y_eq h + y0' h' - w0^2 y0 h, the derivative of the terms of y;
 * with h' formed by osc_cs this does not cancel unless those terms do
 * (the form e^{-bt}[zd0 C - (b zd0 + w0^2 z0) S] lost up to ~(b/w0)^2
 * ulp in C - b S when overdamped). */
static void osc_eval(const osc *o, double t, double *y, double *yd)
{
  double ec, es, ed;
  osc_cs(o, t, &ec, &es, &ed);
  if (y)
    *y = ldexp(o->ys * osc_step(o, t, ec, es) + o->y0s * ec +
                   (o->zd0 + o->beta * o->y0s) * es,
               o->ms);
  if (yd)
    *yd = ldexp(o->zd0 * ed - o->w02 * o->z0 * es, o->ms - o->ks);
}

int sb_spray_tab_state(double t, double r, double urel, double rho_g,
                       double rho_l, const sb_spray_liquid *liq, double Cd,
                       double y0, double ydot0, double *y, double *ydot)
{
  osc o;
  int st = osc_init(&o, r, urel, rho_g, rho_l, liq, Cd, y0, ydot0, __func__);
  if (st)
    return st;
  if (!(t >= 0) || !isfinite(t))
    return sbi_error(SB_EDOM, __func__, "t = %g: must be finite >= 0", t);
  const double tau = ldexp(t, -o.ks); /* the oscillator's time unit */
  if (o.w2 > 0 && exp(-o.beta * tau) > 0 && sqrt(o.w2) * tau > 0x1p52)
    return sbi_error(SB_ERANGE, __func__, "phase omega t = %g: the "
                     "oscillation is not resolved in double precision",
                     sqrt(o.w2) * tau);
  double yy, yd;
  osc_eval(&o, tau, &yy, &yd);
  if (!isfinite(yy) || !isfinite(yd))
    return sbi_error(SB_ERANGE, __func__, "y = %g, y' = %g overflow", yy,
                     yd);
  if (y)
    *y = yy;
  if (ydot)
    *ydot = yd;
  return SB_SUCCESS;
}

typedef struct {
  const osc *o;
  double level;
} root_ctx;

static double root_f(double t, void *p)
{
  const root_ctx *c = p;
  double y;
  osc_eval(c->o, t, &y, NULL);
  return y - c->level;
}

/* Crossing of y = level in [a, b] where y is monotone; NAN if none. */
static double cross_in(const osc *o, double a, double b, double level,
                       double tol)
{
  root_ctx c = {o, level};
  double fa = root_f(a, &c), fb = root_f(b, &c);
  if (fa == 0)
    return a;
  if ((fa < 0) == (fb < 0) && fb != 0)
    return NAN;
  if (fb == 0)
    return b;
  gsl_function F = {root_f, &c};
  double x;
  int st = sbi_brent(&F, a, b, tol, 0.0, 200, &x);
  return (st && st != SB_EMAXITER) ? NAN : x;
}

/* Times t > 0 where y' = 0: y' = e^{-bt}[zd0 C - (b zd0 + w0^2 z0) S]. */
static double next_extremum(const osc *o, double after)
{
  double p = o->zd0, q = o->beta * o->zd0 + o->w02 * o->z0;
  if (o->w2 > 0) {
    double w = sqrt(o->w2);
    /* zd0 cos wt - (q/w) sin wt = R cos(wt + phi) */
    double phi = atan2(q / w, p);
    double t0 = (0.5 * SBI_PI - phi) / w, per = SBI_PI / w;
    double k = ceil((after - t0) / per + 1e-12);
    double t = t0 + k * per;
    while (t <= after)
      t += per;
    return t;
  }
  /* overdamped / critical: at most one extremum, where S/C = p/q */
  if (q == 0 || p / q <= 0)
    return INFINITY;
  double ratio = p / q, t;
  if (o->w2 == 0)
    t = ratio;
  else {
    double k = sqrt(-o->w2);
    if (k * ratio >= 1)
      return INFINITY;
    t = atanh(k * ratio) / k;
  }
  return t > after ? t : INFINITY;
}

int sb_spray_tab_breakup_time(double r, double urel, double rho_g,
                              double rho_l, const sb_spray_liquid *liq,
                              double Cd, double y0, double ydot0,
                              double tmax, double *tb, double *ydot_b)
{
  osc o;
  int st = osc_init(&o, r, urel, rho_g, rho_l, liq, Cd, y0, ydot0, __func__);
  if (st)
    return st;
  if (!tb || !(tmax >= 0))
    return sbi_error(SB_EDOM, __func__, "NULL tb or tmax = %g < 0", tmax);
  *tb = INFINITY;
  if (fabs(y0) >= 1) {
    *tb = 0;
    if (ydot_b)
      *ydot_b = ydot0;
    return SB_SUCCESS;
  }
  /* in the oscillator's time unit (tb = 2^ks t) */
  const double tm = ldexp(tmax, -o.ks);
  double scale = o.w02 > 0 ? 1.0 / sqrt(o.w02) : 1.0;
  double tol = 1e-12 * scale;
  /* envelope of |z|: e^{-bt} sqrt(A^2 + B^2) (underdamped) */
  double amp = INFINITY;
  if (o.w2 > 0) {
    double B = (o.zd0 + o.beta * o.z0) / sqrt(o.w2);
    amp = sqrt(o.z0 * o.z0 + B * B);
  }
  double a = 0.0;
  for (int seg = 0; seg < 100000 && a < tm; seg++) {
    double b = next_extremum(&o, a);
    if (b > tm)
      b = tm;
    double t1 = cross_in(&o, a, b, 1.0, tol);
    double t2 = cross_in(&o, a, b, -1.0, tol);
    double t = isnan(t1) ? t2 : (isnan(t2) ? t1 : fmin(t1, t2));
    if (!isnan(t) && t > 0) {
      double yd;
      osc_eval(&o, t, NULL, &yd);
      if (!isfinite(yd)) {
        *tb = INFINITY;
        return sbi_error(SB_ERANGE, __func__, "y' = %g at breakup "
                         "overflows", yd);
      }
      *tb = ldexp(t, o.ks);
      if (ydot_b)
        *ydot_b = yd;
      return SB_SUCCESS;
    }
    a = b;
    if (o.w2 > 0) {
      double env = ldexp(amp * exp(-o.beta * a), o.ms);
      if (o.yeq + env < 1.0 && o.yeq - env > -1.0)
        break; /* the decaying oscillation can no longer reach |y| = 1 */
    }
  }
  return SB_SUCCESS;
}

double sb_spray_tab_we_crit(double r, double rho_l,
                            const sb_spray_liquid *liq, double Cd)
{
  osc o;
  if (osc_init(&o, r, 0.0, 0.0, rho_l, liq, Cd, 0.0, 0.0, __func__))
    return NAN;
  if (!(o.w2 > 0)) {
    sbi_error(SB_EDOM, __func__, "overdamped oscillator (w0^2 = %g <= "
              "beta^2 = %g)", o.w02, o.beta * o.beta);
    return NAN;
  }
  return 12.0 / (1.0 + exp(-SBI_PI * o.beta / sqrt(o.w2)));
}

double sb_spray_tab_r32(double r, double ydot, double rho_l, double sigma)
{
  if (!(r > 0) || !(rho_l > 0) || !(sigma > 0) || !isfinite(ydot) ||
      !isfinite(r) || !isfinite(rho_l) || !isfinite(sigma)) {
    sbi_error(SB_EDOM, __func__, "need finite r, rho_l, sigma > 0, finite "
              "ydot");
    return NAN;
  }
  double X = rho_l * r * r * r * ydot * ydot / (8.0 * sigma);
  if (ydot != 0 && !(X >= DBL_MIN && isfinite(X))) {
    /* r^3 ydot^2 over/underflows: the same chain, extended exponent */
    sbi_xd R = sbi_xd_of(r), V = sbi_xd_of(ydot);
    sbi_xd x = sbi_xd_mul(sbi_xd_of(rho_l), R);
    x = sbi_xd_mul(sbi_xd_mul(sbi_xd_mul(sbi_xd_mul(x, R), R), V), V);
    x = sbi_xd_div(sbi_xd_div(x, sbi_xd_of(8.0)), sbi_xd_of(sigma));
    return sbi_xd_val(sbi_xd_div(R, sbi_xd_add(sbi_xd_of(7.0 / 3.0), x)));
  }
  return r / (7.0 / 3.0 + X);
}

/* ------------------------------------------------------------ stepping */

typedef struct {
  sb_spray *s;
  const sb_spray_gas *gas;
  const sb_spray_liquid *liq;
  const sb_spray_tab_params *tp;
  sb_spray_children mode;
  gsl_rng *rng;
} tab_ctx;

/* Child radius.  The children's number law is exponential with mean
 * r32/3, so its Sauter radius E r^3/E r^2 is r32 (O'Rourke & Amsden's
 * chi-square law with two degrees of freedom).  PARTICLES draws that law;
 * a PARCEL stands for w r^3/r_c^3 droplets, so it draws the mass-weighted
 * law r^3 e^{-3r/r32} (Gamma, shape 4) to represent the same number law.
 * Radii above the parent's are redrawn (probability <= e^{-7} for the
 * exponential, since r >= 7/3 r32). */
static double child_radius(gsl_rng *rng, double r32, double r, int parcel)
{
  for (int k = 0; k < 1000; k++) {
    double x = parcel ? gsl_ran_gamma(rng, 4.0, r32 / 3.0)
                      : gsl_ran_exponential(rng, r32 / 3.0);
    if (x > 0 && x <= r)
      return x;
  }
  return r32 < r ? r32 : r;
}

/* Direction perpendicular to the relative velocity u - v. */
static void normal_dir(const tab_ctx *c, const double v[3], double n[3])
{
  double e[3], m = 0;
  for (int k = 0; k < 3; k++) {
    e[k] = c->gas->u[k] - v[k];
    m += e[k] * e[k];
  }
  if (!(m > 0)) {
    gsl_ran_dir_3d(c->rng, &n[0], &n[1], &n[2]);
    return;
  }
  m = sqrt(m);
  for (int k = 0; k < 3; k++)
    e[k] /= m;
  sbi_spray_perp_dir(e, c->rng, n);
}

static int advance(tab_ctx *c, size_t i, double dt, int depth);

/* Break parcel i up (deformation rate yd at breakup), children advance
 * for the remaining time trem. */
static int breakup(tab_ctx *c, size_t i, double yd, double trem, int depth)
{
  sb_spray *s = c->s;
  double r = s->r[i], r32 = sb_spray_tab_r32(r, yd, s->p.rho_l,
                                              c->liq->sigma);
  double vn = 0.5 * r * fabs(yd); /* C_v C_b r ydot, C_v = 1, C_b = 1/2 */
  int tag = c->tp->child_tag >= 0 ? c->tp->child_tag : s->tag[i];
  s->st.tab_breakups++;
  if (c->mode == SB_SPRAY_CHILDREN_PARCEL) {
    double rc = child_radius(c->rng, r32, r, 1), n[3];
    normal_dir(c, s->v + 3 * i, n);
    s->w[i] *= (r / rc) * (r / rc) * (r / rc);
    s->r[i] = rc;
    for (int k = 0; k < 3; k++)
      s->v[3 * i + k] += vn * n[k];
    s->y[i] = s->yd[i] = 0.0;
    s->tag[i] = tag;
    s->formed[i] = 1; /* formed drops: no Reitz blob branch */
    return trem > 0 ? advance(c, i, trem, depth + 1) : SB_SUCCESS;
  }
  /* PARTICLES: children of the parcel's weight until the volume is used */
  double left = r * r * r, v0[3];
  memcpy(v0, s->v + 3 * i, sizeof v0);
  size_t first = s->n, nch = 0;
  while (left > 0) {
    double rc = child_radius(c->rng, r32, r, 0);
    double rc3 = rc * rc * rc;
    if (rc3 >= left || nch + 1 >= c->tp->max_children)
      rc3 = left;
    left -= rc3;
    rc = cbrt(rc3);
    double n[3], v[3];
    normal_dir(c, v0, n);
    for (int k = 0; k < 3; k++)
      v[k] = v0[k] + vn * n[k];
    if (nch == 0) { /* the first child reuses the parent's slot */
      memcpy(s->v + 3 * i, v, sizeof v);
      s->r[i] = rc;
      s->y[i] = s->yd[i] = 0.0;
      s->tag[i] = tag;
      s->formed[i] = 1;
    } else {
      int st = sbi_spray_reserve(s, 1, "sb_spray_tab_step");
      if (st)
        return st;
      size_t k = sbi_spray_push(s, v, rc, s->w[i], tag);
      s->shed[k] = 0.0;
      s->formed[k] = 1;
    }
    nch++;
  }
  if (trem > 0) {
    size_t last = s->n;
    int st = advance(c, i, trem, depth + 1);
    for (size_t k = first; k < last && !st; k++)
      st = advance(c, k, trem, depth + 1);
    return st;
  }
  return SB_SUCCESS;
}

static int advance(tab_ctx *c, size_t i, double dt, int depth)
{
  sb_spray *s = c->s;
  const double *v = s->v + 3 * i;
  double U2 = 0;
  for (int k = 0; k < 3; k++) {
    double d = c->gas->u[k] - v[k];
    U2 += d * d;
  }
  double tb, yb;
  int st = sb_spray_tab_breakup_time(s->r[i], sqrt(U2), c->gas->rho_g,
                                     s->p.rho_l, c->liq, c->tp->Cd, s->y[i],
                                     s->yd[i], dt, &tb, &yb);
  if (st)
    return st;
  if (tb <= dt && depth < 64)
    return breakup(c, i, yb, dt - tb, depth);
  return sb_spray_tab_state(dt, s->r[i], sqrt(U2), c->gas->rho_g, s->p.rho_l,
                            c->liq, c->tp->Cd, s->y[i], s->yd[i], &s->y[i],
                            &s->yd[i]);
}

int sb_spray_tab_step(sb_spray *s, const sb_spray_gas *gas,
                      const sb_spray_liquid *liq,
                      const sb_spray_tab_params *tp, double dt,
                      gsl_rng *rng)
{
  if (!s || !gas || !liq || !tp || !rng)
    return sbi_error(SB_EINVAL, __func__, "NULL argument");
  if (!(dt > 0) || !isfinite(dt))
    return sbi_error(SB_EINVAL, __func__, "dt = %g: must be finite > 0", dt);
  if (!(gas->rho_g >= 0) || !(liq->sigma > 0) || !(liq->mu_l >= 0) ||
      !(tp->Cd >= 0) || tp->max_children < 1)
    return sbi_error(SB_EINVAL, __func__, "need rho_g >= 0, sigma > 0, "
                     "mu_l >= 0, Cd >= 0, max_children >= 1");
  tab_ctx c = {s, gas, liq, tp, tp->children, rng};
  if (c.mode == SB_SPRAY_CHILDREN_AUTO)
    c.mode = s->p.method == SB_SPRAY_BIRD ? SB_SPRAY_CHILDREN_PARTICLES
                                          : SB_SPRAY_CHILDREN_PARCEL;
  if (c.mode == SB_SPRAY_CHILDREN_PARCEL && s->p.method == SB_SPRAY_BIRD)
    return sbi_error(SB_EINVAL, __func__, "children = parcel changes "
                     "weights: not with the Bird method");
  size_t n0 = s->n;
  for (size_t i = 0; i < n0; i++) {
    int st = advance(&c, i, dt, 0);
    if (st)
      return st;
  }
  return SB_SUCCESS;
}
