// SPDX-License-Identifier: GPL-2.0
/*
 * can-dlc: Classical CAN frames with a raw DLC of 9..15 (struct
 * can_frame's len8_dlc), which Debian 12's can-utils (2020.11) can
 * neither send nor show.  The syntax is the one later can-utils use:
 *
 *   can-dlc send IFACE 123#1122334455667788_E   eight bytes, DLC 0xE
 *   can-dlc recv IFACE N                        print the next N frames
 *
 * recv prints one frame a line as ID#DATA, with "_X" appended when the
 * frame came with len8_dlc X (whatever its length, so that a len8_dlc the
 * driver should not have set shows too), or "#R" and the length for a
 * remote frame.  Exit 1 when no frame comes for 20 s, 2 on a bad argument
 * or a socket error.
 */
#define _GNU_SOURCE
#include <ctype.h>
#include <errno.h>
#include <linux/can.h>
#include <net/if.h>
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <unistd.h>

#define WAIT_MS		20000

static void die(const char *what)
{
	fprintf(stderr, "can-dlc: %s: %s\n", what, strerror(errno ? errno : EINVAL));
	exit(2);
}

static int open_on(const char *ifname)
{
	struct sockaddr_can addr = { .can_family = AF_CAN };
	int s;

	addr.can_ifindex = (int)if_nametoindex(ifname);
	if (!addr.can_ifindex)
		die(ifname);
	s = socket(PF_CAN, SOCK_RAW, CAN_RAW);
	if (s < 0)
		die("socket");
	if (bind(s, (struct sockaddr *)&addr, sizeof(addr)) < 0)
		die("bind");
	return s;
}

/* The byte of the two hex digits at @p, or -1. */
static int hex_byte(const char *p)
{
	char two[3] = { 0 };

	if (!isxdigit((unsigned char)p[0]) || !isxdigit((unsigned char)p[1]))
		return -1;
	memcpy(two, p, 2);
	return (int)strtol(two, NULL, 16);
}

/* ID#DATA[_X]: 3 or 8 hex digits of id, up to 8 bytes, raw DLC X. */
static int parse(const char *text, struct can_frame *cf)
{
	const char *hash = strchr(text, '#');
	const char *p;
	unsigned long id;
	char *end;
	long dlc;

	memset(cf, 0, sizeof(*cf));
	if (!hash || (hash - text != 3 && hash - text != 8))
		return -1;
	id = strtoul(text, &end, 16);
	if (end != hash)
		return -1;
	cf->can_id = hash - text == 8 ? (canid_t)id | CAN_EFF_FLAG : (canid_t)id;
	for (p = hash + 1; *p && *p != '_'; p += 2) {
		int byte = hex_byte(p);

		if (cf->len == CAN_MAX_DLEN || byte < 0)
			return -1;
		cf->data[cf->len++] = (__u8)byte;
	}
	if (*p == '_') {
		/* one hex digit, 9..F: a DLC that says more than 8 bytes */
		if (!isxdigit((unsigned char)p[1]) || p[2])
			return -1;
		dlc = strtol(p + 1, NULL, 16);
		if (dlc <= CAN_MAX_DLEN)
			return -1;
		cf->len8_dlc = (__u8)dlc;
	}
	return 0;
}

static int do_send(const char *ifname, const char *text)
{
	struct can_frame cf;
	int s;

	if (parse(text, &cf)) {
		fprintf(stderr, "can-dlc: bad frame '%s'\n", text);
		return 2;
	}
	s = open_on(ifname);
	if (write(s, &cf, sizeof(cf)) != sizeof(cf))
		die("write");
	close(s);
	return 0;
}

static void print_frame(const struct can_frame *cf)
{
	unsigned int i;

	if (cf->can_id & CAN_EFF_FLAG)
		printf("%08X#", cf->can_id & CAN_EFF_MASK);
	else
		printf("%03X#", cf->can_id & CAN_SFF_MASK);
	if (cf->can_id & CAN_RTR_FLAG) {
		printf("R%u", cf->len);
	} else {
		for (i = 0; i < cf->len && i < CAN_MAX_DLEN; i++)
			printf("%02X", cf->data[i]);
	}
	if (cf->len8_dlc)
		printf("_%X", cf->len8_dlc);
	printf("\n");
	fflush(stdout);
}

static int do_recv(const char *ifname, const char *count)
{
	long n = strtol(count, NULL, 10);
	struct can_frame cf;
	int s = open_on(ifname);

	while (n-- > 0) {
		struct pollfd pfd = { .fd = s, .events = POLLIN };
		int ret = poll(&pfd, 1, WAIT_MS);

		if (ret < 0)
			die("poll");
		if (!ret) {
			fprintf(stderr, "can-dlc: no frame for %d ms\n", WAIT_MS);
			return 1;
		}
		if (read(s, &cf, sizeof(cf)) != sizeof(cf))
			die("read");
		print_frame(&cf);
	}
	close(s);
	return 0;
}

int main(int argc, char **argv)
{
	if (argc == 4 && !strcmp(argv[1], "send"))
		return do_send(argv[2], argv[3]);
	if (argc == 4 && !strcmp(argv[1], "recv"))
		return do_recv(argv[2], argv[3]);
	fprintf(stderr, "usage: can-dlc send IFACE ID#DATA[_X]\n"
			"       can-dlc recv IFACE N\n");
	return 2;
}
