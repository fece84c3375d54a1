/* post vtk: ParaView files of a run (a time series over its snapshots) or
 * of an assembly (the packing as made). See post/scene.h for what each
 * file holds and share/paraview/ for a script that shows them. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lib/cli.h"
#include "lib/err.h"
#include "lib/progress.h"
#include "post/cracks_vtk.h"
#include "post/load.h"
#include "post/output.h"
#include "post/post.h"
#include "post/pvd.h"
#include "post/scene.h"

enum { PART_PARTICLES, PART_BONDS, PART_PLATENS, PART_CRACKS, NPARTS };
static const char *const part_name[NPARTS] = {"particles", "bonds", "platens", "cracks"};
static const char *const part_ext[NPARTS] = {"vtu", "vtp", "vtp", "vtp"};

static void write_geometry(const char *dir, const dem_geometry *g)
{
	if (g->ntri == 0)
		return;
	char *path = out_path(dir, "geometry.vtp");
	scene_geometry(path, g);
	free(path);
}

static void assembly_files(const char *file, const char *dir)
{
	dem_assembly a;
	if (assembly_read(file, &a))
		fatal(NULL);
	out_mkdir(dir);
	char *path = out_path(dir, "particles.vtu");
	scene_particles(path, &a, NULL, NULL);
	write_geometry(dir, &a.geom);
	printf("wrote %s (%zu particles) and the geometry in %s\n", path, a.n, dir);
	free(path);
	assembly_free(&a);
}

/* The snapshots shown: every n-th, and always the last. */
static size_t pick_snapshots(size_t nsnap, long every, size_t *snaps)
{
	size_t n = 0;
	for (size_t k = 0; k < nsnap; k += (size_t)every)
		snaps[n++] = k;
	if (snaps[n - 1] != nsnap - 1)
		snaps[n++] = nsnap - 1;
	return n;
}

/* The history value of column col (NaN without it) at the row nearest in
 * time to t. */
static double history_at(const dem_run *r, const char *col, double t)
{
	const double *v = run_column_data(r, col), *ht = run_column_data(r, "t");
	if (!v || !ht || !r->nrows)
		return NAN;
	size_t best = 0;
	for (size_t k = 1; k < r->nrows; k++)
		if (fabs(ht[k] - t) < fabs(ht[best] - t))
			best = k;
	return v[best];
}

/* The files of frame k of the run r (its snapshot snaps[k] of file), their
 * entries[part][k]. */
static void frame_files(const char *file, const dem_run *r, const frame *f, const size_t *snaps,
                        size_t k, const char *dir, pvd_entry *entries[NPARTS])
{
	dem_snapshot s;
	/* The HDF5 library runs one call at a time. */
#pragma omp critical(post_hdf5)
	load_snapshot(file, r, snaps[k], &s);
	/* The frame's state as field data of each of its files (ParaView shows
	 * it with the Annotate tools). */
	double pressure = history_at(r, "pressure", s.t);
	const vtkio_array fields[] = {
	    {"time", VTKIO_F64, 1, &s.t},
	    {"step", VTKIO_I64, 1, &s.step},
	    {"strain_axial", VTKIO_F64, 1, &s.strain_axial},
	    {"stress_axial", VTKIO_F64, 1, &s.stress_axial},
	    {"confining_pressure", VTKIO_F64, 1, &pressure},
	};
	scene_fields(fields, (int)(sizeof fields / sizeof fields[0]));
	for (int p = 0; p < PART_CRACKS; p++) {
		if (p == PART_BONDS && r->bonds.n == 0)
			continue;
		char name[64];
		snprintf(name, sizeof name, "%s_%06zu.%s", part_name[p], k, part_ext[p]);
		char *path = out_path(dir, name);
		if (p == PART_PARTICLES)
			scene_particles(path, &r->assembly, &r->bonds, &s);
		else if (p == PART_BONDS)
			scene_bonds(path, &r->bonds, &s);
		else
			scene_platens(path, f, &r->assembly, &s);
		free(path);
		entries[p][k] = (pvd_entry){s.t, p, xstrdup(name)};
	}
	scene_fields(NULL, 0);
	snapshot_free(&s);
}

/* The files of a run's series (run_files), run.pvd among them. */
static int series_file(const char *name)
{
	if (!strcmp(name, "run.pvd") || !strcmp(name, "geometry.vtp"))
		return 1;
	for (int p = 0; p < NPARTS; p++)
		if (out_series_name(name, part_name[p], part_ext[p]))
			return 1;
	return 0;
}

/* The series of the run in file, into dir as a whole (out_series_begin):
 * written in a staging directory, then moved in, run.pvd last. */
