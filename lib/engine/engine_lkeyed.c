/* engine_lkeyed.c — the Langevin detector's random streams and its
 * parallel first pass (docs/engine_langevin.md §5).
 *
 * Streams.  With the engine's counter-based streams on (the default,
 * sb_engine_params.streams), every record the detector examines draws
 * its interior path from a Philox stream of its own (smolbridge/rng.h):
 * the key mixes the seed, the step and the pass (0 for the step's first
 * pass over the candidates; for a re-detection after an outcome, a hash
 * of the outcome's event: its time and both ids), the counter holds both
 * particles' ids, the lower first, and the record itself is built with
 * the lower id first (engine_langevin.c).  A record's draws then depend
 * on (seed, step, pass, the two ids) alone, not on the order in which the
 * records are examined nor on the particles' order in memory, so the
 * first pass can run on every thread and the run is the same bit for bit
 * on any number of threads and after any sb_engine_sort.  The
 * re-detections stay serial (they follow the events in time order).
 * With the streams off, the detector draws from the engine's generator in
 * record order, as before.
 *
 * The key is splitmix64's finalizer (Steele, Lea & Flood 2014) applied
 * in turn to the seed (with a tag that keeps it apart from the
 * transport's key), the step and the pass: distinct (step, pass) give
 * distinct 64-bit keys but for a collision of probability ~2^-64 per
 * pair of keys; distinct pairs within a key are distinct counters.
 *
 * Parallel first pass.  Each thread takes blocks of records in
 * increasing order and keeps their events with the record's index; the
 * events are then pushed in record order (a merge of the threads' sorted
 * lists), which is the order of the serial pass: the event heap, and so
 * the outcome order, is the same.  So are the sampler's counters
 * (sb_engine_langevin_stats): each record's are taken alone (its hitter
 * reset before it) and its pruned mass, a floating-point sum, is added in
 * record order after the pass, as the serial pass adds it. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <smolbridge/rng.h>

#include "common/internal.h"
#include "engine_internal.h"

/* One event of the first pass: record q's. */
typedef struct {
  size_t q;
  double s;
  sbi_event ev;
} lent;

struct sbi_lbuf {
  lent *v;
  size_t n, cap;
  size_t q;    /* the record being examined */
  sb_langevin_hit_stats acc;  /* the sampler's counts, without the mass */
  int st;      /* first error status of the thread */
  char msg[256];
};

/* Record block of the parallel pass. */
#define LBLOCK 32

