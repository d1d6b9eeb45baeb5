/* test_engine_shear_noise.c — the exact noise of the engine's Langevin
 * step in the linear shear U_x = G (y - L_y/2) (Lees-Edwards on;
 * lib/engine/engine_lees.c, docs/engine_forces.md section 3).
 *
 *  (a) the covariance Sigma(h) of (u_y, y, u_x, x) and the x rows of its
 *      Cholesky factor against Van Loan's matrix exponential at 80 digits
 *      (tests/gen_shear_noise_ref.py), h/tau in [1e-3, 100], G tau in
 *      [1e-3, 10];
 *  (b) Monte Carlo: the engine's one step and ten steps (GSL generator and
 *      keyed streams) against that reference: whitened sample mean
 *      (chi-square, 4 dof) and covariance (chi-square, 10 dof), p >= 1e-3;
 *  (c) the long-time law of a Brownian particle in simple shear,
 *      <x^2> = 2 D t (1 + G^2 t^2/3) (Foister & van de Ven 1980, J. Fluid
 *      Mech. 96:105, eq 4.9) with the inertial corrections of the exact
 *      model, <xy> = D G t^2, <y^2> = 2 D t, over 50 steps of 20 tau.
 * Broken on purpose: dropping the cross term (x rows independent of the
 * y normals) fails (b) (p(cov) = 0 at h = 10 tau, G h = 0.4) and (c)
 * (<x^2> at z = -7.9, <xy> at -5.3); so does the uniform-flow noise of
 * the old step (same numbers). */
#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_cdf.h>
#include <gsl/gsl_linalg.h>
#include <smolbridge/engine.h>

#include "engine/engine_internal.h"
#include "langevin/langevin_shear_internal.h"
#include "refdata.h"
#include "shear_rk4.h"
#include "testutil.h"

/* ------------------------------------------------------- (a) Sigma */

START_TEST(test_cov_reference)
{
  sbt_table t;
  sbt_table_load("shear_noise_cov.csv", &t);
  static const char *nm[10] = {"uy_uy", "y_uy", "y_y", "ux_uy", "ux_y",
                               "ux_ux", "x_uy", "x_y", "x_ux", "x_x"};
  double worst = 0.0;
  for (int r = 0; r < t.nrow; r++) {
    const double x = sbt_at(&t, r, sbt_col(&t, "x")),
                 g = sbt_at(&t, r, sbt_col(&t, "g"));
    double S[4][4];
    sb_langevin_shear_noise_cov(x, g, S);
    int q = 0;
    for (int i = 0; i < 4; i++)
      for (int j = 0; j <= i; j++, q++) {
        const double want = sbt_at(&t, r, sbt_col(&t, nm[q]));
        if (want == 0.0) {
          ck_assert(S[i][j] == 0.0);
          continue;
        }
        const double rel = fabs(S[i][j] / want - 1.0);
        if (rel > worst)
          worst = rel;
        ck_assert_msg(rel <= 1e-12, "x %g g %g %s: %.17g vs %.17g (%.2g)", x,
                      g, nm[q], S[i][j], want, rel);
      }
  }
  printf("shear noise covariance: worst relative error %.2g over %d rows\n",
         worst, t.nrow);
  sbt_table_free(&t);
}
END_TEST

START_TEST(test_chol_reference)
{
  sbt_table t;
  sbt_table_load("shear_noise_chol.csv", &t);
  static const char *nm[7] = {"L31", "L32", "L33", "L41", "L42", "L43",
                              "L44"};
  double worst = 0.0;
  for (int r = 0; r < t.nrow; r++) {
    const double x = sbt_at(&t, r, sbt_col(&t, "x")),
                 g = sbt_at(&t, r, sbt_col(&t, "g"));
    double L[7];
    sb_langevin_shear_noise_chol(x, g, L);
    for (int k = 0; k < 7; k++) {
      const double want = sbt_at(&t, r, sbt_col(&t, nm[k]));
      const double rel = fabs(L[k] / want - 1.0);
      if (rel > worst)
        worst = rel;
      ck_assert_msg(rel <= 1e-11, "x %g g %g %s: %.17g vs %.17g (%.2g)", x,
                    g, nm[k], L[k], want, rel);
    }
  }
  printf("shear noise Cholesky factor: worst relative error %.2g\n", worst);
  sbt_table_free(&t);
}
END_TEST

