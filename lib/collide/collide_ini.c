/* collide_ini.c — reading a collision-engine configuration: key
 * values checked against the key table (collide_keys.c), the INI reader
 * (libinih) over a file or a string, --set overrides.  Messages name
 * where the key came from, the section, key and value, and the valid
 * values. */
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include <smolbridge/engine.h>
#include <smolbridge/ini.h>

#include "collide_internal.h"

/* ------------------------------------------------------------ errors */

int sbi_col_fail(sbi_col_config *c, const char *fmt, ...)
{
  if (c->nerr++ == 0) {
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(c->err, sizeof c->err, fmt, ap);
    va_end(ap);
  }
  return -1;
}

void sbi_col_warn(sbi_col_config *c, const char *fmt, ...)
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

void sbi_col_defaults(sbi_col_config *c)
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
  c->velocity_seed = -1;
  strcpy(c->neigh, "cells");
  strcpy(c->detect, "ballistic");
  strcpy(c->outcome, "elastic");
  strcpy(c->rng, "philox");
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
  c->ou_u2 = c->ou_TL = c->kr_eps_nu = NAN;
  c->kr_omega = 0.0;
  c->kr_shell = 2;
  c->field_seed = -1;
  c->ou_stationary = 1;
  c->mu_f = NAN;
  for (int f = 0; f < 6; f++)
    strcpy(c->wall[f], "periodic");
  strcpy(c->wall_detect, "bridge");
  strcpy(c->deposit, "remove");
  strcpy(c->grid_scheme, "ngp");
  c->region_every = 1;
}

static void species_defaults(sbi_col_species *s)
{
  memset(s, 0, sizeof *s);
  s->radius = s->diameter = s->density = s->mass = s->tau = s->mu = NAN;
  s->B = s->b2 = s->T = s->phi = NAN;
  s->cc = 1.0;
  s->count = -1;
  strcpy(s->drag, "stokes");
  strcpy(s->profile, "uniform");
  strcpy(s->velocities, "placed");
}

/* ------------------------------------------------------------ values */

const char *sbi_col_where(const sbi_col_config *c, const char *sec,
                          const char *key)
{
  for (int i = c->nseen - 1; i >= 0; i--)
    if (!strcmp(c->seen[i].sec, sec) && !strcmp(c->seen[i].key, key))
      return c->seen[i].where;
  return "";
}

int sbi_col_given(const sbi_col_config *c, const char *sec, const char *key)
{
  return sbi_col_where(c, sec, key)[0] != 0;
}

const char *sbi_col_short_name(const sbi_col_config *c, size_t k)
{
  if ((int)k >= c->nsp)
    return "cluster";
  const char *n;
  return sbi_col_is_species(c->sp[k].name, &n) ? n : c->sp[k].name;
}

const char *sbi_col_species_label(const sbi_col_config *c,
                                  const sb_agglo *ag, size_t k, char *buf,
                                  size_t len)
{
  const size_t m =
      ag && (int)k >= c->nsp ? sb_agglo_size_of_species(ag, k) : 0;
  if (!m)
    return sbi_col_short_name(c, k);
  snprintf(buf, len, "cluster_%zu", m);
  return buf;
}

