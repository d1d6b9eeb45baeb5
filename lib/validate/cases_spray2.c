/* cases_spray2.c — V14: spray coalescence vs population balances.
 *
 *  V14/spray-coalescence-constant  Maxwell-type kernel B0, every
 *     collision coalesces: the sizes obey Smoluchowski's equation with the
 *     constant kernel K = B0 exactly; n_k and M0 vs the analytic solution
 *     (replica t-tests).
 *  V14/spray-coalescence-gravity   hard spheres moving at their Stokes
 *     settling velocities (a merged drop takes the settling velocity of its
 *     size): B = pi (r_i + r_j)^2 |U_i - U_j| is the gravitational kernel
 *     (sb_kernel_gravity), so the sizes obey Smoluchowski with it; n_k and
 *     M0 vs CVODE (sb_pbe, discrete sizes).
 *  (TAB and Reitz breakup: cases_spray_breakup.c)
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <smolbridge/kernel.h>
#include <smolbridge/pbe.h>
#include <smolbridge/spray.h>
#include <smolbridge/stats.h>

#include "cases.h"
#include "cases_spray.h"

#define PI 3.14159265358979323846

/* Size class k = round(r^3/r1^3) of each parcel: number (sum of weights)
 * per class 1..kmax into nk[0..kmax-1]; returns the total number. */
static double size_counts(const sb_spray *s, double r1, double *nk,
                          size_t kmax)
{
  const double *r = sb_spray_radii(s), *w = sb_spray_weights(s);
  double tot = 0;
  memset(nk, 0, kmax * sizeof *nk);
  for (size_t i = 0; i < sb_spray_count(s); i++) {
    double x = r[i] / r1;
    size_t k = (size_t)llround(x * x * x);
    if (k >= 1 && k <= kmax)
      nk[k - 1] += w[i];
    tot += w[i];
  }
  return tot;
}

/* ============================================ constant kernel (Maxwell) */

#define CC_K 5
int sbv_spray_case_coal_const(const sbv_ctx *ctx, sbv_report *rep)
{
  const size_t N0 = ctx->full ? 100000 : 20000, R = ctx->full ? 16 : 8;
  const double r1 = 1e-5, taus[2] = {1.0, 4.0};
  const size_t ks[CC_K] = {1, 2, 3, 5, 8};
  /* third run: Bird with theta_cr = pi/6, a quarter of the collisions
   * merge (impact parameter below (r + r*)/2), B0 = 4: the same K = 1 */
  static const char *mname[3] = {"bird", "nanbu", "bird-theta=pi/6"};
  double *x = malloc(3 * 2 * (CC_K + 1) * R * sizeof *x);
  double plot[12][5];
  memset(plot, 0, sizeof plot);
  if (!x)
    return SB_ENOMEM;
  int st = SB_SUCCESS;
  for (int meth = 0; meth < 3 && !st; meth++) {
    gsl_rng *rng = sbv_rng_alloc(ctx, 600 + (unsigned long)meth);
    for (size_t rr = 0; rr < R && !st; rr++) {
      const double V = (double)N0; /* n0 = 1 m^-3, tau = B0 sin^2 n0 t = t */
      sb_spray *s = sbv_spray_new(&(sbv_spray_setup){
          .method = meth == 1 ? SB_SPRAY_NANBU : SB_SPRAY_BIRD,
          .B0 = meth == 2 ? 4.0 : 1.0, .volume = V,
          .theta_cr = meth == 2 ? PI / 6.0 : 0.5 * PI, .capacity = N0});
      if (!s || !rng) {
        sb_spray_free(s);
        st = SB_ENOMEM;
        break;
      }
      st = sb_spray_add_maxwellian(s, N0, r1, 1.0, 0, 300.0, NULL, rng);
      double t = 0;
      for (int it = 0; it < 2 && !st; it++) {
        st = sb_spray_collide(s, taus[it] - t, rng);
        t = taus[it];
        double nk[12], M0 = size_counts(s, r1, nk, 12) / V;
        double *row = x + ((meth * 2 + it) * (CC_K + 1)) * R;
        row[rr] = M0 * (1.0 + 0.5 * t);
        for (int q = 0; q < CC_K; q++)
          row[(1 + q) * R + rr] = nk[ks[q] - 1] / V /
                                  sb_pbe_const_mono_n((double)ks[q], t);
        if (it == 1 && meth < 2)
          for (int k = 0; k < 12; k++)
            plot[k][1 + meth] += nk[k] / V / (double)R;
      }
      sb_spray_free(s);
    }
    gsl_rng_free(rng);
    char name[96];
    for (int it = 0; it < 2 && !st; it++) {
      double *row = x + ((meth * 2 + it) * (CC_K + 1)) * R;
      snprintf(name, sizeof name, "V14/coal-const/%s/M0/tau=%g", mname[meth],
               taus[it]);
      st = sbv_spray_add_replicas(rep, name, row, R, 1.0);
      for (int q = 0; q < CC_K && !st; q++) {
        /* a t-test needs near-normal replicas: skip classes with fewer
         * than ~50 expected droplets per replica (n_8 at tau = 1: 4) */
        if ((double)N0 * sb_pbe_const_mono_n((double)ks[q], taus[it]) < 50)
          continue;
        snprintf(name, sizeof name, "V14/coal-const/%s/n_%zu/tau=%g",
                 mname[meth], ks[q], taus[it]);
        st = sbv_spray_add_replicas(rep, name, row + (1 + q) * R, R, 1.0);
      }
    }
  }
  free(x);
  if (st)
    return st;
  for (int k = 0; k < 12; k++) {
    plot[k][0] = k + 1;
    plot[k][3] = sb_pbe_const_mono_n(k + 1.0, taus[1]);
  }
  sbv_note(rep, "- Maxwell-type kernel B0 = 1 m^3/s, theta_cr = pi/2 "
           "(every collision merges), N0 = %zu monomers in V = N0 m^3 "
           "(n0 = 1 m^-3, tau = B0 n0 t), %zu replicas per method; "
           "criterion: replica means of M0 (1 + tau/2) and n_k/n_k,exact "
           "= 1 (t-test p >= 1e-3); n_k exact = (tau/2)^(k-1)/(1 + "
           "tau/2)^(k+1) (sb_pbe_const_mono_n); Nanbu uses the mass-flow "
           "rule (exact mass, variable weights); 'bird-theta=pi/6': B0 = 4 "
           "m^3/s, theta_cr = pi/6, so a fraction sin^2(pi/6) = 1/4 of the "
           "collisions merge (impact parameter <= (r + r*)/2) and K = 1 "
           "again", N0, R);
  sbv_plot(ctx, rep, "V14_coal_constant",
           "V14: size distribution, constant kernel, tau = 4",
           "k bird nanbu exact", &plot[0][0], 12, 4,
           "set logscale y\nset xlabel 'k'\nset ylabel 'n_k/n_0'\nplot "
           "$DATA u 1:2 w p pt 6 t 'Bird', $DATA u 1:3 w p pt 4 t 'Nanbu', "
           "$DATA u 1:4 w l t 'analytic'");
  return SB_SUCCESS;
}

