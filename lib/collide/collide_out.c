/* collide_out.c — the output directory of a `smolbridge collide` run:
 * prepared before the run (created, its previous run's files removed,
 * writability of it and of the checkpoint path checked, so nothing is
 * lost after the compute), then series.csv, summary.json, sizes.csv,
 * hits.csv and manifest.txt (the files of this run). */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <dirent.h>
#include <unistd.h>

#include <smolbridge/bridge.h>
#include <smolbridge/engine.h>
#include <smolbridge/engine_bridge.h>
#include <smolbridge/kernel.h>
#include <smolbridge/langevin.h>
#include <smolbridge/stats.h>

#include "collide_internal.h"

#define PI 3.14159265358979323846

/* 1 if path can be written (created and removed again if it did not
 * exist), 0 with errno set otherwise. */
static int writable(const char *path)
{
  struct stat st;
  const int existed = stat(path, &st) == 0;
  FILE *g = fopen(path, "ab");
  if (!g)
    return 0;
  fclose(g);
  if (!existed)
    remove(path);
  return 1;
}

/* Files a run writes (also those of earlier versions without a
 * manifest). */
static int ours(const char *name)
{
  static const char *const fixed[] = {"series.csv", "summary.json",
                                      "sizes.csv", "hits.csv", "grid.csv",
                                      "exits.csv", "msd.csv", "contacts.csv",
                                      "batches.csv",
                                      "manifest.txt", NULL};
  for (int i = 0; fixed[i]; i++)
    if (!strcmp(name, fixed[i]))
      return 1;
  size_t n = strlen(name);
  return !strncmp(name, "snap_", 5) && n > 9 &&
         !strcmp(name + n - 4, ".csv");
}

int sbi_col_out_prepare(sbi_col_config *c)
{
  const char *where = sbi_col_given(c, "run", "output")
                          ? sbi_col_where(c, "run", "output")
                          : "[run] output (default)";
  if (sb_mkdir_p(c->output))
    return sbi_col_fail(c, "%s: [run] output = %s: cannot create the "
                        "directory: %s", where, c->output, strerror(errno));
  /* the checkpoint and the states beside it, before the previous run's
   * files go: an input error must leave them */
  if (c->checkpoint[0]) {
    char fh[600];
    for (int k = -1; k < SBI_BESIDE_N; k++) {
      if (k >= 0 && sbi_col_beside(c, k, c->checkpoint, fh, sizeof fh))
        continue;  /* the run has no such state */
      const char *p = k >= 0 ? fh : c->checkpoint;
      if (!writable(p))
        return sbi_col_fail(c, "%s: [run] checkpoint = %s: %s%snot "
                            "writable: %s",
                            sbi_col_where(c, "run", "checkpoint"),
                            c->checkpoint, k >= 0 ? p : "",
                            k >= 0 ? " " : "",
                            strerror(errno));
    }
  }
  DIR *d = opendir(c->output);
  if (!d)
    return sbi_col_fail(c, "%s: [run] output = %s: %s", where, c->output,
                        strerror(errno));
  struct dirent *de;
  char path[1100];
  while ((de = readdir(d)))
    if (ours(de->d_name)) {
      snprintf(path, sizeof path, "%s/%s", c->output, de->d_name);
      if (remove(path) && errno != ENOENT) {
        int e = errno;
        closedir(d);
        return sbi_col_fail(c, "%s: [run] output = %s: cannot remove the "
                            "previous run's %s: %s", where, c->output,
                            de->d_name, strerror(e));
      }
    }
  closedir(d);
  snprintf(path, sizeof path, "%s/manifest.txt", c->output);
  FILE *f = fopen(path, "w");
  if (!f || fputs("# smolbridge collide: run in progress\n", f) < 0 ||
      fclose(f))
    return sbi_col_fail(c, "%s: [run] output = %s: not writable: %s", where,
                        c->output, strerror(errno));
  return 0;
}

void sbi_col_snap_path(const sbi_col_config *c, long k, char *buf, size_t len)
{
  snprintf(buf, len, "%s/snap_%06ld.csv", c->output, k);
}

