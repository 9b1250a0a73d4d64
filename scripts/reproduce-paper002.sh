#!/usr/bin/env bash
# Reproduces paper 002 (Alcorta-Garcia, Anguiano Rostro, Torres Torres 2011), Tables 1-5, with
# `pfgen simulate`: the exponential criterion J = eps log E[exp(eps^-1 int_0^T |x - m|^2 dt)] of the
# risk-sensitive filter (pfgen's `risk-sensitive`, and the printed eq 21 or 25 as the model's
# `rs-printed`), the polynomial filter (pfgen's `optimal`, and the printed eq 22 or 26 as
# `poly-printed`) and, for the reactor, the extended Kalman-Bucy filter (pfgen's `ekf`, and the
# printed eq 23 as `ekf-printed`), for every eps of each table.
#
# The paper starts each filter from its own m(0), P(0). `simulate` takes them from the model's
# `initial:`, so the script writes one copy of examples/paper002/{reactor,satellite}.yaml per filter
# (and, for the risk-sensitive filter, per eps: P(0) = -eps Q(0)^-1) into OUTDIR and runs each with
# the same seed: run r's truth draws only from RandomStream(seed, r, .), and x(0), eps, gamma and dt
# are the same in every copy, so all filters of a row see the same truths.
#
# Invalid printed initial matrices (docs/paper-discrepancies.md, "Paper 002", rows 7-9):
#   reactor case 1's Q(0) = (6, 1e-4, -7) is not negative definite: a lost sign, Q11 = -6 is used;
#   reactor case 2's EKF P(0) = (2, 5, 10) and satellite case 1's polynomial P(0) = (10, 20, 5) are
#   indefinite: the nearest positive semi-definite matrix is used (the negative eigenvalue clipped to
#   0, plus 1e-9 of the largest on the diagonal so that the written decimals stay semi-definite).
# Part 2 runs the three invalid matrices as printed through the printed filters (21), (23) and (26),
# in the variable P - D with D = P(0)printed - P(0)repaired, so that P itself starts where the paper
# says (for (21), P(0) = -eps Q(0)^-1 of the printed and of the repaired Q(0)).
#
# gamma is never given: each table is run in two readings, gamma = 1 (intensity s = eps/2, growing
# with eps) and gamma^2 = eps/2 (unit intensity s = 1 for every eps).
#
#   scripts/reproduce-paper002.sh [RUNS [DT [OUTDIR]]]   (defaults: 1000 runs, dt = 0.001, build/paper002; ~10 min)
#
# PFGEN (default build/generator/pfgen) names the program; THREADS its --threads (default 2);
# CASES the tables to run (default "reactor1 reactor2 reactor3 satellite1 satellite2"); READINGS
# (default "gamma1 unit"); EPS_COUNT the number of each table's eps to run (default all); PART2=0
# skips part 2.
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
runs="${1:-1000}"
dt="${2:-0.001}"
out="${3:-$here/build/paper002}"
pfgen="${PFGEN:-$here/build/generator/pfgen}"
threads="${THREADS:-2}"
cases="${CASES:-reactor1 reactor2 reactor3 satellite1 satellite2}"
readings="${READINGS:-gamma1 unit}"
eps_count="${EPS_COUNT:-99}"
part2="${PART2:-1}"
seed=2
mkdir -p "$out"

