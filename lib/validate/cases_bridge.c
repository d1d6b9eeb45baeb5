/* cases_bridge.c — `smolbridge validate` cases V11 (docs/validation.md):
 * the bridge and first-passage references against Monte Carlo.
 *
 *  V11/bb-cross-mc          1D Brownian-bridge crossing probability and
 *                           first-crossing-time histogram vs simulated
 *                           bridges (exact per-sub-step correction)
 *  V11/bes3b-cross-mc       the same for the Bessel-3 bridge (norm of a 3D
 *                           Brownian motion conditioned on its end norm)
 *  V11/bes3-fpt-mc          Bessel-3 first-passage CDF vs simulated 3D BM
 *  V11/bb-hit-ks            sb_bb_hit_sample vs sb_bb_hit_cdf
 *  V11/bes3b-hit-ks         sb_bes3b_hit_sample vs sb_bes3b_hit_cdf, both
 *                           regimes of 1 - rho (near 1 and small)
 *  V11/bm-fpt-ks            sb_bm_fpt_sample vs sb_bm_fpt_cdf, incl. the
 *                           defective law (fraction of +inf vs 1 - mass)
 *  V11/bes3b-hit-histogram  Mohaupt 2011, Figs 5.8-5.9: histograms of sampled
 *                           collision times vs the density
 *
 * Verdicts.  Every record is a test with a p-value; it passes iff
 * p >= 1e-3 (the generator seeds are fixed, so the verdicts are reproducible).
 * The interval shown is the 95% interval of the estimate (Clopper-Pearson for
 * frequencies, order statistics for medians, central chi-square interval
 * for chi-square statistics).  The simulation methods and why they are
 * exact are explained in smolbridge/simulate.h and docs/simulate.md; the
 * simulators are the library's reference module (sb_sim_*), shared with
 * tests/test_bridge_mc.c, which checks the same things in `make check`.
 *
 * Sample sizes.  --full uses the 100 000 draws of T_a per collision of
 * Mohaupt (2011, §5.4.1 and App. I.4) for the hitting-time histograms and
 * samplers, and 10^6 simulated paths per crossing probability (the thesis
 * validates crossing only through collision kernels, V4-V5: no path count
 * to copy).
 * --quick uses 5e4 draws and 1e5 paths.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_cdf.h>
#include <gsl/gsl_math.h>
#include <gsl/gsl_rng.h>

#include <smolbridge/bridge.h>
#include <smolbridge/passage.h>
#include <smolbridge/simulate.h>
#include <smolbridge/stats.h>

#include "cases.h"

#define NGRID 100    /* sub-steps per simulated bridge */

typedef struct {
  double x, y, a, s2, t;
} bpar;

/* F(q) = p for a continuous CDF on [lo, hi] (Brent); NaN if not bracketed. */
typedef struct {
  sb_cdf_fn cdf;
  void *par;
  double p;
} rootpar;

static double root_f(double x, void *vp)
{
  const rootpar *r = vp;
  return r->cdf(x, r->par) - r->p;
}

static double cdf_solve(sb_cdf_fn cdf, void *par, double p, double lo,
                        double hi)
{
  rootpar rp = {cdf, par, p};
  return sbv_brent(root_f, &rp, lo, hi, 1e-12);
}

/* ================================================ sampler checks */

typedef double (*sample_fn)(const gsl_rng *r, const void *p);
typedef double (*quant_fn)(double q, const void *p);

typedef struct {
  const char *name;  /* record prefix, e.g. "V11/bb-hit-ks/1" */
  sample_fn sample;
  sb_cdf_fn cdf;     /* law of the finite samples (normalised) */
  quant_fn quantile; /* its inverse (for equiprobable chi-square bins) */
  void *par;
  double lo, hi;     /* support */
  double mass;       /* P(finite); 1 - mass of the draws are +inf */
} sampler_case;

/* n draws: [fraction of +inf vs 1 - mass], median with KS p-value,
 * chi-square on 20 equiprobable bins.  Returns a status. */
