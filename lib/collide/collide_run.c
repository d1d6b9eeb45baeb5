/* collide_run.c — sb_collide_run: the warm-up, the measurement cut at
 * the snapshots, the time series, then the outputs (collide_out.c) and
 * the checkpoint.  Progress goes to the caller's callback about every
 * tenth of each stretch; failures are recorded in the run description
 * (collide.c) with the message `smolbridge collide` prints. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <smolbridge/engine.h>
#include <smolbridge/engine_bridge.h>
#include <smolbridge/engine_firsthit.h>

#include "collide_internal.h"

/* The run's progress reporting. */
typedef struct {
  sb_collide_progress_fn fn;
  void *user;
  sb_collide_progress p;   /* times fixed at the start */
  const sb_engine_firsthit *fh;  /* [observe] first_hit, or NULL */
} reporter;

/* Tell the callback; nonzero: it asks to stop. */
static int report(reporter *rp, const sb_engine *e, sb_collide_event ev,
                  double frac)
{
  if (!rp->fn)
    return 0;
  sb_engine_stats s;
  sb_engine_get_stats(e, &s);
  rp->p.event = ev;
  rp->p.t = sb_engine_time(e);
  rp->p.fraction = frac;
  rp->p.particles = sb_engine_count(e);
  rp->p.collisions = (unsigned long long)s.ncoll;
  sb_engine_firsthit_counts fc;
  rp->p.first_contacts =
      rp->fh && !sb_engine_firsthit_get(rp->fh, SB_ENGINE_FIRSTHIT_ALL,
                                        SB_ENGINE_FIRSTHIT_ALL, &fc)
          ? (long long)fc.hits
          : -1;
  return rp->fn(&rp->p, rp->user);
}

/* Step to t_stop, sampling the pair kernels and cluster sizes with the
 * series; progress about every tenth of the stretch and at its end.
 * SB_EINVAL with *stopped set when the callback stops the run. */
static int progress_step(sbi_col_run *r, double t_stop, sbi_col_pairs *ps,
                         reporter *rp, int *stopped)
{
  sb_engine *e = r->e;
  const double dt = sb_engine_get_params(e)->dt, t0 = sb_engine_time(e);
  double last = -1;
  while (sb_engine_time(e) < t_stop - 0.5 * dt) {
    int st = sb_engine_step(e);
    sbi_col_contacts_step_end(r);
    if (!st && r->measuring) {
      st = sbi_col_msd_step(r);
      sbi_col_batches_step(r);
    }
    if (st)
      return st;
    size_t every = sb_engine_get_params(e)->sample_every;
    if (every) {
      sb_engine_stats s0;
      sb_engine_get_stats(e, &s0);
      if (s0.steps % every == 0) {
        if (ps && sbi_col_pairs_sample(ps, e))
          return SB_ENOMEM;
        /* deposits: the measured part only (counters reset after the
         * warm-up) */
        if (ps && r->dep_on && (st = sbi_col_walls_sample(r)))
          return st;
        if (r->agglo && (st = sb_agglo_sample(r->agglo, e)))
          return st;
      }
    }
    double frac = (sb_engine_time(e) - t0) / (t_stop - t0);
    if (frac - last >= 0.1 || frac >= 1.0 - 1e-12) {
      /* the rows written so far reach the disk at every progress point:
       * a killed run keeps them */
      if (r->exits_f)
        fflush(r->exits_f);
      if (r->grid_f)
        fflush(r->grid_f);
      if (report(rp, e, SB_COLLIDE_STEP, frac)) {
        *stopped = 1;
        return SB_EINVAL;
      }
      last = frac;
    }
  }
  return SB_SUCCESS;
}

/* At a stop ([run] stop_every): a row of sizes.csv, and the bridge reach of
 * the current particle count and largest radius (merging lowers the one
 * and raises the other; sb_engine_bridge_attach sets the reach once). */
