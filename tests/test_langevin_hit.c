/* test_langevin_hit.c — the pair first-contact sampler
 * (<smolbridge/langevin_hit.h>) against brute-force fine-step simulation
 * of the same processes, the audit of its pruning budget, deterministic
 * limits, the neighbour reach, and argument checks.
 *
 * Brute force, marginal over the ends ("forward"): both particles are
 * moved from given start states by nf exact Langevin sub-steps
 * (sb_langevin_step coefficients), a contact within a sub-step is the
 * entry root of its chord; the sampler is then called with the same two
 * end states.  If the sampler draws from the right conditional law, its
 * hit indicator and the brute force's have the same mean (paired:
 * McNemar's exact test on the discordant paths), and the hit times and
 * contact velocities the same law (two-sample KS).  The chords miss
 * excursions shorter than a sub-step; nf keeps that bias below the
 * statistical resolution (sub-steps <= 0.03 tau_p).
 *
 * Brute force, fixed ends ("bridge"): each particle's path is built by
 * nf sequential exact bridge draws (sb_langevin_bridge_sample, the state
 * at the next sub-step given the current one and the fixed end). */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <check.h>
#include <gsl/gsl_cdf.h>
#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>

#include <smolbridge/langevin.h>
#include <smolbridge/langevin_hit.h>
#include <smolbridge/langevin_shear.h>
#include <smolbridge/stats.h>

#include "langevin/langevin_hit_internal.h"
#include "sweep.h"
#include "testutil.h"

/* Chord entry fraction of ra -> rb into |r| <= R, or -1. */
static double entry(const double *ra, const double *rb, double R)
{
  double d[3], a = 0, b = 0, c = -R * R;
  for (int k = 0; k < 3; k++) {
    d[k] = rb[k] - ra[k];
    a += d[k] * d[k];
    b += ra[k] * d[k];
    c += ra[k] * ra[k];
  }
  if (c <= 0)
    return 0;
  if (b >= 0 || a == 0 || b * b - a * c < 0)
    return -1;
  double s = c / (-b + sqrt(b * b - a * c));
  return s <= 1 ? s : -1;
}

/* Chord exit fraction of ra -> rb out of |r| < R (ra inside or on the
 * sphere), or -1: the larger root. */
static double exit_root(const double *ra, const double *rb, double R)
{
  double d[3], a = 0, b = 0, c = -R * R, cb = -R * R;
  for (int k = 0; k < 3; k++) {
    d[k] = rb[k] - ra[k];
    a += d[k] * d[k];
    b += ra[k] * d[k];
    c += ra[k] * ra[k];
    cb += rb[k] * rb[k];
  }
  if (cb <= 0 || a == 0)
    return -1;
  return (-b + sqrt(b * b - a * c)) / a;
}

/* Result of one brute-force path. */
typedef struct {
  int hit;
  double t, vn;  /* contact time, normal relative velocity (< 0 in) */
  double ui, xc; /* at contact: particle i's velocity along the line of
                    centres, the barycentre's x */
} bres;

static void forward(const gsl_rng *r, sb_langevin_path *P, int dim, int nf,
                    double dt, double R, bres *o)
{
  sb_langevin_coef c[2];
  for (int p = 0; p < 2; p++)
    sb_langevin_coef_init(&c[p], P[p].tau, P[p].B, dt / nf);
  double x[2][3] = {{0}}, u[2][3] = {{0}};
  for (int p = 0; p < 2; p++)
    for (int k = 0; k < dim; k++) {
      x[p][k] = P[p].x0[k];
      u[p][k] = P[p].u0[k];
    }
  o->hit = 0;
  for (int s = 0; s < nf; s++) {
    double ra[3], rb[3];
    for (int k = 0; k < 3; k++)
      ra[k] = x[0][k] - x[1][k];
    const double xprev = 0.5 * (x[0][0] + x[1][0]);
    for (int p = 0; p < 2; p++)
      for (int k = 0; k < dim; k++) {
        double z1 = gsl_ran_gaussian_ziggurat(r, 1.0);
        double z2 = gsl_ran_gaussian_ziggurat(r, 1.0);
        double w = P[p].us[k], v = u[p][k] - w;
        x[p][k] += w * c[p].dt + v * c[p].gain + c[p].s_xu * z1 +
                   c[p].s_xc * z2;
        u[p][k] = w + v * c[p].decay + c[p].s_u * z1;
      }
    for (int k = 0; k < 3; k++)
      rb[k] = x[0][k] - x[1][k];
    double f;
    if (!o->hit && (f = entry(ra, rb, R)) >= 0) {
      o->hit = 1;
      o->t = (s + f) * dt / nf;
      double vn = 0, ui = 0;
      for (int k = 0; k < 3; k++) {
        const double nk = (ra[k] + f * (rb[k] - ra[k])) / R;
        vn += (u[0][k] - u[1][k]) * nk;
        ui += u[0][k] * nk;
      }
      o->vn = vn;
      o->ui = ui;
      /* the barycentre along the sub-step's chord (x0 before it) */
      const double xb = 0.5 * (x[0][0] + x[1][0]);
      o->xc = xb - (1.0 - f) * (xb - xprev);
    }
  }
  for (int p = 0; p < 2; p++)
    for (int k = 0; k < 3; k++) {
      P[p].x1[k] = x[p][k];
      P[p].u1[k] = u[p][k];
    }
}

static double contact_vn(const sb_langevin_contact *c, double R)
{
  double vn = 0;
  for (int k = 0; k < 3; k++)
    vn += (c->ui[k] - c->uj[k]) * (c->xi[k] - c->xj[k]) / R;
  return vn;
}

/* Particle i's velocity along the line of centres at contact. */
static double contact_ui(const sb_langevin_contact *c, double R)
{
  double v = 0;
  for (int k = 0; k < 3; k++)
    v += c->ui[k] * (c->xi[k] - c->xj[k]) / R;
  return v;
}

/* Particle with equilibrium velocity variance 1/m per component (k_B T
 * = 1): B^2 tau/2 = 1/m. */
static sb_langevin_path particle(double tau, double m)
{
  sb_langevin_path q;
  memset(&q, 0, sizeof q);
  q.tau = tau;
  q.mass = m;
  q.B = sqrt(2.0 / (m * tau));
  return q;
}

/* McNemar's exact test on the discordant counts: two-sided binomial
 * p-value of n10 among n10 + n01 at 1/2. */
static double mcnemar(long n10, long n01)
{
  long n = n10 + n01;
  if (n == 0)
    return 1.0;
  long k = n10 < n01 ? n10 : n01;
  double p = 2.0 * gsl_cdf_binomial_P((unsigned)k, 0.5, (unsigned)n);
  return p > 1.0 ? 1.0 : p;
}

/* One forward configuration: start distance x0 along x (R = 1), dt,
 * particles qi, qj (velocities drawn from equilibrium, plus drift
 * `vin` of i towards j), nf sub-steps, npath paths. */
typedef struct {
  const char *name;
  double dt, x0, vin;
  double tau_i, m_i, tau_j, m_j;
  double us_j;  /* fluid velocity seen by j along x (relative drift) */
  int dim, nf, npath;
} fcase;

static void run_forward(const fcase *fc, unsigned long seed, int check_vn)
{
  gsl_rng *r = gsl_rng_alloc(gsl_rng_taus2);
  gsl_rng_set(r, seed);
  sb_langevin_hit_params hp;
  sb_langevin_hit_params_default(&hp);
  hp.dim = fc->dim;
  sb_langevin_hitter *w = sb_langevin_hitter_alloc(&hp);
  ck_assert_ptr_nonnull(w);
  double *tb = malloc(fc->npath * sizeof *tb), *ts = malloc(fc->npath *
                                                            sizeof *ts);
  double *vb = malloc(fc->npath * sizeof *vb), *vs = malloc(fc->npath *
                                                            sizeof *vs);
  double *ub = malloc(fc->npath * sizeof *ub), *us = malloc(fc->npath *
                                                            sizeof *us);
  double *xb = malloc(fc->npath * sizeof *xb), *xs = malloc(fc->npath *
                                                            sizeof *xs);
  long nb = 0, ns = 0, n10 = 0, n01 = 0;
  for (int n = 0; n < fc->npath; n++) {
    sb_langevin_path P[2] = {particle(fc->tau_i, fc->m_i),
                             particle(fc->tau_j, fc->m_j)};
    P[0].x0[0] = fc->x0;
    P[1].us[0] = fc->us_j;
    for (int p = 0; p < 2; p++)
      for (int k = 0; k < fc->dim; k++)
        P[p].u0[k] = P[p].us[k] +
                     gsl_ran_gaussian_ziggurat(r, 1.0 / sqrt(P[p].mass));
    P[0].u0[0] -= fc->vin;
    bres b;
    forward(r, P, fc->dim, fc->nf, fc->dt, 1.0, &b);
    sb_langevin_contact c;
    int h = sb_langevin_hitter_sample(w, &P[0], &P[1], 1.0, fc->dt, r, &c);
    ck_assert_int_ge(h, 0);
    if (h) {
      ck_assert(c.t >= 0 && c.t <= fc->dt);
      double d2 = 0;
      for (int k = 0; k < 3; k++)
        d2 += (c.xi[k] - c.xj[k]) * (c.xi[k] - c.xj[k]);
      ck_assert_rel(sqrt(d2), 1.0, 1e-12);
      ts[ns] = c.t;
      us[ns] = contact_ui(&c, 1.0);
      xs[ns] = 0.5 * (c.xi[0] + c.xj[0]);
      vs[ns++] = contact_vn(&c, 1.0);
    }
    if (b.hit) {
      tb[nb] = b.t;
      ub[nb] = b.ui;
      xb[nb] = b.xc;
      vb[nb++] = b.vn;
    }
    n10 += b.hit && !h;
    n01 += !b.hit && h;
  }
  double p = mcnemar(n10, n01);
  ck_assert_msg(p >= 1e-3, "%s: brute %ld, sampler %ld hits of %d "
                "(discordant %ld / %ld): McNemar p = %g", fc->name, nb, ns,
                fc->npath, n10, n01, p);
  double D, pks;
  ck_assert_int_eq(sb_ks2_test(tb, nb, ts, ns, &D, &pks), SB_SUCCESS);
  ck_assert_msg(pks >= 1e-3, "%s: hit times KS2 D = %g, p = %g", fc->name,
                D, pks);
  if (check_vn) {
    ck_assert_int_eq(sb_ks2_test(vb, nb, vs, ns, &D, &pks), SB_SUCCESS);
    ck_assert_msg(pks >= 1e-3, "%s: normal velocity KS2 D = %g, p = %g",
                  fc->name, D, pks);
  }
  sb_langevin_hit_stats st;
  sb_langevin_hitter_stats(w, &st);
  ck_assert_uint_eq(st.calls, (uint64_t)fc->npath);
  ck_assert(st.pruned_mass / st.calls <= hp.eps);
  free(tb);
  free(ts);
  /* the states of the particles themselves, not only the relative ones
   * (the barycentre is drawn apart from the relative path for equal
   * particles) */
  ck_assert_int_eq(sb_ks2_test(ub, nb, us, ns, &D, &pks), SB_SUCCESS);
  ck_assert_msg(pks >= 1e-3, "%s: u_i along the normal KS2 D = %g, p = %g",
                fc->name, D, pks);
  ck_assert_int_eq(sb_ks2_test(xb, nb, xs, ns, &D, &pks), SB_SUCCESS);
  ck_assert_msg(pks >= 1e-3, "%s: barycentre x KS2 D = %g, p = %g",
                fc->name, D, pks);
  free(vb);
  free(vs);
  free(ub);
  free(us);
  free(xb);
  free(xs);
  sb_langevin_hitter_free(w);
  gsl_rng_free(r);
}

