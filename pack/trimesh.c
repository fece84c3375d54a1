/* Welding, closedness, orientation and measures of boundary triangulations.
 *
 * Closed: every undirected edge is shared by exactly two triangles.
 * Oriented: two triangles sharing edge {a,b} traverse it in opposite
 * directions (a->b in one, b->a in the other); orientation is propagated
 * through each connected shell by a breadth-first walk.
 * Outward: the enclosed volume V = sum over triangles of a.(b x c)/6
 * (divergence theorem) is positive for a shell whose normals point out. A
 * shell lying inside an odd number of other shells bounds a cavity, so its
 * normals must point into the cavity (negative V); nesting is decided by
 * the parity of crossings of a ray from one of its vertices. */
#include <stdlib.h>
#include <string.h>

#include "lib/err.h"
#include "lib/vec3.h"
#include "pack/trimesh.h"

typedef struct {
	double p[3];
	size_t idx;
} keyed_vertex;

static int cmp_vertex(const void *a, const void *b)
{
	const double *p = ((const keyed_vertex *)a)->p, *q = ((const keyed_vertex *)b)->p;
	for (int k = 0; k < 3; k++)
		if (p[k] != q[k])
			return p[k] < q[k] ? -1 : 1;
	size_t i = ((const keyed_vertex *)a)->idx, j = ((const keyed_vertex *)b)->idx;
	return (i > j) - (i < j);
}

/* Merge vertices with identical coordinates and drop unused ones. */
static void weld(trimesh *m)
{
	keyed_vertex *kv = xmalloc(m->nvert * sizeof *kv);
	for (size_t i = 0; i < m->nvert; i++) {
		v3_copy(kv[i].p, m->vert + 3 * i);
		kv[i].idx = i;
	}
	qsort(kv, m->nvert, sizeof *kv, cmp_vertex);
	int32_t *map = xmalloc(m->nvert * sizeof *map);
	size_t nunique = 0;
	for (size_t i = 0; i < m->nvert; i++) {
		if (i == 0 || memcmp(kv[i].p, kv[i - 1].p, sizeof kv[i].p) != 0)
			nunique++;
		map[kv[i].idx] = (int32_t)(nunique - 1);
	}
	/* Renumber in order of first use so the output does not depend on how
	 * the input numbered unused vertices. */
	int32_t *newid = xmalloc(nunique * sizeof *newid);
	for (size_t i = 0; i < nunique; i++)
		newid[i] = -1;
	double *vert = xmalloc(3 * nunique * sizeof *vert);
	size_t nv = 0;
	for (size_t k = 0; k < 3 * m->ntri; k++) {
		int32_t u = map[m->tri[k]];
		if (newid[u] < 0) {
			newid[u] = (int32_t)nv;
			v3_copy(vert + 3 * nv, m->vert + 3 * (size_t)m->tri[k]);
			nv++;
		}
		m->tri[k] = newid[u];
	}
	free(kv);
	free(map);
	free(newid);
	free(m->vert);
	m->vert = vert;
	m->nvert = nv;
}

typedef struct {
	int32_t a, b;  /* a < b */
	int32_t tri;   /* triangle and its local edge k (vertices k, k+1) */
	int8_t k, fwd; /* fwd: the triangle runs a->b */
} half_edge;

static int cmp_edge(const void *x, const void *y)
{
	const half_edge *e = x, *f = y;
	if (e->a != f->a)
		return e->a < f->a ? -1 : 1;
	if (e->b != f->b)
		return e->b < f->b ? -1 : 1;
	return (e->tri > f->tri) - (e->tri < f->tri);
}

/* Neighbour across each local edge and whether the two triangles run the
 * edge the same way (then one of them must be flipped). */
