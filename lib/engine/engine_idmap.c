/* engine_idmap.c — sets and counters of particle and pair keys (never 0):
 * open addressing with linear probing, multiplicative hashing (Knuth
 * 1998, TAOCP vol. 3, §6.4), grown at half load.  Used by the
 * first-contact observer (pairs seen, each particle's contacts) and by the
 * engine's collision tally (each particle's and each pair's collisions,
 * sb_engine_set_count_variance). */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include "common/internal.h"
#include "engine_internal.h"

static size_t slot(uint64_t key, size_t cap)
{
  return (size_t)((key * 0x9E3779B97F4A7C15ULL) >> 17) & (cap - 1);
}

/* Double m's table (1024 at first); -1 out of memory. */
static int grow(sbi_idmap *m, int counted)
{
  const size_t nc = m->cap ? 2 * m->cap : 1024;
  uint64_t *nk = calloc(nc, sizeof *nk);
  uint32_t *nv = counted ? calloc(nc, sizeof *nv) : NULL;
  if (!nk || (counted && !nv)) {
    free(nk);
    free(nv);
    return -1;
  }
  for (size_t i = 0; i < m->cap; i++)
    if (m->key[i]) {
      size_t h = slot(m->key[i], nc);
      while (nk[h])
        h = (h + 1) & (nc - 1);
      nk[h] = m->key[i];
      if (counted)
        nv[h] = m->val[i];
    }
  free(m->key);
  free(m->val);
  m->key = nk;
  m->val = nv;
  m->cap = nc;
  return 0;
}

long sbi_idmap_add(sbi_idmap *m, uint64_t key, int counted)
{
  if (2 * (m->n + 1) > m->cap && grow(m, counted))
    return -1;
  for (size_t h = slot(key, m->cap);; h = (h + 1) & (m->cap - 1)) {
    if (m->key[h] == key) {
      if (!counted)
        return 1;
      const uint32_t c = m->val[h];
      m->val[h] += c < UINT32_MAX;
      return (long)c;
    }
    if (!m->key[h]) {
      m->key[h] = key;
      if (counted)
        m->val[h] = 1;
      m->n++;
      return 0;
    }
  }
}

int sbi_idmap_has(const sbi_idmap *m, uint64_t key)
{
  if (!m->cap)
    return 0;
  for (size_t h = slot(key, m->cap);; h = (h + 1) & (m->cap - 1)) {
    if (m->key[h] == key)
      return 1;
    if (!m->key[h])
      return 0;
  }
}

long sbi_idmap_put(sbi_idmap *m, uint64_t key, uint32_t val)
{
  const long h = sbi_idmap_add(m, key, m->val != NULL);
  if (h < 0)
    return -1;
  if (m->val)
    for (size_t s = slot(key, m->cap);; s = (s + 1) & (m->cap - 1))
      if (m->key[s] == key) {
        m->val[s] = val;
        break;
      }
  return h;
}

int sbi_idmap_write(const sbi_idmap *m, FILE *f, int counted_map, int swap)
{
  const uint64_t n = m->n;
  /* a counted map that never held a key has no `val` yet */
  const unsigned char counted = counted_map != 0;
  if (!sbi_write_ord(f, &n, sizeof n, 1, swap) ||
      fwrite(&counted, 1, 1, f) != 1)
    return -1;
  for (size_t i = 0; i < m->cap; i++)
    if (m->key[i] &&
        (!sbi_write_ord(f, &m->key[i], sizeof *m->key, 1, swap) ||
         (counted && !sbi_write_ord(f, &m->val[i], sizeof *m->val, 1, swap))))
      return -1;
  return 0;
}

int sbi_idmap_read(sbi_idmap *m, FILE *f, int counted, int swap)
{
  uint64_t n;
  unsigned char c;
  if (!sbi_read_ord(f, &n, sizeof n, 1, swap) || fread(&c, 1, 1, f) != 1)
    return -1;
  if (c != (counted != 0) || n > (uint64_t)1 << 40)
    return -2;
  sbi_idmap_free(m);
  if (counted && grow(m, 1))  /* a counted map keeps `val` */
    return -1;
  for (uint64_t q = 0; q < n; q++) {
    uint64_t key;
    uint32_t val = 0;
    if (!sbi_read_ord(f, &key, sizeof key, 1, swap) ||
        (counted && !sbi_read_ord(f, &val, sizeof val, 1, swap)))
      return -1;
    if (key == 0 || sbi_idmap_has(m, key))
      return -2;
    if (sbi_idmap_put(m, key, val) < 0)
      return -1;
  }
  return 0;
}

void sbi_idmap_free(sbi_idmap *m)
{
  free(m->key);
  free(m->val);
  m->key = NULL;
  m->val = NULL;
  m->cap = m->n = 0;
}
