/* cases_engine2.c — `smolbridge validate` cases of the collision engine II
 * (diffusive-bridge detection; docs/engine_bridge.md).
 *
 *  V4/bridge-brownian   Bessel-3 bridge detection, Brownian spheres
 *                       d = 0.75, 1, 2 um, dt/tau_p = 10, 100, 1000 (Mohaupt
 *                       2011, Tables 5.1-5.2): K_e vs 8 k_B T/(3 mu)
 *  V5/constant-B        pure diffusion with constant B_pos: K_e vs
 *                       4 pi B_pos^2 d for d (and B) varied (Figs 5.5-5.6)
 *  V7/brownian-turb     Brownian + turbulent pair diffusion (Table 6.1):
 *                       K_e vs K_co + K_Saffman-Turner, collision split
 *  V3/diffusive-fail    contact-time and overlap detection in the diffusive
 *                       regime (Figs 3.12-3.13): the bias is shown
 *  V6/correction-step   correction-step outcome (Table 5.3): K_e/K_th
 *  V11/engine-hit-times hit times drawn inside the engine vs the CDF
 *  VX/exact-detection   exact 3-D bridge detection: kernel as V4
 *
 * Kernel design ("first-hit counting").  With the reinsert outcome the
 * measured rate exceeds 8kT/3mu by O(sqrt(phi)) (a reinserted particle has
 * no depletion zone; docs/engine_bridge.md shows it), and from a uniform
 * start the rate has the transient K (1 + R/sqrt(pi D t)).  To test the
 * detector exactly we count, with particles passing through each other,
 * the first detected contact of every pair (a hash set of pair ids): the
 * pairs are then independent two-body problems and the expected number of
 * first contacts up to T is exactly
 *   N(N-1)/(2V) K [T + 2 R sqrt(T/(pi D))],  D = B_ij^2/2, R = r_i + r_j
 * (Smoluchowski's absorbing-sphere flux integrated; the relative
 * displacement stays far below the box).  So
 *   K_e = 2 V N_hit / (N (N-1) [T + 2 R sqrt(T/(pi D))])
 * with the exact Poisson (Garwood) 95% interval shown, and the verdict is
 * PASS iff the exact two-sided Poisson test of N_hit against its expected
 * value gives p >= 1e-3 (add_ratio).
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>

#include <smolbridge/bridge.h>
#include <smolbridge/engine.h>
#include <smolbridge/engine_bridge.h>
#include <smolbridge/kernel.h>
#include <smolbridge/langevin.h>
#include <smolbridge/stats.h>

#include "cases.h"

#define PI 3.14159265358979323846
#define TEMP 296.15          /* K, Table 5.2 */
#define MU_AIR 1.83245e-5    /* Pa s, Table 5.2 */
#define RHO_P 1000.0         /* kg/m^3: rho_p/rho_f = 1000 gives Table 5.1 */

/* ------------------------------------------------ first-hit counting */

typedef struct {
  sb_engine_bridge *b;          /* bridge detector (or NULL: built-in) */
  int builtin;                  /* 0 bridge, 1 contact time, 2 overlap */
  uint64_t *set;                /* open addressing, 0 = empty */
  size_t cap, n;
  size_t n0;                    /* pairs overlapping at the start */
} firsthit;

static int fh_insert(firsthit *f, uint64_t key)
{
  if (2 * (f->n + 1) > f->cap)
    return -1;
  size_t h = (size_t)((key * 0x9E3779B97F4A7C15ULL) >> 17);
  for (;; h++) {
    h &= f->cap - 1;
    if (f->set[h] == key)
      return 0;
    if (!f->set[h]) {
      f->set[h] = key;
      f->n++;
      return 1;
    }
  }
}

/* Wraps a detector: records the pair's first detected contact and
 * returns "no collision", so the particles pass through each other. */
static int fh_detect(const sb_engine *e, const sb_engine_pair *p,
                     const gsl_rng *r, void *ctx, double *s)
{
  firsthit *f = ctx;
  int h;
  if (f->builtin == 3) {
    /* MD-type (Mohaupt 2011, §3.1.2, App. F): straight-line motion with the
     * particle velocities at the step start, x + u dt */
    const double *u0 = sb_engine_start_velocities(e);
    sb_engine_pair q = *p;
    for (int k = 0; k < 3; k++)
      q.dd[k] = (u0[3 * p->i + k] - u0[3 * p->j + k]) * p->dt;
    h = sb_engine_detect_ballistic(&q, s);
  } else if (f->builtin == 1)
    h = sb_engine_detect_ballistic(p, s);
  else if (f->builtin == 2)
    h = sb_engine_detect_overlap(p, s);
  else
    h = sb_engine_detect_bridge(e, p, r, f->b, s);
  if (h <= 0)
    return h;
  const uint64_t *id = sb_engine_ids(e);
  uint64_t a = id[p->i], b = id[p->j];
  if (a > b) {
    uint64_t t = a;
    a = b;
    b = t;
  }
  return fh_insert(f, ((a << 32) | b) + 1) < 0 ? -1 : 0;
}

