/* engine_lees.c — Lees-Edwards sliding boundaries for the linear shear
 * field U_x = G (y - L_y/2) (Lees & Edwards 1972; docs/engine_forces.md).
 *
 * Images.  The periodic image of the box at y + n L_y is shifted along x
 * by n delta(t), delta(t) = G L_y t (mod L_x), and moves at n G L_y: the
 * fluid velocity of the image, U_x(y) + n G L_y, is the field continued
 * linearly, so the flow is continuous across the y boundary.  For a pair
 * (i, j) with y_i - y_j > L_y/2 (n = 1) or < -L_y/2 (n = -1) the
 * separation is (x_i - x_j - n delta, y_i - y_j - n L_y, z_i - z_j),
 * minimum image in x and z, and the relative chord over a step of length
 * h gains -n G L_y h along x (the image's extra displacement).
 *
 * Neighbour search.  The periodic search (cells, sweep, brute) runs
 * unchanged; its pairs across the y boundary (|y_i - y_j| > L_y/2) are
 * dropped, and the pairs across the sliding boundary are found here:
 * particles within the cut-off c' = c + |G| L_y h of the top and the bottom
 * face, the bottom ones sorted by x, each top particle compared with the
 * bottom ones in the x-window of its shifted image, with the criterion
 * |dx0| <= r_i + r_j + |disp_i| + |disp_j| + |G| L_y h + reach (the
 * triangle inequality on the image's chord): a superset, as the periodic
 * search.  The two sets partition the pairs, so none is examined twice.
 *
 * Transport.  With the images on, the x component of a Stokes species'
 * step is corrected so that its mean is exact in the linear field (the
 * fluid velocity seen is G Y(t), not G Y(0)).  With Y(t) = Y0 + w_y t +
 * V_r tau (1 - e^{-t/tau}) (w_y the settling velocity along y, V_r =
 * u0_y - w_y), the x velocity obeys du/dt = (G Y(t) + w_x - u)/tau; the
 * response to G (Y(t) - Y0) over a step h, x = h/tau, e = e^{-x}, is
 * (sb_langevin_shear_mean_coefs)
 *   du = G tau (Bv V_r + C w_y),   dx = G tau^2 (A V_r + D w_y),
 *   A = x(1+e) - 2(1-e),  Bv = 1 - e(1+x),  C = x - (1-e),
 *   D = x^2/2 - x + (1-e)
 * (integrals of the OU response kernel e^{-(h-t)/tau}; tested against a
 * fine Runge-Kutta integration).  This makes the step exact for non-
 * Brownian particles at every dt/tau_p.
 *
 * Noise.  The noise is exact too: the covariance of (u_y, y, u_x, x) over
 * the step, Sigma(h) = int_0^h Phi Q Phi^T ds, has the OU y block, and x
 * blocks from the response of u_x and x to dW_y through G y (kernels K_u,
 * K_x, the integrands of Bv and A; sb_langevin_shear_noise_cov and _chol,
 * lib/langevin/langevin_shear.c).  The transports (engine.c) draw
 * the same six normals per particle; the x component takes the x rows of
 * the lower Cholesky factor of Sigma in the order (u_y, y, u_x, x)
 * against (z1_y, z2_y, z1_x, z2_x), computed once per species, dt and G
 * (sbi_engine_shear_noise).  Tested in tests/test_engine_shear_noise.c
 * against Van Loan's (1978) matrix exponential at 80 digits and by Monte
 * Carlo (docs/engine_forces.md section 3).
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "common/internal.h"
#include "engine_internal.h"

int sb_engine_set_lees_edwards(sb_engine *e, int on)
{
  if (!e)
    return sbi_error(SB_EINVAL, __func__, "engine is NULL");
  if (on && e->fluid != SB_FLUID_SHEAR)
    return sbi_error(SB_EINVAL, __func__, "Lees-Edwards boundaries need "
                     "the built-in shear field (set it first)");
  if (on && e->par.dim < 2)
    return sbi_error(SB_EINVAL, __func__, "needs dim >= 2");
  if (!on)
    e->le_off = 0.0;
  e->lees = on != 0;
  return SB_SUCCESS;
}

double sb_engine_lees_edwards_offset(const sb_engine *e)
{
  if (!e) {
    sbi_error(SB_EINVAL, __func__, "engine is NULL");
    return 0.0;
  }
  return e->lees ? e->le_off : 0.0;
}


int sbi_engine_shear_noise(sb_engine *e, const sbi_shear_noise **tab)
{
  *tab = NULL;
  const double G = e->fluid_p[0], h = e->par.dt;
  if (!e->lees || e->fluid != SB_FLUID_SHEAR || G == 0.0)
    return SB_SUCCESS;
  if (e->nshn < e->nspec) {
    sbi_shear_noise *t = realloc(e->shn, e->nspec * sizeof *t);
    if (!t)
      return sbi_error(SB_ENOMEM, "sb_engine_step", "out of memory");
    for (size_t k = e->nshn; k < e->nspec; k++) {
      memset(&t[k], 0, sizeof t[k]);
      t[k].dt = NAN;  /* no key yet */
    }
    e->shn = t;
    e->nshn = e->nspec;
  }
  for (size_t sp = 0; sp < e->nspec; sp++) {
    sbi_shear_noise *t = &e->shn[sp];
    const double tau = e->spec[sp].tau, B = e->spec[sp].B;
    const int on = !isinf(tau) &&
                   !(sp < e->nsfl && e->sfl[sp].drag != SB_DRAG_STOKES);
    if (t->G == G && t->dt == h && t->tau == tau && t->B == B &&
        t->on == on)
      continue;  /* cached */
    t->G = G;
    t->dt = h;
    t->tau = tau;
    t->B = B;
    t->on = on;
    if (!on)
      continue;
    double Lh[7];
    sb_langevin_shear_noise_chol(h / tau, G * tau, Lh);
    const double bt = B * sqrt(tau);
    for (int k = 0; k < 7; k++)
      t->L[k] = Lh[k] * (k < 3 ? bt : bt * tau);
  }
  *tab = e->shn;
  return SB_SUCCESS;
}

