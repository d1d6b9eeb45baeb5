/* internal.h — helpers shared by the library's modules.  Not installed.
 * Internal symbols use the prefix `sbi_`; the shared library exports only
 * `sb_*`, so these are reachable from the tests (which link the convenience
 * library libsbcore.la) but not from applications. */
#ifndef SB_INTERNAL_H
#define SB_INTERNAL_H

#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <smolbridge/common.h>

#if defined(__GNUC__)
#define SBI_PRINTF(f, a) __attribute__((format(printf, f, a)))
#else
#define SBI_PRINTF(f, a)
#endif

/* Record an error for the calling thread and return `status`.
 * `func` is the public function's name; the message should name the
 * offending argument and its value. */
int sbi_error(int status, const char *func, const char *fmt, ...)
    SBI_PRINTF(3, 4);

/* For `_e` functions: set *res (if not NULL) to NaN, record the message,
 * return status. */
int sbi_fail_res(sb_result *res, int status, const char *func,
                 const char *fmt, ...) SBI_PRINTF(4, 5);
#define SBI_FAIL_RES(res, status, ...) \
  sbi_fail_res((res), (status), __func__, __VA_ARGS__)

/* Saved states (fsutil.c). */
/* A saved state's file opened for reading (*status SB_SUCCESS), or NULL
 * with *status SB_EINVAL (path NULL) or SB_EIO and the message from
 * func. */
FILE *sbi_open_saved(const char *path, const char *func, int *status);
/* A file opened to save a state to path, or NULL with the message from
 * func (SB_EIO). */
FILE *sbi_open_for_save(const char *path, const char *func);
/* Close the save's file f: SB_SUCCESS if every write succeeded (ok) and
 * so did the close, else SB_EIO with the message from func and the
 * partial file removed (a failed save leaves no file behind). */
int sbi_finish_save(FILE *f, int ok, const char *path, const char *func);

/* Saved states protected by a hash: FNV-1a, 64 bits (Fowler, Noll & Vo;
 * basis SBI_FNV_BASIS), of every byte of the file before it, appended
 * in native byte order (by sbi_hsave_finish_ord in the file's).  A save
 * writes its bytes to the memory stream
 * of sbi_hsave_begin (NULL: SB_ENOMEM from func), then sbi_hsave_finish
 * writes them and their hash to path in one piece (as sbi_finish_save:
 * SB_EIO and no file left on failure; ok = 0: a write to memory failed,
 * SB_ENOMEM). */
#define SBI_FNV_BASIS 0xcbf29ce484222325ULL
uint64_t sbi_fnv1a(uint64_t h, const void *p, size_t n);
typedef struct {
  FILE *f;
  char *buf;
  size_t len;
} sbi_hsave;
FILE *sbi_hsave_begin(sbi_hsave *h, const char *func);
int sbi_hsave_finish(sbi_hsave *h, int ok, const char *path,
                     const char *func);
/* As sbi_hsave_finish, the hash written byte-reversed when swap = 1 (a
 * file in the order opposite to this machine's, byteorder.c). */
int sbi_hsave_finish_ord(sbi_hsave *h, int ok, int swap, const char *path,
                         const char *func);
/* The hash at the end of buf (len >= 16 bytes, the hash included): 0 if
 * it matches the bytes before it, 1 if it matches with its 8 bytes in
 * reverse order (a file written on a machine of the other byte order:
 * the saved states are native binary), -1 otherwise (damaged). */
int sbi_hash_check(const char *buf, size_t len);
/* v with its bytes in reverse order. */
uint32_t sbi_bswap32(uint32_t v);
/* The whole of f into memory (*len bytes; at least one byte allocated):
 * NULL on a read error or out of memory. */
char *sbi_slurp(FILE *f, size_t *len);
/* A saved state opened for reading: the whole file read into memory
 * (*mem, to free after closing the stream), its 8-byte magic checked
 * against `magic` (the first 6 bytes; the last 2 are the version, at
 * most magic's own), and for a version >= hashed_from the hash at its end
 * checked before anything else is read.  Returns a stream over the bytes
 * before the hash, from the magic on, with the version in *ver; NULL with
 * *status SB_EINVAL (NULL path), SB_EIO (cannot open or read), SB_EFORMAT
 * ("not a <what>", damaged: the hash does not match, or written on a
 * machine of the other byte order: it matches byte-swapped) or SB_ENOMEM and
 * the message from func. */
FILE *sbi_hload_open(const char *path, const char magic[8], int hashed_from,
                     const char *what, int *ver, char **mem,
                     const char *func, int *status);
/* As sbi_hload_open for a file whose numbers, the hash included, are
 * byte-reversed when swap = 1 (byteorder.c): the hash must match in that
 * order; matching in the other one, the file is refused as written in the
 * other byte order. */
FILE *sbi_hload_open_ord(const char *path, const char magic[8],
                         int hashed_from, const char *what, int *ver,
                         char **mem, int swap, const char *func,
                         int *status);

/* Saved states in a fixed byte order (byteorder.c).  swap = 1: the file's
 * order is the reverse of this machine's, each number (an item of `width`
 * bytes) is reversed on its way to or from the file; the checkpoints of
 * the engine and of pgd are little-endian, swap = !sbi_host_le().  The
 * writers and readers return 1 on success, 0 on a short write or read
 * (or out of memory). */
int sbi_host_le(void);
void sbi_swap_items(void *p, size_t width, size_t n);
int sbi_write_ord(FILE *f, const void *p, size_t width, size_t n, int swap);
int sbi_read_ord(FILE *f, void *p, size_t width, size_t n, int swap);
/* A structure's numbers: `count` items of `width` bytes at `offset`
 * (padding is not listed and is written as it is). */
typedef struct {
  size_t offset, width, count;
} sbi_field;
#define SBI_FIELD(type, member) \
  {offsetof(type, member), sizeof(((type *)0)->member), 1}
#define SBI_FIELDS(type, member, n) \
  {offsetof(type, member), sizeof(((type *)0)->member[0]), (n)}
/* n structures of `size` bytes at p, the numbers of each the fields fl[0
 * .. nfl-1]. */
int sbi_write_fields(FILE *f, const void *p, size_t size, size_t n,
                     const sbi_field *fl, size_t nfl, int swap);
int sbi_read_fields(FILE *f, void *p, size_t size, size_t n,
                    const sbi_field *fl, size_t nfl, int swap);

#endif /* SB_INTERNAL_H */