# The paper's data, case by case (section 4). Matrices are (11, 12, 22). paper_* are the printed
# J values, in the order of eps; a "@t" suffix is the time printed in parentheses beside it.
case_data() {
  rs_m0="1, 5"; poly_m0="1, 5"; ekf_m0="1, 5"; T=2; model=reactor; ekf=1
  case "$1" in
    reactor1)
      table=1; x0="20, 10"; eps_list="0.1 1 10 100 1000"
      rs_q0_printed="6 0.0001 -7"; rs_q0="-6 0.0001 -7"
      poly_p0_printed="100 -1 1e7"; ekf_p0_printed="5 3 5"
      paper_rs="53.4293 53.5165 53.7994 54.7621 58.5054"
      paper_pol="69.2292@0.17 145.7323 157.2172 858.7622 58230"
      paper_kb="69.0816@0.14 277.3136 235.5110 189.6937 185.7343" ;;
    reactor2)
      table=2; x0="50, 1"; eps_list="1 10 100 1000 10000"
      rs_q0_printed="-7 0.0001 -7.5"; rs_q0="$rs_q0_printed"
      poly_p0_printed="85 -10 2e7"; ekf_p0_printed="2 5 10"
      paper_rs="505.8493 513.3591 537.8120 622.1946 960.423"
      paper_pol="705.1152@1.64 712.2522 1430.4728 59067 5597700"
      paper_kb="686.3813@0.28 527.0787 587.0328 641.1202 673.6555" ;;
    reactor3)
      table=3; x0="0.05, 50"; eps_list="0.1 1 10 100 1000 10000"
      rs_q0_printed="-6 0.0001 -7"; rs_q0="$rs_q0_printed"
      poly_p0_printed="100 -5 1e7"; ekf_p0_printed="1.85 3 5"
      paper_rs="42.0377 41.9340 41.6143 40.6851 38.5611 36.1603"
      paper_pol="55.6339 56.1153 70.7942 763.7829 57957 55918000"
      paper_kb="70.3916@0.36 144.2845 317.9369 678.2942 812.9141 859.8006" ;;
    satellite1|satellite2)
      model=satellite; T=1; ekf=0; rs_m0="0.92, 0.5"; poly_m0="0.92, 0.5"; ekf_p0_printed=""
      eps_list="0.01 0.1 1 10 100"; paper_kb=""
      if [ "$1" = satellite1 ]; then
        table=4; x0="0.09, 0.65"; rs_q0_printed="-400 100 -850"; poly_p0_printed="10 20 5"
        paper_rs="0.3239 0.3232 0.3198 0.3063 0.2800"; paper_pol="2.0321 1.1319 0.6655 0.3319 26.8974"
      else
        table=5; x0="0.115, 0.073"; rs_q0_printed="-4500 100 -8500"; poly_p0_printed="1500 -879.21 1000"
        paper_rs="0.3842 0.3835 0.3691 0.2841 0.1454"; paper_pol="0.5895 0.4287 0.4013 0.3054 0.2454"
      fi
      rs_q0="$rs_q0_printed" ;;
    *) echo "reproduce-paper002: unknown case '$1'" >&2; exit 2 ;;
  esac
  poly_p0=$(repaired "$poly_p0_printed")
  ekf_p0=""; [ "$ekf" = 1 ] && ekf_p0=$(repaired "$ekf_p0_printed")
  return 0
}

# A symmetric 2x2 (a b c) as printed when positive semi-definite, else the nearest positive
# semi-definite matrix (Frobenius norm): the negative eigenvalue clipped to 0, plus 1e-9 of the
# largest eigenvalue on the diagonal.
repaired() {
  awk -v m="$1" 'BEGIN {
    split(m, p, " "); a = p[1]; b = p[2]; c = p[3]
    if (a >= 0 && c >= 0 && a * c - b * b >= 0) { print m; exit }
    h = (a + c) / 2; r = sqrt(((a - c) / 2)^2 + b * b); l = h + r
    # eigenvector of l: (b, l - a), or (l - c, b); take the longer for accuracy
    x = b; y = l - a; if (x * x + y * y < 1e-30) { x = l - c; y = b }
    n = sqrt(x * x + y * y); x /= n; y /= n
    f = 1e-9 * l
    printf "%.10g %.10g %.10g\n", l * x * x + f, l * x * y, l * y * y + f }'
}

# P(0) = -eps Q(0)^-1 of the risk-sensitive filter (Z = eps log p = (x - C)^T Q (x - C)/2 + ...).
rs_p0() {  # eps "q11 q12 q22"
  awk -v e="$1" -v m="$2" 'BEGIN {
    split(m, q, " "); d = q[1] * q[3] - q[2] * q[2]
    printf "%.10g %.10g %.10g\n", -e * q[3] / d, e * q[2] / d, -e * q[1] / d }'
}

