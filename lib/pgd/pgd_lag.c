/* pgd_lag.c — the Lagrangian method of the exercise "Couplage
 * Euler-Lagrange" (2022, part 3): drag-only weighted particles, inflow by
 * injection at the entering mass flux, removal at the outflow, deposition
 * of rho and rho u on the grid.  Each particle obeys dx/dt = v,
 * dv/dt = (U_gas - v)/tau, integrated exactly over a step (the B = 0 case
 * of the exact Langevin step, sb_langevin_coef_init). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <smolbridge/langevin.h>
#include <smolbridge/pgd.h>
#include "common/internal.h"
#include "pgd_internal.h"

int sbi_parts_push(sbi_parts *a, const sb_pgd_particle *q)
{
  if (a->n == a->cap) {
    size_t cap = a->cap ? 2 * a->cap : 1024;
    sb_pgd_particle *nq = realloc(a->q, cap * sizeof *nq);
    if (!nq)
      return SB_ENOMEM;
    a->q = nq;
    a->cap = cap;
  }
  a->q[a->n++] = *q;
  return SB_SUCCESS;
}

int sbi_parts_reserve(sbi_parts *a, size_t n)
{
  if (n <= a->cap)
    return SB_SUCCESS;
  size_t cap = a->cap ? a->cap : 1024;
  while (cap < n)
    cap *= 2;
  sb_pgd_particle *nq = realloc(a->q, cap * sizeof *nq);
  if (!nq)
    return SB_ENOMEM;
  a->q = nq;
  a->cap = cap;
  return SB_SUCCESS;
}

void sbi_parts_free(sbi_parts *a)
{
  free(a->q);
  memset(a, 0, sizeof *a);
}

/* Decay e^{-h/tau} and position gain tau (1 - e^{-h/tau}) of a step h. */
void sbi_lag_coef(const sb_pgd_params *p, double h, double *e, double *g)
{
  sb_langevin_coef c;
  if (isinf(p->tau) || sb_langevin_coef_init(&c, p->tau, 0.0, h)) {
    *e = 1.0;
    *g = h;
    return;
  }
  *e = c.decay;
  *g = c.gain;
}

/* The gas velocity that drags q over a move: frozen at its start
 * position; 0 without drag. */
static void drag_gas(const sb_pgd_params *p, const sb_pgd_particle *q,
                     double ug[2])
{
  ug[0] = ug[1] = 0.0;
  if (p->gas && !isinf(p->tau)) {
    sbi_pgd_gas_at(p, q->x[0], q->x[1], ug);
  } else if (!isinf(p->tau)) {
    ug[0] = p->ugas[0];
    ug[1] = p->ugas[1];
  }
}

int sbi_lag_rel_ok(const sb_pgd_params *p, const sb_pgd_particle *q)
{
  double ug[2];
  drag_gas(p, q, ug);
  return isfinite(q->v[0] - ug[0]) && isfinite(q->v[1] - ug[1]);
}

size_t sbi_lag_rel_first_bad(const sb_pgd_params *p,
                             const sb_pgd_particle *q, size_t n)
{
  size_t k = 0;
  while (k < n && sbi_lag_rel_ok(p, q + k))
    k++;
  return k;
}

int sbi_lag_rel_error(const sb_pgd_params *p, const sb_pgd_particle *q,
                      const char *func)
{
  double ug[2];
  drag_gas(p, q, ug);
  return sbi_error(SB_ERANGE, func, "particle at (%g, %g): its velocity "
                   "(%g, %g) relative to the gas (%g, %g) leaves the double "
                   "range", q->x[0], q->x[1], q->v[0], q->v[1], ug[0], ug[1]);
}

void sbi_lag_move_coef(const sb_pgd_params *p, sb_pgd_particle *q, double h,
                       double e, double gain)
{
  double ug[2];
  drag_gas(p, q, ug);
  for (int d = 0; d < 2; d++) {
    double dv = q->v[d] - ug[d];
    q->x[d] += ug[d] * h + dv * gain;
    q->v[d] = ug[d] + dv * e;
  }
}

