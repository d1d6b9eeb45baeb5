#define _POSIX_C_SOURCE 200809L
/* test_engine.c — engine core: two spheres at 45° (Thomine 2008, §7)
 * against
 * the analytic post-collision state, inelastic collisions against the
 * restitution relations, conservation in a many-body run, determinism
 * across neighbour-search methods, checkpoint round trip, transport in a
 * fluid field, detectors against an independent root finder, and error
 * handling. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <signal.h>
#include <sys/resource.h>
#include <unistd.h>

#include <smolbridge/engine.h>
#include <smolbridge/engine_bridge.h>
#include <smolbridge/engine_field.h>
#include <smolbridge/engine_firsthit.h>
#include <smolbridge/langevin.h>
#include <smolbridge/rng.h>

#include "engine/engine_internal.h"
#include "engine_same.h"
#include "testutil.h"

/* Free-flight species of radius 1, mass m (unit-free numbers; the engine
 * only needs consistent units). */
static size_t add_free(sb_engine *e, double r, double m)
{
  sb_engine_species s = {r, m, INFINITY, 0.0, 300.0};
  size_t k;
  ck_assert_int_eq(sb_engine_add_species(e, &s, &k), SB_SUCCESS);
  return k;
}

static sb_engine *box_engine(int dim, double L, double dt, size_t cap)
{
  sb_engine_params p;
  sb_engine_params_default(&p);
  p.dim = dim;
  p.L[0] = p.L[1] = p.L[2] = L;
  p.dt = dt;
  p.capacity = cap;
  sb_engine *e = sb_engine_alloc(&p);
  ck_assert_ptr_nonnull(e);
  return e;
}

/* ------------------------------------------------ two spheres at 45° */

/* Equal spheres (r = 1, m = 1); A moves at v along x, B at rest, placed so
 * that at contact the line of centres makes 45° with x.  Analytic result
 * (equal masses, elastic: the normal components are exchanged):
 * A' = (v/2, v/2), B' = (v/2, -v/2); contact at half the step; end
 * positions = contact + (dt/2) * new velocity. */
static void run_45(int dim)
{
  const double v = 1.0, dt = 1.0, s2 = sqrt(2.0);
  sb_engine *e = box_engine(dim, 100.0, dt, 4);
  size_t sp = add_free(e, 1.0, 1.0);
  double xa[3] = {50.0 - s2 - 0.5 * v * dt, 50.0, 50.0}, ua[3] = {v, 0, 0};
  double xb[3] = {50.0, 50.0 - s2, 50.0}, ub[3] = {0, 0, 0};
  ck_assert_int_eq(sb_engine_add_particle(e, sp, 0, xa, ua), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_add_particle(e, sp, 1, xb, ub), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_step(e), SB_SUCCESS);
  const double *x = sb_engine_positions(e), *u = sb_engine_velocities(e);
  const double tol = 1e-12;
  ck_assert_abs(u[0], v / 2, tol);
  ck_assert_abs(u[1], v / 2, tol);
  ck_assert_abs(u[2], 0.0, tol);
  ck_assert_abs(u[3], v / 2, tol);
  ck_assert_abs(u[4], -v / 2, tol);
  ck_assert_abs(u[5], 0.0, tol);
  /* contact at A = (50 - sqrt2, 50), B = (50, 50 - sqrt2) */
  ck_assert_abs(x[0], 50.0 - s2 + 0.5 * dt * v / 2, 50 * tol);
  ck_assert_abs(x[1], 50.0 + 0.5 * dt * v / 2, 50 * tol);
  ck_assert_abs(x[3], 50.0 + 0.5 * dt * v / 2, 50 * tol);
  ck_assert_abs(x[4], 50.0 - s2 - 0.5 * dt * v / 2, 50 * tol);
  sb_engine_stats st;
  sb_engine_get_stats(e, &st);
  ck_assert_uint_eq(st.ncoll, 1);
  ck_assert_uint_eq(st.fam[0][1], 1);
  sb_engine_free(e);
}

START_TEST(test_45deg_3d) { run_45(3); }
END_TEST

START_TEST(test_45deg_2d) { run_45(2); }
END_TEST

/* Same speed, opposite directions, 45° line of centres: in the centre of
 * mass frame the normal components reverse, so A (v, 0) -> (0, v) and
 * B (-v, 0) -> (0, -v) (a 90° deflection). */
START_TEST(test_45deg_same_speed)
{
  const double v = 2.0, dt = 1.0, s2 = sqrt(2.0);
  sb_engine *e = box_engine(3, 100.0, dt, 4);
  size_t sp = add_free(e, 1.0, 1.0);
  /* contact at s = 1/4: A at (50 - s2, 50), B at (50, 50 - s2) */
  double xa[3] = {50.0 - s2 - 0.25 * v, 50.0, 10.0}, ua[3] = {v, 0, 0};
  double xb[3] = {50.0 + 0.25 * v, 50.0 - s2, 10.0}, ub[3] = {-v, 0, 0};
  sb_engine_add_particle(e, sp, 0, xa, ua);
  sb_engine_add_particle(e, sp, 0, xb, ub);
  ck_assert_int_eq(sb_engine_step(e), SB_SUCCESS);
  const double *x = sb_engine_positions(e), *u = sb_engine_velocities(e);
  ck_assert_abs(u[0], 0.0, 1e-12);
  ck_assert_abs(u[1], v, 1e-12);
  ck_assert_abs(u[3], 0.0, 1e-12);
  ck_assert_abs(u[4], -v, 1e-12);
  ck_assert_abs(x[0], 50.0 - s2, 1e-12 * 50);
  ck_assert_abs(x[1], 50.0 + 0.75 * v, 1e-12 * 50);
  ck_assert_abs(x[3], 50.0, 1e-12 * 50);
  ck_assert_abs(x[4], 50.0 - s2 - 0.75 * v, 1e-12 * 50);
  sb_engine_free(e);
}
END_TEST

/* Unequal masses and eta < 1 in a general 3-D geometry: check relations
 * that do not use the impulse formula: momentum conserved, tangential
 * velocities unchanged, relative normal velocity multiplied by
 * -sqrt(eta), kinetic energy lost = (1 - eta) mu w_n^2 / 2. */
START_TEST(test_inelastic_unequal)
{
  const double eta = 0.64, dt = 1.0;
  sb_engine_params p;
  sb_engine_params_default(&p);
  p.L[0] = p.L[1] = p.L[2] = 100.0;
  p.dt = dt;
  p.eta = eta;
  sb_engine *e = sb_engine_alloc(&p);
  ck_assert_ptr_nonnull(e);
  size_t s1 = add_free(e, 1.0, 1.0), s2 = add_free(e, 2.0, 3.0);
  double xa[3] = {40.0, 50.3, 49.1}, ua[3] = {3.0, -0.2, 0.7};
  double xb[3] = {45.0, 50.0, 50.0}, ub[3] = {-0.5, 0.1, -0.3};
  sb_engine_add_particle(e, s1, 0, xa, ua);
  sb_engine_add_particle(e, s2, 0, xb, ub);
  double p0[3], e0 = sb_engine_kinetic_energy(e, p0);
  ck_assert_int_eq(sb_engine_step(e), SB_SUCCESS);
  sb_engine_stats st;
  sb_engine_get_stats(e, &st);
  ck_assert_uint_eq(st.ncoll, 1);
  double p1[3], e1 = sb_engine_kinetic_energy(e, p1);
  for (int k = 0; k < 3; k++)
    ck_assert_abs(p1[k], p0[k], 1e-12 * 10);
  /* contact normal from the end positions: x_end = x_c + (1-s) dt u' */
  const double *x = sb_engine_positions(e), *u = sb_engine_velocities(e);
  /* independent contact time by bisection on |dx0 + s dd| = 3 */
  double lo = 0, hi = 1;
  for (int it = 0; it < 200; it++) {
    double m = 0.5 * (lo + hi), d2 = 0;
    for (int k = 0; k < 3; k++) {
      double d = (xa[k] - xb[k]) + m * dt * (ua[k] - ub[k]);
      d2 += d * d;
    }
    if (d2 > 9.0)
      lo = m;
    else
      hi = m;
  }
  double s = 0.5 * (lo + hi), n[3], nn = 0;
  for (int k = 0; k < 3; k++) {
    n[k] = (xa[k] - xb[k]) + s * dt * (ua[k] - ub[k]);
    nn += n[k] * n[k];
  }
  nn = sqrt(nn);
  double wn0 = 0, wn1 = 0;
  for (int k = 0; k < 3; k++) {
    n[k] /= nn;
    wn0 += (ua[k] - ub[k]) * n[k];
    wn1 += (u[k] - u[3 + k]) * n[k];
  }
  ck_assert(wn0 < 0);
  ck_assert_rel(wn1, -sqrt(eta) * wn0, 1e-9);
  for (int pi = 0; pi < 2; pi++) {
    const double *u0 = pi ? ub : ua, *u1 = &u[3 * pi];
    double a0 = 0, a1 = 0;
    for (int k = 0; k < 3; k++) {
      a0 += u0[k] * n[k];
      a1 += u1[k] * n[k];
    }
    for (int k = 0; k < 3; k++)
      ck_assert_abs(u1[k] - a1 * n[k], u0[k] - a0 * n[k], 1e-9);
    /* re-advanced from the contact point */
    const double *xs = pi ? xb : xa;
    for (int k = 0; k < 3; k++)
      ck_assert_abs(x[3 * pi + k], xs[k] + s * dt * u0[k] + (1 - s) * dt *
                    u1[k], 1e-9);
  }
  double mu = 1.0 * 3.0 / 4.0;
  ck_assert_rel(e0 - e1, (1 - eta) * 0.5 * mu * wn0 * wn0, 1e-9);
  sb_engine_free(e);
}
END_TEST

/* ------------------------------------------------ many-body conservation */

/* 300 free-flight hard spheres, elastic: momentum and energy conserved
 * to 1e-12 relative over 2000 steps with several hundred collisions. */
START_TEST(test_conservation)
{
  sb_engine_params p;
  sb_engine_params_default(&p);
  p.L[0] = p.L[1] = p.L[2] = 40.0;
  p.dt = 0.01;
  p.capacity = 300;
  p.seed = 7;
  sb_engine *e = sb_engine_alloc(&p);
  ck_assert_ptr_nonnull(e);
  sb_engine_species s1 = {1.0, 1.0, INFINITY, 0.0, 1.0 / SB_BOLTZMANN};
  sb_engine_species s2 = {0.5, 0.3, INFINITY, 0.0, 1.0 / SB_BOLTZMANN};
  sb_engine_add_species(e, &s1, NULL);
  sb_engine_add_species(e, &s2, NULL);
  ck_assert_int_eq(sb_engine_fill_random(e, 0, 0, 200), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_fill_random(e, 1, 1, 100), SB_SUCCESS);
  ck_assert_uint_eq(sb_engine_check_overlaps(e, 0.0), 0);
  double p0[3], e0 = sb_engine_kinetic_energy(e, p0), pscale = 0;
  const double *u = sb_engine_velocities(e), *m = sb_engine_masses(e);
  for (size_t i = 0; i < 300; i++)
    pscale += m[i] * sqrt(u[3 * i] * u[3 * i] + u[3 * i + 1] * u[3 * i + 1] +
                          u[3 * i + 2] * u[3 * i + 2]);
  ck_assert_int_eq(sb_engine_run_until(e, 20.0), SB_SUCCESS);
  sb_engine_stats st;
  sb_engine_get_stats(e, &st);
  ck_assert_uint_eq(st.steps, 2000);
  ck_assert_uint_gt(st.ncoll, 300);
  double p1[3], e1 = sb_engine_kinetic_energy(e, p1);
  ck_assert_rel(e1, e0, 1e-12);
  for (int k = 0; k < 3; k++)
    ck_assert_abs(p1[k], p0[k], 1e-12 * pscale);
  /* earliest-first processing with re-detection leaves no overlaps */
  ck_assert_uint_eq(st.dropped, 0);
  ck_assert_uint_eq(sb_engine_check_overlaps(e, 1e-9), 0);
  uint64_t fsum = st.fam[0][0] + st.fam[0][1] + st.fam[1][1];
  ck_assert_uint_eq(fsum, st.ncoll);
  sb_engine_free(e);
}
END_TEST

/* ------------------------------------- several collisions in one step */

/* Newton's cradle in one step: A moves at v towards B and C at rest on a
 * line (equal masses, elastic).  A hits B at t1 = g1/v and stops, B hits C
 * at t2 = t1 + g2/v and stops, C leaves at v.  One step of length dt >
 * t2 must process both collisions in time order, the second detected on
 * B's new path, and end with A, B at their contact places and C at
 * x_C + v (dt - t2).  (With one collision per particle per step the
 * second would be lost and B would pass through C.) */
START_TEST(test_chain_in_one_step)
{
  for (int m = 0; m < 3; m++) {
    sb_engine *e = box_engine(3, 100.0, 1.0, 3);
    sb_engine_set_neigh(e, (sb_engine_neigh)m);
    add_free(e, 1.0, 1.0);
    const double v = 3.0, g1 = 0.5, g2 = 1.2, c = 50.0;
    double xa[3] = {c, c, c}, xb[3] = {c + 2.0 + g1, c, c},
           xc[3] = {c + 4.0 + g1 + g2, c, c};
    double ua[3] = {v, 0, 0}, z[3] = {0, 0, 0};
    ck_assert_int_eq(sb_engine_add_particle(e, 0, 0, xa, ua), SB_SUCCESS);
    ck_assert_int_eq(sb_engine_add_particle(e, 0, 0, xb, z), SB_SUCCESS);
    ck_assert_int_eq(sb_engine_add_particle(e, 0, 0, xc, z), SB_SUCCESS);
    ck_assert_int_eq(sb_engine_step(e), SB_SUCCESS);
    sb_engine_stats st;
    sb_engine_get_stats(e, &st);
    ck_assert_uint_eq(st.ncoll, 2);
    ck_assert_uint_eq(st.dropped, 0);
    const double *x = sb_engine_positions(e), *u = sb_engine_velocities(e);
    double t2 = (g1 + g2) / v;
    ck_assert_abs(u[0], 0.0, 1e-14);
    ck_assert_abs(u[3], 0.0, 1e-14);
    ck_assert_rel(u[6], v, 1e-14);
    ck_assert_rel(x[0], c + g1, 1e-14);
    ck_assert_rel(x[3], xb[0] + g2, 1e-14);
    ck_assert_rel(x[6], xc[0] + v * (1.0 - t2), 1e-14);
    ck_assert_uint_eq(sb_engine_check_overlaps(e, 1e-12), 0);
    sb_engine_free(e);
  }
}
END_TEST