# A copy of the example with its own initial line (x0, m0 and P0 "a b c").
variant() {  # target x0 m0 P0
  local a b c; read -r a b c <<< "$4"
  awk -v line="initial: {x0: [$2], m0: [$3], P0: [[$a, $b], [$b, $c]]}" \
    '/^initial:/ {print line; next} {print}' "$here/examples/paper002/$model.yaml" > "$1"
}

# One simulate job: J of FILTERS over the runs, as the criterion CSV (J's eps is the model's risk.epsilon, eps, set by --set).
run_job() {  # model-file filters eps gamma csv
  "$pfgen" simulate "$1" --filters "$2" --set "eps=$3" --set "gamma=$4" --runs "$runs" --T "$T" --dt "$dt" \
    --seed "$seed" --threads "$threads" --record-points 2 --cache-dir "$out/cache" \
    --criterion-csv "$5" -q > "${5%.csv}.txt"
}

# "J ± se" of a filter from a criterion CSV, with the number of runs that stopped before T and the
# first stop time ("J ± se [k stop @t]", J then over the completed runs only); "!" when fewer than
# 20 runs carry J (effective sample size).
cell() {  # csv filter
  awk -F, -v f="$2" 'NR > 1 && $1 == f {
    if ($10 + 0 == 0) { J = $5; se = $6; ess = $7 } else { J = $12; se = $13; ess = $14 }
    s = (J == "" ? "-" : sprintf("%.4g ± " (se + 0 < 10 ? "%.2g" : "%.0f"), J, se))
    if (ess != "" && ess + 0 < 20) s = s "!"
    if ($10 + 0 > 0) s = s sprintf(" [%d stop @%.3g]", $10, $11)
    print s; exit }' "$1"
}
# J (or J over the completed runs) and its se, as two numbers, for the verdicts.
j_se() {  # csv filter
  awk -F, -v f="$2" 'NR > 1 && $1 == f {
    if ($10 + 0 == 0) print $5, $6, $10; else print $12, $13, $10; exit }' "$1"
}
stops() {  # csv filter: runs stopped before T
  awk -F, -v f="$2" 'NR > 1 && $1 == f {print $10; exit}' "$1"
}

row() {  # cells... : one tab-separated row, added to $rows
  local IFS=$'\t'; rows+="$*"$'\n'
}
align() {  # prints $rows in columns two blanks apart (no trailing blanks)
  printf '%s' "$rows" | awk -F'\t' '{ for (i = 1; i <= NF; ++i) { c[NR, i] = $i; if (length($i) > w[i]) w[i] = length($i) }
      n[NR] = NF }
    END { for (r = 1; r <= NR; ++r) { s = ""
            for (i = 1; i <= n[r]; ++i) s = s (i < n[r] ? sprintf("%-" w[i] + 2 "s", c[r, i]) : c[r, i])
            print s } }'
  rows=""
}
nth() { awk -v i="$1" '{print $i}' <<< "$2"; }

gamma_of() {  # reading eps
  if [ "$1" = gamma1 ]; then echo 1; else awk -v e="$2" 'BEGIN {printf "%.17g\n", sqrt(e / 2)}'; fi
}

