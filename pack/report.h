/* The packing report (share/doc/format.md, /report): what the assembly
 * achieved, measured from the spheres themselves. (solve/report.h is the
 * run report of solve; hence the pack_ prefix.) */
#ifndef PACK_REPORT_H
#define PACK_REPORT_H

#include <stddef.h>
#include <stdio.h>

#include "lib/assembly.h"
#include "pack/psd.h"
#include "pack/surface.h"
#include "pack/zones.h"

#define REPORT_CORE_DEPTH 2.0    /* mean diameters: the core lies deeper */
#define REPORT_LAYER_DEPTH 0.5   /* mean diameters: the boundary layer's centres lie shallower */
#define REPORT_PROFILE_DEPTH 3.0 /* mean diameters covered by phi(w) */
#define REPORT_PROFILE_BINS 30
#define REPORT_PSD_POINTS 41

/* Fill every measured field of a->report (all but the timings) from a->x,
 * a->r, a->geom; `target` is the distribution the sizes were drawn from
 * (NULL for imported spheres: the target columns then repeat the achieved
 * ones). */
void pack_report_compute(dem_assembly *a, const surface *surf, const zones *z, const psd *target,
                         double beta);

/* The readable summary pack prints. */
void pack_report_print(const dem_assembly *a, FILE *out);

#endif
