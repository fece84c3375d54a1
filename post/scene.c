#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lib/afile.h"
#include "lib/err.h"
#include "lib/vec3.h"
#include "post/scene.h"

/* Each thread's (post vtk writes frames on several). */
static _Thread_local const vtkio_array *fields;
static _Thread_local int nfields;

void scene_fields(const vtkio_array *fd, int n)
{
	fields = fd;
	nfields = n;
}

void scene_put(const char *path, const vtkio_mesh *mesh)
{
	vtkio_mesh with = *mesh, *m = &with;
	with.fdata = fields;
	with.nfdata = nfields;
	char tmp[4096];
	if (afile_begin(path, tmp, sizeof tmp))
		fatal(NULL);
	size_t len = strlen(path);
	int vtu = len > 4 && strcmp(path + len - 4, ".vtu") == 0;
	int rc = vtu ? vtkio_write_vtu(tmp, m) : vtkio_write_vtp(tmp, m);
	if (rc) {
		afile_discard(tmp);
		fatal("%s: cannot write VTK file (disk full or directory not writable?)", tmp);
	}
	if (afile_commit(tmp, path))
		fatal(NULL);
}

void scene_disc(double *x, const double c[3], const double normal[3], double r, int n)
{
	/* u: the coordinate axis least aligned with the normal, made normal to it */
	int least = 0;
	for (int k = 1; k < 3; k++)
		if (fabs(normal[k]) < fabs(normal[least]))
			least = k;
	double e[3] = {0, 0, 0}, u[3], w[3];
	e[least] = 1;
	v3_reject(u, e, normal);
	v3_scale(u, u, 1 / v3_norm(u));
	v3_cross(w, normal, u);
	for (int k = 0; k < n; k++) {
		double a = 2 * POST_PI * k / n, *p = x + 3 * k;
		v3_copy(p, c);
		v3_axpy(p, u, r * cos(a));
		v3_axpy(p, w, r * sin(a));
	}
}

/* The stress of every particle from its bonds' forces (scene.h), [n][9]
 * row-major, and its mean and von Mises invariants. */
static void particle_stress(const dem_assembly *a, const dem_bonds *b, const dem_snapshot *s,
                            double *sig, double *mean, double *mises)
{
	size_t n = a->n;
	memset(sig, 0, 9 * n * sizeof *sig);
	for (size_t k = 0; k < b->n; k++) {
		int32_t i = b->i[k], j = b->j[k];
		double nv[3], f[3], d;
		v3_sub(nv, s->x + 3 * j, s->x + 3 * i);
		d = v3_norm(nv);
		if (!(d > 0))
			continue;
		v3_scale(nv, nv, 1 / d);
		/* The force on i: fn along n (tension positive) and the shear force. */
		for (int c = 0; c < 3; c++)
			f[c] = s->fn[k] * nv[c] + s->fs[3 * k + c];
		double ai = d * a->r[i] / (a->r[i] + a->r[j]), aj = d - ai;
		for (int p = 0; p < 3; p++)
			for (int q = 0; q < 3; q++) {
				/* l_i = ai n with f; l_j = -aj n with -f. */
				sig[9 * i + 3 * p + q] += ai * nv[p] * f[q];
				sig[9 * j + 3 * p + q] += aj * nv[p] * f[q];
			}
	}
	for (size_t k = 0; k < n; k++) {
		double v = 4.0 / 3.0 * POST_PI * a->r[k] * a->r[k] * a->r[k], *t = sig + 9 * k;
		for (int c = 0; c < 9; c++)
			t[c] /= v;
		double p = (t[0] + t[4] + t[8]) / 3, j2 = 0;
		for (int r = 0; r < 3; r++)
			for (int c = 0; c < 3; c++) {
				double sym = 0.5 * (t[3 * r + c] + t[3 * c + r]) - (r == c ? p : 0);
				j2 += 0.5 * sym * sym;
			}
		mean[k] = p;
		mises[k] = sqrt(3 * j2);
	}
}

void scene_particles(const char *path, const dem_assembly *a, const dem_bonds *b,
                     const dem_snapshot *s)
{
	size_t n = a->n;
	int32_t *id = xmalloc(n * sizeof *id);
	for (size_t k = 0; k < n; k++)
		id[k] = (int32_t)k;
	vtkio_array arr[11] = {
	    {"id", VTKIO_I32, 1, id},
	    {"radius", VTKIO_F64, 1, a->r},
	    {"material", VTKIO_I32, 1, a->material},
	};
	int narr = 3;
	double *disp = NULL, *damage = NULL, *sig = NULL, *mean = NULL, *mises = NULL;
	int32_t *broken = NULL;
	if (s) {
		disp = xmalloc(3 * n * sizeof *disp);
		for (size_t k = 0; k < 3 * n; k++)
			disp[k] = s->x[k] - a->x[k];
		damage = xcalloc(n, sizeof *damage);
		broken = xcalloc(n, sizeof *broken);
		int32_t *nb = xcalloc(n, sizeof *nb);
		for (size_t k = 0; k < b->n; k++) {
			int gone = s->state[k] >= BOND_BROKEN_TENSION;
			double d = gone ? 1 : fmax(s->damage_n[k], s->damage_s[k]);
			int32_t ends[2] = {b->i[k], b->j[k]};
			for (int e = 0; e < 2; e++) {
				damage[ends[e]] += d;
				broken[ends[e]] += gone;
				nb[ends[e]]++;
			}
		}
		for (size_t k = 0; k < n; k++)
			if (nb[k])
				damage[k] /= nb[k];
		free(nb);
		arr[narr++] = (vtkio_array){"displacement", VTKIO_F64, 3, disp};
		arr[narr++] = (vtkio_array){"velocity", VTKIO_F64, 3, s->v};
		arr[narr++] = (vtkio_array){"angular_velocity", VTKIO_F64, 3, s->w};
		arr[narr++] = (vtkio_array){"damage", VTKIO_F64, 1, damage};
		arr[narr++] = (vtkio_array){"broken_bonds", VTKIO_I32, 1, broken};
		sig = xmalloc(9 * n * sizeof *sig);
		mean = xmalloc(n * sizeof *mean);
		mises = xmalloc(n * sizeof *mises);
		particle_stress(a, b, s, sig, mean, mises);
		arr[narr++] = (vtkio_array){"stress", VTKIO_F64, 9, sig};
		arr[narr++] = (vtkio_array){"stress_mean", VTKIO_F64, 1, mean};
		arr[narr++] = (vtkio_array){"stress_von_mises", VTKIO_F64, 1, mises};
	}
	vtkio_mesh m = {
	    .npoints = n, .x = s ? s->x : a->x, .kind = VTKIO_VERTS, .pdata = arr, .npdata = narr};
	scene_put(path, &m);
	free(id), free(disp), free(damage), free(broken), free(sig), free(mean), free(mises);
}

