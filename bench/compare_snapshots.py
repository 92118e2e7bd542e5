#!/usr/bin/env python3
"""Compares the last snapshot (HDF5 or CSV) of runs: largest position and velocity
difference against the first run, relative to the particle radius and to the
largest speed. Usage: compare_snapshots.py RUN_DIR RUN_DIR [RUN_DIR...]"""
import csv
import glob
import math
import os
import sys


def last_h5(path):
    import h5py  # only needed for HDF5 snapshots
    with h5py.File(path, "r") as f:
        p = f["particles"]
        ids, r, x, v = p["id"][:], p["radius"][:], p["position"][:], p["velocity"][:]
    return {int(i): (float(r[k]), list(x[k]), list(v[k])) for k, i in enumerate(ids)}


def last_snapshot(directory):
    h5 = sorted(glob.glob(os.path.join(directory, "particles_*.h5")))
    if h5:
        return h5[-1], last_h5(h5[-1])
    files = sorted(glob.glob(os.path.join(directory, "particles_*.csv")))
    if not files:
        sys.exit(f"no snapshots in {directory}")
    with open(files[-1]) as f:
        rows = [r for r in csv.reader(line for line in f if not line.startswith("#"))]
    header, data = rows[0], rows[1:]
    col = {name: k for k, name in enumerate(header)}
    out = {}
    for r in data:
        out[int(r[col["id"]])] = (float(r[col["radius"]]),
                                  [float(r[col[c]]) for c in ("x", "y", "z")],
                                  [float(r[col[c]]) for c in ("vx", "vy", "vz")])
    return files[-1], out


def main():
    ref_file, ref = last_snapshot(sys.argv[1])
    vmax = max(math.dist(v, (0, 0, 0)) for _, _, v in ref.values()) or 1.0
    for other in sys.argv[2:]:
        name, run = last_snapshot(other)
        if set(run) != set(ref):
            print(f"{name}: particle ids differ from {ref_file}")
            continue
        dx = max(math.dist(ref[i][1], run[i][1]) / ref[i][0] for i in ref)
        dv = max(math.dist(ref[i][2], run[i][2]) for i in ref) / vmax
        same = all(ref[i][1] == run[i][1] and ref[i][2] == run[i][2] for i in ref)
        print(f"{name} vs {ref_file}: max |dx|/r = {dx:.3e}, max |dv|/vmax = {dv:.3e}, bitwise equal: {same}")


if __name__ == "__main__":
    main()
