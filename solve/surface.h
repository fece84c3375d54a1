/* The lateral surface of the specimen and the radial strain gauge (surface.c). */
#ifndef DEM_SURFACE_H
#define DEM_SURFACE_H

#include <stddef.h>
#include <stdint.h>

typedef struct engine engine;

typedef struct {
	int ntheta, nz;
	double bin; /* m */
	size_t n, cap;
	int32_t *idx;        /* surface particles (index in the whole specimen),
	                        in increasing order */
	double *area;        /* m^2, tributary area of each */
	int32_t *best;       /* [ntheta * nz] outermost particle of each bin */
	double *best_rho;    /* its outer radial distance */
	double lateral_area; /* m^2, current lateral area from the bins */
	double radius;       /* m, mean outer radius */
	double volume;       /* m^3, enclosed by the bins */
	long updated;        /* step of the last update */
} surface;

/* The gauge's particles: this rank's own (ranks.h). */
typedef struct {
	size_t n;
	int32_t *idx;
	double *rho0;   /* m, initial radial distance */
	double total;   /* particles of the whole gauge */
	double radius0; /* m, initial outer radius */
} gauge;

/* The most bins the lateral surface may take (surface_init). */
enum { SURFACE_MAX_BINS = 10000000 };
/* The surface's bins and its first list. 0, or -1 with err_set() when the
 * particles would need more than SURFACE_MAX_BINS bins (a damaged
 * assembly). */
int surface_init(engine *e);
void surface_update(engine *e);
/* Room for cap surface particles. */
void surface_room(surface *S, size_t cap);
void surface_free(surface *s);
void gauge_init(engine *e);
double gauge_strain(const engine *e);
void gauge_free(gauge *g);

#endif