static int check_sampler(const sbv_ctx *ctx, sbv_report *rep,
                         const sampler_case *c, size_t n,
                         unsigned long stream)
{
  enum { NB = 20 };
  double *xs = malloc(n * sizeof *xs);
  gsl_rng *r = sbv_rng_alloc(ctx, stream);
  if (!xs || !r) {
    free(xs);
    gsl_rng_free(r);
    return SB_ENOMEM;
  }
  size_t m = 0;
  unsigned long ninf = 0, nbad = 0;
  for (size_t i = 0; i < n; i++) {
    double s = c->sample(r, c->par);
    if (isinf(s) && s > 0)
      ninf++;
    else if (!(s >= c->lo && s <= c->hi))
      nbad++; /* NaN or outside the support */
    else
      xs[m++] = s;
  }
  gsl_rng_free(r);
  char name[96];
  int st = SB_SUCCESS;
  if (c->mass < 1.0 || ninf > 0) {
    snprintf(name, sizeof name, "%s/inf-fraction", c->name);
    st |= sbv_add_freq(rep, name, ninf, n, 1.0 - c->mass);
  }
  if (nbad > 0)
    sbv_note(rep, "- %s: %lu draws were NaN or outside [%g, %g] "
                  "(the tests below fail)", c->name, nbad, c->lo, c->hi);

  /* KS (sorts xs), the median with its order-statistic interval and sign
   * test */
  double d = NAN, pks = NAN, chi2 = NAN, dof = NAN, pc = NAN;
  if (sb_ks_test(xs, m, c->cdf, c->par, &d, &pks) != SB_SUCCESS || nbad)
    pks = NAN;
  double hi = c->hi;
  if (isinf(hi)) /* bracket the median of an unbounded law */
    for (hi = 1.0; c->cdf(hi, c->par) < 0.5 && hi < 1e300; hi *= 4.0)
      ;
  double med_ref = cdf_solve(c->cdf, c->par, 0.5, c->lo, hi);
  snprintf(name, sizeof name, "%s/median", c->name);
  st |= sbv_add_median(rep, name, xs, nbad ? 0 : m, med_ref);
  snprintf(name, sizeof name, "%s/KS", c->name);
  st |= sbv_add_ks(rep, name, m, d, pks);

  /* chi-square on NB bins, equiprobable under the module's quantile */
  double edges[NB + 1];
  edges[0] = c->lo;
  edges[NB] = c->hi;
  int ok = 1;
  for (int i = 1; i < NB; i++) {
    edges[i] = c->quantile((double)i / NB, c->par);
    ok &= edges[i] > edges[i - 1];
  }
  int cst = ok ? sb_chi2_test(xs, m, edges, NB, c->cdf, c->par, &chi2, &dof,
                              &pc)
               : SB_EINVAL;
  if (!ok)
    sbv_note(rep, "- %s: quantile not increasing: chi-square skipped",
             c->name);
  snprintf(name, sizeof name, "%s/chi2-20bins", c->name);
  st |= sbv_add_chi2(rep, name, nbad ? SB_EINVAL : cst, chi2, dof, pc);
  free(xs);
  return st ? SB_ENOMEM : SB_SUCCESS;
}

/* -------------------------------------------- bridge hitting times */

static double cb_bb_hit_cdf(double u, void *vp)
{
  const bpar *p = vp;
  return sb_bb_hit_cdf(u, p->x, p->y, p->a, p->s2, p->t);
}
static double cb_bes3b_hit_cdf(double u, void *vp)
{
  const bpar *p = vp;
  return sb_bes3b_hit_cdf(u, p->x, p->y, p->a, p->s2, p->t);
}
static double smp_bb_hit(const gsl_rng *r, const void *vp)
{
  const bpar *p = vp;
  return sb_bb_hit_sample(r, p->x, p->y, p->a, p->s2, p->t);
}
static double smp_bes3b_hit(const gsl_rng *r, const void *vp)
{
  const bpar *p = vp;
  return sb_bes3b_hit_sample(r, p->x, p->y, p->a, p->s2, p->t);
}
static double q_bb_hit(double q, const void *vp)
{
  const bpar *p = vp;
  return sb_bb_hit_quantile(q, p->x, p->y, p->a, p->s2, p->t);
}
static double q_bes3b_hit(double q, const void *vp)
{
  const bpar *p = vp;
  return sb_bes3b_hit_quantile(q, p->x, p->y, p->a, p->s2, p->t);
}

