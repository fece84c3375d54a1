/* An undamped elastic specimen vibrating freely conserves its total energy
 * (kinetic + elastic, as the history table reports them) to 1e-6 relative
 * over 10^5 steps. A jittered FCC block of unequal spheres with bonds
 * only, random initial velocities and spins, so normal, shear and rotational
 * motion all take part; strengths high enough that nothing breaks. The
 * amplitude is small (strains ~1e-8): central differences conserve the
 * shadow energy exactly only for a linear system, and the geometric
 * nonlinearity leaves an error proportional to the amplitude. */
#include <math.h>
#include <stdio.h>

#include "lib/rng.h"
#include "solve/history.h"
#include "tests/check.h"
#include "tests/solve/fixture.h"
#include "tests/solve/harness.h"

int main(void)
{
	lattice l = {.kind = LATTICE_FCC,
	             .nx = 2,
	             .ny = 2,
	             .nz = 3,
	             .r = 1e-3,
	             .jitter = 0.03,
	             .polydisp = 0.05,
	             .seed = 7};
	dem_assembly a;
	fixture_lattice(&a, &l);
	dem_case c;
	harness_case(&c, "{\"assembly\": \"-\", \"material\": {\"name\": \"elastic\", \"law\": "
	                 "\"linear\", \"density\": 2500, \"E\": 1e10, \"nu\": 0.2, "
	                 "\"tensile_strength\": 1e12, \"shear_strength\": 1e12},"
	                 "\"damping\": {\"translational\": 0, \"rotational\": 0},"
	                 "\"output\": {\"history_every\": 1000},"
	                 "\"loading\": [{\"axial\": {\"mode\": \"none\"}}],"
	                 "\"stop\": {\"steps\": 100000}}");
	engine e;
	harness_engine(&e, &c, &a);
	rng g;
	rng_seed(&g, 3);
	for (size_t k = 0; k < 3 * e.p.n; k++) {
		e.p.v[k] = 1e-4 * rng_range(&g, -1, 1);
		e.p.w[k] = 0.1 * rng_range(&g, -1, 1);
	}
	double e0 = 0, worst = 0, row[64];
	for (long s = 0; s <= 100000; s++) {
		int measure = s % 1000 == 0;
		engine_step(&e, measure);
		if (!measure)
			continue;
		history_row(&e, 0, row);
		double total = e.energy.kinetic + engine_elastic(&e);
		if (s == 0)
			e0 = total;
		worst = fmax(worst, fabs(total - e0) / e0);
		if (s == 50000)
			fprintf(stderr, "step %ld: kinetic %.6g J, elastic %.6g J\n", s,
			        e.energy.kinetic, engine_elastic(&e));
	}
	fprintf(stderr,
	        "%zu particles, %zu bonds, dt %.3g s: largest relative change of the total "
	        "energy %.3g\n",
	        e.p.n, e.pairs.bonds.n, e.clock.dt, worst);
	CHECK(e.pairs.bonds.n > 3 * e.p.n);
	CHECK(e0 > 0);
	CHECK(worst < 1e-6);
	/* The energy really moved between kinetic and elastic. */
	CHECK(engine_elastic(&e) > 0.1 * e0);
	engine_free(&e);
	case_free(&c);
	assembly_free(&a);
	return check_done();
}
