#define _POSIX_C_SOURCE 200809L
/* test_engine_physics.c — forces, Lees-Edwards boundaries and walls of the
 * engine (lib/engine/engine_force.c, engine_lees.c, engine_wall.c).
 *
 * Independent checks: the exact shear step against a fine fixed-step
 * Runge-Kutta integration of the same ODEs; the Lees-Edwards neighbour
 * search against all pairs with the shifted-image segment distance; the
 * nonlinear drag step's order from the error ratio against a fine RK4
 * reference; the wall bridge detector against the reflection principle
 * (Monte Carlo, exact binomial test); checkpoints bit-identical.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <gsl/gsl_cdf.h>
#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>

#include <smolbridge/engine.h>
#include <smolbridge/engine_bridge.h>
#include <smolbridge/langevin_hit.h>
#include <smolbridge/stats.h>

#include "engine/engine_internal.h"
#include "shear_rk4.h"
#include "testutil.h"

#define PI_ 3.14159265358979323846

static sb_engine *eng(double L, double dt, size_t cap, unsigned long seed)
{
  sb_engine_params p;
  sb_engine_params_default(&p);
  p.L[0] = p.L[1] = p.L[2] = L;
  p.dt = dt;
  p.capacity = cap;
  p.seed = seed;
  p.outcome = SB_OUTCOME_COUNT;
  sb_engine *e = sb_engine_alloc(&p);
  ck_assert_ptr_nonnull(e);
  return e;
}

/* ------------------------------------------------ exact shear step */

/* One non-Brownian particle, shear with Lees-Edwards, gravity along y: the
 * step matches RK4 (2e5 sub-steps) at dt/tau = 0.003, 0.7, 1.3, 40.  The
 * box (L = 40, the particle at Y = y - L/2 = 1) keeps the longest step
 * (|disp| ~ 2.7) below the search's limit of L/4, which one particle
 * observes as two do. */
START_TEST(test_shear_exact_step)
{
  const double ratios[] = {0.003, 0.7, 1.3, 40.0};
  for (int q = 0; q < 4; q++) {
    const double L = 40.0, tau = 0.5, dt = ratios[q] * tau, G = 0.3;
    sb_engine *e = eng(L, dt, 4, 1);
    sb_engine_species s = {0.1, 1.0, tau, 0.0, 0.0};
    sb_engine_add_species(e, &s, NULL);
    double Gp[3] = {G, 0, 0}, g[3] = {0.0, -0.2, 0.0};
    ck_assert_int_eq(sb_engine_set_fluid(e, SB_FLUID_SHEAR, Gp), 0);
    ck_assert_int_eq(sb_engine_set_lees_edwards(e, 1), 0);
    ck_assert_int_eq(sb_engine_set_gravity(e, g), 0);
    /* rho_p = 1/(4/3 pi 0.001): no buoyancy (rho_f = 0) */
    double x[3] = {2.0, 0.5 * L + 1.0, 5.0}, u[3] = {0.4, 0.35, 0.0};
    sb_engine_add_particle(e, 0, 0, x, u);
    ck_assert_msg(sb_engine_step(e) == 0, "dt/tau %g: %s", ratios[q],
                  sb_last_error());
    const double wy = -0.2 * tau;
    double st[4] = {x[0], u[0], x[1] - 0.5 * L, u[1]};
    /* in coordinates with Y = y - L/2 the fluid is G Y */
    sbt_shear_rk4(st, tau, G, wy, dt, 200000);
    const double *xe = sb_engine_positions(e), *ue = sb_engine_velocities(e);
    double X = xe[0], Y = xe[1] - 0.5 * L;
    if (X < 1.0)
      X += L;  /* no wrap expected for these numbers, but be safe */
    ck_assert_msg(fabs(X - st[0]) <= 1e-10 * (1.0 + fabs(st[0])),
                  "dt/tau %g: x %.15g vs %.15g", ratios[q], X, st[0]);
    ck_assert_msg(fabs(ue[0] - st[1]) <= 1e-10,
                  "dt/tau %g: u %.15g vs %.15g", ratios[q], ue[0], st[1]);
    ck_assert(fabs(Y - st[2]) <= 1e-10);
    ck_assert(fabs(ue[1] - st[3]) <= 1e-10);
    sb_engine_free(e);
  }
}
END_TEST

/* The series and closed forms of the coefficients agree where they meet. */
START_TEST(test_shear_coefs)
{
  double a[4], b[4];
  sb_langevin_shear_mean_coefs(1.0 - 1e-12, a);
  sb_langevin_shear_mean_coefs(1.0, b);
  for (int k = 0; k < 4; k++)
    ck_assert_rel(a[k], b[k], 1e-11);
  /* leading terms at small x */
  sb_langevin_shear_mean_coefs(1e-4, a);
  ck_assert_rel(a[0], 1e-12 / 6.0, 1e-3);
  ck_assert_rel(a[1], 0.5e-8, 1e-3);
  ck_assert_rel(a[2], 0.5e-8, 1e-3);
  ck_assert_rel(a[3], 1e-12 / 6.0, 1e-3);
}
END_TEST

/* ------------------------------------------------ Lees-Edwards */

