/* collide_check.c — cross-key checks of a collision-engine
 * configuration once all keys are in: required keys, conflicting keys,
 * keys that need other values (errors) and keys without effect
 * (warnings).  Messages name where each key came from. */
#include <math.h>
#include <string.h>

#include "collide_internal.h"

/* ------------------------------------------------------------ checks */

int sbi_col_agglo(const sbi_col_config *c)
{
  return !strcmp(c->outcome, "merge") || !strcmp(c->outcome, "dlvo");
}

/* Two keys that set the same thing. */
static int seen_index(const sbi_col_config *c, const char *sec,
                      const char *key)
{
  for (int i = c->nseen - 1; i >= 0; i--)
    if (!strcmp(c->seen[i].sec, sec) && !strcmp(c->seen[i].key, key))
      return i;
  return -1;
}

/* Two keys that set the same thing: the later one is reported. */
static int conflict(sbi_col_config *c, const char *sec, const char *a,
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
  return sbi_col_fail(c, "%s: [%s] %s conflicts with %s (at %s): %s",
                      sbi_col_where(c, sec, b), sec, b, a,
                      sbi_col_where(c, sec, a), why);
}

/* A key given where it has no effect. */
static void unused(sbi_col_config *c, const char *sec, const char *key,
                   const char *why)
{
  if (sbi_col_given(c, sec, key))
    sbi_col_warn(c, "%s: [%s] %s ignored: %s", sbi_col_where(c, sec, key),
                 sec, key, why);
}

static int section_given(const sbi_col_config *c, const char *sec)
{
  for (int i = 0; i < c->nseen; i++)
    if (!strcmp(c->seen[i].sec, sec))
      return 1;
  return 0;
}

static void section_unused(sbi_col_config *c, const char *sec, const char *why)
{
  for (int i = 0; i < c->nseen; i++)
    if (!strcmp(c->seen[i].sec, sec)) {
      sbi_col_warn(c, "%s: [%s] ignored: %s", c->seen[i].where, sec, why);
      return;
    }
}

/* [fluid] type = ou-field | kraichnan: their keys, and the runs they
 * cannot serve.  The OU field follows each particle by its index and the
 * engine's fluid callback passes positions only: every particle stays in
 * its slot for the whole run, no particle is added, removed or re-placed
 * (which would ask the field for one velocity at one place). */
static int check_field(sbi_col_config *c)
{
  static const char *const ou_keys[] = {"u2", "T_L", "stationary_start",
                                        NULL};
  static const char *const kr_keys[] = {"shell", "eps_nu", "omega", NULL};
  static const char *const faces[] = {"x_lo", "x_hi", "y_lo", "y_hi",
                                      "z_lo", "z_hi"};
  const int ou = !strcmp(c->fluid, "ou-field"),
            kr = !strcmp(c->fluid, "kraichnan");
  const char *type = sbi_col_where(c, "fluid", "type");
  for (int i = 0; ou_keys[i] && !ou; i++)
    unused(c, "fluid", ou_keys[i], "only type = ou-field uses it");
  for (int i = 0; kr_keys[i] && !kr; i++)
    unused(c, "fluid", kr_keys[i], "only type = kraichnan uses it");
  if (!ou && !kr) {
    unused(c, "fluid", "seed", "only the random fields (ou-field, "
           "kraichnan) use it");
    return 0;
  }
  unused(c, "fluid", "U", ou ? "type = ou-field" : "type = kraichnan");
  unused(c, "fluid", "G", ou ? "type = ou-field" : "type = kraichnan");
  if (kr) {
    if (isnan(c->kr_eps_nu))
      return sbi_col_fail(c, "%s: [fluid] type = kraichnan needs eps_nu "
                          "(1/s^2)", type);
    return 0;  /* its dim and box: sbi_col_dim_check */
  }
  if (isnan(c->ou_u2) || isnan(c->ou_TL))
    return sbi_col_fail(c, "%s: [fluid] type = ou-field needs u2 (m^2/s^2) "
                        "and T_L (s)", type);
  if (strcmp(c->outcome, "count") && strcmp(c->outcome, "elastic"))
    return sbi_col_fail(c, "%s: [run] outcome = %s with [fluid] type = "
                        "ou-field (%s): the field follows the particles by "
                        "index; an outcome that re-places, merges or "
                        "removes particles cannot keep it (valid: count, "
                        "elastic)", sbi_col_given(c, "run", "outcome")
                        ? sbi_col_where(c, "run", "outcome") : type,
                        c->outcome, type);
  if (c->sort_every > 0)
    return sbi_col_fail(c, "%s: [run] sort_every with [fluid] type = "
                        "ou-field: reordering the particles would hand them "
                        "other particles' seen velocities",
                        sbi_col_where(c, "run", "sort_every"));
  for (int f = 0; f < 6; f++)
    if (strcmp(c->wall[f], "periodic") && strcmp(c->wall[f], "reflect"))
      return sbi_col_fail(c, "%s: [walls] %s = %s with [fluid] type = "
                          "ou-field: a particle that leaves or deposits "
                          "changes the particles the field follows (valid: "
                          "periodic, reflect)",
                          sbi_col_where(c, "walls", faces[f]), faces[f],
                          c->wall[f]);
  for (int k = 0; k < c->nsp; k++)
    if (c->sp[k].inflow[0])
      return sbi_col_fail(c, "%s: [%s] inflow with [fluid] type = ou-field: "
                          "entering particles change the particles the "
                          "field follows", sbi_col_where(c, c->sp[k].name,
                          "inflow"), c->sp[k].name);
  if (!c->restart[0] && (!strcmp(c->placement, "random") ||
                         !c->placement[0]))  /* placed, not restored */
    for (int k = 0; k < c->nsp; k++)
      if (c->sp[k].count > 0 || !isnan(c->sp[k].phi))
        return sbi_col_fail(c, "%s: [run] placement = random%s with [fluid] "
                            "type = ou-field: the engine's random placement "
                            "draws the velocities without the field; give "
                            "placement = uniform or lattice",
                            c->placement[0] ? sbi_col_where(c, "run",
                                                            "placement")
                                            : type,
                            c->placement[0] ? "" : " (the default)");
  return 0;
}

