/* cases_pgd_dense.c — V15, dense crossing jets with collisions (Thomine
 * 2008, §9, Lagrangian side) beside the pressureless Eulerian answer.
 *
 * Set-up: the crossing jets of the course exercise "Couplage
 * Euler-Lagrange" (2022) scaled to a square of side L = 1 mm: a jet of
 * width L/9 enters the west side at mid-height with velocity (U, 0), one
 * enters the south side at mid-width with (0, U), U = 1 m/s.  Each jet is
 * bidisperse as Thomine's: radii a0 = 2 um and 2 a0, equal volume per size
 * (8 small drops per large one), drop density 1000 kg/m^3, free flight (no
 * drag: the exercise's tau = 200 L/U is effectively infinite over a run),
 * discs colliding in the plane with the masses of spheres.
 *
 * The square is the engine's box with open boundaries (engine_open.c):
 * four inflows (two jets, two sizes) inject Poisson streams (uniform over
 * the inlet and in time: each jet is a spatial Poisson process of the
 * chosen area fraction; with collisions a draw that would overlap a drop
 * is redrawn), and every face is open: a drop whose centre crosses one
 * leaves, and the outflow callback records its side, the point where its
 * chord crossed it and its momentum.
 *
 * Three densities (injected area fraction phi in the jet): phi = 0.2
 * without collisions (the drops pass through each other), phi = 0.02 and
 * 0.2 with elastic collisions.  After a warm-up of 2 L/U the exits are
 * recorded in batches of L/(2U); t intervals over the batch means.
 *
 * Records: without collisions, every drop of the west jet leaves through
 * the east side (tolerance band, exact) and the mass in the crossing
 * square holds the two jets' expected masses, 2 n w^2 <m> (Thomine's "mass
 * density about doubles at the crossing": the mean excess over batches vs
 * 0, t test); the drop balance of every batch (injected = removed +
 * the change inside, exactly).  With collisions, the family mixing at the
 * east exit, the share of each family leaving through its own side, the
 * back-scattered share, the mean exit position and direction and the
 * collisions per drop
 * are measured (informational: findings, not code tests) beside the
 * pressureless Eulerian solution of the same inflow (lib/pgd), where the
 * jets merge into one diagonal jet (a delta-shock). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_cdf.h>
#include <gsl/gsl_rng.h>

#include <smolbridge/engine.h>
#include <smolbridge/langevin.h>
#include <smolbridge/pgd.h>

#include "cases.h"

#define PI 3.14159265358979323846
#define NBIN 36      /* exit profile bins over the east + north sides */
#define NSIDE 4      /* 0 east, 1 north, 2 west, 3 south */

static const double DJ_L = 1e-3, DJ_U = 1.0, DJ_A0 = 2e-6, DJ_RHO = 1000.0;

typedef struct {
  double phi;      /* injected area fraction in each jet */
  int collide;     /* elastic collisions, or pass-through */
  const char *label;
} dj_cfg;

static const dj_cfg DJ_CFGS[3] = {
    {0.2, 0, "no-collision/phi=0.2"},
    {0.02, 1, "collisions/phi=0.02"},
    {0.2, 1, "collisions/phi=0.2"},
};

/* Exits and samples of one batch of the measurement time. */
typedef struct {
  double m_side[2][NSIDE];      /* exiting mass per family and side */
  double m_out;                 /* exiting mass, in the order of exits */
  double q_east[2];             /* momentum leaving through the east side */
  double my_east;               /* mass-weighted exit y (east), m */
  double cross, up[2], nsamp;   /* mass in the crossing square and in
                                   the upstream squares of the west and
                                   south jets, samples */
  double coll0, coll1;          /* collision counter at start and end */
  double inj, out;              /* drops injected, leaving */
  double n0, n1;                /* drops inside at start and end */
} dj_batch;

#define MAXB 64

typedef struct {
  dj_batch b[MAXB];
  int nb;                       /* batches */
  double prof[2][NBIN];         /* exit mass per family and bin (E + N) */
  double n_in, n_out, n_inside; /* drop balance (exact integers) */
  double m_expected;            /* expected mass in one square */
  double injected, rejected;
} dj_out;

static double drop_mass(double r) { return DJ_RHO * 4.0 / 3.0 * PI * r * r * r; }

/* The outflow callback's context: the current batch (NULL in the
 * warm-up) and the run's totals. */
