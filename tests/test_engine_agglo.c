/* test_engine_agglo.c — agglomeration in the engine: particle
 * removal, the merge outcome (conservation, barycentre, sizes, growth
 * laws), the size observers, the DLVO sticking fraction, a small
 * constant-kernel run against the analytic Smoluchowski solution, and a
 * merging run that goes on from a checkpoint as if it had not stopped.
 *
 * Units: unit-free (the engine only needs consistent units).  Gas tests:
 * diameter 1, primary mass 1, k_B T / m = 1 (species T = 1/k_B).
 */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <smolbridge/engine.h>
#include <smolbridge/engine_bridge.h>
#include <smolbridge/dlvo.h>
#include <smolbridge/langevin.h>
#include <smolbridge/pbe.h>
#include <smolbridge/stats.h>

#include "engine/engine_internal.h"
#include "engine_same.h"
#include "testutil.h"

#define PI 3.14159265358979323846

static sb_engine *box(double L, double dt, size_t cap, unsigned long seed)
{
  sb_engine_params p;
  sb_engine_params_default(&p);
  p.L[0] = p.L[1] = p.L[2] = L;
  p.dt = dt;
  p.capacity = cap;
  p.seed = seed;
  sb_engine *e = sb_engine_alloc(&p);
  ck_assert_ptr_nonnull(e);
  return e;
}

/* free-flight primary: radius 0.5, mass 1, k_B T/m = 1 */
static void add_gas_species(sb_engine *e)
{
  sb_engine_species s = {0.5, 1.0, INFINITY, 0.0, 1.0 / SB_BOLTZMANN};
  ck_assert_int_eq(sb_engine_add_species(e, &s, NULL), SB_SUCCESS);
}

static sb_agglo *agglo(sb_engine *e, sb_agglo_growth g, sb_agglo_rule rule,
                       double wmax)
{
  sb_agglo_params ap;
  sb_agglo_params_default(&ap);
  ap.growth = g;
  ap.rule = rule;
  ap.wmax = wmax;
  sb_agglo *a = sb_agglo_alloc(&ap);
  ck_assert_ptr_nonnull(a);
  ck_assert_int_eq(sb_agglo_attach(e, a), SB_SUCCESS);
  return a;
}

/* Removal: stable compaction, ids kept. */
START_TEST(test_remove)
{
  sb_engine *e = box(100.0, 1e-3, 8, 1);
  add_gas_species(e);
  for (int k = 0; k < 5; k++) {
    double x[3] = {10.0 * k + 1, 5, 5}, u[3] = {k, 0, 0};
    ck_assert_int_eq(sb_engine_add_particle(e, 0, 0, x, u), SB_SUCCESS);
  }
  ck_assert_int_eq(sb_engine_remove_particle(e, 1), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_remove_particle(e, 3), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_remove_particle(e, 3), SB_SUCCESS); /* twice */
  ck_assert_uint_eq(sb_engine_count(e), 5);  /* deferred */
  ck_assert_int_eq(sb_engine_flush_removals(e), SB_SUCCESS);
  ck_assert_uint_eq(sb_engine_count(e), 3);
  const uint64_t *id = sb_engine_ids(e);
  const double *x = sb_engine_positions(e), *u = sb_engine_velocities(e);
  ck_assert(id[0] == 0 && id[1] == 2 && id[2] == 4);
  ck_assert_abs(x[3 * 1], 21.0, 0.0);
  ck_assert_abs(u[3 * 2], 4.0, 0.0);
  ck_assert_int_ne(sb_engine_remove_particle(e, 3), SB_SUCCESS);
  sb_engine_free(e);
}
END_TEST

/* Head-on pair, then the pair (mass 2) with a third particle (mass 1):
 * momentum, mass, barycentre and size after each merge, across the
 * periodic boundary for the second one. */
