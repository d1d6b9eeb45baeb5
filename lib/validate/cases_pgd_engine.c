/* cases_pgd_engine.c — V15, the crossing jets of the course exercise
 * "Couplage Euler-Lagrange" (2022) run by the collision engine: open
 * boundaries (engine_open.c) inject the two jets as Poisson streams and
 * the particles' density is deposited on the exercise's 45 x 45 grid
 * (sb_engine_grid_fields), the Eulerian view of the Lagrangian solution.
 *
 * Set-up: unit square (m), inflow on the central ninth [4/9, 5/9] of the
 * west side with velocity (1, 0) and of the south side with (0, 1) (m/s),
 * every face open, gas at rest, Stokes drag of relaxation time tau
 * (non-Brownian, particles pass through each other).  Each jet enters as
 * a Poisson stream of rate n0 u w (w = 1/9): a spatial Poisson process of
 * number density n0 at the inlet, each particle carrying the mass 1/n0 so
 * that rho = 1 there (the exercise's inflow density).
 *
 * Exact reference.  A particle of the west jet moves along its row with
 * du/dt = -u/tau, so u = 1 - x/tau and the transit time to x is
 * -tau ln(1 - x/tau).  Once a cell has been reached by the jet, the
 * number of particles in it is Poisson (independent arrivals mapped by a
 * deterministic flight) with mean
 *   lambda = n0 h int dx / (1 - x/tau) = n0 h tau ln((1 - x0/tau)/(1 -
 *   x1/tau))
 * over the cell's [x0, x1] (the steady density n0/(1 - x/tau): mass flux
 * n u conserved along the jet); likewise for the south jet in y, and the
 * crossing cells hold the sum.  Compared: the cells whose whole extent
 * the jets reached at least 0.25 before the end; Pearson chi-square of
 * the counts against lambda (dof = cells), the exact Poisson test of the
 * total, and no particle outside the two bands (deterministic paths).
 * At tau = 200, the rho map against the pressureless Eulerian solution
 * (lib/pgd, upwind) at the same time: the particle jets cross, the
 * Eulerian ones merge into a diagonal delta-jet (relative L1 >= 0.5).
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <smolbridge/engine.h>
#include <smolbridge/pgd.h>
#include <smolbridge/stats.h>

#include "cases.h"

#define NG 45          /* the exercise's grid */
#define B0 20          /* first cell of the inlet band (5 cells) */
#define B1 25

typedef struct {
  double tau, t_end, dt;
  const char *label;
} ejet_cfg;

static const ejet_cfg ECFG[2] = {
    {200.0, 2.0, 0.01, "tau=200"},
    {1.0, 2.0, 0.005, "tau=1"},
};

/* Expected count of one jet in the cell [x0, x1] of its direction (h the
 * cell's width across the jet). */
static double lambda_jet(double n0, double h, double tau, double x0,
                         double x1)
{
  return n0 * h * tau * (log1p(-x0 / tau) - log1p(-x1 / tau));
}

/* Engine run; counts[i + NG j] receives the NGP particle count of each
 * cell at t_end. */
