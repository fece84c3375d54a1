/* The run loop: steps, the history table, snapshots, checkpoints, stop
 * rules, diagnoses of a failing simulation, interruption and the run
 * report. Everything the loop does besides engine_step is timed as output.
 *
 * On several ranks (ranks.h) every rank runs the loop and takes the same
 * decisions from the same global state; rank 0 alone writes the run file
 * (the others have no writer) after the pairs' histories are gathered, and
 * the decisions a clock or a signal makes (a budget, an interruption, a
 * checkpoint due by wall time) are agreed on after each step. */
#include <inttypes.h>
#include <math.h>
#include <signal.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "lib/afile.h"
#include "lib/err.h"
#include "lib/h5.h"
#include "lib/path.h"
#include "lib/progress.h"
#include "lib/timer.h"
#include "solve/boundary.h"
#include "solve/case.h"
#include "solve/checkpoint.h"
#include "solve/diagnose.h"
#include "solve/engine.h"
#include "solve/history.h"
#include "solve/measure.h"
#include "solve/output.h"
#include "solve/par.h"
#include "solve/ranks.h"
#include "solve/report.h"
#include "solve/run.h"
#include "solve/step.h"
#include "solve/timers.h"

static volatile sig_atomic_t interrupted;

static void on_interrupt(int sig) { interrupted = sig; }

typedef struct {
	engine *e;
	run_writer *w;
	const run_opts *o;
	double wall0, last_checkpoint, last_row_wall, last_flush;
	int checkpoints; /* done since the start, for case_checkpoint_interval */
	int64_t last_row_step, step0, last_snapshot_step;
	progress pg;
	/* the recent pace: strain and stress per step since the sample */
	double pace[2], pace_wall, pace_strain, pace_stress;
	int64_t pace_step;
	int how, code;    /* END_*, RUN_* once the run ends */
	char ending[600]; /* the status of a stop rule that held after a step that
	                     wrote no history row: the run ends after one more */
	char status[1100];
} loop_state;

/* Flush the run file at most every few seconds, so that a full disk is
 * noticed soon after, not at the end of the run; a flush costs tens of ms,
 * too much after every snapshot of a short run. On rank 0's clock (every
 * rank flushes together). */
static int flush_now_and_then(loop_state *L)
{
	enum { FLUSH_EVERY = 5 /* s */ };
	double now = timer_now();
	int due = par_rank() == 0 && now - L->last_flush >= FLUSH_EVERY;
	par_max_int(&due, 1);
	if (!due)
		return 0;
	L->last_flush = now;
	return run_flush(L->w);
}

/* The crack log's rows so far. */
static int write_cracks(loop_state *L) { return output_cracks(L->e, L->w); }

static int snapshot(loop_state *L)
{
	engine *e = L->e;
	if (L->last_snapshot_step == e->clock.step)
		return 0;
	L->last_snapshot_step = e->clock.step;
	e->out.last_snapshot_strain = engine_strain(e);
	return output_snapshot(e, L->w) || flush_now_and_then(L);
}

static int snapshot_due(loop_state *L)
{
	engine *e = L->e;
	const dem_case *cs = e->cs;
	double strain = engine_strain(e);
	if (cs->snapshot_every && e->clock.step % cs->snapshot_every == 0)
		return 1;
	if (cs->snapshot_every_strain > 0 &&
	    fabs(strain - e->out.last_snapshot_strain) >= cs->snapshot_every_strain)
		return 1;
	if (e->out.snapshot_strain_next < cs->nsnapshot_strains) {
		double target = cs->snapshot_strains[e->out.snapshot_strain_next];
		double from = e->out.last_snapshot_strain;
		if (from <= target ? strain >= target : strain <= target) {
			e->out.snapshot_strain_next++;
			return 1;
		}
	}
	return 0;
}

static int checkpoint(loop_state *L)
{
	engine *e = L->e;
	L->last_checkpoint = timer_now();
	L->checkpoints++;
	return write_cracks(L) || run_flush(L->w) || checkpoint_write(e, run_hid(L->w)) ? -1 : 0;
}

