"""Where each piece of the bench's figures comes from, and whether it is
stale.

A piece is one directory of logs that one run of tests/bench/run wrote:
OUTDIR/base/ or OUTDIR/<profile>/<scale>x/.  Its run.txt says when it was
measured (date, UTC), on which commit, a hash of the sources its figures
depend on and one of the settings it ran with.  Pieces of several runs
add up to one summary; a piece measured on other sources or with other
settings than the current run's (BENCH_SOURCES, BENCH_SETTINGS_BASE,
BENCH_SETTINGS_TIMED in the environment, set by tests/bench/run) is
stale: its figures stay in summary.json, marked, but make no headline,
and the report fails until it is measured again.
"""
import os


def read_run(piece_dir):
    """The piece's run.txt as a dict ({} when there is none: a piece of
    a run from before run.txt, which counts as stale once sources are
    known)."""
    path = os.path.join(piece_dir, "run.txt")
    if not os.path.exists(path):
        return {}
    out = {}
    with open(path, encoding="utf-8") as f:
        for line in f:
            key, sep, value = line.strip().partition("=")
            if sep:
                out[key] = value
    return out


def stale_reasons(run, kind, env=None):
    """Why a piece of KIND ("base" or "timed") with run.txt RUN is stale:
    [] when it is not, or when the current sources and settings are not
    known (report.py on its own)."""
    env = os.environ if env is None else env
    reasons = []
    sources = env.get("BENCH_SOURCES")
    settings = env.get(f"BENCH_SETTINGS_{kind.upper()}")
    if sources and run.get("sources") != sources:
        reasons.append("measured on other sources")
    if settings and run.get("settings") != settings:
        reasons.append("measured with other settings")
    return reasons


def describe(run):
    """'measured DATE at COMMIT' for a table's heading."""
    if not run:
        return "when and on which commit not recorded"
    return f"measured {run.get('date', '?')} at {run.get('commit', '?')}"


def piece_info(piece_dir, kind):
    """run.txt's fields plus "stale": the reasons, [] when fresh."""
    run = read_run(piece_dir)
    return dict(run, stale=stale_reasons(run, kind))
