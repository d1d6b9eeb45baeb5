/* collide_ini.c — the keys of a `smolbridge collide` configuration: one
 * table gives each key's section, type, unit, default and valid values;
 * it drives the parser (INI file and --set), the error messages and
 * `collide --help`.  Messages name where the key came from, the section,
 * key and value, and the valid values. */
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include <ini.h>

#include <smolbridge/engine.h>

#include "collide.h"

/* ------------------------------------------------------------ names */

static const char *const OUTCOMES[] = {"elastic", "reinsert", "count",
                                       "correction", "merge", "dlvo", NULL};
static const char *const NEIGHS[] = {"cells", "sweep", "brute", NULL};
static const char *const RNGS[] = {"mt19937", "taus2", "philox", NULL};
static const char *const PLACEMENTS[] = {"random", "lattice", "uniform",
                                         NULL};
static const char *const FLUIDS[] = {"rest", "uniform", "shear", NULL};
static const char *const GROWTHS[] = {"stokes", "constant", NULL};
static const char *const ERELS[] = {"contact", "stationary", NULL};
static const char *const ENDS[] = {"position", "diffusive", NULL};
static const char *const BOOLS[] = {"yes", "no", NULL};
static const char *const DRAGS[] = {"stokes", "schiller-naumann", NULL};
static const char *const WALLS[] = {"periodic", "reflect", "absorb", "open",
                                    NULL};
static const char *const FACES[] = {"x_lo", "x_hi", "y_lo", "y_hi", "z_lo",
                                    "z_hi", NULL};
static const char *const WALLDETS[] = {"bridge", "ballistic", "langevin",
                                       NULL};
static const char *const DEPOSITS[] = {"remove", "reinsert", NULL};

/* Detectors with a context of their own (lib/engine/engine_bridge.c);
 * a new one is a name here and a branch in collide_setup.c. */
static const char *const CONTEXT_DETECTORS[] = {"bridge", "exact", NULL};

const char *const *col_detect_names(void)
{
  static const char *names[16];
  if (!names[0]) {  /* the engine's built-ins first, in its order */
    int n = 0;
    const char *const *b = sb_engine_detect_names();
    for (int k = 0; b[k] && n < 12; k++)
      names[n++] = b[k];
    for (int k = 0; CONTEXT_DETECTORS[k] && n < 15; k++)
      names[n++] = CONTEXT_DETECTORS[k];
    names[n] = NULL;
  }
  return names;
}

/* ------------------------------------------------------------ table */

typedef enum {
  K_NUM,      /* double */
  K_INT,      /* long */
  K_SEED,     /* unsigned long, 0 .. 2^32-1 */
  K_NAME,     /* char[16], one of names */
  K_PATH,     /* char[512] */
  K_BOOL,     /* long 0/1 from yes/no */
  K_VEC,      /* double[], count in the int at aux */
  K_PARTICLE  /* species: repeatable */
} ktype;

typedef enum { R_ANY, R_POS, R_NONNEG, R_CLOSED, R_POSINF } krange;

typedef struct {
  const char *sec;    /* "run", ..., "species" */
  const char *key;
  ktype type;
  size_t off;         /* in col_config, or col_species for "species" */
  size_t aux;         /* K_VEC: offset of the count; K_NAME: size */
  krange range;
  double lo, hi;      /* R_CLOSED (and K_INT, K_VEC sizes) */
  const char *const *names;   /* K_NAME; NULL for detect (dynamic) */
  const char *unit, *def, *help;
} keydef;

#define C(f) offsetof(col_config, f)
#define S(f) offsetof(col_species, f)

