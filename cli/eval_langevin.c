/* eval_langevin.c — `smolbridge eval` entries of the langevin module.
 * Arguments in C order; the sb_langevin struct is spelled out as
 * tau, B, us; a generator argument becomes `seed` (MT19937). */
#include <gsl/gsl_rng.h>
#include <smolbridge/common.h>
#include <smolbridge/langevin.h>
#include <smolbridge/langevin_shear.h>

#include "cli.h"

SBE_WRAP3(langevin_var_x)
SBE_WRAP3(langevin_var_u)
SBE_WRAP3(langevin_cov_xu)
SBE_WRAP3(langevin_var_x_cond)
SBE_WRAP2(langevin_var_stat)
SBE_WRAP3(langevin_msd)
SBE_WRAP3(langevin_msd_ballistic)
SBE_WRAP3(langevin_msd_diffusive)
SBE_WRAP3(langevin_vacf)
SBE_WRAP4(stokes_tau)
SBE_WRAP2(sphere_mass)
SBE_WRAP3(brownian_B)
SBE_WRAP4(einstein_D)
SBE_WRAP2(knudsen)
SBE_WRAP1(cunningham)
SBE_WRAP4(cunningham_gen)
SBE_WRAP2(kolmogorov_time)
SBE_WRAP2(kolmogorov_length)
SBE_WRAP2(stokes_number)
SBE_WRAP3(particle_reynolds)
SBE_WRAP1(collision_speed)
SBE_WRAP3(wunsch_dt)
SBE_WRAP4(wunsch_dt_brownian)

static void mom_out(const sb_langevin_mom *m, double *o)
{
  o[0] = m->mean_x;
  o[1] = m->mean_u;
  o[2] = m->var_x;
  o[3] = m->var_u;
  o[4] = m->cov_xu;
}

static int sbe_w_langevin_moments(const double *i, double *o)
{
  sb_langevin p = {i[0], i[1], i[2]};
  sb_langevin_mom m;
  int st = sb_langevin_moments(&p, i[3], i[4], i[5], &m);
  mom_out(&m, o);
  return st;
}

static int sbe_w_langevin_bridge_moments(const double *i, double *o)
{
  sb_langevin p = {i[0], i[1], i[2]};
  sb_langevin_mom m;
  int st = sb_langevin_bridge_moments(&p, i[3], i[4], i[5], i[6], i[7], i[8],
                                      &m);
  mom_out(&m, o);
  return st;
}

static int sbe_w_langevin_coef_init(const double *i, double *o)
{
  sb_langevin_coef c;
  int st = sb_langevin_coef_init(&c, i[0], i[1], i[2]);
  o[0] = c.decay;
  o[1] = c.gain;
  o[2] = c.s_u;
  o[3] = c.s_xu;
  o[4] = c.s_xc;
  return st;
}

static gsl_rng *seeded(double seed)
{
  gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
  if (r)
    gsl_rng_set(r, (unsigned long)seed);
  return r;
}

/* tau B us dt seed x u -> x u */
static int sbe_w_langevin_step(const double *i, double *o)
{
  gsl_rng *r = seeded(i[4]);
  if (!r)
    return SB_ENOMEM;
  sb_langevin p = {i[0], i[1], i[2]};
  o[0] = i[5];
  o[1] = i[6];
  int st = sb_langevin_step(&p, i[3], r, &o[0], &o[1]);
  gsl_rng_free(r);
  return st;
}

/* tau B us dt s x0 u0 x1 u1 seed -> xs us */
static int sbe_w_langevin_bridge_sample(const double *i, double *o)
{
  gsl_rng *r = seeded(i[9]);
  if (!r)
    return SB_ENOMEM;
  sb_langevin p = {i[0], i[1], i[2]};
  int st = sb_langevin_bridge_sample(&p, i[3], i[4], i[5], i[6], i[7], i[8],
                                     r, &o[0], &o[1]);
  gsl_rng_free(r);
  return st;
}

/* tau B G cx cy h s (uy0 y0 ux0 x0) (uy1 y1 ux1 x1) -> the mean of
 * (u_y, y, u_x, x) and the covariance's lower triangle by rows */
