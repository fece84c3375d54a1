/* Soft spheres for packing: harmonic repulsion between overlapping spheres
 * and against the specimen boundary, with a Verlet neighbour list. The
 * energy minimised by pack/fire.c is
 *
 *   U = 1/2 sum_{pairs} (r_i + r_j - d_ij)^2_+  +  1/2 sum_i (r_i - s_i)^2_+
 *
 * (d_ij the centre distance, s_i the signed distance of centre i to the
 * boundary), i.e. unit contact stiffness; F_i = -dU/dx_i. Forces are
 * gathered per sphere in a fixed order, so results are identical whatever
 * the number of threads. */
#ifndef PACK_SOFT_H
#define PACK_SOFT_H

#include <stddef.h>
#include <stdint.h>

#include "pack/surface.h"

#define WALL_MAX 48   /* boundary triangles kept per sphere */
#define WALL_MARGIN 5 /* skins a sphere may move before its triangles are listed again */

/* A boundary triangle listed near a sphere, with a lower bound of its
 * distance (m; single precision, rounded down: a triangle and its
 * distance share a cache line). */
typedef struct {
	float dist;
	int32_t tri;
} wall_entry;

typedef struct {
	size_t n;
	double *x;               /* [n][3] m */
	double *r;               /* [n] m */
	size_t nmobile;          /* spheres 0 .. nmobile-1 move, the others are fixed */
	double box[3];           /* periodic cell lengths (m); all 0: not periodic */
	const surface *wall;     /* boundary to stay inside, or NULL; then */
	const double *wall_vert; /* its triangulation (pack/trimesh.h) */
	const int32_t *wall_tri;
	double skin; /* Verlet skin (m) */
	int half;    /* list each pair once, from its lower index, and gather
	              * the forces on one thread (every sphere mobile, no
	              * boundary, no `worst`): half the pairs to visit */

	/* Neighbour list (CSR over mobile spheres), rebuilt on demand. */
	size_t *nb_start;    /* [n+1] */
	int32_t *nb;         /* neighbour indices */
	uint8_t *nb_shift;   /* periodic image of each: 13 + sum_k 3^k s_k, s_k in -1..1 */
	double shift[27][3]; /* the displacement of each periodic image */
	double *xr;          /* [n][4] scratch: positions and radii together */
	size_t nb_cap;
	double *x_built; /* positions when the list was built */
	double *r_built;
	/* Boundary triangles near each moving sphere (see soft_walls.c):
	 * wall_count[i] of them at wall_pool + i WALL_MAX, nearest first
	 * from the position at the last build, wall_xb[i], valid while the
	 * sphere is within wall_margin[i] of wall_xq[i]; wall_s0[i] is a
	 * lower bound of the signed distance at wall_xq[i]. A caller that
	 * knows one may store it (with wall_xq = the position) to spare a
	 * query. */
	double *wall_s0;
	double *wall_xq; /* [n][3] */
	double *wall_margin;
	int32_t *wall_hint;
	uint8_t *wall_count;
	wall_entry *wall_pool;
	double *wall_xb;     /* [n][3] position at the last build */
	double *wall_near;   /* [n] the first listed distance (INFINITY: none), */
	int32_t *wall_first; /* [n] its triangle, */
	float *wall_second;  /* [n] and the second distance (INFINITY: none) */
	int stale;
	long builds;
	double *worst; /* [n] if not NULL: each mobile sphere's largest relative
	                * overlap, filled by soft_forces */
} soft_system;

/* Allocate the per-sphere work arrays for n spheres, the first nmobile of
 * which move (x and r are the caller's). */
void soft_init(soft_system *s, size_t n, size_t nmobile, double *x, double *r);
void soft_free(soft_system *s);

/* Rebuild the neighbour list now (periodic positions are wrapped into the
 * cell), or only if a sphere moved or grew enough to make it stale. */
void soft_rebuild(soft_system *s);
void soft_update(soft_system *s, int force);

typedef struct {
	double overlap_max;  /* largest overlap relative to the smaller radius
	                      * (pairs) or to the radius (boundary) */
	double overlap_mean; /* mean of the same over touching pairs, seen from
	                      * each mobile sphere */
	double contacts;     /* their number */
	double fmax;         /* max_i |F_i| / r_i */
} soft_stats;

/* Forces on the mobile spheres (f, [nmobile][3]) at the positions and
 * radii of the last soft_update() or soft_rebuild(). */
void soft_forces(soft_system *s, double *f, soft_stats *st);

/* Whether the system is a periodic cell (box lengths set). */
static inline int soft_periodic(const soft_system *s) { return s->box[0] > 0; }

/* Minimum-image separation x_j - x_i. */
void soft_delta(const soft_system *s, size_t i, size_t j, double d[3]);

#endif
