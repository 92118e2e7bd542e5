#!/usr/bin/env python3
"""Summarise a CUDA timeline written by bench/gpu_trace.sh, per step.

    bench/gpu_timeline.py TRACE.csv [--marker REGEX] [--skip K] [--count C] [--detail REGEX]

A step is the stretch from one launch of the marker kernel (a kernel whose
demangled name matches REGEX, default KickDrift: one per step) to the next;
the window is C steps from the K-th (default: the second half of the run).
Prints, per step: the wall span, the device's busy and idle time, each
kernel's count and time, the idle gaps between device activities by the
pair they separate, and the host's runtime API calls (count, time: a
synchronising call's time is the host waiting for the device). --detail
lists, in time order, every device activity and API call of the first step
of the window that launches a kernel matching REGEX (a rebuild: ListPass).
"""
import argparse
import collections
import csv
import re
import shutil
import subprocess
import sys


def demangle(names):
    names = sorted(set(names))
    if not shutil.which("c++filt"):
        return {n: n for n in names}
    out = subprocess.run(["c++filt"], input="\n".join(names), capture_output=True, text=True).stdout.split("\n")
    return dict(zip(names, out))


def short(name):
    """The functor of a for_each kernel, else the kernel's own name."""
    m = re.search(r"for_each\w*kernel\w*<(?:gs::)?([A-Za-z_]\w*)", name)
    if m:
        return m.group(1)
    m = re.search(r"(?:void )?(?:[\w:]*::)?([A-Za-z_]\w*)(?:<|\()", name)
    return m.group(1) if m else name[:40]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("trace")
    ap.add_argument("--marker", default="KickDrift")
    ap.add_argument("--skip", type=int, default=None)
    ap.add_argument("--count", type=int, default=None)
    ap.add_argument("--detail", default=None)
    a = ap.parse_args()
    device, api = [], []
    with open(a.trace, newline="") as f:
        for row in csv.reader(f):
            if len(row) < 4:
                continue
            kind, start, end, name = row[0], int(row[1]), int(row[2]), ",".join(row[3:])
            (api if kind == "api" else device).append((start, end, kind, name))
    if not device:
        sys.exit("no device activity in " + a.trace)
    full = demangle([n for _, _, k, n in device if k == "kernel"])
    device = [(s, e, k, short(full[n]) if k == "kernel" else k + " " + n) for s, e, k, n in device]
    device.sort()
    marks = [s for s, _, k, n in device if k == "kernel" and re.search(a.marker, n)]
    if len(marks) < 3:
        sys.exit(f"fewer than 3 launches of a kernel matching {a.marker!r}")
    skip = a.skip if a.skip is not None else len(marks) // 2
    count = a.count if a.count is not None else len(marks) - 1 - skip
    if skip < 0 or count < 1 or skip + count >= len(marks):
        sys.exit(f"{len(marks)} marker launches: cannot skip {skip} and take {count}")
    t0, t1 = marks[skip], marks[skip + count]
    steps = count
    us = lambda ns: ns / 1e3 / steps
    inside = [(max(s, t0), min(e, t1), k, n) for s, e, k, n in device if e > t0 and s < t1]
    busy, reach, gaps = 0, t0, collections.defaultdict(lambda: [0, 0])
    per_kernel = collections.defaultdict(lambda: [0, 0])
    previous = "(window start)"
    for s, e, k, n in inside:
        if s > reach:
            g = gaps[(previous, n)]
            g[0] += 1
            g[1] += s - reach
        busy += max(0, e - max(s, reach))
        if e > reach:
            reach, previous = e, n
        per_kernel[n][0] += 1
        per_kernel[n][1] += e - s
    span = t1 - t0
    print(f"{steps} steps from marker launch {skip} ({a.marker}): {us(span):.1f} us per step; "
          f"device busy {us(busy):.1f} us, idle {us(span - busy):.1f} us")
    print("\ndevice activity per step (count, us):")
    for n, (c, t) in sorted(per_kernel.items(), key=lambda kv: -kv[1][1]):
        print(f"  {c / steps:7.3f}  {us(t):8.2f}  {n}")
    print("\nidle gaps per step, by the activities they separate (count, us):")
    for (p, n), (c, t) in sorted(gaps.items(), key=lambda kv: -kv[1][1])[:12]:
        print(f"  {c / steps:7.3f}  {us(t):8.2f}  {p} -> {n}")
    calls = collections.defaultdict(lambda: [0, 0])
    for s, e, _, n in api:
        if s >= t0 and s < t1:
            calls[n][0] += 1
            calls[n][1] += min(e, t1) - s
    print("\nhost runtime API calls per step (count, us):")
    for n, (c, t) in sorted(calls.items(), key=lambda kv: -kv[1][1])[:15]:
        print(f"  {c / steps:7.3f}  {us(t):8.2f}  {n}")
    print(f"  host time inside API calls: {us(sum(t for _, t in calls.values())):.1f} us per step")
    if a.detail:
        detail(a.detail, marks[skip:skip + count + 1], device, api)


def detail(pattern, marks, device, api):
    """Every activity of the first step holding a kernel that matches pattern."""
    for s0, s1 in zip(marks, marks[1:]):
        if any(k == "kernel" and re.search(pattern, n) and s0 <= s < s1 for s, _, k, n in device):
            break
    else:
        print(f"\nno step of the window launches a kernel matching {pattern!r}")
        return
    rows = [(s, e, "device", n) for s, e, _, n in device if s0 <= s < s1]
    rows += [(s, e, "host", n) for s, e, _, n in api if s0 <= s < s1]
    print(f"\nthe first step launching {pattern!r}: {(s1 - s0) / 1e3:.1f} us (start offset, duration in us)")
    for s, e, who, n in sorted(rows):
        print(f"  {(s - s0) / 1e3:8.1f} {(e - s) / 1e3:7.1f}  {who:6s} {n}")


if __name__ == "__main__":
    main()
