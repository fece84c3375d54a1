/* The loading program (boundary.c): stages, their loads, and the rules
 * that end them. */
#ifndef DEM_BOUNDARY_H
#define DEM_BOUNDARY_H

#include <stddef.h>

#include "solve/case.h"

typedef struct engine engine;

/* What the loading program sets for the current step. */
typedef struct {
	double pressure;     /* Pa, confinement applied to the surface */
	int method;          /* PRESSURE_* */
	int lateral;         /* LATERAL_* */
	double layer_vel[2]; /* m/s along the axis, end layers (bottom, top) */
	int layers;          /* end layers prescribed */
} loads;

void boundary_begin_stage(engine *e);
/* The loads of the coming step. */
void boundary_prepare(engine *e);
/* Platen velocities for the next step, then the move. */
void boundary_finish_step(engine *e);
/* The stress-drop rule arms once the loading is quasi-static, the kinetic
 * energy below 1 % of the elastic energy (of the last measuring step), and
 * no sooner than the loading could have crossed the specimen: its height
 * at the speed 2 r_mean / dt_crit, which bounds the speed of a wave through
 * the bonds. Before that the kinetic energy lags behind the elastic energy
 * only because nothing has had time to move. */
void boundary_arm_drop(engine *e, double elastic);
/* The peaks the stress-drop rules compare with: the largest axial stress
 * since the rule armed, so a spike at the start of loading is no peak. */
void boundary_track_peak(engine *e);
/* Whether the step about to run ends the run by a time or step count. */
int boundary_clock_ends_run(const engine *e);
/* Closing speed of the ends (m/s) in stage s: its velocity, or its rate
 * times the initial height (for servos, their speed limit). */
double boundary_closing_speed(const engine *e, const stage *s);
/* Whether the run goes on; why gets the reason of a change. */
enum { BOUNDARY_RUNNING, BOUNDARY_NEXT_STAGE, BOUNDARY_COMPLETE, BOUNDARY_STOP };
int boundary_check(engine *e, char *why, size_t n);

#endif
