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
  double m = fabs(a) < fabs(b) ? a : b;
  return a * b > 0 ? m : 0.0;
}

static inline double dmin(double a, double b) { return a < b ? a : b; }
static inline double dmax(double a, double b) { return a > b ? a : b; }

/* Face states of `count` consecutive cells (r, un, ut point at the first;
 * neighbours at -off and +off): density and normal/transverse velocity on
 * the low (L: west or south) and high (H: east or north) faces, MUSCL
 * reconstruction with minmod slopes.  The velocity slope du is shared
 * out so that (rho_L u_L + rho_H u_H)/2 = rho u: u_H = u + (rho_L/rho)
 * du/2, u_L = u - (rho_H/rho) du/2 (the cell's momentum is kept; each
 * face velocity stays between the neighbours' velocities). */
static void faces(size_t count, const double *r, const double *un,
                  const double *ut, ptrdiff_t off, double fl, double *RL,
                  double *NL, double *TL, double *RH, double *NH, double *TH)
{
  for (size_t k = 0; k < count; k++) {
    const double rc = r[k], rm = r[(ptrdiff_t)k - off],
                 rp = r[(ptrdiff_t)k + off];
    const double nc = un[k], tc = ut[k];
    const double nm = un[(ptrdiff_t)k - off], np = un[(ptrdiff_t)k + off];
    /* A delta-shock: a density jump by more than a factor 2 (not a
     * resolved smooth profile) where the flow converges.  There the
     * cell is first order: a reconstructed profile inside the delta
     * would move its mass with face velocities that differ from its
     * momentum (the delta then lags), so the kinetic upwind flux of
     * the cell state is used, which moves the mass centroid exactly
     * with the momentum. */
    int delta = np < nm && dmax(dmax(rm, rc), rp) > 2 * dmin(dmin(rm, rc), rp);
    if (delta || !(rc > fl)) {
      RL[k] = RH[k] = rc;
      NL[k] = NH[k] = nc;
      TL[k] = TH[k] = tc;
      continue;
    }
    double dr = minmod(rc - rm, rp - rc);
    RH[k] = rc + 0.5 * dr;
    RL[k] = rc - 0.5 * dr;
    /* vacuum neighbours carry no velocity: no slope towards them */
    double dn = 0, dt = 0;
    if (rm > fl && rp > fl) {
      dn = minmod(nc - nm, np - nc);
      dt = minmod(tc - ut[(ptrdiff_t)k - off], ut[(ptrdiff_t)k + off] - tc);
    }
    const double half = 0.5 / rc, aH = RL[k] * half, aL = RH[k] * half;
    NH[k] = nc + aH * dn;
    NL[k] = nc - aL * dn;
    TH[k] = tc + aH * dt;
    TL[k] = tc - aL * dt;
  }
}

/* Kinetic fluxes through `count` interfaces: (rH, nH, tH) the high-face
 * state of the cell below/left of each interface, (rL, nL, tL) the
 * low-face state of the cell above/right. */
static void kflux(size_t count, const double *rH, const double *nH,
                  const double *tH, const double *rL, const double *nL,
                  const double *tL, double *Fm, double *Fn, double *Ft)
{
  for (size_t k = 0; k < count; k++) {
    double a = nH[k] > 0 ? rH[k] * nH[k] : 0.0;
    double b = nL[k] < 0 ? rL[k] * nL[k] : 0.0;
    Fm[k] = a + b;
    Fn[k] = a * nH[k] + b * nL[k];
    Ft[k] = a * tH[k] + b * tL[k];
  }
}

int sbi_pgd_nstages(sb_pgd_scheme s)
{
  return s == SB_PGD_MUSCL ? 2 : 1;
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
  double v[3];
  for (int c = 0; c < 3; c++) {
    v[c] = f[c] * wdt_len;
    b[c] += v[c];
  }
  if (f[0] > 0)
    sbi_budget_add(&g->bud, s, 1, v[0], v[1], v[2]);
  else
    sbi_budget_add(&g->bud, s, 0, -v[0], -v[1], -v[2]);
}

