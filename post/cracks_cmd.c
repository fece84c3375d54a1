/* post cracks: the crack log of a run as a table (cracks.csv), as discs in
 * a VTK time series (vtk/cracks.pvd) and as figures: the unrolled lateral
 * surface, an axial section (of a Brazilian disc, its face), crack counts by mode against axial
 * strain and a histogram of crack orientations (post/crackmap.h for the definitions). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "lib/cli.h"
#include "lib/err.h"
#include "lib/vec3.h"
#include "post/crackmap.h"
#include "post/cracks_vtk.h"
#include "post/load.h"
#include "post/output.h"
#include "post/plot.h"
#include "post/post.h"

typedef struct {
	double depth;            /* m, lateral surface layer */
	double psi;              /* deg, section angle */
	double thickness;        /* m, section slab */
	double width;            /* deg, orientation bins */
	int disc;                /* section: a Brazilian disc's face, not an axial section */
	double e[3], v[3], m[3]; /* the section's plane: across, up, its normal */
} map_opts;

static const char *mode_name(int mode) { return mode == CRACK_TENSION ? "tension" : "shear"; }

static void write_csv(const char *path, const dem_run *r, const specimen *sp)
{
	out_text o;
	out_text_open(&o, path);
	fputs("crack,t_s,step,strain_axial,mode,i,j,x_m,y_m,z_m,nx,ny,nz,radius_m,fn_N,fs_N,"
	      "theta_deg,phi_deg,height_m,rho_m\n",
	      o.f);
	for (size_t k = 0; k < r->ncracks; k++) {
		const dem_crack *c = &r->cracks[k];
		crack_place p;
		crack_place_of(sp, c, &p);
		fprintf(o.f,
		        "%zu,%.10g,%lld,%.10g,%s,%d,%d,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,"
		        "%.10g,%.10g,%.10g,%.10g,%.10g,%.10g\n",
		        k, c->t, (long long)c->step, c->strain_axial, mode_name(c->mode), c->i,
		        c->j, c->x[0], c->x[1], c->x[2], c->normal[0], c->normal[1], c->normal[2],
		        c->radius, c->fn, c->fs, p.theta, p.phi, p.height, p.rho);
	}
	out_text_commit(&o);
}

/* Variables every map script reads: the specimen in mm and the legends. */
static void specimen_vars(FILE *f, const specimen *sp, const dem_run *r)
{
	long nt = 0, ns = 0;
	for (size_t k = 0; k < r->ncracks; k++) {
		nt += r->cracks[k].mode == CRACK_TENSION;
		ns += r->cracks[k].mode == CRACK_SHEAR;
	}
	fprintf(f, "H = %.10g\nR = %.10g\nntension = %ld\nnshear = %ld\n", 1e3 * sp->height,
	        1e3 * sp->radius, nt, ns);
}

/* $tension and $shear: phi (deg) and height (mm) of surface cracks. */
static void surface_data(FILE *f, const dem_run *r, const specimen *sp, double depth)
{
	for (int mode = CRACK_TENSION; mode <= CRACK_SHEAR; mode++) {
		fprintf(f, "$%s << EOD\n", mode_name(mode));
		for (size_t k = 0; k < r->ncracks; k++) {
			crack_place p;
			crack_place_of(sp, &r->cracks[k], &p);
			if (r->cracks[k].mode == mode && p.rho >= sp->radius - depth)
				fprintf(f, "%.6g %.6g\n", p.phi, 1e3 * p.height);
		}
		fputs("EOD\n", f);
	}
	fprintf(f, "depth = %.10g\n", 1e3 * depth);
}

/* The plane of a Brazilian disc's face through its centre: unit vectors
 * e (across the loading diameter) and v (along it, from the loading axis
 * made normal to the disc's axis a) and m = a, its normal; 0, or -1 when
 * the loading axis is along the disc's axis. */
static int face_plane(const dem_run *r, const specimen *sp, double e[3], double v[3], double m[3])
{
	double load[3];
	load_axis(r, load);
	v3_copy(m, sp->f.a);
	v3_reject(v, load, m);
	if (v3_norm(v) < 1e-6)
		return -1;
	v3_scale(v, v, 1 / v3_norm(v));
	v3_cross(e, v, m); /* seen from +a: e to the right, v up */
	return 0;
}

/* The plane of the axial section at psi (deg): unit vectors e (across),
 * v = a (up) and m, its normal. */
