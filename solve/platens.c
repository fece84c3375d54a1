/* Rigid platens: two planes normal to the specimen axis, the bottom one
 * facing +axis, the top one -axis, placed at start where they just touch
 * the specimen. A sphere touching a platen is a Cundall–Strack contact
 * (laws/cundall.h) with twice the stiffness and damping of a contact with
 * its own mirror image (the platen is the symmetry plane of that pair:
 * overlap δ with the plane is overlap 2δ with the image) and the platen
 * friction. Candidates are the particles closer than the skin, listed at
 * each neighbour rebuild with their shear history carried over. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lib/err.h"
#include "solve/engine.h"
#include "solve/laws/contact.h"
#include "solve/par.h"
#include "solve/platens.h"
#include "solve/ranks.h"

static double axial(const engine *e, const double *x)
{
	return (x[0] - e->frame.center[0]) * e->frame.axis[0] +
	       (x[1] - e->frame.center[1]) * e->frame.axis[1] +
	       (x[2] - e->frame.center[2]) * e->frame.axis[2];
}

void platens_init(engine *e)
{
	platens *pl = &e->bc.pl;
	const particles *P = &e->p;
	size_t p0, p1;
	int split = ranks_own(e, &p0, &p1);
	double m[2] = {-INFINITY, -INFINITY}; /* -lo, hi */
	for (size_t i = p0; i < p1; i++) {
		double z = axial(e, P->x + 3 * i);
		m[0] = fmax(m[0], -(z - P->r[i]));
		m[1] = fmax(m[1], z + P->r[i]);
	}
	if (split)
		par_max(m, 2);
	pl->z[0] = -m[0];
	pl->z[1] = m[1];
	for (int k = 0; k < 2; k++) {
		pl->cap[k] = 64;
		pl->pc[k] = xmalloc(pl->cap[k] * sizeof *pl->pc[k]);
		pl->pc_old[k] = xmalloc(pl->cap[k] * sizeof *pl->pc_old[k]);
		pl->who[k] = xmalloc(pl->cap[k] * sizeof *pl->who[k]);
	}
}

void platens_rebuild(engine *e)
{
	platens *pl = &e->bc.pl;
	particles *P = &e->p;
	for (int k = 0; k < 2; k++) {
		platen_contact *tmp = pl->pc_old[k];
		pl->pc_old[k] = pl->pc[k];
		pl->pc[k] = tmp;
		size_t old_cap = pl->cap[k];
		size_t n = 0, p0, p1;
		/* Each rank its own particles' (ranks.h). */
		ranks_own(e, &p0, &p1);
		for (size_t i = p0; i < p1; i++) {
			int32_t old = P->pslot[k][i];
			P->pslot[k][i] = -1;
			double z = axial(e, P->x + 3 * i);
			double gap = (k == 0 ? z - pl->z[0] : pl->z[1] - z) - P->r[i];
			if (!pl->active || gap >= e->pairs.skin)
				continue;
			if (n == pl->cap[k]) {
				pl->cap[k] *= 2;
				pl->pc[k] = xrealloc(pl->pc[k], pl->cap[k] * sizeof *pl->pc[k]);
				pl->who[k] = xrealloc(pl->who[k], pl->cap[k] * sizeof *pl->who[k]);
			}
			platen_contact *c = &pl->pc[k][n];
			double kk[3];
			contact_constants(&e->cs->mat, e->lp, P->r[i], P->r[i], P->m[i], P->m[i],
			                  2 * P->r[i], kk);
			c->kn = 2 * kk[0];
			c->ks = 2 * kk[1];
			c->cn = 2 * kk[2];
			if (old >= 0) {
				memcpy(c->t, pl->pc_old[k][old].t, sizeof c->t);
				c->u0 = pl->pc_old[k][old].u0;
			} else {
				memset(c->t, 0, sizeof c->t);
				c->u0 = 0;
			}
			pl->who[k][n] = (int32_t)i;
			P->pslot[k][i] = (int32_t)n++;
		}
		pl->ncand[k] = n;
		pl->z_ref[k] = pl->z[k];
		if (pl->cap[k] != old_cap)
			pl->pc_old[k] = xrealloc(pl->pc_old[k], pl->cap[k] * sizeof *pl->pc_old[k]);
	}
}

void platens_restore(engine *e)
{
	platens *pl = &e->bc.pl;
	particles *P = &e->p;
	size_t p0, p1;
	ranks_own(e, &p0, &p1);
	for (int k = 0; k < 2; k++) {
		size_t m = 0;
		for (size_t i = P->lo; i < P->hi; i++)
			P->pslot[k][i] = -1;
		for (size_t c = 0; c < pl->ncand[k]; c++) {
			int32_t i = pl->who[k][c];
			if ((size_t)i < p0 || (size_t)i >= p1)
				continue;
			pl->pc[k][m] = pl->pc[k][c];
			pl->who[k][m] = i;
			P->pslot[k][i] = (int32_t)m++;
		}
		pl->ncand[k] = m;
	}
}

void platens_free(platens *pl)
{
	for (int k = 0; k < 2; k++) {
		free(pl->pc[k]);
		free(pl->pc_old[k]);
		free(pl->who[k]);
	}
}

/* Move the platens by the velocities the loading program asks for, with the
 * work they do on the specimen (midpoint rule, consistent with the
 * central-difference energy balance). */
void platens_move(engine *e, const double vel[2])
{
	platens *pl = &e->bc.pl;
	for (int k = 0; k < 2; k++) {
		double inward = k == 0 ? 1 : -1;
		e->energy.work += pl->load[k] * inward * 0.5 * (pl->vel[k] + vel[k]) * e->clock.dt;
		pl->vel[k] = vel[k];
		pl->z[k] += vel[k] * e->clock.dt;
	}
}

/* The distance each platen moved since the last rebuild (for its trigger). */
double platens_drift(const engine *e)
{
	return fmax(fabs(e->bc.pl.z[0] - e->bc.pl.z_ref[0]),
	            fabs(e->bc.pl.z[1] - e->bc.pl.z_ref[1]));
}
