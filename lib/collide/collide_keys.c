/* collide_keys.c — the keys of a collision-engine configuration
 * (<smolbridge/collide.h>): one table gives each key's section, type,
 * unit, default and valid values; it drives the parser (INI text and
 * --set, collide_ini.c), the error messages and the key list of
 * `smolbridge collide --help` (sb_collide_key). */
#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include <smolbridge/engine.h>
#include <smolbridge/engine_field.h>
#include "common/internal.h"

#include "collide_internal.h"

/* ------------------------------------------------------------ names */

static const char *const OUTCOMES[] = {"elastic", "reinsert", "count",
                                       "correction", "merge", "dlvo", NULL};
static const char *const NEIGHS[] = {"cells", "sweep", "brute", NULL};
static const char *const RNGS[] = {"mt19937", "taus2", "philox", NULL};
static const char *const PLACEMENTS[] = {"random", "lattice", "uniform",
                                         NULL};
static const char *const FLUIDS[] = {"rest", "uniform", "shear",
                                     "ou-field", "kraichnan", NULL};
static const char *const GROWTHS[] = {"stokes", "constant", NULL};
static const char *const ERELS[] = {"contact", "stationary", NULL};
static const char *const ENDS[] = {"position", "diffusive", NULL};
static const char *const BOOLS[] = {"yes", "no", NULL};
static const char *const GRIDSCHEMES[] = {"ngp", "cic", NULL};
static const char *const DRAGS[] = {"stokes", "schiller-naumann", NULL};
static const char *const WALLS[] = {"periodic", "reflect", "absorb", "open",
                                    NULL};
static const char *const FACES[] = {"x_lo", "x_hi", "y_lo", "y_hi", "z_lo",
                                    "z_hi", NULL};
static const char *const WALLDETS[] = {"bridge", "ballistic", "langevin",
                                       NULL};
static const char *const DEPOSITS[] = {"remove", "reinsert", NULL};
static const char *const STARTS[] = {"placed", "antipodal", NULL};

/* Detectors with a context of their own (lib/engine/engine_bridge.c);
 * a new one is a name here and a branch in collide_setup.c. */
static const char *const CONTEXT_DETECTORS[] = {"bridge", "exact", NULL};
static const char *const PROFILES[] = {"uniform", "parabolic", NULL};

/* Built at each call (no static state: the library is thread-safe). */
const char **sbi_col_detect_names(const char **names, size_t len)
{
  size_t n = 0;  /* the engine's built-ins first, in its order */
  const char *const *b = sb_engine_detect_names();
  for (int k = 0; b[k] && n + 1 < len; k++)
    names[n++] = b[k];
  for (int k = 0; CONTEXT_DETECTORS[k] && n + 1 < len; k++)
    names[n++] = CONTEXT_DETECTORS[k];
  if (n + 1 < len)  /* no particle-particle detection (collide_walls.c) */
    names[n++] = "none";
  if (n + 1 < len)  /* a custom detector of the engine (collide_setup.c) */
    names[n++] = "md";
  names[n] = NULL;
  return names;
}

int sbi_col_bridge(const sbi_col_config *c)
{
  for (int k = 0; CONTEXT_DETECTORS[k]; k++)
    if (!strcmp(c->detect, CONTEXT_DETECTORS[k]))
      return 1;
  return 0;
}

/* ------------------------------------------------------------ table */

#define C(f) offsetof(sbi_col_config, f)
#define S(f) offsetof(sbi_col_species, f)