static int run_engine(const sbv_ctx *ctx, const ejet_cfg *c, double n0,
                      unsigned long stream, double *counts)
{
  const double w = (double)(B1 - B0) / NG, L = 1.0;
  /* particles in the box at the end: both jets up to where they got */
  double xr = c->tau * -expm1(-c->t_end / c->tau);
  if (xr > L)
    xr = L;
  const double npart = 2.0 * n0 * w * c->tau * -log1p(-xr / c->tau);
  sb_engine_params p;
  sb_engine_params_default(&p);
  p.dim = 2;
  p.L[0] = p.L[1] = L;
  p.dt = c->dt;
  p.capacity = (size_t)(1.3 * npart + 1000.0);
  p.seed = ctx->seed * 1000 + 970 + stream;
  p.outcome = SB_OUTCOME_COUNT;
  p.detect = SB_DETECT_OVERLAP;
  sb_engine *e = sb_engine_alloc(&p);
  if (!e)
    return sb_last_status();
  /* tiny non-Brownian spheres (the contact search finds nothing) */
  const double m = 1.0 / n0;
  sb_engine_species s = {1e-9, m, c->tau, 0.0, 0.0};
  int st = sb_engine_add_species(e, &s, NULL);
  for (int k = 0; k < 2 && !st; k++)
    st = sb_engine_set_walls(e, k, SB_WALL_OPEN, SB_WALL_OPEN);
  if (!st)
    st = sb_engine_set_wall_mode(e, SB_WALLDET_BALLISTIC, SB_DEPOSIT_REMOVE);
  for (int j = 0; j < 2 && !st; j++) {
    sb_engine_inflow in;
    memset(&in, 0, sizeof in);
    in.face = j == 0 ? 0 : 2;  /* west (x = 0), south (y = 0) */
    in.family = j;
    in.rate = n0 * 1.0 * w;
    in.lo[0] = (double)B0 / NG;
    in.hi[0] = (double)B1 / NG;
    in.u[j] = 1.0;
    st = sb_engine_add_inflow(e, &in, NULL);
  }
  if (!st)
    st = sb_engine_run_until(e, c->t_end);
  const size_t n[3] = {NG, NG, 1};
  double *rho = st ? NULL : malloc(NG * NG * sizeof *rho);
  if (!st && !rho)
    st = SB_ENOMEM;
  if (!st)
    st = sb_engine_grid_fields(e, n, SB_GRID_NGP, -1, rho, NULL);
  if (!st) {
    const double h2 = 1.0 / (NG * NG);
    for (size_t q = 0; q < NG * NG; q++)
      counts[q] = nearbyint(rho[q] * h2 / m);
  }
  free(rho);
  sb_engine_free(e);
  return st;
}

/* The exercise's pressureless Eulerian solution at t_end on the 45 x 45
 * grid (upwind), rho into rho_e. */
static int run_euler(const ejet_cfg *c, double *rho_e)
{
  sb_pgd_params p;
  sbv_pgd_jets_params(&p, NG, c->tau, SB_PGD_UPWIND, 0.0, 0.0);
  sb_pgd *g = sb_pgd_alloc(&p);
  if (!g)
    return sb_last_status();
  int st = sb_pgd_advance(g, c->t_end, NULL);
  if (!st)
    st = sb_pgd_fields(g, rho_e, NULL, NULL);
  sb_pgd_free(g);
  return st;
}

