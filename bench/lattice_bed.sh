#!/usr/bin/env bash
# Prints the scene of a frictional bed of touching glass spheres (1 mm
# radius) on a simple cubic lattice, SIDE x SIDE sites wide and LAYERS tall,
# in a box that holds it; the benchmarks' large bed (bench/scaling_bed.sh,
# bench/setup_time.sh). Snapshots go to RUN_DIR, with FIELDS (default: the
# default fields).
#   bench/lattice_bed.sh SIDE LAYERS RUN_DIR [FIELDS] > bed.yaml
set -euo pipefail
side=$1 layers=$2 run_dir=$3 fields=${4:-}
py() { python3 -c "print($1)"; }
top=$(py "0.001 + $layers * 0.002 + 0.001")
edge=$(py "0.001 + $side * 0.002 + 0.001")
inner=$(py "$edge - 0.0011")
cat <<YAML
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
  - lattice: {material: glass, radius: 0.001, min: [0.0011, 0.0011, 0.0011], max: [$inner, $inner, $(py "$top - 0.0011")], spacing: 0.002}
time_step: {fraction_of_contact_time: 0.1}
duration: 1
output: {interval: 0, directory: $run_dir${fields:+, fields: [$fields]}}
decomposition: {method: slabs, axis: z}
YAML
