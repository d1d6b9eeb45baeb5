/* cases_spray_relax.c — V13 relaxation cases of the spray collision
 * operators:
 *
 *  V13/spray-two-temperature  binary mixture T_a = 2 T_b, m_b = 2 m_a.
 *     Maxwell kernel: T_a(t), T_b(t) vs the exact exponential (the moment
 *     equation is closed for any distributions).  Hard spheres: (i) the
 *     exact t = 0 rate of the Maxwellian mixture (closed form, docs) vs a
 *     Monte Carlo average of the pair sum over i.i.d. Maxwellian samples;
 *     (ii) the whole relaxation vs its exact (unclosed) moment equation
 *     dE_a/dt = sum over a-b pairs of rate_ij (-mu G.g): E_a(t) - E_a(0)
 *     minus the time integral of that sum, evaluated on the simulated
 *     particles between events, is a martingale (z-test with the realised
 *     quadratic variation); (iii) the Maxwellian closure's curve is shown
 *     with its measured deviation (a note, not a verdict: it is not exact).
 *  V13/spray-vs-engine  the V1 helium gas (Mohaupt 2011, Table 3.1: n/V of 250
 *     molecules in (10 nm)^3, T = 300 K): the MD engine and both
 *     stochastic methods start from the same anisotropic Maxwellian
 *     (T_x = 1.6 T, T_y = T_z = 0.7 T); the anisotropy
 *     A = (T_x - (T_y + T_z)/2)/T and the kernel are compared (Welch
 *     t-tests over replicas).  The dense MD gas collides g(sigma) times
 *     more often (Enskog; Carnahan-Starling g), so the stochastic runs use
 *     the time g t and the kernel reference g K.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_cdf.h>
#include <gsl/gsl_randist.h>
#include <gsl/gsl_statistics_double.h>

#include <smolbridge/engine.h>
#include <smolbridge/kernel.h>
#include <smolbridge/langevin.h>
#include <smolbridge/spray.h>
#include <smolbridge/stats.h>

#include "cases.h"
#include "cases_spray.h"

/* Sonine coefficient a2 = 3 E|c|^4/(5 (E|c|^2)^2) - 1 of the parcels with
 * tag `tag` (c the velocity relative to their mean; 0 for a Maxwellian). */
static double sonine_a2(const sb_spray *s, int tag)
{
  const double *v = sb_spray_velocities(s);
  const int *tg = sb_spray_tags(s);
  double u[3] = {0, 0, 0}, n = 0;
  for (size_t i = 0; i < sb_spray_count(s); i++)
    if (tg[i] == tag) {
      n += 1;
      for (int k = 0; k < 3; k++)
        u[k] += v[3 * i + k];
    }
  for (int k = 0; k < 3; k++)
    u[k] /= n;
  double m2 = sb_spray_velocity_moment(s, 2, u, tag);
  return 0.6 * sb_spray_velocity_moment(s, 4, u, tag) / (m2 * m2) - 1.0;
}

/* ============================================= exact moment equation */

typedef struct {
  const sb_spray *s;
  double rho;
  size_t na;       /* parcels 0..na-1 are species a (tag 0) */
  double S;        /* sum over a-b pairs of B_ij (-mu G.g), J m^3/s */
  double A;        /* time integral of the expected dE_a/dt, J */
  double tlast;
  double c;        /* dE_a/dt = c S */
  double dEa, qv;  /* realised change of E_a and sum of squares */
} mom_ctx;

/* B (-mu G.g) for velocities va (mass ma, radius ra) and vb */
static double pair_term(const double *va, const double *vb, double ma,
                        double mb, double ra, double rb)
{
  double M = ma + mb, mu = ma * mb / M, gg = 0, Gg = 0;
  for (int k = 0; k < 3; k++) {
    double g = va[k] - vb[k], G = (ma * va[k] + mb * vb[k]) / M;
    gg += g * g;
    Gg += G * g;
  }
  double d = ra + rb;
  return 3.14159265358979323846 * d * d * sqrt(gg) * (-mu * Gg);
}

static double full_sum(const sb_spray *s, size_t na, double rho)
{
  size_t n = sb_spray_count(s);
  const double *v = sb_spray_velocities(s), *r = sb_spray_radii(s);
  double S = 0;
  for (size_t i = 0; i < na; i++)
    for (size_t j = na; j < n; j++)
      S += pair_term(v + 3 * i, v + 3 * j, sbv_spray_mass(r[i], rho),
                     sbv_spray_mass(r[j], rho), r[i], r[j]);
  return S;
}

