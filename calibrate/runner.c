#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include "calibrate/runner.h"
#include "lib/afile.h"
#include "lib/err.h"
#include "lib/timer.h"

static volatile sig_atomic_t stop_signal;

static void on_signal(int sig) { stop_signal = sig; }

void runner_install_signals(void)
{
	struct sigaction sa;
	memset(&sa, 0, sizeof sa);
	sa.sa_handler = on_signal;
	sigemptyset(&sa.sa_mask);
	/* No SA_RESTART: a signal interrupts the wait for the children. */
	for (int k = 0; k < AFILE_NSIGNALS; k++)
		sigaction(afile_signals[k], &sa, NULL);
}

int runner_stopped(void) { return stop_signal != 0; }

void job_cmd(job *j, const char *program)
{
	if (j->ncmd >= JOB_MAX_CMDS)
		fatal("internal error: more than %d commands in a job", JOB_MAX_CMDS);
	j->ncmd++;
	job_arg(j, "%s", program);
}

void job_arg(job *j, const char *fmt, ...)
{
	int c = j->ncmd - 1, a = 0;
	while (j->argv[c][a])
		a++;
	if (a + 1 >= JOB_MAX_ARGS)
		fatal("internal error: more than %d arguments in a command", JOB_MAX_ARGS - 1);
	char buf[4600];
	va_list ap;
	va_start(ap, fmt);
	vsnprintf(buf, sizeof buf, fmt, ap);
	va_end(ap);
	j->arg_text[c][a] = xstrdup(buf);
	j->argv[c][a] = j->arg_text[c][a];
}

void job_free(job *j)
{
	for (int c = 0; c < JOB_MAX_CMDS; c++)
		for (int a = 0; a < JOB_MAX_ARGS; a++)
			free(j->arg_text[c][a]);
	free(j->log);
	memset(j, 0, sizeof *j);
}

/* Start the job's command j->next; 0, or -1 when it cannot start. The
 * command dies with calibrate (SIGKILL, even when calibrate itself is
 * killed outright): a run left going would otherwise write the files of
 * the same run that calibrate started again resumes. */
static int launch(job *j)
{
	pid_t parent = getpid(), pid = fork();
	if (pid < 0) {
		snprintf(j->message, sizeof j->message, "cannot start %s: %s", j->argv[j->next][0],
		         strerror(errno));
		return -1;
	}
	if (pid == 0) {
		if (prctl(PR_SET_PDEATHSIG, SIGKILL) || getppid() != parent)
			_exit(128 + SIGKILL);
		int fd = open(j->log, O_WRONLY | O_CREAT | O_APPEND, 0644);
		int null = open("/dev/null", O_RDONLY);
		if (fd < 0 || null < 0)
			_exit(127);
		dup2(null, 0);
		dup2(fd, 1);
		dup2(fd, 2);
		execv(j->argv[j->next][0], (char *const *)j->argv[j->next]);
		dprintf(2, "cannot run %s: %s\n", j->argv[j->next][0], strerror(errno));
		_exit(127);
	}
	j->pid = pid;
	return 0;
}

/* The last non-empty line of the job's log. */
static void last_line(job *j)
{
	FILE *f = fopen(j->log, "r");
	char line[512];
	if (!f)
		return;
	while (fgets(line, sizeof line, f)) {
		line[strcspn(line, "\r\n")] = '\0';
		if (line[0])
			snprintf(j->message, sizeof j->message, "%s", line);
	}
	fclose(f);
}

int runner_run(job *jobs, int n, int parallel, void (*done)(job *, int, void *), void *data)
{
	int running = 0, next = 0, forwarded = 0;
	for (int k = 0; k < n; k++)
		jobs[k].result = JOB_STOPPED, jobs[k].pid = 0;
	while (next < n || running) {
		while (!stop_signal && running < parallel && next < n) {
			job *j = &jobs[next++];
			j->next = 0;
			j->t0 = timer_now();
			j->message[0] = '\0';
			unlink(j->log);
			if (launch(j)) {
				j->result = JOB_FAILED;
				j->failed_cmd = 0;
				j->exit_code = 127;
				done(j, (int)(j - jobs), data);
			} else {
				running++;
			}
		}
		if (!running)
			break;
		int st;
		pid_t pid = waitpid(-1, &st, 0);
		if (pid < 0) {
			if (errno != EINTR)
				fatal("waiting for the runs: %s", strerror(errno));
			if (stop_signal && !forwarded) {
				for (int k = 0; k < next; k++)
					if (jobs[k].pid > 0)
						kill(jobs[k].pid, SIGTERM);
				forwarded = 1;
			}
			continue;
		}
		job *j = NULL;
		for (int k = 0; k < next && !j; k++)
			if (jobs[k].pid == pid)
				j = &jobs[k];
		if (!j)
			continue;
		j->pid = 0;
		int code = WIFEXITED(st) ? WEXITSTATUS(st) : 128 + WTERMSIG(st);
		if (code == 0 && j->next + 1 < j->ncmd && !stop_signal) {
			j->next++;
			if (launch(j) == 0)
				continue;
			code = 127;
		}
		running--;
		j->wall = timer_now() - j->t0;
		j->exit_code = code;
		j->failed_cmd = j->next;
		if (code == 0 && j->next + 1 == j->ncmd)
			j->result = JOB_OK;
		else if (stop_signal)
			j->result = JOB_STOPPED;
		else
			j->result = JOB_FAILED;
		if (j->result == JOB_FAILED && !j->message[0])
			last_line(j);
		done(j, (int)(j - jobs), data);
	}
	return stop_signal ? -1 : 0;
}