/* The crack rows not yet written that one rank may hold (about 400 kB);
 * fewer with DEM_TEST_CRACK_ROWS=N in the environment, so that a test's
 * cracks are written in many rounds (tests/solve/ranks.sh). */
static size_t crack_rows_held(void)
{
	static size_t rows;
	if (!rows) {
		const char *s = getenv("DEM_TEST_CRACK_ROWS");
		rows = s && atoll(s) > 0 ? (size_t)atoll(s) : 4096;
	}
	return rows;
}

/* A checkpoint and the recovery copy of the run file with it. A check of
 * that copy (tests/solve/ranks_failures.sh): with DEM_TEST_KILL=S in the
 * environment, every process kills itself (SIGKILL) once it has saved the
 * copy of a checkpoint at step S or later, as a lost node ends a run, so
 * that the copy of a given step can be compared with another run's. */
static int recovery_point(loop_state *L)
{
	if (checkpoint(L) || run_save_recovery(L->w))
		return -1;
	const char *s = getenv("DEM_TEST_KILL");
	if (s && *s && L->e->clock.step >= atoll(s))
		raise(SIGKILL);
	return 0;
}

/* Whether a checkpoint is due by the step count (agreed) or by rank 0's
 * wall clock (agreed after the step, with the signals). */
static int checkpoint_due_by_step(const loop_state *L)
{
	const dem_case *cs = L->e->cs;
	return cs->checkpoint_every && L->e->clock.step % cs->checkpoint_every == 0;
}

static int checkpoint_due_by_wall(const loop_state *L)
{
	const dem_case *cs = L->e->cs;
	return cs->checkpoint_wall > 0 &&
	       timer_now() - L->last_checkpoint >= case_checkpoint_interval(cs, L->checkpoints);
}

static int history(loop_state *L)
{
	engine *e = L->e;
	double now = timer_now();
	double rate = now > L->last_row_wall && e->clock.step > L->last_row_step
	                  ? (double)(e->clock.step - L->last_row_step) / (now - L->last_row_wall)
	                  : 0;
	L->last_row_wall = now;
	L->last_row_step = e->clock.step;
	double row[64];
	history_row(e, rate, row);
	e->out.history_rows++;
	double elastic = engine_elastic(e);
	if (e->sums.meas.step == 0)
		e->energy.initial = e->energy.kinetic + elastic;
	boundary_arm_drop(e, elastic);
	return run_history(L->w, row);
}

/* The steps one rule leaves before it ends the run (its clock counted from
 * t0, s0), at the recent pace of the strain and the stress per step; after
 * the peak, a stress-drop rule ends it once the stress has fallen to its
 * fraction of the peak. INFINITY where the rule gives no estimate. */
static double rule_left(const engine *e, const stop_rule *r, double t0, int64_t s0, double peak,
                        const double pace[2])
{
	double left = INFINITY, strain = engine_strain(e), stress = engine_stress(e);
	if (r->steps)
		left = fmin(left, (double)(r->steps - (e->clock.step - s0)));
	if (!isnan(r->time))
		left = fmin(left, (r->time - (e->clock.t - t0)) / e->clock.dt);
	if (!isnan(r->strain_axial) && (r->strain_axial - strain) * pace[0] > 0)
		left = fmin(left, (r->strain_axial - strain) / pace[0]);
	if (!isnan(r->stress_drop) && e->prog.drop_armed && peak > 0 && stress < peak &&
	    pace[1] < 0)
		left = fmin(left, (stress - r->stress_drop * peak) / -pace[1]);
	return left;
}

