/* Fuzz target: the bytes as the JSON text of a case through the case reader
 * (case_parse_text, what solve --restart does with a run file's stored
 * configuration): cJSON, every cfg lookup, the material and its contact
 * law's parameters, the loading program. Corpus: the shipped cases with
 * their materials inline (tests/fuzz/corpus/cfg). */
#include <string.h>

#include "solve/case.h"
#include "tests/fuzz/fuzz.h"

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
	(void)argc, (void)argv;
	fuzz_init("fuzz_cfg");
	return 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	char *text = xmalloc(size + 1);
	memcpy(text, data, size);
	text[size] = '\0';
	dem_case c;
	if (case_parse_text(text, "fuzz.json", &c) == 0)
		case_free(&c);
	free(text);
	return 0;
}