static int sbe_w_langevin_shear_bridge_moments(const double *i, double *o)
{
  double m[4], c[4][4];
  int st = sb_langevin_shear_bridge_moments(i[0], i[1], i[2], i[3], i[4],
                                            i[5], i[6], &i[7], &i[11], m, c);
  for (int k = 0; k < 4; k++)
    o[k] = m[k];
  for (int a = 0, q = 4; a < 4; a++)
    for (int b = 0; b <= a; b++)
      o[q++] = c[a][b];
  return st;
}

/* the same arguments and seed -> one draw */
static int sbe_w_langevin_shear_bridge_sample(const double *i, double *o)
{
  gsl_rng *r = seeded(i[15]);
  if (!r)
    return SB_ENOMEM;
  int st = sb_langevin_shear_bridge_sample(i[0], i[1], i[2], i[3], i[4],
                                           i[5], i[6], &i[7], &i[11], r, o);
  gsl_rng_free(r);
  return st;
}

/* tau G cx cy s (uy0 y0 ux0 x0) -> the mean of (u_y, y, u_x, x) */
static int sbe_w_langevin_shear_mean(const double *i, double *o)
{
  return sb_langevin_shear_mean(i[0], i[1], i[2], i[3], i[4], &i[5], o);
}

#define TBT {"tau", "B", "t", NULL}
#define MOM {"mean_x", "mean_u", "var_x", "var_u", "cov_xu", NULL}
#define A_MOM {"tau", "B", "us", "t", "x0", "u0", NULL}
#define A_TB {"tau", "B", NULL}
#define A_COEF {"tau", "B", "dt", NULL}
#define O_COEF {"decay", "gain", "s_u", "s_xu", "s_xc", NULL}
#define A_STEP {"tau", "B", "us", "dt", "seed", "x", "u", NULL}
#define O_STEP {"x", "u", NULL}
#define A_BRM {"tau", "B", "us", "dt", "s", "x0", "u0", "x1", "u1", NULL}
#define A_BRS {"tau", "B", "us", "dt", "s", "x0", "u0", "x1", "u1", "seed", \
               NULL}
#define O_BRS {"xs", "us", NULL}
#define A_SHB {"tau", "B", "G", "cx", "cy", "h", "s", "uy0", "y0", "ux0", \
               "x0", "uy1", "y1", "ux1", "x1", NULL}
#define A_SHS {"tau", "B", "G", "cx", "cy", "h", "s", "uy0", "y0", "ux0", \
               "x0", "uy1", "y1", "ux1", "x1", "seed", NULL}
#define O_SHB {"mean_uy", "mean_y", "mean_ux", "mean_x", "cov_uy_uy", \
               "cov_y_uy", "cov_y_y", "cov_ux_uy", "cov_ux_y", "cov_ux_ux", \
               "cov_x_uy", "cov_x_y", "cov_x_ux", "cov_x_x", NULL}
#define O_SHS {"uy", "y", "ux", "x", NULL}
#define A_SHM {"tau", "G", "cx", "cy", "s", "uy0", "y0", "ux0", "x0", NULL}
#define O_SHM {"mean_uy", "mean_y", "mean_ux", "mean_x", NULL}
#define A_STOKES {"rho_p", "d_p", "mu_f", "cc", NULL}
#define A_MASS {"rho_p", "d_p", NULL}
#define A_B {"T", "m_p", "tau_p", NULL}
#define A_D {"T", "mu_f", "d_p", "cc", NULL}
#define A_KN {"lambda", "d_p", NULL}
#define A_CC {"kn", NULL}
#define A_CCG {"kn", "A1", "A2", "A3", NULL}
#define A_KOL {"eps", "nu", NULL}
#define A_ST {"tau_p", "tau_f", NULL}
#define A_RE {"d_p", "w", "nu_f", NULL}
#define A_U2 {"u2", NULL}
#define A_WU {"d_p", "u2", "frac", NULL}
#define A_WUB {"d_p", "rho_p", "T", "frac", NULL}
#define E(n, args, text) {#n, args, {NULL}, sbe_w_##n, text}
#define EO(n, args, outs, text) {#n, args, outs, sbe_w_##n, text}

