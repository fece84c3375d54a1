/* The ranks of a run (DESIGN.md §4): MPI processes when solve is built with
 * MPI (DEM_MPI) and started by a launcher such as mpirun, otherwise one.
 *
 * Every reduction over the ranks goes through here: exact sums (lib/xsum.h)
 * whose result does not depend on the number of ranks, maxima and minima. */
#ifndef DEM_PAR_H
#define DEM_PAR_H

#include <stddef.h>
#include <stdint.h>

#include "lib/xsum.h"

/* Join the launcher's ranks, if a launcher started this process: 0, or -1
 * with the message set (lib/err.h) when a launcher asked for several
 * processes and this solve was built without MPI. */
int par_init(int *argc, char ***argv);
void par_finalize(void);
int par_rank(void);
int par_size(void);
/* The process count a launcher announced in the environment (Open MPI's
 * mpirun, or a PMI launcher such as MPICH's or Slurm's), or 0 when none
 * did. */
int par_launcher_size(void);
/* Each of the n accumulators summed over the ranks, in place on every rank
 * (normalized first, xsum.h). */
void par_sum(xsum *a, int n);
/* par_sum of a[0..n) and par_max of mx[0..m) in one collective. */
void par_sum_max(xsum *a, int n, double *mx, int m);
/* The largest (smallest) of each of v[0..n) over the ranks, in place. */
void par_max(double *v, int n);
void par_min(double *v, int n);
/* The largest of each of v[0..n) over the ranks, in place. */
void par_max_int(int *v, int n);
/* For each k < n, the largest v[k] over the ranks and, of the ranks that
 * hold it, the smallest at[k] (MPI_MAXLOC), in place. */
void par_maxloc(double *v, int32_t *at, size_t n);
/* Each of v[0..n) summed over the ranks, in place. */
void par_sum_u64(uint64_t *v, size_t n);
/* Rows of `row` bytes: count[q] of them to rank q, from send in rank
 * order; the rows received, in the order of their ranks, into *recv (the
 * caller's to free): their number. Collective. */
size_t par_alltoall_rows(const void *send, const size_t *count, size_t row, void **recv);
/* The same for n rows of `row` bytes in any order, row k to rank to[k]
 * (none where negative), each rank's in their order. Collective. */
size_t par_send_rows(const void *rows, const int *to, size_t n, size_t row, void **recv);

/* The reductions above (each one MPI_Allreduce) this process took part in
 * since par_tally_reset: their number, their payload (the bytes each rank
 * sends and receives back) and the wall seconds spent in them, waiting for
 * the slowest rank included. None on one rank. */
typedef struct {
	double calls, bytes, seconds;
} par_tally;
par_tally par_reductions(void);
void par_tally_reset(void);

#endif
