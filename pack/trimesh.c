/* Measures of a boundary triangulation and the closest point on a
 * triangle (pack/trimesh_close.cpp checks and orients it).
 *
 * The enclosed volume V = sum over triangles of a.(b x c)/6 (divergence
 * theorem) is positive for a closed surface whose normals point out. Volume
 * and area are summed here rather than by CGAL's PMP::volume and PMP::area,
 * which evaluate them in another order: the volume of every shipped
 * geometry would change in its last bits, and with it the sizes scaled to
 * --count and the written file. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lib/vec3.h"
#include "pack/trimesh.h"

void trimesh_measure(const trimesh *m, double *volume, double *area, double bmin[3], double bmax[3])
{
	double v6 = 0, a2 = 0;
	for (size_t t = 0; t < m->ntri; t++) {
		const int32_t *v = m->tri + 3 * t;
		double e1[3], e2[3], n[3];
		v3_sub(e1, m->vert + 3 * v[1], m->vert + 3 * v[0]);
		v3_sub(e2, m->vert + 3 * v[2], m->vert + 3 * v[0]);
		v3_cross(n, e1, e2);
		a2 += v3_norm(n);
		double bc[3];
		v3_cross(bc, m->vert + 3 * v[1], m->vert + 3 * v[2]);
		v6 += v3_dot(m->vert + 3 * v[0], bc);
	}
	*volume = v6 / 6;
	*area = a2 / 2;
	for (int k = 0; k < 3; k++) {
		bmin[k] = m->nvert ? m->vert[k] : 0;
		bmax[k] = bmin[k];
	}
	for (size_t i = 0; i < m->nvert; i++)
		for (int k = 0; k < 3; k++) {
			bmin[k] = fmin(bmin[k], m->vert[3 * i + k]);
			bmax[k] = fmax(bmax[k], m->vert[3 * i + k]);
		}
}

void trimesh_free(trimesh *m)
{
	free(m->vert);
	free(m->tri);
	memset(m, 0, sizeof *m);
}

/* Ericson, Real-Time Collision Detection (2005), 5.1.5: the Voronoi region
 * of p among the triangle's vertices, edges and face, by barycentric signs. */
void trimesh_closest_point(const double a[3], const double b[3], const double c[3],
                           const double p[3], double q[3])
{
	double ab[3], ac[3], ap[3], bp[3], cp[3];
	v3_sub(ab, b, a);
	v3_sub(ac, c, a);
	v3_sub(ap, p, a);
	double d1 = v3_dot(ab, ap), d2 = v3_dot(ac, ap);
	if (d1 <= 0 && d2 <= 0) {
		v3_copy(q, a);
		return;
	}
	v3_sub(bp, p, b);
	double d3 = v3_dot(ab, bp), d4 = v3_dot(ac, bp);
	if (d3 >= 0 && d4 <= d3) {
		v3_copy(q, b);
		return;
	}
	double vc = d1 * d4 - d3 * d2;
	if (vc <= 0 && d1 >= 0 && d3 <= 0) {
		v3_copy(q, a);
		v3_axpy(q, ab, d1 / (d1 - d3));
		return;
	}
	v3_sub(cp, p, c);
	double d5 = v3_dot(ab, cp), d6 = v3_dot(ac, cp);
	if (d6 >= 0 && d5 <= d6) {
		v3_copy(q, c);
		return;
	}
	double vb = d5 * d2 - d1 * d6;
	if (vb <= 0 && d2 >= 0 && d6 <= 0) {
		v3_copy(q, a);
		v3_axpy(q, ac, d2 / (d2 - d6));
		return;
	}
	double va = d3 * d6 - d5 * d4;
	if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) {
		double bc[3];
		v3_sub(bc, c, b);
		v3_copy(q, b);
		v3_axpy(q, bc, (d4 - d3) / ((d4 - d3) + (d5 - d6)));
		return;
	}
	double den = 1 / (va + vb + vc);
	v3_copy(q, a);
	v3_axpy(q, ab, vb * den);
	v3_axpy(q, ac, vc * den);
}
