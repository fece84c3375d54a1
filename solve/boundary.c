/* The loading program: a sequence of stages, each combining the building
 * blocks of the lab tests (case.h): platens at a velocity or strain rate,
 * servo-controlled to a stress or force, held, or absent; end layers moved
 * Yade-style; the lateral surface free, under a pressure, or held radially.
 * Reversing a platen velocity unloads; a stage ends on its `until` rule and
 * the run on its `stop` rule or at the end of the last stage.
 *
 * Servo: each moving platen closes at v = g (F_target - F), limited to the
 * stage's rate times the initial height, with g chosen so that a step
 * corrects the fraction `gain` of the error through the stiffness of the
 * touching contacts (g = gain / (Σ K_n Δt)); without contact it approaches
 * at the limit. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lib/err.h"
#include "solve/boundary.h"
#include "solve/engine.h"
#include "solve/measure.h"
#include "solve/par.h"
#include "solve/platens.h"
#include "solve/ranks.h"
#include "solve/surface.h"

static const stage *current(const engine *e) { return &e->cs->stages[e->prog.stage]; }

static int uses_platens(int axial) { return axial != AXIAL_NONE && axial != AXIAL_LAYERS; }

/* Ramp from the stage's starting value to its target. */
static double ramped(const engine *e, double from, double to)
{
	double ramp = current(e)->ramp;
	double f = ramp > 0 ? (e->clock.t - e->prog.stage_t) / ramp : 1;
	return f >= 1 ? to : from + (to - from) * f;
}

/* The end layers: the particles within `thickness` of the specimen's ends,
 * each rank's own flagged by it (ranks.h), from the ends over all ranks. */
static void select_layers(engine *e, double thickness)
{
	particles *P = &e->p;
	size_t p0, p1;
	ranks_own(e, &p0, &p1);
	double lo = INFINITY, hi = -INFINITY;
	double *z = xmalloc((p1 - p0 + 1) * sizeof *z);
	for (size_t i = p0; i < p1; i++) {
		double zi = 0;
		for (int k = 0; k < 3; k++)
			zi += (P->x[3 * i + k] - e->frame.center[k]) * e->frame.axis[k];
		z[i - p0] = zi;
		lo = fmin(lo, zi - P->r[i]);
		hi = fmax(hi, zi + P->r[i]);
	}
	par_min(&lo, 1);
	par_max(&hi, 1);
	for (size_t i = p0; i < p1; i++) {
		P->flag[i] &= (uint8_t) ~(PF_LAYER_BOTTOM | PF_LAYER_TOP);
		if (z[i - p0] - P->r[i] <= lo + thickness)
			P->flag[i] |= PF_LAYER_BOTTOM;
		else if (z[i - p0] + P->r[i] >= hi - thickness)
			P->flag[i] |= PF_LAYER_TOP;
	}
	free(z);
	e->prog.layers_selected = 1;
}

void boundary_begin_stage(engine *e)
{
	const stage *s = current(e);
	int was = e->bc.pl.active;
	e->bc.pl.active = uses_platens(s->axial);
	if (e->bc.pl.active != was)
		e->pairs.rebuild = 1;
	e->prog.stage_step = e->clock.step;
	e->prog.stage_t = e->clock.t;
	e->prog.stage_strain0 = engine_strain(e);
	e->prog.stage_stress0 = engine_stress(e);
	e->prog.stage_pressure0 = e->prog.pressure;
	e->prog.stage_peak = -INFINITY;
	if (s->axial == AXIAL_LAYERS && !e->prog.layers_selected)
		select_layers(e, s->thickness > 0 ? s->thickness : 2 * e->frame.r_mean);
	particles *P = &e->p;
	size_t p0, p1;
	ranks_own(e, &p0, &p1);
	for (size_t i = p0; i < p1; i++)
		P->flag[i] &= (uint8_t)~PF_CONSTRAINED;
	if (s->lateral == LATERAL_CONSTRAINT) {
		surface_update(e);
		for (size_t i = p0; i < p1; i++)
			if (P->surf[i] >= 0)
				P->flag[i] |= PF_CONSTRAINED;
	}
	if (s->lateral != LATERAL_PRESSURE)
		e->prog.pressure = 0;
}

double boundary_closing_speed(const engine *e, const stage *s)
{
	return s->axial == AXIAL_VELOCITY ? s->velocity : s->rate * e->frame.height0;
}

static double closing_speed(const engine *e) { return boundary_closing_speed(e, current(e)); }

void boundary_prepare(engine *e)
{
	const stage *s = current(e);
	loads *ld = &e->bc.loads;
	ld->lateral = s->lateral;
	ld->method = s->method;
	if (s->lateral == LATERAL_PRESSURE)
		e->prog.pressure = ramped(e, e->prog.stage_pressure0, s->pressure);
	ld->pressure = e->prog.pressure;
	ld->layers = s->axial == AXIAL_LAYERS;
	if (ld->layers) {
		double v = closing_speed(e);
		ld->layer_vel[0] = s->top_only ? 0 : 0.5 * v;
		ld->layer_vel[1] = s->top_only ? -v : -0.5 * v;
	} else {
		ld->layer_vel[0] = ld->layer_vel[1] = 0;
	}
}

