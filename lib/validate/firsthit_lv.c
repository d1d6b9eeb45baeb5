#define _POSIX_C_SOURCE 200809L /* clock_gettime */
/* firsthit_lv.c — first-hit counting of Langevin spheres in the transition
 * regime, one or two species, any detector (estimator and protocol:
 * firsthit.h). */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>
#include <gsl/gsl_roots.h>

#include <smolbridge/engine.h>
#include <smolbridge/engine_bridge.h>
#include <smolbridge/engine_firsthit.h>
#include <smolbridge/langevin.h>
#include <smolbridge/stats.h>

#include "firsthit.h"
#include "runsave.h"

#define PI 3.14159265358979323846

/* Detector context: the run, its bridge detector (Bessel-3 or exact
 * 3-D bridge), its output. */
typedef struct {
  const lv_run *q;
  sb_engine_bridge *b;
  lv_out *o;
} lvctx;

/* The bridge detectors, wrapped by the first-contact observer (which
 * skips the pairs whose first contact is known); the observer watches
 * the other detectors as the built-ins themselves. */
static int lv_detect(const sb_engine *e, const sb_engine_pair *p,
                     const gsl_rng *r, void *vctx, double *s)
{
  const lvctx *f = vctx;
  return sb_engine_detect_bridge(e, p, r, f->b, s);
}

/* A counted first contact: keep its normal velocity (`langevin`: the
 * built-in's draw at the contact; contact time: the chord's). */
static int lv_hit(const sb_engine *e, const sb_engine_pair *p, double s,
                  void *vctx)
{
  const lvctx *f = vctx;
  lv_out *o = f->o;
  if (o->nvn >= f->q->vcap ||
      (f->q->det != LV_LANGEVIN && f->q->det != LV_CHORD))
    return 0;
  const double vn = f->q->det == LV_LANGEVIN ? sb_engine_contact_vn(e)
                                             : sb_engine_chord_vn(e, p, s);
  if (isnan(vn))
    return -1;
  o->vn[o->nvn++] = vn;
  return 0;
}

/* Independent uniform positions (overlaps allowed), Maxwellian velocities
 * (the observer enters the pairs overlapping at the start as seen). */
static int place(const sbv_ctx *ctx, unsigned long stream, sb_engine *e,
                 const lv_run *q)
{
  gsl_rng *r = sbv_rng_alloc(ctx, 100000 + stream);
  if (!r)
    return SB_ENOMEM;
  int st = SB_SUCCESS;
  for (int a = 0; a < q->nsp && !st; a++) {
    const double vsd = sqrt(SB_BOLTZMANN * q->temp / q->mass[a]);
    for (size_t i = 0; i < q->N[a] && !st; i++) {
      double x[3], u[3];
      for (int k = 0; k < 3; k++) {
        x[k] = q->L * gsl_rng_uniform(r);
        u[k] = gsl_ran_gaussian_ziggurat(r, vsd);
      }
      u[0] += q->G * (x[1] - 0.5 * q->L);  /* the shear field, if any */
      st = sb_engine_add_particle(e, (size_t)a, 0, x, u);
    }
  }
  gsl_rng_free(r);
  return st;
}

/* Per pair type (0-0, 0-1, 1-1): counts from the observer, the volume
 * outside the contact ball and the relative diffusivity. */
static int fill_out(const lv_run *q, const sb_engine_firsthit *fh,
                    lv_out *o)
{
  const double V = q->L * q->L * q->L;
  for (int t = 0; t < 3; t++) {
    const size_t sa = t == 2 ? 1 : 0, sb = t == 0 ? 0 : 1;
    sb_engine_firsthit_counts c;
    int st = sb_engine_firsthit_get(fh, sa, sb, &c);
    if (st)
      return st;
    o->hits[t] = (unsigned long)c.hits;
    o->hits_var[t] = c.hits_var;
    o->npairs[t] = c.pairs_apart;
    int a = (int)sa, b = (int)sb;
    if (b >= q->nsp)
      a = b = 0;
    double R = 0.5 * (q->d[a] + q->d[b]);
    o->veff[t] = V - 4.0 * PI * R * R * R / 3.0;
    o->D[t] = SB_BOLTZMANN * q->temp *
              (q->tau[a] / q->mass[a] + q->tau[b] / q->mass[b]);
  }
  return SB_SUCCESS;
}