/* A dense elastic gas with steps of ~1/3 of the mean free time, where a
 * particle often meets two partners in one step: every contact processed
 * (nothing dropped), no overlap after any step, energy and momentum
 * conserved, identical runs with the three neighbour searches. */
START_TEST(test_dense_many_per_step)
{
  sb_engine *e[3];
  for (int m = 0; m < 3; m++) {
    sb_engine_params p;
    sb_engine_params_default(&p);
    p.L[0] = p.L[1] = p.L[2] = 24.0;
    p.dt = 0.4;
    p.capacity = 1500;
    p.seed = 11;
    p.neigh = (sb_engine_neigh)m;
    e[m] = sb_engine_alloc(&p);
    ck_assert_ptr_nonnull(e[m]);
    add_free(e[m], 0.5, 1.0);
    ck_assert_int_eq(sb_engine_fill_random(e[m], 0, 0, 1500), SB_SUCCESS);
    ck_assert_int_eq(sb_engine_thermalize(e[m], 1.0 / SB_BOLTZMANN),
                     SB_SUCCESS);
  }
  double p0[3], e0 = sb_engine_kinetic_energy(e[0], p0);
  uint64_t multi = 0;
  for (int k = 0; k < 40; k++) {
    for (int m = 0; m < 3; m++)
      ck_assert_int_eq(sb_engine_step(e[m]), SB_SUCCESS);
    ck_assert_uint_eq(sb_engine_check_overlaps(e[0], 1e-9), 0);
  }
  sb_engine_stats st;
  sb_engine_get_stats(e[0], &st);
  ck_assert_uint_eq(st.dropped, 0);
  multi = st.redetected;
  /* phi = 0.057, Enskog rate 0.88 per particle and unit time: ~0.35
   * collisions per particle and step, ~10 500 in all */
  ck_assert_uint_gt(st.ncoll, 8000);
  ck_assert_uint_gt(multi, 1000);
  double p1[3], e1 = sb_engine_kinetic_energy(e[0], p1);
  ck_assert_rel(e1, e0, 1e-11);
  for (int m = 1; m < 3; m++)
    ck_assert(!memcmp(sb_engine_positions(e[0]), sb_engine_positions(e[m]),
                      3 * 1500 * sizeof(double)));
  for (int m = 0; m < 3; m++)
    sb_engine_free(e[m]);
}
END_TEST

/* --------------------------------- determinism and neighbour methods */

static sb_engine *brownian_engine(sb_engine_neigh m, unsigned long seed,
                                  sb_engine_outcome o)
{
  sb_engine_params p;
  sb_engine_params_default(&p);
  p.L[0] = 30.0;
  p.L[1] = 25.0;
  p.L[2] = 20.0;
  p.dt = 0.05;
  p.capacity = 400;
  p.seed = seed;
  p.neigh = m;
  p.outcome = o;
  p.sample_every = 10;
  sb_engine *e = sb_engine_alloc(&p);
  ck_assert_ptr_nonnull(e);
  sb_engine_species s = {0.5, 1.0, 1.0, sqrt(2.0), 0.0};  /* vvar = 1 */
  sb_engine_add_species(e, &s, NULL);
  ck_assert_int_eq(sb_engine_fill_random(e, 0, 0, 400), SB_SUCCESS);
  return e;
}


/* The three neighbour searches feed the same (deterministic) detector and
 * the events are processed in (s, i, j) order, so whole runs agree bit
 * for bit; the same seed reproduces a run. */
START_TEST(test_methods_agree)
{
  for (int o = 0; o < 2; o++) {
    sb_engine *a = brownian_engine(SB_NEIGH_CELLS, 3, (sb_engine_outcome)o);
    sb_engine *b = brownian_engine(SB_NEIGH_SWEEP, 3, (sb_engine_outcome)o);
    sb_engine *c = brownian_engine(SB_NEIGH_BRUTE, 3, (sb_engine_outcome)o);
    sb_engine *d = brownian_engine(SB_NEIGH_CELLS, 3, (sb_engine_outcome)o);
    for (int k = 0; k < 300; k++) {
      ck_assert_int_eq(sb_engine_step(a), SB_SUCCESS);
      ck_assert_int_eq(sb_engine_step(b), SB_SUCCESS);
      ck_assert_int_eq(sb_engine_step(c), SB_SUCCESS);
      ck_assert_int_eq(sb_engine_step(d), SB_SUCCESS);
    }
    sb_engine_stats st;
    sb_engine_get_stats(a, &st);
    ck_assert_uint_gt(st.ncoll, 20);
    sbt_assert_same_run(a, b, 0);
    sbt_assert_same_run(a, c, 0);
    sbt_assert_same_run(a, d, 0);
    if (o == SB_OUTCOME_REINSERT)
      ck_assert_uint_eq(sb_engine_check_overlaps(a, 1e-9), 0);
    sb_engine_free(a);
    sb_engine_free(b);
    sb_engine_free(c);
    sb_engine_free(d);
  }
}
END_TEST

/* ------------------------------------------------ checkpoint */

START_TEST(test_checkpoint_roundtrip)
{
  char path[] = "/tmp/sb_engine_ckpt_XXXXXX";
  int fd = mkstemp(path);
  ck_assert_int_ge(fd, 0);
  close(fd);
  sb_engine *a = brownian_engine(SB_NEIGH_CELLS, 11, SB_OUTCOME_REINSERT);
  double U[3] = {0.1, -0.2, 0.05};
  sb_engine_set_fluid(a, SB_FLUID_UNIFORM, U);
  /* the Langevin detector's parameters are kept too */
  const sb_engine_langevin_params lp = {2e-6, 3e-6, 4e-9};
  ck_assert_int_eq(sb_engine_set_langevin(a, &lp), SB_SUCCESS);
  for (int k = 0; k < 150; k++)
    ck_assert_int_eq(sb_engine_step(a), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_checkpoint_save(a, path), SB_SUCCESS);
  int st = -1;
  sb_engine *b = sb_engine_checkpoint_load(path, &st);
  ck_assert_int_eq(st, SB_SUCCESS);
  ck_assert_ptr_nonnull(b);
  sbt_assert_same_run(a, b, 0);
  sb_engine_langevin_params got;
  ck_assert_int_eq(sb_engine_get_langevin(b, &got), SB_SUCCESS);
  ck_assert(got.eps == lp.eps && got.xtol == lp.xtol && got.tol == lp.tol);
  for (int k = 0; k < 150; k++) {
    ck_assert_int_eq(sb_engine_step(a), SB_SUCCESS);
    ck_assert_int_eq(sb_engine_step(b), SB_SUCCESS);
  }
  sbt_assert_same_run(a, b, 0);
  const uint64_t *ia = sb_engine_ids(a), *ib = sb_engine_ids(b);
  ck_assert(!memcmp(ia, ib, sb_engine_count(a) * sizeof *ia));
  /* equal states give byte-identical files (no pointer, no padding) */
  {
    char pb[] = "/tmp/sb_engine_ckpt_XXXXXX";
    int fb = mkstemp(pb);
    ck_assert_int_ge(fb, 0);
    close(fb);
    ck_assert_int_eq(sb_engine_checkpoint_save(a, path), SB_SUCCESS);
    ck_assert_int_eq(sb_engine_checkpoint_save(b, pb), SB_SUCCESS);
    FILE *fa = fopen(path, "rb"), *fbf = fopen(pb, "rb");
    ck_assert(fa && fbf);
    int ca, cb;
    long pos = 0, diff = -1;
    do {
      ca = fgetc(fa);
      cb = fgetc(fbf);
      if (ca != cb && diff < 0)
        diff = pos;
      pos++;
    } while (ca != EOF && cb != EOF);
    fclose(fa);
    fclose(fbf);
    remove(pb);
    ck_assert_msg(diff < 0, "checkpoints differ at byte %ld", diff);
  }
  /* truncated file: clean SB_EFORMAT, no abort from GSL */
  FILE *f = fopen(path, "r+b");
  ck_assert_ptr_nonnull(f);
  fseek(f, 0, SEEK_END);
  long len = ftell(f);
  fclose(f);
  ck_assert_int_eq(truncate(path, len - 100), 0);
  sb_engine *c = sb_engine_checkpoint_load(path, &st);
  ck_assert_ptr_null(c);
  ck_assert_int_eq(st, SB_EFORMAT);
  remove(path);
  c = sb_engine_checkpoint_load(path, &st);
  ck_assert_ptr_null(c);
  ck_assert_int_eq(st, SB_EIO);
  sb_engine_free(a);
  sb_engine_free(b);

  /* another generator type and particle sorting survive the round trip */
  strcpy(path, "/tmp/sb_engine_ckpt_XXXXXX");
  fd = mkstemp(path);
  ck_assert_int_ge(fd, 0);
  close(fd);
  sb_engine_params p;
  sb_engine_params_default(&p);
  p.L[0] = p.L[1] = p.L[2] = 20.0;
  p.dt = 0.05;
  p.capacity = 300;
  p.rng_type = gsl_rng_taus2;
  p.sort_every = 7;
  p.outcome = SB_OUTCOME_REINSERT;
  a = sb_engine_alloc(&p);
  sb_engine_species s = {0.5, 1.0, 1.0, sqrt(2.0), 0.0};
  sb_engine_add_species(a, &s, NULL);
  ck_assert_int_eq(sb_engine_fill_random(a, 0, 0, 300), SB_SUCCESS);
  for (int k = 0; k < 50; k++)
    ck_assert_int_eq(sb_engine_step(a), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_checkpoint_save(a, path), SB_SUCCESS);
  b = sb_engine_checkpoint_load(path, &st);
  ck_assert_ptr_nonnull(b);
  ck_assert_str_eq(gsl_rng_name(sb_engine_rng(b)), "taus2");
  for (int k = 0; k < 50; k++) {
    ck_assert_int_eq(sb_engine_step(a), SB_SUCCESS);
    ck_assert_int_eq(sb_engine_step(b), SB_SUCCESS);
  }
  sbt_assert_same_run(a, b, 0);
  ck_assert(!memcmp(sb_engine_ids(a), sb_engine_ids(b),
                    300 * sizeof(uint64_t)));
  ck_assert_uint_eq(sb_engine_check_overlaps(a, 1e-9), 0);
  remove(path);
  sb_engine_free(a);
  sb_engine_free(b);
}
END_TEST

/* Sorting permutes the particles consistently: the multiset of (id,
 * position, velocity) is unchanged. */
START_TEST(test_sort_permutes)
{
  sb_engine *e = brownian_engine(SB_NEIGH_CELLS, 21, SB_OUTCOME_ELASTIC);
  size_t n = sb_engine_count(e);
  double *x = malloc(3 * n * sizeof *x), *u = malloc(3 * n * sizeof *u);
  memcpy(x, sb_engine_positions(e), 3 * n * sizeof *x);
  memcpy(u, sb_engine_velocities(e), 3 * n * sizeof *u);
  ck_assert_int_eq(sb_engine_sort(e), SB_SUCCESS);
  const uint64_t *id = sb_engine_ids(e);
  const double *x2 = sb_engine_positions(e), *u2 = sb_engine_velocities(e);
  int moved = 0;
  for (size_t k = 0; k < n; k++) {
    size_t i = (size_t)id[k];  /* ids were 0..n-1 in insertion order */
    moved += i != k;
    ck_assert(!memcmp(&x2[3 * k], &x[3 * i], 3 * sizeof(double)));
    ck_assert(!memcmp(&u2[3 * k], &u[3 * i], 3 * sizeof(double)));
  }
  ck_assert_int_gt(moved, 0);
  free(x);
  free(u);
  sb_engine_free(e);
}
END_TEST

/* Keyed streams (params.streams = 1): 6000 Brownian spheres (six
 * transport blocks, cells scanned in parallel), elastic collisions, 40
 * steps.  The run gives the
 * same particles, bit for bit, with 1, 2 and 3 threads, and with the
 * particles re-sorted in memory every step (sort_every = 1: other indices,
 * same ids) -- the generator is keyed by id, not by position in memory;
 * with the engine's sequential generator sorting changes the run (so the
 * comparison can fail). */
static sb_engine *stream_engine(int streams, int threads, size_t sort_every)
{
  sb_engine_params p;
  sb_engine_params_default(&p);
  p.L[0] = p.L[1] = p.L[2] = 75.0;
  p.dt = 0.05;
  p.capacity = 6000;
  p.seed = 77;
  p.streams = streams;
  p.threads = threads;
  p.sort_every = sort_every;
  p.sample_every = 10;
  sb_engine *e = sb_engine_alloc(&p);
  ck_assert_ptr_nonnull(e);
  sb_engine_species s = {0.5, 1.0, 1.0, sqrt(2.0), 0.0};
  sb_engine_add_species(e, &s, NULL);
  ck_assert_int_eq(sb_engine_fill_random(e, 0, 0, 6000), SB_SUCCESS);
  for (int k = 0; k < 40; k++)
    ck_assert_int_eq(sb_engine_step(e), SB_SUCCESS);
  return e;
}

