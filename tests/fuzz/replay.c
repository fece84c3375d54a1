/* The fuzz targets' inputs replayed without libFuzzer, in the test suite's
 * builds (the sanitizers' one too): every file of the directories (or the
 * files) named on the command line is handed once to the target's
 * LLVMFuzzerTestOneInput, linked in from fuzz_<target>.c. The committed
 * corpus holds the regression inputs of fixed findings, so a finding that
 * comes back fails the tests, not only a fuzzing session (tools/fuzz). */
#include <dirent.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "tests/fuzz/fuzz.h"

static int replay(const char *path)
{
	FILE *f = fopen(path, "rb");
	if (!f) {
		fprintf(stderr, "replay: %s: cannot read\n", path);
		return 1;
	}
	fseek(f, 0, SEEK_END);
	long n = ftell(f);
	rewind(f);
	uint8_t *data = malloc(n > 0 ? (size_t)n : 1);
	size_t got = data ? fread(data, 1, (size_t)n, f) : 0;
	fclose(f);
	if (!data || got != (size_t)n) {
		free(data);
		fprintf(stderr, "replay: %s: cannot read\n", path);
		return 1;
	}
	LLVMFuzzerTestOneInput(data, got);
	free(data);
	return 0;
}

int main(int argc, char **argv)
{
	LLVMFuzzerInitialize(&argc, &argv);
	int bad = 0, inputs = 0;
	for (int k = 1; k < argc; k++) {
		struct stat st;
		if (stat(argv[k], &st) == 0 && S_ISDIR(st.st_mode)) {
			DIR *d = opendir(argv[k]);
			for (struct dirent *e; d && (e = readdir(d));) {
				if (e->d_name[0] == '.')
					continue;
				char path[4096];
				snprintf(path, sizeof path, "%s/%s", argv[k], e->d_name);
				bad |= replay(path), inputs++;
			}
			if (d)
				closedir(d);
		} else {
			bad |= replay(argv[k]), inputs++;
		}
	}
	printf("replay: %d inputs\n", inputs);
	return bad || inputs == 0;
}
