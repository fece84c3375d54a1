/* The explicit DEM engine: state, one step, and what the run loop needs.
 *
 * Data layout (DESIGN.md §4): particles as separate arrays in Morton order
 * (orig[] maps back to the assembly's indices); bonds in one flat array of
 * `bond` records, each computed once per step into a per-bond force, then
 * gathered per particle through a CSR index; non-bonded contacts the same
 * way from a Verlet list. Everything a particle needs from another one is
 * read by index from these arrays, so a halo of ghost particles could later
 * provide it under an MPI domain decomposition.
 *
 * Reductions (energies, platen loads, stresses) are summed per fixed block
 * of BLOCK items and the block sums added in block order, so results do not
 * depend on the number of threads, bit for bit. */
#ifndef DEM_ENGINE_H
#define DEM_ENGINE_H

#include <stddef.h>
#include <stdint.h>

#include "lib/assembly.h"
#include "lib/runfile.h"
#include "solve/case.h"
#include "solve/cells.h"
#include "solve/law.h"

enum { BLOCK = 256, BATCH = 32 };

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

/* Pairs (bonds or contacts) with the per-particle gather index. */
typedef struct {
	size_t n, cap;
	bond *rec;
	double *f;    /* [n][6]: force on i (N), then torque per unit radius (N): the
	                 torque on i is r_i times it, on j r_j times it */
	double *k;    /* [n][3] kn, ks, cn of a contact (contacts only) */
	int32_t *off; /* [np + 1] */
	int32_t *ref; /* [2n] pair index * 2 + 1 if the particle is its j */
} pairlist;

