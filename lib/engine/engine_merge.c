/* engine_merge.c — agglomeration in the collision engine:
 * particle removal, the merge outcome, the DLVO sticking outcome and the
 * cluster-size bookkeeping (one engine species per cluster size).
 *
 * Merge (docs/agglomeration.md §merge).  Particles i and j (masses m_i,
 * m_j, k_i and k_j primaries) become one cluster of k = k_i + k_j
 * primaries, kept in slot i; j is removed at the end of the step.  With
 * M = m_i + m_j:
 *   u   = (m_i u_i + m_j u_j)/M                 (momentum conserved)
 *   x   = (m_i x_i + m_j x_j)/M                 (mass barycentre)
 * where x_i, x_j are the end-of-step positions (x_j taken as the minimum
 * image next to x_i: x_i - x_j = dx0 + dd).  Across a Lees-Edwards
 * boundary that image moves n G L_y faster along x than j: u_j there is
 * the image's velocity, so that momentum is conserved in the frame of i,
 * where the cluster stays (docs/engine_forces.md §3).  The chords are straight
 * lines, so the barycentre at the end is the barycentre at contact moved
 * by the centre-of-mass chord velocity over the rest of the step: taking
 * it at the end of the step is the same as merging at contact and moving
 * the cluster with the pair's centre-of-mass chord.  The cluster's
 * species is the one of size k (created on the first merge that makes
 * size k): its radius, mass, tau_p and B follow from k by the growth law.
 *
 * DLVO (Mohaupt 2011, §1.2.4, App. C): the pair sticks (merges) if its
 * relative kinetic energy E_rel exceeds the energy barrier W_max, otherwise it
 * rebounds.  E_rel = mu |w|^2/2 (or its normal part) with w the relative
 * chord velocity dd/dt at contact (ballistic: exact for free flight and a
 * good approximation for dt << tau_p), or drawn from the stationary
 * Maxwellian law (diffusive regime, where the chord velocity is not a
 * velocity), see <smolbridge/dlvo.h>.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <smolbridge/dlvo.h>

#include "common/internal.h"
#include "engine_agglo_state.h"
#include "engine_internal.h"

/* ============================================================ removal */

int sb_engine_remove_particle(sb_engine *e, size_t i)
{
  if (!e || i >= e->n)
    return sbi_error(SB_EINVAL, __func__, "bad engine or particle index");
  if (e->hit[i] != 2) {
    e->hit[i] = 2;
    e->nremove++;
  }
  return SB_SUCCESS;
}

int sbi_engine_purge(sb_engine *e)
{
  if (!e->nremove)
    return SB_SUCCESS;
  /* stable compaction: the survivors keep their relative order, so runs
   * stay reproducible whatever the removal pattern */
  size_t w = 0;
  for (size_t r = 0; r < e->n; r++) {
    if (e->hit[r] == 2)
      continue;
    if (w != r) {
      memcpy(&e->x[3 * w], &e->x[3 * r], 3 * sizeof(double));
      memcpy(&e->u[3 * w], &e->u[3 * r], 3 * sizeof(double));
      memcpy(&e->x0[3 * w], &e->x0[3 * r], 3 * sizeof(double));
      memcpy(&e->u0[3 * w], &e->u0[3 * r], 3 * sizeof(double));
      memcpy(&e->disp[3 * w], &e->disp[3 * r], 3 * sizeof(double));
      memcpy(&e->us[3 * w], &e->us[3 * r], 3 * sizeof(double));
      e->radius[w] = e->radius[r];
      e->mass[w] = e->mass[r];
      e->species[w] = e->species[r];
      e->family[w] = e->family[r];
      e->id[w] = e->id[r];
      e->hit[w] = e->hit[r];
    }
    w++;
  }
  e->n = w;
  e->nremove = 0;
  e->norder = 0;  /* the sweep order refers to old indices */
  return SB_SUCCESS;
}

int sb_engine_flush_removals(sb_engine *e)
{
  if (!e)
    return sbi_error(SB_EINVAL, __func__, "engine is NULL");
  SBI_NOT_IN_STEP(e, __func__);
  return sbi_engine_purge(e);
}

