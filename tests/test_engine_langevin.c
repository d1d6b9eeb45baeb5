#define _POSIX_C_SOURCE 200809L /* mkstemp */
/* test_engine_langevin.c — the engine's Langevin-bridge detector
 * (SB_DETECT_LANGEVIN, lib/engine/engine_langevin.c): names and
 * parameters, the neighbour reach against an all-pairs search, contact
 * states seen by outcomes (elastic rule, merge, DLVO E_rel), collisions
 * chained inside one step, 2-D and fluid fields, and the transition-
 * regime kernel against Gopalakrishnan & Hogan (2011), and pass-through
 * counting of every entry against the Rice flux.
 *
 * Units: unit-free, diameter 1, mass 1, k_B T = 1 (species T =
 * 1/k_B), so that Kn_D = tau sqrt(2 k_B T/m)/d = tau sqrt(2).
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <gsl/gsl_cdf.h>
#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>

#include <smolbridge/engine.h>
#include <smolbridge/kernel.h>
#include <smolbridge/langevin.h>
#include <smolbridge/stats.h>

#include "engine/engine_internal.h"
#include "engine_same.h"
#include "testutil.h"
#include "validate/cases.h"
#include "validate/firsthit.h"
#include "validate/report.h"

static sb_engine *box(int dim, double L, double dt, size_t cap,
                      unsigned long seed)
{
  sb_engine_params p;
  sb_engine_params_default(&p);
  p.dim = dim;
  p.L[0] = p.L[1] = p.L[2] = L;
  p.dt = dt;
  p.capacity = cap;
  p.seed = seed;
  p.detect = SB_DETECT_LANGEVIN;
  sb_engine *e = sb_engine_alloc(&p);
  ck_assert_ptr_nonnull(e);
  return e;
}

/* Brownian sphere of diameter 1, mass 1, k_B T = 1, relaxation time tau. */
static void add_species(sb_engine *e, double tau)
{
  sb_engine_species s = {0.5, 1.0, tau, sqrt(2.0 / tau), 1.0 / SB_BOLTZMANN};
  ck_assert_int_eq(sb_engine_add_species(e, &s, NULL), SB_SUCCESS);
}

START_TEST(test_names_params)
{
  sb_engine_detect d;
  ck_assert_int_eq(sb_engine_detect_from_name("langevin", &d), SB_SUCCESS);
  ck_assert_int_eq(d, SB_DETECT_LANGEVIN);
  ck_assert_int_ne(sb_engine_detect_from_name("custom", &d), SB_SUCCESS);
  sb_engine *e = box(3, 20.0, 1.0, 8, 1);
  sb_engine_langevin_params lp;
  sb_engine_langevin_params_default(&lp);
  ck_assert(lp.eps == 1e-6 && lp.xtol == 1e-6 && lp.tol == 1e-9);
  lp.eps = 0.0;
  ck_assert_int_eq(sb_engine_set_langevin(e, &lp), SB_EINVAL);
  lp.eps = 1e-4;
  ck_assert_int_eq(sb_engine_set_langevin(e, &lp), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_set_detect(e, SB_DETECT_BALLISTIC), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_set_detect(e, SB_DETECT_LANGEVIN), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_set_detect(e, SB_DETECT_CUSTOM), SB_EINVAL);
  ck_assert_int_eq(sb_engine_contact_state(e, NULL, NULL, NULL, NULL),
                   SB_EINVAL);
  sb_engine_free(e);
}
END_TEST

/* An error of sb_engine_langevin_stats names it (it named the langevin
 * function sb_langevin_hitter_stats); before the detector has run the
 * counters are zeros. */
START_TEST(test_stats_error_name)
{
  sb_engine *e = box(3, 20.0, 1.0, 8, 1);
  add_species(e, 1.0);
  ck_assert_ptr_nonnull(e->lh);
  sb_langevin_hit_stats st;
  ck_assert_int_eq(sb_engine_langevin_stats(e, &st), SB_SUCCESS);
  ck_assert(st.calls == 0 && st.nodes == 0 && st.pruned_mass == 0.0);
  sb_clear_error();
  ck_assert_int_eq(sb_engine_langevin_stats(e, NULL), SB_EINVAL);
  ck_assert_msg(!strncmp(sb_last_error(), "sb_engine_langevin_stats:", 25),
                "message: %s", sb_last_error());
  sb_engine_free(e);
}
END_TEST

/* Reach.  All pairs are examined (a reach of 15, cells; the detector's
 * own chord test at rho(1e-30), beyond the three reaches tested) by a
 * wrapper that records every contact and the closest distance of the
 * pair's chords; contacts whose chords stay beyond sigma + rho(tol) are
 * the ones a search with reach rho(tol) would miss.  Their number must
 * stay below the bound N steps tol (expected misses per particle and
 * step <= tol; each contact is seen from one pair), checked at tol =
 * 1e-2 and 1e-4 where it is informative, and at the default 1e-9 (zero
 * expected).
 * 400 particles, Kn_D = 0.5, dt/tau = 1 and 10, 150 steps each. */
typedef struct {
  double rho[3];
  unsigned long beyond[3], hits;
} reach_rec;

static int record_all(const sb_engine *e, const sb_engine_pair *p,
                      const gsl_rng *r, void *ctx, double *s)
{
  reach_rec *rr = ctx;
  int h = sb_engine_detect_langevin(e, p, r, NULL, s);
  if (h != 1)
    return h;
  rr->hits++;
  double dd = 0, xd = 0;
  for (int k = 0; k < 3; k++) {
    dd += p->dd[k] * p->dd[k];
    xd += p->dx0[k] * p->dd[k];
  }
  double lam = dd > 0 ? -xd / dd : 0;
  lam = lam < 0 ? 0 : (lam > 1 ? 1 : lam);
  double m2 = 0;
  for (int k = 0; k < 3; k++) {
    double v = p->dx0[k] + lam * p->dd[k];
    m2 += v * v;
  }
  for (int q = 0; q < 3; q++)
    rr->beyond[q] += sqrt(m2) > p->sigma + rr->rho[q];
  return 0;
}

