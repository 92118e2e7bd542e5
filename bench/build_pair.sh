# Sourced by the device scripts that compare this tree with a base tree
# (bench/output_device.sh, bench/device_history.sh).
# build_pair NAME BASE_SRC TARGET...: builds TARGETs of this tree into NAME
# and, where BASE_SRC is not empty, of BASE_SRC into NAME-base at the same
# time (half the cores), both with CUDA and use_carried_deps's `extra`; the
# logs go to $OUT/build_NAME.log and $OUT/build_NAME-base.log. Sets `after`
# to NAME and `before` to NAME-base, or to nothing where there is no base or
# its build failed (said, with its log's tail). Returns 1 where this tree's
# build failed (said, with its log's tail). Needs `say` and $OUT.
build_pair() {
  local name=$1 base_src=$2
  shift 2
  local cores after_pid base_pid=
  cores=$(nproc)
  build_tree() {  # SOURCE BUILD_DIR JOBS TARGET...
    local src=$1 dir=$2 jobs=$3
    shift 3
    ( cmake -S "$src" -B "$dir" -DCMAKE_BUILD_TYPE=Release -DGS_ENABLE_CUDA=ON "${extra[@]}" &&
      cmake --build "$dir" -j "$jobs" --target "$@" ) > "$OUT/build_$(basename "$dir").log" 2>&1
  }
  build_tree . "$name" "$cores" "$@" &
  after_pid=$!
  if [[ -n $base_src ]]; then
    build_tree "$base_src" "$name-base" "$((cores / 2))" "$@" &
    base_pid=$!
  fi
  after=$name before=
  if ! wait "$after_pid"; then
    say "BUILD FAILED (build_$name.log):"; tail -40 "$OUT/build_$name.log" | tee -a "$log"
    [[ -n $base_pid ]] && wait "$base_pid"
    return 1
  fi
  if [[ -n $base_pid ]]; then
    if wait "$base_pid"; then before=$name-base
    else say "BASE BUILD FAILED: this tree alone"; tail -20 "$OUT/build_$name-base.log" >> "$log"; fi
  fi
}
