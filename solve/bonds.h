/* Bonds: formed once at start, computed once per step by the law, their
 * failures collected as cracks (bonds.c). */
#ifndef DEM_BONDS_H
#define DEM_BONDS_H

#include <stddef.h>
#include <stdint.h>

#include "lib/runfile.h"
#include "solve/law.h"

typedef struct engine engine;

/* Bond failures waiting to be written to /cracks. */
typedef struct {
	size_t n, cap;
	dem_crack *c;
	int32_t *bond; /* the failed bond of each, for sorting */
} crack_buf;

/* Bonds between the particles within the law's range (Eq. 16). */
int bonds_form(engine *e);
void bonds_init_history(engine *e);
/* This step's bond forces, inside the step's parallel region. */
void bonds_forces(engine *e, int measure);
/* Move this step's failures to e->out.cracks, in bond order. */
void bonds_collect_cracks(engine *e);
/* Bond b's ends in the assembly's numbering (ends[0] < ends[1]) and, when c
 * is not NULL, its elastic constants. */
void engine_bond_entry(const engine *e, size_t b, int32_t ends[2], law_const *c);

#endif