static int case_engine_jets(const sbv_ctx *ctx, sbv_report *rep)
{
  const double h = 1.0 / NG;
  /* particles per cell at the inlet */
  const double per_cell = ctx->full ? 80.0 : 20.0, n0 = per_cell / (h * h);
  double *counts = malloc(NG * NG * sizeof *counts);
  double *rho_e = malloc(NG * NG * sizeof *rho_e);
  double *map = malloc(4 * NG * NG * sizeof *map);
  int st = (counts && rho_e && map) ? SB_SUCCESS : SB_ENOMEM;
  char name[96];
  sbv_note(rep, "Crossing jets of the exercise run by the engine: unit "
           "square, inflow on the central ninth of the west (u = (1, 0)) "
           "and south (u = (0, 1)) sides as Poisson streams of %g "
           "particles per inlet cell area (mass 1/n0 each: rho = 1 at the "
           "inlet), every face open, gas at rest, Stokes drag tau, "
           "particles pass through each other; NGP counts on the 45 x 45 "
           "grid at t_end against the exact steady counts n0 h tau ln((1 "
           "- x0/tau)/(1 - x1/tau)) of the cells the jets reached 0.25 "
           "before t_end (Pearson chi-square, dof = cells; exact Poisson "
           "test of the total; no particle outside the bands).", per_cell);
  for (int q = 0; q < 2 && !st; q++) {
    const ejet_cfg *c = &ECFG[q];
    sbv_progress(ctx, "V15 engine jets: %s", c->label);
    st = run_engine(ctx, c, n0, (unsigned long)q, counts);
    if (st)
      break;
    /* cells reached by t_end - 0.25 */
    const double xs = c->tau * -expm1(-(c->t_end - 0.25) / c->tau);
    double chi2 = 0.0, ksum = 0.0, lsum = 0.0, outside = 0.0;
    size_t ncell = 0;
    for (size_t j = 0; j < NG; j++)
      for (size_t i = 0; i < NG; i++) {
        const double k = counts[i + NG * j];
        const int inw = j >= B0 && j < B1, ins = i >= B0 && i < B1;
        if (!inw && !ins) {
          outside += k;
          continue;
        }
        const double x0 = (double)i * h, y0 = (double)j * h;
        if ((inw && x0 + h > xs) || (ins && y0 + h > xs))
          continue;  /* not steady yet */
        double lam = 0.0;
        if (inw)
          lam += lambda_jet(n0, h, c->tau, x0, x0 + h);
        if (ins)
          lam += lambda_jet(n0, h, c->tau, y0, y0 + h);
        chi2 += (k - lam) * (k - lam) / lam;
        ksum += k;
        lsum += lam;
        ncell++;
      }
    const double dof = (double)ncell;
    snprintf(name, sizeof name, "V15/engine-jets/%s/cell-counts-chi2",
             c->label);
    if ((st = sbv_add_chi2(rep, name, SB_SUCCESS, chi2, dof,
                           sb_chi2_sf(chi2, dof))))
      break;
    sb_comparison cmp;
    snprintf(name, sizeof name, "V15/engine-jets/%s/total-count",
             c->label);
    sb_compare_poisson(&cmp, name, (unsigned long)ksum, 1.0 / lsum, 1.0,
                       SBV_ALPHA);
    if ((st = sbv_add(rep, &cmp)))
      break;
    snprintf(name, sizeof name, "V15/engine-jets/%s/outside-bands",
             c->label);
    if ((st = sbv_add_band(rep, name, outside, 0.0, 0.0, 0.0)))
      break;
    sbv_note(rep, "- %s (dt = %g, t_end = %g): %zu steady cells, chi2 = "
             "%.1f (dof %zu), total %.0f particles against %.1f expected "
             "(ratio %.4f), %.0f outside the bands", c->label, c->dt,
             c->t_end, ncell, chi2, ncell, ksum, lsum, ksum / lsum,
             outside);
    if (q == 0) {
      /* the Eulerian jets merge where the particle jets cross */
      if ((st = run_euler(c, rho_e)))
        break;
      double l1 = 0.0, mass = 0.0;
      for (size_t j = 0; j < NG; j++)
        for (size_t i = 0; i < NG; i++) {
          const size_t cc = i + NG * j;
          const double rl = counts[cc] / (n0 * h * h);
          l1 += fabs(rl - rho_e[cc]) * h * h;
          mass += rl * h * h;
          double *row = map + 4 * cc;
          row[0] = ((double)i + 0.5) * h;
          row[1] = ((double)j + 0.5) * h;
          row[2] = rho_e[cc];
          row[3] = rl;
        }
      snprintf(name, sizeof name, "V15/engine-jets/%s/vs-euler/"
               "rel-L1-rho>=0.5", c->label);
      if ((st = sbv_add_band(rep, name, l1 / mass, 0.5, -INFINITY,
                             l1 / mass)))
        break;
      sbv_note(rep, "- %s at t = %g: relative L1(rho) engine vs Euler "
               "(upwind, 45 x 45) = %.3f: the particle jets cross, the "
               "Eulerian ones merge (criterion >= 0.5, as V15/pgd-jets)",
               c->label, c->t_end, l1 / mass);
      sbv_plot(ctx, rep, "engine_jets_map",
               "crossing jets, tau = 200, t = 2, 45 x 45: Euler vs engine",
               "x y rho_euler rho_engine", map, NG * NG, 4,
               "unset title\nset multiplot layout 1,2 title 'crossing "
               "jets, tau = 200, t = 2'\nset size ratio 1\nset xrange "
               "[0:1]\nset yrange [0:1]\nset cbrange [0:3]\nset palette "
               "rgb 33,13,10\nset xlabel 'x'\nset ylabel 'y'\nset title "
               "'Euler (upwind)'\nplot $DATA u 1:2:3 w image notitle\n"
               "set title 'engine (NGP deposit)'\nplot $DATA u 1:2:4 w "
               "image notitle\nunset multiplot");
    }
  }
  free(counts);
  free(rho_e);
  free(map);
  return st;
}

const sbv_case sbv_cases_pgd_engine[] = {
    {"V15/engine-jets",
     "the exercise's crossing jets run by the engine (open boundaries, "
     "grid deposit) vs the exact steady density, and vs the Eulerian "
     "solution",
     case_engine_jets},
};
const size_t sbv_ncases_pgd_engine =
    sizeof sbv_cases_pgd_engine / sizeof sbv_cases_pgd_engine[0];
