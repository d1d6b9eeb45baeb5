/* cases_langevin.c — `smolbridge validate` cases V10 (docs/langevin.md):
 * the exact Langevin scheme (Mohaupt 2011, eq 1.16; sb_langevin_step3_coef)
 * against the Ornstein–Uhlenbeck statistics, as in Mohaupt (2011) App. D.
 *
 *  V10/ou-short-time   Table D.1: tau_p = 3e-6 s, dt = 1e-10 s,
 *                      t_max = 1e-5 s (ballistic: dt/tau_p = 3.3e-5), U(0)
 *                      = 0; mean and variance of U and X vs eqs D.1-D.6 at
 *                      four times, KS of the U and X laws at t_max, plot of
 *                      the four curves (Figs D.1-D.4)
 *  V10/ou-long-time    Table D.2: dt = 1e-2 s, t_max = 250 s (diffusive:
 *                      dt/tau_p = 3.3e3), same records (Figs D.5-D.8)
 *  V10/ou-error-slope  §D.3, eq D.14: RMS error of the estimated mean and
 *                      variance of U vs the number of particles N = 1e2 ...
 *                      1e6 at t_max of both set-ups; fitted log-log slope
 *                      must be -1/2 +- 0.1 (Figs D.9-D.12)
 *
 * Physical parameters.  The tables give N = 10 000, rho_p/rho_f = 1000,
 * d_p = 1 um, tau_p = 3e-6 s.  B needs m_p and T, which they do not give:
 * we take rho_p = 1000 kg/m^3 and T = 293.15 K, so B = sqrt(2 k_B T /
 * (m_p tau_p)) = 2.27 m/s^{3/2} (sb_brownian_B).  Units: SI.
 *
 * Verdicts (level SBV_ALPHA, the interval shown is the one the rule
 * reads).  Mean: t interval and test with the sample standard deviation;
 * variance: two-sided chi-square test of (n-1) s^2/sigma^2 and its exact
 * interval (the samples are exactly Gaussian); law: one-sample KS distance
 * in its acceptance region.  Slopes: -1/2 in the least-squares slope's t
 * interval (approximate).
 *
 * Sample sizes.  --full: the thesis' N = 10 000 particles (3 components
 * each, pooled: 30 000 samples) and its dt, so 1e5 steps (short) and
 * 25 000 steps (long); slope study with 40 replicates per N reaching t_max
 * in 10 exact steps.  --quick: N = 100 (short) and 300 (long) with the
 * same dt and t_max, slope study with 10 replicates and one exact step to
 * t_max (the step is exact for any dt; one step versus many is checked in
 * `make check`, tests/test_langevin_mc.c).
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_cdf.h>
#include <gsl/gsl_fit.h>
#include <gsl/gsl_rng.h>

#include <smolbridge/langevin.h>
#include <smolbridge/simulate.h>
#include <smolbridge/stats.h>

#include "cases.h"

#define NPLOT 100     /* plotted times per set-up */

/* Mohaupt 2011, Tables D.1-D.2 (plus our rho_p, T: see the top of the file) */
#define TAU_P 3e-6
#define D_P 1e-6
#define RHO_P 1000.0
#define TEMP 293.15

typedef struct {
  const char *name;     /* record prefix */
  const char *figs;     /* figures of Mohaupt 2011 reproduced */
  double dt, tmax;
  size_t n_quick, n_full;  /* particles */
  double check_t[4];    /* times of the records */
} lsetup;

static const lsetup short_time = {
    "V10/ou-short-time", "Figs D.1-D.4", 1e-10, 1e-5, 100, 10000,
    {1e-7, 1e-6, 3e-6, 1e-5}};
static const lsetup long_time = {
    "V10/ou-long-time", "Figs D.5-D.8", 1e-2, 250.0, 300, 10000,
    {0.01, 1.0, 10.0, 250.0}};

static double brownian_B(void)
{
  return sb_brownian_B(TEMP, sb_sphere_mass(RHO_P, D_P), TAU_P);
}

/* ------------------------------------------------------------ records */

typedef struct {
  double mean, var; /* sample mean, sample variance (n - 1) */
} mv;

static mv mean_var(const double *v, size_t n)
{
  mv r = {0, 0};
  for (size_t i = 0; i < n; i++)
    r.mean += v[i];
  r.mean /= (double)n;
  for (size_t i = 0; i < n; i++)
    r.var += (v[i] - r.mean) * (v[i] - r.mean);
  r.var /= (double)(n - 1);
  return r;
}

