/* rng_gsl.c — Philox4x32-10 as a gsl_rng_type (smolbridge/rng.h):
 * gsl_rng_set(r, seed) starts a sequence in the generator's own counter
 * domain (word 3 bit 31 set: disjoint from every sb_stream), with a
 * 127-bit block counter; sb_rng_philox_set_stream points it at an
 * sb_stream. */
#include <smolbridge/common.h>
#include <smolbridge/rng.h>

#include "common/internal.h"
#include "rng/rng_internal.h"

typedef struct {
  sb_stream s;
  int own;  /* 1: gsl_rng_set's sequence (carry across counter words) */
} philox_state;

static void philox_set(void *vs, unsigned long seed)
{
  philox_state *p = vs;
  sbi_stream_set(&p->s, (uint64_t)seed, 0, 0);
  p->s.ctr[3] = SBI_DOMAIN_GSL;
  p->own = 1;
}

static unsigned long philox_get(void *vs)
{
  philox_state *p = vs;
  if (p->s.pos >= 4) {
    sbi_philox_block(p->s.ctr, p->s.key, p->s.buf);
    p->s.pos = 0;
    /* next block: carry through the 127 low bits in the own domain; an
     * sb_stream's block counter is ctr[0] alone */
    if (++p->s.ctr[0] == 0 && p->own && ++p->s.ctr[1] == 0 &&
        ++p->s.ctr[2] == 0)
      p->s.ctr[3] = SBI_DOMAIN_GSL | ((p->s.ctr[3] + 1) & 0x7fffffffu);
  }
  return p->s.buf[p->s.pos++];
}

static double philox_get_double(void *vs)
{
  return (double)philox_get(vs) * 0x1p-32;
}

static const gsl_rng_type philox_type = {
    "sb_philox4x32_10", 0xffffffffUL, 0, sizeof(philox_state), philox_set,
    philox_get, philox_get_double};

const gsl_rng_type *const sb_rng_philox = &philox_type;

int sb_rng_philox_set_stream(gsl_rng *r, uint64_t seed, uint64_t id,
                             uint64_t step)
{
  if (!r || r->type != &philox_type)
    return sbi_error(SB_EINVAL, __func__,
                     "r must be a generator of type sb_rng_philox");
  philox_state *p = r->state;
  int st = sb_stream_init(&p->s, seed, id, step);
  p->own = 0;
  if (st) /* the message names this function, not sb_stream_init */
    return sbi_error(st, __func__, "id = %llu, step = %llu: need id <= "
                     "SB_STREAM_MAX_ID = 2^47 - 1, step <= "
                     "SB_STREAM_MAX_STEP = 2^48 - 1", (unsigned long long)id,
                     (unsigned long long)step);
  return st;
}
