/* The history table: one row every `history_every` steps, of the state at
 * the start of that step (positions x(t), forces at x(t), the shadow kinetic
 * energy at t). Columns and units are documented in share/doc/solve.md.
 *
 * Average stress (Love–Weber), compression positive:
 *   σ = -(1/V) sym[ Σ_pairs (x_j - x_i) ⊗ F_i + Σ_boundary (x_c - x_p) ⊗ f ]
 * over bonds and contacts (F_i the force on i) and the boundary forces
 * (platen contacts, confinement, constraint reactions) at their points of
 * application; V the current volume enclosed by the lateral surface bins
 * (surface.c) over the specimen's current height. */
#include <math.h>
#include <string.h>

#include "solve/engine.h"
#include "solve/history.h"
#include "solve/measure.h"

const run_column history_columns[] = {
    {"t", "s"},
    {"step", ""},
    {"strain_axial", ""},
    {"stress_axial", "Pa"},
    {"stress_bottom", "Pa"},
    {"stress_top", "Pa"},
    {"force_axial", "N"},
    {"strain_radial", ""},
    {"strain_volumetric", ""},
    {"pressure", "Pa"},
    {"lateral_force", "N"},
    {"lateral_force_target", "N"},
    {"lateral_area", "m^2"},
    {"volume", "m^3"},
    {"stress_xx", "Pa"},
    {"stress_yy", "Pa"},
    {"stress_zz", "Pa"},
    {"stress_xy", "Pa"},
    {"stress_yz", "Pa"},
    {"stress_xz", "Pa"},
    {"energy_kinetic", "J"},
    {"energy_elastic", "J"},
    {"energy_damped", "J"},
    {"energy_friction", "J"},
    {"energy_fracture", "J"},
    {"energy_work", "J"},
    {"bonds_intact", ""},
    {"bonds_damaged", ""},
    {"bonds_broken_tension", ""},
    {"bonds_broken_shear", ""},
    {"contacts", ""},
    {"contacts_platen", ""},
    {"stage", ""},
    {"rate", "1/s"},
};
const int history_ncolumns = (int)(sizeof history_columns / sizeof history_columns[0]);

void history_row(const engine *e, double rate, double *row)
{
	const measurement *m = &e->sums.meas;
	double love[9];
	for (int c = 0; c < 9; c++)
		love[c] =
		    e->sums.bonds.love[c] + e->sums.contacts.love[c] + e->sums.particles.love[c];
	double ev = m->strain + 2 * m->strain_radial;
	double V = m->volume;
	double s[6];
	static const int ab[6][2] = {{0, 0}, {1, 1}, {2, 2}, {0, 1}, {1, 2}, {0, 2}};
	for (int c = 0; c < 6; c++) {
		int a = ab[c][0], b = ab[c][1];
		s[c] = -0.5 * (love[3 * a + b] + love[3 * b + a]) / V;
	}
	const double *cnt = e->sums.bonds.count;
	double v[] = {m->t,
	              (double)m->step,
	              m->strain,
	              0.5 * (m->stress[0] + m->stress[1]),
	              m->stress[0],
	              m->stress[1],
	              0.5 * (m->stress[0] + m->stress[1]) * e->frame.area0,
	              m->strain_radial,
	              ev,
	              m->pressure,
	              m->lateral_force,
	              m->pressure * m->lateral_area,
	              m->lateral_area,
	              m->volume,
	              s[0],
	              s[1],
	              s[2],
	              s[3],
	              s[4],
	              s[5],
	              e->energy.kinetic,
	              engine_elastic(e),
	              e->energy.damped,
	              e->energy.friction,
	              e->energy.fracture,
	              e->energy.work,
	              cnt[BOND_INTACT],
	              cnt[BOND_DAMAGED],
	              cnt[BOND_BROKEN_TENSION],
	              cnt[BOND_BROKEN_SHEAR],
	              e->sums.contacts.count[4],
	              e->sums.particles.ntouch[0] + e->sums.particles.ntouch[1],
	              (double)(m->stage + 1),
	              rate};
	_Static_assert(sizeof v / sizeof *v == sizeof history_columns / sizeof *history_columns,
	               "one value per history column");
	memcpy(row, v, sizeof v);
}
