/* The explicit DEM engine's state and its setup (setup.c).
 *
 * Data layout (DESIGN.md §4): particles as separate arrays in Morton order
 * walked within cells (order.h; orig[] maps back to the assembly's
 * indices); bonds in one flat array of `bond` records, each computed once
 * per step and its force added to both particles in bond order (bonds.h);
 * non-bonded contacts from a Verlet list, their forces gathered per
 * particle through a CSR index (pairlist.h). Everything a particle needs
 * from another one is read by index from these arrays, which under a domain
 * decomposition hold a rank's own particles and the others it reads
 * (window.h).
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
#include "lib/vec3.h"
#include "solve/blocks.h"
#include "solve/bonds.h"
#include "solve/boundary.h"
#include "solve/case.h"
#include "solve/cells.h"
#include "solve/law.h"
#include "solve/measure.h"
#include "solve/pairlist.h"
#include "solve/platens.h"
#include "solve/ranks.h"
#include "solve/step.h"
#include "solve/surface.h"
#include "solve/timers.h"
#include "solve/window.h"

/* Particle flags. */
enum { PF_LAYER_BOTTOM = 1, PF_LAYER_TOP = 2, PF_CONSTRAINED = 4 };

/* A rank holds the particles of a window of indices [lo, hi) (window.h):
 * its own, [own0, own1), under their index in the whole specimen, and
 * the other ranks' particles it reads numbered next to them in the order
 * of their indices, so that every pair keeps its order. The arrays below
 * are indexed by the window's indices (their memory starts at lo); glob
 * gives each one's index in the whole specimen. With one rank (or
 * engine_opts.whole) the window is the whole specimen (glob NULL). */
typedef struct particles {
	size_t n;         /* particles of the whole specimen */
	size_t lo, hi;    /* the window */
	size_t held_peak; /* the largest window so far, setup included */
	int32_t *glob;    /* [lo, hi) index in the whole specimen, or NULL */
	int32_t *fixed;   /* the other ranks' particles held for the whole run
	                     (the other ends of the crossing bonds), index in
	                     the whole specimen, increasing */
	size_t nfixed;
	double *x, *v, *w; /* [window][3] m, m/s (at t - dt/2), rad/s */
	double *r, *m;     /* m, kg */
	int32_t *orig;     /* index in the assembly */
	size_t own0, own1; /* this rank's particles (ranks.h) */
	double *x_ref;     /* [own][3] positions at the last neighbour rebuild,
	                      particle i's at 3 (i - own0) */
	uint8_t *flag;     /* PF_* */
	int32_t *surf;     /* slot in the lateral surface list, or -1 */
	int32_t *pslot[2]; /* contact slot with platen 0 (bottom) / 1 (top), or -1 */
} particles;

/* The mass of a solid sphere of radius r (m) and density rho (kg/m^3). */
static inline double particle_mass(double rho, double r)
{
	return rho * 4.0 / 3.0 * DEM_PI * r * r * r;
}

/* The index in the whole specimen of the window's particle i. */
static inline size_t particle_global(const particles *P, size_t i)
{
	return P->glob ? (size_t)P->glob[i] : i;
}

/* 1/m and 1/I (I = 2/5 m r², a solid sphere) of particle i, computed where
 * they are needed rather than stored: one expression, so the same bits
 * everywhere. */
static inline double particle_inv_m(const particles *P, size_t i) { return 1 / P->m[i]; }
static inline double particle_inv_i(const particles *P, size_t i)
{
	return 1 / (0.4 * P->m[i] * P->r[i] * P->r[i]);
}

/* The parts of the engine state. Under a domain decomposition the
 * particles, pairs and scratch are each rank's own; the boundary's sums,
 * the frame, the clock, the loading program, the energies and this step's
 * sums are global (reduced over ranks). */

/* Bonds and contacts, and the neighbour search that finds contacts. */
typedef struct {
	/* This rank's bonds, those of its particles i (ranks.h): the bonds
	 * [bond0, bond0 + bonds.n) of the whole specimen's nbonds, sorted by
	 * (i, j). */
	pairlist bonds;
	size_t bond0, nbonds;
	/* Between bonds_form and ranks_split: the search that finds the bonds,
	 * which each rank then makes the records of its own from. */
	bond_search formed;
	pairlist contacts, contacts_old;
	bond_split split; /* the shares of the particles and bonds among threads */
	share_balance balance;
	prefetch_tune prefetch;
	cells grid;
	double skin;      /* m, Verlet skin of the contact list */
	int rebuild;      /* neighbour lists are due */
	int64_t rebuilds; /* neighbour rebuilds so far */
} engine_pairs;

/* The boundary conditions: platens, lateral surface, radial gauge, and
 * what the loading program applies in the current step. */
typedef struct {
	platens pl;
	surface surf;
	gauge gauge;
	loads loads;
} engine_boundary;

