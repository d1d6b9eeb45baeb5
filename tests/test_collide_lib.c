/* test_collide_lib.c — the run description <smolbridge/collide.h>: a
 * configuration read from a string with an override, run into a
 * temporary directory (two spheres at 45 degrees: one collision, Thomine
 * 2008, §7), progress events, warnings, input errors with the key in the
 * message, a run stopped by its callback, the key table, first-contact
 * kernels per species pair of a mixture, the mean-square displacement
 * of free flights through the periodic boundaries, the antipodal start
 * and snapshots at given steps, the normal velocities at first contact
 * against the flux-weighted Maxwellian. */
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

/* Two free-flight spheres of radius r: the first moves along x at 0.1 m/s
 * and touches the second, offset by sqrt(2) r in y, half-way through the
 * first step (a 45-degree collision). */
static void two_spheres(char *text, size_t len, const char *out,
                        const char *length, const char *extra)
{
  const double c = 5e-5, r = 1e-6, s2 = sqrt(2.0);
  snprintf(text, len,
           "[run]\nL = 1e-4\ndt = 1e-5\n%s\nsample_every = 1\n"
           "output = %s\n%s\n[species sphere]\nradius = 1e-6\n"
           "mass = 1e-15\ntau = inf\nT = 300\n"
           "particle = %.17g %.17g %.17g 0.1 0 0\n"
           "particle = %.17g %.17g %.17g 0 0 0\n",
           length, out, extra, c - s2 * r - 0.5 * 0.1 * 1e-5, c, c, c,
           c - s2 * r, c);
}

typedef struct {
  int begin, steps;
  double last_fraction, t_end;
  size_t particles;
  int stop_at;  /* stop at this STEP event (0: never) */
  long long first_contacts;  /* of the last STEP event */
} events;

static int on_progress(const sb_collide_progress *p, void *user)
{
  events *ev = user;
  if (p->event == SB_COLLIDE_BEGIN) {
    ev->begin++;
    ev->particles = p->particles;
    ev->t_end = p->t_end;
    return 0;
  }
  ev->steps++;
  ev->last_fraction = p->fraction;
  ev->first_contacts = p->first_contacts;
  return ev->stop_at && ev->steps >= ev->stop_at;
}

START_TEST(test_run_from_string)
{
  char dir[512], text[2048], path[600];
  sbt_tmp_dir(dir, sizeof dir, "sbcollide");
  two_spheres(text, sizeof text, dir, "steps = 1", "");
  sb_collide *c = sb_collide_alloc();
  ck_assert_ptr_nonnull(c);
  ck_assert_int_eq(sb_collide_read_string(c, text, "two.ini"), SB_SUCCESS);
  /* two steps instead of one: the override decides the end time */
  ck_assert_int_eq(sb_collide_set(c, "run.steps=2"), SB_SUCCESS);
  ck_assert_int_eq(sb_collide_check(c), SB_SUCCESS);
  ck_assert_uint_eq(sb_collide_nwarnings(c), 0);
  ck_assert_str_eq(sb_collide_output(c), dir);
  events ev = {0, 0, 0, 0, 0, 0, 0};
  ck_assert_int_eq(sb_collide_run(c, on_progress, &ev), SB_SUCCESS);
  ck_assert_int_eq(sb_collide_failed(c), SB_COLLIDE_OK);
  ck_assert_str_eq(sb_collide_error(c), "");
  ck_assert_int_eq(ev.begin, 1);
  ck_assert_int_eq(ev.steps, 2);  /* every tenth of 2 steps: each step */
  ck_assert_double_eq(ev.last_fraction, 1.0);
  ck_assert_uint_eq(ev.particles, 2);
  ck_assert_rel(ev.t_end, 2e-5, TOL_TIGHT);
  ck_assert_int_eq(ev.first_contacts, -1);  /* no [observe] first_hit */
  const sb_engine *e = sb_collide_engine(c);
  ck_assert_ptr_nonnull(e);
  sb_engine_stats st;
  sb_engine_get_stats(e, &st);
  ck_assert_uint_eq(st.steps, 2);
  ck_assert_uint_eq(st.ncoll, 1);
  ck_assert_ptr_null(sb_collide_agglo(c));
  ck_assert_int_eq(sb_collide_has_firsthit(c), 0);
  sb_engine_firsthit_kernel_result o;
  ck_assert_int_eq(sb_collide_firsthit(c, &o), SB_EINVAL);
  /* the outputs: summary.json with the override and the collision */
  snprintf(path, sizeof path, "%s/summary.json", dir);
  char *js = sbt_slurp(path);
  ck_assert_ptr_nonnull(strstr(js, "\"status\": \"ok\""));
  ck_assert_ptr_nonnull(strstr(js, "\"overrides\": [\"run.steps=2\"]"));
  ck_assert_ptr_nonnull(strstr(js, "\"collisions\": 1,"));
  free(js);
  snprintf(path, sizeof path, "%s/series.csv", dir);
  char *csv = sbt_slurp(path);
  ck_assert_ptr_nonnull(strstr(csv, "t,ncoll,K,K_lo,K_hi"));
  free(csv);
  /* a configuration runs once */
  ck_assert_int_eq(sb_collide_run(c, NULL, NULL), SB_EINVAL);
  ck_assert_int_eq(sb_collide_failed(c), SB_COLLIDE_EINPUT);
  ck_assert_ptr_nonnull(strstr(sb_collide_error(c), "runs once"));
  sb_collide_free(c);
  sbt_rm_dir(dir);
}
END_TEST

