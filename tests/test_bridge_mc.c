/* test_bridge_mc.c — Monte Carlo validation of the bridge and passage
 * references (validation case V11, docs/validation.md).
 *
 * Three groups of checks, all with fixed seeds (MT19937) and stated sizes:
 *
 *  A. Crossing probabilities vs simulated bridges on a grid, with the
 *     between-grid-point crossing drawn exactly (per-sub-step correction),
 *     so the estimate has NO discretisation bias:
 *       - 1D Brownian bridge: between grid points the path is a Brownian
 *         bridge, so it crosses a (both ends above a) with probability
 *         exp(-2 (X_k - a)(X_{k+1} - a) / (sigma2 dt)), drawn as a Bernoulli.
 *       - 3D Brownian motion conditioned on its end NORM (= Bessel-3 bridge
 *         for the norm), simulated in 3D.  See docs/simulate.md for why
 *         the per-sub-step Bessel-3 correction computed from the norms
 *         alone is exact although the simulation knows the full 3D points.
 *     The simulators are lib/simulate/simulate.c (sb_sim_*), which writes its
 *     crossing formulas independently of lib/bridge/bridge.c.
 *     Because the correction is itself a crossing formula, the grid is made
 *     fine (v_step = v/n much smaller than the length scales), so the
 *     correction only acts at scales where the Bessel-3 bridge is locally a
 *     Brownian bridge, and two grids (coarse and fine) must give the same
 *     answer.  A power check shows that the 3D estimate rejects the 1D
 *     formula applied to the norms.
 *     Criterion: the reference lies in the 99.9% Clopper-Pearson interval
 *     of the crossing frequency (equivalently a two-sided test at 1e-3).
 *
 *  B. The same simulations record the grid interval of the FIRST crossing;
 *     its histogram (conditioned on crossing) is compared with the
 *     conditioned hitting-time CDF by chi-square, p >= 1e-3 (V11: "hit-time
 *     histograms vs CDF"; Mohaupt 2011, Figs 5.8-5.9).  Exact for the same
 *     reason: "first crossing in sub-step k" is decided by exact Bernoulli
 *     draws.
 *
 *  C. Samplers vs their CDFs: sb_bb_hit_sample, sb_bes3b_hit_sample (both
 *     regimes of 1 - rho, see b3h_sets), sb_bm_fpt_sample
 *     (drift towards the level, none, away = defective): one-sample
 *     Kolmogorov-Smirnov (sb_ks_test) and chi-square on 20 bins that are
 *     equiprobable under the module's quantile function (sb_chi2_test),
 *     each with p >= 1e-3; the fraction of +inf samples of a defective law
 *     must lie in the 99.9% Clopper-Pearson interval around 1 - mass.
 *
 * With ~30 independent tests at level 1e-3 the chance of a spurious failure
 * for a correct implementation is ~3%; the seeds are fixed, so the outcome
 * is reproducible.  The whole file runs in ~10 s (-O2).
 */
#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <float.h>

#include <gsl/gsl_math.h>
#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>

#include <smolbridge/bridge.h>
#include <smolbridge/langevin.h>
#include <smolbridge/passage.h>
#include <smolbridge/simulate.h>
#include <smolbridge/stats.h>

#include "sweep.h"
#include "testutil.h"

/* Significance level of every test in this file. */
#define ALPHA 1e-3
/* Coverage of the binomial intervals (two-sided, = 1 - ALPHA). */
#define LEVEL (1.0 - ALPHA)

/* Fixed seeds.  SB_MC_SEED_OFFSET (environment) shifts all of them, to
 * look at the spread of the p-values over other seeds; it is not set by
 * `make check`. */
static gsl_rng *rng_new(unsigned long seed)
{
  gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
  ck_assert_ptr_nonnull(r);
  const char *off = getenv("SB_MC_SEED_OFFSET");
  if (off)
    seed += strtoul(off, NULL, 10) * 100003UL;
  gsl_rng_set(r, seed);
  return r;
}

/* ================================================= A/B: path simulation */

/* The path simulators are the reference module lib/simulate/simulate.c
 * (smolbridge/simulate.h): exact grid values, sub-step crossings drawn
 * exactly with crossing formulas written there independently of
 * lib/bridge/bridge.c, so P(cross) and the first-crossing sub-step have no
 * discretisation bias.  The 3-D simulation of the Bessel-3 bridge (3-D BM
 * conditioned on its end NORM: von Mises-Fisher end point, then a 3-D
 * Brownian bridge) and why the correction from the norms alone is exact
 * are explained in docs/simulate.md. */

typedef struct {
  double x, y, a, s2, t;
} bpar;

/* Simulate N paths on n sub-steps; hits[k] counts first crossings in
 * sub-step k (hits has n entries); returns the number of paths that
 * cross. */
static unsigned long simulate(int bessel, const bpar *p, unsigned long N,
                              int n, unsigned long seed, unsigned long *hits)
{
  gsl_rng *r = rng_new(seed);
  unsigned long nh = 0;
  int st = (bessel ? sb_sim_bes3b_hits : sb_sim_bb_hits)(
      r, p->x, p->y, p->a, p->s2, p->t, n, N, hits, &nh);
  ck_assert_int_eq(st, SB_SUCCESS);
  gsl_rng_free(r);
  return nh;
}

/* Crossing frequency nh/N vs reference P: P in the LEVEL Clopper-Pearson
 * interval.  Returns the z-score (for the power check). */