void scene_bonds(const char *path, const dem_bonds *b, const dem_snapshot *s)
{
	size_t nb = b->n;
	int64_t *off = xmalloc((nb + 1) * sizeof *off), *conn = xmalloc(2 * nb * sizeof *conn);
	int32_t *id = xmalloc(nb * sizeof *id);
	double *fsn = xmalloc(nb * sizeof *fsn), *dmg = xmalloc(nb * sizeof *dmg);
	for (size_t k = 0; k < nb; k++) {
		off[k] = 2 * (int64_t)k;
		conn[2 * k] = b->i[k];
		conn[2 * k + 1] = b->j[k];
		id[k] = (int32_t)k;
		fsn[k] = v3_norm(s->fs + 3 * k);
		dmg[k] =
		    s->state[k] >= BOND_BROKEN_TENSION ? 1 : fmax(s->damage_n[k], s->damage_s[k]);
	}
	off[nb] = 2 * (int64_t)nb;
	vtkio_array arr[] = {
	    {"id", VTKIO_I32, 1, id},
	    {"state", VTKIO_U8, 1, s->state},
	    {"fn", VTKIO_F64, 1, s->fn},
	    {"fs", VTKIO_F64, 3, s->fs},
	    {"fs_magnitude", VTKIO_F64, 1, fsn},
	    {"damage_n", VTKIO_F64, 1, s->damage_n},
	    {"damage_s", VTKIO_F64, 1, s->damage_s},
	    {"damage", VTKIO_F64, 1, dmg},
	    {"area", VTKIO_F64, 1, b->area},
	};
	vtkio_mesh m = {.npoints = s->n,
	                .x = s->x,
	                .kind = VTKIO_LINES,
	                .ncells = nb,
	                .offsets = off,
	                .conn = conn,
	                .cdata = arr,
	                .ncdata = sizeof arr / sizeof arr[0]};
	scene_put(path, &m);
	free(off), free(conn), free(id), free(fsn), free(dmg);
}

enum { PLATEN_SIDES = 64 };

void scene_platens(const char *path, const frame *f, const dem_assembly *a, const dem_snapshot *s)
{
	double lo = INFINITY, hi = -INFINITY, rho_max = 0;
	for (size_t k = 0; k < a->n; k++) {
		double h, rho, phi;
		frame_cyl(f, s->x + 3 * k, &h, &rho, &phi);
		lo = fmin(lo, h - a->r[k]);
		hi = fmax(hi, h + a->r[k]);
		rho_max = fmax(rho_max, rho + a->r[k]);
	}
	double x[2 * 3 * PLATEN_SIDES];
	int64_t off[3] = {0, PLATEN_SIDES, 2 * PLATEN_SIDES}, conn[2 * PLATEN_SIDES];
	int32_t which[2] = {0, 1};
	double stress[2] = {s->stress_axial, s->stress_axial};
	for (int p = 0; p < 2; p++) {
		double c[3];
		v3_copy(c, f->o);
		v3_axpy(c, f->a, p ? hi : lo);
		scene_disc(x + 3 * PLATEN_SIDES * p, c, f->a, 1.2 * rho_max, PLATEN_SIDES);
	}
	for (int k = 0; k < 2 * PLATEN_SIDES; k++)
		conn[k] = k;
	vtkio_array arr[] = {{"platen", VTKIO_I32, 1, which},
	                     {"stress_axial", VTKIO_F64, 1, stress}};
	vtkio_mesh m = {.npoints = 2 * PLATEN_SIDES,
	                .x = x,
	                .kind = VTKIO_POLYS,
	                .ncells = 2,
	                .offsets = off,
	                .conn = conn,
	                .cdata = arr,
	                .ncdata = 2};
	scene_put(path, &m);
}

void scene_geometry(const char *path, const dem_geometry *g)
{
	size_t nt = g->ntri;
	int64_t *off = xmalloc((nt + 1) * sizeof *off), *conn = xmalloc(3 * nt * sizeof *conn);
	for (size_t k = 0; k <= nt; k++)
		off[k] = 3 * (int64_t)k;
	for (size_t k = 0; k < 3 * nt; k++)
		conn[k] = g->tri[k];
	vtkio_mesh m = {.npoints = g->nvert,
	                .x = g->vert,
	                .kind = VTKIO_POLYS,
	                .ncells = nt,
	                .offsets = off,
	                .conn = conn};
	scene_put(path, &m);
	free(off), free(conn);
}
