/* cases_spray_breakup.c — V14 breakup cases of the spray module:
 *
 *  V14/spray-tab    closed form vs GSL's rk8pd integration of the TAB
 *     equation; breakup time vs We against arccos(1 - 12/We)/omega
 *     (undamped); critical We 6 (undamped) and 12/(1 + e^{-pi/(omega
 *     t_d)}) (damped) by integrating to the first maximum; children's
 *     Sauter radius (Monte Carlo) vs r32 and the energy balance (O'Rourke
 *     & Amsden 1987); Bird's constant-weight children vs the exact
 *     expectation of their exact-volume scheme (a renewal equation).
 *  V14/spray-reitz  liquid volume conserved to round-off; the closed form
 *     at frozen Lambda, Omega vs rk8pd; the stepped radius vs the full
 *     model's quadrature solution; parents' radius distribution vs the
 *     push-forward of the initial law (KS); children number vs its
 *     integral.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <gsl/gsl_interp.h>
#include <gsl/gsl_odeiv2.h>
#include <gsl/gsl_sf_gamma.h>

#include <smolbridge/spray.h>
#include <smolbridge/stats.h>

#include "common/numutil.h"
#include "cases.h"
#include "cases_spray.h"

#define PI 3.14159265358979323846

/* ================================================================ TAB */

typedef struct {
  double F, w02, b2; /* y'' = F - w02 y - b2 y' */
} tab_ode;

static int tab_rhs(double t, const double y[], double f[], void *par)
{
  (void)t;
  const tab_ode *o = par;
  f[0] = y[1];
  f[1] = o->F - o->w02 * y[0] - o->b2 * y[1];
  return GSL_SUCCESS;
}

/* Integrate the TAB equation with GSL rk8pd from (y0, yd0) to t. */
static void tab_integrate(const tab_ode *o, double y0, double yd0, double t,
                          double *y, double *yd)
{
  gsl_odeiv2_system sys = {tab_rhs, NULL, 2, (void *)o};
  double h = 1e-3 / sqrt(o->w02);
  gsl_odeiv2_driver *d =
      gsl_odeiv2_driver_alloc_y_new(&sys, gsl_odeiv2_step_rk8pd, h, 1e-13,
                                    1e-13);
  double yy[2] = {y0, yd0}, tt = 0;
  gsl_odeiv2_driver_apply(d, &tt, t, yy);
  gsl_odeiv2_driver_free(d);
  *y = yy[0];
  *yd = yy[1];
}

/* CDF of the exponential law of mean p[0] truncated to [0, p[1]]. */
static double trunc_exp_cdf(double x, void *par)
{
  const double *p = par;
  if (x <= 0)
    return 0.0;
  if (x >= p[1])
    return 1.0;
  return expm1(-x / p[0]) / expm1(-p[1] / p[0]);
}

/* Expected children surface of the Bird (constant weight) TAB breakup:
 * children radii are drawn i.i.d. from the exponential law of mean m
 * truncated at the parent radius r_p until the parent's volume is used,
 * the draw that would exceed the remaining volume v being replaced by a
 * child of volume v.  In units of r_p (r_p = 1, mt = m/r_p), the
 * expected sum of the children's r^2 from a remaining volume v solves the
 * renewal equation
 *   h(v) = int_0^{min(1, v^{1/3})} g(r) [r^2 + h(v - r^3)] dr
 *          + (1 - G(v^{1/3})) v^{2/3},
 * g, G the truncated exponential density and CDF.  Solved on a uniform
 * grid of v, h linear between nodes.  At node v_k = k/K the integrand is
 * smooth between the radii where v_k - r^3 crosses a node, so each of
 * those k pieces is integrated by a fixed Gauss-Legendre rule (exact to
 * rounding for these smooth pieces; an adaptive rule over the whole range
 * meets its k kinks one by one and costs ~100x more).  Only the last
 * piece, the draws with r^3 < 1/K, reads h(v_k) itself, and linearly:
 * h(v_k) = A + B h(v_k), solved in closed form.  The scheme's Sauter
 * radius over many breakups (ratio of sums) converges to r_p / h(1). */
#define RN_K 2000
#define RN_GL 12 /* Gauss-Legendre nodes per piece */

