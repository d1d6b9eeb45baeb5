/* bench_pbe.c — wall time of the population-balance solvers (issue 4):
 * constant kernel K = 1, N0 = 1, monodisperse, integrated to t = 1000
 * (tau = 1000), with K = 1000 discrete sizes and with 200 sections over
 * 12 decades, for both linear solvers; RHS evaluations per second at
 * K = 1000 and 10^4.  Goals: discrete K = 1000 < 1 s, sectional 200 <
 * 50 ms.  The O(K log K) FFT gain term (stretch goal) is not implemented:
 * the direct O(K^2) RHS is what is measured. */
#define _POSIX_C_SOURCE 200809L
#include <stdlib.h>

#include <smolbridge/pbe.h>

#include "benchutil.h"

static double solve_time(sb_pbe_method m, size_t n, sb_pbe_linsol ls,
                         sb_pbe_report *rep, int *status)
{
  sb_kernel_spec ks;
  sb_kernel_spec_init(&ks, SB_KERNEL_CONSTANT);
  sb_pbe_config c;
  sb_pbe_config_init(&c);
  c.method = m;
  c.nsizes = n;
  c.ratio = pow(10.0, 12.0 / (double)(n - 1));
  c.kparams = &ks;
  c.rtol = 1e-6;
  c.linsol = ls;
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
  struct {
    const char *name;
    sb_pbe_method m;
    size_t n;
    sb_pbe_linsol ls;
    double goal;
  } cases[] = {
      {"discrete K=1000, GMRES", SB_PBE_DISCRETE, 1000, SB_PBE_LS_GMRES, 1.0},
      {"discrete K=1000, dense", SB_PBE_DISCRETE, 1000, SB_PBE_LS_DENSE, 1.0},
      {"sectional N=200, GMRES", SB_PBE_SECTIONAL, 200, SB_PBE_LS_GMRES, 0.05},
      {"sectional N=200, dense", SB_PBE_SECTIONAL, 200, SB_PBE_LS_DENSE, 0.05},
  };
  int miss = 0;
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
    sb_pbe_report r = {0};
    int st;
    double dt = solve_time(cases[i].m, cases[i].n, cases[i].ls, &r, &st);
    int bad = st || !(dt <= cases[i].goal);
    miss += bad;
    printf("%-34s %10.3f %8ld %8ld %12.3g %6.2f %s%s\n", cases[i].name, dt,
           r.nsteps, r.nrhs, (double)r.nrhs / dt, cases[i].goal,
           bad ? "MISS" : "PASS", st ? " (solver error)" : "");
  }
  /* RHS evaluation cost, direct O(K^2) */
  sbb_table_header(stdout);
  size_t sizes[] = {1000, 10000};
  for (int s = 0; s < 2; s++) {
    sb_kernel_spec ks;
    sb_kernel_spec_init(&ks, SB_KERNEL_CONSTANT);
    sb_pbe_config c;
    sb_pbe_config_init(&c);
    c.nsizes = sizes[s];
    c.kparams = &ks;
    c.linsol = SB_PBE_LS_GMRES;
    rhs_ctx rc = {sb_pbe_alloc(&c), calloc(sizes[s], sizeof(double)),
                  calloc(sizes[s], sizeof(double))};
    if (!rc.p || !rc.n || !rc.d)
      return 2;
    for (size_t k = 0; k < sizes[s]; k++)
      rc.n[k] = exp(-0.01 * (double)k);
    sbb_opts oo = o;
    if (sizes[s] > 5000) /* ~0.3 s per call: a few calls are enough */
      oo.reps = 3;
    sbb_timing t = sbb_time(k_rhs, &rc, sizes[s] > 5000 ? 2 : 50, oo.reps);
    char name[64];
    snprintf(name, sizeof name, "sb_pbe_rhs discrete K=%zu (direct)",
             sizes[s]);
    sbb_table_row(stdout, name, &t, NAN);
    sb_pbe_free(rc.p);
    free(rc.n);
    free(rc.d);
  }
  return miss ? 1 : 0;
}
