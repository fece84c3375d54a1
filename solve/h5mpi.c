/* What lib/h5.c needs from MPI and parallel HDF5 to write solve's run file
 * on every rank together (h5_procs): compiled, alone, against the parallel
 * build's headers, and linked into solve only. */
#include <errno.h>
#include <hdf5.h>
#include <mpi.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lib/err.h"
#include "lib/h5.h"
#include "solve/h5mpi.h"

/* Every rank opens the file (MPI-IO); the metadata is read by one rank and
 * broadcast, and written collectively, rather than by every rank in small
 * pieces (what thousands of ranks need). */
static hid_t fapl(void)
{
	hid_t p = H5Pcreate(H5P_FILE_ACCESS);
	H5Pset_fapl_mpio(p, MPI_COMM_WORLD, MPI_INFO_NULL);
	H5Pset_all_coll_metadata_ops(p, 1);
	H5Pset_coll_metadata_write(p, 1);
	return p;
}

static hid_t dxpl(void)
{
	hid_t p = H5Pcreate(H5P_DATASET_XFER);
	H5Pset_dxpl_mpio(p, H5FD_MPIO_COLLECTIVE);
	return p;
}

static void bcast(void *buf, size_t n)
{
	for (size_t at = 0, m; at < n; at += m) {
		m = n - at < (1u << 30) ? n - at : (1u << 30);
		MPI_Bcast((char *)buf + at, (int)m, MPI_BYTE, 0, MPI_COMM_WORLD);
	}
}

static void sum(uint64_t *v, size_t n)
{
	MPI_Allreduce(MPI_IN_PLACE, v, (int)n, MPI_UINT64_T, MPI_SUM, MPI_COMM_WORLD);
}

/* The first byte of rank r's share of n bytes among p: floor(r n / p),
 * without forming r n. */
static MPI_Offset share_start(MPI_Offset n, int r, int p) { return r * (n / p) + r * (n % p) / p; }

/* Why an MPI-IO call failed with error code e: as strerror says it where
 * its class is an errno's (MPI 4.0, 14.7.6, the I/O error classes), else
 * as the MPI library says it (in buf). */
static const char *why(int e, char buf[MPI_MAX_ERROR_STRING])
{
	int c = MPI_ERR_OTHER;
	MPI_Error_class(e, &c);
	int no = c == MPI_ERR_NO_SUCH_FILE ? ENOENT
	         : c == MPI_ERR_ACCESS     ? EACCES
	         : c == MPI_ERR_NO_SPACE   ? ENOSPC
	         : c == MPI_ERR_QUOTA      ? EDQUOT
	         : c == MPI_ERR_READ_ONLY  ? EROFS
	                                   : 0;
	if (no)
		return strerror(no);
	int len = 0;
	MPI_Error_string(e, buf, &len);
	return buf;
}

/* rc of every rank agreed: -1 on each when any failed, with the message
 * of the first that did (err_msg there) on each. */
