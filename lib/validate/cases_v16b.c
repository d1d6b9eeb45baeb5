/* cases_v16b.c — V16/deposition: Brownian particles between two
 * absorbing walls (docs/engine_forces.md §walls).
 *
 * Particles of diffusivity D = k_B T tau_p / m (Langevin, dt/tau_p ~ 1e8:
 * Brownian positions) start uniform and independent in a slab whose
 * contact planes are W = L_y - 2r apart (x, z periodic); a particle is
 * absorbed when the Brownian bridge of its wall-normal coordinate over a
 * step reaches a contact plane (Mohaupt 2011, §5.1).  Particle-particle
 * detection is off, so the particles are independent.
 *
 *  - Transient: the fraction absorbed by time t is 1 - S(t),
 *    S(t) = sum_{k odd} 8/(k pi)^2 exp(-(k pi)^2 D t / W^2), whose short-
 *    time form (images beyond e^{-W^2/(D t)} dropped) is the flux
 *    n sqrt(D/(pi t)) on each wall (Smoluchowski 1917).  The count in each
 *    time window is binomial(N, P_window): exact binomial test.  The same
 *    run with chord-only detection (the end point beyond the plane)
 *    shows what the bridge adds: it under-counts.
 *  - Steady state with a source: every absorbed particle is reinserted
 *    uniformly (a uniform volume source; N constant).  The steady profile
 *    c = (s/2D) y (W - y) gives the absorption rate 12 D N / W^2 on the
 *    two walls together; with reinsertion at the end of the step the
 *    exact rate of the protocol is N / (dt sum_{j>=0} S(j dt)).  The count is a superposition of renewal
 *    processes (not Poisson: the variance is ~1.4 times the mean), so the
 *    row is the Student mean of independent replicas.
 *
 * Each run draws its placement from a stream of its own, as `smolbridge
 * collide` draws placement = uniform from placement_seed: write mode
 * (--write-ini) writes every run as a collide file (detect = none, the
 * deposits per step in series.csv, profile = parabolic for the steady
 * source; docs/validation.md).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_rng.h>

#include <smolbridge/engine.h>

#include "common/internal.h"
#include "cases.h"
#include "v16.h"

#define PI 3.14159265358979323846
#define KB 1.380649e-23

double v16_slab_absorbed(double D, double t, double W)
{
  if (!(t > 0.0))
    return 0.0;
  const double q = PI * PI * D * t / (W * W);
  double S = 0.0;
  for (int k = 1; k < 200001; k += 2) {
    double term = 8.0 / (PI * PI * k * k) * exp(-q * k * k);
    S += term;
    if (term < 1e-18 * S)
      break;
  }
  /* 1 - S loses no digit that matters here (S <= 1, windows >= 1e-3) */
  return 1.0 - S;
}

typedef struct {
  double r, m, tau, B, D, W;
} brown;

static void brown_init(brown *b)
{
  /* 100 nm spheres in water at 300 K */
  const double T = 300.0, mu = 1e-3, rho = 1000.0;
  b->r = 50e-9;
  b->m = rho * 4.0 / 3.0 * PI * b->r * b->r * b->r;
  b->tau = rho * 4.0 * b->r * b->r / (18.0 * mu);
  b->B = sqrt(2.0 * KB * T / (b->m * b->tau));
  b->D = KB * T * b->tau / b->m;
}

static void setup_slab(const brown *b, double Ly, double Lxz, size_t n,
                       v16_setup *s)
{
  memset(s, 0, sizeof *s);
  s->L[0] = s->L[2] = Lxz;
  s->L[1] = Ly;
  s->nsp = 1;
  s->sp[0] = (v16_species){b->r, 1000.0, b->tau, b->B, n, SB_DRAG_STOKES,
                           0.0, 0.0};
  s->walls[1] = SB_WALL_ABSORB;
  s->walldet = SB_WALLDET_BRIDGE;
  s->deposit = SB_DEPOSIT_REMOVE;
  s->nodetect = 1;
}

/* Placement streams: each run its own generator (a collide file's
 * placement_seed); the bridge run keeps the case's first stream. */
#define DEP_BRIDGE_STREAM 1603UL
#define DEP_CHORD_STREAM 1604UL
#define DEP_STEADY_STREAM 16030UL  /* + replica */

