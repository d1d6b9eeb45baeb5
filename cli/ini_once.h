/* ini_once.h — each key once: the INI readers of `smolbridge spray` and
 * `smolbridge pgd` refuse a key given twice in a section and a section
 * header repeated, as `smolbridge collide` does (lib/collide/
 * collide_ini.c), instead of taking the last value or merging the two
 * sections silently.  The keys read, with their places, also let them
 * warn about keys that have no effect in the configuration (as collide
 * does, lib/collide/collide_check.c). */
#ifndef SB_CLI_INI_ONCE_H
#define SB_CLI_INI_ONCE_H

#include <stddef.h>
#include <stdio.h>

#define SBC_INI_MAXWARN 64

typedef struct {
  struct sbc_ini_seen {
    char *sec, *key, *where;  /* key NULL: a section header */
  } *e;
  size_t n, cap;
  /* the warnings given, "FILE:LINE: MESSAGE" (the first SBC_INI_MAXWARN;
   * kept by sbc_ini_once_free) for summary.json, as collide lists its */
  char warn[SBC_INI_MAXWARN][512];
  size_t nwarn;
} sbc_ini_keys;

/* Record key (NULL: the header of section sec) read at where
 * ("FILE:LINE").  0 the first time; 1 if it was seen before, with msg
 * (len bytes) "[sec] key given twice (first at FILE:LINE); give each key
 * once" or "section [sec] repeated (first at FILE:LINE); put its keys in
 * one section"; -1 out of memory (msg says so). */
int sbc_ini_once(sbc_ini_keys *o, const char *sec, const char *key,
                 const char *where, char *msg, size_t len);
/* Where key of section sec was read, or NULL. */
const char *sbc_ini_where(const sbc_ini_keys *o, const char *sec,
                          const char *key);
/* A section header read with no key under it whose name is `name` or
 * "name ..." (a named section such as [droplets NAME]): 1 with *sec and
 * *where ("FILE:LINE" of the header) set for the first one, 0 if none. */
int sbc_ini_keyless(const sbc_ini_keys *o, const char *name,
                    const char **sec, const char **where);
void sbc_ini_once_free(sbc_ini_keys *o);

/* 1 if sec is one of names (NULL-terminated) or the named section
 * "named NAME" (or bare "named"), e.g. [droplets NAME]; else 0. */
int sbc_ini_section_known(const char *sec, const char *const *names,
                          const char *named);

/* "CMD: warning: WHERE: MESSAGE" on stderr: a key without effect (the
 * run goes on, its exit status unchanged); "WHERE: MESSAGE" recorded in
 * o's warnings. */
void sbc_ini_warn(sbc_ini_keys *o, const char *cmd, const char *where,
                  const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;
/* If key of section sec was read: "CMD: warning: FILE:LINE: [sec] key
 * ignored: why" (the format of `smolbridge collide`); 1 if it warned. */
int sbc_ini_unused(sbc_ini_keys *o, const char *cmd, const char *sec,
                   const char *key, const char *why);
/* The same for every key read in section sec but `keep` (may be NULL);
 * the number of warnings. */
int sbc_ini_section_unused(sbc_ini_keys *o, const char *cmd,
                           const char *sec, const char *keep,
                           const char *why);

/* The member of summary.json that lists them, as `smolbridge collide`
 * writes it: "warnings": ["FILE:LINE: MESSAGE", ...] (no newline). */
void sbc_ini_json_warnings(FILE *f, const sbc_ini_keys *o);

#endif /* SB_CLI_INI_ONCE_H */