START_TEST(test_merge_pair)
{
  const double L = 20.0, dt = 0.01;
  sb_engine *e = box(L, dt, 4, 2);
  add_gas_species(e);
  double xa[3] = {5.0, 5.0, 5.0}, ua[3] = {1.0, 0.3, -0.2};
  double xb[3] = {6.05, 5.1, 5.0}, ub[3] = {-1.5, 0.1, 0.4};
  ck_assert_int_eq(sb_engine_add_particle(e, 0, 0, xa, ua), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_add_particle(e, 0, 0, xb, ub), SB_SUCCESS);
  double xc[3] = {L - 0.3, 5.5, 5.0}, uc[3] = {1.0, 0.0, 0.0};
  ck_assert_int_eq(sb_engine_add_particle(e, 0, 1, xc, uc), SB_SUCCESS);
  sb_agglo *a = agglo(e, SB_AGGLO_STOKES, SB_AGGLO_MERGE, 0.0);
  double p0[3];
  sb_engine_kinetic_energy(e, p0);
  /* contact of a and b within the first step(s) */
  int steps = 0;
  while (sb_engine_count(e) == 3 && steps < 100) {
    ck_assert_int_eq(sb_engine_step(e), SB_SUCCESS);
    steps++;
  }
  ck_assert_uint_eq(sb_engine_count(e), 2);
  /* free flight: barycentre of the end positions, independently */
  double t = steps * dt;
  const double *x = sb_engine_positions(e), *u = sb_engine_velocities(e);
  const double *m = sb_engine_masses(e), *r = sb_engine_radii(e);
  ck_assert_abs(m[0], 2.0, 0.0);
  ck_assert_rel(r[0], 0.5 * cbrt(2.0), TOL_TIGHT);
  for (int k = 0; k < 3; k++) {
    double want = 0.5 * (xa[k] + ua[k] * t + xb[k] + ub[k] * t);
    ck_assert_rel(x[k], want, 1e-12);
    ck_assert_rel(u[k], 0.5 * (ua[k] + ub[k]), 1e-14);
  }
  ck_assert_uint_eq(sb_agglo_size_of_species(a, sb_engine_species_of(e)[0]),
                    2);
  ck_assert_uint_eq(sb_engine_ids(e)[1], 2);
  /* second merge, across x = 0 = L: push the cluster towards -x */
  double xd[3] = {1.5, 5.5, 5.0}, ud[3] = {-1.0, 0.0, 0.5};
  ck_assert_int_eq(sb_engine_set_particle(e, 0, xd, ud), SB_SUCCESS);
  double xc2[3];  /* c moved during the first phase */
  memcpy(xc2, &sb_engine_positions(e)[3], sizeof xc2);
  double q0[3];
  sb_engine_kinetic_energy(e, q0);
  steps = 0;
  while (sb_engine_count(e) == 2 && steps < 100) {
    ck_assert_int_eq(sb_engine_step(e), SB_SUCCESS);
    steps++;
  }
  ck_assert_uint_eq(sb_engine_count(e), 1);
  t = steps * dt;
  x = sb_engine_positions(e);
  u = sb_engine_velocities(e);
  double q1[3];
  sb_engine_kinetic_energy(e, q1);
  for (int k = 0; k < 3; k++)
    ck_assert_abs(q1[k], q0[k], 1e-12 * (fabs(q0[k]) + 3.0));
  /* barycentre (2 xd' + 1 xc')/3 with xc' the image next to xd' */
  ck_assert(xc2[0] > 0.5 * L);  /* c is still on the far side */
  double w0 = xd[0] + ud[0] * t, w2 = (xc2[0] - L) + uc[0] * t;
  double bx = (2.0 * w0 + w2) / 3.0;
  bx -= L * floor(bx / L);
  ck_assert_rel(x[0], bx, 1e-12);
  ck_assert_rel(x[1], (2.0 * (xd[1] + ud[1] * t) + xc2[1]) / 3.0, 1e-12);
  ck_assert_abs(sb_engine_masses(e)[0], 3.0, 0.0);
  ck_assert_uint_eq(sb_agglo_size_of_species(a, sb_engine_species_of(e)[0]),
                    3);
  sb_agglo_stats st;
  sb_agglo_get_stats(a, &st);
  ck_assert_uint_eq(st.nmerge, 2);
  (void)p0;
  sb_agglo_free(a);
  sb_engine_free(e);
}
END_TEST

/* Outside a step sb_agglo_merge merges at the current positions (not an
 * error: no message is left behind), across the periodic boundary; the
 * partner goes with sb_engine_flush_removals.  Mass, momentum and the
 * barycentre by hand. */
