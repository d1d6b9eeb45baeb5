/* collide_msd.c — [observe] msd_every: the mean-square displacement of
 * the particles (unwrapped through the periodic boundaries) against the
 * lag, averaged over time origins and particles, and the self-diffusion
 * coefficient from its slope (Einstein 1905; Allen & Tildesley 2017,
 * §8.2, eq 8.12):
 *   D = [MSD(k2 ts) - MSD(k1 ts)] / (2 dim (k2 - k1) ts),
 * ts = msd_every dt the sampling interval, lags k1 < k2 ([observe]
 * msd_fit, in samples) past the velocity relaxation.  Positions are
 * unwrapped at every measured step by the minimum image of the step's
 * displacement (displacements per step stay below half the box).  The
 * particle set must not change (no merging, no open boundaries). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <smolbridge/engine.h>
#include "common/internal.h"

#include "collide_internal.h"

struct sbi_col_msd {
  size_t n, dim, every, nsamp, cap, k1, k2;
  unsigned long long steps;  /* measured steps so far */
  double L[3], dt;
  double *xw;     /* wrapped positions at the last step (3n) */
  double *xu;     /* unwrapped positions (3n) */
  double *traj;   /* unwrapped positions at the samples (3n per sample) */
  double *msd;    /* MSD(k), k < nsamp, after sbi_col_msd_finish */
};

void sbi_col_msd_free(sbi_col_msd *m)
{
  if (!m)
    return;
  free(m->xw);
  free(m->xu);
  free(m->traj);
  free(m->msd);
  free(m);
}

int sbi_col_msd_check(sbi_col_config *c)
{
  const char *w = sbi_col_where(c, "observe", "msd_every");
  if (c->msd_every <= 0) {
    if (sbi_col_given(c, "observe", "msd_fit"))
      sbi_col_warn(c, "%s: [observe] msd_fit ignored: msd_every = 0 (no "
                   "mean-square displacement)",
                   sbi_col_where(c, "observe", "msd_fit"));
    return 0;
  }
  if (c->nmsd_fit == 2 &&
      !(c->msd_fit[0] == floor(c->msd_fit[0]) &&
        c->msd_fit[1] == floor(c->msd_fit[1]) && c->msd_fit[0] < c->msd_fit[1]))
    return sbi_col_fail(c, "%s: [observe] msd_fit = %g %g: valid: two whole "
                        "lags k1 < k2, in samples of msd_every steps",
                        sbi_col_where(c, "observe", "msd_fit"), c->msd_fit[0],
                        c->msd_fit[1]);
  if (c->sort_every > 0)
    return sbi_col_fail(c, "%s: [observe] msd_every with [run] sort_every = "
                        "%ld: sorting moves the particles in memory; valid: "
                        "sort_every = 0", w, c->sort_every);
  if (sbi_col_agglo(c) || !strcmp(c->outcome, "reinsert"))
    return sbi_col_fail(c, "%s: [observe] msd_every with outcome = %s: "
                        "the particles that collide %s; valid outcomes: "
                        "elastic, count, correction", w, c->outcome,
                        sbi_col_agglo(c) ? "merge" : "jump elsewhere");
  if (sbi_col_msd_lees_check(c))
    return -1;
  for (int k = 0; k < c->nsp; k++)
    if (c->sp[k].inflow[0])
      return sbi_col_fail(c, "%s: [observe] msd_every with [%s] inflow: the "
                          "particle set changes; valid: no inflow", w,
                          c->sp[k].name);
  /* on restart the walls are the checkpoint's where the file gives none:
   * sbi_col_dim_check, once they are read */
  return c->restart[0] ? 0 : sbi_col_msd_walls_check(c);
}

/* The faces of the run's box, 2 dim of them (a 2-D box has no z faces;
 * their keys are warned as ignored, sbi_col_dim_check): an absorbing face
 * removes or reinserts the particles it touches, an open one lets them
 * out.  The deposition outcome acts at absorbing faces only
 * (engine_wall.c), so reflecting faces keep the particles whatever
 * [walls] deposit says. */
