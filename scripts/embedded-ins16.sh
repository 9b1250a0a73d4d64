#!/usr/bin/env bash
# The 16-state INS's float `ekf` on a Cortex-M4F (docs/benchmarks.md, "A 16-state INS"): the path of
# scripts/embedded-check.sh (same toolchain, flags, start-up code and linker script, same QEMU
# machine) for embedded/ins16_main.cpp, which steps the filter 1000 times (dt = 0.01) with Params
# set before each step. Reports flash and RAM, the step function's code size, the measured stack
# peak, and instructions executed per step: QEMU runs with -icount shift=0 (its virtual clock
# advances 1 ns per instruction) and the firmware reads SysTick, calibrated against a loop of known
# instruction count. QEMU does not model the M4's pipeline: these are instructions, not cycles.
# Twice: with the C++ backend's header, and with the C99 backend's .h/.c (`--language c`) compiled
# as strict C99, side by side.
#
# Checks, each fatal: no heap symbol linked; the step is single-precision FPU code only (no
# software floating point, no double, no libm call); the emulated runs end normally; the C
# firmware prints exactly what the C++ firmware prints; every printed value of the float run agrees
# with the host's double run within |f - d| <= ATOL + RTOL |d|.
#
# Usage: scripts/embedded-ins16.sh [--pfgen PATH] [--work DIR]
#   (the Debian packages of scripts/embedded-check.sh must be installed; run that script once)
set -euo pipefail

root="$(cd "$(dirname "$0")/.." && pwd)"
pfgen="$root/build/generator/pfgen"
work="$root/build/embedded-ins16"
while [ $# -gt 0 ]; do
  case "$1" in
    --pfgen) pfgen="$2"; shift 2 ;;
    --work) work="$2"; shift 2 ;;
    *) echo "embedded-ins16: unknown argument '$1'" >&2; exit 2 ;;
  esac
done
fail() { echo "embedded-ins16: FAIL: $*" >&2; exit 1; }
for tool in arm-none-eabi-g++ qemu-system-arm; do
  command -v "$tool" > /dev/null || fail "$tool not found (scripts/embedded-check.sh installs it)"
done
[ -x "$pfgen" ] || fail "pfgen not found at $pfgen (build it first, or pass --pfgen)"

# Tolerance: float's unit roundoff u = 6e-8 over 1000 steps of a 16-state filter. The estimate
# and the covariance are contracted by the observations (velocity and position), so rounding does
# not grow without bound. Entries that stay near zero on this noise-free circle (q1, q2, the bias
# estimates, about 1e-5) carry the rounding of the terms they are computed from (q0 = 1, v = 10,
# p = 50 to 100: one rounding of p is 6e-6), hence the absolute term. What the check measures is
# reported; the bound catches a float build that computes something else (a wrong literal, a
# promotion, a lost term), which moves values by orders more.
RTOL=1e-3
ATOL=5e-5
symbol=pfgen_embedded_step_ins16
# The stack reserved (link.ld's STACK_SIZE; 4 KB for the small filters of embedded-check.sh): the
# Heun step keeps the 152-entry state, its rates and the predictor, and derivatives() its parts'
# shared values, on the stack. The measured peak is reported.
stack_size=16384
rm -rf "$work"
mkdir -p "$work"
cd "$work"

"$pfgen" codegen "$root/examples/ins16.yaml" --filter ekf --scalar float -o gen-float
"$pfgen" codegen "$root/examples/ins16.yaml" --filter ekf --scalar double -o gen-double
"$pfgen" codegen "$root/examples/ins16.yaml" --filter ekf --language c --scalar float -o gen-c-float

common_flags=(-O2 -mcpu=cortex-m4 -mthumb -mfloat-abi=hard -mfpu=fpv4-sp-d16 -fno-math-errno
              -ffunction-sections -fdata-sections -Wall -Wextra -Wdouble-promotion -Werror)
arm_flags=(-std=c++17 "${common_flags[@]}" -fno-exceptions -fno-rtti -fno-threadsafe-statics -fno-use-cxa-atexit)
# The C filter as a C code base compiles it: strict C99. GCC contracts a * b + c into one fused
# multiply-add by default in C++ but not in ISO C (-std=c99 implies -ffp-contract=off); the same
# contraction for both is what makes their results comparable bit for bit.
c_flags=(-std=c99 -Wpedantic "${common_flags[@]}" -ffp-contract=fast)

