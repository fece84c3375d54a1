#include <math.h>
#include <nlopt.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "calibrate/runner.h"
#include "calibrate/search.h"
#include "lib/err.h"
#include "lib/timer.h"

const char *const search_status_text[] = {"met", "budget", "converged", "stopped"};

/* Rounds at most (the rounds without a gain of 2 % of the objective after
 * which the search has converged: search.patience). */
enum { MAX_ROUNDS = 12 };

typedef enum { STOP_NONE, STOP_MET, STOP_PREDICTED, STOP_BUDGET, STOP_SIGNAL, STOP_ERROR } stop;

typedef struct {
	evaluator *e;
	const space *s;
	search_result *r;
	int quiet;
	double t0;
	long new_runs, logged_runs; /* the evaluator's at the last point shown */
	double S, K;                /* the scales of the next point: those of the best prediction */
	int round;
	const char *stage;
	nlopt_opt opt;
	stop stop;
	double worst_f; /* largest objective of a point that ran */
	/* The best point of the round by its prediction (by its own fit
	 * without the scaling). */
	int have;
	double best_f, best_z[CAL_MAX_FREE];
} ctx;

static int scaled(const space *s)
{
	return s->anchor[CLS_STRESS] >= 0 || s->anchor[CLS_STIFF] >= 0;
}

static void record(search_result *r, const path_point *p)
{
	if (r->npath == r->cap)
		r->path = xrealloc(r->path,
		                   (size_t)(r->cap = r->cap ? 2 * r->cap : 64) * sizeof *r->path);
	r->path[r->npath++] = *p;
}

/* Point p on the terminal; "from the log" where its runs came from the
 * log and none ran now (a calibration resumed), rather than the seconds
 * so far. */
static void show(ctx *c, const path_point *p)
{
	if (c->quiet)
		return;
	const cal_spec *sp = c->e->sp;
	fprintf(stderr, "calibrate: point %d, round %d %s: ", c->r->npath, p->round + 1, p->stage);
	if (!p->ok) {
		fprintf(stderr, "failed: %s", p->message);
	} else {
		const cal_target *t = &sp->target[p->fit.worst_target];
		fprintf(stderr, "worst %s %s %+.2f %% (%.2f x tol), objective %.3g",
		        sp->test[t->test].name, quantities[t->quantity].name,
		        100 * p->fit.err[p->fit.worst_target], p->fit.worst, p->fit.f);
		if (p->predicted)
			fprintf(stderr, "; scaled: %.2f x tol", p->pred.worst);
	}
	fprintf(stderr, " | runs %ld of %ld, ", c->e->runs[PHASE_SEARCH], sp->runs);
	if (c->e->new_runs == c->new_runs && c->e->logged_runs > c->logged_runs)
		fprintf(stderr, "from the log\n");
	else
		fprintf(stderr, "%.0f s\n", timer_now() - c->t0);
	c->new_runs = c->e->new_runs;
	c->logged_runs = c->e->logged_runs;
}

static double penalty(const ctx *c) { return fmax(100, 4 * c->worst_f); }

/* Evaluate the point z at the round's scales: the objective NLopt sees
 * (the prediction of the best scaled copy, with the scaling). A point
 * whose values would leave a key's bounds is run projected onto them: what
 * is run, logged and predicted is the projection. */