static int agree(int rc)
{
	int rank, size;
	MPI_Comm_rank(MPI_COMM_WORLD, &rank);
	MPI_Comm_size(MPI_COMM_WORLD, &size);
	int first = rc ? rank : size;
	MPI_Allreduce(MPI_IN_PLACE, &first, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
	if (first == size)
		return 0;
	char msg[2048];
	if (rank == first)
		snprintf(msg, sizeof msg, "%s", err_msg());
	MPI_Bcast(msg, sizeof msg, MPI_CHAR, first, MPI_COMM_WORLD);
	return err_set("%s", msg);
}

/* Every file error is returned (files' default error handler, MPI 4.0,
 * 14.7), to be agreed on. The source is complete on disk: its writers
 * synced it (H5Fflush: MPI_File_sync) before the barrier, which orders
 * their writes before these reads (MPI 4.0, 14.6.1, sync-barrier). Rank 0
 * created to (afile_begin_shared) before the others came here; the
 * others only open it. */
int h5mpi_copy(const char *from, const char *to, size_t piece, uint64_t *mine)
{
	int rank, size;
	MPI_Comm_rank(MPI_COMM_WORLD, &rank);
	MPI_Comm_size(MPI_COMM_WORLD, &size);
	/* Each piece's count is an int (below 2^31). */
	piece = piece == 0 || piece > (1u << 30) ? H5MPI_PIECE : piece;
	if (mine)
		*mine = 0;
	MPI_Barrier(MPI_COMM_WORLD);
	char buf[MPI_MAX_ERROR_STRING];
	MPI_File in, out;
	/* A file that some ranks can open and others cannot (a directory
	 * not shared) is an error MPI_File_open does not survive everywhere:
	 * ROMIO fails on every rank, Open MPI 4.1's OMPIO stalls inside it
	 * (seen with a path missing on one rank of 3), as it would in
	 * H5Fcreate of the run file, in the same directory, earlier, had
	 * h5_begin_shared not found first that some rank does not see the
	 * file rank 0 made (lib/h5.c, seen_by_all). A rank
	 * whose open succeeded while another's failed therefore leaves its
	 * handle open: its close would wait for the others. */
	int e = MPI_File_open(MPI_COMM_WORLD, from, MPI_MODE_RDONLY, MPI_INFO_NULL, &in);
	int rc = e ? err_set("%s: cannot open: %s", from, why(e, buf)) : 0;
	if (agree(rc))
		return -1;
	e = MPI_File_open(MPI_COMM_WORLD, to, MPI_MODE_WRONLY | MPI_MODE_CREATE, MPI_INFO_NULL,
	                  &out);
	rc = e ? err_set("%s: cannot create: %s", to, why(e, buf)) : 0;
	if (agree(rc)) {
		MPI_File_close(&in);
		return -1;
	}
	/* The size is rank 0's (every rank reads the same file). */
	MPI_Offset n = 0;
	e = rank == 0 ? MPI_File_get_size(in, &n) : MPI_SUCCESS;
	MPI_Bcast(&n, 1, MPI_OFFSET, 0, MPI_COMM_WORLD);
	rc = e ? err_set("%s: cannot read its size: %s", from, why(e, buf)) : 0;
	/* to may be longer (an earlier copy's, left by a kill). */
	e = MPI_File_set_size(out, n);
	rc = rc || (e && err_set("%s: cannot write a copy of %s: %s", to, from, why(e, buf)));
	MPI_Offset at = share_start(n, rank, size), end = share_start(n, rank + 1, size);
	char *b = at < end ? xmalloc(piece) : NULL;
	while (!rc && at < end) {
		int m = end - at < (MPI_Offset)piece ? (int)(end - at) : (int)piece, got = 0;
		MPI_Status st;
		e = MPI_File_read_at(in, at, b, m, MPI_BYTE, &st);
		if (!e)
			MPI_Get_count(&st, MPI_BYTE, &got);
		if (e || got != m) {
			rc = err_set("%s: cannot read bytes %lld to %lld: %s", from, (long long)at,
			             (long long)at + m, e ? why(e, buf) : "the file ends before");
			break;
		}
		e = MPI_File_write_at(out, at, b, m, MPI_BYTE, &st);
		if (!e)
			MPI_Get_count(&st, MPI_BYTE, &got);
		if (e || got != m) {
			rc = err_set("%s: cannot write a copy of %s: %s", to, from,
			             e ? why(e, buf) : "a short write");
			break;
		}
		at += m;
		if (mine)
			*mine += (uint64_t)m;
	}
	free(b);
	/* Collective: every rank comes here, failed or not. */
	e = MPI_File_sync(out);
	rc = rc || (e && err_set("%s: cannot sync: %s", to, why(e, buf)));
	e = MPI_File_close(&out);
	rc = rc || (e && err_set("%s: cannot write a copy of %s: %s", to, from, why(e, buf)));
	MPI_File_close(&in);
	/* After every rank's close: rank 0 may then read to on its own. */
	return agree(rc);
}

static int copy(const char *from, const char *to) { return h5mpi_copy(from, to, 0, NULL); }

void h5mpi_install(void)
{
	static h5_procs p = {.fapl = fapl, .dxpl = dxpl, .bcast = bcast, .sum = sum, .copy = copy};
	int up = 0;
	MPI_Initialized(&up);
	if (!up)
		return;
	MPI_Comm_rank(MPI_COMM_WORLD, &p.rank);
	MPI_Comm_size(MPI_COMM_WORLD, &p.size);
	h5_set_procs(&p);
}