/* dt/tau = 0.01 and 1 (3-D, equal particles), hit probability, times and
 * normal velocity at contact; sub-steps 1e-5 and 2.4e-4 tau. */
START_TEST(test_forward_short)
{
  const fcase c1 = {"dt/tau=0.01", 0.01, 1.01, 0, 1, 1, 1, 1, 0, 3, 1024,
                    3000};
  const fcase c2 = {"dt/tau=1", 1.0, 1.5, 0, 1, 1, 1, 1, 0, 3, 4096, 3000};
  run_forward(&c1, 101, 1);
  run_forward(&c2, 102, 1);
}
END_TEST

/* Unequal particles (tau 1 and 4, masses 1 and 8), a relative fluid
 * drift, and 2-D; dt/tau_i = 1. */
START_TEST(test_forward_mixed)
{
  const fcase c3 = {"unequal", 1.0, 1.5, 0, 1, 1, 4, 8, 0, 3, 2048, 3000};
  const fcase c4 = {"drift", 1.0, 2.0, 0, 1, 1, 1, 1, -1.0, 3, 2048, 3000};
  const fcase c5 = {"2-D", 1.0, 1.5, 0, 1, 1, 1, 1, 0, 2, 2048, 3000};
  run_forward(&c3, 103, 1);
  run_forward(&c4, 104, 0);
  run_forward(&c5, 105, 0);
}
END_TEST

/* Long steps: dt/tau = 100 and 1000 (diffusive), sub-steps 0.024 and
 * 0.03 tau. */
START_TEST(test_forward_long)
{
  const fcase c6 = {"dt/tau=100", 100.0, 2.0, 0, 1, 1, 1, 1, 0, 3, 4096,
                    1500};
  const fcase c7 = {"dt/tau=1000", 1000.0, 2.0, 0, 1, 1, 1, 1, 0, 3, 32768,
                    600};
  run_forward(&c6, 106, 0);
  run_forward(&c7, 107, 0);
}
END_TEST

/* Contact states that involve each particle, not only the relative
 * motion: particle 0's velocity along the line of centres and the
 * barycentre's x (for equal particles the sampler draws the barycentre
 * apart from the relative path). */
static void cs_of(const double x[2][3], const double u[2][3], double R,
                  double cs[2])
{
  cs[0] = 0.0;
  for (int k = 0; k < 3; k++)
    cs[0] += u[0][k] * (x[0][k] - x[1][k]) / R;
  cs[1] = 0.5 * (x[0][0] + x[1][0]);
}

/* cs_of at fraction f of a sub-step from (xp, up) to (x, u), the states
 * interpolated linearly along it. */
static void cs_at(const double xp[2][3], const double up[2][3],
                  const double x[2][3], const double u[2][3], double f,
                  double R, double cs[2])
{
  double xa[2][3], ua[2][3];
  for (int p = 0; p < 2; p++)
    for (int k = 0; k < 3; k++) {
      xa[p][k] = xp[p][k] + f * (x[p][k] - xp[p][k]);
      ua[p][k] = up[p][k] + f * (u[p][k] - up[p][k]);
    }
  cs_of(xa, ua, R, cs);
}

/* The sampler's one-pass bridge coefficients (sbi_lh_bridge_coef)
 * against sb_langevin_bridge_moments at unit end states (the definition
 * of each coefficient), over h/tau = 1e-9 to 1e4 and s/h = 0.001 to 0.999,
 * for three tau: agreement to 1e-14 of each coefficient's scale (x
 * coefficients min(h, tau), velocity ones 1, covariances their own), and
 * 1e-11 for the fluid velocity's wx, which cancels (s - ax h - bx - cx) as
 * it does in the moments.  Both wx and wu vanish: a constant fluid
 * velocity acts on the bridge through its end states only. */
START_TEST(test_bridge_coef)
{
  const double taus[3] = {1.0, 3e-7, 2.5e3};
  for (int it = 0; it < 3; it++)
    for (double lh = -9.0; lh <= 4.01; lh += 0.5)
      for (double f = 0.001; f < 1.0; f *= 1.7) {
        const double tau = taus[it], B = 0.37 / sqrt(tau);
        const double h = tau * pow(10.0, lh), s = f * h;
        sb_langevin p = {tau, B, 0.0};
        sb_langevin_mom m;
        double o[11];
        ck_assert_int_eq(sb_langevin_bridge_moments(&p, h, s, 0, 0, 1, 0, &m),
                         SB_SUCCESS);
        o[0] = m.mean_x, o[4] = m.mean_u;
        o[8] = m.var_x, o[9] = m.var_u, o[10] = m.cov_xu;
        sb_langevin_bridge_moments(&p, h, s, 0, 1, 0, 0, &m);
        o[1] = m.mean_x, o[5] = m.mean_u;
        sb_langevin_bridge_moments(&p, h, s, 0, 0, 0, 1, &m);
        o[2] = m.mean_x, o[6] = m.mean_u;
        p.us = 1.0;
        sb_langevin_bridge_moments(&p, h, s, 0, 0, 0, 0, &m);
        o[3] = m.mean_x, o[7] = m.mean_u;
        sbi_lh_coef c;
        ck_assert_int_eq(sbi_lh_bridge_coef(tau, B, h, s, &c), SB_SUCCESS);
        const double n[11] = {c.ax, c.bx, c.cx, c.wx, c.au, c.bu,
                              c.cu, c.wu, c.vx, c.vu, c.cxu};
        const double mh = fmin(h, tau);
        const double sc[11] = {1, mh, mh, mh, 1 / mh, 1, 1, 1, o[8], o[9],
                               sqrt(o[8] * o[9])};
        for (int k = 0; k < 11; k++)
          ck_assert_msg(fabs(n[k] - o[k]) <= (k == 3 ? 1e-11 : 1e-14) * sc[k],
                        "coefficient %d at tau %g, h/tau %g, s/h %g: %.17g "
                        "against %.17g", k, tau, h / tau, f, n[k], o[k]);
        ck_assert(fabs(c.wx) <= 1e-11 * mh && fabs(c.wu) <= 1e-14);
      }
  sbi_lh_coef c;
  ck_assert_int_eq(sbi_lh_bridge_coef(1.0, 1.0, 1.0, 0.0, &c), SB_EDOM);
  ck_assert_int_eq(sbi_lh_bridge_coef(1.0, 0.0, 1.0, 0.5, &c), SB_EDOM);
  ck_assert_int_eq(sbi_lh_bridge_coef(INFINITY, 1.0, 1.0, 0.5, &c), SB_EDOM);
}
END_TEST

/* Fixed ends: brute force by sequential bridge draws.  n NULL: the
 * pair's contact |x_0 - x_1| <= R (exitm: the first exit, |x_0 - x_1| >=
 * R from inside); else particle 0 alone against the half-space n.x <= R
 * (n a unit vector; P[1] unused). */
static int bridge_brute(const gsl_rng *r, const sb_langevin_path *P, int nf,
                        double dt, double R, const double *n, int exitm,
                        double *t, double *cs)
{
  double x[2][3], u[2][3];
  for (int p = 0; p < 2; p++)
    for (int k = 0; k < 3; k++) {
      x[p][k] = P[p].x0[k];
      u[p][k] = P[p].u0[k];
    }
  const double h = dt / nf;
  for (int s = 0; s < nf; s++) {
    double ra[3], rb[3], rem = dt - s * h, xp[2][3], up[2][3];
    memcpy(xp, x, sizeof xp);
    memcpy(up, u, sizeof up);
    for (int k = 0; k < 3; k++)
      ra[k] = x[0][k] - (n ? 0.0 : x[1][k]);
    for (int p = 0; p < (n ? 1 : 2); p++) {
      for (int k = 0; k < 3; k++) {
        sb_langevin lp = {P[p].tau, P[p].B, P[p].us[k]};
        double xn = P[p].x1[k], un = P[p].u1[k];
        if (s < nf - 1)
          sb_langevin_bridge_sample(&lp, rem, h, x[p][k], u[p][k],
                                    P[p].x1[k], P[p].u1[k], r, &xn, &un);
        x[p][k] = xn;
        u[p][k] = un;
      }
    }
    for (int k = 0; k < 3; k++)
      rb[k] = x[0][k] - (n ? 0.0 : x[1][k]);
    double f = exitm ? exit_root(ra, rb, R) : entry(ra, rb, R);
    if (n) {  /* linear entry into the half-space */
      double pa = ra[0] * n[0] + ra[1] * n[1] + ra[2] * n[2] - R;
      double pb = rb[0] * n[0] + rb[1] * n[1] + rb[2] * n[2] - R;
      f = pa <= 0 ? 0 : (pb <= 0 ? pa / (pa - pb) : -1);
    }
    if (f >= 0) {
      *t = (s + f) * h;
      if (cs)
        cs_at(xp, up, x, u, f, R, cs);
      return 1;
    }
  }
  return 0;
}

/* Brute force (hb hits of nb, times tb) and sampler (hs of ns, times
 * ts) agree: two-sample binomial |z| <= 3.5 on the hit probability (which
 * must be away from 0 and 1) and KS2 of the hit times (p >= 1e-3); frees
 * both arrays. */
static void same_law(int cfg, double *tb, long hb, int nb, double *ts,
                     long hs, int ns)
{
  double pb = (double)hb / nb, ps = (double)hs / ns;
  double pp = (double)(hb + hs) / (nb + ns);
  double z = (pb - ps) / sqrt(pp * (1 - pp) * (1.0 / nb + 1.0 / ns));
  ck_assert_msg(fabs(z) <= 3.5, "config %d: brute %g, sampler %g, z = %g",
                cfg, pb, ps, z);
  ck_assert_msg(pb > 0.05 && pb < 0.95, "config %d: p = %g (choose a "
                "configuration with both outcomes)", cfg, pb);
  double D, p;
  ck_assert_int_eq(sb_ks2_test(tb, hb, ts, hs, &D, &p), SB_SUCCESS);
  ck_assert_msg(p >= 1e-3, "config %d: KS2 D = %g, p = %g", cfg, D, p);
  free(tb);
  free(ts);
}

/* ns sampler draws for the pair P over [0, 1] (R = 1): the hit times
 * into ts and the contact states (cs_of) into cv; returns the hits
 * (exitm: the exits, sb_langevin_hitter_sample_exit). */