/* Section name of species a of the run in its collide file. */
static const char *lv_name(const lv_run *q, int a)
{
  static const char *const dflt[2][2] = {{"p", ""}, {"p0", "p1"}};
  return q->names[a][0] ? q->names[a] : dflt[q->nsp > 1][a];
}

/* The settling velocities that collide's placement adds (the engine's
 * sb_engine_settling_velocity of the same species under the same g), in
 * vs[a][k]; the file gives each species the opposite as its drift, so
 * that the placed velocities are the Maxwellian ones of place(). */
static int lv_settling(const lv_run *q, const sb_engine_params *p,
                       double vs[2][3])
{
  sb_engine_params pp = *p;
  pp.capacity = 1;
  sb_engine *e = sb_engine_alloc(&pp);
  int st = e ? SB_SUCCESS : SB_ENOMEM;
  for (int a = 0; a < q->nsp && !st; a++) {
    double B = sqrt(2.0 * SB_BOLTZMANN * q->temp / (q->mass[a] * q->tau[a]));
    sb_engine_species s = {0.5 * q->d[a], q->mass[a], q->tau[a], B, q->temp};
    st = sb_engine_add_species(e, &s, NULL);
  }
  if (!st)
    st = sb_engine_set_gravity(e, q->g);
  for (int a = 0; a < q->nsp && !st; a++)
    st = sb_engine_settling_velocity(e, (size_t)a, vs[a]);
  sb_engine_free(e);
  return st;
}

/* The run as a collide configuration (write mode): one or two species
 * (collide's first_hit counts every species pair), gravity with the
 * settling velocity taken out of the placement, shear; o gets unit
 * values (lv_kernel: K = 1), so the next record's estimate is the factor
 * of its expect line (one species; the two-species cases write their
 * expect lines, first_hit.pairs[a,b].K). */
static int write_lv(const sbv_ctx *ctx, unsigned long stream,
                    const lv_run *q, const sb_engine_params *p, lv_out *o)
{
  sbv_report *rep = ctx->ini_rep;
  o->unit = 1;
  for (int t = 0; t < 3; t++)
    o->npairs[t] = 1.0;
  char name[128];
  fh_ini_name(rep, name, sizeof name, "firsthit_lv");
  const int grav = q->g[0] != 0.0 || q->g[1] != 0.0 || q->g[2] != 0.0;
  double vs[2][3] = {{0, 0, 0}, {0, 0, 0}};
  if (grav) {
    int st = lv_settling(q, p, vs);
    if (st)
      return st;
  }
  static const char *const det[] = {"langevin", "ballistic", "overlap",
                                    "bridge", "exact"};
  FILE *f = fh_ini_open(ctx, stream, p, q->L, q->T, q->t1, det[q->det],
                        name);
  if (!f)
    return SB_EIO;
  /* T gives B = sqrt(2 k_B T / (m tau)) and the Maxwellian velocities
   * sqrt(k_B T / m), as the run; shear: collide's placement adds the
   * fluid velocity G (y - L/2) to u_x, as place() */
  if (q->G != 0.0 || grav)
    fprintf(f, "\n[fluid]\n");
  if (q->G != 0.0)
    fprintf(f, "type = shear\nG = %.17g\nlees_edwards = yes\n", q->G);
  if (grav)
    fprintf(f, "g = %.17g %.17g %.17g\n", q->g[0], q->g[1], q->g[2]);
  fprintf(f, "\n[observe]\nfirst_hit = yes\n");
  /* fh_contact: no key, collide's default (each pair's r_i + r_j) */
  if (!q->fh_contact && q->fh_radius > 0.0)
    fprintf(f, "first_hit_radius = %.17g\n", q->fh_radius);
  else if (!q->fh_contact)
    fprintf(f, "first_hit_capacitance = yes\n");
  fprintf(f, "first_hit_skip_seen = yes\n");
  /* the normal velocities at the first vcap contacts (contacts.csv) */
  if (q->vcap && (q->det == LV_LANGEVIN || q->det == LV_CHORD))
    fprintf(f, "first_hit_velocities = %zu\n", q->vcap);
  for (int a = 0; a < q->nsp; a++) {
    fprintf(f, "\n[species %s]\nradius = %.17g\nmass = %.17g\ntau = %.17g\n"
            "T = %.17g\ncount = %zu\n", lv_name(q, a), 0.5 * q->d[a],
            q->mass[a], q->tau[a], q->temp, q->N[a]);
    if (grav)  /* u + (v_s + drift) = u + 0 exactly */
      fprintf(f, "; the case starts at the Maxwellian velocities: the "
              "opposite of the\n; settling velocity that the placement "
              "adds\ndrift = %.17g %.17g %.17g\n", -vs[a][0], -vs[a][1],
              -vs[a][2]);
  }
  return sbv_ini_end(rep, f, q->nsp == 1 ? "first_hit.K" : NULL);
}