START_TEST(test_merge_outside_step)
{
  const double L = 20.0;
  sb_engine *e = box(L, 0.01, 4, 5);
  add_gas_species(e);
  double xa[3] = {0.3, 5.0, 5.0}, ua[3] = {1.0, 0.3, -0.2};
  double xb[3] = {L - 0.6, 5.2, 5.0}, ub[3] = {-1.5, 0.1, 0.4};
  ck_assert_int_eq(sb_engine_add_particle(e, 0, 0, xa, ua), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_add_particle(e, 0, 0, xb, ub), SB_SUCCESS);
  sb_agglo *a = agglo(e, SB_AGGLO_STOKES, SB_AGGLO_MERGE, 0.0);
  sb_engine_pair p;
  memset(&p, 0, sizeof p);
  p.i = 0;
  p.j = 1;
  p.dx0[0] = xa[0] - (xb[0] - L);  /* the image of b next to a */
  p.dx0[1] = xa[1] - xb[1];
  p.sigma = 1.0;
  p.dt = 0.01;
  sb_clear_error();
  ck_assert_int_eq(sb_agglo_merge(e, a, &p, 0.5), SB_SUCCESS);
  ck_assert_msg(sb_last_status() == SB_SUCCESS, "message left: %s",
                sb_last_error());
  ck_assert_uint_eq(sb_engine_count(e), 2);  /* b is marked */
  ck_assert_int_eq(sb_engine_flush_removals(e), SB_SUCCESS);
  ck_assert_uint_eq(sb_engine_count(e), 1);
  const double *x = sb_engine_positions(e), *u = sb_engine_velocities(e);
  ck_assert_abs(sb_engine_masses(e)[0], 2.0, 0.0);
  ck_assert_uint_eq(sb_engine_ids(e)[0], 0);
  double bx = 0.5 * (xa[0] + xb[0] - L);
  bx -= L * floor(bx / L);
  ck_assert_rel(x[0], bx, 1e-14);
  ck_assert_rel(x[1], 0.5 * (xa[1] + xb[1]), 1e-14);
  for (int k = 0; k < 3; k++)
    ck_assert_abs(u[k], 0.5 * (ua[k] + ub[k]), 1e-15);
  ck_assert_uint_eq(sb_agglo_size_of_species(a, sb_engine_species_of(e)[0]),
                    2);
  /* the species of size 2 was created: two species now */
  ck_assert_uint_eq(sb_engine_species_count(e), 2);
  ck_assert_ptr_nonnull(sb_engine_get_species(e, 1));
  /* still an error: a pair with itself */
  p.j = 0;
  ck_assert_int_eq(sb_agglo_merge(e, a, &p, 0.5), SB_EINVAL);
  sb_agglo_free(a);
  sb_engine_free(e);
}
END_TEST

/* Growth laws: STOKES species of size k follow r ~ k^(1/3), m ~ k,
 * D = (B tau)^2/2 ~ k^(-1/3) (Stokes-Einstein) and equipartition
 * m B^2 tau/2 = k_B T; CONSTANT keeps r, tau, B. */
START_TEST(test_growth)
{
  sb_engine *e = box(10.0, 1e-3, 4, 3);
  sb_engine_species s = {0.5, 2.0, 0.1, 3.0, 0.0};
  ck_assert_int_eq(sb_engine_add_species(e, &s, NULL), SB_SUCCESS);
  sb_agglo *a = agglo(e, SB_AGGLO_STOKES, SB_AGGLO_MERGE, 0.0);
  const double D1 = 0.5 * pow(s.B * s.tau, 2), E1 = s.mass * s.B * s.B *
                                                  s.tau;
  for (size_t k = 2; k <= 64; k *= 2) {
    size_t sp;
    ck_assert_int_eq(sb_agglo_species_of_size(a, e, k, &sp), SB_SUCCESS);
    const sb_engine_species *q = sb_engine_get_species(e, sp);
    double kd = (double)k;
    ck_assert_rel(q->radius, 0.5 * pow(kd, 1.0 / 3.0), 1e-14);
    ck_assert_rel(q->mass, 2.0 * kd, 1e-15);
    ck_assert_rel(0.5 * pow(q->B * q->tau, 2), D1 * pow(kd, -1.0 / 3.0),
                  1e-13);
    ck_assert_rel(q->mass * q->B * q->B * q->tau, E1, 1e-13);
    ck_assert_uint_eq(sb_agglo_size_of_species(a, sp), k);
    size_t sp2;  /* found again, not re-created */
    sb_agglo_species_of_size(a, e, k, &sp2);
    ck_assert_uint_eq(sp, sp2);
  }
  sb_agglo_free(a);
  sb_agglo_params ap;
  sb_agglo_params_default(&ap);
  ap.growth = SB_AGGLO_CONSTANT;
  ap.kmax = 5;
  a = sb_agglo_alloc(&ap);
  ck_assert_int_eq(sb_agglo_attach(e, a), SB_SUCCESS);
  size_t sp;
  ck_assert_int_eq(sb_agglo_species_of_size(a, e, 5, &sp), SB_SUCCESS);
  const sb_engine_species *q = sb_engine_get_species(e, sp);
  ck_assert(q->radius == s.radius && q->tau == s.tau && q->B == s.B);
  ck_assert_rel(q->mass, 10.0, 1e-15);
  ck_assert_int_eq(sb_agglo_species_of_size(a, e, 6, &sp), SB_EINVAL);
  sb_agglo_free(a);
  sb_engine_free(e);
}
END_TEST