static const keydef KEYS[] = {
    /* ---------------------------------------------------------- [run] */
    {"run", "seed", K_SEED, C(seed), 0, R_CLOSED, 0, 4294967295.0, NULL,
     "-", "1", "seed of the engine's generator"},
    {"run", "dim", K_INT, C(dim), 0, R_CLOSED, 2, 3, NULL, "-", "3",
     "2 or 3 dimensions"},
    {"run", "L", K_NUM, C(L), 0, R_POS, 0, 0, NULL, "m", "required",
     "cubic (square) box edge; or Lx, Ly, Lz"},
    {"run", "Lx", K_NUM, C(Lx), 0, R_POS, 0, 0, NULL, "m", "-", "box edge"},
    {"run", "Ly", K_NUM, C(Ly), 0, R_POS, 0, 0, NULL, "m", "-", "box edge"},
    {"run", "Lz", K_NUM, C(Lz), 0, R_POS, 0, 0, NULL, "m", "-",
     "box edge (3-D)"},
    {"run", "dt", K_NUM, C(dt), 0, R_POS, 0, 0, NULL, "s", "required",
     "time step"},
    {"run", "t_end", K_NUM, C(t_end), 0, R_POS, 0, 0, NULL, "s",
     "- (or steps)", "end time, warm-up included"},
    {"run", "steps", K_INT, C(steps), 0, R_CLOSED, 1, 2e9, NULL, "-",
     "- (or t_end)", "measured steps after the warm-up"},
    {"run", "warmup", K_NUM, C(warmup), 0, R_NONNEG, 0, 0, NULL, "s", "0",
     "run this long, then reset the counters"},
    {"run", "thermalize", K_NUM, C(thermalize), 0, R_NONNEG, 0, 0, NULL,
     "K", "0 (off)", "zero momentum, rescale the kinetic energy to T"},
    {"run", "neigh", K_NAME, C(neigh), 16, R_ANY, 0, 0, NEIGHS, "-",
     "cells", "neighbour search"},
    {"run", "detect", K_NAME, C(detect), 16, R_ANY, 0, 0, NULL, "-",
     "ballistic", "collision detector"},
    {"run", "outcome", K_NAME, C(outcome), 16, R_ANY, 0, 0, OUTCOMES, "-",
     "elastic", "what a collision does"},
    {"run", "eta", K_NUM, C(eta), 0, R_CLOSED, 0, 1, NULL, "-", "1",
     "energy-loss factor of elastic collisions and DLVO rebounds"},
    {"run", "langevin_eps", K_NUM, C(lv_eps), 0, R_CLOSED, 1e-300, 0.1,
     NULL, "-", "1e-6",
     "detect = langevin: probability budget per pair and step of the "
     "pruning"},
    {"run", "langevin_xtol", K_NUM, C(lv_xtol), 0, R_CLOSED, 1e-300, 0.01,
     NULL, "-", "1e-6",
     "detect = langevin: contact position resolution relative to r_i + r_j"},
    {"run", "langevin_tol", K_NUM, C(lv_tol), 0, R_CLOSED, 1e-300, 0.5,
     NULL, "-", "1e-9",
     "detect = langevin: neighbour reach, expected contacts missed per "
     "particle per step"},
    {"run", "sample_every", K_INT, C(sample_every), 0, R_CLOSED, 1, 2e9,
     NULL, "steps", "run/200", "time-series period"},
    {"run", "snapshot_every", K_INT, C(snapshot_every), 0, R_CLOSED, 0, 2e9,
     NULL, "steps", "0 (off)", "snapshot period"},
    {"run", "sort_every", K_INT, C(sort_every), 0, R_CLOSED, 0, 2e9, NULL,
     "steps", "0 (off)", "reorder particles in memory (speed)"},
    {"run", "rng", K_NAME, C(rng), 16, R_ANY, 0, 0, RNGS, "-", "mt19937",
     "generator type; philox: per-particle counter-based streams for "
     "transport (parallel; results independent of the thread count and "
     "of the particle order)"},
    {"run", "threads", K_INT, C(threads), 0, R_CLOSED, 0, 4096, NULL, "-",
     "0 (OMP_NUM_THREADS)",
     "threads of the engine's parallel parts (results do not depend on "
     "it)"},
    {"run", "placement", K_NAME, C(placement), 16, R_ANY, 0, 0, PLACEMENTS,
     "-", "random (lattice above phi 0.3)",
     "random: no overlaps; lattice: FCC/square sites; uniform: overlaps "
     "allowed"},
    {"run", "placement_seed", K_INT, C(placement_seed), 0, R_CLOSED, 0,
     4294967295.0, NULL, "-", "- (engine generator)",
     "separate MT19937 generator for placement = uniform"},
    {"run", "output", K_PATH, C(output), 0, R_ANY, 0, 0, NULL, "path",
     "collide-out", "output directory"},
    {"run", "checkpoint", K_PATH, C(checkpoint), 0, R_ANY, 0, 0, NULL,
     "path", "-", "write a checkpoint at the end"},
    {"run", "restart", K_PATH, C(restart), 0, R_ANY, 0, 0, NULL, "path", "-",
     "start from a checkpoint"},
    /* ------------------------------------------------------- [bridge] */
    {"bridge", "ends", K_NAME, C(ends), 16, R_ANY, 0, 0, ENDS, "-",
     "position", "bridge end points: X, or Y = X + tau_p U"},
    {"bridge", "tol", K_NUM, C(tol), 0, R_CLOSED, 1e-300, 0.5, NULL, "-",
     "1e-9", "missed collisions per particle and step (reach)"},
    {"bridge", "exact_tol", K_NUM, C(exact_tol), 0, R_CLOSED, 1e-12, 0.1,
     NULL, "-", "1e-3", "tolerance of detect = exact"},
    /* --------------------------------------------------- [turbulence] */
    {"turbulence", "eps", K_NUM, C(eps), 0, R_POS, 0, 0, NULL, "m^2/s^3",
     "-", "dissipation rate: turbulent pair diffusion"},
    {"turbulence", "nu", K_NUM, C(nu), 0, R_POS, 0, 0, NULL, "m^2/s",
     "required with eps", "kinematic viscosity"},
    /* ------------------------------------------------------ [observe] */
    {"observe", "hit_times", K_INT, C(hit_times), 0, R_CLOSED, 0, 1e8, NULL,
     "-", "0", "record up to this many bridge hits (hits.csv, KS)"},
    {"observe", "first_hit", K_BOOL, C(first_hit), 0, R_ANY, 0, 0, BOOLS,
     "-", "no", "count the first contact of every pair (outcome count)"},
    {"observe", "first_hit_radius", K_NUM, C(first_hit_radius), 0, R_POS, 0,
     0, NULL, "m", "r_i + r_j", "radius of the reference absorbing sphere"},
    {"observe", "first_hit_capacitance", K_BOOL, C(first_hit_capacitance), 0,
     R_ANY, 0, 0, BOOLS, "-", "no", "reference radius K/(4 pi D) of the "
     "measured kernel (Langevin spheres, any Kn_D)"},
    {"observe", "first_hit_skip_seen", K_BOOL, C(first_hit_skip_seen), 0,
     R_ANY, 0, 0, BOOLS, "-", "no", "do not pass pairs whose first contact "
     "is known to the detector (fewer draws)"},
    /* -------------------------------------------------------- [agglo] */
    {"agglo", "growth", K_NAME, C(growth), 16, R_ANY, 0, 0, GROWTHS, "-",
     "stokes", "species of a cluster of k primaries"},
    {"agglo", "wmax", K_NUM, C(wmax), 0, R_NONNEG, 0, 0, NULL, "J", "0",
     "DLVO barrier"},
    {"agglo", "wmax_kT", K_NUM, C(wmax_kT), 0, R_NONNEG, 0, 0, NULL, "k_B T",
     "-", "barrier in units of k_B T of the first species"},
    {"agglo", "erel", K_NAME, C(erel), 16, R_ANY, 0, 0, ERELS, "-",
     "contact", "where E_rel comes from"},
    {"agglo", "erel_normal", K_INT, C(erel_normal), 0, R_CLOSED, 0, 1, NULL,
     "-", "0", "1: only the normal part of E_rel"},
    {"agglo", "kobs", K_INT, C(kobs), 0, R_CLOSED, 1, 100000, NULL, "-",
     "10", "n_k columns of sizes.csv"},
    /* -------------------------------------------------------- [fluid] */
    {"fluid", "type", K_NAME, C(fluid), 16, R_ANY, 0, 0, FLUIDS, "-", "rest",
     "fluid velocity field"},
    {"fluid", "U", K_VEC, C(U), C(nU), R_ANY, 2, 3, NULL, "m/s", "0 0 0",
     "velocity of type = uniform"},
    {"fluid", "G", K_NUM, C(G), 0, R_ANY, 0, 0, NULL, "1/s",
     "required with shear", "shear rate: U_x = G (y - L_y/2)"},
    {"fluid", "lees_edwards", K_BOOL, C(lees), 0, R_ANY, 0, 0, BOOLS, "-",
     "yes", "type = shear: Lees-Edwards sliding boundaries in y"},
    {"fluid", "g", K_VEC, C(g), C(ng), R_ANY, 2, 3, NULL, "m/s^2", "0 0 0",
     "constant acceleration (gravity), buoyancy factor 1 - rho/rho_p"},
    {"fluid", "rho", K_NUM, C(rho_f), 0, R_NONNEG, 0, 0, NULL, "kg/m^3",
     "0", "fluid density (buoyancy, particle Reynolds number)"},
    {"fluid", "mu", K_NUM, C(mu_f), 0, R_POS, 0, 0, NULL, "Pa s",
     "species mu", "fluid viscosity of a nonlinear drag law"},
    /* -------------------------------------------------------- [walls] */
    {"walls", "x_lo", K_NAME, C(wall[0]), 16, R_ANY, 0, 0, WALLS, "-",
     "periodic", "face x = 0 (a wall needs both faces walls)"},
    {"walls", "x_hi", K_NAME, C(wall[1]), 16, R_ANY, 0, 0, WALLS, "-",
     "periodic", "face x = L_x"},
    {"walls", "y_lo", K_NAME, C(wall[2]), 16, R_ANY, 0, 0, WALLS, "-",
     "periodic", "face y = 0"},
    {"walls", "y_hi", K_NAME, C(wall[3]), 16, R_ANY, 0, 0, WALLS, "-",
     "periodic", "face y = L_y"},
    {"walls", "z_lo", K_NAME, C(wall[4]), 16, R_ANY, 0, 0, WALLS, "-",
     "periodic", "face z = 0 (3-D)"},
    {"walls", "z_hi", K_NAME, C(wall[5]), 16, R_ANY, 0, 0, WALLS, "-",
     "periodic", "face z = L_z (3-D)"},
    {"walls", "detect", K_NAME, C(wall_detect), 16, R_ANY, 0, 0, WALLDETS,
     "-", "bridge", "wall contact: Brownian bridge, straight chord or "
     "Langevin bridge"},
    {"walls", "deposit", K_NAME, C(deposit), 16, R_ANY, 0, 0, DEPOSITS, "-",
     "remove", "deposited particle: removed, or reinserted uniformly"},
    /* ------------------------------------------------ [species NAME] */
    {"species", "radius", K_NUM, S(radius), 0, R_POS, 0, 0, NULL, "m",
     "required (or diameter)", "sphere radius"},
    {"species", "diameter", K_NUM, S(diameter), 0, R_POS, 0, 0, NULL, "m",
     "-", "sphere diameter"},
    {"species", "mass", K_NUM, S(mass), 0, R_POS, 0, 0, NULL, "kg",
     "required (or density)", "particle mass"},
    {"species", "density", K_NUM, S(density), 0, R_POS, 0, 0, NULL,
     "kg/m^3", "-", "mass of a sphere of this density"},
    {"species", "tau", K_NUM, S(tau), 0, R_POSINF, 0, 0, NULL, "s",
     "from mu", "relaxation time; inf = free flight"},
    {"species", "mu", K_NUM, S(mu), 0, R_POS, 0, 0, NULL, "Pa s", "-",
     "viscosity: Stokes tau = rho d^2 Cc/(18 mu)"},
    {"species", "cunningham", K_NUM, S(cc), 0, R_CLOSED, 1, 1e300, NULL, "-",
     "1", "slip correction of the Stokes tau"},
    {"species", "B", K_NUM, S(B), 0, R_NONNEG, 0, 0, NULL, "m s^-3/2",
     "from T", "velocity diffusion coefficient"},
    {"species", "b2", K_NUM, S(b2), 0, R_POS, 0, 0, NULL, "m^2/s", "-",
     "position variance rate B_pos^2 (diffusive limit): B = sqrt(b2)/tau"},
    {"species", "T", K_NUM, S(T), 0, R_NONNEG, 0, 0, NULL, "K", "0",
     "temperature of the velocities (B = sqrt(2 k_B T/(m tau)))"},
    {"species", "count", K_INT, S(count), 0, R_CLOSED, 0, 1e9, NULL, "-",
     "- (or phi, particle)", "particles placed by `placement`"},
    {"species", "phi", K_NUM, S(phi), 0, R_CLOSED, 0, 0.5, NULL, "-", "-",
     "volume (area) fraction"},
    {"species", "particle", K_PARTICLE, 0, 0, R_ANY, 4, 6, NULL, "m, m/s",
     "-", "x y z ux uy uz (2-D: x y ux uy); repeatable, up to 64"},
    {"species", "drag", K_NAME, S(drag), 24, R_ANY, 0, 0, DRAGS, "-",
     "stokes", "drag law (schiller-naumann: non-Brownian, needs a mu)"},
    {"species", "family", K_INT, S(family), 0, R_CLOSED, 0,
     SB_ENGINE_MAXFAM - 1, NULL, "-", "0", "family tag"},
    {"species", "region", K_VEC, S(region), S(nregion), R_ANY, 4, 6, NULL,
     "m", "whole box", "x0 x1 y0 y1 [z0 z1] of the placement"},
    {"species", "drift", K_VEC, S(drift), S(ndrift), R_ANY, 2, 3, NULL,
     "m/s", "0", "added to the placed particles' velocities"},
    {"species", "inflow", K_NAME, S(inflow), 16, R_ANY, 0, 0, FACES, "-",
     "- (none)", "face through which a stream of this species enters"},
    {"species", "inflow_rate", K_NUM, S(inflow_rate), 0, R_POS, 0, 0, NULL,
     "1/s", "required with inflow",
     "particles per second through the inlet (density x u_n x area)"},
    {"species", "inflow_region", K_VEC, S(inflow_region), S(ninflow_region),
     R_ANY, 2, 4, NULL, "m", "whole face",
     "inlet: lo hi along the face's first other axis [, lo hi along the "
     "second]"},
    {"species", "inflow_velocity", K_VEC, S(inflow_u), S(ninflow_u), R_ANY,
     2, 3, NULL, "m/s", "required with inflow",
     "velocity of the entering particles (normal part inward)"},
    {"species", "inflow_no_overlap", K_BOOL, S(inflow_no_overlap), 0, R_ANY,
     0, 0, BOOLS, "-", "no", "redraw an entering particle that overlaps"},
};
#define NKEYS (sizeof KEYS / sizeof KEYS[0])

