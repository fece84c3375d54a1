/* The step's reductions: per-block partial sums (blocks.h) added exactly
 * (lib/xsum.h), so the totals are the same to the bit however the blocks
 * are shared among threads (and, under a domain decomposition, ranks) and
 * in whatever order the partial sums meet; with the step's maxima, all of
 * them over the ranks in one collective. */
#ifndef DEM_REDUCE_H
#define DEM_REDUCE_H

#include <stddef.h>

#include "lib/xsum.h"

enum { REDUCE_SUMS = 64, REDUCE_MAXIMA = 8 };

/* Sums and maxima gathered on this rank, then reduced over the ranks at
 * once (reduce_finish). */
typedef struct {
	int nsum, nmax;
	xsum sum[REDUCE_SUMS];
	double max[REDUCE_MAXIMA];
} reduction;

void reduce_clear(reduction *r);
/* nf new sums: the first nf doubles of each of the nb blocks at blk, stride
 * doubles apart. Returns the index of the first. */
int reduce_add_blocks(reduction *r, const double *blk, size_t nb, size_t stride, int nf);
/* The same blocks added to the accumulators acc[0..nf) (a worker's part of
 * the sums: exact, so the parts may be split any way). */
void reduce_part_add(xsum *acc, const double *blk, size_t nb, size_t stride, int nf);
/* nf new sums, each the merge of nparts parts: those of part q start
 * `bytes` bytes after part q - 1's, the first at first. Returns the index
 * of the first. */
int reduce_add_parts(reduction *r, const xsum *first, int nparts, size_t bytes, int nf);
/* v as a new maximum: its index. */
int reduce_add_max(reduction *r, double v);
/* Every sum and every maximum over the ranks (par_sum_max): one collective. */
void reduce_finish(reduction *r);
/* out[f] = sum k + f, rounded to the nearest double, for f < nf. */
void reduce_sums(const reduction *r, int k, int nf, double *out);

/* out[f] = Σ_k blk[k stride + f] for f < nf, over the nb blocks of every
 * rank (par.h), exact and then rounded to the nearest double. */
void reduce_blocks(const double *blk, size_t nb, size_t stride, int nf, double *out);

#endif