static size_t nsamples(const sbv_ctx *ctx)
{
  return ctx->full ? 100000 : 50000;
}

static void note_bpar(sbv_report *rep, int i, const bpar *p)
{
  sbv_note(rep, "- set %d: x = %g, y = %g, a = %g, sigma2 = %g, t = %g "
                "(v = %g)", i, p->x, p->y, p->a, p->s2, p->t, p->s2 * p->t);
}

static const bpar bbh_sets[] = {
    {1.5, 1.2, 1.0, 1.0, 1.0},
    {1.05, 3.0, 1.0, 0.5, 2.0},
    {3.0, 1.01, 1.0, 0.5, 2.0},
};

static int case_bb_hit_ks(const sbv_ctx *ctx, sbv_report *rep)
{
  size_t n = nsamples(ctx);
  sbv_note(rep, "%zu draws per set; KS p-value and chi-square on 20 bins "
                "equiprobable under sb_bb_hit_quantile; pass iff p >= %g. "
                "Reference median: root of sb_bb_hit_cdf = 1/2.", n, SBV_ALPHA);
  for (int i = 0; i < (int)(sizeof bbh_sets / sizeof bbh_sets[0]); i++) {
    char name[64];
    snprintf(name, sizeof name, "V11/bb-hit-ks/%d", i + 1);
    note_bpar(rep, i + 1, &bbh_sets[i]);
    sampler_case c = {name, smp_bb_hit, cb_bb_hit_cdf, q_bb_hit,
                      (void *)&bbh_sets[i], 0.0, bbh_sets[i].t, 1.0};
    int st = check_sampler(ctx, rep, &c, n, 100 + (unsigned long)i);
    if (st)
      return st;
  }
  return SB_SUCCESS;
}

/* 1 - rho = -expm1(-2a(x+y-a)/v) from ~1 to 5e-4: both CDF routes of
 * lib/bridge/bridge_hit.c (closed form; quadrature where it cancels). */
static const bpar b3h_sets[] = {
    {1.1, 1.2, 1.0, 1.0, 0.03}, /* 1 - rho ~ 1 */
    {1.0, 1.2, 0.5, 1.0, 1.0},  /* 0.82 */
    {0.5, 0.6, 0.2, 1.0, 2.0},  /* 0.165 */
    {1.0, 1.0, 0.02, 1.0, 1.0}, /* 0.076 */
    {1.0, 1.5, 1e-4, 1.0, 1.0}, /* 5e-4 */
};

static int case_bes3b_hit_ks(const sbv_ctx *ctx, sbv_report *rep)
{
  size_t n = nsamples(ctx);
  sbv_note(rep, "%zu draws per set; KS and chi-square (20 bins "
                "equiprobable under sb_bes3b_hit_quantile); pass iff p >= "
                "%g.  The sets span 1 - rho = 1 - exp(-2a(x+y-a)/v) from ~1 "
                "to 5e-4 (closed-form and quadrature routes of the CDF).", n, SBV_ALPHA);
  for (int i = 0; i < (int)(sizeof b3h_sets / sizeof b3h_sets[0]); i++) {
    const bpar *p = &b3h_sets[i];
    char name[64];
    snprintf(name, sizeof name, "V11/bes3b-hit-ks/%d", i + 1);
    note_bpar(rep, i + 1, p);
    sbv_note(rep, "  (1 - rho = %.3g)",
             -expm1(-2 * p->a * (p->x + p->y - p->a) / (p->s2 * p->t)));
    sampler_case c = {name, smp_bes3b_hit, cb_bes3b_hit_cdf, q_bes3b_hit,
                      (void *)p, 0.0, p->t, 1.0};
    int st = check_sampler(ctx, rep, &c, n, 200 + (unsigned long)i);
    if (st)
      return st;
  }
  return SB_SUCCESS;
}

/* ------------------------------------------------- first passage */

typedef struct {
  double x, a, mu, s2, mass;
} fpar;

