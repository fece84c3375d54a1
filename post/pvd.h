/* ParaView data collections (.pvd): a time series of VTK XML files, each
 * dataset with its time (s) and part (several parts at one time make a
 * multiblock dataset). Written atomically. */
#ifndef DEM_POST_PVD_H
#define DEM_POST_PVD_H

#include <stddef.h>

typedef struct {
	double t;         /* s */
	int part;         /* 0 when a collection has a single part */
	const char *file; /* relative to the .pvd */
} pvd_entry;

void pvd_write(const char *path, const pvd_entry *e, size_t n);

#endif
