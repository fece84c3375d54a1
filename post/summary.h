/* What a laboratory test measured, from a run's history table: the figures
 * of summary.json (post summary, share/doc/post.md).
 *
 * The loading stress is the deviator q = sigma_a - p_c (sigma_a alone when
 * the history has no pressure column): the axial stress of a UCS or a
 * Brazilian test, the differential stress of a triaxial or USC test. With
 * its peak q_p at row k_p:
 *   Young's modulus  E  = dq/d(eps_a), least squares over the rows before
 *                         k_p with q in [0.4, 0.6] q_p (the tangent at 50 %
 *                         of the peak; the two rows around 0.5 q_p when the
 *                         band holds fewer than two); with unload-reload
 *                         cycles, q_p and k_p of the first loading branch
 *                         (before the axial strain first falls back by
 *                         more than 1e-4)
 *   Poisson's ratio  nu = -d(eps_r)/d(eps_a) over the same rows (eps_r is
 *                         compression positive, so a bulging specimen has
 *                         nu > 0)
 *   Brazilian        sigma_t = 2 P / (pi D t), P the largest platen load
 *                         (force_axial), D the disc's diameter, t its
 *                         thickness
 *   hydrostatic      K = dp/d(eps_v) over the rows with p in [0.25, 0.75]
 *                         of its largest value
 *   quasi-static     the largest E_kin/E_el over the rows of the loading
 *                         branch (q in [0.5, 1] q_p before k_p; p in
 *                         [0.5, 1] p_max for a hydrostatic test)
 *   wall time        sum over rows of (step_k - step_{k-1}) / rate_k (the
 *                         rate column is steps per wall second since the
 *                         previous row)
 * A figure that is not defined for the test, or that the history cannot
 * give, is NaN (null in the JSON). */
#ifndef DEM_POST_SUMMARY_H
#define DEM_POST_SUMMARY_H

#include <stddef.h>

#include "lib/runfile.h"

typedef enum { TEST_COMPRESSION, TEST_BTS, TEST_HYDROSTATIC } summary_kind;

/* Above this kinetic/elastic energy ratio on the loading branch the run is
 * flagged as not quasi-static. */
#define SUMMARY_KE_RATIO_MAX 0.05

typedef struct {
	double peak_stress;    /* Pa, largest axial stress */
	double strain_at_peak; /* axial strain there */
	double peak_deviator;  /* Pa, largest q */
	double strain_at_peak_deviator;
	double pressure_at_peak; /* Pa, p_c at the peak of q */
	double young_modulus;    /* Pa */
	double poisson_ratio;
	double bts_strength;    /* Pa */
	double peak_force;      /* N, largest platen load */
	double bulk_modulus;    /* Pa */
	double residual_stress; /* Pa, axial stress at the last row */
	double residual_deviator;
	double pressure_final; /* Pa */
	double strain_axial_final, strain_volumetric_final;
	double ke_ratio_max; /* kinetic / elastic energy on the loading branch */
	double bonds_intact, bonds_damaged, bonds_broken_tension, bonds_broken_shear;
	double steps, time; /* last row: step, s */
	double wall_time;   /* s */
} summary;

/* Whether the run reached its end (status "complete" or "stopped: ...":
 * a stop rule, or a diagnosed failure, whose status reads the same), not
 * interrupted before it. */
int summary_finished(const dem_run *r);
/* Whether the run has no peak: its axial-strain stop ended it with the
 * axial stress still within 1 % of its highest (still rising, or on a
 * plateau), so its "peak" is where the run stopped, not a limit stress. */
int summary_no_peak(const dem_run *r);

/* Figures of the history of r for a test of that kind; D and t (m) are the
 * Brazilian disc's diameter and thickness (ignored otherwise). Returns 0,
 * or -1 with err_set() when the history lacks strain_axial or stress_axial
 * or is empty. */
int summary_compute(const dem_run *r, summary_kind kind, double D, double t, summary *s);

/* The splitting tensile stress of a Brazilian test (Pa): 2P/(pi D t) for
 * the load P (N) on a disc of diameter D and thickness t (m). */
static inline double summary_splitting_stress(double P, double D, double t)
{
	return 2 * P / (3.14159265358979323846 * D * t);
}

#endif
