/* kernel.c — collision and agglomeration kernels (SI units).
 * Formulas, sources and derivations: lib/smolbridge/kernel.h, docs/kernel.md.
 */
#include <stdio.h>
#include <math.h>
#include <string.h>

#include <gsl/gsl_math.h> /* M_PI under -std=c11 */

#include <smolbridge/kernel.h>

#include "common/internal.h"
#include "common/numutil.h"
#include "kernel_internal.h"

/* Boltzmann constant, J/K (exact in SI 2019; same value as SB_BOLTZMANN). */
static const double kB = 1.380649e-23;

/* x finite and > 0 */
static int pos(double x) { return isfinite(x) && x > 0.0; }
/* x finite and >= 0 */
static int nonneg(double x) { return isfinite(x) && x >= 0.0; }

#define CHECK(cond, ...)                                      \
  do {                                                        \
    if (!(cond)) {                                            \
      sbi_error(SB_EDOM, __func__, __VA_ARGS__);              \
      return NAN;                                             \
    }                                                         \
  } while (0)

/* Hard spheres or discs: diameters, masses and T all > 0. */
#define CHECK_KINETIC(d_i, d_j, m_i, m_j, T)                              \
  CHECK(pos(d_i) && pos(d_j), "diameters must be > 0 (got %g, %g)", d_i, \
        d_j);                                                             \
  CHECK(pos(m_i) && pos(m_j) && pos(T),                                   \
        "masses and T must be > 0 (got %g, %g, %g)", m_i, m_j, T)

#define CHECK_RADII(a, b)                                               \
  CHECK(pos(a) && pos(b), "radii must be finite and > 0 (got %g, %g)", \
        (a), (b))

/* A kernel's value, or NaN and SB_ERANGE (recorded for func) where it is
 * not finite: the result, or an intermediate such as 1/m for a mass of
 * 1e-320, overflowed at extreme arguments. */
static double kernel_value(double K, const char *func)
{
  if (isfinite(K))
    return K;
  sbi_error(SB_ERANGE, func, "the value overflows at these arguments "
            "(got %g)", K);
  return NAN;
}

/* The kernels are evaluated in sbi_xd arithmetic (numutil.h): the same
 * operations in the same order as the plain formulas (so the same bits
 * wherever no intermediate over/underflows), but an intermediate such as
 * 1/m for m = 1e-320, k_B T for T = 1e-320 or 3 pi mu r for mu = 1e-320
 * no longer turns a representable kernel into inf, 0 or a subnormal that
 * has lost its digits. */
#define X(x) sbi_xd_of(x)
#define MUL(a, b) sbi_xd_mul((a), (b))
#define DIV(a, b) sbi_xd_div((a), (b))
#define ADD(a, b) sbi_xd_add((a), (b))
#define SQRT(a) sbi_xd_sqrt(a)

/* A kernel in sbi_xd form: its value, or NaN and SB_ERANGE (for func)
 * where it exceeds DBL_MAX. */
static double kernel_xd(sbi_xd K, const char *func)
{
  return kernel_value(sbi_xd_val(K), func);
}

/* m1 m2/(m1 + m2) for m1, m2 > 0 */
static sbi_xd reduced(double m1, double m2)
{
  return DIV(MUL(X(m1), X(m2)), ADD(X(m1), X(m2)));
}

/* Stokes–Einstein diffusivity with optional Cunningham slip correction
 * (Davies 1945 coefficients, Knudsen number lambda/r). */
static sbi_xd diffusivity(double r, double T, double mu, double lambda)
{
  sbi_xd c = X(1.0);
  if (lambda > 0.0) {
    const sbi_xd kn = DIV(X(lambda), X(r));
    const double knv = sbi_xd_val(kn); /* inf: exp(-0) = 1 */
    c = ADD(X(1.0), MUL(kn, X(1.257 + 0.4 * exp(-1.1 / knv))));
  }
  return DIV(MUL(MUL(X(kB), X(T)), c), MUL(MUL(X(6.0 * M_PI), X(mu)), X(r)));
}

