/* test_engine_field.c — random fluid velocity fields
 * (lib/engine/engine_field.c, <smolbridge/engine_field.h>).
 *
 * Independent checks: the stationary variance and covariance of a Stokes
 * particle driven by the OU seen velocity against the fixed point of the
 * 2x2 covariance recursion of the engine's scheme, iterated numerically,
 * and their dt -> 0 limit u'^2 T_L/(T_L + tau); the OU field's one-step
 * statistics (variance u'^2, lag-one correlation exp(-dt/T_L)) by Monte
 * Carlo with a fixed seed; the Kraichnan field's mode count, divergence
 * (central differences), periodicity, frozen time dependence, the ratio
 * <(dU_x/dx)^2>/(eps/nu) from the lattice shell enumerated here, and its
 * flux kernel against Saffman & Turner (1956) at small R k; argument and
 * attach checks; runs in both fields that go on from a checkpoint and
 * the saved field as if they had not stopped.
 */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <gsl/gsl_rng.h>

#include <smolbridge/engine.h>
#include <smolbridge/engine_field.h>
#include <smolbridge/kernel.h>

#include "engine_same.h"
#include "testutil.h"

#define PI 3.14159265358979323846

/* Fixed point of Sigma <- A Sigma A^T + Q for (u, U):
 * u' = a u + (1 - a) U, U' = b U + q Z. */
static void ou_fixed_point(double u2, double TL, double tau, double dt,
                           double *v, double *c)
{
  const double a = exp(-dt / tau), b = exp(-dt / TL);
  const double q2 = u2 * (1.0 - b * b);
  double suu = 0.0, suU = 0.0, sUU = u2;
  for (int it = 0; it < 200000; it++) {
    const double nuu = a * a * suu + 2.0 * a * (1.0 - a) * suU +
                       (1.0 - a) * (1.0 - a) * sUU;
    const double nuU = b * (a * suU + (1.0 - a) * sUU);
    const double nUU = b * b * sUU + q2;
    suu = nuu;
    suU = nuU;
    sUU = nUU;
  }
  *v = suu;
  *c = suU;
}

START_TEST(test_ou_particle_law)
{
  const double u2 = 1e-2, TL = 5e-5;
  const double taus[2] = {1e-3, 2.5e-4}, dts[2] = {5e-6, 5e-5};
  for (int i = 0; i < 2; i++)
    for (int j = 0; j < 2; j++) {
      double v, c;
      ou_fixed_point(u2, TL, taus[i], dts[j], &v, &c);
      ck_assert_msg(sbt_reldiff(sb_field_ou_particle_var(u2, TL, taus[i],
                                                         dts[j]), v) < 1e-10,
                    "var tau %g dt %g", taus[i], dts[j]);
      ck_assert_msg(sbt_reldiff(sb_field_ou_particle_cov(u2, TL, taus[i],
                                                         dts[j]), c) < 1e-10,
                    "cov tau %g dt %g", taus[i], dts[j]);
    }
  /* dt -> 0: the continuous value u2 T_L/(T_L + tau), deviation O(dt/T_L) */
  const double lim = u2 * TL / (TL + taus[0]);
  ck_assert(sbt_reldiff(sb_field_ou_particle_var(u2, TL, taus[0], 1e-10),
                        lim) < 1e-4);
  ck_assert(sbt_reldiff(sb_field_ou_particle_cov(u2, TL, taus[0], 1e-10),
                        lim) < 1e-4);
}
END_TEST

/* The start law: mean (c/u2) U, variance v - c^2/u2. */
START_TEST(test_ou_start)
{
  gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
  gsl_rng_set(r, 11);
  const double u2 = 2e-2, TL = 1e-4, dt = 1e-5, tau = 3e-4;
  sb_field_ou *f = sb_field_ou_alloc(4, u2, TL, dt, r);
  ck_assert_ptr_nonnull(f);
  double mean[3], var;
  ck_assert_int_eq(sb_field_ou_start(f, 3, tau, mean, &var), SB_SUCCESS);
  const double v = sb_field_ou_particle_var(u2, TL, tau, dt),
               c = sb_field_ou_particle_cov(u2, TL, tau, dt);
  for (int k = 0; k < 3; k++)
    ck_assert(sbt_reldiff(mean[k], c / u2 * sb_field_ou_seen(f)[9 + k]) <
              TOL_TIGHT);
  ck_assert(sbt_reldiff(var, v - c * c / u2) < TOL_TIGHT);
  ck_assert_int_eq(sb_field_ou_start(f, 4, tau, mean, &var), SB_EINVAL);
  ck_assert_int_eq(sb_field_ou_start(f, 0, 0.0, mean, &var), SB_EINVAL);
  ck_assert_int_eq(sb_field_ou_start(f, 0, INFINITY, mean, &var),
                   SB_SUCCESS);
  ck_assert(mean[0] == 0.0 && var == 0.0);
  sb_field_ou_free(f);
  gsl_rng_free(r);
}
END_TEST

