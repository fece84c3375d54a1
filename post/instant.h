/* Choosing the snapshot for "the state at an instant": a snapshot index, a
 * time, an axial strain, an axial stress level (e.g. the macroscopic limit
 * stress sigma_a^l of Onate et al. 2015, sec. 9) or the peak axial stress.
 *
 * Strain, stress and peak are located on the finest series the run has:
 * the history table (columns t, strain_axial, stress_axial) when present,
 * else the snapshots' own attributes. A level is reached at the first row
 * where the series attains it (time interpolated linearly between rows);
 * the snapshot used is the one nearest in time to that instant, and the
 * description says so when the instant falls between two snapshots. */
#ifndef DEM_POST_INSTANT_H
#define DEM_POST_INSTANT_H

#include <stddef.h>

#include "lib/runfile.h"

typedef enum { AT_PEAK, AT_SNAPSHOT, AT_TIME, AT_STRAIN, AT_STRESS } instant_kind;

typedef struct {
	instant_kind kind;
	double value; /* s, strain, Pa; for AT_SNAPSHOT the index (negative: from the end) */
} instant;

/* Pick the snapshot of run r (read from path) for the instant. On success
 * *snap is its index and desc (size n) a one-line account of the choice.
 * Returns 0, or -1 with err_set() naming path and the value at fault. */
int instant_pick(const char *path, const dem_run *r, const instant *in, size_t *snap, char *desc,
                 size_t n);

/* Parse the instant options of a command: at most one of the texts may be
 * non-NULL (none: the peak). Returns 0, or -1 with err_set(). */
int instant_parse(instant *in, const char *snapshot, const char *time, const char *strain,
                  const char *stress);

#endif