/* K_co = 4 pi (D_i + D_j)(r_i + r_j) */
static sbi_xd k_co(double ri, double rj, double T, double mu, double lambda)
{
  return MUL(MUL(X(4.0 * M_PI), ADD(diffusivity(ri, T, mu, lambda),
                                    diffusivity(rj, T, mu, lambda))),
             ADD(X(ri), X(rj)));
}

/* (4/3) pi rho r^3 */
static sbi_xd sphere_mass(double rho, double r)
{
  return MUL(MUL(MUL(MUL(MUL(X(rho), X(4.0 / 3.0)), X(M_PI)), X(r)), X(r)),
             X(r));
}

/* 1/m_i + 1/m_j */
static sbi_xd inv_sum(sbi_xd mi, sbi_xd mj)
{
  return ADD(DIV(X(1.0), mi), DIV(X(1.0), mj));
}

/* K_fm = pi (r_i + r_j)^2 c_ij, c_ij^2 = (8kT/pi)(1/m_i + 1/m_j) */
static sbi_xd k_fm(double ri, double rj, double T, double rho)
{
  const sbi_xd mi = sphere_mass(rho, ri), mj = sphere_mass(rho, rj);
  const sbi_xd c = SQRT(MUL(DIV(MUL(X(8.0 * kB), X(T)), X(M_PI)),
                            inv_sum(mi, mj)));
  const sbi_xd r = ADD(X(ri), X(rj));
  return MUL(MUL(MUL(X(M_PI), r), r), c);
}

double sb_kernel_brownian_co(double r_i, double r_j, double T, double mu)
{
  CHECK_RADII(r_i, r_j);
  CHECK(pos(T) && pos(mu), "T and mu must be > 0 (got %g, %g)", T, mu);
  /* (2kT/3mu)(1/r_i + 1/r_j)(r_i + r_j): the same as k_co with lambda 0,
   * written this way so that the monodisperse value is exactly 8kT/3mu
   * up to rounding. */
  return kernel_xd(MUL(MUL(DIV(MUL(X(2.0 * kB), X(T)), MUL(X(3.0), X(mu))),
                           inv_sum(X(r_i), X(r_j))),
                       ADD(X(r_i), X(r_j))),
                   __func__);
}

double sb_kernel_brownian_fm(double r_i, double r_j, double T, double rho_p)
{
  CHECK_RADII(r_i, r_j);
  CHECK(pos(T) && pos(rho_p), "T and rho_p must be > 0 (got %g, %g)", T,
        rho_p);
  return kernel_xd(k_fm(r_i, r_j, T, rho_p), __func__);
}

double sb_kernel_brownian_tr(double r_i, double r_j, double T, double mu,
                             double rho_p, double lambda)
{
  CHECK_RADII(r_i, r_j);
  CHECK(pos(T) && pos(mu) && pos(rho_p),
        "T, mu, rho_p must be > 0 (got %g, %g, %g)", T, mu, rho_p);
  CHECK(nonneg(lambda), "lambda must be >= 0 (got %g)", lambda);
  const sbi_xd kco = k_co(r_i, r_j, T, mu, lambda);
  const sbi_xd kfm = k_fm(r_i, r_j, T, rho_p);
  /* Dahneke's Knudsen number */
  const double kn = sbi_xd_val(DIV(kco, MUL(X(2.0), kfm)));
  /* (1 + kn)/(1 + 2kn(1 + kn)); for kn -> inf this is 1/(2kn), giving
   * kco/(2kn) = kfm. */
  if (kn > 1e150) /* avoid overflow of kn^2: the fm limit is exact here */
    return kernel_xd(kfm, __func__);
  return kernel_xd(DIV(MUL(kco, X(1.0 + kn)),
                       X(1.0 + 2.0 * kn * (1.0 + kn))),
                   __func__);
}

