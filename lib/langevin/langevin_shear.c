/* langevin_shear.c — a Langevin particle in the linear shear
 * u_f = (G y + c_x, c_y) (in the plane of the flow; the third component is
 * a plain Ornstein-Uhlenbeck process): the coefficients of its exact step
 * (mean and noise; used by the engine's Lees-Edwards transport,
 * docs/engine_forces.md section 3) and of its exact bridge, the law of the
 * state inside a step given both ends (langevin_shear.h). */
#include <float.h>
#include <math.h>
#include <string.h>

#include <gsl/gsl_randist.h>
#include <smolbridge/langevin.h>
#include <smolbridge/langevin_shear.h>

#include "common/internal.h"
#include "langevin/langevin_shear_internal.h"

void sb_langevin_shear_mean_coefs(double x, double c[4])
{
  if (x < 1.0) {
    /* A = sum_{m>=3} (-1)^m (2-m) x^m/m!, Bv = sum_{m>=2} (-1)^m (m-1)
     * x^m/m!, C = sum_{m>=2} (-1)^m x^m/m!, D = -sum_{m>=3} (-1)^m x^m/m!
     * (terms below 1e-17 of the leading one at m = 24) */
    double A = 0.0, Bv = 0.0, C = 0.0, D = 0.0, t = 1.0;
    for (int m = 1; m <= 24; m++) {
      t *= -x / m;  /* (-x)^m / m! */
      if (m >= 2) {
        Bv += (m - 1) * t;
        C += t;
      }
      if (m >= 3) {
        A += (2 - m) * t;
        D -= t;
      }
    }
    c[0] = A;
    c[1] = Bv;
    c[2] = C;
    c[3] = D;
    return;
  }
  const double e = exp(-x), ome = -expm1(-x);
  c[0] = x * (1.0 + e) - 2.0 * ome;
  c[1] = ome - x * e;
  c[2] = x - ome;
  c[3] = 0.5 * x * x - x + ome;
}

/* ---------------------------------------------- exact shear noise */

/* The kernels of the noise in units tau = B = 1 (r = h - s the age of the
 * increment dW_y(s)): u_y and y respond with k_u = e^-r, k_y = 1 - e^-r;
 * the x velocity and position respond through G y with
 *   K_u = 1 - e^-r - r e^-r,   K_x = r - 2 + 2 e^-r + r e^-r
 * (per unit g = G tau).  Each as terms c r^a e^{-k r}, a, k in {0, 1}:
 * kt[kernel][a][k]; order k_u, k_y, K_u, K_x. */
static const double shn_kt[4][2][2] = {
    {{0, 1}, {0, 0}},
    {{1, -1}, {0, 0}},
    {{1, -1}, {0, -1}},
    {{-2, 2}, {1, 1}},
};
/* the seven integrals over [0, x]: (K_u k_u, K_u k_y, K_x k_u, K_x k_y,
 * K_u K_u, K_u K_x, K_x K_x) as pairs of kernels */
static const int shn_pair[7][2] = {{2, 0}, {2, 1}, {3, 0}, {3, 1},
                                   {2, 2}, {2, 3}, {3, 3}};

#define SHN_SERIES_X 1.5

void sbi_shear_noise_ints(double x, double f[7])
{
  if (x < SHN_SERIES_X) {
    /* the products' Taylor series integrated term by term, from the
     * generated table (Horner from the highest degree; the terms fall as
     * (2x)^n/n!, below 1e-17 of the leading one by n = 60 at x = 1.5) */
    for (int m = 0; m < 7; m++) {
      const double *c = sbi_shear_noise_tab[m];
      double acc = 0.0;
      for (int n = SBI_SHN_NT - 1; n >= 0; n--)
        acc = acc * x + c[n];
      f[m] = acc * x;
    }
    return;
  }
  /* closed form: int_0^x r^a e^{-k r} dr = x^{a+1}/(a+1) (k = 0),
   * a!/k^{a+1} (1 - e^{-kx} sum_{j<=a} (kx)^j/j!) (k > 0) */
  double J[3][3];
  for (int a = 0; a <= 2; a++) {
    J[a][0] = pow(x, a + 1) / (a + 1);
    for (int k = 1; k <= 2; k++) {
      const double y = k * x;
      double s = 0.0, term = 1.0, fa = 1.0;
      for (int j = 0; j <= a; j++) {
        if (j > 0) {
          term *= y / j;
          fa *= j;
        }
        s += term;
      }
      J[a][k] = fa / pow((double)k, a + 1) * (1.0 - exp(-y) * s);
    }
  }
  for (int m = 0; m < 7; m++) {
    const int p = shn_pair[m][0], q = shn_pair[m][1];
    double acc = 0.0;
    for (int a1 = 0; a1 < 2; a1++)
      for (int k1 = 0; k1 < 2; k1++)
        for (int a2 = 0; a2 < 2; a2++)
          for (int k2 = 0; k2 < 2; k2++)
            acc += shn_kt[p][a1][k1] * shn_kt[q][a2][k2] *
                   J[a1 + a2][k1 + k2];
    f[m] = acc;
  }
}