/* x direction: flux divergence of every row into dr, dqx, dqy. */
static void sweep_x(struct sb_pgd *g, double dt, double bw)
{
  const int muscl = g->p.scheme == SB_PGD_MUSCL;
  const double fl = g->p.rho_floor, lam = dt / g->dx;
  const double flen = dt * bw * g->dy;
  const size_t nx = g->nx, m = nx + 4;
  double *w = g->line, *Fm = w + 6 * m, *Fn = Fm + m, *Ft = Fn + m;
  for (size_t j = 0; j < g->ny; j++) {
    const size_t c0 = sbi_pgd_idx(g, 0, (long)j);
    const double *r = g->rho + c0, *un = g->ux + c0, *ut = g->uy + c0;
    if (muscl) { /* faces of cells -1 .. nx */
      double *RL = w, *NL = w + m, *TL = w + 2 * m, *RH = w + 3 * m,
             *NH = w + 4 * m, *TH = w + 5 * m;
      faces(nx + 2, r - 1, un - 1, ut - 1, 1, fl, RL, NL, TL, RH, NH, TH);
      kflux(nx + 1, RH, NH, TH, RL + 1, NL + 1, TL + 1, Fm, Fn, Ft);
    } else {
      kflux(nx + 1, r - 1, un - 1, ut - 1, r, un, ut, Fm, Fn, Ft);
    }
    double *dr = g->dr + c0, *dn = g->dqx + c0, *dt_ = g->dqy + c0;
    for (size_t k = 0; k < nx; k++) {
      dr[k] -= lam * (Fm[k + 1] - Fm[k]);
      dn[k] -= lam * (Fn[k + 1] - Fn[k]);
      dt_[k] -= lam * (Ft[k + 1] - Ft[k]);
    }
    /* outward fluxes through the two ends of the row, as (mass, qx, qy) */
    double fa[3] = {-Fm[0], -Fn[0], -Ft[0]};
    double fb[3] = {Fm[nx], Fn[nx], Ft[nx]};
    if (g->p.bc[SB_PGD_WEST] != SB_PGD_PERIODIC || g->external[SB_PGD_WEST])
      boundary_flux(g, SB_PGD_WEST, j, fa, flen);
    if (g->p.bc[SB_PGD_EAST] != SB_PGD_PERIODIC || g->external[SB_PGD_EAST])
      boundary_flux(g, SB_PGD_EAST, j, fb, flen);
  }
}

/* y direction, row interface by row interface (contiguous in memory):
 * interface j separates rows j - 1 and j. */
static void sweep_y(struct sb_pgd *g, double dt, double bw)
{
  const int muscl = g->p.scheme == SB_PGD_MUSCL;
  const double fl = g->p.rho_floor, lam = dt / g->dy;
  const double flen = dt * bw * g->dx;
  const size_t nx = g->nx, ny = g->ny;
  const ptrdiff_t off = (ptrdiff_t)g->sx;
  double *w = g->line;
  /* faces of the row below (H only needed) and of the current row */
  double *pRH = w, *pNH = w + nx, *pTH = w + 2 * nx;
  double *RL = w + 3 * nx, *NL = w + 4 * nx, *TL = w + 5 * nx;
  double *RH = w + 6 * nx, *NH = w + 7 * nx, *TH = w + 8 * nx;
  double *Gm = w + 9 * nx, *Gn = w + 10 * nx, *Gt = w + 11 * nx;
  for (long j = muscl ? -1 : 0; j <= (long)ny; j++) {
    const size_t c0 = sbi_pgd_idx(g, 0, j);
    const double *r = g->rho + c0, *un = g->uy + c0, *ut = g->ux + c0;
    if (muscl) {
      faces(nx, r, un, ut, off, fl, RL, NL, TL, RH, NH, TH);
      if (j >= 0)
        kflux(nx, pRH, pNH, pTH, RL, NL, TL, Gm, Gn, Gt);
      double *t;
      t = pRH, pRH = RH, RH = t;
      t = pNH, pNH = NH, NH = t;
      t = pTH, pTH = TH, TH = t;
      if (j < 0)
        continue;
    } else {
      kflux(nx, r - off, un - off, ut - off, r, un, ut, Gm, Gn, Gt);
    }
    if (j >= 1) { /* top face of row j - 1 */
      const size_t b0 = c0 - g->sx;
      for (size_t i = 0; i < nx; i++) {
        g->dr[b0 + i] -= lam * Gm[i];
        g->dqy[b0 + i] -= lam * Gn[i];
        g->dqx[b0 + i] -= lam * Gt[i];
      }
    }
    if (j < (long)ny) { /* bottom face of row j */
      for (size_t i = 0; i < nx; i++) {
        g->dr[c0 + i] += lam * Gm[i];
        g->dqy[c0 + i] += lam * Gn[i];
        g->dqx[c0 + i] += lam * Gt[i];
      }
    }
    int s = j == 0 ? SB_PGD_SOUTH : j == (long)ny ? SB_PGD_NORTH : -1;
    if (s >= 0 && (g->p.bc[s] != SB_PGD_PERIODIC || g->external[s])) {
      double sg = s == SB_PGD_SOUTH ? -1.0 : 1.0;
      for (size_t i = 0; i < nx; i++) {
        double f[3] = {sg * Gm[i], sg * Gt[i], sg * Gn[i]};
        boundary_flux(g, s, i, f, flen);
      }
    }
  }
}