static double bird_children_area(double mt)
{
  double *h = calloc(RN_K + 1, sizeof *h);
  gsl_integration_glfixed_table *gl = gsl_integration_glfixed_table_alloc(RN_GL);
  if (!h || !gl) {
    free(h);
    if (gl)
      gsl_integration_glfixed_table_free(gl);
    return NAN;
  }
  const double Z = -expm1(-1.0 / mt), K = RN_K;
  double xi[RN_GL], wi[RN_GL];
  for (int i = 0; i < RN_GL; i++)
    gsl_integration_glfixed_point(-1.0, 1.0, (size_t)i, &xi[i], &wi[i], gl);
  for (int k = 1; k <= RN_K; k++) {
    const double v = k / K, top = cbrt(v);
    /* piece j: v - r^3 in [j/K, (j+1)/K], r from cbrt(v - j/K) down to
     * cbrt(v - (j+1)/K); h between nodes j and j + 1 */
    double E = 0.0, A = 0.0, B = 0.0, hi = top;
    for (int j = 0; j < k; j++) {
      const double lo = j == k - 1 ? 0.0 : cbrt((k - j - 1) / K);
      const double c = 0.5 * (hi + lo), d = 0.5 * (hi - lo);
      for (int i = 0; i < RN_GL; i++) {
        const double r = c + d * xi[i], w = d * wi[i];
        const double g = w * exp(-r / mt) / (mt * Z);
        /* theta: position of v - r^3 between nodes j and j + 1 */
        const double theta = (k - j) - K * r * r * r;
        if (j < k - 1) {
          E += g * (r * r + h[j] + theta * (h[j + 1] - h[j]));
        } else { /* j = k - 1: nodes k - 1 and k, h[k] unknown */
          A += g * (r * r + (1.0 - theta) * h[k - 1]);
          B += g * theta;
        }
      }
      hi = lo;
    }
    const double tail = (1.0 + expm1(-top / mt) / Z) * pow(v, 2.0 / 3.0);
    h[k] = (E + A + tail) / (1.0 - B);
  }
  double area = h[RN_K];
  free(h);
  gsl_integration_glfixed_table_free(gl);
  return area;
}