static const char *const *names_of(const keydef *k)
{
  return k->names ? k->names : col_detect_names();
}

static void join(char *buf, size_t len, const char *const *names)
{
  buf[0] = 0;
  for (int i = 0; names[i]; i++) {
    size_t n = strlen(buf);
    snprintf(buf + n, len - n, "%s%s", i ? ", " : "", names[i]);
  }
}

static void range_text(const keydef *k, char *buf, size_t len)
{
  if (k->type == K_NAME || k->type == K_BOOL) {
    join(buf, len, names_of(k));
    return;
  }
  switch (k->range) {
  case R_POS: snprintf(buf, len, "> 0"); break;
  case R_POSINF: snprintf(buf, len, "> 0, or inf"); break;
  case R_NONNEG: snprintf(buf, len, ">= 0"); break;
  case R_CLOSED:
    if (k->type == K_INT || k->type == K_SEED)
      snprintf(buf, len, "integer %.0f .. %.0f", k->lo, k->hi);
    else if (k->hi >= 1e300)
      snprintf(buf, len, ">= %g", k->lo);
    else
      snprintf(buf, len, "%g .. %g", k->lo, k->hi);
    break;
  default:
    if (k->type == K_VEC || k->type == K_PARTICLE)
      snprintf(buf, len, "%.0f to %.0f numbers", k->lo, k->hi);
    else if (k->type == K_PATH)
      snprintf(buf, len, "a path");
    else
      snprintf(buf, len, "a finite number");
  }
}