static double check_cross(const char *what, unsigned long nh, unsigned long N,
                          double P)
{
  double lo, hi, ph = (double)nh / (double)N;
  ck_assert_int_eq(sb_binomial_ci(nh, N, LEVEL, &lo, &hi), SB_SUCCESS);
  double z = sb_zscore(ph, P, sqrt(P * (1.0 - P) / (double)N));
  printf("%-34s N=%lu  MC %.5f  [%.5f, %.5f]  ref %.5f  z=%+.2f\n", what, N,
         ph, lo, hi, P, z);
  ck_assert_msg(lo <= P && P <= hi,
                "%s: reference %.6f outside the %.1f%% interval [%.6f, %.6f] "
                "of the simulated frequency %.6f (z = %.2f)",
                what, P, 100 * LEVEL, lo, hi, ph, z);
  return z;
}

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

/* Chi-square of the first-crossing sub-step histogram against the
 * conditioned hitting-time CDF.  Sub-steps are merged into bins of expected
 * count >= 40 (bins end on grid points); every crossing is represented by
 * the midpoint of its sub-step, which lies inside its bin. */
static void check_hit_histogram(const char *what, int bessel, const bpar *p,
                                const unsigned long *hits, int n,
                                unsigned long nh)
{
  const double dt = p->t / n;
  sb_cdf_fn cdf = bessel ? cb_bes3b_hit_cdf : cb_bb_hit_cdf;
  double *edges = malloc((size_t)(n + 1) * sizeof *edges);
  double *xs = malloc(nh * sizeof *xs);
  ck_assert_ptr_nonnull(edges);
  ck_assert_ptr_nonnull(xs);
  size_t nb = 0, m = 0;
  edges[0] = 0.0;
  double Fprev = 0.0, Flast = 0.0; /* F at the last edge; at the last point */
  for (int k = 0; k < n; k++) {
    double tk1 = (k + 1) * dt;
    double F = k == n - 1 ? 1.0 : cdf(tk1, (void *)p);
    ck_assert_msg(F >= Flast * (1.0 - TOL_TIGHT) && F <= 1.0,
                  "%s: hit cdf not monotone in [0,1] at u=%g: %.17g after "
                  "%.17g", what, tk1, F, Flast);
    Flast = F;
    for (unsigned long j = 0; j < hits[k]; j++)
      xs[m++] = (k + 0.5) * dt;
    if ((F - Fprev) * (double)nh >= 40.0 || k == n - 1) {
      if (k == n - 1 && nb > 0 && (F - Fprev) * (double)nh < 40.0)
        nb--; /* merge a small last bin into the previous one */
      edges[++nb] = (k == n - 1) ? p->t : tk1;
      Fprev = F;
    }
  }
  edges[nb] = p->t;
  double chi2, dof, pv;
  int st = sb_chi2_test(xs, m, edges, nb, cdf, (void *)p, &chi2, &dof, &pv);
  printf("%-34s hits=%lu  bins=%zu  chi2=%.1f dof=%.0f  p=%.4f\n", what, nh,
         nb, chi2, dof, pv);
  ck_assert_msg(st == SB_SUCCESS, "%s: sb_chi2_test status %d", what, st);
  ck_assert_msg(pv >= ALPHA, "%s: chi-square p = %.3g < %g (chi2 %.1f, dof %.0f)",
                what, pv, ALPHA, chi2, dof);
  free(edges);
  free(xs);
}

/* ------------------------------------------------------------ A + B: 1D */

/* N = 2e5 bridges on n = 100 sub-steps for each set; the hit-time
 * histogram uses the same paths. */
static const bpar bb_sets[] = {
    {1.5, 1.6, 1.0, 1.0, 0.5},   /* P = exp(-1.2) = 0.30 */
    {1.1, 2.0, 1.0, 0.5, 1.0},   /* starts close: early hits */
    {3.0, 1.05, 1.0, 2.0, 1.5},  /* ends close: late hits */
    {-0.7, -0.2, -1.0, 0.3, 2.0} /* negative coordinates */
};

/* Set p simulated N times on NS = 100 sub-steps (seed): crossing
 * frequency vs the closed form, then the first-crossing histogram vs the
 * conditioned hitting-time CDF, from the same paths. */
static void cross_and_histogram(int bessel, const bpar *p, int set,
                                unsigned long N, unsigned long seed)
{
  enum { NS = 100 };
  const char *kind = bessel ? "bes3b" : "bb";
  unsigned long hits[NS];
  unsigned long nh = simulate(bessel, p, N, NS, seed, hits);
  double v = p->s2 * p->t;
  double P = bessel ? sb_bes3b_cross_prob(p->x, p->y, p->a, v)
                    : sb_bb_cross_prob(p->x, p->y, p->a, v);
  char what[64];
  snprintf(what, sizeof what, "%s cross set %d", kind, set);
  check_cross(what, nh, N, P);
  snprintf(what, sizeof what, "%s hit-time histogram set %d", kind, set);
  check_hit_histogram(what, bessel, p, hits, NS, nh);
}

START_TEST(test_bb_cross_mc)
{
  cross_and_histogram(0, &bb_sets[_i], _i, 200000, 1001 + _i);
}
END_TEST

/* ------------------------------------------------------------ A + B: 3D */

/* Sets span a^2/v from 0.04 to 10 (the Bessel-3 correction to the 1D
 * formula is large when v >~ a^2); N = 1e5, n = 100. */
static const bpar bes_sets[] = {
    {1.0, 1.2, 0.5, 1.0, 1.0},  /* P = 0.446, 1D formula 0.497 */
    {0.5, 0.6, 0.2, 1.0, 2.0},  /* v >> a^2: 1 - rho = 0.165 */
    {2.0, 2.0, 1.0, 1.0, 1.0},  /* |A| = |B| = 2r, v = r^2: 0.135 */
    {1.1, 1.2, 1.0, 1.0, 0.1},  /* as Mohaupt 2011, ch. 5: v = 0.1 a^2 */
};

START_TEST(test_bes3b_cross_mc)
{
  cross_and_histogram(1, &bes_sets[_i], _i, 100000, 2001 + _i);
}
END_TEST

