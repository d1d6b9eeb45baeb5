/* cases_spray.c — `smolbridge validate` cases of the spray collision
 * operators (V13) and the table of all spray cases (V13, V14).
 *
 *  V13/spray-bkw          Maxwell-type kernel, Bird and Nanbu, from a BKW
 *                         state: E|v|^4 over time and P(|v| <= s) at the
 *                         reference quartiles vs the BKW solution
 *  V13/spray-hs-frequency hard spheres, bidisperse Maxwellian mixture:
 *                         collision counts per species pair vs the kinetic
 *                         kernel sb_kernel_kinetic
 *  V13/spray-conservation Bird: momentum and energy to round-off; Nanbu
 *                         (variable weights): drift vs its martingale
 *                         quadratic variation
 *  (two-temperature relaxation and the engine comparison:
 *  cases_spray_relax.c; V14: cases_spray2.c)
 *
 * Monte Carlo verdicts use R independent replicas: each replica gives one
 * estimate, the record is the replica mean with its Student interval and
 * the t-test p-value (PASS iff p >= 1e-3).  Replicas, not a Poisson or
 * i.i.d. error, because collision counts of a gas at equilibrium are
 * overdispersed (the collision rate fluctuates with the particles'
 * speeds; V13/spray-hs-frequency records the index of dispersion
 * var/mean of each count over its replicas: 1.03-1.27 pooled over 160
 * seeds) and Bird's exact conservation correlates the particles.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_cdf.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_randist.h>
#include <gsl/gsl_roots.h>

#include <smolbridge/kernel.h>
#include <smolbridge/langevin.h>
#include <smolbridge/spray.h>
#include <smolbridge/stats.h>

#include "cases.h"
#include "cases_spray.h"

#define PI 3.14159265358979323846

double sbv_spray_mass(double r, double rho)
{
  return rho * (4.0 / 3.0) * PI * r * r * r;
}

sb_spray *sbv_spray_new(const sbv_spray_setup *u)
{
  sb_spray_params p;
  sb_spray_params_default(&p);
  p.method = u->method;
  if (u->B0 > 0) {
    p.cross = SB_SPRAY_MAXWELL;
    p.B0 = u->B0;
  }
  if (u->volume > 0)
    p.volume = u->volume;
  if (u->rho_l > 0)
    p.rho_l = u->rho_l;
  p.theta_cr = u->theta_cr;
  if (u->capacity > 0)
    p.capacity = u->capacity;
  if (u->settling) {
    p.merge_velocity = sb_spray_stokes_settling;
    p.merge_ctx = (void *)u->settling;
  }
  return sb_spray_alloc(&p);
}

int sbv_spray_add_replicas(sbv_report *rep, const char *name,
                           const double *x, size_t R, double ref)
{
  /* Student interval at 1 - alpha and the t test it inverts */
  sb_comparison c;
  sb_compare_mean(&c, name, x, R, ref, SBV_SPRAY_ALPHA);
  return sbv_add(rep, &c);
}

int sbv_spray_add_z(sbv_report *rep, const char *name, double est,
                    double ref, double z)
{
  /* acceptance region of the estimate: ref -+ z_{1-alpha/2} se, with
   * se = (est - ref)/z (the estimate is usually z itself, ref 0) */
  double q = gsl_cdf_ugaussian_Qinv(0.5 * SBV_SPRAY_ALPHA);
  double se = z != 0.0 ? fabs((est - ref) / z) : 0.0;
  double p = sb_zscore_pvalue(z);
  sb_comparison c;
  sb_compare(&c, name, SB_RULE_ACCEPT, est, ref, ref - q * se, ref + q * se,
             1.0 - SBV_SPRAY_ALPHA, isnan(p) ? NAN : p);
  return sbv_add(rep, &c);
}

int sbv_spray_add_tol(sbv_report *rep, const char *name, double est,
                      double ref, double tol)
{
  return sbv_add_band(rep, name, est, ref, est - tol, est + tol);
}

/* ================================================================ BKW */

typedef struct {
  double K, theta, p;
} q_ctx;

