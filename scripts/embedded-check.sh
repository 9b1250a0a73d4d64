#!/usr/bin/env bash
# Embedded proof (docs/guide/embedded.md): the float code `pfgen codegen --scalar float`
# writes for paper 000's and paper 001's examples (optimal filter), for paper 003's Example 1
# with gamma = 1 (sampled observations, cd-optimal: predict/update) and for delay_linear (delayed
# observations, delay-optimal with its history ring), cross-compiled for a
# Cortex-M4F (arm-none-eabi, hard float) into a bare-metal program, run under
#   qemu-system-arm -machine mps2-an386
# on the recorded observations and samples of embedded/observations.hpp, and compared with the
# host's double-precision run of the same program (embedded/main.cpp with the --scalar double code).
#
# Checks, each fatal: the committed observation header is what embedded/tools/ regenerates; the
# firmware links no heap symbol; the filter step functions are single-precision FPU code only
# (no software floating point); the emulated run ends normally; every printed value agrees with
# the host's within |float - double| <= ATOL + RTOL * |double|. Prints a report (also written to
# WORK/report.txt) with flash and RAM use and the largest deviations.
#
# Usage: scripts/embedded-check.sh [--pfgen PATH] [--work DIR] [--no-install]
#   --pfgen PATH   the built pfgen (default build/generator/pfgen)
#   --work DIR     scratch directory (default build/embedded); recreated on each run
#   --no-install   fail instead of installing missing Debian packages
# Missing Debian packages (gcc-arm-none-eabi libnewlib-arm-none-eabi libstdc++-arm-none-eabi-newlib
# qemu-system-arm) are installed first (apt-get update, then apt-get install; root or sudo).
set -euo pipefail

root="$(cd "$(dirname "$0")/.." && pwd)"
pfgen="$root/build/generator/pfgen"
work="$root/build/embedded"
install=1
while [ $# -gt 0 ]; do
  case "$1" in
    --pfgen) pfgen="$2"; shift 2 ;;
    --work) work="$2"; shift 2 ;;
    --no-install) install=0; shift ;;
    *) echo "embedded-check: unknown argument '$1'" >&2; exit 2 ;;
  esac
done

# The tolerance, justified in docs/guide/embedded.md: float's unit roundoff is
# u = 2^-24 = 6e-8; with k = 10-20 roundings per state entry per step, rounding errors that add
# up like a random walk over N = 500 steps give sqrt(N) * k * u = 1.3e-5 to 2.7e-5 relative, and
# RTOL keeps a factor 4-8 over that (the filters are stable, so the linear worst case
# N * k * u = 6e-4 is not approached). ATOL covers entries that pass near zero (m1) or decay
# (P22), whose error is set by the O(0.1-1) entries they are computed from, not by their own size.
# The sampled run (200 samples, 10 predictions and one update each) stays well inside the same
# bounds: each update contracts the error it inherits (Id - K C = R / (R + C^2 P) = 4.4e-4 here,
# with the predicted P = 22.7), so rounding does not accumulate across samples; what remains is one sample's rounding of
# m = y / C + ..., about |m| * u, and of P = R / C^2 + ..., about P * u.
RTOL=1e-4
ATOL=1e-5

models=(basin2006_quadratic basin_skliar_partial)
# The sampled filter run: cd-optimal (Heun predictions, Kalman update) over recorded samples.
sampled_models=(allahyani_date_example1_gamma1)
# The delayed filter run: delay-optimal (fixed grid, history ring of m and x*).
delayed_models=(delay_linear)
step_symbols=(pfgen_embedded_step_basin2006_quadratic pfgen_embedded_step_basin_skliar_partial
              pfgen_embedded_advance_allahyani_date_example1_gamma1 pfgen_embedded_step_delay_linear)
qemu_timeout=60

fail() { echo "embedded-check: FAIL: $*" >&2; exit 1; }
now() { date +%s.%N; }
elapsed() { awk -v a="$1" -v b="$(now)" 'BEGIN { printf "%.1f", b - a }'; }
start=$(now)