void sb_langevin_shear_noise_cov(double x, double g, double S[4][4])
{
  sb_langevin_coef c;
  double f[7];
  sb_langevin_coef_init(&c, 1.0, 1.0, x);
  sbi_shear_noise_ints(x, f);
  const double a = c.s_u, b = c.s_xu, cc = c.s_xc;
  memset(S, 0, 16 * sizeof(double));
  S[0][0] = a * a;
  S[1][0] = a * b;
  S[1][1] = b * b + cc * cc;
  S[2][2] = a * a + g * g * f[4];
  S[3][2] = a * b + g * g * f[5];
  S[3][3] = b * b + cc * cc + g * g * f[6];
  S[2][0] = g * f[0];
  S[2][1] = g * f[1];
  S[3][0] = g * f[2];
  S[3][1] = g * f[3];
  for (int i = 0; i < 4; i++)
    for (int j = i + 1; j < 4; j++)
      S[i][j] = S[j][i];
}

void sb_langevin_shear_noise_chol(double x, double g, double L[7])
{
  sb_langevin_coef c;
  double f[7];
  sb_langevin_coef_init(&c, 1.0, 1.0, x);
  sbi_shear_noise_ints(x, f);
  /* y rows: the OU factor (a 0; b cc) of the step; x rows: M = C L_y^-T
   * against the y normals, then the Cholesky factor of the Schur
   * complement S = Sigma_OU + R, R = g^2 S2 - M M^T the covariance of the
   * shear part given the y noise (long double: R and its determinant
   * cancel by up to 5 digits at small x) */
  const long double a = c.s_u, b = c.s_xu, cc = c.s_xc, gg = g;
  if (!(a > 0) || !(cc > 0)) {  /* x = 0: no noise */
    for (int k = 0; k < 7; k++)
      L[k] = 0.0;
    return;
  }
  const long double M00 = gg * f[0] / a, M10 = gg * f[2] / a;
  const long double M01 = (gg * f[1] - b * M00) / cc;
  const long double M11 = (gg * f[3] - b * M10) / cc;
  long double R00 = gg * gg * f[4] - M00 * M00 - M01 * M01;
  const long double R01 = gg * gg * f[5] - M00 * M10 - M01 * M11;
  long double R11 = gg * gg * f[6] - M10 * M10 - M11 * M11;
  if (R00 < 0)
    R00 = 0;
  if (R11 < 0)
    R11 = 0;
  long double detR = R00 * R11 - R01 * R01;
  if (detR < 0)
    detR = 0;
  long double q = b * b * R00 - 2 * a * b * R01 + a * a * R11;
  if (q < 0)
    q = 0;
  const long double S00 = a * a + R00, S10 = a * b + R01;
  const long double L33 = sqrtl(S00);
  L[0] = (double)M00;
  L[1] = (double)M01;
  L[2] = (double)L33;
  L[3] = (double)M10;
  L[4] = (double)M11;
  L[5] = (double)(S10 / L33);
  /* L44^2 = S11 - L43^2 = cc^2 + (q + det R)/S00, q = (b, -a) R (b, -a)^T
   * (the conditional variance of the x noise given the other three,
   * without the difference of the two large terms) */
  L[6] = (double)sqrtl(cc * cc + (q + detR) / S00);
}

/* ------------------------------------------------------------ bridge */

void sb_langevin_shear_propagator(double x, double g, double Phi[4][4],
                                  double a[4][2])
{
  double c[4];
  sb_langevin_shear_mean_coefs(x, c);
  const double e = exp(-x), ome = -expm1(-x);
  memset(Phi, 0, 16 * sizeof(double));
  /* rows u_y, y (the Ornstein-Uhlenbeck step), u_x, x: u_x relaxes to
   * G y, whose path is y(0) + u_y(0) (1 - e^-t) */
  Phi[0][0] = e;
  Phi[1][0] = ome;
  Phi[1][1] = 1.0;
  Phi[2][0] = g * c[1];
  Phi[2][1] = g * ome;
  Phi[2][2] = e;
  Phi[3][0] = g * c[0];
  Phi[3][1] = g * c[2];
  Phi[3][2] = ome;
  Phi[3][3] = 1.0;
  /* the constant drift velocities: c_x as u_x's relaxation target, c_y as
   * u_y's, which reaches u_x and x through G y (the integrals of Bv and A
   * over the step are A and D - A) */
  a[0][0] = 0.0;
  a[0][1] = ome;
  a[1][0] = 0.0;
  a[1][1] = c[2];
  a[2][0] = ome;
  a[2][1] = g * c[0];
  a[3][0] = c[2];
  a[3][1] = g * (c[3] - c[0]);
}

