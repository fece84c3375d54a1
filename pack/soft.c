/* Neighbour list and forces of the soft-sphere system (see soft.h).
 *
 * Verlet list: pairs with d_ij < r_i + r_j + skin, found through a cell
 * grid of edge >= 2 r_max + skin. It stays valid while every sphere has
 * moved less than (skin - 2 max growth of a radius) / 2 since the build.
 *
 * Boundary: at each build a sphere near the boundary stores the tangent
 * plane at its closest boundary point, s(x) = s_q - n.(x - x_q); between
 * builds it moves less than skin/2, over which the plane is exact for a
 * flat face and off by (skin/2)^2 / 2R on a face of curvature radius R.
 * Since the signed distance is 1-Lipschitz, a sphere with
 * s_q - |x - x_q| > r + skin cannot touch the boundary before the next
 * build and is not queried. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lib/err.h"
#include "lib/vec3.h"
#include "pack/cells.h"
#include "pack/par.h"
#include "pack/soft.h"
#include "pack/trimesh.h"

void soft_init(soft_system *s, size_t n, size_t nmobile, double *x, double *r)
{
	memset(s, 0, sizeof *s);
	s->n = n;
	s->x = x;
	s->r = r;
	s->nmobile = nmobile;
	s->nb_start = xcalloc(n + 1, sizeof *s->nb_start);
	s->xr = xmalloc(4 * n * sizeof *s->xr + 1);
	s->x_built = xmalloc(3 * n * sizeof *s->x_built + 1);
	s->r_built = xmalloc(n * sizeof *s->r_built + 1);
	s->wall_s0 = xmalloc(n * sizeof *s->wall_s0 + 1);
	s->wall_xq = xmalloc(3 * n * sizeof *s->wall_xq + 1);
	s->wall_xb = xmalloc(3 * n * sizeof *s->wall_xb + 1);
	s->wall_hint = xmalloc(n * sizeof *s->wall_hint + 1);
	s->wall_margin = xcalloc(n + 1, sizeof *s->wall_margin);
	s->wall_count = xcalloc(n + 1, 1);
	for (size_t i = 0; i < n; i++) {
		s->wall_s0[i] = -INFINITY;
		s->wall_hint[i] = -1;
	}
	memcpy(s->wall_xq, x, 3 * n * sizeof *x);
	s->stale = 1;
}

void soft_free(soft_system *s)
{
	free(s->nb_start);
	free(s->xr);
	free(s->nb);
	free(s->nb_shift);
	free(s->x_built);
	free(s->r_built);
	free(s->wall_s0);
	free(s->wall_xq);
	free(s->wall_xb);
	free(s->wall_hint);
	free(s->wall_margin);
	free(s->wall_count);
	free(s->wall_pool);
	free(s->wall_near);
	free(s->wall_first);
	free(s->wall_second);
	memset(s, 0, sizeof *s);
}

static int periodic(const soft_system *s) { return s->box[0] > 0; }

void soft_delta(const soft_system *s, size_t i, size_t j, double d[3])
{
	v3_sub(d, s->x + 3 * j, s->x + 3 * i);
	if (periodic(s))
		for (int k = 0; k < 3; k++)
			d[k] -= s->box[k] * nearbyint(d[k] / s->box[k]);
}

static int is_mobile(const soft_system *s, size_t i) { return i < s->nmobile; }

/* x_j - x_i through the periodic image with the given code (13: none). */
static inline void image_delta(const soft_system *s, size_t i, size_t j, int code, double d[3])
{
	v3_sub(d, s->x + 3 * j, s->x + 3 * i);
	if (code != 13)
		v3_add(d, d, s->shift[code]);
}

/* The image code of a minimum-image separation d (small grids). */
static int image_code(const soft_system *s, size_t i, size_t j, const double d[3])
{
	int code = 0;
	static const int stride[3] = {1, 3, 9};
	for (int k = 0; k < 3; k++) {
		double raw = s->x[3 * j + k] - s->x[3 * i + k];
		code += stride[k] * (int)(nearbyint((d[k] - raw) / s->box[k]) + 1);
	}
	return code;
}

