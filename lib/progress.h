/* A one-line progress report on stderr for long work: done/total, rate,
 * ETA and a caller-supplied detail (e.g. strain and stress). Quiet when
 * stderr is not a terminal, so logs and CI output stay clean. */
#ifndef DEM_PROGRESS_H
#define DEM_PROGRESS_H

typedef struct {
	const char *what; /* "steps", "spheres", ... */
	double total;     /* expected amount of work, <= 0 if unknown */
	double t_start, t_last;
	int active;
} progress;

void progress_start(progress *p, const char *what, double total);
/* Redraw at most every 0.2 s. detail may be NULL. */
void progress_update(progress *p, double done, const char *detail);
/* Clear the line. */
void progress_end(progress *p);
/* Force the progress line on or off regardless of the terminal (tests). */
void progress_force(int on);

#endif
