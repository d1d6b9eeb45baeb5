/* langevin_internal.h — scaled Langevin kernels shared by langevin.c and
 * langevin_step.c (prefix sbi_, not installed). */
#ifndef SB_LANGEVIN_INTERNAL_H
#define SB_LANGEVIN_INTERNAL_H

#include <smolbridge/langevin.h>

#include "common/numutil.h"

/* The unit-free kernels K(h) of langevin.c, h = t/tau (tau = B = 1):
 *   A    a = 1 - e^{-h}
 *   VU   a (2 - a)/2           (var_u)
 *   CXU  a^2/2                 (cov_xu)
 *   XU2  a^3/(2 (2 - a))       (cov_xu^2/var_u, s_xu^2 of the step)
 *   VX   c(h) + XU2            (var_x)
 *   VXC  c(h) = h - 2 tanh(h/2) (var_x|u)
 *   MSD  VX + CXU = h - a      (msd) */
enum { SBI_LK_A, SBI_LK_VU, SBI_LK_CXU, SBI_LK_XU2, SBI_LK_VX, SBI_LK_VXC,
       SBI_LK_MSD };

/* K(h) for h given as an sbi_xd (h = t/tau may over- or underflow a
 * double).  The double kernel (same bits) wherever h and K(h) are normal
 * doubles; the leading term of the small-h expansion where K(h) is below
 * DBL_MIN (h < 1e-100: relative error O(h)); the large-h limit where h
 * exceeds DBL_MAX (1 for A, 1/2 for VU, CXU, XU2; h for VX, VXC, MSD:
 * relative error O(1/h)). */
sbi_xd sbi_langevin_kern(int kind, sbi_xd h);

/* 1 if tau, |t| and B (or t, B zero) lie in [2^-100, 2^100]: then h = t/tau
 * is in [2^-200, 2^200] and no intermediate of the double formulas
 * (B^2 tau^k K(h) >= 2^-510, <= 2^510) leaves the normal range, so they
 * are used as they read (the fast path; the sbi_xd forms give the same
 * bits there, at 3-4 times the cost). */
int sbi_langevin_plain_ok(double tau, double B, double t);

/* c(h) = h - 2 tanh(h/2) in doubles (its small-h series), h >= 0 */
double sbi_langevin_cfun(double h);

#endif /* SB_LANGEVIN_INTERNAL_H */