static int build_adjacency(const trimesh *m, const char *source, int32_t *nb, uint8_t *same)
{
	size_t ne = 3 * m->ntri;
	half_edge *e = xmalloc(ne * sizeof *e);
	for (size_t t = 0; t < m->ntri; t++)
		for (int k = 0; k < 3; k++) {
			int32_t u = m->tri[3 * t + k], v = m->tri[3 * t + (k + 1) % 3];
			half_edge *h = &e[3 * t + k];
			h->a = u < v ? u : v;
			h->b = u < v ? v : u;
			h->tri = (int32_t)t;
			h->k = (int8_t)k;
			h->fwd = u < v;
		}
	qsort(e, ne, sizeof *e, cmp_edge);
	size_t open = 0, nonmanifold = 0;
	for (size_t i = 0; i < ne;) {
		size_t j = i;
		while (j < ne && e[j].a == e[i].a && e[j].b == e[i].b)
			j++;
		if (j - i == 1)
			open++;
		else if (j - i > 2)
			nonmanifold++;
		else {
			nb[3 * e[i].tri + e[i].k] = e[i + 1].tri;
			nb[3 * e[i + 1].tri + e[i + 1].k] = e[i].tri;
			same[3 * e[i].tri + e[i].k] = same[3 * e[i + 1].tri + e[i + 1].k] =
			    e[i].fwd == e[i + 1].fwd;
		}
		i = j;
	}
	free(e);
	if (open)
		return err_set("%s: the boundary is not a closed surface: %zu edge%s to only one "
		               "triangle (an open surface encloses no volume to fill)",
		               source, open, open == 1 ? " belongs" : "s belong");
	if (nonmanifold)
		return err_set("%s: the boundary is not a manifold surface: %zu edge%s shared by "
		               "more than two triangles",
		               source, nonmanifold, nonmanifold == 1 ? " is" : "s are");
	return 0;
}

/* Does the ray from o along dir cross triangle (a, b, c)? (Moller-Trumbore) */
static int ray_crosses(const double o[3], const double dir[3], const double *a, const double *b,
                       const double *c)
{
	double e1[3], e2[3], p[3], s[3], q[3];
	v3_sub(e1, b, a);
	v3_sub(e2, c, a);
	v3_cross(p, dir, e2);
	double det = v3_dot(e1, p);
	if (det == 0)
		return 0;
	v3_sub(s, o, a);
	double u = v3_dot(s, p) / det;
	if (u < 0 || u > 1)
		return 0;
	v3_cross(q, s, e1);
	double v = v3_dot(dir, q) / det;
	if (v < 0 || u + v > 1)
		return 0;
	return v3_dot(e2, q) / det > 0;
}

static double tri_volume6(const trimesh *m, size_t t)
{
	const int32_t *v = m->tri + 3 * t;
	double bc[3];
	v3_cross(bc, m->vert + 3 * v[1], m->vert + 3 * v[2]);
	return v3_dot(m->vert + 3 * v[0], bc);
}

/* Flip every shell whose orientation disagrees with its nesting depth. */
static void orient_shells(trimesh *m, const int32_t *comp, int ncomp)
{
	double *vol = xcalloc((size_t)ncomp, sizeof *vol);
	size_t *first = xmalloc((size_t)ncomp * sizeof *first);
	for (size_t t = m->ntri; t-- > 0;) {
		vol[comp[t]] += tri_volume6(m, t);
		first[comp[t]] = t;
	}
	/* An irrational-looking direction, so the ray misses edges and vertices. */
	static const double dir[3] = {0.2898114, 0.5173462, 0.8053527};
	for (int c = 0; c < ncomp; c++) {
		const double *o = m->vert + 3 * (size_t)m->tri[3 * first[c]];
		int depth = 0;
		for (int d = 0; d < ncomp && ncomp > 1; d++) {
			if (d == c)
				continue;
			int crossings = 0;
			for (size_t t = 0; t < m->ntri; t++)
				if (comp[t] == d) {
					const int32_t *v = m->tri + 3 * t;
					crossings +=
					    ray_crosses(o, dir, m->vert + 3 * v[0],
					                m->vert + 3 * v[1], m->vert + 3 * v[2]);
				}
			depth += crossings & 1;
		}
		int want_positive = (depth & 1) == 0;
		if ((vol[c] > 0) != want_positive)
			for (size_t t = 0; t < m->ntri; t++)
				if (comp[t] == c) {
					int32_t s = m->tri[3 * t + 1];
					m->tri[3 * t + 1] = m->tri[3 * t + 2];
					m->tri[3 * t + 2] = s;
				}
	}
	free(vol);
	free(first);
}

