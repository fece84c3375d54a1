/* The explicit DEM engine's state and its setup (setup.c).
 *
 * Data layout (DESIGN.md §4): particles as separate arrays in Morton order
 * (orig[] maps back to the assembly's indices); bonds in one flat array of
 * `bond` records, each computed once per step into a per-bond force, then
 * gathered per particle through a CSR index (pairlist.h); non-bonded
 * contacts the same way from a Verlet list. Everything a particle needs from
 * another one is read by index from these arrays, so a halo of ghost
 * particles could later provide it under an MPI domain decomposition.
 * Reductions are summed in fixed blocks (blocks.h), so results do not
 * depend on the number of threads, bit for bit.
 *
 * Each engine file has its own header for its functions: pairlist, bonds,
 * contacts, platens, surface, boundary (the loading program), measure,
 * timestep, step; the state they share is the struct below. */
#ifndef DEM_ENGINE_H
#define DEM_ENGINE_H

#include <stddef.h>
#include <stdint.h>

#include "lib/assembly.h"
#include "solve/blocks.h"
#include "solve/bonds.h"
#include "solve/boundary.h"
#include "solve/case.h"
#include "solve/cells.h"
#include "solve/law.h"
#include "solve/measure.h"
#include "solve/pairlist.h"
#include "solve/platens.h"
#include "solve/step.h"
#include "solve/surface.h"

/* Particle flags. */
enum { PF_LAYER_BOTTOM = 1, PF_LAYER_TOP = 2, PF_CONSTRAINED = 4 };

typedef struct {
	size_t n;
	double *x, *v, *w; /* [n][3] m, m/s (at t - dt/2), rad/s */
	double *r, *m, *inv_m, *inv_i;
	int32_t *orig;     /* index in the assembly */
	double *x_ref;     /* [n][3] positions at the last neighbour rebuild */
	uint8_t *flag;     /* PF_* */
	int32_t *surf;     /* slot in the lateral surface list, or -1 */
	int32_t *pslot[2]; /* contact slot with platen 0 (bottom) / 1 (top), or -1 */
	double *omega2;    /* 1/s^2, bound on ω² from the bonds (timestep.c) */
} particles;

typedef struct engine engine;

struct engine {
	const dem_case *cs;
	const law *law;
	law_params *lp;
	int nthreads; /* threads asked for */
	int team;     /* threads used in a step */

	particles p;
	pairlist bonds, contacts, contacts_old;
	cells grid;
	platens pl;
	surface surf;
	gauge gg;
	loads ld;

	/* specimen frame */
	double center[3], axis[3], e1[3], e2[3];
	double height0; /* m, platen gap at the start */
	double area0;   /* m^2, cross-section for the axial stress */
	double r_mean, r_max;
	double skin;

	double dt, dt_crit;
	double xi_max; /* largest fraction of critical damping (Eq. 13) */
	int64_t step;
	double t;

	/* loading program */
	int stage;
	int64_t stage_step; /* step at which the stage started */
	double stage_t;
	double stage_strain0, stage_stress0, stage_pressure0;
	double stage_peak;
	double peak;
	double pressure;     /* Pa, currently applied */
	int layers_selected; /* end layers chosen (at the first layers stage) */
	int drop_armed;      /* quasi-static reached: the stress-drop rule may fire */

	/* energies (J), accumulated */
	double e_damped, e_friction, e_fracture, e_work;
	double e_initial; /* kinetic + elastic at the start */
	double ke;        /* shadow kinetic energy of the last step */
	double ke_noise;  /* kinetic energy of every particle moving 1e-12 r per step */

	/* this step's reductions */
	pair_sums bsum, csum;
	particle_sums psum;
	measurement meas;
	int rebuild; /* neighbour lists are due */
	int64_t rebuilds;

	/* bookkeeping for the output */
	crack_buf cracks; /* failures not yet written */
	crack_buf *thread_cracks;
	size_t history_rows, crack_rows;
	double last_snapshot_strain; /* strain at the last snapshot */
	size_t snapshot_strain_next; /* next of cs->snapshot_strains to write */

	/* scratch, allocated once */
	pair_sums *bblock, *cblock;
	size_t ncblock;
	particle_sums *pblock;
	double *scratch; /* [n] */

	/* timers (s) */
	double tm[7];
};

/* Timer slots: the phases of the run loop, its total, and the setup before
 * it (bonds formed, lists built, run file created), not counted in the
 * loop's rate. */
enum { TM_NEIGHBOUR, TM_BONDS, TM_CONTACTS, TM_INTEGRATE, TM_OUTPUT, TM_TOTAL, TM_SETUP };

/* The state at the start of a run (particles sorted, bonds formed, time
 * step chosen). Prints a summary with the time step on stderr unless
 * quiet. */
int engine_setup(engine *e, const dem_case *cs, const dem_assembly *a, int quiet);
void engine_free(engine *e);

#endif
