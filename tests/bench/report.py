#!/usr/bin/env python3
"""Turn the logs of one "make bench" into figures.

    report.py OUTDIR [DOC]

Reads OUTDIR/<driver>-<chip>.console.log (the "bench:" lines of
tests/bench/guest.sh) and OUTDIR/userspace-<chip>.txt (mcp2510ctl bench)
of the base profile, and OUTDIR/<profile>-<driver>-<chip>.console.log of
the board profiles (SPI time on), whichever are there.  Prints tables,
writes OUTDIR/summary.json and, for base, the plot's data and
docs/performance.svg (gnuplot); given DOC, replaces the figures between
DOC's "bench:begin" and "bench:end" markers (base) and between
"bench-profiles:begin" and "bench-profiles:end" (board profiles).
"""
import json
import os
import re
import subprocess
import sys

DRIVERS = ("mcp2510", "mcp251x")
CHIPS = ("mcp2510", "mcp2515")
KEY_BITRATES = (125000, 500000, 1000000)
PROFILES = ("pi", "slow")
BEGIN = "<!-- bench:begin (written by make bench) -->"
END = "<!-- bench:end -->"
PROFILES_BEGIN = "<!-- bench-profiles:begin (written by make bench) -->"
PROFILES_END = "<!-- bench-profiles:end -->"


def parse_console(path):
    """The guest's measurements: {what: [fields, ...]}."""
    found = {}
    with open(path, encoding="utf-8", errors="replace") as f:
        for line in f:
            m = re.match(r"^bench: (\S+)(.*)$", line.strip())
            if not m:
                continue
            fields = {}
            for item in m.group(2).split():
                key, _, value = item.partition("=")
                try:
                    fields[key] = float(value)
                except ValueError:
                    fields[key] = value
            found.setdefault(m.group(1), []).append(fields)
    if "done" not in found:
        sys.exit(f"report: {path} does not hold a complete run")
    return found


def complete(path):
    """PATH holds a run that reached its end."""
    if not os.path.exists(path):
        return False
    with open(path, encoding="utf-8", errors="replace") as f:
        return any(line.startswith("bench: done") for line in f)


def per_frame(value, frames):
    return round(value / frames, 2) if frames else None


def cpu_us_per_frame(run, idle, frames):
    """Busy CPU time of a burst less that of the same time without one."""
    baseline = idle["busy_cs"] * run["window_cs"] / idle["window_cs"]
    return round((run["busy_cs"] - baseline) * 1e4 / frames, 1) if frames else None


def tx_utilisation(run):
    """Frames per second on the bus over the most that length allows."""
    n = run["mon_frames"]
    if n < 2 or run["mon_span_ns"] <= 0:
        return None, None
    per_second = (n - 1) * 1e9 / run["mon_span_ns"]
    most = run["bitrate"] / run["mon_bits"]
    return round(per_second / most, 4), round(run["mon_idle_ns"] / (n - 1) / 1e3, 2)


def add_tx_figures(fig, bursts):
    """TX bus utilisation and idle time per gap, by bit rate, into fig."""
    for run in bursts:
        rate = str(int(run["bitrate"]))
        util, idle_us = tx_utilisation(run)
        fig["tx_bus_utilisation"][rate] = util
        fig["tx_idle_us_per_gap"][rate] = idle_us


