/* eval_bridge.c — `smolbridge eval` entries of the bridge and passage
 * modules. */
#include <gsl/gsl_rng.h>
#include <smolbridge/bridge.h>
#include <smolbridge/common.h>
#include <smolbridge/passage.h>

#include "cli.h"

SBE_WRAP4(bb_cross_prob)
SBE_WRAP4(bb_cross_logprob)
SBE_WRAP4(bb_nocross_prob)
SBE_WRAP4(bes3b_cross_prob)
SBE_WRAP4(bes3b_cross_logprob)
SBE_WRAP4(bes3b_nocross_prob)
SBE_WRAP6(bb_hit_pdf)
SBE_WRAP6(bb_hit_cdf)
SBE_WRAP6(bb_hit_sf)
SBE_WRAP6(bb_hit_quantile)
SBE_WRAP6(bes3b_hit_pdf)
SBE_WRAP6(bes3b_hit_cdf)
SBE_WRAP6(bes3b_hit_sf)
SBE_WRAP6(bes3b_hit_quantile)
SBE_WRAP5(bm_fpt_pdf)
SBE_WRAP5(bm_fpt_cdf)
SBE_WRAP5(bm_fpt_sf)
SBE_WRAP4(bm_fpt_mass)
SBE_WRAP4(bm_fpt_logmass)
SBE_WRAP5(bm_fpt_quantile)
SBE_WRAP4(bes3_fpt_pdf)
SBE_WRAP4(bes3_fpt_cdf)
SBE_WRAP4(bes3_fpt_sf)

/* Samplers: the first argument is the seed of an MT19937 generator. */
static gsl_rng *seeded(double seed)
{
  gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
  if (r)
    gsl_rng_set(r, (unsigned long)seed);
  return r;
}
#define SBE_SAMPLER(f, call)                                            \
  static int sbe_w_##f(const double *i, double *o)                      \
  {                                                                     \
    gsl_rng *r = seeded(i[0]);                                          \
    if (!r)                                                             \
      return SB_ENOMEM;                                                 \
    o[0] = call;                                                        \
    gsl_rng_free(r);                                                    \
    return SB_SUCCESS;                                                  \
  }
SBE_SAMPLER(bb_hit_sample, sb_bb_hit_sample(r, i[1], i[2], i[3], i[4], i[5]))
SBE_SAMPLER(bes3b_hit_sample,
            sb_bes3b_hit_sample(r, i[1], i[2], i[3], i[4], i[5]))
SBE_SAMPLER(bm_fpt_sample, sb_bm_fpt_sample(r, i[1], i[2], i[3], i[4]))

#define XYAV {"x", "y", "a", "v", NULL}
#define HIT(first) {first, "x", "y", "a", "sigma2", "t", NULL}
#define FPT(first) {first, "x", "a", "mu", "sigma2", NULL}
#define MASS {"x", "a", "mu", "sigma2", NULL}
#define B3FPT {"t", "x", "a", "sigma2", NULL}
#define E(n, args, text) {#n, args, {NULL}, sbe_w_##n, text}

static const sbe_func funcs[] = {
    E(bb_cross_prob, XYAV, "Brownian bridge: P(min <= a)"),
    E(bb_cross_logprob, XYAV, "Brownian bridge: log P(min <= a)"),
    E(bb_nocross_prob, XYAV, "Brownian bridge: P(min > a)"),
    E(bes3b_cross_prob, XYAV, "Bessel-3 bridge: P(min <= a)"),
    E(bes3b_cross_logprob, XYAV, "Bessel-3 bridge: log P(min <= a)"),
    E(bes3b_nocross_prob, XYAV, "Bessel-3 bridge: P(min > a)"),
    E(bb_hit_pdf, HIT("u"), "Brownian bridge: density of T_a | T_a < t"),
    E(bb_hit_cdf, HIT("u"), "Brownian bridge: P(T_a <= u | T_a < t)"),
    E(bb_hit_sf, HIT("u"), "Brownian bridge: P(T_a > u | T_a < t)"),
    E(bb_hit_quantile, HIT("p"), "Brownian bridge: quantile of T_a | T_a < t"),
    E(bb_hit_sample, HIT("seed"), "Brownian bridge: one draw of T_a | T_a < t"),
    E(bes3b_hit_pdf, HIT("u"), "Bessel-3 bridge: density of T_a | T_a < t"),
    E(bes3b_hit_cdf, HIT("u"), "Bessel-3 bridge: P(T_a <= u | T_a < t)"),
    E(bes3b_hit_sf, HIT("u"), "Bessel-3 bridge: P(T_a > u | T_a < t)"),
    E(bes3b_hit_quantile, HIT("p"),
      "Bessel-3 bridge: quantile of T_a | T_a < t"),
    E(bes3b_hit_sample, HIT("seed"),
      "Bessel-3 bridge: one draw of T_a | T_a < t"),
    E(bm_fpt_pdf, FPT("t"), "BM with drift: first-passage density"),
    E(bm_fpt_cdf, FPT("t"), "BM with drift: P(T <= t)"),
    E(bm_fpt_sf, FPT("t"), "BM with drift: P(T > t) (T = inf included)"),
    E(bm_fpt_mass, MASS, "BM with drift: P(T < inf)"),
    E(bm_fpt_logmass, MASS, "BM with drift: log P(T < inf)"),
    E(bm_fpt_quantile, FPT("p"), "BM with drift: quantile of T (inf above mass)"),
    E(bm_fpt_sample, FPT("seed"), "BM with drift: one draw of T (inf: no hit)"),
    E(bes3_fpt_pdf, B3FPT, "Bessel-3 down to a < x: first-passage density"),
    E(bes3_fpt_cdf, B3FPT, "Bessel-3 down to a < x: P(T <= t), mass a/x"),
    E(bes3_fpt_sf, B3FPT, "Bessel-3 down to a < x: P(T > t)"),
};

const sbe_table sbe_table_bridge = {funcs, sizeof funcs / sizeof funcs[0]};