typedef struct {
  double d;        /* diameter, m */
  double tau;      /* relaxation time, s */
  double b2;       /* per-particle position variance rate B_pos^2, m^2/s */
  double b2brown;  /* its Brownian part (split) */
  double mass;     /* kg */
  double dt;       /* s */
  double L;        /* box edge, m */
  size_t N;
  double T;        /* simulated time, s */
  int builtin;     /* 0 bridge, 1 contact time, 2 overlap */
  sb_bridge_mode mode;
  sb_bridge_ends ends;
} fh_run;

typedef struct {
  unsigned long hits;
  double K, lo, hi;  /* kernel estimate and 95% interval, m^3/s */
  double cpu;        /* s */
  double steps;
} fh_out;

/* Independent uniform positions (overlaps allowed: the particles pass
 * through each other), equilibrium velocities; the pairs overlapping at
 * the start go into the set first (they are not "first contacts"), so
 * every counted pair starts uniform outside the contact ball, as the
 * reference assumes.  (Non-overlapping filling would give the hard-sphere
 * pair correlation g(a) ~ 1 + 2.5 phi, biasing the count at high phi.) */
static int place_uniform(const sbv_ctx *ctx, unsigned long stream,
                         sb_engine *e, const fh_run *q, firsthit *f,
                         double *npout)
{
  gsl_rng *r = sbv_rng_alloc(ctx, 100000 + stream);
  if (!r)
    return SB_ENOMEM;
  const double vsd = sqrt(0.5 * q->b2 / q->tau);  /* B^2 tau/2, B tau = B_pos */
  int st = SB_SUCCESS;
  for (size_t i = 0; i < q->N && !st; i++) {
    double x[3], u[3];
    for (int k = 0; k < 3; k++) {
      x[k] = q->L * gsl_rng_uniform(r);
      u[k] = gsl_ran_gaussian_ziggurat(r, vsd);
    }
    st = sb_engine_add_particle(e, 0, 0, x, u);
  }
  gsl_rng_free(r);
  if (st)
    return st;
  const double *x = sb_engine_positions(e);
  const uint64_t *id = sb_engine_ids(e);
  const double a2 = q->d * q->d;
  size_t nov = 0;
  for (size_t i = 0; i < q->N; i++)
    for (size_t j = i + 1; j < q->N; j++) {
      double d2 = 0.0;
      for (int k = 0; k < 3; k++) {
        double dx = x[3 * i + k] - x[3 * j + k];
        dx -= q->L * floor(dx / q->L + 0.5);
        d2 += dx * dx;
      }
      if (d2 <= a2) {
        uint64_t ai = id[i], bj = id[j];
        if (fh_insert(f, ((ai < bj ? ai : bj) << 32 | (ai < bj ? bj : ai)) +
                             1) < 0)
          return SB_ENOMEM;
        nov++;
      }
    }
  f->n0 = f->n;
  *npout = 0.5 * (double)q->N * (double)(q->N - 1) - (double)nov;
  return SB_SUCCESS;
}

/* Default engine parameters for a cubic box of edge L, step dt and room
 * for N particles, the engine seeded from the independent stream. */
static int cube_params(const sbv_ctx *ctx, unsigned long stream, double L,
                       double dt, size_t N, sb_engine_params *p)
{
  sb_engine_params_default(p);
  p->L[0] = p->L[1] = p->L[2] = L;
  p->dt = dt;
  p->capacity = N;
  gsl_rng *sr = sbv_rng_alloc(ctx, stream);
  if (!sr)
    return SB_ENOMEM;
  p->seed = gsl_rng_get(sr);
  gsl_rng_free(sr);
  p->rng_type = gsl_rng_taus2;
  return SB_SUCCESS;
}