/* The series and the closed forms of the integrals meet at x = 1.5. */
START_TEST(test_ints_branches)
{
  double a[7], b[7];
  sbi_shear_noise_ints(1.5 * (1.0 - 1e-15), a);
  sbi_shear_noise_ints(1.5, b);
  for (int k = 0; k < 7; k++)
    ck_assert_rel(a[k], b[k], 1e-13);
  /* leading terms: K_u ~ r^2/2, K_x ~ r^3/6 */
  sbi_shear_noise_ints(1e-5, a);
  ck_assert_rel(a[0], 1e-15 / 6.0, 1e-4);   /* int r^2/2 */
  ck_assert_rel(a[4], 1e-25 / 20.0, 1e-4);  /* int r^4/4 */
  ck_assert_rel(a[6], 1e-35 / 252.0, 1e-4); /* int r^6/36 */
}
END_TEST

/* ------------------------------------------------ engine Monte Carlo */

/* N particles at y = L/2 (fluid at rest there), u = 0, spread in x and z
 * (the field does not depend on them), tau = B = 1, shear G; OUTCOME_COUNT
 * (paths unchanged by contacts).  Returns the engine. */
static sb_engine *shear_engine(size_t N, double L, double Ly, double dt,
                               double G, int streams, unsigned long seed,
                               int threads)
{
  sb_engine_params p;
  sb_engine_params_default(&p);
  p.L[0] = p.L[2] = L;  /* wide in x: the image shift G L_y dt < L/2 */
  p.L[1] = Ly;
  p.dt = dt;
  p.capacity = N;
  p.seed = seed;
  p.outcome = SB_OUTCOME_COUNT;
  p.neigh = SB_NEIGH_SWEEP;
  p.streams = streams;
  p.threads = threads;
  sb_engine *e = sb_engine_alloc(&p);
  ck_assert_ptr_nonnull(e);
  sb_engine_species s = {1e-6, 1.0, 1.0, 1.0, 0.0};
  ck_assert_int_eq(sb_engine_add_species(e, &s, NULL), 0);
  double Gp[3] = {G, 0, 0};
  ck_assert_int_eq(sb_engine_set_fluid(e, SB_FLUID_SHEAR, Gp), 0);
  ck_assert_int_eq(sb_engine_set_lees_edwards(e, 1), 0);
  const size_t nx = (size_t)ceil(sqrt((double)N));
  const double sp = 0.8 * L / (double)nx;
  for (size_t i = 0; i < N; i++) {
    double x[3] = {0.1 * L + sp * (double)(i % nx), 0.5 * Ly,
                   0.1 * L + sp * (double)(i / nx)};
    double u[3] = {0, 0, 0};
    ck_assert_int_eq(sb_engine_add_particle(e, 0, 0, x, u), 0);
  }
  return e;
}

/* Displacement of particle i over the last step (x - x0, minimum image;
 * no particle crosses the sliding boundary in these runs). */
static void last_disp(const sb_engine *e, size_t i, double d[3])
{
  const double *x = sb_engine_positions(e), *x0 = sb_engine_start_positions(e);
  const double *L = sb_engine_get_params(e)->L;
  for (int k = 0; k < 3; k++) {
    d[k] = x[3 * i + k] - x0[3 * i + k];
    d[k] -= L[k] * nearbyint(d[k] / L[k]);
  }
}