/* The saved-run key of q (runsave.h): every input of the run. */
static void lv_key(const sbv_ctx *ctx, unsigned long stream,
                   const lv_run *q, sbv_runkey *k)
{
  sbv_runkey_init(k, ctx, "firsthit-lv", stream);
  sbv_runkey_num(k, "nsp", q->nsp);
  for (int a = 0; a < q->nsp; a++) {
    sbv_runkey_num(k, "d", q->d[a]);
    sbv_runkey_num(k, "tau", q->tau[a]);
    sbv_runkey_num(k, "m", q->mass[a]);
    sbv_runkey_num(k, "N", (double)q->N[a]);
  }
  const double in[] = {q->temp, q->dt, q->L, q->t1, q->T, q->det,
                       (double)q->vcap, q->g[0], q->g[1], q->g[2], q->G};
  static const char *const nm[] = {"temp", "dt", "L", "t1", "T", "det",
                                   "vcap", "gx", "gy", "gz", "G"};
  for (size_t i = 0; i < sizeof in / sizeof in[0]; i++)
    sbv_runkey_num(k, nm[i], in[i]);
  if (q->default_rng)
    sbv_runkey_num(k, "default_rng", 1.0);
  if (q->sort_every)
    sbv_runkey_num(k, "sort_every", (double)q->sort_every);
}

/* lv_out's numbers (not vn) to and from a flat array. */
#define LV_NSAVE 21
static void lv_to_array(const lv_out *o, double *v)
{
  for (int t = 0; t < 3; t++) {
    v[t] = (double)o->hits[t];
    v[3 + t] = o->npairs[t];
    v[6 + t] = o->veff[t];
    v[9 + t] = o->D[t];
    v[18 + t] = o->hits_var[t];
  }
  v[12] = o->T, v[13] = (double)o->nvn, v[14] = o->cpu;
  v[15] = o->steps, v[16] = o->ncand, v[17] = o->pruned_mass;
}

static void lv_from_array(const double *v, lv_out *o)
{
  for (int t = 0; t < 3; t++) {
    o->hits[t] = (unsigned long)v[t];
    o->npairs[t] = v[3 + t];
    o->veff[t] = v[6 + t];
    o->D[t] = v[9 + t];
    o->hits_var[t] = v[18 + t];
  }
  o->T = v[12], o->nvn = (size_t)v[13], o->cpu = v[14];
  o->steps = v[15], o->ncand = v[16], o->pruned_mass = v[17];
}

static int lv_engine_run(const sbv_ctx *ctx, unsigned long stream,
                         const lv_run *q, sb_engine_params *p, lv_out *o);

int lv_firsthit(const sbv_ctx *ctx, unsigned long stream, const lv_run *q,
                lv_out *o)
{
  memset(o, 0, sizeof *o);
  sb_engine_params p;
  size_t ntot = q->N[0] + (q->nsp > 1 ? q->N[1] : 0);
  if (fh_cube_params(ctx, stream, q->L, q->dt, ntot, &p))
    return SB_ENOMEM;
  if (q->default_rng) {
    sb_engine_params d;
    sb_engine_params_default(&d);
    p.rng_type = d.rng_type;
    p.streams = d.streams;
  }
  p.sort_every = q->sort_every;
  if (sbv_writing(ctx))
    return write_lv(ctx, stream, q, &p, o);
  sbv_runkey k;
  lv_key(ctx, stream, q, &k);
  double v[LV_NSAVE], *vn;
  size_t nvn;
  int got = sbv_run_load(ctx, &k, v, LV_NSAVE, &vn, &nvn);
  if (got < 0)
    return got;
  if (got) {
    lv_from_array(v, o);
    if (nvn != o->nvn || nvn > q->vcap ||
        (q->vcap && !vn && !(vn = malloc(sizeof *vn)))) {
      free(vn);  /* inconsistent file (or out of memory): run it */
      memset(o, 0, sizeof *o);
    } else {
      o->vn = vn;
      return SB_SUCCESS;
    }
  }
  int st = lv_engine_run(ctx, stream, q, &p, o);
  if (!st) {
    lv_to_array(o, v);
    sbv_run_save(ctx, &k, v, LV_NSAVE, o->vn, o->nvn);
  }
  return st;
}

