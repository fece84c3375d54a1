/* The constants of a non-bonded contact (between spheres, or between a
 * sphere and a platen): a Cundall–Strack contact (cundall.h) whose stiffness
 * comes from the material's "contact" object (E, ν) when given, else from
 * the law's own bond stiffness for the pair, and whose normal damping is the
 * fraction ξ of the pair's critical damping. */
#ifndef DEM_LAWS_CONTACT_H
#define DEM_LAWS_CONTACT_H

#include "solve/law.h"
#include "solve/laws/material.h"

/* Normal and shear stiffness (N/m) and normal damping (N s/m) of a contact
 * between spheres of radii ri, rj (m) and masses mi, mj (kg) touching at
 * distance d0 (m); lp are the material's law parameters as set up. */
void contact_constants(const material *m, const law_params *lp, double ri, double rj, double mi,
                       double mj, double d0, double k[3]);

#endif
