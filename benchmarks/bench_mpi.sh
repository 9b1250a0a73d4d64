#!/usr/bin/env bash
# Scaling of `mpirun -n K pfgen simulate` from 1 to 2 ranks (docs/guide/mpi.md): RUNS runs
# (default 2000) of the satellite example, --threads 1 per rank, warm plugin cache. Each repeat
# times the whole mpirun command with 1 rank, then with 2 (alternating, so that a change in the
# machine's load hits both), once with Open MPI's default start-up and once with `--mca pml ob1`
# (point-to-point over shared memory and TCP, without probing for InfiniBand-class fabrics: the
# setting for one machine), and prints the medians and the median of the pairs' ratios; it checks
# that stdout and the CSV of 1 rank, 2 ranks and the plain single process are byte-identical.
# Then it measures what a projection to many ranks needs, each the median of REPEATS: the fixed
# cost of a job (the whole mpirun command for 2 runs, with 1 rank and with 2: MPI's start-up,
# reading and deriving, loading the plugin, MPI's finalisation), and from `--timing` of one 1-rank
# and one 2-rank job of RUNS runs: the work per run (1 rank: wall minus aggregation, over the
# runs), the series folding per run (shared among the ranks) and the rest of the folding (rank 0
# alone), the bytes per run of the exchange (each rank receives the other ranks' runs' values at
# its own record times: a quarter of every run's values with 2 ranks) and of the gather into
# rank 0. The projection for K ranks of one thread each over many machines is
#   T(K) = fixed + R (w + s) / K + R x (K - 1) / (K^2 BW) + R b / BW + R a,
# R runs, w work, s series folding, x exchanged and b gathered bytes, a rank 0's folding per run,
# BW the bandwidth of each rank's link (assumed 1.25 GB/s, a 10 Gb/s network); printed for
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
# The launcher's options of a setting.
launch() {
  case "$1" in
    default) mpirun -n "$2" --oversubscribe "${@:3}" ;;
    ob1) mpirun -n "$2" --oversubscribe --mca pml ob1 "${@:3}" ;;
  esac
}

for i in $(seq 1 "$repeats"); do
  for setting in default ob1; do
    for ranks in 1 2; do
      start=$(now)
      launch "$setting" "$ranks" "$pfgen" "${job[@]}" -o "$work/r$ranks.csv" >"$work/out$ranks.txt"
      echo "$setting $ranks $(now) $start" | awk '{printf "%s %s %.3f\n", $1, $2, $3 - $4}' >>"$work/times"
    done
    for ranks in 1 2; do
      if cmp -s <(sed "s|$work/r$ranks.csv|CSV|" "$work/out$ranks.txt") <(sed "s|$work/r.csv|CSV|" "$work/single.txt") &&
         cmp -s "$work/r$ranks.csv" "$work/r.csv"; then :; else echo "bench_mpi: $ranks ranks: output DIFFERS" >&2; exit 1; fi
    done
  done
done
printf '%d runs of the Alcorta-Garcia et al. 2011 satellite (4 filters, 1000 steps a run), --threads 1 per rank, median of %d:\n' "$runs" "$repeats"
for setting in default ob1; do
  awk -v setting="$setting" "$median_awk"'
    $1 != setting { next }
    $2 == 1 { one[++n1] = $3 } $2 == 2 { two[++n2] = $3; ratio[n2] = one[n2] / $3 }
    END {
      name = setting == "default" ? "Open MPI defaults" : "--mca pml ob1"
      printf "  %-18s mpirun -n 1: %.2f s   mpirun -n 2: %.2f s   speed-up, median of the pairs: %.2fx\n", name ":", median(one, n1), median(two, n2), median(ratio, n2)
    }' "$work/times"
done
echo "  stdout and CSV of 1 rank, 2 ranks and the single process: identical"

