/* One time step (step.c). */
#ifndef DEM_STEP_H
#define DEM_STEP_H

#include <stddef.h>

#include "lib/xsum.h"
#include "solve/pairlist.h"

typedef struct engine engine;

/* Sums over one block of particles (blocks.h). */
typedef struct {
	double ke;     /* shadow kinetic energy (v- · v+) */
	double ke_new; /* kinetic energy at t + dt/2 (for diagnoses) */
	double e_damped, e_work;
	double load[2], ksum[2], ntouch[2];
	double layer[2];         /* N, reaction of the end layers */
	double lateral_force;    /* N, Σ |confinement force| */
	double constraint_force; /* N, Σ radial reaction of constrained particles */
	double platen_friction, platen_viscous, platen_elastic;
	double love[9];
	/* Not summed: the largest, the lowest (disp2 and v2max stay adjacent,
	 * particles_sum reduces them as a pair). */
	double disp2; /* max squared displacement since the rebuild */
	double v2max; /* m^2/s^2, largest squared speed at t + dt/2 */
	double bad;   /* lowest particle index with a non-finite state, or n */
} particle_sums;

/* One thread's part of a step's sums, over the blocks of its shares: the
 * bonds' fields (pair_sums), the contacts', the particles' up to disp2,
 * exactly (reduce.h), so the step's totals do not depend on how the blocks
 * are shared; then the largest disp2, v2max and -bad. */
enum {
	STEP_PAIR_SUMS = sizeof(pair_sums) / sizeof(double),
	STEP_PARTICLE_SUMS = offsetof(particle_sums, disp2) / sizeof(double),
	STEP_SUMS = 2 * STEP_PAIR_SUMS + STEP_PARTICLE_SUMS
};
typedef struct {
	xsum sum[STEP_SUMS];
	double top[3];
} step_part;

/* One time step; measure != 0 also computes what the history needs
 * (elastic energy, Love–Weber sums, bond counts). */
void engine_step(engine *e, int measure);

#endif
