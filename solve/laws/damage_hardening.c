/* The material keys of the damage and hardening core, which the local model
 * (onate) and the exponential law share; their meaning, unit, default and
 * source are in share/doc/materials.md. */
#include "solve/laws/damage_hardening.h"

int dh_parse(cfg *m, dh_params *q)
{
	if (cfg_number(m, "E0", &q->E0, "Pa", CFG_POS, INFINITY) ||
	    cfg_number(m, "nu", &q->nu, "", 0, 0.5) ||
	    cfg_number(m, "tensile_strength", &q->sigma_t, "Pa", 0, INFINITY) ||
	    cfg_number(m, "delta_n", &q->delta_n, "", 0, INFINITY) ||
	    cfg_number_or(m, "xi", &q->xi, 0.9, "", 0, 1))
		return -1;
	q->eps_t = q->sigma_t / q->E0;
	return 0;
}