/* A growable neighbour buffer for one chunk of spheres. */
typedef struct {
	int32_t *j;
	uint8_t *shift;
	size_t n, cap;
} nbuf;

/* Room for m more neighbours. */
static void nbuf_reserve(nbuf *b, size_t m)
{
	if (b->n + m <= b->cap)
		return;
	b->cap = 2 * (b->n + m) > 4096 ? 2 * (b->n + m) : 4096;
	b->j = xrealloc(b->j, b->cap * sizeof *b->j);
	b->shift = xrealloc(b->shift, b->cap);
}

/* The candidates of one grid cell: every sphere in the cells around it,
 * moved to its image next to the cell (or left where it is in a periodic
 * box too short for three cells a side, where each pair takes its minimum
 * image), with the image code; arrays by coordinate for a tight test loop. */
typedef struct {
	double *x[4]; /* x, y, z, r */
	int32_t *j;
	uint8_t *code;
	size_t n, cap;
	size_t own; /* half lists: the first `own` are the cell's own spheres */
} cands;

/* Append the spheres of the cell at coordinates cc (wrapped if periodic). */
static void cands_add(const soft_system *s, const pack_cells *g, const double *xs, const int cc[3],
                      int small, cands *c)
{
	int code = 13, w[3];
	double sh[3] = {0, 0, 0};
	for (int k = 0; k < 3; k++) {
		w[k] = cc[k] < 0            ? cc[k] + g->dim[k]
		       : cc[k] >= g->dim[k] ? cc[k] - g->dim[k]
		                            : cc[k];
		int o = cc[k] < w[k] ? -1 : cc[k] > w[k] ? 1 : 0;
		if (periodic(s) && !small) {
			code += (k == 0 ? 1 : k == 1 ? 3 : 9) * o;
			sh[k] = o * s->box[k];
		}
	}
	size_t id =
	    ((size_t)w[2] * (size_t)g->dim[1] + (size_t)w[1]) * (size_t)g->dim[0] + (size_t)w[0];
	size_t m = g->start[id + 1] - g->start[id];
	if (c->n + m > c->cap) {
		c->cap = 2 * (c->n + m);
		for (int k = 0; k < 4; k++)
			c->x[k] = xrealloc(c->x[k], c->cap * sizeof *c->x[k]);
		c->j = xrealloc(c->j, c->cap * sizeof *c->j);
		c->code = xrealloc(c->code, c->cap);
	}
	for (size_t q = g->start[id]; q < g->start[id + 1]; q++, c->n++) {
		for (int k = 0; k < 3; k++)
			c->x[k][c->n] = xs[4 * q + k] + sh[k];
		c->x[3][c->n] = xs[4 * q + 3];
		c->j[c->n] = g->item[q];
		c->code[c->n] = (uint8_t)code;
	}
}

/* The candidates of the cell at c0: the 27 cells around it; for a half
 * list, its own cell first and then the 13 cells after it in the order
 * (z, y, x), so that each pair of cells is met once. */
static void cands_gather(const soft_system *s, const pack_cells *g, const double *xs,
                         const int c0[3], int small, cands *c)
{
	int lo[3], hi[3], half = s->half && !small;
	for (int k = 0; k < 3; k++) {
		int span = g->dim[k] >= 3 || !periodic(s) ? 1 : 0;
		lo[k] = c0[k] - span;
		hi[k] = c0[k] + span;
		if (!periodic(s)) {
			lo[k] = lo[k] < 0 ? 0 : lo[k];
			hi[k] = hi[k] >= g->dim[k] ? g->dim[k] - 1 : hi[k];
		}
	}
	c->n = c->own = 0;
	if (half) {
		cands_add(s, g, xs, c0, small, c);
		c->own = c->n;
	}
	for (int cz = lo[2]; cz <= hi[2]; cz++)
		for (int cy = lo[1]; cy <= hi[1]; cy++)
			for (int cx = lo[0]; cx <= hi[0]; cx++) {
				int cc[3] = {cx, cy, cz};
				int after = cz != c0[2]   ? cz > c0[2]
				            : cy != c0[1] ? cy > c0[1]
				                          : cx > c0[0];
				if (!half || after)
					cands_add(s, g, xs, cc, small, c);
			}
}

