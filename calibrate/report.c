#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "calibrate/report.h"
#include "lib/afile.h"
#include "lib/err.h"
#include "lib/json.h"

static char *join(const char *dir, const char *name)
{
	size_t n = strlen(dir) + strlen(name) + 2;
	char *p = xmalloc(n);
	snprintf(p, n, "%s/%s", dir, name);
	return p;
}

/* A quantity's value in its shown unit: "37.02 MPa", "0.197 %". */
static const char *shown(const quantity *q, double v, char *buf, size_t n)
{
	if (!isfinite(v))
		snprintf(buf, n, "–");
	else
		snprintf(buf, n, "%.4g%s%s", v * q->factor, q->shown[0] ? " " : "", q->shown);
	return buf;
}

static const char *percent(double e, char *buf, size_t n)
{
	if (!isfinite(e))
		snprintf(buf, n, "–");
	else
		snprintf(buf, n, "%+.2f %%", 100 * e);
	return buf;
}

/* Write text to path atomically. */
static int write_text(const char *path, const char *text, size_t len)
{
	char tmp[4200];
	if (afile_begin(path, tmp, sizeof tmp))
		return -1;
	FILE *f = fopen(tmp, "w");
	if (!f) {
		afile_discard(tmp);
		return err_set("%s: cannot create: %s", tmp, strerror(errno));
	}
	int bad = fwrite(text, 1, len, f) != len;
	if (fclose(f) || bad) {
		afile_discard(tmp);
		return err_set("%s: cannot write: %s", tmp, strerror(errno));
	}
	return afile_commit(tmp, path);
}

static const path_point *best_point(const report *rp) { return &rp->r->path[rp->r->best]; }

static void targets_md(FILE *f, const report *rp)
{
	const cal_spec *sp = rp->sp;
	const path_point *b = best_point(rp), *s0 = &rp->r->path[0];
	fit cf;
	if (rp->confirm && rp->confirm->ok)
		fit_compute(sp, rp->confirm, &cf);
	fprintf(f, "## Targets\n\n| test | quantity | target | tolerance | start | calibrated "
	           "(search specimen) | error | confirming specimen | error |\n"
	           "|---|---|---|---|---|---|---|---|---|\n");
	for (int i = 0; i < sp->ntarget; i++) {
		const cal_target *t = &sp->target[i];
		const quantity *q = &quantities[t->quantity];
		char a[64], b1[64], c[64], d[64], e[64], g[64];
		double conf =
		    rp->confirm && rp->confirm->ok ? rp->confirm->q[t->test][t->quantity] : NAN;
		fprintf(
		    f, "| %s | %s | %s | %.3g %% | %s | %s | %s | %s | %s |\n",
		    sp->test[t->test].name, q->name, shown(q, t->value, a, sizeof a), 100 * t->tol,
		    s0->ok ? shown(q, t->value * (1 + s0->fit.err[i]), b1, sizeof b1) : "failed",
		    shown(q, rp->r->best_out.q[t->test][t->quantity], c, sizeof c),
		    percent(b->fit.err[i], d, sizeof d), shown(q, conf, e, sizeof e),
		    percent(isfinite(conf) ? cf.err[i] : NAN, g, sizeof g));
	}
	fputc('\n', f);
}

static void params_md(FILE *f, const report *rp)
{
	const cal_spec *sp = rp->sp;
	const path_point *b = best_point(rp);
	fprintf(f,
	        "## Parameters\n\n| key | start | calibrated | bounds | uncertainty from the "
	        "tolerances and noise |%s\n|---|---|---|---|---|%s\n",
	        rp->truth ? " truth | error |" : "", rp->truth ? "---|---|" : "");
	for (int k = 0; k < sp->nkey; k++) {
		const cal_key *p = &sp->key[k];
		char u[64] = "";
		if (p->free && rp->sens->ran)
			snprintf(u, sizeof u,
			         isfinite(rp->sens->sigma[k]) ? "±%.3g %%" : "not identified",
			         100 * rp->sens->sigma[k]);
		static const char *const where[] = {", below them", ", at the lower bound", "",
		                                    ", at the upper bound", ", above them"};
		if (p->free)
			fprintf(f, "| %s | %.6g | %.6g | [%g, %g]%s%s | %s |", p->name, p->start,
			        b->v[k], p->lo, p->hi, p->log ? " log" : "",
			        where[report_bound(p, b->v[k]) + 2], u);
		else
			fprintf(f,
			        "| %s | %.6g | %.6g | keeps its template ratio to the free %s | |",
			        p->name, rp->r->path[0].v[k], b->v[k],
			        p->cls == CLS_STRESS ? "stresses" : "stiffnesses");
		if (rp->truth)
			fprintf(f, " %.6g | %+.2f %% |", rp->truth[k],
			        100 * (b->v[k] / rp->truth[k] - 1));
		fputc('\n', f);
	}
	fputc('\n', f);
}

