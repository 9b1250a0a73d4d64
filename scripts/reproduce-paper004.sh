#!/usr/bin/env bash
# Reproduces paper 004 (Basin, Rodriguez-Gonzalez, Martinez-Zuniga), section 5, with `pfgen simulate`:
# dx = x^2 dt (no state noise), dy = x(t - 0.8) dt + dW2, x0 = 1.1, m0 = 0.1, P0 = 1, T = 4, and
# three filters: the paper's Phi* filter (eqs 17-18, pfgen's delay-optimal), the same without Phi*
# (eqs 19-20, delay-uncorrected) and the extended Kalman-Bucy filter (eqs 21-22: textbook
# delay-ekf, and the printed one as the model's user filter ekf-printed).
#
# 1. The example as printed (examples/paper004/as_printed.yaml): the noise-free truth blows up at
#    t = 1/1.1 ~ 0.909, so T = 4 is never reached; the script shows where truths and filters stop.
# 2. The 0.09 x^2 variant the printed truth follows (examples/paper004/quadratic_009.yaml), with every
#    filter derived for it: mean x, m, m1, m2 and mean |x - m| at t = 1, 2, 3, 4 beside the paper's
#    printed values, each figure the mean over runs +- its standard error. The truth is
#    deterministic, so mean m = x - mean e (e = x - m, from simulate's "Errors at the report
#    times"). Then whether the Phi* filter beats the comparators on these runs.
#
#   scripts/reproduce-paper004.sh [RUNS [DT [OUTDIR]]]     (defaults: 2000 runs, dt = 0.001, build/paper004; ~15 s)
#
# DT must divide the delay 0.8 (the filters step on a fixed grid). PFGEN (default
# build/generator/pfgen) names the program; THREADS its --threads (default 2).
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
runs="${1:-2000}"
dt="${2:-0.001}"
out="${3:-$here/build/paper004}"
pfgen="${PFGEN:-$here/build/generator/pfgen}"
threads="${THREADS:-2}"
mkdir -p "$out"

printed_filters="delay-optimal,delay-uncorrected,delay-ekf,ekf-printed"
variant_filters="delay-optimal,delay-uncorrected,delay-ekf,ekf-printed,ekf-printed-2p"
"$pfgen" simulate "$here/examples/paper004/as_printed.yaml" --filters "$printed_filters" --runs "$runs" --T 4 \
  --dt "$dt" --seed 4 --threads "$threads" --record-points 400 --cache-dir "$out/cache" -q > "$out/as_printed.txt"
"$pfgen" simulate "$here/examples/paper004/quadratic_009.yaml" --filters "$variant_filters" --runs "$runs" --T 4 \
  --dt "$dt" --seed 4 --threads "$threads" --record-points 400 --cache-dir "$out/cache" -q > "$out/quadratic_009.txt"

# Fields of one row of "Errors at the report times": filter state t runs mean_e se mean_abs se.
errors_row() {  # file filter t
  awk -v f="$2" -v t="$3" '/^Errors at the report times/ {s = 1; next} s && $1 == f && $3 == t {print; exit}' "$1"
}
# The truth's mean at a report time (the truth is deterministic: every run has the same x).
truth_mean() {  # file t
  awk -v t="$2" '/^Truth at the report times/ {s = 1; next} s && $1 == "t" && $3 == t {print $6; exit}' "$1"
}
# "mean m ± se" = x - mean e.
estimate() {  # file filter t
  local row x
  row=$(errors_row "$1" "$2" "$3"); x=$(truth_mean "$1" "$3")
  [ -z "$row" ] || [ -z "$x" ] && { echo "-"; return; }
  awk -v x="$x" '{ if ($5 == "-") print "-"; else printf "%.4g ± %s\n", x - $5, $6 }' <<< "$row"
}
abs_error() {  # file filter t
  local row
  row=$(errors_row "$1" "$2" "$3")
  [ -z "$row" ] && { echo "-"; return; }
  awk '{ if ($7 == "-") print "-"; else printf "%s ± %s\n", $7, $8 }' <<< "$row"
}
runs_counted() { local row; row=$(errors_row "$1" "$2" "$3"); awk '{print $4}' <<< "${row:-- - - -}"; }

times=(1 2 3 4)
paper_x=(1.221 1.372 1.566 1.821)
paper_m=(0.377 1.1 1.533 1.820)
paper_m1=(0.272 0.744 1.136 1.466)
paper_m2=(0.205 0.611 0.901 1.119)

line() {  # label cells... (no trailing blanks)
  { printf '%-40s' "$1"; shift
    for cell in "$@"; do printf '  %-18s' "$cell"; done; printf '\n'; } | sed 's/ *$//'
}
paper_line() {  # label values...
  local label="$1"; shift
  line "$label" "$@"
}
variant="$out/quadratic_009.txt"