int lv_pool(lv_out *acc, lv_out *add, size_t vcap)
{
  int st = SB_SUCCESS;
  /* the estimator pools runs of one box and one end time only */
  if (acc->T != add->T || acc->unit != add->unit)
    st = SB_EINVAL;
  for (int t = 0; t < 3 && !st; t++)
    if (acc->veff[t] != add->veff[t] || acc->D[t] != add->D[t])
      st = SB_EINVAL;
  size_t n = acc->nvn + add->nvn;
  if (n > vcap)
    n = vcap;
  if (!st && n > acc->nvn) {
    double *v = realloc(acc->vn, n * sizeof *v);
    if (!v)
      st = SB_ENOMEM;
    else {
      memcpy(v + acc->nvn, add->vn, (n - acc->nvn) * sizeof *v);
      acc->vn = v;
      acc->nvn = n;
    }
  }
  if (!st) {
    for (int t = 0; t < 3; t++) {
      acc->hits[t] += add->hits[t];
      acc->hits_var[t] += add->hits_var[t];  /* independent runs */
      acc->npairs[t] += add->npairs[t];
    }
    acc->cpu += add->cpu;
    acc->steps += add->steps;
    acc->ncand += add->ncand;
    acc->pruned_mass += add->pruned_mass;
  }
  free(add->vn);
  add->vn = NULL;
  add->nvn = 0;
  return st;
}

/* CPU seconds of the process, or of the calling thread (a run that is
 * one of several running at once). */
