/* Wall-clock timing and per-phase timers for run reports (in the spirit of
 * CoMD's performanceTimers). */
#ifndef DEM_TIMER_H
#define DEM_TIMER_H

/* Seconds since an arbitrary origin, monotonic. */
double timer_now(void);
/* Seconds of CPU time used by the calling thread: unlike the wall clock it
 * does not count the time the thread waits for a core, so it measures a
 * one-thread run on a machine shared with other work. */
double timer_thread_cpu(void);

#endif
