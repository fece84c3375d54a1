/* Points in the order of a Morton (Z-order) curve over a box (lib/morton.h),
 * so that neighbours in space sit near each other in memory. */
#ifndef PACK_MORTON_H
#define PACK_MORTON_H

#include <stddef.h>

/* order[k] = index (into x, [n][3]) of the k-th point along the curve over
 * the box [lo, hi] cut into 2^10 cells per edge (points outside it count
 * in the nearest cell); ties keep index order. */
void morton_order(const double *x, size_t n, const double lo[3], const double hi[3], size_t *order);

#endif
