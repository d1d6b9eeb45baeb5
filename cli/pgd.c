/* pgd.c — `smolbridge pgd CONFIG.ini`: pressureless gas dynamics from an
 * INI file (<smolbridge/ini.h>): a 1-D Riemann problem or a 2-D run with inflows,
 * Eulerian, Lagrangian or domain-decomposed.  Writes fields.csv (and for
 * 2-D fields.vtk), exact.csv for Riemann problems, and summary.json to
 * the output directory; keys without effect are warned about on stderr.
 * Keys, units and defaults: docs/pgd.md. */
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

#include <smolbridge/ini.h>
#include <smolbridge/pgd.h>

#include "cli.h"
#include "ini_once.h"
#include "par.h"
#include "pgd_par.h"

typedef struct {
  sb_pgd_params p;
  double t_end, output_every;
  char method[16], output[512], kinds[64];
  char checkpoint[512], restart[512];  /* [run] checkpoint, restart */
  size_t bx, by;
  int have_riemann, have_initial, have_ny, have_L[2], have_x0;
  int n_origin, n_U, n_init_u;  /* numbers given (1: x only, 2: x y) */
  sb_pgd_riemann rp;
  double init_rho, init_u[2];
  /* inflow sections under construction */
  struct {
    char name[64];
    int side;
    double first, count, rho, u[2];
  } in[SB_PGD_MAXINFLOW];
  int nin;
  char err[512];
  char err_where[256];  /* "FILE:LINE" of the first error */
  sbc_ini_keys once;    /* the keys and headers read */
} config;

static int fail(config *c, const char *fmt, ...)
{
  if (!c->err[0]) {
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(c->err, sizeof c->err, fmt, ap);
    va_end(ap);
  }
  return 0; /* handler: error on this line (key_fn) */
}

static int num(config *c, const char *sec, const char *key, const char *v,
               double *out, double lo, double hi, const char *what)
{
  char *end;
  errno = 0;
  double x = strtod(v, &end);
  while (*end == ' ' || *end == '\t')
    end++;
  int inf_ok = isinf(hi) && isinf(x) && x > 0;
  if (end == v || *end || (errno == ERANGE && !inf_ok) || isnan(x) ||
      !(x >= lo && x <= hi) || (isinf(x) && !inf_ok))
    return fail(c, "[%s] %s = '%s': must be %s", sec, key, v, what);
  *out = x;
  return 1;
}

static int count(config *c, const char *sec, const char *key, const char *v,
                 size_t *out, double lo, double hi)
{
  double x;
  char what[96];
  snprintf(what, sizeof what, "an integer in [%g, %g]", lo, hi);
  if (!num(c, sec, key, v, &x, lo, hi, what))
    return 0;
  if (x != floor(x))
    return fail(c, "[%s] %s = '%s': must be %s", sec, key, v, what);
  *out = (size_t)x;
  return 1;
}

/* One or two numbers "a [b]". */
static int pair(config *c, const char *sec, const char *key, const char *v,
                double out[2], int *n)
{
  char *end;
  errno = 0;
  double a = strtod(v, &end), b = 0;
  const char *p = end;
  int k = end != v && isfinite(a) && errno != ERANGE;
  if (k) {
    while (*p == ' ' || *p == '\t' || *p == ',')
      p++;
    if (*p) {
      b = strtod(p, &end);
      k = end != p && isfinite(b) ? 2 : 0;
      while (k && (*end == ' ' || *end == '\t'))
        end++;
      if (*end)
        k = 0;
    }
  }
  if (!k)
    return fail(c, "[%s] %s = '%s': must be one or two finite numbers "
                "(x [y])", sec, key, v);
  out[0] = a;
  out[1] = b;
  if (n)
    *n = k;
  return 1;
}

static int side_of(const char *v)
{
  static const char *names[4] = {"west", "east", "south", "north"};
  for (int s = 0; s < 4; s++)
    if (!strcmp(v, names[s]))
      return s;
  return -1;
}

/* The sections of a configuration ("inflow NAME" any name). */
static int known_section(const char *sec)
{
  static const char *const names[] = {"run", "riemann", "initial", "drag",
                                      "boundary", "particles",
                                      "decomposition", NULL};
  return sbc_ini_section_known(sec, names, "inflow");
}

static int unknown_section(config *c, const char *sec)
{
  return fail(c, "unknown section [%s] (run, riemann, initial, drag, "
              "boundary, inflow NAME, particles, decomposition)", sec);
}

