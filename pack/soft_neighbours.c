/* The Verlet neighbour list of the soft-sphere system (see soft.h): pairs
 * with d_ij < r_i + r_j + skin, found through a cell grid of edge >= 2 r_max
 * + skin. It stays valid while every sphere has moved less than (skin - 2
 * max growth of a radius) / 2 since the build. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lib/err.h"
#include "lib/vec3.h"
#include "pack/cells.h"
#include "pack/par.h"
#include "pack/soft.h"
#include "pack/soft_walls.h"

static int is_mobile(const soft_system *s, size_t i) { return i < s->nmobile; }

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
		if (soft_periodic(s) && !small) {
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
		int span = g->dim[k] >= 3 || !soft_periodic(s) ? 1 : 0;
		lo[k] = c0[k] - span;
		hi[k] = c0[k] + span;
		if (!soft_periodic(s)) {
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

/* The displacement of each periodic image code, 13 + sum_k 3^k s_k. */
static void image_shifts(soft_system *s)
{
	static const int stride[3] = {1, 3, 9};
	for (int code = 0; code < 27; code++)
		for (int k = 0; k < 3; k++)
			s->shift[code][k] = s->box[k] * (double)(code / stride[k] % 3 - 1);
}

/* One build of the list: the neighbours by chunks of grid cells, each
 * chunk into its own buffer, then laid out in sphere order, so that the
 * list is the same whatever the thread count. */
typedef struct {
	pack_cells g;
	double *xs; /* [n][4] positions and radii, in cell order */
	int small;  /* a periodic box too short for three cells a side */
	size_t ncell, nchunk;
	nbuf *buf;         /* [nchunk] */
	size_t *at;        /* [n] where sphere i's neighbours start in its chunk's buffer */
	int32_t *chunk_of; /* [n] */
} list_build;

enum { CHUNK = 64 }; /* grid cells per chunk */

/* The grid over the spheres (reach 2 r_max + skin) and their positions and
 * radii in its order, with the chunks' buffers. */
static void build_start(list_build *L, const soft_system *s)
{
	size_t n = s->n;
	double rmax = 0;
	for (size_t i = 0; i < n; i++)
		rmax = fmax(rmax, s->r[i]);
	pack_cells *g = &L->g;
	pack_cells_build(g, s->x, n, 2 * rmax + s->skin, soft_periodic(s) ? s->box : NULL);
	L->xs = xmalloc(4 * n * sizeof *L->xs + 1);
	for (size_t q = 0; q < n; q++) {
		size_t i = (size_t)g->item[q];
		v3_copy(L->xs + 4 * q, s->x + 3 * i);
		L->xs[4 * q + 3] = s->r[i];
	}
	L->small = soft_periodic(s) && (g->dim[0] < 3 || g->dim[1] < 3 || g->dim[2] < 3);
	L->ncell = (size_t)g->dim[0] * (size_t)g->dim[1] * (size_t)g->dim[2];
	L->nchunk = (L->ncell + CHUNK - 1) / CHUNK;
	L->buf = xcalloc(L->nchunk + 1, sizeof *L->buf);
	L->at = xmalloc(n * sizeof *L->at + 1);
	L->chunk_of = xmalloc(n * sizeof *L->chunk_of + 1);
}

/* The neighbours of the mobile spheres of grid cell id, into the buffer of
 * chunk ch; each sphere's count goes to nb_start[i + 1]. */
static void list_cell(soft_system *s, list_build *L, size_t id, size_t ch, cands *c)
{
	const pack_cells *g = &L->g;
	int mobile = 0;
	for (size_t q = g->start[id]; q < g->start[id + 1]; q++)
		mobile |= is_mobile(s, (size_t)g->item[q]);
	if (!mobile)
		return;
	int c0[3] = {(int)(id % (size_t)g->dim[0]),
	             (int)(id / (size_t)g->dim[0] % (size_t)g->dim[1]),
	             (int)(id / (size_t)g->dim[0] / (size_t)g->dim[1])};
	cands_gather(s, g, L->xs, c0, L->small, c);
	for (size_t q = g->start[id]; q < g->start[id + 1]; q++) {
		size_t i = (size_t)g->item[q];
		if (!is_mobile(s, i))
			continue;
		L->at[i] = L->buf[ch].n;
		L->chunk_of[i] = (int32_t)ch;
		s->nb_start[i + 1] = scan_neighbours(s, c, i, L->small, &L->buf[ch]);
	}
}

static void list_chunks(soft_system *s, list_build *L)
{
	size_t nchunk = L->nchunk, ncell = L->ncell;
#pragma omp parallel if (s->n >= PAR_MIN)
	{
		cands c = {0};
#pragma omp for schedule(dynamic, 1)
		for (size_t ch = 0; ch < nchunk; ch++) {
			size_t end = (ch + 1) * CHUNK < ncell ? (ch + 1) * CHUNK : ncell;
			for (size_t id = ch * CHUNK; id < end; id++)
				list_cell(s, L, id, ch, &c);
		}
		cands_free(&c);
	}
}

/* The counts summed into nb_start, then each mobile sphere's neighbours
 * copied from its chunk's buffer (and its boundary triangles listed, on
 * the same pass). */
static void lay_out(soft_system *s, const list_build *L)
{
	size_t n = s->n, nm = s->nmobile;
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
#pragma omp parallel for schedule(dynamic, 256) if (n >= PAR_MIN)
	for (size_t i = 0; i < nm; i++) {
		const nbuf *b = &L->buf[L->chunk_of[i]];
		size_t m = s->nb_start[i + 1] - s->nb_start[i];
		memcpy(s->nb + s->nb_start[i], b->j + L->at[i], m * sizeof *b->j);
		memcpy(s->nb_shift + s->nb_start[i], b->shift + L->at[i], m);
		if (s->wall)
			soft_walls_update(s, i);
	}
}

static void build_free(list_build *L)
{
	for (size_t ch = 0; ch < L->nchunk; ch++) {
		free(L->buf[ch].j);
		free(L->buf[ch].shift);
	}
	free(L->buf);
	free(L->at);
	free(L->chunk_of);
	free(L->xs);
	pack_cells_free(&L->g);
}

/* What the list was built from, to tell when it goes stale, and the
 * positions and radii side by side for soft_forces(). */
static void remember_build(soft_system *s)
{
	size_t n = s->n;
	memcpy(s->x_built, s->x, 3 * n * sizeof *s->x);
	memcpy(s->r_built, s->r, n * sizeof *s->r);
	for (size_t i = 0; i < n; i++) {
		v3_copy(s->xr + 4 * i, s->x + 3 * i);
		s->xr[4 * i + 3] = s->r[i];
	}
	s->stale = 0;
	s->builds++;
}

void soft_rebuild(soft_system *s)
{
	if (s->wall)
		soft_walls_prepare(s);
	image_shifts(s);
	if (soft_periodic(s))
		for (size_t i = 0; i < 3 * s->n; i++)
			s->x[i] -= s->box[i % 3] * floor(s->x[i] / s->box[i % 3]);
	list_build L;
	build_start(&L, s);
	list_chunks(s, &L);
	lay_out(s, &L);
	build_free(&L);
	remember_build(s);
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