static double eval_z(ctx *c, const double *zin)
{
	const cal_spec *sp = c->e->sp;
	search_result *r = c->r;
	if (c->stop) {
		if (c->opt)
			nlopt_force_stop(c->opt);
		return HUGE_VAL;
	}
	path_point p;
	memset(&p, 0, sizeof p);
	p.round = c->round;
	snprintf(p.stage, sizeof p.stage, "%s", c->stage);
	double z[CAL_MAX_FREE];
	memcpy(z, zin, (size_t)c->s->nz * sizeof *z);
	space_project(c->s, c->S, c->K, z);
	space_values(c->s, c->S, c->K, z, p.v);
	/* NLopt starts each stage where the last ended: that point is known. */
	int again = -1;
	for (int k = 0; k < r->npath && again < 0; k++)
		if (memcmp(r->path[k].v, p.v, sizeof p.v) == 0)
			again = k;
	if (again < 0 && ((c->e->runs[PHASE_SEARCH] + eval_runs_per_point(c->e) > sp->runs) ||
	                  (sp->wall > 0 && timer_now() - c->t0 > sp->wall))) {
		c->stop = STOP_BUDGET;
		if (c->opt)
			nlopt_force_stop(c->opt);
		return HUGE_VAL;
	}
	outcome o;
	if (eval_points(c->e, (const double(*)[CAL_MAX_KEYS])p.v, 1, SPECIMEN_SEARCH, PHASE_SEARCH,
	                &o)) {
		c->stop = runner_stopped() ? STOP_SIGNAL : STOP_ERROR;
		if (c->opt)
			nlopt_force_stop(c->opt);
		return HUGE_VAL;
	}
	p.ok = o.ok;
	double f;
	if (!o.ok) {
		snprintf(p.message, sizeof p.message, "%s", o.message);
		if (r->npath == 0) {
			err_set("the start fails: %s", o.message);
			c->stop = STOP_ERROR;
		}
		f = penalty(c);
	} else {
		fit_compute(sp, &o, &p.fit);
		f = p.fit.f;
		c->worst_f = fmax(c->worst_f, f);
		if (r->best < 0 || f < r->path[r->best].fit.f) {
			r->best = again >= 0 ? again : r->npath;
			r->best_out = o;
		}
		double sigma = 0, kappa = 0;
		if (scaled(c->s)) {
			if (fit_project(c->s, c->S, c->K, z, &o, &sigma, &kappa, &p.pred) == 0) {
				p.predicted = 1;
				f = p.pred.f;
			} else {
				f = penalty(c);
			}
		}
		if (!c->have || f < c->best_f) {
			c->have = 1;
			c->best_f = f;
			memcpy(c->best_z, z, (size_t)c->s->nz * sizeof *z);
			/* The next points are run at these scales: near the targets'
			 * level, where the runs are short and the scaling's
			 * prediction closest; the objective, the prediction at the
			 * best scales, hardly depends on where it was run. */
			c->S *= exp(sigma);
			c->K *= exp(kappa);
		}
		if (p.fit.met)
			c->stop = STOP_MET;
		else if (p.predicted && p.pred.met)
			c->stop = STOP_PREDICTED;
	}
	if (again < 0) {
		record(r, &p);
		show(c, &p);
	}
	if (c->stop && c->opt)
		nlopt_force_stop(c->opt);
	return f;
}

static double nl_objective(unsigned n, const double *x, double *grad, void *data)
{
	(void)n, (void)grad;
	return eval_z(data, x);
}

/* One NLopt stage from z (updated to the stage's best). */
static void run_nlopt(ctx *c, nlopt_algorithm alg, double *z, int maxeval, double shrink)
{
	const space *s = c->s;
	unsigned n = (unsigned)s->nz;
	double dx[CAL_MAX_FREE], xt[CAL_MAX_FREE];
	for (int j = 0; j < s->nz; j++) {
		dx[j] = fmin(fmax(s->step[j] * shrink, 2 * s->xtol[j]), (s->hi[j] - s->lo[j]) / 4);
		xt[j] = s->xtol[j];
		z[j] = fmin(fmax(z[j], s->lo[j]), s->hi[j]);
	}
	nlopt_opt o = nlopt_create(alg, n);
	if (!o)
		fatal("NLopt: cannot create the %s search", nlopt_algorithm_name(alg));
	nlopt_set_lower_bounds(o, s->lo);
	nlopt_set_upper_bounds(o, s->hi);
	nlopt_set_min_objective(o, nl_objective, c);
	nlopt_set_initial_step(o, dx);
	nlopt_set_xtol_abs(o, xt);
	if (maxeval > 0)
		nlopt_set_maxeval(o, maxeval);
	c->opt = o;
	double f;
	nlopt_optimize(o, z, &f);
	c->opt = NULL;
	nlopt_destroy(o);
	if (c->have)
		memcpy(z, c->best_z, n * sizeof *z);
}

long search_global_points(const space *s)
{
	return s->sp->global_points ? s->sp->global_points : 8L * (s->nz + 1);
}

