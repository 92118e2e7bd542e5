#!/usr/bin/env python3
"""Mixing curves of one or more runs: the Lacey index M and 1 - RSD against impeller
revolutions, on linear and logarithmic revolution axes (seed paper Figs. 7-10).

    plot_mixing.py --run case_a=out/a/mixing.csv --run case_b=out/b/mixing.csv --out-dir plots

reads the runs' mixing logs (docs/MIXING.md: time,step,revolutions,lacey,rsd,
one_minus_rsd,samples,particles_per_sample,concentration) and writes
<out-dir>/<prefix>_lacey.png, _lacey_log.png, _one_minus_rsd.png and
_one_minus_rsd_log.png. A log whose scene gave no revolution_period has an empty
revolutions column: --rpm converts its time. Needs numpy and matplotlib.
"""
import argparse
import csv
import math
import os
import sys

import numpy as np

# What each figure shows: CSV column, axis label, file name part.
STATISTICS = [("lacey", "Lacey index M", "lacey"), ("one_minus_rsd", "1 - RSD", "one_minus_rsd")]


class InputError(Exception):
    """Bad input: the message says what and where; main() exits non-zero with it."""


def parse_arguments(argv):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0], epilog=__doc__.split("\n\n", 1)[1],
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--run", action="append", required=True, metavar="LABEL=MIXING.CSV",
                   help="a run's mixing log and the label its curve gets in the legend (repeatable)")
    p.add_argument("--out-dir", default=".", help="directory for the PNG files (made if missing; default .)")
    p.add_argument("--prefix", default="mixing", help="start of the PNG file names (default mixing)")
    p.add_argument("--rpm", action="append", default=[], metavar="[LABEL=]RPM",
                   help="impeller speed [1/min] to turn time into revolutions where a log's revolutions column is "
                        "empty; RPM alone applies to every run, LABEL=RPM to one (repeatable)")
    p.add_argument("--start", type=float, default=0.0,
                   help="with --rpm: the time [s] the impeller started, revolution 0 (default 0)")
    return p.parse_args(argv)


def parse_runs(options):
    """[(label, path)] in the order given; labels must be unique."""
    runs = []
    for option in options:
        label, sep, path = option.partition("=")
        if not sep or not label or not path:
            raise InputError(f"--run {option}: expected LABEL=PATH, e.g. case_a=out/a/mixing.csv")
        if label in (l for l, _ in runs):
            raise InputError(f"--run {option}: the label '{label}' is given twice")
        runs.append((label, path))
    return runs


def parse_rpm(options, labels):
    """{label: rpm}; a bare number applies to every run."""
    rpm = {}
    for option in options:
        label, sep, value = option.rpartition("=")
        targets = [label] if sep else labels
        if sep and label not in labels:
            raise InputError(f"--rpm {option}: no run is labelled '{label}' (runs: {', '.join(labels)})")
        try:
            speed = float(value)
        except ValueError:
            speed = float("nan")
        if not (math.isfinite(speed) and speed > 0):
            raise InputError(f"--rpm {option}: the speed must be a positive number of revolutions per minute")
        rpm.update({t: speed for t in targets})
    return rpm


def read_log(path):
    """The log's columns as float arrays (an empty cell is nan); InputError for what is not a mixing log."""
    if not os.path.isfile(path):
        raise InputError(f"{path}: no such file")
    with open(path, newline="") as f:
        reader = csv.reader(f)
        header = next(reader, None)
        if not header:
            raise InputError(f"{path}: empty file, not a mixing log")
        header = [name.strip() for name in header]
        rows = [row for row in reader if row]
    missing = [c for c in ("lacey", "one_minus_rsd") if c not in header]
    if not ("revolutions" in header or "time" in header):
        missing.append("revolutions (or time)")
    if missing:
        raise InputError(f"{path}: missing column {', '.join(missing)} (header: {','.join(header)}); "
                         "expected a grainstorm mixing log (docs/MIXING.md)")
    if not rows:
        raise InputError(f"{path}: no evaluations below the header")
    columns = {name: np.empty(len(rows)) for name in header}
    for line, row in enumerate(rows, start=2):
        if len(row) != len(header):
            raise InputError(f"{path}:{line}: {len(row)} fields, the header has {len(header)}")
        for name, cell in zip(header, row):
            try:
                columns[name][line - 2] = float(cell) if cell.strip() else math.nan
            except ValueError:
                raise InputError(f"{path}:{line}: column {name} holds '{cell}', not a number")
    return columns