/* Crossing the top face: y - L_y, x - delta, u_x - G L_y. */
START_TEST(test_le_wrap)
{
  const double L = 10.0, G = 0.5, dt = 0.1;
  sb_engine *e = eng(L, dt, 4, 1);
  sb_engine_species s = {0.1, 1.0, INFINITY, 0.0, 1.0};
  sb_engine_add_species(e, &s, NULL);
  double Gp[3] = {G, 0, 0};
  sb_engine_set_fluid(e, SB_FLUID_SHEAR, Gp);
  ck_assert_int_eq(sb_engine_set_lees_edwards(e, 1), 0);
  double x[3] = {3.0, 9.99, 5.0}, u[3] = {0.0, 0.2, 0.0};
  sb_engine_add_particle(e, 0, 0, x, u);
  ck_assert_int_eq(sb_engine_step(e), 0);
  double d = sb_engine_lees_edwards_offset(e);
  ck_assert_rel(d, G * L * dt, 1e-14);
  const double *xe = sb_engine_positions(e), *ue = sb_engine_velocities(e);
  ck_assert_rel(xe[1], 9.99 + 0.02 - L, 1e-12);
  ck_assert_rel(xe[0], 3.0 - d, 1e-14);
  ck_assert_rel(ue[0], -G * L, 1e-14);
  sb_engine_free(e);
}
END_TEST

/* Every pair whose shifted-image segments come within sigma is a
 * candidate, none twice (300 particles, delta not a multiple of L_x). */
START_TEST(test_le_superset)
{
  const double L = 20.0, G = 0.7, dt = 0.2, r = 0.4;
  for (int m = 0; m < 3; m++) {
    sb_engine *e = eng(L, dt, 400, 3);
    sb_engine_set_neigh(e, (sb_engine_neigh)m);
    sb_engine_species s = {r, 1.0, 1.0, 0.0, 0.0};
    sb_engine_add_species(e, &s, NULL);
    double Gp[3] = {G, 0, 0};
    sb_engine_set_fluid(e, SB_FLUID_SHEAR, Gp);
    sb_engine_set_lees_edwards(e, 1);
    gsl_rng *rg = gsl_rng_alloc(gsl_rng_mt19937);
    gsl_rng_set(rg, 7);
    for (int k = 0; k < 300; k++) {
      double x[3], u[3];
      for (int c = 0; c < 3; c++) {
        x[c] = L * gsl_rng_uniform(rg);
        u[c] = gsl_ran_gaussian(rg, 1.0);
      }
      sb_engine_add_particle(e, 0, 0, x, u);
    }
    e->le_off = 7.3;  /* some shift */
    const size_t n = sb_engine_count(e);
    double *disp = malloc(3 * n * sizeof *disp);
    for (size_t i = 0; i < 3 * n; i++)
      disp[i] = 0.6 * gsl_ran_gaussian(rg, 1.0);
    size_t np;
    const size_t *pairs;
    ck_assert_int_eq(sb_engine_neighbours(e, (sb_engine_neigh)m, disp, 0.0,
                                          &np, &pairs), 0);
    unsigned char *seen = calloc(n * n, 1);
    for (size_t q = 0; q < np; q++) {
      size_t i = pairs[2 * q], j = pairs[2 * q + 1];
      ck_assert(i < j);
      ck_assert_msg(!seen[i * n + j], "pair (%zu, %zu) twice", i, j);
      seen[i * n + j] = 1;
    }
    const double *x = sb_engine_positions(e);
    size_t need = 0;
    for (size_t i = 0; i < n; i++)
      for (size_t j = i + 1; j < n; j++) {
        double dy = x[3 * i + 1] - x[3 * j + 1];
        int im = dy > 0.5 * L ? 1 : (dy < -0.5 * L ? -1 : 0);
        double a[3] = {x[3 * i] - x[3 * j] - im * 7.3, dy - im * L,
                       x[3 * i + 2] - x[3 * j + 2]};
        a[0] -= L * round(a[0] / L);
        a[2] -= L * round(a[2] / L);
        double b[3] = {disp[3 * i] - disp[3 * j] - im * G * L * dt,
                       disp[3 * i + 1] - disp[3 * j + 1],
                       disp[3 * i + 2] - disp[3 * j + 2]};
        double bb = b[0] * b[0] + b[1] * b[1] + b[2] * b[2];
        double ab = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        double sm = bb > 0 ? -ab / bb : 0.0;
        sm = sm < 0 ? 0 : (sm > 1 ? 1 : sm);
        double d2 = 0;
        for (int c = 0; c < 3; c++)
          d2 += (a[c] + sm * b[c]) * (a[c] + sm * b[c]);
        if (d2 <= 4 * r * r) {
          need++;
          ck_assert_msg(seen[i * n + j], "method %d misses (%zu, %zu) "
                        "image %d", m, i, j, im);
        }
      }
    ck_assert(need > 20);
    free(seen);
    free(disp);
    gsl_rng_free(rg);
    sb_engine_free(e);
  }
}
END_TEST

/* Two tracers across the sliding boundary meet once: the lower one's
 * image (y + L_y, x + delta) overtakes the upper one. */
START_TEST(test_le_pair_collides)
{
  const double L = 10.0, G = 1.0, dt = 0.01;
  sb_engine *e = eng(L, dt, 4, 1);
  sb_engine_species s = {0.2, 1.0, 1e-6, 0.0, 0.0};
  sb_engine_add_species(e, &s, NULL);
  double Gp[3] = {G, 0, 0};
  sb_engine_set_fluid(e, SB_FLUID_SHEAR, Gp);
  sb_engine_set_lees_edwards(e, 1);
  /* upper at y = 9.9 (U = 4.9), lower at y = 0.15 (U = -4.85; image
   * moves at +5.15, 0.25 above): relative x velocity 0.25 */
  double xa[3] = {5.0, 9.9, 5.0}, ua[3] = {4.9, 0, 0};
  double xb[3] = {4.0, 0.15, 5.0}, ub[3] = {-4.85, 0, 0};
  sb_engine_add_particle(e, 0, 0, xa, ua);
  sb_engine_add_particle(e, 0, 0, xb, ub);
  ck_assert_int_eq(sb_engine_run_until(e, 10.0), 0);
  sb_engine_stats st;
  sb_engine_get_stats(e, &st);
  ck_assert_uint_eq(st.ncoll, 1);
  sb_engine_free(e);
}
END_TEST