typedef struct {
  dj_batch *bt;
  dj_out *o;
} dj_exit;

/* Record a drop leaving the square (sb_engine_outflow_fn): its side, the
 * point where its chord crossed it, its momentum. */
static int on_exit(const sb_engine *e, size_t i, int face, double t_exit,
                   void *vctx)
{
  dj_exit *x = vctx;
  if (!x->bt)
    return 0;
  static const int side_of[4] = {2, 0, 3, 1}; /* x_lo, x_hi, y_lo, y_hi */
  const int s = side_of[face], f = sb_engine_families(e)[i];
  const double *p = &sb_engine_positions(e)[3 * i];
  const double *u = &sb_engine_velocities(e)[3 * i];
  const double m = sb_engine_masses(e)[i];
  /* back along the chord to the face: the state is at the step's end */
  const double back = sb_engine_time(e) + sb_engine_get_params(e)->dt - t_exit;
  x->bt->m_side[f][s] += m;
  x->bt->m_out += m;
  double along = NAN;  /* exit point along the side, units L */
  if (s == 0) {
    const double y = p[1] - u[1] * back;
    along = y / DJ_L;
    x->bt->q_east[0] += m * u[0];
    x->bt->q_east[1] += m * u[1];
    x->bt->my_east += m * y;
  } else if (s == 1) {
    along = (p[0] - u[0] * back) / DJ_L;
  }
  if (s <= 1 && isfinite(along)) {
    /* east side bottom to top, then north side right to left */
    double c = s == 0 ? along : 2.0 - along;
    int b = (int)(c / 2.0 * NBIN);
    b = b < 0 ? 0 : (b >= NBIN ? NBIN - 1 : b);
    x->o->prof[f][b] += m;
  }
  return 0;
}

/* The crossing square and the two upstream squares of the jets (side
 * L/9, the upstream ones centred 2.5 widths before it), x0 x1 y0 y1:
 * collide's [observe] region lines of the written files. */
static void squares(double sq[3][4])
{
  const double w = DJ_L / 9.0;
  const double c[3][2] = {{4.0, 4.0}, {1.5, 4.0}, {4.0, 1.5}};
  for (int q = 0; q < 3; q++) {
    sq[q][0] = c[q][0] * w;
    sq[q][1] = (c[q][0] + 1.0) * w;
    sq[q][2] = c[q][1] * w;
    sq[q][3] = (c[q][1] + 1.0) * w;
  }
}

/* Mass inside the crossing square and the two upstream squares. */
static void sample_squares(const sb_engine *e, dj_batch *o)
{
  double sq[3][4];
  squares(sq);
  const double *x = sb_engine_positions(e), *m = sb_engine_masses(e);
  for (int q = 0; q < 3; q++) {
    double s = q ? o->up[q - 1] : o->cross;
    for (size_t i = 0; i < sb_engine_count(e); i++) {
      const double px = x[3 * i], py = x[3 * i + 1];
      if (px >= sq[q][0] && px < sq[q][1] && py >= sq[q][2] && py < sq[q][3])
        s += m[i];
    }
    if (q)
      o->up[q - 1] = s;
    else
      o->cross = s;
  }
  o->nsamp += 1.0;
}

static double count_out(const sb_engine *e)
{
  double s = 0.0;
  for (int f = 0; f < 4; f++)
    s += (double)sb_engine_outflows(e, f);
  return s;
}

/* One run: the square is the engine's box with open faces (detected on
 * the straight chords: free flight) and four inflows (two jets, two
 * sizes). */
