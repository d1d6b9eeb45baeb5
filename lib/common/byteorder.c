/* byteorder.c — numbers of saved states in a fixed byte order.
 *
 * The checkpoints of the engine and of pgd store every integer and double
 * little-endian, whatever the machine: on a little-endian machine the
 * bytes are the memory's, on a big-endian one each number is reversed on
 * its way to and from the file.  The functions take `swap`, whether the
 * file's order is the reverse of this machine's (sbi_host_le() == 0 for a
 * little-endian file); a test sets it on a little-endian machine to run
 * the path a big-endian one takes.  Widths are 1, 2, 4 or 8 bytes (any
 * width works: the bytes of each item are reversed).  Doubles are
 * IEEE 754 binary64 with the integers' byte order (C11 Annex F; true of
 * every platform the library builds on). */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "internal.h"

int sbi_host_le(void)
{
  const uint16_t one = 1;
  unsigned char low;
  memcpy(&low, &one, 1);
  return low == 1;
}

void sbi_swap_items(void *p, size_t width, size_t n)
{
  unsigned char *c = p;
  for (size_t k = 0; k < n; k++, c += width)
    for (size_t a = 0, b = width - 1; a < b; a++, b--) {
      const unsigned char t = c[a];
      c[a] = c[b];
      c[b] = t;
    }
}

int sbi_write_ord(FILE *f, const void *p, size_t width, size_t n, int swap)
{
  if (n == 0)
    return 1;
  if (!swap || width == 1)
    return fwrite(p, width, n, f) == n;
  /* reversed through a small buffer: the caller's numbers stay as they
   * are */
  unsigned char tmp[512];
  const size_t per = width <= sizeof tmp ? sizeof tmp / width : 0;
  if (per == 0)
    return 0;
  const unsigned char *c = p;
  for (size_t done = 0; done < n;) {
    const size_t m = n - done < per ? n - done : per;
    memcpy(tmp, c + done * width, m * width);
    sbi_swap_items(tmp, width, m);
    if (fwrite(tmp, width, m, f) != m)
      return 0;
    done += m;
  }
  return 1;
}

int sbi_read_ord(FILE *f, void *p, size_t width, size_t n, int swap)
{
  if (n == 0)
    return 1;
  if (fread(p, width, n, f) != n)
    return 0;
  if (swap)
    sbi_swap_items(p, width, n);
  return 1;
}

/* Each listed field of the structure at p reversed in place. */
static void swap_fields(unsigned char *p, const sbi_field *fl, size_t nfl)
{
  for (size_t k = 0; k < nfl; k++)
    sbi_swap_items(p + fl[k].offset, fl[k].width, fl[k].count);
}

int sbi_write_fields(FILE *f, const void *p, size_t size, size_t n,
                     const sbi_field *fl, size_t nfl, int swap)
{
  if (n == 0)
    return 1;
  if (!swap)
    return fwrite(p, size, n, f) == n;
  unsigned char *tmp = malloc(size);
  int ok = tmp != NULL;
  for (size_t k = 0; k < n && ok; k++) {
    memcpy(tmp, (const unsigned char *)p + k * size, size);
    swap_fields(tmp, fl, nfl);
    ok = fwrite(tmp, size, 1, f) == 1;
  }
  free(tmp);
  return ok;
}

int sbi_read_fields(FILE *f, void *p, size_t size, size_t n,
                    const sbi_field *fl, size_t nfl, int swap)
{
  if (n == 0)
    return 1;
  if (fread(p, size, n, f) != n)
    return 0;
  for (size_t k = 0; k < n && swap; k++)
    swap_fields((unsigned char *)p + k * size, fl, nfl);
  return 1;
}
