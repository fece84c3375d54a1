/* Void filling along the boundary (see voids.h).
 *
 * The voids the cut leaves lie against the boundary, so candidates are
 * spheres tangent to it: at a point q of a boundary triangle with outward
 * normal n, the sphere of radius rho centred at q - rho n stays clear of a
 * sphere (x_j, r_j) iff |a - rho n| >= rho + r_j with a = q - x_j, i.e.
 *     rho <= (|a|^2 - r_j^2) / (2 (a.n + r_j))      when a.n + r_j > 0
 * (no bound otherwise). The room rho(q) is the least bound over the
 * spheres near q. Points q on a lattice of spacing 0.6 rmin over every
 * triangle are visited from the roomiest down; a sphere goes in where the
 * room, counting the spheres inserted so far, still holds a sphere of
 * rmin, with a radius drawn from the distribution but no larger than the
 * room. At the roomiest point of a void the sphere touches the boundary
 * and, typically, three neighbours. Near an edge of the boundary a
 * candidate could cross the adjacent face: its depth is checked against
 * the whole boundary before it goes in. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lib/err.h"
#include "lib/rng.h"
#include "lib/vec3.h"
#include "pack/cells.h"
#include "pack/voids.h"

typedef struct {
	double room;
	double q[3], n[3]; /* boundary point and outward normal */
	uint64_t key;      /* triangle and lattice point: a total order for ties */
} candidate;

static int cmp_candidate(const void *x, const void *y)
{
	const candidate *a = x, *b = y;
	if (a->room != b->room)
		return a->room > b->room ? -1 : 1;
	return (a->key > b->key) - (a->key < b->key);
}

/* The room at q against sphere (x, r). */
static double bound(const double q[3], const double n[3], const double *x, double r)
{
	double a[3];
	v3_sub(a, q, x);
	double an = v3_dot(a, n) + r;
	if (an <= 0)
		return INFINITY;
	return (v3_dot(a, a) - r * r) / (2 * an);
}

/* The room at q against the spheres of g (points x, radii r), capped; once
 * it falls below `enough` the search stops (the point is of no use). The
 * cell of q comes first, as its spheres are the likeliest to bound it. */
static double room(const pack_cells *g, const double *x, const double *r, const double q[3],
                   const double n[3], double cap, double enough)
{
	int c0[3];
	pack_cells_coord(g, q, c0);
	double c = cap;
	for (int o = 0; o < 27; o++) {
		int c1[3]; /* from offset 13, the cell itself */
		if (!pack_cells_near(g->dim, c0, (o + 13) % 27, c1))
			continue;
		size_t id = pack_cells_index(g, c1);
		for (size_t q2 = g->start[id]; q2 < g->start[id + 1]; q2++) {
			size_t j = (size_t)g->item[q2];
			c = fmin(c, bound(q, n, x + 3 * j, r[j]));
		}
		if (c < enough)
			return c;
	}
	return c;
}