def driver_figures(log):
    idle = log["idle"][0]
    rx = log["cpu-rx"][0]
    tx = log["cpu-tx"][0]
    fig = {
        "rx_spi_bytes_per_frame": per_frame(rx["spi_bytes"], rx["frames_rx"]),
        "rx_spi_transfers_per_frame": per_frame(rx["spi_transfers"], rx["frames_rx"]),
        "tx_spi_bytes_per_frame": per_frame(tx["spi_bytes"], tx["frames_tx"]),
        "tx_spi_transfers_per_frame": per_frame(tx["spi_transfers"], tx["frames_tx"]),
        "irqs_per_frame": per_frame(rx["irqs_delivered"], rx["frames_rx"]),
        "tx_irqs_per_frame": per_frame(tx["irqs_delivered"], tx["frames_tx"]),
        "cpu_us_per_frame": cpu_us_per_frame(rx, idle, rx["received"]),
        "tx_cpu_us_per_frame": cpu_us_per_frame(tx, idle, tx["frames_tx"]),
        "cpu_burst_loss": round(1 - rx["received"] / rx["frames"], 4),
        "rx_timestamp_error_us": rx_timestamp_error(log, log["setup"][0]["time_scale"]),
        **latency_figures(log, log["setup"][0]["time_scale"]),
        "tx_bus_utilisation": {},
        "tx_idle_us_per_gap": {},
        "rx_loss": {},
        "rx_overflows": {},
    }
    lossless = 0
    for run in sorted(log.get("rx", []), key=lambda r: r["bitrate"]):
        rate = str(int(run["bitrate"]))
        loss = round(1 - run["received"] / run["frames"], 4)
        fig["rx_loss"][rate] = loss
        fig["rx_overflows"][rate] = int(run["overflows"])
        if loss == 0 and lossless == len(fig["rx_loss"]) - 1:
            lossless += 1
            fig["rx_max_lossless_bitrate"] = int(run["bitrate"])
    fig.setdefault("rx_max_lossless_bitrate", 0)
    add_tx_figures(fig, sorted(log.get("tx", []), key=lambda r: r["bitrate"]))
    return fig


def max_lossless(runs):
    """The highest flooded bit rate without loss below every lossy one."""
    lossy = [r["bitrate"] for r in runs if r["received"] < r["frames"]]
    ok = [r["bitrate"] for r in runs if r["received"] >= r["frames"]
          and (not lossy or r["bitrate"] < min(lossy))]
    return int(max(ok)) if ok else 0


def spi_us(run, frames_key):
    frames = run[frames_key]
    return round(run.get("spi_busy_ns", 0) / frames / 1e3, 2) if frames else None


def late_us(run, frames_key):
    frames = run[frames_key]
    return round(run.get("spi_late_ns", 0) / frames / 1e3, 2) if frames else None


def last_by_bitrate(runs):
    """A measurement repeated after a clock stall: the last try of each."""
    return sorted({r["bitrate"]: r for r in runs}.values(), key=lambda r: r["bitrate"])


def distribution_us(run, name, scale):
    """The NAME_* percentiles (ns of real time) of a guest measurement in
    microseconds of bus time (real time over time_scale, as a board would
    see it)."""
    def us(ns):
        return round(ns / 1e3 / scale, 2)
    return {
        "p50": us(run[f"{name}_p50_ns"]),
        "p99": us(run[f"{name}_p99_ns"]),
        "max": us(run[f"{name}_max_ns"]),
        "frames": int(run[f"{name}_n"]),
        "not_on_bus": int(run[f"{name}_missing"]),
        "bitrate": int(run["bitrate"]),
    }


def rx_timestamp_error(log, scale):
    """How far receive timestamps lie after the end of frame on the bus,
    in a flood, from the last rxts run; None for a log without one."""
    runs = log.get("rxts")
    return distribution_us(runs[-1], "err", scale) if runs else None


LATENCIES = (("tx-latency", "tx_latency_us"), ("rx-latency", "rx_latency_us"))


def latency_figures(log, scale):
    """Lone frames end to end: TX from write() to the end of frame on the
    bus, RX from there to recvmsg(), from the last run of each."""
    return {key: distribution_us(log[what][-1], "lat", scale)
            for what, key in LATENCIES if log.get(what)}


def rt_figures(log):
    """The latency-only run on the PREEMPT_RT kernel."""
    setup = log["setup"][0]
    kept = [log[what][-1] for what, _ in LATENCIES if log.get(what)]
    fig = latency_figures(log, setup["time_scale"])
    fig["valid"] = all(k.get("stalls", 0) == 0 for k in kept)
    return fig


