/* The columns of the history table and how a row is filled. */
#ifndef DEM_HISTORY_H
#define DEM_HISTORY_H

#include "lib/runfile.h"
#include "solve/engine.h"

extern const run_column history_columns[];
extern const int history_ncolumns;

/* The row of the last measuring step; rate in steps per wall-clock second. */
void history_row(const engine *e, double rate, double *row);

#endif