static int run_firsthit(const sbv_ctx *ctx, unsigned long stream,
                        const fh_run *q, fh_out *o)
{
  sb_engine_params p;
  if (cube_params(ctx, stream, q->L, q->dt, q->N, &p))
    return SB_ENOMEM;
  p.outcome = SB_OUTCOME_COUNT;
  sb_engine *e = sb_engine_alloc(&p);
  if (!e)
    return SB_ENOMEM;
  /* Langevin species with B tau = B_pos (diffusive limit for dt >> tau) */
  double Bv = sqrt(q->b2) / q->tau;
  sb_engine_species s = {0.5 * q->d, q->mass, q->tau, Bv, 0.0};
  firsthit f = {NULL, q->builtin, NULL, 0, 0, 0};
  double npout = 0.0;  /* pairs apart at the start */
  size_t cap = 1;
  while (cap < 4 * q->N * 4)
    cap <<= 1;
  cap = cap < (1u << 16) ? (1u << 16) : cap;
  f.set = calloc(cap, sizeof *f.set);
  f.cap = cap;
  sb_engine_bridge_params bp;
  sb_engine_bridge_params_default(&bp);
  bp.mode = q->mode;
  bp.ends = q->ends;
  bp.outcome = SB_BRIDGE_OUT_COUNT;
  f.b = sb_engine_bridge_alloc(&bp);
  int st = (!f.set || !f.b) ? SB_ENOMEM : SB_SUCCESS;
  if (!st)
    st = sb_engine_add_species(e, &s, NULL);
  if (!st)
    st = place_uniform(ctx, stream, e, q, &f, &npout);
  if (!st)
    st = sb_engine_bridge_set_b2(f.b, 0, q->b2, q->b2brown);
  if (!st)
    st = sb_engine_bridge_attach(e, f.b);
  if (!st) {
    /* chords and overlap need no reach; the bridge its tail reach; the
     * velocity chords 7 sd of the relative speed (|u_i - u_j| dt) */
    double reach = q->builtin == 3
                       ? 7.0 * sqrt(2.0 * q->b2 / (2.0 * q->tau)) * q->dt
                       : (q->builtin ? 0.0 : sb_engine_bridge_reach(e, f.b));
    st = sb_engine_set_detector(e, fh_detect, &f, reach);
  }
  clock_t c0 = clock();
  if (!st)
    st = sb_engine_run_until(e, q->T);
  o->cpu = (double)(clock() - c0) / CLOCKS_PER_SEC;
  if (!st) {
    sb_engine_stats es;
    sb_engine_get_stats(e, &es);
    double D = q->b2, R = q->d;  /* D = B_ij^2/2 = b2 */
    double Teff = es.t + 2.0 * R * sqrt(es.t / (PI * D));
    /* each pair apart at the start is uniform on the torus minus the
     * contact ball; the pairs overlapping at the start were put in the
     * set beforehand and are not counted */
    double V = q->L * q->L * q->L, vb = 4.0 * PI * R * R * R / 3.0;
    double scale = (V - vb) / (npout * Teff);
    f.n -= f.n0;
    o->hits = (unsigned long)f.n;
    o->K = scale * (double)f.n;
    o->steps = (double)es.steps;
    st = sb_poisson_rate_ci(o->hits, scale, 0.95, &o->lo, &o->hi);
  }
  sb_engine_bridge_free(f.b);
  free(f.set);
  sb_engine_free(e);
  return st;
}

/* Box edge for about `hits` first contacts of N particles within the
 * effective time Teff, and at least 10 relative displacement standard
 * deviations sqrt(2 b2 T): a pair near contact would need a 5 sd
 * excursion to meet another image (probability < 1e-6). */
static double box_for(double K, size_t N, double Teff, double hits,
                      double b2T)
{
  double L = cbrt(K * (double)N * (double)N * Teff / (2.0 * hits));
  double Lmin = 10.0 * sqrt(2.0 * b2T);
  return L > Lmin ? L : Lmin;
}

/* T + 2 R sqrt(T/(pi D)), D = b2 (see the file comment). */
static double teff(const fh_run *q)
{
  return q->T + 2.0 * q->d * sqrt(q->T / (PI * q->b2));
}

/* Run q with Bessel-3 bridge detection on the positions in a box sized
 * (box_for) for about `hits` first contacts at the kernel Kth. */
static int run_bessel(const sbv_ctx *ctx, unsigned long stream, fh_run *q,
                      double Kth, double hits, fh_out *o)
{
  q->L = box_for(Kth, q->N, teff(q), hits, q->b2 * q->T);
  q->mode = SB_BRIDGE_BESSEL;
  q->ends = SB_BRIDGE_ENDS_POSITION;
  return run_firsthit(ctx, stream, q, o);
}

/* Record a kernel ratio K_e/K_th = scale * hits against 1: exact
 * two-sided Poisson test of the contact count, pass iff p >= ALPHA (the
 * table shows the 95% interval; with dozens of comparisons per run a 95%
 * verdict would fail a correct code often). */
#define ALPHA 1e-3
static int add_ratio(sbv_report *rep, const char *name, double ratio,
                     unsigned long hits)
{
  sb_comparison c;
  double scale = hits > 0 ? ratio / (double)hits : 1.0;
  int st = sb_compare_poisson(&c, name, hits, scale, 1.0, ALPHA);
  return st ? st : sbv_add(rep, &c);
}

/* Brownian sphere of diameter d in air (Tables 5.1-5.2). */
static void brownian(double d, double *tau, double *m, double *b2)
{
  *tau = sb_stokes_tau(RHO_P, d, MU_AIR, 1.0);
  *m = sb_sphere_mass(RHO_P, d);
  *b2 = 2.0 * SB_BOLTZMANN * TEMP * *tau / *m;  /* eq 5.17 */
}

/* A fresh run of Brownian particles of diameter d in air, dt = ratio tau. */
static void brownian_run(fh_run *q, double d, double ratio)
{
  memset(q, 0, sizeof *q);
  q->d = d;
  brownian(q->d, &q->tau, &q->mass, &q->b2);
  q->b2brown = q->b2;
  q->dt = ratio * q->tau;
}

/* ================================================= V4 bridge, Brownian */