/* Velocities of every padded cell (0 in vacuum). */
static void velocities(struct sb_pgd *g)
{
  const double fl = g->p.rho_floor;
  const size_t n = g->sx * g->sy;
  for (size_t c = 0; c < n; c++) {
    double r = g->rho[c];
    double inv = r > fl ? 1.0 / r : 0.0;
    g->ux[c] = g->qx[c] * inv;
    g->uy[c] = g->qy[c] * inv;
  }
}

/* Speed bound of one cell, folded into *s: (|qx| ix + |qy| iy)/rho, the
 * gas velocity included where there is drag (the drag relaxes u towards
 * it, so |u| stays below max(|u|, |U|)).  Divides only near or above the
 * running maximum; the result is the exact maximum of the quotients,
 * independent of the order of the cells (domain decomposition). */
static inline void speed_acc(double r, double qx, double qy, double gx,
                             double gy, int drag, double ix, double iy,
                             double fl, double *s)
{
  if (!(r > fl))
    return;
  double ax = fabs(qx), ay = fabs(qy);
  if (drag) {
    double bx = r * fabs(gx), by = r * fabs(gy);
    ax = ax > bx ? ax : bx;
    ay = ay > by ? ay : by;
  }
  double v = ax * ix + ay * iy;
  if (v >= *s * r * (1 - 1e-12)) {
    double w = v / r;
    if (w > *s)
      *s = w;
  }
}

/* Whether every cell, ghosts included, is vacuum: then a stage changes
 * nothing (no flux anywhere) and is skipped.  Mostly empty blocks of a
 * decomposition (the corners of the crossing jets) cost one scan. */
static int all_vacuum(const struct sb_pgd *g, int stage)
{
  const size_t n = g->sx * g->sy;
  for (size_t c = 0; c < n; c++)
    if (g->rho[c] != 0)
      return 0;
  if (stage == 1) /* Heun's second stage also averages with the start */
    for (size_t c = 0; c < n; c++)
      if (g->r0[c] != 0)
        return 0;
  return 1;
}

void sbi_pgd_stage(struct sb_pgd *g, double dt, int stage)
{
  const int muscl = g->p.scheme == SB_PGD_MUSCL;
  const size_t n = g->sx * g->sy;
  if (all_vacuum(g, muscl ? stage : 0)) {
    g->empty = 1;
    g->speed = 0;
    g->speed_ok = 1;
    return;
  }
  g->empty = 0;
  memset(g->dr, 0, n * sizeof(double));
  memset(g->dqx, 0, n * sizeof(double));
  memset(g->dqy, 0, n * sizeof(double));
  double bw = muscl ? 0.5 : 1.0;  /* Heun: each stage's flux counts 1/2 */
  velocities(g);
  sweep_x(g, dt, bw);
  if (g->p.dim == 2)
    sweep_y(g, dt, bw);
  const int last = stage == sbi_pgd_nstages(g->p.scheme) - 1;
  const int drag = !isinf(g->p.tau);
  const double fl = g->p.rho_floor, ix = 1.0 / g->dx;
  const double iy = g->p.dim == 2 ? 1.0 / g->dy : 0.0;
  double sp = 0;
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
      if (last)
        speed_acc(r, x, y, g->ugx[c], g->ugy[c], drag, ix, iy, fl, &sp);
    }
  }
  g->speed = sp;
  g->speed_ok = last;
}