/* A dense free-flight gas with merging: after many merges the number of
 * primaries (M1) and the total mass are exact, the total momentum is
 * conserved to 1e-12 of sum |m u|, sum_k k n_k = M1 and the histogram
 * agrees with the moments. */
START_TEST(test_merge_conservation)
{
  const size_t N = 400;
  sb_engine *e = box(cbrt(N * PI / 6.0 / 0.05), 0.02, N, 4);
  add_gas_species(e);
  ck_assert_int_eq(sb_engine_fill_random(e, 0, 0, N), SB_SUCCESS);
  sb_agglo *a = agglo(e, SB_AGGLO_STOKES, SB_AGGLO_MERGE, 0.0);
  double p0[3], scale = 0.0;
  sb_engine_kinetic_energy(e, p0);
  const double *u0 = sb_engine_velocities(e);
  for (size_t i = 0; i < 3 * N; i++)
    scale += fabs(u0[i]);
  ck_assert_int_eq(sb_engine_run_until(e, 4.0), SB_SUCCESS);
  sb_agglo_stats st;
  sb_agglo_get_stats(a, &st);
  ck_assert_uint_gt(st.nmerge, N / 2);  /* many merges happened */
  ck_assert_uint_eq(sb_engine_count(e) + st.nmerge, N);
  double m[3], nk[1000], tail, p1[3], M = 0.0;
  ck_assert_int_eq(sb_agglo_moments(a, e, m), SB_SUCCESS);
  ck_assert_abs(m[0], (double)sb_engine_count(e), 0.0);
  ck_assert_abs(m[1], (double)N, 0.0);
  ck_assert_int_eq(sb_agglo_count_sizes(a, e, 1000, nk, &tail), SB_SUCCESS);
  ck_assert_abs(tail, 0.0, 0.0);
  double s0 = 0, s1 = 0, s2 = 0;
  for (size_t k = 1; k <= 1000; k++) {
    s0 += nk[k - 1];
    s1 += k * nk[k - 1];
    s2 += (double)k * k * nk[k - 1];
  }
  ck_assert(s0 == m[0] && s1 == m[1] && s2 == m[2]);
  const double *mass = sb_engine_masses(e);
  for (size_t i = 0; i < sb_engine_count(e); i++)
    M += mass[i];
  ck_assert_rel(M, (double)N, 1e-13);
  sb_engine_kinetic_energy(e, p1);
  for (int k = 0; k < 3; k++)
    ck_assert_abs(p1[k], p0[k], 1e-12 * scale);
  /* the time series */
  ck_assert_int_eq(sb_agglo_sample(a, e), SB_SUCCESS);
  size_t nr, nc;
  const double *row = sb_agglo_series(a, &nr, &nc);
  ck_assert_uint_eq(nr, 1);
  ck_assert_uint_eq(nc, 14);
  ck_assert(row[1] == m[0] && row[4] == nk[0] && row[13] == nk[9]);
  sb_agglo_free(a);
  sb_engine_free(e);
}
END_TEST

/* DLVO sticking fraction, ballistic free-flight gas at k_B T/m = 1 with a
 * barrier W_max = x k_B T (CONSTANT growth: the radius stays 1).  Pairs
 * met at contact have E_rel ~ Gamma(2, k_B T) (flux-weighted law,
 * <smolbridge/dlvo.h>), so psi = Q(x) = (1 + x) e^-x; for the normal part
 * Gamma(1): e^-x.  Sticking removes the fast particles (they collide
 * more) and the free-flight gas has no thermostat, so it cools: the
 * measurement uses a short run in which only ~5% of the particles
 * collide (kinetic energy per cluster still 0.98 of 3/2 k_B T; run to
 * t = 10 instead, psi(1.5) falls to 0.41).  Sample: N = 40000 at volume
 * fraction 0.03 to t = 0.25, about 2100 decisions per x; pass: the
 * reference lies in the Clopper-Pearson 99.9% interval of psi (about
 * +-0.035). */