static int case_v4(const sbv_ctx *ctx, sbv_report *rep)
{
  const double dps[3] = {0.75e-6, 1e-6, 2e-6};
  const double ratios[3] = {10.0, 100.0, 1000.0};
  const size_t N = ctx->full ? 8000 : 4000;
  const double hits = ctx->full ? 10000 : 1500;
  const size_t nsteps = ctx->full ? 2000 : 300;
  const double Kth = 8.0 * SB_BOLTZMANN * TEMP / (3.0 * MU_AIR);
  sbv_note(rep, "First-hit counting (see the file comment), N = %zu, "
           "%zu steps, box sized for ~%.0f first contacts per run; "
           "Bessel-3 criterion on the positions X (as Mohaupt 2011).  "
           "K_th = "
           "8 k_B T/(3 mu) = %.4g m^3/s (T = 296.15 K, mu = 1.83245e-5 "
           "Pa s, rho_p = 1000).", N, nsteps, hits, Kth);
  int st = SB_SUCCESS;
  double plot[9 * 5];
  for (int a = 0; a < 3 && !st; a++)
    for (int k = 0; k < 3 && !st; k++) {
      fh_run q;
      brownian_run(&q, dps[a], ratios[k]);
      q.N = N;
      q.T = (double)nsteps * q.dt;
      fh_out o;
      st = run_bessel(ctx, 100 + (unsigned long)(3 * a + k), &q, Kth, hits,
                      &o);
      if (st)
        break;
      char name[96];
      snprintf(name, sizeof name, "V4/bridge/d=%.2gum/dt=%gtau/K_e/K_th",
               q.d * 1e6, ratios[k]);
      st = add_ratio(rep, name, o.K / Kth, o.hits);
      double *row = plot + 5 * (3 * a + k);
      row[0] = 3 * a + k + 1;
      row[1] = ratios[k];
      row[2] = o.K / Kth;
      row[3] = o.lo / Kth;
      row[4] = o.hi / Kth;
      sbv_note(rep, "d = %.2g um, dt/tau = %g: %lu first contacts in %.0f "
               "steps, K_e/K_th = %.4f [%.4f, %.4f], %.2f s CPU",
               q.d * 1e6, ratios[k], o.hits, o.steps, o.K / Kth,
               o.lo / Kth, o.hi / Kth, o.cpu);
    }
  if (!st)
    sbv_plot(ctx, rep, "V4_bridge_brownian",
             "V4: K_e/K_th with 95% intervals, Bessel-3 bridge detection "
             "(runs 1-3: d = 0.75 um, 4-6: 1 um, 7-9: 2 um; dt/tau = 10, "
             "100, 1000; cf. Mohaupt 2011, Fig 5.4)",
             "run dt/tau K_e/K_th lo hi", plot, 9, 5,
             "set xlabel 'run'\nset ylabel 'K_e / K_th'\n"
             "set yrange [0.8:1.2]\nset xrange [0:10]\n"
             "plot '$DATA' u 1:3:4:5 w yerrorbars pt 7 t 'K_e/K_th', "
             "1 lw 2 t ''\n");
  return st;
}

/* ======================================================= V5 constant B */

static int case_v5(const sbv_ctx *ctx, sbv_report *rep)
{
  /* Mohaupt 2011, Figs 5.5-5.6: d_ref = 0.1 um; B_pos = 1e-3 m/s^1/2
   * constant, and B_pos proportional to d.  Pure diffusion: a Langevin
   * species with dt/tau = 1e6 and B tau = B_pos.  sigma_X/d = 5 per step. */
  const double dref = 0.1e-6, Bref = 1e-3;
  const double mult[3] = {1.0, 2.0, 4.0};
  const size_t N = ctx->full ? 8000 : 4000;
  const double hits = ctx->full ? 10000 : 1500;
  const size_t nsteps = 20;
  double logK[2][3], logd[3];
  int st = SB_SUCCESS;
  sbv_note(rep, "First-hit counting, N = %zu, 20 steps with sigma_X/d = "
           "B_pos sqrt(dt)/d = 5, dt/tau = 1e6, box sized for ~%.0f first contacts; "
           "K_th = 4 pi B_pos^2 d (sb_kernel_diffusion).", N, hits);
  for (int series = 0; series < 2 && !st; series++)
    for (int k = 0; k < 3 && !st; k++) {
      fh_run q;
      memset(&q, 0, sizeof q);
      q.d = dref * mult[k];
      double B = series == 0 ? Bref : Bref * mult[k];
      q.b2 = q.b2brown = B * B;
      q.dt = 25.0 * q.d * q.d / q.b2;
      q.tau = q.dt * 1e-6;  /* tau |U| ~ 3.5e-3 d: X ~ Y */
      q.mass = sb_sphere_mass(RHO_P, q.d);
      q.N = N;
      q.T = (double)nsteps * q.dt;
      double Kth = sb_kernel_diffusion(0.5 * q.d, 0.5 * q.d, q.b2, q.b2);
      fh_out o;
      st = run_bessel(ctx, 200 + (unsigned long)(3 * series + k), &q, Kth,
                      hits, &o);
      if (st)
        break;
      char name[96];
      snprintf(name, sizeof name, "V5/%s/d=%gd_ref/K_e/K_th",
               series ? "B~d" : "B=1e-3", mult[k]);
      st = add_ratio(rep, name, o.K / Kth, o.hits);
      logK[series][k] = log(o.K);
      logd[k] = log(q.d);
      sbv_note(rep, "%s, d = %g d_ref: %lu contacts, K_e/K_th = %.4f "
               "[%.4f, %.4f]", series ? "B_pos = 1e-3 d/d_ref" :
               "B_pos = 1e-3", mult[k], o.hits, o.K / Kth, o.lo / Kth,
               o.hi / Kth);
    }
  if (!st) {
    for (int series = 0; series < 2; series++) {
      /* least-squares slope of log K_e vs log d: 1 (B fixed), 3 (B ~ d) */
      double mx = 0, my = 0, sxx = 0, sxy = 0;
      for (int k = 0; k < 3; k++) {
        mx += logd[k] / 3;
        my += logK[series][k] / 3;
      }
      for (int k = 0; k < 3; k++) {
        sxx += (logd[k] - mx) * (logd[k] - mx);
        sxy += (logd[k] - mx) * (logK[series][k] - my);
      }
      sbv_note(rep, "log-log slope of K_e vs d: %.3f (expected %d; Mohaupt "
               "2011, Figs 5.5-5.6)", sxy / sxx, series ? 3 : 1);
    }
  }
  return st;
}