/* Transition regime of Langevin spheres (Gopalakrishnan & Hogan 2011,
 * eq 7).  g(Kn) = H(Kn)/Kn^2 is the kernel in units of kT R/f_red:
 *   g = (4 pi + 25.836 Kn + sqrt(8 pi) 11.211 Kn^2)
 *       / (1 + 3.502 Kn + 7.211 Kn^2 + 11.211 Kn^3),
 * finite at Kn = 0 (the continuum 4 pi); for huge Kn it is evaluated in
 * powers of 1/Kn (no overflow). */
/* Kn g(Kn) in powers of u = 1/Kn (u = 0 allowed: sqrt(8 pi)). */
static double gh_kng(double u)
{
  return (sqrt(8.0 * M_PI) * 11.211 + u * (25.836 + u * 4.0 * M_PI)) /
         (11.211 + u * (7.211 + u * (3.502 + u)));
}

static double gh_g(double kn)
{
  const double s8pi = sqrt(8.0 * M_PI);
  if (kn > 1e50) {
    double u = 1.0 / kn;
    return u * (s8pi * 11.211 + u * (25.836 + u * 4.0 * M_PI)) /
           (11.211 + u * (7.211 + u * (3.502 + u)));
  }
  return (4.0 * M_PI + kn * (25.836 + kn * s8pi * 11.211)) /
         (1.0 + kn * (3.502 + kn * (7.211 + kn * 11.211)));
}

double sb_kernel_gh_H(double kn)
{
  CHECK(kn >= 0.0 && isfinite(kn), "Kn_D must be finite and >= 0 (got %g)",
        kn);
  if (kn > 1e100)  /* H ~ sqrt(8 pi) Kn: kn^2 would overflow */
    return kernel_value(kn * (kn * gh_g(kn)), __func__);
  return kn * kn * gh_g(kn);
}

/* Kn_D = sqrt(kT m_red)/(f_red R), f = m/tau. */
static sbi_xd gh_knd(double r_i, double r_j, double m_i, double m_j,
                     double tau_i, double tau_j, double T, sbi_xd *m_red,
                     sbi_xd *f_red, sbi_xd *R)
{
  const sbi_xd f_i = DIV(X(m_i), X(tau_i)), f_j = DIV(X(m_j), X(tau_j));
  *m_red = reduced(m_i, m_j);
  *f_red = DIV(MUL(f_i, f_j), ADD(f_i, f_j));
  *R = ADD(X(r_i), X(r_j));
  return DIV(SQRT(MUL(MUL(X(kB), X(T)), *m_red)), MUL(*f_red, *R));
}

double sb_kernel_brownian_gh_kn(double r_i, double r_j, double m_i,
                                double m_j, double tau_i, double tau_j,
                                double T)
{
  CHECK_RADII(r_i, r_j);
  CHECK(pos(m_i) && pos(m_j) && pos(tau_i) && pos(tau_j) && pos(T),
        "masses, tau and T must be finite and > 0 (got %g, %g, %g, %g, %g)",
        m_i, m_j, tau_i, tau_j, T);
  sbi_xd mr, fr, R;
  return kernel_xd(gh_knd(r_i, r_j, m_i, m_j, tau_i, tau_j, T, &mr, &fr, &R),
                   __func__);
}

