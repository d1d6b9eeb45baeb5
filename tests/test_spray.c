/* test_spray.c — deterministic checks of the spray module: collision
 * geometry and conservation, the exact solutions (BKW, two-temperature,
 * TAB, Reitz) against mpmath references (tests/gen_spray_ref.py ->
 * tests/data/spray_*.csv: BKW verified there as a solution in Bobylev's
 * Fourier form, the ODEs integrated by Taylor series), conservation of the
 * operators to round-off, and argument checking. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>

#include <smolbridge/langevin.h>
#include <smolbridge/spray.h>

#include "refdata.h"
#include "spray_extreme.h"
#include "sweep.h"
#include "testutil.h"

#define PI 3.14159265358979323846

static double dot3(const double *a, const double *b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* ------------------------------------------------ collision geometry */

START_TEST(test_post_collision_conserves)
{
  gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
  gsl_rng_set(r, 5);
  for (int k = 0; k < 2000; k++) {
    double v1[3], v2[3], s[3], a[3], b[3];
    double m1 = exp(4 * gsl_rng_uniform(r) - 2), m2 = exp(4 * gsl_rng_uniform(r) - 2);
    for (int q = 0; q < 3; q++) {
      v1[q] = gsl_ran_gaussian(r, 1.0);
      v2[q] = gsl_ran_gaussian(r, 3.0);
    }
    gsl_ran_dir_3d(r, &s[0], &s[1], &s[2]);
    sb_spray_post_collision(v1, v2, m1, m2, s, a, b);
    double e0 = m1 * dot3(v1, v1) + m2 * dot3(v2, v2);
    double e1 = m1 * dot3(a, a) + m2 * dot3(b, b);
    ck_assert_rel(e1, e0, 64 * DBL_EPSILON);
    double sc = m1 * sqrt(dot3(v1, v1)) + m2 * sqrt(dot3(v2, v2));
    for (int q = 0; q < 3; q++)
      ck_assert_abs(m1 * a[q] + m2 * b[q], m1 * v1[q] + m2 * v2[q],
                    16 * DBL_EPSILON * sc);
    /* the relative velocity turns to |g| sigma */
    double g[3] = {v1[0] - v2[0], v1[1] - v2[1], v1[2] - v2[2]}, gm = sqrt(dot3(g, g));
    for (int q = 0; q < 3; q++)
      ck_assert_abs(a[q] - b[q], gm * s[q], 64 * DBL_EPSILON * gm);
    /* the thesis slides' form with m proportional to r^3 */
    double r1 = cbrt(m1), r2 = cbrt(m2), R = r1 * r1 * r1 + r2 * r2 * r2;
    for (int q = 0; q < 3; q++) {
      double G = (r1 * r1 * r1 * v1[q] + r2 * r2 * r2 * v2[q]) / R;
      ck_assert_abs(a[q], G + r2 * r2 * r2 / R * gm * s[q], 1e-13 * (1 + gm));
      ck_assert_abs(b[q], G - r1 * r1 * r1 / R * gm * s[q], 1e-13 * (1 + gm));
    }
  }
  gsl_rng_free(r);
}
END_TEST

START_TEST(test_coalescence_geometry)
{
  /* b^2/(r+r*)^2 = (1 + cos chi)/2 <= sin^2(theta_cr) */
  double th = 0.3, c = -cos(2 * th);
  ck_assert_int_eq(sb_spray_coalesces(c - 1e-12, th), 1);
  ck_assert_int_eq(sb_spray_coalesces(c + 1e-12, th), 0);
  ck_assert_int_eq(sb_spray_coalesces(-1.0, 0.0), 0);
  ck_assert_int_eq(sb_spray_coalesces(1.0, 0.5 * PI), 1);
  ck_assert_int_eq(sb_spray_coalesces(-1.0, 0.5 * PI), 1);
  /* NaN (or an infinite angle): 0 with SB_EDOM recorded, the status
   * channel of an int result; valid arguments leave the record clear */
  const double bad[][2] = {{NAN, 0.3}, {-0.5, NAN}, {NAN, 0.0},
                           {-1.0, INFINITY}, {-1.0, -INFINITY}};
  for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
    sb_clear_error();
    ck_assert_int_eq(sb_spray_coalesces(bad[i][0], bad[i][1]), 0);
    ck_assert_int_eq(sb_last_status(), SB_EDOM);
    ck_assert_ptr_nonnull(strstr(sb_last_error(), "sb_spray_coalesces"));
  }
  sb_clear_error();
  ck_assert_int_eq(sb_spray_coalesces(-INFINITY, 0.3), 1);
  ck_assert_int_eq(sb_spray_coalesces(INFINITY, 0.3), 0);
  ck_assert_int_eq(sb_spray_coalesces(c, 0.0), 0);
  ck_assert_int_eq(sb_last_status(), SB_SUCCESS);
  /* cos chi is uniform on [-1, 1] for isotropic sigma: the merging
   * fraction (1 + c)/2 is sin^2 theta_cr */
  ck_assert_rel(0.5 * (1 + c), sin(th) * sin(th), 4 * DBL_EPSILON);
  ck_assert_rel(sb_spray_pair_rate(SB_SPRAY_HARD_SPHERE, 0, 1, 2, 3),
                PI * 9 * 3, TOL_TIGHT);
  ck_assert_rel(sb_spray_pair_rate(SB_SPRAY_MAXWELL, 2.5, 1, 2, 3), 2.5,
                TOL_TIGHT);
  sb_spray_settling st = {1000, 1.2, 1.8e-5, {0, 0, -9.80665}};
  double v[3];
  sb_spray_stokes_settling(1e-5, v, &st);
  ck_assert_rel(v[2], -2 * (1000 - 1.2) * 9.80665 * 1e-10 / (9 * 1.8e-5),
                TOL_TIGHT);
  ck_assert_abs(v[0], 0, 0);
}
END_TEST

/* ------------------------------------------------ exact solutions */

