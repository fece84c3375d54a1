/* A uniform grid of cells over the particles (counting sort by cell), for
 * the neighbour searches of bond formation and of the Verlet list: every
 * pair closer than the cell size lies in the same or adjacent cells. */
#ifndef DEM_CELLS_H
#define DEM_CELLS_H

#include <stddef.h>
#include <stdint.h>

typedef struct {
	double lo[3]; /* m, grid origin */
	double h;     /* m, cell size */
	int dim[3];
	size_t ncell, cap_cell, cap_item;
	int32_t *start; /* [ncell + 1] */
	int32_t *item;  /* [n] particles, by cell */
	int32_t *cell;  /* [n] cell of each particle */
	int32_t *fill;  /* [ncell] scratch */
} cells;

/* The cell size the grid uses for n particles in the box [lo, hi]: h, or
 * larger where cells of h would outnumber 8 n + 27 (a sparse assembly). */
double cells_size(const double lo[3], const double hi[3], size_t n, double h);
/* Sort the n particles at x into cells of size at least h (buffers are
 * reused between calls). */
void cells_build(cells *g, const double *x, size_t n, double h);
void cells_free(cells *g);

/* The cells around cell c (itself included, at most 27); returns how many. */
int cells_around(const cells *g, int32_t c, int32_t out[27]);

/* The particles j > i whose centres lie within scale (r_i + r_j) + add of
 * particle i's (x, r: every particle's centre and radius), in increasing
 * order; returns their number, or -1 if there are more than cap. */
int cells_partners(const cells *g, const double *x, const double *r, size_t i, double scale,
                   double add, int32_t *js, int cap);

/* The pairs a bond is formed between: every i < j whose centres lie within
 * scale (r_i + r_j) (Eq. 16), in (i, j) order, in cells of size h (at
 * least 2 scale r_max), with their centre distance: p->n pairs in arrays
 * the caller frees (cells_pairs_free). -1 when a particle has more than
 * CELLS_CAP partners (overlapping spheres?), its index in *crowded, nothing
 * allocated. */
enum { CELLS_CAP = 4096 };
typedef struct {
	size_t n;
	int32_t *i, *j;
	double *d;
} cells_pairs;
void cells_pairs_free(cells_pairs *p);
int cells_pairs_within(const double *x, const double *r, size_t n, double scale, double h,
                       cells_pairs *p, size_t *crowded);

#endif
