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
  "$(dirname "$0")/lattice_bed.sh" "$side" "$layers" "$out/run_${mode}_$n" > "$out/bed_${mode}_$n.yaml"
  mpirun --allow-run-as-root -np "$n" --bind-to none "$build/src/grainstorm" run "$out/bed_${mode}_$n.yaml" \
    --backend cuda --steps "$steps" --overwrite 2>&1 | grep -E "particles,|^done|time per phase|decomposition:|split|rror" |
    sed "s/^/[$mode $count, $n GPU] /"
done