int sbi_engine_shear_correct(sb_engine *e)
{
  const double G = e->fluid_p[0], h = e->par.dt;
  int bad = 0;
  if (G == 0.0)
    return 0;
  for (size_t i = 0; i < e->n; i++) {
    const size_t sp = e->species[i];
    const double tau = e->spec[sp].tau;
    if (isinf(tau) || (sp < e->nsfl && e->sfl[sp].drag != SB_DRAG_STOKES))
      continue;  /* free flight; nonlinear drag keeps the frozen field */
    double c[4];
    sb_langevin_shear_mean_coefs(h / tau, c);
    const double wy = (e->has_grav && sp < e->nvset) ? e->vset[3 * sp + 1]
                                                     : 0.0;
    const double vr = e->u0[3 * i + 1] - wy;
    const double du = G * tau * (c[1] * vr + c[2] * wy);
    const double dx = G * tau * tau * (c[0] * vr + c[3] * wy);
    e->u[3 * i] += du;
    e->x[3 * i] += dx;
    e->disp[3 * i] += dx;
    /* y - y is 0, or NaN for an infinite or NaN y */
    bad |= !isfinite((e->x[3 * i] - e->x[3 * i]) +
                     (e->u[3 * i] - e->u[3 * i]));
  }
  return bad;
}

int sbi_engine_image(const sb_engine *e, const double *xi, const double *xj,
                     double t, double sh[3], double *du)
{
  const int dim = e->par.dim;
  const int n = e->lees ? sbi_lees_n(e, xi[1] - xj[1]) : 0;
  const double G = e->fluid_p[0], Ly = e->par.L[1];
  sh[0] = sh[1] = sh[2] = 0.0;
  if (n) {
    sh[0] = n * sbi_lees_delta(e, t);
    sh[1] = n * Ly;
  }
  for (int k = 0; k < dim; k++) {
    if (e->wall[2 * k] != SB_WALL_PERIODIC)
      continue;  /* no image across a wall */
    const double d = xi[k] - xj[k] - sh[k];
    sh[k] += d - sbi_minimg(d, e->par.L[k]);
  }
  *du = n * G * Ly;
  return n;
}