/* The same tracer pair seen by the detectors that take the pair's law
 * between the step ends (count outcome): the Langevin detector (built in,
 * and through sb_engine_langevin_contact with the contact state) and the
 * Brownian-bridge detectors (exact 3-D and Bessel-3, position and
 * diffusive ends).  Nearly noiseless tracers (B tau = 1e-9 m/sqrt(s)):
 * the first contact is the straight-path one, x separation 1 - 0.25 t
 * reaching sqrt(0.4^2 - 0.25^2) = 0.3122 at t = 2.7510 s, within a step
 * (diffusive ends, X + tau U: tau = 2e-4 s earlier; without the image's
 * velocity jump G L_y = 10 m/s they would be 8e-3 s early); without the
 * image shift there is no contact at all (the pair is 9.75 apart in y). */
typedef struct {
  int kind;  /* 0 Langevin contact, 1 bridge */
  sb_engine_bridge *b;
  double first;
  int nfirst;
  double gap, vx;
} le_first;

static int le_first_det(const sb_engine *e, const sb_engine_pair *p,
                        const gsl_rng *r, void *vc, double *s)
{
  le_first *f = vc;
  int h;
  if (f->kind == 0) {
    sb_langevin_contact c;
    h = sb_engine_langevin_contact(e, p, r, s, &c);
    if (h == 1 && !f->nfirst) {
      double d2 = 0.0;
      for (int k = 0; k < 3; k++)
        d2 += (c.xi[k] - c.xj[k]) * (c.xi[k] - c.xj[k]);
      f->gap = sqrt(d2) - p->sigma;
      f->vx = c.ui[0] - c.uj[0];
    }
  } else
    h = sb_engine_detect_bridge(e, p, r, f->b, s);
  if (h == 1 && !f->nfirst++)
    f->first = p->t0 + *s * p->dt;
  return h == 1 ? 0 : h;
}

START_TEST(test_le_bridge_detectors)
{
  const double L = 10.0, G = 1.0, dt = 0.01, tau = 2e-4;
  const double tc = (1.0 - sqrt(0.16 - 0.0625)) / 0.25;
  for (int v = 0; v < 6; v++) {
    sb_engine *e = eng(L, dt, 4, 3 + v);
    sb_engine_species s = {0.2, 1.0, tau, 1e-9 / tau, 0.0};
    sb_engine_add_species(e, &s, NULL);
    double Gp[3] = {G, 0, 0};
    sb_engine_set_fluid(e, SB_FLUID_SHEAR, Gp);
    ck_assert_int_eq(sb_engine_set_lees_edwards(e, 1), 0);
    double xa[3] = {5.0, 9.9, 5.0}, ua[3] = {4.9, 0, 0};
    double xb[3] = {4.0, 0.15, 5.0}, ub[3] = {-4.85, 0, 0};
    sb_engine_add_particle(e, 0, 0, xa, ua);
    sb_engine_add_particle(e, 0, 0, xb, ub);
    le_first f = {v == 1 ? 0 : 1, NULL, NAN, 0, NAN, NAN};
    if (v == 0)
      ck_assert_int_eq(sb_engine_set_detect(e, SB_DETECT_LANGEVIN), 0);
    else if (v == 1)
      ck_assert_int_eq(sb_engine_set_detector(e, le_first_det, &f, 0.01), 0);
    else {
      sb_engine_bridge_params bp;
      sb_engine_bridge_params_default(&bp);
      bp.mode = v < 4 ? SB_BRIDGE_EXACT : SB_BRIDGE_BESSEL;
      bp.ends = v % 2 ? SB_BRIDGE_ENDS_DIFFUSIVE : SB_BRIDGE_ENDS_POSITION;
      bp.outcome = SB_BRIDGE_OUT_COUNT;
      f.b = sb_engine_bridge_alloc(&bp);
      ck_assert_ptr_nonnull(f.b);
      ck_assert_int_eq(sb_engine_set_detector(e, le_first_det, &f, 0.01), 0);
    }
    ck_assert_int_eq(sb_engine_run_until(e, 6.0), 0);
    if (v == 0) {
      sb_engine_stats st;
      sb_engine_get_stats(e, &st);
      ck_assert_uint_eq(st.ncoll, 1);  /* entered once, overlaps after */
    } else {
      ck_assert_msg(f.nfirst >= 1, "variant %d: no contact", v);
      ck_assert_msg(fabs(f.first - tc) < 1e-3, "variant %d: first contact "
                    "at %.6f, expected %.6f", v, f.first, tc);
    }
    if (v == 1) {
      ck_assert(fabs(f.gap) < 1e-6);
      ck_assert_rel(f.vx, -0.25, 1e-3);  /* image velocity included */
    }
    sb_engine_bridge_free(f.b);
    sb_engine_free(e);
  }
}
END_TEST

