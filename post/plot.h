/* PNG figures drawn by gnuplot (pngcairo terminal, gnuplot-nox). A figure
 * is one of the scripts of share/gnuplot/, compiled into post, preceded by
 * share/gnuplot/style.gp and by the data it plots: post writes the data as gnuplot datablocks and
 * variables (each script lists the ones it reads), then pipes the whole to
 * gnuplot, which draws into a temporary file renamed when complete. */
#ifndef DEM_POST_PLOT_H
#define DEM_POST_PLOT_H

#include <stdio.h>

/* The text of share/gnuplot/<name>.gp, or NULL (generated at build time). */
const char *plot_script(const char *name);

/* A figure being prepared: write datablocks and variables to f. */
typedef struct {
	FILE *f;
	char *text;
	size_t len;
} plot_data;

void plot_begin(plot_data *d);
/* Drop a figure prepared in vain. */
void plot_discard(plot_data *d);
/* Draw script (a share/gnuplot name) with d's data into png, width x
 * height pixels. Frees d. Returns 0, or -1 with err_set(). */
int plot_png(plot_data *d, const char *script, const char *png, int width, int height);

/* Helpers writing gnuplot text: a single-quoted string literal, and a
 * number (NaN for a missing value, which gnuplot leaves out). */
void plot_quote(FILE *f, const char *s);
void plot_num(FILE *f, double v);

#endif
