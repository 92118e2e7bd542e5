#!/usr/bin/env bash
# Weak and strong scaling of a frictional bed of touching spheres (a lattice
# that starts settling at once), stacked along z, the slab axis; one GPU per
# rank, 1, 2, 4 and 8 ranks up to NMAX.
#   bench/scaling_bed.sh BUILD_DIR weak|strong N NMAX STEPS OUTDIR
#   weak:   N particles per rank; the bed grows along z with the ranks.
#   strong: N particles in all, a bed twice as tall as wide, on every rank count.
set -euo pipefail
build=$1 mode=$2 count=$3 nmax=$4 steps=$5 out=$6
mkdir -p "$out"
py() { python3 -c "print($1)"; }
for n in 1 2 4 8; do
  ((n <= nmax)) || continue
  if [[ $mode == weak ]]; then
    side=$(py "round(($count) ** (1/3))")
    layers=$((side * n))
  else
    side=$(py "round(($count / 2) ** (1/3))")
    layers=$(py "round($count / $side**2)")
  fi
  top=$(py "0.001 + $layers * 0.002 + 0.001")
  edge=$(py "0.001 + $side * 0.002 + 0.001")
  inner=$(py "$edge - 0.0011")
  cat > "$out/bed_${mode}_$n.yaml" <<YAML
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
time_step: {fraction_of_contact_time: 0.2}
duration: 1
output: {interval: 0, directory: $out/run_${mode}_$n}
decomposition: {method: slabs, axis: z}
YAML
  mpirun --allow-run-as-root -np "$n" --bind-to none "$build/src/grainstorm" run "$out/bed_${mode}_$n.yaml" \
    --backend cuda --steps "$steps" --overwrite 2>&1 | grep -E "particles,|^done|time per phase|decomposition:|split|rror" |
    sed "s/^/[$mode $count, $n GPU] /"
done
