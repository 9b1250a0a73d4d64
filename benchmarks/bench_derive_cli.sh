#!/usr/bin/env bash
# Whole-command time of `pfgen derive` on the dense cubic benchmark model,
# beside the in-process derivation of the same model (bench_derive). A user meets the whole
# command: reading and checking the model file, the derivation, printing tens of megabytes and
# the process's exit; bench_derive times only derive_filter(). The difference is what the model
# file and the printing cost.
#
# whole_s: median wall-clock seconds of `pfgen derive MODEL --format F >/dev/null` over RUNS runs
# (after one warm-up run), as users run it (glibc's default 4 kB heap pages); whole_thp_s: the same
# with PFGEN_HUGE_PAGES=1 (the transparent-huge-page heap, generator/cli/program/huge_page_heap.hpp), the
# runs of the two interleaved, and xthp their ratio whole_thp_s / whole_s (below 1: huge pages pay
# on this machine); derive_s: bench_derive's median for the same n in this session, with 4 kB
# pages, and derive_thp_s the same with the huge-page heap; out_MB: the size of the output;
# read/derive/print: the medians of the whole_s runs' own phases (`pfgen derive --timing`): reading
# and checking the model file, deriving in that fresh process, printing.
# Targets: n = 10 in <= 0.2 s, n = 20 in <= 3 s, text and JSON.
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

printf '%4s %-6s %10s %10s %12s %6s %11s %12s %8s %12s  %s\n' "n" "format" "whole_s" "derive_s" "derive_thp_s" "|" "whole_thp_s" "xthp" "out_MB" "min..max" "read/derive/print"
for n in $sizes; do
  model="$work/dense_cubic_$n.yaml"
  "$build/benchmarks/dense_cubic_yaml" "$n" >"$model"
  derive=$(env -u GLIBC_TUNABLES "$build/benchmarks/bench_derive" --sizes "$n" --repeats "$runs" --baseline-max-n 0 | awk 'NR == 2 {print $4}')
  derive_thp=$(GLIBC_TUNABLES=glibc.malloc.hugetlb=1 "$build/benchmarks/bench_derive" --sizes "$n" --repeats "$runs" --baseline-max-n 0 | awk 'NR == 2 {print $4}')
  for format in $formats; do
    env -u PFGEN_HUGE_PAGES "$pfgen" derive "$model" --format "$format" >"$work/out"  # warm-up, and the output's size
    bytes=$(stat -c %s "$work/out")
    : >"$work/times"
    : >"$work/times_thp"
    : >"$work/phases"
    for _ in $(seq "$runs"); do
      seconds env -u PFGEN_HUGE_PAGES "$pfgen" derive "$model" --format "$format" --timing "$work/timing.json" >>"$work/times"
      cat "$work/timing.json" >>"$work/phases"
      seconds env PFGEN_HUGE_PAGES=1 "$pfgen" derive "$model" --format "$format" >>"$work/times_thp"
    done
    whole=$(median <"$work/times")
    whole_thp=$(median <"$work/times_thp")
    range=$(sort -g "$work/times" | awk 'NR == 1 {lo = $1} {hi = $1} END {printf "%.2f..%.2f", lo, hi}')
    phase() { sed -E "s/.*\"$1\": ([^,}]*).*/\1/" "$work/phases" | median; }
    phases=$(printf '%.2f/%.2f/%.2f' "$(phase read_seconds)" "$(phase derive_seconds)" "$(phase print_seconds)")
    printf '%4s %-6s %10.3f %10.3f %12.3f %6s %11.3f %11.2fx %8.1f %12s  %s\n' "$n" "$format" "$whole" "$derive" "$derive_thp" "|" \
      "$whole_thp" "$(awk -v a="$whole_thp" -v b="$whole" 'BEGIN {print a / b}')" "$(awk -v b="$bytes" 'BEGIN {print b / 1e6}')" "$range" "$phases"
  done
done