START_TEST(test_input_errors)
{
  char text[2048];
  /* a bad value: the file:line, the key and the valid values */
  two_spheres(text, sizeof text, "unused-out", "steps = 1",
              "detect = brige");
  sb_collide *c = sb_collide_alloc();
  ck_assert_int_eq(sb_collide_read_string(c, text, "two.ini"), SB_EINVAL);
  ck_assert_int_eq(sb_collide_failed(c), SB_COLLIDE_EINPUT);
  ck_assert_msg(!strncmp(sb_collide_error(c), "two.ini:7: [run] detect = "
                         "brige: unknown; valid: ballistic", 48),
                "message: %s", sb_collide_error(c));
  /* the first error sticks: nothing runs, no output directory */
  ck_assert_int_eq(sb_collide_set(c, "run.dt=1e-6"), SB_EINVAL);
  ck_assert_int_eq(sb_collide_run(c, NULL, NULL), SB_EINVAL);
  ck_assert_ptr_null(sb_collide_engine(c));
  ck_assert_int_eq(access("unused-out", F_OK), -1);
  sb_collide_free(c);
  /* an override out of range */
  two_spheres(text, sizeof text, "unused-out", "steps = 1", "");
  c = sb_collide_alloc();
  ck_assert_int_eq(sb_collide_read_string(c, text, NULL), SB_SUCCESS);
  ck_assert_int_eq(sb_collide_set(c, "run.dt=-1"), SB_EINVAL);
  ck_assert_str_eq(sb_collide_error(c), "--set run.dt=-1: [run] dt = -1: "
                   "out of range; valid: > 0 s");
  sb_collide_free(c);
  /* nothing but comments; the default name */
  c = sb_collide_alloc();
  ck_assert_int_eq(sb_collide_read_string(c, "; nothing\n", NULL), SB_EINVAL);
  ck_assert_msg(!strncmp(sb_collide_error(c), "string: no keys", 15),
                "message: %s", sb_collide_error(c));
  sb_collide_free(c);
  /* a line longer than the INI reader takes, then a good one */
  char longer[1200];
  memset(longer, ' ', sizeof longer);
  memcpy(longer, "[run]\nL = 1", 11);
  snprintf(longer + sizeof longer - 12, 12, "0\ndt = 1\n");
  c = sb_collide_alloc();
  ck_assert_int_eq(sb_collide_read_string(c, longer, "long.ini"), SB_EINVAL);
  ck_assert_msg(strstr(sb_collide_error(c), "long.ini:2: line longer than"),
                "message: %s", sb_collide_error(c));
  sb_collide_free(c);
}
END_TEST

