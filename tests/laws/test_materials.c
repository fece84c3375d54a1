/* The shipped material files: every one parses with its law and leaves no
 * key unused; their numbers are the papers' tables; bad materials give one
 * exact message naming the file and the key. */
#include <cjson/cJSON.h>
#include <dirent.h>
#include <stdlib.h>

#include "tests/laws/drive.h"

#define DIR_MATERIALS "share/materials"

static cfg *load(const char *file)
{
	char path[512];
	snprintf(path, sizeof path, "%s/%s", DIR_MATERIALS, file);
	cfg *c = cfg_load(path);
	if (!c)
		fprintf(stderr, "%s\n", err_msg());
	return c;
}

/* What the engine does with a material file: its keys, the law's, and no
 * key left unused. */
static int check_file(const char *file)
{
	cfg *c = load(file);
	if (!c)
		return -1;
	material m;
	int ok = material_parse(c, &m) == 0 && cfg_check_unused(c) == 0 && m.name[0] &&
	         m.density > 1000 && m.density < 3000;
	if (!ok)
		fprintf(stderr, "%s: %s\n", file, err_msg());
	material_free(&m);
	cfg_free(c);
	return ok ? 0 : -1;
}

static void test_every_file_parses(void)
{
	DIR *d = opendir(DIR_MATERIALS);
	CHECK(d != NULL);
	if (!d)
		return;
	int n = 0;
	struct dirent *e;
	while ((e = readdir(d))) {
		size_t len = strlen(e->d_name);
		if (len < 6 || strcmp(e->d_name + len - 5, ".json") != 0)
			continue;
		CHECK(check_file(e->d_name) == 0);
		n++;
	}
	closedir(d);
	CHECK(n == 9);
}

static double number(cfg *c, const char *key)
{
	double v = NAN;
	cfg_number(c, key, &v, "", -INFINITY, INFINITY);
	return v;
}

/* Each file against its table (densities from g/cc, stresses from MPa). */
static void test_tables(void)
{
	static const struct {
		const char *file;
		double rho, e, lcs[3], yrc[3], mu1, mu2, sigt, tau;
	} onate[] = {
	    {"cement.json", 1700, 3.8e9, {8.5e6, 9e6, 11e6}, {3, 9, 24}, 0.3, 0.4, 4.8e6, 8.5e6},
	    {"cement-500psi.json",
	     1700,
	     3.8e9,
	     {9.5e6, 11e6, 13e6},
	     {3, 9, 24},
	     0.3,
	     0.4,
	     4.8e6,
	     8.5e6},
	    {"cement-1000psi.json",
	     1700,
	     3.8e9,
	     {10e6, 11e6, 14e6},
	     {3, 9, 24},
	     0.3,
	     0.4,
	     4.8e6,
	     8.5e6},
	    {"cement-2000psi.json",
	     1700,
	     3.8e9,
	     {13e6, 14e6, 15e6},
	     {3, 9, 24},
	     0.3,
	     0.4,
	     4.8e6,
	     8.5e6},
	    {"cement-4000psi.json",
	     1700,
	     3.8e9,
	     {21e6, 23e6, 26e6},
	     {3, 9, 24},
	     0.3,
	     0.4,
	     4.8e6,
	     8.5e6},
	    {"concrete.json", 2500, 28e9, {20e6, 45e6, 70e6}, {3, 12, 22}, 0.9, 0.25, 5e6, 16e6},
	    {"shale.json", 2550, 30e9, {20e6, 30e6, 40e6}, {1, 1, 1}, 0.7, 0.6, 5e6, 25e6},
	};
	for (size_t k = 0; k < sizeof onate / sizeof onate[0]; k++) {
		cfg *c = load(onate[k].file);
		CHECK(c != NULL);
		if (!c)
			continue;
		CHECK(number(c, "density") == onate[k].rho);
		CHECK(number(c, "E0") == onate[k].e);
		CHECK(number(c, "nu") == 0.2);
		CHECK(number(c, "mu1") == onate[k].mu1 && number(c, "mu2") == onate[k].mu2);
		CHECK(number(c, "tensile_strength") == onate[k].sigt);
		CHECK(number(c, "shear_strength") == onate[k].tau);
		char key[16];
		for (int i = 0; i < 3; i++) {
			snprintf(key, sizeof key, "LCS%d", i + 1);
			CHECK(number(c, key) == onate[k].lcs[i]);
			snprintf(key, sizeof key, "YRC%d", i + 1);
			CHECK(number(c, key) == onate[k].yrc[i]);
		}
		CHECK(number(c, "delta_n") == 0.2 && number(c, "delta_s") == 0.2);
		CHECK(number(c, "alpha") == 1.0);
		cfg_free(c);
	}
	cfg *c = load("concrete-jcfpm.json");
	CHECK(c && number(c, "density") == 2400 && number(c, "E") == 17e9);
	CHECK(c && number(c, "ks_ratio") == 0.15 && number(c, "tensile_strength") == 3.163e6);
	CHECK(c && number(c, "cohesion") == 9e6 && number(c, "friction_angle_deg") == 34.25);
	CHECK(c && number(c, "interaction_range") == 1.4);
	cfg_free(c);
	c = load("concrete-exponential.json");
	CHECK(c && number(c, "tensile_strength") == 10e6 && number(c, "cohesion") == 13e6);
	CHECK(c && number(c, "friction_angle_deg") == 30);
	CHECK(c && number(c, "contact_friction_angle_deg") == 30);
	CHECK(c && number(c, "gamma1") == 0.2 && number(c, "gamma2") == 16);
	CHECK(c && number(c, "gamma3") == 0.275 && number(c, "eps_max") == 0.002);
	cfg_free(c);
}

