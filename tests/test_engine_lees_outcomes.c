#define _POSIX_C_SOURCE 200809L
/* test_engine_lees_outcomes.c — outcomes that change a path (elastic,
 * merge, reinsert) across the Lees-Edwards sliding boundary
 * (lib/engine/engine_lees.c, engine_detect.c, engine_neigh.c,
 * engine_outcome.c, engine_merge.c; docs/engine_forces.md §3).
 *
 * Independent checks: a collision across the boundary against the same
 * collision placed inside the box and seen in the sheared frame (the
 * frame moving with the fluid at the box centre, where the image of the
 * partner is an ordinary particle): shifting by -L_y/2 along y subtracts
 * G L_y/2 from every x velocity, and the image's velocity is its
 * particle's plus G L_y; and the orthokinetic kernel of Smoluchowski
 * (1917), K = (4/3) G (r_i + r_j)^3, of tracers with the reinsert
 * outcome, for all contacts and for the contacts found by the
 * re-detection of a particle reinserted earlier in the same step.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_rng.h>

#include <smolbridge/engine.h>
#include <smolbridge/kernel.h>
#include <smolbridge/stats.h>

#include "engine/engine_internal.h"
#include "testutil.h"

/* Cube of edge L with the shear U_x = G (y - L/2) and Lees-Edwards images
 * shifted by delta at the start. */
static sb_engine *le_engine(double L, double dt, double G, double delta,
                            sb_engine_detect det, sb_engine_outcome out,
                            size_t cap, unsigned long seed)
{
  sb_engine_params p;
  sb_engine_params_default(&p);
  p.L[0] = p.L[1] = p.L[2] = L;
  p.dt = dt;
  p.capacity = cap;
  p.seed = seed;
  p.detect = det;
  p.outcome = out;
  sb_engine *e = sb_engine_alloc(&p);
  ck_assert_ptr_nonnull(e);
  const double Gp[3] = {G, 0.0, 0.0};
  ck_assert_int_eq(sb_engine_set_fluid(e, SB_FLUID_SHEAR, Gp), 0);
  ck_assert_int_eq(sb_engine_set_lees_edwards(e, 1), 0);
  e->le_off = delta;  /* as after some time of shearing */
  return e;
}

/* ------------------------------------------------ deterministic */

#define LBOX 20.0
#define GS 0.1
#define DELTA 3.3

/* A particle of the across-boundary set-up: position and velocity in the
 * box (across) or its image brought into the box's middle (inside).
 * lift = 1 for a particle whose image above the box takes part (at
 * y + L, x + delta, u_x + G L), 0 for one already near the top. */
typedef struct {
  double x[3], u[3];
  int lift;
} body;

static void place(sb_engine *e, size_t sp, const body *b, int inside)
{
  double x[3], u[3];
  memcpy(x, b->x, sizeof x);
  memcpy(u, b->u, sizeof u);
  if (inside) {
    /* into the frame of the box's centre: y - L/2, u_x - G L/2; the
     * image above the box first (y + L, x + delta, u_x + G L) */
    if (b->lift) {
      x[0] += DELTA;
      x[1] += LBOX;
      u[0] += GS * LBOX;
    }
    x[1] -= 0.5 * LBOX;
    u[0] -= 0.5 * GS * LBOX;
  }
  ck_assert_int_eq(sb_engine_add_particle(e, sp, 0, x, u), 0);
}

/* Velocity of body k after the run, in the centre frame (what the inside
 * run gives directly). */
static void centre_velocity(const sb_engine *e, size_t k, const body *b,
                            int inside, double u[3])
{
  memcpy(u, &sb_engine_velocities(e)[3 * k], 3 * sizeof(double));
  if (!inside)
    u[0] += (b->lift ? GS * LBOX : 0.0) - 0.5 * GS * LBOX;
}

/* End velocities of nb bodies across the boundary (a) and inside (b)
 * agree: to rounding with the chord detector (d = 0), to the contact
 * resolution of the Langevin one (xtol = 1e-6 of the contact distance). */
static void same_velocities(int d, int nb, double a[][3], double b[][3])
{
  const double tol = d ? 1e-5 : 1e-12;
  for (int k = 0; k < nb; k++)
    for (int c = 0; c < 3; c++)
      ck_assert_msg(fabs(a[k][c] - b[k][c]) < tol,
                    "detector %d particle %d u[%d]: across %.15g, "
                    "inside %.15g", d, k, c, a[k][c], b[k][c]);
}

