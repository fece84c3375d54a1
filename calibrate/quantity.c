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

int quantity_test_kind(const char *test)
{
	if (strcmp(test, "bts") == 0)
		return QTY_BTS;
	if (strcmp(test, "hydrostatic") == 0)
		return QTY_HYDROSTATIC;
	return QTY_COMPRESSION;
}