START_TEST(test_checks_and_warnings)
{
  char text[2048];
  /* a key without effect: a warning naming its line */
  two_spheres(text, sizeof text, "unused-out", "steps = 1",
              "[bridge]\ntol = 1e-6");
  sb_collide *c = sb_collide_alloc();
  ck_assert_int_eq(sb_collide_read_string(c, text, "w.ini"), SB_SUCCESS);
  ck_assert_int_eq(sb_collide_check(c), SB_SUCCESS);
  ck_assert_uint_eq(sb_collide_nwarnings(c), 1);
  ck_assert_str_eq(sb_collide_warning(c, 0), "w.ini:8: [bridge] ignored: "
                   "only detect = bridge or exact use it");
  ck_assert_ptr_null(sb_collide_warning(c, 1));
  /* no keys after the checks */
  ck_assert_int_eq(sb_collide_set(c, "run.dt=1e-6"), SB_EINVAL);
  sb_collide_free(c);
  /* conflicting keys: the later one is reported, an override by its
   * option */
  two_spheres(text, sizeof text, "unused-out", "steps = 1", "");
  c = sb_collide_alloc();
  ck_assert_int_eq(sb_collide_read_string(c, text, "c.ini"), SB_SUCCESS);
  ck_assert_int_eq(sb_collide_set(c, "run.t_end=1e-5"), SB_SUCCESS);
  ck_assert_int_eq(sb_collide_check(c), SB_EINVAL);
  ck_assert_int_eq(sb_collide_failed(c), SB_COLLIDE_EINPUT);
  ck_assert_str_eq(sb_collide_error(c), "--set run.t_end=1e-5: [run] t_end "
                   "conflicts with steps (at c.ini:4): give the end time or "
                   "the number of measured steps");
  sb_collide_free(c);
}
END_TEST

START_TEST(test_nothing_to_measure)
{
  char dir[512], text[2048], path[600];
  sbt_tmp_dir(dir, sizeof dir, "sbcollide");
  two_spheres(text, sizeof text, dir, "t_end = 1e-5", "warmup = 2e-5");
  sb_collide *c = sb_collide_alloc();
  ck_assert_int_eq(sb_collide_read_string(c, text, "m.ini"), SB_SUCCESS);
  ck_assert_int_eq(sb_collide_setup(c), SB_SUCCESS);  /* it can be built */
  ck_assert_ptr_nonnull(sb_collide_engine(c));
  ck_assert_int_eq(sb_collide_run(c, NULL, NULL), SB_EINVAL);
  ck_assert_int_eq(sb_collide_failed(c), SB_COLLIDE_EINPUT);
  ck_assert_str_eq(sb_collide_error(c), "m.ini:7: nothing to measure: the "
                   "warm-up (2e-05 s) does not end before t_end (1e-05 s "
                   "from t = 0 s)");
  snprintf(path, sizeof path, "%s/summary.json", dir);
  ck_assert_int_eq(access(path, F_OK), -1);  /* no run, no outputs */
  sb_collide_free(c);
  sbt_rm_dir(dir);
}
END_TEST

START_TEST(test_stopped_by_callback)
{
  char dir[512], text[2048], path[600];
  sbt_tmp_dir(dir, sizeof dir, "sbcollide");
  two_spheres(text, sizeof text, dir, "steps = 1", "");
  sb_collide *c = sb_collide_alloc();
  ck_assert_int_eq(sb_collide_read_string(c, text, "s.ini"), SB_SUCCESS);
  ck_assert_int_eq(sb_collide_set(c, "run.steps=50"), SB_SUCCESS);
  events ev = {0, 0, 0, 0, 0, 3, 0};
  ck_assert_int_ne(sb_collide_run(c, on_progress, &ev), SB_SUCCESS);
  ck_assert_int_eq(sb_collide_failed(c), SB_COLLIDE_ERUN);
  ck_assert_int_eq(ev.steps, 3);
  ck_assert_msg(!strncmp(sb_collide_error(c), "stopped by the progress "
                         "callback", 32), "message: %s", sb_collide_error(c));
  snprintf(path, sizeof path, "%s/summary.json", dir);
  char *js = sbt_slurp(path);
  ck_assert_ptr_nonnull(strstr(js, "\"status\": \"failed\""));
  free(js);
  sb_collide_free(c);
  sbt_rm_dir(dir);
}
END_TEST

START_TEST(test_key_table)
{
  const size_t n = sb_collide_nkeys();
  ck_assert_uint_gt(n, 50);
  sb_collide_keyinfo k;
  ck_assert_int_eq(sb_collide_key(0, &k), SB_SUCCESS);
  ck_assert_str_eq(k.section, "run");
  ck_assert_str_eq(k.key, "seed");
  ck_assert_str_eq(k.valid, "integer 0 .. 4294967295");
  int detect = 0;
  for (size_t i = 0; i < n; i++) {
    ck_assert_int_eq(sb_collide_key(i, &k), SB_SUCCESS);
    if (!strcmp(k.section, "run") && !strcmp(k.key, "detect")) {
      detect = 1;  /* the engine's detectors and the bridge ones */
      ck_assert_ptr_nonnull(strstr(k.valid, "ballistic"));
      ck_assert_ptr_nonnull(strstr(k.valid, "exact"));
    }
  }
  ck_assert_int_eq(detect, 1);
  ck_assert_int_eq(sb_collide_key(n, &k), SB_EINVAL);
}
END_TEST

