#include <errno.h>
#include <math.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "lib/afile.h"
#include "lib/err.h"
#include "post/plot.h"

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

/* The figure's script beside it: gnuplot run in its directory draws it. */
static int write_script(const plot_data *d, const char *body, const char *path, const char *ext,
                        int width, int height)
{
	size_t n = strlen(path);
	char *gp = xmalloc(n + 4), tmp[4096];
	memcpy(gp, path, n + 1);
	strcpy(gp + (n - strlen(ext)), "gp");
	const char *slash = strrchr(path, '/');
	if (afile_begin(gp, tmp, sizeof tmp)) {
		free(gp);
		return -1;
	}
	FILE *f = fopen(tmp, "w");
	if (!f) {
		afile_discard(tmp);
		int rc = err_set("%s: cannot write: %s", gp, strerror(errno));
		free(gp);
		return rc;
	}
	fprintf(f,
	        "# %s, drawn by post: run `gnuplot %s` in this directory to draw it again\n"
	        "# (the style, the data and the plot commands are all below).\n",
	        slash ? slash + 1 : path, strrchr(gp, '/') ? strrchr(gp, '/') + 1 : gp);
	gnuplot_input(f, d, body, ext, slash ? slash + 1 : path, width, height);
	int bad = ferror(f);
	if (fclose(f) || bad) {
		afile_discard(tmp);
		int rc = err_set("%s: cannot write: %s", gp, strerror(errno));
		free(gp);
		return rc;
	}
	int rc = afile_commit(tmp, gp);
	free(gp);
	return rc;
}

int plot_draw(plot_data *d, const char *script, const char *path, int width, int height)
{
	fclose(d->f);
	const char *style = plot_script("style"), *body = plot_script(script);
	const char *ext = extension(path);
	char tmp[4096];
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
	/* A gnuplot that dies early must not kill post with SIGPIPE. */
	void (*old)(int) = signal(SIGPIPE, SIG_IGN);
	FILE *gp = popen("gnuplot", "w");
	if (!gp) {
		signal(SIGPIPE, old);
		free(d->text);
		afile_discard(tmp);
		return err_set("%s: cannot start gnuplot", path);
	}
	gnuplot_input(gp, d, body, ext, tmp, width, height);
	int status = pclose(gp);
	signal(SIGPIPE, old);
	if (status == -1 || !WIFEXITED(status) || WEXITSTATUS(status) != 0 ||
	    !figure_ok(tmp, ext)) {
		free(d->text);
		afile_discard(tmp);
		return err_set("%s: gnuplot failed to draw the figure (script share/gnuplot/%s.gp; "
		               "its message is above)",
		               path, script);
	}
	rc = write_script(d, body, path, ext, width, height);
	free(d->text);
	if (rc) {
		afile_discard(tmp);
		return -1;
	}
	return afile_commit(tmp, path);
}
