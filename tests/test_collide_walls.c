/* test_collide_walls.c — collide runs at walls (lib/collide/
 * collide_walls.c): [run] detect = none (no particle-particle contact,
 * the walls still detect), [species] profile = parabolic (the placement
 * density (y - lo)(hi - y) between the contact planes, against the
 * Beta(2, 2) law), and the deposit columns of series.csv (cumulative
 * deposits per absorbing face at each sample, against the exact slab
 * law 1 - S(t) of Brownian particles between two absorbing planes,
 * Smoluchowski 1917 / Carslaw & Jaeger 1959 §3.3), and the batches of
 * [observe] batch_steps and region (collide_batches.c) against the exact
 * exits and region masses of particles in free flight. */
#define _POSIX_C_SOURCE 200809L /* mkdtemp, fork, waitpid */
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
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

/* batches.csv: the header names into names[][32] and the rows into
 * v[row][col]; returns the number of rows. */
static size_t read_batches(const char *dir, char names[][32], int *ncol,
                           double v[][64], size_t max)
{
  char path[600], line[8192];
  snprintf(path, sizeof path, "%s/batches.csv", dir);
  FILE *f = fopen(path, "r");
  ck_assert_ptr_nonnull(f);
  ck_assert_ptr_nonnull(fgets(line, sizeof line, f));
  *ncol = 0;
  for (char *s = strtok(line, ",\n"); s && *ncol < 64;
       s = strtok(NULL, ",\n"))
    snprintf(names[(*ncol)++], 32, "%s", s);
  size_t n = 0;
  while (n < max && fgets(line, sizeof line, f)) {
    int k = 0;
    for (char *s = strtok(line, ",\n"); s && k < 64; s = strtok(NULL, ",\n"))
      v[n][k++] = strtod(s, NULL);
    ck_assert_int_eq(k, *ncol);
    n++;
  }
  fclose(f);
  return n;
}

static int col_of(char names[][32], int ncol, const char *name)
{
  for (int k = 0; k < ncol; k++)
    if (!strcmp(names[k], name))
      return k;
  ck_abort_msg("batches.csv has no column %s", name);
  return -1;
}

/* Free flight in the unit square, every face open, dt = 0.01 s, three
 * batches of 100 steps, regions sampled every 10 steps.  Exact answers:
 * b (mass 3, family 1) from (0.25, 0.8) at (0, -1) leaves through y_lo
 * at t = 0.8 (batch 0) at x = 0.25; a (mass 2, family 0) from (0.5, 0.5)
 * at (0, 0.3) leaves through y_hi at t = 5/3 (batch 1) at x = 0.5; a
 * resting a in region 1 (mass 2 at every sample); a b from (0.55, 0.25)
 * at (0.1, 0) enters region 2 (x >= 0.6049) at step 55: 5 of the 10
 * samples of batch 0 (mean 1.5), all later ones (3).  An inflow of
 * family 2 on x_lo (y in [0.4, 0.45], leaving through x_hi) adds exits
 * that every row must balance: injected - left = n_end - n_start, m_left
 * = the sum of the exit-mass columns; its x_hi exits are summed from
 * exits.csv (the same exits, written row by row) per batch. */
/* A run killed half-way keeps the exits.csv rows and grid.csv frames
 * written up to its last progress point (they go to the files as the run
 * goes, flushed at every progress point): an inflow on x_lo at speed 2
 * crosses the unit box in 0.5, so by t = 1.5, where the child process
 * kills itself from the progress callback, about 20 drops have left
 * through x_hi; grid frames every 0.25.  A run stopped by the callback
 * (status failed) keeps them too. */
static int stop_at(const sb_collide_progress *p, void *user)
{
  const double *t = user;
  if (p->event == SB_COLLIDE_STEP && p->t >= t[0]) {
    if (t[1] > 0.0)
      raise(SIGKILL);
    return 1;
  }
  return 0;
}

static void check_kept_rows(const char *dir, double t_stop)
{
  char path[600], line[1024];
  snprintf(path, sizeof path, "%s/exits.csv", dir);
  FILE *f = fopen(path, "r");
  ck_assert_ptr_nonnull(f);
  ck_assert_ptr_nonnull(fgets(line, sizeof line, f));
  ck_assert_str_eq(line, "t,face,species,family,mass,x,y,z,ux,uy,uz\n");
  int nx = 0;
  while (fgets(line, sizeof line, f)) {
    double t;
    char face[8];
    ck_assert_int_eq(sscanf(line, "%lf,%7[^,]", &t, face), 2);
    ck_assert_str_eq(face, "x_hi");
    ck_assert(t > 0.5 && t < t_stop + 0.1);
    nx++;
  }
  fclose(f);
  ck_assert_int_gt(nx, 5);  /* ~20 expected */
  snprintf(path, sizeof path, "%s/grid.csv", dir);
  f = fopen(path, "r");
  ck_assert_ptr_nonnull(f);
  int nrow = 0;
  while (fgets(line, sizeof line, f))
    nrow++;
  fclose(f);
  ck_assert_int_ge(nrow, 1 + 5 * 16);  /* frames at 0.25 .. 1.25 */
  ck_assert_int_eq((nrow - 1) % 16, 0);
}

