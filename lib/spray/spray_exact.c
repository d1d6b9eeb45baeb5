/* spray_exact.c — exact solutions the collision operators are checked
 * against: the BKW solution (Bobylev 1975; Krook & Wu 1976) and the
 * two-temperature relaxation of a binary mixture.  Derivations:
 * docs/spray.md, "Exact results". */
#include <math.h>

#include <gsl/gsl_randist.h>
#include <gsl/gsl_sf_gamma.h>

#include <smolbridge/langevin.h>
#include <smolbridge/spray.h>

#include "common/internal.h"
#include "spray_internal.h"

/* M4 - 15 theta^2 = -15 theta^2 (1 - K)^2 decays as exp(-lambda t/3) for
 * isotropic Maxwell scattering, so 1 - K decays as exp(-lambda t/6). */
double sb_spray_bkw_K(double K0, double lambda, double t)
{
  if (!(K0 >= 0.6 && K0 <= 1.0) || !(lambda >= 0) || !(t >= 0)) {
    sbi_error(SB_EDOM, __func__, "need 3/5 <= K0 <= 1, lambda >= 0, t >= 0 "
              "(K0 = %g, lambda = %g, t = %g)", K0, lambda, t);
    return NAN;
  }
  return 1.0 - (1.0 - K0) * exp(-lambda * t / 6.0);
}

static int bkw_dom(double K, double theta, const char *func)
{
  if (!(K >= 0.6 && K <= 1.0) || !(theta > 0) || !isfinite(theta)) {
    sbi_error(SB_EDOM, func, "need 3/5 <= K <= 1 and theta > 0 (K = %g, "
              "theta = %g)", K, theta);
    return 1;
  }
  return 0;
}

double sb_spray_bkw_pdf(double v, double K, double theta)
{
  if (bkw_dom(K, theta, __func__) || isnan(v))
    return NAN;
  double kt = K * theta, x = v * v / (2.0 * kt);
  double a = (5.0 * K - 3.0) / (2.0 * K);
  double b = (1.0 - K) / K;  /* (1-K) v^2/(2 K^2 theta) = b x */
  return pow(2.0 * SBI_PI * kt, -1.5) * exp(-x) * (a + b * x);
}

double sb_spray_bkw_speed_cdf(double s, double K, double theta)
{
  if (bkw_dom(K, theta, __func__) || isnan(s))
    return NAN;
  if (s <= 0)
    return 0.0;
  if (isinf(s))
    return 1.0;
  double x = s * s / (2.0 * K * theta);
  double a = (5.0 * K - 3.0) / (2.0 * K), c = 3.0 * (1.0 - K) / (2.0 * K);
  return a * gsl_sf_gamma_inc_P(1.5, x) + c * gsl_sf_gamma_inc_P(2.5, x);
}

double sb_spray_bkw_m4(double K, double theta)
{
  if (bkw_dom(K, theta, __func__))
    return NAN;
  return theta * theta * K * (30.0 - 15.0 * K);
}

double sb_spray_bkw_m6(double K, double theta)
{
  if (bkw_dom(K, theta, __func__))
    return NAN;
  return theta * theta * theta * K * K * (315.0 - 210.0 * K);
}

/* f = a Maxwell(K theta) + (1 - a) (v^2/(3 K theta)) Maxwell(K theta),
 * a = (5K - 3)/(2K); the second part has a chi-5 speed. */
int sb_spray_bkw_sample(double K, double theta, gsl_rng *rng, double v[3])
{
  if (bkw_dom(K, theta, __func__))
    return SB_EDOM;
  if (!rng || !v)
    return sbi_error(SB_EDOM, __func__, "NULL rng or v");
  double a = (5.0 * K - 3.0) / (2.0 * K);
  double dof = gsl_rng_uniform(rng) < a ? 3.0 : 5.0;
  double sp = sqrt(K * theta * gsl_ran_chisq(rng, dof));
  gsl_ran_dir_3d(rng, &v[0], &v[1], &v[2]);
  for (int k = 0; k < 3; k++)
    v[k] *= sp;
  return SB_SUCCESS;
}

static int mix_check(const sb_spray_mixture *m, const char *func)
{
  if (!m)
    return sbi_error(SB_EDOM, func, "NULL mixture");
  double a[] = {m->n_a, m->n_b, m->m_a, m->m_b, m->T_a0, m->T_b0};
  for (int k = 0; k < 6; k++)
    if (!(a[k] > 0) || !isfinite(a[k]))
      return sbi_error(SB_EDOM, func, "n, m and T must be finite > 0");
  return SB_SUCCESS;
}

