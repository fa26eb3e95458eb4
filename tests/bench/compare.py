"""The headline figures before and after the calibration of the board
profiles: the "before" column from tests/bench/before.json (the figures
docs/performance.md stated for the old model), the "after" columns from
the pieces of this summary at 0.5x, 1x and 2x, or why there is none.

Each figure is a claim the old figures made; "held at" lists the scales
at which the new figure says the same: the same zero-loss bit rate, the
same ratio, or a TX bus utilisation within one percentage point.
"""
import json
import os

SCALES = ("0.5x", "1x", "2x")
PROFILES = ("pi", "pi-rt", "slow")
CHIPS = ("mcp2510", "mcp2515")
NOT_MEASURED = "not yet measured"


def load_before():
    here = os.path.dirname(os.path.abspath(__file__))
    with open(os.path.join(here, "before.json"), encoding="utf-8") as f:
        return json.load(f)


def lossless_rate(entry, driver, chip):
    return entry[driver][chip]["rx_max_lossless_bitrate"]


def utilisation_1m(entry, driver, chip):
    return entry[driver][chip]["tx_bus_utilisation"].get("1000000")


def ratio(ours, theirs):
    return round(ours / theirs, 2) if ours and theirs else None


def kbit(rate):
    return f"{rate // 1000} kbit/s" if rate else "none"


def percent(value):
    return f"{100 * value:.1f}%"


def same_util(before, after):
    return abs(before - after) <= 0.01


def equal(before, after):
    return before == after


LOSSLESS = ("rx_max_lossless_bitrate", lossless_rate)
UTILISATION = ("tx_bus_utilisation_1m", utilisation_1m)
# (label, driver or None for the ratio, (before.json's key, the figure of
# an entry), format, the new figure says the same as the old one)
ROWS = (
    ("zero-loss bit rate", "mcp2510", LOSSLESS, kbit, equal),
    ("zero-loss bit rate", "mcp251x", LOSSLESS, kbit, equal),
    ("zero-loss ratio, this driver / mcp251x", None, LOSSLESS, "{:g}".format, equal),
    ("TX bus utilisation at 1 Mbit/s", "mcp2510", UTILISATION, percent, same_util),
    ("TX bus utilisation at 1 Mbit/s", "mcp251x", UTILISATION, percent, same_util),
)


def figure(entry, driver, get, chip):
    if driver is None:
        return ratio(get(entry, "mcp2510", chip), get(entry, "mcp251x", chip))
    return get(entry, driver, chip)


def before_figure(before, profile, chip, driver, key):
    old = before["profiles"].get(profile, {}).get(chip)
    if old is None:
        return None
    if driver is None:
        return ratio(old[key]["mcp2510"], old[key]["mcp251x"])
    return old[key][driver]


def after_cell(profiles, profile, label, chip, driver, get, show):
    """(cell text, figure or None) of one scale."""
    entry = profiles.get(profile, {}).get(label)
    if entry is None:
        return NOT_MEASURED, None
    if entry.get("run", {}).get("stale"):
        return "stale", None
    value = figure(entry, driver, get, chip)
    return ("missing" if value is None else show(value)), value


def before_after(profiles):
    """The table's lines (markdown)."""
    before = load_before()
    out = [f"Before: {before['source']}. After: this model, from the pieces in"
           " build/bench/summary.json (\"not yet measured\" where a piece has not"
           " run; \"stale\" where it ran on other sources or settings; \"missing\""
           " where a measurement stalled in each try).", "",
           "| profile | chip | figure | driver | before (1x) | after 0.5x | after 1x"
           " | after 2x | held at |", "|---|---|---|---|---|---|---|---|---|"]
    for profile in PROFILES:
        for chip in CHIPS:
            for what, driver, (key, get), show, same in ROWS:
                old = before_figure(before, profile, chip, driver, key)
                cells, held, measured = [], [], False
                for label in SCALES:
                    text, value = after_cell(profiles, profile, label, chip, driver, get, show)
                    cells.append(text)
                    measured = measured or text != NOT_MEASURED
                    if value is not None and old is not None and same(old, value):
                        held.append(label)
                if old is None:
                    held_text = "-"
                elif not measured:
                    held_text = NOT_MEASURED
                else:
                    held_text = ", ".join(held) or "none"
                out.append(f"| {profile} | {chip.upper()} | {what} | {driver or 'both'}"
                           f" | {'not run' if old is None else show(old)}"
                           f" | {' | '.join(cells)} | {held_text} |")
    return out + [""]
