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
	int between; /* 1 + the phase that runs between steps (the run loop's
	                output), or 0 */
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

/* phase_stop(from) and phase_start(to) at once, reading each clock once:
 * the thread's CPU clock costs a system call (1.2 µs on a virtual machine,
 * against 25 ns for the wall clock), and a step crosses eight phase
 * boundaries. */
static inline void phase_switch(phase_timers *t, int from, int to)
{
	double now = timer_now(), cpu = timer_thread_cpu();
	t->total[from] += now - t->start[from];
	t->cpu[from] += cpu - t->cpu_start[from];
	t->start[to] = now;
	t->cpu_start[to] = cpu;
}

/* seconds of phase from, timed inside it, counted in phase to (wall and
 * CPU alike: what the timing thread spent on to's work within from). */
static inline void phase_move(phase_timers *t, int from, int to, double seconds)
{
	t->total[from] -= seconds;
	t->cpu[from] -= seconds;
	t->total[to] += seconds;
	t->cpu[to] += seconds;
}

/* The first phase of a step starts, and the last ends: from and to the
 * phase between steps, if one runs, reading the clocks once. */
static inline void phase_enter(phase_timers *t, int k)
{
	if (t->between)
		phase_switch(t, t->between - 1, k);
	else
		phase_start(t, k);
}

static inline void phase_leave(phase_timers *t, int k)
{
	if (t->between)
		phase_switch(t, k, t->between - 1);
	else
		phase_stop(t, k);
}

#endif