# simulate's "Truth at the report times" section: the same in every job of a row when the truths are.
truth_table() { awk '/^Truth at the report times/ {s = 1; next} s && /^t = / {print; next} s {exit}' "$1"; }
same_truths=0
verdict_rs=0; verdict_total=0
echo "Alcorta-Garcia et al. 2011 reproduction: $runs runs per job, dt = $dt, seed $seed; J ± standard error (delta method)"
echo "(J over the runs that reached T when some stopped: [k stop @t] = k runs stopped, the first at t;"
echo " '!' = fewer than 20 runs carry J (effective sample size); '-' = no run reached T)."
for name in $cases; do
  case_data "$name"
  dir="$out/$name"; mkdir -p "$dir"
  variant "$dir/poly.yaml" "$x0" "$poly_m0" "$poly_p0"
  [ "$ekf" = 1 ] && variant "$dir/ekf.yaml" "$x0" "$ekf_m0" "$ekf_p0"
  for reading in $readings; do
    echo
    if [ "$reading" = gamma1 ]; then what="gamma = 1: noise intensity s = eps/2"; else what="gamma^2 = eps/2: unit noise intensity s = 1"; fi
    echo "Table $table ($name: x(0) = ($x0), T = $T), $what"
    echo "  initial: R-S C(0) = ($rs_m0), Q(0) = ($rs_q0) [printed ($rs_q0_printed)]; Pol m(0) = ($poly_m0), P(0) = ($poly_p0) [printed ($poly_p0_printed)]$([ "$ekf" = 1 ] && echo "; K-B m(0) = ($ekf_m0), P(0) = ($ekf_p0) [printed ($ekf_p0_printed)]")"
    rows=""
    if [ "$ekf" = 1 ]; then
      row "eps" "J_R-S paper" "J_R-S risk-sensitive" "J_R-S eq 21 printed" "J_Pol paper" "J_Pol optimal" \
        "J_Pol eq 22 printed" "J_K-B paper" "J_K-B ekf" "J_K-B eq 23 printed" "truth stopped"
    else
      row "eps" "J_R-S paper" "J_R-S risk-sensitive" "J_R-S eq 25 printed" "J_Pol paper" "J_Pol optimal" \
        "J_Pol eq 26 printed" "truth stopped"
    fi
    i=0
    for eps in $eps_list; do
      i=$((i + 1)); [ "$i" -gt "$eps_count" ] && break
      gamma=$(gamma_of "$reading" "$eps")
      tag="$reading-eps$eps"
      variant "$dir/rs-$eps.yaml" "$x0" "$rs_m0" "$(rs_p0 "$eps" "$rs_q0")"
      run_job "$dir/rs-$eps.yaml" risk-sensitive,rs-printed "$eps" "$gamma" "$dir/rs-$tag.csv"
      run_job "$dir/poly.yaml" optimal,poly-printed "$eps" "$gamma" "$dir/poly-$tag.csv"
      truth=$(awk '/^Truth diverged: no run/ {print "0"; exit} /^Truth diverged/ {print $3; exit}' "$dir/poly-$tag.txt")
      rs=$(cell "$dir/rs-$tag.csv" risk-sensitive)
      rs_printed=$(cell "$dir/rs-$tag.csv" rs-printed)
      jobs=("$dir/rs-$tag.txt" "$dir/poly-$tag.txt")
      if [ "$ekf" = 1 ]; then
        run_job "$dir/ekf.yaml" ekf,ekf-printed "$eps" "$gamma" "$dir/ekf-$tag.csv"
        jobs+=("$dir/ekf-$tag.txt")
        row "$eps" "$(nth "$i" "$paper_rs")" "$rs" "$rs_printed" "$(nth "$i" "$paper_pol")" "$(cell "$dir/poly-$tag.csv" optimal)" \
          "$(cell "$dir/poly-$tag.csv" poly-printed)" "$(nth "$i" "$paper_kb")" "$(cell "$dir/ekf-$tag.csv" ekf)" \
          "$(cell "$dir/ekf-$tag.csv" ekf-printed)" "$truth"
      else
        row "$eps" "$(nth "$i" "$paper_rs")" "$rs" "$rs_printed" "$(nth "$i" "$paper_pol")" "$(cell "$dir/poly-$tag.csv" optimal)" \
          "$(cell "$dir/poly-$tag.csv" poly-printed)" "$truth"
      fi
      for job in "${jobs[@]:1}"; do
        if [ "$(truth_table "$job")" != "$(truth_table "${jobs[0]}")" ]; then
          echo "reproduce-paper002: the truths of $job and ${jobs[0]} differ" >&2; exit 1
        fi
      done
      same_truths=$((same_truths + 1))
      # The paper's claim: J_R-S is the smallest. Against pfgen's own comparators, over the same
      # truths; "smaller" when the difference exceeds 2 standard errors and no run of either stopped.
      comparators=("$dir/poly-$tag.csv optimal"); [ "$ekf" = 1 ] && comparators+=("$dir/ekf-$tag.csv ekf")
      for pair in "${comparators[@]}"; do
        read -r csv f <<< "$pair"
        verdict_total=$((verdict_total + 1))
        awk -v a="$(j_se "$dir/rs-$tag.csv" risk-sensitive)" -v b="$(j_se "$csv" "$f")" 'BEGIN {
          split(a, x, " "); split(b, y, " ")
          if (x[1] == "" || y[1] == "" || x[3] + 0 > 0 || y[3] + 0 > 0) exit 1
          exit !(x[1] - y[1] < -2 * sqrt(x[2]^2 + y[2]^2)) }' && verdict_rs=$((verdict_rs + 1))
      done
    done
    align
  done
