/* The keys of the contact area and interaction range (area.h). */
#include "solve/laws/area.h"

int area_parse(cfg *m, area_keys *a)
{
	return cfg_number_or(m, "alpha", &a->alpha, 0, "", CFG_POS, INFINITY) ||
	       cfg_number_or(m, "beta", &a->beta, 0.10, "", 0, 1);
}

void area_setup(area_keys *a, const law_packing *pk)
{
	if (a->alpha == 0)
		a->alpha = pk->coordination > 0 ? 40 * pk->porosity / pk->coordination : 1;
}
