#include <errno.h>
#include <inttypes.h>
#include <stdio.h>
#include <string.h>
#include <sys/resource.h>
#include <unistd.h>

#include "lib/cfg.h"
#include "lib/err.h"
#include "lib/json.h"
#include "solve/ranks.h"
#include "solve/report.h"

static const char *const phase_names[] = {"neighbour", "bonds", "contacts", "integration",
                                          "output"};
/* ranks.h, RANKS_FORCES ... */
static const char *const exchange_names[RANKS_NX] = {"forces", "halo", "ghosts", "gathers",
                                                     "reductions"};

size_t engine_bytes(const engine *e)
{
	size_t n = e->p.hi - e->p.lo, p0, p1;
	ranks_own(e, &p0, &p1);
	/* Of the particles it holds (window.h) x v w (3 each), r m, orig surf
	 * pslot[2], flag, and its index in the whole specimen with several
	 * ranks; of this rank's own particles x_ref (3) and the sum of the
	 * bond forces on each (6) */
	size_t bytes = n * (9 * sizeof(double) + 2 * sizeof(double) + 4 * sizeof(int32_t) + 1 +
	                    (e->p.glob ? sizeof(int32_t) : 0)) +
	               (p1 - p0) * 9 * sizeof(double);
	const bond_split *S = &e->pairs.split;
	bytes += S->cfirst ? S->cfirst[S->n] * (sizeof(int32_t) + sizeof(bond_part)) : 0;
	/* bonds: record, state, the law's constant where it keeps one, force
	 * (single precision); contacts: record (with the constants), force,
	 * gather index */
	bytes += e->pairs.bonds.cap * (sizeof(pair_rec) + sizeof(uint8_t) +
	                               (e->pairs.bonds.k ? sizeof(double) : 0) + 3 * sizeof(float));
	bytes +=
	    e->pairs.contacts.cap * (sizeof(pair_rec) + 6 * sizeof(double) + 2 * sizeof(int32_t)) +
	    (p1 - p0 + 1) * sizeof(int32_t);
	for (int k = 0; k < 2; k++)
		bytes += e->bc.pl.cap[k] * (2 * sizeof(platen_contact) + sizeof(int32_t));
	return bytes;
}

long report_peak_rss(void)
{
	struct rusage u;
	return getrusage(RUSAGE_SELF, &u) == 0 ? u.ru_maxrss * 1024L : 0;
}

/* Resident size before any input is read: the program and its libraries. */
static long rss_start;

void report_start(void) { rss_start = report_peak_rss(); }

/* The largest time of this rank's shares after the barrier of the step
 * over their mean (bonds.h, share_balance), over the run. */
static double threads_balance(const engine *e)
{
	const share_balance *B = &e->pairs.balance;
	double top = 0, sum = 0;
	int s0 = e->ranks.s0, s1 = e->ranks.s1;
	if (B->n != e->pairs.split.n || s1 <= s0)
		return 1;
	for (int k = s0; k < s1; k++) {
		double t = B->busy_run[k] + B->busy[k];
		top = t > top ? t : top;
		sum += t;
	}
	return sum > 0 ? top * (s1 - s0) / sum : 1;
}