START_TEST(test_reach_complete)
{
  const double tau = 0.5 / sqrt(2.0), tols[3] = {1e-2, 1e-4, 1e-9};
  for (int c = 0; c < 2; c++) {
    const double dt = c ? 10.0 * tau : tau;
    const size_t N = 400;
    sb_engine *e = box(3, c ? 70.0 : 40.0, dt, N, 11 + c);
    add_species(e, tau);
    ck_assert_int_eq(sb_engine_fill_random(e, 0, 0, N), SB_SUCCESS);
    ck_assert_int_eq(sb_engine_set_outcome(e, SB_OUTCOME_COUNT, 1.0),
                     SB_SUCCESS);
    reach_rec rr;
    memset(&rr, 0, sizeof rr);
    sb_engine_langevin_params lp;
    sb_engine_langevin_params_default(&lp);
    for (int q = 0; q < 3; q++) {
      lp.tol = tols[q];
      ck_assert_int_eq(sb_engine_set_langevin(e, &lp), SB_SUCCESS);
      rr.rho[q] = sb_engine_langevin_reach(e);
      ck_assert_msg(rr.rho[q] >= 0.0 && rr.rho[q] < 15.0, "rho %g",
                    rr.rho[q]);
    }
    ck_assert(rr.rho[0] <= rr.rho[1] && rr.rho[1] < rr.rho[2]);
    /* the detector skips the chords beyond its reach: make it examine
     * everything that can matter here */
    lp.tol = 1e-30;
    ck_assert_int_eq(sb_engine_set_langevin(e, &lp), SB_SUCCESS);
    const double rall = sb_engine_langevin_reach(e);
    ck_assert_msg(rall > 1.2 * rr.rho[2], "rho %g %g", rr.rho[2], rall);
    ck_assert_int_eq(sb_engine_set_detector(e, record_all, &rr, 15.0),
                     SB_SUCCESS);
    const int steps = 150;
    for (int s = 0; s < steps; s++)
      ck_assert_int_eq(sb_engine_step(e), SB_SUCCESS);
    ck_assert_msg(rr.hits > 100, "%lu contacts", rr.hits);
    for (int q = 0; q < 3; q++) {
      double bound = (double)N * steps * tols[q];
      ck_assert_msg((double)rr.beyond[q] <= bound + 3.0 * sqrt(bound) + 1,
                    "dt/tau %g, tol %g: %lu contacts beyond the reach %g "
                    "(bound %g)", dt / tau, tols[q], rr.beyond[q],
                    rr.rho[q], bound);
    }
    ck_assert_uint_eq(rr.beyond[2], 0);
    sb_engine_free(e);
  }
}
END_TEST

/* The detector's chord test (engine_langevin.c, beyond_reach): a record
 * at the start of the step whose relative chord stays beyond sigma + rho
 * (rho the engine's reach at the default tol) is decided without calling
 * the sampler, every other one calls it.  All pairs within 15 are
 * candidates (custom detector around sb_engine_detect_langevin); the
 * sampler's call counter shows which were examined.  400 particles,
 * Kn_D = 0.5, dt/tau = 10, 20 steps; every candidate must agree, and both
 * kinds must occur.  (That the skipped pairs hold at most tol contacts
 * per particle and step is test_reach_complete.) */
typedef struct {
  double rho;
  unsigned long skipped, examined, wrong;
} skip_rec;

static int check_skip(const sb_engine *e, const sb_engine_pair *p,
                      const gsl_rng *r, void *ctx, double *s)
{
  skip_rec *sr = ctx;
  sb_langevin_hit_stats a, b;
  ck_assert_int_eq(sb_engine_langevin_stats(e, &a), SB_SUCCESS);
  int h = sb_engine_detect_langevin(e, p, r, NULL, s);
  ck_assert_int_eq(sb_engine_langevin_stats(e, &b), SB_SUCCESS);
  const int examined = b.calls > a.calls;
  double dd = 0, xd = 0;
  for (int k = 0; k < 3; k++) {
    dd += p->dd[k] * p->dd[k];
    xd += p->dx0[k] * p->dd[k];
  }
  double lam = dd > 0 ? -xd / dd : 0;
  lam = lam < 0 ? 0 : (lam > 1 ? 1 : lam);
  double m2 = 0;
  for (int k = 0; k < 3; k++) {
    double v = p->dx0[k] + lam * p->dd[k];
    m2 += v * v;
  }
  const int within = sqrt(m2) <= p->sigma + sr->rho;
  sr->examined += examined;
  sr->skipped += !examined;
  sr->wrong += examined != within;
  if (!examined)
    ck_assert_int_eq(h, 0);
  return h < 0 ? h : 0;
}

START_TEST(test_reach_skip)
{
  const double tau = 0.5 / sqrt(2.0), dt = 10.0 * tau;
  const size_t N = 400;
  sb_engine *e = box(3, 70.0, dt, N, 21);
  add_species(e, tau);
  ck_assert_int_eq(sb_engine_fill_random(e, 0, 0, N), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_set_outcome(e, SB_OUTCOME_COUNT, 1.0),
                   SB_SUCCESS);
  skip_rec sr;
  memset(&sr, 0, sizeof sr);
  sr.rho = sb_engine_langevin_reach(e);
  ck_assert_msg(sr.rho > 0.0 && sr.rho < 15.0, "rho %g", sr.rho);
  ck_assert_int_eq(sb_engine_set_detector(e, check_skip, &sr, 15.0),
                   SB_SUCCESS);
  for (int k = 0; k < 20; k++)
    ck_assert_int_eq(sb_engine_step(e), SB_SUCCESS);
  ck_assert_msg(sr.wrong == 0 && sr.skipped > 1000 && sr.examined > 100,
                "rho %g: %lu skipped, %lu examined, %lu wrong", sr.rho,
                sr.skipped, sr.examined, sr.wrong);
  sb_engine_free(e);
}
END_TEST

/* Two particles on a collision course with almost no noise (tau = 1e4,
 * k_B T tiny through B): the elastic outcome sees both states at contact,
 * reverses the normal relative velocity there (eta = 1, equal masses:
 * the velocities are exchanged) and conserves the momentum. */
typedef struct {
  int calls;
  double before[2][3], after[2][3], sep;
} el_rec;

static int check_elastic(sb_engine *e, const sb_engine_pair *p, double s,
                         void *ctx)
{
  el_rec *er = ctx;
  double xi[3], xj[3];
  ck_assert_int_eq(sb_engine_contact_state(e, xi, er->before[0], xj,
                                           er->before[1]), SB_SUCCESS);
  double d = 0;
  for (int k = 0; k < 3; k++)
    d += (xi[k] - xj[k]) * (xi[k] - xj[k]);
  er->sep = sqrt(d);
  /* the engine shows the contact state through the accessors */
  const double *u = sb_engine_velocities(e);
  for (int k = 0; k < 3; k++)
    ck_assert(u[3 * p->i + k] == er->before[0][k]);
  int st = sb_engine_outcome_elastic(e, p, s);
  for (int k = 0; k < 3; k++) {
    er->after[0][k] = u[3 * p->i + k];
    er->after[1][k] = u[3 * p->j + k];
  }
  er->calls++;
  return st;
}

START_TEST(test_elastic_contact)
{
  sb_engine *e = box(3, 50.0, 2.0, 2, 3);
  sb_engine_species s = {0.5, 1.0, 1e4, 1e-8, 0.0};
  ck_assert_int_eq(sb_engine_add_species(e, &s, NULL), SB_SUCCESS);
  double x0[3] = {10, 10, 10}, u0[3] = {1, 0, 0};
  double x1[3] = {12, 10.2, 10}, u1[3] = {0, 0, 0};
  sb_engine_add_particle(e, 0, 0, x0, u0);
  sb_engine_add_particle(e, 0, 0, x1, u1);
  el_rec er;
  memset(&er, 0, sizeof er);
  sb_engine_set_outcome_fn(e, check_elastic, &er);
  ck_assert_int_eq(sb_engine_step(e), SB_SUCCESS);
  ck_assert_int_eq(er.calls, 1);
  ck_assert_rel(er.sep, 1.0, 1e-12);
  for (int k = 0; k < 3; k++)
    ck_assert_abs(er.after[0][k] + er.after[1][k],
                  er.before[0][k] + er.before[1][k], 1e-12);
  /* normal n along (x_i - x_j) at contact: w_n reversed */
  double n[3] = {-sqrt(1 - 0.04), -0.2, 0}, wb = 0, wa = 0;
  for (int k = 0; k < 3; k++) {
    wb += (er.before[0][k] - er.before[1][k]) * n[k];
    wa += (er.after[0][k] - er.after[1][k]) * n[k];
  }
  ck_assert(wb < 0);
  ck_assert_abs(wa, -wb, 1e-6);
  /* after the step the pair is apart and separating */
  ck_assert_uint_eq(sb_engine_check_overlaps(e, 1e-9), 0);
  sb_engine_free(e);
}
END_TEST