static double cb_fpt_cdf(double t, void *vp)
{
  const fpar *p = vp;
  if (isinf(t))
    return t > 0 ? 1.0 : 0.0;
  return sb_bm_fpt_cdf(t, p->x, p->a, p->mu, p->s2) / p->mass;
}
static double smp_fpt(const gsl_rng *r, const void *vp)
{
  const fpar *p = vp;
  return sb_bm_fpt_sample(r, p->x, p->a, p->mu, p->s2);
}
static double q_fpt(double q, const void *vp)
{
  const fpar *p = vp;
  return sb_bm_fpt_quantile(q * p->mass, p->x, p->a, p->mu, p->s2);
}

static int case_bm_fpt_ks(const sbv_ctx *ctx, sbv_report *rep)
{
  static const fpar sets[] = {
      {1.0, 0.0, -1.0, 1.0, 1.0}, /* drift towards: inverse Gaussian */
      {0.0, 1.0, 50.0, 0.01, 1.0}, /* strong drift: near Gaussian */
      {1.0, 0.0, 0.0, 1.0, 1.0},  /* no drift: Levy */
      {1.0, 0.0, 0.5, 1.0, 1.0},  /* drift away: defective */
  };
  size_t n = nsamples(ctx);
  sbv_note(rep, "%zu draws per set.  Finite draws vs sb_bm_fpt_cdf / mass "
                "(KS, chi-square); fraction of +inf draws vs 1 - mass "
                "(exact binomial test); pass iff p >= %g.", n, SBV_ALPHA);
  for (int i = 0; i < (int)(sizeof sets / sizeof sets[0]); i++) {
    fpar p = sets[i];
    p.mass = sb_bm_fpt_mass(p.x, p.a, p.mu, p.s2);
    sbv_note(rep, "- set %d: x = %g, a = %g, mu = %g, sigma2 = %g; "
                  "P(T < inf) = %.6g", i + 1, p.x, p.a, p.mu, p.s2, p.mass);
    if (!(p.mass > 0 && p.mass <= 1)) {
      sbv_note(rep, "  sb_bm_fpt_mass returned %g: set skipped", p.mass);
      char name[64];
      snprintf(name, sizeof name, "V11/bm-fpt-ks/%d/mass", i + 1);
      sbv_add_band(rep, name, p.mass, p.mass, 1e-300, 1.0); /* fails */
      continue;
    }
    char name[64];
    snprintf(name, sizeof name, "V11/bm-fpt-ks/%d", i + 1);
    sampler_case c = {name, smp_fpt, cb_fpt_cdf, q_fpt, &p, 0.0, INFINITY,
                      p.mass};
    int st = check_sampler(ctx, rep, &c, n, 300 + (unsigned long)i);
    if (st)
      return st;
  }
  return SB_SUCCESS;
}

/* ============================= crossing probabilities by simulation */

/* Histogram of first-crossing sub-steps vs the hitting-time CDF: bins of
 * whole sub-steps with expected count >= 40, chi-square; optionally a
 * plot (MC density vs the density of the reference). */
