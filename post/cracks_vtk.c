#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "lib/err.h"
#include "post/cracks_vtk.h"
#include "post/output.h"
#include "post/scene.h"

enum { DISC_SIDES = 16 };

size_t cracks_frames(const dem_run *r, const size_t *snaps, size_t nsnap, double *times)
{
	double last = -INFINITY, end = -INFINITY;
	for (size_t k = 0; k < nsnap; k++) {
		times[k] = r->snap_t[snaps[k]];
		last = fmax(last, times[k]);
	}
	const double *t = run_column_data(r, "t");
	if (t && r->nrows)
		end = t[r->nrows - 1];
	int later = 0;
	for (size_t k = 0; k < r->ncracks; k++) {
		end = fmax(end, r->cracks[k].t);
		later |= r->cracks[k].t > last;
	}
	if (later)
		times[nsnap++] = end;
	return nsnap;
}

/* The discs of the cracks with time <= t. */
static void write_discs(const char *path, const dem_run *r, double t)
{
	size_t n = 0;
	for (size_t k = 0; k < r->ncracks; k++)
		n += r->cracks[k].t <= t;
	size_t na = n ? n : 1; /* allocation size: xmalloc(0) may give NULL */
	double *x = xmalloc(na * 3 * DISC_SIDES * sizeof *x);
	int64_t *off = xmalloc((n + 1) * sizeof *off),
	        *conn = xmalloc(na * DISC_SIDES * sizeof *conn);
	int32_t *row = xmalloc(na * sizeof *row), *mode = xmalloc(na * sizeof *mode);
	int32_t *pi = xmalloc(na * sizeof *pi), *pj = xmalloc(na * sizeof *pj);
	int64_t *step = xmalloc(na * sizeof *step);
	double *v = xmalloc(na * 9 * sizeof *v); /* t, strain, fn, fs, radius, normal[3] */
	double *ct = v, *ce = v + n, *cfn = v + 2 * n, *cfs = v + 3 * n, *crad = v + 4 * n;
	double *cnorm = v + 5 * n;
	size_t c = 0;
	for (size_t k = 0; k < r->ncracks; k++) {
		const dem_crack *q = &r->cracks[k];
		if (!(q->t <= t))
			continue;
		scene_disc(x + 3 * DISC_SIDES * c, q->x, q->normal, q->radius, DISC_SIDES);
		off[c] = (int64_t)(DISC_SIDES * c);
		for (int s = 0; s < DISC_SIDES; s++)
			conn[DISC_SIDES * c + (size_t)s] = (int64_t)(DISC_SIDES * c) + s;
		row[c] = (int32_t)k;
		mode[c] = q->mode;
		pi[c] = q->i;
		pj[c] = q->j;
		step[c] = q->step;
		ct[c] = q->t;
		ce[c] = q->strain_axial;
		cfn[c] = q->fn;
		cfs[c] = q->fs;
		crad[c] = q->radius;
		for (int d = 0; d < 3; d++)
			cnorm[3 * c + (size_t)d] = q->normal[d];
		c++;
	}
	off[n] = (int64_t)(DISC_SIDES * n);
	vtkio_array arr[] = {
	    {"crack", VTKIO_I32, 1, row},
	    {"mode", VTKIO_I32, 1, mode},
	    {"t", VTKIO_F64, 1, ct},
	    {"step", VTKIO_I64, 1, step},
	    {"strain_axial", VTKIO_F64, 1, ce},
	    {"fn", VTKIO_F64, 1, cfn},
	    {"fs_magnitude", VTKIO_F64, 1, cfs},
	    {"radius", VTKIO_F64, 1, crad},
	    {"normal", VTKIO_F64, 3, cnorm},
	    {"i", VTKIO_I32, 1, pi},
	    {"j", VTKIO_I32, 1, pj},
	};
	vtkio_mesh m = {.npoints = DISC_SIDES * n,
	                .x = x,
	                .kind = VTKIO_POLYS,
	                .ncells = n,
	                .offsets = off,
	                .conn = conn,
	                .cdata = arr,
	                .ncdata = sizeof arr / sizeof arr[0]};
	scene_put(path, &m);
	free(x), free(off), free(conn), free(row), free(mode), free(pi), free(pj), free(step);
	free(v);
}

void cracks_series(const char *dir, const dem_run *r, const double *times, size_t nframes,
                   pvd_entry *e)
{
	pvd_entry *own = e ? e : xmalloc((nframes ? nframes : 1) * sizeof *own);
	/* Each frame its own file, on the threads. */
#pragma omp parallel for schedule(dynamic, 1)
	for (size_t f = 0; f < nframes; f++) {
		char name[64];
		snprintf(name, sizeof name, "cracks_%06zu.vtp", f);
		char *path = out_path(dir, name);
		write_discs(path, r, times[f]);
		free(path);
		own[f] = (pvd_entry){times[f], 0, xstrdup(name)};
	}
	char *pvd = out_path(dir, "cracks.pvd");
	pvd_write(pvd, own, nframes);
	free(pvd);
	if (!e) {
		for (size_t f = 0; f < nframes; f++)
			free((char *)own[f].file);
		free(own);
	}
}
