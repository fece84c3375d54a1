#include <stdio.h>
#include <string.h>

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
