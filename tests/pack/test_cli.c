/* The pack program end to end on small specimens: every bad input gives one
 * message, a non-zero exit and no output file; every geometry source gives
 * a valid assembly; the same seed gives the same spheres, another seed
 * others; x y z r export and import round-trip; a --config file is the
 * same as the options it holds. (Thread counts: test_density.c.) */
#include "tests/pack/run.h"

#include "lib/err.h"
#include "pack/geometry.h"
#include "pack/surface.h"

#define SMALL "--shape box --length 0.012 --width 0.012 --height 0.012"

static const char *out_path(void) { return check_tmp("cli_out.h5"); }

static void write_file(const char *path, const char *text)
{
	FILE *f = fopen(path, "w");
	fputs(text, f);
	fclose(f);
}

/* pack <args> OUT must fail with status `status` and exactly `message` on
 * stderr (or a message starting with it when prefix), leaving no file. */
static void refused(int status, const char *message, int prefix, const char *args)
{
	const char *out = out_path();
	char tmp[1100];
	snprintf(tmp, sizeof tmp, "%s.tmp", out);
	remove(out);
	harness_result r = run_pack("%s %s", args, out);
	CHECK(r.status == status);
	if (prefix)
		CHECK(strncmp(r.err, message, strlen(message)) == 0);
	else
		CHECK_STR(r.err, message);
	if (r.status != status ||
	    (prefix ? strncmp(r.err, message, strlen(message)) != 0 : strcmp(r.err, message) != 0))
		fprintf(stderr, "  for: pack %s\n  got status %d: %s", args, r.status, r.err);
	CHECK(!harness_exists(out));
	CHECK(!harness_exists(tmp));
	harness_free(&r);
}

/* refused(), with `text` first written to the scratch file `name`; `opts`
 * and `message` are formats naming that file by "%s" (at most twice). */
static void refused_file(int status, const char *name, const char *text, const char *opts,
                         const char *message, int prefix)
{
	char path[1024], args[2048], msg[4096];
	snprintf(path, sizeof path, "%s", check_tmp(name));
	write_file(path, text);
	snprintf(args, sizeof args, opts, path, path);
	snprintf(msg, sizeof msg, message, path, path);
	refused(status, msg, prefix, args);
}

