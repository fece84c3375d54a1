/* JSON configuration: typed lookups, ranges, messages naming file/key/value,
 * unknown-key detection. */
#include <limits.h>

#include "lib/cfg.h"
#include "lib/err.h"
#include "tests/check.h"

static void test_values(void)
{
	cfg *c = cfg_parse("{\"E0\": 3.8e9, \"n\": 12, \"law\": \"onate\", \"flag\": true,"
	                   " \"lcs\": [8.5, 9.0, 11], \"contact\": {\"mu\": 0.4},"
	                   " \"cycles\": [{\"at\": 0.001}, {\"at\": 0.002}]}",
	                   "m.json");
	CHECK(c != NULL);
	double e, mu, missing;
	long n;
	const char *law;
	int flag, choice;
	double *lcs;
	size_t nlcs;
	CHECK(cfg_number(c, "E0", &e, "Pa", CFG_POS, INFINITY) == 0);
	CHECK(e == 3.8e9);
	CHECK(cfg_integer(c, "n", &n, 0, 100) == 0 && n == 12);
	CHECK(cfg_string(c, "law", &law) == 0);
	CHECK_STR(law, "onate");
	CHECK(cfg_bool_or(c, "flag", &flag, 0) == 0 && flag == 1);
	CHECK(cfg_number_or(c, "absent", &missing, 7.5, "m", 0, INFINITY) == 0 && missing == 7.5);
	CHECK(cfg_numbers(c, "lcs", &lcs, &nlcs, 3, "Pa", 0, INFINITY) == 0);
	CHECK(nlcs == 3 && lcs[2] == 11);
	free(lcs);
	cfg *contact = cfg_object(c, "contact");
	CHECK(contact && cfg_number(contact, "mu", &mu, "", 0, INFINITY) == 0 && mu == 0.4);
	CHECK(cfg_list(c, "cycles") == 2);
	double at;
	CHECK(cfg_number(cfg_item(c, "cycles", 1), "at", &at, "", 0, 1) == 0 && at == 0.002);
	CHECK(cfg_number(cfg_item(c, "cycles", 0), "at", &at, "", 0, 1) == 0 && at == 0.001);
	static const char *const words[] = {"linear", "onate", NULL};
	CHECK(cfg_choice_or(c, "law", &choice, words, 0) == 0 && choice == 1);
	CHECK(cfg_check_unused(c) == 0);
	cfg_free(c);
}

