#!/usr/bin/env bash
# The dense bed of about N spheres of 1 mm radius: side^2 x layers sites of a
# simple cubic lattice of spacing one diameter, in a box that holds it exactly
# (the outer spheres touch its walls). Radii are stored in fp32, 4.7e-11 m
# above 1 mm, so every touching pair overlaps by that much: six contacts per
# sphere (walls included) from the first step on, and the bed stays at rest
# under gravity.
# Used by bench/gpu_bench.sh and bench/memory_bench.sh.
#   bench/dense_bed.sh N FRICTION(true|false) > scene.yaml
set -euo pipefail
python3 - "$1" "$2" <<'PY'
import sys
n, friction = int(sys.argv[1]), sys.argv[2]
side = round(n ** (1 / 3))
layers = round(n / side ** 2)
s = 0.002  # spacing
edge, top = side * s, layers * s
print(f"""domain: {{min: [-0.001, -0.001, -0.001], max: [{edge + 0.001!r}, {edge + 0.001!r}, {top + 0.001!r}]}}
gravity: [0, 0, -9.81]
contact_model: linear
precision: fp32
effects: {{friction: {friction}}}
materials:
  - {{name: glass, density: 2500}}
pairs:
  - {{materials: [glass, glass], stiffness_normal: 2000, restitution: 0.5, friction: 0.5}}
walls:
  - box: {{min: [0, 0, 0], max: [{edge!r}, {edge!r}, {top!r}]}}
    material: glass
particles:
  - lattice: {{material: glass, radius: 0.001, min: [0.001, 0.001, 0.001], max: [{edge - s / 4!r}, {edge - s / 4!r}, {top - s / 4!r}], spacing: {s!r}}}
time_step: {{fraction_of_contact_time: 0.1}}
duration: 1
output: {{interval: 0, fields: [id]}}""")
PY