/* Sample (u_y, y, u_x, x) after nsteps steps of dt from rest, whitened by
 * the reference covariance of the total time; chi-square p-values of the
 * mean (4 dof) and the covariance (10 dof, the standardised elements of
 * W W^T/N - I, variance 2/N on the diagonal and 1/N off it). */
static void mc_check(double dt, int nsteps, double G, const double *Sref,
                     size_t N, int streams, unsigned long seed,
                     double *p_mean, double *p_cov)
{
  sb_engine *e = shear_engine(N, 1e5, 1000.0, dt, G, streams, seed, 1);
  double *acc = calloc(4 * N, sizeof *acc);
  ck_assert_ptr_nonnull(acc);
  for (int s = 0; s < nsteps; s++) {
    ck_assert_msg(sb_engine_step(e) == 0, "%s", sb_last_error());
    for (size_t i = 0; i < N; i++) {
      double d[3];
      last_disp(e, i, d);
      acc[4 * i + 1] += d[1];
      acc[4 * i + 3] += d[0];
    }
  }
  const double *u = sb_engine_velocities(e);
  gsl_matrix *C = gsl_matrix_alloc(4, 4);
  for (int i = 0; i < 4; i++)
    for (int j = 0; j < 4; j++)
      gsl_matrix_set(C, i, j, Sref[4 * i + j]);
  ck_assert_int_eq(gsl_linalg_cholesky_decomp1(C), 0);
  double m[4] = {0}, M[4][4] = {{0}};
  for (size_t i = 0; i < N; i++) {
    double v[4] = {u[3 * i + 1], acc[4 * i + 1], u[3 * i], acc[4 * i + 3]};
    /* w = L^-1 v (forward substitution) */
    double w[4];
    for (int r = 0; r < 4; r++) {
      double s = v[r];
      for (int c = 0; c < r; c++)
        s -= gsl_matrix_get(C, r, c) * w[c];
      w[r] = s / gsl_matrix_get(C, r, r);
    }
    for (int r = 0; r < 4; r++) {
      m[r] += w[r];
      for (int c = 0; c <= r; c++)
        M[r][c] += w[r] * w[c];
    }
  }
  double chim = 0.0, chic = 0.0;
  for (int r = 0; r < 4; r++) {
    chim += m[r] * m[r] / (double)N;
    for (int c = 0; c <= r; c++) {
      const double d = M[r][c] / (double)N - (r == c);
      chic += d * d * (double)N / (r == c ? 2.0 : 1.0);
    }
  }
  *p_mean = gsl_cdf_chisq_Q(chim, 4.0);
  *p_cov = gsl_cdf_chisq_Q(chic, 10.0);
  gsl_matrix_free(C);
  free(acc);
  sb_engine_free(e);
}

/* Reference Sigma (order u_y, y, u_x, x; tau = B = 1) from the CSV row
 * (x, g). */
static void ref_sigma(double x, double g, double S[16])
{
  sbt_table t;
  sbt_table_load("shear_noise_cov.csv", &t);
  static const char *nm[10] = {"uy_uy", "y_uy", "y_y", "ux_uy", "ux_y",
                               "ux_ux", "x_uy", "x_y", "x_ux", "x_x"};
  int found = 0;
  for (int r = 0; r < t.nrow && !found; r++) {
    if (sbt_at(&t, r, sbt_col(&t, "x")) != x ||
        sbt_at(&t, r, sbt_col(&t, "g")) != g)
      continue;
    int q = 0;
    for (int i = 0; i < 4; i++)
      for (int j = 0; j <= i; j++, q++)
        S[4 * i + j] = S[4 * j + i] = sbt_at(&t, r, sbt_col(&t, nm[q]));
    found = 1;
  }
  sbt_table_free(&t);
  ck_assert_msg(found, "no reference row x %g g %g", x, g);
}