void report_print(const engine *e, int64_t step0, const char *status, const run_opts *o)
{
	double steps = (double)(e->clock.step - step0), wall = e->tm.total[TM_TOTAL];
	double n = (double)e->p.n, nb = (double)e->pairs.nbonds;
	double rate = wall > 0 ? steps * n / wall : 0;
	double ns_bond = steps > 0 && nb > 0 ? 1e9 * e->tm.total[TM_BONDS] / (steps * nb) : 0;
	double ns_bond_cpu = steps > 0 && nb > 0 ? 1e9 * e->tm.cpu[TM_BONDS] / (steps * nb) : 0;
	size_t state = engine_bytes(e);
	long rss = report_peak_rss();
	double pbal[2], bbal[2];
	ranks_balance(e, pbal, bbal);
	if (!o->quiet) {
		fprintf(
		    stderr,
		    "%s: run report: %.0f steps in %.3g s, %.4g particle-steps/s on %d thread%s, "
		    "%.3g ns per bond update, %.0f bytes of state per particle, %" PRId64
		    " neighbour rebuilds\n",
		    err_program_name(), steps, wall, rate, e->team, e->team > 1 ? "s" : "", ns_bond,
		    state / n, e->pairs.rebuilds);
		if (e->ranks.s1 - e->ranks.s0 > 1)
			fprintf(stderr,
			        "  threads: the slowest share of the particles took %.3f times the "
			        "mean after the step's barrier; their ends moved %d times to "
			        "balance them\n",
			        threads_balance(e), e->pairs.balance.resplits);
		if (e->ranks.size > 1) {
			const rank_split *R = &e->ranks;
			fprintf(stderr,
			        "  on %d ranks: particles per rank %.0f at most, %.0f on average "
			        "(%.3f); bonds %.0f, %.0f (%.3f)\n",
			        R->size, pbal[0], pbal[1], pbal[0] / pbal[1], bbal[0], bbal[1],
			        bbal[1] > 0 ? bbal[0] / bbal[1] : 1);
			fprintf(stderr,
			        "  state received per rank and step: halo %.4g bytes at most, "
			        "%.4g on average; ghosts %.4g, %.4g; in all, with the full "
			        "gathers, %.4g, %.4g (every particle every step: %.4g, %.4g)\n",
			        R->traffic_halo[0], R->traffic_halo[1], R->traffic_ghosts[0],
			        R->traffic_ghosts[1], R->traffic_state[0], R->traffic_state[1],
			        R->traffic_allgather[0], R->traffic_allgather[1]);
			fprintf(stderr,
			        "  crossing forces received per rank and step: %.4g bytes at most, "
			        "%.4g on average; per step %.3g reductions of %.4g bytes in all, "
			        "%.3g collective gathers\n",
			        R->traffic_forces[0], R->traffic_forces[1], R->reductions_per_step,
			        R->reduction_bytes_per_step, R->gathers_per_step);
			fprintf(stderr,
			        "  memory per rank: particles held %.0f at most, %.0f on average "
			        "(of %.0f; at any time, setup included, %.0f at most); engine "
			        "state %.4g MB at most, %.4g on average; peak resident %.4g MB, "
			        "%.4g\n",
			        R->held[0], R->held[1], n, R->held_peak[0],
			        1e-6 * R->memory_state[0], 1e-6 * R->memory_state[1],
			        1e-6 * R->memory_rss[0], 1e-6 * R->memory_rss[1]);
			fprintf(stderr, "  exchanges per rank, largest and mean over the ranks "
			                "(waiting for the others included):");
			for (int k = 0; k < RANKS_NX; k++)
				fprintf(stderr, "%s %s %.3g s, %.3g s (%.1f %%)", k ? ";" : "",
				        exchange_names[k], R->seconds[k][0], R->seconds[k][1],
				        wall > 0 ? 100 * R->seconds[k][1] / wall : 0);
			fputc('\n', stderr);
		}
		for (int k = 0; k < TM_TOTAL; k++)
			fprintf(stderr, "  %-12s %9.3f s %6.1f %%\n", phase_names[k],
			        e->tm.total[k], wall > 0 ? 100 * e->tm.total[k] / wall : 0);
		fprintf(stderr, "  (setup before the loop: %.3f s)\n", e->tm.total[TM_SETUP]);
	}
	if (!o->report)
		return;
	cJSON *j = cJSON_CreateObject();
	json_str(j, "status", status);
	json_num(j, "particles", n);
	json_num(j, "bonds", nb);
	json_num(j, "threads", e->team);
	json_num(j, "threads_busy_max_over_mean", threads_balance(e));
	json_num(j, "threads_resplits", e->pairs.balance.resplits);
	json_str(j, "bond_prefetch", e->pairs.prefetch.off ? "off" : "on");
	json_num(j, "ranks", e->ranks.size);
	json_num(j, "rank_particles_max_over_mean", pbal[0] / pbal[1]);
	json_num(j, "rank_bonds_max_over_mean", bbal[1] > 0 ? bbal[0] / bbal[1] : 1);
	/* Bytes of particle state and of crossing forces each rank received per
	 * step (ranks.h). */
	static const char *const traffic[5][2] = {
	    {"halo_bytes_per_step_max", "halo_bytes_per_step_mean"},
	    {"ghost_bytes_per_step_max", "ghost_bytes_per_step_mean"},
	    {"state_bytes_per_step_max", "state_bytes_per_step_mean"},
	    {"allgather_bytes_per_step_max", "allgather_bytes_per_step_mean"},
	    {"force_bytes_per_step_max", "force_bytes_per_step_mean"}};
	const double *tv[5] = {e->ranks.traffic_halo, e->ranks.traffic_ghosts,
	                       e->ranks.traffic_state, e->ranks.traffic_allgather,
	                       e->ranks.traffic_forces};
	for (int k = 0; k < 5; k++)
		for (int m = 0; m < 2; m++)
			json_num(j, traffic[k][m], tv[k][m]);
	json_num(j, "reductions_per_step", e->ranks.reductions_per_step);
	json_num(j, "reduction_bytes_per_step", e->ranks.reduction_bytes_per_step);
	json_num(j, "gathers_per_step", e->ranks.gathers_per_step);
	json_num(j, "rank_particles_held_max", e->ranks.held[0]);
	json_num(j, "rank_particles_held_mean", e->ranks.held[1]);
	json_num(j, "rank_particles_held_peak_max", e->ranks.held_peak[0]);
	json_num(j, "rank_particles_held_peak_mean", e->ranks.held_peak[1]);
	json_num(j, "rank_state_bytes_max", e->ranks.memory_state[0]);
	json_num(j, "rank_state_bytes_mean", e->ranks.memory_state[1]);
	json_num(j, "rank_peak_rss_bytes_max", e->ranks.memory_rss[0]);
	json_num(j, "rank_peak_rss_bytes_mean", e->ranks.memory_rss[1]);
	/* Wall seconds of the run per kind of exchange (ranks.h), the largest
	 * and the mean over the ranks; they overlap the phases. */
	cJSON *xmax = cJSON_AddObjectToObject(j, "exchange_seconds_max");
	cJSON *xmean = cJSON_AddObjectToObject(j, "exchange_seconds_mean");
	for (int k = 0; k < RANKS_NX; k++) {
		json_num(xmax, exchange_names[k], e->ranks.seconds[k][0]);
		json_num(xmean, exchange_names[k], e->ranks.seconds[k][1]);
	}
	json_num(j, "steps", steps);
	json_num(j, "wall", wall);
	json_num(j, "particle_steps_per_second", rate);
	json_num(j, "ns_per_bond", ns_bond);
	json_num(j, "ns_per_bond_cpu", ns_bond_cpu);
	json_num(j, "state_bytes", (double)state);
	json_num(j, "peak_rss_bytes", (double)rss);
	json_num(j, "start_rss_bytes", (double)rss_start);
	json_num(j, "rebuilds", (double)e->pairs.rebuilds);
	json_num(j, "dt", e->clock.dt);
	json_num(j, "setup", e->tm.total[TM_SETUP]);
	cJSON *ph = cJSON_AddObjectToObject(j, "phases");
	for (int k = 0; k < TM_TOTAL; k++)
		json_num(ph, phase_names[k], e->tm.total[k]);
	/* The same in CPU time of the first thread (the whole run's on one
	 * thread): what a shared machine disturbs least. */
	json_num(j, "cpu", e->tm.cpu[TM_TOTAL]);
	cJSON *pc = cJSON_AddObjectToObject(j, "phases_cpu");
	for (int k = 0; k < TM_TOTAL; k++)
		json_num(pc, phase_names[k], e->tm.cpu[k]);
	if (json_write(o->report, j))
		fatal(NULL);
}

int report_replaceable(const char *path)
{
	if (access(path, F_OK) != 0)
		return 1;
	cJSON *j = cfg_load_json(path);
	int ours = cJSON_IsObject(j) && cJSON_IsString(cJSON_GetObjectItem(j, "status")) &&
	           cJSON_GetObjectItem(j, "particles") != NULL;
	cJSON_Delete(j);
	err_clear();
	return ours;
}
