/* The run report at the end (CoMD-style phase timers): on stderr, and as
 * JSON when --report is given. */
#ifndef DEM_REPORT_H
#define DEM_REPORT_H

#include <stdint.h>

#include "solve/engine.h"
#include "solve/run.h"

/* Bytes of the engine's state (particles, bonds, contacts, lists). */
size_t engine_bytes(const engine *e);
/* Note the resident size at start (before the inputs): call first in main. */
void report_start(void);
/* The largest resident size so far, bytes. */
long report_peak_rss(void);
void report_print(const engine *e, int64_t step0, const char *status, const run_opts *o);
/* Whether path may take the report: missing, or a report written before
 * (a JSON object with the report's "status" and "particles"). */
int report_replaceable(const char *path);

#endif
