/* smolbridge/kernel.h — collision and agglomeration kernels (SI units).
 *
 * Convention: K(i, j) is the collision rate coefficient such that the
 * number of i–j collisions per unit volume and time is K n_i n_j (m^3/s),
 * and K n^2 / 2 for collisions within one species.  Every collision sticks
 * (efficiency psi = 1); multiply by an efficiency yourself if needed.
 *
 * Physical kernels take radii r (m), temperature T (K), dynamic viscosity
 * mu (Pa s), densities rho (kg/m^3), kinematic viscosity nu (m^2/s),
 * dissipation rate eps (m^2/s^3), shear rate G (1/s).  They return NaN and
 * record SB_EDOM (sb_last_error) when an argument is not finite and
 * positive (rho_f, lambda may be 0), and NaN with SB_ERANGE where the
 * value overflows (exceeds DBL_MAX) -- never a silent inf or NaN.  The
 * formulas are evaluated with an extended exponent, so an intermediate
 * that over- or underflows (1/m for a mass of 1e-320, k_B T for
 * T = 1e-320, 3 pi mu r for mu = 1e-320) does not matter: the value is
 * returned wherever it is a double (subnormal, or 0, where it underflows).
 * Accuracy: closed forms, a few ulp (also at those corners).
 * Boltzmann constant: k_B = 1.380649e-23 J/K (exact, SI 2019).
 * Derivations and sources: docs/kernel.md.
 */
#ifndef SMOLBRIDGE_KERNEL_H
#define SMOLBRIDGE_KERNEL_H

#include <stddef.h>
#include <smolbridge/common.h>