START_TEST(test_bkw_reference)
{
  sbt_table t;
  sbt_table_load("spray_bkw.csv", &t);
  int ck = sbt_col(&t, "kind"), cx = sbt_col(&t, "x"), cK = sbt_col(&t, "K"),
      cv = sbt_col(&t, "value");
  for (int i = 0; i < t.nrow; i++) {
    int kind = (int)sbt_at(&t, i, ck);
    double x = sbt_at(&t, i, cx), K = sbt_at(&t, i, cK), ref = sbt_at(&t, i, cv);
    double got = kind == 0   ? sb_spray_bkw_pdf(x, K, 1.0)
                 : kind == 1 ? sb_spray_bkw_speed_cdf(x, K, 1.0)
                 : kind == 4 ? sb_spray_bkw_m4(K, 1.0)
                             : sb_spray_bkw_m6(K, 1.0);
    if (ref == 0)
      ck_assert_abs(got, 0, 1e-17);
    else
      ck_assert_msg(sbt_reldiff(got, ref) <= 1e-13,
                    "kind %d x %g K %g: %.17g vs %.17g", kind, x, K, got, ref);
  }
  sbt_table_free(&t);
  /* scaling with theta and the time law */
  ck_assert_rel(sb_spray_bkw_m4(0.7, 4.0), 16 * sb_spray_bkw_m4(0.7, 1.0),
                TOL_TIGHT);
  ck_assert_rel(sb_spray_bkw_K(0.6, 2.0, 3.0), 1 - 0.4 * exp(-1.0), TOL_TIGHT);
  ck_assert(isnan(sb_spray_bkw_K(0.5, 1, 1)));
  ck_assert_int_eq(sb_last_status(), SB_EDOM);
  ck_assert(isnan(sb_spray_bkw_pdf(1.0, 0.59, 1.0)));
  ck_assert(isnan(sb_spray_bkw_m4(0.8, -1)));
}
END_TEST

START_TEST(test_two_temperature)
{
  sbt_table t;
  sbt_table_load("spray_twotemp.csv", &t);
  for (int i = 0; i < t.nrow; i++) {
    const double *r = t.v + (size_t)i * t.ncol;
    sb_spray_mixture mx = {r[0], r[1], r[2], r[3], r[4], r[5], r[6], r[7]};
    double Ta, Tb;
    ck_assert_int_eq(sb_spray_two_temp_hs(&mx, r[8], &Ta, &Tb), SB_SUCCESS);
    ck_assert_msg(sbt_reldiff(Ta, r[9]) <= 1e-11, "row %d: %.17g vs %.17g",
                  i, Ta, r[9]);
    /* n_a T_a + n_b T_b is conserved */
    ck_assert_rel(mx.n_a * Ta + mx.n_b * Tb, mx.n_a * mx.T_a0 + mx.n_b * mx.T_b0,
                  64 * DBL_EPSILON);
    /* the closed form's slope at t = 0 is the rate */
    double h = 1e-7 * fabs((mx.T_a0 - mx.T_b0) /
                           sb_spray_two_temp_hs_rate(&mx, mx.T_a0, mx.T_b0));
    double Tp, Tm;
    sb_spray_two_temp_hs(&mx, h, &Tp, NULL);
    sb_spray_two_temp_hs(&mx, 0, &Tm, NULL);
    ck_assert_rel((Tp - Tm) / h, sb_spray_two_temp_hs_rate(&mx, mx.T_a0, mx.T_b0),
                  1e-6);
  }
  sbt_table_free(&t);
  /* Maxwell kernel: exponential with rate 2 B0 (n_a + n_b) m_a m_b/M^2 */
  sb_spray_mixture mx = {1.0, 3.0, 1e-12, 3e-12, 1e-5, 2e-5, 400, 100};
  double Ta, Tb, rate = 2 * 0.5 * 4.0 * 3e-24 / (16e-24);
  ck_assert_int_eq(sb_spray_two_temp_maxwell(&mx, 0.5, 2.0, &Ta, &Tb), 0);
  ck_assert_rel(Ta - Tb, 300 * exp(-rate * 2.0), 1e-14);
  ck_assert_rel(Ta + 3 * Tb, 700, 1e-15);
  mx.T_a0 = -1;
  ck_assert_int_eq(sb_spray_two_temp_maxwell(&mx, 0.5, 1, &Ta, &Tb), SB_EDOM);
  ck_assert_int_eq(sb_spray_two_temp_hs(&mx, 1, &Ta, &Tb), SB_EDOM);
}
END_TEST

static sb_spray_liquid liq_of(double sigma, double mu)
{
  sb_spray_liquid l = {sigma, mu};
  return l;
}

START_TEST(test_tab_reference)
{
  sbt_table t;
  sbt_table_load("spray_tab.csv", &t);
  for (int i = 0; i < t.nrow; i++) {
    const double *r = t.v + (size_t)i * t.ncol;
    /* case,r,U,rho_g,rho_l,sigma,mu_l,Cd,y0,yd0,t,y,yd */
    sb_spray_liquid liq = liq_of(r[5], r[6]);
    double w0 = sqrt(8 * r[5] / (r[4] * r[1] * r[1] * r[1]));
    if (r[10] < 0) {
      double tb;
      ck_assert_int_eq(sb_spray_tab_breakup_time(r[1], r[2], r[3], r[4], &liq,
                                                 r[7], r[8], r[9], 4e-4, &tb,
                                                 NULL),
                       SB_SUCCESS);
      if (isinf(r[11]))
        ck_assert_msg(isinf(tb), "case %g: breakup at %g, none expected",
                      r[0], tb);
      else
        ck_assert_msg(sbt_reldiff(tb, r[11]) <= 1e-10,
                      "case %g: t_b %.17g vs %.17g", r[0], tb, r[11]);
      continue;
    }
    double y, yd;
    ck_assert_int_eq(sb_spray_tab_state(r[10], r[1], r[2], r[3], r[4], &liq,
                                        r[7], r[8], r[9], &y, &yd),
                     SB_SUCCESS);
    ck_assert_msg(fabs(y - r[11]) <= 1e-12 * (1 + fabs(r[11])),
                  "case %g t %g: y %.17g vs %.17g", r[0], r[10], y, r[11]);
    ck_assert_msg(fabs(yd - r[12]) <= 1e-12 * w0 * (1 + fabs(r[11])),
                  "case %g t %g: yd %.17g vs %.17g", r[0], r[10], yd, r[12]);
  }
  sbt_table_free(&t);
}
END_TEST

