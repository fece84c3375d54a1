/* Small assemblies for the engine's tests, built directly with
 * lib/assembly.h: simple cubic and face-centred cubic lattices of touching
 * spheres, optionally jittered and cut to a cylinder, and rigidly rotated
 * copies. */
#ifndef DEM_TEST_SOLVE_FIXTURE_H
#define DEM_TEST_SOLVE_FIXTURE_H

#include <stdint.h>

#include "lib/assembly.h"

enum { LATTICE_SC, LATTICE_FCC };

typedef struct {
	int kind;        /* LATTICE_* */
	int nx, ny, nz;  /* cells along each axis */
	double r;        /* m, sphere radius (neighbours touch) */
	double jitter;   /* random displacement, fraction of r (uniform in each axis) */
	double polydisp; /* random radius change, fraction of r */
	double diameter; /* m, keep spheres inside this cylinder (0: keep the box) */
	uint64_t seed;
} lattice;

/* n spheres for a test to place (caller frees with assembly_free):
 * positions and radii zero, every sphere of the first material, no
 * geometry. */
void fixture_spheres(dem_assembly *a, size_t n);
/* Fill a (caller frees with assembly_free). Geometry: a box or a cylinder
 * along z, centred at the origin, sized to the sphere extents. */
void fixture_lattice(dem_assembly *a, const lattice *l);
/* The jittered, slightly polydisperse FCC cylinder (23.5 mm across, twice
 * as high, about 2 500 spheres of radius 1 mm) of the whole-run tests. */
void fixture_cylinder(dem_assembly *a, uint64_t seed);
/* Rotate positions, centre and axis by the rotation matrix R (row-major),
 * and grow the bounding box to enclose the turned one. */
void fixture_rotate(dem_assembly *a, const double R[9]);
/* A rotation matrix from an axis and an angle (rad). */
void fixture_rotation(const double axis[3], double angle, double R[9]);
/* Write a to path; aborts the test on error. */
void fixture_write(const dem_assembly *a, const char *path);

#endif
