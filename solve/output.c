/* What solve writes into run.h5 besides the history: the bond table,
 * snapshots (particles and bonds, in the assembly's order) and the crack
 * log. Internal (Morton) indices are mapped back through orig[]; a bond
 * whose ends swap in that mapping has its normal and shear force reversed,
 * so every record reads "from i to j" with i < j. */
#include <stdlib.h>
#include <string.h>

#include "lib/err.h"
#include "solve/output.h"

int output_bonds(const engine *e, run_writer *w)
{
	dem_bonds b;
	engine_bond_table(e, &b);
	int rc = run_write_bonds(w, &b);
	bonds_free(&b);
	return rc;
}

int output_snapshot(const engine *e, run_writer *w)
{
	const particles *P = &e->p;
	const pairlist *B = &e->bonds;
	size_t n = P->n, nb = B->n;
	dem_snapshot s = {.step = e->step,
	                  .t = e->t,
	                  .strain_axial = engine_strain(e),
	                  .stress_axial = engine_stress(e),
	                  .n = n,
	                  .nbonds = nb};
	s.x = xmalloc((3 * n + 1) * sizeof *s.x);
	s.v = xmalloc((3 * n + 1) * sizeof *s.v);
	s.w = xmalloc((3 * n + 1) * sizeof *s.w);
	for (size_t i = 0; i < n; i++) {
		size_t o = (size_t)P->orig[i];
		memcpy(s.x + 3 * o, P->x + 3 * i, 3 * sizeof *s.x);
		memcpy(s.v + 3 * o, P->v + 3 * i, 3 * sizeof *s.v);
		memcpy(s.w + 3 * o, P->w + 3 * i, 3 * sizeof *s.w);
	}
	s.state = xmalloc(nb + 1);
	s.damage_n = xmalloc((nb + 1) * sizeof *s.damage_n);
	s.damage_s = xmalloc((nb + 1) * sizeof *s.damage_s);
	s.fn = xmalloc((nb + 1) * sizeof *s.fn);
	s.fs = xmalloc((3 * nb + 1) * sizeof *s.fs);
	for (size_t b = 0; b < nb; b++) {
		const bond *bd = &B->rec[b];
		const double *f = B->f + 6 * b, *xi = P->x + 3 * bd->i, *xj = P->x + 3 * bd->j;
		double d[3] = {xj[0] - xi[0], xj[1] - xi[1], xj[2] - xi[2]};
		double l = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
		double fn = (f[0] * d[0] + f[1] * d[1] + f[2] * d[2]) / l;
		double sign = P->orig[bd->i] < P->orig[bd->j] ? 1 : -1;
		s.state[b] = bd->state;
		e->law->damage(e->lp, bd, &s.damage_n[b], &s.damage_s[b]);
		s.fn[b] = fn;
		for (int k = 0; k < 3; k++)
			s.fs[3 * b + k] = sign * (f[k] - fn * d[k] / l);
	}
	int rc = run_snapshot(w, &s);
	snapshot_free(&s);
	return rc;
}

int output_cracks(engine *e, run_writer *w)
{
	if (run_cracks(w, e->cracks.c, e->cracks.n))
		return -1;
	e->crack_rows += e->cracks.n;
	e->cracks.n = 0;
	return 0;
}