static void sticking(double x, int normal, unsigned long seed)
{
  const size_t N = 40000;
  const double phi = 0.03;
  sb_engine *e = box(cbrt(N * PI / 6.0 / phi), 0.01, N, seed);
  add_gas_species(e);
  ck_assert_int_eq(sb_engine_fill_random(e, 0, 0, N), SB_SUCCESS);
  sb_agglo_params ap;
  sb_agglo_params_default(&ap);
  ap.growth = SB_AGGLO_CONSTANT;
  ap.rule = SB_AGGLO_DLVO;
  ap.wmax = x; /* k_B T = m (k_B T/m) = 1 */
  ap.erel_normal = normal;
  sb_agglo *a = sb_agglo_alloc(&ap);
  ck_assert_int_eq(sb_agglo_attach(e, a), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_run_until(e, 0.25), SB_SUCCESS);
  sb_agglo_stats st;
  sb_agglo_get_stats(a, &st);
  unsigned long n = st.nmerge + st.nrebound;
  double lo, hi;
  ck_assert_int_eq(sb_binomial_ci(st.nmerge, n, 0.999, &lo, &hi),
                   SB_SUCCESS);
  double want = sb_dlvo_erel_Q(ap.wmax, 1.0,
                               normal ? SB_DLVO_EREL_COLLISION_NORMAL
                                      : SB_DLVO_EREL_COLLISION,
                               3);
  ck_assert_msg(n > 1800, "only %lu decisions", n);
  ck_assert_msg(lo <= want && want <= hi,
                "x = %g normal = %d: psi = %lu/%lu = %.4f, [%.4f, %.4f], "
                "predicted %.4f", x, normal, st.nmerge, n,
                (double)st.nmerge / n, lo, hi, want);
  sb_agglo_free(a);
  sb_engine_free(e);
}

START_TEST(test_dlvo_sticking)
{
  sticking(1.5, 0, 11);
  sticking(1.0, 1, 12);
}
END_TEST

/* Stationary E_rel law (diffusive regime): for a pair of a primary (mass
 * 1) and a cluster of 3 (mass 3), both at k_B T/m equilibrium (variance
 * 1/m per component, species T = 1/k_B), theta = mu (1/m_i + 1/m_j) = 1
 * and E_rel ~ Gamma(3/2, 1): mean 3/2, variance 3/2.  Sample: 20000 draws;
 * pass: |mean - 3/2| <= 3.29 sqrt(1.5/20000) (99.9%, normal limit) and the
 * KS p-value against the Gamma(3/2) CDF of sb_dlvo_erel_P is >= 0.001. */
static double cdf_g32(double x, void *par)
{
  (void)par;
  return sb_dlvo_erel_P(x, 1.0, SB_DLVO_EREL_STATIONARY, 3);
}

/* An error of sb_agglo_erel_of names it, not the dlvo sampler it calls
 * (sb_dlvo_erel_sample): an energy scale mu (s_i^2 + s_j^2) that
 * overflows (velocity scale set to 1e300 m/s through the internal
 * header) is NaN and SB_ERANGE from sb_agglo_erel_of. */
START_TEST(test_erel_error_name)
{
  sb_engine *e = box(20.0, 0.01, 4, 21);
  add_gas_species(e);
  sb_agglo_params ap;
  sb_agglo_params_default(&ap);
  ap.rule = SB_AGGLO_DLVO;
  ap.erel = SB_AGGLO_EREL_STATIONARY;
  sb_agglo *a = sb_agglo_alloc(&ap);
  ck_assert_int_eq(sb_agglo_attach(e, a), SB_SUCCESS);
  double x0[3] = {1, 1, 1}, x1[3] = {5, 5, 5}, u[3] = {0, 0, 0};
  ck_assert_int_eq(sb_engine_add_particle(e, 0, 0, x0, u), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_add_particle(e, 0, 0, x1, u), SB_SUCCESS);
  sb_engine_pair p = {0, 1, {-4, -4, -4}, {0, 0, 0}, 1.0, 0.01, 0.0};
  gsl_rng *r = sb_engine_rng(e);
  ck_assert(isfinite(sb_agglo_erel_of(e, a, &p, 0.0, r)));
  e->vsd[0] = 1e300;
  sb_clear_error();
  ck_assert(isnan(sb_agglo_erel_of(e, a, &p, 0.0, r)));
  ck_assert_msg(!strncmp(sb_last_error(), "sb_agglo_erel_of:", 17),
                "message: %s", sb_last_error());
  sb_agglo_free(a);
  sb_engine_free(e);
}
END_TEST

