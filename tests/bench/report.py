#!/usr/bin/env python3
"""Turn the logs of one "make bench" into figures.

    report.py OUTDIR [DOC]

Reads every piece in OUTDIR, whichever run wrote it: OUTDIR/base/
(<driver>-<chip>.console.log, the "bench:" lines of tests/bench/guest.sh,
and userspace-<chip>.txt, mcp2510ctl bench) and OUTDIR/<profile>/<scale>x/
(<driver>-<chip>.console.log, with rt-<driver>-<chip>.console.log for the
PREEMPT_RT kernel's latency), each with its run.txt (tests/bench/pieces.py).
Prints tables and headlines, writes OUTDIR/summary.json and, for base,
the plot's data; given DOC, draws DOC's performance.svg (gnuplot) and
replaces the figures between DOC's "bench:begin" and "bench:end" markers
(base), "bench-profiles:begin" and "bench-profiles:end" (board profiles)
and "bench-compare:begin" and "bench-compare:end" (before and after).

Exits 1 when a figure is missing (a measurement void in each of its
tries, tests/bench/figures.py, or a piece whose runs are incomplete) or
a piece is stale.
"""
import json
import os
import re
import subprocess
import sys

from compare import before_after
from figures import figures, parse_console
from pieces import piece_info
from tables import CHIPS, DRIVERS, headlines, profile_tables, tables

BEGIN = "<!-- bench:begin (written by make bench) -->"
END = "<!-- bench:end -->"
PROFILES_BEGIN = "<!-- bench-profiles:begin (written by make bench) -->"
PROFILES_END = "<!-- bench-profiles:end -->"
COMPARE_BEGIN = "<!-- bench-compare:begin (written by make bench) -->"
COMPARE_END = "<!-- bench-compare:end -->"
SCALE_DIR = re.compile(r"^\d+(\.\d+)?x$")


def complete(path):
    """PATH holds a run that reached its end."""
    if not os.path.exists(path):
        return False
    with open(path, encoding="utf-8", errors="replace") as f:
        return any(line.startswith("bench: done") for line in f)


def run_setup(s):
    """The settings of a run that a figure depends on."""
    out = {
        "kernel": "6.1",
        "time_scale": int(s["time_scale"]),
        "frames_per_latency": int(s["frames"]),
        "flood_frames": int(s["flood_frames"]),
        "cpu_frames": int(s["cpu_frames"]),
        "cpu_bitrate": int(s["cpu_bitrate"]),
        "saturation_bitrate": int(s["saturation_bitrate"]),
        "stall_tries": int(s["stall_tries"]),
        "guest_cpus": int(s["cpus"]),
        "clocksource": s["clocksource"],
    }
    for key in ("spi_msg_ns", "spi_cs_setup_ns", "spi_cs_hold_ns", "spi_ctlr_max_hz",
                "irq_latency_ns", "cost_scale_pct", "probe_frames", "tx_frames"):
        if key in s:
            out[key] = int(s[key])
    return out


def userspace_figures(path):
    text = open(path, encoding="utf-8").read()

    def grab(pattern):
        m = re.search(pattern, text)
        if not m:
            sys.exit(f"report: {path}: no match for {pattern}")
        return float(m.group(1))

    # simulated time stands still while the program works: the bus waits
    # for it, so neither loss nor bus utilisation can be measured
    return {
        "rx_spi_bytes_per_frame": grab(r"rx: [\d.]+ spi transfers/frame, ([\d.]+)"),
        "rx_spi_transfers_per_frame": grab(r"rx: ([\d.]+) spi transfers"),
        "tx_spi_bytes_per_frame": grab(r"tx: [\d.]+ spi transfers/frame, ([\d.]+)"),
        "tx_spi_transfers_per_frame": grab(r"tx: ([\d.]+) spi transfers"),
        "irqs_per_frame": None,
        "cpu_us_per_frame": grab(r"cpu: ([\d.]+) us/frame"),
        "tx_bus_utilisation": {},
        "rx_loss": {},
        "rx_max_lossless_bitrate": None,
    }


def have_base(out):
    return os.path.exists(os.path.join(out, "base", "mcp2510-mcp2510.console.log"))


def collect(out, missing):
    """The base profile, as {driver: figures of the MCP2510 with the
    MCP2515's under "mcp2515"}, "userspace", "setup" and "run"."""
    out = os.path.join(out, "base")
    paths = [os.path.join(out, f"{d}-{c}.console.log") for d in DRIVERS for c in CHIPS]
    paths += [os.path.join(out, f"userspace-{c}.txt") for c in CHIPS]
    if not all(complete(p) or p.endswith(".txt") and os.path.exists(p) for p in paths):
        missing.append("base: the runs are incomplete")
        return {}
    summary = {}
    setup = None
    for driver in DRIVERS:
        chips = {}
        for chip in CHIPS:
            log = parse_console(os.path.join(out, f"{driver}-{chip}.console.log"))
            setup = setup or log["setup"][0]
            chips[chip] = figures(log)
            missing += [f"base {driver} on {chip}: {m}" for m in chips[chip]["missing"]]
        summary[driver] = dict(chips["mcp2510"], chip="mcp2510", mcp2515=chips["mcp2515"])
    chips = {c: userspace_figures(os.path.join(out, f"userspace-{c}.txt")) for c in CHIPS}
    summary["userspace"] = dict(chips["mcp2510"], chip="mcp2510", mcp2515=chips["mcp2515"])
    summary["setup"] = run_setup(setup)
    summary["run"] = piece_info(out, "base")
    return summary


def scale_key(label):
    return float(label[:-1])