static const sbe_func funcs[] = {
    EO(langevin_moments, A_MOM, MOM,
       "OU/Langevin: exact mean and covariance of (X_t, U_t) from (x0, u0)"),
    E(langevin_var_x, TBT, "OU/Langevin: Var X_t (stable for t << tau)"),
    E(langevin_var_u, TBT, "OU/Langevin: Var U_t = B^2 tau/2 (1 - e^-2t/tau)"),
    E(langevin_cov_xu, TBT, "OU/Langevin: Cov(X_t, U_t)"),
    E(langevin_var_x_cond, TBT,
      "OU/Langevin: Var(X_t | U_t) = B^2 tau^2 [t - 2 tau tanh(t/2tau)]"),
    E(langevin_var_stat, A_TB,
      "OU/Langevin: stationary velocity variance B^2 tau/2"),
    E(langevin_msd, TBT,
      "OU/Langevin: mean-square displacement, Maxwellian start"),
    E(langevin_msd_ballistic, TBT, "OU/Langevin: MSD ballistic limit"),
    E(langevin_msd_diffusive, TBT, "OU/Langevin: MSD diffusive limit"),
    E(langevin_vacf, TBT, "OU/Langevin: velocity autocorrelation"),
    EO(langevin_coef_init, A_COEF,
       O_COEF,
       "OU/Langevin: coefficients of the exact step (Mohaupt 2011, "
       "eq 1.16)"),
    EO(langevin_step,
       A_STEP,
       O_STEP, "OU/Langevin: one exact step from (x, u)"),
    EO(langevin_bridge_moments,
       A_BRM, MOM,
       "OU/Langevin bridge: law of (X_s, U_s) given both end states"),
    EO(langevin_bridge_sample,
       A_BRS,
       O_BRS,
       "OU/Langevin bridge: one draw of (X_s, U_s) given both ends"),
    EO(langevin_shear_mean, A_SHM, O_SHM,
       "Langevin particle in the linear shear (G y + cx, cy): mean of "
       "(u_y, y, u_x, x) after s from a given state (the path without "
       "noise)"),
    EO(langevin_shear_bridge_moments, A_SHB, O_SHB,
       "Langevin bridge in the linear shear (G y + cx, cy): law of "
       "(u_y, y, u_x, x) at s given both end states"),
    EO(langevin_shear_bridge_sample, A_SHS, O_SHS,
       "Langevin bridge in the linear shear: one draw at s given both ends"),
    E(stokes_tau, A_STOKES,
      "SI: Stokes relaxation time rho_p d_p^2 Cc/(18 mu_f) [s]"),
    E(sphere_mass, A_MASS, "SI: sphere mass [kg]"),
    E(brownian_B, A_B,
      "SI: B = sqrt(2 k_B T/(m_p tau_p)) [m/s^1.5]"),
    E(einstein_D, A_D,
      "SI: Stokes-Einstein D = k_B T Cc/(3 pi mu_f d_p) [m^2/s]"),
    E(knudsen, A_KN, "Knudsen number 2 lambda/d_p"),
    E(cunningham, A_CC,
      "Cunningham slip correction (Davies 1945 coefficients)"),
    E(cunningham_gen, A_CCG,
      "Cunningham correction 1 + Kn (A1 + A2 exp(-A3/Kn))"),
    E(kolmogorov_time, A_KOL, "SI: Kolmogorov time sqrt(nu/eps) [s]"),
    E(kolmogorov_length, A_KOL, "SI: Kolmogorov length (nu^3/eps)^1/4 [m]"),
    E(stokes_number, A_ST, "Stokes number tau_p/tau_f"),
    E(particle_reynolds, A_RE, "particle Reynolds number w d_p/nu_f"),
    E(collision_speed, A_U2,
      "SI: mean relative speed of colliding pairs (3/2) sqrt(pi u2) [m/s]"),
    E(wunsch_dt, A_WU,
      "SI: Wunsch step limit frac d_p/((3/2) sqrt(pi u2)) (Mohaupt 2011, "
      "eq 3.2) [s]"),
    E(wunsch_dt_brownian, A_WUB,
      "SI: Wunsch step limit of a Brownian sphere, u2 = k_B T/m_p [s]"),
};

const sbe_table sbe_table_langevin = {funcs, sizeof funcs / sizeof funcs[0]};