START_TEST(test_erel_stationary)
{
  sb_engine *e = box(20.0, 0.01, 4, 21);
  add_gas_species(e);
  sb_agglo_params ap;
  sb_agglo_params_default(&ap);
  ap.growth = SB_AGGLO_CONSTANT;
  ap.rule = SB_AGGLO_DLVO;
  ap.erel = SB_AGGLO_EREL_STATIONARY;
  sb_agglo *a = sb_agglo_alloc(&ap);
  ck_assert_int_eq(sb_agglo_attach(e, a), SB_SUCCESS);
  size_t sp3;
  ck_assert_int_eq(sb_agglo_species_of_size(a, e, 3, &sp3), SB_SUCCESS);
  double x0[3] = {1, 1, 1}, x1[3] = {5, 5, 5}, u[3] = {0, 0, 0};
  ck_assert_int_eq(sb_engine_add_particle(e, 0, 0, x0, u), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_add_particle(e, sp3, 0, x1, u), SB_SUCCESS);
  sb_engine_pair p = {0, 1, {-4, -4, -4}, {0, 0, 0}, 1.0, 0.01, 0.0};
  enum { N = 20000 };
  static double E[N];
  double m = 0.0;
  gsl_rng *r = sb_engine_rng(e);
  for (int k = 0; k < N; k++) {
    E[k] = sb_agglo_erel_of(e, a, &p, 0.0, r);
    m += E[k] / N;
  }
  ck_assert_abs(m, 1.5, 3.29 * sqrt(1.5 / N));
  double d, pv;
  ck_assert_int_eq(sb_ks_test(E, N, cdf_g32, NULL, &d, &pv), SB_SUCCESS);
  ck_assert_msg(pv >= 1e-3, "KS p = %g (D = %g)", pv, d);
  sb_agglo_free(a);
  sb_engine_free(e);
}
END_TEST

/* Constant kernel (V8 in small): Brownian primaries in the diffusive
 * limit (dt = 1000 tau_p) detected by the Bessel-3 bridge (exact pair
 * rate), CONSTANT growth: every cluster keeps the position diffusivity
 * b2/2 and the contact distance d, so K = 2 pi B_ij^2 d = 4 pi b2 d
 * (B_ij^2 = 2 b2 the relative variance rate) and M0/N0 = 1/(1 + tau/2),
 * tau = K n0 t.  Volume fraction 1e-5 (the transient excess of the
 * Smoluchowski rate, 2 d/sqrt(pi D12 t), is 1.2% of tau at the half-life).
 * Sample: 8 runs of N0 = 500 to the half-life (tau = 2); pass: the
 * analytic M0/N0 = 1/2 lies in the 99% Student interval of the runs'
 * mean (about +-3%). */
START_TEST(test_constant_kernel)
{
  const size_t N0 = 500, R = 8;
  const double d = 1.0, b2 = 1.0, phi = 1e-5;
  const double n0 = phi * 6.0 / (PI * d * d * d);
  const double K = 4.0 * PI * b2 * d, thalf = 2.0 / (K * n0);
  const double dt = 4.5 * d * d / b2; /* rms relative step 3 d */
  double m0[8];
  for (size_t r = 0; r < R; r++) {
    sb_engine *e = box(cbrt(N0 / n0), dt, N0, 100 + r);
    double tau = dt / 1000.0;
    sb_engine_species s = {0.5 * d, 1.0, tau, sqrt(b2) / tau, 0.0};
    ck_assert_int_eq(sb_engine_add_species(e, &s, NULL), SB_SUCCESS);
    ck_assert_int_eq(sb_engine_fill_random(e, 0, 0, N0), SB_SUCCESS);
    sb_engine_bridge_params bp;
    sb_engine_bridge_params_default(&bp);
    bp.ends = SB_BRIDGE_ENDS_DIFFUSIVE;
    sb_engine_bridge *b = sb_engine_bridge_alloc(&bp);
    ck_assert_int_eq(sb_engine_bridge_attach(e, b), SB_SUCCESS);
    sb_agglo *a = agglo(e, SB_AGGLO_CONSTANT, SB_AGGLO_MERGE, 0.0);
    ck_assert_int_eq(sb_engine_run_until(e, thalf), SB_SUCCESS);
    double m[3];
    sb_agglo_moments(a, e, m);
    m0[r] = m[0] / N0;
    sb_agglo_free(a);
    sb_engine_bridge_free(b);
    sb_engine_free(e);
  }
  double mean, lo, hi;
  ck_assert_int_eq(sb_mean_ci(m0, R, 0.99, &mean, &lo, &hi), SB_SUCCESS);
  ck_assert_msg(lo <= 0.5 && 0.5 <= hi,
                "M0/N0 at the half-life = %.4f [%.4f, %.4f], want 0.5",
                mean, lo, hi);
}
END_TEST

