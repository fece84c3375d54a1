/* pack: a dense polydisperse sphere assembly inside a specimen, with its
 * packing report (share/doc/pack.md). */
#include <malloc.h>
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "lib/afile.h"
#include "lib/assembly.h"
#include "lib/depfile.h"
#include "lib/err.h"
#include "lib/timer.h"
#include "pack/options.h"
#include "pack/packer.h"
#include "pack/report.h"
#include "pack/textio.h"

static double smallest_extent(const dem_geometry *g)
{
	double e = INFINITY;
	for (int k = 0; k < 3; k++)
		e = fmin(e, g->bbox_max[k] - g->bbox_min[k]);
	return e;
}

/* Apply --count / --mean-radius and check that the spheres fit. */
static void size_spheres(const pack_options *o, psd *d, const dem_geometry *g)
{
	if (o->count > 0 && o->mean_radius > 0)
		fatal("--count %ld and --mean-radius %g: expected one of them, not both", o->count,
		      o->mean_radius);
	if (o->count > 0)
		psd_scale(d, packer_count_scale(d, g->volume, o->count));
	else if (o->mean_radius > 0)
		psd_scale(d, o->mean_radius / psd_moment(d, 1));
	double ext = smallest_extent(g);
	if (2 * d->rmax < ext)
		return;
	if (o->count > 0)
		fatal(
		    "--count %ld: too few spheres: they would need radii up to %.3g m, larger than "
		    "the specimen (smallest extent %.3g m)",
		    o->count, d->rmax, ext);
	fatal("spheres of radius up to %.3g m do not fit in the specimen: expected the largest "
	      "diameter below its smallest extent (%.3g m)",
	      d->rmax, ext);
}

/* Imported spheres must have their centres inside the specimen and fit in
 * it. */
static void import_spheres(const pack_options *o, double *x, double *r, size_t n, spheres *S,
                           const surface *surf, const zones *z, const dem_geometry *g)
{
	double ext = smallest_extent(g);
	for (size_t i = 0; i < n; i++) {
		if (2 * r[i] >= ext)
			fatal("%s: sphere %zu of radius %g m does not fit in the specimen: "
			      "expected a diameter below its smallest extent (%.3g m)",
			      o->import_path, i + 1, r[i], ext);
		int32_t hint = z->hint[zones_cell(z, x + 3 * i)];
		double s = surface_distance(surf, x + 3 * i, NULL, &hint);
		if (s < 0)
			fatal("%s: sphere %zu at (%g, %g, %g) m lies outside the specimen",
			      o->import_path, i + 1, x[3 * i], x[3 * i + 1], x[3 * i + 2]);
		spheres_push(S, x + 3 * i, r[i], s, s);
	}
	free(x);
	free(r);
}

/* --grow-to: every radius times one factor, so that the sphere volume is
 * grow_to times the specimen's. The neighbours then overlap; a bonded model
 * takes the distance at bonding as the zero-force length, so they carry no
 * force for it. */
static double grow_spheres(const pack_options *o, spheres *S, const dem_geometry *g)
{
	double phi = sphere_volume(S->r, S->n) / g->volume;
	if (phi > o->grow_to)
		fatal("--grow-to %g: the spheres already fill %.4f of the specimen: expected a "
		      "solid fraction above that (or 0)",
		      o->grow_to, phi);
	double f = cbrt(o->grow_to / phi);
	for (size_t i = 0; i < S->n; i++)
		S->r[i] *= f;
	return f;
}

/* The files that go with the assembly, written before it replaces the
 * output: --export and --depfile. */
typedef struct {
	const pack_options *o;
	const dem_assembly *a;
} side_outputs;

static int write_side_outputs(void *ctx)
{
	const side_outputs *s = ctx;
	const pack_options *o = s->o;
	const char *inputs[] = {o->config, o->geometry, o->grading, o->import_path};
	return (o->export_path && textio_write(o->export_path, s->a->x, s->a->r, s->a->n)) ||
	               (o->depfile && depfile_write(o->depfile, o->output, inputs, 4))
	           ? -1
	           : 0;
}

/* OpenMP threads spin while they wait for the next parallel loop unless
 * told otherwise; on cores shared with other work a spinning thread holds
 * the core its partner needs, and the FIRE loops of the wall band, which
 * meet at a barrier a few times per iteration, run many times slower
 * (measured on the reference case with the machine loaded: 20 to 65 s
 * instead of 3 s). The policy is read from the environment when the
 * OpenMP runtime starts, before main(), and there is no call to change it
 * later; setting it earlier still, from the executable's .preinit_array,
 * does not last, as the C library resets the environment when it starts.
 * So pack restarts itself once with passive waiting unless the
 * environment already chose a policy; the restart costs a few hundredths
 * of a second, gmsh's libraries being loaded only later (gmshlib.h). */
static void wait_passively(char **argv)
{
	if (getenv("OMP_WAIT_POLICY"))
		return;
	setenv("OMP_WAIT_POLICY", "passive", 1);
	execv("/proc/self/exe", argv);
}

