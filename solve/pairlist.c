/* The pair-list machinery shared by bonds and contacts (pairlist.h). */
#include <stdlib.h>
#include <string.h>

#include "lib/err.h"
#include "solve/pairlist.h"
#include "solve/window.h"

void pairlist_free(pairlist *l)
{
	free(l->rec), free(l->state), free(l->k), free(l->f), free(l->fb), free(l->ref);
	window_array_free(l->off, l->off0, sizeof *l->off);
	memset(l, 0, sizeof *l);
}

pair_rec *pairlist_records(pair_rec *rec, size_t n, size_t cap)
{
	pair_rec *to = xaligned(64, (cap + 1) * sizeof *to);
	if (n)
		memcpy(to, rec, n * sizeof *to);
	memset(to + n, 0, (cap + 1 - n) * sizeof *to);
	free(rec);
	return to;
}

/* The gather index: for each particle the pairs it belongs to, in pair
 * order, so every particle sums its forces in a fixed order. */
void pairlist_csr(pairlist *l, size_t lo, size_t hi)
{
	int32_t *off = l->off;
	memset(off + lo, 0, (hi - lo + 1) * sizeof *off);
	for (size_t b = 0; b < l->n; b++)
		for (int end = 0; end < 2; end++) {
			size_t p = (size_t)(end ? l->rec[b].j : l->rec[b].i);
			if (p >= lo && p < hi)
				off[p + 1]++;
		}
	for (size_t p = lo; p < hi; p++)
		off[p + 1] += off[p];
	for (size_t b = 0; b < l->n; b++)
		for (int end = 0; end < 2; end++) {
			/* Pairs are sorted by i, so filling in pair order keeps each
			 * list sorted. */
			size_t p = (size_t)(end ? l->rec[b].j : l->rec[b].i);
			if (p >= lo && p < hi)
				l->ref[off[p]++] = (int32_t)(2 * b + (size_t)end);
		}
	for (size_t p = hi; p > lo; p--)
		off[p] = off[p - 1];
	off[lo] = 0;
}

void love_add(double love[9], const batch_geom *g, int q, const double f[6])
{
	for (int a = 0; a < 3; a++)
		for (int c = 0; c < 3; c++)
			love[3 * a + c] += g->d[q] * g->n[a][q] * f[c];
}

int pairlist_count(const pairlist *l, size_t i)
{
	int n = 0;
	for (size_t b = 0; b < l->n; b++)
		n += (size_t)l->rec[b].i == i || (size_t)l->rec[b].j == i;
	return n;
}
