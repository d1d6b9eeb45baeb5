/* firsthit.c — kernel measurement by first-hit counting (firsthit.h). */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>

#include <smolbridge/engine.h>
#include <smolbridge/engine_bridge.h>
#include <smolbridge/engine_firsthit.h>
#include <smolbridge/stats.h>

#include "firsthit.h"
#include "report.h"
#include "runsave.h"

#define PI 3.14159265358979323846

/* Independent uniform positions (overlaps allowed), velocities N(0, vsd);
 * the observer enters the pairs overlapping at the start as seen, so
 * every counted pair starts uniform outside the contact ball. */
static int place_uniform(const sbv_ctx *ctx, unsigned long stream,
                         sb_engine *e, const fh_run *q)
{
  gsl_rng *r = sbv_rng_alloc(ctx, 100000 + stream);
  if (!r)
    return SB_ENOMEM;
  const double vsd = q->vsd > 0.0 ? q->vsd : sqrt(0.5 * q->b2 / q->tau);
  int st = SB_SUCCESS;
  for (size_t i = 0; i < q->N && !st; i++) {
    double x[3], u[3];
    for (int k = 0; k < 3; k++) {
      x[k] = q->L * gsl_rng_uniform(r);
      u[k] = gsl_ran_gaussian_ziggurat(r, vsd);
    }
    st = sb_engine_add_particle(e, 0, 0, x, u);
  }
  gsl_rng_free(r);
  return st;
}

void fh_run_init(fh_run *q)
{
  memset(q, 0, sizeof *q);
  q->builtin = FH_BRIDGE;
  q->mode = SB_BRIDGE_BESSEL;
  q->ends = SB_BRIDGE_ENDS_POSITION;
}

int fh_cube_params(const sbv_ctx *ctx, unsigned long stream, double L,
                   double dt, size_t N, sb_engine_params *p)
{
  sbv_engine_params(p);
  p->L[0] = p->L[1] = p->L[2] = L;
  p->dt = dt;
  p->capacity = N;
  gsl_rng *sr = sbv_rng_alloc(ctx, stream);
  if (!sr)
    return SB_ENOMEM;
  p->seed = gsl_rng_get(sr);
  gsl_rng_free(sr);
  p->rng_type = gsl_rng_taus2;
  return SB_SUCCESS;
}

double fh_teff(const fh_run *q)
{
  double a = q->a_eff > 0.0 ? q->a_eff : q->d;
  return (q->T - q->t1) +
         2.0 * a * (sqrt(q->T) - sqrt(q->t1)) / sqrt(PI * q->b2);
}

double fh_box_for(double K, size_t N, double Teff, double hits, double b2T)
{
  double L = cbrt(K * (double)N * (double)N * Teff / (2.0 * hits));
  double Lmin = 10.0 * sqrt(2.0 * b2T);
  return L > Lmin ? L : Lmin;
}

void fh_size_for(fh_run *q, double K, double hits, size_t nmax)
{
  const double Teff = fh_teff(q), b2T = q->b2 * q->T;
  q->L = fh_box_for(K, q->N, Teff, hits, b2T);
  const double n = ceil(sqrt(2.0 * hits * q->L * q->L * q->L / (K * Teff)));
  if (n > (double)q->N) {
    q->N = n < (double)nmax ? (size_t)n : nmax;
    q->L = fh_box_for(K, q->N, Teff, hits, b2T);
  }
}

FILE *fh_ini_open(const sbv_ctx *ctx, unsigned long stream,
                  const sb_engine_params *p, double L, double T, double t1,
                  const char *detect, const char *name)
{
  sbv_report *rep = ctx->ini_rep;
  FILE *f = sbv_ini_begin(ctx, rep, name, "first-hit counting run");
  if (!f)
    return NULL;
  fprintf(f, "seed = %lu\nrng = taus2\nL = %.17g\ndt = %.17g\n"
          "t_end = %.17g\n", p->seed, L, p->dt, T);
  if (t1 > 0)
    fprintf(f, "warmup = %.17g\n", t1);
  fprintf(f, "detect = %s\noutcome = count\nplacement = uniform\n"
          "placement_seed = %lu\n", detect,
          sbv_rng_seed(ctx, 100000 + stream));
  return f;
}

const char *fh_ini_name(sbv_report *rep, char *buf, size_t n,
                        const char *dflt)
{
  snprintf(buf, n, "%s", rep->ini_next[0] ? rep->ini_next : dflt);
  rep->ini_next[0] = 0;
  return buf;
}

