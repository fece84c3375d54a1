/* Cracks as discs for ParaView: each bond failure of the crack log is a
 * 16-sided polygon centred at the contact point, normal to the bond
 * direction, of radius r_c, carrying its row, mode (1 tension, 2 shear),
 * time, step, axial strain, forces at failure, the two particles and the
 * normal. A time series shows at each frame every crack that happened at
 * or before the frame's time: a crack appears at its time and stays. */
#ifndef DEM_POST_CRACKS_VTK_H
#define DEM_POST_CRACKS_VTK_H

#include <stddef.h>

#include "lib/runfile.h"
#include "post/pvd.h"

/* The frames of a crack series: the times of the given snapshots, plus the
 * end of the run (its last history or crack time) when there are cracks
 * after the last of them. times has room for nsnap + 1. Returns the count. */
size_t cracks_frames(const dem_run *r, const size_t *snaps, size_t nsnap, double *times);

/* Write <dir>/cracks_NNNNNN.vtp for each frame and <dir>/cracks.pvd. The
 * entries (file names owned by the caller afterwards: free e[k].file) are
 * returned in e[nframes] for a combined collection, or freed when e is
 * NULL. */
void cracks_series(const char *dir, const dem_run *r, const double *times, size_t nframes,
                   pvd_entry *e);

#endif
