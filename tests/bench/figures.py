"""The figures of one run of tests/bench/guest.sh (one driver on one chip),
from its console's "bench:" lines.

A measurement is one (what, bit rate); the guest tries it again while it
is void (the bus clock stalled across it, or the bus monitor lost records
of a TX burst), and the figures come from its last try.  A last try that
is still void gives no figure: the measurement is listed as missing.

Floods and bursts are counted end to end by can-flood: lost, duplicated,
reordered and corrupted frames.  Lossless means all four are zero.  The
RX search probes each bit rate with a short flood ("rx-probe") and floods
it in full ("rx") only when the probe was lossless: a rate's verdict is
its full flood's where there is one, else its probe's (which then lost
frames: damage in a short flood decides as well as in a long one).
"""
import re
import sys

DAMAGE = ("lost", "duplicated", "reordered", "corrupted")


def parse_console(path):
    """The guest's measurements: {what: [fields, ...]} in order."""
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


def void(run):
    return run.get("stalls", 0) > 0 or run.get("monitor_missed", 0) > 0


def last_tries(log, what):
    """{bit rate (None without one): the last try} of WHAT, by bit rate."""
    kept = {}
    for run in log.get(what, []):
        rate = run.get("bitrate")
        kept[None if rate is None else int(rate)] = run
    return dict(sorted(kept.items(), key=lambda kv: kv[0] or 0))


class Run:
    """The kept tries of one log and the measurements missing from it."""

    def __init__(self, log):
        self.log = log
        self.missing = []
        self.missing_rates = {}
        self.tries = 0
        self.kept = 0

    def get(self, what):
        """{bit rate: run} of WHAT's valid last tries."""
        out = {}
        self.tries += len(self.log.get(what, []))
        for rate, run in last_tries(self.log, what).items():
            self.kept += 1
            if void(run):
                self.missing.append(what if rate is None else f"{what} {rate}")
                self.missing_rates.setdefault(what, []).append(rate)
            else:
                out[rate] = run
        return out

    def one(self, what):
        """The valid last try of WHAT, at whatever bit rate, or None."""
        runs = self.get(what)
        return next(iter(runs.values()), None)


def per_frame(value, frames):
    return round(value / frames, 2) if frames else None


def unique(run):
    """Frames of the flood that arrived (each counted once)."""
    return run["frames"] - run["lost"]


def lossless(run):
    return all(run[k] == 0 for k in DAMAGE)


def damage(run):
    return {k: int(run[k]) for k in DAMAGE}


def loss_bound(run):
    """The loss rate's 95 % upper bound: with none of n frames lost, 3/n
    (the rule of three); else the measured rate."""
    n = run["frames"]
    return round(3 / n if run["lost"] == 0 else run["lost"] / n, 4)


def cpu_us_per_frame(run, idle, frames, less_us=0):
    """Busy CPU time of a burst less that of the same time without one
    (and less LESS_US, a far-side counter's own time)."""
    if not frames or idle is None or run is None:
        return None
    baseline = idle["busy_cs"] * run["window_cs"] / idle["window_cs"]
    return round(((run["busy_cs"] - baseline) * 1e4 - less_us) / frames, 1)


def tx_utilisation(run):
    """Frames per second on the bus over the most that length allows, and
    the mean idle time per gap in µs."""
    n = run["mon_frames"]
    if n < 2 or run["mon_span_ns"] <= 0:
        return None, None
    per_second = (n - 1) * 1e9 / run["mon_span_ns"]
    most = run["bitrate"] / run["mon_bits"]
    return round(per_second / most, 4), round(run["mon_idle_ns"] / (n - 1) / 1e3, 2)


def max_lossless(runs):
    """The highest flooded bit rate that was lossless below every lossy
    one; 0 when none was."""
    lossy = [r["bitrate"] for r in runs if not lossless(r)]
    ok = [r["bitrate"] for r in runs if lossless(r)
          and (not lossy or r["bitrate"] < min(lossy))]
    return int(max(ok)) if ok else 0


def distribution_us(run, name, scale):
    """The NAME_* percentiles (ns of real time) in µs of bus time (real
    time over time_scale, as a board would see it)."""
    def us(ns):
        return round(ns / 1e3 / scale, 2)
    return {
        "p50": us(run[f"{name}_p50_ns"]),
        "p99": us(run[f"{name}_p99_ns"]),
        "max": us(run[f"{name}_max_ns"]),
        "frames": int(run[f"{name}_n"]),
        "not_on_bus": int(run[f"{name}_missing"]),
    }


def by_rate(runs, name, scale):
    return {str(rate): distribution_us(run, name, scale) for rate, run in runs.items()}


def latency_figures(r, scale):
    """Lone frames end to end (TX from write() to the end of frame on the
    bus, RX from there to recvmsg()) and receive timestamps in a flood,
    by bit rate."""
    fig = {
        "tx_latency_us": by_rate(r.get("tx-latency"), "lat", scale),
        "rx_latency_us": by_rate(r.get("rx-latency"), "lat", scale),
    }
    if "rxts" in r.log or "idle" in r.log:
        fig["rx_timestamp_error_us"] = by_rate(r.get("rxts"), "err", scale)
    return fig


