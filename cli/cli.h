/* cli.h — shared declarations of the `smolbridge` command. */
#ifndef SB_CLI_H
#define SB_CLI_H

#include <stddef.h>
#include <stdio.h>

/* ------------------------------------------------------------ subcommands */
int sbc_eval_main(int argc, char **argv);
int sbc_validate_main(int argc, char **argv);
int sbc_pbe_main(int argc, char **argv);       /* cli/pbe.c */
int sbc_collide_main(int argc, char **argv);   /* cli/collide.c */
int sbc_pgd_main(int argc, char **argv);       /* cli/pgd.c */
int sbc_spray_main(int argc, char **argv);     /* cli/spray.c */

/* cli/gnuplot.c: run gnuplot on script in dir (NULL: here) without a
 * shell, its messages discarded: 0 if it succeeded, -1 otherwise
 * (missing included); write s as a gnuplot single-quoted string. */
int sbc_gnuplot(const char *dir, const char *script);
void sbc_gnuplot_string(FILE *f, const char *s);

/* ------------------------------------------------------------ eval table
 * `smolbridge eval NAME key=value ...` calls a public function through an
 * entry of this table.  Each module lists its functions in cli/eval_MODULE.c
 * (C name without the sb_ prefix, arguments in C order).  Entries that
 * need randomness take a `seed` argument (the wrapper builds an MT19937
 * generator from it). */
#define SBE_MAXARGS 16
#define SBE_MAXOUTS 16

typedef struct {
  const char *name;                   /* C name without "sb_" */
  const char *args[SBE_MAXARGS + 1];  /* argument names, NULL-terminated */
  const char *outs[SBE_MAXOUTS + 1];  /* output names; {NULL}: one value */
  /* Evaluate: in[] holds the arguments in order; fill out[] (one value, or
   * one per name in outs).  Return a smolbridge status code. */
  int (*call)(const double *in, double *out);
  const char *summary;                /* one line for --list */
} sbe_func;

typedef struct {
  const sbe_func *funcs;
  size_t n;
} sbe_table;

/* Per-module tables (cli/eval_MODULE.c). */
extern const sbe_table sbe_table_bridge;   /* bridge and passage */
extern const sbe_table sbe_table_langevin; /* langevin */
extern const sbe_table sbe_table_kernel;   /* kernel, pbe analytic solutions */
extern const sbe_table sbe_table_dlvo;     /* dlvo */
extern const sbe_table sbe_table_stats;    /* stats */

/* Wrapper generators for plain `double sb_NAME(double, ...)` functions. */
#define SBE_WRAP1(f) static int sbe_w_##f(const double *i, double *o) \
  { o[0] = sb_##f(i[0]); return 0; }
#define SBE_WRAP2(f) static int sbe_w_##f(const double *i, double *o) \
  { o[0] = sb_##f(i[0], i[1]); return 0; }
#define SBE_WRAP3(f) static int sbe_w_##f(const double *i, double *o) \
  { o[0] = sb_##f(i[0], i[1], i[2]); return 0; }
#define SBE_WRAP4(f) static int sbe_w_##f(const double *i, double *o) \
  { o[0] = sb_##f(i[0], i[1], i[2], i[3]); return 0; }
#define SBE_WRAP5(f) static int sbe_w_##f(const double *i, double *o) \
  { o[0] = sb_##f(i[0], i[1], i[2], i[3], i[4]); return 0; }
#define SBE_WRAP6(f) static int sbe_w_##f(const double *i, double *o) \
  { o[0] = sb_##f(i[0], i[1], i[2], i[3], i[4], i[5]); return 0; }

#endif /* SB_CLI_H */
