/* The results of a study's points (post study --table): runs.csv,
 * study.csv and, with figures, response.png and curves.png in dir, the
 * study's output directory (share/doc/studies.md). */
#ifndef DEM_POST_STUDY_TABLE_H
#define DEM_POST_STUDY_TABLE_H

#include "post/study.h"

/* Collect the points' summary.json and curve.csv under dir; *failed is the
 * number of runs without a summary. 0, or -1 with err_set(). */
int study_table(const study *s, const char *dir, int figures, int *failed);

#endif
