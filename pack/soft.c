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
	free(s->wall_hint);
	free(s->wall_margin);
	free(s->wall_count);
	free(s->wall_pool);
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

static void nbuf_push(nbuf *b, int32_t j, uint8_t shift)
{
	if (b->n == b->cap) {
		b->cap = b->cap ? 2 * b->cap : 4096;
		b->j = xrealloc(b->j, b->cap * sizeof *b->j);
		b->shift = xrealloc(b->shift, b->cap);
	}
	b->j[b->n] = j;
	b->shift[b->n++] = shift;
}

/* Append the neighbours of sphere i within r_i + r_j + skin, with the
 * periodic image each was seen through, to b; xs holds (x, y, z, r) of
 * the spheres in cell order. Returns their number. */
static size_t scan_neighbours(const soft_system *s, const cells *g, const double *xs, size_t i,
                              double rmax, nbuf *b)
{
	int c0[3], lo[3], hi[3];
	cells_coord(g, s->x + 3 * i, c0);
	for (int k = 0; k < 3; k++) {
		int span = g->dim[k] >= 3 || !periodic(s) ? 1 : 0;
		lo[k] = c0[k] - span;
		hi[k] = c0[k] + span;
		if (!periodic(s)) {
			lo[k] = lo[k] < 0 ? 0 : lo[k];
			hi[k] = hi[k] >= g->dim[k] ? g->dim[k] - 1 : hi[k];
		}
	}
	int small = periodic(s) && (g->dim[0] < 3 || g->dim[1] < 3 || g->dim[2] < 3);
	const double *xi = s->x + 3 * i, reach = s->r[i] + s->skin;
	/* A cell farther from x_i than r_i + skin + r_max holds no neighbour:
	 * for the small spheres of a wide distribution most corner cells. */
	double far2 = (reach + rmax) * (reach + rmax), gap[3][3];
	for (int k = 0; k < 3; k++)
		for (int o = 0; o < 3; o++) {
			double a = g->lo[k] + (c0[k] + o - 1) * g->edge[k], e = a + g->edge[k];
			double t = xi[k] < a ? a - xi[k] : xi[k] > e ? xi[k] - e : 0;
			gap[k][o] = t * t;
		}
	size_t count = 0;
	for (int cz = lo[2]; cz <= hi[2]; cz++) {
		int wz = cz < 0 ? cz + g->dim[2] : cz >= g->dim[2] ? cz - g->dim[2] : cz;
		for (int cy = lo[1]; cy <= hi[1]; cy++) {
			int wy = cy < 0 ? cy + g->dim[1] : cy >= g->dim[1] ? cy - g->dim[1] : cy;
			for (int cx = lo[0]; cx <= hi[0]; cx++) {
				int wx = cx < 0            ? cx + g->dim[0]
				         : cx >= g->dim[0] ? cx - g->dim[0]
				                           : cx;
				int code = 13;
				double sh[3] = {0, 0, 0};
				if (periodic(s) && !small) {
					int o[3] = {cx - wx, cy - wy, cz - wz};
					for (int k = 0; k < 3; k++) {
						int sk = o[k] < 0 ? -1 : o[k] > 0 ? 1 : 0;
						code += (k == 0 ? 1 : k == 1 ? 3 : 9) * sk;
						sh[k] = sk * s->box[k];
					}
				}
				if (!small && gap[0][cx - c0[0] + 1] + gap[1][cy - c0[1] + 1] +
				                      gap[2][cz - c0[2] + 1] >=
				                  far2)
					continue;
				size_t id = ((size_t)wz * (size_t)g->dim[1] + (size_t)wy) *
				                (size_t)g->dim[0] +
				            (size_t)wx;
				for (size_t q = g->start[id]; q < g->start[id + 1]; q++) {
					const double *xj = xs + 4 * q;
					double d[3] = {xj[0] + sh[0] - xi[0], xj[1] + sh[1] - xi[1],
					               xj[2] + sh[2] - xi[2]};
					double cut = reach + xj[3];
					if (d[0] * d[0] + d[1] * d[1] + d[2] * d[2] >= cut * cut)
						continue;
					size_t j = (size_t)g->item[q];
					if (j == i)
						continue;
					int sc = code;
					if (small) {
						soft_delta(s, i, j, d);
						sc = image_code(s, i, j, d);
						if (v3_dot(d, d) >= cut * cut)
							continue;
					}
					nbuf_push(b, (int32_t)j, (uint8_t)sc);
					count++;
				}
			}
		}
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

/* The boundary triangles sphere i may touch before the next build. A query
 * at x_q lists the triangles within r + skin + WALL_MARGIN (the WALL_MAX
 * closest, the margin shrinking to what they cover if there are more);
 * the list serves every build while the sphere stays within the margin of
 * x_q. Without a list, the depth bound s_q - |x - x_q| tells whether the
 * sphere can reach the boundary at all. */
static void wall_update(soft_system *s, size_t i)
{
	double d[3];
	v3_sub(d, s->x + 3 * i, s->wall_xq + 3 * i);
	double moved = v3_norm(d), reach = s->r[i] + s->skin;
	if (s->wall_count[i] && moved <= s->wall_margin[i])
		return;
	s->wall_count[i] = 0;
	if (s->wall_s0[i] - moved > reach)
		return;
	v3_copy(s->wall_xq + 3 * i, s->x + 3 * i);
	s->wall_s0[i] = surface_distance(s->wall, s->x + 3 * i, NULL, &s->wall_hint[i]);
	if (s->wall_s0[i] > reach + WALL_MARGIN * s->skin)
		return;
	enum { CAP = 4 * WALL_MAX };
	int32_t buf[CAP];
	double dist[CAP], q[3], margin = WALL_MARGIN * s->skin;
	size_t m = surface_near(s->wall, s->x + 3 * i, reach + margin, buf, CAP);
	m = m < CAP ? m : CAP;
	for (size_t k = 0; k < m; k++)
		dist[k] = triangle_distance(s, buf[k], s->x + 3 * i, q);
	while (m > WALL_MAX) { /* drop the farthest; the list covers less */
		size_t far = 0;
		for (size_t k = 1; k < m; k++)
			far = dist[k] > dist[far] ? k : far;
		margin = fmin(margin, dist[far] - reach);
		buf[far] = buf[m - 1];
		dist[far] = dist[m - 1];
		m--;
	}
	memcpy(s->wall_pool + i * WALL_MAX, buf, m * sizeof *buf);
	s->wall_count[i] = (uint8_t)m;
	s->wall_margin[i] = margin;
}

void soft_rebuild(soft_system *s)
{
	if (s->wall && !s->wall_pool)
		s->wall_pool = xmalloc(s->nmobile * WALL_MAX * sizeof *s->wall_pool + 1);
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
	cells g;
	cells_build(&g, s->x, s->n, 2 * rmax + s->skin, periodic(s) ? s->box : NULL);
	size_t n = s->n;
	double *xs = xmalloc(4 * n * sizeof *xs + 1);
	for (size_t q = 0; q < n; q++) {
		size_t i = (size_t)g.item[q];
		v3_copy(xs + 4 * q, s->x + 3 * i);
		xs[4 * q + 3] = s->r[i];
	}
	/* Neighbours by chunks of spheres into their own buffers, then laid
	 * out in sphere order: the same list whatever the thread count. */
	enum { CHUNK = 512 };
	size_t nchunk = (n + CHUNK - 1) / CHUNK;
	nbuf *buf = xcalloc(nchunk + 1, sizeof *buf);
#pragma omp parallel for schedule(dynamic, 1) if (n >= PAR_MIN)
	for (size_t c = 0; c < nchunk; c++) {
		size_t end = (c + 1) * CHUNK < n ? (c + 1) * CHUNK : n;
		for (size_t i = c * CHUNK; i < end; i++) {
			s->nb_start[i + 1] =
			    is_mobile(s, i) ? scan_neighbours(s, &g, xs, i, rmax, &buf[c]) : 0;
			if (s->wall && is_mobile(s, i))
				wall_update(s, i);
		}
	}
	s->nb_start[0] = 0;
	for (size_t i = 0; i < n; i++)
		s->nb_start[i + 1] += s->nb_start[i];
	if (s->nb_start[n] > s->nb_cap) {
		s->nb_cap = s->nb_start[n] + s->nb_start[n] / 4;
		free(s->nb);
		free(s->nb_shift);
		s->nb = xmalloc(s->nb_cap * sizeof *s->nb);
		s->nb_shift = xmalloc(s->nb_cap);
	}
#pragma omp parallel for schedule(static) if (n >= PAR_MIN)
	for (size_t c = 0; c < nchunk; c++) {
		size_t at = s->nb_start[c * CHUNK];
		if (buf[c].n) {
			memcpy(s->nb + at, buf[c].j, buf[c].n * sizeof *buf[c].j);
			memcpy(s->nb_shift + at, buf[c].shift, buf[c].n);
		}
		free(buf[c].j);
		free(buf[c].shift);
	}
	free(buf);
	free(xs);
	cells_free(&g);
	memcpy(s->x_built, s->x, 3 * n * sizeof *s->x);
	memcpy(s->r_built, s->r, n * sizeof *s->r);
	for (size_t i = 0; i < n; i++) {
		v3_copy(s->xr + 4 * i, s->x + 3 * i);
		s->xr[4 * i + 3] = s->r[i];
	}
	s->stale = 0;
	s->builds++;
}

void soft_update(soft_system *s, int force)
{
	if (force || s->stale) {
		soft_rebuild(s);
		return;
	}
	double move = 0, grow = 0;
	size_t n = s->nmobile;
#pragma omp parallel for reduction(max : move, grow) schedule(static) if (n >= PAR_MIN)
	for (size_t i = 0; i < n; i++) {
		double d[3];
		v3_sub(d, s->x + 3 * i, s->x_built + 3 * i);
		move = fmax(move, v3_dot(d, d));
		grow = fmax(grow, s->r[i] - s->r_built[i]);
	}
	if (2 * sqrt(move) + 2 * grow > s->skin)
		soft_rebuild(s);
}

#define FORCE_BLOCK 1024

void soft_forces(soft_system *s, double *f, soft_stats *out)
{
	size_t n = s->nmobile, nblock = (n + FORCE_BLOCK - 1) / FORCE_BLOCK;
	double *part = xcalloc(2 * nblock + 1, sizeof *part), *xr = s->xr;
	double worst = 0, fmx = 0;
	/* Position and radius side by side: one cache line per neighbour (the
	 * fixed spheres' were laid out at the last build). */
#pragma omp parallel for schedule(static) if (n >= PAR_MIN)
	for (size_t i = 0; i < n; i++) {
		v3_copy(xr + 4 * i, s->x + 3 * i);
		xr[4 * i + 3] = s->r[i];
	}
#pragma omp parallel for reduction(max : worst, fmx) schedule(static) if (n >= PAR_MIN)
	for (size_t b = 0; b < nblock; b++) {
		double sum = 0, count = 0;
		size_t end = (b + 1) * FORCE_BLOCK < n ? (b + 1) * FORCE_BLOCK : n;
		for (size_t i = b * FORCE_BLOCK; i < end; i++) {
			double fi[3] = {0, 0, 0}, wi = 0;
			{
				const double *pi = xr + 4 * i;
				double ri = pi[3];
				for (size_t q = s->nb_start[i]; q < s->nb_start[i + 1]; q++) {
					const double *pj = xr + 4 * (size_t)s->nb[q];
					double d[3];
					v3_sub(d, pj, pi);
					if (s->nb_shift[q] != 13)
						v3_add(d, d, s->shift[s->nb_shift[q]]);
					double dd = v3_dot(d, d), rs = ri + pj[3];
					if (dd >= rs * rs)
						continue;
					/* One division for both delta/dist and delta/min(r). */
					double dist = sqrt(dd), delta = rs - dist;
					double rmin = ri < pj[3] ? ri : pj[3],
					       inv = 1 / (dist * rmin);
					v3_axpy(fi, d, -delta * rmin * inv);
					double rel = delta * dist * inv;
					wi = rel > wi ? rel : wi;
					sum += rel;
					count += 1;
				}
				if (s->wall_count[i]) {
					/* Push the centre away from its closest boundary point. */
					const int32_t *tl = s->wall_pool + i * WALL_MAX;
					double q[3] = {0, 0, 0}, qk[3], dmin = INFINITY;
					for (int k = 0; k < s->wall_count[i]; k++) {
						double dk =
						    triangle_distance(s, tl[k], s->x + 3 * i, qk);
						if (dk < dmin) {
							dmin = dk;
							v3_copy(q, qk);
						}
					}
					double delta = ri - dmin;
					if (delta > 0 && dmin > 0) {
						double d[3];
						v3_sub(d, s->x + 3 * i, q);
						v3_axpy(fi, d, delta / dmin);
						wi = delta / ri > wi ? delta / ri : wi;
						sum += delta / ri;
						count += 1;
					}
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
