/* bench_engine_langevin.c — speed of the Langevin-bridge detector
 * (SB_DETECT_LANGEVIN, docs/engine_langevin.md).
 *
 *  1. Overhead over the Bessel-3 bridge detector (Mohaupt 2011, ch. 5) at
 *     the same dt: wall time per step of the whole engine (transport,
 *     neighbour search, detection; pass-through counting) for Kn_D = 0.5
 *     spheres (d = 100 nm, V12's physics), phi = 1e-4, N = 2e4 (quick:
 *     5e3), at dt/tau_p = 1 and 100.  Goal: langevin / Bessel-3 <= 3.
 *  2. Headline: wall time to the long-time kernel at Kn_D = 0.5 to +-2%
 *     (95%: ~9600 first contacts, V12's first-hit protocol) with
 *     `langevin` at its best dt/tau_p (of 1, 2, 3, 5, 10, 20 and 50)
 *     against contact time at dt/tau_p = 0.01 (the converged reference
 *     of V12), one run on this machine, both on the engine's default
 *     generator (Philox streams), at the volume fraction of section 1,
 *     phi = 1e-4: V12's runs in a box wide enough for that phi (section
 *     5).  The counts do not depend on phi; `langevin`'s cost does (the
 *     pairs near contact per particle-step grow with phi), so the same
 *     runs are also given in V12's own box (phi ~ 2e-3, sized for the
 *     fewest particle-steps, dt/tau_p = 1, 2, 3, 10 and 100).  The
 *     contact-time runs are timed over their first steps and
 *     extrapolated to their length (the cost per step is constant);
 *     --full runs them to the end.  Goal: ratio >= 100 at phi = 1e-4.
 *  3. Threads: wall time per step of the section 1 engine (`langevin`,
 *     the engine's default streams: every record on its own stream, the
 *     first pass and the Langevin search's stencil query on all threads)
 *     on one thread and on all of them, at dt/tau_p = 1, 2 and 100; the
 *     contacts must be the same.
 *  4. Section 2 (b)'s two runs in V12's box (`langevin` at dt = 2 tau_p,
 *     contact time at 0.01 tau_p) on one thread and on all of them, wall time, default
 *     generator: both first-contact observers watch their built-in
 *     detector, whose search and first pass run on the threads.
 *  5. (--density only) The headline at fixed volume fractions phi =
 *     2e-3 (about V12's own box, section 2 (b)), 2e-4, 1e-4,
 *     5e-5 and 2e-5 (--phi X: at X alone): the same runs in wider boxes
 *     (headline_at_phi).  Contact time costs the same per particle-step
 *     at every phi, `langevin` less as the gas thins, so the speed-up
 *     grows and its best dt with it.  Takes ~25 minutes.
 * Options: --quick (smaller N), --full (no extrapolation), --density
 * (section 5 alone), --phi X (section 5 at phi = X alone), --dt Y
 * (with --phi: the langevin run at dt = Y tau_p alone, to profile).
 * Times of sections 1 and 2 are the process's CPU time (one thread:
 * OMP_NUM_THREADS=1), which a loaded machine inflates far less than the
 * wall time; sections 3 and 4 give wall times.
 */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <gsl/gsl_rng.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include <smolbridge/engine.h>
#include <smolbridge/engine_bridge.h>
#include <smolbridge/kernel.h>
#include <smolbridge/langevin.h>
#include <smolbridge/validate.h>

#include "validate/cases.h"
#include "validate/firsthit.h"
#include "validate/v12.h"

#define PI 3.14159265358979323846

