/* Names beside the file that gives them, names as shell words, absolute
 * names, and make dependency files: the exact text make reads, escapes,
 * and the empty rule per prerequisite. */
#include <stdlib.h>
#include <unistd.h>

#include "lib/depfile.h"
#include "lib/path.h"
#include "tests/check.h"

static void beside(const char *file, const char *name, const char *want)
{
	char *got = path_beside(file, name);
	CHECK_STR(got, want);
	free(got);
}

static char *slurp(const char *path)
{
	FILE *f = fopen(path, "r");
	if (!f)
		return NULL;
	char *buf = calloc(1, 4096);
	fread(buf, 1, 4095, f);
	fclose(f);
	return buf;
}

int main(void)
{
	beside("share/cases/ucs.json", "../materials/cement.json",
	       "share/cases/../materials/cement.json");
	beside("ucs.json", "cement.json", "cement.json");
	beside("/a/b/ucs.json", "/m/cement.json", "/m/cement.json");
	beside("/ucs.json", "cement.json", "/cement.json");
	/* Names pasted into a shell command (solve's restart hint). */
	const char *words[][2] = {{"runs/demo-ucs/run.h5", "runs/demo-ucs/run.h5"},
	                          {"my runs/run 1.h5", "'my runs/run 1.h5'"},
	                          {"it's.h5", "'it'\\''s.h5'"},
	                          {"$HOME/r.h5", "'$HOME/r.h5'"},
	                          {"", "''"}};
	for (size_t k = 0; k < sizeof words / sizeof words[0]; k++) {
		char *w = path_shell_word(words[k][0]);
		CHECK_STR(w, words[k][1]);
		free(w);
	}

	/* A missing file's absolute name, from the root too. */
	char here[4096];
	CHECK(getcwd(here, sizeof here) != NULL);
	CHECK(chdir("/") == 0);
	char *abs = path_absolute("no-such-dir/x");
	CHECK_STR(abs, "/no-such-dir/x");
	free(abs);
	CHECK(chdir(here) == 0);

	char dir[] = "/tmp/dem-depfile-XXXXXX";
	CHECK(mkdtemp(dir) != NULL);
	char path[256];
	snprintf(path, sizeof path, "%s/run.d", dir);
	const char *deps[] = {"case.json", NULL, "my mat$.json"};
	CHECK(depfile_write(path, "runs/a/run.h5", deps, 3) == 0);
	char *text = slurp(path);
	CHECK(text != NULL);
	if (text)
		CHECK_STR(text, "runs/a/run.h5: case.json my\\ mat$$.json\n\ncase.json:\n\n"
		                "my\\ mat$$.json:\n");
	free(text);
	snprintf(path, sizeof path, "%s/run.d.tmp", dir);
	CHECK(access(path, F_OK) != 0);
	snprintf(path, sizeof path, "%s/run.d", dir);
	unlink(path);
	CHECK(depfile_write("/nonexistent-dir/run.d", "x", deps, 1) != 0);
	rmdir(dir);
	return check_done();
}
