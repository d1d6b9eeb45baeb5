/* collide.h — `smolbridge collide`: the run configuration and the files
 * that fill it (collide_ini.c: keys and checks; collide_setup.c: the
 * engine built from it; collide_out.c: output files; collide.c: the
 * command).  Every key with its unit and default: docs/engine.md §9. */
#ifndef SB_CLI_COLLIDE_H
#define SB_CLI_COLLIDE_H

#include <stddef.h>
#include <stdio.h>

#include <smolbridge/engine.h>
#include <smolbridge/engine_bridge.h>
#include <smolbridge/engine_firsthit.h>

#define COL_MAXSPEC 16
#define COL_MAXPART 64
#define COL_MAXSEEN 512
#define COL_MAXWARN 32
#define COL_WHERE 128     /* "file:line" or "--set run.dt=1e-7" */

/* One [species NAME] section. */
typedef struct {
  char name[72];                /* "species colloid" */
  char where[COL_WHERE];        /* its header */
  double radius, diameter, density, mass, tau, mu, cc, B, b2, T, phi;
  long count, family;
  double region[6];
  int nregion;
  double drift[3];
  int ndrift;
  char drag[24];                    /* drag law (engine_force.c) */
  char inflow[16];                  /* open boundaries (engine_open.c): */
  double inflow_rate;               /* face, particles/s, */
  double inflow_region[4];          /* inlet, velocity */
  int ninflow_region;
  double inflow_u[3];
  int ninflow_u;
  long inflow_no_overlap;
  int npart;                        /* explicit particles */
  double part[COL_MAXPART][6];      /* x y z ux uy uz (2-D: z = uz = 0) */
  int part_n[COL_MAXPART];           /* numbers given (4 or 6) */
  char part_where[COL_MAXPART][COL_WHERE];
} col_species;

/* A key seen, with where it came from (duplicates, conflicts, messages). */
typedef struct {
  char sec[72], key[32];
  char where[COL_WHERE];
  int override;                 /* set by --set */
} col_seen;

typedef struct {
  /* [run] */
  unsigned long seed;
  long dim;
  double L, Lx, Ly, Lz, dt, t_end, warmup, thermalize, eta;
  double lv_eps, lv_xtol, lv_tol;  /* detect = langevin (NaN: default) */
  long steps, sample_every, snapshot_every, sort_every, threads;
  long placement_seed;          /* -1: the engine's generator */
  char neigh[16], detect[16], outcome[16], rng[16], placement[16];
  char output[512], checkpoint[512], restart[512];
  /* [bridge] (detect = bridge | exact) */
  char ends[16];
  double tol, exact_tol;
  /* [turbulence] */
  double eps, nu;
  /* [observe] */
  long hit_times, first_hit;
  double first_hit_radius;
  long first_hit_capacitance, first_hit_skip_seen;
  /* [agglo] (outcome = merge | dlvo) */
  char growth[16], erel[16];
  double wmax, wmax_kT;
  long erel_normal, kobs;
  /* [fluid] */
  char fluid[16];
  double U[3], G;
  int nU;
  /* [fluid] forces and Lees-Edwards (docs/engine_forces.md) */
  long lees;
  double g[3], rho_f, mu_f;
  int ng;
  /* [walls] */
  char wall[6][16], wall_detect[16], deposit[16];
  /* species */
  col_species sp[COL_MAXSPEC];
  int nsp;
  double b2_total[COL_MAXSPEC]; /* bridge b2 (turbulence included) and */
  double b2_brown[COL_MAXSPEC]; /* its Brownian part (set up by setup) */
  /* bookkeeping */
  col_seen seen[COL_MAXSEEN];
  int nseen;
  char sections[COL_MAXSPEC + 8][72];       /* headers seen in the file */
  char section_where[COL_MAXSPEC + 8][COL_WHERE];
  int nsections;
  char overrides[32][160];
  int noverrides;
  char warn[COL_MAXWARN][400];
  int nwarn;
  char err[1024];               /* first error */
  int nerr;
  char where[COL_WHERE];        /* origin of the key being set */
} col_config;

/* ------------------------------------------------------ collide_ini.c */