def revolutions_of(label, path, log, rpm, start):
    """The revolutions column, or time converted with the run's rpm."""
    if "revolutions" in log and np.isfinite(log["revolutions"]).all():
        if label in rpm:
            print(f"plot_mixing: {label}: {path} has revolutions; --rpm is not used for it", file=sys.stderr)
        return log["revolutions"]
    if label not in rpm:
        raise InputError(f"{path}: no revolutions, or empty cells in that column (a scene without "
                         "analysis.mixing.revolution_period leaves it empty); "
                         f"give --rpm RPM or --rpm {label}=RPM to convert its time")
    if "time" not in log:
        raise InputError(f"{path}: no time column to convert with --rpm")
    return (log["time"] - start) * rpm[label] / 60.0


def random_mixture_rsd(log):
    """RSD of a random mixture sampled as this run was, sqrt((1-p)/(p n)) (docs/MIXING.md);
    None when the log lacks the columns or they are undefined."""
    columns = [log.get("concentration"), log.get("particles_per_sample")]
    if any(c is None or not np.isfinite(c).any() for c in columns):
        return None
    p, n = np.nanmedian(log["concentration"]), np.nanmedian(log["particles_per_sample"])
    if not (0 < p < 1 and n > 0):
        return None
    return math.sqrt((1 - p) / (p * n))


def load_runs(runs, rpm, start):
    """Per run: label, revolutions, the log, and the random-mixture level of 1 - RSD."""
    loaded = []
    for label, path in runs:
        log = read_log(path)
        revolutions = revolutions_of(label, path, log, rpm, start)
        for column, name, _ in STATISTICS:
            if not np.isfinite(log[column]).any():
                print(f"plot_mixing: {label}: {path} has no defined {name} (all nan)", file=sys.stderr)
        rsd = random_mixture_rsd(log)
        loaded.append((label, revolutions, log, None if rsd is None else 1 - rsd))
    return loaded


def plot_statistic(loaded, column, name, log_axis, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import matplotlib.ticker
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    for k, (label, revolutions, log, random_level) in enumerate(loaded):
        colour = f"C{k % 10}"
        shown = revolutions > 0 if log_axis else np.isfinite(revolutions)
        ax.plot(revolutions[shown], log[column][shown], "o-", color=colour, ms=3, lw=1, label=label)
        if column == "one_minus_rsd" and random_level is not None:
            ax.axhline(random_level, color=colour, ls=":", lw=1)
    if column == "lacey":
        ax.axhline(1.0, color="0.4", ls="--", lw=1, label="random mixture")
    else:
        ax.plot([], [], color="0.4", ls=":", lw=1, label="random mixture (per run)")
    if log_axis:
        ax.set_xscale("log")
        ax.xaxis.set_major_formatter(matplotlib.ticker.FuncFormatter(lambda x, _: f"{x:g}"))  # 1, 10, not 10^0
    ax.set_xlabel("revolutions" + (" (log scale)" if log_axis else ""))
    ax.set_ylabel(name)
    ax.set_title(f"{name} against revolutions")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def plot(args):
    runs = parse_runs(args.run)
    loaded = load_runs(runs, parse_rpm(args.rpm, [label for label, _ in runs]), args.start)
    try:
        os.makedirs(args.out_dir, exist_ok=True)
    except OSError as e:
        raise InputError(f"--out-dir {args.out_dir}: cannot be made ({e.strerror})")
    for column, name, part in STATISTICS:
        for log_axis in (False, True):
            path = os.path.join(args.out_dir, f"{args.prefix}_{part}{'_log' if log_axis else ''}.png")
            plot_statistic(loaded, column, name, log_axis, path)
            print(path)


def main(argv=None):
    args = parse_arguments(sys.argv[1:] if argv is None else argv)
    try:
        plot(args)
    except InputError as e:
        print(f"plot_mixing: error: {e}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
