// SPDX-License-Identifier: LGPL-2.1-or-later
/* The shared simulated bus's packets and names (simbus.h). */
#define _GNU_SOURCE
#include <errno.h>
#include <string.h>
#include <sys/socket.h>

#include "simbus.h"

int simbus_send(int fd, const struct simbus_msg *m)
{
	ssize_t n;

	do
		n = send(fd, m, sizeof(*m), MSG_NOSIGNAL);
	while (n < 0 && errno == EINTR);
	if (n < 0)
		return errno == ECONNRESET ? -EPIPE : -errno;
	return n == sizeof(*m) ? 0 : -EPROTO;
}

int simbus_recv(int fd, struct simbus_msg *m)
{
	ssize_t n;

	do
		n = recv(fd, m, sizeof(*m), 0);
	while (n < 0 && errno == EINTR);
	if (n < 0)
		return errno == ECONNRESET ? -EPIPE : -errno;
	if (n == 0)
		return -EPIPE;
	if (n != sizeof(*m) || m->len > SIMBUS_XFER_MAX)
		return -EPROTO;
	m->name[SIMBUS_NAME_MAX - 1] = '\0';
	return 0;
}

int simbus_check_name(const char *name)
{
	size_t len = strlen(name);

	if (!len || name[0] == '.')
		return -EINVAL;
	if (len >= SIMBUS_NAME_MAX)
		return -ENAMETOOLONG;
	if (strspn(name, "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz"
		   "0123456789._-") != len)
		return -EINVAL;
	return 0;
}
