/* What the loading program and the history measure: the axial strain and
 * stress from the platens (or end layers), the elastic energy, and the
 * scalars of a measuring step. */
#ifndef DEM_MEASURE_H
#define DEM_MEASURE_H

#include <stdint.h>

typedef struct engine engine;

/* The scalars of a measuring step, taken at the step's start time. */
typedef struct {
	double t;
	int64_t step;
	int stage;
	double strain, stress[2]; /* axial; bottom and top platen (Pa) */
	double strain_radial;
	double pressure;      /* Pa, applied or (under a constraint) developed */
	double lateral_force; /* N, applied or reaction */
	double lateral_area;  /* m^2 */
	double volume;        /* m^3, enclosed by the lateral surface */
} measurement;

/* Axial strain (platen gap change / initial gap) and stress (platen load /
 * initial cross-section), compression positive; k = 0 bottom, 1 top. */
double engine_strain(const engine *e);
double engine_stress(const engine *e);
double engine_stress_of(const engine *e, int k);
/* Elastic energy of the last measuring step (J): bonds, contacts, platens. */
double engine_elastic(const engine *e);

#endif