/* First-contact counting of a two-species mixture (outcome = count,
 * exact Brownian-bridge detection, dt = 1000 tau_p: diffusive): one
 * kernel per species pair.  Checked against an independent computation:
 * the pairs apart are the pair count of each type minus the pairs in
 * contact at the start; E[hits]/K is Smoluchowski's (1917) exposure
 * P/(V - 4 pi R^3/3) [(t - t1) + 2 R (sqrt t - sqrt t1)/sqrt(pi D)] with
 * R = r_a + r_b and D = (b2_a + b2_b)/2, computed here from the keys; and
 * each pair's count against K = 4 pi D R (Poisson, seed 8: about 1500,
 * 2000 and 300 first contacts; |z| < 4). */
START_TEST(test_firsthit_mixture)
{
  const double r[2] = {1e-7, 2e-7}, b2[2] = {2e-10, 2e-11};
  const double n[2] = {1500, 1000}, L = 1e-5, t1 = 1e-5;
  char dir[512], text[2048], path[600];
  sbt_tmp_dir(dir, sizeof dir, "sbcollide");
  snprintf(text, sizeof text,
           "[run]\nL = %g\ndt = 1e-6\nt_end = 2e-3\nwarmup = %g\nseed = 8\n"
           "detect = exact\noutcome = count\nplacement = uniform\n"
           "output = %s\n[observe]\nfirst_hit = yes\n"
           "[species a]\nradius = %g\nmass = 1e-18\ntau = 1e-9\nb2 = %g\n"
           "count = %g\n"
           "[species b]\nradius = %g\nmass = 1e-18\ntau = 1e-9\nb2 = %g\n"
           "count = %g\n", L, t1, dir, r[0], b2[0], n[0], r[1], b2[1], n[1]);
  sb_collide *c = sb_collide_alloc();
  ck_assert_int_eq(sb_collide_read_string(c, text, "mix.ini"), SB_SUCCESS);
  ck_assert_int_eq(sb_collide_run(c, NULL, NULL), SB_SUCCESS);
  const double t = sb_engine_time(sb_collide_engine(c));
  ck_assert_rel(t, 2e-3, 1e-9);
  sb_engine_firsthit_kernel_result all, o;
  /* a mixture has no single kernel: counts over all pairs, SB_EDOM */
  ck_assert_int_eq(sb_collide_firsthit(c, &all), SB_EDOM);
  ck_assert(isnan(all.K));
  uint64_t hits = 0, warm = 0, c0 = 0;
  double apart = 0.0;
  for (size_t a = 0; a < 2; a++)
    for (size_t b = a; b < 2; b++) {
      ck_assert_int_eq(sb_collide_firsthit_pair(c, b, a, &o), SB_SUCCESS);
      const double R = r[a] + r[b], D = 0.5 * (b2[a] + b2[b]);
      const double P = a == b ? 0.5 * n[a] * (n[a] - 1.0) : n[a] * n[b];
      ck_assert_double_eq(o.c.pairs_apart, P - (double)o.c.contact0);
      ck_assert_rel(o.a, R, TOL_TIGHT);
      ck_assert_rel(o.D, D, TOL_TIGHT);
      const double epk = o.c.pairs_apart / (L * L * L - 4.0 * PI * R * R *
                                            R / 3.0) *
                         ((t - t1) + 2.0 * R * (sqrt(t) - sqrt(t1)) /
                                         sqrt(PI * D));
      ck_assert_rel(o.expected_per_K, epk, 1e-12);
      ck_assert_rel(o.K, (double)o.c.hits / epk, 1e-12);
      const double E = epk * 4.0 * PI * D * R;
      const double z = ((double)o.c.hits - E) / sqrt(E);
      ck_assert_msg(fabs(z) < 4.0 && o.c.hits > 200, "pair %zu-%zu: %llu "
                    "first contacts, expected %.1f (z = %.2f)", a, b,
                    (unsigned long long)o.c.hits, E, z);
      ck_assert(o.lo < o.K && o.K < o.hi);
      hits += o.c.hits;
      warm += o.c.warm;
      c0 += o.c.contact0;
      apart += o.c.pairs_apart;
    }
  ck_assert_uint_eq(all.c.hits, hits);
  ck_assert_uint_eq(all.c.warm, warm);
  ck_assert_uint_eq(all.c.contact0, c0);
  ck_assert_double_eq(all.c.pairs_apart, apart);
  ck_assert_int_eq(sb_collide_firsthit_pair(c, 0, 2, &o), SB_EINVAL);
  /* summary.json: one entry per pair, by name, after the totals */
  snprintf(path, sizeof path, "%s/summary.json", dir);
  char *js = sbt_slurp(path);
  char *fh = strstr(js, "\"first_hit\": {\"hits\": ");
  ck_assert_ptr_nonnull(fh);
  ck_assert_ptr_nonnull(strstr(fh, "\"K\": null, \"ci95\": [null, null], "
                               "\"pairs\": ["));
  ck_assert_ptr_nonnull(strstr(fh, "{\"species\": [\"a\", \"a\"], \"hits\": "));
  ck_assert_ptr_nonnull(strstr(fh, "{\"species\": [\"a\", \"b\"], \"hits\": "));
  ck_assert_ptr_nonnull(strstr(fh, "{\"species\": [\"b\", \"b\"], \"hits\": "));
  free(js);
  sb_collide_free(c);
  sbt_rm_dir(dir);
}
END_TEST