/* A chain inside one step (almost ballistic particles): A hits B at
 * t = 0.5, B (velocity 1 after the exchange) hits C at t = 2.0; dt = 3.
 * Both collisions happen, in order, through re-detection. */
START_TEST(test_chain)
{
  sb_engine *e = box(3, 50.0, 3.0, 3, 4);
  sb_engine_species s = {0.5, 1.0, 1e4, 1e-8, 0.0};
  ck_assert_int_eq(sb_engine_add_species(e, &s, NULL), SB_SUCCESS);
  double xa[3] = {10, 10, 10}, xb[3] = {11.5, 10, 10}, xc[3] = {13, 10, 10};
  double ua[3] = {1, 0, 0}, zero[3] = {0, 0, 0};
  sb_engine_add_particle(e, 0, 0, xa, ua);
  sb_engine_add_particle(e, 0, 0, xb, zero);
  sb_engine_add_particle(e, 0, 0, xc, zero);
  ck_assert_int_eq(sb_engine_step(e), SB_SUCCESS);
  sb_engine_stats st;
  sb_engine_get_stats(e, &st);
  ck_assert_uint_eq(st.ncoll, 2);
  ck_assert(st.redetected > 0);
  ck_assert_uint_eq(st.dropped, 0);
  const double *u = sb_engine_velocities(e);
  ck_assert_abs(u[0], 0.0, 1e-5);
  ck_assert_abs(u[3], 0.0, 1e-5);
  ck_assert_abs(u[6], 1.0, 1e-3);  /* drag: e^{-3e-4} */
  sb_engine_free(e);
}
END_TEST

/* Merge at contact: the cluster starts at the contact barycentre with the
 * contact momentum; DLVO E_rel (contact, normal) is mu v_n^2 / 2 of the
 * sampled contact velocities. */
typedef struct {
  sb_agglo *a;
  int calls;
  double erel, want;
} dl_rec;

static int check_dlvo(sb_engine *e, const sb_engine_pair *p, double s,
                      void *ctx)
{
  dl_rec *d = ctx;
  double xi[3], ui[3], xj[3], uj[3];
  ck_assert_int_eq(sb_engine_contact_state(e, xi, ui, xj, uj), SB_SUCCESS);
  double vn = 0, R = p->sigma;
  for (int k = 0; k < 3; k++)
    vn += (ui[k] - uj[k]) * (xi[k] - xj[k]) / R;
  const double *m = sb_engine_masses(e);
  double mu = m[p->i] * m[p->j] / (m[p->i] + m[p->j]);
  d->want = 0.5 * mu * vn * vn;
  d->erel = sb_agglo_erel_of(e, d->a, p, s, NULL);
  d->calls++;
  return sb_engine_outcome_agglo(e, p, s, d->a);
}

START_TEST(test_merge_dlvo_contact)
{
  sb_engine *e = box(3, 30.0, 1.0, 40, 5);
  add_species(e, 0.4);
  ck_assert_int_eq(sb_engine_fill_random(e, 0, 0, 40), SB_SUCCESS);
  sb_agglo_params ap;
  sb_agglo_params_default(&ap);
  ap.rule = SB_AGGLO_DLVO;
  ap.erel = SB_AGGLO_EREL_CONTACT;
  ap.erel_normal = 1;
  ap.wmax = 0.5;  /* k_B T / 2 */
  sb_agglo *a = sb_agglo_alloc(&ap);
  ck_assert_int_eq(sb_agglo_attach(e, a), SB_SUCCESS);
  dl_rec d = {a, 0, 0, 0};
  sb_engine_set_outcome_fn(e, check_dlvo, &d);
  double m3[3];
  for (int s = 0; s < 400 && d.calls < 20; s++) {
    ck_assert_int_eq(sb_engine_step(e), SB_SUCCESS);
    if (d.calls)
      ck_assert_rel(d.erel, d.want, 1e-12);
  }
  ck_assert(d.calls >= 5);
  sb_agglo_stats as;
  sb_agglo_get_stats(a, &as);
  ck_assert_uint_eq(as.nmerge + as.nrebound, (uint64_t)d.calls);
  ck_assert(as.nmerge > 0 && as.nrebound > 0);
  sb_agglo_moments(a, e, m3);
  ck_assert(m3[1] == 40.0);  /* primaries conserved */
  ck_assert(m3[0] == 40.0 - (double)as.nmerge);
  sb_agglo_free(a);
  sb_engine_free(e);
}
END_TEST

/* Merge momentum: two nearly ballistic particles meet; the cluster's
 * velocity after the step is the contact momentum over the total mass
 * (the fresh step of a tau = 1e4 cluster barely changes it). */
START_TEST(test_merge_momentum)
{
  sb_engine *e = box(3, 50.0, 2.0, 2, 6);
  sb_engine_species s = {0.5, 1.0, 1e4, 1e-8, 0.0};
  ck_assert_int_eq(sb_engine_add_species(e, &s, NULL), SB_SUCCESS);
  double x0[3] = {10, 10, 10}, u0[3] = {1, 0.5, 0};
  double x1[3] = {12, 10, 10}, u1[3] = {-1, 0, 0};
  sb_engine_add_particle(e, 0, 0, x0, u0);
  sb_engine_add_particle(e, 0, 0, x1, u1);
  sb_agglo_params ap;
  sb_agglo_params_default(&ap);
  ap.growth = SB_AGGLO_CONSTANT;
  sb_agglo *a = sb_agglo_alloc(&ap);
  ck_assert_int_eq(sb_agglo_attach(e, a), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_step(e), SB_SUCCESS);
  ck_assert_uint_eq(sb_engine_count(e), 1);
  const double *u = sb_engine_velocities(e), *x = sb_engine_positions(e);
  /* drag over the rest of the step: a factor e^{-1.5e-4} */
  ck_assert_abs(u[0], 0.0, 1e-5);
  ck_assert_abs(u[1], 0.25, 1e-4);
  /* the barycentre moves at the centre-of-mass velocity (0, 0.25)
   * before and after the contact: at t = 2 it is at (11, 10.5) */
  ck_assert_abs(x[0], 11.0, 1e-4);
  ck_assert_abs(x[1], 10.5, 1e-3);
  sb_agglo_free(a);
  sb_engine_free(e);
}
END_TEST