int main(int argc, char **argv)
{
	wait_passively(argv);
	/* The relaxation loops allocate and free arrays of megabytes at every
	 * neighbour-list build; served from the heap and kept there, they are
	 * reused instead of being returned to the kernel and faulted in again,
	 * page by page, the next time. */
	mallopt(M_MMAP_THRESHOLD, 1 << 30);
	mallopt(M_TRIM_THRESHOLD, 1 << 30);
	pack_options o;
	options_parse(&o, argc, argv);
	afile_install_signal_cleanup();
	if (o.threads > 0)
		omp_set_num_threads((int)o.threads);
	double t0 = timer_now();

	dem_assembly a;
	memset(&a, 0, sizeof a);
	/* A built-in shape's size is known before gmsh meshes it: then the
	 * mesh is made on one thread while the periodic cell is made on the
	 * other (below); a file is meshed first. */
	geometry_spec gs;
	if (options_geometry(&o, &gs))
		fatal(NULL);
	int builtin = geometry_extent(&gs, &a.geom) == 0;
	if (!builtin && geometry_build(&gs, &a.geom))
		fatal(NULL);
	psd d = {0}, *target = NULL;
	double rmean = 0, rmax = 0, *xi = NULL, *ri = NULL;
	size_t ni = 0;
	spheres S = {0};
	if (o.import_path) {
		if (o.count > 0 || o.mean_radius > 0)
			fatal("--import %s: the spheres are taken as listed: --count and "
			      "--mean-radius "
			      "do not apply (expected 0)",
			      o.import_path);
		if (textio_read(o.import_path, &xi, &ri, &ni))
			fatal(NULL);
		for (size_t i = 0; i < ni; i++) {
			rmean += ri[i] / (double)ni;
			rmax = fmax(rmax, ri[i]);
		}
	} else {
		if (options_psd(&o, &d))
			fatal(NULL);
		size_spheres(&o, &d, &a.geom);
		target = &d;
		rmean = psd_moment(&d, 1);
		rmax = d.rmax;
	}
	/* The periodic cell, on one thread, while another meshes a built-in
	 * shape and builds the boundary's search tree and the distance zones. */
	dem_geometry mesh = a.geom;
	surface *surf = NULL;
	zones z;
	jam_cell cell = {0};
	packer_stats st = {0};
	packer_params pp = {(uint64_t)o.seed, o.cell, o.keep, o.band, o.count};
	double depth = fmax(o.band, REPORT_PROFILE_DEPTH + 1) * 2 * rmean + 3 * rmax;
#pragma omp parallel sections
	{
#pragma omp section
		{
			if (builtin && geometry_build(&gs, &mesh))
				fatal(NULL);
			surf = surface_new(mesh.vert, mesh.nvert, mesh.tri, mesh.ntri);
			if (!surf)
				fatal("out of memory building the boundary's search tree");
			zones_build(&z, surf, mesh.bbox_min, mesh.bbox_max, 2 * rmean, depth);
			a.report.time_geometry = timer_now() - t0;
		}
#pragma omp section
		if (!o.import_path)
			packer_cell(&cell, &d, &a.geom, &pp, &st);
	}
	a.geom = mesh;
	if (o.import_path) {
		import_spheres(&o, xi, ri, ni, &S, surf, &z, &a.geom);
	} else {
		packer_fill(&S, &cell, &d, &a.geom, surf, &z, &pp, &st);
		jam_free(&cell);
		a.report.time_cell = st.time_cell;
		a.report.time_fill = st.time_fill;
	}
	double grown = o.grow_to > 0 ? grow_spheres(&o, &S, &a.geom) : 1;
	double t2 = timer_now();
	a.n = S.n;
	a.x = S.x;
	a.r = S.r;
	a.material = xcalloc(S.n + 1, sizeof *a.material);
	pack_report_compute(&a, surf, &z, target, o.beta);
	if (o.import_path && a.report.overlap_max >= 2)
		fatal("%s: a sphere lies entirely inside another (overlap %.0f %% of the smaller "
		      "radius): expected distinct spheres",
		      o.import_path, 100 * a.report.overlap_max);
	double t3 = timer_now();
	a.report.time_report = t3 - t2;
	a.report.time = t3 - t0;
	char *config = options_json(&o);
	prov_init(&a.prov, "pack", config, (uint64_t)o.seed);
	free(config);
	side_outputs side = {&o, &a};
	if (assembly_write_with(o.output, &a, write_side_outputs, &side))
		fatal(NULL);
	if (!o.quiet) {
		pack_report_print(&a, stdout);
		if (!o.import_path)
			packer_print(&st, stdout);
		if (o.grow_to > 0)
			printf(
			    "  grown            radii x %.4f to solid fraction %.4f (--grow-to)\n",
			    grown, o.grow_to);
	}
	free(S.r0);
	free(S.lo);
	free(S.hi);
	assembly_free(&a);
	zones_free(&z);
	surface_free(surf);
	psd_free(&d);
	options_free(&o);
	return 0;
}
