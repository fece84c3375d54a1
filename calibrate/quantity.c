#include <stdio.h>
#include <string.h>

#include "calibrate/quantity.h"

const quantity quantities[] = {
    {"peak_stress", "peak axial stress", "Pa", "MPa", 1e-6, 1, 0, QTY_ANY},
    {"peak_deviator", "peak deviator stress", "Pa", "MPa", 1e-6, 1, 0, QTY_COMPRESSION},
    {"strain_at_peak", "axial strain at the peak", "-", "%", 100, 1, -1, QTY_ANY},
    {"strain_at_peak_deviator", "axial strain at the peak deviator", "-", "%", 100, 1, -1,
     QTY_COMPRESSION},
    {"young_modulus", "Young's modulus", "Pa", "GPa", 1e-9, 0, 1, QTY_COMPRESSION},
    {"poisson_ratio", "Poisson's ratio", "-", "", 1, 0, 0, QTY_COMPRESSION},
    {"bts_strength", "tensile strength 2P/(pi D t)", "Pa", "MPa", 1e-6, 1, 0, QTY_BTS},
    {"peak_force", "peak platen load", "N", "kN", 1e-3, 1, 0, QTY_ANY},
    {"bulk_modulus", "bulk modulus", "Pa", "GPa", 1e-9, 0, 1, QTY_HYDROSTATIC},
    {"residual_stress", "axial stress at the end", "Pa", "MPa", 1e-6, 1, 0, QTY_ANY},
    {"residual_deviator", "deviator stress at the end", "Pa", "MPa", 1e-6, 1, 0, QTY_COMPRESSION},
    {"pressure_final", "confining pressure at the end", "Pa", "MPa", 1e-6, 1, 0,
     QTY_COMPRESSION | QTY_HYDROSTATIC},
};
const int nquantities = (int)(sizeof quantities / sizeof quantities[0]);

int quantity_find(const char *name)
{
	for (int k = 0; k < nquantities; k++)
		if (strcmp(quantities[k].name, name) == 0)
			return k;
	return -1;
}

const char *quantity_list(void)
{
	static char list[1024];
	size_t len = 0;
	list[0] = '\0';
	for (int k = 0; k < nquantities; k++)
		len += (size_t)snprintf(list + len, sizeof list - len, "%s%s", k ? ", " : "",
		                        quantities[k].name);
	return list;
}

int quantity_positive(const quantity *q) { return q->a != 0 || q->b != 0; }

/* A target for a rock, a concrete or a cement (share/doc/calibrate.md): a
 * stress of 1 kPa or more, a modulus of 1 MPa or more, a strain of at most
 * 1; a value in MPa or GPa, or a strain in percent, falls outside. */
int quantity_plausible(const quantity *q, double v, char *buf, size_t n)
{
	int pa = strcmp(q->unit, "Pa") == 0;
	if (pa && q->a == 1 && q->b == 0 && v < 1e3) {
		snprintf(buf, n,
		         "%g Pa is too small for a stress of a rock, a concrete or a cement: "
		         "expected Pa, at least 1e3 (1 kPa); did you mean %ge6 (%g MPa)?",
		         v, v, v);
		return -1;
	}
	if (pa && q->a == 0 && q->b == 1 && v < 1e6) {
		/* Rocks have moduli of 0.1 to 150 GPa: 28 is in GPa, 4000 in MPa. */
		int gpa = v < 200;
		snprintf(buf, n,
		         "%g Pa is too small for a modulus of a rock, a concrete or a cement: "
		         "expected Pa, at least 1e6 (1 MPa); did you mean %ge%d (%g %s)?",
		         v, v, gpa ? 9 : 6, v, gpa ? "GPa" : "MPa");
		return -1;
	}
	if (strcmp(q->unit, "-") == 0 && q->a == 1 && q->b == -1 && v > 1) {
		snprintf(buf, n,
		         "a strain above 1 (100 %%): expected a fraction, not a percent; did you "
		         "mean %g (%g %%)?",
		         v / 100, v);
		return -1;
	}
	return 0;
}

int quantity_test_kind(const char *test)
{
	if (strcmp(test, "bts") == 0)
		return QTY_BTS;
	if (strcmp(test, "hydrostatic") == 0)
		return QTY_HYDROSTATIC;
	return QTY_COMPRESSION;
}
