#!/usr/bin/env bash
# Device memory per particle on one GPU (issue 21: at most 250 bytes per
# particle with friction, 120 without; the largest frictional bed on one
# H200 at least 4e8 particles, set up and run). From the repository root:
#   [OUT=dir] [N=4000000] [LARGEST="400000000:12 400000000:10 360000000:12"] \
#     [REBUILDING="340000000 300000000"] bench/memory_bench.sh BUILD [BASE_BUILD]
# BUILD, BASE_BUILD: CUDA build directories (src/grainstorm, bench/settle_bench),
# e.g. this tree and main built beside it; BACKEND=cpu makes it a dry run on
# the CPU (with small N and LARGEST). Results go to $OUT (default
# ./memory_out): memory_bench.txt (the summary) and one log per run.
#  1. settle_bench --n N --effects friction|none --digest yes, each build: the
#     exact peak and held bytes per particle (the high-water mark of device
#     allocations over the particles) and the final state's digest, which
#     must agree between the builds (a memory change must not change a bit).
#  2. the static dense bed of bench/gpu_bench.sh (touching simple-cubic
#     lattice in a box that holds it, gravity) of N spheres, friction and
#     none, 50 steps through `grainstorm run`: the run log's peak (BUILD
#     prints bytes per owned particle; a build before 2026-12-03 prints the
#     peak to 0.1 GiB only, so its figure is coarse).
#  3. the largest frictional lattice bed (bench/lattice_bed.sh, twice as tall
#     as wide) with BUILD: each of LARGEST's N:SLOTS (particles, contact_slots)
#     in turn, 3 steps, until one runs; each try's outcome is reported (an
#     out-of-memory is a clean error naming the size asked for).
#  4. the largest frictional bed that rebuilds its list, with BUILD:
#     settle_bench --n M --steps 30 --effects friction for each M of
#     REBUILDING in turn (default none), until one runs (--contacts no: no
#     host copy of the state at the end, which 128 GiB of host memory would
#     not hold at 3e8 and more): a pressed lattice
#     that loosens, its list rebuilt every few steps (list_builds) and
#     re-sorted, at 5.7 contacts per sphere at its first rebuilds; its peak
#     bytes per particle.
# About 3-4 minutes on an H200 (most of it the largest bed's set-up); a
# try that would start with less than 60 s of the budget (BUDGET_S, default
# 300) left is skipped.
set -uo pipefail
# Without BUILD every run below would fail into its log and the script exit 0.
if (($# < 1 || $# > 2)) || [[ -z $1 ]]; then
  echo "usage: [OUT=dir] [N=4000000] [LARGEST=\"N:SLOTS ...\"] [REBUILDING=\"M ...\"] [BACKEND=cuda] [BUDGET_S=300]" \
    "bench/memory_bench.sh BUILD [BASE_BUILD]" >&2
  exit 2
fi
root=$(pwd)
absolute() { [[ $1 == /* ]] && echo "$1" || echo "$root/$1"; }
build=$(absolute "$1") base=${2:+$(absolute "$2")}
[[ -x $build/bench/settle_bench ]] || { echo "memory_bench.sh: no bench/settle_bench in BUILD $build" >&2; exit 2; }
backend=${BACKEND:-cuda}  # BACKEND=cpu: a dry run of the script on the CPU
n=${N:-4000000}
largest=${LARGEST:-"400000000:12 400000000:10 360000000:12"}
budget=${BUDGET_S:-300}
OUT=${OUT:-$root/memory_out}
mkdir -p "$OUT"
OUT=$(cd "$OUT" && pwd)
summary=$OUT/memory_bench.txt
work=/tmp/memory_bench
mkdir -p "$work"
say() { echo "$*" | tee -a "$summary"; }
left() { echo $((budget - SECONDS)); }
{ date -u; nvidia-smi --query-gpu=name,memory.total,driver_version --format=csv,noheader 2>&1
  git rev-parse HEAD 2>/dev/null; } > "$summary"

# Bytes per particle of a run log: the exact figure where the log has it,
# else the peak printed in GiB/MiB over the particle count.
bytes_of() {
  python3 - "$1" <<'PY'
import re, sys
t = open(sys.argv[1]).read()
exact = re.search(r"memory \(rank 0\): [^,\n]+, ([\d.]+) bytes per owned particle", t)
pool = re.search(r"the pool held at most [^,\n]+, ([\d.]+)\)", t)
if exact: print(exact.group(1) + (f" (the pool {pool.group(1)})" if pool else "")); sys.exit()
n = re.search(r"(\d+) particles, backend", t)
m = re.search(r"memory \(rank 0\): ([\d.]+) (B|KiB|MiB|GiB|TiB)", t)
if not (n and m): print("-"); sys.exit()
scale = {"B": 1, "KiB": 2**10, "MiB": 2**20, "GiB": 2**30, "TiB": 2**40}[m.group(2)]
print(f"~{float(m.group(1)) * scale / int(n.group(1)):.0f} (from {m.group(1)} {m.group(2)})")
PY
}

# "base" and "this": BASE_BUILD and BUILD.
labels=(this)
[[ -n $base ]] && labels=(base this)
dir_of() { [[ $1 == base ]] && echo "$base" || echo "$build"; }

say "== settle_bench --n $n --steps 50 (pressed lattice; peak and held bytes per particle, digest)"
for effects in friction none; do
  for label in "${labels[@]}"; do
    b=$(dir_of "$label") log=$OUT/settle_${effects}_$label.log
    timeout 120 "$b/bench/settle_bench" --backend "$backend" --n "$n" --steps 50 --effects "$effects" --digest yes \
      > "$log" 2>&1
    line=$(grep -oE "peak_bytes_per_particle=[0-9.]+ held_bytes_per_particle=[0-9.]+" "$log" | head -1)
    pool=$(grep -oE "reserved_bytes_per_particle=[0-9.]+" "$log" | head -1)
    digest=$(grep -oE "state_digest=0x[0-9a-f]+" "$log" | head -1)
    say "$effects $label: ${line:-FAILED ($(tail -1 "$log"))} ${pool} ${digest}"
  done
done

# The static dense bed of bench/gpu_bench.sh.
dense_scene() { "$(dirname "${BASH_SOURCE[0]}")/dense_bed.sh" "$@"; }  # N FRICTION > scene

say "== static dense bed, N = $n, 50 steps (grainstorm run)"
for friction in true false; do
  dense_scene "$n" "$friction" > "$work/dense_$friction.yaml"
  for label in "${labels[@]}"; do
    b=$(dir_of "$label") log=$OUT/dense_friction_${friction}_$label.log
    rm -rf "$work/run"
    timeout 120 "$b/src/grainstorm" run "$work/dense_$friction.yaml" --backend "$backend" --steps 50 \
      --out "$work/run" > "$log" 2>&1
    rc=$?
    say "friction $friction $label: $(bytes_of "$log") bytes per particle (exit $rc)"
  done
done
rm -rf "$work/run"

say "== largest frictional lattice bed with BUILD (3 steps)"
for try in $largest; do
  count=${try%%:*} slots=${try##*:}
  if (($(left) < 60)); then say "$count particles, $slots slots: skipped (budget)"; continue; fi
  side=$(python3 -c "print(round(($count / 2) ** (1/3)))")
  layers=$(python3 -c "print(round($count / $side**2))")
  scene=$work/largest_${count}_$slots.yaml
  { "$root/bench/lattice_bed.sh" "$side" "$layers" "$work/largest_run" id; echo "contact_slots: $slots"; } > "$scene"
  log=$OUT/largest_${count}_$slots.log
  rm -rf "$work/largest_run"
  start=$SECONDS
  timeout $(($(left) - 10)) "$build/src/grainstorm" run "$scene" --backend "$backend" --steps 3 --overwrite \
    > "$log" 2>&1
  rc=$?
  rm -rf "$work/largest_run"
  particles=$(grep -oE "[0-9]+ particles, backend" "$log" | head -1 | cut -d' ' -f1)
  if [[ $rc == 0 ]] && grep -q "done:" "$log"; then
    say "$count particles ($particles made), $slots slots: RAN in $((SECONDS - start)) s; $(grep -E "set up in" "$log" | head -1); peak $(bytes_of "$log") bytes per particle"
    break
  fi
  say "$count particles, $slots slots: failed (exit $rc): $(grep -iE "error|memory" "$log" | head -2 | tr '\n' ' ')"
done
rebuilding=${REBUILDING:-}
[[ -n $rebuilding ]] && say "== largest frictional bed that rebuilds its list, with BUILD (settle_bench, 30 steps)"
for m in $rebuilding; do
  if (($(left) < 60)); then say "$m particles: skipped (budget)"; continue; fi
  log=$OUT/rebuilding_$m.log
  timeout $(($(left) - 10)) "$build/bench/settle_bench" --backend "$backend" --n "$m" --steps 30 --effects friction \
    --contacts no > "$log" 2>&1
  rc=$?
  line=$(grep -oE "peak_bytes_per_particle=[0-9.]+ held_bytes_per_particle=[0-9.]+" "$log" | head -1)
  builds=$(grep -oE "list_builds=[0-9]+" "$log" | head -1)
  pool=$(grep -oE "reserved_bytes_per_particle=[0-9.]+" "$log" | head -1)
  if [[ $rc == 0 && -n $line ]]; then
    say "$m particles: RAN, $line $builds $pool"
    break
  fi
  say "$m particles: failed (exit $rc): $(grep -iE "error|memory" "$log" | head -2 | tr '\n' ' ')"
done
say "total $SECONDS s"
