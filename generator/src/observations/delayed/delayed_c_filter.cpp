// A filter for delayed observations in C99 (its templates/c/delayed_filter.h.tmpl and .c.tmpl): its
// history an array the caller owns, the parts of the .c that depend on the delay in steps and on
// x* written for the values this filter has.
#include "pfgen/codegen/backends/c/c_filter_writer.hpp"
#include "pfgen/observations/continuous/continuous_code.hpp"
#include "pfgen/observations/delayed/delayed_code.hpp"

namespace pfgen::codegen {
namespace {

// The parts of a delayed filter's .c that depend on its delay in steps and on x*, written for the
// values it has (so that no branch is always true or always false, which -Wextra reports).
struct DelayedParts {
  std::string initial_history, delayed_inputs, history_store;
};

DelayedParts delayed_parts(const std::string& P, const std::string& scalar, std::size_t delay_steps, bool x_star,
                           const CEmitter& emitter) {
  DelayedParts parts;
  const std::string n = P + "_n", width = P + "_history_width", x_star_offset = "(" + P + "_state_size - " + n + ")";
  const std::string zero = emitter.literal(0), one = emitter.literal(1);
  if (delay_steps == 0) {
    parts.initial_history = "  (void)state;\n  (void)history;\n";
    parts.delayed_inputs = "  (void)history;\n  (void)start;\n  (void)k;\n  (void)offset;\n"
                           "  for (size_t i = 0; i < " + n + "; ++i) delayed[i] = now[i];\n";
    if (x_star) parts.delayed_inputs += "  for (size_t i = 0; i < " + n + "; ++i) delayed[" + n + " + i] = " + one + ";\n";
    parts.history_store = "  (void)history;\n";
    return parts;
  }
  const std::string entry = "i < " + n + " ? state[i] : state[" + P + "_state_size - " + n + " + (i - " + n + ")]";
  parts.initial_history = "  for (size_t slot = 0; slot < " + P + "_delay_steps; ++slot)\n"
                          "    for (size_t i = 0; i < " + width + "; ++i)\n"
                          "      history[slot * " + width + " + i] = " + entry + ";\n";
  std::string& d = parts.delayed_inputs;
  d = "  const " + scalar + "* m_past = history + ((k + offset) % " + P + "_delay_steps) * " + width + ";\n";
  if (x_star) d += "  const " + scalar + "* x_star_past = m_past + " + n + ";\n";
  if (delay_steps == 1) {
    d += "  if (offset == 1) {\n    m_past = start;\n";
    if (x_star) d += "    x_star_past = start + " + x_star_offset + ";\n";
    d += "  }\n";
  } else {
    d += "  (void)start;\n";
  }
  d += "  for (size_t i = 0; i < " + n + "; ++i) delayed[i] = m_past[i];\n";
  if (x_star) {
    d += "  {\n    const " + scalar + "* x_star_now = now + " + x_star_offset + ";\n"
         "    for (size_t i = 0; i < " + n + "; ++i) {\n"
         "      if (k < " + P + "_delay_steps || x_star_now[i] == " + zero + ")\n"
         "        delayed[" + n + " + i] = " + zero + ";\n"
         "      else\n"
         "        delayed[" + n + " + i] = x_star_past[i] / x_star_now[i];\n    }\n  }\n";
  } else {
    d += "  (void)now;\n";
  }
  parts.history_store = "  {\n    " + scalar + "* slot = history + (k % " + P + "_delay_steps) * " + width + ";\n"
                        "    for (size_t i = 0; i < " + width + "; ++i) slot[i] = " + entry + ";\n  }\n";
  return parts;
}

}  // namespace

GeneratedFilter DelayedCode::c_filter(const Model& model, const FilterEquations& eq,
                                      const CodegenOptions& options) const {
  const DelaySteps steps = filter_delay_steps(eq, options);
  CFilterWriter w(model, eq, options);
  const std::size_t n = eq.n();
  const bool x_star = eq.uses_x_star();
  const ContinuousFunctions f = continuous_functions(model, eq, options, w.names, w.emitter);
  w.result.functions = f.stats();
  const std::string extra = delay_banner_line(eq, steps, *options.grid_step);
  std::map<std::string, std::string> values = w.common_values(eq.p, eq.variables.count() + (x_star ? n : 0), extra);
  add_rate_function_values(values, f, w.names, eq, true);
  const std::size_t width = x_star ? 2 * n : n, history = steps.steps * width;
  const DelayedParts parts = delayed_parts(w.prefix, w.emitter.scalar_type(), steps.steps, x_star, w.emitter);
  values.insert({{"delayed", w.names.delayed},
                 {"history_what", x_star ? " and x*" : ""},
                 {"prehistory_x_star", x_star ? " and x*(s) = m0" : ""},
                 {"out_x_star", x_star ? ", x* drift f(x*, t)" : ""},
                 {"initial_x_star", x_star ? ", and x*(0) = m0" : ""}});
  w.write("delayed_filter", values,
          {{"state_x_star",
            x_star ? "\n// then x* (n entries), the noise-free solution dx*/dt = f(x*, t) from x*(0) = m0." : ""},
           {"delay_steps", std::to_string(steps.steps)},
           {"uses_x_star", x_star ? "1" : "0"},
           {"history_width", std::to_string(width)},
           {"history_size", std::to_string(history)},
           {"history_array_size", std::to_string(history > 0 ? history : 1)},  // C has no empty array
           {"delayed_size", std::to_string(x_star ? 2 * n : n)}},
          {{"delay", w.emitter.literal(GiNaC::numeric(eq.delay.to_double()))},
           {"dt", w.emitter.literal(GiNaC::numeric(*options.grid_step))},
           {"initial_body", w.emitter.block(initial_state_statements(initial_values(model, eq.variables, x_star)))},
           {"initial_history_body", parts.initial_history},
           {"delayed_inputs_body", parts.delayed_inputs},
           {"history_store", parts.history_store}});
  return w.result;
}

std::vector<std::string> DelayedCode::c_templates() const {
  return {"c/delayed_filter.h.tmpl", "c/delayed_filter.c.tmpl"};
}

}  // namespace pfgen::codegen