static int parse_number(sbi_col_config *c, const char *sec,
                        const sbi_col_keydef *k, const char *v, double *out)
{
  char r[200];
  sbi_col_range_text(k, r, sizeof r);
  char *end;
  errno = 0;
  double x = strtod(v, &end);
  while (*end == ' ' || *end == '\t')
    end++;
  if (end == v || *end) {
    if (strchr(v, '#'))
      return sbi_col_fail(c, "%s: [%s] %s = %s: not a number ('#' starts a "
                          "comment only at the beginning of a line; an inline "
                          "comment starts with ';' after a space)", c->where,
                          sec, k->key, v);
    return sbi_col_fail(c, "%s: [%s] %s = %s: not a number; valid: %s%s%s",
                        c->where, sec, k->key, v, r,
                        strcmp(k->unit, "-") ? " " : "",
                        strcmp(k->unit, "-") ? k->unit : "");
  }
  int inf_ok = k->range == R_POSINF && isinf(x) && x > 0;
  if (isnan(x) || (isinf(x) && !inf_ok) || (errno == ERANGE && !inf_ok &&
                                            fabs(x) > 1.0))
    return sbi_col_fail(c, "%s: [%s] %s = %s: not a finite number; valid: %s",
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
    return sbi_col_fail(c, "%s: [%s] %s = %s: not an integer; valid: %s",
                        c->where, sec, k->key, v, r);
  if (!ok)
    return sbi_col_fail(c, "%s: [%s] %s = %s: out of range; valid: %s%s%s",
                        c->where, sec, k->key, v, r,
                        strcmp(k->unit, "-") ? " " : "",
                        strcmp(k->unit, "-") ? k->unit : "");
  *out = x;
  return 0;
}

static int parse_list(sbi_col_config *c, const char *sec,
                      const sbi_col_keydef *k, const char *v, double *out,
                      int *n)
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
      return sbi_col_fail(c, "%s: [%s] %s = %s: not a list of %d to %d finite "
                          "numbers%s", c->where, sec, k->key, v, nmin, nmax,
                          strchr(v, '#') ? " ('#' starts a comment only at "
                                           "the beginning of a line; use ';' "
                                           "after a space)"
                                         : "");
    if (cnt == nmax)
      return sbi_col_fail(c, "%s: [%s] %s = %s: more than %d numbers",
                          c->where, sec, k->key, v, nmax);
    if ((k->range == R_NONNEG && x < 0) || (k->range == R_POS && !(x > 0)))
      return sbi_col_fail(c, "%s: [%s] %s = %s: %g out of range; valid: "
                          "numbers %s 0", c->where, sec, k->key, v, x,
                          k->range == R_POS ? ">" : ">=");
    out[cnt++] = x;
    p = end;
  }
  if (cnt < nmin) {
    char want[40];
    if (nmin == nmax)
      snprintf(want, sizeof want, "%d", nmin);
    else
      snprintf(want, sizeof want, "%d to %d", nmin, nmax);
    return sbi_col_fail(c, "%s: [%s] %s = %s: %d number%s; valid: %s",
                        c->where, sec, k->key, v, cnt, cnt == 1 ? "" : "s",
                        want);
  }
  *n = cnt;
  return 0;
}

static sbi_col_species *species_for(sbi_col_config *c, const char *sec)
{
  for (int k = 0; k < c->nsp; k++)
    if (!strcmp(c->sp[k].name, sec))
      return &c->sp[k];
  if (c->nsp == COL_MAXSPEC) {
    sbi_col_fail(c, "%s: [%s]: more than %d species sections", c->where, sec,
                 COL_MAXSPEC);
    return NULL;
  }
  sbi_col_species *s = &c->sp[c->nsp++];
  species_defaults(s);
  copy(s->name, sizeof s->name, sec);
  copy(s->where, sizeof s->where, c->where);
  for (int i = 0; i < c->nsections; i++)  /* its header, if read */
    if (!strcmp(c->sections[i], sec))
      copy(s->where, sizeof s->where, c->section_where[i]);
  return s;
}

static int unknown_section(sbi_col_config *c, const char *where,
                           const char *sec)
{
  return sbi_col_fail(c, "%s: unknown section [%s]; valid: [run], [fluid], "
                      "[walls], [bridge], [turbulence], [observe], [agglo], "
                      "[species NAME]", where, sec);
}

