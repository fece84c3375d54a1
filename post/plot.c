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

/* The file gnuplot wrote is a PNG image of some substance. */
static int png_ok(const char *path)
{
	static const unsigned char sig[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
	unsigned char head[8];
	FILE *f = fopen(path, "rb");
	int ok = f && fread(head, 1, 8, f) == 8 && memcmp(head, sig, 8) == 0;
	if (f)
		fclose(f);
	struct stat st;
	return ok && stat(path, &st) == 0 && st.st_size > 1000;
}

int plot_png(plot_data *d, const char *script, const char *png, int width, int height)
{
	fclose(d->f);
	const char *style = plot_script("style"), *body = plot_script(script);
	char tmp[4096];
	int rc = 0;
	if (!body || !style)
		rc = err_set("gnuplot script '%s' is not built into post", script);
	else if (!have_gnuplot())
		rc = err_set(
		    "%s: gnuplot not found on the PATH: install gnuplot-nox (or use --no-png)",
		    png);
	else if (afile_begin(png, tmp, sizeof tmp))
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
		return err_set("%s: cannot start gnuplot", png);
	}
	fprintf(gp, "set terminal pngcairo size %d,%d enhanced font 'DejaVu Sans,11'\n", width,
	        height);
	fputs("set encoding utf8\nset output ", gp);
	plot_quote(gp, tmp);
	fputc('\n', gp);
	fprintf(gp, "%s\n", style);
	fwrite(d->text, 1, d->len, gp);
	fprintf(gp, "\n%s\nset output\n", body);
	int status = pclose(gp);
	signal(SIGPIPE, old);
	free(d->text);
	if (status == -1 || !WIFEXITED(status) || WEXITSTATUS(status) != 0 || !png_ok(tmp)) {
		afile_discard(tmp);
		return err_set("%s: gnuplot failed to draw the figure (script share/gnuplot/%s.gp; "
		               "its message is above)",
		               png, script);
	}
	return afile_commit(tmp, png);
}
