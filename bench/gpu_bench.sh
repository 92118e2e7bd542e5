#!/usr/bin/env bash
# Before against after on one GPU: the four benchmarks of issue 21, each run by
# both builds in turn (alternating, so drifts of the machine hit both alike),
# each line with particle-steps/s, device bytes per particle and contacts per
# particle; a before/after table at the end.
#   bench/gpu_bench.sh BEFORE_BUILD AFTER_BUILD OUTDIR [SECONDS] [SIZES]
# BEFORE_BUILD, AFTER_BUILD: build directories, relative to the repository
# root (run from there), holding src/grainstorm (and
# bench/settle_bench). SECONDS (default 300): the whole script's budget; a run
# that would start after it is skipped and said so. SIZES (default
# "4000000 16000000 64000000"): the dense beds' particle counts, smallest
# first. Results: OUTDIR/gpu_bench.csv, OUTDIR/gpu_bench.md, logs OUTDIR/*.log.
#
# The benchmarks:
#  dense      the static dense bed: a touching simple-cubic lattice in a box
#             that holds it exactly, gravity, friction, six contacts per
#             sphere; also frictionless (dense_nofric).
#  random     a poured random polydisperse bed: radii 0.8-1.2 mm filled at
#             random into a box and settled under gravity by AFTER_BUILD (to a
#             checkpoint), then timed from that checkpoint by both builds.
#  mixer_b    a flowing bed: mixer case b's soft variant (cases/mixer), settled
#             1 s to a checkpoint, then timed turning at 30 rpm.
#  mixer_a    the small scene: mixer case a, timed from its start (settling).
#  dense_2ranks  the smallest dense bed on 2 ranks sharing the GPU.
# Bytes per particle: the run's peak device memory per owned particle, as
# its log prints it (an older build's, "~", from its peak printed to 0.1 GiB
# or MiB over its particles). Contacts per particle: occupied contact-history
# slots (walls included) over particles at the end (the run's timeseries.csv).
# BACKEND=cpu runs it all on the CPU instead (a dry run of the script);
# SKIP="random mixer_b ..." leaves those benchmarks out; RANDOM_BED_N sets the
# random bed's size (default 2e6); ROUNDS the rounds per benchmark (default 1).
# BEFORE_SRC (a source tree, e.g. git archive <commit> unpacked): the before
# build's own mixer scenes, and each build settles the random bed and mixer
# case b to a checkpoint of its own and is timed from it (an older commit
# reads neither today's checkpoints nor, perhaps, its scenes); without it
# both builds restart from AFTER_BUILD's checkpoints and read this tree's scenes.
set -uo pipefail
backend=${BACKEND:-cuda}
skip=" ${SKIP:-} "
wanted() { [[ $skip != *" $1 "* ]]; }
before=$1 after=$2 out=$3 budget=${4:-300} sizes=${5:-"4000000 16000000 64000000"}
root=$(pwd)
before_src=${BEFORE_SRC:+$(cd "$BEFORE_SRC" && pwd)}
# The mixer scenes a build reads: its own tree's where BEFORE_SRC is given.
mixer_dir() { [[ -n $before_src && $1 == "$before" ]] && echo "$before_src/cases/mixer" || echo "$root/cases/mixer"; }
# The builds that settle a bed to a checkpoint: each where BEFORE_SRC is given, else AFTER_BUILD alone.
settlers() { [[ -n $before_src ]] && echo "$before $after" || echo "$after"; }
mkdir -p "$out"
out=$(cd "$out" && pwd)  # the runs log there from their scenes' directories
deadline=$((SECONDS + budget))
csv=$out/gpu_bench.csv
echo "bench,particles,build,round,particle_steps_per_s,bytes_per_particle,contacts_per_particle" > "$csv"
# particle_steps_per_s: of the step loop alone (step_rate_of, below).
left() { echo $((deadline - SECONDS)); }

# Contacts per particle at the run's end: the last row of its timeseries.csv
# (occupied history slots over particles), or "-" (none, or no friction).
contacts_of() {
  python3 - "$1/timeseries.csv" <<'PY' 2>/dev/null || echo -
import csv, sys
row = list(csv.DictReader(open(sys.argv[1])))[-1]
c, n = float(row["contacts"]), float(row["particles"])
print(f"{c / n:.2f}" if c >= 0 and n > 0 else "-")
PY
}

# Bytes per particle of a run log: its exact figure ("N bytes per owned
# particle") where it has one, else (an older build) the peak printed in
# GiB or MiB over the particle count, marked "~" (printed to 0.1 GiB: +-13
# bytes per particle at 4e6).
bytes_of() {
  python3 - "$1" "$backend" <<'PY'
import re, sys
t = open(sys.argv[1]).read()
exact = re.search(sys.argv[2] + r" memory \(rank 0\): [^,\n]+, ([\d.]+) bytes per owned particle", t)
if exact: print(exact.group(1)); sys.exit()
n = re.search(r"(\d+) particles, backend", t)
m = re.search(sys.argv[2] + r" memory \(rank 0\): ([\d.]+) (B|KiB|MiB|GiB|TiB)", t)
if not (n and m): print("-"); sys.exit()
scale = {"B": 1, "KiB": 2**10, "MiB": 2**20, "GiB": 2**30, "TiB": 2**40}[m.group(2)]
print(f"~{float(m.group(1)) * scale / int(n.group(1)):.0f}")
PY
}