int trimesh_close(trimesh *m, const char *source)
{
	if (m->ntri == 0)
		return err_set("%s: no surface triangles: the geometry has no closed boundary",
		               source);
	weld(m);
	int32_t *nb = xmalloc(3 * m->ntri * sizeof *nb);
	uint8_t *same = xmalloc(3 * m->ntri);
	int32_t *comp = xmalloc(m->ntri * sizeof *comp);
	uint8_t *flip = xcalloc(m->ntri, 1);
	int32_t *queue = xmalloc(m->ntri * sizeof *queue);
	int rc = build_adjacency(m, source, nb, same);
	int ncomp = 0;
	for (size_t t = 0; t < m->ntri; t++)
		comp[t] = -1;
	for (size_t s = 0; rc == 0 && s < m->ntri; s++) {
		if (comp[s] >= 0)
			continue;
		size_t head = 0, tail = 0;
		queue[tail++] = (int32_t)s;
		comp[s] = ncomp;
		while (rc == 0 && head < tail) {
			int32_t t = queue[head++];
			for (int k = 0; k < 3; k++) {
				int32_t u = nb[3 * t + k];
				uint8_t want = flip[t] ^ same[3 * t + k];
				if (comp[u] < 0) {
					comp[u] = ncomp;
					flip[u] = want;
					queue[tail++] = u;
				} else if (flip[u] != want) {
					rc = err_set("%s: the boundary surface is not orientable",
					             source);
				}
			}
		}
		ncomp++;
	}
	if (rc == 0) {
		for (size_t t = 0; t < m->ntri; t++)
			if (flip[t]) {
				int32_t s = m->tri[3 * t + 1];
				m->tri[3 * t + 1] = m->tri[3 * t + 2];
				m->tri[3 * t + 2] = s;
			}
		orient_shells(m, comp, ncomp);
	}
	free(nb);
	free(same);
	free(comp);
	free(flip);
	free(queue);
	return rc;
}

void trimesh_measure(const trimesh *m, double *volume, double *area, double bmin[3], double bmax[3])
{
	double v6 = 0, a2 = 0;
	for (size_t t = 0; t < m->ntri; t++) {
		const int32_t *v = m->tri + 3 * t;
		double e1[3], e2[3], n[3];
		v3_sub(e1, m->vert + 3 * v[1], m->vert + 3 * v[0]);
		v3_sub(e2, m->vert + 3 * v[2], m->vert + 3 * v[0]);
		v3_cross(n, e1, e2);
		a2 += v3_norm(n);
		v6 += tri_volume6(m, t);
	}
	*volume = v6 / 6;
	*area = a2 / 2;
	for (int k = 0; k < 3; k++) {
		bmin[k] = m->nvert ? m->vert[k] : 0;
		bmax[k] = bmin[k];
	}
	for (size_t i = 0; i < m->nvert; i++)
		for (int k = 0; k < 3; k++) {
			bmin[k] = fmin(bmin[k], m->vert[3 * i + k]);
			bmax[k] = fmax(bmax[k], m->vert[3 * i + k]);
		}
}

void trimesh_free(trimesh *m)
{
	free(m->vert);
	free(m->tri);
	memset(m, 0, sizeof *m);
}

/* Ericson, Real-Time Collision Detection (2005), 5.1.5: the Voronoi region
 * of p among the triangle's vertices, edges and face, by barycentric signs. */
void trimesh_closest_point(const double a[3], const double b[3], const double c[3],
                           const double p[3], double q[3])
{
	double ab[3], ac[3], ap[3], bp[3], cp[3];
	v3_sub(ab, b, a);
	v3_sub(ac, c, a);
	v3_sub(ap, p, a);
	double d1 = v3_dot(ab, ap), d2 = v3_dot(ac, ap);
	if (d1 <= 0 && d2 <= 0) {
		v3_copy(q, a);
		return;
	}
	v3_sub(bp, p, b);
	double d3 = v3_dot(ab, bp), d4 = v3_dot(ac, bp);
	if (d3 >= 0 && d4 <= d3) {
		v3_copy(q, b);
		return;
	}
	double vc = d1 * d4 - d3 * d2;
	if (vc <= 0 && d1 >= 0 && d3 <= 0) {
		v3_copy(q, a);
		v3_axpy(q, ab, d1 / (d1 - d3));
		return;
	}
	v3_sub(cp, p, c);
	double d5 = v3_dot(ab, cp), d6 = v3_dot(ac, cp);
	if (d6 >= 0 && d5 <= d6) {
		v3_copy(q, c);
		return;
	}
	double vb = d5 * d2 - d1 * d6;
	if (vb <= 0 && d2 >= 0 && d6 <= 0) {
		v3_copy(q, a);
		v3_axpy(q, ac, d2 / (d2 - d6));
		return;
	}
	double va = d3 * d6 - d5 * d4;
	if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) {
		double bc[3];
		v3_sub(bc, c, b);
		v3_copy(q, b);
		v3_axpy(q, bc, (d4 - d3) / ((d4 - d3) + (d5 - d6)));
		return;
	}
	double den = 1 / (va + vb + vc);
	v3_copy(q, a);
	v3_axpy(q, ab, vb * den);
	v3_axpy(q, ac, vc * den);
}