/* The run as a collide configuration (write mode); the expect line of
 * the case's next record is added by sbv_add. */
static int write_firsthit(const sbv_ctx *ctx, unsigned long stream,
                          const fh_run *q, const sb_engine_params *p,
                          fh_out *o)
{
  sbv_report *rep = ctx->ini_rep;
  memset(o, 0, sizeof *o);
  o->hits = 1;  /* unit values: the record's estimate is the factor */
  o->expected_per_K = o->K = o->lo = o->hi = 1.0;
  char name[128];
  fh_ini_name(rep, name, sizeof name, "firsthit");
  static const char *const det[] = {"bridge", "ballistic", "overlap", "md"};
  FILE *f = fh_ini_open(ctx, stream, p, q->L, q->T, q->t1,
                        q->builtin != FH_BRIDGE      ? det[q->builtin]
                        : q->mode == SB_BRIDGE_EXACT ? "exact"
                                                     : "bridge",
                        name);
  if (!f)
    return SB_EIO;
  if (q->builtin == FH_BRIDGE)
    fprintf(f, "\n[bridge]\nends = %s\n",
            q->ends == SB_BRIDGE_ENDS_DIFFUSIVE ? "diffusive" : "position");
  if (q->eps > 0)
    fprintf(f, "\n[turbulence]\neps = %.17g\nnu = %.17g\n", q->eps, q->nu);
  fprintf(f, "\n[observe]\nfirst_hit = yes\n");
  if (q->a_eff > 0)
    fprintf(f, "first_hit_radius = %.17g\n", q->a_eff);
  fprintf(f, "\n[species p]\nradius = %.17g\nmass = %.17g\ntau = %.17g\n"
          "b2 = %.17g\ncount = %zu\n", 0.5 * q->d, q->mass, q->tau,
          q->eps > 0 ? q->b2brown : q->b2, q->N);
  return sbv_ini_end(rep, f, "first_hit.K");
}

void fh_set_name(sbv_report *rep, const char *name)
{
  snprintf(rep->ini_next, sizeof rep->ini_next, "%s", name);
}

static int fh_engine_run(const sbv_ctx *ctx, unsigned long stream,
                         const fh_run *q, sb_engine_params *p, fh_out *o);

int fh_run_until(const sbv_ctx *ctx, sb_engine *e, double T)
{
  const double t0 = sb_engine_time(e), dt = sb_engine_get_params(e)->dt;
  const double work = (double)sb_engine_count(e) * (T - t0) / dt;
  if (!(work > FH_LONG_RUN))
    return sb_engine_run_until(e, T);
  /* whole steps either way: the parts change nothing in the run */
  for (int k = 1; k <= 20; k++) {
    int st = sb_engine_run_until(e, k == 20 ? T : t0 + (T - t0) * k / 20.0);
    if (st)
      return st;
    sbv_progress(ctx, "    %3d%% of %.3g particle-steps (N = %zu, dt = %.3g s)",
                 5 * k, work, sb_engine_count(e), dt);
  }
  return SB_SUCCESS;
}

int run_firsthit(const sbv_ctx *ctx, unsigned long stream, const fh_run *q,
                 fh_out *o)
{
  sb_engine_params p;
  if (fh_cube_params(ctx, stream, q->L, q->dt, q->N, &p))
    return SB_ENOMEM;
  if (sbv_writing(ctx))
    return write_firsthit(ctx, stream, q, &p, o);
  /* the saved run (runsave.h), keyed by every input */
  sbv_runkey k;
  sbv_runkey_init(&k, ctx, "firsthit", stream);
  const double in[] = {q->d, q->a_eff, q->tau, q->b2, q->b2brown, q->mass,
                       q->vsd, q->dt, q->L, (double)q->N, q->T, q->t1,
                       q->eps, q->nu, q->builtin, q->mode, q->ends};
  static const char *const nm[] = {"d", "a_eff", "tau", "b2", "b2brown",
                                   "m", "vsd", "dt", "L", "N", "T", "t1",
                                   "eps", "nu", "builtin", "mode", "ends"};
  for (size_t i = 0; i < sizeof in / sizeof in[0]; i++)
    sbv_runkey_num(&k, nm[i], in[i]);
  double v[8];
  int got = sbv_run_load_vals(ctx, &k, v, 8);
  if (got < 0)
    return got;
  if (got) {
    o->hits = (unsigned long)v[0];
    o->expected_per_K = v[1], o->K = v[2], o->lo = v[3], o->hi = v[4];
    o->cpu = v[5], o->steps = v[6], o->dispersion = v[7];
    return SB_SUCCESS;
  }
  int st = fh_engine_run(ctx, stream, q, &p, o);
  if (!st) {
    const double out[] = {(double)o->hits, o->expected_per_K, o->K, o->lo,
                          o->hi, o->cpu, o->steps, o->dispersion};
    sbv_run_save(ctx, &k, out, 8, NULL, 0);
  }
  return st;
}

