/* collide.c — `smolbridge collide CONFIG.ini`: run the collision engine
 * from an INI file (libinih), print progress on stderr, write the time
 * series (CSV), snapshots (CSV) and a run summary (JSON) to an output
 * directory.  Every key, unit and default: docs/engine.md; examples:
 * the .ini files in examples/. */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <sys/stat.h>
#include <sys/types.h>

#include <ini.h>

#include <smolbridge/engine.h>
#include <smolbridge/kernel.h>
#include <smolbridge/langevin.h>

#include "cli.h"

#define MAXSPEC 16
#define MAXPART 64

typedef struct {
  char name[64];
  double radius, density, mass, tau, mu, B, T, phi, cc;
  long count;
  int family;
  int has_region;
  double region[6];
  double drift[3];
  int npart;                /* explicit particles (key `particle`) */
  double part[MAXPART][6];  /* x y z ux uy uz (2-D: x y ux uy) */
} spec_cfg;

typedef struct {
  /* [run] */
  unsigned long seed;
  int dim;
  double L[3];
  double dt, t_end, warmup, thermalize;
  long steps;
  char neigh[32], detect[32], outcome[32];
  double eta;
  double lv_eps, lv_xtol, lv_tol;   /* detect = langevin (0: default) */
  long sample_every, snapshot_every, sort_every;
  char rng[32];
  char output[512], checkpoint[512], restart[512];
  /* [agglo] (outcome = merge | dlvo; lib/engine/engine_merge.c) */
  char growth[16], erel[16];
  double wmax, wmax_kT;
  long erel_normal, kobs;
  /* [fluid] */
  char fluid[32];
  int fluid_set;
  double U[3], G;
  /* species */
  spec_cfg sp[MAXSPEC];
  int nsp;
  /* parse errors */
  char err[512];
  int nerr;
} config;

static void cfg_default(config *c)
{
  memset(c, 0, sizeof *c);
  c->seed = 1;
  c->dim = 3;
  c->L[0] = c->L[1] = c->L[2] = NAN;
  c->dt = NAN;
  c->t_end = NAN;
  c->steps = -1;
  strcpy(c->neigh, "cells");
  strcpy(c->detect, "ballistic");
  strcpy(c->outcome, "elastic");
  c->eta = 1.0;
  c->sample_every = -1;
  strcpy(c->output, "collide-out");
  strcpy(c->fluid, "rest");
  strcpy(c->rng, "mt19937");
  strcpy(c->growth, "stokes");
  strcpy(c->erel, "contact");
  c->wmax_kT = NAN;
  c->kobs = 10;
}

static int fail(config *c, const char *fmt, ...)
{
  if (c->nerr++ == 0) {
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(c->err, sizeof c->err, fmt, ap);
    va_end(ap);
  }
  return 0;  /* inih: error on this line */
}

/* Parse a double ("inf" accepted where allowed). */
static int num(config *c, const char *sec, const char *key, const char *v,
               double *out, double lo, double hi, int allow_inf)
{
  char *end;
  errno = 0;
  double x = strtod(v, &end);
  while (*end == ' ' || *end == '\t')
    end++;
  if (end == v || *end || errno == ERANGE || isnan(x) ||
      (isinf(x) && !allow_inf))
    return fail(c, "[%s] %s = '%s': not a number", sec, key, v);
  if (!(x >= lo && x <= hi))
    return fail(c, "[%s] %s = %g: out of range [%g, %g]", sec, key, x, lo,
                hi);
  *out = x;
  return 1;
}

static int vec(config *c, const char *sec, const char *key, const char *v,
               double *out, int nmin, int nmax)
{
  int k = 0;
  const char *p = v;
  char *end;
  while (*p) {
    while (*p == ' ' || *p == '\t' || *p == ',')
      p++;
    if (!*p)
      break;
    if (k >= nmax)
      return fail(c, "[%s] %s: more than %d numbers", sec, key, nmax);
    errno = 0;
    double x = strtod(p, &end);
    if (end == p || !isfinite(x) || errno == ERANGE)
      return fail(c, "[%s] %s = '%s': not a list of numbers", sec, key, v);
    out[k++] = x;
    p = end;
  }
  if (k < nmin)
    return fail(c, "[%s] %s: needs %d to %d numbers", sec, key, nmin, nmax);
  return k;
}

static int str(config *c, const char *sec, const char *key, const char *v,
               char *out, size_t len)
{
  if (strlen(v) >= len)
    return fail(c, "[%s] %s: value too long", sec, key);
  strcpy(out, v);
  return 1;
}

static int integer(config *c, const char *sec, const char *key,
                   const char *v, long *out, long lo, long hi)
{
  double x;
  if (!num(c, sec, key, v, &x, (double)lo, (double)hi, 0))
    return 0;
  if (x != floor(x))
    return fail(c, "[%s] %s = %g: must be an integer", sec, key, x);
  *out = (long)x;
  return 1;
}