int v16_write_walls(const sbv_ctx *ctx, sbv_report *rep, const v16_setup *s,
                    unsigned long placement_seed, size_t sample_every,
                    const char *name, const char *what)
{
  static const char *const face[3][2] = {
      {"x_lo", "x_hi"}, {"y_lo", "y_hi"}, {"z_lo", "z_hi"}};
  if (s->warmup || s->G != 0.0 || s->g[0] != 0.0 || s->g[1] != 0.0 ||
      s->g[2] != 0.0)
    return sbi_error(SB_EINVAL, __func__, "a warm-up, shear or gravity: "
                     "not written by this function");
  FILE *f = sbv_ini_begin(ctx, rep, name, what);
  if (!f)
    return SB_EIO;
  fprintf(f, "seed = %lu\nrng = mt19937\nLx = %.17g\nLy = %.17g\n"
          "Lz = %.17g\ndt = %.17g\nsteps = %zu\nsample_every = %zu\n",
          s->seed, s->L[0], s->L[1], s->L[2], s->dt, s->steps, sample_every);
  if (s->nodetect)
    fprintf(f, "detect = none\n");
  else
    fprintf(f, "detect = ballistic\noutcome = count\n");
  fprintf(f, "placement = uniform\nplacement_seed = %lu\n\n[walls]\n",
          placement_seed);
  for (int c = 0; c < 3; c++)
    if (s->walls[c])
      fprintf(f, "%s = %s\n%s = %s\n", face[c][0],
              s->walls[c] == SB_WALL_ABSORB ? "absorb" : "reflect",
              face[c][1],
              s->walls[c] == SB_WALL_ABSORB ? "absorb" : "reflect");
  fprintf(f, "detect = %s\ndeposit = %s\n",
          s->walldet == SB_WALLDET_BALLISTIC  ? "ballistic"
          : s->walldet == SB_WALLDET_LANGEVIN ? "langevin"
                                              : "bridge",
          s->deposit == SB_DEPOSIT_REINSERT ? "reinsert" : "remove");
  for (size_t a = 0; a < s->nsp; a++) {
    const v16_species *q = &s->sp[a];
    fprintf(f, "\n[species %c]\nradius = %.17g\nmass = %.17g\n"
            "tau = %.17g\nB = %.17g\ncount = %zu\n", (char)('a' + a), q->r,
            q->rho_p * 4.0 / 3.0 * PI * q->r * q->r * q->r, q->tau, q->B,
            q->count);
    if (s->parabolic)
      fprintf(f, "profile = parabolic\n");
  }
  return sbv_ini_end(rep, f, NULL);
}

void v16_expect_window(sbv_report *rep, const char *record, size_t k0,
                       size_t k, double factor)
{
  char fld[64];
  if (k0)
    snprintf(fld, sizeof fld, "series.csv %zu-%zu deposits", k, k0);
  else
    snprintf(fld, sizeof fld, "series.csv %zu deposits", k);
  sbv_ini_expect(rep, record, fld, factor);
}

/* The transient runs (bridge, chord) written as collide files: the
 * window counts are differences of series.csv rows (one per step). */
static int transient_write(const sbv_ctx *ctx, sbv_report *rep,
                           v16_setup *s, size_t N)
{
  int st = SB_SUCCESS;
  for (int det = 0; det < 2 && !st; det++) {
    s->walldet = det ? SB_WALLDET_BALLISTIC : SB_WALLDET_BRIDGE;
    s->seed = ctx->seed * 1000 + 1620 + (unsigned long)det;
    st = v16_write_walls(ctx, rep, s,
                         sbv_rng_seed(ctx, det ? DEP_CHORD_STREAM
                                               : DEP_BRIDGE_STREAM),
                         1, det ? "V16_deposition_transient_chord"
                                : "V16_deposition_transient_bridge",
                         det ? "V16/deposition: transient, chord-only wall "
                               "detection"
                             : "V16/deposition: transient, Brownian-bridge "
                               "wall detection");
    for (size_t k = 0; k < s->nmark && !st && !det; k++) {
      char name[128];
      snprintf(name, sizeof name,
               "V16/deposition/transient/bridge/t=%zudt/window-count",
               s->mark[k]);
      v16_expect_window(rep, name, k ? s->mark[k - 1] : 0, s->mark[k],
                        1.0 / (double)N);
    }
    if (!st && det)
      v16_expect_window(rep, "V16/deposition/transient/chord-only/t=32dt/"
                        "absorbed<ref", 0, s->mark[5], 1.0 / (double)N);
  }
  return st;
}