void sbi_lag_move_all(const sb_pgd_params *p, sb_pgd_particle *q, size_t n,
                      double h, double e, double gain)
{
  for (size_t k = 0; k < n; k++)
    sbi_lag_move_coef(p, q + k, h, e, gain);
}

int sbi_lag_inject(const sb_pgd_params *p, int dir, double xn, double s0,
                   double len, double M, const double P[2], double dt,
                   sbi_parts *out, const char *func)
{
  if (!(M > 0))
    return SB_SUCCESS;
  const size_t nt = p->inject_time, ns = p->inject_face;
  sb_pgd_particle q;
  q.w = M / (double)(nt * ns);
  for (size_t kt = 0; kt < nt; kt++) {
    /* entered at t + (1 - th) dt: moves over th dt before the step ends */
    double th = ((double)kt + 0.5) / (double)nt, e, g;
    sbi_lag_coef(p, th * dt, &e, &g);
    for (size_t ks = 0; ks < ns; ks++) {
      q.x[dir] = xn;
      q.x[1 - dir] = s0 + ((double)ks + 0.5) / (double)ns * len;
      q.v[0] = P[0] / M;
      q.v[1] = P[1] / M;
      if (!sbi_lag_rel_ok(p, &q))
        return sbi_lag_rel_error(p, &q, func);
      sbi_lag_move_coef(p, &q, th * dt, e, g);
      if (sbi_parts_push(out, &q))
        return SB_ENOMEM;
    }
  }
  return SB_SUCCESS;
}

int sbi_lag_place(const sb_pgd_params *p, sb_pgd_particle *q)
{
  for (int d = 0; d < 2; d++) {
    double lo = p->origin[d], L = p->L[d], x = q->x[d];
    if (x >= lo && x < lo + L)
      continue;
    if (p->bc[2 * d] != SB_PGD_PERIODIC)
      return 1 + 2 * d + (x >= lo + L);
    x = fmod(x - lo, L);
    if (x < 0)
      x += L;
    if (!(x < L))  /* fmod round-off */
      x = 0.0;
    q->x[d] = lo + x;
  }
  return 0;
}

double sbi_lag_speed(const sb_pgd_params *p, const sb_pgd_particle *q,
                     size_t n)
{
  const double ix = (double)p->nx / p->L[0], iy = (double)p->ny / p->L[1];
  double s = 0;
  for (size_t k = 0; k < n; k++) {
    double v = fabs(q[k].v[0]) * ix + fabs(q[k].v[1]) * iy;
    if (v > s)
      s = v;
  }
  return s;
}

/* ------------------------------------------------------------ public */

sb_pgd_lag *sb_pgd_lag_alloc(const sb_pgd_params *p)
{
  if (sb_pgd_params_check(p)) {
    sbi_error(SB_EINVAL, __func__, "%s", sb_last_error());
    return NULL;
  }
  if (p->dim != 2) {
    sbi_error(SB_EINVAL, __func__, "particles need dim = 2");
    return NULL;
  }
  sb_pgd_lag *l = calloc(1, sizeof *l);
  if (!l) {
    sbi_error(SB_ENOMEM, __func__, "out of memory");
    return NULL;
  }
  l->p = *p;
  sbi_locator_init(&l->loc, p);
  l->pspeed = sbi_pgd_param_speed(p);
  return l;
}

void sb_pgd_lag_free(sb_pgd_lag *l)
{
  if (!l)
    return;
  sbi_parts_free(&l->a);
  sbi_parts_free(&l->fresh);
  free(l);
}

