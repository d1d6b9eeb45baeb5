/* collide.h — a collision-engine run described by an INI configuration,
 * as `smolbridge collide` runs it: read the configuration (a file or a
 * string), override keys, check it, build the engine, run it and write
 * the outputs (series.csv, summary.json, snapshots, sizes.csv, hits.csv,
 * grid.csv, exits.csv, batches.csv, contacts.csv, msd.csv, manifest.txt)
 * into the directory `[run] output`.  Every key with its
 * unit and default: docs/engine.md §9; this API: docs/engine.md §9,
 * "From C".
 *
 *   sb_collide *c = sb_collide_alloc();
 *   if (sb_collide_read_file(c, "run.ini") ||
 *       sb_collide_set(c, "run.dt=1e-7") || sb_collide_run(c, NULL, NULL))
 *     fprintf(stderr, "%s\n", sb_collide_error(c));
 *   sb_collide_free(c);
 *
 * The library prints nothing: messages are read with sb_collide_error
 * and sb_collide_warning, progress reaches a callback.  An object is used
 * by one thread at a time; distinct objects are independent.  The first
 * error sticks: every later call on the object returns it again. */
#ifndef SB_COLLIDE_H
#define SB_COLLIDE_H

#include <stddef.h>

#include <smolbridge/common.h>
#include <smolbridge/engine.h>
#include <smolbridge/engine_firsthit.h>

