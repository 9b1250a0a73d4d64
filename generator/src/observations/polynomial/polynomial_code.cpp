// The polynomial module's code generation: its filters' functions and file, language-neutral, and its part.
// A linear h is the continuous observation: observation_code gives it the continuous module.
#include "pfgen/observations/polynomial/polynomial_code.hpp"

#include "pfgen/codegen/heun_step.hpp"
#include "pfgen/observations/polynomial/ito_stratonovich_correction.hpp"
#include "pfgen/observations/polynomial/polynomial_observation.hpp"

namespace pfgen::codegen {
namespace {

// increment()'s arrays and the calls that fill them: the rates, c, K, L and yhat at (t, state), and the
// innovation's array. C declares each array on its own line, C++ those of one length together.
ir::Block increment_inputs() {
  const ir::Expr t = ir::name("t"), state = ir::name("state");
  const ir::Expr n = ir::dimension("n"), p = ir::dimension("p"), state_size = ir::dimension("state_size");
  ir::Block block = {
      ir::local_arrays_apart({"rates", "correction"}, ir::Type::Scalar, state_size),
      ir::local_arrays({"K"}, ir::Type::Scalar, ir::mul(n, p)),
      ir::local_arrays({"L"}, ir::Type::Scalar, ir::mul(ir::grouped(ir::sub(state_size, n)), p)),
      ir::local_arrays_apart({"yhat", "innovation"}, ir::Type::Scalar, p),
  };
  for (const auto& [function, array] : {std::pair<const char*, const char*>{"derivatives", "rates"},
                                        {"gain", "K"},
                                        {"covariance_gain", "L"},
                                        {"predicted_observation", "yhat"},
                                        {"stratonovich_correction", "correction"}})
    block.push_back(state_function_call(function, t, state, array));
  return block;
}

// The step's statements: increment()'s inputs, the innovation dy - yhat dt, the increment (rates - c) dt +
// [K; L] (dy - yhat dt), step()'s predictor and corrector and the average. Loops at every n (the written-out
// form was measured on the continuous filter's step only).
void add_step_loops(FilterFile& file, std::size_t n) {
  const HeunStepLoops loops(n, file.p, file.state_size, false);
  const ir::Expr dt = ir::name("dt");
  auto innovation = [](const ir::Expr& r) { return ir::element("innovation", r); };
  ir::Block increment = increment_inputs();
  loops.innovation(increment, "yhat", dt);
  loops.scaled_rates(
      increment,
      [](const ir::Expr& i) { return ir::grouped(ir::sub(ir::element("rates", i), ir::element("correction", i))); },
      dt);
  loops.state_gain(increment, "K", innovation);
  loops.covariance_gain(increment, "L", innovation);
  file.blocks.emplace("increment_body", std::move(increment));
  // step(): the increment at t and, from the predicted state, at t + dt, then their average.
  const ir::Expr t = ir::name("t"), dy = ir::name("dy"), params = ir::name("params");
  file.blocks.emplace("step_increments",
                      loops.predictor_corrector([&](bool end, const ir::Expr& state, const ir::Expr& delta) {
                        return ir::Block{ir::call_internal_function(
                            "increment", {end ? ir::add(t, dt) : t, state, dt, dy, params, delta})};
                      }));
  file.blocks.emplace("average_loop", loops.average());
}

}  // namespace

std::vector<FunctionStats> PolynomialFunctions::stats() const {
  std::vector<FunctionStats> all = {derivatives.stats, gain.stats, covariance_gain.stats, observation.stats,
                                    correction.stats};
  if (realisability) all.push_back(realisability->stats);
  return all;
}

PolynomialFunctions polynomial_functions(const Model& model, const FilterEquations& eq, const CodegenOptions& options,
                                         const FunctionNames& names, const StatementEmitter& emitter) {
  const FilterVariables& vars = eq.variables;
  const std::size_t n = eq.n(), p = eq.p, count = vars.count();
  // sigma, one row per filter variable: K's rows for m, L's (zero for the extended and sigma-point
  // kinds, whose P has no dnu term) for P's upper triangle.
  std::vector<std::vector<Polynomial>> noise(count, std::vector<Polynomial>(p));
  std::vector<Polynomial> gain, covariance_gain;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t r = 0; r < p; ++r) {
      noise[vars.m(i)][r] = eq.gain[i][r];
      gain.push_back(eq.gain[i][r]);
    }
  // Then a moment filter's central moments above P, each with its own dnu term.
  const std::size_t P_entries = n * (n + 1) / 2;
  for (std::size_t u = 0; u < count - n; ++u)
    for (std::size_t r = 0; r < p; ++r) {
      if (u < P_entries && !eq.P_gain.empty()) noise[n + u][r] = eq.P_gain[u][r];
      if (u >= P_entries && !eq.higher_gain.empty()) noise[n + u][r] = eq.higher_gain[u - P_entries][r];
      covariance_gain.push_back(noise[n + u][r]);
    }
  const std::vector<Polynomial> correction =
      ito_stratonovich_correction(noise, model.observation.rate().noise(), vars);

  PolynomialFunctions f;
  f.derivatives = derivatives_code(model, eq, options, names, emitter);
  f.gain = function_code("gain", gain, names.K, model, eq, options, names, emitter);
  f.covariance_gain = function_code("covariance_gain", covariance_gain, names.L, model, eq, options, names, emitter);
  f.observation =
      function_code("predicted_observation", eq.predicted_observation, names.h, model, eq, options, names, emitter);
  f.correction = function_code("stratonovich_correction", correction, names.c, model, eq, options, names, emitter);
  f.realisability = realisability_code(model, eq, options, names, emitter);
  return f;
}

FilterFile PolynomialCode::filter_file(const Model& model, const FilterEquations& eq, const CodegenOptions& options,
                                       const FunctionNames& names, const StatementEmitter& emitter) const {
  PolynomialFunctions f = polynomial_functions(model, eq, options, names, emitter);
  FilterFile file;
  file.layout = "polynomial_filter";
  file.p = eq.p;
  file.state_size = eq.variables.count();
  file.stats = f.stats();
  file.add_function("derivatives", std::move(f.derivatives));
  file.add_function("gain", std::move(f.gain));
  file.add_function("covariance_gain", std::move(f.covariance_gain));
  file.add_function("observation", std::move(f.observation));
  file.add_function("correction", std::move(f.correction));
  file.words = {{"K", names.K}, {"L", names.L}, {"h", names.h}, {"c", names.c}};
  add_realisability_function(file, eq, std::move(f.realisability));
  file.blocks.emplace("initial_body", initial_state_statements(initial_values(model, eq.variables)));
  add_step_loops(file, eq.n());
  return file;
}

const ObservationCode& polynomial_observation_code() {
  static const PolynomialCode part;
  return part;
}

}  // namespace pfgen::codegen