/* The DLVO gas of test_merge_conservation (a barrier of 1.5 k_B T, so
 * the sticking draws come from the engine's generator), Stokes growth. */
static sb_engine *dlvo_gas(unsigned long seed, sb_agglo **a, double wmax,
                           const char *saved, int *st)
{
  const size_t N = 400;
  sb_engine *e = box(cbrt(N * PI / 6.0 / 0.05), 0.02, N, seed);
  add_gas_species(e);
  ck_assert_int_eq(sb_engine_fill_random(e, 0, 0, N), SB_SUCCESS);
  sb_agglo_params ap;
  sb_agglo_params_default(&ap);
  ap.rule = SB_AGGLO_DLVO;
  ap.wmax = wmax;
  *a = sb_agglo_alloc(&ap);
  ck_assert_ptr_nonnull(*a);
  *st = saved ? sb_agglo_load(*a, saved) : SB_SUCCESS;
  return e;
}

/* steps with a size row after each */
static void agglo_steps(sb_engine *e, sb_agglo *a, int n)
{
  for (int k = 0; k < n; k++) {
    ck_assert_int_eq(sb_engine_step(e), SB_SUCCESS);
    ck_assert_int_eq(sb_agglo_sample(a, e), SB_SUCCESS);
  }
}

/* sbt_load_fn: a state loaded into a new context of parameters *ctx. */
static int load_agglo(const char *path, void *ctx)
{
  sb_agglo *a = sb_agglo_alloc(ctx);
  ck_assert_ptr_nonnull(a);
  const int st = sb_agglo_load(a, path);
  sb_agglo_free(a);
  return st;
}

/* A merging run stopped after 60 steps, saved (engine checkpoint and the
 * agglomeration context), restored and run 60 more is the 120-step run:
 * the same particles, counters, merges and rebounds, and the same size
 * rows; a merge after the restart reuses the saved cluster species.
 * Then the errors: a state loaded into an attached context or one with
 * another barrier; an engine at another step, or another run at the same
 * step; files that are not agglomeration files, truncated or with data
 * after the end; saving a context not attached. */