# Particle-steps per second of the steps alone: particles x steps over the
# time inside the step loop (the run log's phases: integration, neighbour
# build, contact forces, exchange), not the set-up and the snapshots, which
# dominate a run of a few hundred steps.
step_rate_of() {
  python3 - "$1" <<'PY'
import re, sys
t = open(sys.argv[1]).read()
n = re.search(r"(\d+) particles, backend .* steps (\d+) to (\d+)", t)
p = re.search(r"integration ([\d.]+), neighbour build ([\d.]+), contact forces ([\d.]+), exchange ([\d.]+)", t)
if not (n and p) or "done:" not in t: sys.exit()
seconds = sum(float(x) for x in p.groups())
print(f"{int(n.group(1)) * (int(n.group(3)) - int(n.group(2))) / seconds:.3g}" if seconds > 0 else "")
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
  rm -rf "$run"  # a restart takes a new directory (--overwrite and --restart exclude each other)
  (cd "$dir" && timeout "$(left)" $LAUNCH "$root/$build/src/grainstorm" run "$scene" --backend "$backend" --steps "$steps" \
     --out "$run" "$@" > "$log" 2>&1)
  local rc=$?
  local rate n
  rate=$(step_rate_of "$log")
  n=$(grep -oE "[0-9]+ particles, backend" "$log" | cut -d' ' -f1)
  [[ $rc == 0 && -n $rate ]] || { echo "FAILED $tag (exit $rc): $(tail -2 "$log" | tr '\n' ' ')"; rate=-; }
  echo "$bench,${n:--},$(basename "$build"),$round,$rate,$(bytes_of "$log"),$(contacts_of "$run")" | tee -a "$csv"
  rm -rf "$run"
}

dense_scene() { "$(dirname "${BASH_SOURCE[0]}")/dense_bed.sh" "$@"; }  # N FRICTION > scene (bench/dense_bed.sh)

scenes=/tmp/gpu_bench_scenes
mkdir -p "$scenes"
for n in $sizes; do
  dense_scene "$n" true > "$scenes/dense_$n.yaml"
  dense_scene "$n" false > "$scenes/dense_nofric_$n.yaml"
done

# Dense beds: 400 steps (the list is built at the first and, in a static bed,
# never again; the rate includes that build), ROUNDS rounds (default 1). The
# smallest size first, the largest last, after the other benchmarks: it is
# what the budget cuts.
rounds=$(seq 1 "${ROUNDS:-1}")
dense_runs() {
  for n in "$@"; do
    wanted dense || break
    for round in $rounds; do
      for b in "$before" "$after"; do
        run_case dense "$b" $round "$root" "$scenes/dense_$n.yaml" 400
      done
    done
    for b in "$before" "$after"; do run_case dense_nofric "$b" 1 "$root" "$scenes/dense_nofric_$n.yaml" 400; done
  done
}
read -r -a size_list <<< "$sizes"
dense_runs "${size_list[@]:0:${#size_list[@]}-1}"

# settle_to_checkpoint BUILD DIR SCENE RUN LOG LIMIT_S: runs SCENE (from DIR) with
# BUILD until its first checkpoint is written (at most LIMIT_S), then stops it (SIGTERM;
# the run writes one more); prints that first checkpoint. A restart must read
# the same scene file (its hash), so the scene runs on past the checkpoint.
settle_to_checkpoint() {
  local build=$1 dir=$2 scene=$3 run=$4 log=$5 limit=$6 pid stop
  rm -rf "$run"
  (cd "$dir" && exec "$root/$build/src/grainstorm" run "$scene" --backend "$backend" --out "$run") \
    > "$log" 2>&1 &
  pid=$! stop=$((SECONDS + limit))
  while kill -0 "$pid" 2> /dev/null && ((SECONDS < stop)); do
    compgen -G "$run/checkpoint_*.h5" > /dev/null && break
    sleep 0.5
  done
  kill -TERM "$pid" 2> /dev/null
  wait "$pid"
  ls "$run"/checkpoint_*.h5 2> /dev/null | sort | head -1
}