static void show_progress(loop_state *L)
{
	engine *e = L->e;
	const dem_case *cs = e->cs;
	double now = timer_now();
	if (now - L->pace_wall >= 1 && e->clock.step > L->pace_step) {
		double steps = (double)(e->clock.step - L->pace_step);
		L->pace[0] = (engine_strain(e) - L->pace_strain) / steps;
		L->pace[1] = (engine_stress(e) - L->pace_stress) / steps;
		L->pace_wall = now;
		L->pace_step = e->clock.step;
		L->pace_strain = engine_strain(e);
		L->pace_stress = engine_stress(e);
	}
	double left = rule_left(e, &cs->stop, 0, 0, e->prog.peak, L->pace);
	if (e->prog.stage + 1 == cs->nstages)
		left = fmin(left, rule_left(e, &cs->stages[e->prog.stage].until, e->prog.stage_t,
		                            e->prog.stage_step, e->prog.stage_peak, L->pace));
	double done = (double)(e->clock.step - L->step0);
	L->pg.total = isfinite(left) ? done + fmax(left, 0) : 0;
	/* Every bond failure so far is a crack, written or waiting (the same
	 * count on every rank). */
	size_t broken = e->out.crack_rows + e->out.cracks.all;
	char detail[200];
	snprintf(
	    detail, sizeof detail, "stage %d  t %.4g s  strain %.4g%%  stress %.4g MPa  broken %zu",
	    e->prog.stage + 1, e->clock.t, 100 * engine_strain(e), 1e-6 * engine_stress(e), broken);
	progress_update(&L->pg, done, detail);
}

/* How a run ends: L->how (END_*), L->code (RUN_*) and L->status. */
enum { END_NONE, END_FAILED, END_INTERRUPTED, END_FINISHED };

static int end(loop_state *L, int how, int code, const char *status)
{
	L->how = how;
	L->code = code;
	snprintf(L->status, sizeof L->status, "%s", status);
	return how;
}

/* Finish the file with the run's status. A finished run also gets a last
 * snapshot; an interrupted one only its checkpoint. */
static void finish(loop_state *L)
{
	engine *e = L->e;
	phase_start(&e->tm, TM_OUTPUT);
	int rc = 0;
	if (L->how == END_FINISHED)
		rc = snapshot(L);
	if (L->how != END_FAILED)
		rc = rc || checkpoint(L);
	rc = rc || write_cracks(L);
	progress_end(&L->pg);
	if (rc) {
		run_abort(L->w);
		fatal(NULL);
	}
	if (run_finish(L->w, L->status))
		fatal(NULL);
	phase_stop(&e->tm, TM_OUTPUT);
}

/* A line on stderr about the run's course, after the progress line. */
static void say(loop_state *L, const char *fmt, ...)
{
	if (L->o->quiet)
		return;
	progress_end(&L->pg);
	va_list ap;
	va_start(ap, fmt);
	fprintf(stderr, "%s: step %" PRId64 ": ", err_program_name(), L->e->clock.step);
	vfprintf(stderr, fmt, ap);
	fputc('\n', stderr);
	va_end(ap);
}

/* Everything the loop does after a step: the peak, the history row, the
 * diagnoses, the stop rules, snapshots, checkpoints and the crack log.
 * Returns END_NONE to go on, else how the run ends (see end()). */
