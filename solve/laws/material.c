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
