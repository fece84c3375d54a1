/* Measurements of the specimen's state (measure.h). */
#include "solve/measure.h"
#include "solve/engine.h"

double engine_strain(const engine *e)
{
	double gap = e->pl.z[1] - e->pl.z[0];
	return (e->height0 - gap) / e->height0;
}

double engine_stress_of(const engine *e, int k) { return e->pl.load[k] / e->area0; }

double engine_stress(const engine *e)
{
	return 0.5 * (engine_stress_of(e, 0) + engine_stress_of(e, 1));
}

double engine_elastic(const engine *e)
{
	return e->bsum.e_elastic + e->csum.e_elastic + e->psum.platen_elastic;
}