static int hit_histogram(const sbv_ctx *ctx, sbv_report *rep,
                         const char *name, int bessel, const bpar *p,
                         const unsigned long *hits, int n, unsigned long nh,
                         const char *plotname)
{
  const double dt = p->t / n;
  sb_cdf_fn cdf = bessel ? cb_bes3b_hit_cdf : cb_bb_hit_cdf;
  double *edges = malloc((size_t)(n + 1) * sizeof *edges);
  double *xs = malloc((nh ? nh : 1) * sizeof *xs);
  double *plot = malloc((size_t)n * 4 * sizeof *plot);
  if (!edges || !xs || !plot) {
    free(edges);
    free(xs);
    free(plot);
    return SB_ENOMEM;
  }
  size_t nb = 0, m = 0;
  double Fprev = 0.0, Fk = 0.0;
  edges[0] = 0.0;
  for (int k = 0; k < n; k++) {
    double Fk1 = k == n - 1 ? 1.0 : cdf((k + 1) * dt, (void *)p);
    for (unsigned long j = 0; j < hits[k]; j++)
      xs[m++] = (k + 0.5) * dt;
    /* plot: per sub-step density, MC and reference */
    double uc = (k + 0.5) * dt;
    plot[4 * k + 0] = uc;
    plot[4 * k + 1] = nh ? (double)hits[k] / ((double)nh * dt) : 0.0;
    plot[4 * k + 2] = (Fk1 - Fk) / dt;
    plot[4 * k + 3] = bessel ? sb_bes3b_hit_pdf(uc, p->x, p->y, p->a, p->s2,
                                                p->t)
                             : sb_bb_hit_pdf(uc, p->x, p->y, p->a, p->s2,
                                             p->t);
    Fk = Fk1;
    if ((Fk1 - Fprev) * (double)nh >= 40.0 || k == n - 1) {
      if (k == n - 1 && nb > 0 && (Fk1 - Fprev) * (double)nh < 40.0)
        nb--; /* merge a short last bin into the previous one */
      edges[++nb] = (k == n - 1) ? p->t : (k + 1) * dt;
      Fprev = Fk1;
    }
  }
  double chi2 = NAN, dof = NAN, pv = NAN;
  int st = nb >= 2 ? sb_chi2_test(xs, m, edges, nb, cdf, (void *)p, &chi2,
                                  &dof, &pv)
                   : SB_EINVAL;
  int rs = sbv_add_chi2(rep, name, st, chi2, dof, pv);
  if (plotname) {
    char title[160];
    snprintf(title, sizeof title, "%s first-crossing time: x=%g y=%g a=%g "
             "sigma2=%g t=%g, %lu crossings", bessel ? "Bessel-3 bridge"
             : "Brownian bridge", p->x, p->y, p->a, p->s2, p->t, nh);
    sbv_plot(ctx, rep, plotname, title,
             "u  MC_density  ref_bin_density  ref_pdf", plot, (size_t)n, 4,
             "set xlabel 'u'\nset ylabel 'density of T_a given a crossing'\n"
             "plot $DATA u 1:2 w p pt 7 ps 0.7 lc rgb 'red' "
             "t 'simulated paths (first crossing sub-step)', "
             "$DATA u 1:3 w histeps lc rgb 'blue' t 'CDF, bin average', "
             "$DATA u 1:4 w l lw 2 lc rgb 'dark-green' t 'density'");
  }
  free(edges);
  free(xs);
  free(plot);
  return rs;
}

static int cross_case(const sbv_ctx *ctx, sbv_report *rep, int bessel,
                      const bpar *sets, int nsets, unsigned long npaths,
                      const char *prefix, const char *plotname)
{
  unsigned long hits[NGRID];
  sbv_note(rep, "%lu simulated %s per set on %d sub-steps; sub-step "
                "crossings drawn exactly (Bernoulli with the bridge formula "
                "of the sub-step), so there is no discretisation bias.  "
                "Records: crossing frequency vs sb_%s_cross_prob (exact binomial test); "
                "first-crossing histogram vs sb_%s_hit_cdf (chi-square, bins "
                "of expected count >= 40); pass iff p >= %g.",
           npaths, bessel ? "3D Brownian motions conditioned on the end "
                            "norm" : "1D Brownian bridges",
           NGRID, bessel ? "bes3b" : "bb", bessel ? "bes3b" : "bb", SBV_ALPHA);
  for (int i = 0; i < nsets; i++) {
    const bpar *p = &sets[i];
    gsl_rng *r = sbv_rng_alloc(ctx, (bessel ? 20 : 10) + (unsigned long)i);
    if (!r)
      return SB_ENOMEM;
    unsigned long nh = 0;
    int sst = (bessel ? sb_sim_bes3b_hits : sb_sim_bb_hits)(
        r, p->x, p->y, p->a, p->s2, p->t, NGRID, npaths, hits, &nh);
    gsl_rng_free(r);
    if (sst != SB_SUCCESS)
      return sst;
    double v = p->s2 * p->t;
    double P = bessel ? sb_bes3b_cross_prob(p->x, p->y, p->a, v)
                      : sb_bb_cross_prob(p->x, p->y, p->a, v);
    note_bpar(rep, i + 1, p);
    if (bessel) {
      double Pbb = exp(-2 * (p->x - p->a) * (p->y - p->a) / v);
      sbv_note(rep, "  (the 1D formula applied to the norms would give "
                    "%.4f, z = %.1f)", Pbb,
               sb_zscore((double)nh / npaths, Pbb,
                         sqrt(Pbb * (1 - Pbb) / npaths)));
    }
    char name[96];
    snprintf(name, sizeof name, "%s/%d/cross-prob", prefix, i + 1);
    int st = sbv_add_freq(rep, name, nh, npaths, P);
    snprintf(name, sizeof name, "%s/%d/hit-time-chi2", prefix, i + 1);
    st |= hit_histogram(ctx, rep, name, bessel, p, hits, NGRID, nh,
                        i == 0 ? plotname : NULL);
    if (st)
      return SB_ENOMEM;
  }
  return SB_SUCCESS;
}

