/* How far a point is from the targets. For target i with value T_i,
 * tolerance tol_i and weight w_i, the point's quantity q_i has the error
 * e_i = q_i / T_i - 1, and the residual
 *   r_i = sqrt(w_i) / tol_i * ln(q_i / T_i)      (a quantity that scales)
 *   r_i = sqrt(w_i) / tol_i * (q_i - T_i) / |T_i| (Poisson's ratio)
 * The objective is sum r_i^2; a point meets the targets when every
 * |e_i| <= tol_i. On a log scale the exact scaling moves the residuals
 * linearly (calibrate/scaling.h). */
#ifndef DEM_CALIBRATE_OBJECTIVE_H
#define DEM_CALIBRATE_OBJECTIVE_H

#include "calibrate/eval.h"
#include "calibrate/space.h"

typedef struct {
	double err[CAL_MAX_TARGETS]; /* relative errors e_i */
	double f;                    /* objective */
	double worst;                /* largest |e_i| / tol_i */
	int worst_target;
	int met;
} fit;

/* The fit of an outcome that holds every quantity (o->ok). */
void fit_compute(const cal_spec *sp, const outcome *o, fit *f);

/* With the scaling: the scales (ln S and ln K changes, within the bounds
 * of the free keys) that best meet the targets from the runs at (S, K, z),
 * and the fit they are predicted to give. -1 when no scale keeps the free
 * keys within their bounds. */
int fit_project(const space *s, double S, double K, const double *z, const outcome *o,
                double *sigma, double *kappa, fit *pred);

#endif
