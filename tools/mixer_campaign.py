#!/usr/bin/env python3
"""The mixer campaign's bookkeeping (bench/mixer_campaign.sh, docs/MIXER.md,
"Running the study across sessions").

    tools/mixer_campaign.py progress CAMPAIGN_DIR
    tools/mixer_campaign.py restore OUT CAMPAIGN_DIR
    tools/mixer_campaign.py analyse CAMPAIGN_DIR [--out-dir docs/data/mixer]
                                   [--prefix campaign] [--plot-dir docs/img]
    tools/mixer_campaign.py plot [DATA_DIR=docs/data/mixer] [--prefix campaign] [--plot-dir docs/img]
    tools/mixer_campaign.py snapshots RUN_DIR SCENE REVOLUTION...

progress: per run (a scene NAME.yaml with its directory NAME/) the
revolutions done (the last row of NAME/mixing.csv) against the scene's target,
and the wall time per revolution (all pieces' wall time in NAME/campaign.log,
settling included, over the revolutions done).

restore: unpacks what a job returned (OUT/campaign.tar.gz.partNN)
into the campaign directory; each run directory in it replaces the one there
whole, so that no older checkpoint stays behind to be carried again.

analyse: runs named VARIANT_sSEED (as make_mixer_cases.py --suffix ..._sSEED
writes them) are grouped by VARIANT; per variant and revolution it writes
OUT_DIR/PREFIX_VARIANT.csv with the mean, the sample standard deviation and
the min and max over the seeds that reached that revolution of the Lacey
index and of 1 - RSD, and the impeller's torque about its axis (mesh0_tz of
NAME/timeseries.csv, the load on the first mesh) averaged over the revolution
that ends there (mean and standard deviation over the seeds), and plots Lacey
and 1 - RSD against revolutions (as the seed's Figs. 7-10) into PLOT_DIR when
matplotlib is present: every variant whose table is in OUT_DIR, this
campaign's just written and those analysed before.

plot: the same plots from the tables analyse wrote (DATA_DIR/PREFIX_*.csv),
every variant there, so that they can be drawn again once the runs'
directories are gone (they do not outlive a session of the GPU jobs).

snapshots: the snapshot files (particles_STEP.h5, with meshes_STEP.h5 where
written) of a run directory nearest to each given revolution, within a
quarter revolution, one path per line; bench/mixer_campaign.sh keeps them
(KEEP_REVOLUTIONS) for the top views of docs/MIXER.md.
"""
import argparse
import csv
import math
import os
import re
import sys


def scene_numbers(path):
    """duration, mixing start and revolution_period of a make_mixer_cases scene."""
    text = open(path).read()

    def number(pattern):
        m = re.search(pattern, text, re.M)
        if not m:
            sys.exit(f"mixer_campaign: {path}: no {pattern!r}")
        return float(m.group(1))
    return (number(r"^duration:\s*([-+0-9.eE]+)"), number(r"^\s+start:\s*([-+0-9.eE]+)"),
            number(r"^\s+revolution_period:\s*([-+0-9.eE]+)"))


def mixing_rows(path):
    """rows of a mixing.csv as dicts of floats; [] when absent."""
    if not os.path.exists(path):
        return []
    with open(path) as f:
        rows = []
        for line, row in enumerate(csv.DictReader(f), start=2):
            try:
                rows.append({k: float(v) for k, v in row.items()})
            except (TypeError, ValueError):
                sys.exit(f"mixer_campaign: {path}:{line}: not a row of numbers")
        return rows


def time_step(run_dir):
    """dt of a run from its run.log's first line ("dt = 4.26e-05 s")."""
    path = os.path.join(run_dir, "run.log")
    m = re.search(r"dt = ([-+0-9.eE]+) s", open(path).read()) if os.path.exists(path) else None
    if not m:
        sys.exit(f"mixer_campaign: {path}: no time step (\"dt = ... s\")")
    return float(m.group(1))


def revolution_torques(run_dir, start, period):
    """{revolution r: mean of mesh0_tz over (start + (r-1) period, start + r period]} from timeseries.csv."""
    path = os.path.join(run_dir, "timeseries.csv")
    if not os.path.exists(path):
        return {}
    sums = {}
    with open(path) as f:
        for row in csv.DictReader(f):
            if "mesh0_tz" not in row:
                return {}
            t = float(row["time"])
            if t <= start:
                continue
            r = math.ceil((t - start) / period - 1e-9)  # a sample at the revolution's end belongs to it
            total, n = sums.get(r, (0.0, 0))
            sums[r] = (total + float(row["mesh0_tz"]), n + 1)
    return {r: total / n for r, (total, n) in sums.items()}


