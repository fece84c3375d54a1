#include <stdlib.h>
#include <string.h>

#include "lib/err.h"
#include "solve/laws/material.h"

int contact_conventions_parse(cfg *c, int *conventions)
{
	static const char *const words[] = {"solve", "yade", NULL};
	*conventions = CONTACT_SOLVE;
	cfg *ct = cfg_object_opt(c, "contact");
	if (!ct)
		return err_msg()[0] ? -1 : 0;
	return cfg_choice_or(ct, "conventions", conventions, words, CONTACT_SOLVE);
}

/* Strengths given in MPa where the laws read Pa: below a millionth of the
 * modulus, which no rock, concrete or cement has (the shipped materials'
 * strengths are 1e-4 to 1e-2 of it); 0, for none, is taken, and so is any
 * strength beside a modulus that is itself no material's (1e14 Pa, a
 * hundred times diamond's, and above). */
static int check_strengths(cfg *c)
{
	static const char *const keys[] = {
	    "tensile_strength", "shear_strength", "cohesion", "LCS1", "LCS2", "LCS3"};
	const char *ek = cfg_has(c, "E0") ? "E0" : cfg_has(c, "E") ? "E" : NULL;
	double E, v;
	if (!ek || cfg_number(c, ek, &E, "Pa", CFG_POS, INFINITY))
		return ek ? -1 : 0;
	for (size_t k = 0; k < sizeof keys / sizeof keys[0]; k++) {
		if (!cfg_has(c, keys[k]) || cfg_number(c, keys[k], &v, "Pa", 0, INFINITY))
			continue;
		if (v > 0 && v < 1e-6 * E && E < 1e14)
			return cfg_error(
			    c, keys[k],
			    "value %g Pa: expected at least a millionth of %s (%g Pa): "
			    "strengths are in Pa (%g MPa is %g Pa), 0 for none",
			    v, ek, E, v, 1e6 * v);
	}
	return 0;
}

int material_parse(cfg *c, material *m)
{
	memset(m, 0, sizeof *m);
	const char *name, *lawname;
	if (cfg_string(c, "name", &name) || cfg_string(c, "law", &lawname) ||
	    cfg_number(c, "density", &m->density, "kg/m^3", CFG_POS, INFINITY))
		return -1;
	m->law = law_find(lawname);
	if (!m->law)
		return cfg_error(c, "law", "%s", err_msg());
	cfg *ct = cfg_object_opt(c, "contact");
	if (!ct && err_msg()[0])
		return -1;
	m->friction = 0.5;
	m->platen_friction = -1;
	if (ct) {
		if (cfg_number_or(ct, "friction", &m->friction, 0.5, "", 0, INFINITY) ||
		    cfg_number_or(ct, "platen_friction", &m->platen_friction, -1, "", 0,
		                  INFINITY) ||
		    cfg_number_or(ct, "damping", &m->damping, 0, "fraction of critical", 0, 1) ||
		    cfg_number_or(ct, "E", &m->E, 0, "Pa", CFG_POS, INFINITY))
			return -1;
		if (m->E > 0 && cfg_number(ct, "nu", &m->nu, "", -0.99, 0.5))
			return -1;
	}
	if (contact_conventions_parse(c, &m->conventions))
		return -1;
	if (m->platen_friction < 0)
		m->platen_friction = m->friction;
	m->params = m->law->parse(c);
	if (!m->params)
		return -1;
	if (check_strengths(c)) {
		m->law->free(m->params);
		m->params = NULL;
		return -1;
	}
	m->name = xstrdup(name);
	return 0;
}

void material_free(material *m)
{
	if (m->law && m->params)
		m->law->free(m->params);
	free(m->name);
	memset(m, 0, sizeof *m);
}
