/* cases_v12.c — V12: one collision detector for every dt/tau_p (Mohaupt
 * 2011, §7.2).  Brownian kernel of Langevin spheres in the transition
 * regime measured by first-hit counting (firsthit.h: independent uniform
 * pairs that pass through each other, first contact of every pair after a
 * warm-up of 50 tau_p, long-time kernel with the Smoluchowski transient of
 * the capacitance radius K/(4 pi D) removed) for every detector:
 *
 *  flat  K_e versus dt/tau_p at several Kn_D; reference: contact time of
 *        the chords at dt/tau_p = 0.01 (converged: the chord error falls
 *        like dt/tau_p), same protocol.  `langevin` rows test K_e/K_ref = 1
 *        (conditional two-sample test); the other detectors are reported;
 *  H     the long-time dimensionless kernel H = K m_red/(f_red R^3) of
 *        `langevin` over Kn_D = 0.01..10 against Gopalakrishnan & Hogan
 *        (2011), Dahneke (1983) and both limits (reported; the GH fit is
 *        the published reference, not an exact one).
 *
 * Physics: spheres of d = 100 nm, rho_p = 1000 kg/m^3, T = 296.15 K; the
 * relaxation time sets Kn_D = tau_p sqrt(2 k_B T/m)/d (the model takes
 * tau_p, m and T as independent: the Langevin parameters are what the
 * kernel depends on).  Mixtures and velocities at contact: cases_v12b.c.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <smolbridge/kernel.h>
#include <smolbridge/langevin.h>

#include "cases.h"
#include "firsthit.h"
#include "v12.h"

#define PI 3.14159265358979323846

void v12_physics(double kn, v12_phys *p)
{
  p->kn = kn;
  p->d = V12_D;
  p->temp = V12_TEMP;
  p->m = sb_sphere_mass(V12_RHO, p->d);
  p->tau = kn * p->d / sqrt(2.0 * SB_BOLTZMANN * p->temp / p->m);
  p->Kgh = sb_kernel_brownian_gh(0.5 * p->d, 0.5 * p->d, p->m, p->m, p->tau,
                                 p->tau, p->temp);
  p->D = 2.0 * SB_BOLTZMANN * p->temp * p->tau / p->m;
}

double v12_H_dahneke(double kn)
{
  /* Dahneke (1983): K/K_co = (1 + x)/(1 + 2x + 2x^2) with his Knudsen
   * number x = 2 D_ij/(c_ij R) = sqrt(pi/2) Kn_D (c_ij = sqrt(8 kT /
   * (pi m_red)), D_ij = kT/f_red); K_co = 4 pi D_ij R, i.e. H_co =
   * 4 pi Kn_D^2.  Its limit sqrt(8 pi) Kn_D is GH's. */
  double x = sqrt(0.5 * PI) * kn;
  return 4.0 * PI * kn * kn * (1.0 + x) / (1.0 + 2.0 * x + 2.0 * x * x);
}

/* Detector names for rows and notes. */
const char *v12_det_name(int det)
{
  static const char *const n[] = {"langevin", "contact-time", "overlap",
                                  "bessel3", "exact-bb3"};
  return det >= 0 && det <= LV_EXACT ? n[det] : "?";
}

/* Candidate pairs per step that a run's search holds at once, expected:
 * N^2/(2V) (4 pi/3) (d + 2 E|disp|)^3, E|disp| = 2 sqrt(2/pi) s with s
 * the per-axis sd of a step's displacement.  Memory goes with it: the
 * `langevin` run at Kn_D = 3, dt = 1000 tau_p (1e8 expected pairs)
 * needed more than 24 GB. */
static double pairs_per_step(const lv_run *q)
{
  const double s = sqrt(sb_langevin_var_x(
      q->tau[0], sqrt(2.0 * SB_BOLTZMANN * q->temp / (q->mass[0] * q->tau[0])),
      q->dt));
  const double c = q->d[0] + 4.0 * sqrt(2.0 / PI) * s;
  const double N = (double)q->N[0];
  return N * N / (2.0 * pow(q->L, 3)) * (4.0 * PI / 3.0) * c * c * c;
}

