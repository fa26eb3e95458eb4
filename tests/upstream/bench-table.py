"""The figures of make upstream-bench: one row per figure, one column per
(step of the series, chip), from the consoles of tests/bench/guest.sh
runs of mcp251x with that step's module.

    python3 bench-table.py DIR STEP... : DIR/step-STEP-CHIP.console.log
"""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "bench"))
import figures  # noqa: E402  (the bench's own reading of a console)

CHIPS = ("mcp2510", "mcp2515")


def at(table, rate, key=None):
    value = (table or {}).get(str(rate))
    if value is None or key is None:
        return value
    return value.get(key)


def rows(fig):
    """(label, value) of the figures the series' patches claim to move."""
    out = [("RX lossless up to (bit/s)", fig.get("rx_max_lossless_bitrate"))]
    for rate in (500000, 1000000):
        damage = at(fig.get("rx_damage"), rate)
        out.append((f"RX flood {rate // 1000}k: lost/reordered",
                    None if damage is None else f"{damage['lost']}/{damage['reordered']}"))
    for rate in (125000, 500000, 1000000):
        out.append((f"TX utilisation {rate // 1000}k", at(fig.get("tx_bus_utilisation"), rate)))
    for key, label in (("rx_spi_transfers_per_frame", "RX SPI transfers/frame"),
                       ("rx_spi_bytes_per_frame", "RX SPI bytes/frame"),
                       ("tx_spi_transfers_per_frame", "TX SPI transfers/frame"),
                       ("tx_spi_bytes_per_frame", "TX SPI bytes/frame"),
                       ("irqs_per_frame", "RX interrupts/frame"),
                       ("cpu_us_per_frame", "RX CPU us/frame"),
                       ("tx_cpu_us_per_frame", "TX CPU us/frame")):
        out.append((label, fig.get(key)))
    out.append(("TX latency 250k p50 (us)", at(fig.get("tx_latency_us"), 250000, "p50")))
    out.append(("RX stamp - end 250k p50 (us)",
                at(fig.get("rx_timestamp_error_us"), 250000, "p50")))
    out.append(("missing measurements", len(fig.get("missing", []))))
    return out


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    directory, steps = sys.argv[1], sys.argv[2:]
    columns, table = [], {}
    for step in steps:
        for chip in CHIPS:
            log = os.path.join(directory, f"step-{step}-{chip}.console.log")
            columns.append(f"{step}/{chip[-4:]}")
            for label, value in rows(figures.figures(figures.parse_console(log))):
                table.setdefault(label, []).append("-" if value is None else str(value))
    width = max(len(label) for label in table)
    print(f"{'step/chip':<{width}}  " + "  ".join(f"{c:>12}" for c in columns))
    for label, values in table.items():
        print(f"{label:<{width}}  " + "  ".join(f"{v:>12}" for v in values))


if __name__ == "__main__":
    main()
