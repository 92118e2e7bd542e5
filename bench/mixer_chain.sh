#!/usr/bin/env bash
# Several long mixer runs side by side on one GPU (a small bed leaves the GPU
# mostly idle, so runs sharing it lose little), in pieces: call it again, on
# the same machine, to go on from the checkpoints. Builds grainstorm first if
# needed. Results (mixing.csv, timeseries.csv, logs, top views of the marking
# and the newest snapshot) go into $OUT/mixruns.tar.gz.
#   bench/mixer_chain.sh LIMIT_S SCENE...     (scenes relative to cases/mixer)
set -uo pipefail
limit=$1; shift
root=$(pwd)
OUT=${OUT:-$root/device_out}
runs=${RUNS:-/tmp/mixruns}
mkdir -p "$OUT" "$runs"
start=$(date +%s)
source "$root/bench/carried_deps.sh"
use_carried_deps "$root"
if [[ ! -x build-gpu/src/grainstorm ]]; then
  { cmake -S . -B build-gpu -DCMAKE_BUILD_TYPE=Release -DGS_ENABLE_CUDA=ON "${extra[@]}" &&
    cmake --build build-gpu -j 16 --target grainstorm; } > "$runs/build.log" 2>&1 || { tail -40 "$runs/build.log"; exit 1; }
fi
left=$((limit - ($(date +%s) - start) - 40))
echo "build took $(($(date +%s) - start)) s; running for $left s"
for scene in "$@"; do
  name=$(basename "$scene" .yaml)
  # A checkpoint carried from an earlier machine starts an absent run: the
  # parts that KEEP_CHECKPOINTS=1 returned, put in carry/seed/.
  if [[ ! -d $runs/$name ]] && compgen -G "carry/seed/seed_$name.tar.gz.part*" > /dev/null; then
    mkdir -p "$runs/$name" && cat carry/seed/seed_$name.tar.gz.part* | tar xzf - -C "$runs/$name"
  fi
  bench/mixer_long.sh build-gpu/src/grainstorm "cases/mixer/$scene" "$runs/$name" "$left" cuda &
done
wait
nvidia-smi --query-gpu=name --format=csv,noheader
pack=$runs/pack
rm -rf "$pack" && mkdir -p "$pack"
for scene in "$@"; do
  name=$(basename "$scene" .yaml) dir=$runs/$(basename "$scene" .yaml)
  cp "$dir"/mixing.csv "$dir"/timeseries.csv "$dir"/run.log "$pack/" 2>/dev/null
  for f in mixing.csv timeseries.csv run.log; do [[ -f $pack/$f ]] && mv "$pack/$f" "$pack/${name}_$f"; done
  tr '\r' '\n' < "$dir/pieces.log" | grep -v '^step ' > "$pack/${name}_pieces.log"
  tr '\r' '\n' < "$dir/pieces.log" | grep '^step ' | tail -1
  tail -3 "$dir/mixing.csv"
  snaps=($(ls "$dir"/particles_*.h5 2>/dev/null | sort))
  ((${#snaps[@]} > 1)) && python3 tools/render_topview.py "${snaps[1]}" -o "$pack/${name}_marked.png" --size 800 > /dev/null
  ((${#snaps[@]} > 2)) && python3 tools/render_topview.py "${snaps[-1]}" -o "$pack/${name}_last.png" --size 800 > /dev/null
done
tar czf "$OUT/mixruns.tar.gz" -C "$pack" .
# KEEP_CHECKPOINTS=1: the newest checkpoint of each unfinished run comes back
# too (seed_NAME.tar.gz.partNN), to be carried to the next machine in carry/seed/.
if [[ ${KEEP_CHECKPOINTS:-0} == 1 ]]; then
  for scene in "$@"; do
    name=$(basename "$scene" .yaml)
    grep -q '^done:' "$runs/$name/pieces.log" && continue
    last=$(ls "$runs/$name"/checkpoint_*.h5 2>/dev/null | sort | tail -1)
    # In parts of 15 MiB: a leased machine returns files of at most 16 MiB.
    [[ -n $last ]] && tar czf - -C "$runs/$name" "$(basename "$last")" | split -b 15M -d - "$OUT/seed_$name.tar.gz.part"
  done
fi
ls -la "$OUT"
