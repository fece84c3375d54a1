/* The critical time step (timestep.c; Oñate et al. 2015 Eq. 11-15). */
#ifndef DEM_TIMESTEP_H
#define DEM_TIMESTEP_H

#include <stddef.h>

typedef struct engine engine;

/* The bound of Eq. 11-15 (s); worst gets the particle setting it. */
double timestep_critical(engine *e, int with_contacts, size_t *worst);
/* The bound on ω² of particle i from its bonds, and their number, over
 * every rank (a scan of the bonds: for messages). Collective. */
double timestep_bond_omega2(const engine *e, size_t i, int *count);
/* The bound on ω² of one pair (normal and shear springs at arms ai, aj). */
double pair_omega2(double kn, double ks, double mi, double mj, double ii, double ij, double ai,
                   double aj);

#endif
