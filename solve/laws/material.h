/* A material file: the keys the engine reads ("name", "law", "density" and
 * the optional "contact" object for non-bonded and platen contacts);
 * everything else belongs to the law, which parses the same object. */
#ifndef DEM_LAWS_MATERIAL_H
#define DEM_LAWS_MATERIAL_H

#include "lib/cfg.h"
#include "solve/law.h"

typedef struct {
	char *name;
	const law *law;
	law_params *params;
	double density; /* kg/m^3 */
	/* Linear Cundall–Strack contacts (solve/laws/cundall.h). */
	double friction;        /* μ between spheres */
	double platen_friction; /* μ between a sphere and a platen */
	double damping;         /* ξ, fraction of the critical damping of the pair */
	double E, nu;           /* Pa, -: contact stiffness from these when E > 0,
	                           else the law's own bond stiffness for the pair */
} material;

/* Read a material object (a whole file, or an object inside a case file).
 * Unknown keys are left for the caller's cfg_check_unused. */
int material_parse(cfg *c, material *m);
void material_free(material *m);

#endif