static int case_bb_cross(const sbv_ctx *ctx, sbv_report *rep)
{
  static const bpar sets[] = {
      {1.5, 1.6, 1.0, 1.0, 0.5},  /* P = exp(-1.2) */
      {3.0, 1.05, 1.0, 2.0, 1.5}, /* late crossings */
  };
  return cross_case(ctx, rep, 0, sets, 2, ctx->full ? 1000000UL : 100000UL,
                    "V11/bb-cross-mc", "V11_bb_cross_hit_hist");
}

static int case_bes3b_cross(const sbv_ctx *ctx, sbv_report *rep)
{
  static const bpar sets[] = {
      {1.0, 1.2, 0.5, 1.0, 1.0}, /* v > a^2: far from the 1D formula */
      /* |A| = |B| = 2r, v = r^2 (docs/engine_bridge.md §6): */
      {2.0, 2.0, 1.0, 1.0, 1.0},
      {1.1, 1.2, 1.0, 1.0, 0.1}, /* as in Mohaupt 2011, ch. 5: v = 0.1 a^2 */
  };
  return cross_case(ctx, rep, 1, sets, 3, ctx->full ? 1000000UL : 100000UL,
                    "V11/bes3b-cross-mc", "V11_bes3b_cross_hit_hist");
}

/* Bessel-3 first passage from x down to a: norm of a simulated 3D BM,
 * sub-step crossings from the Bessel-3 bridge formula given the norms;
 * P(T_a <= s) at s = t/4, t/2, t vs sb_bes3_fpt_cdf. */
static int case_bes3_fpt(const sbv_ctx *ctx, sbv_report *rep)
{
  const double x = 1.5, a = 1.0, s2 = 1.0, t = 2.0;
  enum { NS = 200 };
  const double dt = t / NS;
  unsigned long N = ctx->full ? 1000000UL : 50000UL, cnt[3] = {0, 0, 0};
  unsigned long hits[NS], nh = 0;
  gsl_rng *r = sbv_rng_alloc(ctx, 30);
  if (!r)
    return SB_ENOMEM;
  int sst = sb_sim_bes3_hits(r, x, a, s2, t, NS, N, hits, &nh);
  gsl_rng_free(r);
  if (sst != SB_SUCCESS)
    return sst;
  for (int k = 0; k < NS; k++) {
    cnt[0] += k < NS / 4 ? hits[k] : 0;
    cnt[1] += k < NS / 2 ? hits[k] : 0;
    cnt[2] += hits[k];
  }
  sbv_note(rep, "%lu 3D Brownian motions from |B_0| = %g, sigma2 = %g, "
                "%d steps of %g, sub-step crossings of a = %g drawn "
                "exactly given the norms; total mass a/x = %g.  Pass iff "
                "exact binomial test p >= %g.", N, x, s2, NS, dt, a, a / x, SBV_ALPHA);
  const double tt[3] = {t / 4, t / 2, t};
  for (int j = 0; j < 3; j++) {
    char name[64];
    snprintf(name, sizeof name, "V11/bes3-fpt-mc/cdf(t=%g)", tt[j]);
    if (sbv_add_freq(rep, name, cnt[j], N, sb_bes3_fpt_cdf(tt[j], x, a, s2)))
      return SB_ENOMEM;
  }
  return SB_SUCCESS;
}