def flood_figures(fig, floods, bursts, r):
    """RX loss and damage, TX utilisation and damage, by bit rate (None
    at a bit rate whose measurement is missing)."""
    fig.update(rx_loss={}, rx_damage={}, rx_frames={}, rx_loss_bound_95={}, rx_overflows={},
               rx_sock_drops={}, tx_bus_utilisation={}, tx_idle_us_per_gap={},
               tx_damage={})
    rx_keys = ("rx_loss", "rx_damage", "rx_loss_bound_95")
    for what, keys in (("rx-probe", rx_keys), ("rx", rx_keys),
                       ("tx", ("tx_bus_utilisation", "tx_idle_us_per_gap", "tx_damage"))):
        for rate in r.missing_rates.get(what, []):
            for key in keys:
                fig[key][str(rate)] = None
    for rate, run in floods.items():
        key = str(rate)
        fig["rx_loss"][key] = round(run["lost"] / run["frames"], 4)
        fig["rx_damage"][key] = damage(run)
        fig["rx_frames"][key] = int(run["frames"])
        fig["rx_loss_bound_95"][key] = loss_bound(run)
        fig["rx_overflows"][key] = int(run["overflows"])
        fig["rx_sock_drops"][key] = int(run["sock_drops"])
    for rate, run in bursts.items():
        key = str(rate)
        fig["tx_bus_utilisation"][key], fig["tx_idle_us_per_gap"][key] = tx_utilisation(run)
        fig["tx_damage"][key] = damage(run)


def figures(log):
    """Every figure of one driver on one chip, and "missing": the
    measurements that were void in each of their tries."""
    setup = log["setup"][0]
    scale = setup["time_scale"]
    r = Run(log)
    fig = latency_figures(r, scale)
    idle = r.one("idle")
    rx = r.one("cpu-rx")
    tx = r.one("cpu-tx")
    floods = r.get("rx-probe")
    floods.update(r.get("rx"))
    bursts = r.get("tx")
    if "idle" in log:
        flood_figures(fig, floods, bursts, r)
        fig.update(cpu_figures(rx, tx, idle))
        if "rx-search-incomplete" in log:
            r.missing.append("rx search")
            fig["rx_max_lossless_bitrate"] = None
        elif any(m.split()[0] in ("rx", "rx-probe") for m in r.missing):
            fig["rx_max_lossless_bitrate"] = None
        else:
            fig["rx_max_lossless_bitrate"] = max_lossless(list(floods.values()))
    fig["clock_stalls_boot"] = int(log["done"][0].get("clock_stalls", 0)
                                   - setup.get("clock_stalls", 0))
    fig["measurements_repeated"] = r.tries - r.kept
    # the guest's uptime at its end: what the boot cost, repeats included
    fig["guest_seconds"] = log["done"][0].get("up")
    fig["missing"] = r.missing
    return fig


def cpu_figures(rx, tx, idle):
    """Per-frame costs from the long bursts (None where one is missing)."""
    def of(run, f):
        return None if run is None else f(run)
    rx_frames = of(rx, unique)
    return {
        "rx_spi_bytes_per_frame": of(rx, lambda r: per_frame(r["spi_bytes"], r["frames_rx"])),
        "rx_spi_transfers_per_frame":
            of(rx, lambda r: per_frame(r["spi_transfers"], r["frames_rx"])),
        "tx_spi_bytes_per_frame": of(tx, lambda r: per_frame(r["spi_bytes"], r["frames_tx"])),
        "tx_spi_transfers_per_frame":
            of(tx, lambda r: per_frame(r["spi_transfers"], r["frames_tx"])),
        "irqs_per_frame": of(rx, lambda r: per_frame(r["irqs_delivered"], r["frames_rx"])),
        "tx_irqs_per_frame": of(tx, lambda r: per_frame(r["irqs_delivered"], r["frames_tx"])),
        "spi_busy_us_per_rx_frame":
            of(rx, lambda r: per_frame(r.get("spi_busy_ns", 0) / 1e3, r["frames_rx"])),
        "spi_busy_us_per_tx_frame":
            of(tx, lambda r: per_frame(r.get("spi_busy_ns", 0) / 1e3, r["frames_tx"])),
        "spi_late_us_per_rx_frame":
            of(rx, lambda r: per_frame(r.get("spi_late_ns", 0) / 1e3, r["frames_rx"])),
        # the reading application's time is part of receiving; the far
        # side's counter of a TX burst is not
        "cpu_us_per_frame": cpu_us_per_frame(rx, idle, rx_frames),
        "tx_cpu_us_per_frame": cpu_us_per_frame(tx, idle, of(tx, lambda r: r["frames_tx"]),
                                                of(tx, lambda r: r["cpu_us"]) or 0),
        # all the guest's busy time in the burst, idle load included: an
        # upper bound that needs no subtraction of a noisy baseline
        "cpu_us_per_frame_bound": of(rx, lambda r: per_frame(r["busy_cs"] * 1e4, rx_frames)),
        "cpu_burst_loss": of(rx, lambda r: round(r["lost"] / r["frames"], 4)),
        "cpu_burst_damage": of(rx, damage),
    }
