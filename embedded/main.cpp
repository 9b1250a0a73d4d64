// The embedded proof's filter run: paper 000's and paper 001's optimal filters, as written
// by `pfgen codegen`, stepped over the recorded observation sequence of observations.hpp,
// with every `print_every`-th state printed as one line; then the sampled filter (cd-optimal) of
// paper 003's Example 1 (gamma = 1), advanced over its recorded samples (`substeps` Heun
// predictions and one Kalman update per sample), with the state printed after every sample; then
// the delayed-observation filter (delay-optimal) of examples/delay_linear.yaml over its recorded
// increments, with its fixed-size history (h = 0.5 = 50 steps) in a static array.
//
// One source, two builds (scripts/embedded-check.sh):
//  - firmware: arm-none-eabi-g++ with PFGEN_EMBEDDED_TARGET, the `--scalar float` headers,
//    output over semihosting, run under qemu-system-arm -machine mps2-an386;
//  - host: the native compiler with the `--scalar double` headers, output on stdout.
// The include path picks the headers; the code below only uses the generated Scalar.
//
// Output lines:
//   columns <model> step|sample t <state entries...>
//   traj <model> <k> <t> <state entries...>     (k = 0, print_every, ..., steps; sampled: every sample)
//   info ...                                    (platform facts; not compared)
//   end ok | end FAIL ...
#include <cstddef>

#include "basin2006_quadratic/optimal.hpp"
#include "allahyani_date_example1_gamma1/cd_optimal.hpp"
#include "basin_skliar_partial/optimal.hpp"
#include "delay_linear/delay_optimal.hpp"
#include "observations.hpp"
#include "text_line.hpp"

#if defined(PFGEN_EMBEDDED_TARGET)
#include "board.hpp"
#include "semihosting.hpp"
#else
#include <cstdio>
#endif

namespace quadratic = pfgen_models::basin2006_quadratic::optimal;
namespace partial = pfgen_models::basin_skliar_partial::optimal;
namespace sampled = pfgen_models::allahyani_date_example1_gamma1::cd_optimal;
namespace delayed = pfgen_models::delay_linear::delay_optimal;
namespace observations = pfgen_embedded::observations;
using pfgen_embedded::Line;

static_assert(quadratic::p == 1 && partial::p == 1, "the recorded sequence holds one observation per step");
static_assert(sampled::p == 1, "the recorded samples hold one observation each");
static_assert(delayed::p == 1, "the recorded sequence holds one observation per step");

// Out of line and with C names, so that scripts/embedded-check.sh can disassemble exactly
// the filter step and check that it is single-precision FPU code only.
extern "C" __attribute__((noinline)) void pfgen_embedded_step_basin2006_quadratic(quadratic::Scalar* state,
                                                                                  quadratic::Scalar t,
                                                                                  quadratic::Scalar dt,
                                                                                  const quadratic::Scalar* dy) {
  quadratic::step(state, t, dt, dy, quadratic::Params<quadratic::Scalar>{});
}

extern "C" __attribute__((noinline)) void pfgen_embedded_step_basin_skliar_partial(partial::Scalar* state,
                                                                                   partial::Scalar t,
                                                                                   partial::Scalar dt,
                                                                                   const partial::Scalar* dy) {
  partial::step(state, t, dt, dy, partial::Params<partial::Scalar>{});
}

// One sampling period: predictions from t to t + period(), then the update with the sample y
// taken at t + period(). Returns false when the update refused (S not positive definite).
extern "C" __attribute__((noinline)) bool pfgen_embedded_advance_allahyani_date_example1_gamma1(sampled::Scalar* state,
                                                                                               sampled::Scalar t,
                                                                                               const sampled::Scalar* y) {
  return sampled::advance(state, t, y, sampled::Params<sampled::Scalar>{});
}

// One grid step k of the delayed filter: Heun over [k dt, (k + 1) dt] reading m and x* h ago
// from its history ring, then storing the step's start in it. `flatten` inlines the generated
// step into this symbol (GCC keeps the larger delayed step out of line otherwise), so that the
// check below disassembles all of its arithmetic.
extern "C" __attribute__((noinline, flatten)) void pfgen_embedded_step_delay_linear(delayed::Scalar* state,
                                                                          delayed::Scalar* history, std::size_t k,
                                                                          const delayed::Scalar* dy) {
  delayed::step(state, history, k, dy, delayed::Params<delayed::Scalar>{});
}

