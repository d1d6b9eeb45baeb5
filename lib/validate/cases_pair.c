/* cases_pair.c — `smolbridge validate` case V17/pair-diffusivity: the
 * contact-value conjecture for turbulent pair diffusion (Mohaupt 2011,
 * §6.3.2 and §7.1.1; docs/kernel.md, "Separation-dependent pair
 * diffusivity").
 *
 * The bridge algorithm for turbulence (V7) moves a pair with the relative
 * diffusivity frozen at its contact value b2(R), although in the
 * dissipative range it grows as r^2 (Brunk, Koch & Lion 1998; Mohaupt 2011,
 * eq 6.13).  Here the relative position X of one pair is integrated in 3-D
 * with the separation-dependent per-component variance rate
 *   b2(r) = b2_0 + b2_2 (r/R)^2,   kappa = b2/2,
 * as the Ito SDE dX = grad(kappa) dt + sqrt(b2(|X|)) dW (the drift makes
 * the uniform pair density stationary: dc/dt = div(kappa grad c)), by
 * Euler–Maruyama steps whose continuous interpolation is checked for a
 * contact with the Bessel-3 bridge crossing probability (exact for
 * constant b2: the bridge algorithm itself).  Units: R = 1 and
 * b2(R) = b2_0 + b2_2 = 1.
 *
 * Rate protocol (Northrup, Allison & McCammon 1984, with the outer
 * surface treated analytically as by Luty, McCammon & Zhou 1992): a
 * trajectory starts on the sphere r = b; it ends with a contact (r <= R,
 * or a bridge crossing) or, when a step ends at r' >= q, returns to the
 * sphere b with the exact probability K_D(b)/K_D(r') (K_D(x) the steady
 * rate onto the sphere x: sb_kernel_diffusion_r2) and otherwise escapes.
 * The fraction of trajectories that make contact estimates
 * P = K_inf/K_D(b), K_inf = sb_kernel_diffusion_r2(R, b2_0, b2_2) the
 * steady rate of the infinite system, so K_e = K_D(b) k/n with the exact
 * binomial test and Clopper–Pearson interval of k out of n (rows
 * K_e/K_exact).  The simulated region R < r < q is where the
 * separation dependence, the drift and the contact detection act.
 *
 * Rows: constant b2 (the bridge algorithm at two large steps) against
 * Smoluchowski 2 pi b2 R; b2 ~ r^2 at two fine steps (step convergence),
 * two Brownian + turbulent mixtures (V7's set-up and a Brownian-dominated
 * one) against the exact rate; the same without the Ito drift (expected
 * failure, shown); and, informational, the conjecture: the measured rate
 * over the frozen-contact rate 2 pi b2(R) R (= K_co + K_ST, what V7
 * reproduces), and over Saffman–Turner.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include <gsl/gsl_math.h>
#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>

#include <smolbridge/bridge.h>
#include <smolbridge/kernel.h>
#include <smolbridge/stats.h>

#include "cases.h"

#define TEMP_V7 296.15 /* K, Mohaupt 2011, Table 6.1 */

typedef struct {
  double b0, b2;    /* b2(r) = b0 + b2 r^2 (R = 1) */
  double dt;        /* step, units R^2/b2(R) */
  int drift;        /* 1: Ito drift grad kappa = b2 X (0: left out) */
  double b, q;      /* start and escape radii */
  unsigned long n;  /* trajectories */
} prun;

typedef struct {
  unsigned long hits, n;
  double steps;     /* Euler steps taken in all */
  double KDb, Kinf; /* K_D(b), exact steady rate */
} pout;

/* steady rate onto the sphere of radius x of the model (R = 1) */
static double k_sphere(const prun *p, double x)
{
  return sb_kernel_diffusion_r2(x, p->b0, p->b2 * x * x);
}

