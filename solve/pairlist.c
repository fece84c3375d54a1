/* The pair-list machinery shared by bonds and contacts (pairlist.h). */
#include <stdlib.h>
#include <string.h>

#include "solve/pairlist.h"

void pairlist_free(pairlist *l)
{
	free(l->rec), free(l->f), free(l->off), free(l->ref);
	memset(l, 0, sizeof *l);
}

/* The gather index: for each particle the pairs it belongs to, in pair
 * order, so every particle sums its forces in a fixed order. */
void pairlist_csr(pairlist *l, size_t np)
{
	memset(l->off, 0, (np + 1) * sizeof *l->off);
	for (size_t b = 0; b < l->n; b++) {
		l->off[l->rec[b].i + 1]++;
		l->off[l->rec[b].j + 1]++;
	}
	for (size_t p = 0; p < np; p++)
		l->off[p + 1] += l->off[p];
	for (size_t b = 0; b < l->n; b++) {
		/* Pairs are sorted by i, so filling in pair order keeps each list sorted. */
		l->ref[l->off[l->rec[b].i]++] = (int32_t)(2 * b);
		l->ref[l->off[l->rec[b].j]++] = (int32_t)(2 * b + 1);
	}
	for (size_t p = np; p > 0; p--)
		l->off[p] = l->off[p - 1];
	l->off[0] = 0;
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