/* positions and velocities in id order */
static double *by_id(const sb_engine *e)
{
  size_t n = sb_engine_count(e);
  double *v = malloc(6 * n * sizeof *v);
  const uint64_t *id = sb_engine_ids(e);
  for (size_t k = 0; k < n; k++) {
    ck_assert_uint_lt(id[k], n);
    memcpy(&v[6 * id[k]], &sb_engine_positions(e)[3 * k], 3 * sizeof *v);
    memcpy(&v[6 * id[k] + 3], &sb_engine_velocities(e)[3 * k],
           3 * sizeof *v);
  }
  return v;
}

/* The transport on the keyed streams is sb_langevin_step3_stream: two
 * species (tau_p = 1 and 0.3), 5000 particles (blocks and threads), one
 * step with the count outcome (particles pass through each other), the
 * same positions and velocities bit for bit as the library stepper on the
 * start state with (seed, ids, step 0). */
START_TEST(test_streams_transport_is_step3_stream)
{
  const size_t n = 5000;
  sb_engine_params p;
  sb_engine_params_default(&p);
  p.L[0] = p.L[1] = p.L[2] = 60.0;
  p.dt = 0.05;
  p.capacity = n;
  p.seed = 4242;
  p.streams = 1;
  p.threads = 2;
  p.outcome = SB_OUTCOME_COUNT;
  sb_engine *e = sb_engine_alloc(&p);
  ck_assert_ptr_nonnull(e);
  sb_engine_species sp[2] = {{0.5, 1.0, 1.0, sqrt(2.0), 0.0},
                             {0.3, 0.2, 0.3, 2.0, 0.0}};
  ck_assert_int_eq(sb_engine_add_species(e, &sp[0], NULL), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_add_species(e, &sp[1], NULL), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_fill_random(e, 0, 0, n / 2), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_fill_random(e, 1, 0, n - n / 2), SB_SUCCESS);
  double *x = malloc(3 * n * sizeof *x), *u = malloc(3 * n * sizeof *u);
  size_t *cidx = malloc(n * sizeof *cidx);
  memcpy(x, sb_engine_positions(e), 3 * n * sizeof *x);
  memcpy(u, sb_engine_velocities(e), 3 * n * sizeof *u);
  sb_langevin_coef c[2];
  for (int k = 0; k < 2; k++)
    ck_assert_int_eq(sb_langevin_coef_init(&c[k], sp[k].tau, sp[k].B, p.dt),
                     SB_SUCCESS);
  memcpy(cidx, sb_engine_species_of(e), n * sizeof *cidx);
  ck_assert_int_eq(sb_langevin_step3_stream(n, c, cidx, NULL, x, u, p.seed,
                                            0, sb_engine_ids(e), 0),
                   SB_SUCCESS);
  ck_assert_int_eq(sb_engine_step(e), SB_SUCCESS);
  const double *xe = sb_engine_positions(e), *ue = sb_engine_velocities(e);
  for (size_t q = 0; q < 3 * n; q++) {
    /* the engine wraps into the box after the step */
    const double L = p.L[q % 3], w = x[q] - L * floor(x[q] / L);
    ck_assert(xe[q] == x[q] || xe[q] == w);
    ck_assert(ue[q] == u[q]);
  }
  free(x);
  free(u);
  free(cidx);
  sb_engine_free(e);
}
END_TEST

START_TEST(test_streams_threads_and_order)
{
  sb_engine *a = stream_engine(1, 1, 0), *b = stream_engine(1, 2, 0),
            *c = stream_engine(1, 3, 0), *d = stream_engine(1, 3, 1);
  sbt_assert_same_run(a, b, 0);
  sbt_assert_same_run(a, c, 0);
  sb_engine_stats sa, sd;
  sb_engine_get_stats(a, &sa);
  sb_engine_get_stats(d, &sd);
  ck_assert_uint_gt(sa.ncoll, 0);
  ck_assert_uint_eq(sa.ncoll, sd.ncoll);
  size_t n = sb_engine_count(a);
  double *va = by_id(a), *vd = by_id(d);
  ck_assert(!memcmp(va, vd, 6 * n * sizeof *va));
  /* the sequential generator: sorting changes who draws what */
  sb_engine *g = stream_engine(0, 1, 0), *h = stream_engine(0, 1, 1);
  double *vg = by_id(g), *vh = by_id(h);
  ck_assert(memcmp(vg, vh, 6 * n * sizeof *vg) != 0);
  /* ... and the streams are not the generator */
  ck_assert(memcmp(va, vg, 6 * n * sizeof *va) != 0);
  free(va);
  free(vd);
  free(vg);
  free(vh);
  sb_engine *all[] = {a, b, c, d, g, h};
  for (int k = 0; k < 6; k++)
    sb_engine_free(all[k]);
  /* a checkpoint keeps the streams: the restarted run continues the same
   * way, bit for bit */
  sb_engine *s1 = stream_engine(1, 2, 0);
  char path[] = "/tmp/sb_engine_ckpt_XXXXXX";
  int fd = mkstemp(path);
  ck_assert_int_ge(fd, 0);
  close(fd);
  ck_assert_int_eq(sb_engine_checkpoint_save(s1, path), SB_SUCCESS);
  int st;
  sb_engine *s2 = sb_engine_checkpoint_load(path, &st);
  remove(path);
  ck_assert_ptr_nonnull(s2);
  ck_assert_int_eq(sb_engine_get_params(s2)->streams, 1);
  for (int k = 0; k < 5; k++) {
    ck_assert_int_eq(sb_engine_step(s1), SB_SUCCESS);
    ck_assert_int_eq(sb_engine_step(s2), SB_SUCCESS);
  }
  sbt_assert_same_run(s1, s2, 0);
  sb_engine_free(s1);
  sb_engine_free(s2);
  /* bad values */
  sb_engine_params p;
  sb_engine_params_default(&p);
  p.streams = 2;
  ck_assert_ptr_null(sb_engine_alloc(&p));
  p.streams = 0;
  p.threads = -1;
  ck_assert_ptr_null(sb_engine_alloc(&p));
  /* the library's default is the fast exact choice: keyed streams for
   * the transport, Philox behind gsl_rng for the rest */
  sb_engine_params_default(&p);
  ck_assert_int_eq(p.streams, 1);
  ck_assert_ptr_eq(p.rng_type, sb_rng_philox);
}
END_TEST

/* ------------------------------------------------ fluid and transport */

/* B = 0: the velocity relaxes deterministically towards U_s evaluated at
 * the start position: u(dt) = U_s + (u0 - U_s) e^{-dt/tau}; the shear
 * field U_x = G (y - L/2). */
START_TEST(test_fluid_fields)
{
  sb_engine *e = box_engine(3, 10.0, 0.3, 4);
  sb_engine_species s = {0.1, 1.0, 0.7, 0.0, 1.0};
  sb_engine_add_species(e, &s, NULL);
  double x[3] = {2.0, 8.0, 5.0}, u[3] = {1.0, 0.5, -0.25};
  sb_engine_add_particle(e, 0, 0, x, u);
  double G[3] = {0.4, 0, 0};
  ck_assert_int_eq(sb_engine_set_fluid(e, SB_FLUID_SHEAR, G), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_step(e), SB_SUCCESS);
  const double *v = sb_engine_velocities(e), *y = sb_engine_positions(e);
  double dec = exp(-0.3 / 0.7), Ux = 0.4 * (8.0 - 5.0);
  ck_assert_rel(v[0], Ux + (1.0 - Ux) * dec, 1e-14);
  ck_assert_rel(v[1], 0.5 * dec, 1e-14);
  ck_assert_rel(v[2], -0.25 * dec, 1e-14);
  /* position: x + U dt + (u0 - U) tau (1 - e) */
  ck_assert_rel(y[0], 2.0 + Ux * 0.3 + (1.0 - Ux) * 0.7 * (1 - dec), 1e-14);
  double Uu[3] = {1.0, 2.0, 3.0};
  sb_engine_set_fluid(e, SB_FLUID_UNIFORM, Uu);
  ck_assert_int_eq(sb_engine_run_until(e, 30.0), SB_SUCCESS);
  for (int k = 0; k < 3; k++)
    ck_assert_rel(v[k], Uu[k], 1e-12);
  sb_engine_free(e);
}
END_TEST

/* A user fluid field: evaluated once per step at the start positions. */
static int swirl(size_t n, const double *x, double *us, void *ctx)
{
  (*(int *)ctx)++;
  for (size_t i = 0; i < n; i++) {
    us[3 * i] = -(x[3 * i + 1] - 5.0);
    us[3 * i + 1] = x[3 * i] - 5.0;
    us[3 * i + 2] = 7.0;  /* must be ignored in 2-D */
  }
  return 0;
}

START_TEST(test_fluid_callback_2d)
{
  sb_engine *e = box_engine(2, 10.0, 0.1, 4);
  sb_engine_species s = {0.1, 1.0, 0.5, 0.0, 1.0};
  sb_engine_add_species(e, &s, NULL);
  double x[3] = {7.0, 5.0, 0.0}, u[3] = {0, 0, 0};
  sb_engine_add_particle(e, 0, 0, x, u);
  int calls = 0;
  ck_assert_int_eq(sb_engine_set_fluid_fn(e, swirl, &calls), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_step(e), SB_SUCCESS);
  ck_assert_int_eq(calls, 1);
  const double *v = sb_engine_velocities(e), *y = sb_engine_positions(e);
  double a = -expm1(-0.1 / 0.5);
  ck_assert_abs(v[0], 0.0, 1e-15);
  ck_assert_rel(v[1], 2.0 * a, 1e-14);
  ck_assert(v[2] == 0.0 && y[2] == 0.0);
  sb_engine_free(e);
}
END_TEST

/* ------------------------------------------------ detectors */

/* The ballistic contact time against bisection on |dx0 + s dd| - sigma,
 * on random approaching pairs; the overlap detector misses a pair that
 * passes through within the step, the ballistic one does not. */
START_TEST(test_detectors)
{
  unsigned seed = 12345;
  int found = 0;
  for (int t = 0; t < 2000; t++) {
    sb_engine_pair p;
    memset(&p, 0, sizeof p);
    for (int k = 0; k < 3; k++) {
      seed = seed * 1103515245u + 12345u;
      p.dx0[k] = 4.0 * ((seed >> 8) / 16777216.0) - 2.0;
      seed = seed * 1103515245u + 12345u;
      p.dd[k] = 6.0 * ((seed >> 8) / 16777216.0) - 3.0;
    }
    p.sigma = 1.0;
    p.dt = 1.0;
    double s;
    int hit = sb_engine_detect_ballistic(&p, &s);
    /* reference: minimum distance and first crossing by bisection */
    double a = 0, b = 0, c = -1;
    for (int k = 0; k < 3; k++) {
      a += p.dd[k] * p.dd[k];
      b += p.dx0[k] * p.dd[k];
      c += p.dx0[k] * p.dx0[k];
    }
    if (c <= 0)
      continue;  /* overlapping at start: covered elsewhere */
    double smin = b < 0 ? fmin(-b / a, 1.0) : 0.0;
    double dmin2 = c + 2 * b * smin + a * smin * smin;
    int want = dmin2 <= 0.0;
    ck_assert_int_eq(hit, want);
    if (!want)
      continue;
    found++;
    double lo = 0, hi = smin;
    for (int it = 0; it < 200; it++) {
      double m = 0.5 * (lo + hi);
      if (c + 2 * b * m + a * m * m > 0)
        lo = m;
      else
        hi = m;
    }
    ck_assert_abs(s, 0.5 * (lo + hi), 1e-13);
  }
  ck_assert_int_gt(found, 150);
  /* pass-through: head-on, relative displacement 10 >> sigma */
  sb_engine_pair q = {0, 1, {-3, 0, 0}, {10, 0, 0}, 1.0, 1.0, 0.0};
  double s;
  ck_assert_int_eq(sb_engine_detect_ballistic(&q, &s), 1);
  ck_assert_abs(s, 0.2, 1e-15);
  ck_assert_int_eq(sb_engine_detect_overlap(&q, &s), 0);
  sb_engine_pair r = {0, 1, {-3, 0, 0}, {2.5, 0, 0}, 1.0, 1.0, 0.0};
  ck_assert_int_eq(sb_engine_detect_overlap(&r, &s), 1);
  ck_assert_abs(s, 0.8, 1e-15);
}
END_TEST

/* ------------------------------------------------ kernel observer */

START_TEST(test_kernel_estimate)
{
  sb_engine *e = brownian_engine(SB_NEIGH_CELLS, 5, SB_OUTCOME_COUNT);
  double K, lo, hi;
  ck_assert_int_eq(sb_engine_kernel(e, 0.95, &K, &lo, &hi), SB_EDOM);
  ck_assert(isnan(K));
  for (int k = 0; k < 100; k++)
    sb_engine_step(e);
  sb_engine_stats st;
  sb_engine_get_stats(e, &st);
  ck_assert_int_eq(sb_engine_kernel(e, 0.95, &K, &lo, &hi), SB_SUCCESS);
  double V = 30.0 * 25.0 * 20.0, n = 400;
  ck_assert_rel(K, 2.0 * (double)st.ncoll * V / (n * (n - 1) * st.t), 1e-14);
  ck_assert(lo < K && K < hi);
  size_t ns;
  const sb_engine_sample *ser = sb_engine_series(e, &ns);
  ck_assert_uint_eq(ns, 10);
  ck_assert(ser[9].t == st.t);
  ck_assert_rel(ser[9].K, K, 1e-14);
  sb_engine_reset_counters(e);
  sb_engine_get_stats(e, &st);
  ck_assert_uint_eq(st.ncoll, 0);
  ck_assert_int_eq(sb_engine_kernel(e, 0.95, &K, NULL, NULL), SB_EDOM);
  sb_engine_free(e);
}
END_TEST

/* ------------------------------------------------ errors */