const sbi_col_keydef sbi_col_keys[] = {
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
     "ballistic", "collision detector; none: no particle-particle "
     "contacts (walls still detect)"},
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
    {"run", "stop_every", K_NUM, C(stop_every), 0, R_POS, 0, 0, NULL, "s",
     "- (none)",
     "the run stops every this long after the warm-up: a row of sizes.csv "
     "(merging), and the bridge reach recomputed for the particle count "
     "and largest radius of that time"},
    {"run", "snapshot_every", K_INT, C(snapshot_every), 0, R_CLOSED, 0, 2e9,
     NULL, "steps", "0 (off)", "snapshot period"},
    {"run", "sort_every", K_INT, C(sort_every), 0, R_CLOSED, 0, 2e9, NULL,
     "steps", "0 (off)", "reorder particles in memory (speed)"},
    {"run", "rng", K_NAME, C(rng), 16, R_ANY, 0, 0, RNGS, "-", "philox",
     "generator type; philox (the default, fastest): per-particle "
     "counter-based streams for transport and per-pair streams for the "
     "Langevin detector (parallel; results independent of the thread "
     "count and of the particle order); mt19937, taus2: GSL generators "
     "in particle order (the validation cases)"},
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
    {"run", "velocity_seed", K_INT, C(velocity_seed), 0, R_CLOSED, 0,
     4294967295.0, NULL, "-", "- (engine generator)",
     "separate MT19937 generator for the directions of velocities = "
     "antipodal"},
    {"run", "snapshot_steps", K_VEC, C(snap_steps), C(nsnap_steps),
     R_NONNEG, 1, 64, NULL, "steps", "- (none)",
     "snapshots after these numbers of measured steps (increasing whole "
     "numbers; 0: the start of the measurement)"},
    {"run", "output", K_PATH, C(output), 0, R_ANY, 0, 0, NULL, "path",
     "collide-out", "output directory"},
    {"run", "checkpoint", K_PATH, C(checkpoint), 0, R_ANY, 0, 0, NULL,
     "path", "-", "write a checkpoint at the end, and beside it what the "
     "run keeps apart from the engine (PATH.firsthit, .agglo, .field, "
     ".contacts)"},
    {"run", "restart", K_PATH, C(restart), 0, R_ANY, 0, 0, NULL, "path", "-",
     "start from a checkpoint (and the files written beside it): the run "
     "goes on as if it had not stopped"},
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
    {"observe", "count_variance", K_BOOL, C(count_variance), 0, R_ANY, 0, 0,
     BOOLS, "-", "no", "tally each particle's and each pair's collisions "
     "for the variance of the pair kernels' counts (summary.json "
     "pair_kernels[].dispersion; their ci95 widened by its square root)"},
    {"observe", "exits", K_BOOL, C(exits), 0, R_ANY, 0, 0, BOOLS, "-", "no",
     "record every exit through an open face after the warm-up (exits.csv)"},
    {"observe", "grid", K_VEC, C(grid), C(ngrid), R_ANY, 2, 3, NULL,
     "cells", "- (off)", "nx ny [nz]: deposit the mass and momentum "
     "densities on this grid at every stop_every and at the end (grid.csv)"},
    {"observe", "grid_scheme", K_NAME, C(grid_scheme), 8, R_ANY, 0, 0,
     GRIDSCHEMES, "-", "ngp", "deposit: nearest grid point or cloud in cell"},
    {"observe", "first_hit_skip_seen", K_BOOL, C(first_hit_skip_seen), 0,
     R_ANY, 0, 0, BOOLS, "-", "no", "do not pass pairs whose first contact "
     "is known to the detector (fewer draws)"},
    {"observe", "first_hit_velocities", K_INT, C(first_hit_vn), 0, R_CLOSED,
     0, 1e8, NULL, "-", "0", "record the normal relative velocity of up to "
     "this many first contacts (contacts.csv; detect = langevin or "
     "ballistic)"},
    {"observe", "batch_steps", K_INT, C(batch_steps), 0, R_CLOSED, 0, 2e9,
     NULL, "steps", "0 (off)", "cut the measurement into batches of this "
     "many steps: one row per batch of drops injected and leaving, "
     "collisions, exiting mass, momentum and mass-weighted exit "
     "coordinates per open face, mean mass in each region (batches.csv); "
     "batch means with t intervals"},
    {"observe", "region", K_REGION, 0, 0, R_ANY, 4, 6, NULL, "m",
     "- (none)", "x0 x1 y0 y1 [z0 z1]: a box whose mass is sampled every "
     "region_every steps, its batch mean a column of batches.csv "
     "(repeatable, up to 8)"},
    {"observe", "region_every", K_INT, C(region_every), 0, R_CLOSED, 1, 2e9,
     NULL, "steps", "1", "steps between the samples of the regions"},
    {"observe", "msd_every", K_INT, C(msd_every), 0, R_CLOSED, 0, 2e9, NULL,
     "steps", "0", "sample the unwrapped positions every this many steps: "
     "mean-square displacement (msd.csv) and self-diffusion coefficient"},
    {"observe", "msd_fit", K_VEC, C(msd_fit), C(nmsd_fit), R_NONNEG, 2, 2,
     NULL, "samples", "kmax/4 kmax/2", "lags k1 < k2 of the slope that "
     "gives D"},
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
    {"fluid", "u2", K_NUM, C(ou_u2), 0, R_NONNEG, 0, 0, NULL, "m^2/s^2",
     "required with ou-field",
     "type = ou-field: per-component variance u'^2 of the seen velocity"},
    {"fluid", "T_L", K_NUM, C(ou_TL), 0, R_POS, 0, 0, NULL, "s",
     "required with ou-field",
     "type = ou-field: Lagrangian correlation time of the seen velocity"},
    {"fluid", "stationary_start", K_BOOL, C(ou_stationary), 0, R_ANY, 0, 0,
     BOOLS, "-", "yes",
     "type = ou-field: placed particles start from the stationary joint "
     "law of (u, U) of the engine's step"},
    {"fluid", "shell", K_INT, C(kr_shell), 0, R_CLOSED, 1,
     SB_FIELD_KRAICHNAN_MAXM, NULL, "-", "2",
     "type = kraichnan: wave vectors 2 pi m/L with M - 1/2 < |m| < M + 1/2 "
     "(M = 1, 2, 3: 9, 31, 49 modes)"},
    {"fluid", "eps_nu", K_NUM, C(kr_eps_nu), 0, R_POS, 0, 0, NULL, "1/s^2",
     "required with kraichnan",
     "type = kraichnan: velocity-gradient variance <A_ij A_ij> = eps/nu"},
    {"fluid", "omega", K_NUM, C(kr_omega), 0, R_NONNEG, 0, 0, NULL, "1/s",
     "0 (frozen)", "type = kraichnan: sd of the mode frequencies"},
    {"fluid", "seed", K_INT, C(field_seed), 0, R_CLOSED, 0, 4294967295.0,
     NULL, "-", "- (engine generator)",
     "ou-field, kraichnan: separate MT19937 generator of the field"},
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
    {"species", "profile", K_NAME, S(profile), 16, R_ANY, 0, 0, PROFILES,
     "-", "uniform",
     "placement = uniform: density across walled directions; parabolic: "
     "(x - lo)(hi - x) between the contact planes (steady profile of a "
     "uniform source between absorbing walls)"},
    {"species", "drift", K_VEC, S(drift), S(ndrift), R_ANY, 2, 3, NULL,
     "m/s", "0", "added to the placed particles' velocities"},
    {"species", "velocities", K_NAME, S(velocities), 16, R_ANY, 0, 0, STARTS,
     "-", "placed", "antipodal: every speed sqrt(3 k_B T/m), directions "
     "uniform in antipodal pairs (zero momentum)"},
    {"species", "velocity_scale", K_VEC, S(vscale), S(nvscale), R_NONNEG, 2,
     3, NULL, "-", "1 1 1", "multiply the placed particles' velocity "
     "components (after thermalize): per-axis temperatures s_k^2 T"},
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
const size_t sbi_col_nkeys = sizeof sbi_col_keys / sizeof sbi_col_keys[0];