void col_print_keys(FILE *f)
{
  const char *sec = "";
  int w = 16;  /* the longest key sets the name column */
  for (size_t i = 0; i < NKEYS; i++)
    if ((int)strlen(KEYS[i].key) > w)
      w = (int)strlen(KEYS[i].key);
  for (size_t i = 0; i < NKEYS; i++) {
    const keydef *k = &KEYS[i];
    if (strcmp(sec, k->sec)) {
      sec = k->sec;
      fprintf(f, "\n[%s%s]\n", sec, strcmp(sec, "species") ? "" : " NAME");
    }
    char r[200];
    range_text(k, r, sizeof r);
    fprintf(f, "  %-*s %-9s default %s; %s\n  %-*s %-9s valid: %s\n", w,
            k->key, k->unit, k->def, k->help, w, "", "", r);
  }
}

/* ------------------------------------------------------------ errors */

int col_fail(col_config *c, const char *fmt, ...)
{
  if (c->nerr++ == 0) {
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(c->err, sizeof c->err, fmt, ap);
    va_end(ap);
  }
  return -1;
}

void col_warn(col_config *c, const char *fmt, ...)
{
  if (c->nwarn >= COL_MAXWARN)
    return;
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(c->warn[c->nwarn++], sizeof c->warn[0], fmt, ap);
  va_end(ap);
}

/* Copy a string into a field of the same configuration (snprintf's
 * restrict-qualified arguments must not overlap). */
static void copy(char *dst, size_t n, const char *src)
{
  size_t len = strlen(src);
  if (len >= n)
    len = n - 1;
  memmove(dst, src, len);
  dst[len] = 0;
}

/* ------------------------------------------------------------ defaults */

void col_defaults(col_config *c)
{
  memset(c, 0, sizeof *c);
  c->seed = 1;
  c->dim = 3;
  c->L = c->Lx = c->Ly = c->Lz = NAN;
  c->dt = c->t_end = NAN;
  c->steps = -1;
  c->eta = 1.0;
  c->lv_eps = c->lv_xtol = c->lv_tol = NAN;
  c->sample_every = -1;
  c->placement_seed = -1;
  strcpy(c->neigh, "cells");
  strcpy(c->detect, "ballistic");
  strcpy(c->outcome, "elastic");
  strcpy(c->rng, "mt19937");
  strcpy(c->output, "collide-out");
  strcpy(c->ends, "position");
  c->tol = 1e-9;
  c->exact_tol = 1e-3;
  c->eps = c->nu = NAN;
  c->first_hit_radius = NAN;
  strcpy(c->growth, "stokes");
  strcpy(c->erel, "contact");
  c->wmax_kT = NAN;
  c->kobs = 10;
  strcpy(c->fluid, "rest");
  c->lees = 1;
  c->mu_f = NAN;
  for (int f = 0; f < 6; f++)
    strcpy(c->wall[f], "periodic");
  strcpy(c->wall_detect, "bridge");
  strcpy(c->deposit, "remove");
}

static void species_defaults(col_species *s)
{
  memset(s, 0, sizeof *s);
  s->radius = s->diameter = s->density = s->mass = s->tau = s->mu = NAN;
  s->B = s->b2 = s->T = s->phi = NAN;
  s->cc = 1.0;
  s->count = -1;
  strcpy(s->drag, "stokes");
}

/* ------------------------------------------------------------ values */

static int is_species(const char *sec, const char **name)
{
  if (strncmp(sec, "species", 7))
    return 0;
  if (sec[7] != ' ' && sec[7] != '.' && sec[7] != ':' && sec[7])
    return 0;
  const char *n = sec[7] ? sec + 8 : sec + 7;
  while (*n == ' ')
    n++;
  *name = n;
  return 1;
}

const char *col_where(const col_config *c, const char *sec, const char *key)
{
  for (int i = c->nseen - 1; i >= 0; i--)
    if (!strcmp(c->seen[i].sec, sec) && !strcmp(c->seen[i].key, key))
      return c->seen[i].where;
  return "";
}

int col_given(const col_config *c, const char *sec, const char *key)
{
  return col_where(c, sec, key)[0] != 0;
}

const char *col_short_name(const col_config *c, size_t k)
{
  if ((int)k >= c->nsp)
    return "cluster";
  const char *n;
  return is_species(c->sp[k].name, &n) ? n : c->sp[k].name;
}

/* "value: problem" in the standard form. */
#define BAD(c, sec, key, v, ...)                                          \
  col_fail(c, "%s: [%s] %s = %s: " __VA_ARGS__)

static int parse_number(col_config *c, const char *sec, const keydef *k,
                        const char *v, double *out)
{
  char r[200];
  range_text(k, r, sizeof r);
  char *end;
  errno = 0;
  double x = strtod(v, &end);
  while (*end == ' ' || *end == '\t')
    end++;
  if (end == v || *end) {
    if (strchr(v, '#'))
      return col_fail(c, "%s: [%s] %s = %s: not a number ('#' starts a "
                      "comment only at the beginning of a line; an inline "
                      "comment starts with ';' after a space)", c->where,
                      sec, k->key, v);
    return col_fail(c, "%s: [%s] %s = %s: not a number; valid: %s%s%s",
                    c->where, sec, k->key, v, r,
                    strcmp(k->unit, "-") ? " " : "",
                    strcmp(k->unit, "-") ? k->unit : "");
  }
  int inf_ok = k->range == R_POSINF && isinf(x) && x > 0;
  if (isnan(x) || (isinf(x) && !inf_ok) || (errno == ERANGE && !inf_ok &&
                                            fabs(x) > 1.0))
    return col_fail(c, "%s: [%s] %s = %s: not a finite number; valid: %s",
                    c->where, sec, k->key, v, r);
  int ok = 1;
  switch (k->range) {
  case R_POS: ok = x > 0; break;
  case R_POSINF: ok = x > 0; break;
  case R_NONNEG: ok = x >= 0; break;
  case R_CLOSED: ok = x >= k->lo && x <= k->hi; break;
  default: break;
  }
  if (ok && (k->type == K_INT || k->type == K_SEED) && x != floor(x))
    return col_fail(c, "%s: [%s] %s = %s: not an integer; valid: %s",
                    c->where, sec, k->key, v, r);
  if (!ok)
    return col_fail(c, "%s: [%s] %s = %s: out of range; valid: %s%s%s",
                    c->where, sec, k->key, v, r,
                    strcmp(k->unit, "-") ? " " : "",
                    strcmp(k->unit, "-") ? k->unit : "");
  *out = x;
  return 0;
}

