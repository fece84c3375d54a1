#include <math.h>

#include "calibrate/objective.h"
#include "calibrate/scaling.h"

/* Residual of target k at log-ratio or relative difference d. */
static double weight(const cal_target *t) { return sqrt(t->weight) / t->tol; }

static void finish(const cal_spec *sp, const double *d, fit *f)
{
	f->f = 0;
	f->worst = 0;
	f->worst_target = 0;
	f->met = 1;
	for (int k = 0; k < sp->ntarget; k++) {
		const cal_target *t = &sp->target[k];
		const quantity *q = &quantities[t->quantity];
		double r = weight(t) * d[k];
		f->f += r * r;
		f->err[k] = quantity_positive(q) ? expm1(d[k]) : d[k];
		double w = fabs(f->err[k]) / t->tol;
		if (w > f->worst)
			f->worst = w, f->worst_target = k;
		f->met &= fabs(f->err[k]) <= t->tol;
	}
}

/* ln(q/T) for the quantities that scale, (q - T)/|T| for the others. */
static void differences(const cal_spec *sp, const outcome *o, double *d)
{
	for (int k = 0; k < sp->ntarget; k++) {
		const cal_target *t = &sp->target[k];
		double q = o->q[t->test][t->quantity];
		d[k] = quantity_positive(&quantities[t->quantity])
		           ? log(q / t->value)
		           : (q - t->value) / fabs(t->value);
	}
}

void fit_compute(const cal_spec *sp, const outcome *o, fit *f)
{
	double d[CAL_MAX_TARGETS];
	differences(sp, o, d);
	finish(sp, d, f);
}

int fit_project(const space *s, double S, double K, const double *z, const outcome *o,
                double *sigma, double *kappa, fit *pred)
{
	const cal_spec *sp = s->sp;
	double box[4];
	if (space_scale_box(s, S, K, z, box))
		return -1;
	double d[CAL_MAX_TARGETS], c[CAL_MAX_TARGETS], a[CAL_MAX_TARGETS], b[CAL_MAX_TARGETS];
	differences(sp, o, d);
	for (int k = 0; k < sp->ntarget; k++) {
		const cal_target *t = &sp->target[k];
		const quantity *q = &quantities[t->quantity];
		c[k] = weight(t) * d[k];
		a[k] = quantity_positive(q) ? weight(t) * q->a : 0;
		b[k] = quantity_positive(q) ? weight(t) * q->b : 0;
	}
	scaling_project(sp->ntarget, c, a, b, box, sigma, kappa);
	for (int k = 0; k < sp->ntarget; k++) {
		const quantity *q = &quantities[sp->target[k].quantity];
		if (quantity_positive(q))
			d[k] += q->a * *sigma + q->b * *kappa;
	}
	finish(sp, d, pred);
	return 0;
}
