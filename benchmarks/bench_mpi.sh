#!/usr/bin/env bash
# Scaling of `mpirun -n K pfgen simulate` from 1 to 2 ranks (issue 14; docs/guide/mpi.md
# machines (MPI)"): RUNS runs (default 2000) of paper 002's satellite example, --threads 1 per
# rank, warm plugin cache. Each repeat times the whole mpirun command with 1 rank, then with 2
# (alternating, so that a change in the machine's load hits both), and prints the medians and the
# median of the pairs' ratios; it checks that stdout and the CSV of 1 rank, 2 ranks and the plain
# single process are byte-identical.
# Then it measures what a projection to many ranks needs, each the median of REPEATS: the fixed
# cost of a job (the whole mpirun command for 2 runs, with 1 rank and with 2: MPI's start-up, reading
# and deriving, loading the plugin, MPI's finalisation), and from `--timing` of one 1-rank and one
# 2-rank job of RUNS runs: the work per run (1 rank: wall minus aggregation, over the runs), the
# bytes per run rank 0 gathers and the seconds the 2-rank gather took, and rank 0's aggregation
# (folding the runs into statistics) per run. The projection for K ranks of one thread each over
# many machines is
#   T(K) = fixed + R w / K + R b / BW + R a,
# R runs, w work, b bytes and a aggregation per run, BW the bandwidth into rank 0 (assumed
# 1.25 GB/s, a 10 Gb/s network; the gather is one rank receiving in turn); printed for
# K = 1, 2, 8, 64 and R = RUNS and 100 RUNS.
# Needs a build configured with -DPFGEN_WITH_MPI=ON and Open MPI's mpirun.
# Usage: benchmarks/bench_mpi.sh [BUILD_DIR] [REPEATS] [RUNS]   (defaults: build, 5, 2000)
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$root/build}"
repeats="${2:-5}"
runs="${3:-2000}"
pfgen="$build/generator/pfgen"
[ -x "$pfgen" ] || { echo "bench_mpi: build pfgen first (-DPFGEN_WITH_MPI=ON)" >&2; exit 1; }
command -v mpirun >/dev/null || { echo "bench_mpi: no mpirun (apt-get install openmpi-bin)" >&2; exit 1; }
if [ "$(id -u)" -eq 0 ]; then  # Open MPI refuses root unless told
  export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
fi
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
job=(simulate "$root/examples/paper002/satellite.yaml" --threads 1 --cache-dir "$work/cache" -q)

"$pfgen" "${job[@]}" --runs 1 >/dev/null  # compile the plugin once, not timed
job+=(--runs "$runs")
"$pfgen" "${job[@]}" -o "$work/r.csv" >"$work/single.txt"

now() { date +%s.%N; }
# The median of a[1..n], for the awk programs below.
median_awk='function median(a, n,   i, j, t) {
  for (i = 2; i <= n; ++i) for (j = i; j > 1 && a[j - 1] > a[j]; --j) { t = a[j]; a[j] = a[j - 1]; a[j - 1] = t }
  return n % 2 ? a[(n + 1) / 2] : (a[n / 2] + a[n / 2 + 1]) / 2
}'

for i in $(seq 1 "$repeats"); do
  for ranks in 1 2; do
    start=$(now)
    mpirun -n "$ranks" --oversubscribe "$pfgen" "${job[@]}" -o "$work/r$ranks.csv" >"$work/out$ranks.txt"
    echo "$ranks $(now) $start" | awk '{printf "%s %.3f\n", $1, $2 - $3}' >>"$work/times"
  done
  for ranks in 1 2; do
    if cmp -s <(sed "s|$work/r$ranks.csv|CSV|" "$work/out$ranks.txt") <(sed "s|$work/r.csv|CSV|" "$work/single.txt") &&
       cmp -s "$work/r$ranks.csv" "$work/r.csv"; then :; else echo "bench_mpi: $ranks ranks: output DIFFERS" >&2; exit 1; fi
  done