def snapshots(run_dir, scene, revolutions):
    _, start, period = scene_numbers(scene)
    dt = time_step(run_dir)
    found = {}
    for f in os.listdir(run_dir):
        m = re.fullmatch(r"particles_(\d+)\.h5", f)
        if m:
            found[int(m.group(1))] = f
    for rev in revolutions:
        near = [(abs((step * dt - start) / period - rev), step) for step in found]
        near = [n for n in near if n[0] <= 0.25]
        if not near:
            print(f"mixer_campaign: {run_dir}: no snapshot within a quarter revolution of {rev}", file=sys.stderr)
            continue
        step = min(near)[1]
        print(os.path.join(run_dir, found[step]))
        meshes = os.path.join(run_dir, found[step].replace("particles_", "meshes_"))
        if os.path.exists(meshes):
            print(meshes)


def runs(campaign):
    names = sorted(f[:-5] for f in os.listdir(campaign) if f.endswith(".yaml"))
    if not names:
        sys.exit(f"mixer_campaign: no scenes (*.yaml) in {campaign}")
    return names


def progress(campaign):
    print(f"{'run':32} {'revolutions':>12} {'pieces':>6} {'wall s':>8} {'wall s/rev':>10}  state")
    for name in runs(campaign):
        duration, start, period = scene_numbers(os.path.join(campaign, name + ".yaml"))
        target = round((duration - start) / period)
        rows = mixing_rows(os.path.join(campaign, name, "mixing.csv"))
        done = round(rows[-1]["revolutions"]) if rows else 0
        pieces, wall, state = 0, 0, "not started"
        log = os.path.join(campaign, name, "campaign.log")
        if os.path.exists(log):
            for line in open(log):
                m = re.search(r"wall_s (\d+) exit (\d+)$", line)
                if m:
                    pieces, wall = pieces + 1, wall + int(m.group(1))
                    code = int(m.group(2))
                    state = {0: "finished", 3: "stopped, to be continued"}.get(code, f"FAILED (exit {code})")
        per = f"{wall / done:.1f}" if done else "-"
        print(f"{name:32} {done:>5} / {target:<4} {pieces:>6} {wall:>8} {per:>10}  {state}")


def restore(out, campaign):
    import glob
    import io
    import shutil
    import tarfile
    parts = sorted(glob.glob(os.path.join(out, "campaign.tar.gz.part*")))
    if not parts:
        sys.exit(f"mixer_campaign: no campaign.tar.gz.part* in {out}")
    data = b"".join(open(p, "rb").read() for p in parts)
    with tarfile.open(fileobj=io.BytesIO(data), mode="r:gz") as tar:
        members = tar.getmembers()
        for m in members:
            if m.name.startswith("/") or ".." in m.name.split("/"):
                sys.exit(f"mixer_campaign: {parts[0]}: unsafe path {m.name!r}")
        runs_in = {m.name.split("/")[1] for m in members
                   if m.isdir() and m.name.startswith("./") and m.name.count("/") == 1 and m.name != "./"}
        os.makedirs(campaign, exist_ok=True)
        for name in sorted(runs_in):
            shutil.rmtree(os.path.join(campaign, name), ignore_errors=True)
        tar.extractall(campaign)
    print(f"{campaign}: {len(runs_in)} run director{'y' if len(runs_in) == 1 else 'ies'} replaced from {len(parts)} part(s)")


def spread(values):
    mean = sum(values) / len(values)
    sd = math.sqrt(sum((v - mean) ** 2 for v in values) / (len(values) - 1)) if len(values) > 1 else float("nan")
    return mean, sd, min(values), max(values)


def analyse(campaign, out_dir, prefix, plot_dir):
    variants = {}
    for name in runs(campaign):
        m = re.fullmatch(r"(.+)_s(\d+)", name)
        variant = m.group(1) if m else name
        rows = mixing_rows(os.path.join(campaign, name, "mixing.csv"))
        if rows:
            _, start, period = scene_numbers(os.path.join(campaign, name + ".yaml"))
            torque = revolution_torques(os.path.join(campaign, name), start, period)
            for r in rows:
                r["torque"] = torque.get(round(r["revolutions"]), float("nan"))
            variants.setdefault(variant, []).append((name, rows))
    if not variants:
        sys.exit(f"mixer_campaign: no run in {campaign} has a mixing.csv yet")
    os.makedirs(out_dir, exist_ok=True)
    tables = {}
    for variant, members in sorted(variants.items()):
        by_rev = {}
        for _, rows in members:
            for r in rows:
                by_rev.setdefault(round(r["revolutions"]), []).append(r)
        path = os.path.join(out_dir, f"{prefix}_{variant}.csv")
        table = []
        with open(path, "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(["revolutions", "runs", "lacey_mean", "lacey_sd", "lacey_min", "lacey_max",
                        "one_minus_rsd_mean", "one_minus_rsd_sd", "one_minus_rsd_min", "one_minus_rsd_max",
                        "concentration_mean", "torque_mean", "torque_sd"])
            for rev in sorted(by_rev):
                rs = by_rev[rev]
                lacey = spread([r["lacey"] for r in rs])
                orsd = spread([r["one_minus_rsd"] for r in rs])
                conc = sum(r["concentration"] for r in rs) / len(rs)
                torques = [r["torque"] for r in rs if not math.isnan(r["torque"])]
                torque = spread(torques)[:2] if torques else (float("nan"), float("nan"))
                w.writerow([rev, len(rs)] + [f"{v:.6g}" for v in lacey + orsd + (conc,) + torque])
                table.append((rev, len(rs), lacey, orsd))
        tables[variant] = table
        print(f"{path}: {len(members)} run(s) ({', '.join(n for n, _ in members)}), revolutions 0-{max(by_rev)}")
    if plot_dir:
        # Every variant with a table in out_dir, not only this campaign's: a
        # campaign directory may hold some variants, and plots drawn from it
        # alone would drop the others from the shared figures.
        plot(read_tables(out_dir, prefix), plot_dir, prefix)