/* A dense elastic suspension in 3-D with shear and in 2-D at rest
 * (area fraction 0.25, dt = 2 tau_p): steps run, the detector works
 * (contacts, no drops) and overlaps at step ends stay rare: below 0.5% of
 * the contacts (each pair's interior path is drawn on its own, so a
 * contact state with one partner can overlap a third particle; measured
 * ~0.1% here). */
START_TEST(test_dense_runs)
{
  for (int dim = 2; dim <= 3; dim++) {
    const size_t N = dim == 3 ? 300 : 200;
    sb_engine *e = box(dim, 25.0, 0.7, N, 7 + dim);
    add_species(e, 0.35);
    ck_assert_int_eq(sb_engine_fill_random(e, 0, 0, N), SB_SUCCESS);
    if (dim == 3) {
      double G[3] = {0.3, 0, 0};
      sb_engine_set_fluid(e, SB_FLUID_SHEAR, G);
    }
    size_t tot = 0;
    for (int s = 0; s < 60; s++) {
      ck_assert_int_eq(sb_engine_step(e), SB_SUCCESS);
      tot += sb_engine_check_overlaps(e, 1e-3);
    }
    sb_engine_stats st;
    sb_engine_get_stats(e, &st);
    ck_assert(st.ncoll > 50);
    ck_assert_uint_eq(st.dropped, 0);
    ck_assert_msg((double)tot <= 0.005 * (double)st.ncoll, "dim %d: %zu "
                  "overlaps at step ends, %llu contacts", dim, tot,
                  (unsigned long long)st.ncoll);
    sb_langevin_hit_stats hs;
    ck_assert_int_eq(sb_engine_langevin_stats(e, &hs), SB_SUCCESS);
    ck_assert(hs.calls > 0 && hs.pruned_mass <= 1e-6 * (double)hs.calls);
    sb_engine_free(e);
  }
}
END_TEST

/* The keyed engine of the two tests below: 1500 spheres (tau = 0.35,
 * dt = 0.7), 15 steps, outcome `out`, in 2-D or 3-D, in the Lees-Edwards
 * shear or not, on `threads` threads, re-sorted in memory every `sort`
 * steps; the final states by id (v), the stats and the sampler's. */
typedef struct {
  uint64_t id;
  double x[3], u[3];
} id_state;

static int by_id(const void *a, const void *b)
{
  const uint64_t p = ((const id_state *)a)->id, q = ((const id_state *)b)->id;
  return (p > q) - (p < q);
}

static void keyed_run(int dim, sb_engine_outcome out, int shear, int threads,
                      int sort, id_state *v, sb_engine_stats *st,
                      sb_langevin_hit_stats *hs)
{
  const size_t N = 1500;
  sb_engine_params p;
  sb_engine_params_default(&p);
  p.dim = dim;
  p.L[0] = p.L[1] = p.L[2] = dim == 3 ? 30.0 : 120.0;
  p.dt = 0.7;
  p.capacity = N;
  p.seed = 31;
  p.detect = SB_DETECT_LANGEVIN;
  p.outcome = out;
  p.threads = threads;
  p.sort_every = (size_t)sort;
  ck_assert_int_eq(p.streams, 1);
  sb_engine *e = sb_engine_alloc(&p);
  ck_assert_ptr_nonnull(e);
  add_species(e, 0.35);
  if (shear) {  /* Lees-Edwards: pairs across the sliding boundary */
    const double G[3] = {0.05, 0.0, 0.0};
    ck_assert_int_eq(sb_engine_set_fluid(e, SB_FLUID_SHEAR, G), 0);
    ck_assert_int_eq(sb_engine_set_lees_edwards(e, 1), 0);
  }
  ck_assert_int_eq(sb_engine_fill_random(e, 0, 0, N), SB_SUCCESS);
  for (int k = 0; k < 15; k++)
    ck_assert_msg(sb_engine_step(e) == SB_SUCCESS, "%s", sb_last_error());
  ck_assert_uint_eq(sb_engine_count(e), N);
  const double *x = sb_engine_positions(e), *u = sb_engine_velocities(e);
  const uint64_t *id = sb_engine_ids(e);
  for (size_t k = 0; k < N; k++) {
    v[k].id = id[k];
    memcpy(v[k].x, &x[3 * k], sizeof v[k].x);
    memcpy(v[k].u, &u[3 * k], sizeof v[k].u);
  }
  qsort(v, N, sizeof *v, by_id);
  sb_engine_get_stats(e, st);
  ck_assert_int_eq(sb_engine_langevin_stats(e, hs), SB_SUCCESS);
  sb_engine_free(e);
}

/* Runs a (t = 0) and b (t = 1) of keyed_run for five set-ups (pass-
 * through count, elastic bounces with re-detections in 3-D, 2-D and the
 * shear, reinsertion) must be the same: contacts, sampler counts, and
 * every particle's state bit for bit. */
static void keyed_pairs_identical(const char *what, int threads[2],
                                  int sort[2], int same_mass)
{
  static const struct {
    int dim;
    sb_engine_outcome out;
    int shear;
  } cfg[5] = {{3, SB_OUTCOME_COUNT, 0}, {3, SB_OUTCOME_ELASTIC, 0},
              {2, SB_OUTCOME_ELASTIC, 0}, {3, SB_OUTCOME_ELASTIC, 1},
              {3, SB_OUTCOME_REINSERT, 0}};
  const size_t N = 1500;
  id_state *v[2];
  for (int t = 0; t < 2; t++)
    v[t] = malloc(N * sizeof *v[t]);
  for (int c = 0; c < 5; c++) {
    sb_engine_stats st[2];
    sb_langevin_hit_stats hs[2];
    for (int t = 0; t < 2; t++)
      keyed_run(cfg[c].dim, cfg[c].out, cfg[c].shear, threads[t], sort[t],
                v[t], &st[t], &hs[t]);
    printf("%s, %d-D %s%s: %llu / %llu contacts, %llu / %llu sampler "
           "calls\n", what, cfg[c].dim,
           cfg[c].out == SB_OUTCOME_COUNT
               ? "count"
               : (cfg[c].out == SB_OUTCOME_ELASTIC ? "elastic" : "reinsert"),
           cfg[c].shear ? " in shear" : "",
           (unsigned long long)st[0].ncoll, (unsigned long long)st[1].ncoll,
           (unsigned long long)hs[0].calls, (unsigned long long)hs[1].calls);
    ck_assert(st[0].ncoll > 100);
    ck_assert_uint_eq(st[0].ncoll, st[1].ncoll);
    ck_assert_uint_eq(hs[0].calls, hs[1].calls);
    ck_assert_uint_eq(hs[0].hits, hs[1].hits);
    ck_assert_uint_eq(hs[0].nodes, hs[1].nodes);
    ck_assert_uint_eq(hs[0].pruned, hs[1].pruned);
    ck_assert_uint_eq(hs[0].leaves, hs[1].leaves);
    ck_assert_uint_eq(hs[0].depth_max, hs[1].depth_max);
    /* the pruned mass, a floating-point sum over the records, is summed
     * in record order: the same bits on any number of threads (the
     * record order follows the particles' order in memory) */
    if (same_mass)
      ck_assert_msg(memcmp(&hs[0].pruned_mass, &hs[1].pruned_mass,
                           sizeof(double)) == 0,
                    "pruned_mass %.17g / %.17g", hs[0].pruned_mass,
                    hs[1].pruned_mass);
    ck_assert(memcmp(v[0], v[1], N * sizeof *v[0]) == 0);
  }
  for (int t = 0; t < 2; t++)
    free(v[t]);
}