/* One step of the field: variance u2 kept, lag-one correlation
 * b = exp(-dt/T_L).  3 x 20000 samples (seed 5): the sample variance
 * has relative sd sqrt(2/60000) = 0.0058, the correlation sd
 * (1 - b^2)/sqrt(60000) = 0.0016 at b = 0.6; bounds at 5 sd. */
START_TEST(test_ou_step)
{
  gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
  gsl_rng_set(r, 5);
  const size_t n = 20000;
  const double u2 = 3e-3, TL = 1e-4, dt = -TL * log(0.6);
  sb_field_ou *f = sb_field_ou_alloc(n, u2, TL, dt, r);
  ck_assert_ptr_nonnull(f);
  double *u0 = malloc(3 * n * sizeof *u0), *u1 = malloc(3 * n * sizeof *u1);
  ck_assert_ptr_nonnull(u0);
  ck_assert_ptr_nonnull(u1);
  ck_assert_int_eq(sb_field_ou_fluid(n, NULL, u0, f), SB_SUCCESS);
  ck_assert_int_eq(sb_field_ou_fluid(n, NULL, u1, f), SB_SUCCESS);
  double s00 = 0.0, s11 = 0.0, s01 = 0.0;
  for (size_t i = 0; i < 3 * n; i++) {
    s00 += u0[i] * u0[i];
    s11 += u1[i] * u1[i];
    s01 += u0[i] * u1[i];
  }
  const double m = 3.0 * (double)n;
  ck_assert_msg(fabs(s11 / m / u2 - 1.0) < 5.0 * sqrt(2.0 / m), "var %g",
                s11 / m / u2);
  const double rho = s01 / sqrt(s00 * s11);
  ck_assert_msg(fabs(rho - 0.6) < 5.0 * (1.0 - 0.36) / sqrt(m), "rho %g",
                rho);
  /* any call but the per-step one is refused */
  ck_assert_int_eq(sb_field_ou_fluid(1, NULL, u0, f), SB_EINVAL);
  free(u0);
  free(u1);
  sb_field_ou_free(f);
  gsl_rng_free(r);
}
END_TEST

/* Lattice shell enumerated here: number of modes (one of +-m) and
 * sum |m|^2 khat_x^2 (1 - khat_x^2) / (2 sum |m|^2). */
static void shell(int M, size_t *nm, double *ratio)
{
  double s2 = 0.0, sa = 0.0;
  size_t n = 0;
  for (int i = -M; i <= M; i++)
    for (int j = -M; j <= M; j++)
      for (int k = -M; k <= M; k++) {
        const double m2 = i * i + j * j + k * k, r = sqrt(m2);
        if (!(r > M - 0.5 && r < M + 0.5))
          continue;
        n++;
        s2 += m2;
        sa += m2 * (i * i / m2) * (1.0 - i * i / m2);
      }
  *nm = n / 2;
  *ratio = sa / (2.0 * s2);  /* both sums over +-m: the halves cancel */
}