static void sensitivities_md(FILE *f, const report *rp)
{
	const cal_spec *sp = rp->sp;
	if (!rp->sens->ran)
		return;
	fprintf(f,
	        "## Sensitivities at the optimum\n\nElasticities: the change of each quantity, "
	        "as a fraction of its target, per relative change of each key (central "
	        "differences, steps of %.3g %%); noise: what the three runs of each key leave "
	        "beyond a straight line, as a fraction of the target.%s\n\n| target |",
	        100 * sp->sens_step,
	        sp->nkey > sp->nfree ? " The keys that keep their ratio to a free one move with it."
	                             : "");
	for (int k = 0; k < sp->nfree; k++)
		fprintf(f, " %s |", sp->key[k].name);
	fprintf(f, " noise |\n|---|");
	for (int k = 0; k <= sp->nfree; k++)
		fprintf(f, "---|");
	fputc('\n', f);
	for (int i = 0; i < sp->ntarget; i++) {
		const cal_target *t = &sp->target[i];
		fprintf(f, "| %s %s |", sp->test[t->test].name, quantities[t->quantity].name);
		for (int k = 0; k < sp->nfree; k++)
			fprintf(f, " %+.3f |", rp->sens->J[i][k]);
		fprintf(f, " ±%.2g %% |\n", 100 * rp->sens->noise[i]);
	}
	fputc('\n', f);
}

static const char *status_line(const report *rp)
{
	if (rp->met)
		return "every target met on the search specimens";
	return rp->r->status == SEARCH_BUDGET ? "not every target met: the budget ran out"
	                                      : "not every target met: the search converged";
}

static char *report_text(const report *rp, const char *dir)
{
	const cal_spec *sp = rp->sp;
	const evaluator *e = rp->e;
	char *text = NULL;
	size_t len = 0;
	FILE *f = open_memstream(&text, &len);
	fprintf(f, "# Calibration: %s\n\n", sp->name);
	fprintf(f, "Material template: %s (law `%s`); calibrated material: %s/material.json.\n\n",
	        sp->material_name, sp->law, dir);
	fprintf(f, "Result: **%s** after %d point%s in %d round%s%s%s.\n\n", status_line(rp),
	        rp->r->npath, rp->r->npath == 1 ? "" : "s", rp->r->rounds,
	        rp->r->rounds == 1 ? "" : "s", rp->r->global_used ? " (a global stage first)" : "",
	        sp->scaling ? ", with the exact scaling" : "");
	fprintf(f, "Runs: %ld for the search, %ld for the sensitivities, %ld to confirm",
	        e->runs[PHASE_SEARCH], e->runs[PHASE_SENSITIVITY], e->runs[PHASE_CONFIRM]);
	if (rp->truth)
		fprintf(f, ", %ld for the truth", e->runs[PHASE_TRUTH]);
	fprintf(f,
	        "; %ld of them run now (%.0f s of solver time), %ld taken from the log. Wall time "
	        "of this invocation %.0f s, %.0f s of it to the end of the search.\n\n",
	        e->new_runs, e->run_wall, e->logged_runs, rp->wall, rp->search_wall);
	targets_md(f, rp);
	params_md(f, rp);
	sensitivities_md(f, rp);
	if (rp->nnotes) {
		fprintf(f, "## Warnings and diagnosis\n\n");
		for (int k = 0; k < rp->nnotes; k++)
			fprintf(f, "* %s\n", rp->notes[k]);
		fputc('\n', f);
	}
	fprintf(f, "Path of the parameters: path.csv (every point evaluated, in order); every run: "
	           "log.csv; figures: convergence.png, targets.png.\n");
	fclose(f);
	return text;
}

