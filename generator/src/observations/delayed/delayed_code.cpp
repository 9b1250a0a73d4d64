// The delayed module's code generation: the grid its filters step on, their file (language-neutral),
// and its part.
#include "pfgen/observations/delayed/delayed_code.hpp"

#include "pfgen/codegen/heun_step.hpp"
#include "pfgen/observations/continuous/continuous_code.hpp"
#include "pfgen/observations/delayed/delayed_history.hpp"
#include "pfgen_support/shortest_double.hpp"

namespace pfgen::codegen {
namespace {

// increment()'s arrays, the grid's step (`step`, the file's dt()) and the calls that fill the arrays: the
// rates, K and h at (t, state) with the delayed inputs.
ir::Block increment_inputs() {
  const ir::Expr t = ir::name("t"), state = ir::name("state"), delayed = ir::name("delayed");
  ir::Block block = {
      ir::local_arrays({"rates"}, ir::Type::Scalar, ir::dimension("state_size")),
      ir::local_arrays({"K"}, ir::Type::Scalar, ir::mul(ir::dimension("n"), ir::dimension("p"))),
      ir::local_arrays({"h"}, ir::Type::Scalar, ir::dimension("p")),
      ir::declare("step", ir::Type::Scalar, ir::file_scalar("dt")),
  };
  for (const auto& [function, array] : {std::pair<const char*, const char*>{"derivatives", "rates"},
                                        {"gain", "K"},
                                        {"predicted_observation", "h"}})
    block.push_back(state_function_call(function, t, state, array, delayed));
  return block;
}

// The time at the start of grid step k (`k_end` false) or at its end: k dt, (k + 1) dt.
ir::Expr grid_time(bool end) {
  const ir::Expr k = end ? ir::grouped(ir::add(ir::name("k"), ir::integer(1))) : ir::name("k");
  return ir::mul(ir::cast_to_scalar(k), ir::file_scalar("dt"));
}

// The step's statements: increment()'s inputs and its increment rates dt + K (dy - h dt) over the grid's
// step, step()'s times, predictor and corrector and the average. Loops at every n (the written-out form was
// measured on the continuous filter's step only).
void add_step_loops(FilterFile& file, std::size_t n) {
  const HeunStepLoops loops(n, file.p, file.state_size, false);
  const ir::Expr step = ir::name("step");
  ir::Block increment = increment_inputs();
  loops.scaled_rates(increment, [](const ir::Expr& i) { return ir::element("rates", i); }, step);
  loops.state_gain(increment, "K", [&](const ir::Expr& r) {
    return ir::grouped(ir::sub(ir::element("dy", r), ir::mul(ir::element("h", r), step)));
  });
  file.blocks.emplace("increment_body", std::move(increment));
  // step(): t_k and t_{k+1}, the delayed inputs and the increment at t_k and, from the predicted state, at t_{k+1};
  // the template stores the start state in the history before the average.
  const ir::Expr history = ir::name("history"), k = ir::name("k"), dy = ir::name("dy"), params = ir::name("params");
  ir::Block body = {ir::declare("t", ir::Type::Scalar, grid_time(false)),
                    ir::declare("t_end", ir::Type::Scalar, grid_time(true)),
                    ir::local_arrays({"delayed"}, ir::Type::Scalar, ir::dimension("delayed_size"))};
  for (ir::Statement& s : loops.predictor_corrector([&](bool end, const ir::Expr& state, const ir::Expr& delta) {
         return ir::Block{
             ir::call_internal_function("delayed_inputs", {history, ir::name("state"), state, k,
                                                           ir::integer(end ? 1 : 0), ir::local_array("delayed", true)}),
             ir::call_internal_function("increment", {ir::name(end ? "t_end" : "t"), state,
                                                      ir::local_array("delayed", false), dy, params, delta})};
       }))
    body.push_back(std::move(s));
  file.blocks.emplace("step_increments", std::move(body));
  file.blocks.emplace("average_loop", loops.average());
}

}  // namespace

DelaySteps filter_delay_steps(const FilterEquations& eq, const CodegenOptions& options) {
  if (!options.grid_step)
    throw CodegenError("filter '" + eq.name + "': a filter for delayed observations steps on a fixed grid: give --dt "
                       "(or simulation: dt in the model file)");
  const DelaySteps steps = delay_steps(eq.delay, *options.grid_step);
  if (!steps.problem.empty()) throw CodegenError("filter '" + eq.name + "': " + steps.problem);
  return steps;
}

std::string delay_banner_line(const FilterEquations& eq, const DelaySteps& steps, double grid_step) {
  return "// Delayed observations: h = " + pfgen_support::shortest_double(eq.delay.to_double()) + " = " +
         std::to_string(steps.steps) + " steps of dt = " + pfgen_support::shortest_double(grid_step) +
         "; the caller supplies dy over each step of this dt.\n";
}

FilterFile DelayedCode::filter_file(const Model& model, const FilterEquations& eq, const CodegenOptions& options,
                                    const FunctionNames& names, const StatementEmitter& emitter) const {
  const DelaySteps steps = filter_delay_steps(eq, options);
  const std::size_t n = eq.n();
  const bool x_star = eq.uses_x_star();
  FilterFile file;
  file.layout = "delayed_filter";
  file.p = eq.p;
  file.state_size = eq.variables.count() + (x_star ? n : 0);
  file.banner_extra = delay_banner_line(eq, steps, *options.grid_step);
  // No layer views the state as m and P (C++'s --eigen is ignored): it carries x* and the filter
  // keeps a history, so the file's own Filter is the interface.
  file.state_is_m_and_P = false;
  add_rate_functions(file, continuous_functions(model, eq, options, names, emitter), names, eq);
  file.blocks.emplace("initial_body", initial_state_statements(initial_values(model, eq.variables, x_star)));
  file.numbers = {{"delay", GiNaC::numeric(eq.delay.to_double())}, {"dt", GiNaC::numeric(*options.grid_step)}};
  file.flags.emplace("uses_x_star", x_star);
  const std::size_t width = x_star ? 2 * n : n, history = steps.steps * width;
  file.words.insert({{"delayed", names.delayed},
                     {"history_what", x_star ? " and x*" : ""},
                     {"prehistory_x_star", x_star ? " and x*(s) = m0" : ""},
                     {"out_x_star", x_star ? ", x* drift f(x*, t)" : ""},
                     {"initial_x_star", x_star ? ", and x*(0) = m0" : ""},
                     {"delay_steps", std::to_string(steps.steps)},
                     {"history_width", std::to_string(width)},
                     {"history_size", std::to_string(history)},
                     {"history_array_size", std::to_string(history > 0 ? history : 1)},  // C has no empty array
                     {"delayed_size", std::to_string(width)}});
  // The ring in the delay's case, and for any delay (a backend's template places one of the two).
  for (auto& [key, block] : history_statements(steps.steps, x_star)) file.blocks.emplace(key, std::move(block));
  for (auto& [key, block] : any_delay_history_statements()) file.blocks.emplace(key, std::move(block));
  file.frames.emplace("state_x_star", x_star ? "state_x_star" : "");
  add_step_loops(file, n);
  return file;
}

const ObservationCode& delayed_observation_code() {
  static const DelayedCode part;
  return part;
}

}  // namespace pfgen::codegen