/* ------------------------------------------------------------ pairs */

static int npairs_of(int nsp) { return nsp * (nsp + 1) / 2; }

int sbi_col_pairs_sample(sbi_col_pairs *ps, const sb_engine *e)
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

static int write_series(const char *path, const sbi_col_run *run,
                        const sbi_col_config *c, const sbi_col_pairs *ps)
{
  const sb_engine *e = run->e;
  FILE *f = fopen(path, "w");
  if (!f)
    return -1;
  size_t n;
  const sb_engine_sample *s = sb_engine_series(e, &n);
  int np = ps->nsp > 1 ? npairs_of(ps->nsp) : 0;
  fprintf(f, "t,ncoll,K,K_lo,K_hi,ekin,px,py,pz");
  for (int a = 0; a < ps->nsp && np; a++)
    for (int b = a; b < ps->nsp; b++) {
      const char *x = sbi_col_short_name(c, (size_t)a);
      const char *y = sbi_col_short_name(c, (size_t)b);
      fprintf(f, ",K_%s_%s,K_%s_%s_lo,K_%s_%s_hi", x, y, x, y, x, y);
    }
  sbi_col_walls_header(f, c);
  fprintf(f, "\n");
  size_t w = 1 + 3 * (size_t)np, next = 0;
  for (size_t k = 0; k < n; k++) {
    fprintf(f, "%.17g,%llu,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g",
            s[k].t, (unsigned long long)s[k].ncoll, s[k].K, s[k].K_lo,
            s[k].K_hi, s[k].ekin, s[k].p[0], s[k].p[1], s[k].p[2]);
    const double *r = NULL;  /* the pair row sampled at the same time */
    for (size_t q = 0; np && q < ps->nrows; q++)
      if (ps->rows[q * w] == s[k].t)
        r = ps->rows + q * w;
    for (int q = 0; q < 3 * np; q++)
      fprintf(f, ",%.17g", r ? r[1 + q] : NAN);
    sbi_col_walls_row(f, c, run, s[k].t, &next);
    fprintf(f, "\n");
  }
  return fclose(f) ? -1 : 0;
}

/* ------------------------------------------------------------ JSON */

static void jstr(FILE *f, const char *s)
{
  fputc('"', f);
  for (; *s; s++) {
    unsigned char ch = (unsigned char)*s;
    if (ch == '"' || ch == '\\')
      fprintf(f, "\\%c", ch);
    else if (ch < 0x20)
      fprintf(f, "\\u%04x", ch);
    else
      fputc(ch, f);
  }
  fputc('"', f);
}

/* The name of species k in summary.json: a merging run's cluster species
 * are cluster_K, K its number of primaries (they all used to be
 * "cluster", so pair_kernels listed several pairs under one name). */
static void jspecies(FILE *f, const sbi_col_config *c, const sb_agglo *ag,
                     size_t k)
{
  char buf[32];
  jstr(f, sbi_col_species_label(c, ag, k, buf, sizeof buf));
}

void sbi_col_jnum(FILE *f, double x)
{
  if (isfinite(x))
    fprintf(f, "%.17g", x);
  else
    fprintf(f, "null");
}

/* The theoretical kernels that apply to species pair (a, b) with the
 * fluid at rest: free flight at a common T: kinetic theory (2-D: of hard
 * discs, m^2/s); Langevin species in 3-D: the continuum kernel
 * 4 pi (D_a + D_b)(r_a + r_b), D = (B tau)^2/2, and at a common T > 0 the
 * free-molecular kernel and the transition kernel of Gopalakrishnan &
 * Hogan (2011) with its Kn_D.  Diffusion in 2-D has no steady kernel (the
 * rate decays as 1/ln t), so Langevin pairs in 2-D have none. */