/* Defaults (docs/engine.md §9). */
void col_defaults(col_config *c);
/* Read an INI file; 0 or -1 with c->err set ("FILE:LINE: ..."). */
int col_read_file(col_config *c, const char *path);
/* --set SECTION.KEY=VALUE (species.NAME.KEY for [species NAME]). */
int col_override(col_config *c, const char *arg);
/* Cross-key checks after all keys: conflicts, requirements, keys that do
 * not apply (warnings in c->warn).  0 or -1 with c->err set. */
int col_check(col_config *c);
/* Where a key was set ("" if it was not); section "species NAME". */
const char *col_where(const col_config *c, const char *sec, const char *key);
int col_given(const col_config *c, const char *sec, const char *key);
/* "he" for [species he]. */
const char *col_short_name(const col_config *c, size_t k);
/* The sections and keys with unit, default and valid values (--help). */
void col_print_keys(FILE *f);
/* Names accepted for detect (the engine's built-ins and the bridge
 * detectors), NULL-terminated. */
const char *const *col_detect_names(void);
/* Set c->err (first error only); returns -1. */
int col_fail(col_config *c, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
void col_warn(col_config *c, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
/* 1 for the outcomes handled by the agglomeration context. */
int col_agglo(const col_config *c);
/* 1 for the detectors with a bridge context. */
int col_bridge(const col_config *c);

/* ---------------------------------------------------- collide_setup.c */

/* A run being set up or running. */
typedef struct {
  sb_engine *e;
  sb_engine_bridge *bridge;     /* detect = bridge | exact */
  sb_agglo *agglo;              /* outcome = merge | dlvo */
  sb_engine_firsthit *fh;       /* [observe] first_hit */
  double t_end;                 /* absolute end time, s */
  double warm;                  /* warm-up, s (0 on restart) */
} col_run;

/* Build the engine, species, particles and contexts.  0 or -1 with
 * c->err set (the run is then freed). */
int col_setup(col_config *c, col_run *r);
void col_run_free(col_run *r);
/* --------------------------------------------------- collide_firsthit.c */

/* Install first-hit counting around the run's detector (bridge context
 * r->bridge, or the built-in `builtin`) with the neighbour reach. */
int col_firsthit_attach(const col_config *c, col_run *r,
                        sb_engine_detect builtin, double reach);
/* Start of counting (end of the warm-up), s. */
void col_firsthit_start(col_run *r, double t1);
void col_firsthit_free(sb_engine_firsthit *f);
/* First-hit results (one species): 0, a status (the counts set, the
 * kernel NaN when it has no estimate), or -1 without the observer. */
int col_firsthit_result(const col_run *r, const col_config *c,
                        sb_engine_firsthit_kernel_result *o);

/* ------------------------------------------------------ collide_out.c */

/* Prepare the output directory before the run: create it, remove the
 * files a previous run wrote there (its manifest.txt), check that it and
 * the checkpoint path are writable.  0 or -1 with c->err set. */
int col_out_prepare(col_config *c);
/* Pair-kernel rows sampled with the series (series.csv columns). */
typedef struct {
  int nsp;
  double *rows;
  size_t nrows, cap;
} col_pairs;
int col_pairs_sample(col_pairs *ps, const sb_engine *e);
/* Write series.csv, summary.json, sizes.csv, hits.csv and manifest.txt;
 * status "ok" or "failed" (summary.json of a failed run says why). */
int col_out_write(const col_config *c, const col_run *r,
                  const col_pairs *ps, double secs, const char *status,
                  const char *why, long nsnap);
/* Snapshot path of number k. */
void col_snap_path(const col_config *c, long k, char *buf, size_t len);

/* ------------------------------------------- collide.c, collide_sweep.c */

/* What one run gives a sweep's summary. */
typedef struct {
  char status[16];      /* ok, input error, run error, write error */
  char why[1100];       /* the message when not ok */
  char kind[16];        /* K_e (collision kernel) or first-hit */
  size_t particles;
  unsigned long long ncoll, steps;
  double K, lo, hi;     /* m^3/s and its 95% interval, NaN if none */
  double cpu_seconds;
} col_point;

/* One run of CONFIG.ini with the overrides; progress on stderr when
 * verbose; *res (may be NULL) receives the summary.  Exit status as the
 * command's. */
int col_run_point(const char *ini, const char *const *sets, int nsets,
                  int verbose, col_point *res);
/* --sweep FILE: the points over the ranks (collide_sweep.c). */
int col_sweep(const char *ini, const char *const *sets, int nsets,
              const char *file);

#endif /* SB_CLI_COLLIDE_H */