/* Grid independence: a coarse (n = 10) and a fine (n = 400) grid both
 * reproduce the reference (N = 5e4 each).  With n = 10 the correction does
 * most of the work; with n = 400 the sub-step variance is v/400, where the
 * Bessel-3 bridge is locally a Brownian bridge, so the reference is tested
 * by the simulated 3D paths rather than by the correction.  Power check:
 * the fine-grid estimate rejects the 1D formula applied to the norms
 * (|z| > 10 at N = 5e4 for set 0, where the two differ by 0.05). */
START_TEST(test_bes3b_grid_independence)
{
  const bpar *p = &bes_sets[0];
  enum { N = 50000 };
  unsigned long *hits = malloc(400 * sizeof *hits);
  ck_assert_ptr_nonnull(hits);
  double v = p->s2 * p->t;
  double P = sb_bes3b_cross_prob(p->x, p->y, p->a, v);
  unsigned long nh10 = simulate(1, p, N, 10, 3001, hits);
  check_cross("bes3b cross set 0, n=10", nh10, N, P);
  unsigned long nh400 = simulate(1, p, N, 400, 3002, hits);
  check_cross("bes3b cross set 0, n=400", nh400, N, P);
  double Pbb = exp(-2.0 * (p->x - p->a) * (p->y - p->a) / v);
  double z = sb_zscore((double)nh400 / N, Pbb, sqrt(Pbb * (1 - Pbb) / N));
  printf("%-34s z vs 1D formula on norms = %.1f\n", "bes3b power check", z);
  ck_assert_msg(fabs(z) > 10.0,
                "the simulation cannot tell the Bessel-3 bridge from the 1D "
                "bridge formula (z = %.2f)", z);
  free(hits);
}
END_TEST

/* ====================================================== C: samplers */

typedef double (*sample_fn)(const gsl_rng *r, const void *p);

typedef struct {
  const char *what;
  sample_fn sample;
  sb_cdf_fn cdf;        /* CDF of the finite part, normalised to 1 */
  double (*quantile)(double q, const void *p); /* inverse of cdf */
  const void *par;
  double lo, hi;        /* support for the chi-square edges */
  double mass;          /* P(sample finite) */
} sampler_case;

enum { NKS = 50000, NBINS = 20 };

/* Draw NKS samples; binomial check of the +inf fraction against 1 - mass;
 * KS of the finite ones against cdf; chi-square on NBINS bins that are
 * equiprobable according to the quantile. */
static void check_sampler(const sampler_case *c, unsigned long seed)
{
  gsl_rng *r = rng_new(seed);
  double *xs = malloc(NKS * sizeof *xs);
  ck_assert_ptr_nonnull(xs);
  size_t m = 0;
  unsigned long ninf = 0;
  for (size_t i = 0; i < NKS; i++) {
    double s = c->sample(r, c->par);
    ck_assert_msg(!isnan(s), "%s: sampler returned NaN", c->what);
    if (isinf(s)) {
      ck_assert_msg(s > 0, "%s: sampler returned -inf", c->what);
      ninf++;
    } else {
      ck_assert_msg(s >= c->lo && s <= c->hi, "%s: sample %g outside [%g, %g]",
                    c->what, s, c->lo, c->hi);
      xs[m++] = s;
    }
  }
  gsl_rng_free(r);

  double lo, hi;
  ck_assert_int_eq(sb_binomial_ci(ninf, NKS, LEVEL, &lo, &hi), SB_SUCCESS);
  ck_assert_msg(lo <= 1.0 - c->mass && 1.0 - c->mass <= hi,
                "%s: fraction of +inf %.5f, interval [%.5f, %.5f] excludes "
                "1 - mass = %.5f", c->what, (double)ninf / NKS, lo, hi,
                1.0 - c->mass);

  double edges[NBINS + 1];
  edges[0] = c->lo;
  edges[NBINS] = c->hi;
  for (int i = 1; i < NBINS; i++) {
    edges[i] = c->quantile((double)i / NBINS, c->par);
    ck_assert_msg(edges[i] > edges[i - 1], "%s: quantile not increasing at "
                  "p = %g: %g <= %g", c->what, (double)i / NBINS, edges[i],
                  edges[i - 1]);
  }
  double chi2, dof, pc, d, pks;
  int st2 = sb_chi2_test(xs, m, edges, NBINS, c->cdf, (void *)c->par, &chi2,
                         &dof, &pc);
  int stk = sb_ks_test(xs, m, c->cdf, (void *)c->par, &d, &pks);
  printf("%-44s n=%zu inf=%lu  KS D=%.4f p=%.4f  chi2=%.1f p=%.4f\n", c->what,
         m, ninf, d, pks, chi2, pc);
  ck_assert_msg(stk == SB_SUCCESS, "%s: sb_ks_test status %d", c->what, stk);
  ck_assert_msg(st2 == SB_SUCCESS, "%s: sb_chi2_test status %d", c->what,
                st2);
  ck_assert_msg(pks >= ALPHA, "%s: KS p = %.3g < %g (D = %.4f, n = %zu)",
                c->what, pks, ALPHA, d, m);
  ck_assert_msg(pc >= ALPHA, "%s: chi-square p = %.3g < %g (chi2 = %.1f)",
                c->what, pc, ALPHA, chi2);
  free(xs);
}

/* ---------------------------------------------------------- bridge hits */

