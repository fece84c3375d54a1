#include <math.h>
#include <string.h>

#include "calibrate/scaling.h"

static const char *const onate_keys[] = {
    "tensile_strength", "shear_strength", "LCS1", "LCS2", "LCS3", "E0", "contact.E", NULL};
static const char *const jcfpm_keys[] = {"tensile_strength", "cohesion", "E", "contact.E", NULL};
static const char *const linear_keys[] = {
    "tensile_strength", "shear_strength", "E", "kn", "ks", "contact.E", NULL};
/* Where the stiffnesses begin in each list. */
static const struct {
	const char *law;
	const char *const *keys;
	int first_stiff;
} laws[] = {
    {"onate", onate_keys, 5},
    {"jcfpm", jcfpm_keys, 2},
    {"linear", linear_keys, 2},
};
enum { NLAWS = sizeof laws / sizeof laws[0] };

static int law_index(const char *law)
{
	for (int k = 0; k < NLAWS; k++)
		if (strcmp(laws[k].law, law) == 0)
			return k;
	return -1;
}

int scaling_law(const char *law) { return law_index(law) >= 0; }

const char *const *scaling_keys(const char *law)
{
	int l = law_index(law);
	return l < 0 ? NULL : laws[l].keys;
}

scale_class scaling_class(const char *law, const char *key)
{
	int l = law_index(law);
	if (l < 0)
		return CLS_NONE;
	for (int k = 0; laws[l].keys[k]; k++)
		if (strcmp(laws[l].keys[k], key) == 0)
			return k < laws[l].first_stiff ? CLS_STRESS : CLS_STIFF;
	return CLS_NONE;
}

static double clamp(double x, double lo, double hi) { return x < lo ? lo : x > hi ? hi : x; }

static double cost(int m, const double *c, const double *a, const double *b, double s, double k)
{
	double f = 0;
	for (int i = 0; i < m; i++) {
		double r = c[i] + a[i] * s + b[i] * k;
		f += r * r;
	}
	return f;
}

/* The best value of one scale with the other held, within [lo, hi]: a
 * one-dimensional least-squares fit, clamped (the cost is convex). */
static double best_one(int m, const double *c, const double *a, const double *other, double held,
                       double lo, double hi)
{
	double num = 0, den = 0;
	for (int i = 0; i < m; i++) {
		num -= a[i] * (c[i] + other[i] * held);
		den += a[i] * a[i];
	}
	return den > 0 ? clamp(num / den, lo, hi) : clamp(0, lo, hi);
}

double scaling_project(int m, const double *c, const double *a, const double *b,
                       const double box[4], double *sigma, double *kappa)
{
	/* Normal equations, with a ridge of a millionth of their trace that
	 * picks the smallest change along a direction the targets leave free
	 * (e.g. strains alone fix only s/k). */
	double saa = 0, sab = 0, sbb = 0, sac = 0, sbc = 0;
	for (int i = 0; i < m; i++) {
		saa += a[i] * a[i], sab += a[i] * b[i], sbb += b[i] * b[i];
		sac += a[i] * c[i], sbc += b[i] * c[i];
	}
	double ridge = 1e-6 * (saa + sbb) + 1e-300;
	saa += ridge, sbb += ridge;
	double det = saa * sbb - sab * sab;
	double s = (-sac * sbb + sbc * sab) / det, k = (-sbc * saa + sac * sab) / det;
	if (s >= box[0] && s <= box[1] && k >= box[2] && k <= box[3]) {
		*sigma = s, *kappa = k;
		return cost(m, c, a, b, s, k);
	}
	/* Outside the box: the minimum of a convex function lies on its
	 * boundary; try each edge (the other scale at its best there). */
	double best = INFINITY;
	for (int e = 0; e < 4; e++) {
		double ts, tk;
		if (e < 2) {
			ts = box[e];
			tk = best_one(m, c, b, a, ts, box[2], box[3]);
		} else {
			tk = box[e];
			ts = best_one(m, c, a, b, tk, box[0], box[1]);
		}
		double f = cost(m, c, a, b, ts, tk);
		if (f < best)
			best = f, *sigma = ts, *kappa = tk;
	}
	return best;
}
