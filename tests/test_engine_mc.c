/* test_engine_mc.c — small, fast Monte Carlo checks of the engine's
 * collision kernel against kinetic theory.
 *
 * Units: unit-free numbers (the engine only needs consistent units):
 * diameter d = 1, mass m = 1, k_B T / m = 1 (species T = 1/k_B).  The
 * kinetic-theory kernel of identical hard spheres is
 *     K_kin = pi d^2 <|v_i - v_j|> = pi d^2 sqrt(16 k_B T / (pi m))
 * (relative velocity Maxwellian with variance 2 k_B T / m per component;
 * Mohaupt 2011, eq 3.6, is misprinted: docs/errata.md).  In an equilibrium
 * hard-sphere fluid the pair density at contact is enhanced by the contact
 * value of the radial distribution function, here Carnahan-Starling
 *     g(sigma) = (1 - phi/2) / (1 - phi)^3
 * (1.3% at phi = 0.005; Enskog's correction to the collision frequency).
 *
 * Pass criterion: the reference lies in the exact 99% Poisson interval of
 * the estimate K_e = 2 N_c V / (n (n - 1) t) (sb_engine_kernel).  Seeds are
 * fixed, so the outcome is reproducible; sample sizes (~3000-5000
 * collisions, interval about +-5%) are stated per test.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <smolbridge/engine.h>
#include <smolbridge/langevin.h>

#include "testutil.h"

#define PI 3.14159265358979323846
#define LEVEL 0.99

static double g_cs(double phi)
{
  return (1.0 - 0.5 * phi) / ((1.0 - phi) * (1.0 - phi) * (1.0 - phi));
}

static const double K_KIN = PI * 2.2567583341910251; /* pi sqrt(16/pi) */

/* Box edge for n spheres of diameter 1 at volume fraction phi. */
static double box_for(size_t n, double phi)
{
  return cbrt((double)n * PI / 6.0 / phi);
}

static sb_engine *gas(size_t n, double phi, double dt, unsigned long seed,
                      sb_engine_detect det, sb_engine_outcome o, double tau)
{
  sb_engine_params p;
  sb_engine_params_default(&p);
  double L = box_for(n, phi);
  p.L[0] = p.L[1] = p.L[2] = L;
  p.dt = dt;
  p.capacity = n;
  p.seed = seed;
  p.detect = det;
  p.outcome = o;
  sb_engine *e = sb_engine_alloc(&p);
  ck_assert_ptr_nonnull(e);
  /* tau = inf: free flight; else B from B^2 tau / 2 = k_B T / m = 1 */
  sb_engine_species s = {0.5, 1.0, tau, isinf(tau) ? 0.0 : sqrt(2.0 / tau),
                         1.0 / SB_BOLTZMANN};
  ck_assert_int_eq(sb_engine_add_species(e, &s, NULL), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_fill_random(e, 0, 0, n), SB_SUCCESS);
  return e;
}

static void check_kernel(const sb_engine *e, double Kref, const char *what)
{
  double K, lo, hi;
  ck_assert_int_eq(sb_engine_kernel(e, LEVEL, &K, &lo, &hi), SB_SUCCESS);
  sb_engine_stats st;
  sb_engine_get_stats(e, &st);
  ck_assert_msg(lo <= Kref && Kref <= hi,
                "%s: K_e = %.5g [%.5g, %.5g] (N_c = %llu) excludes K_ref = "
                "%.5g (K_e/K_ref = %.4f)",
                what, K, lo, hi, (unsigned long long)st.ncoll, Kref,
                K / Kref);
}

/* A. Molecular dynamics of a hard-sphere gas (free flight, elastic,
 * ballistic detection), the set-up of Mohaupt (2011) §3.2.1 with n = 250:
 * phi = 0.005, dt = 0.05 (mean free path 22 d, v dt ~ 0.08 d), velocities
 * thermalised to k_B T/m = 1 (zero momentum), 300 time units after a
 * 20-unit warm-up: ~2500 collisions.  Reference K_kin g_CS(phi). */
START_TEST(test_md_gas)
{
  const double phi = 0.005;
  sb_engine *e = gas(250, phi, 0.05, 2024, SB_DETECT_BALLISTIC,
                     SB_OUTCOME_ELASTIC, INFINITY);
  ck_assert_int_eq(sb_engine_thermalize(e, 1.0 / SB_BOLTZMANN), SB_SUCCESS);
  double e0 = sb_engine_kinetic_energy(e, NULL);
  ck_assert_int_eq(sb_engine_run_until(e, 20.0), SB_SUCCESS);
  sb_engine_reset_counters(e);
  ck_assert_int_eq(sb_engine_run_until(e, 320.0), SB_SUCCESS);
  check_kernel(e, K_KIN * g_cs(phi), "MD gas");
  ck_assert_rel(sb_engine_kinetic_energy(e, NULL), e0, 1e-11);
  sb_engine_free(e);
}
END_TEST