/* One pair's relative motion until contact (1) or escape (0). */
static int trajectory(const prun *p, gsl_rng *rng, double KDb, double *steps)
{
  const double R = 1.0;
  double X[3] = {p->b, 0.0, 0.0};
  double r = p->b;
  for (;;) {
    double bb = p->b0 + p->b2 * r * r;
    double v = bb * p->dt, s = sqrt(v);
    double f = p->drift ? 1.0 + p->b2 * p->dt : 1.0;
    double Y[3];
    for (int k = 0; k < 3; k++)
      Y[k] = f * X[k] + s * gsl_ran_gaussian_ziggurat(rng, 1.0);
    double rn = sqrt(Y[0] * Y[0] + Y[1] * Y[1] + Y[2] * Y[2]);
    *steps += 1.0;
    if (rn <= R)
      return 1;
    /* Bessel-3 bridge crossing of R between r and rn; below e^-40 the
     * draw cannot matter (the exponent 2(r-R)(rn-R)/v screens it) */
    if (2.0 * (r - R) * (rn - R) < 40.0 * v) {
      double P = sb_bes3b_cross_prob(r, rn, R, v);
      if (gsl_rng_uniform(rng) < P)
        return 1;
    }
    if (rn >= p->q) {
      /* outside: return to the sphere b with probability K_D(b)/K_D(rn) */
      if (gsl_rng_uniform(rng) >= KDb / k_sphere(p, rn))
        return 0;
      X[0] = p->b;
      X[1] = X[2] = 0.0;
      r = p->b;
      continue;
    }
    X[0] = Y[0];
    X[1] = Y[1];
    X[2] = Y[2];
    r = rn;
  }
}

static int run(const sbv_ctx *ctx, unsigned long stream, const prun *p,
               pout *o)
{
  gsl_rng *rng = sbv_rng_alloc(ctx, stream);
  if (!rng)
    return SB_ENOMEM;
  o->KDb = k_sphere(p, p->b);
  o->Kinf = sb_kernel_diffusion_r2(1.0, p->b0, p->b2);
  o->hits = 0;
  o->n = p->n;
  o->steps = 0.0;
  for (unsigned long i = 0; i < p->n; i++)
    o->hits += (unsigned long)trajectory(p, rng, o->KDb, &o->steps);
  gsl_rng_free(rng);
  return SB_SUCCESS;
}

/* K_e/K_exact row: exact binomial test of the contact count against
 * P = K_inf/K_D(b) and its Clopper-Pearson interval, both scaled by
 * K_D(b)/K_inf (the verdict is unchanged by the scaling). */
static int add_rate(sbv_report *rep, const char *name, const pout *o,
                    sb_comparison *c)
{
  double P = o->Kinf / o->KDb;
  sb_compare_binomial(c, name, o->hits, o->n, P, SBV_ALPHA);
  double f = 1.0 / P;
  c->estimate *= f;
  c->reference *= f;
  c->ci_low *= f;
  c->ci_high *= f;
  return sbv_add(rep, c);
}

/* Informational row: the measured rate (with its interval) over `den`. */
static int add_ratio_info(sbv_report *rep, const char *name,
                          const sb_comparison *c, const pout *o, double den)
{
  double k = o->Kinf / den; /* c holds K_e/K_inf */
  return sbv_add_info(rep, name, c->estimate * k, 1.0, c->ci_low * k,
                      c->ci_high * k, c->level);
}

