/* langevin_si.c — SI helpers for Brownian particles: Stokes relaxation time,
 * the velocity-diffusion coefficient B, the Stokes–Einstein diffusion
 * coefficient, Knudsen number and the Cunningham slip correction.
 * Sources are given in langevin.h and docs/langevin.md. */
#include <math.h>

#include <gsl/gsl_math.h>
#include <smolbridge/langevin.h>

#include "common/internal.h"

/* positive and finite */
static int pos(double v) { return v > 0 && isfinite(v); }

double sb_stokes_tau(double rho_p, double d_p, double mu_f, double cc)
{
  if (!pos(rho_p) || !pos(d_p) || !pos(mu_f) || !(cc >= 1) || !isfinite(cc)) {
    sbi_error(SB_EDOM, __func__,
              "rho_p = %g, d_p = %g, mu_f = %g must be positive and cc = %g "
              ">= 1, all finite", rho_p, d_p, mu_f, cc);
    return NAN;
  }
  /* Mohaupt 2011, eq 1.4: tau_p = (rho_p/rho_f) d_p^2 / (18 nu_f),
   * mu = rho nu; the slip correction divides the drag by Cc, so tau_p is
   * multiplied. */
  return rho_p * d_p * d_p * cc / (18.0 * mu_f);
}

double sb_sphere_mass(double rho_p, double d_p)
{
  if (!pos(rho_p) || !pos(d_p)) {
    sbi_error(SB_EDOM, __func__,
              "rho_p = %g, d_p = %g must be positive and finite", rho_p, d_p);
    return NAN;
  }
  return rho_p * M_PI * d_p * d_p * d_p / 6.0;
}

double sb_brownian_B(double T, double m_p, double tau_p)
{
  if (!pos(T) || !pos(m_p) || !pos(tau_p)) {
    sbi_error(SB_EDOM, __func__,
              "T = %g, m_p = %g, tau_p = %g must be positive and finite", T,
              m_p, tau_p);
    return NAN;
  }
  /* Mohaupt 2011, eq A.5: B^2 tau_p / 2 = k_B T / m_p (equipartition) */
  return sqrt(2.0 * SB_BOLTZMANN * T / (m_p * tau_p));
}

double sb_einstein_D(double T, double mu_f, double d_p, double cc)
{
  if (!pos(T) || !pos(mu_f) || !pos(d_p) || !(cc >= 1) || !isfinite(cc)) {
    sbi_error(SB_EDOM, __func__,
              "T = %g, mu_f = %g, d_p = %g must be positive and cc = %g >= 1,"
              " all finite", T, mu_f, d_p, cc);
    return NAN;
  }
  /* Einstein (1905), Stokes mobility Cc / (3 pi mu d) */
  return SB_BOLTZMANN * T * cc / (3.0 * M_PI * mu_f * d_p);
}

double sb_knudsen(double lambda, double d_p)
{
  if (!pos(lambda) || !pos(d_p)) {
    sbi_error(SB_EDOM, __func__,
              "lambda = %g, d_p = %g must be positive and finite", lambda,
              d_p);
    return NAN;
  }
  return 2.0 * lambda / d_p;
}

double sb_cunningham_gen(double kn, double A1, double A2, double A3)
{
  if (!(kn >= 0) || !isfinite(kn) || !isfinite(A1) || !isfinite(A2) ||
      !(A3 >= 0) || !isfinite(A3)) {
    sbi_error(SB_EDOM, __func__,
              "kn = %g must be >= 0, A1 = %g, A2 = %g finite, A3 = %g >= 0",
              kn, A1, A2, A3);
    return NAN;
  }
  if (kn == 0)
    return 1.0; /* continuum limit */
  return 1.0 + kn * (A1 + A2 * exp(-A3 / kn));
}

double sb_cunningham(double kn)
{
  if (!(kn >= 0) || !isfinite(kn)) {
    sbi_error(SB_EDOM, __func__, "kn = %g must be >= 0 and finite", kn);
    return NAN;
  }
  /* Davies (1945) */
  return sb_cunningham_gen(kn, 1.257, 0.400, 1.10);
}

/* ------------------------------------------------ dimensionless numbers */

double sb_kolmogorov_time(double eps, double nu)
{
  if (!pos(eps) || !pos(nu)) {
    sbi_error(SB_EDOM, __func__,
              "eps = %g, nu = %g must be positive and finite", eps, nu);
    return NAN;
  }
  return sqrt(nu / eps); /* Pope (2000), eq 6.1 */
}

double sb_kolmogorov_length(double eps, double nu)
{
  if (!pos(eps) || !pos(nu)) {
    sbi_error(SB_EDOM, __func__,
              "eps = %g, nu = %g must be positive and finite", eps, nu);
    return NAN;
  }
  /* (nu^3/eps)^(1/4) = sqrt(nu) (nu/eps)^(1/4), no overflow of nu^3 */
  return sqrt(nu) * sqrt(sqrt(nu / eps));
}

double sb_stokes_number(double tau_p, double tau_f)
{
  if (!pos(tau_p) || !pos(tau_f)) {
    sbi_error(SB_EDOM, __func__,
              "tau_p = %g, tau_f = %g must be positive and finite", tau_p,
              tau_f);
    return NAN;
  }
  return tau_p / tau_f;
}

double sb_particle_reynolds(double d_p, double w, double nu_f)
{
  if (!pos(d_p) || !(w >= 0) || !isfinite(w) || !pos(nu_f)) {
    sbi_error(SB_EDOM, __func__,
              "d_p = %g, nu_f = %g must be positive and w = %g >= 0, all "
              "finite", d_p, nu_f, w);
    return NAN;
  }
  return w * d_p / nu_f;
}

double sb_collision_speed(double u2)
{
  if (!pos(u2)) {
    sbi_error(SB_EDOM, __func__, "u2 = %g must be positive and finite", u2);
    return NAN;
  }
  /* The relative velocity w is Gaussian with per-component variance
   * s2 = 2 u2; collisions sample it with weight |w| (flux through the
   * contact sphere), so their mean speed is E|w|^2/E|w| =
   * 3 s2 / sqrt(8 s2/pi) = (3/2) sqrt(pi u2). */
  return 1.5 * sqrt(M_PI * u2);
}

double sb_wunsch_dt(double d_p, double u2, double frac)
{
  if (!pos(d_p) || !pos(u2) || !pos(frac)) {
    sbi_error(SB_EDOM, __func__,
              "d_p = %g, u2 = %g, frac = %g must be positive and finite",
              d_p, u2, frac);
    return NAN;
  }
  /* Mohaupt 2011, eq 3.2: (3/2) sqrt(pi T_p) dt_lim / d_p = frac */
  return frac * d_p / sb_collision_speed(u2);
}

double sb_wunsch_dt_brownian(double d_p, double rho_p, double T, double frac)
{
  if (!pos(d_p) || !pos(rho_p) || !pos(T) || !pos(frac)) {
    sbi_error(SB_EDOM, __func__,
              "d_p = %g, rho_p = %g, T = %g, frac = %g must be positive "
              "and finite", d_p, rho_p, T, frac);
    return NAN;
  }
  double m = rho_p * M_PI * d_p * d_p * d_p / 6.0;
  return sb_wunsch_dt(d_p, SB_BOLTZMANN * T / m, frac);
}
