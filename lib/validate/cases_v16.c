/* cases_v16.c — V16: the engine against the laminar-shear and
 * differential-settling kernels of lib/kernel (docs/engine_forces.md).
 *
 * Protocol of the kernel runs: non-Brownian spheres (B = 0) placed
 * uniformly and independently (overlaps allowed), each starting at its
 * equilibrium velocity (the fluid velocity at its position plus its
 * settling velocity), particles pass through each other (outcome count,
 * which skips pairs that overlap at the start of a step), contact-time
 * detection.  Relative paths are then straight lines (a tracer pair in a
 * linear shear keeps its y separation; settling velocities are constant)
 * and the pair density stays uniform, so the count of contacts is a
 * Poisson process of rate K P / V from t = 0, as long as no pair's
 * relative path crosses the periodic box more than once in the run (a
 * pair aligned with the relative velocity would meet again at every
 * crossing: the boxes are sized so that it does not): the kernel estimate
 * K_e = N_c V / int P dt has the exact Garwood interval, no warm-up and no
 * transient.  The references:
 *  - laminar shear, K = (4/3) G (r_i + r_j)^3 (Smoluchowski 1917),
 *    sb_kernel_shear; with the Lees-Edwards sliding boundaries;
 *  - differential settling, K = pi (r_i + r_j)^2 |v_i - v_j| with the
 *    Stokes settling velocities 2 (rho_p - rho_f) g r^2 / (9 mu)
 *    (sb_kernel_gravity, collision efficiency 1: every pair whose
 *    straight relative path meets the collision sphere collides; no
 *    hydrodynamic interaction), and with Schiller-Naumann drag the same
 *    geometric kernel with the terminal velocities of the nonlinear law.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>

#include <smolbridge/engine.h>
#include <smolbridge/kernel.h>

#include "cases.h"
#include "v16.h"

#define PI 3.14159265358979323846

/* ------------------------------------------------------------ runner */

