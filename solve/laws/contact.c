#include <math.h>

#include "solve/laws/contact.h"

void contact_constants(const material *m, const law_params *lp, double ri, double rj, double mi,
                       double mj, double d0, double k[3])
{
	law_pair q = {.ri = ri, .rj = rj, .mi = mi, .mj = mj, .d0 = d0};
	law_const c;
	m->law->constants(lp, &q, &c);
	if (m->E > 0) {
		c.kn = c.area * m->E / d0;
		c.ks = c.kn / (2 * (1 + m->nu));
	}
	k[0] = c.kn;
	k[1] = c.ks;
	k[2] = 2 * m->damping * sqrt(mi * mj / (mi + mj) * c.kn);
}