/* Lattice points of triangle t with room >= cmin, appended to *out. */
static void scan_triangle(const dem_geometry *geo, size_t t, double h, const pack_cells *g,
                          const double *x, const double *r, double cmin, double cap,
                          candidate **out, size_t *n, size_t *capn)
{
	const int32_t *v = geo->tri + 3 * t;
	const double *p[3] = {geo->vert + 3 * v[0], geo->vert + 3 * v[1], geo->vert + 3 * v[2]};
	/* Lattice axes: along the longest edge (a -> b) and across it. */
	int k0 = 0;
	double best = -1;
	for (int k = 0; k < 3; k++) {
		double e[3];
		v3_sub(e, p[(k + 1) % 3], p[k]);
		if (v3_dot(e, e) > best) {
			best = v3_dot(e, e);
			k0 = k;
		}
	}
	const double *a = p[k0], *b = p[(k0 + 1) % 3], *c = p[(k0 + 2) % 3];
	double e[3], f[3], nrm[3], u[3], w[3];
	v3_sub(e, b, a);
	v3_sub(f, c, a);
	v3_cross(nrm, e, f);
	double area2 = v3_norm(nrm);
	if (!(area2 > 0))
		return;
	v3_scale(nrm, nrm, 1 / area2);
	double len = v3_norm(e);
	v3_scale(u, e, 1 / len);
	v3_cross(w, nrm, u); /* in-plane, across the edge, towards c */
	double cu = v3_dot(f, u), cw = v3_dot(f, w);
	long nu = (long)ceil(len / h), nw = (long)ceil(cw / h);
	for (long j = 0; j < nw; j++)
		for (long i = 0; i < nu; i++) {
			double su = (i + 0.5) * h, sw = (j + 0.5) * h;
			/* inside the triangle: below the edges a-c and b-c */
			if (sw * cu > su * cw || sw * (len - cu) > (len - su) * cw)
				continue;
			candidate cd;
			v3_copy(cd.q, a);
			v3_axpy(cd.q, u, su);
			v3_axpy(cd.q, w, sw);
			v3_copy(cd.n, nrm);
			cd.room = room(g, x, r, cd.q, cd.n, cap, cmin);
			if (cd.room < cmin)
				continue;
			cd.key = ((uint64_t)t << 32) | (uint64_t)(j * nu + i);
			if (*n == *capn) {
				*capn = *capn ? 2 * *capn : 64;
				*out = xrealloc(*out, *capn * sizeof **out);
			}
			(*out)[(*n)++] = cd;
		}
}

/* The spheres of S that can bound a tangent sphere, those whose depth may
 * be below `reach`, copied to *x and *r (a grid over them alone is
 * small); returns how many. */
static size_t near_boundary(const spheres *S, double reach, double **x, double **r)
{
	size_t m = 0;
	for (size_t i = 0; i < S->n; i++)
		m += S->lo[i] < reach;
	*x = xmalloc(3 * m * sizeof **x + 1);
	*r = xmalloc(m * sizeof **r + 1);
	for (size_t i = 0, k = 0; i < S->n; i++)
		if (S->lo[i] < reach) {
			v3_copy(*x + 3 * k, S->x + 3 * i);
			(*r)[k++] = S->r[i];
		}
	return m;
}

/* The lattice points of every boundary triangle with room >= cmin among
 * the spheres of S, roomiest first (ties by triangle and point, so the
 * order does not depend on the threads); their number in *count. */
static candidate *candidates(const spheres *S, const dem_geometry *geo, double h, double cmin,
                             double cap, double rmax, size_t *count)
{
	double *x, *r;
	size_t m = near_boundary(S, 2 * cap + rmax, &x, &r);
	pack_cells g;
	pack_cells_build(&g, x, m, 2 * cap + rmax, NULL);
	candidate *all = NULL;
	size_t nall = 0, ntri = geo->ntri;
#pragma omp parallel
	{
		candidate *mine = NULL;
		size_t n = 0, capn = 0;
#pragma omp for schedule(dynamic, 16) nowait
		for (size_t t = 0; t < ntri; t++)
			scan_triangle(geo, t, h, &g, x, r, cmin, cap, &mine, &n, &capn);
#pragma omp critical
		{
			if (n) {
				all = xrealloc(all, (nall + n) * sizeof *all);
				memcpy(all + nall, mine, n * sizeof *mine);
				nall += n;
			}
		}
		free(mine);
	}
	pack_cells_free(&g);
	free(x);
	free(r);
	if (nall)
		qsort(all, nall, sizeof *all, cmp_candidate);
	*count = nall;
	return all;
}

/* The spheres inserted so far (those of S from index `first` on) in a
 * linked-cell grid over the boundary's bounding box: they come one at a
 * time, each to be checked against those before it. */
typedef struct {
	const double *lo; /* the grid's corner */
	double edge;
	int dim[3];
	long *head, *next; /* the last sphere in each cell, the one before it */
	size_t first, n;
} inserted_grid;