static void test_bad_input(void)
{
	/* An output that would overwrite an input or another output. */
	char clash[2200], message[4400];
	snprintf(clash, sizeof clash, "--depfile %s", out_path());
	snprintf(message, sizeof message,
	         "pack: --depfile %s would overwrite OUTPUT %s: expected another file name "
	         "(usage: ",
	         out_path(), out_path());
	refused(2, message, 1, clash);
	refused(2, "pack: --depfile ./x.d would overwrite --export x.d: expected another file name",
	        1, "--export x.d --depfile ./x.d");
	refused(2, "pack: --export '/tmp': expected a file name (this is a directory)", 1,
	        "--export /tmp");
	refused(2,
	        "pack: --export share/specimens/demo.json would overwrite --config "
	        "share/specimens/demo.json: expected another file name",
	        1, "--config share/specimens/demo.json --export share/specimens/demo.json");
	refused(1, "pack: --rmin 0.002 is larger than --rmax 0.0015: expected rmin <= rmax (m)\n",
	        0, "--rmin 0.002 --rmax 0.0015");
	refused(2, "pack: --rmin -0.001: expected a number in [1e-09, 1000] (m)\n", 0,
	        "--rmin -0.001");
	refused(2, "pack: --diameter -0.05: expected a number in [1e-06, 1000] (m)\n", 0,
	        "--diameter -0.05");
	/* A 1 nm box made the geometry kernel throw. */
	refused(2, "pack: --length 1e-9: expected a number in [1e-06, 1000] (m)\n", 0,
	        "--shape box --length 1e-9");
	/* Sizes that would need petabytes. */
	refused(1,
	        "pack: --radius 1e-07 m: the specimen (2.45e-05 m^3) would hold about 3.61e+15 "
	        "spheres of these sizes: expected at most 1e+09 (larger radii, or --count)\n",
	        0, "--dist fuzz --radius 1e-7 --fuzz 0.2");
	refused(1, "pack: --threads 4000: expected at most ", 1, "--threads 4000");
	refused(1, "pack: --geometry /tmp: a directory: expected a geometry file\n", 0,
	        "--geometry /tmp");
	refused(1,
	        "pack: --geometry share/specimens/demo.json: expected a file gmsh reads, named "
	        ".geo, .step/.stp, .brep, .msh or .stl (a specimen file goes to --config)\n",
	        0, "--geometry share/specimens/demo.json");
	refused(1,
	        "pack: spheres of radius up to 0.012 m do not fit in the specimen: expected the "
	        "largest diameter below its smallest extent (0.02 m)\n",
	        0, "--diameter 0.02 --height 0.04 --rmin 0.01 --rmax 0.012");
	refused(1,
	        "pack: share/geometry/open_box.geo: the boundary is not a closed surface: 24 edges "
	        "belong to only one triangle (an open surface encloses no volume to fill)\n",
	        0, "--geometry share/geometry/open_box.geo");
	/* gmsh's Exit command in a geometry file. */
	refused_file(
	    1, "cli_exit.geo",
	    "SetFactory(\"OpenCASCADE\");\nBox(1) = {0, 0, 0, 0.012, 0.012, 0.012};\nExit;\n",
	    "--geometry %s",
	    "pack: %s: the geometry file ended the program while gmsh read it (an 'Exit' "
	    "command?): expected a geometry to fill\n",
	    0);
	refused(1, "pack: no/such/specimen.step: cannot open: No such file or directory\n", 0,
	        "--geometry no/such/specimen.step");
	refused_file(1, "garbage.geo", "this is not a geometry;\n", "--geometry %s",
	             "pack: %s: '%s', line 1: ", 1);
	refused(1, "pack: --count 3: too few spheres: they would need radii up to ", 1,
	        "--count 3");
	refused(2, "pack: --count 2000000000: expected an integer in [0, 1e+09]\n", 0,
	        "--count 2000000000");
	refused(1, "pack: --count 1000 and --mean-radius 0.001: expected one of them, not both\n",
	        0, "--count 1000 --mean-radius 0.001");
	refused(1, "pack: --dist weibull: expected uniform, fuzz, lognormal or grading\n", 0,
	        "--dist weibull");
	refused(1, "pack: --shape sphere: expected cylinder, disc or box (or --geometry FILE)\n", 0,
	        "--shape sphere");
	refused(1,
	        "pack: --dist grading: expected --grading FILE.json (sieve sizes and fractions "
	        "passing)\n",
	        0, "--dist grading");
	refused_file(1, "mix.json", "{\"sieve\": [0.001, 0.004], \"passing\": [0, 0.9]}",
	             "--dist grading --grading %s",
	             "pack: %s: key 'passing': last value 0.9: expected 1 (everything passes the "
	             "largest sieve)\n",
	             0);
	refused_file(1, "bad_list.txt", "0 0 0 0.001\n0 0 0.001\n", "--import %s",
	             "pack: %s: line 2: expected four numbers 'x y z r' (m)\n", 0);
	refused_file(1, "bad_list.txt", "0 0 0 0.001\n0.5 0 0 0.001\n", "--import %s",
	             "pack: %s: sphere 2 at (0.5, 0, 0) m lies outside the specimen\n", 0);
	refused_file(1, "bad_list.txt", "0 0 0 0.001\n", "--import %s --count 3000",
	             "pack: --import %s: the spheres are taken as listed: --count and "
	             "--mean-radius do not apply (expected 0)\n",
	             0);
	refused_file(1, "bad_config.json", "{\"diamter\": 0.05}", "--config %s",
	             "pack: %s: key 'diamter': unknown key (misspelt, or not used by this "
	             "program)\n",
	             0);
	refused_file(1, "bad_config.json", "{\"rmax\": -1}", "--config %s",
	             "pack: %s: key 'rmax': value -1: expected", 1);
	harness_result r = run_pack("--quiet " SMALL " no/such/dir/out.h5");
	CHECK(r.status == 1);
	CHECK(strncmp(r.err, "pack: no/such/dir/out.h5", 24) == 0);
	harness_free(&r);
}

/* Every centre lies inside the specimen, at least a radius less 1 % deep,
 * and no pair overlaps by 1 % of the smaller radius. */
