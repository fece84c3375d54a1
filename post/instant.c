#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "lib/err.h"
#include "post/instant.h"

/* The macroscopic series an instant is located on. */
typedef struct {
	size_t n;
	const double *t, *strain, *stress;
} series;

static series get_series(const dem_run *r)
{
	const double *t = run_column_data(r, "t");
	const double *e = run_column_data(r, "strain_axial");
	const double *s = run_column_data(r, "stress_axial");
	if (t && e && s && r->nrows > 0)
		return (series){r->nrows, t, e, s};
	return (series){r->nsnap, r->snap_t, r->snap_strain, r->snap_stress};
}

/* The row of the first largest value of v. */
static size_t argmax(const series *s, const double *v)
{
	size_t p = 0;
	for (size_t k = 1; k < s->n; k++)
		if (v[k] > v[p])
			p = k;
	return p;
}

/* The time at which v first attains level (interpolated), or -1. */
static int first_reach(const series *s, const double *v, double level, double *t)
{
	for (size_t k = 0; k < s->n; k++) {
		if (!(v[k] >= level))
			continue;
		if (k == 0 || v[k] == v[k - 1]) {
			*t = s->t[k];
		} else {
			double f = (level - v[k - 1]) / (v[k] - v[k - 1]);
			*t = s->t[k - 1] + f * (s->t[k] - s->t[k - 1]);
		}
		return 0;
	}
	return -1;
}

/* The value of v at time t, interpolated on the series. */
static double at_time(const series *s, const double *v, double t)
{
	if (s->n == 0)
		return NAN;
	if (t <= s->t[0])
		return v[0];
	for (size_t k = 1; k < s->n; k++)
		if (t <= s->t[k]) {
			double dt = s->t[k] - s->t[k - 1];
			double f = dt > 0 ? (t - s->t[k - 1]) / dt : 1;
			return v[k - 1] + f * (v[k] - v[k - 1]);
		}
	return v[s->n - 1];
}

static size_t nearest_snapshot(const dem_run *r, double t)
{
	size_t best = 0;
	for (size_t k = 1; k < r->nsnap; k++)
		if (fabs(r->snap_t[k] - t) < fabs(r->snap_t[best] - t))
			best = k;
	return best;
}

/* "" when a snapshot sits at time t, else where t falls among them. */
static void describe_gap(const dem_run *r, double t, char *buf, size_t n)
{
	size_t ns = r->nsnap, a = 0;
	buf[0] = '\0';
	for (size_t k = 0; k < ns; k++)
		if (fabs(r->snap_t[k] - t) <= 1e-9 * fabs(t))
			return;
	if (t < r->snap_t[0]) {
		snprintf(buf, n, "before the first snapshot: using ");
	} else if (t > r->snap_t[ns - 1]) {
		snprintf(buf, n, "after the last snapshot: using ");
	} else {
		while (a + 1 < ns && r->snap_t[a + 1] <= t)
			a++;
		snprintf(buf, n,
		         "between snapshots %zu (t = %.6g s) and %zu (t = %.6g s): using the "
		         "nearest, ",
		         a, r->snap_t[a], a + 1, r->snap_t[a + 1]);
	}
}

static int event_time(const char *path, const dem_run *r, const instant *in, double *t, char *what,
                      size_t n)
{
	series s = get_series(r);
	double last_t = fmax(s.t[s.n - 1], r->snap_t[r->nsnap - 1]);
	double first_t = fmin(s.t[0], r->snap_t[0]);
	switch (in->kind) {
	case AT_SNAPSHOT:
		return 0; /* not located on a series */
	case AT_PEAK: {
		size_t p = argmax(&s, s.stress);
		*t = s.t[p];
		snprintf(what, n, "peak axial stress %.4g MPa at t = %.6g s (axial strain %.4g %%)",
		         s.stress[p] * 1e-6, *t, 100 * s.strain[p]);
		return 0;
	}
	case AT_TIME:
		if (in->value < first_t || in->value > last_t)
			return err_set("%s: --time %g s: outside the run (t from %g to %g s)", path,
			               in->value, first_t, last_t);
		*t = in->value;
		snprintf(what, n, "t = %.6g s (axial strain %.4g %%, axial stress %.4g MPa)", *t,
		         100 * at_time(&s, s.strain, *t), 1e-6 * at_time(&s, s.stress, *t));
		return 0;
	case AT_STRAIN:
		if (first_reach(&s, s.strain, in->value, t))
			return err_set(
			    "%s: --strain %g: the axial strain never reaches it (largest %g)", path,
			    in->value, s.strain[argmax(&s, s.strain)]);
		snprintf(what, n, "axial strain first reaches %.4g %% at t = %.6g s",
		         100 * in->value, *t);
		return 0;
	case AT_STRESS:
		if (first_reach(&s, s.stress, in->value, t))
			return err_set(
			    "%s: --stress %g Pa: the axial stress never reaches it (peak %g Pa)",
			    path, in->value, s.stress[argmax(&s, s.stress)]);
		snprintf(what, n,
		         "axial stress first reaches %.4g MPa at t = %.6g s (axial strain %.4g %%)",
		         1e-6 * in->value, *t, 100 * at_time(&s, s.strain, *t));
		return 0;
	}
	return err_set("unknown instant");
}

