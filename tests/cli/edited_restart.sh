#!/usr/bin/env bash
# A restart with an edited scene (--edited-scene, docs/OUTPUT.md):
#  1. without the option an edited scene is refused, the message says how to go on;
#  2. a new wall listed before the others (every wall's index moves by one)
#     and edited output settings: the contacts' springs follow their walls, so
#     the continued run equals the unedited one bit for bit, on 1 and 2 ranks,
#     and the run log lists the edits;
#  3. a moved wall that cuts into the particles is refused, naming the wall
#     (the box's other walls, planes through the same places, are kept);
#  4. contact_slots below a particle's contacts is refused, naming the key;
#  5. an edit that changes the time step (a stiffer pair, a shorter contact
#     time) is refused, naming the step to keep (the run's time is its step
#     count times the step);
#  6. --steps before the checkpoint's step is refused, and the output
#     directory keeps what followed the checkpoint.
# usage: edited_restart.sh GRAINSTORM MPIEXEC SCENE WORKDIR
set -euo pipefail
gs=$1 mpiexec=$2 scene=$3 work=$4
source "$(dirname "${BASH_SOURCE[0]}")/restart_helpers.sh"
refused() {  # refused NAME PATTERN SCENE: the restart fails on every rank, says PATTERN, writes nothing
  local name=$1 pattern=$2; shift 2
  set +e; mpi 2 run "$@" --backend cpu --restart "$checkpoint" --steps "$end" --edited-scene --out "$name" \
    > "$name.log" 2> "$name.err"; local code=$?; set -e
  [[ $code != 0 ]] || fail "$name: accepted"
  grep -q "$pattern" "$name.err" || fail "$name: the refusal does not say '$pattern': $(cat "$name.err")"
  [[ ! -e $name ]] || fail "$name: a refused restart wrote output"
  echo "$name refused: $(grep -o "error: .*" "$name.err" | head -c 240)"
}

# The bed has settled onto the box's floor and walls by step 20,000 (0.2 s).
cp "$scene" scene.yaml
"$gs" run scene.yaml --backend cpu --steps 20000 --out first > /dev/null
checkpoint=first/checkpoint_0000020000.h5
[[ -f $checkpoint ]] || fail "no checkpoint at the end of the first run"
end=21000
"$gs" run scene.yaml --backend cpu --restart "$checkpoint" --steps "$end" --out reference > /dev/null

# 1. An edit alone is refused.
python3 - <<'PY'
text = open("scene.yaml").read()
far = "  - plane: {point: [0, 0, 0.0405], normal: [0, 0, -1]}\n    name: far\n    material: glass\n"
edited = text.replace("walls:\n", "walls:\n" + far).replace("interval: 0.02,", "interval: 0.01,")
assert edited != text and "name: far" in edited and "interval: 0.01" in edited
open("edited.yaml", "w").write("# edited: a far wall first, snapshots twice as often\n" + edited)
moved = text.replace("box: {min: [0, 0, 0],", "box: {min: [0, 0, 0.0004],")
assert moved != text
open("moved.yaml", "w").write(moved)
narrow = text + "contact_slots: 2\n"
open("narrow.yaml", "w").write(narrow)
stiffer = text.replace("stiffness_normal: 1000,", "stiffness_normal: 4000,")
assert stiffer != text
open("stiffer.yaml", "w").write(stiffer)
PY
set +e; "$gs" run edited.yaml --backend cpu --restart "$checkpoint" --out plain > plain.log 2> plain.err; code=$?; set -e
[[ $code != 0 ]] || fail "an edited scene was restarted without --edited-scene"
grep -q -- "--edited-scene" plain.err || fail "the refusal does not name --edited-scene: $(cat plain.err)"

# 2. The springs follow their walls: bit for bit the unedited continuation.
for np in 1 2; do
  mpi $np run edited.yaml --backend cpu --restart "$checkpoint" --steps "$end" --edited-scene --out "edited$np" \
    > /dev/null
  cmp "$(last_csv reference)" "$(last_csv edited$np)" || fail "the edited restart on $np ranks differs"
done
log=edited2/run.log
grep -q "edited scene: the checkpoint was written for scene hash" "$log" || fail "no edit in the log"
grep -q "added walls\[0\].name: far" "$log" || fail "the new wall is not listed: $(cat "$log")"
grep -q "changed output.interval: 0.02 -> 0.01" "$log" || fail "the changed interval is not listed"
grep -q "walls: 6 of the scene's 7 as in the checkpoint; new or moved: 'far'" "$log" || fail "walls: $(cat "$log")"
echo "edited restart (a wall added first, output edited): bitwise equal to the unedited one on 1 and 2 ranks"

# 3. and 4.
refused moved "cuts .* m into particle" moved.yaml
grep -q "wall 'box.zmin'" moved.err || fail "moved: the wall is not named: $(cat moved.err)"
refused narrow "contact_slots" narrow.yaml

# 5. and 6.
refused stiffer "time_step: {absolute:" stiffer.yaml
before=$(cd reference && ls -l --time-style=+%s . | md5sum)
set +e; mpi 2 run scene.yaml --backend cpu --restart "$checkpoint" --steps 100 --out reference > early.log 2> early.err
code=$?; set -e
[[ $code != 0 ]] || fail "a restart with --steps before the checkpoint's step was accepted"
grep -q "ends before the checkpoint's step 20000" early.err || fail "early: $(cat early.err)"
[[ $(cd reference && ls -l --time-style=+%s . | md5sum) == "$before" ]] || fail "early: the output directory changed"
echo "early end refused: $(grep -o "error: .*" early.err | head -c 240)"
