/* bench_pbe.c — wall time of the population-balance solvers:
 * constant kernel K = 1, N0 = 1, monodisperse, integrated to t = 1000
 * (tau = 1000), with K = 1000 discrete sizes and with 200 sections over
 * 12 decades, for the linear solvers and gain evaluations; cost of one
 * RHS at K = 1000 (tabulated general kernel, separable direct, FFT) and
 * at K = 10^4 (direct vs FFT, ratio printed).  Goals: discrete K = 1000
 * < 1 s, sectional 200 < 50 ms.  The discrete dense solve (16 s at
 * K = 1000) is left out. */
#define _POSIX_C_SOURCE 200809L
#include <stdlib.h>

#include <smolbridge/pbe.h>

#include "benchutil.h"

/* the constant kernel as a user callback: tabulated general path */
static double k_user(double a, double b, const void *p)
{
  (void)a;
  (void)b;
  (void)p;
  return 1.0;
}

static double solve_time(sb_pbe_method m, size_t n, sb_pbe_linsol ls,
                         sb_pbe_gain gain, int user, sb_pbe_report *rep,
                         int *status)
{
  sb_kernel_spec ks;
  sb_kernel_spec_init(&ks, SB_KERNEL_CONSTANT);
  sb_pbe_config c;
  sb_pbe_config_init(&c);
  c.method = m;
  c.nsizes = n;
  if (m == SB_PBE_SECTIONAL)
    sb_pbe_config_sectional(&c, n, 12.0);
  c.kparams = &ks;
  if (user)
    c.kernel = k_user;
  c.rtol = 1e-6;
  c.linsol = ls;
  c.gain = gain;
  double t0 = sbb_now_ns();
  sb_pbe *p = sb_pbe_alloc(&c);
  if (!p) {
    *status = sb_last_status();
    return NAN;
  }
  sb_pbe_init_mono(p, 1.0);
  double t = 1000.0;
  *status = sb_pbe_solve(p, &t, 1, NULL, NULL, rep);
  double dt = (sbb_now_ns() - t0) * 1e-9;
  sb_pbe_free(p);
  return dt;
}

typedef struct {
  sb_pbe *p;
  double *n, *d;
} rhs_ctx;

static void k_rhs(void *ctx, size_t ncalls)
{
  rhs_ctx *c = ctx;
  for (size_t i = 0; i < ncalls; i++) {
    sb_pbe_rhs(c->p, 0.0, c->n, c->d);
    sbb_consume(c->d[1]);
  }
}

int main(int argc, char **argv)
{
  sbb_opts o = sbb_opts_parse(argc, argv);
  sbb_print_machine(stdout);
  printf("# constant kernel to tau = 1000, rtol 1e-6; wall time of alloc + "
         "solve\n");
  printf("%-34s %10s %8s %8s %12s %6s %s\n", "case", "seconds", "steps",
         "RHS", "RHS/s", "goal", "verdict");
  /* size and goal per method: discrete K = 1000 in 1 s, sectional
   * N = 200 in 50 ms */
  const char *mname[] = {"discrete K=1000", "sectional N=200"};
  const size_t msize[] = {1000, 200};
  const double mgoal[] = {1.0, 0.05};
  struct {
    sb_pbe_method m;
    const char *variant;
    sb_pbe_linsol ls;
    sb_pbe_gain gain;
    int user;
  } cases[] = {
      {SB_PBE_DISCRETE, "default", SB_PBE_LS_AUTO, SB_PBE_GAIN_AUTO, 0},
      {SB_PBE_DISCRETE, "FFT", SB_PBE_LS_AUTO, SB_PBE_GAIN_FFT, 0},
      {SB_PBE_DISCRETE, "user kernel", SB_PBE_LS_AUTO, SB_PBE_GAIN_AUTO, 1},
      {SB_PBE_DISCRETE, "plain GMRES", SB_PBE_LS_GMRES, SB_PBE_GAIN_AUTO, 0},
      {SB_PBE_SECTIONAL, "default", SB_PBE_LS_AUTO, SB_PBE_GAIN_AUTO, 0},
      {SB_PBE_SECTIONAL, "plain GMRES", SB_PBE_LS_GMRES, SB_PBE_GAIN_AUTO, 0},
      {SB_PBE_SECTIONAL, "dense", SB_PBE_LS_DENSE, SB_PBE_GAIN_AUTO, 0},
  };
  int miss = 0;
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
    sb_pbe_report r = {0};
    int st, m = (int)cases[i].m;
    double goal = mgoal[m];
    double dt = solve_time(cases[i].m, msize[m], cases[i].ls, cases[i].gain,
                           cases[i].user, &r, &st);
    int bad = st || !(dt <= goal);
    if (i == 0 || i == 4) /* the goals apply to the defaults */
      miss += bad;
    char name[64];
    snprintf(name, sizeof name, "%s %s", mname[m], cases[i].variant);
    printf("%-34s %10.3f %8ld %8ld %12.3g %6.2f %s%s\n", name, dt, r.nsteps,
           r.nrhs, (double)r.nrhs / dt, goal, bad ? "MISS" : "PASS",
           st ? " (solver error)" : "");
  }
  /* RHS evaluation cost: general tabulated path, separable direct O(K^2),
   * FFT O(K log K) */
  sbb_table_header(stdout);
  struct {
    size_t n;
    sb_pbe_gain gain;
    int user;
    const char *what;
  } rc_cases[] = {
      {1000, SB_PBE_GAIN_DIRECT, 1, "tabulated"},
      {1000, SB_PBE_GAIN_DIRECT, 0, "direct"},
      {1000, SB_PBE_GAIN_FFT, 0, "FFT"},
      {10000, SB_PBE_GAIN_DIRECT, 0, "direct"},
      {10000, SB_PBE_GAIN_FFT, 0, "FFT"},
  };
  double med[5];
  for (int s = 0; s < 5; s++) {
    size_t K = rc_cases[s].n;
    sb_kernel_spec ks;
    sb_kernel_spec_init(&ks, SB_KERNEL_CONSTANT);
    sb_pbe_config c;
    sb_pbe_config_init(&c);
    c.nsizes = K;
    c.kparams = &ks;
    if (rc_cases[s].user)
      c.kernel = k_user;
    c.gain = rc_cases[s].gain;
    rhs_ctx rc = {sb_pbe_alloc(&c), calloc(K, sizeof(double)),
                  calloc(K, sizeof(double))};
    if (!rc.p || !rc.n || !rc.d)
      return 2;
    for (size_t k = 0; k < K; k++)
      rc.n[k] = exp(-0.01 * (double)k);
    sbb_timing t = sbb_run(k_rhs, &rc, &o);
    med[s] = t.median;
    char name[64];
    snprintf(name, sizeof name, "sb_pbe_rhs K=%zu (%s)", K, rc_cases[s].what);
    sbb_table_row(stdout, name, &t, NAN);
    sb_pbe_free(rc.p);
    free(rc.n);
    free(rc.d);
  }
  printf("# ratio direct/FFT: K=1000 %.2f, K=10000 %.1f; tabulated/direct "
         "K=1000 %.2f\n", med[1] / med[2], med[3] / med[4], med[0] / med[1]);
  return miss ? 1 : 0;
}