static int handler(void *user, const char *sec, const char *key,
                   const char *v)
{
  config *c = user;
  sb_pgd_params *p = &c->p;
  if (!strcmp(sec, "run")) {
    if (!strcmp(key, "dim")) {
      size_t d;
      if (!count(c, sec, key, v, &d, 1, 2))
        return 0;
      p->dim = (int)d;
      return 1;
    }
    if (!strcmp(key, "nx"))
      return count(c, sec, key, v, &p->nx, 2, 1e8);
    if (!strcmp(key, "ny")) {
      c->have_ny = 1;
      return count(c, sec, key, v, &p->ny, 2, 1e8);
    }
    if (!strcmp(key, "L")) {
      c->have_L[0] = c->have_L[1] = 1;
      if (!num(c, sec, key, v, &p->L[0], 1e-300, 1e300, "a length > 0"))
        return 0;
      p->L[1] = p->L[0];
      return 1;
    }
    if (!strcmp(key, "Lx") || !strcmp(key, "Ly")) {
      int d = key[1] == 'y';
      c->have_L[d] = 1;
      return num(c, sec, key, v, &p->L[d], 1e-300, 1e300, "a length > 0");
    }
    if (!strcmp(key, "origin")) {
      double o[2];
      if (!pair(c, sec, key, v, o, &c->n_origin))
        return 0;
      p->origin[0] = o[0];
      p->origin[1] = o[1];
      return 1;
    }
    if (!strcmp(key, "t_end"))
      return num(c, sec, key, v, &c->t_end, 0, 1e300, "a time >= 0");
    if (!strcmp(key, "scheme")) {
      sb_pgd_scheme s;
      if (sb_pgd_scheme_from_name(v, &s))
        return fail(c, "[run] scheme = '%s': must be upwind or muscl", v);
      p->scheme = s;
      return 1;
    }
    if (!strcmp(key, "cfl"))
      return num(c, sec, key, v, &p->cfl, 1e-6, 1,
                 "in (0, 1] (upwind) or (0, 0.5] (muscl)");
    if (!strcmp(key, "dt_max"))
      return num(c, sec, key, v, &p->dt_max, 1e-300, INFINITY,
                 "a time > 0 or inf");
    if (!strcmp(key, "method")) {
      if (strcmp(v, "euler") && strcmp(v, "lagrange") &&
          strcmp(v, "decomposition"))
        return fail(c, "[run] method = '%s': must be euler, lagrange or "
                    "decomposition", v);
      snprintf(c->method, sizeof c->method, "%s", v);
      return 1;
    }
    if (!strcmp(key, "output")) {
      if (!*v || strlen(v) >= sizeof c->output)
        return fail(c, "[run] output: must be a directory name (< 512 "
                    "characters)");
      snprintf(c->output, sizeof c->output, "%s", v);
      return 1;
    }
    if (!strcmp(key, "checkpoint") || !strcmp(key, "restart")) {
      char *dst = key[0] == 'c' ? c->checkpoint : c->restart;
      if (!*v || strlen(v) >= sizeof c->checkpoint)
        return fail(c, "[run] %s: must be a file name (< 512 characters)",
                    key);
      snprintf(dst, sizeof c->checkpoint, "%s", v);
      return 1;
    }
    if (!strcmp(key, "output_every"))
      return num(c, sec, key, v, &c->output_every, 1e-300, 1e300,
                 "a time interval > 0");
    if (!strcmp(key, "rho_floor"))
      return num(c, sec, key, v, &p->rho_floor, 0, 1e300, "a density >= 0");
    return fail(c, "[run]: unknown key '%s' (dim, nx, ny, L, Lx, Ly, "
                "origin, t_end, scheme, cfl, dt_max, method, output, "
                "output_every, rho_floor, checkpoint, restart)", key);
  }
  if (!strcmp(sec, "riemann")) {
    c->have_riemann = 1;
    sb_pgd_riemann *r = &c->rp;
    if (!strcmp(key, "x0")) {
      c->have_x0 = 1;
      return num(c, sec, key, v, &r->x0, -1e300, 1e300, "a position");
    }
    if (!strcmp(key, "rho_l"))
      return num(c, sec, key, v, &r->rho_l, 0, 1e300, "a density >= 0");
    if (!strcmp(key, "rho_r"))
      return num(c, sec, key, v, &r->rho_r, 0, 1e300, "a density >= 0");
    if (!strcmp(key, "u_l"))
      return num(c, sec, key, v, &r->u_l, -1e300, 1e300, "a velocity");
    if (!strcmp(key, "u_r"))
      return num(c, sec, key, v, &r->u_r, -1e300, 1e300, "a velocity");
    return fail(c, "[riemann]: unknown key '%s' (x0, rho_l, u_l, rho_r, "
                "u_r)", key);
  }
  if (!strcmp(sec, "initial")) {
    c->have_initial = 1;
    if (!strcmp(key, "rho"))
      return num(c, sec, key, v, &c->init_rho, 0, 1e300, "a density >= 0");
    if (!strcmp(key, "u"))
      return pair(c, sec, key, v, c->init_u, &c->n_init_u);
    return fail(c, "[initial]: unknown key '%s' (rho, u)", key);
  }
  if (!strcmp(sec, "drag")) {
    if (!strcmp(key, "tau"))
      return num(c, sec, key, v, &p->tau, 1e-300, INFINITY,
                 "a time > 0 or inf (no drag)");
    if (!strcmp(key, "U"))
      return pair(c, sec, key, v, p->ugas, &c->n_U);
    return fail(c, "[drag]: unknown key '%s' (tau, U)", key);
  }
  if (!strcmp(sec, "boundary")) {
    int s = side_of(key);
    if (s < 0)
      return fail(c, "[boundary]: unknown key '%s' (west, east, south, "
                  "north)", key);
    if (!strcmp(v, "transmissive"))
      p->bc[s] = SB_PGD_TRANSMISSIVE;
    else if (!strcmp(v, "outflow"))
      p->bc[s] = SB_PGD_OUTFLOW;
    else if (!strcmp(v, "periodic"))
      p->bc[s] = SB_PGD_PERIODIC;
    else
      return fail(c, "[boundary] %s = '%s': must be transmissive, outflow "
                  "or periodic", key, v);
    return 1;
  }
  if (!strcmp(sec, "particles")) {
    if (!strcmp(key, "inject_time"))
      return count(c, sec, key, v, &p->inject_time, 1, 1000);
    if (!strcmp(key, "inject_face"))
      return count(c, sec, key, v, &p->inject_face, 1, 1000);
    return fail(c, "[particles]: unknown key '%s' (inject_time, "
                "inject_face)", key);
  }
  if (!strcmp(sec, "decomposition")) {
    if (!strcmp(key, "blocks")) {
      double b[2];
      int n;
      if (!pair(c, sec, key, v, b, &n))
        return 0;
      if (n != 2 || b[0] < 1 || b[1] < 1 || b[0] > 64 || b[1] > 64 ||
          b[0] != floor(b[0]) || b[1] != floor(b[1]))
        return fail(c, "[decomposition] blocks = '%s': must be two "
                    "integers px py in [1, 64]", v);
      c->bx = (size_t)b[0];
      c->by = (size_t)b[1];
      return 1;
    }
    if (!strcmp(key, "kinds")) {
      if (strlen(v) >= sizeof c->kinds || strspn(v, "EL") != strlen(v))
        return fail(c, "[decomposition] kinds = '%s': letters E "
                    "(Eulerian) and L (Lagrangian), one per block", v);
      snprintf(c->kinds, sizeof c->kinds, "%s", v);
      return 1;
    }
    return fail(c, "[decomposition]: unknown key '%s' (blocks, kinds)",
                key);
  }
  if (!strncmp(sec, "inflow", 6) && (sec[6] == ' ' || !sec[6])) {
    int k;
    for (k = 0; k < c->nin; k++)
      if (!strcmp(c->in[k].name, sec))
        break;
    if (k == c->nin) {
      if (c->nin == SB_PGD_MAXINFLOW)
        return fail(c, "[%s]: more than %d inflow sections", sec,
                    SB_PGD_MAXINFLOW);
      c->nin++;
      memset(&c->in[k], 0, sizeof c->in[k]);
      snprintf(c->in[k].name, sizeof c->in[k].name, "%s", sec);
      c->in[k].side = -1;
      c->in[k].count = -1;
      c->in[k].rho = NAN;
    }
    if (!strcmp(key, "side")) {
      c->in[k].side = side_of(v);
      if (c->in[k].side < 0)
        return fail(c, "[%s] side = '%s': must be west, east, south or "
                    "north", sec, v);
      return 1;
    }
    if (!strcmp(key, "first"))
      return num(c, sec, key, v, &c->in[k].first, 0, 1e8,
                 "a boundary cell index >= 0");
    if (!strcmp(key, "count"))
      return num(c, sec, key, v, &c->in[k].count, 1, 1e8,
                 "a number of cells >= 1");
    if (!strcmp(key, "rho"))
      return num(c, sec, key, v, &c->in[k].rho, 0, 1e300, "a density >= 0");
    if (!strcmp(key, "u"))
      return pair(c, sec, key, v, c->in[k].u, NULL);
    return fail(c, "[%s]: unknown key '%s' (side, first, count, rho, u)",
                sec, key);
  }
  return unknown_section(c, sec);
}

