/* The Morton (Z-order) curve, shared by pack and solve to lay points out so
 * that neighbours in space sit near each other in memory: a point's key
 * interleaves the bits of its grid cell's three coordinates, and points go
 * in key order. How positions map to cells stays with each caller (pack
 * cuts a given box into 2^10 cells per edge, solve scales the particles'
 * bounding cube to coordinates 0 to 2^21 - 1), since the order decides the
 * bits of their results. */
#ifndef DEM_MORTON_H
#define DEM_MORTON_H

#include <stddef.h>
#include <stdint.h>

#define MORTON_BITS 21 /* per coordinate: three of them fill a 64-bit key */

/* The key of the cell at coordinates c (only their low MORTON_BITS bits
 * count): bit b of c[d] becomes bit 3 b + d. */
uint64_t morton_key(const uint64_t c[3]);

/* order[k] = the index i of the k-th smallest of key[0..n); equal keys keep
 * index order, so the order is the same whatever the sort. */
void morton_sort(const uint64_t *key, size_t n, size_t *order);

#endif