START_TEST(test_le_errors)
{
  sb_engine *e = eng(10.0, 0.1, 4, 1);
  ck_assert_int_eq(sb_engine_set_lees_edwards(e, 1), SB_EINVAL);
  double Gp[3] = {1.0, 0, 0};
  sb_engine_set_fluid(e, SB_FLUID_SHEAR, Gp);
  ck_assert_int_eq(sb_engine_set_lees_edwards(e, 1), 0);
  ck_assert_int_eq(sb_engine_set_walls(e, 1, SB_WALL_ABSORB, SB_WALL_ABSORB),
                   SB_EINVAL);
  /* every outcome works (test_engine_lees_outcomes); the field must
   * stay the built-in shear */
  sb_engine_set_outcome(e, SB_OUTCOME_ELASTIC, 1.0);
  ck_assert_int_eq(sb_engine_step(e), 0);
  double U[3] = {1.0, 0, 0};
  sb_engine_set_fluid(e, SB_FLUID_UNIFORM, U);
  ck_assert_int_eq(sb_engine_step(e), SB_EINVAL);
  sb_engine_free(e);
}
END_TEST

/* ------------------------------------------------ gravity and drag */

START_TEST(test_drag_factor)
{
  ck_assert(sb_drag_factor(SB_DRAG_STOKES, 5.0) == 1.0);
  ck_assert_rel(sb_drag_factor(SB_DRAG_SCHILLER_NAUMANN, 1.0), 1.15, 1e-15);
  ck_assert_rel(sb_drag_factor(SB_DRAG_SCHILLER_NAUMANN, 100.0),
                1.0 + 0.15 * exp(0.687 * log(100.0)), 1e-14);
  ck_assert_rel(sb_drag_factor(SB_DRAG_SCHILLER_NAUMANN, 2000.0),
                0.44 * 2000.0 / 24.0, 1e-15);
  /* nearly continuous at Re = 1000 */
  double a = sb_drag_factor(SB_DRAG_SCHILLER_NAUMANN, 1000.0),
         b = sb_drag_factor(SB_DRAG_SCHILLER_NAUMANN, 1000.0 + 1e-9);
  ck_assert(fabs(a / b - 1.0) < 4e-3);
  ck_assert(isnan(sb_drag_factor(SB_DRAG_STOKES, -1.0)));
}
END_TEST

/* Stokes settling with buoyancy reached from rest, and the terminal
 * velocity of Schiller-Naumann drag against bisection. */
START_TEST(test_settling)
{
  const double r = 1e-5, rho = 2500.0, m = rho * 4.0 / 3.0 * PI_ * r * r * r;
  sb_engine *e = eng(1e-3, 1e-4, 4, 1);
  sb_engine_species s = {r, m, 2e-5, 0.0, 0.0};
  sb_engine_add_species(e, &s, NULL);
  sb_engine_species_fluid fl = {SB_DRAG_STOKES, 1000.0, 1e-3};
  ck_assert_int_eq(sb_engine_set_species_fluid(e, 0, &fl), 0);
  double g[3] = {0, -9.81, 0}, v[3];
  ck_assert_int_eq(sb_engine_set_gravity(e, g), 0);
  ck_assert_int_eq(sb_engine_settling_velocity(e, 0, v), 0);
  ck_assert_rel(v[1], -2e-5 * 9.81 * (1.0 - 1000.0 / 2500.0), 1e-14);
  double x[3] = {5e-4, 5e-4, 5e-4}, u[3] = {0, 0, 0};
  sb_engine_add_particle(e, 0, 0, x, u);
  for (int k = 0; k < 10; k++)
    ck_assert_int_eq(sb_engine_step(e), 0);
  ck_assert_rel(sb_engine_velocities(e)[1], v[1], 1e-12);
  /* free flight and gravity */
  sb_engine_species f = {r, m, INFINITY, 0.0, 300.0};
  sb_engine_add_species(e, &f, NULL);
  ck_assert_int_eq(sb_engine_step(e), SB_EINVAL);
  /* a fill draws the settling velocity: it fails as the step does (not
   * succeed without it, leaving the message behind) and adds nothing */
  sb_clear_error();
  ck_assert_int_eq(sb_engine_fill_random(e, 0, 0, 2), SB_EINVAL);
  ck_assert_int_eq(sb_last_status(), SB_EINVAL);
  ck_assert_ptr_nonnull(strstr(sb_last_error(), "free-flight"));
  ck_assert_uint_eq(sb_engine_count(e), 1);
  sb_engine_free(e);

  /* Schiller-Naumann: 100 um water drop in air */
  e = eng(1e-2, 1e-4, 4, 1);
  const double r2 = 5e-5, m2 = 1000.0 * 4.0 / 3.0 * PI_ * r2 * r2 * r2;
  const double tau = 1000.0 * 4 * r2 * r2 / (18 * 1.8e-5);
  sb_engine_species s2 = {r2, m2, tau, 0.0, 0.0};
  sb_engine_add_species(e, &s2, NULL);
  sb_engine_species_fluid sn = {SB_DRAG_SCHILLER_NAUMANN, 1.2, 1.8e-5};
  ck_assert_int_eq(sb_engine_set_species_fluid(e, 0, &sn), 0);
  sb_engine_set_gravity(e, g);
  sb_engine_settling_velocity(e, 0, v);
  const double vst = tau * 9.81 * (1 - 1.2 / 1000.0);
  double lo = 0, hi = vst;
  for (int it = 0; it < 100; it++) {
    double mm = 0.5 * (lo + hi), Re = 1.2 * mm * 2 * r2 / 1.8e-5;
    if (mm * (1 + 0.15 * pow(Re, 0.687)) < vst)
      lo = mm;
    else
      hi = mm;
  }
  ck_assert_rel(-v[1], 0.5 * (lo + hi), 1e-12);
  /* a Brownian species cannot take a nonlinear law */
  sb_engine_species s3 = {r2, m2, tau, 1.0, 0.0};
  sb_engine_add_species(e, &s3, NULL);
  ck_assert_int_eq(sb_engine_set_species_fluid(e, 1, &sn), SB_EINVAL);
  sb_engine_free(e);
}
END_TEST

