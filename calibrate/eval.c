#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "calibrate/eval.h"
#include "calibrate/runner.h"
#include "lib/cfg.h"
#include "lib/err.h"
#include "lib/json.h"

static const char *const phase_names[] = {"truth", "search", "sensitivity", "confirm"};
static const char *const kind_names[] = {"search", "confirm"};

static int make_dir(const char *path)
{
	if (mkdir(path, 0777) == 0 || errno == EEXIST)
		return 0;
	return err_set("%s: cannot create the directory: %s", path, strerror(errno));
}

static char *join(const char *dir, const char *name)
{
	size_t n = strlen(dir) + strlen(name) + 2;
	char *p = xmalloc(n);
	snprintf(p, n, "%s/%s", dir, name);
	return p;
}

int eval_init(evaluator *e, const cal_spec *sp, const char *out, const char *bin, int parallel,
              int keep_runs)
{
	memset(e, 0, sizeof *e);
	e->sp = sp;
	e->out = xstrdup(out);
	e->bin = xstrdup(bin);
	e->parallel = parallel;
	e->keep_runs = keep_runs;
	char *runs = join(out, "runs"), *specimens = join(out, "specimens"),
	     *log = join(out, "log.csv");
	int rc =
	    make_dir(out) || make_dir(runs) || make_dir(specimens) || runlog_open(&e->log, log, sp);
	free(runs), free(specimens), free(log);
	for (int t = 0; t < sp->ntest && !rc; t++) {
		e->cases[t] = spec_case_as_run(&sp->test[t]);
		rc = e->cases[t] ? 0 : -1;
	}
	return rc;
}

void eval_free(evaluator *e)
{
	for (int t = 0; t < e->sp->ntest; t++) {
		free(e->assembly[t][0]), free(e->assembly[t][1]);
		cJSON_Delete(e->cases[t]);
	}
	runlog_free(&e->log);
	free(e->asked);
	free(e->out), free(e->bin);
	memset(e, 0, sizeof *e);
}

int eval_runs_per_point(const evaluator *e) { return e->sp->ntest; }

cJSON *eval_material(const cal_spec *sp, const double *v)
{
	cJSON *m = cJSON_Duplicate(sp->material, 1);
	for (int k = 0; k < sp->nkey; k++)
		cJSON_SetNumberValue(spec_material_number(m, sp->key[k].name), v[k]);
	return m;
}

static void hex(char out[17], unsigned long long h) { snprintf(out, 17, "%016llx", h); }

static void ignore(job *j, int k, void *data) { (void)j, (void)k, (void)data; }

