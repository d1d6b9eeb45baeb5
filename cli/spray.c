/* spray.c — `smolbridge spray CONFIG.ini`: run the homogeneous spray
 * kinetics (collisions, coalescence, TAB and Reitz breakup) from an INI
 * file (libinih), write OUTPUT/series.csv, OUTPUT/final.csv and
 * OUTPUT/summary.json, and optionally check the run against the BKW exact
 * solution; keys without effect are warned about on stderr.  Every key,
 * unit and default: docs/spray.md; examples:
 * examples/spray_*.ini.  Exit status: 0 success, 1 failed run or check,
 * 2 bad usage or input. */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>

#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>

#include <smolbridge/ini.h>
#include <smolbridge/spray.h>

#include "cli.h"
#include "ini_once.h"

#define MAXPOP 16

typedef struct {
  char name[64];
  long count;
  double radius, weight, T, theta, K0;
  double u[3];
  int tag, has_T, has_theta, has_weight, settle;
  char dist[16];
} pop_cfg;

typedef struct {
  unsigned long seed;
  char method[16], select[16], cross[16], merge[16], coal[16], output[512];
  double B0, volume, weight, rho_l, theta_cr, dt, t_end;
  long steps, sample_every;
  sb_spray_gas gas;
  double gvec[3];
  sb_spray_liquid liq;
  int tab, reitz;          /* on: the section is present, and */
  int tab_off, reitz_off;  /* not enable = 0 (wherever it stands) */
  sb_spray_tab_params tp;
  sb_spray_reitz_params rp;
  char tab_children[16], reitz_children[16];
  int check_bkw;
  double check_nse;
  pop_cfg pop[MAXPOP];
  int npop;
  char err[512];
  int nerr;
  char err_where[600];  /* FILE:LINE of the first error */
  sbc_ini_keys once;    /* the keys and headers read */
} config;

static void cfg_default(config *c)
{
  memset(c, 0, sizeof *c);
  c->seed = 1;
  strcpy(c->method, "bird");
  strcpy(c->select, "majorant");
  strcpy(c->cross, "hard-sphere");
  strcpy(c->merge, "momentum");
  strcpy(c->coal, "theta");
  strcpy(c->output, "spray-out");
  c->B0 = NAN;
  c->volume = NAN;
  c->weight = 1.0;
  c->rho_l = 1000.0;
  c->dt = NAN;
  c->t_end = NAN;
  c->steps = -1;
  c->sample_every = 1;
  c->gas.rho_g = 1.2;
  c->gas.mu_g = 1.8e-5;
  c->gvec[2] = -9.80665;
  c->liq.sigma = 0.072;
  c->liq.mu_l = 1e-3;
  sb_spray_tab_params_default(&c->tp);
  sb_spray_reitz_params_default(&c->rp);
  strcpy(c->tab_children, "auto");
  strcpy(c->reitz_children, "auto");
  c->check_nse = 5.0;
}

static int fail(config *c, const char *fmt, ...)
{
  if (c->nerr++ == 0) {
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(c->err, sizeof c->err, fmt, ap);
    va_end(ap);
  }
  return 0;
}

static int num(config *c, const char *sec, const char *key, const char *v,
               double *out, double lo, double hi)
{
  char *end;
  errno = 0;
  double x = strtod(v, &end);
  while (*end == ' ' || *end == '\t')
    end++;
  if (end == v || *end || errno == ERANGE || !isfinite(x))
    return fail(c, "[%s] %s = '%s': not a number", sec, key, v);
  if (!(x >= lo && x <= hi))
    return fail(c, "[%s] %s = %g: out of range [%g, %g]", sec, key, x, lo,
                hi);
  *out = x;
  return 1;
}

static int integer(config *c, const char *sec, const char *key,
                   const char *v, long *out, long lo, long hi)
{
  double x;
  if (!num(c, sec, key, v, &x, (double)lo, (double)hi))
    return 0;
  if (x != floor(x))
    return fail(c, "[%s] %s = %g: must be an integer", sec, key, x);
  *out = (long)x;
  return 1;
}

static int vec3(config *c, const char *sec, const char *key, const char *v,
                double out[3])
{
  char *end;
  const char *p = v;
  for (int k = 0; k < 3; k++) {
    while (*p == ' ' || *p == '\t' || *p == ',')
      p++;
    errno = 0;
    out[k] = strtod(p, &end);
    if (end == p || errno == ERANGE || !isfinite(out[k]))
      return fail(c, "[%s] %s = '%s': needs three numbers", sec, key, v);
    p = end;
  }
  while (*p == ' ' || *p == '\t')
    p++;
  if (*p)
    return fail(c, "[%s] %s = '%s': needs three numbers", sec, key, v);
  return 1;
}