static long sampler_draws(sb_langevin_hitter *w, const sb_langevin_path *P,
                          int exitm, int ns, const gsl_rng *r, double *ts,
                          double (*cv)[2])
{
  long hs = 0;
  for (int n = 0; n < ns; n++) {
    sb_langevin_contact c;
    int h = exitm ? sb_langevin_hitter_sample_exit(w, &P[0], &P[1], 1.0,
                                                   1.0, r, &c)
                  : sb_langevin_hitter_sample(w, &P[0], &P[1], 1.0, 1.0,
                                              r, &c);
    ck_assert_int_ge(h, 0);
    if (h) {
      const double x[2][3] = {{c.xi[0], c.xi[1], c.xi[2]},
                              {c.xj[0], c.xj[1], c.xj[2]}};
      const double u[2][3] = {{c.ui[0], c.ui[1], c.ui[2]},
                              {c.uj[0], c.uj[1], c.uj[2]}};
      cs_of(x, u, 1.0, cv[hs]);
      ts[hs++] = c.t;
    }
  }
  return hs;
}

/* The contact states of the brute force (cb, hb) and of the sampler
 * (cv, hs) agree, one quantity at a time: KS2 p >= 1e-3; frees both. */
static void same_contact_states(int cfg, double (*cb)[2], long hb,
                                double (*cv)[2], long hs)
{
  for (int q = 0; q < 2; q++) {
    double *a = malloc(hb * sizeof *a), *b = malloc(hs * sizeof *b), D, p;
    for (long k = 0; k < hb; k++)
      a[k] = cb[k][q];
    for (long k = 0; k < hs; k++)
      b[k] = cv[k][q];
    ck_assert_int_eq(sb_ks2_test(a, hb, b, hs, &D, &p), SB_SUCCESS);
    ck_assert_msg(p >= 1e-3, "config %d: %s at contact KS2 D = %g, p = %g",
                  cfg, q ? "barycentre x" : "u_i along the normal", D, p);
    free(a);
    free(b);
  }
  free(cb);
  free(cv);
}

/* Fixed-end draws of the pair P (R = 1, dt = 1): nb brute-force paths of
 * 256 bridge sub-steps and ns sampler calls, first contacts or (exitm)
 * first exits: the times and the states there (cs_of). */
typedef struct {
  int nb, ns;
  long hb, hs;
  double *tb, *ts;
  double (*cb)[2], (*cv)[2];
} fixed_draws;

static void fixed_draws_run(fixed_draws *d, const sb_langevin_path *P,
                            int exitm, int nb, int ns, const gsl_rng *r,
                            sb_langevin_hitter *w)
{
  d->nb = nb;
  d->ns = ns;
  d->tb = malloc(nb * sizeof *d->tb);
  d->ts = malloc(ns * sizeof *d->ts);
  d->cb = malloc(nb * sizeof *d->cb);
  d->cv = malloc(ns * sizeof *d->cv);
  ck_assert(d->tb && d->ts && d->cb && d->cv);
  d->hb = 0;
  for (int n = 0; n < nb; n++)
    d->hb += bridge_brute(r, P, 256, 1.0, 1.0, NULL, exitm, &d->tb[d->hb],
                          d->cb[d->hb]);
  d->hs = sampler_draws(w, P, exitm, ns, r, d->ts, d->cv);
}

/* Three end configurations at dt/tau = 1 (R = 1): the chord passing the
 * sphere at 1.05 (grazing), a chord passing at 1.2 with transverse
 * velocities towards the sphere at the start and away at the end (the
 * mean path bends inwards), and unequal particles.  1000
 * brute-force paths of 256 bridge sub-steps, 6000 sampler draws:
 * two-sample binomial z-test |z| <= 3.5 and KS2 on the hit times
 * (p >= 1e-3). */
START_TEST(test_fixed_ends)
{
  gsl_rng *r = gsl_rng_alloc(gsl_rng_taus2);
  gsl_rng_set(r, 201);
  sb_langevin_hitter *w = sb_langevin_hitter_alloc(NULL);
  for (int cfg = 0; cfg < 3; cfg++) {
    sb_langevin_path P[2] = {particle(1, 1), particle(cfg == 2 ? 3 : 1,
                                                      cfg == 2 ? 5 : 1)};
    if (cfg == 0) {
      double a[3] = {1.05, 1.2, 0}, b[3] = {1.05, -1.2, 0};
      memcpy(P[0].x0, a, sizeof a);
      memcpy(P[0].x1, b, sizeof b);
      P[0].u0[1] = P[0].u1[1] = -1.5;
    } else if (cfg == 1) {
      double a[3] = {1.6, 1.2, 0}, b[3] = {-1.6, 1.2, 0};
      memcpy(P[0].x0, a, sizeof a);
      memcpy(P[0].x1, b, sizeof b);
      P[0].u0[0] = P[0].u1[0] = -3.2;
      P[0].u0[1] = -0.5;
      P[0].u1[1] = 0.5;
    } else {
      double a[3] = {1.2, 0.4, 0.1}, b[3] = {0.1, 1.25, -0.3};
      memcpy(P[0].x0, a, sizeof a);
      memcpy(P[0].x1, b, sizeof b);
      P[1].u1[2] = 0.5;
    }
    fixed_draws d;
    fixed_draws_run(&d, P, 0, 1000, 6000, r, w);
    same_contact_states(cfg, d.cb, d.hb, d.cv, d.hs);
    same_law(cfg, d.tb, d.hb, d.nb, d.ts, d.hs, d.ns);
  }
  sb_langevin_hitter_free(w);
  gsl_rng_free(r);
}
END_TEST

/* First exit (sb_langevin_hitter_sample_exit) against the same brute
 * force (256 sequential bridge sub-steps, the chord's exit root), at
 * dt/tau = 4 (R = 1, k_B T = 1), for four configurations: a pair that has
 * just entered (touching, relative velocity inwards; the state of a
 * contact) and ends inside near the sphere, so that it exits in ~40% of
 * the paths; a pair starting inside that ends outside (it always exits:
 * the exit time's law and the states); the first for unequal particles
 * (mixture: both particles' walk); a pair at rest at both ends, 0.6 R
 * from the centre on opposite sides, at dt/tau = 5 and m = 0.25 (exit in
 * ~48%; the chord's clearance 0.4 R lets the closed-form bound act from
 * the top level: pruning every sub-interval whose mean path is clear
 * gives no exit at all).  1000 brute-force paths, 6000 sampler draws:
 * two-sample binomial |z| <= 3.5, KS2 of the exit times and of the
 * states at the exit (p >= 1e-3); every exit at distance R. */
START_TEST(test_exit_fixed_ends)
{
  gsl_rng *r = gsl_rng_alloc(gsl_rng_taus2);
  gsl_rng_set(r, 211);
  sb_langevin_hitter *w = sb_langevin_hitter_alloc(NULL);
  for (int cfg = 0; cfg < 4; cfg++) {
    sb_langevin_path P[2] = {particle(0.25, 1),
                             particle(cfg == 2 ? 0.75 : 0.25, cfg == 2 ? 5 : 1)};
    if (cfg == 3) {
      P[0] = P[1] = particle(0.2, 0.25);
      P[0].x0[0] = 0.6;
      P[0].x1[0] = -0.6;
      P[0].x0[1] = 0.1;
      P[0].x1[1] = -0.1;
    } else if (cfg != 1) {
      const double a[3] = {0.6, 0.8, 0}, b[3] = {-0.6, 0.75, 0.1};
      memcpy(P[0].x0, a, sizeof a);
      memcpy(P[0].x1, b, sizeof b);
      P[0].u0[0] = -1.0;
      P[0].u0[1] = -0.3;
      P[0].u1[0] = -1.0;
      P[0].u1[1] = 0.3;
    } else {
      const double a[3] = {0.2, -0.3, 0.1}, b[3] = {1.3, 0.4, -0.2};
      memcpy(P[0].x0, a, sizeof a);
      memcpy(P[0].x1, b, sizeof b);
      P[0].u1[0] = 1.0;
    }
    fixed_draws d;
    fixed_draws_run(&d, P, 1, 1000, 6000, r, w);
    printf("exit fixed ends %d: brute force %ld/%d, sampler %ld/%d\n", cfg,
           d.hb, d.nb, d.hs, d.ns);
    same_contact_states(20 + cfg, d.cb, d.hb, d.cv, d.hs);
    if (cfg == 1) {  /* sure: only the law of the time */
      ck_assert_int_eq(d.hb, d.nb);
      ck_assert_int_eq(d.hs, d.ns);
      double D, p;
      ck_assert_int_eq(sb_ks2_test(d.tb, d.hb, d.ts, d.hs, &D, &p),
                       SB_SUCCESS);
      ck_assert_msg(p >= 1e-3, "exit times: KS2 D = %g, p = %g", D, p);
      free(d.tb);
      free(d.ts);
    } else
      same_law(20 + cfg, d.tb, d.hb, d.nb, d.ts, d.hs, d.ns);
  }
  /* the exit is at distance R; apart at the start: out at once */
  sb_langevin_path P[2] = {particle(1, 1), particle(1, 1)};
  const double a[3] = {0.2, -0.3, 0.1}, b[3] = {1.3, 0.4, -0.2};
  memcpy(P[0].x0, a, sizeof a);
  memcpy(P[0].x1, b, sizeof b);
  sb_langevin_contact c;
  ck_assert_int_eq(sb_langevin_hitter_sample_exit(w, &P[0], &P[1], 1.0, 1.0,
                                                  r, &c), 1);
  double d2 = 0;
  for (int k = 0; k < 3; k++)
    d2 += (c.xi[k] - c.xj[k]) * (c.xi[k] - c.xj[k]);
  ck_assert_double_eq_tol(sqrt(d2), 1.0, 1e-12);
  ck_assert_int_eq(sb_langevin_hitter_sample_exit(w, &P[0], &P[1], 0.3, 1.0,
                                                  r, &c), 1);
  ck_assert_double_eq(c.t, 0.0);
  sb_langevin_hitter_free(w);
  gsl_rng_free(r);
}
END_TEST

/* Brute force for every entry: nf sequential bridge sub-steps of the
 * pair P over [0, 1] (R = 1), an entry in a sub-step when its start is
 * outside and its chord enters (a chord enters at most once); the entry
 * times into t (up to nmax) and the contact states (cs_at) into cs.
 * Returns the number of entries. */
static int bridge_brute_all(const gsl_rng *r, const sb_langevin_path *P,
                            int nf, double *t, double (*cs)[2], int nmax)
{
  double x[2][3], u[2][3];
  for (int p = 0; p < 2; p++)
    for (int k = 0; k < 3; k++) {
      x[p][k] = P[p].x0[k];
      u[p][k] = P[p].u0[k];
    }
  const double h = 1.0 / nf;
  int n = 0;
  for (int s = 0; s < nf; s++) {
    double ra[3], rb[3], xp[2][3], up[2][3], a2 = 0;
    memcpy(xp, x, sizeof xp);
    memcpy(up, u, sizeof up);
    for (int k = 0; k < 3; k++) {
      ra[k] = x[0][k] - x[1][k];
      a2 += ra[k] * ra[k];
    }
    for (int p = 0; p < 2; p++)
      for (int k = 0; k < 3; k++) {
        sb_langevin lp = {P[p].tau, P[p].B, P[p].us[k]};
        double xn = P[p].x1[k], un = P[p].u1[k];
        if (s < nf - 1)
          sb_langevin_bridge_sample(&lp, 1.0 - s * h, h, x[p][k], u[p][k],
                                    P[p].x1[k], P[p].u1[k], r, &xn, &un);
        x[p][k] = xn;
        u[p][k] = un;
      }
    for (int k = 0; k < 3; k++)
      rb[k] = x[0][k] - x[1][k];
    double f = a2 > 1.0 ? entry(ra, rb, 1.0) : -1;
    if (f >= 0) {
      if (n < nmax) {
        t[n] = (s + f) * h;
        cs_at(xp, up, x, u, f, 1.0, cs[n]);
      }
      n++;
    }
  }
  return n;
}