START_TEST(test_tab_critical_and_r32)
{
  const double r = 1e-4, rho_l = 1000, rho_g = 1.2;
  sb_spray_liquid inv = liq_of(0.072, 0), vis = liq_of(0.072, 1e-3);
  ck_assert_rel(sb_spray_tab_we_crit(r, rho_l, &inv, 5), 6.0, TOL_TIGHT);
  /* undamped from rest: y = We/12 (1 - cos w t), t_b = acos(1 - 12/We)/w */
  double w0 = sqrt(8 * 0.072 / (rho_l * r * r * r));
  for (double We = 6.5; We < 200; We *= 2) {
    double U = sqrt(We * 0.072 / (rho_g * r)), tb, ydb;
    sb_spray_tab_breakup_time(r, U, rho_g, rho_l, &inv, 5, 0, 0, 1, &tb, &ydb);
    ck_assert_rel(tb, acos(1 - 12 / We) / w0, 1e-11);
    ck_assert_rel(ydb, We / 12 * w0 * sin(w0 * tb), 1e-10);
  }
  /* damped: breakup iff We > We_crit (the first maximum is the largest) */
  double wc = sb_spray_tab_we_crit(r, rho_l, &vis, 5);
  ck_assert(wc > 6 && wc < 6.2);
  for (int s = -1; s <= 1; s += 2) {
    double U = sqrt(wc * (1 + s * 1e-7) * 0.072 / (rho_g * r)), tb;
    sb_spray_tab_breakup_time(r, U, rho_g, rho_l, &vis, 5, 0, 0, 1, &tb, NULL);
    ck_assert_int_eq(isinf(tb) != 0, s < 0);
  }
  /* overdamped: no critical We */
  sb_spray_liquid thick = liq_of(0.072, 10.0);
  ck_assert(isnan(sb_spray_tab_we_crit(1e-5, rho_l, &thick, 5)));
  /* energy: 4 pi r^2 s (1 + 8K/20) + K pi/5 rho r^5 yd^2 = 4 pi r^2 s
   * (r/r32) + pi/6 rho r^5 yd^2, K = 10/3 */
  double yd = 3e4, r32 = sb_spray_tab_r32(r, yd, rho_l, 0.072);
  double K = 10.0 / 3.0, R5 = pow(r, 5);
  ck_assert_rel(4 * PI * r * r * 0.072 * (r / r32) + PI / 6 * rho_l * R5 * yd * yd,
                4 * PI * r * r * 0.072 * (1 + 8 * K / 20) + K * PI / 5 * rho_l * R5 * yd * yd,
                1e-14);
  ck_assert_rel(sb_spray_tab_r32(r, 0, rho_l, 0.072), 3 * r / 7, TOL_TIGHT);
  ck_assert(isnan(sb_spray_tab_r32(-1, 0, 1, 1)));
  double y, ydd;
  ck_assert_int_eq(sb_spray_tab_state(1, -1, 1, 1, 1, &vis, 5, 0, 0, &y, &ydd),
                   SB_EDOM);
}
END_TEST

START_TEST(test_reitz_reference)
{
  sbt_table t;
  sbt_table_load("spray_reitz.csv", &t);
  sb_spray_reitz_params rp;
  sb_spray_reitz_params_default(&rp);
  for (int i = 0; i < t.nrow; i++) {
    const double *r = t.v + (size_t)i * t.ncol;
    /* kind,a,U,rho_g,rho_l,sigma,mu_l,t,value */
    sb_spray_liquid liq = liq_of(r[5], r[6]);
    double L, O, got;
    ck_assert_int_eq(sb_spray_reitz_wave(r[1], r[2], r[3], r[4], &liq, &L, &O),
                     SB_SUCCESS);
    int kind = (int)r[0];
    if (kind == 0)
      got = L;
    else if (kind == 1)
      got = O;
    else if (kind == 2)
      got = sb_spray_reitz_radius_frozen(r[1], rp.B0 * L,
                                         L * O / (3.726 * rp.B1), r[7]);
    else
      ck_assert_int_eq(sb_spray_reitz_radius(r[1], r[7], r[2], r[3], r[4], &liq,
                                             &rp, &got),
                       SB_SUCCESS);
    double tol = kind < 2 ? 1e-13 : (kind == 2 ? 1e-12 : 1e-9);
    ck_assert_msg(sbt_reldiff(got, r[8]) <= tol, "kind %d t %g: %.17g vs %.17g",
                  kind, r[7], got, r[8]);
  }
  sbt_table_free(&t);
  /* frozen closed form: limits and the overflow branch */
  ck_assert_rel(sb_spray_reitz_radius_frozen(5, 1, 1, 0), 5, 0);
  ck_assert_rel(sb_spray_reitz_radius_frozen(0.5, 1, 1, 3), 0.5, 0);
  ck_assert_rel(sb_spray_reitz_radius_frozen(5, 1, 1, 1e4), 1, 1e-15);
  /* x0 = 1999: x + ln x = x0 + ln x0 - c t, starts above e^700 */
  double a = sb_spray_reitz_radius_frozen(2000, 1, 1, 10);
  double x = a - 1;
  ck_assert_rel(x + log(x), 1999 + log(1999.0) - 10, 1e-15);
  ck_assert(isnan(sb_spray_reitz_radius_frozen(-1, 1, 1, 1)));
  double L, O;
  sb_spray_liquid bad = liq_of(-1, 0);
  ck_assert_int_eq(sb_spray_reitz_wave(1e-5, 10, 1, 1000, &bad, &L, &O), SB_EDOM);
}
END_TEST

/* ------------------------------------------------ the operators */

static sb_spray *make_sel(sb_spray_method m, sb_spray_cross c, double theta,
                          size_t n, unsigned long seed, gsl_rng **rng,
                          sb_spray_select sel)
{
  sb_spray_params p;
  sb_spray_params_default(&p);
  p.method = m;
  p.select = sel;
  p.cross = c;
  p.B0 = 1e-6;
  p.volume = 1e-6;
  p.theta_cr = theta;
  sb_spray *s = sb_spray_alloc(&p);
  ck_assert_ptr_nonnull(s);
  *rng = gsl_rng_alloc(gsl_rng_mt19937);
  gsl_rng_set(*rng, seed);
  double T = 4.0 / 3.0 * PI * 1e-15 * 1000 / SB_BOLTZMANN;
  double u[3] = {0.5, 0, -0.2};
  for (size_t i = 0; i < n; i++) {
    double r = 1e-5 * (1 + (double)(i % 3)), v[3];
    double sd = sqrt(SB_BOLTZMANN * T / (1000 * 4.0 / 3.0 * PI * r * r * r));
    for (int k = 0; k < 3; k++)
      v[k] = u[k] + gsl_ran_gaussian(*rng, sd);
    ck_assert_int_eq(sb_spray_add(s, v, r, 0.5 + (double)(i % 4), (int)(i % 3), NULL),
                     SB_SUCCESS);
  }
  return s;
}

static sb_spray *make(sb_spray_method m, sb_spray_cross c, double theta,
                      size_t n, unsigned long seed, gsl_rng **rng)
{
  return make_sel(m, c, theta, n, seed, rng, SB_SPRAY_MAJORANT);
}

