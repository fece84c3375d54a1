/* Checks of the loading program at setup (plan.h).
 *
 * Refused: end layers thicker than half the specimen; ends that move a
 * hundredth of the mean radius or more per step (an impact, not a
 * laboratory test: blamed on the rate when the strain rate is beyond
 * 100 /s, else on the time step, which the material's density and
 * stiffness set); a stage that no rule can end, so that the run would
 * never end: its ends stand still, or move away from the strain its rules
 * aim at, while only strain rules (or a stress drop, before anything has
 * compressed the specimen) could end it, or a stress servo holds the
 * stress short of the only stress rules.
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

/* Whether the axial strain, starting at strain0 (NaN: not known before the
 * run), reaches target while the ends close at speed v (m/s; negative:
 * they open; NaN: not known before the run, as under a servo): it grows
 * as they close (engine_strain), and a rule holds once it has crossed its
 * target from where it started (boundary.c). */
static int strain_reachable(double target, double strain0, double v)
{
	return isnan(v) || isnan(strain0) || (target - strain0) * v > 0;
}

/* Where a stage that ended on its until rule u left the axial strain (or,
 * with stress set, the stress): that rule's target when it is u's only
 * rule, else not known before the run (NaN). */
static double ended_at(const stop_rule *u, int stress)
{
	int rules = !isnan(u->strain_axial) + !isnan(u->stress_axial) + !isnan(u->stress_drop) +
	            !isnan(u->time) + (u->steps != 0);
	return rules == 1 ? (stress ? u->stress_axial : u->strain_axial) : NAN;
}

/* Whether the axial stress, starting at stress0, reaches target under a
 * stage that servo-controls it to servo (NaN: a stage that does not, or
 * a start not known before the run: assumed to). */
static int stress_reachable(double target, double stress0, double servo)
{
	if (isnan(servo) || isnan(stress0))
		return 1;
	return stress0 <= target ? servo >= target : servo <= target;
}

/* Whether a rule can end a stage (or the run) whose ends close at speed v
 * from the axial strain strain0 (and, under a stress servo, drive the
 * stress from stress0 to servo); a stress drop only after a compressive
 * peak, so when this or an earlier stage compresses (compressed). */
static int can_end(const stop_rule *r, double v, double strain0, double stress0, double servo,
                   int compressed)
{
	return !isnan(r->time) || r->steps ||
	       (!isnan(r->stress_axial) && stress_reachable(r->stress_axial, stress0, servo)) ||
	       (!isnan(r->stress_drop) && compressed) ||
	       (!isnan(r->strain_axial) && strain_reachable(r->strain_axial, strain0, v));
}

/* Steps the rule allows from strain0 at closing speed v (m/s); INFINITY if
 * it gives no bound that can be known before the run (a stress rule). */
static double rule_steps(const engine *e, const stop_rule *r, double strain0, double v)
{
	double dt = e->clock.dt, n = INFINITY;
	if (r->steps)
		n = fmin(n, (double)r->steps);
	if (!isnan(r->time))
		n = fmin(n, r->time / dt);
	if (!isnan(r->strain_axial) && strain_reachable(r->strain_axial, strain0, v))
		n = fmin(n, fabs(r->strain_axial - strain0) * e->frame.height0 / fabs(v) / dt);
	return n;
}

/* Why stage k (s) can never end, when neither its until rule nor the run's
 * stop rule can hold under it, into an error; 0 when one can. strain0 and
 * stress0: where the stage starts, as far as known before the run (NaN:
 * not known). */
static int check_ends(const engine *e, int k, const stage *s, double strain0, double stress0,
                      int compressed)
{
	const stop_rule *stop = &e->cs->stop;
	int servo = s->axial == AXIAL_STRESS;
	double v = servo      ? NAN
	           : moves(s) ? boundary_closing_speed(e, s)
	                      : 0,
	       target = servo ? s->target : NAN;
	if (!moves(s) && !servo)
		return 0;
	/* Under a servo the strain is not known before the run; a strain rule
	 * of the run's stop is taken to be for later stages, if any. */
	double v_stop = servo && k + 1 < e->cs->nstages ? 0 : v;
	if (can_end(&s->until, v, strain0, stress0, target, compressed) ||
	    can_end(stop, v_stop, 0, 0, target, compressed))
		return 0;
	if (servo)
		return err_set("loading stage %d: axial.stress %g Pa: the servo holds the stress "
		               "there, so no stress rule beyond it (until or stop.stress_axial) "
		               "can hold and the run would never end (give a time or steps "
		               "rule, or a target the servo reaches)",
		               k + 1, s->target);
	if (v == 0)
		return err_set("loading stage %d: %s 0: the ends stand still, so its strain "
		               "rule can never hold (give a speed, or a time or steps rule)",
		               k + 1, speed_key(s));
	double aim = !isnan(s->until.strain_axial) ? s->until.strain_axial : stop->strain_axial;
	return err_set("loading stage %d: %s %g: the ends %s, so the axial strain %s from "
	               "%g and never reaches %g (compression is positive: %s); the run "
	               "would never end",
	               k + 1, speed_key(s), s->axial == AXIAL_VELOCITY ? s->velocity : s->rate,
	               v > 0 ? "close" : "open", v > 0 ? "grows" : "falls",
	               !isnan(s->until.strain_axial) ? strain0 : 0.0, aim,
	               v > 0 ? "give a target above it, or a negative speed to pull"
	                     : "give a positive speed to compress, or a target below it");
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
	double total = 0, strain0 = 0, stress0 = 0, vmax = 0, stop_v = 0;
	int longest = 0, compressed = 0;
	double longest_n = -1;
	if (cs->stop.strain_axial == 0)
		return err_set(
		    "stop.strain_axial 0: the run starts at that strain and would end at "
		    "its first step (give the axial strain to stop at, compression "
		    "positive)");
	for (int k = 0; k < cs->nstages; k++) {
		const stage *s = &cs->stages[k];
		if (s->axial == AXIAL_LAYERS && s->thickness >= 0.5 * e->frame.height0)
			return err_set(
			    "loading stage %d: axial.thickness %g m: expected less than half "
			    "the specimen's height (%g m)",
			    k + 1, s->thickness, e->frame.height0);
		if (check_speed(e, k, s))
			return -1;
		compressed |= (s->axial == AXIAL_STRESS && s->target > 0) ||
		              (moves(s) && boundary_closing_speed(e, s) > 0);
		if (check_ends(e, k, s, strain0, stress0, compressed))
			return -1;
		double v = moves(s) ? boundary_closing_speed(e, s) : 0;
		double n = rule_steps(e, &s->until, strain0, v);
		total += n;
		if (n > longest_n)
			longest_n = n, longest = k;
		strain0 = ended_at(&s->until, 0);
		stress0 = ended_at(&s->until, 1);
		if (isnan(stress0) && s->axial == AXIAL_STRESS)
			stress0 = s->target;
		vmax = fmax(vmax, fabs(v));
		stop_v = stop_v != 0 ? stop_v : v;
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