/* A brute force of every entry of the pair P over [0, 1] (R = 1): the
 * entry times into t and the contact states into cs (up to nmax);
 * returns the number of entries. */
typedef int (*brute_all_fn)(const gsl_rng *r, const sb_langevin_path *P,
                            const void *ctx, double *t, double (*cs)[2],
                            int nmax);

/* nb brute-force paths against ns sb_langevin_hitter_sample_all calls:
 * the mean number of entries (Welch |z| <= 3.5), the numbers of calls
 * with 0, 1 and >= 2 entries (chi-square of the 2 x 3 table,
 * p >= 1e-3), KS2 of all entry times and of the contact states
 * (p >= 1e-3). */
static void all_entries_check(int cfg, const sb_langevin_path *P,
                              brute_all_fn brute, const void *ctx, int nb,
                              int ns, const gsl_rng *r,
                              sb_langevin_hitter *w)
{
  enum { NMAX = 64 };
  double *tb = malloc(nb * NMAX * sizeof *tb),
         *ts = malloc(ns * NMAX * sizeof *ts);
  double(*cb)[2] = malloc(nb * NMAX * sizeof *cb),
  (*cv)[2] = malloc(ns * NMAX * sizeof *cv);
  double hist[2][3] = {{0}}, sum[2] = {0}, sq[2] = {0};
  long hb = 0, hs = 0;
  for (int n = 0; n < nb; n++) {
    int k = brute(r, P, ctx, &tb[hb], &cb[hb], NMAX);
    ck_assert_int_le(k, NMAX);
    hb += k;
    hist[0][k < 2 ? k : 2]++;
    sum[0] += k;
    sq[0] += (double)k * k;
  }
  for (int n = 0; n < ns; n++) {
    int k = sb_langevin_hitter_sample_all(w, &P[0], &P[1], 1.0, 1.0, r);
    ck_assert_int_ge(k, 0);
    ck_assert_int_le(k, NMAX);
    const sb_langevin_contact *c = sb_langevin_hitter_entries(w);
    for (int q = 0; q < k; q++) {
      const double x[2][3] = {{c[q].xi[0], c[q].xi[1], c[q].xi[2]},
                              {c[q].xj[0], c[q].xj[1], c[q].xj[2]}};
      const double u[2][3] = {{c[q].ui[0], c[q].ui[1], c[q].ui[2]},
                              {c[q].uj[0], c[q].uj[1], c[q].uj[2]}};
      ck_assert(q == 0 || c[q].t > c[q - 1].t);
      cs_of(x, u, 1.0, cv[hs]);
      ts[hs++] = c[q].t;
    }
    hist[1][k < 2 ? k : 2]++;
    sum[1] += k;
    sq[1] += (double)k * k;
  }
  const int N[2] = {nb, ns};
  double m[2], v[2];
  for (int q = 0; q < 2; q++) {
    m[q] = sum[q] / N[q];
    v[q] = (sq[q] / N[q] - m[q] * m[q]) / (N[q] - 1);
  }
  const double z = (m[0] - m[1]) / sqrt(v[0] + v[1]);
  printf("all entries %d: brute force %.4f per path (0/1/2+: %g %g %g), "
         "sampler %.4f (%g %g %g), z = %.2f\n", cfg, m[0], hist[0][0],
         hist[0][1], hist[0][2], m[1], hist[1][0], hist[1][1], hist[1][2],
         z);
  ck_assert_msg(fabs(z) <= 3.5, "config %d: mean entries z = %g", cfg, z);
  double chi2 = 0;
  for (int c = 0; c < 3; c++) {
    const double col = hist[0][c] + hist[1][c];
    for (int q = 0; q < 2; q++) {
      const double e = col * N[q] / (nb + ns);
      if (e > 0)
        chi2 += (hist[q][c] - e) * (hist[q][c] - e) / e;
    }
  }
  ck_assert_msg(gsl_cdf_chisq_Q(chi2, 2) >= 1e-3,
                "config %d: 0/1/2+ entries chi2 = %g", cfg, chi2);
  double D, p;
  ck_assert_int_eq(sb_ks2_test(tb, hb, ts, hs, &D, &p), SB_SUCCESS);
  ck_assert_msg(p >= 1e-3, "config %d: entry times KS2 D = %g, p = %g", cfg,
                D, p);
  same_contact_states(cfg, cb, hb, cv, hs);
  free(tb);
  free(ts);
}

static int brute_all_bridge(const gsl_rng *r, const sb_langevin_path *P,
                            const void *ctx, double *t, double (*cs)[2],
                            int nmax)
{
  (void)ctx;
  return bridge_brute_all(r, P, 512, t, cs, nmax);
}

/* Every entry (sb_langevin_hitter_sample_all) against that brute force
 * (512 sub-steps), m = 0.25, k_B T = 1, R = 1, dt = 1: a chord tangent
 * to the sphere at dt/tau = 5 (0, 1, 2 or more entries), the same for
 * unequal particles (mixture), and a pair that has just entered
 * (touching, relative velocity inwards: it is not entering at 0) and
 * ends inside near the sphere, at dt/tau = 4 (re-entries).  1000 brute
 * paths, 4000 sampler calls (all_entries_check). */
START_TEST(test_all_entries)
{
  gsl_rng *r = gsl_rng_alloc(gsl_rng_taus2);
  gsl_rng_set(r, 221);
  sb_langevin_hitter *w = sb_langevin_hitter_alloc(NULL);
  for (int cfg = 0; cfg < 3; cfg++) {
    sb_langevin_path P[2] = {particle(0.2, 0.25),
                             particle(cfg == 1 ? 0.6 : 0.2,
                                      cfg == 1 ? 1.25 : 0.25)};
    if (cfg < 2) {
      const double a[3] = {0.9, 1.0, 0}, b[3] = {-0.9, 1.0, 0.0};
      memcpy(P[0].x0, a, sizeof a);
      memcpy(P[0].x1, b, sizeof b);
    } else {
      P[0] = P[1] = particle(0.25, 1);
      const double a[3] = {0.6, 0.8, 0}, b[3] = {-0.6, 0.75, 0.1};
      memcpy(P[0].x0, a, sizeof a);
      memcpy(P[0].x1, b, sizeof b);
      P[0].u0[0] = -1.0;
      P[0].u0[1] = -0.3;
      P[0].u1[0] = -1.0;
      P[0].u1[1] = 0.3;
    }
    all_entries_check(30 + cfg, P, brute_all_bridge, NULL, 1000, 4000, r,
                      w);
  }
  sb_langevin_hitter_free(w);
  gsl_rng_free(r);
}
END_TEST

/* The exact shear bridge's sub-steps of one particle, the same for every
 * path: at sub-step s of nf over dt, the law of the state h = dt/nf on,
 * given the current state and the end: in-plane mean coefficients and
 * Cholesky factor (sb_langevin_shear_bridge_coefs, in units tau = B = 1:
 * velocities scale by B sqrt(tau), positions by B tau^1.5). */
typedef struct {
  int nf;
  double D[4], c[2];
  sb_langevin_shear_bridge b[256];
  double L[256][4][4];
} shear_tab;

static void shear_tab_init(const sb_langevin_path *P, int nf, double dt,
                           shear_tab *T)
{
  ck_assert(nf <= 256);
  T->nf = nf;
  if (P->B == 0.0)  /* no noise: shear_det_rk4, no table */
    return;
  const double vu = P->B * sqrt(P->tau), vx = vu * P->tau;
  T->D[0] = T->D[2] = vu;
  T->D[1] = T->D[3] = vx;
  T->c[0] = (P->us[0] - P->G * P->x0[1]) / vu; /* the drifts, scaled */
  T->c[1] = P->us[1] / vu;
  const double h = dt / nf;
  for (int s = 0; s < nf - 1; s++) {
    const double rem = dt - s * h;
    ck_assert_int_eq(sb_langevin_shear_bridge_coefs(rem / P->tau,
                                                    P->G * P->tau,
                                                    h / P->tau, &T->b[s]),
                     SB_SUCCESS);
    double(*C)[4] = T->b[s].cov, (*L)[4] = T->L[s];
    memset(L, 0, 16 * sizeof(double));
    for (int j = 0; j < 4; j++) /* Cholesky of C */
      for (int i = j; i < 4; i++) {
        double t = C[i][j];
        for (int k = 0; k < j; k++)
          t -= L[i][k] * L[j][k];
        if (i == j) {
          ck_assert(t > 0.0);
          L[j][j] = sqrt(t);
        } else
          L[i][j] = t / L[j][j];
      }
  }
}

/* Sub-step s of particle P from (x, u) (the third component from its own
 * bridge). */
static void shear_substep(const gsl_rng *r, const sb_langevin_path *P,
                          const shear_tab *T, int s, double dt, double x[3],
                          double u[3])
{
  const double *D = T->D;
  const double s0[4] = {u[1] / D[0], x[1] / D[1], u[0] / D[2], x[0] / D[3]};
  const double s1[4] = {P->u1[1] / D[0], P->x1[1] / D[1], P->u1[0] / D[2],
                        P->x1[0] / D[3]};
  const sb_langevin_shear_bridge *b = &T->b[s];
  double m[4], z[4];
  for (int i = 0; i < 4; i++) {
    m[i] = b->kc[i][0] * T->c[0] + b->kc[i][1] * T->c[1];
    for (int j = 0; j < 4; j++)
      m[i] += b->ka[i][j] * s0[j] + b->kb[i][j] * s1[j];
  }
  for (int i = 0; i < 4; i++)
    z[i] = gsl_ran_gaussian_ziggurat(r, 1.0);
  for (int i = 0; i < 4; i++)
    for (int j = 0; j <= i; j++)
      m[i] += T->L[s][i][j] * z[j];
  u[1] = D[0] * m[0], x[1] = D[1] * m[1], u[0] = D[2] * m[2],
  x[0] = D[3] * m[3];
  const double h = dt / T->nf, rem = dt - s * h;
  sb_langevin lp = {P->tau, P->B, P->us[2]};
  ck_assert_int_eq(sb_langevin_bridge_sample(&lp, rem, h, x[2], u[2],
                                             P->x1[2], P->u1[2], r, &x[2],
                                             &u[2]), SB_SUCCESS);
}

/* A Stokes particle without noise (B = 0) in the shear (G y + c_x, c_y)
 * (c from its path: us at x0), moved over h by classical Runge-Kutta on
 * du/dt = (fluid(x) - u)/tau with 32 stages (independent of the
 * library's closed-form map; error ~ (h/32 tau)^4). */
