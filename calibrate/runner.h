/* Independent runs side by side: each job is a short sequence of commands
 * (pack; or solve then post summary) run as child processes, their output
 * in the job's log file, at most `parallel` jobs at a time. The results of
 * a job depend only on its commands, never on the schedule.
 *
 * Ctrl-C, a closed terminal and the signals a batch scheduler sends
 * (lib/afile.h) stop the calibration: the running commands are asked to
 * stop (solve checkpoints and exits), and runner_run reports it. */
#ifndef DEM_CALIBRATE_RUNNER_H
#define DEM_CALIBRATE_RUNNER_H

#include <sys/types.h>

enum { JOB_MAX_CMDS = 3, JOB_MAX_ARGS = 24 };

typedef enum { JOB_OK, JOB_FAILED, JOB_STOPPED } job_result;

typedef struct {
	const char *argv[JOB_MAX_CMDS][JOB_MAX_ARGS]; /* NULL-terminated */
	char *arg_text[JOB_MAX_CMDS][JOB_MAX_ARGS];   /* owned copies (job_arg) */
	int ncmd;
	char *log; /* standard output and error of every command */
	/* Results. */
	job_result result;
	int failed_cmd;    /* which command failed */
	int exit_code;     /* its exit status, or 128 + signal */
	char message[512]; /* the last line of its output */
	double wall;       /* s */
	/* Internal. */
	int next;
	pid_t pid;
	double t0;
} job;

/* Start a new command of the job; then add its arguments (copied). */
void job_cmd(job *j, const char *program);
void job_arg(job *j, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
void job_free(job *j);

/* Install the handlers of the stopping signals (once, at start). */
void runner_install_signals(void);
/* Whether a signal asked the calibration to stop. */
int runner_stopped(void);

/* Run the jobs, at most `parallel` at a time, in order of index; done(j, k)
 * is called as each ends (in the order they end). Returns 0, or -1 when
 * a signal stopped the work (the jobs not done have result JOB_STOPPED). */
int runner_run(job *jobs, int n, int parallel, void (*done)(job *, int, void *), void *data);

#endif
