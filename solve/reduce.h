/* The step's reductions: per-block partial sums (blocks.h) added exactly
 * (lib/xsum.h), so the totals are the same to the bit however the blocks
 * are shared among threads (and, under a domain decomposition, ranks) and
 * in whatever order the partial sums meet. */
#ifndef DEM_REDUCE_H
#define DEM_REDUCE_H

#include <stddef.h>

/* out[f] = Σ_k blk[k stride + f] for f < nf, over the nb blocks of every
 * rank (par.h), exact and then rounded to the nearest double. */
void reduce_blocks(const double *blk, size_t nb, size_t stride, int nf, double *out);

#endif
