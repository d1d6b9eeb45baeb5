/* sweep.h — the extreme-argument sweep shared by the Check suites of the
 * reference functions (test_langevin, test_spray, test_pgd_exact,
 * test_langevin_hit, test_bridge, test_passage, test_kernel, test_dlvo).
 *
 * What it checks: each argument of a function in turn is set to each value
 * of a list of extremes (subnormal, tiny, huge, +-DBL_MAX, +-inf, NaN; the
 * other arguments keep ordinary values), and the function must either
 * succeed with finite outputs, or fail the documented way: an error status
 * (SB_EDOM or SB_ERANGE), a plain return value of NaN and an error
 * message naming the public function (the scalar form: where the suite
 * gives its name).
 *
 * Why: the closed forms over- or underflow in intermediates (t/tau, B^2,
 * d^3, 1/m, double-double products) long before their values leave the
 * double range.  The sweep catches an inf or NaN returned with status 0,
 * a crash or hang at a corner, and an error the caller cannot attribute.
 * It does not check the values: each suite compares those at the corners
 * with mpmath rows of its reference tables.
 *
 * One list for every sweep, sbt_sweep_ext: +-1e-320, +-1e-300, 0,
 * +-1e300, +-DBL_MAX, +-inf, NaN, and 2^+-995, 1e+-154, where
 * double-double products or squares over/underflow.  The order of the
 * values is part of the sweep: a sampler drawing from one generator
 * through the whole sweep sees the same stream every run (the last four
 * values came last, so the draws at the first twelve are those of before).
 * A suite may sweep more values on top (sbt_sweep_vec_over), never fewer.
 *
 * A message names a function when the name occurs in it as a whole word
 * (sbt_names): "sb_kernel_shear_langevin: ..." does not name
 * sb_kernel_shear. */
#ifndef SB_SWEEP_H
#define SB_SWEEP_H

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include <check.h>
#include <smolbridge/common.h>

static const double sbt_sweep_ext[] = {
    1e-320,  -1e-320,  1e-300,   -1e-300,  0.0,       1e300,
    -1e300,  DBL_MAX,  -DBL_MAX, INFINITY, -INFINITY, NAN,
    0x1p995, 0x1p-995, 1e154,    1e-154};
#define SBT_SWEEP_NEXT ((int)(sizeof sbt_sweep_ext / sizeof sbt_sweep_ext[0]))

static inline int sbt_is_ident(char c)
{
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') ||
         (c >= '0' && c <= '9') || c == '_';
}

/* Whether msg contains the identifier nm as a whole word: not preceded or
 * followed by a letter, digit or underscore (so a message from
 * sb_kernel_shear_langevin does not name sb_kernel_shear). */
static inline int sbt_names(const char *msg, const char *nm)
{
  const size_t len = strlen(nm);
  if (len == 0)
    return 0;
  for (const char *p = strstr(msg, nm); p != NULL; p = strstr(p + 1, nm))
    if ((p == msg || !sbt_is_ident(p[-1])) && !sbt_is_ident(p[len]))
      return 1;
  return 0;
}

/* A check that does not stop the sweep: where cond is false, print the
 * message (printf arguments) on stderr and count it in the int lvalue
 * nbad.  The suite asserts nbad == 0 after the sweep, so every failing
 * corner is listed, not only the first. */
#define SBT_XCHECK(nbad, cond, ...)                                         \
  do {                                                                      \
    if (!(cond)) {                                                          \
      fprintf(stderr, __VA_ARGS__);                                         \
      fputc('\n', stderr);                                                  \
      (nbad)++;                                                             \
    }                                                                       \
  } while (0)

/* A function under the vector sweep: a wrapper that calls the public
 * function with the arguments a[], stores its n outputs in out[] (at most
 * SBT_SWEEP_MAXOUT), the public function's name in *nm, and returns its
 * status. */
typedef int (*sbt_xfn)(const double *a, double *out, int *n, const char **nm);
enum { SBT_SWEEP_MAXARG = 16, SBT_SWEEP_MAXOUT = 8 };

/* nonneg mask of sbt_sweep_vec: outputs 0 .. k-1 are >= 0 */
#define SBT_SWEEP_FIRST(k) ((1u << (k)) - 1u)

/* What sbt_sweep_vec expects of a function that fails (flags, or-ed):
 * SBT_SWEEP_NAN   its single output is NaN (a plain return value);
 * SBT_SWEEP_ZERO  its single output is 0 (an int result, which has no NaN);
 * SBT_SWEEP_NO_ERANGE  SB_ERANGE is a failure too (outputs that always fit
 *                 in a double, e.g. temperatures between two given ones);
 * SBT_SWEEP_NAN0  its first output is NaN, whatever the number of outputs
 *                 (the value of an sb_result, its error bound the second). */
