/* The Morton order across the ranks (solve/order.h): on any number of ranks
 * each rank receives its share of the order, whole blocks in even shares,
 * with every particle's position and radius, and the order gathered from
 * the shares is the one process's. Point sets: uniform, clustered (most
 * keys in a few groups of leading bits, so one rank sorts most of them),
 * with equal positions (equal keys, in the order of the assembly), and
 * fewer particles than ranks have blocks, and a jittered lattice of
 * touching spheres in two walk cells. Each is given to order_morton whole
 * on every rank and in pieces; every rank checks its share, and rank 0
 * prints a line per set with a hash of the order, which order_ranks.sh
 * compares over the rank counts. On the lattice, the walk within cells
 * must bring a pair's far end for the first time in the order of places
 * (the pairs of each place in turn, as the bond loop runs), but where a
 * cell or a walk starts. */
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

enum { NSETS = 5, LX = 20, LY = 20, LZ = 50, NMAX = LX * LY * LZ };

/* Set k of n points into x, r. */
static size_t make_set(int k, double *x, double *r)
{
	rng g;
	rng_seed(&g, 100 + (uint64_t)k);
	size_t n = k == 3 ? 10 : 5000;
	if (k == 4) { /* spacing 1, radius 0.5, jittered by 2 % */
		for (size_t i = 0; i < NMAX; i++) {
			size_t at[3] = {i % LX, i / LX % LY, i / LX / LY};
			for (int c = 0; c < 3; c++)
				x[3 * i + c] = (double)at[c] + 0.02 * (rng_uniform(&g) - 0.5);
			r[i] = 0.5;
		}
		return NMAX;
	}
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

/* Of the lattice in the order all (place: its particle), the first touches
 * of a pair's far end (in the bond loop's order: the pairs (i, j), j after
 * i, of each place i in turn) that are not at the place after the last
 * first touch. */
static size_t out_of_order(const int32_t *all)
{
	static size_t place[NMAX];
	static char touched[NMAX];
	for (size_t q = 0; q < NMAX; q++)
		place[all[q]] = q, touched[q] = 0;
	size_t last = 0, out = 0;
	for (size_t q = 0; q < NMAX; q++) {
		int32_t i = all[q];
		size_t at[3] = {(size_t)i % LX, (size_t)i / LX % LY, (size_t)i / LX / LY};
		size_t lim[3] = {LX, LY, LZ}, step[3] = {1, LX, LX * LY};
		size_t far[6], nfar = 0;
		for (int c = 0; c < 3; c++) {
			if (at[c] > 0 && place[(size_t)i - step[c]] > q)
				far[nfar++] = place[(size_t)i - step[c]];
			if (at[c] + 1 < lim[c] && place[(size_t)i + step[c]] > q)
				far[nfar++] = place[(size_t)i + step[c]];
		}
		for (size_t a = 1; a < nfar; a++) /* the bond loop's order of j */
			for (size_t b = a; b > 0 && far[b - 1] > far[b]; b--) {
				size_t t = far[b];
				far[b] = far[b - 1], far[b - 1] = t;
			}
		for (size_t a = 0; a < nfar; a++)
			if (!touched[far[a]]) {
				touched[far[a]] = 1;
				out += far[a] != last + 1 && far[a] != q + 1;
				last = far[a];
			}
	}
	return out;
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
	static double x[3 * NMAX], r[NMAX];
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
			order_morton(&a, 0, 1.1, &o);
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
			if (k == 4 && rank == 0 && piece == 0) {
				/* Two cells, a walk each: the far ends of the pairs across
				 * their interface (400) come out of order, and about as
				 * many in the second cell's walk among them: 812 of 20 000.
				 * In the Morton order alone, 16 957. */
				size_t out = out_of_order(all);
				printf("lattice: %zu first touches out of order\n", out);
				CHECK(out < NMAX / 10);
			}
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
