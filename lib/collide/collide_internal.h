/* collide_internal.h — the run configuration of <smolbridge/collide.h>
 * and the files that fill it (collide_keys.c: the key table;
 * collide_ini.c: INI reader and --set; collide_check.c: cross-key checks;
 * collide_setup.c: the engine built from it; collide_out.c: output
 * files; collide_run.c: the run; collide.c: the public object).  Every
 * key with its unit and default: docs/engine.md §9. */
#ifndef SB_COLLIDE_INTERNAL_H
#define SB_COLLIDE_INTERNAL_H

#include <stddef.h>
#include <stdio.h>

#include <gsl/gsl_rng.h>

#include <smolbridge/collide.h>
#include <smolbridge/engine.h>
#include <smolbridge/engine_bridge.h>
#include <smolbridge/engine_firsthit.h>
#include <smolbridge/engine_field.h>

#define COL_MAXSPEC 16
#define COL_MAXPART 64
#define COL_MAXSEEN 512
#define COL_MAXWARN 32
#define COL_WHERE 128     /* "file:line" or "--set run.dt=1e-7" */
#define COL_MAXREGION 8   /* [observe] region lines */

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
  char profile[16];                 /* placement density across walls */
  char drag[24];                    /* drag law (engine_force.c) */
  char velocities[16];              /* placed | antipodal (collide_start.c) */
  double vscale[3];                 /* velocity_scale per axis */
  int nvscale;
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
} sbi_col_species;

/* A key seen, with where it came from (duplicates, conflicts, messages). */
typedef struct {
  char sec[72], key[32];
  char where[COL_WHERE];
  int override;                 /* set by --set */
} sbi_col_seen;

typedef struct {
  /* [run] */
  unsigned long seed;
  long dim;
  double L, Lx, Ly, Lz, dt, t_end, warmup, thermalize, eta;
  double lv_eps, lv_xtol, lv_tol;  /* detect = langevin (NaN: default) */
  long steps, sample_every, snapshot_every, sort_every, threads;
  long placement_seed;          /* -1: the engine's generator */
  long velocity_seed;           /* velocities = antipodal; -1: the engine's */
  double snap_steps[64];        /* [run] snapshot_steps (whole numbers) */
  int nsnap_steps;
  double stop_every;            /* [run] stop_every (s; 0: none) */
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
  double grid[3];               /* [observe] grid: cells per axis */
  int ngrid;
  char grid_scheme[8];
  long exits;                   /* [observe] exits (exits.csv) */
  long count_variance;          /* [observe] count_variance: the engine's
                                   collision tally */
  long first_hit_vn;            /* contacts.csv rows (0: off) */
  long batch_steps;             /* [observe] batch_steps (0: off) */
  double regions[COL_MAXREGION][6]; /* [observe] region: lo hi per axis */
  int nregion_n[COL_MAXREGION];     /* numbers given (4 or 6) */
  char region_where[COL_MAXREGION][COL_WHERE];
  int nregions;
  long region_every;            /* steps between region samples */
  long msd_every;               /* steps between MSD samples (0: off) */
  double msd_fit[2];            /* fit lags, samples */
  int nmsd_fit;
  /* [agglo] (outcome = merge | dlvo) */
  char growth[16], erel[16];
  double wmax, wmax_kT;
  long erel_normal, kobs;
  /* [fluid] */
  char fluid[16];
  double U[3], G;
  int nU;
  /* [fluid] random fields (<smolbridge/engine_field.h>) */
  double ou_u2, ou_TL, kr_eps_nu, kr_omega;
  long kr_shell, field_seed, ou_stationary;
  /* [fluid] forces and Lees-Edwards (docs/engine_forces.md) */
  long lees;
  double g[3], rho_f, mu_f;
  int ng;
  /* [walls] */
  char wall[6][16], wall_detect[16], deposit[16];
  /* species */
  sbi_col_species sp[COL_MAXSPEC];
  int nsp;
  double b2_total[COL_MAXSPEC]; /* bridge b2 (turbulence included) and */
  double b2_brown[COL_MAXSPEC]; /* its Brownian part (set up by setup) */
  /* bookkeeping */
  sbi_col_seen seen[COL_MAXSEEN];
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
} sbi_col_config;

