/* The material keys of the damage and hardening core, which the local model
 * (onate) and the exponential law share; their meaning, unit, default and
 * source are in share/doc/materials.md. */
#include "solve/laws/damage_hardening.h"

/* "xi" defaults to 0.9 because that is the value of Oñate et al. (seeds/000
 * Sect. 5.1, after Eq. 28: "In our work we have taken xi = 0.9"): xi is
 * their contact damping of Eq. 27-30, a fraction of the critical damping
 * per unit length (xi / r_c), and the exponential law takes its elastic
 * constants and damping from the same model. The linear law's "xi" is
 * another quantity, off by default (linear.c). */
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