double sb_kernel_brownian_gh(double r_i, double r_j, double m_i, double m_j,
                             double tau_i, double tau_j, double T)
{
  CHECK_RADII(r_i, r_j);
  CHECK(pos(m_i) && pos(m_j) && pos(tau_i) && pos(tau_j) && pos(T),
        "masses, tau and T must be finite and > 0 (got %g, %g, %g, %g, %g)",
        m_i, m_j, tau_i, tau_j, T);
  sbi_xd mr, fr, R;
  const sbi_xd knx = gh_knd(r_i, r_j, m_i, m_j, tau_i, tau_j, T, &mr, &fr,
                            &R);
  const double kn = sbi_xd_val(knx);
  /* beta = H f_red R^3/m_red = (H/Kn^2) kT R/f_red: no division by a
   * vanishing Kn^2.  Near the free-molecular limit (Kn_D > 1e50, where
   * f_red may be so small that kT R/f_red overflows) the same as
   * (Kn g) R^2 sqrt(kT/m_red), Kn g -> sqrt(8 pi). */
  if (kn > 1e50)
    return kernel_xd(MUL(MUL(MUL(X(gh_kng(sbi_xd_val(DIV(X(1.0), knx)))), R),
                             R),
                         SQRT(DIV(MUL(X(kB), X(T)), mr))),
                     __func__);
  return kernel_xd(DIV(MUL(MUL(MUL(X(gh_g(kn)), X(kB)), X(T)), R), fr),
                   __func__);
}

double sb_kernel_kinetic(double d_i, double d_j, double m_i, double m_j,
                         double T)
{
  CHECK_KINETIC(d_i, d_j, m_i, m_j, T);
  const sbi_xd r = MUL(X(0.5), ADD(X(d_i), X(d_j)));
  return kernel_xd(MUL(MUL(MUL(X(M_PI), r), r),
                       SQRT(MUL(DIV(MUL(X(8.0 * kB), X(T)), X(M_PI)),
                                inv_sum(X(m_i), X(m_j))))),
                   __func__);
}

double sb_kernel_kinetic_2d(double d_i, double d_j, double m_i, double m_j,
                            double T)
{
  CHECK_KINETIC(d_i, d_j, m_i, m_j, T);
  /* mean Rayleigh speed sqrt(pi/2) sigma, sigma^2 = kT/m_red */
  return kernel_xd(MUL(ADD(X(d_i), X(d_j)),
                       SQRT(MUL(MUL(MUL(X(0.5 * M_PI), X(kB)), X(T)),
                                inv_sum(X(m_i), X(m_j))))),
                   __func__);
}

double sb_kernel_gravity(double r_i, double r_j, double rho_p, double rho_f,
                         double mu, double g)
{
  CHECK_RADII(r_i, r_j);
  CHECK(pos(rho_p) && nonneg(rho_f) && pos(mu) && nonneg(g),
        "need rho_p > 0, rho_f >= 0, mu > 0, g >= 0 (got %g, %g, %g, %g)",
        rho_p, rho_f, mu, g);
  /* |U_i - U_j| = 2|rho_p - rho_f| g |r_i^2 - r_j^2|/(9 mu), with the
   * difference of squares factored to avoid cancellation. */
  const sbi_xd r = ADD(X(r_i), X(r_j));
  const sbi_xd du =
      DIV(MUL(MUL(MUL(MUL(X(2.0), X(fabs(rho_p - rho_f))), X(g)),
                  X(fabs(r_i - r_j))),
              r),
          MUL(X(9.0), X(mu)));
  return kernel_xd(MUL(MUL(MUL(X(M_PI), r), r), du), __func__);
}

double sb_kernel_shear(double r_i, double r_j, double G)
{
  CHECK_RADII(r_i, r_j);
  CHECK(nonneg(G), "G must be >= 0 (got %g)", G);
  const sbi_xd r = ADD(X(r_i), X(r_j));
  return kernel_xd(MUL(MUL(MUL(MUL(X(4.0 / 3.0), X(G)), r), r), r), __func__);
}

double sb_kernel_saffman_turner(double r_i, double r_j, double eps,
                                double nu)
{
  CHECK_RADII(r_i, r_j);
  CHECK(nonneg(eps) && pos(nu), "need eps >= 0, nu > 0 (got %g, %g)", eps,
        nu);
  const sbi_xd r = ADD(X(r_i), X(r_j));
  return kernel_xd(MUL(MUL(MUL(SQRT(DIV(MUL(X(8.0 * M_PI), X(eps)),
                                        MUL(X(15.0), X(nu)))),
                               r),
                           r),
                       r),
                   __func__);
}

