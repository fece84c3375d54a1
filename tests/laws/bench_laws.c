/* Throughput of each law's force_batch on bonds in a mix of states (a
 * benchmark: prints figures, asserts nothing; label bench). */
#include "tests/laws/drive.h"

#include "lib/rng.h"
#include "lib/timer.h"

enum { NB = 1 << 16, NSTEP = 200 };

static const char *materials[] = {
    "share/materials/concrete.json",
    "share/materials/concrete-jcfpm.json",
    "share/materials/concrete-exponential.json",
};

int main(void)
{
	static law_pair pair[NB];
	static bond b[NB];
	static law_batch B[NB / LAW_LANES];
	for (size_t m = 0; m < sizeof materials / sizeof materials[0]; m++) {
		cfg *c = cfg_load(materials[m]);
		material mat;
		if (!c || material_parse(c, &mat)) {
			fprintf(stderr, "%s\n", err_msg());
			return 1;
		}
		cfg_free(c);
		const law *L = mat.law;
		const law_params *p = mat.params;
		double rho = mat.density;
		rng g;
		rng_seed(&g, 1);
		for (int q = 0; q < NB; q++) {
			pair[q].ri = rng_range(&g, 0.5e-3, 1e-3);
			pair[q].rj = rng_range(&g, 0.5e-3, 1e-3);
			pair[q].d0 = (pair[q].ri + pair[q].rj) * rng_range(&g, 0.98, 1.05);
			pair[q].mi = rho * 4.2 * pair[q].ri * pair[q].ri * pair[q].ri;
			pair[q].mj = rho * 4.2 * pair[q].rj * pair[q].rj * pair[q].rj;
			b[q] = drive_bond(L, p, &pair[q]);
			law_batch *l = &B[q / LAW_LANES];
			int k = q % LAW_LANES;
			l->n = LAW_LANES;
			l->ri[k] = pair[q].ri;
			l->rj[k] = pair[q].rj;
			l->mi[k] = pair[q].mi;
			l->mj[k] = pair[q].mj;
			l->d0[k] = pair[q].d0;
			for (int c = 0; c < 3; c++)
				l->t[c][k] = b[q].t[c];
			for (int c = 0; c < LAW_NHIST; c++)
				l->h[c][k] = b[q].h[c];
			l->k[k] = b[q].k;
			l->state[k] = b[q].state;
		}
		double t0 = timer_now(), work = 0;
		for (int s = 0; s < NSTEP; s++) {
			for (int q = 0; q < NB; q++) {
				law_batch *l = &B[q / LAW_LANES];
				int k = q % LAW_LANES;
				l->un[k] = pair[q].d0 * 2e-5 * (q % 97 - 60) * s / NSTEP;
				l->vn[k] = 1e-4;
				l->dus[0][k] = pair[q].d0 * 1e-6 * (q % 13 - 6);
				l->dus[1][k] = l->dus[2][k] = 0;
			}
			double t1 = timer_now();
			for (int k = 0; k < NB / LAW_LANES; k++)
				L->force_batch(p, &B[k]);
			work += timer_now() - t1;
		}
		int st[4] = {0};
		for (int q = 0; q < NB; q++)
			st[B[q / LAW_LANES].state[q % LAW_LANES]]++;
		printf("{\"bench\": \"laws\", \"figure\": \"ns_per_bond\", \"law\": \"%s\", "
		       "\"value\": %.1f, \"intact\": %d, \"damaged\": %d, \"broken_tension\": %d, "
		       "\"broken_shear\": %d, \"wall\": %.2f}\n",
		       L->name, work / ((double)NB * NSTEP) * 1e9, st[0], st[1], st[2], st[3],
		       timer_now() - t0);
		material_free(&mat);
	}
	return 0;
}