/* (T only sets the velocities of random placement, not used here) */
static const sb_engine_species free_a = {0.4, 1.0, INFINITY, 0.0, 1.0};
static const sb_engine_species free_b = {0.4, 3.0, INFINITY, 0.0, 1.0};

/* Two free-flight spheres (masses 1 and 3) meet across the sliding
 * boundary: a near the top, b's image above it.  Their velocities after
 * the elastic bounce (restitution 0.6) equal, in the centre frame, those
 * of the same pair placed inside the box; chord and Langevin contacts. */
START_TEST(test_le_elastic_pair)
{
  const body bd[2] = {
      {{10.0, 19.3, 10.0}, {0.93, 0.8, 0.05}, 0},
      {{10.0 - DELTA + 0.25, 0.35, 10.1}, {-0.965, -0.3, 0.0}, 1}};
  const sb_engine_detect det[2] = {SB_DETECT_BALLISTIC, SB_DETECT_LANGEVIN};
  for (int d = 0; d < 2; d++) {
    double uf[2][2][3];
    for (int inside = 0; inside < 2; inside++) {
      sb_engine *e = le_engine(LBOX, 0.05, GS, inside ? 0.0 : DELTA, det[d],
                               SB_OUTCOME_ELASTIC, 4, 1);
      ck_assert_int_eq(sb_engine_set_outcome(e, SB_OUTCOME_ELASTIC, 0.36),
                       0);
      sb_engine_add_species(e, &free_a, NULL);
      sb_engine_add_species(e, &free_b, NULL);
      place(e, 0, &bd[0], inside);
      place(e, 1, &bd[1], inside);
      double p0[3];
      sb_engine_kinetic_energy(e, p0);
      for (int s = 0; s < 10; s++)
        ck_assert_int_eq(sb_engine_step(e), 0);
      sb_engine_stats st;
      sb_engine_get_stats(e, &st);
      ck_assert_uint_eq(st.ncoll, 1);
      for (int k = 0; k < 2; k++)
        centre_velocity(e, (size_t)k, &bd[k], inside, uf[inside][k]);
      sb_engine_free(e);
    }
    /* the bounce changed the velocities ... */
    ck_assert(fabs(uf[0][0][1] - bd[0].u[1]) > 0.1);
    /* ... as inside the box */
    same_velocities(d, 2, uf[0], uf[1]);
  }
}
END_TEST

/* Three equal free-flight spheres in one step: c (below a) hits a, which
 * then hits b's image across the boundary later in the same step, found
 * by the re-detection after the first bounce; b leaves upwards.  The end
 * velocities equal those of the same chain inside the box. */
START_TEST(test_le_redetect_chain)
{
  const body bd[3] = {
      {{10.0, 18.5, 10.0}, {0.85, 0.0, 0.0}, 0},                 /* a */
      {{10.1 - DELTA, 0.5, 10.05}, {-0.95, 0.0, 0.0}, 1},        /* b */
      {{9.9, 17.0, 9.95}, {0.70, 4.0, 0.0}, 0}};                 /* c */
  const sb_engine_detect det[2] = {SB_DETECT_BALLISTIC, SB_DETECT_LANGEVIN};
  for (int d = 0; d < 2; d++) {
    double uf[2][3][3];
    uint64_t nre = 0;
    for (int inside = 0; inside < 2; inside++) {
      sb_engine *e = le_engine(LBOX, 0.5, GS, inside ? 0.0 : DELTA, det[d],
                               SB_OUTCOME_ELASTIC, 4, 1);
      sb_engine_add_species(e, &free_a, NULL);
      for (int k = 0; k < 3; k++)
        place(e, 0, &bd[k], inside);
      ck_assert_int_eq(sb_engine_step(e), 0);
      sb_engine_stats st;
      sb_engine_get_stats(e, &st);
      ck_assert_msg(st.ncoll == 2, "detector %d %s: %llu collisions", d,
                    inside ? "inside" : "across",
                    (unsigned long long)st.ncoll);
      if (!inside)
        nre = st.redetected;
      for (int k = 0; k < 3; k++)
        centre_velocity(e, (size_t)k, &bd[k], inside, uf[inside][k]);
      sb_engine_free(e);
    }
    ck_assert(nre > 0);
    ck_assert(uf[0][1][1] > 1.0);  /* b was hit */
    same_velocities(d, 3, uf[0], uf[1]);
  }
}
END_TEST