/* A word among the NULL-terminated list `valid`. */
static int word(config *c, const char *sec, const char *key, const char *v,
                char *out, size_t len, const char *const *valid)
{
  for (int k = 0; valid[k]; k++)
    if (!strcmp(v, valid[k])) {
      snprintf(out, len, "%s", v);
      return 1;
    }
  char list[256] = "";
  for (int k = 0; valid[k]; k++) {
    strncat(list, valid[k], sizeof list - strlen(list) - 1);
    if (valid[k + 1])
      strncat(list, " | ", sizeof list - strlen(list) - 1);
  }
  return fail(c, "[%s] %s = '%s': must be %s", sec, key, v, list);
}

static const char *const METHODS[] = {"bird", "nanbu", NULL};
static const char *const SELECTS[] = {"majorant", "ntc", NULL};
static const char *const CROSSES[] = {"hard-sphere", "maxwell", NULL};
static const char *const MERGES[] = {"momentum", "settling", NULL};
static const char *const COALS[] = {"theta", "orourke", NULL};
static const char *const CHILDREN[] = {"auto", "parcel", "particles", NULL};
static const char *const DISTS[] = {"maxwell", "bkw", NULL};

static int h_run(config *c, const char *s, const char *k, const char *v)
{
  long l;
  if (!strcmp(k, "seed")) {
    if (!integer(c, s, k, v, &l, 0, 4294967295L))
      return 0;
    c->seed = (unsigned long)l;
    return 1;
  }
  if (!strcmp(k, "method"))
    return word(c, s, k, v, c->method, sizeof c->method, METHODS);
  if (!strcmp(k, "select"))
    return word(c, s, k, v, c->select, sizeof c->select, SELECTS);
  if (!strcmp(k, "cross"))
    return word(c, s, k, v, c->cross, sizeof c->cross, CROSSES);
  if (!strcmp(k, "merge_velocity"))
    return word(c, s, k, v, c->merge, sizeof c->merge, MERGES);
  if (!strcmp(k, "coalescence"))
    return word(c, s, k, v, c->coal, sizeof c->coal, COALS);
  if (!strcmp(k, "B0"))
    return num(c, s, k, v, &c->B0, 1e-300, 1e300);
  if (!strcmp(k, "volume"))
    return num(c, s, k, v, &c->volume, 1e-300, 1e300);
  if (!strcmp(k, "weight"))
    return num(c, s, k, v, &c->weight, 1e-300, 1e300);
  if (!strcmp(k, "rho_l"))
    return num(c, s, k, v, &c->rho_l, 1e-300, 1e300);
  if (!strcmp(k, "theta_cr"))
    return num(c, s, k, v, &c->theta_cr, 0, 1.5707963267948966);
  if (!strcmp(k, "dt"))
    return num(c, s, k, v, &c->dt, 1e-300, 1e300);
  if (!strcmp(k, "t_end"))
    return num(c, s, k, v, &c->t_end, 0, 1e300);
  if (!strcmp(k, "steps"))
    return integer(c, s, k, v, &c->steps, 0, 2000000000L);
  if (!strcmp(k, "sample_every"))
    return integer(c, s, k, v, &c->sample_every, 1, 2000000000L);
  if (!strcmp(k, "output")) {
    if (strlen(v) >= sizeof c->output)
      return fail(c, "[%s] %s: value too long", s, k);
    strcpy(c->output, v);
    return 1;
  }
  return fail(c, "[run]: unknown key '%s' (valid: seed, method, select, "
              "cross, B0, volume, weight, rho_l, theta_cr, coalescence, "
              "merge_velocity, dt, t_end, steps, sample_every, output)", k);
}

static int h_gas(config *c, const char *s, const char *k, const char *v)
{
  if (!strcmp(k, "u"))
    return vec3(c, s, k, v, c->gas.u);
  if (!strcmp(k, "rho_g"))
    return num(c, s, k, v, &c->gas.rho_g, 0, 1e300);
  if (!strcmp(k, "mu_g"))
    return num(c, s, k, v, &c->gas.mu_g, 0, 1e300);
  if (!strcmp(k, "g"))
    return vec3(c, s, k, v, c->gvec);
  return fail(c, "[gas]: unknown key '%s' (valid: u, rho_g, mu_g, g)", k);
}

static int h_liquid(config *c, const char *s, const char *k, const char *v)
{
  if (!strcmp(k, "sigma"))
    return num(c, s, k, v, &c->liq.sigma, 1e-300, 1e300);
  if (!strcmp(k, "mu_l"))
    return num(c, s, k, v, &c->liq.mu_l, 0, 1e300);
  return fail(c, "[liquid]: unknown key '%s' (valid: sigma, mu_l)", k);
}