static void cands_free(cands *c)
{
	for (int k = 0; k < 4; k++)
		free(c->x[k]);
	free(c->j);
	free(c->code);
}

/* Append the neighbours of sphere i within r_i + r_j + skin among the
 * candidates of its cell to b (each pair once for a half list); returns
 * their number. A loop without
 * branches tests the distances and one more appends the hits (the
 * compiler vectorises the first); a periodic box too short for three
 * cells a side takes the minimum image of each pair instead. */
static size_t scan_neighbours(const soft_system *s, const cands *c, size_t i, int small, nbuf *b)
{
	const double *xi = s->x + 3 * i, reach = s->r[i] + s->skin;
	size_t count = 0;
	if (small) {
		for (size_t k = 0; k < c->n; k++) {
			size_t j = (size_t)c->j[k];
			double d[3], cut = reach + c->x[3][k];
			soft_delta(s, i, j, d);
			if (j == i || (s->half && j < i) || v3_dot(d, d) >= cut * cut)
				continue;
			nbuf_reserve(b, 1);
			b->j[b->n] = (int32_t)j;
			b->shift[b->n++] = (uint8_t)image_code(s, i, j, d);
			count++;
		}
		return count;
	}
	enum { BLOCK = 256 };
	const double *restrict cx = c->x[0], *restrict cy = c->x[1], *restrict cz = c->x[2],
	                       *restrict cr = c->x[3];
	double x0 = xi[0], y0 = xi[1], z0 = xi[2];
	for (size_t k0 = 0; k0 < c->n; k0 += BLOCK) {
		size_t m = c->n - k0 < BLOCK ? c->n - k0 : BLOCK;
		unsigned char hit[BLOCK];
		for (size_t k = 0; k < m; k++) {
			double dx = cx[k0 + k] - x0, dy = cy[k0 + k] - y0, dz = cz[k0 + k] - z0,
			       cut = reach + cr[k0 + k];
			hit[k] = dx * dx + dy * dy + dz * dz < cut * cut;
		}
		nbuf_reserve(b, m);
		int32_t *restrict oj = b->j + b->n;
		uint8_t *restrict oc = b->shift + b->n;
		size_t o = 0;
		for (size_t k = 0; k < m; k++) {
			int32_t j = c->j[k0 + k];
			oj[o] = j;
			oc[o] = c->code[k0 + k];
			/* of the cell's own spheres, a half list takes the later */
			o += hit[k] & ((size_t)j != i) & (k0 + k >= c->own || (size_t)j > i);
		}
		b->n += o;
		count += o;
	}
	return count;
}

/* Distance from p to the triangle k (pack/trimesh.h) and the closest point. */
static double triangle_distance(const soft_system *s, int32_t k, const double p[3], double q[3])
{
	const int32_t *t = s->wall_tri + 3 * (size_t)k;
	trimesh_closest_point(s->wall_vert + 3 * t[0], s->wall_vert + 3 * t[1],
	                      s->wall_vert + 3 * t[2], p, q);
	double d[3];
	v3_sub(d, p, q);
	return v3_norm(d);
}

/* The triangles of e[0..m) sorted by their distance from p (then by
 * index), with that distance rounded down to single precision. */
static void sort_by_distance(const soft_system *s, const double p[3], wall_entry *e, size_t m)
{
	double q[3];
	for (size_t k = 0; k < m; k++) { /* insertion sort: m is small */
		wall_entry ek = e[k];
		double dk = triangle_distance(s, ek.tri, p, q);
		ek.dist = (float)dk;
		if (ek.dist > dk)
			ek.dist = nextafterf(ek.dist, -INFINITY);
		size_t at = k;
		for (; at > 0 && (e[at - 1].dist > ek.dist ||
		                  (e[at - 1].dist == ek.dist && e[at - 1].tri > ek.tri));
		     at--)
			e[at] = e[at - 1];
		e[at] = ek;
	}
}

/* The first two entries of sphere i's list, kept apart (see wall_contact). */
static void wall_inline(soft_system *s, size_t i)
{
	const wall_entry *e = s->wall_pool + i * WALL_MAX;
	int m = s->wall_count[i];
	s->wall_near[i] = m > 0 ? e[0].dist : INFINITY;
	s->wall_first[i] = m > 0 ? e[0].tri : -1;
	s->wall_second[i] = m > 1 ? e[1].dist : INFINITY;
}