/* Sample mean vs mu: one-sample t test and the t interval at
 * 1 - SBV_ALPHA (Gaussian samples here: exact). */
static int add_mean(sbv_report *rep, const char *name, mv s, double mu,
                    size_t n)
{
  sb_comparison c;
  double nu = (double)(n - 1), se = sqrt(s.var / (double)n);
  double tq = gsl_cdf_tdist_Qinv(0.5 * SBV_ALPHA, nu);
  double pv = se > 0 ? fmin(1.0, 2.0 * gsl_cdf_tdist_Q(fabs(s.mean - mu) /
                                                        se, nu))
                     : (s.mean == mu ? 1.0 : 0.0);
  sb_compare(&c, name, SB_RULE_COVER, s.mean, mu, s.mean - tq * se,
             s.mean + tq * se, 1.0 - SBV_ALPHA, pv);
  return sbv_add(rep, &c);
}

/* Sample variance vs sigma2: two-sided chi-square test and the exact
 * interval at 1 - SBV_ALPHA (Gaussian samples). */
static int add_var(sbv_report *rep, const char *name, mv s, double sigma2,
                   size_t n)
{
  sb_comparison c;
  double nu = (double)(n - 1), q = nu * s.var / sigma2;
  double pv = 2.0 * fmin(gsl_cdf_chisq_P(q, nu), gsl_cdf_chisq_Q(q, nu));
  sb_compare(&c, name, SB_RULE_COVER, s.var, sigma2,
             nu * s.var / gsl_cdf_chisq_Qinv(0.5 * SBV_ALPHA, nu),
             nu * s.var / gsl_cdf_chisq_Pinv(0.5 * SBV_ALPHA, nu),
             1.0 - SBV_ALPHA, fmin(pv, 1.0));
  return sbv_add(rep, &c);
}

typedef struct {
  double mean, sd;
} gpar;

static double gauss_cdf(double x, void *vp)
{
  const gpar *g = vp;
  return gsl_cdf_gaussian_P(x - g->mean, g->sd);
}

/* KS of the samples (copied, sorted) against N(mean, var). */
static int add_ks(sbv_report *rep, const char *name, const double *v,
                  size_t n, double mean, double var)
{
  double *w = malloc(n * sizeof *w);
  if (!w)
    return SB_ENOMEM;
  memcpy(w, v, n * sizeof *w);
  gpar g = {mean, sqrt(var)};
  double d = NAN, p = NAN;
  if (sb_ks_test(w, n, gauss_cdf, &g, &d, &p) != SB_SUCCESS)
    d = p = NAN;
  free(w);
  return sbv_add_ks(rep, name, n, d, p);
}

/* ------------------------------------------------- trajectories (D.1-2) */

/* Plot columns */
enum {
  C_T, C_MU, C_MU_TH, C_MU_LO, C_MU_HI, C_VU, C_VU_TH, C_MX, C_MX_TH,
  C_MX_LO, C_MX_HI, C_VX, C_VX_TH, NCOL
};

/* Plot columns of one variable: sample mean, theory, theory -+ 1.96 sd /
 * sqrt(n), sample variance, theory (same order for U and X). */
static void plot_cols(double *q, mv s, double mean, double var, size_t n)
{
  q[0] = s.mean;
  q[1] = mean;
  q[2] = mean - 1.96 * sqrt(var / (double)n);
  q[3] = mean + 1.96 * sqrt(var / (double)n);
  q[4] = s.var;
  q[5] = var;
}