static double q_f(double s, void *par)
{
  const q_ctx *q = par;
  return sb_spray_bkw_speed_cdf(s, q->K, q->theta) - q->p;
}

/* Speed quantile of the BKW law (GSL Brent). */
static double bkw_quantile(double K, double theta, double p)
{
  q_ctx q = {K, theta, p};
  gsl_function F = {q_f, &q};
  gsl_root_fsolver *s = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
  if (!s)
    return NAN;
  gsl_root_fsolver_set(s, &F, 1e-6 * sqrt(theta), 20.0 * sqrt(theta));
  double x = NAN;
  for (int it = 0; it < 200; it++) {
    gsl_root_fsolver_iterate(s);
    x = gsl_root_fsolver_root(s);
    if (gsl_root_test_interval(gsl_root_fsolver_x_lower(s),
                               gsl_root_fsolver_x_upper(s), 0, 1e-14) ==
        GSL_SUCCESS)
      break;
  }
  gsl_root_fsolver_free(s);
  return x;
}

#define BKW_NT 5
#define BKW_NQ 3
#define BKW_NH 40

static int case_bkw(const sbv_ctx *ctx, sbv_report *rep)
{
  const size_t N = ctx->full ? 100000 : 10000, R = ctx->full ? 20 : 10;
  const double K0 = 0.6, theta = 1.0, tq = 2.0; /* tq: the histogram */
  const double times[BKW_NT] = {0.5, 1, 2, 4, 8};
  const double qp[BKW_NQ] = {0.25, 0.5, 0.75};
  static const char *mname[2] = {"bird", "nanbu"};
  double *m4 = malloc(2 * BKW_NT * R * sizeof *m4);
  /* the speed law is checked at times[0], [2], [4] */
  double *pq = malloc(2 * 3 * BKW_NQ * R * sizeof *pq);
  double *speeds = malloc(N * sizeof *speeds);
  double plot[BKW_NT + 1][4], hist[BKW_NH][4];
  memset(hist, 0, sizeof hist);
  if (!m4 || !pq || !speeds) {
    free(m4);
    free(pq);
    free(speeds);
    return SB_ENOMEM;
  }
  int st = SB_SUCCESS;
  double sq[3][BKW_NQ], m4sd[2] = {0, 0};
  double Kq = sb_spray_bkw_K(K0, 1.0, tq);
  const double smax = 5.0;
  for (int meth = 0; meth < 2 && !st; meth++) {
    /* per-particle rate n B0 = 1/s; Bird's pair rate W B N/((N-1) V)
     * makes the M4 relaxation rate N/(N-1) n B0 / 3 exactly */
    double lam = meth == 0 ? (double)N / (double)(N - 1) : 1.0;
    for (int k = 0; k < 3; k++)
      for (int q = 0; q < BKW_NQ; q++)
        sq[k][q] = bkw_quantile(sb_spray_bkw_K(K0, lam, times[2 * k]), theta,
                                qp[q]);
    gsl_rng *rng = sbv_rng_alloc(ctx, 100 + (unsigned long)meth);
    for (size_t rr = 0; rr < R && !st; rr++) {
      sb_spray *s = sbv_spray_new(&(sbv_spray_setup){
          .method = (sb_spray_method)meth, .B0 = 1.0, .volume = (double)N,
          .capacity = N});
      if (!s || !rng) {
        sb_spray_free(s);
        st = SB_ENOMEM;
        break;
      }
      for (size_t i = 0; i < N && !st; i++) {
        double v[3];
        sb_spray_bkw_sample(K0, theta, rng, v);
        st = sb_spray_add(s, v, 1e-3, 1.0, 0, NULL);
      }
      double t = 0;
      for (int k = 0; k < BKW_NT && !st; k++) {
        st = sb_spray_collide(s, times[k] - t, rng);
        t = times[k];
        double K = sb_spray_bkw_K(K0, lam, t);
        double ref = sb_spray_bkw_m4(K, theta);
        double m = sb_spray_velocity_moment(s, 4, NULL, -1);
        m4[(meth * BKW_NT + k) * R + rr] = m / ref;
        if (k % 2 == 0) {
          const double *v = sb_spray_velocities(s);
          size_t cnt[BKW_NQ] = {0, 0, 0};
          for (size_t i = 0; i < N; i++) {
            double sp = sqrt(v[3 * i] * v[3 * i] + v[3 * i + 1] * v[3 * i + 1] +
                             v[3 * i + 2] * v[3 * i + 2]);
            for (int q = 0; q < BKW_NQ; q++)
              cnt[q] += sp <= sq[k / 2][q];
            int b = (int)(sp / smax * BKW_NH);
            if (t == tq && b < BKW_NH)
              hist[b][1 + meth] += 1.0 / ((double)N * R * smax / BKW_NH);
          }
          for (int q = 0; q < BKW_NQ; q++)
            pq[((meth * 3 + k / 2) * BKW_NQ + q) * R + rr] =
                (double)cnt[q] / (double)N;
        }
      }
      sb_spray_free(s);
    }
    gsl_rng_free(rng);
    if (st)
      break;
    char name[96];
    for (int k = 0; k < BKW_NT; k++) {
      snprintf(name, sizeof name, "V13/bkw/%s/M4/t=%g", mname[meth],
               times[k]);
      st = sbv_spray_add_replicas(rep, name, m4 + (meth * BKW_NT + k) * R,
                                  R, 1.0);
    }
    for (int k = 0; k < 3 && !st; k++)
      for (int q = 0; q < BKW_NQ && !st; q++) {
        snprintf(name, sizeof name, "V13/bkw/%s/P(|v|<=s%.0f)/t=%g",
                 mname[meth], 100 * qp[q], times[2 * k]);
        st = sbv_spray_add_replicas(rep, name,
                                    pq + ((meth * 3 + k) * BKW_NQ + q) * R, R,
                                    qp[q]);
      }
    /* replica spread of M4/ref at the last time: the Nanbu variance */
    double mean = 0, var = 0;
    const double *x = m4 + (meth * BKW_NT + BKW_NT - 1) * R;
    for (size_t k = 0; k < R; k++)
      mean += x[k] / (double)R;
    for (size_t k = 0; k < R; k++)
      var += (x[k] - mean) * (x[k] - mean) / (double)(R - 1);
    m4sd[meth] = sqrt(var);
  }
  if (!st) {
    sbv_note(rep, "- Maxwell kernel B0 = 1 m^3/s, n = 1 m^-3 (lambda = n B0 "
             "= 1/s), theta = 1 m^2/s^2, BKW start K0 = 3/5; N = %zu "
             "particles, %zu replicas per method; M4 reference "
             "theta^2 K (30 - 15 K), K = 1 - (1 - K0) exp(-lambda t/6) "
             "(Bird: lambda N/(N-1), its exact finite-N rate)", N, R);
    sbv_note(rep, "- criterion: replica mean of M4/M4_ref = 1 and of the "
             "fraction with |v| <= s_q (s_q the exact 25/50/75%% speed "
             "quantiles at t = 0.5, 2 and 8 s) = q, t-test p >= 1e-3");
    sbv_note(rep, "- replica standard deviation of M4/M4_ref at t = %g s: "
             "Bird %.4f, Nanbu %.4f (ratio %.2f: the variance the "
             "one-sided updates add)", times[BKW_NT - 1], m4sd[0], m4sd[1],
             m4sd[1] / m4sd[0]);
    for (int k = 0; k <= BKW_NT; k++) {
      double t = k ? times[k - 1] : 0.0;
      plot[k][0] = t;
      plot[k][3] = sb_spray_bkw_m4(sb_spray_bkw_K(K0, 1.0, t), theta);
      for (int meth = 0; meth < 2; meth++) {
        double mean = 0;
        for (size_t rr = 0; rr < R && k; rr++)
          mean += m4[(meth * BKW_NT + k - 1) * R + rr] / (double)R;
        plot[k][1 + meth] = k ? mean * plot[k][3] : plot[k][3];
      }
    }
    sbv_plot(ctx, rep, "V13_bkw_m4", "V13: BKW fourth moment, Bird and Nanbu",
             "t M4_bird M4_nanbu M4_exact", &plot[0][0], BKW_NT + 1, 4,
             "set xlabel 't (1/lambda)'\nset ylabel 'E|v|^4 (theta^2)'\n"
             "set key bottom right\nplot $DATA u 1:2 w p pt 6 t 'Bird', "
             "$DATA u 1:3 w p pt 4 t 'Nanbu', $DATA u 1:4 w l t 'BKW'");
    for (int b = 0; b < BKW_NH; b++) {
      double sp = (b + 0.5) * smax / BKW_NH;
      hist[b][0] = sp;
      hist[b][3] = 4 * PI * sp * sp * sb_spray_bkw_pdf(sp, Kq, theta);
    }
    sbv_plot(ctx, rep, "V13_bkw_speed", "V13: speed density at t = 2/lambda",
             "s bird nanbu exact", &hist[0][0], BKW_NH, 4,
             "set xlabel '|v| (theta^1/2)'\nset ylabel 'density'\nplot "
             "$DATA u 1:2 w p pt 6 t 'Bird', $DATA u 1:3 w p pt 4 t "
             "'Nanbu', $DATA u 1:4 w l t 'BKW'");
  }
  free(m4);
  free(pq);
  free(speeds);
  return st;
}

