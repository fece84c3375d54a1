/* Bonds, snapshots and the crack log in run.h5 (share/doc/format.md). */
#ifndef DEM_OUTPUT_H
#define DEM_OUTPUT_H

#include <math.h>

#include "lib/runfile.h"
#include "solve/engine.h"

/* On several ranks every rank calls these with the run file they share
 * (parallel HDF5): each rank's own rows go into it (ranks_rows_write). */
int output_bonds(engine *e, run_writer *w);
/* Particles and bonds now; bond forces are those of the last step. */
int output_snapshot(engine *e, run_writer *w);
/* Append the failures collected so far to /cracks. */
int output_cracks(engine *e, run_writer *w);

#endif