START_TEST(test_bird_conserves_exactly)
{
  for (int sel = 0; sel < 2; sel++)
    for (int cr = 0; cr < 2; cr++) {
      gsl_rng *rng;
      sb_spray *s = make_sel(SB_SPRAY_BIRD, (sb_spray_cross)cr, 0, 3000, 7,
                             &rng, (sb_spray_select)sel);
      ck_assert_int_eq(sb_spray_get_params(s)->select, sel);
      sb_spray_totals a, b;
      sb_spray_get_totals(s, &a);
      for (int k = 0; k < 20; k++)
        ck_assert_int_eq(sb_spray_collide(s, 0.02, rng), SB_SUCCESS);
      sb_spray_get_totals(s, &b);
      sb_spray_stats st;
      sb_spray_get_stats(s, &st);
      ck_assert_msg(st.bounces > 1000, "only %llu collisions", st.bounces);
      /* each collision conserves to a few ulp; the round-off of ~1e4
       * collisions adds up like a random walk */
      ck_assert_rel(b.energy, a.energy, 1e-12);
      double ps = a.mass * sqrt(2 * a.energy / a.mass);
      for (int q = 0; q < 3; q++)
        ck_assert_abs(b.momentum[q], a.momentum[q], 1e-13 * ps);
      ck_assert_rel(sb_spray_time(s), 0.4, 1e-14);
      sb_spray_free(s);
      gsl_rng_free(rng);
    }
}
END_TEST

START_TEST(test_ntc_and_names)
{
  sb_spray_method m;
  sb_spray_cross c;
  sb_spray_select sel;
  ck_assert_int_eq(sb_spray_method_from_name("nanbu", &m), 0);
  ck_assert_int_eq(m, SB_SPRAY_NANBU);
  ck_assert_int_eq(sb_spray_cross_from_name("maxwell", &c), 0);
  ck_assert_int_eq(c, SB_SPRAY_MAXWELL);
  ck_assert_int_eq(sb_spray_select_from_name("ntc", &sel), 0);
  ck_assert_int_eq(sel, SB_SPRAY_NTC);
  ck_assert_int_eq(sb_spray_method_from_name("dsmc", &m), SB_EINVAL);
  /* NTC: Bird only; conserves exactly too */
  sb_spray_params p;
  sb_spray_params_default(&p);
  p.select = SB_SPRAY_NTC;
  p.method = SB_SPRAY_NANBU;
  ck_assert_ptr_null(sb_spray_alloc(&p));
  ck_assert_int_eq(sb_last_status(), SB_EINVAL);
  p.method = SB_SPRAY_BIRD;
  p.volume = -1;
  ck_assert_ptr_null(sb_spray_alloc(&p));
  p.volume = 1e-6;
  p.theta_cr = 2;
  ck_assert_ptr_null(sb_spray_alloc(&p));
  p.theta_cr = 0;
  sb_spray *s = sb_spray_alloc(&p);
  gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
  ck_assert_int_eq(sb_spray_add_maxwellian(s, 2000, 1e-5, 1, 0, 1e11, NULL, rng), 0);
  sb_spray_totals a, b;
  sb_spray_get_totals(s, &a);
  for (int k = 0; k < 10; k++)
    sb_spray_collide(s, 0.3, rng);
  sb_spray_get_totals(s, &b);
  ck_assert_rel(b.energy, a.energy, 1e-13);
  sb_spray_stats st;
  sb_spray_get_stats(s, &st);
  ck_assert(st.bounces > 500);
  double v[3] = {0, 0, 0};
  ck_assert_int_eq(sb_spray_add(s, v, -1, 1, 0, NULL), SB_EINVAL);
  v[1] = NAN;
  ck_assert_int_eq(sb_spray_add(s, v, 1, 1, 0, NULL), SB_EINVAL);
  ck_assert_int_eq(sb_spray_collide(s, -1, rng), SB_EINVAL);
  ck_assert_int_eq(sb_spray_set_velocity(s, 1u << 30, v), SB_EINVAL);
  sb_spray_free(s);
  gsl_rng_free(rng);
}
END_TEST

START_TEST(test_coalescence_mass)
{
  for (int m = 0; m < 2; m++) {
    gsl_rng *rng;
    sb_spray *s = make((sb_spray_method)m, SB_SPRAY_HARD_SPHERE, 0.5 * PI, 2000,
                       11, &rng);
    sb_spray_totals a, b;
    sb_spray_get_totals(s, &a);
    for (int k = 0; k < 10; k++)
      ck_assert_int_eq(sb_spray_collide(s, 0.5, rng), SB_SUCCESS);
    sb_spray_get_totals(s, &b);
    sb_spray_stats st;
    sb_spray_get_stats(s, &st);
    ck_assert(st.merges > 200);
    ck_assert_uint_eq(st.bounces, 0);
    ck_assert_rel(b.mass, a.mass, 1e-13);
    ck_assert_rel(b.volume, a.volume, 1e-13);
    ck_assert(b.number < a.number);
    ck_assert(b.energy < a.energy); /* merging is inelastic */
    if (m == 0) { /* Bird: pairs merge into one, momentum exact */
      ck_assert_uint_eq(sb_spray_count(s), 2000 - st.merges);
      double ps = a.mass * sqrt(2 * a.energy / a.mass);
      for (int q = 0; q < 3; q++)
        ck_assert_abs(b.momentum[q], a.momentum[q], 1e-14 * ps);
    } else {
      ck_assert_uint_eq(sb_spray_count(s), 2000);
    }
    sb_spray_free(s);
    gsl_rng_free(rng);
  }
}
END_TEST

START_TEST(test_tab_step_children)
{
  for (int m = 0; m < 2; m++) {
    sb_spray_params p;
    sb_spray_params_default(&p);
    p.method = (sb_spray_method)m;
    sb_spray *s = sb_spray_alloc(&p);
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    double v[3] = {1, 2, 3};
    for (int i = 0; i < 50; i++)
      sb_spray_add(s, v, 1e-4, 2.0, 0, NULL);
    sb_spray_gas gas = {{100, 2, 3}, 1.2, 0};
    sb_spray_liquid liq = liq_of(0.072, 1e-3);
    sb_spray_tab_params tp;
    sb_spray_tab_params_default(&tp);
    tp.child_tag = 3;
    sb_spray_totals a, b;
    sb_spray_get_totals(s, &a);
    /* We = 1.2 * 99^2 * 1e-4/0.072 = 16: breakup at ~5.5e-5 s; the
     * children cannot reach |y| = 1 in the 5e-6 s left */
    ck_assert_int_eq(sb_spray_tab_step(s, &gas, &liq, &tp, 6e-5, rng), 0);
    sb_spray_get_totals(s, &b);
    sb_spray_stats st;
    sb_spray_get_stats(s, &st);
    ck_assert_uint_eq(st.tab_breakups, 50);
    ck_assert_rel(b.volume, a.volume, 1e-13);
    const double *vv = sb_spray_velocities(s);
    const int *tag = sb_spray_tags(s);
    for (size_t i = 0; i < sb_spray_count(s); i++) {
      ck_assert_int_eq(tag[i], 3);
      /* the normal velocity is perpendicular to u - v of the parent */
      double d[3] = {vv[3 * i] - 1, vv[3 * i + 1] - 2, vv[3 * i + 2] - 3};
      ck_assert_abs(d[0], 0, 1e-12); /* u - v = (99, 0, 0) */
      (void)d;
    }
    if (m == 0)
      ck_assert(sb_spray_count(s) > 50);
    else
      ck_assert_uint_eq(sb_spray_count(s), 50);
    sb_spray_free(s);
    gsl_rng_free(rng);
  }
}
END_TEST

