/* langevin_si.c — SI helpers for Brownian particles: Stokes relaxation time,
 * the velocity-diffusion coefficient B, the Stokes–Einstein diffusion
 * coefficient, Knudsen number and the Cunningham slip correction.
 * Sources are given in langevin.h and docs/langevin.md. */
#include <math.h>

#include <gsl/gsl_math.h>
#include <smolbridge/langevin.h>

#include "common/internal.h"
#include "common/numutil.h"

/* positive and finite */
static int pos(double v) { return v > 0 && isfinite(v); }

/* The helpers are products and quotients of their arguments, evaluated in
 * sbi_xd arithmetic (numutil.h): the same operations in the same order as
 * the plain formulas, so the same bits wherever nothing over/underflows,
 * and the right value wherever it is a double when an intermediate such
 * as d_p^3 or nu/eps leaves the double range. */
#define X(x) sbi_xd_of(x)
#define MUL(a, b) sbi_xd_mul((a), (b))
#define DIV(a, b) sbi_xd_div((a), (b))
#define SQRT(a) sbi_xd_sqrt(a)

/* rho_p pi d_p^3 / 6 */
static sbi_xd sphere_mass(double rho_p, double d_p)
{
  return DIV(MUL(MUL(MUL(MUL(X(rho_p), X(M_PI)), X(d_p)), X(d_p)), X(d_p)),
             X(6.0));
}

/* (3/2) sqrt(pi u2) */
static sbi_xd collision_speed(sbi_xd u2)
{
  return MUL(X(1.5), SQRT(MUL(X(M_PI), u2)));
}

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
  return sbi_xd_checked(DIV(MUL(MUL(MUL(X(rho_p), X(d_p)), X(d_p)), X(cc)),
                            MUL(X(18.0), X(mu_f))),
                        __func__);
}

double sb_sphere_mass(double rho_p, double d_p)
{
  if (!pos(rho_p) || !pos(d_p)) {
    sbi_error(SB_EDOM, __func__,
              "rho_p = %g, d_p = %g must be positive and finite", rho_p, d_p);
    return NAN;
  }
  return sbi_xd_checked(sphere_mass(rho_p, d_p), __func__);
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
  return sbi_xd_checked(SQRT(DIV(MUL(X(2.0 * SB_BOLTZMANN), X(T)),
                                 MUL(X(m_p), X(tau_p)))),
                        __func__);
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
  return sbi_xd_checked(DIV(MUL(MUL(X(SB_BOLTZMANN), X(T)), X(cc)),
                            MUL(MUL(X(3.0 * M_PI), X(mu_f)), X(d_p))),
                        __func__);
}

double sb_knudsen(double lambda, double d_p)
{
  if (!pos(lambda) || !pos(d_p)) {
    sbi_error(SB_EDOM, __func__,
              "lambda = %g, d_p = %g must be positive and finite", lambda,
              d_p);
    return NAN;
  }
  return sbi_xd_checked(DIV(MUL(X(2.0), X(lambda)), X(d_p)), __func__);
}

/* 1 + kn (A1 + A2 exp(-A3/kn)); NaN and SB_ERANGE (for func) where it
 * overflows (kn or A1, A2 near DBL_MAX) */
static double cunningham(double kn, double A1, double A2, double A3,
                         const char *func)
{
  if (kn == 0)
    return 1.0; /* continuum limit */
  const double cc = 1.0 + kn * (A1 + A2 * exp(-A3 / kn));
  if (isfinite(cc))
    return cc;
  sbi_error(SB_ERANGE, func, "kn = %g, A1 = %g, A2 = %g: the correction "
            "overflows a double", kn, A1, A2);
  return NAN;
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
  return cunningham(kn, A1, A2, A3, __func__);
}

double sb_cunningham(double kn)
{
  if (!(kn >= 0) || !isfinite(kn)) {
    sbi_error(SB_EDOM, __func__, "kn = %g must be >= 0 and finite", kn);
    return NAN;
  }
  /* Davies (1945) */
  return cunningham(kn, 1.257, 0.400, 1.10, __func__);
}

/* ------------------------------------------------ dimensionless numbers */

double sb_kolmogorov_time(double eps, double nu)
{
  if (!pos(eps) || !pos(nu)) {
    sbi_error(SB_EDOM, __func__,
              "eps = %g, nu = %g must be positive and finite", eps, nu);
    return NAN;
  }
  /* Pope (2000), 6.1 */
  return sbi_xd_checked(SQRT(DIV(X(nu), X(eps))), __func__);
}

double sb_kolmogorov_length(double eps, double nu)
{
  if (!pos(eps) || !pos(nu)) {
    sbi_error(SB_EDOM, __func__,
              "eps = %g, nu = %g must be positive and finite", eps, nu);
    return NAN;
  }
  /* (nu^3/eps)^(1/4) = sqrt(nu) (nu/eps)^(1/4), no overflow of nu^3 */
  return sbi_xd_checked(MUL(SQRT(X(nu)), SQRT(SQRT(DIV(X(nu), X(eps))))),
                        __func__);
}

double sb_stokes_number(double tau_p, double tau_f)
{
  if (!pos(tau_p) || !pos(tau_f)) {
    sbi_error(SB_EDOM, __func__,
              "tau_p = %g, tau_f = %g must be positive and finite", tau_p,
              tau_f);
    return NAN;
  }
  return sbi_xd_checked(DIV(X(tau_p), X(tau_f)), __func__);
}

double sb_particle_reynolds(double d_p, double w, double nu_f)
{
  if (!pos(d_p) || !(w >= 0) || !isfinite(w) || !pos(nu_f)) {
    sbi_error(SB_EDOM, __func__,
              "d_p = %g, nu_f = %g must be positive and w = %g >= 0, all "
              "finite", d_p, nu_f, w);
    return NAN;
  }
  return sbi_xd_checked(DIV(MUL(X(w), X(d_p)), X(nu_f)), __func__);
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
  return sbi_xd_checked(collision_speed(X(u2)), __func__);
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
  return sbi_xd_checked(DIV(MUL(X(frac), X(d_p)), collision_speed(X(u2))),
                        __func__);
}

double sb_wunsch_dt_brownian(double d_p, double rho_p, double T, double frac)
{
  if (!pos(d_p) || !pos(rho_p) || !pos(T) || !pos(frac)) {
    sbi_error(SB_EDOM, __func__,
              "d_p = %g, rho_p = %g, T = %g, frac = %g must be positive "
              "and finite", d_p, rho_p, T, frac);
    return NAN;
  }
  /* sb_wunsch_dt with u2 = k_B T / m, m = rho_p pi d_p^3/6 */
  const sbi_xd u2 = DIV(MUL(X(SB_BOLTZMANN), X(T)), sphere_mass(rho_p, d_p));
  return sbi_xd_checked(DIV(MUL(X(frac), X(d_p)), collision_speed(u2)),
                        __func__);
}