/* Reference: du/dt = -(f(Re)/tau)(u - w) + a by RK4, 3-D. */
static void sn_rhs(const double *u, double tau, const double *a, double k,
                   double *d)
{
  double v = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
  double f = 1.0 + 0.15 * pow(k * v, 0.687);
  for (int c = 0; c < 3; c++)
    d[c] = -f / tau * u[c] + a[c];
}

/* u(T), x(T) of the engine with n steps, and the RK4 reference. */
static void sn_run(int n, double T, double *xe, double *ue)
{
  const double r = 5e-5, tau = 0.0077, m = 1e-9;
  sb_engine *e = eng(10.0, T / n, 4, 1);
  sb_engine_species s = {r, m, tau, 0.0, 0.0};
  sb_engine_add_species(e, &s, NULL);
  sb_engine_species_fluid sn = {SB_DRAG_SCHILLER_NAUMANN, 1.2, 1.8e-5};
  sb_engine_set_species_fluid(e, 0, &sn);
  double g[3] = {0.0, -9.81, 0.0};
  sb_engine_set_gravity(e, g);
  double x[3] = {5, 5, 5}, u[3] = {2.0, 1.0, -0.5};
  sb_engine_add_particle(e, 0, 0, x, u);
  for (int k = 0; k < n; k++)
    ck_assert_int_eq(sb_engine_step(e), 0);
  memcpy(ue, sb_engine_velocities(e), 3 * sizeof(double));
  memcpy(xe, sb_engine_positions(e), 3 * sizeof(double));
  sb_engine_free(e);
}

START_TEST(test_sn_order)
{
  /* rho_p = 1e-9 / (4/3 pi 1.25e-13) = 1910 kg/m^3, buoyancy 1.2/1910 */
  const double T = 0.02, r = 5e-5, tau = 0.0077;
  const double rho_p = 1e-9 / (4.0 / 3.0 * PI_ * r * r * r);
  const double a[3] = {0.0, -9.81 * (1 - 1.2 / rho_p), 0.0};
  const double k = 1.2 * 2 * r / 1.8e-5;
  double u[3] = {2.0, 1.0, -0.5}, x[3] = {5, 5, 5};
  const long N = 200000;
  const double h = T / N;
  for (long q = 0; q < N; q++) {
    double k1[3], k2[3], k3[3], k4[3], t[3];
    sn_rhs(u, tau, a, k, k1);
    for (int c = 0; c < 3; c++)
      t[c] = u[c] + 0.5 * h * k1[c];
    sn_rhs(t, tau, a, k, k2);
    for (int c = 0; c < 3; c++)
      t[c] = u[c] + 0.5 * h * k2[c];
    sn_rhs(t, tau, a, k, k3);
    for (int c = 0; c < 3; c++)
      t[c] = u[c] + h * k3[c];
    sn_rhs(t, tau, a, k, k4);
    for (int c = 0; c < 3; c++) {
      /* x with the same stages (u is linear in the stages) */
      x[c] += h * (u[c] + h / 6.0 * (k1[c] + k2[c] + k3[c]));
      u[c] += h / 6.0 * (k1[c] + 2 * k2[c] + 2 * k3[c] + k4[c]);
    }
  }
  double err[3];
  for (int q = 0; q < 3; q++) {
    double xe[3], ue[3];
    sn_run(10 << q, T, xe, ue);
    double d = 0;
    for (int c = 0; c < 3; c++)
      d += (ue[c] - u[c]) * (ue[c] - u[c]);
    err[q] = sqrt(d);
  }
  for (int q = 0; q < 2; q++) {
    double ratio = err[q] / err[q + 1];
    ck_assert_msg(ratio > 3.5 && ratio < 4.6, "error ratio %g (%g, %g): "
                  "not second order", ratio, err[q], err[q + 1]);
  }
}
END_TEST

/* ------------------------------------------------ walls */

/* Bridge detector: particles at distance h0 from an absorbing plane,
 * Brownian (dt/tau_p = 1e6), one step.  P(contact) = 2 Phi(-h0/sqrt(2 D
 * dt)) by the reflection principle; 40000 particles, exact binomial test
 * at p >= 1e-4.  Chord-only detection gives Phi(-h0/sqrt(2 D dt)). */
static int never(const sb_engine *e, const sb_engine_pair *p,
                 const gsl_rng *r, void *ctx, double *s)
{
  (void)e, (void)p, (void)r, (void)ctx, (void)s;
  return 0;
}

