/* What a calibration leaves in its output directory (share/doc/calibrate.md,
 * "Outputs"): the calibrated material, ready for solve (material.json); the
 * report, as text (report.md, also printed) and JSON (report.json): target
 * against achieved, on the search specimens and the confirming ones, the
 * parameters, the sensitivities, the warnings and the diagnosis; the path
 * of the parameters (path.csv); the figures (convergence.png,
 * targets.png, drawn by gnuplot through post's scripts). */
#ifndef DEM_CALIBRATE_REPORT_H
#define DEM_CALIBRATE_REPORT_H

#include "calibrate/eval.h"
#include "calibrate/search.h"
#include "calibrate/sensitivity.h"

enum { REPORT_MAX_NOTES = 64 };

typedef struct {
	const cal_spec *sp;
	const evaluator *e;
	const search_result *r;
	const sensitivity *sens;
	const outcome *confirm;        /* NULL when not run */
	double wall;                   /* s, the whole calibration */
	double search_wall;            /* s, to the end of the search */
	int met;                       /* every target met on the search specimens */
	const double *truth;           /* a blind recovery's true key values, or NULL */
	char *notes[REPORT_MAX_NOTES]; /* warnings and diagnosis */
	int nnotes;
} report;

/* Where the value v of free key p lies: 0 within its bounds, -1 or 1 at
 * its lower or upper bound (within 1 % of the range, of the logarithms on
 * a log scale), -2 or 2 below or above them. */
int report_bound(const cal_key *p, double v);
/* The warnings and the diagnosis (report->notes). */
void report_diagnose(report *rp);
/* Write material.json, report.md, report.json and path.csv in dir, and
 * print the report on stdout. 0, or -1 with err_set(). */
int report_write(const report *rp, const char *dir);
/* The figures; 0, or -1 with err_set() (gnuplot missing or failing). */
int report_plots(const report *rp, const char *dir);
void report_free(report *rp);

#endif