static int at_stop(const sbi_col_config *c, sbi_col_run *r)
{
  sb_engine *e = r->e;
  int st = sbi_col_grid_sample(c, r);
  if (!st && r->bridge && !r->fh) {  /* first-hit wraps the detector */
    double reach = sb_engine_bridge_reach(e, r->bridge);
    if (!(reach >= 0.0))
      return sb_last_status();
    st = sb_engine_set_detector(e, sb_engine_detect_bridge, r->bridge,
                                reach);
  }
  if (!st && r->agglo) {
    size_t nr, nc;
    const double *rows = sb_agglo_series(r->agglo, &nr, &nc);
    if (!(nr > 0 && rows[(nr - 1) * nc] == sb_engine_time(e)))
      st = sb_agglo_sample(r->agglo, e);
  }
  return st;
}

/* The warm-up, then the measurement cut at the snapshots.  The status of
 * the first failing step. */
static int run_steps(sbi_col_config *c, sbi_col_run *r, sbi_col_pairs *ps,
                     reporter *rp, long *nsnap, int *stopped)
{
  sb_engine *e = r->e;
  const double dt = sb_engine_get_params(e)->dt;
  const double t0 = sb_engine_time(e);
  int st = SB_SUCCESS;
  if (r->warm > 0) {
    st = progress_step(r, t0 + r->warm, NULL, rp, stopped);
    sb_engine_reset_counters(e);
    if (!st)
      st = sbi_col_exits_reset(r);  /* as the outflow counters */
    if (r->bridge)
      sb_engine_bridge_reset(r->bridge);
    if (r->agglo)
      sb_agglo_reset_stats(r->agglo);
  }
  r->measuring = 1;
  sbi_col_batches_start(r);
  if (!r->ekin0_saved)  /* a restart keeps the first run's */
    r->ekin0 = sb_engine_kinetic_energy(e, NULL);
  if (!st)
    st = sbi_col_msd_start(c, r);
  char path[1100];
  int isnap = 0;  /* [run] snapshot_steps: the next one */
  /* [run] stop_every: stop k at t_meas + k stop_every */
  const double t_meas = t0 + r->warm;
  long istop = 1;
  while (!st && sb_engine_time(e) < r->t_end - 0.5 * dt) {
    /* snapshot_steps reached */
    while (!st && isnap < c->nsnap_steps &&
           !(sb_engine_time(e) <
             t_meas + (c->snap_steps[isnap] - 0.5) * dt)) {
      sbi_col_snap_path(c, *nsnap, path, sizeof path);
      st = sb_engine_snapshot_csv(e, path);
      isnap++;
      if (!st)
        (*nsnap)++;
    }
    if (st)
      break;
    double t_next = r->t_end;
    if (isnap < c->nsnap_steps &&
        t_meas + c->snap_steps[isnap] * dt < t_next)
      t_next = t_meas + c->snap_steps[isnap] * dt;
    if (c->snapshot_every > 0) {
      double ts = sb_engine_time(e) + (double)c->snapshot_every * dt;
      if (ts < t_next)
        t_next = ts;
    }
    const double t_stop = t_meas + (double)istop * c->stop_every;
    if (c->stop_every > 0 && t_stop < t_next)
      t_next = t_stop;
    st = progress_step(r, t_next, ps, rp, stopped);
    /* a stop is reached as sb_engine_run_until reaches its end time */
    if (!st && c->stop_every > 0 && t_stop < r->t_end + 0.5 * dt &&
        !(sb_engine_time(e) < t_stop - 0.5 * dt)) {
      st = at_stop(c, r);
      istop++;
    }
    if (!st && c->snapshot_every > 0) {
      sbi_col_snap_path(c, *nsnap, path, sizeof path);
      st = sb_engine_snapshot_csv(e, path);
      if (!st)
        (*nsnap)++;
    }
  }
  /* snapshot_steps reached by the last step */
  while (!st && isnap < c->nsnap_steps &&
         !(sb_engine_time(e) < t_meas + (c->snap_steps[isnap] - 0.5) * dt)) {
    sbi_col_snap_path(c, *nsnap, path, sizeof path);
    st = sb_engine_snapshot_csv(e, path);
    isnap++;
    if (!st)
      (*nsnap)++;
  }
  if (!st)  /* the last grid frame at the end time */
    st = sbi_col_grid_sample(c, r);
  if (!st && r->agglo) {  /* the last size row at the end time */
    size_t nr, nc;
    const double *rows = sb_agglo_series(r->agglo, &nr, &nc);
    if (!(nr > 0 && rows[(nr - 1) * nc] == sb_engine_time(e)))
      st = sb_agglo_sample(r->agglo, e);
  }
  return st;
}