int sbv_spray_case_tab(const sbv_ctx *ctx, sbv_report *rep)
{
  const double r = 100e-6, rho_l = 1000.0, rho_g = 1.2, Cd = 5.0;
  sb_spray_liquid liq = {0.072, 1e-3}, inv = {0.072, 0.0};
  const double w02 = 8 * liq.sigma / (rho_l * r * r * r), w0 = sqrt(w02);
  char name[96];
  int st = SB_SUCCESS;
  /* (a) closed form vs rk8pd, damped, We = 10, from (0.2, -1000/s) */
  {
    double We = 10, U = sqrt(We * liq.sigma / (rho_g * r));
    tab_ode o = {(2.0 / 3.0) * rho_g / rho_l * U * U / (r * r), w02,
                 Cd * liq.mu_l / (rho_l * r * r)};
    double worst = 0;
    for (int k = 1; k <= 8; k++) {
      double t = k * 0.7 / w0, y, yd, yc, ydc;
      tab_integrate(&o, 0.2, -1000.0, t, &y, &yd);
      sb_spray_tab_state(t, r, U, rho_g, rho_l, &liq, Cd, 0.2, -1000.0, &yc,
                         &ydc);
      worst = fmax(worst, fmax(fabs(yc - y), fabs(ydc - yd) / w0));
    }
    st = sbv_spray_add_tol(rep, "V14/tab/closed-form-vs-rk8pd", worst, 0.0,
                           1e-9);
  }
  /* (b) breakup time vs We, undamped: arccos(1 - 12/We)/omega */
  enum { NWE = 7 };
  const double wes[NWE] = {6.05, 6.5, 8, 12, 24, 50, 100};
  double plot[NWE][4];
  for (int k = 0; k < NWE && !st; k++) {
    double U = sqrt(wes[k] * liq.sigma / (rho_g * r)), tb, tbd;
    sb_spray_tab_breakup_time(r, U, rho_g, rho_l, &inv, Cd, 0, 0, 1.0, &tb,
                              NULL);
    sb_spray_tab_breakup_time(r, U, rho_g, rho_l, &liq, Cd, 0, 0, 1.0, &tbd,
                              NULL);
    double ex = acos(1.0 - 12.0 / wes[k]) / w0;
    plot[k][0] = wes[k];
    plot[k][1] = tb * w0;
    plot[k][2] = ex * w0;
    plot[k][3] = isinf(tbd) ? NAN : tbd * w0;
    snprintf(name, sizeof name, "V14/tab/t_b*omega/We=%g/undamped", wes[k]);
    st = sbv_spray_add_tol(rep, name, tb * w0, ex * w0, 1e-9);
  }
  /* (c) critical We: undamped 6; damped 12/(1 + e^{-pi beta/omega}),
   * checked by rk8pd integration to the first maximum t = pi/omega */
  double wc = sb_spray_tab_we_crit(r, rho_l, &liq, Cd);
  double beta = Cd * liq.mu_l / (2 * rho_l * r * r);
  double om = sqrt(w02 - beta * beta), ymax = NAN;
  {
    double U = sqrt(wc * liq.sigma / (rho_g * r)), yd;
    tab_ode o = {(2.0 / 3.0) * rho_g / rho_l * U * U / (r * r), w02,
                 2 * beta};
    tab_integrate(&o, 0, 0, PI / om, &ymax, &yd);
  }
  if (!st)
    st = sbv_spray_add_tol(rep, "V14/tab/We_crit/undamped",
                           sb_spray_tab_we_crit(r, rho_l, &inv, Cd), 6.0,
                           1e-12);
  if (!st)
    st = sbv_spray_add_tol(rep, "V14/tab/y_max(We_crit)/damped-rk8pd", ymax,
                           1.0, 1e-9);
  for (int sgn = -1; sgn <= 1 && !st; sgn += 2) {
    double We = wc * (1 + sgn * 1e-6), tb;
    double U = sqrt(We * liq.sigma / (rho_g * r));
    sb_spray_tab_breakup_time(r, U, rho_g, rho_l, &liq, Cd, 0, 0, 1.0, &tb,
                              NULL);
    snprintf(name, sizeof name, "V14/tab/breaks(We=We_crit%s1e-6)",
             sgn < 0 ? "-" : "+");
    st = sbv_spray_add_tol(rep, name, isinf(tb) ? 0.0 : 1.0,
                           sgn < 0 ? 0.0 : 1.0, 0.0);
  }
  /* (d) energy balance of r32 at breakup (y = 1, ydot): parent surface
   * 4 pi r^2 sigma + oscillation K pi/5 rho r^5 (ydot^2 + w0^2) (K = 10/3)
   * = children surface 4 pi r^2 sigma (r/r32) + pi/6 rho r^5 ydot^2 */
  const double ydb = 0.8 * w0, Kosc = 10.0 / 3.0;
  double r32 = sb_spray_tab_r32(r, ydb, rho_l, liq.sigma);
  double Ep = 4 * PI * r * r * liq.sigma +
              Kosc * PI / 5 * rho_l * pow(r, 5) * (ydb * ydb + w02);
  double Ec = 4 * PI * r * r * liq.sigma * (r / r32) +
              PI / 6 * rho_l * pow(r, 5) * ydb * ydb;
  if (!st)
    st = sbv_spray_add_tol(rep, "V14/tab/r32-energy-balance", Ec / Ep, 1.0,
                           1e-13);
  /* (e) Monte Carlo: parents at y = 1 with ydot = ydb break in the first
   * step.  Nanbu parcels (Gamma(4) radii, weights w r^3/r_c^3): the
   * children's Sauter radius vs that of the exponential law (mean
   * m = r32/3) truncated at r, 3 m P(4,a)/P(3,a).  Bird particles: the
   * exact volume constraint (the last child takes the remainder) biases
   * the Sauter radius; verdicts on the law itself (the first child of
   * each breakup, kept in the parent's slot, is an exact draw of the
   * truncated exponential: KS) and on the Sauter radius against the
   * scheme's exact expectation r / h(1) (bird_children_area). */
  const size_t M = ctx->full ? 50000 : 10000, R = ctx->full ? 16 : 8;
  double *x = malloc(2 * R * sizeof *x);
  if (!x)
    return SB_ENOMEM;
  double a = r / (r32 / 3.0);
  double sref = r32 * gsl_sf_gamma_inc_P(4, a) / gsl_sf_gamma_inc_P(3, a);
  double sbird = r / bird_children_area(r32 / (3.0 * r));
  double ksp = NAN;
  for (int meth = 0; meth < 2 && !st; meth++) {
    gsl_rng *rng = sbv_rng_alloc(ctx, 800 + (unsigned long)meth);
    for (size_t rr = 0; rr < R && !st; rr++) {
      sb_spray *s = sbv_spray_new(&(sbv_spray_setup){
          .method = (sb_spray_method)meth, .rho_l = rho_l, .capacity = M});
      if (!s || !rng) {
        sb_spray_free(s);
        st = SB_ENOMEM;
        break;
      }
      const double zero[3] = {0, 0, 0};
      const size_t np = M / 10;
      for (size_t i = 0; i < np && !st; i++) {
        size_t idx;
        st = sb_spray_add(s, zero, r, 1.0, 0, &idx);
        if (!st)
          st = sb_spray_set_tab(s, idx, 1.0, ydb);
      }
      sb_spray_gas gas = {{0, 0, 0}, rho_g, 0};
      sb_spray_tab_params tp;
      sb_spray_tab_params_default(&tp);
      tp.child_tag = 1;
      if (!st)
        st = sb_spray_tab_step(s, &gas, &liq, &tp, 1e-9, rng);
      const double *rc = sb_spray_radii(s), *w = sb_spray_weights(s);
      double s3 = 0, s2 = 0;
      for (size_t i = 0; i < sb_spray_count(s); i++) {
        s3 += w[i] * rc[i] * rc[i] * rc[i];
        s2 += w[i] * rc[i] * rc[i];
      }
      /* Bird: against the exact expectation of its scheme */
      x[meth * R + rr] = s3 / s2 / (meth == 0 ? sbird : sref);
      if (meth == 0 && rr == 0 && !st) {
        double *first = malloc(np * sizeof *first), D;
        if (!first) {
          st = SB_ENOMEM;
        } else {
          memcpy(first, rc, np * sizeof *first);
          double par[2] = {r32 / 3.0, r};
          sb_ks_test(first, np, trunc_exp_cdf, par, &D, &ksp);
          free(first);
          st = sbv_add_ks(rep, "V14/tab/children-law-KS/bird-particles",
                          np, D, ksp);
        }
      }
      sb_spray_free(s);
    }
    gsl_rng_free(rng);
    if (!st)
      st = sbv_spray_add_replicas(rep, meth == 0
                                           ? "V14/tab/children-r32/"
                                             "bird-particles/scheme"
                                           : "V14/tab/children-r32/"
                                             "nanbu-parcel",
                                  x + meth * R, R, 1.0);
  }
  double bird_r32 = 0;
  for (size_t rr = 0; rr < R; rr++)
    bird_r32 += x[rr] * sbird / sref / (double)R;
  free(x);
  if (st)
    return st;
  sbv_note(rep, "- water drop r = 100 um in air (rho_g = 1.2), sigma = "
           "0.072 N/m, mu_l = 1e-3 Pa s, C_d = 5 (O'Rourke & Amsden): "
           "omega0 = %.4g /s, 1/t_d = %.4g /s, damped We_crit = %.6f", w0,
           beta, wc);
  sbv_note(rep, "- children Sauter radius: %zu parents at y = 1, ydot = "
           "0.8 omega0 break; reference r32 P(4,a)/P(3,a) = %.6g m (r32 = "
           "%.6g m, exponential law truncated at r, a = 3 r/r32); Bird's "
           "particles (constant weight, exact volume: children are drawn "
           "until the parent's volume is used, the last takes the rest): "
           "Sauter radius / reference = %.4f, the scheme's exact "
           "expectation r/h(1) = %.6f of the reference (renewal equation "
           "for the expected children surface h, docs/spray.md §5): a bias "
           "of the exact-volume representation, checked against r/h(1); "
           "their first child per breakup follows the law exactly (KS p = "
           "%.3g)", M / 10, sref, r32, bird_r32, sbird / sref, ksp);
  sbv_plot(ctx, rep, "V14_tab_breakup_time",
           "V14: TAB breakup time vs We (start at rest)",
           "We tb_undamped exact_undamped tb_damped", &plot[0][0], NWE, 4,
           "set logscale x\nset xlabel 'We'\nset ylabel 'omega0 t_b'\nplot "
           "$DATA u 1:2 w p pt 6 t 'root finder, undamped', $DATA u 1:3 w l "
           "t 'arccos(1-12/We)', $DATA u 1:4 w lp pt 4 t 'damped (C_d = 5)'");
  return SB_SUCCESS;
}

