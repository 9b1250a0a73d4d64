#!/usr/bin/env bash
# Scaling of `mpirun -n K pfgen simulate` from 1 to 2 ranks (issue 14; docs/guide/mpi.md
# machines (MPI)"): RUNS runs (default 2000) of paper 002's satellite example, --threads 1 per
# rank, warm plugin cache. Each repeat times the whole mpirun command with 1 rank, then with 2
# (alternating, so that a change in the machine's load hits both), and prints the medians and the
# median of the pairs' ratios; it checks that stdout and the CSV of 1 rank, 2 ranks and the plain
# single process are byte-identical.
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
awk -v runs="$runs" -v r="$repeats" '
  function median(a, n,   i, j, t) {
    for (i = 2; i <= n; ++i) for (j = i; j > 1 && a[j - 1] > a[j]; --j) { t = a[j]; a[j] = a[j - 1]; a[j - 1] = t }
    return n % 2 ? a[(n + 1) / 2] : (a[n / 2] + a[n / 2 + 1]) / 2
  }
  $1 == 1 { one[++n1] = $2 } $1 == 2 { two[++n2] = $2; ratio[n2] = one[n2] / $2 }
  END {
    printf "%d runs of the Alcorta-Garcia et al. 2011 satellite (4 filters, 1000 steps a run), --threads 1 per rank, median of %d:\n", runs, r
    printf "  mpirun -n 1: %.2f s wall\n", median(one, n1)
    printf "  mpirun -n 2: %.2f s wall   (speed-up, median of the pairs: %.2fx)\n", median(two, n2), median(ratio, n2)
    printf "  stdout and CSV of 1 rank, 2 ranks and the single process: identical\n"
  }' "$work/times"