static void check_valid(const char *path, const char *what)
{
	dem_assembly a;
	if (assembly_read(path, &a)) {
		CHECK(0);
		fprintf(stderr, "%s: %s\n", what, err_msg());
		return;
	}
	CHECK(a.n > 50);
	surface *s = surface_new(a.geom.vert, a.geom.nvert, a.geom.tri, a.geom.ntri);
	double worst = 0;
	for (size_t i = 0; i < a.n; i++)
		worst =
		    fmax(worst, (a.r[i] - surface_distance(s, a.x + 3 * i, NULL, NULL)) / a.r[i]);
	CHECK(worst < 0.01);
	CHECK(run_max_overlap(&a) < 0.01);
	CHECK(a.report.solid_fraction > 0.5);
	if (worst >= 0.01 || a.report.solid_fraction <= 0.5)
		fprintf(stderr, "  %s: boundary %g, solid fraction %g\n", what, worst,
		        a.report.solid_fraction);
	surface_free(s);
	assembly_free(&a);
}

static void test_geometry_sources(void)
{
	static const char *sources[][2] = {
	    {"cylinder", "--diameter 0.016 --height 0.02"},
	    {"disc", "--shape disc --diameter 0.02 --thickness 0.01"},
	    {"box", SMALL},
	    {".geo", "--geometry share/geometry/disc_brazilian.geo --mean-radius 0.0015"},
	    {".brep", "--geometry share/geometry/box_20mm.brep --mean-radius 0.0015"},
	    {".step", "--geometry share/geometry/cylinder_20x40_mm.step --mean-radius 0.0015"},
	    {".msh", "--geometry share/geometry/cylinder_20x40.msh --mean-radius 0.0015"},
	};
	for (size_t k = 0; k < sizeof sources / sizeof sources[0]; k++) {
		harness_result r = run_pack("--quiet %s %s", sources[k][1], out_path());
		CHECK(r.status == 0);
		if (r.status)
			fprintf(stderr, "  %s: %s", sources[k][0], r.err);
		harness_free(&r);
		check_valid(out_path(), sources[k][0]);
	}
}

static int same_spheres(const char *p, const char *q)
{
	dem_assembly a, b;
	if (assembly_read(p, &a))
		return 0;
	if (assembly_read(q, &b)) {
		assembly_free(&a);
		return 0;
	}
	int same = a.n == b.n && memcmp(a.x, b.x, 3 * a.n * sizeof *a.x) == 0 &&
	           memcmp(a.r, b.r, a.n * sizeof *a.r) == 0;
	assembly_free(&a);
	assembly_free(&b);
	return same;
}

static void test_seed(void)
{
	const char *one = check_tmp("cli_s1.h5"), *two = check_tmp("cli_s2.h5");
	harness_result r1 = run_pack("--quiet " SMALL " --seed 1 %s", one);
	harness_result r2 = run_pack("--quiet " SMALL " --seed 1 %s", two);
	CHECK(r1.status == 0 && r2.status == 0);
	CHECK(same_spheres(one, two));
	harness_free(&r1);
	harness_free(&r2);
	r2 = run_pack("--quiet " SMALL " --seed 2 %s", two);
	CHECK(r2.status == 0);
	CHECK(!same_spheres(one, two));
	harness_free(&r2);
}

static void test_export_import(void)
{
	const char *a = check_tmp("cli_a.h5"), *b = check_tmp("cli_b.h5");
	const char *txt = check_tmp("cli_a.txt");
	harness_result r = run_pack("--quiet " SMALL " --export %s %s", txt, a);
	CHECK(r.status == 0);
	harness_free(&r);
	r = run_pack(SMALL " --import %s %s", txt, b);
	CHECK(r.status == 0);
	CHECK_CONTAINS(r.out, "pack: ");
	harness_free(&r);
	CHECK(same_spheres(a, b));
	dem_assembly x, y;
	CHECK(assembly_read(a, &x) == 0 && assembly_read(b, &y) == 0);
	CHECK_NEAR(x.report.solid_fraction, y.report.solid_fraction, 1e-15);
	CHECK_NEAR(x.report.coordination, y.report.coordination, 1e-15);
	assembly_free(&x);
	assembly_free(&y);

	/* Imported spheres must fit in the specimen and be distinct. */
	refused_file(1, "cli_bad.txt", "0 0 0 0.001\n0.003 0 0 0.006\n", SMALL " --import %s",
	             "pack: %s: sphere 2 of radius 0.006 m does not fit in the specimen: expected "
	             "a diameter below its smallest extent (0.012 m)\n",
	             0);
	refused_file(1, "cli_bad.txt", "0 0 0 0.001\n0.003 0 0 0.001\n0 0 0 0.001\n",
	             SMALL " --import %s",
	             "pack: %s: a sphere lies entirely inside another (overlap 200 %% of the "
	             "smaller radius): expected distinct spheres\n",
	             0);
}