static double cpu_seconds(int thread)
{
  struct timespec ts;
  if (clock_gettime(thread ? CLOCK_THREAD_CPUTIME_ID
                           : CLOCK_PROCESS_CPUTIME_ID, &ts))
    return NAN;
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* The run itself (lv_firsthit without the saved runs). */
static int lv_engine_run(const sbv_ctx *ctx, unsigned long stream,
                         const lv_run *q, sb_engine_params *pp, lv_out *o)
{
  sb_engine_params p = *pp;
  p.outcome = SB_OUTCOME_COUNT;
  if (q->threads > 0)
    p.threads = q->threads;
  sb_engine *e = sb_engine_alloc(&p);
  lvctx f = {q, NULL, o};
  sb_engine_firsthit_params fp;
  sb_engine_firsthit_params_default(&fp);
  if (q->det == LV_LANGEVIN || q->det == LV_CHORD || q->det == LV_OVERLAP)
    fp.builtin = q->det == LV_LANGEVIN ? SB_DETECT_LANGEVIN
                 : q->det == LV_CHORD  ? SB_DETECT_BALLISTIC
                                       : SB_DETECT_OVERLAP;  /* observed */
  else {
    fp.detect = lv_detect;
    fp.detect_ctx = &f;
  }
  fp.skip_seen = 1;
  fp.on_hit = lv_hit;
  fp.hit_ctx = &f;
  sb_engine_firsthit *fh = sb_engine_firsthit_alloc(&fp);
  if (q->vcap)
    o->vn = malloc(q->vcap * sizeof *o->vn);
  int st = (!e || !fh || (q->vcap && !o->vn)) ? SB_ENOMEM : SB_SUCCESS;
  for (int a = 0; a < q->nsp && !st; a++) {
    double B = sqrt(2.0 * SB_BOLTZMANN * q->temp / (q->mass[a] * q->tau[a]));
    sb_engine_species s = {0.5 * q->d[a], q->mass[a], q->tau[a], B, q->temp};
    st = sb_engine_add_species(e, &s, NULL);
  }
  /* hook: gravity (settling velocity tau_p g; V16/combined) */
  if (!st && (q->g[0] != 0.0 || q->g[1] != 0.0 || q->g[2] != 0.0))
    st = sb_engine_set_gravity(e, q->g);
  /* hook: shear with Lees-Edwards images (every detector is image-aware
   * with the count outcome; V16/combined-shear-diffusive) */
  if (!st && q->G != 0.0) {
    const double Gv[3] = {q->G, 0.0, 0.0};
    st = sb_engine_set_fluid(e, SB_FLUID_SHEAR, Gv);
    if (!st)
      st = sb_engine_set_lees_edwards(e, 1);
  }
  if (!st)
    st = place(ctx, stream, e, q);
  double reach = 0.0;
  if (!st && (q->det == LV_BESSEL || q->det == LV_EXACT)) {
    sb_engine_bridge_params bp;
    sb_engine_bridge_params_default(&bp);
    bp.mode = q->det == LV_EXACT ? SB_BRIDGE_EXACT : SB_BRIDGE_BESSEL;
    bp.outcome = SB_BRIDGE_OUT_COUNT;
    f.b = sb_engine_bridge_alloc(&bp);
    st = !f.b ? SB_ENOMEM : sb_engine_bridge_attach(e, f.b);
    if (!st)
      reach = sb_engine_bridge_reach(e, f.b);
    /* lv_detect never reports a contact: back to the plain count outcome
     * (which the Lees-Edwards images require) */
    if (!st)
      st = sb_engine_set_outcome(e, SB_OUTCOME_COUNT, 1.0);
  } else if (!st && q->det == LV_LANGEVIN)
    reach = sb_engine_langevin_reach(e);
  if (!st && !(reach >= 0.0))
    st = SB_EINVAL;
  if (!st)
    st = sb_engine_firsthit_set_warmup(fh, q->t1);
  if (!st)
    st = sb_engine_firsthit_attach(e, fh, reach);
  const double c0 = cpu_seconds(q->threads == 1);
  if (!st)
    st = fh_run_until(ctx, e, q->T);
  o->cpu = cpu_seconds(q->threads == 1) - c0;
  if (!st) {
    sb_engine_stats es;
    sb_engine_get_stats(e, &es);
    o->T = es.t;
    o->steps = (double)es.steps;
    o->ncand = (double)es.ncand;
    sb_langevin_hit_stats hs;
    if (q->det == LV_LANGEVIN && !sb_engine_langevin_stats(e, &hs))
      o->pruned_mass = hs.pruned_mass;
    st = fill_out(q, fh, o);
  }
  sb_engine_bridge_free(f.b);
  sb_engine_firsthit_free(fh);
  sb_engine_free(e);
  if (st) {
    free(o->vn);
    o->vn = NULL;
  }
  return st;
}

/* The estimator's inputs for pair type `type` (capacitance radius). */
static void lv_inputs(const lv_run *q, const lv_out *o, int type,
                      sb_engine_firsthit_kernel_result *k)
{
  memset(k, 0, sizeof *k);
  k->c.hits = o->hits[type];
  k->c.hits_var = o->hits_var[type];
  k->c.pairs_apart = o->npairs[type];
  k->radius = SB_ENGINE_FIRSTHIT_CAPACITANCE;
  k->D = o->D[type];
  k->t1 = q->t1;
  k->t = o->T;
  k->veff = o->veff[type];
}

/* The forward map is f(K) = c1 K + c2 K^2 (firsthit.h). */
static void coefs(const lv_run *q, const lv_out *o, int type, double *c1,
                  double *c2)
{
  sb_engine_firsthit_kernel_result k;
  lv_inputs(q, o, type, &k);
  if (sb_engine_firsthit_coefs(&k, c1, c2))
    *c1 = *c2 = NAN;
}

double lv_expected(const lv_run *q, const lv_out *o, int type, double K)
{
  double c1, c2;
  coefs(q, o, type, &c1, &c2);
  return c1 * K + c2 * K * K;
}

int lv_kernel(const lv_run *q, const lv_out *o, int type, double *K,
              double *lo, double *hi)
{
  if (type < 0 || type > 2 || !(o->npairs[type] > 0.0))
    return SB_EDOM;
  sb_engine_firsthit_kernel_result k;
  lv_inputs(q, o, type, &k);
  int st = o->unit ? SB_SUCCESS : sb_engine_firsthit_estimate(&k, 0.95);
  if (o->unit)  /* write mode: the record's estimate is the factor */
    k.K = k.lo = k.hi = 1.0;
  *K = k.K;
  if (lo)
    *lo = k.lo;
  if (hi)
    *hi = k.hi;
  return st;
}

/* The kernel K > 0 of the forward map a K + b K^2 = y (y >= 0). */
static double finv(double a, double b, double y)
{
  return 2.0 * y / (a + sqrt(a * a + 4.0 * b * y));
}

int lv_add_compare(sbv_report *rep, const char *name, const lv_run *q1,
                   const lv_out *o1, const lv_run *q2, const lv_out *o2,
                   int type)
{
  sbv_ini_no_expect(rep);  /* write mode: two runs, no one file's record */
  const unsigned long h1 = o1->hits[type], h2 = o2->hits[type];
  const unsigned long n = h1 + h2;
  double a1, b1, a2, b2;
  coefs(q1, o1, type, &a1, &b1);
  coefs(q2, o2, type, &a2, &b2);
  sb_comparison c;
  if (n == 0 || !(a1 > 0.0) || !(a2 > 0.0)) {
    sb_compare(&c, name, SB_RULE_COVER, NAN, 1.0, NAN, NAN,
               1.0 - SBV_ALPHA, NAN);
    return sbv_add(rep, &c);
  }
  /* common K: (a1 + a2) K + (b1 + b2) K^2 = n */
  const double A = a1 + a2, B = b1 + b2;
  const double K = 2.0 * (double)n / (A + sqrt(A * A + 4.0 * B * n));
  const double e1 = a1 + b1 * K, e2 = a2 + b2 * K;  /* f(K)/K */
  const double pi = e1 / (e1 + e2);
  double p = sb_binomial_pvalue(h1, n, pi), lo, hi;
  sb_binomial_ci(h1, n, 1.0 - SBV_ALPHA, &lo, &hi);
  /* a share q of the n contacts to run 1 is K1 = f1^-1(n q), K2 =
   * f2^-1(n (1 - q)): the estimate (q = h1/n) is each run's own estimate
   * (lv_kernel), and the ratio is 1 exactly at q = pi, so the interval
   * covers 1 when the binomial interval covers pi.  (The secants f(K)/K
   * at the common K would give E[h1]/E[h2] ~ (K1/K2)^(1 + beta), beta
   * the transient's share of the count: 0.8 at Kn_D = 0.01.) */
  double est = h2 ? finv(a1, b1, (double)h1) / finv(a2, b2, (double)h2)
                  : INFINITY;
  double rlo = finv(a1, b1, n * lo) / finv(a2, b2, n * (1.0 - lo));
  double rhi = hi < 1.0 ? finv(a1, b1, n * hi) / finv(a2, b2, n * (1.0 - hi))
                        : INFINITY;
  sb_compare(&c, name, SB_RULE_COVER, est, 1.0, rlo, rhi, 1.0 - SBV_ALPHA,
             p);
  return sbv_add(rep, &c);
}

typedef struct {
  size_t nx, ny;
  double la;
} ks2par;

static double ks2_f(double d, void *vp)
{
  const ks2par *k = vp;
  double p = sb_ks2_pvalue(k->nx, k->ny, d);
  return log(p > 1e-300 ? p : 1e-300) - k->la;
}

int lv_add_ks2(sbv_report *rep, const char *name, double *x, size_t nx,
               double *y, size_t ny)
{
  double d = NAN, p = NAN, crit = NAN;
  if (nx && ny && sb_ks2_test(x, nx, y, ny, &d, &p) == SB_SUCCESS) {
    ks2par k = {nx, ny, log(SBV_ALPHA)};
    gsl_function F = {ks2_f, &k};
    gsl_root_fsolver *s = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
    double lo = 1e-6, hi = 1.0 - 1e-9;
    if (s && ks2_f(lo, &k) > 0.0 && ks2_f(hi, &k) < 0.0 &&
        gsl_root_fsolver_set(s, &F, lo, hi) == GSL_SUCCESS)
      for (int i = 0; i < 200; i++) {
        if (gsl_root_fsolver_iterate(s) != GSL_SUCCESS)
          break;
        crit = gsl_root_fsolver_root(s);
        if (gsl_root_test_interval(gsl_root_fsolver_x_lower(s),
                                   gsl_root_fsolver_x_upper(s), 0,
                                   1e-10) == GSL_SUCCESS)
          break;
      }
    if (s)
      gsl_root_fsolver_free(s);
  }
  /* reference: mean of D under H0 ~ 0.8687 / sqrt(n_e) */
  double ne = nx && ny ? (double)nx * ny / (double)(nx + ny) : NAN;
  sb_comparison c;
  sb_compare(&c, name, SB_RULE_ACCEPT, d, 0.868731160636 / sqrt(ne), 0.0,
             crit, 1.0 - SBV_ALPHA, p);
  return sbv_add(rep, &c);
}