START_TEST(test_stopped_run_keeps_rows)
{
  for (int kill = 1; kill >= 0; kill--) {
    char dir[512], text[2048];
    sbt_tmp_dir(dir, sizeof dir, "sbstop");
    snprintf(text, sizeof text,
             "[run]\ndim = 2\nL = 1\ndt = 0.01\nsteps = 300\nseed = 5\n"
             "detect = none\noutput = %s\nstop_every = 0.25\n"
             "[walls]\nx_lo = open\nx_hi = open\ny_lo = open\n"
             "y_hi = open\n[observe]\nexits = yes\ngrid = 4 4\n"
             "[species c]\nradius = 0.005\nmass = 1\ntau = inf\nT = 1\n"
             "inflow = x_lo\ninflow_rate = 20\ninflow_region = 0.4 0.45\n"
             "inflow_velocity = 2 0\n", dir);
    double stop[2] = {1.5, kill};
    if (kill) {
      fflush(NULL);
      pid_t pid = fork();
      ck_assert_int_ge(pid, 0);
      if (pid == 0) {  /* the run, killed from its callback */
        sb_collide *c = sb_collide_alloc();
        if (c && !sb_collide_read_string(c, text, "stop.ini"))
          sb_collide_run(c, stop_at, stop);
        _exit(3);  /* not reached */
      }
      int ws = 0;
      ck_assert_int_eq(waitpid(pid, &ws, 0), pid);
      ck_assert(WIFSIGNALED(ws) && WTERMSIG(ws) == SIGKILL);
    } else {
      sb_collide *c = sb_collide_alloc();
      ck_assert_int_eq(sb_collide_read_string(c, text, "stop.ini"), 0);
      ck_assert_int_ne(sb_collide_run(c, stop_at, stop), 0);
      sb_collide_free(c);
    }
    check_kept_rows(dir, stop[0]);
  }
}
END_TEST