/* ============================================================== Reitz */

typedef struct {
  double R, c;
} rz_ode;

static int rz_rhs(double t, const double y[], double f[], void *par)
{
  (void)t;
  const rz_ode *o = par;
  f[0] = -o->c * (y[0] - o->R) / y[0];
  return GSL_SUCCESS;
}

typedef struct {
  double U, rho_g, rho_l;
  const sb_spray_liquid *liq;
  double B0;
} rz_par;

static double child_density(double a, void *par) /* d(a^3)/R(a)^3 */
{
  const rz_par *p = par;
  double L, O;
  sb_spray_reitz_wave(a, p->U, p->rho_g, p->rho_l, p->liq, &L, &O);
  double R = p->B0 * L;
  return 3 * a * a / (R * R * R);
}

/* Children of the model (Reitz 1987): radius R(a) = B0 Lambda(a), born
 * at the rate d(a^3)/R(a)^3 as the parent shrinks.  Table of the
 * cumulative number G(a) = int 3 s^2/R(s)^3 ds on CH_NG radii (GSL QAG
 * per interval, Steffen interpolation).  R(a) need not be monotone (at
 * high We_g it has a flat maximum near the stable radius). */
#define CH_NG 400
typedef struct {
  double a[CH_NG], G[CH_NG];
  gsl_interp *aG;
  gsl_interp_accel *acc;
} child_law;

static int child_law_init(child_law *c, rz_par *par, double lo, double hi)
{
  gsl_function F = {child_density, par};
  c->aG = gsl_interp_alloc(gsl_interp_steffen, CH_NG);
  c->acc = gsl_interp_accel_alloc();
  if (!c->aG || !c->acc) {
    return SB_ENOMEM;
  }
  for (int k = 0; k < CH_NG; k++) {
    c->a[k] = lo + (hi - lo) * k / (CH_NG - 1.0);
    c->G[k] = 0;
    if (k) {
      double res, e;
      sbi_integrate(&F, c->a[k - 1], c->a[k], 0, 1e-12, 200, &res, &e);
      c->G[k] = c->G[k - 1] + res;
    }
  }
  gsl_interp_init(c->aG, c->a, c->G, CH_NG);
  return SB_SUCCESS;
}