static int run_dense(const sbv_ctx *ctx, unsigned long stream,
                     const dj_cfg *c, int nbatch, double t_batch, dj_out *o)
{
  memset(o, 0, sizeof *o);
  o->nb = nbatch < MAXB ? nbatch : MAXB;
  const double w = DJ_L / 9.0, r[2] = {DJ_A0, 2.0 * DJ_A0};
  /* number densities: phi = n0 pi a0^2 + n1 pi (2 a0)^2 with n0 = 8 n1 */
  const double n1 = c->phi / (PI * DJ_A0 * DJ_A0 * 12.0), n[2] = {8.0 * n1,
                                                                  n1};
  const double dt = 1e-6, t_warm = 2.0 * DJ_L / DJ_U;
  o->m_expected = w * w * (n[0] * drop_mass(r[0]) + n[1] * drop_mass(r[1]));
  sb_engine_params p;
  sbv_engine_params(&p);  /* MT19937, as the written file's rng = mt19937 */
  p.dim = 2;
  p.L[0] = p.L[1] = DJ_L;
  p.dt = dt;
  p.seed = ctx->seed * 1000 + 950 + stream;
  p.outcome = c->collide ? SB_OUTCOME_ELASTIC : SB_OUTCOME_COUNT;
  /* drops inside: two jets of L x w at most, three times for slowed ones */
  p.capacity = (size_t)(6.0 * (n[0] + n[1]) * w * DJ_L) + 1000;
  sb_engine *e = sb_engine_alloc(&p);
  int st = !e ? SB_ENOMEM : SB_SUCCESS;
  for (int k = 0; k < 2 && !st; k++) {
    /* free flight; T only sets the engine's thermal scale (the injected
     * velocities are exact), here a speed of 1e-4 U */
    const double T = drop_mass(r[k]) * 1e-8 * DJ_U * DJ_U / SB_BOLTZMANN;
    sb_engine_species s = {r[k], drop_mass(r[k]), INFINITY, 0.0, T};
    st = sb_engine_add_species(e, &s, NULL);
  }
  for (int k = 0; k < 2 && !st; k++)
    st = sb_engine_set_walls(e, k, SB_WALL_OPEN, SB_WALL_OPEN);
  if (!st)
    st = sb_engine_set_wall_mode(e, SB_WALLDET_BALLISTIC, SB_DEPOSIT_REMOVE);
  for (int jet = 0; jet < 2 && !st; jet++)
    for (int sp = 0; sp < 2 && !st; sp++) {
      sb_engine_inflow in = {jet ? 2 : 0, (size_t)sp, jet,
                             n[sp] * DJ_U * w, {4.0 * w, 0}, {5.0 * w, 0},
                             {jet ? 0.0 : DJ_U, jet ? DJ_U : 0.0, 0.0},
                             c->collide};
      st = sb_engine_add_inflow(e, &in, NULL);
    }
  dj_exit ex = {NULL, o};
  if (!st)
    st = sb_engine_set_outflow_fn(e, on_exit, &ex);
  const long warm = lround(t_warm / dt), per = lround(t_batch / dt);
  const long total = warm + per * o->nb;
  sb_engine_stats es;
  for (long k = 0; k < total && !st; k++) {
    const long mk = k - warm;   /* step index in the measurement */
    dj_batch *bt = mk >= 0 ? &o->b[mk / per] : NULL;
    if (bt && mk % per == 0) {
      sb_engine_get_stats(e, &es);
      bt->coll0 = (double)es.ncoll;
      for (size_t q = 0; q < 4; q++)
        bt->inj -= (double)sb_engine_inflow_injected(e, q);
      bt->out = -count_out(e);
      bt->n0 = (double)sb_engine_count(e);
    }
    ex.bt = bt;
    st = sb_engine_step(e);
    if (!st && bt && mk % 10 == 9)
      sample_squares(e, bt);
    if (!st && bt && mk % per == per - 1) {
      sb_engine_get_stats(e, &es);
      bt->coll1 = (double)es.ncoll;
      for (size_t q = 0; q < 4; q++)
        bt->inj += (double)sb_engine_inflow_injected(e, q);
      bt->out += count_out(e);
      bt->n1 = (double)sb_engine_count(e);
    }
  }
  if (!st) {
    for (size_t q = 0; q < 4; q++) {
      o->n_in += (double)sb_engine_inflow_injected(e, q);
      o->rejected += (double)sb_engine_inflow_skipped(e, q);
    }
    for (int f = 0; f < 4; f++)
      o->n_out += (double)sb_engine_outflows(e, f);
    o->n_inside = (double)sb_engine_count(e);
    o->injected = o->n_in;
  }
  sb_engine_free(e);
  return st;
}

/* The pressureless Eulerian answer: the exercise's jets (rho = 1, unit
 * speed, unit square, tau = 200) at t = 3, east-side outflow profile of
 * the mass flux in NBIN/2 bins, its mean exit y and direction. */
