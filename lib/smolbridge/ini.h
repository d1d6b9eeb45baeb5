/* smolbridge/ini.h — the INI reader of the configuration files
 * (`smolbridge collide`, `smolbridge spray`, <smolbridge/collide.h>):
 * libinih's parser (key = value lines under [section] headers, ';' and
 * '#' comments) with the line numbers and the checks it leaves to the
 * caller.
 *
 * Checks: a line longer than the parser's buffer (libinih's INI_MAX_LINE,
 * it would split the line silently), an indented line (libinih takes it
 * as the continuation of the previous value), a line that is not
 * key = value, [section] or a comment.  Messages "FILE:LINE: ..." go to
 * the caller's buffer; nothing is printed.  Thread safety: no shared
 * state. */
#ifndef SMOLBRIDGE_INI_H
#define SMOLBRIDGE_INI_H

#include <stddef.h>
#include <smolbridge/common.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Called for each key = value in section `section` ("" before the first
 *  header); where = "FILE:LINE".  Return 0 to go on, non-zero for an
 *  error the callback reports itself (reading goes on, so that the caller
 *  keeps its first error; the reader then returns SB_EINVAL). */
typedef int (*sb_ini_key_fn)(void *user, const char *section,
                             const char *key, const char *value,
                             const char *where);

/** Called for each section header line as it is read, with the name
 *  between the brackets and where = "FILE:LINE" (a header without keys
 *  is seen too).  Return as sb_ini_key_fn. */
typedef int (*sb_ini_section_fn)(void *user, const char *section,
                                 const char *where);

/** Read the file `path` (text == NULL), or the text `text` with `path`
 *  naming it in the messages.  `section` may be NULL.  Returns
 *  SB_SUCCESS; SB_EIO (cannot open or read the file: err says why);
 *  SB_EINVAL when a check failed (err holds "FILE:LINE: ..."; reading
 *  stops there) or a callback returned non-zero (err unchanged);
 *  err (errlen bytes, may be NULL) gets the message. */
int sb_ini_read(const char *path, const char *text, sb_ini_key_fn key,
                sb_ini_section_fn section, void *user, char *err,
                size_t errlen);

#ifdef __cplusplus
}
#endif

#endif /* SMOLBRIDGE_INI_H */
