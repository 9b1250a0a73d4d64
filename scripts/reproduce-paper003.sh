#!/usr/bin/env bash
# Reproduces paper 003 (Allahyani and Date), Tables I-III, with `pfgen simulate`: examples 1
# (gamma = 0, 0.5, 1) and 2 (gamma = 0, 0.5, 1), the paper's CDF (cd-euler with 5 or 10
# sub-steps) and DDF (cd-euler with 1 sub-step) beside pfgen's cd-optimal and cd-ekf, all
# stepped on the same truths and samples. Prints the tables laid out like the paper's, in both
# readings of its "true values of the measurement" (noise-free C x(t_k), and the sample y_k),
# each figure the mean over runs +- its standard error, and the differences DDF - CDF and
# cd-optimal - CDF paired run by run (same truths, same samples) with their standard errors;
# then the state-error RMS.
#
#   scripts/reproduce-paper003.sh [RUNS [DT [OUTDIR]]]     (defaults: 100 runs, dt = 0.01, build/paper003)
#
# PFGEN (default build/generator/pfgen) names the program; THREADS its --threads (default 2).
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
runs="${1:-100}"
dt="${2:-0.01}"
out="${3:-$here/build/paper003}"
pfgen="${PFGEN:-$here/build/generator/pfgen}"
threads="${THREADS:-2}"
samples=200
mkdir -p "$out"

ex1=("$here/examples/paper003/example1_gamma0.yaml" "$here/examples/allahyani_date_example1_gamma05.yaml"
     "$here/examples/allahyani_date_example1_gamma1.yaml")
ex2=("$here/examples/paper003/example2_gamma0.yaml" "$here/examples/paper003/example2_gamma05.yaml"
     "$here/examples/paper003/example2_gamma1.yaml")
# The CDF of the table first: the table's paired differences are taken against the first filter.
filters1a="cd-euler@5,cd-euler@1,cd-euler@10,cd-optimal,cd-ekf"
filters1b="cd-euler@10,cd-euler@1,cd-euler@5,cd-optimal,cd-ekf"
filters2="cd-euler@10,cd-euler@1,cd-optimal,cd-ekf"

simulate() {  # model filters file
  "$pfgen" simulate "$1" --filters "$2" --runs "$runs" --T "$samples" --dt "$dt" --seed 3 \
    --threads "$threads" --record-points 200 --cache-dir "$out/cache" -q > "$3"
}
for g in 0 1 2; do
  simulate "${ex1[$g]}" "$filters1a" "$out/example1_$g.txt"    # Table I (the same truths and samples as Table II)
  simulate "${ex1[$g]}" "$filters1b" "$out/example1b_$g.txt"  # Table II
  simulate "${ex2[$g]}" "$filters2" "$out/example2_$g.txt"
done

# "mean ± se" of one metric (field: 5 AvRMSE clean, 8 AvMRAE clean, 11 AvRMSE noisy, 14 AvMRAE
# noisy) of one filter from the table's sampled section.
metric() {
  awk -v f="$2" -v k="$3" '/^At the samples/ {s = 1; next} s && $1 == f && $2 == "y1" {print $k " ± " $(k + 2); exit}' "$1"
}
# "difference ± se" of one paired metric (field: 4 dAvRMSE clean, 7 dAvMRAE clean, 10 dAvRMSE
# noisy, 13 dAvMRAE noisy) of one filter against the job's first filter.
paired() {
  awk -v f="$2" -v k="$3" '/^Paired against/ {s = 1; next} s && $1 == f && $2 == "y1" {print $k " ± " $(k + 2); exit}' "$1"
}
# The state-error RMS over [0, T] of one filter and state.
state_rms() {
  awk -v f="$2" -v x="$3" '$1 == f && $2 == x && $3 ~ /^[0-9.e+-]+$/ {print $3; exit}' "$1"
}
# Runs counted for the sampled metrics, and truths stopped.
counted() { awk -v f="$2" '/^At the samples/ {s = 1; next} s && $1 == f && $2 == "y1" {print $3; exit}' "$1"; }
truth_line() { grep -m1 '^Truth diverged' "$1" | sed 's/^Truth diverged: //'; }

row() {  # label job filter field [paired]
  printf '%-30s' "$1"
  for g in 0 1 2; do
    if [ -n "${5:-}" ]; then v=$(paired "$out/$2_$g.txt" "$3" "$4"); else v=$(metric "$out/$2_$g.txt" "$3" "$4"); fi
    printf '  %-20s' "${v:--}"
  done
  printf '\n'
}
table() {  # title job field-rmse field-mrae cdf-filter
  local title="$1" job="$2" fr="$3" fm="$4" cdf="$5"
  echo "$title"
  printf '%-30s  %-20s  %-20s  %-20s\n' "" "gamma = 0" "gamma = 0.5" "gamma = 1"
  for what in AvRMSE AvMRAE; do
    local field="$fr"
    [ "$what" = AvMRAE ] && field="$fm"
    row "$what CDF ($cdf)" "$job" "$cdf" "$field"
    row "$what DDF (cd-euler@1)" "$job" cd-euler@1 "$field"
    row "$what cd-optimal" "$job" cd-optimal "$field"
    row "$what cd-ekf" "$job" cd-ekf "$field"
    # Paired, run by run, against the CDF (the job's first filter): fields 4, 7, 10, 13.
    local pf=$(( field == 5 ? 4 : field == 8 ? 7 : field == 11 ? 10 : 13 ))
    row "  $what DDF - CDF (paired)" "$job" cd-euler@1 "$pf" paired
    row "  $what cd-optimal - CDF" "$job" cd-optimal "$pf" paired
  done
  echo
}

echo "Allahyani & Date reproduction: $runs runs of $samples samples, truth dt = $dt, seed 3 (mean ± standard error over runs)"
echo
for reading in clean noisy; do
  if [ "$reading" = clean ]; then fr=5; fm=8; label="Y = C x(t_k), noise-free"; else fr=11; fm=14; label="Y = y_k, the noisy sample"; fi
  table "Table I (Delta = 1/5), $label" example1 "$fr" "$fm" cd-euler@5
  table "Table II (Delta = 1/10), $label" example1b "$fr" "$fm" cd-euler@10
  table "Table III (example 2, Delta = 1/10), $label" example2 "$fr" "$fm" cd-euler@10
done

echo "State-error RMS over [0, $samples] (all grid points; runs whose truth and filter completed):"
printf '%-14s %-6s' "filter" "state"
for e in 1 2; do for g in 0 0.5 1; do printf '  %-12s' "ex$e g=$g"; done; done
printf '\n'
for f in cd-euler@5 cd-euler@10 cd-euler@1 cd-optimal cd-ekf; do
  for x in x x1 x2; do
    line=$(printf '%-14s %-6s' "$f" "$x"); any=0
    for e in 1 2; do for g in 0 1 2; do
      v=$(state_rms "$out/example${e}_$g.txt" "$f" "$x"); [ -n "$v" ] && any=1
      line+=$(printf '  %-12s' "${v:--}")
    done; done
    [ "$any" = 1 ] && echo "$line"
  done
done
echo
echo "Runs counted / truths stopped:"
for e in 1 2; do for g in 0 1 2; do
  echo "  example $e, gamma index $g: $(counted "$out/example${e}_$g.txt" cd-optimal) runs counted; truth diverged: $(truth_line "$out/example${e}_$g.txt")"
done; done
echo "Full tables: $out/example{1,1b,2}_{0,1,2}.txt (1: Table I's job, 1b: Table II's; gamma index 0, 1, 2 = gamma 0, 0.5, 1)"
