#include <inttypes.h>
#include <math.h>
#include <stdio.h>

#include "solve/diagnose.h"

static int finite6(const double *f)
{
	return isfinite(f[0] + f[1] + f[2] + f[3] + f[4] + f[5]);
}

/* The first pair of list L at particle i with a non-finite force, or -1. */
static int64_t bad_pair(const pairlist *L, size_t i)
{
	for (int32_t q = L->off[i]; q < L->off[i + 1]; q++)
		if (!finite6(L->f + 6 * (L->ref[q] >> 1)))
			return L->ref[q] >> 1;
	return -1;
}

void diagnose_nan(const engine *e, size_t i, char *msg, size_t n)
{
	const particles *P = &e->p;
	int len = snprintf(msg, n,
	                   "stopped: non-finite state at step %" PRId64 " (t = %g s): particle %d "
	                   "(radius %g m)",
	                   e->step - 1, e->t - e->dt, P->orig[i], P->r[i]);
	int64_t b = bad_pair(&e->bonds, i);
	const pairlist *L = &e->bonds;
	const char *what = "bond";
	if (b < 0) {
		b = bad_pair(&e->contacts, i);
		L = &e->contacts;
		what = "contact";
	}
	if (len < 0 || (size_t)len >= n)
		return;
	if (b >= 0)
		snprintf(msg + len, n - (size_t)len,
		         ": the force of %s %d-%d (law %s) is not finite", what,
		         P->orig[L->rec[b].i], P->orig[L->rec[b].j],
		         L == &e->bonds ? e->law->name : "contact");
	else
		snprintf(msg + len, n - (size_t)len,
		         ": its forces are finite, so its motion diverged (time step too large?)");
}

/* Bound on ω of particle i times the time step (2 is the stability limit). */
static double omega_dt(const engine *e, size_t i)
{
	return sqrt(e->p.omega2[i]) * e->dt;
}

int diagnose_runaway(const engine *e, char *msg, size_t n)
{
	double input = e->e_initial + fabs(e->e_work);
	if (!(e->ke > 2 * input + 1e-300))
		return 0;
	const particles *P = &e->p;
	size_t worst = 0;
	double top = -1;
	for (size_t i = 0; i < P->n; i++) {
		const double *v = P->v + 3 * i;
		double k = P->m[i] * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
		if (k > top) {
			top = k;
			worst = i;
		}
	}
	snprintf(msg, n,
	         "stopped: kinetic energy %g J exceeds twice the energy put in (%g J) at step "
	         "%" PRId64 ": the integration is unstable; fastest particle %d (speed %g m/s, "
	         "bonds give omega dt = %.3g, stable below 2)",
	         e->ke, input, e->step - 1, P->orig[worst], sqrt(top / P->m[worst]),
	         omega_dt(e, worst));
	return 1;
}

int diagnose_timestep(const engine *e, char *msg, size_t n)
{
	size_t worst;
	double crit = timestep_critical(e, 1, &worst);
	if (e->dt <= crit)
		return 0;
	const particles *P = &e->p;
	snprintf(msg, n,
	         "stopped: time step %g s above the stable limit %g s at step %" PRId64
	         ": particle %d has %d bonds and %d contacts (lower time_step.safety)",
	         e->dt, crit, e->step, P->orig[worst],
	         e->bonds.off[worst + 1] - e->bonds.off[worst],
	         e->contacts.off[worst + 1] - e->contacts.off[worst]);
	return 1;
}
