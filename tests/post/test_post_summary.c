/* post summary on run files written here with known histories: a
 * triaxial test whose deviator rises linearly (modulus E0, Poisson ratio
 * NU0) to a peak and softens, the same with an unload-reload cycle
 * (the modulus is the first loading branch's), a Brazilian test of known peak load, a
 * hydrostatic ramp of known bulk modulus; the figures of summary.json are
 * those of the construction, a fast loading is flagged, and the file is
 * written to --out. */
#include <math.h>

#include "lib/cfg.h"
#include "lib/runfile.h"
#include "tests/check.h"
#include "tests/post/harness.h"

#define PI 3.14159265358979323846
enum { ROWS = 101, PEAK_ROW = 40 };
static const double E0 = 10e9, NU0 = 0.25, PC = 5e6, DE = 1e-4, K0 = 4e9, PMAX = 8e6;
static const double D = 0.04, T = 0.02;

static const run_column cols[] = {
    {"t", "s"},
    {"step", ""},
    {"strain_axial", ""},
    {"stress_axial", "Pa"},
    {"strain_radial", ""},
    {"strain_volumetric", ""},
    {"pressure", "Pa"},
    {"force_axial", "N"},
    {"energy_kinetic", "J"},
    {"energy_elastic", "J"},
    {"bonds_broken_tension", ""},
    {"bonds_broken_shear", ""},
    {"rate", "1/s"},
};
enum { NCOLS = sizeof cols / sizeof cols[0] };

/* BTS_RISING: a Brazilian test whose load still rises when its strain stop
 * ends it (no peak); INTERRUPTED: the triaxial history of a run stopped
 * by Ctrl-C before its stop rule. */
typedef enum { TRIAXIAL, BTS, HYDROSTATIC, CYCLE, BTS_RISING, INTERRUPTED } kind;

/* Deviator of the triaxial history: E0 e up to the peak row, then falling
 * linearly to half the peak at the last row. */
static double deviator(int k)
{
	double qp = E0 * DE * PEAK_ROW;
	return k <= PEAK_ROW ? E0 * DE * k
	                     : qp * (1 - 0.5 * (k - PEAK_ROW) / (ROWS - 1 - PEAK_ROW));
}

/* Axial strain and deviator of a history with an unload-reload cycle:
 * loading at E0 to row 20, unloading at 3 E0 to row 30 (the strain falls
 * by 2 DE), then loading at 3 E0 to the end (the peak, at the last row). */
static void cycle(int k, double *e, double *q)
{
	if (k <= 20)
		*e = DE * k, *q = E0 * *e;
	else if (k <= 30)
		*e = DE * (20 - 0.2 * (k - 20)), *q = E0 * DE * 20 - 3 * E0 * (DE * 20 - *e);
	else
		*e = DE * (18 + (k - 30)), *q = E0 * DE * 14 + 3 * E0 * (*e - DE * 18);
}

/* Axial force of the Brazilian history: 5 kN at row 30, zero at both ends. */
static double bts_force(int k) { return k <= 30 ? 5e3 * k / 30 : 5e3 * (ROWS - 1 - k) / 70; }