done
echo
echo "Truths: the same in every job of each of the $same_truths rows (simulate's truth table at the report times compared)."
echo "The paper's claim (J_R-S smallest for every eps) holds, on our runs, in $verdict_rs of $verdict_total comparisons"
echo "of risk-sensitive against optimal and ekf (smaller by more than 2 standard errors, no run stopped)."

# Part 2: the invalid printed P(0) or Q(0), run as printed through the printed filters, in the variable
# P~ = P - D (D = printed - repaired): every P in the filter's equations is replaced by P~ + D.
shifted_variant() {  # target filter printed repaired x0 m0
  local d11 d12 d22
  read -r d11 d12 d22 <<< "$(awk -v p="$3" -v r="$4" 'BEGIN {split(p, a, " "); split(r, b, " ");
    printf "%.10g %.10g %.10g\n", a[1] - b[1], a[2] - b[2], a[3] - b[3]}')"
  variant "$1.tmp" "$5" "$6" "$4"
  sed -E -e "/^  $2:/,/^  [a-z]/ { /gain|P_drift|m_drift|^      - |^         \"|^      [A-Za-z][A-Za-z0-9_]*: / {
      s/\bP11\b/(P11 + ($d11))/g; s/\bP12\b/(P12 + ($d12))/g; s/\bP22\b/(P22 + ($d22))/g } }" "$1.tmp" > "$1"
  rm -f "$1.tmp"
}
if [ "$part2" = 1 ]; then
  echo
  echo "2. The invalid printed initial matrices as printed (gamma = 1), through the printed filters:"
  rows=""
  row "case" "filter" "eps" "J from printed P(0)" "J from repaired P(0)"
  for spec in "reactor1 rs-printed rs" "reactor2 ekf-printed ekf" "satellite1 poly-printed poly"; do
    read -r name f group <<< "$spec"
    case " $cases " in *" $name "*) ;; *) continue ;; esac
    case_data "$name"
    dir="$out/$name"; i=0
    for eps in $eps_list; do
      i=$((i + 1)); [ "$i" -gt "$eps_count" ] && break
      case "$group" in
        ekf) printed="$ekf_p0_printed"; rep="$ekf_p0"; m0="$ekf_m0" ;;
        poly) printed="$poly_p0_printed"; rep="$poly_p0"; m0="$poly_m0" ;;
        rs) printed="$(rs_p0 "$eps" "$rs_q0_printed")"; rep="$(rs_p0 "$eps" "$rs_q0")"; m0="$rs_m0" ;;
      esac
      shifted_variant "$dir/$group-printed-p0.yaml" "$f" "$printed" "$rep" "$x0" "$m0"
      run_job "$dir/$group-printed-p0.yaml" "$f" "$eps" 1 "$dir/$group-printed-p0-eps$eps.csv"
      row "$name" "$f" "$eps" "$(cell "$dir/$group-printed-p0-eps$eps.csv" "$f")" \
        "$(cell "$dir/$group-gamma1-eps$eps.csv" "$f" 2>/dev/null || echo -)"
    done
  done
  align
fi
shown="${out#"$here"/}"
echo "Full outputs (simulate's tables and criterion CSVs): $shown/<case>/"
