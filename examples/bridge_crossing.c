/* bridge_crossing.c — a first look at the bridge references.
 *
 * Two Brownian particles are at distance x at the start of a time step and at
 * distance y at its end; they touch if their separation falls to the contact
 * distance a in between.  The separation of two 3-D Brownian particles is a
 * Bessel-3 bridge, so the touch probability is sb_bes3b_cross_prob.  This
 * program
 *   1. checks the 1-D Brownian-bridge formula against a simulation of bridges
 *      on a grid (with the exact per-sub-step crossing correction), and
 *   2. checks the Bessel-3 hitting-time sampler against the mean of T_a
 *      computed from the survival function by quadrature.
 * It prints each comparison and exits non-zero if one fails.
 *
 * Build: cc bridge_crossing.c $(pkg-config --cflags --libs smolbridge)
 */
#include <math.h>
#include <stdio.h>

#include <gsl/gsl_integration.h>
#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>
#include <smolbridge.h>

enum { NPATH = 20000, NSTEP = 64, NHIT = 50000 };

/* One Brownian bridge from x to y over variance v on a grid of NSTEP
 * sub-steps; returns 1 if it goes below a (between grid points the path is
 * again a Brownian bridge, so each sub-step crosses with the exact
 * probability sb_bb_cross_prob). */
static int bridge_crosses(const gsl_rng *r, double x, double y, double a,
                          double v)
{
  double pos = x, left = v; /* position, remaining variance */
  for (int k = 0; k < NSTEP; k++) {
    double dv = v / NSTEP;
    /* next point of the bridge: Gaussian with the bridge's mean, variance */
    double mean = pos + (y - pos) * dv / left;
    double var = dv * (left - dv) / left;
    double next = k + 1 == NSTEP ? y : mean + sqrt(var) * gsl_ran_gaussian(r, 1.0);
    if (gsl_rng_uniform(r) < sb_bb_cross_prob(pos, next, a, dv))
      return 1;
    pos = next;
    left -= dv;
  }
  return 0;
}

struct hit_args { double x, y, a, sigma2, t; };

static double hit_sf(double u, void *p)
{
  const struct hit_args *h = p;
  return sb_bes3b_hit_sf(u, h->x, h->y, h->a, h->sigma2, h->t);
}

int main(void)
{
  gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
  gsl_rng_set(r, 2024);
  int failures = 0;

  /* 1. Brownian bridge crossing probability vs simulation */
  double x = 1.6, y = 1.3, a = 1.0, v = 0.5;
  unsigned long hits = 0;
  for (int i = 0; i < NPATH; i++)
    hits += bridge_crosses(r, x, y, a, v);
  double lo, hi;
  sb_binomial_ci(hits, NPATH, 0.95, &lo, &hi);
  double p = sb_bb_cross_prob(x, y, a, v);
  int ok = lo <= p && p <= hi;
  failures += !ok;
  printf("Brownian bridge P(min <= a): formula %.6f, simulation %.6f "
         "[%.6f, %.6f] (%d paths): %s\n",
         p, (double)hits / NPATH, lo, hi, NPATH, ok ? "agree" : "DISAGREE");

  /* 2. Bessel-3 bridge: mean hitting time, sampler vs quadrature of the
   *    survival function, E[T] = integral of P(T > u) over [0, t] */
  struct hit_args h = {1.5, 1.2, 1.0, 1.0, 0.8};
  double sum = 0, sum2 = 0;
  for (int i = 0; i < NHIT; i++) {
    double u = sb_bes3b_hit_sample(r, h.x, h.y, h.a, h.sigma2, h.t);
    sum += u;
    sum2 += u * u;
  }
  double mean = sum / NHIT;
  double sem = sqrt((sum2 / NHIT - mean * mean) / (NHIT - 1));
  gsl_integration_workspace *w = gsl_integration_workspace_alloc(200);
  gsl_function F = {hit_sf, &h};
  double ref, err;
  gsl_integration_qags(&F, 0.0, h.t, 0.0, 1e-10, 200, w, &ref, &err);
  gsl_integration_workspace_free(w);
  ok = fabs(mean - ref) <= 1.96 * sem;
  failures += !ok;
  printf("Bessel-3 bridge E[T_a | hit]: quadrature %.6f, sampler %.6f +- "
         "%.6f (%d draws, 95%%): %s\n",
         ref, mean, 1.96 * sem, NHIT, ok ? "agree" : "DISAGREE");
  printf("Bessel-3 bridge P(touch) for x=%g y=%g a=%g v=%g: %.6f\n", h.x, h.y,
         h.a, h.sigma2 * h.t, sb_bes3b_cross_prob(h.x, h.y, h.a, h.sigma2 * h.t));

  gsl_rng_free(r);
  return failures ? 1 : 0;
}
