/* Bonds, snapshots and the crack log in run.h5 (share/doc/format.md). */
#ifndef DEM_OUTPUT_H
#define DEM_OUTPUT_H

#include <math.h>

#include "lib/runfile.h"
#include "solve/engine.h"

int output_bonds(const engine *e, run_writer *w);
/* Particles and bonds now; bond forces are those of the last step. */
int output_snapshot(const engine *e, run_writer *w);
/* Append the failures collected so far to /cracks. */
int output_cracks(engine *e, run_writer *w);

#endif