int search_budget_short(const space *s, char *buf, size_t n)
{
	const cal_spec *sp = s->sp;
	if (s->nz == 0 || sp->global == GLOBAL_NEVER)
		return 0;
	/* Each point runs every test once. */
	long points = search_global_points(s), per = sp->ntest, need = (points + 2) * per;
	if (sp->runs >= need)
		return 0;
	char dflt[96] = "";
	if (!sp->global_points)
		snprintf(dflt, sizeof dflt,
		         ", by default 8 x (n + 1) = %ld for n = %d search variable%s", points,
		         s->nz, s->nz == 1 ? "" : "s");
	snprintf(buf, n,
	         "%s: the budget of %ld runs cannot finish the global stage%s: the start and the "
	         "global stage's %ld points (search.global_points%s) take up to %ld runs at %ld "
	         "per point (one per "
	         "test), so the local stage would never start; give budget.runs (or --runs) of at "
	         "least %ld, fewer search.global_points, or \"search\": {\"global\": \"never\"}",
	         sp->source, sp->runs,
	         sp->global == GLOBAL_AUTO ? " when the start is poor (search.global \"auto\")"
	                                   : "",
	         points, dflt, (points + 1) * per, per, need);
	return 1;
}

static const nlopt_algorithm local_algorithms[] = {NLOPT_LN_BOBYQA, NLOPT_LN_COBYLA,
                                                   NLOPT_LN_SBPLX};

int search_run(evaluator *e, const space *s, int quiet, search_result *r)
{
	const cal_spec *sp = e->sp;
	memset(r, 0, sizeof *r);
	r->best = -1;
	ctx c;
	memset(&c, 0, sizeof c);
	c.e = e, c.s = s, c.r = r, c.quiet = quiet, c.t0 = timer_now(), c.new_runs = e->new_runs,
	c.logged_runs = e->logged_runs;
	/* The global methods that draw random numbers draw the same ones. */
	nlopt_srand((unsigned long)sp->seed);
	double v[CAL_MAX_KEYS], z[CAL_MAX_FREE];
	for (int k = 0; k < sp->nkey; k++)
		v[k] = sp->key[k].start;
	space_coords(s, v, &c.S, &c.K, z);
	c.stage = "start";
	eval_z(&c, z);
	double best_before = INFINITY;
	int stalls = 0;
	for (c.round = 0; !c.stop || c.stop == STOP_PREDICTED; c.round++) {
		if (c.round == 0 && s->nz > 0 && !c.stop) {
			const path_point *p0 = &r->path[0];
			double worst = 0;
			const fit *f0 = p0->predicted ? &p0->pred : &p0->fit;
			for (int k = 0; k < sp->ntarget; k++)
				worst = fmax(worst, fabs(f0->err[k]));
			if (sp->global == GLOBAL_ALWAYS ||
			    (sp->global == GLOBAL_AUTO && (!p0->ok || worst > sp->global_above))) {
				c.stage = "global";
				r->global_used = 1;
				run_nlopt(&c, NLOPT_GN_DIRECT_L, z, (int)search_global_points(s),
				          1);
			}
		}
		long left = (sp->runs - e->runs[PHASE_SEARCH]) / eval_runs_per_point(e) + 1;
		if (s->nz > 0 && !c.stop) {
			c.stage = "local";
			run_nlopt(&c, local_algorithms[sp->local], z, (int)left, pow(0.5, c.round));
		}
		if (c.stop && c.stop != STOP_PREDICTED)
			break;
		if (!scaled(s)) {
			r->status = SEARCH_CONVERGED;
			break;
		}
		/* The round's best point, at its best scales, is run. */
		c.stop = STOP_NONE;
		c.have = 0;
		c.stage = "scaled";
		eval_z(&c, z);
		if (c.stop && c.stop != STOP_PREDICTED)
			break;
		double best_now = r->best >= 0 ? r->path[r->best].fit.f : INFINITY;
		stalls = best_now > 0.98 * best_before ? stalls + 1 : 0;
		best_before = fmin(best_before, best_now);
		if (stalls >= sp->patience || c.round + 1 >= MAX_ROUNDS) {
			r->status = SEARCH_CONVERGED;
			break;
		}
	}
	r->rounds = c.round + 1;
	switch (c.stop) {
	case STOP_MET:
		r->status = SEARCH_MET;
		break;
	case STOP_BUDGET:
		r->status = SEARCH_BUDGET;
		break;
	case STOP_SIGNAL:
		r->status = SEARCH_STOPPED;
		return -1;
	case STOP_ERROR:
		return -1;
	default:
		break;
	}
	if (r->best < 0)
		return err_set("no point of the search ran: %s",
		               r->npath ? r->path[r->npath - 1].message : "the budget allows none");
	return 0;
}

void search_free(search_result *r)
{
	free(r->path);
	memset(r, 0, sizeof *r);
}