int sb_engine_set_particle_species(sb_engine *e, size_t i, size_t species)
{
  if (!e || i >= e->n || species >= e->nspec)
    return sbi_error(SB_EINVAL, __func__,
                     "bad engine, particle %zu or species %zu", i, species);
  e->species[i] = species;
  e->radius[i] = e->spec[species].radius;
  e->mass[i] = e->spec[species].mass;
  return SB_SUCCESS;
}

/* ============================================================ context */


void sb_agglo_params_default(sb_agglo_params *p)
{
  if (!p) {
    sbi_error(SB_EINVAL, __func__, "params is NULL");
    return;
  }
  memset(p, 0, sizeof *p);
  p->primary = 0;
  p->growth = SB_AGGLO_STOKES;
  p->rule = SB_AGGLO_MERGE;
  p->wmax = 0.0;
  p->erel = SB_AGGLO_EREL_CONTACT;
  p->kmax = (size_t)1 << 20;
  p->kobs = 10;
}

sb_agglo *sb_agglo_alloc(const sb_agglo_params *p)
{
  if (!p) {
    sbi_error(SB_EINVAL, __func__, "params is NULL");
    return NULL;
  }
  if ((unsigned)p->growth > SB_AGGLO_CUSTOM ||
      (p->growth == SB_AGGLO_CUSTOM && !p->species_fn)) {
    sbi_error(SB_EINVAL, __func__, "growth = %d: unknown, or custom without "
              "species_fn", (int)p->growth);
    return NULL;
  }
  if ((unsigned)p->rule > SB_AGGLO_DLVO ||
      (unsigned)p->erel > SB_AGGLO_EREL_STATIONARY) {
    sbi_error(SB_EINVAL, __func__, "rule = %d or erel = %d: unknown",
              (int)p->rule, (int)p->erel);
    return NULL;
  }
  if (!(p->wmax >= 0.0) || !isfinite(p->wmax)) {
    sbi_error(SB_EINVAL, __func__, "wmax = %g: must be finite >= 0",
              p->wmax);
    return NULL;
  }
  if (p->kmax < 2 || p->kmax > ((size_t)1 << 40) || p->kobs > 100000) {
    sbi_error(SB_EINVAL, __func__, "kmax = %zu (2..2^40) or kobs = %zu "
              "(<= 1e5) out of range", p->kmax, p->kobs);
    return NULL;
  }
  sb_agglo *a = calloc(1, sizeof *a);
  if (!a) {
    sbi_error(SB_ENOMEM, __func__, "out of memory");
    return NULL;
  }
  a->par = *p;
  return a;
}

void sb_agglo_free(sb_agglo *a)
{
  if (!a)
    return;
  free(a->sp_of_k);
  free(a->k_of_sp);
  free(a->rows);
  free(a);
}

/* Grow an array of size_t to hold index idx, new entries = fill. */
static int grow_index(size_t **arr, size_t *cap, size_t idx, size_t fill,
                      const char *who)
{
  if (idx < *cap)
    return SB_SUCCESS;
  size_t nc = *cap ? *cap : 16;
  while (nc <= idx)
    nc *= 2;
  size_t *na = realloc(*arr, nc * sizeof *na);
  if (!na)
    return sbi_error(SB_ENOMEM, who, "out of memory");
  for (size_t k = *cap; k < nc; k++)
    na[k] = fill;
  *arr = na;
  *cap = nc;
  return SB_SUCCESS;
}

int sbi_agglo_set_map(sb_agglo *a, size_t k, size_t sp, const char *who)
{
  int st = grow_index(&a->sp_of_k, &a->ncap_k, k, SIZE_MAX, who);
  if (!st)
    st = grow_index(&a->k_of_sp, &a->ncap_sp, sp, 0, who);
  if (st)
    return st;
  a->sp_of_k[k] = sp;
  a->k_of_sp[sp] = k;
  return SB_SUCCESS;
}

