/* FIRE, the fast inertial relaxation engine (Bitzek et al., PRL 97, 170201,
 * 2006, with the FIRE 2.0 half-step correction of Guenole et al., Comput.
 * Mater. Sci. 175, 109584, 2020), minimising the soft-sphere energy of
 * pack/soft.h. Inertia carries spheres through the shallow valleys where
 * plain overlap-removal sweeps stall near jamming. */
#ifndef PACK_FIRE_H
#define PACK_FIRE_H

#include "pack/soft.h"

typedef struct {
	double *v, *f; /* [n][3] velocities and forces */
	double dt, alpha;
	int npos;
	long iter;
	soft_stats stats; /* after the last step */
} fire_state;

/* Start from rest at the system's current configuration. */
void fire_start(fire_state *st, soft_system *s);
/* One iteration: fire_move (velocities and positions from the current
 * forces) then fire_forces (forces and stats at the new positions). A
 * caller may change radii between the two. */
void fire_step(fire_state *st, soft_system *s);
void fire_move(fire_state *st, soft_system *s);
void fire_forces(fire_state *st, soft_system *s);
void fire_end(fire_state *st);

/* Iterate until the largest relative overlap is below otol, max |F|/r is
 * below ftol, or max_iter steps were taken; returns the steps taken. */
long fire_minimise(soft_system *s, long max_iter, double otol, double ftol, double *overlap);

#endif
