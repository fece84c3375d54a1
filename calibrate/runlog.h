/* The run log (log.csv in the output directory): one row per solver run
 * the calibration made, with the values of the material keys it changes,
 * the run's status and every quantity of its summary.json. A run is known
 * by a key, a hash of everything its result depends on (the case file
 * written, with the material inline, and the assembly's bytes), so a
 * calibration that starts again in the same directory takes the runs it
 * needs from the log instead of repeating them, whatever stopped it before.
 * The file is rewritten atomically (lib/afile.h) after every run, its rows
 * in the order the calibration first asked for them, so it does not depend
 * on which parallel run ended first. */
#ifndef DEM_CALIBRATE_RUNLOG_H
#define DEM_CALIBRATE_RUNLOG_H

#include "calibrate/quantity.h"
#include "calibrate/spec.h"

typedef struct {
	char key[17];
	long seq;
	char phase[16], test[48], specimen[8];
	double v[CAL_MAX_KEYS];
	char *status; /* "ok", or "failed: <message>" */
	double q[QTY_MAX];
	double wall; /* s */
} runrec;

typedef struct {
	char *path;
	char *header;
	int nkey;
	runrec *r;
	int n, cap;
} runlog;

/* Open the log at path: read its runs when it exists (its columns must be
 * those of this calibration). 0, or -1 with err_set(). */
int runlog_open(runlog *l, const char *path, const cal_spec *sp);
const runrec *runlog_find(const runlog *l, const char *key);
/* Add a run (copied) and write the log. 0, or -1 with err_set(). */
int runlog_add(runlog *l, const runrec *r);
void runlog_free(runlog *l);

/* 64-bit FNV-1a hash, continued from h (start with HASH_START). */
#define HASH_START 0xcbf29ce484222325ULL
unsigned long long hash_bytes(unsigned long long h, const void *p, size_t n);
/* The hash of a file's bytes; 0 with err_set() when it cannot be read. */
unsigned long long hash_file(const char *path);

#endif
