/* main.c — the `smolbridge` command: dispatch to subcommands. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_errno.h>
#include <smolbridge/common.h>

#include "cli.h"
#include "par.h"

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
"  eval FUNCTION --help          the arguments of one function\n"
"  pbe --kernel NAME ...         solve the Smoluchowski population balance\n"
"  collide CONFIG.ini            run the collision engine\n"
"  pgd CONFIG.ini                pressureless gas dynamics (Euler/Lagrange)\n"
"  spray CONFIG.ini              homogeneous spray kinetics (Bird, Nanbu, breakup)\n"
"  validate [--quick|--full]     run the validation cases, write a report\n"
"\n"
"  smolbridge COMMAND --help     help on one command\n"
"  smolbridge --help (-h, help)  this help\n"
"  smolbridge --version (-V)     print the version and whether MPI is built in\n"
"\n"
"See smolbridge(1) and docs/ for the theory behind each function.\n");
}

static int dispatch(int argc, char **argv);

/* Under mpirun/srun (an MPI build): validate, collide --sweep and pgd
 * with method = decomposition share the work between the ranks; every
 * other command runs on rank 0 only. */
int main(int argc, char **argv)
{
  int st = sbc_par_init(&argc, &argv);
  if (st)
    return st;
  int distributed = argc >= 2 && (!strcmp(argv[1], "validate") ||
                                  !strcmp(argv[1], "collide") ||
                                  !strcmp(argv[1], "pgd"));
  int rc = 0;
  /* one voice: the other ranks' stderr (the same messages, or progress)
   * is dropped unless SB_MPI_VERBOSE is set; rank 0 reports their
   * failures */
  if (sbc_par_rank() != 0 && !getenv("SB_MPI_VERBOSE") &&
      !freopen("/dev/null", "w", stderr))
    return 2;
  if (distributed || sbc_par_rank() == 0) {
    if (!distributed && sbc_par_size() > 1)
      fprintf(stderr, "smolbridge: '%s' runs on rank 0 only (%d ranks); "
              "validate, collide --sweep and pgd (decomposition) use them all\n",
              argc >= 2 ? argv[1] : "", sbc_par_size());
    rc = dispatch(argc, argv);
  }
  sbc_par_finalize();
  return rc;
}

static int dispatch(int argc, char **argv)
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
    char mpi[128];
    sbc_par_describe(mpi, sizeof mpi);
    printf("MPI: %s\n", mpi);
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