/* sb_ini_key_fn: the handler, with the place of the first error; a key
 * given twice is an error (no value is replaced silently). */
static int key_fn(void *user, const char *sec, const char *key,
                  const char *v, const char *where)
{
  config *c = user;
  const int had = c->err[0] != 0;
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
  if (known && !sbc_ini_once(&c->once, sec, NULL, where, msg, sizeof msg))
    return 0;
  if (!c->err[0])
    snprintf(c->err_where, sizeof c->err_where, "%s", where);
  /* an unknown header is an error even without keys under it */
  if (!known)
    unknown_section(c, sec);
  else
    fail(c, "%s", msg);
  return 1;
}

/* ------------------------------------------------ keys without effect */

/* If cond: "pgd: warning: FILE:LINE: [sec] key ignored: why", when key was
 * read (the format of `smolbridge collide`). */
static void unused(config *c, int cond, const char *sec,
                   const char *key, const char *why)
{
  if (cond)
    sbc_ini_unused(&c->once, "pgd", sec, key, why);
}

/* A key "x [y]" read with its y value (n = 2) in 1-D. */
static void unused_y(config *c, int n, const char *sec,
                     const char *key)
{
  const char *w = sbc_ini_where(&c->once, sec, key);
  if (w && n == 2)
    sbc_ini_warn(&c->once, "pgd", w, "[%s] %s ignored in y: dim = 1 (the x value is "
                 "used)", sec, key);
}

/* Warn about the keys read that have no effect in this configuration
 * (the run goes on; docs/pgd.md §9). */
static void warn_unused(config *c)
{
  const int dim = c->p.dim ? c->p.dim : 1;
  const int euler = !strcmp(c->method, "euler"),
            dd = !strcmp(c->method, "decomposition");
  const int drag = !isinf(c->p.tau);
  char why[128];
  if (dim == 1) {
    unused(c, 1, "run", "ny", "dim = 1 (one row of cells)");
    unused(c, 1, "run", "Ly", "dim = 1 (the domain is L or Lx, along x)");
    unused(c, 1, "boundary", "south", "dim = 1 (only west and east)");
    unused(c, 1, "boundary", "north", "dim = 1 (only west and east)");
    unused_y(c, c->n_origin, "run", "origin");
    unused_y(c, c->n_init_u, "initial", "u");
    if (drag)
      unused_y(c, c->n_U, "drag", "U");
  }
  unused(c, !drag, "drag", "U", "no drag (tau = inf, the default)");
  unused(c, !strcmp(c->method, "lagrange"), "run", "scheme",
         "method = lagrange (the scheme is the Eulerian solver's)");
  snprintf(why, sizeof why, "method = %s starts empty (inflows only)",
           c->method);
  unused(c, !euler && !(c->init_rho > 0), "initial", "rho", why);
  unused(c, !euler && !(c->init_rho > 0), "initial", "u", why);
  unused(c, euler && c->restart[0], "initial", "rho",
         "the state comes from the restart checkpoint");
  unused(c, euler && c->restart[0], "initial", "u",
         "the state comes from the restart checkpoint");
  if (euler)
    sbc_ini_section_unused(&c->once, "pgd", "particles", NULL,
                           "method = euler has no particles");
  else if (dd && c->kinds[0] && !strchr(c->kinds, 'L'))
    sbc_ini_section_unused(&c->once, "pgd", "particles", NULL,
                           "[decomposition] kinds has no L block (no "
                           "particles)");
  snprintf(why, sizeof why, "method = %s (blocks are for method = "
           "decomposition)", c->method);
  if (!dd)
    sbc_ini_section_unused(&c->once, "pgd", "decomposition", NULL, why);
}