/* Where the walls of direction k were given (its first face key). */
static const char *wall_where(const sbi_col_config *c, int k)
{
  static const char *const faces[] = {"x_lo", "x_hi", "y_lo", "y_hi",
                                      "z_lo", "z_hi"};
  return sbi_col_given(c, "walls", faces[2 * k])
             ? sbi_col_where(c, "walls", faces[2 * k])
             : sbi_col_where(c, "walls", faces[2 * k + 1]);
}

static const char *const FACES[] = {"x_lo", "x_hi", "y_lo", "y_hi", "z_lo",
                                    "z_hi"};

/* No walls in direction k (x or y) with the Lees-Edwards boundaries of
 * the shear field: those of [fluid] type = shear, or on restart without
 * [fluid] type the checkpoint's (sbi_col_fluid_check, once it is read).
 * On restart the walls of a direction the file does not give are the
 * checkpoint's (sbi_col_dim_check, once they are read). */
static int walls_lees(sbi_col_config *c, int k)
{
  const int lo = 2 * k, hi = 2 * k + 1;
  if (k >= 2 || strcmp(c->fluid, "shear") || !c->lees ||
      (!strcmp(c->wall[lo], "periodic") && !strcmp(c->wall[hi], "periodic")))
    return 0;
  const int kept = c->restart[0] && !sbi_col_given(c, "fluid", "type");
  if (!sbi_col_given(c, "walls", FACES[lo]) &&
      !sbi_col_given(c, "walls", FACES[hi]))
    return sbi_col_fail(c, "%s: [fluid] type = shear%s with the restart "
                        "checkpoint's walls %s = %s, %s = %s: its "
                        "Lees-Edwards sliding boundaries need x and y "
                        "periodic; give [walls] %s = periodic and %s = "
                        "periodic, or [fluid] lees_edwards = no",
                        kept ? sbi_col_where(c, "run", "restart")
                             : sbi_col_where(c, "fluid", "type"),
                        kept ? " (the restart checkpoint's)" : "", FACES[lo],
                        c->wall[lo], FACES[hi], c->wall[hi], FACES[lo],
                        FACES[hi]);
  const int w = sbi_col_given(c, "walls", FACES[lo]) ? lo : hi;
  return sbi_col_fail(c, "%s: [walls] %s = %s with [fluid] type = shear "
                      "(%s): its Lees-Edwards sliding boundaries need x "
                      "and y periodic; put the walls in z, or give "
                      "[fluid] lees_edwards = no",
                      sbi_col_where(c, "walls", FACES[w]), FACES[w],
                      c->wall[w], kept ? "the restart checkpoint's"
                                       : sbi_col_where(c, "fluid", "type"));
}

/* [walls]: both faces of a walled direction walls, none in x or y with
 * the Lees-Edwards boundaries (sb_engine_set_walls refuses both; here
 * with the lines of the keys); the z faces of a 2-D box do nothing
 * (sbi_col_dim_check). */
