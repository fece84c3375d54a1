/* A run file's dataset written from the rows every rank holds (ranks.h,
 * ranks_rows_write): the rows of each chunk are gathered on one rank, an
 * even share of the chunks on each, which writes them (parallel HDF5). */
#include <stdlib.h>
#include <string.h>

#ifdef DEM_MPI
#include <mpi.h>
#endif

#include "lib/err.h"
#include "lib/h5.h"
#include "lib/timer.h"
#include "solve/blocks.h"
#include "solve/engine.h"
#include "solve/par.h"
#include "solve/ranks.h"

#ifdef DEM_MPI
/* The chunks a rank writes in a round: 16, or DEM_ROWS_ROUND from the
 * environment (the same on every rank; a check of the rounds' bookkeeping
 * with small datasets). */
static size_t round_chunks(void)
{
	const char *s = getenv("DEM_ROWS_ROUND");
	long n = s ? atol(s) : 0;
	return n > 0 ? (size_t)n : 16;
}

/* The items a round sends: positions [s0, s1) of this rank's items sorted
 * by row (item order[s], or s when order is NULL), item k at row dest[k]
 * (first + k when dest is NULL), filled by fill. */
typedef struct {
	size_t s0, s1, first;
	const size_t *order;
	const int32_t *dest;
	ranks_fill fill;
	void *ctx;
} items;

static size_t item_of(const items *it, size_t s) { return it->order ? it->order[s] : s; }

static size_t row_of(const items *it, size_t k)
{
	return it->dest ? (size_t)it->dest[k] : it->first + k;
}

/* The items' rows sent to the ranks that gather them, rank q rows [lo[q],
 * lo[q + 1]): this rank's into the returned buffer (room for whole chunks
 * of `piece` rows), those it holds itself filled in place. The bytes
 * received are added to *recv_bytes. */
static unsigned char *exchange(size_t row, const size_t *lo, size_t piece, const items *it,
                               double *recv_bytes)
{
	int size = par_size(), rank = par_rank();
	size_t have = lo[rank + 1] - lo[rank], room = have, mine = it->s1 - it->s0;
	if (piece && room % piece)
		room += piece - room % piece;
	unsigned char *out = xmalloc(room * row + 1);
	int *scnt = xcalloc((size_t)size, sizeof *scnt),
	    *rcnt = xmalloc((size_t)size * sizeof *rcnt);
	int *sdsp = xmalloc((size_t)size * sizeof *sdsp),
	    *rdsp = xmalloc((size_t)size * sizeof *rdsp);
	for (size_t s = it->s0; s < it->s1; s++)
		scnt[run_of(lo, size, row_of(it, item_of(it, s)))]++;
	size_t keep = (size_t)scnt[rank];
	scnt[rank] = 0;
	MPI_Alltoall(scnt, 1, MPI_INT, rcnt, 1, MPI_INT, MPI_COMM_WORLD);
	sdsp[0] = rdsp[0] = 0;
	for (int q = 1; q < size; q++) {
		sdsp[q] = sdsp[q - 1] + scnt[q - 1];
		rdsp[q] = rdsp[q - 1] + rcnt[q - 1];
	}
	size_t nrecv = have - keep;
	unsigned char *send = xmalloc((mine - keep) * row + 1), *recv = xmalloc(nrecv * row + 1);
	/* Items in row order (no order, no dest) send each rank one run of
	 * rows: its first row, per rank; else each row's. */
	int runs = !it->order && !it->dest;
	size_t nidx = runs ? (size_t)size : mine - keep, ridx_n = runs ? (size_t)size : nrecv;
	int64_t *sidx = xmalloc((nidx + 1) * sizeof *sidx);
	int64_t *ridx = xmalloc((ridx_n + 1) * sizeof *ridx);
	for (size_t q = 0; runs && q < (size_t)size; q++)
		sidx[q] = -1;
	/* In row order: the rows of earlier ranks, this rank's own, then
	 * later ranks'. A run of consecutive items is filled at once. */
	size_t ns = 0;
	for (size_t s = it->s0, m; s < it->s1; s += m) {
		size_t k = item_of(it, s), at = row_of(it, k);
		int q = run_of(lo, size, at);
		for (m = 1; s + m < it->s1 && runs && at + m < lo[q + 1]; m++)
			;
		unsigned char *to = q == rank ? out + (at - lo[rank]) * row : send + ns * row;
		it->fill(it->ctx, k, m, to);
		if (q == rank)
			continue;
		if (runs && sidx[q] < 0)
			sidx[q] = (int64_t)at;
		for (size_t u = 0; !runs && u < m; u++)
			sidx[ns + u] = (int64_t)(at + u);
		ns += m;
	}
	MPI_Datatype t;
	MPI_Type_contiguous((int)row, MPI_BYTE, &t);
	MPI_Type_commit(&t);
	if (runs)
		MPI_Alltoall(sidx, 1, MPI_INT64_T, ridx, 1, MPI_INT64_T, MPI_COMM_WORLD);
	else
		MPI_Alltoallv(sidx, scnt, sdsp, MPI_INT64_T, ridx, rcnt, rdsp, MPI_INT64_T,
		              MPI_COMM_WORLD);
	MPI_Alltoallv(send, scnt, sdsp, t, recv, rcnt, rdsp, t, MPI_COMM_WORLD);
	MPI_Type_free(&t);
	if (runs) {
		for (int q = 0; q < size; q++)
			if (rcnt[q])
				memcpy(out + ((size_t)ridx[q] - lo[rank]) * row,
				       recv + (size_t)rdsp[q] * row, (size_t)rcnt[q] * row);
	} else {
		for (size_t k = 0; k < nrecv; k++)
			memcpy(out + ((size_t)ridx[k] - lo[rank]) * row, recv + k * row, row);
	}
	*recv_bytes += (double)(nrecv * row);
	free(send), free(recv), free(sidx), free(ridx);
	free(scnt), free(rcnt), free(sdsp), free(rdsp);
	return out;
}