/* ------------------------------------------------------------ helpers */

/* Whether path can be written (a file it creates is removed again). */
static int writable(const char *path)
{
  struct stat st;
  const int existed = stat(path, &st) == 0;
  FILE *f = fopen(path, "ab");
  if (!f)
    return 0;
  fclose(f);
  if (!existed)
    remove(path);
  return 1;
}

/* Remove the files a previous run may have left (ours only). */
static void clean_outputs(const char *dir)
{
  static const char *fixed[] = {"fields.csv", "fields.vtk", "exact.csv",
                                "summary.json", "series.csv"};
  char path[1100];
  for (size_t k = 0; k < sizeof fixed / sizeof fixed[0]; k++) {
    snprintf(path, sizeof path, "%s/%s", dir, fixed[k]);
    remove(path);
  }
  for (int k = 0; k < 100000; k++) {
    snprintf(path, sizeof path, "%s/fields_%05d.csv", dir, k);
    if (remove(path) != 0)
      break;
  }
}

static void rp_init(double x, double y, double *rho, double u[2], void *d)
{
  (void)y;
  double r, v;
  sb_pgd_riemann_eval(d, x, 0, &r, &v);
  *rho = r;
  u[0] = v;
  u[1] = 0;
}

static void uniform_init(double x, double y, double *rho, double u[2],
                         void *d)
{
  (void)x, (void)y;
  const config *c = d;
  *rho = c->init_rho;
  u[0] = c->init_u[0];
  u[1] = c->init_u[1];
}

/* On restart: the parameters of the file (a) against the checkpoint's
 * (b), which must be the same (those the run uses: the scheme, the
 * gas velocity and [particles] only where they have an effect).  0, or 1 with the first
 * difference in msg (as "[section] key = file's; the checkpoint's"). */
static int params_differ(const sb_pgd_params *a, const sb_pgd_params *b,
                         int scheme, int particles, char *msg, size_t len)
{
  static const char *side[4] = {"west", "east", "south", "north"};
  const int d2 = a->dim == 2;
  msg[0] = 0;
#define DIFF(cond, ...)                                                   \
  do {                                                                    \
    if (cond) {                                                           \
      snprintf(msg, len, __VA_ARGS__);                                    \
      return 1;                                                           \
    }                                                                     \
  } while (0)
#define NUM(sec, key, x, y)                                               \
  DIFF((x) != (y), "[%s] %s = %.17g here, %.17g in the checkpoint: a "    \
       "restart keeps the parameters of the run", sec, key, (double)(x),  \
       (double)(y))
  NUM("run", "dim", a->dim, b->dim);
  NUM("run", "nx", a->nx, b->nx);
  if (d2)
    NUM("run", "ny", a->ny, b->ny);
  NUM("run", d2 ? "Lx" : "L", a->L[0], b->L[0]);
  if (d2)
    NUM("run", "Ly", a->L[1], b->L[1]);
  NUM("run", "origin (x)", a->origin[0], b->origin[0]);
  if (d2)
    NUM("run", "origin (y)", a->origin[1], b->origin[1]);
  DIFF(scheme && a->scheme != b->scheme, "[run] scheme = %s here, %s in the "
       "checkpoint: a restart keeps the parameters of the run",
       sb_pgd_scheme_name(a->scheme), sb_pgd_scheme_name(b->scheme));
  NUM("run", "cfl", a->cfl, b->cfl);
  NUM("run", "dt_max", a->dt_max, b->dt_max);
  NUM("run", "rho_floor", a->rho_floor, b->rho_floor);
  NUM("drag", "tau", a->tau, b->tau);
  if (!isinf(a->tau)) {
    NUM("drag", "U (x)", a->ugas[0], b->ugas[0]);
    if (d2)
      NUM("drag", "U (y)", a->ugas[1], b->ugas[1]);
  }
  for (int s = 0; s < (d2 ? 4 : 2); s++)
    DIFF(a->bc[s] != b->bc[s], "[boundary] %s differs from the "
         "checkpoint's: a restart keeps the parameters of the run", side[s]);
  NUM("inflow", "sections (number)", a->ninflow, b->ninflow);
  for (size_t k = 0; k < a->ninflow; k++) {
    const sb_pgd_inflow *x = &a->inflow[k], *y = &b->inflow[k];
    DIFF(x->side != y->side || x->first != y->first || x->count != y->count ||
         x->rho != y->rho || x->u[0] != y->u[0] || x->u[1] != y->u[1],
         "inflow section %zu (in the order of the file) differs from the "
         "checkpoint's: a restart keeps the parameters of the run", k + 1);
  }
  if (particles) {
    NUM("particles", "inject_time", a->inject_time, b->inject_time);
    NUM("particles", "inject_face", a->inject_face, b->inject_face);
  }
  return 0;
#undef NUM
#undef DIFF
}

/* On restart with method = decomposition: [decomposition] blocks and
 * kinds against the checkpoint's (as params_differ). */
static int blocks_differ(const config *c, const sb_pgd_dd *d, char *msg,
                         size_t len)
{
  size_t px, py;
  char kinds[64];  /* as the config's: at most 63 blocks */
  sb_pgd_dd_layout(d, &px, &py, NULL);
  if (px * py >= sizeof kinds) {
    snprintf(msg, len, "[decomposition] blocks = %zu %zu here, %zu %zu in "
             "the checkpoint", c->bx, c->by, px, py);
    return 1;
  }
  sb_pgd_dd_layout(d, NULL, NULL, kinds);
  if (px != c->bx || py != c->by)
    snprintf(msg, len, "[decomposition] blocks = %zu %zu here, %zu %zu in "
             "the checkpoint: a restart keeps the parameters of the run",
             c->bx, c->by, px, py);
  else if (strcmp(kinds, c->kinds))
    snprintf(msg, len, "[decomposition] kinds = %.63s here, %.63s in the "
             "checkpoint: a restart keeps the parameters of the run",
             c->kinds, kinds);
  else
    return 0;
  return 1;
}