/* Change of S when parcel p moves from vold to its current velocity
 * (partners taken at their current velocities, `skip` excluded). */
static double row_delta(const mom_ctx *m, size_t p, const double *vold,
                        size_t skip)
{
  size_t n = sb_spray_count(m->s);
  const double *v = sb_spray_velocities(m->s), *r = sb_spray_radii(m->s);
  double d = 0, mp = sbv_spray_mass(r[p], m->rho);
  size_t lo = p < m->na ? m->na : 0, hi = p < m->na ? n : m->na;
  for (size_t q = lo; q < hi; q++) {
    if (q == skip)
      continue;
    double mq = sbv_spray_mass(r[q], m->rho);
    if (p < m->na)
      d += pair_term(v + 3 * p, v + 3 * q, mp, mq, r[p], r[q]) -
           pair_term(vold, v + 3 * q, mp, mq, r[p], r[q]);
    else
      d += pair_term(v + 3 * q, v + 3 * p, mq, mp, r[q], r[p]) -
           pair_term(v + 3 * q, vold, mq, mp, r[q], r[p]);
  }
  return d;
}

static void mom_obs(const sb_spray_event *e, void *ctx)
{
  mom_ctx *m = ctx;
  m->A += m->c * m->S * (e->t - m->tlast);
  m->tlast = e->t;
  const double *v = sb_spray_velocities(m->s);
  int pair = memcmp(e->vj, e->vj_new, sizeof e->vj) != 0;
  double de = 0;
  if (e->i < m->na)
    de += 0.5 * sbv_spray_mass(e->r_i, m->rho) * e->w_i *
          (v[3 * e->i] * v[3 * e->i] + v[3 * e->i + 1] * v[3 * e->i + 1] +
           v[3 * e->i + 2] * v[3 * e->i + 2] -
           (e->vi[0] * e->vi[0] + e->vi[1] * e->vi[1] + e->vi[2] * e->vi[2]));
  if (pair && e->j < m->na)
    de += 0.5 * sbv_spray_mass(e->r_j, m->rho) * e->w_j *
          (v[3 * e->j] * v[3 * e->j] + v[3 * e->j + 1] * v[3 * e->j + 1] +
           v[3 * e->j + 2] * v[3 * e->j + 2] -
           (e->vj[0] * e->vj[0] + e->vj[1] * e->vj[1] + e->vj[2] * e->vj[2]));
  m->dEa += de;
  m->qv += de * de;
  /* update S: rows of the changed parcels, then their common pair */
  m->S += row_delta(m, e->i, e->vi, pair ? e->j : (size_t)-1);
  if (pair) {
    m->S += row_delta(m, e->j, e->vj, e->i);
    int ia = e->i < m->na, ja = e->j < m->na;
    if (ia != ja) {
      const double *va_new = v + 3 * (ia ? e->i : e->j);
      const double *vb_new = v + 3 * (ia ? e->j : e->i);
      const double *va_old = ia ? e->vi : e->vj, *vb_old = ia ? e->vj : e->vi;
      double ra = ia ? e->r_i : e->r_j, rb = ia ? e->r_j : e->r_i;
      double ma = sbv_spray_mass(ra, m->rho), mb = sbv_spray_mass(rb, m->rho);
      m->S += pair_term(va_new, vb_new, ma, mb, ra, rb) -
              pair_term(va_old, vb_old, ma, mb, ra, rb);
    }
  }
}

#define TT_NT 3

