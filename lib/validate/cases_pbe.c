/* cases_pbe.c — `smolbridge validate` cases for the CVODE side of V8
 * (engine agglomeration vs population balance): the population-balance
 * solvers against the analytic solutions.  Deterministic (no randomness);
 * each record's interval is the tolerance band around the numerical value:
 * PASS iff the analytic value lies in [est (1 - tol), est (1 + tol)]. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include <smolbridge/pbe.h>

#include "cases.h"

static int add_rel(sbv_report *rep, const char *name, double est,
                   double ref, double tol)
{
  return sbv_add_relband(rep, name, est, ref, tol);
}

/* Discrete system, K = 60 sizes + lumped tail, vs analytic n_k, k <= 50. */
static int case_discrete(const sbv_ctx *ctx, sbv_report *rep)
{
  static const char *names[] = {"constant", "additive", "multiplicative"};
  double plotdata[50 * 5];
  for (int kind = 0; kind < 3; kind++) {
    sb_kernel_spec ks;
    sb_kernel_spec_init(&ks, (sb_kernel_type)kind);
    sb_pbe_config c;
    sb_pbe_config_init(&c);
    c.nsizes = 60;
    c.kparams = &ks;
    c.rtol = 1e-10;
    c.atol = 1e-40;
    sb_pbe *p = sb_pbe_alloc(&c);
    if (!p)
      return sb_last_status();
    sb_pbe_init_mono(p, 1.0);
    double ts1[] = {0.1, 1, 10}, ts2[] = {0.1, 0.5, 0.9};
    const double *ts = kind == 2 ? ts2 : ts1;
    for (int it = 0; it < 3; it++) {
      sb_pbe_report r;
      int st = sb_pbe_solve(p, &ts[it], 1, NULL, NULL, &r);
      if (st) {
        sbv_note(rep, "- %s: %s", names[kind], sb_last_error());
        sb_pbe_free(p);
        return st;
      }
      const double *n = sb_pbe_state(p);
      sb_pbe_analytic_cmp cmp;
      sb_pbe_compare_analytic(n, 50, (sb_pbe_kernel_kind)kind, ts[it], 0,
                              &cmp);
      for (int k = 1; k <= 50 && kind == 0 && it > 0; k++) {
        double *row = plotdata + (k - 1) * 5; /* tau = 1: cols 1-2, 10: 3-4 */
        row[0] = k;
        row[2 * it - 1] = n[k - 1];
        row[2 * it] = sb_pbe_mono_n(SB_PBE_CONSTANT, k, ts[it]);
      }
      char name[96];
      snprintf(name, sizeof name, "V8/pbe-discrete/%s/tau=%g/worst-n_k",
               names[kind], ts[it]);
      add_rel(rep, name, cmp.nworst, cmp.exact_worst, 1e-6);
      snprintf(name, sizeof name, "V8/pbe-discrete/%s/tau=%g/M1", names[kind],
               ts[it]);
      double m[3];
      sb_pbe_state_moments(p, m);
      add_rel(rep, name, m[1], 1.0, 1e-12);
      sbv_note(rep, "- %s, tau = %g: max relative error on n_k (k <= 50) "
               "%.2g, M1 drift %.2g, %ld steps", names[kind], ts[it], cmp.maxrel,
               r.m1_drift, r.nsteps);
    }
    sb_pbe_free(p);
  }
  sbv_note(rep, "- criterion: relative error <= 1e-6 on every n_k, k <= 50 "
           "(the worst k is recorded); K = 60 sizes plus the lumped tail, "
           "rtol 1e-10");
  sbv_plot(ctx, rep, "pbe_discrete_constant",
           "Constant kernel: CVODE discrete vs analytic",
           "k n(tau=1) exact(tau=1) n(tau=10) exact(tau=10)", plotdata, 50, 5,
           "set logscale y\nset xlabel 'k'\nset ylabel 'n_k/N0'\n"
           "plot $DATA u 1:2 w p pt 6 t 'CVODE tau=1', $DATA u 1:3 w l t "
           "'exact tau=1', $DATA u 1:4 w p pt 4 t 'CVODE tau=10', $DATA u "
           "1:5 w l t 'exact tau=10'");
  return 0;
}

/* Sectional, constant kernel, 300 sections over 12 decades, tau to 1e4. */

/* Sectional solver, 300 sections over 12 decades, monodisperse start (NULL
 * on error, recorded). */
