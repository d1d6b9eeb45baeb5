/* pgd_checkpoint.c — save and restore the Eulerian solver (sb_pgd), the
 * Lagrangian particles (sb_pgd_lag) and a one-part domain decomposition
 * (sb_pgd_dd) so that a restored run continues bit for bit as the run
 * that was not stopped.
 *
 * Format (little-endian on every machine, common/byteorder.c, in the
 * style of the engine's checkpoint, engine_checkpoint.c): the 8-byte
 * magic "SBPGDE01" (solver), "SBPGDL01" (particles) or "SBPGDD01"
 * (decomposition), three bytes with the sizes of double, size_t and int
 * of the build that wrote it, the parameters field by field in
 * fixed-width types (int32 for enums and flags, uint64 for counts), then
 * the state, then the FNV-1a hash of every byte before it
 * (common/internal.h, sbi_hsave_finish), checked before anything is read:
 * a file that was cut, changed or is in big-endian order (an older
 * build's on a big-endian machine) is refused with a message saying
 * which.
 *
 *   parameters: dim, nx, ny, L[2], origin[2], scheme, cfl, dt_max, tau,
 *     ugas[2], gas (1 if a callback was set), its fingerprint
 *     (sbi_pgd_gas_print), bc[4], ninflow and each inflow (side, first,
 *     count, rho, u[2]), rho_floor, inject_time, inject_face;
 *   solver: t, steps, the cached speed bound and its flag, the vacuum
 *     flag, the boundary budget (in and out, 4 sides x 3), the number of
 *     padded cells and the padded rho, rho ux, rho uy (ghosts included);
 *   particles: t, steps, the budget, the number of particles and each
 *     (w, x[2], v[2]);
 *   decomposition: px, py, the kinds (px py bytes), t, steps, the
 *     budget, then per block an Eulerian block's solver state (as above)
 *     and its pending fluxes towards Lagrangian neighbours, or a
 *     Lagrangian block's particles (as above).
 *
 * The gas callback (a function pointer) cannot be saved: a solver or
 * particles loaded from a checkpoint saved with one refuse to step until
 * the caller attaches a callback with the same velocities at the cell
 * centres again (sb_pgd_set_gas, sb_pgd_lag_set_gas). */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <smolbridge/pgd.h>
#include "common/internal.h"
#include "pgd_internal.h"
#include "pgd_dd_internal.h"

static const char MAGIC_E[8] = {'S', 'B', 'P', 'G', 'D', 'E', '0', '1'};
static const char MAGIC_L[8] = {'S', 'B', 'P', 'G', 'D', 'L', '0', '1'};
static const char MAGIC_D[8] = {'S', 'B', 'P', 'G', 'D', 'D', '0', '1'};
static const unsigned char SIZES[3] = {sizeof(double), sizeof(size_t),
                                       sizeof(int)};

/* FNV-1a of one gas sample (both components) into the hash at ctx. */
static void print_visit(void *ctx, size_t i, size_t j, const double ug[2])
{
  uint64_t *h = ctx;
  (void)i, (void)j;
  *h = sbi_fnv1a(*h, ug, 2 * sizeof *ug);
}

uint64_t sbi_pgd_gas_print(const sb_pgd_params *p)
{
  if (!p->gas)
    return 0;
  uint64_t h = SBI_FNV_BASIS;
  const sbi_pgd_cells cells = sbi_pgd_grid_cells(p);
  sbi_pgd_gas_at_centres(p, &cells, print_visit, &h);
  return h;
}

/* ------------------------------------------------------------ writing */

/* A checkpoint's stream and its byte order: swap = 1 when the file's
 * (little-endian) is the reverse of this machine's (common/internal.h,
 * sbi_write_ord). */
typedef struct {
  FILE *fp;
  int swap;
} ck_file;

static int w_i32(ck_file *f, int v)
{
  const int32_t x = (int32_t)v;
  return sbi_write_ord(f->fp, &x, sizeof x, 1, f->swap);
}

static int w_u64(ck_file *f, uint64_t v)
{
  return sbi_write_ord(f->fp, &v, sizeof v, 1, f->swap);
}