static int h_tab(config *c, const char *s, const char *k, const char *v)
{
  long l;
  c->tab = !c->tab_off;
  if (!strcmp(k, "enable")) {
    if (!integer(c, s, k, v, &l, 0, 1))
      return 0;
    c->tab = (int)l;
    c->tab_off = !l;
    return 1;
  }
  if (!strcmp(k, "Cd"))
    return num(c, s, k, v, &c->tp.Cd, 0, 1e300);
  if (!strcmp(k, "children"))
    return word(c, s, k, v, c->tab_children, sizeof c->tab_children,
                CHILDREN);
  if (!strcmp(k, "child_tag")) {
    if (!integer(c, s, k, v, &l, -1, 1000000))
      return 0;
    c->tp.child_tag = (int)l;
    return 1;
  }
  return fail(c, "[tab]: unknown key '%s' (valid: enable, Cd, children, "
              "child_tag)", k);
}

static int h_reitz(config *c, const char *s, const char *k, const char *v)
{
  long l;
  c->reitz = !c->reitz_off;
  if (!strcmp(k, "enable")) {
    if (!integer(c, s, k, v, &l, 0, 1))
      return 0;
    c->reitz = (int)l;
    c->reitz_off = !l;
    return 1;
  }
  if (!strcmp(k, "B0"))
    return num(c, s, k, v, &c->rp.B0, 1e-300, 1e300);
  if (!strcmp(k, "B1"))
    return num(c, s, k, v, &c->rp.B1, 1e-300, 1e300);
  if (!strcmp(k, "emit_fraction"))
    return num(c, s, k, v, &c->rp.emit_fraction, 0, 1e300);
  if (!strcmp(k, "children"))
    return word(c, s, k, v, c->reitz_children, sizeof c->reitz_children,
                CHILDREN);
  if (!strcmp(k, "stripping") || !strcmp(k, "blob")) {
    if (!integer(c, s, k, v, &l, 0, 1))
      return 0;
    *(k[0] == 's' ? &c->rp.stripping : &c->rp.blob) = (int)l;
    return 1;
  }
  if (!strcmp(k, "child_tag")) {
    if (!integer(c, s, k, v, &l, -1, 1000000))
      return 0;
    c->rp.child_tag = (int)l;
    return 1;
  }
  return fail(c, "[reitz]: unknown key '%s' (valid: enable, B0, B1, "
              "emit_fraction, children, stripping, blob, child_tag)", k);
}

static int h_check(config *c, const char *s, const char *k, const char *v)
{
  long l;
  if (!strcmp(k, "bkw")) {
    if (!integer(c, s, k, v, &l, 0, 1))
      return 0;
    c->check_bkw = (int)l;
    return 1;
  }
  if (!strcmp(k, "nse"))
    return num(c, s, k, v, &c->check_nse, 0, 1e300);
  return fail(c, "[check]: unknown key '%s' (valid: bkw, nse)", k);
}

static int h_pop(config *c, const char *s, const char *k, const char *v)
{
  pop_cfg *p = NULL;
  for (int i = 0; i < c->npop; i++)
    if (!strcmp(c->pop[i].name, s))
      p = &c->pop[i];
  if (!p) {
    if (c->npop == MAXPOP)
      return fail(c, "[%s]: more than %d [droplets] sections", s, MAXPOP);
    p = &c->pop[c->npop];
    memset(p, 0, sizeof *p);
    snprintf(p->name, sizeof p->name, "%s", s);
    p->count = -1;
    p->radius = NAN;
    p->weight = 1.0;
    p->K0 = 0.6;
    p->tag = c->npop;
    strcpy(p->dist, "maxwell");
    c->npop++;
  }
  long l;
  if (!strcmp(k, "count"))
    return integer(c, s, k, v, &p->count, 0, 100000000L);
  if (!strcmp(k, "radius"))
    return num(c, s, k, v, &p->radius, 1e-300, 1e300);
  if (!strcmp(k, "weight")) {
    p->has_weight = 1;
    return num(c, s, k, v, &p->weight, 1e-300, 1e300);
  }
  if (!strcmp(k, "T")) {
    p->has_T = 1;
    return num(c, s, k, v, &p->T, 0, 1e300);
  }
  if (!strcmp(k, "theta")) {
    p->has_theta = 1;
    return num(c, s, k, v, &p->theta, 0, 1e300);
  }
  if (!strcmp(k, "u"))
    return vec3(c, s, k, v, p->u);
  if (!strcmp(k, "distribution"))
    return word(c, s, k, v, p->dist, sizeof p->dist, DISTS);
  if (!strcmp(k, "K0"))
    return num(c, s, k, v, &p->K0, 0.6, 1.0);
  if (!strcmp(k, "settling")) {
    if (!integer(c, s, k, v, &l, 0, 1))
      return 0;
    p->settle = (int)l;
    return 1;
  }
  if (!strcmp(k, "tag")) {
    if (!integer(c, s, k, v, &l, 0, 1000000))
      return 0;
    p->tag = (int)l;
    return 1;
  }
  return fail(c, "[%s]: unknown key '%s' (valid: count, radius, weight, T, "
              "theta, u, distribution, K0, settling, tag)", s, k);
}