START_TEST(test_errors)
{
  sb_engine_params p;
  sb_engine_params_default(&p);
  p.dim = 4;
  ck_assert_ptr_null(sb_engine_alloc(&p));
  ck_assert_int_eq(sb_last_status(), SB_EINVAL);
  ck_assert(strstr(sb_last_error(), "dim") != NULL);
  sb_engine_params_default(&p);
  p.L[1] = -1;
  ck_assert_ptr_null(sb_engine_alloc(&p));
  sb_engine_params_default(&p);
  p.dt = NAN;
  ck_assert_ptr_null(sb_engine_alloc(&p));
  sb_engine_params_default(&p);
  p.eta = 1.5;
  ck_assert_ptr_null(sb_engine_alloc(&p));
  ck_assert_ptr_null(sb_engine_alloc(NULL));

  sb_engine *e = box_engine(3, 10.0, 1.0, 2);
  sb_engine_species bad = {-1, 1, 1, 1, 0};
  ck_assert_int_eq(sb_engine_add_species(e, &bad, NULL), SB_EINVAL);
  sb_engine_species bad2 = {1, 1, INFINITY, 0, 0};  /* free flight, T = 0 */
  ck_assert_int_eq(sb_engine_add_species(e, &bad2, NULL), SB_EINVAL);
  sb_engine_species bad3 = {1, 1, 1, NAN, 0};
  ck_assert_int_eq(sb_engine_add_species(e, &bad3, NULL), SB_EINVAL);
  double x[3] = {1, 1, 1}, u[3] = {0, 0, 0};
  ck_assert_int_eq(sb_engine_add_particle(e, 0, 0, x, u), SB_EINVAL);
  size_t sp = add_free(e, 0.5, 1.0);
  ck_assert_int_eq(sb_engine_add_particle(e, sp, SB_ENGINE_MAXFAM, x, u),
                   SB_EINVAL);
  double xn[3] = {NAN, 1, 1};
  ck_assert_int_eq(sb_engine_add_particle(e, sp, 0, xn, u), SB_EINVAL);
  ck_assert_int_eq(sb_engine_add_particle(e, sp, 0, x, u), SB_SUCCESS);
  double u2[3] = {6.0, 0, 0}, x2[3] = {5, 5, 5};
  ck_assert_int_eq(sb_engine_add_particle(e, sp, 0, x2, u2), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_add_particle(e, sp, 0, x2, u2), SB_EINVAL);
  /* displacement 6 > L/2: refused, with the reason */
  ck_assert_int_eq(sb_engine_step(e), SB_EINVAL);
  ck_assert(strstr(sb_last_error(), "too large") != NULL);
  ck_assert_int_eq(sb_engine_set_dt(e, -1.0), SB_EINVAL);
  ck_assert_int_eq(sb_engine_set_outcome(e, SB_OUTCOME_ELASTIC, 2.0),
                   SB_EINVAL);
  ck_assert_int_eq(sb_engine_set_fluid(e, SB_FLUID_CALLBACK, NULL),
                   SB_EINVAL);
  ck_assert_int_eq(sb_engine_fill_random(e, sp, 0, 1), SB_EINVAL);
  sb_engine_neigh m;
  ck_assert_int_eq(sb_engine_neigh_from_name("grid", &m), SB_EINVAL);
  ck_assert_int_eq(sb_engine_neigh_from_name("sweep", &m), SB_SUCCESS);
  ck_assert_int_eq(m, SB_NEIGH_SWEEP);
  sb_engine_free(e);
  sb_engine_free(NULL);

  /* a full box: fill_random gives up cleanly */
  e = box_engine(2, 10.0, 1.0, 1000);
  add_free(e, 1.0, 1.0);
  ck_assert_int_eq(sb_engine_fill_random(e, 0, 0, 1000), SB_EMAXITER);
  ck_assert_uint_eq(sb_engine_count(e), 0);
  sb_engine_free(e);

  /* not a checkpoint */
  char path[] = "/tmp/sb_engine_bad_XXXXXX";
  int fd = mkstemp(path);
  ck_assert_int_ge(fd, 0);
  ck_assert_int_eq(write(fd, "hello world, not a checkpoint", 29), 29);
  close(fd);
  int st;
  ck_assert_ptr_null(sb_engine_checkpoint_load(path, &st));
  ck_assert_int_eq(st, SB_EFORMAT);
  remove(path);
}
END_TEST

/* Species whose spread or step leaves the doubles: refused up front where
 * a coefficient or the stationary velocity spread cannot be represented
 * (SB_ERANGE naming the parameters), the spread taken as B sqrt(tau / 2)
 * where only B^2 tau / 2 overflows; a step whose new state overflows
 * (B = DBL_MAX, tau = dt = 1: the velocity's sd is 0.66 DBL_MAX) is
 * SB_ERANGE with every particle at its start of step, on both transport
 * paths, in 3-D and 2-D. */
START_TEST(test_species_extreme)
{
  sb_engine *e = box_engine(3, 10.0, 1.0, 4);
  /* B^2 tau / 2 = inf but B sqrt(tau / 2) = 1.3e158 */
  sb_engine_species a = {0.1, 1.0, 1e-300, DBL_MAX, 0.0};
  ck_assert_int_eq(sb_engine_add_species(e, &a, NULL), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_fill_random(e, 0, 0, 2), SB_SUCCESS);
  const double *u = sb_engine_velocities(e);
  for (int k = 0; k < 6; k++)
    ck_assert(isfinite(u[k]) && u[k] != 0.0);
  /* B sqrt(tau / 2) = 7e349 > DBL_MAX */
  sb_engine_species b = {0.1, 1.0, 1e300, 1e200, 0.0};
  ck_assert_int_eq(sb_engine_add_species(e, &b, NULL), SB_ERANGE);
  ck_assert(strstr(sb_last_error(), "B = 1e+200") != NULL);
  ck_assert(strstr(sb_last_error(), "sb_engine_add_species") != NULL);
  /* k_B T / m overflows, sqrt(k_B T / m) = 5e292 does not */
  sb_engine_species c = {0.1, 1e-300, INFINITY, 0.0, DBL_MAX};
  ck_assert_int_eq(sb_engine_add_species(e, &c, NULL), SB_SUCCESS);
  ck_assert_uint_eq(sb_engine_species_count(e), 2);
  double xc[3] = {1, 1, 1}, uc[3];
  ck_assert_int_eq(
      sbi_engine_equilibrium_velocity(e, 1, xc, uc, SB_EINVAL, "t"),
      SB_SUCCESS);
  for (int k = 0; k < 3; k++)
    ck_assert(isfinite(uc[k]) && fabs(uc[k]) > 1e290);
  /* a step coefficient beyond DBL_MAX: SB_ERANGE (was SB_EINVAL) */
  sb_engine_species f = {0.1, 1.0, 1e300, 1e300, 1.0};
  sb_engine_free(e);
  e = box_engine(3, 10.0, 1e300, 4);
  ck_assert_int_eq(sb_engine_add_species(e, &f, NULL), SB_ERANGE);
  ck_assert(strstr(sb_last_error(), "exceeds DBL_MAX") != NULL);
  sb_engine_free(e);

  for (int c = 0; c < 4; c++) {
    const int streams = c & 1, dim = 3 - (c >> 1);
    sb_engine_params p;
    sb_engine_params_default(&p);
    p.dim = dim;
    p.L[0] = p.L[1] = p.L[2] = 10.0;
    p.dt = 1.0;
    p.capacity = 4;
    p.streams = streams;
    e = sb_engine_alloc(&p);
    ck_assert_ptr_nonnull(e);
    sb_engine_species s = {0.1, 1.0, 1.0, DBL_MAX, 0.0};
    ck_assert_int_eq(sb_engine_add_species(e, &s, NULL), SB_SUCCESS);
    double x0[3] = {5, 5, 5}, u0[3] = {0, 0, 0};
    ck_assert_int_eq(sb_engine_add_particle(e, 0, 0, x0, u0), SB_SUCCESS);
    const double *x = sb_engine_positions(e);
    u = sb_engine_velocities(e);
    int erange = 0;
    for (int k = 0; k < 40 && !erange; k++) {
      double xb[3], ub[3];
      memcpy(xb, x, sizeof xb);
      memcpy(ub, u, sizeof ub);
      int st = sb_engine_step(e);
      for (int q = 0; q < 3; q++)
        ck_assert_msg(isfinite(x[q]) && isfinite(u[q]),
                      "%d-D, streams %d, step %d (status %d): x[%d] = %g, "
                      "u[%d] = %g", dim, streams, k, st, q, x[q], q, u[q]);
      if (st == SB_EINVAL) {
        /* a finite step of ~DBL_MAX: beyond half the box, refused (one
         * particle is checked as two or more are), its end state finite
         * (it was wrapped into the box with status 0); the next step goes
         * on from there */
        ck_assert(strstr(sb_last_error(), "sb_engine_step") != NULL);
        continue;
      }
      if (st) {
        ck_assert_int_eq(st, SB_ERANGE);
        ck_assert(strstr(sb_last_error(), "exceeds DBL_MAX") != NULL);
        ck_assert(memcmp(xb, x, sizeof xb) == 0);
        ck_assert(memcmp(ub, u, sizeof ub) == 0);
        erange = 1;
      }
    }
    ck_assert_msg(erange, "%d-D, streams %d: no SB_ERANGE in 40 steps", dim,
                  streams);
    sb_engine_free(e);
  }
}
END_TEST

/* One particle: its displacement is checked as for two or more (it was
 * not searched, so a huge finite step wrapped silently into the box): a
 * step longer than half the box is SB_EINVAL ("step too large"; "non-
 * finite displacement" where its length overflows), on both transport
 * paths, as with a second particle far away; a short step of one
 * particle and a step of none still run. */
START_TEST(test_one_particle_step_checked)
{
  for (int streams = 0; streams < 2; streams++)
    for (int np = 0; np < 3; np++) {
      sb_engine_params p;
      sb_engine_params_default(&p);
      p.L[0] = p.L[1] = p.L[2] = 10.0;
      p.dt = 1.0;
      p.capacity = 4;
      p.streams = streams;
      sb_engine *e = sb_engine_alloc(&p);
      ck_assert_ptr_nonnull(e);
      size_t sp = add_free(e, 0.1, 1.0);
      /* free flight at T = 300 K, m = 1: the thermal velocity is 6e-11 */
      const double speeds[3] = {1.0, 6.0, 1e300};
      for (int k = 0; k < 3; k++) {
        if (np == 0 && k > 0)
          break;
        double x[3] = {5, 5, 5}, u[3] = {speeds[k], 0, 0};
        sb_engine_free(e);
        e = sb_engine_alloc(&p);
        sp = add_free(e, 0.1, 1.0);
        if (np > 0)
          ck_assert_int_eq(sb_engine_add_particle(e, sp, 0, x, u),
                           SB_SUCCESS);
        double xf[3] = {1, 1, 1}, uf[3] = {0, 0, 0};
        if (np > 1)
          ck_assert_int_eq(sb_engine_add_particle(e, sp, 0, xf, uf),
                           SB_SUCCESS);
        int st = sb_engine_step(e);
        if (np == 0 || k == 0) {
          ck_assert_int_eq(st, SB_SUCCESS);
          ck_assert_uint_eq(sb_engine_count(e), (size_t)np);
          if (np)
            ck_assert_abs(sb_engine_positions(e)[0], 6.0, 1e-9);
          continue;
        }
        ck_assert_msg(st == SB_EINVAL, "streams %d, %d particle(s), u = %g: "
                      "status %d (%s)", streams, np, u[0], st,
                      sb_last_error());
        /* u = 1e300: the length of the displacement overflows, a step
         * too large for the box (it said "non-finite displacement") */
        const char *why = k == 1 ? "step too large"
                                 : "step too large for the box: particle "
                                   "0 moves by (1e+300, 0, 0) m, a length "
                                   "of 1e+300 m (whose square overflows";
        ck_assert_msg(strstr(sb_last_error(), why) != NULL &&
                          strstr(sb_last_error(), "sb_engine_step") != NULL,
                      "%s", sb_last_error());
      }
      sb_engine_free(e);
    }
}
END_TEST

/* The nonlinear drag step and the exact shear step after the transport:
 * a new x or u that is not finite is SB_ERANGE naming the part of the
 * step, every particle back at its start of step (as for the transport).
 * Drag: u_x = 1e200 gives |u - U_s|^2 = inf, so Re = inf and the drag
 * factor NaN (the Stokes transport of the same state is finite).  Shear:
 * G = 1e10 1/s and u_y = 1e300 m/s give the correction G tau c_1 u_y of
 * u_x = inf. */
