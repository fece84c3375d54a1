/* Overlap pruning (see prune.h). Deleting every sphere of every offending
 * pair empties the band; deleting one sphere at a time, the one of the
 * worst pair with the larger total excess overlap, resolves each cluster of
 * overlaps with the fewest removals, since removing it relieves its other
 * contacts too. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lib/err.h"
#include "lib/vec3.h"
#include "pack/prune.h"
#include "pack/soft.h"

typedef struct {
	soft_system sys;
	const double *s; /* exact depth of each sphere near the boundary */
	uint8_t *gone;
	double limit;
} pruner;

/* Worst relative overlap of sphere i beyond the limit, its partner (-1:
 * the boundary), and the sum of its excess overlaps. */
static double worst(const pruner *p, size_t i, long *partner, double *total)
{
	const soft_system *s = &p->sys;
	double w = 0, ri = s->r[i];
	*partner = -2;
	*total = 0;
	if (p->s[i] < ri && (ri - p->s[i]) / ri > p->limit) {
		w = (ri - p->s[i]) / ri;
		*partner = -1;
		*total += w;
	}
	for (size_t q = s->nb_start[i]; q < s->nb_start[i + 1]; q++) {
		size_t j = (size_t)s->nb[q];
		if (p->gone[j])
			continue;
		double d[3];
		soft_delta(s, i, j, d);
		double rel = (ri + s->r[j] - v3_norm(d)) / fmin(ri, s->r[j]);
		if (rel <= p->limit)
			continue;
		*total += rel;
		if (rel > w) {
			w = rel;
			*partner = (long)j;
		}
	}
	return w;
}

size_t prune_overlaps(spheres *S, const surface *surf, double depth, double limit)
{
	double rmax = 0;
	for (size_t i = 0; i < S->n; i++)
		rmax = fmax(rmax, S->r[i]);
	size_t *idx = xmalloc(S->n * sizeof *idx + 1), m = 0;
	for (size_t i = 0; i < S->n; i++)
		if (S->lo[i] < depth)
			idx[m++] = i;
	pruner p;
	double *x = xmalloc(3 * m * sizeof *x + 1), *r = xmalloc(m * sizeof *r + 1);
	double *s = xmalloc(m * sizeof *s + 1), *w = xmalloc(m * sizeof *w + 1);
	double *tot = xmalloc(m * sizeof *tot + 1);
	long *partner = xmalloc(m * sizeof *partner + 1);
	for (size_t k = 0; k < m; k++) {
		size_t i = idx[k];
		v3_copy(x + 3 * k, S->x + 3 * i);
		r[k] = S->r[i];
		s[k] = S->lo[i];
	}
	/* Exact depths where a sphere may cross the boundary. */
#pragma omp parallel for schedule(dynamic, 256)
	for (size_t k = 0; k < m; k++)
		if (S->hi[idx[k]] > s[k] && s[k] < (1 + limit) * r[k]) {
			int32_t hint = -1;
			s[k] = surface_distance(surf, x + 3 * k, NULL, &hint);
		}
	soft_init(&p.sys, m, m, x, r);
	p.sys.skin = 1e-9 * rmax;
	soft_rebuild(&p.sys);
	p.s = s;
	p.gone = xcalloc(m + 1, 1);
	p.limit = limit;
#pragma omp parallel for schedule(dynamic, 256)
	for (size_t k = 0; k < m; k++)
		w[k] = worst(&p, k, &partner[k], &tot[k]);
	size_t removed = 0;
	for (;;) {
		size_t a = 0;
		for (size_t k = 1; k < m; k++)
			if (w[k] > w[a])
				a = k;
		if (m == 0 || w[a] <= limit)
			break;
		size_t out = a;
		if (partner[a] >= 0 && tot[partner[a]] > tot[a])
			out = (size_t)partner[a];
		p.gone[out] = 1;
		w[out] = 0;
		removed++;
		for (size_t q = p.sys.nb_start[out]; q < p.sys.nb_start[out + 1]; q++) {
			size_t j = (size_t)p.sys.nb[q];
			if (!p.gone[j])
				w[j] = worst(&p, j, &partner[j], &tot[j]);
		}
	}
	uint8_t *keep = xmalloc(S->n + 1);
	memset(keep, 1, S->n);
	for (size_t k = 0; k < m; k++)
		if (p.gone[k])
			keep[idx[k]] = 0;
	spheres_compact(S, keep);
	soft_free(&p.sys);
	free(keep);
	free(p.gone);
	free(idx);
	free(x);
	free(r);
	free(s);
	free(w);
	free(tot);
	free(partner);
	return removed;
}