# The step a checkpoint was written at, from its name.
step_of() { local b; b=$(basename "$1" .h5); echo $((10#${b#checkpoint_})); }

# The random polydisperse bed: 2e6 spheres filled at solid fraction 0.21 into
# a 0.3 m x 0.3 m box, settled 0.3 s (the top ones fall 0.29 m, in 0.24 s:
# most of the bed is at rest by then) to a checkpoint, then 300 steps timed
# per build from it.
random_n=${RANDOM_BED_N:-2000000}
cat > "$scenes/random.yaml" <<YAML
domain: {min: [0, 0, 0], max: [0.3, 0.3, 0.45]}
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
  - box: {min: [0, 0, 0], max: [0.3, 0.3, 0.45]}
    material: glass
particles:
  - random_fill:
      material: glass
      region: {box: {min: [0.001, 0.001, 0.001], max: [0.299, 0.299, 0.449]}}
      count: $random_n
      radius: {min: 0.0008, max: 0.0012}
      seed: 7
time_step: {fraction_of_contact_time: 0.1}
duration: 10
output: {interval: 0, fields: [id], checkpoint_interval: 0.3}
YAML
if wanted random && (($(left) > 120)); then
  for settler in $(settlers); do
    tag=$(basename "$settler")
    checkpoint=$(settle_to_checkpoint "$settler" "$root" "$scenes/random.yaml" /tmp/gpu_bench_random_$tag \
      "$out/random_settle_$tag.log" $(($(left) > 150 ? 90 : $(left) - 60)))
    grep -E "particles,|set up|stopped|peak" "$out/random_settle_$tag.log"
    if [[ -z $checkpoint ]]; then echo "random bed: no checkpoint (see random_settle_$tag.log)"; continue; fi
    timed=$([[ -n $before_src ]] && echo "$settler" || echo "$before $after")  # each from its own, or both from one
    for round in $rounds; do
      for b in $timed; do
        run_case random "$b" $round "$root" "$scenes/random.yaml" $(($(step_of "$checkpoint") + 300)) \
          --restart "$checkpoint"
      done
    done
  done
else
  echo "skipped random bed: $(wanted random && echo "out of time" || echo "in SKIP")" | tee -a "$out/skipped.txt"
fi

# Mixer case b, soft: settled to t = 1 s (the impeller starts then) to a
# checkpoint, then 5000 steps (0.18 s, a tenth of a turn) timed turning.
for b in "$before" "$after"; do
  sed -e 's/checkpoint_minutes: 30/checkpoint_interval: 1/' \
    -e 's/fields: \[id, material, marker, radius, position, velocity\]/fields: [id]/' \
    "$(mixer_dir "$b")/case_b_soft.yaml" > "$(mixer_dir "$b")/.gpu_bench_b.yaml"
done
if wanted mixer_b && (($(left) > 90)); then
  for settler in $(settlers); do
    tag=$(basename "$settler")
    checkpoint=$(settle_to_checkpoint "$settler" "$(mixer_dir "$settler")" .gpu_bench_b.yaml /tmp/gpu_bench_b_$tag \
      "$out/mixer_b_settle_$tag.log" $(($(left) > 120 ? 60 : $(left) - 60)))
    grep -E "particles,|stopped|peak" "$out/mixer_b_settle_$tag.log"
    if [[ -z $checkpoint ]]; then echo "mixer b: no checkpoint (see mixer_b_settle_$tag.log)"; continue; fi
    timed=$([[ -n $before_src ]] && echo "$settler" || echo "$before $after")
    for round in $rounds; do
      for b in $timed; do
        run_case mixer_b "$b" $round "$(mixer_dir "$b")" .gpu_bench_b.yaml $(($(step_of "$checkpoint") + 5000)) \
          --restart "$checkpoint"
      done
    done
  done
else
  echo "skipped mixer b: $(wanted mixer_b && echo "out of time" || echo "in SKIP")" | tee -a "$out/skipped.txt"
fi

# Mixer case a from its start: the small scene (7,680 spheres).
for b in "$before" "$after"; do
  sed -e 's/fields: \[id, material, marker, radius, position, velocity\]/fields: [id]/' \
    "$(mixer_dir "$b")/case_a.yaml" > "$(mixer_dir "$b")/.gpu_bench_a.yaml"
done
for round in $rounds; do
  wanted mixer_a || break
  for b in "$before" "$after"; do run_case mixer_a "$b" $round "$(mixer_dir "$b")" .gpu_bench_a.yaml 20000; done
done
for b in "$before" "$after"; do rm -f "$(mixer_dir "$b")"/.gpu_bench_a.yaml "$(mixer_dir "$b")"/.gpu_bench_b.yaml; done

# The dense bed on 2 ranks sharing the GPU (each rank finds its contacts anew every step).
n2=${sizes%% *}
if wanted dense_2ranks && command -v mpirun > /dev/null; then
  LAUNCH="mpirun --allow-run-as-root --oversubscribe -np 2"
  for b in "$before" "$after"; do run_case dense_2ranks "$b" 1 "$root" "$scenes/dense_$n2.yaml" 200; done
  LAUNCH=
fi

dense_runs "${size_list[@]: -1}"

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