/* The estimator's exposure over (t1, T] at the GH kernel (firsthit.h):
 * (T - t1) + 2 a (sqrt T - sqrt t1) / sqrt(pi D), a = K_GH / (4 pi D). */
static double v12_teff(const v12_phys *ph, double t1, double T)
{
  const double a = ph->Kgh / (4.0 * PI * ph->D);
  return (T - t1) + 2.0 * a * (sqrt(T) - sqrt(t1)) / sqrt(PI * ph->D);
}

void v12_size(const v12_phys *ph, int det, double dtt, double hits,
              double t1, double T, size_t vcap, lv_run *q)
{
  v12_size_cap(ph, det, dtt, hits, t1, T, vcap, V12_BUDGET, V12_NMAX, q);
}

void v12_size_cap(const v12_phys *ph, int det, double dtt, double hits,
                  double t1, double T, size_t vcap, double budget,
                  double nmax_particles, lv_run *q)
{
  memset(q, 0, sizeof *q);
  const double tau = ph->tau, dt = dtt * tau;
  q->nsp = 1;
  q->d[0] = ph->d;
  q->tau[0] = tau;
  q->mass[0] = ph->m;
  q->temp = ph->temp;
  q->dt = dt;
  q->det = det;
  q->vcap = vcap;
  q->t1 = t1;
  /* the run ends at a step boundary, at least 5 steps in */
  if (T < 5.0 * dt)
    T = 5.0 * dt;
  T = dt * ceil(T / dt - 1e-9);
  q->T = T;
  /* box: 10 relative displacement sd over the run (the torus is infinite
   * space for every pair), 6 diameters, and twice the search cut-off */
  const double sd_rel = sqrt(2.0 * ph->D * T);
  const double sd_step = sqrt(2.0 * sb_langevin_var_x(
                                        tau, sqrt(2.0 * SB_BOLTZMANN *
                                                  ph->temp / (ph->m * tau)),
                                        dt));
  double L = 10.0 * sd_rel;
  if (L < 6.0 * ph->d)
    L = 6.0 * ph->d;
  if (L < 2.5 * (ph->d + 20.0 * sd_step))
    L = 2.5 * (ph->d + 20.0 * sd_step);
  q->L = L;
  /* particles for ~hits counted contacts, hits = N^2 K T_eff / (2 V),
   * in the smallest box allowed; denser than V12_PHIMAX (overlapping
   * particles cost neighbour-search work), the box grows at that density
   * instead; at most `budget` particle-steps (then fewer contacts: at
   * the capped density the box shrinks with N, hits ~ N).  T_eff is the
   * estimator's exposure (firsthit.h): the long-time part T - t1 and the
   * start-up transient 2 a (sqrt T - sqrt t1) / sqrt(pi D) of the
   * capacitance radius a = K / (4 pi D), which at small Kn_D is most of
   * the count (5x the long-time part at Kn_D = 0.01 over 350 tau_p) */
  const double vp = PI * pow(ph->d, 3) / 6.0, nmax = V12_PHIMAX / vp;
  const double KM = ph->Kgh * v12_teff(ph, q->t1, T);
  double N = sqrt(2.0 * hits * L * L * L / KM);
  int capped = 0;
  if (N > nmax * L * L * L) {
    capped = 1;
    const double V = 2.0 * hits / (nmax * nmax * KM);
    N = nmax * V;
    L = cbrt(V);
  }
  const double nb = fmin(budget / (T / dt), nmax_particles);
  if (N > nb) {
    N = nb;
    if (capped)
      L = fmax(cbrt(N / nmax), q->L);
  }
  if (N < 100.0)
    N = 100.0;
  q->L = L;
  q->N[0] = (size_t)N;
  /* at most V12_PAIRS_MAX candidate pairs per step (memory; pairs ~ N^2:
   * then fewer contacts) */
  const double P = pairs_per_step(q);
  if (P > V12_PAIRS_MAX && N * sqrt(V12_PAIRS_MAX / P) >= 100.0)
    q->N[0] = (size_t)(N * sqrt(V12_PAIRS_MAX / P));
}

