/* engine_firsthit_state.h — the state of a first-contact observer
 * (engine_firsthit.c counts, engine_firsthit_io.c saves and restores). */
#ifndef SBI_ENGINE_FIRSTHIT_STATE_H
#define SBI_ENGINE_FIRSTHIT_STATE_H

#include <stdint.h>

#include <smolbridge/engine_firsthit.h>

#include "engine_internal.h"

/* species pairs of the table (a <= b) */
#define NPT (SB_ENGINE_PAIR_SPECIES * (SB_ENGINE_PAIR_SPECIES + 1) / 2)

struct sb_engine_firsthit {
  sb_engine_firsthit_params par;
  int attached;
  /* restored by sb_engine_firsthit_load: attach keeps the counts and
   * checks that the engine is at the saved step */
  int restored;
  uint64_t saved_steps, saved_print;
  sbi_idmap set;       /* pair keys of the pairs seen */
  double t1;       /* end of the warm-up, s */
  uint64_t hits[NPT], warm[NPT], contact0[NPT];
  double pairs_apart[NPT];
  uint64_t hits_all, warm_all, contact0_all;
  double pairs_apart_all;
  /* each particle's counted contacts with each partner species (slot
   * SB_ENGINE_PAIR_SPECIES: with any), key (id << 5 | slot) + 1, and
   * per species pair the sums of their squares over the first species'
   * side [0] and the second's [1] (one side for a species with itself) */
  sbi_idmap counts;
  double sq[NPT][2], sq_all;
  double ns[SB_ENGINE_PAIR_SPECIES], n_all;  /* particles at attachment */
};

#endif
