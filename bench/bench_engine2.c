/* bench_engine2.c — speed of the diffusive-bridge collision detection
 * (docs/engine_bridge.md).
 *
 *  1. Headline: wall time to estimate the Brownian kernel to +-2% (95%:
 *     ~9600 collisions) for d_p = 0.1 um monodisperse, phi = 1e-4,
 *     N = 1e5 (quick: 2e4): contact-time (ballistic) detection at
 *     dt = tau_p/10 vs the Bessel-3 bridge at dt = 1000 tau_p, one run on
 *     this machine.  The bridge run is timed to the collision count; the
 *     ballistic run is timed over a few hundred steps and extrapolated with
 *     its measured collisions per step (or, if it saw too few, the
 *     theoretical K_th n N dt/2 per step, which V2 shows it reproduces).
 *  2. Particle-steps per second with bridge detection (d = 1 um, phi =
 *     1e-4, dt = 1000 tau_p, correction-step outcome), N = 1e5 and 1e6
 *     (quick: 1e4, 1e5); exact-mode overhead relative to the Bessel
 *     criterion (goal <= 2x).
 */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <gsl/gsl_rng.h>

#include <smolbridge/engine.h>
#include <smolbridge/engine_bridge.h>
#include <smolbridge/langevin.h>

#define PI 3.14159265358979323846