int v16_run(const v16_setup *s, gsl_rng *r, v16_result *out)
{
  sb_engine_params p;
  sbv_engine_params(&p);
  p.dim = 3;
  memcpy(p.L, s->L, sizeof p.L);
  p.dt = s->dt;
  p.seed = s->seed;
  p.outcome = SB_OUTCOME_COUNT;
  p.detect = SB_DETECT_BALLISTIC;
  size_t ntot = 0;
  for (size_t a = 0; a < s->nsp; a++)
    ntot += s->sp[a].count;
  p.capacity = ntot + 1;
  memset(out, 0, sizeof *out);
  sb_engine *e = sb_engine_alloc(&p);
  if (!e)
    return SB_ENOMEM;
  /* the collisions tallied for the counts' variance (the kernel rows) */
  int st = sb_engine_set_count_variance(e, 1);
  if (!st && s->G != 0.0) {
    double G[3] = {s->G, 0, 0};
    st = sb_engine_set_fluid(e, SB_FLUID_SHEAR, G);
    if (!st && s->lees)
      st = sb_engine_set_lees_edwards(e, 1);
  }
  if (!st)
    st = sb_engine_set_gravity(e, s->g);
  for (size_t a = 0; a < s->nsp && !st; a++) {
    const v16_species *q = &s->sp[a];
    double m = q->rho_p * 4.0 / 3.0 * PI * q->r * q->r * q->r;
    sb_engine_species sp = {q->r, m, q->tau, q->B, 0.0};
    st = sb_engine_add_species(e, &sp, NULL);
    if (!st) {
      sb_engine_species_fluid fl = {q->drag, q->rho_f, q->mu};
      st = sb_engine_set_species_fluid(e, a, &fl);
    }
  }
  for (size_t a = 0; a < s->nsp && !st; a++) {
    const v16_species *q = &s->sp[a];
    double vs[3];
    st = sb_engine_settling_velocity(e, a, vs);
    if (a < 4)
      memcpy(out->vset[a], vs, sizeof vs);
    /* as smolbridge collide's placement = uniform: x and u drawn per
     * component in turn, u = N(0, sd) + U_s(x) + settling velocity */
    const double sd = sqrt(q->B * q->B * q->tau / 2.0);
    for (size_t k = 0; k < q->count && !st; k++) {
      double x[3], u[3];
      for (int c = 0; c < 3; c++) {
        double lo = 0.0, w = s->L[c];
        if (s->walls[c]) {  /* between the contact planes, rounded as
                               collide's placement */
          lo = q->r;
          w = (s->L[c] - q->r) - lo;
        }
        /* density y (W - y) across walls: Beta(2, 2), as collide's
         * [species] profile = parabolic */
        x[c] = lo + w * (s->walls[c] && s->parabolic
                             ? gsl_ran_beta(r, 2.0, 2.0)
                             : gsl_rng_uniform(r));
        u[c] = gsl_ran_gaussian_ziggurat(r, sd);
      }
      const double us[3] = {s->G * (x[1] - 0.5 * s->L[1]), 0.0, 0.0};
      for (int c = 0; c < 3; c++)
        u[c] += us[c] + vs[c];
      st = sb_engine_add_particle(e, a, 0, x, u);
    }
  }
  for (int c = 0; c < 3 && !st; c++)
    if (s->walls[c])
      st = sb_engine_set_walls(e, c, s->walls[c], s->walls[c]);
  if (!st)
    st = sb_engine_set_wall_mode(e, s->walldet, s->deposit);
  if (!st && s->nodetect)
    st = sb_engine_set_detector(e, sb_engine_detect_none, NULL, 0.0);
  if (!st && s->warmup > 0) {
    for (size_t k = 0; k < s->warmup && !st; k++)
      st = sb_engine_step(e);
    sb_engine_reset_counters(e);
  }
  /* steps, with the cumulative deposits at the requested checkpoints */
  size_t next = 0;
  for (size_t k = 1; k <= s->steps && !st; k++) {
    st = sb_engine_step(e);
    while (!st && next < s->nmark && s->mark[next] == k) {
      uint64_t d = 0;
      for (int f = 0; f < 6; f++)
        d += sb_engine_deposits(e, f);
      out->dep[next++] = d;
    }
  }
  if (!st) {
    for (size_t a = 0; a < s->nsp && a < 4; a++)
      for (size_t b = a; b < s->nsp && b < 4; b++) {
        st = sb_engine_pair_kernel(e, a, b, 0.95, &out->pk[a][b]);
        if (st)
          break;
      }
    for (int f = 0; f < 6; f++)
      out->ndep += sb_engine_deposits(e, f);
    out->t = sb_engine_time(e);
    out->n_end = sb_engine_count(e);
    /* mean velocity of species 0 (settling check) */
    const double *u = sb_engine_velocities(e);
    const size_t *spc = sb_engine_species_of(e);
    size_t c0 = 0;
    for (size_t i = 0; i < sb_engine_count(e); i++)
      if (spc[i] == 0) {
        for (int c = 0; c < 3; c++)
          out->umean[c] += u[3 * i + c];
        c0++;
      }
    for (int c = 0; c < 3; c++)
      out->umean[c] /= c0 ? (double)c0 : 1.0;
  }
  sb_engine_free(e);
  return st;
}


/* Box for n particles of radius r at volume fraction phi, elongated
 * along `ax` by `stretch`. */
static void box_for(double phi, size_t n, double r, int ax, double stretch,
                    double L[3])
{
  double V = (double)n * 4.0 / 3.0 * PI * r * r * r / phi;
  double l = cbrt(V / stretch);
  L[0] = L[1] = L[2] = l;
  L[ax] = l * stretch;
}

/* ====================================================== V16/shear */

void v16_ini_run(FILE *f, unsigned long seed, const double L[3], double dt,
                 size_t steps, unsigned long placement_seed)
{
  v16_ini_run_detect(f, seed, L, dt, steps, placement_seed, "ballistic");
}

void v16_ini_run_detect(FILE *f, unsigned long seed, const double L[3],
                        double dt, size_t steps,
                        unsigned long placement_seed, const char *detect)
{
  fprintf(f, "seed = %lu\nrng = mt19937\nLx = %.17g\nLy = %.17g\n"
          "Lz = %.17g\n"
          "dt = %.17g\nsteps = %zu\ndetect = %s\noutcome = count\n"
          "placement = uniform\nplacement_seed = %lu\n", seed, L[0], L[1],
          L[2], dt, steps, detect, placement_seed);
}

/* Write mode: a v16_run without walls as a collide configuration (the
 * placement drawn from stream `stream` as v16_run draws it: a collide
 * file's placement_seed); out gets unit values (pk.K = 1 from one
 * collision) so that a record's estimate is its factor.  One species: the
 * next record's field is kernel.K; several: the caller writes the expect
 * lines of pair_kernels[a,b].K (species a, b, ...). */
