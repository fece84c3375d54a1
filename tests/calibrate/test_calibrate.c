/* calibrate's pieces without a run: the projection on the scales, the search
 * space (values and coordinates, the keys that follow the scales), the run
 * log read back as written, the calibration file's checks, and the
 * uncertainties the sensitivities leave. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "calibrate/quantity.h"
#include "calibrate/report.h"
#include "calibrate/runlog.h"
#include "calibrate/scaling.h"
#include "calibrate/search.h"
#include "calibrate/sensitivity.h"
#include "calibrate/space.h"
#include "calibrate/spec.h"
#include "lib/err.h"
#include "tests/check.h"

/* Residuals of quantities at scales off by s0, k0 come back to zero. */
static void test_project(void)
{
	const char *names[] = {"peak_stress", "young_modulus", "strain_at_peak", "poisson_ratio"};
	double c[4], a[4], b[4], sigma, kappa;
	const double s0 = log(1.3), k0 = log(0.8);
	for (int i = 0; i < 4; i++) {
		const quantity *q = &quantities[quantity_find(names[i])];
		a[i] = q->a, b[i] = q->b;
		c[i] = -(a[i] * s0 + b[i] * k0);
	}
	c[3] = 0.5; /* Poisson's ratio: no scale moves it */
	const double open[4] = {-5, 5, -5, 5};
	double f = scaling_project(4, c, a, b, open, &sigma, &kappa);
	CHECK_NEAR(sigma, s0, 1e-5);
	CHECK_NEAR(kappa, k0, 1e-5);
	CHECK_NEAR(f, 0.25, 1e-9);
	/* The stress scale held within 0.1: the best stiffness scale for it. */
	const double box[4] = {-0.1, 0.1, -5, 5};
	scaling_project(4, c, a, b, box, &sigma, &kappa);
	CHECK_NEAR(sigma, 0.1, 1e-12);
	/* Young's modulus asks for k0, the strain for k = s - (s0 - k0). */
	CHECK_NEAR(kappa, (k0 + (0.1 - (s0 - k0))) / 2, 1e-9);
	/* A class without a free key stays at 1. */
	const double held[4] = {-5, 5, 0, 0};
	scaling_project(4, c, a, b, held, &sigma, &kappa);
	CHECK(kappa == 0);
	/* Strains alone fix s/k only: the smallest change along the rest. */
	double cs[1] = {-(s0 - k0)}, as[1] = {1}, bs[1] = {-1};
	scaling_project(1, cs, as, bs, open, &sigma, &kappa);
	CHECK_NEAR(sigma - kappa, s0 - k0, 1e-5);
	CHECK_NEAR(sigma, -kappa, 1e-5);
}

static void test_space(const cal_spec *sp)
{
	space s;
	space_init(&s, sp);
	/* E0 and tensile_strength are the anchors: no search variable. */
	CHECK(s.nz == 0);
	CHECK(s.anchor[CLS_STIFF] == 0 && s.anchor[CLS_STRESS] == 1);
	double v[CAL_MAX_KEYS], S, K, z[CAL_MAX_FREE];
	for (int k = 0; k < sp->nkey; k++)
		v[k] = sp->key[k].start;
	space_coords(&s, v, &S, &K, z);
	CHECK_REL(S, 3.2e6 / 5e6, 1e-12);
	CHECK_REL(K, 40e9 / 28e9, 1e-12);
	double w[CAL_MAX_KEYS];
	space_values(&s, S, K, z, w);
	CHECK_REL(w[0], 40e9, 1e-12);
	CHECK_REL(w[1], 3.2e6, 1e-12);
	/* The other stresses keep their template ratio to the strength. */
	int found = 0;
	for (int k = 2; k < sp->nkey; k++)
		if (strcmp(sp->key[k].name, "LCS1") == 0) {
			CHECK_REL(w[k], 20e6 * S, 1e-12);
			CHECK(!sp->key[k].free && sp->key[k].cls == CLS_STRESS);
			found = 1;
		}
	CHECK(found);
	/* The bounds of the free keys bound the scales. */
	double box[4];
	CHECK(space_scale_box(&s, S, K, z, box) == 0);
	CHECK_NEAR(box[0], log(1e6 / 3.2e6), 1e-12);
	CHECK_NEAR(box[1], log(20e6 / 3.2e6), 1e-12);
	CHECK_NEAR(box[3], log(100e9 / 40e9), 1e-12);
}