/* The sections of a configuration ("droplets NAME" any name). */
static int known_section(const char *sec)
{
  static const char *const names[] = {"run", "gas", "liquid", "tab",
                                      "reitz", "check", NULL};
  return sbc_ini_section_known(sec, names, "droplets");
}

static int unknown_section(config *c, const char *sec)
{
  return fail(c, "unknown section [%s] (valid: run, gas, liquid, tab, "
              "reitz, check, droplets NAME)", sec);
}

static int handler(void *user, const char *sec, const char *key,
                   const char *v)
{
  config *c = user;
  if (!strcmp(sec, "run"))
    return h_run(c, sec, key, v);
  if (!strcmp(sec, "gas"))
    return h_gas(c, sec, key, v);
  if (!strcmp(sec, "liquid"))
    return h_liquid(c, sec, key, v);
  if (!strcmp(sec, "tab"))
    return h_tab(c, sec, key, v);
  if (!strcmp(sec, "reitz"))
    return h_reitz(c, sec, key, v);
  if (!strcmp(sec, "check"))
    return h_check(c, sec, key, v);
  if (!strncmp(sec, "droplets", 8) && (sec[8] == ' ' || !sec[8]))
    return h_pop(c, sec, key, v);
  return unknown_section(c, sec);
}

/* sb_ini_key_fn: the handler, with the place of the first error; a key
 * given twice is an error (no value is replaced silently). */
static int key_fn(void *user, const char *sec, const char *key,
                  const char *v, const char *where)
{
  config *c = user;
  const int had = c->nerr;
  char msg[1400];
  if (sbc_ini_once(&c->once, sec, key, where, msg, sizeof msg))
    fail(c, "%s", msg);
  else if (handler(c, sec, key, v))
    return 0;
  if (!had)
    snprintf(c->err_where, sizeof c->err_where, "%s", where);
  return 1;
}

/* sb_ini_section_fn: a section header repeated is an error (its keys
 * would merge with the first one's). */
static int section_fn(void *user, const char *sec, const char *where)
{
  config *c = user;
  char msg[1400];
  const int known = known_section(sec);
  if (known && !sbc_ini_once(&c->once, sec, NULL, where, msg, sizeof msg)) {
    /* the section's presence enables its model (docs/spray.md), also
     * with no key in it; enable = 0 anywhere in it turns it off */
    if (!strcmp(sec, "tab"))
      c->tab = !c->tab_off;
    if (!strcmp(sec, "reitz"))
      c->reitz = !c->reitz_off;
    return 0;
  }
  if (!c->nerr)
    snprintf(c->err_where, sizeof c->err_where, "%s", where);
  /* an unknown header is an error even without keys under it */
  if (!known)
    unknown_section(c, sec);
  else
    fail(c, "%s", msg);
  return 1;
}

static sb_spray_children children_of(const char *w)
{
  return !strcmp(w, "parcel")      ? SB_SPRAY_CHILDREN_PARCEL
         : !strcmp(w, "particles") ? SB_SPRAY_CHILDREN_PARTICLES
                                   : SB_SPRAY_CHILDREN_AUTO;
}

/* ------------------------------------------------ keys without effect */

/* If cond: "spray: warning: FILE:LINE: [sec] key ignored: why", when key
 * was read (the format of `smolbridge collide`). */
static void unused(config *c, int cond, const char *sec,
                   const char *key, const char *why)
{
  if (cond)
    sbc_ini_unused(&c->once, "spray", sec, key, why);
}

/* Warn about the keys read that have no effect in this configuration
 * (the run goes on; docs/spray.md §8). */