namespace {

constexpr int print_every = 10;

void write_line(const Line& line) {
#if defined(PFGEN_EMBEDDED_TARGET)
  pfgen_embedded::semihosting::write(line.c_str());
  pfgen_embedded::semihosting::write("\n");
#else
  std::fputs(line.c_str(), stdout);
  std::fputc('\n', stdout);
#endif
}

template <class Scalar>
bool finite(Scalar value) {
  return value == value && value - value == Scalar(0);
}

// Runs one filter over its recorded sequence; false if the state stopped being finite.
template <class Scalar, std::size_t StateSize, class Init, class Step>
bool run(const char* model, const char* const (&columns)[StateSize], const float* dy_record, Init initial_state,
         Step step) {
  Line header;
  header.text("columns ");
  header.text(model);
  header.text(" step t");
  for (const char* column : columns) {
    header.text(" ");
    header.text(column);
  }
  write_line(header);

  Scalar state[StateSize];
  initial_state(state);
  const Scalar dt = Scalar(observations::dt);
  bool ok = true;
  for (int k = 0;; ++k) {
    const Scalar t = Scalar(k) * dt;
    if (k % print_every == 0) {
      Line line;
      line.text("traj ");
      line.text(model);
      line.text(" ");
      line.integer(k);
      line.text(" ");
      line.number(static_cast<double>(t));
      for (std::size_t i = 0; i < StateSize; ++i) {
        line.text(" ");
        line.number(static_cast<double>(state[i]));
        ok = ok && finite(state[i]);
      }
      write_line(line);
    }
    if (k == observations::steps) break;
    const Scalar dy[1] = {Scalar(dy_record[k])};
    step(state, t, dt, dy);
  }
  return ok;
}

// Runs the sampled filter over its recorded samples; false if an update refused or the state
// stopped being finite. Line k holds the state after the k-th sample (k = 0: the initial state).
template <class Scalar, std::size_t StateSize>
bool run_sampled(const char* model, const char* const (&columns)[StateSize]) {
  Line header;
  header.text("columns ");
  header.text(model);
  header.text(" sample t");
  for (const char* column : columns) {
    header.text(" ");
    header.text(column);
  }
  write_line(header);

  Scalar state[StateSize];
  sampled::initial_state(state);
  const Scalar period = Scalar(observations::period);
  bool ok = true;
  for (int k = 0;; ++k) {
    const Scalar t = Scalar(k) * period;
    Line line;
    line.text("traj ");
    line.text(model);
    line.text(" ");
    line.integer(k);
    line.text(" ");
    line.number(static_cast<double>(t));
    for (std::size_t i = 0; i < StateSize; ++i) {
      line.text(" ");
      line.number(static_cast<double>(state[i]));
      ok = ok && finite(state[i]);
    }
    write_line(line);
    if (k == observations::samples) break;
    const Scalar y[1] = {Scalar(observations::allahyani_date_example1_gamma1_y[k])};
    ok = pfgen_embedded_advance_allahyani_date_example1_gamma1(state, t, y) && ok;
  }
  return ok;
}

}  // namespace

int main() {
  const char* const quadratic_columns[quadratic::state_size] = {"m1", "P11"};
  const char* const partial_columns[partial::state_size] = {"m1", "m2", "P11", "P12", "P22"};

  const bool quadratic_ok = run<quadratic::Scalar>(
      "basin2006_quadratic", quadratic_columns, observations::basin2006_quadratic_dy,
      [](quadratic::Scalar* state) { quadratic::initial_state(state); }, pfgen_embedded_step_basin2006_quadratic);
  const bool partial_ok = run<partial::Scalar>(
      "basin_skliar_partial", partial_columns, observations::basin_skliar_partial_dy,
      [](partial::Scalar* state) { partial::initial_state(state); }, pfgen_embedded_step_basin_skliar_partial);
  const char* const sampled_columns[sampled::state_size] = {"m1", "P11"};
  const bool sampled_ok = run_sampled<sampled::Scalar>("allahyani_date_example1_gamma1", sampled_columns);
  // The delayed filter: its history (delay_steps x (m, x*)) lives here, sized at compile time.
  static_assert(delayed::delay_steps == 50 && delayed::history_size == 100, "delay_linear: h = 0.5 = 50 steps of 0.01");
  static delayed::Scalar history[delayed::history_size];
  std::size_t step_index = 0;
  const char* const delayed_columns[delayed::state_size] = {"m1", "P11", "xs1"};
  const bool delayed_ok = run<delayed::Scalar>(
      "delay_linear", delayed_columns, observations::delay_linear_dy,
      [](delayed::Scalar* state) {
        delayed::initial_state(state);
        delayed::initial_history(state, history);
      },
      [&step_index](delayed::Scalar* state, delayed::Scalar, delayed::Scalar, const delayed::Scalar* dy) {
        pfgen_embedded_step_delay_linear(state, history, step_index++, dy);
      });

  Line info;
  info.text("info scalar_bytes ");
  info.integer(static_cast<long>(sizeof(quadratic::Scalar)));
#if defined(PFGEN_EMBEDDED_TARGET)
  info.text(" stack_reserved ");
  info.integer(static_cast<long>(pfgen_embedded::board::stack_reserved_bytes()));
  info.text(" stack_peak ");
  info.integer(static_cast<long>(pfgen_embedded::board::stack_peak_bytes()));
#endif
  write_line(info);

  Line end;
  const bool all_ok = quadratic_ok && partial_ok && sampled_ok && delayed_ok;
  end.text(all_ok ? "end ok" : "end FAIL: a filter state is not finite or an update refused its sample");
  write_line(end);
  return all_ok ? 0 : 1;
}