/* End time, warm-up and sampling period; SB_EINVAL when the warm-up does
 * not end before the end time. */
static int plan(sb_collide *cl)
{
  sbi_col_config *c = &cl->c;
  sbi_col_run *r = &cl->r;
  sb_engine *e = r->e;
  const double dt = sb_engine_get_params(e)->dt;
  const double t0 = sb_engine_time(e);
  /* t_end is the absolute end time (warm-up inside it); steps counts the
   * measured steps after the warm-up */
  r->warm = c->restart[0] ? 0.0 : c->warmup;
  r->t_end = !isnan(c->t_end) ? c->t_end
                              : t0 + r->warm + (double)c->steps * dt;
  if (!(r->t_end - t0 - r->warm >= 0.5 * dt)) {
    sbi_col_fail(c, "%s: nothing to measure: the warm-up (%g s) does not "
                 "end before t_end (%g s from t = %g s)",
                 sbi_col_given(c, "run", "warmup")
                     ? sbi_col_where(c, "run", "warmup")
                     : sbi_col_where(c, "run", "t_end"),
                 r->warm, r->t_end - t0, t0);
    return SB_EINVAL;
  }
  if (c->nsnap_steps > 0) {
    const double last = c->snap_steps[c->nsnap_steps - 1];
    const double nmeas = (r->t_end - t0 - r->warm) / dt;
    if (last > nmeas + 0.5) {
      sbi_col_fail(c, "%s: [run] snapshot_steps = ... %.0f: the run "
                   "measures %.0f steps; valid: at most that",
                   sbi_col_where(c, "run", "snapshot_steps"), last,
                   floor(nmeas + 0.5));
      return SB_EINVAL;
    }
  }
  if (c->stop_every > 0 && !(c->stop_every >= dt)) {
    sbi_col_fail(c, "%s: [run] stop_every = %g s: shorter than the step "
                 "(dt = %g s); valid: >= dt",
                 sbi_col_where(c, "run", "stop_every"), c->stop_every, dt);
    return SB_EINVAL;
  }
  const long nmeas = lround((r->t_end - t0 - r->warm) / dt);
  if (sbi_col_batches_setup(c, r, nmeas))
    return SB_EINVAL;
  /* the msd samples (collide_msd.c): the fit's lags must fit the run */
  if (c->msd_every > 0 && c->nmsd_fit == 2) {
    const long cap = (nmeas > 0 ? nmeas : 0) / c->msd_every + 1;
    if (!(c->msd_fit[1] < (double)cap)) {
      sbi_col_fail(c, "%s: [observe] msd_fit = %g %g: the run takes %ld "
                   "samples of msd_every = %ld steps (lags 0 .. %ld); "
                   "valid: lags below %ld",
                   sbi_col_where(c, "observe", "msd_fit"), c->msd_fit[0],
                   c->msd_fit[1], cap, c->msd_every, cap - 1, cap);
      return SB_EINVAL;
    }
  }
  /* ~200 samples over the run; a restart keeps the checkpoint's period,
   * so that its rows fall where those of the run in one go would */
  long nst = lround((r->t_end - t0) / dt);
  if (c->sample_every > 0)
    sb_engine_set_sample_every(e, (size_t)c->sample_every);
  else if (!c->restart[0])
    sb_engine_set_sample_every(e, (size_t)(nst / 200 > 0 ? nst / 200 : 1));
  return SB_SUCCESS;
}

