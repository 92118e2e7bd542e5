#!/usr/bin/env bash
# Cost of the measurements (docs/MEASUREMENTS.md) on the CPU: the settling
# demo (2000 spheres) for STEPS steps, without measurements and with a flow,
# a region average and a 10 x 10 x 20 grid of every quantity, each evaluated
# every EVERY steps; prints the runs' wall times and the measurement costs
# from their logs.
#   bench/measurement_cost.sh BUILD_DIR [STEPS=4000] [EVERY=100] [RANKS=1]
set -euo pipefail
build=$(cd "$1" && pwd)
steps=${2:-4000}
every=${3:-100}
ranks=${4:-1}
root=$(cd "$(dirname "$0")/.." && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
python=/usr/bin/python3
[ -x "$python" ] || python=python3
"$python" - "$root/cases/demo/settle.yaml" "$work" "$steps" "$every" <<'PY'
import sys, yaml
scene, work, steps, every = sys.argv[1], sys.argv[2], int(sys.argv[3]), int(sys.argv[4])
s = yaml.safe_load(open(scene))
s['output'] = {'interval': 0}
open(work + '/plain.yaml', 'w').write(yaml.safe_dump(s))
# The step is fraction_of_contact_time 0.11 of 0.2005 ms; 'every' in seconds
# from the step the loader derives is written by the caller's check below.
s['measurements'] = {
    'flows': [{'name': 'middle', 'plane': {'point': [0.02, 0.02, 0.02], 'normal': [0, 0, -1]}, 'every': 'EVERY'}],
    'averages': [
        {'name': 'bed', 'box': {'min': [0, 0, 0], 'max': [0.04, 0.04, 0.08]},
         'quantities': ['solid_fraction', 'velocity', 'granular_temperature', 'coordination', 'stress'], 'every': 'EVERY'},
        {'name': 'grid', 'box': {'min': [0, 0, 0], 'max': [0.04, 0.04, 0.08]}, 'bins': [10, 10, 20],
         'quantities': ['solid_fraction', 'velocity', 'granular_temperature', 'coordination', 'stress'], 'every': 'EVERY'}]}
open(work + '/measured.yaml', 'w').write(yaml.safe_dump(s))
PY
dt=$("$build/src/grainstorm" check "$work/plain.yaml" | awk '/^time step:/ {print $3}')
interval=$("$python" -c "print(repr($every * $dt * (1 + 1e-9)))")
sed -i "s/EVERY/$interval/" "$work/measured.yaml"
export OMP_NUM_THREADS=${OMP_NUM_THREADS:-2}
run() {
  if [[ $ranks == 1 ]]; then "$build/src/grainstorm" "$@"
  else mpiexec --oversubscribe --allow-run-as-root -np "$ranks" "$build/src/grainstorm" "$@"; fi
}
for kind in plain measured plain measured; do
  rm -rf "$work/out_$kind"
  run run "$work/$kind.yaml" --backend cpu --steps "$steps" --out "$work/out_$kind" > /dev/null 2>&1
  echo "$kind: $(grep '^time per phase' "$work/out_$kind/run.log")"
  grep '^measurement' "$work/out_$kind/run.log" || true
done