const char *const *sbi_col_names_of(const sbi_col_keydef *k,
                                    const char **names, size_t len)
{
  return k->names ? k->names : sbi_col_detect_names(names, len);
}

void sbi_col_join(char *buf, size_t len, const char *const *names)
{
  buf[0] = 0;
  for (int i = 0; names[i]; i++) {
    size_t n = strlen(buf);
    snprintf(buf + n, len - n, "%s%s", i ? ", " : "", names[i]);
  }
}

void sbi_col_range_text(const sbi_col_keydef *k, char *buf, size_t len)
{
  if (k->type == K_NAME || k->type == K_BOOL) {
    const char *nm[16];
    sbi_col_join(buf, len, sbi_col_names_of(k, nm, 16));
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
    if (k->type == K_VEC || k->type == K_PARTICLE || k->type == K_REGION)
      snprintf(buf, len, "%.0f to %.0f numbers", k->lo, k->hi);
    else if (k->type == K_PATH)
      snprintf(buf, len, "a path");
    else
      snprintf(buf, len, "a finite number");
  }
}


int sbi_col_is_species(const char *sec, const char **name)
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


const sbi_col_keydef *sbi_col_find_key(const char *sec, const char *key)
{
  for (size_t i = 0; i < sbi_col_nkeys; i++)
    if (!strcmp(sbi_col_keys[i].sec, sec) && !strcmp(sbi_col_keys[i].key, key))
      return &sbi_col_keys[i];
  return NULL;
}

void sbi_col_keys_of(const char *sec, char *buf, size_t len)
{
  buf[0] = 0;
  for (size_t i = 0; i < sbi_col_nkeys; i++)
    if (!strcmp(sbi_col_keys[i].sec, sec)) {
      size_t n = strlen(buf);
      snprintf(buf + n, len - n, "%s%s", n ? ", " : "", sbi_col_keys[i].key);
    }
}

/* Set one key (c->where names its origin).  override: --set. */

/* ------------------------------------------------------------ API */

size_t sb_collide_nkeys(void) { return sbi_col_nkeys; }

int sb_collide_key(size_t i, sb_collide_keyinfo *k)
{
  if (i >= sbi_col_nkeys || !k)
    return sbi_error(SB_EINVAL, "sb_collide_key", "key %zu of %zu", i,
                     sbi_col_nkeys);
  const sbi_col_keydef *d = &sbi_col_keys[i];
  k->section = d->sec;
  k->key = d->key;
  k->unit = d->unit;
  k->def = d->def;
  k->help = d->help;
  sbi_col_range_text(d, k->valid, sizeof k->valid);
  return SB_SUCCESS;
}