/* The deterministic map in physical units, written directly in tau, G
 * and s: the entries of D Phi D^-1 and D a / vu (D = diag(vu, vx, vu, vx),
 * vu = sqrt(tau), vx = tau^1.5 with B = 1) are Phi's and a's times 1, tau
 * or 1/tau, which cancel against the powers of x = s/tau in the
 * coefficients:
 *   tau (1 - e^-x), tau Bv, tau C, tau A, tau^2 A, tau^2 (D - A)
 * are formed without x itself for x >= 1 (closed forms in s and tau) and
 * from the series of Bv/x^2, C/x^2, A/x^3, (D - A)/x^4 (O(1)) times
 * powers of s and x for x < 1.  So nothing overflows or underflows unless
 * the entry does: tau from subnormal to 1e300 with s, G ordinary (the
 * scaling through sqrt(tau) and tau^1.5 underflowed below tau ~ 1e-205,
 * and x^2/2 overflowed above x ~ 1e154).  x < 1 also takes D - A from its
 * own series, without the cancellation of D and A. */
void sbi_shear_det_map(double tau, double G, double s, double ka[4][4],
                       double kc[4][2])
{
  const double x = s / tau, e = exp(-x), ome = -expm1(-x);
  double t1, tbv, tc, ta, tta, ttda; /* the products above */
  if (x < 1.0) {
    /* t_m = (-1)^m x^(m-k)/m! from m = k: Bv/x^2 = sum_{m>=2} (m-1) t_m,
     * C/x^2 = sum_{m>=2} t_m (k = 2); A/x^3 = sum_{m>=3} (2-m) t_m
     * (k = 3); (D - A)/x^4 = sum_{m>=4} (m-3) t_m (k = 4); terms below
     * 1e-17 of the leading one by m = 26 */
    double bv2 = 0.0, c2 = 0.0, a3 = 0.0, da4 = 0.0;
    double t = 0.5;
    for (int m = 2; m <= 26; m++, t *= -x / m) {
      bv2 += (m - 1) * t;
      c2 += t;
    }
    t = -1.0 / 6.0;
    for (int m = 3; m <= 27; m++, t *= -x / m)
      a3 += (2 - m) * t;
    t = 1.0 / 24.0;
    for (int m = 4; m <= 28; m++, t *= -x / m)
      da4 += (m - 3) * t;
    /* tau (1 - e^-x) = s (1 - e^-x)/x (-> s as x -> 0) */
    t1 = x > 0.0 ? s * (ome / x) : s;
    const double sx = s * x; /* tau x^2 = s x, tau^2 x^3 = s (s x) */
    tbv = sx * bv2;
    tc = sx * c2;
    ta = sx * x * a3;
    tta = s * sx * a3;
    ttda = sx * sx * da4;
  } else {
    t1 = tau * ome;
    tbv = t1 - s * e;               /* tau (1 - e^-x - x e^-x) */
    tc = s - t1;                    /* tau (x - (1 - e^-x)) */
    ta = s * (1.0 + e) - 2.0 * t1;  /* tau (x (1 + e^-x) - 2 (1 - e^-x)) */
    tta = tau * ta;
    /* tau^2 (x^2/2 - 2x - x e^-x + 3 (1 - e^-x)) */
    ttda = s * (0.5 * s - 2.0 * tau - tau * e) + 3.0 * tau * t1;
  }
  memset(ka, 0, 16 * sizeof(double));
  ka[0][0] = e;
  ka[1][0] = t1;
  ka[1][1] = 1.0;
  ka[2][0] = G * tbv;
  ka[2][1] = G * ome;
  ka[2][2] = e;
  ka[3][0] = G * tta;
  ka[3][1] = G * tc;
  ka[3][2] = t1;
  ka[3][3] = 1.0;
  kc[0][0] = 0.0;
  kc[0][1] = ome;
  kc[1][0] = 0.0;
  kc[1][1] = tc;
  kc[2][0] = ome;
  kc[2][1] = G * ta;
  kc[3][0] = tc;
  kc[3][1] = G * ttda;
}

void sbi_shear_det_state(double tau, double G, double cx, double cy,
                         double s, const double sa[4], double out[4])
{
  double ka[4][4], kc[4][2];
  sbi_shear_det_map(tau, G, s, ka, kc);
  /* a zero drift or state component contributes 0 even where its
   * coefficient overflows (tau^2 (D - A) ~ s^2/2 at s ~ 1e300) */
  const double c[2] = {cx, cy};
  for (int i = 0; i < 4; i++) {
    double t = 0.0;
    for (int j = 0; j < 2; j++)
      if (c[j] != 0.0)
        t += kc[i][j] * c[j];
    for (int j = 0; j < 4; j++)
      if (sa[j] != 0.0)
        t += ka[i][j] * sa[j];
    out[i] = t;
  }
}