static int case_pair(const sbv_ctx *ctx, sbv_report *rep)
{
  const unsigned long m = ctx->full ? 10 : 1;
  const double b = 1.5, q = 4.0;
  /* V7's set-up (Mohaupt 2011, Table 6.1): d = 1 um in water, eps =
   * 1e-4 m^2/s^3, 296.15 K; Brownian b2 of the pair and turbulent b2 at
   * contact, per Mohaupt 2011, eqs 6.17 and 6.22 */
  const double d = 1e-6, mu = 1e-3, nu = 1e-6, eps = 1e-4;
  double bB = 2.0 * sb_brownian_b2(0.5 * d, TEMP_V7, mu);
  double bT = sb_turb_pair_b2(d, eps, nu);
  double a7 = bT / bB;
  struct {
    const char *tag;
    double b0, b2, dt;
    int drift;
    unsigned long n;
  } runs[] = {
      {"constant-D/dt=0.05", 1.0, 0.0, 0.05, 1, 20000},
      {"constant-D/dt=0.5", 1.0, 0.0, 0.5, 1, 20000},
      {"r2/dt=2e-3", 0.0, 1.0, 2e-3, 1, 16000},
      {"r2/dt=5e-4", 0.0, 1.0, 5e-4, 1, 6000},
      {"r2/dt=2e-3/no-Ito-drift", 0.0, 1.0, 2e-3, 0, 1000},
      {"mix-V7/dt=2e-3", 1.0 / (1.0 + a7), a7 / (1.0 + a7), 2e-3, 1, 12000},
      {"mix-a=0.1/dt=2e-3", 1.0 / 1.1, 0.1 / 1.1, 2e-3, 1, 12000},
  };
  enum { NRUN = sizeof runs / sizeof runs[0] };
  sbv_note(rep, "Relative position of one pair, b2(r) = b2_0 + b2_2 "
           "(r/R)^2 with R = 1 and b2(R) = 1 (time unit R^2/b2(R)); "
           "Euler-Maruyama with the Ito drift grad kappa = b2_2 X, contact "
           "by the Bessel-3 bridge crossing probability; start on r = %g, "
           "return from r' >= %g with probability K_D(b)/K_D(r') "
           "(Northrup-Allison-McCammon protocol).  K_e = K_D(b) k/n; rule: "
           "exact binomial test of k at 1e-4 (Clopper-Pearson interval, "
           "scaled).", b, q);
  sbv_note(rep, "V7 set-up (d = 1 um, water, eps = 1e-4, 296.15 K): "
           "Brownian pair b2 = %.4g m^2/s, turbulent b2(d) = %.4g m^2/s, "
           "a = b2_2/b2_0 = %.4f.", bB, bT, a7);
  int st = SB_SUCCESS;
  sb_comparison c[NRUN];
  pout o[NRUN];
  for (int i = 0; i < NRUN && !st; i++) {
    prun p = {runs[i].b0, runs[i].b2, runs[i].dt, runs[i].drift, b, q,
              runs[i].n * m};
    sbv_progress(ctx, "V17 %s: %lu trajectories", runs[i].tag, p.n);
    st = run(ctx, 1700 + (unsigned long)i, &p, &o[i]);
    if (st)
      break;
    char name[96];
    snprintf(name, sizeof name, "V17/%s/K_e/K_exact", runs[i].tag);
    if (runs[i].drift) {
      st = add_rate(rep, name, &o[i], &c[i]);
    } else {
      /* expected failure: without the drift the pair density is not
       * uniform (it relaxes to ~ 1/kappa) and contacts are too many */
      double P = o[i].Kinf / o[i].KDb;
      sb_compare_binomial(&c[i], name, o[i].hits, o[i].n, P, SBV_ALPHA);
      double f = 1.0 / P;
      st = sbv_add_side(rep, name, 1, c[i].estimate * f, 1.0,
                        c[i].ci_low * f, c[i].ci_high * f, c[i].level,
                        c[i].p_value);
    }
    sbv_note(rep, "%s: %lu of %lu trajectories made contact, %.0f steps; "
             "K_e/K_exact = %.4f [%.4f, %.4f] (%.2f%%), K_exact = %.5f "
             "(2 pi b2(R) R = %.5f)", runs[i].tag, o[i].hits, o[i].n,
             o[i].steps, c[i].estimate / c[i].reference,
             c[i].ci_low / c[i].reference, c[i].ci_high / c[i].reference,
             100.0 * (1.0 - c[i].level), o[i].Kinf, 2.0 * M_PI);
  }
  if (st)
    return st;
  /* the conjecture: separation-dependent rate over the frozen-contact
   * rate 2 pi b2(R) R = 2 pi (what the bridge algorithm and V7 give) */
  const int conj[3] = {2, 5, 6};
  const char *ctag[3] = {"r2", "mix-V7", "mix-a=0.1"};
  for (int j = 0; j < 3 && !st; j++) {
    char name[96];
    snprintf(name, sizeof name, "V17/conjecture/%s/K(D(r))/K(D(R))",
             ctag[j]);
    st = add_ratio_info(rep, name, &c[conj[j]], &o[conj[j]], 2.0 * M_PI);
    sbv_note(rep, "conjecture, %s: exact K(D(r))/K(D(R)) = %.4f", ctag[j],
             o[conj[j]].Kinf / (2.0 * M_PI));
  }
  if (!st) /* pure turbulence: frozen contact rate = Saffman-Turner */
    st = add_ratio_info(rep, "V17/conjecture/r2/K(D(r))/K_ST", &c[2], &o[2],
                        2.0 * M_PI);
  if (!st) {
    double Kr = sb_kernel_brownian_turb_r2(0.5 * d, 0.5 * d, TEMP_V7, mu,
                                           eps, nu);
    double Kc = sb_kernel_brownian_turb(0.5 * d, 0.5 * d, TEMP_V7, mu, eps,
                                        nu);
    sbv_note(rep, "V7 set-up in SI: K with b2(r) = %.4g m^3/s, frozen at "
             "contact (K_co + K_ST) = %.4g m^3/s, ratio %.4f", Kr, Kc,
             Kr / Kc);
  }
  if (st)
    return st;
  /* plot: exact ratio vs a = b2_2/b2_0 and the measured points */
  enum { NC = 61 };
  double pl[(NC + 3) * 5];
  for (int i = 0; i < NC; i++) {
    double a = pow(10.0, -3.0 + 0.1 * i);
    double r = sb_kernel_diffusion_r2(1.0, 1.0, a) / (2.0 * M_PI * (1 + a));
    double *row = pl + 5 * i;
    row[0] = a;
    row[1] = r;
    row[2] = row[3] = row[4] = NAN;
  }
  const double apt[3] = {1e3, a7, 0.1}; /* pure r^2 drawn at a = 1e3 */
  for (int j = 0; j < 3; j++) {
    double *row = pl + 5 * (NC + j);
    double k = o[conj[j]].Kinf / (2.0 * M_PI);
    row[0] = apt[j];
    row[1] = NAN;
    row[2] = c[conj[j]].estimate * k;
    row[3] = c[conj[j]].ci_low * k;
    row[4] = c[conj[j]].ci_high * k;
  }
  sbv_plot(ctx, rep, "V17_pair_diffusivity",
           "V17: steady rate with b2(r) = b2_0 + b2_2 (r/R)^2 over the "
           "rate at the contact value (the conjecture: 1); curve exact, "
           "points Monte Carlo (pure r^2 drawn at a = 1e3)",
           "a K(D(r))/K(D(R))_exact mc lo hi", pl, NC + 3, 5,
           "set logscale x\nset xlabel 'a = b2_2/b2_0 (turbulent/Brownian "
           "at contact)'\nset ylabel 'K(D(r)) / K(D(R))'\n"
           "set yrange [0.9:3.1]\nset key left\n"
           "plot '$DATA' u 1:2 w l lw 2 t 'exact', '' u 1:3:4:5 w "
           "yerrorbars pt 7 t 'fine-step Monte Carlo', 1 dt 2 t "
           "'conjecture', 3 dt 3 t 'pure r^2'\n");
  return SB_SUCCESS;
}

const sbv_case sbv_cases_pair[] = {
    {"V17/pair-diffusivity",
     "pair diffusivity growing as r^2 vs frozen at contact: fine-step SDE "
     "rate vs the exact steady rate (Mohaupt 2011, §6.3, §7.1.1)",
     case_pair},
};
const size_t sbv_ncases_pair = sizeof sbv_cases_pair / sizeof sbv_cases_pair[0];
