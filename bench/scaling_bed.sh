#!/usr/bin/env bash
# Weak scaling of a settled frictional bed: PER_GPU particles per rank, the
# bed stacked along z (the slab axis), 1 to NMAX ranks, one GPU each.
#   bench/scaling_bed.sh BUILD_DIR PER_GPU NMAX STEPS OUTDIR
set -euo pipefail
build=$1 per=$2 nmax=$3 steps=$4 out=$5
mkdir -p "$out"
side=$(python3 -c "print(round(($per) ** (1/3)))")
for n in $(seq 1 "$nmax"); do
  [[ $n == 1 || $n == 2 || $n == 4 || $n == 8 ]] || continue
  layers=$(( side * n ))
  top=$(python3 -c "print(0.001 + $layers * 0.002 + 0.001)")
  edge=$(python3 -c "print(0.001 + $side * 0.002 + 0.001)")
  cat > "$out/bed_$n.yaml" <<YAML
domain: {min: [-0.001, -0.001, -0.001], max: [$edge, $edge, $top]}
gravity: [0, 0, -9.81]
contact_model: linear
precision: fp32
effects: {friction: true}
materials:
  - {name: glass, density: 2500}
pairs:
  - {materials: [glass, glass], stiffness_normal: 2000, restitution: 0.5, friction: 0.5}
walls:
  - box: {min: [0, 0, 0], max: [$edge, $edge, $top]}
    material: glass
particles:
  - lattice: {material: glass, radius: 0.001, min: [0.0011, 0.0011, 0.0011], max: [$(python3 -c "print($edge - 0.0011)"), $(python3 -c "print($edge - 0.0011)"), $(python3 -c "print($top - 0.0011)")], spacing: 0.002}
time_step: {fraction_of_contact_time: 0.2}
duration: 1
output: {interval: 0, directory: $out/run_$n}
decomposition: {method: slabs, axis: z}
YAML
  mpirun --allow-run-as-root -np "$n" --bind-to none "$build/src/grainstorm" run "$out/bed_$n.yaml" --backend cuda \
    --steps "$steps" 2>/dev/null | grep -E "particles,|^done|time per phase|decomposition:" | sed "s/^/[$n GPU] /"
done
