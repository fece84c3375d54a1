/* Rigid platens at the specimen's ends (platens.c; the contact force of a
 * sphere with a platen is in platen_contact.h). */
#ifndef DEM_PLATENS_H
#define DEM_PLATENS_H

#include <stddef.h>
#include <stdint.h>

typedef struct engine engine;

typedef struct {
	double t[3];       /* N, shear force history */
	double kn, ks, cn; /* of the sphere–platen contact */
	double u0;         /* m, with Yade's conventions: the overlap at which it started
	                      (cundall_started), else 0 */
} platen_contact;

typedef struct {
	int active;      /* platens in contact with the specimen this stage */
	double z[2];     /* m, axial position (bottom, top) from the centre */
	double vel[2];   /* m/s along the axis, this step (t + dt/2) */
	double load[2];  /* N, compressive force from the specimen */
	double ksum[2];  /* N/m, normal stiffness of touching contacts */
	double z_ref[2]; /* at the last neighbour rebuild */
	size_t ncand[2], cap[2];
	platen_contact *pc[2], *pc_old[2];
	int32_t *who[2]; /* particle of each candidate */
} platens;

/* Place the platens where they just touch the specimen. */
void platens_init(engine *e);
/* List the particles within the skin of each platen (at a neighbour rebuild). */
void platens_rebuild(engine *e);
/* After a checkpoint has replaced the candidates with the whole
 * specimen's: keep this rank's particles' (ranks.h), and their slots. */
void platens_restore(engine *e);
/* Move the platens at vel (m/s along the axis) for one step, with their work. */
void platens_move(engine *e, const double vel[2]);
/* The distance each platen moved since the last rebuild. */
double platens_drift(const engine *e);
void platens_free(platens *pl);

#endif
