/* smolbridge/dlvo.h — DLVO interaction of two spheres or of a sphere and a
 * plane (SI units): London–van der Waals and electric double-layer
 * energies and forces, the energy barrier, the relative kinetic energy of
 * two colliding particles and its laws, and the sticking rule.
 *
 * Geometry: surface-to-surface separation D > 0 (m), radii r1 > 0 and
 * r2 > 0 (m); r2 = +INFINITY means a sphere of radius r1 facing a plane
 * (every formula below is the r2 -> infinity limit of the sphere–sphere
 * one).  R = r1 r2/(r1 + r2) is the Derjaguin radius (R = r1 for a plane).
 * Energies W are in J, forces F = -dW/dD in N (F > 0 repulsive).
 *
 * Models (derivations and sources in docs/dlvo.md):
 *  - van der Waals, full Hamaker (1937) sphere–sphere form
 *      W = -(A/6) [2 r1 r2/(D(D + 2r1 + 2r2)) + 2 r1 r2/((D + 2r1)(D + 2r2))
 *                  + ln(D(D + 2r1 + 2r2)/((D + 2r1)(D + 2r2)))]
 *    = -(A/6) g(t), t = 2 r1 r2/(D(D + 2r1 + 2r2)),
 *      g(t) = t + t/(1 + 2t) - ln(1 + 2t)   (sphere–plane: t = r1/D);
 *    its Derjaguin (D << r) limit is Mohaupt (2011) eqs 1.6–1.7, W = -A R/(6D)
 *    (Israelachvili 2011, ch. 13), and at large D it decays as
 *    -(16/9) A r1^3 r2^3/D^6 (spheres) or -(2/9) A r1^3/D^3 (plane).
 *    A is the Hamaker constant of the two bodies across the medium.
 *  - double layer, linear superposition approximation (LSA) with the
 *    Derjaguin approximation, symmetric z:z electrolyte (Israelachvili 2011
 *    ch. 14, weak-overlap approximation; Gregory 1975):
 *      W = 64 pi eps R (kT/(z e))^2 g1 g2 exp(-kappa D),
 *      g_i = tanh(z e psi_i/(4 kT)),   eps = eps_r eps_0,
 *    equivalently 128 pi R n0 kT g1 g2 exp(-kappa D)/kappa^2 with
 *    kappa^2 = 2 n0 z^2 e^2/(eps kT).  Valid for kappa D >~ 1 (weak
 *    overlap), any potential.  This is Mohaupt (2011) eq 1.9 corrected:
 *    the thesis prints the flat-plate energy per unit area with kappa^-1
 *    in the denominator (dimensionally wrong), omits the Derjaguin factor
 *    2 pi R/kappa, and writes g = tanh(e phi0/4) without z/kT (eq 1.10);
 *    its forces (eqs 1.13–1.14) have the sign of +dW/dD (docs/errata.md).
 *  - double layer at constant surface potential, low potentials
 *    (Hogg, Healy & Fuerstenau 1966, "HHF"), Derjaguin approximation:
 *      W = pi eps R [(psi1 + psi2)^2 ln(1 + exp(-kappa D))
 *                    + (psi1 - psi2)^2 ln(1 - exp(-kappa D))].
 *    Valid for |psi| <~ 25 mV and kappa R >> 1, all kappa D; it agrees
 *    with LSA when both apply (large kappa D, small psi).
 *
 * Constants: k_B = 1.380649e-23 J/K and e = 1.602176634e-19 C (exact,
 * SI 2019); eps_0 = 8.8541878128e-12 F/m (CODATA 2018).
 *
 * Accuracy: the closed forms are evaluated without cancellation (the
 * Hamaker bracket by its series for t < 1/4, by log1p-minus-x beyond:
 * relative error below 2e-14 for every D); the _e forms return honest
 * absolute error bounds, checked in tests/test_dlvo.c against mpmath at
 * 60 digits.  Errors: NaN (or the status) and SB_EDOM on a bad argument.
 *
 * Extreme arguments: potentials, forces and kappa are formed with an
 * extended exponent (no intermediate over/underflows), so each returns
 * its value wherever it is a double -- 0 or a subnormal where it
 * underflows (the error bound covers that) -- and NaN with SB_ERANGE
 * (the message names the function) where the value or its error bound
 * exceeds DBL_MAX; never a silent inf or NaN.  One documented exception:
 * the Hamaker energy (and the total energy with it) is -inf for A > 0
 * (+inf for A < 0) with SB_SUCCESS where t = R/D exceeds DBL_MAX (D below
 * about R/DBL_MAX: the contact singularity), even though |W| ~ A t/6 may
 * still be a double there.  Checked over 1e-320 ... DBL_MAX, +-inf for
 * every argument against mpmath (docs/dlvo.md, "Extreme arguments").
 */
