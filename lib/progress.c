#include <stdio.h>
#include <unistd.h>

#include "lib/progress.h"
#include "lib/timer.h"

static int forced = -1;
static double log_every = 30;

void progress_force(int on) { forced = on; }

void progress_log_every(double s) { log_every = s; }

void progress_start(progress *p, const char *what, double total)
{
	p->what = what;
	p->total = total;
	p->t_start = p->t_last = timer_now();
	p->active = forced >= 0 ? forced : isatty(STDERR_FILENO);
	p->log = !p->active && forced != 0 && log_every > 0;
}

static void format_duration(char *buf, size_t n, double s)
{
	if (s < 0 || s > 1e7)
		snprintf(buf, n, "--");
	else if (s < 60)
		snprintf(buf, n, "%.0fs", s);
	else if (s < 3600)
		snprintf(buf, n, "%dm%02ds", (int)(s / 60), (int)s % 60);
	else
		snprintf(buf, n, "%dh%02dm", (int)(s / 3600), (int)(s / 60) % 60);
}

void progress_update(progress *p, double done, const char *detail)
{
	double now = timer_now();
	if (!(p->active && now - p->t_last >= 0.2) && !(p->log && now - p->t_last >= log_every))
		return;
	p->t_last = now;
	double rate = done / (now - p->t_start > 0 ? now - p->t_start : 1e-9);
	char eta[32] = "--", elapsed[32];
	if (p->total > 0 && rate > 0)
		format_duration(eta, sizeof eta, (p->total - done) / rate);
	format_duration(elapsed, sizeof elapsed, now - p->t_start);
	const char *start = p->active ? "\r\033[K" : "", *end = p->active ? "" : "\n";
	if (p->total > 0)
		fprintf(stderr, "%s%.0f/%.0f %s (%.0f%%)  %.3g %s/s  %s elapsed, ETA %s  %s%s",
		        start, done, p->total, p->what, 100.0 * done / p->total, rate, p->what,
		        elapsed, eta, detail ? detail : "", end);
	else
		fprintf(stderr, "%s%.0f %s  %.3g %s/s  %s elapsed  %s%s", start, done, p->what,
		        rate, p->what, elapsed, detail ? detail : "", end);
	fflush(stderr);
}

void progress_end(progress *p)
{
	if (p->active)
		fprintf(stderr, "\r\033[K");
	p->active = 0;
}
