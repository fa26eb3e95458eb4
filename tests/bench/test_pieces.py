#!/usr/bin/env python3
"""The bench report's pieces on canned logs: pieces of several runs add
up to one summary, each with when and on which commit it was measured; a
piece measured on other sources or settings is stale, makes no headline
and fails the report; the before/after table says what has not been
measured yet.  Run by make bench-check."""
import json
import os
import subprocess
import sys
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)

from test_report import SETUP, flood, run_lines, write_base  # noqa: E402

PI_SETUP = SETUP.replace("spi_time=0", "spi_time=1") + (
    " profile=pi spi_msg_ns=5000 spi_cs_setup_ns=1000 spi_cs_hold_ns=3000"
    " spi_ctlr_max_hz=0 irq_latency_ns=4000 cost_scale_pct=100 probe_frames=200"
    " tx_frames=300")
CURRENT = {"BENCH_SOURCES": "s1", "BENCH_SETTINGS_TIMED": "t1", "BENCH_SETTINGS_BASE": "b1"}


def write_piece(out, label, run, rx_rate=125000, complete=True):
    """A piece of profile pi at LABEL whose run.txt holds RUN (None: no
    run.txt), each driver lossless up to RX_RATE."""
    sdir = os.path.join(out, "pi", label)
    os.makedirs(sdir)
    lines = [PI_SETUP] + run_lines(rx_lines=[flood("rx", rx_rate)])[1:]
    if not complete:
        lines = lines[:-1]
    for driver in ("mcp2510", "mcp251x"):
        for chip in ("mcp2510", "mcp2515"):
            with open(os.path.join(sdir, f"{driver}-{chip}.console.log"), "w") as f:
                f.write("\n".join(lines) + "\n")
    if run is not None:
        with open(os.path.join(sdir, "run.txt"), "w") as f:
            f.write("".join(f"{k}={v}\n" for k, v in run.items()))


def run_of(date, commit, sources="s1", settings="t1"):
    return {"date": date, "commit": commit, "sources": sources, "settings": settings}


def report(out, env=None, doc=None):
    res = subprocess.run([sys.executable, os.path.join(HERE, "report.py"), out]
                         + ([doc] if doc else []), capture_output=True, text=True,
                         env=dict(os.environ, **(CURRENT if env is None else env)))
    with open(os.path.join(out, "summary.json")) as f:
        return res, json.load(f)