static void shear_det_rk4(const sb_langevin_path *P, double h, double x[3],
                          double u[3])
{
  const double cx = P->us[0] - P->G * P->x0[1], cy = P->us[1];
  const int n = 32;
  const double k = h / n;
  for (int s = 0; s < n; s++) {
    double y[6] = {x[0], x[1], x[2], u[0], u[1], u[2]}, d[4][6];
    for (int q = 0; q < 4; q++) {
      const double f = q == 0 ? 0.0 : (q == 3 ? 1.0 : 0.5);
      double z[6];
      for (int i = 0; i < 6; i++)
        z[i] = y[i] + (q ? f * k * d[q - 1][i] : 0.0);
      d[q][0] = z[3];
      d[q][1] = z[4];
      d[q][2] = z[5];
      d[q][3] = (P->G * z[1] + cx - z[3]) / P->tau;
      d[q][4] = (cy - z[4]) / P->tau;
      d[q][5] = (P->us[2] - z[5]) / P->tau;
    }
    for (int i = 0; i < 6; i++)
      y[i] += k / 6.0 * (d[0][i] + 2.0 * d[1][i] + 2.0 * d[2][i] + d[3][i]);
    memcpy(x, y, 3 * sizeof(double));
    memcpy(u, y + 3, 3 * sizeof(double));
  }
}

/* Brute force in a linear shear: nf sequential exact shear-bridge
 * sub-steps per particle (B = 0: shear_det_rk4), contact on the
 * sub-steps' chords: the first
 * (nmax = 0; a start inside is a contact at 0) or every entry from
 * outside (the first nmax stored); returns the number found. */
static int shear_brute(const gsl_rng *r, const sb_langevin_path *P,
                       const shear_tab *T, double dt, double R, double *t,
                       double (*cs)[2], int nmax)
{
  int n = 0;
  double x[2][3], u[2][3];
  for (int p = 0; p < 2; p++)
    for (int k = 0; k < 3; k++) {
      x[p][k] = P[p].x0[k];
      u[p][k] = P[p].u0[k];
    }
  const int nf = T[0].nf;
  const double h = dt / nf;
  for (int s = 0; s < nf; s++) {
    double ra[3], rb[3], xp[2][3], up[2][3];
    memcpy(xp, x, sizeof xp);
    memcpy(up, u, sizeof up);
    for (int k = 0; k < 3; k++)
      ra[k] = x[0][k] - x[1][k];
    for (int p = 0; p < 2; p++)
      if (P[p].B == 0.0)
        shear_det_rk4(&P[p], h, x[p], u[p]);
      else if (s < nf - 1)
        shear_substep(r, &P[p], &T[p], s, dt, x[p], u[p]);
      else
        for (int k = 0; k < 3; k++) {
          x[p][k] = P[p].x1[k];
          u[p][k] = P[p].u1[k];
        }
    for (int k = 0; k < 3; k++)
      rb[k] = x[0][k] - x[1][k];
    const double a2 = ra[0] * ra[0] + ra[1] * ra[1] + ra[2] * ra[2];
    const double f = nmax && a2 <= R * R ? -1 : entry(ra, rb, R);
    if (f >= 0) {
      if (!nmax || n < nmax) {
        t[n] = (s + f) * h;
        cs_at(xp, up, x, u, f, R, cs[n]);
      }
      n++;
      if (!nmax)
        return 1;
    }
  }
  return n;
}

/* The pair P (R = 1, dt = 1) in the shear G = 2 with drifts (cx, cy)
 * (us = (cx + G y0, cy)): 5000 brute-force paths of 128 sub-steps
 * (shear_brute) against 30 000 sampler draws, the hit probability, the
 * hit times and the contact states (same_law, same_contact_states). */
static void shear_vs_brute(int cfg, const char *what, sb_langevin_path *P,
                           double cx, double cy, shear_tab *T,
                           const gsl_rng *r, sb_langevin_hitter *w)
{
  for (int p = 0; p < 2; p++) {
    P[p].G = 2.0;
    P[p].us[0] = cx + P[p].G * P[p].x0[1];
    P[p].us[1] = cy;
    shear_tab_init(&P[p], 128, 1.0, &T[p]);
  }
  const int nb = 5000, ns = 30000;
  double *tb = malloc(nb * sizeof *tb), *ts = malloc(ns * sizeof *ts);
  double(*cb)[2] = malloc(nb * sizeof *cb), (*cv)[2] = malloc(ns *
                                                            sizeof *cv);
  long hb = 0;
  for (int n = 0; n < nb; n++)
    hb += shear_brute(r, P, T, 1.0, 1.0, &tb[hb], &cb[hb], 0);
  const long hs = sampler_draws(w, P, 0, ns, r, ts, cv);
  same_contact_states(cfg, cb, hb, cv, hs);
  printf("%s: brute force %ld/%d, sampler %ld/%d\n", what, hb, nb, hs, ns);
  same_law(cfg, tb, hb, nb, ts, hs, ns);
}

/* The sampler in a linear shear (sb_langevin_path.G) against the brute
 * force of the exact shear bridge: G dt = 2 (a strong shear), dt/tau = 1,
 * R = 1, drifts (us_x - G y0 = 0.8, us_y = -0.3); equal particles (the
 * relative walk) and unequal ones (tau 1 and 3, masses 1 and 5).  5000
 * brute-force paths of 128 sub-steps, 30 000 sampler draws: the
 * two-sample binomial z-test |z| <= 3.5, KS2 of the hit times and of
 * the contact states (particle i's velocity along the line of centres,
 * the barycentre's x) (p >= 1e-3).  Broken on purpose: the sampler with
 * the uniform-flow bridge (G ignored, as before the shear bridge) hits
 * 0.180 against the brute force's 0.152 in the first configuration,
 * z = -4.8. */
START_TEST(test_shear_fixed_ends)
{
  gsl_rng *r = gsl_rng_alloc(gsl_rng_taus2);
  gsl_rng_set(r, 303);
  sb_langevin_hitter *w = sb_langevin_hitter_alloc(NULL);
  shear_tab *T = malloc(2 * sizeof *T);
  ck_assert_ptr_nonnull(T);
  for (int cfg = 0; cfg < 2; cfg++) {
    sb_langevin_path P[2] = {particle(1, 1), particle(cfg ? 3 : 1,
                                                      cfg ? 5 : 1)};
    const double a[3] = {1.1, 1.5, 0.2}, b[3] = {1.15, -1.4, -0.1};
    memcpy(P[0].x0, a, sizeof a);
    memcpy(P[0].x1, b, sizeof b);
    P[0].u0[1] = -1.0;
    P[0].u1[1] = -0.8;
    char what[32];
    snprintf(what, sizeof what, "shear fixed ends %d", cfg);
    shear_vs_brute(10 + cfg, what, P, 0.8, -0.3, T, r, w);
  }
  free(T);
  sb_langevin_hitter_free(w);
  gsl_rng_free(r);
}
END_TEST

static int brute_all_shear(const gsl_rng *r, const sb_langevin_path *P,
                           const void *ctx, double *t, double (*cs)[2],
                           int nmax)
{
  return shear_brute(r, P, ctx, 1.0, 1.0, t, cs, nmax);
}

/* Every entry in a linear shear: sb_langevin_hitter_sample_all against
 * the brute force of the exact shear bridge (256 sub-steps), G dt = 2,
 * dt/tau = 5, m = 0.25, drifts (0.8, -0.3), the relative chord tangent
 * to the sphere; equal particles (the relative walk: each entry's
 * barycentre from its bridge after the previous one's) and unequal ones
 * (tau 0.2 and 0.6, masses 0.25 and 1.25).  1500 brute paths, 6000
 * sampler calls (all_entries_check).  With the uniform-flow bridge (G
 * ignored by the sampler) the mean number of entries of the first
 * configuration is 0.60 against the brute force's 0.86: z = 15. */
START_TEST(test_shear_all_entries)
{
  gsl_rng *r = gsl_rng_alloc(gsl_rng_taus2);
  gsl_rng_set(r, 313);
  sb_langevin_hitter *w = sb_langevin_hitter_alloc(NULL);
  shear_tab *T = malloc(2 * sizeof *T);
  ck_assert_ptr_nonnull(T);
  for (int cfg = 0; cfg < 2; cfg++) {
    sb_langevin_path P[2] = {particle(0.2, 0.25),
                             particle(cfg ? 0.6 : 0.2, cfg ? 1.25 : 0.25)};
    const double a[3] = {0.9, 1.0, 0}, b[3] = {-0.9, 1.0, 0.0};
    memcpy(P[0].x0, a, sizeof a);
    memcpy(P[0].x1, b, sizeof b);
    for (int p = 0; p < 2; p++) {
      P[p].G = 2.0;
      P[p].us[0] = 0.8 + P[p].G * P[p].x0[1];
      P[p].us[1] = -0.3;
      shear_tab_init(&P[p], 256, 1.0, &T[p]);
    }
    all_entries_check(40 + cfg, P, brute_all_shear, T, 1500, 6000, r, w);
  }
  free(T);
  sb_langevin_hitter_free(w);
  gsl_rng_free(r);
}
END_TEST

/* A Stokes particle without noise (B = 0) in a linear shear follows the
 * field along its path, G y(t) + c_x, not the field at its start.
 * (i) Against a particle at rest (free flight, u = 0): the contact time
 * and state against a Runge-Kutta integration of the equation of motion
 * (shear_det_rk4 and bisection on |r| = R): 1e-6 in time, velocity and
 * position.  (ii) Against a particle with noise in the same shear (tau 1
 * and 0.5, masses 1 and 0.25): the sampler against the brute force of 128
 * sub-steps (the noisy one's exact shear bridge, the other's Runge-Kutta
 * path), 5000 paths against 30 000 draws, the tests of
 * test_shear_fixed_ends (0.474 against 0.479).  With the uniform-flow
 * path for the particle without noise (the field frozen at its start, as
 * before), (i) finds the contact at t = 0.708 instead of 0.777 and (ii)
 * hits every time (20 000 draws) against the brute force's 0.47. */
static double det_rk4_contact(const sb_langevin_path *P, double R,
                              double x[3], double u[3])
{
  /* scan in 1/1024 steps for the first |r| <= R, then bisect */
  const int n = 1024;
  double xa[3], ua[3];
  memcpy(xa, P->x0, sizeof xa);
  memcpy(ua, P->u0, sizeof ua);
  for (int s = 0; s < n; s++) {
    double xb[3], ub[3];
    memcpy(xb, xa, sizeof xb);
    memcpy(ub, ua, sizeof ub);
    shear_det_rk4(P, 1.0 / n, xb, ub);
    if (xb[0] * xb[0] + xb[1] * xb[1] + xb[2] * xb[2] <= R * R) {
      double lo = 0.0, hi = 1.0 / n;
      for (int it = 0; it < 60; it++) {
        const double m = 0.5 * (lo + hi);
        memcpy(x, xa, 3 * sizeof(double));
        memcpy(u, ua, 3 * sizeof(double));
        shear_det_rk4(P, m, x, u);
        if (x[0] * x[0] + x[1] * x[1] + x[2] * x[2] <= R * R)
          hi = m;
        else
          lo = m;
      }
      memcpy(x, xa, 3 * sizeof(double));
      memcpy(u, ua, 3 * sizeof(double));
      shear_det_rk4(P, hi, x, u);
      return s / (double)n + hi;
    }
    memcpy(xa, xb, sizeof xa);
    memcpy(ua, ub, sizeof ua);
  }
  return -1.0;
}

