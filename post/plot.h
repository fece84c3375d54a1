/* Figures drawn by gnuplot (gnuplot-nox): PNG (pngcairo), PDF (pdfcairo) or
 * SVG, by the figure file's extension. A figure is one of the scripts of
 * share/gnuplot/, compiled into post, preceded by share/gnuplot/style.gp
 * and by the data it plots: post writes the data as gnuplot datablocks and
 * variables (each script lists the ones it reads), then pipes the whole to
 * gnuplot, which draws into a temporary file renamed when complete. The
 * same whole is left beside the figure as NAME.gp, so `gnuplot NAME.gp` in
 * that directory draws it again, restyled as the user edits it. */
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
/* The figure format of plot_file: "png" (default), "pdf" or "svg"; 0, or
 * -1 with err_set() for another. */
int plot_set_format(const char *format);
/* A line of small print at the foot of every figure (the case and the
 * material), so that a figure copied out of its folder stays identifiable;
 * NULL for none. */
void plot_set_footer(const char *text);
/* DIR/NAME.<format> (malloc'd). */
char *plot_file(const char *dir, const char *name);
/* Draw script (a share/gnuplot name) with d's data into path, a .png, .pdf
 * or .svg file, width x height pixels (PDF: the same size at 128 pixels
 * per inch), and write the script beside it (path with .gp). Frees d.
 * Returns 0, or -1 with err_set(). */
int plot_draw(plot_data *d, const char *script, const char *path, int width, int height);

/* Helpers writing gnuplot text: a single-quoted string literal, and a
 * number (NaN for a missing value, which gnuplot leaves out). */
void plot_quote(FILE *f, const char *s);
void plot_num(FILE *f, double v);

#endif
