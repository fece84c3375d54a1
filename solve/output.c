/* What solve writes into run.h5 besides the history: the bond table,
 * snapshots (particles and bonds, in the assembly's order) and the crack
 * log. Internal (Morton) indices are mapped back through orig[]; a bond
 * whose ends swap in that mapping has its normal and shear force reversed,
 * so every record reads "from i to j" with i < j. */
#include <stdlib.h>
#include <string.h>

#include "lib/err.h"
#include "solve/bonds.h"
#include "solve/measure.h"
#include "solve/output.h"
#include "solve/ranks.h"

/* Rows of the bond table (run_fill). */
static void bond_rows(void *ctx, int f, size_t at, size_t m, void *buf)
{
	const engine *e = ctx;
	pairs_view v; /* the whole specimen's (ranks_gather_output) */
	ranks_pairs(e, &v);
	int32_t *iv = buf;
	double *dv = buf;
	for (size_t k = 0; k < m; k++) {
		int32_t ends[2];
		law_const c;
		int ends_only = f == BTAB_I || f == BTAB_J;
		engine_bond_entry(e, v.bonds, at + k, ends, ends_only ? NULL : &c);
		switch (f) {
		case BTAB_I:
			iv[k] = ends[0];
			break;
		case BTAB_J:
			iv[k] = ends[1];
			break;
		case BTAB_D0:
			dv[k] = v.bonds->rec[at + k].d0;
			break;
		case BTAB_AREA:
			dv[k] = c.area;
			break;
		case BTAB_KN:
			dv[k] = c.kn;
			break;
		default:
			dv[k] = c.ks;
			break;
		}
	}
}

int output_bonds(const engine *e, run_writer *w)
{
	return run_write_bonds_fill(w, e->pairs.nbonds, bond_rows, (void *)e);
}

typedef struct {
	const engine *e;
	int32_t *internal; /* [n] engine index of each assembly particle */
} snapshot_ctx;

/* Rows of a snapshot (run_fill): particles in the assembly's order, bonds
 * in the bond table's. */
static void snapshot_rows(void *ctx, int f, size_t at, size_t m, void *buf)
{
	const snapshot_ctx *c = ctx;
	const particles *P = &c->e->p;
	pairs_view v; /* the whole specimen's (ranks_gather_output) */
	ranks_pairs(c->e, &v);
	const pairlist *B = v.bonds;
	double *dv = buf;
	if (f == SNAP_X || f == SNAP_V || f == SNAP_W) {
		const double *src = f == SNAP_X ? P->x : f == SNAP_V ? P->v : P->w;
		for (size_t k = 0; k < m; k++)
			memcpy(dv + 3 * k, src + 3 * (size_t)c->internal[at + k], 3 * sizeof *dv);
		return;
	}
	for (size_t k = 0; k < m; k++) {
		const bond *bd = &B->rec[at + k];
		if (f == SNAP_STATE) {
			((uint8_t *)buf)[k] = bd->state;
		} else if (f == SNAP_DAMAGE_N || f == SNAP_DAMAGE_S) {
			double dn, ds;
			c->e->law->damage(c->e->lp, bd, &dn, &ds);
			dv[k] = f == SNAP_DAMAGE_N ? dn : ds;
		} else {
			const double *fo = B->f + 3 * (at + k), *xi = P->x + 3 * bd->i,
			             *xj = P->x + 3 * bd->j;
			double d[3] = {xj[0] - xi[0], xj[1] - xi[1], xj[2] - xi[2]};
			double l = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
			double fn = (fo[0] * d[0] + fo[1] * d[1] + fo[2] * d[2]) / l;
			double sign = P->orig[bd->i] < P->orig[bd->j] ? 1 : -1;
			if (f == SNAP_FN)
				dv[k] = fn;
			else
				for (int q = 0; q < 3; q++)
					dv[3 * k + q] = sign * (fo[q] - fn * d[q] / l);
		}
	}
}

int output_snapshot(const engine *e, run_writer *w)
{
	const particles *P = &e->p;
	dem_snapshot s = {.step = e->clock.step,
	                  .t = e->clock.t,
	                  .strain_axial = engine_strain(e),
	                  .stress_axial = engine_stress(e),
	                  .n = P->n,
	                  .nbonds = e->pairs.nbonds};
	snapshot_ctx c = {e, xmalloc((P->n + 1) * sizeof *c.internal)};
	for (size_t i = 0; i < P->n; i++)
		c.internal[P->orig[i]] = (int32_t)i;
	int rc = run_snapshot_fill(w, &s, snapshot_rows, &c);
	free(c.internal);
	return rc;
}

int output_cracks(engine *e, run_writer *w)
{
	if (run_cracks(w, e->out.cracks.c, e->out.cracks.n))
		return -1;
	e->out.crack_rows += e->out.cracks.n;
	e->out.cracks.n = 0;
	return 0;
}
