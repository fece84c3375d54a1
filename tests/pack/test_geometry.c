/* Specimen geometry: every source (built-in cylinder, disc, box; .geo,
 * .brep, .step in millimetres, .msh volume mesh) gives a closed, outward
 * triangulation whose volume, area and signed distances match the shape's
 * own formulas; open and unreadable files, and boundaries that enclose no
 * well-defined solid, are refused with one clear message. A built-in
 * shape's extent is known before it is meshed. */
#include "tests/check.h"

#include "lib/err.h"
#include "lib/rng.h"
#include "pack/geometry.h"
#include "pack/surface.h"
#include "pack/trimesh.h"

#define GEO "share/geometry/"

/* Chord error of the built-in circles: R (1 - cos(pi / 160)). */
static double chord(double r) { return r * (1 - cos(M_PI / 160)); }

static double mesh_volume(const dem_geometry *g)
{
	trimesh m = {g->nvert, g->ntri, g->vert, g->tri};
	double v, a, lo[3], hi[3];
	trimesh_measure(&m, &v, &a, lo, hi);
	return v;
}

/* Signed distance to a z-axis cylinder of radius R and height H centred on
 * the origin (positive inside). */
static double cylinder_depth(const double p[3], double R, double H)
{
	double rho = sqrt(p[0] * p[0] + p[1] * p[1]), dr = R - rho, dz = 0.5 * H - fabs(p[2]);
	if (dr >= 0 && dz >= 0)
		return fmin(dr, dz);
	if (dr < 0 && dz < 0)
		return -sqrt(dr * dr + dz * dz);
	return fmin(dr, dz);
}

/* Random points around a cylinder: the surface's signed distance agrees
 * with the exact one within the chord error. */
static void check_cylinder_distances(const dem_geometry *g, double R, double H)
{
	surface *s = surface_new(g->vert, g->nvert, g->tri, g->ntri);
	CHECK(s != NULL);
	rng r;
	rng_seed(&r, 5);
	double worst = 0;
	int sign_ok = 1;
	for (int k = 0; k < 4000; k++) {
		double p[3] = {rng_range(&r, -0.6 * H, 0.6 * H), rng_range(&r, -0.6 * H, 0.6 * H),
		               rng_range(&r, -0.6 * H, 0.6 * H)};
		p[0] *= 2 * R / H;
		p[1] *= 2 * R / H;
		double exact = cylinder_depth(p, R, H), got = surface_distance(s, p, NULL, NULL);
		worst = fmax(worst, fabs(got - exact));
		if (fabs(exact) > 2 * chord(R) && (got > 0) != (exact > 0))
			sign_ok = 0;
	}
	CHECK(sign_ok);
	CHECK_NEAR(worst, 0, 2 * chord(R) + 1e-12);
	/* The outward normal at the middle of the lateral face points along x. */
	double p[3] = {0.9 * R, 0, 0}, n[3];
	CHECK_NEAR(surface_distance(s, p, n, NULL), 0.1 * R, chord(R));
	CHECK_NEAR(n[0], 1, 1e-3);
	surface_free(s);
}

static void test_builtin_cylinder(void)
{
	geometry_spec gs = {SHAPE_CYLINDER, 0.05, 0.1, {0, 0, 0}, NULL, 1};
	dem_geometry g;
	CHECK(geometry_build(&gs, &g) == 0);
	CHECK_STR(g.shape, "cylinder");
	CHECK_REL(g.volume, M_PI * 0.025 * 0.025 * 0.1, 1e-15);
	CHECK_REL(mesh_volume(&g), g.volume, 3e-4);
	CHECK_REL(g.area, 2 * M_PI * 0.025 * (0.1 + 0.025), 3e-4);
	CHECK_NEAR(g.bbox_min[2], -0.05, 1e-15);
	CHECK_NEAR(g.bbox_max[0], 0.025, 1e-15);
	CHECK(g.axis[2] == 1 && g.diameter == 0.05 && g.height == 0.1);
	CHECK_NEAR(geometry_inner_volume(&g, 0.005), M_PI * 0.02 * 0.02 * 0.09, 1e-18);
	check_cylinder_distances(&g, 0.025, 0.1);
	free(g.vert);
	free(g.tri);
}