/* Wall-clock seconds (C11 timespec_get). */
static double wall_now(void)
{
  struct timespec ts;
  return timespec_get(&ts, TIME_UTC) == TIME_UTC
             ? (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec
             : NAN;
}

int sb_collide_run(sb_collide *cl, sb_collide_progress_fn fn, void *user)
{
  int st = sb_collide_setup(cl);
  if (st)
    return st;
  if (cl->ran)
    return sbi_col_failure(cl, SB_COLLIDE_EINPUT, SB_EINVAL,
                           "sb_collide_run: a configuration runs once; "
                           "allocate another");
  cl->ran = 1;
  sbi_col_config *c = &cl->c;
  sbi_col_run *r = &cl->r;
  sb_engine *e = r->e;
  if (plan(cl) || sbi_col_out_prepare(c))
    return sbi_col_failure(cl, SB_COLLIDE_EINPUT, SB_EINVAL, c->err);
  const double t0 = sb_engine_time(e);
  if (!c->restart[0])  /* on restart the saved warm-up end stays */
    sbi_col_firsthit_start(r, t0 + r->warm);
  reporter rp = {fn, user, {SB_COLLIDE_BEGIN, t0, t0, t0 + r->warm,
                            r->t_end, sb_engine_get_params(e)->dt, 0.0, 0,
                            0, -1}, r->fh};
  int stopped = 0;
  if (report(&rp, e, SB_COLLIDE_BEGIN, 0.0))
    stopped = 1, st = SB_EINVAL;
  /* per-pair columns for 2 to 4 species (clusters: sizes.csv) */
  double cpu0 = (double)clock() / CLOCKS_PER_SEC, wall0 = wall_now();
  long nsnap = 0;
  if (!st)
    st = run_steps(c, r, &r->pairs, &rp, &nsnap, &stopped);
  const double secs[2] = {wall_now() - wall0,
                          (double)clock() / CLOCKS_PER_SEC - cpu0};
  if (st) {
    char why[600];
    if (stopped)
      snprintf(why, sizeof why, "stopped by the progress callback at t = "
               "%g s", sb_engine_time(e));
    else
      snprintf(why, sizeof why, "step failed at t = %g s: %s",
               sb_engine_time(e), sb_last_error());
    sbi_col_failure(cl, SB_COLLIDE_ERUN, st, why);
    if (sbi_col_out_write(c, r, &r->pairs, secs, "failed", why, nsnap))
      sbi_col_more(cl, "could not write the outputs in %s/", c->output);
    return st;
  }
  if (sbi_col_out_write(c, r, &r->pairs, secs, "ok", NULL, nsnap)) {
    sbi_col_failure(cl, SB_COLLIDE_EWRITE, SB_EIO, "");
    sbi_col_more(cl, "could not write the outputs in %s/", c->output);
  }
  if (c->checkpoint[0] && (sb_engine_checkpoint_save(e, c->checkpoint) ||
                           sbi_col_save_beside(c, r))) {
    if (!cl->failed)
      sbi_col_failure(cl, SB_COLLIDE_EWRITE, SB_EIO, "");
    sbi_col_more(cl, "checkpoint: %s", sb_last_error());
  }
  sb_engine_stats fs;
  sb_engine_get_stats(e, &fs);
  if (fs.dropped)  /* after summary.json: its warnings are the input's */
    sbi_col_warn(c, "%llu collision events were dropped (the custom "
                 "detector does not re-examine pairs after an outcome "
                 "within a step); the kernel is low by about that many "
                 "collisions of %llu: shorten dt",
                 (unsigned long long)fs.dropped,
                 (unsigned long long)fs.ncoll);
  return cl->failed ? cl->status : SB_SUCCESS;
}
