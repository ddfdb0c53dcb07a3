/* Counting MPI traffic without touching Anvil: a PMPI interposition library.
 *
 *   ANVIL_MPI_COUNTS=/tmp/run LD_PRELOAD=build/benchmarks/libanvil_mpi_counts.so \
 *     mpirun -np 4 build/anvil SCENE.prm
 *
 * writes /tmp/run.RANK (one per process) at MPI_Finalize with the number of
 * point-to-point messages this rank sent and their bytes, and the number of
 * collective calls and the bytes this rank contributed to them (its send
 * buffer: count x type size; what a collective moves on the wire depends on
 * the MPI library's algorithm, typically log2(P) or 2 times that).
 * benchmarks/communication.py runs scenes with it and prints the figures
 * per step. */
#include <mpi.h>

#include <cstdio>
#include <cstdlib>

extern "C" {
static unsigned long long p2p_receives = 0, p2p_messages = 0, p2p_bytes = 0, coll_calls = 0, coll_bytes = 0;

static unsigned long long bytes_of(const long long count, MPI_Datatype type)
{
  int size = 0;
  if (type != MPI_DATATYPE_NULL)
    PMPI_Type_size(type, &size);
  return (unsigned long long)count * (unsigned long long)size;
}

static void p2p(const long long count, MPI_Datatype type)
{
  ++p2p_messages;
  p2p_bytes += bytes_of(count, type);
}

static void coll(const long long count, MPI_Datatype type)
{
  ++coll_calls;
  coll_bytes += bytes_of(count, type);
}

int MPI_Send(const void *b, int c, MPI_Datatype t, int d, int g, MPI_Comm m)
{
  p2p(c, t);
  return PMPI_Send(b, c, t, d, g, m);
}
int MPI_Ssend(const void *b, int c, MPI_Datatype t, int d, int g, MPI_Comm m)
{
  p2p(c, t);
  return PMPI_Ssend(b, c, t, d, g, m);
}
int MPI_Isend(const void *b, int c, MPI_Datatype t, int d, int g, MPI_Comm m, MPI_Request *r)
{
  p2p(c, t);
  return PMPI_Isend(b, c, t, d, g, m, r);
}
int MPI_Issend(const void *b, int c, MPI_Datatype t, int d, int g, MPI_Comm m, MPI_Request *r)
{
  p2p(c, t);
  return PMPI_Issend(b, c, t, d, g, m, r);
}
int MPI_Sendrecv(const void *sb, int sc, MPI_Datatype st, int d, int sg, void *rb, int rc,
                 MPI_Datatype rt, int src, int rg, MPI_Comm m, MPI_Status *status)
{
  p2p(sc, st);
  return PMPI_Sendrecv(sb, sc, st, d, sg, rb, rc, rt, src, rg, m, status);
}
int MPI_Irecv(void *b, int c, MPI_Datatype t, int src, int g, MPI_Comm m, MPI_Request *r)
{
  ++p2p_receives;
  return PMPI_Irecv(b, c, t, src, g, m, r);
}
int MPI_Allreduce(const void *s, void *r, int c, MPI_Datatype t, MPI_Op o, MPI_Comm m)
{
  coll(c, t);
  return PMPI_Allreduce(s, r, c, t, o, m);
}
int MPI_Iallreduce(const void *s, void *r, int c, MPI_Datatype t, MPI_Op o, MPI_Comm m, MPI_Request *q)
{
  coll(c, t);
  return PMPI_Iallreduce(s, r, c, t, o, m, q);
}
int MPI_Reduce(const void *s, void *r, int c, MPI_Datatype t, MPI_Op o, int root, MPI_Comm m)
{
  coll(c, t);
  return PMPI_Reduce(s, r, c, t, o, root, m);
}
int MPI_Bcast(void *b, int c, MPI_Datatype t, int root, MPI_Comm m)
{
  coll(c, t);
  return PMPI_Bcast(b, c, t, root, m);
}
int MPI_Allgather(const void *s, int sc, MPI_Datatype st, void *r, int rc, MPI_Datatype rt, MPI_Comm m)
{
  coll(sc, st);
  return PMPI_Allgather(s, sc, st, r, rc, rt, m);
}
int MPI_Allgatherv(const void *s, int sc, MPI_Datatype st, void *r, const int *rc, const int *dp,
                   MPI_Datatype rt, MPI_Comm m)
{
  coll(sc, st);
  return PMPI_Allgatherv(s, sc, st, r, rc, dp, rt, m);
}
int MPI_Gather(const void *s, int sc, MPI_Datatype st, void *r, int rc, MPI_Datatype rt, int root,
               MPI_Comm m)
{
  coll(sc, st);
  return PMPI_Gather(s, sc, st, r, rc, rt, root, m);
}
int MPI_Gatherv(const void *s, int sc, MPI_Datatype st, void *r, const int *rc, const int *dp,
                MPI_Datatype rt, int root, MPI_Comm m)
{
  coll(sc, st);
  return PMPI_Gatherv(s, sc, st, r, rc, dp, rt, root, m);
}
int MPI_Alltoall(const void *s, int sc, MPI_Datatype st, void *r, int rc, MPI_Datatype rt, MPI_Comm m)
{
  int p = 1;
  PMPI_Comm_size(m, &p);
  coll((long long)sc * p, st);
  return PMPI_Alltoall(s, sc, st, r, rc, rt, m);
}
int MPI_Exscan(const void *s, void *r, int c, MPI_Datatype t, MPI_Op o, MPI_Comm m)
{
  coll(c, t);
  return PMPI_Exscan(s, r, c, t, o, m);
}
int MPI_Scan(const void *s, void *r, int c, MPI_Datatype t, MPI_Op o, MPI_Comm m)
{
  coll(c, t);
  return PMPI_Scan(s, r, c, t, o, m);
}
int MPI_Barrier(MPI_Comm m)
{
  coll(0, MPI_BYTE);
  return PMPI_Barrier(m);
}
int MPI_Ibarrier(MPI_Comm m, MPI_Request *r)
{
  coll(0, MPI_BYTE);
  return PMPI_Ibarrier(m, r);
}

int MPI_Finalize(void)
{
  const char *prefix = getenv("ANVIL_MPI_COUNTS");
  if (prefix)
    {
      int rank = 0;
      PMPI_Comm_rank(MPI_COMM_WORLD, &rank);
      char name[4096];
      snprintf(name, sizeof name, "%s.%d", prefix, rank);
      FILE *f = fopen(name, "w");
      if (f)
        {
          fprintf(f,
                  "p2p_messages %llu\np2p_bytes %llu\np2p_receives %llu\ncollective_calls %llu\n"
                  "collective_bytes %llu\n",
                  p2p_messages, p2p_bytes, p2p_receives, coll_calls, coll_bytes);
          fclose(f);
        }
    }
  return PMPI_Finalize();
}
}
