/* Dependency files for make, as a compiler writes with -MD -MP: the line
 * "target: prerequisite ..." followed by an empty rule for each
 * prerequisite, so a workflow re-runs a stage when any input it read
 * changes (a material file named by a case, a geometry named by a pack
 * configuration) and does not fail when one of them is removed. */
#ifndef DEM_DEPFILE_H
#define DEM_DEPFILE_H

/* Write path (atomically) for target and its n prerequisites; NULL entries
 * are skipped. Names with spaces are escaped for make. Returns 0 or -1 with
 * err_set(). */
int depfile_write(const char *path, const char *target, const char *const *deps, int n);

#endif