/* With the engine's streams on (the default) every record draws from its
 * own stream (engine_lkeyed.c), so the run does not depend on the
 * threads: keyed_run on 1 and on 2 threads (the parallel first pass:
 * several hundred records per step), the sampler's counters included,
 * its pruned mass bit for bit.  With the streams off the detector
 * draws from the engine's generator (its own test: the runs of V12). */
START_TEST(test_threads_identical)
{
  int threads[2] = {1, 2}, sort[2] = {0, 0};
  keyed_pairs_identical("threads 1 / 2", threads, sort, 1);
}
END_TEST

/* A record is built and keyed with the particle of lower id first, the
 * re-detections after an event are keyed by the event (engine_lkeyed.c)
 * and the reinsertion moves the particle of higher id, so re-sorting the
 * particles in memory leaves the run unchanged: keyed_run with
 * sort_every = 0 and 1 (the order changes every step). */
START_TEST(test_memory_order_free)
{
  int threads[2] = {1, 1}, sort[2] = {0, 1};
  keyed_pairs_identical("sort_every 0 / 1", threads, sort, 0);
}
END_TEST

/* A keyed run continued from a checkpoint is the run itself: 1500
 * spheres with elastic bounces on 2 threads, 8 steps, saved and loaded,
 * then 7 more steps of both (each record's stream depends on the step
 * and the ids, which the checkpoint keeps). */
START_TEST(test_keyed_checkpoint)
{
  char path[] = "/tmp/sb_lkeyed_ckpt_XXXXXX";
  int fd = mkstemp(path);
  ck_assert_int_ge(fd, 0);
  close(fd);
  sb_engine_params p;
  sb_engine_params_default(&p);
  p.L[0] = p.L[1] = p.L[2] = 30.0;
  p.dt = 0.7;
  p.capacity = 1500;
  p.seed = 37;
  p.detect = SB_DETECT_LANGEVIN;
  p.outcome = SB_OUTCOME_ELASTIC;
  p.threads = 2;
  sb_engine *a = sb_engine_alloc(&p);
  ck_assert_ptr_nonnull(a);
  add_species(a, 0.35);
  ck_assert_int_eq(sb_engine_fill_random(a, 0, 0, 1500), SB_SUCCESS);
  for (int k = 0; k < 8; k++)
    ck_assert_int_eq(sb_engine_step(a), SB_SUCCESS);
  ck_assert_int_eq(sb_engine_checkpoint_save(a, path), SB_SUCCESS);
  int st = -1;
  sb_engine *b = sb_engine_checkpoint_load(path, &st);
  remove(path);
  ck_assert_int_eq(st, SB_SUCCESS);
  ck_assert_ptr_nonnull(b);
  for (int k = 0; k < 7; k++) {
    ck_assert_int_eq(sb_engine_step(a), SB_SUCCESS);
    ck_assert_int_eq(sb_engine_step(b), SB_SUCCESS);
  }
  sb_engine_stats sa;
  sb_engine_get_stats(a, &sa);
  ck_assert(sa.ncoll > 100);
  sbt_assert_same_run(a, b, 0);
  sb_engine_free(a);
  sb_engine_free(b);
}
END_TEST

/* Units: the same run (seed, configuration) in unit-free and in SI-like
 * units (lengths x 1e-7 m, times x 1e-6 s) gives the same contacts: the
 * engine, the reach and the sampler are scale invariant.  300 particles,
 * dt = 30 tau_p, pass-through, 20 steps. */
static int count_contacts(double X, double T)
{
  const double tau = 0.5 / sqrt(2.0) * T, v = X / T;
  sb_engine_params p;
  sb_engine_params_default(&p);
  p.L[0] = p.L[1] = p.L[2] = 120.0 * X;
  p.dt = 30.0 * tau;
  p.capacity = 300;
  p.seed = 21;
  p.outcome = SB_OUTCOME_COUNT;
  p.detect = SB_DETECT_LANGEVIN;
  sb_engine *e = sb_engine_alloc(&p);
  ck_assert_ptr_nonnull(e);
  sb_engine_species s = {0.5 * X, 1.0, tau, sqrt(2.0 * v * v / tau),
                         v * v / SB_BOLTZMANN};
  ck_assert_int_eq(sb_engine_add_species(e, &s, NULL), SB_SUCCESS);
  gsl_rng *r = gsl_rng_alloc(gsl_rng_taus2);
  gsl_rng_set(r, 5);
  for (int i = 0; i < 300; i++) {
    double x[3], u[3];
    for (int k = 0; k < 3; k++) {
      x[k] = p.L[0] * gsl_rng_uniform(r);
      u[k] = v * gsl_ran_gaussian_ziggurat(r, 1.0);
    }
    ck_assert_int_eq(sb_engine_add_particle(e, 0, 0, x, u), SB_SUCCESS);
  }
  gsl_rng_free(r);
  for (int k = 0; k < 20; k++)
    ck_assert_int_eq(sb_engine_step(e), SB_SUCCESS);
  sb_engine_stats st;
  sb_engine_get_stats(e, &st);
  sb_engine_free(e);
  return (int)st.ncoll;
}

START_TEST(test_units)
{
  int a = count_contacts(1.0, 1.0), b = count_contacts(1e-7, 1e-6);
  ck_assert_int_gt(a, 20);
  ck_assert_int_eq(a, b);
}
END_TEST

/* A quick-mode validation context of base seed `seed` (options opt). */
static void quick_ctx(unsigned long seed, sb_validate_options *opt,
                      sbv_ctx *ctx)
{
  sb_validate_options_init(opt);
  *ctx = (sbv_ctx){0, seed, NULL, opt, NULL, NULL};
}

/* A first-hit run of N Kn_D = 0.5 spheres (d = 100 nm, 1000 kg/m^3,
 * 296.15 K) with `langevin` at dt = tau_p, warm-up w tau_p, end e tau_p,
 * in a box of 10 relative displacement sd over the run. */
static void kn05_run(size_t N, double w, double e, lv_run *q)
{
  const double T = 296.15, d = 1e-7, m = sb_sphere_mass(1000.0, d);
  const double tau = 0.5 * d / sqrt(2.0 * SB_BOLTZMANN * T / m);
  memset(q, 0, sizeof *q);
  q->nsp = 1;
  q->d[0] = d;
  q->tau[0] = tau;
  q->mass[0] = m;
  q->N[0] = N;
  q->temp = T;
  q->dt = tau;
  q->det = LV_LANGEVIN;
  q->t1 = w * tau;
  q->T = e * tau;
  const double D = 2 * SB_BOLTZMANN * T * tau / m;
  q->L = 10.0 * sqrt(2 * D * q->T);
}

