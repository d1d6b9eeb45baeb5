/* ini_read.c — the INI reader of the configuration files
 * (<smolbridge/ini.h>): libinih's stream parser fed line by line, so
 * that each key and header carries its line, and the lines libinih would
 * misread are refused. */
#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

#include <ini.h>

#include <smolbridge/ini.h>

typedef struct {
  FILE *f;                  /* the file, or */
  const char *s;            /* the rest of the text */
  const char *path;
  int line;
  int indented;             /* the current line starts with a blank */
  int stop;                 /* a check failed: no more lines */
  int failed;               /* a callback failed */
  sb_ini_key_fn key;
  sb_ini_section_fn section;
  void *user;
  char *err;
  size_t errlen;
} reader;

static void say(reader *r, const char *msg)
{
  if (r->err && r->errlen)
    snprintf(r->err, r->errlen, "%s:%d: %s", r->path, r->line, msg);
}

/* fgets on the file or the text; *end: nothing follows. */
static char *get_line(reader *r, char *str, int num, int *end)
{
  if (r->f) {
    char *got = fgets(str, num, r->f);
    *end = feof(r->f);
    return got;
  }
  if (!*r->s)
    return NULL;
  size_t n = 0;
  while (n + 1 < (size_t)num && r->s[n] && (n == 0 || r->s[n - 1] != '\n')) {
    str[n] = r->s[n];
    n++;
  }
  str[n] = 0;
  r->s += n;
  *end = !*r->s;
  return str;
}

static char *read_line(char *str, int num, void *stream)
{
  reader *r = stream;
  int end;
  if (r->stop || !get_line(r, str, num, &end))
    return NULL;
  r->line++;
  size_t n = strlen(str);
  if (n == (size_t)num - 1 && str[n - 1] != '\n' && !end) {
    char msg[160];
    snprintf(msg, sizeof msg, "line longer than %d characters (the limit "
             "of the INI reader, libinih); shorten it", num - 2);
    say(r, msg);
    r->stop = 1;
    return NULL;
  }
  const char *s = str;
  r->indented = (*s == ' ' || *s == '\t');
  while (*s == ' ' || *s == '\t')
    s++;
  const char *e = *s == '[' ? strchr(s, ']') : NULL;
  if (*s == '[' && !e) {  /* libinih would go on, and the section's keys
                             would be blamed for coming before any */
    say(r, "section header without ']'");
    r->stop = 1;
    return NULL;
  }
  if (e && r->section) {  /* libinih does not report headers */
    char name[200], where[1100];
    size_t k = (size_t)(e - s - 1);
    if (k >= sizeof name)
      k = sizeof name - 1;
    memcpy(name, s + 1, k);
    name[k] = 0;
    snprintf(where, sizeof where, "%s:%d", r->path, r->line);
    r->failed |= r->section(r->user, name, where) != 0;
  }
  return str;
}

static int handler(void *user, const char *sec, const char *key,
                   const char *value)
{
  reader *r = user;
  if (r->stop)
    return 1;
  if (r->indented) {
    char msg[400];
    snprintf(msg, sizeof msg, "the line starts with a blank: the INI "
             "reader takes an indented line as the continuation of the "
             "previous value ([%s] %s); write keys at the start of the line",
             sec, key);
    say(r, msg);
    r->stop = 1;
    return 1;
  }
  char where[1100];
  snprintf(where, sizeof where, "%s:%d", r->path, r->line);
  r->failed |= r->key(r->user, sec, key, value, where) != 0;
  return 1;
}

int sb_ini_read(const char *path, const char *text, sb_ini_key_fn key,
                sb_ini_section_fn section, void *user, char *err,
                size_t errlen)
{
  if (err && errlen)
    err[0] = 0;
  if (!path || !key) {
    if (err && errlen)
      snprintf(err, errlen, "sb_ini_read: NULL path or key callback");
    return SB_EINVAL;
  }
  reader r = {NULL, text, path, 0, 0, 0, 0, key, section, user, err, errlen};
  if (!text) {
    struct stat st;
    if (stat(path, &st) == 0 && S_ISDIR(st.st_mode)) {
      if (err && errlen)
        snprintf(err, errlen, "%s: is a directory, not a configuration "
                 "file", path);
      return SB_EIO;
    }
    if (!(r.f = fopen(path, "r"))) {
      if (err && errlen)
        snprintf(err, errlen, "%s: cannot read: %s", path, strerror(errno));
      return SB_EIO;
    }
  }
  const int line = ini_parse_stream(read_line, &r, handler, &r);
  int st = SB_SUCCESS;
  if (r.f) {
    const int bad = ferror(r.f);
    fclose(r.f);
    if (bad) {
      if (err && errlen)
        snprintf(err, errlen, "%s: read error", path);
      return SB_EIO;
    }
  }
  if (r.stop || r.failed)
    st = SB_EINVAL;
  else if (line > 0) {
    r.line = line;
    say(&r, "not 'key = value', '[section]' or a comment");
    st = SB_EINVAL;
  }
  return st;
}
