// SPDX-License-Identifier: LGPL-2.1-or-later
/*
 * Finding or starting the broker of a shared simulated bus (simbus.h).
 *
 * Every user takes BUS.lock (flock) before it connects, and a broker
 * takes it before it decides to leave, so a broker never unlinks its
 * socket under a user that is about to connect, and two first users
 * start one broker.  A socket nobody listens on is a crashed broker's:
 * it is unlinked and a new broker started.
 *
 * The broker is this process forked twice (so it is nobody's child to
 * reap) in a session of its own, with /dev/null for stdio and no other
 * descriptor of the process that started it.
 */
#define _GNU_SOURCE
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <sys/file.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <sys/wait.h>

#include "simbus.h"

#define SIMBUS_DIR	"mcp2510-sim"
#define BROKER_LISTEN_FD	3

/* The directory of the sockets, created 0700; it must be ours alone. */
static int simbus_dir(char *dir, size_t len)
{
	const char *run = getenv("XDG_RUNTIME_DIR");
	struct stat st;
	int n;

	if (run && *run)
		n = snprintf(dir, len, "%s/" SIMBUS_DIR, run);
	else
		n = snprintf(dir, len, "/tmp/" SIMBUS_DIR "-%u",
			     (unsigned int)getuid());
	if (n < 0 || (size_t)n >= len)
		return -ENAMETOOLONG;
	if (mkdir(dir, 0700) && errno != EEXIST)
		return -errno;
	if (lstat(dir, &st))
		return -errno;
	if (!S_ISDIR(st.st_mode) || st.st_uid != getuid() ||
	    (st.st_mode & 077))
		return -EACCES;
	return 0;
}

static int socket_addr(struct sockaddr_un *sa, const char *dir, const char *bus)
{
	int n;

	memset(sa, 0, sizeof(*sa));
	sa->sun_family = AF_UNIX;
	n = snprintf(sa->sun_path, sizeof(sa->sun_path), "%s/%s", dir, bus);
	return n < 0 || (size_t)n >= sizeof(sa->sun_path) ? -ENAMETOOLONG : 0;
}

int simbus_lock(const char *sock_path)
{
	char path[sizeof(((struct sockaddr_un *)NULL)->sun_path) + 8];
	int fd;

	snprintf(path, sizeof(path), "%s.lock", sock_path);
	fd = open(path, O_RDWR | O_CREAT | O_CLOEXEC, 0600);
	if (fd < 0)
		return -errno;
	if (flock(fd, LOCK_EX)) {
		close(fd);
		return -errno;
	}
	return fd;
}

static int seqpacket(void)
{
	int fd = socket(AF_UNIX, SOCK_SEQPACKET | SOCK_CLOEXEC, 0);

	return fd < 0 ? -errno : fd;
}

/* The broker's end, run in the grandchild. */
static _Noreturn void broker_exec(int listen_fd, const char *path)
{
	int null = open("/dev/null", O_RDWR);
	sigset_t none;

	if (null < 0 || dup2(null, 0) < 0 || dup2(null, 1) < 0 ||
	    dup2(null, 2) < 0 || dup2(listen_fd, BROKER_LISTEN_FD) < 0)
		_exit(1);
	/* the starter's lock too: the broker takes its own */
	closefrom(BROKER_LISTEN_FD + 1);
	setsid();
	/* the starter may block or catch signals (mcp2510d's signalfd) */
	sigemptyset(&none);
	sigprocmask(SIG_SETMASK, &none, NULL);
	signal(SIGTERM, SIG_DFL);
	signal(SIGINT, SIG_DFL);
	signal(SIGPIPE, SIG_IGN);
	simbus_broker_run(BROKER_LISTEN_FD, path);
}

/* Bind @sa afresh and fork the broker onto it. */
static int start_broker(const struct sockaddr_un *sa)
{
	int fd = seqpacket(), ret;
	pid_t pid;

	if (fd < 0)
		return fd;
	unlink(sa->sun_path);
	if (bind(fd, (const struct sockaddr *)sa, sizeof(*sa)) ||
	    listen(fd, SOMAXCONN)) {
		ret = -errno;
		goto out;
	}
	pid = fork();
	if (pid < 0) {
		ret = -errno;
		unlink(sa->sun_path);
		goto out;
	}
	if (!pid) {
		if (fork())
			_exit(0);
		broker_exec(fd, sa->sun_path);
	}
	/* reaped, unless SIGCHLD is ignored: connecting tells how it went */
	waitpid(pid, NULL, 0);
	ret = 0;
out:
	close(fd);
	return ret;
}

static int try_connect(const struct sockaddr_un *sa)
{
	int fd = seqpacket(), ret;

	if (fd < 0)
		return fd;
	if (!connect(fd, (const struct sockaddr *)sa, sizeof(*sa)))
		return fd;
	ret = -errno;
	close(fd);
	return ret;
}

int simbus_connect(const char *bus)
{
	char dir[sizeof(((struct sockaddr_un *)NULL)->sun_path)];
	struct sockaddr_un sa;
	int lock_fd, fd, ret;

	ret = simbus_check_name(bus);
	if (!ret)
		ret = simbus_dir(dir, sizeof(dir));
	if (!ret)
		ret = socket_addr(&sa, dir, bus);
	if (ret)
		return ret;
	lock_fd = simbus_lock(sa.sun_path);
	if (lock_fd < 0)
		return lock_fd;
	fd = try_connect(&sa);
	if (fd == -ENOENT || fd == -ECONNREFUSED) {
		fd = start_broker(&sa);
		if (!fd)
			fd = try_connect(&sa);
	}
	close(lock_fd);
	return fd;
}