class Pieces(unittest.TestCase):
    def test_pieces_of_two_runs_add_up(self):
        with tempfile.TemporaryDirectory() as out:
            write_piece(out, "1x", run_of("2026-12-01T10:00Z", "aaa1111"))
            write_piece(out, "2x", run_of("2026-12-02T11:00Z", "bbb2222"), rx_rate=250000)
            res, summary = report(out)
        self.assertEqual(res.returncode, 0, res.stderr)
        pi = summary["profiles"]["pi"]
        self.assertEqual(pi["1x"]["run"]["commit"], "aaa1111")
        self.assertEqual(pi["2x"]["run"]["date"], "2026-12-02T11:00Z")
        self.assertEqual(summary["stale"], [])
        self.assertIn("pi (1x, 2x), MCP2510: lossless at the socket up to 125-250 kbit/s"
                      " (this driver) and 125-250 kbit/s (mcp251x); ratio 1",
                      summary["headlines"])
        self.assertIn("**pi 1x** (measured 2026-12-01T10:00Z at aaa1111)", res.stdout)
        self.assertIn("RX floods of 1000 frames after probes of 200, TX bursts of 300",
                      res.stdout)
        self.assertIn("**pi 2x** (measured 2026-12-02T11:00Z at bbb2222)", res.stdout)

    def test_a_piece_on_other_sources_is_stale(self):
        with tempfile.TemporaryDirectory() as out:
            write_piece(out, "1x", run_of("2026-12-01T10:00Z", "aaa1111"))
            write_piece(out, "2x", run_of("2026-12-01T09:00Z", "ccc3333", sources="s0"),
                        rx_rate=250000)
            res, summary = report(out)
        self.assertNotEqual(res.returncode, 0)
        self.assertEqual(summary["stale"], ["pi 2x: measured on other sources"])
        self.assertIn("pi 2x: measured on other sources", res.stderr)
        self.assertEqual(summary["profiles"]["pi"]["2x"]["run"]["stale"],
                         ["measured on other sources"])
        # the stale piece's figures make no headline
        self.assertIn("pi (1x), MCP2510: lossless at the socket up to 125 kbit/s"
                      " (this driver) and 125 kbit/s (mcp251x); ratio 1", summary["headlines"])
        self.assertIn("| pi | MCP2510 | zero-loss bit rate | mcp2510 | 1000 kbit/s"
                      " | not yet measured | 125 kbit/s | stale | none |", res.stdout)

    def test_other_settings_or_no_record_is_stale(self):
        with tempfile.TemporaryDirectory() as out:
            write_piece(out, "1x", run_of("2026-12-01T10:00Z", "aaa1111", settings="t0"))
            write_piece(out, "2x", None)
            res, summary = report(out)
        self.assertNotEqual(res.returncode, 0)
        self.assertEqual(sorted(summary["stale"]),
                         ["pi 1x: measured with other settings",
                          "pi 2x: measured on other sources, measured with other settings"])
        self.assertEqual(summary["headlines"], [])

    def test_a_base_piece_with_other_settings_is_stale(self):
        with tempfile.TemporaryDirectory() as out:
            base = write_base(out, run_lines())
            with open(os.path.join(base, "run.txt"), "w") as f:
                f.write("date=2026-12-01T10:00Z\ncommit=aaa1111\nsources=s1\nsettings=b0\n")
            res, summary = report(out)
        self.assertNotEqual(res.returncode, 0)
        self.assertEqual(summary["stale"], ["base: measured with other settings"])
        self.assertIn("measured 2026-12-01T10:00Z at aaa1111; stale: measured with other"
                      " settings: Debian 6.1 kernel", res.stdout)

    def test_without_the_current_sources_nothing_is_stale(self):
        with tempfile.TemporaryDirectory() as out:
            write_piece(out, "1x", run_of("2026-12-01T10:00Z", "aaa1111", sources="s0"))
            res, summary = report(out, env={})
        self.assertEqual(res.returncode, 0, res.stderr)
        self.assertEqual(summary["stale"], [])

    def test_an_incomplete_piece_is_missing(self):
        with tempfile.TemporaryDirectory() as out:
            write_piece(out, "1x", run_of("2026-12-01T10:00Z", "aaa1111"))
            write_piece(out, "2x", run_of("2026-12-01T10:00Z", "aaa1111"), complete=False)
            res, summary = report(out)
        self.assertNotEqual(res.returncode, 0)
        self.assertEqual(summary["missing"], ["pi 2x: the runs are incomplete"])
        self.assertNotIn("2x", summary["profiles"]["pi"])


class BeforeAfter(unittest.TestCase):
    def test_the_table_in_the_document(self):
        with tempfile.TemporaryDirectory() as out:
            write_piece(out, "1x", run_of("2026-12-01T10:00Z", "aaa1111"), rx_rate=1000000)
            doc = os.path.join(out, "doc.md")
            with open(doc, "w") as f:
                f.write("<!-- bench-profiles:begin (written by make bench) -->\n"
                        "<!-- bench-profiles:end -->\n"
                        "<!-- bench-compare:begin (written by make bench) -->\n"
                        "earlier table\n<!-- bench-compare:end -->\n")
            res, _ = report(out, doc=doc)
            with open(doc) as f:
                text = f.read()
        self.assertEqual(res.returncode, 0, res.stderr)
        self.assertNotIn("earlier table", text.split("bench-compare:begin")[1])
        # held where the new figure is the old one, at the scale that ran
        self.assertIn("| pi | MCP2510 | zero-loss bit rate | mcp2510 | 1000 kbit/s"
                      " | not yet measured | 1000 kbit/s | not yet measured | 1x |", text)
        self.assertIn("| pi | MCP2510 | zero-loss bit rate | mcp251x | 250 kbit/s"
                      " | not yet measured | 1000 kbit/s | not yet measured | none |", text)
        self.assertIn("| pi | MCP2510 | TX bus utilisation at 1 Mbit/s | mcp2510 | 95.2%"
                      " | not yet measured | missing | not yet measured | none |", text)
        self.assertIn("| slow | MCP2515 | zero-loss bit rate | mcp2510 | 800 kbit/s"
                      " | not yet measured | not yet measured | not yet measured"
                      " | not yet measured |", text)
        self.assertIn("| pi-rt | MCP2510 | zero-loss bit rate | mcp2510 | not run", text)


if __name__ == "__main__":
    unittest.main()