int sbv_spray_case_two_temp(const sbv_ctx *ctx, sbv_report *rep)
{
  const size_t R = ctx->full ? 20 : 6;
  const double rho = 1000.0, ra = 10e-6, rb = ra * cbrt(2.0);
  const double ma = sbv_spray_mass(ra, rho), mb = 2.0 * ma;
  const double T = ma / SB_BOLTZMANN; /* k_B T/m_a = 1 m^2/s^2 */
  static const char *mname[2] = {"bird", "nanbu"};
  int st = SB_SUCCESS;
  char name[96];
  /* ---- Maxwell kernel: exact ---- */
  {
    const size_t Na = ctx->full ? 20000 : 5000;
    const double V = 1.0, B0 = 1.0 / (2.0 * (double)Na); /* rate 4/9 /s */
    const double ts[TT_NT] = {0.5, 1.5, 4.0};
    double *x = malloc(2 * 2 * TT_NT * R * sizeof *x);
    if (!x)
      return SB_ENOMEM;
    for (int meth = 0; meth < 2 && !st; meth++) {
      gsl_rng *rng = sbv_rng_alloc(ctx, 400 + (unsigned long)meth);
      for (size_t rr = 0; rr < R && !st; rr++) {
        sb_spray *s = sbv_spray_new(&(sbv_spray_setup){
            .method = (sb_spray_method)meth, .B0 = B0, .volume = V,
            .rho_l = rho, .capacity = 2 * Na});
        if (!s || !rng) {
          sb_spray_free(s);
          st = SB_ENOMEM;
          break;
        }
        st = sb_spray_add_maxwellian(s, Na, ra, 1.0, 0, 2 * T, NULL, rng);
        if (!st)
          st = sb_spray_add_maxwellian(s, Na, rb, 1.0, 1, T, NULL, rng);
        /* zero momentum per species, so the mixture only exchanges
         * energy; the reference starts from the realised temperatures */
        for (int sp = 0; sp < 2 && !st; sp++) {
          double u[3] = {0, 0, 0};
          const double *v = sb_spray_velocities(s);
          for (size_t i = sp * Na; i < (sp + 1) * Na; i++)
            for (int k = 0; k < 3; k++)
              u[k] += v[3 * i + k] / (double)Na;
          for (size_t i = sp * Na; i < (sp + 1) * Na; i++) {
            double w[3];
            for (int k = 0; k < 3; k++)
              w[k] = v[3 * i + k] - u[k];
            sb_spray_set_velocity(s, i, w);
          }
        }
        sb_spray_mixture mx = {(double)Na / V, (double)Na / V, ma, mb, ra,
                               rb, sb_spray_temperature(s, 0),
                               sb_spray_temperature(s, 1)};
        /* Bird's pair rate carries N/(N-1) */
        double Beff = meth == 0 ? B0 * (2.0 * Na) / (2.0 * Na - 1.0) : B0;
        double t = 0;
        for (int k = 0; k < TT_NT && !st; k++) {
          st = sb_spray_collide(s, ts[k] - t, rng);
          t = ts[k];
          double Ta, Tb;
          sb_spray_two_temp_maxwell(&mx, Beff, t, &Ta, &Tb);
          x[((meth * 2 + 0) * TT_NT + k) * R + rr] =
              sb_spray_temperature(s, 0) / Ta;
          x[((meth * 2 + 1) * TT_NT + k) * R + rr] =
              sb_spray_temperature(s, 1) / Tb;
        }
        sb_spray_free(s);
      }
      gsl_rng_free(rng);
      for (int sp = 0; sp < 2 && !st; sp++)
        for (int k = 0; k < TT_NT && !st; k++) {
          snprintf(name, sizeof name, "V13/two-temp/maxwell/%s/T_%c/t=%g",
                   mname[meth], 'a' + sp, ts[k]);
          st = sbv_spray_add_replicas(rep, name,
                                      x + ((meth * 2 + sp) * TT_NT + k) * R,
                                      R, 1.0);
        }
    }
    free(x);
    if (st)
      return st;
    sbv_note(rep, "- Maxwell kernel: N_a = N_b = %zu, V = 1 m^3, B0 = "
             "1/(2 N_a) m^3/s, T_a = 2 T_b, m_b = 2 m_a, zero momentum per "
             "species; exact Delta(t) = Delta0 exp(-2 B0 (n_a + n_b) m_a "
             "m_b/(m_a+m_b)^2 t) (Bird: B0 N/(N-1)); %zu replicas; "
             "criterion T(t)/T_exact(t) = 1, t-test p >= 1e-3", Na, R);
  }
  /* ---- hard spheres ---- */
  const size_t Na = ctx->full ? 2000 : 700, N = 2 * Na;
  const double V = 1e-6;
  sb_spray_mixture mx0 = {(double)Na / V, (double)Na / V, ma, mb, ra, rb,
                          2 * T, T};
  double rate0 = sb_spray_two_temp_hs_rate(&mx0, 2 * T, T);
  double tau = T / fabs(rate0);   /* time for T_a to move by T at rate0 */
  const double tend = 1.5 * tau;
  double *r0 = malloc((R > 10 ? R : 10) * sizeof *r0);
  double zsum[2] = {0, 0}, qsum[2] = {0, 0};
  /* NP output steps over 1.5 tau; the closure rows at k = 4, 8, 12
   * (t = 0.5, 1, 1.5 tau), the Sonine coefficients at k = 8 */
  enum { NP = 12, NC = 3 };
  double plot[NP + 1][5];
  memset(plot, 0, sizeof plot);
  /* per method and replica: closure deviation at NC times, change of
   * a2 of species a and b at t = tau */
  double *cdev = malloc(2 * (NC + 2) * R * sizeof *cdev);
  if (!r0 || !cdev) {
    free(r0);
    free(cdev);
    return SB_ENOMEM;
  }
  for (int meth = 0; meth < 2 && !st; meth++) {
    gsl_rng *rng = sbv_rng_alloc(ctx, 410 + (unsigned long)meth);
    for (size_t rr = 0; rr < R && !st; rr++) {
      sb_spray *s = sbv_spray_new(&(sbv_spray_setup){
          .method = (sb_spray_method)meth, .volume = V, .rho_l = rho,
          .capacity = N});
      if (!s || !rng) {
        sb_spray_free(s);
        st = SB_ENOMEM;
        break;
      }
      st = sb_spray_add_maxwellian(s, Na, ra, 1.0, 0, 2 * T, NULL, rng);
      if (!st)
        st = sb_spray_add_maxwellian(s, Na, rb, 1.0, 1, T, NULL, rng);
      mom_ctx m;
      memset(&m, 0, sizeof m);
      m.s = s;
      m.rho = rho;
      m.na = Na;
      m.S = full_sum(s, Na, rho);
      /* dE_a/dt = (pair rate factor / V) S: Bird W N/(N-1), Nanbu w */
      m.c = (meth == 0 ? (double)N / (double)(N - 1) : 1.0) / V;
      sb_spray_set_observer(s, mom_obs, &m);
      /* the closure from this replica's realised temperatures */
      sb_spray_mixture mr = mx0;
      mr.T_a0 = sb_spray_temperature(s, 0);
      mr.T_b0 = sb_spray_temperature(s, 1);
      double a20[2] = {sonine_a2(s, 0), sonine_a2(s, 1)};
      double *cd = cdev + meth * (NC + 2) * R;
      for (int k = 1; k <= NP && !st; k++) {
        st = sb_spray_collide(s, tend / NP, rng);
        double Ta = sb_spray_temperature(s, 0), Tb = sb_spray_temperature(s, 1);
        double Tac, Tbc;
        sb_spray_two_temp_hs(&mr, tend * k / NP, &Tac, &Tbc);
        if (k % (NP / NC) == 0)
          cd[(k / (NP / NC) - 1) * R + rr] = ((Ta - Tb) - (Tac - Tbc)) / T;
        if (k == 2 * NP / NC)
          for (int sp = 0; sp < 2; sp++)
            cd[(NC + sp) * R + rr] = sonine_a2(s, sp) - a20[sp];
        if (meth == 0) {
          plot[k][1] += Ta / T / (double)R;
          plot[k][2] += Tb / T / (double)R;
          plot[k][3] += Tac / T / (double)R;
          plot[k][4] += Tbc / T / (double)R;
          if (k == 1) {
            plot[0][1] += mr.T_a0 / T / (double)R;
            plot[0][2] += mr.T_b0 / T / (double)R;
          }
        }
      }
      m.A += m.c * m.S * (sb_spray_time(s) - m.tlast);
      zsum[meth] += m.dEa - m.A;
      qsum[meth] += m.qv;
      sb_spray_free(s);
    }
    gsl_rng_free(rng);
  }
  /* (i) the closed-form t = 0 rate vs a Monte Carlo average over
   * independent Maxwellian pairs, 10 batches */
  if (!st) {
    gsl_rng *rng = sbv_rng_alloc(ctx, 420);
    const size_t Mp = ctx->full ? 2000000 : 300000;
    const double sa = sqrt(2 * T * SB_BOLTZMANN / ma);
    const double sb = sqrt(T * SB_BOLTZMANN / mb);
    for (size_t bb = 0; bb < 10 && rng; bb++) {
      double sum = 0;
      for (size_t k = 0; k < Mp; k++) {
        double va[3], vb[3];
        for (int q = 0; q < 3; q++) {
          va[q] = gsl_ran_gaussian_ziggurat(rng, sa);
          vb[q] = gsl_ran_gaussian_ziggurat(rng, sb);
        }
        sum += pair_term(va, vb, ma, mb, ra, rb);
      }
      r0[bb] = mx0.n_b * sum / (double)Mp / (1.5 * SB_BOLTZMANN) / rate0;
    }
    gsl_rng_free(rng);
    st = rng ? sbv_spray_add_replicas(rep, "V13/two-temp/hard-sphere/"
                                      "rate(t=0)", r0, 10, 1.0)
             : SB_ENOMEM;
  }
  for (int meth = 0; meth < 2 && !st; meth++) {
    double z = zsum[meth] / sqrt(qsum[meth]);
    snprintf(name, sizeof name, "V13/two-temp/hard-sphere/%s/moment-eq-z",
             mname[meth]);
    st = sbv_spray_add_z(rep, name, z, 0.0, z);
  }
  /* (iii) the Maxwellian closure: informational rows (it is not the
   * hard-sphere answer, docs/spray.md §3), replica mean and its 95%
   * Student interval */
  for (int meth = 0; meth < 2 && !st; meth++)
    for (int q = 0; q < NC + 2 && !st; q++) {
      const double *x = cdev + (meth * (NC + 2) + q) * R;
      double mean = gsl_stats_mean(x, 1, R);
      double h = gsl_cdf_tdist_Qinv(0.025, (double)R - 1) *
                 gsl_stats_sd_m(x, 1, R, mean) / sqrt((double)R);
      if (q < NC)
        snprintf(name, sizeof name, "V13/two-temp/hard-sphere/%s/"
                 "(Delta-Delta_closure)/T_b0/t=%gtau", mname[meth],
                 (q + 1) * 1.5 / NC);
      else
        snprintf(name, sizeof name, "V13/two-temp/hard-sphere/%s/"
                 "a2_%c(tau)-a2_%c(0)", mname[meth], 'a' + q - NC,
                 'a' + q - NC);
      st = sbv_add_info(rep, name, mean, 0.0, mean - h, mean + h, 0.95);
    }
  free(r0);
  free(cdev);
  if (st)
    return st;
  for (int k = 0; k <= NP; k++)
    plot[k][0] = (double)k / NP * tend / tau;
  plot[0][3] = plot[0][1];
  plot[0][4] = plot[0][2];
  sbv_note(rep, "- hard spheres: r_a = 10 um, r_b = 2^(1/3) r_a, N_a = N_b "
           "= %zu in 1e-6 m^3, T_a = 2 T_b (k_B T_b/m_a = 1 m^2/s^2), run "
           "1.5 tau (tau = T_b/|dT_a/dt(0)| = %.3g s), %zu replicas per "
           "method", Na, tau, R);
  sbv_note(rep, "- rate(t=0): n_b E[B (-mu G.g)]/(3/2 k_B) over independent "
           "Maxwellian pairs (10 batches) against the closed form (16/3) "
           "sqrt(2/pi) pi d^2 n_b m_a m_b/M^2 s (T_a - T_b); moment-eq-z: "
           "(E_a(t) - E_a(0) - int c S dt)/sqrt(sum of squared jumps), S "
           "the a-b pair sum on the simulated particles, pooled over "
           "replicas, ~N(0,1)");
  sbv_note(rep, "- Maxwellian closure (not exact for hard spheres: the "
           "exchange rate weights |g|, so it depends on the species' "
           "shapes, which leave the Maxwellian at first order in T_a - "
           "T_b), started from each replica's temperatures: info rows "
           "(Delta - Delta_closure)/T_b(0) at t = 0.5, 1, 1.5 tau and the "
           "change of each species' Sonine coefficient a2 = 3 E|c|^4/(5 "
           "E|c|^2^2) - 1 by t = tau (replica means, 95%% Student "
           "intervals)");
  sbv_plot(ctx, rep, "V13_two_temperature",
           "V13: two-temperature relaxation, hard spheres (Bird)",
           "t/tau Ta Tb Ta_closure Tb_closure", &plot[0][0], NP + 1, 5,
           "set xlabel 't/tau'\nset ylabel 'T/T_b(0)'\nplot $DATA u 1:2 w p "
           "pt 6 t 'T_a Bird', $DATA u 1:3 w p pt 4 t 'T_b Bird', $DATA u "
           "1:4 w l t 'T_a closure', $DATA u 1:5 w l t 'T_b closure'");
  return SB_SUCCESS;
}

