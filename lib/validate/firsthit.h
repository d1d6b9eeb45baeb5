/* firsthit.h — kernel measurement by first-hit counting (private to
 * lib/validate).
 *
 * Particles pass through each other and the first detected contact of
 * every pair is counted (the observer of <smolbridge/engine_firsthit.h>,
 * which also holds the estimator below): the pairs are then
 * independent two-body problems, whatever the volume fraction, and the
 * expected number of first contacts from a uniform start is exactly the
 * Smoluchowski absorbing-sphere flux integrated over time,
 *   E[hits in (t1, T]] = P / (V - v_a) * K * [ (T - t1)
 *                        + 2 a (sqrt(T) - sqrt(t1)) / sqrt(pi D) ],
 * P the pairs apart at the start, V the box volume, v_a the contact ball,
 * D = B_ij^2/2 the relative diffusivity, a the contact distance and K =
 * 4 pi D a (Smoluchowski 1917; the relative displacement stays far below
 * the box, so the torus is infinite space for every pair).  Positions are
 * independent and uniform (overlaps allowed) so that every counted pair
 * starts uniform outside the contact ball; a non-overlapping filling would
 * carry the hard-sphere pair correlation g(a) ~ 1 + 2.5 phi into the
 * transient.
 *
 * Langevin particles (finite tau_p): the motion is ballistic below tau_p,
 * and an absorbing sphere seen by a Langevin particle acts, for the outer
 * diffusion field, as a sphere of radius a - l with the Milne extrapolation
 * length of the Klein-Kramers equation l = |zeta(1/2)| sqrt(k_B T / m_red)
 * tau_p (Burschka & Titulaer 1981; Marshall & Watson 1985), up to O(l^2/a)
 * and to corrections that decay once the pairs are older than a few
 * tau_p.  fh_run.a_eff carries that radius; a warm-up t1 of many tau_p
 * (hits before t1 are recorded in the set but not counted) leaves out the
 * kinetic start-up, whose count offset the diffusion form does not hold.
 */
#ifndef SB_VALIDATE_FIRSTHIT_H
#define SB_VALIDATE_FIRSTHIT_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <smolbridge/engine.h>
#include <smolbridge/engine_bridge.h>
#include "cases.h"

/* Detectors the first-hit wrapper can call. */
enum {
  FH_BRIDGE = 0,   /* sb_engine_detect_bridge (Bessel-3 or exact mode) */
  FH_CHORD = 1,    /* contact time of the displacement chords */
  FH_OVERLAP = 2,  /* overlap at step end */
  FH_MD = 3        /* contact time of x + u dt (velocities at step start:
                      Mohaupt 2011, §3.2, App. F) */
};

typedef struct {
  double d;        /* diameter = contact distance a, m */
  double a_eff;    /* radius of the absorbing sphere in the reference
                      (0: d; Langevin: d - l, see the file comment), m */
  double tau;      /* relaxation time, s */
  double b2;       /* per-particle position variance rate B_pos^2, m^2/s;
                      the relative diffusivity is D = b2 */
  double b2brown;  /* its Brownian part (collision split) */
  double mass;     /* kg */
  double vsd;      /* velocity standard deviation per component, m/s
                      (0: the equilibrium value sqrt(b2 / (2 tau))) */
  double dt;       /* s */
  double L;        /* box edge, m */
  size_t N;
  double T;        /* simulated time, s */
  double t1;       /* warm-up: first hits before t1 are not counted, s */
  double eps, nu;  /* turbulence behind b2 - b2brown (V7), else 0; for
                      the configuration written in write mode */
  int builtin;     /* FH_* */
  sb_bridge_mode mode;
  sb_bridge_ends ends;
} fh_run;

typedef struct {
  unsigned long hits;   /* first contacts counted in (t1, T] */
  double expected_per_K;/* E[hits] / K: hits = K expected_per_K on
                           average, s/m^3 */
  double K;             /* kernel estimate hits / expected_per_K, m^3/s */
  double dispersion;    /* var(hits) / hits estimated from each particle's
                           contacts (the observer's hits_var; > 1: pairs
                           sharing a particle correlated), NaN if unknown */
  double lo, hi;        /* its 95% interval: the Garwood interval of the
                           count, widened by sqrt(dispersion) above 1 */
  double cpu;           /* s */
  double steps;
} fh_out;

/* Defaults: builtin FH_BRIDGE, Bessel mode, position ends, no warm-up. */
void fh_run_init(fh_run *q);

/* One run (engine seeded from `stream`).  Write mode (sbv_writing): the
 * run is written as a collide configuration instead (`name` its file),
 * and o gets unit values (one hit, K = 1). */
int run_firsthit(const sbv_ctx *ctx, unsigned long stream, const fh_run *q,
                 fh_out *o);
/* Write-mode file name of the next run_firsthit call (rep: the report the
 * case writes to). */
void fh_set_name(sbv_report *rep, const char *name);