static double now(void)
{
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

/* First-hit counting (as lib/validate/cases_engine2.c): the detector records the
 * first detected contact of every pair and lets the particles pass. */
typedef struct {
  sb_engine_bridge *b;
  uint64_t *set;
  size_t cap, n;
} firsthit;

static int fh_detect(const sb_engine *e, const sb_engine_pair *p,
                     const gsl_rng *r, void *ctx, double *s)
{
  firsthit *f = ctx;
  int h = sb_engine_detect_bridge(e, p, r, f->b, s);
  if (h <= 0)
    return h;
  const uint64_t *id = sb_engine_ids(e);
  uint64_t a = id[p->i], b = id[p->j];
  uint64_t key = ((a < b ? a : b) << 32 | (a < b ? b : a)) + 1;
  if (2 * (f->n + 1) > f->cap)
    return -1;
  for (size_t h2 = (size_t)((key * 0x9E3779B97F4A7C15ULL) >> 17);; h2++) {
    h2 &= f->cap - 1;
    if (f->set[h2] == key)
      break;
    if (!f->set[h2]) {
      f->set[h2] = key;
      f->n++;
      break;
    }
  }
  return 0;
}

static sb_engine *make(size_t n, double d, double ratio, double phi)
{
  const double T = 296.15, mu = 1.83245e-5, rho = 1000.0;
  double tau = sb_stokes_tau(rho, d, mu, 1.0), m = sb_sphere_mass(rho, d);
  sb_engine_params p;
  sb_engine_params_default(&p);
  double L = cbrt((double)n * PI * d * d * d / 6.0 / phi);
  p.L[0] = p.L[1] = p.L[2] = L;
  p.dt = ratio * tau;
  p.capacity = n;
  p.seed = 42;
  p.rng_type = gsl_rng_taus2;
  p.sort_every = 20;
  p.outcome = SB_OUTCOME_REINSERT;
  sb_engine *e = sb_engine_alloc(&p);
  sb_engine_species s = {0.5 * d, m, tau,
                         sqrt(2.0 * SB_BOLTZMANN * T / (m * tau)), T};
  if (!e || sb_engine_add_species(e, &s, NULL) ||
      sb_engine_fill_random(e, 0, 0, n)) {
    sb_engine_free(e);
    return NULL;
  }
  return e;
}

int main(int argc, char **argv)
{
  int quick = argc > 1 && strcmp(argv[1], "--quick") == 0;
  const double Kth = 8.0 * SB_BOLTZMANN * 296.15 / (3.0 * 1.83245e-5);
  const double target = 9604.0;  /* (1.96/0.02)^2 collisions */

  /* ---- 1. headline */
  size_t n = quick ? 20000 : 100000;
  const double d = 0.1e-6, phi = 1e-4;
  sb_engine *eb = make(n, d, 1000.0, phi);
  sb_engine_bridge *b = sb_engine_bridge_alloc(NULL);
  if (!eb || !b || sb_engine_bridge_attach(eb, b))
    return 1;
  double t0 = now();
  sb_engine_stats st;
  do {
    if (sb_engine_step(eb))
      return 1;
    sb_engine_get_stats(eb, &st);
  } while ((double)st.ncoll < target);
  double tb = now() - t0, tb_fh = NAN;
  double Kb;
  sb_engine_kernel(eb, 0.95, &Kb, NULL, NULL);
  printf("headline: d = 0.1 um, phi = 1e-4, N = %zu\n", n);
  printf("  bridge, dt = 1000 tau: %llu collisions in %llu steps, %.2f s "
         "wall, K_e/K_th = %.3f\n", (unsigned long long)st.ncoll,
         (unsigned long long)st.steps, tb, Kb / Kth);
  /* the bridge with first-hit counting (no reinsertion): first contacts
   * up to T estimate K [T + 2R sqrt(T/(pi D))] n(n-1)/(2V) exactly */
  {
    sb_engine *ef = make(n, d, 1000.0, phi);
    sb_engine_bridge_params bp;
    sb_engine_bridge_params_default(&bp);
    bp.outcome = SB_BRIDGE_OUT_COUNT;
    firsthit f = {sb_engine_bridge_alloc(&bp), NULL, (size_t)1 << 16, 0};
    f.set = calloc(f.cap, sizeof *f.set);
    if (!ef || !f.b || !f.set || sb_engine_bridge_attach(ef, f.b) ||
        sb_engine_set_detector(ef, fh_detect, &f,
                               sb_engine_bridge_reach(ef, f.b)))
      return 1;
    t0 = now();
    while ((double)f.n < target)
      if (sb_engine_step(ef))
        return 1;
    double tf = now() - t0;
    const sb_engine_params *pf = sb_engine_get_params(ef);
    double Vf = pf->L[0] * pf->L[1] * pf->L[2], T = sb_engine_time(ef);
    double tau = sb_stokes_tau(1000.0, d, 1.83245e-5, 1.0);
    double m = sb_sphere_mass(1000.0, d);
    double D = 2.0 * SB_BOLTZMANN * 296.15 * tau / m;  /* = B_ij^2/2 */
    double Ke = 2.0 * Vf * (double)f.n /
                ((double)n * (double)(n - 1) * (T + 2 * d * sqrt(T / (PI * D))));
    printf("  bridge, dt = 1000 tau, first-hit counting: %zu first contacts "
           "in %.2f s wall, K_e/K_th = %.3f\n", f.n, tf, Ke / Kth);
    tb_fh = tf;
    free(f.set);
    sb_engine_bridge_free(f.b);
    sb_engine_free(ef);
  }
  sb_engine *ea = make(n, d, 0.1, phi);
  if (!ea)
    return 1;
  const int nsteps = quick ? 100 : 300;
  t0 = now();
  for (int k = 0; k < nsteps; k++)
    if (sb_engine_step(ea))
      return 1;
  double ta = now() - t0;
  sb_engine_get_stats(ea, &st);
  const sb_engine_params *pa = sb_engine_get_params(ea);
  double V = pa->L[0] * pa->L[1] * pa->L[2];
  double per_step_th = Kth * (double)n * (double)(n - 1) / (2.0 * V) * pa->dt;
  double per_step = st.ncoll >= 30 ? (double)st.ncoll / nsteps : per_step_th;
  double ta_full = ta / nsteps * target / per_step;
  printf("  contact time, dt = tau/10: %d steps in %.2f s, %llu collisions "
         "(theory %.3g/step); extrapolated to %.0f collisions: %.3g s "
         "(%.2f h)\n", nsteps, ta, (unsigned long long)st.ncoll,
         per_step_th, target, ta_full, ta_full / 3600.0);
  printf("  speed-up bridge vs contact time: %.3g x with the reinsert "
         "outcome for both (the engine's reinsertion scans all N particles "
         "per collision), %.3g x with first-hit counting for the bridge "
         "(goal >= 1000)\n", ta_full / tb, ta_full / tb_fh);
  sb_engine_free(ea);
  sb_engine_free(eb);
  sb_engine_bridge_free(b);

  /* ---- 2. particle-steps/s, exact-mode overhead */
  size_t ns[2] = {quick ? 10000 : 100000, quick ? 100000 : 1000000};
  for (int k = 0; k < 2; k++) {
    double rate[2];
    for (int mode = 0; mode < 2; mode++) {
      if (k == 1 && mode == 1 && !quick)
        continue;  /* exact mode only at the smaller N in full */
      sb_engine *e = make(ns[k], 1e-6, 1000.0, phi);
      sb_engine_bridge_params bp;
      sb_engine_bridge_params_default(&bp);
      bp.mode = mode ? SB_BRIDGE_EXACT : SB_BRIDGE_BESSEL;
      bp.ends = mode ? SB_BRIDGE_ENDS_DIFFUSIVE : SB_BRIDGE_ENDS_POSITION;
      /* correction step: O(1) per collision (the engine's reinsertion
       * checks all N particles for a free place) */
      bp.outcome = SB_BRIDGE_OUT_CORRECT;
      sb_engine_bridge *bb = sb_engine_bridge_alloc(&bp);
      if (!e || !bb || sb_engine_bridge_attach(e, bb))
        return 1;
      int steps = ns[k] >= 1000000 ? 10 : 50;
      sb_engine_step(e);  /* warm-up */
      t0 = now();
      for (int s = 0; s < steps; s++)
        if (sb_engine_step(e))
          return 1;
      double t = now() - t0;
      rate[mode] = (double)ns[k] * steps / t;
      printf("N = %zu, %s: %.3g particle-steps/s (%.0f ns each)\n", ns[k],
             mode ? "exact" : "Bessel-3", rate[mode], 1e9 / rate[mode]);
      sb_engine_free(e);
      sb_engine_bridge_free(bb);
    }
    if (k == 0 || quick)
      printf("  exact-mode overhead at N = %zu: %.2f x (goal <= 2)\n", ns[k],
             rate[0] / rate[1]);
  }
  return 0;
}