static int w_dbl(ck_file *f, const double *v, size_t n)
{
  return sbi_write_ord(f->fp, v, sizeof *v, n, f->swap);
}

/* The header and parameters; gas_set and print describe the callback. */
static int write_params(ck_file *f, const char magic[8],
                        const sb_pgd_params *p, int gas_set, uint64_t print)
{
  int ok = fwrite(magic, 1, 8, f->fp) == 8 &&
           fwrite(SIZES, 1, 3, f->fp) == 3 &&
           w_i32(f, p->dim) && w_u64(f, p->nx) && w_u64(f, p->ny) &&
           w_dbl(f, p->L, 2) && w_dbl(f, p->origin, 2) &&
           w_i32(f, (int)p->scheme) && w_dbl(f, &p->cfl, 1) &&
           w_dbl(f, &p->dt_max, 1) && w_dbl(f, &p->tau, 1) &&
           w_dbl(f, p->ugas, 2) && w_i32(f, gas_set) && w_u64(f, print);
  for (int s = 0; s < 4 && ok; s++)
    ok = w_i32(f, (int)p->bc[s]);
  ok = ok && w_u64(f, p->ninflow);
  for (size_t k = 0; k < p->ninflow && ok; k++) {
    const sb_pgd_inflow *in = &p->inflow[k];
    ok = w_i32(f, (int)in->side) && w_u64(f, in->first) &&
         w_u64(f, in->count) && w_dbl(f, &in->rho, 1) && w_dbl(f, in->u, 2);
  }
  return ok && w_dbl(f, &p->rho_floor, 1) && w_u64(f, p->inject_time) &&
         w_u64(f, p->inject_face);
}

static int write_budget(ck_file *f, const sbi_budget *b)
{
  return w_dbl(f, &b->in[0][0], 12) && w_dbl(f, &b->out[0][0], 12);
}

/* The callback's flag and fingerprint of an object (a loaded one whose
 * callback is still missing keeps the checkpoint's). */
static void gas_of(const sb_pgd_params *p, int missing, uint64_t kept,
                   int *set, uint64_t *print)
{
  *set = missing || p->gas != NULL;
  *print = missing ? kept : sbi_pgd_gas_print(p);
}

/* The solver's checkpoint in the order swap (ck_file); messages from
 * func. */
static int save_solver(const sb_pgd *g, const char *path, int swap,
                       const char *func)
{
  if (!g || !path)
    return sbi_error(SB_EINVAL, func, "NULL argument");
  int set;
  uint64_t print;
  gas_of(&g->p, g->gas_missing, g->gas_print, &set, &print);
  sbi_hsave hs;
  ck_file ck = {sbi_hsave_begin(&hs, func), swap}, *f = &ck;
  if (!ck.fp)
    return SB_ENOMEM;
  const size_t n = g->sx * g->sy;
  const int ok = write_params(f, MAGIC_E, &g->p, set, print) &&
                 w_dbl(f, &g->t, 1) && w_u64(f, g->steps) &&
                 w_dbl(f, &g->speed, 1) && w_i32(f, g->speed_ok) &&
                 w_i32(f, g->empty) && write_budget(f, &g->bud) &&
                 w_u64(f, n) && w_dbl(f, g->rho, n) && w_dbl(f, g->qx, n) &&
                 w_dbl(f, g->qy, n);
  return sbi_hsave_finish_ord(&hs, ok, swap, path, func);
}

int sb_pgd_checkpoint_save(const sb_pgd *g, const char *path)
{
  return save_solver(g, path, !sbi_host_le(), __func__);
}

int sbi_pgd_checkpoint_save_ord(const sb_pgd *g, const char *path, int swap)
{
  return save_solver(g, path, swap, __func__);
}