/* ============================================ gravitational kernel */

#define GR_K 6
#define GR_NT 4
int sbv_spray_case_coal_gravity(const sbv_ctx *ctx, sbv_report *rep)
{
  const size_t N0 = ctx->full ? 40000 : 10000, R = ctx->full ? 16 : 6;
  const double r1 = 10e-6, rho = 1000.0, rho_g = 1.2, mu_g = 1.8e-5;
  const double gacc = 9.80665, v1 = 4.0 / 3.0 * PI * r1 * r1 * r1;
  const double frac[4] = {0.4, 0.3, 0.2, 0.1};
  /* n0 such that the 1-2 collision time n0 K(1,2) = 1/s */
  const double r2 = r1 * cbrt(2.0);
  const double K12 = sb_kernel_gravity(r1, r2, rho, rho_g, mu_g, gacc);
  const double n0 = 1.0 / K12, V = (double)N0 / n0;
  const double ts[GR_NT] = {0.125, 0.25, 0.375, 0.5};
  static const char *mname[2] = {"bird", "nanbu"};
  /* CVODE reference, 400 discrete sizes, the tail leaves (the kernel's
   * homogeneity 4/3 > 1 in volume: the infinite system gels at once, so
   * only early times have a truncation-independent solution; the lost
   * mass is reported) */
  sb_kernel_spec ks;
  sb_kernel_spec_init(&ks, SB_KERNEL_GRAVITY);
  ks.rho_p = rho;
  ks.rho_f = rho_g;
  ks.mu = mu_g;
  ks.g = gacc;
  sb_pbe_config c;
  sb_pbe_config_init(&c);
  c.nsizes = 400;
  c.v1 = v1;
  c.kparams = &ks;
  c.rtol = 1e-10;
  c.atol = 1e-14 * n0;
  c.tail = 0;
  sb_pbe *pb = sb_pbe_alloc(&c);
  if (!pb)
    return sb_last_status();
  double nin[400] = {0};
  for (int k = 0; k < 4; k++)
    nin[k] = frac[k] * n0;
  double ref[GR_NT][GR_K + 1], drift = 0;
  int st = sb_pbe_set_initial(pb, nin);
  for (int it = 0; it < GR_NT && !st; it++) {
    sb_pbe_report pr;
    st = sb_pbe_solve(pb, &ts[it], 1, NULL, NULL, &pr);
    drift = pr.m1_drift;
    if (st)
      break;
    double m[3];
    sb_pbe_state_moments(pb, m);
    ref[it][0] = m[0];
    for (int k = 0; k < GR_K; k++)
      ref[it][1 + k] = sb_pbe_state(pb)[k];
    /* restart from the initial state for the next output time */
    st = sb_pbe_set_initial(pb, nin);
  }
  sb_pbe_free(pb);
  if (st) {
    sbv_note(rep, "- CVODE: %s", sb_last_error());
    return st;
  }
  double *x = malloc(2 * GR_NT * (GR_K + 1) * R * sizeof *x);
  if (!x)
    return SB_ENOMEM;
  sb_spray_settling set = {rho, rho_g, mu_g, {0.0, 0.0, -gacc}};
  /* Nanbu's mass-flow parcels drift to the largest sizes for this
   * gelling kernel, which makes its cost grow quickly after t ~ 0.5 */
  for (int meth = 0; meth < 2 && !st; meth++) {
    gsl_rng *rng = sbv_rng_alloc(ctx, 700 + (unsigned long)meth);
    for (size_t rr = 0; rr < R && !st; rr++) {
      sb_spray *s = sbv_spray_new(&(sbv_spray_setup){
          .method = (sb_spray_method)meth, .volume = V, .rho_l = rho,
          .theta_cr = 0.5 * PI, .capacity = N0, .settling = &set});
      if (!s || !rng) {
        sb_spray_free(s);
        st = SB_ENOMEM;
        break;
      }
      /* sizes drawn i.i.d. from the initial fractions */
      for (size_t i = 0; i < N0 && !st; i++) {
        double u = gsl_rng_uniform(rng), acc = 0;
        int k = 0;
        while (k < 3 && u >= (acc += frac[k]))
          k++;
        double r = r1 * cbrt(k + 1.0), v[3];
        sb_spray_stokes_settling(r, v, &set);
        st = sb_spray_add(s, v, r, 1.0, 0, NULL);
      }
      double t = 0;
      for (int it = 0; it < GR_NT && !st; it++) {
        st = sb_spray_collide(s, ts[it] - t, rng);
        t = ts[it];
        double nk[GR_K], M0 = size_counts(s, r1, nk, GR_K) / V;
        double *row = x + ((meth * GR_NT + it) * (GR_K + 1)) * R;
        row[rr] = M0 / ref[it][0];
        for (int k = 0; k < GR_K; k++)
          row[(1 + k) * R + rr] = nk[k] / V / ref[it][1 + k];
      }
      sb_spray_free(s);
    }
    gsl_rng_free(rng);
    char name[96];
    for (int it = 0; it < GR_NT && !st; it++) {
      double *row = x + ((meth * GR_NT + it) * (GR_K + 1)) * R;
      snprintf(name, sizeof name, "V14/coal-gravity/%s/M0/t=%g", mname[meth],
               ts[it]);
      st = sbv_spray_add_replicas(rep, name, row, R, 1.0);
      for (int k = 0; k < GR_K && !st; k++) {
        /* near-normal replicas only: >= 50 expected droplets */
        if (ref[it][1 + k] * V < 50)
          continue;
        snprintf(name, sizeof name, "V14/coal-gravity/%s/n_%d/t=%g",
                 mname[meth], k + 1, ts[it]);
        st = sbv_spray_add_replicas(rep, name, row + (1 + k) * R, R, 1.0);
      }
    }
  }
  free(x);
  if (!st)
    sbv_note(rep, "- water drops r_k = 10 um k^(1/3) in air (rho_g = 1.2 "
             "kg/m^3, mu_g = 1.8e-5 Pa s), Stokes settling, efficiency 1; "
             "initial sizes k = 1..4 with fractions 0.4/0.3/0.2/0.1, "
             "n0 = 1/K(1,2) = %.4g m^-3 (time in units of 1/(n0 K12)), N0 "
             "= %zu, %zu replicas per method; reference: CVODE discrete "
             "population balance with sb_kernel_gravity, 400 sizes, rtol "
             "1e-10, mass lost above size 400 by t = 0.5: %.2g (M0 = %.6g "
             "n0); later times depend on the truncation (gelation)", n0, N0,
             R, drift, ref[GR_NT - 1][0] / n0);
  return st;
}