/* The Langevin detector's exact shear bridge across the sliding
 * boundary: a Brownian pair (tau = 1, k_B T = 1, dt = tau, G dt = 0.1)
 * whose partner is an image above the box has the contact law of the
 * same pair inside the box (the image sees the field continued linearly:
 * its drift is its particle's).  A custom detector calls
 * sb_engine_langevin_contact 4000 times for the step's pair.  Both runs
 * draw from the same generator (seed, and keyed transport), and the
 * sampler's inputs agree to rounding, so the hit counts (~45%) agree
 * draw for draw: they may differ by at most 10 (a decision flipped by
 * rounding, a chance of ~1e-10).  Broken on purpose: without the image's
 * velocity offset in the fluid velocity the sampler receives, the counts
 * differ by 64. */
typedef struct {
  long hits, calls;
} le_count;

static int le_count_contacts(const sb_engine *e, const sb_engine_pair *p,
                             const gsl_rng *r, void *vctx, double *s)
{
  le_count *c = vctx;
  for (int k = 0; k < 4000; k++) {
    double f;
    const int h = sb_engine_langevin_contact(e, p, r, &f, NULL);
    ck_assert_int_ge(h, 0);
    c->hits += h;
    c->calls++;
  }
  *s = 0.0;
  return 0;
}

START_TEST(test_le_langevin_shear_law)
{
  const body bd[2] = {
      {{10.0, 19.3, 10.0}, {0.9, 0.8, 0.05}, 0},
      {{10.0 - DELTA + 0.3, 0.5, 10.1}, {-0.9, -0.3, 0.0}, 1}};
  const sb_engine_species brown = {0.4, 1.0, 1.0, sqrt(2.0), 1.0 /
                                                                 SB_BOLTZMANN};
  le_count cnt[2] = {{0, 0}, {0, 0}};
  for (int inside = 0; inside < 2; inside++) {
    sb_engine *e = le_engine(LBOX, 1.0, GS, inside ? 0.0 : DELTA,
                             SB_DETECT_BALLISTIC, SB_OUTCOME_COUNT, 4, 1);
    ck_assert_int_eq(sb_engine_set_detector(e, le_count_contacts,
                                            &cnt[inside], 1), 0);
    sb_engine_add_species(e, &brown, NULL);
    place(e, 0, &bd[0], inside);
    place(e, 0, &bd[1], inside);
    ck_assert_msg(sb_engine_step(e) == 0, "%s", sb_last_error());
    sb_engine_free(e);
  }
  ck_assert(cnt[0].calls == 4000 && cnt[1].calls == 4000);
  printf("langevin shear across / inside the box: %ld / %ld hits of 4000\n",
         cnt[0].hits, cnt[1].hits);
  ck_assert_msg(cnt[0].hits > 200 && cnt[0].hits < 3800, "%ld hits",
                cnt[0].hits);
  ck_assert_msg(labs(cnt[0].hits - cnt[1].hits) <= 10,
                "across %ld, inside %ld", cnt[0].hits, cnt[1].hits);
}
END_TEST

/* Stokes spheres without noise (B = 0, tau = 1) in the shear: the
 * Langevin detector follows each path in the linear field, G (y(t) -
 * L/2) along it, as the transport does (engine_lees.c).  The contact
 * time of a pair closing along y (dt = tau), inside the box and across
 * the sliding boundary, against a Runge-Kutta integration of both
 * equations of motion in the centre frame (256 steps and bisection):
 * within 2e-6 tau (the leaf resolution, 1e-6 of the contact distance,
 * over an approach speed ~1: 5e-7 measured).  With the field frozen at
 * each path's start (the uniform-flow path, as before) the contact comes
 * at 0.7144 instead of 0.7022. */
typedef struct {
  double s;
  int hits;
} le_first;

static int le_first_contact(const sb_engine *e, const sb_engine_pair *p,
                            const gsl_rng *r, void *vctx, double *s)
{
  le_first *c = vctx;
  const int h = sb_engine_langevin_contact(e, p, r, s, NULL);
  ck_assert_int_ge(h, 0);
  if (h) {
    c->s = *s;
    c->hits++;
  }
  return h;
}

