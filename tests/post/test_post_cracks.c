/* post cracks on a synthetic run: the table holds every crack row of
 * run.h5 with its orientation, the VTK series ends with one disc per
 * crack row, and the four figures are real images showing tension and
 * shear cracks in their colours. A run without cracks draws nothing. A
 * Brazilian disc's section is its face. */
#include <math.h>

#include "lib/runfile.h"
#include "lib/vec3.h"
#include "tests/check.h"
#include "tests/post/harness.h"
#include "tests/post/synth.h"
#include "tests/post/vtkread.h"

#define PI 3.14159265358979323846

static void check_csv(const char *csv, const dem_run *r)
{
	char *text = harness_slurp(csv), *save = NULL, buf[64];
	size_t row = 0;
	int bad = 0;
	for (char *line = strtok_r(text, "\n", &save); line; line = strtok_r(NULL, "\n", &save)) {
		if (row++ == 0) {
			CHECK_STR(line, "crack,t_s,step,strain_axial,mode,i,j,x_m,y_m,z_m,nx,ny,nz,"
			                "radius_m,fn_N,fs_N,theta_deg,phi_deg,height_m,rho_m");
			continue;
		}
		const dem_crack *c = &r->cracks[row - 2];
		double theta = asin(fabs(v3_dot(c->normal, r->assembly.geom.axis))) * 180 / PI;
		bad += strtol(harness_field(line, 0, buf, sizeof buf), NULL, 10) != (long)(row - 2);
		bad += fabs(strtod(harness_field(line, 1, buf, sizeof buf), NULL) - c->t) >
		       1e-9 * c->t;
		bad += strcmp(harness_field(line, 4, buf, sizeof buf),
		              c->mode == CRACK_TENSION ? "tension" : "shear") != 0;
		bad += strtol(harness_field(line, 5, buf, sizeof buf), NULL, 10) != c->i;
		bad += fabs(strtod(harness_field(line, 16, buf, sizeof buf), NULL) - theta) > 1e-7;
	}
	CHECK(row == r->ncracks + 1);
	CHECK(bad == 0);
	free(text);
}

static void check_png(const char *dir, const char *name, int w, int h)
{
	char path[1200];
	snprintf(path, sizeof path, "%s/%s", dir, name);
	const unsigned colours[2] = {0xD62728, 0x1F4E9E}; /* tension, shear */
	long count[2] = {0, 0}, distinct = 0;
	int width = 0, height = 0;
	CHECK(vtkr_png(path, &width, &height, &distinct, colours, count, 2) == 0);
	if (width != w || height != h || distinct <= 20 || count[0] <= 50 || count[1] <= 50)
		fprintf(stderr, "%s: %dx%d, %ld colours, %ld tension and %ld shear pixels\n", name,
		        width, height, distinct, count[0], count[1]);
	CHECK(width == w && height == h);
	CHECK(distinct > 20);
	CHECK(count[0] > 50 && count[1] > 50);
}

/* A Brazilian test: the section is the disc's face, seen along the disc's
 * axis with the loading diameter up, holding every crack of the
 * thickness (the default slab), each at its place in that plane, its
 * trace normal to the in-plane part of its normal. */
