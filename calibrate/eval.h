/* Evaluating materials: every test of the calibration run by solve on its
 * specimen with the material of a point, then measured by post summary,
 * the runs of a batch of points side by side (calibrate/runner.h), each
 * taken from the run log when it is there (calibrate/runlog.h). */
#ifndef DEM_CALIBRATE_EVAL_H
#define DEM_CALIBRATE_EVAL_H

#include "calibrate/quantity.h"
#include "calibrate/runlog.h"
#include "calibrate/spec.h"

enum { SPECIMEN_SEARCH, SPECIMEN_CONFIRM };

typedef struct {
	const cal_spec *sp;
	runlog log;
	char *out;    /* output directory */
	char *bin;    /* where pack, solve and post are */
	int parallel; /* runs at a time */
	int keep_runs;
	char *assembly[CAL_MAX_TESTS][2];
	char asm_hash[CAL_MAX_TESTS][2][17];
	cJSON *cases[CAL_MAX_TESTS]; /* each test's case, as run (no material yet) */
	/* Distinct runs asked for, in order (the log's seq). */
	char (*asked)[17];
	long nasked, cap_asked;
	long new_runs, logged_runs; /* run now / taken from the log */
	long runs[4];               /* distinct runs asked for by phase (eval_phase) */
	double run_wall;            /* s, sum of the new runs' wall times */
} evaluator;

typedef enum { PHASE_TRUTH, PHASE_SEARCH, PHASE_SENSITIVITY, PHASE_CONFIRM } eval_phase;

/* What a point gave: every quantity of every test, or why not. */
typedef struct {
	int ok;
	char message[700];
	double q[CAL_MAX_TESTS][QTY_MAX];
} outcome;

/* 0, or -1 with err_set() (the log cannot be read, a case cannot be). */
int eval_init(evaluator *e, const cal_spec *sp, const char *out, const char *bin, int parallel,
              int keep_runs);
void eval_free(evaluator *e);
/* Make (pack) the specimens of one kind that are missing. 0; -1 with
 * err_set(), or when a signal stopped it (runner_stopped()). */
int eval_specimens(evaluator *e, int kind);
/* The material at the key values v (caller frees with cJSON_Delete). */
cJSON *eval_material(const cal_spec *sp, const double *v);
/* Evaluate np points (values of every key, sp->nkey each) on the specimens
 * of one kind. 0 (each outcome says whether its point gave every target's
 * quantity); -1 when a signal stopped it, or with err_set() on an error of
 * the calibration itself (a log that cannot be written). */
int eval_points(evaluator *e, const double (*v)[CAL_MAX_KEYS], int np, int kind, eval_phase phase,
                outcome *out);
/* How many runs a point needs (the tests). */
int eval_runs_per_point(const evaluator *e);

#endif