# One firmware per backend: main.o with the C++ header, or with the C header and the C filter's
# object. Sets text, data, bss, stack_reserved, step_bytes, instructions, f32, stack_peak,
# step_instructions, per_tick, cpi and step_cycles for the variant; its files are <variant>.*.
measure() {
  local variant="$1"
  local sources=("$root/embedded/ins16_main.cpp" "$root/embedded/startup.cpp")
  local defines=(-DPFGEN_EMBEDDED_TARGET -I gen-float)
  local functions='5ins163ekf'  # the generated C++ functions (mangled)
  if [ "$variant" = c ]; then
    arm-none-eabi-gcc "${c_flags[@]}" -c gen-c-float/ins16/ekf.c -o c-ekf.o
    sources+=(c-ekf.o)
    defines=(-DPFGEN_EMBEDDED_TARGET -DPFGEN_EMBEDDED_C -I gen-c-float)
    functions='^pfgen_models_ins16_ekf_'
  fi
  arm-none-eabi-g++ "${arm_flags[@]}" "${defines[@]}" -I "$root/embedded" "${sources[@]}" \
    -nostartfiles -T "$root/embedded/link.ld" -Wl,--defsym=STACK_SIZE="$stack_size" -Wl,--gc-sections \
    -Wl,-Map="$variant.map" --specs=rdimon.specs -lrdimon -o "$variant.elf"

  heap_symbols=$(arm-none-eabi-nm "$variant.elf" | awk '{ print $NF }' |
    grep -E '^(malloc|free|calloc|realloc|_malloc_r|_free_r|_calloc_r|_realloc_r|__malloc_lock|_sbrk|_sbrk_r|_Znw.*|_Zna.*|_Zdl.*|_Zda.*)$' || true)
  [ -z "$heap_symbols" ] || fail "$variant: heap symbols linked: $(tr "\n" " " <<< "$heap_symbols")"

  # The step and every function it calls (the generated derivatives() is written in parts, each
  # its own function): single-precision FPU code only.
  arm-none-eabi-objdump -d --no-show-raw-insn "$variant.elf" > "$variant.s"
  awk -v s="$symbol" -v f="$functions" '
    /^[0-9a-f]+ <.*>:$/ { name = $2; gsub(/[<>:]/, "", name); inside = (name == s || name ~ f) }
    inside' "$variant.s" > "$variant-step.s"
  f32=$(grep -c '\.f32' "$variant-step.s" || true)
  soft=$(grep -cE '__aeabi_|__(add|sub|mul|div)[sd]f3|\.f64|<(sqrtf?|__errno)>' "$variant-step.s" || true)
  instructions=$(grep -cE '^ +[0-9a-f]+:' "$variant-step.s" || true)
  [ "$f32" -gt 0 ] || fail "$variant: $symbol: no single-precision FPU instruction found"
  [ "$soft" -eq 0 ] || fail "$variant: $symbol: software floating point, double precision or a libm call ($work/$variant-step.s)"
  step_bytes=0
  for size in $(arm-none-eabi-nm -S "$variant.elf" | awk -v s="$symbol" -v f="$functions" '$4 == s || $4 ~ f { print $2 }'); do
    step_bytes=$((step_bytes + 16#$size))
  done
  read -r text data bss < <(arm-none-eabi-size "$variant.elf" | awk 'NR == 2 { print $1, $2, $3 }')
  stack_reserved=$(arm-none-eabi-size -A "$variant.elf" | awk '$1 == ".stack" { print $2 }')

  set +e
  timeout 120 qemu-system-arm -machine mps2-an386 -nographic -monitor none -serial none -icount shift=0 \
    -chardev file,id=semihosting,path="$variant.txt" \
    -semihosting-config enable=on,target=native,chardev=semihosting \
    -kernel "$variant.elf" > "$variant-qemu.log" 2>&1
  local status=$?
  set -e
  [ "$status" -eq 0 ] || fail "$variant: the firmware exited with status $status ($work/$variant.txt, $work/$variant-qemu.log)"
  grep -qx 'end ok' "$variant.txt" || fail "$variant: the firmware did not report 'end ok' ($work/$variant.txt)"
  stack_peak=$(awk '$1 == "info" { for (i = 2; i < NF; i++) if ($i == "stack_peak") print $(i + 1) }' "$variant.txt")
  [ "$stack_peak" -lt "$stack_reserved" ] || fail "$variant: the stack peak reached the reserved $stack_reserved bytes"

  # Instructions per step: SysTick ticks of every 100 steps times instructions per tick.
  local per_step
  per_step=$(awk '
    $1 == "calibration" { per_tick = $2 / $3 }
    $1 == "ticks" { ticks += $3; steps += 100 }
    END { if (!per_tick || !steps) exit 1; printf "%.0f %.2f", ticks * per_tick / steps, per_tick }' "$variant.txt") ||
    fail "$variant: no SysTick figures in $work/$variant.txt"
  read -r step_instructions per_tick <<< "$per_step"
  # A cycle estimate, not a measurement: the step code's static instruction mix weighted by the
  # Cortex-M4 TRM's cycle counts without wait states or pipelining of neighbouring loads (VLDR, VSTR,
  # LDR 2; VFMA, VFMS, VMLA, VMLS, VNMLA 3; VDIV, VSQRT 14; LDRD, STRD 3; BL 4; others 1), which bounds
  # cycles per instruction from above (back-to-back loads pipeline to 1 cycle each); every part of
  # derivatives() and gain() runs twice per Heun step, so the executed mix is close to the static one.
  cpi=$(awk '
    /^ +[0-9a-f]+:/ {
      op = $2; sub(/\..*/, "", op); n++
      if (op ~ /^(vldr|vstr|ldr|ldrb|ldrh)$/) c += 2
      else if (op ~ /^(vfma|vfms|vfnma|vfnms|vmla|vmls|vnmla|vnmls|ldrd|strd)$/) c += 3
      else if (op ~ /^(vdiv|vsqrt)$/) c += 14
      else if (op ~ /^(bl|blx)$/) c += 4
      else c += 1
    }
    END { printf "%.2f", c / n }' "$variant-step.s")
  step_cycles=$(awk -v i="$step_instructions" -v c="$cpi" 'BEGIN { printf "%.0f", i * c }')
  report+="$(printf '  %-4s flash %7d B (text %d, data %d)  step code %6d B, %5d instructions  stack peak %5d B of %d  %6d instructions/step  <= ~%6d cycles/step (%s cpi)' \
    "$variant" $((text + data)) "$text" "$data" "$step_bytes" "$instructions" "$stack_peak" "$stack_reserved" \
    "$step_instructions" "$step_cycles" "$cpi")"$'\n'
}

report=""
measure cpp
measure c
# The two backends compute the same operations in the same order: every printed value is the same.
cmp -s <(grep '^traj' cpp.txt) <(grep '^traj' c.txt) ||
  fail "the C filter's trajectory differs from the C++ filter's ($work/cpp.txt, $work/c.txt)"

c++ -std=c++17 -O2 -Wall -Wextra -Wdouble-promotion -Werror -I gen-double -I "$root/embedded" \
  "$root/embedded/ins16_main.cpp" -o host
./host > host.txt
grep -qx 'end ok' host.txt || fail "the host run did not report 'end ok' ($work/host.txt)"

compare=$(awk -v rtol="$RTOL" -v atol="$ATOL" '
  function abs(x) { return x < 0 ? -x : x }
  FNR == 1 { file++ }
  $1 != "traj" { next }
  file == 1 { for (i = 4; i <= NF; i++) host[$2, $3, i] = $i; next }
  {
    for (i = 4; i <= NF; i++) {
      if (!(($2, $3, i) in host)) { print "error: no host value for " $2 " " $3; bad = 1; continue }
      f = $i + 0; d = host[$2, $3, i] + 0; dev = abs(f - d); count++
      if (d != 0 && dev / abs(d) > worst) { worst = dev / abs(d); where = $2 " step " $3 " column " i - 4 }
      if (dev > worst_abs) { worst_abs = dev; where_abs = $2 " step " $3 " column " i - 4 }
      if (!(dev <= atol + rtol * abs(d))) { print "error: " $2 " step " $3 ": float " $i ", double " host[$2, $3, i]; bad = 1 }
    }
  }
  END {
    printf "%d values, largest absolute deviation %.2e (%s), largest relative %.2e (%s)\n", count, worst_abs,
      where_abs, worst, where
    exit bad
  }' host.txt cpp.txt) ||
  fail "float and double runs disagree: $compare"

{
  echo "embedded-ins16: ins16 ekf (--scalar float) on Cortex-M4F (qemu-system-arm -machine mps2-an386 -icount shift=0),"
  echo "  the C++ backend's header and the C99 backend's .h/.c (--language c) side by side:"
  printf '%s' "$report"
  echo "  C and C++ trajectories: identical, bit for bit ($(grep -c '^traj' c.txt) lines)"
  echo "  float vs host double: $compare; tolerance $ATOL + $RTOL |double|"
  echo "embedded-ins16: OK"
} | tee report.txt
