/* The exact scaling of the bonded laws (share/doc/validation.md §1,
 * share/doc/calibrate.md): every force of the `onate`, `jcfpm` and
 * `linear` laws is a stiffness times a displacement, bounded by a strength
 * times an area. Multiply every stress of the material (strengths, limit
 * compressive stresses) by s and every stiffness (moduli) by k: the forces
 * at displacements scaled by s/k are those of before times s, so a
 * quasi-static test gives stresses times s, moduli times k and strains
 * times s/k (calibrate/quantity.h), ratios unchanged. It holds for tests
 * that prescribe motions, not stresses (a confining pressure would have to
 * scale too), and up to the inertia of the loading (the time step and the
 * wave speed do not scale as the strains do): one run then predicts every
 * run of the two-parameter family, closely, and the search is left with
 * the dimensionless ratios. */
#ifndef DEM_CALIBRATE_SCALING_H
#define DEM_CALIBRATE_SCALING_H

typedef enum { CLS_NONE, CLS_STRESS, CLS_STIFF } scale_class;

/* Whether the law has the exact scaling. */
int scaling_law(const char *law);
/* The class of a material key under the law's scaling (CLS_NONE for a key
 * that does not scale, or a law without it). Keys of the nested contact
 * object are dotted: "contact.E". */
scale_class scaling_class(const char *law, const char *key);
/* The law's scaling keys, NULL-terminated: stresses then stiffnesses. */
const char *const *scaling_keys(const char *law);

/* The scales that best meet the targets from one run, in logarithms: m
 * residuals r_i = c_i + a_i sigma + b_i kappa (sigma = ln s, kappa = ln k,
 * each residual already weighted), minimise sum r_i^2 over sigma in
 * [box[0], box[1]] and kappa in [box[2], box[3]] (an empty interval
 * [0, 0] holds a scale at 1). Writes sigma and kappa and returns the
 * minimum. When the residuals leave a scale undetermined, the smallest
 * change is taken. */
double scaling_project(int m, const double *c, const double *a, const double *b,
                       const double box[4], double *sigma, double *kappa);

#endif