static double smp_bb_hit(const gsl_rng *r, const void *vp)
{
  const bpar *p = vp;
  return sb_bb_hit_sample(r, p->x, p->y, p->a, p->s2, p->t);
}
static double q_bb_hit(double q, const void *vp)
{
  const bpar *p = vp;
  return sb_bb_hit_quantile(q, p->x, p->y, p->a, p->s2, p->t);
}
static double smp_bes3b_hit(const gsl_rng *r, const void *vp)
{
  const bpar *p = vp;
  return sb_bes3b_hit_sample(r, p->x, p->y, p->a, p->s2, p->t);
}
static double q_bes3b_hit(double q, const void *vp)
{
  const bpar *p = vp;
  return sb_bes3b_hit_quantile(q, p->x, p->y, p->a, p->s2, p->t);
}

/* Brownian bridge: central, near start, near end, ending on the level
 * (beta = 0: the conditioned law is a time-changed Levy law), tiny v. */
static const bpar bbh_sets[] = {
    {1.5, 1.2, 1.0, 1.0, 1.0},   {1.05, 3.0, 1.0, 0.5, 2.0},
    {3.0, 1.01, 1.0, 0.5, 2.0},  {2.0, 1.0, 1.0, 1.0, 1.0},
    {1e-3, 2e-3, 0.0, 1e-6, 1.0}, {-0.5, 4.0, -1.0, 3.0, 0.7},
};

START_TEST(test_bb_hit_sampler)
{
  const bpar *p = &bbh_sets[_i];
  char what[96];
  snprintf(what, sizeof what, "bb_hit_sample (%g,%g,%g,%g,%g)", p->x, p->y,
           p->a, p->s2, p->t);
  sampler_case c = {what, smp_bb_hit, cb_bb_hit_cdf, q_bb_hit, p, 0.0, p->t,
                    1.0};
  check_sampler(&c, 4001 + _i);
}
END_TEST

/* Bessel-3 bridge: 1 - rho = -expm1(-2a(x+y-a)/v) from ~1 (seed-like
 * collisions, v << a^2) down to 5e-4 (v >> a^2).  This covers both ways
 * lib/bridge/bridge_hit.c evaluates the CDF (the closed-form difference of two
 * inverse-Gaussian laws, and the quadrature used when that difference
 * cancels, i.e. 1 - rho small) and every regime a sampler with a
 * rejection/inversion switch would have; y = a is the end-point case. */
static const bpar b3h_sets[] = {
    {1.1, 1.2, 1.0, 1.0, 0.03},  /* 1 - rho ~ 1 (seed-like, Fig 5.8) */
    {1.5, 1.3, 1.0, 1.0, 0.3},   /* 1 - rho ~ 1 */
    {1.0, 1.2, 0.5, 1.0, 1.0},   /* 1 - rho = 0.82 */
    {0.5, 0.6, 0.2, 1.0, 2.0},   /* 1 - rho = 0.165 */
    {1.0, 1.0, 0.02, 1.0, 1.0},  /* 1 - rho = 0.076 */
    {1.0, 1.5, 1e-4, 1.0, 1.0},  /* 1 - rho = 5e-4 */
    {2.0, 1.0, 1.0, 1.0, 1.0},   /* ends on the level */
};

START_TEST(test_bes3b_hit_sampler)
{
  const bpar *p = &b3h_sets[_i];
  char what[96];
  snprintf(what, sizeof what, "bes3b_hit_sample (%g,%g,%g,%g,%g)", p->x,
           p->y, p->a, p->s2, p->t);
  sampler_case c = {what, smp_bes3b_hit, cb_bes3b_hit_cdf, q_bes3b_hit, p,
                    0.0, p->t, 1.0};
  check_sampler(&c, 5001 + _i);
}
END_TEST

/* ------------------------------------------------------ first passage */

typedef struct {
  double x, a, mu, s2;
  double mass;
} fpar;

static double smp_fpt(const gsl_rng *r, const void *vp)
{
  const fpar *p = vp;
  return sb_bm_fpt_sample(r, p->x, p->a, p->mu, p->s2);
}
/* CDF of T given T < inf (the law of the finite samples). */
static double cb_fpt_cdf(double t, void *vp)
{
  const fpar *p = vp;
  if (isinf(t))
    return t > 0 ? 1.0 : 0.0;
  return sb_bm_fpt_cdf(t, p->x, p->a, p->mu, p->s2) / p->mass;
}
static double q_fpt(double q, const void *vp)
{
  const fpar *p = vp;
  return sb_bm_fpt_quantile(q * p->mass, p->x, p->a, p->mu, p->s2);
}

/* Drift towards the level (IG), from both sides; none (Levy, infinite
 * mean); away from the level (defective, mass exp(-2 d |mu| / s2)). */
static const fpar fpt_sets[] = {
    {1.0, 0.0, -1.0, 1.0, 1.0},  /* towards, from above: IG(1, 1) */
    {-2.0, 1.0, 0.5, 2.0, 1.0},  /* towards, from below */
    {0.0, 1e-3, 50.0, 1.0, 1.0}, /* IG shape/mean = 0.05: very skewed */
    {0.0, 1.0, 50.0, 0.01, 1.0}, /* IG shape/mean = 5000: near Gaussian */
    {1.0, 0.0, 0.0, 1.0, 1.0},   /* Levy */
    {1.0, 0.0, 0.5, 1.0, 0.0},   /* away: mass e^-1 */
    {-1.0, 0.5, -0.2, 3.0, 0.0}, /* away from below: mass e^-0.2 */
};

START_TEST(test_bm_fpt_sampler)
{
  fpar p = fpt_sets[_i];
  double m = sb_bm_fpt_mass(p.x, p.a, p.mu, p.s2);
  /* independent mass: 1 unless the drift points away from the level */
  double d = fabs(p.x - p.a), nu = p.mu * (p.a > p.x ? 1.0 : -1.0);
  double mref = nu >= 0 ? 1.0 : exp(-2.0 * d * fabs(nu) / p.s2);
  ck_assert_rel(m, mref, 1e-14);
  p.mass = m;
  char what[96];
  snprintf(what, sizeof what, "bm_fpt_sample (x=%g,a=%g,mu=%g,s2=%g)", p.x,
           p.a, p.mu, p.s2);
  sampler_case c = {what, smp_fpt, cb_fpt_cdf, q_fpt, &p, 0.0, INFINITY, m};
  check_sampler(&c, 6001 + _i);
}
END_TEST

