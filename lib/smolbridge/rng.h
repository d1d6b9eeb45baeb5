/* smolbridge/rng.h — counter-based random streams (Philox4x32-10).
 *
 * A counter-based generator is a keyed bijection: the output for a
 * counter c and key k is philox(c, k), with no state carried from one
 * draw to the next (Salmon, Moraes, Dror & Shaw 2011, "Parallel random
 * numbers: as easy as 1, 2, 3", Proc. SC'11, §2-§4).  smolbridge uses the
 * Philox4x32-10 bijection of Random123 (128-bit counter, 64-bit key,
 * 10 rounds; passes TestU01's BigCrush with every key, Salmon et al.
 * 2011, Table 2) to give each (seed, particle, step) its own stream:
 *
 *   key      = the 64-bit seed
 *   counter  = (block, step bits 0-31, id bits 0-31,
 *               step bits 32-47 | id bits 32-46 << 16 | 0 << 31)
 *
 * so the numbers drawn for particle `id` at step `step` are a function of
 * (seed, id, step) alone: the same on any number of threads or MPI ranks,
 * in any order of the particles, with no shared state.  Distinct (seed,
 * id, step) triples are distinct (key, counter) pairs, hence disjoint
 * blocks of one bijection (for one key) or of independently keyed
 * bijections (different seeds); a stream holds 2^32 blocks of four 32-bit
 * words (2^34 words) before its block counter wraps.
 *
 * Two interfaces:
 *  - sb_stream, a small value (40 bytes) that the caller owns: one per
 *    thread or per particle; it is thread-safe as long as one stream is
 *    not shared between threads without a lock.  sb_stream_gaussian uses
 *    the ziggurat method (Marsaglia & Tsang 2000, J. Stat. Softw. 5(8),
 *    128 layers, 32 random bits per fast-path draw: the same 24-bit
 *    resolution within a layer as gsl_ran_gaussian_ziggurat) with exact
 *    wedge and tail tests; sb_stream_uniform returns (2k + 1)/2^53 with k
 *    uniform on [0, 2^52): 53-bit resolution, never 0 or 1.
 *  - sb_rng_philox, a gsl_rng_type, so that every function taking a
 *    gsl_rng can draw from Philox: gsl_rng_set(r, seed) starts the
 *    generator's own sequence (counter domain bit 31 of word 3 set, a
 *    127-bit block counter: no overlap with any sb_stream, period 2^129
 *    words), and sb_rng_philox_set_stream(r, seed, id, step) points it at
 *    the stream of (seed, id, step) (the same words as sb_stream_u32).
 *
 * GSL's generators (MT19937 by default) stay the generators of the
 * reference functions; the counter-based stream is an option for
 * per-particle randomness (docs/rng.md).
 */
#ifndef SMOLBRIDGE_RNG_H
#define SMOLBRIDGE_RNG_H

#include <stddef.h>
#include <stdint.h>

#include <gsl/gsl_rng.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Largest particle id of a stream: 2^47 - 1. */
#define SB_STREAM_MAX_ID ((UINT64_C(1) << 47) - 1)
/** Largest step of a stream: 2^48 - 1. */
#define SB_STREAM_MAX_STEP ((UINT64_C(1) << 48) - 1)

/** The Philox4x32-10 bijection (Salmon et al. 2011, §4.2): out =
 *  philox(ctr, key), Random123's philox4x32_R(10, ctr, key). */
void sb_philox4x32_10(const uint32_t ctr[4], const uint32_t key[2],
                      uint32_t out[4]);

/** A counter-based stream: key, counter, and the current block's words.
 *  Treat the fields as private; copy it freely (a copy continues the same
 *  sequence independently). */
typedef struct {
  uint32_t key[2];  /**< seed, low word first */
  uint32_t ctr[4];  /**< next block's counter (layout above) */
  uint32_t buf[4];  /**< the current block's output */
  uint32_t pos;     /**< words of buf already used (4: none left) */
} sb_stream;

/** Start the stream of (seed, id, step) at its first word.
 *  Domain: id <= SB_STREAM_MAX_ID, step <= SB_STREAM_MAX_STEP; else
 *  SB_EDOM (and the stream is set to (seed, 0, 0)).  SB_EINVAL if s is
 *  NULL. */
int sb_stream_init(sb_stream *s, uint64_t seed, uint64_t id, uint64_t step);

/** Next 32-bit word, uniform on [0, 2^32).  A NULL s returns 0 and sets
 *  SB_EINVAL (sb_last_error()); 0 is also a valid word, so a caller that
 *  may pass NULL checks the pointer itself. */
uint32_t sb_stream_u32(sb_stream *s);

/** Uniform on (0, 1): (2k + 1)/2^53, k uniform on [0, 2^52), from two
 *  words.  A NULL s returns NaN (never a valid draw) and sets SB_EINVAL. */
double sb_stream_uniform(sb_stream *s);

/** Standard normal N(0, 1), ziggurat (one word on the fast path, 98.8%
 *  of draws; more words and two uniforms otherwise).  A NULL s returns
 *  NaN and sets SB_EINVAL. */
double sb_stream_gaussian(sb_stream *s);

/** n uniforms (as sb_stream_uniform) / n standard normals (as
 *  sb_stream_gaussian), the same values as n single calls.  SB_EINVAL for
 *  a NULL pointer with n > 0. */
int sb_stream_uniform_fill(sb_stream *s, size_t n, double *u);
int sb_stream_gaussian_fill(sb_stream *s, size_t n, double *z);

/** Keyed batch: for j = 0..n-1, the first m normals of the stream
 *  (seed, id_j, step) into z[j m .. j m + m - 1], id_j = ids[j] (or
 *  id0 + j when ids is NULL).  Exactly what sb_stream_init and
 *  sb_stream_gaussian_fill give particle by particle, so any split of the
 *  particles over threads or calls gives the same numbers.  Domain as
 *  sb_stream_init (checked for every id first: SB_EDOM and nothing
 *  written). */
int sb_stream_gaussian_keyed(uint64_t seed, uint64_t step, size_t n,
                             const uint64_t *ids, uint64_t id0, size_t m,
                             double *z);

/** Philox4x32-10 as a GSL generator: 32-bit words, range [0, 2^32 - 1];
 *  gsl_rng_set(r, seed) uses all 64 bits of an unsigned long seed. */
extern const gsl_rng_type *const sb_rng_philox;

/** Point a generator of type sb_rng_philox at the stream of (seed, id,
 *  step): its next words are those of sb_stream_init(s, seed, id, step)
 *  followed by sb_stream_u32.  SB_EINVAL if r is NULL or not of type
 *  sb_rng_philox; SB_EDOM as sb_stream_init (the message names this
 *  function). */
int sb_rng_philox_set_stream(gsl_rng *r, uint64_t seed, uint64_t id,
                             uint64_t step);

#ifdef __cplusplus
}
#endif

#endif /* SMOLBRIDGE_RNG_H */