/* Write mode: open the collide file `name` of a first-hit run (engine
 * parameters p, box edge L, end T, warm-up t1, collide detector name) and
 * write its [run] keys, the placement drawn from stream 100000 + stream
 * as the run draws it; the caller adds the rest and calls sbv_ini_end.
 * NULL on error. */
FILE *fh_ini_open(const sbv_ctx *ctx, unsigned long stream,
                  const sb_engine_params *p, double L, double T, double t1,
                  const char *detect, const char *name);
/* The file name set by fh_set_name (then cleared), or dflt, in buf. */
const char *fh_ini_name(sbv_report *rep, char *buf, size_t n,
                        const char *dflt);

/* Run engine e to time T (sb_engine_run_until); a long run, more than
 * FH_LONG_RUN particle-steps (minutes), in 20 parts with a progress line
 * after each (the same steps: the run is unchanged). */
#define FH_LONG_RUN 1e9
int fh_run_until(const sbv_ctx *ctx, sb_engine *e, double T);

/* (T - t1) + 2 a_eff (sqrt(T) - sqrt(t1)) / sqrt(pi D), D = b2. */
double fh_teff(const fh_run *q);

/* Box edge for about `hits` first contacts of N particles within the
 * effective time Teff, and at least 10 relative displacement standard
 * deviations sqrt(2 b2 T). */
double fh_box_for(double K, size_t N, double Teff, double hits, double b2T);

/* Sets q->L by fh_box_for for about `hits` first contacts of kernel K;
 * where the box's lower bound binds (long runs, large steps), raises q->N
 * (up to nmax) instead, the expected count being K N^2 Teff / (2 L^3). */
void fh_size_for(fh_run *q, double K, double hits, size_t nmax);

/* Default engine parameters for a cubic box of edge L, step dt and room
 * for N particles, the engine seeded from the independent stream. */
int fh_cube_params(const sbv_ctx *ctx, unsigned long stream, double L,
                   double dt, size_t N, sb_engine_params *p);

/* |zeta(1/2)|: the Milne extrapolation length of the Klein-Kramers
 * equation in units of sqrt(k_B T / m) tau. */
#define FH_MILNE 1.4603545088095868

/* Contacts a --full first-contact run is sized for: +-1% (95%) needs
 * (1.96 / 0.01)^2 = 38 400 Poisson contacts times the count's variance
 * over its mean (fh_out.dispersion), which grows with the contacts per
 * particle: measured 1.00-1.20 for V4, V5, V7 and VX (4-10 per particle)
 * and 1.21-1.68 for V2's first-hit rows (15-22 per particle). */
#define FH_FULL_HITS 50000.0
#define FH_FULL_HITS_V2 64000.0

/* ------------------------------------------------------------------
 * First-hit counting of Langevin spheres in the transition regime
 * (firsthit_lv.c): one or two species (per pair type counts), any
 * detector, normal relative velocities at the first contacts, and the
 * long-time kernel with the transient removed self-consistently.
 *
 * Estimator (sb_engine_firsthit_estimate with the capacitance radius).
 * For a pair uniform (outside contact) at t = 0 the
 * absorption rate tends to K (1 + a / sqrt(pi D t)) + O(tau_p / t), with
 * D = D_i + D_j (Einstein, D = k_B T tau_p / m) and a = K / (4 pi D) the
 * capacitance radius of the absorber that the outer diffusion field sees
 * (the Smoluchowski transient of that sphere; for a pure diffusion
 * absorber a = R, for Langevin spheres at small Kn_D a = R - l with the
 * Milne length l of V2).  Integrated over (t1, T]:
 *   E[hits] = P/(V - v_a) [K (T - t1) + K^2 2 (sqrt T - sqrt t1) /
 *             (4 pi D sqrt(pi D))],
 * a quadratic in K solved exactly; the Garwood interval of the count maps
 * through the same increasing function.  The O(tau_p/t) remainder
 * integrates to O(tau_p log(T/t1)) against T - t1: the warm-up t1 >= 50
 * tau_p keeps it below ~0.2% (measured by varying t1, docs/validation.md,
 * V12).  At large Kn_D, a << R and the rate is close to free-molecular
 * from the start. */

enum {
  LV_LANGEVIN = 0,  /* sb_engine_langevin_contact */
  LV_CHORD = 1,     /* contact time of the displacement chords */
  LV_OVERLAP = 2,   /* overlap at step end */
  LV_BESSEL = 3,    /* Bessel-3 bridge of the positions (Mohaupt 2011,
                       ch. 5) */
  LV_EXACT = 4      /* exact 3-D Brownian bridge (sb_bb3_hit_sample) */
};

