#!/usr/bin/env bash
# The seed mixer's case a end to end on 2 CPU-emulated ranks (CTest): the
# particles settle with the impeller at rest, are marked by the side of the
# plane x = 0, and the impeller turns 2 revolutions. The cheaper variant
# (cases/mixer/case_a_ci.yaml: Table 4 stiffness x 0.01, so 10x longer steps)
# keeps it to minutes. Checks: particle count conserved, the tracer is about
# half of the bed (mean x near 0.5, as the seed's Table 3), the bed starts
# segregated (Lacey index near 0 at the marking), mixes (Lacey rises by at
# least 0.04 over the 2 revolutions: 0.023 to 0.094 at the stable step of
# 2026-12-02, 0.02 to 0.18 at the earlier 0.2 t_c; one evaluation's sampling
# noise is about 0.03, docs/MIXING.md), and the impeller's torque opposes its
# rotation once it turns.
# usage: mixer_case_a.sh GRAINSTORM MPIEXEC SCENE_DIR WORKDIR
set -euo pipefail
gs=$1 mpiexec=$2 scenes=$3 work=$4
rm -rf "$work" && mkdir -p "$work"
export OMP_NUM_THREADS=1 OMP_WAIT_POLICY=passive
fail() { echo "FAIL: $*" >&2; exit 1; }
(cd "$scenes" && "$mpiexec" --oversubscribe --allow-run-as-root -np 2 "$gs" run case_a_ci.yaml --backend cpu \
   --out "$work/run" > "$work/run.log" 2>&1) || { tail -20 "$work/run.log"; fail "the run failed"; }
grep -q "particles marked 1 / 0" "$work/run.log" || fail "no marking in run.log"
python3 - "$work/run" <<'PY'
import csv, sys
run = sys.argv[1]
rows = list(csv.DictReader(open(f"{run}/mixing.csv")))
if len(rows) != 3:
    sys.exit(f"FAIL: expected evaluations at 0, 1 and 2 revolutions, got {len(rows)}")
revs = [float(r["revolutions"]) for r in rows]
lacey = [float(r["lacey"]) for r in rows]
mean_x = [float(r["concentration"]) for r in rows]
print("revolutions", revs, "lacey", lacey, "mean x", mean_x)
if abs(revs[0]) > 1e-4 or abs(revs[-1] - 2) > 1e-4:
    sys.exit("FAIL: revolutions are not counted from the impeller's start")
if not 0.35 < mean_x[0] < 0.65:
    sys.exit(f"FAIL: tracer fraction {mean_x[0]} is not about one half")
if lacey[0] > 0.15:
    sys.exit(f"FAIL: the bed is not segregated at the marking (Lacey {lacey[0]})")
if lacey[-1] < lacey[0] + 0.04:
    sys.exit(f"FAIL: the Lacey index did not rise: {lacey}")
series = list(csv.DictReader(open(f"{run}/timeseries.csv")))
if any(int(r["particles"]) != 7680 for r in series):
    sys.exit("FAIL: particles were lost or gained")
turning = [float(r["mesh0_tz"]) for r in series if float(r["time"]) > 0.5]
print("impeller torque z [N m] while turning:", turning)
if not turning or max(turning) >= 0:
    sys.exit("FAIL: the bed does not resist the impeller (torque z should be negative)")
PY
