/* The ranks of a run (par.h). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#ifdef DEM_MPI
#include <mpi.h>
#endif

#include "lib/err.h"
#include "lib/timer.h"
#include "solve/par.h"

static int rank_, size_ = 1;
static par_tally tally_;
#ifdef DEM_MPI
static int mpi_; /* MPI_Init was called */

/* A rank that exits before par_finalize (an error, fatal()) takes the
 * others down with it, instead of leaving them waiting in a collective. */
static void abort_unfinished(void)
{
	if (mpi_ && size_ > 1)
		MPI_Abort(MPI_COMM_WORLD, 1);
}

/* Before a rank's error message: an error every rank finds alike (a bad
 * input) is printed once, by rank 0, whose exit stops the others while
 * they wait here; an error of one rank alone is printed after the wait,
 * naming the rank. */
static void fatal_on_rank(void)
{
	static char name[64];
	if (rank_ == 0)
		return;
	struct timespec wait = {.tv_sec = 2};
	nanosleep(&wait, NULL);
	snprintf(name, sizeof name, "%s (rank %d of %d)", err_program_name(), rank_, size_);
	err_program(name);
}
#endif

int par_launcher_size(void)
{
	static const char *vars[] = {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE"};
	for (size_t k = 0; k < sizeof vars / sizeof vars[0]; k++) {
		const char *v = getenv(vars[k]);
		if (v && *v)
			return atoi(v) > 0 ? atoi(v) : 1;
	}
	return 0;
}

int par_init(int *argc, char ***argv)
{
	int launched = par_launcher_size();
#ifdef DEM_MPI
	/* A plain `solve` does not start MPI at all: it runs as before,
	 * without MPI's start-up time. */
	if (launched) {
		int provided;
		MPI_Init_thread(argc, argv, MPI_THREAD_FUNNELED, &provided);
		mpi_ = 1;
		MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
		MPI_Comm_size(MPI_COMM_WORLD, &size_);
		atexit(abort_unfinished);
		if (size_ > 1)
			err_fatal_hook(fatal_on_rank);
	}
	return 0;
#else
	(void)argc, (void)argv;
	if (launched > 1)
		return err_set("started as %d processes by a launcher (mpirun?), but this solve "
		               "was built without MPI: install OpenMPI (tools/deps) and rebuild "
		               "(tools/build), or run it as one process",
		               launched);
	return 0;
#endif
}

void par_finalize(void)
{
#ifdef DEM_MPI
	if (mpi_)
		MPI_Finalize();
	mpi_ = 0;
#endif
}

int par_rank(void) { return rank_; }
int par_size(void) { return size_; }

par_tally par_reductions(void) { return tally_; }
void par_tally_reset(void) { tally_ = (par_tally){0}; }

#ifdef DEM_MPI
/* Every reduction: counted and timed (a clock read each side, some 50 ns
 * against the microseconds of an MPI_Allreduce). */
static void reduce(void *v, int n, MPI_Datatype type, size_t width, MPI_Op op)
{
	if (size_ == 1)
		return;
	double t0 = timer_now();
	MPI_Allreduce(MPI_IN_PLACE, v, n, type, op, MPI_COMM_WORLD);
	tally_.seconds += timer_now() - t0;
	tally_.calls++;
	tally_.bytes += (double)n * (double)width;
}
#endif

void par_sum(xsum *a, int n)
{
	if (size_ == 1)
		return;
	for (int k = 0; k < n; k++)
		xsum_normalize(&a[k]);
#ifdef DEM_MPI
	reduce(a, n * DEM_XSUM_WORDS, MPI_INT64_T, sizeof(int64_t), MPI_SUM);
#endif
}

#ifdef DEM_MPI
/* par_sum_max's operation, on elements that are each a whole buffer of
 * int64 words (so that MPI never splits one): the count W of summed words,
 * W words summed, then doubles (their bits) of which the larger is kept, as
 * MPI_MAX keeps it. */
static void sum_max_op(void *in, void *inout, int *len, MPI_Datatype *type)
{
	int size;
	MPI_Type_size(*type, &size);
	size_t words = (size_t)size / sizeof(int64_t);
	for (int el = 0; el < *len; el++) {
		const int64_t *a = (const int64_t *)in + (size_t)el * words;
		int64_t *b = (int64_t *)inout + (size_t)el * words;
		size_t w = (size_t)a[0];
		for (size_t k = 1; k <= w; k++)
			b[k] += a[k];
		for (size_t k = w + 1; k < words; k++) {
			double x, y;
			memcpy(&x, &a[k], sizeof x);
			memcpy(&y, &b[k], sizeof y);
			if (x > y)
				b[k] = a[k];
		}
	}
}
#endif

void par_sum_max(xsum *a, int n, double *mx, int m)
{
	if (size_ == 1)
		return;
#ifdef DEM_MPI
	static MPI_Op op;
	static int made;
	if (!made)
		MPI_Op_create(sum_max_op, 1, &op), made = 1;
	size_t w = (size_t)n * DEM_XSUM_WORDS, len = 1 + w + (size_t)m;
	int64_t *buf = xmalloc(len * sizeof *buf);
	buf[0] = (int64_t)w;
	for (int k = 0; k < n; k++) {
		xsum_normalize(&a[k]);
		memcpy(buf + 1 + (size_t)k * DEM_XSUM_WORDS, a[k].d, sizeof a[k].d);
	}
	memcpy(buf + 1 + w, mx, (size_t)m * sizeof *mx);
	MPI_Datatype whole;
	MPI_Type_contiguous((int)len, MPI_INT64_T, &whole);
	MPI_Type_commit(&whole);
	reduce(buf, 1, whole, len * sizeof *buf, op);
	MPI_Type_free(&whole);
	for (int k = 0; k < n; k++)
		memcpy(a[k].d, buf + 1 + (size_t)k * DEM_XSUM_WORDS, sizeof a[k].d);
	memcpy(mx, buf + 1 + w, (size_t)m * sizeof *mx);
	free(buf);
#else
	(void)a, (void)n, (void)mx, (void)m;
#endif
}

void par_sum_u64(uint64_t *v, size_t n)
{
#ifdef DEM_MPI
	reduce(v, (int)n, MPI_UINT64_T, sizeof *v, MPI_SUM);
#else
	(void)v, (void)n;
#endif
}

size_t par_alltoall_rows(const void *send, const size_t *count, size_t row, void **recv)
{
	size_t mine = size_ == 1 ? count[0] : 0;
#ifdef DEM_MPI
	if (size_ > 1) {
		int64_t *sn = xmalloc(4 * (size_t)size_ * sizeof *sn), *rn = sn + size_;
		int *c = xmalloc(4 * (size_t)size_ * sizeof *c);
		int *sc = c, *sd = c + size_, *rc = c + 2 * size_, *rd = c + 3 * size_;
		for (int q = 0; q < size_; q++)
			sn[q] = (int64_t)count[q];
		MPI_Alltoall(sn, 1, MPI_INT64_T, rn, 1, MPI_INT64_T, MPI_COMM_WORLD);
		for (int q = 0, s = 0; q < size_; q++) {
			if (sn[q] > INT32_MAX || rn[q] > INT32_MAX ||
			    mine + (size_t)rn[q] > INT32_MAX || s + sn[q] > INT32_MAX)
				fatal("par_alltoall_rows: more than 2^31 rows to or from a rank");
			sc[q] = (int)sn[q], sd[q] = s, s += sc[q];
			rc[q] = (int)rn[q], rd[q] = (int)mine, mine += (size_t)rn[q];
		}
		*recv = xmalloc((mine + 1) * row);
		MPI_Datatype t;
		MPI_Type_contiguous((int)row, MPI_BYTE, &t);
		MPI_Type_commit(&t);
		MPI_Alltoallv(send, sc, sd, t, *recv, rc, rd, t, MPI_COMM_WORLD);
		MPI_Type_free(&t);
		free(sn), free(c);
		return mine;
	}
#endif
	*recv = xmalloc((mine + 1) * row);
	memcpy(*recv, send, mine * row);
	return mine;
}

size_t par_send_rows(const void *rows, const int *to, size_t n, size_t row, void **recv)
{
	size_t *count = xcalloc((size_t)size_, sizeof *count);
	size_t *at = xcalloc((size_t)size_ + 1, sizeof *at);
	for (size_t k = 0; k < n; k++)
		if (to[k] >= 0)
			count[to[k]]++;
	for (int q = 0; q < size_; q++)
		at[q + 1] = at[q] + count[q];
	unsigned char *by = xmalloc(at[size_] * row + 1);
	for (size_t k = 0; k < n; k++) /* by rank, each in order */
		if (to[k] >= 0)
			memcpy(by + at[to[k]]++ * row, (const unsigned char *)rows + k * row, row);
	size_t m = par_alltoall_rows(by, count, row, recv);
	free(by), free(count), free(at);
	return m;
}

#ifdef DEM_MPI
void par_max(double *v, int n) { reduce(v, n, MPI_DOUBLE, sizeof *v, MPI_MAX); }
void par_min(double *v, int n) { reduce(v, n, MPI_DOUBLE, sizeof *v, MPI_MIN); }
void par_max_int(int *v, int n) { reduce(v, n, MPI_INT, sizeof *v, MPI_MAX); }
void par_maxloc(double *v, int32_t *at, size_t n)
{
	if (size_ == 1)
		return;
	struct {
		double v;
		int at;
	} *pair = xmalloc((n + 1) * sizeof *pair);
	for (size_t k = 0; k < n; k++) {
		pair[k].v = v[k];
		pair[k].at = at[k];
	}
	reduce(pair, (int)n, MPI_DOUBLE_INT, sizeof(double) + sizeof(int), MPI_MAXLOC);
	for (size_t k = 0; k < n; k++) {
		v[k] = pair[k].v;
		at[k] = pair[k].at;
	}
	free(pair);
}
#else
void par_maxloc(double *v, int32_t *at, size_t n) { (void)v, (void)at, (void)n; }
void par_max(double *v, int n) { (void)v, (void)n; }
void par_min(double *v, int n) { (void)v, (void)n; }
void par_max_int(int *v, int n) { (void)v, (void)n; }
#endif