static void run_files(const char *file, const char *dir, long every)
{
	dem_run r;
	load_run("vtk", file, &r);
	if (r.nsnap == 0)
		fatal("%s: the run has no snapshots (it stopped before writing one)", file);
	out_mkdir(dir);
	char *stage = out_series_begin(dir, "vtk");
	frame f;
	frame_of(&f, &r.assembly.geom);
	size_t *snaps = xmalloc(r.nsnap * sizeof *snaps);
	size_t nframes = pick_snapshots(r.nsnap, every, snaps);
	/* entries[part][frame]; the crack series may have one more frame */
	pvd_entry *entries[NPARTS];
	for (int p = 0; p < NPARTS; p++)
		entries[p] = xcalloc(nframes + 1, sizeof *entries[p]);
	progress pr;
	progress_start(&pr, "snapshots", (double)nframes);
	/* The frames on the threads, each its own files (the same whatever the
	 * threads), the snapshots read one at a time. */
	size_t done = 0;
#pragma omp parallel for schedule(dynamic, 1)
	for (size_t k = 0; k < nframes; k++) {
		frame_files(file, &r, &f, snaps, k, stage, entries);
#pragma omp critical(post_progress)
		progress_update(&pr, (double)++done, NULL);
	}
	progress_end(&pr);
	double *times = xmalloc((nframes + 1) * sizeof *times);
	size_t ncrack = cracks_frames(&r, snaps, nframes, times);
	cracks_series(stage, &r, times, ncrack, entries[PART_CRACKS]);
	for (size_t k = 0; k < ncrack; k++)
		entries[PART_CRACKS][k].part = PART_CRACKS;
	/* One collection per part, and run.pvd with every part at each time. */
	pvd_entry *all = xmalloc(NPARTS * (nframes + 1) * sizeof *all);
	size_t nall = 0;
	for (int p = 0; p < NPARTS; p++) {
		size_t n =
		    p == PART_CRACKS ? ncrack : (p == PART_BONDS && !r.bonds.n ? 0 : nframes);
		if (p != PART_CRACKS && n) {
			char name[64];
			snprintf(name, sizeof name, "%s.pvd", part_name[p]);
			char *path = out_path(stage, name);
			pvd_entry *single = xmalloc(n * sizeof *single);
			for (size_t k = 0; k < n; k++)
				single[k] = (pvd_entry){entries[p][k].t, 0, entries[p][k].file};
			pvd_write(path, single, n);
			free(single);
			free(path);
		}
		for (size_t k = 0; k < n; k++)
			all[nall++] = entries[p][k];
	}
	/* run.pvd: its presence says the series is complete. */
	write_geometry(stage, &r.assembly.geom);
	char *run_pvd = out_path(stage, "run.pvd");
	pvd_write(run_pvd, all, nall);
	out_series_commit(dir, stage, "run.pvd", series_file);
	free(run_pvd);
	run_pvd = out_path(dir, "run.pvd");
	printf("wrote %zu snapshots (%zu particles, %zu bonds, %zu cracks) to %s; open %s\n",
	       nframes, r.assembly.n, r.bonds.n, r.ncracks, dir, run_pvd);
	for (size_t k = 0; k < nall; k++)
		free((char *)all[k].file);
	for (int p = 0; p < NPARTS; p++)
		free(entries[p]);
	free(all), free(times), free(snaps), free(run_pvd), free(stage);
	run_free(&r);
}

int post_vtk(int argc, char **argv)
{
	const char *out = NULL;
	long every = 1, threads = 0;
	const cli_opt opts[] = {
	    {"out", CLI_STR, &out, "DIR", "", "output directory (default: vtk/ beside the file)", 0,
	     0},
	    {"every", CLI_INT, &every, "N", "", "every N-th snapshot (the last always)", 1, 1e9},
	    POST_THREADS_OPT(threads),
	};
	const char *file = post_one_file(
	    "post vtk [options] RUN.h5|ASSEMBLY.h5",
	    "ParaView files, binary compressed VTK XML. From a run, one frame per\n"
	    "snapshot: particles_N.vtu (points with radius, displacement, velocity,\n"
	    "damage, material), bonds_N.vtp (lines with state, forces, damage),\n"
	    "platens_N.vtp, cracks_N.vtp (discs), a .pvd series for each and run.pvd\n"
	    "with all of them, and geometry.vtp. From an assembly: particles.vtu and\n"
	    "geometry.vtp. share/paraview/show_run.py renders a run.",
	    opts, (int)(sizeof opts / sizeof opts[0]), argc, argv);
	post_threads(threads);
	file_kind kind = load_kind("vtk", file);
	char *dir;
	if (out) {
		dir = xstrdup(out);
	} else {
		char *base = out_dir(NULL, file);
		dir = out_path(base, "vtk");
		free(base);
	}
	if (kind == FILE_ASSEMBLY)
		assembly_files(file, dir);
	else
		run_files(file, dir, every);
	free(dir);
	return 0;
}
