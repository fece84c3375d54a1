/* Reading post's inputs, or exiting with a message that names the file and
 * says what was expected. */
#ifndef DEM_POST_LOAD_H
#define DEM_POST_LOAD_H

#include "lib/assembly.h"
#include "lib/runfile.h"

typedef enum { FILE_RUN, FILE_ASSEMBLY } file_kind;

/* The kind of a toolchain file (by its `format` attribute); fatal when the
 * file is missing or of neither kind. */
file_kind load_kind(const char *cmd, const char *path);
/* run_read(), fatal on failure. cmd names the command in messages. The
 * run's caption becomes the footer of the figures drawn next (plot.h). */
void load_run(const char *cmd, const char *path, dem_run *r);
/* "PATH · test · material name" of a run (malloc'd). */
char *load_caption(const char *path, const dem_run *r);
/* Whether the run's case is a Brazilian test (its `test` is "bts"). */
int load_is_bts(const dem_run *r);
/* The run's loading axis, a unit vector: the case's `axis` when it has
 * one (as solve takes it), else the geometry's, else z. */
void load_axis(const dem_run *r, double a[3]);
/* run_read_snapshot(), fatal on failure. */
void load_snapshot(const char *path, const dem_run *r, size_t k, dem_snapshot *s);

#endif