START_TEST(test_reitz_step)
{
  for (int m = 0; m < 2; m++) {
    sb_spray_params p;
    sb_spray_params_default(&p);
    p.method = (sb_spray_method)m;
    sb_spray *s = sb_spray_alloc(&p);
    double v[3] = {0, 0, 0};
    for (int i = 0; i < 10; i++)
      sb_spray_add(s, v, 5e-5 + 1e-6 * i, 1.0, 0, NULL);
    sb_spray_gas gas = {{100, 0, 0}, 10, 1.8e-5};
    sb_spray_liquid liq = liq_of(0.072, 1e-3);
    sb_spray_reitz_params rp;
    sb_spray_reitz_params_default(&rp);
    rp.child_tag = 1;
    sb_spray_totals a, b;
    sb_spray_get_totals(s, &a);
    for (int k = 0; k < 100; k++)
      ck_assert_int_eq(sb_spray_reitz_step(s, &gas, &liq, &rp, 1e-6), 0);
    sb_spray_get_totals(s, &b);
    ck_assert_rel(b.volume, a.volume, 1e-14);
    sb_spray_stats st;
    sb_spray_get_stats(s, &st);
    ck_assert(st.reitz_children > 0);
    const double *r = sb_spray_radii(s);
    const int *tag = sb_spray_tags(s);
    for (size_t i = 0; i < sb_spray_count(s); i++)
      if (tag[i] == 1)
        ck_assert(r[i] > 4e-6 && r[i] < 6e-6); /* R = B0 Lambda ~ 5 um */
    /* parent radius vs the frozen closed form over one step */
    double L, O, a0 = r[0];
    sb_spray_reitz_wave(a0, 100, 10, 1000, &liq, &L, &O);
    sb_spray_reitz_step(s, &gas, &liq, &rp, 1e-6);
    ck_assert_rel(sb_spray_radii(s)[0],
                  sb_spray_reitz_radius_frozen(a0, 0.61 * L, L * O / 37.26, 1e-6),
                  1e-15);
    rp.children = SB_SPRAY_CHILDREN_PARCEL;
    if (m == 0)
      ck_assert_int_eq(sb_spray_reitz_step(s, &gas, &liq, &rp, 1e-6), SB_EINVAL);
    sb_spray_free(s);
  }
}
END_TEST

/* Reitz (1987), second branch: when B0 Lambda >= a (low We_g) the drops
 * form once with the volume of a cylinder of radius a and length one
 * wavelength or one wave period's travel U 2 pi/Omega, the smaller. */
START_TEST(test_reitz_blob)
{
  sb_spray_liquid liq = liq_of(0.072, 1e-3);
  const double a = 50e-6, U = 10, rho_g = 1.2;
  double L, O;
  sb_spray_reitz_wave(a, U, rho_g, 1000, &liq, &L, &O);
  ck_assert(0.61 * L > a); /* We_g = 0.083: the second branch */
  double r = sb_spray_reitz_blob_radius(a, U, L, O);
  double vw = PI * a * a * L, vp = PI * a * a * U * (2 * PI / O);
  ck_assert_rel(4.0 / 3.0 * PI * r * r * r, fmin(vw, vp), 1e-14);
  ck_assert(r > a);
  ck_assert(isnan(sb_spray_reitz_blob_radius(a, 0, L, O)));
  /* Nanbu without and with the branch; Bird (constant weights cannot
   * keep the volume) is refused */
  for (int run = 0; run < 3; run++) {
    int blob = run > 0;
    sb_spray_params p;
    sb_spray_params_default(&p);
    p.method = run < 2 ? SB_SPRAY_NANBU : SB_SPRAY_BIRD;
    sb_spray *s = sb_spray_alloc(&p);
    double v[3] = {0, 0, 0};
    sb_spray_add(s, v, a, 2.0, 0, NULL);
    sb_spray_gas gas = {{U, 0, 0}, rho_g, 1.8e-5};
    sb_spray_reitz_params rp;
    sb_spray_reitz_params_default(&rp);
    rp.blob = blob;
    if (run == 2) {
      ck_assert_int_eq(sb_spray_reitz_step(s, &gas, &liq, &rp, 1e-4),
                       SB_EINVAL);
      sb_spray_free(s);
      continue;
    }
    sb_spray_totals t0, t1;
    sb_spray_get_totals(s, &t0);
    for (int k = 0; k < 3; k++) /* once: the formed drop is stable */
      ck_assert_int_eq(sb_spray_reitz_step(s, &gas, &liq, &rp, 1e-4), 0);
    sb_spray_get_totals(s, &t1);
    sb_spray_stats st;
    sb_spray_get_stats(s, &st);
    ck_assert_int_eq(sb_spray_count(s), 1);
    ck_assert_rel(t1.volume, t0.volume, 1e-15);
    if (blob) {
      ck_assert(st.reitz_blobs == 1);
      ck_assert_rel(sb_spray_radii(s)[0], r, 1e-15);
      ck_assert_rel(sb_spray_weights(s)[0], 2.0 * pow(a / r, 3), 1e-15);
    } else { /* a < B0 Lambda: the first branch does nothing */
      ck_assert(st.reitz_blobs == 0);
      ck_assert(sb_spray_radii(s)[0] == a);
    }
    sb_spray_free(s);
  }
}
END_TEST