void sbi_engine_boundary_fix_pair(const sb_engine *e, const double *xi,
                                  const double *xj, double t,
                                  sb_engine_pair *p)
{
  const int dim = e->par.dim;
  int n = 0;
  if (e->lees)
    n = sbi_lees_n(e, xi[1] - xj[1]);
  for (int k = 0; k < dim; k++) {
    double d = xi[k] - xj[k];
    if (e->wall[2 * k] != SB_WALL_PERIODIC) {
      p->dx0[k] = d;  /* no image across a wall */
      continue;
    }
    if (k == 0)
      d -= n * sbi_lees_delta(e, t);
    else if (k == 1)
      d -= n * e->par.L[1];
    p->dx0[k] = sbi_minimg(d, e->par.L[k]);
  }
  if (n)
    p->dd[0] -= n * e->fluid_p[0] * e->par.L[1] * p->dt;
}

void sbi_engine_lees_near(const sb_engine *e, const double *ref,
                          const double *x, double t, double out[3])
{
  const int n = sbi_lees_n(e, x[1] - ref[1]);
  for (int c = 0; c < 3; c++) {
    if (c >= e->par.dim) {
      out[c] = ref[c];
      continue;
    }
    double d = x[c] - ref[c];
    if (c == 0)
      d -= n * sbi_lees_delta(e, t);
    else if (c == 1)
      d -= n * e->par.L[1];
    out[c] = ref[c] + sbi_minimg(d, e->par.L[c]);
  }
}

double sbi_engine_lees_dist2(const sb_engine *e, const double *p,
                             const double *q, double t, int *n)
{
  *n = sbi_lees_n(e, p[1] - q[1]);
  double d2 = 0.0;
  for (int c = 0; c < e->par.dim; c++) {
    double d = p[c] - q[c];
    if (c == 0)
      d -= *n * sbi_lees_delta(e, t);
    else if (c == 1)
      d -= *n * e->par.L[1];
    d = sbi_minimg(d, e->par.L[c]);
    d2 += d * d;
  }
  return d2;
}

typedef struct {
  double x;
  size_t i;
} xkey;

static int xkey_cmp(const void *a, const void *b)
{
  const xkey *p = a, *q = b;
  if (p->x != q->x)
    return p->x < q->x ? -1 : 1;
  return p->i < q->i ? -1 : (p->i > q->i);
}

/* First index of keys with x >= v. */
static size_t lower(const xkey *k, size_t n, double v)
{
  size_t lo = 0, hi = n;
  while (lo < hi) {
    size_t m = lo + (hi - lo) / 2;
    if (k[m].x < v)
      lo = m + 1;
    else
      hi = m;
  }
  return lo;
}

static int try_pair(sb_engine *e, const double *x0, size_t i, size_t j,
                    double extra, double reach, const char *who)
{
  const double *L = e->par.L;
  if (!(x0[3 * i + 1] - x0[3 * j + 1] > 0.5 * L[1]))
    return SB_SUCCESS;  /* not across: the periodic search has it */
  double d[3] = {0, 0, 0};
  d[0] = sbi_minimg(x0[3 * i] - x0[3 * j] - e->le_off, L[0]);
  d[1] = x0[3 * i + 1] - x0[3 * j + 1] - L[1];
  if (e->par.dim == 3)
    d[2] = sbi_minimg(x0[3 * i + 2] - x0[3 * j + 2], L[2]);
  double lim = e->radius[i] + e->radius[j] + e->dn[i] + e->dn[j] + extra +
               reach;
  if (d[0] * d[0] + d[1] * d[1] + d[2] * d[2] > lim * lim)
    return SB_SUCCESS;
  return sbi_engine_push_pair(e, i < j ? i : j, i < j ? j : i, who);
}