/* The boundary triangles sphere i may touch before the next build. A query
 * at x_q lists the triangles within r + skin + WALL_MARGIN (the WALL_MAX
 * nearest, the margin shrinking to what they cover if there are more);
 * the list serves every build while the sphere stays within the margin of
 * x_q. At every build the list is sorted again by the distances from the
 * sphere's position then, the base point x_b, so that the bound in
 * wall_contact() stays tight. Without a list, the depth bound
 * s_q - |x - x_q| tells whether the sphere can reach the boundary at all. */
static void wall_update(soft_system *s, size_t i)
{
	double d[3], *xi = s->x + 3 * i;
	wall_entry *pool = s->wall_pool + i * WALL_MAX;
	v3_sub(d, xi, s->wall_xq + 3 * i);
	double moved = v3_norm(d), reach = s->r[i] + s->skin;
	v3_copy(s->wall_xb + 3 * i, xi);
	if (s->wall_count[i] && moved <= s->wall_margin[i]) {
		sort_by_distance(s, xi, pool, s->wall_count[i]);
		wall_inline(s, i);
		return;
	}
	s->wall_count[i] = 0;
	wall_inline(s, i);
	if (s->wall_s0[i] - moved > reach)
		return;
	v3_copy(s->wall_xq + 3 * i, xi);
	s->wall_s0[i] = surface_distance(s->wall, xi, NULL, &s->wall_hint[i]);
	if (s->wall_s0[i] > reach + WALL_MARGIN * s->skin)
		return;
	enum { CAP = 4 * WALL_MAX };
	int32_t found[CAP];
	wall_entry buf[CAP];
	double margin = WALL_MARGIN * s->skin;
	size_t m = surface_near(s->wall, xi, reach + margin, found, CAP);
	m = m < CAP ? m : CAP;
	for (size_t k = 0; k < m; k++)
		buf[k].tri = found[k];
	sort_by_distance(s, xi, buf, m);
	if (m > WALL_MAX) { /* keep the nearest; the list covers less */
		margin = fmin(margin, buf[WALL_MAX].dist - reach);
		m = WALL_MAX;
	}
	memcpy(pool, buf, m * sizeof *buf);
	s->wall_count[i] = (uint8_t)m;
	wall_inline(s, i);
	s->wall_margin[i] = margin;
}

/* The closest point q of the boundary to sphere i among its listed
 * triangles, if closer than its radius; returns that distance (or
 * INFINITY). A triangle listed at distance d_k from x_b is at least
 * d_k - |x - x_b| from x (the distance is 1-Lipschitz), so the ascending
 * list is cut as soon as that bound reaches the best found or the radius.
 * Most spheres are decided by the first two entries, kept apart from the
 * list so that the test reads memory in sphere order only. */
static double wall_contact(const soft_system *s, size_t i, double q[3])
{
	const double *xi = s->x + 3 * i;
	double d[3], qk[3], best = s->r[i];
	v3_sub(d, xi, s->wall_xb + 3 * i);
	double moved = v3_norm(d), found = INFINITY;
	if (s->wall_near[i] - moved >= best)
		return found;
	double d0 = triangle_distance(s, s->wall_first[i], xi, qk);
	if (d0 < best) {
		best = found = d0;
		v3_copy(q, qk);
	}
	if (s->wall_second[i] - moved >= best)
		return found;
	const wall_entry *e = s->wall_pool + i * WALL_MAX;
	for (int k = 1; k < s->wall_count[i] && e[k].dist - moved < best; k++) {
		double dk = triangle_distance(s, e[k].tri, xi, qk);
		if (dk < best) {
			best = found = dk;
			v3_copy(q, qk);
		}
	}
	return found;
}