/* ============================================================ engine */

#define AVOGADRO 6.02214076e23
#define ENG_NT 3

/* Anisotropy (T_x - (T_y + T_z)/2)/T of equal-mass velocities. */
static double anisotropy(const double *v, size_t n)
{
  double s[3] = {0, 0, 0}, m[3] = {0, 0, 0};
  for (size_t i = 0; i < n; i++)
    for (int k = 0; k < 3; k++)
      m[k] += v[3 * i + k] / (double)n;
  for (size_t i = 0; i < n; i++)
    for (int k = 0; k < 3; k++) {
      double d = v[3 * i + k] - m[k];
      s[k] += d * d;
    }
  double tot = (s[0] + s[1] + s[2]) / 3.0;
  return (s[0] - 0.5 * (s[1] + s[2])) / tot;
}

static double g_cs(double phi)
{
  return (1.0 - 0.5 * phi) / ((1.0 - phi) * (1.0 - phi) * (1.0 - phi));
}

/* Welch two-sample t-test of the means of x (nx) and y (ny); records
 * mean(x) - mean(y) against 0. */
static int add_welch(sbv_report *rep, const char *name, const double *x,
                     size_t nx, const double *y, size_t ny, double ref)
{
  double mx = 0, my = 0, vx = 0, vy = 0;
  for (size_t i = 0; i < nx; i++)
    mx += x[i] / (double)nx;
  for (size_t i = 0; i < ny; i++)
    my += y[i] / (double)ny;
  for (size_t i = 0; i < nx; i++)
    vx += (x[i] - mx) * (x[i] - mx) / (double)(nx - 1);
  for (size_t i = 0; i < ny; i++)
    vy += (y[i] - my) * (y[i] - my) / (double)(ny - 1);
  double a = vx / (double)nx, b = vy / (double)ny, se = sqrt(a + b);
  double dof = (a + b) * (a + b) /
               (a * a / (double)(nx - 1) + b * b / (double)(ny - 1));
  double t = (mx - my - ref) / se;
  double p = 2.0 * gsl_cdf_tdist_Q(fabs(t), dof);
  /* Welch interval at 1 - alpha: the test above inverted */
  double q = gsl_cdf_tdist_Qinv(0.5 * SBV_SPRAY_ALPHA, dof) * se;
  sb_comparison c;
  sb_compare(&c, name, SB_RULE_COVER, mx - my, ref, mx - my - q,
             mx - my + q, 1.0 - SBV_SPRAY_ALPHA, p > 1 ? 1 : p);
  return sbv_add(rep, &c);
}

