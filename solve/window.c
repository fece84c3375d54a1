/* The particles a rank holds: a window of indices (window.h). */
#include <stdlib.h>
#include <string.h>

#include "lib/err.h"
#include "solve/blocks.h"
#include "solve/engine.h"
#include "solve/ranks.h"
#include "solve/window.h"

void *window_array(size_t lo, size_t hi, size_t item)
{
	/* Addressed by the window's indices: the memory of index lo first. */
	return (char *)xcalloc(hi - lo + 1, item) - lo * item;
}

void window_array_free(void *a, size_t lo, size_t item)
{
	if (a)
		free((char *)a + lo * item);
}

/* An array of the window's items, not zeroed. */
static void *raw_array(size_t lo, size_t hi, size_t item)
{
	return (char *)xmalloc((hi - lo + 1) * item) - lo * item;
}

/* The particles' arrays as bytes, each with its item size: x, v, w, r, m,
 * orig, then flag (ARR_FLAG), surf and the platen slots. */
enum { NARR = 10, ARR_FLAG = 6 };
static void arrays(const particles *P, char *a[NARR], size_t item[NARR])
{
	char *p[NARR] = {(char *)P->x,        (char *)P->v,       (char *)P->w,    (char *)P->r,
	                 (char *)P->m,        (char *)P->orig,    (char *)P->flag, (char *)P->surf,
	                 (char *)P->pslot[0], (char *)P->pslot[1]};
	size_t s[NARR] = {3 * sizeof *P->x,   3 * sizeof *P->v, 3 * sizeof *P->w,
	                  sizeof *P->r,       sizeof *P->m,     sizeof *P->orig,
	                  sizeof *P->flag,    sizeof *P->surf,  sizeof *P->pslot[0],
	                  sizeof *P->pslot[1]};
	memcpy(a, p, sizeof p);
	memcpy(item, s, sizeof s);
}

/* The arrays of P from a (arrays' order). */
static void set_arrays(particles *P, char *const a[NARR])
{
	P->x = (double *)a[0], P->v = (double *)a[1], P->w = (double *)a[2];
	P->r = (double *)a[3], P->m = (double *)a[4], P->orig = (int32_t *)a[5];
	P->flag = (uint8_t *)a[6], P->surf = (int32_t *)a[7];
	P->pslot[0] = (int32_t *)a[8], P->pslot[1] = (int32_t *)a[9];
}

/* The window [lo, hi) of P, and the most particles it has held. */
static void set_range(particles *P, size_t lo, size_t hi)
{
	P->lo = lo;
	P->hi = hi;
	P->held_peak = hi - lo > P->held_peak ? hi - lo : P->held_peak;
}

/* The particles' arrays for [lo, hi), zeroed. */
static void alloc_arrays(particles *P, size_t lo, size_t hi)
{
	char *a[NARR];
	size_t item[NARR];
	arrays(&(particles){0}, a, item); /* the item sizes */
	for (int q = 0; q < NARR; q++)
		a[q] = window_array(lo, hi, item[q]);
	set_arrays(P, a);
	set_range(P, lo, hi);
}

void particles_alloc(particles *P, size_t n, size_t lo, size_t hi)
{
	alloc_arrays(P, lo, hi);
	for (size_t i = lo; i < hi; i++)
		P->surf[i] = P->pslot[0][i] = P->pslot[1][i] = -1;
	P->n = n;
	P->glob = NULL;
}

void particles_alloc_own(particles *P, size_t n, size_t p0, size_t p1)
{
	particles_alloc(P, n, p0, p1);
	P->own0 = p0;
	P->own1 = p1;
	P->glob = window_array(p0, p1, sizeof *P->glob);
	for (size_t i = p0; i < p1; i++)
		P->glob[i] = (int32_t)i;
}

void particles_free(particles *P)
{
	char *a[NARR];
	size_t item[NARR];
	arrays(P, a, item);
	for (int k = 0; k < NARR; k++)
		window_array_free(a[k], P->lo, item[k]);
	window_array_free(P->glob, P->lo, sizeof *P->glob);
}

void particle_row(const particles *P, size_t i, double *row)
{
	memcpy(row, P->x + 3 * i, 3 * sizeof *row);
	memcpy(row + 3, P->v + 3 * i, 3 * sizeof *row);
	memcpy(row + 6, P->w + 3 * i, 3 * sizeof *row);
	row[PARTICLE_R] = P->r[i];
	row[PARTICLE_M] = P->m[i];
	row[PARTICLE_ORIG] = P->orig[i];
}