int sb_langevin_shear_mean(double tau, double G, double cx, double cy,
                           double s, const double s0[4], double out[4])
{
  if (!s0 || !out)
    return sbi_error(SB_EINVAL, __func__, "NULL state");
  int ok = tau > 0.0 && isfinite(tau) && isfinite(G) && isfinite(cx) &&
           isfinite(cy) && s >= 0.0 && isfinite(s);
  for (int k = 0; k < 4; k++)
    ok = ok && isfinite(s0[k]);
  if (!ok) {
    for (int k = 0; k < 4; k++)
      out[k] = NAN;
    return sbi_error(SB_EDOM, __func__, "tau = %g, G = %g, cx = %g, "
                     "cy = %g, s = %g: tau > 0, s >= 0, all finite", tau, G,
                     cx, cy, s);
  }
  sbi_shear_det_state(tau, G, cx, cy, s, s0, out);
  for (int k = 0; k < 4; k++)
    if (!isfinite(out[k])) {
      for (int j = 0; j < 4; j++)
        out[j] = NAN;
      return sbi_error(SB_ERANGE, __func__, "the mean overflows (tau = %g, "
                       "G = %g, s = %g)", tau, G, s);
    }
  return SB_SUCCESS;
}

/* Cholesky factor of a 4 x 4 matrix, written out for this fixed size
 * rather than with GSL's, whose failure on a matrix that is not positive
 * definite goes through the process-wide GSL error handler. */
int sbi_shear_chol4(const double M[4][4], double L[4][4])
{
  memset(L, 0, 16 * sizeof(double));
  for (int j = 0; j < 4; j++)
    for (int i = j; i < 4; i++) {
      double t = 0.5 * (M[i][j] + M[j][i]);
      for (int k = 0; k < j; k++)
        t -= L[i][k] * L[j][k];
      if (i == j) {
        if (!(t > 0.0) || !isfinite(t))
          return SB_EDOM;
        L[j][j] = sqrt(t);
      } else
        L[i][j] = t / L[j][j];
    }
  return SB_SUCCESS;
}

/* Inverse of the symmetric positive definite 4 x 4 matrix M into Mi, by
 * the Cholesky factor of D M D, D = diag(M_ii^-1/2) (unit diagonal: the
 * factorisation sees the correlations, not the scales).  SB_EDOM when a
 * pivot is not positive. */
static int spd_inverse(const double M[4][4], double Mi[4][4])
{
  double d[4], W[4][4], L[4][4], V[4][4] = {{0}};
  for (int i = 0; i < 4; i++) {
    if (!(M[i][i] > 0.0) || !isfinite(M[i][i]))
      return SB_EDOM;
    d[i] = 1.0 / sqrt(M[i][i]);
  }
  for (int i = 0; i < 4; i++)
    for (int j = 0; j < 4; j++)
      W[i][j] = d[i] * d[j] * M[i][j];
  if (sbi_shear_chol4(W, L))
    return SB_EDOM;
  /* V = L^-1 (lower), then (D M D)^-1 = V^T V */
  for (int j = 0; j < 4; j++) {
    V[j][j] = 1.0 / L[j][j];
    for (int i = j + 1; i < 4; i++) {
      double t = 0.0;
      for (int k = j; k < i; k++)
        t -= L[i][k] * V[k][j];
      V[i][j] = t / L[i][i];
    }
  }
  for (int i = 0; i < 4; i++)
    for (int j = 0; j < 4; j++) {
      double t = 0.0;
      for (int k = i > j ? i : j; k < 4; k++)
        t += V[k][i] * V[k][j];
      Mi[i][j] = d[i] * d[j] * t;
    }
  return SB_SUCCESS;
}

/* C = A B and C = A^T B for a 4 x 4 A and a 4 x n B (flat, row-major:
 * plain pointers, which GCC's access checks follow at every -O level) */
static void mul(const double *A, const double *B, int n, double *C)
{
  for (int i = 0; i < 4; i++)
    for (int j = 0; j < n; j++) {
      double t = 0.0;
      for (int k = 0; k < 4; k++)
        t += A[4 * i + k] * B[k * n + j];
      C[i * n + j] = t;
    }
}

static void mul_t(const double *A, const double *B, int n, double *C)
{
  for (int i = 0; i < 4; i++)
    for (int j = 0; j < n; j++) {
      double t = 0.0;
      for (int k = 0; k < 4; k++)
        t += A[4 * k + i] * B[k * n + j];
      C[i * n + j] = t;
    }
}

static void bridge_nan(sb_langevin_shear_bridge *b)
{
  for (int i = 0; i < 4; i++) {
    for (int j = 0; j < 4; j++)
      b->ka[i][j] = b->kb[i][j] = b->cov[i][j] = NAN;
    b->kc[i][0] = b->kc[i][1] = NAN;
  }
}

