/* bench-cores: what two cores of this machine give over one, measured with
 * fixed kernels that share nothing: one copy alone, then two copies at once
 * (a thread each), in turns; the speed-up is 2 x alone / together. On a
 * shared machine the second core is not always a whole core (two virtual
 * cores may be the two threads of one physical core, for a while or for
 * good; the neighbours share the cache and memory): tools/bench-solve reads
 * its two-thread speed-ups beside these, measured in the same round.
 *
 * With --latency, instead: how long one core waits for a read at a random
 * place of an array of each size, which tells how much of the last-level
 * cache a core of a shared machine has (what a specimen's scattered reads
 * see, beside the cache size the machine reports). */
#include <math.h>
#include <pthread.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "lib/cli.h"
#include "lib/err.h"

static double now(void)
{
	struct timespec t;
	clock_gettime(CLOCK_MONOTONIC, &t);
	return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

typedef double v4 __attribute__((vector_size(32)));

/* Vector arithmetic in registers: eight independent chains of
 * multiply-adds, enough to keep the floating-point units busy. */
static double kernel_compute(long reps)
{
	v4 a[8], m = {0.999999, 0.999999, 0.999999, 0.999999}, c = {1e-9, 1e-9, 1e-9, 1e-9};
	for (int k = 0; k < 8; k++)
		a[k] = (v4){1.0 + k, 2, 3, 4};
	for (long i = 0; i < reps; i++)
		for (int k = 0; k < 8; k++)
			a[k] = a[k] * m + c;
	double s = 0;
	for (int k = 0; k < 8; k++)
		s += a[k][0] + a[k][1] + a[k][2] + a[k][3];
	return s;
}

/* Sweeps over a private array, each value read, updated and written back:
 * held in the core's first-level cache (the load and store units), or
 * larger than the caches (the shared cache and memory, as the bond records
 * of a large specimen each step). */
static double kernel_sweep(double *buf, size_t n, long sweeps)
{
	for (long s = 0; s < sweeps; s++)
		for (size_t i = 0; i < n; i++)
			buf[i] = buf[i] * 0.999999 + 1e-9;
	return buf[n / 2];
}

/* Nanoseconds per read of a chain of dependent reads, each at a random
 * line of an array of bytes bytes: one cycle through every line (Sattolo's
 * shuffle), followed reads times. */
static double chase_ns(size_t bytes, long reads, uint64_t seed)
{
	enum { LINE = 64 / sizeof(size_t) };
	size_t lines = bytes / 64, *a = xmalloc(lines * 64),
	       *order = xmalloc(lines * sizeof *order);
	for (size_t k = 0; k < lines; k++)
		order[k] = k;
	for (size_t k = lines - 1; k > 0; k--) {
		seed ^= seed << 13, seed ^= seed >> 7, seed ^= seed << 17;
		size_t m = (size_t)(seed % k), t = order[k];
		order[k] = order[m], order[m] = t;
	}
	for (size_t k = 0; k < lines; k++)
		a[LINE * order[k]] = LINE * order[(k + 1) % lines];
	size_t p = 0;
	for (size_t k = 0; k < lines; k++) /* once through: the pages touched */
		p = a[p];
	double t0 = now();
	for (long k = 0; k < reads; k++)
		p = a[p];
	double ns = (now() - t0) / (double)reads * 1e9;
	free(a), free(order);
	return p == (size_t)-1 ? 0 : ns; /* p used: the chain is not optimised away */
}

/* The latency line: ns per random read for arrays of 1 to max_mb MB. */
static void latency(double max_mb, long reads)
{
	printf("{\"bench\": \"cores\", \"kernel\": \"latency\", \"ns_per_read\": {");
	for (double mb = 1; mb <= max_mb; mb *= 2)
		printf("%s\"%g\": %.1f", mb > 1 ? ", " : "", mb,
		       chase_ns((size_t)(mb * 1048576), reads, 88172645463325252u));
	printf("}, \"reads\": %ld, \"note\": \"one thread; each read waits for the one before, at "
	       "a random line of an array of that many MB (2^20 bytes)\"}\n",
	       reads);
}

enum { KERNEL_COMPUTE, KERNEL_CACHE, KERNEL_MEMORY, NKERNELS };
static const char *const kernel_name[NKERNELS] = {"compute", "cache", "memory"};

typedef struct {
	int kernel;
	long reps;
	double *buf;
	size_t n;
	pthread_barrier_t *start;
	double seconds, sink;
} job;

static void run_job(job *j)
{
	double t0 = now();
	j->sink = j->kernel == KERNEL_COMPUTE ? kernel_compute(j->reps)
	                                      : kernel_sweep(j->buf, j->n, j->reps);
	j->seconds = now() - t0;
}

static void *thread_main(void *arg)
{
	job *j = arg;
	pthread_barrier_wait(j->start);
	run_job(j);
	return NULL;
}

/* The two jobs at once, each on a thread of its own: the longer time. */
static double together(job j[2])
{
	pthread_barrier_t start;
	pthread_barrier_init(&start, NULL, 2);
	pthread_t th[2];
	for (int k = 0; k < 2; k++) {
		j[k].start = &start;
		if (pthread_create(&th[k], NULL, thread_main, &j[k]) != 0)
			fatal("bench-cores: cannot start a thread");
	}
	for (int k = 0; k < 2; k++)
		pthread_join(th[k], NULL);
	pthread_barrier_destroy(&start);
	return j[0].seconds > j[1].seconds ? j[0].seconds : j[1].seconds;
}

static int cmp_double(const void *a, const void *b)
{
	double x = *(const double *)a, y = *(const double *)b;
	return (x > y) - (x < y);
}

/* Kernel k timed alone and two copies at once, rounds turns of each (about
 * seconds a run), its line printed; buf: each copy's array of n values. */
static void measure(int k, double *const buf[2], size_t n, long rounds, double seconds)
{
	/* The repetitions that take about that long alone. */
	job probe = {.kernel = k, .reps = 1, .buf = buf[0], .n = n};
	for (;;) {
		run_job(&probe);
		if (probe.seconds >= seconds / 8 || probe.reps > (1L << 40))
			break;
		probe.reps *= 2;
	}
	long reps = (long)ceil((double)probe.reps * seconds / probe.seconds);
	double *alone = xmalloc((size_t)rounds * sizeof *alone),
	       *both = xmalloc((size_t)rounds * sizeof *both),
	       *speedup = xmalloc((size_t)rounds * sizeof *speedup);
	for (long r = 0; r < rounds; r++) {
		job one = {.kernel = k, .reps = reps, .buf = buf[0], .n = n};
		job two[2] = {{.kernel = k, .reps = reps, .buf = buf[0], .n = n},
		              {.kernel = k, .reps = reps, .buf = buf[1], .n = n}};
		run_job(&one);
		alone[r] = one.seconds;
		both[r] = together(two);
		speedup[r] = 2 * alone[r] / both[r];
	}
	qsort(alone, (size_t)rounds, sizeof *alone, cmp_double);
	qsort(both, (size_t)rounds, sizeof *both, cmp_double);
	qsort(speedup, (size_t)rounds, sizeof *speedup, cmp_double);
	long mid = (rounds - 1) / 2;
	printf("{\"bench\": \"cores\", \"kernel\": \"%s\", \"bytes\": %zu, \"alone\": %.6g, "
	       "\"together\": %.6g, \"speedup\": %.4g, \"speedup_lowest\": %.4g, "
	       "\"speedup_highest\": %.4g, \"rounds\": %ld}\n",
	       kernel_name[k], k == KERNEL_COMPUTE ? 0 : n * sizeof(double), alone[mid], both[mid],
	       speedup[mid], speedup[0], speedup[rounds - 1], rounds);
	free(alone), free(both), free(speedup);
}

int main(int argc, char **argv)
{
	long rounds = 3, reads = 2000000;
	int lat = 0;
	double seconds = 0.1, megabytes = 16, kilobytes = 24, lat_mb = 128;
	const cli_opt opts[] = {
	    {"rounds", CLI_INT, &rounds, "N", "", "turns of alone and together per kernel", 1, 100},
	    {"seconds", CLI_NUM, &seconds, "S", "s", "about how long one copy of a kernel runs",
	     0.01, 10},
	    {"kilobytes", CLI_NUM, &kilobytes, "K", "kB",
	     "array of each copy of the cache kernel (within the first-level cache)", 1, 1e5},
	    {"megabytes", CLI_NUM, &megabytes, "M", "MB",
	     "array of each copy of the memory kernel (beyond the caches)", 0.1, 4096},
	    {"latency", CLI_FLAG, &lat, NULL, "",
	     "instead of the kernels: ns per random read for arrays of 1, 2, 4, ... MB", 0, 0},
	    {"latency-megabytes", CLI_NUM, &lat_mb, "M", "MB", "largest array of --latency", 1,
	     4096},
	    {"reads", CLI_INT, &reads, "N", "", "reads timed per array of --latency", 1000, 1e9},
	};
	const cli_spec spec = {
	    .usage = "bench-cores [options]",
	    .summary =
	        "Time three fixed kernels, one copy alone and two copies at once (a thread each, "
	        "sharing nothing), in turns: vector multiply-adds in registers (compute), sweeps "
	        "over a small array (cache) and over a large one (memory). Per kernel one JSON "
	        "line: the median seconds and speed-up 2 x alone / together, 2 for two whole "
	        "cores; about 1 for the cache kernel when the two are threads of one core. "
	        "With --latency, one line instead: the ns one core waits per random read of "
	        "arrays of 1, 2, 4, ... MB (where it rises, the core's share of the caches ends).",
	    .opts = opts,
	    .nopts = (int)(sizeof opts / sizeof opts[0])};
	cli_parse(&spec, argc, argv, NULL);
	if (lat) {
		latency(lat_mb, reads);
		return 0;
	}
	size_t n_cache = (size_t)(kilobytes * 1e3 / sizeof(double)),
	       n_memory = (size_t)(megabytes * 1e6 / sizeof(double));
	double *buf[2];
	for (int c = 0; c < 2; c++) {
		buf[c] = xmalloc(n_memory * sizeof(double));
		for (size_t i = 0; i < n_memory; i++)
			buf[c][i] = (double)(i % 1000);
	}
	measure(KERNEL_COMPUTE, buf, 0, rounds, seconds);
	measure(KERNEL_CACHE, buf, n_cache < n_memory ? n_cache : n_memory, rounds, seconds);
	measure(KERNEL_MEMORY, buf, n_memory, rounds, seconds);
	free(buf[0]), free(buf[1]);
	return 0;
}