START_TEST(test_after_transport_overflow)
{
  for (int kind = 0; kind < 2; kind++)
    for (int streams = 0; streams < 2; streams++) {
      sb_engine_params p;
      sb_engine_params_default(&p);
      p.L[0] = p.L[1] = p.L[2] = 10.0;
      p.dt = 1.0;
      p.capacity = 4;
      p.streams = streams;
      sb_engine *e = sb_engine_alloc(&p);
      ck_assert_ptr_nonnull(e);
      sb_engine_species s = {0.1, 1.0, 1.0, 0.0, 0.0};  /* B = 0, T = 0 */
      ck_assert_int_eq(sb_engine_add_species(e, &s, NULL), SB_SUCCESS);
      double xa[3] = {2, 5, 5}, xb[3] = {7, 5, 2}, ua[3] = {0, 0, 0};
      if (kind == 0) {
        sb_engine_species_fluid f = {SB_DRAG_SCHILLER_NAUMANN, 1000.0,
                                     1e-3};
        ck_assert_int_eq(sb_engine_set_species_fluid(e, 0, &f), SB_SUCCESS);
        ua[0] = 1e200;
      } else {
        const double G[3] = {1e10, 0, 0};
        ck_assert_int_eq(sb_engine_set_fluid(e, SB_FLUID_SHEAR, G),
                         SB_SUCCESS);
        ck_assert_int_eq(sb_engine_set_lees_edwards(e, 1), SB_SUCCESS);
        ua[1] = 1e300;  /* at y = L/2: the shear's U_x is 0 */
      }
      const double ub[3] = {0, 0, 0};
      ck_assert_int_eq(sb_engine_add_particle(e, 0, 0, xa, ua), SB_SUCCESS);
      ck_assert_int_eq(sb_engine_add_particle(e, 0, 0, xb, ub), SB_SUCCESS);
      double x0[6], u0[6];
      memcpy(x0, sb_engine_positions(e), sizeof x0);
      memcpy(u0, sb_engine_velocities(e), sizeof u0);
      int st = sb_engine_step(e);
      ck_assert_msg(st == SB_ERANGE, "kind %d, streams %d: status %d (%s)",
                    kind, streams, st, sb_last_error());
      ck_assert(strstr(sb_last_error(), kind ? "after the exact shear step"
                                             : "after the nonlinear drag "
                                               "step") != NULL);
      ck_assert(strstr(sb_last_error(), "particle 0") != NULL);
      ck_assert_mem_eq(sb_engine_positions(e), x0, sizeof x0);
      ck_assert_mem_eq(sb_engine_velocities(e), u0, sizeof u0);
      ck_assert(sb_engine_time(e) == 0.0);
      sb_engine_free(e);
    }
}
END_TEST

/* A fluid field that is 0 for the first call (the step's transport) and
 * ctx->v from the second on (the draws of the step's reinsertions and
 * arrivals). */
typedef struct {
  int calls;
  double v;
} fluid_after;

static int fluid_after_first(size_t n, const double *x, double *us,
                             void *ctx)
{
  (void)x;
  fluid_after *f = ctx;
  const double v = f->calls++ ? f->v : 0.0;
  for (size_t i = 0; i < 3 * n; i++)
    us[i] = v;
  return 0;
}

/* Reinsertions (absorbing wall with deposit = reinsert, the reinsert
 * outcome) and inflow arrivals whose drawn velocity or flight is not
 * usable: nothing infinite, NaN or outside the box in the state.  A fluid
 * callback that returns an infinite velocity is SB_EINVAL naming the
 * callback and the particle (it was SB_ERANGE "the fluid field's
 * velocity", after u = inf, then x = NaN, had been stored with status
 * 0); a finite one of 1.5e308 m/s carries the flight of the reinsert
 * outcome (the rest of the step, 0.5 s) and an arrival's (tau = 1 s)
 * ~1e308 m away, where the wrap x - L floor(x / L) is all rounding:
 * SB_ERANGE "too far out to be wrapped" (the position was stored wrapped
 * from its rounding, with status 0). */
START_TEST(test_reinsert_overflow)
{
  for (int big = 0; big < 2; big++)
    for (int kind = 0; kind < 3; kind++) {
      if (big && kind == 0)
        continue;  /* no flight: a finite velocity is placed */
      sb_engine *e = box_engine(3, 10.0, 1.0, 8);
      size_t sp;
      if (kind < 2)
        sp = add_free(e, 0.1, 1.0);
      else {
        sb_engine_species s = {0.1, 1.0, 1.0, 0.0, 0.0};
        ck_assert_int_eq(sb_engine_add_species(e, &s, &sp), SB_SUCCESS);
      }
      fluid_after fa = {0, big ? 1.5e308 : INFINITY};
      ck_assert_int_eq(sb_engine_set_fluid_fn(e, fluid_after_first, &fa),
                       SB_SUCCESS);
      if (kind == 0) {  /* reaches the absorbing face y = 0 */
        ck_assert_int_eq(sb_engine_set_walls(e, 1, SB_WALL_ABSORB,
                                             SB_WALL_ABSORB), SB_SUCCESS);
        ck_assert_int_eq(sb_engine_set_wall_mode(e, SB_WALLDET_BALLISTIC,
                                                 SB_DEPOSIT_REINSERT),
                         SB_SUCCESS);
        double x[3] = {5, 0.5, 5}, u[3] = {0, -1, 0};
        ck_assert_int_eq(sb_engine_add_particle(e, sp, 0, x, u),
                         SB_SUCCESS);
      } else if (kind == 1) {  /* head-on at half the step */
        ck_assert_int_eq(sb_engine_set_outcome(e, SB_OUTCOME_REINSERT, 1.0),
                         SB_SUCCESS);
        double xa[3] = {4, 5, 5}, ua[3] = {1, 0, 0};
        double xb[3] = {6, 5, 5}, ub[3] = {-1, 0, 0};
        ck_assert_int_eq(sb_engine_add_particle(e, sp, 0, xa, ua),
                         SB_SUCCESS);
        ck_assert_int_eq(sb_engine_add_particle(e, sp, 0, xb, ub),
                         SB_SUCCESS);
      } else {  /* ~ 4 arrivals a step through x = 0 */
        sb_engine_inflow in = {0, sp, 0, 4.0, {4, 4}, {6, 6}, {1, 0, 0}, 0};
        ck_assert_int_eq(sb_engine_add_inflow(e, &in, NULL), SB_SUCCESS);
      }
      int st = SB_SUCCESS;
      for (int k = 0; k < 5 && !st; k++) {
        st = sb_engine_step(e);
        const double *x = sb_engine_positions(e),
                     *u = sb_engine_velocities(e);
        for (size_t i = 0; i < 3 * sb_engine_count(e); i++)
          ck_assert_msg(isfinite(u[i]) && x[i] >= 0.0 && x[i] < 10.0,
                        "big %d, kind %d, step %d (status %d): x[%zu] = "
                        "%g, u[%zu] = %g", big, kind, k, st, i, x[i], i,
                        u[i]);
      }
      ck_assert_msg(st == (big ? SB_ERANGE : SB_EINVAL), "big %d, kind %d: "
                    "status %d (%s)", big, kind, st, sb_last_error());
      ck_assert(strstr(sb_last_error(), "sb_engine_step") != NULL);
      const char *why = big ? (kind == 1 ? "reinserted particle"
                                         : "inflow 0")
                            : "fluid callback returned the velocity us[0] "
                              "= inf";
      ck_assert_msg(strstr(sb_last_error(), why) != NULL, "big %d, kind "
                    "%d: %s", big, kind, sb_last_error());
      if (big)
        ck_assert_msg(strstr(sb_last_error(), "too far out to be wrapped"),
                      "%s", sb_last_error());
      else  /* the particle: a wall's or outcome's, or a new arrival */
        ck_assert_msg(strstr(sb_last_error(), kind == 2 ? "a new particle"
                                                        : "for particle "),
                      "kind %d: %s", kind, sb_last_error());
      sb_engine_free(e);
    }
}
END_TEST

/* Positions the wrap into the box cannot take: x = 1.7e308 m in a box of
 * 1e-4 m (x / L overflows: the wrap stored -inf with status 0) and 1e20 m
 * (ulp(x) = 16384 m, 1.6e8 boxes: the stored coordinate was rounding,
 * and could be negative) are SB_EINVAL from sb_engine_add_particle and
 * sb_engine_set_particle, the engine unchanged; 6e7 box lengths (below
 * the 2^26 limit) are still taken.  A coordinate just below a multiple
 * of L (x = -6.73...: x - L floor(x / L) rounds to -8.9e-16) lands inside
 * the box (it was stored as -8.9e-16), within 2 ulp(x) of the exact
 * x + 3 L (fmod, then one rounding).  A checkpoint holding a position
 * outside the box or not finite (written through the internal header) is
 * refused on load naming the particle. */
START_TEST(test_wrap_far_position)
{
  sb_engine *e = box_engine(3, 1e-4, 1e-6, 4);
  size_t sp = add_free(e, 1e-6, 1.0);
  const double u[3] = {0, 0, 0};
  const double far[2] = {1.7e308, 1e20};
  for (int q = 0; q < 2; q++) {
    double x[3] = {5e-5, 5e-5, 5e-5};
    x[q] = far[q];  /* the x and y components */
    ck_assert_int_eq(sb_engine_add_particle(e, sp, 0, x, u), SB_EINVAL);
    ck_assert_msg(strstr(sb_last_error(), "sb_engine_add_particle") &&
                      strstr(sb_last_error(), "cannot be wrapped"),
                  "%s", sb_last_error());
    ck_assert_uint_eq(sb_engine_count(e), 0);
  }
  const double x0[3] = {5e-5, 5e-5, 5e-5};
  ck_assert_int_eq(sb_engine_add_particle(e, sp, 0, x0, u), SB_SUCCESS);
  for (int q = 0; q < 2; q++) {
    double x[3] = {5e-5, 5e-5, 5e-5};
    x[2] = -far[q];
    ck_assert_int_eq(sb_engine_set_particle(e, 0, x, u), SB_EINVAL);
    ck_assert_msg(strstr(sb_last_error(), "sb_engine_set_particle") &&
                      strstr(sb_last_error(), "particle 0"),
                  "%s", sb_last_error());
    ck_assert_mem_eq(sb_engine_positions(e), x0, sizeof x0);
  }
  /* 6e7 boxes out: taken, inside the box */
  const double xf[3] = {6e7 * 1e-4, 5e-5, 5e-5};
  ck_assert_int_eq(sb_engine_set_particle(e, 0, xf, u), SB_SUCCESS);
  ck_assert(sb_engine_positions(e)[0] >= 0.0 &&
            sb_engine_positions(e)[0] < 1e-4);
  sb_engine_free(e);

  /* just below -3 L: L floor(x / L) = -3 L rounds above x */
  const double L = 2.2443204799908911;
  e = box_engine(3, L, 1e-3, 4);
  sp = add_free(e, 0.01, 1.0);
  const double xn[3] = {-6.7329614399726738, 1.0, 1.0};
  ck_assert_int_eq(sb_engine_add_particle(e, sp, 0, xn, u), SB_SUCCESS);
  /* fmod is exact, then one rounding; the wrap's error is ~ ulp(x) */
  const double w = sb_engine_positions(e)[0], ref = fmod(xn[0], L) + L,
               ulp = nextafter(-xn[0], INFINITY) + xn[0];
  ck_assert_msg(w >= 0.0 && w < L && fabs(w - ref) <= 2.0 * ulp,
                "x = %.17g stored as %.17g (expected %.17g)", xn[0], w, ref);
  sb_engine_free(e);

  /* checkpoints: a position outside the box, or not finite */
  char path[] = "/tmp/sb_engine_pos_XXXXXX";
  int fd = mkstemp(path);
  ck_assert_int_ge(fd, 0);
  close(fd);
  const double bad[3] = {-1e-3, 10.0, NAN};
  for (int c = 0; c < 4; c++) {
    e = box_engine(3, 10.0, 0.1, 8);
    sp = add_free(e, 0.5, 1.0);
    ck_assert_int_eq(sb_engine_fill_random(e, sp, 0, 4), SB_SUCCESS);
    if (c > 0)
      e->x[3 * 2 + 1] = bad[c - 1];
    ck_assert_int_eq(sb_engine_checkpoint_save(e, path), SB_SUCCESS);
    sb_engine_free(e);
    int st;
    e = sb_engine_checkpoint_load(path, &st);
    if (c == 0) {
      ck_assert_int_eq(st, SB_SUCCESS);
      sb_engine_free(e);
      continue;
    }
    ck_assert_ptr_null(e);
    ck_assert_int_eq(st, SB_EINVAL);
    ck_assert_msg(strstr(sb_last_error(), "sb_engine_checkpoint_load") &&
                      strstr(sb_last_error(), "particle 2 has x[1]"),
                  "case %d: %s", c, sb_last_error());
  }
  remove(path);
}
END_TEST

/* A fluid callback that returns NaN for the particle ctx names (-1: none)
 * and 1 m/s elsewhere. */
static int fluid_nan_for(size_t n, const double *x, double *us, void *ctx)
{
  (void)x;
  const long *which = ctx;
  for (size_t i = 0; i < n; i++)
    for (int k = 0; k < 3; k++)
      us[3 * i + k] = (long)i == *which && k == 1 ? NAN : 1.0;
  return 0;
}

/* A fluid callback's velocity that is not finite is SB_EINVAL naming the
 * callback, the particle and the component, at the step's transport
 * before anything moved (it went into the step, which then failed with
 * SB_ERANGE "exceeds DBL_MAX", a cause that was not): positions,
 * velocities and time as before, and the engine steps on once the
 * callback is good (2-D and 3-D, both transports). */
START_TEST(test_fluid_callback_nonfinite)
{
  for (int dim = 2; dim <= 3; dim++)
    for (int streams = 0; streams < 2; streams++) {
      sb_engine_params p;
      sb_engine_params_default(&p);
      p.dim = dim;
      p.L[0] = p.L[1] = p.L[2] = 10.0;
      p.dt = 0.1;
      p.capacity = 4;
      p.streams = streams;
      sb_engine *e = sb_engine_alloc(&p);
      ck_assert_ptr_nonnull(e);
      sb_engine_species s = {0.1, 1.0, 1.0, 0.1, 0.0};
      ck_assert_int_eq(sb_engine_add_species(e, &s, NULL), SB_SUCCESS);
      const double xa[3] = {2, 2, 2}, xb[3] = {7, 7, 7}, u[3] = {0, 1, 0};
      ck_assert_int_eq(sb_engine_add_particle(e, 0, 0, xa, u), SB_SUCCESS);
      ck_assert_int_eq(sb_engine_add_particle(e, 0, 0, xb, u), SB_SUCCESS);
      long which = 1;
      ck_assert_int_eq(sb_engine_set_fluid_fn(e, fluid_nan_for, &which),
                       SB_SUCCESS);
      double x0[6], u0[6];
      memcpy(x0, sb_engine_positions(e), sizeof x0);
      memcpy(u0, sb_engine_velocities(e), sizeof u0);
      ck_assert_int_eq(sb_engine_step(e), SB_EINVAL);
      ck_assert_msg(strstr(sb_last_error(), "sb_engine_step: the fluid "
                                            "callback returned the "
                                            "velocity us[1] = nan for "
                                            "particle 1") != NULL,
                    "dim %d, streams %d: %s", dim, streams,
                    sb_last_error());
      ck_assert_mem_eq(sb_engine_positions(e), x0, sizeof x0);
      ck_assert_mem_eq(sb_engine_velocities(e), u0, sizeof u0);
      ck_assert(sb_engine_time(e) == 0.0);
      which = -1;
      ck_assert_int_eq(sb_engine_step(e), SB_SUCCESS);
      ck_assert(sb_engine_time(e) > 0.0);
      sb_engine_free(e);
    }
}
END_TEST