def profile_figures(log):
    """One driver on one chip with SPI time on (a board profile).  The
    guest repeats a measurement across which the bus clock stalled; the
    figures come from the last try of each, and clock_stalls counts the
    stalls within those."""
    setup = log["setup"][0]
    idle = log["idle"][-1]
    rx = log["cpu-rx"][-1]
    tx = log["cpu-tx"][-1]
    floods = last_by_bitrate(log.get("rx", []))
    bursts = last_by_bitrate(log.get("tx", []))
    kept = [idle, rx, tx] + floods + bursts + [
        log[w][-1] for w in ("rxts", "tx-latency", "rx-latency") if log.get(w)]
    boot_stalls = int(log["done"][0].get("clock_stalls", 0) - setup.get("clock_stalls", 0))
    if all("stalls" in k for k in kept):
        stalls = int(sum(k["stalls"] for k in kept))
    else:
        stalls = boot_stalls
    tries = sum(len(log.get(w, []))
                for w in ("idle", "cpu-rx", "cpu-tx", "rx", "tx", "rxts",
                          "tx-latency", "rx-latency"))
    cpu = cpu_us_per_frame(rx, idle, rx["received"])
    scale = setup["time_scale"]
    fig = {
        "rx_max_lossless_bitrate": max_lossless(floods),
        "rx_loss": {},
        "rx_overflows": {},
        "tx_bus_utilisation": {},
        "tx_idle_us_per_gap": {},
        "spi_busy_us_per_rx_frame": spi_us(rx, "frames_rx"),
        "spi_busy_us_per_tx_frame": spi_us(tx, "frames_tx"),
        "spi_late_us_per_rx_frame": late_us(rx, "frames_rx"),
        "spi_late_us_per_tx_frame": late_us(tx, "frames_tx"),
        "rx_spi_transfers_per_frame": per_frame(rx["spi_transfers"], rx["frames_rx"]),
        "tx_spi_transfers_per_frame": per_frame(tx["spi_transfers"], tx["frames_tx"]),
        "cpu_us_per_rx_frame": cpu,
        "cpu_us_per_rx_frame_over_time_scale": None if cpu is None else round(cpu / scale, 2),
        # all the guest's busy time in the burst, idle load included: an
        # upper bound that needs no subtraction of a noisy baseline
        "cpu_us_per_rx_frame_bound_over_time_scale":
            per_frame(rx["busy_cs"] * 1e4 / scale, rx["received"]),
        "cpu_burst_loss": round(1 - rx["received"] / rx["frames"], 4),
        "rx_timestamp_error_us": rx_timestamp_error(log, scale),
        **latency_figures(log, scale),
        "clock_stalls": stalls,
        "clock_stalls_boot": boot_stalls,
        "measurements_repeated": tries - len(kept),
        "valid": stalls == 0,
    }
    for run in floods:
        rate = str(int(run["bitrate"]))
        fig["rx_loss"][rate] = round(1 - run["received"] / run["frames"], 4)
        fig["rx_overflows"][rate] = int(run["overflows"])
    add_tx_figures(fig, bursts)
    return fig


def profile_setup(log):
    s = log["setup"][0]
    return {
        "kernel": "6.1",
        "time_scale": int(s["time_scale"]),
        "frames_per_bitrate": int(s["frames"]),
        "cpu_frames": int(s["cpu_frames"]),
        "cpu_bitrate": int(s["cpu_bitrate"]),
        "guest_cpus": int(s["cpus"]),
        "clocksource": s["clocksource"],
        "spi_msg_ns": int(s["spi_msg_ns"]),
        "spi_cs_setup_ns": int(s["spi_cs_setup_ns"]),
        "spi_cs_hold_ns": int(s["spi_cs_hold_ns"]),
        "spi_ctlr_max_hz": int(s["spi_ctlr_max_hz"]),
        "irq_latency_ns": int(s["irq_latency_ns"]),
    }


