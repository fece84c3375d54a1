#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "lib/afile.h"
#include "lib/err.h"
#include "post/output.h"

void out_mkdir(const char *dir)
{
	char *p = xstrdup(dir);
	for (char *s = p + 1; *s; s++) {
		if (*s != '/')
			continue;
		*s = '\0';
		if (mkdir(p, 0777) != 0 && errno != EEXIST)
			fatal("%s: cannot create directory: %s", p, strerror(errno));
		*s = '/';
	}
	if (mkdir(p, 0777) != 0 && errno != EEXIST)
		fatal("%s: cannot create directory: %s", p, strerror(errno));
	struct stat st;
	if (stat(p, &st) != 0 || !S_ISDIR(st.st_mode))
		fatal("%s: not a directory", p);
	free(p);
}

char *out_dir(const char *opt, const char *input)
{
	char *dir;
	if (opt) {
		dir = xstrdup(opt);
	} else {
		const char *slash = strrchr(input, '/');
		dir = slash ? xstrdup(input) : xstrdup(".");
		if (slash)
			dir[slash - input + (slash == input)] = '\0';
	}
	out_mkdir(dir);
	return dir;
}

char *out_path(const char *dir, const char *name)
{
	size_t n = strlen(dir) + strlen(name) + 2;
	char *p = xmalloc(n);
	snprintf(p, n, "%s/%s", dir, name);
	return p;
}

void out_text_open(out_text *o, const char *path)
{
	o->path = xstrdup(path);
	if (afile_begin(path, o->tmp, sizeof o->tmp))
		fatal(NULL);
	o->f = fopen(o->tmp, "w");
	if (!o->f)
		fatal("%s: cannot create file: %s", o->tmp, strerror(errno));
}

void out_text_commit(out_text *o)
{
	int bad = ferror(o->f);
	if (fclose(o->f) != 0 || bad) {
		afile_discard(o->tmp);
		fatal("%s: cannot write (disk full?)", o->tmp);
	}
	if (afile_commit(o->tmp, o->path))
		fatal(NULL);
	free(o->path);
	o->f = NULL;
	o->path = NULL;
}

void out_csv_str(FILE *f, const char *s)
{
	if (!strpbrk(s, ",\"\n")) {
		fputs(s, f);
		return;
	}
	fputc('"', f);
	for (; *s; s++) {
		if (*s == '"')
			fputc('"', f);
		fputc(*s, f);
	}
	fputc('"', f);
}

void out_csv_num(FILE *f, double v)
{
	if (isfinite(v))
		fprintf(f, "%.10g", v);
}