/* The Langevin detector, a Schiller-Naumann species: a collision whose
 * outcome (a custom one, through the internal header) gives j u_x =
 * 1e200 continues j with the nonlinear drag step over the rest of the
 * step, whose rate is then NaN (Re = inf).  That is SB_ERANGE "after a
 * collision" naming the particle, every particle back at its start of
 * step and the engine out of the step (it kept the NaN state with
 * status 0). */
static int outcome_fling(sb_engine *e, const sb_engine_pair *p, double s,
                         void *ctx)
{
  (void)s;
  ++*(int *)ctx;
  e->u[3 * p->j] = 1e200;
  return SB_SUCCESS;
}

START_TEST(test_drag_piece_overflow)
{
  sb_engine_params p;
  sb_engine_params_default(&p);
  p.L[0] = p.L[1] = p.L[2] = 10.0;
  p.dt = 0.1;
  p.capacity = 4;
  p.detect = SB_DETECT_LANGEVIN;
  sb_engine *e = sb_engine_alloc(&p);
  ck_assert_ptr_nonnull(e);
  sb_engine_species s = {0.1, 1.0, 1.0, 0.0, 0.0};  /* B = 0 */
  ck_assert_int_eq(sb_engine_add_species(e, &s, NULL), SB_SUCCESS);
  sb_engine_species_fluid f = {SB_DRAG_SCHILLER_NAUMANN, 1.0, 1e-3};
  ck_assert_int_eq(sb_engine_set_species_fluid(e, 0, &f), SB_SUCCESS);
  int nout = 0;
  ck_assert_int_eq(sb_engine_set_outcome_fn(e, outcome_fling, &nout),
                   SB_SUCCESS);
  /* 0.1 apart at 1 m/s each, head-on: contact early in the step */
  const double xa[3] = {4.85, 5, 5}, xb[3] = {5.15, 5, 5};
  const double ua[3] = {1, 0, 0}, ub[3] = {-1, 0, 0};
  ck_assert_int_eq(sb_engine_add_particle(e, 0, 0, xa, ua), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_add_particle(e, 0, 0, xb, ub), SB_SUCCESS);
  double x0[6], u0[6];
  memcpy(x0, sb_engine_positions(e), sizeof x0);
  memcpy(u0, sb_engine_velocities(e), sizeof u0);
  const int st = sb_engine_step(e);
  ck_assert_int_eq(nout, 1);
  ck_assert_msg(st == SB_ERANGE, "status %d (%s)", st, sb_last_error());
  ck_assert_msg(strstr(sb_last_error(), "after the nonlinear drag step "
                                        "after a collision") &&
                    strstr(sb_last_error(), "particle 1"),
                "%s", sb_last_error());
  ck_assert_mem_eq(sb_engine_positions(e), x0, sizeof x0);
  ck_assert_mem_eq(sb_engine_velocities(e), u0, sizeof u0);
  ck_assert(sb_engine_time(e) == 0.0);
  ck_assert_int_eq(sb_engine_set_dt(e, 0.05), SB_SUCCESS);  /* not in it */
  sb_engine_free(e);
}
END_TEST

/* A fill whose velocity is not finite names the cause (it said "fluid
 * field" whatever it was): the species' velocity spread (B sqrt(tau / 2) =
 * DBL_MAX: a draw beyond one standard deviation overflows), SB_ERANGE as
 * a reinsertion's draw (it was SB_EINVAL), or the fluid callback's
 * output, SB_EINVAL; nothing added. */
START_TEST(test_fill_velocity_cause)
{
  sb_engine *e = box_engine(3, 10.0, 1e-6, 8);
  sb_engine_species s = {0.1, 1.0, 2.0, DBL_MAX, 0.0};
  ck_assert_int_eq(sb_engine_add_species(e, &s, NULL), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_fill_random(e, 0, 0, 8), SB_ERANGE);
  ck_assert(strstr(sb_last_error(), "sb_engine_fill_random") != NULL);
  ck_assert_msg(strstr(sb_last_error(), "velocity spread") != NULL &&
                    strstr(sb_last_error(), "fluid") == NULL,
                "%s", sb_last_error());
  ck_assert_uint_eq(sb_engine_count(e), 0);
  sb_engine_free(e);

  e = box_engine(3, 10.0, 1e-6, 8);
  size_t sp = add_free(e, 0.1, 1.0);
  fluid_after fa = {1, INFINITY};  /* inf from the first call */
  ck_assert_int_eq(sb_engine_set_fluid_fn(e, fluid_after_first, &fa),
                   SB_SUCCESS);
  ck_assert_int_eq(sb_engine_fill_random(e, sp, 0, 2), SB_EINVAL);
  ck_assert_msg(strstr(sb_last_error(), "fluid callback returned the "
                                        "velocity us[0] = inf for a new "
                                        "particle") != NULL,
                "%s", sb_last_error());
  ck_assert_uint_eq(sb_engine_count(e), 0);
  sb_engine_free(e);
}
END_TEST

/* sb_engine_set_dt: a step coefficient beyond DBL_MAX (tau = B = 1e300
 * at dt = 1e300, the species sb_engine_add_species refuses at that dt) is
 * SB_ERANGE naming the species (was SB_EINVAL), dt and the coefficients
 * unchanged; a bad dt is still SB_EINVAL. */
START_TEST(test_set_dt_erange)
{
  sb_engine *e = box_engine(3, 10.0, 1.0, 4);
  sb_engine_species s = {0.1, 1.0, 1e300, 1e300, 1.0};
  ck_assert_int_eq(sb_engine_add_species(e, &s, NULL), SB_SUCCESS);
  const sb_langevin_coef c0 = e->coef[0];
  ck_assert_int_eq(sb_engine_set_dt(e, 1e300), SB_ERANGE);
  ck_assert(strstr(sb_last_error(), "sb_engine_set_dt") != NULL);
  ck_assert(strstr(sb_last_error(), "species 0") != NULL);
  ck_assert(strstr(sb_last_error(), "exceeds DBL_MAX") != NULL);
  ck_assert(sb_engine_get_params(e)->dt == 1.0);
  ck_assert_mem_eq(&e->coef[0], &c0, sizeof c0);
  ck_assert_int_eq(sb_engine_set_dt(e, NAN), SB_EINVAL);
  ck_assert_int_eq(sb_engine_set_dt(e, 0.0), SB_EINVAL);
  ck_assert_int_eq(sb_engine_set_dt(e, 0.5), SB_SUCCESS);
  ck_assert(sb_engine_get_params(e)->dt == 0.5);
  sb_engine_free(e);
}
END_TEST

/* A fill is all or nothing: one that cannot place every particle (no
 * room, or the fluid field fails part-way) leaves the particles, their
 * order and positions and the id counter as they were, and the engine
 * goes on (a fill, steps).  2-D box of 10 x 10, disks of radius 1 (at
 * most ~30 fit): 900 cannot. */
static int fluid_third_fails(size_t n, const double *x, double *us,
                             void *ctx)
{
  (void)x;
  int *calls = ctx;
  for (size_t i = 0; i < n; i++)
    us[3 * i] = us[3 * i + 1] = us[3 * i + 2] = 0.0;
  return ++*calls == 3 ? 5 : 0;
}

START_TEST(test_fill_all_or_nothing)
{
  sb_engine *e = box_engine(2, 10.0, 0.01, 1000);
  size_t sp = add_free(e, 1.0, 1.0);
  ck_assert_int_eq(sb_engine_fill_random(e, sp, 1, 5), SB_SUCCESS);
  ck_assert_uint_eq(sb_engine_count(e), 5);
  double x0[15], u0[15];
  uint64_t id0[5];
  memcpy(x0, sb_engine_positions(e), sizeof x0);
  memcpy(u0, sb_engine_velocities(e), sizeof u0);
  memcpy(id0, sb_engine_ids(e), sizeof id0);
  const double lo[3] = {0, 0, 0}, hi[3] = {10, 5, 0};
  for (int box = 0; box < 2; box++) {
    int st = box ? sb_engine_fill_box(e, sp, 2, 900, lo, hi, NULL)
                 : sb_engine_fill_random(e, sp, 2, 900);
    ck_assert_int_eq(st, SB_EMAXITER);
    ck_assert_uint_eq(sb_engine_count(e), 5);
    ck_assert_mem_eq(sb_engine_positions(e), x0, sizeof x0);
    ck_assert_mem_eq(sb_engine_velocities(e), u0, sizeof u0);
    ck_assert_mem_eq(sb_engine_ids(e), id0, sizeof id0);
  }
  /* the fluid field fails at the third particle of five */
  int calls = 0;
  ck_assert_int_eq(sb_engine_set_fluid_fn(e, fluid_third_fails, &calls),
                   SB_SUCCESS);
  ck_assert_int_eq(sb_engine_fill_random(e, sp, 2, 5), SB_EINVAL);
  ck_assert_int_eq(calls, 3);
  ck_assert_uint_eq(sb_engine_count(e), 5);
  ck_assert_mem_eq(sb_engine_positions(e), x0, sizeof x0);
  ck_assert_int_eq(sb_engine_set_fluid(e, SB_FLUID_REST, NULL), SB_SUCCESS);
  /* the next particle gets the next id of the first fill (5), and the
   * engine steps */
  ck_assert_int_eq(sb_engine_fill_random(e, sp, 3, 2), SB_SUCCESS);
  ck_assert_uint_eq(sb_engine_count(e), 7);
  ck_assert_uint_eq(sb_engine_ids(e)[5], 5);
  ck_assert_uint_eq(sb_engine_ids(e)[6], 6);
  ck_assert_int_eq(sb_engine_families(e)[6], 3);
  ck_assert_uint_eq(sb_engine_check_overlaps(e, 1e-12), 0);
  for (int k = 0; k < 20; k++)
    ck_assert_int_eq(sb_engine_step(e), SB_SUCCESS);
  ck_assert_uint_eq(sb_engine_count(e), 7);
  sb_engine_free(e);
}
END_TEST

/* FNV-1a, 64 bits (Fowler, Noll & Vo): the hash a checkpoint ends with,
 * computed here independently of the library. */
static uint64_t fnv1a(const unsigned char *p, size_t n)
{
  uint64_t h = 0xcbf29ce484222325ULL;
  for (size_t k = 0; k < n; k++)
    h = (h ^ p[k]) * 0x100000001b3ULL;
  return h;
}

static void swap_bytes(unsigned char *p, size_t n)
{
  for (size_t a = 0, b = n - 1; a < b; a++, b--) {
    unsigned char t = p[a];
    p[a] = p[b];
    p[b] = t;
  }
}

/* A checkpoint written on a machine of the other byte order: its header
 * numbers (dimension, L, dt, seed) and the hash at its end byte-swapped,
 * the hash taken over the swapped bytes, as that machine writes it.  The
 * load refuses it with SB_EFORMAT saying so (it used to say "damaged"),
 * by its hash; the same file as version 5 (no hash) by its dimension; a
 * file with one byte changed is still "damaged", and the original loads. */
START_TEST(test_checkpoint_byte_order)
{
  char path[] = "/tmp/sb_engine_bo_XXXXXX";
  int fd = mkstemp(path);
  ck_assert_int_ge(fd, 0);
  close(fd);
  sb_engine *e = box_engine(3, 10.0, 0.1, 8);
  size_t sp = add_free(e, 0.5, 1.0);
  ck_assert_int_eq(sb_engine_fill_random(e, sp, 0, 4), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_checkpoint_save(e, path), SB_SUCCESS);
  sb_engine_free(e);
  FILE *f = fopen(path, "rb");
  ck_assert_ptr_nonnull(f);
  static unsigned char buf[1 << 16], sw[1 << 16];
  const size_t n = fread(buf, 1, sizeof buf, f);
  fclose(f);
  ck_assert(n > 64 && n < sizeof buf && buf[7] == '6');
  /* the parameter block after the magic: int dim (and padding), double
   * L[3], double dt, unsigned long seed */
  memcpy(sw, buf, n);
  swap_bytes(sw + 8, sizeof(int));
  for (int k = 0; k < 5; k++)
    swap_bytes(sw + 16 + 8 * k, 8);
  uint64_t h = fnv1a(sw, n - 8);
  memcpy(sw + n - 8, &h, 8);
  swap_bytes(sw + n - 8, 8);
  const size_t len[3] = {n, n, n - 8};
  for (int c = 0; c < 3; c++) {
    if (c == 1) {  /* one byte changed: damaged, whatever its order */
      sw[n / 2] ^= 1;
    }
    if (c == 2) {  /* version 5: no hash */
      sw[n / 2] ^= 1;
      sw[7] = '5';
    }
    sbt_write_file(path, (const char *)sw, len[c]);
    int st = 0;
    sb_clear_error();
    ck_assert_ptr_null(sb_engine_checkpoint_load(path, &st));
    ck_assert_int_eq(st, SB_EFORMAT);
    ck_assert_msg(strstr(sb_last_error(), c == 1 ? "is damaged"
                                                 : "other byte order"),
                  "case %d: %s", c, sb_last_error());
  }
  sbt_write_file(path, (const char *)buf, n);
  int st = 0;
  e = sb_engine_checkpoint_load(path, &st);
  ck_assert_int_eq(st, SB_SUCCESS);
  sb_engine_free(e);
  remove(path);
}
END_TEST

