#!/usr/bin/env bash
# The force kernel's place on the roofline (issue 21): bytes it moves to and
# from the GPU's memory per particle-step, against the device's bandwidth, in
# the static dense bed of bench/dense_bed.sh (six contacts per sphere), from
# Nsight Compute's counters on a few launches of a running bed.
#   bench/force_roofline.sh BUILD OUT [N=4000000] [FRICTION=true]
# BUILD: a CUDA build directory holding src/grainstorm. Writes OUT/ncu.csv
# (ncu's raw page, one row per launch), OUT/run.log and OUT/roofline.md: per
# launch the kernel's time, its DRAM and L2 bytes per particle-step, the
# bandwidth it reached and the share of the peak (as ncu reports it), and the
# particle-steps per second the kernel would reach if it moved its bytes at
# the peak. Caches and clocks are left as they are between launches
# (--cache-control none, --clock-control none): the bytes of a step in a run,
# not of a cold cache. Needs ncu on PATH (CUDA's Nsight Compute).
set -euo pipefail
(($# >= 2)) || { echo "usage: bench/force_roofline.sh BUILD OUT [N] [FRICTION]" >&2; exit 2; }
build=$1 out=$2 n=${3:-4000000} friction=${4:-true}
command -v ncu > /dev/null || { echo "force_roofline: ncu (Nsight Compute) is not on PATH" >&2; exit 1; }
gs=$(realpath "$build/src/grainstorm")
mkdir -p "$out"
out=$(realpath "$out")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$(dirname "${BASH_SOURCE[0]}")/dense_bed.sh" "$n" "$friction" > "$work/dense.yaml"

# One force launch per step on one rank; the first 40 steps (the list's
# build, the first sorts) are skipped, five launches are measured.
metrics=dram__bytes_read.sum,dram__bytes_write.sum,lts__t_bytes.sum,gpu__time_duration.sum
metrics+=,dram__throughput.avg.pct_of_peak_sustained_elapsed,sm__throughput.avg.pct_of_peak_sustained_elapsed
(cd "$work" && ncu --csv --page raw --print-units base --cache-control none --clock-control none \
   --kernel-name-base demangled -k regex:ForceKernel --launch-skip 40 --launch-count 5 --metrics "$metrics" \
   "$gs" run dense.yaml --backend cuda --steps 60 --out run > "$out/ncu.out" 2> "$out/ncu.err") ||
  { tail -20 "$out/ncu.err" >&2; exit 1; }
# ncu prints the program's own output first; its CSV starts at the "ID" header.
sed -n '/^"ID"/,$p' "$out/ncu.out" > "$out/ncu.csv"
cp "$work/run/run.log" "$out/run.log" 2> /dev/null || true

python3 - "$out/ncu.csv" "$out/run.log" "$n" "$friction" > "$out/roofline.md" <<'PY'
import csv, re, sys
rows = list(csv.DictReader(open(sys.argv[1])))
friction = sys.argv[4]
try:  # the bed's particle count, as the run reports it (the lattice rounds the request)
    n = int(re.search(r"(\d+) particles, backend", open(sys.argv[2]).read()).group(1))
except (OSError, AttributeError):
    n = int(sys.argv[3])
units = rows[0] if rows and not rows[0]["ID"] else {}
launches = [r for r in rows if r["ID"]]
if not launches:
    sys.exit("force_roofline: no ForceKernel launch in ncu's output")
scale = {"byte": 1, "Kbyte": 1e3, "Mbyte": 1e6, "Gbyte": 1e9, "nsecond": 1e-9, "usecond": 1e-6, "ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1,
         "msecond": 1e-3, "second": 1, "%": 1, "": 1}

# Without a units row, ncu's base units: bytes, nanoseconds, percent.
base = {"gpu__time_duration.sum": "nsecond"}

def value(r, m):
    return float(r[m].replace(",", "")) * scale[units.get(m) or base.get(m, "")]

print(f"Force kernel, dense bed of {n} spheres, friction {friction} (ncu, launches 41-45)\n")
print("| launch | time [us] | DRAM bytes per particle-step | L2 bytes per particle-step | DRAM bandwidth [TB/s] "
      "| DRAM % of peak | SM % of peak | kernel particle-steps/s | at the peak bandwidth |")
print("|---|---:|---:|---:|---:|---:|---:|---:|---:|")
for r in launches:
    t = value(r, "gpu__time_duration.sum")
    dram = value(r, "dram__bytes_read.sum") + value(r, "dram__bytes_write.sum")
    l2 = value(r, "lts__t_bytes.sum")
    pct = value(r, "dram__throughput.avg.pct_of_peak_sustained_elapsed")
    sm = value(r, "sm__throughput.avg.pct_of_peak_sustained_elapsed")
    bw = dram / t
    peak = bw / (pct / 100) if pct > 0 else float("nan")
    print(f"| {r['ID']} | {t * 1e6:.0f} | {dram / n:.0f} | {l2 / n:.0f} | {bw / 1e12:.2f} | {pct:.0f} | {sm:.0f} "
          f"| {n / t:.3g} | {n / (dram / peak):.3g} |")
PY
cat "$out/roofline.md"
