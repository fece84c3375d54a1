#include <dirent.h>
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

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

/* Remove dir's files that go(name) accepts (all when go is NULL). */
static void remove_files(const char *dir, int (*go)(const char *name))
{
	DIR *d = opendir(dir);
	if (!d)
		fatal("%s: cannot read directory: %s", dir, strerror(errno));
	for (struct dirent *e; (e = readdir(d));) {
		if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, "..") || (go && !go(e->d_name)))
			continue;
		char *path = out_path(dir, e->d_name);
		if (unlink(path) != 0 && errno != ENOENT)
			fatal("%s: cannot remove: %s", path, strerror(errno));
		free(path);
	}
	closedir(d);
}

char *out_series_begin(const char *dir, const char *name)
{
	size_t n = strlen(name) + 6;
	char *base = xmalloc(n);
	snprintf(base, n, ".%s.new", name);
	char *stage = out_path(dir, base);
	free(base);
	/* What a killed run left. */
	if (access(stage, F_OK) == 0) {
		remove_files(stage, NULL);
		if (rmdir(stage) != 0)
			fatal("%s: cannot remove: %s", stage, strerror(errno));
	}
	out_mkdir(stage);
	/* an interrupted post leaves no staged files */
	if (afile_stage_dir(stage))
		fatal(NULL);
	return stage;
}

void out_series_commit(const char *dir, const char *stage, const char *marker,
                       int (*ours)(const char *name))
{
	char *mark = out_path(dir, marker), *staged_mark = out_path(stage, marker);
	/* from here on the staged files are the series' own (a run killed
	 * meanwhile leaves no marker: an incomplete series) */
	afile_stage_dir(NULL);
	if (unlink(mark) != 0 && errno != ENOENT)
		fatal("%s: cannot remove: %s", mark, strerror(errno));
	afile_sync_dir(dir);
	remove_files(dir, ours);
	DIR *d = opendir(stage);
	if (!d)
		fatal("%s: cannot read directory: %s", stage, strerror(errno));
	for (struct dirent *e; (e = readdir(d));) {
		if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, "..") ||
		    !strcmp(e->d_name, marker))
			continue;
		char *from = out_path(stage, e->d_name), *to = out_path(dir, e->d_name);
		if (rename(from, to) != 0)
			fatal("%s: cannot rename to %s: %s", from, to, strerror(errno));
		free(from), free(to);
	}
	closedir(d);
	afile_sync_dir(dir);
	if (rename(staged_mark, mark) != 0)
		fatal("%s: cannot rename to %s: %s", staged_mark, mark, strerror(errno));
	afile_sync_dir(dir);
	if (rmdir(stage) != 0)
		fatal("%s: cannot remove: %s", stage, strerror(errno));
	free(mark), free(staged_mark);
}

int out_series_name(const char *name, const char *part, const char *ext)
{
	size_t n = strlen(part);
	if (strncmp(name, part, n) != 0)
		return 0;
	const char *rest = name + n;
	if (!strcmp(rest, ".pvd"))
		return 1;
	if (*rest++ != '_')
		return 0;
	size_t d = strspn(rest, "0123456789");
	return d > 0 && rest[d] == '.' && !strcmp(rest + d + 1, ext);
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