static void test_errors(void)
{
	cfg *c = cfg_parse("{\"E0\": -3.8e9, \"contact\": {\"muu\": 0.4}, \"law\": \"onat\"}",
	                   "cement.json");
	double e;
	CHECK(cfg_number(c, "E0", &e, "Pa", CFG_POS, INFINITY) == -1);
	CHECK_STR(err_msg(), "cement.json: key 'E0': value -3800000000: expected a positive "
	                     "number (Pa)");
	CHECK(cfg_number(c, "nu", &e, "", 0, 0.5) == -1);
	CHECK_STR(err_msg(), "cement.json: key 'nu': missing: expected a number in [0, 0.5]");
	/* A missing key where one like it is given names it: one letter more or
	 * less, two swapped, another case, '_'; not one letter for another. */
	cfg *near = cfg_parse("{\"stpo\": 1, \"mu_1\": 2, \"Density\": 3, \"tensile_strenght\": 4,"
	                      " \"mu2\": 5, \"rat\": 6}",
	                      "c.json");
	const char *keys[][2] = {{"stop", "stpo"},
	                         {"mu1", "mu_1"},
	                         {"density", "Density"},
	                         {"tensile_strength", "tensile_strenght"},
	                         {"rate", "rat"}};
	for (size_t k = 0; k < sizeof keys / sizeof keys[0]; k++) {
		char want[200];
		snprintf(want, sizeof want, " (found '%s': misspelt?)", keys[k][1]);
		CHECK(cfg_number(near, keys[k][0], &e, "", 0, 1) == -1);
		CHECK_CONTAINS(err_msg(), want);
	}
	CHECK(cfg_number(near, "mu3", &e, "", 0, 1) == -1);
	CHECK(strstr(err_msg(), "found") == NULL);
	cfg_free(near);
	static const char *const words[] = {"linear", "onate", NULL};
	int choice;
	CHECK(cfg_choice_or(c, "law", &choice, words, 0) == -1);
	CHECK_STR(err_msg(),
	          "cement.json: key 'law': value \"onat\": expected one of 'linear', 'onate'");
	cfg *contact = cfg_object(c, "contact");
	double mu;
	CHECK(cfg_number_or(contact, "mu", &mu, 0.5, "", 0, INFINITY) == 0 && mu == 0.5);
	CHECK(cfg_check_unused(c) == -1);
	CHECK_CONTAINS(err_msg(), "cement.json: key 'contact.muu': unknown key");
	cfg_free(c);

	CHECK(cfg_parse("{\"a\": 1,\n \"b\": }", "bad.json") == NULL);
	CHECK_CONTAINS(err_msg(), "bad.json: line 2: not valid JSON");
	/* Text after the object (two objects, a stray word) is not ignored;
	 * white space is fine. */
	CHECK(cfg_parse("{\"a\": 1}\n{}", "two.json") == NULL);
	CHECK_CONTAINS(err_msg(), "two.json: line 2: not valid JSON");
	CHECK(cfg_parse("{\"a\": 1} xyz", "junk.json") == NULL);
	CHECK_CONTAINS(err_msg(), "junk.json: line 1: not valid JSON");
	c = cfg_parse("{\"a\": 1}\n\n", "ok.json");
	CHECK(c != NULL);
	cfg_free(c);
	/* A key given twice is named as such. */
	double E;
	c = cfg_parse("{\"E\": 1, \"E\": 2}", "twice.json");
	CHECK(c && cfg_number(c, "E", &E, "Pa", CFG_POS, INFINITY) == 0 && E == 1);
	CHECK(cfg_check_unused(c) == -1);
	CHECK_STR(err_msg(), "twice.json: key 'E': given twice");
	cfg_free(c);
	/* A number too large for a double is named as such, not as null. */
	c = cfg_parse("{\"E\": 1e400}", "big.json");
	CHECK(c && cfg_number(c, "E", &E, "Pa", CFG_POS, INFINITY) == -1);
	CHECK_STR(err_msg(), "big.json: key 'E': value +inf (beyond the range of a double): "
	                     "expected a positive number (Pa)");
	cfg_free(c);
	CHECK(cfg_parse("[1, 2]", "arr.json") == NULL);
	CHECK_CONTAINS(err_msg(), "expected a JSON object");
	CHECK(cfg_load("/nonexistent/x.json") == NULL);
	CHECK_CONTAINS(err_msg(), "/nonexistent/x.json: cannot open");

	c = cfg_parse("{\"lcs\": [1, \"x\"], \"n\": 2.5}", "t.json");
	double *v = NULL;
	size_t nv;
	long n;
	CHECK(cfg_numbers(c, "lcs", &v, &nv, 0, "Pa", 0, INFINITY) == -1 && v == NULL);
	CHECK_CONTAINS(err_msg(), "key 'lcs[1]': value \"x\"");
	CHECK(cfg_integer(c, "n", &n, 0, 10) == -1);
	CHECK_CONTAINS(err_msg(), "value 2.5: expected an integer");
	cfg_free(c);

	/* Integers beyond a long are refused before any conversion (which would
	 * be undefined), up to the very edge of the range. */
	c = cfg_parse(
	    "{\"huge\": 1e300, \"edge\": 9223372036854775807, \"ok\": 4611686018427387904, "
	    "\"neg\": -1e300}",
	    "t.json");
	CHECK(cfg_integer(c, "huge", &n, 0, 10) == -1);
	CHECK_CONTAINS(err_msg(), "key 'huge': value 1e+300: expected an integer in [0, 10]");
	CHECK(cfg_integer(c, "edge", &n, 0, LONG_MAX) == -1);
	CHECK_CONTAINS(err_msg(), "key 'edge': value ");
	CHECK(cfg_integer(c, "ok", &n, 0, LONG_MAX) == 0 && n == 4611686018427387904L);
	CHECK(cfg_integer(c, "neg", &n, LONG_MIN, 0) == -1);
	CHECK_CONTAINS(err_msg(), "key 'neg': value -1e+300: expected an integer");
	cfg_free(c);
}

int main(void)
{
	test_values();
	test_errors();
	return check_done();
}