/* Fields of a Lagrangian or decomposed run as CSV (cell centres). */
static int write_fields(const sb_pgd_params *p, const double *rho,
                        const double *qx, const double *qy, const char *path)
{
  FILE *f = fopen(path, "w");
  if (!f)
    return -1;
  double dx = p->L[0] / (double)p->nx, dy = p->L[1] / (double)p->ny;
  fprintf(f, "x,y,rho,ux,uy\n");
  for (size_t j = 0; j < p->ny; j++)
    for (size_t i = 0; i < p->nx; i++) {
      size_t k = i + p->nx * j;
      double r = rho[k], ok = r > p->rho_floor;
      fprintf(f, "%.17g,%.17g,%.17g,%.17g,%.17g\n",
              p->origin[0] + ((double)i + 0.5) * dx,
              p->origin[1] + ((double)j + 0.5) * dy, r, ok ? qx[k] / r : 0.0,
              ok ? qy[k] / r : 0.0);
    }
  return fclose(f) ? -1 : 0;
}

static void usage(FILE *f)
{
  fprintf(f,
"Usage: smolbridge pgd CONFIG.ini\n"
"\n"
"Pressureless gas dynamics (the T = 0 moment system of a spray) on a\n"
"regular grid; dimensionless or any consistent units.\n"
"  [run]            dim (1 | 2), nx, ny, L | Lx Ly, origin, t_end,\n"
"                   scheme = upwind | muscl, cfl, dt_max,\n"
"                   method = euler | lagrange | decomposition (2-D),\n"
"                   output (directory), output_every, rho_floor,\n"
"                   checkpoint (file written at t_end), restart (file to\n"
"                   go on from)\n"
"  [riemann]        (1-D) x0, rho_l, u_l, rho_r, u_r\n"
"  [initial]        uniform initial state: rho, u = ux [uy]\n"
"  [drag]           tau (inf: none), U = gas velocity ux [uy]\n"
"  [boundary]       west | east | south | north = transmissive | outflow\n"
"                   | periodic\n"
"  [inflow NAME]    side, first, count (boundary cells), rho, u = ux uy\n"
"  [particles]      inject_time, inject_face (per inflow face and step)\n"
"  [decomposition]  blocks = px py, kinds (E/L per block from the south-\n"
"                   west, row by row)\n"
"Under mpirun/srun (a build with --with-mpi), method = decomposition\n"
"shares the blocks between the ranks (at most one rank per block) and\n"
"writes the files of the one-process run; other methods run on rank 0.\n"
"Writes OUTPUT/fields.csv (x,rho,u in 1-D; x,y,rho,ux,uy in 2-D),\n"
"fields.vtk (2-D), exact.csv (Riemann problems), summary.json, and\n"
"fields_NNNNN.csv every output_every.  Keys, units, defaults:\n"
"docs/pgd.md; examples: examples/pgd_*.ini.  Keys without effect in\n"
"the configuration are warned about on stderr.\n"
"Exit status: 0 done, 1 the run failed, 2 usage or input error.\n");
}

/* ------------------------------------------------------------ main */

/* Rank 0's message for a failed run (the others' stderr is dropped). */
static const char *why(int st)
{
  return st == SBC_PGD_OTHER_RANK ? "another rank failed (SB_MPI_VERBOSE=1 "
                                    "shows its message)"
                                  : sb_last_error();
}

/* Every rank runs this (main.c): all parse the file and agree on input
 * errors; a decomposition steps its blocks on every rank, anything else
 * runs on rank 0 alone. */
