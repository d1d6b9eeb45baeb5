/* cases_v12b.c — V12, second part: a 20 nm + 200 nm mixture (kernels per
 * pair type against Gopalakrishnan & Hogan 2011; the joint conditioning
 * of the Langevin detector against the independence of barycentre and
 * relative coordinate assumed by Mohaupt 2011, eqs 5.24-5.26), and the
 * velocities at contact (Mohaupt 2011, §7.2.1): the law of the normal
 * relative velocity at first contact against converged contact time and
 * the flux-weighted Maxwellian, and the DLVO sticking fraction versus the
 * barrier height.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>

#include <smolbridge/kernel.h>
#include <smolbridge/langevin.h>
#include <smolbridge/langevin_hit.h>
#include <smolbridge/stats.h>

#include "cases.h"
#include "firsthit.h"
#include "v12.h"

#define PI 3.14159265358979323846
#define MU_AIR 1.83245e-5
#define LAMBDA_AIR 66e-9

/* ------------------------------------------------------------ mixture */

typedef struct {
  double d, m, tau, B;
} mix_sp;

static void mix_species(double d, mix_sp *s)
{
  s->d = d;
  s->m = sb_sphere_mass(V12_RHO, d);
  s->tau = sb_stokes_tau(V12_RHO, d, MU_AIR,
                         sb_cunningham(sb_knudsen(LAMBDA_AIR, d)));
  s->B = sb_brownian_B(V12_TEMP, s->m, s->tau);
}

/* Contact place.  Given both ends, the exact law makes the large
 * particle's deviation from its chord at contact regress on the relative
 * deviation with slope -V_b/(V_s + V_b) (V the bridge variances; -D_b /
 * (D_s + D_b) for dt >> tau_p, where w = (D_s x_b + D_b x_s)/(D_s + D_b)
 * is independent of the relative path, so conditioning on the contact
 * does not change it).  Mohaupt (2011, eqs 5.24-5.26) draws the mass
 * barycentre independently of the relative coordinate: slope -m_s/M,
 * right only when m_s D_s = m_b D_b.  Pairs from exact transport, first
 * contacts from the sampler; slope by least squares over the three
 * components, with its standard error from the residuals. */
static int bary_slope(const sbv_ctx *ctx, const mix_sp *s, const mix_sp *b,
                      double dt, long ncall, double *slope, double *se,
                      long *nhit)
{
  gsl_rng *r = sbv_rng_alloc(ctx, 1401);
  sb_langevin_hitter *w = sb_langevin_hitter_alloc(NULL);
  if (!r || !w) {
    gsl_rng_free(r);
    sb_langevin_hitter_free(w);
    return SB_ENOMEM;
  }
  const double R = 0.5 * (s->d + b->d);
  const sb_langevin ps = {s->tau, s->B, 0.0}, pb = {b->tau, b->B, 0.0};
  const double vs = sqrt(SB_BOLTZMANN * V12_TEMP / s->m);
  const double vb = sqrt(SB_BOLTZMANN * V12_TEMP / b->m);
  const double sd = sqrt(2.0 * (sb_langevin_var_x(s->tau, s->B, dt) +
                                sb_langevin_var_x(b->tau, b->B, dt)));
  double sx = 0, sy = 0, sxx = 0, sxy = 0, syy = 0;
  long n = 0;
  int st = SB_SUCCESS;
  for (long c = 0; c < ncall && !st; c++) {
    sb_langevin_path P[2];
    memset(P, 0, sizeof P);
    const mix_sp *sp[2] = {s, b};
    const sb_langevin *lp[2] = {&ps, &pb};
    double dir[3];
    gsl_ran_dir_3d(r, &dir[0], &dir[1], &dir[2]);
    const double x0 = R + 2.0 * sd * gsl_rng_uniform(r);
    for (int p = 0; p < 2; p++) {
      P[p].tau = sp[p]->tau;
      P[p].B = sp[p]->B;
      P[p].mass = sp[p]->m;
      for (int k = 0; k < 3; k++) {
        P[p].x0[k] = p ? 0.0 : x0 * dir[k];
        P[p].u0[k] = gsl_ran_gaussian_ziggurat(r, p ? vb : vs);
        double x = P[p].x0[k], u = P[p].u0[k];
        sb_langevin_step(lp[p], dt, r, &x, &u);
        P[p].x1[k] = x;
        P[p].u1[k] = u;
      }
    }
    sb_langevin_contact ct;
    int h = sb_langevin_hitter_sample(w, &P[0], &P[1], R, dt, r, &ct);
    if (h < 0)
      st = -h;
    if (h != 1 || ct.t <= 0.0)
      continue;
    const double f = ct.t / dt;
    for (int k = 0; k < 3; k++) {
      double chs = P[0].x0[k] + f * (P[0].x1[k] - P[0].x0[k]);
      double chb = P[1].x0[k] + f * (P[1].x1[k] - P[1].x0[k]);
      double y = ct.xj[k] - chb;
      double x = (ct.xi[k] - chs) - y;  /* relative (small - large) */
      sx += x, sy += y, sxx += x * x, sxy += x * y, syy += y * y;
    }
    n++;
  }
  const double m3 = 3.0 * (double)n;
  const double cxx = sxx - sx * sx / m3, cxy = sxy - sx * sy / m3;
  const double cyy = syy - sy * sy / m3;
  *slope = cxy / cxx;
  *se = sqrt((cyy - cxy * cxy / cxx) / (m3 - 2.0) / cxx);
  *nhit = n;
  sb_langevin_hitter_free(w);
  gsl_rng_free(r);
  return st;
}

