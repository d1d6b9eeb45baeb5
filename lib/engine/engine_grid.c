/* engine_grid.c — the particles' mass and momentum densities on a regular
 * grid of the box (an Eulerian view of the engine: comparison with the
 * pressureless-gas solver, lib/pgd, and density maps).
 *
 * Cells are cell-centred over [0, L_k): cell i of direction k covers
 * [i h_k, (i + 1) h_k), h_k = L_k / n_k.  Two assignment schemes
 * (Hockney & Eastwood 1988, ch. 5):
 *  - NGP (nearest grid point): a particle's whole mass goes to the cell
 *    that holds its centre;
 *  - CIC (cloud in cell): the particle is a uniform cube of one cell
 *    edge, shared among the 2^dim cells it overlaps with weights linear
 *    in the distance to their centres (a linear field is reproduced
 *    exactly at the cell centres away from walls).
 * Along a periodic direction the share beyond the box wraps round; along
 * a walled or open one it is folded back into the edge cell, so that both
 * schemes conserve the mass and momentum of the deposited particles to
 * rounding.  Densities are per cell volume h_x h_y h_z (3-D) or per cell
 * area h_x h_y (2-D: kg/m^2, kg/(m s)).
 */
#include <math.h>
#include <string.h>

#include "common/internal.h"
#include "engine_internal.h"

/* Cell index and CIC weights along one direction: the particle at
 * coordinate x (in [0, L)) touches cells c0 and c0 + 1 (wrapped or
 * folded), with weights w0 and 1 - w0. */
static void cic_1d(double x, double h, size_t n, int periodic, size_t *c0,
                   size_t *c1, double *w0)
{
  double s = x / h - 0.5;  /* in cell-centre units */
  double f = floor(s);
  double frac = s - f;
  long i0 = (long)f, i1 = i0 + 1, nn = (long)n;
  if (periodic) {
    i0 = ((i0 % nn) + nn) % nn;
    i1 = ((i1 % nn) + nn) % nn;
  } else {
    if (i0 < 0)
      i0 = 0;
    if (i1 > nn - 1)
      i1 = nn - 1;
    if (i0 > nn - 1)
      i0 = nn - 1;
    if (i1 < 0)
      i1 = 0;
  }
  *c0 = (size_t)i0;
  *c1 = (size_t)i1;
  *w0 = 1.0 - frac;
}

static size_t ngp_1d(double x, double h, size_t n)
{
  double s = floor(x / h);
  if (s < 0.0)
    return 0;
  return s >= (double)n ? n - 1 : (size_t)s;
}

int sb_engine_grid_fields(const sb_engine *e, const size_t n[3],
                          sb_engine_grid_scheme scheme, int family,
                          double *rho, double *mom)
{
  if (!e || !n || !rho) {
    sbi_error(SB_EINVAL, __func__, "NULL argument");
    return SB_EINVAL;
  }
  const int dim = e->par.dim;
  size_t nn[3] = {n[0], n[1], dim == 3 ? n[2] : 1};
  for (int k = 0; k < dim; k++)
    if (nn[k] == 0 || nn[k] > ((size_t)1 << 24)) {
      sbi_error(SB_EINVAL, __func__, "grid size n[%d] = %zu (1 to 2^24)",
                k, nn[k]);
      return SB_EINVAL;
    }
  if (scheme != SB_GRID_NGP && scheme != SB_GRID_CIC) {
    sbi_error(SB_EINVAL, __func__, "unknown scheme %d", (int)scheme);
    return SB_EINVAL;
  }
  if (family < -1) {
    sbi_error(SB_EINVAL, __func__, "family %d (>= 0, or -1 for all)",
              family);
    return SB_EINVAL;
  }
  /* the cells of the three components of mom must be countable */
  if ((double)nn[0] * (double)nn[1] * (double)nn[2] * 3.0 * sizeof(double) >
      (double)SIZE_MAX) {
    sbi_error(SB_EINVAL, __func__, "grid %zu x %zu x %zu: too many cells",
              nn[0], nn[1], nn[2]);
    return SB_EINVAL;
  }
  const size_t ncell = nn[0] * nn[1] * nn[2];
  memset(rho, 0, ncell * sizeof *rho);
  if (mom)
    memset(mom, 0, 3 * ncell * sizeof *mom);
  double h[3] = {1.0, 1.0, 1.0}, vcell = 1.0;
  int per[3] = {1, 1, 1};
  for (int k = 0; k < dim; k++) {
    h[k] = e->par.L[k] / (double)nn[k];
    vcell *= h[k];
    per[k] = sb_engine_periodic(e, k);
  }
  const double inv = 1.0 / vcell;
  for (size_t p = 0; p < e->n; p++) {
    if (family >= 0 && e->family[p] != family)
      continue;
    const double *x = &e->x[3 * p], *u = &e->u[3 * p];
    const double m = e->mass[p] * inv;
    size_t c[3][2] = {{0, 0}, {0, 0}, {0, 0}};
    double w[3][2] = {{1, 0}, {1, 0}, {1, 0}};
    int two = scheme == SB_GRID_CIC;
    for (int k = 0; k < dim; k++) {
      if (two) {
        cic_1d(x[k], h[k], nn[k], per[k], &c[k][0], &c[k][1], &w[k][0]);
        w[k][1] = 1.0 - w[k][0];
      } else {
        c[k][0] = ngp_1d(x[k], h[k], nn[k]);
      }
    }
    const int nb = two ? 2 : 1, nbz = two && dim == 3 ? 2 : 1;
    for (int a = 0; a < nb; a++)
      for (int b = 0; b < nb; b++)
        for (int cz = 0; cz < nbz; cz++) {
          double wt = w[0][a] * w[1][b] * w[2][cz];
          size_t idx = c[0][a] + nn[0] * (c[1][b] + nn[1] * c[2][cz]);
          rho[idx] += m * wt;
          if (mom)
            for (int k = 0; k < 3; k++)
              mom[3 * idx + k] += m * wt * u[k];
        }
  }
  return SB_SUCCESS;
}