static void json_references(FILE *f, const sbi_col_config *c,
                            const sb_engine_species *sa,
                            const sb_engine_species *sb)
{
  fprintf(f, "\"references\": {");
  int rest = !strcmp(c->fluid, "rest");
  int same_T = sa->T > 0 && sa->T == sb->T;
  if (rest && isinf(sa->tau) && isinf(sb->tau) && same_T) {
    fprintf(f, "\"kinetic\": ");
    sbi_col_jnum(f, (c->dim == 2 ? sb_kernel_kinetic_2d : sb_kernel_kinetic)(
                        2 * sa->radius, 2 * sb->radius, sa->mass, sb->mass,
                        sa->T));
  } else if (rest && c->dim == 3 && isfinite(sa->tau) && isfinite(sb->tau)) {
    double ba = sa->B * sa->tau, bb = sb->B * sb->tau;
    fprintf(f, "\"continuum\": ");
    sbi_col_jnum(f,
                 sb_kernel_diffusion(sa->radius, sb->radius, ba * ba, bb * bb));
    if (same_T) {
      double R = sa->radius + sb->radius;
      double mr = sa->mass * sb->mass / (sa->mass + sb->mass);
      fprintf(f, ", \"free_molecular\": ");
      sbi_col_jnum(f, PI * R * R * sqrt(8 * SB_BOLTZMANN * sa->T / (PI * mr)));
      fprintf(f, ", \"transition_gh\": ");
      sbi_col_jnum(f, sb_kernel_brownian_gh(sa->radius, sb->radius, sa->mass,
                                            sb->mass, sa->tau, sb->tau, sa->T));
      fprintf(f, ", \"Kn_D\": ");
      sbi_col_jnum(f,
                   sb_kernel_brownian_gh_kn(sa->radius, sb->radius, sa->mass,
                                            sb->mass, sa->tau, sb->tau, sa->T));
    }
  }
  fprintf(f, "}");
}

/* Why there is no kernel estimate. */
static const char *why_no_kernel(const sb_engine *e, const sb_engine_stats *s)
{
  if (sb_engine_count(e) < 2 && !(s->exposure > 0))
    return "fewer than 2 particles: no pairs";
  if (!(s->t > s->t_reset))
    return "no measured time after the warm-up";
  return "no pair exposure in the measured interval";
}

static double uniform_cdf(double u, void *p)
{
  (void)p;
  return u < 0 ? 0 : (u > 1 ? 1 : u);
}

/* hits.csv and the KS test of the hit times through their CDF (PIT). */
static int write_hits(FILE *js, const sbi_col_config *c, const sbi_col_run *r,
                      const char *path)
{
  size_t nh;
  const sb_engine_bridge_hit *h = sb_engine_bridge_hits(r->bridge, &nh);
  FILE *f = fopen(path, "w");
  if (!f)
    return -1;
  double *u = malloc((nh ? nh : 1) * sizeof *u);
  fprintf(f, "x,y,a,sigma2,dt,ta,F\n");
  for (size_t i = 0; i < nh; i++) {
    double F = sb_bes3b_hit_cdf(h[i].ta, h[i].x, h[i].y, h[i].a,
                                h[i].sigma2, h[i].dt);
    if (u)
      u[i] = F;
    fprintf(f, "%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", h[i].x,
            h[i].y, h[i].a, h[i].sigma2, h[i].dt, h[i].ta, F);
  }
  double D = NAN, p = NAN;
  if (u && nh > 0)
    sb_ks_test(u, nh, uniform_cdf, NULL, &D, &p);
  free(u);
  fprintf(js, "  \"hit_times\": {\"recorded\": %zu, \"cap\": %ld, "
          "\"file\": \"hits.csv\", \"ks_D\": ", nh, c->hit_times);
  sbi_col_jnum(js, D);
  fprintf(js, ", \"ks_p\": ");
  sbi_col_jnum(js, p);
  fprintf(js, "},\n");
  return fclose(f) ? -1 : 0;
}

