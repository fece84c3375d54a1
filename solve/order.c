/* The particles in Morton order across the ranks, walked breadth first
 * within cells (order.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lib/err.h"
#include "lib/morton.h"
#include "solve/blocks.h"
#include "solve/cells.h"
#include "solve/order.h"
#include "solve/par.h"

/* A particle on its way to its place. */
typedef struct {
	uint64_t key;
	int32_t orig, pad;
	double x[3], r;
} item;

enum { LEAD_BITS = 16, LEAD_SHIFT = 3 * MORTON_BITS - LEAD_BITS };
/* The walk's cells: Morton cells (a key's leading bits, a multiple of 3)
 * of at least CELL_MEAN particles on average over those occupied, and no
 * finer than two groups of leading bits (CELL_SHIFT_MIN), so a cell is
 * whole groups. A particle's neighbours in the walk: the first NEAR_SCAN
 * of each grid cell (cells.h) around it within reach (order.h). */
enum { CELL_MEAN = 4096, CELL_SHIFT_MIN = 48, NEAR_SCAN = 64 };

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

/* The key's leading bits that make its walk cell, from the count of the
 * keys of each group of leading bits (of all the ranks): the finest
 * Morton cells whose mean occupancy is CELL_MEAN or more, or the coarsest
 * one allowed finer than that. */
static int cell_shift(const uint64_t *count, size_t n)
{
	int shift = CELL_SHIFT_MIN;
	for (; shift < 3 * MORTON_BITS; shift += 3) {
		size_t cells = 0;
		uint64_t prev = UINT64_MAX;
		for (size_t g = 0; g < (size_t)1 << LEAD_BITS; g++)
			if (count[g] && g >> (shift - LEAD_SHIFT) != prev)
				cells++, prev = g >> (shift - LEAD_SHIFT);
		if (cells * CELL_MEAN <= n)
			break;
	}
	return shift;
}

/* The m items of one cell (sorted by key) in the order of a breadth-first
 * walk from the first one not reached yet, each particle's unreached
 * neighbours (centres within reach times the sum of their radii) in the
 * order of their keys. In the bond loop, which runs over the pairs (i, j)
 * of each particle i in turn, the particles j then come for the first time
 * in the order of memory, and stay in the cache until their own turn. */
static void walk_cell(item *it, size_t m, double reach)
{
	if (m < 3)
		return;
	/* Cells of the reach of the largest pair (cells.h). */
	double *x = xmalloc(3 * m * sizeof *x), rmax = 0;
	for (size_t k = 0; k < m; k++) {
		memcpy(x + 3 * k, it[k].x, sizeof it[k].x);
		rmax = fmax(rmax, it[k].r);
	}
	cells g = {0};
	cells_build(&g, x, m, 2 * reach * rmax); /* each cell's items in the order of their keys */
	free(x);
	size_t *queue = xmalloc(m * sizeof *queue), head = 0, tail = 0;
	size_t *near = xmalloc(27 * NEAR_SCAN * sizeof *near);
	char *seen = xcalloc(m, 1);
	for (size_t s = 0; s < m; s++) {
		if (seen[s])
			continue;
		seen[s] = 1, queue[tail++] = s;
		while (head < tail) {
			size_t u = queue[head++], found = 0;
			int32_t around[27];
			int nc = cells_around(&g, g.cell[u], around);
			for (int c = 0; c < nc; c++) {
				int32_t q0 = g.start[around[c]], q1 = g.start[around[c] + 1];
				for (int32_t q = q0; q < q1 && q < q0 + NEAR_SCAN; q++) {
					size_t v = (size_t)g.item[q];
					double d2 = 0, near_d = reach * (it[u].r + it[v].r);
					for (int k = 0; k < 3; k++)
						d2 += (it[v].x[k] - it[u].x[k]) *
						      (it[v].x[k] - it[u].x[k]);
					if (!seen[v] && d2 < near_d * near_d)
						near[found++] = v, seen[v] = 1;
				}
			}
			/* In the order of their keys (insertion: a few each). */
			for (size_t a = 1; a < found; a++)
				for (size_t b = a; b > 0 && near[b - 1] > near[b]; b--) {
					size_t t = near[b];
					near[b] = near[b - 1], near[b - 1] = t;
				}
			memcpy(queue + tail, near, found * sizeof *near);
			tail += found;
		}
	}
	cells_free(&g);
	item *tmp = xmalloc(m * sizeof *tmp);
	for (size_t k = 0; k < m; k++)
		tmp[k] = it[queue[k]];
	memcpy(it, tmp, m * sizeof *it);
	free(tmp), free(seen), free(near), free(queue);
}

/* The m items (sorted by key, whole cells) walked cell by cell. */
static void walk_cells(item *it, size_t m, int shift, double reach)
{
	for (size_t k = 0, end; k < m; k = end) {
		for (end = k + 1; end < m && it[end].key >> shift == it[k].key >> shift; end++)
			;
		walk_cell(it + k, end - k, reach);
	}
}

void order_morton(const dem_assembly *a, int plain, double reach, order_range *o)
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
	/* The count of the keys of each group of leading bits, over the ranks. */
	size_t ngroups = (size_t)1 << LEAD_BITS;
	uint64_t *count = xcalloc(ngroups, sizeof *count);
	for (size_t k = 0; k < m; k++)
		count[it[k].key >> LEAD_SHIFT]++;
	par_sum_u64(count, ngroups);
	int shift = cell_shift(count, n);
	if (ranks > 1) {
		/* Each walk cell (whole groups of keys, their leading bits) to the
		 * rank whose share holds its first place, in the order of the
		 * assembly. */
		size_t *share = xmalloc(((size_t)ranks + 1) * sizeof *share);
		for (int q = 0; q <= ranks; q++)
			share[q] = order_share(n, q, ranks);
		int *to = xmalloc(ngroups * sizeof *to);
		size_t place = 0, mine = 0; /* the first place of this rank's groups */
		int seen = 0;
		size_t cell_place = 0; /* the first place of g's walk cell (plain: of g) */
		for (size_t g = 0; g < ngroups; g++) {
			if (plain || g == 0 ||
			    g >> (shift - LEAD_SHIFT) != (g - 1) >> (shift - LEAD_SHIFT))
				cell_place = place;
			to[g] = run_of(share, ranks, cell_place);
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
		if (!plain)
			walk_cells(it, m, shift, reach);
		dest = xrealloc(dest, (m + 1) * sizeof *dest);
		for (size_t k = 0; k < m; k++)
			dest[k] = run_of(share, ranks, mine + k);
		m = send_on(&it, m, dest);
		free(dest), free(share);
	} else {
		free(count);
		sort_items(it, m);
		if (!plain)
			walk_cells(it, m, shift, reach);
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
