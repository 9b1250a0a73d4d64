#!/usr/bin/env bash
# Whole-command time of `pfgen derive` on the dense cubic benchmark model,
# beside the in-process derivation of the same model (bench_derive). A user meets the whole
# command: reading and checking the model file, the derivation, printing tens of megabytes and
# the process's exit; bench_derive times only derive_filter(). The difference is what the model
# file and the printing cost.
#
# whole_s: median wall-clock seconds of `pfgen derive MODEL --format F >/dev/null` over RUNS runs
# (after one warm-up run); derive_s: bench_derive's median for the same n in this session;
# out_MB: the size of the output. Targets: n = 10 in <= 0.2 s, n = 20 in <= 3 s, text and JSON.
#
# Usage: benchmarks/bench_derive_cli.sh [BUILD_DIR] [SIZES] [RUNS] [FORMATS]
#        (defaults: build, "10 20", 5, "text json latex"); needs -DPFGEN_BUILD_BENCHMARKS=ON.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$root/build}"
sizes="${2:-10 20}"
runs="${3:-5}"
formats="${4:-text json latex}"
pfgen="$build/generator/pfgen"
for tool in "$pfgen" "$build/benchmarks/dense_cubic_yaml" "$build/benchmarks/bench_derive"; do
  [ -x "$tool" ] || { echo "bench_derive_cli: build $tool first" >&2; exit 1; }
done
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

median() { sort -g | awk '{v[NR] = $1} END {print v[int((NR + 1) / 2)]}'; }
seconds() {  # wall-clock seconds of one run of the command, its output discarded
  local start end
  start=$(date +%s.%N)
  "$@" >/dev/null
  end=$(date +%s.%N)
  awk -v s="$start" -v e="$end" 'BEGIN {print e - s}'
}

printf '%4s %-6s %10s %10s %8s %12s\n' "n" "format" "whole_s" "derive_s" "out_MB" "min..max"
for n in $sizes; do
  model="$work/dense_cubic_$n.yaml"
  "$build/benchmarks/dense_cubic_yaml" "$n" >"$model"
  derive=$("$build/benchmarks/bench_derive" --sizes "$n" --repeats "$runs" --baseline-max-n 0 | awk 'NR == 2 {print $4}')
  for format in $formats; do
    "$pfgen" derive "$model" --format "$format" >"$work/out"  # warm-up, and the output's size
    bytes=$(stat -c %s "$work/out")
    : >"$work/times"
    for _ in $(seq "$runs"); do seconds "$pfgen" derive "$model" --format "$format" >>"$work/times"; done
    whole=$(median <"$work/times")
    range=$(sort -g "$work/times" | awk 'NR == 1 {lo = $1} {hi = $1} END {printf "%.2f..%.2f", lo, hi}')
    printf '%4s %-6s %10.3f %10.3f %8.1f %12s\n' "$n" "$format" "$whole" "$derive" "$(awk -v b="$bytes" 'BEGIN {print b / 1e6}')" "$range"
  done
done