typedef struct {
  int nsp;                 /* 1 or 2 species */
  double d[2];             /* diameters, m */
  double tau[2], mass[2];  /* s, kg */
  size_t N[2];             /* particles of each species */
  double temp;             /* K */
  double dt, L;            /* s, m */
  double t1, T;            /* warm-up end and run end, s */
  int det;                 /* LV_* */
  size_t vcap;             /* keep up to vcap normal velocities at first
                              contacts (0: none) */
  double g[3];             /* constant acceleration, m/s^2 (0: none;
                              V16/combined: Brownian + settling) */
  double G;                /* shear rate, 1/s (0: none; else the fluid
                              U_x = G (y - L/2) with Lees-Edwards
                              boundaries, velocities started at it:
                              V16/combined-shear-diffusive) */
  double fh_radius;        /* write mode: first_hit_radius of the file
                              (0: first_hit_capacitance, the V12 records) */
  int fh_contact;          /* write mode: 1: no reference radius key (each
                              pair's contact distance r_i + r_j) */
  char names[2][16];       /* write mode: species section names ("": p,
                              or p0 and p1) */
  int threads;             /* engine threads (0: the engine's default);
                              1 for a run inside a parallel loop over
                              runs, whose cpu is then its thread's time.
                              Results do not depend on it */
  int default_rng;         /* 1: the engine's default generator (Philox
                              streams, sb_engine_params_default) instead
                              of the cases' pinned one; bench/, not in
                              write mode) */
  size_t sort_every;       /* sb_engine_params.sort_every (0: never, the
                              cases); bench/: with default_rng the
                              contacts do not depend on it */
} lv_run;

typedef struct {
  unsigned long hits[3];   /* first contacts after the warm-up, per pair
                              type (species 0-0, 0-1, 1-1) */
  double hits_var[3];      /* estimated variance of each count, from each
                              particle's contacts
                              (sb_engine_firsthit_counts.hits_var) */
  double npairs[3];        /* pairs apart at the start, per type */
  double veff[3];          /* V minus the contact ball, m^3 */
  double D[3];             /* relative diffusivities, m^2/s */
  double T;                /* time reached, s */
  double *vn;              /* normal relative velocities (< 0: approach)
                              at first contacts after the warm-up, all
                              types, m/s; caller frees */
  size_t nvn;
  double cpu, steps, ncand;
  double pruned_mass;      /* Langevin detector: summed pruned bounds */
  int unit;                /* write mode: the run was written, not run;
                              lv_kernel gives K = 1 */
} lv_out;

/* Run (engine seeded from `stream`); o->vn is allocated when vcap > 0.
 * Write mode (sbv_writing): the run is written as a collide configuration
 * instead (named by fh_set_name) and o gets unit values (o->unit); one
 * species: the next record's expect line reads first_hit.K; two: the
 * case writes its expect lines (first_hit.pairs[a,b].K). */
int lv_firsthit(const sbv_ctx *ctx, unsigned long stream, const lv_run *q,
                lv_out *o);

/* Pool run `add` into `acc`: independent repeats of one run (the same
 * lv_run, other streams) count as one run of their summed pairs, the
 * box and the end time being the same (SB_EINVAL otherwise).  Hits,
 * pairs, CPU time, steps and candidates add up; the normal velocities
 * are appended up to vcap.  add->vn is freed in any case. */
int lv_pool(lv_out *acc, lv_out *add, size_t vcap);
/* Long-time kernel of pair type `type` from a run (estimator above) with
 * its 95% interval; SB_EDOM if the type had no pairs. */
int lv_kernel(const lv_run *q, const lv_out *o, int type, double *K,
              double *lo, double *hi);
/* The expected count of pair type `type` for a kernel K (the estimator's
 * forward map: hits = lv_expected(K)). */
double lv_expected(const lv_run *q, const lv_out *o, int type, double K);

/* Row: the kernels of pair type `type` of two runs (1: tested, 2:
 * reference) are equal.  Conditional test: given n = h1 + h2, h1 is
 * binomial with p = f1(K)/(f1(K) + f2(K)) under H0 (f the runs' forward
 * maps lv_expected), the common K taken at its estimate from n
 * (f1 + f2 = n; a plug-in for the transient term, so the test is
 * approximately exact); exact binomial p-value and Clopper-Pearson
 * interval at 1 - SBV_ALPHA.  A share q of the n contacts maps to the
 * ratio f1^-1(n q) / f2^-1(n (1 - q)): the estimate (q = h1/n) is the
 * ratio of the runs' own estimates (lv_kernel), the interval is the map
 * of the binomial one, and it covers 1 exactly when the binomial interval
 * covers p.  Rule cover, reference 1. */
int lv_add_compare(sbv_report *rep, const char *name, const lv_run *q1,
                   const lv_out *o1, const lv_run *q2, const lv_out *o2,
                   int type);
/* Row: two samples have the same law (two-sample KS, acceptance region
 * [0, D_crit] at SBV_ALPHA).  Sorts both arrays. */
int lv_add_ks2(sbv_report *rep, const char *name, double *x, size_t nx,
               double *y, size_t ny);

#endif /* SB_VALIDATE_FIRSTHIT_H */
