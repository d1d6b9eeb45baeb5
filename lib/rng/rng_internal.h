/* rng_internal.h — private to lib/rng: the Philox block function, the
 * counter layout and the ziggurat tables (rng_zigtab.c, written by
 * gen_zigtab.py). */
#ifndef SB_RNG_INTERNAL_H
#define SB_RNG_INTERNAL_H

#include <stdint.h>

#include <Random123/philox.h>
#include <smolbridge/rng.h>

/* Counter word 3: step bits 32-47 (low 16), id bits 32-46 (bits 16-30),
 * bit 31 the domain (0: sb_stream, 1: the gsl_rng sequence). */
#define SBI_DOMAIN_GSL UINT32_C(0x80000000)

static inline void sbi_philox_block(const uint32_t ctr[4],
                                    const uint32_t key[2], uint32_t out[4])
{
  philox4x32_ctr_t c = {{ctr[0], ctr[1], ctr[2], ctr[3]}};
  philox4x32_key_t k = {{key[0], key[1]}};
  philox4x32_ctr_t r = philox4x32_R(10, c, k);
  out[0] = r.v[0];
  out[1] = r.v[1];
  out[2] = r.v[2];
  out[3] = r.v[3];
}

static inline void sbi_stream_set(sb_stream *s, uint64_t seed, uint64_t id,
                                  uint64_t step)
{
  s->key[0] = (uint32_t)seed;
  s->key[1] = (uint32_t)(seed >> 32);
  s->ctr[0] = 0;
  s->ctr[1] = (uint32_t)step;
  s->ctr[2] = (uint32_t)id;
  s->ctr[3] = (uint32_t)((step >> 32) & 0xffffu) |
              (uint32_t)(((id >> 32) & 0x7fffu) << 16);
  s->pos = 4;
}

/* the next word; the block counter is ctr[0] (wraps after 2^32 blocks) */
static inline uint32_t sbi_stream_u32(sb_stream *s)
{
  if (s->pos >= 4) {
    sbi_philox_block(s->ctr, s->key, s->buf);
    s->ctr[0]++;
    s->pos = 0;
  }
  return s->buf[s->pos++];
}

/* ziggurat tables (rng_zigtab.c) */
extern const double sbi_zig_r, sbi_zig_v;
extern const double sbi_zig_w[128];
extern const uint32_t sbi_zig_k[128];
extern const double sbi_zig_f[129];

#endif /* SB_RNG_INTERNAL_H */