/* An --export or --depfile that cannot be written leaves the assembly that
 * was at the output path as it was, and no temporary file. */
static void test_side_output_failure(void)
{
	char keep[1024], copy[1024], tmp[1100];
	snprintf(keep, sizeof keep, "%s", check_tmp("cli_keep.h5"));
	snprintf(copy, sizeof copy, "%s", check_tmp("cli_keep_copy.h5"));
	snprintf(tmp, sizeof tmp, "%s.tmp", keep);
	harness_result r = run_pack("--quiet " SMALL " --seed 3 %s", keep);
	CHECK(r.status == 0);
	harness_free(&r);
	r = run_pack("--quiet " SMALL " --seed 3 %s", copy);
	harness_free(&r);
	static const char *const side[] = {"--export /nonexistent/x.txt",
	                                   "--depfile /nonexistent/x.d"};
	for (int k = 0; k < 2; k++) {
		r = run_pack("--quiet " SMALL " --seed 4 %s %s", side[k], keep);
		CHECK(r.status == 1);
		CHECK_CONTAINS(r.err, "/nonexistent/x.");
		harness_free(&r);
		CHECK(same_spheres(keep, copy));
		CHECK(!harness_exists(tmp));
	}
}

/* A setting that does not apply to the shape or size distribution chosen is
 * named in a warning; the settings that do apply give none. */
static void test_ignored_options(void)
{
	static const char *const cases[][2] = {
	    {"--shape disc --height 0.02", "pack: warning: --height does not apply to --shape "
	                                   "disc: ignored\n"},
	    {SMALL " --diameter 0.02", "pack: warning: --diameter does not apply to --shape box: "
	                               "ignored\n"},
	    {SMALL " --fuzz 0.2", "pack: warning: --fuzz does not apply to --dist uniform: "
	                          "ignored\n"},
	    {SMALL " --scale 2", "pack: warning: --scale does not apply without --geometry: "
	                         "ignored\n"},
	    {"--geometry share/geometry/box_20mm.brep --count 300 --diameter 0.03",
	     "pack: warning: --diameter does not apply with --geometry: ignored\n"},
	    {"--geometry share/geometry/cylinder_20x40_mm.step --count 300 --scale 0.001",
	     "pack: warning: --scale does not apply to a STEP file (read in metres): ignored\n"},
	    {SMALL " --dist fuzz --radius 0.0008 --fuzz 0.2", ""},
	};
	for (size_t k = 0; k < sizeof cases / sizeof *cases; k++) {
		harness_result r = run_pack("--quiet %s %s", cases[k][0], out_path());
		CHECK(r.status == 0);
		CHECK_STR(r.err, cases[k][1]);
		harness_free(&r);
	}
	/* A file drawn in millimetres (no unit) read as metres: the specimen's
	 * size says so. */
	const char *geo = check_tmp("cli_mm.geo");
	FILE *f = fopen(geo, "w");
	CHECK(f &&
	      fputs("SetFactory(\"OpenCASCADE\");\nBox(1) = {0, 0, 0, 20, 20, 40};\n", f) >= 0 &&
	      fclose(f) == 0);
	harness_result r = run_pack("--quiet --geometry %s --count 300 %s", geo, out_path());
	CHECK(r.status == 0);
	CHECK_CONTAINS(r.err, "a specimen of 1.6e+04 m^3: if it was drawn in millimetres, give "
	                      "--scale 0.001");
	harness_free(&r);
	/* So do a built-in shape's sizes given in millimetres. */
	r = run_pack("--quiet --diameter 25 --height 50 --count 300 %s", out_path());
	CHECK(r.status == 0);
	CHECK_CONTAINS(r.err, "a specimen of 2.454e+04 m^3: its sizes are in metres (a 25 mm "
	                      "diameter is --diameter 0.025)");
	harness_free(&r);
	/* Spheres too large for any to fit: said, not an HDF5 error. */
	refused(1,
	        "pack: no sphere of radius 0.004 to 0.0049 m fits in the specimen (1e-06 m^3): "
	        "expected smaller spheres (--rmin, --rmax, --mean-radius) or a larger specimen\n",
	        0,
	        "--shape box --length 0.01 --width 0.01 --height 0.01 --rmin 0.004 --rmax 0.0049");
}