static int write_v16(const sbv_ctx *ctx, sbv_report *rep,
                     const v16_setup *s, unsigned long stream,
                     const char *name, const char *what, v16_result *out)
{
  memset(out, 0, sizeof *out);
  for (int a = 0; a < 4; a++)
    for (int b = 0; b < 4; b++)
      out->pk[a][b].ncoll = 1, out->pk[a][b].K = 1.0;
  FILE *f = sbv_ini_begin(ctx, rep, name, what);
  if (!f)
    return SB_EIO;
  v16_ini_run(f, s->seed, s->L, s->dt, s->steps, sbv_rng_seed(ctx, stream));
  fprintf(f, "\n[fluid]\n");
  if (s->G != 0.0)
    fprintf(f, "type = shear\nG = %.17g\nlees_edwards = %s\n", s->G,
            s->lees ? "yes" : "no");
  const int grav = s->g[0] != 0.0 || s->g[1] != 0.0 || s->g[2] != 0.0;
  if (grav)
    fprintf(f, "g = %.17g %.17g %.17g\n", s->g[0], s->g[1], s->g[2]);
  /* one fluid for all species (the cases' species share it); none for
   * the linear drag of given tau_p; its density where the buoyancy or a
   * nonlinear drag uses it, its viscosity where a nonlinear drag does
   * (collide warns about the others) */
  int nonlin = 0;
  for (size_t a = 0; a < s->nsp; a++)
    nonlin |= s->sp[a].drag == SB_DRAG_SCHILLER_NAUMANN;
  if (s->sp[0].mu > 0.0 && (grav || nonlin))
    fprintf(f, "rho = %.17g\n", s->sp[0].rho_f);
  if (s->sp[0].mu > 0.0 && nonlin)
    fprintf(f, "mu = %.17g\n", s->sp[0].mu);
  for (size_t a = 0; a < s->nsp; a++) {
    const v16_species *q = &s->sp[a];
    double m = q->rho_p * 4.0 / 3.0 * PI * q->r * q->r * q->r;
    fprintf(f, "\n[species %c]\nradius = %.17g\nmass = %.17g\n"
            "tau = %.17g\nB = %.17g\ndrag = %s\ncount = %zu\n",
            (char)('a' + a), q->r, m, q->tau, q->B,
            q->drag == SB_DRAG_SCHILLER_NAUMANN ? "schiller-naumann"
                                                : "stokes",
            q->count);
  }
  return sbv_ini_end(rep, f, s->nsp == 1 ? "kernel.K" : NULL);
}

/* One run of a case: written (write mode) or run, its placement from
 * its own stream. */
static int run_or_write(const sbv_ctx *ctx, sbv_report *rep,
                        const v16_setup *s, unsigned long stream,
                        const char *name, const char *what,
                        v16_result *out)
{
  if (sbv_writing(ctx))
    return write_v16(ctx, rep, s, stream, name, what, out);
  gsl_rng *r = sbv_rng_alloc(ctx, stream);
  int st = r ? v16_run(s, r, out) : SB_ENOMEM;
  gsl_rng_free(r);
  return st;
}

