"""The bench's figures as markdown tables (docs/performance.md) and as
headlines, each claim with the band in which it holds over the cost
scales that ran."""
from pieces import describe

DRIVERS = ("mcp2510", "mcp251x")
CHIPS = ("mcp2510", "mcp2515")


def fmt(value, spec="{:.2f}"):
    return "-" if value is None else spec.format(value)


def pct(value):
    return "-" if value is None else f"{100 * value:.1f}%"


def khz(rate):
    if rate is None:
        return "missing"
    return f"{rate // 1000} kbit/s" if rate else "none measured"


def damage_text(d):
    """lost/duplicated/reordered/corrupted, as 'l/d/r/c'."""
    return "/".join(str(d[k]) for k in ("lost", "duplicated", "reordered", "corrupted"))


def rows(summary):
    """(driver, chip, figures) of the base profile in table order."""
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
    head = [title, "chip"] + [f"{r // 1000}k" for r in rates]
    head += ["zero loss up to"] if extra else []
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for driver, chip, f in rows(summary):
        if driver == "userspace":
            continue
        cells = [pct(f[key].get(str(r))) for r in rates]
        if key == "tx_bus_utilisation":
            cells = [f"{c} ({fmt(f['tx_idle_us_per_gap'].get(str(r)), '{:.0f}')} µs)"
                     for c, r in zip(cells, rates)]
        if key == "rx_loss":
            cells = [f"{c} ({f['rx_overflows'].get(str(r), '-')})" for c, r in zip(cells, rates)]
        cells = [driver, chip] + cells + ([extra(f)] if extra else [])
        lines.append("| " + " | ".join(cells) + " |")
    return lines


def provenance(run):
    """When and on which commit a piece was measured, and if stale, why."""
    stale = f"; stale: {', '.join(run['stale'])}" if run["stale"] else ""
    return describe(run) + stale


def flood_sizes(s):
    """The frames of the floods and bursts of a run's settings."""
    if "tx_frames" not in s:
        return f"{s['flood_frames']} frames per flood or burst"
    return (f"RX floods of {s['flood_frames']} frames after probes of {s['probe_frames']},"
            f" TX bursts of {s['tx_frames']}")


def tables(summary):
    s = summary["setup"]
    out = [f"{provenance(summary['run'])}: Debian {s['kernel']} kernel in QEMU (TCG, {s['guest_cpus']} CPUs, clock source"
           f" {s['clocksource']}), mcp2510-sim.ko time_scale={s['time_scale']};"
           f" {flood_sizes(s)}, counted end to end,"
           f" {s['cpu_frames']} for the per-frame costs (125 kbit/s)."
           " Userspace port: host, in-process model.", ""]
    out += ["Per 8-byte standard frame:", ""] + cost_table(summary) + [""]
    out += ["TX bus utilisation (mean idle bus time between frames, bus time):", ""]
    out += rate_table(summary, "tx_bus_utilisation", "TX") + [""]
    out += ["RX loss of a phantom flood at the socket (overflows):", ""]
    out += rate_table(summary, "rx_loss", "RX",
                      lambda f: khz(f["rx_max_lossless_bitrate"])) + [""]
    return out


def profile_tables(profiles):
    out = []
    for name, scales in profiles.items():
        for label, entry in scales.items():
            out += profile_table(f"{name} {label}", entry)
    return out


def profile_table(title, entry):
    s = entry["setup"]
    sck = f"{s['spi_ctlr_max_hz'] / 1e6:g} MHz" if s["spi_ctlr_max_hz"] else "the chip's limit"
    out = [f"**{title}** ({provenance(entry['run'])}): costs at {s['cost_scale_pct']} %: SPI message overhead"
           f" {s['spi_msg_ns'] / 1e3:g} µs, CS setup {s['spi_cs_setup_ns']} ns and hold"
           f" {s['spi_cs_hold_ns']} ns, SCK at most {sck} (MCP2510 5 MHz, MCP2515 10 MHz),"
           f" interrupt latency {s['irq_latency_ns'] / 1e3:g} µs (before scaling);"
           f" time_scale={s['time_scale']}, {flood_sizes(s)},"
           f" {s['cpu_frames']} frames at {s['cpu_bitrate'] // 1000} kbit/s for the"
           " per-frame costs.", ""]
    rates = sorted({int(r) for d in DRIVERS for c in CHIPS
                    for r in entry[d][c]["tx_bus_utilisation"]})
    out += ["| driver | chip | zero loss up to | floods: lost/dup/reord/corrupt of frames | "
            + " | ".join(f"TX {r // 1000}k" for r in rates)
            + " | SPI µs per RX frame | SPI µs per TX frame | SPI late µs per RX frame"
            " | guest CPU µs per RX frame / time_scale (bound) | missing |",
            "|---|---|---|---|" + "---|" * len(rates) + "---|---|---|---|---|"]
    scale = s["time_scale"]
    for driver in DRIVERS:
        for chip in CHIPS:
            f = entry[driver][chip]
            floods = ", ".join(f"{int(r) // 1000}k {damage_text(d)} of {f['rx_frames'][r]}"
                               for r, d in sorted(f["rx_damage"].items(), key=lambda x: int(x[0]))
                               if d is not None)
            util = [pct(f["tx_bus_utilisation"].get(str(r))) for r in rates]
            cpu = f["cpu_us_per_frame"]
            bound = f["cpu_us_per_frame_bound"]
            out.append(f"| {driver} | {chip} | {khz(f['rx_max_lossless_bitrate'])} | {floods}"
                       f" | " + " | ".join(util)
                       + f" | {fmt(f['spi_busy_us_per_rx_frame'])}"
                       f" | {fmt(f['spi_busy_us_per_tx_frame'])}"
                       f" | {fmt(f['spi_late_us_per_rx_frame'])}"
                       f" | {fmt(None if cpu is None else cpu / scale)}"
                       f" ({fmt(None if bound is None else bound / scale)})"
                       f" | {', '.join(f['missing']) or '-'} |")
    out.append("")
    return out + compare_table(entry, s)