int eval_specimens(evaluator *e, int kind)
{
	const cal_spec *sp = e->sp;
	job jobs[CAL_MAX_TESTS];
	int njobs = 0, rc = 0;
	memset(jobs, 0, sizeof jobs);
	for (int t = 0; t < sp->ntest && !rc; t++) {
		const cal_test *ts = &sp->test[t];
		const cal_specimen *s = kind == SPECIMEN_SEARCH ? &ts->search : &ts->confirm;
		if (kind == SPECIMEN_CONFIRM && !ts->has_confirm)
			continue;
		if (s->assembly) {
			e->assembly[t][kind] = xstrdup(s->assembly);
			continue;
		}
		/* Named by a hash of what makes it: the configuration's bytes,
		 * the count and the seed. */
		unsigned long long h = hash_file(s->config);
		if (!h) {
			rc = -1;
			break;
		}
		h = hash_bytes(h, &s->count, sizeof s->count);
		h = hash_bytes(h, &s->seed, sizeof s->seed);
		char name[64];
		snprintf(name, sizeof name, "specimens/%016llx.h5", h);
		e->assembly[t][kind] = join(e->out, name);
		if (access(e->assembly[t][kind], R_OK) == 0)
			continue;
		job *j = &jobs[njobs++];
		char pack[4200];
		snprintf(pack, sizeof pack, "%s/pack", e->bin);
		job_cmd(j, pack);
		job_arg(j, "--config");
		job_arg(j, "%s", s->config);
		if (s->count)
			job_arg(j, "--count"), job_arg(j, "%ld", s->count);
		if (s->seed)
			job_arg(j, "--seed"), job_arg(j, "%ld", s->seed);
		job_arg(j, "--threads");
		job_arg(j, "1");
		job_arg(j, "--quiet");
		job_arg(j, "%s", e->assembly[t][kind]);
		size_t n = strlen(e->assembly[t][kind]) + 5;
		j->log = xmalloc(n);
		snprintf(j->log, n, "%s.txt", e->assembly[t][kind]);
	}
	/* Tests sharing a specimen share its file: pack it once. */
	for (int a = 0; a < njobs; a++)
		for (int b = a + 1; b < njobs; b++)
			if (jobs[a].ncmd && jobs[b].ncmd && strcmp(jobs[a].log, jobs[b].log) == 0)
				job_free(&jobs[b]);
	int kept = 0;
	for (int a = 0; a < njobs; a++)
		if (jobs[a].ncmd)
			jobs[kept++] = jobs[a];
	njobs = kept;
	if (!rc && njobs) {
		if (runner_run(jobs, njobs, e->parallel, ignore, NULL))
			rc = -1;
		for (int k = 0; k < njobs && !rc; k++)
			if (jobs[k].result != JOB_OK)
				rc = err_set("pack failed on %s (its output: %s): %s",
				             jobs[k].argv[0][2], jobs[k].log, jobs[k].message);
	}
	for (int k = 0; k < njobs; k++)
		job_free(&jobs[k]);
	for (int t = 0; t < sp->ntest && !rc; t++) {
		if (!e->assembly[t][kind])
			continue;
		unsigned long long h = hash_file(e->assembly[t][kind]);
		if (!h)
			rc = -1;
		hex(e->asm_hash[t][kind], h);
	}
	return rc;
}

/* One run of a batch. */
typedef struct {
	int point, test;
	char key[17];
	long seq;
	char *dir;
	int pending; /* to be run (not in the log) */
} pending_run;

typedef struct {
	evaluator *e;
	pending_run *runs;
	const double (*v)[CAL_MAX_KEYS];
	int kind;
	eval_phase phase;
	int failed_write;
} batch;

static long asked_seq(evaluator *e, const char *key, int *fresh)
{
	for (long k = 0; k < e->nasked; k++)
		if (strcmp(e->asked[k], key) == 0) {
			*fresh = 0;
			return k;
		}
	if (e->nasked == e->cap_asked)
		e->asked = xrealloc(e->asked,
		                    (size_t)(e->cap_asked = e->cap_asked ? 2 * e->cap_asked : 256) *
		                        sizeof *e->asked);
	memcpy(e->asked[e->nasked], key, 17);
	*fresh = 1;
	return e->nasked++;
}

/* The quantities of summary.json, NaN where null. */
static int read_summary(const char *path, double *q)
{
	cJSON *j = cfg_load_json(path);
	if (!j)
		return -1;
	for (int k = 0; k < nquantities; k++) {
		cJSON *v = cJSON_GetObjectItemCaseSensitive(j, quantities[k].name);
		q[k] = cJSON_IsNumber(v) ? v->valuedouble : NAN;
	}
	cJSON_Delete(j);
	return 0;
}

