#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lib/err.h"
#include "post/experiment.h"

static const char *const names[EXP_NCOLS] = {"strain_axial", "strain_radial", "strain_volumetric",
                                             "stress_axial"};

void experiment_free(experiment *e)
{
	for (int c = 0; c < EXP_NCOLS; c++)
		free(e->col[c]);
	memset(e, 0, sizeof *e);
}

/* Split line at commas in place (no quoting: the fields are numbers and
 * names). Returns the number of fields. */
static int split(char *line, char **field, int max)
{
	int n = 0;
	line[strcspn(line, "\r\n")] = '\0';
	for (char *p = line; n < max;) {
		field[n++] = p;
		p = strchr(p, ',');
		if (!p)
			break;
		*p++ = '\0';
	}
	for (int k = 0; k < n; k++) {
		while (*field[k] == ' ' || *field[k] == '\t')
			field[k]++;
		size_t len = strlen(field[k]);
		while (len && (field[k][len - 1] == ' ' || field[k][len - 1] == '\t'))
			field[k][--len] = '\0';
	}
	return n;
}

enum { MAX_FIELDS = 64 };

/* A column this reader uses (others are ignored, duplicates too). */
static int used(const char *name)
{
	for (int c = 0; c < EXP_NCOLS; c++)
		if (strcmp(name, names[c]) == 0)
			return 1;
	return strcmp(name, "stress_axial_MPa") == 0;
}

int experiment_read(const char *path, experiment *e)
{
	memset(e, 0, sizeof *e);
	FILE *f = fopen(path, "r");
	if (!f)
		return err_set("%s: cannot read: %s", path, strerror(errno));
	int where[EXP_NCOLS]; /* field index of each column, -1 absent */
	double scale = 1;     /* 1e6 for stress_axial_MPa */
	int header = 0, nheader = 0, rc = 0;
	size_t cap = 0, lineno = 0;
	char line[8192], *field[MAX_FIELDS];
	while (!rc && fgets(line, sizeof line, f)) {
		lineno++;
		/* The byte order mark some spreadsheets write first. */
		if (lineno == 1 && strncmp(line, "\xEF\xBB\xBF", 3) == 0)
			memmove(line, line + 3, strlen(line + 3) + 1);
		if (line[0] == '#' || strspn(line, " \t\r\n") == strlen(line))
			continue;
		int nf = split(line, field, MAX_FIELDS);
		if (header && nf != nheader) {
			rc = err_set("%s: line %zu: %d fields, the header has %d (a decimal comma? "
			             "the separator is the comma, the decimal mark the point)",
			             path, lineno, nf, nheader);
			break;
		}
		if (!header) {
			header = 1, nheader = nf;
			for (int c = 0; c < EXP_NCOLS; c++)
				where[c] = -1;
			/* A column used twice: which of the two is meant is unknown. */
			for (int k = 0; !rc && k < nf; k++)
				for (int q = k + 1; !rc && q < nf; q++)
					if (used(field[k]) && strcmp(field[k], field[q]) == 0)
						rc = err_set(
						    "%s: line %zu: column '%s' is named twice "
						    "in the header (fields %d and %d): "
						    "expected each column once",
						    path, lineno, field[k], k + 1, q + 1);
			for (int k = 0; k < nf; k++) {
				for (int c = 0; c < EXP_NCOLS; c++)
					if (strcmp(field[k], names[c]) == 0)
						where[c] = k;
				if (strcmp(field[k], "stress_axial_MPa") == 0)
					where[EXP_STRESS_AXIAL] = k, scale = 1e6;
			}
			int both = 0;
			for (int k = 0; k < nf; k++)
				both += strcmp(field[k], "stress_axial") == 0 ||
				        strcmp(field[k], "stress_axial_MPa") == 0;
			if (rc)
				break;
			else if (both > 1)
				rc = err_set("%s: line %zu: the header names stress_axial and "
				             "stress_axial_MPa: expected one of them",
				             path, lineno);
			else if (where[EXP_STRAIN_AXIAL] < 0 || where[EXP_STRESS_AXIAL] < 0)
				rc = err_set("%s: line %zu: the header must name the columns "
				             "strain_axial and "
				             "stress_axial (Pa) or stress_axial_MPa",
				             path, lineno);
			for (int c = 0; !rc && c < EXP_NCOLS; c++)
				if (where[c] >= 0)
					e->col[c] = xmalloc(sizeof(double));
			continue;
		}
		if (e->n == cap) {
			cap = cap ? 2 * cap : 64;
			for (int c = 0; c < EXP_NCOLS; c++)
				if (e->col[c])
					e->col[c] = xrealloc(e->col[c], cap * sizeof(double));
		}
		for (int c = 0; !rc && c < EXP_NCOLS; c++) {
			if (where[c] < 0)
				continue;
			double v = NAN;
			if (where[c] < nf && field[where[c]][0]) {
				char *end;
				errno = 0;
				v = strtod(field[where[c]], &end);
				if (errno || *end || !isfinite(v))
					rc = err_set("%s: line %zu: column '%s': value '%s': "
					             "expected a number",
					             path, lineno,
					             c == EXP_STRESS_AXIAL && scale != 1
					                 ? "stress_axial_MPa"
					                 : names[c],
					             field[where[c]]);
			}
			e->col[c][e->n] = c == EXP_STRESS_AXIAL ? v * scale : v;
		}
		e->n++;
	}
	fclose(f);
	if (!rc && !header)
		rc = err_set("%s: empty: expected a header naming strain_axial and stress_axial",
		             path);
	if (!rc && e->n == 0)
		rc = err_set("%s: a header and no points", path);
	/* Stresses in Pa below a kilopascal are MPa written under the Pa
	 * column (laboratory tests of rock and concrete). */
	double top = 0;
	for (size_t k = 0; !rc && k < e->n; k++)
		if (isfinite(e->col[EXP_STRESS_AXIAL][k]))
			top = fmax(top, fabs(e->col[EXP_STRESS_AXIAL][k]));
	if (!rc && scale == 1 && top > 0 && top < 1e3)
		rc = err_set("%s: column 'stress_axial' (Pa): at most %g Pa: values in MPa go in a "
		             "column named stress_axial_MPa",
		             path, top);
	if (rc)
		experiment_free(e);
	return rc;
}