int v12_mixture(const sbv_ctx *ctx, sbv_report *rep)
{
  const int full = ctx->full;
  mix_sp s, b;
  mix_species(20e-9, &s);
  mix_species(200e-9, &b);
  /* kernels per pair type: both species by first-hit counting with the
   * Langevin detector at dt = 10 tau_s; warm-up 50 tau_b */
  lv_run q;
  memset(&q, 0, sizeof q);
  q.nsp = 2;
  q.d[0] = s.d, q.d[1] = b.d;
  q.tau[0] = s.tau, q.tau[1] = b.tau;
  q.mass[0] = s.m, q.mass[1] = b.m;
  q.temp = V12_TEMP;
  q.det = LV_LANGEVIN;
  q.dt = 10.0 * s.tau;
  q.t1 = V12_WARM * b.tau;
  q.T = q.dt * ceil((q.t1 + (full ? 300.0 : 100.0) * b.tau) / q.dt);
  const double Ds = SB_BOLTZMANN * V12_TEMP * s.tau / s.m;
  const double Db = SB_BOLTZMANN * V12_TEMP * b.tau / b.m;
  q.L = 10.0 * sqrt(2.0 * 2.0 * Ds * q.T);
  double Kgh[3], kn[3];
  const mix_sp *A[3] = {&s, &s, &b}, *Bq[3] = {&s, &b, &b};
  for (int t = 0; t < 3; t++) {
    Kgh[t] = sb_kernel_brownian_gh(0.5 * A[t]->d, 0.5 * Bq[t]->d, A[t]->m,
                                   Bq[t]->m, A[t]->tau, Bq[t]->tau,
                                   V12_TEMP);
    kn[t] = sb_kernel_brownian_gh_kn(0.5 * A[t]->d, 0.5 * Bq[t]->d, A[t]->m,
                                     Bq[t]->m, A[t]->tau, Bq[t]->tau,
                                     V12_TEMP);
  }
  /* equal numbers, sized for ~hits contacts of the rarest type */
  const double hits = full ? 10000.0 : 150.0, V = pow(q.L, 3);
  double kmin = fmin(Kgh[0] / 2.0, fmin(Kgh[1], Kgh[2] / 2.0));
  double N = sqrt(hits * V / (kmin * (q.T - q.t1)));
  N = fmin(fmax(N, 100.0), V12_NMAX / 2.0);
  q.N[0] = q.N[1] = (size_t)N;
  sbv_progress(ctx, "  V12 mixture");
  lv_out o;
  static const char *const tn[3] = {"20-20", "20-200", "200-200"};
  if (sbv_writing(ctx)) {
    /* one file; each record is its pair's first_hit.pairs[i,j].K (the
     * capacitance radius, as lv_kernel) over K_GH.  The barycentre
     * slope below is a Monte Carlo of pairs without an engine. */
    static const char *const pn[3] = {"d20nm,d20nm", "d20nm,d200nm",
                                      "d200nm,d200nm"};
    snprintf(q.names[0], sizeof q.names[0], "d20nm");
    snprintf(q.names[1], sizeof q.names[1], "d200nm");
    fh_set_name(rep, "V12_mixture");
    int st = lv_firsthit(ctx, 1400, &q, &o);
    for (int t = 0; t < 3 && !st; t++) {
      char name[96], field[64];
      snprintf(name, sizeof name, "V12/mixture/%s/K_e/K_GH", tn[t]);
      snprintf(field, sizeof field, "first_hit.pairs[%s].K", pn[t]);
      sbv_ini_expect(rep, name, field, 1.0 / Kgh[t]);
    }
    return st;
  }
  int st = lv_firsthit(ctx, 1400, &q, &o);
  if (st)
    return st;
  sbv_note(rep, "Mixture 20 nm + 200 nm (rho_p = %g kg/m^3, air %g K, "
           "Cunningham slip, lambda = %g nm): tau_p = %.3g and %.3g s; "
           "`langevin` at dt = 10 tau_s = %.2f tau_b; %zu + %zu particles, "
           "L = %.3g m, %.3g steps, %.1f s.", V12_RHO, V12_TEMP,
           LAMBDA_AIR * 1e9, s.tau, b.tau, q.dt / b.tau, q.N[0], q.N[1],
           q.L, o.steps, o.cpu);
  double plot[3 * 5];
  for (int t = 0; t < 3 && !st; t++) {
    double K = NAN, lo = NAN, hi = NAN;
    lv_kernel(&q, &o, t, &K, &lo, &hi);
    char name[96];
    snprintf(name, sizeof name, "V12/mixture/%s/K_e/K_GH", tn[t]);
    st = sbv_add_info(rep, name, K / Kgh[t], 1.0, lo / Kgh[t], hi / Kgh[t],
                      0.95);
    sbv_note(rep, "- %s nm: Kn_D = %.3f, K_GH = %.4g m^3/s, K_e/K_GH = "
             "%.4f [%.4f, %.4f], %lu contacts", tn[t], kn[t], Kgh[t],
             K / Kgh[t], lo / Kgh[t], hi / Kgh[t], o.hits[t]);
    double *p = plot + 5 * t;
    p[0] = t, p[1] = kn[t], p[2] = K / Kgh[t], p[3] = lo / Kgh[t];
    p[4] = hi / Kgh[t];
  }
  free(o.vn);
  if (!st)
    st = sbv_plot(ctx, rep, "V12_mixture", "V12: 20 nm + 200 nm, K_e/K_GH "
                  "per pair type (95% intervals)", "type Kn K/KGH lo hi",
                  plot, 3, 5,
                  "set xrange [-0.5:2.5]\nset xtics ('20-20' 0, '20-200' "
                  "1, '200-200' 2)\nset ylabel 'K_e / K_GH'\n"
                  "plot $DATA u 1:3:4:5 w yerrorbars pt 7 t 'langevin', 1 "
                  "lc rgb 'black' t ''");
  if (st)
    return st;
  /* contact place: dt = 200 tau_b (Brownian limit of the bridges) */
  double slope, se;
  long nh;
  sbv_progress(ctx, "  V12 mixture: contact place");
  st = bary_slope(ctx, &s, &b, 200.0 * b.tau, full ? 400000 : 100000, &slope,
                  &se, &nh);
  if (st)
    return st;
  const double exact = -Db / (Ds + Db), thesis = -s.m / (s.m + b.m);
  const double z = 3.89;  /* two-sided 1e-4 normal quantile */
  st = sbv_add_side(rep, "V12/mixture/place/slope/thesis-eq5.26", 0, slope,
                    thesis, slope - z * se, slope + z * se, 1.0 - SBV_ALPHA,
                    NAN);
  if (!st)
    st = sbv_add_info(rep, "V12/mixture/place/slope/-Db/(Ds+Db)", slope,
                      exact, slope - z * se, slope + z * se,
                      1.0 - SBV_ALPHA);
  sbv_note(rep, "Contact place (20-200 pairs, dt = 200 tau_b, %ld "
           "contacts): regression slope of the large particle's deviation "
           "from its chord on the relative deviation = %.5f +- %.5f; exact "
           "(joint conditioning, Brownian limit) -D_b/(D_s + D_b) = %.5f; "
           "Mohaupt (2011) eq 5.26 (barycentre independent of the relative "
           "coordinate) -m_s/M = %.5f: the large particle moves ~%.0fx "
           "more at contact than the thesis' correction step places it "
           "(normal approximation for the slope's interval).  The "
           "Brownian-limit value is approached, not reached: contacts "
           "early in the step see the large particle's motion smoothed "
           "over its tau_p (informational row).", nh, slope, se, exact,
           thesis, slope / thesis);
  return st;
}

