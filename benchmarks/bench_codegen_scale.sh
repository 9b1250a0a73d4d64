#!/bin/sh
# Code generation at scale (docs/benchmarks.md, "Code generation at scale"): for each n, the dense
# cubic model (dense_cubic_yaml) is derived (`pfgen derive --filter optimal`, output discarded) and
# generated (`pfgen codegen --filter optimal`, C++, template scalar, parts of at most 500
# operations), each one process under /usr/bin/time -v: wall seconds and peak memory (maximum
# resident set size). The generated header is then compiled, a translation unit calling
# derivatives<double> out of line, with `g++ -std=c++17 -O2 -c` under the same measure.
#
#   benchmarks/bench_codegen_scale.sh [--pfgen build/generator/pfgen] [--baseline PFGEN]
#       [--dense-cubic-yaml build/benchmarks/dense_cubic_yaml] [--sizes "10 16 20"] [--no-compile] [--work DIR]
#
# --dense-cubic-yaml names the program that writes the model of size n (its one argument);
# benchmarks/dense_cubic_diagonal_yaml.py writes another dense cubic model, with other numbers
# and diagonal noise.
#
# --baseline PFGEN also runs another pfgen build's codegen on the same model, right after this
# one's (an older commit, for a before/after measured in one run); its wall seconds and peak memory
# are columns of their own, with `ratio` = baseline wall / this wall. Its output is compared with
# this build's, byte for byte (`same`: yes or no; "-" when the baseline failed).
#
# Output: one Markdown table row per n: derive s and MB, codegen s and MB, the filter's operations
# without CSE (the expanded equations, as `--stats` counts them: ops_naive) and with it (`ops_cse`,
# what is written), derivatives()' parts, then g++ -O2 s and MB. A failed step prints its first
# error line in place of its figures.
set -eu
pfgen=build/generator/pfgen
baseline=
yaml=build/benchmarks/dense_cubic_yaml
sizes="10 16 20"
compile=yes
work=
while [ $# -gt 0 ]; do
  case $1 in
    --pfgen) pfgen=$2; shift 2 ;;
    --baseline) baseline=$2; shift 2 ;;
    --dense-cubic-yaml) yaml=$2; shift 2 ;;
    --sizes) sizes=$2; shift 2 ;;
    --no-compile) compile=no; shift ;;
    --work) work=$2; shift 2 ;;
    *) echo "bench_codegen_scale.sh: unknown argument '$1'" >&2; exit 2 ;;
  esac
done
[ -x "$pfgen" ] || { echo "bench_codegen_scale.sh: no pfgen at '$pfgen' (build it, or pass --pfgen)" >&2; exit 1; }
[ -x "$yaml" ] || { echo "bench_codegen_scale.sh: no dense_cubic_yaml at '$yaml' (configure with -DPFGEN_BUILD_BENCHMARKS=ON)" >&2; exit 1; }
[ -z "$baseline" ] || [ -x "$baseline" ] || { echo "bench_codegen_scale.sh: no baseline pfgen at '$baseline'" >&2; exit 1; }
command -v /usr/bin/time >/dev/null || { echo "bench_codegen_scale.sh: needs /usr/bin/time (Debian package time)" >&2; exit 1; }
if [ -z "$work" ]; then work=$(mktemp -d); trap 'rm -rf "$work"' EXIT; else mkdir -p "$work"; fi

# measure LABEL COMMAND...: runs the command under /usr/bin/time -v, its stdout to $work/LABEL.out;
# sets wall (s), peak (MB) and ok (yes/no).
measure() {
  label=$1; shift
  if /usr/bin/time -v "$@" > "$work/$label.out" 2> "$work/$label.time"; then ok=yes; else ok=no; fi
  wall=$(sed -n 's|.*Elapsed (wall clock) time (h:mm:ss or m:ss): ||p' "$work/$label.time" |
         awk -F: '{ s = 0; for (i = 1; i <= NF; ++i) s = s * 60 + $i; printf "%.2f", s }')
  peak=$(sed -n 's|.*Maximum resident set size (kbytes): ||p' "$work/$label.time" | awk '{ printf "%.0f", $1 / 1024 }')
}
first_error() { grep -m1 -i "error" "$work/$1.time" | cut -c1-120; }