static int parse_list(col_config *c, const char *sec, const keydef *k,
                      const char *v, double *out, int *n)
{
  int cnt = 0, nmax = (int)k->hi, nmin = (int)k->lo;
  const char *p = v;
  while (*p) {
    while (*p == ' ' || *p == '\t' || *p == ',')
      p++;
    if (!*p)
      break;
    char *end;
    errno = 0;
    double x = strtod(p, &end);
    if (end == p || !isfinite(x) || (errno == ERANGE && fabs(x) > 1.0))
      return col_fail(c, "%s: [%s] %s = %s: not a list of %d to %d finite "
                      "numbers%s", c->where, sec, k->key, v, nmin, nmax,
                      strchr(v, '#') ? " ('#' starts a comment only at the "
                      "beginning of a line; use ';' after a space)" : "");
    if (cnt == nmax)
      return col_fail(c, "%s: [%s] %s = %s: more than %d numbers", c->where,
                      sec, k->key, v, nmax);
    out[cnt++] = x;
    p = end;
  }
  if (cnt < nmin)
    return col_fail(c, "%s: [%s] %s = %s: %d numbers; valid: %d to %d",
                    c->where, sec, k->key, v, cnt, nmin, nmax);
  *n = cnt;
  return 0;
}

static col_species *species_for(col_config *c, const char *sec)
{
  for (int k = 0; k < c->nsp; k++)
    if (!strcmp(c->sp[k].name, sec))
      return &c->sp[k];
  if (c->nsp == COL_MAXSPEC) {
    col_fail(c, "%s: [%s]: more than %d species sections", c->where, sec,
             COL_MAXSPEC);
    return NULL;
  }
  col_species *s = &c->sp[c->nsp++];
  species_defaults(s);
  copy(s->name, sizeof s->name, sec);
  copy(s->where, sizeof s->where, c->where);
  for (int i = 0; i < c->nsections; i++)  /* its header, if read */
    if (!strcmp(c->sections[i], sec))
      copy(s->where, sizeof s->where, c->section_where[i]);
  return s;
}

static const keydef *find_key(const char *sec, const char *key)
{
  for (size_t i = 0; i < NKEYS; i++)
    if (!strcmp(KEYS[i].sec, sec) && !strcmp(KEYS[i].key, key))
      return &KEYS[i];
  return NULL;
}

static void keys_of(const char *sec, char *buf, size_t len)
{
  buf[0] = 0;
  for (size_t i = 0; i < NKEYS; i++)
    if (!strcmp(KEYS[i].sec, sec)) {
      size_t n = strlen(buf);
      snprintf(buf + n, len - n, "%s%s", n ? ", " : "", KEYS[i].key);
    }
}

/* Set one key (c->where names its origin).  override: --set. */
static int set_key(col_config *c, const char *section, const char *key,
                   const char *value, int override)
{
  char sec[72];
  const char *sname;
  int species = is_species(section, &sname);
  if (species) {
    if (!*sname)
      return col_fail(c, "%s: [%s]: a species section needs a name: "
                      "[species NAME]", c->where, section);
    snprintf(sec, sizeof sec, "species %s", sname);
  } else
    copy(sec, sizeof sec, section);
  const keydef *k = find_key(species ? "species" : sec, key);
  if (!k) {
    char valid[600];
    keys_of(species ? "species" : sec, valid, sizeof valid);
    if (!valid[0])
      return col_fail(c, "%s: unknown section [%s]; valid: [run], [fluid], "
                      "[walls], [bridge], [turbulence], [observe], [agglo], "
                      "[species NAME]", c->where, section);
    return col_fail(c, "%s: [%s] %s: unknown key; valid: %s", c->where, sec,
                    key, valid);
  }
  if (k->type != K_PARTICLE) {
    for (int i = 0; i < c->nseen; i++)
      if (!strcmp(c->seen[i].sec, sec) && !strcmp(c->seen[i].key, key)) {
        if (override) {
          snprintf(c->seen[i].where, sizeof c->seen[i].where, "%s",
                   c->where);
          c->seen[i].override = 1;
          goto store;
        }
        if (!c->seen[i].override)
          return col_fail(c, "%s: [%s] %s given twice (first at %s); give "
                          "each key once", c->where, sec, key,
                          c->seen[i].where);
      }
  }
  if (c->nseen == COL_MAXSEEN)
    return col_fail(c, "%s: more than %d keys", c->where, COL_MAXSEEN);
  col_seen *sn = &c->seen[c->nseen++];
  copy(sn->sec, sizeof sn->sec, sec);
  copy(sn->key, sizeof sn->key, key);
  copy(sn->where, sizeof sn->where, c->where);
  sn->override = override;
store:;
  col_species *sp = NULL;
  if (species && !(sp = species_for(c, sec)))
    return -1;
  char *base = species ? (char *)sp : (char *)c;
  void *field = base + k->off;
  double x;
  int n;
  switch (k->type) {
  case K_NUM:
    return parse_number(c, sec, k, value, (double *)field);
  case K_INT:
    if (parse_number(c, sec, k, value, &x))
      return -1;
    *(long *)field = (long)x;
    return 0;
  case K_SEED:
    if (parse_number(c, sec, k, value, &x))
      return -1;
    *(unsigned long *)field = (unsigned long)x;
    return 0;
  case K_NAME:
  case K_BOOL: {
    const char *const *names = names_of(k);
    for (int i = 0; names[i]; i++)
      if (!strcmp(value, names[i])) {
        if (k->type == K_BOOL)
          *(long *)field = i == 0;
        else
          copy((char *)field, k->aux, value);
        return 0;
      }
    char valid[300];
    join(valid, sizeof valid, names);
    return col_fail(c, "%s: [%s] %s = %s: unknown; valid: %s%s", c->where,
                    sec, key, value, valid,
                    strchr(value, '#') ? " ('#' starts a comment only at "
                    "the beginning of a line; use ';' after a space)" : "");
  }
  case K_PATH:
    if (strlen(value) >= 512)
      return col_fail(c, "%s: [%s] %s: path longer than 511 characters",
                      c->where, sec, key);
    if (!value[0])
      return col_fail(c, "%s: [%s] %s: empty path", c->where, sec, key);
    copy((char *)field, 512, value);
    return 0;
  case K_VEC:
    if (parse_list(c, sec, k, value, (double *)field, &n))
      return -1;
    *(int *)(base + k->aux) = n;
    return 0;
  case K_PARTICLE: {
    double q[6];
    if (sp->npart == COL_MAXPART)
      return col_fail(c, "%s: [%s] particle: more than %d; use count with "
                      "region for more", c->where, sec, COL_MAXPART);
    if (parse_list(c, sec, k, value, q, &n))
      return -1;
    if (n == 5)
      return col_fail(c, "%s: [%s] particle = %s: 5 numbers; valid: 4 "
                      "(2-D: x y ux uy) or 6 (3-D: x y z ux uy uz)",
                      c->where, sec, value);
    double *o = sp->part[sp->npart];
    if (n == 4) {
      o[0] = q[0], o[1] = q[1], o[2] = 0, o[3] = q[2], o[4] = q[3];
      o[5] = 0;
    } else
      memcpy(o, q, sizeof q);
    copy(sp->part_where[sp->npart], COL_WHERE, c->where);
    sp->part_n[sp->npart++] = n;
    return 0;
  }
  }
  return col_fail(c, "%s: [%s] %s: internal error", c->where, sec, key);
}

