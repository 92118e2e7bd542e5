#!/usr/bin/env bash
# What accuracy costs on the mixer (issue "what accuracy costs in time"): the
# Lacey curve of case a (the cheaper CI variant: Table 4 stiffness x 0.01) over
# one revolution, evaluated every quarter revolution, for force precision x
# time step (0.1 and 0.05 contact times, within the scene's stable limit of
# 0.117), against fp64 forces at 0.025 contact times. Runs one after the
# other, so each wall time is the run's own. Prints accuracy_study's CSV
# (backend,scene,model,precision,fraction,wall_s,error,values) for
# bench/plot_accuracy.py; the error is the largest |M - M_ref| over the curve.
#   bench/mixer_accuracy.sh BUILD_DIR BACKEND OUTDIR
set -uo pipefail
build=$1 backend=$2 out=$3
root=$(pwd)
mkdir -p "$out"
variant() {  # precision fraction -> scene path
  local p=$1 f=$2 scene="$root/cases/mixer/accuracy_${1}_${2}.yaml"
  sed -e "s/^precision: fp32/precision: $p/" -e "s/fraction_of_contact_time: [0-9.]*/fraction_of_contact_time: $f/" \
      -e "s/^duration: 4.4 /duration: 2.4 /" -e "s/^    revolution_period: 2$/    revolution_period: 2\n    every: 0.5/" \
      "$root/cases/mixer/case_a_ci.yaml" > "$scene"
  # Each edit must have matched: a scene changed since would run unlabelled.
  grep -q "^precision: $p\$" "$scene" && grep -q "fraction_of_contact_time: $f}" "$scene" &&
    grep -q "^duration: 2.4 " "$scene" && grep -q "^    every: 0.5\$" "$scene" ||
    { echo "mixer_accuracy.sh: cases/mixer/case_a_ci.yaml no longer takes the edits for $p $f" >&2; rm -f "$scene"; exit 1; }
  echo "$scene"
}
runs=("fp64 0.025" "fp32 0.1" "fp64 0.1" "fp32 0.05" "fp64 0.05")
for r in "${runs[@]}"; do
  set -- $r
  scene=$(variant "$1" "$2") || exit 1
  (cd "$root/cases/mixer" && "$root/$build/src/grainstorm" run "$scene" --backend "$backend" \
     --out "$out/run_$1_$2" --overwrite > "$out/run_$1_$2.log" 2>&1) || echo "run $1 $2 failed" >&2
  rm -f "$scene" "$out/run_$1_$2"/particles_*.h5 "$out/run_$1_$2"/meshes_*.h5 "$out/run_$1_$2"/checkpoint_*.h5
done
python3 - "$out" "$backend" "${runs[@]}" <<'PY'
import csv, re, sys
out, backend, runs = sys.argv[1], sys.argv[2], [r.split() for r in sys.argv[3:]]
def curve(p, f):
    return [float(r["lacey"]) for r in csv.DictReader(open(f"{out}/run_{p}_{f}/mixing.csv"))]
def wall(p, f):
    m = re.search(r"total wall ([0-9.]+)", open(f"{out}/run_{p}_{f}.log").read())
    return float(m.group(1))
ref = curve(*runs[0])
print("backend,scene,model,precision,fraction,wall_s,error,values")
print("reference", *runs[0], "lacey", ref, file=sys.stderr)
for p, f in runs[1:]:
    c = curve(p, f)
    n = min(len(c), len(ref))
    err = max(abs(a - b) for a, b in zip(c[:n], ref[:n]))
    print(f"{backend},mixer_a,linear,{p},{f},{wall(p, f):.4g},{err:.4g},{' '.join(f'{x:.4f}' for x in c)}")
PY