static int handler(void *user, const char *sec, const char *key,
                   const char *v)
{
  config *c = user;
  if (!strcmp(sec, "run")) {
    long l;
    if (!strcmp(key, "seed")) {
      if (!integer(c, sec, key, v, &l, 0, 4294967295L))
        return 0;
      c->seed = (unsigned long)l;
      return 1;
    }
    if (!strcmp(key, "dim")) {
      if (!integer(c, sec, key, v, &l, 2, 3))
        return 0;
      c->dim = (int)l;
      return 1;
    }
    if (!strcmp(key, "L")) {
      double x;
      if (!num(c, sec, key, v, &x, 1e-300, 1e300, 0))
        return 0;
      c->L[0] = c->L[1] = c->L[2] = x;
      return 1;
    }
    if (!strcmp(key, "Lx"))
      return num(c, sec, key, v, &c->L[0], 1e-300, 1e300, 0);
    if (!strcmp(key, "Ly"))
      return num(c, sec, key, v, &c->L[1], 1e-300, 1e300, 0);
    if (!strcmp(key, "Lz"))
      return num(c, sec, key, v, &c->L[2], 1e-300, 1e300, 0);
    if (!strcmp(key, "dt"))
      return num(c, sec, key, v, &c->dt, 1e-300, 1e300, 0);
    if (!strcmp(key, "t_end"))
      return num(c, sec, key, v, &c->t_end, 0, 1e300, 0);
    if (!strcmp(key, "steps"))
      return integer(c, sec, key, v, &c->steps, 0, 2000000000L);
    if (!strcmp(key, "warmup"))
      return num(c, sec, key, v, &c->warmup, 0, 1e300, 0);
    if (!strcmp(key, "thermalize"))
      return num(c, sec, key, v, &c->thermalize, 0, 1e300, 0);
    if (!strcmp(key, "neigh"))
      return str(c, sec, key, v, c->neigh, sizeof c->neigh);
    if (!strcmp(key, "detect"))
      return str(c, sec, key, v, c->detect, sizeof c->detect);
    if (!strcmp(key, "outcome"))
      return str(c, sec, key, v, c->outcome, sizeof c->outcome);
    if (!strcmp(key, "eta"))
      return num(c, sec, key, v, &c->eta, 0, 1, 0);
    if (!strcmp(key, "langevin_eps"))
      return num(c, sec, key, v, &c->lv_eps, 1e-300, 0.1, 0);
    if (!strcmp(key, "langevin_xtol"))
      return num(c, sec, key, v, &c->lv_xtol, 1e-300, 0.01, 0);
    if (!strcmp(key, "langevin_tol"))
      return num(c, sec, key, v, &c->lv_tol, 1e-300, 0.5, 0);
    if (!strcmp(key, "sample_every"))
      return integer(c, sec, key, v, &c->sample_every, 0, 2000000000L);
    if (!strcmp(key, "sort_every"))
      return integer(c, sec, key, v, &c->sort_every, 0, 2000000000L);
    if (!strcmp(key, "rng")) {
      if (strcmp(v, "mt19937") && strcmp(v, "taus2"))
        return fail(c, "[run] rng = '%s': must be mt19937 or taus2", v);
      return str(c, sec, key, v, c->rng, sizeof c->rng);
    }
    if (!strcmp(key, "snapshot_every"))
      return integer(c, sec, key, v, &c->snapshot_every, 0, 2000000000L);
    if (!strcmp(key, "output"))
      return str(c, sec, key, v, c->output, sizeof c->output);
    if (!strcmp(key, "checkpoint"))
      return str(c, sec, key, v, c->checkpoint, sizeof c->checkpoint);
    if (!strcmp(key, "restart"))
      return str(c, sec, key, v, c->restart, sizeof c->restart);
    return fail(c, "[run]: unknown key '%s'", key);
  }
  if (!strcmp(sec, "agglo")) {
    if (!strcmp(key, "growth"))
      return str(c, sec, key, v, c->growth, sizeof c->growth);
    if (!strcmp(key, "erel"))
      return str(c, sec, key, v, c->erel, sizeof c->erel);
    if (!strcmp(key, "wmax"))
      return num(c, sec, key, v, &c->wmax, 0, 1e300, 0);
    if (!strcmp(key, "wmax_kT"))
      return num(c, sec, key, v, &c->wmax_kT, 0, 1e300, 0);
    if (!strcmp(key, "erel_normal"))
      return integer(c, sec, key, v, &c->erel_normal, 0, 1);
    if (!strcmp(key, "kobs"))
      return integer(c, sec, key, v, &c->kobs, 1, 100000);
    return fail(c, "[agglo]: unknown key '%s'", key);
  }
  if (!strcmp(sec, "fluid")) {
    c->fluid_set = 1;
    if (!strcmp(key, "type"))
      return str(c, sec, key, v, c->fluid, sizeof c->fluid);
    if (!strcmp(key, "U"))
      return vec(c, sec, key, v, c->U, 2, 3) > 0;
    if (!strcmp(key, "G"))
      return num(c, sec, key, v, &c->G, -1e300, 1e300, 0);
    return fail(c, "[fluid]: unknown key '%s'", key);
  }
  if (!strncmp(sec, "species", 7) && (sec[7] == ' ' || sec[7] == '.' ||
                                      sec[7] == ':' || !sec[7])) {
    spec_cfg *s = NULL;
    for (int k = 0; k < c->nsp; k++)
      if (!strcmp(c->sp[k].name, sec))
        s = &c->sp[k];
    if (!s) {
      if (c->nsp == MAXSPEC)
        return fail(c, "[%s]: more than %d species", sec, MAXSPEC);
      s = &c->sp[c->nsp++];
      memset(s, 0, sizeof *s);
      snprintf(s->name, sizeof s->name, "%s", sec);
      s->radius = s->density = s->mass = s->tau = s->mu = s->B = NAN;
      s->T = NAN;
      s->phi = NAN;
      s->cc = 1.0;
      s->count = -1;
    }
    if (!strcmp(key, "radius"))
      return num(c, sec, key, v, &s->radius, 1e-300, 1e300, 0);
    if (!strcmp(key, "diameter")) {
      double d;
      if (!num(c, sec, key, v, &d, 1e-300, 1e300, 0))
        return 0;
      s->radius = 0.5 * d;
      return 1;
    }
    if (!strcmp(key, "density"))
      return num(c, sec, key, v, &s->density, 1e-300, 1e300, 0);
    if (!strcmp(key, "mass"))
      return num(c, sec, key, v, &s->mass, 1e-300, 1e300, 0);
    if (!strcmp(key, "tau"))
      return num(c, sec, key, v, &s->tau, 1e-300, INFINITY, 1);
    if (!strcmp(key, "mu"))
      return num(c, sec, key, v, &s->mu, 1e-300, 1e300, 0);
    if (!strcmp(key, "cunningham"))
      return num(c, sec, key, v, &s->cc, 1.0, 1e300, 0);
    if (!strcmp(key, "B"))
      return num(c, sec, key, v, &s->B, 0, 1e300, 0);
    if (!strcmp(key, "T"))
      return num(c, sec, key, v, &s->T, 0, 1e300, 0);
    if (!strcmp(key, "count")) {
      long l;
      if (!integer(c, sec, key, v, &l, 0, 1000000000L))
        return 0;
      s->count = l;
      return 1;
    }
    if (!strcmp(key, "phi"))
      return num(c, sec, key, v, &s->phi, 0, 0.5, 0);
    if (!strcmp(key, "family")) {
      long l;
      if (!integer(c, sec, key, v, &l, 0, SB_ENGINE_MAXFAM - 1))
        return 0;
      s->family = (int)l;
      return 1;
    }
    if (!strcmp(key, "region")) {
      int k = vec(c, sec, key, v, s->region, 4, 6);
      if (k <= 0)
        return 0;
      if (k == 5)
        return fail(c, "[%s] region: needs 4 (2-D) or 6 (3-D) numbers",
                    sec);
      s->has_region = k;
      return 1;
    }
    if (!strcmp(key, "drift"))
      return vec(c, sec, key, v, s->drift, 2, 3) > 0;
    if (!strcmp(key, "particle")) {
      double q[6] = {0, 0, 0, 0, 0, 0};
      if (s->npart == MAXPART)
        return fail(c, "[%s] particle: more than %d", sec, MAXPART);
      int k = vec(c, sec, key, v, q, 4, 6);
      if (k <= 0)
        return 0;
      if (k == 5)
        return fail(c, "[%s] particle: needs 4 (2-D: x y ux uy) or 6 "
                    "(3-D) numbers", sec);
      double *o = s->part[s->npart++];
      if (k == 4) {
        o[0] = q[0], o[1] = q[1], o[2] = 0, o[3] = q[2], o[4] = q[3];
        o[5] = 0;
      } else
        memcpy(o, q, sizeof q);
      return 1;
    }
    return fail(c, "[%s]: unknown key '%s'", sec, key);
  }
  return fail(c, "unknown section [%s]", sec);
}