/* Checkpoints are little-endian on every machine: a big-endian one
 * reverses each number on its way to and from the file.  That path, run
 * here with the order reversed (sbi_engine_checkpoint_save_ord, swap =
 * 1), for both generators whose state it converts (Philox with the
 * tally, the species and a time series; MT19937): the file has the
 * dimension, L, the positions and the hash reversed number by number
 * (checked at their places in the format), and reading it back the same
 * way gives an engine whose checkpoint is the original's byte for byte;
 * the public load refuses it as in the other byte order. */
START_TEST(test_checkpoint_swapped_order)
{
  char le[] = "/tmp/sb_engine_le_XXXXXX", be[] = "/tmp/sb_engine_be_XXXXXX";
  close(mkstemp(le));
  close(mkstemp(be));
  static unsigned char a[1 << 16], b[1 << 16], c[1 << 16];
  for (int gen = 0; gen < 2; gen++) {
    sb_engine_params p;
    sb_engine_params_default(&p);
    p.L[0] = p.L[1] = p.L[2] = 10.0;
    p.dt = 0.05;
    p.capacity = 16;
    p.sample_every = 2;
    p.rng_type = gen ? gsl_rng_mt19937 : sb_rng_philox;
    sb_engine *e = sb_engine_alloc(&p);
    ck_assert_ptr_nonnull(e);
    size_t sp = add_free(e, 0.5, 1.0);
    ck_assert_int_eq(sb_engine_fill_random(e, sp, 0, 12), SB_SUCCESS);
    ck_assert_int_eq(sb_engine_set_count_variance(e, 1), SB_SUCCESS);
    for (int k = 0; k < 9; k++)
      ck_assert_int_eq(sb_engine_step(e), SB_SUCCESS);
    ck_assert_int_eq(sb_engine_checkpoint_save(e, le), SB_SUCCESS);
    ck_assert_int_eq(sbi_engine_checkpoint_save_ord(e, be, 1), SB_SUCCESS);
    sb_engine_free(e);
    FILE *f = fopen(le, "rb"), *g = fopen(be, "rb");
    ck_assert(f && g);
    const size_t n = fread(a, 1, sizeof a, f);
    ck_assert_uint_eq(fread(b, 1, sizeof b, g), n);
    fclose(f);
    fclose(g);
    ck_assert(n > 64 && n < sizeof a && !memcmp(a, b, 8));
    /* the dimension, L[3] and, after the parameters, n, the id counter,
     * the species count and the one species, the positions */
    const size_t at_x = 8 + offsetof(sb_engine_params, streams) + 24 +
                        sizeof(sb_engine_species);
    const size_t at[] = {8, 8 + offsetof(sb_engine_params, L), at_x};
    const size_t count[] = {1, 3, 36}, width[] = {sizeof(int), 8, 8};
    for (int q = 0; q < 3; q++) {
      const size_t o = at[q], w = width[q];
      for (size_t k = 0; k < count[q] * w; k++)
        ck_assert_msg(b[o + k] == a[o + (k / w) * w + w - 1 - k % w],
                      "generator %d: byte %zu", gen, o + k);
    }
    const uint64_t h = fnv1a(b, n - 8);
    for (int k = 0; k < 8; k++)
      ck_assert_uint_eq(b[n - 8 + k], (h >> (8 * (7 - k))) & 0xff);
    int st = -1;
    e = sbi_engine_checkpoint_load_ord(be, 1, &st);
    ck_assert_msg(e != NULL, "generator %d: %s", gen, sb_last_error());
    ck_assert_int_eq(st, SB_SUCCESS);
    ck_assert_int_eq(sb_engine_checkpoint_save(e, be), SB_SUCCESS);
    sb_engine_free(e);
    g = fopen(be, "rb");
    ck_assert_ptr_nonnull(g);
    ck_assert_uint_eq(fread(c, 1, sizeof c, g), n);
    fclose(g);
    ck_assert_msg(!memcmp(a, c, n), "generator %d: the state changed", gen);
    sbt_write_file(be, b, n);  /* the reversed file again */
    ck_assert_ptr_null(sb_engine_checkpoint_load(be, &st));
    ck_assert_int_eq(st, SB_EFORMAT);
    ck_assert_msg(strstr(sb_last_error(), "other byte order"), "%s",
                  sb_last_error());
  }
  remove(le);
  remove(be);
}
END_TEST

/* A checkpoint whose particles share an id (or hold one at or above the
 * id counter) is refused on load, naming the id: ids key the transport
 * streams, the tallies and the saved states beside a checkpoint.  The
 * files are written by the library (a valid hash) from an engine whose
 * ids were changed through the internal header. */
START_TEST(test_checkpoint_bad_ids)
{
  char path[] = "/tmp/sb_engine_ids_XXXXXX";
  int fd = mkstemp(path);
  ck_assert_int_ge(fd, 0);
  close(fd);
  for (int c = 0; c < 3; c++) {
    sb_engine *e = box_engine(3, 10.0, 0.1, 8);
    size_t sp = add_free(e, 0.5, 1.0);
    ck_assert_int_eq(sb_engine_fill_random(e, sp, 0, 4), SB_SUCCESS);
    if (c == 1)
      e->id[3] = e->id[1];  /* two particles of id 1 */
    if (c == 2)
      e->id[2] = 17;  /* the counter is 4 */
    ck_assert_int_eq(sb_engine_checkpoint_save(e, path), SB_SUCCESS);
    sb_engine_free(e);
    int st;
    e = sb_engine_checkpoint_load(path, &st);
    if (c == 0) {
      ck_assert_int_eq(st, SB_SUCCESS);
      ck_assert_ptr_nonnull(e);
      sb_engine_free(e);
      continue;
    }
    ck_assert_ptr_null(e);
    ck_assert_int_eq(st, SB_EINVAL);
    ck_assert_int_eq(sb_last_status(), SB_EINVAL);
    ck_assert_msg(strstr(sb_last_error(), c == 1 ? "two particles have id 1"
                                                 : "has id 17"),
                  "%s", sb_last_error());
    ck_assert_ptr_nonnull(strstr(sb_last_error(),
                                 "sb_engine_checkpoint_load"));
  }
  remove(path);
}
END_TEST

/* The message of an error names the public function the caller entered,
 * not a helper it shares with another one. */
static int fluid_fails(size_t n, const double *x, double *us, void *ctx)
{
  (void)n;
  (void)x;
  (void)us;
  (void)ctx;
  return 7;
}

static void assert_named(const char *func)
{
  const char *m = sb_last_error();
  ck_assert_msg(strncmp(m, func, strlen(func)) == 0 &&
                    m[strlen(func)] == ':',
                "message \"%s\" does not name %s", m, func);
}

START_TEST(test_error_names)
{
  sb_engine *e = box_engine(3, 10.0, 1.0, 8);
  size_t sp = add_free(e, 0.5, 1.0);
  double x[3] = {5, 5, 5}, u[3] = {0, 0, 0};
  /* fill_random through fill_box: it reported itself as fill_box */
  ck_assert_int_eq(sb_engine_fill_random(e, 9, 0, 1), SB_EINVAL);
  assert_named("sb_engine_fill_random");
  ck_assert_int_eq(sb_engine_fill_box(e, 9, 0, 1, x, x, NULL), SB_EINVAL);
  assert_named("sb_engine_fill_box");
  /* the fluid field of the initial velocities: it reported the step */
  ck_assert_int_eq(sb_engine_set_fluid_fn(e, fluid_fails, NULL), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_fill_random(e, sp, 0, 1), SB_EINVAL);
  assert_named("sb_engine_fill_random");
  ck_assert_ptr_nonnull(strstr(sb_last_error(), "fluid callback failed"));
  ck_assert_int_eq(sb_engine_set_fluid(e, SB_FLUID_REST, NULL), SB_SUCCESS);
  /* the neighbour search outside a step: it reported the step */
  ck_assert_int_eq(sb_engine_add_particle(e, sp, 0, x, u), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_add_particle(e, sp, 0, x, u), SB_SUCCESS);
  double disp[6] = {6, 0, 0, 0, 0, 0};
  size_t np;
  const size_t *pairs;
  for (int m = 0; m <= SB_NEIGH_BRUTE; m++) {
    ck_assert_int_eq(sb_engine_neighbours(e, (sb_engine_neigh)m, disp, 0.0,
                                          &np, &pairs), SB_EINVAL);
    assert_named("sb_engine_neighbours");
    ck_assert_ptr_nonnull(strstr(sb_last_error(), "too large"));
  }
  /* run_until: its own name, the step's message after it (whole) */
  double u6[3] = {6, 0, 0};
  ck_assert_int_eq(sb_engine_set_particle(e, 0, x, u6), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_run_until(e, 3.0), SB_EINVAL);
  assert_named("sb_engine_run_until");
  ck_assert_ptr_nonnull(strstr(sb_last_error(), ": sb_engine_step: step "
                                                "too large"));
  /* the first-contact kernel through _get; contact_vn through
   * contact_state */
  sb_engine_firsthit_params fp;
  sb_engine_firsthit_params_default(&fp);
  sb_engine_firsthit *f = sb_engine_firsthit_alloc(&fp);
  ck_assert_ptr_nonnull(f);
  sb_engine_firsthit_kernel_result kr;
  ck_assert_int_eq(sb_engine_firsthit_kernel(f, e, 0, 0, 1.0, 1.0, 0.95,
                                             &kr), SB_EINVAL);
  assert_named("sb_engine_firsthit_kernel");
  sb_engine_firsthit_free(f);
  ck_assert(isnan(sb_engine_contact_vn(e)));
  assert_named("sb_engine_contact_vn");
  /* the Langevin detector through sb_engine_langevin_contact */
  sb_engine_pair pp = {0, 5, {2, 0, 0}, {0, 0, 0}, 1.0, 1.0, 0.0};
  double s;
  ck_assert_int_lt(sb_engine_detect_langevin(e, &pp, sb_engine_rng(e), NULL,
                                             &s), 0);
  assert_named("sb_engine_detect_langevin");
  sb_engine_free(e);
}
END_TEST

/* A save that cannot write its whole file fails with SB_EIO and leaves
 * no partial file (engine_checkpoint.c, sbi_finish_save): the process's
 * file-size limit set to 4 kB (SIGXFSZ ignored, so the write fails with
 * EFBIG) against a checkpoint of 2000 particles; and a save to a device
 * (/dev/null) that succeeds does not touch it. */
START_TEST(test_checkpoint_write_error)
{
  sb_engine *e = box_engine(3, 100.0, 1.0, 2000);
  add_free(e, 0.5, 1.0);
  ck_assert_int_eq(sb_engine_fill_random(e, 0, 0, 2000), SB_SUCCESS);
  char path[] = "/tmp/sb_engine_full_XXXXXX";
  int fd = mkstemp(path);
  ck_assert_int_ge(fd, 0);
  close(fd);
  struct rlimit old, lim;
  ck_assert_int_eq(getrlimit(RLIMIT_FSIZE, &old), 0);
  lim = old;
  lim.rlim_cur = 4096;
  void (*was)(int) = signal(SIGXFSZ, SIG_IGN);
  ck_assert_int_eq(setrlimit(RLIMIT_FSIZE, &lim), 0);
  const int st = sb_engine_checkpoint_save(e, path);
  ck_assert_int_eq(setrlimit(RLIMIT_FSIZE, &old), 0);
  signal(SIGXFSZ, was);
  ck_assert_int_eq(st, SB_EIO);
  ck_assert_msg(access(path, F_OK) != 0, "a partial checkpoint was left");
  ck_assert_int_eq(sb_engine_checkpoint_save(e, path), SB_SUCCESS);
  ck_assert_int_eq(access(path, F_OK), 0);
  remove(path);
  ck_assert_int_eq(sb_engine_checkpoint_save(e, "/dev/null"), SB_SUCCESS);
  ck_assert_int_eq(access("/dev/null", F_OK), 0);
  sb_engine_free(e);
}
END_TEST

/* A custom detector plugs in (the interface the bridge detector of
 * engine_bridge.c uses): here a
 * detector that reports every candidate at s = 1/2 with an extra reach;
 * and a custom outcome that counts calls. */
static int det_all(const sb_engine *e, const sb_engine_pair *p,
                   const gsl_rng *r, void *ctx, double *s)
{
  (void)e;
  (void)r;
  (void)p;
  (*(int *)ctx)++;
  *s = 0.5;
  return 1;
}

static int out_count(sb_engine *e, const sb_engine_pair *p, double s,
                     void *ctx)
{
  (void)e;
  (void)p;
  ck_assert(s == 0.5);
  (*(int *)ctx)++;
  return SB_SUCCESS;
}

START_TEST(test_custom_callbacks)
{
  sb_engine *e = box_engine(3, 20.0, 1.0, 4);
  size_t sp = add_free(e, 0.5, 1.0);
  double x1[3] = {5, 5, 5}, x2[3] = {8, 5, 5}, u[3] = {0, 0, 0};
  sb_engine_add_particle(e, sp, 0, x1, u);
  sb_engine_add_particle(e, sp, 0, x2, u);
  int ndet = 0, nout = 0;
  /* at rest, 3 apart, sigma 1: a candidate only with reach >= 2 */
  ck_assert_int_eq(sb_engine_set_detector(e, det_all, &ndet, 1.0),
                   SB_SUCCESS);
  ck_assert_int_eq(sb_engine_set_outcome_fn(e, out_count, &nout),
                   SB_SUCCESS);
  sb_engine_step(e);
  ck_assert_int_eq(ndet, 0);
  sb_engine_set_detector(e, det_all, &ndet, 2.5);
  sb_engine_step(e);
  ck_assert_int_eq(ndet, 1);
  ck_assert_int_eq(nout, 1);
  sb_engine_free(e);
}
END_TEST