/* ------------------------------------------------------ collide_ini.c */

/* Defaults (docs/engine.md §9). */
void sbi_col_defaults(sbi_col_config *c);
/* Read an INI file; 0 or -1 with c->err set ("FILE:LINE: ..."). */
int sbi_col_read_file(sbi_col_config *c, const char *path);
/* Read an INI text; name stands for the file in the messages. */
int sbi_col_read_string(sbi_col_config *c, const char *text,
                        const char *name);
/* --set SECTION.KEY=VALUE (species.NAME.KEY for [species NAME]). */
int sbi_col_override(sbi_col_config *c, const char *arg);
/* Cross-key checks after all keys: conflicts, requirements, keys that do
 * not apply (warnings in c->warn).  0 or -1 with c->err set. */
int sbi_col_check(sbi_col_config *c);
/* The checks that depend on dim, the box and the walls: the keys whose
 * number of values depends on dim ([fluid] U and g, the inflows' keys),
 * the z faces of a 2-D box, the Kraichnan field's cube, [observe] exits
 * and count_variance against the open faces, and on restart the
 * checkpoint's walls against [fluid] type = shear, msd_every and
 * [walls] detect and deposit: sbi_col_check for
 * a new run, collide_setup.c on restart once the checkpoint's dim, box
 * and walls are in c.  0 or -1 with c->err set. */
int sbi_col_dim_check(sbi_col_config *c);
/* On restart without [fluid] type, once the checkpoint's field and
 * Lees-Edwards images are in c (collide_setup.c): the checks that depend
 * on them.  0 or -1 with c->err set. */
int sbi_col_fluid_check(sbi_col_config *c);
/* Where a key was set ("" if it was not); section "species NAME". */
const char *sbi_col_where(const sbi_col_config *c, const char *sec,
                          const char *key);
int sbi_col_given(const sbi_col_config *c, const char *sec,
                  const char *key);
/* "he" for [species he]. */
const char *sbi_col_short_name(const sbi_col_config *c, size_t k);
/* The name of engine species k in every output (summary.json, exits.csv,
 * contacts.csv): NAME of its [species NAME] section, or, for a cluster
 * species of the agglomeration context ag (may be NULL), "cluster_K" with
 * K its number of primaries, written in buf (len bytes, 32 will do). */
const char *sbi_col_species_label(const sbi_col_config *c,
                                  const sb_agglo *ag, size_t k, char *buf,
                                  size_t len);
/* Names accepted for detect (the engine's built-ins, then the bridge
 * detectors), NULL-terminated, in names[0..len-1]; returns names. */
const char **sbi_col_detect_names(const char **names, size_t len);
/* The key table (collide_keys.c): each key's section, type, place in
 * sbi_col_config (or sbi_col_species), range, unit, default and help. */
typedef enum {
  K_NUM,      /* double */
  K_INT,      /* long */
  K_SEED,     /* unsigned long, 0 .. 2^32-1 */
  K_NAME,     /* char[16], one of names */
  K_PATH,     /* char[512] */
  K_BOOL,     /* long 0/1 from yes/no */
  K_VEC,      /* double[], count in the int at aux */
  K_PARTICLE, /* species: repeatable */
  K_REGION    /* [observe] region: repeatable */
} sbi_col_ktype;

typedef enum { R_ANY, R_POS, R_NONNEG, R_CLOSED, R_POSINF } sbi_col_krange;