static void test_builtin_disc_and_box(void)
{
	geometry_spec disc = {SHAPE_DISC, 0.0378, 0.0219, {0, 0, 0}, NULL, 1};
	dem_geometry g;
	CHECK(geometry_build(&disc, &g) == 0);
	CHECK_STR(g.shape, "disc");
	CHECK_REL(mesh_volume(&g), M_PI * 0.0189 * 0.0189 * 0.0219, 3e-4);
	check_cylinder_distances(&g, 0.0189, 0.0219);
	free(g.vert);
	free(g.tri);

	geometry_spec box = {SHAPE_BOX, 0, 0, {0.02, 0.03, 0.04}, NULL, 1};
	CHECK(geometry_build(&box, &g) == 0);
	CHECK_STR(g.shape, "box");
	CHECK(g.ntri == 12);
	CHECK_REL(g.volume, 0.02 * 0.03 * 0.04, 1e-15);
	CHECK_REL(mesh_volume(&g), g.volume, 1e-12);
	CHECK_REL(g.area, 2 * (0.02 * 0.03 + 0.02 * 0.04 + 0.03 * 0.04), 1e-12);
	CHECK_NEAR(geometry_inner_volume(&g, 0.005), 0.01 * 0.02 * 0.03, 1e-18);
	surface *s = surface_new(g.vert, g.nvert, g.tri, g.ntri);
	double p[3] = {0.001, 0.002, 0.003}, corner[3] = {0.011, 0.016, 0.021};
	CHECK_NEAR(surface_distance(s, p, NULL, NULL), 0.009, 1e-15);
	CHECK_NEAR(surface_distance(s, corner, NULL, NULL), -sqrt(3e-6), 1e-15);
	surface_free(s);
	free(g.vert);
	free(g.tri);
}

static void test_files(void)
{
	struct {
		const char *file;
		double volume, tol;
	} cases[] = {
	    {GEO "cylinder_1x2in.geo", M_PI * 0.0127 * 0.0127 * 0.0508, 1e-3},
	    {GEO "box_20mm.brep", 8e-6, 1e-12},
	    {GEO "cylinder_20x40_mm.step", M_PI * 0.01 * 0.01 * 0.04, 1e-3},
	    {GEO "cylinder_20x40.msh", M_PI * 0.01 * 0.01 * 0.04, 0.03},
	};
	for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
		geometry_spec gs = {SHAPE_FILE, 0, 0, {0, 0, 0}, cases[k].file, 1};
		dem_geometry g;
		int rc = geometry_build(&gs, &g);
		CHECK(rc == 0);
		if (rc) {
			fprintf(stderr, "%s\n", err_msg());
			continue;
		}
		CHECK_STR(g.shape, "file");
		CHECK_STR(g.source, cases[k].file);
		CHECK_REL(g.volume, cases[k].volume, cases[k].tol);
		CHECK_REL(mesh_volume(&g), g.volume, 1e-12);
		CHECK(geometry_inner_volume(&g, 0.001) < 0);
		free(g.vert);
		free(g.tri);
	}
	/* --scale multiplies the coordinates of unit-less formats. */
	geometry_spec gs = {SHAPE_FILE, 0, 0, {0, 0, 0}, GEO "box_20mm.brep", 0.5};
	dem_geometry g;
	CHECK(geometry_build(&gs, &g) == 0);
	CHECK_REL(g.volume, 1e-6, 1e-12);
	free(g.vert);
	free(g.tri);
	/* and not those of a STEP file, read in metres. */
	gs = (geometry_spec){SHAPE_FILE, 0, 0, {0, 0, 0}, GEO "cylinder_20x40_mm.step", 0.001};
	CHECK(geometry_build(&gs, &g) == 0);
	CHECK_REL(g.volume, M_PI * 0.01 * 0.01 * 0.04, 1e-3);
	free(g.vert);
	free(g.tri);
	CHECK(geometry_is_step("a/b.STP") && geometry_is_step("c.step") &&
	      !geometry_is_step("d.brep") && !geometry_is_step("step"));
}

static void test_bad_files(void)
{
	dem_geometry g;
	geometry_spec open = {SHAPE_FILE, 0, 0, {0, 0, 0}, GEO "open_box.geo", 1};
	CHECK(geometry_build(&open, &g) == -1);
	CHECK_STR(err_msg(), GEO "open_box.geo: the boundary is not a closed surface: 24 edges "
	                         "belong to only one triangle (an open surface encloses no volume "
	                         "to fill)");
	geometry_spec missing = {SHAPE_FILE, 0, 0, {0, 0, 0}, "no/such/file.step", 1};
	CHECK(geometry_build(&missing, &g) == -1);
	CHECK_STR(err_msg(), "no/such/file.step: cannot open: No such file or directory");
	const char *bad = check_tmp("garbage.geo");
	FILE *f = fopen(bad, "w");
	fputs("this is not a geometry;\n", f);
	fclose(f);
	geometry_spec garbage = {SHAPE_FILE, 0, 0, {0, 0, 0}, bad, 1};
	CHECK(geometry_build(&garbage, &g) == -1);
	CHECK_CONTAINS(err_msg(), "garbage.geo");
	CHECK_CONTAINS(err_msg(), "line 1");
}