/* An outcome that calls what it must not: the engine refuses inside a
 * step (a nested step ran 1075 steps; run_until overflowed the stack). */
static int out_reenter(sb_engine *e, const sb_engine_pair *p, double s,
                       void *ctx)
{
  (void)p;
  (void)s;
  int *st = ctx;
  const double x[3] = {1, 1, 1}, u[3] = {0, 0, 0};
  st[0] = sb_engine_step(e);
  st[1] = sb_engine_run_until(e, 100.0);
  st[2] = sb_engine_set_dt(e, 1e-3);
  st[3] = sb_engine_add_particle(e, 0, 0, x, u);
  st[4] = sb_engine_sort(e);
  st[5] = sb_engine_flush_removals(e);
  st[6]++;
  return sb_engine_outcome_elastic(e, p, s);
}

START_TEST(test_misuse)
{
  /* 1. re-entry from a callback: SB_EINVAL each, the step goes on */
  sb_engine *e = box_engine(3, 20.0, 1.0, 8);
  size_t sp = add_free(e, 0.5, 1.0);
  double x1[3] = {5, 5, 5}, x2[3] = {6.5, 5, 5}, u1[3] = {1, 0, 0},
         u2[3] = {0, 0, 0};
  sb_engine_add_particle(e, sp, 0, x1, u1);
  sb_engine_add_particle(e, sp, 0, x2, u2);
  int st[7] = {0};
  ck_assert_int_eq(sb_engine_set_outcome_fn(e, out_reenter, st), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_step(e), SB_SUCCESS);
  ck_assert_int_eq(st[6], 1);
  for (int k = 0; k < 6; k++)
    ck_assert_msg(st[k] == SB_EINVAL, "call %d: status %d", k, st[k]);
  ck_assert(sb_engine_time(e) == 1.0);
  ck_assert_uint_eq(sb_engine_count(e), 2);
  /* 2. an inflow far beyond the capacity: an error at once (a rate of
   * 1e30/s hung in GSL's Poisson draw) */
  sb_engine_inflow in = {0, sp, 0, 1e30, {0, 0}, {20, 20}, {1, 0, 0}, 0};
  ck_assert_int_eq(sb_engine_add_inflow(e, &in, NULL), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_set_outcome(e, SB_OUTCOME_ELASTIC, 1.0),
                   SB_SUCCESS);
  ck_assert_int_eq(sb_engine_step(e), SB_EINVAL);
  ck_assert_ptr_nonnull(strstr(sb_last_error(), "capacity 8 is full"));
  /* 3. sizes whose products wrap in size_t */
  const size_t big[3] = {(size_t)1 << 24, (size_t)1 << 24, (size_t)1 << 16};
  double cell = 0;
  ck_assert_int_eq(sb_engine_grid_fields(e, big, SB_GRID_NGP, -1, &cell,
                                         NULL), SB_EINVAL);
  gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
  ck_assert_ptr_null(sb_field_ou_alloc(((size_t)1 << 61) + 1, 1, 1, 1e-6, r));
  gsl_rng_free(r);
  sb_engine_bridge_params bp;
  sb_engine_bridge_params_default(&bp);
  bp.record_cap = ((size_t)1 << 60) + 1;
  ck_assert_ptr_null(sb_engine_bridge_alloc(&bp));
  sb_engine_bridge *b = sb_engine_bridge_alloc(NULL);
  ck_assert_ptr_nonnull(b);
  ck_assert_int_eq(sb_engine_bridge_set_b2(b, (size_t)-1, 1e-12, 0),
                   SB_EINVAL);
  sb_engine_bridge_free(b);
  /* 4. a pair of one particle, a path that is not finite */
  sb_engine_pair self = {0, 0, {0, 0, 0}, {0, 0, 0}, 1.0, 1.0, 0.0};
  ck_assert_int_eq(sb_engine_outcome_elastic(e, &self, 0.5), SB_EINVAL);
  ck_assert_int_eq(sb_engine_outcome_reinsert(e, &self, 0.5), SB_EINVAL);
  const double xnan[3] = {NAN, 0, 0};
  ck_assert_int_eq(sb_engine_outcome_path(e, 0, xnan), SB_EINVAL);
  /* 5. NULL where it crashed */
  double sfrac;
  ck_assert_int_lt(sb_engine_detect_md(e, NULL, NULL, NULL, &sfrac), 0);
  sb_engine_firsthit_params_default(NULL);
  sb_field_kraichnan_eval(NULL, 0.0, 1, x1, u1);
  ck_assert_int_eq(sb_last_status(), SB_EINVAL);
  /* 6. every public function of the engine headers that takes a pointer
   * records SB_EINVAL for a NULL one (and returns its documented failure
   * value); none returned without an error before */
#define NULL_EINVAL(call)                                                  \
  do {                                                                     \
    sb_clear_error();                                                      \
    (void)(call);                                                          \
    ck_assert_msg(sb_last_status() == SB_EINVAL, "%s: status %d (\"%s\")", \
                  #call, sb_last_status(), sb_last_error());               \
  } while (0)
  sb_engine_pair pp = {0, 1, {2, 0, 0}, {0, 0, 0}, 1.0, 1.0, 0.0};
  gsl_rng *g = sb_engine_rng(e);
  size_t nn = 7;
  ck_assert_int_lt(sb_engine_pair_can_meet(NULL, NULL, 0.0, 0, 1), 0);
  NULL_EINVAL(sb_engine_pair_can_meet(NULL, NULL, 0.0, 0, 1));
  ck_assert_ptr_nonnull(strstr(sb_last_error(), "sb_engine_pair_can_meet"));
  ck_assert_int_lt(sb_engine_pair_can_meet(e, NULL, 0.0, 0, 0), 0);
  ck_assert_int_lt(sb_engine_pair_can_meet(e, NULL, 0.0, 0, 2), 0);
  ck_assert_int_lt(sb_engine_pair_can_meet(e, NULL, NAN, 0, 1), 0);
  ck_assert_int_ge(sb_engine_pair_can_meet(e, NULL, 0.0, 0, 1), 0);
  NULL_EINVAL(sb_engine_params_default(NULL));
  NULL_EINVAL(sb_engine_langevin_params_default(NULL));
  NULL_EINVAL(sb_engine_bridge_params_default(NULL));
  NULL_EINVAL(sb_agglo_params_default(NULL));
  NULL_EINVAL(sb_engine_firsthit_params_default(NULL));
  ck_assert_ptr_null(sb_engine_get_params(NULL));
  NULL_EINVAL(sb_engine_get_params(NULL));
  NULL_EINVAL(sb_engine_get_species(NULL, 0));
  ck_assert_uint_eq(sb_engine_species_count(NULL), 0);
  NULL_EINVAL(sb_engine_species_count(NULL));
  /* past the last species: NULL, the end-of-list sentinel, no error */
  {
    const size_t ns = sb_engine_species_count(e);
    ck_assert_uint_ge(ns, 1);
    ck_assert_ptr_nonnull(sb_engine_get_species(e, ns - 1));
    sb_clear_error();
    ck_assert_ptr_null(sb_engine_get_species(e, ns));
    ck_assert_ptr_null(sb_engine_get_species(e, SIZE_MAX));
    ck_assert_int_eq(sb_last_status(), SB_SUCCESS);
  }
  ck_assert(isnan(sb_engine_kinetic_energy(NULL, NULL)));
  NULL_EINVAL(sb_engine_kinetic_energy(NULL, NULL));
  ck_assert_uint_eq(sb_engine_count(NULL), 0);
  NULL_EINVAL(sb_engine_count(NULL));
  ck_assert(isnan(sb_engine_time(NULL)));
  NULL_EINVAL(sb_engine_time(NULL));
  NULL_EINVAL(sb_engine_positions(NULL));
  NULL_EINVAL(sb_engine_velocities(NULL));
  NULL_EINVAL(sb_engine_start_positions(NULL));
  NULL_EINVAL(sb_engine_start_velocities(NULL));
  NULL_EINVAL(sb_engine_radii(NULL));
  NULL_EINVAL(sb_engine_masses(NULL));
  NULL_EINVAL(sb_engine_species_of(NULL));
  NULL_EINVAL(sb_engine_families(NULL));
  NULL_EINVAL(sb_engine_ids(NULL));
  ck_assert_ptr_null(sb_engine_rng(NULL));
  NULL_EINVAL(sb_engine_rng(NULL));
  NULL_EINVAL(sb_engine_reset_counters(NULL));
  NULL_EINVAL(sb_engine_get_count_variance(NULL));
  ck_assert_ptr_null(sb_engine_series(NULL, &nn));
  ck_assert_uint_eq(nn, 0);
  NULL_EINVAL(sb_engine_series(NULL, NULL));
  NULL_EINVAL(sb_engine_check_overlaps(NULL, 0.0));
  NULL_EINVAL(sb_engine_lees_edwards_offset(NULL));
  NULL_EINVAL(sb_engine_deposits(NULL, 0));
  NULL_EINVAL(sb_engine_periodic(NULL, 0));
  NULL_EINVAL(sb_engine_ninflows(NULL));
  NULL_EINVAL(sb_engine_inflow_injected(NULL, 0));
  NULL_EINVAL(sb_engine_inflow_skipped(NULL, 0));
  NULL_EINVAL(sb_engine_outflows(NULL, 0));
  ck_assert_int_lt(sb_engine_detect_ballistic(NULL, &sfrac), 0);
  NULL_EINVAL(sb_engine_detect_ballistic(&pp, NULL));
  NULL_EINVAL(sb_engine_detect_overlap(NULL, &sfrac));
  NULL_EINVAL(sb_engine_detect_md(NULL, &pp, g, NULL, &sfrac));
  NULL_EINVAL(sb_engine_detect_md(e, NULL, g, NULL, &sfrac));
  ck_assert_int_lt(sb_engine_detect_none(NULL, &pp, g, NULL, &sfrac), 0);
  NULL_EINVAL(sb_engine_detect_none(NULL, &pp, g, NULL, &sfrac));
  NULL_EINVAL(sb_engine_detect_langevin(NULL, &pp, g, NULL, &sfrac));
  NULL_EINVAL(sb_engine_langevin_contact(e, &pp, NULL, &sfrac, NULL));
  NULL_EINVAL(sb_engine_detect_bridge(e, &pp, g, NULL, &sfrac));
  NULL_EINVAL(sb_engine_outcome_bridge(e, &pp, 0.5, NULL));
  NULL_EINVAL(sb_engine_bridge_reset(NULL));
  NULL_EINVAL(sb_engine_bridge_hits(NULL, NULL));
  ck_assert(isnan(sb_engine_chord_vn(NULL, &pp, 0.5)));
  NULL_EINVAL(sb_engine_chord_vn(e, NULL, 0.5));
  NULL_EINVAL(sb_engine_firsthit_warmup(NULL));
  NULL_EINVAL(sb_agglo_size_of_species(NULL, 0));
  NULL_EINVAL(sb_agglo_reset_stats(NULL));
  NULL_EINVAL(sb_agglo_series(NULL, NULL, NULL));
  NULL_EINVAL(sb_field_ou_seen(NULL));
  NULL_EINVAL(sb_field_kraichnan_modes(NULL));
  ck_assert(isnan(sb_field_kraichnan_u2(NULL)));
  NULL_EINVAL(sb_field_kraichnan_a11(NULL));
  NULL_EINVAL(sb_field_kraichnan_flux_kernel(NULL, 1.0));
#undef NULL_EINVAL
  sb_engine_free(e);
}
END_TEST

static Suite *suite(void)
{
  Suite *s = suite_create("engine");
  TCase *tc = tcase_create("core");
  tcase_set_timeout(tc, 30);
  tcase_add_test(tc, test_45deg_3d);
  tcase_add_test(tc, test_45deg_2d);
  tcase_add_test(tc, test_45deg_same_speed);
  tcase_add_test(tc, test_inelastic_unequal);
  tcase_add_test(tc, test_conservation);
  tcase_add_test(tc, test_chain_in_one_step);
  tcase_add_test(tc, test_dense_many_per_step);
  tcase_add_test(tc, test_methods_agree);
  tcase_add_test(tc, test_checkpoint_roundtrip);
  tcase_add_test(tc, test_sort_permutes);
  tcase_add_test(tc, test_streams_threads_and_order);
  tcase_add_test(tc, test_streams_transport_is_step3_stream);
  tcase_add_test(tc, test_fluid_fields);
  tcase_add_test(tc, test_fluid_callback_2d);
  tcase_add_test(tc, test_detectors);
  tcase_add_test(tc, test_kernel_estimate);
  tcase_add_test(tc, test_errors);
  tcase_add_test(tc, test_species_extreme);
  tcase_add_test(tc, test_one_particle_step_checked);
  tcase_add_test(tc, test_after_transport_overflow);
  tcase_add_test(tc, test_reinsert_overflow);
  tcase_add_test(tc, test_fill_velocity_cause);
  tcase_add_test(tc, test_wrap_far_position);
  tcase_add_test(tc, test_fluid_callback_nonfinite);
  tcase_add_test(tc, test_drag_piece_overflow);
  tcase_add_test(tc, test_set_dt_erange);
  tcase_add_test(tc, test_error_names);
  tcase_add_test(tc, test_fill_all_or_nothing);
  tcase_add_test(tc, test_checkpoint_bad_ids);
  tcase_add_test(tc, test_checkpoint_byte_order);
  tcase_add_test(tc, test_checkpoint_swapped_order);
  tcase_add_test(tc, test_checkpoint_write_error);
  tcase_add_test(tc, test_custom_callbacks);
  tcase_add_test(tc, test_misuse);
  suite_add_tcase(s, tc);
  return s;
}

int main(void) { return sbt_run_suite(suite()); }
