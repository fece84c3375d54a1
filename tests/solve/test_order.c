/* The Morton order across the ranks (solve/order.h): on any number of ranks
 * each rank receives its share of the order, whole blocks in even shares,
 * with every particle's position and radius, and the order gathered from
 * the shares is the one process's. Point sets: uniform, clustered (most
 * keys in a few groups of leading bits, so one rank sorts most of them),
 * with equal positions (equal keys, in the order of the assembly), and
 * fewer particles than ranks have blocks. Each is given to order_morton
 * whole on every rank and in pieces; every rank checks its share, and
 * rank 0 prints a line per set with a hash of the order, which
 * order_ranks.sh compares over the rank counts. */
#include <inttypes.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lib/err.h"
#include "lib/rng.h"
#include "solve/order.h"
#include "solve/par.h"
#include "solve/ranks.h"
#include "tests/check.h"

enum { NSETS = 4 };

/* Set k of n points into x, r. */
static size_t make_set(int k, double *x, double *r)
{
	rng g;
	rng_seed(&g, 100 + (uint64_t)k);
	size_t n = k == 3 ? 10 : 5000;
	for (size_t i = 0; i < n; i++) {
		double *p = x + 3 * i;
		for (int c = 0; c < 3; c++)
			p[c] = rng_uniform(&g);
		if (k == 1 && i % 10) /* clustered in a small cube */
			for (int c = 0; c < 3; c++)
				p[c] = 0.5 + 1e-4 * p[c];
		if (k == 2 && i % 3) /* equal to an earlier point */
			memcpy(p, x + 3 * (i / 7), 3 * sizeof *p);
		r[i] = 0.001 * (1 + rng_uniform(&g));
	}
	return n;
}

static uint64_t mix(uint64_t h, uint64_t v)
{
	h ^= v + 0x9e3779b97f4a7c15u + (h << 6) + (h >> 2);
	return h * 0x100000001b3u;
}

int main(int argc, char **argv)
{
	if (par_init(&argc, &argv)) {
		fprintf(stderr, "test_order: %s\n", err_msg());
		return 1;
	}
	int rank = par_rank(), ranks = par_size();
	static double x[3 * 5000], r[5000];
	for (int k = 0; k < NSETS; k++) {
		size_t n = make_set(k, x, r);
		uint64_t hash[2];
		for (int piece = 0; piece < 2; piece++) {
			dem_assembly a = {.n = n, .x = x, .r = r};
			if (piece) {
				a.piece = 1;
				a.first = n * (size_t)rank / (size_t)ranks;
				a.held = n * (size_t)(rank + 1) / (size_t)ranks - a.first;
				a.x = x + 3 * a.first;
				a.r = r + a.first;
			}
			order_range o;
			order_morton(&a, &o);
			CHECK(o.first == order_share(n, rank, ranks));
			CHECK(o.first + o.n == order_share(n, rank + 1, ranks));
			CHECK(o.first % 256 == 0);
			for (size_t q = 0; q < o.n; q++) {
				int32_t i = o.orig[q];
				CHECK(i >= 0 && (size_t)i < n);
				CHECK(memcmp(o.x + 3 * q, x + 3 * i, 3 * sizeof *x) == 0);
				CHECK(o.r[q] == r[i]);
			}
			int32_t *all = malloc((n + 1) * sizeof *all);
			ranks_allgather_rows(o.orig, o.n, sizeof *o.orig, all);
			/* Each particle once; equal positions in the assembly's order. */
			char *seen = calloc(n, 1);
			uint64_t h = 0;
			for (size_t q = 0; q < n; q++) {
				CHECK(!seen[all[q]]);
				seen[all[q]] = 1;
				if (q &&
				    memcmp(x + 3 * all[q], x + 3 * all[q - 1], 3 * sizeof *x) == 0)
					CHECK(all[q] > all[q - 1]);
				h = mix(h, (uint64_t)all[q]);
			}
			hash[piece] = h;
			free(seen), free(all);
			order_free(&o);
		}
		CHECK(hash[0] == hash[1]);
		if (rank == 0)
			printf("order %d: %zu particles, %016" PRIx64 "\n", k, n, hash[0]);
	}
	int rc = check_done();
	par_finalize();
	return rc;
}