static int case_shear(const sbv_ctx *ctx, sbv_report *rep)
{
  int st = SB_SUCCESS;
  const double target = ctx->full ? 40000.0 : 2500.0;
  const double tau = 1e-7;  /* 10 um spheres: tracers at G tau << 1 */
  sbv_note(rep, "Non-Brownian spheres (tau_p = 1e-7 s, B = 0) in the "
           "shear U_x = G (y - L_y/2) with Lees-Edwards boundaries, "
           "uniform independent placement, volume fraction 5e-2 "
           "(monodisperse; 1e-2 for the plain periodic box), outcome count, contact-time detection.  "
           "Target %.0f contacts per row; exact Poisson test at 1e-4 "
           "against K = (4/3) G (r_i + r_j)^3 (Smoluchowski 1917).",
           target);
  /* runs: 0: G = 100, 1: G = 10, 2: bidisperse G = 100, 3: G = 100
   * without Lees-Edwards (the velocity jump G L_y across the y
   * boundary: expected excess) */
  for (int run = 0; run < 4 && !st; run++) {
    v16_setup s;
    memset(&s, 0, sizeof s);
    s.G = run == 1 ? 10.0 : 100.0;
    s.lees = run != 3;
    s.nsp = run == 2 ? 2 : 1;
    s.sp[0] = (v16_species){5e-6, 1000.0, tau, 0.0, 0, SB_DRAG_STOKES, 0.0,
                            0.0};
    s.sp[1] = (v16_species){2.5e-6, 1000.0, tau, 0.0, 0, SB_DRAG_STOKES,
                            0.0, 0.0};
    /* phi = 0.05 (pairs are independent with pass-through particles,
     * so the kernel does not depend on it; a denser box needs fewer
     * particle-steps), flattened along y (L_y = 0.4 of the cube's
     * edge: ~4% of the contacts are across the sliding boundary, whose
     * search test_engine_physics checks pair by pair);
     * the plain periodic box at 1e-2, cubic */
    const size_t n0 = ctx->full ? 8000 : 2000;
    s.sp[0].count = n0;
    s.sp[1].count = run == 2 ? 2 * n0 : 0;
    box_for(run == 3 ? 1e-2 : 5e-2, n0, 5e-6, 1, run == 3 ? 1.0 : 0.4,
            s.L);
    double V = s.L[0] * s.L[1] * s.L[2];
    /* steps: largest relative displacement per step 4 radii */
    s.dt = 4.0 * 5e-6 / (s.G * s.L[1]);
    double Kth = sb_kernel_shear(5e-6, run == 2 ? 2.5e-6 : 5e-6, s.G);
    double P = run == 2 ? (double)n0 * (double)(2 * n0)
                        : 0.5 * (double)n0 * (double)(n0 - 1);
    double want = run == 3 ? 400.0 : target;
    double t = want / (Kth * P / V);
    s.steps = (size_t)ceil(t / s.dt);
    s.seed = ctx->seed * 1000 + 1600 + (unsigned long)run;
    v16_result res;
    /* the placement of each run from its own stream (a collide file's
     * placement_seed) */
    const unsigned long stream = 16010 + (unsigned long)run;
    static const char *const fn[4] = {"V16_shear_G100", "V16_shear_G10",
                                      "V16_shear_bidisperse_G100",
                                      "V16_shear_no_lees_edwards"};
    st = run_or_write(ctx, rep, &s, stream, fn[run],
                      "V16: spheres in laminar shear", &res);
    if (st)
      break;
    char name[128];
    if (run < 2) {
      snprintf(name, sizeof name, "V16/shear/G=%.0f/d=10um/K_e/K_th", s.G);
      st = sbv_add_pair_kernel(rep, name, &res.pk[0][0], Kth, 0,
                               "collisions");
    } else if (run == 2) {
      if (sbv_writing(ctx)) {
        sbv_ini_expect(rep, "V16/shear/bidisperse/G=100/10um-5um/K_e/K_th",
                       "pair_kernels[a,b].K", 1.0 / Kth);
        sbv_ini_expect(rep, "V16/shear/bidisperse/G=100/10um-10um/K_e/K_th",
                       "pair_kernels[a,a].K",
                       1.0 / sb_kernel_shear(5e-6, 5e-6, s.G));
        sbv_ini_expect(rep, "V16/shear/bidisperse/G=100/5um-5um/K_e/K_th",
                       "pair_kernels[b,b].K",
                       1.0 / sb_kernel_shear(2.5e-6, 2.5e-6, s.G));
      }
      st = sbv_add_pair_kernel(
          rep, "V16/shear/bidisperse/G=100/10um-5um/K_e/K_th",
          &res.pk[0][1], Kth, 0, "collisions");
      if (!st)
        st = sbv_add_pair_kernel(
            rep, "V16/shear/bidisperse/G=100/10um-10um/K_e/K_th",
            &res.pk[0][0], sb_kernel_shear(5e-6, 5e-6, s.G), 0,
            "collisions");
      if (!st)
        st = sbv_add_pair_kernel(
            rep, "V16/shear/bidisperse/G=100/5um-5um/K_e/K_th",
            &res.pk[1][1], sb_kernel_shear(2.5e-6, 2.5e-6, s.G), 0,
            "collisions");
    } else {
      const sb_engine_pair_stats *ps = &res.pk[0][0];
      double lo = 0.0, hi = 0.0;
      double sc = ps->ncoll ? ps->K / (double)ps->ncoll / Kth : 1.0;
      sb_poisson_rate_ci((unsigned long)ps->ncoll, sc, 1.0 - SBV_ALPHA, &lo,
                         &hi);
      st = sbv_add_side(rep, "V16/shear/periodic-no-lees-edwards/K_e/K_th>1",
                        1, ps->K / Kth, 1.0, lo, hi, 1.0 - SBV_ALPHA, NAN);
      sbv_note(rep, "- without Lees-Edwards images (plain periodic box): "
               "K_e/K_th = %.3f (%llu contacts): pairs across the y "
               "boundary meet with the velocity jump G L_y",
               ps->K / Kth, (unsigned long long)ps->ncoll);
    }
    sbv_progress(ctx, "  V16 shear run %d: %zu steps", run, s.steps);
  }
  return st;
}

