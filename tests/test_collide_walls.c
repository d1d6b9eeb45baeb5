/* test_collide_walls.c — collide runs at walls (lib/collide/
 * collide_walls.c): [run] detect = none (no particle-particle contact,
 * the walls still detect), [species] profile = parabolic (the placement
 * density (y - lo)(hi - y) between the contact planes, against the
 * Beta(2, 2) law), and the deposit columns of series.csv (cumulative
 * deposits per absorbing face at each sample, against the exact slab
 * law 1 - S(t) of Brownian particles between two absorbing planes,
 * Smoluchowski 1917 / Carslaw & Jaeger 1959 §3.3). */
#define _POSIX_C_SOURCE 200809L /* mkdtemp */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <smolbridge/collide.h>
#include <smolbridge/stats.h>

#include "outdir.h"
#include "testutil.h"

#define PI 3.14159265358979323846

/* Run a configuration; returns the run (free it) after asserting its
 * status. */
static sb_collide *run_text(const char *text, int want)
{
  sb_collide *c = sb_collide_alloc();
  ck_assert_ptr_nonnull(c);
  int st = sb_collide_read_string(c, text, "walls.ini");
  if (!st)
    st = sb_collide_run(c, NULL, NULL);
  ck_assert_msg((st != 0) == (want != 0), "status %d (%s)", st,
                sb_collide_error(c));
  return c;
}

/* Two free-flight spheres that touch half-way through the first step
 * (test_collide_lib.c): one collision with a detector, none with
 * detect = none. */
START_TEST(test_detect_none)
{
  char dir[512], text[2048];
  const double c0 = 5e-5, r = 1e-6, s2 = sqrt(2.0);
  for (int none = 0; none < 2; none++) {
    sbt_tmp_dir(dir, sizeof dir, "sbwalls");
    snprintf(text, sizeof text,
             "[run]\nL = 1e-4\ndt = 1e-5\nsteps = 2\ndetect = %s\n"
             "output = %s\n[species sphere]\nradius = 1e-6\nmass = 1e-15\n"
             "tau = inf\nT = 300\n"
             "particle = %.17g %.17g %.17g 0.1 0 0\n"
             "particle = %.17g %.17g %.17g 0 0 0\n",
             none ? "none" : "ballistic", dir,
             c0 - s2 * r - 0.5 * 0.1 * 1e-5, c0, c0, c0, c0 - s2 * r, c0);
    sb_collide *c = run_text(text, 0);
    sb_engine_stats st;
    sb_engine_get_stats(sb_collide_engine(c), &st);
    ck_assert_uint_eq(st.ncoll, none ? 0 : 1);
    ck_assert_uint_eq(sb_collide_nwarnings(c), 0);
    sb_collide_free(c);
    /* the summary says what ran: no outcome without contacts */
    char path[600];
    snprintf(path, sizeof path, "%s/summary.json", dir);
    char *js = sbt_slurp(path);
    ck_assert_ptr_nonnull(strstr(js, none ? "\"outcome\": \"none\""
                                          : "\"outcome\": \"elastic\""));
    free(js);
    sbt_rm_dir(dir);
  }
  /* an outcome has nothing to act on (warned); first_hit nothing to
   * count (an error naming both keys) */
  sb_collide *c = sb_collide_alloc();
  ck_assert_int_eq(sb_collide_read_string(
                       c, "[run]\nL = 1e-4\ndt = 1e-5\nsteps = 2\n"
                          "detect = none\noutcome = count\n"
                          "[species s]\nradius = 1e-6\nmass = 1e-15\n"
                          "tau = inf\nT = 300\ncount = 10\n", "w.ini"),
                   SB_SUCCESS);
  ck_assert_int_eq(sb_collide_check(c), SB_SUCCESS);
  ck_assert_uint_eq(sb_collide_nwarnings(c), 1);
  ck_assert_ptr_nonnull(strstr(sb_collide_warning(c, 0),
                               "[run] outcome ignored: detect = none"));
  sb_collide_free(c);
  c = sb_collide_alloc();
  ck_assert_int_eq(sb_collide_read_string(
                       c, "[run]\nL = 1e-4\ndt = 1e-5\nsteps = 2\n"
                          "detect = none\noutcome = count\n"
                          "[observe]\nfirst_hit = yes\n"
                          "[species s]\nradius = 1e-6\nmass = 1e-15\n"
                          "tau = 1e-6\nT = 300\ncount = 10\n", "w.ini"),
                   SB_SUCCESS);
  ck_assert_int_ne(sb_collide_check(c), SB_SUCCESS);
  ck_assert_ptr_nonnull(strstr(sb_collide_error(c), "w.ini:8: [observe] "
                               "first_hit with detect = none"));
  ck_assert_ptr_nonnull(strstr(sb_collide_error(c), "w.ini:5"));
  sb_collide_free(c);
}
END_TEST