/* Both bodies (centre frame: fluid G y) moved by classical Runge-Kutta
 * over t; y[6 k + (x, y, z, u_x, u_y, u_z)]. */
static void le_rk4(double *y, double t, double tau)
{
  const int n = 256;
  const double k = t / n;
  for (int s = 0; s < n; s++) {
    double d[4][12], z[12];
    for (int q = 0; q < 4; q++) {
      const double f = q == 0 ? 0.0 : (q == 3 ? 1.0 : 0.5);
      for (int i = 0; i < 12; i++)
        z[i] = y[i] + (q ? f * k * d[q - 1][i] : 0.0);
      for (int b = 0; b < 2; b++) {
        const double *w = z + 6 * b;
        double *o = d[q] + 6 * b;
        o[0] = w[3], o[1] = w[4], o[2] = w[5];
        o[3] = (GS * w[1] - w[3]) / tau;
        o[4] = -w[4] / tau;
        o[5] = -w[5] / tau;
      }
    }
    for (int i = 0; i < 12; i++)
      y[i] += k / 6.0 * (d[0][i] + 2.0 * d[1][i] + 2.0 * d[2][i] + d[3][i]);
  }
}

static double le_gap(const double *y0, double t, double tau)
{
  double y[12];
  memcpy(y, y0, sizeof y);
  le_rk4(y, t, tau);
  double r2 = 0.0;
  for (int c = 0; c < 3; c++)
    r2 += (y[c] - y[6 + c]) * (y[c] - y[6 + c]);
  return sqrt(r2) - 0.8;
}

START_TEST(test_le_langevin_no_noise)
{
  /* at rest along x in the centre frame, closing along y */
  const body bd[2] = {{{10.0, 19.0, 10.0}, {1.0, 1.5, 0.0}, 0},
                      {{10.6 - DELTA, 1.0, 10.1}, {-1.0, -1.5, 0.0}, 1}};
  const sb_engine_species stokes = {0.4, 1.0, 1.0, 0.0, 1.0};
  /* the reference, in the centre frame (place(inside) by hand) */
  double y0[12];
  for (int b = 0; b < 2; b++) {
    for (int c = 0; c < 3; c++) {
      y0[6 * b + c] = bd[b].x[c];
      y0[6 * b + 3 + c] = bd[b].u[c];
    }
    if (bd[b].lift) {
      y0[6 * b] += DELTA;
      y0[6 * b + 1] += LBOX;
      y0[6 * b + 3] += GS * LBOX;
    }
    y0[6 * b + 1] -= 0.5 * LBOX;
    y0[6 * b + 3] -= 0.5 * GS * LBOX;
  }
  double lo = 0.0, hi = 0.0;  /* the first sign change on a 1/100 grid */
  ck_assert(le_gap(y0, 0.0, 1.0) > 0.0);
  while (hi < 1.0 && le_gap(y0, hi + 0.01, 1.0) > 0.0)
    hi += 0.01;
  ck_assert(hi < 1.0);
  lo = hi;
  hi += 0.01;
  for (int it = 0; it < 60; it++) {
    const double m = 0.5 * (lo + hi);
    if (le_gap(y0, m, 1.0) > 0.0)
      lo = m;
    else
      hi = m;
  }
  for (int inside = 0; inside < 2; inside++) {
    le_first c = {NAN, 0};
    sb_engine *e = le_engine(LBOX, 1.0, GS, inside ? 0.0 : DELTA,
                             SB_DETECT_BALLISTIC, SB_OUTCOME_COUNT, 4, 1);
    ck_assert_int_eq(sb_engine_set_detector(e, le_first_contact, &c, 1), 0);
    sb_engine_add_species(e, &stokes, NULL);
    place(e, 0, &bd[0], inside);
    place(e, 0, &bd[1], inside);
    ck_assert_msg(sb_engine_step(e) == 0, "%s", sb_last_error());
    sb_engine_free(e);
    printf("Stokes pair without noise in the shear, %s: contact at %.9f "
           "(Runge-Kutta %.9f)\n", inside ? "inside" : "across",
           c.s, hi);
    ck_assert_int_eq(c.hits, 1);
    ck_assert_msg(fabs(c.s - hi) < 2e-6, "%s: %.9f against %.9f",
                  inside ? "inside" : "across", c.s, hi);
  }
}
END_TEST