def compare_table(entry, s):
    """Latency and receive timestamps where both drivers keep up and,
    apart, at saturation: median / 99th percentile, µs of bus time."""
    sat = str(s["saturation_bitrate"])
    rates = sorted({r for d in DRIVERS for c in CHIPS
                    for r in entry[d][c]["tx_latency_us"]}, key=int)
    if not rates:
        return []

    def cell(dist):
        return f"{fmt(dist['p50'])} / {fmt(dist['p99'])}" if dist else "-"
    heads = [f"{int(r) // 1000}k{' (saturated)' if r == sat else ''}" for r in rates]
    out = ["Median / 99th percentile in µs of bus time: TX lone frames from write() to the"
           " end of frame on the bus, RX from there to recvmsg(), receive timestamp after the"
           " end of frame in a flood; on 6.1 and on PREEMPT_RT (rt):", "",
           "| driver | chip | figure | " + " | ".join(heads) + " |",
           "|---|---|---|" + "---|" * len(rates)]
    for driver in DRIVERS:
        for chip in CHIPS:
            f = entry[driver][chip]
            rt = f.get("rt") or {}
            for label, src, key in (("TX", f, "tx_latency_us"), ("RX", f, "rx_latency_us"),
                                    ("stamp", f, "rx_timestamp_error_us"),
                                    ("TX rt", rt, "tx_latency_us"),
                                    ("RX rt", rt, "rx_latency_us")):
                cells = [cell(src.get(key, {}).get(r)) for r in rates]
                out.append(f"| {driver} | {chip} | {label} | " + " | ".join(cells) + " |")
    return out + [""]


def band(values):
    """'A' or 'A-B' of the values that are there; None when none is."""
    have = sorted(v for v in values if v is not None)
    if not have:
        return None
    lo, hi = have[0], have[-1]
    return f"{lo:g}" if lo == hi else f"{lo:g}-{hi:g}"


def headlines(profiles):
    """Each claim with its band over the cost scales of its profile."""
    out = []
    for name, scales in profiles.items():
        labels = ", ".join(scales)
        for chip in CHIPS:
            rx = {d: [e[d][chip]["rx_max_lossless_bitrate"] for e in scales.values()]
                  for d in DRIVERS}
            ours = band([None if r is None else r / 1000 for r in rx["mcp2510"]])
            theirs = band([None if r is None else r / 1000 for r in rx["mcp251x"]])
            ratio = band([round(a / b, 2) if a and b else None
                          for a, b in zip(rx["mcp2510"], rx["mcp251x"])])
            out.append(f"{name} ({labels}), {chip.upper()}: lossless at the socket up to"
                       f" {ours or '-'} kbit/s (this driver) and {theirs or '-'} kbit/s"
                       f" (mcp251x); ratio {ratio or '-'}")
            sat = next(iter(scales.values()))["setup"]["saturation_bitrate"]
            for rate in (str(r) for r in compare_rates(scales)):
                where = " (saturated)" if int(rate) == sat else ""
                for key, what in (("rx_latency_us", "RX latency"),
                                  ("rx_timestamp_error_us", "timestamp error")):
                    med = {d: band([e[d][chip].get(key, {}).get(rate, {}).get("p50")
                                    for e in scales.values()]) for d in DRIVERS}
                    out.append(f"{name} ({labels}), {chip.upper()}, {int(rate) // 1000} kbit/s{where}:"
                               f" {what} median {med['mcp2510'] or '-'} µs (this driver),"
                               f" {med['mcp251x'] or '-'} µs (mcp251x)")
    return out


def compare_rates(scales):
    entry = next(iter(scales.values()))
    rates = {int(r) for d in DRIVERS for c in CHIPS for r in entry[d][c]["tx_latency_us"]}
    return sorted(rates)