/* Platen velocities for the next step, then the move. */
void boundary_finish_step(engine *e)
{
	const stage *s = current(e);
	double vel[2] = {0, 0};
	switch (s->axial) {
	case AXIAL_VELOCITY:
	case AXIAL_STRAIN_RATE:
	case AXIAL_LAYERS: {
		double v = closing_speed(e);
		vel[0] = s->top_only ? 0 : 0.5 * v;
		vel[1] = s->top_only ? -v : -0.5 * v;
		break;
	}
	case AXIAL_STRESS:
	case AXIAL_FORCE: {
		double target = s->axial == AXIAL_STRESS ? s->target * e->frame.area0 : s->target;
		target = ramped(e, e->prog.stage_stress0 * e->frame.area0, target);
		double vmax = s->rate * e->frame.height0;
		for (int k = s->top_only ? 1 : 0; k < 2; k++) {
			double err = target - e->bc.pl.load[k];
			double v = e->bc.pl.ksum[k] > 0
			               ? e->cs->servo_gain * err / (e->bc.pl.ksum[k] * e->clock.dt)
			               : (err > 0 ? vmax : -vmax);
			v = v > vmax ? vmax : v < -vmax ? -vmax : v;
			vel[k] = k == 0 ? v : -v;
		}
		break;
	}
	default:
		break;
	}
	platens_move(e, vel);
}

/* value crossed target coming from start */
static int reached(double value, double start, double target)
{
	return start <= target ? value >= target : value <= target;
}

/* The clock's parts of a rule at time t and step s, counted from t0, s0. */
static int time_reached(const stop_rule *r, double t, double t0)
{
	return !isnan(r->time) && t - t0 >= r->time * (1 - 1e-12);
}

static int steps_done(const stop_rule *r, int64_t s, int64_t s0)
{
	return r->steps && s - s0 >= r->steps;
}

/* Checks one rule; the elapsed time and steps are counted from t0, s0. */
static int rule_holds(const engine *e, const stop_rule *r, double strain0, double stress0,
                      double peak, int armed, double t0, int64_t s0, char *why, size_t n)
{
	double strain = engine_strain(e), stress = engine_stress(e);
	if (!isnan(r->strain_axial) && reached(strain, strain0, r->strain_axial))
		return snprintf(why, n, "axial strain reached %g", r->strain_axial), 1;
	if (!isnan(r->stress_axial) && reached(stress, stress0, r->stress_axial))
		return snprintf(why, n, "axial stress reached %g Pa", r->stress_axial), 1;
	if (!isnan(r->stress_drop) && armed && peak > 0 && stress < r->stress_drop * peak)
		return snprintf(why, n, "axial stress fell below %g of the peak %g Pa",
		                r->stress_drop, peak),
		       1;
	if (time_reached(r, e->clock.t, t0))
		return snprintf(why, n, "time %g s reached", r->time), 1;
	if (steps_done(r, e->clock.step, s0))
		return snprintf(why, n, "%ld steps done", r->steps), 1;
	return 0;
}

int boundary_clock_ends_run(const engine *e)
{
	double t = e->clock.t + e->clock.dt;
	int64_t s = e->clock.step + 1;
	const stop_rule *stop = &e->cs->stop, *until = &current(e)->until;
	int last = e->prog.stage + 1 == e->cs->nstages;
	return time_reached(stop, t, 0) || steps_done(stop, s, 0) ||
	       (last && (time_reached(until, t, e->prog.stage_t) ||
	                 steps_done(until, s, e->prog.stage_step)));
}

void boundary_arm_drop(engine *e, double elastic)
{
	double crossing = e->frame.height0 * e->clock.dt_crit / (2 * e->frame.r_mean);
	if (!e->prog.drop_armed && e->clock.t >= crossing && elastic > 0 &&
	    e->energy.kinetic < 0.01 * elastic)
		e->prog.drop_armed = 1;
}

void boundary_track_peak(engine *e)
{
	if (!e->prog.drop_armed)
		return;
	double stress = engine_stress(e);
	e->prog.peak = stress > e->prog.peak ? stress : e->prog.peak;
	e->prog.stage_peak = stress > e->prog.stage_peak ? stress : e->prog.stage_peak;
}

int boundary_check(engine *e, char *why, size_t n)
{
	if (rule_holds(e, &e->cs->stop, 0, 0, e->prog.peak, e->prog.drop_armed, 0, 0, why, n))
		return BOUNDARY_STOP;
	const stage *s = current(e);
	char reason[256];
	if (!rule_holds(e, &s->until, e->prog.stage_strain0, e->prog.stage_stress0,
	                e->prog.stage_peak, e->prog.drop_armed, e->prog.stage_t, e->prog.stage_step,
	                reason, sizeof reason))
		return BOUNDARY_RUNNING;
	if (e->prog.stage + 1 == e->cs->nstages) {
		snprintf(why, n, "end of the loading program (stage %d: %s)", e->prog.stage + 1,
		         reason);
		return BOUNDARY_COMPLETE;
	}
	snprintf(why, n, "stage %d ended: %s", e->prog.stage + 1, reason);
	e->prog.stage++;
	boundary_begin_stage(e);
	return BOUNDARY_NEXT_STAGE;
}
