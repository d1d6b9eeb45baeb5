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
#include <smolbridge/langevin.h>
#include <smolbridge/stats.h>

#include "firsthit.h"

#define PI 3.14159265358979323846

typedef struct {
  const lv_run *q;
  sb_engine_bridge *b;
  fh_set s;
  lv_out *o;
} lvctx;

static int pair_type(const sb_engine *e, size_t i, size_t j)
{
  const size_t *sp = sb_engine_species_of(e);
  return (int)(sp[i] + sp[j]);
}

/* Normal relative velocity at a chord contact at fraction s: velocities
 * interpolated linearly over the step (dt << tau_p for the reference). */
static double chord_vn(const sb_engine *e, const sb_engine_pair *p, double s)
{
  const double *u0 = sb_engine_start_velocities(e);
  const double *u1 = sb_engine_velocities(e);
  double n[3], nn = 0.0, vn = 0.0;
  for (int k = 0; k < 3; k++) {
    n[k] = p->dx0[k] + s * p->dd[k];
    nn += n[k] * n[k];
  }
  nn = sqrt(nn);
  for (int k = 0; k < 3; k++) {
    double ui = u0[3 * p->i + k] + s * (u1[3 * p->i + k] - u0[3 * p->i + k]);
    double uj = u0[3 * p->j + k] + s * (u1[3 * p->j + k] - u0[3 * p->j + k]);
    vn += (ui - uj) * n[k] / nn;
  }
  return vn;
}

/* Records the first detected contact of every pair and returns "no
 * collision" (the particles pass through each other). */
static int lv_detect(const sb_engine *e, const sb_engine_pair *p,
                     const gsl_rng *r, void *vctx, double *s)
{
  lvctx *f = vctx;
  const uint64_t *id = sb_engine_ids(e);
  const uint64_t key = fh_pair_key(id[p->i], id[p->j]);
  if (fh_set_has(&f->s, key))
    return 0;  /* its first contact is known: nothing to do */
  int h;
  double vn = NAN;
  switch (f->q->det) {
  case LV_LANGEVIN: {
    sb_langevin_contact c;
    h = sb_engine_langevin_contact(e, p, r, s, &c);
    if (h == 1) {
      vn = 0.0;
      for (int k = 0; k < 3; k++)
        vn += (c.ui[k] - c.uj[k]) * (c.xi[k] - c.xj[k]) / p->sigma;
    }
    break;
  }
  case LV_CHORD:
    h = sb_engine_detect_ballistic(p, s);
    if (h == 1)
      vn = chord_vn(e, p, *s);
    break;
  case LV_OVERLAP:
    h = sb_engine_detect_overlap(p, s);
    break;
  default:
    h = sb_engine_detect_bridge(e, p, r, f->b, s);
  }
  if (h <= 0)
    return h;
  if (fh_set_insert(&f->s, key) < 0)
    return -1;
  if (p->t0 + *s * p->dt >= f->q->t1) {
    lv_out *o = f->o;
    o->hits[pair_type(e, p->i, p->j)]++;
    if (!isnan(vn) && o->nvn < f->q->vcap)
      o->vn[o->nvn++] = vn;
  }
  return 0;
}

/* Independent uniform positions (overlaps allowed), Maxwellian velocities;
 * pairs overlapping at the start are entered in the set first. */
static int place(const sbv_ctx *ctx, unsigned long stream, sb_engine *e,
                 const lv_run *q, lvctx *f)
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
  if (st)
    return st;
  const size_t n = sb_engine_count(e);
  const double *x = sb_engine_positions(e), *rad = sb_engine_radii(e);
  const uint64_t *id = sb_engine_ids(e);
  double nov[3] = {0, 0, 0};
  /* cells of edge >= the largest contact distance: overlapping pairs lie
   * in neighbouring cells (at least 3 per direction, or one cell) */
  double dmax = 0.0;
  for (size_t i = 0; i < n; i++)
    dmax = fmax(dmax, 2.0 * rad[i]);
  int nc = (int)floor(q->L / dmax);
  nc = nc > 64 ? 64 : nc;
  if (nc < 3)
    nc = 1;
  const size_t ncell = (size_t)nc * nc * nc;
  size_t *head = malloc(ncell * sizeof *head), *next = malloc(n * sizeof *next);
  if (!head || !next) {
    free(head);
    free(next);
    return SB_ENOMEM;
  }
  for (size_t c = 0; c < ncell; c++)
    head[c] = SIZE_MAX;
  int (*cell)[3] = malloc(n * sizeof *cell);
  if (!cell) {
    free(head);
    free(next);
    return SB_ENOMEM;
  }
  for (size_t i = 0; i < n; i++) {
    size_t c = 0;
    for (int k = 0; k < 3; k++) {
      int v = (int)(x[3 * i + k] / q->L * nc);
      cell[i][k] = v < 0 ? 0 : (v >= nc ? nc - 1 : v);
      c = c * (size_t)nc + (size_t)cell[i][k];
    }
    next[i] = head[c];
    head[c] = i;
  }
  const int span = nc == 1 ? 0 : 1;
  for (size_t i = 0; i < n; i++)
    for (int a = -span; a <= span; a++)
      for (int b = -span; b <= span; b++)
        for (int g = -span; g <= span; g++) {
          const int o[3] = {a, b, g};
          size_t c = 0;
          for (int k = 0; k < 3; k++)
            c = c * (size_t)nc + (size_t)((cell[i][k] + o[k] + nc) % nc);
          for (size_t j = head[c]; j != SIZE_MAX; j = next[j]) {
            if (j <= i)
              continue;
            double d2 = 0.0;
            for (int k = 0; k < 3; k++) {
              double dx = x[3 * i + k] - x[3 * j + k];
              dx -= q->L * floor(dx / q->L + 0.5);
              d2 += dx * dx;
            }
            double sg = rad[i] + rad[j];
            if (d2 <= sg * sg) {
              if (fh_set_insert(&f->s, fh_pair_key(id[i], id[j])) < 0) {
                free(head);
                free(next);
                free(cell);
                return SB_ENOMEM;
              }
              nov[pair_type(e, i, j)] += 1.0;
            }
          }
        }
  free(head);
  free(next);
  free(cell);
  const double N0 = (double)q->N[0], N1 = q->nsp > 1 ? (double)q->N[1] : 0.0;
  const double tot[3] = {0.5 * N0 * (N0 - 1.0), N0 * N1, 0.5 * N1 * (N1 - 1.0)};
  const double V = q->L * q->L * q->L;
  for (int t = 0; t < 3; t++) {
    int a = t == 2 ? 1 : 0, b = t == 0 ? 0 : 1;
    if (b >= q->nsp)
      a = b = 0;
    double R = 0.5 * (q->d[a] + q->d[b]);
    f->o->npairs[t] = tot[t] - nov[t];
    f->o->veff[t] = V - 4.0 * PI * R * R * R / 3.0;
    f->o->D[t] = SB_BOLTZMANN * q->temp *
                 (q->tau[a] / q->mass[a] + q->tau[b] / q->mass[b]);
  }
  return SB_SUCCESS;
}

