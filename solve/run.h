/* Running a case from start, or continuing one from its checkpoint. */
#ifndef DEM_RUN_H
#define DEM_RUN_H

#include "lib/assembly.h"
#include "solve/case.h"

typedef struct {
	const char *output;  /* the run file */
	const char *restart; /* the run file to continue, or NULL */
	long max_steps;      /* steps in this invocation before interrupting; 0: no limit */
	double max_wall;     /* s of wall time before interrupting; 0: no limit */
	const char *report;  /* JSON run report file, or NULL */
	int threads;         /* OpenMP threads; 0: the case's "threads", else all cores */
	int quiet;
} run_opts;

/* Exit codes: 0 complete or stopped by a rule, 1 a diagnosed failure (the
 * file is kept with its status), 3 interrupted (restartable). */
enum { RUN_OK = 0, RUN_FAILED = 1, RUN_INTERRUPTED = 3 };

/* Run the case on the assembly. The run takes the assembly over: it frees
 * it once the run file holds it, to keep one copy in memory. */
int run_case(const dem_case *cs, dem_assembly *a, const run_opts *o);
/* The same for an engine already set up from cs and a. */
struct engine;
int run_engine(struct engine *e, const dem_assembly *a, const run_opts *o);
int run_restart(const run_opts *o);

#endif