static sb_pbe *sectional_300(sb_kernel_spec *ks, sb_kernel_type type)
{
  sb_kernel_spec_init(ks, type);
  sb_pbe_config c;
  sb_pbe_config_init(&c);
  sb_pbe_config_sectional(&c, 300, 12.0);
  c.kparams = ks;
  sb_pbe *p = sb_pbe_alloc(&c);
  if (p)
    sb_pbe_init_mono(p, 1.0);
  return p;
}

static int case_sectional(const sbv_ctx *ctx, sbv_report *rep)
{
  sb_kernel_spec ks;
  sb_pbe *p = sectional_300(&ks, SB_KERNEL_CONSTANT);
  if (!p)
    return sb_last_status();
  double ts[] = {0.01, 0.1, 1, 10, 100, 1000, 10000}, mom[7][3];
  sb_pbe_report r;
  int st = sb_pbe_solve_moments(p, ts, 7, mom, &r);
  sb_pbe_free(p);
  if (st) {
    sbv_note(rep, "- %s", sb_last_error());
    return st;
  }
  double rows[7 * 5]; /* tau, M0, M0 exact, M2, M2 exact */
  for (int i = 0; i < 7; i++) {
    double m[3], *row = rows + 5 * i;
    sb_pbe_analytic_moments(SB_PBE_CONSTANT, 0, ts[i], m);
    row[0] = ts[i];
    row[1] = mom[i][0];
    row[2] = m[0];
    row[3] = mom[i][2];
    row[4] = m[2];
  }
  char name[96];
  for (int i = 0; i < 7; i += 3) {
    snprintf(name, sizeof name, "V8/pbe-sectional/constant/tau=%g/M0", ts[i]);
    add_rel(rep, name, rows[5 * i + 1], rows[5 * i + 2], 0.01);
    snprintf(name, sizeof name, "V8/pbe-sectional/constant/tau=%g/M2", ts[i]);
    add_rel(rep, name, rows[5 * i + 3], rows[5 * i + 4], 0.01);
  }
  add_rel(rep, "V8/pbe-sectional/constant/M1-drift", 1.0 + r.m1_drift, 1.0,
          1e-10);
  sbv_note(rep, "- 300 sections, ratio 10^(12/299); criterion: M0, M2 "
           "within 1%%, M1 within 1e-10; M1 drift %.2g, %ld steps",
           r.m1_drift, r.nsteps);
  sbv_plot(ctx, rep, "pbe_sectional_constant",
           "Sectional (fixed pivot) vs analytic moments, constant kernel",
           "tau M0 M0exact M2 M2exact", rows, 7, 5,
           "set logscale xy\nset xlabel 'tau'\nplot $DATA u 1:2 w p pt 6 t "
           "'M0', $DATA u 1:3 w l t 'M0 exact', $DATA u 1:4 w p pt 4 t 'M2', "
           "$DATA u 1:5 w l t 'M2 exact'");
  return 0;
}

/* Gelation of the multiplicative kernel: M2 = 1/(1 - tau) diverges at
 * tau = 1; estimate by linear extrapolation of 1/M2 through M2 = 20. */
static int case_gelation(const sbv_ctx *ctx, sbv_report *rep)
{
  (void)ctx;
  sb_kernel_spec ks;
  sb_pbe *p = sectional_300(&ks, SB_KERNEL_MULTIPLICATIVE);
  if (!p)
    return sb_last_status();
  double ts[200];
  int nt = 0;
  for (double t = 0.5; t < 0.9999 && nt < 200; t += 0.0025)
    ts[nt++] = t;
  double tgel; /* NaN if M2 never crossed 20 */
  sb_pbe_gelation_time(p, ts, (size_t)nt, 20.0, &tgel);
  sb_pbe_free(p);
  add_rel(rep, "V8/pbe-gelation/multiplicative/tau_gel", tgel, 1.0, 0.01);
  sbv_note(rep, "- sectional, 300 sections over 12 decades; 1/M2 "
           "extrapolated to 0 through M2 = 20; exact tau_gel = 1 "
           "(K N0 v1^2 t); criterion +-1%%; estimate %.5f", tgel);
  return 0;
}

/* Self-preserving distribution, Brownian continuum kernel in units of
 * K0 = 2kT/(3 mu): grids 2^(1/4) and 2^(1/8) over 9 decades, to
 * tau = K0 N0 t = 1e4; sigma_g extrapolated (h^2) vs the published 1.445
 * (Vemury, Kusters & Pratsinis 1994; Friedlander & Wang 1966 ~1.44), and
 * M0 tau vs 2/a, a = 2 + 2 exp(ln^2 1.445) (lognormal estimate). */
