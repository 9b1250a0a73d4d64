#!/usr/bin/env bash
# Whole-command times for examples/ins16.yaml (docs/benchmarks.md, "A 16-state INS"): `pfgen derive` of its
# `ekf` and `optimal` filters (text and JSON) and `pfgen codegen` of both, as a user meets them
# (reading and checking the model file, the derivation, printing or generating, the process's
# exit). Median wall-clock and CPU (user + system) seconds over RUNS runs after one warm-up run,
# output discarded (/usr/bin/time). On a loaded machine the CPU seconds are the steadier figure.
#
# Usage: benchmarks/bench_ins16.sh [BUILD_DIR] [RUNS]   (defaults: build, 5)
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$root/build}"
runs="${2:-5}"
pfgen="$build/generator/pfgen"
model="$root/examples/ins16.yaml"
[ -x "$pfgen" ] || { echo "bench_ins16: build $pfgen first" >&2; exit 1; }
[ -x /usr/bin/time ] || { echo "bench_ins16: needs /usr/bin/time (Debian package time)" >&2; exit 1; }
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

median() { sort -g | awk '{v[NR] = $1} END {print v[int((NR + 1) / 2)]}'; }
seconds() {  # "wall cpu" seconds of one run of the command, its output discarded
  /usr/bin/time -f '%e %U %S' -o "$work/time" "$@" >/dev/null
  awk '{print $1, $2 + $3}' "$work/time"
}
measure() {  # label, command...: prints the median and the range
  local label="$1"
  shift
  "$@" >/dev/null  # warm-up
  : >"$work/times"
  for _ in $(seq "$runs"); do seconds "$@" >>"$work/times"; done
  printf '%-38s %8.3f %14s %8.3f\n' "$label" "$(cut -d' ' -f1 "$work/times" | median)" \
    "$(cut -d' ' -f1 "$work/times" | sort -g | awk 'NR == 1 {lo = $1} {hi = $1} END {printf "%.3f..%.3f", lo, hi}')" \
    "$(cut -d' ' -f2 "$work/times" | median)"
}

printf '%-38s %8s %14s %8s\n' "command (examples/ins16.yaml)" "wall_s" "wall min..max" "cpu_s"
for filter in ekf optimal; do
  for format in text json; do
    measure "derive --filter $filter --format $format" "$pfgen" derive "$model" --filter "$filter" --format "$format"
  done
done
measure "codegen --filter ekf,optimal" "$pfgen" codegen "$model" --filter ekf,optimal -o "$work/gen"
