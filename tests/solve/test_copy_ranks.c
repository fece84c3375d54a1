/* The run file's copy by every rank together (solve/h5mpi.c h5mpi_copy,
 * lib/h5.c h5_copy_shared): files of 0, 1 and 2 bytes, of odd sizes across
 * several pieces and of several default pieces, copied byte for byte over
 * a longer file left in the way, each rank copying its even share; a
 * missing source and a destination that cannot be made fail on every
 * rank, with the same message naming the file. Every rank checks its own
 * result. Usage: test_copy_ranks RANKS DIR (a scratch directory). */
#include <mpi.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "lib/err.h"
#include "lib/h5.h"
#include "solve/h5mpi.h"
#include "tests/bytes.h"
#include "tests/check.h"

static int rank, size;

/* The message of rank 0 is this rank's. */
static int same_message(void)
{
	char msg[1024];
	snprintf(msg, sizeof msg, "%s", err_msg());
	char first[1024];
	memcpy(first, msg, sizeof msg);
	MPI_Bcast(first, sizeof first, MPI_CHAR, 0, MPI_COMM_WORLD);
	return strcmp(first, msg) == 0;
}

/* A copy from `from` to `to` that fails on every rank with the same
 * message, which names `named` and says `says`. */
static void copy_fails(const char *from, const char *to, const char *named, const char *says)
{
	err_clear();
	CHECK(h5mpi_copy(from, to, 1000, NULL) == -1);
	CHECK_CONTAINS(err_msg(), named);
	CHECK_CONTAINS(err_msg(), says);
	CHECK(same_message());
}

/* A copy of n bytes in pieces of piece, through h5mpi_copy, or (piece <
 * 0) through h5_copy_shared. */
static void copy(const char *dir, size_t n, long piece)
{
	char from[1024], to[1024];
	snprintf(from, sizeof from, "%s/from-%zu", dir, n);
	snprintf(to, sizeof to, "%s/to-%zu", dir, n);
	unsigned char *b = bytes(n, (uint32_t)n), *junk = bytes(n + 5000, 7);
	if (rank == 0) {
		put(from, b, n);
		put(to, junk, n + 5000); /* what a killed copy left: longer */
	}
	MPI_Barrier(MPI_COMM_WORLD);
	uint64_t mine = 0;
	if (piece < 0) {
		CHECK(h5_copy_shared(from, to) == 0);
	} else {
		CHECK(h5mpi_copy(from, to, (size_t)piece, &mine) == 0);
		/* Rank r's share: bytes [r n / P, (r + 1) n / P). */
		uint64_t lo = (uint64_t)rank * n / (uint64_t)size;
		uint64_t hi = (uint64_t)(rank + 1) * n / (uint64_t)size;
		CHECK(mine == hi - lo);
		uint64_t all = mine;
		MPI_Allreduce(MPI_IN_PLACE, &all, 1, MPI_UINT64_T, MPI_SUM, MPI_COMM_WORLD);
		CHECK(all == n);
	}
	CHECK(holds(to, b, n));
	free(b);
	free(junk);
}

int main(int argc, char **argv)
{
	MPI_Init(&argc, &argv);
	MPI_Comm_rank(MPI_COMM_WORLD, &rank);
	MPI_Comm_size(MPI_COMM_WORLD, &size);
	CHECK(argc == 3 && size == atoi(argv[1]));
	const char *dir = argc == 3 ? argv[2] : "/tmp";
	if (rank == 0)
		mkdir(dir, 0777);
	MPI_Barrier(MPI_COMM_WORLD);

	/* Fewer bytes than ranks: some ranks copy none. */
	copy(dir, 0, 1000);
	copy(dir, 1, 1000);
	copy(dir, 2, 1000);
	/* Odd sizes, each rank's share several pieces and a part. */
	copy(dir, 10007, 1000);
	copy(dir, 3 * 4096 + 17, 4096);
	/* The default pieces (4 MiB): 9 MiB and an odd tail. */
	copy(dir, (9 << 20) + 3, 0);
	/* The copy lib/h5.c calls, once installed. */
	h5mpi_install();
	copy(dir, 123457, -1);

	/* A missing source: -1 and the same message on every rank. */
	char from[1024], to[1024];
	snprintf(from, sizeof from, "%s/no-such-file", dir);
	snprintf(to, sizeof to, "%s/to-missing", dir);
	copy_fails(from, to, from, "cannot open: No such file or directory");
	err_clear();
	CHECK(h5_copy_shared(from, to) == -1);
	CHECK_CONTAINS(err_msg(), from);
	CHECK(same_message());
	/* A destination in a missing directory. */
	snprintf(from, sizeof from, "%s/from-10007", dir);
	snprintf(to, sizeof to, "%s/no-such-dir/to", dir);
	copy_fails(from, to, to, "cannot create");

	int failed = check_done();
	MPI_Allreduce(MPI_IN_PLACE, &failed, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
	MPI_Finalize();
	return failed;
}
