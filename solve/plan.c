/* Checks of the loading program at setup (plan.h).
 *
 * Refused: end layers thicker than half the specimen; ends that move a
 * hundredth of the mean radius or more per step (an impact, not a
 * laboratory test: blamed on the rate when the strain rate is beyond
 * 100 /s, else on the time step, which the material's density and
 * stiffness set); a stage whose ends stand still while only a strain rule
 * could end it (the run would never end).
 * Announced: a program of more than 1e8 steps, estimated from the stages'
 * step counts, times and strain targets at their rates; a Verlet skin that
 * the ends cross in fewer than ten steps (a neighbour rebuild every few
 * steps). */
#include <math.h>
#include <stdio.h>

#include "lib/err.h"
#include "solve/boundary.h"
#include "solve/engine.h"
#include "solve/plan.h"

enum { MANY_STEPS = 100000000 };

static int moves(const stage *s)
{
	return s->axial == AXIAL_VELOCITY || s->axial == AXIAL_STRAIN_RATE ||
	       s->axial == AXIAL_LAYERS;
}

static const char *speed_key(const stage *s)
{
	return s->axial == AXIAL_VELOCITY ? "axial.velocity" : "axial.rate";
}

/* Whether a rule can end a stage (or the run) whose ends move at speed v. */
static int can_end(const stop_rule *r, double v)
{
	return !isnan(r->time) || r->steps || !isnan(r->stress_axial) || !isnan(r->stress_drop) ||
	       (!isnan(r->strain_axial) && v > 0);
}

/* Steps the rule allows from strain0 at speed v (m/s); INFINITY if it gives
 * no bound that can be known before the run (a stress rule). */
static double rule_steps(const engine *e, const stop_rule *r, double strain0, double v)
{
	double dt = e->clock.dt, n = INFINITY;
	if (r->steps)
		n = fmin(n, (double)r->steps);
	if (!isnan(r->time))
		n = fmin(n, r->time / dt);
	if (!isnan(r->strain_axial) && v > 0)
		n = fmin(n, fabs(r->strain_axial - strain0) * e->frame.height0 / v / dt);
	return n;
}

static int check_speed(const engine *e, int k, const stage *s)
{
	double v = fabs(boundary_closing_speed(e, s)), dt = e->clock.dt;
	if (s->axial == AXIAL_NONE || s->axial == AXIAL_HOLD || !(v * dt >= 0.01 * e->frame.r_mean))
		return 0;
	char cause[300];
	if (v / e->frame.height0 > 100)
		snprintf(cause, sizeof cause, "lower its %s", speed_key(s));
	else
		snprintf(cause, sizeof cause,
		         "the time step %g s is too long: it comes from the material's density "
		         "(%g kg/m^3) and stiffness",
		         dt, e->cs->mat.density);
	return err_set("loading stage %d: the ends would move %g m per time step (%g m/s), "
	               "more than a hundredth of the mean sphere radius (%g m): expected a "
	               "quasi-static loading (%s)",
	               k + 1, v * dt, v, e->frame.r_mean, cause);
}

int plan_check(const engine *e, int quiet)
{
	const dem_case *cs = e->cs;
	double total = 0, strain0 = 0, vmax = 0, stop_v = 0;
	int longest = 0;
	double longest_n = -1;
	for (int k = 0; k < cs->nstages; k++) {
		const stage *s = &cs->stages[k];
		if (s->axial == AXIAL_LAYERS && s->thickness >= 0.5 * e->frame.height0)
			return err_set(
			    "loading stage %d: axial.thickness %g m: expected less than half "
			    "the specimen's height (%g m)",
			    k + 1, s->thickness, e->frame.height0);
		if (check_speed(e, k, s))
			return -1;
		double v = moves(s) ? fabs(boundary_closing_speed(e, s)) : 0;
		if (moves(s) && v == 0 && !can_end(&s->until, v) && !can_end(&cs->stop, v))
			return err_set(
			    "loading stage %d: %s 0: the ends stand still, so its "
			    "strain rule can never hold (give a speed, or a time or steps "
			    "rule)",
			    k + 1, speed_key(s));
		double n = rule_steps(e, &s->until, strain0, v);
		total += n;
		if (n > longest_n)
			longest_n = n, longest = k;
		if (!isnan(s->until.strain_axial))
			strain0 = s->until.strain_axial;
		vmax = fmax(vmax, v);
		stop_v = stop_v > 0 ? stop_v : v;
	}
	total = fmin(total, rule_steps(e, &cs->stop, 0, stop_v));
	if (quiet)
		return 0;
	if (isfinite(total) && total > MANY_STEPS)
		fprintf(stderr,
		        "%s: warning: the loading program needs about %.3g steps of %g s (stage %d "
		        "the longest: check its until rule and %s, or the stop rule)\n",
		        err_program_name(), total, e->clock.dt, longest + 1,
		        speed_key(&cs->stages[longest]));
	double drift = vmax * e->clock.dt;
	if (drift > 0 && e->pairs.skin < 10 * drift)
		fprintf(stderr,
		        "%s: warning: neighbours.skin %g m: the ends move %g m per step, so the "
		        "neighbour lists are rebuilt every few steps (a skin of at least %g m "
		        "avoids it; the default is a quarter of the mean radius)\n",
		        err_program_name(), e->pairs.skin, drift, 10 * drift);
	return 0;
}