/* ------------------------------------------------------------ build */

static int mkdir_p(const char *path)
{
  char buf[1024];
  snprintf(buf, sizeof buf, "%s", path);
  for (char *p = buf + 1; *p; p++)
    if (*p == '/') {
      *p = 0;
      if (mkdir(buf, 0777) && errno != EEXIST)
        return -1;
      *p = '/';
    }
  if (mkdir(buf, 0777) && errno != EEXIST)
    return -1;
  return 0;
}

#define PI 3.14159265358979323846

/* Complete a species from the alternative keys; message on error. */
static int species_build(const spec_cfg *s,
                         sb_engine_species *o, char *msg, size_t len)
{
  if (!(s->radius > 0)) {
    snprintf(msg, len, "[%s]: radius (or diameter) is required", s->name);
    return -1;
  }
  double d = 2 * s->radius, m = s->mass;
  if (isnan(m)) {
    if (!(s->density > 0)) {
      snprintf(msg, len, "[%s]: mass or density is required", s->name);
      return -1;
    }
    m = sb_sphere_mass(s->density, d);  /* spheres, also in 2-D */
  }
  double tau = s->tau;
  if (isnan(tau)) {
    if (!(s->mu > 0) || !(s->density > 0)) {
      snprintf(msg, len, "[%s]: tau, or mu and density (Stokes tau), is "
               "required", s->name);
      return -1;
    }
    tau = sb_stokes_tau(s->density, d, s->mu, s->cc);
  }
  double T = isnan(s->T) ? 0.0 : s->T, B = s->B;
  if (isnan(B)) {
    if (isinf(tau))
      B = 0.0;
    else if (T > 0)
      B = sb_brownian_B(T, m, tau);
    else {
      snprintf(msg, len, "[%s]: B or T is required", s->name);
      return -1;
    }
  }
  if (isinf(tau) && !(T > 0)) {
    snprintf(msg, len, "[%s]: free flight (tau = inf) needs T > 0",
             s->name);
    return -1;
  }
  *o = (sb_engine_species){s->radius, m, tau, B, T};
  return 0;
}

static long species_count(const config *c, const spec_cfg *s, double vol)
{
  if (s->count >= 0)
    return s->count + s->npart;
  if (!isnan(s->phi)) {
    double r = s->radius;
    double v1 = c->dim == 3 ? 4.0 / 3.0 * PI * r * r * r : PI * r * r;
    return lround(s->phi * vol / v1) + s->npart;
  }
  return s->npart > 0 ? s->npart : -1;
}

/* ------------------------------------------------------------ output */

/* Per-species-pair kernels sampled with the time series: the pairs
 * (a <= b) of the species declared in the file (at most 4 species, 10
 * pairs, in series.csv; all tracked pairs in summary.json). */
