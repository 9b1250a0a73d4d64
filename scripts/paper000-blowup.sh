#!/usr/bin/env bash
# Paper 000's blow-up claim: does the state dx = 0.1x^2 dt + 0.1x^2 dW1 from x0 = 1.1 blow up near
# t = 9.2 (the paper sets its horizon to 9.2 and speaks of "the asymptotic time point 9.205")?
# It depends on how dW1 is read. The noise-free state blows up at 1/0.11 = 9.09. With Ito noise
# z = 10/x never reaches 0 and x never blows up; with Stratonovich noise u = -10/x obeys
# du = dt + dW1 and x blows up when u reaches 0: an inverse Gaussian time with mean 100/11 and
# shape (100/11)^2 (docs/theory.md §1.2). This script simulates both readings with the same seed
# (examples/basin2006_quadratic.yaml and examples/paper000/stratonovich.yaml), lists the blow-up
# times of the Stratonovich truth (simulate --stops-csv) beside the exact law, and prints what
# every filter does up to the blow-up (simulate's tables).
#
#   scripts/paper000-blowup.sh [RUNS [DT [T [OUTDIR]]]]   (defaults: 2000 runs, dt = 0.001, T = 30, build/paper000)
#
# PFGEN (default build/generator/pfgen) names the program; THREADS its --threads (default 2).
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
runs="${1:-2000}"
dt="${2:-0.001}"
T="${3:-30}"
out="${4:-$here/build/paper000}"
pfgen="${PFGEN:-$here/build/generator/pfgen}"
threads="${THREADS:-2}"
mkdir -p "$out"

run() {  # model tag
  "$pfgen" simulate "$1" --runs "$runs" --dt "$dt" --T "$T" --threads "$threads" --report-times 2,4,6,8,9.2 \
    --windows 0:4,4:9.2 --record-points 2 --cache-dir "$out/cache" --stops-csv "$out/$2-stops.csv" -q > "$out/$2.txt"
}
run "$here/examples/paper000/stratonovich.yaml" stratonovich
run "$here/examples/basin2006_quadratic.yaml" ito

# The truth's blow-up times of one reading, against the exact inverse Gaussian law (mean mu = 100/11,
# shape mu^2). erfc: Numerical Recipes' erfcc (relative error below 1.2e-7 everywhere), with the
# exponents of exp(2 lambda/mu) Phi(-...) added before exp so that neither overflows.
summary() {  # label stops-csv
  awk -F, -v label="$1" -v runs="$runs" -v T="$T" '
    function log_erfc(z,   t, p) {  # z >= 0
      t = 1 / (1 + 0.5 * z)
      p = -0.82215223 + t * 0.17087277
      p = 0.27886807 + t * (-1.13520398 + t * (1.48851587 + t * p))
      p = 1.00002368 + t * (0.37409196 + t * (0.09678418 + t * (-0.18628806 + t * p)))
      return log(t) - z * z - 1.26551223 + t * p
    }
    function Phi(x) { return x >= 0 ? 1 - 0.5 * exp(log_erfc(x / sqrt(2))) : 0.5 * exp(log_erfc(-x / sqrt(2))) }
    function F(t,   a, second) {  # the inverse Gaussian distribution function
      if (t <= 0) return 0
      a = sqrt(lambda / t)
      second = a * (t / mu + 1) / sqrt(2)  # Phi(-a (t/mu + 1)) = erfc(second) / 2
      return Phi(a * (t / mu - 1)) + 0.5 * exp(2 * lambda / mu + log_erfc(second))
    }
    function quantile(q,   lo, hi, mid, k) {
      lo = 0; hi = 1000
      for (k = 0; k < 200; ++k) { mid = (lo + hi) / 2; if (F(mid) < q) lo = mid; else hi = mid }
      return (lo + hi) / 2
    }
    function sample_quantile(q,   k) {  # of all runs; "> T" when it falls among the censored ones
      k = int(q * runs + 0.5); if (k < 1) k = 1
      return k <= n ? sprintf("%.3f", s[k]) : "> " T
    }
    BEGIN { mu = 100 / 11; lambda = mu * mu }
    NR > 1 && $1 == "truth" { s[++n] = $4 + 0; total += $4; if ($4 <= 9.2) by92++ }
    END {
      # insertion sort is too slow for 2000; a simple shell sort
      for (gap = int(n / 2); gap > 0; gap = int(gap / 2))
        for (i = gap + 1; i <= n; ++i) { v = s[i]; for (j = i; j > gap && s[j - gap] > v; j -= gap) s[j] = s[j - gap]; s[j] = v }
      printf "%s\t%d of %d\t%d of %d\t%s\t%s\t%s\t%s\t%s\t%s\n", label, by92, runs, n, runs,
        n ? sprintf("%.3f", total / n) : "-", sample_quantile(0.05), sample_quantile(0.25), sample_quantile(0.5),
        sample_quantile(0.75), sample_quantile(0.95)
      if (label != "stratonovich") exit
      # The exact law: P(tau <= 9.2), P(tau <= T), E[tau | tau <= T] (trapezoid on int_0^T (F(T) - F(t)) dt / F(T)).
      FT = F(T); m = 0; steps = 30000; h = T / steps
      for (k = 0; k <= steps; ++k) m += (k == 0 || k == steps ? 0.5 : 1) * (FT - F(k * h)) * h
      printf "exact (inverse Gaussian)\t%.1f of %d\t%.1f of %d\t%.3f\t%.3f\t%.3f\t%.3f\t%.3f\t%.3f\n", F(9.2) * runs, runs,
        FT * runs, runs, m / FT, quantile(0.05), quantile(0.25), quantile(0.5), quantile(0.75), quantile(0.95)
    }' "$2"
}

align() { awk -F'\t' '{ for (i = 1; i <= NF; ++i) { c[NR, i] = $i; if (length($i) > w[i]) w[i] = length($i) } n[NR] = NF }
  END { for (r = 1; r <= NR; ++r) { s = ""; for (i = 1; i <= n[r]; ++i) s = s (i < n[r] ? sprintf("%-" w[i] + 2 "s", c[r, i]) : c[r, i]); print s } }'; }

echo "Basin, Perez & Skliar 2006: the state x0 = 1.1, dx = 0.1x^2 dt + 0.1x^2 dW1: blow-up times of the truth, $runs runs, dt = $dt, T = $T, seed 1"
echo "(noise-free blow-up at 1/0.11 = 9.091; the paper's horizon 9.2, its asymptotic time 9.205)"
{
  printf "reading\tblown up by 9.2\tblown up by T\tmean (blown up)\tq05\tq25\tmedian\tq75\tq95\n"
  summary stratonovich "$out/stratonovich-stops.csv"
  summary ito "$out/ito-stops.csv"
} | align
echo
# simulate's sections by their first line, each to its blank line (the error table, the runs
# counted, the truth's quantiles).
section() { awk -v head="$1" 'index($0, head) == 1 {p = 1} p && /^$/ {exit} p' "$2"; }
echo "Stratonovich reading: the filters up to the blow-up (each figure over the runs whose truth is alive):"
section "filter   " "$out/stratonovich.txt"
echo
section "Runs counted" "$out/stratonovich.txt"
echo
section "Truth at the report times" "$out/stratonovich.txt"
echo
echo "Ito reading (the same seed): the filters and the truth, which never blows up:"
section "filter   " "$out/ito.txt"
echo
section "Truth diverged" "$out/ito.txt"
echo
section "Truth at the report times" "$out/ito.txt"
echo
shown="${out#"$here"/}"
echo "Full outputs (simulate's tables, stop CSVs): $shown/"
