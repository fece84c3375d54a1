/* Bad case files give one clear message naming the file, the key, the value
 * and what was expected; good ones parse into the expected settings. */
#include <stdio.h>
#include <string.h>

#include "lib/err.h"
#include "tests/check.h"
#include "tests/solve/harness.h"

#define MAT                                                                                    \
	"\"material\": {\"name\": \"m\", \"law\": \"linear\", \"density\": 2000, \"E\": 1e9, " \
	"\"nu\": 0.2, \"tensile_strength\": 1e6, \"shear_strength\": 2e6}"
#define ONE_STAGE "\"loading\": [{\"axial\": {\"mode\": \"strain_rate\", \"rate\": 0.1}}]"

/* The message of loading case text written to bad.json. */
static const char *error_of(const char *text)
{
	const char *path = harness_file("bad.json", text);
	dem_case c;
	if (case_load(path, NULL, &c) == 0) {
		case_free(&c);
		return "(loaded without error)";
	}
	static char msg[1024];
	const char *m = err_msg();
	/* Drop the scratch directory from the file name. */
	const char *slash = strrchr(path, '/');
	size_t dir = slash ? (size_t)(slash - path) + 1 : 0;
	snprintf(msg, sizeof msg, "%s", strncmp(m, path, dir) == 0 ? m + dir : m);
	return msg;
}

static void expect(const char *text, const char *message)
{
	const char *got = error_of(text);
	CHECK_STR(got, message);
}

