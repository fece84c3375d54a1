#include <math.h>

#include "lib/vec3.h"
#include "post/frame.h"

void frame_of(frame *f, const dem_geometry *g)
{
	v3_copy(f->o, g->center);
	double len = v3_norm(g->axis);
	if (len > 0)
		v3_scale(f->a, g->axis, 1 / len);
	else
		f->a[0] = f->a[1] = 0, f->a[2] = 1;
	int least = 0;
	for (int k = 1; k < 3; k++)
		if (fabs(f->a[k]) < fabs(f->a[least]))
			least = k;
	double u[3] = {0, 0, 0};
	u[least] = 1;
	v3_reject(f->e1, u, f->a);
	v3_scale(f->e1, f->e1, 1 / v3_norm(f->e1));
	v3_cross(f->e2, f->a, f->e1);
}

void frame_cyl(const frame *f, const double p[3], double *h, double *rho, double *phi)
{
	double d[3], r[3];
	v3_sub(d, p, f->o);
	*h = v3_dot(d, f->a);
	v3_reject(r, d, f->a);
	*rho = v3_norm(r);
	double ang = atan2(v3_dot(d, f->e2), v3_dot(d, f->e1)) * POST_DEG;
	*phi = ang < 0 ? ang + 360 : ang;
}

double frame_theta(const frame *f, const double n[3])
{
	double c = fabs(v3_dot(n, f->a)) / v3_norm(n);
	return asin(fmin(c, 1.0)) * POST_DEG;
}