/* ============================================ V7 Brownian + turbulent */

static int case_v7(const sbv_ctx *ctx, sbv_report *rep)
{
  /* Table 6.1 and Fig 6.4: hematite d = 1 um, rho_p = 2700, water
   * (rho_f = 1000, nu = 1e-6, mu = 1e-3), eps = 1e-4 m^2/s^3, T = 296.15,
   * dt/tau = 1000.  Per-particle virtual diffusion (eq 6.22): b2 =
   * b2_Brown + B_turb,ij^2(d)/2, so that B_ij^2 = 2 b2_Brown +
   * B_turb,ij^2(d) (eq 6.17). */
  const double d = 1e-6, rho = 2700.0, nu = 1e-6, mu = 1e-3, eps = 1e-4;
  const size_t N = ctx->full ? 6000 : 3000;
  const double hits = ctx->full ? 10000 : 1500;
  fh_run q;
  memset(&q, 0, sizeof q);
  q.d = d;
  q.tau = sb_stokes_tau(rho, d, mu, 1.0);
  q.mass = sb_sphere_mass(rho, d);
  double bb = sb_brownian_b2(0.5 * d, TEMP, mu);
  double bt = sb_turb_pair_b2(d, eps, nu);
  q.b2 = bb + 0.5 * bt;
  q.b2brown = bb;
  q.dt = 1000.0 * q.tau;
  q.N = N;
  q.T = (ctx->full ? 2000.0 : 300.0) * q.dt;
  double Kco = sb_kernel_brownian_co(0.5 * d, 0.5 * d, TEMP, mu);
  double Kst = sb_kernel_saffman_turner(0.5 * d, 0.5 * d, eps, nu);
  double Kth = Kco + Kst;
  /* the split is accumulated by the bridge outcome: run a reinsert run
   * for it after the first-hit kernel */
  fh_out o;
  int st = run_bessel(ctx, 300, &q, Kth, hits, &o);
  if (st)
    return st;
  st = add_ratio(rep, "V7/brownian+turb/K_e/(K_co+K_ST)", o.K / Kth, o.hits);
  sbv_note(rep, "First-hit counting, N = %zu, box sized for the count, %lu contacts: "
           "K_e/(K_co + K_ST) = %.4f [%.4f, %.4f]; K_co = %.4g, K_ST = "
           "%.4g m^3/s.", N, o.hits, o.K / Kth, o.lo / Kth, o.hi / Kth,
           Kco, Kst);
  /* the split as recorded by the engine: a run with the bridge outcome
   * (reinsert), same particles and box */
  sb_engine_bridge_stats bs;
  memset(&bs, 0, sizeof bs);
  {
    sb_engine_params p;
    if (cube_params(ctx, 301, q.L, q.dt, N, &p))
      return SB_ENOMEM;
    sb_engine *e = sb_engine_alloc(&p);
    sb_engine_bridge *b = sb_engine_bridge_alloc(NULL);
    sb_engine_species sp = {0.5 * d, q.mass, q.tau, sqrt(q.b2) / q.tau, 0.0};
    st = (e && b) ? sb_engine_add_species(e, &sp, NULL) : SB_ENOMEM;
    if (!st)
      st = sb_engine_fill_random(e, 0, 0, N);
    if (!st)
      st = sb_engine_bridge_set_b2(b, 0, q.b2, q.b2brown);
    if (!st)
      st = sb_engine_bridge_attach(e, b);
    if (!st)
      st = sb_engine_run_until(e, q.T);
    if (!st)
      sb_engine_bridge_get_stats(b, &bs);
    sb_engine_bridge_free(b);
    sb_engine_free(e);
    if (st)
      return st;
  }
  double fb = 2.0 * bb / (2.0 * bb + bt);
  sbv_note(rep, "Split recorded by the engine (reinsert run, same box and "
           "time): %llu collisions, Brownian %.1f%%, turbulent %.1f%%.",
           (unsigned long long)bs.ncoll,
           bs.ncoll ? 100.0 * bs.coll_brown / (double)bs.ncoll : NAN,
           bs.ncoll ? 100.0 * bs.coll_turb / (double)bs.ncoll : NAN);
  sbv_note(rep, "Collision split (expected share of each mechanism, "
           "proportional to its part of B_ij^2): Brownian %.1f%%, turbulent "
           "%.1f%% (= K_co/(K_co+K_ST) = %.1f%%).  Mohaupt (2011, §6.4) "
           "reports 27%% / 73%% for Table 6.1; with its own eqs 6.5-6.6 and "
           "these parameters the shares are the ones above "
           "(docs/errata.md).", 100 * fb,
           100 * (1 - fb), 100 * Kco / Kth);
  return st;
}