int v12_run(const sbv_ctx *ctx, unsigned long stream, const v12_phys *ph,
            int det, double dtt, double hits, double meas, size_t vcap,
            lv_run *q, lv_out *o)
{
  return v12_run_cap(ctx, stream, ph, det, dtt, hits, meas, vcap,
                     V12_BUDGET, V12_NMAX, 0, q, o);
}

int v12_run_cap(const sbv_ctx *ctx, unsigned long stream,
                const v12_phys *ph, int det, double dtt, double hits,
                double meas, size_t vcap, double budget, double nmax,
                int threads, lv_run *q, lv_out *o)
{
  v12_size_cap(ph, det, dtt, hits, V12_WARM * ph->tau,
               (V12_WARM + meas) * ph->tau, vcap, budget, nmax, q);
  q->threads = threads;
  if (sbv_writing(ctx)) {
    char name[96];
    snprintf(name, sizeof name, "V12_Kn%g_dt%g_%s", ph->kn, dtt,
             v12_det_name(det));
    fh_set_name(ctx->ini_rep, name);
  }
  return lv_firsthit(ctx, stream, q, o);
}

/* ------------------------------------------------------------ flat */

typedef struct {
  int det;
  double dtt;
} v12_cell;

/* Write mode: the H row of the run just written (record
 * V12/H/Kn=KN/H_e/H_GH = K c / H_GH, c = tau_p / d^3) is that run's alone,
 * but is added after other records: its expect line now. */
static void h_expect(const sbv_ctx *ctx, sbv_report *rep, double kn,
                     double c)
{
  if (!sbv_writing(ctx))
    return;
  char name[96];
  snprintf(name, sizeof name, "V12/H/Kn=%g/H_e/H_GH", kn);
  sbv_ini_expect(rep, name, "first_hit.K", c / sb_kernel_gh_H(kn));
  sbv_ini_no_expect(rep);
}

/* Keep the velocities of a run for the velocity laws (cases_v12b.c). */
static void keep_vn(v12_vel *vel, int *nvel, double kn, int which,
                    lv_out *o)
{
  for (int k = 0; k < *nvel; k++)
    if (vel[k].kn == kn) {
      if (which < 0) {
        vel[k].vref = o->vn;
        vel[k].nref = o->nvn;
      } else {
        vel[k].vl[which] = o->vn;
        vel[k].nl[which] = o->nvn;
      }
      o->vn = NULL;
      return;
    }
}

/* One engine run of the flat sweep: its place in the sweep, its sizing
 * (v12_run_cap's arguments) and its outcome. */
typedef struct {
  int k, det;          /* Kn_D index, LV_* */
  double dtt, hits, meas, budget, nmax;
  size_t vcap;
  int pool;            /* 1: repeat the run until ~hits contacts where
                          the pair cap holds it below (v12_repeats) */
  int reps;            /* runs pooled into q, o */
  lv_run q;
  lv_out o;
  int st;
} v12_task;

/* Repeats of the sized run q for ~hits contacts, at most V12_REPS_MAX:
 * 1 unless the candidate-pair cap of v12_size_cap (memory) held q's
 * particles, hence its contacts (~N^2), below the aim; the particle-step
 * budget is not lifted this way.  The expected count is the sizing's
 * N^2 K_GH T_eff / (2 L^3); 5% short of the aim is accepted (57 000 of
 * 60 000 contacts still give +-0.97% against the reference). */
static int v12_repeats(const v12_phys *ph, const lv_run *q, double hits)
{
  if (pairs_per_step(q) < 0.99 * V12_PAIRS_MAX)
    return 1;
  const double N = (double)q->N[0];
  const double E =
      N * N * ph->Kgh * v12_teff(ph, q->t1, q->T) / (2.0 * q->L * q->L * q->L);
  const double r = ceil(0.95 * hits / E);
  return r < 1.0 ? 1 : r > V12_REPS_MAX ? V12_REPS_MAX : (int)r;
}

