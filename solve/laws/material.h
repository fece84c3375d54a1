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
	int conventions;        /* CONTACT_SOLVE or CONTACT_YADE */
} material;

/* The material's "contact.conventions". CONTACT_SOLVE: a contact pushes
 * from the moment the spheres (or a sphere and a platen) touch; a platen
 * contact's shear force keeps its direction while the sphere spins about
 * the normal (the platen does not turn), and acts at the contact point on
 * the platen. CONTACT_YADE, Yade's JCFPM (JointedCohesiveFrictionalPM with
 * ScGeom), for like-for-like comparisons: a contact found overlapping
 * exerts no force in that step and takes that overlap as its zero-force
 * point; it ends, without force, in the first step it is open past that
 * point, and starts again at its next overlap (so does a jcfpm bond that
 * broke: one broken in tension, or in shear while in tension, has ended);
 * a platen contact turns its shear force with half the sphere's spin
 * about the normal, as a pair of spheres with their mean spin, and its
 * torque acts at r - overlap/2 from the centre. */
enum { CONTACT_SOLVE, CONTACT_YADE };

/* The "conventions" of material c's "contact" object into *conventions
 * (CONTACT_SOLVE when absent); -1 with the error set on a bad value. */
int contact_conventions_parse(cfg *c, int *conventions);

/* Read a material object (a whole file, or an object inside a case file).
 * Unknown keys are left for the caller's cfg_check_unused. */
int material_parse(cfg *c, material *m);
void material_free(material *m);

#endif