/* ===================================================== V16/settling */

static int case_settling(const sbv_ctx *ctx, sbv_report *rep)
{
  const double target = ctx->full ? 40000.0 : 2500.0;
  const double grav = 9.81;
  int st = SB_SUCCESS;
  sbv_note(rep, "Bidisperse non-Brownian spheres under gravity g = %.2f "
           "m/s^2 (-y), uniform independent placement at their settling "
           "velocities, outcome count, contact-time detection; exact "
           "Poisson test at 1e-4 of the cross-species kernel against "
           "pi (r_i + r_j)^2 |v_i - v_j| (efficiency 1, as "
           "sb_kernel_gravity).  Target %.0f contacts.", grav, target);
  /* run 0: Stokes, glass-like spheres in water (rho_p = 2500, rho_f =
   * 1000, mu = 1e-3), d = 20 and 10 um; run 1: Schiller-Naumann, water
   * drops in air (rho_p = 1000, rho_f = 1.2, mu = 1.8e-5), d = 100 and
   * 60 um (Re_p ~ 2 and 0.5) */
  for (int run = 0; run < 2 && !st; run++) {
    v16_setup s;
    memset(&s, 0, sizeof s);
    const int sn = run == 1;
    const double rho_p = sn ? 1000.0 : 2500.0, rho_f = sn ? 1.2 : 1000.0,
                 mu = sn ? 1.8e-5 : 1e-3;
    const double r1 = sn ? 50e-6 : 10e-6, r2 = sn ? 30e-6 : 5e-6;
    const double tau1 = rho_p * 4 * r1 * r1 / (18 * mu),
                 tau2 = rho_p * 4 * r2 * r2 / (18 * mu);
    const sb_engine_drag law = sn ? SB_DRAG_SCHILLER_NAUMANN
                                  : SB_DRAG_STOKES;
    s.nsp = 2;
    s.sp[0] = (v16_species){r1, rho_p, tau1, 0.0, 0, law, rho_f, mu};
    s.sp[1] = (v16_species){r2, rho_p, tau2, 0.0, 0, law, rho_f, mu};
    const size_t n1 = ctx->full ? 6000 : 2000;
    s.sp[0].count = n1;
    s.sp[1].count = n1;
    s.g[1] = -grav;
    /* tall along g: each pair's relative path crosses the periodic box
     * less than once in the run (in a cube it would cross ~1.2 times,
     * and a pair aligned in x, z then meets again: more variance than
     * Poisson) */
    box_for(5e-3, n1, r1, 1, 4.0, s.L);
    const double V = s.L[0] * s.L[1] * s.L[2];
    /* reference velocities */
    double v1, v2;
    if (!sn) {
      v1 = 2.0 * (rho_p - rho_f) * grav * r1 * r1 / (9.0 * mu);
      v2 = 2.0 * (rho_p - rho_f) * grav * r2 * r2 / (9.0 * mu);
    } else {
      v1 = v16_terminal_sn(r1, rho_p, rho_f, mu, grav);
      v2 = v16_terminal_sn(r2, rho_p, rho_f, mu, grav);
    }
    const double dv = fabs(v1 - v2);
    const double Kth = sn ? PI * (r1 + r2) * (r1 + r2) * dv
                          : sb_kernel_gravity(r1, r2, rho_p, rho_f, mu, grav);
    s.dt = 0.5 * r1 / (fabs(v1) + fabs(v2));
    double P = (double)n1 * (double)n1;
    double t = target / (Kth * P / V);
    s.steps = (size_t)ceil(t / s.dt);
    s.seed = ctx->seed * 1000 + 1610 + (unsigned long)run;
    v16_result res;
    st = run_or_write(ctx, rep, &s, 16020 + (unsigned long)run,
                      sn ? "V16_settling_schiller_naumann"
                         : "V16_settling_stokes",
                      "V16: bidisperse spheres settling", &res);
    if (st)
      break;
    char name[128];
    snprintf(name, sizeof name, "V16/settling/%s/d=%.0fum-%.0fum/K_e/K_th",
             sn ? "schiller-naumann" : "stokes", 2e6 * r1, 2e6 * r2);
    /* write mode: the velocity records below are not summary fields */
    if (sbv_writing(ctx))
      sbv_ini_expect(rep, name, "pair_kernels[a,b].K", 1.0 / Kth);
    st = sbv_add_pair_kernel(rep, name, &res.pk[0][1], Kth, 0,
                             "collisions");
    /* the engine's settling velocity (from its root finder or tau g')
     * against the independent reference, and the mean velocity of the
     * species at the end of the run (it must stay there) */
    if (!st) {
      snprintf(name, sizeof name, "V16/settling/%s/d=%.0fum/v_s",
               sn ? "schiller-naumann" : "stokes", 2e6 * r1);
      st = sbv_add_relband(rep, name, -res.vset[0][1], v1, 1e-10);
    }
    if (!st) {
      snprintf(name, sizeof name, "V16/settling/%s/d=%.0fum/mean-u_y-end",
               sn ? "schiller-naumann" : "stokes", 2e6 * r1);
      st = sbv_add_relband(rep, name, -res.umean[1], v1, 1e-9);
    }
    sbv_note(rep, "- %s: v_s = %.5g and %.5g m/s (Re_p = %.3g, %.3g), %zu "
             "steps of %.3g s", sn ? "Schiller-Naumann" : "Stokes", v1, v2,
             rho_f * v1 * 2 * r1 / mu, rho_f * v2 * 2 * r2 / mu, s.steps,
             s.dt);
    sbv_progress(ctx, "  V16 settling run %d: %zu steps", run, s.steps);
  }
  return st;
}