echo "Basin, Rodriguez-Gonzalez & Martinez-Zuniga 2004 reproduction: $runs runs, dt = $dt (delay 0.8 = $(awk -v d="$dt" 'BEGIN {printf "%d", 0.8 / d + 0.5}') steps), seed 4; mean over runs ± standard error"
echo
echo "1. The example as printed (dx = x^2 dt from x0 = 1.1): the truth blows up at t = 1/1.1 = 0.909"
grep -m1 '^Truth diverged' "$out/as_printed.txt" | sed 's/^/   /'
awk '/^Truth at the report times/ {s = 1; print "   " $0; next} s && NF == 0 {exit} s {print "   " $0}' "$out/as_printed.txt"
echo "   Filters (RMS over [0, 4] is over runs whose truth and filter lived to t = 4; '-' when none did):"
awk '/^filter +state +RMS/ {s = 1; print "   " $0; next} s && NF == 0 {exit} s {print "   " $0}' "$out/as_printed.txt"
echo
echo "2. The 0.09 x^2 variant (the drift the printed truth follows), filters derived for it"
line "t" "${times[@]}"
cells=(); for t in "${times[@]}"; do cells+=("$(truth_mean "$variant" "$t")"); done
line "x, ours (deterministic)" "${cells[@]}"
paper_line "x, paper" "${paper_x[@]}"
for f in delay-optimal delay-uncorrected delay-ekf ekf-printed ekf-printed-2p; do
  case "$f" in
    delay-optimal) label="m  delay-optimal (eqs 17-18)" ;;
    delay-uncorrected) label="m1 delay-uncorrected (eqs 19-20)" ;;
    delay-ekf) label="m2 delay-ekf (textbook 4 m P)" ;;
    ekf-printed) label="m2 ekf-printed (eq 22 scaled: 0.18 P)" ;;
    ekf-printed-2p) label="m2 ekf-printed-2p (eq 22's 2 P)" ;;
  esac
  cells=(); for t in "${times[@]}"; do cells+=("$(estimate "$variant" "$f" "$t")"); done
  line "$label" "${cells[@]}"
  case "$f" in
    delay-optimal) paper_line "m, paper" "${paper_m[@]}" ;;
    delay-uncorrected) paper_line "m1, paper" "${paper_m1[@]}" ;;
    ekf-printed-2p) paper_line "m2, paper" "${paper_m2[@]}" ;;
  esac
done
echo
echo "Mean |x - m| (paper: |x - m| of its one printed run)"
line "t" "${times[@]}"
for f in delay-optimal delay-uncorrected delay-ekf ekf-printed ekf-printed-2p; do
  cells=(); for t in "${times[@]}"; do cells+=("$(abs_error "$variant" "$f" "$t")"); done
  line "$f" "${cells[@]}"
done
for pair in "m:paper_m" "m1:paper_m1" "m2:paper_m2"; do
  name="${pair%%:*}"; declare -n values="${pair##*:}"
  cells=(); for i in 0 1 2 3; do cells+=("$(awk -v x="${paper_x[$i]}" -v m="${values[$i]}" 'BEGIN {printf "%.3f", x - m}')"); done
  line "$name, paper" "${cells[@]}"
  unset -n values
done
echo
cells=(); for t in "${times[@]}"; do cells+=("$(runs_counted "$variant" delay-optimal "$t")"); done
echo "Runs counted at t = 1..4 (delay-optimal): ${cells[*]}; $(grep -m1 '^Truth diverged' "$variant")"

# The verdict: at each t, delay-optimal's mean |e| against each comparator's, the difference
# measured in its standard error sqrt(se1^2 + se2^2) (the same runs, so this overstates the
# uncertainty of the difference: a difference beyond 2 of them is real).
echo
echo "Does the Phi* filter (delay-optimal) beat the comparators on our runs? (mean |e| at t = 1, 2, 3, 4; 'better' or 'worse' when the difference exceeds 2 standard errors)"
verdicts=""
for f in delay-uncorrected delay-ekf ekf-printed ekf-printed-2p; do
  cells=()
  for t in "${times[@]}"; do
    a=$(errors_row "$variant" delay-optimal "$t"); b=$(errors_row "$variant" "$f" "$t")
    cells+=("$(awk -v a="$a" -v b="$b" 'BEGIN {
      split(a, x, " "); split(b, y, " ");
      if (x[7] == "-" || y[7] == "-" || x[8] == "-" || y[8] == "-") { print "-"; exit }
      d = x[7] - y[7]; s = sqrt(x[8]^2 + y[8]^2);
      w = (d < -2 * s) ? "better" : (d > 2 * s) ? "worse" : "tie";
      printf "%s (%+.3g)\n", w, d }')")
  done
  line "vs $f" "${cells[@]}"
  verdicts+=" ${cells[*]}"
done
count_word() { awk -v w="$1" '{n += gsub(w, "")} END {print n + 0}' <<< "$verdicts"; }
better=$(count_word better); worse=$(count_word worse)
echo "In all: delay-optimal better in $better, worse in $worse of 16 comparisons (4 comparators x 4 times)."
shown="${out#"$here"/}"  # relative to the repository when it is inside it
echo "Full tables: $shown/as_printed.txt, $shown/quadratic_009.txt"
