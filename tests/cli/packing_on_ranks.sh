#!/usr/bin/env bash
# The packing checks of a run, spread over its ranks (src/run/packing_on_ranks.hpp),
# reach the verdict `grainstorm check` reaches over every particle on its own:
# a random fill that does not fit the domain, and a sphere that overlaps
# particles of a fill, are each refused on 1, 2 and 3 ranks with exactly the
# check's message (the set's file:line and key, the same particles), once,
# with a non-zero exit and nothing written.
# usage: packing_on_ranks.sh GRAINSTORM MPIEXEC MISFIT_SCENE OVERLAP_SCENE WORKDIR
set -euo pipefail
gs=$1 mpiexec=$2 misfit=$3 overlap=$4 work=$5
rm -rf "$work" && mkdir -p "$work" && cd "$work"
export OMP_NUM_THREADS=2 OMP_WAIT_POLICY=passive
fail() { echo "FAIL: $*" >&2; exit 1; }

for scene in "$misfit" "$overlap"; do
  name=$(basename "$scene" .yaml)
  set +e
  "$gs" check "$scene" > "$name.check.out" 2> "$name.check.err"
  code=$?
  set -e
  [[ $code != 0 ]] || fail "$name: check passed"
  expect=$(grep "^grainstorm: error: " "$name.check.err") || fail "$name: check gave no error: $(cat "$name.check.err")"
  for ranks in 1 2 3; do
    set +e
    timeout 120 "$mpiexec" --oversubscribe --allow-run-as-root -np $ranks "$gs" run "$scene" --backend cpu \
      --out "$name.$ranks" > "$name.$ranks.out" 2> "$name.$ranks.err"
    code=$?
    set -e
    [[ $code != 124 ]] || fail "$name on $ranks ranks: still running after 120 s"
    [[ $code != 0 ]] || fail "$name on $ranks ranks: exit code 0"
    got=$(grep "^grainstorm: " "$name.$ranks.err" || true)
    [[ $got == "$expect" ]] || fail "$name on $ranks ranks: '$got', expected '$expect'"
    [[ ! -e $name.$ranks ]] || fail "$name on $ranks ranks: $name.$ranks was written"
  done
  echo "$name: $expect"
done