static int run_setup(const sbv_ctx *ctx, sbv_report *rep, const lsetup *S,
                     unsigned long stream)
{
  const size_t np = ctx->full ? S->n_full : S->n_quick, n = 3 * np;
  const double B = brownian_B();
  const sb_langevin p = {TAU_P, B, 0.0};
  const long nsteps = lround(S->tmax / S->dt);
  const long every = nsteps / NPLOT;
  double *x = calloc(n, sizeof *x), *u = calloc(n, sizeof *u);
  double *plot = malloc((NPLOT + 1) * NCOL * sizeof *plot);
  gsl_rng *r = sbv_rng_alloc(ctx, stream);
  int st = SB_SUCCESS;
  if (!x || !u || !plot || !r) {
    st = SB_ENOMEM;
    goto done;
  }
  sbv_note(rep, "%s (Mohaupt 2011, %s): %zu particles x 3 components pooled "
                "(%zu samples), tau_p = %g s, B = %.6g m/s^1.5, dt = %g s "
                "(dt/tau_p = %.3g), %ld steps to t_max = %g s, X(0) = U(0) "
                "= 0, us = 0.", S->name, S->figs, np, n, TAU_P, B, S->dt,
           S->dt / TAU_P, nsteps, S->tmax);

  long check_step[4];
  for (int k = 0; k < 4; k++)
    check_step[k] = lround(S->check_t[k] / S->dt);
  size_t row = 0;
  for (long step = 0; step <= nsteps; step++) {
    if (step > 0)
      sb_sim_langevin(&p, S->dt, 1, r, np, x, u);
    int is_plot = step % every == 0, is_check = -1;
    for (int k = 0; k < 4; k++)
      if (step == check_step[k])
        is_check = k;
    if (!is_plot && is_check < 0)
      continue;
    double t = (double)step * S->dt;
    sb_langevin_mom m;
    sb_langevin_moments(&p, t, 0.0, 0.0, &m);
    mv su = mean_var(u, n), sx = mean_var(x, n);
    if (is_plot && row <= NPLOT) {
      double *q = plot + row++ * NCOL;
      q[C_T] = t;
      plot_cols(q + C_MU, su, m.mean_u, m.var_u, n);
      plot_cols(q + C_MX, sx, m.mean_x, m.var_x, n);
    }
    if (is_check >= 0) {
      char name[96];
      snprintf(name, sizeof name, "%s/t=%g/mean-U", S->name, t);
      st |= add_mean(rep, name, su, m.mean_u, n);
      snprintf(name, sizeof name, "%s/t=%g/var-U", S->name, t);
      st |= add_var(rep, name, su, m.var_u, n);
      snprintf(name, sizeof name, "%s/t=%g/mean-X", S->name, t);
      st |= add_mean(rep, name, sx, m.mean_x, n);
      snprintf(name, sizeof name, "%s/t=%g/var-X", S->name, t);
      st |= add_var(rep, name, sx, m.var_x, n);
      if (step == nsteps) {
        snprintf(name, sizeof name, "%s/t=%g/U-law-KS", S->name, t);
        st |= add_ks(rep, name, u, n, m.mean_u, m.var_u);
        snprintf(name, sizeof name, "%s/t=%g/X-law-KS", S->name, t);
        st |= add_ks(rep, name, x, n, m.mean_x, m.var_x);
      }
    }
  }
  sbv_note(rep, "Records at t = %g, %g, %g, %g s: mean (z-test) and "
                "variance (chi-square) of U and X vs sb_langevin_moments "
                "(eqs D.1-D.6, exact); KS of the U and X samples at t_max.",
           S->check_t[0], S->check_t[1], S->check_t[2], S->check_t[3]);
  char plotname[64], title[160];
  snprintf(plotname, sizeof plotname, "V10_%s",
           S == &short_time ? "ou_short_time" : "ou_long_time");
  snprintf(title, sizeof title, "V10 %s (Mohaupt 2011, %s): %zu samples, "
           "dt/tau_p = %.3g", S == &short_time ? "short times" : "long times",
           S->figs, n, S->dt / TAU_P);
  /* a 2x2 multiplot: one overall title instead of one per panel */
  char body[2048];
  snprintf(body, sizeof body,
      "unset title\nset multiplot layout 2,2 title '%s'\n"
      "set xlabel 't [s]'\nset key left top\n"
      "set ylabel 'E[U] [m/s]'\n"
      "plot $DATA u 1:4:5 w filledcurves lc rgb '#ddddff' t '95%% band', "
      "$DATA u 1:2 w p pt 7 ps 0.4 lc rgb 'red' t 'simulated', "
      "$DATA u 1:3 w l lw 2 lc rgb 'blue' t 'theory (D.1)'\n"
      "set ylabel 'Var[U] [m^2/s^2]'\nset key right bottom\n"
      "plot $DATA u 1:6 w p pt 7 ps 0.4 lc rgb 'red' t 'simulated', "
      "$DATA u 1:7 w l lw 2 lc rgb 'blue' t 'theory (D.2)'\n"
      "set ylabel 'E[X] [m]'\nset key left top\n"
      "plot $DATA u 1:10:11 w filledcurves lc rgb '#ddddff' t '95%% band', "
      "$DATA u 1:8 w p pt 7 ps 0.4 lc rgb 'red' t 'simulated', "
      "$DATA u 1:9 w l lw 2 lc rgb 'blue' t 'theory (D.4)'\n"
      "set ylabel 'Var[X] [m^2]'\n"
      "plot $DATA u 1:12 w p pt 7 ps 0.4 lc rgb 'red' t 'simulated', "
      "$DATA u 1:13 w l lw 2 lc rgb 'blue' t 'theory (D.6)'\n"
      "unset multiplot", title);
  if (sbv_plot(ctx, rep, plotname, title,
               "t mean_U mean_U_th lo hi var_U var_U_th mean_X mean_X_th lo "
               "hi var_X var_X_th (lo, hi: theory +- 1.96 sd/sqrt(n))",
               plot, row, NCOL, body) != SB_SUCCESS)
    st |= SB_EIO;
done:
  gsl_rng_free(r);
  free(x);
  free(u);
  free(plot);
  return st == SB_SUCCESS ? SB_SUCCESS : (st == SB_EIO ? SB_EIO : SB_ENOMEM);
}

