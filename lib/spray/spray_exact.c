/* spray_exact.c — exact solutions the collision operators are checked
 * against: the BKW solution (Bobylev 1975; Krook & Wu 1976) and the
 * two-temperature relaxation of a binary mixture.  Derivations:
 * docs/spray.md, "Exact results". */
#include <float.h>
#include <math.h>

#include <gsl/gsl_randist.h>
#include <gsl/gsl_sf_gamma.h>

#include <smolbridge/langevin.h>
#include <smolbridge/spray.h>

#include "common/internal.h"
#include "common/numutil.h"
#include "spray_internal.h"

/* M4 - 15 theta^2 = -15 theta^2 (1 - K)^2 decays as exp(-lambda t/3) for
 * isotropic Maxwell scattering, so 1 - K decays as exp(-lambda t/6). */
double sb_spray_bkw_K(double K0, double lambda, double t)
{
  if (!(K0 >= 0.6 && K0 <= 1.0) || !(lambda >= 0) || !(t >= 0) ||
      !isfinite(lambda) || !isfinite(t)) {
    sbi_error(SB_EDOM, __func__, "need 3/5 <= K0 <= 1, finite lambda >= 0, "
              "t >= 0 (K0 = %g, lambda = %g, t = %g)", K0, lambda, t);
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

/* Scalar arguments other than K and theta: not NaN. */
static int arg_dom(double v, const char *func)
{
  if (isnan(v)) {
    sbi_error(SB_EDOM, func, "argument is NaN");
    return 1;
  }
  return 0;
}

double sb_spray_bkw_pdf(double v, double K, double theta)
{
  if (bkw_dom(K, theta, __func__) || arg_dom(v, __func__))
    return NAN;
  double kt = K * theta, x = v * v / (2.0 * kt);
  double a = (5.0 * K - 3.0) / (2.0 * K);
  double b = (1.0 - K) / K;  /* (1-K) v^2/(2 K^2 theta) = b x */
  double f = pow(2.0 * SBI_PI * kt, -1.5) * exp(-x) * (a + b * x);
  if (f >= DBL_MIN && f <= DBL_MAX)
    return f;
  /* x = inf or > 1e6: e^{-x} beats every prefactor (< 2^1700) */
  if (!(x < 1e6))
    return 0.0;
  /* (2 pi K theta)^{-3/2} or e^{-x} leaves the range: extended exponent */
  sbi_xd q = sbi_xd_mul(sbi_xd_mul(sbi_xd_of(2.0 * SBI_PI), sbi_xd_of(K)),
                        sbi_xd_of(theta));
  sbi_xd p = sbi_xd_div(sbi_xd_of(1.0), sbi_xd_mul(q, sbi_xd_sqrt(q)));
  f = sbi_xd_val(sbi_xd_mul(sbi_xd_mul(p, sbi_xd_expneg(x)),
                            sbi_xd_of(a + b * x)));
  if (isinf(f)) {
    sbi_error(SB_ERANGE, __func__, "f(%g) overflows (K theta = %g)", v, kt);
    return NAN;
  }
  return f;
}

double sb_spray_bkw_speed_cdf(double s, double K, double theta)
{
  if (bkw_dom(K, theta, __func__) || arg_dom(s, __func__))
    return NAN;
  if (s <= 0)
    return 0.0;
  if (isinf(s))
    return 1.0;
  double x = s * s / (2.0 * K * theta);
  if (isinf(x))
    return 1.0; /* 1 - P < e^{-x} x^{3/2} underflows long before */
  double a = (5.0 * K - 3.0) / (2.0 * K), c = 3.0 * (1.0 - K) / (2.0 * K);
  return a * gsl_sf_gamma_inc_P(1.5, x) + c * gsl_sf_gamma_inc_P(2.5, x);
}

double sb_spray_bkw_m4(double K, double theta)
{
  if (bkw_dom(K, theta, __func__))
    return NAN;
  double m = theta * theta * K * (30.0 - 15.0 * K);
  if (!(theta * theta >= DBL_MIN && m <= DBL_MAX)) {
    /* theta^2 over/underflows: the same chain, extended exponent */
    sbi_xd T = sbi_xd_of(theta);
    m = sbi_xd_val(sbi_xd_mul(sbi_xd_mul(sbi_xd_mul(T, T), sbi_xd_of(K)),
                              sbi_xd_of(30.0 - 15.0 * K)));
    if (isinf(m)) {
      sbi_error(SB_ERANGE, __func__, "E|v|^4 overflows (theta = %g)", theta);
      return NAN;
    }
  }
  return m;
}

double sb_spray_bkw_m6(double K, double theta)
{
  if (bkw_dom(K, theta, __func__))
    return NAN;
  double m = theta * theta * theta * K * K * (315.0 - 210.0 * K);
  if (!(theta * theta * theta >= DBL_MIN && m <= DBL_MAX)) {
    sbi_xd T = sbi_xd_of(theta), k = sbi_xd_of(K);
    m = sbi_xd_val(sbi_xd_mul(
        sbi_xd_mul(sbi_xd_mul(sbi_xd_mul(sbi_xd_mul(T, T), T), k), k),
        sbi_xd_of(315.0 - 210.0 * K)));
    if (isinf(m)) {
      sbi_error(SB_ERANGE, __func__, "E|v|^6 overflows (theta = %g)", theta);
      return NAN;
    }
  }
  return m;
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
  double c2 = gsl_ran_chisq(rng, dof), kc = K * theta * c2;
  /* K theta chi^2 over/underflows: the square roots apart */
  double sp = kc >= DBL_MIN && kc <= DBL_MAX
                  ? sqrt(kc)
                  : sqrt(K) * sqrt(theta) * sqrt(c2);
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

/* The fractions n_a/n, n_b/n (n = n_a + n_b), also where n overflows. */
static void fractions(const sb_spray_mixture *m, double *fa, double *fb)
{
  double n = m->n_a + m->n_b;
  if (isinf(n)) {
    double s = fmax(m->n_a, m->n_b), a = m->n_a / s, b = m->n_b / s;
    n = a + b;
    *fa = a / n;
    *fb = b / n;
  } else {
    *fa = m->n_a / n;
    *fb = m->n_b / n;
  }
}

/* (n_x/(n_a + n_b)) y for the fraction f = n_x/n, with an extended
 * exponent where f, y or the product is not a normal double. */
static double frac_times(const sb_spray_mixture *m, double f, double nx,
                         sbi_xd y)
{
  const double yv = sbi_xd_val(y), p = f * yv;
  if (yv == 0.0 || (isnormal(f) && isnormal(yv) && isnormal(p)))
    return p;
  sbi_xd n = sbi_xd_add(sbi_xd_of(m->n_a), sbi_xd_of(m->n_b));
  return sbi_xd_val(sbi_xd_mul(sbi_xd_div(sbi_xd_of(nx), n), y));
}

/* 1 - exp(-x) for x >= 0, also where x is below DBL_MIN (x (1 - x/2),
 * relative error below x^2/6 < 2^-60, for x < 2^-30). */
static sbi_xd one_minus_expneg(sbi_xd x)
{
  const double v = sbi_xd_val(x);
  if (v >= 0x1p-30)
    return sbi_xd_of(-expm1(-v));
  return sbi_xd_mul(x, sbi_xd_of(1.0 - 0.5 * v));
}

/* Delta(t) and gap = Delta0 - Delta(t) (same sign as Delta0, formed by
 * the caller without cancellation, with an extended exponent) -> T_a,
 * T_b with n_a T_a + n_b T_b conserved.  The hotter species is T_m + f_other |Delta| and the colder
 * T_0 + f_hot |gap|: both sums of non-negative terms, so each is
 * accurate to a few ulp (T_m - f |Delta| for the colder species would
 * lose about log2(T_m/T) bits, down to a negative T, where a rare
 * species is much hotter). */
/* The mixture temperature T_m = (n_a T_a0 + n_b T_b0)/(n_a + n_b):
 * through the fractions n_a/n, n_b/n where n_a T_a0 or n overflows, and
 * with an extended exponent where a product or the mean is below DBL_MIN
 * (n T near 1e-300; a subnormal n_a T_a0 keeps fewer than 53 bits even
 * where T_m is normal); the plain bits otherwise. */
static double mix_Tm(const sb_spray_mixture *m)
{
  const double n = m->n_a + m->n_b;
  const double pa = m->n_a * m->T_a0, pb = m->n_b * m->T_b0;
  double Tm = (pa + pb) / n;
  if (!isfinite(Tm) || !isfinite(n)) {
    double fa, fb;
    fractions(m, &fa, &fb);
    Tm = fa * m->T_a0 + fb * m->T_b0;
  }
  if (!isnormal(pa) || !isnormal(pb) || !isnormal(Tm)) {
    const sbi_xd nx = sbi_xd_add(sbi_xd_of(m->n_a), sbi_xd_of(m->n_b));
    Tm = sbi_xd_val(sbi_xd_div(
        sbi_xd_add(sbi_xd_mul(sbi_xd_of(m->n_a), sbi_xd_of(m->T_a0)),
                   sbi_xd_mul(sbi_xd_of(m->n_b), sbi_xd_of(m->T_b0))),
        nx));
  }
  return Tm;
}

static void split_T(const sb_spray_mixture *m, double delta, sbi_xd gap,
                    double *Ta, double *Tb)
{
  const double Tm = mix_Tm(m);
  double fa, fb;
  fractions(m, &fa, &fb);
  if (m->T_a0 == m->T_b0) {
    *Ta = *Tb = m->T_a0;
  } else if (m->T_a0 > m->T_b0) {
    *Ta = Tm + fb * delta;
    *Tb = m->T_b0 + frac_times(m, fa, m->n_a, gap);
  } else {
    *Ta = m->T_a0 - frac_times(m, fb, m->n_b, gap);
    *Tb = Tm - fa * delta;
  }
}

/* pre (n_a + n_b) m_a m_b/(m_a + m_b)^2 with an extended exponent. */
static sbi_xd mix_rate_x(double pre, const sb_spray_mixture *mx)
{
  sbi_xd Mx = sbi_xd_add(sbi_xd_of(mx->m_a), sbi_xd_of(mx->m_b));
  sbi_xd nx = sbi_xd_add(sbi_xd_of(mx->n_a), sbi_xd_of(mx->n_b));
  sbi_xd q = sbi_xd_mul(sbi_xd_mul(sbi_xd_mul(sbi_xd_of(pre), nx),
                                   sbi_xd_of(mx->m_a)),
                        sbi_xd_of(mx->m_b));
  return sbi_xd_div(q, sbi_xd_mul(Mx, Mx));
}

/* The same as a double (pre >= 0), with an extended exponent where a
 * product over/underflows (same bits otherwise). */
static double mix_rate(double pre, const sb_spray_mixture *mx)
{
  double M = mx->m_a + mx->m_b, n = mx->n_a + mx->n_b;
  double num = pre * n * mx->m_a * mx->m_b, M2 = M * M;
  if (pre == 0 || (num >= DBL_MIN && num <= DBL_MAX && M2 >= DBL_MIN &&
                   M2 <= DBL_MAX))
    return num / M2;
  return sbi_xd_val(mix_rate_x(pre, mx));
}

/* Outputs finite, else SB_ERANGE. */
static int temps_ok(double Ta, double Tb, const char *func)
{
  if (!isfinite(Ta) || !isfinite(Tb))
    return sbi_error(SB_ERANGE, func, "T_a = %g, T_b = %g: an intermediate "
                     "leaves the double range", Ta, Tb);
  return SB_SUCCESS;
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
  if (!(B0 > 0) || !(t >= 0) || !isfinite(B0) || !isfinite(t))
    return sbi_error(SB_EDOM, __func__, "B0 = %g, t = %g: need finite "
                     "B0 > 0, t >= 0", B0, t);
  const double rate = mix_rate(2.0 * B0, mx);
  /* x = rate t; a rate below DBL_MIN (n B0 near 1e-300) keeps fewer
   * than 53 bits as a double: then x from the rate with an extended
   * exponent (rate t itself is below ~4 there, as t <= DBL_MAX) */
  const sbi_xd x = sbi_xd_mul(rate >= DBL_MIN ? sbi_xd_of(rate)
                                              : mix_rate_x(2.0 * B0, mx),
                              sbi_xd_of(t));
  double e = t == 0 ? 1.0 : exp(-sbi_xd_val(x)), Ta, Tb;
  /* Delta0 - Delta = Delta0 (1 - e), 1 - e by expm1 */
  const double D0 = mx->T_a0 - mx->T_b0;
  const sbi_xd ome = one_minus_expneg(x);
  split_T(mx, D0 * e, sbi_xd_mul(sbi_xd_of(D0), ome), &Ta, &Tb);
  if ((st = temps_ok(Ta, Tb, __func__)))
    return st;
  if (T_a)
    *T_a = Ta;
  if (T_b)
    *T_b = Tb;
  return SB_SUCCESS;
}

/* (16/3) sqrt(2/pi) pi d^2 (n_a + n_b) m_a m_b/(m_a + m_b)^2, d = r_a + r_b,
 * with an extended exponent throughout (the over/underflow branches of
 * the hard-sphere law). */
static sbi_xd hs_Cx(const sb_spray_mixture *mx)
{
  sbi_xd dx = sbi_xd_add(sbi_xd_of(mx->r_a), sbi_xd_of(mx->r_b));
  sbi_xd c = sbi_xd_mul(
      sbi_xd_mul(sbi_xd_of((16.0 / 3.0) * sqrt(2.0 / SBI_PI) * SBI_PI), dx),
      dx);
  sbi_xd M = sbi_xd_add(sbi_xd_of(mx->m_a), sbi_xd_of(mx->m_b));
  sbi_xd nx = sbi_xd_add(sbi_xd_of(mx->n_a), sbi_xd_of(mx->n_b));
  c = sbi_xd_mul(sbi_xd_mul(sbi_xd_mul(c, nx), sbi_xd_of(mx->m_a)),
                 sbi_xd_of(mx->m_b));
  return sbi_xd_div(c, sbi_xd_mul(M, M));
}

static double hs_C(const sb_spray_mixture *mx)
{
  double d = mx->r_a + mx->r_b;
  double pre = (16.0 / 3.0) * sqrt(2.0 / SBI_PI) * SBI_PI * d * d;
  if (!(pre >= DBL_MIN && pre <= DBL_MAX))
    return sbi_xd_val(hs_Cx(mx));
  return mix_rate(pre, mx);
}

static int radii_ok(const sb_spray_mixture *mx)
{
  return mx->r_a > 0 && mx->r_b > 0 && isfinite(mx->r_a) &&
         isfinite(mx->r_b);
}

double sb_spray_two_temp_hs_rate(const sb_spray_mixture *mx, double T_a,
                                 double T_b)
{
  if (mix_check(mx, __func__))
    return NAN;
  if (!radii_ok(mx) || !(T_a > 0) || !(T_b > 0) || !isfinite(T_a) ||
      !isfinite(T_b)) {
    sbi_error(SB_EDOM, __func__, "need finite r_a, r_b, T_a, T_b > 0 "
              "(T_a = %g, T_b = %g)", T_a, T_b);
    return NAN;
  }
  double s = sqrt(SB_BOLTZMANN * (T_a / mx->m_a + T_b / mx->m_b));
  double n = mx->n_a + mx->n_b;
  double c = hs_C(mx), p = -c * mx->n_b, q = p / n, w = q * s;
  double r = w * (T_a - T_b);
  if (!(isnormal(c) && isnormal(s) && isnormal(p) && isnormal(q) &&
        isnormal(w) && isnormal(r))) {
    /* outside the plain products' range (n overflows, k T/m for
     * m = 1e-320, s = inf but C tiny, or a subnormal partial product;
     * also T_a = T_b, where r = 0 either way): C, s and n_b/n with an
     * extended exponent */
    const sbi_xd fb =
        sbi_xd_div(sbi_xd_of(mx->n_b),
                   sbi_xd_add(sbi_xd_of(mx->n_a), sbi_xd_of(mx->n_b)));
    const sbi_xd k = sbi_xd_of(SB_BOLTZMANN);
    const sbi_xd sx = sbi_xd_sqrt(sbi_xd_add(
        sbi_xd_div(sbi_xd_mul(k, sbi_xd_of(T_a)), sbi_xd_of(mx->m_a)),
        sbi_xd_div(sbi_xd_mul(k, sbi_xd_of(T_b)), sbi_xd_of(mx->m_b))));
    r = -sbi_xd_val(sbi_xd_mul(sbi_xd_mul(sbi_xd_mul(hs_Cx(mx), fb), sx),
                                sbi_xd_of(T_a - T_b)));
  }
  if (!isfinite(r)) {
    sbi_error(SB_ERANGE, __func__, "the rate overflows (T_a = %g, T_b = %g)",
              T_a, T_b);
    return NAN;
  }
  return r;
}

/* T_a(t), T_b(t) of sb_spray_two_temp_hs where a double intermediate of
 * the plain closed form leaves the normal range (n_a T_a0 or n
 * overflows, n_b/n underflows, k T/m overflows for m = 1e-320 or is
 * subnormal for m = 1e300, C = inf at t = 0, ...).  T_a, T_b lie between
 * T_a0 and T_b0, so they are doubles whatever the arguments.  With
 * s = u0 + sqrt(alpha), w = sqrt(alpha)/s, rho0 = beta Delta0/s^2
 * (1 - rho0 = 2 w), gam = rho0/(2 w) = beta Delta0/(2 sqrt(alpha) s)
 * and e = exp(-C sqrt(alpha) t), the solution is
 *   F = Delta/Delta0 = e/(1 + z)^2,  z = gam (1 - e),
 *   1 - F = (1 - e)(u0/sqrt(alpha) + gam^2 (1 - e))/(1 + z)^2
 * (using 1 + 2 gam = u0/sqrt(alpha)); z > -1/2 and both factors of 1 - F
 * are sums of non-negative terms.  The hotter species is then
 * T_m + f |Delta| and the colder T_0 + f |Delta0| (1 - F) (f the other
 * species' fraction): sums of positive terms, without the cancellation
 * of T_m - f |Delta|.  Everything is formed with an extended exponent
 * and 1 - e by expm1. */
static void two_temp_hs_wide(const sb_spray_mixture *mx, double t,
                             double *Ta, double *Tb)
{
  const sbi_xd na = sbi_xd_of(mx->n_a), nb = sbi_xd_of(mx->n_b);
  const sbi_xd Ta0 = sbi_xd_of(mx->T_a0), Tb0 = sbi_xd_of(mx->T_b0);
  const sbi_xd n = sbi_xd_add(na, nb);
  const sbi_xd fa = sbi_xd_div(na, n), fb = sbi_xd_div(nb, n);
  const sbi_xd Tm = sbi_xd_add(sbi_xd_mul(fa, Ta0), sbi_xd_mul(fb, Tb0));
  const double D0 = mx->T_a0 - mx->T_b0;
  const sbi_xd k = sbi_xd_of(SB_BOLTZMANN);
  const sbi_xd ia = sbi_xd_div(sbi_xd_of(1.0), sbi_xd_of(mx->m_a));
  const sbi_xd ib = sbi_xd_div(sbi_xd_of(1.0), sbi_xd_of(mx->m_b));
  const sbi_xd alpha = sbi_xd_mul(sbi_xd_mul(k, Tm), sbi_xd_add(ia, ib));
  /* beta = k (f_b/m_a - f_a/m_b);  u0^2 = alpha + beta Delta0 =
   * k (T_a0/m_a + T_b0/m_b), a sum of positive terms */
  const sbi_xd fan = sbi_xd_mul(sbi_xd_of(-1.0), fa);
  const sbi_xd beta = sbi_xd_mul(
      k, sbi_xd_add(sbi_xd_mul(fb, ia), sbi_xd_mul(fan, ib)));
  const sbi_xd u0 = sbi_xd_sqrt(
      sbi_xd_mul(k, sbi_xd_add(sbi_xd_mul(Ta0, ia), sbi_xd_mul(Tb0, ib))));
  const sbi_xd sa = sbi_xd_sqrt(alpha), s = sbi_xd_add(u0, sa);
  /* x = C sqrt(alpha) t (t = 0: x = 0 even where C overflows) */
  const double x =
      t == 0.0 ? 0.0
               : sbi_xd_val(sbi_xd_mul(sbi_xd_mul(hs_Cx(mx), sa),
                                       sbi_xd_of(t)));
  const sbi_xd e = sbi_xd_of(exp(-x)), ome = sbi_xd_of(-expm1(-x));
  const sbi_xd gam =
      sbi_xd_div(sbi_xd_mul(beta, sbi_xd_of(D0)),
                 sbi_xd_mul(sbi_xd_mul(sbi_xd_of(2.0), sa), s));
  const sbi_xd opz = sbi_xd_add(sbi_xd_of(1.0), sbi_xd_mul(gam, ome));
  const sbi_xd opz2 = sbi_xd_mul(opz, opz);
  const sbi_xd F = sbi_xd_div(e, opz2);
  const sbi_xd omF = sbi_xd_div(
      sbi_xd_mul(ome, sbi_xd_add(sbi_xd_div(u0, sa),
                                 sbi_xd_mul(sbi_xd_mul(gam, gam), ome))),
      opz2);
  const sbi_xd aD = sbi_xd_of(fabs(D0));
  /* hot: T_m + f |Delta0| F;  cold: T_0 + f |Delta0| (1 - F) */
  if (D0 >= 0.0) {
    *Ta = sbi_xd_val(sbi_xd_add(Tm, sbi_xd_mul(sbi_xd_mul(fb, aD), F)));
    *Tb = sbi_xd_val(sbi_xd_add(Tb0, sbi_xd_mul(sbi_xd_mul(fa, aD), omF)));
  } else {
    *Tb = sbi_xd_val(sbi_xd_add(Tm, sbi_xd_mul(sbi_xd_mul(fa, aD), F)));
    *Ta = sbi_xd_val(sbi_xd_add(Ta0, sbi_xd_mul(sbi_xd_mul(fb, aD), omF)));
  }
}

/* dD/dt = -C D sqrt(alpha + beta D), s^2 = alpha + beta D.  With
 * u = sqrt(alpha + beta D): (u - sqrt(alpha))/(u + sqrt(alpha)) =
 * rho0 exp(-C sqrt(alpha) t), and D = 4 alpha rho/(beta (1 - rho)^2),
 * rho = rho0 e, e = exp(-C sqrt(alpha) t).  Evaluated as in
 * two_temp_hs_wide, without the division by beta (which may vanish) and
 * without the cancellation of 1 - rho (rho0 near 1 where u0 >>
 * sqrt(alpha), e.g. a rare, much hotter species): with r =
 * u0/sqrt(alpha), gam = (r - 1)/2 > -1/2 and z = gam (1 - e) > -1/2,
 *   F = D/D0 = e/(1 + z)^2,
 *   1 - F = (1 - e) r/(1 + z)^2 + (z/(1 + z))^2
 * (both terms non-negative); the hotter species is T_m + f |D| and the
 * colder T_0 + f' |D0| (1 - F) (split_T). */
int sb_spray_two_temp_hs(const sb_spray_mixture *mx, double t, double *T_a,
                         double *T_b)
{
  int st = mix_check(mx, __func__);
  if (st)
    return st;
  if (!radii_ok(mx) || !(t >= 0) || !isfinite(t))
    return sbi_error(SB_EDOM, __func__, "need finite r_a, r_b > 0 and "
                     "t >= 0");
  const double k = SB_BOLTZMANN, n = mx->n_a + mx->n_b;
  /* T_m as split_T forms it (with an extended exponent where n_a T_a0
   * or n_b T_b0 is subnormal: alpha, and with it e and u0/sqrt(alpha),
   * lost those bits where T_m is normal) */
  const double Tm = mix_Tm(mx);
  double D0 = mx->T_a0 - mx->T_b0;
  double alpha = k * Tm * (1.0 / mx->m_a + 1.0 / mx->m_b);
  /* u0^2 = alpha + beta D0 = k (T_a0/m_a + T_b0/m_b), a sum of positive
   * terms (alpha + beta D0 cancels where u0 << sqrt(alpha)) */
  double sa = sqrt(alpha),
         u0 = sqrt(k * (mx->T_a0 / mx->m_a + mx->T_b0 / mx->m_b));
  double C = hs_C(mx), Csa = -C * sa;
  double e = exp(Csa * t);
  const sbi_xd omex =
      one_minus_expneg(sbi_xd_mul(sbi_xd_of(-Csa), sbi_xd_of(t)));
  const double ome = sbi_xd_val(omex), r = u0 / sa, gam = 0.5 * (r - 1.0);
  const double z = gam * ome, opz = 1.0 + z, opz2 = opz * opz;
  const double D = D0 * (e / opz2), zq = z / opz;
  double Ta, Tb;
  /* the plain form where its intermediates are normal doubles; a
   * subnormal e or Delta (e = exp(-x) below DBL_MIN) only where Delta
   * is negligible against T_m, as before */
  const int negl = fabs(D) <= 0x1p-60 * Tm;
  if (isfinite(n) && isnormal(mx->n_a / n) && isnormal(mx->n_b / n) &&
      isnormal(Tm) && isnormal(alpha) && isnormal(sa) && isnormal(u0) &&
      isnormal(r) && isnormal(opz2) && isnormal(C) && isnormal(Csa) &&
      (isnormal(e) || e == 0.0 || D0 == 0.0 || negl) &&
      (isnormal(D) || D == 0.0 || negl)) {
    const sbi_xd omF = sbi_xd_add(
        sbi_xd_div(sbi_xd_mul(omex, sbi_xd_of(r)), sbi_xd_of(opz2)),
        sbi_xd_of(zq * zq));
    split_T(mx, D, sbi_xd_mul(sbi_xd_of(D0), omF), &Ta, &Tb);
  } else {
    two_temp_hs_wide(mx, t, &Ta, &Tb);
  }
  if ((st = temps_ok(Ta, Tb, __func__)))
    return st;
  if (T_a)
    *T_a = Ta;
  if (T_b)
    *T_b = Tb;
  return SB_SUCCESS;
}