START_TEST(test_wall_bridge_mc)
{
  const double tau = 1e-6, dt = 1.0, D = 1e-6;
  const double B = sqrt(2.0 * D) / tau, sig = sqrt(2.0 * D * dt);
  const double h0 = 0.8 * sig, r = 1e-6;
  const size_t N = 40000;
  for (int det = 0; det < 2; det++) {
    sb_engine_params p;
    sb_engine_params_default(&p);
    p.L[0] = p.L[2] = 2.0;
    p.L[1] = 0.1;
    p.dt = dt;
    p.capacity = N;
    p.seed = 21 + det;
    p.outcome = SB_OUTCOME_COUNT;
    sb_engine *e = sb_engine_alloc(&p);
    sb_engine_species s = {r, 1.0, tau, B, 0.0};
    sb_engine_add_species(e, &s, NULL);
    ck_assert_int_eq(sb_engine_set_walls(e, 1, SB_WALL_ABSORB,
                                         SB_WALL_REFLECT), 0);
    sb_engine_set_wall_mode(e, det ? SB_WALLDET_BALLISTIC
                                   : SB_WALLDET_BRIDGE, SB_DEPOSIT_REMOVE);
    sb_engine_set_detector(e, never, NULL, 0.0);
    gsl_rng *rg = gsl_rng_alloc(gsl_rng_mt19937);
    for (size_t k = 0; k < N; k++) {
      double x[3] = {2.0 * gsl_rng_uniform(rg), r + h0,
                     2.0 * gsl_rng_uniform(rg)}, u[3] = {0, 0, 0};
      sb_engine_add_particle(e, 0, 0, x, u);
    }
    gsl_rng_free(rg);
    ck_assert_int_eq(sb_engine_step(e), 0);
    uint64_t c = sb_engine_deposits(e, 2);
    ck_assert_uint_eq(sb_engine_count(e), N - c);
    double P = (det ? 1.0 : 2.0) * gsl_cdf_ugaussian_P(-h0 / sig);
    double pv = sb_binomial_pvalue((unsigned long)c, N, P);
    ck_assert_msg(pv >= 1e-4, "det %d: %llu of %zu, P = %g, p = %g", det,
                  (unsigned long long)c, N, P, pv);
    /* reflecting top: everybody below L - r */
    const double *x = sb_engine_positions(e);
    for (size_t i = 0; i < sb_engine_count(e); i++)
      ck_assert(x[3 * i + 1] >= r && x[3 * i + 1] <= 0.1 - r);
    sb_engine_free(e);
  }
}
END_TEST

/* Ballistic deposition: a particle falling at v reaches the floor in the
 * step that takes it below r; with reinsertion N stays. */
START_TEST(test_wall_ballistic)
{
  sb_engine *e = eng(10.0, 0.1, 4, 1);
  sb_engine_species s = {0.5, 1.0, INFINITY, 0.0, 1.0};
  sb_engine_add_species(e, &s, NULL);
  ck_assert_int_eq(sb_engine_set_walls(e, 1, SB_WALL_ABSORB, SB_WALL_ABSORB),
                   0);
  ck_assert_int_eq(sb_engine_set_walls(e, 0, SB_WALL_PERIODIC,
                                       SB_WALL_ABSORB), SB_EINVAL);
  sb_engine_set_wall_mode(e, SB_WALLDET_BALLISTIC, SB_DEPOSIT_REINSERT);
  double x[3] = {5, 2.0, 5}, u[3] = {0, -1.0, 0};
  sb_engine_add_particle(e, 0, 0, x, u);
  /* contact plane y = 0.5 reached at t = 1.5: step 15 */
  for (int k = 0; k < 14; k++)
    sb_engine_step(e);
  ck_assert_uint_eq(sb_engine_deposits(e, 2), 0);
  sb_engine_step(e);
  sb_engine_step(e);
  ck_assert_uint_eq(sb_engine_deposits(e, 2), 1);
  ck_assert_uint_eq(sb_engine_count(e), 1);
  ck_assert(!sb_engine_periodic(e, 1) && sb_engine_periodic(e, 0));
  sb_engine_free(e);
}
END_TEST

/* ------------------------------------------------ checkpoint */

static sb_engine *cp_engine(void)
{
  sb_engine *e = eng(1e-3, 2e-4, 200, 5);
  const double r = 1e-5, m = 2500.0 * 4.0 / 3.0 * PI_ * r * r * r;
  sb_engine_species s = {r, m, 2e-5, 0.0, 0.0};
  sb_engine_add_species(e, &s, NULL);
  sb_engine_species_fluid fl = {SB_DRAG_SCHILLER_NAUMANN, 1000.0, 1e-3};
  sb_engine_set_species_fluid(e, 0, &fl);
  double Gp[3] = {50.0, 0, 0}, g[3] = {0, 0, -2000.0};
  sb_engine_set_fluid(e, SB_FLUID_SHEAR, Gp);
  sb_engine_set_lees_edwards(e, 1);
  sb_engine_set_gravity(e, g);
  sb_engine_set_walls(e, 2, SB_WALL_ABSORB, SB_WALL_REFLECT);
  sb_engine_set_wall_mode(e, SB_WALLDET_BALLISTIC, SB_DEPOSIT_REINSERT);
  gsl_rng *rg = gsl_rng_alloc(gsl_rng_mt19937);
  for (int k = 0; k < 150; k++) {
    double x[3] = {1e-3 * gsl_rng_uniform(rg), 1e-3 * gsl_rng_uniform(rg),
                   1e-5 + 0.98e-3 * gsl_rng_uniform(rg)};
    double u[3] = {0, 0, -1e-3 * gsl_rng_uniform(rg)};
    sb_engine_add_particle(e, 0, 0, x, u);
  }
  gsl_rng_free(rg);
  return e;
}