static int after_step(loop_state *L, int measure, int64_t rebuilds)
{
	engine *e = L->e;
	const run_opts *o = L->o;
	char why[512], diag[1024];
	boundary_track_peak(e);
	if (e->sums.particles.bad < (double)e->p.n) {
		diagnose_nan(e, (size_t)e->sums.particles.bad, diag, sizeof diag);
		if (measure)
			history(L);
		return end(L, END_FAILED, RUN_FAILED, diag);
	}
	if (measure && history(L))
		fatal(NULL);
	/* Before any stop rule: a runaway can look like a stress drop. */
	if (diagnose_speed(e, diag, sizeof diag) || diagnose_runaway(e, diag, sizeof diag) ||
	    (e->pairs.rebuilds != rebuilds && diagnose_timestep(e, diag, sizeof diag)))
		return end(L, END_FAILED, RUN_FAILED, diag);
	if (L->ending[0])
		return end(L, END_FINISHED, RUN_OK, L->ending);
	int stop = boundary_check(e, why, sizeof why);
	if (stop != BOUNDARY_RUNNING)
		say(L, "%s", why);
	if (stop == BOUNDARY_COMPLETE || stop == BOUNDARY_STOP) {
		char status[sizeof L->ending] = "complete";
		if (stop == BOUNDARY_STOP)
			snprintf(status, sizeof status, "stopped: %s", why);
		if (measure)
			return end(L, END_FINISHED, RUN_OK, status);
		/* So that the history ends at the stop: one more step, measured. */
		snprintf(L->ending, sizeof L->ending, "%s", status);
		return END_NONE;
	}
	/* What a signal or rank 0's clock decided before the step, agreed by
	 * the ranks in the step's reduction (loop). */
	const double *agreed = e->sums.agree;
	if (snapshot_due(L) && snapshot(L))
		fatal(NULL);
	if ((checkpoint_due_by_step(L) || agreed[2]) && recovery_point(L))
		fatal(NULL);
	if (e->out.cracks.most >= crack_rows_held() && (write_cracks(L) || flush_now_and_then(L)))
		fatal(NULL);
	int budget = (o->max_steps && e->clock.step - L->step0 >= o->max_steps) || agreed[1];
	if (agreed[0] || budget) {
		if (!o->quiet) {
			progress_end(&L->pg);
			/* DEM_CONTINUE: the command that continues the run
			 * where solve is run for another (the make workflows,
			 * which then run post too) */
			const char *how = getenv("DEM_CONTINUE");
			char *word = path_shell_word(o->output), launch[64] = "";
			if (par_size() > 1) /* any rank count continues it */
				snprintf(launch, sizeof launch, "mpirun -np %d ", par_size());
			fprintf(stderr, "%s: interrupted at step %" PRId64 " (%s); continue with: ",
			        err_program_name(), e->clock.step,
			        agreed[0] ? strsignal((int)agreed[0]) : "budget");
			if (how && *how)
				fprintf(stderr, "%s\n", how);
			else
				fprintf(stderr, "%ssolve --restart %s\n", launch, word);
			free(word);
		}
		return end(L, END_INTERRUPTED, RUN_INTERRUPTED, "interrupted");
	}
	show_progress(L);
	return END_NONE;
}

/* A check of an interrupted run (tests/workflows/make.sh, mpirun.sh):
 * with DEM_TEST_INTERRUPT=S in the environment, rank 0 sends SIGINT before
 * step S to the process group of its session's leader, as Ctrl-C in a
 * terminal sends it to the foreground group (run it in a session of its
 * own: setsid): make, its shells and solve, or mpirun, which passes it on
 * to the ranks in groups of their own. */
static void test_interrupt(const engine *e)
{
	const char *s = getenv("DEM_TEST_INTERRUPT");
	if (s && *s && e->clock.step == atoll(s) && par_rank() == 0)
		kill(-getsid(0), SIGINT);
}

/* Steps until the run ends; everything besides engine_step is timed as
 * output (the phase between steps). */
static void loop(loop_state *L)
{
	engine *e = L->e;
	phase_start(&e->tm, TM_OUTPUT);
	e->tm.between = 1 + TM_OUTPUT;
	for (int how = END_NONE; how == END_NONE;) {
		int measure = L->ending[0] || e->clock.step % e->cs->history_every == 0 ||
		              boundary_clock_ends_run(e);
		int64_t rebuilds = e->pairs.rebuilds;
		double *agree = e->sums.agree;
		test_interrupt(e);
		agree[0] = interrupted;
		agree[1] = par_rank() == 0 && L->o->max_wall > 0 &&
		           timer_now() - L->wall0 >= L->o->max_wall;
		agree[2] = par_rank() == 0 && checkpoint_due_by_wall(L);
		engine_step(e, measure);
		how = after_step(L, measure, rebuilds);
	}
	e->tm.between = 0;
	phase_stop(&e->tm, TM_OUTPUT);
	finish(L);
}