static void warn_unused(config *c)
{
  const int orourke = !strcmp(c->coal, "orourke");
  const int merges = orourke || c->theta_cr > 0;
  const int breakup = c->tab || c->reitz;
  const int bird = !strcmp(c->method, "bird");
  int settles = merges && !strcmp(c->merge, "settling");
  for (int i = 0; i < c->npop; i++)
    settles |= c->pop[i].settle;
  unused(c, strcmp(c->cross, "maxwell"), "run", "B0",
         "cross = hard-sphere (B0 is the rate of cross = maxwell)");
  unused(c, !bird, "run", "weight",
         "method = nanbu (each [droplets] section sets its weight)");
  unused(c, orourke, "run", "theta_cr",
         "coalescence = orourke (the Weber-number boundary decides)");
  unused(c, !merges, "run", "merge_velocity",
         "no collision coalesces (theta_cr = 0 with coalescence = theta)");
  unused(c, !breakup, "gas", "u",
         "no breakup model ([tab], [reitz]) is on");
  unused(c, !breakup && !settles, "gas", "rho_g",
         "no breakup model ([tab], [reitz]) is on and nothing settles");
  unused(c, !settles && !(c->reitz && c->rp.stripping), "gas", "mu_g",
         "nothing settles and no Reitz stripping test (stripping = 1)");
  unused(c, !breakup && !orourke, "liquid", "sigma",
         "no breakup model ([tab], [reitz]) is on and coalescence = theta");
  unused(c, !breakup, "liquid", "mu_l",
         "no breakup model ([tab], [reitz]) is on");
  unused(c, c->reitz && (!strcmp(c->reitz_children, "particles") ||
                         (!strcmp(c->reitz_children, "auto") && bird)),
         "reitz", "emit_fraction",
         "the children are particles (emit_fraction paces parcel "
         "children)");
  for (int i = 0; i < c->npop; i++)
    unused(c, strcmp(c->pop[i].dist, "bkw"), c->pop[i].name, "K0",
           "distribution = maxwell (K0 is the start of distribution = "
           "bkw)");
  unused(c, !c->check_bkw, "check", "nse",
         "no BKW check (bkw = 1) uses it");
  unused(c, !settles, "gas", "g",
         "nothing settles (gravity acts through merge_velocity = settling "
         "or [droplets] settling = 1)");
  if (c->tab_off)
    sbc_ini_section_unused(&c->once, "spray", "tab", "enable",
                           "enable = 0 turns TAB off");
  if (c->reitz_off)
    sbc_ini_section_unused(&c->once, "spray", "reitz", "enable",
                           "enable = 0 turns Reitz breakup off");
}

static void usage(FILE *f)
{
  fprintf(f,
"Usage: smolbridge spray CONFIG.ini\n"
"\n"
"Homogeneous spray kinetics: Bird or Nanbu stochastic collisions (hard\n"
"spheres or a Maxwell-type kernel), coalescence by impact parameter,\n"
"TAB and Reitz-wave breakup.  Sections of CONFIG.ini:\n"
"  [run]            seed, method = bird | nanbu, select = majorant | ntc,\n"
"                   cross = hard-sphere | maxwell, B0 (m^3/s), volume (m^3),\n"
"                   weight, rho_l (kg/m^3), theta_cr (rad),\n"
"                   coalescence = theta | orourke (Weber-dependent,\n"
"                   uses [liquid] sigma),\n"
"                   merge_velocity = momentum | settling, dt (s),\n"
"                   t_end (s) | steps, sample_every, output\n"
"  [gas]            u (m/s, 3 numbers), rho_g (kg/m^3), mu_g (Pa s),\n"
"                   g (m/s^2, 3 numbers)\n"
"  [liquid]         sigma (N/m), mu_l (Pa s)\n"
"  [tab]            enable, Cd, children = auto | parcel | particles,\n"
"                   child_tag\n"
"  [reitz]          enable, B0, B1, emit_fraction, children, stripping,\n"
"                   blob, child_tag\n"
"  [droplets NAME]  count, radius (m), weight, T (K) | theta (m^2/s^2),\n"
"                   u (m/s), distribution = maxwell | bkw, K0, settling,\n"
"                   tag\n"
"  [check]          bkw = 1: compare E|v|^4 with the BKW solution\n"
"                   (maxwell kernel, one population), nse (default 5)\n"
"Writes OUTPUT/series.csv, OUTPUT/final.csv, OUTPUT/summary.json.\n"
"Keys without effect in the configuration are warned about on stderr.\n"
"Exit status: 0 success, 1 failed run or check, 2 bad usage or input.\n"
"Every key with its unit and default: docs/spray.md.\n");
}

/* Build the spray from the configuration; NULL (message printed) on
 * error, *rc set to the exit status. */
