/* langevin_shear_internal.h — the shear step's noise integrals and the
 * deterministic shear map (private to lib/; tests use it). */
#ifndef SB_LANGEVIN_SHEAR_INTERNAL_H
#define SB_LANGEVIN_SHEAR_INTERNAL_H

/* Units tau = B = 1, x = h/tau: the seven integrals over r in [0, x] of
 * (K_u k_u, K_u k_y, K_x k_u, K_x k_y, K_u^2, K_u K_x, K_x^2), the
 * responses to dW_y of r ago: k_u = e^-r, k_y = 1 - e^-r (u_y and y),
 * K_u = 1 - e^-r (1 + r), K_x = r - 2 + e^-r (2 + r) (u_x and x, per unit
 * g = G tau); series below x = 1.5, closed forms above. */
void sbi_shear_noise_ints(double x, double f[7]);

/* The series' coefficients: f_m(x) = x sum_n sbi_shear_noise_tab[m][n]
 * x^n for x < 1.5 (langevin_shear_tab.c, generated in exact rational
 * arithmetic by gen_langevin_shear_tab.py). */
#define SBI_SHN_NT 64
extern const double sbi_shear_noise_tab[7][SBI_SHN_NT];

/* Lower Cholesky factor L of the symmetric positive definite 4 x 4 M
 * (entries above the diagonal zero); SB_EDOM when a pivot is not
 * positive. */
int sbi_shear_chol4(const double M[4][4], double L[4][4]);

/* A Stokes particle without noise (B = 0) in the shear, physical units:
 * its in-plane state S = (u_y, y, u_x, x) after a time s >= 0 from S(0)
 * is S(s) = ka S(0) + kc (c_x, c_y) (the mean transition of
 * sb_langevin_shear_propagator, exact for such a particle; the fluid
 * velocity is (G y + c_x, c_y)). */
void sbi_shear_det_map(double tau, double G, double s, double ka[4][4],
                       double kc[4][2]);
/* The state itself: out = S(s) from sa = S(0). */
void sbi_shear_det_state(double tau, double G, double cx, double cy,
                         double s, const double sa[4], double out[4]);

#endif /* SB_LANGEVIN_SHEAR_INTERNAL_H */
