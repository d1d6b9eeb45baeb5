/* smolbridge/pbe.h — the Smoluchowski population balance for pure
 * coagulation, integrated with SUNDIALS CVODE (BDF, Newton), and its
 * analytic solutions.
 *
 * Discrete system (Smoluchowski 1917; Mohaupt 2011, eq 2.2), sizes
 * k = 1..K, volumes v_k = k v1:
 *   dn_k/dt = 1/2 sum_{i+j=k} K(v_i,v_j) n_i n_j - n_k sum_{i=1..K} K(v_i,v_k) n_i
 *             + s_k(t) - r(t, v_k) n_k
 * (collisions that would make a size above K leave the system: their mass
 * is reported as M1 drift).  Sectional method: the fixed-pivot technique of
 * Kumar & Ramkrishna (1996, Chem. Eng. Sci. 51:1311) on a geometric grid of
 * pivots x_i = v1 r^i, i = 0..N-1: a particle of volume x_j + x_k between
 * pivots x_i <= v <= x_{i+1} is split between them with fractions
 * (x_{i+1} - v)/(x_{i+1} - x_i) and (v - x_i)/(x_{i+1} - x_i), which
 * conserves number and mass exactly.
 *
 * Units: whatever the kernel uses (SI: v in m^3, n in 1/m^3, t in s);
 * the solver itself is unit-free.  Theory, solver choice and accuracy
 * measurements: docs/pbe.md.
 */
#ifndef SMOLBRIDGE_PBE_H
#define SMOLBRIDGE_PBE_H

#include <stddef.h>
#include <smolbridge/common.h>
#include <smolbridge/kernel.h>

