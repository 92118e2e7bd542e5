#!/usr/bin/env bash
# Before against after on one GPU: the four benchmarks of issue 21, each run by
# both builds in turn (alternating, so drifts of the machine hit both alike),
# each line with particle-steps/s, device bytes per particle and contacts per
# particle; a before/after table at the end.
#   bench/gpu_bench.sh BEFORE_BUILD AFTER_BUILD OUTDIR [SECONDS] [SIZES]
# BEFORE_BUILD, AFTER_BUILD: build directories holding src/grainstorm (and
# bench/settle_bench). SECONDS (default 300): the whole script's budget; a run
# that would start after it is skipped and said so. SIZES (default
# "4000000 16000000 64000000"): the dense beds' particle counts, smallest
# first. Results: OUTDIR/gpu_bench.csv, OUTDIR/gpu_bench.md, logs OUTDIR/*.log.
#
# The benchmarks:
#  dense      the static dense bed: a touching simple-cubic lattice in a box
#             that holds it exactly (bench/lattice_bed.sh), gravity, friction,
#             six contacts per sphere; also frictionless (dense_nofric).
#  random     a poured random polydisperse bed: radii 0.8-1.2 mm filled at
#             random into a box and settled under gravity by AFTER_BUILD (to a
#             checkpoint), then timed from that checkpoint by both builds.
#  mixer_b    a flowing bed: mixer case b's soft variant (cases/mixer), settled
#             1 s to a checkpoint, then timed turning at 30 rpm.
#  mixer_a    the small scene: mixer case a, timed from its start (settling).
#  dense_2ranks  the smallest dense bed on 2 ranks sharing the GPU.
# Bytes per particle: the run's peak device memory (printed to 0.1 GiB or
# MiB) over its particles. Contacts per particle: the mean contact_count of
# the run's last snapshot (needs h5py; "-" without it), walls included.
# BACKEND=cpu runs it all on the CPU instead (a dry run of the script);
# SKIP="random mixer_b ..." leaves those benchmarks out; RANDOM_BED_N sets the
# random bed's size (default 4e6).
set -uo pipefail
backend=${BACKEND:-cuda}
skip=" ${SKIP:-} "
wanted() { [[ $skip != *" $1 "* ]]; }
before=$1 after=$2 out=$3 budget=${4:-300} sizes=${5:-"4000000 16000000 64000000"}
root=$(pwd)
mkdir -p "$out"
deadline=$((SECONDS + budget))
csv=$out/gpu_bench.csv
echo "bench,particles,build,round,particle_steps_per_s,bytes_per_particle,contacts_per_particle" > "$csv"
left() { echo $((deadline - SECONDS)); }

# Mean of a snapshot's contact_count, or "-".
contacts_of() {
  local snap
  snap=$(ls "$1"/particles_*.h5 2>/dev/null | sort | tail -1)
  [[ -n $snap ]] || { echo -; return; }
  python3 - "$snap" <<'PY' 2>/dev/null || echo -
import sys, h5py
with h5py.File(sys.argv[1], "r") as f:
    c = f["particles"]["contact_count"][:]
print(f"{c.mean():.2f}")
PY
}

# Bytes per particle from a run log's "peak cuda memory" and particle count.
bytes_of() {
  python3 - "$1" "$backend" <<'PY'
import re, sys
t = open(sys.argv[1]).read()
n = re.search(r"(\d+) particles, backend", t)
m = re.search(sys.argv[2] + r" memory \(rank 0\): ([\d.]+) (B|KiB|MiB|GiB|TiB)", t)
if not (n and m): print("-"); sys.exit()
scale = {"B": 1, "KiB": 2**10, "MiB": 2**20, "GiB": 2**30, "TiB": 2**40}[m.group(2)]
print(f"{float(m.group(1)) * scale / int(n.group(1)):.0f}")
PY
}