/* mean(x), summed as add_welch does */
static double mean_of(const double *x, size_t n)
{
  double m = 0;
  for (size_t i = 0; i < n; i++)
    m += x[i] / (double)n;
  return m;
}

/* Write mode: the MD replicas as collide files (thermalized, then
 * [species] velocity_scale; snapshots at the steps where the case's
 * sb_engine_run_until(ts[k]) stops).  Each record is mean(stochastic) -
 * mean(engine): the stochastic means (no engine run) are the offsets of
 * "expect-diff-mean" lines, the engine side the mean over the files of
 * the snapshot's anisotropy or of kernel.K / (g K_kin). */
static int engine_write(const sbv_ctx *ctx, sbv_report *rep, size_t Re,
                        size_t ne, double L, double m, double rvdw,
                        double T, double sx, double syz, const double *ts,
                        double gK, const double *As, const double *Ks,
                        size_t Rs)
{
  static const char *mname[2] = {"bird", "nanbu"};
  const double dt = 1e-14;
  long steps[ENG_NT];
  double t = 0.0;
  long nst = 0;
  for (int k = 0; k < ENG_NT; k++) {  /* the engine adds dt per step */
    while (t < ts[k] - 0.5 * dt) {
      t += dt;
      nst++;
    }
    steps[k] = nst;
  }
  int st = SB_SUCCESS;
  for (size_t rr = 0; rr < Re && !st; rr++) {
    char fn[64], name[96], spec[128];
    snprintf(fn, sizeof fn, "V13_spray_vs_engine_r%zu", rr + 1);
    FILE *f = sbv_ini_begin(ctx, rep, fn, "V13: MD helium gas from an "
                            "anisotropic Maxwellian (T_x = 1.6 T, T_y = "
                            "T_z = 0.7 T)");
    if (!f)
      return SB_EIO;
    fprintf(f, "seed = %lu\nrng = mt19937\nL = %.17g\ndt = %.17g\n"
            "t_end = %.17g\nthermalize = %.17g\ndetect = ballistic\n"
            "outcome = elastic\nsnapshot_steps = %ld %ld %ld\n\n"
            "[species He]\nradius = %.17g\nmass = %.17g\ntau = inf\n"
            "T = %.17g\ncount = %zu\nvelocity_scale = %.17g %.17g %.17g\n",
            ctx->seed * 1000 + 500 + rr, L, dt, ts[ENG_NT - 1], T, steps[0],
            steps[1], steps[2], rvdw, m, T, ne, sx, syz, syz);
    st = sbv_ini_end(rep, f, NULL);
    for (int meth = 0; meth < 2 && !st; meth++) {
      for (int k = 0; k < ENG_NT; k++) {
        snprintf(name, sizeof name, "V13/vs-engine/%s/A(t=%gtc)-A_engine",
                 mname[meth], ts[k] / ts[1]);
        snprintf(spec, sizeof spec, "%.17g anisotropy:snap_%06d.csv 1",
                 mean_of(As + (meth * ENG_NT + k) * Rs, Rs), k);
        sbv_ini_expect_stat(rep, "expect-diff-mean", name, spec);
      }
      snprintf(name, sizeof name, "V13/vs-engine/%s/K-K_engine/(gK_kin)",
               mname[meth]);
      snprintf(spec, sizeof spec, "%.17g kernel.K %.17g",
               mean_of(Ks + meth * Rs, Rs), 1.0 / gK);
      sbv_ini_expect_stat(rep, "expect-diff-mean", name, spec);
    }
  }
  return st;
}

