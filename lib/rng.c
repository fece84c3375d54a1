#include <math.h>

#include "lib/rng.h"

static uint64_t splitmix64(uint64_t *x)
{
	uint64_t z = (*x += 0x9e3779b97f4a7c15ULL);
	z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
	z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
	return z ^ (z >> 31);
}

void rng_seed(rng *g, uint64_t seed)
{
	uint64_t x = seed;
	for (int k = 0; k < 4; k++)
		g->s[k] = splitmix64(&x);
}

void rng_seed_stream(rng *g, uint64_t seed, uint64_t k)
{
	uint64_t x = seed ^ (0xd1b54a32d192ed03ULL * (k + 1));
	rng_seed(g, splitmix64(&x));
}

static inline uint64_t rotl(uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }

uint64_t rng_u64(rng *g)
{
	uint64_t *s = g->s;
	uint64_t result = rotl(s[1] * 5, 7) * 9;
	uint64_t t = s[1] << 17;
	s[2] ^= s[0];
	s[3] ^= s[1];
	s[1] ^= s[2];
	s[0] ^= s[3];
	s[2] ^= t;
	s[3] = rotl(s[3], 45);
	return result;
}

double rng_uniform(rng *g) { return (double)(rng_u64(g) >> 11) * 0x1.0p-53; }

double rng_range(rng *g, double a, double b) { return a + (b - a) * rng_uniform(g); }

double rng_normal(rng *g)
{
	double u, v, s;
	do {
		u = 2.0 * rng_uniform(g) - 1.0;
		v = 2.0 * rng_uniform(g) - 1.0;
		s = u * u + v * v;
	} while (s >= 1.0 || s == 0.0);
	return u * sqrt(-2.0 * log(s) / s);
}
