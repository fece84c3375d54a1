/* What the targets say about the parameters, at the calibrated point: the
 * sensitivities of every target to every free key by forward differences
 * (one run per test and key, side by side), as elasticities
 *   J_ik = (dq_i / |T_i|) / (dp_k / p_k)
 * (the relative change of the quantity, as a fraction of its target, per
 * relative change of the key); from them, with the residuals' weights
 * W_i = w_i / (tol_i^2 + noise_i^2) (calibrate/objective.h's, widened by
 * each target's measured noise), the uncertainty of each key that the
 * targets' tolerances and noise leave, sqrt of the diagonal of
 * (J^T W J)^-1 (the pseudo-inverse: a key along a direction the targets
 * do not see is not identifiable), the cosines between keys' columns (two
 * keys trade off when their columns are nearly parallel) and between
 * targets' rows (two targets conflict when every key moves them together
 * and they ask to move apart). */
#ifndef DEM_CALIBRATE_SENSITIVITY_H
#define DEM_CALIBRATE_SENSITIVITY_H

#include "calibrate/eval.h"

typedef struct {
	int ran;                /* the perturbed points ran */
	double h[CAL_MAX_FREE]; /* the relative width of each difference */
	double J[CAL_MAX_TARGETS][CAL_MAX_FREE];
	double sigma[CAL_MAX_FREE]; /* relative uncertainty; INFINITY: not identifiable */
	double key_cos[CAL_MAX_FREE][CAL_MAX_FREE];
	double target_cos[CAL_MAX_TARGETS][CAL_MAX_TARGETS];
	/* The noise of each target, relative to its value: what the three
	 * runs of a key (down, at, up) leave beyond a straight line,
	 * (q+ + q- - 2 q0) / sqrt(6) for independent noise of deviation s,
	 * root-mean-square over the keys (curvature counts as noise). */
	double noise[CAL_MAX_TARGETS];
	char message[700]; /* why they did not run */
} sensitivity;

/* The sensitivities at the key values v, whose outcome is at. 0; -1 when
 * a signal stopped it or with err_set() on an error of the calibration. */
int sensitivity_run(evaluator *e, const double *v, const outcome *at, sensitivity *s);

/* The uncertainties and cosines from s->J and s->noise (NaN: none measured). */
void sensitivity_analyse(const cal_spec *sp, sensitivity *s);

/* Above this |cosine| two keys trade off, or two targets move together. */
#define SENS_PARALLEL 0.95
/* Above this relative uncertainty a key is not identified by the targets;
 * above SENS_LOOSE, loosely. */
#define SENS_UNIDENTIFIED 0.25
#define SENS_LOOSE 0.05

#endif