def collect_profiles(out):
    """{profile: {driver: {chip: figures}, "setup": ...}} of the complete runs."""
    found = {}
    for profile in PROFILES:
        paths = {(d, c): os.path.join(out, f"{profile}-{d}-{c}.console.log")
                 for d in DRIVERS for c in CHIPS}
        if not any(os.path.exists(p) for p in paths.values()):
            continue
        if not all(complete(p) for p in paths.values()):
            print(f"report: the {profile} profile's runs are incomplete, left out",
                  file=sys.stderr)
            continue
        entry = {}
        for (driver, chip), path in paths.items():
            log = parse_console(path)
            entry.setdefault("setup", profile_setup(log))
            entry.setdefault(driver, {})[chip] = profile_figures(log)
            rt = os.path.join(out, f"{profile}-rt-{driver}-{chip}.console.log")
            if complete(rt):
                entry[driver][chip]["rt"] = rt_figures(parse_console(rt))
        found[profile] = entry
    return found


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
    return os.path.exists(os.path.join(out, "mcp2510-mcp2510.console.log"))


def collect(out):
    summary = {}
    setup = None
    for driver in DRIVERS:
        chips = {}
        for chip in CHIPS:
            log = parse_console(os.path.join(out, f"{driver}-{chip}.console.log"))
            setup = setup or log["setup"][0]
            chips[chip] = driver_figures(log)
        summary[driver] = dict(chips["mcp2510"], chip="mcp2510", mcp2515=chips["mcp2515"])
    chips = {c: userspace_figures(os.path.join(out, f"userspace-{c}.txt")) for c in CHIPS}
    summary["userspace"] = dict(chips["mcp2510"], chip="mcp2510", mcp2515=chips["mcp2515"])
    summary["setup"] = {
        "kernel": "6.1",
        "time_scale": int(setup["time_scale"]),
        "frames_per_bitrate": int(setup["frames"]),
        "cpu_frames": int(setup["cpu_frames"]),
        "guest_cpus": int(setup["cpus"]),
        "clocksource": setup["clocksource"],
    }
    return summary


def fmt(value, spec="{:.2f}"):
    return "-" if value is None else spec.format(value)


def pct(value):
    return "-" if value is None else f"{100 * value:.1f}%"


def rows(summary):
    """(driver, chip, figures) in table order."""
    for driver in DRIVERS + ("userspace",):
        for chip in CHIPS:
            fig = summary[driver]
            yield driver, chip, fig if chip == "mcp2510" else fig["mcp2515"]