/* ============================================== V3 contact-time, overlap */

static int case_v3(const sbv_ctx *ctx, sbv_report *rep)
{
  const double dps[2] = {0.15e-6, 1e-6};
  const double ratios[3] = {10.0, 100.0, 1000.0};
  const size_t N = ctx->full ? 6000 : 3000;
  const double Kth = 8.0 * SB_BOLTZMANN * TEMP / (3.0 * MU_AIR);
  int st = SB_SUCCESS;
  sbv_note(rep, "First-hit counting with the deterministic detectors: "
           "'MD' (contact time of straight-line motion with the particle "
           "velocities, x + u dt: Mohaupt 2011, §3.1.2, App. F), 'chord' "
           "(contact "
           "time of the actual displacement chords) and 'overlap' (overlap "
           "at step end).  A record PASSES when the bias is shown at 95%%, "
           "i.e. 1 lies outside the interval of K_e/K_th (written [0, lower]"
           " for an overestimate, [upper, inf] for an underestimate); the "
           "chord detector (not one of the thesis' algorithms) and the "
           "overlap detector at dt = 10 tau_p are listed without verdict: "
           "both are close to 1 when sigma_X << d (sigma_X/d ~ 0.04 at "
           "dt = 10 tau_p, d = 1 um).  Mohaupt (2011, §3.3, Fig 3.13) "
           "finds the overlap result acceptable at dt = 100 tau_p for "
           "d = 1 um (sigma_X/d ~ 0.1); that record has a verdict.");
  for (int a = 0; a < 2 && !st; a++)
    for (int k = 0; k < 3 && !st; k++)
      for (int det = 1; det <= 3 && !st; det++) {
        fh_run q;
        brownian_run(&q, dps[a], ratios[k]);
        q.N = det == 3 ? N / 4 : N;
        /* the bridge reference rate sets the duration (~400 contacts) */
        q.T = (det == 3 ? 30.0 : 300.0) * q.dt;
        q.L = box_for(Kth, N, teff(&q), 400.0, q.b2 * q.T);
        q.builtin = det;
        if (det == 3) {  /* the velocity chords must fit in half the box */
          double rv = 7.0 * sqrt(q.b2 / q.tau) * q.dt;
          if (q.L < 3.0 * rv)
            q.L = 3.0 * rv;
        }
        fh_out o;
        st = run_firsthit(ctx, 400 + (unsigned long)(6 * a + 2 * k + det),
                          &q, &o);
        if (st)
          break;
        static const char *dn[4] = {"", "chord", "overlap", "MD"};
        char name[96];
        sb_comparison c;
        int over = o.K > Kth;
        snprintf(name, sizeof name, "V3/%s/d=%.2gum/dt=%gtau: %s", dn[det],
                 q.d * 1e6, ratios[k], over ? "1 < K_e/K_th" : "K_e/K_th < 1");
        /* the thesis' finding reproduced (Mohaupt 2011, §3.3): the 95%
         * interval of K_e/K_th lies entirely above 1 (contact time) or
         * entirely below 1 (overlap) */
        sb_compare_interval(&c, name, o.K / Kth, 1.0, o.lo / Kth,
                            o.hi / Kth);
        c.verdict = (over ? o.lo / Kth > 1.0 : o.hi / Kth < 1.0) ? SB_PASS
                                                                 : SB_FAIL;
        /* chords: not one of the thesis' algorithms; overlap at dt = 10
         * tau: sigma_X << d, a bias of a few % is not resolvable here:
         * notes only.  (The thesis calls the overlap result acceptable at
         * dt = 100 tau, d = 1 um; we resolve a deficit there.) */
        if (det == 3 || (det == 2 && ratios[k] >= 100.0))
          st = sbv_add(rep, &c);
        sbv_note(rep, "%s, d = %.2g um, dt/tau = %g: %lu contacts, "
                 "K_e/K_th = %.4f [%.4f, %.4f]", dn[det], q.d * 1e6,
                 ratios[k], o.hits, o.K / Kth, o.lo / Kth, o.hi / Kth);
      }
  return st;
}

/* ==================================== V6 correction step, V11 hit times */

static double pit_cdf(double u, void *p)
{
  (void)p;
  return u < 0 ? 0 : (u > 1 ? 1 : u);
}

