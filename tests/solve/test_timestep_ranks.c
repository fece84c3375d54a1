/* The critical time step's bound (solve/timestep.c) on several ranks: a
 * bond's or a contact's share of it reaches both of its particles, though
 * their ranks may differ (solve/ranks.h). On the fixture cylinder, 16
 * rounds with its bonds and 16 with none (every near pair a contact), each
 * with the masses and the contacts' stiffnesses drawn anew (from the
 * particle or the pair and the round alone, the same on every rank): rank
 * 0 prints each round's bound and the particle that sets it ("bound"
 * lines). They must be the same on any number of ranks: timestep_ranks.sh
 * runs this on 1, 3 and 7 and compares. Usage: test_timestep_ranks */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lib/err.h"
#include "lib/rng.h"
#include "solve/bonds.h"
#include "solve/contacts.h"
#include "solve/par.h"
#include "solve/ranks.h"
#include "solve/timestep.h"
#include "tests/check.h"
#include "tests/solve/fixture.h"
#include "tests/solve/harness.h"

static const char *case_json =
    "{\"assembly\": \"-\", \"material\": {\"name\": \"m\", \"law\": \"jcfpm\", "
    "\"density\": 2500, \"E\": 1e9, \"ks_ratio\": 0.2, \"tensile_strength\": 1e6, "
    "\"cohesion\": 1e6, \"friction_angle_deg\": 30, \"interaction_range\": 1},"
    "\"loading\": [{\"axial\": {\"mode\": \"strain_rate\", \"rate\": 1}}], "
    "\"stop\": {\"steps\": 10}}";

/* A number in [0.01, 1) from the pair (i, j) (or a particle i, j = -1) and
 * a draw. */
static double draw(int32_t i, int32_t j, int round)
{
	rng r;
	rng_seed(&r, ((uint64_t)(uint32_t)i << 32 | (uint32_t)j) * 131 + (uint64_t)round);
	return 0.01 + 0.99 * rng_uniform(&r);
}

int main(int argc, char **argv)
{
	if (par_init(&argc, &argv)) {
		fprintf(stderr, "test_timestep_ranks: %s\n", err_msg());
		return 1;
	}
	dem_case c;
	harness_case(&c, case_json);
	dem_assembly a;
	fixture_cylinder(&a, 5);
	engine e; /* every rank holds every particle, whose masses change below */
	if (engine_setup(&e, &c, &a, &(engine_opts){.quiet = 1, .whole = 1})) {
		fprintf(stderr, "test_timestep_ranks: %s\n", err_msg());
		return 1;
	}
	CHECK(e.pairs.bonds.n > 0);
	double *m0 = xmalloc(e.p.n * sizeof *m0);
	memcpy(m0, e.p.m, e.p.n * sizeof *m0);
	for (int round = 0; round < 32; round++) {
		if (round == 16) { /* no bonds: every near pair a contact */
			e.pairs.bonds.n = e.pairs.nbonds = 0;
			bonds_split(&e, e.pairs.split.n);
			ranks_split(&e);
			contacts_rebuild(&e);
		}
		for (size_t i = 0; i < e.p.n; i++)
			e.p.m[i] = m0[i] * draw(e.p.orig[i], -1, 3 * round);
		pairlist *L = &e.pairs.contacts;
		for (size_t q = 0; q < L->n; q++) {
			pair_rec *b = &L->rec[q];
			b->h[0] = 1e6 * draw(b->i, b->j, 3 * round + 1);
			b->h[1] = 1e6 * draw(b->i, b->j, 3 * round + 2);
		}
		size_t worst;
		double crit = timestep_critical(&e, 1, &worst);
		CHECK(isfinite(crit) && crit > 0 && worst < e.p.n);
		if (par_rank() == 0)
			printf("bound %a %d\n", crit, e.p.orig[worst]);
	}
	free(m0);
	engine_free(&e);
	case_free(&c);
	assembly_free(&a);
	int failed = check_done();
	par_finalize();
	return failed;
}