static void json_run(FILE *f, const sbi_col_config *c, const sb_engine *e,
                     const sb_agglo *ag)
{
  const sb_engine_params *p = sb_engine_get_params(e);
  fprintf(f, "  \"seed\": %lu,\n", c->restart[0] ? p->seed : c->seed);
  fprintf(f, "  \"dim\": %d,\n  \"L\": [%.17g, %.17g, %.17g],\n", p->dim,
          p->L[0], p->L[1], p->dim == 3 ? p->L[2] : 0.0);
  fprintf(f, "  \"dt\": %.17g,\n  \"neigh\": \"%s\",\n  \"detect\": "
          "\"%s\",\n  \"outcome\": \"%s\",\n  \"eta\": %.17g,\n",
          p->dt, c->neigh, c->detect,
          sbi_col_detect_none(c) ? "none" : c->outcome, p->eta);
  fprintf(f, "  \"fluid\": \"%s\",\n", c->fluid);
  fprintf(f, "  \"rng\": \"%s\",\n",
          p->rng_type ? p->rng_type->name : gsl_rng_mt19937->name);
  /* the placement only where it placed particles: else the explicit
   * particles, or none at the start (inflows only) */
  int placed = 0, expl = 0;
  for (int k = 0; k < c->nsp; k++) {
    placed |= c->sp[k].count > 0 || !isnan(c->sp[k].phi);
    expl |= c->sp[k].npart > 0;
  }
  fprintf(f, "  \"placement\": \"%s\",\n",
          c->restart[0] ? "restart"
          : placed      ? c->placement
          : expl        ? "explicit"
                        : "none");
  fprintf(f, "  \"restart\": ");
  jstr(f, c->restart);
  fprintf(f, ",\n  \"overrides\": [");
  for (int i = 0; i < c->noverrides; i++) {
    fprintf(f, "%s", i ? ", " : "");
    jstr(f, c->overrides[i]);
  }
  fprintf(f, "],\n  \"warnings\": [");
  for (int i = 0; i < c->nwarn; i++) {
    fprintf(f, "%s", i ? ", " : "");
    jstr(f, c->warn[i]);
  }
  fprintf(f, "],\n  \"species\": [\n");
  const sb_engine_species *s;
  for (size_t k = 0; (s = sb_engine_get_species(e, k)); k++) {
    fprintf(f, "    {\"name\": ");
    jspecies(f, c, ag, k);
    fprintf(f, ", \"radius\": %.17g, \"mass\": %.17g, \"tau\": ", s->radius,
            s->mass);
    if (isinf(s->tau))
      fprintf(f, "\"inf\"");
    else
      fprintf(f, "%.17g", s->tau);
    fprintf(f, ", \"B\": %.17g, \"T\": %.17g}%s\n", s->B, s->T,
            sb_engine_get_species(e, k + 1) ? "," : "");
  }
  fprintf(f, "  ],\n");
}