/* The long-time kernel by first-hit counting (lib/validate/firsthit_lv.c)
 * at Kn_D = 0.5, dt = tau_p: ~1500 contacts, against the GH fit within
 * 10% (3.5 standard errors of the count plus the fit's few %). */
START_TEST(test_kernel_gh)
{
  sb_validate_options opt;
  sbv_ctx ctx;
  quick_ctx(77, &opt, &ctx);
  lv_run q;
  kn05_run(5000, 50.0, 250.0, &q);
  const double T = q.temp, d = q.d[0], m = q.mass[0], tau = q.tau[0];
  lv_out o;
  ck_assert_int_eq(lv_firsthit(&ctx, 1, &q, &o), SB_SUCCESS);
  double K, lo, hi;
  ck_assert_int_eq(lv_kernel(&q, &o, 0, &K, &lo, &hi), SB_SUCCESS);
  double Kgh = sb_kernel_brownian_gh(d / 2, d / 2, m, m, tau, tau, T);
  ck_assert_msg(o.hits[0] > 800, "%lu contacts", o.hits[0]);
  ck_assert_msg(fabs(K / Kgh - 1.0) < 0.10, "K/K_GH = %g [%g, %g], %lu "
                "contacts", K / Kgh, lo / Kgh, hi / Kgh, o.hits[0]);
}
END_TEST

/* Two first-hit runs compared (lv_add_compare) and pooled (lv_pool, the
 * --full V12 runs the candidate-pair cap holds below their contacts).
 * The row's ratio is the runs' own estimates'.  Pooling: counts,
 * pairs and work add up, the velocities are appended up to the cap, the
 * pooled kernel lies between the two runs' and its interval is narrower
 * than either; runs of another end time do not pool. */
START_TEST(test_compare_pool)
{
  sb_validate_options opt;
  sbv_ctx ctx;
  quick_ctx(78, &opt, &ctx);
  lv_run q;
  kn05_run(3000, 20.0, 120.0, &q);
  q.vcap = 100000;  /* every contact's velocity */
  const double tau = q.tau[0];
  lv_out o1, o2;
  ck_assert_int_eq(lv_firsthit(&ctx, 1, &q, &o1), SB_SUCCESS);
  ck_assert_int_eq(lv_firsthit(&ctx, 2, &q, &o2), SB_SUCCESS);
  ck_assert_msg(o1.hits[0] > 100 && o2.hits[0] > 100, "%lu, %lu contacts",
                o1.hits[0], o2.hits[0]);
  ck_assert(o1.nvn == o1.hits[0] && o2.nvn == o2.hits[0]);
  const size_t cap = o1.nvn + o2.nvn / 2;  /* the pool's cap */
  double K1, l1, h1, K2, l2, h2, K, lo, hi;
  ck_assert_int_eq(lv_kernel(&q, &o1, 0, &K1, &l1, &h1), SB_SUCCESS);
  ck_assert_int_eq(lv_kernel(&q, &o2, 0, &K2, &l2, &h2), SB_SUCCESS);
  ck_assert(K1 != K2);  /* other streams, other runs */
  /* the two-run row: its estimate is K1/K2 of the runs' own estimates
   * (not the count ratio at a common K, off by the transient's share),
   * its interval holds it and covers 1 exactly when p >= alpha */
  sbv_report *rep = sb_validate_report_alloc();
  ck_assert_ptr_nonnull(rep);
  ck_assert_int_eq(lv_add_compare(rep, "two runs", &q, &o1, &q, &o2, 0),
                   SB_SUCCESS);
  ck_assert_uint_eq(rep->nrecs, 1);
  const sb_comparison *c = &rep->recs[0];
  ck_assert_msg(fabs(c->estimate / (K1 / K2) - 1.0) < 1e-12, "%.15g vs %.15g",
                c->estimate, K1 / K2);
  ck_assert(c->ci_low < c->estimate && c->estimate < c->ci_high);
  ck_assert_int_eq(c->ci_low <= 1.0 && 1.0 <= c->ci_high,
                   c->p_value >= SBV_ALPHA);
  sb_validate_report_free(rep);
  const unsigned long hits = o1.hits[0] + o2.hits[0];
  const double pairs = o1.npairs[0] + o2.npairs[0], cpu = o1.cpu + o2.cpu;
  const double v0 = o2.vn[0];
  const size_t n1 = o1.nvn;
  lv_out acc = o1;
  ck_assert_int_eq(lv_pool(&acc, &o2, cap), SB_SUCCESS);
  ck_assert_ptr_null(o2.vn);
  ck_assert_uint_eq(acc.hits[0], hits);
  ck_assert(acc.npairs[0] == pairs && acc.cpu == cpu);
  ck_assert_uint_eq(acc.nvn, cap);
  ck_assert(acc.vn[n1] == v0);
  ck_assert_int_eq(lv_kernel(&q, &acc, 0, &K, &lo, &hi), SB_SUCCESS);
  ck_assert_msg(K > fmin(K1, K2) && K < fmax(K1, K2), "%g not in (%g, %g)",
                K, K1, K2);
  ck_assert(hi - lo < fmin(h1 - l1, h2 - l2));
  /* another end time: not the same run */
  lv_run q3 = q;
  q3.T = 100 * tau;
  q3.vcap = 0;
  lv_out o3;
  ck_assert_int_eq(lv_firsthit(&ctx, 3, &q3, &o3), SB_SUCCESS);
  ck_assert_int_eq(lv_pool(&acc, &o3, cap), SB_EINVAL);
  ck_assert_uint_eq(acc.hits[0], hits);
  free(acc.vn);
}
END_TEST

/* Pass-through counting counts every entry into contact, at any dt: a
 * pair that leaves contact and enters again inside a step, or that
 * overlaps at the start of a step, is followed through (the every-entry
 * walk).  Non-interacting spheres placed uniformly (overlaps allowed) at
 * their equilibrium velocities make a stationary pair process, and the
 * mean number of entries per unit time is Rice's flux through the
 * contact sphere, Abrahamson's kernel sqrt(8 pi) R^2 sqrt(2 v2) (v2 =
 * k_B T/m = 1).  2000 spheres (volume fraction 0.002), tau = 0.5
 * (Kn_D = 0.71), at dt = tau and 10 tau; 8 replicas of ~5000 entries
 * each (the count is over-dispersed: a grazing pair re-enters many
 * times): the mean of the replicas' K_e/K_abr within Student's t
 * interval at p >= 1e-3.  Counting a pair at most once per step (the
 * former rule) reads 0.946 at dt = tau: t = -6.5, caught.  */