void particle_set_row(particles *P, size_t i, const double *row)
{
	memcpy(P->x + 3 * i, row, 3 * sizeof *row);
	memcpy(P->v + 3 * i, row + 3, 3 * sizeof *row);
	memcpy(P->w + 3 * i, row + 6, 3 * sizeof *row);
	P->r[i] = row[PARTICLE_R];
	P->m[i] = row[PARTICLE_M];
	P->orig[i] = (int32_t)row[PARTICLE_ORIG];
}

int64_t window_local(const particles *P, size_t g)
{
	if (!P->glob)
		return g < P->n ? (int64_t)g : -1;
	if (g >= P->own0 && g < P->own1)
		return (int64_t)g;
	size_t a = g < P->own0 ? P->lo : P->own1, b = g < P->own0 ? P->own0 : P->hi;
	size_t k = first_not_below(P->glob, a, b, g);
	return k < b && (size_t)P->glob[k] == g ? (int64_t)k : -1;
}

static int cmp_i32(const void *a, const void *b)
{
	int32_t x = *(const int32_t *)a, y = *(const int32_t *)b;
	return (x > y) - (x < y);
}

/* The pairs of L with both ends held renumbered by map (-1: not held), the
 * others dropped; their number dropped. */
static size_t renumber_pairs(pairlist *L, const int32_t *map)
{
	size_t m = 0;
	for (size_t c = 0; c < L->n; c++) {
		int32_t i = map[L->rec[c].i], j = map[L->rec[c].j];
		if (i < 0 || j < 0)
			continue;
		L->rec[m] = L->rec[c];
		L->rec[m].i = i;
		L->rec[m].j = j;
		if (m != c)
			memcpy(L->f + 6 * m, L->f + 6 * c, 6 * sizeof *L->f);
		m++;
	}
	size_t dropped = L->n - m;
	L->n = m;
	return dropped;
}

/* Merge the increasing lists a and b (of na and nb) into out, each index
 * once: their number. */
static size_t merge(const int32_t *a, size_t na, const int32_t *b, size_t nb, int32_t *out)
{
	size_t i = 0, j = 0, m = 0;
	while (i < na || j < nb) {
		int32_t x = j == nb || (i < na && a[i] <= b[j]) ? a[i] : b[j];
		i += i < na && a[i] == x;
		j += j < nb && b[j] == x;
		out[m++] = x;
	}
	return m;
}

size_t window_set(engine *e, const int32_t *want, size_t nw)
{
	particles *P = &e->p;
	bond_split *S = &e->pairs.split;
	size_t p0 = e->ranks.p0, p1 = e->ranks.p1;
	int32_t *g = xmalloc((nw + P->nfixed + 1) * sizeof *g);
	size_t k = merge(want, nw, P->fixed, P->nfixed, g), before = 0;
	while (before < k && (size_t)g[before] < p0)
		before++;
	size_t lo = p0 - before, hi = p1 + (k - before);
	int32_t *glob = window_array(lo, hi, sizeof *glob);
	for (size_t i = lo; i < hi; i++)
		glob[i] = i < p0 ? g[i - lo] : i >= p1 ? g[before + (i - p1)] : (int32_t)i;
	free(g);
	/* Each old index's new one (or -1), by merging the two windows. */
	int32_t *map = window_array(P->lo, P->hi, sizeof *map);
	for (size_t i = P->lo, j = lo; i < P->hi; i++) {
		size_t gi = particle_global(P, i);
		while (j < hi && (size_t)glob[j] < gi)
			j++;
		map[i] = j < hi && (size_t)glob[j] == gi ? (int32_t)j : -1;
	}
	/* The new arrays one at a time, each old one freed once copied (a
	 * window change holds one array twice, not all of them). The
	 * particles new to the window have no place on a platen or the
	 * surface (their state is the caller's to fill); the others are kept. */
	char *a[NARR], *b[NARR];
	size_t item[NARR];
	arrays(P, a, item);
	for (int q = 0; q < NARR; q++) {
		b[q] = raw_array(lo, hi, item[q]);
		for (size_t i = lo; q >= ARR_FLAG && i < hi; i++) /* flag 0; surf, slots -1 */
			if (i < p0 || i >= p1)
				memset(b[q] + i * item[q], q == ARR_FLAG ? 0 : 0xff, item[q]);
		for (size_t i = P->lo; i < P->hi; i++)
			if (map[i] >= 0 && (i < p0 || i >= p1))
				memcpy(b[q] + (size_t)map[i] * item[q], a[q] + i * item[q],
				       item[q]);
		/* the own ones in one piece */
		memcpy(b[q] + p0 * item[q], a[q] + p0 * item[q], (p1 - p0) * item[q]);
		window_array_free(a[q], P->lo, item[q]);
	}
	/* The lists' particles: the bonds' other ends and the crossing slots'
	 * are held (above); a contact is dropped with an end. */
	pairlist *B = &e->pairs.bonds;
	for (size_t b2 = 0; b2 < B->n; b2++)
		B->rec[b2].j = map[B->rec[b2].j];
	for (size_t c = 0; c < S->ncross; c++) {
		S->ci[c] = map[S->ci[c]];
		S->cj[c] = map[S->cj[c]];
	}
	size_t dropped = renumber_pairs(&e->pairs.contacts, map);
	window_array_free(map, P->lo, sizeof *map);
	window_array_free(P->glob, P->lo, sizeof *P->glob); /* x_ref, the own particles', stays */
	set_arrays(P, b);
	P->glob = glob;
	set_range(P, lo, hi);
	return dropped;
}