/* A free strength tied to the anchor as a ratio: its box, [min / anchor
 * max, max / anchor min], is wider than its bounds at any one anchor
 * value. Every value run stays within the bounds, and a point projected
 * onto them is a point whose scaled copies are what the scaling predicts. */
static void test_bounds(void)
{
	static cal_spec sp;
	sp.law = "onate", sp.scaling = 1, sp.step = 0.5, sp.xtol = 0.02;
	sp.nfree = sp.nkey = 2;
	sp.key[0] = (cal_key){.name = "tensile_strength",
	                      .cls = CLS_STRESS,
	                      .free = 1,
	                      .lo = 1e6,
	                      .hi = 20e6,
	                      .start = 5e6,
	                      .tmpl = 5e6,
	                      .log = 1};
	sp.key[1] = (cal_key){.name = "shear_strength",
	                      .cls = CLS_STRESS,
	                      .free = 1,
	                      .lo = 3e6,
	                      .hi = 100e6,
	                      .start = 16e6,
	                      .tmpl = 16e6,
	                      .log = 1};
	space s;
	space_init(&s, &sp);
	CHECK(s.nz == 1 && s.kind[0] == Z_RATIO);
	double v[CAL_MAX_KEYS];
	for (int i = 0; i <= 8; i++)
		for (int j = 0; j <= 8; j++) {
			/* The anchor over its bounds, the ratio over its box. */
			double S = exp(log(0.2) + i / 8.0 * log(20.0));
			double z[1] = {s.lo[0] + j / 8.0 * (s.hi[0] - s.lo[0])};
			space_values(&s, S, 1, z, v);
			CHECK(v[1] >= 3e6 && v[1] <= 100e6);
			CHECK(v[0] >= 1e6 && v[0] <= 20e6);
		}
	/* The strength at its maximum, the ratio at its box's: the shear
	 * strength would be 2e9, 20 times its maximum. */
	double S = 4, z[1] = {s.hi[0]};
	CHECK(space_project(&s, S, 1, z) == 1);
	CHECK_NEAR(z[0], log(100e6 / 20e6), 1e-12);
	space_values(&s, S, 1, z, v);
	CHECK_REL(v[1], 100e6, 1e-12);
	CHECK(v[1] <= 100e6);
	/* Its scaled copies keep the ratio as run, within the bounds. */
	double box[4];
	CHECK(space_scale_box(&s, S, 1, z, box) == 0);
	CHECK_NEAR(box[1], 0, 1e-12);
	CHECK_NEAR(box[0], log(1e6 / 20e6), 1e-12);
	double w[CAL_MAX_KEYS];
	space_values(&s, S * exp(-1), 1, z, w);
	CHECK_REL(w[1], v[1] * exp(-1), 1e-12);
	CHECK_REL(w[0], v[0] * exp(-1), 1e-12);
	/* A point within the bounds is not moved. */
	z[0] = log(16.0 / 5);
	CHECK(space_project(&s, 1, 1, z) == 0 && z[0] == log(16.0 / 5));

	/* The report: a key at its bound is said to be, one beyond it is not. */
	const cal_key *p = &sp.key[1];
	CHECK(report_bound(p, 50e6) == 0);
	CHECK(report_bound(p, 99e6) == 1 && report_bound(p, 100e6) == 1);
	CHECK(report_bound(p, 3e6) == -1);
	CHECK(report_bound(p, 1.80155e8) == 2 && report_bound(p, 1.8e6) == -2);
	sensitivity sens = {.ran = 0};
	path_point pt = {.v = {5e6, 1.80155e8}, .ok = 1, .fit = {.met = 1}};
	search_result r = {.path = &pt, .npath = 1, .best = 0, .status = SEARCH_MET};
	report rp = {.sp = &sp, .r = &r, .sens = &sens, .met = 1};
	report_diagnose(&rp);
	int above = 0;
	for (int k = 0; k < rp.nnotes; k++) {
		CHECK(!strstr(rp.notes[k], "ended at its upper bound"));
		above += strstr(rp.notes[k], "shear_strength ended at 1.80155e+08, above its "
		                             "bounds [3e+06, 1e+08]") != NULL;
	}
	CHECK(above == 1);
	report_free(&rp);
}