int sb_langevin_shear_bridge_coefs(double x, double g, double s,
                                   sb_langevin_shear_bridge *b)
{
  if (!b)
    return sbi_error(SB_EINVAL, __func__, "b is NULL");
  bridge_nan(b);
  if (!(x >= 1e-9 && x <= 1e9) || !isfinite(g) || !(fabs(g) * x <= 100.0) ||
      !(s >= 1e-3 * x && s <= (1.0 - 1e-3) * x))
    return sbi_error(SB_EDOM, __func__,
                     "x = %g (in [1e-9, 1e9]), g = %g (|g| x <= 100), s = %g "
                     "(s/x in [1e-3, 0.999])", x, g, s);
  const double r = x - s;
  double Ss[4][4], Sr[4][4], Ps[4][4], Pr[4][4], as[4][2], ar[4][2];
  sb_langevin_shear_noise_cov(s, g, Ss);
  sb_langevin_shear_noise_cov(r, g, Sr);
  sb_langevin_shear_propagator(s, g, Ps, as);
  sb_langevin_shear_propagator(r, g, Pr, ar);
  double Js[4][4], Jr[4][4], Q[4][4], C[4][4];
  if (spd_inverse(Ss, Js) || spd_inverse(Sr, Jr))
    return sbi_error(SB_EDOM, __func__, "the step's noise covariance is not "
                     "positive definite (x = %g, g = %g, s = %g)", x, g, s);
  /* the end's information Phi(r)^T Sigma(r)^-1 Phi(r) = Pr^T H,
   * H = Jr Pr; the precision at s is Js + Pr^T H */
  double H[4][4], T[4][4];
  mul(&Jr[0][0], &Pr[0][0], 4, &H[0][0]);
  mul_t(&Pr[0][0], &H[0][0], 4, &T[0][0]);
  for (int i = 0; i < 4; i++)
    for (int j = 0; j < 4; j++)
      Q[i][j] = Js[i][j] + 0.5 * (T[i][j] + T[j][i]);
  if (spd_inverse(Q, C))
    return sbi_error(SB_EDOM, __func__, "the bridge's precision is not "
                     "positive definite (x = %g, g = %g, s = %g)", x, g, s);
  if (s <= 0.5 * x) {
    /* the gain form (the information form's C Js Ps cancels as s -> 0):
     * K = Sigma(s) Phi(r)^T Sigma(x)^-1, ka = Phi(s) - K Phi(x), kb = K,
     * kc = a(s) - K a(x) */
    double Sx[4][4], Jx[4][4], Px[4][4], ax[4][2], SsPt[4][4];
    sb_langevin_shear_noise_cov(x, g, Sx);
    sb_langevin_shear_propagator(x, g, Px, ax);
    if (spd_inverse(Sx, Jx))
      return sbi_error(SB_EDOM, __func__, "the step's noise covariance is not "
                       "positive definite (x = %g, g = %g)", x, g);
    for (int i = 0; i < 4; i++)
      for (int j = 0; j < 4; j++) {
        double t = 0.0;
        for (int k = 0; k < 4; k++)
          t += Ss[i][k] * Pr[j][k];
        SsPt[i][j] = t;
      }
    mul(&SsPt[0][0], &Jx[0][0], 4, &b->kb[0][0]);
    double KPx[4][4], Kax[4][2];
    mul(&b->kb[0][0], &Px[0][0], 4, &KPx[0][0]);
    mul(&b->kb[0][0], &ax[0][0], 2, &Kax[0][0]);
    for (int i = 0; i < 4; i++) {
      for (int j = 0; j < 4; j++)
        b->ka[i][j] = Ps[i][j] - KPx[i][j];
      for (int j = 0; j < 2; j++)
        b->kc[i][j] = as[i][j] - Kax[i][j];
    }
  } else {
    /* the information form (the gain form's Phi(s) - K Phi(x) cancels
     * as s -> x): ka = C Js Ps, kb = C Pr^T Jr,
     * kc = C (Js as - Pr^T Jr ar) */
    double PtJ[4][4], JsPs[4][4], Jsas[4][2], Jrar[4][2], PtJar[4][2];
    double v[4][2];
    mul(&Js[0][0], &Ps[0][0], 4, &JsPs[0][0]);
    mul(&C[0][0], &JsPs[0][0], 4, &b->ka[0][0]);
    mul_t(&Pr[0][0], &Jr[0][0], 4, &PtJ[0][0]);
    mul(&C[0][0], &PtJ[0][0], 4, &b->kb[0][0]);
    mul(&Js[0][0], &as[0][0], 2, &Jsas[0][0]);
    mul(&Jr[0][0], &ar[0][0], 2, &Jrar[0][0]);
    mul_t(&Pr[0][0], &Jrar[0][0], 2, &PtJar[0][0]);
    for (int i = 0; i < 4; i++)
      for (int j = 0; j < 2; j++)
        v[i][j] = Jsas[i][j] - PtJar[i][j];
    mul(&C[0][0], &v[0][0], 2, &b->kc[0][0]);
  }
  for (int i = 0; i < 4; i++)
    for (int j = 0; j < 4; j++)
      b->cov[i][j] = 0.5 * (C[i][j] + C[j][i]);
  return SB_SUCCESS;
}

