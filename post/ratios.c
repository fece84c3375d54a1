#include <math.h>
#include <stdlib.h>

#include "lib/err.h"
#include "lib/vec3.h"
#include "post/frame.h"
#include "post/ratios.h"

const char *const ratio_group_name[RATIO_NGROUPS] = {"all", "intact", "damaged"};

void ratio_bins_width(ratio_bins *b, double w)
{
	b->n = (int)ceil(90.0 / w - 1e-9);
	b->edges = xmalloc((size_t)(b->n + 1) * sizeof *b->edges);
	for (int k = 0; k < b->n; k++)
		b->edges[k] = k * w;
	b->edges[b->n] = 90;
}

void ratio_bins_solid_angle(ratio_bins *b, int n)
{
	b->n = n;
	b->edges = xmalloc((size_t)(n + 1) * sizeof *b->edges);
	for (int k = 0; k < n; k++)
		b->edges[k] = asin((double)k / n) * POST_DEG;
	b->edges[n] = 90;
}

void ratio_bins_free(ratio_bins *b)
{
	free(b->edges);
	b->edges = NULL;
	b->n = 0;
}

int ratio_bin_of(const ratio_bins *b, double theta)
{
	int lo = 0, hi = b->n - 1; /* the last bin k with edges[k] <= theta */
	while (lo < hi) {
		int mid = (lo + hi + 1) / 2;
		if (b->edges[mid] <= theta)
			lo = mid;
		else
			hi = mid - 1;
	}
	return lo;
}

/* A bonded contact in compression: its group, bin and stresses. */
typedef struct {
	int group, bin;
	double sn, tau;
} contact;

static void accumulate(ratio_stat *st, const contact *c, size_t nc, int nbins, int pass)
{
	for (size_t k = 0; k < nc; k++) {
		int groups[2] = {RATIO_ALL, c[k].group};
		for (int g = 0; g < 2; g++) {
			ratio_stat *s = &st[groups[g] * nbins + c[k].bin];
			if (pass == 0) {
				s->count++;
				s->sn_mean += c[k].sn;
				s->tau_mean += c[k].tau;
			} else {
				s->sn_std += (c[k].sn - s->sn_mean) * (c[k].sn - s->sn_mean);
				s->tau_std += (c[k].tau - s->tau_mean) * (c[k].tau - s->tau_mean);
			}
		}
	}
}

long ratios_compute(const dem_bonds *b, const dem_snapshot *s, const frame *f,
                    const ratio_bins *bins, ratio_stat *stat)
{
	int nb = bins->n;
	contact *c = xmalloc((b->n ? b->n : 1) * sizeof *c);
	size_t nc = 0;
	for (size_t k = 0; k < b->n; k++) {
		if (s->state[k] != BOND_INTACT && s->state[k] != BOND_DAMAGED)
			continue;
		if (!(s->fn[k] < 0))
			continue;
		double d[3];
		v3_sub(d, s->x + 3 * (size_t)b->j[k], s->x + 3 * (size_t)b->i[k]);
		if (!(b->area[k] > 0) || !(v3_norm(d) > 0)) {
			free(c);
			return err_set("bond %zu (particles %d and %d): %s", k, b->i[k], b->j[k],
			               b->area[k] > 0 ? "the two centres coincide"
			                              : "area is not positive");
		}
		c[nc].group = s->state[k] == BOND_INTACT ? RATIO_INTACT : RATIO_DAMAGED;
		c[nc].bin = ratio_bin_of(bins, frame_theta(f, d));
		c[nc].sn = -s->fn[k] / b->area[k];
		c[nc].tau = v3_norm(s->fs + 3 * k) / b->area[k];
		nc++;
	}
	for (int k = 0; k < RATIO_NGROUPS * nb; k++)
		stat[k] = (ratio_stat){0};
	accumulate(stat, c, nc, nb, 0);
	for (int k = 0; k < RATIO_NGROUPS * nb; k++)
		if (stat[k].count) {
			stat[k].sn_mean /= (double)stat[k].count;
			stat[k].tau_mean /= (double)stat[k].count;
		}
	accumulate(stat, c, nc, nb, 1);
	for (int k = 0; k < RATIO_NGROUPS * nb; k++) {
		ratio_stat *st = &stat[k];
		if (st->count) {
			st->sn_std = sqrt(st->sn_std / (double)st->count);
			st->tau_std = sqrt(st->tau_std / (double)st->count);
		} else {
			st->sn_mean = st->sn_std = st->tau_mean = st->tau_std = NAN;
		}
	}
	free(c);
	return (long)nc;
}