static void axial_plane(const specimen *sp, double psi, double e[3], double v[3], double m[3])
{
	const frame *fr = &sp->f;
	double c = cos(psi / POST_DEG), s = sin(psi / POST_DEG);
	for (int k = 0; k < 3; k++)
		e[k] = c * fr->e1[k] + s * fr->e2[k];
	v3_copy(v, fr->a);
	v3_cross(m, fr->a, e);
}

/* $tension and $shear: crack traces in the section o->e, o->v, o->m, u h
 * du dh (mm): the axial section at psi, or for a Brazilian test (o->disc)
 * the disc's face, h then along the loading diameter from the centre. */
static void section_data(FILE *f, const dem_run *r, const specimen *sp, const map_opts *o)
{
	const frame *fr = &sp->f;
	const double *e = o->e, *v = o->v, *m = o->m;
	int disc = o->disc;
	for (int mode = CRACK_TENSION; mode <= CRACK_SHEAR; mode++) {
		fprintf(f, "$%s << EOD\n", mode_name(mode));
		for (size_t k = 0; k < r->ncracks; k++) {
			const dem_crack *q = &r->cracks[k];
			double d[3];
			v3_sub(d, q->x, fr->o);
			if (q->mode != mode || fabs(v3_dot(d, m)) > 0.5 * o->thickness)
				continue;
			crack_place p;
			crack_place_of(sp, q, &p);
			double nu = v3_dot(q->normal, e), nh = v3_dot(q->normal, v);
			double len = hypot(nu, nh), tu = 1, th = 0; /* trace direction */
			if (len > 1e-9)
				tu = -nh / len, th = nu / len;
			double u = v3_dot(d, e), h = disc ? v3_dot(d, v) : p.height, rc = q->radius;
			fprintf(f, "%.6g %.6g %.6g %.6g\n", 1e3 * (u - rc * tu),
			        1e3 * (h - rc * th), 2e3 * rc * tu, 2e3 * rc * th);
		}
		fputs("EOD\n", f);
	}
	fprintf(f, "thickness = %.10g\npsi = %.10g\ndisc = %d\n", 1e3 * o->thickness, o->psi, disc);
}

/* $hist: bin centre, width (deg), tension and shear counts. */
static void orientation_data(FILE *f, const dem_run *r, const specimen *sp, double w)
{
	int nb = (int)ceil(90.0 / w - 1e-9);
	long *count = xcalloc(2 * (size_t)nb, sizeof *count);
	for (size_t k = 0; k < r->ncracks; k++) {
		crack_place p;
		crack_place_of(sp, &r->cracks[k], &p);
		int b = (int)(p.theta / w);
		b = b < nb ? b : nb - 1;
		count[2 * b + (r->cracks[k].mode == CRACK_SHEAR)]++;
	}
	fputs("$hist << EOD\n", f);
	for (int b = 0; b < nb; b++) {
		double lo = b * w, hi = fmin(90, (b + 1) * w);
		fprintf(f, "%.6g %.6g %ld %ld\n", 0.5 * (lo + hi), hi - lo, count[2 * b],
		        count[2 * b + 1]);
	}
	fputs("EOD\n", f);
	free(count);
}

static void draw(const char *dir, const char *script, plot_data *d, int w, int h)
{
	char *fig = plot_file(dir, script);
	if (plot_draw(d, script, fig, w, h))
		fatal(NULL);
	printf("wrote %s\n", fig);
	free(fig);
}

static void plot_maps(const char *dir, const dem_run *r, const specimen *sp, const map_opts *o)
{
	plot_data d;
	plot_begin(&d);
	specimen_vars(d.f, sp, r);
	surface_data(d.f, r, sp, o->depth);
	draw(dir, "cracks_surface", &d, 1100, 750);
	plot_begin(&d);
	specimen_vars(d.f, sp, r);
	section_data(d.f, r, sp, o);
	draw(dir, "cracks_section", &d, o->disc ? 800 : 700, o->disc ? 850 : 900);
	plot_begin(&d);
	specimen_vars(d.f, sp, r);
	crackmap_count_data(d.f, r);
	fputs("with_stress = 0\n", d.f);
	draw(dir, "cracks_count", &d, 900, 650);
	plot_begin(&d);
	specimen_vars(d.f, sp, r);
	orientation_data(d.f, r, sp, o->width);
	draw(dir, "cracks_orientation", &d, 900, 650);
}

/* The files of the crack series (vtk/cracks.pvd and its frames). */
static int crack_file(const char *name) { return out_series_name(name, "cracks", "vtp"); }

