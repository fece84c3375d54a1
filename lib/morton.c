#include <stdlib.h>

#include "lib/err.h"
#include "lib/morton.h"

/* Spread the low 21 bits of v to every third bit. */
static uint64_t spread(uint64_t v)
{
	v &= 0x1fffff;
	v = (v | v << 32) & 0x1f00000000ffffULL;
	v = (v | v << 16) & 0x1f0000ff0000ffULL;
	v = (v | v << 8) & 0x100f00f00f00f00fULL;
	v = (v | v << 4) & 0x10c30c30c30c30c3ULL;
	v = (v | v << 2) & 0x1249249249249249ULL;
	return v;
}

uint64_t morton_key(const uint64_t c[3])
{
	return spread(c[0]) | spread(c[1]) << 1 | spread(c[2]) << 2;
}

typedef struct {
	uint64_t key;
	size_t i;
} keyed;

static int cmp_keyed(const void *a, const void *b)
{
	const keyed *u = a, *v = b;
	if (u->key != v->key)
		return u->key < v->key ? -1 : 1;
	return (u->i > v->i) - (u->i < v->i);
}

void morton_sort(const uint64_t *key, size_t n, size_t *order)
{
	keyed *k = xmalloc(n * sizeof *k + 1);
	for (size_t i = 0; i < n; i++)
		k[i] = (keyed){key[i], i};
	qsort(k, n, sizeof *k, cmp_keyed);
	for (size_t i = 0; i < n; i++)
		order[i] = k[i].i;
	free(k);
}