START_TEST(test_save_load)
{
  const double W = 1.5 * 1.0;  /* k_B T = 1 */
  char dir[] = "/tmp/sb_agglo_XXXXXX";
  ck_assert_ptr_nonnull(mkdtemp(dir));
  char ck[64], ag[64], bad[64];
  snprintf(ck, sizeof ck, "%s/run.ck", dir);
  snprintf(ag, sizeof ag, "%s/run.ck.agglo", dir);
  snprintf(bad, sizeof bad, "%s/bad", dir);
  int st;
  sb_agglo *a, *b;
  sb_engine *e = dlvo_gas(4, &a, W, NULL, &st);
  ck_assert_int_eq(sb_agglo_save(a, e, ag), SB_EINVAL);  /* not attached */
  ck_assert_int_eq(sb_agglo_attach(e, a), SB_SUCCESS);
  agglo_steps(e, a, 120);
  /* stopped at 60 */
  sb_engine *f = dlvo_gas(4, &b, W, NULL, &st);
  ck_assert_int_eq(sb_agglo_attach(f, b), SB_SUCCESS);
  agglo_steps(f, b, 60);
  ck_assert_int_eq(sb_engine_checkpoint_save(f, ck), SB_SUCCESS);
  ck_assert_int_eq(sb_agglo_save(b, f, ag), SB_SUCCESS);
  ck_assert_int_eq(sb_agglo_load(b, ag), SB_EINVAL);  /* attached */
  sb_agglo_stats half;
  sb_agglo_get_stats(b, &half);
  sb_agglo_free(b);
  sb_engine_free(f);
  f = sb_engine_checkpoint_load(ck, &st);
  ck_assert_int_eq(st, SB_SUCCESS);
  sb_agglo_params ap;
  sb_agglo_params_default(&ap);
  ap.rule = SB_AGGLO_DLVO;
  ap.wmax = W;
  b = sb_agglo_alloc(&ap);
  ck_assert_int_eq(sb_agglo_load(b, ag), SB_SUCCESS);
  ck_assert_int_eq(sb_agglo_attach(f, b), SB_SUCCESS);
  agglo_steps(f, b, 60);
  sbt_assert_same_run(e, f, SBT_SAME_CANDIDATES);
  sb_agglo_stats sa, sb;
  sb_agglo_get_stats(a, &sa);
  sb_agglo_get_stats(b, &sb);
  printf("agglo save/load: %llu / %llu merges (%llu at the stop), %llu / "
         "%llu rebounds\n", (unsigned long long)sa.nmerge,
         (unsigned long long)sb.nmerge, (unsigned long long)half.nmerge,
         (unsigned long long)sa.nrebound, (unsigned long long)sb.nrebound);
  ck_assert_uint_gt(half.nmerge, 20);
  ck_assert_uint_gt(sa.nmerge, half.nmerge + 20);
  ck_assert_uint_gt(sa.nrebound, 20);
  ck_assert_uint_eq(sa.nmerge, sb.nmerge);
  ck_assert_uint_eq(sa.nrebound, sb.nrebound);
  ck_assert(sa.erel_sum == sb.erel_sum);
  size_t ra, rb, ca, cb;
  const double *xa = sb_agglo_series(a, &ra, &ca);
  const double *xb = sb_agglo_series(b, &rb, &cb);
  ck_assert_uint_eq(ra, 120);
  ck_assert_uint_eq(ra, rb);
  ck_assert_uint_eq(ca, cb);
  ck_assert(!memcmp(xa, xb, ra * ca * sizeof *xa));
  double na[64], nb[64], ta, tb;
  ck_assert_int_eq(sb_agglo_count_sizes(a, e, 64, na, &ta), SB_SUCCESS);
  ck_assert_int_eq(sb_agglo_count_sizes(b, f, 64, nb, &tb), SB_SUCCESS);
  ck_assert(!memcmp(na, nb, sizeof na) && ta == tb);
  for (size_t k = 1; k <= 64; k++)  /* the same species for each size */
    if (na[k - 1] > 0)
      ck_assert_uint_eq(sb_agglo_size_of_species(a, k - 1),
                        sb_agglo_size_of_species(b, k - 1));
  sb_agglo_free(a);
  sb_agglo_free(b);
  sb_engine_free(e);
  /* the errors: another barrier; the engine at another step; another run
   * at the saved step */
  e = dlvo_gas(4, &a, 2.0 * W, ag, &st);
  ck_assert_int_eq(st, SB_EINVAL);
  ck_assert_ptr_nonnull(strstr(sb_last_error(), "other agglomeration"));
  sb_agglo_free(a);
  sb_engine_free(e);
  a = sb_agglo_alloc(&ap);
  ck_assert_int_eq(sb_agglo_load(a, ag), SB_SUCCESS);
  ck_assert_int_eq(sb_agglo_attach(f, a), SB_EINVAL);  /* f is at 120 */
  ck_assert_ptr_nonnull(strstr(sb_last_error(), "step 60"));
  sb_agglo_free(a);
  sb_engine_free(f);
  e = dlvo_gas(5, &a, W, NULL, &st);
  ck_assert_int_eq(sb_agglo_attach(e, a), SB_SUCCESS);
  agglo_steps(e, a, 60);
  sb_agglo_free(a);
  a = sb_agglo_alloc(&ap);
  ck_assert_int_eq(sb_agglo_load(a, ag), SB_SUCCESS);
  ck_assert_int_eq(sb_agglo_attach(e, a), SB_EINVAL);
  ck_assert_ptr_nonnull(strstr(sb_last_error(), "other particles"));
  sb_agglo_free(a);
  sb_engine_free(e);
  /* files: truncated, trailing data, not such a file, missing */
  sbt_damaged_copies(ag, bad, 60, "SBFHIT01", load_agglo, &ap);
  /* a flipped byte; the format without the hash (version 01) */
  sbt_hash_checked(ag, bad, "01", load_agglo, &ap);
  remove(ck);
  remove(ag);
  rmdir(dir);
}
END_TEST

static Suite *suite(void)
{
  Suite *s = suite_create("engine_agglo");
  TCase *tc = tcase_create("merge");
  tcase_add_test(tc, test_remove);
  tcase_add_test(tc, test_merge_pair);
  tcase_add_test(tc, test_merge_outside_step);
  tcase_add_test(tc, test_growth);
  tcase_add_test(tc, test_merge_conservation);
  tcase_add_test(tc, test_save_load);
  suite_add_tcase(s, tc);
  TCase *mc = tcase_create("mc");
  tcase_add_test(mc, test_dlvo_sticking);
  tcase_add_test(mc, test_erel_stationary);
  tcase_add_test(mc, test_erel_error_name);
  tcase_add_test(mc, test_constant_kernel);
  tcase_set_timeout(mc, 60);
  suite_add_tcase(s, mc);
  return s;
}

int main(void) { return sbt_run_suite(suite()); }