START_TEST(test_kraichnan_field)
{
  gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
  gsl_rng_set(r, 9);
  const double L = 1e-3, eps_nu = 1e4;
  const size_t want[3] = {9, 31, 49};
  for (int M = 1; M <= 3; M++) {
    sb_field_kraichnan *f = sb_field_kraichnan_alloc(L, M, eps_nu, 0.0, r);
    ck_assert_ptr_nonnull(f);
    size_t nm;
    double ratio;
    shell(M, &nm, &ratio);
    ck_assert_uint_eq(nm, want[M - 1]);
    ck_assert_uint_eq(sb_field_kraichnan_modes(f), nm);
    ck_assert(sbt_reldiff(sb_field_kraichnan_a11(f), ratio * eps_nu) <
              1e-13);
    /* divergence by central differences (h = 1e-6 L: O(h^2) error) and
     * periodicity, at a few points */
    for (int p = 0; p < 5; p++) {
      double x[3], xp[6][3], up[6][3], u[3], ush[3];
      for (int c = 0; c < 3; c++)
        x[c] = L * gsl_rng_uniform(r);
      const double h = 1e-6 * L;
      for (int c = 0; c < 6; c++) {
        for (int d = 0; d < 3; d++)
          xp[c][d] = x[d];
        xp[c][c / 2] += c % 2 ? -h : h;
      }
      sb_field_kraichnan_eval(f, 0.0, 6, &xp[0][0], &up[0][0]);
      double div = 0.0, g2 = 0.0;
      for (int c = 0; c < 3; c++) {
        const double d = (up[2 * c][c] - up[2 * c + 1][c]) / (2.0 * h);
        div += d;
        g2 += d * d;
      }
      ck_assert_msg(fabs(div) < 1e-6 * sqrt(g2), "div %g", div);
      sb_field_kraichnan_eval(f, 0.0, 1, x, u);
      double xs[3] = {x[0] + L, x[1] - 2.0 * L, x[2]};
      sb_field_kraichnan_eval(f, 5.0, 1, xs, ush);  /* frozen: any t */
      for (int c = 0; c < 3; c++)
        ck_assert(fabs(u[c] - ush[c]) < 1e-9 * sqrt(sb_field_kraichnan_u2(f)));
    }
    sb_field_kraichnan_free(f);
  }
  /* time-dependent field: moves */
  sb_field_kraichnan *f = sb_field_kraichnan_alloc(L, 2, eps_nu, 100.0, r);
  const double x[3] = {1e-4, 2e-4, 3e-4};
  double u0[3], u1[3];
  sb_field_kraichnan_eval(f, 0.0, 1, x, u0);
  sb_field_kraichnan_eval(f, 1e-2, 1, x, u1);
  ck_assert(fabs(u0[0] - u1[0]) + fabs(u0[1] - u1[1]) > 0.0);
  sb_field_kraichnan_free(f);
  gsl_rng_free(r);
}
END_TEST

/* Flux kernel -> Saffman & Turner (1956) as R k -> 0 (the lattice shell
 * M = 2 is isotropic to about 2.4e-4 in this integral). */
START_TEST(test_kraichnan_flux_limit)
{
  gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
  gsl_rng_set(r, 1);
  const double L = 1e-3, eps_nu = 1e4, k = 2.0 * PI * 2 / L;
  sb_field_kraichnan *f = sb_field_kraichnan_alloc(L, 2, eps_nu, 0.0, r);
  for (int i = 0; i < 2; i++) {
    const double R = (i ? 1e-3 : 0.1) / k;
    const double Kst = sb_kernel_saffman_turner(0.5 * R, 0.5 * R, eps_nu,
                                                1.0);
    const double q = sb_field_kraichnan_flux_kernel(f, R) / Kst;
    ck_assert_msg(fabs(q - 1.0) < 1e-3, "R k = %g: K/K_ST = %.6f", R * k, q);
  }
  sb_field_kraichnan_free(f);
  gsl_rng_free(r);
}
END_TEST

START_TEST(test_errors_attach)
{
  gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
  ck_assert_ptr_null(sb_field_ou_alloc(0, 1.0, 1.0, 1.0, r));
  ck_assert_ptr_null(sb_field_ou_alloc(3, -1.0, 1.0, 1.0, r));
  ck_assert_ptr_null(sb_field_ou_alloc(3, 1.0, 0.0, 1.0, r));
  ck_assert_ptr_null(sb_field_ou_alloc(3, 1.0, 1.0, 1.0, NULL));
  ck_assert_ptr_null(sb_field_kraichnan_alloc(1.0, 0, 1.0, 0.0, r));
  ck_assert_ptr_null(sb_field_kraichnan_alloc(1.0, 4, 1.0, 0.0, r));
  ck_assert_ptr_null(sb_field_kraichnan_alloc(1.0, 2, 0.0, 0.0, r));
  ck_assert_ptr_null(sb_field_kraichnan_alloc(1.0, 2, 1.0, -1.0, r));
  sb_engine_params p;
  sb_engine_params_default(&p);
  p.L[0] = p.L[1] = p.L[2] = 1e-3;
  p.L[2] = 2e-3;
  p.dt = 1e-6;
  p.capacity = 4;
  sb_engine *e = sb_engine_alloc(&p);
  ck_assert_ptr_nonnull(e);
  sb_engine_species s = {1e-6, 1e-15, 1e-5, 0.0, 0.0};
  ck_assert_int_eq(sb_engine_add_species(e, &s, NULL), SB_SUCCESS);
  sb_field_kraichnan *k = sb_field_kraichnan_alloc(1e-3, 2, 1.0, 0.0, r);
  ck_assert_int_eq(sb_field_kraichnan_attach(e, k), SB_EINVAL);
  sb_field_ou *o = sb_field_ou_alloc(2, 1.0, 1.0, 1e-6, r);
  const double x[3] = {1e-4, 1e-4, 1e-4}, u[3] = {0, 0, 0};
  ck_assert_int_eq(sb_engine_add_particle(e, 0, 0, x, u), SB_SUCCESS);
  ck_assert_int_eq(sb_field_ou_attach(e, o), SB_EINVAL);
  ck_assert_int_eq(sb_engine_add_particle(e, 0, 0, x, u), SB_SUCCESS);
  ck_assert_int_eq(sb_field_ou_attach(e, o), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_step(e), SB_SUCCESS);
  sb_engine_free(e);
  sb_field_ou_free(o);
  sb_field_kraichnan_free(k);
  sb_field_ou_free(NULL);
  sb_field_kraichnan_free(NULL);
  gsl_rng_free(r);
}
END_TEST