static sb_spray *build(const config *c, gsl_rng *rng, const char *file,
                       sb_spray_settling *set, int *rc)
{
  sb_spray_params p;
  sb_spray_params_default(&p);
  *rc = 2;
  if (sb_spray_method_from_name(c->method, &p.method) ||
      sb_spray_select_from_name(c->select, &p.select) ||
      sb_spray_cross_from_name(c->cross, &p.cross))
    return NULL;
  if (isnan(c->volume)) {
    fprintf(stderr, "spray: %s: [run] volume is required\n", file);
    return NULL;
  }
  if (c->steps >= 0 && !isnan(c->t_end)) {
    fprintf(stderr, "spray: %s: [run] t_end and steps: give one of them\n",
            file);
    return NULL;
  }
  for (int i = 0; i < c->npop; i++) {
    const pop_cfg *q = &c->pop[i];
    if (q->has_T && q->has_theta) {
      fprintf(stderr, "spray: %s: [%s]: T and theta both set the velocity "
              "variance; give one of them\n", file, q->name);
      return NULL;
    }
    if (p.method == SB_SPRAY_BIRD && q->has_weight) {
      fprintf(stderr, "spray: %s: [%s] weight = %g: method = bird gives "
              "every parcel the [run] weight (%g); weights per population "
              "need method = nanbu\n", file, q->name, q->weight, c->weight);
      return NULL;
    }
  }
  if (p.cross == SB_SPRAY_MAXWELL && isnan(c->B0)) {
    fprintf(stderr, "spray: %s: [run] B0 is required with cross = maxwell\n",
            file);
    return NULL;
  }
  p.volume = c->volume;
  p.B0 = isnan(c->B0) ? 1.0 : c->B0;
  p.weight = c->weight;
  p.rho_l = c->rho_l;
  p.theta_cr = c->theta_cr;
  if (!strcmp(c->coal, "orourke"))
    p.coal = SB_SPRAY_COAL_OROURKE;
  p.sigma = c->liq.sigma;
  set->rho_l = c->rho_l;
  set->rho_g = c->gas.rho_g;
  set->mu_g = c->gas.mu_g;
  memcpy(set->gvec, c->gvec, sizeof set->gvec);
  if (!strcmp(c->merge, "settling")) {
    p.merge_velocity = sb_spray_stokes_settling;
    p.merge_ctx = set;
  }
  long total = 0;
  for (int i = 0; i < c->npop; i++)
    total += c->pop[i].count > 0 ? c->pop[i].count : 0;
  p.capacity = total > 0 ? (size_t)total : 16;
  sb_spray *s = sb_spray_alloc(&p);
  if (!s) {
    fprintf(stderr, "spray: %s: %s\n", file, sb_last_error());
    return NULL;
  }
  const double kB = 1.380649e-23;
  for (int i = 0; i < c->npop; i++) {
    const pop_cfg *q = &c->pop[i];
    if (q->count < 0 || isnan(q->radius)) {
      fprintf(stderr, "spray: %s: [%s]: count and radius are required\n",
              file, q->name);
      sb_spray_free(s);
      return NULL;
    }
    double m = c->rho_l * 4.0 / 3.0 * 3.14159265358979323846 * q->radius *
               q->radius * q->radius;
    double theta = q->has_theta ? q->theta : (q->has_T ? kB * q->T / m : 0);
    int st = SB_SUCCESS;
    for (long k = 0; k < q->count && !st; k++) {
      double v[3] = {q->u[0], q->u[1], q->u[2]};
      if (q->settle)
        sb_spray_stokes_settling(q->radius, v, set);
      if (!strcmp(q->dist, "bkw")) {
        double w[3];
        st = sb_spray_bkw_sample(q->K0, theta > 0 ? theta : 1e-300, rng, w);
        for (int d = 0; d < 3; d++)
          v[d] += w[d];
      } else if (theta > 0) {
        double sd = sqrt(theta);
        for (int d = 0; d < 3; d++)
          v[d] += gsl_ran_gaussian_ziggurat(rng, sd);
      }
      if (!st)
        st = sb_spray_add(s, v, q->radius, q->weight, q->tag, NULL);
    }
    if (st) {
      fprintf(stderr, "spray: %s: [%s]: %s\n", file, q->name,
              sb_last_error());
      sb_spray_free(s);
      return NULL;
    }
  }
  *rc = 0;
  return s;
}

/* E|v - u|^4 over all parcels and its i.i.d. standard error. */
static void m4_stats(const sb_spray *s, double *m4, double *se)
{
  double u[3] = {0, 0, 0}, wt = 0;
  const double *v = sb_spray_velocities(s), *w = sb_spray_weights(s);
  size_t n = sb_spray_count(s);
  for (size_t i = 0; i < n; i++) {
    wt += w[i];
    for (int k = 0; k < 3; k++)
      u[k] += w[i] * v[3 * i + k];
  }
  for (int k = 0; k < 3; k++)
    u[k] /= wt;
  *m4 = sb_spray_velocity_moment(s, 4, u, -1);
  double m8 = sb_spray_velocity_moment(s, 8, u, -1);
  *se = sqrt((m8 - *m4 * *m4) / (double)n);
}

static void write_final(FILE *f, const sb_spray *s)
{
  const double *v = sb_spray_velocities(s), *r = sb_spray_radii(s),
               *w = sb_spray_weights(s), *y = sb_spray_tab_y(s),
               *yd = sb_spray_tab_ydot(s);
  const int *tag = sb_spray_tags(s);
  fprintf(f, "tag,r,w,vx,vy,vz,y,ydot\n");
  for (size_t i = 0; i < sb_spray_count(s); i++)
    fprintf(f, "%d,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", tag[i], r[i],
            w[i], v[3 * i], v[3 * i + 1], v[3 * i + 2], y[i], yd[i]);
}