/* B. Ideal gas, particles pass through each other (count-only outcome),
 * ballistic detection: every contact counted once.  The velocities never
 * change, so the reference is the exact conditional rate for the drawn
 * velocities, K_ref = pi d^2 (mean over pairs of |v_i - v_j|), computed
 * directly (O(n^2)), and checked against K_kin to 5%.  n = 250,
 * phi = 0.005, dt = 0.05, t = 300: ~2500 contacts.  The overlap
 * detector at a large step (v_rel dt ~ 3 d) must miss many of them. */
static double pair_mean_speed(const sb_engine *e)
{
  const size_t n = sb_engine_count(e);
  const double *u = sb_engine_velocities(e);
  double s = 0.0;
  for (size_t i = 0; i < n; i++)
    for (size_t j = i + 1; j < n; j++) {
      double d2 = 0.0;
      for (int k = 0; k < 3; k++) {
        double d = u[3 * i + k] - u[3 * j + k];
        d2 += d * d;
      }
      s += sqrt(d2);
    }
  return s / (0.5 * (double)n * (double)(n - 1));
}

START_TEST(test_ideal_gas_count)
{
  sb_engine *e = gas(250, 0.005, 0.05, 77, SB_DETECT_BALLISTIC,
                     SB_OUTCOME_COUNT, INFINITY);
  double Kref = PI * pair_mean_speed(e);
  ck_assert_rel(Kref, K_KIN, 0.05);
  ck_assert_int_eq(sb_engine_run_until(e, 300.0), SB_SUCCESS);
  check_kernel(e, Kref, "ideal gas, ballistic");
  sb_engine_free(e);

  /* overlap detection with dt = 1.3 (mean |v_rel| dt ~ 3 d): K_e well
   * below the reference (Mohaupt 2011, §3.3: pass-through is
   * missed) */
  e = gas(250, 0.005, 1.3, 78, SB_DETECT_OVERLAP, SB_OUTCOME_COUNT,
          INFINITY);
  Kref = PI * pair_mean_speed(e);
  ck_assert_int_eq(sb_engine_run_until(e, 300.0), SB_SUCCESS);
  double K, lo, hi;
  sb_engine_kernel(e, LEVEL, &K, &lo, &hi);
  ck_assert_msg(hi < 0.8 * Kref, "overlap detection: K_e/K_ref = %.3f",
                K / Kref);
  sb_engine_free(e);
}
END_TEST

/* C. Brownian (Langevin) hard spheres with elastic collisions, ballistic
 * regime dt/tau = 0.01: the Langevin thermostat and elastic collisions
 * keep the canonical equilibrium, whose contact flux is the kinetic-theory
 * rate K_kin g(sigma) whatever the dynamics (the positions' stationary law
 * is the hard-sphere one, velocities Maxwellian and independent of them).
 * The chord velocity's variance is lower than k_B T/m by ~dt/(3 tau) =
 * 0.3% (MSD(dt)/dt^2), negligible here.  n = 500, phi = 0.01, tau = 1,
 * warm-up 3 tau, then 120 tau: ~4000 collisions. */
START_TEST(test_langevin_elastic_equilibrium)
{
  const double phi = 0.01;
  sb_engine *e = gas(500, phi, 0.01, 99, SB_DETECT_BALLISTIC,
                     SB_OUTCOME_ELASTIC, 1.0);
  ck_assert_int_eq(sb_engine_run_until(e, 3.0), SB_SUCCESS);
  sb_engine_reset_counters(e);
  ck_assert_int_eq(sb_engine_run_until(e, 123.0), SB_SUCCESS);
  check_kernel(e, K_KIN * g_cs(phi), "Langevin elastic");
  /* the thermostat holds k_B T/m = 1: mean kinetic energy 3/2 per
   * particle (500 particles, relative sd ~ 3%) */
  ck_assert_rel(sb_engine_kinetic_energy(e, NULL) / 500.0, 1.5, 0.1);
  sb_engine_free(e);
}
END_TEST

static Suite *suite(void)
{
  Suite *s = suite_create("engine_mc");
  TCase *tc = tcase_create("kernel");
  tcase_set_timeout(tc, 60);
  tcase_add_test(tc, test_md_gas);
  tcase_add_test(tc, test_ideal_gas_count);
  tcase_add_test(tc, test_langevin_elastic_equilibrium);
  suite_add_tcase(s, tc);
  return s;
}

int main(void) { return sbt_run_suite(suite()); }
