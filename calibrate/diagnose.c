/* The warnings and the diagnosis of a calibration (calibrate/report.h). */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "calibrate/report.h"
#include "lib/err.h"

static void note(report *rp, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void note(report *rp, const char *fmt, ...)
{
	if (rp->nnotes == REPORT_MAX_NOTES)
		return;
	char buf[1024];
	va_list ap;
	va_start(ap, fmt);
	vsnprintf(buf, sizeof buf, fmt, ap);
	va_end(ap);
	rp->notes[rp->nnotes++] = xstrdup(buf);
}

static const char *target_name(const cal_spec *sp, int i, char *buf, size_t n)
{
	const cal_target *t = &sp->target[i];
	snprintf(buf, n, "%s %s", sp->test[t->test].name, quantities[t->quantity].name);
	return buf;
}

/* Targets that every key moves together while they ask to move apart. */
static void conflicts(report *rp, const fit *f)
{
	const cal_spec *sp = rp->sp;
	const sensitivity *s = rp->sens;
	for (int i = 0; i < sp->ntarget; i++)
		for (int j = i + 1; j < sp->ntarget; j++) {
			int off = fabs(f->err[i]) > sp->target[i].tol ||
			          fabs(f->err[j]) > sp->target[j].tol;
			double c = s->target_cos[i][j];
			int apart = (c > SENS_PARALLEL && f->err[i] * f->err[j] < 0) ||
			            (c < -SENS_PARALLEL && f->err[i] * f->err[j] > 0);
			if (!off || !apart)
				continue;
			char a[128], b[128];
			note(rp,
			     "conflict: %s (%+.2f %%) and %s (%+.2f %%) ask to move %s, but the "
			     "free "
			     "keys move them %s (cosine %.3f of their sensitivities): no choice of "
			     "these keys meets both on this packing",
			     target_name(sp, i, a, sizeof a), 100 * f->err[i],
			     target_name(sp, j, b, sizeof b), 100 * f->err[j],
			     c > 0 ? "apart" : "the same way",
			     c > 0 ? "together" : "against each other", c);
		}
	for (int i = 0; i < sp->ntarget; i++) {
		double norm = 0;
		for (int k = 0; k < sp->nfree; k++)
			norm += s->J[i][k] * s->J[i][k];
		norm = sqrt(norm);
		double off = fabs(f->err[i]) - sp->target[i].tol;
		char a[128];
		if (off <= 0)
			continue;
		if (norm < 1e-3)
			note(rp,
			     "%s does not respond to the free keys (its sensitivities are below "
			     "0.001): free a key that moves it",
			     target_name(sp, i, a, sizeof a));
		/* The relative change of the keys that would meet it, along the
		 * direction that moves it most, as the sensitivities extrapolate. */
		else if (off / norm > 1)
			note(rp,
			     "%s is out of reach of these keys: off by "
			     "%+.2f %%, it moves by at most %.3g of its "
			     "target per relative change of the keys, so "
			     "meeting it would take changing them by some "
			     "%.0f %%; free a key that moves it, or loosen "
			     "or drop it (more runs will not help)",
			     target_name(sp, i, a, sizeof a), 100 * f->err[i], norm,
			     100 * off / norm);
	}
}

static void identifiability(report *rp)
{
	const cal_spec *sp = rp->sp;
	const sensitivity *s = rp->sens;
	for (int k = 0; k < sp->nfree; k++)
		if (!(s->sigma[k] <= SENS_UNIDENTIFIED))
			note(rp,
			     "%s is not identified by these targets: their tolerances and noise "
			     "leave it uncertain by %s",
			     sp->key[k].name,
			     isfinite(s->sigma[k]) ? "more than 25 %"
			                           : "any amount (a direction they "
			                             "do not see)");
		else if (s->sigma[k] > SENS_LOOSE)
			note(rp,
			     "%s is loosely identified: the targets' tolerances and noise leave it "
			     "uncertain by ±%.3g %% (tighter tolerances on the targets it moves, "
			     "or less noise in them from a larger search specimen, would fix it "
			     "better)",
			     sp->key[k].name, 100 * s->sigma[k]);
	for (int k = 0; k < sp->nfree; k++)
		for (int l = k + 1; l < sp->nfree; l++)
			if (fabs(s->key_cos[k][l]) > SENS_PARALLEL)
				note(rp,
				     "%s and %s trade off: they move the targets alike (cosine "
				     "%.3f of "
				     "their sensitivities), so the targets cannot fix both; hold "
				     "one "
				     "fixed, or add a target that separates them",
				     sp->key[k].name, sp->key[l].name, s->key_cos[k][l]);
}

/* Targets whose tolerance is within the noise of the search specimen. */
static void noise(report *rp)
{
	const cal_spec *sp = rp->sp;
	for (int i = 0; i < sp->ntarget; i++)
		if (rp->sens->noise[i] > sp->target[i].tol / 2) {
			char a[128];
			note(
			    rp,
			    "%s varies by about ±%.2g %% between neighbouring points (the noise of "
			    "the search specimen, from the sensitivity runs): its tolerance of "
			    "%.3g %% "
			    "is within it; a larger search specimen, or a looser tolerance, would "
			    "make the match mean more",
			    target_name(sp, i, a, sizeof a), 100 * rp->sens->noise[i],
			    100 * sp->target[i].tol);
		}
}

int report_bound(const cal_key *p, double v)
{
	if (v < p->lo)
		return -2;
	if (v > p->hi)
		return 2;
	double x = p->log ? log(v) : v, lo = p->log ? log(p->lo) : p->lo,
	       hi = p->log ? log(p->hi) : p->hi, tol = 0.01 * (hi - lo);
	return x <= lo + tol ? -1 : x >= hi - tol ? 1 : 0;
}

static void at_bounds(report *rp, const double *v)
{
	const cal_spec *sp = rp->sp;
	for (int k = 0; k < sp->nfree; k++) {
		const cal_key *p = &sp->key[k];
		int b = report_bound(p, v[k]);
		if (b == -1 || b == 1)
			note(rp, "%s ended at its %s bound (%g)%s", p->name,
			     b < 0 ? "lower" : "upper", b < 0 ? p->lo : p->hi,
			     rp->met ? "" : ": the bounds may keep the targets out of reach");
		else if (b)
			note(rp, "%s ended at %g, %s its bounds [%g, %g]", p->name, v[k],
			     b < 0 ? "below" : "above", p->lo, p->hi);
	}
}

void report_diagnose(report *rp)
{
	const cal_spec *sp = rp->sp;
	const search_result *r = rp->r;
	const path_point *best = &r->path[r->best];
	if (!rp->met) {
		if (r->status == SEARCH_BUDGET)
			note(
			    rp,
			    "the budget (%ld runs%s) ran out before every target was met; the best "
			    "compromise is written",
			    sp->runs, sp->wall > 0 ? " or its wall time" : "");
		else
			note(rp,
			     "the search converged without meeting every target (%d rounds): the "
			     "best compromise is written",
			     r->rounds);
		for (int i = 0; i < sp->ntarget; i++)
			if (fabs(best->fit.err[i]) > sp->target[i].tol) {
				char a[128];
				note(rp, "not met: %s off by %+.2f %% (tolerance %.3g %%)",
				     target_name(sp, i, a, sizeof a), 100 * best->fit.err[i],
				     100 * sp->target[i].tol);
			}
	}
	at_bounds(rp, best->v);
	if (rp->sens->ran) {
		if (!rp->met)
			conflicts(rp, &best->fit);
		identifiability(rp);
		noise(rp);
	} else {
		note(rp, "no sensitivities: %s", rp->sens->message);
	}
	if (rp->confirm && rp->confirm->ok) {
		fit f;
		fit_compute(sp, rp->confirm, &f);
		for (int i = 0; i < sp->ntarget; i++) {
			const cal_target *t = &sp->target[i];
			if (!sp->test[t->test].has_confirm || fabs(f.err[i]) <= t->tol)
				continue;
			char a[128];
			note(rp,
			     "on the confirming specimen, %s is off by %+.2f %% (%+.2f %% on the "
			     "search "
			     "specimen): the search specimen does not represent it within its "
			     "tolerance",
			     target_name(sp, i, a, sizeof a), 100 * f.err[i],
			     100 * best->fit.err[i]);
		}
	} else if (rp->confirm) {
		note(rp, "a confirming run failed: %s", rp->confirm->message);
	}
}

void report_free(report *rp)
{
	for (int k = 0; k < rp->nnotes; k++)
		free(rp->notes[k]);
	rp->nnotes = 0;
}