static int transient(const sbv_ctx *ctx, sbv_report *rep)
{
  brown b;
  brown_init(&b);
  const double Ly = 20e-6, W = Ly - 2.0 * b.r, TW = W * W / b.D;
  const size_t N = ctx->full ? 400000 : 20000;
  v16_setup s;
  setup_slab(&b, Ly, 20.0 * W, N, &s);
  s.dt = 2.5e-4 * TW;
  s.steps = 32;
  s.nmark = 6;
  for (size_t k = 0; k < 6; k++)
    s.mark[k] = (size_t)1 << k;
  if (sbv_writing(ctx))
    return transient_write(ctx, rep, &s, N);
  int st = SB_SUCCESS;
  v16_result res[2];
  for (int det = 0; det < 2 && !st; det++) {
    s.walldet = det ? SB_WALLDET_BALLISTIC : SB_WALLDET_BRIDGE;
    s.seed = ctx->seed * 1000 + 1620 + (unsigned long)det;
    gsl_rng *r = sbv_rng_alloc(ctx, det ? DEP_CHORD_STREAM
                                        : DEP_BRIDGE_STREAM);
    st = r ? v16_run(&s, r, &res[det]) : SB_ENOMEM;
    gsl_rng_free(r);
  }
  if (st)
    return st;
  sbv_note(rep, "Transient: %zu particles (100 nm, water, 300 K: D = %.4g "
           "m^2/s, tau_p = %.3g s), slab W = %.4g m between absorbing "
           "walls, dt = 2.5e-4 W^2/D = %.3g s (dt/tau_p = %.2g, one step "
           "moves sqrt(2 D dt) = 0.022 W); window counts vs binomial(N, "
           "P_window), exact test at 1e-4.", N, b.D, b.tau, W, s.dt,
           s.dt / b.tau);
  double plot[6 * 4];
  unsigned long long prev = 0;
  double pprev = 0.0;
  for (size_t k = 0; k < 6 && !st; k++) {
    double t = (double)s.mark[k] * s.dt;
    double P = v16_slab_absorbed(b.D, t, W);
    unsigned long long c = res[0].dep[k] - prev;
    char name[128];
    snprintf(name, sizeof name,
             "V16/deposition/transient/bridge/t=%zudt/window-count", s.mark[k]);
    st = sbv_add_freq(rep, name, c, N, P - pprev);
    /* flux relative to the semi-infinite n sqrt(D/(pi t)) on two walls,
     * averaged over the window: expected 2 sqrt(D/pi)(sqrt t - sqrt t0)
     * W per particle-slab */
    double t0 = k ? (double)s.mark[k - 1] * s.dt : 0.0;
    double semi = 2.0 * 2.0 * sqrt(b.D / PI) * (sqrt(t) - sqrt(t0)) / W;
    plot[4 * k] = t / TW;
    plot[4 * k + 1] = (double)c / (double)N / semi;
    plot[4 * k + 2] = (P - pprev) / semi;
    plot[4 * k + 3] =
        (double)(res[1].dep[k] - (k ? res[1].dep[k - 1] : 0)) / (double)N /
        semi;
    prev = res[0].dep[k];
    pprev = P;
  }
  if (!st) {
    /* chord-only detection at the same step: expected below */
    double P = v16_slab_absorbed(b.D, 32 * s.dt, W);
    unsigned long long c = res[1].dep[5];
    double lo, hi;
    sb_binomial_ci((unsigned long)c, (unsigned long)N, 1.0 - SBV_ALPHA, &lo,
                   &hi);
    st = sbv_add_side(rep, "V16/deposition/transient/chord-only/t=32dt/"
                      "absorbed<ref", 0, (double)c / (double)N, P, lo, hi,
                      1.0 - SBV_ALPHA, NAN);
    sbv_note(rep, "- absorbed by t = 32 dt: bridge %.4f, chord only %.4f, "
             "exact %.4f (semi-infinite 4 sqrt(D t/pi)/W = %.4f)",
             (double)res[0].dep[5] / (double)N, (double)c / (double)N, P,
             4.0 * sqrt(b.D * 32 * s.dt / PI) / W);
  }
  if (!st)
    sbv_plot(ctx, rep, "V16_deposition_transient",
             "V16: deposition flux / n sqrt(D/(pi t)) (two walls)",
             "t_over_W2/D bridge exact chord_only", plot, 6, 4,
             "set logscale x\nset xlabel 't D / W^2'\n"
             "set ylabel 'flux / (n sqrt(D/(pi t)))'\n"
             "plot $DATA u 1:2 w lp t 'bridge', $DATA u 1:3 w l t "
             "'exact (slab)', $DATA u 1:4 w lp t 'chord only', 1 lc rgb "
             "'black' t 'semi-infinite'");
  return st;
}