int sb_agglo_attach(sb_engine *e, sb_agglo *a)
{
  if (!e || !a)
    return sbi_error(SB_EINVAL, __func__, "NULL argument");
  const size_t p = a->par.primary;
  if (p >= e->nspec)
    return sbi_error(SB_EINVAL, __func__, "primary species %zu does not "
                     "exist", p);
  if (a->restored) {  /* sb_agglo_load: the saved sizes */
    int st = sbi_agglo_check_restored(a, e);
    if (st)
      return st;
  }
  for (size_t i = 0; i < e->n; i++)
    if (e->species[i] != p && !(e->species[i] < a->ncap_sp &&
                                a->k_of_sp[e->species[i]]))
      return sbi_error(SB_EINVAL, __func__, "particle %zu has species %zu, "
                       "not a cluster species (primary %zu)", i,
                       e->species[i], p);
  a->prim = e->spec[p];
  int st = sbi_agglo_set_map(a, 1, p, __func__);
  if (st)
    return st;
  return sb_engine_set_outcome_fn(e, sb_engine_outcome_agglo, a);
}

size_t sb_agglo_size_of_species(const sb_agglo *a, size_t sp)
{
  if (!a) {
    sbi_error(SB_EINVAL, __func__, "context is NULL");
    return 0;
  }
  return sp < a->ncap_sp ? a->k_of_sp[sp] : 0;
}

/* Species properties of a cluster of k primaries (growth law). */
static int grow_species(const sb_agglo *a, size_t k, sb_engine_species *s,
                        const char *who)
{
  const sb_engine_species *p1 = &a->prim;
  const double kd = (double)k;
  *s = *p1;
  s->mass = kd * p1->mass;
  switch (a->par.growth) {
  case SB_AGGLO_CONSTANT:
    return SB_SUCCESS;
  case SB_AGGLO_STOKES:
    s->radius = p1->radius * cbrt(kd);
    if (isfinite(p1->tau)) {
      /* tau = m/(6 pi mu r) ~ k/k^(1/3); B^2 = 2 kT/(m tau) ~ k^(-5/3) */
      double k23 = cbrt(kd) * cbrt(kd);
      s->tau = p1->tau * k23;
      s->B = p1->B / sqrt(kd * k23);
    }
    return SB_SUCCESS;
  case SB_AGGLO_CUSTOM: {
    int st = a->par.species_fn(k, p1, s, a->par.species_ctx);
    if (st)
      return sbi_error(st, who, "growth callback failed for k = %zu", k);
    return SB_SUCCESS;
  }
  }
  return sbi_error(SB_EINVAL, who, "unknown growth law %d",
                   (int)a->par.growth);
}

/* sb_agglo_species_of_size for the public function who (a merge: the
 * function that merged) */
static int species_of_size(sb_agglo *a, sb_engine *e, size_t k, size_t *sp,
                           const char *who)
{
  if (!a || !e || k < 1)
    return sbi_error(SB_EINVAL, who, "NULL argument or k = 0");
  if (k > a->par.kmax)
    return sbi_error(SB_EINVAL, who, "cluster size %zu exceeds kmax = "
                     "%zu", k, a->par.kmax);
  if (a->ncap_k == 0)
    return sbi_error(SB_EINVAL, who, "context not attached");
  if (k < a->ncap_k && a->sp_of_k[k] != SIZE_MAX) {
    if (sp)
      *sp = a->sp_of_k[k];
    return SB_SUCCESS;
  }
  sb_engine_species s;
  int st = grow_species(a, k, &s, who);
  if (st)
    return st;
  size_t idx;
  st = sb_engine_add_species(e, &s, &idx);
  if (st)
    return sbi_error(st, who, "species of clusters of size %zu: %s", k,
                     sb_last_error());
  st = sbi_agglo_set_map(a, k, idx, who);
  if (!st && sp)
    *sp = idx;
  return st;
}

int sb_agglo_species_of_size(sb_agglo *a, sb_engine *e, size_t k,
                             size_t *sp)
{
  return species_of_size(a, e, k, sp, __func__);
}

int sb_agglo_get_stats(const sb_agglo *a, sb_agglo_stats *st)
{
  if (!a || !st)
    return sbi_error(SB_EINVAL, __func__, "NULL argument");
  *st = a->st;
  return SB_SUCCESS;
}