static cJSON *numbers(const double *v, int n)
{
	cJSON *a = cJSON_CreateArray();
	for (int k = 0; k < n; k++)
		cJSON_AddItemToArray(a, isfinite(v[k]) ? cJSON_CreateNumber(v[k])
		                                       : cJSON_CreateNull());
	return a;
}

static int report_json(const report *rp, const char *path)
{
	const cal_spec *sp = rp->sp;
	const evaluator *e = rp->e;
	const path_point *b = best_point(rp);
	cJSON *j = cJSON_CreateObject();
	json_str(j, "calibration", sp->name);
	json_str(j, "law", sp->law);
	json_str(j, "material", "material.json");
	json_bool(j, "met", 1, rp->met);
	json_str(j, "status", search_status_text[rp->r->status]);
	json_num(j, "points", rp->r->npath);
	json_num(j, "rounds", rp->r->rounds);
	json_bool(j, "scaling", 1, sp->scaling);
	json_bool(j, "global_stage", 1, rp->r->global_used);
	cJSON *runs = cJSON_AddObjectToObject(j, "runs");
	json_num(runs, "search", (double)e->runs[PHASE_SEARCH]);
	json_num(runs, "sensitivity", (double)e->runs[PHASE_SENSITIVITY]);
	json_num(runs, "confirm", (double)e->runs[PHASE_CONFIRM]);
	json_num(runs, "truth", (double)e->runs[PHASE_TRUTH]);
	json_num(runs, "new", (double)e->new_runs);
	json_num(runs, "from_log", (double)e->logged_runs);
	json_num(runs, "solver_time", e->run_wall);
	json_num(j, "wall_time", rp->wall);
	json_num(j, "search_wall_time", rp->search_wall);
	fit cf;
	int conf = rp->confirm && rp->confirm->ok;
	if (conf)
		fit_compute(sp, rp->confirm, &cf);
	cJSON *ts = cJSON_AddArrayToObject(j, "targets");
	for (int i = 0; i < sp->ntarget; i++) {
		const cal_target *t = &sp->target[i];
		cJSON *o = cJSON_CreateObject();
		json_str(o, "test", sp->test[t->test].name);
		json_str(o, "quantity", quantities[t->quantity].name);
		json_num(o, "value", t->value);
		json_num(o, "tolerance", t->tol);
		json_num(o, "weight", t->weight);
		json_num(o, "achieved", rp->r->best_out.q[t->test][t->quantity]);
		json_num(o, "error", b->fit.err[i]);
		json_bool(o, "met", 1, fabs(b->fit.err[i]) <= t->tol);
		int has = conf && sp->test[t->test].has_confirm;
		json_num(o, "confirm", has ? rp->confirm->q[t->test][t->quantity] : NAN);
		json_num(o, "confirm_error", has ? cf.err[i] : NAN);
		json_num(o, "noise", rp->sens->ran ? rp->sens->noise[i] : NAN);
		cJSON_AddItemToArray(ts, o);
	}
	cJSON *ps = cJSON_AddArrayToObject(j, "parameters");
	for (int k = 0; k < sp->nkey; k++) {
		const cal_key *p = &sp->key[k];
		cJSON *o = cJSON_CreateObject();
		json_str(o, "key", p->name);
		json_bool(o, "free", 1, p->free);
		json_num(o, "start", rp->r->path[0].v[k]);
		json_num(o, "calibrated", b->v[k]);
		if (rp->truth)
			json_num(o, "truth", rp->truth[k]);
		if (p->free) {
			json_num(o, "min", p->lo);
			json_num(o, "max", p->hi);
			static const char *const bound[] = {"below", "lower", "", "upper", "above"};
			json_str(o, "bound", bound[report_bound(p, b->v[k]) + 2]);
			json_num(o, "uncertainty", rp->sens->ran ? rp->sens->sigma[k] : NAN);
			if (rp->sens->ran) {
				double col[CAL_MAX_TARGETS];
				for (int i = 0; i < sp->ntarget; i++)
					col[i] = rp->sens->J[i][k];
				cJSON_AddItemToObject(o, "sensitivities",
				                      numbers(col, sp->ntarget));
			}
		}
		cJSON_AddItemToArray(ps, o);
	}
	cJSON *notes = cJSON_AddArrayToObject(j, "notes");
	for (int k = 0; k < rp->nnotes; k++)
		cJSON_AddItemToArray(notes, cJSON_CreateString(rp->notes[k]));
	cJSON *pth = cJSON_AddArrayToObject(j, "path");
	for (int n = 0; n < rp->r->npath; n++) {
		const path_point *p = &rp->r->path[n];
		cJSON *o = cJSON_CreateObject();
		json_num(o, "round", p->round + 1);
		json_str(o, "stage", p->stage);
		cJSON_AddItemToObject(o, "values", numbers(p->v, sp->nkey));
		json_bool(o, "ok", 1, p->ok);
		json_num(o, "objective", p->ok ? p->fit.f : NAN);
		json_num(o, "worst", p->ok ? p->fit.worst : NAN);
		json_num(o, "scaled_worst", p->predicted ? p->pred.worst : NAN);
		cJSON_AddItemToArray(pth, o);
	}
	return json_write(path, j);
}