/* A budget that cannot finish the global stage and start the local one is
 * named, with the numbers and what to change. */
static void test_budget(void)
{
	static cal_spec sp;
	sp.law = "onate", sp.source = "cal.json", sp.step = 0.5, sp.xtol = 0.02;
	sp.nfree = sp.nkey = 1, sp.ntest = 2, sp.runs = 20, sp.global = GLOBAL_AUTO;
	sp.key[0] = (cal_key){.name = "nu", .free = 1, .lo = 0.1, .hi = 0.4, .start = 0.2};
	space s;
	space_init(&s, &sp);
	CHECK(s.nz == 1 && search_global_points(&s) == 16);
	char buf[1024];
	/* The start, 16 points and a local one, 2 runs each: 36 runs. */
	CHECK(search_budget_short(&s, buf, sizeof buf) == 1);
	CHECK(strstr(buf, "cal.json: the budget of 20 runs cannot finish the global stage"));
	CHECK(strstr(buf, "16 points (search.global_points, by default 8 x (n + 1) = 16 for n = "
	                  "1 search variable)"));
	CHECK(strstr(buf, "the local stage would never start"));
	CHECK(strstr(buf, "at least 36"));
	sp.runs = 36;
	CHECK(search_budget_short(&s, buf, sizeof buf) == 0);
	sp.runs = 20, sp.global_points = 8;
	CHECK(search_budget_short(&s, buf, sizeof buf) == 0);
	sp.global_points = 0, sp.global = GLOBAL_NEVER;
	CHECK(search_budget_short(&s, buf, sizeof buf) == 0);
}

static void test_runlog(const cal_spec *sp, const char *dir)
{
	char path[4096];
	snprintf(path, sizeof path, "%s/calibrate-log.csv", dir);
	remove(path);
	runlog l;
	CHECK(runlog_open(&l, path, sp) == 0 && l.n == 0);
	runrec r;
	memset(&r, 0, sizeof r);
	for (int q = 0; q < QTY_MAX; q++)
		r.q[q] = NAN;
	snprintf(r.key, sizeof r.key, "0123456789abcdef");
	r.seq = 7;
	snprintf(r.phase, sizeof r.phase, "search");
	snprintf(r.test, sizeof r.test, "ucs");
	snprintf(r.specimen, sizeof r.specimen, "search");
	r.v[0] = 0.1 + 0.2; /* not a short decimal: written to the last bit */
	r.q[0] = 1.0 / 3;
	r.status = "failed: solve: case.json: key \"x\", a \"quoted\" value";
	CHECK(runlog_add(&l, &r) == 0);
	snprintf(r.key, sizeof r.key, "fedcba9876543210");
	r.seq = 3;
	r.status = "ok";
	CHECK(runlog_add(&l, &r) == 0);
	runlog_free(&l);
	CHECK(runlog_open(&l, path, sp) == 0 && l.n == 2);
	const runrec *a = runlog_find(&l, "0123456789abcdef");
	CHECK(a && a->v[0] == 0.1 + 0.2 && a->q[0] == 1.0 / 3 && isnan(a->q[1]));
	CHECK(a &&
	      strcmp(a->status, "failed: solve: case.json: key \"x\", a \"quoted\" value") == 0);
	CHECK(l.r[0].seq == 3); /* rows in the order they were asked for */
	CHECK(!runlog_find(&l, "0000000000000000"));
	runlog_free(&l);
	/* Another calibration's log is refused. */
	cal_spec other = *sp;
	other.nkey = 1;
	CHECK(runlog_open(&l, path, &other) == -1 && strstr(err_msg(), "another calibration"));
	runlog_free(&l);
	remove(path);
}

