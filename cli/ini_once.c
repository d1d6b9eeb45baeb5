/* ini_once.c — keys and section headers given once (ini_once.h). */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ini_once.h"

static char *dup_str(const char *s)
{
  size_t n = strlen(s) + 1;
  char *d = malloc(n);
  if (d)
    memcpy(d, s, n);
  return d;
}

int sbc_ini_once(sbc_ini_keys *o, const char *sec, const char *key,
                 const char *where, char *msg, size_t len)
{
  for (size_t i = 0; i < o->n; i++) {
    const struct sbc_ini_seen *e = &o->e[i];
    if (strcmp(e->sec, sec) || (key == NULL) != (e->key == NULL) ||
        (key && strcmp(e->key, key)))
      continue;
    if (key)
      snprintf(msg, len, "[%s] %s given twice (first at %s); give each key "
               "once", sec, key, e->where);
    else
      snprintf(msg, len, "section [%s] repeated (first at %s); put its keys "
               "in one section", sec, e->where);
    return 1;
  }
  if (o->n == o->cap) {
    size_t cap = o->cap ? 2 * o->cap : 64;
    struct sbc_ini_seen *e = realloc(o->e, cap * sizeof *e);
    if (!e) {
      snprintf(msg, len, "out of memory");
      return -1;
    }
    o->e = e;
    o->cap = cap;
  }
  struct sbc_ini_seen *e = &o->e[o->n];
  e->sec = dup_str(sec);
  e->key = key ? dup_str(key) : NULL;
  e->where = dup_str(where);
  if (!e->sec || (key && !e->key) || !e->where) {
    free(e->sec);
    free(e->key);
    free(e->where);
    snprintf(msg, len, "out of memory");
    return -1;
  }
  o->n++;
  return 0;
}

const char *sbc_ini_where(const sbc_ini_keys *o, const char *sec,
                          const char *key)
{
  for (size_t i = 0; i < o->n; i++)
    if (o->e[i].key && !strcmp(o->e[i].sec, sec) &&
        !strcmp(o->e[i].key, key))
      return o->e[i].where;
  return NULL;
}

int sbc_ini_keyless(const sbc_ini_keys *o, const char *name,
                    const char **sec, const char **where)
{
  const size_t len = strlen(name);
  for (size_t i = 0; i < o->n; i++) {
    const struct sbc_ini_seen *h = &o->e[i];
    if (h->key || strncmp(h->sec, name, len) ||
        (h->sec[len] != ' ' && h->sec[len]))
      continue;
    size_t j = 0;
    while (j < o->n && !(o->e[j].key && !strcmp(o->e[j].sec, h->sec)))
      j++;
    if (j == o->n) {
      *sec = h->sec;
      *where = h->where;
      return 1;
    }
  }
  return 0;
}

void sbc_ini_once_free(sbc_ini_keys *o)
{
  for (size_t i = 0; i < o->n; i++) {
    free(o->e[i].sec);
    free(o->e[i].key);
    free(o->e[i].where);
  }
  free(o->e);
  o->e = NULL;
  o->n = o->cap = 0;
}

void sbc_ini_warn(sbc_ini_keys *o, const char *cmd, const char *where,
                  const char *fmt, ...)
{
  char msg[sizeof o->warn[0] - 112];  /* room for where */
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  fprintf(stderr, "%s: warning: %s: %s\n", cmd, where, msg);
  if (o->nwarn < SBC_INI_MAXWARN)
    snprintf(o->warn[o->nwarn++], sizeof o->warn[0], "%s: %s", where, msg);
}

int sbc_ini_unused(sbc_ini_keys *o, const char *cmd, const char *sec,
                   const char *key, const char *why)
{
  const char *w = sbc_ini_where(o, sec, key);
  if (!w)
    return 0;
  sbc_ini_warn(o, cmd, w, "[%s] %s ignored: %s", sec, key, why);
  return 1;
}

void sbc_ini_json_warnings(FILE *f, const sbc_ini_keys *o)
{
  fputs("\"warnings\": [", f);
  for (size_t i = 0; i < o->nwarn; i++) {
    fputs(i ? ", \"" : "\"", f);
    for (const unsigned char *p = (const unsigned char *)o->warn[i]; *p; p++)
      if (*p == '"' || *p == '\\')
        fprintf(f, "\\%c", *p);
      else if (*p < 0x20)
        fprintf(f, "\\u%04x", *p);
      else
        fputc(*p, f);
    fputc('"', f);
  }
  fputc(']', f);
}

int sbc_ini_section_unused(sbc_ini_keys *o, const char *cmd,
                           const char *sec, const char *keep,
                           const char *why)
{
  int n = 0;
  for (size_t i = 0; i < o->n; i++) {
    const struct sbc_ini_seen *e = &o->e[i];
    if (!e->key || strcmp(e->sec, sec) || (keep && !strcmp(e->key, keep)))
      continue;
    sbc_ini_warn(o, cmd, e->where, "[%s] %s ignored: %s", sec, e->key, why);
    n++;
  }
  return n;
}

int sbc_ini_section_known(const char *sec, const char *const *names,
                          const char *named)
{
  for (int k = 0; names[k]; k++)
    if (!strcmp(sec, names[k]))
      return 1;
  const size_t n = strlen(named);
  return !strncmp(sec, named, n) && (sec[n] == ' ' || !sec[n]);
}