/* --grow-to scales every radius by one factor about the same centres, to
 * the solid fraction asked for (recomputed here from the written spheres). */
static void test_grow(void)
{
	const char *a = check_tmp("cli_g0.h5"), *b = check_tmp("cli_g1.h5");
	harness_result r = run_pack("--quiet " SMALL " %s", a);
	CHECK(r.status == 0);
	harness_free(&r);
	r = run_pack(SMALL " --grow-to 0.7 %s", b);
	CHECK(r.status == 0);
	CHECK_CONTAINS(r.out, "to solid fraction 0.7000 (--grow-to)");
	harness_free(&r);
	dem_assembly x, y;
	if (assembly_read(a, &x) || assembly_read(b, &y)) {
		CHECK(0);
		return;
	}
	CHECK(x.n == y.n && x.n > 50);
	double f = y.r[0] / x.r[0], vs = 0, worst = 0;
	for (size_t i = 0; i < x.n && x.n == y.n; i++) {
		for (int k = 0; k < 3; k++)
			worst = fmax(worst, fabs(x.x[3 * i + k] - y.x[3 * i + k]));
		worst = fmax(worst, fabs(y.r[i] / x.r[i] - f));
		vs += 4.0 / 3.0 * M_PI * y.r[i] * y.r[i] * y.r[i];
	}
	CHECK(f > 1.02);
	CHECK(worst < 1e-12);
	CHECK_NEAR(vs / y.geom.volume, 0.7, 1e-12);
	CHECK(y.report.coordination > x.report.coordination);
	assembly_free(&x);
	assembly_free(&y);
	refused(1, "pack: --grow-to 0.3: the spheres already fill 0.", 1, SMALL " --grow-to 0.3");
	/* One sphere imported into a cylinder would grow past the cylinder. */
	const char *one = check_tmp("cli_one.txt");
	FILE *t = fopen(one, "w");
	CHECK(t && fputs("0 0 0.01 0.001\n", t) >= 0 && fclose(t) == 0);
	char args[1200];
	snprintf(args, sizeof args, "--diameter 0.025 --height 0.05 --import %s --grow-to 0.6",
	         one);
	refused(1,
	        "pack: --grow-to 0.6: the spheres fill 0.0002 of the specimen, so their radii "
	        "would grow 15.2 times: expected a dense packing (a factor of at most 1.25, from "
	        "a solid fraction of 0.307): pack or import more spheres first\n",
	        0, args);
}

