/* solve's run file written by every rank together (h5mpi.c; a solve built
 * with MPI). */
#ifndef DEM_H5MPI_H
#define DEM_H5MPI_H

#include <stddef.h>
#include <stdint.h>

/* Hand lib/h5.c what a file shared by the ranks needs, once MPI is up
 * (nothing with one process, or without MPI). */
void h5mpi_install(void);

/* The copy of h5_procs (lib/h5.h): rank r of P copies the bytes
 * [r n / P, (r + 1) n / P) of from's n (rounded down: the shares differ by
 * a byte at most) into to, in pieces of at most piece bytes (0:
 * H5MPI_PIECE), through MPI-IO on MPI_COMM_WORLD; to then has n bytes.
 * *mine (when not NULL) is what this rank copied. Every rank calls it; 0,
 * or -1 on every rank with the message of the first rank that failed,
 * which names the file. */
enum { H5MPI_PIECE = 4 << 20 };
int h5mpi_copy(const char *from, const char *to, size_t piece, uint64_t *mine);

#endif