def cost_table(summary):
    lines = ["| driver | chip | RX SPI bytes | RX transfers | TX SPI bytes | TX transfers"
             " | IRQs per RX frame | IRQs per TX frame | CPU µs per RX frame | CPU µs per TX frame |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    for driver, chip, f in rows(summary):
        lines.append(
            f"| {driver} | {chip} | {fmt(f['rx_spi_bytes_per_frame'])}"
            f" | {fmt(f['rx_spi_transfers_per_frame'])} | {fmt(f['tx_spi_bytes_per_frame'])}"
            f" | {fmt(f['tx_spi_transfers_per_frame'])} | {fmt(f['irqs_per_frame'])}"
            f" | {fmt(f.get('tx_irqs_per_frame'))} | {fmt(f['cpu_us_per_frame'], '{:.0f}')}"
            f" | {fmt(f.get('tx_cpu_us_per_frame'), '{:.0f}')} |")
    return lines


def rate_table(summary, key, title, extra=None):
    rates = sorted({int(r) for driver, _, f in rows(summary)
                    if driver != "userspace" for r in f[key]})
    head = f"| {title} | chip | " + " | ".join(f"{r // 1000}k" for r in rates)
    head += " | zero loss up to |" if extra else " |"
    lines = [head, "|---|---|" + "---|" * (len(rates) + (1 if extra else 0))]
    for driver, chip, f in rows(summary):
        if driver == "userspace":
            continue
        cells = [pct(f[key].get(str(r))) for r in rates]
        if key == "tx_bus_utilisation":
            cells = [f"{c} ({fmt(f['tx_idle_us_per_gap'].get(str(r)), '{:.0f}')} µs)"
                     for c, r in zip(cells, rates)]
        if key == "rx_loss":
            cells = [f"{c} ({f['rx_overflows'].get(str(r), '-')})" for c, r in zip(cells, rates)]
        line = f"| {driver} | {chip} | " + " | ".join(cells)
        if extra:
            line += f" | {extra(f)} |"
        lines.append(line + ("" if extra else " |"))
    return lines


def tables(summary):
    s = summary["setup"]
    out = [f"Debian {s['kernel']} kernel in QEMU (TCG, {s['guest_cpus']} CPUs, clock source"
           f" {s['clocksource']}), mcp2510-sim.ko time_scale={s['time_scale']};"
           f" {s['frames_per_bitrate']} frames per bit rate, {s['cpu_frames']}"
           " for the per-frame costs (125 kbit/s). Userspace port: host, in-process model.", ""]
    out += ["Per 8-byte standard frame:", ""] + cost_table(summary) + [""]
    out += ["TX bus utilisation (mean idle bus time between frames, bus time):", ""]
    out += rate_table(summary, "tx_bus_utilisation", "TX") + [""]
    out += ["RX loss of a phantom flood (overflows):", ""]
    out += rate_table(summary, "rx_loss", "RX",
                      lambda f: f"{f['rx_max_lossless_bitrate'] // 1000} kbit/s"
                      if f["rx_max_lossless_bitrate"] else "none") + [""]
    return out


def khz(rate):
    return f"{rate // 1000} kbit/s" if rate else "none measured"


def profile_tables(profiles):
    out = []
    for name, entry in profiles.items():
        s = entry["setup"]
        sck = f"{s['spi_ctlr_max_hz'] / 1e6:g} MHz" if s["spi_ctlr_max_hz"] else "the chip's limit"
        out += [f"**{name}**: SPI message overhead {s['spi_msg_ns'] / 1e3:g} µs, CS setup"
                f" {s['spi_cs_setup_ns']} ns and hold {s['spi_cs_hold_ns']} ns, SCK at most {sck}"
                f" (MCP2510 5 MHz, MCP2515 10 MHz), interrupt latency"
                f" {s['irq_latency_ns'] / 1e3:g} µs; time_scale={s['time_scale']},"
                f" {s['frames_per_bitrate']} frames per flood or burst, {s['cpu_frames']}"
                f" frames at {s['cpu_bitrate'] // 1000} kbit/s for the per-frame costs.", ""]
        rates = sorted({int(r) for d in DRIVERS for c in CHIPS
                        for r in entry[d][c]["tx_bus_utilisation"]})
        out += ["| driver | chip | zero loss up to | floods: loss (overflows) | "
                + " | ".join(f"TX {r // 1000}k" for r in rates)
                + " | SPI µs per RX frame | SPI µs per TX frame | SPI late µs per RX frame"
                " | guest CPU µs per RX frame / time_scale (bound) | clock stalls |",
                "|---|---|---|---|" + "---|" * len(rates) + "---|---|---|---|---|"]
        for driver in DRIVERS:
            for chip in CHIPS:
                f = entry[driver][chip]
                floods = ", ".join(f"{int(r) // 1000}k {pct(v)} ({f['rx_overflows'][r]})"
                                   for r, v in sorted(f["rx_loss"].items(), key=lambda x: int(x[0])))
                util = [pct(f["tx_bus_utilisation"].get(str(r))) for r in rates]
                stalls = (f"{f['clock_stalls']}" + ("" if f["valid"] else " (run invalid)")
                          + f"; {f['measurements_repeated']} repeated")
                out.append(f"| {driver} | {chip} | {khz(f['rx_max_lossless_bitrate'])} | {floods}"
                           f" | " + " | ".join(util)
                           + f" | {fmt(f['spi_busy_us_per_rx_frame'])}"
                           f" | {fmt(f['spi_busy_us_per_tx_frame'])}"
                           f" | {fmt(f['spi_late_us_per_rx_frame'])}"
                           f" | {fmt(f['cpu_us_per_rx_frame_over_time_scale'])}"
                           f" ({fmt(f['cpu_us_per_rx_frame_bound_over_time_scale'])})"
                           f" | {stalls} |")
        out.append("")
        out += rx_timestamp_table(entry)
        out += latency_table(entry)
    return out


def rx_timestamp_table(entry):
    """Receive timestamp error per driver and chip, when measured."""
    figs = [(d, c, entry[d][c].get("rx_timestamp_error_us")) for d in DRIVERS for c in CHIPS]
    if not any(f for _, _, f in figs):
        return []
    out = ["Receive timestamp after the end of frame on the bus (µs of bus time,"
           " a flood at the per-frame cost bit rate):", "",
           "| driver | chip | median | 99th percentile | frames |", "|---|---|---|---|---|"]
    for driver, chip, f in figs:
        if f:
            out.append(f"| {driver} | {chip} | {fmt(f['p50'])} | {fmt(f['p99'])} | {f['frames']} |")
        else:
            out.append(f"| {driver} | {chip} | - | - | - |")
    return out + [""]


def latency_table(entry):
    """Lone frames end to end per driver and chip, on 6.1 and on
    PREEMPT_RT, when measured."""
    def cell(f, key):
        d = (f or {}).get(key)
        return f"{fmt(d['p50'])} / {fmt(d['p99'])}" if d else "-"
    rows = [(d, c, entry[d][c], entry[d][c].get("rt")) for d in DRIVERS for c in CHIPS]
    if not any(f.get("tx_latency_us") for _, _, f, _ in rows):
        return []
    out = ["Lone frames end to end (µs of bus time, median / 99th percentile): TX from"
           " write() to the end of frame on the bus, RX from there to recvmsg():", "",
           "| driver | chip | TX 6.1 | RX 6.1 | TX PREEMPT_RT | RX PREEMPT_RT |",
           "|---|---|---|---|---|---|"]
    for driver, chip, f, rt in rows:
        out.append(f"| {driver} | {chip} | {cell(f, 'tx_latency_us')} | {cell(f, 'rx_latency_us')}"
                   f" | {cell(rt, 'tx_latency_us')} | {cell(rt, 'rx_latency_us')} |")
    return out + [""]


def write_plot_data(out, summary):
    path = os.path.join(out, "plot.dat")
    with open(path, "w", encoding="utf-8") as f:
        for driver in DRIVERS:
            for chip in CHIPS:
                fig = summary[driver] if chip == "mcp2510" else summary[driver]["mcp2515"]
                f.write(f"# {driver}.ko on {chip.upper()}: bitrate util_pct loss_pct\n")
                for rate in sorted(fig["rx_loss"], key=int):
                    util = fig["tx_bus_utilisation"].get(rate)
                    f.write(f"{rate} {'NaN' if util is None else 100 * util}"
                            f" {100 * fig['rx_loss'][rate]}\n")
                f.write("\n\n")
    return path


def plot(out, summary, svg):
    data = write_plot_data(out, summary)
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


def main():
    if len(sys.argv) not in (2, 3):
        sys.exit(__doc__)
    out = sys.argv[1]
    doc = sys.argv[2] if len(sys.argv) == 3 else None
    base = have_base(out)
    summary = collect(out) if base else {}
    profiles = collect_profiles(out)
    if not base and not profiles:
        sys.exit(f"report: no bench logs in {out}")
    if profiles:
        summary["profiles"] = profiles
    with open(os.path.join(out, "summary.json"), "w", encoding="utf-8") as f:
        json.dump(summary, f, indent=2, sort_keys=True)
        f.write("\n")
    done = [os.path.join(out, "summary.json")]
    if base:
        lines = tables(summary)
        print("\n".join(lines))
        svg = os.path.join(out, "performance.svg")
        if doc:
            svg = os.path.join(os.path.dirname(os.path.abspath(doc)), "performance.svg")
            update_doc(doc, lines)
        plot(out, summary, svg)
        done.append(svg)
    if profiles:
        lines = profile_tables(profiles)
        print("\n".join(lines))
        if doc:
            update_doc(doc, lines, PROFILES_BEGIN, PROFILES_END)
        for name, entry in profiles.items():
            for driver in DRIVERS:
                for chip in CHIPS:
                    fig = entry[driver][chip]
                    for kernel, f in (("6.1", fig), ("PREEMPT_RT", fig.get("rt"))):
                        if f and not f["valid"]:
                            print(f"bench: {name}: {driver} on {chip} ({kernel}): a clock"
                                  " stall fired, the run is invalid", file=sys.stderr)
    print(f"bench: {', '.join(done)}")


if __name__ == "__main__":
    main()