# run_case BENCH BUILD ROUND DIR SCENE STEPS [grainstorm args...]: one timed
# run in DIR (a scene's relative paths resolve there); one CSV line. LAUNCH
# (e.g. "mpirun -np 2") is put before the command.
LAUNCH=
run_case() {
  local bench=$1 build=$2 round=$3 dir=$4 scene=$5 steps=$6
  shift 6
  local tag=${bench}_$(basename "$build")_$round log run
  log=$out/$tag.log run=/tmp/gpu_bench_runs/$tag
  if (($(left) < 15)); then echo "skipped $tag: out of time" | tee -a "$out/skipped.txt"; return; fi
  (cd "$dir" && timeout "$(left)" $LAUNCH "$root/$build/src/grainstorm" run "$scene" --backend "$backend" --steps "$steps" \
     --out "$run" --overwrite "$@" > "$log" 2>&1)
  local rc=$?
  local rate n
  rate=$(grep -oE "done: .* ([0-9.e+]+) particle-steps/s" "$log" | grep -oE "[0-9.e+]+ particle-steps" | cut -d' ' -f1)
  n=$(grep -oE "[0-9]+ particles, backend" "$log" | cut -d' ' -f1)
  [[ $rc == 0 && -n $rate ]] || { echo "FAILED $tag (exit $rc): $(tail -2 "$log" | tr '\n' ' ')"; rate=-; }
  echo "$bench,${n:--},$(basename "$build"),$round,$rate,$(bytes_of "$log"),$(contacts_of "$run")" | tee -a "$csv"
  rm -rf "$run"
}

# The dense bed of about N spheres: side^2 x layers sites.
dense_scene() {  # N FRICTION(true|false) RUN_DIR > scene
  local side layers
  side=$(python3 -c "print(round(($1) ** (1 / 3)))")
  layers=$(python3 -c "print(round($1 / $side ** 2))")
  if [[ $2 == true ]]; then
    bench/lattice_bed.sh "$side" "$layers" "$3" "id, contact_count"
  else
    bench/lattice_bed.sh "$side" "$layers" "$3" "id" | sed 's/effects: {friction: true}/effects: {friction: false}/'
  fi
}

scenes=/tmp/gpu_bench_scenes
mkdir -p "$scenes"
for n in $sizes; do
  dense_scene "$n" true /tmp/gpu_bench_runs/x > "$scenes/dense_$n.yaml"
  dense_scene "$n" false /tmp/gpu_bench_runs/x > "$scenes/dense_nofric_$n.yaml"
done

# Dense beds: 200 steps (the list is built at the first and, in a static bed,
# never again; the rate includes that build). Smallest first, so the large
# ones are what the budget cuts.
for n in $sizes; do
  wanted dense || break
  for round in 1 2; do
    for b in "$before" "$after"; do
      run_case dense "$b" $round "$root" "$scenes/dense_$n.yaml" 200
    done
  done
  for b in "$before" "$after"; do run_case dense_nofric "$b" 1 "$root" "$scenes/dense_nofric_$n.yaml" 200; done
done

# The random polydisperse bed: 4e6 spheres filled at solid fraction 0.24 into
# a 0.4 m x 0.4 m box, settled 0.3 s (the top ones fall 0.27 m, in 0.23 s:
# most of the bed is at rest by then), checkpointed, then 300 steps timed per
# build.
random_n=${RANDOM_BED_N:-4000000}
cat > "$scenes/random.yaml" <<YAML
domain: {min: [0, 0, 0], max: [0.4, 0.4, 0.45]}
gravity: [0, 0, -9.81]
contact_model: linear
precision: fp32
effects: {friction: true}
contact_slots: 16
materials:
  - {name: glass, density: 2500}
pairs:
  - {materials: [glass, glass], stiffness_normal: 2000, restitution: 0.5, friction: 0.5}
walls:
  - box: {min: [0, 0, 0], max: [0.4, 0.4, 0.45]}
    material: glass
particles:
  - random_fill:
      material: glass
      region: {box: {min: [0.001, 0.001, 0.001], max: [0.399, 0.399, 0.449]}}
      count: $random_n
      radius: {min: 0.0008, max: 0.0012}
      seed: 7
time_step: {fraction_of_contact_time: 0.1}
duration: 0.35
output: {interval: 0, fields: [id, contact_count], checkpoint_interval: 0.3}
YAML
if wanted random && (($(left) > 120)); then
  (timeout $(($(left) - 60)) "$after/src/grainstorm" run "$scenes/random.yaml" --backend "$backend" --out /tmp/gpu_bench_random \
     --overwrite > "$out/random_settle.log" 2>&1) || echo "random bed: settling failed or cut (see random_settle.log)"
  grep -E "particles,|set up|done|peak" "$out/random_settle.log"
  checkpoint=$(ls /tmp/gpu_bench_random/checkpoint_*.h5 2>/dev/null | sort | tail -1)
  if [[ -n $checkpoint ]]; then
    sed -i 's/^duration: 0.35/duration: 1/' "$scenes/random.yaml"
    for round in 1 2; do
      for b in "$before" "$after"; do
        run_case random "$b" $round "$root" "$scenes/random.yaml" 300 --restart "$checkpoint"
      done
    done
  fi