/* ======================================================= HS frequency */

/* Index of dispersion s^2/mean of R counts and its 95% interval
 * D (R-1)/chi2_{R-1} quantiles (exact for Gaussian replicas; a Poisson
 * count has D = 1). */
static void dispersion(const double *c, size_t R, double *D, double *lo,
                       double *hi)
{
  double m = 0, v = 0, nu = (double)R - 1;
  for (size_t k = 0; k < R; k++)
    m += c[k] / (double)R;
  for (size_t k = 0; k < R; k++)
    v += (c[k] - m) * (c[k] - m) / nu;
  *D = v / m;
  *lo = *D * nu / gsl_cdf_chisq_Qinv(0.025, nu);
  *hi = *D * nu / gsl_cdf_chisq_Pinv(0.025, nu);
}

typedef struct {
  double count[2][2]; /* [tag_i][tag_j] */
} pair_count;

static void count_pairs(const sb_spray_event *e, void *ctx)
{
  pair_count *c = ctx;
  c->count[e->tag_i][e->tag_j] += 1.0;
}

static int case_frequency(const sbv_ctx *ctx, sbv_report *rep)
{
  const size_t Na = ctx->full ? 20000 : 4000, Nb = Na, N = Na + Nb;
  const size_t R = ctx->full ? 16 : 8;
  const double ra = 10e-6, rb = 20e-6, rho = 1000.0, V = 1e-6;
  const double ma = sbv_spray_mass(ra, rho), mb = sbv_spray_mass(rb, rho);
  const double T = ma / SB_BOLTZMANN; /* k_B T/m_a = 1 m^2/s^2 */
  double Kref[2][2];
  Kref[0][0] = sb_kernel_kinetic(2 * ra, 2 * ra, ma, ma, T);
  Kref[1][1] = sb_kernel_kinetic(2 * rb, 2 * rb, mb, mb, T);
  Kref[0][1] = Kref[1][0] = sb_kernel_kinetic(2 * ra, 2 * rb, ma, mb, T);
  const double na = (double)Na / V;
  const double tend = 2.0 / (na * (Kref[0][0] + Kref[0][1]));
  static const char *mname[2] = {"bird", "nanbu"};
  static const char *pname[2][2] = {{"aa", "ab"}, {"ba", "bb"}};
  double *est = malloc(2 * 2 * 4 * R * sizeof *est);
  if (!est)
    return SB_ENOMEM;
  double *cnt = est + 2 * 4 * R; /* raw counts, same layout */
  double dmax = 0;
  int st = SB_SUCCESS;
  for (int meth = 0; meth < 2 && !st; meth++) {
    gsl_rng *rng = sbv_rng_alloc(ctx, 200 + (unsigned long)meth);
    for (size_t rr = 0; rr < R && !st; rr++) {
      sb_spray *s = sbv_spray_new(&(sbv_spray_setup){
          .method = (sb_spray_method)meth, .volume = V, .rho_l = rho,
          .capacity = N});
      if (!s || !rng) {
        sb_spray_free(s);
        st = SB_ENOMEM;
        break;
      }
      pair_count pc;
      memset(&pc, 0, sizeof pc);
      sb_spray_set_observer(s, count_pairs, &pc);
      /* i.i.d. Maxwellian, not re-centred: the product Maxwellian at a
       * common T is invariant, so the expected rate is exact at all t */
      st = sb_spray_add_maxwellian(s, Na, ra, 1.0, 0, T, NULL, rng);
      if (!st)
        st = sb_spray_add_maxwellian(s, Nb, rb, 1.0, 1, T, NULL, rng);
      if (!st)
        st = sb_spray_collide(s, tend, rng);
      double Nn[2] = {(double)Na, (double)Nb};
      for (int a = 0; a < 2; a++)
        for (int b = 0; b < 2; b++) {
          double pairs, scale;
          if (meth == 0) { /* unordered; pair rate W B N/((N-1) V) */
            pairs = a == b ? Nn[a] * (Nn[a] - 1) / 2 : Nn[0] * Nn[1];
            scale = (double)N / (double)(N - 1) / V;
            double c = a == b ? pc.count[a][a]
                              : pc.count[0][1] + pc.count[1][0];
            cnt[(meth * 4 + 2 * a + b) * R + rr] = c;
            est[(meth * 4 + 2 * a + b) * R + rr] =
                c / (pairs * scale * tend) / Kref[a][b];
          } else { /* ordered (i updates, j partner); rate w B / V */
            pairs = a == b ? Nn[a] * (Nn[a] - 1) : Nn[a] * Nn[b];
            cnt[(meth * 4 + 2 * a + b) * R + rr] = pc.count[a][b];
            est[(meth * 4 + 2 * a + b) * R + rr] =
                pc.count[a][b] / (pairs / V * tend) / Kref[a][b];
          }
        }
      sb_spray_free(s);
    }
    gsl_rng_free(rng);
    char name[96];
    for (int a = 0; a < 2 && !st; a++)
      for (int b = 0; b < 2 && !st; b++) {
        if (meth == 0 && a == 1 && b == 0)
          continue; /* Bird counts a-b pairs once */
        snprintf(name, sizeof name, "V13/hs-frequency/%s/%s/K_e/K_kin",
                 mname[meth], meth == 0 && a != b ? "ab" : pname[a][b]);
        st = sbv_spray_add_replicas(rep, name, est + (meth * 4 + 2 * a + b) * R,
                                    R, 1.0);
        if (!st) {
          double D, lo, hi;
          dispersion(cnt + (meth * 4 + 2 * a + b) * R, R, &D, &lo, &hi);
          dmax = fmax(dmax, D);
          snprintf(name, sizeof name, "V13/hs-frequency/%s/%s/var/mean",
                   mname[meth], meth == 0 && a != b ? "ab" : pname[a][b]);
          st = sbv_add_info(rep, name, D, 1.0, lo, hi, 0.95);
        }
      }
  }
  if (!st)
    sbv_note(rep, "- hard spheres r_a = 10 um, r_b = 20 um, rho = 1000 "
             "kg/m^3, N_a = N_b = %zu in V = 1e-6 m^3, common T with "
             "k_B T/m_a = 1 m^2/s^2, run 2 collision times of species a; "
             "%zu replicas; K_kin = pi (r_i + r_j)^2 sqrt(8 k_B T/(pi "
             "m_red)) (sb_kernel_kinetic: %.4g, %.4g, %.4g m^3/s for aa, "
             "ab, bb); Nanbu counts ordered pairs (ab: a updated by b)",
             Na, R, Kref[0][0], Kref[0][1], Kref[1][1]);
  if (!st)
    sbv_note(rep, "- var/mean: index of dispersion of the raw collision "
             "count over the %zu replicas (info; 95%% chi-square interval); "
             "a Poisson count has 1, and the largest here is %.2f: the "
             "collision rate of a finite gas fluctuates with its particles' "
             "speeds, so a Poisson interval on one count would be too "
             "narrow; the verdicts are replica t-tests", R, dmax);
  free(est);
  return st;
}

