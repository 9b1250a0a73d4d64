// A filter for delayed observations in Rust (templates/rust/delayed_filter.rs.tmpl): its history
// an array the caller owns, the parts that depend on the delay in steps and on x* written for the
// values this filter has, as the C backend's (observations/delayed/delayed_c_filter.cpp).
#include "pfgen/codegen/backends/rust/rust_filter_writer.hpp"
#include "pfgen/observations/continuous/continuous_code.hpp"
#include "pfgen/observations/delayed/delayed_code.hpp"

namespace pfgen::codegen {
namespace {

struct DelayedParts {
  std::string initial_history, delayed_inputs, history_store;
};

// Written for the delay in steps and x* this filter has, so that no index is out of range for a
// zero-length history and no binding is mutable that never changes (both of which rustc reports).
DelayedParts delayed_parts(std::size_t delay_steps, bool x_star, const RustEmitter& emitter) {
  DelayedParts parts;
  const std::string zero = emitter.literal_text(0), one = emitter.literal_text(1);
  if (delay_steps == 0) {
    parts.initial_history = "    let _ = state;\n    let _ = history;\n";
    parts.delayed_inputs = "    let _ = history;\n    let _ = start;\n    let _ = k;\n    let _ = offset;\n"
                           "    for i in 0..STATES {\n        delayed[i] = now[i];\n    }\n";
    if (x_star) parts.delayed_inputs += "    for i in 0..STATES {\n        delayed[STATES + i] = " + one + ";\n    }\n";
    parts.history_store = "    let _ = history;\n";
    return parts;
  }
  const std::string entry = "if i < STATES { state[i] } else { state[STATE_SIZE - STATES + (i - STATES)] }";
  parts.initial_history = "    for slot in 0..DELAY_STEPS {\n"
                          "        for i in 0..HISTORY_WIDTH {\n"
                          "            history[slot * HISTORY_WIDTH + i] = " + entry + ";\n        }\n    }\n";
  const std::string mut = delay_steps == 1 ? "mut " : "";
  std::string& d = parts.delayed_inputs;
  d = "    let " + mut + "m_past: &[Scalar] = &history[((k + offset) % DELAY_STEPS) * HISTORY_WIDTH..];\n";
  if (x_star) d += "    let " + mut + "x_star_past: &[Scalar] = &m_past[STATES..];\n";
  if (delay_steps == 1) {
    d += "    if offset == 1 {\n        m_past = &start[..];\n";
    if (x_star) d += "        x_star_past = &start[STATE_SIZE - STATES..];\n";
    d += "    }\n";
  } else {
    d += "    let _ = start;\n";
  }
  d += "    for i in 0..STATES {\n        delayed[i] = m_past[i];\n    }\n";
  if (x_star) {
    d += "    let x_star_now = &now[STATE_SIZE - STATES..];\n"
         "    for i in 0..STATES {\n"
         "        if k < DELAY_STEPS || x_star_now[i] == " + zero + " {\n"
         "            delayed[STATES + i] = " + zero + ";\n"
         "        } else {\n"
         "            delayed[STATES + i] = x_star_past[i] / x_star_now[i];\n        }\n    }\n";
  } else {
    d += "    let _ = now;\n";
  }
  parts.history_store = "    {\n        let slot = &mut history[(k % DELAY_STEPS) * HISTORY_WIDTH..(k % DELAY_STEPS + 1) * HISTORY_WIDTH];\n"
                        "        for i in 0..HISTORY_WIDTH {\n            slot[i] = " + entry + ";\n        }\n    }\n";
  return parts;
}

}  // namespace

GeneratedFilter DelayedCode::rust_filter(const Model& model, const FilterEquations& eq,
                                              const CodegenOptions& options) const {
  const DelaySteps steps = filter_delay_steps(eq, options);
  RustFilterWriter w(model, eq, options);
  const std::size_t n = eq.n();
  const bool x_star = eq.uses_x_star();
  const ContinuousFunctions f = continuous_functions(model, eq, options, w.names, w.emitter);
  w.result.functions = f.stats();
  const std::string extra = delay_banner_line(eq, steps, *options.grid_step);
  std::map<std::string, std::string> values = w.common_values(eq.p, eq.variables.count() + (x_star ? n : 0), extra);
  RustFilterWriter::add_function(values, "derivatives", f.derivatives);
  RustFilterWriter::add_function(values, "gain", f.gain);
  RustFilterWriter::add_function(values, "observation", f.observation);
  const std::size_t width = x_star ? 2 * n : n;
  const DelayedParts parts = delayed_parts(steps.steps, x_star, w.emitter);
  values.insert({{"K", w.names.K},
                 {"h", w.names.h},
                 {"gain_meaning", gain_meaning(eq)},
                 {"delayed", w.names.delayed},
                 {"history_what", x_star ? " and x*" : ""},
                 {"prehistory_x_star", x_star ? " and x*(s) = m0" : ""},
                 {"out_x_star", x_star ? ", x* drift f(x*, t)" : ""},
                 {"initial_x_star", x_star ? ", and x*(0) = m0" : ""},
                 {"state_x_star",
                  x_star ? "\n// then x* (STATES entries), the noise-free solution dx*/dt = f(x*, t) from x*(0) = m0." : ""},
                 {"delay_steps", std::to_string(steps.steps)},
                 {"uses_x_star", x_star ? "true" : "false"},
                 {"history_width", std::to_string(width)},
                 {"history_size", std::to_string(steps.steps * width)},
                 {"delayed_size", std::to_string(x_star ? 2 * n : n)},
                 {"delay", w.emitter.literal_text(GiNaC::numeric(eq.delay.to_double()))},
                 {"dt", w.emitter.literal_text(GiNaC::numeric(*options.grid_step))},
                 {"initial_body", w.body(initial_state_statements(initial_values(model, eq.variables, x_star)))},
                 {"initial_history_body", parts.initial_history},
                 {"delayed_inputs_body", parts.delayed_inputs},
                 {"history_store", parts.history_store}});
  w.write("delayed_filter", values);
  return w.result;
}

}  // namespace pfgen::codegen
