#include <math.h>

#include "calibrate/space.h"

void space_init(space *s, const cal_spec *sp)
{
	s->sp = sp;
	s->nz = 0;
	s->anchor[CLS_NONE] = s->anchor[CLS_STRESS] = s->anchor[CLS_STIFF] = -1;
	for (int k = 0; k < sp->nfree; k++) {
		const cal_key *p = &sp->key[k];
		if (p->cls != CLS_NONE && s->anchor[p->cls] < 0) {
			s->anchor[p->cls] = k;
			continue;
		}
		int z = s->nz++;
		s->zkey[z] = k;
		if (p->cls != CLS_NONE) {
			const cal_key *a = &sp->key[s->anchor[p->cls]];
			s->kind[z] = Z_RATIO;
			s->lo[z] = log(p->lo / a->hi);
			s->hi[z] = log(p->hi / a->lo);
		} else if (p->log) {
			s->kind[z] = Z_LOG;
			s->lo[z] = log(p->lo);
			s->hi[z] = log(p->hi);
		} else {
			s->kind[z] = Z_LINEAR;
			s->lo[z] = p->lo;
			s->hi[z] = p->hi;
		}
		if (s->kind[z] == Z_LINEAR) {
			s->step[z] = sp->step * (p->hi - p->lo) / 2;
			s->xtol[z] = sp->xtol * (p->hi - p->lo);
		} else {
			s->step[z] = log1p(sp->step);
			s->xtol[z] = log1p(sp->xtol);
		}
	}
}

static double scale_of(scale_class c, double S, double K) { return c == CLS_STRESS ? S : K; }

void space_values(const space *s, double S, double K, const double *z, double *v)
{
	const cal_spec *sp = s->sp;
	for (int k = 0; k < sp->nkey; k++) {
		const cal_key *p = &sp->key[k];
		if (p->cls != CLS_NONE)
			v[k] = scale_of(p->cls, S, K) * p->tmpl;
		else
			v[k] = p->start;
	}
	for (int j = 0; j < s->nz; j++) {
		int k = s->zkey[j];
		switch (s->kind[j]) {
		case Z_LINEAR:
			v[k] = z[j];
			break;
		case Z_LOG:
			v[k] = exp(z[j]);
			break;
		case Z_RATIO:
			v[k] = v[s->anchor[sp->key[k].cls]] * exp(z[j]);
			break;
		}
	}
	for (int k = 0; k < sp->nfree; k++)
		v[k] = fmin(fmax(v[k], sp->key[k].lo), sp->key[k].hi);
}

int space_project(const space *s, double S, double K, double *z)
{
	const cal_spec *sp = s->sp;
	int moved = 0;
	for (int j = 0; j < s->nz; j++) {
		const cal_key *p = &sp->key[s->zkey[j]];
		double lo = s->lo[j], hi = s->hi[j];
		if (s->kind[j] == Z_RATIO) {
			const cal_key *a = &sp->key[s->anchor[p->cls]];
			double va = scale_of(p->cls, S, K) * a->tmpl;
			lo = fmax(lo, log(p->lo / va));
			hi = fmin(hi, log(p->hi / va));
		}
		double x = fmin(fmax(z[j], lo), hi);
		moved += x != z[j];
		z[j] = x;
	}
	return moved;
}

void space_coords(const space *s, const double *v, double *S, double *K, double *z)
{
	const cal_spec *sp = s->sp;
	int as = s->anchor[CLS_STRESS], ak = s->anchor[CLS_STIFF];
	*S = as >= 0 ? v[as] / sp->key[as].tmpl : 1;
	*K = ak >= 0 ? v[ak] / sp->key[ak].tmpl : 1;
	for (int j = 0; j < s->nz; j++) {
		int k = s->zkey[j];
		switch (s->kind[j]) {
		case Z_LINEAR:
			z[j] = v[k];
			break;
		case Z_LOG:
			z[j] = log(v[k]);
			break;
		case Z_RATIO:
			z[j] = log(v[k] / v[s->anchor[sp->key[k].cls]]);
			break;
		}
	}
}

int space_scale_box(const space *s, double S, double K, const double *z, double box[4])
{
	const cal_spec *sp = s->sp;
	double v[CAL_MAX_KEYS];
	space_values(s, S, K, z, v);
	box[0] = box[2] = -INFINITY;
	box[1] = box[3] = INFINITY;
	for (int c = CLS_STRESS; c <= CLS_STIFF; c++) {
		double *b = box + 2 * (c - CLS_STRESS);
		if (s->anchor[c] < 0) {
			b[0] = b[1] = 0;
			continue;
		}
		for (int k = 0; k < sp->nfree; k++)
			if (sp->key[k].cls == (scale_class)c) {
				b[0] = fmax(b[0], log(sp->key[k].lo / v[k]));
				b[1] = fmin(b[1], log(sp->key[k].hi / v[k]));
			}
		if (b[0] > b[1])
			return -1;
	}
	return 0;
}