int sb_pgd_lag_checkpoint_save(const sb_pgd_lag *l, const char *path)
{
  if (!l || !path)
    return sbi_error(SB_EINVAL, __func__, "NULL argument");
  int set;
  uint64_t print;
  gas_of(&l->p, l->gas_missing, l->gas_print, &set, &print);
  sbi_hsave hs;
  const int swap = !sbi_host_le();
  ck_file ck = {sbi_hsave_begin(&hs, __func__), swap}, *f = &ck;
  if (!ck.fp)
    return SB_ENOMEM;
  int ok = write_params(f, MAGIC_L, &l->p, set, print) &&
           w_dbl(f, &l->t, 1) && w_u64(f, l->steps) &&
           write_budget(f, &l->bud) && w_u64(f, l->a.n);
  for (size_t k = 0; k < l->a.n && ok; k++) {
    const sb_pgd_particle *q = &l->a.q[k];
    ok = w_dbl(f, &q->w, 1) && w_dbl(f, q->x, 2) && w_dbl(f, q->v, 2);
  }
  return sbi_hsave_finish_ord(&hs, ok, swap, path, __func__);
}

/* ------------------------------------------------------------ reading */

static int r_i32(ck_file *f, int *v)
{
  int32_t x;
  if (!sbi_read_ord(f->fp, &x, sizeof x, 1, f->swap))
    return 0;
  *v = (int)x;
  return 1;
}

static int r_u64(ck_file *f, uint64_t *v)
{
  return sbi_read_ord(f->fp, v, sizeof *v, 1, f->swap);
}

static int r_size(ck_file *f, size_t *v)
{
  uint64_t x;
  if (!r_u64(f, &x) || x > ((uint64_t)1 << 40))
    return 0;
  *v = (size_t)x;
  return 1;
}

static int r_dbl(ck_file *f, double *v, size_t n)
{
  return sbi_read_ord(f->fp, v, sizeof *v, n, f->swap);
}

static int read_budget(ck_file *f, sbi_budget *b)
{
  return r_dbl(f, &b->in[0][0], 12) && r_dbl(f, &b->out[0][0], 12);
}

/* After the magic: the sizes and the parameters into *p (checked), the
 * callback's flag and fingerprint.  SB_SUCCESS, else SB_EFORMAT with the
 * message from func. */
static int read_params(ck_file *f, const char *path, const char *func,
                       sb_pgd_params *p, int *gas_set, uint64_t *print)
{
  unsigned char sz[3];
  if (fread(sz, 1, 3, f->fp) != 3)
    return sbi_error(SB_EFORMAT, func, "'%s': truncated header", path);
  if (memcmp(sz, SIZES, 3))
    return sbi_error(SB_EFORMAT, func, "'%s' was written by a build with "
                     "other type sizes (double, size_t, int: %d, %d, %d "
                     "bytes; here %d, %d, %d): load it with a build like "
                     "the one that wrote it", path, sz[0], sz[1], sz[2],
                     SIZES[0], SIZES[1], SIZES[2]);
  memset(p, 0, sizeof *p);
  int dim, scheme, bc[4] = {0, 0, 0, 0};
  int ok = r_i32(f, &dim) && r_size(f, &p->nx) && r_size(f, &p->ny) &&
           r_dbl(f, p->L, 2) && r_dbl(f, p->origin, 2) &&
           r_i32(f, &scheme) && r_dbl(f, &p->cfl, 1) &&
           r_dbl(f, &p->dt_max, 1) && r_dbl(f, &p->tau, 1) &&
           r_dbl(f, p->ugas, 2) && r_i32(f, gas_set) && r_u64(f, print);
  for (int s = 0; s < 4 && ok; s++)
    ok = r_i32(f, &bc[s]);
  ok = ok && r_size(f, &p->ninflow) && p->ninflow <= SB_PGD_MAXINFLOW;
  for (size_t k = 0; k < p->ninflow && ok; k++) {
    sb_pgd_inflow *in = &p->inflow[k];
    int side;
    ok = r_i32(f, &side) && r_size(f, &in->first) && r_size(f, &in->count) &&
         r_dbl(f, &in->rho, 1) && r_dbl(f, in->u, 2) && side >= 0 &&
         side <= 3;
    in->side = ok ? (sb_pgd_side)side : SB_PGD_WEST;
  }
  ok = ok && r_dbl(f, &p->rho_floor, 1) && r_size(f, &p->inject_time) &&
       r_size(f, &p->inject_face);
  if (!ok || (scheme != SB_PGD_UPWIND && scheme != SB_PGD_MUSCL) ||
      (*gas_set != 0 && *gas_set != 1))
    return sbi_error(SB_EFORMAT, func, "'%s': not a valid pgd checkpoint "
                     "(its parameters are cut short or out of range)",
                     path);
  for (int s = 0; s < 4; s++) {
    if (bc[s] < SB_PGD_TRANSMISSIVE || bc[s] > SB_PGD_PERIODIC)
      return sbi_error(SB_EFORMAT, func, "'%s': not a valid pgd "
                       "checkpoint (boundary condition %d)", path, bc[s]);
    p->bc[s] = (sb_pgd_bc)bc[s];
  }
  p->dim = dim;
  p->scheme = (sb_pgd_scheme)scheme;
  if (sb_pgd_params_check(p))
    return sbi_error(SB_EFORMAT, func, "'%s': not a valid pgd checkpoint "
                     "(its parameters: %s)", path, sb_last_error());
  return SB_SUCCESS;
}