/* The runs of the flat sweep in row order: per Kn_D the reference (if
 * any), then every detector and dt/tau_p the mode asks for.  Returns the
 * count (at most 6 + 6 * 30). */
static size_t flat_tasks(int full, const double *kns, int nkn,
                         v12_task *tk)
{
  static const double dts[] = {0.01, 0.1, 1.0, 10.0, 100.0, 1000.0};
  /* --full: the verdict rows' runs (reference, `langevin`) for +-1% */
  const double hits = full ? 40000.0 : 250.0, meas = full ? 300.0 : 150.0;
  const double hits_ref = full ? V12_HITS_REF : hits;
  const double hits_lv = full ? V12_HITS_LV : hits;
  const double budget = full ? V12_BUDGET_FULL : V12_BUDGET;
  const double nmax = full ? V12_NMAX_FULL : V12_NMAX;
  const size_t vcap = full ? 20000 : 2000;
  size_t n = 0;
  for (int k = 0; k < nkn; k++) {
    if (full || fabs(kns[k] - 0.5) < 1e-9)
      tk[n++] = (v12_task){.k = k, .det = LV_CHORD, .dtt = 0.01,
                           .hits = hits_ref, .meas = meas, .budget = budget,
                           .nmax = nmax, .vcap = vcap, .pool = full};
    for (int det = LV_LANGEVIN; det <= LV_EXACT; det++)
      for (int t = 0; t < 6; t++) {
        const double dtt = dts[t];
        if (det == LV_CHORD && dtt == 0.01)
          continue;  /* the reference */
        const double dt2 = kns[k] > 1.0 ? 10.0 : 100.0;
        if (!full && (det == LV_LANGEVIN ? (dtt != 1.0 && dtt != dt2)
                                         : dtt != 1.0))
          continue;
        if (full && det != LV_LANGEVIN && det != LV_CHORD && dtt == 0.01)
          continue;
        const int keep = det == LV_LANGEVIN && (dtt == 1.0 || dtt == 10.0);
        const int lv = det == LV_LANGEVIN;
        tk[n++] = (v12_task){.k = k, .det = det, .dtt = dtt,
                             .hits = lv ? hits_lv : hits, .meas = meas,
                             .budget = lv ? budget : V12_BUDGET,
                             .nmax = lv ? nmax : V12_NMAX,
                             .vcap = keep ? vcap : 0, .pool = full && lv};
      }
  }
  return n;
}

/* Make run t (one engine thread and its own CPU clock when par). */
static void task_run(const sbv_ctx *ctx, const double *kns, v12_task *t,
                     int par)
{
  v12_phys ph;
  v12_physics(kns[t->k], &ph);
  if (t->det == LV_CHORD && t->dtt == 0.01)
    sbv_progress(ctx, "  V12 flat Kn_D=%g: reference", kns[t->k]);
  else
    sbv_progress(ctx, "  V12 flat Kn_D=%g %s dt/tau=%g", kns[t->k],
                 v12_det_name(t->det), t->dtt);
  const unsigned long stream = 1200 + 10 * (unsigned long)t->k;
  t->st = v12_run_cap(ctx, stream, &ph, t->det, t->dtt, t->hits, t->meas,
                      t->vcap, t->budget, t->nmax, par ? 1 : 0, &t->q,
                      &t->o);
  /* pooled repeats on the next streams (write mode: the first run's
   * file only) */
  t->reps = 1;
  const int reps = t->pool && !sbv_writing(ctx)
                       ? v12_repeats(&ph, &t->q, t->hits) : 1;
  for (int r = 1; r < reps && !t->st; r++) {
    sbv_progress(ctx, "  V12 flat Kn_D=%g %s dt/tau=%g: repeat %d of %d",
                 kns[t->k], v12_det_name(t->det), t->dtt, r + 1, reps);
    lv_run q;
    lv_out o;
    t->st = v12_run_cap(ctx, stream + (unsigned long)r, &ph, t->det, t->dtt,
                        t->hits, t->meas, t->vcap, t->budget, t->nmax,
                        par ? 1 : 0, &q, &o);
    if (!t->st)
      t->st = lv_pool(&t->o, &o, t->vcap);
    t->reps += !t->st;
  }
}