/* 400 Stokes spheres (r = 4e-5 m, tau = 2e-5 s; phi ~ 0.1) in a cube of
 * 1e-3 m at dt = 1e-5 s,
 * elastic, sort_every 0 (the OU field follows particles by index). */
static sb_engine *field_engine(void)
{
  sb_engine_params p;
  sb_engine_params_default(&p);
  p.L[0] = p.L[1] = p.L[2] = 1e-3;
  p.dt = 1e-5;
  p.capacity = 400;
  p.seed = 17;
  p.sort_every = 0;
  sb_engine *e = sb_engine_alloc(&p);
  ck_assert_ptr_nonnull(e);
  sb_engine_species sp = {4e-5, 1e-12, 2e-5, 0.0, 0.0};
  ck_assert_int_eq(sb_engine_add_species(e, &sp, NULL), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_fill_random(e, 0, 0, 400), SB_SUCCESS);
  return e;
}

static void field_steps(sb_engine *e, int n)
{
  for (int k = 0; k < n; k++)
    ck_assert_msg(sb_engine_step(e) == SB_SUCCESS, "%s", sb_last_error());
}

/* sbt_load_fn: the saved OU field (u2 3e-3, T_L 1e-4, dt 1e-5) loaded
 * with the MT19937 generator *ctx, which must then be unchanged when the
 * load fails. */
static int load_ou(const char *path, void *ctx)
{
  gsl_rng *r = ctx, *before = gsl_rng_clone(r);
  int st;
  sb_field_ou *f = sb_field_ou_load(path, 3e-3, 1e-4, 1e-5, r, &st);
  if (!f)
    ck_assert(!memcmp(gsl_rng_state(r), gsl_rng_state(before),
                      gsl_rng_size(r)));
  sb_field_ou_free(f);
  gsl_rng_free(before);
  return st;
}

static int load_kr(const char *path, void *ctx)
{
  (void)ctx;
  int st;
  sb_field_kraichnan *f =
      sb_field_kraichnan_load(path, 1e-3, 2, 1e4, 300.0, &st);
  sb_field_kraichnan_free(f);
  return st;
}

/* Runs in a random field stopped after 30 steps, saved (the engine's
 * checkpoint and the field beside it) and restored go on as the run in
 * one go, bit for bit, for 30 more steps: the OU field drawing from a
 * generator of its own (its state saved with it) and from the engine's
 * (restored by the checkpoint), and a time-dependent Kraichnan field
 * drawn from the engine's generator (so it cannot be drawn again).
 * Then the errors: other parameters, a generator of another type,
 * damaged files. */
