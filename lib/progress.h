/* A one-line progress report on stderr for long work: done/total, rate,
 * ETA and a caller-supplied detail (e.g. strain and stress). On a terminal
 * the line is redrawn in place; in a log (make, a batch job) the same line
 * is written once every log interval, as LAMMPS's thermo output is, so a
 * long run is never silent. */
#ifndef DEM_PROGRESS_H
#define DEM_PROGRESS_H

typedef struct {
	const char *what; /* "steps", "spheres", ... */
	double total;     /* expected amount of work, <= 0 if unknown */
	double t_start, t_last;
	int active; /* redrawn on a terminal */
	int log;    /* written as lines to a log */
} progress;

void progress_start(progress *p, const char *what, double total);
/* Redraw at most every 0.2 s. detail may be NULL. */
void progress_update(progress *p, double done, const char *detail);
/* Clear the line. */
void progress_end(progress *p);
/* Force the progress line on or off regardless of the terminal (tests). */
void progress_force(int on);
/* Seconds between two lines in a log (30 by default); 0 writes none. */
void progress_log_every(double s);

#endif