static int set_key(sbi_col_config *c, const char *section, const char *key,
                   const char *value, int override)
{
  char sec[72];
  const char *sname;
  int species = sbi_col_is_species(section, &sname);
  if (species) {
    if (!*sname)
      return sbi_col_fail(c, "%s: [%s]: a species section needs a name: "
                          "[species NAME]", c->where, section);
    snprintf(sec, sizeof sec, "species %s", sname);
  } else
    copy(sec, sizeof sec, section);
  const sbi_col_keydef *k = sbi_col_find_key(species ? "species" : sec, key);
  if (!k) {
    char valid[600];
    sbi_col_keys_of(species ? "species" : sec, valid, sizeof valid);
    if (!valid[0])
      return unknown_section(c, c->where, section);
    return sbi_col_fail(c, "%s: [%s] %s: unknown key; valid: %s", c->where,
                        sec, key, valid);
  }
  if (k->type != K_PARTICLE && k->type != K_REGION) {
    for (int i = 0; i < c->nseen; i++)
      if (!strcmp(c->seen[i].sec, sec) && !strcmp(c->seen[i].key, key)) {
        if (override) {
          snprintf(c->seen[i].where, sizeof c->seen[i].where, "%s",
                   c->where);
          c->seen[i].override = 1;
          goto store;
        }
        if (!c->seen[i].override)
          return sbi_col_fail(c, "%s: [%s] %s given twice (first at %s); give "
                              "each key once", c->where, sec, key,
                              c->seen[i].where);
      }
  }
  if (c->nseen == COL_MAXSEEN)
    return sbi_col_fail(c, "%s: more than %d keys", c->where, COL_MAXSEEN);
  sbi_col_seen *sn = &c->seen[c->nseen++];
  copy(sn->sec, sizeof sn->sec, sec);
  copy(sn->key, sizeof sn->key, key);
  copy(sn->where, sizeof sn->where, c->where);
  sn->override = override;
store:;
  sbi_col_species *sp = NULL;
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
    const char *nm[16];
    const char *const *names = sbi_col_names_of(k, nm, 16);
    for (int i = 0; names[i]; i++)
      if (!strcmp(value, names[i])) {
        if (k->type == K_BOOL)
          *(long *)field = i == 0;
        else
          copy((char *)field, k->aux, value);
        return 0;
      }
    char valid[300];
    sbi_col_join(valid, sizeof valid, names);
    return sbi_col_fail(c, "%s: [%s] %s = %s: unknown; valid: %s%s", c->where,
                        sec, key, value, valid,
                        strchr(value, '#') ? " ('#' starts a comment only "
                                             "at the beginning of a line; use "
                                             "';' after a space)"
                                           : "");
  }
  case K_PATH:
    if (strlen(value) >= 512)
      return sbi_col_fail(c, "%s: [%s] %s: path longer than 511 characters",
                          c->where, sec, key);
    if (!value[0])
      return sbi_col_fail(c, "%s: [%s] %s: empty path", c->where, sec, key);
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
      return sbi_col_fail(c, "%s: [%s] particle: more than %d; use count with "
                          "region for more", c->where, sec, COL_MAXPART);
    if (parse_list(c, sec, k, value, q, &n))
      return -1;
    if (n == 5)
      return sbi_col_fail(c, "%s: [%s] particle = %s: 5 numbers; valid: 4 "
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
  case K_REGION: {
    if (c->nregions == COL_MAXREGION)
      return sbi_col_fail(c, "%s: [%s] region: more than %d", c->where, sec,
                          COL_MAXREGION);
    double *o = c->regions[c->nregions];
    if (parse_list(c, sec, k, value, o, &n))
      return -1;
    if (n != 4 && n != 6)
      return sbi_col_fail(c, "%s: [%s] region = %s: %d numbers; valid: 4 "
                          "(2-D: x0 x1 y0 y1) or 6 (3-D: x0 x1 y0 y1 z0 z1)",
                          c->where, sec, value, n);
    copy(c->region_where[c->nregions], COL_WHERE, c->where);
    c->nregion_n[c->nregions++] = n;
    return 0;
  }
  }
  return sbi_col_fail(c, "%s: [%s] %s: internal error", c->where, sec, key);
}

/* ------------------------------------------------------------ INI file */

/* Record a section header the reader sees: a repeated header would
 * silently merge two sections. */