START_TEST(test_save_load)
{
  char dir[] = "/tmp/sb_field_XXXXXX";
  ck_assert_ptr_nonnull(mkdtemp(dir));
  char ck[64], fp[64], bad[64];
  snprintf(ck, sizeof ck, "%s/run.ck", dir);
  snprintf(fp, sizeof fp, "%s/run.ck.field", dir);
  snprintf(bad, sizeof bad, "%s/bad", dir);
  const double u2 = 3e-3, TL = 1e-4, dt = 1e-5;
  for (int kind = 0; kind < 3; kind++) {  /* OU own / OU engine / KR */
    sb_engine *e[2];
    gsl_rng *g[2] = {NULL, NULL};
    sb_field_ou *ou[2] = {NULL, NULL};
    sb_field_kraichnan *kr[2] = {NULL, NULL};
    for (int k = 0; k < 2; k++) {
      e[k] = field_engine();
      if (kind == 0) {
        g[k] = gsl_rng_alloc(gsl_rng_mt19937);
        gsl_rng_set(g[k], 23);
      }
      gsl_rng *src = kind == 0 ? g[k] : sb_engine_rng(e[k]);
      if (kind < 2) {
        ou[k] = sb_field_ou_alloc(400, u2, TL, dt, src);
        ck_assert_int_eq(sb_field_ou_attach(e[k], ou[k]), SB_SUCCESS);
      } else {
        kr[k] = sb_field_kraichnan_alloc(1e-3, 2, 1e4, 300.0, src);
        ck_assert_int_eq(sb_field_kraichnan_attach(e[k], kr[k]),
                         SB_SUCCESS);
      }
    }
    field_steps(e[0], 60);
    field_steps(e[1], 30);
    ck_assert_int_eq(sb_engine_checkpoint_save(e[1], ck), SB_SUCCESS);
    ck_assert_int_eq(kind < 2 ? sb_field_ou_save(ou[1], kind == 0, fp)
                              : sb_field_kraichnan_save(kr[1], fp),
                     SB_SUCCESS);
    sb_engine_free(e[1]);
    sb_field_ou_free(ou[1]);
    sb_field_kraichnan_free(kr[1]);
    ou[1] = NULL;
    kr[1] = NULL;
    int st;
    e[1] = sb_engine_checkpoint_load(ck, &st);
    ck_assert_int_eq(st, SB_SUCCESS);
    if (kind == 0)
      gsl_rng_set(g[1], 99);  /* its state comes from the file */
    if (kind < 2) {
      ou[1] = sb_field_ou_load(fp, u2, TL, dt,
                               kind == 0 ? g[1] : sb_engine_rng(e[1]), &st);
      ck_assert_msg(st == SB_SUCCESS, "%s", sb_last_error());
      ck_assert_int_eq(sb_field_ou_attach(e[1], ou[1]), SB_SUCCESS);
    } else {
      kr[1] = sb_field_kraichnan_load(fp, 1e-3, 2, 1e4, 300.0, &st);
      ck_assert_msg(st == SB_SUCCESS, "%s", sb_last_error());
      ck_assert_int_eq(sb_field_kraichnan_attach(e[1], kr[1]), SB_SUCCESS);
    }
    field_steps(e[1], 30);
    sbt_assert_same_run(e[0], e[1], SBT_SAME_CANDIDATES);
    sb_engine_stats st0;
    sb_engine_get_stats(e[0], &st0);
    ck_assert_uint_gt(st0.ncoll, 0);
    if (kind < 2)
      ck_assert(!memcmp(sb_field_ou_seen(ou[0]), sb_field_ou_seen(ou[1]),
                        3 * 400 * sizeof(double)));
    /* the errors */
    if (kind == 0) {
      ck_assert_ptr_null(sb_field_ou_load(fp, 2.0 * u2, TL, dt, g[1], &st));
      ck_assert_int_eq(st, SB_EINVAL);
      gsl_rng *t = gsl_rng_alloc(gsl_rng_taus2);
      ck_assert_ptr_null(sb_field_ou_load(fp, u2, TL, dt, t, &st));
      ck_assert_int_eq(st, SB_EINVAL);
      ck_assert_ptr_nonnull(strstr(sb_last_error(), "another type"));
      gsl_rng_free(t);
      sbt_damaged_copies(fp, bad, 30, "SBFKR001", load_ou, g[1]);
      /* a flipped byte; the format without the hash (version 001) */
      sbt_hash_checked(fp, bad, "01", load_ou, g[1]);
    } else if (kind == 2) {
      ck_assert_ptr_null(
          sb_field_kraichnan_load(fp, 1e-3, 2, 1e4, 0.0, &st));
      ck_assert_int_eq(st, SB_EINVAL);
      sbt_damaged_copies(fp, bad, 30, "SBFOU001", load_kr, NULL);
      sbt_hash_checked(fp, bad, "01", load_kr, NULL);
    }
    for (int k = 0; k < 2; k++) {
      sb_engine_free(e[k]);
      sb_field_ou_free(ou[k]);
      sb_field_kraichnan_free(kr[k]);
      if (g[k])
        gsl_rng_free(g[k]);
    }
  }
  remove(ck);
  remove(fp);
  rmdir(dir);
}
END_TEST

static Suite *suite(void)
{
  Suite *s = suite_create("engine_field");
  TCase *tc = tcase_create("core");
  tcase_set_timeout(tc, 60);
  tcase_add_test(tc, test_ou_particle_law);
  tcase_add_test(tc, test_ou_start);
  tcase_add_test(tc, test_ou_step);
  tcase_add_test(tc, test_kraichnan_field);
  tcase_add_test(tc, test_kraichnan_flux_limit);
  tcase_add_test(tc, test_errors_attach);
  tcase_add_test(tc, test_save_load);
  suite_add_tcase(s, tc);
  return s;
}

int main(void) { return sbt_run_suite(suite()); }