static void child_law_free(child_law *c)
{
  gsl_interp_free(c->aG);
  gsl_interp_accel_free(c->acc);
}

static double child_G(const child_law *c, double a)
{
  return gsl_interp_eval(c->aG, c->a, c->G, a, c->acc);
}

/* One step of the parents rb[] -> ra[]: add to sumd[i] the model's
 * children minus those of radius R(rb) the step emits (the shed volume
 * over R(rb)^3) and keep in maxn[i] the model's largest number per step. */
static void child_step_bound(const child_law *c, const rz_par *par,
                             const double *rb, const double *ra, size_t np,
                             double *sumd, double *maxn)
{
  for (size_t i = 0; i < np; i++) {
    if (!(ra[i] < rb[i]))
      continue;
    double L, O;
    sb_spray_reitz_wave(rb[i], par->U, par->rho_g, par->rho_l, par->liq, &L,
                        &O);
    double R = par->B0 * L;
    double n = child_G(c, rb[i]) - child_G(c, ra[i]);
    double m = (rb[i] * rb[i] * rb[i] - ra[i] * ra[i] * ra[i]) / (R * R * R);
    sumd[i] += fabs(n - m);
    maxn[i] = fmax(maxn[i], n);
  }
}

static int cmp_double(const void *x, const void *y)
{
  double a = *(const double *)x, b = *(const double *)y;
  return (a > b) - (a < b);
}

/* Bird children (tag 1, weight 1) of the parents 0..np-1 (started at
 * a0[], now at their current radii): their radius counting function vs
 * the model's, sup_x |N_mc(<= x) - N_ref(<= x)| / N_ref.  N_ref: each
 * parent's path [a_t, a0] cut into CH_NS pieces, each a point mass (its
 * number G(top) - G(bottom)) at R of its middle.  Bound of a correct
 * scheme, per parent: the children R(a_start) of each step differ from
 * the model's (radii between R(a_end) and R(a_start)) by sumd (their
 * number), at most one step's children per monotone piece of R straddle
 * x (two pieces: maxn twice), one child may wait in the shed volume, and
 * the reference's own pieces straddling x (twice the largest). */
#define CH_NS 2000
typedef struct {
  double R, n;
} rmass;

static int cmp_rmass(const void *x, const void *y)
{
  double a = ((const rmass *)x)->R, b = ((const rmass *)y)->R;
  return (a > b) - (a < b);
}

static int reitz_children_law(sbv_report *rep, const child_law *c,
                              const rz_par *par, const sb_spray *s,
                              const double *a0, size_t np,
                              const double *sumd, const double *maxn,
                              double *sup, double *bound)
{
  size_t n = sb_spray_count(s), m = 0, nr = np * CH_NS;
  const double *r = sb_spray_radii(s);
  const int *tag = sb_spray_tags(s);
  double *x = malloc(n * sizeof *x);
  rmass *ref = malloc(nr * sizeof *ref);
  if (!x || !ref) {
    free(x);
    free(ref);
    return SB_ENOMEM;
  }
  for (size_t i = 0; i < n; i++)
    if (tag[i] == 1)
      x[m++] = r[i];
  qsort(x, m, sizeof *x, cmp_double);
  double nref = 0, b = 0;
  for (size_t i = 0; i < np; i++) {
    double big = 0;
    for (size_t j = 0; j < CH_NS; j++) {
      double lo = r[i] + (a0[i] - r[i]) * (double)j / CH_NS;
      double hi = r[i] + (a0[i] - r[i]) * (double)(j + 1) / CH_NS, L, O;
      sb_spray_reitz_wave(0.5 * (lo + hi), par->U, par->rho_g, par->rho_l,
                          par->liq, &L, &O);
      rmass *q = ref + i * CH_NS + j;
      q->R = par->B0 * L;
      q->n = child_G(c, hi) - child_G(c, lo);
      nref += q->n;
      big = fmax(big, q->n);
    }
    b += sumd[i] + 2.0 * maxn[i] + 1.0 + 2.0 * big;
  }
  qsort(ref, nr, sizeof *ref, cmp_rmass);
  /* sup over the jumps of both step functions */
  double d = 0, cum = 0;
  size_t k = 0;
  for (size_t j = 0; j <= nr; j++) {
    double xr = j < nr ? ref[j].R : INFINITY;
    while (k < m && x[k] < xr) { /* N_ref constant = cum on [.., xr) */
      d = fmax(d, fmax(fabs((double)(k + 1) - cum), fabs((double)k - cum)));
      k++;
    }
    d = fmax(d, fabs((double)k - cum));
    if (j < nr)
      cum += ref[j].n;
    d = fmax(d, fabs((double)k - cum));
  }
  free(x);
  free(ref);
  *sup = d / nref;
  *bound = b / nref;
  return sbv_spray_add_tol(rep, "V14/reitz/bird/children-radius-law-sup",
                           *sup, 0.0, *bound);
}