void soft_rebuild(soft_system *s)
{
	if (s->wall && !s->wall_pool) {
		s->wall_pool = xmalloc(s->nmobile * WALL_MAX * sizeof *s->wall_pool + 1);
		s->wall_near = xmalloc(s->nmobile * sizeof *s->wall_near + 1);
		s->wall_first = xmalloc(s->nmobile * sizeof *s->wall_first + 1);
		s->wall_second = xmalloc(s->nmobile * sizeof *s->wall_second + 1);
		for (size_t i = 0; i < s->nmobile; i++)
			s->wall_near[i] = INFINITY;
	}
	for (int code = 0; code < 27; code++)
		for (int k = 0; k < 3; k++)
			s->shift[code][k] = s->box[k] * (double)(code /
			                                             (k == 0   ? 1
			                                              : k == 1 ? 3
			                                                       : 9) %
			                                             3 -
			                                         1);
	if (periodic(s))
		for (size_t i = 0; i < 3 * s->n; i++)
			s->x[i] -= s->box[i % 3] * floor(s->x[i] / s->box[i % 3]);
	double rmax = 0;
	for (size_t i = 0; i < s->n; i++)
		rmax = fmax(rmax, s->r[i]);
	pack_cells g;
	pack_cells_build(&g, s->x, s->n, 2 * rmax + s->skin, periodic(s) ? s->box : NULL);
	size_t n = s->n;
	double *xs = xmalloc(4 * n * sizeof *xs + 1);
	for (size_t q = 0; q < n; q++) {
		size_t i = (size_t)g.item[q];
		v3_copy(xs + 4 * q, s->x + 3 * i);
		xs[4 * q + 3] = s->r[i];
	}
	/* Neighbours by chunks of grid cells into their own buffers, then
	 * laid out in sphere order: the same list whatever the thread count. */
	int small = periodic(s) && (g.dim[0] < 3 || g.dim[1] < 3 || g.dim[2] < 3);
	size_t ncell = (size_t)g.dim[0] * (size_t)g.dim[1] * (size_t)g.dim[2];
	enum { CHUNK = 64 };
	size_t nchunk = (ncell + CHUNK - 1) / CHUNK;
	nbuf *buf = xcalloc(nchunk + 1, sizeof *buf);
	size_t *at = xmalloc(n * sizeof *at + 1);
	int32_t *chunk_of = xmalloc(n * sizeof *chunk_of + 1);
#pragma omp parallel if (n >= PAR_MIN)
	{
		cands c = {0};
#pragma omp for schedule(dynamic, 1)
		for (size_t ch = 0; ch < nchunk; ch++) {
			size_t end = (ch + 1) * CHUNK < ncell ? (ch + 1) * CHUNK : ncell;
			for (size_t id = ch * CHUNK; id < end; id++) {
				int mobile = 0;
				for (size_t q = g.start[id]; q < g.start[id + 1]; q++)
					mobile |= is_mobile(s, (size_t)g.item[q]);
				if (!mobile)
					continue;
				int c0[3] = {(int)(id % (size_t)g.dim[0]),
				             (int)(id / (size_t)g.dim[0] % (size_t)g.dim[1]),
				             (int)(id / (size_t)g.dim[0] / (size_t)g.dim[1])};
				cands_gather(s, &g, xs, c0, small, &c);
				for (size_t q = g.start[id]; q < g.start[id + 1]; q++) {
					size_t i = (size_t)g.item[q];
					if (!is_mobile(s, i))
						continue;
					at[i] = buf[ch].n;
					chunk_of[i] = (int32_t)ch;
					s->nb_start[i + 1] =
					    scan_neighbours(s, &c, i, small, &buf[ch]);
				}
			}
		}
		cands_free(&c);
	}
	s->nb_start[0] = 0;
	for (size_t i = 0; i < n; i++)
		s->nb_start[i + 1] = s->nb_start[i] + (is_mobile(s, i) ? s->nb_start[i + 1] : 0);
	if (s->nb_start[n] > s->nb_cap) {
		s->nb_cap = s->nb_start[n] + s->nb_start[n] / 4;
		free(s->nb);
		free(s->nb_shift);
		s->nb = xmalloc(s->nb_cap * sizeof *s->nb);
		s->nb_shift = xmalloc(s->nb_cap);
	}
	size_t nm = s->nmobile;
#pragma omp parallel for schedule(dynamic, 256) if (n >= PAR_MIN)
	for (size_t i = 0; i < nm; i++) {
		const nbuf *b = &buf[chunk_of[i]];
		size_t m = s->nb_start[i + 1] - s->nb_start[i];
		memcpy(s->nb + s->nb_start[i], b->j + at[i], m * sizeof *b->j);
		memcpy(s->nb_shift + s->nb_start[i], b->shift + at[i], m);
		if (s->wall)
			wall_update(s, i);
	}
	for (size_t ch = 0; ch < nchunk; ch++) {
		free(buf[ch].j);
		free(buf[ch].shift);
	}
	free(buf);
	free(at);
	free(chunk_of);
	free(xs);
	pack_cells_free(&g);
	memcpy(s->x_built, s->x, 3 * n * sizeof *s->x);
	memcpy(s->r_built, s->r, n * sizeof *s->r);
	for (size_t i = 0; i < n; i++) {
		v3_copy(s->xr + 4 * i, s->x + 3 * i);
		s->xr[4 * i + 3] = s->r[i];
	}
	s->stale = 0;
	s->builds++;
}