static double beta22_cdf(double u, void *p)
{
  (void)p;
  return u <= 0 ? 0 : (u >= 1 ? 1 : u * u * (3.0 - 2.0 * u));
}

static double uniform_cdf(double u, void *p)
{
  (void)p;
  return u <= 0 ? 0 : (u >= 1 ? 1 : u);
}

/* 20000 particles placed with profile = parabolic between y walls (seed
 * fixed): the reduced wall-normal coordinate (y - r)/(L_y - 2r) against
 * Beta(2, 2), whose density 6 u (1 - u) is the profile, and x, z against
 * the uniform law, KS p > 1e-3; the default (uniform) profile is
 * rejected by the Beta(2, 2) test (p < 1e-9: the test discriminates). */
START_TEST(test_profile_parabolic)
{
  const size_t N = 20000;
  const double r = 5e-8, L = 2e-5;
  double *u = malloc(N * sizeof *u);
  ck_assert_ptr_nonnull(u);
  for (int para = 1; para >= 0; para--) {
    char text[1024];
    snprintf(text, sizeof text,
             "[run]\nL = %g\ndt = 1e-3\nsteps = 1\ndetect = none\n"
             "placement = uniform\nplacement_seed = 77\n"
             "[walls]\ny_lo = absorb\ny_hi = absorb\n"
             "[species a]\nradius = %g\nmass = 5e-19\ntau = 1e-9\n"
             "b2 = 8e-12\ncount = %zu\n%s", L, r, N,
             para ? "profile = parabolic\n" : "");
    sb_collide *c = sb_collide_alloc();
    ck_assert_int_eq(sb_collide_read_string(c, text, "p.ini"), SB_SUCCESS);
    ck_assert_int_eq(sb_collide_setup(c), SB_SUCCESS);
    const sb_engine *e = sb_collide_engine(c);
    ck_assert_uint_eq(sb_engine_count(e), N);
    const double *x = sb_engine_positions(e);
    double D, p;
    for (int k = 0; k < 3; k++) {
      for (size_t i = 0; i < N; i++) {
        u[i] = k == 1 ? (x[3 * i + 1] - r) / (L - 2.0 * r) : x[3 * i + k] / L;
        ck_assert(u[i] >= 0.0 && u[i] < 1.0);
      }
      ck_assert_int_eq(sb_ks_test(u, N, k == 1 ? beta22_cdf : uniform_cdf,
                                  NULL, &D, &p), SB_SUCCESS);
      if (k == 1 && !para)
        ck_assert_msg(p < 1e-9, "uniform y accepted as Beta(2,2): D = %g, "
                      "p = %g", D, p);
      else
        ck_assert_msg(p > 1e-3, "profile %s, axis %d: KS D = %g, p = %g",
                      para ? "parabolic" : "uniform", k, D, p);
    }
    sb_collide_free(c);
  }
  free(u);
  /* errors: another placement, or no walls */
  static const char *const bad[][2] = {
      {"placement = random\n[walls]\ny_lo = absorb\ny_hi = absorb\n",
       "b.ini:15: [species a] profile = parabolic needs [run] placement = "
       "uniform"},
      {"placement = uniform\n",
       "b.ini:12: [species a] profile = parabolic: no direction has walls"}};
  for (int i = 0; i < 2; i++) {
    char text[1024];
    snprintf(text, sizeof text,
             "[run]\nL = 1e-5\ndt = 1e-3\nsteps = 1\n%s"
             "[species a]\nradius = 5e-8\nmass = 5e-19\ntau = 1e-9\n"
             "b2 = 8e-12\ncount = 10\nprofile = parabolic\n", bad[i][0]);
    sb_collide *c = sb_collide_alloc();
    ck_assert_int_eq(sb_collide_read_string(c, text, "b.ini"), SB_SUCCESS);
    ck_assert_int_ne(sb_collide_check(c), SB_SUCCESS);
    ck_assert_msg(strstr(sb_collide_error(c), bad[i][1]) != NULL,
                  "error '%s', want '%s'", sb_collide_error(c), bad[i][1]);
    sb_collide_free(c);
  }
}
END_TEST

