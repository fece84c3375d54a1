/* The run's phase timers, in the spirit of CoMD's performanceTimers: each
 * phase is timed by a start and a stop around it, and the run report gives
 * the time of each. */
#ifndef DEM_TIMERS_H
#define DEM_TIMERS_H

#include "lib/timer.h"

/* The phases of the run loop, its total, and the setup before it (bonds
 * formed, lists built, run file created), not counted in the loop's rate. */
enum { TM_NEIGHBOUR, TM_BONDS, TM_CONTACTS, TM_INTEGRATE, TM_OUTPUT, TM_TOTAL, TM_SETUP, TM_N };

typedef struct {
	double total[TM_N]; /* s, accumulated */
	double start[TM_N]; /* s, of the phase running */
	double cpu[TM_N];   /* s, CPU time of the timing thread, accumulated */
	double cpu_start[TM_N];
} phase_timers;

static inline void phase_start(phase_timers *t, int k)
{
	t->start[k] = timer_now();
	t->cpu_start[k] = timer_thread_cpu();
}

static inline void phase_stop(phase_timers *t, int k)
{
	t->total[k] += timer_now() - t->start[k];
	t->cpu[k] += timer_thread_cpu() - t->cpu_start[k];
}

#endif