# --- Debian packages -----------------------------------------------------------------------
packages=(gcc-arm-none-eabi libnewlib-arm-none-eabi libstdc++-arm-none-eabi-newlib qemu-system-arm)
missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
if [ ${#missing[@]} -gt 0 ]; then
  [ "$install" -eq 1 ] || fail "missing Debian packages: ${missing[*]}"
  echo "embedded-check: installing ${missing[*]}"
  SUDO=""
  if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
  $SUDO apt-get update
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y --no-install-recommends "${missing[@]}"
fi
install_s=$(elapsed "$start")
t_work=$(now)

[ -x "$pfgen" ] || fail "pfgen not found at $pfgen (build it first, or pass --pfgen)"
rm -rf "$work"
mkdir -p "$work"
cd "$work"

# --- float and double code from the built pfgen (generated/ holds template code) -----------
for m in "${models[@]}"; do
  "$pfgen" codegen "$root/examples/$m.yaml" --filter optimal --scalar float -o gen-float
  "$pfgen" codegen "$root/examples/$m.yaml" --filter optimal --scalar double -o gen-double
done
for m in "${sampled_models[@]}"; do
  "$pfgen" codegen "$root/examples/$m.yaml" --filter cd-optimal --scalar float -o gen-float
  "$pfgen" codegen "$root/examples/$m.yaml" --filter cd-optimal --scalar double -o gen-double
done
for m in "${delayed_models[@]}"; do  # the grid dt is the model's simulation: dt (0.01)
  "$pfgen" codegen "$root/examples/$m.yaml" --filter delay-optimal --scalar float -o gen-float
  "$pfgen" codegen "$root/examples/$m.yaml" --filter delay-optimal --scalar double -o gen-double
done

# --- the recorded observations are what the committed tool writes -------------------------
c++ -std=c++17 -O2 -o record_observations "$root/embedded/tools/record_observations.cpp"
./record_observations > observations.hpp
cmp -s observations.hpp "$root/embedded/observations.hpp" ||
  fail "embedded/observations.hpp differs from what embedded/tools/record_observations.cpp writes ($work/observations.hpp)"

# --- the C99 backend for the target: every example, every filter ---------------------------
# Each float .c compiles as strict C99 with the firmware's flags, and calls nothing but sqrtf.
c_files=0
for model in "$root"/examples/*.yaml; do
  "$pfgen" codegen "$model" --language c --scalar float -o gen-c-float
done
for c_file in gen-c-float/*/*.c; do
  arm-none-eabi-gcc -std=c99 -O2 -mcpu=cortex-m4 -mthumb -mfloat-abi=hard -mfpu=fpv4-sp-d16 \
    -Wall -Wextra -Wpedantic -Wdouble-promotion -Werror -c "$c_file" -o c-filter.o ||
    fail "$c_file does not compile as C99 for the Cortex-M4F"
  calls=$(arm-none-eabi-nm -u c-filter.o | awk '$2 != "sqrtf" { print $2 }' | tr "\n" " ")
  [ -z "$calls" ] || fail "$c_file calls $calls"
  c_files=$((c_files + 1))
done
[ "$c_files" -gt 0 ] || fail "no C filter was generated"

# --- firmware ------------------------------------------------------------------------------
# -fno-math-errno: the sampled update's std::sqrt (of a pivot already checked positive) becomes
# the vsqrt.f32 instruction alone; without it GCC keeps a call to newlib's sqrtf for the errno
# case, which links __errno and newlib's 1 KB reentrancy structure (impure_data) into RAM.
arm_flags=(-std=c++17 -O2 -mcpu=cortex-m4 -mthumb -mfloat-abi=hard -mfpu=fpv4-sp-d16 -fno-math-errno
           -fno-exceptions -fno-rtti -fno-threadsafe-statics -fno-use-cxa-atexit
           -ffunction-sections -fdata-sections -Wall -Wextra -Wdouble-promotion -Werror)
arm-none-eabi-g++ "${arm_flags[@]}" -DPFGEN_EMBEDDED_TARGET -I gen-float -I "$root/embedded" \
  "$root/embedded/main.cpp" "$root/embedded/startup.cpp" \
  -nostartfiles -T "$root/embedded/link.ld" -Wl,--gc-sections -Wl,-Map=fw.map \
  --specs=rdimon.specs -lrdimon -o fw.elf

# No heap: neither defined nor referenced (an undefined one would not link, but look anyway).
heap_symbols=$(arm-none-eabi-nm fw.elf | awk '{ print $NF }' |
  grep -E '^(malloc|free|calloc|realloc|_malloc_r|_free_r|_calloc_r|_realloc_r|__malloc_lock|_sbrk|_sbrk_r|_Znw.*|_Zna.*|_Zdl.*|_Zda.*)$' || true)
[ -z "$heap_symbols" ] || fail "heap symbols linked into fw.elf: $(tr "\n" " " <<< "$heap_symbols")"

# The filter steps run on the single-precision FPU: no software floating-point helper is called
# and no double-precision instruction appears (fpv4-sp-d16 has none anyway).
step_report=""
for s in "${step_symbols[@]}"; do
  arm-none-eabi-objdump -d --no-show-raw-insn --disassemble="$s" fw.elf > "$s.s"
  f32=$(grep -c '\.f32' "$s.s" || true)
  soft=$(grep -cE '__aeabi_|__(add|sub|mul|div)[sd]f3|\.f64|<(sqrtf?|__errno)>' "$s.s" || true)
  [ "$f32" -gt 0 ] || fail "$s: no single-precision FPU instruction found"
  [ "$soft" -eq 0 ] || fail "$s: software floating point, double precision or a libm call in the filter step ($work/$s.s)"
  bytes=$((16#$(arm-none-eabi-nm -S fw.elf | awk -v s="$s" '$4 == s { print $2 }')))
  step_report+="    ${s#pfgen_embedded_*_}: $bytes bytes of code, $f32 .f32 FPU instructions, 0 soft-float or libm calls"$'\n'
done

read -r text data bss < <(arm-none-eabi-size fw.elf | awk 'NR == 2 { print $1, $2, $3 }')
stack_reserved=$(arm-none-eabi-size -A fw.elf | awk '$1 == ".stack" { print $2 }')
flash=$((text + data))
# What the flash holds besides the filters: the recorded observations.
observation_bytes=0
for h in $(arm-none-eabi-nm -S fw.elf | awk '$4 ~ /observations.*_(dy|y)E?$/ { print $2 }'); do
  observation_bytes=$((observation_bytes + 16#$h))
done
ram=$((data + bss))

# --- host: the same program on the double-precision code -----------------------------------
c++ -std=c++17 -O2 -Wall -Wextra -Wdouble-promotion -Werror -I gen-double -I "$root/embedded" \
  "$root/embedded/main.cpp" -o host
./host > host.txt
build_s=$(elapsed "$t_work")

# --- emulated run: semihosting output goes to target.txt -----------------------------------
t_qemu=$(now)
set +e
timeout "$qemu_timeout" qemu-system-arm -machine mps2-an386 -nographic -monitor none -serial none \
  -chardev file,id=semihosting,path=target.txt \
  -semihosting-config enable=on,target=native,chardev=semihosting \
  -kernel fw.elf > qemu.log 2>&1
qemu_status=$?
set -e
qemu_s=$(elapsed "$t_qemu")
[ "$qemu_status" -ne 124 ] || fail "qemu-system-arm did not finish within ${qemu_timeout}s"
[ "$qemu_status" -eq 0 ] || fail "the firmware exited with status $qemu_status (output: $work/target.txt, $work/qemu.log)"
grep -qx 'end ok' target.txt || fail "the firmware did not report 'end ok' ($work/target.txt)"
grep -qx 'end ok' host.txt || fail "the host run did not report 'end ok' ($work/host.txt)"
stack_peak=$(awk '$1 == "info" { for (i = 2; i < NF; i++) if ($i == "stack_peak") print $(i + 1) }' target.txt)

# --- compare every printed value -----------------------------------------------------------
# Writes one summary line per model, then "worst <ratio> <where>", then "compared <count>".
set +e
awk -v rtol="$RTOL" -v atol="$ATOL" '
  function abs(x) { return x < 0 ? -x : x }
  function numeric(s) { return s ~ /^-?[0-9]\.[0-9]+e[-+][0-9]+$/ }
  FNR == 1 { file++ }
  $1 == "columns" { names[$2] = $0; next }
  $1 != "traj" { next }
  file == 1 { key = $2 SUBSEP $3; hostn[key] = NF; for (i = 4; i <= NF; i++) host[key, i] = $i; next }
  {
    key = $2 SUBSEP $3; seen[key] = 1
    if (!(key in hostn)) { print "error no host line for " $2 " step " $3; bad = 1; next }
    if (hostn[key] != NF) { print "error column count differs for " $2 " step " $3; bad = 1; next }
    split(names[$2], col, " ")
    for (i = 4; i <= NF; i++) {
      if (!numeric($i) || !numeric(host[key, i])) { print "error non-numeric value " $i " / " host[key, i]; bad = 1; continue }
      f = $i + 0; d = host[key, i] + 0; dev = abs(f - d)
      ratio = dev / (atol + rtol * abs(d))
      count++
      if (!($2 in model)) { model[$2] = 1; order[++models] = $2 }
      if (dev > maxabs[$2]) { maxabs[$2] = dev; maxabs_at[$2] = col[i] " at step " $3 }
      if (d != 0 && dev / abs(d) > maxrel[$2]) { maxrel[$2] = dev / abs(d); maxrel_at[$2] = col[i] " at step " $3 }
      if (ratio > worstm[$2]) worstm[$2] = ratio
      if (ratio > worst) { worst = ratio; worst_at = $2 " " col[i] " at step " $3 ": float " $i ", double " host[key, i] }
      if (ratio > 1) { print "error " $2 " " col[i] " step " $3 ": float " $i " vs double " host[key, i]; bad = 1 }
    }
  }
  END {
    for (key in hostn) if (!(key in seen)) { split(key, part, SUBSEP); print "error no firmware line for " part[1] " step " part[2]; bad = 1 }
    for (j = 1; j <= models; j++) {
      m = order[j]
      printf "model %s max_abs %.2e (%s) max_rel %.2e (%s) worst/tolerance %.3f\n", m, maxabs[m], maxabs_at[m], maxrel[m], maxrel_at[m], worstm[m]
    }
    printf "worst %.3f %s\n", worst, worst_at
    printf "compared %d\n", count
    exit bad
  }' host.txt target.txt > compare.txt
compare_status=$?
set -e
grep '^error' compare.txt >&2 || true
[ "$compare_status" -eq 0 ] || fail "float and double trajectories disagree beyond the tolerance ($work/compare.txt)"
compared=$(awk '$1 == "compared" { print $2 }' compare.txt)
[ "$compared" -gt 0 ] || fail "no values compared"
total_s=$(elapsed "$t_work")

{
  echo "embedded-check: Cortex-M4F (qemu-system-arm -machine mps2-an386) vs host double, optimal filters of"
  echo "  ${models[*]}, sampled cd-optimal filter of ${sampled_models[*]}, delayed delay-optimal filter of ${delayed_models[*]};"
  echo "  $(grep -c '^traj' target.txt) trajectory lines, $compared values compared"
  echo "  flash (text + data): $flash bytes   [text $text, data $data; of which $observation_bytes bytes of recorded observations]"
  echo "  RAM (data + bss):    $ram bytes   [data $data, bss $((bss - stack_reserved)), stack reserved $stack_reserved; stack peak measured $stack_peak]"
  echo "  heap symbols: none (malloc, free, _sbrk, _sbrk_r, operator new/delete absent)"
  echo "  C99 backend: $c_files float .c files of the examples compile with arm-none-eabi-gcc -std=c99 -Wpedantic -Werror, calling nothing but sqrtf"
  echo "  filter steps:"
  printf '%s' "$step_report"
  echo "  tolerance: |float - double| <= $ATOL + $RTOL * |double|"
  awk '$1 == "model" { sub(/^model /, "    "); print }' compare.txt
  awk '$1 == "worst" { printf "  worst deviation / tolerance: %s (", $2; $1 = ""; $2 = ""; sub(/^  /, ""); print $0 ")" }' compare.txt
  echo "  time: ${total_s}s (build ${build_s}s, qemu ${qemu_s}s; package check/install ${install_s}s)"
  echo "embedded-check: OK"
} | tee report.txt
