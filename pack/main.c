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
#include "lib/h5.h"
#include "lib/progress.h"
#include "lib/timer.h"
#include "pack/lattice.h"
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

/* The most spheres pack makes, as --count allows: more would need more
 * memory than a machine has (about 1 kB each while packing). */
enum { MAX_SPHERES = 1000000000 };

/* The options that set the sizes, for a message. */
static const char *sizes_from(const pack_options *o)
{
	static char s[600];
	if (o->mean_radius > 0)
		snprintf(s, sizeof s, "--mean-radius %g m", o->mean_radius);
	else if (strcmp(o->dist, "uniform") == 0)
		snprintf(s, sizeof s, "--rmin %g m, --rmax %g m", o->rmin, o->rmax);
	else if (strcmp(o->dist, "grading") == 0)
		snprintf(s, sizeof s, "--grading %s", o->grading ? o->grading : "(inline)");
	else
		snprintf(s, sizeof s, "--radius %g m", o->radius);
	return s;
}

/* Apply --count / --mean-radius and check that the spheres fit. */
static void size_spheres(const pack_options *o, psd *d, const dem_geometry *g)
{
	if (o->count > 0 && o->mean_radius > 0)
		fatal("--count %ld and --mean-radius %g: expected one of them, not both", o->count,
		      o->mean_radius);
	if (o->count > 0 && options_hcp(o))
		psd_scale(d, lattice_hcp_radius(g->volume, o->count) / d->rmax);
	else if (o->count > 0) {
		double r0 = d->rmin, r1 = d->rmax, s = packer_count_scale(d, g->volume, o->count);
		psd_scale(d, s);
		/* a sieve curve is in real sizes: say that it was scaled */
		if (d->kind == PSD_GRADING && !o->quiet)
			fprintf(
			    stderr,
			    "%s: --count %ld: the grading curve's sizes scaled by %.3g (radii %.3g "
			    "to %.3g mm instead of %.3g to %.3g)\n",
			    err_program_name(), o->count, s, 1e3 * d->rmin, 1e3 * d->rmax, 1e3 * r0,
			    1e3 * r1);
	} else if (o->mean_radius > 0)
		psd_scale(d, o->mean_radius / psd_moment(d, 1));
	double n = packer_count_estimate(d, g->volume);
	if (n > MAX_SPHERES)
		fatal("%s: the specimen (%.3g m^3) would hold about %.3g spheres of these sizes: "
		      "expected at most %.0g (larger radii, or --count)",
		      sizes_from(o), g->volume, n, (double)MAX_SPHERES);
	double ext = smallest_extent(g);
	if (2 * d->rmax < ext)
		return;
	if (o->count > 0)
		fatal(
		    "--count %ld: too few spheres: they would need radii up to %.3g m, larger than "
		    "the specimen (smallest extent %.3g m)",
		    o->count, d->rmax, ext);
	fatal("spheres of radius up to %.3g m do not fit in the specimen%s%s: expected the "
	      "largest diameter below its smallest extent (%.3g m)",
	      d->rmax, o->geometry ? " " : "", o->geometry ? o->geometry : "", ext);
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
	/* Growth is for dense packings (from 0.6 or so to 0.75: a factor of
	 * 1.08); a loose one would grow spheres through each other and past
	 * the specimen. */
	if (f > 1.25)
		fatal("--grow-to %g: the spheres fill %.4f of the specimen, so their radii would "
		      "grow %.3g times: expected a dense packing (a factor of at most 1.25, from "
		      "a solid fraction of %.3g): pack or import more spheres first",
		      o->grow_to, phi, f, o->grow_to / (1.25 * 1.25 * 1.25));
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

/* The relaxation loops allocate and free arrays of megabytes at every
 * neighbour-list build; served from the heap and kept there, they are
 * reused instead of being returned to the kernel and faulted in again,
 * page by page, the next time. */
static void keep_freed_memory(void)
{
	mallopt(M_MMAP_THRESHOLD, 1 << 30);
	mallopt(M_TRIM_THRESHOLD, 1 << 30);
}

/* One run of pack: what each step below hands on to the next. */
typedef struct {
	pack_options o;
	double t0; /* s, when the work began */
	geometry_spec gs;
	int builtin; /* a built-in shape, meshed beside the periodic cell */
	dem_assembly a;
	psd d, *target;     /* the sizes drawn from (target NULL: imported) */
	double rmean, rmax; /* m */
	double *xi, *ri;    /* the imported spheres, ni of them */
	size_t ni;
	surface *surf; /* the boundary's search tree */
	zones z;       /* and its distance zones */
	jam_cell cell; /* the periodic cell */
	packer_params pp;
	packer_stats st;
	spheres S;
	double grown; /* --grow-to's factor on the radii */
} pack_run;

/* The process, before any work: waiting threads, the heap, the options,
 * cleanup on a signal, the thread count. */
static void start(pack_run *r, int argc, char **argv)
{
	wait_passively(argv);
	keep_freed_memory();
	options_parse(&r->o, argc, argv);
	afile_install_signal_cleanup();
	if (r->o.quiet)
		progress_force(0);
	/* Far more threads than cores only wait, and may fail to start. */
	int most = 4 * omp_get_num_procs();
	if (r->o.threads > most)
		fatal("--threads %ld: expected at most %d (four per core of this machine; 0 uses "
		      "every core)",
		      r->o.threads, most);
	if (r->o.threads > 0)
		omp_set_num_threads((int)r->o.threads);
	h5_set_threads(omp_get_max_threads()); /* the assembly's chunks compressed on them */
	r->t0 = timer_now();
}

/* A built-in shape's size is known before gmsh meshes it: then the mesh is
 * made on one thread while the periodic cell is made on the other
 * (boundary_and_cell); a file is meshed first. */
static void specimen(pack_run *r)
{
	if (options_geometry(&r->o, &r->gs))
		fatal(NULL);
	r->builtin = geometry_extent(&r->gs, &r->a.geom) == 0;
	if (!r->builtin && geometry_build(&r->gs, &r->a.geom))
		fatal(NULL);
	/* A laboratory specimen of a cubic metre or more: most likely a file
	 * drawn in millimetres, which carries no unit. */
	if (!r->builtin && r->a.geom.volume >= 1 && r->gs.scale == 1 &&
	    !geometry_is_step(r->gs.file))
		warn("%s: a specimen of %.4g m^3: if it was drawn in millimetres, give --scale "
		     "0.001",
		     r->gs.file, r->a.geom.volume);
	if (r->builtin && r->a.geom.volume >= 1)
		warn("a specimen of %.4g m^3: its sizes are in metres (a 25 mm diameter is "
		     "--diameter 0.025)",
		     r->a.geom.volume);
}

/* The sizes: the imported spheres as listed, or the distribution scaled to
 * --count or --mean-radius. */
static void sizes(pack_run *r)
{
	const pack_options *o = &r->o;
	if (o->import_path) {
		if (o->count > 0 || o->mean_radius > 0)
			fatal("--import %s: the spheres are taken as listed: --count and "
			      "--mean-radius do not apply (expected 0)",
			      o->import_path);
		if (textio_read(o->import_path, &r->xi, &r->ri, &r->ni))
			fatal(NULL);
		for (size_t i = 0; i < r->ni; i++) {
			r->rmean += r->ri[i] / (double)r->ni;
			r->rmax = fmax(r->rmax, r->ri[i]);
		}
		return;
	}
	if (options_psd(o, &r->d))
		fatal(NULL);
	size_spheres(o, &r->d, &r->a.geom);
	r->target = &r->d;
	r->rmean = psd_moment(&r->d, 1);
	r->rmax = r->d.rmax;
}

/* Mesh a built-in shape (into mesh), then build the boundary's search tree
 * and distance zones down to `depth`. */
static void build_boundary(pack_run *r, dem_geometry *mesh, double depth)
{
	if (r->builtin && geometry_build(&r->gs, mesh))
		fatal(NULL);
	r->surf = surface_new(mesh->vert, mesh->nvert, mesh->tri, mesh->ntri);
	if (!r->surf)
		fatal("out of memory building the boundary's search tree");
	zones_build(&r->z, r->surf, mesh->bbox_min, mesh->bbox_max, 2 * r->rmean, depth);
	r->a.report.time_geometry = timer_now() - r->t0;
}

/* The periodic cell, on one thread, while another builds the boundary; the
 * cell reads the specimen's extent (a.geom), so the mesh goes to a copy
 * that replaces it afterwards. */
static void boundary_and_cell(pack_run *r)
{
	const pack_options *o = &r->o;
	dem_geometry mesh = r->a.geom;
	r->pp = (packer_params){(uint64_t)o->seed, o->cell, o->keep, o->band, o->count};
	double depth = fmax(o->band, REPORT_PROFILE_DEPTH + 1) * 2 * r->rmean + 3 * r->rmax;
#pragma omp parallel sections
	{
#pragma omp section
		build_boundary(r, &mesh, depth);
#pragma omp section
		if (!o->import_path && !options_hcp(o))
			packer_cell(&r->cell, &r->d, &r->a.geom, &r->pp, &r->st);
	}
	r->a.geom = mesh;
}

/* The lattice of --arrangement hcp. With --count, the radius is found by
 * bisection on the number of spheres kept, which the layers make a step
 * function of it: the radius giving the count closest to the target in at
 * most 30 fills (each a few hundredths of a second per 10^4 spheres). */
static size_t fill_lattice(pack_run *r, double rad)
{
	r->S.n = 0;
	return lattice_hcp(&r->S, rad, &r->a.geom, r->surf, &r->z);
}

static void place_lattice(pack_run *r)
{
	double t = timer_now(), rad = r->d.rmax;
	if (r->o.count > 0) {
		double lo = 0.8 * rad, hi = 1.25 * rad, best = rad, miss = INFINITY;
		for (int k = 0; k < 30 && miss > 0; k++) {
			double mid = 0.5 * (lo + hi);
			double n = (double)fill_lattice(r, mid), m = fabs(n - (double)r->o.count);
			if (m < miss)
				miss = m, best = mid;
			*(n > (double)r->o.count ? &lo : &hi) = mid;
		}
		rad = best;
	}
	if (fill_lattice(r, rad) == 0)
		fatal(
		    "--arrangement hcp: no sphere of radius %g m fits in the specimen: expected a "
		    "smaller --radius",
		    rad);
	psd_uniform(&r->d, rad, rad);
	r->a.report.time_fill = timer_now() - t;
}

/* The spheres in the specimen: the imported ones, checked, the lattice, or
 * the cell tiled over it and repaired along the boundary. */
static void place_spheres(pack_run *r)
{
	if (options_hcp(&r->o)) {
		place_lattice(r);
		return;
	}
	if (r->o.import_path) {
		import_spheres(&r->o, r->xi, r->ri, r->ni, &r->S, r->surf, &r->z, &r->a.geom);
		return;
	}
	packer_fill(&r->S, &r->cell, &r->d, &r->a.geom, r->surf, &r->z, &r->pp, &r->st);
	jam_free(&r->cell);
	if (r->S.n == 0)
		fatal("no sphere of radius %g to %g m fits in the specimen (%g m^3): expected "
		      "smaller spheres (--rmin, --rmax, --mean-radius) or a larger specimen",
		      r->d.rmin, r->d.rmax, r->a.geom.volume);
	r->a.report.time_cell = r->st.time_cell;
	r->a.report.time_fill = r->st.time_fill;
}

/* The assembly made of the spheres (grown if asked), and its report. */
static void measure(pack_run *r)
{
	dem_assembly *a = &r->a;
	r->grown = r->o.grow_to > 0 ? grow_spheres(&r->o, &r->S, &a->geom) : 1;
	double t2 = timer_now();
	a->n = r->S.n;
	a->x = r->S.x;
	a->r = r->S.r;
	a->material = xcalloc(r->S.n + 1, sizeof *a->material);
	pack_report_compute(a, r->surf, &r->z, r->target, r->o.beta);
	if (r->o.import_path && a->report.overlap_max >= 2)
		fatal("%s: a sphere lies entirely inside another (overlap %.0f %% of the smaller "
		      "radius): expected distinct spheres",
		      r->o.import_path, 100 * a->report.overlap_max);
	double t3 = timer_now();
	a->report.time_report = t3 - t2;
	a->report.time = t3 - r->t0;
}

/* The assembly with its provenance, and the side outputs. */
static void write_output(pack_run *r)
{
	char *config = options_json(&r->o);
	prov_init(&r->a.prov, "pack", config, (uint64_t)r->o.seed);
	free(config);
	side_outputs side = {&r->o, &r->a};
	if (assembly_write_with(r->o.output, &r->a, write_side_outputs, &side))
		fatal(NULL);
}

static void print_summary(const pack_run *r)
{
	pack_report_print(&r->a, stdout);
	if (options_hcp(&r->o))
		printf(
		    "  arrangement      hexagonal close packing of radius %.6g m, c axis along z "
		    "(--arrangement hcp)\n",
		    r->d.rmax);
	else if (!r->o.import_path)
		packer_print(&r->st, stdout);
	if (r->o.grow_to > 0)
		printf("  grown            radii x %.4f to solid fraction %.4f (--grow-to)\n",
		       r->grown, r->o.grow_to);
}

static void free_run(pack_run *r)
{
	free(r->S.r0);
	free(r->S.lo);
	free(r->S.hi);
	assembly_free(&r->a);
	zones_free(&r->z);
	surface_free(r->surf);
	psd_free(&r->d);
	options_free(&r->o);
}

int main(int argc, char **argv)
{
	pack_run r = {0};
	start(&r, argc, argv);
	specimen(&r);
	sizes(&r);
	boundary_and_cell(&r);
	place_spheres(&r);
	measure(&r);
	write_output(&r);
	if (!r.o.quiet)
		print_summary(&r);
	free_run(&r);
	return 0;
}