/* [observe] msd_every: particles that pass through each other (outcome
 * count) fly straight, so the unwrapped displacement over a lag t is u t
 * exactly and MSD(t) = <|u|^2> t^2, whatever the origin; the particles
 * cross the box ~40 times (unwrapping through the boundaries).  The
 * slope between lags k1, k2 then gives D = <|u|^2> (k1 + k2) ts / 6. */
START_TEST(test_msd_free_flight)
{
  char dir[512], text[2048], path[600];
  sbt_tmp_dir(dir, sizeof dir, "sbcollide");
  snprintf(text, sizeof text,
           "[run]\nL = 1e-6\ndt = 1e-8\nsteps = 2000\nseed = 3\n"
           "outcome = count\noutput = %s\n[observe]\nmsd_every = 100\n"
           "msd_fit = 4 12\n[species p]\nradius = 1e-8\nmass = 1e-21\n"
           "tau = inf\nT = 300\ncount = 50\n", dir);
  sb_collide *c = sb_collide_alloc();
  ck_assert_int_eq(sb_collide_read_string(c, text, "msd.ini"), SB_SUCCESS);
  ck_assert_int_eq(sb_collide_run(c, NULL, NULL), SB_SUCCESS);
  const sb_engine *e = sb_collide_engine(c);
  const double *u = sb_engine_velocities(e);
  double u2 = 0.0, umax = 0.0;
  for (size_t i = 0; i < 50; i++) {
    double v2 = u[3 * i] * u[3 * i] + u[3 * i + 1] * u[3 * i + 1] +
                u[3 * i + 2] * u[3 * i + 2];
    u2 += v2 / 50.0;
    umax = fmax(umax, sqrt(v2));
  }
  const double ts = 100 * 1e-8;
  ck_assert(umax * 2000 * 1e-8 > 10 * 1e-6);  /* many box crossings */
  snprintf(path, sizeof path, "%s/msd.csv", dir);
  FILE *f = fopen(path, "r");
  ck_assert_ptr_nonnull(f);
  char head[64];
  ck_assert_ptr_nonnull(fgets(head, sizeof head, f));
  ck_assert_str_eq(head, "lag,t,msd,origins\n");
  size_t k, no, nrow = 0;
  double t, m;
  while (fscanf(f, "%zu,%lf,%lf,%zu", &k, &t, &m, &no) == 4) {
    ck_assert_uint_eq(k, nrow);
    ck_assert_uint_eq(no, 21 - k);
    ck_assert_rel(t, (double)k * ts, 1e-12);
    if (k)
      ck_assert_rel(m, u2 * t * t, 1e-9);
    else
      ck_assert_double_eq(m, 0.0);
    nrow++;
  }
  fclose(f);
  ck_assert_uint_eq(nrow, 21);  /* samples at 0, 100, ..., 2000 steps */
  snprintf(path, sizeof path, "%s/summary.json", dir);
  char *js = sbt_slurp(path);
  const char *q = strstr(js, "\"msd\": {\"every\": 100, ");
  ck_assert_ptr_nonnull(q);
  q = strstr(q, "\"fit\": [4, 12], \"D\": ");
  ck_assert_ptr_nonnull(q);
  double D = strtod(q + strlen("\"fit\": [4, 12], \"D\": "), NULL);
  ck_assert_rel(D, u2 * 16.0 * ts / 6.0, 1e-9);
  free(js);
  sb_collide_free(c);
  sbt_rm_dir(dir);
  /* errors that name the key: a lag beyond the run, sorting */
  c = sb_collide_alloc();
  ck_assert_int_eq(sb_collide_read_string(c, text, "msd.ini"), SB_SUCCESS);
  ck_assert_int_eq(sb_collide_set(c, "observe.msd_fit=4 21"), SB_SUCCESS);
  ck_assert_int_ne(sb_collide_run(c, NULL, NULL), SB_SUCCESS);
  ck_assert_ptr_nonnull(strstr(sb_collide_error(c), "msd_fit"));
  sb_collide_free(c);
  sbt_rm_dir(dir);
  c = sb_collide_alloc();
  ck_assert_int_eq(sb_collide_read_string(c, text, "msd.ini"), SB_SUCCESS);
  ck_assert_int_eq(sb_collide_set(c, "run.sort_every=10"), SB_SUCCESS);
  ck_assert_int_eq(sb_collide_check(c), SB_EINVAL);
  ck_assert_ptr_nonnull(strstr(sb_collide_error(c), "sort_every"));
  sb_collide_free(c);
}
END_TEST