static int euler_jets(double *prof, double *y_mean, double *angle)
{
  const size_t nx = 45, wc = 5;
  sb_pgd_params p;
  sb_pgd_params_default(&p, 2);
  p.nx = p.ny = nx;
  p.tau = 200.0;
  for (int s = 0; s < 4; s++)
    p.bc[s] = SB_PGD_OUTFLOW;
  sb_pgd_params_add_inflow(&p, SB_PGD_WEST, (nx - wc) / 2, wc, 1, 1, 0);
  sb_pgd_params_add_inflow(&p, SB_PGD_SOUTH, (nx - wc) / 2, wc, 1, 0, 1);
  sb_pgd *g = sb_pgd_alloc(&p);
  if (!g)
    return SB_ENOMEM;
  int st = sb_pgd_advance(g, 3.0, NULL);
  double mf = 0.0, my = 0.0, qx = 0.0, qy = 0.0;
  for (int b = 0; b < NBIN; b++)
    prof[b] = 0.0;
  for (size_t j = 0; j < nx && !st; j++) {
    /* east column and north row: the mass flux through the side */
    double rho, u[2];
    double y = ((double)j + 0.5) / (double)nx;
    if ((st = sb_pgd_get_cell(g, nx - 1, j, &rho, u)))
      break;
    double f = u[0] > 0 ? rho * u[0] : 0.0;
    mf += f;
    my += f * y;
    qx += f * u[0];
    qy += f * u[1];
    prof[(int)(y / 2.0 * NBIN)] += f / (double)nx;
    if ((st = sb_pgd_get_cell(g, j, nx - 1, &rho, u)))
      break;
    f = u[1] > 0 ? rho * u[1] : 0.0;
    int b = (int)((2.0 - y) / 2.0 * NBIN);
    prof[b >= NBIN ? NBIN - 1 : b] += f / (double)nx;
  }
  double tot = 0.0;
  for (int b = 0; b < NBIN; b++)
    tot += prof[b];
  for (int b = 0; b < NBIN; b++)  /* density in s, as the Lagrangian ones */
    prof[b] = tot > 0 ? prof[b] / tot * NBIN / 2.0 : 0.0;
  *y_mean = mf > 0 ? my / mf : NAN;
  *angle = atan2(qy, qx) * 180.0 / PI;
  sb_pgd_free(g);
  return st;
}

/* The file of run k of configuration ci: the same run in `smolbridge
 * collide` (four species, one inflow each in the engine's inflow order;
 * [observe] batch_steps and region give the batches), its records as
 * statistics over the rows of batches.csv ("; expect-batches"). */
