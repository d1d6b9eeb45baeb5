/* pgd_scheme.c — the finite-volume step of sb_pgd: kinetic fluxes
 * (first-order upwind, or MUSCL with the momentum-conserving velocity
 * reconstruction), SSP-RK2 stages, exact drag relaxation, Strang
 * splitting, the CFL rule.
 *
 * Kinetic flux (Bouchut, Jin & Li 2003): the monokinetic distribution
 * rho delta(v - u) split by the sign of the normal velocity,
 *   F(UL, UR) = rho_L max(u_L, 0) (1, u_L) + rho_R min(u_R, 0) (1, u_R);
 * the new u of a cell is then a convex combination of old (reconstructed)
 * velocities: positivity and the maximum principle on u under the CFL
 * condition (docs/pgd.md gives the short proof). */
#include <math.h>
#include <string.h>

#include <smolbridge/pgd.h>
#include "common/internal.h"
#include "pgd_internal.h"

static inline double minmod(double a, double b)
{
  if (a > 0 && b > 0)
    return a < b ? a : b;
  if (a < 0 && b < 0)
    return a > b ? a : b;
  return 0.0;
}

/* Interface fluxes of one line of n cells gathered with their G ghost
 * cells on each side: r, un (normal velocity), ut (transverse velocity)
 * at indices 0 .. n+3 (interior cell k at k + 2).  F[3 m .. 3 m + 2] =
 * (mass, normal momentum, transverse momentum) flux through interface m
 * (m = 0 .. n; interface m is the left face of interior cell m). */
static void line_fluxes(int muscl, size_t n, const double *r,
                        const double *un, const double *ut, double fl,
                        double *F, double *w)
{
  const size_t m = n + 4;
  const double *rE = r, *rW = r, *unE = un, *unW = un, *utE = ut, *utW = ut;
  if (muscl) {
    double *RE = w, *RW = w + m, *NE = w + 2 * m, *NW = w + 3 * m,
           *TE = w + 4 * m, *TW = w + 5 * m;
    for (size_t c = 1; c + 1 < m; c++) {
      double dr = minmod(r[c] - r[c - 1], r[c + 1] - r[c]);
      RE[c] = r[c] + 0.5 * dr;
      RW[c] = r[c] - 0.5 * dr;
      if (!(r[c] > fl)) {
        NE[c] = NW[c] = un[c];
        TE[c] = TW[c] = ut[c];
        continue;
      }
      /* vacuum neighbours carry no velocity: no slope towards them.  A
       * sharp density peak (more than twice a neighbour: not a resolved
       * smooth profile) squeezed from both sides is a delta-shock: its
       * mass moves with one velocity, so no slope either (a converging
       * slope would hold the peak back in its cell) */
      int lv = r[c - 1] > fl, rv = r[c + 1] > fl;
      int peak = r[c] >= r[c - 1] && r[c] >= r[c + 1] &&
                 r[c] > 2 * fmin(r[c - 1], r[c + 1]) && un[c + 1] < un[c - 1];
      int slope = lv && rv && !peak;
      double dn = slope ? minmod(un[c] - un[c - 1], un[c + 1] - un[c]) : 0;
      double dt = slope ? minmod(ut[c] - ut[c - 1], ut[c + 1] - ut[c]) : 0;
      /* u_E = u + (rho_W/rho) du/2, u_W = u - (rho_E/rho) du/2 keeps
       * (rho_E u_E + rho_W u_W)/2 = rho u: the cell's momentum */
      double aE = 0.5 * RW[c] / r[c], aW = 0.5 * RE[c] / r[c];
      NE[c] = un[c] + aE * dn;
      NW[c] = un[c] - aW * dn;
      TE[c] = ut[c] + aE * dt;
      TW[c] = ut[c] - aW * dt;
    }
    rE = RE, rW = RW, unE = NE, unW = NW, utE = TE, utW = TW;
  }
  for (size_t k = 0; k <= n; k++) {
    size_t L = k + 1, R = k + 2;
    double aL = unE[L] > 0 ? rE[L] * unE[L] : 0.0;
    double aR = unW[R] < 0 ? rW[R] * unW[R] : 0.0;
    F[3 * k] = aL + aR;
    F[3 * k + 1] = aL * unE[L] + aR * unW[R];
    F[3 * k + 2] = aL * utE[L] + aR * utW[R];
  }
}

int sbi_pgd_nstages(const struct sb_pgd *g)
{
  return g->p.scheme == SB_PGD_MUSCL ? 2 : 1;
}

