// SPDX-License-Identifier: GPL-2.0
/*
 * mcp2510d: run a chip through libmcp2510 and bridge it to a SocketCAN
 * interface (vcan0, say), so candump, cansend and every other SocketCAN
 * program can use a chip that has no kernel driver.
 */
#define _GNU_SOURCE
#include <errno.h>
#include <net/if.h>
#include <signal.h>
#include <string.h>
#include <unistd.h>
#include <sys/signalfd.h>
#include <sys/socket.h>
#include <linux/can/raw.h>

#include "bridge.h"
#include "cli.h"

#define PROG "mcp2510d"

enum { OPT_IFACE = CLI_OPT_FIRST_OWN, OPT_FILTER };

static const struct cli_option own_options[] = {
	{ "iface", true, OPT_IFACE },
	{ "filter", true, OPT_FILTER },
	{ NULL, false, 0 },
};

static void usage(FILE *out)
{
	fputs("Usage: mcp2510d --device DEV --iface IFACE [OPTIONS]\n"
	      "Run an MCP2510/MCP2515/MCP25625 through libmcp2510 and bridge it to\n"
	      "the SocketCAN interface IFACE (e.g. vcan0): frames and error frames\n"
	      "the chip receives are written to IFACE, frames sent on IFACE by other\n"
	      "programs go out on the chip's bus.  Stops on SIGINT or SIGTERM.\n\n"
	      "Options:\n"
	      "  --iface IFACE       the SocketCAN interface (required)\n"
	      "  --filter NAME=VALUE an acceptance filter setting, as mcp2510ctl filter\n"
	      "                      takes it (mask0=7ff filter0=123 ...), on top of\n"
	      "                      those the chip holds; may be repeated\n", out);
	fputs(cli_device_help, out);
	fputs("  -h, --help          this text\n", out);
}

struct daemon_opts {
	struct cli_device dev;
	const char *iface;
};

/* 0 to run, or the exit status to end with. */
static int parse_args(int argc, char **argv, struct daemon_opts *o)
{
	const struct cli_option *const tables[] = { cli_device_options,
						    own_options, NULL };
	struct cli_args a = { argc, argv, 1, false, PROG, stderr };
	const char *value;
	enum cli_kind kind;
	int id;

	while ((kind = cli_next(&a, tables, &id, &value)) != CLI_END) {
		if (kind == CLI_ERROR)
			return EXIT_USAGE;
		if (kind == CLI_ARG) {
			cli_error(stderr, PROG, "unexpected argument '%s'", value);
			return EXIT_USAGE;
		}
		if (id == CLI_OPT_HELP) {
			usage(stdout);
			return -1;
		}
		if (id == CLI_OPT_VERSION) {
			cli_version(stdout, PROG);
			return -1;
		}
		if (id == OPT_IFACE)
			o->iface = value;
		else if (id == OPT_FILTER) {
			if (cli_device_add_filter(&o->dev, &a, value))
				return EXIT_USAGE;
		} else if (cli_device_set(&o->dev, &a, id, value))
			return EXIT_USAGE;
	}
	if (cli_device_check(&o->dev, &a))
		return EXIT_USAGE;
	if (!o->iface) {
		cli_error(stderr, PROG, "no --iface given (e.g. --iface vcan0)");
		return EXIT_USAGE;
	}
	return 0;
}

static int raw_socket_setup(int s, unsigned int ifindex)
{
	struct sockaddr_can addr = { .can_family = AF_CAN,
				     .can_ifindex = (int)ifindex };
	can_err_mask_t errors = CAN_ERR_MASK;
	int off = 0;

	/* error frames both ways; never read back what we wrote */
	if (setsockopt(s, SOL_CAN_RAW, CAN_RAW_ERR_FILTER, &errors,
		       sizeof(errors)) ||
	    setsockopt(s, SOL_CAN_RAW, CAN_RAW_RECV_OWN_MSGS, &off, sizeof(off)))
		return -1;
	return bind(s, (struct sockaddr *)&addr, sizeof(addr));
}

static int raw_socket_open(const char *iface)
{
	unsigned int ifindex = if_nametoindex(iface);
	int s;

	if (!ifindex) {
		cli_error(stderr, PROG, "no interface %s: %s", iface,
			  strerror(errno));
		return -1;
	}
	s = socket(PF_CAN, SOCK_RAW | SOCK_CLOEXEC | SOCK_NONBLOCK, CAN_RAW);
	if (s < 0 || raw_socket_setup(s, ifindex)) {
		cli_error(stderr, PROG, "CAN_RAW socket on %s: %s", iface,
			  strerror(errno));
		if (s >= 0)
			close(s);
		return -1;
	}
	return s;
}

static int stop_signals_fd(void)
{
	sigset_t set;

	sigemptyset(&set);
	sigaddset(&set, SIGINT);
	sigaddset(&set, SIGTERM);
	if (sigprocmask(SIG_BLOCK, &set, NULL))
		return -1;
	return signalfd(-1, &set, SFD_CLOEXEC);
}

static int run(struct mcp2510 *h, int sock, int stop_fd)
{
	struct bridge b;
	int ret;

	bridge_init(&b, h, sock);
	while (!(ret = bridge_poll(&b, stop_fd, -1)))
		;
	if (ret < 0) {
		cli_error(stderr, PROG, "bridge: %s", strerror(errno));
		return EXIT_FAIL;
	}
	fprintf(stderr,
		"%s: stopped; %llu frames to the interface, %llu to the chip, %llu dropped\n",
		PROG, (unsigned long long)b.counts.to_socket,
		(unsigned long long)b.counts.to_chip,
		(unsigned long long)b.counts.socket_drops + b.counts.chip_drops);
	return 0;
}

int main(int argc, char **argv)
{
	struct cli_args a = { argc, argv, 1, false, PROG, stderr };
	struct daemon_opts o = { .iface = NULL };
	struct mcp2510 *h;
	int ret, sock, stop_fd;

	cli_device_init(&o.dev);
	ret = parse_args(argc, argv, &o);
	if (ret)
		return ret < 0 ? 0 : ret;
	stop_fd = stop_signals_fd();
	if (stop_fd < 0) {
		cli_error_errno(&a, "signals");
		return EXIT_FAIL;
	}
	ret = EXIT_FAIL;
	sock = raw_socket_open(o.iface);
	if (sock < 0)
		goto out_signals;
	h = cli_device_open(&o.dev, &a, false);
	if (!h)
		goto out_socket;
	if (!cli_device_up(&o.dev, h, &a))
		ret = run(h, sock, stop_fd);
	mcp2510_close(h);
out_socket:
	close(sock);
out_signals:
	close(stop_fd);
	return ret;
}