START_TEST(test_shear_deterministic)
{
  gsl_rng *r = gsl_rng_alloc(gsl_rng_taus2);
  gsl_rng_set(r, 323);
  sb_langevin_hitter *w = sb_langevin_hitter_alloc(NULL);
  /* (i) against a particle at rest at the origin */
  sb_langevin_path P[2];
  memset(P, 0, sizeof P);
  P[0].tau = 1.0;
  P[0].mass = 1.0;
  P[0].G = 2.0;
  const double x0[3] = {-1.6, 1.4, 0.2}, u0[3] = {0.4, -1.5, 0.0};
  memcpy(P[0].x0, x0, sizeof x0);
  memcpy(P[0].u0, u0, sizeof u0);
  memcpy(P[0].x1, x0, sizeof x0); /* ignored without noise */
  P[0].us[0] = 0.3 + P[0].G * x0[1];
  P[0].us[1] = -0.2;
  P[1].tau = INFINITY;
  P[1].mass = 1.0;
  double xr[3], ur[3];
  const double tr = det_rk4_contact(&P[0], 1.0, xr, ur);
  ck_assert(tr > 0.0 && tr < 1.0);
  sb_langevin_contact c;
  ck_assert_int_eq(sb_langevin_hitter_sample(w, &P[0], &P[1], 1.0, 1.0, r,
                                             &c), 1);
  printf("shear, no noise: contact at %.9f (Runge-Kutta %.9f)\n", c.t, tr);
  ck_assert_abs(c.t, tr, 1e-6);
  for (int k = 0; k < 3; k++) {
    ck_assert_abs(c.ui[k], ur[k], 1e-6);
    ck_assert_abs(c.xi[k] - c.xj[k], xr[k], 1e-6);
    ck_assert_abs(c.uj[k], 0.0, 1e-15);
  }
  /* (ii) against a particle with noise */
  shear_tab *T = malloc(2 * sizeof *T);
  ck_assert_ptr_nonnull(T);
  P[0].x0[0] = -1.25;
  P[0].x0[1] = 1.5;
  P[0].x0[2] = 0.1;
  P[0].u0[0] = 0.0;
  P[0].u0[1] = -3.0;
  P[1] = particle(0.5, 0.25);
  const double b[3] = {0.3, -0.2, 0.0};
  memcpy(P[1].x1, b, sizeof b);
  P[1].u0[0] = 0.5;
  P[1].u1[1] = 0.4;
  shear_vs_brute(50, "shear, one without noise", P, 0.3, -0.2, T, r, w);
  free(T);
  sb_langevin_hitter_free(w);
  gsl_rng_free(r);
}
END_TEST

/* One particle against a plane (sb_langevin_hitter_sample_plane), fixed
 * ends at dt/tau = 1, 10 and 0.1 (kT = m = 1, dt = 1): the same
 * brute force (256 sequential bridge sub-steps, particle 0 only, linear
 * entry into the half-space), 1000 paths against 6000 sampler draws,
 * two-sample binomial |z| <= 3.5 and KS2 of the hit times (p >= 1e-3);
 * every contact lies on the plane.  The normal is passed unnormalised
 * (2 e_y, level 2 a): the plane is u.x = a. */
START_TEST(test_plane_fixed_ends)
{
  gsl_rng *r = gsl_rng_alloc(gsl_rng_taus2);
  gsl_rng_set(r, 202);
  sb_langevin_hitter *w = sb_langevin_hitter_alloc(NULL);
  static const double taus[3] = {1.0, 0.1, 10.0};
  static const double y0[3] = {0.15, 0.2, 0.1}, y1[3] = {0.15, 0.25, 0.1};
  static const double v0[3] = {-0.5, 0.0, -0.3}, v1[3] = {0.5, 0.0, 0.3};
  static const double lev[3] = {0.0, 0.05, 0.0};
  const double nn[3] = {0.0, 2.0, 0.0}, un[3] = {0.0, 1.0, 0.0};
  for (int cfg = 0; cfg < 3; cfg++) {
    sb_langevin_path P[2] = {particle(taus[cfg], 1), particle(1, 1)};
    P[0].x0[0] = 0.2;
    P[0].x1[0] = -0.3;
    P[0].x0[1] = y0[cfg];
    P[0].x1[1] = y1[cfg];
    P[0].u0[1] = v0[cfg];
    P[0].u1[1] = v1[cfg];
    P[0].us[1] = 0.7;  /* fluid seen: must not matter given the ends */
    const int nb = 1000, ns = 6000;
    double *tb = malloc(nb * sizeof *tb), *ts = malloc(ns * sizeof *ts);
    long hb = 0, hs = 0;
    for (int n = 0; n < nb; n++)
      hb += bridge_brute(r, P, 256, 1.0, lev[cfg], un, 0, &tb[hb], NULL);
    for (int n = 0; n < ns; n++) {
      sb_langevin_contact c;
      int h = sb_langevin_hitter_sample_plane(w, &P[0], nn, 2.0 * lev[cfg],
                                              0.1, 1.0, r, &c);
      ck_assert_int_ge(h, 0);
      if (h) {
        ck_assert(fabs(c.xi[1] - lev[cfg]) < 1e-9);
        ts[hs++] = c.t;
      }
    }
    same_law(cfg, tb, hb, nb, ts, hs, ns);
  }
  /* a start beyond the plane is a contact at t = 0; bad normal */
  sb_langevin_path q = particle(1, 1);
  q.x0[1] = -0.1;
  q.x1[1] = 0.5;
  sb_langevin_contact c;
  ck_assert_int_eq(sb_langevin_hitter_sample_plane(w, &q, un, 0.0, 0.1, 1.0,
                                                   r, &c), 1);
  ck_assert(c.t == 0.0);
  const double zero[3] = {0, 0, 0};
  ck_assert_int_lt(sb_langevin_hitter_sample_plane(w, &q, zero, 0.0, 0.1,
                                                   1.0, r, &c), 0);
  sb_langevin_hitter_free(w);
  gsl_rng_free(r);
}
END_TEST

/* Given both end states the bridge does not depend on the (constant)
 * fluid velocity seen: the constant force us/tau adds a term to the
 * control whose integral, u(T) - u(0) + (x(T) - x(0))/tau, the ends fix,
 * so the path law (minimum-energy mean and covariance) is unchanged.  The
 * fluid enters only through the ends the transport produced. */
START_TEST(test_fluid_free)
{
  for (double h = 1e-3; h < 1e4; h *= 10.0) {
    sb_langevin p0 = {1.0, 1.3, 0.0}, p1 = {1.0, 1.3, 7.0};
    sb_langevin_mom m0, m1;
    ck_assert_int_eq(sb_langevin_bridge_moments(&p0, h, 0.3 * h, 0.2, -1.0,
                                                1.1, 0.4, &m0), SB_SUCCESS);
    ck_assert_int_eq(sb_langevin_bridge_moments(&p1, h, 0.3 * h, 0.2, -1.0,
                                                1.1, 0.4, &m1), SB_SUCCESS);
    ck_assert_abs(m1.mean_x, m0.mean_x, 1e-9 * (1.0 + 7.0 * h));
    ck_assert_abs(m1.mean_u, m0.mean_u, 1e-9 * 8.0);
    ck_assert_rel(m1.var_x, m0.var_x, 1e-14);
  }
}
END_TEST

/* The pruning budget, measured: with audit on, every pruned sub-interval
 * is explored and those holding a contact are counted.  Their expected
 * number is at most the sum of the pruned bounds (Rice: an upper bound on
 * the probability), which is at most eps per call.  eps = 1e-2 (so that
 * misses are frequent enough to count), 3000 calls in the diffusive
 * configuration where pruning is most active: audit hits <= pruned mass
 * + 4 sqrt(mass) + 3 and pruned mass / calls <= eps; then the default
 * eps = 1e-6 misses nothing in 1000 audited calls.  The same for the
 * exit sampler (sb_langevin_hitter_sample_exit; _i = 1: the pair starts
 * inside, at 0.9 R). */
static void audit_budget(int exitm)
{
  gsl_rng *r = gsl_rng_alloc(gsl_rng_taus2);
  gsl_rng_set(r, exitm ? 302 : 301);
  const double eps[2] = {1e-2, 1e-6};
  const int ncall[2] = {3000, 1000};
  for (int q = 0; q < 2; q++) {
    sb_langevin_hit_params hp;
    sb_langevin_hit_params_default(&hp);
    hp.eps = eps[q];
    hp.audit = 1;
    sb_langevin_hitter *w = sb_langevin_hitter_alloc(&hp);
    sb_langevin p = {1.0, sqrt(2.0), 0.0};
    for (int n = 0; n < ncall[q]; n++) {
      sb_langevin_path P[2] = {particle(1, 1), particle(1, 1)};
      double dir[3];
      gsl_ran_dir_3d(r, &dir[0], &dir[1], &dir[2]);
      const double dt = n % 2 ? 30.0 : 1.0;
      for (int k = 0; k < 3; k++)
        P[0].x0[k] = (exitm ? 0.9 : 1.8) * dir[k];
      for (int a = 0; a < 2; a++)
        for (int k = 0; k < 3; k++) {
          P[a].u0[k] = gsl_ran_gaussian_ziggurat(r, 1.0);
          double x = P[a].x0[k], u = P[a].u0[k];
          sb_langevin_step(&p, dt, r, &x, &u);
          P[a].x1[k] = x;
          P[a].u1[k] = u;
        }
      ck_assert_int_ge(exitm ? sb_langevin_hitter_sample_exit(
                                   w, &P[0], &P[1], 1.0, dt, r, NULL)
                             : sb_langevin_hitter_sample(w, &P[0], &P[1],
                                                         1.0, dt, r, NULL),
                       0);
    }
    sb_langevin_hit_stats st;
    sb_langevin_hitter_stats(w, &st);
    double m = st.pruned_mass;
    ck_assert_msg(st.pruned > 0, "nothing pruned");
    ck_assert_msg(m / st.calls <= eps[q], "pruned mass %g per call", m /
                  st.calls);
    printf("audit (%s) eps %g: pruned %llu, mass %g, audited misses "
           "%llu\n", exitm ? "exit" : "entry", eps[q],
           (unsigned long long)st.pruned, m,
           (unsigned long long)st.audit_hits);
    ck_assert_msg((double)st.audit_hits <= m + 4 * sqrt(m) + 3,
                  "eps %g: %llu audited misses, bound %g", eps[q],
                  (unsigned long long)st.audit_hits, m);
    if (q == 1)
      ck_assert_uint_eq(st.audit_hits, 0);
    sb_langevin_hitter_free(w);
  }
  gsl_rng_free(r);
}

START_TEST(test_audit_budget) { audit_budget(0); }
END_TEST

START_TEST(test_audit_exit) { audit_budget(1); }
END_TEST

/* The Rice bound is an upper bound: at the top level it exceeds the
 * brute-force contact probability for fixed ends (dt/tau = 1, two
 * configurations with p ~ 0.05 and ~ 1e-3); and it tends to 0 far away. */
