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

/* What rows of the bond table and of a snapshot are filled from: the
 * whole specimen's bonds and every particle by its row (one process), or
 * this rank's own bonds and particles (ranks_rows_write). */
typedef struct {
	engine *e;
	const pairlist *bonds;   /* row k is bond k of this list */
	const int32_t *internal; /* engine index of each particle row, or NULL:
	                            row k is particle p0 + k */
	size_t p0;
	int f; /* the field ranks_rows_write fills */
} rows_ctx;

/* Rows of the bond table (run_fill). */
static void bond_rows(void *ctx, int f, size_t at, size_t m, void *buf)
{
	const rows_ctx *c = ctx;
	int32_t *iv = buf;
	double *dv = buf;
	for (size_t k = 0; k < m; k++) {
		int32_t ends[2];
		law_const lc;
		int ends_only = f == BTAB_I || f == BTAB_J;
		engine_bond_entry(c->e, c->bonds, at + k, ends, ends_only ? NULL : &lc);
		switch (f) {
		case BTAB_I:
			iv[k] = ends[0];
			break;
		case BTAB_J:
			iv[k] = ends[1];
			break;
		case BTAB_D0:
			dv[k] = c->bonds->rec[at + k].d0;
			break;
		case BTAB_AREA:
			dv[k] = lc.area;
			break;
		case BTAB_KN:
			dv[k] = lc.kn;
			break;
		default:
			dv[k] = lc.ks;
			break;
		}
	}
}

/* Rows of a snapshot (run_fill): particles in the assembly's order, bonds
 * in the bond table's. */
static void snapshot_rows(void *ctx, int f, size_t at, size_t m, void *buf)
{
	const rows_ctx *c = ctx;
	const particles *P = &c->e->p;
	const pairlist *B = c->bonds;
	double *dv = buf;
	if (f == SNAP_X || f == SNAP_V || f == SNAP_W) {
		const double *src = f == SNAP_X ? P->x : f == SNAP_V ? P->v : P->w;
		for (size_t k = 0; k < m; k++) {
			size_t i = c->internal ? (size_t)c->internal[at + k] : c->p0 + at + k;
			memcpy(dv + 3 * k, src + 3 * i, 3 * sizeof *dv);
		}
		return;
	}
	for (size_t k = 0; k < m; k++) {
		const pair_rec *bd = &B->rec[at + k];
		if (f == SNAP_STATE) {
			((uint8_t *)buf)[k] = B->state[at + k];
		} else if (f == SNAP_DAMAGE_N || f == SNAP_DAMAGE_S) {
			double dn, ds;
			bond view = pairlist_bond(B, at + k);
			c->e->law->damage(c->e->lp, &view, &dn, &ds);
			dv[k] = f == SNAP_DAMAGE_N ? dn : ds;
		} else {
			const float *fo = B->fb + 3 * (at + k);
			const double *xi = P->x + 3 * bd->i, *xj = P->x + 3 * bd->j;
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

/* On several ranks: each field from every rank's own rows (run_put). */
static void own_bond_rows(void *ctx, size_t k0, size_t m, void *buf)
{
	bond_rows(ctx, ((rows_ctx *)ctx)->f, k0, m, buf);
}

static void own_snapshot_rows(void *ctx, size_t k0, size_t m, void *buf)
{
	snapshot_rows(ctx, ((rows_ctx *)ctx)->f, k0, m, buf);
}

static int put_own(rows_ctx *c, int snapshot, int f, h5_rows *r)
{
	engine *e = c->e;
	size_t cols, size;
	int per_bond;
	run_field_shape(snapshot, f, &cols, &size, &per_bond);
	c->f = f;
	ranks_fill fill = snapshot ? own_snapshot_rows : own_bond_rows;
	if (per_bond)
		return ranks_rows_write(e, r, e->pairs.nbonds, cols, size, e->pairs.bonds.n,
		                        e->pairs.bond0, NULL, fill, c);
	const rank_split *R = &e->ranks;
	return ranks_rows_write(e, r, e->p.n, cols, size, R->p1 - R->p0, 0, e->p.orig + R->p0, fill,
	                        c);
}

static int put_bonds(void *ctx, int f, h5_rows *r) { return put_own(ctx, 0, f, r); }
static int put_snapshot(void *ctx, int f, h5_rows *r) { return put_own(ctx, 1, f, r); }

int output_bonds(engine *e, run_writer *w)
{
	rows_ctx c = {e, &e->pairs.bonds, NULL, 0, 0};
	if (e->ranks.size > 1)
		return run_write_bonds_put(w, e->pairs.nbonds, put_bonds, &c);
	return run_write_bonds_fill(w, e->pairs.nbonds, bond_rows, &c);
}

int output_snapshot(engine *e, run_writer *w)
{
	const particles *P = &e->p;
	bonds_output_forces(e);
	dem_snapshot s = {.step = e->clock.step,
	                  .t = e->clock.t,
	                  .strain_axial = engine_strain(e),
	                  .stress_axial = engine_stress(e),
	                  .n = P->n,
	                  .nbonds = e->pairs.nbonds};
	if (e->ranks.size > 1) {
		rows_ctx c = {e, &e->pairs.bonds, NULL, e->ranks.p0, 0};
		return run_snapshot_put(w, &s, put_snapshot, &c);
	}
	int32_t *internal = xmalloc((P->n + 1) * sizeof *internal);
	for (size_t i = 0; i < P->n; i++)
		internal[P->orig[i]] = (int32_t)i;
	rows_ctx c = {e, &e->pairs.bonds, internal, 0, 0};
	int rc = run_snapshot_fill(w, &s, snapshot_rows, &c);
	free(internal);
	return rc;
}

int output_cracks(engine *e, run_writer *w)
{
	/* On several ranks each writes its own rows. */
	crack_buf *cb = &e->out.cracks;
	if (e->ranks.size > 1
	        ? run_cracks_runs(w, cb->c, cb->n, cb->all, cb->run_at, cb->run_n, cb->nruns)
	        : run_cracks(w, cb->c, cb->n))
		return -1;
	e->out.crack_rows += cb->all;
	cb->n = cb->all = cb->nruns = cb->most = 0;
	if (cb->held)
		memset(cb->held, 0, (size_t)e->ranks.size * sizeof *cb->held);
	return 0;
}