/* Of the m particles list[0..m) (indices in the whole specimen: the window
 * is not made yet), the other ranks', in increasing order, each once: their
 * number. */
static size_t others(const engine *e, int32_t *list, size_t m)
{
	size_t k = 0;
	for (size_t q = 0; q < m; q++)
		if ((size_t)list[q] < e->ranks.p0 || (size_t)list[q] >= e->ranks.p1)
			list[k++] = list[q];
	qsort(list, k, sizeof *list, cmp_i32);
	size_t u = 0;
	for (size_t q = 0; q < k; q++)
		if (!u || list[q] != list[u - 1])
			list[u++] = list[q];
	return u;
}

void window_start(engine *e)
{
	if (e->ranks.size == 1)
		return;
	particles *P = &e->p;
	const bond_split *S = &e->pairs.split;
	P->fixed = xmalloc((2 * S->ncross + 1) * sizeof *P->fixed);
	for (size_t c = 0; c < S->ncross; c++) {
		P->fixed[2 * c] = (int32_t)particle_global(P, (size_t)S->ci[c]);
		P->fixed[2 * c + 1] = (int32_t)particle_global(P, (size_t)S->cj[c]);
	}
	P->nfixed = others(e, P->fixed, 2 * S->ncross);
	const pairlist *C = &e->pairs.contacts;
	int32_t *want = xmalloc((2 * C->n + 1) * sizeof *want);
	for (size_t c = 0; c < C->n; c++) {
		want[2 * c] = (int32_t)particle_global(P, (size_t)C->rec[c].i);
		want[2 * c + 1] = (int32_t)particle_global(P, (size_t)C->rec[c].j);
	}
	size_t dropped = window_set(e, want, others(e, want, 2 * C->n));
	free(want);
	if (dropped)
		fatal("window_start: %zu contacts without their ends (an internal error)", dropped);
	/* The halo in the new numbering. */
	ranks_contacts(e);
}

void window_hold_contacts(engine *e)
{
	particles *P = &e->p;
	pairlist *L = &e->pairs.contacts;
	size_t n = L->n;
	int32_t *want = xmalloc((2 * n + 1) * sizeof *want);
	for (size_t c = 0; c < n; c++)
		want[2 * c] = L->rec[c].i, want[2 * c + 1] = L->rec[c].j;
	L->n = 0; /* not renumbered: their ends are not the window's */
	window_set(e, want, others(e, want, 2 * n));
	free(want);
	L->n = n;
	for (size_t c = 0; c < n; c++) {
		L->rec[c].i = (int32_t)window_local(P, (size_t)L->rec[c].i);
		L->rec[c].j = (int32_t)window_local(P, (size_t)L->rec[c].j);
	}
}

size_t window_ghosts(engine *e, double reach)
{
	particles *P = &e->p;
	double *gh;
	size_t ng = ranks_share_ghosts(e, reach, &gh);
	int32_t *want = xmalloc((ng + 1) * sizeof *want);
	for (size_t k = 0; k < ng; k++)
		want[k] = (int32_t)gh[GHOST_COLS * k];
	window_set(e, want, ng);
	for (size_t k = 0; k < ng; k++)
		particle_set_row(P, (size_t)window_local(P, (size_t)want[k]),
		                 gh + GHOST_COLS * k + 1);
	free(want), free(gh);
	return ng;
}