int sbc_spray_main(int argc, char **argv)
{
  if (argc < 2 || !strcmp(argv[1], "-h") || !strcmp(argv[1], "--help")) {
    usage(argc < 2 ? stderr : stdout);
    return argc < 2 ? 2 : 0;
  }
  if (argc > 2) {
    fprintf(stderr, "spray: one CONFIG.ini expected\n");
    return 2;
  }
  static config c;
  cfg_default(&c);
  const char *file = argv[1];
  char err[1024];
  int rst = sb_ini_read(file, NULL, key_fn, section_fn, &c, err,
                        sizeof err);
  /* a [droplets NAME] header alone would add no population */
  const char *ksec, *kwhere;
  if (!c.nerr && !rst &&
      sbc_ini_keyless(&c.once, "droplets", &ksec, &kwhere)) {
    snprintf(c.err_where, sizeof c.err_where, "%s", kwhere);
    fail(&c, "[%s] has no keys: a population needs count and radius (m)",
         ksec);
  }
  /* a [check] header alone checks nothing: a key left out, most likely */
  if (!c.nerr && !rst && sbc_ini_keyless(&c.once, "check", &ksec, &kwhere)) {
    snprintf(c.err_where, sizeof c.err_where, "%s", kwhere);
    fail(&c, "[check] has no keys: it checks nothing; valid keys: bkw = 1 "
         "(compare E|v|^4 with the BKW solution), nse (its tolerance in "
         "standard errors, default 5); or leave the section out");
  }
  if (!c.nerr && !rst)
    warn_unused(&c);
  sbc_ini_once_free(&c.once);
  if (c.nerr) {
    fprintf(stderr, "spray: %s: %s\n", c.err_where, c.err);
    return 2;
  }
  if (rst) {
    fprintf(stderr, "spray: %s\n", err);
    return 2;
  }
  if (c.npop == 0) {
    fprintf(stderr, "spray: %s: no [droplets NAME] section\n", file);
    return 2;
  }
  if (isnan(c.dt) || (isnan(c.t_end) && c.steps < 0)) {
    fprintf(stderr, "spray: %s: [run] dt and t_end (or steps) are "
            "required\n", file);
    return 2;
  }
  long nsteps = c.steps >= 0 ? c.steps : lround(c.t_end / c.dt);
  c.tp.children = children_of(c.tab_children);
  c.rp.children = children_of(c.reitz_children);
  gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
  if (!rng)
    return 1;
  gsl_rng_set(rng, c.seed);
  sb_spray_settling set;
  int rc;
  sb_spray *s = build(&c, rng, file, &set, &rc);
  if (!s) {
    if (rc == 2 && sb_last_status() && c.nerr == 0 && !c.err[0])
      fprintf(stderr, "spray: %s: %s\n", file, sb_last_error());
    gsl_rng_free(rng);
    return rc;
  }
  const sb_spray_params *sp = sb_spray_get_params(s);
  if (c.check_bkw && (sp->cross != SB_SPRAY_MAXWELL || c.npop != 1 ||
                      strcmp(c.pop[0].dist, "bkw"))) {
    fprintf(stderr, "spray: %s: [check] bkw needs cross = maxwell and one "
            "[droplets] population with distribution = bkw\n", file);
    sb_spray_free(s);
    gsl_rng_free(rng);
    return 2;
  }
  char path[600];
  if (sb_mkdir_p(c.output)) {
    fprintf(stderr, "spray: cannot create '%s': %s\n", c.output,
            strerror(errno));
    sb_spray_free(s);
    gsl_rng_free(rng);
    return 1;
  }
  snprintf(path, sizeof path, "%s/series.csv", c.output);
  FILE *f = fopen(path, "w");
  if (!f) {
    fprintf(stderr, "spray: cannot write %s\n", path);
    sb_spray_free(s);
    gsl_rng_free(rng);
    return 1;
  }
  /* BKW reference: lambda = n B0 (Bird: times N/(N-1)) */
  double lam = 0, theta = 0, K0 = c.pop[0].K0;
  if (c.check_bkw) {
    sb_spray_totals t0;
    sb_spray_get_totals(s, &t0);
    double N = (double)sb_spray_count(s);
    lam = t0.number / sp->volume * sp->B0;
    if (sp->method == SB_SPRAY_BIRD)
      lam *= N / (N - 1);
    const pop_cfg *q = &c.pop[0];
    double m = c.rho_l * 4.0 / 3.0 * 3.14159265358979323846 * q->radius *
               q->radius * q->radius;
    theta = q->has_theta ? q->theta : 1.380649e-23 * q->T / m;
  }
  fprintf(f, "t,parcels,number,mass,energy,px,py,pz,volume,T,M4,bounces,"
          "merges,tab_breakups,reitz_children%s\n",
          c.check_bkw ? ",M4_bkw" : "");
  fprintf(stderr, "spray: %zu parcels, %s/%s, dt = %g s, %ld steps, seed "
          "%lu, output %s/\n", sb_spray_count(s), c.method, c.cross, c.dt,
          nsteps, c.seed, c.output);
  int st = SB_SUCCESS;
  double worst = 0, m4 = NAN, se = NAN, ref = NAN;
  for (long k = 0; k <= nsteps && !st; k++) {
    if (k > 0) {
      st = sb_spray_collide(s, c.dt, rng);
      if (!st && c.tab)
        st = sb_spray_tab_step(s, &c.gas, &c.liq, &c.tp, c.dt, rng);
      if (!st && c.reitz)
        st = sb_spray_reitz_step(s, &c.gas, &c.liq, &c.rp, c.dt);
    }
    if (st || (k % c.sample_every && k != nsteps))
      continue;
    sb_spray_totals t;
    sb_spray_stats ss;
    sb_spray_get_totals(s, &t);
    sb_spray_get_stats(s, &ss);
    m4_stats(s, &m4, &se);
    fprintf(f, "%.17g,%zu,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,"
            "%.17g,%llu,%llu,%llu,%llu", sb_spray_time(s), sb_spray_count(s),
            t.number, t.mass, t.energy, t.momentum[0], t.momentum[1],
            t.momentum[2], t.volume, sb_spray_temperature(s, -1), m4,
            ss.bounces, ss.merges, ss.tab_breakups, ss.reitz_children);
    if (c.check_bkw) {
      ref = sb_spray_bkw_m4(sb_spray_bkw_K(K0, lam, sb_spray_time(s)), theta);
      fprintf(f, ",%.17g", ref);
      double z = fabs(m4 - ref) / se;
      if (z > worst)
        worst = z;
    }
    fprintf(f, "\n");
  }
  fclose(f);
  if (st) {
    fprintf(stderr, "spray: step failed: %s\n", sb_last_error());
    sb_spray_free(s);
    gsl_rng_free(rng);
    return 1;
  }
  snprintf(path, sizeof path, "%s/final.csv", c.output);
  if ((f = fopen(path, "w"))) {
    write_final(f, s);
    fclose(f);
  }
  sb_spray_stats ss;
  sb_spray_totals t;
  sb_spray_get_stats(s, &ss);
  sb_spray_get_totals(s, &t);
  snprintf(path, sizeof path, "%s/summary.json", c.output);
  if ((f = fopen(path, "w"))) {
    fprintf(f, "{\n  \"program\": \"smolbridge spray\",\n  \"version\": "
            "\"%s\",\n  \"seed\": %lu,\n  \"method\": \"%s\",\n  \"select\": "
            "\"%s\",\n  \"cross\": \"%s\",\n  \"volume\": %.17g,\n  \"dt\": "
            "%.17g,\n  \"time\": %.17g,\n  \"parcels\": %zu,\n  \"number\": "
            "%.17g,\n  \"candidates\": %llu,\n  \"bounces\": %llu,\n  "
            "\"merges\": %llu,\n  \"tab_breakups\": %llu,\n  "
            "\"reitz_children\": %llu", sb_version(), c.seed, c.method,
            c.select, c.cross, sp->volume, c.dt, sb_spray_time(s),
            sb_spray_count(s), t.number, ss.candidates, ss.bounces,
            ss.merges, ss.tab_breakups, ss.reitz_children);
    fprintf(f, ",\n  ");
    sbc_ini_json_warnings(f, &c.once);
    if (c.check_bkw)
      fprintf(f, ",\n  \"bkw\": {\"M4\": %.17g, \"M4_exact\": %.17g, "
              "\"worst_se\": %.6g, \"nse\": %.6g}", m4, ref, worst,
              c.check_nse);
    fprintf(f, "\n}\n");
    fclose(f);
  }
  /* collisions: every accepted pair, whether it bounced or merged */
  fprintf(stderr, "spray: done, t = %g s, %zu parcels, %llu collisions "
          "(%llu bounces, %llu merges), %llu TAB breakups, %llu Reitz "
          "children\n", sb_spray_time(s), sb_spray_count(s),
          ss.bounces + ss.merges, ss.bounces, ss.merges, ss.tab_breakups,
          ss.reitz_children);
  sb_spray_free(s);
  gsl_rng_free(rng);
  if (c.check_bkw) {
    int ok = worst <= c.check_nse;
    fprintf(stderr, "spray: BKW check: E|v|^4 = %.6g vs %.6g at the end; "
            "largest deviation %.2f i.i.d. standard errors (limit %g): %s\n",
            m4, ref, worst, c.check_nse, ok ? "pass" : "FAIL");
    return ok ? 0 : 1;
  }
  return 0;
}
