#define _XOPEN_SOURCE 700 /* realpath */
#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "lib/err.h"
#include "lib/path.h"

char *path_beside(const char *file, const char *name)
{
	const char *slash = strrchr(file, '/');
	if (name[0] == '/' || !slash)
		return xstrdup(name);
	size_t dir = (size_t)(slash - file), n = dir + 1 + strlen(name) + 1;
	char *out = xmalloc(n);
	snprintf(out, n, "%.*s/%s", (int)dir, file, name);
	return out;
}

char *path_absolute(const char *name)
{
	char real[PATH_MAX], cwd[PATH_MAX];
	if (realpath(name, real))
		return xstrdup(real);
	if (name[0] == '/' || !getcwd(cwd, sizeof cwd))
		return xstrdup(name);
	size_t n = strlen(cwd) + strlen(name) + 2;
	char *out = xmalloc(n);
	snprintf(out, n, "%s/%s", strcmp(cwd, "/") ? cwd : "", name);
	return out;
}

char *path_shell_word(const char *name)
{
	if (name[0] && strspn(name, "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
	                            "0123456789/._-+,:@%=") == strlen(name))
		return xstrdup(name);
	/* Each ' as '\'' (close, an escaped quote, open again). */
	size_t n = 3;
	for (const char *c = name; *c; c++)
		n += *c == '\'' ? 4 : 1;
	char *out = xmalloc(n), *o = out;
	*o++ = '\'';
	for (const char *c = name; *c; c++)
		if (*c == '\'') {
			memcpy(o, "'\\''", 4);
			o += 4;
		} else {
			*o++ = *c;
		}
	*o++ = '\'';
	*o = '\0';
	return out;
}

/* The directory part of name ("." for none); returns what follows it. */
static const char *dir_of(const char *name, char *dir, size_t n)
{
	const char *slash = strrchr(name, '/');
	if (!slash)
		snprintf(dir, n, ".");
	else if (slash == name)
		snprintf(dir, n, "/");
	else
		snprintf(dir, n, "%.*s", (int)(slash - name), name);
	return slash ? slash + 1 : name;
}

/* name with its directory resolved (the name itself may not exist yet), or
 * name as given when the directory cannot be. */
static void canonical(const char *name, char *out, size_t n)
{
	char dir[PATH_MAX], real[PATH_MAX];
	const char *base = dir_of(name, dir, sizeof dir);
	if (realpath(dir, real))
		snprintf(out, n, "%s/%s", real, base);
	else
		snprintf(out, n, "%s", name);
}

int path_same(const char *a, const char *b)
{
	struct stat sa, sb;
	if (stat(a, &sa) == 0 && stat(b, &sb) == 0)
		return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
	char ca[2 * PATH_MAX], cb[2 * PATH_MAX];
	canonical(a, ca, sizeof ca);
	canonical(b, cb, sizeof cb);
	return strcmp(ca, cb) == 0;
}

int path_check_outputs(const path_role *out, int nout, const path_role *in, int nin)
{
	for (int k = 0; k < nout; k++) {
		if (!out[k].path)
			continue;
		struct stat st;
		if (!out[k].path[0] || (stat(out[k].path, &st) == 0 && S_ISDIR(st.st_mode)))
			return err_set("%s '%s': expected a file name%s", out[k].role, out[k].path,
			               out[k].path[0] ? " (this is a directory)" : "");
		for (int j = 0; j < nin + k; j++) {
			const path_role *o = j < nin ? &in[j] : &out[j - nin];
			if (o->path && path_same(out[k].path, o->path))
				return err_set(
				    "%s %s would overwrite %s %s: expected another file name",
				    out[k].role, out[k].path, o->role, o->path);
		}
	}
	return 0;
}

int path_check_writable(const path_role *out, int nout)
{
	for (int k = 0; k < nout; k++) {
		char dir[PATH_MAX];
		if (!out[k].path)
			continue;
		dir_of(out[k].path, dir, sizeof dir);
		struct stat st;
		if (stat(dir, &st) == 0 && !S_ISDIR(st.st_mode))
			return err_set("%s: cannot write in %s (%s): it is a file, not a directory",
			               out[k].path, dir, out[k].role);
		if (access(dir, W_OK | X_OK))
			return err_set("%s: cannot write in directory %s (%s): %s", out[k].path,
			               dir, out[k].role, strerror(errno));
	}
	return 0;
}