/* f[0] f[1] ... f[n-1] with the binary exponents summed apart (frexp)
 * and applied once at the end: no intermediate overflow or underflow, inf
 * or 0 only where the product itself overflows or underflows. */
static double scaled_prod(const double *f, int n)
{
  double m = 1.0;
  int e = 0;
  for (int i = 0; i < n; i++) {
    int k;
    m *= frexp(f[i], &k);
    e += k;
    m = frexp(m, &k); /* keep m in [1/2, 1) */
    e += k;
  }
  return ldexp(m, e);
}

int sb_langevin_shear_bridge_moments(double tau, double B, double G,
                                     double cx, double cy, double h,
                                     double s, const double s0[4],
                                     const double s1[4], double mean[4],
                                     double cov[4][4])
{
  if (mean)
    for (int i = 0; i < 4; i++)
      mean[i] = NAN;
  if (cov)
    for (int i = 0; i < 16; i++)
      (&cov[0][0])[i] = NAN;
  if (!s0 || !s1 || !mean || !cov)
    return sbi_error(SB_EINVAL, __func__, "NULL argument");
  int fin = isfinite(cx) && isfinite(cy) && isfinite(G);
  for (int i = 0; i < 4; i++)
    fin &= isfinite(s0[i]) && isfinite(s1[i]);
  if (!(tau > 0.0) || !isfinite(tau) || !(B > 0.0) || !isfinite(B) ||
      !(h > 0.0) || !isfinite(h) || !fin)
    return sbi_error(SB_EDOM, __func__, "tau = %g, B = %g (> 0), h = %g "
                     "(> 0), G, cx, cy and the states finite", tau, B, h);
  sb_langevin_shear_bridge b;
  if (sb_langevin_shear_bridge_coefs(h / tau, G * tau, s / tau, &b))
    return sbi_error(SB_EDOM, __func__, "%s", sb_last_error());
  /* units: velocities B sqrt(tau), positions B tau^(3/2).  The mean does
   * not depend on B: its coefficients are taken to physical units by the
   * ratios of the scales (1, tau or 1/tau); the covariance is B^2 tau
   * r_i r_j cov_ij (r = 1 for a velocity, tau for a position), a product
   * formed with the exponents set aside, so neither B sqrt(tau) nor its
   * square over- or underflows on the way. */
  const double r[4] = {1.0, tau, 1.0, tau};
  for (int i = 0; i < 4; i++) {
    double m = 0.0;
    for (int k = 0; k < 2; k++)
      m += b.kc[i][k] * r[i] * (k == 0 ? cx : cy);
    for (int j = 0; j < 4; j++) {
      /* sc_i/sc_j: 1, tau (position from velocity), 1/tau (the reverse) */
      const double q = i % 2 == j % 2 ? 1.0 : (j % 2 ? 1.0 / tau : tau);
      const double t = b.ka[i][j] * s0[j] + b.kb[i][j] * s1[j];
      if (t != 0.0)
        m += t * q;
    }
    mean[i] = m;
    for (int j = 0; j < 4; j++) {
      const double f[6] = {B, B, tau, r[i], r[j], b.cov[i][j]};
      cov[i][j] = scaled_prod(f, 6);
    }
  }
  for (int i = 0; i < 4; i++)
    for (int j = 0; j < 4; j++)
      if (!isfinite(mean[i]) || !isfinite(cov[i][j])) {
        for (int k = 0; k < 4; k++) {
          mean[k] = NAN;
          for (int l = 0; l < 4; l++)
            cov[k][l] = NAN;
        }
        return sbi_error(SB_ERANGE, __func__, "the moments overflow (tau = "
                         "%g, B = %g, h = %g)", tau, B, h);
      }
  return SB_SUCCESS;
}

/* The draw of sb_langevin_shear_bridge_sample for checked arguments;
 * errors are recorded for who. */
static int bridge_draw(double tau, double B, double G, double cx, double cy,
                       double h, double s, const double s0[4],
                       const double s1[4], const gsl_rng *r, double out[4],
                       const char *who);

/* The same draw formed in SI units, for B sqrt(tau) or B tau^1.5 below
 * DBL_MIN (where bridge_draw's states in units of those scales
 * overflow): the mean as in sb_langevin_shear_bridge_moments (no scales),
 * the noise the unit-scale Cholesky draw times B sqrt(tau) r_i with the
 * exponents set aside (scaled_prod); the same normals in the same order.
 * Returns 1, out untouched and no number drawn, if the interval would
 * get below 1e-9 tau (the Ornstein-Uhlenbeck branch of bridge_draw, left
 * to the caller). */