typedef struct {
  const char *sec;    /* "run", ..., "species" */
  const char *key;
  sbi_col_ktype type;
  size_t off;         /* in sbi_col_config, or sbi_col_species for "species" */
  size_t aux;         /* K_VEC: offset of the count; K_NAME: size */
  sbi_col_krange range;
  double lo, hi;      /* R_CLOSED (and K_INT, K_VEC sizes) */
  const char *const *names;   /* K_NAME; NULL for detect (dynamic) */
  const char *unit, *def, *help;
} sbi_col_keydef;

extern const sbi_col_keydef sbi_col_keys[];
extern const size_t sbi_col_nkeys;
/* The valid names of a K_NAME or K_BOOL key, in names[0..len-1]. */
const char *const *sbi_col_names_of(const sbi_col_keydef *k,
                                    const char **names, size_t len);
/* "a, b, c" */
void sbi_col_join(char *buf, size_t len, const char *const *names);
/* The valid values of key k in words. */
void sbi_col_range_text(const sbi_col_keydef *k, char *buf, size_t len);
/* The key of a section ("species" for every [species NAME]), or NULL. */
const sbi_col_keydef *sbi_col_find_key(const char *sec, const char *key);
/* The keys of a section, "a, b, c". */
void sbi_col_keys_of(const char *sec, char *buf, size_t len);
/* 1 if sec names a species section ("species NAME", "species.NAME",
 * "species:NAME"), with *name pointing at NAME. */