#ifdef __cplusplus
extern "C" {
#endif

/* ------------------------------------------------------------ solver */

typedef enum {
  SB_PBE_DISCRETE = 0,  /**< sizes k v1, k = 1..nsizes */
  SB_PBE_SECTIONAL = 1  /**< fixed pivots v1 ratio^i, i = 0..nsizes-1 */
} sb_pbe_method;

typedef enum {
  SB_PBE_LS_AUTO = 0,   /**< default: GMRES_DIAG (measured 7-9x faster than
                             dense at 300 sections, and robust) */
  SB_PBE_LS_DENSE = 1,  /**< dense LU with the analytic Jacobian: robust
                             (kernels spanning many decades), O(N^3) */
  SB_PBE_LS_GMRES = 2,  /**< Jacobian-free GMRES, no preconditioner: O(N^2)
                             per step, fastest for mild kernels (constant),
                             may fail to converge for stiff ones
                             (multiplicative over 12 decades); docs/pbe.md */
  SB_PBE_LS_GMRES_DIAG = 3 /**< GMRES, left-preconditioned by the diagonal
                             of I - gamma J with a rank-one correction that
                             keeps the M1 invariant exact: robust for the
                             stiff kernels at GMRES cost; docs/pbe.md */
} sb_pbe_linsol;

/** Evaluation of the discrete gain term for the separable built-in
 *  kernels (sb_kernel_spec_fn with type constant, additive or
 *  multiplicative; other kernels always use the tabulated direct sum). */
typedef enum {
  SB_PBE_GAIN_AUTO = 0,  /**< FFT for the constant kernel from 4096 sizes
                              when atol is not below its default (1e-14
                              max n(0)), direct otherwise */
  SB_PBE_GAIN_DIRECT = 1,/**< direct convolution sum, O(N^2/2): every
                              n_k relatively accurate (tiny tails too) */
  SB_PBE_GAIN_FFT = 2    /**< zero-padded FFT convolution, O(N log N):
                              absolute error ~ 1e-15 of the largest gain
                              rate, so n_k far below the peak lose their
                              relative accuracy (keep atol >= ~1e-13 of
                              max n).  With GMRES, additive and
                              multiplicative kernels take 5-20x more
                              steps at K >= 1000 (noise); docs/pbe.md */
} sb_pbe_gain;

/** Optional source: fill s[0..nbins-1] with the number rate added to each
 *  bin at time t (same units as dn/dt); v holds the bins' volumes. */
typedef void (*sb_pbe_source_fn)(double t, const double *v, double *s,
                                 size_t nbins, const void *params);
/** Optional first-order removal rate (1/time) of particles of volume v. */
typedef double (*sb_pbe_removal_fn)(double t, double v, const void *params);

typedef struct {
  sb_pbe_method method;
  size_t nsizes;        /**< K (discrete) or N (sectional), >= 2 */
  double v1;            /**< monomer volume / smallest pivot, > 0
                             (discrete: nsizes v1 finite, else SB_EDOM) */
  double ratio;         /**< sectional pivot ratio x_{i+1}/x_i, > 1 */
  sb_kernel_fn kernel;  /**< collision kernel K(v_i, v_j) */
  const void *kparams;  /**< its parameters */
  double rtol;          /**< CVODE relative tolerance (default 1e-8) */
  double atol;          /**< absolute tolerance on n; <= 0: 1e-14 max n(0)
                             (the tail's mass: atol times the mean volume
                             at the start).  Both must be normal doubles
                             (>= DBL_MIN), or the solve fails with SB_EDOM:
                             for concentrations below ~1e-294 solve for
                             n/N0 with the kernel N0 K (the population
                             balance is invariant under n -> n/c,
                             K -> c K), as `smolbridge pbe` does */
  sb_pbe_linsol linsol; /**< linear solver of the Newton iteration */
  long max_steps;       /**< CVODE steps allowed per output interval */
  sb_pbe_source_fn source;   /**< NULL: no source */
  const void *sparams;
  sb_pbe_removal_fn removal; /**< NULL: no removal */
  const void *rparams;
  int tail;             /**< discrete only (default 1): particles larger
                             than K form one lumped class (its number and
                             mass are tracked, its volume is their mean)
                             that keeps colliding, instead of leaving.  For
                             the constant, additive and multiplicative
                             kernels the lumped class is exact (the rates
                             involve only its number and mass), so n_k,
                             k <= K, M0 and M1 are those of the infinite
                             system; for other kernels it approximates the
                             tail's sizes by their mean.  0: the tail
                             leaves (M1 drift reports the lost mass). */
  sb_pbe_gain gain;     /**< discrete separable kernels: direct or FFT */
} sb_pbe_config;

/** Statistics and conservation check of one sb_pbe_solve. */
typedef struct {
  double m1_drift;   /**< max over outputs of |M1(t) - M1(0)|/M1(0) */
  long nsteps;       /**< CVODE steps */
  long nrhs;         /**< right-hand-side evaluations (incl. difference
                          quotients of GMRES) */
  long njac;         /**< Jacobian evaluations (dense) */
  long nliniters;    /**< linear iterations (GMRES) */
  long nerrfails;    /**< error-test failures */
} sb_pbe_report;

/** Called at each output time with the volumes v, the concentrations n and
 *  moments M0, M1, M2 (sum of v^j n, including the lumped tail: its number,
 *  mass and number x mean volume^2).  Return 0 to continue, nonzero to
 *  stop the solve (sb_pbe_solve then returns SB_EINVAL). */
typedef int (*sb_pbe_output_fn)(double t, const double *v, const double *n,
                                size_t nbins, const double moments[3],
                                void *data);

typedef struct sb_pbe sb_pbe;

/** Defaults: discrete, nsizes 100, v1 1, ratio 2, constant kernel K = 1
 *  (through a static spec), rtol 1e-8, atol automatic, LS_AUTO, max_steps
 *  100000, no source, no removal, tail 1. */
void sb_pbe_config_init(sb_pbe_config *cfg);

/** Allocate a solver (tabulates the kernel on the grid).  NULL on error,
 *  with the status in sb_last_status() (SB_EINVAL, SB_EDOM, SB_ENOMEM). */
sb_pbe *sb_pbe_alloc(const sb_pbe_config *cfg);
void sb_pbe_free(sb_pbe *p);

size_t sb_pbe_nbins(const sb_pbe *p);
/** Volumes of the bins (discrete sizes or pivots). */
const double *sb_pbe_volumes(const sb_pbe *p);

/** Initial state: n[0..nbins-1] copied (finite, >= 0). */
int sb_pbe_set_initial(sb_pbe *p, const double *n);
/** Monodisperse start: N0 particles of volume v1 (bin 0). */
int sb_pbe_init_mono(sb_pbe *p, double n0);
/** Exponential start n(v) = (N0/v0) exp(-v/v0).  Sectional: each cell
 *  [x_i, x_{i+1}] is split between its pivots conserving number and mass
 *  (below x_0: mass-conserving to pivot 0; above the last: dropped).
 *  Discrete: the geometric distribution n_k = N0 (1-q) q^(k-1),
 *  q = 1 - v1/v0 (mean volume v0, needs v0 > v1).  SB_EDOM for n0, v0
 *  not finite > 0; SB_ERANGE where the state overflows (the mass n0 v0
 *  near DBL_MAX: solve for n/N0 instead), and the initial state is then
 *  cleared (sb_pbe_solve fails until one is set). */
int sb_pbe_init_exp(sb_pbe *p, double n0, double v0);

/** Integrate from t = 0 (the initial state) to each times[i] (increasing,
 *  >= 0), calling `out` (may be NULL) at each.  The state after the call is
 *  the one at the last time (sb_pbe_state).  `rep` (may be NULL) receives
 *  the statistics and the M1 drift.  Returns SB_SUCCESS, SB_EINVAL (bad
 *  times, no initial state, or `out` asked to stop), SB_ENOMEM, or
 *  SB_ESOLVER with CVODE's message in sb_last_error(). */
int sb_pbe_solve(sb_pbe *p, const double *times, size_t ntimes,
                 sb_pbe_output_fn out, void *data, sb_pbe_report *rep);

/** Current state (initial state before any solve). */
const double *sb_pbe_state(const sb_pbe *p);
/** Number and mass (volume) concentrations of the lumped tail (0 when the
 *  tail is disabled or for the sectional method). */
void sb_pbe_tail(const sb_pbe *p, double *number, double *mass);
/** Moments of the current state including the tail (see sb_pbe_output_fn). */
void sb_pbe_state_moments(const sb_pbe *p, double m[3]);

/** Evaluate the right-hand side dn/dt at (t, n) (for tests and benches).
 *  SB_EDOM if t or an n[k] is not finite, SB_ERANGE if a rate exceeds
 *  DBL_MAX (dndt is then unspecified), SB_EINVAL for NULL arguments. */
int sb_pbe_rhs(sb_pbe *p, double t, const double *n, double *dndt);

/** M0, M1, M2 = sum_k v_k^j n_k (compensated summation); +-inf where a
 *  sum exceeds DBL_MAX. */
void sb_pbe_moments(const double *v, const double *n, size_t nbins,
                    double m[3]);

/* ------------------------------------------------- analytic solutions
 * Unit-free: n in units of N0 (initial number concentration), sizes in
 * units of the monomer volume v1 (or the initial mean volume v0), and the
 * dimensionless time tau:
 *   constant K:            tau = K N0 t
 *   additive K(v+v'):      tau = K N0 v1 t    (mono)  or K N0 v0 t (exp)
 *   multiplicative K v v': tau = K N0 v1^2 t  (gelation at tau = 1)
 * The _log forms return log(n_k/N0) (lgamma/log1p/expm1 based: no overflow
 * or underflow for any k); the plain forms return exp of it (0 on
 * underflow).  Domain: integer k >= 1 (as double), tau >= 0 (< 1 for
 * multiplicative); NaN and SB_EDOM (the message names the function
 * called) otherwise.  log n is -inf (status 0) only where n = 0 (tau =
 * 0, k > 1); where log n < -DBL_MAX (k or x ~ 1e308: e.g. the constant
 * kernel at k = DBL_MAX, tau = 1) the _logn form is NaN with SB_ERANGE
 * (the message names it) and the _n form 0 without error (n underflows).
 * Accuracy: monodisperse
 * starts, ~1e-14 of |log n| + log k (the k log k - k of the factorials
 * taken out through GSL's gammastar, log1p forms: tested to k = 1e15);
 * exponential starts, a few ulp of the largest term (~ x).  Sources and
 * checks: docs/pbe.md. */

/** Constant kernel, monodisperse: n_k = (tau/2)^(k-1)/(1 + tau/2)^(k+1). */
double sb_pbe_const_mono_logn(double k, double tau);
double sb_pbe_const_mono_n(double k, double tau);

/** Additive kernel, monodisperse (Golovin):
 *  n_k = (1 - phi)(k phi)^(k-1) exp(-k phi)/k!,  phi = 1 - exp(-tau). */
double sb_pbe_add_mono_logn(double k, double tau);
double sb_pbe_add_mono_n(double k, double tau);

/** Multiplicative kernel, monodisperse, before gelation (tau < 1):
 *  n_k = k^(k-3) tau^(k-1) exp(-k tau)/(k-1)!  (NOT divided by k!). */
double sb_pbe_mult_mono_logn(double k, double tau);
double sb_pbe_mult_mono_n(double k, double tau);

/** Constant kernel, exponential start, density in units of N0/v0 at
 *  x = v/v0: n = exp(-x/(1 + tau/2))/(1 + tau/2)^2. */
double sb_pbe_const_exp_logn(double x, double tau);
double sb_pbe_const_exp_n(double x, double tau);

/** Additive kernel, exponential start (Golovin 1963; Scott 1968):
 *  n = (1 - T) exp(-(1 + T) x) I_1(2 x sqrt(T))/(x sqrt(T)),
 *  T = 1 - exp(-tau), in units of N0/v0 at x = v/v0 > 0. */
double sb_pbe_add_exp_logn(double x, double tau);
double sb_pbe_add_exp_n(double x, double tau);

typedef enum {
  SB_PBE_CONSTANT = 0, SB_PBE_ADDITIVE = 1, SB_PBE_MULTIPLICATIVE = 2
} sb_pbe_kernel_kind;

/** Exact moments M0/N0, M1/(N0 v), M2/(N0 v^2) (v = v1 or v0) at tau for a
 *  monodisperse (exp_start = 0) or exponential (exp_start = 1) start:
 *  constant: M0 = 1/(1 + tau/2), M2 = M2(0) + tau; additive: M0 = e^-tau,
 *  M2 = M2(0) e^(2 tau); multiplicative (mono only, tau < 1):
 *  M0 = 1 - tau/2, M2 = 1/(1 - tau).  M1 = 1 (pre-gel).  M2(0) = 1 (mono)
 *  or 2 (exp).  Errors: SB_EINVAL (m NULL, unknown kind, multiplicative
 *  with exp_start), SB_EDOM (tau not finite >= 0, or >= 1 multiplicative),
 *  SB_ERANGE where M2 exceeds DBL_MAX (additive, tau > ~354.9); the
 *  contents of m are then unspecified. */
int sb_pbe_analytic_moments(sb_pbe_kernel_kind kind, int exp_start,
                            double tau, double m[3]);

/* ------------------------------------------------- checks (pbe_check.c)
 * Shared by the tests, `smolbridge validate` and the benches, so that the
 * comparisons are written once. */

/** Sectional grid of `nsections` pivots spanning `decades` decades above
 *  v1: sets method SB_PBE_SECTIONAL, nsizes = nsections and
 *  ratio = 10^(decades/(nsections - 1)); other fields are left as they are.
 *  SB_EINVAL (cfg unchanged) if cfg is NULL, nsections < 2, decades is
 *  not finite > 0, or the ratio rounds to 1 or overflows. */
int sb_pbe_config_sectional(sb_pbe_config *cfg, size_t nsections,
                            double decades);
/** The same with a given pivot ratio (> 1, finite): nsizes is the
 *  smallest count reaching `decades` decades above v1,
 *  ceil(decades ln 10 / ln ratio) + 1; SB_EINVAL (cfg unchanged) as
 *  above or if that count exceeds 1e6 (sb_pbe_alloc's limit). */
int sb_pbe_config_sectional_ratio(sb_pbe_config *cfg, double ratio,
                                  double decades);

/* The functions below that delegate (to the analytic solutions or to
 * sb_pbe_solve) report its errors under their own name followed by the
 * delegate's message. */

/** Integrate like sb_pbe_solve (no output callback) and store the moments
 *  M0, M1, M2 at each times[i] in m[i] (see sb_pbe_output_fn); rows past
 *  a failure are left as they were.  Returns sb_pbe_solve's status
 *  (SB_EINVAL also for m NULL). */
int sb_pbe_solve_moments(sb_pbe *p, const double *times, size_t ntimes,
                         double m[][3], sb_pbe_report *rep);

/** Number-weighted geometric standard deviation of the diameter
 *  (d ~ v^(1/3)) of a distribution: exp of the standard deviation of
 *  ln(v_i)/3 weighted by n_i over the bins with n_i > 0 (sectional pivots
 *  stand for their sections), in two passes (mean, then squared
 *  deviations: 1 to a few ulp for a single occupied bin; weights scaled
 *  where their sums would overflow).  NaN and SB_EINVAL if no bin has
 *  n_i > 0; NaN and SB_EDOM if an n_i is NaN, or a bin with n_i > 0 has
 *  n_i infinite or v_i not finite > 0. */
double sb_pbe_sigma_g(const double *v, const double *n, size_t nbins);

/** n_k/N0 of the monodisperse analytic solution for `kind`: dispatches to
 *  sb_pbe_const_mono_n, sb_pbe_add_mono_n or sb_pbe_mult_mono_n (same
 *  domain and accuracy); NaN and SB_EINVAL for an unknown kind. */
double sb_pbe_mono_n(sb_pbe_kernel_kind kind, double k, double tau);

/** Result of sb_pbe_compare_analytic. */
typedef struct {
  double maxrel;  /**< max of |n_k/exact_k - 1| over the checked k (NaN
                       counts as +inf); 0 if none was checked */
  size_t kworst;  /**< the k where it is reached (the largest k on ties);
                       0 if none was checked */
  double nworst;  /**< n_k at kworst */
  double exact_worst; /**< the analytic n_k at kworst */
  size_t nchecked;    /**< number of k checked (exact_k >= nmin) */
} sb_pbe_analytic_cmp;

/** Maximum relative error of a discrete solution n[0..kmax-1] (sizes
 *  k = 1..kmax, in units of N0, monodisperse start, e.g. sb_pbe_state) at
 *  dimensionless time tau against sb_pbe_mono_n(kind, k, tau), over the k
 *  whose analytic n_k >= nmin (nmin = 0: all).  Returns SB_SUCCESS, or
 *  SB_EINVAL (NULL pointer, kmax = 0) / the analytic solution's status
 *  (SB_EDOM: tau outside its domain), with *res zeroed. */
int sb_pbe_compare_analytic(const double *n, size_t kmax,
                            sb_pbe_kernel_kind kind, double tau, double nmin,
                            sb_pbe_analytic_cmp *res);

/** Gelation time estimate: solve p (initial state set) to the increasing
 *  `times`, find the first output where M2 > m2_cross and extrapolate 1/M2
 *  linearly to zero through it and the next output (the solve stops
 *  there).  For the multiplicative kernel M2 = 1/(1 - tau), so 1/M2 is
 *  linear in tau and the estimate is limited by the discretisation only.
 *  *tgel is NaN on failure.  Returns SB_SUCCESS, the solve's status
 *  (SB_ESOLVER, ...), or SB_EINVAL when M2 has not crossed m2_cross
 *  before the last time.  On success the error record keeps the solve's
 *  "stopped by the output callback" entry (the stop is this function's). */
int sb_pbe_gelation_time(sb_pbe *p, const double *times, size_t ntimes,
                         double m2_cross, double *tgel);

#ifdef __cplusplus
}
#endif

#endif /* SMOLBRIDGE_PBE_H */
