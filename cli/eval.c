/* eval.c — `smolbridge eval FUNCTION key=value ...`: call a public reference
 * function by name and print its value(s) to 17 significant digits. */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <smolbridge/common.h>

#include "cli.h"

static const sbe_table *const tables[] = {&sbe_table_bridge,
                                          &sbe_table_langevin, &sbe_table_kernel,
                                          &sbe_table_dlvo, &sbe_table_stats};

static void usage(FILE *out)
{
  fprintf(out,
"Usage: smolbridge eval FUNCTION key=value ...\n"
"       smolbridge eval --list\n"
"       smolbridge eval FUNCTION --help\n"
"\n"
"Evaluate a public reference function of libsmolbridge.  FUNCTION is the C\n"
"name without the sb_ prefix; every argument is given as name=value, in any\n"
"order, with the names of the C prototype (see --list).  Values are printed\n"
"with 17 significant digits; functions with several outputs print one\n"
"name=value per line.  Samplers take seed=N (MT19937).\n"
"\n"
"Example: smolbridge eval bes3b_cross_prob x=1.5 y=1.3 a=1 v=1\n"
"\n"
"Exit status: 0 on success, 1 if the function reports an error (the message\n"
"is printed on stderr; the value printed is then NaN), 2 on a usage error.\n");
}

static const sbe_func *find(const char *name)
{
  for (size_t t = 0; t < sizeof tables / sizeof tables[0]; t++)
    for (size_t i = 0; i < tables[t]->n; i++)
      if (!strcmp(tables[t]->funcs[i].name, name))
        return &tables[t]->funcs[i];
  return NULL;
}

static void print_signature(FILE *out, const sbe_func *f)
{
  fprintf(out, "%s", f->name);
  for (int k = 0; f->args[k]; k++)
    fprintf(out, " %s=", f->args[k]);
  if (f->outs[0]) {
    fprintf(out, "  ->");
    for (int k = 0; f->outs[k]; k++)
      fprintf(out, " %s", f->outs[k]);
  }
  fprintf(out, "\n");
}

static void list(void)
{
  for (size_t t = 0; t < sizeof tables / sizeof tables[0]; t++)
    for (size_t i = 0; i < tables[t]->n; i++) {
      const sbe_func *f = &tables[t]->funcs[i];
      printf("%-22s %s\n", f->name, f->summary);
      printf("%-22s   ", "");
      print_signature(stdout, f);
    }
}

/* Parse a double; accepts inf, nan and C syntax.  Returns 0 on success. */
static int parse_double(const char *s, double *x)
{
  char *end;
  errno = 0;
  *x = strtod(s, &end);
  /* ERANGE: an overflow (rejected), or an underflow, which is kept if
   * it gave a subnormal number and not 0 */
  const int range = errno == ERANGE && !(*x != 0.0 && fabs(*x) < 1.0);
  return (end == s || *end != '\0' || range) ? -1 : 0;
}

int sbc_eval_main(int argc, char **argv)
{
  if (argc < 2) {
    usage(stderr);
    return 2;
  }
  if (!strcmp(argv[1], "--help") || !strcmp(argv[1], "-h")) {
    usage(stdout);
    return 0;
  }
  if (!strcmp(argv[1], "--list")) {
    list();
    return 0;
  }
  const char *name = argv[1];
  if (!strncmp(name, "sb_", 3))
    name += 3;
  const sbe_func *f = find(name);
  if (!f) {
    fprintf(stderr, "smolbridge eval: unknown function '%s' (see "
                    "'smolbridge eval --list')\n", argv[1]);
    return 2;
  }
  int nargs = 0;
  while (f->args[nargs])
    nargs++;
  double in[SBE_MAXARGS];
  int given[SBE_MAXARGS] = {0};
  for (int i = 2; i < argc; i++) {
    if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
      printf("%s: %s\nUsage: smolbridge eval ", f->name, f->summary);
      print_signature(stdout, f);
      return 0;
    }
    const char *eq = strchr(argv[i], '=');
    if (!eq) {
      fprintf(stderr, "smolbridge eval: argument '%s' is not key=value\n",
              argv[i]);
      return 2;
    }
    size_t klen = (size_t)(eq - argv[i]);
    int k;
    for (k = 0; k < nargs; k++)
      if (strlen(f->args[k]) == klen && !strncmp(f->args[k], argv[i], klen))
        break;
    if (k == nargs) {
      fprintf(stderr, "smolbridge eval: %s has no argument '%.*s'; usage: ",
              f->name, (int)klen, argv[i]);
      print_signature(stderr, f);
      return 2;
    }
    if (given[k]) {
      fprintf(stderr, "smolbridge eval: argument '%s' given twice\n",
              f->args[k]);
      return 2;
    }
    if (parse_double(eq + 1, &in[k]) != 0) {
      fprintf(stderr, "smolbridge eval: %s: '%s' is not a number (argument "
                      "%s)\n", f->name, eq + 1, f->args[k]);
      return 2;
    }
    /* a generator seed is an integer that MT19937 accepts */
    if (!strcmp(f->args[k], "seed") &&
        !(in[k] >= 0 && in[k] <= 4294967295.0 && in[k] == floor(in[k]))) {
      fprintf(stderr, "smolbridge eval: %s: seed = %s: must be an integer "
                      "from 0 to 4294967295\n", f->name, eq + 1);
      return 2;
    }
    given[k] = 1;
  }
  for (int k = 0; k < nargs; k++)
    if (!given[k]) {
      fprintf(stderr, "smolbridge eval: missing argument '%s'; usage: ",
              f->args[k]);
      print_signature(stderr, f);
      return 2;
    }

  double out[SBE_MAXOUTS];
  for (int k = 0; k < SBE_MAXOUTS; k++)
    out[k] = NAN;
  sb_clear_error();
  int status = f->call(in, out);
  if (status == SB_SUCCESS && sb_last_status() != SB_SUCCESS)
    status = sb_last_status(); /* plain double functions report this way */
  if (!f->outs[0]) {
    printf("%.17g\n", out[0]);
  } else {
    for (int k = 0; f->outs[k]; k++)
      printf("%s=%.17g\n", f->outs[k], out[k]);
  }
  if (status != SB_SUCCESS) {
    /* name the function called and its arguments: the library's message
     * may come from an inner routine */
    fprintf(stderr, "smolbridge eval: %s(", f->name);
    for (int k = 0; k < nargs; k++)
      fprintf(stderr, "%s%s=%.17g", k ? ", " : "", f->args[k], in[k]);
    const char *msg = sb_last_error();
    fprintf(stderr, "): %s%s%s\n", sb_strerror(status), msg[0] ? ": " : "",
            msg);
    return 1;
  }
  return 0;
}