static int case_short(const sbv_ctx *ctx, sbv_report *rep)
{
  return run_setup(ctx, rep, &short_time, 1001);
}

static int case_long(const sbv_ctx *ctx, sbv_report *rep)
{
  return run_setup(ctx, rep, &long_time, 1002);
}

/* --------------------------------------------------- error slope (D.3) */

#define NN 9 /* N = 10^{2, 2.5, ..., 6} */

/* RMS over R replicates of the errors of the estimated mean and variance
 * of U at t (N samples each, K exact steps from U(0) = 0). */
static int rms_errors(const sb_langevin *p, double t, int K, int R,
                      size_t N, const gsl_rng *r, double *rms_m,
                      double *rms_v)
{
  size_t np = (N + 2) / 3;
  double *x = malloc(3 * np * sizeof *x), *u = malloc(3 * np * sizeof *u);
  if (!x || !u) {
    free(x); free(u);
    return SB_ENOMEM;
  }
  sb_langevin_mom m;
  sb_langevin_moments(p, t, 0.0, 0.0, &m);
  double sm = 0, sv = 0;
  for (int rep = 0; rep < R; rep++) {
    memset(x, 0, 3 * np * sizeof *x);
    memset(u, 0, 3 * np * sizeof *u);
    sb_sim_langevin(p, t / K, K, r, np, x, u);
    mv s = mean_var(u, N); /* the first N components */
    sm += (s.mean - m.mean_u) * (s.mean - m.mean_u);
    sv += (s.var - m.var_u) * (s.var - m.var_u);
  }
  *rms_m = sqrt(sm / R);
  *rms_v = sqrt(sv / R);
  free(x); free(u);
  return SB_SUCCESS;
}

static int add_slope(sbv_report *rep, const char *name, const double *lnN,
                     const double *rms)
{
  double lny[NN], c0, c1, cov00, cov01, cov11, sumsq;
  for (int i = 0; i < NN; i++)
    lny[i] = log(rms[i]);
  gsl_fit_linear(lnN, 1, lny, 1, NN, &c0, &c1, &cov00, &cov01, &cov11,
                 &sumsq);
  /* t interval of the least-squares slope from the residual scatter
   * (approximate: assumes independent Gaussian residuals of log RMS) */
  double nu = NN - 2.0, se = sqrt(cov11);
  double tq = gsl_cdf_tdist_Qinv(0.5 * SBV_ALPHA, nu);
  double pv = se > 0 ? fmin(1.0, 2.0 * gsl_cdf_tdist_Q(fabs(c1 + 0.5) / se,
                                                        nu))
                     : NAN;
  sb_comparison c;
  sb_compare(&c, name, SB_RULE_COVER, c1, -0.5, c1 - tq * se, c1 + tq * se,
             1.0 - SBV_ALPHA, pv);
  return sbv_add(rep, &c);
}

