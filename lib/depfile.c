#include <stdio.h>

#include "lib/afile.h"
#include "lib/depfile.h"
#include "lib/err.h"

static void put_name(FILE *f, const char *s)
{
	for (; *s; s++) {
		if (*s == ' ' || *s == '#' || *s == '\\')
			fputc('\\', f);
		if (*s == '$')
			fputc('$', f);
		fputc(*s, f);
	}
}

int depfile_write(const char *path, const char *target, const char *const *deps, int n)
{
	char tmp[4096];
	if (afile_begin(path, tmp, sizeof tmp))
		return -1;
	FILE *f = fopen(tmp, "w");
	if (!f) {
		afile_discard(tmp);
		return err_set("%s: cannot write the dependency file", path);
	}
	put_name(f, target);
	fputc(':', f);
	for (int k = 0; k < n; k++)
		if (deps[k]) {
			fputc(' ', f);
			put_name(f, deps[k]);
		}
	fputc('\n', f);
	for (int k = 0; k < n; k++)
		if (deps[k]) {
			fputc('\n', f);
			put_name(f, deps[k]);
			fputs(":\n", f);
		}
	if (fclose(f) != 0) {
		afile_discard(tmp);
		return err_set("%s: cannot write the dependency file", path);
	}
	return afile_commit(tmp, path);
}