#ifndef SMOLBRIDGE_DLVO_H
#define SMOLBRIDGE_DLVO_H

#include <gsl/gsl_rng.h>
#include <smolbridge/common.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Elementary charge, C (exact, SI 2019). */
#define SB_DLVO_ECHARGE 1.602176634e-19
/** Vacuum permittivity, F/m (CODATA 2018). */
#define SB_DLVO_EPS0 8.8541878128e-12

/* ============================================================ Debye length */

/** Inverse Debye length of a symmetric z:z electrolyte,
 *  kappa = sqrt(2 n0 z^2 e^2/(eps_r eps_0 k_B T)), 1/m.  n0 [m^-3] > 0 is
 *  the bulk number density of each ion species (1 mM = 6.02214076e23 m^-3),
 *  z > 0, eps_r > 0, T [K] > 0.  Water at 25 C, 1 mM 1:1: 1/kappa = 9.6 nm.
 *  NaN and SB_EDOM on bad input, NaN and SB_ERANGE where kappa exceeds
 *  DBL_MAX. */
double sb_dlvo_debye_kappa(double n0, double z, double eps_r, double T);

/* ============================================================ van der Waals */

/** Full Hamaker sphere–sphere (r2 = INFINITY: sphere–plane) energy, J.
 *  A [J] finite (> 0 attractive), r1 > 0, r2 > 0 or +inf, D > 0.
 *  Returns -inf (A > 0; +inf for A < 0, 0 for A = 0) with SB_SUCCESS
 *  where t = 2 r1 r2/(D(D + 2r1 + 2r2)) exceeds DBL_MAX (D below about
 *  R/DBL_MAX: the contact singularity, by convention); NaN and SB_ERANGE
 *  where W exceeds DBL_MAX otherwise (|A| near DBL_MAX). */
double sb_dlvo_vdw_hamaker(double A, double r1, double r2, double D);
int sb_dlvo_vdw_hamaker_e(double A, double r1, double r2, double D,
                          sb_result *res);
/** Its force -dW/dD, N:
 *  -(32/3) A r1^3 r2^3 (D + r1 + r2)/[(D(D + 2r1 + 2r2))^2 ((D + 2r1)(D +
 *  2r2))^2]; sphere–plane -(2/3) A r1^3/(D^2 (D + 2r1)^2).  NaN and
 *  SB_ERANGE where F exceeds DBL_MAX (e.g. A = 1e300 J, or D below about
 *  1e-168 m for A = 1e-20 J, R = 1 um), also where t does. */
double sb_dlvo_vdw_hamaker_force(double A, double r1, double r2, double D);
int sb_dlvo_vdw_hamaker_force_e(double A, double r1, double r2, double D,
                                sb_result *res);

/** Derjaguin (short-distance) form -A R/(6D), J (Mohaupt 2011,
 *  eqs 1.6–1.7).  NaN and SB_ERANGE where it exceeds DBL_MAX. */
double sb_dlvo_vdw_derjaguin(double A, double r1, double r2, double D);
int sb_dlvo_vdw_derjaguin_e(double A, double r1, double r2, double D,
                            sb_result *res);
/** Its force -A R/(6 D^2), N; NaN and SB_ERANGE where it exceeds
 *  DBL_MAX (e.g. D = 1e-320 m). */
double sb_dlvo_vdw_derjaguin_force(double A, double r1, double r2, double D);
int sb_dlvo_vdw_derjaguin_force_e(double A, double r1, double r2, double D,
                                  sb_result *res);

/* ============================================================ double layer */

/** LSA double-layer energy (formula above), J.  kappa [1/m] > 0,
 *  eps_r > 0, T [K] > 0, z > 0, psi1, psi2 [V] finite.  exp(-kappa D) is
 *  formed without underflow, so a large prefactor times a tiny
 *  exponential is right; NaN and SB_ERANGE where W exceeds DBL_MAX. */