/* GSL's ziggurat returns exactly 0 with probability 2^-24 (when the 24-bit
 * mantissa index is 0; measured: 10 zeros in 2e8 draws), about once per
 * 1.7e7 calls.  A Levy sampler written as shape / Z^2 then returns +inf,
 * although T < inf almost surely without drift.  This generator returns 0
 * on its first call (so the first ziggurat draw is exactly 0), then
 * splitmix64 output; the sampler must still return a finite time. */
static unsigned long zf_get(void *vs)
{
  unsigned long long *s = vs;
  if (*s == 0) {
    *s = 0x9E3779B97F4A7C15ULL;
    return 0;
  }
  unsigned long long z = (*s += 0x9E3779B97F4A7C15ULL);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return (unsigned long)((z ^ (z >> 31)) >> 32);
}
static double zf_get_double(void *vs)
{
  return ((double)zf_get(vs) + 0.5) / 4294967296.0;
}
static void zf_set(void *vs, unsigned long seed)
{
  (void)seed;
  *(unsigned long long *)vs = 0; /* next call returns 0 */
}
static const gsl_rng_type zero_first_type = {
    "zero-first", 0xffffffffUL, 0, sizeof(unsigned long long), zf_set,
    zf_get, zf_get_double};

START_TEST(test_fpt_sampler_gaussian_zero)
{
  gsl_rng *r = gsl_rng_alloc(&zero_first_type);
  ck_assert_ptr_nonnull(r);
  ck_assert_double_eq(gsl_ran_gaussian_ziggurat(r, 1.0), 0.0);
  gsl_rng_set(r, 0);
  double s = sb_bm_fpt_sample(r, 1.0, 0.0, 0.0, 1.0);
  ck_assert_msg(isfinite(s) && s > 0.0,
                "sb_bm_fpt_sample without drift returned %g after an exact "
                "zero from the Gaussian generator (Levy: T < inf a.s.)", s);
  gsl_rng_free(r);
}
END_TEST

/* ---------------------------------------------------- Bessel-3 passage */

/* sb_bes3_fpt_cdf against a simulated Bessel-3 process: the norm of 3D BM
 * from (x,0,0) on n = 200 steps of size dt over [0, t], crossing of a
 * between grid points drawn exactly from the Bessel-3 BRIDGE formula given
 * the norms (sb_sim_bes3_hits; same Markov argument), so P(T_a <= t) is
 * reproduced without bias.  N = 5e4; criterion: reference in the 99.9%
 * Clopper-Pearson interval at t/4, t/2 and t (the three are nested events
 * of the same paths, each tested on its own). */
START_TEST(test_bes3_fpt_mc)
{
  const double x = 1.5, a = 1.0, s2 = 1.0, t = 2.0;
  enum { N = 50000, NS = 200 };
  gsl_rng *r = rng_new(7001);
  unsigned long hits[NS], nh, cnt[3] = {0, 0, 0};
  ck_assert_int_eq(sb_sim_bes3_hits(r, x, a, s2, t, NS, N, hits, &nh),
                   SB_SUCCESS);
  for (int k = 0; k < NS; k++) {
    cnt[0] += k < NS / 4 ? hits[k] : 0;
    cnt[1] += k < NS / 2 ? hits[k] : 0;
    cnt[2] += hits[k];
  }
  gsl_rng_free(r);
  const double tt[3] = {t / 4, t / 2, t};
  for (int j = 0; j < 3; j++) {
    char what[64];
    snprintf(what, sizeof what, "bes3_fpt_cdf t=%g", tt[j]);
    check_cross(what, cnt[j], N, sb_bes3_fpt_cdf(tt[j], x, a, s2));
  }
}
END_TEST

/* ------------------------------------------- simulator argument checks */

/* Bad arguments give a status and draw nothing; a start on or below the
 * level is a crossing in sub-step 0 without draws; a = 0 is never reached
 * by a Bessel-3 path. */
START_TEST(test_sim_args)
{
  gsl_rng *r = rng_new(8001);
  unsigned long h[4], nh = 7;
  int k = 5;
  ck_assert_int_eq(sb_sim_bb_path(r, 2, 2, 1, 0.0, 1, 4, &k), SB_EDOM);
  ck_assert_int_eq(sb_sim_bb_path(r, NAN, 2, 1, 1, 1, 4, &k), SB_EDOM);
  ck_assert_int_eq(sb_sim_bb_path(r, 2, 2, 1, 1, -1, 4, &k), SB_EDOM);
  ck_assert_int_eq(sb_sim_bb_path(r, 2, 2, 1, 1, 1, 0, &k), SB_EINVAL);
  ck_assert_int_eq(sb_sim_bb_path(NULL, 2, 2, 1, 1, 1, 4, &k), SB_EINVAL);
  ck_assert_int_eq(sb_sim_bes3b_path(r, 2, 2, -1, 1, 1, 4, &k), SB_EDOM);
  ck_assert_int_eq(sb_sim_bes3_path(r, 2, 1, 1, INFINITY, 4, &k), SB_EDOM);
  ck_assert_int_eq(sb_sim_bes3b_hits(r, 2, 2, 1, 1, 1, 4, 10, h, NULL),
                   SB_EINVAL);
  ck_assert_int_eq(k, 5); /* untouched */
  gsl_rng *r2 = rng_new(8001);
  ck_assert_int_eq(sb_sim_bb_path(r, 0.5, 2, 1, 1, 1, 4, &k), SB_SUCCESS);
  ck_assert_int_eq(k, 0);
  ck_assert_int_eq(sb_sim_bes3b_hits(r, 1, 2, 1, 1, 1, 4, 3, h, &nh),
                   SB_SUCCESS);
  ck_assert(nh == 3 && h[0] == 3 && h[1] == 0 && h[3] == 0);
  /* no draws were made: r is still in r2's state */
  ck_assert(gsl_rng_get(r) == gsl_rng_get(r2));
  ck_assert_int_eq(sb_sim_bes3_hits(r, 1.0, 0.0, 1, 1, 4, 100, h, &nh),
                   SB_SUCCESS);
  ck_assert(nh == 0);
  double x[3] = {0}, u[3] = {0};
  sb_langevin bad = {-1.0, 1.0, 0.0}, ok = {1.0, 1.0, NAN};
  ck_assert_int_eq(sb_sim_langevin(&bad, 0.1, 1, r, 1, x, u), SB_EDOM);
  ck_assert_int_eq(sb_sim_langevin(&ok, 0.1, 1, r, 1, x, u), SB_EDOM);
  ck_assert_int_eq(sb_sim_langevin(NULL, 0.1, 1, r, 1, x, u), SB_EINVAL);
  ck_assert(x[0] == 0 && u[0] == 0);
  gsl_rng_free(r);
  gsl_rng_free(r2);
}
END_TEST