int sbi_col_msd_walls_check(sbi_col_config *c)
{
  static const char *const FACE[6] = {"x_lo", "x_hi", "y_lo", "y_hi",
                                      "z_lo", "z_hi"};
  if (c->msd_every <= 0)
    return 0;
  for (int f = 0; f < 2 * c->dim; f++) {
    if (strcmp(c->wall[f], "absorb") && strcmp(c->wall[f], "open"))
      continue;
    /* a direction the file does not give keeps the checkpoint's walls
     * (restart_box in collide_setup.c) */
    const int kept = c->restart[0] &&
                     !sbi_col_given(c, "walls", FACE[f & ~1]) &&
                     !sbi_col_given(c, "walls", FACE[f | 1]);
    const char *w = sbi_col_where(c, "observe", "msd_every");
    if (kept)
      return sbi_col_fail(c, "%s: [observe] msd_every with the restart "
                          "checkpoint's [walls] %s = %s: particles leave or "
                          "jump; valid walls: periodic, reflect: give [walls] "
                          "%s and %s one of them", w, FACE[f], c->wall[f],
                          FACE[f & ~1], FACE[f | 1]);
    return sbi_col_fail(c, "%s: [observe] msd_every with [walls] %s = %s: "
                        "particles leave or jump; valid walls: periodic, "
                        "reflect", w, FACE[f], c->wall[f]);
  }
  return 0;
}

/* The Lees-Edwards images: a particle crossing y = 0 or L_y is shifted
 * along x by the moving offset, which the minimum image of a step's
 * displacement does not undo.  On restart without [fluid] type the field
 * and the images are the checkpoint's: collide_setup.c calls this again
 * once they are known. */
int sbi_col_msd_lees_check(sbi_col_config *c)
{
  if (c->msd_every <= 0 || strcmp(c->fluid, "shear") || !c->lees)
    return 0;
  const int kept = c->restart[0] && !sbi_col_given(c, "fluid", "type");
  return sbi_col_fail(c, "%s: [observe] msd_every with Lees-Edwards images "
                      "(%s): an image crossing shifts x by a moving offset; "
                      "give [fluid] lees_edwards = no",
                      sbi_col_where(c, "observe", "msd_every"),
                      kept ? "the restart checkpoint's [fluid] type = shear"
                           : "[fluid] type = shear");
}

static int take_sample(sbi_col_msd *m)
{
  if (m->nsamp >= m->cap)
    return SB_SUCCESS;  /* the run's last partial interval */
  memcpy(m->traj + 3 * m->n * m->nsamp, m->xu, 3 * m->n * sizeof *m->xu);
  m->nsamp++;
  return SB_SUCCESS;
}

int sbi_col_msd_start(const sbi_col_config *c, sbi_col_run *r)
{
  if (c->msd_every <= 0)
    return SB_SUCCESS;
  sbi_col_msd *m = calloc(1, sizeof *m);
  if (!m)
    return SB_ENOMEM;
  const sb_engine_params *p = sb_engine_get_params(r->e);
  m->n = sb_engine_count(r->e);
  m->dim = (size_t)p->dim;
  m->every = (size_t)c->msd_every;
  m->dt = p->dt;
  for (int k = 0; k < 3; k++)
    m->L[k] = p->L[k];
  long nst = lround((r->t_end - sb_engine_time(r->e)) / m->dt);
  m->cap = (size_t)(nst > 0 ? nst : 0) / m->every + 1;
  m->xw = malloc(3 * m->n * sizeof *m->xw);
  m->xu = calloc(3 * m->n, sizeof *m->xu);
  m->traj = malloc(3 * m->n * m->cap * sizeof *m->traj);
  r->msd = m;
  if (!m->xw || !m->xu || !m->traj)
    return SB_ENOMEM;
  memcpy(m->xw, sb_engine_positions(r->e), 3 * m->n * sizeof *m->xw);
  if (c->nmsd_fit == 2 && !((size_t)c->msd_fit[1] < m->cap))
    return sbi_error(SB_EINVAL, "[observe] msd_fit", "lag %g samples: the "
                     "run takes %zu samples (lags 0 .. %zu); valid: lags "
                     "below that", c->msd_fit[1], m->cap, m->cap - 1);
  return take_sample(m);
}

