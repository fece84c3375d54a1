/* solve's run file written by every rank together (h5mpi.c; a solve built
 * with MPI). */
#ifndef DEM_H5MPI_H
#define DEM_H5MPI_H

/* Hand lib/h5.c what a file shared by the ranks needs, once MPI is up
 * (nothing with one process, or without MPI). */
void h5mpi_install(void);

#endif