/* The run itself (run_firsthit without the saved runs). */
static int fh_engine_run(const sbv_ctx *ctx, unsigned long stream,
                         const fh_run *q, sb_engine_params *pp, fh_out *o)
{
  sb_engine_params p = *pp;
  p.outcome = SB_OUTCOME_COUNT;
  sb_engine *e = sb_engine_alloc(&p);
  if (!e)
    return SB_ENOMEM;
  /* Langevin species with B tau = B_pos (diffusive limit for dt >> tau) */
  double Bv = sqrt(q->b2) / q->tau;
  sb_engine_species s = {0.5 * q->d, q->mass, q->tau, Bv, 0.0};
  sb_engine_bridge_params bp;
  sb_engine_bridge_params_default(&bp);
  bp.mode = q->mode;
  bp.ends = q->ends;
  bp.outcome = SB_BRIDGE_OUT_COUNT;
  sb_engine_bridge *b = sb_engine_bridge_alloc(&bp);
  sb_engine_firsthit_params fp;
  sb_engine_firsthit_params_default(&fp);
  if (q->builtin == FH_BRIDGE) {
    fp.detect = sb_engine_detect_bridge;
    fp.detect_ctx = b;
  } else if (q->builtin == FH_MD)
    fp.detect = sb_engine_detect_md;  /* Mohaupt 2011, §3.2, App. F */
  else
    fp.builtin = q->builtin == FH_OVERLAP ? SB_DETECT_OVERLAP
                                          : SB_DETECT_BALLISTIC;
  sb_engine_firsthit *f = sb_engine_firsthit_alloc(&fp);
  int st = !b || !f ? SB_ENOMEM : SB_SUCCESS;
  if (!st)
    st = sb_engine_add_species(e, &s, NULL);
  if (!st)
    st = place_uniform(ctx, stream, e, q);
  if (!st)
    st = sb_engine_bridge_set_b2(b, 0, q->b2, q->b2brown);
  if (!st)
    st = sb_engine_bridge_attach(e, b);
  if (!st)
    st = sb_engine_firsthit_set_warmup(f, q->t1);
  if (!st) {
    /* chords and overlap need no reach; the bridge its tail reach; the
     * velocity chords 7 sd of the relative speed (|u_i - u_j| dt) */
    double vsd = q->vsd > 0.0 ? q->vsd : sqrt(0.5 * q->b2 / q->tau);
    double reach = q->builtin == FH_MD
                       ? 7.0 * sqrt(2.0) * vsd * q->dt
                       : (q->builtin != FH_BRIDGE
                              ? 0.0
                              : sb_engine_bridge_reach(e, b));
    st = sb_engine_firsthit_attach(e, f, reach);
  }
  clock_t c0 = clock();
  if (!st)
    st = fh_run_until(ctx, e, q->T);
  o->cpu = (double)(clock() - c0) / CLOCKS_PER_SEC;
  if (!st) {
    /* each pair apart at the start is uniform on the torus minus the
     * contact ball; the reference radius a_eff (or d) */
    sb_engine_firsthit_kernel_result k;
    st = sb_engine_firsthit_kernel(f, e, 0, 0, q->a_eff > 0.0 ? q->a_eff
                                                              : q->d,
                                   q->b2, 0.95, &k);
    o->expected_per_K = k.expected_per_K;
    o->hits = (unsigned long)k.c.hits;
    o->K = k.K;
    o->lo = k.lo;
    o->hi = k.hi;
    o->dispersion = k.dispersion;
    sb_engine_stats es;
    sb_engine_get_stats(e, &es);
    o->steps = (double)es.steps;
  }
  sb_engine_bridge_free(b);
  sb_engine_firsthit_free(f);
  sb_engine_free(e);
  return st;
}