static void test_config(void)
{
	char cli[1024], file[1024], config[1024]; /* check_tmp's buffers rotate */
	snprintf(cli, sizeof cli, "%s", check_tmp("cli_c1.h5"));
	snprintf(file, sizeof file, "%s", check_tmp("cli_c2.h5"));
	snprintf(config, sizeof config, "%s", check_tmp("cli_config.json"));
	write_file(config, "{\"shape\": \"box\", \"length\": 0.012, \"width\": 0.012,"
	                   " \"height\": 0.012, \"dist\": \"lognormal\", \"radius\": 0.0008,"
	                   " \"sigma\": 0.2, \"seed\": 7}");
	harness_result r1 =
	    run_pack("--quiet " SMALL " --dist lognormal --radius 0.0008 --sigma 0.2 "
	             "--seed 7 %s",
	             cli);
	harness_result r2 = run_pack("--quiet --config %s %s", config, file);
	CHECK(r1.status == 0 && r2.status == 0);
	CHECK(same_spheres(cli, file));
	harness_free(&r1);
	harness_free(&r2);
	/* The command line wins over the file. */
	r2 = run_pack("--quiet --config %s --seed 8 %s", config, file);
	CHECK(r2.status == 0);
	CHECK(!same_spheres(cli, file));
	harness_free(&r2);
	/* A geometry named in the file is found beside it, whatever the current
	 * directory, and the dependency file names both. */
	const char *geo = check_tmp("cli_cube.geo"), *named = check_tmp("cli_named.json");
	const char *dep = check_tmp("cli_named.d");
	write_file(geo, "SetFactory(\"OpenCASCADE\");\nBox(1) = {0, 0, 0, 0.012, 0.012, 0.012};\n");
	write_file(named, "{\"geometry\": \"cli_cube.geo\", \"dist\": \"lognormal\", "
	                  "\"radius\": 0.0008, \"sigma\": 0.2, \"seed\": 7}");
	r2 = run_pack("--quiet --config %s --depfile %s %s", named, dep, file);
	CHECK(r2.status == 0);
	char *rule = harness_slurp(dep), want[4096];
	snprintf(want, sizeof want, "%s: %s %s\n", file, named, geo);
	CHECK(strncmp(rule, want, strlen(want)) == 0);
	free(rule);
	harness_free(&r2);
	/* A grading curve held in the file is the same as one in its own file;
	 * a misspelt key inside it is refused. */
	char mix[1024], held[1024], one[1024], two[1024]; /* check_tmp's buffers rotate */
	snprintf(mix, sizeof mix, "%s", check_tmp("cli_mix.json"));
	snprintf(held, sizeof held, "%s", check_tmp("cli_held.json"));
	snprintf(one, sizeof one, "%s", check_tmp("cli_g1.h5"));
	snprintf(two, sizeof two, "%s", check_tmp("cli_g2.h5"));
	write_file(mix, "{\"sieve\": [0.0012, 0.0024], \"passing\": [0, 1]}");
	r1 = run_pack("--quiet " SMALL " --dist grading --grading %s --seed 4 %s", mix, one);
	write_file(held, "{\"shape\": \"box\", \"length\": 0.012, \"width\": 0.012, "
	                 "\"height\": 0.012, \"dist\": \"grading\", \"seed\": 4, "
	                 "\"grading\": {\"sieve\": [0.0012, 0.0024], \"passing\": [0, 1]}}");
	r2 = run_pack("--quiet --config %s %s", held, two);
	CHECK(r1.status == 0 && r2.status == 0);
	CHECK(same_spheres(one, two));
	harness_free(&r1);
	harness_free(&r2);
	/* --count scales the curve's sizes (real ones), and says by how much
	 * and to which radii (the curve's 0.6 to 1.2 mm: 200 spheres fill the
	 * 12 mm cube with larger ones). */
	r1 = run_pack(SMALL " --dist grading --grading %s --count 200 --seed 4 %s", mix, one);
	CHECK(r1.status == 0);
	double scale = 0, lo = 0, hi = 0;
	const char *said =
	    strstr(r1.err, "pack: --count 200: the grading curve's sizes scaled by ");
	CHECK(said && sscanf(said,
	                     "pack: --count 200: the grading curve's sizes scaled by %lf (radii "
	                     "%lf to %lf mm instead of 0.6 to 1.2)",
	                     &scale, &lo, &hi) == 3);
	CHECK(scale > 1 && scale < 2);
	CHECK_REL(lo, 0.6 * scale, 1e-2);
	CHECK_REL(hi, 1.2 * scale, 1e-2);
	harness_free(&r1);
	write_file(held, "{\"dist\": \"grading\", "
	                 "\"grading\": {\"sieve\": [0.0012, 0.0024], \"pasing\": [0, 1]}}");
	r2 = run_pack("--quiet --config %s %s", held, two);
	char msg[1200];
	snprintf(msg, sizeof msg, "pack: %s: key 'grading.passing': ", held);
	CHECK(r2.status == 1 && strncmp(r2.err, msg, strlen(msg)) == 0);
	harness_free(&r2);
}

int main(void)
{
	test_bad_input();
	test_geometry_sources();
	test_seed();
	test_export_import();
	test_side_output_failure();
	test_ignored_options();
	test_grow();
	test_config();
	return check_done();
}