void sb_agglo_reset_stats(sb_agglo *a)
{
  if (!a) {
    sbi_error(SB_EINVAL, __func__, "context is NULL");
    return;
  }
  memset(&a->st, 0, sizeof a->st);
}

/* ============================================================ merge */

static size_t size_of(const sb_agglo *a, const sb_engine *e, size_t i)
{
  size_t sp = e->species[i];
  return sp < a->ncap_sp ? a->k_of_sp[sp] : 0;
}

/* sb_agglo_merge for the public function who (the outcome, or a direct
 * call) */
static int agglo_merge(sb_engine *e, sb_agglo *a, const sb_engine_pair *p,
                       double s, const char *who)
{
  /* the end of step: barycentre of the ends (see the file comment) */
  if (!e || !a || !p || p->i >= e->n || p->j >= e->n || p->i == p->j)
    return sbi_error(SB_EINVAL, who, "bad argument");
  const size_t i = p->i, j = p->j;
  const size_t ki = size_of(a, e, i), kj = size_of(a, e, j);
  if (!ki || !kj)
    return sbi_error(SB_EINVAL, who, "particle %zu or %zu is not a "
                     "cluster of this context", i, j);
  size_t sp;
  int st = species_of_size(a, e, ki + kj, &sp, who);
  if (st)
    return st;
  const double mi = e->mass[i], mj = e->mass[j], M = mi + mj;
  const double fi = mi / M, fj = mj / M;
  const double du = sbi_engine_pair_du(e, p);  /* j's image, along x */
  /* the cluster is at the barycentre of the contact positions at the
   * contact time (x_j = x_i - (dx0 + s dd) there), so the engine can
   * examine its pairs over the rest of the step from that place */
  double xi[3], bc[3] = {0, 0, 0};
  /* outside a step there is no path to examine: the merge is at the
   * current positions (nothing to declare) */
  if (e->in_step &&
      sb_engine_position_at(e, i, p->t0 + s * p->dt, xi) == SB_SUCCESS) {
    for (int k = 0; k < e->par.dim; k++)
      bc[k] = xi[k] - fj * (p->dx0[k] + s * p->dd[k]);
    sb_engine_outcome_path(e, i, bc);
  }
  for (int k = 0; k < e->par.dim; k++) {
    /* x_j next to x_i: x_i - x_j = dx0 + dd (unwrapped chords); with the
     * Langevin detector both are at contact (the engine then moves the
     * cluster by a fresh Langevin step over the rest of the step) */
    double rel = e->contact ? e->contact->crel[k] : p->dx0[k] + p->dd[k];
    double xb = e->x[3 * i + k] - fj * rel;
    e->u[3 * i + k] =
        fi * e->u[3 * i + k] + fj * (e->u[3 * j + k] + (k == 0 ? du : 0.0));
    e->disp[3 * i + k] += xb - e->x[3 * i + k];
    e->x[3 * i + k] = xb;
  }
  if (!e->in_step)  /* a step wraps at its end; outside one, now */
    sbi_engine_wrap_one(e, i);
  e->species[i] = sp;
  e->radius[i] = e->spec[sp].radius;
  e->mass[i] = e->spec[sp].mass;
  a->st.nmerge++;
  return sb_engine_remove_particle(e, j);
}

int sb_agglo_merge(sb_engine *e, sb_agglo *a, const sb_engine_pair *p,
                   double s)
{
  return agglo_merge(e, a, p, s, __func__);
}

/* ============================================================ DLVO */