/* Open a checkpoint of the kind magic in the order swap: ck->fp, the
 * stream (after the magic), and its memory, or ck->fp NULL with *status
 * and the message. */
static void open_ck(ck_file *ck, const char *path, const char magic[8],
                    const char *what, char **mem, int swap,
                    const char *func, int *status)
{
  int ver;
  FILE *f = sbi_hload_open_ord(path, magic, 1, what, &ver, mem, swap, func,
                               status);
  if (f && fseek(f, 8, SEEK_SET)) {
    fclose(f);
    free(*mem);
    *mem = NULL;
    *status = sbi_error(SB_EIO, func, "cannot read '%s'", path);
    f = NULL;
  }
  ck->fp = f;
  ck->swap = swap;
}

/* The solver of a checkpoint in the order swap; messages from func. */
static sb_pgd *load_solver(const char *path, int swap, int *status,
                           const char *func)
{
  int dummy;
  if (!status)
    status = &dummy;
  char *mem = NULL;
  ck_file ck, *f = &ck;
  open_ck(&ck, path, MAGIC_E, "pgd solver checkpoint (sb_pgd)", &mem, swap,
          func, status);
  if (!ck.fp)
    return NULL;
  sb_pgd *g = NULL;
  sb_pgd_params p;
  int set;
  uint64_t print;
  *status = read_params(f, path, func, &p, &set, &print);
  if (*status)
    goto out;
  g = sb_pgd_alloc(&p);
  if (!g) {
    *status = sbi_error(sb_last_status() == SB_ENOMEM ? SB_ENOMEM
                                                       : SB_EFORMAT,
                        func, "'%s': %s", path, sb_last_error());
    goto out;
  }
  uint64_t n, steps = 0;
  int speed_ok, empty;
  const size_t want = g->sx * g->sy;
  if (!r_dbl(f, &g->t, 1) || !r_u64(f, &steps) ||
      !r_dbl(f, &g->speed, 1) || !r_i32(f, &speed_ok) || !r_i32(f, &empty) ||
      !read_budget(f, &g->bud) || !r_u64(f, &n) || n != want ||
      !r_dbl(f, g->rho, want) || !r_dbl(f, g->qx, want) ||
      !r_dbl(f, g->qy, want) || fgetc(f->fp) != EOF || !isfinite(g->t) ||
      (speed_ok != 0 && speed_ok != 1) || (empty != 0 && empty != 1)) {
    *status = sbi_error(SB_EFORMAT, func, "'%s': not a valid pgd "
                        "solver checkpoint (its state does not fit its "
                        "parameters, or data after the end)", path);
    goto out;
  }
  g->steps = (size_t)steps;
  g->speed_ok = speed_ok;
  g->empty = empty;
  g->gas_missing = set;
  g->gas_print = print;
  fclose(f->fp);
  free(mem);
  *status = SB_SUCCESS;
  return g;
out:
  sb_pgd_free(g);
  fclose(f->fp);
  free(mem);
  return NULL;
}

sb_pgd *sb_pgd_checkpoint_load(const char *path, int *status)
{
  return load_solver(path, !sbi_host_le(), status, __func__);
}

sb_pgd *sbi_pgd_checkpoint_load_ord(const char *path, int swap, int *status)
{
  return load_solver(path, swap, status, __func__);
}