# The projection's inputs, with Open MPI's defaults (what many machines with a fast fabric use).
for i in $(seq 1 "$repeats"); do
  for setting in default ob1; do
    for ranks in 1 2; do
      start=$(now)
      launch "$setting" "$ranks" "$pfgen" "${job[@]:0:${#job[@]}-2}" --runs 2 -o "$work/tiny.csv" >/dev/null
      echo "$setting $ranks $(now) $start" | awk '{printf "%s %s %.3f\n", $1, $2, $3 - $4}' >>"$work/fixed"
    done
  done
done
for ranks in 1 2; do
  launch default "$ranks" "$pfgen" "${job[@]}" -o "$work/r$ranks.csv" --timing "$work/t$ranks.json" >/dev/null
done
field() { sed -n "s|.*\"$2\": \([0-9.e+-]*\).*|\1|p" "$1"; }
awk -v runs="$runs" -v r="$repeats" \
    -v wall1="$(field "$work/t1.json" wall_seconds)" -v agg1="$(field "$work/t1.json" aggregation_seconds)" \
    -v series1="$(field "$work/t1.json" series_seconds)" -v agg2="$(field "$work/t2.json" aggregation_seconds)" \
    -v exchange2="$(field "$work/t2.json" exchange_seconds)" -v xbytes2="$(field "$work/t2.json" exchanged_bytes)" \
    -v gather2="$(field "$work/t2.json" gather_seconds)" -v bytes2="$(field "$work/t2.json" gathered_bytes)" \
    "$median_awk"'
  $1 == "default" && $2 == 1 { f1[++n1] = $3 } $1 == "default" && $2 == 2 { f2[++n2] = $3 }
  $1 == "ob1" && $2 == 1 { o1[++m1] = $3 } $1 == "ob1" && $2 == 2 { o2[++m2] = $3 }
  END {
    fixed1 = median(f1, n1); fixed2 = median(f2, n2)
    w = (wall1 - agg1) / runs; s = series1 / runs; a = (agg1 - series1) / runs
    x = 4 * xbytes2 / runs; b = bytes2 / runs; bw = 1.25e9
    printf "projection inputs (medians of %d; per run of this job):\n", r
    printf "  fixed cost of a job: %.3f s with 1 rank, %.3f s with 2 (whole mpirun command, 2 runs; with --mca pml ob1: %.3f s and %.3f s)\n", fixed1, fixed2, median(o1, m1), median(o2, m2)
    printf "  work per run: %.3f ms (1 rank); folding per run: %.3f ms of series, shared among the ranks, and %.4f ms on rank 0 alone\n", w * 1e3, s * 1e3, a * 1e3
    printf "  exchanged per run: %.1f kB (2 ranks: %.1f MB into rank 0 in %.3f s, waiting for the other rank included)\n", x / 1e3, xbytes2 / 1e6, exchange2
    printf "  gathered per run: %.2f kB (2 ranks: %.2f MB into rank 0 in %.3f s); rank 0 folding with 2 ranks: %.3f s (1 rank: %.3f s)\n", b / 1e3, bytes2 / 1e6, gather2, agg2, agg1
    printf "projected T(K) = fixed + R (w + s) / K + R x (K - 1) / (K^2 BW) + R b / BW + R a, BW = 1.25 GB/s per rank:\n"
    printf "  %6s %8s %12s %10s %12s %10s\n", "K", "", "R = " runs, "speed-up", "R = " 100 * runs, "speed-up"
    split("1 2 8 64", ks, " ")
    for (i = 1; i <= 4; ++i) {
      k = ks[i]
      for (j = 1; j <= 2; ++j) {
        R = j == 1 ? runs : 100 * runs
        t[j] = fixed2 + R * (w + s) / k + (k > 1 ? R * x * (k - 1) / (k * k * bw) + R * b / bw : 0) + R * a
        base[j] = fixed2 + R * (w + s) + R * a
      }
      printf "  %6d %8s %10.2f s %9.1fx %10.1f s %9.1fx\n", k, "", t[1], base[1] / t[1], t[2], base[2] / t[2]
    }
    printf "  (the limit as K grows: (w + s + a) / (b / BW + a) = %.0fx)\n", (w + s + a) / (b / bw + a)
  }' "$work/fixed"