double sb_dlvo_edl_lsa(double D, double r1, double r2, double kappa,
                       double eps_r, double T, double z, double psi1,
                       double psi2);
int sb_dlvo_edl_lsa_e(double D, double r1, double r2, double kappa,
                      double eps_r, double T, double z, double psi1,
                      double psi2, sb_result *res);
/** Its force kappa W, N. */
double sb_dlvo_edl_lsa_force(double D, double r1, double r2, double kappa,
                             double eps_r, double T, double z, double psi1,
                             double psi2);
int sb_dlvo_edl_lsa_force_e(double D, double r1, double r2, double kappa,
                            double eps_r, double T, double z, double psi1,
                            double psi2, sb_result *res);

/** HHF constant-potential double-layer energy (formula above), J.  For
 *  kappa D > 1 evaluated as pi eps R [(psi1^2 + psi2^2) ln(1 - e^{-2 kappa
 *  D}) + 4 psi1 psi2 atanh(e^{-kappa D})] (the same function without the
 *  cancellation of the printed terms, e.g. at psi = 1e300 V); NaN and
 *  SB_ERANGE where W exceeds DBL_MAX. */
double sb_dlvo_edl_hhf(double D, double r1, double r2, double kappa,
                       double eps_r, double psi1, double psi2);
int sb_dlvo_edl_hhf_e(double D, double r1, double r2, double kappa,
                      double eps_r, double psi1, double psi2,
                      sb_result *res);
/** Its force pi eps R kappa [(psi1 + psi2)^2/(e^{kappa D} + 1)
 *  - (psi1 - psi2)^2/(e^{kappa D} - 1)], N; for kappa D > 1 as
 *  pi eps R kappa [2 psi1 psi2/sinh(kappa D) - 2 (psi1^2 + psi2^2)/
 *  expm1(2 kappa D)].  NaN and SB_ERANGE where F exceeds DBL_MAX. */
double sb_dlvo_edl_hhf_force(double D, double r1, double r2, double kappa,
                             double eps_r, double psi1, double psi2);
int sb_dlvo_edl_hhf_force_e(double D, double r1, double r2, double kappa,
                            double eps_r, double psi1, double psi2,
                            sb_result *res);

/* ============================================================ a pair */

typedef enum {
  SB_DLVO_VDW_DERJAGUIN = 0, /**< -A R/(6D) (Mohaupt 2011, eqs 1.6–1.7) */
  SB_DLVO_VDW_HAMAKER = 1    /**< full Hamaker sphere–sphere/plane form */
} sb_dlvo_vdw_model;

typedef enum {
  SB_DLVO_EDL_LSA = 0, /**< linear superposition (Mohaupt 2011, eq 1.9) */
  SB_DLVO_EDL_HHF = 1  /**< constant potential, low potential (HHF) */
} sb_dlvo_edl_model;

/** A sphere–sphere or sphere–plane pair in an electrolyte (SI units).
 *  Use sb_dlvo_debye_kappa to get kappa from the ion density. */
typedef struct {
  double r1, r2;     /**< radii, m (r2 = INFINITY: plane) */
  double A;          /**< Hamaker constant, J (>= 0 for the barrier) */
  double T;          /**< temperature, K */
  double eps_r;      /**< relative permittivity of the medium (water 78.4) */
  double z;          /**< valence of the symmetric electrolyte (LSA only) */
  double kappa;      /**< inverse Debye length, 1/m */
  double psi1, psi2; /**< surface potentials, V */
  double d_contact;  /**< closest separation for the barrier search, m > 0
                          (e.g. 0.4 nm: where Born repulsion takes over) */
  sb_dlvo_vdw_model vdw;
  sb_dlvo_edl_model edl;
} sb_dlvo_pair;

/** Check every field of *p (SB_SUCCESS or SB_EDOM with a message). */
int sb_dlvo_pair_check(const sb_dlvo_pair *p);

/** Total DLVO energy W(D) = W_vdw + W_edl, J (Mohaupt 2011, eqs
 *  1.11–1.12, corrected as above).  D > 0.  -inf with the Hamaker model
 *  where its energy is (D below about R/DBL_MAX); NaN and SB_ERANGE where
 *  a part or the sum exceeds DBL_MAX. */
