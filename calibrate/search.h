/* The search (share/doc/calibrate.md, "How it searches"): NLopt's local
 * method (BOBYQA by default) from the start, after one of its global ones
 * (DIRECT-L) when the start is poor, in rounds. With the scaling the
 * search variables are the ratios and dimensionless keys only: each point's
 * runs give the scales that best meet the targets (calibrate/objective.h),
 * the round ends on the point whose scaled copy is predicted best, and that
 * copy is run; the next round starts from it, so the scales stop moving
 * and the prediction becomes the runs. Every evaluated point is kept, in
 * order: the path of the parameters. */
#ifndef DEM_CALIBRATE_SEARCH_H
#define DEM_CALIBRATE_SEARCH_H

#include <stddef.h>

#include "calibrate/eval.h"
#include "calibrate/objective.h"
#include "calibrate/space.h"

typedef struct {
	int round;
	char stage[8]; /* start, global, local, scaled */
	double v[CAL_MAX_KEYS];
	int ok;
	char message[700]; /* why not */
	fit fit;           /* of its runs (ok) */
	int predicted;     /* with the scaling: the fit of its best scaled copy */
	fit pred;
} path_point;

typedef enum { SEARCH_MET, SEARCH_BUDGET, SEARCH_CONVERGED, SEARCH_STOPPED } search_status;

typedef struct {
	path_point *path;
	int npath, cap;
	int best; /* the evaluated point of least objective, -1 if none */
	outcome best_out;
	search_status status;
	int rounds;
	int global_used;
} search_result;

/* Points of the global stage: search.global_points, by default
 * 8 * (n + 1) for n search variables. */
long search_global_points(const space *s);
/* When the global stage may run (search.global) and the budget of runs
 * cannot take the start, its points and one point of the local stage: 1,
 * with a warning naming the numbers and what to change in buf; else 0. */
int search_budget_short(const space *s, char *buf, size_t n);

/* Search from the start values; 0, or -1 with err_set() on an error (the
 * start fails, the log cannot be written) or when a signal stopped it
 * (runner_stopped(), status SEARCH_STOPPED). */
int search_run(evaluator *e, const space *s, int quiet, search_result *r);
void search_free(search_result *r);

extern const char *const search_status_text[];

#endif