static void check_disc_face(const char *parent)
{
	char dir[1100], run[1200], path[1300];
	snprintf(dir, sizeof dir, "%s/bts", parent);
	snprintf(run, sizeof run, "%s/bts.h5", parent);
	synth_opts o = synth_defaults();
	o.diameter = 14e-3, o.height = 5e-3, o.nparticles = 300;
	o.center[2] = 0;
	o.load[0] = 1; /* the disc of axis z loaded along x */
	CHECK(synth_run(run, &o) == 0);
	dem_run r;
	CHECK(run_read(run, &r) == 0);
	CHECK(r.ncracks > 20);
	post_result res = harness_post("cracks --no-vtk --out %s %s", dir, run);
	CHECK(res.status == 0);
	harness_free(&res);
	check_png(dir, "cracks_section.png", 800, 850);
	snprintf(path, sizeof path, "%s/cracks_section.gp", dir);
	char *text = harness_slurp(path);
	CHECK(text && strstr(text, "disc = 1"));
	size_t nmax = r.ncracks + 1;
	double(*rows)[4] = malloc(2 * nmax * sizeof *rows);
	size_t nt = harness_datablock(text, "$tension", 4, rows[0], nmax);
	size_t ns = harness_datablock(text, "$shear", 4, rows[nmax], nmax);
	CHECK(nt + ns == r.ncracks);
	/* In the face: u across the loading diameter (-y seen from +z), h
	 * along it (x), from the centre, in mm. */
	int missing = 0, skew = 0;
	double hmin = INFINITY, hmax = -INFINITY;
	for (size_t k = 0; k < r.ncracks && nt <= nmax && ns <= nmax; k++) {
		const dem_crack *c = &r.cracks[k];
		double u = -1e3 * (c->x[1] - o.center[1]), h = 1e3 * (c->x[0] - o.center[0]);
		int shear = c->mode == CRACK_SHEAR, found = 0;
		const double(*b)[4] = rows + (shear ? nmax : 0);
		for (size_t q = 0; q < (shear ? ns : nt) && !found; q++) {
			double mu = b[q][0] + 0.5 * b[q][2], mh = b[q][1] + 0.5 * b[q][3];
			if (fabs(mu - u) > 1e-3 || fabs(mh - h) > 1e-3)
				continue;
			found = 1;
			double nu = -c->normal[1], nh = c->normal[0];
			skew += fabs(b[q][2] * nu + b[q][3] * nh) > 1e-3 * hypot(nu, nh);
		}
		missing += !found;
		hmin = fmin(hmin, h), hmax = fmax(hmax, h);
	}
	CHECK(missing == 0);
	CHECK(skew == 0);
	CHECK(hmax - hmin > 0.5 * 1e3 * o.diameter); /* cracks along the diameter */
	free(rows);
	free(text);
	run_free(&r);
}

int main(void)
{
	char dir[1024], run[1100], path[1200];
	harness_dir(dir, sizeof dir, "cracks");
	snprintf(run, sizeof run, "%s/run.h5", dir);
	synth_opts o = synth_defaults();
	CHECK(synth_run(run, &o) == 0);
	dem_run r;
	CHECK(run_read(run, &r) == 0);
	CHECK(r.ncracks > 20);
	post_result res = harness_post("cracks %s", run);
	CHECK(res.status == 0);
	harness_free(&res);
	snprintf(path, sizeof path, "%s/cracks.csv", dir);
	check_csv(path, &r);
	/* the series: one frame per snapshot, the last with every crack */
	snprintf(path, sizeof path, "%s/vtk/cracks.pvd", dir);
	char *pvd = harness_slurp(path);
	int frames = 0;
	for (const char *p = strstr(pvd, "<DataSet "); p; p = strstr(p + 1, "<DataSet "))
		frames++;
	CHECK(frames == (int)r.nsnap);
	free(pvd);
	snprintf(path, sizeof path, "%s/vtk/cracks_%06zu.vtp", dir, r.nsnap - 1);
	vtkr *v = vtkr_open(path);
	CHECK(v && vtkr_ncells(v) == (long)r.ncracks);
	if (v)
		vtkr_close(v);
	check_png(dir, "cracks_surface.png", 1100, 750);
	check_png(dir, "cracks_section.png", 700, 900);
	check_png(dir, "cracks_count.png", 900, 650);
	check_png(dir, "cracks_orientation.png", 900, 650);
	run_free(&r);

	/* no cracks: the table and series, a note, no figure */
	const double t[2] = {0, 1e-3}, s[2] = {0, 5e6};
	snprintf(run, sizeof run, "%s/calm.h5", dir);
	CHECK(synth_tiny(run, 2, t, s, 2, t, s, 1) == 0);
	res = harness_post("cracks --out %s/calm %s", dir, run);
	CHECK(res.status == 0);
	char want[2048];
	snprintf(want, sizeof want, "%s: no cracks in the run: no crack figures drawn\n", run);
	CHECK_CONTAINS(res.out, want);
	harness_free(&res);
	snprintf(path, sizeof path, "%s/calm/cracks_surface.png", dir);
	CHECK(!harness_exists(path));
	snprintf(path, sizeof path, "%s/calm/cracks.csv", dir);
	CHECK(harness_exists(path));
	check_disc_face(dir);
	return check_done();
}
