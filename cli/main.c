/* main.c — the `smolbridge` command: dispatch to subcommands. */
#include <stdio.h>
#include <string.h>

#include <gsl/gsl_errno.h>
#include <smolbridge/common.h>

#include "cli.h"

static void usage(FILE *out)
{
  fprintf(out,
"Usage: smolbridge COMMAND [ARGS...]\n"
"\n"
"Stochastic-process references and Monte Carlo validation for particle\n"
"collision and agglomeration.\n"
"\n"
"Commands:\n"
"  eval FUNCTION key=value ...   evaluate a reference function (17 digits)\n"
"  eval --list                   list the functions and their arguments\n"
"  pbe --kernel NAME ...         solve the Smoluchowski population balance\n"
"  collide CONFIG.ini            run the collision engine\n"
"  pgd CONFIG.ini                pressureless gas dynamics (Euler/Lagrange)\n"
"  spray CONFIG.ini              homogeneous spray kinetics (Bird, Nanbu, breakup)\n"
"  validate [--quick|--full]     run the validation cases, write a report\n"
"\n"
"  smolbridge COMMAND --help     help on one command\n"
"  smolbridge --version          print the version\n"
"\n"
"See smolbridge(1) and docs/ for the theory behind each function.\n");
}

int main(int argc, char **argv)
{
  /* The library checks arguments before calling GSL; this is a second line
   * of defence so that no GSL error can abort the command. */
  gsl_set_error_handler_off();

  if (argc < 2) {
    usage(stderr);
    return 2;
  }
  const char *cmd = argv[1];
  if (!strcmp(cmd, "-h") || !strcmp(cmd, "--help") || !strcmp(cmd, "help")) {
    usage(stdout);
    return 0;
  }
  if (!strcmp(cmd, "--version") || !strcmp(cmd, "-V")) {
    printf("smolbridge %s\n", sb_version());
    return 0;
  }
  if (!strcmp(cmd, "eval"))
    return sbc_eval_main(argc - 1, argv + 1);
  if (!strcmp(cmd, "pbe"))
    return sbc_pbe_main(argc - 1, argv + 1);
  if (!strcmp(cmd, "collide"))
    return sbc_collide_main(argc - 1, argv + 1);
  if (!strcmp(cmd, "pgd"))
    return sbc_pgd_main(argc - 1, argv + 1);
  if (!strcmp(cmd, "spray"))
    return sbc_spray_main(argc - 1, argv + 1);
  if (!strcmp(cmd, "validate"))
    return sbc_validate_main(argc - 1, argv + 1);
  fprintf(stderr, "smolbridge: unknown command '%s'\n\n", cmd);
  usage(stderr);
  return 2;
}
