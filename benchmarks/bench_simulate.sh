#!/usr/bin/env bash
# Benchmark of `pfgen simulate` (issue 5): 1000 runs of paper 000's example with three filters
# (optimal, additive and the paper's printed comparator), T = 9, dt = 1e-4, on 2 threads.
#
# Prints, from one invocation of this script:
#   - the cold compile of the generated plugin (fresh cache directory; not part of the target),
#   - the median wall time (whole command, warm plugin cache: derivation, loading, the runs and
#     the statistics) of REPEATS runs on 2 threads, and on 1 thread as the baseline
#     measured in the same script run (ratio = thread speed-up),
#   - the ratio of filter-stepping time to truth-simulation time (thread-seconds, from pfgen's
#     own --timing report, which times each phase of each run).
#   - with a BASELINE pfgen (another build, e.g. of an older commit): the same 2-thread job run
#     with it, in turn with this build's (so both see the same machine), its median, the ratio,
#     and whether the two summary tables are identical.
# Usage: benchmarks/bench_simulate.sh [BUILD_DIR] [REPEATS] [BASELINE_PFGEN]   (defaults: build, 3)
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$root/build}"
repeats="${2:-3}"
baseline="${3:-}"
pfgen="$build/generator/pfgen"
[ -x "$pfgen" ] || { echo "bench_simulate: build pfgen first (scripts/build.sh)" >&2; exit 1; }
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
job=("$root/examples/basin2006_quadratic.yaml" --filters optimal,additive,ekf-printed --T 9 --dt 1e-4
     --seed 1 --report-times 2,4,6,8,9 --windows 0:4,4:9 --cache-dir "$work/cache" -q)

field() {  # field FILE NAME: a number from pfgen's flat --timing JSON
  sed -n "s/.*\"$2\": *\([-0-9.eE+]*\).*/\1/p" "$1"
}

"$pfgen" simulate "${job[@]}" --runs 1 --threads 1 --timing "$work/cold.json" >/dev/null
echo "cold compile of the plugin: $(field "$work/cold.json" compile_seconds) s (not counted below)"

median() { sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }
run_series() {  # run_series THREADS: prints the median wall time of $repeats runs
  local threads=$1 times=()
  for i in $(seq 1 "$repeats"); do
    "$pfgen" simulate "${job[@]}" --runs 1000 --threads "$threads" --timing "$work/t$threads-$i.json" >"$work/table-$threads-$i.txt"
    times+=("$(field "$work/t$threads-$i.json" total_seconds)")
  done
  printf '%s\n' "${times[@]}" | median
}
if [ -n "$baseline" ]; then
  # The baseline's own plugin cache (its plugin ABI may differ), compiled before timing.
  base_job=("${job[@]}")
  for k in "${!base_job[@]}"; do [ "${base_job[$k]}" = "$work/cache" ] && base_job[$k]="$work/base-cache"; done
  "$baseline" simulate "${base_job[@]}" --runs 1 --threads 1 >/dev/null
  new_times=() base_times=()
  for i in $(seq 1 "$repeats"); do
    "$baseline" simulate "${base_job[@]}" --runs 1000 --threads 2 --timing "$work/b-$i.json" >"$work/base-table-$i.txt"
    base_times+=("$(field "$work/b-$i.json" total_seconds)")
    "$pfgen" simulate "${job[@]}" --runs 1000 --threads 2 --timing "$work/n-$i.json" >"$work/new-table-$i.txt"
    new_times+=("$(field "$work/n-$i.json" total_seconds)")
  done
  base=$(printf '%s\n' "${base_times[@]}" | median)
  new=$(printf '%s\n' "${new_times[@]}" | median)
  cmp -s "$work/base-table-1.txt" "$work/new-table-1.txt" && same="identical" || same="DIFFERENT"
  awk -v b="$base" -v n="$new" -v r="$repeats" -v same="$same" -v bt="$(field "$work/b-1.json" truth_seconds)" \
      -v bf="$(field "$work/b-1.json" filter_seconds)" -v nt="$(field "$work/n-1.json" truth_seconds)" \
      -v nf="$(field "$work/n-1.json" filter_seconds)" 'BEGIN {
    printf "1000 runs x 90000 steps, 3 filters, --threads 2, in turn (median of %d):\n", r
    printf "  baseline: %.2f s wall (thread-seconds: truth %.2f, filters %.2f)\n", b, bt, bf
    printf "  this:     %.2f s wall (thread-seconds: truth %.2f, filters %.2f)\n", n, nt, nf
    printf "  speed-up: %.2fx; summary tables: %s\n", b / n, same
  }'
  exit 0
fi
wall2=$(run_series 2)
wall1=$(run_series 1)
cmp -s "$work/table-1-1.txt" "$work/table-2-1.txt" && same="identical" || same="DIFFERENT"
truth=$(field "$work/t2-1.json" truth_seconds)
filters=$(field "$work/t2-1.json" filter_seconds)
awk -v w2="$wall2" -v w1="$wall1" -v tr="$truth" -v fi="$filters" -v r="$repeats" -v same="$same" 'BEGIN {
  printf "1000 runs x 90000 steps, 3 filters (median of %d):\n", r
  printf "  --threads 2: %.2f s wall   (target < 15 s)\n", w2
  printf "  --threads 1: %.2f s wall   (baseline; speed-up %.2fx)\n", w1, w1 / w2
  printf "  thread-seconds: truth %.2f s, filters %.2f s, filters/truth = %.2f\n", tr, fi, fi / tr
  printf "  summary tables for 1 and 2 threads: %s\n", same
}'