double sb_kernel_abrahamson(double r_i, double r_j, double u2_i,
                            double u2_j)
{
  CHECK_RADII(r_i, r_j);
  CHECK(nonneg(u2_i) && nonneg(u2_j),
        "velocity variances must be >= 0 (got %g, %g)", u2_i, u2_j);
  /* Flux of a Maxwellian relative velocity (per-component variance
   * s2 = u2_i + u2_j) through a sphere of radius r: pi r^2 E|w|, with
   * E|w| = sqrt(8 s2/pi). */
  const sbi_xd r = ADD(X(r_i), X(r_j));
  return kernel_xd(MUL(MUL(SQRT(MUL(X(8.0 * M_PI), ADD(X(u2_i), X(u2_j)))),
                           r),
                       r),
                   __func__);
}

/* E[(w.n)^-] for w.n ~ N(m, var): the inward flux density of the
 * sheared Gaussian relative velocity along n (sb_kernel_shear_langevin).
 * var = 2 u2 q(n), q = (1 + gt^2/2) nx^2 - gt nx ny + ny^2 + nz^2, is
 * formed as (sqrt(2 u2) s)^2 q/s^2 with s = max(1, gt), so that gt^2 does
 * not overflow (gt up to ~1e308). */
typedef struct {
  double R, G, u2, gt;
} shear_flux;

static double shear_flux_at(const double n[3], void *ctx)
{
  const shear_flux *k = ctx;
  const double nx = n[0], ny = n[1], nz = n[2], gt = k->gt;
  const double sc = gt > 1.0 ? gt : 1.0, a = 1.0 / sc, b = gt / sc;
  const double m = k->G * k->R * nx * ny;
  const double qs = (a * a + 0.5 * b * b) * nx * nx - b * a * nx * ny +
                    a * a * (ny * ny + nz * nz);
  const double sd = M_SQRT2 * sqrt(k->u2) * sc * sqrt(qs), z = m / sd;
  return sd * exp(-0.5 * z * z) / sqrt(2.0 * M_PI) -
         0.5 * m * erfc(z / M_SQRT2);
}

double sb_kernel_shear_langevin(double r_i, double r_j, double u2, double tau,
                                double G)
{
  CHECK_RADII(r_i, r_j);
  CHECK(nonneg(u2) && nonneg(tau) && nonneg(G),
        "need u2, tau, G finite and >= 0 (got %g, %g, %g)", u2, tau, G);
  if (u2 == 0.0)
    return sb_kernel_shear(r_i, r_j, G);  /* the integrand's limit (-m)^+ */
  /* 96 Gauss-Legendre nodes in cos(theta), 192 midpoints in phi (the
   * integrand is periodic in phi) */
  const double R = r_i + r_j;
  shear_flux k = {R, G, u2, G * tau};
  const double K = R * R * sbi_sphere_integral(shear_flux_at, &k, 96, 192,
                                               0.5);
  if (!isfinite(K)) { /* K ~ R^2 sqrt(2 pi u2) G tau at large G tau */
    sbi_error(SB_ERANGE, __func__, "the kernel overflows (G tau = %g, "
              "G R = %g, R = %g)", G * tau, G * R, R);
    return NAN;
  }
  return K;
}

double sb_kernel_diffusion(double r_i, double r_j, double b2_i, double b2_j)
{
  CHECK_RADII(r_i, r_j);
  CHECK(nonneg(b2_i) && nonneg(b2_j),
        "variance rates must be >= 0 (got %g, %g)", b2_i, b2_j);
  return kernel_xd(MUL(MUL(X(2.0 * M_PI), ADD(X(b2_i), X(b2_j))),
                       ADD(X(r_i), X(r_j))),
                   __func__);
}

/* kT/(3 pi mu r) */
sbi_xd sbi_kernel_b2_brownian(double r, double T, double mu)
{
  return DIV(MUL(X(kB), X(T)), MUL(MUL(X(3.0 * M_PI), X(mu)), X(r)));
}