static double k_brown_co(double v, double w, const void *par)
{
  (void)par;
  return (1 / cbrt(v) + 1 / cbrt(w)) * (cbrt(v) + cbrt(w));
}

static int case_selfpres(const sbv_ctx *ctx, sbv_report *rep)
{
  double sg[2] = {0, 0}, m0t = 0, mr = 0, plot[400 * 2];
  size_t np = 0;
  for (int g = 0; g < 2; g++) {
    sb_pbe_config c;
    sb_pbe_config_init(&c);
    sb_pbe_config_sectional_ratio(&c, pow(2.0, 1.0 / (g ? 8.0 : 4.0)), 9.0);
    c.kernel = k_brown_co;
    c.kparams = NULL;
    sb_pbe *p = sb_pbe_alloc(&c);
    if (!p)
      return sb_last_status();
    sb_pbe_init_mono(p, 1.0);
    double t = 1e4;
    int st = sb_pbe_solve(p, &t, 1, NULL, NULL, NULL);
    if (st) {
      sbv_note(rep, "- %s", sb_last_error());
      sb_pbe_free(p);
      return st;
    }
    const double *v = sb_pbe_volumes(p), *n = sb_pbe_state(p);
    size_t nb = sb_pbe_nbins(p);
    double m[3];
    sb_pbe_state_moments(p, m);
    sg[g] = sb_pbe_sigma_g(v, n, nb);
    if (g) {
      m0t = m[0] * t;
      mr = m[0] * m[2] / (m[1] * m[1]);
      /* similarity variables: eta = v M0/M1, psi = n(v) M1/M0^2 with the
       * density n(v) = N_i/(x_i (r^1/2 - r^-1/2)) */
      double w = sqrt(c.ratio) - 1 / sqrt(c.ratio);
      for (size_t i = 0; i < nb && np < 400; i++) {
        double eta = v[i] * m[0] / m[1];
        double psi = n[i] / (v[i] * w) * m[1] / (m[0] * m[0]);
        if (eta > 1e-3 && eta < 10 && psi > 1e-8) {
          plot[2 * np] = eta;
          plot[2 * np + 1] = psi;
          np++;
        }
      }
    }
    sb_pbe_free(p);
  }
  double sgx = sg[1] + (sg[1] - sg[0]) / 3;
  add_rel(rep, "V8/pbe-self-preserving/brownian-co/sigma_g", sgx, 1.445,
          0.003);
  double l = log(1.445), a = 2 + 2 * exp(l * l);
  add_rel(rep, "V8/pbe-self-preserving/brownian-co/M0*tau", m0t, 2 / a,
          0.005);
  sbv_note(rep, "- sectional grids 2^(1/4), 2^(1/8) over 9 decades, "
           "tau = K0 N0 t = 1e4: sigma_g %.5f, %.5f, extrapolated %.5f "
           "(published 1.445); M0 K0 t = %.5f (lognormal estimate %.5f; "
           "M0 ~ 1/t); M0 M2/M1^2 = %.5f", sg[0], sg[1], sgx, m0t, 2 / a,
           mr);
  sbv_plot(ctx, rep, "pbe_self_preserving",
           "Self-preserving distribution, Brownian continuum kernel",
           "eta psi", plot, np, 2,
           "set logscale xy\nset xlabel 'eta = v M0/M1'\nset ylabel "
           "'psi = n(v) M1/M0^2'\nplot $DATA u 1:2 w lp pt 6 t "
           "'sectional 2^(1/8), tau = 1e4'");
  return 0;
}

const sbv_case sbv_cases_pbe[] = {
    {"V8/pbe-discrete", "CVODE discrete Smoluchowski vs analytic n_k",
     case_discrete},
    {"V8/pbe-sectional", "fixed-pivot sectional moments vs analytic",
     case_sectional},
    {"V8/pbe-gelation", "multiplicative kernel: M2 diverges at tau = 1",
     case_gelation},
    {"V8/pbe-self-preserving",
     "Brownian continuum kernel reaches the self-preserving form",
     case_selfpres},
};
const size_t sbv_ncases_pbe = sizeof sbv_cases_pbe / sizeof sbv_cases_pbe[0];