/* Speed, direction and momentum of velocities = antipodal, read back
 * from the snapshots that snapshot_steps = 0 3 10 takes (at the steps
 * the engine's stats count); energy conserved by the elastic gas. */
START_TEST(test_antipodal_snapshots)
{
  char dir[512], text[2048], path[600];
  sbt_tmp_dir(dir, sizeof dir, "sbcollide");
  const double m = 6.6e-27, T = 300.0, kB = 1.380649e-23;
  snprintf(text, sizeof text,
           "[run]\nL = 2e-8\ndt = 2e-13\nsteps = 10\nseed = 5\n"
           "velocity_seed = 77\nsnapshot_steps = 0 3 10\noutput = %s\n"
           "[species he]\nradius = 1.4e-10\nmass = %g\ntau = inf\n"
           "T = %g\ncount = 400\nvelocities = antipodal\n", dir, m, T);
  sb_collide *c = sb_collide_alloc();
  ck_assert_int_eq(sb_collide_read_string(c, text, "a.ini"), SB_SUCCESS);
  ck_assert_int_eq(sb_collide_run(c, NULL, NULL), SB_SUCCESS);
  const double v = sqrt(3.0 * kB * T / m);
  double p[3] = {0, 0, 0}, mx[3] = {0, 0, 0};
  snprintf(path, sizeof path, "%s/snap_000000.csv", dir);
  FILE *f = fopen(path, "r");
  ck_assert_ptr_nonnull(f);
  char line[512];
  ck_assert_ptr_nonnull(fgets(line, sizeof line, f));
  double prev[3] = {0, 0, 0};
  for (int i = 0; i < 400; i++) {
    double x[3], u[3];
    unsigned long id, sp;
    int fam;
    ck_assert_int_eq(fscanf(f, "%lu,%lu,%d,%lf,%lf,%lf,%lf,%lf,%lf", &id, &sp,
                            &fam, &x[0], &x[1], &x[2], &u[0], &u[1], &u[2]),
                     9);
    ck_assert_rel(sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]), v, 1e-12);
    for (int k = 0; k < 3; k++) {
      p[k] += u[k];
      mx[k] = fmax(mx[k], fabs(u[k]));
      if (i % 2)  /* the partner of the particle before */
        ck_assert_double_eq(u[k], -prev[k]);
      prev[k] = u[k];
    }
  }
  fclose(f);
  for (int k = 0; k < 3; k++) {
    ck_assert(fabs(p[k]) <= 1e-9 * v);
    ck_assert(mx[k] > 0.9 * v);  /* directions spread over the sphere */
  }
  /* three snapshots: steps 0, 3, 10 */
  snprintf(path, sizeof path, "%s/snap_000002.csv", dir);
  f = fopen(path, "r");
  ck_assert_ptr_nonnull(f);
  fclose(f);
  snprintf(path, sizeof path, "%s/manifest.txt", dir);
  char *man = sbt_slurp(path);
  ck_assert_ptr_nonnull(strstr(man, "snap_000002.csv"));
  ck_assert_ptr_null(strstr(man, "snap_000003.csv"));
  free(man);
  snprintf(path, sizeof path, "%s/summary.json", dir);
  char *js = sbt_slurp(path);
  const char *q = strstr(js, "\"rel_change\": ");
  ck_assert_ptr_nonnull(q);
  ck_assert(strtod(q + 14, NULL) < 1e-12);
  free(js);
  sb_collide_free(c);
  sbt_rm_dir(dir);
  /* a snapshot after the end of the run */
  c = sb_collide_alloc();
  ck_assert_int_eq(sb_collide_read_string(c, text, "a.ini"), SB_SUCCESS);
  ck_assert_int_eq(sb_collide_set(c, "run.snapshot_steps=0 11"), SB_SUCCESS);
  ck_assert_int_eq(sb_collide_run(c, NULL, NULL), SB_EINVAL);
  ck_assert_ptr_nonnull(strstr(sb_collide_error(c), "snapshot_steps"));
  sb_collide_free(c);
  /* an odd count has no antipodal pairing */
  c = sb_collide_alloc();
  ck_assert_int_eq(sb_collide_read_string(c, text, "a.ini"), SB_SUCCESS);
  ck_assert_int_eq(sb_collide_set(c, "species.he.count=401"), SB_SUCCESS);
  ck_assert_int_eq(sb_collide_setup(c), SB_EINVAL);
  ck_assert_ptr_nonnull(strstr(sb_collide_error(c), "even number"));
  sb_collide_free(c);
  rmdir(dir);
}
END_TEST