static void json_kernels(FILE *f, const sbi_col_config *c, const sb_engine *e,
                         const sb_agglo *ag)
{
  sb_engine_stats st;
  sb_engine_get_stats(e, &st);
  double K = NAN, lo = NAN, hi = NAN;
  int kst = sb_engine_kernel(e, 0.95, &K, &lo, &hi);
  fprintf(f, "  \"particles\": %zu,\n", sb_engine_count(e));
  fprintf(f, "  \"time\": %.17g,\n  \"steps\": %llu,\n", st.t,
          (unsigned long long)st.steps);
  fprintf(f, "  \"t_measure_start\": %.17g,\n  \"t_measure_end\": %.17g,\n",
          st.t_reset, st.t);
  fprintf(f, "  \"pair_exposure\": ");
  sbi_col_jnum(f, st.exposure);
  fprintf(f, ",\n");
  /* walls: depositions per face x_lo, x_hi, y_lo, y_hi, z_lo, z_hi */
  fprintf(f, "  \"deposits\": [");
  for (int q = 0; q < 6; q++)
    fprintf(f, "%s%llu", q ? ", " : "",
            (unsigned long long)sb_engine_deposits(e, q));
  /* open boundaries: outflows per face (same order), and per inflow
   * (in species order) the particles injected and the draws skipped */
  fprintf(f, "],\n  \"outflows\": [");
  for (int q = 0; q < 6; q++)
    fprintf(f, "%s%llu", q ? ", " : "",
            (unsigned long long)sb_engine_outflows(e, q));
  fprintf(f, "],\n  \"inflows\": [");
  for (size_t q = 0; q < sb_engine_ninflows(e); q++)
    fprintf(f, "%s{\"injected\": %llu, \"skipped\": %llu}", q ? ", " : "",
            (unsigned long long)sb_engine_inflow_injected(e, q),
            (unsigned long long)sb_engine_inflow_skipped(e, q));
  fprintf(f, "],\n  \"lees_edwards_offset\": %.17g,\n",
          sb_engine_lees_edwards_offset(e));
  fprintf(f, "  \"collisions\": %llu,\n  \"candidates\": %llu,\n  "
          "\"dropped\": %llu,\n  \"redetected\": %llu,\n",
          (unsigned long long)st.ncoll, (unsigned long long)st.ncand,
          (unsigned long long)st.dropped,
          (unsigned long long)st.redetected);
  const int none = sbi_col_detect_none(c);  /* nothing is detected */
  if (kst || !isfinite(K) || none) {
    fprintf(f, "  \"kernel\": {\"K\": null, \"ci95\": null, \"why\": ");
    jstr(f, none ? "detect = none: contacts between particles are not "
                   "detected"
                 : why_no_kernel(e, &st));
    fprintf(f, "},\n");
  } else {
    fprintf(f, "  \"kernel\": {\"K\": %.17g, \"ci95\": [", K);
    sbi_col_jnum(f, lo);
    fprintf(f, ", ");
    sbi_col_jnum(f, hi);
    fprintf(f, "]},\n");
  }
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
      fprintf(f, "%s\n    {\"species\": [", firstp ? "" : ",");
      jspecies(f, c, ag, a);
      fprintf(f, ", ");
      jspecies(f, c, ag, b);
      fprintf(f, "], \"collisions\": %llu, \"exposure\": ",
              (unsigned long long)ps.ncoll);
      sbi_col_jnum(f, ps.exposure);
      fprintf(f, ", \"K\": ");
      sbi_col_jnum(f, ps.K);
      fprintf(f, ", \"ci95\": [");
      sbi_col_jnum(f, ps.lo);
      fprintf(f, ", ");
      sbi_col_jnum(f, ps.hi);
      fprintf(f, "], \"ncoll_var\": ");
      sbi_col_jnum(f, ps.ncoll_var);
      fprintf(f, ", \"dispersion\": ");
      sbi_col_jnum(f, ps.dispersion);
      fprintf(f, ", ");
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
  fprintf(f, "],\n");
}

/* `"dispersion": .., "expected_per_K": .., "K": .., "ci95": [lo, hi]` of a
 * first-contact result */
static void jfirsthit_kernel(FILE *f, const sb_engine_firsthit_kernel_result *o)
{
  fprintf(f, "\"dispersion\": ");
  sbi_col_jnum(f, o->dispersion);
  fprintf(f, ", \"expected_per_K\": ");
  sbi_col_jnum(f, o->expected_per_K);
  fprintf(f, ", \"K\": ");
  sbi_col_jnum(f, o->K);
  fprintf(f, ", \"ci95\": [");
  sbi_col_jnum(f, o->lo);
  fprintf(f, ", ");
  sbi_col_jnum(f, o->hi);
  fprintf(f, "]");
}

/* [observe] first_hit: the kernel of the one species pair (or, for a
 * mixture, the counts over all pairs and a null kernel), then one entry
 * per species pair (a <= b) with its own count, reference and kernel. */