static int header(void *user, const char *sec, const char *where)
{
  sbi_col_config *c = user;
  char name[72];
  copy(name, sizeof name, sec);
  /* normalise "species.x" / "species:x" like the keys */
  const char *sn;
  if (sbi_col_is_species(name, &sn)) {
    if (!sn[0])
      return sbi_col_fail(c, "%s: [%s]: a species section needs a name: "
                          "[species NAME]", where, sec);
    /* the name heads CSV columns and --set keys (species.NAME.key):
     * no commas, quotes, dots or spaces */
    if (strspn(sn, "abcdefghijklmnopqrstuvwxyz"
                   "ABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-") != strlen(sn))
      return sbi_col_fail(c, "%s: [%s]: the species name '%s' may hold only "
                          "letters, digits, '_' and '-'", where, sec, sn);
    char tmp[72];
    snprintf(tmp, sizeof tmp, "species %s", sn);
    copy(name, sizeof name, tmp);
  } else {
    /* an unknown header is an error even without keys under it (a
     * misspelt [walls] would otherwise leave its section out silently) */
    char valid[600];
    sbi_col_keys_of(name, valid, sizeof valid);
    if (!valid[0])
      return unknown_section(c, where, sec);
  }
  for (int i = 0; i < c->nsections; i++)
    if (!strcmp(c->sections[i], name))
      return sbi_col_fail(c, "%s: section [%s] repeated (first at %s); put "
                          "its keys in one section", where, name,
                          c->section_where[i]);
  if (c->nsections < COL_MAXSPEC + 8) {
    copy(c->sections[c->nsections], sizeof c->sections[0], name);
    snprintf(c->section_where[c->nsections], COL_WHERE, "%s", where);
    c->nsections++;
  }
  return 0;
}

static int handler(void *user, const char *sec, const char *key,
                   const char *value, const char *where)
{
  sbi_col_config *c = user;
  snprintf(c->where, sizeof c->where, "%s", where);
  if (!sec[0])
    return sbi_col_fail(c, "%s: %s = %s before any section; put it under "
                        "[run], [fluid], ... or [species NAME]", c->where,
                        key, value);
  return set_key(c, sec, key, value, 0);
}

/* The reader's result: the first error (a key's, or the reader's), no
 * keys at all. */
static int read_end(sbi_col_config *c, const char *path, int st,
                    const char *err)
{
  if (c->nerr)
    return -1;
  if (st)
    return sbi_col_fail(c, "%s", err);
  if (c->nseen == 0)
    return sbi_col_fail(c, "%s: no keys (empty file?); a configuration "
                        "needs at least [run] L, dt, t_end or steps, and a "
                        "[species NAME] section", path);
  return 0;
}

int sbi_col_read_file(sbi_col_config *c, const char *path)
{
  char err[1024];
  int st = sb_ini_read(path, NULL, handler, header, c, err, sizeof err);
  return read_end(c, path, st, err);
}

int sbi_col_read_string(sbi_col_config *c, const char *text,
                        const char *name)
{
  char err[1024];
  int st = sb_ini_read(name, text ? text : "", handler, header, c, err,
                       sizeof err);
  return read_end(c, name, st, err);
}

int sbi_col_override(sbi_col_config *c, const char *arg)
{
  snprintf(c->where, sizeof c->where, "--set %s", arg);
  const char *eq = strchr(arg, '=');
  char path[200];
  size_t n = eq ? (size_t)(eq - arg) : 0;
  if (!eq || n == 0 || n >= sizeof path)
    return sbi_col_fail(c, "--set %s: expected SECTION.KEY=VALUE (e.g. "
                        "run.dt=1e-7, species.NAME.phi=1e-3)", arg);
  /* blanks around '=' as in an INI line ("run.dt = 1e-7" quoted) */
  while (n > 0 && (arg[n - 1] == ' ' || arg[n - 1] == '\t'))
    n--;
  memcpy(path, arg, n);
  path[n] = 0;
  const char *val = eq + 1;
  while (*val == ' ' || *val == '\t')
    val++;
  char *dot = strrchr(path, '.');
  if (!dot || dot == path || !dot[1])
    return sbi_col_fail(c, "--set %s: expected SECTION.KEY=VALUE (e.g. "
                        "run.dt=1e-7, species.NAME.phi=1e-3)", arg);
  *dot = 0;
  if (c->noverrides < 32)
    snprintf(c->overrides[c->noverrides++], sizeof c->overrides[0], "%s",
             arg);
  const char *sn;
  if (sbi_col_is_species(path, &sn) && c->nsp) {
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
                 sbi_col_short_name(c, (size_t)k));
      }
      return sbi_col_fail(c, "--set %s: no section [%s]; species: %s", arg,
                          sec, names);
    }
  }
  return set_key(c, path, dot + 1, val, 1);
}