#ifdef __cplusplus
extern "C" {
#endif

/** A run description (opaque): the configuration, then the engine built
 *  from it and the run's results. */
typedef struct sb_collide sb_collide;

/** Kind of the first failure.  The values are the exit status of
 *  `smolbridge collide` (SB_COLLIDE_EWRITE exits with 1). */
typedef enum {
  SB_COLLIDE_OK = 0,      /**< no failure */
  SB_COLLIDE_ERUN = 1,    /**< a step failed (or the progress callback
                               stopped the run); the outputs say why */
  SB_COLLIDE_EINPUT = 2,  /**< the configuration: syntax, unknown key,
                               bad value, conflicting keys, a set-up that
                               cannot be built, nothing to measure, an
                               output directory that cannot be prepared */
  SB_COLLIDE_EWRITE = 3   /**< the run completed but its outputs or its
                               checkpoint could not be written */
} sb_collide_failure;

/** Allocate an empty configuration (every key at its default).  NULL
 *  when out of memory. */
sb_collide *sb_collide_alloc(void);
void sb_collide_free(sb_collide *c);

/** Read an INI file: [section] headers, `key = value` lines, comments
 *  starting a line with ';' or '#' or following a value after " ;".
 *  SB_SUCCESS, or SB_EINVAL with the message "PATH:LINE: ..." naming the
 *  section, key and value at fault and the valid values (an unreadable
 *  file: "PATH: cannot read: ...").  Reading a second file or string
 *  adds its keys; a key given twice is an error, and so is an unknown
 *  section header, also one without keys under it. */
int sb_collide_read_file(sb_collide *c, const char *path);

/** Read an INI configuration from the string `text` (as
 *  sb_collide_read_file); `name` stands for the file name in the
 *  messages ("NAME:LINE: ..."; "string" if NULL). */
int sb_collide_read_string(sb_collide *c, const char *text,
                           const char *name);

/** Override or add one key, as `--set`: "SECTION.KEY=VALUE", with
 *  "species.NAME.KEY=VALUE" for [species NAME] (the section must exist
 *  when species were read).  Messages start with "--set
 *  SECTION.KEY=VALUE: "; summary.json lists the overrides.  SB_SUCCESS
 *  or SB_EINVAL. */
int sb_collide_set(sb_collide *c, const char *assignment);

/** Cross-key checks once all keys are in: required keys, conflicting
 *  keys, keys that need other values, a [species NAME] header without
 *  keys ("PATH:LINE: [species NAME] has no keys: ..."; it would add no
 *  species); keys that have no effect give warnings
 *  (sb_collide_warning).  SB_SUCCESS or SB_EINVAL.  Called by
 *  sb_collide_setup when not called before. */
int sb_collide_check(sb_collide *c);

/** Build the engine, its species and particles (placement) and the
 *  detector, outcome and observer contexts (after sb_collide_check, which
 *  it calls if needed).  Input errors found only now (a particle larger
 *  than the box, a box too full for random placement; on restart without
 *  [fluid] type, what depends on the checkpoint's fluid field and
 *  Lees-Edwards images, e.g. [observe] msd_every or [walls] in x or y
 *  against the images, with the messages of a new run, and the warnings
 *  about it; on restart, what depends on the checkpoint's dim: the
 *  number of values of [fluid] U and g and of the inflows' keys; ...;
 *  also running out of memory, with its message) return SB_EINVAL.  On
 *  restart the engine's capacity is that of the run in one go, to the
 *  particle (with [run] steps counted from the checkpoint's steps, not
 *  its summed time).  Called by sb_collide_run when not called before. */
int sb_collide_setup(sb_collide *c);

/** Events of a run (sb_collide_progress.event). */
typedef enum {
  SB_COLLIDE_BEGIN = 0,  /**< set up, output directory prepared; before
                              the first step */
  SB_COLLIDE_STEP = 1    /**< after a step, about every tenth of a stretch
                              and at its end (stretches: the warm-up, then
                              the measurement, cut at every snapshot) */
} sb_collide_event;

/** What the progress callback receives. */
typedef struct {
  sb_collide_event event;
  double t;                      /**< engine time now, s */
  double t_begin;                /**< start time (0, or the restart
                                      checkpoint's), s */
  double t_measure;              /**< end of the warm-up, s */
  double t_end;                  /**< end time, s */
  double dt;                     /**< time step, s */
  double fraction;               /**< of the current stretch done, 0..1 */
  size_t particles;              /**< particles (clusters) now */
  unsigned long long collisions; /**< collisions counted since the start
                                      (since the warm-up's end after it) */
  long long first_contacts;      /**< [observe] first_hit: first contacts
                                      counted after the warm-up's end (the
                                      kernel's count); -1 without it */
} sb_collide_progress;

/** Progress callback: return 0 to go on, nonzero to stop the run (it
 *  then fails with SB_COLLIDE_ERUN and writes its outputs with status
 *  "failed"). */
typedef int (*sb_collide_progress_fn)(const sb_collide_progress *p,
                                      void *user);

/** Run: set up if needed, check that something is measured (the warm-up
 *  ends before t_end), prepare the output directory (create it, remove
 *  the files of an earlier run listed in its manifest.txt, check that it
 *  and the checkpoint path are writable), run to t_end with the warm-up,
 *  time series and snapshots, write the outputs and the checkpoint.  `fn`
 *  (may be NULL) receives progress events with `user`.  SB_SUCCESS, or a
 *  status with sb_collide_failed() telling the kind: SB_EINVAL for input
 *  errors, the engine's status for a failed step, SB_EIO for outputs that
 *  could not be written.  A configuration runs once. */
int sb_collide_run(sb_collide *c, sb_collide_progress_fn fn, void *user);

/** Kind of the first failure (SB_COLLIDE_OK if none). */
sb_collide_failure sb_collide_failed(const sb_collide *c);

/** The failure's message ("" if none): for input errors "WHERE: ..."
 *  with WHERE the file and line ("run.ini:12") or the override ("--set
 *  run.dt=-1"); a failed run gives one line per problem ("step failed at
 *  t = ... s: ...", then "could not write the outputs in DIR/" or
 *  "checkpoint: ..."), separated by '\n'.  Valid until the next call on
 *  c. */
const char *sb_collide_error(const sb_collide *c);

/** Warnings so far (keys without effect, collision events dropped by a
 *  run), in order; each "WHERE: ..." without a trailing newline.
 *  sb_collide_warning returns NULL for i >= sb_collide_nwarnings(c). */
size_t sb_collide_nwarnings(const sb_collide *c);
const char *sb_collide_warning(const sb_collide *c, size_t i);

/** The output directory (`[run] output`, default "collide-out"). */
const char *sb_collide_output(const sb_collide *c);
/** The checkpoint path (`[run] checkpoint`), "" without one. */
const char *sb_collide_checkpoint(const sb_collide *c);

/** The engine of the run, after sb_collide_setup (NULL before): its
 *  parameters, counts, kernel estimate (sb_engine_kernel) and statistics
 *  after the run. */
const sb_engine *sb_collide_engine(const sb_collide *c);

/** The agglomeration context (outcome = merge | dlvo), else NULL. */
const sb_agglo *sb_collide_agglo(const sb_collide *c);

/** 1 if the run counts first contacts (`[observe] first_hit = yes`,
 *  after sb_collide_setup), else 0. */
int sb_collide_has_firsthit(const sb_collide *c);

/** Name of species k (NAME of its [species NAME] section, in the order
 *  of the sections), NULL for k out of range; valid while c lives. */
const char *sb_collide_species_name(const sb_collide *c, size_t k);

/** First-contact kernel of `[observe] first_hit = yes` (95% interval,
 *  the reference radius of the configuration) in *o: the status of
 *  sb_engine_firsthit_kernel (the counts are set even when it fails; K
 *  is NaN when there is no estimate, as in free flight); SB_EINVAL
 *  without that observer.  With several species there is one kernel per
 *  species pair (sb_collide_firsthit_pair): *o then has the counts over
 *  all pairs, K, its interval, radius and D NaN, and the status is
 *  SB_EDOM. */
int sb_collide_firsthit(const sb_collide *c,
                        sb_engine_firsthit_kernel_result *o);

/** First-contact kernel of species pair (a, b) (indices in the order of
 *  the [species NAME] sections, either order): reference radius the
 *  contact distance r_a + r_b (or first_hit_radius with one species, or
 *  the capacitance radius with first_hit_capacitance), relative
 *  diffusivity D_a + D_b = (b2_a + b2_b)/2, 95% interval.  Status as
 *  sb_collide_firsthit; SB_EINVAL for a species index out of range or
 *  without the observer.  Pair (0, 0) of one species is
 *  sb_collide_firsthit. */
int sb_collide_firsthit_pair(const sb_collide *c, size_t a, size_t b,
                             sb_engine_firsthit_kernel_result *o);

/** One key of the configuration, for help texts. */
typedef struct {
  const char *section;  /**< "run", "bridge", ..., "species" (for
                             [species NAME]) */
  const char *key;
  const char *unit;     /**< "-" when it has none */
  const char *def;      /**< the default, in words */
  const char *help;     /**< what it sets */
  char valid[200];      /**< valid values, as the messages give them */
} sb_collide_keyinfo;

/** Number of keys; sb_collide_key fills *k for key i in the table's
 *  order (grouped by section), SB_EINVAL for i >= sb_collide_nkeys(). */
size_t sb_collide_nkeys(void);
int sb_collide_key(size_t i, sb_collide_keyinfo *k);

#ifdef __cplusplus
}
#endif

#endif /* SB_COLLIDE_H */
