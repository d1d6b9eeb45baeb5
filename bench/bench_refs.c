/* bench_refs.c — ns per call of the bridge and passage references
 * single thread, median of repeated batches.
 *
 * Goals: crossing probability <= 50 ns; hit-time quantile and
 * sampler <= 1 us; first-passage pdf/cdf <= 100 ns.  exp() and GSL's
 * ziggurat Gaussian are timed for scale.  Arguments come from arrays of
 * 4096 pre-generated random parameter sets (fixed seed), so the compiler
 * cannot hoist the call, and every result goes into a volatile sink.  The
 * argument ranges are the regimes a collision-detection code meets
 * (x, y within a few sqrt(v) of the level; v/a^2 over four decades).
 *
 * Usage: bench/bench_refs [--quick] [--reps N] [--ms T]   (see benchutil.h)
 * Exit status 0 even if a goal is missed (the table says MISS).
 */
#define _POSIX_C_SOURCE 200809L
#include "benchutil.h"

#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>

#include <smolbridge/bridge.h>
#include <smolbridge/passage.h>

#define LOG2N 12 /* 4096 argument sets per table */

typedef struct {
  const sbb_args *args;
  gsl_rng *r;
} bctx;

/* A kernel evaluating `expr` (which reads A[col][j]) n times. */
#define KERNEL(name, expr)                                                  \
  static void name(void *vc, size_t n)                                      \
  {                                                                         \
    const bctx *c = vc;                                                     \
    const size_t m = c->args->mask;                                         \
    double *const *A = c->args->col;                                        \
    double s = 0.0;                                                         \
    for (size_t i = 0; i < n; i++) {                                        \
      const size_t j = i & m;                                               \
      (void)j;                                                              \
      s += (expr);                                                          \
    }                                                                       \
    sbb_consume(s);                                                         \
    (void)A;                                                                \
  }

/* ------------------------------------------------------------ kernels */
/* crossing: columns x, y, a, v */
KERNEL(k_exp, exp(-A[0][j]))
KERNEL(k_gauss, gsl_ran_gaussian_ziggurat(c->r, 1.0))
KERNEL(k_bb_cross, sb_bb_cross_prob(A[0][j], A[1][j], A[2][j], A[3][j]))
KERNEL(k_bb_logp, sb_bb_cross_logprob(A[0][j], A[1][j], A[2][j], A[3][j]))
KERNEL(k_bb_nocross, sb_bb_nocross_prob(A[0][j], A[1][j], A[2][j], A[3][j]))
KERNEL(k_b3_cross, sb_bes3b_cross_prob(A[0][j], A[1][j], A[2][j], A[3][j]))
KERNEL(k_b3_logp, sb_bes3b_cross_logprob(A[0][j], A[1][j], A[2][j], A[3][j]))
KERNEL(k_b3_nocross,
       sb_bes3b_nocross_prob(A[0][j], A[1][j], A[2][j], A[3][j]))
/* hitting times: columns p, x, y, a, sigma2, t */
KERNEL(k_bb_hq, sb_bb_hit_quantile(A[0][j], A[1][j], A[2][j], A[3][j],
                                   A[4][j], A[5][j]))
KERNEL(k_bb_hs, sb_bb_hit_sample(c->r, A[1][j], A[2][j], A[3][j], A[4][j],
                                 A[5][j]))
KERNEL(k_bb_hc, sb_bb_hit_cdf(A[0][j] * A[5][j], A[1][j], A[2][j], A[3][j],
                              A[4][j], A[5][j]))
KERNEL(k_b3_hq, sb_bes3b_hit_quantile(A[0][j], A[1][j], A[2][j], A[3][j],
                                      A[4][j], A[5][j]))
KERNEL(k_b3_hs, sb_bes3b_hit_sample(c->r, A[1][j], A[2][j], A[3][j],
                                    A[4][j], A[5][j]))
KERNEL(k_b3_hc, sb_bes3b_hit_cdf(A[0][j] * A[5][j], A[1][j], A[2][j],
                                 A[3][j], A[4][j], A[5][j]))
/* BM first passage: columns t, x, a, mu, sigma2 (col 5: p) */
KERNEL(k_bm_pdf, sb_bm_fpt_pdf(A[0][j], A[1][j], A[2][j], A[3][j], A[4][j]))
KERNEL(k_bm_cdf, sb_bm_fpt_cdf(A[0][j], A[1][j], A[2][j], A[3][j], A[4][j]))
KERNEL(k_bm_q, sb_bm_fpt_quantile(A[5][j], A[1][j], A[2][j], A[3][j],
                                  A[4][j]))
KERNEL(k_bm_s, sb_bm_fpt_sample(c->r, A[1][j], A[2][j], A[3][j], A[4][j]))
/* Bessel-3 first passage: columns t, x, a, sigma2 */
KERNEL(k_b3f_pdf, sb_bes3_fpt_pdf(A[0][j], A[1][j], A[2][j], A[3][j]))
KERNEL(k_b3f_cdf, sb_bes3_fpt_cdf(A[0][j], A[1][j], A[2][j], A[3][j]))

