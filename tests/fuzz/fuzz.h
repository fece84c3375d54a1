/* What the fuzz targets (tests/fuzz, built with -DDEM_FUZZ=ON; tools/fuzz
 * runs them) share: quiet libraries, and the check that a reader closed
 * every object it opened in the file it was given. */
#ifndef DEM_FUZZ_H
#define DEM_FUZZ_H

#include <hdf5.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

#include "lib/err.h"
#include "lib/h5.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int LLVMFuzzerInitialize(int *argc, char ***argv);

/* HDF5 prints nothing; messages name the target. */
static inline void fuzz_init(const char *name)
{
	err_program(name);
	h5_quiet();
}

/* Close a file opened by h5_open_image. An object of it left open by a
 * reader is a finding (a solve that restarts, or a post over many
 * snapshots, would keep it): abort so that libFuzzer reports the input. */
static inline void fuzz_close(hid_t f)
{
	if (H5Fget_obj_count(f, H5F_OBJ_ALL) != 1)
		abort();
	H5Fclose(f);
}

#endif