/* Runs of more expected candidate pairs per step than this go alone, one
 * after the other: at once, two of them could exhaust the memory. */
#define V12_PAIRS_ALONE 5e6

/* Entries {alone, particle-steps, run}: the runs alone first, then by
 * particle-steps, descending. */
static int by_cost(const void *a, const void *b)
{
  const double *x = a, *y = b;
  if (x[0] != y[0])
    return (x[0] < y[0]) - (x[0] > y[0]);
  return (x[1] < y[1]) - (x[1] > y[1]);
}

/* Make the runs before the rows.  Each is seeded from its own stream, so
 * their order and concurrency change nothing: the runs with many
 * candidate pairs per step go first, alone (on the engine's threads),
 * then the others at once on the OpenMP threads, one engine thread
 * each, the largest first.  (Write mode runs each in row order as its
 * rows are made: a file is named and paired with the record that
 * follows it.) */
static int flat_run(const sbv_ctx *ctx, const double *kns, v12_task *tk,
                    size_t n)
{
  double *order = malloc(3 * n * sizeof *order);
  if (!order)
    return SB_ENOMEM;
  size_t nalone = 0;
  for (size_t r = 0; r < n; r++) {  /* particle-steps of each run */
    v12_phys ph;
    v12_physics(kns[tk[r].k], &ph);
    lv_run q;
    v12_size_cap(&ph, tk[r].det, tk[r].dtt, tk[r].hits, V12_WARM * ph.tau,
                 (V12_WARM + tk[r].meas) * ph.tau, 0, tk[r].budget,
                 tk[r].nmax, &q);
    const int alone = pairs_per_step(&q) > V12_PAIRS_ALONE;
    nalone += alone;
    order[3 * r] = alone;
    order[3 * r + 1] = (double)q.N[0] * q.T / q.dt;
    order[3 * r + 2] = (double)r;
  }
  qsort(order, n, 3 * sizeof *order, by_cost);
  for (size_t m = 0; m < nalone; m++)
    task_run(ctx, kns, &tk[(size_t)order[3 * m + 2]], 0);
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 1)
#endif
  for (size_t m = nalone; m < n; m++)
    task_run(ctx, kns, &tk[(size_t)order[3 * m + 2]], 1);
  free(order);
  for (size_t r = 0; r < n; r++)
    if (tk[r].st)
      return tk[r].st;
  return SB_SUCCESS;
}

