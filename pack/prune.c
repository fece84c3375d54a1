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

/* The spheres near the boundary as a soft system (a list of their
 * neighbours), with what the greedy removal keeps of each. */
typedef struct {
	soft_system sys;
	size_t m;
	size_t *idx;     /* [m] index in S of each */
	double *x, *r;   /* [m][3], [m] their positions and radii */
	double *s;       /* [m] exact depth of each sphere near the boundary */
	double *w, *tot; /* [m] worst overlap beyond the limit (see worst()), total */
	long *partner;   /* [m] */
	uint8_t *gone;   /* [m] removed */
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

/* The spheres shallower than `depth` (by their bound S->lo), their exact
 * depths where they may cross the boundary, their neighbours and their
 * worst overlaps. */
static void pruner_init(pruner *p, const spheres *S, const surface *surf, double depth,
                        double limit)
{
	double rmax = 0;
	for (size_t i = 0; i < S->n; i++)
		rmax = fmax(rmax, S->r[i]);
	size_t m = 0, *idx = xmalloc(S->n * sizeof *idx + 1);
	for (size_t i = 0; i < S->n; i++)
		if (S->lo[i] < depth)
			idx[m++] = i;
	double *x = xmalloc(3 * m * sizeof *x + 1), *r = xmalloc(m * sizeof *r + 1);
	double *s = xmalloc(m * sizeof *s + 1);
	for (size_t k = 0; k < m; k++) {
		v3_copy(x + 3 * k, S->x + 3 * idx[k]);
		r[k] = S->r[idx[k]];
		s[k] = S->lo[idx[k]];
	}
#pragma omp parallel for schedule(dynamic, 256)
	for (size_t k = 0; k < m; k++)
		if (S->hi[idx[k]] > s[k] && s[k] < (1 + limit) * r[k]) {
			int32_t hint = -1;
			s[k] = surface_distance(surf, x + 3 * k, NULL, &hint);
		}
	*p = (pruner){.m = m, .idx = idx, .x = x, .r = r, .s = s, .limit = limit};
	soft_init(&p->sys, m, m, x, r);
	p->sys.skin = 1e-9 * rmax;
	soft_rebuild(&p->sys);
	p->gone = xcalloc(m + 1, 1);
	p->w = xmalloc(m * sizeof *p->w + 1);
	p->tot = xmalloc(m * sizeof *p->tot + 1);
	p->partner = xmalloc(m * sizeof *p->partner + 1);
#pragma omp parallel for schedule(dynamic, 256)
	for (size_t k = 0; k < m; k++)
		p->w[k] = worst(p, k, &p->partner[k], &p->tot[k]);
}

/* Remove the sphere of the worst pair with the larger total, one at a
 * time, until no overlap exceeds the limit; returns how many went. */
static size_t prune(pruner *p)
{
	size_t removed = 0, m = p->m;
	double *w = p->w;
	for (;;) {
		size_t a = 0;
		for (size_t k = 1; k < m; k++)
			if (w[k] > w[a])
				a = k;
		if (m == 0 || w[a] <= p->limit)
			return removed;
		size_t out = a;
		if (p->partner[a] >= 0 && p->tot[p->partner[a]] > p->tot[a])
			out = (size_t)p->partner[a];
		p->gone[out] = 1;
		w[out] = 0;
		removed++;
		for (size_t q = p->sys.nb_start[out]; q < p->sys.nb_start[out + 1]; q++) {
			size_t j = (size_t)p->sys.nb[q];
			if (!p->gone[j])
				w[j] = worst(p, j, &p->partner[j], &p->tot[j]);
		}
	}
}

static void pruner_free(pruner *p)
{
	soft_free(&p->sys);
	free(p->gone);
	free(p->idx);
	free(p->x);
	free(p->r);
	free(p->s);
	free(p->w);
	free(p->tot);
	free(p->partner);
}

size_t prune_overlaps(spheres *S, const surface *surf, double depth, double limit)
{
	pruner p;
	pruner_init(&p, S, surf, depth, limit);
	size_t removed = prune(&p);
	uint8_t *keep = xmalloc(S->n + 1);
	memset(keep, 1, S->n);
	for (size_t k = 0; k < p.m; k++)
		if (p.gone[k])
			keep[p.idx[k]] = 0;
	spheres_compact(S, keep);
	free(keep);
	pruner_free(&p);
	return removed;
}
