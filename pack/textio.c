#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lib/afile.h"
#include "lib/err.h"
#include "pack/textio.h"

int textio_write(const char *path, const double *x, const double *r, size_t n)
{
	char tmp[4096];
	if (afile_begin(path, tmp, sizeof tmp))
		return err_set("%s: file name too long", path);
	FILE *f = fopen(tmp, "w");
	if (!f) {
		afile_discard(tmp);
		return err_set("%s: cannot create: %s", path, strerror(errno));
	}
	fprintf(f, "#format x_y_z_r\n");
	for (size_t i = 0; i < n; i++)
		fprintf(f, "%.17g %.17g %.17g %.17g\n", x[3 * i], x[3 * i + 1], x[3 * i + 2], r[i]);
	int bad = ferror(f);
	if (fclose(f) != 0 || bad) {
		afile_discard(tmp);
		return err_set("%s: write error", path);
	}
	if (afile_commit(tmp, path)) {
		afile_discard(tmp);
		return -1;
	}
	return 0;
}

/* The line's four numbers, or -1 with a message naming file and line. */
static int parse_line(const char *path, long lineno, char *line, double v[4])
{
	char *p = line, *end;
	for (int k = 0; k < 4; k++) {
		errno = 0;
		v[k] = strtod(p, &end);
		if (end == p || errno || !isfinite(v[k]))
			return err_set("%s: line %ld: expected four numbers 'x y z r' (m)", path,
			               lineno);
		p = end;
	}
	p += strspn(p, " \t\r\n");
	if (*p) {
		p[strcspn(p, "\r\n")] = '\0';
		return err_set("%s: line %ld: unexpected '%.20s' after 'x y z r'", path, lineno, p);
	}
	if (!(v[3] > 0))
		return err_set("%s: line %ld: radius %g: expected a positive radius (m)", path,
		               lineno, v[3]);
	return 0;
}

int textio_read(const char *path, double **x, double **r, size_t *n)
{
	FILE *f = fopen(path, "r");
	if (!f)
		return err_set("%s: cannot open: %s", path, strerror(errno));
	size_t cap = 1024, m = 0, len = 0;
	double *xs = xmalloc(3 * cap * sizeof *xs), *rs = xmalloc(cap * sizeof *rs);
	char *line = NULL;
	long lineno = 0;
	int rc = 0;
	while (getline(&line, &len, f) > 0) {
		lineno++;
		char *p = line + strspn(line, " \t\r\n");
		if (*p == '\0' || *p == '#')
			continue;
		double v[4];
		if ((rc = parse_line(path, lineno, p, v)))
			break;
		if (m == cap) {
			cap *= 2;
			xs = xrealloc(xs, 3 * cap * sizeof *xs);
			rs = xrealloc(rs, cap * sizeof *rs);
		}
		memcpy(xs + 3 * m, v, 3 * sizeof *v);
		rs[m++] = v[3];
	}
	free(line);
	if (rc == 0 && ferror(f))
		rc = err_set("%s: read error", path);
	fclose(f);
	if (rc == 0 && m == 0)
		rc = err_set("%s: no spheres: expected lines 'x y z r' (m)", path);
	if (rc) {
		free(xs);
		free(rs);
		return -1;
	}
	*x = xs;
	*r = rs;
	*n = m;
	return 0;
}