static int write_dense(const sbv_ctx *ctx, sbv_report *rep, int ci, int k,
                       int nbatch, double t_batch)
{
  static const char *const file[3] = {"nocoll_phi0.2", "coll_phi0.02",
                                      "coll_phi0.2"};
  const dj_cfg *c = &DJ_CFGS[ci];
  const double w = DJ_L / 9.0, r[2] = {DJ_A0, 2.0 * DJ_A0};
  const double n1 = c->phi / (PI * DJ_A0 * DJ_A0 * 12.0), n[2] = {8.0 * n1,
                                                                  n1};
  const double dt = 1e-6, t_warm = 2.0 * DJ_L / DJ_U;
  const double m_expected =
      w * w * (n[0] * drop_mass(r[0]) + n[1] * drop_mass(r[1]));
  const long per = lround(t_batch / dt);
  char fn[64], name[160], spec[400];
  snprintf(fn, sizeof fn, "V15_dense_jets_%s_r%d", file[ci], k + 1);
  FILE *f = sbv_ini_begin(ctx, rep, fn, "V15: dense crossing jets (Thomine "
                          "2008, §9), batch means of the exits and of the "
                          "mass in three squares");
  if (!f)
    return SB_EIO;
  fprintf(f, "seed = %lu\nrng = mt19937\ndim = 2\nL = %.17g\ndt = %.17g\n"
          "warmup = %.17g\nsteps = %ld\nneigh = cells\ndetect = ballistic\n"
          "outcome = %s\n\n[walls]\nx_lo = open\nx_hi = open\ny_lo = open\n"
          "y_hi = open\ndetect = ballistic\n\n[observe]\n"
          "batch_steps = %ld\nregion_every = 10\n",
          ctx->seed * 1000 + 950 + (unsigned long)(10 * ci + k), DJ_L, dt,
          t_warm, per * nbatch, c->collide ? "elastic" : "count", per);
  double sq[3][4];
  squares(sq);
  fprintf(f, "; the crossing square, the upstream squares of the west and "
          "south jets\n");
  for (int q = 0; q < 3; q++)
    fprintf(f, "region = %.17g %.17g %.17g %.17g\n", sq[q][0], sq[q][1],
            sq[q][2], sq[q][3]);
  for (int jet = 0; jet < 2; jet++)
    for (int sp = 0; sp < 2; sp++) {
      const double T =
          drop_mass(r[sp]) * 1e-8 * DJ_U * DJ_U / SB_BOLTZMANN;
      fprintf(f, "\n[species %s_%s]\nradius = %.17g\nmass = %.17g\n"
              "tau = inf\nT = %.17g\nfamily = %d\ninflow = %s\n"
              "inflow_rate = %.17g\ninflow_region = %.17g %.17g\n"
              "inflow_velocity = %.17g %.17g\ninflow_no_overlap = %s\n",
              jet ? "south" : "west", sp ? "large" : "small", r[sp],
              drop_mass(r[sp]), T, jet, jet ? "y_lo" : "x_lo",
              n[sp] * DJ_U * w, 4.0 * w, 5.0 * w, jet ? 0.0 : DJ_U,
              jet ? DJ_U : 0.0, c->collide ? "yes" : "no");
    }
  int st = sbv_ini_end(rep, f, NULL);
  /* the records: E, N, W, S = x_hi, y_hi, x_lo, y_lo; family 0 the west
   * jet, 1 the south jet */
  struct {
    const char *what;
    char spec[400];
  } rows[10];
  int nr = 0;
  rows[nr].what = "drop-balance";
  snprintf(rows[nr++].spec, 400, "max abs(injected - left - (n_end - "
           "n_start))");
  if (!c->collide) {
    rows[nr].what = "west-jet-share-east";
    snprintf(rows[nr++].spec, 400, "min m_x_hi_f0 / (m_x_hi_f0 + "
             "m_x_hi_f1)");
    rows[nr].what = "crossing-excess";
    snprintf(rows[nr++].spec, 400, "mean region1 / %.17g - 2.0",
             m_expected);
  }
  rows[nr].what = "crossing/one-jet";
  snprintf(rows[nr++].spec, 400, "mean 2.0 * region1 / (region2 + "
           "region3)");
  rows[nr].what = "east-exit-west-jet-share";
  snprintf(rows[nr++].spec, 400, "mean m_x_hi_f0 / (m_x_hi_f0 + "
           "m_x_hi_f1)");
  rows[nr].what = "own-side-share";
  snprintf(rows[nr++].spec, 400, "mean (m_x_hi_f0 + m_y_hi_f1) / m_left");
  rows[nr].what = "back-scattered-share";
  snprintf(rows[nr++].spec, 400, "mean (m_x_lo_f0 + m_y_lo_f0 + m_x_lo_f1 "
           "+ m_y_lo_f1) / m_left");
  rows[nr].what = "east-exit-y/L";
  snprintf(rows[nr++].spec, 400, "mean my_x_hi / (m_x_hi_f0 + m_x_hi_f1) "
           "/ %.17g", DJ_L);
  rows[nr].what = "east-exit-angle-deg";
  snprintf(rows[nr++].spec, 400, "mean atan2(py_x_hi, px_x_hi) * 180.0 / "
           "pi");
  if (c->collide) {
    rows[nr].what = "collisions-per-drop";
    snprintf(rows[nr++].spec, 400, "mean 2.0 * collisions / injected");
  }
  for (int q = 0; q < nr && !st; q++) {
    snprintf(name, sizeof name, "V15/dense-jets/%s/%s", c->label,
             rows[q].what);
    snprintf(spec, sizeof spec, "%s", rows[q].spec);
    sbv_ini_expect_stat(rep, "expect-batches", name, spec);
  }
  return st;
}

static int add_info_mean(sbv_report *rep, const char *name, const double *x,
                         size_t n, double ref)
{
  double s = 0.0, s2 = 0.0;
  for (size_t k = 0; k < n; k++)
    s += x[k];
  double mean = s / (double)n;
  for (size_t k = 0; k < n; k++)
    s2 += (x[k] - mean) * (x[k] - mean);
  double se = n > 1 ? sqrt(s2 / (double)(n - 1) / (double)n) : NAN;
  double tq = n > 1 ? gsl_cdf_tdist_Pinv(0.975, (double)(n - 1)) : NAN;
  return sbv_add_info(rep, name, mean, ref, mean - tq * se, mean + tq * se,
                      0.95);
}

