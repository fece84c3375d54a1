/* The cement triaxial cases on a small specimen (1 500 spheres of the
 * 1" x 2" core): unconfined, 1000 psi and 4000 psi, each with its
 * material of Oñate et al. 2015 (Tables 3-4) and the shipped cases'
 * loading program (hydrostatic stage, then the top end layer driven at
 * a constant strain rate at constant p_c, confinement by the paper's
 * method) at a faster rate so the test stays short. What the paper's
 * Fig. 16 shows must hold: the peak axial stress rises with the
 * confinement, and the response after the peak turns from brittle (the
 * unconfined specimen loses half its strength) to ductile (confined,
 * the deviator keeps at least 90 % of its peak to the end). Figures come
 * from post summary. */
#define _XOPEN_SOURCE 700
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "lib/cfg.h"
#include "tests/check.h"

#define PSI 6894.757293168

static const char *bin(void)
{
	const char *b = getenv("DEM_BIN");
	return b && b[0] ? b : "build/bin";
}

static int run(const char *fmt, const char *a, const char *b, const char *c)
{
	char cmd[8192];
	snprintf(cmd, sizeof cmd, fmt, bin(), a, b, c);
	int rc = system(cmd);
	if (rc != 0)
		fprintf(stderr, "failed (%d): %s\n", rc, cmd);
	return rc;
}

typedef struct {
	double peak_stress, peak_deviator, residual_deviator;
} figures;

/* Write the case for confinement psi with material file mat, run it on
 * the assembly and read its summary. */
static figures triaxial(const char *assembly, int psi, const char *mat)
{
	char name[64], path[PATH_MAX], matpath[PATH_MAX], json[16384], run_h5[PATH_MAX + 8];
	snprintf(name, sizeof name, "triaxial-%dpsi.json", psi);
	snprintf(path, sizeof path, "%s", check_tmp(name));
	CHECK(realpath(mat, matpath) != NULL);
	double pc = psi * PSI;
	char lateral[256], hydro[1024] = "";
	if (psi > 0) {
		snprintf(lateral, sizeof lateral,
		         "{\"mode\": \"pressure\", \"pressure\": %.17g, \"method\": \"paper\"}",
		         pc);
		snprintf(
		    hydro, sizeof hydro,
		    "{\"name\": \"hydrostatic\", \"ramp\": 3e-4, \"axial\": {\"mode\": "
		    "\"stress\", \"stress\": %.17g, \"rate\": 100}, \"lateral\": %s, \"until\": "
		    "{\"time\": 8e-4}},",
		    pc, lateral);
	} else {
		snprintf(lateral, sizeof lateral, "{\"mode\": \"free\"}");
	}
	/* 1.2 % of axial strain after the hydrostatic stage at 10/s */
	snprintf(json, sizeof json,
	         "{\"test\": \"triaxial\", \"assembly\": \"%s\", \"material\": \"%s\",\n"
	         " \"output\": {\"history_every\": 50},\n"
	         " \"loading\": [%s {\"name\": \"axial\", \"axial\": {\"mode\": \"layers\", "
	         "\"move\": \"top\", \"rate\": 10}, \"lateral\": %s}],\n"
	         " \"stop\": {\"time\": %g, \"stress_drop\": 0.5}}\n",
	         assembly, matpath, hydro, lateral, psi > 0 ? 8e-4 + 1.2e-3 : 1.2e-3);
	FILE *f = fopen(path, "w");
	CHECK(f != NULL);
	fputs(json, f);
	fclose(f);
	snprintf(run_h5, sizeof run_h5, "%s.h5", path);
	char out[PATH_MAX + 8];
	snprintf(out, sizeof out, "%s.out", path);
	figures fg = {NAN, NAN, NAN};
	if (run("%s/solve --quiet --output %s %s%s", run_h5, path, "") ||
	    run("%s/post summary --out %s %s >/dev/null%s", out, run_h5, ""))
		return fg;
	char sj[PATH_MAX + 32];
	snprintf(sj, sizeof sj, "%s/summary.json", out);
	cfg *c = cfg_load(sj);
	CHECK(c != NULL);
	if (!c)
		return fg;
	CHECK(cfg_number(c, "peak_stress", &fg.peak_stress, "Pa", 0, INFINITY) == 0);
	CHECK(cfg_number(c, "peak_deviator", &fg.peak_deviator, "Pa", 0, INFINITY) == 0);
	CHECK(cfg_number(c, "residual_deviator", &fg.residual_deviator, "Pa", -INFINITY,
	                 INFINITY) == 0);
	cfg_free(c);
	fprintf(stderr, "%5d psi: peak axial %.3g MPa, peak deviator %.3g MPa, last %.3g MPa\n",
	        psi, 1e-6 * fg.peak_stress, 1e-6 * fg.peak_deviator, 1e-6 * fg.residual_deviator);
	return fg;
}

int main(void)
{
	char assembly[PATH_MAX];
	snprintf(assembly, sizeof assembly, "%s", check_tmp("triaxial-assembly.h5"));
	CHECK(run("%s/pack --quiet --config %s --count 1500 --seed 1 %s%s",
	          "share/specimens/cement-1x2in.json", assembly, "") == 0);
	figures u = triaxial(assembly, 0, "share/materials/cement.json");
	figures m = triaxial(assembly, 1000, "share/materials/cement-1000psi.json");
	figures h = triaxial(assembly, 4000, "share/materials/cement-4000psi.json");
	CHECK(u.peak_stress < m.peak_stress && m.peak_stress < h.peak_stress);
	double ru = u.residual_deviator / u.peak_deviator,
	       rm = m.residual_deviator / m.peak_deviator,
	       rh = h.residual_deviator / h.peak_deviator;
	fprintf(stderr, "last / peak deviator: %.3f, %.3f, %.3f\n", ru, rm, rh);
	CHECK(ru < 0.6); /* the last history row before the stress fell below half the peak */
	CHECK(rm >= 0.9);
	CHECK(rh >= 0.9);
	return check_done();
}