static int check_walls(sbi_col_config *c)
{
  const char *const *faces = FACES;
  for (int k = 0; k < c->dim; k++) {
    const int lo = 2 * k, hi = 2 * k + 1;
    const int plo = !strcmp(c->wall[lo], "periodic"),
              phi = !strcmp(c->wall[hi], "periodic");
    if (plo != phi) {
      const int w = plo ? hi : lo, p = plo ? lo : hi;
      return sbi_col_fail(c, "%s: [walls] %s = %s with %s = periodic: a "
                          "walled direction needs walls on both faces; "
                          "valid: %s = reflect, absorb or open",
                          sbi_col_where(c, "walls", faces[w]), faces[w],
                          c->wall[w], faces[p], faces[p]);
    }
    if (walls_lees(c, k))
      return -1;
  }
  return 0;
}

/* [walls] detect and deposit without the faces they act on: the wall
 * detector without an absorbing or open face (reflecting faces fold the
 * end state, engine_wall.c), the deposition outcome without an absorbing
 * face.  The faces are the run's 2 dim (a 2-D box has none in z), on
 * restart those the checkpoint keeps where the file gives none
 * (restart_box in collide_setup.c): sbi_col_dim_check runs it then. */
static void check_wall_keys(sbi_col_config *c)
{
  int detected = 0, absorb = 0;
  for (int f = 0; f < 2 * c->dim; f++) {
    detected |= !strcmp(c->wall[f], "absorb") || !strcmp(c->wall[f], "open");
    absorb |= !strcmp(c->wall[f], "absorb");
  }
  if (!detected)
    unused(c, "walls", "detect", "no absorbing or open face (it detects "
           "the contacts with those)");
  if (!absorb)
    unused(c, "walls", "deposit", "no absorbing face");
}

/* Keys of the walls and of the fluid's forces that have no effect: those
 * of the walls (check_wall_keys; on restart once the checkpoint's walls
 * are read), the fluid density without gravity or a nonlinear drag law
 * (it enters only the buoyancy and the particle Reynolds number,
 * engine_force.c), the fluid viscosity without a nonlinear-drag species
 * that lacks its own mu, the Lees-Edwards switch without the shear
 * field.  On restart the checkpoint keeps the fluid properties and drag
 * laws (collide_setup.c sets them only for a new run). */
static void check_inert(sbi_col_config *c)
{
  /* on restart without [fluid] type it applies to the checkpoint's
   * field (collide_setup.c) */
  if (strcmp(c->fluid, "shear") &&
      (!c->restart[0] || sbi_col_given(c, "fluid", "type")))
    unused(c, "fluid", "lees_edwards", "only type = shear uses it");
  if (c->restart[0]) {
    const char *why = "the fluid properties and drag laws come from the "
                      "restart checkpoint";
    unused(c, "fluid", "rho", why);
    unused(c, "fluid", "mu", why);
    for (int k = 0; k < c->nsp; k++)
      unused(c, c->sp[k].name, "drag", why);
    return;
  }
  check_wall_keys(c);
  int gravity = 0, nonlin = 0, nonlin_own_mu = 1;
  for (int k = 0; k < c->ng && k < c->dim; k++)
    gravity |= c->g[k] != 0.0;
  for (int k = 0; k < c->nsp; k++)
    if (strcmp(c->sp[k].drag, "stokes")) {
      nonlin = 1;
      nonlin_own_mu &= !isnan(c->sp[k].mu);
    }
  if (!gravity && !nonlin)
    unused(c, "fluid", "rho", "no gravity ([fluid] g) and no nonlinear drag "
           "law ([species] drag): the fluid density enters only the "
           "buoyancy and the particle Reynolds number");
  if (!nonlin || nonlin_own_mu)
    unused(c, "fluid", "mu", nonlin ? "every species with a nonlinear drag "
           "law gives its own mu" : "no species with a nonlinear drag law "
           "([species] drag)");
}

/* [observe] exits without an open face, and count_variance with what
 * changes the population (the tally's variance is that of a fixed
 * population, docs/engine.md §6).  The faces are the run's: a 2-D box's
 * z faces are periodic by now, and on restart the walls are the
 * checkpoint's where the file gives none (restart_box in
 * collide_setup.c). */