START_TEST(test_bound)
{
  gsl_rng *r = gsl_rng_alloc(gsl_rng_taus2);
  gsl_rng_set(r, 401);
  sb_langevin_hitter *w = sb_langevin_hitter_alloc(NULL);
  const double ys[2] = {1.4, 1.8};
  for (int c = 0; c < 2; c++) {
    sb_langevin_path P[2] = {particle(1, 1), particle(1, 1)};
    P[0].x0[0] = P[0].x1[0] = ys[c];
    P[0].x0[1] = 1.0;
    P[0].x1[1] = -1.0;
    P[0].u0[1] = P[0].u1[1] = -2.0;
    double bound = sb_langevin_hitter_bound(w, &P[0], &P[1], 1.0, 1.0);
    const int nb = 3000;
    long hb = 0;
    double t;
    for (int n = 0; n < nb; n++)
      hb += bridge_brute(r, P, 256, 1.0, 1.0, NULL, 0, &t, NULL);
    double lo, hi;
    sb_binomial_ci((unsigned long)hb, (unsigned long)nb, 0.999, &lo, &hi);
    ck_assert_msg(bound >= lo, "y = %g: bound %g below brute force %g [%g, "
                  "%g]", ys[c], bound, (double)hb / nb, lo, hi);
    ck_assert(bound <= 1.0);
  }
  sb_langevin_path P[2] = {particle(1, 1), particle(1, 1)};
  P[0].x0[0] = P[0].x1[0] = 20.0;
  ck_assert(sb_langevin_hitter_bound(w, &P[0], &P[1], 1.0, 1.0) < 1e-30);
  sb_langevin_hitter_free(w);
  gsl_rng_free(r);
}
END_TEST

/* No noise: free flight (tau = inf) is a straight line, so the contact is
 * the ballistic root; B = 0 relaxes deterministically (velocity decays
 * like e^{-t/tau}: starting at 1.5 with u = -1, tau = 1, the position
 * 1.5 - (1 - e^{-t}) reaches 1 at t = ln 2). */
START_TEST(test_deterministic)
{
  gsl_rng *r = gsl_rng_alloc(gsl_rng_taus2);
  sb_langevin_hitter *w = sb_langevin_hitter_alloc(NULL);
  sb_langevin_path P[2];
  memset(P, 0, sizeof P);
  P[0].tau = P[1].tau = INFINITY;
  P[0].mass = P[1].mass = 1;
  P[0].x0[0] = 3.0;
  P[0].u0[0] = -1.0;
  sb_langevin_contact c;
  ck_assert_int_eq(sb_langevin_hitter_sample(w, &P[0], &P[1], 1.0, 4.0, r,
                                             &c), 1);
  ck_assert_rel(c.t, 2.0, 1e-9);
  ck_assert_rel(c.ui[0], -1.0, 1e-15);
  P[0].x0[1] = 1.2;  /* passes at 1.2 > R */
  ck_assert_int_eq(sb_langevin_hitter_sample(w, &P[0], &P[1], 1.0, 4.0, r,
                                             &c), 0);
  P[0].x0[1] = 0.0;
  P[0].tau = 1.0;
  P[0].B = 0.0;
  P[0].x0[0] = 1.5;
  ck_assert_int_eq(sb_langevin_hitter_sample(w, &P[0], &P[1], 1.0, 4.0, r,
                                             &c), 1);
  ck_assert_abs(c.t, log(2.0), 1e-5);
  ck_assert_rel(c.ui[0], -0.5, 1e-4);
  /* a stochastic partner against a free-flight particle still works */
  P[1] = particle(1, 1);
  P[1].x1[0] = P[1].x0[0] = 0.0;
  int h = sb_langevin_hitter_sample(w, &P[0], &P[1], 1.0, 1.0, r, &c);
  ck_assert(h == 0 || h == 1);
  sb_langevin_hitter_free(w);
  gsl_rng_free(r);
}
END_TEST

/* Overlap at the start, bad arguments. */
START_TEST(test_args)
{
  gsl_rng *r = gsl_rng_alloc(gsl_rng_taus2);
  sb_langevin_hitter *w = sb_langevin_hitter_alloc(NULL);
  sb_langevin_path P[2] = {particle(1, 1), particle(1, 1)};
  P[0].x0[0] = 0.5;
  sb_langevin_contact c;
  ck_assert_int_eq(sb_langevin_hitter_sample(w, &P[0], &P[1], 1.0, 1.0, r,
                                             &c), 1);
  ck_assert(c.t == 0.0);
  ck_assert_int_eq(sb_langevin_hitter_sample(w, &P[0], &P[1], -1.0, 1.0, r,
                                             &c), -SB_EDOM);
  ck_assert_int_eq(sb_langevin_hitter_sample(w, &P[0], &P[1], 1.0, 0.0, r,
                                             &c), -SB_EDOM);
  ck_assert_int_eq(sb_langevin_hitter_sample(NULL, &P[0], &P[1], 1.0, 1.0,
                                             r, &c), -SB_EINVAL);
  P[1].x1[2] = NAN;
  ck_assert_int_eq(sb_langevin_hitter_sample(w, &P[0], &P[1], 1.0, 1.0, r,
                                             &c), -SB_EDOM);
  sb_langevin_hit_params hp;
  sb_langevin_hit_params_default(&hp);
  hp.eps = 0.5;
  ck_assert_ptr_null(sb_langevin_hitter_alloc(&hp));
  hp.eps = 1e-6;
  hp.dim = 4;
  ck_assert_ptr_null(sb_langevin_hitter_alloc(&hp));
  sb_langevin_hitter_free(w);
  gsl_rng_free(r);
}
END_TEST

/* The reach: the miss bound decreases in rho, the reach meets the
 * tolerance, free flight needs none, it stays within a few standard
 * deviations of the relative displacement, and it scales with the units. */
START_TEST(test_reach)
{
  const double n = 1.0, R = 1.0, tau = 1.0, B = sqrt(2.0);
  double prev = INFINITY;
  for (double rho = 0.0; rho < 6.0; rho += 0.5) {
    double m = sb_langevin_miss_bound(3, n, R, tau, B, tau, B, 1.0, rho);
    ck_assert(m >= 0.0 && m <= prev);
    prev = m;
  }
  for (int dim = 2; dim <= 3; dim++)
    for (double dt = 0.01; dt <= 1000.0; dt *= 10.0) {
      double rho = sb_langevin_reach(dim, n, R, tau, B, tau, B, dt, 1e-9);
      ck_assert_msg(rho > 0.0 && isfinite(rho), "dt %g: rho %g", dt, rho);
      double m = sb_langevin_miss_bound(dim, n, R, tau, B, tau, B, dt, rho);
      ck_assert_msg(m <= 1.0001e-9 && m >= 0.9e-9, "dt %g: miss %g", dt, m);
      /* a deviation of a few relative-displacement sd (per component
       * (2 D dt)^(1/2) at most, D = B^2 tau^2 / 2) */
      double sdx = sqrt(2.0 * sb_langevin_var_x(tau, B, dt));
      ck_assert_msg(rho < 12.0 * sdx, "dt %g: rho %g, sd %g", dt, rho, sdx);
    }
  ck_assert(sb_langevin_reach(3, n, R, INFINITY, 0, INFINITY, 0, 1.0,
                              1e-9) == 0.0);
  /* units: lengths X, times T scale the reach by X (SI nanoparticles:
   * X = 1e-7 m, T = 1e-6 s; a quadrature in metres once returned 0) */
  const double X[3] = {1e-7, 1e3, 1e-7}, T[3] = {1e-6, 1e2, 1.0};
  for (int k = 0; k < 3; k++)
    for (double dt = 0.01; dt <= 1000.0; dt *= 100.0) {
      double r1 = sb_langevin_reach(3, n, R, tau, B, tau, B, dt, 1e-9);
      double Bs = B * X[k] / pow(T[k], 1.5);
      double r2 = sb_langevin_reach(3, n / (X[k] * X[k] * X[k]), R * X[k],
                                    tau * T[k], Bs, tau * T[k], Bs,
                                    dt * T[k], 1e-9);
      ck_assert_rel(r2, X[k] * r1, 1e-5);
    }
  ck_assert(isnan(sb_langevin_reach(3, -1.0, R, tau, B, tau, B, 1.0, 1e-9)));
  /* a bound beyond DBL_MAX (sd of the deviation ~1e153, the shell 4 pi
   * (R + y)^2 overflows) is SB_ERANGE, not inf with status 0 */
  sb_clear_error();
  ck_assert(isnan(sb_langevin_miss_bound(3, 1.0, 1.0, 1.0, 1e154, 2.0, 0.7,
                                         1.0, 0.5)));
  ck_assert_int_eq(sb_last_status(), SB_ERANGE);
  ck_assert(sbt_names(sb_last_error(), "sb_langevin_miss_bound"));
}
END_TEST

/* The miss bound and reach at huge B (B_i or B_j = 1e100 ... DBL_MAX, the
 * other 1; R = 1).  Scaling law: the moments of Z are quadratic in
 * (B_i, B_j), so sc, L and every length of the integral scale by lambda
 * with B -> lambda B, and
 *   E(n, R, lambda B, lambda rho) = lambda^dim E(n, R / lambda, B, rho);
 * E is linear in n, so the reach depends on n / tol only:
 *   reach(n, R, lambda B, tol) = lambda reach(n', R / lambda, B, tol'),
 *   n' / tol' = n lambda^dim / tol.
 * Here R / lambda <= 1e-100 is negligible against sc ~ 1 (the reference
 * takes R = 1e-300) and so is the other particle's B (reference 0).
 * Checked: the bound at rho = 0.5 lambda is lambda^dim times the
 * reference (n = 1 and 1e-300), or NaN with SB_ERANGE naming the function
 * where that exceeds DBL_MAX; the reach is lambda times the reference
 * where n' and tol' are normal doubles, and always finite and positive
 * (or NaN with SB_ERANGE), with the bound at it within [0.9, 1] tol.
 * Before: 0 with status 0 for B >= 1e155 (B^2 tau overflowed), minutes
 * per call at 1e100, SB_EDOM at 1e154. */