#define SERIES_MAXSP 4
typedef struct {
  int nsp;            /* species with columns in series.csv */
  double *rows;       /* per sample: t, then K, lo, hi per pair */
  size_t nrows, cap;
} pair_series;

static int npairs_of(int nsp) { return nsp * (nsp + 1) / 2; }

/* "he" for the section [species he] */
static const char *short_name(const config *c, size_t k)
{
  if ((int)k >= c->nsp)
    return "cluster";
  const char *n = c->sp[k].name;
  return strncmp(n, "species ", 8) == 0 ? n + 8 : n;
}

static int pair_series_sample(pair_series *ps, const sb_engine *e)
{
  if (ps->nsp <= 1)
    return 0;
  size_t w = 1 + 3 * (size_t)npairs_of(ps->nsp);
  if (ps->nrows == ps->cap) {
    size_t nc = ps->cap ? 2 * ps->cap : 256;
    double *nr = realloc(ps->rows, nc * w * sizeof *nr);
    if (!nr)
      return -1;
    ps->rows = nr;
    ps->cap = nc;
  }
  double *r = ps->rows + ps->nrows++ * w;
  r[0] = sb_engine_time(e);
  int q = 0;
  for (int a = 0; a < ps->nsp; a++)
    for (int b = a; b < ps->nsp; b++, q++) {
      sb_engine_pair_stats st;
      sb_engine_pair_kernel(e, (size_t)a, (size_t)b, 0.95, &st);
      r[1 + 3 * q] = st.K;
      r[2 + 3 * q] = st.lo;
      r[3 + 3 * q] = st.hi;
    }
  return 0;
}

/* The theoretical kernels that apply to species pair (a, b) with the fluid
 * at rest, written as JSON members: free flight (both tau = inf) at a
 * common T: kinetic theory; Langevin species: the continuum (Smoluchowski)
 * kernel 4 pi (D_a + D_b)(r_a + r_b), D = (B tau)^2/2, and with a common
 * T > 0 the free-molecular kernel and the transition kernel of
 * Gopalakrishnan & Hogan (2011) with its Kn_D. */
static void json_references(FILE *f, const config *c,
                            const sb_engine_species *sa,
                            const sb_engine_species *sb)
{
  fprintf(f, "\"references\": {");
  int rest = !strcmp(c->fluid, "rest");
  int same_T = sa->T > 0 && sa->T == sb->T;
  const char *sep = "";
  if (rest && isinf(sa->tau) && isinf(sb->tau) && same_T) {
    fprintf(f, "\"kinetic\": %.17g",
            sb_kernel_kinetic(2 * sa->radius, 2 * sb->radius, sa->mass,
                              sb->mass, sa->T));
  } else if (rest && isfinite(sa->tau) && isfinite(sb->tau)) {
    double ba = sa->B * sa->tau, bb = sb->B * sb->tau;
    fprintf(f, "\"continuum\": %.17g",
            sb_kernel_diffusion(sa->radius, sb->radius, ba * ba, bb * bb));
    sep = ", ";
    if (same_T) {
      double R = sa->radius + sb->radius;
      double mr = sa->mass * sb->mass / (sa->mass + sb->mass);
      fprintf(f, "%s\"free_molecular\": %.17g, \"transition_gh\": %.17g, "
              "\"Kn_D\": %.17g", sep,
              PI * R * R * sqrt(8 * SB_BOLTZMANN * sa->T / (PI * mr)),
              sb_kernel_brownian_gh(sa->radius, sb->radius, sa->mass,
                                    sb->mass, sa->tau, sb->tau, sa->T),
              sb_kernel_brownian_gh_kn(sa->radius, sb->radius, sa->mass,
                                       sb->mass, sa->tau, sb->tau, sa->T));
    }
  }
  fprintf(f, "}");
}

