#include <math.h>
#include <stdio.h>
#include <string.h>

#include "calibrate/sensitivity.h"
#include "calibrate/space.h"

/* Eigenvalues and eigenvectors of the symmetric n x n matrix a (cyclic
 * Jacobi rotations; a is destroyed): a's diagonal holds the eigenvalues,
 * the columns of v the eigenvectors. */
static void jacobi(int n, double a[CAL_MAX_FREE][CAL_MAX_FREE],
                   double v[CAL_MAX_FREE][CAL_MAX_FREE])
{
	for (int i = 0; i < n; i++)
		for (int j = 0; j < n; j++)
			v[i][j] = i == j;
	for (int sweep = 0; sweep < 100; sweep++) {
		double off = 0, diag = 0;
		for (int i = 0; i < n; i++) {
			diag += a[i][i] * a[i][i];
			for (int j = i + 1; j < n; j++)
				off += a[i][j] * a[i][j];
		}
		if (off <= 1e-30 * diag || off == 0)
			return;
		for (int p = 0; p < n; p++)
			for (int q = p + 1; q < n; q++) {
				if (a[p][q] == 0)
					continue;
				double theta = (a[q][q] - a[p][p]) / (2 * a[p][q]);
				double t =
				    (theta >= 0 ? 1 : -1) / (fabs(theta) + sqrt(theta * theta + 1));
				double c = 1 / sqrt(t * t + 1), s = t * c;
				for (int k = 0; k < n; k++) {
					double akp = a[k][p], akq = a[k][q];
					a[k][p] = c * akp - s * akq;
					a[k][q] = s * akp + c * akq;
				}
				for (int k = 0; k < n; k++) {
					double apk = a[p][k], aqk = a[q][k];
					a[p][k] = c * apk - s * aqk;
					a[q][k] = s * apk + c * aqk;
				}
				for (int k = 0; k < n; k++) {
					double vkp = v[k][p], vkq = v[k][q];
					v[k][p] = c * vkp - s * vkq;
					v[k][q] = s * vkp + c * vkq;
				}
			}
	}
}

static double cosine(int n, const double *x, int sx, const double *y, int sy)
{
	double xy = 0, xx = 0, yy = 0;
	for (int k = 0; k < n; k++) {
		xy += x[k * sx] * y[k * sy];
		xx += x[k * sx] * x[k * sx];
		yy += y[k * sy] * y[k * sy];
	}
	return xx > 0 && yy > 0 ? xy / sqrt(xx * yy) : 0;
}

void sensitivity_analyse(const cal_spec *sp, sensitivity *s)
{
	int n = sp->nfree, m = sp->ntarget;
	/* A target fixes the keys no better than its tolerance and its noise
	 * together: a match within 2 % of a quantity that moves by 10 % between
	 * neighbouring points says little about the keys only it sees. */
	double jw[CAL_MAX_TARGETS][CAL_MAX_FREE];
	for (int i = 0; i < m; i++) {
		double tol = sp->target[i].tol;
		double width = isfinite(s->noise[i]) ? hypot(tol, s->noise[i]) : tol;
		for (int k = 0; k < n; k++)
			jw[i][k] = s->J[i][k] * sqrt(sp->target[i].weight) / width;
	}
	double f[CAL_MAX_FREE][CAL_MAX_FREE], v[CAL_MAX_FREE][CAL_MAX_FREE];
	for (int k = 0; k < n; k++)
		for (int l = 0; l < n; l++) {
			f[k][l] = 0;
			for (int i = 0; i < m; i++)
				f[k][l] += jw[i][k] * jw[i][l];
		}
	jacobi(n, f, v);
	double lmax = 0;
	for (int j = 0; j < n; j++)
		lmax = fmax(lmax, f[j][j]);
	for (int k = 0; k < n; k++) {
		double var = 0;
		for (int j = 0; j < n; j++) {
			if (f[j][j] > 1e-9 * lmax && f[j][j] > 0)
				var += v[k][j] * v[k][j] / f[j][j];
			else if (v[k][j] * v[k][j] > 1e-6)
				var = INFINITY;
		}
		s->sigma[k] = sqrt(var);
	}
	for (int k = 0; k < n; k++)
		for (int l = 0; l < n; l++)
			s->key_cos[k][l] =
			    cosine(m, &jw[0][k], CAL_MAX_FREE, &jw[0][l], CAL_MAX_FREE);
	for (int i = 0; i < m; i++)
		for (int j = 0; j < m; j++)
			s->target_cos[i][j] = cosine(n, jw[i], 1, jw[j], 1);
}

int sensitivity_run(evaluator *e, const double *v, const outcome *at, sensitivity *s)
{
	const cal_spec *sp = e->sp;
	memset(s, 0, sizeof *s);
	/* Central differences: a step up and a step down of each key, relative
	 * (a step of the range from 0), held within the bounds. */
	double pts[2 * CAL_MAX_FREE][CAL_MAX_KEYS], dv[CAL_MAX_FREE][2];
	int n = sp->nfree;
	space sc; /* its anchors: the keys the tied ones keep their ratio to */
	space_init(&sc, sp);
	for (int k = 0; k < n; k++) {
		const cal_key *p = &sp->key[k];
		double h = v[k] != 0 ? sp->sens_step * fabs(v[k]) : sp->sens_step * (p->hi - p->lo);
		dv[k][0] = fmin(h, p->hi - v[k]);
		dv[k][1] = -fmin(h, v[k] - p->lo);
		for (int side = 0; side < 2; side++) {
			double *pt = pts[2 * k + side];
			memcpy(pt, v, sizeof pts[0]);
			pt[k] = v[k] + dv[k][side];
			/* The keys tied to an anchor keep their ratio to it, as
			 * everywhere in the calibration: they move with it. */
			if (p->cls != CLS_NONE && sc.anchor[p->cls] == k && v[k] != 0)
				for (int j = n; j < sp->nkey; j++)
					if (sp->key[j].cls == p->cls)
						pt[j] = v[j] * (pt[k] / v[k]);
		}
		double scale = v[k] != 0 ? fabs(v[k]) : p->hi - p->lo;
		s->h[k] = (dv[k][0] - dv[k][1]) / scale;
	}
	outcome out[2 * CAL_MAX_FREE];
	if (eval_points(e, (const double(*)[CAL_MAX_KEYS])pts, 2 * n, SPECIMEN_SEARCH,
	                PHASE_SENSITIVITY, out))
		return -1;
	for (int k = 0; k < 2 * n; k++)
		if (!out[k].ok) {
			snprintf(s->message, sizeof s->message, "%s changed by %+.3g %%: %s",
			         sp->key[k / 2].name, 100 * dv[k / 2][k % 2] / fabs(v[k / 2]),
			         out[k].message);
			return 0;
		}
	for (int i = 0; i < sp->ntarget; i++) {
		const cal_target *t = &sp->target[i];
		double q0 = at->q[t->test][t->quantity], sum = 0;
		for (int k = 0; k < n; k++) {
			double up = out[2 * k].q[t->test][t->quantity],
			       down = out[2 * k + 1].q[t->test][t->quantity];
			s->J[i][k] = (up - down) / fabs(t->value) / s->h[k];
			/* Unequal steps (at a bound): the line through the ends. */
			double w = dv[k][0] / (dv[k][0] - dv[k][1]);
			double d = (q0 - (w * down + (1 - w) * up)) / fabs(t->value);
			sum += d * d / (w * w + (1 - w) * (1 - w) + 1);
		}
		s->noise[i] = sqrt(sum / n);
	}
	s->ran = 1;
	sensitivity_analyse(sp, s);
	return 0;
}