int sb_pgd_lag_add(sb_pgd_lag *l, const sb_pgd_particle *q)
{
  if (!l || !q)
    return sbi_error(SB_EINVAL, __func__, "NULL argument");
  if (!(q->w >= 0) || !isfinite(q->w) || !isfinite(q->x[0]) ||
      !isfinite(q->x[1]) || !isfinite(q->v[0]) || !isfinite(q->v[1]))
    return sbi_error(SB_EDOM, __func__, "weight must be >= 0, position and "
                     "velocity finite");
  sb_pgd_particle c = *q;
  if (sbi_lag_place(&l->p, &c))
    return sbi_error(SB_EDOM, __func__, "particle at (%g, %g) outside the "
                     "domain", q->x[0], q->x[1]);
  if (sbi_parts_push(&l->a, &c))
    return sbi_error(SB_ENOMEM, __func__, "out of memory");
  return SB_SUCCESS;
}

size_t sb_pgd_lag_count(const sb_pgd_lag *l) { return l ? l->a.n : 0; }

const sb_pgd_particle *sb_pgd_lag_particles(const sb_pgd_lag *l)
{
  return l ? l->a.q : NULL;
}

double sb_pgd_lag_time(const sb_pgd_lag *l) { return l ? l->t : NAN; }

double sb_pgd_lag_dt(const sb_pgd_lag *l)
{
  if (!l)
    return NAN;
  double s = sbi_lag_speed(&l->p, l->a.q, l->a.n);
  return sbi_pgd_dt_from_speed(&l->p, fmax(s, l->pspeed));
}

/* Inject the inflow of every inflow face of p over a step dt: SB_ENOMEM
 * (no message), SB_ERANGE (message named after func). */
static int inject_inflows(const sb_pgd_params *p, double dt, sbi_parts *out,
                          sbi_budget *bud, const char *func)
{
  const double dx = p->L[0] / (double)p->nx, dy = p->L[1] / (double)p->ny;
  for (size_t m = 0; m < p->ninflow; m++) {
    const sb_pgd_inflow *in = &p->inflow[m];
    int dir = in->side >= SB_PGD_SOUTH;
    double sgn = in->side == SB_PGD_WEST || in->side == SB_PGD_SOUTH ? 1 : -1;
    double un = sgn * in->u[dir];
    double len = dir ? dx : dy;
    double xn = p->origin[dir] + (sgn > 0 ? 0.0 : p->L[dir]);
    if (!(un > 0) || !(in->rho > 0))
      continue;
    for (size_t k = in->first; k < in->first + in->count; k++) {
      double M = in->rho * un * len * dt;
      double P[2] = {M * in->u[0], M * in->u[1]};
      double s0 = p->origin[1 - dir] + (double)k * len;
      const int st = sbi_lag_inject(p, dir, xn, s0, len, M, P, dt, out,
                                    func);
      if (st)
        return st;
      sbi_budget_add(bud, in->side, 0, M, P[0], P[1]);
    }
  }
  return SB_SUCCESS;
}

int sb_pgd_lag_step(sb_pgd_lag *l, double dt)
{
  if (!l)
    return sbi_error(SB_EINVAL, __func__, "NULL particles");
  if (!(dt > 0) || !isfinite(dt))
    return sbi_error(SB_EINVAL, __func__, "dt = %g: must be > 0", dt);
  if (l->gas_missing)
    return sbi_error(SB_EINVAL, __func__, "the checkpoint these particles "
                     "were loaded from had a gas velocity callback: attach "
                     "it again with sb_pgd_lag_set_gas");
  /* everything that can fail comes first, so that a refused step
   * changes nothing: the inflow's particles (they do not depend on the
   * others) and its budget go to the side, every relative velocity is
   * checked, and there is room for the particles after the move */
  sbi_budget bud = l->bud;
  l->fresh.n = 0;
  int st = inject_inflows(&l->p, dt, &l->fresh, &bud, __func__);
  if (!st && sbi_parts_reserve(&l->a, l->a.n + l->fresh.n))
    st = SB_ENOMEM;
  if (st == SB_ENOMEM)
    return sbi_error(SB_ENOMEM, __func__, "out of memory");
  if (st)
    return st;
  const size_t bad = sbi_lag_rel_first_bad(&l->p, l->a.q, l->a.n);
  if (bad < l->a.n)
    return sbi_lag_rel_error(&l->p, &l->a.q[bad], __func__);
  double e, g;
  sbi_lag_coef(&l->p, dt, &e, &g);
  sbi_lag_move_all(&l->p, l->a.q, l->a.n, dt, e, g);
  for (size_t k = 0; k < l->fresh.n; k++)
    l->a.q[l->a.n++] = l->fresh.q[k];  /* room reserved */
  l->bud = bud;
  /* remove the particles that left; keep the order of the others */
  size_t w = 0;
  for (size_t k = 0; k < l->a.n; k++) {
    sb_pgd_particle *q = &l->a.q[k];
    int side = sbi_lag_place(&l->p, q);
    if (side) {
      sbi_budget_add(&l->bud, side - 1, 1, q->w, q->w * q->v[0],
                     q->w * q->v[1]);
      continue;
    }
    l->a.q[w++] = *q;
  }
  l->a.n = w;
  l->t += dt;
  l->steps++;
  return SB_SUCCESS;
}

