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

enum { OPT_IFACE = CLI_OPT_FIRST_OWN, OPT_FILTER, OPT_RESTART_MS };

static const struct cli_option own_options[] = {
	{ "iface", true, OPT_IFACE },
	{ "filter", true, OPT_FILTER },
	{ "restart-ms", true, OPT_RESTART_MS },
	{ NULL, false, 0 },
};

static void usage(FILE *out)
{
	fputs("Usage: mcp2510d --device DEV --iface IFACE [OPTIONS]\n"
	      "Run an MCP2510/MCP2515/MCP25625 through libmcp2510 and bridge it to\n"
	      "the SocketCAN interface IFACE (e.g. vcan0): frames and error frames\n"
	      "the chip receives are written to IFACE, frames sent on IFACE by other\n"
	      "programs go out on the chip's bus.  Stops on SIGINT or SIGTERM;\n"
	      "SIGUSR1 prints the statistics, SIGHUP restarts a bus-off chip\n"
	      "when --restart-ms is 0.\n\n"
	      "Options:\n"
	      "  --iface IFACE       the SocketCAN interface (required)\n"
	      "  --filter NAME=VALUE an acceptance filter setting, as mcp2510ctl filter\n"
	      "                      takes it (mask0=7ff filter0=123 ...), on top of\n"
	      "                      those the chip holds; may be repeated\n"
	      "  --restart-ms MS     after bus-off, rejoin the bus MS ms later; 0 (the\n"
	      "                      default): stay bus-off until SIGHUP\n", out);
	fputs(cli_device_help, out);
	fputs("  -h, --help          this text\n", out);
}

struct daemon_opts {
	struct cli_device dev;
	const char *iface;
	int restart_ms;
};

/* As "ip link set ... type can restart-ms MS": milliseconds, 0 for none. */
static int set_restart_ms(struct daemon_opts *o, const char *value)
{
	if (!cli_int(value, false, &o->restart_ms))
		return 0;
	cli_error(stderr, PROG, "invalid value '%s' for --restart-ms", value);
	return -1;
}

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
		} else if (id == OPT_RESTART_MS) {
			if (set_restart_ms(o, value))
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
	if (!o->dev.device) {
		cli_error(stderr, PROG,
			  "no --device given (spidev:/dev/spidevB.C or sim)");
		return EXIT_USAGE;
	}
	/* a bit rate CAN cannot use is a wrong command line, found first */
	if (cli_device_timing(&o->dev, &a))
		return EXIT_USAGE;
	if (o->dev.ctrlmode & CAN_CTRLMODE_LISTENONLY)
		cli_error(stderr, PROG,
			  "note: --listen-only: frames sent on %s are dropped (counted as ignored)",
			  o->iface);
	return 0;
}

static int raw_socket_setup(int s, unsigned int ifindex)
{
	struct sockaddr_can addr = { .can_family = AF_CAN,
				     .can_ifindex = (int)ifindex };
	can_err_mask_t errors = CAN_ERR_MASK;
	int off = 0, on = 1;

	/*
	 * Error frames both ways; never read back what we wrote; the count
	 * of frames the receive queue dropped comes with each frame read.
	 */
	if (setsockopt(s, SOL_CAN_RAW, CAN_RAW_ERR_FILTER, &errors,
		       sizeof(errors)) ||
	    setsockopt(s, SOL_CAN_RAW, CAN_RAW_RECV_OWN_MSGS, &off, sizeof(off)) ||
	    setsockopt(s, SOL_SOCKET, SO_RXQ_OVFL, &on, sizeof(on)))
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

/* SIGINT and SIGTERM stop, SIGHUP restarts, SIGUSR1 prints statistics. */
static int signals_fd(void)
{
	sigset_t set;

	sigemptyset(&set);
	sigaddset(&set, SIGINT);
	sigaddset(&set, SIGTERM);
	sigaddset(&set, SIGHUP);
	sigaddset(&set, SIGUSR1);
	if (sigprocmask(SIG_BLOCK, &set, NULL))
		return -1;
	return signalfd(-1, &set, SFD_CLOEXEC | SFD_NONBLOCK);
}

/* SIGHUP: a manual restart, allowed when the kernel would allow one. */
static void manual_restart(struct bridge *b)
{
	if (b->restart_ms) {
		cli_error(stderr, PROG, "SIGHUP ignored: the restart comes by itself (--restart-ms %d)",
			  b->restart_ms);
		return;
	}
	if (bridge_restart(b))
		cli_error(stderr, PROG, "restart: %s", errno == EBUSY ?
			  "the chip is not bus-off" : strerror(errno));
}

/* 1 to stop, 0 to go on. */
static int take_signals(struct bridge *b, int sig_fd)
{
	struct signalfd_siginfo si;

	while (read(sig_fd, &si, sizeof(si)) == (ssize_t)sizeof(si)) {
		if (si.ssi_signo == SIGUSR1)
			bridge_print_stats(b, stderr, PROG);
		else if (si.ssi_signo == SIGHUP)
			manual_restart(b);
		else
			return 1;
	}
	return 0;
}

/* Bus-off and restarts are told as the kernel's can-dev tells them. */
static void report_bus(const struct bridge *b, struct bridge_counts *seen,
		       const char *iface)
{
	const struct bridge_counts *c = &b->counts;

	if (c->bus_offs != seen->bus_offs && b->restart_ms)
		fprintf(stderr, "%s: %s: bus-off, scheduling restart in %d ms\n",
			PROG, iface, b->restart_ms);
	else if (c->bus_offs != seen->bus_offs)
		fprintf(stderr, "%s: %s: bus-off, restart with SIGHUP\n",
			PROG, iface);
	if (c->restart_failures != seen->restart_failures)
		fprintf(stderr, "%s: %s: restart failed, trying again\n",
			PROG, iface);
	if (c->restarts != seen->restarts)
		fprintf(stderr, "%s: %s: restarted\n", PROG, iface);
	*seen = *c;
}

static int run(struct mcp2510 *h, int sock, int sig_fd,
	       const struct daemon_opts *o)
{
	struct bridge_counts seen = { 0 };
	struct bridge b;
	int ret;

	bridge_init(&b, h, sock);
	b.restart_ms = o->restart_ms;
	do {
		ret = bridge_poll(&b, sig_fd, -1);
		/* 1: a signal came; it may have been SIGHUP's restart */
		if (ret > 0)
			ret = take_signals(&b, sig_fd);
		report_bus(&b, &seen, o->iface);
	} while (!ret);
	if (ret < 0)
		cli_error(stderr, PROG, "bridge: %s", strerror(errno));
	else
		fprintf(stderr, "%s: stopped\n", PROG);
	/* count what never went out before telling the totals */
	bridge_stop(&b);
	bridge_print_stats(&b, stderr, PROG);
	return ret < 0 ? EXIT_FAIL : 0;
}

int main(int argc, char **argv)
{
	struct cli_args a = { argc, argv, 1, false, PROG, stderr };
	struct daemon_opts o = { .iface = NULL };
	struct mcp2510 *h;
	int ret, sock, sig_fd;

	cli_device_init(&o.dev);
	ret = parse_args(argc, argv, &o);
	if (ret)
		return ret < 0 ? 0 : ret;
	sig_fd = signals_fd();
	if (sig_fd < 0) {
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
		ret = run(h, sock, sig_fd, &o);
	mcp2510_close(h);
out_socket:
	close(sock);
out_signals:
	close(sig_fd);
	return ret;
}