/* A check of the diagnosis of a non-finite state: with DEM_TEST_NAN=K in
 * the environment, the particle of index K in the assembly gets a NaN
 * velocity before the loop's first step. */
static void test_nan(engine *e)
{
	const char *s = getenv("DEM_TEST_NAN");
	if (!s || !*s)
		return;
	size_t p0, p1;
	ranks_own(e, &p0, &p1);
	for (size_t i = p0; i < p1; i++)
		if (e->p.orig[i] == atol(s))
			e->p.v[3 * i] = NAN;
}

static int run_loop(engine *e, run_writer *w, const run_opts *o)
{
	phase_start(&e->tm, TM_TOTAL);
	ranks_traffic_start(e);
	loop_state L = {.e = e, .w = w, .o = o, .last_snapshot_step = -1};
	L.wall0 = L.last_checkpoint = L.last_row_wall = L.last_flush = timer_now();
	L.last_row_step = L.step0 = L.pace_step = e->clock.step;
	L.pace_wall = L.wall0;
	L.pace_strain = engine_strain(e);
	L.pace_stress = engine_stress(e);
	progress_start(&L.pg, "steps", 0);
	/* Any signal that asks the program to end finishes the step and
	 * checkpoints: a closed terminal, or a batch scheduler before its kill. */
	struct sigaction sa = {.sa_handler = on_interrupt}, old[AFILE_NSIGNALS];
	sigemptyset(&sa.sa_mask);
	interrupted = 0;
	for (int k = 0; k < AFILE_NSIGNALS; k++)
		sigaction(afile_signals[k], &sa, &old[k]);
	phase_start(&e->tm, TM_OUTPUT);
	if (e->clock.step == 0 && snapshot(&L))
		fatal(NULL);
	phase_stop(&e->tm, TM_OUTPUT);
	L.last_snapshot_step = e->clock.step;
	test_nan(e);
	loop(&L);
	for (int k = 0; k < AFILE_NSIGNALS; k++)
		sigaction(afile_signals[k], &old[k], NULL);
	phase_stop(&e->tm, TM_TOTAL);
	ranks_traffic(e, (double)(e->clock.step - L.step0),
	              (double[2]){(double)engine_bytes(e), (double)report_peak_rss()});
	if (L.code == RUN_FAILED && par_rank() == 0)
		fprintf(stderr, "%s: %s\n", err_program_name(), L.status);
	/* The last snapshot, written as the run ends, holds the strains it has
	 * crossed since the one before (a stop rule may end the run in the
	 * step that crosses one). */
	size_t next = e->out.snapshot_strain_next, n = e->cs->nsnapshot_strains;
	const double *at = e->cs->snapshot_strains, strain = engine_strain(e);
	for (; next < n; next++) {
		double from = next ? at[next - 1] : 0;
		if (!(from <= at[next] ? strain >= at[next] : strain <= at[next]))
			break;
	}
	if (L.code == RUN_OK && next < n && par_rank() == 0 && !o->quiet)
		fprintf(stderr,
		        "%s: warning: output.snapshot_strains: %zu of %zu not reached (the first: "
		        "%g; each is taken once the strain has passed the one before)\n",
		        err_program_name(), n - next, n, e->cs->snapshot_strains[next]);
	if (par_rank() == 0)
		report_print(e, L.step0, L.status, o);
	return L.code;
}

/* The run file, with the assembly embedded, made by every rank (parallel
 * HDF5): rank 0's provenance. */
static run_writer *create(engine *e, const dem_assembly *a, const run_opts *o)
{
	phase_start(&e->tm, TM_SETUP);
	dem_provenance prov;
	prov_init(&prov, "solve", e->cs->config, 0);
	run_writer *w = run_create(o->output, &prov, a, history_columns, history_ncolumns);
	prov_free(&prov);
	if (!w)
		fatal(NULL);
	phase_stop(&e->tm, TM_SETUP);
	return w;
}