double sb_dlvo_energy(const sb_dlvo_pair *p, double D);
int sb_dlvo_energy_e(const sb_dlvo_pair *p, double D, sb_result *res);
/** Total force F(D) = -dW/dD, N (> 0 repulsive; Mohaupt 2011, eqs
 *  1.13–1.14, with the sign corrected).  NaN and SB_ERANGE where a part or
 *  the sum exceeds DBL_MAX. */
double sb_dlvo_force(const sb_dlvo_pair *p, double D);
int sb_dlvo_force_e(const sb_dlvo_pair *p, double D, sb_result *res);

/* ============================================================ barrier */

typedef enum {
  /** W <= 0 everywhere on [d_contact, inf): nothing to overcome;
   *  W_max = 0, D_max = +INFINITY. */
  SB_DLVO_NO_BARRIER = 0,
  /** an interior maximum W_max > 0 at D_max in (d_contact, inf). */
  SB_DLVO_BARRIER = 1,
  /** W decreases at contact and W(d_contact) > 0 is the largest value:
   *  the maximum lies below d_contact; W_max = W(d_contact),
   *  D_max = d_contact. */
  SB_DLVO_BARRIER_CONTACT = 2
} sb_dlvo_barrier_kind;

/** Result of sb_dlvo_barrier. */
typedef struct {
  sb_dlvo_barrier_kind kind;
  double W_max, W_max_err; /**< energy to overcome from infinity, J, >= 0 */
  double D_max, D_max_err; /**< its position, m */
  double W_min2, D_min2;   /**< deepest local minimum beyond D_max
                                (secondary minimum), J and m; NaN if none */
} sb_dlvo_barrier_t;

/** The energy barrier W_max = max(0, sup_{D >= d_contact} W(D)): the
 *  kinetic energy two particles coming from far apart need to reach
 *  contact.  Method: the sign of F is scanned on a log grid (40 points
 *  per decade) from d_contact to a D_hi beyond which no stationary point
 *  can exist (F < 0 and |F_edl| < 1e-3 |F_vdw| at D_hi >= d_contact +
 *  40/kappa, where the exponential has overtaken the power law); each
 *  sign change is refined with GSL's Brent root finder on F
 *  (relative tolerance 1e-14).  Stationary points closer together than
 *  the grid spacing (a barrier of relative height < ~1e-4 of its
 *  neighbour terms) may be missed.  Requires A >= 0.  Returns SB_SUCCESS
 *  (the kind says whether there is a barrier), SB_EDOM on bad input,
 *  SB_EMAXITER if the tail or the root finder fails. */
int sb_dlvo_barrier(const sb_dlvo_pair *p, sb_dlvo_barrier_t *b);

/* ============================================================ kinetic energy */

/** Relative kinetic energy of two particles (Mohaupt 2011, App. C,
 *  eq C.13):
 *  E = (1/2) m1 m2/(m1 + m2) |v1 - v2|^2, J.  Masses [kg] > 0, velocities
 *  [m/s] 3-vectors, finite.  NaN and SB_EDOM otherwise.  Any finite
 *  masses and velocities: |v1 - v2| outside [1e-100, 1e100] m/s is
 *  evaluated in scaled form (no overflow of the difference or its square,
 *  none of m1/m2), so E is right (a few ulps) wherever it is a normal
 *  double, and 0 where it underflows; NaN and SB_ERANGE where it
 *  overflows. */
double sb_dlvo_erel(double m1, double m2, const double v1[3],
                    const double v2[3]);

/** The part of it along the line of centres n (any non-zero 3-vector,
 *  e.g. x2 - x1): (1/2) mu ((v1 - v2).n)^2/|n|^2, J — the energy that
 *  works against a central force; the tangential part is conserved.
 *  Domain and overflow as sb_dlvo_erel (n of any finite magnitude). */
double sb_dlvo_erel_normal(double m1, double m2, const double v1[3],
                           const double v2[3], const double n[3]);

/** Sticking rule (Mohaupt 2011, §1.2.4): 1 (adhesion) if E_rel > W_max,
 *  0 (rebound) otherwise (also if either is NaN). */
int sb_dlvo_sticks(double E_rel, double W_max);