void sbi_pgd_drag(struct sb_pgd *g, double h, int track)
{
  if (isinf(g->p.tau) || !(h > 0) || g->empty)
    return;
  const double e = exp(-h / g->p.tau), a = -expm1(-h / g->p.tau);
  const double fl = g->p.rho_floor, ix = 1.0 / g->dx;
  const double iy = g->p.dim == 2 ? 1.0 / g->dy : 0.0;
  double sp = 0;
  for (size_t j = 0; j < g->ny; j++) {
    size_t c = sbi_pgd_idx(g, 0, (long)j);
    for (size_t i = 0; i < g->nx; i++, c++) {
      double r = g->rho[c];
      double x = e * g->qx[c] + a * r * g->ugx[c];
      double y = e * g->qy[c] + a * r * g->ugy[c];
      g->qx[c] = x;
      g->qy[c] = y;
      if (track)
        speed_acc(r, x, y, g->ugx[c], g->ugy[c], 1, ix, iy, fl, &sp);
    }
  }
  g->speed = sp;
  g->speed_ok = track;
}

double sbi_pgd_speed(const struct sb_pgd *g)
{
  const double fl = g->p.rho_floor, ix = 1.0 / g->dx;
  const double iy = g->p.dim == 2 ? 1.0 / g->dy : 0.0;
  const int drag = !isinf(g->p.tau);
  double s = 0;
  if (g->speed_ok) {
    s = g->speed;
  } else {
    for (size_t j = 0; j < g->ny; j++) {
      size_t c = sbi_pgd_idx(g, 0, (long)j);
      for (size_t i = 0; i < g->nx; i++, c++)
        speed_acc(g->rho[c], g->qx[c], g->qy[c], g->ugx[c], g->ugy[c], drag,
                  ix, iy, fl, &s);
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

/* One Strang step, dt already checked. */
static void step(sb_pgd *g, double dt)
{
  sbi_pgd_drag(g, 0.5 * dt, 0);
  sbi_pgd_transport_begin(g);
  for (int s = 0; s < sbi_pgd_nstages(g->p.scheme); s++) {
    sbi_pgd_fill_ghosts(g);
    sbi_pgd_stage(g, dt, s);
  }
  sbi_pgd_drag(g, 0.5 * dt, 1);
  g->t += dt;
  g->steps++;
}

/* A solver loaded without its gas callback cannot step. */
static int gas_missing(const sb_pgd *g, const char *func)
{
  return g->gas_missing
             ? sbi_error(SB_EINVAL, func, "the checkpoint this solver was "
                         "loaded from had a gas velocity callback: attach "
                         "it again with sb_pgd_set_gas")
             : SB_SUCCESS;
}

int sb_pgd_step(sb_pgd *g, double dt)
{
  if (!g)
    return sbi_error(SB_EINVAL, __func__, "NULL solver");
  if (g->gas_missing)
    return gas_missing(g, __func__);
  double lim = sb_pgd_dt(g);
  if (!(dt > 0) || !isfinite(dt) || dt > lim * (1 + 1e-12))
    return sbi_error(SB_EINVAL, __func__, "dt = %g: must be in (0, %g] "
                     "(CFL %g)", dt, lim, g->p.cfl);
  step(g, dt);
  return SB_SUCCESS;
}

int sb_pgd_advance(sb_pgd *g, double t_end, size_t *nsteps)
{
  if (!g)
    return sbi_error(SB_EINVAL, __func__, "NULL solver");
  if (!(t_end >= g->t) || !isfinite(t_end))
    return sbi_error(SB_EINVAL, __func__, "t_end = %g before t = %g", t_end,
                     g->t);
  if (g->gas_missing && g->t < t_end)
    return gas_missing(g, __func__);
  size_t k = 0;
  while (g->t < t_end) {
    double dt = sb_pgd_dt(g), left = t_end - g->t;
    int last = dt >= left * (1 - 1e-12);
    if (last)
      dt = left;
    step(g, dt);
    k++;
    if (last)
      g->t = t_end;
  }
  if (nsteps)
    *nsteps = k;
  return SB_SUCCESS;
}
