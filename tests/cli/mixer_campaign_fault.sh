#!/usr/bin/env bash
# bench/mixer_campaign.sh on the CPU (CTest) with two runs: one that stops with
# a fault in its first step (tests/cli/leaves_domain.yaml) and one that
# finishes (tests/cli/settle_small.yaml). The failed run is reported, its
# fault snapshot comes back with its logs, the finished one comes back
# without a checkpoint, and a second job skips the failed run (RETRY=0).
# usage: mixer_campaign_fault.sh GRAINSTORM SOURCE_DIR WORKDIR
set -euo pipefail
gs=$1 src=$2 work=$3
rm -rf "$work" && mkdir -p "$work/build/src" "$work/camp"
ln -s "$(realpath "$gs")" "$work/build/src/grainstorm"
cp "$src/tests/cli/leaves_domain.yaml" "$work/camp/a_fault.yaml"
cp "$src/tests/cli/settle_small.yaml" "$work/camp/b_done.yaml"
: > "$work/camp/impeller.stl"  # the campaign's mesh; these scenes use none
fail() { echo "FAIL: $*" >&2; cat "$work"/job*.out >&2; exit 1; }
job() {  # N OUT: one job of the campaign
  (cd "$src" && WORK="$work/work$1" BACKEND=cpu PACK=0 BUDGET_S=120 RESERVE_S=5 MIN_PIECE_S=1 OMP_NUM_THREADS=1 \
     bench/mixer_campaign.sh "$work/build" "$2" "$work/out$1" > "$work/job$1.out" 2>&1) || fail "job $1 exited $?"
}
job 1 "$work/camp"
grep -q "^a_fault: FAILED (exit 1)" "$work/job1.out" || fail "the fault is not reported"
grep -q "^b_done: finished" "$work/job1.out" || fail "the finished run is not reported"
ls "$work/out1/a_fault"/fault_*.h5 > /dev/null 2>&1 || fail "no fault snapshot came back"
"$gs" info "$(ls "$work/out1/a_fault"/fault_*.h5)" | grep -q "particles:     2" || fail "the fault snapshot does not read"
ls "$work/out1/b_done"/checkpoint_*.h5 > /dev/null 2>&1 && fail "a finished run's checkpoint came back"
ls "$work/out1/b_done"/fault_*.h5 > /dev/null 2>&1 && fail "a fault snapshot for a finished run"
job 2 "$work/out1"
grep -q "^a_fault: skipped, its last piece failed" "$work/job2.out" || fail "the second job did not skip the failed run"
echo "mixer campaign with a fault: ok"