/* Append a cube of edge `edge` with its lowest corner at (x, y, z); with
 * `flip`, every other triangle points into it. */
static void add_cube(trimesh *m, double x, double y, double z, double edge, int flip)
{
	static const double unit[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
	                                  {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
	static const int32_t faces[12][3] = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7},
	                                     {0, 1, 5}, {0, 5, 4}, {1, 2, 6}, {1, 6, 5},
	                                     {2, 3, 7}, {2, 7, 6}, {3, 0, 4}, {3, 4, 7}};
	const double lo[3] = {x, y, z};
	int32_t base = (int32_t)m->nvert;
	m->vert = realloc(m->vert, 3 * (m->nvert + 8) * sizeof *m->vert);
	m->tri = realloc(m->tri, 3 * (m->ntri + 12) * sizeof *m->tri);
	for (int v = 0; v < 8; v++)
		for (int k = 0; k < 3; k++)
			m->vert[3 * (base + v) + k] = lo[k] + edge * unit[v][k];
	for (int t = 0; t < 12; t++) {
		int32_t *o = m->tri + 3 * (m->ntri + t);
		int f = flip && t % 2;
		o[0] = base + faces[t][0];
		o[1] = base + faces[t][f ? 2 : 1];
		o[2] = base + faces[t][f ? 1 : 2];
	}
	m->nvert += 8;
	m->ntri += 12;
}

/* A cube with every other triangle flipped and a smaller cube inside it
 * (a cavity): orientation makes the outer normals point out and the
 * cavity's point into the cavity, so the volume is the difference. */
static void test_orientation(void)
{
	trimesh m = {0};
	add_cube(&m, 0, 0, 0, 1, 1);
	add_cube(&m, 0.25, 0.25, 0.25, 0.5, 1);
	CHECK(trimesh_close(&m, "cubes") == 0);
	double v, a, lo[3], hi[3];
	trimesh_measure(&m, &v, &a, lo, hi);
	CHECK_NEAR(v, 1 - 0.125, 1e-15);
	CHECK_NEAR(a, 6 + 1.5, 1e-15);
	/* A triangle across the outer cube leaves one of its edges open... */
	m.tri = realloc(m.tri, 78 * sizeof(int32_t));
	int32_t extra[6] = {0, 1, 6, 0, 6, 1};
	memcpy(m.tri + 72, extra, sizeof extra);
	m.ntri = 25;
	CHECK(trimesh_close(&m, "cubes") == -1);
	CHECK_STR(err_msg(), "cubes: the boundary is not a closed surface: 1 edge belongs to only "
	                     "one triangle (an open surface encloses no volume to fill)");
	/* ...and its reverse closes it, but two edges then have four triangles. */
	m.ntri = 26;
	CHECK(trimesh_close(&m, "cubes") == -1);
	CHECK_STR(err_msg(), "cubes: the boundary is not a manifold surface: 2 edges are shared by "
	                     "more than two triangles");
	trimesh_free(&m);
}

/* A cube whose triangles each have their own three vertices, numbered
 * backwards: welding leaves its 8 corners in order of first use, and a
 * triangle that points in is flipped from (a, b, c) to (a, c, b). */
static void test_weld(void)
{
	trimesh cube = {0};
	add_cube(&cube, 0, 0, 0, 1, 1);
	trimesh m = {36, 12, malloc(108 * sizeof(double)), malloc(36 * sizeof(int32_t))};
	for (int k = 0; k < 36; k++) {
		memcpy(m.vert + 3 * (35 - k), cube.vert + 3 * cube.tri[k], 3 * sizeof(double));
		m.tri[k] = 35 - k;
	}
	CHECK(trimesh_close(&m, "cube") == 0);
	CHECK(m.nvert == 8);
	static const double first[4][3] = {{0, 0, 0}, {1, 1, 0}, {1, 0, 0}, {0, 1, 0}};
	for (int i = 0; i < 4; i++)
		for (int k = 0; k < 3; k++)
			CHECK(m.vert[3 * i + k] == first[i][k]);
	static const int32_t tri[6] = {0, 1, 2, 0, 3, 1};
	for (int k = 0; k < 6; k++)
		CHECK(m.tri[k] == tri[k]);
	double v, a, lo[3], hi[3];
	trimesh_measure(&m, &v, &a, lo, hi);
	CHECK_NEAR(v, 1, 1e-15);
	trimesh_free(&m);
	trimesh_free(&cube);
}