/** Laws of the relative kinetic energy when the two velocities are
 *  independent stationary Maxwellians (each component of v_i ~
 *  N(0, kT/m_i), so v1 - v2 ~ N(0, kT/mu) per component).  With
 *  theta = kT (or mu s2 in general, s2 the per-component variance of the
 *  relative velocity) every law is a Gamma(shape k, scale theta):
 *   STATIONARY        E = mu|w|^2/2 of a random pair:  k = dim/2
 *   STATIONARY_NORMAL E_n of a random pair, fixed n:   k = 1/2
 *   COLLISION         E of colliding pairs (weighted by the approach
 *                     flux max(0, -w.n) over isotropic n): k = (dim+1)/2
 *   COLLISION_NORMAL  E_n of colliding pairs:          k = 1
 *  (3-D: 3/2, 1/2, 2, 1).  The COLLISION laws are those of pairs sampled
 *  at contact in a ballistic (kinetic-theory) encounter; the STATIONARY
 *  law is that of velocities drawn independently of the encounter (e.g.
 *  diffusive regime with velocities resampled from equilibrium). */
typedef enum {
  SB_DLVO_EREL_STATIONARY = 0,
  SB_DLVO_EREL_STATIONARY_NORMAL = 1,
  SB_DLVO_EREL_COLLISION = 2,
  SB_DLVO_EREL_COLLISION_NORMAL = 3
} sb_dlvo_erel_law;

/** Gamma shape k of a law in dimension dim (1, 2 or 3); NaN if invalid. */
double sb_dlvo_erel_shape(sb_dlvo_erel_law law, int dim);

/** Density of E (1/J) at E >= 0 (E = inf allowed); theta [J] > 0,
 *  finite.  E = 0 gives +inf for k = 1/2, 1/theta for k = 1, 0
 *  otherwise; 0 where E/theta overflows or e^-E/theta underflows; NaN and
 *  SB_ERANGE where the density overflows (theta below ~1e-308 J). */
double sb_dlvo_erel_pdf(double E, double theta, sb_dlvo_erel_law law,
                        int dim);
/** P(E_rel <= E) and Q = P(E_rel > E), each computed directly (no 1 - x):
 *  with x = E/theta,
 *   k = 1/2: P = erf(sqrt x),  Q = erfc(sqrt x)
 *   k = 1:   P = -expm1(-x),   Q = exp(-x)
 *   k = 3/2: Q = erfc(sqrt x) + 2 sqrt(x/pi) exp(-x)
 *   k = 2:   Q = (1 + x) exp(-x)
 *  and P for k = 3/2, 2 by the positive series x^k e^{-x} sum_n
 *  x^n/Gamma(k+n+1) for x < 2, the closed forms 1 - Q otherwise.
 *  Q(W_max) is the probability of sticking under the rule above.
 *  Domain: E >= 0 (inf allowed), theta > 0 finite; where E/theta
 *  overflows (E = inf, or theta tiny) P = 1 and Q = 0, the correctly
 *  rounded values.  Relative error <= 1e-14; err bounds from GSL's
 *  erf/erfc; for P with k = 1 and k = 2 a bound of a few ulp at every x
 *  (the rounding of x = E/theta enters through the density, x e^-x), for
 *  Q the x eps relative that e^-x's sensitivity to x requires. */
double sb_dlvo_erel_P(double E, double theta, sb_dlvo_erel_law law,
                      int dim);
int sb_dlvo_erel_P_e(double E, double theta, sb_dlvo_erel_law law, int dim,
                     sb_result *res);
double sb_dlvo_erel_Q(double E, double theta, sb_dlvo_erel_law law,
                      int dim);
int sb_dlvo_erel_Q_e(double E, double theta, sb_dlvo_erel_law law, int dim,
                     sb_result *res);
/** log Q, finite where Q underflows (E/theta > ~700); -inf at E = inf
 *  (Q = 0); NaN and SB_ERANGE where E is finite but E/theta overflows
 *  (log Q ~ -E/theta is then below -DBL_MAX). */
double sb_dlvo_erel_logQ(double E, double theta, sb_dlvo_erel_law law,
                         int dim);

/** One draw of E_rel from a law (gsl_ran_gamma, one call). NaN on bad
 *  input. */
double sb_dlvo_erel_sample(const gsl_rng *r, double theta,
                           sb_dlvo_erel_law law, int dim);

#ifdef __cplusplus
}
#endif

#endif /* SMOLBRIDGE_DLVO_H */