static int steady(const sbv_ctx *ctx, sbv_report *rep)
{
  brown b;
  brown_init(&b);
  const double Ly = 20e-6, W = Ly - 2.0 * b.r, TW = W * W / b.D;
  const size_t N = ctx->full ? 4000 : 500, R = ctx->full ? 16 : 4;
  v16_setup s;
  setup_slab(&b, Ly, 10.0 * W, N, &s);
  s.deposit = SB_DEPOSIT_REINSERT;
  s.dt = TW / 3000.0;
  /* start in the steady state: each particle's law with reinsertion is
   * stationary from t = 0 when it starts from the steady profile */
  s.parabolic = 1;
  s.steps = ctx->full ? 6000 : 2400;
  double ratio[16];
  /* a deposited particle is reinserted at the end of its step, so a
   * particle's cycle is its absorption time rounded up to the step:
   * mean dt sum_{j>=0} S(j dt) (renewal theorem: rate N / that), which
   * is W^2/(12 D) + dt/2 + O(dt^2); the continuous 12 D N / W^2 is
   * 0.2% higher at this step */
  double cyc = 0.0;
  for (size_t j = 0; j < 10000000; j++) {
    double S = 1.0 - v16_slab_absorbed(b.D, (double)j * s.dt, W);
    cyc += S * s.dt;
    if (S < 1e-17)
      break;
  }
  const double ref = (double)N / cyc;
  const double ref_cont = 12.0 * b.D * (double)N / (W * W);
  int st = SB_SUCCESS;
  unsigned long long tot = 0;
  for (size_t q = 0; q < R && !st; q++) {
    s.seed = ctx->seed * 1000 + 1630 + (unsigned long)q;
    if (sbv_writing(ctx)) {
      /* one file per replica, the deposits of the run in series.csv's
       * one row; the record is their mean */
      char fn[64];
      snprintf(fn, sizeof fn, "V16_deposition_steady_r%zu", q);
      st = v16_write_walls(ctx, rep, &s,
                           sbv_rng_seed(ctx, DEP_STEADY_STREAM + q),
                           s.steps, fn, "V16/deposition: steady source "
                           "(reinsertion), one replica");
      if (!st)
        sbv_ini_expect_mean(rep, "V16/deposition/steady-source/rate/ref",
                            "series.csv 1 deposits",
                            1.0 / ((double)s.steps * s.dt) / ref);
      continue;
    }
    gsl_rng *r = sbv_rng_alloc(ctx, DEP_STEADY_STREAM + q);
    v16_result res;
    st = r ? v16_run(&s, r, &res) : SB_ENOMEM;
    gsl_rng_free(r);
    if (st)
      break;
    ratio[q] = (double)res.ndep / ((double)s.steps * s.dt) / ref;
    tot += res.ndep;
    if (res.n_end != N)
      st = SB_EINVAL;
  }
  if (sbv_writing(ctx))
    return st;
  if (!st)
    st = sbv_add_mean(rep, "V16/deposition/steady-source/rate/ref",
                      ratio, R, 1.0);
  sbv_note(rep, "Steady state with a uniform volume source (reinsertion): "
           "%zu replicas of %zu particles started in the steady profile "
           "c ~ y (W - y), dt = W^2/(3000 D), %.1f W^2/D measured; %llu "
           "depositions; rate against N / (dt sum_j S(j dt)) = %.6g "
           "(12 D N / W^2 = %.6g without the reinsertion delay; Student t "
           "over replicas).", R, N, (double)s.steps / 3000.0, tot, ref,
           ref_cont);
  return st;
}

int v16_case_deposition(const sbv_ctx *ctx, sbv_report *rep)
{
  int st = transient(ctx, rep);
  if (!st)
    st = steady(ctx, rep);
  return st;
}