/* Write the bond table, then run. */
static int bonds_then_loop(engine *e, run_writer *w, const run_opts *o)
{
	phase_start(&e->tm, TM_SETUP);
	if (output_bonds(e, w))
		fatal(NULL);
	phase_stop(&e->tm, TM_SETUP);
	return run_loop(e, w, o);
}

int run_engine(engine *e, const dem_assembly *a, const run_opts *o)
{
	return bonds_then_loop(e, create(e, a, o), o);
}

static int run_continue(const run_opts *o, const char *from, dem_run *r);

/* Whether the recovery copy beside the output (read into r) is of a run of
 * this same case on this same assembly that was killed outright (1), of
 * another run (-1: this run replaces it, once it has started), or absent
 * (0). */
static int killed_before(const dem_case *cs, const dem_assembly *a, const char *ckpt, dem_run *r)
{
	if (access(ckpt, F_OK) != 0)
		return 0;
	/* Each rank compares its piece of the two assemblies. */
	const dem_assembly *b = &r->assembly;
	int same = run_read_head_part(ckpt, par_rank(), par_size(), r) == 0;
	same = same && strcmp(r->prov.config, cs->config) == 0 && b->n == a->n &&
	       b->piece == a->piece && b->first == a->first && b->held == a->held;
	size_t m = a->piece ? a->held : a->n;
	same = same && memcmp(b->x, a->x, 3 * m * sizeof *a->x) == 0 &&
	       memcmp(b->r, a->r, m * sizeof *a->r) == 0;
	int differ = !same;
	par_max_int(&differ, 1);
	if (!differ)
		return 1;
	run_free(r);
	return -1;
}

int run_case(const dem_case *cs, dem_assembly *a, const run_opts *o)
{
	char ckpt[4200];
	dem_run r = {0};
	run_recovery_name(o->output, ckpt, sizeof ckpt);
	/* Not a run another solve is writing, before its recovery copy is
	 * taken for a killed one's or setup takes its time. */
	if (afile_check_free(o->output))
		fatal(NULL);
	int before = killed_before(cs, a, ckpt, &r);
	if (before > 0) {
		if (!o->quiet)
			fprintf(stderr,
			        "%s: %s: a run of this case did not finish; continuing it\n",
			        err_program_name(), o->output);
		assembly_free(a);
		run_opts cont = *o;
		cont.restart = o->output;
		return run_continue(&cont, ckpt, &r);
	}
	engine e;
	/* For the tests of checkpoints written before the walk (order.h), with
	 * DEM_TEST_PLAIN_ORDER=1 in the environment a new run has its
	 * particles in the Morton order alone, as those did. */
	const char *plain = getenv("DEM_TEST_PLAIN_ORDER");
	if (engine_setup(&e, cs, a,
	                 &(engine_opts){.threads = o->threads,
	                                .quiet = o->quiet,
	                                .plain_order = plain && strcmp(plain, "1") == 0}))
		fatal("%s: %s", cs->source, err_msg());
	h5_set_threads(e.team); /* the run file's chunks compressed on the step's threads */
	run_writer *w = create(&e, a, o);
	/* Another run's recovery copy goes once this run has passed its
	 * checks and is being written: a restart would take it for this
	 * run's. */
	if (before < 0 && par_rank() == 0)
		unlink(ckpt);
	assembly_free(a); /* in the run file now; the engine keeps what it needs */
	int code = bonds_then_loop(&e, w, o);
	engine_free(&e);
	return code;
}

/* Snapshots written after the checkpoint are redone by the continued run. */
typedef struct {
	int64_t keep;
	size_t n;
	char names[64][32];
} later;

static herr_t collect_later(hid_t g, const char *name, const H5L_info_t *info, void *data)
{
	(void)g, (void)info;
	later *l = data;
	if (strtoll(name, NULL, 10) > l->keep && l->n < 64)
		snprintf(l->names[l->n++], sizeof l->names[0], "%s", name);
	return 0;
}