static void write_run(const char *path, kind kd, double ke_fraction)
{
	double x[6] = {0, 0, 0, 0, 0, 2e-3}, r[2] = {1e-3, 1e-3};
	int32_t mat[2] = {0, 0};
	dem_assembly a = {.n = 2, .x = x, .r = r, .material = mat};
	prov_init(&a.prov, "pack", "{}", 0);
	int bts = kd == BTS || kd == BTS_RISING;
	strcpy(a.geom.shape, bts ? "disc" : "cylinder");
	a.geom.axis[2] = 1;
	a.geom.diameter = D;
	a.geom.height = T;
	a.report.solid_fraction = 0.55;
	static const char *config[] = {
	    "{\"test\":\"triaxial\",\"material\":{\"name\":\"test cement\",\"law\":\"onate\"}}",
	    "{\"test\":\"bts\",\"material\":{\"name\":\"test cement\",\"law\":\"onate\"}}",
	    "{\"test\":\"hydrostatic\",\"material\":{\"name\":\"test cement\",\"law\":\"onate\"}}",
	    "{\"test\":\"triaxial\",\"material\":{\"name\":\"test cement\",\"law\":\"onate\"}}",
	    "{\"test\":\"bts\",\"material\":{\"name\":\"test cement\",\"law\":\"onate\"}}",
	    "{\"test\":\"triaxial\",\"material\":{\"name\":\"test cement\",\"law\":\"onate\"}}"};
	dem_provenance prov;
	prov_init(&prov, "solve", config[kd], 0);
	run_writer *w = run_create(path, &prov, &a, cols, NCOLS);
	int32_t bi[1] = {0}, bj[1] = {1};
	double d0[1] = {2e-3}, area[1] = {1e-6}, kn[1] = {1e6};
	dem_bonds b = {.n = 1, .i = bi, .j = bj, .d0 = d0, .area = area, .kn = kn, .ks = kn};
	CHECK(w && run_write_bonds(w, &b) == 0);
	for (int k = 0; w && k < ROWS; k++) {
		double e = DE * k, p = PC, sa = PC + deviator(k), er = -NU0 * e, ev = e + 2 * er;
		double f = kd == BTS_RISING ? 5e3 * k / (ROWS - 1) : bts_force(k);
		if (bts)
			p = 0, sa = f / (PI * D * D / 4);
		if (kd == HYDROSTATIC)
			p = sa = PMAX * k / (ROWS - 1), ev = p / K0, e = ev / 3, er = ev / 3;
		if (kd == CYCLE) {
			double qc;
			cycle(k, &e, &qc);
			sa = PC + qc, er = -NU0 * e, ev = e + 2 * er;
		}
		double row[NCOLS] = {
		    1e-6 * k, 100.0 * k, e,         sa,        er, ev, p, f, ke_fraction * (1 + e),
		    1 + e,    k / 2,     k - k / 2, 1000.0 + k};
		CHECK(run_history(w, row) == 0);
	}
	CHECK(w && run_finish(w, kd == BTS_RISING    ? "stopped: axial strain reached 0.03"
	                         : kd == INTERRUPTED ? "interrupted"
	                                             : "complete") == 0);
	prov_free(&prov);
	prov_free(&a.prov);
}

/* warn: 0 none, 1 not quasi-static, 2 no peak, 3 not finished. */
static cfg *summary_of(const char *dir, const char *run, int warn)
{
	post_result res = harness_post("summary --out %s/out %s", dir, run);
	CHECK(res.status == 0);
	if (warn == 1)
		CHECK_CONTAINS(res.err, "the loading is too fast to be quasi-static");
	else if (warn == 2)
		CHECK_CONTAINS(res.err, "no peak: the axial-strain stop ended the run with the "
		                        "stress within 1 % of its highest");
	else if (warn == 3)
		CHECK_CONTAINS(res.err, "the run did not reach its stop rule (status "
		                        "'interrupted'): the peak and the other figures are those "
		                        "of its history so far (solve --restart continues it)");
	else
		CHECK_STR(res.err, "");
	harness_free(&res);
	char path[1200];
	snprintf(path, sizeof path, "%s/out/summary.json", dir);
	cfg *c = cfg_load(path);
	CHECK(c != NULL);
	return c;
}

static double num(cfg *c, const char *key)
{
	double v = NAN;
	CHECK(cfg_number(c, key, &v, "", -INFINITY, INFINITY) == 0);
	return v;
}

