/* v16.h — shared by the V16 cases (lib/validate/cases_v16*.c): one
 * engine run of non-interacting (count) particles with forces, shear,
 * Lees-Edwards images and walls, and the references they share. */
#ifndef SB_VALIDATE_V16_H
#define SB_VALIDATE_V16_H

#include <stddef.h>
#include <stdio.h>
#include <gsl/gsl_rng.h>
#include <smolbridge/engine.h>

#include "cases.h"

typedef struct {
  double r, rho_p, tau, B;  /* m, kg/m^3, s, m s^-3/2 */
  size_t count;
  sb_engine_drag drag;
  double rho_f, mu;         /* kg/m^3, Pa s */
} v16_species;

#define V16_MARKS 16

typedef struct {
  double L[3], dt;
  unsigned long seed;
  double G;                 /* shear rate (0: fluid at rest) */
  int lees;                 /* Lees-Edwards images */
  double g[3];              /* acceleration */
  size_t nsp;
  v16_species sp[4];
  sb_engine_wall walls[3];  /* per direction, both faces (0: periodic) */
  sb_engine_walldet walldet;
  sb_engine_deposit deposit;
  int nodetect;             /* no particle-particle detection */
  int parabolic;            /* walled directions: density y (W - y) (the
                               steady profile with a volume source)
                               instead of uniform */
  size_t warmup, steps;     /* steps (counters reset after the warm-up) */
  size_t nmark;             /* cumulative deposits after these steps */
  size_t mark[V16_MARKS];
} v16_setup;

typedef struct {
  sb_engine_pair_stats pk[4][4];  /* a <= b */
  double vset[4][3];        /* settling velocities, m/s */
  double umean[3];          /* mean velocity of species 0 at the end */
  unsigned long long dep[V16_MARKS], ndep;
  double t;
  size_t n_end;
} v16_result;

/* Place the particles uniformly and independently (inside the contact
 * planes of walled directions) at their equilibrium velocities, drawn
 * from r in the order of smolbridge collide's placement = uniform (x and
 * u per component in turn, species in order), run. */
int v16_run(const v16_setup *s, gsl_rng *r, v16_result *out);
/* Schiller-Naumann terminal speed by bisection, m/s. */
double v16_terminal_sn(double r, double rho_p, double rho_f, double mu,
                       double g);
/* Fraction of particles, uniform in a slab of width W between two
 * absorbing planes, absorbed by time t (diffusivity D): 1 - S(t),
 * S = sum_{k odd} 8/(k pi)^2 exp(-(k pi)^2 D t / W^2). */
double v16_slab_absorbed(double D, double t, double W);

int v16_case_deposition(const sbv_ctx *ctx, sbv_report *rep);

/* Species sp (one, Stokes, with noise) in the shear U_x = G (y - L_y/2)
 * with Lees-Edwards images, n particles placed uniformly from r at
 * their stationary peculiar velocities (sd B sqrt(tau/2)) plus the flow,
 * in the order of smolbridge collide's placement = uniform; status. */
int v16_shear_fill(sb_engine *e, gsl_rng *r, const sb_engine_species *sp,
                   size_t n, const double L[3], double G);
/* V16/combined-shear's rows for the Langevin detector at dt = tau_p
 * (cases_v16l.c). */
int v16_shear_langevin_rows(const sbv_ctx *ctx, sbv_report *rep);

/* Write mode: the [run] keys (after sbv_ini_begin) of a V16 count run
 * with contact-time detection and uniform placement from placement_seed,
 * as v16_run and the random-field cases draw it. */
void v16_ini_run(FILE *f, unsigned long seed, const double L[3], double dt,
                 size_t steps, unsigned long placement_seed);
/* The same with another detector (its INI name). */
void v16_ini_run_detect(FILE *f, unsigned long seed, const double L[3],
                        double dt, size_t steps,
                        unsigned long placement_seed, const char *detect);

/* Write mode: v16_run of a setup with walls (no warm-up, one fluid at
 * rest) as the collide file `name` (sbv_ini_begin): placement = uniform
 * from placement_seed ([species] profile = parabolic for s->parabolic),
 * detect = none for s->nodetect, and the deposits in series.csv every
 * sample_every steps.  The caller then adds the expect lines. */
int v16_write_walls(const sbv_ctx *ctx, sbv_report *rep, const v16_setup *s,
                    unsigned long placement_seed, size_t sample_every,
                    const char *name, const char *what);
/* Write mode: the expect line of a record that is the deposits of the
 * window (step k0, step k] of a run written with sample_every = 1 (row k
 * of series.csv is step k; k0 = 0: the run's start) times factor. */
void v16_expect_window(sbv_report *rep, const char *record, size_t k0,
                       size_t k, double factor);

#endif /* SB_VALIDATE_V16_H */