/* Two free-flight primaries merge across the boundary: one cluster of
 * twice the mass whose momentum is the pair's in the frame of a (b's
 * image velocity), as inside the box; chord and Langevin contacts. */
START_TEST(test_le_merge_pair)
{
  const body bd[2] = {
      {{10.0, 19.0, 10.0}, {0.9, 0.6, 0.05}, 0},
      {{10.0 - DELTA + 0.3, 0.3, 10.1}, {-0.97, -0.2, 0.0}, 1}};
  const sb_engine_detect det[2] = {SB_DETECT_BALLISTIC, SB_DETECT_LANGEVIN};
  for (int d = 0; d < 2; d++) {
    double uf[2][3], mf[2];
    for (int inside = 0; inside < 2; inside++) {
      sb_engine *e = le_engine(LBOX, 0.05, GS, inside ? 0.0 : DELTA, det[d],
                               SB_OUTCOME_ELASTIC, 4, 1);
      sb_engine_add_species(e, &free_a, NULL);
      place(e, 0, &bd[0], inside);
      place(e, 0, &bd[1], inside);
      sb_agglo_params ap;
      sb_agglo_params_default(&ap);
      ap.growth = SB_AGGLO_CONSTANT;
      sb_agglo *a = sb_agglo_alloc(&ap);
      ck_assert_ptr_nonnull(a);
      ck_assert_int_eq(sb_agglo_attach(e, a), 0);
      for (int s = 0; s < 20; s++)
        ck_assert_int_eq(sb_engine_step(e), 0);
      ck_assert_uint_eq(sb_engine_count(e), 1);
      double m[3];
      sb_agglo_moments(a, e, m);
      ck_assert(m[1] == 2.0);  /* primaries conserved */
      mf[inside] = sb_engine_masses(e)[0];
      body cl = bd[0];  /* the cluster stays in a's frame */
      centre_velocity(e, 0, &cl, inside, uf[inside]);
      sb_agglo_free(a);
      sb_engine_free(e);
    }
    ck_assert(mf[0] == 2.0 && mf[1] == 2.0);
    /* momentum of the pair in the centre frame, (u_a + u_b') / 2 */
    for (int c = 0; c < 3; c++) {
      double ua = bd[0].u[c] - (c == 0 ? 0.5 * GS * LBOX : 0.0);
      double ub = bd[1].u[c] + (c == 0 ? 0.5 * GS * LBOX : 0.0);
      ck_assert_msg(fabs(uf[0][c] - 0.5 * (ua + ub)) < 1e-12,
                    "detector %d u[%d] across %.15g, pair %.15g", d, c,
                    uf[0][c], 0.5 * (ua + ub));
      ck_assert(fabs(uf[0][c] - uf[1][c]) < 1e-12);
    }
  }
}
END_TEST

/* ------------------------------------------------ Monte Carlo */

/* A reinsert outcome whose reinserted particle is independent of all the
 * others: moved to a uniform point of the box (overlaps allowed) with the
 * fluid velocity there, on which it flows for the rest of the step.  The
 * others around it then have the uniform density n exactly, so its
 * contacts over the rest of the step -- found only by the re-detection,
 * across the sliding boundary as inside -- form a Poisson process of rate
 * K (N - 1)/V: the kernel K_th = (4/3) G (r_i + r_j)^3 with exposure
 * sum (N - 1)(1 - t) dt over the reinsertions (t the step fraction).
 * (The engine's reinsert outcome avoids overlaps: its contact density
 * is then n g(sigma) with g(sigma) - 1 = O(phi).) */
typedef struct {
  double G;
  uint64_t step;       /* steps taken when the marks were set */
  unsigned char *mark; /* by id: reinserted in this step */
  size_t nmark;
  uint64_t nfresh;     /* contacts with a marked partner */
  double expo;         /* sum (N - 1)(1 - t) dt */
} fresh_ctx;