static int case_v6(const sbv_ctx *ctx, sbv_report *rep)
{
  /* Table 5.3-5.4: d = 1 um, B_pos = 1e-2 m/s^1/2, L = 5e-3 m, phi = 1e-10
   * (24 particles), dt/tau_p = 0.1, 1, 5 with tau_p = 3.03 us of the
   * Table 5.1 sphere; pure diffusion of the positions (eq 5.6) with
   * B tau = B_pos, tau_engine = 1e-6 dt. */
  const double d = 1e-6, Bp = 1e-2;
  const double ratios[3] = {0.1, 1.0, 5.0};
  /* The thesis' 24 particles in 5 mm need ~2000 s of simulated time for
   * 5500 collisions (1e10 steps at dt = 0.1 tau_p): we keep d, B_pos and
   * the steps but put N particles in a box sized for `target` collisions
   * in `nmeas` steps after `nwarm` warm-up steps (phi ~ 1e-4). */
  const size_t N = ctx->full ? 4000 : 2000;
  const double target = ctx->full ? 5500 : 800;
  const size_t nwarm = 500, nmeas = ctx->full ? 4000 : 1000;
  double taup, m, b2dummy;
  brownian(d, &taup, &m, &b2dummy);
  const double b2 = Bp * Bp;
  const double Kth = sb_kernel_diffusion(0.5 * d, 0.5 * d, b2, b2);
  int st = SB_SUCCESS;
  sbv_note(rep, "Correction step (Mohaupt 2011, §5.4.3), %zu particles, "
           "B_pos = 1e-2, d = 1 um, K_th = 4 pi B_pos^2 d = %.4g m^3/s; "
           "%zu warm-up steps, then ~%.0f collisions expected in %zu steps; "
           "K_e = 2 N_c V/(N (N-1) t) (sb_engine_kernel).  Hit times of all "
           "detections are tested against the conditioned CDF (probability "
           "integral transform, KS).  Note: elastic spheres have no "
           "depletion zone; if the correction step kept the pair "
           "distribution uniform, counting steps with a contact would give "
           "K_th (1 + 2 d/sqrt(pi B_pos^2 dt)) (listed), which tends to "
           "K_th only for sigma_X >> d.", N, Kth, nwarm, target, nmeas);
  for (int k = 0; k < 3 && !st; k++) {
    const double dt = ratios[k] * taup;
    const double L = cbrt(Kth * (double)N * (double)N * (double)nmeas * dt /
                          (2.0 * target));
    sb_engine_params p;
    if (cube_params(ctx, 500 + (unsigned long)k, L, dt, N, &p))
      return SB_ENOMEM;
    sb_engine *e = sb_engine_alloc(&p);
    if (!e)
      return SB_ENOMEM;
    double tau = p.dt * 1e-6;  /* pure diffusion: tau |U| << d */
    sb_engine_species s = {0.5 * d, m, tau, Bp / tau, 0.0};
    sb_engine_bridge_params bp;
    sb_engine_bridge_params_default(&bp);
    bp.outcome = SB_BRIDGE_OUT_CORRECT;
    bp.record_cap = 20000;
    sb_engine_bridge *b = sb_engine_bridge_alloc(&bp);
    st = b ? sb_engine_add_species(e, &s, NULL) : SB_ENOMEM;
    if (!st)
      st = sb_engine_fill_random(e, 0, 0, N);
    if (!st)
      st = sb_engine_bridge_attach(e, b);
    for (size_t t = 0; t < nwarm && !st; t++)
      st = sb_engine_step(e);
    sb_engine_reset_counters(e);
    sb_engine_bridge_reset(b);
    for (size_t t = 0; t < nmeas && !st; t++)
      st = sb_engine_step(e);
    if (!st) {
      double K, lo, hi;
      sb_engine_kernel(e, 0.95, &K, &lo, &hi);
      sb_engine_bridge_stats bs;
      sb_engine_bridge_get_stats(b, &bs);
      char name[96];
      /* elastic spheres keep a uniform pair distribution (no depletion
       * zone), so counting steps with a contact gives per step up to the
       * uniform-start value K (dt + 2R sqrt(dt/(pi D))), D = b2: the
       * expected K_e/K_th lies in [1, Kunif], not at the thesis' 1 when
       * sigma_X is not >> d.  Verdict: the 95% interval meets [1, Kunif]. */
      double Kunif = 1.0 + 2.0 * d / sqrt(PI * b2 * p.dt);
      snprintf(name, sizeof name,
               "V6/correction/dt=%gtau_p: 1 <= K_e/K_th <= %.3f", ratios[k],
               Kunif);
      sb_comparison cv;
      sb_compare_interval(&cv, name, K / Kth, 1.0, lo / Kth, hi / Kth);
      cv.verdict = (hi / Kth >= 1.0 && lo / Kth <= Kunif) ? SB_PASS : SB_FAIL;
      st = sbv_add(rep, &cv);
      sbv_note(rep, "dt/tau_p = %g (sigma_X/d = %.1f): %llu collisions "
               "(%llu at an overlapping start), K_e/K_th = %.4f [%.4f, "
               "%.4f]; a uniform pair distribution would give %.4f",
               ratios[k], Bp * sqrt(p.dt) / d,
               (unsigned long long)bs.ncoll,
               (unsigned long long)bs.noverlap, K / Kth, lo / Kth,
               hi / Kth, Kunif);
      size_t nh;
      const sb_engine_bridge_hit *h = sb_engine_bridge_hits(b, &nh);
      double *u = malloc((nh ? nh : 1) * sizeof *u);
      if (!u)
        st = SB_ENOMEM;
      size_t nu = 0;
      for (size_t i = 0; i < nh && u; i++)
        u[nu++] = sb_bes3b_hit_cdf(h[i].ta, h[i].x, h[i].y, h[i].a,
                                   h[i].sigma2, h[i].dt);
      if (u && nu > 10) {
        double D, pv;
        if (!sb_ks_test(u, nu, pit_cdf, NULL, &D, &pv)) {
          if (k == 0) {  /* u is sorted now: empirical CDF of the PIT */
            double *pl = malloc(2 * nu * sizeof *pl);
            for (size_t i = 0; pl && i < nu; i++) {
              pl[2 * i] = u[i];
              pl[2 * i + 1] = (i + 1.0) / (double)nu;
            }
            if (pl)
              sbv_plot(ctx, rep, "V11_engine_hit_times",
                       "V11: hit times inside the engine, F(T_a) through "
                       "the conditioned CDF (uniform if exact; cf. Mohaupt "
                       "2011, Figs 5.8-5.9)",
                       "F(T_a) empirical_cdf", pl, nu, 2,
                       "set xlabel 'F(T_a)'\nset ylabel 'empirical CDF'\n"
                       "plot '$DATA' u 1:2 w l lw 2 t 'engine', x t "
                       "'uniform'\n");
            free(pl);
          }
          sb_comparison c;
          snprintf(name, sizeof name, "V11/engine-hit-times/dt=%gtau_p/KS",
                   ratios[k]);
          sb_compare_pvalue(&c, name, D, 0.0, NAN, NAN, pv, 0.001);
          st = sbv_add(rep, &c);
          sbv_note(rep, "  hit times: %zu PIT values, KS D = %.4f, p = "
                   "%.3f", nu, D, pv);
        }
      }
      free(u);
    }
    sb_engine_bridge_free(b);
    sb_engine_free(e);
  }
  return st;
}

