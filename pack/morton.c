#include <stdint.h>
#include <stdlib.h>

#include "lib/err.h"
#include "lib/morton.h"
#include "pack/morton.h"

void morton_order(const double *x, size_t n, const double lo[3], const double hi[3], size_t *order)
{
	uint64_t *key = xmalloc(n * sizeof *key + 1);
	for (size_t i = 0; i < n; i++) {
		uint64_t c[3];
		for (int d = 0; d < 3; d++) {
			double t = hi[d] > lo[d] ? (x[3 * i + d] - lo[d]) / (hi[d] - lo[d]) : 0;
			c[d] = t <= 0 ? 0 : t >= 1 ? 1023 : (uint64_t)(t * 1024);
		}
		key[i] = morton_key(c);
	}
	morton_sort(key, n, order);
	free(key);
}
