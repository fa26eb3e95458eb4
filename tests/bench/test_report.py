#!/usr/bin/env python3
"""The bench report's counting on canned guest lines: what counts as
lossless, which try of a measurement is kept, what is missing, and that
a missing figure fails the report.  Run by make bench-check."""
import json
import os
import subprocess
import sys
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)

import figures  # noqa: E402

SETUP = ("bench: setup driver=mcp2510 variant=mcp2510 time_scale=10 frames=50"
         " flood_frames=1000 cpu_frames=1000 cpu_bitrate=125000 cpus=2"
         " stall_tries=3 saturation_bitrate=1000000 clocksource=tsc spi_time=0"
         " clock_stalls=0")
COUNTERS = ("spi_transfers=4000 spi_bytes=23000 frames_tx=1000 frames_rx=1000"
            " irqs_delivered=1000 overflows=0 spi_busy_ns=0")


def flood(what, rate, stalls=0, lost=0, dup=0, reord=0, corrupt=0, extra=""):
    received = 1000 - lost + dup + corrupt
    return (f"bench: {what} bitrate={rate} frames=1000 seconds=11 busy_cs=500"
            f" window_cs=1200 received={received} lost={lost} duplicated={dup}"
            f" reordered={reord} corrupted={corrupt} lossless=0 sock_drops=0"
            f" cpu_us=1000 {extra} {COUNTERS} stalls={stalls}")


def latency(what, rate, stalls=0, p50=1000000):
    return (f"bench: {what} bitrate={rate} lat_n=50 lat_p50_ns={p50}"
            f" lat_p99_ns={2 * p50} lat_max_ns={3 * p50} lat_missing=0"
            f" stamp_n=50 stamp_p50_ns=1 stamp_p99_ns=1 stamp_max_ns=1"
            f" stamp_missing=0 stalls={stalls}")


TX = ("mon_frames=256 mon_bits=111 mon_span_ns=230000000 mon_idle_ns=1000000"
      " monitor_missed=0")


def run_lines(rx_lines=(), lat_lines=()):
    lines = [SETUP]
    lines += list(lat_lines) or [latency("tx-latency", 125000),
                                 latency("rx-latency", 125000)]
    lines += ["bench: idle seconds=11 busy_cs=400 window_cs=1200 stalls=0",
              flood("cpu-rx", 125000), flood("cpu-tx", 125000, extra=TX),
              "bench: rxts bitrate=125000 frames=50 err_n=50 err_p50_ns=10000"
              " err_p99_ns=20000 err_max_ns=30000 err_missing=0 stalls=0"]
    lines += list(rx_lines) or [flood("rx", 125000)]
    lines += [flood("tx", 125000, extra=TX), "bench: done clock_stalls=0"]
    return lines


def parse(lines):
    with tempfile.NamedTemporaryFile("w", suffix=".log", delete=False) as f:
        f.write("\n".join(lines) + "\n")
    try:
        return figures.parse_console(f.name)
    finally:
        os.unlink(f.name)


def as_run(line):
    return parse([line, "bench: done"])[line.split()[1]][0]


def write_base(out, lines):
    """A base piece in OUT whose four boots logged LINES; returns its
    directory."""
    out = os.path.join(out, "base")
    os.makedirs(out)
    for driver in ("mcp2510", "mcp251x"):
        for chip in ("mcp2510", "mcp2515"):
            with open(os.path.join(out, f"{driver}-{chip}.console.log"), "w") as f:
                f.write("\n".join(lines) + "\n")
    for chip in ("mcp2510", "mcp2515"):
        with open(os.path.join(out, f"userspace-{chip}.txt"), "w") as f:
            f.write("rx: 6.00 spi transfers/frame, 29.00 bytes\n"
                    "tx: 6.00 spi transfers/frame, 29.00 bytes\ncpu: 3.0 us/frame\n")
    return out


class Lossless(unittest.TestCase):
    def test_every_frame_once_in_order_is_lossless(self):
        runs = [as_run(flood("rx", 125000)), as_run(flood("rx", 250000))]
        self.assertEqual(figures.max_lossless(runs), 250000)

    def test_more_received_than_sent_is_not_lossless(self):
        runs = [as_run(flood("rx", 125000, dup=1))]
        self.assertEqual(figures.max_lossless(runs), 0)

    def test_reordered_or_corrupted_is_not_lossless(self):
        for damage in ({"reord": 2}, {"corrupt": 1}, {"lost": 1}):
            runs = [as_run(flood("rx", 125000)), as_run(flood("rx", 250000, **damage))]
            self.assertEqual(figures.max_lossless(runs), 125000, damage)