static int path_csv(const report *rp, const char *path)
{
	const cal_spec *sp = rp->sp;
	char *text = NULL;
	size_t len = 0;
	FILE *f = open_memstream(&text, &len);
	fprintf(f, "point,round,stage,ok,objective,worst,scaled_worst");
	for (int k = 0; k < sp->nkey; k++)
		fprintf(f, ",%s", sp->key[k].name);
	for (int i = 0; i < sp->ntarget; i++)
		fprintf(f, ",error_%s_%s", sp->test[sp->target[i].test].name,
		        quantities[sp->target[i].quantity].name);
	fputc('\n', f);
	for (int n = 0; n < rp->r->npath; n++) {
		const path_point *p = &rp->r->path[n];
		fprintf(f, "%d,%d,%s,%d", n + 1, p->round + 1, p->stage, p->ok);
		if (p->ok)
			fprintf(f, ",%.10g,%.10g", p->fit.f, p->fit.worst);
		else
			fprintf(f, ",,");
		if (p->predicted)
			fprintf(f, ",%.10g", p->pred.worst);
		else
			fprintf(f, ",");
		for (int k = 0; k < sp->nkey; k++)
			fprintf(f, ",%.17g", p->v[k]);
		for (int i = 0; i < sp->ntarget; i++)
			if (p->ok)
				fprintf(f, ",%.10g", p->fit.err[i]);
			else
				fprintf(f, ",");
		fputc('\n', f);
	}
	fclose(f);
	int rc = write_text(path, text, len);
	free(text);
	return rc;
}

static int material_json(const report *rp, const char *path)
{
	const cal_spec *sp = rp->sp;
	cJSON *m = eval_material(sp, best_point(rp)->v);
	char name[1024];
	snprintf(name, sizeof name, "%s, calibrated (%s)%s", sp->material_name, sp->name,
	         rp->met ? "" : ", targets not all met");
	cJSON_ReplaceItemInObjectCaseSensitive(m, "name", cJSON_CreateString(name));
	return json_write(path, m);
}

int report_write(const report *rp, const char *dir)
{
	char *mat = join(dir, "material.json"), *md = join(dir, "report.md"),
	     *js = join(dir, "report.json"), *pth = join(dir, "path.csv");
	char *text = report_text(rp, dir);
	int rc = material_json(rp, mat) || write_text(md, text, strlen(text)) ||
	         report_json(rp, js) || path_csv(rp, pth);
	if (rc == 0)
		fputs(text, stdout);
	free(text);
	free(mat), free(md), free(js), free(pth);
	return rc ? -1 : 0;
}