static int lees_pairs(sb_engine *e, const double *x0, double reach,
                      double cut, const char *who)
{
  const double *L = e->par.L;
  const double extra = fabs(e->fluid_p[0]) * L[1] * e->par.dt;
  const double c = cut + extra;
  for (int k = 0; k < e->par.dim; k++)
    if (!(c < 0.5 * L[k]))
      return sbi_error(SB_EINVAL, who,
                       "step too large for the box: reach with the "
                       "Lees-Edwards velocity jump |G| L_y dt, %g m, is not "
                       "below L[%d]/2 = %g m", c, k, 0.5 * L[k]);
  size_t nb = 0, nt = 0;
  for (size_t i = 0; i < e->n; i++) {
    double y = x0[3 * i + 1];
    nb += y <= c;
    nt += y >= L[1] - c;
  }
  if (!nb || !nt)
    return SB_SUCCESS;
  xkey *bot = malloc(nb * sizeof *bot);
  size_t *top = malloc(nt * sizeof *top);
  if (!bot || !top) {
    free(bot);
    free(top);
    return sbi_error(SB_ENOMEM, who, "out of memory");
  }
  nb = nt = 0;
  for (size_t i = 0; i < e->n; i++) {
    double y = x0[3 * i + 1];
    if (y <= c)
      bot[nb++] = (xkey){x0[3 * i], i};
    if (y >= L[1] - c)
      top[nt++] = i;
  }
  qsort(bot, nb, sizeof *bot, xkey_cmp);
  int st = SB_SUCCESS;
  for (size_t q = 0; q < nt && !st; q++) {
    const size_t i = top[q];
    /* the image of a bottom particle j sits at x_j + delta: look for
     * x_j near x_i - delta, window [xc - c, xc + c] modulo L_x */
    const double xc = sbi_wrap(x0[3 * i] - e->le_off, L[0]);
    double lo = xc - c, hi = xc + c;
    double r[2][2] = {{lo < 0.0 ? 0.0 : lo, hi > L[0] ? L[0] : hi},
                      {1.0, 0.0}};
    if (lo < 0.0) {
      r[1][0] = lo + L[0];
      r[1][1] = L[0];
    } else if (hi > L[0]) {
      r[1][0] = 0.0;
      r[1][1] = hi - L[0];
    }
    for (int w = 0; w < 2 && !st; w++) {
      if (r[w][0] > r[w][1])
        continue;
      for (size_t b = lower(bot, nb, r[w][0]); b < nb && bot[b].x <= r[w][1];
           b++)
        if (bot[b].i != i && (st = try_pair(e, x0, i, bot[b].i, extra,
                                            reach, who)))
          break;
    }
  }
  free(bot);
  free(top);
  return st;
}

int sbi_engine_boundary_pairs(sb_engine *e, const double *x0,
                              const double *disp, double reach, double cut,
                              const char *who)
{
  (void)disp;
  if (!e->lees && !e->walled)
    return SB_SUCCESS;
  const int dim = e->par.dim;
  /* drop the periodic search's pairs across a wall or the sliding
   * boundary */
  size_t w = 0;
  for (size_t q = 0; q < e->npairs; q++) {
    const size_t i = e->pairs[2 * q], j = e->pairs[2 * q + 1];
    int keep = 1;
    for (int k = 0; k < dim && keep; k++)
      if (e->wall[2 * k] != SB_WALL_PERIODIC || (k == 1 && e->lees))
        keep = fabs(x0[3 * i + k] - x0[3 * j + k]) <= 0.5 * e->par.L[k];
    if (keep) {
      e->pairs[2 * w] = i;
      e->pairs[2 * w + 1] = j;
      w++;
    }
  }
  e->npairs = w;
  return e->lees ? lees_pairs(e, x0, reach, cut, who) : SB_SUCCESS;
}