/* sqrt(2/(15 pi)) sqrt(eps/nu) r^2 */
sbi_xd sbi_kernel_b2_turb(sbi_xd r, double eps, double nu)
{
  return MUL(MUL(MUL(X(sqrt(2.0 / (15.0 * M_PI))), SQRT(DIV(X(eps), X(nu)))),
                 r),
             r);
}

double sb_brownian_b2(double r, double T, double mu)
{
  CHECK(pos(r) && pos(T) && pos(mu), "r, T, mu must be > 0 (got %g, %g, %g)",
        r, T, mu);
  return kernel_xd(sbi_kernel_b2_brownian(r, T, mu), __func__);
}

double sb_turb_pair_b2(double r, double eps, double nu)
{
  CHECK(pos(r) && nonneg(eps) && pos(nu),
        "need r > 0, eps >= 0, nu > 0 (got %g, %g, %g)", r, eps, nu);
  return kernel_xd(sbi_kernel_b2_turb(X(r), eps, nu), __func__);
}

double sb_kernel_brownian_turb(double r_i, double r_j, double T, double mu,
                               double eps, double nu)
{
  CHECK_RADII(r_i, r_j);
  CHECK(pos(T) && pos(mu), "T and mu must be > 0 (got %g, %g)", T, mu);
  CHECK(nonneg(eps) && pos(nu), "need eps >= 0, nu > 0 (got %g, %g)", eps,
        nu);
  const sbi_xd r = ADD(X(r_i), X(r_j));
  const sbi_xd b2 = ADD(ADD(sbi_kernel_b2_brownian(r_i, T, mu),
                            sbi_kernel_b2_brownian(r_j, T, mu)),
                        sbi_kernel_b2_turb(r, eps, nu));
  return kernel_xd(MUL(MUL(X(2.0 * M_PI), b2), r), __func__);
}

/* ------------------------------------------------------ test kernels */

/* Volumes finite and > 0, K finite and >= 0 (as sb_kernel_spec_check). */
#define CHECK_TEST(v_i, v_j, K)                                           \
  CHECK(pos(v_i) && pos(v_j), "volumes must be finite and > 0 (got %g, "  \
        "%g)", v_i, v_j);                                                 \
  CHECK(nonneg(K), "K must be finite and >= 0 (got %g)", K)

double sb_kernel_constant(double v_i, double v_j, double K)
{
  CHECK_TEST(v_i, v_j, K);
  return K;
}

double sb_kernel_additive(double v_i, double v_j, double K)
{
  CHECK_TEST(v_i, v_j, K);
  return kernel_xd(MUL(X(K), ADD(X(v_i), X(v_j))), __func__);
}

double sb_kernel_multiplicative(double v_i, double v_j, double K)
{
  CHECK_TEST(v_i, v_j, K);
  return kernel_xd(MUL(MUL(X(K), X(v_i)), X(v_j)), __func__);
}

/* ------------------------------------------------------ callback form */

static const char *const type_names[SB_KERNEL_NTYPES] = {
    [SB_KERNEL_CONSTANT] = "constant",
    [SB_KERNEL_ADDITIVE] = "additive",
    [SB_KERNEL_MULTIPLICATIVE] = "multiplicative",
    [SB_KERNEL_BROWNIAN_CO] = "brownian-co",
    [SB_KERNEL_BROWNIAN_FM] = "brownian-fm",
    [SB_KERNEL_BROWNIAN_TR] = "brownian-tr",
    [SB_KERNEL_GRAVITY] = "gravity",
    [SB_KERNEL_SHEAR] = "shear",
    [SB_KERNEL_SAFFMAN_TURNER] = "saffman-turner",
    [SB_KERNEL_BROWNIAN_TURB] = "brownian-turb",
    [SB_KERNEL_KINETIC] = "kinetic",
    [SB_KERNEL_ABRAHAMSON] = "abrahamson",
    [SB_KERNEL_DIFFUSION] = "diffusion",
};

