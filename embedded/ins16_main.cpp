// The 16-state INS (examples/ins16.yaml) on the Cortex-M4F: its `ekf`, as written by
// `pfgen codegen --scalar float`, stepped 1000 times (dt = 0.01, 10 s) the way firmware steps it:
// before each step the gyro and accelerometer readings go into Params (here the level right turn
// of the model's defaults, w = (0, 0, 0.2) rad/s, a = (0, 2, -9.81) m/s^2), and dy holds the
// velocity and position increments of the noise-free circle the turn flies (radius 50 m at 10 m/s,
// computed in double, rounded to float, so the host run reads the very same inputs).
//
// It also counts what one step costs: SysTick runs from the processor clock, and under
// qemu-system-arm -icount shift=0 QEMU's virtual clock advances one nanosecond per executed
// instruction, so SysTick ticks count instructions (at 25 MHz: one tick per 40 instructions).
// A loop of known length (2 instructions per iteration) calibrates instructions per tick;
// scripts/embedded-ins16.sh turns the ticks of each 100 steps into instructions per step. QEMU
// executes instructions; it does not model the M4's pipeline, so this is not a cycle count.
//
// One source, three builds (scripts/embedded-ins16.sh): firmware with PFGEN_EMBEDDED_TARGET and the
// `--scalar float` header; the same firmware on the C99 backend's float code (PFGEN_EMBEDDED_C);
// host with the `--scalar double` header. Output lines:
//   traj <group> <k> <t> <8 values>   groups m1..m8, m9..m16, P11..P88 (diagonal), P99..P16_16
//   ticks <k> <SysTick ticks of the 100 steps before step k>   (firmware only)
//   calibration <iterations> <ticks>                           (firmware only)
//   info ..., end ok | end FAIL
#include <cstddef>
#include <cstdint>

#if defined(PFGEN_EMBEDDED_C)
#include "ins16/ekf.h"
#else
#include "ins16/ekf.hpp"
#endif
#include "text_line.hpp"

#if defined(PFGEN_EMBEDDED_TARGET)
#include "board.hpp"
#include "semihosting.hpp"
#else
#include <cstdio>
#endif

// The filter as this program calls it: the C++ backend's header, or with PFGEN_EMBEDDED_C the C99
// backend's (`pfgen codegen --language c --scalar float`), whose step computes the same numbers.
namespace ekf {
#if defined(PFGEN_EMBEDDED_C)
using Scalar = float;
constexpr int n = pfgen_models_ins16_ekf_n, p = pfgen_models_ins16_ekf_p, state_size = pfgen_models_ins16_ekf_state_size;
using Params = pfgen_models_ins16_ekf_params;
inline void initial_state(Scalar* state) { pfgen_models_ins16_ekf_initial_state(state); }
inline Params default_params() {
  Params params;
  pfgen_models_ins16_ekf_default_params(&params);
  return params;
}
inline void step(Scalar* state, Scalar t, Scalar dt, const Scalar* dy, const Params& params) {
  pfgen_models_ins16_ekf_step(state, t, dt, dy, &params);
}
#else
using namespace pfgen_models::ins16::ekf;
using Params = pfgen_models::ins16::ekf::Params<Scalar>;
inline Params default_params() { return Params{}; }
#endif
}  // namespace ekf
using pfgen_embedded::Line;
using Scalar = ekf::Scalar;

static_assert(ekf::n == 16 && ekf::p == 6, "ins16: 16 states, velocity and position observed");

// Out of line with a C name, so that the script can disassemble and size exactly the filter step.
extern "C" __attribute__((noinline)) void pfgen_embedded_step_ins16(Scalar* state, Scalar t, Scalar dt,
                                                                    const Scalar* dy,
                                                                    const ekf::Params& params) {
  ekf::step(state, t, dt, dy, params);
}