static int case_dense(const sbv_ctx *ctx, sbv_report *rep)
{
  /* quick: one run of 6 batches of L/(2U); full: 4 runs of 20 */
  const int R = ctx->full ? 4 : 1, NB = ctx->full ? 20 : 6;
  const double t_batch = 0.5 * DJ_L / DJ_U;
  enum { NMAX = 4 * 20 };
  if (sbv_writing(ctx)) {  /* the runs as collide files */
    int st = SB_SUCCESS;
    for (int ci = 0; ci < 3 && !st; ci++)
      for (int k = 0; k < R && !st; k++)
        st = write_dense(ctx, rep, ci, k, NB, t_batch);
    return st;
  }
  double eprof[NBIN], ey, eang;
  int st = euler_jets(eprof, &ey, &eang);
  if (st)
    return st;
  sbv_note(rep, "Dense crossing jets (Thomine 2008, §9) in the course "
           "exercise's geometry: square of side L = 1 mm, jets of width "
           "L/9 entering the west and south sides at their middles with "
           "U = 1 m/s, drops of radius 2 and 4 um (8:1 in number: equal "
           "volume), density 1000 kg/m^3, free flight; the engine's open "
           "boundaries: Poisson inflows, outflow through every face.  Warm-up 2 L/U, then %d "
           "run(s) of %d batches of L/(2U); the intervals are t intervals "
           "(95%%; the test: 99.99%%) over the batch means, which are "
           "nearly independent (a drop crosses a jet in L/(9U)).  Euler: "
           "lib/pgd, upwind, 45 x 45 cells, tau = 200, steady at "
           "t = 3 L/U: east exit at y = %.3f L, direction %.1f deg (one "
           "diagonal jet: the delta-shock).", R, NB, ey, eang);
  double data[NBIN * 8];
  for (int b = 0; b < NBIN; b++) {
    data[8 * b] = (b + 0.5) * 2.0 / NBIN;
    data[8 * b + 7] = eprof[b];
  }
  for (int ci = 0; ci < 3 && !st; ci++) {
    const dj_cfg *c = &DJ_CFGS[ci];
    double mix[NMAX], own[NMAX], back[NMAX], yE[NMAX], ang[NMAX];
    double col[NMAX], exc[NMAX], ratio[NMAX], bal = 0.0, fam0E = 1.0;
    double unacc = 0.0;
    double prof[2][NBIN] = {{0}}, mtot = 0.0, rej = 0.0, inj = 0.0;
    size_t n = 0;
    for (int k = 0; k < R && !st; k++) {
      sbv_progress(ctx, "  V15 dense jets %s run %d/%d", c->label, k + 1, R);
      dj_out *o = malloc(sizeof *o);
      if (!o || (st = run_dense(ctx, (unsigned long)(10 * ci + k), c, NB,
                                t_batch, o))) {
        free(o);
        st = st ? st : SB_ENOMEM;
        break;
      }
      for (int q = 0; q < o->nb && n < NMAX; q++, n++) {
        const dj_batch *bt = &o->b[q];
        double mE = bt->m_side[0][0] + bt->m_side[1][0], m0 = 0, m1 = 0;
        for (int sd = 0; sd < NSIDE; sd++)
          m0 += bt->m_side[0][sd], m1 += bt->m_side[1][sd];
        mix[n] = mE > 0 ? bt->m_side[0][0] / mE : NAN;
        own[n] = (bt->m_side[0][0] + bt->m_side[1][1]) / bt->m_out;
        back[n] = (bt->m_side[0][2] + bt->m_side[0][3] + bt->m_side[1][2] +
                   bt->m_side[1][3]) / bt->m_out;
        yE[n] = mE > 0 ? bt->my_east / mE / DJ_L : NAN;
        ang[n] = atan2(bt->q_east[1], bt->q_east[0]) * 180.0 / PI;
        col[n] = bt->inj > 0 ? 2.0 * (bt->coll1 - bt->coll0) / bt->inj : 0;
        double cross = bt->cross / bt->nsamp;
        double up = bt->up[0] / bt->nsamp + bt->up[1] / bt->nsamp;
        /* the jets are Poisson processes of known density: the crossing
         * square holds 2 m_expected on average (the upstream squares hold
         * the same drops a little earlier, so their difference has
         * anti-correlated batch means and is not used for the test) */
        exc[n] = cross / o->m_expected - 2.0;
        ratio[n] = 2.0 * cross / up;  /* crossing / one upstream jet */
        fam0E = fmin(fam0E, mix[n]);
        mtot += m0 + m1;
        /* drops of the batch: injected - left - the change inside */
        double b = fabs(bt->inj - bt->out - (bt->n1 - bt->n0));
        bal = b > bal ? b : bal;
      }
      /* the whole run, warm-up included (the note) */
      unacc = fmax(unacc, fabs(o->n_in - o->n_out - o->n_inside));
      for (int f = 0; f < 2; f++)
        for (int q = 0; q < NBIN; q++)
          prof[f][q] += o->prof[f][q];
      rej += o->rejected;
      inj += o->injected;
      free(o);
    }
    if (st)
      break;
    char name[160];
    snprintf(name, sizeof name, "V15/dense-jets/%s/drop-balance", c->label);
    st = sbv_add_band(rep, name, bal, 0.0, bal, bal);  /* exactly 0 */
    if (!c->collide) {
      snprintf(name, sizeof name, "V15/dense-jets/%s/west-jet-share-east",
               c->label);
      if (!st)
        st = sbv_add_band(rep, name, fam0E, 1.0, fam0E - 1e-12,
                          fam0E + 1e-12);
      snprintf(name, sizeof name, "V15/dense-jets/%s/crossing-excess",
               c->label);
      if (!st)
        st = sbv_add_mean(rep, name, exc, n, 0.0);
    }
    const struct {
      const char *what;
      const double *x;
      double ref;
    } rows[] = {
        {"crossing/one-jet", ratio, 2.0},
        {"east-exit-west-jet-share", mix, 0.5},
        {"own-side-share", own, 0.5},
        {"back-scattered-share", back, 0.0},
        {"east-exit-y/L", yE, ey},
        {"east-exit-angle-deg", ang, eang},
        {"collisions-per-drop", col, 0.0},
    };
    for (size_t q = 0; q < sizeof rows / sizeof rows[0] && !st; q++) {
      if (!c->collide && q == 6)
        continue;
      snprintf(name, sizeof name, "V15/dense-jets/%s/%s", c->label,
               rows[q].what);
      st = add_info_mean(rep, name, rows[q].x, n, rows[q].ref);
    }
    sbv_note(rep, "- %s: %.0f drops injected, %.0f arrivals skipped (no "
             "position free of overlap in 100 draws), %.0f drops "
             "unaccounted for over the run (warm-up included); the "
             "reference column of the informational "
             "rows is the pressureless answer (mixing 0.5 and own side 0.5 "
             "for one merged jet; the crossing holds twice one jet's mass).",
             c->label, inj, rej, unacc);
    for (int b = 0; b < NBIN; b++)
      for (int f = 0; f < 2; f++)
        data[8 * b + 1 + 2 * ci + f] =
            mtot > 0 ? prof[f][b] / mtot * NBIN / 2.0 : 0.0;
  }
  if (!st)
    st = sbv_plot(
        ctx, rep, "V15_dense_jets",
        "V15: exit mass profiles of the crossing jets, east side (0-1, "
        "bottom to top) then north side (1-2, east to west)",
        "s west0 south0 west1 south1 west2 south2 euler", data, NBIN, 8,
        "set xlabel 's (east side y/L, then north side 2 - x/L)'\n"
        "set ylabel 'exit mass density (normalised)'\nset key top left\n"
        "plot $DATA u 1:2 w steps t 'no collision, west jet', "
        "'' u 1:3 w steps t 'no collision, south jet', "
        "'' u 1:4 w steps t 'phi 0.02, west', '' u 1:5 w steps t 'phi "
        "0.02, south', '' u 1:6 w steps t 'phi 0.2, west', "
        "'' u 1:7 w steps t 'phi 0.2, south', "
        "'' u 1:8 w l lw 2 t 'Euler (pressureless)'");
  return st;
}

const sbv_case sbv_cases_pgd_dense[] = {
    {"V15/dense-jets",
     "dense crossing jets with collisions (Thomine 2008, §9): family "
     "mixing and exit profiles at three densities beside the pressureless "
     "Eulerian answer",
     case_dense},
};
const size_t sbv_ncases_pgd_dense =
    sizeof sbv_cases_pgd_dense / sizeof sbv_cases_pgd_dense[0];