void sbi_pgd_transport_begin(struct sb_pgd *g)
{
  size_t n = g->sx * g->sy;
  if (g->p.scheme == SB_PGD_MUSCL) {
    memcpy(g->r0, g->rho, n * sizeof(double));
    memcpy(g->qx0, g->qx, n * sizeof(double));
    memcpy(g->qy0, g->qy, n * sizeof(double));
  }
  for (int s = 0; s < 4; s++)
    if (g->nb[s])
      memset(g->bflux[s], 0, 3 * g->nb[s] * sizeof(double));
}

/* Record the outward flux f[3] (mass, qx, qy per unit time and face
 * length) through boundary cell k of side s, weighted by wdt len. */
static void boundary_flux(struct sb_pgd *g, int s, size_t k, const double f[3],
                          double wdt_len)
{
  double *b = g->bflux[s] + 3 * k;
  for (int c = 0; c < 3; c++) {
    double v = f[c] * wdt_len;
    b[c] += v;
    if (c == 0 ? v > 0 : f[0] > 0)
      g->out_tot[c] += v;
    else
      g->in_tot[c] -= v;
  }
}

/* One direction's flux divergence into dr, dqx, dqy; dir 0 = x rows,
 * 1 = y columns. */
static void sweep(struct sb_pgd *g, int dir, double dt, double bw)
{
  const int muscl = g->p.scheme == SB_PGD_MUSCL;
  const double fl = g->p.rho_floor;
  const size_t n = dir ? g->ny : g->nx, nl = dir ? g->nx : g->ny;
  const size_t m = n + 4;
  const size_t stride = dir ? g->sx : 1;
  const double lam = dt / (dir ? g->dy : g->dx);
  const double flen = dt * bw * (dir ? g->dx : g->dy);
  const double *qn = dir ? g->qy : g->qx, *qt = dir ? g->qx : g->qy;
  double *dn = dir ? g->dqy : g->dqx, *dtr = dir ? g->dqx : g->dqy;
  double *r = g->line, *un = r + m, *ut = un + m, *F = ut + m, *w = F + 3 * m;
  const int sl = dir ? SB_PGD_SOUTH : SB_PGD_WEST;
  for (size_t l = 0; l < nl; l++) {
    size_t c0 = dir ? sbi_pgd_idx(g, (long)l, -SBI_PGD_G)
                    : sbi_pgd_idx(g, -SBI_PGD_G, (long)l);
    for (size_t k = 0; k < m; k++) {
      size_t c = c0 + k * stride;
      r[k] = g->rho[c];
      un[k] = sbi_pgd_vel(r[k], qn[c], fl);
      ut[k] = sbi_pgd_vel(r[k], qt[c], fl);
    }
    line_fluxes(muscl, n, r, un, ut, fl, F, w);
    for (size_t k = 0; k < n; k++) {
      size_t c = c0 + (k + SBI_PGD_G) * stride;
      const double *a = F + 3 * k, *b = a + 3;
      g->dr[c] -= lam * (b[0] - a[0]);
      dn[c] -= lam * (b[1] - a[1]);
      dtr[c] -= lam * (b[2] - a[2]);
    }
    /* outward fluxes through the two ends of the line, as (mass, qx, qy) */
    const double *a = F, *b = F + 3 * n;
    double fa[3] = {-a[0], dir ? -a[2] : -a[1], dir ? -a[1] : -a[2]};
    double fb[3] = {b[0], dir ? b[2] : b[1], dir ? b[1] : b[2]};
    if (g->p.bc[sl] != SB_PGD_PERIODIC || g->external[sl])
      boundary_flux(g, sl, l, fa, flen);
    if (g->p.bc[sl + 1] != SB_PGD_PERIODIC || g->external[sl + 1])
      boundary_flux(g, sl + 1, l, fb, flen);
  }
}