static int bridge_draw_si(double tau, double B, double G, double cx,
                          double cy, double h, double s, const double s0[4],
                          const double s1[4], const gsl_rng *r,
                          double out[4], const char *who)
{
  const double g = G * tau, rs[4] = {1.0, tau, 1.0, tau};
  /* the halving below, without draws: does it reach h < 1e-9 tau? */
  for (double hh = h, ss = s; ss > 0.0 && ss < hh;) {
    if (hh < 1e-9 * tau)
      return 1;
    if (ss >= 1e-3 * hh && ss <= 0.999 * hh)
      break;
    hh *= 0.5;
    if (ss >= hh)
      ss -= hh;
  }
  double sa[4], sb[4];
  memcpy(sa, s0, sizeof sa);
  memcpy(sb, s1, sizeof sb);
  for (;;) {
    if (s <= 0.0 || s >= h) {
      memcpy(out, s <= 0.0 ? sa : sb, 4 * sizeof *out);
      return SB_SUCCESS;
    }
    if (h < 1e-9 * tau)
      return 1;
    const int inside = s >= 1e-3 * h && s <= 0.999 * h;
    const double t = inside ? s : 0.5 * h;
    sb_langevin_shear_bridge b;
    double m[4], L[4][4], z[4];
    if (sb_langevin_shear_bridge_coefs(h / tau, g, t / tau, &b) ||
        sbi_shear_chol4(b.cov, L))
      return sbi_error(SB_EDOM, who, "no shear bridge at h/tau = %g, "
                       "s/h = %g, G tau = %g", h / tau, t / h, g);
    for (int j = 0; j < 4; j++)
      z[j] = gsl_ran_gaussian_ziggurat(r, 1.0);
    for (int i = 0; i < 4; i++) {
      double mi = 0.0, ni = 0.0;
      for (int k = 0; k < 2; k++)
        mi += b.kc[i][k] * rs[i] * (k == 0 ? cx : cy);
      for (int j = 0; j < 4; j++) {
        const double q = i % 2 == j % 2 ? 1.0 : (j % 2 ? 1.0 / tau : tau);
        const double tt = b.ka[i][j] * sa[j] + b.kb[i][j] * sb[j];
        if (tt != 0.0)
          mi += tt * q;
      }
      for (int j = 0; j <= i; j++)
        ni += L[i][j] * z[j];
      const double f[4] = {B, sqrt(tau), rs[i], ni};
      m[i] = mi + scaled_prod(f, 4);
    }
    if (inside) {
      memcpy(out, m, sizeof m);
      return SB_SUCCESS;
    }
    if (s < t)
      memcpy(sb, m, sizeof m);
    else {
      memcpy(sa, m, sizeof m);
      s -= t;
    }
    h = t;
  }
}

int sb_langevin_shear_bridge_sample(double tau, double B, double G,
                                    double cx, double cy, double h,
                                    double s, const double s0[4],
                                    const double s1[4], const gsl_rng *r,
                                    double out[4])
{
  if (out)
    for (int i = 0; i < 4; i++)
      out[i] = NAN;
  if (!s0 || !s1 || !out || !r)
    return sbi_error(SB_EINVAL, __func__, "NULL argument");
  int fin = isfinite(cx) && isfinite(cy) && isfinite(G) && isfinite(s);
  for (int i = 0; i < 4; i++)
    fin &= isfinite(s0[i]) && isfinite(s1[i]);
  if (!(tau > 0.0) || !isfinite(tau) || !(B > 0.0) || !isfinite(B) ||
      !(h > 0.0) || !isfinite(h) || !fin || !(s >= 0.0 && s <= h) ||
      !(fabs(G) * h <= 100.0))
    return sbi_error(SB_EDOM, __func__, "tau = %g, B = %g, h = %g (> 0), "
                     "s = %g in [0, h], |G| h = %g <= 100, all finite", tau,
                     B, h, s, fabs(G) * h);
  const double vu = B * sqrt(tau), vx = vu * tau;
  int st;
  if (vu >= DBL_MIN && vx >= DBL_MIN) {
    st = bridge_draw(tau, B, G, cx, cy, h, s, s0, s1, r, out, __func__);
  } else if ((st = bridge_draw_si(tau, B, G, cx, cy, h, s, s0, s1, r, out,
                                   __func__)) == 1) {
    /* The scales B sqrt(tau), B tau^1.5 are subnormal or 0 (B = 1e-320):
     * the states divided by them overflowed (NaN); within 1e-9 tau of an
     * end the SI-unit draw does not apply.  The law is linear: states,
     * drifts and B scaled by 2^k give the draw scaled by 2^k (the same
     * normals), so draw with B sqrt(tau) tau^(0 or 1) near 1 (k no larger
     * than keeps the scaled states below 2^1000) and scale back exactly;
     * states more than ~1e300 standard deviations apart stay out of
     * reach (SB_ERANGE below). */
    const double lt = log2(tau), lmin = lt < 0.0 ? 1.5 * lt : 0.5 * lt;
    double big = fmax(fabs(cx), fabs(cy));
    for (int i = 0; i < 4; i++)
      big = fmax(big, fmax(fabs(s0[i]), fabs(s1[i])));
    int k = -(ilogb(B) + (int)floor(lmin));
    if (big > 0.0 && k > 1000 - ilogb(big))
      k = 1000 - ilogb(big);
    double t0[4], t1[4];
    for (int i = 0; i < 4; i++) {
      t0[i] = ldexp(s0[i], k);
      t1[i] = ldexp(s1[i], k);
    }
    st = bridge_draw(tau, ldexp(B, k), G, ldexp(cx, k), ldexp(cy, k), h, s,
                     t0, t1, r, out, __func__);
    for (int i = 0; i < 4; i++)
      out[i] = ldexp(out[i], -k);
  }
  if (st == SB_SUCCESS)
    for (int i = 0; i < 4; i++)
      if (!isfinite(out[i])) {
        for (int j = 0; j < 4; j++)
          out[j] = NAN;
        return sbi_error(SB_ERANGE, __func__, "the draw is not finite "
                         "(tau = %g, B = %g, h = %g: the states are beyond "
                         "DBL_MAX standard deviations)", tau, B, h);
      }
  return st;
}