int sbi_col_is_species(const char *sec, const char **name);
/* Set c->err (first error only); returns -1. */
int sbi_col_fail(sbi_col_config *c, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
void sbi_col_warn(sbi_col_config *c, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
/* 1 for the outcomes handled by the agglomeration context. */
int sbi_col_agglo(const sbi_col_config *c);
/* 1 for the detectors with a bridge context. */
int sbi_col_bridge(const sbi_col_config *c);
/* detect = md (sb_engine_detect_md) and its neighbour reach (m). */
int sbi_col_md(const sbi_col_config *c);
double sbi_col_md_reach(const sbi_col_config *c, const sb_engine *e);

/* ---------------------------------------------------- collide_setup.c */

/* A run being set up or running. */
typedef struct sbi_col_msd sbi_col_msd;  /* collide_msd.c */
typedef struct sbi_col_contacts sbi_col_contacts;  /* collide_contacts.c */
typedef struct sbi_col_batches sbi_col_batches;    /* collide_batches.c */

/* Pair-kernel rows sampled with the series (series.csv columns). */
typedef struct {
  int nsp;
  double *rows;
  size_t nrows, cap;
} sbi_col_pairs;

typedef struct {
  sb_engine *e;
  sb_engine_bridge *bridge;     /* detect = bridge | exact */
  sb_agglo *agglo;              /* outcome = merge | dlvo */
  sb_engine_firsthit *fh;       /* [observe] first_hit */
  sb_field_ou *ou;              /* [fluid] type = ou-field */
  sb_field_kraichnan *kr;       /* [fluid] type = kraichnan */
  gsl_rng *field_rng;           /* [fluid] seed (owned), or NULL */
  sbi_col_msd *msd;             /* [observe] msd_every, or NULL */
  sbi_col_contacts *contacts;   /* [observe] first_hit_velocities */
  sbi_col_batches *batches;     /* [observe] batch_steps, or NULL */
  int measuring;                /* after the warm-up */
  double ekin0;                 /* kinetic energy at the measurement start */
  int ekin0_saved;              /* restart: ekin0 is the first run's */
  sbi_col_pairs pairs;          /* pair kernels sampled with the series */
  double t_end;                 /* absolute end time, s */
  double warm;                  /* warm-up, s (0 on restart) */
  double *dep;                  /* deposits sampled with the series: rows */
  size_t ndep, capdep;          /* t, per face x_lo .. z_hi (walls.c) */
  int dep_on;                   /* a face absorbs */
  FILE *grid_f;                 /* [observe] grid: grid.csv, written as
                                   the frames come (collide_grid.c) */
  size_t grid_frames;           /* frames written */
  double grid_last_t;           /* time of the last frame, s */
  FILE *exits_f;                /* [observe] exits: exits.csv, written as
                                   the particles leave (collide_exits.c) */
  const sbi_col_config *exits_c;/* for the species names of its rows */
  int record_exits;             /* [observe] exits: rows of exits.csv */
} sbi_col_run;

/* ---------------------------------------------------- collide_exits.c */

/* [observe] exits (and batch_steps): the outflow callback that writes
 * each exit to exits.csv as it happens, the reset at the end of the
 * warm-up (the file starts again; SB_EIO), and the close at the end (the
 * header alone if no particle left; 0 or -1 on a write error). */
int sbi_col_exits_attach(const sbi_col_config *c, sbi_col_run *r);
int sbi_col_exits_reset(sbi_col_run *r);
int sbi_col_exits_close(const sbi_col_config *c, sbi_col_run *r);

/* --------------------------------------------------- collide_batches.c */

/* [observe] batch_steps and region: the measurement cut into batches of
 * batch_steps steps, one row of batches.csv per batch (drops injected and
 * leaving, collisions, exiting mass per open face and family, exiting
 * momentum and mass-weighted exit coordinates per open face, mean mass in
 * each region), and the batch means with t intervals in summary.json. */
/* Cross-key checks (0 or -1 with c->err). */
int sbi_col_batches_check(sbi_col_config *c);
/* Allocate for nsteps measured steps (0 or -1 with c->err). */
int sbi_col_batches_setup(sbi_col_config *c, sbi_col_run *r, long nsteps);
/* The start of the measurement; a measured step done. */
void sbi_col_batches_start(sbi_col_run *r);
void sbi_col_batches_step(sbi_col_run *r);
/* An exit through an open face (from the outflow callback): mass m,
 * family, the crossing point x and the velocity u. */
void sbi_col_batches_exit(sbi_col_run *r, int face, int family, double m,
                          const double x[3], const double u[3]);
int sbi_col_batches_write(FILE *js, const sbi_col_config *c,
                          const sbi_col_run *r, const char *path);
void sbi_col_batches_free(sbi_col_batches *b);

/* ----------------------------------------------------- collide_grid.c */

/* [observe] grid: a frame of the mass and momentum densities now (once
 * per time), grid.csv, its summary.json entry. */
int sbi_col_grid_on(const sbi_col_config *c);
int sbi_col_grid_sample(const sbi_col_config *c, sbi_col_run *r);
/* Close grid.csv (written frame by frame; the header alone if no frame);
 * 0 or -1 on a write error. */
int sbi_col_grid_close(const sbi_col_config *c, sbi_col_run *r);
void sbi_col_grid_json(FILE *f, const sbi_col_config *c,
                       const sbi_col_run *r);

/* Build the engine, species, particles and contexts.  0 or -1 with
 * c->err set (the run is then freed). */
int sbi_col_setup(sbi_col_config *c, sbi_col_run *r);
void sbi_col_run_free(sbi_col_run *r);
/* ------------------------------------------------- collide_beside.c */

/* The states a run keeps beside its checkpoint, besides the engine's:
 * its counts, the first-contact observer's (CHECKPOINT.firsthit) or the
 * agglomeration context's (CHECKPOINT.agglo), its random field
 * (CHECKPOINT.field), the contacts' velocities of first_hit_velocities
 * (CHECKPOINT.contacts), the bridge detector's counters and hit
 * records (CHECKPOINT.bridge) and the outputs' part before the
 * checkpoint (CHECKPOINT.run, collide_runstate.c).  The file name of state `which` from `checkpoint`
 * into buf (0), or 1 when the run has no such state. */
enum {
  SBI_BESIDE_COUNTS, SBI_BESIDE_FIELD, SBI_BESIDE_CONTACTS,
  SBI_BESIDE_BRIDGE, SBI_BESIDE_RUN, SBI_BESIDE_N
};
int sbi_col_beside(const sbi_col_config *c, int which,
                   const char *checkpoint, char *buf, size_t len);
/* On restart, the file of state `which` beside [run] restart into buf: 0
 * (also when the run has no such state), or SB_EIO with sb_last_error()
 * saying it is missing and that without it `lost` (what it holds) is
 * unknown. */
int sbi_col_restart_beside(const sbi_col_config *c, int which,
                           const char *lost, char *buf, size_t len);
/* Save the states beside [run] checkpoint (nothing without one): 0 or a
 * status with sb_last_error() set. */
int sbi_col_save_beside(const sbi_col_config *c, const sbi_col_run *r);

/* ------------------------------------------------- collide_runstate.c */

/* What series.csv and summary.json need from the part of a run before
 * its checkpoint, beside it in CHECKPOINT.run: the kinetic energy at the
 * measurement start and the rows sampled with the series (pair kernels,
 * deposits).  Save: 0 or SB_EIO with sb_last_error() set.  Load on
 * restart: 0 (a missing file is a warning: a checkpoint of an older
 * version), or a status with c->err set. */
int sbi_col_runstate_save(const sbi_col_config *c, const sbi_col_run *r);
int sbi_col_runstate_load(sbi_col_config *c, sbi_col_run *r);

/* --------------------------------------------------- collide_firsthit.c */

/* Install first-hit counting around the run's detector (bridge context
 * r->bridge, or the built-in `builtin`) with the neighbour reach; on
 * restart with the counts saved beside the checkpoint. */
int sbi_col_firsthit_attach(const sbi_col_config *c, sbi_col_run *r,
                            sb_engine_detect builtin, double reach);
/* Start of counting (end of the warm-up), s. */
void sbi_col_firsthit_start(sbi_col_run *r, double t1);
void sbi_col_firsthit_free(sb_engine_firsthit *f);
/* First-hit results of species pair (a, b) (a, b < nsp): 0, a status
 * (the counts set, the kernel NaN when it has no estimate), or -1
 * without the observer. */
int sbi_col_firsthit_pair(const sbi_col_run *r, const sbi_col_config *c,
                          size_t a, size_t b,
                          sb_engine_firsthit_kernel_result *o);
/* One species: sbi_col_firsthit_pair(0, 0).  Several: the counts of all
 * pairs, the kernel NaN, SB_EDOM.  -1 without the observer. */
int sbi_col_firsthit_result(const sbi_col_run *r, const sbi_col_config *c,
                            sb_engine_firsthit_kernel_result *o);

/* ---------------------------------------------------- collide_walls.c */

/* 1 if a face absorbs (series.csv then has deposit columns). */
int sbi_col_walls_absorb(const sbi_col_config *c);
/* Append the deposits per face at the engine's time to r->dep. */
int sbi_col_walls_sample(sbi_col_run *r);
/* series.csv: the deposit columns' names, and the row sampled at time t
 * (nan where none was: the warm-up); *next (0 before the first row)
 * follows the rows, whose times increase. */
void sbi_col_walls_header(FILE *f, const sbi_col_config *c);
void sbi_col_walls_row(FILE *f, const sbi_col_config *c,
                       const sbi_col_run *r, double t, size_t *next);
/* Coordinate k of a uniform placement in [lo, hi): the species' profile
 * along walled directions, uniform otherwise. */
double sbi_col_place_coord(const sbi_col_config *c,
                           const sbi_col_species *s, int k, double lo,
                           double hi, gsl_rng *g);
/* [run] detect = none, and its detector (no contact ever). */
int sbi_col_detect_none(const sbi_col_config *c);
int sbi_col_none_attach(sbi_col_run *r);
/* ------------------------------------------------- collide_contacts.c */

/* [observe] first_hit_velocities: set the observer's detector and hit
 * callback in fp (built-in langevin or ballistic), contacts.csv and the
 * summary's "contacts" entry (nothing without the key). */
int sbi_col_contacts_setup(const sbi_col_config *c, sbi_col_run *r,
                           sb_engine_detect builtin,
                           sb_engine_firsthit_params *fp);
int sbi_col_contacts_write(FILE *js, const sbi_col_config *c,
                           const sbi_col_run *r, const char *path);
void sbi_col_contacts_free(sbi_col_contacts *k);
/* At the end of each step: the step's contacts in order of time (then of
 * the pair's ids), the first cap of all kept.  The record then does not
 * depend on the order of the particles in memory or on the threads. */
void sbi_col_contacts_step_end(sbi_col_run *r);
/* The recorded contacts to path, beside a checkpoint, and back into the
 * run's (set up) record on restart: 0 or a status with sb_last_error()
 * set. */
int sbi_col_contacts_save(const sbi_col_run *r, const char *path);
int sbi_col_contacts_load(sbi_col_run *r, const char *path);

/* ---------------------------------------------------- collide_start.c */

/* [species NAME] velocities = antipodal: checks, and the velocities set
 * after the placement and thermalize (0 or -1 with c->err). */
int sbi_col_start_check(sbi_col_config *c);
int sbi_col_start_velocities(sbi_col_config *c, sbi_col_run *r);

/* ------------------------------------------------------ collide_msd.c */

/* [observe] msd_every: start at the end of the warm-up (r->t_end set),
 * a step of the measurement, msd.csv and the summary's "msd" entry
 * (nothing without the key). */
/* Cross-key checks of msd_every and msd_fit (0 or -1 with c->err); the
 * walls of the run's box (its 2 dim faces) with msd_every: from
 * sbi_col_msd_check for a new run, sbi_col_dim_check on restart (once
 * the checkpoint's dim and walls are in c). */
int sbi_col_msd_check(sbi_col_config *c);
int sbi_col_msd_walls_check(sbi_col_config *c);
int sbi_col_msd_lees_check(sbi_col_config *c);
int sbi_col_msd_start(const sbi_col_config *c, sbi_col_run *r);
int sbi_col_msd_step(sbi_col_run *r);
int sbi_col_msd_write(FILE *js, const sbi_col_config *c,
                      const sbi_col_run *r, const char *path);
void sbi_col_msd_free(sbi_col_msd *m);

/* ------------------------------------------------------ collide_out.c */

/* Prepare the output directory before the run: create it, remove the
 * files a previous run wrote there (its manifest.txt), check that it and
 * the checkpoint path are writable.  0 or -1 with c->err set. */
int sbi_col_out_prepare(sbi_col_config *c);
int sbi_col_pairs_sample(sbi_col_pairs *ps, const sb_engine *e);
/* Write series.csv, summary.json, sizes.csv, hits.csv and manifest.txt;
 * status "ok" or "failed" (summary.json of a failed run says why); secs:
 * the run's wall-clock and CPU (all threads) seconds. */
int sbi_col_out_write(const sbi_col_config *c, sbi_col_run *r,
                      const sbi_col_pairs *ps, const double secs[2],
                      const char *status, const char *why, long nsnap);
/* Snapshot path of number k. */
void sbi_col_snap_path(const sbi_col_config *c, long k, char *buf, size_t len);
/* A JSON number: x to 17 digits, or null for NaN/inf (not JSON). */
void sbi_col_jnum(FILE *f, double x);

/* ---------------------------------------------- collide.c, collide_run.c */

struct sb_collide {
  sbi_col_config c;
  sbi_col_run r;
  int checked, set_up, ran;
  sb_collide_failure failed;    /* the first failure */
  int status;                   /* its status code */
  char msg[2400];               /* its message, lines joined by '\n' */
};

/* Record the first failure: kind, status and message (from c.err for
 * input errors found by the configuration code).  Returns status. */
int sbi_col_failure(sb_collide *cl, sb_collide_failure kind, int status,
                    const char *msg);
/* Append a line to the message of a failed run. */
void sbi_col_more(sb_collide *cl, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

#endif /* SB_COLLIDE_INTERNAL_H */