/* ======================================================= conservation */

typedef struct {
  double rho;
  double dE, dE2, dP[3], dP2[3]; /* sums over events (w_i m_i changes) */
} mart;

static void mart_obs(const sb_spray_event *e, void *ctx)
{
  mart *m = ctx;
  double mi = sbv_spray_mass(e->r_i, m->rho) * e->w_i;
  double e0 = 0, e1 = 0;
  for (int k = 0; k < 3; k++) {
    e0 += e->vi[k] * e->vi[k];
    e1 += e->vi_new[k] * e->vi_new[k];
    double dp = mi * (e->vi_new[k] - e->vi[k]);
    m->dP[k] += dp;
    m->dP2[k] += dp * dp;
  }
  double de = 0.5 * mi * (e1 - e0);
  m->dE += de;
  m->dE2 += de * de;
}

static int case_conservation(const sbv_ctx *ctx, sbv_report *rep)
{
  const size_t N = ctx->full ? 100000 : 20000;
  const double ra = 10e-6, rb = 15e-6, rho = 1000.0, V = 1e-6;
  const double T = sbv_spray_mass(ra, rho) / SB_BOLTZMANN;
  const double u0[3] = {0.3, -0.2, 0.1};
  int st = SB_SUCCESS;
  double zE = 0, zP[3] = {0, 0, 0}, relE = 0, relP = 0, relsd = 0;
  for (int meth = 0; meth < 2 && !st; meth++) {
    gsl_rng *rng = sbv_rng_alloc(ctx, 300 + (unsigned long)meth);
    sb_spray *s = sbv_spray_new(&(sbv_spray_setup){
        .method = (sb_spray_method)meth, .volume = V, .rho_l = rho,
        .capacity = N});
    if (!s || !rng) {
      sb_spray_free(s);
      gsl_rng_free(rng);
      return SB_ENOMEM;
    }
    mart m;
    memset(&m, 0, sizeof m);
    m.rho = rho;
    if (meth == 1)
      sb_spray_set_observer(s, mart_obs, &m);
    /* Nanbu: weights uniform in [0.5, 2] to exercise variable weights */
    for (size_t i = 0; i < N && !st; i++) {
      double r = i % 2 ? rb : ra, w = meth ? 0.5 + 1.5 * gsl_rng_uniform(rng)
                                           : 1.0;
      double sd = sqrt(SB_BOLTZMANN * T / sbv_spray_mass(r, rho)), v[3];
      for (int k = 0; k < 3; k++)
        v[k] = u0[k] + gsl_ran_gaussian_ziggurat(rng, sd);
      st = sb_spray_add(s, v, r, w, (int)(i % 2), NULL);
    }
    sb_spray_totals t0, t1;
    sb_spray_get_totals(s, &t0);
    double K = sb_kernel_kinetic(2 * ra, 2 * rb, sbv_spray_mass(ra, rho),
                                 sbv_spray_mass(rb, rho), T);
    double tend = 5.0 / ((double)N / V * K);
    if (!st)
      st = sb_spray_collide(s, tend, rng);
    if (st) {  /* no totals to compare: the run did not happen */
      sb_spray_free(s);
      gsl_rng_free(rng);
      break;
    }
    sb_spray_get_totals(s, &t1);
    double pscale = t0.mass * sqrt(2 * t0.energy / t0.mass);
    if (meth == 0) {
      double dp = 0;
      for (int k = 0; k < 3; k++)
        dp = fmax(dp, fabs(t1.momentum[k] - t0.momentum[k]));
      relP = dp / pscale;
      relE = fabs(t1.energy - t0.energy) / t0.energy;
      st = sbv_spray_add_tol(rep, "V13/conservation/bird/momentum", relP,
                             0.0, 1e-13);
      if (!st)
        st = sbv_spray_add_tol(rep, "V13/conservation/bird/energy", relE,
                               0.0, 1e-13);
    } else {
      zE = (t1.energy - t0.energy) / sqrt(m.dE2);
      relsd = sqrt(m.dE2) / t0.energy;
      st = sbv_spray_add_z(rep, "V13/conservation/nanbu/energy-z", zE, 0.0,
                           zE);
      for (int k = 0; k < 3 && !st; k++) {
        char name[96];
        zP[k] = (t1.momentum[k] - t0.momentum[k]) / sqrt(m.dP2[k]);
        snprintf(name, sizeof name, "V13/conservation/nanbu/momentum-%c-z",
                 'x' + k);
        st = sbv_spray_add_z(rep, name, zP[k], 0.0, zP[k]);
      }
      /* the event sums must account for the whole change */
      if (!st)
        st = sbv_spray_add_tol(rep, "V13/conservation/nanbu/energy-bookkeeping",
                               (t1.energy - t0.energy - m.dE) / t0.energy,
                               0.0, 1e-10);
    }
    sb_spray_free(s);
    gsl_rng_free(rng);
  }
  if (!st) {
    sbv_note(rep, "- hard spheres, r = 10 and 15 um alternating, N = %zu, "
             "common granular temperature (k_B T/m = 1 m^2/s^2 for 10 um), "
             "mean velocity (0.3, -0.2, 0.1) m/s, 5 collision times", N);
    sbv_note(rep, "- Bird: max |dP|/(M c) = %.2g, |dE|/E = %.2g "
             "(criterion <= 1e-13)", relP, relE);
    sbv_note(rep, "- Nanbu (weights uniform in [0.5, 2]): energy and "
             "momentum are martingales; z = drift / sqrt(sum of squared "
             "event increments) ~ N(0,1): z_E = %.3f, z_P = (%.3f, %.3f, "
             "%.3f); the energy's random walk has relative sd %.3g after 5 "
             "collision times (~ sqrt(t/N)): the variance Nanbu adds",
             zE, zP[0], zP[1], zP[2], relsd);
  }
  return st;
}