/* ------------------------------------------------------- argument sets */

static double unif(const gsl_rng *r, double lo, double hi)
{
  return lo + (hi - lo) * gsl_rng_uniform(r);
}
static double logunif(const gsl_rng *r, double lo, double hi)
{
  return exp(unif(r, log(lo), log(hi)));
}

/* Crossing: a in [0.1, 10] (log-uniform), v/a^2 in [1e-2, 1e2], x and y
 * at a + |N(0, 2^2)| sqrt(v): crossing probabilities from ~1 to ~1e-8. */
static int fill_cross(sbb_args *A, const gsl_rng *r)
{
  if (sbb_args_alloc(A, LOG2N, 4))
    return -1;
  for (size_t i = 0; i < A->n; i++) {
    double a = logunif(r, 0.1, 10.0), v = a * a * logunif(r, 1e-2, 1e2);
    A->col[0][i] = a + fabs(gsl_ran_gaussian(r, 2.0)) * sqrt(v);
    A->col[1][i] = a + fabs(gsl_ran_gaussian(r, 2.0)) * sqrt(v);
    A->col[2][i] = a;
    A->col[3][i] = v;
  }
  return 0;
}

/* Hitting times: p uniform; a = 1, t = 1, sigma2 = v; x, y as above with
 * v in [vlo, vhi] (Bessel-3: regime of 1 - rho, see main). */
static int fill_hit(sbb_args *A, const gsl_rng *r, double a, double vlo,
                    double vhi)
{
  if (sbb_args_alloc(A, LOG2N, 6))
    return -1;
  for (size_t i = 0; i < A->n; i++) {
    double v = logunif(r, vlo, vhi);
    A->col[0][i] = gsl_rng_uniform_pos(r);
    A->col[1][i] = a + fabs(gsl_ran_gaussian(r, 1.0)) * sqrt(v);
    A->col[2][i] = a + fabs(gsl_ran_gaussian(r, 1.0)) * sqrt(v);
    A->col[3][i] = a;
    A->col[4][i] = v;
    A->col[5][i] = 1.0;
  }
  return 0;
}

/* BM first passage: x in [0.5, 2] above a = 0, mu in [-2, 2] (both signs:
 * towards, and away = defective), sigma2 in [0.1, 10], t around the
 * natural time x^2/sigma2. */
static int fill_fpt(sbb_args *A, const gsl_rng *r)
{
  if (sbb_args_alloc(A, LOG2N, 6))
    return -1;
  for (size_t i = 0; i < A->n; i++) {
    double x = unif(r, 0.5, 2.0), s2 = logunif(r, 0.1, 10.0);
    A->col[0][i] = x * x / s2 * logunif(r, 0.05, 20.0);
    A->col[1][i] = x;
    A->col[2][i] = 0.0;
    A->col[3][i] = unif(r, -2.0, 2.0);
    A->col[4][i] = s2;
    A->col[5][i] = gsl_rng_uniform_pos(r) * 0.3; /* p below every mass */
  }
  return 0;
}

static int fill_b3fpt(sbb_args *A, const gsl_rng *r)
{
  if (sbb_args_alloc(A, LOG2N, 4))
    return -1;
  for (size_t i = 0; i < A->n; i++) {
    double a = logunif(r, 0.1, 10.0), x = a * unif(r, 1.01, 3.0);
    double s2 = logunif(r, 0.1, 10.0);
    A->col[0][i] = (x - a) * (x - a) / s2 * logunif(r, 0.05, 20.0);
    A->col[1][i] = x;
    A->col[2][i] = a;
    A->col[3][i] = s2;
  }
  return 0;
}

/* ------------------------------------------------------------- main */

