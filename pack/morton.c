#include <stdint.h>
#include <stdlib.h>

#include "lib/err.h"
#include "pack/morton.h"

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

void morton_order(const double *x, size_t n, const double lo[3], const double hi[3], size_t *order)
{
	keyed *k = xmalloc(n * sizeof *k + 1);
	for (size_t i = 0; i < n; i++) {
		uint64_t key = 0;
		for (int d = 0; d < 3; d++) {
			double t = hi[d] > lo[d] ? (x[3 * i + d] - lo[d]) / (hi[d] - lo[d]) : 0;
			uint64_t c = t <= 0 ? 0 : t >= 1 ? 1023 : (uint64_t)(t * 1024);
			for (int b = 0; b < 10; b++)
				key |= ((c >> b) & 1) << (3 * b + d);
		}
		k[i].key = key;
		k[i].i = i;
	}
	qsort(k, n, sizeof *k, cmp_keyed);
	for (size_t i = 0; i < n; i++)
		order[i] = k[i].i;
	free(k);
}
