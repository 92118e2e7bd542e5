#!/usr/bin/env bash
# Set-up time of a run whose particles come from one random fill: N spheres
# of d = 1 mm at a solid fraction of 0.2 in a box twice as tall as wide, on R
# ranks free to use every core (--bind-to none). The run is stopped once it has
# printed its set-up line (what follows is not set-up).
#   bench/setup_fill.sh BUILD_DIR N [RANKS=1] [BACKEND=cpu] [OUTDIR=/tmp/setup_fill]
# Prints the run's "set up in" line (scene load, packing checks, decomposition, particles,
# first forces) and the wall-clock seconds until it.
set -euo pipefail
build=$1 count=$2 ranks=${3:-1} backend=${4:-cpu} out=${5:-/tmp/setup_fill}
mkdir -p "$out"
# Box side a with 2 a^3 * 0.2 = N * pi / 6 * d^3.
side=$(python3 -c "print(round(($count * 3.14159265 / 6 * 1e-9 / 0.4) ** (1 / 3), 6))")
height=$(python3 -c "print(2 * $side)")
outer=$(python3 -c "print($side + 0.001)") top=$(python3 -c "print($height + 0.001)")
scene=$out/fill_$count.yaml
cat > "$scene" <<YAML
domain: {min: [-0.001, -0.001, -0.001], max: [$outer, $outer, $top]}
gravity: [0, 0, -9.81]
contact_model: linear
precision: fp32
effects: {friction: true, rolling_resistance: false, cohesion: false}
materials: [{name: glass, density: 2500}]
pairs: [{materials: [glass, glass], stiffness_normal: 1000, restitution: 0.5, friction: 0.5}]
walls: [{box: {min: [0, 0, 0], max: [$side, $side, $height]}, material: glass, name: box}]
particles:
  - random_fill: {material: glass, region: {box: {min: [0, 0, 0], max: [$side, $side, $height]}}, count: $count, radius: 0.0005, seed: 1}
time_step: {fraction_of_contact_time: 0.1}
duration: 1
output: {interval: 1, directory: $out/run_$count}
YAML
log=$out/setup_$count.log
start=$(date +%s.%N)
mpiexec --allow-run-as-root --oversubscribe --bind-to none -n "$ranks" \
  "$build/src/grainstorm" run "$scene" --backend "$backend" --steps 1 --overwrite > "$log" 2>&1 &
run=$!
while kill -0 $run 2>/dev/null && ! grep -q "set up in" "$log"; do sleep 0.1; done
end=$(date +%s.%N)
kill $run 2>/dev/null || true
wait $run 2>/dev/null || true
grep -E "particles,|set up in|rror" "$log" || tail -5 "$log"
python3 -c "print('wall clock to set-up line: %.2f s' % ($end - $start))"