/* ==================================================== VX exact mode */

static int case_exact(const sbv_ctx *ctx, sbv_report *rep)
{
  const double ratios[2] = {100.0, 1000.0};
  const size_t N = ctx->full ? 8000 : 4000;
  const double hits = ctx->full ? 10000 : 1500;
  const double Kth = 8.0 * SB_BOLTZMANN * TEMP / (3.0 * MU_AIR);
  int st = SB_SUCCESS;
  sbv_note(rep, "Exact endpoint-conditioned 3-D bridge detection "
           "(sb_bb3_hit_sample, tol 1e-3), diffusive end points, first-hit "
           "counting as V4, d = 1 um.");
  for (int k = 0; k < 2 && !st; k++) {
    fh_run q;
    brownian_run(&q, 1e-6, ratios[k]);
    q.N = N;
    q.T = 300.0 * q.dt;
    q.L = box_for(Kth, N, teff(&q), hits, q.b2 * q.T);
    q.mode = SB_BRIDGE_EXACT;
    q.ends = SB_BRIDGE_ENDS_DIFFUSIVE;
    fh_out o;
    st = run_firsthit(ctx, 600 + (unsigned long)k, &q, &o);
    if (st)
      break;
    char name[96];
    snprintf(name, sizeof name, "VX/exact/d=1um/dt=%gtau/K_e/K_th",
             ratios[k]);
    st = add_ratio(rep, name, o.K / Kth, o.hits);
    sbv_note(rep, "dt/tau = %g: %lu contacts, K_e/K_th = %.4f [%.4f, "
             "%.4f], %.2f s CPU", ratios[k], o.hits, o.K / Kth, o.lo / Kth,
             o.hi / Kth, o.cpu);
  }
  return st;
}

const sbv_case sbv_cases_engine2[] = {
    {"V4/bridge-brownian",
     "Bessel-3 bridge detection, Brownian, d = 0.75-2 um, dt/tau = 10-1000 "
     "(Mohaupt 2011, Tables 5.1-5.2)",
     case_v4},
    {"V5/constant-B",
     "constant-B diffusion: K = 4 pi B^2 d (Mohaupt 2011, Figs 5.5-5.6)",
     case_v5},
    {"V7/brownian-turb",
     "Brownian + turbulent pair diffusion (Mohaupt 2011, Table 6.1)",
     case_v7},
    {"V3/diffusive-fail",
     "contact-time and overlap detection fail in the diffusive regime "
     "(Mohaupt 2011, Figs 3.12-3.13)",
     case_v3},
    {"V6/correction-step",
     "correction step (Mohaupt 2011, Table 5.3) and hit times",
     case_v6},
    {"VX/exact-detection", "exact 3-D bridge detection: kernel", case_exact},
};
const size_t sbv_ncases_engine2 =
    sizeof sbv_cases_engine2 / sizeof sbv_cases_engine2[0];
