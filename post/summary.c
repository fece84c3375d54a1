/* The figures of summary.json (equations in post/summary.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lib/err.h"
#include "post/summary.h"

static double last_or_nan(const double *v, size_t n) { return v ? v[n - 1] : NAN; }

/* Least-squares slope of y against x over the rows k < end with
 * lo <= w[k] <= hi; NaN with fewer than two rows or no spread in x. */
static double slope_band(const double *x, const double *y, const double *w, size_t end, double lo,
                         double hi)
{
	double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
	for (size_t k = 0; k < end; k++)
		if (w[k] >= lo && w[k] <= hi) {
			n++, sx += x[k], sy += y[k], sxx += x[k] * x[k], sxy += x[k] * y[k];
		}
	double d = n * sxx - sx * sx;
	return n >= 2 && d > 0 ? (n * sxy - sx * sy) / d : NAN;
}

/* Slope of y against x between the last row before end where w is below
 * level and the row after it. */
static double slope_crossing(const double *x, const double *y, const double *w, size_t end,
                             double level)
{
	for (size_t k = end; k-- > 1;)
		if (w[k - 1] < level && w[k] >= level)
			return x[k] != x[k - 1] ? (y[k] - y[k - 1]) / (x[k] - x[k - 1]) : NAN;
	return NAN;
}

/* The tangent slope of y(x) at w = 0.5 wp on the rows before end. */
static double tangent_at_half(const double *x, const double *y, const double *w, size_t end,
                              double wp)
{
	double s = slope_band(x, y, w, end, 0.4 * wp, 0.6 * wp);
	return isfinite(s) ? s : slope_crossing(x, y, w, end, 0.5 * wp);
}

/* The peak of q on the first loading branch: before the axial strain first
 * falls back by more than UNLOAD_STRAIN (an unloading stage). */
#define UNLOAD_STRAIN 1e-4
static size_t first_loading_peak(const double *ea, const double *q, size_t n)
{
	size_t kp = 0;
	double emax = ea[0];
	for (size_t k = 0; k < n && ea[k] > emax - UNLOAD_STRAIN; k++) {
		emax = fmax(emax, ea[k]);
		kp = q[k] > q[kp] ? k : kp;
	}
	return kp;
}

static double ke_ratio(const dem_run *r, const double *w, size_t end, double lo, double hi)
{
	const double *ek = run_column_data(r, "energy_kinetic");
	const double *ee = run_column_data(r, "energy_elastic");
	if (!ek || !ee)
		return NAN;
	double m = NAN;
	for (size_t k = 0; k < end; k++)
		if (w[k] >= lo && w[k] <= hi && ee[k] > 0)
			m = isnan(m) ? ek[k] / ee[k] : fmax(m, ek[k] / ee[k]);
	return m;
}

static double wall_time(const dem_run *r)
{
	const double *step = run_column_data(r, "step"), *rate = run_column_data(r, "rate");
	if (!step || !rate)
		return NAN;
	double t = 0;
	for (size_t k = 1; k < r->nrows; k++)
		if (isfinite(rate[k]) && rate[k] > 0)
			t += (step[k] - step[k - 1]) / rate[k];
	return t;
}

static void hydrostatic(const dem_run *r, summary *s)
{
	const double *p = run_column_data(r, "pressure");
	const double *ev = run_column_data(r, "strain_volumetric");
	if (!p)
		return;
	double pmax = 0;
	for (size_t k = 0; k < r->nrows; k++)
		pmax = fmax(pmax, p[k]);
	if (pmax <= 0)
		return;
	if (ev)
		s->bulk_modulus = slope_band(ev, p, p, r->nrows, 0.25 * pmax, 0.75 * pmax);
	s->ke_ratio_max = ke_ratio(r, p, r->nrows, 0.5 * pmax, pmax);
}

int summary_finished(const dem_run *r)
{
	return r->status && (!strcmp(r->status, "complete") || !strncmp(r->status, "stopped: ", 9));
}