#ifdef __cplusplus
extern "C" {
#endif

/* ------------------------------------------------------ physical kernels */

/** Brownian, continuum regime (Smoluchowski 1917; Mohaupt 2011,
 *  eq 2.9):
 *  K = 4 pi (D_i + D_j)(r_i + r_j), D = kT/(6 pi mu r)
 *    = (2kT/3mu)(1/r_i + 1/r_j)(r_i + r_j).  Monodisperse: 8kT/(3mu).
 *  Valid for Knudsen number lambda/r << 1. */
double sb_kernel_brownian_co(double r_i, double r_j, double T, double mu);

/** Brownian, free-molecular regime (kinetic theory of spheres;
 *  Mohaupt 2011, eq 2.10): K = pi (r_i + r_j)^2 sqrt(8kT/(pi m_red)),
 *  m = rho_p 4/3 pi r^3, m_red = m_i m_j/(m_i + m_j).  Monodisperse:
 *  4 sqrt(6 kT d/rho_p).  Valid for lambda/r >> 1. */
double sb_kernel_brownian_fm(double r_i, double r_j, double T, double rho_p);

/** Brownian, transition regime, Dahneke (1983) flux-matching form:
 *  K = K_co (1 + Kn_D)/(1 + 2 Kn_D + 2 Kn_D^2),  Kn_D = K_co/(2 K_fm)
 *    = 2 (D_i + D_j)/(c_ij (r_i + r_j)),  c_ij = sqrt(c_i^2 + c_j^2),
 *  c = sqrt(8kT/(pi m)).  Tends to K_co as Kn_D -> 0 and to K_fm as
 *  Kn_D -> infinity.  (Mohaupt 2011, eq 2.13, omits K_co's size
 *  dependence and eq 2.14 writes r_i + r_j for d_i + d_j: docs/errata.md.)
 *  D includes the Cunningham slip correction C = 1 + (lambda/r)(1.257 +
 *  0.4 exp(-1.1 r/lambda)) (Davies 1945) when the gas mean free path
 *  lambda > 0; lambda = 0 gives Stokes–Einstein D. */
double sb_kernel_brownian_tr(double r_i, double r_j, double T, double mu,
                             double rho_p, double lambda);

/** Brownian kernel of Langevin spheres in the transition regime,
 *  Gopalakrishnan & Hogan (2011, Aerosol Sci. Technol. 45:1499, eq 7):
 *  with the diffusive Knudsen number
 *    Kn_D = sqrt(k_B T m_red) / (f_red R),  R = r_i + r_j,
 *  f = m/tau the friction coefficients, m_red and f_red the reduced mass
 *  and friction, and
 *    H(Kn) = (4 pi Kn^2 + 25.836 Kn^3 + sqrt(8 pi) 11.211 Kn^4)
 *            / (1 + 3.502 Kn + 7.211 Kn^2 + 11.211 Kn^3),
 *  the kernel is beta = H f_red R^3 / m_red (m^3/s).  Inputs: radii (m),
 *  masses (kg), relaxation times tau_p (s), temperature (K); every one
 *  finite and > 0 (else NaN, SB_EDOM).
 *  Limits (exact, tested): Kn_D -> 0, H -> 4 pi Kn^2 and beta -> the
 *  continuum 4 pi (D_i + D_j) R with D = kT tau/m; Kn_D -> inf,
 *  H -> sqrt(8 pi) Kn and beta -> the free-molecular pi R^2 sqrt(8 kT /
 *  (pi m_red)).  Accuracy: H is a fit of the authors' mean-first-passage
 *  Langevin simulations over 0.01 <= Kn_D <= 10 (their paper gives its
 *  quality; outside that range it only interpolates between the limits).
 *  Its first-order continuum correction H/(4 pi Kn^2) = 1 - 1.446 Kn_D
 *  agrees within 1% with the exact 1 - |zeta(1/2)| Kn_D = 1 - 1.4604 Kn_D
 *  from the Milne extrapolation length of the Klein-Kramers equation
 *  (Marshall & Watson 1985).  Unlike sb_kernel_brownian_tr (Dahneke) it
 *  takes the particles' Langevin parameters directly, as the engine does.
 *  The reduced mass and friction are formed without their products
 *  underflowing, and beyond Kn_D = 1e50 beta = (Kn g) R^2 sqrt(kT/m_red),
 *  so tau up to 1e300 gives the free-molecular limit (it was NaN).
 *  Cost: a few ns. */
double sb_kernel_brownian_gh(double r_i, double r_j, double m_i, double m_j,
                             double tau_i, double tau_j, double T);
/** Its diffusive Knudsen number Kn_D (same arguments; NaN on bad input). */
double sb_kernel_brownian_gh_kn(double r_i, double r_j, double m_i,
                                double m_j, double tau_i, double tau_j,
                                double T);
/** The dimensionless kernel H(Kn_D) of the fit, Kn_D >= 0 finite. */
double sb_kernel_gh_H(double kn);

/** Kinetic theory of hard spheres (gas molecules), diameters d (m), masses
 *  m (kg): K = pi ((d_i + d_j)/2)^2 sqrt(8kT/(pi m_red)).  Monodisperse:
 *  pi d^2 sqrt(16 kT/(pi m)).  (Mohaupt 2011, eq 3.6, is
 *  misprinted: docs/errata.md.) */
double sb_kernel_kinetic(double d_i, double d_j, double m_i, double m_j,
                         double T);

/** Kinetic theory of hard discs in 2-D (the plane's counterpart of
 *  sb_kernel_kinetic), diameters d (m), masses m (kg): the relative
 *  velocity of a Maxwellian pair has the variance k_B T/m_red per
 *  component, so its speed is Rayleigh distributed with the mean
 *  sqrt(pi k_B T/(2 m_red)), and a disc sweeps a strip of width d_i + d_j:
 *  K = (d_i + d_j) sqrt(pi k_B T/(2 m_red)), in m^2/s (a rate per unit
 *  area density).  Monodisperse: 2 d sqrt(pi k_B T/m).  All arguments
 *  > 0 (NaN and SB_EDOM otherwise). */
double sb_kernel_kinetic_2d(double d_i, double d_j, double m_i, double m_j,
                            double T);

/** Differential gravitational settling (Pearson, Valioulis & List
 *  1984; Mohaupt 2011, eq 2.3): K = pi (r_i + r_j)^2 |U_i - U_j|, Stokes
 *  terminal velocity U = 2 (rho_p - rho_f) g r^2/(9 mu).  No hydrodynamic
 *  interaction (collision efficiency 1); valid for particle Reynolds
 *  number << 1. */
double sb_kernel_gravity(double r_i, double r_j, double rho_p, double rho_f,
                         double mu, double g);

/** Laminar shear, velocity gradient G (Smoluchowski 1917; Mohaupt 2011,
 *  eq 2.4): K = (4/3) G (r_i + r_j)^3. */
double sb_kernel_shear(double r_i, double r_j, double G);

/** Saffman & Turner (1956) turbulent kernel, inertialess particles much
 *  smaller than the Kolmogorov scale (Mohaupt 2011, eq 2.5):
 *  K = sqrt(8 pi eps/(15 nu)) (r_i + r_j)^3. */
double sb_kernel_saffman_turner(double r_i, double r_j, double eps,
                                double nu);

/** Abrahamson (1975) kernel for inertial particles (Stokes number >> 1)
 *  whose velocities are independent isotropic Gaussians with per-component
 *  variances u2_i, u2_j (m^2/s^2):
 *  K = sqrt(8 pi) (r_i + r_j)^2 sqrt(u2_i + u2_j)
 *    = sqrt(32 pi/3) (r_i + r_j)^2 sqrt((E_i + E_j)/2),  E = (3/2) u2
 *  (the kinetic energy per unit mass).  Mohaupt (2011) eq 2.7 drops the
 *  square root on (E_i + E_j)/2 (docs/errata.md).  With u2 = kT/m it
 *  equals sb_kernel_kinetic. */
double sb_kernel_abrahamson(double r_i, double r_j, double u2_i,
                            double u2_j);

/** Pass-through (flux) kernel of two identical Langevin spheres in the
 *  linear shear U_x = G y (m^3/s): each relaxes in time tau (s) towards
 *  the local flow and has the stationary velocity variance u2 = B^2 tau/2
 *  (m^2/s^2) per component in the gradient and vorticity directions.  The
 *  peculiar velocity c = u - G y e_x obeys dc_x = -c_x/tau dt - G c_y dt +
 *  B dW_x, dc_y = -c_y/tau dt + B dW_y, so the relative velocity at
 *  separation R = r_i + r_j has the mean G R n_x n_y along the normal n
 *  and the covariance S = 2 u2 [[1 + (G tau)^2/2, -G tau/2, 0],
 *  [-G tau/2, 1, 0], [0, 0, 1]].  With uniform, independent positions the
 *  mean number of entries into contact per unit time is Rice's flux
 *    K = R^2 int dOmega [s phi(m/s) - m Phi(-m/s)],  m = G R n_x n_y,
 *    s^2 = n.S.n
 *  (Rice 1944): the kernel of pass-through counting at every Knudsen
 *  number (docs/engine_forces.md §8.3b).  Limits: G = 0, Abrahamson's
 *  sb_kernel_abrahamson(r_i, r_j, u2, u2); u2 -> 0, the laminar
 *  (4/3) G R^3 of sb_kernel_shear (returned exactly at u2 = 0); the
 *  additive K_Abrahamson + K_shear overestimates it by 7-29% at
 *  Pe_k = G R/sqrt(2 u2) = 0.3-3.  96 x 192-node quadrature on the sphere:
 *  relative accuracy 1e-14 against 30-digit values at Pe_k = 0.3-3 and
 *  G tau = 0.01-0.5 (tests/test_kernel.c); the integrand steepens as
 *  Pe_k grows (2e-4 at u2 -> 0) and its kink at n_x = 0 sharpens as
 *  G tau grows (an audit against mpmath quadrature: ~1e-16 up to
 *  G tau = 5, 5e-9 at 20, 3e-6 at 100, 4.5e-5 from 1e3 on: mpmath at 1e3
 *  and 1e6, the limit R^2 sqrt(2 pi u2) G tau (1 + O(1/(G tau))) beyond;
 *  the variance is formed without (G tau)^2, so any G tau up to ~1e308
 *  works).  NaN and SB_EDOM unless the radii are > 0 and u2, tau, G >= 0,
 *  all finite; NaN and SB_ERANGE where K overflows (e.g. tau = G = 1e200,
 *  K ~ 1e386). */
double sb_kernel_shear_langevin(double r_i, double r_j, double u2, double tau,
                                double G);

/** Pure diffusion (Friedlander 2000; Mohaupt 2011,
 *  eqs 5.19, 6.18): each particle's position
 *  diffuses with per-component variance rate b2 = B_pos^2 (m^2/s), the
 *  relative position with B_ij^2 = b2_i + b2_j; K = 2 pi B_ij^2 (r_i + r_j)
 *  = 4 pi D_ij (r_i + r_j), D_ij = B_ij^2/2.  Monodisperse: 4 pi B_pos^2 d. */
double sb_kernel_diffusion(double r_i, double r_j, double b2_i, double b2_j);

/** Per-particle Brownian position variance rate in the diffusive limit,
 *  B_pos^2 = 2 kT tau_p/m_p = 2 D = kT/(3 pi mu r) (m^2/s) (Mohaupt 2011,
 *  eq 6.22, first term). */
double sb_brownian_b2(double r, double T, double mu);

/** Turbulent relative (pair) variance rate at centre separation r (Mohaupt
 *  2011, eqs 6.13–6.17; Brunk, Koch & Lion 1998 with total strain
 *  tau_S Gamma_k = sqrt(270/pi)):
 *  B_ij^2(r) = D_ij(r)/3 = sqrt(2/(15 pi)) sqrt(eps/nu) r^2.
 *  With r = r_i + r_j, sb_kernel_diffusion-type 2 pi B_ij^2 r recovers
 *  Saffman–Turner exactly (eqs 6.18–6.19). */
double sb_turb_pair_b2(double r, double eps, double nu);

/** Combined Brownian + turbulent pair diffusion (Mohaupt 2011,
 *  eqs 6.20–6.23):
 *  B_ij^2 = b2_Brown,i + b2_Brown,j + B_turb,ij^2(r_i + r_j) and
 *  K = 2 pi B_ij^2 (r_i + r_j) = K_co + K_Saffman–Turner. */
double sb_kernel_brownian_turb(double r_i, double r_j, double T, double mu,
                               double eps, double nu);

/** Steady collision rate when the pair diffusivity depends on the
 *  separation r (the test of the contact-value conjecture of Mohaupt
 *  2011, §6.3.2, §7.1.1; docs/kernel.md).  The relative position
 *  diffuses isotropically with per-component variance rate
 *    b2(r) = b2_0 + b2_2 (r/R)^2   (m^2/s),  R = the contact distance,
 *  i.e. dc/dt = div(kappa grad c), kappa = b2/2 (Ito SDE dX = grad kappa
 *  dt + sqrt(b2) dW), absorbing at r = R, uniform far away.  Exact:
 *    K = 4 pi / int_R^inf ds/(s^2 kappa(s)) = 2 pi b2_2 R / g(t),
 *    t = sqrt(b2_0/b2_2),  g(t) = (t - atan t)/t^3  (g(0) = 1/3).
 *  b2_2 = 0: Smoluchowski, 2 pi b2_0 R.  b2_0 = 0 (pure r^2 growth, the
 *  dissipative range): 6 pi b2_2 R, three times the rate 2 pi b2(R) R
 *  that the diffusivity frozen at contact gives.  For an anisotropic
 *  pair diffusivity (Brunk, Koch & Lion 1998) only the radial component
 *  enters, as b2(r).  Domain: R > 0, b2_0, b2_2 >= 0 not both 0, all
 *  finite, else NaN and SB_EDOM.  Accuracy: a few ulp (series of g for
 *  t <= 0.4), also where 2 pi b2 R over/underflows as a double product
 *  (b2 near DBL_MAX, R = 1e-320 or 1e300 with b2 = 1e-315: formed with
 *  an extended exponent); NaN and SB_ERANGE where K exceeds DBL_MAX. */
double sb_kernel_diffusion_r2(double R, double b2_0, double b2_2);

/** sb_kernel_diffusion_r2 for Brownian + turbulent pair diffusion with
 *  the turbulent part growing as r^2: b2_0 = sb_brownian_b2(r_i) +
 *  sb_brownian_b2(r_j), b2_2 = sb_turb_pair_b2(r_i + r_j, eps, nu).
 *  Compare sb_kernel_brownian_turb (the same diffusivity frozen at
 *  contact, = K_co + K_Saffman-Turner); with T -> 0 this is three times
 *  Saffman-Turner.  Domain: radii, T, mu, nu finite and > 0, eps finite
 *  and >= 0, else NaN and SB_EDOM.  b2_0 and b2_2 are formed with an
 *  extended exponent, so K is returned wherever it is a double even if
 *  they are not (T = 1e300 with radii of 1e-300); NaN and SB_ERANGE
 *  naming this function where K exceeds DBL_MAX. */
double sb_kernel_brownian_turb_r2(double r_i, double r_j, double T,
                                  double mu, double eps, double nu);

/* ------------------------------------------------------ test kernels */

/** Constant kernel K (m^3/s).  Volumes v_i, v_j [m^3] finite and > 0 and
 *  K finite and >= 0 (as sb_kernel_spec_check), else NaN and SB_EDOM. */
double sb_kernel_constant(double v_i, double v_j, double K);
/** Additive (Golovin) kernel K (v_i + v_j), K in 1/s.  Domain as the
 *  constant kernel; NaN and SB_ERANGE where the value overflows. */
double sb_kernel_additive(double v_i, double v_j, double K);
/** Multiplicative kernel K v_i v_j, K in 1/(m^3 s).  Domain as the
 *  constant kernel; NaN and SB_ERANGE where the value overflows (the
 *  product is formed without intermediate over/underflow). */
double sb_kernel_multiplicative(double v_i, double v_j, double K);

/* ------------------------------------------------------ callback form */

/** A kernel as a function of the two particle volumes (m^3), used by the
 *  population balance (<smolbridge/pbe.h>).  It must be symmetric,
 *  non-negative and finite for positive volumes, and thread-safe. */
typedef double (*sb_kernel_fn)(double v_i, double v_j, const void *params);

/** Built-in kernels available through sb_kernel_spec_fn. */
typedef enum {
  SB_KERNEL_CONSTANT = 0,   /* K */
  SB_KERNEL_ADDITIVE,       /* K (v_i + v_j) */
  SB_KERNEL_MULTIPLICATIVE, /* K v_i v_j */
  SB_KERNEL_BROWNIAN_CO,    /* T, mu */
  SB_KERNEL_BROWNIAN_FM,    /* T, rho_p */
  SB_KERNEL_BROWNIAN_TR,    /* T, mu, rho_p, lambda */
  SB_KERNEL_GRAVITY,        /* rho_p, rho_f, mu, g */
  SB_KERNEL_SHEAR,          /* G */
  SB_KERNEL_SAFFMAN_TURNER, /* eps, nu */
  SB_KERNEL_BROWNIAN_TURB,  /* T, mu, eps, nu */
  SB_KERNEL_KINETIC,        /* T, rho_p: hard spheres, m = rho_p v */
  SB_KERNEL_ABRAHAMSON,     /* u2: same velocity variance for all sizes */
  SB_KERNEL_DIFFUSION,      /* b2: same position variance rate */
  SB_KERNEL_NTYPES
} sb_kernel_type;

/** Parameters of a built-in kernel (only those listed for its type are
 *  used; radii are r = (3 v/(4 pi))^(1/3)). */
typedef struct {
  sb_kernel_type type;
  double K;      /**< test kernels' coefficient */
  double T;      /**< temperature, K */
  double mu;     /**< dynamic viscosity, Pa s */
  double rho_p;  /**< particle density, kg/m^3 */
  double rho_f;  /**< fluid density, kg/m^3 */
  double lambda; /**< gas mean free path, m (0: no slip correction) */
  double g;      /**< gravitational acceleration, m/s^2 */
  double G;      /**< laminar shear rate, 1/s */
  double eps;    /**< turbulent dissipation rate, m^2/s^3 */
  double nu;     /**< kinematic viscosity, m^2/s */
  double u2;     /**< velocity variance per component, m^2/s^2
                      (abrahamson) */
  double b2;     /**< position variance rate B_pos^2, m^2/s (diffusion) */
} sb_kernel_spec;

/** Fill *s with `type` and defaults: K = 1, water at 20 C (T = 293.15,
 *  mu = 1.002e-3, rho_f = 998.2, nu = 1.004e-6), rho_p = 1000, lambda = 0,
 *  g = 9.80665, G = 1, eps = 1e-4, u2 = 1, b2 = 1e-12.  SB_EINVAL for an
 *  unknown type. */
int sb_kernel_spec_init(sb_kernel_spec *s, sb_kernel_type type);

/** Type from its name ("constant", "additive", "multiplicative",
 *  "brownian-co", "brownian-fm", "brownian-tr", "gravity", "shear",
 *  "saffman-turner", "brownian-turb", "kinetic", "abrahamson",
 *  "diffusion"); returns SB_EINVAL if unknown, with the valid names in
 *  the message.  type may be NULL (the name is only checked). */
int sb_kernel_type_from_name(const char *name, sb_kernel_type *type);
/** Name of a type (NULL if out of range). */
const char *sb_kernel_type_name(sb_kernel_type type);

/** Set a parameter by its field name ("K", "T", "mu", "rho_p", "rho_f",
 *  "lambda", "g", "G", "eps", "nu", "u2", "b2"); SB_EINVAL if unknown. */
int sb_kernel_spec_set(sb_kernel_spec *s, const char *key, double value);

/** Check that the parameters used by s->type are valid (SB_EDOM if not). */
int sb_kernel_spec_check(const sb_kernel_spec *s);

/** The built-in kernel as an sb_kernel_fn; `spec` is a const
 *  sb_kernel_spec * (checked with sb_kernel_spec_check beforehand). */
double sb_kernel_spec_fn(double v_i, double v_j, const void *spec);

/** Radius of the sphere of volume v: (3 v/(4 pi))^(1/3). */
double sb_radius_from_volume(double v);

#ifdef __cplusplus
}
#endif

#endif /* SMOLBRIDGE_KERNEL_H */
