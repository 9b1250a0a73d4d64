// The polynomial observation in a simulation plugin: the truth's observation(t, A0, A, B) with
// A0 = 0 and A = 0 and its observation_rate(t, x, h), the nonlinear h; the filters behind the
// ABI's step signature and their table, as the continuous observation's. A linear h is the
// continuous observation's part, written A0 + A x.
#include "pfgen/codegen/backends/cpp/simulation_plugin.hpp"
#include "pfgen/codegen/backends/cpp/truth_codegen.hpp"
#include "pfgen/codegen/backends/cpp/truth_functions.hpp"
#include "pfgen/observations/continuous/continuous_code.hpp"
#include "pfgen/observations/polynomial/polynomial_code.hpp"
#include "pfgen/observations/polynomial/polynomial_observation.hpp"

namespace pfgen::codegen {

void PolynomialCode::truth_observation(const Model& model, TruthNames& names, TruthCode& code) const {
  if (const std::optional<ContinuousObservation> linear = linear_form(model))
    return rate_truth_observation(model, *linear, names, code);
  const PolynomialObservation& observation = model.observation.polynomial();
  const std::size_t p = observation.h.size();
  code.r = observation.B.empty() ? 0 : observation.B.front().size();
  // The runtime reads B once when it does not depend on t; h(t, x) is called at every step anyway.
  code.observation_is_constant = !depends_on_time(model, observation.B);
  const ExMatrix zero_A0{ExVector(p, GiNaC::ex(0))}, zero_A(p, ExVector(model.n(), GiNaC::ex(0)));
  code.definitions += matrices_function(model, names, "observation", {{"A0", zero_A0}, {"A", zero_A}, {"B", observation.B}});
  code.definitions += state_function(model, names, "observation_rate", "h", observation_polynomials(model));
  code.definitions += observation_noise_function(model, names, observation.B);
}

void PolynomialCode::plugin_options(const Model& model, std::optional<double> grid_step, CodegenOptions& options) const {
  continuous_observation_code().plugin_options(model, grid_step, options);
}

std::string PolynomialCode::plugin_wrappers(const Model& model, const std::vector<std::string>& names,
                                            const std::vector<bool>& in_lanes) const {
  return continuous_observation_code().plugin_wrappers(model, names, in_lanes);
}

std::map<std::string, std::string> PolynomialCode::plugin_table(const Model& model, const std::vector<std::string>& names,
                                                                const std::vector<std::string>& labels,
                                                                std::optional<double> grid_step,
                                                                const std::vector<bool>& in_lanes) const {
  std::map<std::string, std::string> table =
      continuous_observation_code().plugin_table(model, names, labels, grid_step, in_lanes);
  if (!written_linear(model)) table["observation_rate"] = "&pfgen_simulation::truth::observation_rate";
  return table;
}

}  // namespace pfgen::codegen