int sbc_pgd_main(int argc, char **argv)
{
  const int rank = sbc_par_rank(), nranks = sbc_par_size();
  if (argc < 2 || !strcmp(argv[1], "-h") || !strcmp(argv[1], "--help")) {
    if (rank == 0)
      usage(argc < 2 ? stderr : stdout);
    return argc < 2 ? 2 : 0;
  }
  if (argc > 2) {
    fprintf(stderr, "pgd: one CONFIG.ini expected\n");
    return 2;
  }
  const char *file = argv[1];
  static config c;
  memset(&c, 0, sizeof c);
  sb_pgd_params_default(&c.p, 1);
  c.p.dim = 0; /* set from [run] dim (default 1) */
  c.t_end = NAN;
  c.rp.tau = INFINITY;
  snprintf(c.method, sizeof c.method, "euler");
  snprintf(c.output, sizeof c.output, "pgd-out");
  c.bx = c.by = 3;
  c.p.nx = 0;
  char err[1024] = "";
  int rst = sb_ini_read(file, NULL, key_fn, section_fn, &c, err,
                        sizeof err);
  /* an [inflow NAME] header alone would add no inflow */
  const char *ksec, *kwhere;
  if (!c.err[0] && !rst &&
      sbc_ini_keyless(&c.once, "inflow", &ksec, &kwhere)) {
    snprintf(c.err_where, sizeof c.err_where, "%s", kwhere);
    fail(&c, "[%s] has no keys: an inflow needs side, count and rho", ksec);
  }
  /* L sets both edges: with Lx or Ly one of the two would be lost */
  const char *wl = sbc_ini_where(&c.once, "run", "L");
  for (int d = 0; d < 2 && wl && !c.err[0]; d++) {
    const char *w = sbc_ini_where(&c.once, "run", d ? "Ly" : "Lx");
    if (w) {
      snprintf(c.err_where, sizeof c.err_where, "%s", w);
      fail(&c, "[run] %s conflicts with L (at %s): L sets both edges; give "
           "L, or Lx and Ly", d ? "Ly" : "Lx", wl);
    }
  }
  if (!c.err[0] && !rst && rank == 0)
    warn_unused(&c);
  sbc_ini_once_free(&c.once);
  if (c.err[0] || (rst && !err[0])) {
    fprintf(stderr, "pgd: %s: %s\n", c.err_where, c.err[0] ? c.err :
            "invalid line");
    return 2;
  }
  if (rst) {  /* cannot read, or not key = value / [section] (file:line) */
    fprintf(stderr, "pgd: %s\n", err);
    return 2;
  }
  sb_pgd_params *p = &c.p;
  if (!p->dim)
    p->dim = 1;
#define INPUT_ERROR(...)                                                    \
  do {                                                                      \
    fprintf(stderr, "pgd: %s: ", file);                                     \
    fprintf(stderr, __VA_ARGS__);                                           \
    fputc('\n', stderr);                                                    \
    return 2;                                                               \
  } while (0)
  if (!p->nx)
    INPUT_ERROR("[run] nx is required");
  if (isnan(c.t_end))
    INPUT_ERROR("[run] t_end is required");
  if (p->dim == 1) {
    p->ny = 1;
    if (c.nin)
      INPUT_ERROR("[inflow]: 1-D inflows are not available from the "
                  "command line (use 2-D, or the library)");
    if (!c.have_riemann && !c.have_initial && !c.restart[0])
      INPUT_ERROR("1-D runs need [riemann] (or [initial])");
    if (strcmp(c.method, "euler"))
      INPUT_ERROR("[run] method = %s: 1-D runs are Eulerian", c.method);
    p->ugas[1] = 0;
  } else {
    if (!c.have_ny)
      p->ny = p->nx;
    if (c.have_riemann)
      INPUT_ERROR("[riemann] is 1-D (dim = 1)");
  }
  if (c.have_riemann && c.have_initial)
    INPUT_ERROR("[riemann] and [initial]: give one initial state");
  if (c.have_riemann) {
    c.rp.tau = p->tau;
    c.rp.ugas = p->ugas[0];
    if (!c.have_x0) /* default: the middle of the domain */
      c.rp.x0 = p->origin[0] + 0.5 * p->L[0];
    else if (!(c.rp.x0 > p->origin[0] && c.rp.x0 < p->origin[0] + p->L[0]))
      INPUT_ERROR("[riemann] x0 = %g: outside the domain (%g, %g)",
                  c.rp.x0, p->origin[0], p->origin[0] + p->L[0]);
  }
  /* the snapshots are fields_00000.csv ... fields_99999.csv */
  if (c.output_every > 0 && c.t_end / c.output_every > 99999.0)
    INPUT_ERROR("[run] output_every = %g: %.3g snapshots up to t_end = %g; "
                "valid: at most 99999 (output_every >= %g)", c.output_every,
                c.t_end / c.output_every, c.t_end, c.t_end / 99999.0);
  for (int k = 0; k < c.nin; k++) {
    if (c.in[k].side < 0 || c.in[k].count < 1 || isnan(c.in[k].rho))
      INPUT_ERROR("[%s]: side, count and rho are required", c.in[k].name);
    if (sb_pgd_params_add_inflow(p, (sb_pgd_side)c.in[k].side,
                                 (size_t)c.in[k].first,
                                 (size_t)c.in[k].count, c.in[k].rho,
                                 c.in[k].u[0], c.in[k].u[1]))
      INPUT_ERROR("[%s]: %s", c.in[k].name, sb_last_error());
  }
  if (sb_pgd_params_check(p))
    INPUT_ERROR("%s", sb_last_error());
  const int lag = !strcmp(c.method, "lagrange");
  const int dd = !strcmp(c.method, "decomposition");
  if ((lag || dd) && c.have_initial && c.init_rho > 0)
    INPUT_ERROR("[initial]: particle runs start empty (inflows only)");
  if (dd) {
    if (!c.kinds[0])
      INPUT_ERROR("[decomposition] kinds is required for method = "
                  "decomposition");
    if (strlen(c.kinds) != c.bx * c.by)
      INPUT_ERROR("[decomposition] kinds: %zu letters for %zu x %zu "
                  "blocks", strlen(c.kinds), c.bx, c.by);
    if ((size_t)nranks > c.bx * c.by)
      INPUT_ERROR("%d MPI ranks for %zu blocks: use at most one rank per "
                  "block", nranks, c.bx * c.by);
    if ((c.checkpoint[0] || c.restart[0]) && nranks > 1)
      INPUT_ERROR("[run] %s: checkpoints of method = decomposition are "
                  "for a run in one process (not yet over %d MPI ranks)",
                  c.checkpoint[0] ? "checkpoint" : "restart", nranks);
  }
  if (c.checkpoint[0] && c.restart[0] &&
      !strcmp(c.checkpoint, c.restart))
    INPUT_ERROR("[run] checkpoint = restart = '%s': give the checkpoint "
                "another name (the restart's would be overwritten)",
                c.restart);
#undef INPUT_ERROR
  /* ranks > 1 take part in a decomposition only */
  const int par = dd && nranks > 1;
  if (!dd && nranks > 1) {
    if (rank != 0)
      return 0;
    fprintf(stderr, "pgd: method = %s runs on rank 0 only (%d ranks); "
            "method = decomposition uses them all\n", c.method, nranks);
  }

  /* ---- build */
  sb_pgd *g = NULL;
  sb_pgd_lag *l = NULL;
  sb_pgd_dd *d = NULL;
  int st = SB_SUCCESS;
  if (c.restart[0]) {
    /* the state from the checkpoint, its parameters those of the file */
    char msg[700];
    if (dd)
      d = sb_pgd_dd_checkpoint_load(c.restart, &st);
    else if (lag)
      l = sb_pgd_lag_checkpoint_load(c.restart, &st);
    else
      g = sb_pgd_checkpoint_load(c.restart, &st);
    if (!g && !l && !d) {
      fprintf(stderr, "pgd: %s: [run] restart: %s\n", file, sb_last_error());
      return 2;
    }
    const sb_pgd_params *ck = g   ? sb_pgd_get_params(g)
                              : l ? sb_pgd_lag_get_params(l)
                                  : sb_pgd_dd_get_params(d);
    const double t0 = g   ? sb_pgd_time(g)
                      : l ? sb_pgd_lag_time(l)
                          : sb_pgd_dd_time(d);
    if (params_differ(p, ck, !lag, lag || dd, msg, sizeof msg) ||
        (d && blocks_differ(&c, d, msg, sizeof msg)) || !(c.t_end >= t0)) {
      if (msg[0])
        fprintf(stderr, "pgd: %s: [run] restart = %s: %s\n", file,
                c.restart, msg);
      else
        fprintf(stderr, "pgd: %s: [run] t_end = %g: before the time of the "
                "restart checkpoint %s, t = %.17g\n", file, c.t_end,
                c.restart, t0);
      sb_pgd_free(g);
      sb_pgd_lag_free(l);
      sb_pgd_dd_free(d);
      return 2;
    }
  } else if (dd)
    d = sbc_pgd_dd_alloc(p, c.bx, c.by, c.kinds);
  else if (lag)
    l = sb_pgd_lag_alloc(p);
  else
    g = sb_pgd_alloc(p);
  if (!g && !l && !d) {
    fprintf(stderr, "pgd: %s: %s\n", file, sb_last_error());
    return 2;
  }
  if (c.restart[0])
    ;  /* the state is the checkpoint's */
  else if (g && c.have_riemann)
    st = sb_pgd_init(g, rp_init, &c.rp);
  else if (g && c.have_initial)
    st = sb_pgd_init(g, uniform_init, &c);
  if (st) {
    fprintf(stderr, "pgd: initial state: %s\n", sb_last_error());
    sb_pgd_free(g);
    sb_pgd_lag_free(l);
    return 2;
  }
  int bad_dir = rank == 0 && sb_mkdir_p(c.output);
  if (bad_dir)
    fprintf(stderr, "pgd: cannot create directory '%s': %s\n", c.output,
            strerror(errno));
  if (par ? sbc_par_max_int(bad_dir) : bad_dir) {
    sb_pgd_free(g);
    sb_pgd_lag_free(l);
    sb_pgd_dd_free(d);
    return 1;
  }
  /* the checkpoint path, before the run (as collide), and before the
   * previous run's files go: an input error leaves them */
  if (rank == 0 && c.checkpoint[0] && !writable(c.checkpoint)) {
    fprintf(stderr, "pgd: %s: [run] checkpoint = %s: not writable: %s\n",
            file, c.checkpoint, strerror(errno));
    sb_pgd_free(g);
    sb_pgd_lag_free(l);
    sb_pgd_dd_free(d);
    return 2;
  }
  if (rank == 0)
    clean_outputs(c.output);
  fprintf(stderr, "pgd: %d-D, %zu x %zu cells, %s, %s, t_end = %g -> %s/",
          p->dim, p->nx, p->ny, c.method, sb_pgd_scheme_name(p->scheme),
          c.t_end, c.output);
  if (par)
    fprintf(stderr, " (%d ranks)", nranks);
  fputc('\n', stderr);

  /* ---- run */
  const size_t nn = p->nx * p->ny;
  double *f = malloc(3 * nn * sizeof *f);
  int nomem = f == NULL;
  if (par) /* a rank leaving the loop alone would leave the others waiting */
    nomem = sbc_par_max_int(nomem);
  char path[1100];
  clock_t c0 = clock();
  double t = 0, next = c.output_every > 0 ? c.output_every : INFINITY;
  size_t nsteps = 0;
  int snap = 0;
  if (c.restart[0]) {
    /* from the checkpoint's time on, with the snapshot times and numbers
     * of the run in one go (next summed as it sums it); a snapshot at
     * the checkpoint's time is the restart's (the loop's first pass
     * takes no step and writes it), since the run that wrote the
     * checkpoint ended there and wrote fields.csv instead */
    t = g ? sb_pgd_time(g) : l ? sb_pgd_lag_time(l) : sb_pgd_dd_time(d);
    while (next < t) {
      next += c.output_every;
      snap++;
    }
    nsteps = g ? sb_pgd_steps(g) : l ? sb_pgd_lag_steps(l)
                                     : sb_pgd_dd_steps(d);
  }
  while (!st && !nomem && t < c.t_end) {
    double stop = fmin(c.t_end, next);
    size_t k = 0;
    st = g ? sb_pgd_advance(g, stop, &k)
           : l ? sb_pgd_lag_advance(l, stop, &k)
               : sbc_pgd_dd_advance(d, stop, &k);
    nsteps += k;
    t = stop;
    if (!st && t == next && t < c.t_end) {
      snprintf(path, sizeof path, "%s/fields_%05d.csv", c.output, snap++);
      if (g)
        st = sb_pgd_write_csv(g, path);
      else if (l || !(st = sbc_pgd_dd_gather(d))) {
        if (l)
          sb_pgd_lag_deposit(l, f, f + nn, f + 2 * nn);
        else
          sb_pgd_dd_fields(d, f, f + nn, f + 2 * nn);
        if (rank == 0)
          st = write_fields(p, f, f + nn, f + 2 * nn, path) ? SB_EIO : 0;
      }
      if (par && sbc_par_max_int(st != 0) && !st)
        st = SBC_PGD_OTHER_RANK; /* rank 0 could not write */
      next += c.output_every;
      fprintf(stderr, "pgd: t = %g (%.0f%%)\n", t, 100 * t / c.t_end);
    }
  }
  double secs = (double)(clock() - c0) / CLOCKS_PER_SEC;
  if (nomem)
    st = SB_ENOMEM;
  if (!st && d)
    st = sbc_pgd_dd_gather(d);
  if (st) {
    fprintf(stderr, "pgd: run failed at t = %g: %s\n", t, why(st));
    goto done;
  }
  if (c.checkpoint[0] && rank == 0) {
    st = g   ? sb_pgd_checkpoint_save(g, c.checkpoint)
         : l ? sb_pgd_lag_checkpoint_save(l, c.checkpoint)
             : sb_pgd_dd_checkpoint_save(d, c.checkpoint);
    if (st) {
      fprintf(stderr, "pgd: [run] checkpoint: %s\n", sb_last_error());
      goto done;
    }
  }
  if (rank != 0) /* rank 0 has every block now, and writes */
    goto done;

  /* ---- outputs */
  snprintf(path, sizeof path, "%s/fields.csv", c.output);
  if (g) {
    st = sb_pgd_write_csv(g, path);
    if (!st && p->dim == 2) {
      snprintf(path, sizeof path, "%s/fields.vtk", c.output);
      st = sb_pgd_write_vtk(g, path);
    }
  } else {
    if (l)
      sb_pgd_lag_deposit(l, f, f + nn, f + 2 * nn);
    else
      sb_pgd_dd_fields(d, f, f + nn, f + 2 * nn);
    st = write_fields(p, f, f + nn, f + 2 * nn, path) ? SB_EIO : 0;
  }
  double tot[3], in[3], out[3];
  if (g) {
    sb_pgd_totals(g, tot);
    sb_pgd_boundary_totals(g, in, out);
  } else if (l) {
    sb_pgd_lag_totals(l, tot);
    sb_pgd_lag_boundary_totals(l, in, out);
  } else {
    sb_pgd_dd_totals(d, tot);
    sb_pgd_dd_boundary_totals(d, in, out);
  }
  sb_pgd_riemann_sol w;
  double l1 = NAN, w1 = NAN;
  if (!st && g && c.have_riemann) {
    snprintf(path, sizeof path, "%s/exact.csv", c.output);
    FILE *e = fopen(path, "w");
    if (!e) {
      st = SB_EIO;
    } else {
      double h = p->L[0] / (double)p->nx;
      fprintf(e, "x,rho,u\n");
      for (size_t i = 0; i < p->nx; i++) {
        /* the faces as sb_pgd_riemann_error computes them, so that
         * neighbours share them exactly and a delta on a face is counted
         * once ([a, b)); x +- h/2 rounded apart and dropped it */
        double a = p->origin[0] + (double)i * h,
               b = p->origin[0] + (double)(i + 1) * h;
        double x = p->origin[0] + ((double)i + 0.5) * h, m, q;
        sb_pgd_riemann_integral(&c.rp, c.t_end, a, b, &m, &q);
        fprintf(e, "%.17g,%.17g,%.17g\n", x, m / h, m > 0 ? q / m : 0.0);
      }
      st = fclose(e) ? SB_EIO : 0;
      sb_pgd_fields(g, f, NULL, NULL);
      sb_pgd_riemann_error(&c.rp, c.t_end, p->origin[0], h, p->nx, f, &l1,
                           &w1);
    }
    sb_pgd_riemann_solve(&c.rp, c.t_end, &w);
  }
  if (st) {
    fprintf(stderr, "pgd: cannot write the outputs in '%s'\n", c.output);
    goto done;
  }
  snprintf(path, sizeof path, "%s/summary.json", c.output);
  FILE *js = fopen(path, "w");
  if (!js) {
    fprintf(stderr, "pgd: cannot write %s\n", path);
    st = SB_EIO;
    goto done;
  }
  fprintf(js, "{\n  \"program\": \"smolbridge pgd\",\n  \"version\": "
          "\"%s\",\n  \"dim\": %d,\n  \"nx\": %zu,\n  \"ny\": %zu,\n"
          "  \"method\": \"%s\",\n  \"scheme\": \"%s\",\n  \"t\": %.17g,\n"
          "  \"steps\": %zu,\n  \"cpu_seconds\": %.3f,\n", sb_version(),
          p->dim, p->nx, p->ny, c.method, sb_pgd_scheme_name(p->scheme),
          c.t_end, nsteps, secs);
  fprintf(js, "  ");
  sbc_ini_json_warnings(js, &c.once);
  fprintf(js, ",\n");
  fprintf(js, "  \"mass\": %.17g,\n  \"momentum\": [%.17g, %.17g],\n"
          "  \"inflow\": [%.17g, %.17g, %.17g],\n"
          "  \"outflow\": [%.17g, %.17g, %.17g]", tot[0], tot[1], tot[2],
          in[0], in[1], in[2], out[0], out[1], out[2]);
  if (l || d)
    fprintf(js, ",\n  \"particles\": %zu",
            l ? sb_pgd_lag_count(l) : sb_pgd_dd_particles(d));
  if (g && c.have_riemann) {
    static const char *wn[] = {"contact", "vacuum", "delta", "none"};
    fprintf(js, ",\n  \"exact\": {\"wave\": \"%s\", \"x_left\": %.17g, "
            "\"x_right\": %.17g, \"delta_mass\": %.17g, \"l1\": %.17g, "
            "\"w1\": %.17g}", wn[w.type], w.xl, w.xr, w.mass, l1, w1);
  }
  fprintf(js, "\n}\n");
  if (fclose(js)) {
    st = SB_EIO;
    fprintf(stderr, "pgd: cannot write %s\n", path);
    goto done;
  }
  fprintf(stderr, "pgd: done, %zu steps, %.2f s; mass %.10g (in %.10g, out "
          "%.10g)\n", nsteps, secs, tot[0], in[0], out[0]);
done:
  free(f);
  sb_pgd_free(g);
  sb_pgd_lag_free(l);
  sb_pgd_dd_free(d);
  return st ? 1 : 0;
}