/* One round of chunks: rank q gathers the rows [lo[q], lo[q + 1]) and
 * writes them, every rank together (HDF5 compresses each chunk where it
 * is written). */
static int write_round(engine *e, h5_rows *r, const size_t *lo, size_t piece, size_t row,
                       const items *it)
{
	int rank = par_rank();
	unsigned char *raw = exchange(row, lo, piece, it, &e->ranks.recv_all);
	int rc = h5_rows_write_at(r, lo[rank], lo[rank + 1] - lo[rank], raw);
	free(raw);
	return rc;
}

static const int32_t *sort_dest;
static int by_dest(const void *a, const void *b)
{
	int32_t x = sort_dest[*(const size_t *)a], y = sort_dest[*(const size_t *)b];
	return (x > y) - (x < y);
}
#endif

int ranks_rows_write(engine *e, h5_rows *r, size_t rows, size_t cols, size_t size, size_t mine,
                     size_t first, const int32_t *dest, ranks_fill fill, void *ctx)
{
#ifdef DEM_MPI
	int nr = par_size(), rc = 0;
	double t0 = timer_now();
	size_t width = cols ? cols : 1, row = width * size, piece = h5_chunk_rows(rows, cols);
	items it = {0, mine, first, NULL, dest, fill, ctx};
	size_t *lo = xmalloc(((size_t)nr + 1) * sizeof *lo);
	if (!piece) {
		/* Every row to rank 0, which writes them. */
		for (int q = 0; q <= nr; q++)
			lo[q] = q ? rows : 0;
		rc = write_round(e, r, lo, 0, row, &it);
	} else {
		/* Rounds of a few chunks a rank, so that no rank holds more than
		 * those and what it sends: its items in row order, each round
		 * taking the next of them. */
		size_t *order = NULL;
		if (dest) {
			order = xmalloc((mine + 1) * sizeof *order);
			for (size_t k = 0; k < mine; k++)
				order[k] = k;
			sort_dest = dest;
			qsort(order, mine, sizeof *order, by_dest);
			it.order = order;
		}
		size_t nchunks = (rows + piece - 1) / piece;
		size_t each = round_chunks();
		for (size_t c0 = 0, nc; c0 < nchunks; c0 += nc) {
			/* This round's chunks, split evenly among the ranks. */
			nc = nchunks - c0 < each * (size_t)nr ? nchunks - c0 : each * (size_t)nr;
			for (int q = 0; q <= nr; q++) {
				size_t at = (c0 + (size_t)q * nc / (size_t)nr) * piece;
				lo[q] = at < rows ? at : rows;
			}
			for (it.s1 = it.s0;
			     it.s1 < mine && row_of(&it, item_of(&it, it.s1)) < lo[nr];)
				it.s1++;
			rc = write_round(e, r, lo, piece, row, &it) || rc;
			it.s0 = it.s1;
		}
		free(order);
	}
	free(lo);
	e->ranks.sec[RANKS_GATHERS] += timer_now() - t0;
	return rc ? -1 : 0;
#else
	(void)e, (void)r, (void)rows, (void)cols, (void)size, (void)mine, (void)first, (void)dest,
	    (void)fill, (void)ctx;
	return err_set("ranks_rows_write: solve is built without MPI");
#endif
}

size_t ranks_total(size_t mine)
{
	if (par_size() == 1)
		return mine;
	xsum s;
	xsum_clear(&s);
	xsum_add(&s, (double)mine);
	par_sum(&s, 1);
	return (size_t)xsum_round(&s);
}

void ranks_gather_u64(const uint64_t *mine, size_t n, uint64_t *all)
{
#ifdef DEM_MPI
	if (par_size() > 1) {
		MPI_Gather(mine, (int)n, MPI_UINT64_T, all, (int)n, MPI_UINT64_T, 0,
		           MPI_COMM_WORLD);
		return;
	}
#endif
	memcpy(all, mine, n * sizeof *all);
}

int ranks_rows_put(engine *e, hid_t d, hid_t type, size_t cols, size_t mine, ranks_fill fill,
                   void *ctx)
{
	size_t width = cols ? cols : 1, row = width * H5Tget_size(type);
	size_t piece = H5_PIECE_ELEMENTS / width;
	double t0 = timer_now();
	/* This rank's rows follow those of the ranks before it. */
	uint64_t at = 0;
#ifdef DEM_MPI
	if (par_size() > 1) {
		uint64_t own = mine;
		MPI_Exscan(&own, &at, 1, MPI_UINT64_T, MPI_SUM, MPI_COMM_WORLD);
		if (par_rank() == 0)
			at = 0;
	}
#endif
	/* Each rank looks up the chunks of its own rows (h5_settle). */
	h5_settle(d);
	unsigned char *buf = xmalloc(piece * row);
	int rc = 0;
	for (size_t k0 = 0, m; !rc && k0 < mine; k0 += m) {
		m = mine - k0 < piece ? mine - k0 : piece;
		fill(ctx, k0, m, buf);
		rc = h5_slab(d, type, at + k0, m, cols, buf, 1);
	}
	free(buf);
	e->ranks.sec[RANKS_GATHERS] += timer_now() - t0;
	return rc ? -1 : 0;
}
