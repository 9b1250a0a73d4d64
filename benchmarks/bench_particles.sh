#!/usr/bin/env bash
# The particle reference's time per particle step, two pfgen builds side by side (an older
# commit's and this one's; docs/benchmarks.md, "The particle reference"). For each model, both
# builds run `pfgen simulate MODEL --reference particles:N --runs 1 --threads 1 --T T`, REPEATS
# times in turn (which goes first alternates), and the script prints each build's median ns per
# particle step (reference_seconds of --timing over N x steps), the median of the per-repetition
# ratios B/A, and whether the two builds' outputs (summary and CSV) are byte-identical.
#
#   benchmarks/bench_particles.sh PFGEN_A PFGEN_B [REPEATS] [N] [T]
#   (defaults: 5 repetitions, N = 1000, T = 3; models: the scalar examples Basin, Perez & Skliar
#   2006 (continuous, adaptive Euler) and Allahyani & Date's example 1 (sampled, two noises), and
#   the double well (two states, one noise))
set -euo pipefail
[ $# -ge 2 ] || { sed -n '2,13p' "$0" >&2; exit 2; }
a="$1" b="$2"
repeats="${3:-5}" particles="${4:-1000}" horizon="${5:-3}"
root="$(cd "$(dirname "$0")/.." && pwd)"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
models=("basin2006_quadratic.yaml" "paper003/example1_gamma0.yaml" "reference/double_well.yaml")
field() { sed -n "s/.*\"$2\": *\([-0-9.eE+]*\).*/\1/p" "$1"; }
median() { sort -g | awk '{v[NR]=$1} END {print v[int((NR+1)/2)]}'; }
printf '%-34s %10s %10s %8s  %s\n' "model (N = $particles, T = $horizon)" "ns_A" "ns_B" "B/A" "outputs"
for model in "${models[@]}"; do
  ns_a=() ns_b=() ratios=()
  for r in $(seq 1 "$repeats"); do
    order=(a b); [ $((r % 2)) -eq 0 ] && order=(b a)
    for which in "${order[@]}"; do
      pfgen="$a"; [ "$which" = b ] && pfgen="$b"
      "$pfgen" simulate "$root/examples/$model" --reference "particles:$particles" --runs 1 --threads 1 \
        --T "$horizon" --cache-dir "$work/cache-$which" --timing "$work/$which.json" -q \
        -o "$work/$which.csv" >"$work/$which.txt" 2>/dev/null
    done
    steps=$(field "$work/a.json" steps)
    x=$(awk -v s="$(field "$work/a.json" reference_seconds)" -v k="$steps" -v n="$particles" 'BEGIN {print s / k / n * 1e9}')
    y=$(awk -v s="$(field "$work/b.json" reference_seconds)" -v k="$steps" -v n="$particles" 'BEGIN {print s / k / n * 1e9}')
    ns_a+=("$x") ns_b+=("$y") ratios+=("$(awk -v x="$x" -v y="$y" 'BEGIN {print y / x}')")
  done
  same="identical"
  cmp -s <(sed '/^csv:/d' "$work/a.txt") <(sed '/^csv:/d' "$work/b.txt") && cmp -s "$work/a.csv" "$work/b.csv" || same="DIFFERENT"
  printf '%-34s %10.1f %10.1f %7.2fx  %s\n' "$model" "$(printf '%s\n' "${ns_a[@]}" | median)" \
    "$(printf '%s\n' "${ns_b[@]}" | median)" "$(printf '%s\n' "${ratios[@]}" | median)" "$same"
done
