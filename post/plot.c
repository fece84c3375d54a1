#include <errno.h>
#include <math.h>
#include <spawn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "lib/afile.h"
#include "lib/err.h"
#include "post/plot.h"

extern char **environ;

void plot_begin(plot_data *d)
{
	d->text = NULL;
	d->len = 0;
	d->f = open_memstream(&d->text, &d->len);
	if (!d->f)
		fatal("out of memory");
}

void plot_discard(plot_data *d)
{
	fclose(d->f);
	free(d->text);
}

void plot_quote(FILE *f, const char *s)
{
	fputc('\'', f);
	for (; *s; s++) {
		if (*s == '\'')
			fputc('\'', f); /* gnuplot doubles a quote inside '...' */
		fputc(*s, f);
	}
	fputc('\'', f);
}

void plot_num(FILE *f, double v)
{
	if (isfinite(v))
		fprintf(f, "%.10g", v);
	else
		fputs("NaN", f);
}

/* Is gnuplot on the PATH? */
static int have_gnuplot(void)
{
	const char *path = getenv("PATH");
	if (!path)
		return 0;
	char *copy = xstrdup(path), *save = NULL;
	int found = 0;
	for (char *dir = strtok_r(copy, ":", &save); dir && !found;
	     dir = strtok_r(NULL, ":", &save)) {
		char exe[4096];
		snprintf(exe, sizeof exe, "%s/gnuplot", dir);
		found = access(exe, X_OK) == 0;
	}
	free(copy);
	return found;
}

static const char *format = "png";
static char *footer;

int plot_set_format(const char *f)
{
	if (strcmp(f, "png") && strcmp(f, "pdf") && strcmp(f, "svg"))
		return err_set("--format %s: expected png, pdf or svg", f);
	format = f;
	return 0;
}

void plot_set_footer(const char *text)
{
	free(footer);
	footer = text ? xstrdup(text) : NULL;
}

char *plot_file(const char *dir, const char *name)
{
	size_t n = strlen(dir) + strlen(name) + 8;
	char *p = xmalloc(n);
	snprintf(p, n, "%s/%s.%s", dir, name, format);
	return p;
}

/* The extension of path (after its last dot), or "". */
static const char *extension(const char *path)
{
	const char *dot = strrchr(path, '.'), *slash = strrchr(path, '/');
	return dot && (!slash || dot > slash) ? dot + 1 : "";
}

/* The file gnuplot wrote begins as a file of its kind should and has some
 * substance. */