START_TEST(test_passthrough_flux)
{
  const size_t N = 2000, nrep = 8;
  const double L = 80.0, tau = 0.5, R = 1.0;
  const double Kabr = sb_kernel_abrahamson(0.5, 0.5, 1.0, 1.0);
  ck_assert_double_eq_tol(Kabr, sqrt(8.0 * 3.14159265358979323846) * R * R * sqrt(2.0),
                          1e-12 * Kabr);
  const double dts[2] = {tau, 10.0 * tau};
  for (int q = 0; q < 2; q++) {
    double x[8];
    for (size_t k = 0; k < nrep; k++) {
      sb_engine *e = box(3, L, dts[q], N + 1, 500 + 10 * q + k);
      ck_assert_int_eq(sb_engine_set_outcome(e, SB_OUTCOME_COUNT, 1.0),
                       SB_SUCCESS);
      add_species(e, tau);
      gsl_rng *r = gsl_rng_alloc(gsl_rng_taus2);
      gsl_rng_set(r, 900 + 10 * q + k);
      for (size_t i = 0; i < N; i++) {
        double xp[3], u[3];
        for (int c = 0; c < 3; c++) {
          xp[c] = L * gsl_rng_uniform(r);
          u[c] = gsl_ran_gaussian_ziggurat(r, 1.0);
        }
        ck_assert_int_eq(sb_engine_add_particle(e, 0, 0, xp, u),
                         SB_SUCCESS);
      }
      gsl_rng_free(r);
      const size_t steps = (size_t)(180.0 / dts[q]);
      for (size_t s = 0; s < steps; s++) {
        int st = sb_engine_step(e);
        ck_assert_msg(st == SB_SUCCESS, "step %zu: %s", s, sb_last_error());
      }
      double K;
      ck_assert_int_eq(sb_engine_kernel(e, 0.95, &K, NULL, NULL),
                       SB_SUCCESS);
      x[k] = K / Kabr;
      sb_engine_free(e);
    }
    double m = 0, v = 0;
    for (size_t k = 0; k < nrep; k++)
      m += x[k] / nrep;
    for (size_t k = 0; k < nrep; k++)
      v += (x[k] - m) * (x[k] - m) / (nrep - 1);
    const double t = (m - 1.0) / sqrt(v / nrep);
    const double p = 2.0 * gsl_cdf_tdist_Q(fabs(t), nrep - 1);
    printf("pass-through flux, dt/tau = %g: K_e/K_abr = %.4f (t = %.2f, "
           "p = %.3g)\n", dts[q] / tau, m, t, p);
    ck_assert_msg(p >= 1e-3, "dt/tau = %g: K_e/K_abr = %g, t = %g",
                  dts[q] / tau, m, t);
  }
}
END_TEST

/* A noise-free Stokes sphere (B = 0, tau = 1) in the uniform flow
 * w = (1, 0, 0) starting at u = -w curves back: x(s) = x0 + w (s -
 * 2 tau (1 - e^{-s/tau})), at most 0.307 behind x0 (s = tau ln 2), and
 * ends 0.054 behind it at dt = 1.5 tau.  A sphere at rest 1.0 behind it
 * (free flight; contact distance 0.7) is touched at the s where x - x0 =
 * -0.3, found here by bisection on that closed form.  The chords stay
 * 0.946 apart, so the search finds the pair only through the path's
 * bulge (sbi_engine_det_bulge); the contact time within the leaf
 * resolution over the approach speed.  Without the bulge the pair is
 * never examined: no contact. */
/* A cube of edge L in the uniform flow (1, 0, 0), step dt, outcome out
 * (elastic: restitution 1), with species 0 a Stokes sphere without noise
 * (tau = 1) and species 1 a free-flight one, both of radius 0.35 and
 * mass 1. */
static sb_engine *flow_box(double L, double dt, sb_engine_outcome out)
{
  sb_engine *e = box(3, L, dt, 4, 5);
  const double U[3] = {1.0, 0.0, 0.0};
  ck_assert_int_eq(sb_engine_set_fluid(e, SB_FLUID_UNIFORM, U), 0);
  ck_assert_int_eq(sb_engine_set_outcome(e, out, 1.0), 0);
  const sb_engine_species stokes = {0.35, 1.0, 1.0, 0.0, 0.0};
  const sb_engine_species flight = {0.35, 1.0, INFINITY, 0.0, 1.0};
  ck_assert_int_eq(sb_engine_add_species(e, &stokes, NULL), 0);
  ck_assert_int_eq(sb_engine_add_species(e, &flight, NULL), 0);
  return e;
}

static double back_path(double s)
{
  return s - 2.0 * (1.0 - exp(-s));
}

/* A custom detector: the Langevin contact, its step fraction kept. */
static int record_contact(const sb_engine *e, const sb_engine_pair *p,
                          const gsl_rng *r, void *ctx, double *s)
{
  const int h = sb_engine_langevin_contact(e, p, r, s, NULL);
  if (h == 1)
    *(double *)ctx = *s;
  return h;
}

START_TEST(test_curved_no_noise)
{
  double lo = 0.0, hi = log(2.0);  /* back_path decreases on [0, ln 2] */
  for (int it = 0; it < 80; it++) {
    const double m = 0.5 * (lo + hi);
    if (back_path(m) > -0.3)
      lo = m;
    else
      hi = m;
  }
  for (int custom = 0; custom < 2; custom++) {
    sb_engine *e = flow_box(10.0, 1.5, SB_OUTCOME_COUNT);
    const double xa[3] = {5.0, 5.0, 5.0}, ua[3] = {-1.0, 0.0, 0.0};
    const double xb[3] = {4.0, 5.0, 5.0}, ub[3] = {0.0, 0.0, 0.0};
    ck_assert_int_eq(sb_engine_add_particle(e, 0, 0, xa, ua), 0);
    ck_assert_int_eq(sb_engine_add_particle(e, 1, 0, xb, ub), 0);
    double st_s = NAN;
    if (custom)
      ck_assert_int_eq(sb_engine_set_detector(e, record_contact, &st_s, 1),
                       0);
    ck_assert_msg(sb_engine_step(e) == 0, "%s", sb_last_error());
    sb_engine_stats st;
    sb_engine_get_stats(e, &st);
    ck_assert_msg(st.ncoll == 1, "%s detector: %llu contacts",
                  custom ? "custom" : "langevin",
                  (unsigned long long)st.ncoll);
    ck_assert_abs(sb_engine_positions(e)[0], 5.0 + back_path(1.5), 1e-12);
    if (custom) {
      printf("curved noise-free path: contact at %.9f tau (closed form "
             "%.9f)\n", 1.5 * st_s, hi);
      /* the leaf resolution 1e-6 R over the approach speed (0.12: near
       * the turning point), twice */
      const double vn = fabs(1.0 - 2.0 * exp(-hi));
      ck_assert_abs(1.5 * st_s, hi, 2.0 * 0.7e-6 / vn);
    }
    sb_engine_free(e);
  }
}
END_TEST

/* The same bulge on a piece that starts mid-step (the re-detection after
 * an outcome): in the flow w = (1, 0, 0), Stokes sphere A (B = 0, tau = 1)
 * moves with the fluid from x = 5 and free-flight C (at 6.2, u = -2)
 * bounces off it at t = 1/6 (elastic, equal masses: velocities
 * exchanged), so A restarts at u = -2 and curves back, at most 0.90
 * behind the bounce point, ending 0.25 behind it at dt = 1/6 + 2.5.
 * Sphere B at rest at x = 3.6 is reached when A is at 4.3: its velocity
 * after their bounce is A's there, w - 3 e^{-s'} from the closed form
 * (within 1e-4).  Without the bulge on the new piece B is not among A's
 * partners: one collision. */