/* ------------------------------------------------------------ INI file */

typedef struct {
  FILE *f;
  col_config *c;
  const char *path;
  int line;
  int indented;        /* the current line starts with a blank */
  int stop;
} reader;

/* Record a section header the reader sees (inih does not report
 * them): a repeated header would silently merge two sections. */
static void header(reader *r, const char *s)
{
  const char *e = strchr(s, ']');
  if (!e)
    return;
  char name[72];
  size_t n = (size_t)(e - s - 1);
  if (n >= sizeof name)
    n = sizeof name - 1;
  memcpy(name, s + 1, n);
  name[n] = 0;
  /* normalise "species.x" / "species:x" like the keys */
  const char *sn;
  if (is_species(name, &sn)) {
    char tmp[72];
    snprintf(tmp, sizeof tmp, "species %s", sn);
    copy(name, sizeof name, tmp);
  }
  col_config *c = r->c;
  for (int i = 0; i < c->nsections; i++)
    if (!strcmp(c->sections[i], name)) {
      col_fail(c, "%s:%d: section [%s] repeated (first at %s); put its "
               "keys in one section", r->path, r->line, name,
               c->section_where[i]);
      return;
    }
  if (c->nsections < COL_MAXSPEC + 8) {
    copy(c->sections[c->nsections], sizeof c->sections[0], name);
    snprintf(c->section_where[c->nsections], COL_WHERE, "%s:%d", r->path,
             r->line);
    c->nsections++;
  }
}

static char *read_line(char *str, int num, void *stream)
{
  reader *r = stream;
  if (r->stop || !fgets(str, num, r->f))
    return NULL;
  r->line++;
  size_t n = strlen(str);
  if (n == (size_t)num - 1 && str[n - 1] != '\n' && !feof(r->f)) {
    col_fail(r->c, "%s:%d: line longer than %d characters (the limit of "
             "the INI reader, libinih); shorten it", r->path, r->line,
             num - 2);
    r->stop = 1;
    return NULL;
  }
  const char *s = str;
  r->indented = (*s == ' ' || *s == '\t');
  while (*s == ' ' || *s == '\t')
    s++;
  if (*s == '[')
    header(r, s);
  return str;
}

static int handler(void *user, const char *sec, const char *key,
                   const char *value)
{
  reader *r = user;
  col_config *c = r->c;
  snprintf(c->where, sizeof c->where, "%s:%d", r->path, r->line);
  if (r->indented) {
    col_fail(c, "%s: the line starts with a blank: the INI reader takes "
             "an indented line as the continuation of the previous value "
             "([%s] %s); write keys at the start of the line", c->where,
             sec, key);
    return 0;
  }
  if (!sec[0]) {
    col_fail(c, "%s: %s = %s before any section; put it under [run], "
             "[fluid], ... or [species NAME]", c->where, key, value);
    return 0;
  }
  return set_key(c, sec, key, value, 0) == 0;
}

int col_read_file(col_config *c, const char *path)
{
  struct stat st;
  if (stat(path, &st))
    return col_fail(c, "%s: cannot read: %s", path, strerror(errno));
  if (S_ISDIR(st.st_mode))
    return col_fail(c, "%s: is a directory, not a configuration file",
                    path);
  reader r = {fopen(path, "r"), c, path, 0, 0, 0};
  if (!r.f)
    return col_fail(c, "%s: cannot read: %s", path, strerror(errno));
  /* handler and reader share the reader struct */
  int line = ini_parse_stream(read_line, &r, handler, &r);
  int err = ferror(r.f);
  fclose(r.f);
  if (err)
    return col_fail(c, "%s: read error", path);
  if (c->nerr)
    return -1;
  if (line > 0)
    return col_fail(c, "%s:%d: not 'key = value', '[section]' or a "
                    "comment", path, line);
  if (c->nseen == 0)
    return col_fail(c, "%s: no keys (empty file?); a configuration needs "
                    "at least [run] L, dt, t_end or steps, and a [species "
                    "NAME] section", path);
  return 0;
}

int col_override(col_config *c, const char *arg)
{
  snprintf(c->where, sizeof c->where, "--set %s", arg);
  const char *eq = strchr(arg, '=');
  char path[200];
  size_t n = eq ? (size_t)(eq - arg) : 0;
  if (!eq || n == 0 || n >= sizeof path)
    return col_fail(c, "--set %s: expected SECTION.KEY=VALUE (e.g. "
                    "run.dt=1e-7, species.NAME.phi=1e-3)", arg);
  memcpy(path, arg, n);
  path[n] = 0;
  char *dot = strrchr(path, '.');
  if (!dot || dot == path || !dot[1])
    return col_fail(c, "--set %s: expected SECTION.KEY=VALUE (e.g. "
                    "run.dt=1e-7, species.NAME.phi=1e-3)", arg);
  *dot = 0;
  if (c->noverrides < 32)
    snprintf(c->overrides[c->noverrides++], sizeof c->overrides[0], "%s",
             arg);
  const char *sn;
  if (is_species(path, &sn) && c->nsp) {
    char sec[72];
    snprintf(sec, sizeof sec, "species %s", sn);
    int found = 0;
    for (int k = 0; k < c->nsp; k++)
      found |= !strcmp(c->sp[k].name, sec);
    if (!found) {
      char names[400] = "";
      for (int k = 0; k < c->nsp; k++) {
        size_t m = strlen(names);
        snprintf(names + m, sizeof names - m, "%s%s", k ? ", " : "",
                 col_short_name(c, (size_t)k));
      }
      return col_fail(c, "--set %s: no section [%s]; species: %s", arg, sec,
                      names);
    }
  }
  return set_key(c, path, dot + 1, eq + 1, 1);
}

/* ------------------------------------------------------------ checks */

int col_agglo(const col_config *c)
{
  return !strcmp(c->outcome, "merge") || !strcmp(c->outcome, "dlvo");
}