double sb_agglo_erel_of(const sb_engine *e, const sb_agglo *a,
                        const sb_engine_pair *p, double s, const gsl_rng *r)
{
  if (!e || !a || !p || p->i >= e->n || p->j >= e->n ||
      !(s >= 0.0 && s <= 1.0)) {
    sbi_error(SB_EINVAL, __func__, "bad argument");
    return NAN;
  }
  const double mi = e->mass[p->i], mj = e->mass[p->j];
  const double mu = mi * mj / (mi + mj);
  if (a->par.erel == SB_AGGLO_EREL_STATIONARY) {
    if (!r) {
      sbi_error(SB_EINVAL, __func__, "stationary law needs a generator");
      return NAN;
    }
    double si = e->vsd[e->species[p->i]], sj = e->vsd[e->species[p->j]];
    double theta = mu * (si * si + sj * sj);
    if (!(theta > 0.0))
      return 0.0;  /* no velocity fluctuations: E_rel = 0 */
    const sb_dlvo_erel_law law = a->par.erel_normal
                                     ? SB_DLVO_EREL_STATIONARY_NORMAL
                                     : SB_DLVO_EREL_STATIONARY;
    /* sb_dlvo_erel_sample's own checks, so that an error names this
     * function (it cannot fail past them) */
    if (!isfinite(theta) || isnan(sb_dlvo_erel_shape(law, e->par.dim))) {
      sbi_error(SB_ERANGE, __func__, "the energy scale mu (s_i^2 + s_j^2) "
                "= %g is not finite (s_i = %g, s_j = %g m/s)", theta, si,
                sj);
      return NAN;
    }
    return sb_dlvo_erel_sample(r, theta, law, e->par.dim);
  }
  if (e->contact) {
    /* Langevin detector: the sampled velocities at contact */
    const sbi_event *c = e->contact;
    double w[3], w2 = 0.0, cn = 0.0, cc = 0.0;
    for (int k = 0; k < 3; k++) {
      /* to j's image across a Lees-Edwards boundary */
      w[k] = c->cu[0][k] - c->cu[1][k] - (k == 0 ? c->cdu : 0.0);
      w2 += w[k] * w[k];
      cn += w[k] * c->crel[k];
      cc += c->crel[k] * c->crel[k];
    }
    if (!a->par.erel_normal)
      return 0.5 * mu * w2;
    return cc > 0.0 ? 0.5 * mu * cn * cn / cc : 0.0;
  }
  /* relative chord velocity at contact (constant along a chord) */
  const double dt = p->dt;
  double w2 = 0.0, wn = 0.0, nn = 0.0;
  for (int k = 0; k < 3; k++) {
    double w = p->dd[k] / dt;
    w2 += w * w;
  }
  if (!a->par.erel_normal)
    return 0.5 * mu * w2;
  /* normal part along the line of centres at contact, n = dx0 + s dd */
  for (int k = 0; k < 3; k++) {
    double n = p->dx0[k] + s * p->dd[k];
    wn += (p->dd[k] / dt) * n;
    nn += n * n;
  }
  return nn > 0.0 ? 0.5 * mu * wn * wn / nn : 0.0;
}

int sb_engine_outcome_agglo(sb_engine *e, const sb_engine_pair *p, double s,
                            void *ctx)
{
  sb_agglo *a = ctx;
  if (!e || !p || !a)
    return sbi_error(SB_EINVAL, __func__, "NULL argument");
  if (a->par.rule == SB_AGGLO_MERGE)
    return agglo_merge(e, a, p, s, __func__);
  double E = sb_agglo_erel_of(e, a, p, s, e->rng);
  double W = a->par.wmax;
  if (a->par.wmax_fn)
    W = a->par.wmax_fn(e->radius[p->i], e->radius[p->j], a->par.wmax_ctx);
  if (!(W >= 0.0) || isnan(E))
    return sbi_error(SB_EDOM, __func__, "E_rel = %g, W_max = %g: invalid",
                     E, W);
  a->st.erel_sum += E;
  if (sb_dlvo_sticks(E, W))
    return agglo_merge(e, a, p, s, __func__);
  a->st.nrebound++;
  if (a->par.erel == SB_AGGLO_EREL_CONTACT) {
    /* a bounce changes the velocities, not the places at contact */
    double x[3];
    const double tc = p->t0 + s * p->dt;
    if (sb_engine_position_at(e, p->i, tc, x) == SB_SUCCESS)
      sb_engine_outcome_path(e, p->i, x);
    if (sb_engine_position_at(e, p->j, tc, x) == SB_SUCCESS)
      sb_engine_outcome_path(e, p->j, x);
    return sb_engine_outcome_elastic(e, p, s);
  }
  return SB_SUCCESS;  /* diffusive: the pair stays where the step put it */
}