static double flux_cdf(double x, void *p)
{
  double s = *(double *)p;
  return x <= 0.0 ? 0.0 : -expm1(-0.5 * x * x / (s * s));
}

/* contacts.csv: free flights from a uniform start, pairs passing through
 * each other (outcome count), chord detection over one step: the first
 * contacts are straight-line flux across the contact sphere, so |v_n|
 * follows the flux-weighted Maxwellian 1 - exp(-v^2/(2 s^2)) of the
 * relative velocity, s^2 = k_B T/m_red (Mohaupt 2011, §7.2.1).  KS
 * over all the contacts (seed 11: about 4500; 50000 particles, so that
 * each takes part in ~0.2 of them and the contacts are nearly
 * independent), p > 1e-4, and a z-test of their mean (a 5% error in
 * v_n: z ~ 7); every v_n < 0 (approach). */
START_TEST(test_contact_velocities)
{
  char dir[512], text[2048], path[600];
  sbt_tmp_dir(dir, sizeof dir, "sbcollide");
  const double m = 1e-21, T = 300.0, kB = 1.380649e-23;
  snprintf(text, sizeof text,
           "[run]\nL = 4e-6\ndt = 4e-8\nsteps = 1\nseed = 11\n"
           "detect = ballistic\noutcome = count\nplacement = uniform\n"
           "output = %s\n[observe]\nfirst_hit = yes\n"
           "first_hit_velocities = 20000\n[species p]\nradius = 1e-8\n"
           "mass = %g\ntau = inf\nT = %g\ncount = 50000\n", dir, m, T);
  sb_collide *c = sb_collide_alloc();
  ck_assert_int_eq(sb_collide_read_string(c, text, "c.ini"), SB_SUCCESS);
  events ev;
  memset(&ev, 0, sizeof ev);
  ck_assert_int_eq(sb_collide_run(c, on_progress, &ev), SB_SUCCESS);
  sb_engine_firsthit_kernel_result o;
  sb_collide_firsthit(c, &o);
  ck_assert(o.c.hits > 4000 && o.c.hits < 20000);
  ck_assert_int_eq(ev.first_contacts, (long long)o.c.hits);  /* progress */
  snprintf(path, sizeof path, "%s/contacts.csv", dir);
  FILE *f = fopen(path, "r");
  ck_assert_ptr_nonnull(f);
  char line[256];
  ck_assert_ptr_nonnull(fgets(line, sizeof line, f));
  ck_assert_str_eq(line, "t,a,b,vn\n");
  double *v = malloc(20000 * sizeof *v), t;
  size_t n = 0;
  char a[8], b[8];
  while (n < 20000 && fscanf(f, "%lf,%7[^,],%7[^,],%lf", &t, a, b, &v[n]) == 4) {
    ck_assert(v[n] < 0.0);
    ck_assert(t >= 0.0 && t <= 4e-8);
    v[n] = fabs(v[n]);
    n++;
  }
  fclose(f);
  ck_assert_uint_eq(n, o.c.hits);  /* all recorded */
  double s = sqrt(kB * T / (0.5 * m)), D, p, mean = 0.0;
  for (size_t i = 0; i < n; i++)
    mean += v[i] / (double)n;
  ck_assert_int_eq(sb_ks_test(v, n, flux_cdf, &s, &D, &p), SB_SUCCESS);
  ck_assert_msg(p > 1e-4, "KS of |v_n|: D = %g, p = %g", D, p);
  /* and the mean, E|v_n| = s sqrt(pi/2), sd s sqrt(2 - pi/2): |z| < 4
   * (a 5% error in the velocities gives z ~ 7) */
  const double z = (mean - s * sqrt(0.5 * PI)) /
                   (s * sqrt(2.0 - 0.5 * PI) / sqrt((double)n));
  ck_assert_msg(fabs(z) < 4.0, "mean |v_n| = %g s, z = %.2f", mean / s, z);
  free(v);
  sb_collide_free(c);
  sbt_rm_dir(dir);
  /* a mixture re-sorted in memory every step: each row names its pair's
   * species in the [species] order (p before q), whichever of the two
   * particles comes first in memory */
  snprintf(text, sizeof text,
           "[run]\nL = 4e-6\ndt = 1e-8\nsteps = 3\nseed = 12\n"
           "sort_every = 1\ndetect = ballistic\noutcome = count\n"
           "placement = uniform\noutput = %s\n[observe]\nfirst_hit = yes\n"
           "first_hit_velocities = 20000\n[species p]\nradius = 1e-8\n"
           "mass = %g\ntau = inf\nT = %g\ncount = 25000\n[species q]\n"
           "radius = 1e-8\nmass = %g\ntau = inf\nT = %g\ncount = 25000\n",
           dir, m, T, m, T);
  c = sb_collide_alloc();
  ck_assert_int_eq(sb_collide_read_string(c, text, "c.ini"), SB_SUCCESS);
  ck_assert_int_eq(sb_collide_run(c, NULL, NULL), SB_SUCCESS);
  f = fopen(path, "r");
  ck_assert_ptr_nonnull(f);
  ck_assert_ptr_nonnull(fgets(line, sizeof line, f));
  size_t npq = 0, nrow = 0;
  double vn;
  while (fscanf(f, "%lf,%7[^,],%7[^,],%lf", &t, a, b, &vn) == 4) {
    ck_assert_msg(strcmp(a, "q") || strcmp(b, "p"), "row %zu: q, p", nrow);
    npq += !strcmp(a, "p") && !strcmp(b, "q");
    nrow++;
  }
  fclose(f);
  ck_assert_uint_gt(npq, 100);
  sb_collide_free(c);
  sbt_rm_dir(dir);
  /* a detector without contact velocities: an error naming the key */
  c = sb_collide_alloc();
  ck_assert_int_eq(sb_collide_read_string(c, text, "c.ini"), SB_SUCCESS);
  ck_assert_int_eq(sb_collide_set(c, "run.detect=overlap"), SB_SUCCESS);
  ck_assert_int_eq(sb_collide_check(c), SB_EINVAL);
  ck_assert_ptr_nonnull(strstr(sb_collide_error(c), "first_hit_velocities"));
  sb_collide_free(c);
}
END_TEST

static Suite *suite(void)
{
  Suite *s = suite_create("collide_lib");
  TCase *tc = tcase_create("core");
  tcase_set_timeout(tc, 30);
  tcase_add_test(tc, test_run_from_string);
  tcase_add_test(tc, test_input_errors);
  tcase_add_test(tc, test_checks_and_warnings);
  tcase_add_test(tc, test_nothing_to_measure);
  tcase_add_test(tc, test_stopped_by_callback);
  tcase_add_test(tc, test_key_table);
  tcase_add_test(tc, test_msd_free_flight);
  tcase_add_test(tc, test_antipodal_snapshots);
  tcase_add_test(tc, test_contact_velocities);
  suite_add_tcase(s, tc);
  TCase *tm = tcase_create("firsthit");
  tcase_set_timeout(tm, 300);  /* ~2 s; sanitizer builds are slower */
  tcase_add_test(tm, test_firsthit_mixture);
  suite_add_tcase(s, tm);
  return s;
}

int main(void) { return sbt_run_suite(suite()); }