static void run_done(job *j, int k, void *data)
{
	batch *b = data;
	evaluator *e = b->e;
	pending_run *r = NULL;
	int seen = 0;
	for (pending_run *p = b->runs;; p++)
		if (p->pending && seen++ == k) {
			r = p;
			break;
		}
	if (j->result == JOB_STOPPED)
		return;
	runrec rec;
	memset(&rec, 0, sizeof rec);
	memcpy(rec.key, r->key, 17);
	rec.seq = r->seq;
	snprintf(rec.phase, sizeof rec.phase, "%s", phase_names[b->phase]);
	snprintf(rec.test, sizeof rec.test, "%s", e->sp->test[r->test].name);
	snprintf(rec.specimen, sizeof rec.specimen, "%s", kind_names[b->kind]);
	memcpy(rec.v, b->v[r->point], sizeof rec.v);
	rec.wall = j->wall;
	for (int q = 0; q < QTY_MAX; q++)
		rec.q[q] = NAN;
	char status[700], *summary = join(r->dir, "summary.json");
	if (j->result == JOB_OK && read_summary(summary, rec.q) == 0)
		snprintf(status, sizeof status, "ok");
	else if (j->result == JOB_OK)
		snprintf(status, sizeof status, "failed: %s", err_msg());
	else
		snprintf(status, sizeof status, "failed: %s (exit status %d)", j->message,
		         j->exit_code);
	free(summary);
	rec.status = status;
	if (!e->keep_runs) {
		char *run = join(r->dir, "run.h5"), *ckpt = join(r->dir, "run.h5.ckpt");
		unlink(run), unlink(ckpt);
		free(run), free(ckpt);
	}
	e->new_runs++;
	e->run_wall += j->wall;
	if (runlog_add(&e->log, &rec))
		b->failed_write = 1;
}

/* The threads of each solve: the cores left to a batch smaller than them. */
static int threads_per_run(const evaluator *e, int nrun)
{
	int t = nrun > 0 ? e->parallel / nrun : 1;
	return t < 1 ? 1 : t;
}

static int write_case(const char *dir, const cJSON *cs)
{
	char *path = join(dir, "case.json");
	int rc = json_write(path, cJSON_Duplicate(cs, 1));
	free(path);
	return rc;
}

/* The run of test t on a point's material m: its key, its place in the
 * order asked for, its directory; pending when the log lacks it (its case
 * is then written). 0, or -1 with err_set(). */
static int plan_run(evaluator *e, pending_run *runs, int k, const cJSON *m, int kind,
                    eval_phase phase)
{
	pending_run *r = &runs[k];
	cJSON *cs = cJSON_Duplicate(e->cases[r->test], 1);
	cJSON_AddItemToObject(cs, "material", cJSON_Duplicate(m, 1));
	char *text = cJSON_PrintUnformatted(cs);
	unsigned long long h = hash_bytes(HASH_START, text, strlen(text));
	h = hash_bytes(h, e->asm_hash[r->test][kind], 16);
	free(text);
	hex(r->key, h);
	int fresh;
	r->seq = asked_seq(e, r->key, &fresh);
	if (fresh)
		e->runs[phase]++;
	char name[64];
	snprintf(name, sizeof name, "runs/%s", r->key);
	r->dir = join(e->out, name);
	int dup = 0, rc = 0;
	for (int j = 0; j < k; j++)
		dup |= runs[j].pending && strcmp(runs[j].key, r->key) == 0;
	if (dup || runlog_find(&e->log, r->key)) {
		e->logged_runs += fresh && !dup;
	} else {
		r->pending = 1;
		rc = make_dir(r->dir) || write_case(r->dir, cs) ? -1 : 0;
	}
	cJSON_Delete(cs);
	return rc;
}

/* solve, then post summary, in the run's directory. */
static void solve_job(const evaluator *e, const pending_run *r, int kind, int threads, job *j)
{
	char prog[4200];
	snprintf(prog, sizeof prog, "%s/solve", e->bin);
	job_cmd(j, prog);
	job_arg(j, "--quiet");
	job_arg(j, "--threads");
	job_arg(j, "%d", threads);
	job_arg(j, "--assembly");
	job_arg(j, "%s", e->assembly[r->test][kind]);
	job_arg(j, "--output");
	job_arg(j, "%s/run.h5", r->dir);
	job_arg(j, "%s/case.json", r->dir);
	snprintf(prog, sizeof prog, "%s/post", e->bin);
	job_cmd(j, prog);
	job_arg(j, "summary");
	job_arg(j, "--out");
	job_arg(j, "%s", r->dir);
	job_arg(j, "%s/run.h5", r->dir);
	j->log = join(r->dir, "log.txt");
}