/* The Table 4 files are the Table 3 file with only the name and the LCS set
 * changed. */
static cJSON *without_lcs(const char *file)
{
	cfg *c = load(file);
	if (!c)
		return NULL;
	char *text = cfg_text(c);
	cJSON *j = cJSON_Parse(text);
	free(text);
	cfg_free(c);
	for (const char *const *k = (const char *const[]){"name", "LCS1", "LCS2", "LCS3", NULL}; *k;
	     k++)
		cJSON_DeleteItemFromObjectCaseSensitive(j, *k);
	return j;
}

static void test_triaxial_cement(void)
{
	static const char *files[] = {"cement-500psi.json", "cement-1000psi.json",
	                              "cement-2000psi.json", "cement-4000psi.json"};
	cJSON *base = without_lcs("cement.json");
	CHECK(base != NULL);
	for (int k = 0; k < 4; k++) {
		cJSON *j = without_lcs(files[k]);
		CHECK(j && base && cJSON_Compare(base, j, 1));
		cJSON_Delete(j);
	}
	cJSON_Delete(base);
}

/* One message naming file, key, value and what was expected. */
static void test_errors(void)
{
	const law *on = law_find("onate"), *jc = law_find("jcfpm"), *ex = law_find("exponential");
	const char *head = "{\"name\": \"bad\", \"law\": \"onate\", \"density\": 2500,"
	                   " \"nu\": 0.2, \"tensile_strength\": 5e6, \"shear_strength\": 16e6,"
	                   " \"mu1\": 0.9, \"mu2\": 0.25, \"delta_n\": 0.2, \"delta_s\": 0.2,"
	                   " \"YRC1\": 3, \"YRC2\": 12, \"YRC3\": 22";
	char json[1024];
#define ONATE(extra) (snprintf(json, sizeof json, "%s, %s}", head, extra), json)
	CHECK_STR(drive_error(on,
	                      ONATE("\"E0\": 28e9, \"LCS1\": 20e6, \"LCS2\": 45e6, \"LCS3\": "
	                            "70e6, \"E00\": 1"),
	                      "bad.json"),
	          "bad.json: key 'E00': unknown key (misspelt, or not used by this program)");
	CHECK_STR(
	    drive_error(on, ONATE("\"LCS1\": 20e6, \"LCS2\": 45e6, \"LCS3\": 70e6"), "bad.json"),
	    "bad.json: key 'E0': missing: expected a positive number (Pa)");
	CHECK_STR(
	    drive_error(on, ONATE("\"E0\": -28e9, \"LCS1\": 20e6, \"LCS2\": 45e6, \"LCS3\": 70e6"),
	                "bad.json"),
	    "bad.json: key 'E0': value -28000000000: expected a positive number (Pa)");
	CHECK_STR(drive_error(on,
	                      ONATE("\"E0\": 28e9, \"LCS1\": 20e6, \"LCS2\": 15e6, \"LCS3\": 70e6"),
	                      "bad.json"),
	          "bad.json: key 'LCS2': value 15000000: expected a number greater than LCS1 = "
	          "20000000 (Pa)");
	CHECK_STR(drive_error(on,
	                      ONATE("\"E0\": 28e9, \"LCS1\": 20e6, \"LCS2\": 45e6, \"LCS3\": 45e6"),
	                      "bad.json"),
	          "bad.json: key 'LCS3': value 45000000: expected a number greater than LCS2 = "
	          "45000000 (Pa)");
	CHECK_STR(drive_error(on,
	                      "{\"name\": \"bad\", \"law\": \"onate\", \"density\": 2500,"
	                      " \"E0\": 28e9, \"nu\": 0.2, \"tensile_strength\": 5e6,"
	                      " \"shear_strength\": 16e6, \"mu1\": 0.9, \"mu2\": 0.25,"
	                      " \"delta_n\": 0.2, \"delta_s\": 0.2, \"LCS1\": 20e6, \"LCS2\": 45e6,"
	                      " \"LCS3\": 70e6, \"YRC1\": 3, \"YRC2\": 0.5, \"YRC3\": 22}",
	                      "bad.json"),
	          "bad.json: key 'YRC2': value 0.5: expected a number >= 1");
	CHECK_STR(
	    drive_error(on,
	                ONATE("\"E0\": 28e9, \"LCS1\": 20e6, \"LCS2\": 45e6, \"LCS3\": 70e6,"
	                      " \"criterion\": \"both\""),
	                "bad.json"),
	    "bad.json: key 'criterion': value \"both\": expected one of 'uncoupled', 'coupled'");
	CHECK_STR(drive_error(on,
	                      ONATE("\"E0\": 28e9, \"LCS1\": 20e6, \"LCS2\": 45e6, \"LCS3\": 70e6,"
	                            " \"alpha\": 0"),
	                      "bad.json"),
	          "bad.json: key 'alpha': value 0: expected a positive number");
	CHECK_STR(drive_error(jc,
	                      "{\"name\": \"j\", \"law\": \"jcfpm\", \"density\": 2400,"
	                      " \"E\": 17e9, \"ks_ratio\": 0.15, \"tensile_strength\": 3.163e6,"
	                      " \"cohesion\": 9e6, \"friction_angle_deg\": 34.25}",
	                      "j.json"),
	          "j.json: key 'interaction_range': missing: expected a number in [1, 2]");
	CHECK_STR(
	    drive_error(jc,
	                "{\"name\": \"j\", \"law\": \"jcfpm\", \"density\": 2400,"
	                " \"E\": 17e9, \"ks_ratio\": 0.15, \"tensile_strength\": -3.163e6,"
	                " \"cohesion\": 9e6, \"friction_angle_deg\": 34.25,"
	                " \"interaction_range\": 1.4}",
	                "j.json"),
	    "j.json: key 'tensile_strength': value -3163000: expected a non-negative number (Pa)");
	CHECK_STR(drive_error(ex,
	                      "{\"name\": \"e\", \"law\": \"exponential\", \"density\": 2500,"
	                      " \"E0\": 28e9, \"nu\": 0.2, \"tensile_strength\": 10e6,"
	                      " \"delta_n\": 0.2, \"cohesion\": 13e6, \"friction_angle_deg\": 30,"
	                      " \"contact_friction_angle_deg\": 30, \"interaction_range\": 1.1,"
	                      " \"gamma2\": -16}",
	                      "e.json"),
	          "e.json: key 'gamma2': value -16: expected a non-negative number");
#undef ONATE
}

int main(void)
{
	test_every_file_parses();
	test_tables();
	test_triaxial_cement();
	test_errors();
	return check_done();
}