START_TEST(test_reach_huge_B)
{
  static const double Bs[] = {1e100, 1e150, 1e154, 1e155, 1e200, 1e300,
                              DBL_MAX};
  const double lmax = log(DBL_MAX), tol = 1e-9;
  int bad = 0;
  for (int dim = 2; dim <= 3; dim++)
    for (int dt10 = 0; dt10 < 2; dt10++) {
      const double dt = dt10 ? 100.0 : 1.0;
      const double e1 = sb_langevin_miss_bound(dim, 1.0, 1e-300, 1.0, 1.0,
                                               1.0, 0.0, dt, 0.5);
      ck_assert(e1 > 0.0 && isfinite(e1));
      for (size_t b = 0; b < sizeof Bs / sizeof Bs[0]; b++)
        for (int j = 0; j < 2; j++) {
          const double lam = Bs[b], Bi = j ? 1.0 : lam, Bj = j ? lam : 1.0;
          const double ns[2] = {1.0, 1e-300};
          for (int k = 0; k < 2; k++) {
            const double le = log(ns[k]) + dim * log(lam) + log(e1);
            sb_clear_error();
            const double m = sb_langevin_miss_bound(dim, ns[k], 1.0, 1.0, Bi,
                                                    1.0, Bj, dt, 0.5 * lam);
            const int st = sb_last_status();
            if (le < lmax - 1.0)
              SBT_XCHECK(bad, st == 0 && sbt_reldiff(m, exp(le)) < 1e-6,
                         "miss, dim %d dt %g B%c %g n %g: %g (status %d), "
                         "want %g", dim, dt, j ? 'j' : 'i', lam, ns[k], m,
                         st, exp(le));
            else if (le > lmax + 1.0)
              SBT_XCHECK(bad, isnan(m) && st == SB_ERANGE &&
                                  sbt_names(sb_last_error(),
                                            "sb_langevin_miss_bound"),
                         "miss, dim %d dt %g B%c %g n %g: %g (status %d), "
                         "want NaN, SB_ERANGE", dim, dt, j ? 'j' : 'i', lam,
                         ns[k], m, st);
          }
          sb_clear_error();
          const double r = sb_langevin_reach(dim, 1.0, 1.0, 1.0, Bi, 1.0, Bj,
                                             dt, tol);
          const int st = sb_last_status();
          if (st != 0) {
            SBT_XCHECK(bad, isnan(r) && st == SB_ERANGE &&
                                sbt_names(sb_last_error(),
                                          "sb_langevin_reach"),
                       "reach, dim %d dt %g B%c %g: %g (status %d)", dim, dt,
                       j ? 'j' : 'i', lam, r, st);
            continue;
          }
          SBT_XCHECK(bad, r > 0.0 && isfinite(r),
                     "reach, dim %d dt %g B%c %g: %g with status 0", dim, dt,
                     j ? 'j' : 'i', lam, r);
          const double m = sb_langevin_miss_bound(dim, 1.0, 1.0, 1.0, Bi, 1.0,
                                                  Bj, dt, r);
          SBT_XCHECK(bad, m <= 1.0001 * tol && m >= 0.9 * tol,
                     "reach, dim %d dt %g B%c %g: bound %g at the reach %g",
                     dim, dt, j ? 'j' : 'i', lam, m, r);
          const double lr = dim * log(lam) - log(tol); /* log(n'/tol') */
          if (0.5 * lr < 700.0) {
            const double r1 = sb_langevin_reach(dim, exp(0.5 * lr), 1e-300,
                                                1.0, 1.0, 1.0, 0.0, dt,
                                                exp(-0.5 * lr));
            SBT_XCHECK(bad, sbt_reldiff(r, lam * r1) < 1e-5,
                       "reach, dim %d dt %g B%c %g: %.9g, want %.9g", dim,
                       dt, j ? 'j' : 'i', lam, r, lam * r1);
          }
        }
    }
  ck_assert_int_eq(bad, 0);
}
END_TEST

/* ------------------------------------------------- extreme arguments */

static int hx_bad; /* failures of test_extreme_arguments, printed */

#define HXCHECK(cond, ...) SBT_XCHECK(hx_bad, cond, __VA_ARGS__)

static int finite_contact(const sb_langevin_contact *c, double dt)
{
  int ok = c->t >= 0.0 && c->t <= dt;
  for (int k = 0; k < 3; k++)
    ok = ok && isfinite(c->xi[k]) && isfinite(c->ui[k]) &&
         isfinite(c->xj[k]) && isfinite(c->uj[k]);
  return ok;
}

/* A sampler's return value h: >= 0 with finite contacts, or -SB_EDOM /
 * -SB_ERANGE with a message naming the function. */
static void hx_check(int h, const char *nm, const char *what, double v,
                     const sb_langevin_contact *c, int nc, double dt)
{
  if (h < 0) {
    HXCHECK(h == -SB_EDOM || h == -SB_ERANGE, "%s, %s = %g: status %d", nm,
            what, v, h);
    HXCHECK(sbt_names(sb_last_error(), nm),
            "%s, %s = %g: message \"%s\"", nm, what, v, sb_last_error());
    return;
  }
  for (int i = 0; i < nc; i++)
    HXCHECK(finite_contact(&c[i], dt), "%s, %s = %g: contact %d at t = %g "
            "not finite or outside [0, dt]", nm, what, v, i, c[i].t);
}

/* The reach functions in the sweep's form (sweep.h, sbt_xfn), 3-D */
static int hx_miss(const double *a, double *out, int *n, const char **nm)
{
  out[0] = sb_langevin_miss_bound(3, a[0], a[1], a[2], a[3], a[4], a[5],
                                  a[6], a[7]);
  *n = 1;
  *nm = "sb_langevin_miss_bound";
  return sb_last_status();
}
static int hx_reach(const double *a, double *out, int *n, const char **nm)
{
  out[0] = sb_langevin_reach(3, a[0], a[1], a[2], a[3], a[4], a[5], a[6],
                             a[7]);
  *n = 1;
  *nm = "sb_langevin_reach";
  return sb_last_status();
}

/* Each parameter of particle i (tau, B, mass, a start and end state
 * component, us, G), R and dt, and the arguments of the reach functions,
 * in turn over sbt_sweep_ext (+-1e-320, +-1e-300, 0, +-1e300, +-DBL_MAX,
 * +-inf, NaN, 2^+-995, 1e+-154):
 * every sampler returns a contact with finite states in [0, dt], no
 * contact, or -SB_EDOM / -SB_ERANGE naming itself; the bound is in [0, 1]
 * or NaN with an error; the miss bound and reach are finite and >= 0 or
 * NaN with SB_EDOM, SB_ERANGE or SB_EMAXITER naming the function
 * (sbt_sweep_vec).  The samplers keep a loop of their own: a contact is 13
 * numbers (sbt_sweep_vec takes SBT_SWEEP_MAXOUT), sample_all returns a
 * variable number of them, the contact time must lie in [0, dt], and the
 * five functions share one generator and hitter in a fixed order. */
START_TEST(test_extreme_arguments)
{
  const double *ext = sbt_sweep_ext;
  const int next = SBT_SWEEP_NEXT;
  gsl_rng *r = gsl_rng_alloc(gsl_rng_taus2);
  gsl_rng_set(r, 20261129);
  sb_langevin_hitter *w = sb_langevin_hitter_alloc(NULL);
  ck_assert_ptr_nonnull(w);
  enum { NPAR = 11 };
  static const char *pname[NPAR] = {"tau", "B", "mass", "x0", "u0", "x1",
                                    "u1", "us", "G", "R", "dt"};
  for (int a = 0; a < NPAR; a++)
    for (int e = 0; e < next; e++) {
      sb_langevin_path P[2] = {particle(1, 1), particle(1, 1)};
      P[0].x0[0] = 2.5, P[0].u0[0] = -1.0;
      P[0].x1[0] = 1.6, P[0].x1[1] = 0.2, P[0].u1[0] = -0.5;
      P[1].x1[0] = 0.1;
      double R = 1.0, dt = 1.0;
      double *arg[NPAR] = {&P[0].tau, &P[0].B, &P[0].mass, &P[0].x0[0],
                           &P[0].u0[0], &P[0].x1[0], &P[0].u1[0],
                           &P[0].us[0], &P[0].G, &R, &dt};
      *arg[a] = ext[e];
      sb_langevin_contact c;
      int h = sb_langevin_hitter_sample(w, &P[0], &P[1], R, dt, r, &c);
      hx_check(h, "sb_langevin_hitter_sample", pname[a], ext[e], &c, h == 1,
               dt);
      h = sb_langevin_hitter_sample_exit(w, &P[0], &P[1], R, dt, r, &c);
      hx_check(h, "sb_langevin_hitter_sample_exit", pname[a], ext[e], &c,
               h == 1, dt);
      h = sb_langevin_hitter_sample_all(w, &P[0], &P[1], R, dt, r);
      hx_check(h, "sb_langevin_hitter_sample_all", pname[a], ext[e],
               sb_langevin_hitter_entries(w), h > 0 ? h : 0, dt);
      const double n[3] = {1.0, 0.0, 0.0};
      h = sb_langevin_hitter_sample_plane(w, &P[0], n, R, 0.1, dt, r, &c);
      hx_check(h, "sb_langevin_hitter_sample_plane", pname[a], ext[e], &c,
               h == 1, dt);
      sb_clear_error();
      const double b = sb_langevin_hitter_bound(w, &P[0], &P[1], R, dt);
      HXCHECK((b >= 0.0 && b <= 1.0) ||
                  (isnan(b) && sb_last_status() != SB_SUCCESS),
              "sb_langevin_hitter_bound, %s = %g: %g with status %d",
              pname[a], ext[e], b, sb_last_status());
    }
  sb_langevin_hitter_free(w);
  gsl_rng_free(r);

  /* n, R, tau_i, B_i, tau_j, B_j, dt and rho (miss bound) or tol (reach):
   * finite and >= 0 with status 0, or NaN with an error naming the
   * function (sweep.h) */
  static const double mbase[8] = {1.0, 1.0, 1.0, 1.4, 2.0, 0.7, 1.0, 0.5};
  static const double rbase[8] = {1.0, 1.0, 1.0, 1.4, 2.0, 0.7, 1.0, 1e-9};
  hx_bad += sbt_sweep_vec(hx_miss, mbase, 8, 8, 1u, SB_EMAXITER,
                          SBT_SWEEP_NAN, 0);
  hx_bad += sbt_sweep_vec(hx_reach, rbase, 8, 8, 1u, SB_EMAXITER,
                          SBT_SWEEP_NAN, 1);
  ck_assert_int_eq(hx_bad, 0);
}
END_TEST
#undef HXCHECK

static Suite *suite(void)
{
  Suite *s = suite_create("langevin_hit");
  TCase *tc = tcase_create("core");
  tcase_add_test(tc, test_args);
  tcase_add_test(tc, test_deterministic);
  tcase_add_test(tc, test_reach);
  tcase_add_test(tc, test_reach_huge_B);
  tcase_add_test(tc, test_extreme_arguments);
  tcase_add_test(tc, test_fluid_free);
  tcase_add_test(tc, test_bridge_coef);
  suite_add_tcase(s, tc);
  TCase *ta = tcase_create("budget");
  tcase_set_timeout(ta, 30);
  tcase_add_test(ta, test_bound);
  tcase_add_test(ta, test_audit_budget);
  tcase_add_test(ta, test_audit_exit);
  suite_add_tcase(s, ta);
  TCase *tb = tcase_create("fixed");
  tcase_set_timeout(tb, 30);
  tcase_add_test(tb, test_fixed_ends);
  tcase_add_test(tb, test_plane_fixed_ends);
  tcase_add_test(tb, test_exit_fixed_ends);
  tcase_add_test(tb, test_all_entries);
  suite_add_tcase(s, tb);
  TCase *tsh = tcase_create("shear");
  tcase_set_timeout(tsh, 120);
  tcase_add_test(tsh, test_shear_fixed_ends);
  tcase_add_test(tsh, test_shear_all_entries);
  tcase_add_test(tsh, test_shear_deterministic);
  suite_add_tcase(s, tsh);
  TCase *tf = tcase_create("forward");
  tcase_set_timeout(tf, 60);
  tcase_add_test(tf, test_forward_short);
  tcase_add_test(tf, test_forward_mixed);
  tcase_add_test(tf, test_forward_long);
  suite_add_tcase(s, tf);
  return s;
}

int main(void) { return sbt_run_suite(suite()); }
