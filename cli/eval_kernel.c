/* eval_kernel.c — `smolbridge eval` entries of the kernel module and the
 * analytic population-balance solutions. */
#include <smolbridge/common.h>
#include <smolbridge/kernel.h>
#include <smolbridge/pbe.h>

#include "cli.h"

SBE_WRAP4(kernel_brownian_co)
SBE_WRAP4(kernel_brownian_fm)
SBE_WRAP6(kernel_brownian_tr)
SBE_WRAP5(kernel_kinetic)
SBE_WRAP5(kernel_kinetic_2d)
static int sbe_w_kernel_brownian_gh(const double *i, double *o)
{
  o[0] = sb_kernel_brownian_gh(i[0], i[1], i[2], i[3], i[4], i[5], i[6]);
  return 0;
}
static int sbe_w_kernel_brownian_gh_kn(const double *i, double *o)
{
  o[0] = sb_kernel_brownian_gh_kn(i[0], i[1], i[2], i[3], i[4], i[5], i[6]);
  return 0;
}
SBE_WRAP1(kernel_gh_H)
SBE_WRAP6(kernel_gravity)
SBE_WRAP3(kernel_shear)
SBE_WRAP4(kernel_saffman_turner)
SBE_WRAP4(kernel_abrahamson)
SBE_WRAP5(kernel_shear_langevin)
SBE_WRAP4(kernel_diffusion)
SBE_WRAP3(brownian_b2)
SBE_WRAP3(turb_pair_b2)
SBE_WRAP6(kernel_brownian_turb)
SBE_WRAP3(kernel_constant)
SBE_WRAP3(kernel_additive)
SBE_WRAP3(kernel_multiplicative)
SBE_WRAP2(pbe_const_mono_n)
SBE_WRAP2(pbe_const_mono_logn)
SBE_WRAP2(pbe_add_mono_n)
SBE_WRAP2(pbe_add_mono_logn)
SBE_WRAP2(pbe_mult_mono_n)
SBE_WRAP2(pbe_mult_mono_logn)
SBE_WRAP2(pbe_const_exp_n)
SBE_WRAP2(pbe_const_exp_logn)
SBE_WRAP2(pbe_add_exp_n)
SBE_WRAP2(pbe_add_exp_logn)

#define RR(...) {"r_i", "r_j", __VA_ARGS__, NULL}
#define VV {"v_i", "v_j", "K", NULL}
#define KT {"k", "tau", NULL}
#define XT {"x", "tau", NULL}
#define KIN {"d_i", "d_j", "m_i", "m_j", "T", NULL}
#define GH RR("m_i", "m_j", "tau_i", "tau_j", "T")
#define KN {"kn", NULL}
#define RTMU {"r", "T", "mu", NULL}
#define REPSNU {"r", "eps", "nu", NULL}

#define E(n, args, text) {#n, args, {NULL}, sbe_w_##n, text}

static const sbe_func funcs[] = {
    E(kernel_brownian_co, RR("T", "mu"), "Brownian continuum kernel, m^3/s"),
    E(kernel_brownian_fm, RR("T", "rho_p"),
      "Brownian free-molecular kernel, m^3/s"),
    E(kernel_brownian_tr, RR("T", "mu", "rho_p", "lambda"),
      "Brownian transition kernel (Dahneke), m^3/s"),
    E(kernel_brownian_gh, GH,
      "Langevin transition kernel (Gopalakrishnan & Hogan 2011), m^3/s"),
    E(kernel_brownian_gh_kn, GH, "its diffusive Knudsen number Kn_D"),
    E(kernel_gh_H, KN, "dimensionless kernel H(Kn_D)"),
    E(kernel_kinetic, KIN, "hard-sphere kinetic theory, m^3/s"),
    E(kernel_kinetic_2d, KIN, "hard-disc kinetic theory (2-D), m^2/s"),
    E(kernel_gravity, RR("rho_p", "rho_f", "mu", "g"),
      "differential settling kernel, m^3/s"),
    E(kernel_shear, RR("G"), "laminar shear kernel, m^3/s"),
    E(kernel_saffman_turner, RR("eps", "nu"), "Saffman-Turner kernel, m^3/s"),
    E(kernel_abrahamson, RR("u2_i", "u2_j"), "Abrahamson inertial kernel, m^3/s"),
    E(kernel_shear_langevin, RR("u2", "tau", "G"),
      "pass-through kernel of Langevin spheres in shear, m^3/s"),
    E(kernel_diffusion, RR("b2_i", "b2_j"), "pure-diffusion kernel, m^3/s"),
    E(brownian_b2, RTMU, "Brownian position variance rate, m^2/s"),
    E(turb_pair_b2, REPSNU,
      "turbulent pair variance rate at separation r, m^2/s"),
    E(kernel_brownian_turb, RR("T", "mu", "eps", "nu"),
      "Brownian + turbulent pair-diffusion kernel, m^3/s"),
    E(kernel_constant, VV, "test kernel K"),
    E(kernel_additive, VV, "test kernel K (v_i + v_j)"),
    E(kernel_multiplicative, VV, "test kernel K v_i v_j"),
    E(pbe_const_mono_n, KT, "constant kernel, mono start: n_k/N0"),
    E(pbe_const_mono_logn, KT, "constant kernel, mono start: log(n_k/N0)"),
    E(pbe_add_mono_n, KT, "additive kernel, mono start: n_k/N0"),
    E(pbe_add_mono_logn, KT, "additive kernel, mono start: log(n_k/N0)"),
    E(pbe_mult_mono_n, KT, "multiplicative kernel, mono, tau<1: n_k/N0"),
    E(pbe_mult_mono_logn, KT, "multiplicative, mono, tau<1: log(n_k/N0)"),
    E(pbe_const_exp_n, XT, "constant kernel, exp start: n v0/N0 at x=v/v0"),
    E(pbe_const_exp_logn, XT, "constant kernel, exp start: log(n v0/N0)"),
    E(pbe_add_exp_n, XT, "additive kernel, exp start: n v0/N0 at x=v/v0"),
    E(pbe_add_exp_logn, XT, "additive kernel, exp start: log(n v0/N0)"),
};

const sbe_table sbe_table_kernel = {funcs, sizeof funcs / sizeof funcs[0]};
