/* Checkpoints of the engine state in run.h5 (/checkpoint). */
#ifndef DEM_CHECKPOINT_H
#define DEM_CHECKPOINT_H

#include <hdf5.h>

#include "solve/engine.h"

/* Write (or overwrite) /checkpoint in an open run file. On several ranks
 * every rank calls it, and rank 0, which has the file, writes each rank's
 * own rows (file: -1 elsewhere). Collective. */
int checkpoint_write(engine *e, hid_t file);
/* Restore the state of an engine freshly set up from the same assembly and
 * configuration. */
int checkpoint_read(engine *e, const char *path);
/* The same from an open run file (h5_open, or h5_open_image). */
int checkpoint_read_file(engine *e, hid_t file);
/* Whether the checkpoint of the run file at path has its particles in the
 * Morton order alone (*plain = 1: written before the walk, order.h, so
 * without its `order_walk` attribute), to set the engine up for it. */
int checkpoint_plain_order(const char *path, int *plain);

#endif