sb_pgd_lag *sb_pgd_lag_checkpoint_load(const char *path, int *status)
{
  int dummy;
  if (!status)
    status = &dummy;
  char *mem = NULL;
  ck_file ck, *f = &ck;
  open_ck(&ck, path, MAGIC_L, "pgd particle checkpoint (sb_pgd_lag)", &mem,
          !sbi_host_le(), __func__, status);
  if (!ck.fp)
    return NULL;
  sb_pgd_lag *l = NULL;
  sb_pgd_params p;
  int set;
  uint64_t print, steps;
  size_t n = 0;
  *status = read_params(f, path, __func__, &p, &set, &print);
  if (*status)
    goto out;
  l = sb_pgd_lag_alloc(&p);
  if (!l) {
    *status = sbi_error(sb_last_status() == SB_ENOMEM ? SB_ENOMEM
                                                       : SB_EFORMAT,
                        __func__, "'%s': %s", path, sb_last_error());
    goto out;
  }
  int ok = r_dbl(f, &l->t, 1) && r_u64(f, &steps) &&
           read_budget(f, &l->bud) && r_size(f, &n) && isfinite(l->t);
  if (ok && n) {
    l->a.q = malloc(n * sizeof *l->a.q);
    if (!l->a.q) {
      *status = sbi_error(SB_ENOMEM, __func__, "out of memory for the %zu "
                          "particles of '%s'", n, path);
      goto out;
    }
    l->a.cap = n;
  }
  for (size_t k = 0; k < n && ok; k++) {
    sb_pgd_particle *q = &l->a.q[k];
    ok = r_dbl(f, &q->w, 1) && r_dbl(f, q->x, 2) && r_dbl(f, q->v, 2);
    l->a.n = k + 1;
  }
  if (!ok || fgetc(f->fp) != EOF) {
    *status = sbi_error(SB_EFORMAT, __func__, "'%s': not a valid pgd "
                        "particle checkpoint (cut short, or data after the "
                        "end)", path);
    goto out;
  }
  l->steps = (size_t)steps;
  l->gas_missing = set;
  l->gas_print = print;
  fclose(f->fp);
  free(mem);
  *status = SB_SUCCESS;
  return l;
out:
  sb_pgd_lag_free(l);
  fclose(f->fp);
  free(mem);
  return NULL;
}

/* ------------------------------------------------ the gas, attached again */

/* p with the callback (gas, data): SB_SUCCESS, or SB_EINVAL when the
 * object was loaded from a checkpoint whose callback gave other
 * velocities at the cell centres. */
static int check_gas(const sb_pgd_params *p, int missing, uint64_t print,
                     sb_pgd_gas_fn gas, void *data, const char *func)
{
  if (!missing)
    return SB_SUCCESS;
  sb_pgd_params q = *p;
  q.gas = gas;
  q.gas_data = data;
  if (!gas)
    return sbi_error(SB_EINVAL, func, "gas is NULL: the checkpoint was "
                     "saved with a gas velocity callback, attach it again");
  if (sbi_pgd_gas_print(&q) != print)
    return sbi_error(SB_EINVAL, func, "this gas velocity callback differs "
                     "at the cell centres from the one the checkpoint was "
                     "saved with");
  return SB_SUCCESS;
}

int sb_pgd_set_gas(sb_pgd *g, sb_pgd_gas_fn gas, void *data)
{
  if (!g)
    return sbi_error(SB_EINVAL, __func__, "NULL solver");
  const int st = check_gas(&g->p, g->gas_missing, g->gas_print, gas, data,
                           __func__);
  if (st)
    return st;
  g->p.gas = gas;
  g->p.gas_data = data;
  sbi_pgd_geometry(g, g->dx, g->dy, g->p.origin, 0, 0);
  if (!g->gas_missing)  /* the same samples as saved: the cache holds */
    g->speed_ok = 0;
  g->gas_missing = 0;
  return SB_SUCCESS;
}

int sb_pgd_lag_set_gas(sb_pgd_lag *l, sb_pgd_gas_fn gas, void *data)
{
  if (!l)
    return sbi_error(SB_EINVAL, __func__, "NULL particles");
  const int st = check_gas(&l->p, l->gas_missing, l->gas_print, gas, data,
                           __func__);
  if (st)
    return st;
  l->p.gas = gas;
  l->p.gas_data = data;
  l->pspeed = sbi_pgd_param_speed(&l->p);
  l->gas_missing = 0;
  return SB_SUCCESS;
}