int lv_firsthit(const sbv_ctx *ctx, unsigned long stream, const lv_run *q,
                lv_out *o)
{
  memset(o, 0, sizeof *o);
  sb_engine_params p;
  size_t ntot = q->N[0] + (q->nsp > 1 ? q->N[1] : 0);
  if (fh_cube_params(ctx, stream, q->L, q->dt, ntot, &p))
    return SB_ENOMEM;
  p.outcome = SB_OUTCOME_COUNT;
  sb_engine *e = sb_engine_alloc(&p);
  lvctx f = {q, NULL, {NULL, 0, 0}, o};
  if (q->vcap)
    o->vn = malloc(q->vcap * sizeof *o->vn);
  int st = (!e || (q->vcap && !o->vn)) ? SB_ENOMEM : SB_SUCCESS;
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
    st = place(ctx, stream, e, q, &f);
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
    st = sb_engine_set_detector(e, lv_detect, &f, reach);
  clock_t c0 = clock();
  if (!st)
    st = sb_engine_run_until(e, q->T);
  o->cpu = (double)(clock() - c0) / CLOCKS_PER_SEC;
  if (!st) {
    sb_engine_stats es;
    sb_engine_get_stats(e, &es);
    o->T = es.t;
    o->steps = (double)es.steps;
    o->ncand = (double)es.ncand;
    sb_langevin_hit_stats hs;
    if (q->det == LV_LANGEVIN && !sb_engine_langevin_stats(e, &hs))
      o->pruned_mass = hs.pruned_mass;
  }
  sb_engine_bridge_free(f.b);
  free(f.s.set);
  sb_engine_free(e);
  if (st) {
    free(o->vn);
    o->vn = NULL;
  }
  return st;
}

/* The forward map is f(K) = c1 K + c2 K^2 (firsthit.h). */
static void coefs(const lv_run *q, const lv_out *o, int type, double *c1,
                  double *c2)
{
  const double D = o->D[type];
  const double c = o->npairs[type] / o->veff[type];
  *c1 = c * (o->T - q->t1);
  *c2 = c * 2.0 * (sqrt(o->T) - sqrt(q->t1)) / (4.0 * PI * D * sqrt(PI * D));
}

double lv_expected(const lv_run *q, const lv_out *o, int type, double K)
{
  double c1, c2;
  coefs(q, o, type, &c1, &c2);
  return c1 * K + c2 * K * K;
}

/* Inverse of lv_expected in K for a count h (the positive root). */
static double kernel_of(const lv_run *q, const lv_out *o, int type, double h)
{
  double c1, c2;
  coefs(q, o, type, &c1, &c2);
  if (!(c2 > 0.0))
    return h / c1;
  /* (-c1 + sqrt(c1^2 + 4 c2 h)) / (2 c2), written without cancellation */
  return 2.0 * h / (c1 + sqrt(c1 * c1 + 4.0 * c2 * h));
}

int lv_kernel(const lv_run *q, const lv_out *o, int type, double *K,
              double *lo, double *hi)
{
  if (type < 0 || type > 2 || !(o->npairs[type] > 0.0))
    return SB_EDOM;
  double l, u;
  int st = sb_poisson_ci(o->hits[type], 0.95, &l, &u);
  if (st)
    return st;
  *K = kernel_of(q, o, type, (double)o->hits[type]);
  if (lo)
    *lo = kernel_of(q, o, type, l);
  if (hi)
    *hi = kernel_of(q, o, type, u);
  return SB_SUCCESS;
}

int lv_add_compare(sbv_report *rep, const char *name, const lv_run *q1,
                   const lv_out *o1, const lv_run *q2, const lv_out *o2,
                   int type)
{
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
  /* E[h1]/E[h2] = (K1 e1)/(K2 e2): ratio = p/(1 - p) e2/e1 */
  const double w = e2 / e1;
  double est = h2 ? (double)h1 / (double)h2 * w : INFINITY;
  double rlo = lo / (1.0 - lo) * w;
  double rhi = hi < 1.0 ? hi / (1.0 - hi) * w : INFINITY;
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