int col_bridge(const col_config *c)
{
  for (int k = 0; CONTEXT_DETECTORS[k]; k++)
    if (!strcmp(c->detect, CONTEXT_DETECTORS[k]))
      return 1;
  return 0;
}

/* Two keys that set the same thing. */
static int seen_index(const col_config *c, const char *sec, const char *key)
{
  for (int i = c->nseen - 1; i >= 0; i--)
    if (!strcmp(c->seen[i].sec, sec) && !strcmp(c->seen[i].key, key))
      return i;
  return -1;
}

/* Two keys that set the same thing: the later one is reported. */
static int conflict(col_config *c, const char *sec, const char *a,
                    const char *b, const char *why)
{
  int ia = seen_index(c, sec, a), ib = seen_index(c, sec, b);
  if (ia < 0 || ib < 0)
    return 0;
  if (ia > ib) {
    const char *t = a;
    a = b;
    b = t;
  }
  return col_fail(c, "%s: [%s] %s conflicts with %s (at %s): %s",
                  col_where(c, sec, b), sec, b, a, col_where(c, sec, a),
                  why);
}

/* A key given where it has no effect. */
static void unused(col_config *c, const char *sec, const char *key,
                   const char *why)
{
  if (col_given(c, sec, key))
    col_warn(c, "%s: [%s] %s ignored: %s", col_where(c, sec, key), sec, key,
             why);
}

static int section_given(const col_config *c, const char *sec)
{
  for (int i = 0; i < c->nseen; i++)
    if (!strcmp(c->seen[i].sec, sec))
      return 1;
  return 0;
}

static void section_unused(col_config *c, const char *sec, const char *why)
{
  for (int i = 0; i < c->nseen; i++)
    if (!strcmp(c->seen[i].sec, sec)) {
      col_warn(c, "%s: [%s] ignored: %s", c->seen[i].where, sec, why);
      return;
    }
}