static int figure_ok(const char *path, const char *ext)
{
	static const unsigned char png[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
	char head[512] = {0};
	FILE *f = fopen(path, "rb");
	size_t n = f ? fread(head, 1, sizeof head - 1, f) : 0;
	if (f)
		fclose(f);
	int ok = !strcmp(ext, "png")   ? n >= 8 && memcmp(head, png, 8) == 0
	         : !strcmp(ext, "pdf") ? n >= 5 && memcmp(head, "%PDF-", 5) == 0
	                               : strstr(head, "<svg") != NULL;
	struct stat st;
	return ok && stat(path, &st) == 0 && st.st_size > 1000;
}

/* The gnuplot lines that open a figure: the terminal for ext, the output
 * file, the common style and the footer. */
static void prelude(FILE *f, const char *ext, const char *out, int width, int height)
{
	if (!strcmp(ext, "pdf"))
		fprintf(f, "set terminal pdfcairo size %gin,%gin enhanced font 'DejaVu Sans,8'\n",
		        width / 128.0, height / 128.0);
	else if (!strcmp(ext, "svg"))
		fprintf(f,
		        "set terminal svg size %d,%d enhanced font 'DejaVu Sans,11' "
		        "background rgb 'white'\n",
		        width, height);
	else
		fprintf(f, "set terminal pngcairo size %d,%d enhanced font 'DejaVu Sans,11'\n",
		        width, height);
	fputs("set encoding utf8\nset output ", f);
	plot_quote(f, out);
	fprintf(f, "\n%s\n", plot_script("style"));
	if (footer) {
		/* A line more at the foot, for the footer below the axis label. */
		fputs("set bmargin 4\nset label 1001 ", f);
		plot_quote(f, footer);
		fputs(" at screen 0.995, 0.008 right font ',7' tc rgb '#777777' noenhanced\n", f);
	}
}

/* gnuplot's whole input for a figure: the prelude, d's data, the script's
 * body and the closing of the output. */
static void gnuplot_input(FILE *f, const plot_data *d, const char *body, const char *ext,
                          const char *out, int width, int height)
{
	prelude(f, ext, out, width, height);
	fwrite(d->text, 1, d->len, f);
	fprintf(f, "\n%s\nset output\n", body);
}

/* The name of the script of the figure path (of extension ext): the same
 * with the extension "gp". */
static char *script_name(const char *path, const char *ext)
{
	size_t n = strlen(path);
	char *gp = xmalloc(n + 4);
	memcpy(gp, path, n + 1);
	strcpy(gp + (n - strlen(ext)), "gp");
	return gp;
}

/* gnuplot_input into the file name, written whole or not at all: its
 * temporary name (afile.h) into tmp, removed again on failure; first, a
 * comment line of head when not NULL. */
static int write_input(const char *name, char *tmp, size_t n, const char *head, const plot_data *d,
                       const char *body, const char *ext, const char *out, int width, int height)
{
	if (afile_begin(name, tmp, n))
		return -1;
	FILE *f = fopen(tmp, "w");
	if (!f) {
		afile_discard(tmp);
		return err_set("%s: cannot write: %s", name, strerror(errno));
	}
	if (head)
		fputs(head, f);
	gnuplot_input(f, d, body, ext, out, width, height);
	int bad = ferror(f);
	if (fclose(f) || bad) {
		afile_discard(tmp);
		return err_set("%s: cannot write: %s", name, strerror(errno));
	}
	return 0;
}

/* The figure's script beside it: gnuplot run in its directory draws it. */
static int write_script(const plot_data *d, const char *body, const char *path, const char *ext,
                        const char *gp, int width, int height)
{
	const char *slash = strrchr(path, '/'), *gslash = strrchr(gp, '/');
	char head[8192], tmp[4096];
	snprintf(head, sizeof head,
	         "# %s, drawn by post: run `gnuplot %s` in this directory to draw it again\n"
	         "# (the style, the data and the plot commands are all below).\n",
	         slash ? slash + 1 : path, gslash ? gslash + 1 : gp);
	if (write_input(gp, tmp, sizeof tmp, head, d, body, ext, slash ? slash + 1 : path, width,
	                height))
		return -1;
	return afile_commit(tmp, gp);
}

/* gnuplot on the file in: 0 and its wait status in *status (-1 when it
 * could not be waited for), or the error number when it did not start.
 * Given the file's name, not fed through a pipe: from a pipe gnuplot
 * reads a byte at a time, one system call each (half a second for the
 * half megabyte of data of a run's bond counts). */
static int run_gnuplot(const char *in, int *status)
{
	char prog[] = "gnuplot", *arg = xmalloc(strlen(in) + 3);
	/* not taken for an option */
	sprintf(arg, "%s%s", in[0] == '-' ? "./" : "", in);
	char *argv[] = {prog, arg, NULL};
	pid_t pid;
	*status = -1;
	int rc = posix_spawnp(&pid, prog, NULL, NULL, argv, environ);
	if (!rc)
		while (waitpid(pid, status, 0) < 0 && errno == EINTR)
			;
	free(arg);
	return rc;
}

int plot_draw(plot_data *d, const char *script, const char *path, int width, int height)
{
	fclose(d->f);
	const char *style = plot_script("style"), *body = plot_script(script);
	const char *ext = extension(path);
	char tmp[4096], in[4096];
	int rc = 0;
	if (!body || !style)
		rc = err_set("gnuplot script '%s' is not built into post", script);
	else if (strcmp(ext, "png") && strcmp(ext, "pdf") && strcmp(ext, "svg"))
		rc = err_set("%s: expected a .png, .pdf or .svg figure", path);
	else if (!have_gnuplot())
		rc = err_set(
		    "%s: gnuplot not found on the PATH: install gnuplot-nox (or use --no-png)",
		    path);
	else if (afile_begin(path, tmp, sizeof tmp))
		rc = -1;
	if (rc) {
		free(d->text);
		return -1;
	}
	/* gnuplot's input (drawing the figure's temporary name) where the
	 * script goes, under the script's temporary name until it is drawn. */
	char *gp = script_name(path, ext);
	rc = write_input(gp, in, sizeof in, NULL, d, body, ext, tmp, width, height);
	if (!rc) {
		int status, start = run_gnuplot(in, &status);
		afile_discard(in);
		if (start)
			rc = err_set("%s: cannot start gnuplot: %s", path, strerror(start));
		else if (status == -1 || !WIFEXITED(status) || WEXITSTATUS(status) != 0 ||
		         !figure_ok(tmp, ext))
			rc = err_set("%s: gnuplot failed to draw the figure (script "
			             "share/gnuplot/%s.gp; its message is above)",
			             path, script);
	}
	rc = rc || write_script(d, body, path, ext, gp, width, height);
	free(gp);
	free(d->text);
	if (rc) {
		afile_discard(tmp);
		return -1;
	}
	return afile_commit(tmp, path);
}