/* One step of h = 10 tau at G tau = 0.04 and of h = tau at G tau = 0.4
 * (G h = 0.4: the engine needs G h < 1/2), both generators: 40 000
 * particles each, p >= 1e-3 for the mean and the covariance.  Ten steps
 * of tau at G tau = 0.4 against Sigma(10 tau). */
START_TEST(test_mc_steps)
{
  static const struct {
    double x, g;
    int nsteps;
    double xref;
  } c[] = {{10.0, 0.04, 1, 10.0}, {1.0, 0.4, 1, 1.0}, {1.0, 0.4, 10, 10.0}};
  const size_t N = 40000;
  for (int q = 0; q < 3; q++)
    for (int streams = 0; streams <= 1; streams++) {
      double S[16], pm, pc;
      ref_sigma(c[q].xref, c[q].g, S);
      mc_check(c[q].x, c[q].nsteps, c[q].g, S, N, streams, 11 + q, &pm,
               &pc);
      printf("shear MC h/tau %g x %d, G tau %g, %s: p(mean) %.3g "
             "p(cov) %.3g (N = %zu)\n", c[q].x, c[q].nsteps, c[q].g,
             streams ? "streams" : "gsl", pm, pc, N);
      ck_assert_msg(pm >= 1e-3 && pc >= 1e-3,
                    "h/tau %g x %d G tau %g streams %d: p %g %g", c[q].x,
                    c[q].nsteps, c[q].g, streams, pm, pc);
    }
}
END_TEST

/* (c) Long-time dispersion: 50 000 particles, 20 steps of h = 4.5 tau
 * (t = 90 tau; G h = 0.45, the engine needs G h < 1/2), G tau = 0.1,
 * tau = B = 1 (D = B^2 tau^2/2 = 1/2).  From rest the exact model gives,
 * in units of tau and B (x = t/tau, g = G tau; from the kernel K_x of
 * engine_lees.c, terms O(e^-x) dropped)
 *   <x^2> = x - 3/2 + g^2 (x^3/3 - 2 x^2 + 4 x - 3/4),
 * whose leading term is Foister & van de Ven's 2 D G^2 t^3/3 and whose
 * x^2 term is the inertial lag (relative -6 tau/t); <y^2> = x - 3/2,
 * <xy> = g int K_x k_y -> D G t^2.  The closed form is checked against
 * sb_langevin_shear_noise_cov (1e-12), then z-scores of the sample second moments
 * (standard errors from the sample fourth moments), |z| <= 4.  Twenty
 * steps, not hundreds: the error of the uniform-flow noise in <x^2> and
 * <xy> is relative O(h/t) (the within-step shear correlation, once per
 * step); here it is -7.9 and -5.3 standard errors. */