def read_tables(data_dir, prefix):
    """The tables analyse wrote ({prefix}_VARIANT.csv in data_dir), as analyse
    hands them to plot: per variant, per revolution (revolution, runs, (mean,
    sd, min, max) of the Lacey index, the same of 1 - RSD)."""
    tables = {}
    for name in sorted(os.listdir(data_dir)):
        m = re.fullmatch(re.escape(prefix) + r"_(.+)\.csv", name)
        if not m:
            continue
        table = []
        with open(os.path.join(data_dir, name), newline="") as f:
            for r in csv.DictReader(f):
                stats = lambda key: tuple(float(r[f"{key}_{s}"]) for s in ("mean", "sd", "min", "max"))
                table.append((int(r["revolutions"]), int(r["runs"]), stats("lacey"), stats("one_minus_rsd")))
        tables[m.group(1)] = table
    if not tables:
        sys.exit(f"mixer_campaign: no {prefix}_*.csv in {data_dir}")
    return tables


def plot(tables, plot_dir, prefix):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib not found: no plots")
        return
    os.makedirs(plot_dir, exist_ok=True)
    for column, label, stem in ((2, "Lacey index M", "lacey"), (3, "1 - RSD", "one_minus_rsd")):
        fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))
        for ax, log in zip(axes, (False, True)):
            for variant, table in tables.items():
                rows = [t for t in table if not log or t[0] > 0]
                revs = [t[0] for t in rows]
                mean = [t[column][0] for t in rows]
                lo = [t[column][2] for t in rows]
                hi = [t[column][3] for t in rows]
                runs_max = max(t[1] for t in table)
                line, = ax.plot(revs, mean, marker="o", ms=3, label=f"{variant} (mean of {runs_max})")
                if runs_max > 1:
                    ax.fill_between(revs, lo, hi, color=line.get_color(), alpha=0.2, lw=0)
            if log:
                ax.set_xscale("log")
            ax.set_xlabel("revolutions" + (" (log)" if log else ""))
            ax.set_ylabel(label)
            ax.grid(alpha=0.3)
        axes[0].legend(fontsize=8)
        fig.suptitle(f"{label}: mean over seeds, band from min to max")
        fig.tight_layout()
        path = os.path.join(plot_dir, f"{prefix}_{stem}.png")
        fig.savefig(path, dpi=110)
        plt.close(fig)
        print(f"{path}: {', '.join(tables)}")


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = p.add_subparsers(dest="command", required=True)
    pr = sub.add_parser("progress")
    pr.add_argument("campaign")
    re_ = sub.add_parser("restore")
    re_.add_argument("out")
    re_.add_argument("campaign_dir")
    an = sub.add_parser("analyse")
    an.add_argument("campaign")
    an.add_argument("--out-dir", default="docs/data/mixer")
    an.add_argument("--prefix", default="campaign")
    an.add_argument("--plot-dir", default="docs/img", help="'' for no plots [docs/img]")
    pl = sub.add_parser("plot")
    pl.add_argument("data_dir", nargs="?", default="docs/data/mixer")
    pl.add_argument("--prefix", default="campaign")
    pl.add_argument("--plot-dir", default="docs/img")
    sn = sub.add_parser("snapshots")
    sn.add_argument("run_dir")
    sn.add_argument("scene")
    sn.add_argument("revolutions", nargs="+", type=float)
    a = p.parse_args()
    if a.command == "restore":
        restore(a.out, a.campaign_dir)
        return
    if a.command == "snapshots":
        snapshots(a.run_dir, a.scene, a.revolutions)
        return
    if a.command == "plot":
        plot(read_tables(a.data_dir, a.prefix), a.plot_dir, a.prefix)
        return
    if not os.path.isdir(a.campaign):
        sys.exit(f"mixer_campaign: {a.campaign} is not a directory")
    if a.command == "progress":
        progress(a.campaign)
    else:
        analyse(a.campaign, a.out_dir, a.prefix, a.plot_dir)


if __name__ == "__main__":
    main()