def collect_profiles(out, missing):
    """{profile: {scale: {driver: {chip: figures}, "setup": ...}}} of the
    complete runs under OUTDIR/<profile>/<scale>x/."""
    found = {}
    for profile in sorted(os.listdir(out)):
        pdir = os.path.join(out, profile)
        if profile == "base" or not os.path.isdir(pdir):
            continue
        labels = sorted((d for d in os.listdir(pdir) if SCALE_DIR.match(d)), key=scale_key)
        for label in labels:
            entry = collect_scale(os.path.join(pdir, label), f"{profile} {label}", missing)
            if entry:
                found.setdefault(profile, {})[label] = entry
    return found


def collect_scale(sdir, name, missing):
    paths = {(d, c): os.path.join(sdir, f"{d}-{c}.console.log") for d in DRIVERS for c in CHIPS}
    if not all(complete(p) for p in paths.values()):
        missing.append(f"{name}: the runs are incomplete")
        return None
    entry = {"run": piece_info(sdir, "timed")}
    for (driver, chip), path in paths.items():
        log = parse_console(path)
        entry.setdefault("setup", run_setup(log["setup"][0]))
        fig = figures(log)
        rt = os.path.join(sdir, f"rt-{driver}-{chip}.console.log")
        if complete(rt):
            fig["rt"] = figures(parse_console(rt))
            fig["missing"] += [f"{m} (PREEMPT_RT)" for m in fig["rt"]["missing"]]
        missing += [f"{name} {driver} on {chip}: {m}" for m in fig["missing"]]
        entry.setdefault(driver, {})[chip] = fig
    return entry


def write_plot_data(out, summary):
    path = os.path.join(out, "plot.dat")
    with open(path, "w", encoding="utf-8") as f:
        for driver in DRIVERS:
            for chip in CHIPS:
                fig = summary[driver] if chip == "mcp2510" else summary[driver]["mcp2515"]
                f.write(f"# {driver}.ko on {chip.upper()}: bitrate util_pct loss_pct\n")
                for rate in sorted(fig["rx_loss"], key=int):
                    util = fig["tx_bus_utilisation"].get(rate)
                    loss = fig["rx_loss"][rate]
                    f.write(f"{rate} {'NaN' if util is None else 100 * util}"
                            f" {'NaN' if loss is None else 100 * loss}\n")
                f.write("\n\n")
    return path


def plot(data, summary, svg):
    here = os.path.dirname(os.path.abspath(__file__))
    subprocess.run(["gnuplot", "-e", f"data='{data}'; out='{svg}';"
                    f" scale={summary['setup']['time_scale']}",
                    os.path.join(here, "plot.gp")], check=True)


def update_doc(doc, lines, begin=BEGIN, end_mark=END):
    text = open(doc, encoding="utf-8").read()
    start, end = text.find(begin), text.find(end_mark)
    if start < 0 or end < start:
        sys.exit(f"report: {doc} lacks the {begin} ... {end_mark} markers")
    text = text[:start + len(begin)] + "\n" + "\n".join(lines) + "\n" + text[end:]
    with open(doc, "w", encoding="utf-8") as f:
        f.write(text)


def stale_pieces(summary):
    """'NAME: reasons' of every stale piece."""
    pieces = [("base", summary["run"])] if "run" in summary else []
    pieces += [(f"{p} {label}", e["run"]) for p, scales in summary.get("profiles", {}).items()
               for label, e in scales.items()]
    return [f"{name}: {', '.join(run['stale'])}" for name, run in pieces if run["stale"]]


def fresh(profiles):
    """The profiles' pieces that are not stale."""
    out = {p: {label: e for label, e in scales.items() if not e["run"]["stale"]}
           for p, scales in profiles.items()}
    return {p: scales for p, scales in out.items() if scales}


def main():
    if len(sys.argv) not in (2, 3):
        sys.exit(__doc__)
    out = sys.argv[1]
    doc = sys.argv[2] if len(sys.argv) == 3 else None
    missing = []
    summary = collect(out, missing) if have_base(out) else {}
    base = bool(summary)
    profiles = collect_profiles(out, missing)
    if not base and not profiles and not missing:
        sys.exit(f"report: no bench logs in {out}")
    if profiles:
        summary["profiles"] = profiles
        summary["headlines"] = headlines(fresh(profiles))
    summary["missing"] = missing
    summary["stale"] = stale_pieces(summary)
    with open(os.path.join(out, "summary.json"), "w", encoding="utf-8") as f:
        json.dump(summary, f, indent=2, sort_keys=True)
        f.write("\n")
    done = [os.path.join(out, "summary.json")]
    if base:
        lines = tables(summary)
        print("\n".join(lines))
        data = write_plot_data(out, summary)
        if doc:
            svg = os.path.join(os.path.dirname(os.path.abspath(doc)), "performance.svg")
            update_doc(doc, lines)
            plot(data, summary, svg)
            done.append(svg)
    if profiles:
        lines = profile_tables(profiles) + ["Headlines (band over the cost scales):", ""]
        lines += [f"- {h}" for h in summary["headlines"]] or ["- none: every piece is stale"]
        print("\n".join(lines))
        if doc:
            update_doc(doc, lines, PROFILES_BEGIN, PROFILES_END)
    compare = before_after(profiles)
    print("\n".join(compare))
    if doc:
        update_doc(doc, compare, COMPARE_BEGIN, COMPARE_END)
    print(f"bench: {', '.join(done)}")
    for m in missing:
        print(f"bench: missing: {m}", file=sys.stderr)
    for m in summary["stale"]:
        print(f"bench: stale: {m} (run it again)", file=sys.stderr)
    if missing or summary["stale"]:
        sys.exit(f"bench: {len(missing)} figures missing, {len(summary['stale'])} pieces"
                 " stale: rerun those pieces on a quieter host")


if __name__ == "__main__":
    main()
