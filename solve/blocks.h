/* Fixed blocks and batches: what keeps the engine's results independent of
 * the number of threads (DESIGN.md §4).
 *
 * Reductions (energies, platen loads, stresses, bond counts) are summed per
 * fixed block of BLOCK items (particles, bonds or contacts), and the block
 * sums are added in block order afterwards, so no sum depends on how the
 * blocks are shared among threads. Inside a block, pairs are handed to the
 * laws BATCH at a time. */
#ifndef DEM_BLOCKS_H
#define DEM_BLOCKS_H

#include <stddef.h>
#include <stdint.h>

#include "solve/clones.h"

enum { BLOCK = 256, BATCH = 32 };

static inline size_t nblocks(size_t n) { return (n + BLOCK - 1) / BLOCK; }

/* End of block k of n items. */
static inline size_t block_end(size_t k, size_t n)
{
	return (k + 1) * BLOCK < n ? (k + 1) * BLOCK : n;
}

/* Of n runs of items starting at first[0..n) (increasing; runs may be
 * empty), the one that holds item p: the last whose first is at most p. */
static inline int run_of(const size_t *first, int n, size_t p)
{
	int lo = 0, hi = n - 1;
	while (lo < hi) {
		int mid = (lo + hi + 1) / 2;
		if (first[mid] <= p)
			lo = mid;
		else
			hi = mid - 1;
	}
	return lo;
}

/* Of the increasing indices a[lo, hi), the first not below g (hi if
 * none). */
static inline size_t first_not_below(const int32_t *a, size_t lo, size_t hi, size_t g)
{
	while (lo < hi) {
		size_t mid = lo + (hi - lo) / 2;
		if ((size_t)a[mid] < g)
			lo = mid + 1;
		else
			hi = mid;
	}
	return lo;
}

#endif
