/* Experimental points to overlay on the curves: a CSV file whose first
 * non-comment line names the columns. Recognised columns (others are
 * ignored): strain_axial, strain_radial, strain_volumetric (compression
 * positive, as in run.h5) and stress_axial (Pa) or stress_axial_MPa.
 * Lines starting with '#' and blank lines are skipped; an empty field is
 * a missing value; every row has the header's number of fields; a file
 * without rows, with both stress columns, naming a recognised column
 * twice, or whose stress_axial stays below 1 kPa (MPa under the Pa
 * column) is refused. */
#ifndef DEM_POST_EXPERIMENT_H
#define DEM_POST_EXPERIMENT_H

#include <stddef.h>

enum { EXP_STRAIN_AXIAL, EXP_STRAIN_RADIAL, EXP_STRAIN_VOLUMETRIC, EXP_STRESS_AXIAL, EXP_NCOLS };

typedef struct {
	size_t n;
	double *col[EXP_NCOLS]; /* [n] each; NULL for a column the file lacks; NaN if missing */
} experiment;

/* Read path; needs strain_axial and a stress column. Returns 0, or -1 with
 * err_set() naming the file, line and field. */
int experiment_read(const char *path, experiment *e);
void experiment_free(experiment *e);

#endif