/* The specimen's frame and sizes, fixed at start. */
typedef struct {
	double center[3], axis[3], e1[3], e2[3];
	double height0; /* m, platen gap at the start */
	double area0;   /* m^2, cross-section for the axial stress */
	double r_mean, r_max;
} engine_frame;

typedef struct {
	double dt, dt_crit; /* s */
	double xi_max;      /* largest fraction of critical damping (Eq. 13) */
	int64_t step;
	double t; /* s */
} engine_clock;

/* The loading program's state (boundary.c). */
typedef struct {
	int stage;
	int64_t stage_step; /* step at which the stage started */
	double stage_t;
	double stage_strain0, stage_stress0, stage_pressure0;
	double stage_peak;
	double peak;
	double pressure;     /* Pa, currently applied */
	int layers_selected; /* end layers chosen (at the first layers stage) */
	int drop_armed;      /* quasi-static reached: the stress-drop rule may fire */
} engine_program;

/* Energies (J), accumulated. */
typedef struct {
	double damped, friction, fracture, work;
	double initial; /* kinetic + elastic at the start */
	double kinetic; /* shadow kinetic energy of the last step */
	double noise;   /* kinetic energy of every particle moving 1e-12 r per step */
} engine_energy;

/* Flags every rank must agree on, each the largest over the ranks (run.c:
 * a signal, the wall-clock budget, a checkpoint due by the clock). */
enum { ENGINE_AGREE = 3 };

/* This step's reductions (blocks.h) and measurement. */
typedef struct {
	pair_sums bonds, contacts;
	particle_sums particles;
	measurement meas;
	/* Set before the step, the largest over the ranks after it (in the
	 * step's one reduction). */
	double agree[ENGINE_AGREE];
} engine_sums;

/* Bookkeeping for the output. */
typedef struct {
	crack_buf cracks; /* failures not yet written */
	crack_buf *thread_cracks;
	size_t history_rows, crack_rows;
	double last_snapshot_strain; /* strain at the last snapshot */
	size_t snapshot_strain_next; /* next of cs->snapshot_strains to write */
} engine_output;

/* Per-block sums and a per-particle buffer, allocated once. */
typedef struct {
	pair_sums *bblock, *cblock; /* bonds and contacts by the block of their i */
	size_t *cfirst;             /* [particle blocks + 1] first contact of each */
	particle_sums *pblock;
	step_part *parts; /* [threads] each thread's part of the step's sums */
	int nparts;       /* the threads of the last step */
	double *acc;      /* [own][6] sum of the bond forces and torques per unit
	                     radius, particle i's at 6 (i - p.own0) (engine_acc);
	                     zero between steps (bonds_share) */
} engine_scratch;

typedef struct engine engine;

struct engine {
	/* The run's definition, read-only after setup. */
	const dem_case *cs;
	const law *law;
	law_params *lp; /* the engine's own copy of the material's (law.copy) */
	int nthreads;   /* threads asked for */
	int team;       /* threads used in a step */
	/* The particles in the Morton order alone (order.h). */
	int plain_order;
	/* Every particle moved by integrate_one, the one-by-one form that the
	 * particles' vector form (solve/step.c) matches to the bit: for the
	 * tests only (DEM_TEST_ONE_BY_ONE=1). */
	int one_by_one;

	particles p;
	engine_pairs pairs;
	engine_boundary bc;
	engine_frame frame;
	engine_clock clock;
	engine_program prog;
	engine_energy energy;
	engine_sums sums;
	engine_output out;
	engine_scratch scratch;
	rank_split ranks; /* this rank's particles, and what crosses to others */
	phase_timers tm;
};

/* Particle i's sums of bond forces (6 doubles); i is this rank's own. */
static inline double *engine_acc(const engine *e, size_t i)
{
	return e->scratch.acc + 6 * (i - e->p.own0);
}

typedef struct {
	int threads; /* OpenMP threads; 0: the case's "threads", else all cores */
	int quiet;   /* no summary on stderr */
	int whole;   /* with several ranks, every rank keeps every particle (no
	                window_start: for tests that change them all) */
	int restart; /* the state comes from a checkpoint (checkpoint_read, then
	                engine_timestep_set), which holds the contacts and the time
	                step: no contact search or time step here */
	/* The particles in the Morton order alone, as in the checkpoints written
	 * before the walk within cells (order.h, checkpoint_plain_order). */
	int plain_order;
} engine_opts;

/* The state at the start of a run (particles sorted, bonds formed, time
 * step chosen); with several ranks, each holds its window of particles
 * (window.h) once they are split among the ranks, unless o->whole. Prints a summary with the time
 * step on stderr unless quiet. */
int engine_setup(engine *e, const dem_case *cs, const dem_assembly *a, const engine_opts *o);
/* What follows from the time step (the noise energy): called by setup,
 * and after a setup with o->restart once the checkpoint is read. */
void engine_timestep_set(engine *e);
void engine_free(engine *e);

#endif