static int flat(const sbv_ctx *ctx, sbv_report *rep, double *Hrow,
                size_t *nH, v12_vel *vel, int *nvel)
{
  static const double kn_full[] = {0.01, 0.05, 0.2, 0.5, 1.0, 3.0};
  static const double kn_quick[] = {0.05, 0.5, 3.0};
  const int full = ctx->full;
  const double *kns = full ? kn_full : kn_quick;
  const int nkn = full ? 6 : 3;
  const double hits = full ? 40000.0 : 250.0, meas = full ? 300.0 : 150.0;
  *nvel = full ? 2 : 1;
  vel[0].kn = full ? 0.05 : 0.5;
  vel[1].kn = 0.5;
  sbv_note(rep, "Flat: first-hit counting (firsthit.h), warm-up %.0f "
           "tau_p, measured over %.0f tau_p (or 5 steps), box 10 relative "
           "displacement sd, ~%.0f contacts per run (--full: %.0f for "
           "`langevin`, %.0f for the reference, within %.2g particle-steps "
           "and %.0f particles per run); reference: contact "
           "time of the chords at dt/tau_p = 0.01 with the same protocol.  "
           "%s", V12_WARM, meas, hits, V12_HITS_LV, V12_HITS_REF,
           V12_BUDGET_FULL, V12_NMAX_FULL, full ? "" : "Quick mode: Kn_D = "
           "0.05, 0.5, 3; the reference at Kn_D = 0.5 only; `langevin` at "
           "dt/tau_p = 1 and 100 (1 and 10 at Kn_D = 3) is tested against "
           "the reference where it exists and against itself elsewhere; "
           "the other detectors at dt/tau_p = 1.");
  v12_task *tk = calloc(6 + 6 * 30, sizeof *tk);
  double *plot = malloc(nkn * 30 * 6 * sizeof *plot);
  if (!tk || !plot) {
    free(tk);
    free(plot);
    return SB_ENOMEM;
  }
  const size_t ntask = flat_tasks(full, kns, nkn, tk);
  const int writing = sbv_writing(ctx);
  int st = writing ? SB_SUCCESS : flat_run(ctx, kns, tk, ntask);
  size_t np = 0;
  *nH = 0;
  /* the rows, in order */
  size_t r = 0;
  for (int k = 0; k < nkn && !st; k++) {
    v12_phys ph;
    v12_physics(kns[k], &ph);
    lv_run qr, ql1 = {0};
    lv_out orf, ol1 = {0};
    memset(&qr, 0, sizeof qr);
    memset(&orf, 0, sizeof orf);
    const int have_ref = r < ntask && tk[r].k == k && tk[r].det == LV_CHORD &&
                         tk[r].dtt == 0.01;
    if (have_ref && writing && (task_run(ctx, kns, &tk[r], 0), tk[r].st))
      st = tk[r].st;
    if (have_ref && !st) {
      qr = tk[r].q;
      orf = tk[r].o;
      tk[r++].o.vn = NULL;
      keep_vn(vel, nvel, kns[k], -1, &orf);
      free(orf.vn);
      orf.vn = NULL;
    }
    double Kref = ph.Kgh, Kl, Kh;
    if (have_ref && !lv_kernel(&qr, &orf, 0, &Kref, &Kl, &Kh)) {
      sbv_note(rep, "- Kn_D = %g: tau_p = %.3g s, N = %zu, L = %.3g m, "
               "reference K/K_GH = %.4f [%.4f, %.4f] (%lu contacts, %.1f s)",
               kns[k], ph.tau, qr.N[0], qr.L, Kref / ph.Kgh, Kl / ph.Kgh,
               Kh / ph.Kgh, orf.hits[0], orf.cpu);
      double *row = plot + 6 * np++;
      row[0] = kns[k], row[1] = 0.01, row[2] = LV_CHORD, row[3] = 1.0;
      row[4] = Kl / Kref, row[5] = Kh / Kref;
    }
    for (; r < ntask && tk[r].k == k && !st; r++) {
      if (writing && (task_run(ctx, kns, &tk[r], 0), tk[r].st)) {
        st = tk[r].st;
        break;
      }
      const int det = tk[r].det;
      const double dtt = tk[r].dtt;
      lv_run q = tk[r].q;
      lv_out o = tk[r].o;
      char reps_note[64] = "";
      if (tk[r].reps > 1)
        snprintf(reps_note, sizeof reps_note, " (%d runs of N particles "
                 "pooled, streams apart)", tk[r].reps);
      tk[r].o.vn = NULL;
      const int keep = tk[r].vcap > 0;
      if (keep)
        keep_vn(vel, nvel, kns[k], dtt == 1.0 ? 0 : 1, &o);
      free(o.vn);
      o.vn = NULL;
      double K, lo, hi;
      lv_kernel(&q, &o, 0, &K, &lo, &hi);
      char name[96];
      snprintf(name, sizeof name, "V12/flat/Kn=%g/dt=%g/%s/K_e/K_ref",
               kns[k], dtt, v12_det_name(det));
      if (det == LV_LANGEVIN && have_ref)
        st = lv_add_compare(rep, name, &q, &o, &qr, &orf, 0);
      else if (det == LV_LANGEVIN && dtt == 1.0) {
        ql1 = q;  /* the self-consistency pair below */
        ol1 = o;
      } else if (det == LV_LANGEVIN) {
        snprintf(name, sizeof name, "V12/flat/Kn=%g/dt=%g/langevin/"
                 "K_e/K_e(dt=1)", kns[k], dtt);
        st = lv_add_compare(rep, name, &q, &o, &ql1, &ol1, 0);
      } else {
        if (have_ref)  /* K_ref from the reference run */
          sbv_ini_no_expect(rep);
        st = sbv_add_info(rep, name, K / Kref, 1.0, lo / Kref, hi / Kref,
                          0.95);
      }
      if (np < (size_t)nkn * 30) {
        double *row = plot + 6 * np++;
        row[0] = kns[k], row[1] = dtt, row[2] = det, row[3] = K / Kref;
        row[4] = lo / Kref, row[5] = hi / Kref;
      }
      if (det == LV_LANGEVIN && dtt == (full ? 10.0 : 1.0) &&
          *nH < 16) {  /* the long-time kernel H at this Kn_D */
        double *h = Hrow + 8 * (*nH)++;
        double c = ph.tau / pow(ph.d, 3);  /* H = K m_red/(f_red R^3) */
        h[0] = kns[k], h[1] = K * c, h[2] = lo * c, h[3] = hi * c;
        h_expect(ctx, rep, kns[k], c);
      }
      sbv_note(rep, "  - %s dt/tau_p = %g: K/K_ref = %.4f [%.4f, %.4f], "
               "%lu contacts, N = %zu, %.3g steps, %.2f candidates per "
               "particle and step, %.2f s%s", v12_det_name(det), dtt,
               K / Kref, lo / Kref, hi / Kref, o.hits[0], q.N[0], o.steps,
               o.ncand / (o.steps * (double)q.N[0]), o.cpu, reps_note);
    }
  }
  for (size_t t = 0; t < ntask; t++)
    free(tk[t].o.vn);
  free(tk);
  if (!st) {
    for (int k = 0; k < nkn; k++) {
      char nm[64], title[128];
      snprintf(nm, sizeof nm, "V12_flat_Kn%g", kns[k]);
      snprintf(title, sizeof title, "V12: K_e / K_ref versus dt/tau_p, "
               "Kn_D = %g (95%% intervals)", kns[k]);
      char body[1024];
      snprintf(body, sizeof body,
               "set logscale x\nset xrange [0.005:2000]\n"
               "set xlabel 'dt / tau_p'\n"
               "set ylabel 'K_e / K_ref (contact time, dt = 0.01 tau_p)'\n"
               "set key outside\n"
               "k = %g\n"
               "plot for [d=0:4] $DATA u ($1==k && $3==d ? $2 : 1/0):4:5:6 "
               "w yerrorlines t word('langevin contact-time overlap bessel3 "
               "exact-bb3', d+1), 1 lc rgb 'black' t ''", kns[k]);
      st = sbv_plot(ctx, rep, nm, title, "Kn_D dt/tau det K/Kref lo hi",
                    plot, np, 6, body);
      if (st)
        break;
    }
  }
  free(plot);
  return st;
}