static void check_open(sbi_col_config *c)
{
  int open = 0;
  for (int f = 0; f < 6; f++)
    open |= !strcmp(c->wall[f], "open");
  if (c->exits > 0 && !open)
    unused(c, "observe", "exits", "no [walls] face is open");
  if (c->count_variance > 0) {
    int inflow = 0;
    for (int k = 0; k < c->nsp; k++)
      inflow |= c->sp[k].inflow[0] != 0;
    const char *why = !strcmp(c->outcome, "reinsert") ? "outcome = reinsert"
                      : sbi_col_agglo(c)             ? "merging"
                      : inflow                       ? "an inflow"
                      : open                         ? "an open face"
                                                     : NULL;
    if (why)
      sbi_col_warn(c, "%s: [observe] count_variance with %s: its variance "
                   "assumes a fixed population of particles, so the "
                   "dispersion and the widened interval are approximate",
                   sbi_col_where(c, "observe", "count_variance"), why);
  }
}

int sbi_col_dim_check(sbi_col_config *c)
{
  /* U of the checkpoint's field (restart without [fluid] type) is
   * warned as ignored */
  if (c->nU && c->nU != c->dim &&
      (!c->restart[0] || sbi_col_given(c, "fluid", "type")))
    return sbi_col_fail(c, "%s: [fluid] U: %d numbers for dim = %ld",
                        sbi_col_where(c, "fluid", "U"), c->nU, c->dim);
  if (c->ng && c->ng != c->dim)  /* the engine reads dim of them */
    return sbi_col_fail(c, "%s: [fluid] g: %d numbers for dim = %ld",
                        sbi_col_where(c, "fluid", "g"), c->ng, c->dim);
  /* [observe] grid: one number of cells per axis */
  const char *of = c->restart[0] ? " (the restart checkpoint's)" : "";
  if (c->restart[0] && c->dim != 3 && sbi_col_bridge(c))
    return sbi_col_fail(c, "%s: [run] detect = %s needs dim = 3 (the "
                        "restart checkpoint's dim = %ld)",
                        sbi_col_where(c, "run", "detect"), c->detect, c->dim);
  if (c->restart[0] && c->dim != 3 && c->first_hit)
    return sbi_col_fail(c, "%s: [observe] first_hit needs dim = 3 (the "
                        "reference is the 3-D Smoluchowski transient; the "
                        "restart checkpoint's dim = %ld)",
                        sbi_col_where(c, "observe", "first_hit"), c->dim);
  if (c->ngrid == 3 && c->dim == 2)
    return sbi_col_fail(c, "%s: [observe] grid has 3 values in 2-D%s; "
                        "valid: nx ny", sbi_col_where(c, "observe", "grid"),
                        of);
  if (c->ngrid == 2 && c->dim == 3)
    return sbi_col_fail(c, "%s: [observe] grid has 2 values in 3-D%s; "
                        "valid: nx ny nz", sbi_col_where(c, "observe", "grid"),
                        of);
  /* the z faces of a 2-D box */
  if (c->dim == 2)
    for (int f = 4; f < 6; f++) {
      unused(c, "walls", FACES[f], c->restart[0]
             ? "the restart checkpoint's dim = 2 (no z direction)"
             : "dim = 2 (no z direction)");
      strcpy(c->wall[f], "periodic");  /* nor deposit columns */
    }
  /* on restart the walls of the directions the file does not give are
   * the checkpoint's, which [fluid] type = shear, msd_every and the
   * walls' keys meet here (a new run: sbi_col_msd_check, check_inert) */
  if (c->restart[0] && (walls_lees(c, 0) || walls_lees(c, 1) ||
                        sbi_col_msd_walls_check(c)))
    return -1;
  if (c->restart[0])
    check_wall_keys(c);
  check_open(c);
  /* the Kraichnan field: 3-D, periodic in a cube (on restart the
   * checkpoint's box; sb_field_kraichnan_load) */
  if (!strcmp(c->fluid, "kraichnan")) {
    const char *type = sbi_col_where(c, "fluid", "type");
    if (c->dim != 3)
      return sbi_col_fail(c, "%s: [fluid] type = kraichnan is a 3-D field "
                          "(%sdim = %ld)", type, c->restart[0]
                          ? "the restart checkpoint's " : "", c->dim);
    if (!(c->Lx == c->Ly && c->Ly == c->Lz))
      return c->restart[0]
                 ? sbi_col_fail(c, "%s: [fluid] type = kraichnan is "
                                "periodic in a cube: the restart "
                                "checkpoint's box is Lx, Ly, Lz = %g, %g, "
                                "%g m", type, c->Lx, c->Ly, c->Lz)
                 : sbi_col_fail(c, "%s: [fluid] type = kraichnan is "
                                "periodic in a cube: give [run] L (here Lx, "
                                "Ly, Lz = %g, %g, %g m)", type, c->Lx, c->Ly,
                                c->Lz);
  }
  /* the inflows: a restart adds them again from the file */
  for (int k = 0; k < c->nsp; k++) {
    const sbi_col_species *s = &c->sp[k];
    const char *n = s->name;
    if (s->inflow[0]) {
      if (isnan(s->inflow_rate) || s->ninflow_u == 0)
        return sbi_col_fail(c, "%s: [%s] inflow: inflow_rate (1/s) and "
                            "inflow_velocity (m/s) are required",
                            sbi_col_where(c, n, "inflow"), n);
      if (s->ninflow_u != c->dim)
        return sbi_col_fail(c, "%s: [%s] inflow_velocity: %d numbers for dim "
                            "= %ld", sbi_col_where(c, n, "inflow_velocity"), n,
                            s->ninflow_u, c->dim);
      if (s->ninflow_region && s->ninflow_region != 2 * (c->dim - 1))
        return sbi_col_fail(c, "%s: [%s] inflow_region: %d numbers for dim = "
                            "%ld; valid: %ld",
                            sbi_col_where(c, n, "inflow_region"), n,
                            s->ninflow_region, c->dim, 2 * (c->dim - 1));
    } else {
      unused(c, n, "inflow_rate", "no inflow face");
      unused(c, n, "inflow_region", "no inflow face");
      unused(c, n, "inflow_velocity", "no inflow face");
      unused(c, n, "inflow_no_overlap", "no inflow face");
    }
  }
  return 0;
}