START_TEST(test_totals_and_temperature)
{
  sb_spray_params p;
  sb_spray_params_default(&p);
  p.method = SB_SPRAY_NANBU;
  sb_spray *s = sb_spray_alloc(&p);
  double v1[3] = {1, 0, 0}, v2[3] = {-1, 0, 2};
  sb_spray_add(s, v1, 1e-5, 2.0, 0, NULL);
  sb_spray_add(s, v2, 1e-5, 1.0, 1, NULL);
  sb_spray_totals t;
  sb_spray_get_totals(s, &t);
  double m = 1000 * 4.0 / 3.0 * PI * 1e-15;
  ck_assert_rel(t.number, 3, TOL_TIGHT);
  ck_assert_rel(t.mass, 3 * m, TOL_TIGHT);
  ck_assert_rel(t.momentum[0], m, TOL_TIGHT);
  ck_assert_rel(t.energy, 0.5 * m * (2 + 5), TOL_TIGHT);
  ck_assert_rel(t.volume, 3 * 4.0 / 3.0 * PI * 1e-15, TOL_TIGHT);
  /* weighted |v|^2 mean: (2*1 + 1*5)/3 */
  ck_assert_rel(sb_spray_velocity_moment(s, 2, NULL, -1), 7.0 / 3.0, TOL_TIGHT);
  ck_assert_rel(sb_spray_velocity_moment(s, 1, v1, 1), sqrt(8.0), TOL_TIGHT);
  ck_assert(isnan(sb_spray_velocity_moment(s, 2, NULL, 7)));
  /* one parcel per tag: no thermal spread */
  ck_assert_abs(sb_spray_temperature(s, 0), 0, 1e-30);
  /* both: mean velocity (1/3, 0, 2/3); sum w m |v - u|^2 = m (2 (4/9 +
   * 4/9) + (16/9 + 16/9)) = m 48/9 */
  ck_assert_rel(sb_spray_temperature(s, -1), m * 48.0 / 9.0 / (9 * SB_BOLTZMANN),
                1e-13);
  sb_spray_clear(s);
  ck_assert_uint_eq(sb_spray_count(s), 0);
  sb_spray_free(s);
}
END_TEST

/* ------------------------------------------------- extreme arguments */

/* One public reference function of spray.h on an argument vector a: its
 * status (sb_last_status for the plain forms, after sb_clear_error), its
 * outputs out[0..n-1] and the name its error messages must carry. */
typedef sbt_xfn xfn;

#define XPLAIN(NAME, FN, ...)                                              \
  static int NAME(const double *a, double *out, int *n, const char **nm)   \
  {                                                                         \
    *nm = #FN;                                                              \
    sb_clear_error();                                                       \
    out[0] = FN(__VA_ARGS__);                                               \
    *n = 1;                                                                 \
    return sb_last_status();                                                \
  }
XPLAIN(x_coalesces, sb_spray_coalesces, a[0], a[1])
XPLAIN(x_orourke, sb_spray_orourke_b2, a[0], a[1], a[2], a[3], a[4])
XPLAIN(x_rate_hs, sb_spray_pair_rate, SB_SPRAY_HARD_SPHERE, a[0], a[1], a[2],
       a[3])
XPLAIN(x_rate_mx, sb_spray_pair_rate, SB_SPRAY_MAXWELL, a[0], a[1], a[2],
       a[3])
XPLAIN(x_r32, sb_spray_tab_r32, a[0], a[1], a[2], a[3])
XPLAIN(x_blob, sb_spray_reitz_blob_radius, a[0], a[1], a[2], a[3])
XPLAIN(x_frozen, sb_spray_reitz_radius_frozen, a[0], a[1], a[2], a[3])
XPLAIN(x_bkw_K, sb_spray_bkw_K, a[0], a[1], a[2])
XPLAIN(x_bkw_pdf, sb_spray_bkw_pdf, a[0], a[1], a[2])
XPLAIN(x_bkw_cdf, sb_spray_bkw_speed_cdf, a[0], a[1], a[2])
XPLAIN(x_bkw_m4, sb_spray_bkw_m4, a[0], a[1])
XPLAIN(x_bkw_m6, sb_spray_bkw_m6, a[0], a[1])

static int x_we_crit(const double *a, double *out, int *n, const char **nm)
{
  sb_spray_liquid liq = {a[2], a[3]};
  *nm = "sb_spray_tab_we_crit";
  sb_clear_error();
  out[0] = sb_spray_tab_we_crit(a[0], a[1], &liq, a[4]);
  *n = 1;
  return sb_last_status();
}

/* a = t, r, urel, rho_g, rho_l, sigma, mu_l, Cd, y0, ydot0 */
static int x_tab_state(const double *a, double *out, int *n, const char **nm)
{
  sb_spray_liquid liq = {a[5], a[6]};
  *nm = "sb_spray_tab_state";
  *n = 2;
  return sb_spray_tab_state(a[0], a[1], a[2], a[3], a[4], &liq, a[7], a[8],
                            a[9], &out[0], &out[1]);
}

/* a = r, urel, rho_g, rho_l, sigma, mu_l, Cd, y0, ydot0, tmax; tb may be
 * +inf (documented: no breakup) */
static int x_tab_tb(const double *a, double *out, int *n, const char **nm)
{
  sb_spray_liquid liq = {a[4], a[5]};
  *nm = "sb_spray_tab_breakup_time";
  *n = 2;
  int st = sb_spray_tab_breakup_time(a[0], a[1], a[2], a[3], &liq, a[6],
                                     a[7], a[8], a[9], &out[0], &out[1]);
  if (st == SB_SUCCESS && out[0] == INFINITY)
    out[0] = out[1] = 0.0; /* (y' at breakup: not set) */
  return st;
}

/* a = a, U, rho_g, rho_l, sigma, mu_l */
static int x_wave(const double *a, double *out, int *n, const char **nm)
{
  sb_spray_liquid liq = {a[4], a[5]};
  *nm = "sb_spray_reitz_wave";
  *n = 2;
  return sb_spray_reitz_wave(a[0], a[1], a[2], a[3], &liq, &out[0], &out[1]);
}

/* a = a0, t, U, rho_g, rho_l, sigma, mu_l */
static int x_reitz_radius(const double *a, double *out, int *n,
                          const char **nm)
{
  sb_spray_liquid liq = {a[5], a[6]};
  sb_spray_reitz_params rp;
  sb_spray_reitz_params_default(&rp);
  *nm = "sb_spray_reitz_radius";
  *n = 1;
  out[0] = NAN; /* (a plain NaN on error for the check below) */
  return sb_spray_reitz_radius(a[0], a[1], a[2], a[3], a[4], &liq, &rp,
                               &out[0]);
}

static gsl_rng *xrng;

static int x_bkw_sample(const double *a, double *out, int *n, const char **nm)
{
  *nm = "sb_spray_bkw_sample";
  *n = 3;
  out[0] = out[1] = out[2] = 0.0;
  return sb_spray_bkw_sample(a[0], a[1], xrng, out);
}

/* a = n_a, n_b, m_a, m_b, T_a0, T_b0, B0, t */
static int x_tt_maxwell(const double *a, double *out, int *n, const char **nm)
{
  sb_spray_mixture mx = {a[0], a[1], a[2], a[3], 1e-6, 2e-6, a[4], a[5]};
  *nm = "sb_spray_two_temp_maxwell";
  *n = 2;
  return sb_spray_two_temp_maxwell(&mx, a[6], a[7], &out[0], &out[1]);
}