static int fresh_outcome(sb_engine *e, const sb_engine_pair *p, double s,
                         void *vc)
{
  fresh_ctx *f = vc;
  const sb_engine_params *par = sb_engine_get_params(e);
  sb_engine_stats st;
  sb_engine_get_stats(e, &st);
  const uint64_t *id = sb_engine_ids(e);
  if (st.steps != f->step) {
    memset(f->mark, 0, f->nmark);
    f->step = st.steps;
  }
  if (f->mark[id[p->i]] || f->mark[id[p->j]])
    f->nfresh++;
  const double dt = par->dt;
  const double tf = (p->t0 + s * p->dt - sb_engine_time(e)) / dt;
  const double rest = (1.0 - tf) * dt;
  f->expo += (double)(sb_engine_count(e) - 1) * rest;
  gsl_rng *r = sb_engine_rng(e);
  double x[3];
  for (int k = 0; k < 3; k++)
    x[k] = par->L[k] * gsl_rng_uniform(r);
  const double ux = f->G * (x[1] - 0.5 * par->L[1]);
  ck_assert_int_eq(sb_engine_outcome_path(e, p->j, x), 0);
  const size_t j = p->j;
  for (int k = 0; k < 3; k++) {
    e->u[3 * j + k] = k == 0 ? ux : 0.0;
    e->x[3 * j + k] = x[k] + (k == 0 ? ux * rest : 0.0);
  }
  f->mark[id[j]] = 1;
  return SB_SUCCESS;
}

/* Contact-time detection of pairs not overlapping at the record's start
 * (the pass-through rule of the count outcome: a reinserted particle may
 * land on another). */
static int det_nonoverlap(const sb_engine *e, const sb_engine_pair *p,
                          const gsl_rng *r, void *ctx, double *s)
{
  (void)e, (void)r, (void)ctx;
  const double *d = p->dx0;
  if (d[0] * d[0] + d[1] * d[1] + d[2] * d[2] <
      p->sigma * p->sigma * (1.0 - SB_ENGINE_TOUCH))
    return 0;
  return sb_engine_detect_ballistic(p, s);
}

/* Tracers (tau_p = 1e-7 s << 1/G, B = 0) of radius 0.5 m at volume
 * fraction 0.05 in a box 40 x 16 x 40 m, G = 1/s, dt = 0.2 s (relative x
 * displacement across the box 3.2 m per step), seed 7, 400 steps: 174
 * contacts of a particle reinserted earlier in the same step.  Their
 * kernel is (4/3) G (2r)^3 within its exact 95% Poisson interval
 * (measured 1.034 K_th; with a plain minimum-image re-detection 3.07
 * K_th). */
START_TEST(test_le_reinsert_kernel)
{
  sb_engine_params p;
  sb_engine_params_default(&p);
  p.L[0] = 40.0;
  p.L[1] = 16.0;
  p.L[2] = 40.0;
  p.dt = 0.2;
  p.seed = 7;
  const double r = 0.5, G = 1.0, phi = 0.05;
  const double V = p.L[0] * p.L[1] * p.L[2];
  const size_t n =
      (size_t)(phi * V / (4.0 / 3.0 * 3.14159265358979323846 * r * r * r));
  p.capacity = n + 1;
  p.outcome = SB_OUTCOME_COUNT;
  sb_engine *e = sb_engine_alloc(&p);
  ck_assert_ptr_nonnull(e);
  const double Gp[3] = {G, 0.0, 0.0};
  sb_engine_set_fluid(e, SB_FLUID_SHEAR, Gp);
  ck_assert_int_eq(sb_engine_set_lees_edwards(e, 1), 0);
  const sb_engine_species sp = {r, 1.0, 1e-7, 0.0, 0.0};
  sb_engine_add_species(e, &sp, NULL);
  ck_assert_int_eq(sb_engine_fill_random(e, 0, 0, n), 0);
  fresh_ctx f = {G, (uint64_t)-1, calloc(n + 2, 1), n + 2, 0, 0.0};
  ck_assert_ptr_nonnull(f.mark);
  ck_assert_int_eq(sb_engine_set_detector(e, det_nonoverlap, NULL, 0.0), 0);
  ck_assert_int_eq(sb_engine_set_redetect(e, 1), 0);
  ck_assert_int_eq(sb_engine_set_outcome_fn(e, fresh_outcome, &f), 0);
  for (int s = 0; s < 400; s++)
    ck_assert_int_eq(sb_engine_step(e), 0);
  const double Kth = sb_kernel_shear(r, r, G);
  double lo, hi;
  ck_assert_int_eq(sb_poisson_rate_ci((unsigned long)f.nfresh, V / f.expo,
                                      0.95, &lo, &hi), 0);
  const double K = (double)f.nfresh * V / f.expo;
  ck_assert_msg(lo <= Kth && Kth <= hi, "contacts of reinserted "
                "particles: K/K_th = %.4f [%.4f, %.4f] (%llu)", K / Kth,
                lo / Kth, hi / Kth, (unsigned long long)f.nfresh);
  ck_assert(f.nfresh > 100);
  free(f.mark);
  sb_engine_free(e);
}
END_TEST