static void inserted_init(inserted_grid *g, const dem_geometry *geo, double edge, size_t first)
{
	size_t ngrid = 1;
	g->lo = geo->bbox_min;
	g->edge = edge;
	for (int k = 0; k < 3; k++) {
		g->dim[k] = (int)ceil((geo->bbox_max[k] - geo->bbox_min[k]) / edge) + 1;
		ngrid *= (size_t)g->dim[k];
	}
	g->head = xmalloc(ngrid * sizeof *g->head);
	for (size_t k = 0; k < ngrid; k++)
		g->head[k] = -1;
	g->next = NULL;
	g->first = first;
	g->n = 0;
}

/* The cell coordinates of p, clamped to the grid. */
static void inserted_coord(const inserted_grid *g, const double p[3], int c[3])
{
	for (int q = 0; q < 3; q++) {
		c[q] = (int)floor((p[q] - g->lo[q]) / g->edge);
		c[q] = c[q] < 0 ? 0 : c[q] >= g->dim[q] ? g->dim[q] - 1 : c[q];
	}
}

static size_t inserted_index(const inserted_grid *g, const int c[3])
{
	return ((size_t)c[2] * (size_t)g->dim[1] + (size_t)c[1]) * (size_t)g->dim[0] + (size_t)c[0];
}

/* cd's room, bounded again by the inserted spheres around it. */
static void inserted_bound(const inserted_grid *g, const spheres *S, candidate *cd)
{
	int c[3];
	inserted_coord(g, cd->q, c);
	for (int o = 0; o < 27; o++) {
		int cc[3];
		if (!pack_cells_near(g->dim, c, o, cc))
			continue;
		size_t id = inserted_index(g, cc);
		for (long j = g->head[id]; j >= 0; j = g->next[j]) {
			size_t i = g->first + (size_t)j;
			cd->room = fmin(cd->room, bound(cd->q, cd->n, S->x + 3 * i, S->r[i]));
		}
	}
}

static void inserted_add(inserted_grid *g, const double p[3])
{
	int c[3];
	inserted_coord(g, p, c);
	size_t id = inserted_index(g, c);
	g->next = xrealloc(g->next, (g->n + 1) * sizeof *g->next);
	g->next[g->n] = g->head[id];
	g->head[id] = (long)g->n;
	g->n++;
}

/* A radius from d, drawn again (up to 20 times) while larger than the
 * room, then brought within [cmin, room]. */
static double draw_radius(const psd *d, rng *gen, double room, double cmin)
{
	double rad = psd_sample(d, gen);
	for (int t = 0; t < 20 && rad > room; t++)
		rad = psd_sample(d, gen);
	return fmax(cmin, fmin(rad, room));
}

size_t voids_fill(spheres *S, const surface *surf, const dem_geometry *geo, const psd *d,
                  uint64_t seed)
{
	double rmax = d->rmax;
	for (size_t i = 0; i < S->n; i++)
		rmax = fmax(rmax, S->r[i]);
	double cmin = d->rmin, cap = rmax, h = 0.6 * d->rmin;
	size_t nall;
	candidate *all = candidates(S, geo, h, cmin, cap, rmax, &nall);
	/* Greedy insertion, roomiest first, against the spheres inserted so
	 * far. */
	rng gen;
	rng_seed_stream(&gen, seed, 0x766f6964);
	inserted_grid g;
	inserted_init(&g, geo, 2 * cap + rmax, S->n);
	for (size_t k = 0; k < nall; k++) {
		candidate *cd = &all[k];
		inserted_bound(&g, S, cd);
		if (cd->room < cmin)
			continue;
		double rad = draw_radius(d, &gen, cd->room, cmin), p[3];
		v3_copy(p, cd->q);
		v3_axpy(p, cd->n, -rad);
		int32_t hint = -1;
		double s = surface_distance(surf, p, NULL, &hint);
		if (s < rad * (1 - 1e-9))
			continue;
		spheres_push(S, p, rad, s, s);
		inserted_add(&g, p);
	}
	free(g.head);
	free(g.next);
	free(all);
	return g.n;
}