namespace {

constexpr int steps = 1000;
constexpr int print_every = 100;
constexpr float dt_float = 0.01f;

void write_line(const Line& line) {
#if defined(PFGEN_EMBEDDED_TARGET)
  pfgen_embedded::semihosting::write(line.c_str());
  pfgen_embedded::semihosting::write("\n");
#else
  std::fputs(line.c_str(), stdout);
  std::fputc('\n', stdout);
#endif
}

bool finite(Scalar value) { return value == value && value - value == Scalar(0); }

#if defined(PFGEN_EMBEDDED_TARGET)
// SysTick (ARMv7-M): 24-bit down counter from the processor clock, no interrupt.
volatile std::uint32_t& syst_csr = *reinterpret_cast<volatile std::uint32_t*>(0xE000E010u);
volatile std::uint32_t& syst_rvr = *reinterpret_cast<volatile std::uint32_t*>(0xE000E014u);
volatile std::uint32_t& syst_cvr = *reinterpret_cast<volatile std::uint32_t*>(0xE000E018u);
void start_systick() {
  syst_rvr = 0xFFFFFFu;
  syst_cvr = 0u;
  syst_csr = 5u;  // enable, processor clock
}
std::uint32_t ticks_since(std::uint32_t start) { return (start - syst_cvr) & 0xFFFFFFu; }

// 2 instructions per iteration (subs, bne): the calibration of instructions per tick.
__attribute__((noinline)) void spin(std::uint32_t iterations) {
  asm volatile("1: subs %0, %0, #1\n\tbne 1b" : "+r"(iterations) : : "cc");
}
#endif

void print_state(int k, Scalar t, const Scalar* state, bool& ok) {
  static const char* const groups[4] = {"m1-8", "m9-16", "Pdiag1-8", "Pdiag9-16"};
  for (int g = 0; g < 4; ++g) {
    Line line;
    line.text("traj ");
    line.text(groups[g]);
    line.text(" ");
    line.integer(k);
    line.text(" ");
    line.number(static_cast<double>(t));
    for (int i = 8 * (g % 2); i < 8 * (g % 2) + 8; ++i) {
      // P's diagonal entry i sits at n + i n - i (i - 1) / 2 in the upper triangle, row by row.
      const int index = g < 2 ? i : ekf::n + i * ekf::n - i * (i - 1) / 2;
      line.text(" ");
      line.number(static_cast<double>(state[index]));
      ok = ok && finite(state[index]);
    }
    write_line(line);
  }
}

}  // namespace

int main() {
  Scalar state[ekf::state_size];
  ekf::initial_state(state);
  ekf::Params params = ekf::default_params();
  const Scalar dt = Scalar(dt_float);
  // The circle: v = V (cos wt, sin wt, 0), p = (V / w) (sin wt, 1 - cos wt, 0), V = 10, w = 0.2.
  const double speed = 10.0, rate = 0.2, step = static_cast<double>(dt_float);
  // cos and sin of rate * step, by their series to double precision (no libm on the target).
  const double angle = rate * step;
  const double c = 1.0 - angle * angle / 2.0 + angle * angle * angle * angle / 24.0;
  const double s = angle - angle * angle * angle / 6.0 + angle * angle * angle * angle * angle / 120.0;
  double cos_wt = 1.0, sin_wt = 0.0;
  bool ok = true;
#if defined(PFGEN_EMBEDDED_TARGET)
  start_systick();
  std::uint32_t started = syst_cvr;
  spin(100000);
  const std::uint32_t calibration_ticks = ticks_since(started);
  started = syst_cvr;
#endif
  for (int k = 0;; ++k) {
    const Scalar t = Scalar(k) * dt;
    if (k % print_every == 0) {
#if defined(PFGEN_EMBEDDED_TARGET)
      const std::uint32_t ticks = ticks_since(started);
      if (k > 0) {
        Line line;
        line.text("ticks ");
        line.integer(k);
        line.text(" ");
        line.integer(static_cast<long>(ticks));
        write_line(line);
      }
#endif
      print_state(k, t, state, ok);
#if defined(PFGEN_EMBEDDED_TARGET)
      started = syst_cvr;
#endif
    }
    if (k == steps) break;
    // The readings of this step, as a driver would deliver them.
    params.wx = Scalar(0.0f);
    params.wy = Scalar(0.0f);
    params.wz = Scalar(0.2f);
    params.ax = Scalar(0.0f);
    params.ay = Scalar(2.0f);
    params.az = Scalar(-9.81f);
    const double next_cos = cos_wt * c - sin_wt * s, next_sin = sin_wt * c + cos_wt * s;
    // dy = the exact integrals of v and p over [t, t + dt] (no observation noise).
    const double radius = speed / rate;
    const double vn = radius * (next_sin - sin_wt), ve = radius * (cos_wt - next_cos);
    const double pn = radius / rate * (cos_wt - next_cos), pe = radius * (step - (next_sin - sin_wt) / rate);
    const Scalar dy[6] = {Scalar(static_cast<float>(vn)), Scalar(static_cast<float>(ve)), Scalar(0.0f),
                          Scalar(static_cast<float>(pn)), Scalar(static_cast<float>(pe)), Scalar(0.0f)};
    pfgen_embedded_step_ins16(state, t, dt, dy, params);
    cos_wt = next_cos;
    sin_wt = next_sin;
  }

  Line info;
  info.text("info scalar_bytes ");
  info.integer(static_cast<long>(sizeof(Scalar)));
#if defined(PFGEN_EMBEDDED_TARGET)
  info.text(" stack_reserved ");
  info.integer(static_cast<long>(pfgen_embedded::board::stack_reserved_bytes()));
  info.text(" stack_peak ");
  info.integer(static_cast<long>(pfgen_embedded::board::stack_peak_bytes()));
  write_line(info);
  Line calibration;
  calibration.text("calibration 200000 ");  // instructions in spin(100000), less a few of call and return
  calibration.integer(static_cast<long>(calibration_ticks));
  write_line(calibration);
#else
  write_line(info);
#endif
  Line end;
  end.text(ok ? "end ok" : "end FAIL: the ekf state is not finite");
  write_line(end);
  return ok ? 0 : 1;
}