int main(int argc, char **argv)
{
  sbb_opts o = sbb_opts_parse(argc, argv);
  gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
  if (!r)
    return 1;
  gsl_rng_set(r, 20240601UL);
  sbb_args cross, hit, b3A, b3B, b3C, b3D, fpt, b3f;
  if (fill_cross(&cross, r) || fill_hit(&hit, r, 1.0, 1e-2, 1e1) ||
      /* Bessel-3 regime A: v << a^2, 1 - rho ~ 1 (the collisions of
       * Mohaupt 2011, ch. 5) */
      fill_hit(&b3A, r, 1.0, 1e-2, 0.3) ||
      /* regime B: v >> a^2 (a = 0.01, v in [0.5, 5]), 1 - rho ~ 1e-2 */
      fill_hit(&b3B, r, 0.01, 0.5, 5.0) ||
      /* regimes C and D: a = 1e-4 and 1e-6, 1 - rho ~ 1e-4 and 1e-6 (a
       * pair that barely reaches contact distance; the mixture (2) of
       * bridge_hit.c over a very short range of the minimum) */
      fill_hit(&b3C, r, 1e-4, 0.5, 5.0) || fill_hit(&b3D, r, 1e-6, 0.5, 5.0) ||
      fill_fpt(&fpt, r) ||
      fill_b3fpt(&b3f, r)) {
    fprintf(stderr, "bench_refs: out of memory\n");
    return 1;
  }
  gsl_rng *rs = gsl_rng_alloc(gsl_rng_mt19937); /* for the samplers */
  gsl_rng_set(rs, 1UL);

  const double G_CROSS = 50, G_HIT = 1000, G_FPT = 100;
  const struct {
    const char *name;
    sbb_kernel k;
    const sbb_args *args;
    double goal;
  } rows[] = {
      {"exp (scale)", k_exp, &cross, NAN},
      {"gsl_ran_gaussian_ziggurat (scale)", k_gauss, &cross, NAN},
      {"sb_bb_cross_prob", k_bb_cross, &cross, G_CROSS},
      {"sb_bb_cross_logprob", k_bb_logp, &cross, G_CROSS},
      {"sb_bb_nocross_prob", k_bb_nocross, &cross, G_CROSS},
      {"sb_bes3b_cross_prob", k_b3_cross, &cross, G_CROSS},
      {"sb_bes3b_cross_logprob", k_b3_logp, &cross, G_CROSS},
      {"sb_bes3b_nocross_prob", k_b3_nocross, &cross, G_CROSS},
      {"sb_bb_hit_cdf (info)", k_bb_hc, &hit, NAN},
      {"sb_bb_hit_quantile", k_bb_hq, &hit, G_HIT},
      {"sb_bb_hit_sample", k_bb_hs, &hit, G_HIT},
      {"sb_bes3b_hit_cdf, 1-rho~1 (info)", k_b3_hc, &b3A, NAN},
      {"sb_bes3b_hit_quantile, 1-rho~1", k_b3_hq, &b3A, G_HIT},
      {"sb_bes3b_hit_sample, 1-rho~1", k_b3_hs, &b3A, G_HIT},
      {"sb_bes3b_hit_cdf, 1-rho~1e-2 (info)", k_b3_hc, &b3B, NAN},
      {"sb_bes3b_hit_quantile, 1-rho~1e-2", k_b3_hq, &b3B, G_HIT},
      {"sb_bes3b_hit_sample, 1-rho~1e-2", k_b3_hs, &b3B, G_HIT},
      {"sb_bes3b_hit_cdf, 1-rho~1e-4 (info)", k_b3_hc, &b3C, NAN},
      {"sb_bes3b_hit_quantile, 1-rho~1e-4", k_b3_hq, &b3C, G_HIT},
      {"sb_bes3b_hit_cdf, 1-rho~1e-6 (info)", k_b3_hc, &b3D, NAN},
      {"sb_bes3b_hit_quantile, 1-rho~1e-6", k_b3_hq, &b3D, G_HIT},
      {"sb_bes3b_hit_sample, 1-rho~1e-6", k_b3_hs, &b3D, G_HIT},
      {"sb_bm_fpt_pdf", k_bm_pdf, &fpt, G_FPT},
      {"sb_bm_fpt_cdf", k_bm_cdf, &fpt, G_FPT},
      {"sb_bm_fpt_quantile (info)", k_bm_q, &fpt, NAN},
      {"sb_bm_fpt_sample (info)", k_bm_s, &fpt, NAN},
      {"sb_bes3_fpt_pdf", k_b3f_pdf, &b3f, G_FPT},
      {"sb_bes3_fpt_cdf", k_b3f_cdf, &b3f, G_FPT},
  };
  sbb_print_machine(stdout);
  printf("# goals: crossing <= %.0f ns, hit quantile/sampler <= "
         "%.0f ns, fpt pdf/cdf <= %.0f ns\n", G_CROSS, G_HIT, G_FPT);
  sbb_table_header(stdout);
  int miss = 0, ngoal = 0;
  for (size_t i = 0; i < sizeof rows / sizeof rows[0]; i++) {
    bctx c = {rows[i].args, rs};
    sbb_timing t = sbb_run(rows[i].k, &c, &o);
    miss += sbb_table_row(stdout, rows[i].name, &t, rows[i].goal);
    ngoal += !isnan(rows[i].goal);
    fflush(stdout);
  }
  printf("# %d of %d goals met\n", ngoal - miss, ngoal);
  sbb_args_free(&cross);
  sbb_args_free(&hit);
  sbb_args_free(&b3A);
  sbb_args_free(&b3B);
  sbb_args_free(&b3C);
  sbb_args_free(&b3D);
  sbb_args_free(&fpt);
  sbb_args_free(&b3f);
  gsl_rng_free(r);
  gsl_rng_free(rs);
  return 0;
}