/* Terminal speed with Schiller-Naumann drag: v f(Re(v)) = v_Stokes,
 * solved by bisection (independent of the engine's Brent solver). */
double v16_terminal_sn(double r, double rho_p, double rho_f, double mu,
                       double g)
{
  const double vst = 2.0 * (rho_p - rho_f) * g * r * r / (9.0 * mu);
  double lo = 0.0, hi = vst;
  for (int it = 0; it < 200; it++) {
    double m = 0.5 * (lo + hi);
    double Re = rho_f * m * 2.0 * r / mu;
    double f = Re <= 1000.0 ? 1.0 + 0.15 * pow(Re, 0.687) : 0.44 * Re / 24.0;
    if (m * f < vst)
      lo = m;
    else
      hi = m;
  }
  return 0.5 * (lo + hi);
}

const sbv_case sbv_cases_v16[] = {
    {"V16/shear",
     "laminar shear with Lees-Edwards boundaries: K = (4/3) G (r_i + "
     "r_j)^3 for two shear rates and a bidisperse pair (Smoluchowski "
     "1917; Lees & Edwards 1972)",
     case_shear},
    {"V16/settling",
     "differential settling, K = pi (r_i + r_j)^2 |v_i - v_j|, Stokes and "
     "Schiller-Naumann drag (Smoluchowski 1917; Schiller & Naumann 1933)",
     case_settling},
    {"V16/deposition",
     "deposition on absorbing walls: transient flux n sqrt(D/(pi t)) and "
     "the steady flux with a volume source, Brownian-bridge wall contact "
     "(Mohaupt 2011, §5.1)",
     v16_case_deposition},
};
const size_t sbv_ncases_v16 = sizeof sbv_cases_v16 / sizeof sbv_cases_v16[0];

int v16_shear_fill(sb_engine *e, gsl_rng *r, const sb_engine_species *sp,
                   size_t n, const double L[3], double G)
{
  const double Gv[3] = {G, 0.0, 0.0};
  int st = sb_engine_add_species(e, sp, NULL);
  if (!st)
    st = sb_engine_set_fluid(e, SB_FLUID_SHEAR, Gv);
  if (!st)
    st = sb_engine_set_lees_edwards(e, 1);
  const double usd = sqrt(sp->B * sp->B * sp->tau / 2.0);
  for (size_t i = 0; i < n && !st; i++) {
    double x[3], u[3];
    for (int c = 0; c < 3; c++) {
      x[c] = L[c] * gsl_rng_uniform(r);
      u[c] = gsl_ran_gaussian_ziggurat(r, usd);
    }
    u[0] += G * (x[1] - 0.5 * L[1]);
    st = sb_engine_add_particle(e, 0, 0, x, u);
  }
  return st;
}