/* The grid simulators at extreme arguments.  (1) Every argument of the
 * three path functions over the shared sweep list sbt_sweep_ext (sweep.h:
 * +-1e-320 ... +-DBL_MAX, +-inf, NaN, 0, 2^+-995, 1e+-154) and, on top,
 * 1e-150, 1e150 and +-1 (the others x = 2, y = 1, a = 0.5, sigma2 = t =
 * 1), n = 1 and 8, 20 paths each: status 0 with k in [-1, n), or an
 * error naming the function.
 * (2) t = 1e300 and DBL_MAX, sigma2 = 1e-300 t = 1e300 (sigma2 t^2 beyond
 * the doubles: the sub-step variance was +inf, the positions NaN, and the
 * path never crossed): the crossing frequency of 2000 paths (n = 8, seed
 * 8101) within 5 binomial sd (+ 0.005) of sb_bb_cross_prob /
 * sb_bes3b_cross_prob / sb_bes3_fpt_cdf, and the _hits counts agree.
 * (3) sigma2 t = 1e-320 with |a| = 1e300: no crossing. */
START_TEST(test_sim_extreme)
{
  gsl_rng *r = rng_new(8101);
  double ext[SBT_SWEEP_NEXT + 4];
  memcpy(ext, sbt_sweep_ext, sizeof sbt_sweep_ext);
  const double more[4] = {1e-150, 1e150, 1.0, -1.0};
  memcpy(ext + SBT_SWEEP_NEXT, more, sizeof more);
  static const char *name[3] = {"sb_sim_bb_path", "sb_sim_bes3b_path",
                                "sb_sim_bes3_path"};
  for (int kind = 0; kind < 3; kind++)
    for (int i = 0; i < 5; i++)
      for (size_t e = 0; e < sizeof ext / sizeof ext[0]; e++)
        for (int n = 1; n <= 8; n *= 8) {
          double a[5] = {2.0, 1.0, 0.5, 1.0, 1.0};
          a[i] = ext[e];
          for (int rep = 0; rep < 20; rep++) {
            int k = -7;
            sb_clear_error();
            int st = kind == 0 ? sb_sim_bb_path(r, a[0], a[1], a[2], a[3],
                                                a[4], n, &k)
                     : kind == 1 ? sb_sim_bes3b_path(r, a[0], a[1], a[2],
                                                     a[3], a[4], n, &k)
                                 : sb_sim_bes3_path(r, a[0], a[2], a[3], a[4],
                                                    n, &k);
            if (st != SB_SUCCESS) {
              ck_assert(strstr(sb_last_error(), name[kind]) != NULL);
              break;
            }
            ck_assert_msg(k >= -1 && k < n, "%s argument %d = %g: k = %d",
                          name[kind], i, ext[e], k);
          }
        }
  const double sets[3][2] = {{1.0, 1e300}, {1.0, DBL_MAX}, {1e-300, 1e300}};
  for (int kind = 0; kind < 3; kind++)
    for (int j = 0; j < 3; j++) {
      const double x = 2.0, y = 1.0, a = 0.5, s2 = sets[j][0], t = sets[j][1];
      /* the exact P(cross) from the closed forms (bridge, passage) */
      const double v = s2 * t;
      const double P =
          kind == 0   ? sb_bb_cross_prob(x, y, a, v)
          : kind == 1 ? sb_bes3b_cross_prob(x, y, a, v)
                      : sb_bes3_fpt_cdf(t, x, a, s2);
      const int N = 2000;
      int cnt = 0;
      for (int p = 0; p < N; p++) {
        int k;
        int st = kind == 0   ? sb_sim_bb_path(r, x, y, a, s2, t, 8, &k)
                 : kind == 1 ? sb_sim_bes3b_path(r, x, y, a, s2, t, 8, &k)
                             : sb_sim_bes3_path(r, x, a, s2, t, 8, &k);
        ck_assert_int_eq(st, SB_SUCCESS);
        cnt += k >= 0;
      }
      const double f = (double)cnt / N, sd = sqrt(P * (1 - P) / N);
      ck_assert_msg(fabs(f - P) <= 5 * sd + 0.005,
                    "kind %d sigma2 %g t %g: frequency %g, P = %g", kind, s2,
                    t, f, P);
      unsigned long h[8], nh;
      int st = kind == 0   ? sb_sim_bb_hits(r, x, y, a, s2, t, 8, N, h, &nh)
               : kind == 1 ? sb_sim_bes3b_hits(r, x, y, a, s2, t, 8, N, h, &nh)
                           : sb_sim_bes3_hits(r, x, a, s2, t, 8, N, h, &nh);
      ck_assert_int_eq(st, SB_SUCCESS);
      ck_assert_msg(fabs((double)nh / N - P) <= 5 * sd + 0.005,
                    "hits kind %d sigma2 %g t %g: %lu of %d, P = %g", kind,
                    s2, t, nh, N, P);
    }
  /* sigma2 t far below 1 with positions far above its root: the laws are
   * deterministic (P = 0 here, computed by sb_bb_cross_prob); scaling the
   * positions with sigma2 t would overflow them */
  ck_assert(sb_bb_cross_prob(-1.0, -1e150, -1e300, 1e-320) == 0.0);
  for (int p = 0; p < 200; p++) {
    int k;
    ck_assert_int_eq(sb_sim_bb_path(r, -1.0, -1e150, -1e300, 1e-320, 1.0, 4,
                                    &k),
                     SB_SUCCESS);
    ck_assert_int_eq(k, -1);
  }
  gsl_rng_free(r);
}
END_TEST