/* ============================================================ observers */

int sb_agglo_count_sizes(const sb_agglo *a, const sb_engine *e, size_t kmax,
                         double *nk, double *tail)
{
  if (!a || !e || (kmax && !nk))
    return sbi_error(SB_EINVAL, __func__, "NULL argument");
  for (size_t k = 0; k < kmax; k++)
    nk[k] = 0.0;
  double t = 0.0;
  for (size_t i = 0; i < e->n; i++) {
    size_t k = size_of(a, e, i);
    if (!k)
      return sbi_error(SB_EINVAL, __func__, "particle %zu (species %zu) is "
                       "not a cluster", i, e->species[i]);
    if (k <= kmax)
      nk[k - 1] += 1.0;
    else
      t += 1.0;
  }
  if (tail)
    *tail = t;
  return SB_SUCCESS;
}

int sb_agglo_moments(const sb_agglo *a, const sb_engine *e, double m[3])
{
  if (!a || !e || !m)
    return sbi_error(SB_EINVAL, __func__, "NULL argument");
  double s0 = 0.0, s1 = 0.0, s2 = 0.0;  /* integers: exact below 2^53 */
  for (size_t i = 0; i < e->n; i++) {
    double k = (double)size_of(a, e, i);
    if (!(k > 0.0))
      return sbi_error(SB_EINVAL, __func__, "particle %zu is not a cluster",
                       i);
    s0 += 1.0;
    s1 += k;
    s2 += k * k;
  }
  m[0] = s0;
  m[1] = s1;
  m[2] = s2;
  return SB_SUCCESS;
}

int sb_agglo_sample(sb_agglo *a, const sb_engine *e)
{
  if (!a || !e)
    return sbi_error(SB_EINVAL, __func__, "NULL argument");
  const size_t nc = 4 + a->par.kobs;
  if (a->nrows == a->caprows) {
    size_t cap = a->caprows ? 2 * a->caprows : 64;
    double *nr = realloc(a->rows, cap * nc * sizeof *nr);
    if (!nr)
      return sbi_error(SB_ENOMEM, __func__, "out of memory");
    a->rows = nr;
    a->caprows = cap;
  }
  double *row = &a->rows[a->nrows * nc];
  row[0] = e->t;
  int st = sb_agglo_moments(a, e, &row[1]);
  if (!st)
    st = sb_agglo_count_sizes(a, e, a->par.kobs, &row[4], NULL);
  if (st)
    return st;
  a->nrows++;
  return SB_SUCCESS;
}

const double *sb_agglo_series(const sb_agglo *a, size_t *nrows,
                              size_t *ncols)
{
  if (nrows)
    *nrows = a ? a->nrows : 0;
  if (ncols)
    *ncols = a ? 4 + a->par.kobs : 0;
  if (!a) {
    sbi_error(SB_EINVAL, __func__, "context is NULL");
    return NULL;
  }
  return a->rows;
}

int sb_agglo_series_csv(const sb_agglo *a, const char *path)
{
  if (!a || !path)
    return sbi_error(SB_EINVAL, __func__, "NULL argument");
  FILE *f = fopen(path, "w");
  if (!f)
    return sbi_error(SB_EIO, __func__, "cannot open '%s'", path);
  const size_t nc = 4 + a->par.kobs;
  fprintf(f, "t,M0,M1,M2");
  for (size_t k = 1; k <= a->par.kobs; k++)
    fprintf(f, ",n%zu", k);
  fputc('\n', f);
  for (size_t r = 0; r < a->nrows; r++) {
    const double *row = &a->rows[r * nc];
    fprintf(f, "%.17g", row[0]);
    for (size_t c = 1; c < nc; c++)
      fprintf(f, ",%.17g", row[c]);
    fputc('\n', f);
  }
  if (fclose(f) != 0)
    return sbi_error(SB_EIO, __func__, "write error on '%s'", path);
  return SB_SUCCESS;
}