int summary_no_peak(const dem_run *r)
{
	const double *sa = run_column_data(r, "stress_axial");
	if (!sa || r->nrows <= 2 || !r->status || !strstr(r->status, "axial strain reached"))
		return 0;
	size_t top = 0;
	for (size_t k = 1; k < r->nrows; k++)
		top = sa[k] > sa[top] ? k : top;
	return sa[r->nrows - 1] >= 0.99 * sa[top];
}

int summary_compute(const dem_run *r, summary_kind kind, double D, double t, summary *s)
{
	const double *ea = run_column_data(r, "strain_axial");
	const double *sa = run_column_data(r, "stress_axial");
	if (!ea || !sa)
		return err_set("the history has no column '%s'",
		               ea ? "stress_axial" : "strain_axial");
	size_t n = r->nrows;
	if (n == 0)
		return err_set("the history table is empty (the run stopped before its first row)");
	const double *p = run_column_data(r, "pressure");
	const double *er = run_column_data(r, "strain_radial");
	const double *fa = run_column_data(r, "force_axial");
	*s = (summary){.peak_stress = NAN,
	               .strain_at_peak = NAN,
	               .peak_deviator = NAN,
	               .strain_at_peak_deviator = NAN,
	               .pressure_at_peak = NAN,
	               .young_modulus = NAN,
	               .poisson_ratio = NAN,
	               .bts_strength = NAN,
	               .peak_force = NAN,
	               .bulk_modulus = NAN,
	               .residual_stress = NAN,
	               .residual_deviator = NAN,
	               .pressure_final = NAN,
	               .strain_axial_final = NAN,
	               .strain_volumetric_final = NAN,
	               .ke_ratio_max = NAN,
	               .bonds_intact = NAN,
	               .bonds_damaged = NAN,
	               .bonds_broken_tension = NAN,
	               .bonds_broken_shear = NAN,
	               .steps = NAN,
	               .time = NAN,
	               .wall_time = NAN};
	double *q = xmalloc(n * sizeof *q);
	size_t kp = 0, ks = 0;
	for (size_t k = 0; k < n; k++) {
		q[k] = sa[k] - (p ? p[k] : 0);
		kp = q[k] > q[kp] ? k : kp;
		ks = sa[k] > sa[ks] ? k : ks;
	}
	s->peak_stress = sa[ks], s->strain_at_peak = ea[ks];
	s->peak_deviator = q[kp], s->strain_at_peak_deviator = ea[kp];
	s->pressure_at_peak = p ? p[kp] : 0;
	s->residual_stress = sa[n - 1], s->residual_deviator = q[n - 1];
	if (kind == TEST_HYDROSTATIC) {
		hydrostatic(r, s);
	} else if (q[kp] > 0) {
		size_t k1 = first_loading_peak(ea, q, n);
		if (kind == TEST_COMPRESSION && q[k1] > 0) {
			s->young_modulus = tangent_at_half(ea, q, q, k1, q[k1]);
			if (er)
				s->poisson_ratio = -tangent_at_half(ea, er, q, k1, q[k1]);
		}
		s->ke_ratio_max = ke_ratio(r, q, kp + 1, 0.5 * q[kp], q[kp]);
	}
	if (fa) {
		s->peak_force = fa[0];
		for (size_t k = 1; k < n; k++)
			s->peak_force = fmax(s->peak_force, fa[k]);
		if (kind == TEST_BTS && D > 0 && t > 0)
			s->bts_strength = summary_splitting_stress(s->peak_force, D, t);
	}
	s->pressure_final = p ? p[n - 1] : 0;
	s->strain_axial_final = ea[n - 1];
	s->strain_volumetric_final = last_or_nan(run_column_data(r, "strain_volumetric"), n);
	s->bonds_intact = last_or_nan(run_column_data(r, "bonds_intact"), n);
	s->bonds_damaged = last_or_nan(run_column_data(r, "bonds_damaged"), n);
	s->bonds_broken_tension = last_or_nan(run_column_data(r, "bonds_broken_tension"), n);
	s->bonds_broken_shear = last_or_nan(run_column_data(r, "bonds_broken_shear"), n);
	s->steps = last_or_nan(run_column_data(r, "step"), n);
	s->time = last_or_nan(run_column_data(r, "t"), n);
	s->wall_time = wall_time(r);
	free(q);
	return 0;
}
