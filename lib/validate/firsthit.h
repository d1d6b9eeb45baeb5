/* firsthit.h — kernel measurement by first-hit counting (private to
 * lib/validate).
 *
 * Particles pass through each other and the first detected contact of
 * every pair is counted (a hash set of pair ids): the pairs are then
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
  double lo, hi;        /* its 95% Garwood interval */
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

/* (T - t1) + 2 a_eff (sqrt(T) - sqrt(t1)) / sqrt(pi D), D = b2. */
double fh_teff(const fh_run *q);

/* Box edge for about `hits` first contacts of N particles within the
 * effective time Teff, and at least 10 relative displacement standard
 * deviations sqrt(2 b2 T). */
double fh_box_for(double K, size_t N, double Teff, double hits, double b2T);

/* Default engine parameters for a cubic box of edge L, step dt and room
 * for N particles, the engine seeded from the independent stream. */
int fh_cube_params(const sbv_ctx *ctx, unsigned long stream, double L,
                   double dt, size_t N, sb_engine_params *p);

/* |zeta(1/2)|: the Milne extrapolation length of the Klein-Kramers
 * equation in units of sqrt(k_B T / m) tau. */
#define FH_MILNE 1.4603545088095868

#endif /* SB_VALIDATE_FIRSTHIT_H */
