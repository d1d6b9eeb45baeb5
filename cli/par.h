/* par.h — process-level parallelism of the smolbridge command: MPI ranks
 * when built with ./configure --with-mpi and started by mpirun or srun,
 * otherwise a single process (rank 0 of 1).  Only the command uses MPI;
 * the library knows nothing of it.  docs/parallel.md. */
#ifndef SB_CLI_PAR_H
#define SB_CLI_PAR_H

#include <stddef.h>

/* Start MPI if the process was launched by an MPI starter (and the build
 * has MPI).  A build without MPI started as several processes prints an
 * error (from its first process) and returns 2; so does a failing
 * MPI_Init.  SB_NO_MPI=1 in the environment skips the detection. */
int sbc_par_init(int *argc, char ***argv);
void sbc_par_finalize(void);
int sbc_par_rank(void);
int sbc_par_size(void);
/* "yes (MPI 3.1, 2 ranks)", "yes (not started by mpirun/srun)" or
 * "no (./configure --with-mpi)", for --version */
void sbc_par_describe(char *buf, size_t len);
/* "" or " (rank R of P)" for messages */
const char *sbc_par_tag(void);

/* Every rank sends len bytes; rank 0 gets the concatenation in rank order
 * in *all (malloc'd; free it) and each rank's length in lens[0..P-1]
 * (malloc'd).  Others get NULL.  0 on success, -1 on failure (all ranks
 * see the same result). */
int sbc_par_gather(const void *buf, size_t len, unsigned char **all,
                   size_t **lens);

/* The largest v over the ranks, on every rank. */
int sbc_par_max_int(int v);

/* Stop the whole job (MPI_Abort; exit in one process) after printing
 * why on this rank's stderr (rank 0's, or every rank's with
 * SB_MPI_VERBOSE=1): for failures that cannot be agreed on without a
 * collective, such as running out of memory in the middle of a message
 * exchange. */
_Noreturn void sbc_par_abort(const char *why);

/* The smallest v over the ranks, on every rank. */
double sbc_par_min_double(double v);

/* Every rank sends send[q] (nsend[q] doubles; q = its own rank is
 * ignored) to every rank q and receives from each rank q recv[q]
 * (malloc'd, NULL when empty; free them) of nrecv[q] doubles.  A
 * collective call (one MPI_Alltoall of the counts, then point to point);
 * 0, or -1 in a build without MPI.  Out of memory, or a message above
 * INT_MAX values, stops the job (MPI_Abort) with a message. */
int sbc_par_exchange(double *const *send, const size_t *nsend,
                     double **recv, size_t *nrecv);

#endif /* SB_CLI_PAR_H */
