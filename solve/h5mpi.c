/* What lib/h5.c needs from MPI and parallel HDF5 to write solve's run file
 * on every rank together (h5_procs): compiled, alone, against the parallel
 * build's headers, and linked into solve only. */
#include <hdf5.h>
#include <mpi.h>

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

void h5mpi_install(void)
{
	static h5_procs p = {.fapl = fapl, .dxpl = dxpl, .bcast = bcast, .sum = sum};
	int up = 0;
	MPI_Initialized(&up);
	if (!up)
		return;
	MPI_Comm_rank(MPI_COMM_WORLD, &p.rank);
	MPI_Comm_size(MPI_COMM_WORLD, &p.size);
	h5_set_procs(&p);
}
