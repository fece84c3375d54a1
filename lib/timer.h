/* Wall-clock timing and per-phase timers for run reports (in the spirit of
 * CoMD's performanceTimers). */
#ifndef DEM_TIMER_H
#define DEM_TIMER_H

/* Seconds since an arbitrary origin, monotonic. */
double timer_now(void);

#endif