static double now(void)
{
  struct timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

static double wall(void)
{
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

/* Seconds per step (CPU time; wall time with threads > 0, that many
 * threads and the engine's default streams) of an engine of N Kn_D = 0.5
 * spheres at dt/tau_p = dtt with detector `bessel` (1) or langevin (0),
 * pass-through; *cand: candidates per particle and step (threads > 0:
 * the contacts). */
static double per_step_on(size_t N, double dtt, int bessel, int threads,
                          double *cand)
{
  v12_phys ph;
  v12_physics(0.5, &ph);
  const double phi = 1e-4;
  const double L = cbrt((double)N * PI * pow(ph.d, 3) / 6.0 / phi);
  sb_engine_params p;
  sb_engine_params_default(&p);
  p.L[0] = p.L[1] = p.L[2] = L;
  p.dt = dtt * ph.tau;
  p.capacity = N;
  p.seed = 7;
  if (!threads) {
    p.rng_type = gsl_rng_taus2;
    p.threads = 1;
  } else
    p.threads = threads;
  p.outcome = SB_OUTCOME_COUNT;
  p.detect = bessel ? SB_DETECT_BALLISTIC : SB_DETECT_LANGEVIN;
  sb_engine *e = sb_engine_alloc(&p);
  double B = sb_brownian_B(ph.temp, ph.m, ph.tau);
  sb_engine_species s = {0.5 * ph.d, ph.m, ph.tau, B, ph.temp};
  sb_engine_bridge *b = NULL;
  if (!e || sb_engine_add_species(e, &s, NULL) ||
      sb_engine_fill_random(e, 0, 0, N))
    goto fail;
  if (bessel) {
    sb_engine_bridge_params bp;
    sb_engine_bridge_params_default(&bp);
    bp.outcome = SB_BRIDGE_OUT_COUNT;
    b = sb_engine_bridge_alloc(&bp);
    if (!b || sb_engine_bridge_attach(e, b))
      goto fail;
  }
  const int warm = 3, steps = dtt >= 100.0 ? 10 : 40;
  for (int k = 0; k < warm; k++)
    if (sb_engine_step(e))
      goto fail;
  sb_engine_reset_counters(e);
  double t0 = threads ? wall() : now();
  for (int k = 0; k < steps; k++)
    if (sb_engine_step(e))
      goto fail;
  double t = ((threads ? wall() : now()) - t0) / steps;
  sb_engine_stats st;
  sb_engine_get_stats(e, &st);
  *cand = threads ? (double)st.ncoll
                  : (double)st.ncand / ((double)steps * (double)N);
  sb_engine_bridge_free(b);
  sb_engine_free(e);
  return t;
fail:
  fprintf(stderr, "bench: %s\n", sb_last_error());
  sb_engine_bridge_free(b);
  sb_engine_free(e);
  return NAN;
}

static double per_step(size_t N, double dtt, int bessel, double *cand)
{
  return per_step_on(N, dtt, bessel, 0, cand);
}

/* Section 2 with V12's pinned generator (taus2, one stream: rng = 0) or
 * the engine's default (Philox streams, rng = 1), the same for both
 * detectors; *ratio = contact time / best langevin. */
static int headline(int rng, int quick, int full, double *ratio)
{
  printf("   %s:\n", rng ? "default generator (Philox streams, "
                             "sb_engine_params_default)"
                           : "V12's generator (taus2, one stream)");
  sb_validate_options opt;
  sb_validate_options_init(&opt);
  sbv_ctx ctx = {0, 12345, NULL, &opt, NULL, NULL};
  v12_phys ph;
  v12_physics(0.5, &ph);
  const double hits = 9600.0;
  double best = INFINITY, bestdt = NAN;
  static const double DTT[5] = {1.0, 2.0, 3.0, 10.0, 100.0};
  for (int k = 0; k < 5; k++) {
    const double dtt = DTT[k];
    lv_run q;
    lv_out o;
    v12_size(&ph, LV_LANGEVIN, dtt, hits, V12_WARM * ph.tau,
             (V12_WARM + 300.0) * ph.tau, 0, &q);
    q.default_rng = rng;
    double t0 = now();
    if (lv_firsthit(&ctx, 9, &q, &o)) {
      fprintf(stderr, "bench: %s\n", sb_last_error());
      return 1;
    }
    double t = now() - t0;
    double K, lo, hi;
    lv_kernel(&q, &o, 0, &K, &lo, &hi);
    printf("   langevin, dt = %5g tau_p: %6.2f s, %lu contacts, N = %zu, "
           "%.0f steps, K/K_GH = %.4f [%.4f, %.4f]\n", dtt, t, o.hits[0],
           q.N[0], o.steps, K / ph.Kgh, lo / ph.Kgh, hi / ph.Kgh);
    free(o.vn);
    if (t < best)
      best = t, bestdt = dtt;
  }
  lv_run q;
  v12_size(&ph, LV_CHORD, 0.01, hits, V12_WARM * ph.tau,
           (V12_WARM + 300.0) * ph.tau, 0, &q);
  q.default_rng = rng;
  const double Tfull = q.T;
  const double frac = full ? 1.0 : (quick ? 0.02 : 0.1);
  if (!full)
    q.T = q.dt * ceil(frac * Tfull / q.dt);
  lv_out o;
  double t0 = now();
  if (lv_firsthit(&ctx, 9, &q, &o)) {
    fprintf(stderr, "bench: %s\n", sb_last_error());
    return 1;
  }
  free(o.vn);
  double tc = (now() - t0) * Tfull / q.T;
  printf("   contact time, dt = 0.01 tau_p: %.1f s%s (N = %zu, %.0f "
         "steps)\n", tc, full ? "" : " (extrapolated from its first steps)",
         q.N[0], Tfull / q.dt);
  printf("   speed-up of langevin (dt = %g tau_p) over contact time: %.0fx\n",
         bestdt, tc / best);
  *ratio = tc / best;
  return 0;
}

/* Section 4: wall seconds of the headline's run with detector det at
 * dt/tau_p = dtt on `threads` threads (default generator), timed over
 * the fraction frac of its steps and extrapolated to its length. */
static double headline_wall(int det, double dtt, int threads, double frac)
{
  sb_validate_options opt;
  sb_validate_options_init(&opt);
  sbv_ctx ctx = {0, 12345, NULL, &opt, NULL, NULL};
  v12_phys ph;
  v12_physics(0.5, &ph);
  lv_run q;
  v12_size(&ph, det, dtt, 9600.0, V12_WARM * ph.tau,
           (V12_WARM + 300.0) * ph.tau, 0, &q);
  q.default_rng = 1;
  q.threads = threads;
  const double Tfull = q.T;
  q.T = q.dt * ceil(frac * Tfull / q.dt);
  lv_out o;
  const double t0 = wall();
  if (lv_firsthit(&ctx, 9, &q, &o)) {
    fprintf(stderr, "bench: %s\n", sb_last_error());
    return NAN;
  }
  free(o.vn);
  return (wall() - t0) * Tfull / q.T;
}

/* Section 5 (--density): the headline at a fixed volume fraction phi.
 * Each run is V12's first-contact run (the same hits, warm-up and length,
 * the default generator) in a box s >= 1 times wider than V12's holding
 * s^(3/2) times the particles: the expected count N^2 K T / (2V) is
 * unchanged and phi falls as s^(-3/2), so s is chosen for the given phi;
 * a step whose protocol box is already more dilute than phi is left out
 * (V12 widens the box with the step's displacement).  Each pair sees the
 * same free space (the box only grows), so every run estimates the same
 * kernel; what phi changes is the number of pairs near contact per
 * particle-step, which the langevin detector pays for and contact time
 * hardly does.  The contact-time run is timed over its first 2% of
 * steps (at least 200) and extrapolated, or to its end with --full. */
static int headline_at_phi(double phi, int full, double only_dt,
                           size_t sort_every, double *ratio)
{
  *ratio = NAN;
  sb_validate_options opt;
  sb_validate_options_init(&opt);
  sbv_ctx ctx = {0, 12345, NULL, &opt, NULL, NULL};
  v12_phys ph;
  v12_physics(0.5, &ph);
  const double vp = PI * pow(ph.d, 3) / 6.0;
  static const double DTT[7] = {1.0, 2.0, 3.0, 5.0, 10.0, 20.0, 50.0};
  double best = INFINITY, bestdt = NAN;
  printf("   phi = %.1e:\n", phi);
  for (int k = 0; k < 8; k++) {
    const int ct = k == 7;  /* the last run: contact time */
    const double dtt = ct ? 0.01 : DTT[k];
    if (only_dt > 0.0 && dtt != only_dt)
      continue;  /* --dt: that langevin run alone (for a profile) */
    lv_run q;
    v12_size(&ph, ct ? LV_CHORD : LV_LANGEVIN, dtt, 9600.0,
             V12_WARM * ph.tau, (V12_WARM + 300.0) * ph.tau, 0, &q);
    q.default_rng = 1;
    q.sort_every = sort_every;
    const double phi0 = (double)q.N[0] * vp / (q.L * q.L * q.L);
    if (phi0 < phi * (1.0 - 1e-9)) {
      printf("     langevin, dt = %4g tau_p: left out (its box holds "
             "phi = %.2e at most)\n", dtt, phi0);
      continue;
    }
    const double s = pow(phi0 / phi, 2.0 / 3.0);
    q.L *= s;
    q.N[0] = (size_t)((double)q.N[0] * pow(s, 1.5));
    const double Tfull = q.T;
    if (ct && !full)
      q.T = q.dt * ceil(fmax(200.0, 0.02 * Tfull / q.dt));
    lv_out o;
    const double t0 = now();
    if (lv_firsthit(&ctx, 9, &q, &o)) {
      fprintf(stderr, "bench: %s\n", sb_last_error());
      return 1;
    }
    const double t = (now() - t0) * Tfull / q.T;
    free(o.vn);
    if (ct) {  /* o.ncand: the candidates of the timed steps */
      printf("     contact time, dt = 0.01 tau_p: %.1f s (N = %zu, %.0f of "
             "%.0f steps, %.0f ns per particle-step, %.0f candidates)\n     "
             "speed-up of langevin (dt = %g tau_p): %.0fx\n", t, q.N[0],
             q.T / q.dt, Tfull / q.dt,
             1e9 * t / ((double)q.N[0] * Tfull / q.dt), o.ncand, bestdt,
             t / best);
      *ratio = t / best;
      break;
    }
    double K, lo, hi;
    lv_kernel(&q, &o, 0, &K, &lo, &hi);
    printf("     langevin, dt = %4g tau_p: %7.2f s (N = %zu, %.0f ns per "
           "particle-step), %lu contacts, K/K_GH = %.4f [%.4f, %.4f]\n",
           dtt, t, q.N[0], 1e9 * t / ((double)q.N[0] * Tfull / q.dt),
           o.hits[0], K / ph.Kgh, lo / ph.Kgh, hi / ph.Kgh);
    if (t < best)
      best = t, bestdt = dtt;
  }
  fflush(stdout);
  return 0;
}

int main(int argc, char **argv)
{
  int quick = 0, full = 0, density = 0;
  double phi_one = 0.0, only_dt = 0.0;
  size_t sort_every = 0;
  for (int k = 1; k < argc; k++) {
    quick |= !strcmp(argv[k], "--quick");
    full |= !strcmp(argv[k], "--full");
    density |= !strcmp(argv[k], "--density");
    if (!strcmp(argv[k], "--phi") && k + 1 < argc) {
      char *end;
      phi_one = strtod(argv[++k], &end);
      if (*end || !(phi_one > 0.0 && phi_one <= 0.01)) {
        fprintf(stderr, "bench: --phi takes a volume fraction in (0, "
                "0.01], not '%s'\n", argv[k]);
        return 2;
      }
      density = 1;
    }
    if (!strcmp(argv[k], "--dt") && k + 1 < argc)
      only_dt = atof(argv[++k]);
    if (!strcmp(argv[k], "--sort") && k + 1 < argc)
      sort_every = (size_t)atol(argv[++k]);
  }
  if (density) {
    printf("5. The headline at fixed volume fractions (V12's runs in "
           "wider boxes, default generator, CPU time, one thread)\n");
    static const double PHI[5] = {2e-3, 2e-4, 1e-4, 5e-5, 2e-5};
    double ratio;
    for (int k = 0; k < 5; k++)
      if ((!phi_one || !k) &&
          headline_at_phi(phi_one ? phi_one : PHI[k], full, only_dt,
                          sort_every, &ratio))
        return 1;
    return 0;
  }
  printf("bench_engine_langevin: Kn_D = 0.5 spheres (d = 100 nm, rho = "
         "1000 kg/m^3, 296.15 K), single thread, CPU time\n\n");
  /* 1. overhead per step */
  const size_t N = quick ? 5000 : 20000;
  printf("1. Engine step, N = %zu, phi = 1e-4, pass-through counting\n", N);
  printf("   %-10s %14s %14s %8s %10s %10s  %s\n", "dt/tau_p", "Bessel-3 us",
         "langevin us", "ratio", "cand B", "cand L", "goal <= 3");
  const double dts[2] = {1.0, 100.0};
  int met = 0;
  for (int k = 0; k < 2; k++) {
    double cb, cl;
    double tb = per_step(N, dts[k], 1, &cb);
    double tl = per_step(N, dts[k], 0, &cl);
    int ok = tl / tb <= 3.0;
    met += ok;
    printf("   %-10g %14.1f %14.1f %8.2f %10.2f %10.2f  %s\n", dts[k],
           1e6 * tb, 1e6 * tl, tl / tb, cb, cl, ok ? "PASS" : "MISS");
  }
  /* 2. headline: at section 1's density, then in V12's own box */
  printf("\n2. Time to the kernel to +-2%% (95%%, ~9600 first contacts), "
         "Kn_D = 0.5, default generator\n   (a) at phi = 1e-4, the "
         "density of section 1 (V12's runs in a wider box, section 5):\n");
  double r_dilute, r_box;
  if (headline_at_phi(1e-4, full, 0.0, 0, &r_dilute))
    return 1;
  printf("   (b) in V12's own box (phi ~ 2e-3, sized for the fewest "
         "particle-steps):\n");
  if (headline(1, quick, full, &r_box))
    return 1;
  int ok = r_dilute >= 100.0;
  met += ok;
  printf("   headline at phi = 1e-4: %.0fx  %s (goal >= 100); in V12's "
         "box: %.0fx\n", r_dilute, ok ? "PASS" : "MISS", r_box);
  /* 3. threads */
#ifdef _OPENMP
  const int nt = omp_get_num_procs();  /* whatever OMP_NUM_THREADS says */
#else
  const int nt = 1;
#endif
  printf("\n3. Threads: wall time per step, langevin, N = %zu, the "
         "engine's streams (1 and %d threads)\n", N, nt);
  /* 2 tau_p: the headline's best step, where the Langevin search runs */
  const double dth[3] = {1.0, 2.0, 100.0};
  for (int k = 0; k < 3; k++) {
    double c1, c2;
    double t1 = per_step_on(N, dth[k], 0, 1, &c1);
    double t2 = per_step_on(N, dth[k], 0, nt, &c2);
    printf("   dt/tau_p = %-5g %10.1f us %10.1f us  speed-up %.2fx  "
           "contacts %.0f / %.0f%s\n", dth[k], 1e6 * t1, 1e6 * t2, t1 / t2,
           c1, c2, c1 == c2 ? "" : "  DIFFER");
  }
  /* 4. the headline on the threads: both runs' first pass and search
   * are parallel (the observed built-ins), the transport too */
  printf("\n4. V12's box on threads: wall time to +-2%%, default "
         "generator, langevin at dt = 2 tau_p, contact time at 0.01 tau_p (%s)\n",
         full ? "run to the end" : "extrapolated from its first steps");
  const double fr = full ? 1.0 : (quick ? 0.02 : 0.1);
  for (int th = 1; th <= nt; th += nt > 1 ? nt - 1 : 1) {
    const double tl = headline_wall(LV_LANGEVIN, 2.0, th, 1.0);
    const double tc = headline_wall(LV_CHORD, 0.01, th, fr);
    printf("   %d thread%s: langevin %6.2f s, contact time %6.1f s, "
           "ratio %.0fx\n", th, th > 1 ? "s" : " ", tl, tc, tc / tl);
  }
  printf("\n%d of 3 goals met\n", met);
  return 0;
}