int col_check(col_config *c)
{
  if (c->nerr)
    return -1;
  const char *run = "run";
  if (conflict(c, run, "L", "Lx", "L sets all edges") ||
      conflict(c, run, "L", "Ly", "L sets all edges") ||
      conflict(c, run, "L", "Lz", "L sets all edges") ||
      conflict(c, run, "t_end", "steps",
               "give the end time or the number of measured steps") ||
      conflict(c, "agglo", "wmax", "wmax_kT", "two values of the barrier"))
    return -1;
  if (!isnan(c->L))
    c->Lx = c->Ly = c->Lz = c->L;
  if (c->dim == 2)
    unused(c, run, "Lz", "dim = 2");
  /* restart: the state comes from the checkpoint */
  if (c->restart[0]) {
    static const char *const kept[] = {"dim", "L", "Lx", "Ly", "Lz",
                                       "seed", "rng", "placement",
                                       "placement_seed", "thermalize",
                                       "warmup", NULL};
    for (int i = 0; kept[i]; i++)
      unused(c, run, kept[i], "the state comes from the restart "
             "checkpoint");
    for (int k = 0; k < c->nsp; k++)
      col_warn(c, "%s: [%s] ignored: the particles come from the restart "
               "checkpoint", c->sp[k].where, c->sp[k].name);
    if (col_agglo(c))
      return col_fail(c, "%s: [run] restart with outcome = %s: the cluster "
                      "sizes are not in a checkpoint; run merging in one "
                      "go", col_where(c, run, "restart"), c->outcome);
    if (c->first_hit)
      return col_fail(c, "%s: [observe] first_hit with restart: the "
                      "counted pairs are not in a checkpoint",
                      col_where(c, "observe", "first_hit"));
  } else {
    if (isnan(c->Lx) || isnan(c->Ly) || (c->dim == 3 && isnan(c->Lz)))
      return col_fail(c, "[run] L (or Lx, Ly%s) is required: the box "
                      "edge in m", c->dim == 3 ? ", Lz" : "");
    if (c->nsp == 0)
      return col_fail(c, "no [species NAME] section: give at least one "
                      "with radius, mass (or density), tau (or mu) and "
                      "count, phi or particle");
  }
  if (isnan(c->dt) && !c->restart[0])
    return col_fail(c, "[run] dt is required: the time step in s");
  if (isnan(c->t_end) && c->steps < 0)
    return col_fail(c, "[run] t_end or steps is required");
  /* detector and outcome */
  const int bridge = col_bridge(c), agglo = col_agglo(c);
  if (bridge && c->dim != 3)
    return col_fail(c, "%s: [run] detect = %s needs dim = 3",
                    col_where(c, run, "detect"), c->detect);
  if (!strcmp(c->outcome, "correction") && !bridge)
    return col_fail(c, "%s: [run] outcome = correction (the correction "
                    "step of the bridge detectors) needs detect = bridge "
                    "or exact", col_where(c, run, "outcome"));
  if (bridge && !strcmp(c->outcome, "elastic"))
    return col_fail(c, "%s: [run] outcome = elastic with detect = %s: the "
                    "bridge detectors have no contact velocity; valid: "
                    "reinsert, count, correction, merge, dlvo",
                    col_given(c, run, "outcome") ? col_where(c, run,
                                                             "outcome")
                                                 : col_where(c, run,
                                                             "detect"),
                    c->detect);
  if (!bridge)
    section_unused(c, "bridge", "only detect = bridge or exact use it");
  if (!bridge && section_given(c, "turbulence"))
    return col_fail(c, "%s: [turbulence] needs detect = bridge or exact "
                    "(turbulent pair diffusion is a bridge model)",
                    col_where(c, "turbulence", col_given(c, "turbulence",
                                                         "eps")
                                                   ? "eps"
                                                   : "nu"));
  if (col_given(c, "turbulence", "eps") != col_given(c, "turbulence", "nu"))
    return col_fail(c, "[turbulence] needs both eps and nu");
  if (!strcmp(c->detect, "bridge"))
    unused(c, "bridge", "exact_tol", "detect = bridge (only exact uses it)");
  if (!agglo)
    section_unused(c, "agglo", "outcome is not merge or dlvo");
  else if (strcmp(c->outcome, "dlvo")) {
    unused(c, "agglo", "wmax", "outcome = merge (no barrier)");
    unused(c, "agglo", "wmax_kT", "outcome = merge (no barrier)");
    unused(c, "agglo", "erel", "outcome = merge");
    unused(c, "agglo", "erel_normal", "outcome = merge");
  }
  if (strcmp(c->detect, "langevin")) {
    unused(c, run, "langevin_eps", "only detect = langevin uses it");
    unused(c, run, "langevin_xtol", "only detect = langevin uses it");
    unused(c, run, "langevin_tol", "only detect = langevin uses it");
  }
  if (strcmp(c->outcome, "elastic") && strcmp(c->outcome, "dlvo"))
    unused(c, run, "eta", "only outcome = elastic or dlvo (rebounds) "
           "use it");
  /* observers */
  if (c->hit_times && !bridge)
    return col_fail(c, "%s: [observe] hit_times records bridge hits: "
                    "needs detect = bridge or exact",
                    col_where(c, "observe", "hit_times"));
  if (c->first_hit) {
    if (strcmp(c->outcome, "count"))
      return col_fail(c, "%s: [observe] first_hit needs outcome = count "
                      "(pairs pass through each other)",
                      col_where(c, "observe", "first_hit"));
    if (c->nsp != 1)
      return col_fail(c, "%s: [observe] first_hit needs exactly one "
                      "species (the reference is one pair type)",
                      col_where(c, "observe", "first_hit"));
    if (c->dim != 3)
      return col_fail(c, "%s: [observe] first_hit needs dim = 3 (the "
                      "reference is the 3-D Smoluchowski transient)",
                      col_where(c, "observe", "first_hit"));
    if (c->first_hit_capacitance &&
        conflict(c, "observe", "first_hit_capacitance", "first_hit_radius",
                 "two reference radii"))
      return -1;
  } else {
    unused(c, "observe", "first_hit_radius", "first_hit = no");
    unused(c, "observe", "first_hit_capacitance", "first_hit = no");
    unused(c, "observe", "first_hit_skip_seen", "first_hit = no");
  }
  /* fluid */
  if (!strcmp(c->fluid, "rest")) {
    unused(c, "fluid", "U", "type = rest");
    unused(c, "fluid", "G", "type = rest");
  } else if (!strcmp(c->fluid, "uniform")) {
    unused(c, "fluid", "G", "type = uniform");
    if (!col_given(c, "fluid", "U"))
      return col_fail(c, "%s: [fluid] type = uniform needs U (m/s)",
                      col_where(c, "fluid", "type"));
  } else if (!strcmp(c->fluid, "shear")) {
    unused(c, "fluid", "U", "type = shear");
    if (!col_given(c, "fluid", "G"))
      return col_fail(c, "%s: [fluid] type = shear needs G (1/s)",
                      col_where(c, "fluid", "type"));
  }
  if (c->nU && c->nU != c->dim)
    return col_fail(c, "%s: [fluid] U: %d numbers for dim = %ld",
                    col_where(c, "fluid", "U"), c->nU, c->dim);
  if (strcmp(c->placement, "uniform"))
    unused(c, run, "placement_seed", "only placement = uniform uses it");
  /* species */
  for (int k = 0; k < c->nsp && !c->restart[0]; k++) {
    col_species *s = &c->sp[k];
    const char *n = s->name;
    if (conflict(c, n, "radius", "diameter", "give one of them") ||
        conflict(c, n, "mass", "density", "the mass follows from the "
                 "density; give one of them") ||
        conflict(c, n, "tau", "mu", "mu gives the Stokes tau; give one of "
                 "them") ||
        conflict(c, n, "count", "phi", "both set the number of "
                 "particles") ||
        conflict(c, n, "B", "b2", "b2 sets B = sqrt(b2)/tau") ||
        conflict(c, n, "B", "T", "T sets B = sqrt(2 k_B T/(m tau)); give "
                 "B with T = 0, or T") ||
        conflict(c, n, "b2", "T", "b2 sets the noise and the velocities; "
                 "T those of a thermal species"))
      return -1;
    if (!isnan(s->diameter))
      s->radius = 0.5 * s->diameter;
    if (isnan(s->radius))
      return col_fail(c, "%s: [%s]: radius (or diameter) is required",
                      s->where, n);
    if (isnan(s->mass) && isnan(s->density))
      return col_fail(c, "%s: [%s]: mass (kg) or density (kg/m^3) is "
                      "required", s->where, n);
    if (isnan(s->tau) && isnan(s->mu))
      return col_fail(c, "%s: [%s]: tau (s, or inf for free flight) or mu "
                      "(Pa s, Stokes tau) is required", s->where, n);
    if (!isnan(s->mu) && isnan(s->density))
      return col_fail(c, "%s: [%s] mu: the Stokes tau needs density, not "
                      "mass", col_where(c, n, "mu"), n);
    if (isnan(s->mu))
      unused(c, n, "cunningham", "no mu (tau is given)");
    if (s->count < 0 && isnan(s->phi) && s->npart == 0 && !s->inflow[0])
      return col_fail(c, "%s: [%s]: count, phi, particle or inflow is "
                      "required", s->where, n);
    if (s->inflow[0]) {
      if (isnan(s->inflow_rate) || s->ninflow_u == 0)
        return col_fail(c, "%s: [%s] inflow: inflow_rate (1/s) and "
                        "inflow_velocity (m/s) are required",
                        col_where(c, n, "inflow"), n);
      if (s->ninflow_u != c->dim)
        return col_fail(c, "%s: [%s] inflow_velocity: %d numbers for dim "
                        "= %ld", col_where(c, n, "inflow_velocity"), n,
                        s->ninflow_u, c->dim);
      if (s->ninflow_region && s->ninflow_region != 2 * (c->dim - 1))
        return col_fail(c, "%s: [%s] inflow_region: %d numbers for dim = "
                        "%ld; valid: %ld", col_where(c, n, "inflow_region"),
                        n, s->ninflow_region, c->dim, 2 * (c->dim - 1));
    } else {
      unused(c, n, "inflow_rate", "no inflow face");
      unused(c, n, "inflow_region", "no inflow face");
      unused(c, n, "inflow_velocity", "no inflow face");
      unused(c, n, "inflow_no_overlap", "no inflow face");
    }
    if (s->nregion && s->nregion != 2 * c->dim)
      return col_fail(c, "%s: [%s] region: %d numbers for dim = %ld; "
                      "valid: %ld (x0 x1 y0 y1%s)", col_where(c, n,
                                                              "region"),
                      n, s->nregion, c->dim, 2 * c->dim,
                      c->dim == 3 ? " z0 z1" : "");
    if (s->ndrift && s->ndrift != c->dim)
      return col_fail(c, "%s: [%s] drift: %d numbers for dim = %ld",
                      col_where(c, n, "drift"), n, s->ndrift, c->dim);
    for (int q = 0; q < s->npart; q++)
      if (s->part_n[q] != 2 * c->dim)
        return col_fail(c, "%s: [%s] particle: %d numbers for dim = %ld; "
                        "valid: %s", s->part_where[q], n, s->part_n[q],
                        c->dim, c->dim == 3 ? "6 (x y z ux uy uz)"
                                            : "4 (x y ux uy)");
  }
  return c->nerr ? -1 : 0;
}
