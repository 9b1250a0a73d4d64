// The continuous module's code generation: its filters' functions and file, language-neutral, and its part.
#include "pfgen/observations/continuous/continuous_code.hpp"

#include "pfgen/codegen/heun_step.hpp"

namespace pfgen::codegen {
namespace {

// increment()'s start in four parts, which each language's template places in its own order (C declares
// the views before the call, C++ after it, Rust the innovation's first, splitting `all` there): the array
// `all`, which rates() writes whole, [drift, K, h]; the call; the view K; and the view `innovation` of
// its h, which becomes dy - h dt.
void add_increment_start(FilterFile& file) {
  const ir::Expr n = ir::dimension("n"), p = ir::dimension("p"), state_size = ir::dimension("state_size");
  const ir::Expr h_offset = ir::add(state_size, ir::mul(n, p));
  file.blocks.emplace("increment_array",
                      ir::Block{ir::local_array_written_by("all", ir::Type::Scalar, ir::add(h_offset, p), "rates()")});
  file.blocks.emplace("increment_call",
                      ir::Block{state_function_call("rates", ir::name("t"), ir::name("state"), "all")});
  file.blocks.emplace("gain_view", ir::Block{ir::local_view("K", "all", state_size, ir::mul(n, p))});
  file.blocks.emplace("innovation_view",
                      ir::Block{ir::local_tail_view("innovation", "all", h_offset, p, "h, replaced by dy - h dt")});
}

// The step's statements: increment()'s start, the innovation dy - h dt, the increment rates dt + K (dy - h dt),
// step()'s predictor and corrector and the average.
void add_step_loops(FilterFile& file, std::size_t n) {
  add_increment_start(file);
  const HeunStepLoops loops(n, file.p, file.state_size, n < kStepWrittenOutBelow);
  const ir::Expr dt = ir::name("dt");
  ir::Block increment;
  loops.innovation(increment, "innovation", dt);
  loops.scaled_rates(increment, [](const ir::Expr& i) { return ir::element("all", i); }, dt);
  loops.state_gain(increment, "K", [](const ir::Expr& r) { return ir::element("innovation", r); });
  file.blocks.emplace("increment_loops", std::move(increment));
  // step(): the increment at t and, from the predicted state, at t + dt, then their average; the
  // increments write every entry of first and second, and predicted() every entry of predicted.
  const ir::Expr t = ir::name("t"), dy = ir::name("dy"), params = ir::name("params");
  auto increment_at = [&](bool end, const ir::Expr& state, const ir::Expr& delta) {
    return ir::Block{
        ir::call_internal_function("increment", {end ? ir::add(t, dt) : t, state, dt, dy, params, delta})};
  };
  file.blocks.emplace("step_increments", loops.predictor_corrector(increment_at, true));
  file.blocks.emplace("average_loop", loops.average());
}

}  // namespace

std::vector<FunctionStats> ContinuousFunctions::stats() const {
  std::vector<FunctionStats> all = {derivatives.stats, gain.stats, observation.stats};
  if (rates) all.push_back(rates->stats);
  return all;
}

ContinuousFunctions continuous_functions(const Model& model, const FilterEquations& eq, const CodegenOptions& options,
                                         const FunctionNames& names, const StatementEmitter& emitter, bool with_rates) {
  std::vector<Polynomial> gain_outputs;
  for (const auto& row : eq.gain) gain_outputs.insert(gain_outputs.end(), row.begin(), row.end());
  ContinuousFunctions f;
  DerivativesForm rates_form = DerivativesForm::Expanded;
  f.derivatives = derivatives_code(model, eq, options, names, emitter, &rates_form);
  f.gain = function_code("gain", gain_outputs, names.K, model, eq, options, names, emitter);
  f.observation =
      function_code("predicted_observation", eq.predicted_observation, names.h, model, eq, options, names, emitter);
  if (with_rates) {
    OpCounts naive = f.derivatives.stats.naive;
    naive += f.gain.stats.naive;
    naive += f.observation.stats.naive;
    f.rates = rates_code(model, eq, options, names, emitter, rates_form, naive);
  }
  return f;
}

std::string gain_meaning(const FilterEquations& eq) {
  if (eq.is_user_filter()) return "as given in the model file";
  if (eq.uses_x_star()) return "P Phi*^T A^T (B B^T)^-1, Phi* = diag(phi)";
  return "P A^T (B B^T)^-1";
}

FilterFile ContinuousCode::filter_file(const Model& model, const FilterEquations& eq, const CodegenOptions& options,
                                       const FunctionNames& names, const StatementEmitter& emitter) const {
  // A filter whose covariance has a dy term of its own (a moment filter: its third moments enter dP's) steps as a
  // nonlinear h's filters do, with the Ito-Stratonovich correction.
  if (!eq.P_gain.empty()) return polynomial_observation_code().filter_file(model, eq, options, names, emitter);
  FilterFile file;
  file.layout = "filter";
  file.p = eq.p;
  file.state_size = eq.variables.count();
  add_rate_functions(file, continuous_functions(model, eq, options, names, emitter, true), names, eq);
  file.blocks.emplace("initial_body", initial_state_statements(initial_values(model, eq.variables)));
  add_step_loops(file, eq.n());
  return file;
}

void add_rate_functions(FilterFile& file, ContinuousFunctions functions, const FunctionNames& names,
                        const FilterEquations& eq) {
  file.stats = functions.stats();
  file.add_function("derivatives", std::move(functions.derivatives));
  file.add_function("gain", std::move(functions.gain));
  file.add_function("observation", std::move(functions.observation));
  if (functions.rates) file.add_function("rates", std::move(*functions.rates));
  file.words.insert({{"K", names.K}, {"h", names.h}, {"gain_meaning", gain_meaning(eq)}});
}

const ObservationCode& continuous_observation_code() {
  static const ContinuousCode part;
  return part;
}

}  // namespace pfgen::codegen