done
awk -v runs="$runs" -v r="$repeats" "$median_awk"'
  $1 == 1 { one[++n1] = $2 } $1 == 2 { two[++n2] = $2; ratio[n2] = one[n2] / $2 }
  END {
    printf "%d runs of the Alcorta-Garcia et al. 2011 satellite (4 filters, 1000 steps a run), --threads 1 per rank, median of %d:\n", runs, r
    printf "  mpirun -n 1: %.2f s wall\n", median(one, n1)
    printf "  mpirun -n 2: %.2f s wall   (speed-up, median of the pairs: %.2fx)\n", median(two, n2), median(ratio, n2)
    printf "  stdout and CSV of 1 rank, 2 ranks and the single process: identical\n"
  }' "$work/times"

# The projection's inputs.
for i in $(seq 1 "$repeats"); do
  for ranks in 1 2; do
    start=$(now)
    mpirun -n "$ranks" --oversubscribe "$pfgen" "${job[@]:0:${#job[@]}-2}" --runs 2 -o "$work/tiny.csv" >/dev/null
    echo "$ranks $(now) $start" | awk '{printf "%s %.3f\n", $1, $2 - $3}' >>"$work/fixed"
  done
done
for ranks in 1 2; do
  mpirun -n "$ranks" --oversubscribe "$pfgen" "${job[@]}" -o "$work/r$ranks.csv" --timing "$work/t$ranks.json" >/dev/null
done
field() { sed -n "s|.*\"$2\": \([0-9.e+-]*\).*|\1|p" "$1"; }
awk -v runs="$runs" -v r="$repeats" \
    -v wall1="$(field "$work/t1.json" wall_seconds)" -v agg1="$(field "$work/t1.json" aggregation_seconds)" \
    -v agg2="$(field "$work/t2.json" aggregation_seconds)" -v gather2="$(field "$work/t2.json" gather_seconds)" \
    -v bytes2="$(field "$work/t2.json" gathered_bytes)" "$median_awk"'
  $1 == 1 { f1[++n1] = $2 } $1 == 2 { f2[++n2] = $2 }
  END {
    fixed1 = median(f1, n1); fixed2 = median(f2, n2)
    w = (wall1 - agg1) / runs; a = (agg1 + agg2) / 2 / runs; b = bytes2 / runs; bw = 1.25e9
    printf "projection inputs (medians of %d; per run of this job):\n", r
    printf "  fixed cost of a job: %.3f s with 1 rank, %.3f s with 2 (whole mpirun command, 2 runs)\n", fixed1, fixed2
    printf "  work per run: %.3f ms (1 rank); rank 0 aggregation per run: %.3f ms (%.3f s and %.3f s for %d runs)\n", w * 1e3, a * 1e3, agg1, agg2, runs
    printf "  gathered per run: %.1f kB; the 2-rank gather of %.1f MB took %.3f s on this machine (rank 0 waiting included)\n", b / 1e3, bytes2 / 1e6, gather2
    printf "projected T(K) = fixed + R w / K + R b / BW + R a, BW = 1.25 GB/s into rank 0:\n"
    printf "  %6s %8s %12s %10s %12s %10s\n", "K", "", "R = " runs, "speed-up", "R = " 100 * runs, "speed-up"
    split("1 2 8 64", ks, " ")
    for (i = 1; i <= 4; ++i) {
      k = ks[i]
      for (j = 1; j <= 2; ++j) {
        R = j == 1 ? runs : 100 * runs
        t[j] = fixed2 + R * w / k + (k > 1 ? R * b / bw : 0) + R * a
        base[j] = fixed2 + R * w + R * a
      }
      printf "  %6d %8s %10.2f s %9.1fx %10.1f s %9.1fx\n", k, "", t[1], base[1] / t[1], t[2], base[2] / t[2]
    }
    printf "  (the limit as K grows: (w + a) / (b / BW + a) = %.1fx)\n", (w + a) / (b / bw + a)
  }' "$work/fixed"
