/* engine_bridge_state.h — the state of a bridge detector (engine_bridge.c
 * detects and counts, engine_bridge_io.c saves and restores). */
#ifndef SBI_ENGINE_BRIDGE_STATE_H
#define SBI_ENGINE_BRIDGE_STATE_H

#include <stdint.h>

#include <smolbridge/engine_bridge.h>

struct sb_engine_bridge {
  sb_engine_bridge_params par;
  size_t nb2;               /* entries in b2/b2b/b2set */
  double *b2, *b2b;         /* per-species overrides */
  unsigned char *b2set;
  sb_engine_bridge_stats st;
  sb_engine_bridge_hit *hits;
  size_t nhits;
  /* restored by sb_engine_bridge_load: the next attach checks that the
   * engine is at the saved step with the saved particles */
  int restored;
  uint64_t saved_steps, saved_print;
};

#endif