int sb_pgd_lag_advance(sb_pgd_lag *l, double t_end, size_t *nsteps)
{
  if (!l)
    return sbi_error(SB_EINVAL, __func__, "NULL particles");
  if (!(t_end >= l->t) || !isfinite(t_end))
    return sbi_error(SB_EINVAL, __func__, "t_end = %g before t = %g", t_end,
                     l->t);
  size_t k = 0;
  while (l->t < t_end) {
    double dt = sb_pgd_lag_dt(l), left = t_end - l->t;
    int last = dt >= left * (1 - 1e-12);
    if (last)
      dt = left;
    int st = sb_pgd_lag_step(l, dt);
    if (st)
      return st;
    k++;
    if (last)
      l->t = t_end;
  }
  if (nsteps)
    *nsteps = k;
  return SB_SUCCESS;
}

int sb_pgd_lag_deposit(const sb_pgd_lag *l, double *rho, double *qx,
                       double *qy)
{
  if (!l)
    return sbi_error(SB_EINVAL, __func__, "NULL particles");
  const sb_pgd_params *p = &l->p;
  size_t n = p->nx * p->ny;
  double iA = (double)p->nx * (double)p->ny / (p->L[0] * p->L[1]);
  if (rho)
    memset(rho, 0, n * sizeof *rho);
  if (qx)
    memset(qx, 0, n * sizeof *qx);
  if (qy)
    memset(qy, 0, n * sizeof *qy);
  for (size_t k = 0; k < l->a.n; k++) {
    const sb_pgd_particle *q = &l->a.q[k];
    size_t c = sbi_locate1(&l->loc, 0, q->x[0]) +
               p->nx * sbi_locate1(&l->loc, 1, q->x[1]);
    if (rho)
      rho[c] += q->w * iA;
    if (qx)
      qx[c] += q->w * q->v[0] * iA;
    if (qy)
      qy[c] += q->w * q->v[1] * iA;
  }
  return SB_SUCCESS;
}

void sb_pgd_lag_totals(const sb_pgd_lag *l, double tot[3])
{
  tot[0] = tot[1] = tot[2] = 0;
  for (size_t k = 0; k < l->a.n; k++) {
    tot[0] += l->a.q[k].w;
    tot[1] += l->a.q[k].w * l->a.q[k].v[0];
    tot[2] += l->a.q[k].w * l->a.q[k].v[1];
  }
}

void sb_pgd_lag_boundary_totals(const sb_pgd_lag *l, double in[3],
                                double out[3])
{
  sbi_budget_get(&l->bud, -1, in, out);
}

void sb_pgd_lag_side_totals(const sb_pgd_lag *l, sb_pgd_side s, double in[3],
                            double out[3])
{
  sbi_budget_get(&l->bud, (int)s & 3, in, out);
}
