/* v12.h — shared parts of case V12 (private to lib/validate):
 * cases_v12.c (kernel versus dt and Kn_D, H(Kn_D)) and cases_v12b.c
 * (mixture, velocities at contact, DLVO sticking). */
#ifndef SB_VALIDATE_V12_H
#define SB_VALIDATE_V12_H

#include "cases.h"
#include "firsthit.h"

#define V12_D 1e-7         /* diameter, m */
#define V12_RHO 1000.0     /* particle density, kg/m^3 */
#define V12_TEMP 296.15    /* K */
#define V12_WARM 50.0      /* warm-up, tau_p */
#define V12_NMAX 60000.0   /* largest particle number of a run */
#define V12_PHIMAX 0.2     /* largest volume fraction (overlaps allowed) */
#define V12_BUDGET 6e8     /* largest particle-steps of a run */
/* --full: the runs of the verdict rows (the reference and `langevin`)
 * are sized for a ratio within +-1% (95%): V12_HITS_REF and V12_HITS_LV
 * contacts (1/60000 + 1/150000 -> +-0.95%), within these caps */
#define V12_HITS_REF 150000.0
#define V12_HITS_LV 60000.0
#define V12_BUDGET_FULL 1.2e10
#define V12_NMAX_FULL 2e6
/* largest expected candidate pairs per step of a run (cases_v12.c,
 * pairs_per_step, which leaves out the detector's reach: measured ~550
 * bytes each, 11 GB at the cap for `langevin` at Kn_D = 3, dt = 1000
 * tau_p) */
#define V12_PAIRS_MAX 2e7
/* --full: a verdict run that this cap holds below its contacts is
 * repeated on the next streams and pooled (cases_v12.c, v12_repeats), at
 * most this many times (streams 1200 + 10 k + r stay apart per Kn_D) */
#define V12_REPS_MAX 9

/* One monodisperse species at diffusive Knudsen number kn. */
typedef struct {
  double kn, d, m, tau, temp;
  double Kgh;  /* GH kernel, m^3/s */
  double D;    /* relative diffusivity 2 k_B T tau / m, m^2/s */
} v12_phys;

void v12_physics(double kn, v12_phys *p);
/* Dahneke's H in terms of GH's Kn_D (cases_v12.c). */
double v12_H_dahneke(double kn);
const char *v12_det_name(int det);

/* Size a first-hit run: warm-up end t1, end T (raised to 5 steps and a
 * step boundary), box and particle number for ~hits contacts. */
void v12_size(const v12_phys *ph, int det, double dtt, double hits,
              double t1, double T, size_t vcap, lv_run *q);
/* The same within a budget of particle-steps and a particle number of
 * one's own (v12_size: V12_BUDGET, V12_NMAX). */
void v12_size_cap(const v12_phys *ph, int det, double dtt, double hits,
                  double t1, double T, size_t vcap, double budget,
                  double nmax_particles, lv_run *q);
/* A first-hit run sized for ~hits counted contacts over meas tau_p after
 * the warm-up (cases_v12.c: box, particle number, end time). */
int v12_run(const sbv_ctx *ctx, unsigned long stream, const v12_phys *ph,
            int det, double dtt, double hits, double meas, size_t vcap,
            lv_run *q, lv_out *o);
/* v12_run with the caps of v12_size_cap and the engine threads of
 * lv_run.threads (0: the engine's default; 1 inside a parallel loop over
 * runs, whose CPU time is then its thread's). */
int v12_run_cap(const sbv_ctx *ctx, unsigned long stream,
                const v12_phys *ph, int det, double dtt, double hits,
                double meas, size_t vcap, double budget, double nmax,
                int threads, lv_run *q, lv_out *o);

/* Normal relative velocities at first contacts kept from the flat runs:
 * the reference (contact time, dt = 0.01 tau_p) and `langevin` at dt = 1
 * and 10 tau_p (NULL when not run). */
typedef struct {
  double kn;
  double *vref, *vl[2];
  size_t nref, nl[2];
} v12_vel;

/* cases_v12b.c */
int v12_mixture(const sbv_ctx *ctx, sbv_report *rep);
int v12_velocities(const sbv_ctx *ctx, sbv_report *rep, const v12_vel *vel,
                   int nvel);

#endif /* SB_VALIDATE_V12_H */