header="| n | derive s | derive MB | codegen s | codegen MB | ops naive | ops (CSE) | parts |"
rule="|---|---|---|---|---|---|---|---|"
if [ -n "$baseline" ]; then
  header="$header baseline codegen s | baseline MB | ratio | same |"
  rule="$rule---|---|---|---|"
fi
if [ "$compile" = yes ]; then
  header="$header g++ -O2 s | g++ MB |"
  rule="$rule---|---|"
fi
echo "$header"
echo "$rule"
for n in $sizes; do
  "$yaml" "$n" > "$work/model.yaml"
  name=$(sed -n 's|^name: *||p' "$work/model.yaml")
  mv "$work/model.yaml" "$work/$name.yaml"
  measure derive "$pfgen" derive "$work/$name.yaml" --filter optimal
  row="| $n"
  derive_cols=" $wall | $peak |"
  [ "$ok" = yes ] || derive_cols=" failed: $(first_error derive) | - |"
  rm -rf "$work/out"
  measure codegen "$pfgen" codegen "$work/$name.yaml" --filter optimal -o "$work/out" --stats
  codegen_ok=$ok
  codegen_wall=$wall
  header_file=$work/out/$name/optimal.hpp
  if [ "$ok" = yes ]; then
    naive=$(sed -n 's|^{"model": [^,]*, "filter": [^,]*, "ops_naive": \([0-9]*\), "ops_cse": \([0-9]*\),.*|\1|p' "$work/codegen.out")
    cse=$(sed -n 's|^{"model": [^,]*, "filter": [^,]*, "ops_naive": \([0-9]*\), "ops_cse": \([0-9]*\),.*|\2|p' "$work/codegen.out")
    parts=$(sed -n 's|^  // [0-9]* operations in \([0-9]*\) parts.*|\1|p' "$header_file" | head -1)
    row="$row |$derive_cols $wall | $peak | $naive | $cse | ${parts:-1} |"
  else
    row="$row |$derive_cols failed: $(first_error codegen) | $peak | - | - | - |"
  fi
  if [ -n "$baseline" ]; then
    rm -rf "$work/base"
    measure base "$baseline" codegen "$work/$name.yaml" --filter optimal -o "$work/base"
    if [ "$ok" = yes ] && [ "$codegen_ok" = yes ]; then
      ratio=$(awk -v b="$wall" -v a="$codegen_wall" 'BEGIN { printf "%.1fx", b / a }')
      if diff -r "$work/out" "$work/base" > /dev/null; then same=yes; else same=no; fi
      row="$row $wall | $peak | $ratio | $same |"
    else
      # A refusal by the baseline's budget is named with its count; another failure by its first line.
      refused=$(sed -n "s|.* has \([0-9]*\) terms in its equations; code generation holds at most.*|refused: \1 terms, over its budget|p" "$work/base.time" | head -1)
      [ -n "$refused" ] || refused="failed: $(grep -m1 "error" "$work/base.time" | cut -c1-60)"
      row="$row $refused | $peak | - | - |"
    fi
  fi
  if [ "$compile" = yes ]; then
    if [ "$codegen_ok" = yes ]; then
      tu=$work/tu_$name.cpp
      cat > "$tu" <<EOF
#include "$header_file"
void call_derivatives(const double* state, double* out) {
  pfgen_models::$name::optimal::derivatives(0.0, state, pfgen_models::$name::optimal::Params<double>{}, out);
}
EOF
      measure compile g++ -std=c++17 -O2 -c "$tu" -o "$work/tu_$name.o"
      [ "$ok" = yes ] && row="$row $wall | $peak |" || row="$row failed | $peak |"
    else
      row="$row - | - |"
    fi
  fi
  echo "$row"
done
