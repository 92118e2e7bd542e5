#!/usr/bin/env bash
# A long mixer run in pieces of at most LIMIT seconds of wall time each: the
# first piece starts the scene, every later one restarts from the newest
# checkpoint in RUN_DIR. A piece that reaches its limit is stopped by SIGTERM,
# on which grainstorm writes a checkpoint (exit code 3); the finished run
# exits 0. Lets a run longer than one machine lease go on in the next one.
#   bench/mixer_long.sh GRAINSTORM SCENE RUN_DIR LIMIT_S [BACKEND]
set -uo pipefail
gs=$(realpath "$1") scene=$2 run=$3 limit=$4 backend=${5:-cuda}
mkdir -p "$run"
run=$(realpath "$run")
last=$(ls "$run"/checkpoint_*.h5 2>/dev/null | sort | tail -1)
args=(run "$(basename "$scene")" --backend "$backend" --out "$run")
# The first piece replaces an earlier run's files (pieces.log stays).
if [[ -n $last ]]; then args+=(--restart "$last"); else args+=(--overwrite); fi
echo "=== piece from ${last:-the start}, at most $limit s" >> "$run/pieces.log"
(cd "$(dirname "$scene")" && timeout --preserve-status -s TERM "$limit" "$gs" "${args[@]}" >> "$run/pieces.log" 2>&1)
rc=$?
# Only the newest checkpoint is needed to go on.
ls "$run"/checkpoint_*.h5 2>/dev/null | sort | head -n -1 | xargs -r rm -f
echo "$(basename "$scene" .yaml): exit $rc ($( ((rc == 0)) && echo finished || echo "stopped, will restart"))"
exit $rc
