#!/usr/bin/env python3
"""How many triangles of a turning mesh each sphere of a checkpoint has within
reach: the spheres that make the mesh rule's work long (docs/MESHES.md, "Cost").

    mesh_reach.py CHECKPOINT MESH.stl [--rpm 30] [--start 1] [--axis-point X Y Z] [--top 8]

The mesh turns about the z axis through --axis-point at --rpm from time --start
(the mixer's impeller: docs/MIXER.md), so at the checkpoint's time t it has
turned by 2 pi rpm/60 (t - start); each sphere is taken into the mesh's
reference frame and the closest point of every triangle whose box, grown by the
sphere's radius, holds its centre is computed (as walls/sphere_triangle.hpp
does, in double precision). Prints the number of spheres with more than
--cap triangles in reach (the rule's in-reach list, kMeshInReachCap) and the
--top spheres with the most: triangles in reach, triangles near, index, centre
in the mesh frame in mm. Needs numpy and h5py.
"""
import argparse
import math
import struct
import sys

import h5py
import numpy as np


def load_stl(path):
    data = open(path, "rb").read()
    if data[:5] == b"solid" and b"facet" in data[:300]:
        v = [[float(w) for w in line.split()[1:4]] for line in data.decode().splitlines()
             if line.strip().startswith("vertex")]
        return np.array(v).reshape(-1, 3, 3)
    n = struct.unpack("<I", data[80:84])[0]
    rows = np.frombuffer(data[84:84 + 50 * n], dtype=np.dtype([("n", "<f4", 3), ("v", "<f4", (3, 3)), ("c", "<u2")]))
    return rows["v"].astype(float)


def closest_points(p, a, b, c):
    """Closest point of each triangle (a[i], b[i], c[i]) to the point p (Ericson's regions)."""
    ab, ac, ap = b - a, c - a, p - a
    d1, d2 = (ab * ap).sum(1), (ac * ap).sum(1)
    bp, cp = p - b, p - c
    d3, d4 = (ab * bp).sum(1), (ac * bp).sum(1)
    d5, d6 = (ab * cp).sum(1), (ac * cp).sum(1)
    vc, vb, va = d1 * d4 - d3 * d2, d5 * d2 - d1 * d6, d3 * d6 - d5 * d4
    denom = va + vb + vc
    denom = np.where(denom == 0, 1e-300, denom)
    q = a + ab * (vb / denom)[:, None] + ac * (vc / denom)[:, None]

    def safe(x):
        return np.where(x == 0, 1.0, x)

    m = (va <= 0) & (d4 - d3 >= 0) & (d5 - d6 >= 0)
    q[m] = (b + (c - b) * ((d4 - d3) / safe((d4 - d3) + (d5 - d6)))[:, None])[m]
    m = (vb <= 0) & (d2 >= 0) & (d6 <= 0)
    q[m] = (a + ac * (d2 / safe(d2 - d6))[:, None])[m]
    m = (vc <= 0) & (d1 >= 0) & (d3 <= 0)
    q[m] = (a + ab * (d1 / safe(d1 - d3))[:, None])[m]
    q[(d6 >= 0) & (d5 <= d6)] = c[(d6 >= 0) & (d5 <= d6)]
    q[(d3 >= 0) & (d4 <= d3)] = b[(d3 >= 0) & (d4 <= d3)]
    q[(d1 <= 0) & (d2 <= 0)] = a[(d1 <= 0) & (d2 <= 0)]
    return q


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("checkpoint")
    ap.add_argument("stl")
    ap.add_argument("--rpm", type=float, default=30.0)
    ap.add_argument("--start", type=float, default=1.0, help="time the mesh starts turning [s]")
    ap.add_argument("--axis-point", type=float, nargs=3, default=[0.0, 0.0, 0.0])
    ap.add_argument("--cap", type=int, default=16)
    ap.add_argument("--top", type=int, default=8)
    args = ap.parse_args(argv)

    tri = load_stl(args.stl)
    with h5py.File(args.checkpoint, "r") as h:
        x = h["particles/position"][()]
        radius = h["particles/radius"][()].astype(float)
        time = float(h.attrs["time"])
    angle = 2 * math.pi * args.rpm / 60 * max(0.0, time - args.start)
    c, s = math.cos(angle), math.sin(angle)
    rel = x - np.array(args.axis_point)
    ref = np.stack([c * rel[:, 0] + s * rel[:, 1], -s * rel[:, 0] + c * rel[:, 1], rel[:, 2]], 1) + args.axis_point
    lo, hi = tri.min(1), tri.max(1)
    rows = []
    for i in range(len(ref)):
        near = np.all((lo - radius[i] <= ref[i]) & (ref[i] <= hi + radius[i]), 1)
        if not near.any():
            continue
        t = tri[near]
        q = closest_points(np.repeat(ref[i][None], len(t), 0), t[:, 0], t[:, 1], t[:, 2])
        in_reach = int((np.linalg.norm(q - ref[i], axis=1) < radius[i]).sum())
        rows.append((in_reach, int(near.sum()), i, ref[i] * 1e3))
    rows.sort(key=lambda r: -r[0])
    print(f"{args.checkpoint}: t = {time:.4f} s, mesh turned {math.degrees(angle) % 360:.1f} deg, "
          f"{len(rows)} spheres near it, {sum(r[0] > args.cap for r in rows)} with more than {args.cap} in reach")
    for in_reach, near, i, p in rows[:args.top]:
        print(f"  sphere {i}: {in_reach} in reach of {near} near, at ({p[0]:.2f}, {p[1]:.2f}, {p[2]:.2f}) mm")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