class Search(unittest.TestCase):
    """The RX search's probes and full floods."""

    def probe(self, rate, **kw):
        return flood("rx-probe", rate, **kw).replace("frames=1000", "frames=200")

    def test_a_lossy_probe_decides_its_rate(self):
        fig = figures.figures(parse(run_lines(rx_lines=[
            self.probe(1000000, lost=3), self.probe(500000), flood("rx", 500000)])))
        self.assertEqual(fig["rx_max_lossless_bitrate"], 500000)
        self.assertEqual(fig["rx_frames"], {"1000000": 200, "500000": 1000})
        self.assertEqual(fig["rx_loss"]["1000000"], 0.015)
        self.assertEqual(fig["missing"], [])

    def test_a_lossless_probe_claims_nothing_without_its_flood(self):
        fig = figures.figures(parse(run_lines(rx_lines=[
            self.probe(500000), flood("rx", 500000, lost=1), self.probe(250000),
            flood("rx", 250000)])))
        self.assertEqual(fig["rx_max_lossless_bitrate"], 250000)
        self.assertEqual(fig["rx_frames"]["500000"], 1000)
        self.assertEqual(fig["rx_loss_bound_95"]["250000"], 0.003)

    def test_a_stalled_probe_leaves_no_lossless_rate(self):
        fig = figures.figures(parse(run_lines(rx_lines=[
            self.probe(1000000, stalls=1), "bench: rx-search-incomplete"])))
        self.assertIsNone(fig["rx_max_lossless_bitrate"])
        self.assertIn("rx-probe 1000000", fig["missing"])


class Stalls(unittest.TestCase):
    def test_the_last_clean_try_is_kept(self):
        fig = figures.figures(parse(run_lines(
            lat_lines=[latency("tx-latency", 125000, stalls=1, p50=9000000),
                       latency("tx-latency", 125000, p50=1000000),
                       latency("rx-latency", 125000)])))
        self.assertEqual(fig["tx_latency_us"]["125000"]["p50"], 100.0)
        self.assertEqual(fig["missing"], [])
        self.assertEqual(fig["measurements_repeated"], 1)
        self.assertIsNone(fig["guest_seconds"])

    def test_the_boot_is_timed_by_its_last_line(self):
        lines = run_lines()
        lines[-1] += " up=412.5"
        self.assertEqual(figures.figures(parse(lines))["guest_seconds"], 412.5)

    def test_a_stalled_last_try_is_missing(self):
        fig = figures.figures(parse(run_lines(
            lat_lines=[latency("tx-latency", 125000, stalls=1),
                       latency("tx-latency", 125000, stalls=2),
                       latency("rx-latency", 125000)])))
        self.assertNotIn("125000", fig["tx_latency_us"])
        self.assertEqual(fig["missing"], ["tx-latency 125000"])

    def test_a_stalled_flood_leaves_no_lossless_rate(self):
        fig = figures.figures(parse(run_lines(
            rx_lines=[flood("rx", 125000), flood("rx", 250000, stalls=1)])))
        self.assertIsNone(fig["rx_max_lossless_bitrate"])
        self.assertEqual(fig["missing"], ["rx 250000"])

    def test_a_monitor_that_lost_records_voids_a_burst(self):
        fig = figures.figures(parse(run_lines() + [flood(
            "tx", 500000, extra=TX.replace("missed=0", "missed=3"))]))
        self.assertIn("tx 500000", fig["missing"])


class Report(unittest.TestCase):
    """report.py on a directory of base logs."""

    def report(self, lines):
        with tempfile.TemporaryDirectory() as out:
            write_base(out, lines)
            res = subprocess.run([sys.executable, os.path.join(HERE, "report.py"), out], capture_output=True, text=True)
            with open(os.path.join(out, "summary.json")) as f:
                return res, json.load(f)

    def test_a_complete_run_passes(self):
        res, summary = self.report(run_lines())
        self.assertEqual(res.returncode, 0, res.stderr)
        self.assertEqual(summary["mcp2510"]["rx_max_lossless_bitrate"], 125000)

    def test_profiles_by_scale_with_headlines(self):
        setup = SETUP.replace("spi_time=0", "spi_time=1") + (
            " profile=pi spi_msg_ns=10000 spi_cs_setup_ns=100 spi_cs_hold_ns=100"
            " spi_ctlr_max_hz=0 irq_latency_ns=20000 cost_scale_pct=100")
        lines = [setup] + run_lines()[1:]
        with tempfile.TemporaryDirectory() as out:
            for label in ("1x", "2x"):
                sdir = os.path.join(out, "pi", label)
                os.makedirs(sdir)
                for driver in ("mcp2510", "mcp251x"):
                    for chip in ("mcp2510", "mcp2515"):
                        for prefix in ("", "rt-"):
                            name = f"{prefix}{driver}-{chip}.console.log"
                            with open(os.path.join(sdir, name), "w") as f:
                                f.write("\n".join(lines) + "\n")
            res = subprocess.run([sys.executable, os.path.join(HERE, "report.py"), out],
                                 capture_output=True, text=True)
            with open(os.path.join(out, "summary.json")) as f:
                summary = json.load(f)
        self.assertEqual(res.returncode, 0, res.stderr)
        fig = summary["profiles"]["pi"]["2x"]["mcp251x"]["mcp2515"]
        self.assertEqual(fig["rx_max_lossless_bitrate"], 125000)
        self.assertEqual(fig["rt"]["rx_latency_us"]["125000"]["p50"], 100.0)
        self.assertIn("pi (1x, 2x), MCP2515: lossless at the socket up to 125 kbit/s"
                      " (this driver) and 125 kbit/s (mcp251x); ratio 1", summary["headlines"])

    def test_a_missing_figure_fails_the_report(self):
        res, summary = self.report(run_lines(rx_lines=[flood("rx", 125000, stalls=1)]))
        self.assertNotEqual(res.returncode, 0)
        self.assertIn("rx 125000", res.stderr)
        self.assertIsNone(summary["mcp2510"]["rx_max_lossless_bitrate"])


if __name__ == "__main__":
    unittest.main()