START_TEST(test_long_time)
{
  const size_t N = 50000;
  const double h = 4.5, G = 0.1;
  const int nsteps = 20;
  for (int streams = 0; streams <= 1; streams++) {
    sb_engine *e = shear_engine(N, 1e6, 4000.0, h, G, streams, 5, 1);
    double *X = calloc(N, sizeof *X), *Y = calloc(N, sizeof *Y);
    ck_assert_ptr_nonnull(X);
    ck_assert_ptr_nonnull(Y);
    for (int s = 0; s < nsteps; s++) {
      ck_assert_msg(sb_engine_step(e) == 0, "%s", sb_last_error());
      for (size_t i = 0; i < N; i++) {
        double d[3];
        last_disp(e, i, d);
        X[i] += d[0];
        Y[i] += d[1];
      }
    }
    const double t = h * nsteps, g = G;
    const double wxx = t - 1.5 + g * g * (t * t * t / 3 - 2 * t * t +
                                          4 * t - 0.75);
    const double wyy = t - 1.5;
    double Sx[4][4];
    sb_langevin_shear_noise_cov(t, g, Sx);
    ck_assert_rel(Sx[3][3], wxx, 1e-12);
    ck_assert_rel(Sx[1][1], wyy, 1e-12);
    /* <xy> = g int K_x k_y dr: (x^2/2 - 3x + ...) -> use the reference
     * integral at this x (checked in (a)) */
    double f[7];
    sbi_shear_noise_ints(t, f);
    const double wxy = g * f[3];
    double sxx = 0, syy = 0, sxy = 0, qxx = 0, qyy = 0, qxy = 0;
    for (size_t i = 0; i < N; i++) {
      sxx += X[i] * X[i];
      syy += Y[i] * Y[i];
      sxy += X[i] * Y[i];
      qxx += pow(X[i], 4);
      qyy += pow(Y[i], 4);
      qxy += X[i] * X[i] * Y[i] * Y[i];
    }
    const double n = (double)N;
    sxx /= n;
    syy /= n;
    sxy /= n;
    const double zxx = (sxx - wxx) / sqrt((qxx / n - sxx * sxx) / n);
    const double zyy = (syy - wyy) / sqrt((qyy / n - syy * syy) / n);
    const double zxy = (sxy - wxy) / sqrt((qxy / n - sxy * sxy) / n);
    const double fvdv = 2.0 * 0.5 * t * (1.0 + G * G * t * t / 3.0);
    printf("shear long time (%s, t = %g tau, G tau = %g, N = %zu): <x^2> "
           "%.6g (exact %.6g, Foister-van de Ven %.6g) z %.2f; <y^2> %.5g "
           "z %.2f; <xy> %.5g (D G t^2 = %.5g) z %.2f\n",
           streams ? "streams" : "gsl", t, G, N, sxx, wxx, fvdv, zxx, syy,
           zyy, sxy, 0.5 * G * t * t, zxy);
    ck_assert_msg(fabs(zxx) <= 4.0 && fabs(zyy) <= 4.0 && fabs(zxy) <= 4.0,
                  "z %g %g %g", zxx, zyy, zxy);
    free(X);
    free(Y);
    sb_engine_free(e);
  }
}
END_TEST

/* Streams: bit-identical states for 1 and 3 threads with the shear
 * noise. */
START_TEST(test_threads_identical)
{
  const size_t N = 3000;
  sb_engine *a = shear_engine(N, 1e4, 400.0, 2.0, 0.2, 1, 3, 1);
  sb_engine *b = shear_engine(N, 1e4, 400.0, 2.0, 0.2, 1, 3, 3);
  for (int s = 0; s < 3; s++) {
    ck_assert_int_eq(sb_engine_step(a), 0);
    ck_assert_int_eq(sb_engine_step(b), 0);
  }
  ck_assert(memcmp(sb_engine_positions(a), sb_engine_positions(b),
                   3 * N * sizeof(double)) == 0);
  ck_assert(memcmp(sb_engine_velocities(a), sb_engine_velocities(b),
                   3 * N * sizeof(double)) == 0);
  sb_engine_free(a);
  sb_engine_free(b);
}
END_TEST


/* ------------------------------------ rest of a step after an outcome */

typedef struct {
  int n;
  double s, x[3], u[3];
} reins_rec;

static int reinsert_and_record(sb_engine *e, const sb_engine_pair *p,
                               double s, void *ctx)
{
  reins_rec *r = ctx;
  int st = sb_engine_outcome_reinsert(e, p, s);
  if (st)
    return st;
  r->n++;
  r->s = p->t0 + s * p->dt;  /* time of the collision (step starts at 0) */
  memcpy(r->x, sb_engine_positions(e) + 3 * p->j, sizeof r->x);
  memcpy(r->u, sb_engine_velocities(e) + 3 * p->j, sizeof r->u);
  return 0;
}

/* With the Langevin detector a particle changed by an outcome continues by
 * a fresh step over the rest of the step: in the shear, the exact step of
 * the linear field (mean correction from the piece's start).  A pair
 * meets in the first step, j is reinserted; B = 1e-9 (noise ~1e-9), G =
 * 0.3, settling w_y = -0.1 along y, tau = 0.5, dt = 0.5: j's end state
 * against RK4 (1e5 steps) from its reinsertion state over the rest of the
 * step, 1e-7.  (With the frozen field at the new place, as before, the
 * x error is G tau^2 (A V_r + D w_y) ~ 1e-3.) */
