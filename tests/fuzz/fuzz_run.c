/* Fuzz target: the bytes as a run file (run.h5) opened from memory, read as
 * post reads it: run_read (provenance, status, the embedded assembly,
 * bonds, history, the snapshot list, cracks), then every snapshot
 * (run_read_snapshot). Corpus: small complete and interrupted runs written
 * by solve (tests/fuzz/corpus/run). */
#include "lib/runfile.h"
#include "tests/fuzz/fuzz.h"

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
	(void)argc, (void)argv;
	fuzz_init("fuzz_run");
	return 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	hid_t f = h5_open_image(data, size, RUN_FORMAT);
	if (f < 0)
		return 0;
	dem_run r;
	if (run_read_file(f, &r) == 0) {
		for (size_t k = 0; k < r.nsnap; k++) {
			dem_snapshot s;
			if (run_read_snapshot_file(f, &r, k, &s) == 0)
				snapshot_free(&s);
		}
		run_free(&r);
	}
	fuzz_close(f);
	return 0;
}