static uint64_t mix64(uint64_t z)
{
  z += 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

void sbi_engine_langevin_slots_free(sb_engine *e)
{
  for (int t = 0; t < e->nlt; t++) {
    if (t > 0)
      sb_langevin_hitter_free(e->lht[t]);
    if (e->lrt[t])
      gsl_rng_free(e->lrt[t]);
    free(e->lbt[t].v);
  }
  free(e->lht);
  free(e->lrt);
  free(e->lbt);
  e->lht = NULL;
  e->lrt = NULL;
  e->lbt = NULL;
  e->nlt = 0;
}

/* Slots 0 .. nt - 1 (slot 0's hitter is e->lh); status. */
static int slots_ensure(sb_engine *e, int nt)
{
  if (nt <= e->nlt)
    return SB_SUCCESS;
  sb_langevin_hitter **h = realloc(e->lht, (size_t)nt * sizeof *h);
  if (h)
    e->lht = h;
  gsl_rng **r = realloc(e->lrt, (size_t)nt * sizeof *r);
  if (r)
    e->lrt = r;
  struct sbi_lbuf *b = realloc(e->lbt, (size_t)nt * sizeof *b);
  if (b)
    e->lbt = b;
  if (!h || !r || !b)
    return sbi_error(SB_ENOMEM, "sb_engine_step", "out of memory");
  for (int t = e->nlt; t < nt; t++) {
    memset(&e->lbt[t], 0, sizeof e->lbt[t]);
    e->lrt[t] = gsl_rng_alloc(sb_rng_philox);
    e->lht[t] = t ? sbi_engine_langevin_hitter(e) : e->lh;
    if (!e->lrt[t] || !e->lht[t]) {
      if (e->lrt[t])
        gsl_rng_free(e->lrt[t]);
      if (t && e->lht[t])
        sb_langevin_hitter_free(e->lht[t]);
      return sbi_error(SB_ENOMEM, "sb_engine_step", "out of memory");
    }
    e->nlt = t + 1;
  }
  return SB_SUCCESS;
}

/* Slot t's generator on record p's stream for this step and pass. */
static const gsl_rng *pair_rng(const sb_engine *e, int t,
                               const sb_engine_pair *p, uint64_t pass)
{
  const uint64_t key =
      mix64(mix64(mix64(e->par.seed ^ 0x4c414e4745564e21ULL) ^ e->steps) ^
            pass);
  const uint64_t a = e->id[p->i], b = e->id[p->j];
  if (sb_rng_philox_set_stream(e->lrt[t], key, a < b ? a : b, a < b ? b : a))
    return NULL;
  return e->lrt[t];
}

void sbi_engine_langevin_redetect_key(sb_engine *e, const sbi_event *ev)
{
  uint64_t sb;
  memcpy(&sb, &ev->s, sizeof sb);
  const uint64_t a = e->id[ev->p.i], b = e->id[ev->p.j];
  /* odd: never the first pass's 0 */
  e->lredet = mix64(mix64(mix64(sb) ^ (a < b ? a : b)) ^ (a < b ? b : a)) |
              1u;
}

/* ------------------------------------------------------------ serial */

typedef struct {
  sb_engine *e;
  const sb_engine_pair *p;
  double t;
} push_ctx;

static int push_sink(void *ctx, double s, sbi_event *ev)
{
  push_ctx *c = ctx;
  return sbi_engine_deliver(c->e, c->p, c->t, s, ev);
}

int sbi_engine_langevin_record(sb_engine *e, const sb_engine_pair *p,
                               double t)
{
  const gsl_rng *r = e->rng;
  if (e->par.streams) {
    int st = slots_ensure(e, 1);
    if (st)
      return st;
    r = pair_rng(e, 0, p, e->in_step ? e->lredet : 0);
    if (!r)
      return sbi_error(SB_EDOM, "sb_engine_step", "streams: step %llu or "
                       "particle id beyond the streams' range",
                       (unsigned long long)e->steps);
  }
  push_ctx c = {e, p, t};
  sb_langevin_hit_stats rec;
  memset(&rec, 0, sizeof rec);
  const int st = sbi_engine_langevin_events(e, e->lh, r, p, t, push_sink, &c,
                                            &rec);
  sbi_engine_langevin_fold(e->lacc, &rec, 1);  /* as the parallel pass */
  return st;
}

/* ------------------------------------------------------------ parallel */

static int buf_sink(void *ctx, double s, sbi_event *ev)
{
  struct sbi_lbuf *b = ctx;
  if (b->n == b->cap) {
    size_t cap = b->cap ? 2 * b->cap : 64;
    lent *v = realloc(b->v, cap * sizeof *v);
    if (!v)
      return SB_ENOMEM;
    b->v = v;
    b->cap = cap;
  }
  b->v[b->n].q = b->q;
  b->v[b->n].s = s;
  b->v[b->n].ev = *ev;
  b->n++;
  return SB_SUCCESS;
}

/* Thread t's share of the first pass: blocks b = t, t + nt, ... (so that
 * its events are in record order). */
static void pass_thread(const sb_engine *e, int t, int nt, size_t np)
{
  struct sbi_lbuf *b = &e->lbt[t];
  b->n = 0;
  b->st = SB_SUCCESS;
  memset(&b->acc, 0, sizeof b->acc);
  for (size_t q0 = (size_t)t * LBLOCK; q0 < np && !b->st;
       q0 += (size_t)nt * LBLOCK) {
    const size_t q1 = q0 + LBLOCK < np ? q0 + LBLOCK : np;
    for (size_t q = q0; q < q1 && !b->st; q++) {
      sb_engine_pair p;
      sbi_engine_make_pair(e, e->pairs[2 * q], e->pairs[2 * q + 1], &p);
      const gsl_rng *r = pair_rng(e, t, &p, 0);
      b->q = q;
      sb_langevin_hit_stats rec;
      memset(&rec, 0, sizeof rec);
      b->st = r ? sbi_engine_langevin_events(e, e->lht[t], r, &p, 0.0,
                                             buf_sink, b, &rec)
                : SB_EDOM;
      sbi_engine_langevin_fold(&b->acc, &rec, 0);
      e->lpm[q] = rec.pruned_mass;  /* added in record order afterwards */
      if (b->st)
        snprintf(b->msg, sizeof b->msg, "%s",
                 r ? sb_last_error() : "streams: a particle id or the "
                                       "step is out of range");
    }
  }
}

int sbi_engine_langevin_first_pass(sb_engine *e, int nt)
{
  if (nt > 64)
    nt = 64;  /* the merge's cursors */
  int st = slots_ensure(e, nt);
  if (st)
    return st;
  const size_t np = e->npairs;
  if (np > e->caplpm) {
    double *m = realloc(e->lpm, np * sizeof *m);
    if (!m)
      return sbi_error(SB_ENOMEM, "sb_engine_step", "out of memory");
    e->lpm = m;
    e->caplpm = np;
  }
  for (size_t q = 0; q < np; q++)
    e->lpm[q] = 0.0;
  const sb_engine *ce = e;
#ifdef _OPENMP
#pragma omp parallel for schedule(static, 1) num_threads(nt)
#endif
  for (int t = 0; t < nt; t++)
    pass_thread(ce, t, nt, np);
  /* the sampler's counters as the serial pass adds them: the pruned mass
   * record by record, in record order, whatever the threads */
  for (int t = 0; t < nt; t++)
    sbi_engine_langevin_fold(e->lacc, &e->lbt[t].acc, 0);
  for (size_t q = 0; q < np; q++)
    e->lacc->pruned_mass += e->lpm[q];
  for (int t = 0; t < nt; t++)
    if (e->lbt[t].st)
      return sbi_error(e->lbt[t].st, "sb_engine_step", "%s", e->lbt[t].msg);
  /* thread t holds the blocks t, t + nt, ...: visit the blocks in order */
  size_t at[64] = {0};
  for (size_t blk = 0; blk * LBLOCK < np; blk++) {
    const int t = (int)(blk % (size_t)nt);
    const struct sbi_lbuf *b = &e->lbt[t];
    const size_t q1 = (blk + 1) * LBLOCK;
    while (at[t] < b->n && b->v[at[t]].q < q1) {
      lent *x = &b->v[at[t]++];
      sb_engine_pair p;
      sbi_engine_make_pair(e, e->pairs[2 * x->q], e->pairs[2 * x->q + 1],
                           &p);
      st = sbi_engine_deliver(e, &p, 0.0, x->s, &x->ev);
      if (st)
        return st;
    }
  }
  return SB_SUCCESS;
}