int sbi_col_fluid_check(sbi_col_config *c)
{
  if (strcmp(c->fluid, "shear") && sbi_col_given(c, "fluid", "lees_edwards"))
    sbi_col_warn(c, "%s: [fluid] lees_edwards ignored: the restart "
                 "checkpoint's field is %s (only type = shear uses it)",
                 sbi_col_where(c, "fluid", "lees_edwards"), c->fluid);
  return walls_lees(c, 0) || walls_lees(c, 1) ? -1
                                              : sbi_col_msd_lees_check(c);
}

int sbi_col_check(sbi_col_config *c)
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
  if (c->dim == 2 && !c->restart[0])  /* on restart: the box is kept */
    unused(c, run, "Lz", "dim = 2");
  /* a [species NAME] header without keys would add no species (and on
   * restart misplace the saved ones) */
  for (int i = 0; i < c->nsections; i++) {
    if (strncmp(c->sections[i], "species ", 8))
      continue;
    int k = 0;
    while (k < c->nsp && strcmp(c->sp[k].name, c->sections[i]))
      k++;
    if (k == c->nsp)
      return sbi_col_fail(c, "%s: [%s] has no keys: a species needs radius "
                          "(or diameter), mass (or density), tau (or mu) "
                          "and count, phi, particle or inflow",
                          c->section_where[i], c->sections[i]);
  }
  /* restart: the state comes from the checkpoint */
  if (c->restart[0]) {
    static const char *const kept[] = {"dim", "L", "Lx", "Ly", "Lz",
                                       "seed", "rng", "placement",
                                       "placement_seed", "thermalize",
                                       "velocity_seed",
                                       "warmup", NULL};
    for (int i = 0; kept[i]; i++)
      unused(c, run, kept[i], "the state comes from the restart "
             "checkpoint");
    /* the sections name and describe the saved species
     * (collide_setup.c checks them); their placement keys are unused */
    static const char *const placed[] = {"count", "phi", "region",
                                         "profile", "drift", "velocities",
                                         "velocity_scale", NULL};
    for (int k = 0; k < c->nsp; k++) {
      for (int i = 0; placed[i]; i++)
        unused(c, c->sp[k].name, placed[i], "the particles come from the "
               "restart checkpoint");
      if (c->sp[k].npart)
        sbi_col_warn(c, "%s: [%s] particle ignored: the particles come from "
                     "the restart checkpoint", c->sp[k].where,
                     c->sp[k].name);
    }
  } else {
    if (isnan(c->Lx) || isnan(c->Ly) || (c->dim == 3 && isnan(c->Lz)))
      return sbi_col_fail(c, "[run] L (or Lx, Ly%s) is required: the box "
                          "edge in m", c->dim == 3 ? ", Lz" : "");
    if (c->nsp == 0)
      return sbi_col_fail(c, "no [species NAME] section: give at least one "
                          "with radius, mass (or density), tau (or mu) and "
                          "count, phi or particle");
  }
  if (isnan(c->dt) && !c->restart[0])
    return sbi_col_fail(c, "[run] dt is required: the time step in s");
  if (isnan(c->t_end) && c->steps < 0)
    return sbi_col_fail(c, "[run] t_end or steps is required");
  /* detector and outcome */
  const int bridge = sbi_col_bridge(c), agglo = sbi_col_agglo(c);
  if (bridge && c->dim != 3 && !c->restart[0])  /* on restart:
                                                   sbi_col_dim_check */
    return sbi_col_fail(c, "%s: [run] detect = %s needs dim = 3",
                        sbi_col_where(c, run, "detect"), c->detect);
  if (!strcmp(c->outcome, "correction") && !bridge)
    return sbi_col_fail(c, "%s: [run] outcome = correction (the correction "
                        "step of the bridge detectors) needs detect = bridge "
                        "or exact", sbi_col_where(c, run, "outcome"));
  if (bridge && !strcmp(c->outcome, "elastic"))
    return sbi_col_fail(c, "%s: [run] outcome = elastic with detect = %s: the "
                        "bridge detectors have no contact velocity; valid: "
                        "reinsert, count, correction, merge, dlvo",
                        sbi_col_given(c, run, "outcome")
                            ? sbi_col_where(c, run, "outcome")
                            : sbi_col_where(c, run, "detect"),
                        c->detect);
  if (!bridge)
    section_unused(c, "bridge", "only detect = bridge or exact use it");
  if (!bridge && section_given(c, "turbulence"))
    return sbi_col_fail(c, "%s: [turbulence] needs detect = bridge or exact "
                        "(turbulent pair diffusion is a bridge model)",
                        sbi_col_where(c, "turbulence",
                                      sbi_col_given(c, "turbulence", "eps")
                                          ? "eps"
                                          : "nu"));
  if (sbi_col_given(c, "turbulence", "eps") !=
      sbi_col_given(c, "turbulence", "nu"))
    return sbi_col_fail(c, "[turbulence] needs both eps and nu");
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
  if (!agglo && !(bridge && !c->first_hit) && !c->ngrid)
    unused(c, run, "stop_every", "it samples sizes.csv (outcome = merge or dlvo), "
           "recomputes the bridge reach (detect = bridge or exact, "
           "without first_hit) and deposits the [observe] grid");
  /* the bridge reach is set at attach (sb_engine_bridge_attach) for the
   * particle number and largest radius of that time; merging raises the
   * radius, and the tail bound [bridge] tol then no longer holds */
  if (agglo && bridge && !(c->stop_every > 0))
    sbi_col_warn(c, "%s: [run] detect = %s with outcome = %s and no [run] "
                 "stop_every: the bridge reach is computed once, from the "
                 "initial radii; growing clusters can outgrow it (contacts "
                 "missed beyond [bridge] tol): give stop_every (s, e.g. a "
                 "tenth of the run) to recompute it at every stop",
                 sbi_col_where(c, run, "detect"), c->detect, c->outcome);
  if (strcmp(c->detect, "langevin")) {
    unused(c, run, "langevin_eps", "only detect = langevin uses it");
    unused(c, run, "langevin_xtol", "only detect = langevin uses it");
    unused(c, run, "langevin_tol", "only detect = langevin uses it");
  }
  if (strcmp(c->outcome, "elastic") && strcmp(c->outcome, "dlvo"))
    unused(c, run, "eta", "only outcome = elastic or dlvo (rebounds) "
           "use it");
  if (sbi_col_detect_none(c)) {
    unused(c, run, "outcome", "detect = none (no contact to act on)");
    if (!strcmp(c->outcome, "elastic") || !strcmp(c->outcome, "dlvo"))
      unused(c, run, "eta", "detect = none (no contact)");
    if (c->first_hit)
      return sbi_col_fail(c, "%s: [observe] first_hit with detect = none: "
                          "no contact is detected; give a detector (%s)",
                          sbi_col_where(c, "observe", "first_hit"),
                          sbi_col_where(c, run, "detect"));
  }
  /* observers */
  for (int k = 0; k < c->ngrid; k++)
    if (!(c->grid[k] >= 1 && c->grid[k] <= 16777216.0 &&
          c->grid[k] == floor(c->grid[k])))
      return sbi_col_fail(c, "%s: [observe] grid: %g cells along axis %d; "
                          "valid: whole numbers 1 to 16777216, one per axis "
                          "(nx ny, or nx ny nz in 3-D)",
                          sbi_col_where(c, "observe", "grid"), c->grid[k], k);
  /* its number of values: sbi_col_dim_check */
  if (!c->ngrid)
    unused(c, "observe", "grid_scheme", "no [observe] grid");
  /* [observe] exits and count_variance against the open faces:
   * sbi_col_dim_check (on restart the checkpoint's dim and walls) */
  if (c->hit_times && !bridge)
    return sbi_col_fail(c, "%s: [observe] hit_times records bridge hits: "
                        "needs detect = bridge or exact",
                        sbi_col_where(c, "observe", "hit_times"));
  if (c->first_hit) {
    if (strcmp(c->outcome, "count"))
      return sbi_col_fail(c, "%s: [observe] first_hit needs outcome = count "
                          "(pairs pass through each other)",
                          sbi_col_where(c, "observe", "first_hit"));
    if (c->nsp > 1 && sbi_col_given(c, "observe", "first_hit_radius"))
      return sbi_col_fail(c, "%s: [observe] first_hit_radius with %d "
                          "species: one reference radius serves one pair "
                          "type; leave it out (each species pair (i, j) "
                          "then uses its contact distance r_i + r_j) or "
                          "give first_hit_capacitance = yes",
                          sbi_col_where(c, "observe", "first_hit_radius"),
                          c->nsp);
    if (c->dim != 3 && !c->restart[0])  /* on restart: sbi_col_dim_check */
      return sbi_col_fail(c, "%s: [observe] first_hit needs dim = 3 (the "
                          "reference is the 3-D Smoluchowski transient)",
                          sbi_col_where(c, "observe", "first_hit"));
    if (c->first_hit_capacitance &&
        conflict(c, "observe", "first_hit_capacitance", "first_hit_radius",
                 "two reference radii"))
      return -1;
    if (c->first_hit_vn > 0 && strcmp(c->detect, "langevin") &&
        strcmp(c->detect, "ballistic"))
      return sbi_col_fail(c, "%s: [observe] first_hit_velocities with "
                          "detect = %s: this detector gives no velocity at "
                          "the contact; valid: detect = langevin or "
                          "ballistic",
                          sbi_col_where(c, "observe", "first_hit_velocities"),
                          c->detect);
  } else {
    unused(c, "observe", "first_hit_radius", "first_hit = no");
    unused(c, "observe", "first_hit_capacitance", "first_hit = no");
    unused(c, "observe", "first_hit_skip_seen", "first_hit = no");
    unused(c, "observe", "first_hit_velocities", "first_hit = no");
  }
  if (sbi_col_msd_check(c) || sbi_col_start_check(c) ||
      sbi_col_batches_check(c))
    return -1;
  for (int i = 0; i < c->nsnap_steps; i++)
    if (!(c->snap_steps[i] == floor(c->snap_steps[i]) &&
          c->snap_steps[i] <= 2e9 &&
          (i == 0 || c->snap_steps[i] > c->snap_steps[i - 1])))
      return sbi_col_fail(c, "%s: [run] snapshot_steps: %g%s; valid: "
                          "increasing whole numbers of steps (0 .. 2e9)",
                          sbi_col_where(c, "run", "snapshot_steps"),
                          c->snap_steps[i], i ? " after a larger or equal "
                          "one" : "");
  if (c->nsnap_steps && c->snapshot_every > 0 &&
      conflict(c, "run", "snapshot_steps", "snapshot_every",
               "two snapshot schedules"))
    return -1;
  /* fluid (on restart without type the checkpoint's: sbi_col_fluid_check
   * once it is read) */
  if (c->restart[0] && !sbi_col_given(c, "fluid", "type")) {
    const char *why = "on restart the checkpoint's field is kept unless "
                      "[fluid] type is given";
    unused(c, "fluid", "U", why);
    unused(c, "fluid", "G", why);
  } else if (!strcmp(c->fluid, "rest")) {
    unused(c, "fluid", "U", "type = rest");
    unused(c, "fluid", "G", "type = rest");
  } else if (!strcmp(c->fluid, "uniform")) {
    unused(c, "fluid", "G", "type = uniform");
    if (!sbi_col_given(c, "fluid", "U"))
      return sbi_col_fail(c, "%s: [fluid] type = uniform needs U (m/s)",
                          sbi_col_where(c, "fluid", "type"));
  } else if (!strcmp(c->fluid, "shear")) {
    unused(c, "fluid", "U", "type = shear");
    if (!sbi_col_given(c, "fluid", "G"))
      return sbi_col_fail(c, "%s: [fluid] type = shear needs G (1/s)",
                          sbi_col_where(c, "fluid", "type"));
  }
  if (check_field(c) || check_walls(c))
    return -1;
  if (!c->restart[0] && sbi_col_dim_check(c))  /* on restart: once the
                                                  checkpoint's dim is in */
    return -1;
  if (strcmp(c->placement, "uniform"))
    unused(c, run, "placement_seed", "only placement = uniform uses it");
  /* species */
  for (int k = 0; k < c->nsp && !c->restart[0]; k++) {
    sbi_col_species *s = &c->sp[k];
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
      return sbi_col_fail(c, "%s: [%s]: radius (or diameter) is required",
                          s->where, n);
    if (isnan(s->mass) && isnan(s->density))
      return sbi_col_fail(c, "%s: [%s]: mass (kg) or density (kg/m^3) is "
                          "required", s->where, n);
    if (isnan(s->tau) && isnan(s->mu))
      return sbi_col_fail(c, "%s: [%s]: tau (s, or inf for free flight) or mu "
                          "(Pa s, Stokes tau) is required", s->where, n);
    if (!isnan(s->mu) && isnan(s->density))
      return sbi_col_fail(c, "%s: [%s] mu: the Stokes tau needs density, not "
                          "mass", sbi_col_where(c, n, "mu"), n);
    if (isnan(s->mu))
      unused(c, n, "cunningham", "no mu (tau is given)");
    if (s->count < 0 && isnan(s->phi) && s->npart == 0 && !s->inflow[0])
      return sbi_col_fail(c, "%s: [%s]: count, phi, particle or inflow is "
                          "required", s->where, n);
    if (s->nregion && s->nregion != 2 * c->dim)
      return sbi_col_fail(c, "%s: [%s] region: %d numbers for dim = %ld; "
                          "valid: %ld (x0 x1 y0 y1%s)", sbi_col_where(c, n,
                                                                  "region"),
                          n, s->nregion, c->dim, 2 * c->dim,
                          c->dim == 3 ? " z0 z1" : "");
    for (int k = 0; k < c->dim && s->nregion; k++) {
      const double L[3] = {c->Lx, c->Ly, c->Lz}, r = s->radius;
      const double lo = s->region[2 * k], hi = s->region[2 * k + 1];
      const char *w = sbi_col_where(c, n, "region");
      const char a = (char)('x' + k);
      if (!(lo >= 0.0 && lo < hi && hi <= L[k]))
        return sbi_col_fail(c, "%s: [%s] region: %c0 = %g, %c1 = %g m; "
                            "valid: 0 <= %c0 < %c1 <= %g (the box)", w, n, a,
                            lo, a, hi, a, a, L[k]);
      /* between walls the centres stay a radius from the faces
       * (collide_setup.c, region_of) */
      if (strcmp(c->wall[2 * k], "periodic") &&
          !(fmax(lo, r) < fmin(hi, L[k] - r)))
        return sbi_col_fail(c, "%s: [%s] region: %c0 = %g, %c1 = %g m leaves "
                            "no room for centres between the %c walls (%s): "
                            "they are placed in [max(%c0, r), min(%c1, L%c - "
                            "r)] with r = %g m, L%c = %g m", w, n, a, lo, a,
                            hi, a, wall_where(c, k), a, a, a, r, a, L[k]);
    }
    if (strcmp(s->profile, "uniform")) {
      int walled = 0;
      for (int k = 0; k < c->dim; k++)
        walled |= strcmp(c->wall[2 * k], "periodic") != 0;
      if (strcmp(c->placement, "uniform"))
        return sbi_col_fail(c, "%s: [%s] profile = %s needs [run] placement "
                            "= uniform (the other placements are uniform "
                            "in the box)", sbi_col_where(c, n, "profile"), n,
                            s->profile);
      if (!walled)
        return sbi_col_fail(c, "%s: [%s] profile = %s: no direction has "
                            "walls ([walls]); the profile is across the gap "
                            "between two walls", sbi_col_where(c, n,
                                                               "profile"),
                            n, s->profile);
    }
    if (s->count < 0 && isnan(s->phi)) {  /* placed by particle lines or
                                              an inflow only */
      unused(c, n, "region", "no count or phi (it bounds the particles "
             "they place)");
      unused(c, n, "drift", "no count or phi (it is added to the "
             "velocities of the particles they place)");
    }
    if (s->ndrift && s->ndrift != c->dim)
      return sbi_col_fail(c, "%s: [%s] drift: %d numbers for dim = %ld",
                          sbi_col_where(c, n, "drift"), n, s->ndrift, c->dim);
    for (int q = 0; q < s->npart; q++)
      if (s->part_n[q] != 2 * c->dim)
        return sbi_col_fail(c, "%s: [%s] particle: %d numbers for dim = %ld; "
                            "valid: %s", s->part_where[q], n, s->part_n[q],
                            c->dim, c->dim == 3 ? "6 (x y z ux uy uz)"
                                                : "4 (x y ux uy)");
  }
  check_inert(c);
  return c->nerr ? -1 : 0;
}