/* Positions and radii are also laid out side by side for soft_forces().
 * The list stays valid while no pair has closed its gap by the skin: a
 * pair's centres approach by at most the sum of their displacements, so
 * the two largest displacements bound every pair (twice the largest, as
 * often used, rebuilds early when one sphere outruns the rest). Both are
 * exact maxima, whatever the order they are taken in. */
void soft_update(soft_system *s, int force)
{
	if (force || s->stale) {
		soft_rebuild(s);
		return;
	}
	enum { BLOCK = 4096 };
	size_t n = s->nmobile, nblock = (n + BLOCK - 1) / BLOCK;
	double part[3 * 64], *p = nblock <= 64 ? part : xmalloc(3 * nblock * sizeof *p);
#pragma omp parallel for schedule(static) if (n >= PAR_MIN)
	for (size_t b = 0; b < nblock; b++) {
		double m1 = 0, m2 = 0, grow = 0;
		size_t end = (b + 1) * BLOCK < n ? (b + 1) * BLOCK : n;
		for (size_t i = b * BLOCK; i < end; i++) {
			double d[3];
			v3_copy(s->xr + 4 * i, s->x + 3 * i);
			s->xr[4 * i + 3] = s->r[i];
			v3_sub(d, s->x + 3 * i, s->x_built + 3 * i);
			double m = v3_dot(d, d);
			m2 = m > m2 ? (m > m1 ? m1 : m) : m2;
			m1 = m > m1 ? m : m1;
			grow = fmax(grow, s->r[i] - s->r_built[i]);
		}
		p[3 * b] = m1;
		p[3 * b + 1] = m2;
		p[3 * b + 2] = grow;
	}
	double m1 = 0, m2 = 0, grow = 0;
	for (size_t b = 0; b < nblock; b++) {
		for (int k = 0; k < 2; k++) {
			double m = p[3 * b + k];
			m2 = m > m2 ? (m > m1 ? m1 : m) : m2;
			m1 = m > m1 ? m : m1;
		}
		grow = fmax(grow, p[3 * b + 2]);
	}
	if (p != part)
		free(p);
	if (sqrt(m1) + sqrt(m2) + 2 * grow > s->skin)
		soft_rebuild(s);
}

/* soft_forces() over a half list: each pair once, its force added to
 * both spheres, in list order on one thread (so, again, the same result
 * every time). The statistics count each touching pair from both sides,
 * as the full list does. */