int main(void)
{
	expect("{\"assembly\": \"a.h5\", " ONE_STAGE ", \"stop\": {\"steps\": 10}}",
	       "bad.json: key 'material': missing: expected a material file name or an object");
	/* A material file that cannot be read: the key, then the file as resolved
	 * beside the case. */
	const char *got =
	    error_of("{\"assembly\": \"a.h5\", \"material\": \"no-such.json\", " ONE_STAGE
	             ", \"stop\": {\"steps\": 10}}");
	CHECK(strncmp(got, "bad.json: key 'material': ", 26) == 0);
	char want[1200];
	snprintf(want, sizeof want, "%s: cannot open: No such file or directory",
	         check_tmp("no-such.json"));
	CHECK(strstr(got, want) != NULL);
	expect("{\"assembly\": \"\", " MAT ", " ONE_STAGE ", \"stop\": {\"steps\": 10}}",
	       "bad.json: key 'assembly': empty: expected the assembly file's name");
	expect("{\"assembly\": \"a.h5\", \"material\": [], " ONE_STAGE
	       ", \"stop\": {\"steps\": 10}}",
	       "bad.json: key 'material': expected a material file name or an object");
	expect("{\"assembly\": \"a.h5\", \"material\": {\"name\": \"m\", \"law\": \"linear\", "
	       "\"density\": -5}, " ONE_STAGE "}",
	       "bad.json: key 'material.density': value -5: expected a positive number (kg/m^3)");
	/* The list of laws grows with the library: its start is checked. */
	static const char unknown_law[] = "bad.json: key 'material.law': unknown law "
	                                  "\"elastoplastic\": expected one of 'linear', ";
	const char *law = error_of("{\"assembly\": \"a.h5\", \"material\": {\"name\": \"m\", "
	                           "\"law\": \"elastoplastic\", \"density\": 5}, " ONE_STAGE "}");
	CHECK(strncmp(law, unknown_law, strlen(unknown_law)) == 0);
	expect("{\"assembly\": \"a.h5\", \"material\": {\"name\": \"m\", \"law\": \"linear\", "
	       "\"density\": 2000, \"E\": 1e9, \"nu\": 0.7, \"tensile_strength\": 1e6, "
	       "\"shear_strength\": 2e6}, " ONE_STAGE "}",
	       "bad.json: key 'material.nu': value 0.7: expected a number in [-0.99, 0.5]");
	expect("{\"assembly\": \"a.h5\", " MAT ", " ONE_STAGE ", \"stop\": {\"steps\": 10}, "
	       "\"colour\": \"red\"}",
	       "bad.json: key 'colour': unknown key (misspelt, or not used by this program)");
	expect("{\"assembly\": \"a.h5\", \"material\": {\"name\": \"m\", \"law\": \"linear\", "
	       "\"density\": 2000, \"E\": 1e9, \"nu\": 0.2, \"tensile_strength\": 1e6, "
	       "\"shear_strength\": 2e6, \"Young\": 3}, " ONE_STAGE ", \"stop\": {\"steps\": 10}}",
	       "bad.json: key 'material.Young': unknown key (misspelt, or not used by this "
	       "program)");
	expect("{\"assembly\": \"a.h5\", " MAT
	       ", \"loading\": [{\"axial\": {\"mode\": \"push\"}}], "
	       "\"stop\": {\"steps\": 10}}",
	       "bad.json: key 'loading[0].axial.mode': value \"push\": expected one of 'none', "
	       "'hold', 'velocity', 'strain_rate', 'stress', 'force', 'layers'");
	expect("{\"assembly\": \"a.h5\", " MAT ", \"loading\": [{\"axial\": {\"mode\": "
	       "\"strain_rate\"}}], \"stop\": {\"steps\": 10}}",
	       "bad.json: key 'loading[0].axial.rate': missing: expected a number (1/s)");
	expect("{\"assembly\": \"a.h5\", " MAT ", \"loading\": [{\"axial\": {\"mode\": "
	       "\"strain_rate\", \"rate\": 0.1, \"stress\": 5e6}}], \"stop\": {\"steps\": 10}}",
	       "bad.json: key 'loading[0].axial.stress': unknown key (misspelt, or not used by "
	       "this program)");
	expect("{\"assembly\": \"a.h5\", " MAT ", \"loading\": [{\"lateral\": {\"mode\": "
	       "\"pressure\", \"pressure\": -1}}], \"stop\": {\"steps\": 10}}",
	       "bad.json: key 'loading[0].lateral.pressure': value -1: expected a non-negative "
	       "number (Pa)");
	expect("{\"assembly\": \"a.h5\", " MAT ", \"loading\": [{\"axial\": {\"mode\": \"hold\"}}, "
	       "{\"axial\": {\"mode\": \"hold\"}}], \"stop\": {\"steps\": 10}}",
	       "bad.json: key 'loading': stage 1: no condition in 'until': every stage but the "
	       "last needs a condition that ends it");
	expect("{\"assembly\": \"a.h5\", " MAT ", \"loading\": [{\"axial\": {\"mode\": \"hold\"}, "
	       "\"until\": {}}, {\"axial\": {\"mode\": \"hold\"}}], \"stop\": {\"steps\": 10}}",
	       "bad.json: key 'loading': stage 1: no condition in 'until': every stage but the "
	       "last needs a condition that ends it");
	expect("{\"assembly\": \"a.h5\", " MAT ", " ONE_STAGE "}",
	       "bad.json: key 'stop': missing: the run never ends (give 'stop' or an 'until' in "
	       "the last stage)");
	/* An empty stop object is taken when the last stage's until ends the
	 * run. */
	expect("{\"assembly\": \"a.h5\", " MAT ", \"loading\": [{\"axial\": {\"mode\": "
	       "\"strain_rate\", \"rate\": 0.1}, \"until\": {\"strain_axial\": 0.002}}], "
	       "\"stop\": {}}",
	       "(loaded without error)");
	expect(
	    "{\"assembly\": \"a.h5\", " MAT ", " ONE_STAGE ", \"stop\": {\"stress_axial\": 1e6}}",
	    "bad.json: key 'stop': no rule: expected strain_axial, stress_drop, time or steps (a "
	    "stress to reach is a stage's 'until' rule)");
	expect("{\"assembly\": \"a.h5\", " MAT ", " ONE_STAGE
	       ", \"surface\": {\"update_every\": 2.5}, \"stop\": {\"steps\": 10}}",
	       "bad.json: key 'surface.update_every': value 2.5: expected a whole number of steps");
	/* Strengths given in MPa. */
	expect("{\"assembly\": \"a.h5\", \"material\": {\"name\": \"m\", \"law\": \"onate\", "
	       "\"density\": 1700, \"E0\": 3.8e9, \"nu\": 0.2, \"tensile_strength\": 4.8e6, "
	       "\"shear_strength\": 8.5, \"mu1\": 0.3, \"mu2\": 0.4, \"LCS1\": 8.5e6, \"LCS2\": "
	       "9e6, \"LCS3\": 11e6, \"YRC1\": 3, \"YRC2\": 9, \"YRC3\": 24, \"delta_n\": 0.2, "
	       "\"delta_s\": 0.2}, " ONE_STAGE ", \"stop\": {\"steps\": 10}}",
	       "bad.json: key 'material.shear_strength': value 8.5 Pa: expected at least a "
	       "millionth of E0 (3.8e+09 Pa): strengths are in Pa (8.5 MPa is 8.5e+06 Pa), 0 for "
	       "none");
	expect("{\"assembly\": \"a.h5\", " MAT ", \"loading\": []}",
	       "bad.json: key 'loading': missing: expected a non-empty array of stage objects");
	expect("{\"assembly\": \"a.h5\", " MAT ", " ONE_STAGE ", \"stop\": {\"stress_drop\": 1.5}}",
	       "bad.json: key 'stop.stress_drop': value 1.5: expected a number in [0, 1]");
	expect("{\"assembly\": \"a.h5\", " MAT ", " ONE_STAGE
	       ", \"stop\": {\"steps\": 10}, \"time_step\": {\"safety\": 1.5}}",
	       "bad.json: key 'time_step.safety': value 1.5: expected a number in (0, 1]");
	expect("{\"assembly\": \"a.h5\", " MAT ", " ONE_STAGE
	       ", \"stop\": {\"steps\": 10}, \"damping\": {\"form\": \"yade\"}}",
	       "bad.json: key 'damping.form': value \"yade\": expected one of 'vector', "
	       "'components'");
	expect("{\"assembly\": \"a.h5\", " MAT ", " ONE_STAGE
	       ", \"stop\": {\"steps\": 10}, \"axis\": [0, 0, 0]}",
	       "bad.json: key 'axis': value [0, 0, 0]: expected a non-zero direction");
	expect("{\"assembly\": 3, " MAT ", " ONE_STAGE ", \"stop\": {\"steps\": 10}}",
	       "bad.json: key 'assembly': value 3: expected a string");
	expect("{\"assembly\": \"a.h5\", " MAT ", " ONE_STAGE ", \"stop\": {\"steps\": 10}",
	       "bad.json: line 1: not valid JSON");

	/* A good case: every setting lands where it should. */
	const char *path = harness_file(
	    "good.json",
	    "{\"assembly\": \"sub/a.h5\", " MAT ", \"test\": \"triaxial\", \"threads\": 3,"
	    "\"axis\": [1, 0, 0],"
	    "\"time_step\": {\"safety\": 0.5}, \"damping\": {\"translational\": 0.2, \"form\": "
	    "\"components\"},"
	    "\"output\": {\"history_every\": 7, \"snapshot_strains\": [0.001, 0.002]},"
	    "\"loading\": [{\"name\": \"confine\", \"ramp\": 0.01, \"axial\": {\"mode\": "
	    "\"stress\", \"stress\": 1e6}, \"lateral\": {\"mode\": \"pressure\", \"pressure\": "
	    "1e6, "
	    "\"method\": \"tributary\"}, \"until\": {\"time\": 0.02}},"
	    "{\"axial\": {\"mode\": \"strain_rate\", \"rate\": -0.5, \"move\": \"top\"}, "
	    "\"lateral\": {\"mode\": \"pressure\", \"pressure\": 1e6}, \"until\": "
	    "{\"stress_axial\": "
	    "2e6}}], \"stop\": {\"strain_axial\": 0.01, \"stress_drop\": 0.5}}");
	dem_case c;
	CHECK(case_load(path, NULL, &c) == 0);
	CHECK_CONTAINS(c.assembly, "/sub/a.h5");
	CHECK_STR(c.test, "triaxial");
	CHECK(c.threads == 3 && c.safety == 0.5 && c.alpha_t == 0.2 && c.alpha_r == 0.1 &&
	      c.damping_form == DAMPING_COMPONENTS);
	CHECK(c.axis[0] == 1 && c.axis[1] == 0 && c.axis[2] == 0);
	CHECK(c.history_every == 7 && c.nsnapshot_strains == 2 && c.snapshot_strains[1] == 0.002);
	CHECK(c.nstages == 2);
	CHECK_STR(c.stages[0].name, "confine");
	CHECK(c.stages[0].axial == AXIAL_STRESS && c.stages[0].target == 1e6 &&
	      c.stages[0].rate == 1.0 && c.stages[0].ramp == 0.01);
	CHECK(c.stages[0].lateral == LATERAL_PRESSURE && c.stages[0].method == PRESSURE_TRIBUTARY);
	CHECK(c.stages[0].until.time == 0.02);
	CHECK(c.stages[1].axial == AXIAL_STRAIN_RATE && c.stages[1].rate == -0.5 &&
	      c.stages[1].top_only);
	CHECK(c.stages[1].method == PRESSURE_PAPER && c.stages[1].until.stress_axial == 2e6);
	CHECK(c.stop.strain_axial == 0.01 && c.stop.stress_drop == 0.5);
	/* The provenance configuration has the material inline. */
	CHECK_CONTAINS(c.config, "\"law\":\t\"linear\"");
	/* Checkpoints by wall time: the first after a tenth of the period (at
	 * most a minute), then doubling up to it. */
	c.checkpoint_wall = 600;
	CHECK(case_checkpoint_interval(&c, 0) == 60 && case_checkpoint_interval(&c, 1) == 120 &&
	      case_checkpoint_interval(&c, 3) == 480 && case_checkpoint_interval(&c, 4) == 600 &&
	      case_checkpoint_interval(&c, 40) == 600);
	c.checkpoint_wall = 5;
	CHECK(case_checkpoint_interval(&c, 0) == 0.5 && case_checkpoint_interval(&c, 3) == 4 &&
	      case_checkpoint_interval(&c, 4) == 5);
	c.checkpoint_wall = 7200;
	CHECK(case_checkpoint_interval(&c, 0) == 60 && case_checkpoint_interval(&c, 7) == 7200);
	c.checkpoint_wall = 0;
	CHECK(case_checkpoint_interval(&c, 0) == 0);
	case_free(&c);
	return check_done();
}
