/* Diagnoses of a failing simulation, each a one-line message naming the
 * particle or bond at fault (assembly indices). Those that look at every
 * particle first gather the particles of other ranks (ranks.h), on every
 * rank alike: collective. */
#ifndef DEM_DIAGNOSE_H
#define DEM_DIAGNOSE_H

#include <stddef.h>

#include "solve/engine.h"

/* Particle i's state is not finite after this step (i: the first such of
 * the whole specimen). Collective. */
void diagnose_nan(const engine *e, size_t i, char *msg, size_t n);
/* 1 (and a message) if the kinetic energy exceeds twice the energy the run
 * has received (initial plus external work): the integration is unstable. */
int diagnose_runaway(engine *e, char *msg, size_t n);
/* 1 (and a message) if a particle moved more than half the Verlet skin in
 * the last step: contacts could pass unseen between neighbour rebuilds. */
int diagnose_speed(engine *e, char *msg, size_t n);
/* 1 (and a message) if the time step exceeds the critical bound with the
 * current contacts (checked after each neighbour rebuild). */
int diagnose_timestep(engine *e, char *msg, size_t n);

#endif
