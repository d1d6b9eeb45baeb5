/* par.c — MPI for the smolbridge command (par.h); without SB_HAVE_MPI (set
 * by Makefile.am for ./configure --with-mpi) a single process, and a clear
 * error when it was started as several. */
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "par.h"

#ifdef SB_HAVE_MPI
#include <mpi.h>
#endif

static int g_rank = 0, g_size = 1, g_mpi = 0;
static char g_tag[48] = "";

/* The rank and size an MPI starter put in the environment (Open MPI,
 * PMIx as under Slurm's srun, MPICH/Hydra's PMI), or -1. */
static long env_long(const char *const *names)
{
  for (int i = 0; names[i]; i++) {
    const char *v = getenv(names[i]);
    if (v && *v)
      return strtol(v, NULL, 10);
  }
  return -1;
}
static const char *const SIZE_VARS[] = {"OMPI_COMM_WORLD_SIZE", "PMIX_SIZE",
                                        "PMI_SIZE", "MPI_LOCALNRANKS",
                                        NULL};
static const char *const RANK_VARS[] = {"OMPI_COMM_WORLD_RANK", "PMIX_RANK",
                                        "PMI_RANK", NULL};

int sbc_par_init(int *argc, char ***argv)
{
  const char *off = getenv("SB_NO_MPI");
  if (off && *off && strcmp(off, "0"))
    return 0;
  long size = env_long(SIZE_VARS), rank = env_long(RANK_VARS);
  int launched = size >= 1 || rank >= 0;
#ifdef SB_HAVE_MPI
  if (!launched)
    return 0;
  if (MPI_Init(argc, argv) != MPI_SUCCESS) {
    fprintf(stderr, "smolbridge: MPI_Init failed\n");
    return 2;
  }
  g_mpi = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &g_rank);
  MPI_Comm_size(MPI_COMM_WORLD, &g_size);
  if (g_size > 1)
    snprintf(g_tag, sizeof g_tag, " (rank %d of %d)", g_rank, g_size);
  return 0;
#else
  (void)argc;
  (void)argv;
  (void)launched;
  if (size > 1) {
    if (rank <= 0)
      fprintf(stderr, "smolbridge: started as %ld processes, but this "
              "smolbridge was built without MPI: every process would do "
              "the whole job.  Rebuild with ./configure --with-mpi (Debian: "
              "apt-get install openmpi-bin libopenmpi-dev) or run it "
              "without mpirun/srun (docs/parallel.md).\n", size);
    return 2;
  }
  return 0;
#endif
}

void sbc_par_finalize(void)
{
#ifdef SB_HAVE_MPI
  if (g_mpi)
    MPI_Finalize();
  g_mpi = 0;
#endif
}

int sbc_par_rank(void) { return g_rank; }
int sbc_par_size(void) { return g_size; }
const char *sbc_par_tag(void) { return g_tag; }

void sbc_par_describe(char *d, size_t len)
{
#ifdef SB_HAVE_MPI
  int v = 0, sv = 0;
  MPI_Get_version(&v, &sv);  /* callable before MPI_Init */
  if (g_mpi)
    snprintf(d, len, "yes (MPI %d.%d, %d rank%s)", v, sv, g_size,
             g_size == 1 ? "" : "s");
  else
    snprintf(d, len, "yes (MPI %d.%d; not started by mpirun or srun)",
             v, sv);
#else
  snprintf(d, len, "no (./configure --with-mpi to build it)");
#endif
}

_Noreturn void sbc_par_abort(const char *why)
{
  fprintf(stderr, "smolbridge%s: %s: stopping the MPI job\n", g_tag, why);
#ifdef SB_HAVE_MPI
  if (g_mpi)
    MPI_Abort(MPI_COMM_WORLD, 1);
#endif
  exit(1);
}

#ifdef SB_HAVE_MPI

/* *v <- op of *v over the ranks, on every rank */
static void reduce(void *v, MPI_Datatype type, MPI_Op op)
{
  if (g_mpi && g_size > 1)
    MPI_Allreduce(MPI_IN_PLACE, v, 1, type, op, MPI_COMM_WORLD);
}
#endif

int sbc_par_max_int(int v)
{
#ifdef SB_HAVE_MPI
  reduce(&v, MPI_INT, MPI_MAX);
#endif
  return v;
}

double sbc_par_min_double(double v)
{
#ifdef SB_HAVE_MPI
  reduce(&v, MPI_DOUBLE, MPI_MIN);
#endif
  return v;
}

