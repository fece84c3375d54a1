/* Fuzz target: the bytes as an interrupted run file opened from memory,
 * restarted the way solve --restart does it (run.c's run_continue) up to
 * the first step: the run file read, its stored configuration parsed, an
 * engine set up (quietly, one thread) on its embedded assembly, and its
 * /checkpoint read into that engine. Corpus: runs of a few dozen spheres
 * stopped by --max-steps (tests/fuzz/corpus/checkpoint), so that an
 * execution stays well under a millisecond. */
#include "lib/runfile.h"
#include "solve/case.h"
#include "solve/checkpoint.h"
#include "solve/engine.h"
#include "tests/fuzz/fuzz.h"

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
	(void)argc, (void)argv;
	fuzz_init("fuzz_checkpoint");
	return 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	hid_t f = h5_open_image(data, size, RUN_FORMAT);
	if (f < 0)
		return 0;
	dem_run r;
	if (run_read_file(f, &r) == 0) {
		dem_case cs;
		if (case_parse_text(r.prov.config, H5_IMAGE_NAME, &cs) == 0) {
			engine e;
			if (engine_setup(&e, &cs, &r.assembly,
			                 &(engine_opts){.threads = 1, .quiet = 1}) == 0)
				checkpoint_read_file(&e, f);
			engine_free(&e);
			case_free(&cs);
		}
		run_free(&r);
	}
	fuzz_close(f);
	return 0;
}
