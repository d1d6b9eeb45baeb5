/* langevin_shear_internal.h — the shear step's noise integrals (private
 * to lib/langevin; tests use it). */
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

#endif /* SB_LANGEVIN_SHEAR_INTERNAL_H */