/* Two keys, two targets within 2 %: each target seen by one key gives it
 * the tolerance as its uncertainty, widened by the target's noise; seen by
 * both (sum and difference), tol / sqrt(2) each. */
static void test_uncertainty(void)
{
	static cal_spec sp;
	sp.nfree = 2, sp.ntarget = 2;
	for (int i = 0; i < 2; i++)
		sp.target[i].tol = 0.02, sp.target[i].weight = 1;
	sensitivity s = {.J = {{1, 0}, {0, 2}}, .noise = {NAN, 0.1}};
	sensitivity_analyse(&sp, &s);
	CHECK_NEAR(s.sigma[0], 0.02, 1e-12);
	CHECK_NEAR(s.sigma[1], hypot(0.02, 0.1) / 2, 1e-12);
	CHECK_NEAR(s.key_cos[0][1], 0, 1e-12);
	s = (sensitivity){.J = {{1, 1}, {1, -1}}, .noise = {0, 0}};
	sensitivity_analyse(&sp, &s);
	CHECK_NEAR(s.sigma[0], 0.02 / sqrt(2), 1e-12);
	CHECK_NEAR(s.sigma[1], 0.02 / sqrt(2), 1e-12);
	/* A key no target sees is not identified. */
	s = (sensitivity){.J = {{1, 0}, {2, 0}}, .noise = {0, 0}};
	sensitivity_analyse(&sp, &s);
	CHECK(isinf(s.sigma[1]));
}

/* The diagnosis of an unmet target: out of reach when meeting it would
 * take changing the keys by more than their whole values (its
 * sensitivities extrapolated), not when a small step would do. */
static void test_out_of_reach(void)
{
	static cal_spec sp;
	static cal_test test = {.name = "ucs"};
	sp.nfree = sp.nkey = 2, sp.ntarget = 2, sp.runs = 8;
	sp.test[0] = test;
	for (int k = 0; k < 2; k++)
		sp.key[k] = (cal_key){.name = k ? "nu" : "E0", .free = 1, .lo = 0.01, .hi = 100};
	for (int i = 0; i < 2; i++)
		sp.target[i] = (cal_target){.test = 0, .quantity = i, .tol = 0.05, .weight = 1};
	/* Target 0 off by 80 % and moved by 0.03 per relative change: out of
	 * reach (some 2 500 %); target 1 off by 20 % and moved by 1: not. */
	sensitivity s = {.ran = 1, .J = {{0.03, 0}, {0, 1}}, .noise = {0, 0}};
	sensitivity_analyse(&sp, &s);
	path_point pt = {.v = {1, 1}, .ok = 1, .fit = {.err = {-0.8, 0.2}}};
	search_result r = {.path = &pt, .npath = 1, .best = 0, .status = SEARCH_BUDGET};
	report rp = {.sp = &sp, .r = &r, .sens = &s};
	report_diagnose(&rp);
	int reach = 0;
	for (int k = 0; k < rp.nnotes; k++)
		if (strstr(rp.notes[k], "out of reach of these keys")) {
			reach++;
			CHECK(strstr(rp.notes[k], quantities[0].name) != NULL);
			CHECK(strstr(rp.notes[k], "some 2500 %") != NULL);
		}
	CHECK(reach == 1);
	report_free(&rp);
}

int main(void)
{
	const char *tmp = getenv("TEST_TMPDIR");
	test_project();
	test_uncertainty();
	test_out_of_reach();
	test_bounds();
	test_budget();
	cal_spec sp;
	int rc = spec_load("tests/calibrate/data/recovery.json", &sp);
	CHECK(rc == 0);
	if (rc) {
		fprintf(stderr, "%s\n", err_msg());
		return check_done();
	}
	CHECK(sp.nfree == 2 && sp.nkey == 6 && sp.ntest == 2 && sp.ntarget == 3);
	CHECK(sp.target[0].from_truth && sp.scaling);
	test_space(&sp);
	test_runlog(&sp, tmp ? tmp : ".");
	spec_free(&sp);
	return check_done();
}
