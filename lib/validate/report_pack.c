/* report_pack.c — a report as a byte buffer and back (smolbridge/
 * validate.h): how the ranks of an MPI ensemble send their cases to rank 0
 * (cli/par.c), which appends them in the order of the serial run.  The
 * buffer is a byte image (doubles and enums as stored in memory), read
 * back by the same build: ranks of one program. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <smolbridge/validate.h>

#include "common/internal.h"
#include "validate/report.h"

static const char MAGIC[8] = "SBVREP1";

typedef struct {
  unsigned char *b;
  size_t len, cap;
  int err;
} wbuf;

static void put(wbuf *w, const void *p, size_t n)
{
  if (w->err)
    return;
  if (w->len + n > w->cap) {
    size_t nc = w->cap ? 2 * w->cap : 1024;
    while (nc < w->len + n)
      nc *= 2;
    unsigned char *q = realloc(w->b, nc);
    if (!q) {
      w->err = 1;
      return;
    }
    w->b = q;
    w->cap = nc;
  }
  memcpy(w->b + w->len, p, n);
  w->len += n;
}

static void put_u64(wbuf *w, uint64_t v) { put(w, &v, sizeof v); }

int sb_validate_report_pack(const sb_validate_report *rep, void **buf,
                            size_t *len)
{
  if (!rep || !buf || !len)
    return sbi_error(SB_EINVAL, __func__, "NULL argument");
  wbuf w = {NULL, 0, 0, 0};
  put(&w, MAGIC, sizeof MAGIC);
  put_u64(&w, rep->ncases);
  for (size_t k = 0; k < rep->ncases; k++) {
    const struct sbv_case_log *c = &rep->cases[k];
    const char *name = c->case_name ? c->case_name : "";
    size_t nl = strlen(name), tl = c->notes ? strlen(c->notes) : 0;
    int32_t st = c->status;
    put_u64(&w, nl);
    put(&w, name, nl);
    put(&w, &st, sizeof st);
    put(&w, &c->seconds, sizeof c->seconds);
    put_u64(&w, tl);
    put(&w, c->notes ? c->notes : "", tl);
    put_u64(&w, c->count);
    for (size_t i = 0; i < c->count; i++) {
      /* the bytes after the name's terminator are whatever the record's
       * writer left there: send zeros */
      sb_comparison t = rep->recs[c->first + i];
      size_t L = 0;
      while (L < sizeof t.name - 1 && t.name[L])
        L++;
      memset(t.name + L, 0, sizeof t.name - L);
      put(&w, &t, sizeof t);
    }
  }
  if (w.err) {
    free(w.b);
    *buf = NULL;
    *len = 0;
    return sbi_error(SB_ENOMEM, __func__, "out of memory");
  }
  *buf = w.b;
  *len = w.len;
  return SB_SUCCESS;
}

typedef struct {
  const unsigned char *b;
  size_t len, pos;
} rbuf;

static int get(rbuf *r, void *p, size_t n)
{
  if (n > r->len - r->pos)
    return -1;
  memcpy(p, r->b + r->pos, n);
  r->pos += n;
  return 0;
}

static int grow(void **p, size_t *cap, size_t need, size_t size)
{
  if (need <= *cap)
    return 0;
  size_t nc = *cap ? 2 * *cap : 16;
  while (nc < need)
    nc *= 2;
  void *q = realloc(*p, nc * size);
  if (!q)
    return -1;
  *p = q;
  *cap = nc;
  return 0;
}

int sb_validate_report_append_packed(sb_validate_report *rep,
                                     const void *buf, size_t len)
{
  if (!rep || (!buf && len))
    return sbi_error(SB_EINVAL, __func__, "NULL argument");
  rbuf r = {buf, len, 0};
  char magic[sizeof MAGIC];
  uint64_t ncases;
  if (get(&r, magic, sizeof magic) || memcmp(magic, MAGIC, sizeof MAGIC) ||
      get(&r, &ncases, sizeof ncases))
    return sbi_error(SB_EFORMAT, __func__, "not a packed report");
  for (uint64_t k = 0; k < ncases; k++) {
    uint64_t nl, tl, count;
    int32_t st;
    double secs;
    char name[256];
    if (get(&r, &nl, sizeof nl) || nl >= sizeof name ||
        get(&r, name, nl))
      return sbi_error(SB_EFORMAT, __func__, "case %llu: bad name",
                       (unsigned long long)k);
    name[nl] = '\0';
    /* the registry's own string (reports keep a pointer to it) */
    const char *reg = NULL;
    for (size_t i = 0; i < sb_validate_ncases() && !reg; i++)
      if (!strcmp(sb_validate_case_name(i), name))
        reg = sb_validate_case_name(i);
    if (!reg)
      return sbi_error(SB_EFORMAT, __func__, "unknown case '%s'", name);
    if (get(&r, &st, sizeof st) || get(&r, &secs, sizeof secs) ||
        get(&r, &tl, sizeof tl) || tl > r.len - r.pos)
      return sbi_error(SB_EFORMAT, __func__, "case %s: truncated", name);
    char *notes = NULL;
    if (tl) {
      notes = malloc(tl + 1);
      if (!notes)
        return sbi_error(SB_ENOMEM, __func__, "out of memory");
      get(&r, notes, tl);
      notes[tl] = '\0';
    }
    if (get(&r, &count, sizeof count) ||
        count > (r.len - r.pos) / sizeof(sb_comparison)) {
      free(notes);
      return sbi_error(SB_EFORMAT, __func__, "case %s: truncated", name);
    }
    if (grow((void **)&rep->recs, &rep->caprecs, rep->nrecs + count,
             sizeof *rep->recs) ||
        sbv_report_begin_case(rep, reg)) {
      free(notes);
      return sbi_error(SB_ENOMEM, __func__, "out of memory");
    }
    get(&r, rep->recs + rep->nrecs, count * sizeof *rep->recs);
    rep->nrecs += count;
    struct sbv_case_log *c = &rep->cases[rep->ncases - 1];
    c->notes = notes;
    sbv_report_end_case(rep, st, secs);
  }
  if (r.pos != r.len)
    return sbi_error(SB_EFORMAT, __func__, "%zu bytes left over",
                     r.len - r.pos);
  return SB_SUCCESS;
}