/* a = n_a, n_b, m_a, m_b, r_a, r_b, T_a0, T_b0, t */
static int x_tt_hs(const double *a, double *out, int *n, const char **nm)
{
  sb_spray_mixture mx = {a[0], a[1], a[2], a[3], a[4], a[5], a[6], a[7]};
  *nm = "sb_spray_two_temp_hs";
  *n = 2;
  return sb_spray_two_temp_hs(&mx, a[8], &out[0], &out[1]);
}

/* a = n_a, n_b, m_a, m_b, r_a, r_b, T_a0, T_b0, T_a, T_b */
static int x_tt_hs_rate(const double *a, double *out, int *n, const char **nm)
{
  sb_spray_mixture mx = {a[0], a[1], a[2], a[3], a[4], a[5], a[6], a[7]};
  *nm = "sb_spray_two_temp_hs_rate";
  sb_clear_error();
  out[0] = sb_spray_two_temp_hs_rate(&mx, a[8], a[9]);
  *n = 1;
  return sb_last_status();
}

/* A row of tests/data/spray_extreme.csv (spray_extreme.h): the value by
 * the spray function of its kind, and the tolerance (the Reitz radius:
 * its documented accuracy ~1e-10; the breakup time: 1e-12 of the period,
 * here 5e-11 relative). */
static double spray_row(int kind, const double *a, double *got)
{
  /* kinds 19-24: the arguments and outputs of 16, 17, 9, 12, 6, 11 */
  static const int same[] = {16, 17, 9, 12, 6, 11};
  if (kind >= 19 && kind <= 24)
    kind = same[kind - 19];
  switch (kind) {
  case 0:
    *got = sb_spray_pair_rate(SB_SPRAY_HARD_SPHERE, 1.0, a[0], a[1], a[2]);
    break;
  case 1:
    *got = sb_spray_orourke_b2(a[0], a[1], a[2], a[3], a[4]);
    break;
  case 2:
    *got = sb_spray_tab_r32(a[0], a[1], a[2], a[3]);
    break;
  case 3:
    *got = sb_spray_reitz_blob_radius(a[0], a[1], a[2], a[3]);
    break;
  case 4:
    *got = sb_spray_bkw_pdf(a[0], a[1], a[2]);
    break;
  case 5:
    *got = sb_spray_bkw_m6(a[0], a[1]);
    break;
  case 6: {
    sb_spray_mixture mx = {a[0], a[1], a[2], a[3], 1e-6, 1e-6, a[4], a[5]};
    ck_assert_int_eq(sb_spray_two_temp_maxwell(&mx, a[6], a[7], got,
                                               NULL),
                     SB_SUCCESS);
    break;
  }
  case 9: { /* r_a = r_b = a[6], t = a[7] */
    sb_spray_mixture mx = {a[0], a[1], a[2], a[3], a[6], a[6], a[4], a[5]};
    ck_assert_int_eq(sb_spray_two_temp_hs(&mx, a[7], got, NULL),
                     SB_SUCCESS);
    break;
  }
  case 11: { /* T_b of the Maxwell law (arguments as kind 6) */
    sb_spray_mixture mx = {a[0], a[1], a[2], a[3], 1e-6, 1e-6, a[4], a[5]};
    ck_assert_int_eq(sb_spray_two_temp_maxwell(&mx, a[6], a[7], NULL,
                                               got),
                     SB_SUCCESS);
    break;
  }
  case 12: { /* T_b of the hard-sphere law (arguments as kind 9) */
    sb_spray_mixture mx = {a[0], a[1], a[2], a[3], a[6], a[6], a[4], a[5]};
    ck_assert_int_eq(sb_spray_two_temp_hs(&mx, a[7], NULL, got),
                     SB_SUCCESS);
    break;
  }
  case 10: { /* r_a = r_b = a[4], rate at T_a = a[5], T_b = a[6] */
    sb_spray_mixture mx = {a[0], a[1], a[2], a[3], a[4], a[4], a[5], a[6]};
    sb_clear_error();
    *got = sb_spray_two_temp_hs_rate(&mx, a[5], a[6]);
    ck_assert_int_eq(sb_last_status(), SB_SUCCESS);
    break;
  }
  case 15: { /* Reitz full model: SB_ERANGE before (plain fits) */
    sb_spray_liquid liq = {a[5], a[6]};
    sb_spray_reitz_params rp;
    sb_spray_reitz_params_default(&rp);
    ck_assert_int_eq(sb_spray_reitz_radius(a[0], a[1], a[2], a[3], a[4],
                                           &liq, &rp, got),
                     SB_SUCCESS);
    break;
  }
  case 16:
  case 17: { /* TAB state: SB_ERANGE before (beta^2, r^3, beta z0 or
                beta y0' overflowing) */
    sb_spray_liquid liq = {0.072, a[4]};
    double y, yd;
    ck_assert_int_eq(sb_spray_tab_state(a[0], a[1], a[2], a[3], 1000.0,
                                        &liq, a[5], a[6], a[7], &y, &yd),
                     SB_SUCCESS);
    *got = kind == 16 ? y : yd;
    break;
  }
  case 18: {
    sb_spray_liquid liq = {0.072, a[3]};
    ck_assert_int_eq(sb_spray_tab_breakup_time(a[0], a[1], a[2], 1000.0,
                                               &liq, a[4], a[5], a[6],
                                               a[7], got, NULL),
                     SB_SUCCESS);
    break;
  }
  default:
    return 0.0; /* (pgd rows: test_pgd_exact.c) */
  }
  return kind == 15 || kind == 18 ? 1e-9 : 1e-13;
}

/* Each argument of each closed-form reference function of spray.h in turn
 * over +-1e-320, +-1e-300, 0, +-1e300, +-DBL_MAX, +-inf, NaN (the others
 * ordinary): the outputs are finite (those that are >= 0 by definition
 * checked so) with status 0, or the status is SB_EDOM/SB_ERANGE, a plain
 * value NaN and the message names the public function.  The
 * two-temperature hard-sphere T_a, T_b lie between T_a0 and T_b0, so
 * SB_ERANGE is wrong there. */