int post_cracks(int argc, char **argv)
{
	const char *out = NULL;
	map_opts o = {.width = 10};
	int no_png = 0, no_vtk = 0;
	long threads = 0;
	const char *format = "png";
	const cli_opt opts[] = {
	    {"out", CLI_STR, &out, "DIR", "", "output directory (default: that of the run)", 0, 0},
	    {"surface-depth", CLI_NUM, &o.depth, "D", "m",
	     "surface map: cracks within D of the lateral surface; 0: 2 mean diameters", 0, 1e3},
	    {"section-angle", CLI_NUM, &o.psi, "A", "deg",
	     "section map: angle of the axial section plane around the axis", -360, 360},
	    {"section-thickness", CLI_NUM, &o.thickness, "D", "m",
	     "section map: slab thickness; 0: 2 mean diameters (a Brazilian disc: all of it)", 0,
	     1e3},
	    {"bin-width", CLI_NUM, &o.width, "DEG", "deg", "orientation histogram bin width", 1,
	     90},
	    {"no-png", CLI_FLAG, &no_png, NULL, "", "no figures", 0, 0},
	    {"no-vtk", CLI_FLAG, &no_vtk, NULL, "", "no VTK series", 0, 0},
	    {"format", CLI_STR, &format, "png|pdf|svg", "",
	     "figure format (each figure's gnuplot script is left beside it as NAME.gp)", 0, 0},
	    POST_THREADS_OPT(threads),
	};
	const char *file = post_one_file(
	    "post cracks [options] RUN.h5",
	    "The crack log of a run: cracks.csv (every bond failure with its mode,\n"
	    "time, axial strain, forces, place and orientation), vtk/cracks.pvd (one\n"
	    "disc per crack, appearing at its time), and figures: cracks_surface.png\n"
	    "(unrolled lateral surface), cracks_section.png (axial section; a\n"
	    "Brazilian disc's face), cracks_count.png (cracks by mode against\n"
	    "axial strain) and cracks_orientation.png (histogram of crack\n"
	    "orientations).",
	    opts, (int)(sizeof opts / sizeof opts[0]), argc, argv);
	if (plot_set_format(format))
		fatal(NULL);
	post_threads(threads);
	dem_run r;
	load_run("cracks", file, &r);
	specimen sp;
	specimen_of(&sp, &r.assembly);
	if (o.depth == 0)
		o.depth = 4 * sp.mean_radius;
	/* A Brazilian disc splits along its loading diameter, through its
	 * thickness: its section is its face, every crack of the thickness. */
	o.disc = load_is_bts(&r);
	if (o.disc && face_plane(&r, &sp, o.e, o.v, o.m)) {
		printf("%s: a Brazilian test loaded along the disc's axis: cracks_section.png is "
		       "an axial section\n",
		       file);
		o.disc = 0;
	}
	if (o.disc && o.psi != 0)
		printf("%s: a Brazilian test: cracks_section.png shows the disc's face; "
		       "--section-angle is not used\n",
		       file);
	if (!o.disc)
		axial_plane(&sp, o.psi, o.e, o.v, o.m);
	if (o.thickness == 0)
		o.thickness = o.disc ? sp.height + 2 * sp.mean_radius : 4 * sp.mean_radius;
	char *dir = out_dir(out, file);
	char *csv = out_path(dir, "cracks.csv");
	write_csv(csv, &r, &sp);
	printf("wrote %s (%zu cracks)\n", csv, r.ncracks);
	if (!no_vtk) {
		char *vdir = out_path(dir, "vtk");
		out_mkdir(vdir);
		char *stage = out_series_begin(vdir, "cracks");
		size_t *all = xmalloc((r.nsnap ? r.nsnap : 1) * sizeof *all);
		for (size_t k = 0; k < r.nsnap; k++)
			all[k] = k;
		double *times = xmalloc((r.nsnap + 1) * sizeof *times);
		size_t nf = cracks_frames(&r, all, r.nsnap, times);
		cracks_series(stage, &r, times, nf, NULL);
		out_series_commit(vdir, stage, "cracks.pvd", crack_file);
		printf("wrote %s/cracks.pvd (%zu frames)\n", vdir, nf);
		free(all), free(times), free(vdir), free(stage);
	}
	if (!no_png && r.ncracks == 0)
		printf("%s: no cracks in the run: no crack figures drawn\n", file);
	else if (!no_png)
		plot_maps(dir, &r, &sp, &o);
	free(csv), free(dir);
	run_free(&r);
	return 0;
}
