/* The case file: which assembly and material, the loading program (a
 * sequence of stages, each a combination of the boundary-condition building
 * blocks), output intervals, time step, damping and stop criteria. Every key
 * is documented in share/doc/solve.md. */
#ifndef DEM_CASE_H
#define DEM_CASE_H

#include "lib/cfg.h"
#include "solve/laws/material.h"

/* How the specimen's ends are loaded in a stage. */
enum {
	AXIAL_NONE,        /* no platens, no prescribed end layers */
	AXIAL_HOLD,        /* platens fixed where they are */
	AXIAL_VELOCITY,    /* platens close at a velocity (m/s) */
	AXIAL_STRAIN_RATE, /* platens close at a strain rate (1/s) */
	AXIAL_STRESS,      /* platens servo-controlled to an axial stress */
	AXIAL_FORCE,       /* platens servo-controlled to an axial force */
	AXIAL_LAYERS       /* end-layer particles moved at a strain rate (Yade style) */
};
/* How the lateral surface is loaded. */
enum { LATERAL_FREE, LATERAL_PRESSURE, LATERAL_CONSTRAINT };
/* How a confining pressure becomes forces on surface particles. */
enum { PRESSURE_TRIBUTARY, PRESSURE_PAPER };
/* How the global non-viscous damping acts on a particle's force and torque. */
enum {
	DAMPING_VECTOR,    /* the vector, along the velocity (Eq. 39-40) */
	DAMPING_COMPONENTS /* each Cartesian component on its own (Yade's NewtonIntegrator) */
};

/* Conditions that end a stage or the run; unset ones are NaN / 0. */
typedef struct {
	double strain_axial; /* reached (crossed from the starting side) */
	double stress_axial; /* Pa, reached */
	double stress_drop;  /* stress below this fraction of the peak, after the peak */
	double time;         /* s (of the stage, or of the run) */
	long steps;          /* steps (of the stage, or of the run) */
} stop_rule;

typedef struct {
	char name[64];
	int axial;        /* AXIAL_* */
	double velocity;  /* m/s (VELOCITY), closing positive */
	double rate;      /* 1/s (STRAIN_RATE, LAYERS; the servo's speed limit) */
	double target;    /* Pa (STRESS) or N (FORCE), compression positive */
	double ramp;      /* s, time to reach target and pressure (0: at once) */
	int top_only;     /* only the top platen / layer moves */
	double thickness; /* m, end layers (LAYERS); 0: one mean diameter */
	int lateral;      /* LATERAL_* */
	double pressure;  /* Pa (PRESSURE) */
	int method;       /* PRESSURE_* */
	stop_rule until;
} stage;

typedef struct {
	char *source;        /* the case file's name (for messages) */
	char *material_file; /* the material file read, NULL if inline */
	char *assembly;      /* path of the assembly file */
	material mat;
	char *config;                 /* the whole case with the material resolved (JSON) */
	char *test;                   /* label, e.g. "ucs" */
	int threads;                  /* 0: OpenMP's default */
	double axis[3];               /* loading axis; zero: the assembly geometry's axis */
	double dt;                    /* s, fixed time step; 0: from the critical estimate */
	double safety;                /* fraction of the critical time step */
	double alpha_t, alpha_r;      /* global non-viscous damping (Eq. 39-40) */
	int damping_form;             /* DAMPING_* */
	double skin;                  /* m, Verlet skin; 0: a quarter of the mean radius */
	double servo_gain;            /* fraction of the force error corrected per step */
	long surface_every;           /* steps between updates of the lateral surface */
	double surface_bin;           /* m, surface bin size; 0: the mean diameter */
	long history_every;           /* steps */
	long snapshot_every;          /* steps; 0: none */
	double snapshot_every_strain; /* 0: none */
	double *snapshot_strains;
	size_t nsnapshot_strains;
	long checkpoint_every;  /* steps; 0: none */
	double checkpoint_wall; /* s of wall time; 0: none */
	stop_rule stop;
	stage *stages;
	int nstages;
} dem_case;

/* s of wall time from the checkpoint done-th (0: the run's start) to the
 * next one: a tenth of checkpoint_wall, at most a minute, doubling after
 * each until checkpoint_wall, so that a run killed early has a recovery
 * copy too; 0 without checkpoints by wall time. */
double case_checkpoint_interval(const dem_case *c, int done);

/* Load a case file; assembly (if not NULL) replaces its "assembly" key. */
int case_load(const char *path, const char *assembly, dem_case *c);
/* Parse a case from the JSON text stored in a run file's provenance (the
 * material is inline, the assembly is the one embedded in the run file). */
int case_parse_text(const char *text, const char *source, dem_case *c);
void case_free(dem_case *c);

#endif