/* ========================= Mohaupt 2011, Figs 5.8-5.9 analogue */

/* Collision of two 1 um particles in air at 296.15 K (Mohaupt 2011,
 * Tables 5.1-5.2: d_p = 1 um, tau_p = 3.03 us, mu_f = 1.83245e-5 Pa s).
 * Relative motion: per-component rate B_ij^2 = 2 (2 D), D = kT/(3 pi mu d)
 * (eq 5.9 with B_pos^2 = 2D).  Units: um and us.  The thesis does not print
 * the x, y of its two collisions (chosen arbitrarily there); we take one with
 * dt = 100 tau_p (x = 1.10, y = 1.05 um) and one with dt = 1000 tau_p
 * (x = 1.4, y = 1.6 um); a = r_ij = d_p = 1 um. */
static void thesis_collisions(bpar out[2])
{
  const double kB = 1.3806503e-23, T = 296.15, mu = 1.83245e-5, d = 1e-6;
  const double tau_p = 3.03;                            /* us */
  double D = kB * T / (3 * M_PI * mu * d);              /* m^2/s */
  double s2 = 4.0 * D * 1e12 / 1e6;                     /* um^2/us */
  bpar c1 = {1.10, 1.05, 1.0, s2, 100 * tau_p};
  bpar c2 = {1.40, 1.60, 1.0, s2, 1000 * tau_p};
  out[0] = c1;
  out[1] = c2;
}