/* Fraction of particles uniform in a slab of width W between absorbing
 * planes absorbed by time t: 1 - sum_{k odd} 8/(k pi)^2
 * exp(-(k pi)^2 D t/W^2) (eigenfunction series of the diffusion
 * equation). */
static double slab_absorbed(double D, double t, double W)
{
  double S = 0.0;
  for (int k = 1; k < 100001; k += 2) {
    const double term = 8.0 / (PI * PI * k * k) *
                        exp(-PI * PI * k * k * D * t / (W * W));
    S += term;
    if (term < 1e-18 * S)
      break;
  }
  return 1.0 - S;
}

/* Data rows of series.csv: the columns deposits, deposits_y_lo,
 * deposits_y_hi (by header name) of each row into dep[row][3]; returns
 * the number of rows. */
static size_t read_deposits(const char *dir, double dep[][3], size_t max)
{
  char path[600], line[4096];
  snprintf(path, sizeof path, "%s/series.csv", dir);
  FILE *f = fopen(path, "r");
  ck_assert_ptr_nonnull(f);
  ck_assert_ptr_nonnull(fgets(line, sizeof line, f));
  static const char *const want[3] = {"deposits", "deposits_y_lo",
                                      "deposits_y_hi"};
  int col[3] = {-1, -1, -1}, ncol = 0;
  for (char *s = strtok(line, ",\n"); s; s = strtok(NULL, ",\n"), ncol++)
    for (int q = 0; q < 3; q++)
      if (!strcmp(s, want[q]))
        col[q] = ncol;
  ck_assert_msg(col[0] >= 0 && col[1] >= 0 && col[2] >= 0,
                "series.csv has no deposit columns");
  size_t n = 0;
  while (n < max && fgets(line, sizeof line, f)) {
    int k = 0;
    for (char *s = strtok(line, ",\n"); s; s = strtok(NULL, ",\n"), k++)
      for (int q = 0; q < 3; q++)
        if (k == col[q])
          dep[n][q] = strtod(s, NULL);
    n++;
  }
  fclose(f);
  return n;
}

/* Brownian particles (dt/tau_p = 2e7) uniform between absorbing y
 * walls, no particle-particle detection, a series row every step:
 * row k holds the deposits by step k.  Each cumulative fraction at
 * k = 1, 2, 4, 8, 16 is binomial(N, 1 - S(k dt)) (N = 20000, seed 3,
 * |z| < 4; a row one step off is ~20 sigma away at k = 1); the rows sum
 * their faces, never decrease, and the last is summary.json's deposits.
 * With a warm-up of 4 steps its rows are nan (the counters restart). */