int main(void)
{
	char dir[1024], run[1100];
	harness_dir(dir, sizeof dir, "summary");
	snprintf(run, sizeof run, "%s/run.h5", dir);

	write_run(run, TRIAXIAL, 0.01);
	cfg *c = summary_of(dir, run, 0);
	const char *s = NULL;
	CHECK(cfg_string(c, "test", &s) == 0 && strcmp(s, "triaxial") == 0);
	CHECK(cfg_string(c, "material", &s) == 0 && strcmp(s, "test cement") == 0);
	CHECK(cfg_string(c, "case", &s) == 0 && strcmp(s, "summary") == 0);
	CHECK_REL(num(c, "young_modulus"), E0, 1e-9);
	CHECK_REL(num(c, "poisson_ratio"), NU0, 1e-9);
	CHECK_REL(num(c, "peak_deviator"), E0 * DE * PEAK_ROW, 1e-12);
	CHECK_REL(num(c, "peak_stress"), PC + E0 * DE * PEAK_ROW, 1e-12);
	CHECK_REL(num(c, "strain_at_peak"), DE * PEAK_ROW, 1e-12);
	CHECK_REL(num(c, "confining_pressure"), PC, 1e-12);
	CHECK_REL(num(c, "residual_deviator"), 0.5 * E0 * DE * PEAK_ROW, 1e-12);
	CHECK_REL(num(c, "bonds_broken_tension"), (ROWS - 1) / 2, 1e-12);
	CHECK_REL(num(c, "bonds_broken_shear"), ROWS - 1 - (ROWS - 1) / 2, 1e-12);
	CHECK_REL(num(c, "spheres"), 2, 0);
	CHECK_REL(num(c, "solid_fraction"), 0.55, 0);
	double wall = 0;
	for (int k = 1; k < ROWS; k++)
		wall += 100 / (1000.0 + k);
	CHECK_REL(num(c, "wall_time"), wall, 1e-9);
	CHECK_REL(num(c, "particle_steps_per_second"), 2 * 100.0 * (ROWS - 1) / wall, 1e-9);
	CHECK(num(c, "kinetic_elastic_ratio") <= 0.01 + 1e-12);
	char *text = cfg_text(c);
	CHECK_CONTAINS(text, "\"bts_strength\":null");
	CHECK_CONTAINS(text, "\"quasi_static\":true");
	free(text);
	cfg_free(c);

	write_run(run, TRIAXIAL, 0.2);
	c = summary_of(dir, run, 1);
	text = cfg_text(c);
	CHECK_CONTAINS(text, "\"quasi_static\":false");
	free(text);
	cfg_free(c);

	write_run(run, BTS, 0.01);
	c = summary_of(dir, run, 0);
	CHECK_REL(num(c, "peak_force"), 5e3, 1e-12);
	CHECK_REL(num(c, "bts_strength"), 2 * 5e3 / (PI * D * T), 1e-10);
	text = cfg_text(c);
	CHECK_CONTAINS(text, "\"young_modulus\":null");
	free(text);
	cfg_free(c);

	/* A load still rising at the strain stop: the strength is the stop's,
	 * and the summary says so. */
	write_run(run, BTS_RISING, 0.01);
	c = summary_of(dir, run, 2);
	CHECK_REL(num(c, "peak_force"), 5e3, 1e-12);
	text = cfg_text(c);
	CHECK_CONTAINS(text, "\"warning\":\"no peak: ");
	free(text);
	cfg_free(c);

	/* the modulus of the first loading branch, not of the reloading */
	write_run(run, CYCLE, 0.01);
	c = summary_of(dir, run, 0);
	CHECK_REL(num(c, "young_modulus"), E0, 1e-9);
	CHECK_REL(num(c, "peak_deviator"), E0 * DE * (14 + 3 * (ROWS - 1 - 30)), 1e-9);
	cfg_free(c);

	/* an interrupted run: the figures of its history so far, and a
	 * warning saying so, in summary.json too */
	write_run(run, INTERRUPTED, 0.01);
	c = summary_of(dir, run, 3);
	CHECK_REL(num(c, "peak_stress"), PC + E0 * DE * PEAK_ROW, 1e-12);
	text = cfg_text(c);
	CHECK_CONTAINS(text, "\"status\":\"interrupted\"");
	CHECK_CONTAINS(text, "\"warning\":\"the run did not reach its stop rule");
	free(text);
	cfg_free(c);

	write_run(run, HYDROSTATIC, 0.01);
	c = summary_of(dir, run, 0);
	CHECK_REL(num(c, "bulk_modulus"), K0, 1e-9);
	CHECK_REL(num(c, "pressure_final"), PMAX, 1e-12);
	cfg_free(c);
	return check_done();
}