static int case_bes3b_hit_hist(const sbv_ctx *ctx, sbv_report *rep)
{
  enum { NB = 50 };
  bpar col[2];
  thesis_collisions(col);
  size_t n = nsamples(ctx);
  sbv_note(rep, "Analogue of Mohaupt (2011) Figs 5.8-5.9 (and App. I Figs "
                "I.2-I.4): %zu collision times T_a drawn with "
                "sb_bes3b_hit_sample per collision (the thesis used 100000), "
                "histogram vs sb_bes3b_hit_pdf; chi-square on %d equal bins "
                "(merged until each expects >= 10 draws; expected counts "
                "from sb_bes3b_hit_cdf), pass iff p >= %g.  "
                "Particles of 1 um in air at 296.15 K, units um and us; "
                "the thesis does not print its collisions' x, y: ours are "
                "below.", n, NB, SBV_ALPHA);
  double *xs = malloc(n * sizeof *xs), *plot = malloc(NB * 4 * sizeof *plot);
  if (!xs || !plot) {
    free(xs);
    free(plot);
    return SB_ENOMEM;
  }
  int st = SB_SUCCESS;
  for (int c = 0; c < 2 && !st; c++) {
    const bpar *p = &col[c];
    note_bpar(rep, c + 1, p);
    sbv_note(rep, "  (dt = %g tau_p, P(collision) = %.4f)",
             p->t / 3.03, sb_bes3b_cross_prob(p->x, p->y, p->a,
                                              p->s2 * p->t));
    gsl_rng *r = sbv_rng_alloc(ctx, 40 + (unsigned long)c);
    if (!r) {
      st = SB_ENOMEM;
      break;
    }
    for (size_t i = 0; i < n; i++)
      xs[i] = sb_bes3b_hit_sample(r, p->x, p->y, p->a, p->s2, p->t);
    gsl_rng_free(r);
    double edges[NB + 1], w = p->t / NB;
    unsigned long cnt[NB] = {0};
    for (int b = 0; b <= NB; b++)
      edges[b] = b * w;
    edges[NB] = p->t;
    for (size_t i = 0; i < n; i++)
      if (xs[i] >= 0 && xs[i] <= p->t) {
        int b = (int)(xs[i] / w);
        cnt[b < NB ? b : NB - 1]++;
      }
    double Fa = 0.0;
    for (int b = 0; b < NB; b++) {
      double uc = (b + 0.5) * w;
      double Fb = b == NB - 1 ? 1.0 : cb_bes3b_hit_cdf(edges[b + 1],
                                                       (void *)p);
      plot[4 * b + 0] = uc;
      plot[4 * b + 1] = (double)cnt[b] / ((double)n * w);
      plot[4 * b + 2] = (Fb - Fa) / w;
      plot[4 * b + 3] = sb_bes3b_hit_pdf(uc, p->x, p->y, p->a, p->s2, p->t);
      Fa = Fb;
    }
    /* the test on the plot's bins merged until each expects >= 10 draws:
     * bins of tiny expected count (the density vanishes near T_a = 0)
     * make the chi-square law a poor approximation, and their rare
     * contributions skewed the statistic (pooled over 40 seeds its mean
     * was 0.89 dof) */
    double tedges[NB + 1];
    size_t nt = 0;
    tedges[nt++] = edges[0];
    double Fprev = 0.0;
    for (int b = 1; b <= NB; b++) {
      double Fb = b == NB ? 1.0 : cb_bes3b_hit_cdf(edges[b], (void *)p);
      if ((Fb - Fprev) * (double)n >= 10.0 || b == NB) {
        tedges[nt++] = edges[b];
        Fprev = Fb;
      }
    }
    /* a short last bin joins its neighbour */
    if (nt > 2 && (1.0 - cb_bes3b_hit_cdf(tedges[nt - 2], (void *)p)) *
                          (double)n < 10.0) {
      tedges[nt - 2] = tedges[nt - 1];
      nt--;
    }
    double chi2 = NAN, dof = NAN, pv = NAN;
    int cs = sb_chi2_test(xs, n, tedges, nt - 1, cb_bes3b_hit_cdf,
                          (void *)p, &chi2, &dof, &pv);
    char name[64], pname[64], title[200];
    snprintf(name, sizeof name, "V11/bes3b-hit-histogram/fig5.%d", 8 + c);
    st |= sbv_add_chi2(rep, name, cs, chi2, dof, pv);
    snprintf(pname, sizeof pname, "V11_bes3b_hit_fig5_%d", 8 + c);
    snprintf(title, sizeof title, "Collision time T_a (us), Bessel-3 bridge "
             "x=%g y=%g a=%g um, dt=%g us, %zu draws (cf. Mohaupt 2011, Fig "
             "5.%d)",
             p->x, p->y, p->a, p->t, n, 8 + c);
    sbv_plot(ctx, rep, pname, title,
             "u_us  MC_density  ref_bin_density  ref_pdf", plot, NB, 4,
             "set xlabel 'T_a (us)'\nset ylabel 'probability density'\n"
             "plot $DATA u 1:2 w p pt 7 ps 0.8 lc rgb 'red' "
             "t 'sb_bes3b_hit_sample', "
             "$DATA u 1:4 w l lw 2 lc rgb 'dark-green' t 'sb_bes3b_hit_pdf'");
  }
  free(xs);
  free(plot);
  return st ? SB_ENOMEM : SB_SUCCESS;
}

/* ========================================================== table */

const sbv_case sbv_cases_bridge[] = {
    {"V11/bb-cross-mc",
     "1D bridge crossing prob. + first-crossing times vs simulated paths",
     case_bb_cross},
    {"V11/bes3b-cross-mc",
     "Bessel-3 bridge crossing prob. + hit times vs simulated 3D paths",
     case_bes3b_cross},
    {"V11/bes3-fpt-mc", "Bessel-3 first-passage CDF vs simulated 3D BM",
     case_bes3_fpt},
    {"V11/bb-hit-ks", "sb_bb_hit_sample vs sb_bb_hit_cdf (KS, chi-square)",
     case_bb_hit_ks},
    {"V11/bes3b-hit-ks",
     "sb_bes3b_hit_sample vs its CDF, 1 - rho from 1 to 5e-4",
     case_bes3b_hit_ks},
    {"V11/bm-fpt-ks",
     "sb_bm_fpt_sample vs its CDF, incl. the defective law",
     case_bm_fpt_ks},
    {"V11/bes3b-hit-histogram",
     "collision-time histograms vs density (Mohaupt 2011, Figs 5.8-5.9)",
     case_bes3b_hit_hist},
};

const size_t sbv_ncases_bridge =
    sizeof sbv_cases_bridge / sizeof sbv_cases_bridge[0];
