/* The particles in Morton order across the ranks (order.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lib/err.h"
#include "lib/morton.h"
#include "solve/blocks.h"
#include "solve/order.h"
#include "solve/par.h"

/* A particle on its way to its place. */
typedef struct {
	uint64_t key;
	int32_t orig, pad;
	double x[3], r;
} item;

enum { LEAD_BITS = 16, LEAD_SHIFT = 3 * MORTON_BITS - LEAD_BITS };

size_t order_share(size_t n, int k, int ranks)
{
	size_t at = BLOCK * (nblocks(n) * (size_t)k / (size_t)ranks);
	return at < n ? at : n;
}

/* The m items *it sent on, item k to rank dest[k]; those received, in the
 * order of their ranks, in their place. */
static size_t send_on(item **it, size_t m, const int *dest)
{
	void *recv;
	size_t got = par_send_rows(*it, dest, m, sizeof **it, &recv);
	free(*it);
	*it = recv;
	return got;
}

/* The m items sorted by key, equal keys in the order they are in. */
static void sort_items(item *it, size_t m)
{
	uint64_t *key = xmalloc((m + 1) * sizeof *key);
	size_t *order = xmalloc((m + 1) * sizeof *order);
	for (size_t k = 0; k < m; k++)
		key[k] = it[k].key;
	morton_sort(key, m, order);
	item *tmp = xmalloc((m + 1) * sizeof *tmp);
	for (size_t k = 0; k < m; k++)
		tmp[k] = it[order[k]];
	memcpy(it, tmp, m * sizeof *it);
	free(tmp), free(key), free(order);
}

void order_morton(const dem_assembly *a, order_range *o)
{
	int ranks = par_size(), rank = par_rank();
	/* A whole assembly (on every rank): this rank's part of it. */
	size_t n = a->n, first = a->piece ? a->first : n * (size_t)rank / (size_t)ranks;
	size_t m = a->piece ? a->held : n * (size_t)(rank + 1) / (size_t)ranks - first;
	const double *ax = a->x + (a->piece ? 0 : 3 * first), *ar = a->r + (a->piece ? 0 : first);
	/* The bounding cube, as min and max over the ranks. */
	double b[6] = {-INFINITY, -INFINITY, -INFINITY, -INFINITY, -INFINITY, -INFINITY};
	for (size_t i = 0; i < m; i++)
		for (int k = 0; k < 3; k++) {
			b[k] = fmax(b[k], -ax[3 * i + k]);
			b[3 + k] = fmax(b[3 + k], ax[3 * i + k]);
		}
	par_max(b, 6);
	double span = 0;
	for (int k = 0; k < 3; k++)
		span = fmax(span, b[3 + k] + b[k]);
	double scale = span > 0 ? 2097151.0 / span : 0;
	item *it = xmalloc((m + 1) * sizeof *it);
	for (size_t i = 0; i < m; i++) {
		uint64_t c[3];
		for (int k = 0; k < 3; k++)
			c[k] = (uint64_t)((ax[3 * i + k] + b[k]) * scale);
		it[i] = (item){.key = morton_key(c), .orig = (int32_t)(first + i)};
		memcpy(it[i].x, ax + 3 * i, sizeof it[i].x);
		it[i].r = ar[i];
	}
	if (ranks > 1) {
		/* Each group of keys (their leading bits) to the rank whose share
		 * holds its first place, in the order of the assembly. */
		size_t ngroups = (size_t)1 << LEAD_BITS;
		uint64_t *count = xcalloc(ngroups, sizeof *count);
		for (size_t k = 0; k < m; k++)
			count[it[k].key >> LEAD_SHIFT]++;
		par_sum_u64(count, ngroups);
		size_t *share = xmalloc(((size_t)ranks + 1) * sizeof *share);
		for (int q = 0; q <= ranks; q++)
			share[q] = order_share(n, q, ranks);
		int *to = xmalloc(ngroups * sizeof *to);
		size_t place = 0, mine = 0; /* the first place of this rank's groups */
		int seen = 0;
		for (size_t g = 0; g < ngroups; g++) {
			to[g] = run_of(share, ranks, place);
			if (to[g] == rank && !seen)
				mine = place, seen = 1;
			place += count[g];
		}
		free(count);
		int *dest = xmalloc((m + 1) * sizeof *dest);
		for (size_t k = 0; k < m; k++)
			dest[k] = to[it[k].key >> LEAD_SHIFT];
		free(to);
		m = send_on(&it, m, dest);
		/* Sorted, they fill places [mine, mine + m): on to their shares. */
		sort_items(it, m);
		dest = xrealloc(dest, (m + 1) * sizeof *dest);
		for (size_t k = 0; k < m; k++)
			dest[k] = run_of(share, ranks, mine + k);
		m = send_on(&it, m, dest);
		free(dest), free(share);
	} else {
		sort_items(it, m);
	}
	o->first = order_share(n, rank, ranks);
	o->n = m;
	o->orig = xmalloc((m + 1) * sizeof *o->orig);
	o->x = xmalloc((3 * m + 1) * sizeof *o->x);
	o->r = xmalloc((m + 1) * sizeof *o->r);
	for (size_t k = 0; k < m; k++) {
		o->orig[k] = it[k].orig;
		memcpy(o->x + 3 * k, it[k].x, sizeof it[k].x);
		o->r[k] = it[k].r;
	}
	free(it);
	if (o->first + m != order_share(n, rank + 1, ranks))
		fatal("order_morton: %zu particles at place %zu (an internal error)", m, o->first);
}

void order_free(order_range *o)
{
	free(o->orig), free(o->x), free(o->r);
	memset(o, 0, sizeof *o);
}
