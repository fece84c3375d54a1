/* calibrate: the micro parameters of a material from the macroscopic
 * properties it should have (share/doc/calibrate.md). Runs solve and post
 * on small specimens, steered by NLopt, then on the full ones. */
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "calibrate/eval.h"
#include "calibrate/report.h"
#include "calibrate/runner.h"
#include "calibrate/search.h"
#include "calibrate/sensitivity.h"
#include "calibrate/space.h"
#include "calibrate/spec.h"
#include "lib/afile.h"
#include "lib/cli.h"
#include "lib/err.h"
#include "lib/timer.h"

enum { EXIT_INTERRUPTED = 3, EXIT_NOT_MET = 4 };

static _Noreturn void interrupted(const char *out)
{
	fprintf(stderr,
	        "%s: interrupted: the runs done are kept in %s/log.csv; the same command "
	        "continues without repeating them\n",
	        err_program_name(), out);
	exit(EXIT_INTERRUPTED);
}

/* The directory of this program, where pack, solve and post are too. */
static char *own_dir(void)
{
	char buf[PATH_MAX];
	ssize_t n = readlink("/proc/self/exe", buf, sizeof buf - 1);
	if (n <= 0)
		return xstrdup(".");
	buf[n] = '\0';
	char *slash = strrchr(buf, '/');
	if (slash)
		*slash = '\0';
	return xstrdup(buf);
}

/* calibrate-<name of the file without .json> in the current directory. */
static char *default_out(const char *file)
{
	const char *base = strrchr(file, '/');
	base = base ? base + 1 : file;
	size_t n = strlen(base);
	if (n > 5 && strcmp(base + n - 5, ".json") == 0)
		n -= 5;
	char *out = xmalloc(n + 11);
	snprintf(out, n + 11, "calibrate-%.*s", (int)n, base);
	return out;
}

static void check_program(const char *bin, const char *name)
{
	char path[PATH_MAX];
	snprintf(path, sizeof path, "%s/%s", bin, name);
	if (access(path, X_OK) != 0)
		fatal("%s: no such program (calibrate runs pack, solve and post from its own "
		      "directory): give their directory with --bin",
		      path);
}

static void describe(const cal_spec *sp, const space *s)
{
	fprintf(stderr,
	        "calibrate: %s: law %s, %d free keys, %d tests, %d targets, budget %ld runs",
	        sp->name, sp->law, sp->nfree, sp->ntest, sp->ntarget, sp->runs);
	if (sp->wall > 0)
		fprintf(stderr, " or %.0f s", sp->wall);
	fprintf(stderr, "\ncalibrate: search variables:");
	for (int j = 0; j < s->nz; j++) {
		const cal_key *p = &sp->key[s->zkey[j]];
		if (s->kind[j] == Z_RATIO)
			fprintf(stderr, " %s/%s", p->name, sp->key[s->anchor[p->cls]].name);
		else
			fprintf(stderr, " %s", p->name);
	}
	if (!s->nz)
		fprintf(stderr, " none");
	for (int c = CLS_STRESS; c <= CLS_STIFF; c++)
		if (s->anchor[c] >= 0)
			fprintf(stderr, "; %s scale from the runs (%s)",
			        c == CLS_STRESS ? "stress" : "stiffness",
			        sp->key[s->anchor[c]].name);
	fputc('\n', stderr);
}

/* A blind recovery: the targets without a value take what the truth gives
 * on the search specimens. */
static void set_truth(evaluator *e, cal_spec *sp, double *v, int quiet, const char *out)
{
	for (int k = 0; k < sp->nkey; k++)
		v[k] = spec_material_number(sp->truth, sp->key[k].name)->valuedouble;
	outcome o;
	if (eval_points(e, (const double(*)[CAL_MAX_KEYS])v, 1, SPECIMEN_SEARCH, PHASE_TRUTH, &o)) {
		if (runner_stopped())
			interrupted(out);
		fatal(NULL);
	}
	if (!o.ok)
		fatal("%s: the truth fails: %s", sp->source, o.message);
	for (int k = 0; k < sp->ntarget; k++) {
		cal_target *t = &sp->target[k];
		if (!t->from_truth)
			continue;
		t->value = o.q[t->test][t->quantity];
		if (t->value == 0)
			fatal("%s: targets[%d]: the truth gives %s = 0, which no tolerance "
			      "relative to "
			      "it can meet: give a value",
			      sp->source, k, quantities[t->quantity].name);
		if (!quiet)
			fprintf(stderr, "calibrate: the truth gives %s %s = %.6g%s%s\n",
			        sp->test[t->test].name, quantities[t->quantity].name,
			        t->value * quantities[t->quantity].factor,
			        quantities[t->quantity].shown[0] ? " " : "",
			        quantities[t->quantity].shown);
	}
}

