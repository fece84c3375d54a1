#include <errno.h>
#include <inttypes.h>
#include <stdio.h>
#include <string.h>
#include <sys/resource.h>

#include "lib/err.h"
#include "solve/report.h"

static const char *const phase_names[] = {"neighbour", "bonds", "contacts", "integration",
                                          "output"};

size_t engine_bytes(const engine *e)
{
	size_t n = e->p.n;
	/* x v w x_ref (3 each), r m inv_m inv_i omega2, orig surf pslot[2], flag */
	size_t bytes = n * (12 * sizeof(double) + 5 * sizeof(double) + 4 * sizeof(int32_t) + 1);
	const pairlist *l[2] = {&e->pairs.bonds, &e->pairs.contacts};
	for (int k = 0; k < 2; k++)
		bytes += l[k]->cap * (sizeof(bond) + 6 * sizeof(double) + 2 * sizeof(int32_t) +
		                      (l[k]->k ? 3 * sizeof(double) : 0)) +
		         (n + 1) * sizeof(int32_t);
	for (int k = 0; k < 2; k++)
		bytes += e->bc.pl.cap[k] * (2 * sizeof(platen_contact) + sizeof(int32_t));
	return bytes;
}

static long peak_rss(void)
{
	struct rusage u;
	return getrusage(RUSAGE_SELF, &u) == 0 ? u.ru_maxrss * 1024L : 0;
}

/* Resident size before any input is read: the program and its libraries. */
static long rss_start;

void report_start(void) { rss_start = peak_rss(); }

void report_print(const engine *e, int64_t step0, const char *status, const run_opts *o)
{
	double steps = (double)(e->clock.step - step0), wall = e->tm.total[TM_TOTAL];
	double n = (double)e->p.n, nb = (double)e->pairs.bonds.n;
	double rate = wall > 0 ? steps * n / wall : 0;
	double ns_bond = steps > 0 && nb > 0 ? 1e9 * e->tm.total[TM_BONDS] / (steps * nb) : 0;
	size_t state = engine_bytes(e);
	long rss = peak_rss();
	if (!o->quiet) {
		fprintf(
		    stderr,
		    "%s: run report: %.0f steps in %.3g s, %.4g particle-steps/s on %d thread%s, "
		    "%.3g ns per bond update, %.0f bytes of state per particle, %" PRId64
		    " neighbour rebuilds\n",
		    err_program_name(), steps, wall, rate, e->team, e->team > 1 ? "s" : "", ns_bond,
		    state / n, e->pairs.rebuilds);
		for (int k = 0; k < TM_TOTAL; k++)
			fprintf(stderr, "  %-12s %9.3f s %6.1f %%\n", phase_names[k],
			        e->tm.total[k], wall > 0 ? 100 * e->tm.total[k] / wall : 0);
		fprintf(stderr, "  (setup before the loop: %.3f s)\n", e->tm.total[TM_SETUP]);
	}
	if (!o->report)
		return;
	FILE *f = fopen(o->report, "w");
	if (!f)
		fatal("%s: cannot create: %s", o->report, strerror(errno));
	fputs("{\"status\": \"", f);
	for (const char *c = status; *c; c++) {
		if (*c == '"' || *c == '\\')
			fputc('\\', f);
		fputc(*c, f);
	}
	fprintf(f,
	        "\", \"particles\": %zu, \"bonds\": %zu, \"threads\": %d, "
	        "\"steps\": %.0f, \"wall\": %.6g, \"particle_steps_per_s\": %.6g, "
	        "\"ns_per_bond\": %.6g, \"state_bytes\": %zu, \"peak_rss_bytes\": %ld, "
	        "\"start_rss_bytes\": %ld, "
	        "\"rebuilds\": %" PRId64 ", \"dt\": %.6g, \"setup\": %.6g, \"phases\": {",
	        e->p.n, e->pairs.bonds.n, e->team, steps, wall, rate, ns_bond, state, rss,
	        rss_start, e->pairs.rebuilds, e->clock.dt, e->tm.total[TM_SETUP]);
	for (int k = 0; k < TM_TOTAL; k++)
		fprintf(f, "%s\"%s\": %.6g", k ? ", " : "", phase_names[k], e->tm.total[k]);
	fprintf(f, "}}\n");
	if (fclose(f))
		fatal("%s: cannot write", o->report);
}
