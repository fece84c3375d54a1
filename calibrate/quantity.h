/* The quantities a target may name: figures of summary.json (post summary,
 * share/doc/post.md), with their unit, how they are shown, and how they
 * scale with the stresses and the stiffness of a law that has the exact
 * scaling (calibrate/scaling.h):
 *   q(s, k) = q(1, 1) s^a k^b
 * for every stress of the material multiplied by s and every stiffness by
 * k (a stress: a = 1, b = 0; a modulus: 0, 1; a strain: 1, -1; a ratio of
 * strains: 0, 0). */
#ifndef DEM_CALIBRATE_QUANTITY_H
#define DEM_CALIBRATE_QUANTITY_H

#include <stddef.h>

typedef struct {
	const char *name;  /* key of summary.json */
	const char *label; /* what it is, for reports */
	const char *unit;  /* SI unit of the value, "-" for none */
	const char *shown; /* unit in reports and figures */
	double factor;     /* value * factor is in `shown` */
	int a, b;          /* exponents of the stress and stiffness scales */
	int needs;         /* QTY_COMPRESSION, QTY_BTS, QTY_HYDROSTATIC, or a union */
} quantity;

enum { QTY_COMPRESSION = 1, QTY_BTS = 2, QTY_HYDROSTATIC = 4, QTY_ANY = 7 };

/* Every quantity, in the order of the run log's columns. */
extern const quantity quantities[];
extern const int nquantities;
enum { QTY_MAX = 16 };

/* Index of the quantity named name, or -1. */
int quantity_find(const char *name);
/* "peak_stress, strain_at_peak, ..." (a static buffer). */
const char *quantity_list(void);
/* Whether the quantity's value must be positive (it scales: a or b != 0),
 * so that its error is measured on a log scale. */
int quantity_positive(const quantity *q);
/* Whether a target's value v is plausible in the quantity's SI unit for a
 * rock, a concrete or a cement: a stress at least 1e3 Pa, a modulus at
 * least 1e6 Pa, a strain at most 1 (the others: any value). 0 when it
 * is; -1 with what is expected, and the value it may have meant, in buf. */
int quantity_plausible(const quantity *q, double v, char *buf, size_t n);
/* The kind of test (QTY_*) a case's "test" word names. */
int quantity_test_kind(const char *test);

#endif