const char *sb_kernel_type_name(sb_kernel_type type)
{
  if ((int)type < 0 || type >= SB_KERNEL_NTYPES)
    return NULL;
  return type_names[type];
}

int sb_kernel_type_from_name(const char *name, sb_kernel_type *type)
{
  if (name)
    for (int t = 0; t < SB_KERNEL_NTYPES; t++)
      if (!strcmp(name, type_names[t])) {
        if (type)
          *type = (sb_kernel_type)t;
        return SB_SUCCESS;
      }
  char valid[300] = "";
  for (int t = 0; t < SB_KERNEL_NTYPES; t++) {
    size_t n = strlen(valid);
    snprintf(valid + n, sizeof valid - n, "%s%s", t ? ", " : "",
             type_names[t]);
  }
  return sbi_error(SB_EINVAL, __func__, "unknown kernel name '%s'; valid: %s",
                   name ? name : "(null)", valid);
}

int sb_kernel_spec_init(sb_kernel_spec *s, sb_kernel_type type)
{
  if (!s || (int)type < 0 || type >= SB_KERNEL_NTYPES)
    return sbi_error(SB_EINVAL, __func__, "invalid kernel type %d",
                     (int)type);
  s->type = type;
  s->K = 1.0;
  s->T = 293.15;
  s->mu = 1.002e-3;
  s->rho_p = 1000.0;
  s->rho_f = 998.2;
  s->lambda = 0.0;
  s->g = 9.80665;
  s->G = 1.0;
  s->eps = 1e-4;
  s->nu = 1.004e-6;
  s->u2 = 1.0;
  s->b2 = 1e-12;
  return SB_SUCCESS;
}

int sb_kernel_spec_set(sb_kernel_spec *s, const char *key, double value)
{
  static const struct {
    const char *key;
    size_t off;
  } fields[] = {
      {"K", offsetof(sb_kernel_spec, K)},
      {"T", offsetof(sb_kernel_spec, T)},
      {"mu", offsetof(sb_kernel_spec, mu)},
      {"rho_p", offsetof(sb_kernel_spec, rho_p)},
      {"rho_f", offsetof(sb_kernel_spec, rho_f)},
      {"lambda", offsetof(sb_kernel_spec, lambda)},
      {"g", offsetof(sb_kernel_spec, g)},
      {"G", offsetof(sb_kernel_spec, G)},
      {"eps", offsetof(sb_kernel_spec, eps)},
      {"nu", offsetof(sb_kernel_spec, nu)},
      {"u2", offsetof(sb_kernel_spec, u2)},
      {"b2", offsetof(sb_kernel_spec, b2)},
  };
  if (s && key)
    for (size_t i = 0; i < sizeof fields / sizeof fields[0]; i++)
      if (!strcmp(key, fields[i].key)) {
        *(double *)((char *)s + fields[i].off) = value;
        return SB_SUCCESS;
      }
  return sbi_error(SB_EINVAL, __func__, "unknown kernel parameter '%s'",
                   key ? key : "(null)");
}