static void forces_half(soft_system *s, double *f, soft_stats *out)
{
	size_t n = s->n;
	double worst = 0, fmx = 0, sum = 0, count = 0;
	memset(f, 0, 3 * n * sizeof *f);
	for (size_t i = 0; i < n; i++) {
		const double *xi = s->x + 3 * i;
		double ri = s->r[i], fi[3] = {0, 0, 0};
		for (size_t q = s->nb_start[i]; q < s->nb_start[i + 1]; q++) {
			size_t j = (size_t)s->nb[q];
			const double *xj = s->x + 3 * j, *sh = s->shift[s->nb_shift[q]];
			double d[3] = {xj[0] - xi[0] + sh[0], xj[1] - xi[1] + sh[1],
			               xj[2] - xi[2] + sh[2]};
			double dist = sqrt(v3_dot(d, d)), rj = s->r[j], delta = ri + rj - dist,
			       touch = delta > 0;
			double rmin = ri < rj ? ri : rj, inv = touch / (dist * rmin),
			       c = delta * rmin * inv;
			v3_axpy(fi, d, -c);
			v3_axpy(f + 3 * j, d, c);
			double rel = delta * dist * inv;
			worst = rel > worst ? rel : worst;
			sum += 2 * rel;
			count += 2 * touch;
		}
		v3_add(f + 3 * i, f + 3 * i, fi);
	}
	for (size_t i = 0; i < n; i++) {
		double fr = sqrt(v3_dot(f + 3 * i, f + 3 * i)) / s->r[i];
		fmx = fr > fmx ? fr : fmx;
	}
	out->overlap_max = worst;
	out->overlap_mean = count > 0 ? sum / count : 0;
	out->contacts = count;
	out->fmax = fmx;
}

#define FORCE_BLOCK 1024

void soft_forces(soft_system *s, double *f, soft_stats *out)
{
	if (s->half) {
		forces_half(s, f, out);
		return;
	}
	size_t n = s->nmobile, nblock = (n + FORCE_BLOCK - 1) / FORCE_BLOCK;
	double *part = xcalloc(2 * nblock + 1, sizeof *part), *xr = s->xr;
	double worst = 0, fmx = 0;
	/* Positions and radii side by side in xr, one cache line per
	 * neighbour, as soft_update() laid them out. */
#pragma omp parallel for reduction(max : worst, fmx) schedule(static) if (n >= PAR_MIN)
	for (size_t b = 0; b < nblock; b++) {
		double sum = 0, count = 0;
		size_t end = (b + 1) * FORCE_BLOCK < n ? (b + 1) * FORCE_BLOCK : n;
		for (size_t i = b * FORCE_BLOCK; i < end; i++) {
			double fi[3] = {0, 0, 0}, wi = 0;
			{
				const double *pi = xr + 4 * i;
				double ri = pi[3];
				/* Without branches (about half the listed pairs touch,
				 * at random): a pair apart adds zeros, exactly. The
				 * image shift of code 13 is zero. */
				for (size_t q = s->nb_start[i]; q < s->nb_start[i + 1]; q++) {
					const double *pj = xr + 4 * (size_t)s->nb[q],
					             *sh = s->shift[s->nb_shift[q]];
					double d[3] = {pj[0] - pi[0] + sh[0], pj[1] - pi[1] + sh[1],
					               pj[2] - pi[2] + sh[2]};
					double dist = sqrt(v3_dot(d, d)), rs = ri + pj[3];
					double delta = rs - dist, touch = delta > 0;
					/* One division for both delta/dist and delta/min(r). */
					double rmin = ri < pj[3] ? ri : pj[3],
					       inv = touch / (dist * rmin);
					v3_axpy(fi, d, -delta * rmin * inv);
					double rel = delta * dist * inv;
					wi = rel > wi ? rel : wi;
					sum += rel;
					count += touch;
				}
				double q[3] = {0, 0, 0}, dmin;
				if (s->wall_count[i] && (dmin = wall_contact(s, i, q)) < ri &&
				    dmin > 0) {
					/* Push the centre away from its closest boundary point. */
					double delta = ri - dmin, d[3];
					v3_sub(d, s->x + 3 * i, q);
					v3_axpy(fi, d, delta / dmin);
					wi = delta / ri > wi ? delta / ri : wi;
					sum += delta / ri;
					count += 1;
				}
				worst = wi > worst ? wi : worst;
				double fr = sqrt(v3_dot(fi, fi)) / ri;
				fmx = fr > fmx ? fr : fmx;
			}
			v3_copy(f + 3 * i, fi);
			if (s->worst)
				s->worst[i] = wi;
		}
		part[2 * b] = sum;
		part[2 * b + 1] = count;
	}
	double sum = 0, count = 0;
	for (size_t b = 0; b < nblock; b++) {
		sum += part[2 * b];
		count += part[2 * b + 1];
	}
	free(part);
	out->overlap_max = worst;
	out->overlap_mean = count > 0 ? sum / count : 0;
	out->contacts = count;
	out->fmax = fmx;
}
