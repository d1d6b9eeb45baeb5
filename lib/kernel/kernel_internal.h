/* kernel_internal.h — helpers shared by kernel.c and kernel_pair.c
 * (prefix sbi_, not exported, not installed). */
#ifndef SB_KERNEL_INTERNAL_H
#define SB_KERNEL_INTERNAL_H

#include "common/numutil.h"

/* Brownian per-particle variance rate kT/(3 pi mu r) (sb_brownian_b2) and
 * turbulent pair variance rate sqrt(2/(15 pi)) sqrt(eps/nu) r^2
 * (sb_turb_pair_b2), with an extended exponent: the same bits as the
 * plain formulas wherever they stay in the normal range.  Arguments
 * finite, r, T, mu, nu > 0, eps >= 0 (not checked). */
sbi_xd sbi_kernel_b2_brownian(double r, double T, double mu);
sbi_xd sbi_kernel_b2_turb(sbi_xd r, double eps, double nu);

#endif /* SB_KERNEL_INTERNAL_H */
