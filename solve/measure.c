/* Measurements of the specimen's state (measure.h). */
#include "solve/measure.h"
#include "solve/engine.h"

double engine_strain(const engine *e)
{
	double gap = e->bc.pl.z[1] - e->bc.pl.z[0];
	return (e->frame.height0 - gap) / e->frame.height0;
}

double engine_stress_of(const engine *e, int k) { return e->bc.pl.load[k] / e->frame.area0; }

double engine_stress(const engine *e)
{
	return 0.5 * (engine_stress_of(e, 0) + engine_stress_of(e, 1));
}

double engine_elastic(const engine *e)
{
	return e->sums.bonds.e_elastic + e->sums.contacts.e_elastic +
	       e->sums.particles.platen_elastic;
}
