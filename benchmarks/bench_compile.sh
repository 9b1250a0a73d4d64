#!/bin/sh
# Compile time and peak memory of the generated dense cubic optimal filter (docs/benchmarks.md,
# "Compiling large generated functions"). For each n, the model (dense_cubic_yaml) is generated with
# `pfgen codegen --filter optimal` (template scalar, the default), once as is and, with --whole,
# also with --max-function-ops 0 (one function, as before the split); a translation unit including
# the header and calling derivatives<double> out of line is compiled with -O2 -c by g++ and clang++,
# one compile at a time, under /usr/bin/time -v (wall and user seconds, "Maximum resident set size").
#
#   benchmarks/bench_compile.sh [--pfgen build/generator/pfgen] [--dense-cubic-yaml build/benchmarks/dense_cubic_yaml]
#                               [--sizes "4 8 10 12"] [--compilers "g++ clang++"] [--whole] [--work DIR]
#
# Output: one Markdown table row per (n, variant, compiler): n, ops after CSE of derivatives, parts,
# compiler, wall s, user s, peak MB. On a machine shared with other jobs, user seconds are the steadier
# figure. The one-function g++ compile of n = 12 takes minutes and several GB: --whole is opt-in.
set -eu
pfgen=build/generator/pfgen
yaml=build/benchmarks/dense_cubic_yaml
sizes="4 8 10 12"
compilers="g++ clang++"
whole=no
work=$(mktemp -d)
while [ $# -gt 0 ]; do
  case $1 in
    --pfgen) pfgen=$2; shift 2 ;;
    --dense-cubic-yaml) yaml=$2; shift 2 ;;
    --sizes) sizes=$2; shift 2 ;;
    --compilers) compilers=$2; shift 2 ;;
    --whole) whole=yes; shift ;;
    --work) work=$2; mkdir -p "$work"; shift 2 ;;
    *) echo "bench_compile.sh: unknown argument '$1'" >&2; exit 2 ;;
  esac
done
[ -x "$pfgen" ] || { echo "bench_compile.sh: no pfgen at '$pfgen' (build it, or pass --pfgen)" >&2; exit 1; }
[ -x "$yaml" ] || { echo "bench_compile.sh: no dense_cubic_yaml at '$yaml' (configure with -DPFGEN_BUILD_BENCHMARKS=ON)" >&2; exit 1; }

variants=split
[ "$whole" = yes ] && variants="whole split"
echo "| n | variant | ops (CSE) | parts | compiler | wall s | user s | peak MB |"
echo "|---|---|---|---|---|---|---|---|"
for n in $sizes; do
  name=dense_cubic_$n
  "$yaml" "$n" > "$work/$name.yaml"
  for variant in $variants; do
    out=$work/$variant
    if [ "$variant" = whole ]; then limit="--max-function-ops 0"; else limit=""; fi
    # shellcheck disable=SC2086  # $limit is empty or two words
    "$pfgen" codegen "$work/$name.yaml" --filter optimal -o "$out" $limit
    header=$out/$name/optimal.hpp
    ops=$(sed -n 's|^// Ops: .* without CSE, \([0-9]*\) (.*|\1|p' "$header" | head -1)
    parts=$(sed -n 's|^  // [0-9]* operations in \([0-9]*\) parts.*|\1|p' "$header" | head -1)
    tu=$out/tu_$name.cpp
    cat > "$tu" <<EOF
#include "$header"
void call_derivatives(const double* state, double* out) {
  pfgen_models::$name::optimal::derivatives(0.0, state, pfgen_models::$name::optimal::Params<double>{}, out);
}
EOF
    for cxx in $compilers; do
      /usr/bin/time -v "$cxx" -std=c++17 -O2 -c "$tu" -o "$out/tu_$name.o" 2> "$out/time_$cxx.txt"
      wall=$(sed -n 's|.*Elapsed (wall clock) time (h:mm:ss or m:ss): ||p' "$out/time_$cxx.txt" |
             awk -F: '{ s = 0; for (i = 1; i <= NF; ++i) s = s * 60 + $i; printf "%.1f", s }')
      user=$(sed -n 's|.*User time (seconds): ||p' "$out/time_$cxx.txt")
      peak=$(sed -n 's|.*Maximum resident set size (kbytes): ||p' "$out/time_$cxx.txt" | awk '{ printf "%.0f", $1 / 1024 }')
      echo "| $n | $variant | $ops | ${parts:-1} | $cxx | $wall | $user | $peak |"
    done
  done
done
