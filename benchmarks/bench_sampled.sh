#!/usr/bin/env bash
# Benchmark of the sampled filters (issue 11, deliverable 7): filter time per sample of cd-optimal,
# cd-ekf and cd-euler, each with 10 prediction sub-steps per period, on paper 003's examples
# (example 1 and 2, gamma = 1) and on the dense cubic n = 4 model with its continuous
# observation replaced by samples y_k = x(t_k) + v_k every 0.1 (Uv = I). Times come from pfgen's
# own timing (CPU thread-seconds of each filter's pass over a run, divided by the samples it
# absorbed: CPU time, so that other jobs on the cores do not inflate it); the grid step dt equals the period, so a sample costs its 10 predictions, its
# update and one grid point's statistics. The baseline is cd-euler@10 (paper 003's CDF),
# measured in the same pfgen run: ratio = time / cd-euler@10's time.
#
# Usage: benchmarks/bench_sampled.sh [BUILD_DIR] [RUNS]   (defaults: build, 400)
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$root/build}"
runs="${2:-400}"
pfgen="$build/generator/pfgen"
[ -x "$pfgen" ] || { echo "bench_sampled: build pfgen first" >&2; exit 1; }
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

# The dense cubic n = 4 model with sampled observations.
sed '/^observation:/,$d' "$root/benchmarks/models/dense_cubic_4.yaml" | sed 's/^name: dense_cubic_4/name: dense_cubic_4_sampled/' >"$work/dense.yaml"
cat >>"$work/dense.yaml" <<'EOF'
observation:
  sampled:
    period: 0.1
    C: [["1", "0", "0", "0"], ["0", "1", "0", "0"], ["0", "0", "1", "0"], ["0", "0", "0", "1"]]
    Uv: [["1", "0", "0", "0"], ["0", "1", "0", "0"], ["0", "0", "1", "0"], ["0", "0", "0", "1"]]
    substeps: 10
initial: {x0: [0.5, 0.5, 0.5, 0.5], m0: [0, 0, 0, 0], P0: [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]}
EOF

filters="cd-euler@10,cd-optimal@10,cd-ekf@10"
printf '%-46s %-14s %12s %10s\n' "model" "filter" "us/sample" "ratio"
bench() {  # label model T dt
  "$pfgen" simulate "$2" --filters "$filters" --runs "$runs" --T "$3" --dt "$4" --threads 1 --seed 1 \
    --cache-dir "$work/cache" >"$work/table.txt" 2>"$work/timing.txt"
  # The timing lines: "  NAME: ... thread-s, ... ns/step (...), X us/sample (CPU Y)".
  local base
  base=$(awk '$1 == "cd-euler@10:" {for (i = 1; i <= NF; ++i) if ($i == "us/sample") {v = $(i + 2); sub(/\)/, "", v); print v}}' "$work/timing.txt")
  for f in cd-euler@10 cd-optimal@10 cd-ekf@10; do
    awk -v f="$f:" -v label="$1" -v base="$base" '$1 == f {for (i = 1; i <= NF; ++i) if ($i == "us/sample") {
      v = $(i + 2); sub(/\)/, "", v); printf "%-46s %-14s %12.3f %10.2f\n", label, substr(f, 1, length(f) - 1), v, v / base}}' "$work/timing.txt"
  done
}
bench "Allahyani & Date example 1 (n = 1), gamma = 1" "$root/examples/allahyani_date_example1_gamma1.yaml" 200 1
bench "Allahyani & Date example 2 (n = 2), gamma = 1" "$root/examples/paper003/example2_gamma1.yaml" 200 1
bench "dense cubic n = 4, period 0.1" "$work/dense.yaml" 2 0.1
echo "($runs runs each, 1 thread; us/sample = CPU time of the filter pass / samples absorbed)"