void sbi_pgd_stage(struct sb_pgd *g, double dt, int stage)
{
  const int muscl = g->p.scheme == SB_PGD_MUSCL;
  const size_t n = g->sx * g->sy;
  memset(g->dr, 0, n * sizeof(double));
  memset(g->dqx, 0, n * sizeof(double));
  memset(g->dqy, 0, n * sizeof(double));
  double bw = muscl ? 0.5 : 1.0;  /* Heun: each stage's flux counts 1/2 */
  sweep(g, 0, dt, bw);
  if (g->p.dim == 2)
    sweep(g, 1, dt, bw);
  for (size_t j = 0; j < g->ny; j++) {
    size_t c = sbi_pgd_idx(g, 0, (long)j);
    for (size_t i = 0; i < g->nx; i++, c++) {
      double r = g->rho[c] + g->dr[c];
      double x = g->qx[c] + g->dqx[c];
      double y = g->qy[c] + g->dqy[c];
      if (muscl && stage == 1) {
        r = 0.5 * (g->r0[c] + r);
        x = 0.5 * (g->qx0[c] + x);
        y = 0.5 * (g->qy0[c] + y);
      }
      /* the update is a positive combination under the CFL condition;
       * a negative value can only be round-off of a vanishing density */
      if (!(r > 0))
        r = x = y = 0.0;
      g->rho[c] = r;
      g->qx[c] = x;
      g->qy[c] = y;
    }
  }
}

void sbi_pgd_drag(struct sb_pgd *g, double h)
{
  if (isinf(g->p.tau) || !(h > 0))
    return;
  const double e = exp(-h / g->p.tau), a = -expm1(-h / g->p.tau);
  for (size_t j = 0; j < g->ny; j++) {
    size_t c = sbi_pgd_idx(g, 0, (long)j);
    for (size_t i = 0; i < g->nx; i++, c++) {
      g->qx[c] = e * g->qx[c] + a * g->rho[c] * g->ugx[c];
      g->qy[c] = e * g->qy[c] + a * g->rho[c] * g->ugy[c];
    }
  }
}

double sbi_pgd_speed(const struct sb_pgd *g)
{
  const double fl = g->p.rho_floor, ix = 1.0 / g->dx;
  const double iy = g->p.dim == 2 ? 1.0 / g->dy : 0.0;
  const int drag = !isinf(g->p.tau);
  double s = 0;
  for (size_t j = 0; j < g->ny; j++) {
    size_t c = sbi_pgd_idx(g, 0, (long)j);
    for (size_t i = 0; i < g->nx; i++, c++) {
      double ux = fabs(sbi_pgd_vel(g->rho[c], g->qx[c], fl));
      double uy = fabs(sbi_pgd_vel(g->rho[c], g->qy[c], fl));
      if (drag) { /* the drag relaxes u towards the gas */
        ux = fmax(ux, fabs(g->ugx[c]));
        uy = fmax(uy, fabs(g->ugy[c]));
      }
      double v = ux * ix + uy * iy;
      if (v > s)
        s = v;
    }
  }
  for (size_t k = 0; k < g->p.ninflow; k++) {
    const sb_pgd_inflow *in = &g->p.inflow[k];
    double v = fabs(in->u[0]) * ix + fabs(in->u[1]) * iy;
    if (v > s)
      s = v;
  }
  return s;
}

double sb_pgd_dt(const sb_pgd *g)
{
  if (!g)
    return NAN;
  return sbi_pgd_dt_from_speed(&g->p, sbi_pgd_speed(g));
}

int sb_pgd_step(sb_pgd *g, double dt)
{
  if (!g)
    return sbi_error(SB_EINVAL, __func__, "NULL solver");
  double lim = sb_pgd_dt(g);
  if (!(dt > 0) || !isfinite(dt) || dt > lim * (1 + 1e-12))
    return sbi_error(SB_EINVAL, __func__, "dt = %g: must be in (0, %g] "
                     "(CFL %g)", dt, lim, g->p.cfl);
  sbi_pgd_drag(g, 0.5 * dt);
  sbi_pgd_transport_begin(g);
  for (int s = 0; s < sbi_pgd_nstages(g); s++) {
    sbi_pgd_fill_ghosts(g);
    sbi_pgd_stage(g, dt, s);
  }
  sbi_pgd_drag(g, 0.5 * dt);
  g->t += dt;
  g->steps++;
  return SB_SUCCESS;
}

int sb_pgd_advance(sb_pgd *g, double t_end, size_t *nsteps)
{
  if (!g)
    return sbi_error(SB_EINVAL, __func__, "NULL solver");
  if (!(t_end >= g->t) || !isfinite(t_end))
    return sbi_error(SB_EINVAL, __func__, "t_end = %g before t = %g", t_end,
                     g->t);
  size_t k = 0;
  while (g->t < t_end) {
    double dt = sb_pgd_dt(g), left = t_end - g->t;
    int last = dt >= left * (1 - 1e-12);
    if (last)
      dt = left;
    int st = sb_pgd_step(g, dt);
    if (st)
      return st;
    k++;
    if (last)
      g->t = t_end;
  }
  if (nsteps)
    *nsteps = k;
  return SB_SUCCESS;
}
