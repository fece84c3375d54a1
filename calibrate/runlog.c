#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "calibrate/runlog.h"
#include "lib/afile.h"
#include "lib/err.h"

unsigned long long hash_bytes(unsigned long long h, const void *p, size_t n)
{
	const unsigned char *b = p;
	for (size_t k = 0; k < n; k++) {
		h ^= b[k];
		h *= 0x100000001b3ULL;
	}
	return h;
}

unsigned long long hash_file(const char *path)
{
	FILE *f = fopen(path, "rb");
	if (!f) {
		err_set("%s: cannot open: %s", path, strerror(errno));
		return 0;
	}
	unsigned long long h = HASH_START;
	char buf[1 << 16];
	size_t got;
	while ((got = fread(buf, 1, sizeof buf, f)) > 0)
		h = hash_bytes(h, buf, got);
	int bad = ferror(f);
	fclose(f);
	if (bad) {
		err_set("%s: cannot read", path);
		return 0;
	}
	return h;
}

static char *make_header(const cal_spec *sp)
{
	char *h = NULL;
	size_t len = 0;
	FILE *f = open_memstream(&h, &len);
	fputs("key,seq,phase,test,specimen", f);
	for (int k = 0; k < sp->nkey; k++)
		fprintf(f, ",%s", sp->key[k].name);
	fputs(",status", f);
	for (int k = 0; k < nquantities; k++)
		fprintf(f, ",%s", quantities[k].name);
	fputs(",wall", f);
	fclose(f);
	return h;
}

/* Split a CSV line in place into at most max fields (quotes as written by
 * put_field); returns the count. */
static int split(char *line, char **field, int max)
{
	int n = 0;
	char *p = line;
	for (;;) {
		if (n == max)
			return max + 1;
		char *out = p;
		field[n++] = p;
		if (*p == '"') {
			char *in = p + 1;
			for (; *in; in++) {
				if (*in == '"' && in[1] == '"')
					*out++ = '"', in++;
				else if (*in == '"')
					break;
				else
					*out++ = *in;
			}
			p = *in ? in + 1 : in;
		} else {
			while (*p && *p != ',')
				*out++ = *p++;
		}
		if (*p != ',') {
			*out = '\0';
			return n;
		}
		p++;
		*out = '\0';
	}
}

static double num(const char *s)
{
	if (!s[0])
		return NAN;
	char *end;
	double v = strtod(s, &end);
	return *end ? NAN : v;
}

static void put_num(FILE *f, double v)
{
	if (isfinite(v))
		fprintf(f, ",%.17g", v);
	else
		fputc(',', f);
}

static void put_field(FILE *f, const char *s)
{
	fputc(',', f);
	if (!strpbrk(s, ",\"\n")) {
		fputs(s, f);
		return;
	}
	fputc('"', f);
	for (; *s; s++) {
		if (*s == '\n')
			continue;
		if (*s == '"')
			fputc('"', f);
		fputc(*s, f);
	}
	fputc('"', f);
}

static void insert(runlog *l, const runrec *r)
{
	if (l->n == l->cap)
		l->r = xrealloc(l->r, (size_t)(l->cap = l->cap ? 2 * l->cap : 64) * sizeof *l->r);
	int at = l->n;
	while (at > 0 && l->r[at - 1].seq > r->seq)
		at--;
	memmove(l->r + at + 1, l->r + at, (size_t)(l->n - at) * sizeof *l->r);
	l->r[at] = *r;
	l->r[at].status = xstrdup(r->status);
	l->n++;
}

static int read_log(runlog *l, FILE *f)
{
	char *line = NULL;
	size_t cap = 0;
	ssize_t len;
	int lineno = 0, rc = 0;
	const int nfields = 5 + l->nkey + 1 + nquantities + 1;
	char **field = xmalloc((size_t)(nfields + 1) * sizeof *field);
	while (rc == 0 && (len = getline(&line, &cap, f)) > 0) {
		lineno++;
		line[strcspn(line, "\r\n")] = '\0';
		if (lineno == 1) {
			if (strcmp(line, l->header) != 0)
				rc = err_set(
				    "%s: written by another calibration (its columns are not "
				    "this one's): give another --out, or remove it",
				    l->path);
			continue;
		}
		if (split(line, field, nfields) != nfields) {
			rc = err_set("%s: line %d: expected %d fields", l->path, lineno, nfields);
			break;
		}
		runrec r;
		memset(&r, 0, sizeof r);
		snprintf(r.key, sizeof r.key, "%s", field[0]);
		r.seq = strtol(field[1], NULL, 10);
		snprintf(r.phase, sizeof r.phase, "%s", field[2]);
		snprintf(r.test, sizeof r.test, "%s", field[3]);
		snprintf(r.specimen, sizeof r.specimen, "%s", field[4]);
		for (int k = 0; k < l->nkey; k++)
			r.v[k] = num(field[5 + k]);
		r.status = field[5 + l->nkey];
		for (int k = 0; k < nquantities; k++)
			r.q[k] = num(field[6 + l->nkey + k]);
		r.wall = num(field[nfields - 1]);
		if (strlen(field[0]) != 16)
			rc = err_set("%s: line %d: '%s' is not a run key", l->path, lineno,
			             field[0]);
		else
			insert(l, &r);
	}
	free(field);
	free(line);
	return rc;
}

int runlog_open(runlog *l, const char *path, const cal_spec *sp)
{
	memset(l, 0, sizeof *l);
	l->path = xstrdup(path);
	l->nkey = sp->nkey;
	l->header = make_header(sp);
	FILE *f = fopen(path, "r");
	if (!f)
		return errno == ENOENT ? 0 : err_set("%s: cannot open: %s", path, strerror(errno));
	int rc = read_log(l, f);
	fclose(f);
	return rc;
}

const runrec *runlog_find(const runlog *l, const char *key)
{
	for (int k = 0; k < l->n; k++)
		if (strcmp(l->r[k].key, key) == 0)
			return &l->r[k];
	return NULL;
}

static int write_log(const runlog *l)
{
	char tmp[4200];
	if (afile_begin(l->path, tmp, sizeof tmp))
		return -1;
	FILE *f = fopen(tmp, "w");
	if (!f) {
		afile_discard(tmp);
		return err_set("%s: cannot create: %s", tmp, strerror(errno));
	}
	fprintf(f, "%s\n", l->header);
	for (int k = 0; k < l->n; k++) {
		const runrec *r = &l->r[k];
		fprintf(f, "%s,%ld", r->key, r->seq);
		put_field(f, r->phase);
		put_field(f, r->test);
		put_field(f, r->specimen);
		for (int j = 0; j < l->nkey; j++)
			put_num(f, r->v[j]);
		put_field(f, r->status);
		for (int j = 0; j < nquantities; j++)
			put_num(f, r->q[j]);
		put_num(f, r->wall);
		fputc('\n', f);
	}
	int bad = ferror(f);
	if (fclose(f) || bad) {
		afile_discard(tmp);
		return err_set("%s: cannot write: %s", tmp, strerror(errno));
	}
	return afile_commit(tmp, l->path);
}

int runlog_add(runlog *l, const runrec *r)
{
	insert(l, r);
	return write_log(l);
}

void runlog_free(runlog *l)
{
	for (int k = 0; k < l->n; k++)
		free(l->r[k].status);
	free(l->r);
	free(l->header);
	free(l->path);
	memset(l, 0, sizeof *l);
}