/* Push-forward CDF of the parents: a0 = inverse flow (interpolated). */
typedef struct {
  gsl_interp *ip;
  gsl_interp_accel *acc;
  const double *at, *a0;
  size_t n;
  double lo, hi;
} pf_ctx;

static double pf_cdf(double x, void *par)
{
  const pf_ctx *p = par;
  if (x <= p->at[0])
    return 0.0;
  if (x >= p->at[p->n - 1])
    return 1.0;
  double a0 = gsl_interp_eval(p->ip, p->at, p->a0, x, p->acc);
  return (a0 - p->lo) / (p->hi - p->lo);
}

int sbv_spray_case_reitz(const sbv_ctx *ctx, sbv_report *rep)
{
  const double rho_l = 1000.0, rho_g = 10.0, U = 100.0;
  const sb_spray_liquid liq = {0.072, 1e-3};
  sb_spray_reitz_params rp;
  sb_spray_reitz_params_default(&rp);
  const double a0 = 50e-6, lo = 40e-6, hi = 60e-6;
  double L0, O0;
  sb_spray_reitz_wave(a0, U, rho_g, rho_l, &liq, &L0, &O0);
  const double R0 = rp.B0 * L0, c0 = L0 * O0 / (3.726 * rp.B1);
  const double tau0 = a0 / c0, tend = 2.0 * tau0;
  char name[96];
  int st = SB_SUCCESS;
  /* (a) frozen closed form vs rk8pd */
  {
    rz_ode o = {R0, c0};
    gsl_odeiv2_system sys = {rz_rhs, NULL, 1, &o};
    gsl_odeiv2_driver *d = gsl_odeiv2_driver_alloc_y_new(
        &sys, gsl_odeiv2_step_rk8pd, 1e-4 * tau0, 1e-14, 1e-13);
    double y = a0, t = 0, worst = 0;
    for (int k = 1; k <= 10; k++) {
      double tk = k * 0.5 * tau0;
      gsl_odeiv2_driver_apply(d, &t, tk, &y);
      double cf = sb_spray_reitz_radius_frozen(a0, R0, c0, tk);
      worst = fmax(worst, fabs(cf - y) / a0);
    }
    gsl_odeiv2_driver_free(d);
    st = sbv_spray_add_tol(rep, "V14/reitz/frozen-closed-form-vs-rk8pd",
                           worst, 0.0, 1e-10);
  }
  /* (b) stepped radius (Lambda, Omega at each step's radius) vs the full
   * model's quadrature solution, dt = tau0/20, /200, /2000 */
  double err[3];
  for (int q = 0; q < 3 && !st; q++) {
    sb_spray *s = sbv_spray_new(
        &(sbv_spray_setup){.method = SB_SPRAY_NANBU, .rho_l = rho_l});
    if (!s)
      return SB_ENOMEM;
    const double zero[3] = {0, 0, 0};
    sb_spray_gas gas = {{U, 0, 0}, rho_g, 1.8e-5};
    sb_spray_reitz_params rq = rp;
    rq.emit_fraction = 1e30; /* keep one parcel */
    st = sb_spray_add(s, zero, a0, 1.0, 0, NULL);
    int nst = q == 0 ? 20 : (q == 1 ? 200 : 2000);
    for (int k = 0; k < 2 * nst && !st; k++)
      st = sb_spray_reitz_step(s, &gas, &liq, &rq, tend / (2 * nst));
    double aref;
    if (!st)
      st = sb_spray_reitz_radius(a0, tend, U, rho_g, rho_l, &liq, &rp, &aref);
    err[q] = fabs(sb_spray_radii(s)[0] - aref) / aref;
    sb_spray_free(s);
  }
  if (!st)
    st = sbv_spray_add_tol(rep, "V14/reitz/radius-vs-full-model/dt=tau0/2000",
                           err[2], 0.0, 1e-5);
  /* (c) mass, distribution and children: parents uniform in [lo, hi] */
  const size_t Np = ctx->full ? 5000 : 1000;
  const int nsteps = 200;
  double dV[2] = {0, 0}, ksp = NAN, nchild_rel = NAN, chsup = NAN,
         chbound = NAN;
  double hist[30][3], cdfp[40][3]; /* children histogram, parents' CDF */
  memset(hist, 0, sizeof hist);
  memset(cdfp, 0, sizeof cdfp);
  for (int meth = 0; meth < 2 && !st; meth++) {
    gsl_rng *rng = sbv_rng_alloc(ctx, 900 + (unsigned long)meth);
    sb_spray *s = sbv_spray_new(&(sbv_spray_setup){
        .method = (sb_spray_method)meth, .rho_l = rho_l,
        .capacity = meth == 0 ? 64 * Np : 4 * Np});
    if (!s || !rng) {
      sb_spray_free(s);
      gsl_rng_free(rng);
      return SB_ENOMEM;
    }
    const double zero[3] = {0, 0, 0};
    double *a0s = malloc(Np * sizeof *a0s);
    if (!a0s) {
      sb_spray_free(s);
      gsl_rng_free(rng);
      return SB_ENOMEM;
    }
    /* Bird: few parents (each sheds ~10^3 children of weight 1) */
    size_t np = meth == 0 ? Np / 50 : Np;
    for (size_t i = 0; i < np && !st; i++) {
      a0s[i] = lo + (hi - lo) * gsl_rng_uniform(rng);
      st = sb_spray_add(s, zero, a0s[i], 1.0, 0, NULL);
    }
    sb_spray_totals t0, t1;
    sb_spray_get_totals(s, &t0);
    sb_spray_gas gas = {{U, 0, 0}, rho_g, 1.8e-5};
    sb_spray_reitz_params rq = rp;
    rq.child_tag = 1;
    /* Bird: the parents' radii before and after each step, for the
     * children's radius law */
    double *rb = meth == 0 ? calloc(4 * np, sizeof *rb) : NULL;
    if (meth == 0 && !rb)
      st = SB_ENOMEM;
    child_law cl;
    rz_par cpar = {U, rho_g, rho_l, &liq, rp.B0};
    if (meth == 0 && !st) {
      double amin;
      st = sb_spray_reitz_radius(lo, tend, U, rho_g, rho_l, &liq, &rp, &amin);
      if (!st)
        st = child_law_init(&cl, &cpar, 0.99 * amin, hi);
    }
    for (int k = 0; k < nsteps && !st; k++) {
      if (rb)
        memcpy(rb, sb_spray_radii(s), np * sizeof *rb);
      st = sb_spray_reitz_step(s, &gas, &liq, &rq, tend / nsteps);
      if (rb && !st)
        child_step_bound(&cl, &cpar, rb, sb_spray_radii(s), np, rb + 2 * np,
                         rb + 3 * np);
    }
    if (rb && !st)
      st = reitz_children_law(rep, &cl, &cpar, s, a0s, np, rb + 2 * np,
                              rb + 3 * np, &chsup, &chbound);
    if (rb)
      child_law_free(&cl);
    free(rb);
    sb_spray_get_totals(s, &t1);
    dV[meth] = fabs(t1.volume - t0.volume) / t0.volume;
    if (meth == 1 && !st) {
      /* parents: KS vs the push-forward of U[lo, hi] by the flow map */
      enum { NG = 64 };
      double g0[NG], gt[NG];
      for (int k = 0; k < NG && !st; k++) {
        g0[k] = lo + (hi - lo) * k / (NG - 1.0);
        st = sb_spray_reitz_radius(g0[k], tend, U, rho_g, rho_l, &liq, &rp,
                                   &gt[k]);
      }
      gsl_interp *ip = gsl_interp_alloc(gsl_interp_steffen, NG);
      gsl_interp *fw = gsl_interp_alloc(gsl_interp_steffen, NG);
      gsl_interp_accel *acc = gsl_interp_accel_alloc();
      double *xs = malloc(np * sizeof *xs);
      if (!ip || !fw || !acc || !xs)
        st = SB_ENOMEM;
      if (!st) {
        gsl_interp_init(ip, gt, g0, NG);
        gsl_interp_init(fw, g0, gt, NG);
        pf_ctx pf = {ip, acc, gt, g0, NG, lo, hi};
        const double *r = sb_spray_radii(s);
        const int *tag = sb_spray_tags(s);
        size_t m = 0;
        for (size_t i = 0; i < sb_spray_count(s); i++)
          if (tag[i] == 0)
            xs[m++] = r[i];
        double D, pks;
        sb_ks_test(xs, m, pf_cdf, &pf, &D, &pks); /* sorts xs */
        ksp = pks;
        for (int b = 0, q = 0; b < 40; b++) { /* radius in um */
          double x = gt[0] + (gt[NG - 1] - gt[0]) * b / 39.0;
          while ((size_t)q < m && xs[q] <= x)
            q++;
          cdfp[b][0] = 1e6 * x;
          cdfp[b][1] = (double)q / (double)m;
          cdfp[b][2] = pf_cdf(x, &pf);
        }
        st = sbv_add_ks(rep, "V14/reitz/nanbu/parent-radius-KS", m, D, pks);
        /* children: sum of weights vs int d(a^3)/R^3 per parent (a(t)
         * from the interpolated flow map), plus the shed volume not yet
         * emitted */
        rz_par par = {U, rho_g, rho_l, &liq, rp.B0};
        gsl_function F = {child_density, &par};
        gsl_interp_accel *acc2 = gsl_interp_accel_alloc();
        double nref = 0, nmc = 0, shed = 0, res, e;
        const double *w = sb_spray_weights(s), *sv = sb_spray_shed_volume(s);
        for (size_t i = 0; i < np && acc2; i++) {
          double at = gsl_interp_eval(fw, g0, gt, a0s[i], acc2);
          sbi_integrate(&F, at, a0s[i], 0, 1e-10, 200, &res, &e);
          nref += res;
        }
        gsl_interp_accel_free(acc2);
        for (size_t i = 0; i < sb_spray_count(s); i++) {
          if (tag[i] == 1) {
            nmc += w[i];
            int b = (int)((r[i] - 4.8e-6) / 0.45e-6 * 30);
            if (b >= 0 && b < 30)
              hist[b][1] += w[i];
          }
          shed += sv[i];
        }
        /* unemitted shed volume counted as children of the current R */
        nmc += shed / (4.0 / 3.0 * PI * R0 * R0 * R0);
        nchild_rel = nmc / nref - 1;
        if (!st)
          st = sbv_spray_add_tol(rep, "V14/reitz/nanbu/children-number/ref",
                                 nmc / nref, 1.0, 2e-3);
      }
      free(xs);
      gsl_interp_free(ip);
      gsl_interp_free(fw);
      gsl_interp_accel_free(acc);
    }
    free(a0s);
    sb_spray_free(s);
    gsl_rng_free(rng);
    snprintf(name, sizeof name, "V14/reitz/%s/volume-conservation",
             meth == 0 ? "bird" : "nanbu");
    if (!st)
      st = sbv_spray_add_tol(rep, name, dV[meth], 0.0, 1e-13);
  }
  if (st)
    return st;
  for (int b = 0; b < 30; b++)
    hist[b][0] = 4.8 + (b + 0.5) * 0.45 / 30; /* um */
  sbv_note(rep, "- water drops in a gas of rho_g = 10 kg/m^3 at U = 100 "
           "m/s, sigma = 0.072 N/m, mu_l = 1e-3 Pa s; B0 = 0.61, B1 = 10; "
           "at a0 = 50 um: Lambda = %.4g m, Omega = %.4g /s, R = %.4g m, "
           "tau = %.4g s; run 2 tau", L0, O0, R0, tau0);
  sbv_note(rep, "- stepped radius vs the quadrature solution of the full "
           "model at 2 tau: relative error %.2g, %.2g, %.2g for dt = "
           "tau/20, /200, /2000 (first order: Lambda, Omega frozen over a "
           "step)", err[0], err[1], err[2]);
  sbv_note(rep, "- %zu Nanbu parents (PARCEL children, emitted at 3%% of "
           "the parcel volume), %zu Bird parents (children of weight 1); "
           "volume drift %.2g (Bird), %.2g (Nanbu); parents' radii vs the "
           "push-forward CDF: KS p = %.3g; children number / integral - 1 "
           "= %.2g (criterion 2e-3: emission at the current R)", Np,
           Np / 50, dV[0], dV[1], ksp, nchild_rel);
  sbv_note(rep, "- Bird children radii vs the model's law (radius R(a) = "
           "B0 Lambda(a), number d(a^3)/R(a)^3 along each parent's "
           "simulated path; Reitz 1987): sup_x |N(<= x) - N_ref(<= x)|/N_ref "
           "= %.3g, criterion <= %.3g (the scheme's bound: children of one "
           "step take R at the step's start radius, one step straddles x, "
           "one child may wait in the shed volume)", chsup, chbound);
  sbv_plot(ctx, rep, "V14_reitz_children",
           "V14: Reitz children radii (Nanbu, at 2 tau)",
           "r_um number unused", &hist[0][0], 30, 3,
           "set xlabel 'r (um)'\nset ylabel 'droplets'\nset style fill "
           "solid 0.5\nplot $DATA u 1:2 w boxes t 'children (R = B0 "
           "Lambda of the shrinking parents)'");
  sbv_plot(ctx, rep, "V14_reitz_parents",
           "V14: parent radius CDF at 2 tau vs the push-forward",
           "r_um empirical reference", &cdfp[0][0], 40, 3,
           "set xlabel 'r (um)'\nset ylabel 'P(a <= r)'\nset key top "
           "left\nplot $DATA u 1:2 w steps t 'Nanbu parents', $DATA u "
           "1:3 w l t 'exact flow of U[40, 60] um'");
  return SB_SUCCESS;
}