int instant_pick(const char *path, const dem_run *r, const instant *in, size_t *snap, char *desc,
                 size_t n)
{
	if (r->nsnap == 0)
		return err_set("%s: the run has no snapshots (it stopped before writing one)",
		               path);
	char what[256] = "";
	double t = 0;
	if (event_time(path, r, in, &t, what, sizeof what))
		return -1;
	size_t k;
	if (in->kind == AT_SNAPSHOT) {
		long idx = (long)in->value, ns = (long)r->nsnap;
		if (idx < -ns || idx >= ns)
			return err_set(
			    "%s: --snapshot %ld: out of range (the run has %zu snapshots: 0 to "
			    "%zu, or -1 for the last)",
			    path, idx, r->nsnap, r->nsnap - 1);
		k = (size_t)(idx < 0 ? idx + ns : idx);
		/* (snapshot k itself: said once, below) */
		snprintf(what, sizeof what, "%s", idx == -1 ? "the last snapshot" : "");
		t = r->snap_t[k];
	} else {
		k = nearest_snapshot(r, t);
	}
	char gap[160];
	describe_gap(r, t, gap, sizeof gap);
	int len = snprintf(desc, n,
	                   "%s: %s%s%ssnapshot %zu (step %lld, t = %.6g s, axial strain %.4g %%, "
	                   "axial stress %.4g MPa)",
	                   path, what, what[0] ? "; " : "", gap, k, (long long)r->snap_step[k],
	                   r->snap_t[k], 100 * r->snap_strain[k], 1e-6 * r->snap_stress[k]);
	/* Say so when the snapshot's state is far from the instant's. */
	series sr = get_series(r);
	double want = at_time(&sr, sr.stress, t), peak = fabs(sr.stress[argmax(&sr, sr.stress)]);
	double off = fabs(r->snap_stress[k] - want);
	if (in->kind != AT_SNAPSHOT && off > 0.05 * fabs(want) && off > 1e-6 * peak && len > 0 &&
	    (size_t)len < n)
		snprintf(desc + len, n - (size_t)len,
		         "; its axial stress is %.0f %% off the instant's %.4g MPa: ask solve for "
		         "snapshots nearer to it",
		         100 * off / fabs(want), 1e-6 * want);
	*snap = k;
	return 0;
}

enum { INTEGER, NON_NEGATIVE, POSITIVE };

/* The option's value, a finite number of the kind asked for. */
static int parse_number(const char *opt, const char *text, const char *what, int kind, double *out)
{
	char *end;
	errno = 0;
	double v = strtod(text, &end);
	int ok = !errno && end != text && !*end && isfinite(v) &&
	         (kind == INTEGER        ? v == floor(v)
	          : kind == NON_NEGATIVE ? v >= 0
	                                 : v > 0);
	if (!ok)
		return err_set("--%s %s: expected %s", opt, text, what);
	*out = v;
	return 0;
}

int instant_parse(instant *in, const char *snapshot, const char *time, const char *strain,
                  const char *stress)
{
	const char *names[] = {"snapshot", "time", "strain", "stress"};
	const char *texts[] = {snapshot, time, strain, stress};
	const instant_kind kinds[] = {AT_SNAPSHOT, AT_TIME, AT_STRAIN, AT_STRESS};
	in->kind = AT_PEAK;
	in->value = 0;
	int given = -1;
	for (int k = 0; k < 4; k++) {
		if (!texts[k])
			continue;
		if (given >= 0)
			return err_set("--%s and --%s: give one instant only", names[given],
			               names[k]);
		given = k;
		in->kind = kinds[k];
	}
	switch (in->kind) {
	case AT_PEAK:
		return 0;
	case AT_SNAPSHOT:
		return parse_number("snapshot", snapshot, "an integer snapshot index", INTEGER,
		                    &in->value);
	case AT_TIME:
		return parse_number("time", time, "a time in s, >= 0", NON_NEGATIVE, &in->value);
	case AT_STRAIN:
		return parse_number("strain", strain, "an axial strain > 0 (compression positive)",
		                    POSITIVE, &in->value);
	case AT_STRESS:
		return parse_number("stress", stress,
		                    "an axial stress in Pa > 0 (compression positive)", POSITIVE,
		                    &in->value);
	}
	return 0;
}