START_TEST(test_deposit_series)
{
  const size_t N = 20000, steps = 16;
  const double r = 5e-8, Ly = 2e-5, W = Ly - 2.0 * r, D = 4.4e-12;
  const double dt = 2.5e-4 * W * W / D;
  char dir[512], text[1024];
  sbt_tmp_dir(dir, sizeof dir, "sbwalls");
  snprintf(text, sizeof text,
           "[run]\nLx = %.17g\nLy = %.17g\nLz = %.17g\ndt = %.17g\n"
           "steps = %zu\nsample_every = 1\nseed = 3\ndetect = none\n"
           "placement = uniform\noutput = %s\n"
           "[walls]\ny_lo = absorb\ny_hi = absorb\n"
           "[species a]\nradius = %g\nmass = 5e-19\ntau = 1e-9\n"
           "b2 = %.17g\ncount = %zu\n", 20 * W, Ly, 20 * W, dt, steps, dir,
           r, 2.0 * D, N);
  sb_collide *c = run_text(text, 0);
  double dep[64][3];
  ck_assert_uint_eq(read_deposits(dir, dep, 64), steps);
  const sb_engine *e = sb_collide_engine(c);
  for (size_t k = 0; k < steps; k++) {
    ck_assert_double_eq(dep[k][0], dep[k][1] + dep[k][2]);
    if (k)
      ck_assert(dep[k][0] >= dep[k - 1][0]);
  }
  ck_assert_double_eq(dep[steps - 1][1], (double)sb_engine_deposits(e, 2));
  ck_assert_double_eq(dep[steps - 1][2], (double)sb_engine_deposits(e, 3));
  for (size_t k = 1; k <= steps; k *= 2) {
    const double P = slab_absorbed(D, (double)k * dt, W);
    const double z = (dep[k - 1][0] - N * P) / sqrt(N * P * (1.0 - P));
    ck_assert_msg(fabs(z) < 4.0, "step %zu: %g deposited, expected %.1f "
                  "(z = %.2f)", k, dep[k - 1][0], N * P, z);
  }
  sb_collide_free(c);
  sbt_rm_dir(dir);
  /* a warm-up: its rows have no deposit values */
  sbt_tmp_dir(dir, sizeof dir, "sbwalls");
  snprintf(text, sizeof text,
           "[run]\nLx = %.17g\nLy = %.17g\nLz = %.17g\ndt = %.17g\n"
           "steps = 4\nwarmup = %.17g\nsample_every = 1\ndetect = none\n"
           "placement = uniform\noutput = %s\n"
           "[walls]\ny_lo = absorb\ny_hi = absorb\n"
           "[species a]\nradius = %g\nmass = 5e-19\ntau = 1e-9\n"
           "b2 = %.17g\ncount = 2000\n", 20 * W, Ly, 20 * W, dt, 4.0 * dt,
           dir, r, 2.0 * D);
  c = run_text(text, 0);
  ck_assert_uint_eq(read_deposits(dir, dep, 64), 8);
  for (int k = 0; k < 8; k++)
    ck_assert(k < 4 ? isnan(dep[k][0]) : dep[k][0] >= 0.0);
  ck_assert_double_eq(dep[7][0], (double)(sb_engine_deposits(
                                     sb_collide_engine(c), 2) +
                                 sb_engine_deposits(sb_collide_engine(c), 3)));
  sb_collide_free(c);
  sbt_rm_dir(dir);
}
END_TEST

static Suite *suite(void)
{
  Suite *s = suite_create("collide_walls");
  TCase *tc = tcase_create("core");
  tcase_set_timeout(tc, 300);  /* ~1 s; sanitizer builds are slower */
  tcase_add_test(tc, test_detect_none);
  tcase_add_test(tc, test_profile_parabolic);
  tcase_add_test(tc, test_deposit_series);
  suite_add_tcase(s, tc);
  return s;
}

int main(void) { return sbt_run_suite(suite()); }