typedef struct {
	double t[3];       /* N, shear force history */
	double kn, ks, cn; /* of the sphere–platen contact */
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

typedef struct {
	int ntheta, nz;
	double bin; /* m */
	size_t n, cap;
	int32_t *idx;        /* surface particles */
	double *area;        /* m^2, tributary area of each */
	int32_t *best;       /* [ntheta * nz] outermost particle of each bin */
	double *best_rho;    /* its outer radial distance */
	double lateral_area; /* m^2, current lateral area from the bins */
	double radius;       /* m, mean outer radius */
	double volume;       /* m^3, enclosed by the bins */
	long updated;        /* step of the last update */
} surface;

typedef struct {
	size_t n;
	int32_t *idx;
	double *rho0;   /* m, initial radial distance */
	double radius0; /* m, initial outer radius */
} gauge;

/* One bond failure waiting to be written to /cracks. */
typedef struct {
	size_t n, cap;
	dem_crack *c;
	int32_t *bond; /* the failed bond of each, for sorting */
} crack_buf;

/* Sums over one block (see above). */
typedef struct {
	double e_damage, e_friction, e_viscous;
	double e_elastic; /* measuring steps only */
	double love[9];   /* Σ (x_c - x_p) ⊗ f, measuring steps only */
	double count[5];  /* bonds by state / contacts touching */
} pair_sums;

typedef struct {
	double ke;     /* shadow kinetic energy (v- · v+) */
	double ke_new; /* kinetic energy at t + dt/2 (for diagnoses) */
	double e_damped, e_work;
	double load[2], ksum[2], ntouch[2];
	double layer[2];         /* N, reaction of the end layers */
	double lateral_force;    /* N, Σ |confinement force| */
	double constraint_force; /* N, Σ radial reaction of constrained particles */
	double platen_friction, platen_viscous, platen_elastic;
	double love[9];
	double disp2; /* max squared displacement since the rebuild */
	double bad;   /* lowest particle index with a non-finite state, or n */
} particle_sums;

/* What the loading program sets for the current step (boundary.c). */
typedef struct {
	double pressure;     /* Pa, confinement applied to the surface */
	int method;          /* PRESSURE_* */
	int lateral;         /* LATERAL_* */
	double layer_vel[2]; /* m/s along the axis, end layers (bottom, top) */
	int layers;          /* end layers prescribed */
} loads;

/* The scalars of a measuring step, taken at the step's start time. */
typedef struct {
	double t;
	int64_t step;
	int stage;
	double strain, stress[2]; /* axial; bottom and top platen (Pa) */
	double strain_radial;
	double pressure;      /* Pa, applied or (under a constraint) developed */
	double lateral_force; /* N, applied or reaction */
	double lateral_area;  /* m^2 */
	double volume;        /* m^3, enclosed by the lateral surface */
} measurement;

typedef struct engine engine;

struct engine {
	const dem_case *cs;
	const law *law;
	/* The engine's own copy of the material's parameters (law.copy). */
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

/* Timer slots. */
/* Timer slots: the phases of the run loop, its total, and the setup before
 * it (bonds formed, lists built, run file created), not counted in the
 * loop's rate. */
enum { TM_NEIGHBOUR, TM_BONDS, TM_CONTACTS, TM_INTEGRATE, TM_OUTPUT, TM_TOTAL, TM_SETUP };

/* setup.c: the state at the start of a run (particles sorted, bonds formed,
 * time step chosen). Prints a summary with the time step on stderr unless
 * quiet. */
int engine_setup(engine *e, const dem_case *cs, const dem_assembly *a, int quiet);
void engine_free(engine *e);

/* step.c: one time step; measure != 0 also computes what the history needs
 * (elastic energy, Love–Weber sums, bond counts). */
void engine_step(engine *e, int measure);

/* bonds.c */
int bonds_form(engine *e);
void bonds_init_history(engine *e);
void bonds_forces(engine *e, int measure);
void bonds_collect_cracks(engine *e);
/* Bond b's ends in the assembly's numbering (ends[0] < ends[1]) and, when c
 * is not NULL, its elastic constants. */
void engine_bond_entry(const engine *e, size_t b, int32_t ends[2], law_const *c);
void pairlist_free(pairlist *l);
void pairlist_csr(pairlist *l, size_t np);
void pair_sums_total(const pair_sums *blk, size_t nb, pair_sums *out);

/* contacts.c */
void contacts_rebuild(engine *e);
void contacts_forces(engine *e, int measure);
void contact_constants(const engine *e, double ri, double rj, double mi, double mj, double d0,
                       double k[3]);

/* platens.c */
void platens_init(engine *e);
void platens_rebuild(engine *e);
void platens_move(engine *e, const double vel[2]);
double platens_drift(const engine *e);
void platens_free(platens *pl);

/* surface.c */
void surface_init(engine *e);
void surface_update(engine *e);
void gauge_init(engine *e);
double gauge_strain(const engine *e);

/* boundary.c: the loading program. */
void boundary_begin_stage(engine *e);
void boundary_prepare(engine *e);
void boundary_finish_step(engine *e);
void boundary_track_peak(engine *e);
/* Closing speed of the ends (m/s) in stage s: its velocity, or its rate
 * times the initial height (for servos, their speed limit). */
double boundary_closing_speed(const engine *e, const stage *s);
/* Whether the run goes on; why gets the reason of a change. */
enum { BOUNDARY_RUNNING, BOUNDARY_NEXT_STAGE, BOUNDARY_COMPLETE, BOUNDARY_STOP };
int boundary_check(engine *e, char *why, size_t n);
/* Axial strain (platen gap change / initial gap) and stress (platen load /
 * initial cross-section), compression positive; k = 0 bottom, 1 top. */
double engine_strain(const engine *e);
double engine_stress(const engine *e);
double engine_stress_of(const engine *e, int k);

/* timestep.c: the bound of Eq. 11-15; worst gets the particle setting it. */
double timestep_critical(const engine *e, int with_contacts, size_t *worst);
double pair_omega2(double kn, double ks, double mi, double mj, double ii, double ij, double ai,
                   double aj);

/* Deterministic parallel helpers. */
static inline size_t nblocks(size_t n) { return (n + BLOCK - 1) / BLOCK; }

#endif