START_TEST(test_curved_piece)
{
  const double xb = 5.0 + 1.0 / 6.0;
  double lo = 0.0, hi = log(3.0);  /* xb + s - 3 (1 - e^-s) falls to 4.3 */
  for (int it = 0; it < 80; it++) {
    const double m = 0.5 * (lo + hi);
    if (xb + m - 3.0 * (1.0 - exp(-m)) > 4.3)
      lo = m;
    else
      hi = m;
  }
  sb_engine *e = flow_box(30.0, 1.0 / 6.0 + 2.5, SB_OUTCOME_ELASTIC);
  const double xa[3] = {5.0, 5.0, 5.0}, ua[3] = {1.0, 0.0, 0.0};
  const double xc[3] = {6.2, 5.0, 5.0}, uc[3] = {-2.0, 0.0, 0.0};
  const double xB[3] = {3.6, 5.0, 5.0}, uB[3] = {0.0, 0.0, 0.0};
  ck_assert_int_eq(sb_engine_add_particle(e, 0, 0, xa, ua), 0);
  ck_assert_int_eq(sb_engine_add_particle(e, 1, 0, xc, uc), 0);
  ck_assert_int_eq(sb_engine_add_particle(e, 1, 0, xB, uB), 0);
  ck_assert_msg(sb_engine_step(e) == 0, "%s", sb_last_error());
  sb_engine_stats st;
  sb_engine_get_stats(e, &st);
  ck_assert_msg(st.ncoll == 2, "%llu collisions",
                (unsigned long long)st.ncoll);
  const double want = 1.0 - 3.0 * exp(-hi);
  printf("curved piece: B leaves at %.7f (closed form %.7f)\n",
         sb_engine_velocities(e)[6], want);
  ck_assert_abs(sb_engine_velocities(e)[6], want, 1e-4);
  ck_assert_abs(sb_engine_velocities(e)[3], 1.0, 1e-12);  /* C: A's */
  sb_engine_free(e);
}
END_TEST

/* A drop with Schiller & Naumann's drag (B = 0; d = 100 um, tau_p =
 * 30.9 ms in air, Re_p = 13 at the start, so the drag is 1.9 times
 * Stokes') decelerates towards a sphere at rest 30 mm ahead (free flight;
 * contact distance 100 um): the Langevin detector follows the path the
 * engine moves it along, the exact linear step of its rate lam
 * (engine_force.c), x(s) = x0 + u0 (1 - e^{-lam s})/lam.  lam is read off
 * the same step without the sphere (u1 = u0 e^{-lam dt}); the contact
 * time against that closed form (the leaf resolution over the approach
 * speed).  With the Stokes path of tau_p (as before) the contact comes at
 * 20.4 ms instead of 26.7 ms. */
static sb_engine *drop_box(int with_target)
{
  sb_engine *e = box(3, 1.0, 0.05, 4, 5);
  ck_assert_int_eq(sb_engine_set_outcome(e, SB_OUTCOME_COUNT, 0.0), 0);
  const double r = 50e-6, m = 1000.0 * 4.0 / 3.0 * 3.14159265358979323846 * r * r * r;
  const double tau = 1000.0 * (2.0 * r) * (2.0 * r) / (18.0 * 1.8e-5);
  const sb_engine_species drop = {r, m, tau, 0.0, 0.0};
  const sb_engine_species rest = {r, m, INFINITY, 0.0, 300.0};
  ck_assert_int_eq(sb_engine_add_species(e, &drop, NULL), 0);
  ck_assert_int_eq(sb_engine_add_species(e, &rest, NULL), 0);
  const sb_engine_species_fluid f = {SB_DRAG_SCHILLER_NAUMANN, 1.2, 1.8e-5};
  ck_assert_int_eq(sb_engine_set_species_fluid(e, 0, &f), 0);
  const double xa[3] = {0.5, 0.5, 0.5}, ua[3] = {-2.0, 0.0, 0.0};
  const double xb[3] = {0.47, 0.5, 0.5}, ub[3] = {0.0, 0.0, 0.0};
  ck_assert_int_eq(sb_engine_add_particle(e, 0, 0, xa, ua), 0);
  if (with_target)
    ck_assert_int_eq(sb_engine_add_particle(e, 1, 0, xb, ub), 0);
  return e;
}

START_TEST(test_nonlinear_drag_path)
{
  sb_engine *a = drop_box(0);
  ck_assert_int_eq(sb_engine_step(a), SB_SUCCESS);
  const double u1 = sb_engine_velocities(a)[0];
  sb_engine_free(a);
  const double lam = log(-2.0 / u1) / 0.05;
  ck_assert(lam > 1.5 / 0.0309);  /* well above Stokes' rate */
  /* (D - R) lam / |u0| = 1 - e^{-lam s} */
  const double want = -log(1.0 - (0.03 - 100e-6) * lam / 2.0) / lam;
  sb_engine *e = drop_box(1);
  double s = NAN;
  ck_assert_int_eq(sb_engine_set_detector(e, record_contact, &s, 0.0), 0);
  ck_assert_msg(sb_engine_step(e) == SB_SUCCESS, "%s", sb_last_error());
  const double vn = 2.0 * exp(-lam * want);
  printf("Schiller-Naumann drop: contact at %.6f ms (closed form %.6f)\n",
         1e3 * 0.05 * s, 1e3 * want);
  ck_assert_abs(0.05 * s, want, 2.0 * 100e-6 * 1e-6 / vn);
  sb_engine_free(e);
}
END_TEST

static Suite *suite(void)
{
  Suite *s = suite_create("engine_langevin");
  TCase *tc = tcase_create("core");
  tcase_set_timeout(tc, 30);
  tcase_add_test(tc, test_names_params);
  tcase_add_test(tc, test_stats_error_name);
  tcase_add_test(tc, test_elastic_contact);
  tcase_add_test(tc, test_chain);
  tcase_add_test(tc, test_curved_no_noise);
  tcase_add_test(tc, test_curved_piece);
  tcase_add_test(tc, test_nonlinear_drag_path);
  tcase_add_test(tc, test_merge_momentum);
  tcase_add_test(tc, test_merge_dlvo_contact);
  suite_add_tcase(s, tc);
  TCase *tm = tcase_create("mc");
  tcase_set_timeout(tm, 60);
  tcase_add_test(tm, test_reach_complete);
  tcase_add_test(tm, test_reach_skip);
  tcase_add_test(tm, test_dense_runs);
  tcase_add_test(tm, test_threads_identical);
  tcase_add_test(tm, test_memory_order_free);
  tcase_add_test(tm, test_keyed_checkpoint);
  tcase_add_test(tm, test_kernel_gh);
  tcase_add_test(tm, test_compare_pool);
  tcase_add_test(tm, test_units);
  tcase_add_test(tm, test_passthrough_flux);
  suite_add_tcase(s, tm);
  return s;
}

int main(void) { return sbt_run_suite(suite()); }
