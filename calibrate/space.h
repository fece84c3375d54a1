/* The search space. Without the scaling, each free parameter is a search
 * variable, on a linear or log scale. With it (calibrate/scaling.h), the
 * first free key of each class (the stresses, the stiffnesses) is its
 * class's anchor and no search variable: its value is a scale times its
 * template value, and every other key of the class follows the scale, the
 * free ones as their ratio to the anchor (a search variable, log scale),
 * the others (tied) at their template's ratio. A point is then the two
 * scales S, K and the search variables z; the scales that best meet the
 * targets come from the runs at any one point (scaling_project). */
#ifndef DEM_CALIBRATE_SPACE_H
#define DEM_CALIBRATE_SPACE_H

#include "calibrate/spec.h"

typedef enum { Z_LINEAR, Z_LOG, Z_RATIO } zkind;

typedef struct {
	const cal_spec *sp;
	int nz;
	int zkey[CAL_MAX_FREE]; /* the key of each search variable */
	zkind kind[CAL_MAX_FREE];
	double lo[CAL_MAX_FREE], hi[CAL_MAX_FREE]; /* bounds of z (a ratio's: at any anchor) */
	double step[CAL_MAX_FREE];                 /* initial step of the search */
	double xtol[CAL_MAX_FREE];                 /* a round ends on steps below this */
	int anchor[3];                             /* per scale_class: key index or -1 */
} space;

void space_init(space *s, const cal_spec *sp);
/* The value of every key (sp->nkey) at the scales S, K (the anchors'
 * values over their template values; 1 when a class has no anchor) and z.
 * A free key is held within its bounds [min, max]; after space_project
 * that changes nothing but a rounding. */
void space_values(const space *s, double S, double K, const double *z, double *v);
/* Project z onto the bounds at the scales S, K: a search variable that
 * would put its free key outside [min, max] (a ratio whose box, at any
 * anchor value, is wider than the bounds at this one) is moved to the
 * bound; the scaled copies of the projected point (space_scale_box) keep
 * the ratios as run. The number of variables moved. */
int space_project(const space *s, double S, double K, double *z);
/* The scales and search variables of the values v. */
void space_coords(const space *s, const double *v, double *S, double *K, double *z);
/* The changes of ln S and ln K from the point (S, K, z) that keep every
 * free key within its bounds: box = {lo, hi} for ln S, then for ln K
 * ({0, 0} for a class without an anchor). 0, or -1 when no scale does. */
int space_scale_box(const space *s, double S, double K, const double *z, double box[4]);

#endif