else
  echo "skipped random bed: out of time" | tee -a "$out/skipped.txt"
fi

# Mixer case b, soft: settled to t = 1 s (the impeller starts then), then timed turning.
sed -e 's/^duration: .*/duration: 1.05/' -e 's/checkpoint_minutes: 30/checkpoint_interval: 1/' \
  -e 's/fields: \[id, material, marker, radius, position, velocity\]/fields: [id, contact_count]/' \
  cases/mixer/case_b_soft.yaml > cases/mixer/.gpu_bench_b.yaml
if wanted mixer_b && (($(left) > 90)); then
  (cd cases/mixer && timeout $(($(left) - 45)) "$root/$after/src/grainstorm" run .gpu_bench_b.yaml --backend "$backend" \
     --out /tmp/gpu_bench_b --overwrite > "$out/mixer_b_settle.log" 2>&1) || echo "mixer b: settling failed or cut"
  grep -E "particles,|done|peak" "$out/mixer_b_settle.log"
  checkpoint=$(ls /tmp/gpu_bench_b/checkpoint_*.h5 2>/dev/null | sort | tail -1)
  if [[ -n $checkpoint ]]; then
    sed -i 's/^duration: 1.05$/duration: 65/' cases/mixer/.gpu_bench_b.yaml
    for round in 1 2; do
      for b in "$before" "$after"; do
        run_case mixer_b "$b" $round cases/mixer .gpu_bench_b.yaml 5000 --restart "$checkpoint"
      done
    done
  fi
else
  echo "skipped mixer b: out of time" | tee -a "$out/skipped.txt"
fi

# Mixer case a from its start: the small scene (7,680 spheres).
sed -e 's/fields: \[id, material, marker, radius, position, velocity\]/fields: [id, contact_count]/' \
  cases/mixer/case_a.yaml > cases/mixer/.gpu_bench_a.yaml
for round in 1 2; do
  wanted mixer_a || break
  for b in "$before" "$after"; do run_case mixer_a "$b" $round cases/mixer .gpu_bench_a.yaml 20000; done
done
rm -f cases/mixer/.gpu_bench_a.yaml cases/mixer/.gpu_bench_b.yaml

# The dense bed on 2 ranks sharing the GPU (each rank finds its contacts anew every step).
n2=${sizes%% *}
if wanted dense_2ranks && command -v mpirun > /dev/null; then
  LAUNCH="mpirun --allow-run-as-root --oversubscribe -np 2"
  for b in "$before" "$after"; do run_case dense_2ranks "$b" 1 "$root" "$scenes/dense_$n2.yaml" 200; done
  LAUNCH=
fi

# The table: per benchmark and size, the better of the rounds for each build.
python3 - "$csv" "$(basename "$before")" "$(basename "$after")" > "$out/gpu_bench.md" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
before, after = sys.argv[2], sys.argv[3]
def num(s):
    try: return float(s)
    except ValueError: return None
best = {}
for r in rows:
    key = (r["bench"], r["particles"], r["build"])
    rate = num(r["particle_steps_per_s"])
    if rate is not None and (key not in best or rate > num(best[key]["particle_steps_per_s"])):
        best[key] = r
def fmt(r, key):
    return r[key] if r else "-"
print("| benchmark | particles | before (particle-steps/s) | after | after / before | B/particle before | after | contacts/particle |")
print("|---|---|---|---|---|---|---|---|")
seen = []
for r in rows:
    if (r["bench"], r["particles"]) not in seen: seen.append((r["bench"], r["particles"]))
for bench, n in seen:
    b, a = best.get((bench, n, before)), best.get((bench, n, after))
    rb = num(b["particle_steps_per_s"]) if b else None
    ra = num(a["particle_steps_per_s"]) if a else None
    up = f"{ra / rb:.2f}" if rb and ra else "-"
    print(f"| {bench} | {n} | {f'{rb:.3g}' if rb else '-'} | {f'{ra:.3g}' if ra else '-'} | {up} | "
          f"{fmt(b, 'bytes_per_particle')} | {fmt(a, 'bytes_per_particle')} | {fmt(a or b, 'contacts_per_particle')} |")
PY
cat "$out/gpu_bench.md"