static void write_json(FILE *f, const config *c, const sb_engine *e,
                       double secs)
{
  const sb_engine_params *p = sb_engine_get_params(e);
  sb_engine_stats st;
  sb_engine_get_stats(e, &st);
  double K = NAN, lo = NAN, hi = NAN;
  sb_engine_kernel(e, 0.95, &K, &lo, &hi);
  fprintf(f, "{\n  \"program\": \"smolbridge collide\",\n");
  fprintf(f, "  \"version\": \"%s\",\n", sb_version());
  fprintf(f, "  \"seed\": %lu,\n", c->seed);
  fprintf(f, "  \"dim\": %d,\n  \"L\": [%.17g, %.17g, %.17g],\n", p->dim,
          p->L[0], p->L[1], p->dim == 3 ? p->L[2] : 0.0);
  fprintf(f, "  \"dt\": %.17g,\n  \"neigh\": \"%s\",\n  \"detect\": "
          "\"%s\",\n  \"outcome\": \"%s\",\n  \"eta\": %.17g,\n",
          p->dt, c->neigh, c->detect, c->outcome, p->eta);
  fprintf(f, "  \"fluid\": \"%s\",\n", c->fluid);
  fprintf(f, "  \"rng\": \"%s\",\n",
          p->rng_type ? p->rng_type->name : gsl_rng_mt19937->name);
  fprintf(f, "  \"species\": [\n");
  const sb_engine_species *s;
  for (size_t k = 0; (s = sb_engine_get_species(e, k)); k++) {
    char tau[40];
    if (isinf(s->tau))
      snprintf(tau, sizeof tau, "\"inf\"");
    else
      snprintf(tau, sizeof tau, "%.17g", s->tau);
    fprintf(f, "    {\"radius\": %.17g, \"mass\": %.17g, \"tau\": %s, "
            "\"B\": %.17g, \"T\": %.17g}%s\n",
            s->radius, s->mass, tau, s->B, s->T,
            sb_engine_get_species(e, k + 1) ? "," : "");
  }
  fprintf(f, "  ],\n  \"particles\": %zu,\n", sb_engine_count(e));
  fprintf(f, "  \"time\": %.17g,\n  \"steps\": %llu,\n", st.t,
          (unsigned long long)st.steps);
  fprintf(f, "  \"t_measure_start\": %.17g,\n  \"t_measure_end\": %.17g,\n",
          st.t_reset, st.t);
  fprintf(f, "  \"pair_exposure\": %.17g,\n", st.exposure);
  fprintf(f, "  \"collisions\": %llu,\n  \"candidates\": %llu,\n  "
          "\"dropped\": %llu,\n  \"redetected\": %llu,\n",
          (unsigned long long)st.ncoll, (unsigned long long)st.ncand,
          (unsigned long long)st.dropped,
          (unsigned long long)st.redetected);
  if (isnan(K))
    fprintf(f, "  \"kernel\": {\"K\": null, \"ci95\": null, \"why\": "
            "\"no pair exposure in the measured interval\"},\n");
  else
    fprintf(f, "  \"kernel\": {\"K\": %.17g, \"ci95\": [%.17g, %.17g]},\n",
            K, lo, hi);
  /* per species pair (a <= b), with the theory that applies */
  fprintf(f, "  \"pair_kernels\": [");
  int firstp = 1;
  const sb_engine_species *sa, *sb;
  for (size_t a = 0; a < SB_ENGINE_PAIR_SPECIES &&
                     (sa = sb_engine_get_species(e, a)); a++)
    for (size_t b = a; b < SB_ENGINE_PAIR_SPECIES &&
                       (sb = sb_engine_get_species(e, b)); b++) {
      sb_engine_pair_stats ps;
      sb_engine_pair_kernel(e, a, b, 0.95, &ps);
      if (!(ps.exposure > 0.0))
        continue;
      fprintf(f, "%s\n    {\"species\": [\"%s\", \"%s\"], "
              "\"collisions\": %llu, \"exposure\": %.17g, \"K\": %.17g, "
              "\"ci95\": [%.17g, %.17g], ", firstp ? "" : ",",
              short_name(c, a), short_name(c, b),
              (unsigned long long)ps.ncoll, ps.exposure, ps.K, ps.lo,
              ps.hi);
      json_references(f, c, sa, sb);
      fprintf(f, "}");
      firstp = 0;
    }
  fprintf(f, "%s],\n", firstp ? "" : "\n  ");
  fprintf(f, "  \"family_collisions\": [");
  int first = 1;
  for (int a = 0; a < SB_ENGINE_MAXFAM; a++)
    for (int b = a; b < SB_ENGINE_MAXFAM; b++)
      if (st.fam[a][b]) {
        fprintf(f, "%s{\"a\": %d, \"b\": %d, \"n\": %llu}", first ? "" : ", ",
                a, b, (unsigned long long)st.fam[a][b]);
        first = 0;
      }
  fprintf(f, "],\n  \"wall_seconds\": %.3f\n}\n", secs);
}

static int write_series(const char *path, const sb_engine *e,
                        const config *c, const pair_series *ps)
{
  FILE *f = fopen(path, "w");
  if (!f)
    return -1;
  size_t n;
  const sb_engine_sample *s = sb_engine_series(e, &n);
  int np = ps->nsp > 1 ? npairs_of(ps->nsp) : 0;
  fprintf(f, "t,ncoll,K,K_lo,K_hi,ekin,px,py,pz");
  for (int a = 0; a < ps->nsp && np; a++)
    for (int b = a; b < ps->nsp; b++)
      fprintf(f, ",K_%s_%s,K_%s_%s_lo,K_%s_%s_hi", short_name(c, a),
              short_name(c, b), short_name(c, a), short_name(c, b),
              short_name(c, a), short_name(c, b));
  fprintf(f, "\n");
  size_t w = 1 + 3 * (size_t)np;
  for (size_t k = 0; k < n; k++) {
    fprintf(f, "%.17g,%llu,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g",
            s[k].t, (unsigned long long)s[k].ncoll, s[k].K, s[k].K_lo,
            s[k].K_hi, s[k].ekin, s[k].p[0], s[k].p[1], s[k].p[2]);
    /* the pair row sampled at the same time, if any */
    const double *r = NULL;
    for (size_t q = 0; np && q < ps->nrows; q++)
      if (ps->rows[q * w] == s[k].t)
        r = ps->rows + q * w;
    for (int q = 0; q < 3 * np; q++)
      fprintf(f, ",%.17g", r ? r[1 + q] : NAN);
    fprintf(f, "\n");
  }
  return fclose(f) ? -1 : 0;
}

static void usage(FILE *f)
{
  fprintf(f,
"Usage: smolbridge collide CONFIG.ini\n"
"\n"
"Run the Lagrangian collision engine described by CONFIG.ini:\n"
"  [run]          seed, dim, L | Lx Ly Lz (m), dt (s), t_end (s) | steps,\n"
"                 warmup (s), thermalize (K), neigh, detect (ballistic |\n"
"                 overlap | langevin), outcome, eta, langevin_eps,\n"
"                 langevin_xtol, langevin_tol,\n"
"                 sample_every, snapshot_every, sort_every, rng, output,\n"
"                 checkpoint, restart\n"
"  [agglo]        (outcome = merge | dlvo) growth = stokes | constant,\n"
"                 wmax (J) | wmax_kT, erel = contact | stationary,\n"
"                 erel_normal, kobs; writes OUTPUT/sizes.csv\n"
"  [fluid]        type = rest | uniform | shear, U (m/s), G (1/s)\n"
"  [species NAME] radius | diameter (m), mass (kg) | density (kg/m^3),\n"
"                 tau (s, inf) | mu (Pa s) [cunningham], B | T (K),\n"
"                 count | phi | particle, family, region (m), drift (m/s)\n"
"Writes OUTPUT/series.csv, OUTPUT/summary.json, OUTPUT/snap_*.csv.\n"
"Progress goes to stderr.  Every key with its unit and default:\n"
"docs/engine.md; examples: examples/*.ini.\n");
}