/* ================================================================ table */

const sbv_case sbv_cases_spray[] = {
    {"V13/spray-bkw", "Bird and Nanbu vs the BKW exact solution (Maxwell "
     "kernel): E|v|^4 and speed law", case_bkw},
    {"V13/spray-hs-frequency", "hard-sphere collision counts per species "
     "pair vs the kinetic kernel, bidisperse Maxwellian", case_frequency},
    {"V13/spray-two-temperature", "two-temperature mixture: Maxwell kernel "
     "exact, hard spheres vs the exact moment equation",
     sbv_spray_case_two_temp},
    {"V13/spray-conservation", "Bird conserves momentum and energy to "
     "round-off; Nanbu's drift is a martingale", case_conservation},
    {"V13/spray-vs-engine", "Bird and Nanbu vs the MD engine on the V1 "
     "helium gas: kernel and anisotropy relaxation", sbv_spray_case_engine},
    {"V14/spray-coalescence-constant", "Maxwell-type coalescence vs the "
     "analytic constant-kernel Smoluchowski solution",
     sbv_spray_case_coal_const},
    {"V14/spray-coalescence-gravity", "hard-sphere coalescence of settling "
     "drops vs CVODE with the gravitational kernel",
     sbv_spray_case_coal_gravity},
    {"V14/spray-tab", "TAB: closed form, breakup time vs We, critical We, "
     "children Sauter radius", sbv_spray_case_tab},
    {"V14/spray-reitz", "Reitz wave breakup: mass, radius vs closed form, "
     "radius distribution", sbv_spray_case_reitz},
};
const size_t sbv_ncases_spray = sizeof sbv_cases_spray / sizeof
                                sbv_cases_spray[0];
