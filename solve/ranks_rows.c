/* A run file's dataset written from the rows every rank holds (ranks.h,
 * ranks_rows_write): the chunks are compressed where their rows are
 * gathered, an even share of them on each rank, and only the compressed
 * chunks reach rank 0, which writes them in order. */
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

enum { TAG_CHUNK = 7, TAG_ROWS = 8 };

#ifdef DEM_MPI

/* The rows each rank gathers: [lo[q], lo[q + 1]), whole chunks of `piece`
 * rows split evenly among the ranks, or every row on rank 0 when the
 * dataset is not written chunk by chunk (piece 0). */
static size_t *gather_bounds(size_t rows, size_t piece, int size)
{
	size_t *lo = xmalloc(((size_t)size + 1) * sizeof *lo);
	size_t nchunks = piece ? (rows + piece - 1) / piece : 0;
	for (int q = 0; q <= size; q++) {
		size_t at = piece ? (size_t)q * nchunks / (size_t)size * piece : q ? rows : 0;
		lo[q] = at < rows ? at : rows;
	}
	return lo;
}

/* This rank's rows, filled, sent to the ranks that gather them: into the
 * returned buffer (rows [lo[rank], lo[rank + 1]), room for whole chunks of
 * `piece` rows). */
static unsigned char *exchange(size_t row, const size_t *lo, size_t piece, size_t mine,
                               size_t first, const int32_t *dest, ranks_fill fill, void *ctx)
{
	int size = par_size(), rank = par_rank();
	size_t have = lo[rank + 1] - lo[rank], room = have;
	if (piece && room % piece)
		room += piece - room % piece;
	unsigned char *own = xmalloc(mine * row + 1), *out = xmalloc(room * row + 1);
	fill(ctx, 0, mine, own);
	int *scnt = xcalloc((size_t)size, sizeof *scnt),
	    *rcnt = xmalloc((size_t)size * sizeof *rcnt);
	int *sdsp = xmalloc((size_t)size * sizeof *sdsp),
	    *rdsp = xmalloc((size_t)size * sizeof *rdsp);
	int *to = xmalloc((mine + 1) * sizeof *to);
	for (size_t k = 0; k < mine; k++) {
		size_t d = dest ? (size_t)dest[k] : first + k;
		to[k] = run_of(lo, size, d);
		scnt[to[k]]++;
	}
	MPI_Alltoall(scnt, 1, MPI_INT, rcnt, 1, MPI_INT, MPI_COMM_WORLD);
	sdsp[0] = rdsp[0] = 0;
	for (int q = 1; q < size; q++) {
		sdsp[q] = sdsp[q - 1] + scnt[q - 1];
		rdsp[q] = rdsp[q - 1] + rcnt[q - 1];
	}
	MPI_Datatype t;
	MPI_Type_contiguous((int)row, MPI_BYTE, &t);
	MPI_Type_commit(&t);
	if (!dest) {
		/* Runs of rows in row order: each rank's items go in rank order,
		 * and arrive in place. */
		MPI_Alltoallv(own, scnt, sdsp, t, out, rcnt, rdsp, t, MPI_COMM_WORLD);
	} else {
		/* Rows anywhere: each goes with its row number, grouped by rank. */
		unsigned char *send = xmalloc(mine * row + 1), *recv = xmalloc(have * row + 1);
		int64_t *sidx = xmalloc((mine + 1) * sizeof *sidx);
		int64_t *ridx = xmalloc((have + 1) * sizeof *ridx);
		int *at = xmalloc((size_t)size * sizeof *at);
		memcpy(at, sdsp, (size_t)size * sizeof *at);
		for (size_t k = 0; k < mine; k++) {
			size_t s = (size_t)at[to[k]]++;
			memcpy(send + s * row, own + k * row, row);
			sidx[s] = dest[k];
		}
		MPI_Alltoallv(sidx, scnt, sdsp, MPI_INT64_T, ridx, rcnt, rdsp, MPI_INT64_T,
		              MPI_COMM_WORLD);
		MPI_Alltoallv(send, scnt, sdsp, t, recv, rcnt, rdsp, t, MPI_COMM_WORLD);
		for (size_t k = 0; k < have; k++)
			memcpy(out + ((size_t)ridx[k] - lo[rank]) * row, recv + k * row, row);
		free(send), free(recv), free(sidx), free(ridx), free(at);
	}
	MPI_Type_free(&t);
	free(own), free(to), free(scnt), free(rcnt), free(sdsp), free(rdsp);
	return out;
}

/* This rank's chunks compressed on the step's threads: chunk c (of n) at
 * z + c * zcap, its bytes and filter mask in meta[2 c], meta[2 c + 1]. */
static void compress_chunks(const engine *e, unsigned char *raw, size_t rows, size_t piece,
                            size_t width, size_t size, unsigned char *z, size_t zcap,
                            uint64_t *meta)
{
	size_t bytes = piece * width * size, n = (rows + piece - 1) / piece;
#pragma omp parallel num_threads(e->team > 0 ? e->team : 1)
	{
		unsigned char *shuf = xmalloc(bytes);
#pragma omp for schedule(dynamic, 1)
		for (size_t c = 0; c < n; c++) {
			size_t m = rows - c * piece < piece ? rows - c * piece : piece;
			unsigned mask;
			const unsigned char *data;
			size_t zn = h5_chunk_compress(raw + c * bytes, shuf, z + c * zcap, piece, m,
			                              width, size, &mask, &data);
			if (data != z + c * zcap)
				memcpy(z + c * zcap, data, zn);
			meta[2 * c] = zn;
			meta[2 * c + 1] = mask;
		}
		free(shuf);
	}
}
#endif