int sbc_par_exchange(double *const *send, const size_t *nsend,
                     double **recv, size_t *nrecv)
{
  for (int q = 0; q < g_size; q++) {
    recv[q] = NULL;
    nrecv[q] = 0;
  }
  if (g_size == 1 || !g_mpi)
    return 0;
#ifdef SB_HAVE_MPI
  /* counts first (64-bit), then the messages point to point.  Running out
   * of memory here cannot be agreed on without a collective per call (the
   * cost of a step on a busy machine is its number of collectives), and a
   * rank that cannot receive would leave its senders waiting: the job
   * stops instead. */
  const int P = g_size;
  unsigned long long *sc = calloc(2 * (size_t)P, sizeof *sc);
  MPI_Request *rq = malloc(2 * (size_t)P * sizeof *rq);
  if (!sc || !rq)
    sbc_par_abort("out of memory for the message counts");
  unsigned long long *rc = sc + P;
  for (int q = 0; q < P; q++)
    sc[q] = q == g_rank ? 0 : (unsigned long long)nsend[q];
  MPI_Alltoall(sc, 1, MPI_UNSIGNED_LONG_LONG, rc, 1, MPI_UNSIGNED_LONG_LONG,
               MPI_COMM_WORLD);
  int n = 0;
  for (int q = 0; q < P; q++) {
    if (sc[q] > INT_MAX || rc[q] > INT_MAX)
      sbc_par_abort("a message of more than INT_MAX values");
    if (!rc[q])
      continue;
    nrecv[q] = (size_t)rc[q];
    if (!(recv[q] = malloc(nrecv[q] * sizeof(double))))
      sbc_par_abort("out of memory for a message");
    MPI_Irecv(recv[q], (int)rc[q], MPI_DOUBLE, q, 11, MPI_COMM_WORLD,
              &rq[n++]);
  }
  for (int q = 0; q < P; q++)
    if (sc[q])
      MPI_Isend(send[q], (int)sc[q], MPI_DOUBLE, q, 11, MPI_COMM_WORLD,
                &rq[n++]);
  MPI_Waitall(n, rq, MPI_STATUSES_IGNORE);
  free(sc);
  free(rq);
  return 0;
#else
  (void)send;
  (void)nsend;
  return -1;
#endif
}

int sbc_par_gather(const void *buf, size_t len, unsigned char **all,
                   size_t **lens)
{
  *all = NULL;
  *lens = NULL;
  if (g_size == 1 || !g_mpi) {
    *lens = malloc(sizeof **lens);
    *all = malloc(len ? len : 1);
    if (!*lens || !*all) {
      free(*lens);
      free(*all);
      *all = NULL;
      *lens = NULL;
      return -1;
    }
    (*lens)[0] = len;
    if (len)
      memcpy(*all, buf, len);
    return 0;
  }
#ifdef SB_HAVE_MPI
  /* lengths first (as 64-bit counts), then the bytes in pieces below
   * INT_MAX per rank (MPI counts are int) */
  unsigned long long ml = len;
  unsigned long long *ls = NULL;
  int ok = 1;
  if (g_rank == 0) {
    ls = malloc((size_t)g_size * sizeof *ls);
    ok = ls != NULL;
  }
  MPI_Gather(&ml, 1, MPI_UNSIGNED_LONG_LONG, ls, 1, MPI_UNSIGNED_LONG_LONG,
             0, MPI_COMM_WORLD);
  size_t total = 0;
  if (g_rank == 0 && ok) {
    *lens = malloc((size_t)g_size * sizeof **lens);
    for (int r = 0; r < g_size; r++)
      total += (size_t)ls[r];
    *all = malloc(total ? total : 1);
    ok = *lens && *all;
    for (int r = 0; ok && r < g_size; r++)
      (*lens)[r] = (size_t)ls[r];
  }
  MPI_Bcast(&ok, 1, MPI_INT, 0, MPI_COMM_WORLD);
  if (ok) {
    const size_t CH = (size_t)1 << 30;
    if (g_rank == 0) {
      memcpy(*all, buf, len);
      size_t off = len;
      for (int r = 1; r < g_size; r++)
        for (size_t got = 0; got < (size_t)ls[r];) {
          size_t n = (size_t)ls[r] - got < CH ? (size_t)ls[r] - got : CH;
          MPI_Recv(*all + off, (int)n, MPI_BYTE, r, 7, MPI_COMM_WORLD,
                   MPI_STATUS_IGNORE);
          got += n;
          off += n;
        }
    } else {
      for (size_t sent = 0; sent < len;) {
        size_t n = len - sent < CH ? len - sent : CH;
        MPI_Send((const unsigned char *)buf + sent, (int)n, MPI_BYTE, 0, 7,
                 MPI_COMM_WORLD);
        sent += n;
      }
    }
  }
  free(ls);
  if (!ok && g_rank == 0) {
    free(*lens);
    free(*all);
    *lens = NULL;
    *all = NULL;
  }
  return ok ? 0 : -1;
#else
  return -1;
#endif
}
