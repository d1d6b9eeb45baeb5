/* engine_agglo_state.h — the state of an agglomeration context
 * (engine_merge.c merges and counts, engine_agglo_io.c saves and
 * restores). */
#ifndef SBI_ENGINE_AGGLO_STATE_H
#define SBI_ENGINE_AGGLO_STATE_H

#include <stdint.h>

#include <smolbridge/engine.h>

struct sb_agglo {
  sb_agglo_params par;
  sb_engine_species prim;    /* the primary species (copied at attach) */
  size_t *sp_of_k;           /* [k]: species of size k, SIZE_MAX if none */
  size_t ncap_k;             /* entries in sp_of_k */
  size_t *k_of_sp;           /* [species]: size, 0 if not a cluster */
  size_t ncap_sp;
  sb_agglo_stats st;
  double *rows;              /* time series, ncols per row */
  size_t nrows, caprows;
  /* restored by sb_agglo_load: the next attach checks that the engine is
   * at the saved step with the saved particles */
  int restored;
  uint64_t saved_steps, saved_print;
};

/* Size k is species sp (either table grown as needed); SB_ENOMEM with a
 * message from who, the public function entered. */
int sbi_agglo_set_map(sb_agglo *a, size_t k, size_t sp, const char *who);
/* The engine e is the one a restored state was saved with: at its step,
 * with its particles, and every saved cluster species of the mass of its
 * size (engine_agglo_io.c).  SB_EINVAL with a message otherwise. */
int sbi_agglo_check_restored(sb_agglo *a, const sb_engine *e);

#endif
