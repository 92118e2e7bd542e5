# Sourced by bench/validation_{silo,drum,chute}_gpu.sh: the wall budget, the
# timestamped log lines, the machine's description, a Python with matplotlib,
# the binary (built when missing, on the budget's time) and, with MPS=1, a
# private CUDA MPS daemon so that the runs' kernels can share the GPU at once
# instead of by time slices.
#   validation_setup NAME BUILD_DIR OUT   sets: binary, out, python, budget, t_start, backend, size
#   runs_budget RESERVE_S                 prints the seconds left for the runs, RESERVE_S kept for the analysis
#   validation_finish RESULTS STATUS      appends the runs' plan and ends to RESULTS, prints it, exits STATUS

source "$(dirname "${BASH_SOURCE[0]}")/mps.sh"
source "$(dirname "${BASH_SOURCE[0]}")/carried_deps.sh"

validation_log() { echo "[$(date -u +%H:%M:%S) +$(( $(date +%s) - t_start ))s] $case_name: $*" >&2; }

validation_setup() {
  case_name=$1
  t_start=$(date +%s)
  budget=${BUDGET_S:-480}
  backend=${BACKEND:-cuda}
  size=${SIZE:-full}
  root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
  mkdir -p "$2" "$3" || exit 2
  local build_dir
  build_dir=$(cd "$2" && pwd)
  out=$(cd "$3" && pwd)
  binary=$build_dir/src/grainstorm
  python=python3
  for candidate in /usr/bin/python3 python3; do
    if command -v "$candidate" >/dev/null && "$candidate" -c "import matplotlib" 2>/dev/null; then python=$candidate; break; fi
  done
  validation_log "budget ${budget} s, backend $backend, size $size, python $python"
  use_carried_deps "$root"  # also for a binary built before, which may link the carried libraries
  if [[ ! -x $binary ]]; then
    # Built here when missing (the budget pays for it): only the grainstorm target.
    validation_log "no $binary: building it (cmake, the grainstorm target only)"
    local cuda=ON
    [[ $backend == cpu ]] && cuda=OFF
    if ! { cmake -S "$root" -B "$build_dir" -DCMAKE_BUILD_TYPE=Release -DGS_ENABLE_CUDA=$cuda "${extra[@]}" &&
           cmake --build "$build_dir" -j "$(nproc)" --target grainstorm; } > "$out/build.log" 2>&1; then
      tail -30 "$out/build.log" >&2
      validation_log "BUILD FAILED (log: $out/build.log)"
      exit 2
    fi
    validation_log "built"
  fi
  {
    echo "date: $(date -u '+%Y-%m-%d %H:%M:%S UTC')"
    echo "machine: $(nvidia-smi --query-gpu=name,memory.total,driver_version --format=csv,noheader 2>/dev/null | head -1 || echo 'no nvidia-smi'), $(nproc) cores"
    echo "commit: $(git -C "$root" rev-parse --short HEAD 2>/dev/null)$(git -C "$root" status --porcelain 2>/dev/null | grep -q . && echo ' (with local changes)')"
    echo "budget: ${budget} s, backend $backend, size $size${MPS:+, MPS=$MPS}"
  } > "$out/env.txt"
  if [[ ${MPS:-0} == 1 && $backend == cuda ]]; then
    if start_mps "$out"; then
      validation_log "MPS daemon started"
    else
      validation_log "MPS daemon did not start: runs share the GPU by time slices"
    fi
  fi
}

runs_budget() {
  local left=$(( budget - ($(date +%s) - t_start) - $1 ))
  (( left < 10 )) && left=10
  echo "$left"
}

# The tool itself, under a hard limit: at the budget's end what is left (the
# tool and its runs, one process group) gets SIGTERM, and SIGKILL 15 s later.
run_tool() {
  local limit=$(( budget - ($(date +%s) - t_start) ))
  (( limit < 20 )) && limit=20
  OMP_NUM_THREADS=${OMP_NUM_THREADS:-1} MPLBACKEND=Agg timeout -k 15 "$limit" "$@"
}

# The runs' plan and ends (from the progress log) appended to RESULTS, which
# is then printed; exits with STATUS.
validation_finish() {  # RESULTS STATUS
  {
    echo
    echo "The runs' sizes and ends (from $case_name's progress log):"
    echo
    grep -E ": plan: |: (done|stopped|failed|not started)" "$out/${case_name}_progress.log" | sed 's/^/    /'
  } >> "$1"
  validation_log "results in $1"
  cat "$1"
  exit "$2"
}