START_TEST(test_checkpoint)
{
  sb_engine *a = cp_engine();
  for (int k = 0; k < 30; k++)
    ck_assert_int_eq(sb_engine_step(a), 0);
  char path[] = "/tmp/sbphysXXXXXX";
  int fd = mkstemp(path);
  ck_assert(fd >= 0);
  close(fd);
  ck_assert_int_eq(sb_engine_checkpoint_save(a, path), 0);
  int st;
  sb_engine *b = sb_engine_checkpoint_load(path, &st);
  ck_assert_ptr_nonnull(b);
  /* more room (2000 for the file's 200) changes nothing else; less, or
   * 0, leaves the file's; more than 2^40 is refused */
  sb_engine *c = sb_engine_checkpoint_load_capacity(path, 2000, &st);
  ck_assert_ptr_nonnull(c);
  ck_assert_uint_eq(sb_engine_get_params(c)->capacity, 2000);
  sb_engine *d = sb_engine_checkpoint_load_capacity(path, 0, NULL);
  ck_assert_ptr_nonnull(d);
  ck_assert_uint_eq(sb_engine_get_params(d)->capacity, 200);
  sb_engine_free(d);
  st = 0;
  ck_assert_ptr_null(sb_engine_checkpoint_load_capacity(
      path, ((size_t)1 << 40) + 1, &st));
  ck_assert_int_eq(st, SB_EINVAL);
  remove(path);
  ck_assert(sb_engine_lees_edwards_offset(b) ==
            sb_engine_lees_edwards_offset(a));
  for (int k = 0; k < 40; k++) {
    ck_assert_int_eq(sb_engine_step(a), 0);
    ck_assert_int_eq(sb_engine_step(b), 0);
    ck_assert_int_eq(sb_engine_step(c), 0);
  }
  ck_assert_uint_eq(sb_engine_count(a), sb_engine_count(c));
  ck_assert(memcmp(sb_engine_positions(a), sb_engine_positions(c),
                   3 * sb_engine_count(a) * sizeof(double)) == 0);
  ck_assert(memcmp(sb_engine_velocities(a), sb_engine_velocities(c),
                   3 * sb_engine_count(a) * sizeof(double)) == 0);
  sb_engine_free(c);
  ck_assert_uint_eq(sb_engine_count(a), sb_engine_count(b));
  ck_assert(memcmp(sb_engine_positions(a), sb_engine_positions(b),
                   3 * sb_engine_count(a) * sizeof(double)) == 0);
  ck_assert(memcmp(sb_engine_velocities(a), sb_engine_velocities(b),
                   3 * sb_engine_count(a) * sizeof(double)) == 0);
  ck_assert_uint_eq(sb_engine_deposits(a, 4), sb_engine_deposits(b, 4));
  ck_assert(sb_engine_deposits(a, 4) > 0);
  sb_engine_species_fluid fl;
  sb_engine_get_species_fluid(b, 0, &fl);
  ck_assert(fl.drag == SB_DRAG_SCHILLER_NAUMANN && fl.rho_f == 1000.0);
  sb_engine_walldet det = SB_WALLDET_BRIDGE;
  sb_engine_deposit dep = SB_DEPOSIT_REMOVE;
  ck_assert_int_eq(sb_engine_get_wall_mode(b, &det, &dep), SB_SUCCESS);
  ck_assert(det == SB_WALLDET_BALLISTIC && dep == SB_DEPOSIT_REINSERT);
  ck_assert_int_eq(sb_engine_get_wall_mode(b, NULL, NULL), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_get_wall_mode(NULL, &det, &dep), SB_EINVAL);
  /* the walls the checkpoint restored: z absorbing below, reflecting
   * above; x and y periodic */
  sb_engine_wall lo = SB_WALL_OPEN, hi = SB_WALL_OPEN;
  ck_assert_int_eq(sb_engine_get_walls(b, 2, &lo, &hi), SB_SUCCESS);
  ck_assert(lo == SB_WALL_ABSORB && hi == SB_WALL_REFLECT);
  for (int k = 0; k < 2; k++) {
    lo = hi = SB_WALL_OPEN;
    ck_assert_int_eq(sb_engine_get_walls(b, k, &lo, &hi), SB_SUCCESS);
    ck_assert(lo == SB_WALL_PERIODIC && hi == SB_WALL_PERIODIC);
  }
  ck_assert_int_eq(sb_engine_get_walls(b, 2, NULL, NULL), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_get_walls(b, 3, &lo, &hi), SB_EINVAL);
  ck_assert_int_eq(sb_engine_get_walls(b, -1, &lo, &hi), SB_EINVAL);
  ck_assert_int_eq(sb_engine_get_walls(NULL, 0, &lo, &hi), SB_EINVAL);
  /* the fluid the checkpoint restored: shear G = 50 1/s with the images */
  sb_engine_fluid f = SB_FLUID_REST;
  double fp[3] = {-1, -1, -1};
  int lees = 0;
  ck_assert_int_eq(sb_engine_get_fluid(b, &f, fp, &lees), SB_SUCCESS);
  ck_assert(f == SB_FLUID_SHEAR && fp[0] == 50.0 && fp[1] == 0.0 &&
            fp[2] == 0.0 && lees == 1);
  ck_assert_int_eq(sb_engine_get_fluid(b, NULL, NULL, NULL), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_get_fluid(NULL, &f, fp, &lees), SB_EINVAL);
  sb_engine_set_lees_edwards(b, 0);
  sb_engine_set_fluid(b, SB_FLUID_REST, NULL);
  ck_assert_int_eq(sb_engine_get_fluid(b, &f, fp, &lees), SB_SUCCESS);
  ck_assert(f == SB_FLUID_REST && fp[0] == 0.0 && lees == 0);
  sb_engine_free(a);
  sb_engine_free(b);
}
END_TEST