/* Agglomeration context of the run (outcome = merge | dlvo), NULL
 * otherwise; its size series is sampled with the engine's series. */
static sb_agglo *agglo_ctx;

static int progress_step(sb_engine *e, double t_stop, double t0, FILE *err,
                         pair_series *ps)
{
  double last = -1;
  while (sb_engine_time(e) < t_stop - 0.5 * sb_engine_get_params(e)->dt) {
    int st = sb_engine_step(e);
    if (st)
      return st;
    size_t every = sb_engine_get_params(e)->sample_every;
    if (ps && every) {
      sb_engine_stats s0;
      sb_engine_get_stats(e, &s0);
      if (s0.steps % every == 0 && pair_series_sample(ps, e))
        return SB_ENOMEM;
    }
    if (agglo_ctx && every) {
      sb_engine_stats s0;
      sb_engine_get_stats(e, &s0);
      if (s0.steps % every == 0 && (st = sb_agglo_sample(agglo_ctx, e)))
        return st;
    }
    double frac = (sb_engine_time(e) - t0) / (t_stop - t0);
    if (frac - last >= 0.1 || frac >= 1.0 - 1e-12) {
      sb_engine_stats s;
      sb_engine_get_stats(e, &s);
      fprintf(err, "collide: t = %.4g s (%3.0f%%), %llu collisions\n",
              sb_engine_time(e), 100 * frac, (unsigned long long)s.ncoll);
      last = frac;
    }
  }
  return SB_SUCCESS;
}

