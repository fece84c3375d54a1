/* Exact sums of doubles, whatever the order of the terms.
 *
 * A sum of floating-point numbers depends on the order in which they are
 * added. The engine's reductions (energies, platen loads, Love–Weber
 * stresses, bond counts) are sums of per-block partial sums; with an exact
 * accumulator their result is the same to the bit however the blocks are
 * shared among threads or, under a domain decomposition, among ranks, and
 * in whatever order the partial accumulators are merged (an MPI_Allreduce
 * with MPI_SUM over the int64 digits of DEM_XSUM_WORDS words).
 *
 * The accumulator is a fixed-point integer in units of 2^-1074, the
 * smallest subnormal double, as 66 signed 32-bit digits held in int64 words,
 * so every finite double adds exactly; NaN and infinities are counted
 * apart. xsum_round returns the exact sum rounded to the nearest double
 * (ties to even), as if it had been computed in infinite precision.
 *
 * A digit gains less than 2^33 in magnitude per xsum_add, so an accumulator
 * takes at least 2^30 terms before xsum_normalize must run, and a
 * normalized accumulator can be merged with up to 2^30 others. */
#ifndef DEM_XSUM_H
#define DEM_XSUM_H

#include <stdint.h>

enum {
	XSUM_DIGITS = 66, /* 32 bits each: 2^-1074 to beyond 2^1024 */
	XSUM_NAN = XSUM_DIGITS,
	XSUM_PINF,
	XSUM_NINF,
	DEM_XSUM_WORDS /* int64 words in an accumulator */
};

typedef struct {
	int64_t d[DEM_XSUM_WORDS];
} xsum;

void xsum_clear(xsum *s);
void xsum_add(xsum *s, double x);
/* Digits 0 .. XSUM_DIGITS - 2 into [0, 2^32), the top digit signed; the
 * value is unchanged. */
void xsum_normalize(xsum *s);
/* a += b, word by word. */
void xsum_merge(xsum *a, const xsum *b);
/* The sum, correctly rounded (NaN when a NaN or both infinities were
 * added, an infinity when one was, or when the sum overflows). */
double xsum_round(const xsum *s);

#endif