/* trimesh_close refuses m with message msg. */
static void refused(trimesh *m, const char *msg)
{
	CHECK(trimesh_close(m, "mesh") == -1);
	CHECK_STR(err_msg(), msg);
	trimesh_free(m);
}

/* Boundaries that enclose no well-defined solid. */
static void test_defects(void)
{
	trimesh m = {0};
	refused(&m, "mesh: no surface triangles: the geometry has no closed boundary");
	/* A triangle between a corner and a copy of it. */
	add_cube(&m, 0, 0, 0, 1, 0);
	m.vert = realloc(m.vert, 27 * sizeof(double));
	m.tri = realloc(m.tri, 39 * sizeof(int32_t));
	memcpy(m.vert + 24, m.vert, 3 * sizeof(double));
	int32_t collapsed[3] = {0, 8, 1};
	memcpy(m.tri + 36, collapsed, sizeof collapsed);
	m.nvert = 9;
	m.ntri = 13;
	refused(&m, "mesh: the boundary has 1 degenerate triangle (two corners at one point)");
	/* The projective plane: 10 triangles, every edge shared by two, no
	 * consistent orientation (Euler characteristic 6 - 15 + 10 = 1). */
	static const int32_t rp2[10][3] = {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 5}, {0, 5, 1},
	                                   {1, 2, 4}, {2, 3, 5}, {3, 4, 1}, {4, 5, 2}, {5, 1, 3}};
	static const double corners[6][3] = {{0, 0, 1},  {1, 0, 0},  {0, 1, 0},
	                                     {-1, 0, 0}, {0, -1, 0}, {0.3, 0.2, -1}};
	m = (trimesh){6, 10, malloc(sizeof corners), malloc(sizeof rp2)};
	memcpy(m.vert, corners, sizeof corners);
	memcpy(m.tri, rp2, sizeof rp2);
	refused(&m, "mesh: the boundary surface is not orientable");
	/* Two cubes that touch at a corner. */
	add_cube(&m, 0, 0, 0, 1, 0);
	add_cube(&m, 1, 1, 1, 1, 0);
	refused(&m, "mesh: the boundary is not a manifold surface: 1 vertex is shared by "
	            "surfaces that meet only there");
	/* Two cubes that overlap. */
	add_cube(&m, 0, 0, 0, 1, 0);
	add_cube(&m, 0.5, 0.5, 0.5, 1, 0);
	refused(&m, "mesh: the boundary surface intersects itself (triangles that cross, or of "
	            "zero area): its inside is not defined");
}

/* A built-in shape's extent, known before meshing (pack makes its periodic
 * cell from it while gmsh meshes), is the one the built mesh reports, and
 * the mesh fills that box; a file has no extent before it is read. */
static void test_extent(void)
{
	const geometry_spec shapes[3] = {{SHAPE_CYLINDER, 0.05, 0.1, {0, 0, 0}, NULL, 1},
	                                 {SHAPE_DISC, 0.0378, 0.0219, {0, 0, 0}, NULL, 1},
	                                 {SHAPE_BOX, 0, 0, {0.02, 0.03, 0.04}, NULL, 1}};
	for (int k = 0; k < 3; k++) {
		dem_geometry e, g;
		CHECK(geometry_extent(&shapes[k], &e) == 0);
		CHECK(e.nvert == 0 && e.ntri == 0 && e.vert == NULL);
		CHECK(geometry_build(&shapes[k], &g) == 0);
		CHECK_STR(e.shape, g.shape);
		CHECK(e.volume == g.volume && e.diameter == g.diameter && e.height == g.height);
		trimesh m = {g.nvert, g.ntri, g.vert, g.tri};
		double v, a, lo[3], hi[3];
		trimesh_measure(&m, &v, &a, lo, hi);
		for (int j = 0; j < 3; j++) {
			CHECK(e.bbox_min[j] == g.bbox_min[j] && e.bbox_max[j] == g.bbox_max[j]);
			CHECK(e.size[j] == g.size[j] && e.axis[j] == g.axis[j]);
			CHECK_NEAR(lo[j], e.bbox_min[j], 1e-15);
			CHECK_NEAR(hi[j], e.bbox_max[j], 1e-15);
		}
		free(g.vert);
		free(g.tri);
	}
	geometry_spec file = {SHAPE_FILE, 0, 0, {0, 0, 0}, GEO "cylinder_50x100.geo", 1};
	dem_geometry g = {.volume = 7};
	CHECK(geometry_extent(&file, &g) == -1 && g.volume == 7);
}

int main(void)
{
	test_builtin_cylinder();
	test_builtin_disc_and_box();
	test_extent();
	test_files();
	test_bad_files();
	test_orientation();
	test_weld();
	test_defects();
	return check_done();
}
