/* Helpers for the engine's tests: cases from JSON text, engines set up on
 * fixture assemblies, runs through the solve program, and comparisons of
 * run files. */
#ifndef DEM_TEST_SOLVE_HARNESS_H
#define DEM_TEST_SOLVE_HARNESS_H

#include <hdf5.h>
#include <stddef.h>

#include "lib/assembly.h"
#include "lib/runfile.h"
#include "solve/case.h"
#include "solve/engine.h"

/* Parse a case from text; aborts the test with the message on error. */
void harness_case(dem_case *c, const char *json);
/* Set up an engine quietly; aborts on error. */
void harness_engine(engine *e, const dem_case *c, const dem_assembly *a);
/* Run the solve program with the given arguments (a shell command tail);
 * returns its exit status. Output goes to the test's log. */
int harness_solve(const char *args);
/* Read a run file; aborts on error. */
void harness_read(const char *path, dem_run *r);
/* Write text to a scratch file and return its path. */
const char *harness_file(const char *name, const char *text);
/* A copy at `to` of the HDF5 file `from` whose first element of dataset
 * (read and written as type) is changed by edit; aborts on error. */
void harness_edit_copy(const char *from, const char *to, const char *dataset, hid_t type,
                       void (*edit)(void *first));
/* Compare two runs: histories (every column but the wall-clock "rate"),
 * cracks and snapshots, bit for bit. Returns the number of differences and
 * prints the first ones. */
int harness_same_runs(const char *a, const char *b);

#endif