int sbc_collide_main(int argc, char **argv)
{
  if (argc < 2 || !strcmp(argv[1], "-h") || !strcmp(argv[1], "--help")) {
    usage(argc < 2 ? stderr : stdout);
    return argc < 2 ? 2 : 0;
  }
  if (argc > 2) {
    fprintf(stderr, "collide: one CONFIG.ini expected\n");
    return 2;
  }
  static config c;
  cfg_default(&c);
  int line = ini_parse(argv[1], handler, &c);
  if (line < 0) {
    fprintf(stderr, "collide: cannot read '%s'\n", argv[1]);
    return 1;
  }
  if (line > 0 || c.nerr) {
    fprintf(stderr, "collide: %s:%d: %s\n", argv[1], line,
            c.nerr ? c.err : "syntax error");
    return 1;
  }
  sb_engine *e = NULL;
  char msg[512];
  sb_engine_neigh nm;
  sb_engine_detect dm;
  sb_engine_outcome om;
  /* merge | dlvo: the engine starts with the elastic outcome, the
   * agglomeration outcome is attached once the particles exist */
  const int agglo = !strcmp(c.outcome, "merge") || !strcmp(c.outcome, "dlvo");
  om = SB_OUTCOME_ELASTIC;
  if (sb_engine_neigh_from_name(c.neigh, &nm) ||
      sb_engine_detect_from_name(c.detect, &dm) ||
      (!agglo && sb_engine_outcome_from_name(c.outcome, &om))) {
    fprintf(stderr, "collide: [run] neigh/detect/outcome: %s\n",
            sb_last_error());
    return 1;
  }
  if (c.restart[0]) {
    int st;
    e = sb_engine_checkpoint_load(c.restart, &st);
    if (!e) {
      fprintf(stderr, "collide: restart: %s\n", sb_last_error());
      return 1;
    }
  } else {
    sb_engine_params p;
    sb_engine_params_default(&p);
    p.dim = c.dim;
    for (int k = 0; k < c.dim; k++) {
      if (isnan(c.L[k])) {
        fprintf(stderr, "collide: [run] L (or L%c) is required\n", 'x' + k);
        return 1;
      }
      p.L[k] = c.L[k];
    }
    if (isnan(c.dt)) {
      fprintf(stderr, "collide: [run] dt is required\n");
      return 1;
    }
    p.dt = c.dt;
    p.seed = c.seed;
    p.neigh = nm;
    p.detect = dm;
    p.outcome = om;
    p.eta = c.eta;
    p.sort_every = (size_t)c.sort_every;
    p.rng_type = strcmp(c.rng, "taus2") ? gsl_rng_mt19937 : gsl_rng_taus2;
    if (c.nsp == 0) {
      fprintf(stderr, "collide: no [species NAME] section\n");
      return 1;
    }
    double vol = p.L[0] * p.L[1] * (c.dim == 3 ? p.L[2] : 1.0);
    long total = 0;
    for (int k = 0; k < c.nsp; k++) {
      long n = species_count(&c, &c.sp[k], vol);
      if (n < 0) {
        fprintf(stderr, "collide: [%s]: count, phi or particle is "
                "required\n",
                c.sp[k].name);
        return 1;
      }
      total += n;
    }
    p.capacity = total > 0 ? (size_t)total : 1;
    e = sb_engine_alloc(&p);
    if (!e) {
      fprintf(stderr, "collide: %s\n", sb_last_error());
      return 1;
    }
    for (int k = 0; k < c.nsp; k++) {
      sb_engine_species s;
      size_t idx;
      if (species_build(&c.sp[k], &s, msg, sizeof msg)) {
        fprintf(stderr, "collide: %s\n", msg);
        sb_engine_free(e);
        return 1;
      }
      if (sb_engine_add_species(e, &s, &idx)) {
        fprintf(stderr, "collide: [%s]: %s\n", c.sp[k].name,
                sb_last_error());
        sb_engine_free(e);
        return 1;
      }
    }
  }
  /* Langevin detector parameters (not in checkpoints: given again) */
  if (c.lv_eps > 0 || c.lv_xtol > 0 || c.lv_tol > 0) {
    sb_engine_langevin_params lp;
    sb_engine_langevin_params_default(&lp);
    if (c.lv_eps > 0)
      lp.eps = c.lv_eps;
    if (c.lv_xtol > 0)
      lp.xtol = c.lv_xtol;
    if (c.lv_tol > 0)
      lp.tol = c.lv_tol;
    if (sb_engine_set_langevin(e, &lp)) {
      fprintf(stderr, "collide: [run] langevin_*: %s\n", sb_last_error());
      sb_engine_free(e);
      return 1;
    }
  }
  /* fluid (on restart the saved field is kept unless [fluid] is given) */
  if (!c.restart[0] || c.fluid_set) {
    double q[3] = {0, 0, 0};
    sb_engine_fluid f;
    if (!strcmp(c.fluid, "rest"))
      f = SB_FLUID_REST;
    else if (!strcmp(c.fluid, "uniform")) {
      f = SB_FLUID_UNIFORM;
      memcpy(q, c.U, sizeof q);
    } else if (!strcmp(c.fluid, "shear")) {
      f = SB_FLUID_SHEAR;
      q[0] = c.G;
    } else {
      fprintf(stderr, "collide: [fluid] type = '%s': must be rest, uniform "
              "or shear\n", c.fluid);
      sb_engine_free(e);
      return 1;
    }
    sb_engine_set_fluid(e, f, q);
  }
  if (!c.restart[0]) {
    const sb_engine_params *p = sb_engine_get_params(e);
    double vol = p->L[0] * p->L[1] * (c.dim == 3 ? p->L[2] : 1.0);
    for (int k = 0; k < c.nsp; k++) {
      const spec_cfg *s = &c.sp[k];
      size_t n = (size_t)species_count(&c, s, vol);
      double lo[3] = {0, 0, 0}, hi[3];
      memcpy(hi, p->L, sizeof hi);
      if (s->has_region) {
        if ((s->has_region == 6) != (c.dim == 3)) {
          fprintf(stderr, "collide: [%s] region: %d numbers for dim %d\n",
                  s->name, s->has_region, c.dim);
          sb_engine_free(e);
          return 1;
        }
        for (int d = 0; d < c.dim; d++) {
          lo[d] = s->region[2 * d];
          hi[d] = s->region[2 * d + 1];
        }
      }
      for (int q = 0; q < s->npart; q++)
        if (sb_engine_add_particle(e, (size_t)k, s->family, s->part[q],
                                   s->part[q] + 3)) {
          fprintf(stderr, "collide: [%s] particle %d: %s\n", s->name, q + 1,
                  sb_last_error());
          sb_engine_free(e);
          return 1;
        }
      n -= (size_t)s->npart;
      if (n > 0 && sb_engine_fill_box(e, (size_t)k, s->family, n, lo, hi,
                                      s->drift)) {
        fprintf(stderr, "collide: [%s]: %s\n", s->name, sb_last_error());
        sb_engine_free(e);
        return 1;
      }
    }
    if (c.thermalize > 0 && sb_engine_thermalize(e, c.thermalize)) {
      fprintf(stderr, "collide: thermalize: %s\n", sb_last_error());
      sb_engine_free(e);
      return 1;
    }
  }
  if (agglo) {
    sb_agglo_params ap;
    sb_agglo_params_default(&ap);
    ap.rule = strcmp(c.outcome, "dlvo") ? SB_AGGLO_MERGE : SB_AGGLO_DLVO;
    ap.growth = !strcmp(c.growth, "constant") ? SB_AGGLO_CONSTANT
                                               : SB_AGGLO_STOKES;
    ap.erel = !strcmp(c.erel, "stationary") ? SB_AGGLO_EREL_STATIONARY
                                             : SB_AGGLO_EREL_CONTACT;
    ap.erel_normal = (int)c.erel_normal;
    ap.kobs = (size_t)c.kobs;
    const sb_engine_species *s0 = sb_engine_get_species(e, 0);
    ap.wmax = !isnan(c.wmax_kT) && s0
                  ? c.wmax_kT * SB_BOLTZMANN * s0->T
                  : c.wmax;
    if (c.restart[0] || (strcmp(c.growth, "constant") &&
                         strcmp(c.growth, "stokes")) ||
        (strcmp(c.erel, "contact") && strcmp(c.erel, "stationary")) ||
        !(agglo_ctx = sb_agglo_alloc(&ap)) ||
        sb_agglo_attach(e, agglo_ctx)) {
      fprintf(stderr, "collide: [agglo] (outcome %s): growth = constant | "
              "stokes, erel = contact | stationary, one primary species "
              "(the first), no restart; %s\n", c.outcome,
              c.restart[0] ? "" : sb_last_error());
      sb_agglo_free(agglo_ctx);
      sb_engine_free(e);
      return 1;
    }
  }
  const double dt = sb_engine_get_params(e)->dt;
  double t0 = sb_engine_time(e);
  /* t_end is the absolute end time (the warm-up is inside it); steps
   * counts the measured steps, after the warm-up */
  const double warm = c.restart[0] ? 0.0 : c.warmup;
  double t_end = !isnan(c.t_end) ? c.t_end
                 : c.steps >= 0  ? t0 + warm + (double)c.steps * dt
                                 : NAN;
  if (isnan(t_end)) {
    fprintf(stderr, "collide: [run] t_end or steps is required\n");
    sb_engine_free(e);
    return 1;
  }
  if (!(t_end - t0 - warm >= 0.5 * dt)) {
    fprintf(stderr, "collide: nothing to measure: the warm-up (%g s) does "
            "not end before t_end (%g s from t = %g s)\n", warm, t_end - t0,
            t0);
    sb_engine_free(e);
    return 2;
  }
  if (mkdir_p(c.output)) {
    fprintf(stderr, "collide: cannot create '%s': %s\n", c.output,
            strerror(errno));
    sb_engine_free(e);
    return 1;
  }
  /* time series every sample_every steps (default: 200 samples) */
  {
    long nst = lround((t_end - t0) / dt);
    sb_engine_set_sample_every(e, c.sample_every >= 0
                                      ? (size_t)c.sample_every
                                      : (size_t)(nst / 200 > 0 ? nst / 200
                                                               : 1));
  }
  fprintf(stderr, "collide: %zu particles, dt = %g s, t = %g -> %g s, "
          "seed %lu, output %s/\n", sb_engine_count(e), dt, t0, t_end,
          c.seed, c.output);
  pair_series pser = {c.nsp <= SERIES_MAXSP ? c.nsp : 0, NULL, 0, 0};
  if (agglo_ctx)
    pser.nsp = 0;  /* cluster sizes: sizes.csv */
  double tw0 = (double)clock() / CLOCKS_PER_SEC;
  int st = SB_SUCCESS;
  if (c.warmup > 0 && !c.restart[0]) {
    st = progress_step(e, t0 + c.warmup, t0, stderr, NULL);
    sb_engine_reset_counters(e);
  }
  char path[1100];
  long snap = 0;
  while (!st && sb_engine_time(e) < t_end - 0.5 * dt) {
    double t_next = t_end;
    if (c.snapshot_every > 0) {
      double ts = sb_engine_time(e) + (double)c.snapshot_every * dt;
      if (ts < t_next)
        t_next = ts;
    }
    st = progress_step(e, t_next, sb_engine_time(e), stderr, &pser);
    if (!st && c.snapshot_every > 0) {
      snprintf(path, sizeof path, "%s/snap_%06ld.csv", c.output, snap++);
      st = sb_engine_snapshot_csv(e, path);
    }
  }
  if (st) {
    fprintf(stderr, "collide: step failed: %s\n", sb_last_error());
    free(pser.rows);
    sb_engine_free(e);
    return 1;
  }
  double secs = (double)clock() / CLOCKS_PER_SEC - tw0;
  snprintf(path, sizeof path, "%s/series.csv", c.output);
  int werr = write_series(path, e, &c, &pser);
  free(pser.rows);
  if (werr) {
    fprintf(stderr, "collide: cannot write %s\n", path);
    sb_engine_free(e);
    return 1;
  }
  snprintf(path, sizeof path, "%s/summary.json", c.output);
  FILE *f = fopen(path, "w");
  if (!f) {
    fprintf(stderr, "collide: cannot write %s\n", path);
    sb_engine_free(e);
    return 1;
  }
  write_json(f, &c, e, secs);
  fclose(f);
  if (c.checkpoint[0] && sb_engine_checkpoint_save(e, c.checkpoint)) {
    fprintf(stderr, "collide: checkpoint: %s\n", sb_last_error());
    sb_engine_free(e);
    return 1;
  }
  if (agglo_ctx) {
    sb_agglo_stats as;
    sb_agglo_get_stats(agglo_ctx, &as);
    snprintf(path, sizeof path, "%s/sizes.csv", c.output);
    size_t nr, nc;
    const double *rows = sb_agglo_series(agglo_ctx, &nr, &nc);
    int last = nr > 0 && rows[(nr - 1) * nc] == sb_engine_time(e);
    if ((!last && sb_agglo_sample(agglo_ctx, e)) ||
        sb_agglo_series_csv(agglo_ctx, path))
      fprintf(stderr, "collide: cannot write %s\n", path);
    fprintf(stderr, "collide: %llu merges, %llu rebounds, %zu clusters; "
            "sizes in %s\n", (unsigned long long)as.nmerge,
            (unsigned long long)as.nrebound, sb_engine_count(e), path);
    sb_agglo_free(agglo_ctx);
    agglo_ctx = NULL;
  }
  double K, lo, hi;
  sb_engine_stats fs;
  sb_engine_get_stats(e, &fs);
  if (!sb_engine_kernel(e, 0.95, &K, &lo, &hi))
    fprintf(stderr, "collide: done; K_e = %.6g [%.6g, %.6g] (95%%) over "
            "[%g, %g] s\n", K, lo, hi, fs.t_reset, fs.t);
  else
    fprintf(stderr, "collide: done; no kernel: %s\n", sb_last_error());
  if (fs.dropped)
    fprintf(stderr, "collide: warning: %llu collision events were dropped "
            "(the custom detector does not re-examine pairs after an "
            "outcome within a step); the kernel is low by about that many "
            "collisions of %llu: shorten dt\n",
            (unsigned long long)fs.dropped, (unsigned long long)fs.ncoll);
  sb_engine_free(e);
  return 0;
}