/* The engine's reinsert outcome in a flow: the reinserted particle flows
 * on from its new place with its mean velocity (here the shear's) over
 * the rest of the step; in a fluid at rest it stays there. */
typedef struct {
  int checked;
  double G;
} reins_ctx;

static int reins_check(sb_engine *e, const sb_engine_pair *p, double s,
                       void *vc)
{
  reins_ctx *c = vc;
  ck_assert_int_eq(sb_engine_outcome_reinsert(e, p, s), 0);
  const size_t j = p->j;
  const double *L = sb_engine_get_params(e)->L;
  const double tf = (p->t0 + s * p->dt - sb_engine_time(e)) /
                    sb_engine_get_params(e)->dt;
  const double rest = (1.0 - tf) * sb_engine_get_params(e)->dt;
  if (c->G == 0.0) {
    ck_assert_int_eq(e->ndeclared, 0);
  } else {
    ck_assert_int_eq(e->ndeclared, 1);
    ck_assert(e->declared[0].k == j);
    const double *x = e->declared[0].x;
    const double ux = c->G * (x[1] - 0.5 * L[1]);
    ck_assert_rel(e->u[3 * j], ux, 1e-12);
    ck_assert_rel(e->x[3 * j], x[0] + rest * ux, 1e-12);
    ck_assert(e->x[3 * j + 1] == x[1] && e->x[3 * j + 2] == x[2]);
  }
  c->checked++;
  return SB_SUCCESS;
}

START_TEST(test_reinsert_flows_on)
{
  for (int sh = 0; sh < 2; sh++) {
    reins_ctx c = {0, sh ? 1.0 : 0.0};
    sb_engine *e = le_engine(LBOX, 0.2, 1.0, 0.0, SB_DETECT_BALLISTIC,
                             SB_OUTCOME_COUNT, 4, 3);
    if (!sh) {
      const double U0[3] = {0.0, 0.0, 0.0};
      sb_engine_set_lees_edwards(e, 0);
      sb_engine_set_fluid(e, SB_FLUID_REST, U0);
    }
    /* non-Brownian, tau_p = 1e3 s: keeps its approach velocity */
    const sb_engine_species sp = {0.4, 1.0, 1e3, 0.0, 0.0};
    sb_engine_add_species(e, &sp, NULL);
    /* a head-on pair along y in the box's middle (same fluid velocity) */
    const double xa[3] = {10.0, 9.0, 10.0}, ua[3] = {0.0, 2.0, 0.0};
    const double xb[3] = {10.0, 10.1, 10.0}, ub[3] = {0.0, 0.0, 0.0};
    double u1[3], u2[3];
    memcpy(u1, ua, sizeof u1);
    memcpy(u2, ub, sizeof u2);
    u1[0] += c.G * (xa[1] - 0.5 * LBOX);
    u2[0] += c.G * (xb[1] - 0.5 * LBOX);
    sb_engine_add_particle(e, 0, 0, xa, u1);
    sb_engine_add_particle(e, 0, 0, xb, u2);
    ck_assert_int_eq(sb_engine_set_outcome_fn(e, reins_check, &c), 0);
    ck_assert_int_eq(sb_engine_step(e), 0);
    ck_assert_int_eq(c.checked, 1);
    sb_engine_free(e);
  }
}
END_TEST

int main(void)
{
  Suite *s = suite_create("engine_lees_outcomes");
  TCase *tc = tcase_create("lees_outcomes");
  tcase_set_timeout(tc, 60);
  tcase_add_test(tc, test_le_elastic_pair);
  tcase_add_test(tc, test_le_redetect_chain);
  tcase_add_test(tc, test_le_merge_pair);
  tcase_add_test(tc, test_le_langevin_shear_law);
  tcase_add_test(tc, test_le_langevin_no_noise);
  tcase_add_test(tc, test_le_reinsert_kernel);
  tcase_add_test(tc, test_reinsert_flows_on);
  suite_add_tcase(s, tc);
  return sbt_run_suite(s);
}