/* ------------------------------------------------------------ H */

/* Long-time H(Kn_D) of `langevin` at dt = 10 tau_p (full; quick: from
 * the flat runs at dt = tau_p, plus the ends of the range) against GH,
 * Dahneke and the limits. */
static int hsweep(const sbv_ctx *ctx, sbv_report *rep, double *Hrow,
                  size_t nH)
{
  static const double kn_full[] = {0.01, 0.02, 0.1, 2.0, 5.0, 10.0};
  static const double kn_quick[] = {10.0};
  const int full = ctx->full;
  const double *kns = full ? kn_full : kn_quick;
  const int nkn = full ? 6 : 1;
  const double hits = full ? 20000.0 : 200.0, meas = full ? 300.0 : 150.0;
  int st = SB_SUCCESS;
  for (int k = 0; k < nkn && !st && nH < 16; k++) {
    v12_phys ph;
    v12_physics(kns[k], &ph);
    lv_run q;
    lv_out o;
    sbv_progress(ctx, "  V12 H Kn_D=%g", kns[k]);
    st = v12_run(ctx, 1300 + k, &ph, LV_LANGEVIN, full ? 10.0 : 1.0, hits,
                 meas, 0, &q, &o);
    if (st)
      break;
    double K, lo, hi;
    lv_kernel(&q, &o, 0, &K, &lo, &hi);
    double c = ph.tau / pow(ph.d, 3);  /* H = K m_red/(f_red R^3) */
    double *h = Hrow + 8 * nH++;
    h[0] = kns[k], h[1] = K * c, h[2] = lo * c, h[3] = hi * c;
    h_expect(ctx, rep, kns[k], c);
  }
  sbv_note(rep, "H(Kn_D): long-time kernel of `langevin` (dt = %s tau_p) "
           "against Gopalakrishnan & Hogan (2011), Dahneke (1983) and the "
           "limits 4 pi Kn^2, sqrt(8 pi) Kn (informational rows: GH is a "
           "fit).", full ? "10" : "1");
  for (size_t r = 0; r < nH && !st; r++) {
    double *h = Hrow + 8 * r;
    const double kn = h[0];
    h[4] = sb_kernel_gh_H(kn);
    h[5] = v12_H_dahneke(kn);
    h[6] = 4.0 * PI * kn * kn;
    h[7] = sqrt(8.0 * PI) * kn;
    char name[96];
    snprintf(name, sizeof name, "V12/H/Kn=%g/H_e/H_GH", kn);
    st = sbv_add_info(rep, name, h[1] / h[4], 1.0, h[2] / h[4], h[3] / h[4],
                      0.95);
    sbv_note(rep, "- Kn_D = %g: H_e = %.5g [%.5g, %.5g], H_e/H_GH = %.4f, "
             "H_Dahneke/H_GH = %.4f", kn, h[1], h[2], h[3], h[1] / h[4],
             h[5] / h[4]);
  }
  if (!st)
    st = sbv_plot(ctx, rep, "V12_H", "V12: long-time kernel H(Kn_D) of the "
                  "Langevin detector (95% intervals)",
                  "Kn H lo hi H_GH H_Dahneke H_co H_fm", Hrow, nH, 8,
                  "set logscale xy\nset xlabel 'Kn_D'\n"
                  "set ylabel 'H = K m_red / (f_red R^3)'\nset key left\n"
                  "plot $DATA u 1:2:3:4 w yerrorbars pt 7 t 'langevin', "
                  "$DATA u 1:5 w l t 'Gopalakrishnan & Hogan', "
                  "$DATA u 1:6 w l t 'Dahneke', $DATA u 1:7 w l dt 2 t "
                  "'continuum', $DATA u 1:8 w l dt 3 t 'free molecular'");
  return st;
}

static int case_v12(const sbv_ctx *ctx, sbv_report *rep)
{
  double Hrow[16 * 8];
  size_t nH = 0;
  v12_vel vel[2];
  int nvel = 0;
  memset(vel, 0, sizeof vel);
  int st = flat(ctx, rep, Hrow, &nH, vel, &nvel);
  if (!st)
    st = hsweep(ctx, rep, Hrow, nH);
  if (!st)
    st = v12_mixture(ctx, rep);
  if (!st)
    st = v12_velocities(ctx, rep, vel, nvel);
  for (int k = 0; k < 2; k++) {
    free(vel[k].vref);
    free(vel[k].vl[0]);
    free(vel[k].vl[1]);
  }
  return st;
}

const sbv_case sbv_cases_v12[] = {
    {"V12/langevin-detector",
     "Langevin-bridge detection at every dt/tau_p: kernel versus dt and "
     "Kn_D for every detector, H(Kn_D) vs Gopalakrishnan & Hogan, a "
     "20 + 200 nm mixture, velocities at contact and DLVO sticking "
     "(Mohaupt 2011, §7.2)",
     case_v12},
};
const size_t sbv_ncases_v12 = sizeof sbv_cases_v12 / sizeof sbv_cases_v12[0];