START_TEST(test_rest_of_step)
{
  sb_engine_params p;
  sb_engine_params_default(&p);
  p.L[0] = p.L[1] = p.L[2] = 10.0;
  p.dt = 0.5;
  p.capacity = 4;
  p.seed = 9;
  p.detect = SB_DETECT_LANGEVIN;
  sb_engine *e = sb_engine_alloc(&p);
  ck_assert_ptr_nonnull(e);
  const double tau = 0.5, G = 0.3, gy = -0.2, wy = gy * tau;
  sb_engine_species sp = {0.1, 1.0, tau, 1e-9, 0.0};
  ck_assert_int_eq(sb_engine_add_species(e, &sp, NULL), 0);
  double Gp[3] = {G, 0, 0}, g[3] = {0.0, gy, 0.0};
  ck_assert_int_eq(sb_engine_set_fluid(e, SB_FLUID_SHEAR, Gp), 0);
  ck_assert_int_eq(sb_engine_set_lees_edwards(e, 1), 0);
  ck_assert_int_eq(sb_engine_set_gravity(e, g), 0);
  reins_rec r = {0, 0, {0}, {0}};
  ck_assert_int_eq(sb_engine_set_outcome_fn(e, reinsert_and_record, &r), 0);
  double xa[3] = {5.0, 5.0, 5.0}, ua[3] = {2.0, wy, 0.0};
  double xb[3] = {5.6, 5.0, 5.0}, ub[3] = {0.0, wy, 0.0};
  ck_assert_int_eq(sb_engine_add_particle(e, 0, 0, xa, ua), 0);
  ck_assert_int_eq(sb_engine_add_particle(e, 0, 0, xb, ub), 0);
  ck_assert_msg(sb_engine_step(e) == 0, "%s", sb_last_error());
  ck_assert_int_eq(r.n, 1);
  /* the fluid is G (y - L/2) */
  double st[4] = {r.x[0], r.u[0], r.x[1] - 5.0, r.u[1]};
  sbt_shear_rk4(st, tau, G, wy, p.dt - r.s, 100000);
  const double *x = sb_engine_positions(e), *u = sb_engine_velocities(e);
  double X = x[3], Y = x[4] - 5.0;
  X += 10.0 * nearbyint((st[0] - X) / 10.0);  /* wrapped into the box */
  ck_assert_msg(fabs(Y - st[2]) <= 1e-7 && fabs(u[4] - st[3]) <= 1e-7,
                "y %.12g vs %.12g", Y, st[2]);
  ck_assert_msg(fabs(X - st[0]) <= 1e-7, "x %.12g vs %.12g (t %g)", X,
                st[0], r.s);
  ck_assert_msg(fabs(u[3] - st[1]) <= 1e-7, "u %.12g vs %.12g", u[3],
                st[1]);
  sb_engine_free(e);
}
END_TEST

static Suite *suite(void)
{
  Suite *s = suite_create("engine_shear_noise");
  TCase *tc = tcase_create("reference");
  tcase_add_test(tc, test_cov_reference);
  tcase_add_test(tc, test_chol_reference);
  tcase_add_test(tc, test_ints_branches);
  tcase_add_test(tc, test_rest_of_step);
  suite_add_tcase(s, tc);
  TCase *mc = tcase_create("monte_carlo");
  tcase_set_timeout(mc, 300);
  tcase_add_test(mc, test_mc_steps);
  tcase_add_test(mc, test_long_time);
  tcase_add_test(mc, test_threads_identical);
  suite_add_tcase(s, mc);
  return s;
}

int main(void) { return sbt_run_suite(suite()); }