static void json_firsthit(FILE *f, const sbi_col_config *c,
                          const sbi_col_run *r)
{
  sb_engine_firsthit_kernel_result o;
  sbi_col_firsthit_result(r, c, &o);
  fprintf(f, "  \"first_hit\": {\"hits\": %llu, \"warmup_hits\": %llu, "
          "\"pairs_apart\": %.17g, \"radius\": ",
          (unsigned long long)o.c.hits, (unsigned long long)o.c.warm,
          o.c.pairs_apart);
  sbi_col_jnum(f, o.a);
  fprintf(f, ", \"capacitance\": %s, \"D\": ",
          c->first_hit_capacitance > 0 ? "true" : "false");
  sbi_col_jnum(f, o.D);
  fprintf(f, ", \"t1\": %.17g, \"t\": %.17g, ", o.t1, o.t);
  jfirsthit_kernel(f, &o);
  fprintf(f, ", \"pairs\": [");
  for (int a = 0; a < c->nsp; a++)
    for (int b = a; b < c->nsp; b++) {
      sbi_col_firsthit_pair(r, c, (size_t)a, (size_t)b, &o);
      fprintf(f, "%s\n    {\"species\": [", a + b ? "," : "");
      jspecies(f, c, r->agglo, (size_t)a);
      fprintf(f, ", ");
      jspecies(f, c, r->agglo, (size_t)b);
      fprintf(f, "], \"hits\": %llu, \"warmup_hits\": %llu, "
              "\"contact_at_start\": %llu, \"pairs_apart\": %.17g, "
              "\"radius\": ", (unsigned long long)o.c.hits,
              (unsigned long long)o.c.warm, (unsigned long long)o.c.contact0,
              o.c.pairs_apart);
      sbi_col_jnum(f, o.a);
      fprintf(f, ", \"D\": ");
      sbi_col_jnum(f, o.D);
      fprintf(f, ", ");
      jfirsthit_kernel(f, &o);
      fprintf(f, "}");
    }
  fprintf(f, "\n  ]},\n");
}

static void json_contexts(FILE *f, const sbi_col_config *c,
                          const sbi_col_run *r)
{
  if (r->bridge) {
    sb_engine_bridge_stats bs;
    sb_engine_bridge_get_stats(r->bridge, &bs);
    fprintf(f, "  \"bridge\": {\"reach\": ");
    sbi_col_jnum(f, sb_engine_bridge_reach(r->e, r->bridge));
    fprintf(f, ", \"detections\": %llu, \"collisions\": %llu, "
            "\"overlapping_at_start\": %llu, \"brownian_share\": ",
            (unsigned long long)bs.ndetect, (unsigned long long)bs.ncoll,
            (unsigned long long)bs.noverlap);
    sbi_col_jnum(f, bs.ncoll ? bs.coll_brown / (double)bs.ncoll : NAN);
    fprintf(f, ", \"turbulent_share\": ");
    sbi_col_jnum(f, bs.ncoll ? bs.coll_turb / (double)bs.ncoll : NAN);
    fprintf(f, "},\n");
  }
  if (r->agglo) {
    sb_agglo_stats as;
    sb_agglo_get_stats(r->agglo, &as);
    sb_engine_stats st;
    sb_engine_get_stats(r->e, &st);
    const sb_engine_params *p = sb_engine_get_params(r->e);
    double V = p->L[0] * p->L[1] * (p->dim == 3 ? p->L[2] : 1.0);
    double m[3] = {NAN, NAN, NAN};
    sb_agglo_moments(r->agglo, r->e, m);
    unsigned long long nd = as.nmerge + as.nrebound;
    fprintf(f, "  \"agglo\": {\"merges\": %llu, \"rebounds\": %llu, "
            "\"sticking_fraction\": ", (unsigned long long)as.nmerge,
            (unsigned long long)as.nrebound);
    sbi_col_jnum(f, nd ? (double)as.nmerge / (double)nd : NAN);
    fprintf(f, ", \"merge_kernel\": ");
    sbi_col_jnum(f,
                 st.exposure > 0 ? (double)as.nmerge * V / st.exposure : NAN);
    fprintf(f, ", \"mean_Erel_J\": ");
    sbi_col_jnum(f, nd ? as.erel_sum / (double)nd : NAN);
    for (int q = 0; q < 3; q++) {
      fprintf(f, ", \"M%d\": ", q);
      sbi_col_jnum(f, m[q]);
    }
    fprintf(f, ", \"file\": \"sizes.csv\"},\n");
  }
  if (r->fh)
    json_firsthit(f, c, r);
}