static int bridge_draw(double tau, double B, double G, double cx, double cy,
                       double h, double s, const double s0[4],
                       const double s1[4], const gsl_rng *r, double out[4],
                       const char *who)
{
  const double vu = B * sqrt(tau), vx = vu * tau, g = G * tau;
  const double D[4] = {vu, vx, vu, vx}, c[2] = {cx / vu, cy / vu};
  double sa[4], sb[4];
  for (int i = 0; i < 4; i++) {
    sa[i] = s0[i] / D[i];
    sb[i] = s1[i] / D[i];
  }
  for (;;) {
    if (s <= 0.0 || s >= h) {  /* an end */
      for (int i = 0; i < 4; i++)
        out[i] = D[i] * (s <= 0.0 ? sa[i] : sb[i]);
      return SB_SUCCESS;
    }
    if (h < 1e-9 * tau) {
      /* below the coefficients' domain the shear changes the law by
       * O(G h) < 1e-9 tau G: each in-plane pair (u, position) from its
       * Ornstein-Uhlenbeck bridge (velocities in units of vu) */
      const sb_langevin p = {1.0, 1.0, 0.0};
      for (int k = 0; k < 2; k++) {
        double xs, us;
        int st = sb_langevin_bridge_sample(&p, h / tau, s / tau,
                                           sa[2 * k + 1], sa[2 * k],
                                           sb[2 * k + 1], sb[2 * k], r, &xs,
                                           &us);
        if (st)
          return sbi_error(st, who, "%s", sb_last_error());
        out[2 * k] = D[2 * k] * us;
        out[2 * k + 1] = D[2 * k + 1] * xs;
      }
      return SB_SUCCESS;
    }
    /* inside the coefficients' domain s/h in [1e-3, 0.999] draw at s;
     * nearer an end halve the interval by an exact midpoint draw and
     * keep the half that holds s (the bridge of a Markov process) */
    const int inside = s >= 1e-3 * h && s <= 0.999 * h;
    const double t = inside ? s : 0.5 * h;
    sb_langevin_shear_bridge b;
    double m[4], L[4][4];
    if (sb_langevin_shear_bridge_coefs(h / tau, g, t / tau, &b) ||
        sbi_shear_chol4(b.cov, L))
      return sbi_error(SB_EDOM, who, "no shear bridge at h/tau = %g, "
                       "s/h = %g, G tau = %g", h / tau, t / h, g);
    for (int i = 0; i < 4; i++) {
      m[i] = b.kc[i][0] * c[0] + b.kc[i][1] * c[1];
      for (int j = 0; j < 4; j++)
        m[i] += b.ka[i][j] * sa[j] + b.kb[i][j] * sb[j];
    }
    for (int j = 0; j < 4; j++) {
      const double z = gsl_ran_gaussian_ziggurat(r, 1.0);
      for (int i = j; i < 4; i++)
        m[i] += L[i][j] * z;
    }
    if (inside) {
      for (int i = 0; i < 4; i++)
        out[i] = D[i] * m[i];
      return SB_SUCCESS;
    }
    if (s < t)
      memcpy(sb, m, sizeof m);
    else {
      memcpy(sa, m, sizeof m);
      s -= t;
    }
    h = t;
  }
}