START_TEST(test_extreme_arguments)
{
  static const struct {
    xfn f;
    int n;      /* arguments */
    int nonneg; /* outputs 0..nonneg-1 are >= 0 */
    double a[10];
  } k[] = {
      {x_coalesces, 2, 1, {-0.3, 0.9}},
      {x_orourke, 5, 1, {1e-5, 2e-5, 3.0, 1000, 0.072}},
      {x_rate_hs, 4, 1, {1e-9, 1e-5, 2e-5, 3.0}},
      {x_rate_mx, 4, 1, {1e-9, 1e-5, 2e-5, 3.0}},
      {x_tab_state, 10, 0,
       {1e-4, 1e-4, 50, 1.2, 800, 0.03, 1e-3, 5, 0.1, 20}},
      {x_tab_tb, 10, 1, {1e-4, 50, 1.2, 800, 0.03, 1e-3, 5, 0.1, 20, 1e-2}},
      {x_we_crit, 5, 1, {1e-4, 800, 0.03, 1e-3, 5}},
      {x_r32, 4, 1, {1e-4, 30, 800, 0.03}},
      {x_blob, 4, 1, {1e-4, 50, 2e-4, 3e3}},
      {x_wave, 6, 2, {1e-4, 50, 1.2, 800, 0.03, 1e-3}},
      {x_frozen, 4, 1, {1e-4, 2e-5, 0.5, 1e-4}},
      {x_reitz_radius, 7, 1, {1e-4, 1e-4, 50, 1.2, 800, 0.03, 1e-3}},
      {x_bkw_K, 3, 1, {0.7, 2.0, 0.3}},
      {x_bkw_pdf, 3, 1, {0.8, 0.7, 1.3}},
      {x_bkw_cdf, 3, 1, {0.8, 0.7, 1.3}},
      {x_bkw_m4, 2, 1, {0.7, 1.3}},
      {x_bkw_m6, 2, 1, {0.7, 1.3}},
      {x_bkw_sample, 2, 0, {0.7, 1.3}},
      {x_tt_maxwell, 8, 2, {1e20, 2e20, 3e-26, 5e-26, 300, 500, 1e-16, 0.1}},
      {x_tt_hs, 9, 2,
       {1e20, 2e20, 3e-26, 5e-26, 1e-10, 2e-10, 300, 500, 1e-3}},
      {x_tt_hs_rate, 10, 0,
       {1e20, 2e20, 3e-26, 5e-26, 1e-10, 2e-10, 300, 500, 350, 450}},
  };
  int nbad = 0; /* every failure is printed, then counted */
  xrng = gsl_rng_alloc(gsl_rng_mt19937);
  gsl_rng_set(xrng, 20261129);
  const int na = (int)(sizeof k[0].a / sizeof k[0].a[0]);
  for (size_t f = 0; f < sizeof k / sizeof k[0]; f++) {
    /* sb_spray_coalesces returns an int: 0 on an error; T_a, T_b of the
     * hard-sphere law always fit in a double */
    const int flags =
        (k[f].f == x_coalesces ? SBT_SWEEP_ZERO : SBT_SWEEP_NAN) |
        (k[f].f == x_tt_hs ? SBT_SWEEP_NO_ERANGE : 0);
    nbad += sbt_sweep_vec(k[f].f, k[f].a, na, k[f].n,
                          SBT_SWEEP_FIRST(k[f].nonneg), 0, flags, f);
  }
  gsl_rng_free(xrng);
  ck_assert_int_eq(nbad, 0);

  /* Corners where a double intermediate over/underflows but the value is
   * a normal double: tests/data/spray_extreme.csv (gen_spray_ref.py,
   * mpmath, 30 digits).  These gave 0 (pair rate, O'Rourke, BKW
   * density), inf, a wrong r32 (r/(7/3)) or a rate from a subnormal
   * product (two-temperature) before; the two-temperature hard-sphere
   * T_a (kind 9) and its rate (kind 10) SB_ERANGE where n T, k T/m or
   * n/m overflows (n = 1e300, m = 1e-320, T = 1e300), and with status 0
   * a T_a wrong in the fourth digit for m_a = m_b = 1e300 (k T/m
   * subnormal) and T_a = 7.5e-200 instead of T_a0 = 1e-38 at t = 0 for
   * n_a = 6e135, n_b = 8e296, m_a = 1e146, m_b = 2e273.  Kinds 11, 12
   * (T_b of both laws) and the last rows of kinds 6, 9: a rare species
   * at 1e6 K, the other at 1e-12 K (n ratio 1e-3); the colder species
   * came out as T_m - f |Delta|, wrong in every digit or negative.  The
   * last rows of kinds 9, 12: n_a/n_b = 1e-9 (1 - rho cancelled, T_a
   * wrong in the twelfth digit) and m_a/m_b = 1e10 (alpha + beta Delta0
   * cancelled, T_b wrong in the twelfth digit).  The last rows of kinds
   * 6, 11: n = 1e-200, T = 1e-150, where n T underflowed and T_m with
   * it (the hotter T_b relaxed towards 0).  Kinds 19, 20 (TAB y, y'
   * heavily overdamped in the plain range, beta^2/w0^2 up to 1e8): the
   * slow rate k - beta cancelled, y wrong in the ninth digit.  Kinds
   * 21, 22 (hard-sphere T_a, T_b with n_a T_a0, n_b T_b0 near 1e-318
   * while T_m is normal): T_m from the subnormal products, T_a wrong in
   * the tenth digit.  Kinds 23, 24 (Maxwell law with a rate of 1e-313
   * or 1e-316): the subnormal rate, the colder species wrong in the
   * eighth digit.  The last rows of kinds 16, 17 (TAB y << We/12 at t
   * << 1/w0 from y0 ~ 0): y_eq + z cancelled, y wrong in the eighth
   * digit (the tenth overdamped, the third at y0 = -2.3e-13).  The last
   * rows of kinds 19, 20 (overdamped, y0 = 0): y' as e^{-bt}[y0' C -
   * (b y0' + w0^2 z0) S] lost ~(b/w0)^2 ulp in C - b S where the rate's
   * free response is all of y' (U = 0: wrong in the ninth digit at b/w0
   * = 1e4), and e^{-bt} S as a difference of exponentials cancelled at
   * small kt (wrong in the thirteenth digit). */
  ck_assert_int_ge(sbt_spray_extreme(spray_row), 93 + 32 + 6 + 8);
}
END_TEST

static Suite *suite(void)
{
  Suite *s = suite_create("spray");
  TCase *tc = tcase_create("core");
  tcase_set_timeout(tc, 60);
  tcase_add_test(tc, test_post_collision_conserves);
  tcase_add_test(tc, test_coalescence_geometry);
  tcase_add_test(tc, test_bkw_reference);
  tcase_add_test(tc, test_two_temperature);
  tcase_add_test(tc, test_tab_reference);
  tcase_add_test(tc, test_tab_critical_and_r32);
  tcase_add_test(tc, test_reitz_reference);
  tcase_add_test(tc, test_bird_conserves_exactly);
  tcase_add_test(tc, test_ntc_and_names);
  tcase_add_test(tc, test_coalescence_mass);
  tcase_add_test(tc, test_tab_step_children);
  tcase_add_test(tc, test_reitz_step);
  tcase_add_test(tc, test_reitz_blob);
  tcase_add_test(tc, test_totals_and_temperature);
  tcase_add_test(tc, test_extreme_arguments);
  suite_add_tcase(s, tc);
  return s;
}

int main(void) { return sbt_run_suite(suite()); }