/* A deterministic Langevin particle (B = 0, tau = 1) dips below the
 * contact plane inside a step and comes back: from y = 0.3 (plane at
 * r = 0.1) with u_y = -1 and settling velocity +0.8 its path is
 * y(t) = 0.3 + 0.8 t - 1.8 (1 - e^{-t}), below 0.1 for t in about
 * (0.3, 1.4), back at 0.344 at t = dt = 2.  The Langevin wall detector
 * deposits it; the chord and the Brownian bridge (no noise) do not. */
START_TEST(test_wall_langevin_dip)
{
  static const sb_engine_walldet dets[3] = {
      SB_WALLDET_LANGEVIN, SB_WALLDET_BALLISTIC, SB_WALLDET_BRIDGE};
  for (int d = 0; d < 3; d++) {
    sb_engine *e = eng(10.0, 2.0, 4, 1);
    sb_engine_species s = {0.1, 1.0, 1.0, 0.0, 0.0};
    sb_engine_add_species(e, &s, NULL);
    double g[3] = {0.0, 0.8, 0.0};
    ck_assert_int_eq(sb_engine_set_gravity(e, g), 0);
    ck_assert_int_eq(sb_engine_set_walls(e, 1, SB_WALL_ABSORB,
                                         SB_WALL_ABSORB), 0);
    ck_assert_int_eq(sb_engine_set_wall_mode(e, dets[d], SB_DEPOSIT_REMOVE),
                     0);
    double x[3] = {5.0, 0.3, 5.0}, u[3] = {0.0, -1.0, 0.0};
    sb_engine_add_particle(e, 0, 0, x, u);
    ck_assert_int_eq(sb_engine_step(e), 0);
    ck_assert_uint_eq(sb_engine_deposits(e, 2), d == 0 ? 1 : 0);
    if (d)
      ck_assert_rel(sb_engine_positions(e)[1],
                    0.3 + 1.6 - 1.8 * (1.0 - exp(-2.0)), 1e-12);
    sb_engine_free(e);
  }
  sb_engine *e = eng(10.0, 2.0, 4, 1);
  ck_assert_int_eq(sb_engine_set_wall_mode(e, (sb_engine_walldet)3,
                                           SB_DEPOSIT_REMOVE), SB_EINVAL);
  sb_engine_free(e);
}
END_TEST

/* The Langevin wall detector follows a nonlinear-drag species along the
 * engine's own step: a drop (Schiller & Naumann, d = 100 um in air,
 * tau_p = 30.9 ms) thrown at the wall y = 0 at 2 m/s travels 37.5 mm in
 * dt = 50 ms (the Stokes relaxation of tau_p would travel 49.6 mm).  Its
 * surface starting 42 mm from the wall: no deposit (with the Stokes
 * path, as before, one); 33 mm: one. */
START_TEST(test_wall_langevin_drag)
{
  for (int near = 0; near < 2; near++) {
    sb_engine *e = eng(1.0, 0.05, 4, 1);
    const double r = 50e-6,
                 m = 1000.0 * 4.0 / 3.0 * 3.14159265358979 * r * r * r;
    const sb_engine_species s = {r, m, 1000.0 * 4.0 * r * r / (18.0 * 1.8e-5),
                                 0.0, 0.0};
    ck_assert_int_eq(sb_engine_add_species(e, &s, NULL), 0);
    const sb_engine_species_fluid f = {SB_DRAG_SCHILLER_NAUMANN, 1.2,
                                       1.8e-5};
    ck_assert_int_eq(sb_engine_set_species_fluid(e, 0, &f), 0);
    ck_assert_int_eq(sb_engine_set_walls(e, 1, SB_WALL_ABSORB,
                                         SB_WALL_ABSORB), 0);
    ck_assert_int_eq(sb_engine_set_wall_mode(e, SB_WALLDET_LANGEVIN,
                                             SB_DEPOSIT_REMOVE), 0);
    double x[3] = {0.5, r + (near ? 0.033 : 0.042), 0.5},
           u[3] = {0.0, -2.0, 0.0};
    sb_engine_add_particle(e, 0, 0, x, u);
    ck_assert_int_eq(sb_engine_step(e), 0);
    ck_assert_uint_eq(sb_engine_deposits(e, 2), (unsigned)near);
    sb_engine_free(e);
  }
}
END_TEST

static Suite *suite(void)
{
  Suite *s = suite_create("engine_physics");
  TCase *tc = tcase_create("physics");
  tcase_set_timeout(tc, 60);
  tcase_add_test(tc, test_shear_exact_step);
  tcase_add_test(tc, test_shear_coefs);
  tcase_add_test(tc, test_le_wrap);
  tcase_add_test(tc, test_le_superset);
  tcase_add_test(tc, test_le_pair_collides);
  tcase_add_test(tc, test_le_bridge_detectors);
  tcase_add_test(tc, test_le_errors);
  tcase_add_test(tc, test_drag_factor);
  tcase_add_test(tc, test_settling);
  tcase_add_test(tc, test_sn_order);
  tcase_add_test(tc, test_wall_bridge_mc);
  tcase_add_test(tc, test_wall_ballistic);
  tcase_add_test(tc, test_wall_langevin_dip);
  tcase_add_test(tc, test_wall_langevin_drag);
  tcase_add_test(tc, test_checkpoint);
  suite_add_tcase(s, tc);
  return s;
}

int main(void) { return sbt_run_suite(suite()); }