/* The grid simulators where the positions or sigma2 t leave the range
 * the kernels handle (each was wrong with status 0: +-inf or NaN
 * variances and norms, x - a overflowing, 0/0 in the Bessel-3 sub-step
 * probability; frequencies 0 or 1, or 0.49 for 0.11): sigma2 t beyond
 * DBL_MAX or below DBL_MIN with positions on the scale of its root, x - a
 * beyond DBL_MAX, Bessel-3 positions far below the root of sigma2 t or
 * whose squares overflow.  The crossing frequency of 2000 paths (n = 8,
 * seed 8301) within 5 binomial sd (+ 0.005) of P from mpmath (40 digits):
 * exp(-2(x-a)(y-a)/v), expm1(2a(x+y-a)/v)/expm1(2xy/v), (a/x) erfc((x-a)/
 * sqrt(2v)), v = sigma2 t; the _hits counts too.  Where the positions and
 * the root of sigma2 t span more than the doubles: SB_ERANGE naming the
 * function. */
START_TEST(test_sim_scaled)
{
  gsl_rng *r = rng_new(8301);
  static const struct {
    int kind;
    double x, y, a, s2, t, P;
  } c[] = {
      {0, 0.75 * DBL_MAX, 0.0, -0.75 * DBL_MAX, DBL_MAX, DBL_MAX,
       0.10539922456186435434},
      {0, 1e300, 5e299, 0.0, 1e300, 1e300, 0.3678794411714423216},
      {1, 1e300, 2e300, 5e299, 1e300, 1e300, 0.20863581959057165132},
      {1, 1e-300, 1e-300, 5e-301, 1e-300, 1.0, 0.75},
      {1, 1e-300, 1e-300, 5e-301, 1e-300, 1e-300, 0.54494576607658875522},
      {2, 2e-300, 0.0, 1e-300, 1e-300, 1e-300, 0.15865525393145705141},
      {2, 2e300, 0.0, 1e300, 1e300, 1e300, 0.15865525393145705141},
      {1, 1e-300, 1e300, 5e-301, 1e-300, 1e300, 0.26894142136999512075}};
  for (size_t i = 0; i < sizeof c / sizeof c[0]; i++) {
    const int N = 2000;
    int cnt = 0;
    for (int p = 0; p < N; p++) {
      int k = -7;
      const int st =
          c[i].kind == 0
              ? sb_sim_bb_path(r, c[i].x, c[i].y, c[i].a, c[i].s2, c[i].t, 8,
                               &k)
          : c[i].kind == 1
              ? sb_sim_bes3b_path(r, c[i].x, c[i].y, c[i].a, c[i].s2, c[i].t,
                                  8, &k)
              : sb_sim_bes3_path(r, c[i].x, c[i].a, c[i].s2, c[i].t, 8, &k);
      ck_assert_int_eq(st, SB_SUCCESS);
      ck_assert(k >= -1 && k < 8);
      cnt += k >= 0;
    }
    const double P = c[i].P, sd = sqrt(P * (1 - P) / N);
    ck_assert_msg(fabs((double)cnt / N - P) <= 5 * sd + 0.005,
                  "case %zu: frequency %g, P = %g", i, (double)cnt / N, P);
    unsigned long h[8], nh;
    const int st =
        c[i].kind == 0
            ? sb_sim_bb_hits(r, c[i].x, c[i].y, c[i].a, c[i].s2, c[i].t, 8,
                             N, h, &nh)
        : c[i].kind == 1
            ? sb_sim_bes3b_hits(r, c[i].x, c[i].y, c[i].a, c[i].s2, c[i].t,
                                8, N, h, &nh)
            : sb_sim_bes3_hits(r, c[i].x, c[i].a, c[i].s2, c[i].t, 8, N, h,
                               &nh);
    ck_assert_int_eq(st, SB_SUCCESS);
    ck_assert_msg(fabs((double)nh / N - P) <= 5 * sd + 0.005,
                  "hits case %zu: %lu of %d, P = %g", i, nh, N, P);
  }
  /* positions 1e-300 against sqrt(sigma2 t) = 1e300: 1e-600 apart */
  int k = -7;
  sb_clear_error();
  ck_assert_int_eq(sb_sim_bes3b_path(r, 1e-300, 1e-300, 5e-301, 1e300,
                                     1e300, 8, &k),
                   SB_ERANGE);
  ck_assert(strstr(sb_last_error(), "sb_sim_bes3b_path") != NULL);
  ck_assert_int_eq(k, -7);
  gsl_rng_free(r);
}
END_TEST