const sb_pgd_params *sb_pgd_lag_get_params(const sb_pgd_lag *l)
{
  return l ? &l->p : NULL;
}

size_t sb_pgd_lag_steps(const sb_pgd_lag *l) { return l ? l->steps : 0; }

/* ------------------------------------------------ the decomposition */

/* The state of an Eulerian solver (as in sb_pgd_checkpoint_save, without
 * the parameters, which are the block's). */
static int write_grid(ck_file *f, const struct sb_pgd *g)
{
  const size_t n = g->sx * g->sy;
  return w_dbl(f, &g->t, 1) && w_u64(f, g->steps) &&
         w_dbl(f, &g->speed, 1) && w_i32(f, g->speed_ok) &&
         w_i32(f, g->empty) && write_budget(f, &g->bud) && w_u64(f, n) &&
         w_dbl(f, g->rho, n) && w_dbl(f, g->qx, n) && w_dbl(f, g->qy, n);
}

static int read_grid(ck_file *f, struct sb_pgd *g)
{
  uint64_t steps, n;
  int speed_ok, empty;
  const size_t want = g->sx * g->sy;
  if (!r_dbl(f, &g->t, 1) || !r_u64(f, &steps) || !r_dbl(f, &g->speed, 1) ||
      !r_i32(f, &speed_ok) || !r_i32(f, &empty) || !read_budget(f, &g->bud) ||
      !r_u64(f, &n) || n != want || !r_dbl(f, g->rho, want) ||
      !r_dbl(f, g->qx, want) || !r_dbl(f, g->qy, want) ||
      (speed_ok != 0 && speed_ok != 1) || (empty != 0 && empty != 1))
    return 0;
  g->steps = (size_t)steps;
  g->speed_ok = speed_ok;
  g->empty = empty;
  return 1;
}

static int write_parts(ck_file *f, const sbi_parts *a)
{
  int ok = w_u64(f, a->n);
  for (size_t k = 0; k < a->n && ok; k++) {
    const sb_pgd_particle *q = &a->q[k];
    ok = w_dbl(f, &q->w, 1) && w_dbl(f, q->x, 2) && w_dbl(f, q->v, 2);
  }
  return ok;
}

int sb_pgd_dd_checkpoint_save(const sb_pgd_dd *d, const char *path)
{
  if (!d || !path)
    return sbi_error(SB_EINVAL, __func__, "NULL argument");
  if (d->nparts > 1)
    return sbi_error(SB_EINVAL, __func__, "part %d of %d: checkpoints of a "
                     "decomposition are saved from a one-part run",
                     d->part, d->nparts);
  if (d->phase != SBI_DD_IDLE)
    return sbi_error(SB_EINVAL, __func__, "a step is under way");
  if (d->p.gas)
    return sbi_error(SB_EINVAL, __func__, "a decomposition with a gas "
                     "velocity callback cannot be saved (not done yet)");
  sbi_hsave hs;
  const int swap = !sbi_host_le();
  ck_file ck = {sbi_hsave_begin(&hs, __func__), swap}, *f = &ck;
  if (!ck.fp)
    return SB_ENOMEM;
  int ok = write_params(f, MAGIC_D, &d->p, 0, 0) && w_u64(f, d->px) &&
           w_u64(f, d->py);
  for (size_t k = 0; k < d->nblocks && ok; k++)
    ok = fwrite(&d->b[k].kind, 1, 1, f->fp) == 1;
  ok = ok && w_dbl(f, &d->t, 1) && w_u64(f, d->steps) &&
       write_budget(f, &d->bud);
  for (size_t k = 0; k < d->nblocks && ok; k++) {
    const dd_block *b = &d->b[k];
    if (b->kind == 'L') {
      ok = write_parts(f, &b->parts);
      continue;
    }
    ok = write_grid(f, b->e);
    for (int s = 0; s < 4 && ok; s++)
      if (b->pend[s])
        ok = w_dbl(f, b->pend[s], 3 * b->e->nb[s]);
  }
  return sbi_hsave_finish_ord(&hs, ok, swap, path, __func__);
}

