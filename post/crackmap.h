/* Where and how the cracks lie, for maps (post/frame.h for the frame):
 *   height  h - h_bottom (m), h_bottom the lowest particle face at start
 *   rho     distance to the axis (m); phi the angle around it (deg)
 *   theta   orientation of the crack normal (the bond direction) to the
 *           plane normal to the load (deg): 90 a horizontal crack plane,
 *           0 a vertical one (axial splitting)
 * A crack is on the lateral surface when rho >= R - depth, R the
 * specimen radius (geometry diameter / 2, else the largest rho + r of the
 * particles). A crack is in the axial section of angle psi when its
 * distance to the plane through the axis and e(psi) = cos psi e1 +
 * sin psi e2 is at most thickness / 2; there its coordinates are
 * u = d . e(psi) and the height, and its trace is the segment of length
 * 2 r_c normal to the in-plane part (n . e(psi), n . a) of its normal. */
#ifndef DEM_POST_CRACKMAP_H
#define DEM_POST_CRACKMAP_H

#include <stdio.h>

#include "lib/runfile.h"
#include "post/frame.h"

typedef struct {
	frame f;
	double bottom;      /* m, h of the lowest particle face at start */
	double height;      /* m, specimen height (particle extent along the axis) */
	double radius;      /* m, specimen radius R */
	double mean_radius; /* m, mean particle radius */
} specimen;

typedef struct {
	double height, rho, phi, theta; /* m, m, deg, deg */
} crack_place;

void specimen_of(specimen *sp, const dem_assembly *a);
void crack_place_of(const specimen *sp, const dem_crack *c, crack_place *p);

/* Datablock $count: axial strain (%) and the cumulative numbers of cracks
 * in tension, in shear and in all: a row at zero, one per crack in the
 * log's order, and one at the last history row's strain; then the
 * variable cracks, their number. */
void crackmap_count_data(FILE *f, const dem_run *r);

#endif