START_TEST(test_batches)
{
  char dir[512], text[2048];
  sbt_tmp_dir(dir, sizeof dir, "sbbatch");
  snprintf(text, sizeof text,
           "[run]\ndim = 2\nL = 1\ndt = 0.01\nsteps = 300\nseed = 5\n"
           "detect = none\noutput = %s\n"
           "[walls]\nx_lo = open\nx_hi = open\ny_lo = open\ny_hi = open\n"
           "detect = ballistic\n"
           "[observe]\nbatch_steps = 100\nregion_every = 10\nexits = yes\n"
           "region = 0 0.2 0 0.2\nregion = 0.6049 0.95 0.2 0.3\n"
           "[species a]\nradius = 0.01\nmass = 2\ntau = inf\nT = 1\n"
           "family = 0\n"
           "particle = 0.5 0.5 0 0.3\nparticle = 0.1 0.1 0 0\n"
           "[species b]\nradius = 0.01\nmass = 3\ntau = inf\nT = 1\n"
           "family = 1\n"
           "particle = 0.25 0.8 0 -1\nparticle = 0.55 0.25 0.1 0\n"
           "[species c]\nradius = 0.005\nmass = 1\ntau = inf\nT = 1\n"
           "family = 2\ninflow = x_lo\ninflow_rate = 20\n"
           "inflow_region = 0.4 0.45\ninflow_velocity = 2 0\n", dir);
  sb_collide *c = run_text(text, 0);
  static char names[64][32];
  static double v[8][64];
  int nc;
  ck_assert_uint_eq(read_batches(dir, names, &nc, v, 8), 3);
  const int my = col_of(names, nc, "m_y_lo_f1"), py = col_of(names, nc,
                                                             "py_y_lo");
  const int mxl = col_of(names, nc, "mx_y_lo"), ma = col_of(names, nc,
                                                            "m_y_hi_f0");
  const int pa = col_of(names, nc, "py_y_hi"), xa = col_of(names, nc,
                                                           "mx_y_hi");
  const int r1 = col_of(names, nc, "region1"), r2 = col_of(names, nc,
                                                           "region2");
  const int ns = col_of(names, nc, "region_samples");
  const double want_r2[3] = {1.5, 3.0, 3.0};
  for (int q = 0; q < 3; q++) {
    ck_assert_double_eq(v[q][col_of(names, nc, "batch")], q);
    ck_assert_double_eq_tol(v[q][col_of(names, nc, "t_start")], q * 1.0,
                            1e-9);
    ck_assert_double_eq_tol(v[q][col_of(names, nc, "t_end")], q + 1.0,
                            1e-9);
    ck_assert_double_eq(v[q][my], q == 0 ? 3.0 : 0.0);
    ck_assert_double_eq(v[q][py], q == 0 ? -3.0 : 0.0);
    ck_assert_double_eq(v[q][mxl], q == 0 ? 0.75 : 0.0);
    ck_assert_double_eq(v[q][ma], q == 1 ? 2.0 : 0.0);
    ck_assert_double_eq_tol(v[q][pa], q == 1 ? 0.6 : 0.0, 1e-15);
    ck_assert_double_eq_tol(v[q][xa], q == 1 ? 1.0 : 0.0, 1e-12);
    ck_assert_double_eq(v[q][ns], 10.0);
    ck_assert_double_eq(v[q][r1], 2.0);
    ck_assert_double_eq(v[q][r2], want_r2[q]);
    /* the balance of drops and of exiting mass */
    ck_assert_double_eq(v[q][col_of(names, nc, "injected")] -
                            v[q][col_of(names, nc, "left")],
                        v[q][col_of(names, nc, "n_end")] -
                            v[q][col_of(names, nc, "n_start")]);
    double msum = 0.0;
    for (int k = 0; k < nc; k++)
      if (!strncmp(names[k], "m_", 2) && strcmp(names[k], "m_left"))
        msum += v[q][k];
    ck_assert_double_eq_tol(msum, v[q][col_of(names, nc, "m_left")],
                            1e-12 * msum);
    ck_assert(v[q][col_of(names, nc, "injected")] > 5);
    if (q)
      ck_assert_double_eq(v[q][col_of(names, nc, "n_start")],
                          v[q - 1][col_of(names, nc, "n_end")]);
  }
  /* the inflow's exits through x_hi per batch, from exits.csv */
  double mc[3] = {0}, yc[3] = {0}, pc[3] = {0};
  char path[600], line[1024];
  snprintf(path, sizeof path, "%s/exits.csv", dir);
  FILE *f = fopen(path, "r");
  ck_assert_ptr_nonnull(f);
  ck_assert_ptr_nonnull(fgets(line, sizeof line, f));
  int nx = 0;
  while (fgets(line, sizeof line, f)) {
    double t, m, x, y, z, ux;
    char face[8], sp[16];
    ck_assert_int_eq(sscanf(line, "%lf,%7[^,],%15[^,],%*d,%lf,%lf,%lf,%lf,"
                            "%lf", &t, face, sp, &m, &x, &y, &z, &ux), 8);
    if (strcmp(face, "x_hi"))
      continue;
    const int q = (int)floor(t);  /* the batch: crossed within its steps */
    ck_assert(q >= 0 && q < 3);
    mc[q] += m;
    yc[q] += m * y;
    pc[q] += m * ux;
    nx++;
  }
  fclose(f);
  ck_assert(nx > 20);
  for (int q = 0; q < 3; q++) {
    ck_assert_double_eq_tol(v[q][col_of(names, nc, "m_x_hi_f2")], mc[q],
                            1e-12 * mc[q]);
    ck_assert_double_eq_tol(v[q][col_of(names, nc, "my_x_hi")], yc[q],
                            1e-12 * yc[q]);
    ck_assert_double_eq_tol(v[q][col_of(names, nc, "px_x_hi")], pc[q],
                            1e-12 * pc[q]);
  }
  /* summary.json: the batch means (region 2: 2.5 over the 3 batches) */
  snprintf(path, sizeof path, "%s/summary.json", dir);
  char *js = sbt_slurp(path);
  ck_assert_ptr_nonnull(strstr(js, "\"batches\": {\"file\": \"batches.csv\", "
                                   "\"steps\": 100, \"n\": 3"));
  ck_assert_ptr_nonnull(strstr(js, "\"region2\": {\"mean\": 2.5, "));
  ck_assert_ptr_nonnull(strstr(js, "\"region1\": {\"mean\": 2, \"ci95\": "
                                   "[2, 2]}"));
  free(js);
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
  tcase_add_test(tc, test_batches);
  tcase_add_test(tc, test_stopped_run_keeps_rows);
  suite_add_tcase(s, tc);
  return s;
}

int main(void) { return sbt_run_suite(suite()); }