sb_pgd_dd *sb_pgd_dd_checkpoint_load(const char *path, int *status)
{
  int dummy;
  if (!status)
    status = &dummy;
  char *mem = NULL;
  ck_file ck, *f = &ck;
  open_ck(&ck, path, MAGIC_D, "pgd decomposition checkpoint (sb_pgd_dd)",
          &mem, !sbi_host_le(), __func__, status);
  if (!ck.fp)
    return NULL;
  sb_pgd_dd *d = NULL;
  char *kinds = NULL;
  sb_pgd_params p;
  int set;
  uint64_t print, steps;
  size_t px, py;
  *status = read_params(f, path, __func__, &p, &set, &print);
  if (*status)
    goto out;
  if (!r_size(f, &px) || !r_size(f, &py) || px < 1 || py < 1 ||
      px > 4096 || py > 4096) {
    *status = sbi_error(SB_EFORMAT, __func__, "'%s': not a valid pgd "
                        "decomposition checkpoint (blocks)", path);
    goto out;
  }
  kinds = calloc(px * py + 1, 1);
  if (!kinds) {
    *status = sbi_error(SB_ENOMEM, __func__, "out of memory");
    goto out;
  }
  if (fread(kinds, 1, px * py, f->fp) != px * py) {
    *status = sbi_error(SB_EFORMAT, __func__, "'%s': not a valid pgd "
                        "decomposition checkpoint (blocks)", path);
    goto out;
  }
  d = sb_pgd_dd_alloc(&p, px, py, kinds);
  if (!d) {
    *status = sbi_error(sb_last_status() == SB_ENOMEM ? SB_ENOMEM
                                                       : SB_EFORMAT,
                        __func__, "'%s': %s", path, sb_last_error());
    goto out;
  }
  int ok = r_dbl(f, &d->t, 1) && r_u64(f, &steps) &&
           read_budget(f, &d->bud) && isfinite(d->t) && set == 0;
  for (size_t k = 0; k < d->nblocks && ok; k++) {
    dd_block *b = &d->b[k];
    if (b->kind == 'L') {
      size_t n = 0;
      ok = r_size(f, &n);
      for (size_t m = 0; m < n && ok; m++) {
        sb_pgd_particle q;
        ok = r_dbl(f, &q.w, 1) && r_dbl(f, q.x, 2) && r_dbl(f, q.v, 2);
        if (ok && sbi_parts_push(&b->parts, &q)) {
          *status = sbi_error(SB_ENOMEM, __func__, "out of memory");
          goto out;
        }
      }
      continue;
    }
    ok = read_grid(f, b->e);
    for (int s = 0; s < 4 && ok; s++)
      if (b->pend[s])
        ok = r_dbl(f, b->pend[s], 3 * b->e->nb[s]);
  }
  if (!ok || fgetc(f->fp) != EOF) {
    *status = sbi_error(SB_EFORMAT, __func__, "'%s': not a valid pgd "
                        "decomposition checkpoint (its state does not fit "
                        "its parameters, or data after the end)", path);
    goto out;
  }
  d->steps = (size_t)steps;
  free(kinds);
  fclose(f->fp);
  free(mem);
  *status = SB_SUCCESS;
  return d;
out:
  sb_pgd_dd_free(d);
  free(kinds);
  fclose(f->fp);
  free(mem);
  return NULL;
}

size_t sb_pgd_dd_steps(const sb_pgd_dd *d) { return d ? d->steps : 0; }

int sb_pgd_dd_layout(const sb_pgd_dd *d, size_t *px, size_t *py,
                     char *kinds)
{
  if (!d)
    return sbi_error(SB_EINVAL, __func__, "NULL decomposition");
  if (px)
    *px = d->px;
  if (py)
    *py = d->py;
  if (kinds) {
    for (size_t k = 0; k < d->nblocks; k++)
      kinds[k] = d->b[k].kind;
    kinds[d->nblocks] = 0;
  }
  return SB_SUCCESS;
}

const sb_pgd_params *sb_pgd_dd_get_params(const sb_pgd_dd *d)
{
  return d ? &d->p : NULL;
}
