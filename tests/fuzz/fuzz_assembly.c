/* Fuzz target: the bytes as an assembly file (assembly.h5) opened from
 * memory (h5_open_image, HDF5's core driver: nothing is written, so an
 * execution takes microseconds, not a file's creation), then read as
 * assembly_read reads it: format attributes, provenance, particles,
 * geometry, report. Corpus: tiny assemblies written by lattice-assembly
 * and pack (tests/fuzz/corpus/assembly). */
#include "lib/assembly.h"
#include "tests/fuzz/fuzz.h"

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
	(void)argc, (void)argv;
	fuzz_init("fuzz_assembly");
	return 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	hid_t f = h5_open_image(data, size, ASSEMBLY_FORMAT);
	if (f < 0)
		return 0;
	dem_assembly a;
	if (assembly_read_file(f, &a) == 0)
		assembly_free(&a);
	fuzz_close(f);
	return 0;
}
