/* spray_outcome.c — what happens in one collision: pair rate, post-
 * collision velocities for unequal masses, the impact-parameter
 * coalescence test, and the Stokes settling velocity rule.  Pure
 * functions (no state). */
#include <float.h>
#include <math.h>

#include <smolbridge/spray.h>

#include "common/internal.h"
#include "common/numutil.h"
#include "spray_internal.h"

double sb_spray_pair_rate(sb_spray_cross c, double B0, double r1, double r2,
                          double g)
{
  if (c == SB_SPRAY_MAXWELL) {
    if (!(B0 > 0) || !isfinite(B0)) {
      sbi_error(SB_EDOM, __func__, "B0 = %g: must be finite > 0", B0);
      return NAN;
    }
    return B0;
  }
  if (!(r1 >= 0) || !(r2 >= 0) || !(g >= 0) || !isfinite(r1) ||
      !isfinite(r2) || !isfinite(g)) {
    sbi_error(SB_EDOM, __func__, "need finite r1, r2, g >= 0 (r1 = %g, "
              "r2 = %g, g = %g)", r1, r2, g);
    return NAN;
  }
  double d = r1 + r2;
  double B = SBI_PI * d * d * g;
  if ((!(B >= DBL_MIN) && g > 0 && d > 0) || isinf(B)) {
    /* d^2 or the product over/underflows: the same chain with an
     * extended exponent (same bits in the normal range) */
    sbi_xd xd = sbi_xd_add(sbi_xd_of(r1), sbi_xd_of(r2));
    B = sbi_xd_val(sbi_xd_mul(sbi_xd_mul(sbi_xd_mul(sbi_xd_of(SBI_PI), xd),
                                          xd), sbi_xd_of(g)));
    if (isinf(B)) {
      sbi_error(SB_ERANGE, __func__, "pi (r1 + r2)^2 g overflows (r1 = %g, "
                "r2 = %g, g = %g)", r1, r2, g);
      return NAN;
    }
  }
  return B;
}

/* In the centre-of-mass frame the relative velocity keeps its modulus and
 * turns to |g| sigma; v = G + m2/M g, v* = G - m1/M g (Baranger, thesis
 * slides, with m proportional to r^3).  Momentum m1 v1 + m2 v2 = M G and
 * energy M |G|^2/2 + mu |g|^2/2 are unchanged. */
void sb_spray_post_collision(const double v1[3], const double v2[3],
                             double m1, double m2, const double sigma[3],
                             double v1p[3], double v2p[3])
{
  double M = m1 + m2, a1 = m1 / M, a2 = m2 / M;
  double G[3], g2 = 0.0;
  for (int k = 0; k < 3; k++) {
    double g = v1[k] - v2[k];
    g2 += g * g;
    G[k] = a1 * v1[k] + a2 * v2[k];
  }
  double g = sqrt(g2);
  for (int k = 0; k < 3; k++) {
    double gs = g * sigma[k];
    v1p[k] = G[k] + a2 * gs;
    v2p[k] = G[k] - a1 * gs;
  }
}

/* Hard-sphere geometry: b = (r + r*) cos(chi/2), so
 * (b/(r + r*))^2 = (1 + cos chi)/2; coalescence iff b <= (r + r*) sin
 * theta_cr, i.e. chi in [pi - 2 theta_cr, pi] as in the thesis's
 * coalescence term. */
int sb_spray_coalesces(double cos_chi, double theta_cr)
{
  /* an int result has no NaN: 0 with SB_EDOM recorded (header) */
  if (isnan(cos_chi) || isnan(theta_cr) || isinf(theta_cr)) {
    sbi_error(SB_EDOM, __func__, "cos_chi = %g, theta_cr = %g: NaN or an "
              "infinite angle", cos_chi, theta_cr);
    return 0;
  }
  if (!(theta_cr > 0))
    return 0;
  double s = sin(theta_cr);
  return 0.5 * (1.0 + cos_chi) <= s * s;
}

/* O'Rourke (1981): the pair coalesces unless the rotational energy of the
 * combined drop exceeds the surface energy it needs to separate
 * (Brazier-Smith et al. 1972), which gives b_cr^2/(r1 + r2)^2 =
 * 2.4 f(gamma)/We, capped at 1 (gamma = r_large/r_small, We on the small
 * drop's radius and the liquid density). */
double sb_spray_orourke_b2(double r1, double r2, double g, double rho_l,
                           double sigma)
{
  if (!(r1 > 0) || !(r2 > 0) || !(g >= 0) || !(rho_l > 0) || !(sigma > 0) ||
      !isfinite(r1) || !isfinite(r2) || !isfinite(g) || !isfinite(rho_l) ||
      !isfinite(sigma)) {
    sbi_error(SB_EDOM, __func__, "need r1, r2, rho_l, sigma > 0, g >= 0");
    return NAN;
  }
  double rs = fmin(r1, r2), gam = fmax(r1, r2) / rs;
  double f = gam * (gam * (gam - 2.4) + 2.7); /* > 0 for all gamma */
  /* 2.4 f/We = 2.4 f sigma/(rho_l g^2 r_s), compared without dividing
   * (g = 0 is allowed) */
  double num = 2.4 * f * sigma, den = rho_l * g * g * rs;
  if (g > 0 && !(num >= DBL_MIN && den >= DBL_MIN && isfinite(num) &&
                 isfinite(den))) {
    /* gamma^3, g^2 or a product over/underflows: the ratio with an
     * extended exponent (q >= 1 iff its exponent is >= 1) */
    sbi_xd G = sbi_xd_div(sbi_xd_of(fmax(r1, r2)), sbi_xd_of(rs));
    sbi_xd F = sbi_xd_mul(
        G, sbi_xd_add(sbi_xd_mul(G, sbi_xd_add(G, sbi_xd_of(-2.4))),
                      sbi_xd_of(2.7)));
    sbi_xd N = sbi_xd_mul(sbi_xd_mul(sbi_xd_of(2.4), F), sbi_xd_of(sigma));
    sbi_xd D = sbi_xd_mul(sbi_xd_mul(sbi_xd_mul(sbi_xd_of(rho_l),
                                                sbi_xd_of(g)),
                                     sbi_xd_of(g)),
                          sbi_xd_of(rs));
    sbi_xd q = sbi_xd_div(N, D);
    return q.e >= 1 ? 1.0 : sbi_xd_val(q);
  }
  return num >= den ? 1.0 : num / den;
}

void sb_spray_stokes_settling(double r, double v[3], void *ctx)
{
  const sb_spray_settling *p = ctx;
  double g = sqrt(p->gvec[0] * p->gvec[0] + p->gvec[1] * p->gvec[1] +
                  p->gvec[2] * p->gvec[2]);
  if (!(g > 0)) {
    v[0] = v[1] = v[2] = 0.0;
    return;
  }
  double U = 2.0 * (p->rho_l - p->rho_g) * g * r * r / (9.0 * p->mu_g);
  for (int k = 0; k < 3; k++)
    v[k] = U * p->gvec[k] / g;
}
