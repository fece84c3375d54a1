#define _GNU_SOURCE /* syscall (getdents64), for a signal handler */
#include <errno.h>
#include <fcntl.h>
#include <libgen.h>
#include <pthread.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <unistd.h>

#include "lib/afile.h"
#include "lib/err.h"

/* Pending temporaries, kept in static storage so the signal handler can use
 * them without allocating. Threads may write files at once (post vtk): a
 * slot is taken and given back under the lock. Each holds the temporary
 * open with an exclusive flock (or -1 where the file system has none), its
 * claim on the name: a second program writing the same output is refused
 * instead of truncating or removing the first one's temporary. */
enum { MAX_PENDING = 64, NAME_MAX_LEN = 4096 };
static char pending[MAX_PENDING][NAME_MAX_LEN];
static volatile sig_atomic_t pending_used[MAX_PENDING];
static int pending_fd[MAX_PENDING];
static pthread_mutex_t pending_lock = PTHREAD_MUTEX_INITIALIZER;

const int afile_signals[AFILE_NSIGNALS] = {SIGINT, SIGTERM, SIGHUP, SIGUSR1, SIGUSR2, SIGXCPU};

/* A staging directory (afile_stage_dir), removed with the files in it:
 * with system calls only, which a signal handler may make. */
static char stage_dir[NAME_MAX_LEN];
static volatile sig_atomic_t stage_used;

static void remove_stage(void)
{
	if (!stage_used)
		return;
	stage_used = 0;
	int fd = open(stage_dir, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
	if (fd < 0)
		return;
	static char buf[8192]; /* struct linux_dirent64 records */
	for (long n; (n = syscall(SYS_getdents64, fd, buf, sizeof buf)) > 0;)
		for (long at = 0; at < n;) {
			const char *rec = buf + at;
			unsigned short len;
			memcpy(&len, rec + 16, sizeof len); /* after d_ino, d_off */
			const char *name = rec + 19;        /* after d_reclen, d_type */
			if (strcmp(name, ".") && strcmp(name, ".."))
				unlinkat(fd, name, 0);
			at += len;
		}
	close(fd);
	rmdir(stage_dir);
}

static void remove_pending(void)
{
	for (int k = 0; k < MAX_PENDING; k++)
		if (pending_used[k]) {
			unlink(pending[k]);
			pending_used[k] = 0;
		}
	remove_stage();
}

int afile_stage_dir(const char *dir)
{
	stage_used = 0;
	if (!dir)
		return 0;
	if (strlen(dir) >= sizeof stage_dir)
		return err_set("%s: path too long", dir);
	snprintf(stage_dir, sizeof stage_dir, "%s", dir);
	stage_used = 1;
	return 0;
}

static void on_signal(int sig)
{
	remove_pending();
	signal(sig, SIG_DFL);
	raise(sig);
}

void afile_install_signal_cleanup(void)
{
	static int installed;
	if (installed)
		return;
	installed = 1;
	atexit(remove_pending);
	for (int k = 0; k < AFILE_NSIGNALS; k++)
		signal(afile_signals[k], on_signal);
}

/* The claim on tmp: the file opened (made if missing, never truncated)
 * and locked, or -1 when it cannot be opened or locked here (its writer
 * then says why it cannot write it). -2 when another open file holds it.
 * A lock taken on a file that its holder renamed or removed meanwhile is
 * on another file than tmp now: taken again. */
static int claim(const char *tmp)
{
	for (int tries = 0; tries < 100; tries++) {
		int fd = open(tmp, O_RDWR | O_CREAT | O_CLOEXEC, 0666);
		if (fd < 0)
			return -1;
		if (flock(fd, LOCK_EX | LOCK_NB) != 0) {
			int busy = errno == EWOULDBLOCK;
			close(fd);
			return busy ? -2 : -1;
		}
		struct stat held, named;
		if (fstat(fd, &held) == 0 && stat(tmp, &named) == 0 &&
		    held.st_dev == named.st_dev && held.st_ino == named.st_ino)
			return fd;
		close(fd);
	}
	return -1;
}

static int held_error(const char *final, const char *tmp)
{
	return err_set("%s: another program is writing it now (%s is in use): wait for it to "
	               "end, or give another output name",
	               final, tmp);
}

int afile_check_free(const char *final)
{
	char tmp[NAME_MAX_LEN];
	snprintf(tmp, sizeof tmp, "%s.tmp", final);
	return afile_held(final) ? held_error(final, tmp) : 0;
}

int afile_held(const char *final)
{
	char tmp[NAME_MAX_LEN];
	if (snprintf(tmp, sizeof tmp, "%s.tmp", final) >= (int)sizeof tmp)
		return 0;
	int fd = open(tmp, O_RDONLY | O_CLOEXEC);
	if (fd < 0)
		return 0;
	int held = flock(fd, LOCK_SH | LOCK_NB) != 0 && errno == EWOULDBLOCK;
	close(fd);
	return held;
}

static int begin(const char *final, char *tmp, size_t n, int hold)
{
	int len = snprintf(tmp, n, "%s.tmp", final);
	if (len < 0 || (size_t)len >= n || (size_t)len >= NAME_MAX_LEN)
		return err_set("%s: output file name too long", final);
	int fd = claim(tmp);
	if (fd == -2)
		return held_error(final, tmp);
	if (fd >= 0 && !hold) {
		close(fd);
		fd = -1;
	}
	int rc = -1;
	pthread_mutex_lock(&pending_lock);
	for (int k = 0; k < MAX_PENDING && rc; k++)
		if (!pending_used[k]) {
			memcpy(pending[k], tmp, (size_t)len + 1);
			pending_fd[k] = fd;
			pending_used[k] = 1;
			rc = 0;
		}
	pthread_mutex_unlock(&pending_lock);
	if (rc && fd >= 0)
		close(fd);
	return rc ? err_set("%s: too many output files open at once", final) : 0;
}

int afile_begin(const char *final, char *tmp, size_t n) { return begin(final, tmp, n, 1); }

int afile_begin_shared(const char *final, char *tmp, size_t n) { return begin(final, tmp, n, 0); }

/* tmp no longer pending, and its claim given up (after its rename or
 * removal, so that no other program takes the name before). */
static void unregister(const char *tmp)
{
	pthread_mutex_lock(&pending_lock);
	for (int k = 0; k < MAX_PENDING; k++)
		if (pending_used[k] && strcmp(pending[k], tmp) == 0) {
			if (pending_fd[k] >= 0)
				close(pending_fd[k]);
			pending_used[k] = 0;
		}
	pthread_mutex_unlock(&pending_lock);
}

static int fsync_path(const char *path, int flags)
{
	int fd = open(path, flags);
	if (fd < 0)
		return -1;
	int rc = fsync(fd);
	close(fd);
	return rc;
}

int afile_commit(const char *tmp, const char *final)
{
	if (fsync_path(tmp, O_RDONLY) != 0)
		return err_set("%s: cannot sync: %s", tmp, strerror(errno));
	if (rename(tmp, final) != 0)
		return err_set("%s: cannot rename to %s: %s", tmp, final, strerror(errno));
	unregister(tmp);
	char dir[NAME_MAX_LEN];
	snprintf(dir, sizeof dir, "%s", final);
	afile_sync_dir(dirname(dir));
	return 0;
}

void afile_sync_dir(const char *dir) { fsync_path(dir, O_RDONLY | O_DIRECTORY); }

void afile_discard(const char *tmp)
{
	unlink(tmp);
	unregister(tmp);
}