int sb_kernel_spec_check(const sb_kernel_spec *s)
{
  if (!s)
    return sbi_error(SB_EINVAL, __func__, "spec is NULL");
#define NEED(cond, what)                                                 \
  if (!(cond))                                                           \
    return sbi_error(SB_EDOM, __func__, "kernel %s: %s",                 \
                     type_names[s->type], what)
  switch (s->type) {
  case SB_KERNEL_CONSTANT:
  case SB_KERNEL_ADDITIVE:
  case SB_KERNEL_MULTIPLICATIVE:
    NEED(nonneg(s->K), "K must be finite and >= 0");
    break;
  case SB_KERNEL_BROWNIAN_CO:
    NEED(pos(s->T) && pos(s->mu), "T and mu must be > 0");
    break;
  case SB_KERNEL_BROWNIAN_FM:
    NEED(pos(s->T) && pos(s->rho_p), "T and rho_p must be > 0");
    break;
  case SB_KERNEL_BROWNIAN_TR:
    NEED(pos(s->T) && pos(s->mu) && pos(s->rho_p),
         "T, mu, rho_p must be > 0");
    NEED(nonneg(s->lambda), "lambda must be >= 0");
    break;
  case SB_KERNEL_GRAVITY:
    NEED(pos(s->rho_p) && nonneg(s->rho_f) && pos(s->mu) && nonneg(s->g),
         "need rho_p > 0, rho_f >= 0, mu > 0, g >= 0");
    break;
  case SB_KERNEL_SHEAR:
    NEED(nonneg(s->G), "G must be >= 0");
    break;
  case SB_KERNEL_SAFFMAN_TURNER:
    NEED(nonneg(s->eps) && pos(s->nu), "need eps >= 0, nu > 0");
    break;
  case SB_KERNEL_BROWNIAN_TURB:
    NEED(pos(s->T) && pos(s->mu), "T and mu must be > 0");
    NEED(nonneg(s->eps) && pos(s->nu), "need eps >= 0, nu > 0");
    break;
  case SB_KERNEL_KINETIC:
    NEED(pos(s->T) && pos(s->rho_p), "T and rho_p must be > 0");
    break;
  case SB_KERNEL_ABRAHAMSON:
    NEED(nonneg(s->u2), "u2 must be finite and >= 0");
    break;
  case SB_KERNEL_DIFFUSION:
    NEED(nonneg(s->b2), "b2 must be finite and >= 0");
    break;
  default:
    return sbi_error(SB_EINVAL, __func__, "invalid kernel type %d",
                     (int)s->type);
  }
#undef NEED
  return SB_SUCCESS;
}

double sb_radius_from_volume(double v)
{
  return cbrt(3.0 * v / (4.0 * M_PI));
}

double sb_kernel_spec_fn(double v_i, double v_j, const void *spec)
{
  const sb_kernel_spec *s = spec;
  switch (s->type) {
  case SB_KERNEL_CONSTANT:
    return s->K;
  case SB_KERNEL_ADDITIVE:
    return s->K * (v_i + v_j);
  case SB_KERNEL_MULTIPLICATIVE:
    return s->K * v_i * v_j;
  default:
    break;
  }
  double ri = sb_radius_from_volume(v_i), rj = sb_radius_from_volume(v_j);
  switch (s->type) {
  case SB_KERNEL_BROWNIAN_CO:
    return sb_kernel_brownian_co(ri, rj, s->T, s->mu);
  case SB_KERNEL_BROWNIAN_FM:
    return sb_kernel_brownian_fm(ri, rj, s->T, s->rho_p);
  case SB_KERNEL_BROWNIAN_TR:
    return sb_kernel_brownian_tr(ri, rj, s->T, s->mu, s->rho_p, s->lambda);
  case SB_KERNEL_GRAVITY:
    return sb_kernel_gravity(ri, rj, s->rho_p, s->rho_f, s->mu, s->g);
  case SB_KERNEL_SHEAR:
    return sb_kernel_shear(ri, rj, s->G);
  case SB_KERNEL_SAFFMAN_TURNER:
    return sb_kernel_saffman_turner(ri, rj, s->eps, s->nu);
  case SB_KERNEL_BROWNIAN_TURB:
    return sb_kernel_brownian_turb(ri, rj, s->T, s->mu, s->eps, s->nu);
  case SB_KERNEL_KINETIC:
    return sb_kernel_kinetic(2.0 * ri, 2.0 * rj, s->rho_p * v_i,
                             s->rho_p * v_j, s->T);
  case SB_KERNEL_ABRAHAMSON:
    return sb_kernel_abrahamson(ri, rj, s->u2, s->u2);
  case SB_KERNEL_DIFFUSION:
    return sb_kernel_diffusion(ri, rj, s->b2, s->b2);
  default:
    return NAN;
  }
}