static int drop_later_snapshots(run_writer *w, int64_t step)
{
	hid_t g = h5_open_group(run_hid(w), "snapshots");
	if (g < 0)
		return -1;
	later l = {.keep = step};
	do {
		l.n = 0;
		H5Literate(g, H5_INDEX_NAME, H5_ITER_NATIVE, NULL, collect_later, &l);
		for (size_t k = 0; k < l.n; k++)
			H5Ldelete(g, l.names[k], H5P_DEFAULT);
	} while (l.n == 64);
	H5Gclose(g);
	return 0;
}

/* The file a restart continues from (its name into from, its contents
 * into r): the run file when it was interrupted (Ctrl-C, a signal, a
 * budget), or its recovery copy, which is what a run killed outright (kill
 * -9, a lost node) leaves; the one further on when there are both, the
 * copy when the run file is of an earlier run that finished. */
static void restart_source(const char *path, char *from, size_t n, dem_run *r)
{
	char ckpt[4200];
	run_recovery_name(path, ckpt, sizeof ckpt);
	int has_run = access(path, F_OK) == 0, has_ckpt = access(ckpt, F_OK) == 0;
	if (!has_run && !has_ckpt)
		fatal("%s: missing, and no recovery copy %s beside it: nothing to continue", path,
		      ckpt);
	dem_run c;
	int rank = par_rank(), ranks = par_size(); /* each rank a piece of the assembly */
	if (has_ckpt && run_read_head_part(ckpt, rank, ranks, &c))
		fatal(NULL);
	if (has_run) {
		if (run_read_head_part(path, rank, ranks, r))
			fatal(NULL);
		/* A recovery copy beside a finished run file is of a later run
		 * under the same name, killed. */
		int interrupted = strcmp(r->status, "interrupted") == 0;
		if (!interrupted && !has_ckpt)
			fatal("%s: the run has status '%s': only an interrupted run continues",
			      path, r->status);
		if (interrupted && (!has_ckpt || c.nrows <= r->nrows)) {
			if (has_ckpt)
				run_free(&c);
			snprintf(from, n, "%s", path);
			return;
		}
		run_free(r);
	}
	*r = c;
	snprintf(from, n, "%s", ckpt);
}

/* Continue the run stored in from (the run file or its recovery copy,
 * read into r) under the run file's name o->restart. */
static int run_continue(const run_opts *o, const char *from, dem_run *r)
{
	dem_case cs;
	if (case_parse_text(r->prov.config, from, &cs))
		fatal("%s: stored configuration: %s", from, err_msg());
	engine e;
	int plain;
	if (checkpoint_plain_order(from, &plain) ||
	    engine_setup(
	        &e, &cs, &r->assembly,
	        &(engine_opts){
	            .threads = o->threads, .quiet = 1, .restart = 1, .plain_order = plain}))
		fatal(NULL);
	h5_set_threads(e.team);
	phase_start(&e.tm, TM_SETUP);
	if (checkpoint_read(&e, from))
		fatal(NULL);
	engine_timestep_set(&e);
	/* Every rank writes the run file (parallel HDF5). */
	run_writer *w = run_reopen(from, o->restart, e.out.history_rows, e.out.crack_rows);
	if (!w || drop_later_snapshots(w, e.clock.step))
		fatal(NULL);
	if (!o->quiet)
		fprintf(stderr, "%s: %s: continuing from step %" PRId64 " (t = %g s, stage %d)\n",
		        err_program_name(), from, e.clock.step, e.clock.t, e.prog.stage + 1);
	phase_stop(&e.tm, TM_SETUP);
	run_free(r);
	int code = run_loop(&e, w, o);
	engine_free(&e);
	case_free(&cs);
	return code;
}

int run_restart(const run_opts *o)
{
	dem_run r;
	char from[4200];
	if (afile_check_free(o->restart))
		fatal(NULL);
	restart_source(o->restart, from, sizeof from, &r);
	return run_continue(o, from, &r);
}