/* A point's quantities from the log, and whether they meet every target's
 * needs. 0, or -1 when a run is missing (stopped before it ran). */
static int collect(const evaluator *e, const pending_run *runs, int kind, outcome *o)
{
	const cal_spec *sp = e->sp;
	o->ok = 1;
	o->message[0] = '\0';
	for (int t = 0; t < sp->ntest; t++)
		for (int q = 0; q < QTY_MAX; q++)
			o->q[t][q] = NAN;
	for (int t = 0; t < sp->ntest; t++) {
		if (kind == SPECIMEN_CONFIRM && !sp->test[t].has_confirm)
			continue;
		const runrec *rec = runlog_find(&e->log, runs[t].key);
		if (!rec)
			return -1;
		memcpy(o->q[t], rec->q, sizeof o->q[t]);
		if (o->ok && strcmp(rec->status, "ok") != 0) {
			o->ok = 0;
			snprintf(o->message, sizeof o->message, "test '%s' (run %s): %s",
			         sp->test[t].name, runs[t].dir, rec->status);
		}
	}
	for (int k = 0; k < sp->ntarget && o->ok; k++) {
		const cal_target *tg = &sp->target[k];
		const quantity *q = &quantities[tg->quantity];
		if (kind == SPECIMEN_CONFIRM && !sp->test[tg->test].has_confirm)
			continue;
		double x = o->q[tg->test][tg->quantity];
		if (!isfinite(x) || (quantity_positive(q) && x <= 0)) {
			o->ok = 0;
			snprintf(o->message, sizeof o->message,
			         "test '%s' (run %s/summary.json): %s is %s",
			         sp->test[tg->test].name, runs[tg->test].dir, q->name,
			         isfinite(x) ? "not positive" : "null (not measured)");
		}
	}
	return 0;
}

int eval_points(evaluator *e, const double (*v)[CAL_MAX_KEYS], int np, int kind, eval_phase phase,
                outcome *out)
{
	const cal_spec *sp = e->sp;
	int nrun = np * sp->ntest, npending = 0, rc = 0;
	pending_run *runs = xcalloc((size_t)nrun, sizeof *runs);
	for (int p = 0; p < np; p++) {
		cJSON *m = eval_material(sp, v[p]);
		for (int t = 0; t < sp->ntest; t++) {
			int k = p * sp->ntest + t;
			runs[k].point = p, runs[k].test = t;
			if (kind == SPECIMEN_CONFIRM && !sp->test[t].has_confirm)
				continue;
			if (plan_run(e, runs, k, m, kind, phase))
				rc = -1;
			npending += runs[k].pending;
		}
		cJSON_Delete(m);
	}
	job *jobs = xcalloc((size_t)nrun, sizeof *jobs);
	for (int k = 0, j = 0; k < nrun; k++)
		if (runs[k].pending)
			solve_job(e, &runs[k], kind, threads_per_run(e, npending), &jobs[j++]);
	batch b = {e, runs, v, kind, phase, 0};
	if (!rc && npending && runner_run(jobs, npending, e->parallel, run_done, &b))
		rc = -1;
	if (!rc && b.failed_write)
		rc = -1;
	for (int k = 0; k < npending; k++)
		job_free(&jobs[k]);
	free(jobs);
	for (int p = 0; p < np && !rc; p++)
		if (collect(e, runs + p * sp->ntest, kind, &out[p]))
			rc = -1; /* a run stopped before it ran */
	for (int k = 0; k < nrun; k++)
		free(runs[k].dir);
	free(runs);
	return rc;
}