int main(int argc, char **argv)
{
	const char *out = NULL, *bin = NULL;
	long jobs = 0, runs = 0;
	int keep = 0, no_png = 0, no_confirm = 0, no_sens = 0, quiet = 0;
	const cli_opt opts[] = {
	    {"out", CLI_STR, &out, "DIR", "",
	     "output directory: material.json, report, log.csv, runs/ (default: "
	     "calibrate-NAME, NAME the file's name without .json)",
	     0, 0},
	    {"jobs", CLI_INT, &jobs, "N", "", "runs side by side (0: one per core)", 0, 1024},
	    {"runs", CLI_INT, &runs, "N", "runs",
	     "budget of search runs, instead of the file's \"budget\".\"runs\" (0: the file's)", 0,
	     1e6},
	    {"bin", CLI_STR, &bin, "DIR", "",
	     "directory of pack, solve and post (default: that of calibrate)", 0, 0},
	    {"keep-runs", CLI_FLAG, &keep, NULL, "",
	     "keep each run's run.h5 (by default only its case, log and summary.json)", 0, 0},
	    {"no-sensitivity", CLI_FLAG, &no_sens, NULL, "",
	     "skip the sensitivities at the optimum (and the report's identifiability)", 0, 0},
	    {"no-confirm", CLI_FLAG, &no_confirm, NULL, "",
	     "skip the confirming runs on the full specimens", 0, 0},
	    {"no-png", CLI_FLAG, &no_png, NULL, "", "no figures (they need gnuplot)", 0, 0},
	    {"quiet", CLI_FLAG, &quiet, NULL, "",
	     "print nothing but warnings, errors and the report", 0, 0},
	};
	static const char summary[] =
	    "Calibrate a material's micro parameters to measured properties: run the\n"
	    "calibration file's tests (solve, then post summary) on small specimens, steered\n"
	    "by NLopt, until the targets (peak stress, Brazilian strength, E, nu, strain at\n"
	    "peak, ...) are met within their tolerances; then measure the sensitivities and\n"
	    "confirm on the full specimens. Writes the calibrated material, a report, the\n"
	    "path of the parameters and figures; every run goes to a log, so the same\n"
	    "command continues an interrupted calibration without repeating runs.\n"
	    "The calibration file (JSON) is described in share/doc/calibrate.md.\n\n"
	    "Exit status: 0 every target met, 1 error, 2 usage, 3 interrupted (run again to\n"
	    "continue), 4 not every target met (the best compromise and its diagnosis are\n"
	    "written).";
	const cli_spec spec = {
	    .usage = "calibrate [options] CALIBRATION.json",
	    .summary = summary,
	    .epilog = "Example:\n  calibrate --out runs/calibrate-concrete "
	              "share/calibration/concrete-recovery.json",
	    .opts = opts,
	    .nopts = (int)(sizeof opts / sizeof opts[0]),
	    .min_pos = 1,
	    .max_pos = 1,
	};
	char *pos[1];
	cli_parse(&spec, argc, argv, pos);
	afile_install_signal_cleanup();
	runner_install_signals();
	double t0 = timer_now();

	cal_spec sp;
	if (spec_load(pos[0], &sp))
		fatal(NULL);
	if (runs)
		sp.runs = runs;
	space s;
	space_init(&s, &sp);
	char shortfall[1024];
	if (search_budget_short(&s, shortfall, sizeof shortfall))
		warn("%s", shortfall);
	char *outdir = out ? xstrdup(out) : default_out(pos[0]);
	char *bindir = bin ? xstrdup(bin) : own_dir();
	check_program(bindir, "pack");
	check_program(bindir, "solve");
	check_program(bindir, "post");
	if (!jobs)
		jobs = sysconf(_SC_NPROCESSORS_ONLN) > 0 ? sysconf(_SC_NPROCESSORS_ONLN) : 1;
	/* Threads waiting at a barrier sleep: runs side by side share the cores. */
	setenv("OMP_WAIT_POLICY", "passive", 0);

	evaluator e;
	if (eval_init(&e, &sp, outdir, bindir, (int)jobs, keep))
		fatal(NULL);
	if (!quiet)
		describe(&sp, &s);
	if (eval_specimens(&e, SPECIMEN_SEARCH)) {
		if (runner_stopped())
			interrupted(outdir);
		fatal(NULL);
	}
	double truth[CAL_MAX_KEYS];
	if (sp.truth)
		set_truth(&e, &sp, truth, quiet, outdir);
	search_result r;
	if (search_run(&e, &s, quiet, &r)) {
		if (runner_stopped())
			interrupted(outdir);
		fatal("%s: %s", pos[0], err_msg());
	}
	const path_point *best = &r.path[r.best];
	double search_wall = timer_now() - t0;
	if (!quiet)
		fprintf(stderr, "calibrate: search %s%s\n", search_status_text[r.status],
		        no_sens ? "" : "; sensitivities at the best point");
	sensitivity sens;
	memset(&sens, 0, sizeof sens);
	if (no_sens)
		snprintf(sens.message, sizeof sens.message, "skipped (--no-sensitivity)");
	else if (sensitivity_run(&e, best->v, &r.best_out, &sens)) {
		if (runner_stopped())
			interrupted(outdir);
		fatal(NULL);
	}
	outcome conf;
	int confirm = 0;
	for (int t = 0; t < sp.ntest; t++)
		confirm |= sp.test[t].has_confirm && !no_confirm;
	if (confirm) {
		if (!quiet)
			fprintf(stderr, "calibrate: confirming runs on the full specimens\n");
		if (eval_specimens(&e, SPECIMEN_CONFIRM) ||
		    eval_points(&e, (const double(*)[CAL_MAX_KEYS])best->v, 1, SPECIMEN_CONFIRM,
		                PHASE_CONFIRM, &conf)) {
			if (runner_stopped())
				interrupted(outdir);
			fatal(NULL);
		}
	}
	report rp = {.sp = &sp,
	             .e = &e,
	             .r = &r,
	             .sens = &sens,
	             .confirm = confirm ? &conf : NULL,
	             .wall = timer_now() - t0,
	             .search_wall = search_wall,
	             .met = best->fit.met,
	             .truth = sp.truth ? truth : NULL};
	report_diagnose(&rp);
	if (report_write(&rp, outdir))
		fatal(NULL);
	if (!no_png && report_plots(&rp, outdir))
		warn("no figures: %s", err_msg());
	int met = rp.met;
	report_free(&rp);
	search_free(&r);
	eval_free(&e);
	spec_free(&sp);
	free(outdir), free(bindir);
	return met ? 0 : EXIT_NOT_MET;
}