int ranks_rows_write(engine *e, h5_rows *r, size_t rows, size_t cols, size_t size, size_t mine,
                     size_t first, const int32_t *dest, ranks_fill fill, void *ctx)
{
#ifdef DEM_MPI
	int nr = par_size(), rank = par_rank();
	double t0 = timer_now();
	size_t width = cols ? cols : 1, row = width * size, piece = h5_chunk_rows(rows, cols);
	size_t *lo = gather_bounds(rows, piece, nr);
	unsigned char *raw = exchange(row, lo, piece, mine, first, dest, fill, ctx);
	size_t have = lo[rank + 1] - lo[rank];
	int rc = 0;
	if (!piece) {
		/* Rank 0 holds every row: through HDF5's filters. */
		for (size_t at = 0, m; r && (m = h5_rows_piece(r)) > 0 && !rc; at += m)
			rc = h5_rows_put(r, raw + at * row, m);
	} else {
		size_t n = (have + piece - 1) / piece, zcap = h5_chunk_zcap(piece * row);
		unsigned char *z = xmalloc((n ? n : 1) * zcap); /* rank 0 receives into it */
		uint64_t *meta = xmalloc((2 * n + 1) * sizeof *meta);
		compress_chunks(e, raw, have, piece, width, size, z, zcap, meta);
		free(raw);
		raw = NULL;
		if (rank > 0) {
			MPI_Send(meta, (int)(2 * n), MPI_UINT64_T, 0, TAG_CHUNK, MPI_COMM_WORLD);
			for (size_t c = 0; c < n; c++)
				MPI_Send(z + c * zcap, (int)meta[2 * c], MPI_BYTE, 0, TAG_CHUNK,
				         MPI_COMM_WORLD);
		} else {
			/* Rank 0's chunks, then each rank's in turn; after a failed
			 * write the rest are still received. */
			for (size_t c = 0; c < n; c++)
				rc = rc || h5_rows_put_chunk(r, (unsigned)meta[2 * c + 1],
				                             (size_t)meta[2 * c], z + c * zcap);
			for (int q = 1; q < nr; q++) {
				size_t nq = (lo[q + 1] - lo[q] + piece - 1) / piece;
				meta = xrealloc(meta, (2 * nq + 1) * sizeof *meta);
				MPI_Recv(meta, (int)(2 * nq), MPI_UINT64_T, q, TAG_CHUNK,
				         MPI_COMM_WORLD, MPI_STATUS_IGNORE);
				for (size_t c = 0; c < nq; c++) {
					MPI_Recv(z, (int)meta[2 * c], MPI_BYTE, q, TAG_CHUNK,
					         MPI_COMM_WORLD, MPI_STATUS_IGNORE);
					rc = rc || h5_rows_put_chunk(r, (unsigned)meta[2 * c + 1],
					                             (size_t)meta[2 * c], z);
				}
			}
		}
		free(z), free(meta);
	}
	free(raw), free(lo);
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
	unsigned char *buf = xmalloc(piece * row);
	int rank = par_rank(), rc = rank == 0 && d < 0;
	double t0 = timer_now();
	size_t at = 0;
	for (size_t k0 = 0, m; rank == 0 && k0 < mine; k0 += m) {
		m = mine - k0 < piece ? mine - k0 : piece;
		fill(ctx, k0, m, buf);
		rc = rc || h5_slab(d, type, at, m, cols, buf, 1);
		at += m;
	}
#ifdef DEM_MPI
	int size = par_size();
	if (size > 1) {
		/* Rank 0 receives the others' rows in rank order, a piece at a
		 * time; after a failed write the rest are still received. */
		uint64_t own = mine, *cnt = xmalloc((size_t)size * sizeof *cnt);
		ranks_gather_u64(&own, 1, cnt);
		for (int q = 1; rank == 0 && q < size; q++)
			for (size_t k0 = 0, m; k0 < cnt[q]; k0 += m) {
				m = cnt[q] - k0 < piece ? cnt[q] - k0 : piece;
				MPI_Recv(buf, (int)(m * row), MPI_BYTE, q, TAG_ROWS, MPI_COMM_WORLD,
				         MPI_STATUS_IGNORE);
				rc = rc || h5_slab(d, type, at, m, cols, buf, 1);
				at += m;
			}
		for (size_t k0 = 0, m; rank > 0 && k0 < mine; k0 += m) {
			m = mine - k0 < piece ? mine - k0 : piece;
			fill(ctx, k0, m, buf);
			MPI_Send(buf, (int)(m * row), MPI_BYTE, 0, TAG_ROWS, MPI_COMM_WORLD);
		}
		free(cnt);
	}
#endif
	free(buf);
	e->ranks.sec[RANKS_GATHERS] += timer_now() - t0;
	return rc ? -1 : 0;
}