int sbi_col_msd_step(sbi_col_run *r)
{
  sbi_col_msd *m = r->msd;
  if (!m)
    return SB_SUCCESS;
  if (sb_engine_count(r->e) != m->n)
    return sbi_error(SB_EINVAL, "[observe] msd_every", "the particle "
                     "number changed from %zu to %zu: the mean-square "
                     "displacement follows a fixed set of particles",
                     m->n, sb_engine_count(r->e));
  const double *x = sb_engine_positions(r->e);
  /* minimum image of each step's displacement (2-D: z stays 0) */
  for (size_t k = 0; k < 3 * m->n; k++) {
    double dx = x[k] - m->xw[k], L = m->L[k % 3];
    dx -= L * nearbyint(dx / L);
    m->xu[k] += dx;
    m->xw[k] = x[k];
  }
  m->steps++;
  return m->steps % m->every == 0 ? take_sample(m) : SB_SUCCESS;
}

/* MSD(k) averaged over the origins s (s + k < nsamp) and the particles:
 * the sum in the order of sample, then coordinate. */
static double msd_lag(const sbi_col_msd *m, size_t lag)
{
  double sum = 0.0;
  size_t cnt = 0;
  for (size_t s = 0; s + lag < m->nsamp; s++) {
    const double *a = m->traj + 3 * m->n * s;
    const double *b = m->traj + 3 * m->n * (s + lag);
    for (size_t k = 0; k < 3 * m->n; k++)
      sum += (b[k] - a[k]) * (b[k] - a[k]);
    cnt += m->n;
  }
  return cnt ? sum / (double)cnt : NAN;
}

/* The fit lags: msd_fit, or a quarter and a half of the longest lag. */
static void fit_lags(const sbi_col_config *c, const sbi_col_msd *m,
                     size_t *k1, size_t *k2)
{
  if (c->nmsd_fit == 2) {
    *k1 = (size_t)c->msd_fit[0];
    *k2 = (size_t)c->msd_fit[1];
  } else {
    size_t kmax = m->nsamp ? m->nsamp - 1 : 0;
    *k1 = kmax / 4;
    *k2 = kmax / 2 > *k1 ? kmax / 2 : *k1 + 1;
  }
}

int sbi_col_msd_write(FILE *js, const sbi_col_config *c,
                      const sbi_col_run *r, const char *path)
{
  const sbi_col_msd *m = r->msd;
  if (!m)
    return 0;
  const double ts = (double)m->every * m->dt;
  size_t k1, k2;
  fit_lags(c, m, &k1, &k2);
  FILE *f = fopen(path, "w");
  if (!f)
    return -1;
  fprintf(f, "lag,t,msd,origins\n");
  double m1 = NAN, m2 = NAN;
  for (size_t k = 0; k < m->nsamp; k++) {
    double v = msd_lag(m, k);
    if (k == k1)
      m1 = v;
    if (k == k2)
      m2 = v;
    fprintf(f, "%zu,%.17g,%.17g,%zu\n", k, (double)k * ts, v,
            m->nsamp - k);
  }
  double D = k2 < m->nsamp && k1 < k2
                 ? (m2 - m1) / (2.0 * (double)m->dim * (double)(k2 - k1) * ts)
                 : NAN;
  fprintf(js, "  \"msd\": {\"every\": %zu, \"interval\": %.17g, "
          "\"samples\": %zu, \"particles\": %zu, \"fit\": [%zu, %zu], "
          "\"D\": ", m->every, ts, m->nsamp, m->n, k1, k2);
  sbi_col_jnum(js, D);
  fprintf(js, ", \"file\": \"msd.csv\"},\n");
  return fclose(f) ? -1 : 0;
}
