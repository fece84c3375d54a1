/* The figures of a calibration (calibrate/report.h), drawn by gnuplot from
 * share/gnuplot/calibrate_*.gp through post's plotting (post/plot.h). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "calibrate/report.h"
#include "lib/err.h"
#include "post/plot.h"

static char *join(const char *dir, const char *name)
{
	size_t n = strlen(dir) + strlen(name) + 2;
	char *p = xmalloc(n);
	snprintf(p, n, "%s/%s", dir, name);
	return p;
}

static int convergence(const report *rp, const char *png)
{
	const search_result *r = rp->r;
	plot_data d;
	plot_begin(&d);
	fputs("$path << EOD\n", d.f);
	double best_f = INFINITY, best_worst = NAN;
	for (int n = 0; n < r->npath; n++) {
		const path_point *p = &r->path[n];
		if (p->ok && p->fit.f < best_f)
			best_f = p->fit.f, best_worst = p->fit.worst;
		fprintf(d.f, "%d ", n + 1);
		plot_num(d.f, p->ok ? p->fit.worst : NAN);
		fputc(' ', d.f);
		plot_num(d.f, p->predicted ? p->pred.worst : NAN);
		fputc(' ', d.f);
		plot_num(d.f, best_worst);
		fprintf(d.f, " %d\n", p->round + 1);
	}
	fputs("EOD\ntitle_text = ", d.f);
	plot_quote(d.f, rp->sp->name);
	fputc('\n', d.f);
	return plot_draw(&d, "calibrate_convergence", png, 900, 560);
}

static int targets(const report *rp, const char *png)
{
	const cal_spec *sp = rp->sp;
	const search_result *r = rp->r;
	fit cf;
	int conf = rp->confirm && rp->confirm->ok;
	if (conf)
		fit_compute(sp, rp->confirm, &cf);
	plot_data d;
	plot_begin(&d);
	fputs("$targets << EOD\n", d.f);
	for (int i = 0; i < sp->ntarget; i++) {
		const cal_target *t = &sp->target[i];
		char label[160];
		snprintf(label, sizeof label, "%s\\n%s", sp->test[t->test].name,
		         quantities[t->quantity].name);
		fprintf(d.f, "%d \"%s\" ", i, label);
		plot_num(d.f, r->path[0].ok ? 100 * r->path[0].fit.err[i] : NAN);
		fputc(' ', d.f);
		plot_num(d.f, 100 * r->path[r->best].fit.err[i]);
		fputc(' ', d.f);
		plot_num(d.f, conf && sp->test[t->test].has_confirm ? 100 * cf.err[i] : NAN);
		fprintf(d.f, " %g\n", 100 * t->tol);
	}
	fprintf(d.f, "EOD\nntargets = %d\nhas_confirm = %d\ntitle_text = ", sp->ntarget, conf);
	plot_quote(d.f, sp->name);
	fputc('\n', d.f);
	return plot_draw(&d, "calibrate_targets", png, 900, 560);
}

int report_plots(const report *rp, const char *dir)
{
	char *a = join(dir, "convergence.png"), *b = join(dir, "targets.png");
	int rc = convergence(rp, a) || targets(rp, b);
	free(a), free(b);
	return rc ? -1 : 0;
}
