/* Seeded pseudo-random numbers that give the same stream on every platform:
 * xoshiro256** (Blackman & Vigna) seeded through splitmix64. Integer
 * arithmetic only up to the final conversion to double, which is exact. */
#ifndef DEM_RNG_H
#define DEM_RNG_H

#include <stdint.h>

typedef struct {
	uint64_t s[4];
} rng;

void rng_seed(rng *g, uint64_t seed);
/* An independent stream number k of the same seed (e.g. one per thread or
 * per cell), so results do not depend on the order work is done in. */
void rng_seed_stream(rng *g, uint64_t seed, uint64_t k);
uint64_t rng_u64(rng *g);
/* Uniform in [0, 1) with 53 random bits. */
double rng_uniform(rng *g);
/* Uniform in [a, b). */
double rng_range(rng *g, double a, double b);
/* Standard normal (Marsaglia polar method). */
double rng_normal(rng *g);

#endif