/* Delta(t) -> T_a, T_b with n_a T_a + n_b T_b conserved. */
static void split_T(const sb_spray_mixture *m, double delta, double *Ta,
                    double *Tb)
{
  double n = m->n_a + m->n_b;
  double Tm = (m->n_a * m->T_a0 + m->n_b * m->T_b0) / n;
  if (Ta)
    *Ta = Tm + m->n_b / n * delta;
  if (Tb)
    *Tb = Tm - m->n_a / n * delta;
}

/* Isotropic Maxwell scattering: the energy species a gains in an a-b
 * collision, averaged over sigma, is -mu G.g, and E[G.g] = 3 k (T_a -
 * T_b)/(m_a + m_b) for independent species, whatever their laws. */
int sb_spray_two_temp_maxwell(const sb_spray_mixture *mx, double B0,
                              double t, double *T_a, double *T_b)
{
  int st = mix_check(mx, __func__);
  if (st)
    return st;
  if (!(B0 > 0) || !(t >= 0))
    return sbi_error(SB_EDOM, __func__, "B0 = %g, t = %g: need B0 > 0, "
                     "t >= 0", B0, t);
  double M = mx->m_a + mx->m_b;
  double rate = 2.0 * B0 * (mx->n_a + mx->n_b) * mx->m_a * mx->m_b / (M * M);
  split_T(mx, (mx->T_a0 - mx->T_b0) * exp(-rate * t), T_a, T_b);
  return SB_SUCCESS;
}

static double hs_C(const sb_spray_mixture *mx)
{
  double d = mx->r_a + mx->r_b, M = mx->m_a + mx->m_b;
  return (16.0 / 3.0) * sqrt(2.0 / SBI_PI) * SBI_PI * d * d *
         (mx->n_a + mx->n_b) * mx->m_a * mx->m_b / (M * M);
}

double sb_spray_two_temp_hs_rate(const sb_spray_mixture *mx, double T_a,
                                 double T_b)
{
  if (mix_check(mx, __func__) || !(mx->r_a > 0) || !(mx->r_b > 0) ||
      !(T_a > 0) || !(T_b > 0))
    return NAN;
  double s = sqrt(SB_BOLTZMANN * (T_a / mx->m_a + T_b / mx->m_b));
  double n = mx->n_a + mx->n_b;
  return -hs_C(mx) * mx->n_b / n * s * (T_a - T_b);
}

/* dD/dt = -C D sqrt(alpha + beta D), s^2 = alpha + beta D.  With
 * u = sqrt(alpha + beta D): (u - sqrt(alpha))/(u + sqrt(alpha)) =
 * rho0 exp(-C sqrt(alpha) t), and D = 4 alpha rho/(beta (1 - rho)^2),
 * rewritten without the division by beta (which may vanish):
 * D = 4 alpha D0 e/((u0 + sqrt(alpha))^2 (1 - rho)^2), e = exp(-C
 * sqrt(alpha) t), rho = rho0 e, rho0 = beta D0/(u0 + sqrt(alpha))^2. */
int sb_spray_two_temp_hs(const sb_spray_mixture *mx, double t, double *T_a,
                         double *T_b)
{
  int st = mix_check(mx, __func__);
  if (st)
    return st;
  if (!(mx->r_a > 0) || !(mx->r_b > 0) || !(t >= 0))
    return sbi_error(SB_EDOM, __func__, "need r_a, r_b > 0 and t >= 0");
  const double k = SB_BOLTZMANN, n = mx->n_a + mx->n_b;
  double Tm = (mx->n_a * mx->T_a0 + mx->n_b * mx->T_b0) / n;
  double D0 = mx->T_a0 - mx->T_b0;
  double alpha = k * Tm * (1.0 / mx->m_a + 1.0 / mx->m_b);
  double beta = k * (mx->n_b / mx->m_a - mx->n_a / mx->m_b) / n;
  double sa = sqrt(alpha), u0 = sqrt(alpha + beta * D0);
  double q = (u0 + sa) * (u0 + sa);
  double e = exp(-hs_C(mx) * sa * t);
  double rho = beta * D0 / q * e;
  double D = 4.0 * alpha * D0 * e / (q * (1.0 - rho) * (1.0 - rho));
  split_T(mx, D, T_a, T_b);
  return SB_SUCCESS;
}