int sbi_col_out_write(const sbi_col_config *c, sbi_col_run *r,
                      const sbi_col_pairs *ps, const double secs[2],
                      const char *status,
                      const char *why, long nsnap)
{
  char path[1100], files[16][32];
  int nf = 0, err = 0;
  if (r->e) {
    snprintf(path, sizeof path, "%s/series.csv", c->output);
    err |= write_series(path, r, c, ps);
    snprintf(files[nf++], 32, "series.csv");
  }
  if (r->e && c->exits > 0) {  /* written as the run went */
    err |= sbi_col_exits_close(c, r);
    snprintf(files[nf++], 32, "exits.csv");
  }
  if (r->e && sbi_col_grid_on(c)) {
    err |= sbi_col_grid_close(c, r);
    snprintf(files[nf++], 32, "grid.csv");
  }
  if (r->agglo) {
    snprintf(path, sizeof path, "%s/sizes.csv", c->output);
    err |= sb_agglo_series_csv(r->agglo, path) != 0;
    snprintf(files[nf++], 32, "sizes.csv");
  }
  snprintf(path, sizeof path, "%s/summary.json", c->output);
  FILE *f = fopen(path, "w");
  if (!f)
    return -1;
  snprintf(files[nf++], 32, "summary.json");
  fprintf(f, "{\n  \"program\": \"smolbridge collide\",\n");
  fprintf(f, "  \"version\": \"%s\",\n  \"status\": \"%s\",\n",
          sb_version(), status);
  if (why) {
    fprintf(f, "  \"error\": ");
    jstr(f, why);
    fprintf(f, ",\n");
  }
  if (r->e) {
    json_run(f, c, r->e, r->agglo);
    json_kernels(f, c, r->e, r->agglo);
    json_contexts(f, c, r);
    if (sbi_col_grid_on(c))
      sbi_col_grid_json(f, c, r);
    if (r->measuring) {  /* energy conservation over the measurement */
      double e1 = sb_engine_kinetic_energy(r->e, NULL);
      /* null where not finite (an overflowing energy): JSON has no inf */
      fprintf(f, "  \"kinetic_energy\": {\"start\": ");
      sbi_col_jnum(f, r->ekin0);
      fprintf(f, ", \"end\": ");
      sbi_col_jnum(f, e1);
      fprintf(f, ", \"rel_change\": ");
      sbi_col_jnum(f, fabs(e1 / r->ekin0 - 1.0));
      fprintf(f, "},\n");
    }
    if (r->contacts) {
      snprintf(path, sizeof path, "%s/contacts.csv", c->output);
      err |= sbi_col_contacts_write(f, c, r, path);
      snprintf(files[nf++], 32, "contacts.csv");
    }
    if (r->batches) {
      snprintf(path, sizeof path, "%s/batches.csv", c->output);
      err |= sbi_col_batches_write(f, c, r, path);
      snprintf(files[nf++], 32, "batches.csv");
    }
    if (r->msd) {
      snprintf(path, sizeof path, "%s/msd.csv", c->output);
      err |= sbi_col_msd_write(f, c, r, path);
      snprintf(files[nf++], 32, "msd.csv");
    }
    if (r->bridge && c->hit_times > 0) {
      snprintf(path, sizeof path, "%s/hits.csv", c->output);
      err |= write_hits(f, c, r, path);
      snprintf(files[nf++], 32, "hits.csv");
    }
  }
  /* on one line: tests mask it from "wall_seconds" to the end */
  fprintf(f, "  \"snapshots\": %ld,\n  \"wall_seconds\": %.3f, "
          "\"cpu_seconds\": %.3f\n}\n", nsnap, secs[0], secs[1]);
  err |= fclose(f) != 0;
  snprintf(path, sizeof path, "%s/manifest.txt", c->output);
  FILE *m = fopen(path, "w");
  if (!m)
    return -1;
  fprintf(m, "# files written by smolbridge collide (%s); the next run "
          "into this directory removes them\n", status);
  for (int i = 0; i < nf; i++)
    fprintf(m, "%s\n", files[i]);
  for (long k = 0; k < nsnap; k++)
    fprintf(m, "snap_%06ld.csv\n", k);
  err |= fclose(m) != 0;
  return err ? -1 : 0;
}
