/* What the writer and the reader of the run file (runfile_write.c,
 * runfile_read.c) both need to know of its layout beyond runfile.h; not for
 * other callers. The layout is share/doc/format.md. */
#ifndef DEM_RUNFILE_LAYOUT_H
#define DEM_RUNFILE_LAYOUT_H

#include <hdf5.h>
#include <inttypes.h>
#include <stddef.h>

/* The name of a snapshot's group under /snapshots: its step, as printf
 * formats an int64_t, zero-padded so names sort by step. */
#define RUN_SNAPSHOT "%012" PRId64

/* The number of names in the history's "columns" attribute: the column
 * names, in the writer's order, separated by commas. */
static inline int run_column_count(const char *order)
{
	int n = order[0] ? 1 : 0;
	for (const char *p = order; *p; p++)
		n += *p == ',';
	return n;
}

/* The steps of the snapshots in group g (/snapshots), ascending, from the
 * names of its snapshot groups (other names are skipped); *steps is
 * allocated (NULL when there are none), the count returned. */
size_t run_snapshot_steps(hid_t g, int64_t **steps);

#endif
