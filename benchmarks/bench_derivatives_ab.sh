#!/usr/bin/env bash
# Before and after: the generated derivatives() of two pfgen builds (an older commit's and this
# one's) on the same models, timed side by side in one process (docs/benchmarks.md, "Leaner
# generated code"). Each build generates each MODEL:FILTER (C++, --scalar double) into a namespace
# of its own; one program includes both headers, checks that they agree (1e-12 relative) on 64
# random states (m in [-1, 1]^n, P = M M^T / n + 0.1 I, the model's default parameters), then
# times them interleaved: REPEATS repetitions of at least 50 ms each, A and B alternating (which
# goes first alternates too). It prints the op counts (--stats), the median ns per call of each and
# the median of the per-repetition ratios B/A.
#
#   benchmarks/bench_derivatives_ab.sh PFGEN_A PFGEN_B [REPEATS] MODEL.yaml:FILTER ...
#   (REPEATS: a number, default 11; compiled with g++ -O2)
set -euo pipefail
[ $# -ge 3 ] || { sed -n '2,12p' "$0" >&2; exit 2; }
a="$1" b="$2"; shift 2
repeats=11
if [[ "$1" =~ ^[0-9]+$ ]]; then repeats="$1"; shift; fi
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
ops() { sed -n 's/.*"function": "derivatives", "naive": {[^}]*}, "cse": {[^}]*"total": \([0-9]*\)}.*/\1/p'; }
printf '%-34s %8s %8s %10s %10s %8s\n' "model:filter" "ops_A" "ops_B" "ns_A" "ns_B" "B/A"
for spec in "$@"; do
  model="${spec%%:*}" filter="${spec##*:}"
  rm -rf "$work/a" "$work/b"
  ops_a=$("$a" codegen "$model" --filter "$filter" --scalar double --namespace bench_a --stats -o "$work/a" | ops)
  ops_b=$("$b" codegen "$model" --filter "$filter" --scalar double --namespace bench_b --stats -o "$work/b" | ops)
  header_a=$(ls "$work"/a/*/"$filter".hpp) header_b=$(ls "$work"/b/*/"$filter".hpp)
  name=$(basename "$(dirname "$header_a")")
  cat >"$work/ab.cpp" <<CPP
#include "$header_a"
#include "$header_b"
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>
namespace A = bench_a::${name//-/_}::${filter//-/_};
namespace B = bench_b::${name//-/_}::${filter//-/_};
using Clock = std::chrono::steady_clock;
int main() {
  constexpr std::size_t n = A::n, size = A::state_size;
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<std::vector<double>> states(64, std::vector<double>(size));
  for (auto& s : states) {  // m, then P's upper triangle row by row
    double M[n][n], P[n][n];
    for (auto& row : M) for (double& v : row) v = u(rng);
    for (std::size_t i = 0; i < n; ++i) s[i] = u(rng);
    std::size_t k = n;
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = 0; j < n; ++j) {
        P[i][j] = i == j ? 0.1 : 0.0;
        for (std::size_t l = 0; l < n; ++l) P[i][j] += M[i][l] * M[j][l] / n;
        if (j >= i) s[k++] = P[i][j];
      }
  }
  const A::Params<double> pa{};
  const B::Params<double> pb{};
  std::vector<double> oa(size), ob(size);
  for (const auto& s : states) {
    A::derivatives(0.0, s.data(), pa, oa.data());
    B::derivatives(0.0, s.data(), pb, ob.data());
    for (std::size_t i = 0; i < size; ++i)
      if (std::abs(oa[i] - ob[i]) > 1e-12 * std::max(1.0, std::abs(oa[i]))) { std::printf("DISAGREE\\n"); return 1; }
  }
  auto time = [&](auto call) {
    volatile double sink = 0;
    std::size_t calls = 0;
    const auto start = Clock::now();
    do {
      for (const auto& s : states) { call(s.data()); sink = sink + oa[0]; }
      calls += states.size();
    } while (Clock::now() - start < std::chrono::milliseconds(50));
    return std::chrono::duration<double, std::nano>(Clock::now() - start).count() / calls;
  };
  auto call_a = [&](const double* s) { A::derivatives(0.0, s, pa, oa.data()); };
  auto call_b = [&](const double* s) { B::derivatives(0.0, s, pb, oa.data()); };
  std::vector<double> ta, tb, ratio;
  for (int r = 0; r < $repeats; ++r) {
    double x, y;
    if (r % 2) { y = time(call_b); x = time(call_a); } else { x = time(call_a); y = time(call_b); }
    ta.push_back(x); tb.push_back(y); ratio.push_back(y / x);
  }
  auto median = [](std::vector<double> v) { std::sort(v.begin(), v.end()); return v[v.size() / 2]; };
  std::printf("%10.1f %10.1f %7.2fx\\n", median(ta), median(tb), median(ratio));
}
CPP
  g++ -std=c++17 -O2 -I"$(dirname "$(dirname "$header_a")")" "$work/ab.cpp" -o "$work/ab"
  printf '%-34s %8s %8s ' "$(basename "$model" .yaml):$filter" "$ops_a" "$ops_b"
  "$work/ab"
done