/* ------------------------------------------------------------ velocities */

/* P(|v_n| > sqrt(2 W / m_red)) from samples: the sticking fraction of
 * the rule "stick iff the normal relative kinetic energy exceeds W". */
static double stick_frac(const double *vn, size_t n, double vmin)
{
  size_t k = 0;
  for (size_t i = 0; i < n; i++)
    k += fabs(vn[i]) > vmin;
  return n ? (double)k / (double)n : NAN;
}

/* Flux-weighted Maxwellian of |v_n|: CDF 1 - exp(-v^2 / (2 s^2)). */
static double fm_cdf(double v, void *vp)
{
  double s = *(double *)vp;
  return v <= 0.0 ? 0.0 : -expm1(-0.5 * v * v / (s * s));
}

int v12_velocities(const sbv_ctx *ctx, sbv_report *rep, const v12_vel *vel,
                   int nvel)
{
  static const double wkt[7] = {0.0, 0.5, 1.0, 2.0, 3.0, 4.0, 5.0};
  const int full = ctx->full;
  const size_t vcap = full ? 20000 : 2000;
  int st = SB_SUCCESS;
  double plot[2 * 7 * 6];
  size_t np = 0;
  sbv_note(rep, "Velocities at contact: normal relative velocity at first "
           "contacts (after the warm-up) of `langevin` (dt = tau_p%s) "
           "against contact time at dt = 0.01 tau_p (velocities "
           "interpolated to the contact), from the runs of the flat table, "
           "two-sample KS; the sticking fraction S(W) = P(m_red v_n^2 / 2 > "
           "W) of the DLVO rule with E_rel at contact against the "
           "free-molecular exp(-W/kT) and the stationary-Maxwellian "
           "erfc(sqrt(W/kT)) of SB_AGGLO_EREL_STATIONARY.",
           full ? " and 10 tau_p" : "");
  for (int k = 0; k < nvel && !st; k++) {
    const v12_vel *v = &vel[k];
    if (!v->vref)
      continue;
    v12_phys ph;
    v12_physics(v->kn, &ph);
    const double mred = 0.5 * ph.m, kT = SB_BOLTZMANN * ph.temp;
    for (int d = 0; d < 2 && !st; d++) {
      if (!v->vl[d])
        continue;
      const double dtt = d ? 10.0 : 1.0;
      for (int w = 0; w < 7 && !d && np < 14 && !st; w++) {
        double vmin = sqrt(2.0 * wkt[w] * kT / mred);
        double *p = plot + 6 * np++;
        p[0] = wkt[w];
        p[1] = stick_frac(v->vl[d], v->nl[d], vmin);
        p[2] = stick_frac(v->vref, v->nref, vmin);
        p[3] = exp(-wkt[w]);
        p[4] = erfc(sqrt(wkt[w]));
        p[5] = v->kn;
        char name[96];
        snprintf(name, sizeof name, "V12/stick/Kn=%g/W=%gkT/S_lv/S_ct",
                 v->kn, wkt[w]);
        double lo, hi;
        size_t ns = (size_t)(p[1] * v->nl[d] + 0.5);
        sb_binomial_ci(ns, v->nl[d], 0.95, &lo, &hi);
        st = sbv_add_info(rep, name, p[1], p[2], lo, hi, 0.95);
      }
      if (st)
        break;
      char name[96];
      snprintf(name, sizeof name, "V12/vn/Kn=%g/dt=%g/langevin-vs-ct/KS2",
               v->kn, dtt);
      double *a = malloc(v->nl[d] * sizeof *a);
      double *b = malloc(v->nref * sizeof *b);
      if (!a || !b)
        st = SB_ENOMEM;
      else {
        memcpy(a, v->vl[d], v->nl[d] * sizeof *a);
        memcpy(b, v->vref, v->nref * sizeof *b);
        st = lv_add_ks2(rep, name, a, v->nl[d], b, v->nref);
      }
      free(a);
      free(b);
      sbv_note(rep, "- Kn_D = %g, dt = %g tau_p: %zu and %zu contacts; "
               "S(1 kT) = %.3f (langevin), %.3f (contact time), "
               "exp(-1) = %.3f, erfc(1) = %.3f", v->kn, dtt, v->nl[d],
               v->nref, stick_frac(v->vl[d], v->nl[d], sqrt(2.0 * kT / mred)),
               stick_frac(v->vref, v->nref, sqrt(2.0 * kT / mred)),
               exp(-1.0), erfc(1.0));
    }
  }
  if (!st)
    st = sbv_plot(ctx, rep, "V12_sticking", "V12: DLVO sticking fraction "
                  "at first contact versus barrier height",
                  "W/kT S_langevin S_contact exp(-W) erfc(sqrt(W)) Kn",
                  plot, np, 6,
                  "set logscale y\nset xlabel 'W_max / k_B T'\n"
                  "set ylabel 'sticking fraction'\n"
                  "plot $DATA u ($6==0.05?$1:1/0):2 w p pt 7 t 'langevin, "
                  "Kn_D 0.05', $DATA u ($6==0.05?$1:1/0):3 w l t 'contact "
                  "time, Kn_D 0.05', $DATA u ($6==0.5?$1:1/0):2 w p pt 5 t "
                  "'langevin, Kn_D 0.5', $DATA u ($6==0.5?$1:1/0):3 w l t "
                  "'contact time, Kn_D 0.5', $DATA u 1:4 w l dt 2 t "
                  "'exp(-W/kT) (flux-weighted)', $DATA u 1:5 w l dt 3 t "
                  "'erfc(sqrt(W/kT)) (stationary)'");
  if (st)
    return st;
  /* free-molecular limit: first contacts within tau_p of a uniform,
   * Maxwellian start are straight-line flights, so |v_n| follows the
   * flux-weighted Maxwellian of variance k_B T / m_red exactly (up to
   * O(dt/tau_p) curvature) */
  v12_phys ph;
  v12_physics(10.0, &ph);
  lv_run q;
  lv_out o;
  sbv_progress(ctx, "  V12 velocities: free-molecular limit");
  v12_size(&ph, LV_LANGEVIN, 0.25, full ? 20000.0 : 800.0, 0.0,
           0.5 * ph.tau, vcap, &q);
  q.T = 0.5 * ph.tau;  /* two steps */
  if (sbv_writing(ctx))
    fh_set_name(rep, "V12_vn_free_molecular");
  st = lv_firsthit(ctx, 1601, &q, &o);
  if (st)
    return st;
  double s = sqrt(SB_BOLTZMANN * ph.temp / (0.5 * ph.m)), D, p;
  if (sbv_writing(ctx)) {  /* KS of |v_n| s^-1 (contacts.csv) */
    char spec[96];
    snprintf(spec, sizeof spec, "contacts.csv vn flux-maxwell %.17g",
             1.0 / s);
    sbv_ini_no_expect(rep);  /* not first_hit.K */
    sbv_ini_expect_stat(rep, "expect-ks", "V12/vn/free-molecular/KS", spec);
    return SB_SUCCESS;
  }
  for (size_t i = 0; i < o.nvn; i++)
    o.vn[i] = fabs(o.vn[i]);
  st = sb_ks_test(o.vn, o.nvn, fm_cdf, &s, &D, &p);
  if (!st)
    st = sbv_add_ks(rep, "V12/vn/free-molecular/KS", o.nvn, D, p);
  sbv_note(rep, "Free-molecular check: Kn_D = 10, first contacts in "
           "[0, tau_p/2] from a uniform Maxwellian start, dt = tau_p/4: "
           "%zu contacts, KS against the flux-weighted Maxwellian D = %.4f, "
           "p = %.3g.", o.nvn, D, p);
  free(o.vn);
  return st;
}