/* sb_sim_langevin at extreme arguments.  (1) tau, B, dt, us and the start
 * state x0, u0 (all three components) in turn over sbt_sweep_ext (the
 * others tau = 0.7, B = 1.3, dt = 0.4, us = 0.2, x0 = 1.5, u0 = -0.8),
 * three steps of one particle: finite x, u with status 0, or SB_EDOM /
 * SB_ERANGE naming the function.  (2) B = DBL_MAX, tau = dt = 1 (velocity
 * sd ~ 0.8 DBL_MAX: x, u were +-inf with status 0 within 10 steps):
 * SB_ERANGE, the state left finite.  (3) B = 0, tau = dt = 1, us =
 * -DBL_MAX/2, u0 up to DBL_MAX: u0 - us overflows but the new state is a
 * double (x, u were +-inf with status 0; sb_langevin_step, which shares
 * the update, gave SB_ERANGE): the mpmath values (50 digits,
 * x1 = x0 + us + (u0 - us)(1 - e^-1), u1 = us + (u0 - us) e^-1). */
static gsl_rng *lv_rng;
static int x_sim_langevin(const double *a, double *out, int *n,
                          const char **nm)
{
  sb_langevin p = {a[0], a[1], a[3]};
  double x[3] = {a[4], a[4], a[4]}, u[3] = {a[5], a[5], a[5]};
  int st = sb_sim_langevin(&p, a[2], 3, lv_rng, 1, x, u);
  for (int j = 0; j < 3; j++) {
    out[j] = x[j];
    out[3 + j] = u[j];
  }
  *n = 6;
  *nm = "sb_sim_langevin";
  return st;
}

START_TEST(test_sim_langevin_extreme)
{
  lv_rng = rng_new(8202);
  const double base[6] = {0.7, 1.3, 0.4, 0.2, 1.5, -0.8};
  ck_assert_int_eq(sbt_sweep_vec(x_sim_langevin, base, 6, 6, 0u, 0, 0, 0),
                   0);
  gsl_rng_free(lv_rng);
  gsl_rng *r = rng_new(8203);
  sb_langevin big = {1.0, DBL_MAX, 0.0};
  double x[3] = {0.0, 0.0, 0.0}, u[3] = {0.0, 0.0, 0.0};
  sb_clear_error();
  ck_assert_int_eq(sb_sim_langevin(&big, 1.0, 10, r, 1, x, u), SB_ERANGE);
  ck_assert(strstr(sb_last_error(), "sb_sim_langevin") != NULL);
  for (int j = 0; j < 3; j++)
    ck_assert(isfinite(x[j]) && isfinite(u[j]));
  const double dm = DBL_MAX;
  sb_langevin det = {1.0, 0.0, -0.5 * dm};
  double x3[3] = {0.0, -dm, 1e308}, u3[3] = {dm, 0.9 * dm, 0.6 * dm};
  const double wx[3] = {8.0569161608598520929e+307,
                        -1.1056373976774733571e+308,
                        1.351148100481413661e+308};
  const double wu[3] = {9.315495134517264478e+306, 2.7021516760083952199e+306,
                        -1.7137878699518219897e+307};
  ck_assert_int_eq(sb_sim_langevin(&det, 1.0, 1, r, 1, x3, u3), SB_SUCCESS);
  for (int j = 0; j < 3; j++) {
    ck_assert_rel(x3[j], wx[j], TOL_TIGHT);
    ck_assert_rel(u3[j], wu[j], TOL_TIGHT);
  }
  /* the scalar step shares the update (it was SB_ERANGE there) */
  double xs = 0.0, us = dm;
  ck_assert_int_eq(sb_langevin_step(&det, 1.0, r, &xs, &us), SB_SUCCESS);
  ck_assert_rel(xs, wx[0], TOL_TIGHT);
  ck_assert_rel(us, wu[0], TOL_TIGHT);
  gsl_rng_free(r);
}
END_TEST

/* ============================================================ suite */

static Suite *bridge_mc_suite(void)
{
  Suite *s = suite_create("bridge_mc");
  TCase *tc;

  tc = tcase_create("bb_cross");
  tcase_set_timeout(tc, 60);
  tcase_add_loop_test(tc, test_bb_cross_mc, 0,
                      (int)(sizeof bb_sets / sizeof bb_sets[0]));
  suite_add_tcase(s, tc);

  tc = tcase_create("bes3b_cross");
  tcase_set_timeout(tc, 60);
  tcase_add_loop_test(tc, test_bes3b_cross_mc, 0,
                      (int)(sizeof bes_sets / sizeof bes_sets[0]));
  tcase_add_test(tc, test_bes3b_grid_independence);
  tcase_add_test(tc, test_bes3_fpt_mc);
  suite_add_tcase(s, tc);

  tc = tcase_create("samplers");
  tcase_set_timeout(tc, 60);
  tcase_add_loop_test(tc, test_bb_hit_sampler, 0,
                      (int)(sizeof bbh_sets / sizeof bbh_sets[0]));
  tcase_add_loop_test(tc, test_bes3b_hit_sampler, 0,
                      (int)(sizeof b3h_sets / sizeof b3h_sets[0]));
  tcase_add_loop_test(tc, test_bm_fpt_sampler, 0,
                      (int)(sizeof fpt_sets / sizeof fpt_sets[0]));
  tcase_add_test(tc, test_fpt_sampler_gaussian_zero);
  tcase_add_test(tc, test_sim_args);
  suite_add_tcase(s, tc);

  tc = tcase_create("sim_extreme");
  tcase_set_timeout(tc, 60);
  tcase_add_test(tc, test_sim_extreme);
  tcase_add_test(tc, test_sim_langevin_extreme);
  tcase_add_test(tc, test_sim_scaled);
  suite_add_tcase(s, tc);
  return s;
}

int main(void)
{
  return sbt_run_suite(bridge_mc_suite());
}
