#include <math.h>

#include "lib/vec3.h"
#include "post/crackmap.h"

void specimen_of(specimen *sp, const dem_assembly *a)
{
	frame_of(&sp->f, &a->geom);
	double lo = INFINITY, hi = -INFINITY, rho_max = 0, rsum = 0;
	for (size_t k = 0; k < a->n; k++) {
		double h, rho, phi;
		frame_cyl(&sp->f, a->x + 3 * k, &h, &rho, &phi);
		lo = fmin(lo, h - a->r[k]);
		hi = fmax(hi, h + a->r[k]);
		rho_max = fmax(rho_max, rho + a->r[k]);
		rsum += a->r[k];
	}
	sp->bottom = a->n ? lo : 0;
	sp->height = a->n ? hi - lo : a->geom.height;
	sp->radius = a->geom.diameter > 0 ? 0.5 * a->geom.diameter : rho_max;
	sp->mean_radius = a->n ? rsum / (double)a->n : 0;
}

void crack_place_of(const specimen *sp, const dem_crack *c, crack_place *p)
{
	double h;
	frame_cyl(&sp->f, c->x, &h, &p->rho, &p->phi);
	p->height = h - sp->bottom;
	p->theta = frame_theta(&sp->f, c->normal);
}

void crackmap_count_data(FILE *f, const dem_run *r)
{
	long nt = 0, ns = 0;
	fputs("$count << EOD\n", f);
	fputs("0 0 0 0\n", f);
	for (size_t k = 0; k < r->ncracks; k++) {
		nt += r->cracks[k].mode == CRACK_TENSION;
		ns += r->cracks[k].mode == CRACK_SHEAR;
		fprintf(f, "%.10g %ld %ld %ld\n", 100 * r->cracks[k].strain_axial, nt, ns, nt + ns);
	}
	const double *e = run_column_data(r, "strain_axial");
	if (e && r->nrows)
		fprintf(f, "%.10g %ld %ld %ld\n", 100 * e[r->nrows - 1], nt, ns, nt + ns);
	fprintf(f, "EOD\ncracks = %zu\n", r->ncracks);
}
