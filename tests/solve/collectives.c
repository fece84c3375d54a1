/* The collective MPI calls of a process, one line each, in the order made:
 * loaded before the MPI library (LD_PRELOAD), it stands in for them and
 * calls the library's own (PMPI_). Every process writes its lines to
 * $DEM_COLLECTIVES.RANK; those of the processes of a run must be the
 * same, or the run waits forever at the first that differs
 * (ranks_collectives.sh). A line: the call, whether on MPI_COMM_WORLD or
 * another communicator (HDF5's), the count of elements sent (or -1 where
 * it may differ between processes), the root (or -1), and the function
 * that called it, when the dynamic symbols name it. */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <mpi.h>
#include <stdio.h>
#include <stdlib.h>

static FILE *out;

static void note(const char *call, MPI_Comm comm, long count, int root, void *caller)
{
	if (!out) {
		int rank = 0;
		PMPI_Comm_rank(MPI_COMM_WORLD, &rank);
		const char *base = getenv("DEM_COLLECTIVES");
		char path[4096];
		snprintf(path, sizeof path, "%s.%d", base ? base : "collectives", rank);
		if (!(out = fopen(path, "w"))) {
			perror(path);
			abort();
		}
	}
	int same = MPI_UNEQUAL;
	if (comm != MPI_COMM_NULL)
		PMPI_Comm_compare(comm, MPI_COMM_WORLD, &same);
	Dl_info info;
	const char *who = dladdr(caller, &info) && info.dli_sname ? info.dli_sname : "?";
	fprintf(out, "%s %s %ld %d %s\n", call, same == MPI_IDENT ? "world" : "other", count, root,
	        who);
	/* Written at once: a stalled run is killed. */
	fflush(out);
}

#define CALLER __builtin_return_address(0)

int MPI_Barrier(MPI_Comm c)
{
	note("Barrier", c, 0, -1, CALLER);
	return PMPI_Barrier(c);
}

int MPI_Bcast(void *b, int n, MPI_Datatype t, int root, MPI_Comm c)
{
	note("Bcast", c, n, root, CALLER);
	return PMPI_Bcast(b, n, t, root, c);
}

int MPI_Reduce(const void *s, void *r, int n, MPI_Datatype t, MPI_Op o, int root, MPI_Comm c)
{
	note("Reduce", c, n, root, CALLER);
	return PMPI_Reduce(s, r, n, t, o, root, c);
}

int MPI_Allreduce(const void *s, void *r, int n, MPI_Datatype t, MPI_Op o, MPI_Comm c)
{
	note("Allreduce", c, n, -1, CALLER);
	return PMPI_Allreduce(s, r, n, t, o, c);
}

int MPI_Exscan(const void *s, void *r, int n, MPI_Datatype t, MPI_Op o, MPI_Comm c)
{
	note("Exscan", c, n, -1, CALLER);
	return PMPI_Exscan(s, r, n, t, o, c);
}

int MPI_Gather(const void *s, int sn, MPI_Datatype st, void *r, int rn, MPI_Datatype rt, int root,
               MPI_Comm c)
{
	note("Gather", c, sn, root, CALLER);
	return PMPI_Gather(s, sn, st, r, rn, rt, root, c);
}

int MPI_Gatherv(const void *s, int sn, MPI_Datatype st, void *r, const int *rn, const int *at,
                MPI_Datatype rt, int root, MPI_Comm c)
{
	note("Gatherv", c, -1, root, CALLER);
	return PMPI_Gatherv(s, sn, st, r, rn, at, rt, root, c);
}

int MPI_Scatterv(const void *s, const int *sn, const int *at, MPI_Datatype st, void *r, int rn,
                 MPI_Datatype rt, int root, MPI_Comm c)
{
	note("Scatterv", c, -1, root, CALLER);
	return PMPI_Scatterv(s, sn, at, st, r, rn, rt, root, c);
}

int MPI_Allgather(const void *s, int sn, MPI_Datatype st, void *r, int rn, MPI_Datatype rt,
                  MPI_Comm c)
{
	note("Allgather", c, sn, -1, CALLER);
	return PMPI_Allgather(s, sn, st, r, rn, rt, c);
}

int MPI_Allgatherv(const void *s, int sn, MPI_Datatype st, void *r, const int *rn, const int *at,
                   MPI_Datatype rt, MPI_Comm c)
{
	note("Allgatherv", c, -1, -1, CALLER);
	return PMPI_Allgatherv(s, sn, st, r, rn, at, rt, c);
}

int MPI_Alltoall(const void *s, int sn, MPI_Datatype st, void *r, int rn, MPI_Datatype rt,
                 MPI_Comm c)
{
	note("Alltoall", c, sn, -1, CALLER);
	return PMPI_Alltoall(s, sn, st, r, rn, rt, c);
}

int MPI_Alltoallv(const void *s, const int *sn, const int *sat, MPI_Datatype st, void *r,
                  const int *rn, const int *rat, MPI_Datatype rt, MPI_Comm c)
{
	note("Alltoallv", c, -1, -1, CALLER);
	return PMPI_Alltoallv(s, sn, sat, st, r, rn, rat, rt, c);
}

/* The collective file calls (HDF5's MPI-IO driver). */
int MPI_File_write_at_all(MPI_File f, MPI_Offset at, const void *b, int n, MPI_Datatype t,
                          MPI_Status *st)
{
	note("File_write_at_all", MPI_COMM_NULL, -1, -1, CALLER);
	return PMPI_File_write_at_all(f, at, b, n, t, st);
}

int MPI_File_read_at_all(MPI_File f, MPI_Offset at, void *b, int n, MPI_Datatype t, MPI_Status *st)
{
	note("File_read_at_all", MPI_COMM_NULL, -1, -1, CALLER);
	return PMPI_File_read_at_all(f, at, b, n, t, st);
}

int MPI_File_set_view(MPI_File f, MPI_Offset at, MPI_Datatype e, MPI_Datatype ft, const char *rep,
                      MPI_Info i)
{
	note("File_set_view", MPI_COMM_NULL, -1, -1, CALLER);
	return PMPI_File_set_view(f, at, e, ft, rep, i);
}

int MPI_File_set_size(MPI_File f, MPI_Offset n)
{
	note("File_set_size", MPI_COMM_NULL, -1, -1, CALLER);
	return PMPI_File_set_size(f, n);
}

int MPI_File_sync(MPI_File f)
{
	note("File_sync", MPI_COMM_NULL, -1, -1, CALLER);
	return PMPI_File_sync(f);
}