int sbv_spray_case_engine(const sbv_ctx *ctx, sbv_report *rep)
{
  const size_t ne = 500, Re = ctx->full ? 24 : 6;
  const size_t Ns = ctx->full ? 20000 : 5000, Rs = ctx->full ? 16 : 6;
  const double T = 300.0, rvdw = 140e-12, M = 4.0;
  const double m = M * 1e-3 / AVOGADRO, d = 2.0 * rvdw;
  const double L = 10e-9 * cbrt((double)ne / 250.0), V = L * L * L;
  const double n = (double)ne / V;
  const double phi = n * 3.14159265358979323846 * d * d * d / 6.0;
  const double g = g_cs(phi), Kth = sb_kernel_kinetic(d, d, m, m, T);
  const double tc = 1.0 / (n * Kth * g); /* engine mean free time */
  const double ts[ENG_NT] = {0.5 * tc, 1.0 * tc, 2.0 * tc};
  const double sx = sqrt(1.6), syz = sqrt(0.7);
  double *Ae = malloc((ENG_NT * Re + ENG_NT * Rs * 2) * sizeof *Ae);
  double *Ke = malloc((Re + 2 * Rs) * sizeof *Ke);
  if (!Ae || !Ke) {
    free(Ae);
    free(Ke);
    return SB_ENOMEM;
  }
  double *As = Ae + ENG_NT * Re, *Ks = Ke + Re;
  int st = SB_SUCCESS;
  /* MD engine replicas (write mode: after the stochastic ones) */
  for (size_t rr = 0; rr < Re && !st && !sbv_writing(ctx); rr++) {
    sb_engine_params p;
    sbv_engine_params(&p);
    p.L[0] = p.L[1] = p.L[2] = L;
    p.dt = 1e-14;
    p.capacity = ne;
    p.seed = ctx->seed * 1000 + 500 + rr;
    sb_engine *e = sb_engine_alloc(&p);
    if (!e) {
      st = SB_ENOMEM;
      break;
    }
    sb_engine_species sp = {rvdw, m, INFINITY, 0.0, T};
    st = sb_engine_add_species(e, &sp, NULL);
    if (!st)
      st = sb_engine_fill_random(e, 0, 0, ne);
    if (!st)
      st = sb_engine_thermalize(e, T);
    const double *x = sb_engine_positions(e), *v = sb_engine_velocities(e);
    for (size_t i = 0; i < ne && !st; i++) {
      double xi[3], vi[3];
      memcpy(xi, x + 3 * i, sizeof xi);
      vi[0] = sx * v[3 * i];
      vi[1] = syz * v[3 * i + 1];
      vi[2] = syz * v[3 * i + 2];
      st = sb_engine_set_particle(e, i, xi, vi);
    }
    for (int k = 0; k < ENG_NT && !st; k++) {
      st = sb_engine_run_until(e, ts[k]);
      Ae[k * Re + rr] = anisotropy(sb_engine_velocities(e), ne);
    }
    if (!st) {
      double K;
      st = sb_engine_kernel(e, 0.95, &K, NULL, NULL);
      Ke[rr] = K / (g * Kth);
    }
    sb_engine_free(e);
  }
  /* stochastic replicas on the same gas, time scaled by g */
  for (int meth = 0; meth < 2 && !st; meth++) {
    gsl_rng *rng = sbv_rng_alloc(ctx, 500 + (unsigned long)meth);
    double r = rvdw, rho = m / ((4.0 / 3.0) * 3.14159265358979323846 * r * r *
                                r);
    for (size_t rr = 0; rr < Rs && !st; rr++) {
      const double Vs = (double)Ns / n;
      sb_spray *s = sbv_spray_new(&(sbv_spray_setup){
          .method = (sb_spray_method)meth, .volume = Vs, .rho_l = rho,
          .capacity = Ns});
      if (!s || !rng) {
        sb_spray_free(s);
        st = SB_ENOMEM;
        break;
      }
      double sd = sqrt(SB_BOLTZMANN * T / m);
      for (size_t i = 0; i < Ns && !st; i++) {
        double v[3] = {sx * gsl_ran_gaussian_ziggurat(rng, sd),
                       syz * gsl_ran_gaussian_ziggurat(rng, sd),
                       syz * gsl_ran_gaussian_ziggurat(rng, sd)};
        st = sb_spray_add(s, v, r, 1.0, 0, NULL);
      }
      double t = 0;
      for (int k = 0; k < ENG_NT && !st; k++) {
        st = sb_spray_collide(s, g * ts[k] - t, rng);
        t = g * ts[k];
        As[(meth * ENG_NT + k) * Rs + rr] =
            anisotropy(sb_spray_velocities(s), Ns);
      }
      sb_spray_stats ss;
      sb_spray_get_stats(s, &ss);
      /* collisions per unit volume and time over K n^2/2 */
      double coll = meth == 0 ? (double)ss.bounces
                              : 0.5 * (double)ss.bounces;
      Ks[meth * Rs + rr] = coll / (Vs * t) / (0.5 * n * n) / Kth;
      sb_spray_free(s);
    }
    gsl_rng_free(rng);
  }
  if (sbv_writing(ctx)) {
    if (!st)
      st = engine_write(ctx, rep, Re, ne, L, m, rvdw, T, sx, syz, ts,
                        g * Kth, As, Ks, Rs);
    free(Ae);
    free(Ke);
    return st;
  }
  static const char *mname[2] = {"bird", "nanbu"};
  char name[96];
  for (int meth = 0; meth < 2 && !st; meth++) {
    for (int k = 0; k < ENG_NT && !st; k++) {
      snprintf(name, sizeof name, "V13/vs-engine/%s/A(t=%gtc)-A_engine",
               mname[meth], ts[k] / tc);
      st = add_welch(rep, name, As + (meth * ENG_NT + k) * Rs, Rs,
                     Ae + k * Re, Re, 0.0);
    }
    if (!st) {
      snprintf(name, sizeof name, "V13/vs-engine/%s/K-K_engine/(gK_kin)",
               mname[meth]);
      st = add_welch(rep, name, Ks + meth * Rs, Rs, Ke, Re, 0.0);
    }
  }
  if (!st) {
    double a0 = 0;
    for (size_t rr = 0; rr < Re; rr++)
      a0 += Ae[rr] / (double)Re;
    sbv_note(rep, "- He (M = 4 g/mol, d = 280 pm), %zu molecules in (%.3g "
             "nm)^3 (the V1 density), T = 300 K, MD dt = 1e-14 s, %zu MD "
             "replicas; stochastic: N = %zu, %zu replicas per method, time "
             "g t with g = %.4f (Carnahan-Starling, phi = %.4f); tc = "
             "1/(n g K_kin) = %.3g s", ne, L * 1e9, Re, Ns, Rs, g, phi, tc);
    sbv_note(rep, "- start: T_x = 1.6 T, T_y = T_z = 0.7 T (A = 0.9); "
             "engine A(tc/2) = %.3f; criterion: Welch t-test of the replica "
             "means, p >= 1e-3", a0);
  }
  free(Ae);
  free(Ke);
  return st;
}
