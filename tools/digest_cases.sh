#!/usr/bin/env bash
# Digests of the final states of the shipped scenes, on 1..R CPU ranks: one
# line per scene and rank count, "scene ranks steps digest". Two builds that
# print the same lines compute the same bits (a refactor must not change them).
#
#   [DIGEST_BUILD=DIR] [BACKEND=cpu] [SCENES=regex] [DECOMPOSITION=slabs|metis] tools/digest_cases.sh BUILD_DIR [MAX_RANKS=4] [STEPS=200] > digests.txt
#
# BACKEND=cuda runs every rank on the one GPU (ranks sharing a GPU move their
# messages through host buffers); SCENES keeps the scenes whose paths match
# the extended regular expression. DECOMPOSITION=slabs|metis sets every
# scene's decomposition method (default: the scene's own).
# DIGEST_BUILD: the build whose `grainstorm info` digests the checkpoints
# (default BUILD_DIR): the runs of one build digested as another computes
# digests, when the digest itself changed between them.
# Each scene runs from a copy beside it (relative paths keep working) whose
# output section asks for one checkpoint at the end; `grainstorm info` prints
# its state digest (src/io/state_digest.hpp). Mixer case d (7.7e6 spheres) is
# left out: it does not fit a CI machine's time.
set -euo pipefail
build=$(cd "$1" && pwd)
digest_build=$(cd "${DIGEST_BUILD:-$1}" && pwd)
max_ranks=${2:-4}
steps=${3:-200}
root=$(cd "$(dirname "$0")/.." && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"; rm -f "$root"/cases/*/.digest_*.yaml "$root"/cases/*/*/.digest_*.yaml "$root"/tests/cli/.digest_*.yaml' EXIT
python=python3  # one that reads YAML: the system's, where another comes first on PATH without it
for p in /usr/bin/python3 python3; do
  if "$p" -c "import yaml" 2> /dev/null; then python=$p && break; fi
done

scenes=$(cd "$root" && ls cases/demo/*.yaml cases/mixer/*.yaml cases/validation/*/*.yaml tests/cli/settle_small.yaml |
         grep -v 'case_d\.yaml' | grep -E "${SCENES:-.}")
for scene in $scenes; do
  copy="$root/$(dirname "$scene")/.digest_$(basename "$scene")"
  for ranks in $(seq 1 "$max_ranks"); do
    out="$work/$(echo "$scene" | tr / _)_$ranks"
    "$python" - "$root/$scene" "$copy" "$out" "${DECOMPOSITION:-}" <<'PY'
import sys, yaml
scene, copy, out, method = sys.argv[1:]
s = yaml.safe_load(open(scene))
s["output"] = {"interval": 1e9, "directory": out, "format": "csv", "checkpoint_interval": 1e9}
if method:
    s.setdefault("decomposition", {})["method"] = method
analysis = s.get("analysis", {}).get("mixing")
if analysis is not None:
    analysis["output"] = "mixing.csv"
yaml.safe_dump(s, open(copy, "w"))
PY
    mpiexec --oversubscribe --allow-run-as-root -n "$ranks" "$build/src/grainstorm" run "$copy" --backend "${BACKEND:-cpu}" \
      --steps "$steps" > "$work/log" 2>&1 || { echo "$scene $ranks: run failed" >&2; tail -5 "$work/log" >&2; exit 1; }
    checkpoint=$(ls "$out"/checkpoint_*.h5 | tail -1)
    digest=$("$digest_build/src/grainstorm" info "$checkpoint" | sed -n 's/^state digest: *\(0x[0-9a-f]*\).*/\1/p')
    echo "$scene $ranks $steps $digest"
  done
done