enum {
  SBT_SWEEP_NAN = 1,
  SBT_SWEEP_ZERO = 2,
  SBT_SWEEP_NO_ERANGE = 4,
  SBT_SWEEP_NAN0 = 8
};
/* Each of the first narg arguments of f in turn over val[0 .. nval-1]
 * (sbt_sweep_ext or a longer list that contains it), the
 * others from base[0 .. nbase-1] (nbase <= SBT_SWEEP_MAXARG; f may read
 * all of them).  Status 0: every output finite, output j >= 0 where bit j
 * of nonneg is set.  Otherwise: the status is SB_EDOM, SB_ERANGE (unless
 * flags has SBT_SWEEP_NO_ERANGE) or `also' (0: no other), the message
 * names *nm and, where f has a single output, that output is NaN or 0 as
 * flags say (output 0 NaN with SBT_SWEEP_NAN0, any n).  row (the index in
 * the suite's table) labels the messages.
 * Returns the number of failed checks, each printed on stderr
 * (SBT_XCHECK). */
static inline int sbt_sweep_vec_over(sbt_xfn f, const double *base,
                                     int nbase, int narg, unsigned nonneg,
                                     int also, int flags, size_t row,
                                     const double *val, int nval)
{
  int nbad = 0;
  for (int i = 0; i < narg; i++)
    for (int e = 0; e < nval; e++) {
      const double x = val[e];
      double a[SBT_SWEEP_MAXARG] = {0}, out[SBT_SWEEP_MAXOUT];
      int n;
      const char *nm;
      memcpy(a, base, (size_t)nbase * sizeof a[0]);
      a[i] = x;
      sb_clear_error();
      const int st = f(a, out, &n, &nm);
      if (st == SB_SUCCESS) {
        for (int j = 0; j < n; j++)
          SBT_XCHECK(nbad,
                     isfinite(out[j]) && (!(nonneg >> j & 1u) || out[j] >= 0),
                     "%s (row %zu), argument %d = %g: output %d = %g with "
                     "status 0", nm, row, i, x, j, out[j]);
      } else {
        SBT_XCHECK(nbad,
                   st == SB_EDOM ||
                       (st == SB_ERANGE && !(flags & SBT_SWEEP_NO_ERANGE)) ||
                       (also && st == also),
                   "%s (row %zu), argument %d = %g: status %d", nm, row, i,
                   x, st);
        SBT_XCHECK(nbad, sbt_names(sb_last_error(), nm),
                   "%s (row %zu), argument %d = %g: message \"%s\"", nm, row,
                   i, x, sb_last_error());
        if ((flags & (SBT_SWEEP_NAN | SBT_SWEEP_ZERO)) && n == 1)
          SBT_XCHECK(nbad,
                     flags & SBT_SWEEP_ZERO ? out[0] == 0.0 : isnan(out[0]),
                     "%s (row %zu), argument %d = %g: %g with status %d", nm,
                     row, i, x, out[0], st);
        if ((flags & SBT_SWEEP_NAN0) && n >= 1)
          SBT_XCHECK(nbad, isnan(out[0]),
                     "%s (row %zu), argument %d = %g: value %g with status "
                     "%d", nm, row, i, x, out[0], st);
      }
    }
  return nbad;
}

/* sbt_sweep_vec_over with the values sbt_sweep_ext */
static inline int sbt_sweep_vec(sbt_xfn f, const double *base, int nbase,
                                int narg, unsigned nonneg, int also,
                                int flags, size_t row)
{
  return sbt_sweep_vec_over(f, base, nbase, narg, nonneg, also, flags, row,
                            sbt_sweep_ext, SBT_SWEEP_NEXT);
}

/* A function under the scalar sweep: returns the public function's value
 * (the suite's wrapper may map a documented non-finite value to 0). */
typedef double (*sbt_sfn)(const double *a);

/* Each of the narg arguments of f in turn over sbt_sweep_ext (+-inf
 * included), the others from base[0 .. narg-1]: the value is
 * finite with status 0 (and >= 0 where nonneg is set), or NaN with an
 * error status and, where nm is not NULL, a message naming nm (the public
 * function); never NaN or inf with status 0.  Stops the test at the first
 * failure (ck_assert_msg), labelled with fidx, the index in the suite's
 * table. */
static inline void sbt_sweep_scalar(sbt_sfn f, const double *base, int narg,
                                    int nonneg, size_t fidx, const char *nm)
{
  for (int i = 0; i < narg; i++)
    for (int e = 0; e < SBT_SWEEP_NEXT; e++) {
      const double x = sbt_sweep_ext[e];
      double a[SBT_SWEEP_MAXARG];
      memcpy(a, base, (size_t)narg * sizeof a[0]);
      a[i] = x;
      sb_clear_error();
      const double v = f(a);
      const int st = sb_last_status();
      ck_assert_msg(isfinite(v) ? st == SB_SUCCESS && (!nonneg || v >= 0.0)
                                : isnan(v) && st != SB_SUCCESS,
                    "function %zu, argument %d = %g: %g with status %d",
                    fidx, i, x, v, st);
      if (nm != NULL && st != SB_SUCCESS)
        ck_assert_msg(sbt_names(sb_last_error(), nm),
                      "%s (function %zu), argument %d = %g: message \"%s\"",
                      nm, fidx, i, x, sb_last_error());
    }
}

#endif /* SB_SWEEP_H */