static int case_slope(const sbv_ctx *ctx, sbv_report *rep)
{
  const int K = ctx->full ? 10 : 1, R = ctx->full ? 40 : 10;
  const double B = brownian_B();
  const sb_langevin p = {TAU_P, B, 0.0};
  const lsetup *S[2] = {&short_time, &long_time};
  double plot[NN * 9], lnN[NN], rms[4][NN];
  int st = SB_SUCCESS;
  gsl_rng *r = sbv_rng_alloc(ctx, 1003);
  if (!r)
    return SB_ENOMEM;
  sbv_note(rep, "RMS over %d replicates of |estimate - theory| for the "
                "mean and the variance of U (one component), at t_max of "
                "the short-time (1e-5 s) and long-time (250 s) set-ups, "
                "reached in %d exact step(s); N = 10^2, 10^2.5, ..., 10^6. "
                "Least-squares slope of log RMS vs log N; pass iff -1/2 "
                "(eq D.14) lies in the slope's t interval at 1 - %g from "
                "the residual scatter (approximate: residuals taken as "
                "independent and Gaussian).",
           R, K, SBV_ALPHA);
  for (int i = 0; i < NN; i++) {
    size_t N = (size_t)llround(pow(10.0, 2.0 + 0.5 * i));
    lnN[i] = log((double)N);
    plot[i * 9] = (double)N;
    for (int s = 0; s < 2 && st == SB_SUCCESS; s++) {
      st = rms_errors(&p, S[s]->tmax, K, R, N, r, &rms[2 * s][i],
                      &rms[2 * s + 1][i]);
      if (st)
        break;  /* no RMS to plot */
      sb_langevin_mom m;
      sb_langevin_moments(&p, S[s]->tmax, 0.0, 0.0, &m);
      /* exact RMS for Gaussian samples: sd/sqrt(N), var sqrt(2/(N-1)) */
      plot[i * 9 + 1 + 4 * s] = rms[2 * s][i];
      plot[i * 9 + 2 + 4 * s] = sqrt(m.var_u / (double)N);
      plot[i * 9 + 3 + 4 * s] = rms[2 * s + 1][i];
      plot[i * 9 + 4 + 4 * s] = m.var_u * sqrt(2.0 / (double)(N - 1));
    }
  }
  gsl_rng_free(r);
  if (st != SB_SUCCESS)
    return st;
  st |= add_slope(rep, "V10/ou-error-slope/short-time/mean-U", lnN, rms[0]);
  st |= add_slope(rep, "V10/ou-error-slope/short-time/var-U", lnN, rms[1]);
  st |= add_slope(rep, "V10/ou-error-slope/long-time/mean-U", lnN, rms[2]);
  st |= add_slope(rep, "V10/ou-error-slope/long-time/var-U", lnN, rms[3]);
  if (sbv_plot(ctx, rep, "V10_ou_error_slope",
               "V10 statistical error of E[U] and Var[U] vs N (Mohaupt "
               "2011, Figs D.9-D.12)",
               "N rmsE_short exactE_short rmsV_short exactV_short "
               "rmsE_long exactE_long rmsV_long exactV_long",
               plot, NN, 9,
               "set logscale xy\nset format y '%g'\nset xlabel 'N'\n"
               "set ylabel 'RMS error'\nset key bottom left\n"
               "plot $DATA u 1:2 w p pt 7 lc rgb 'red' t 'E[U], short', "
               "$DATA u 1:3 w l lc rgb 'red' t 'sd/sqrt(N)', "
               "$DATA u 1:4 w p pt 5 lc rgb 'blue' t 'Var[U], short', "
               "$DATA u 1:5 w l lc rgb 'blue' t 'var sqrt(2/(N-1))', "
               "$DATA u 1:6 w p pt 6 lc rgb 'dark-red' t 'E[U], long', "
               "$DATA u 1:7 w l dt 2 lc rgb 'dark-red' t '', "
               "$DATA u 1:8 w p pt 4 lc rgb 'dark-blue' t 'Var[U], long', "
               "$DATA u 1:9 w l dt 2 lc rgb 'dark-blue' t ''") !=
      SB_SUCCESS)
    return SB_EIO;
  return st ? SB_ENOMEM : SB_SUCCESS;
}

/* ========================================================== table */

const sbv_case sbv_cases_langevin[] = {
    {"V10/ou-short-time",
     "exact Langevin step vs OU moments, short times (Mohaupt 2011, "
     "Table D.1)",
     case_short},
    {"V10/ou-long-time",
     "exact Langevin step vs OU moments, long times (Mohaupt 2011, "
     "Table D.2)",
     case_long},
    {"V10/ou-error-slope",
     "statistical error of E[U], Var[U] ~ N^-1/2 (Mohaupt 2011, eq D.14)",
     case_slope},
};

const size_t sbv_ncases_langevin =
    sizeof sbv_cases_langevin / sizeof sbv_cases_langevin[0];
