#include "pfgen/codegen/backends/cpp/truth_codegen.hpp"

#include <vector>

#include "pfgen/codegen/backends/cpp/cpp_emitter.hpp"
#include "pfgen/codegen/backends/cpp/truth_functions.hpp"
#include "pfgen/codegen/observation_code.hpp"
#include "pfgen/model/simulation_rules.hpp"

namespace pfgen::codegen {

TruthCode generate_truth_code(const Model& model) {
  const Diffusion& d = model.diffusion;
  TruthCode code;
  code.n = model.n();
  code.p = model.p();
  code.diffusion_is_zero = diffusion_is_zero(model);
  code.diffusion_is_covariance = !code.diffusion_is_zero && !d.g;
  code.q = code.diffusion_is_zero ? 0 : d.g ? d.g->front().size() : code.n;
  code.has_initial_state = model.initial && !model.initial->x0.empty();

  CppEmitter emitter(ScalarMode::Double);
  std::string& out = code.definitions;
  out += "using Scalar = double;\n\n// The model's parameters at their defaults.\nstruct Params {\n";
  std::string initializers;
  for (const auto& p : model.parameters) {
    out += "  Scalar " + p.name + " = " + emitter.literal(p.default_value) + ";\n";
    initializers += (initializers.empty() ? " : " : ", ") + p.name + "(values[" +
                    std::to_string(&p - model.parameters.data()) + "])";
  }
  // Each parameter from values[k], in the model's order: the functions at parameter values given
  // in the call (observation_noise). A constructor, so that no model name can clash with it.
  out += "  Params() = default;\n  explicit Params(const double* values)" + initializers + " {" +
         (initializers.empty() ? " (void)values; " : "") + "}\n";
  out += "};\n\n";

  TruthNames names(model);
  out += state_function(model, names, "drift", "f", in_states(model, {model.drift}));
  if (!code.diffusion_is_zero && d.g) {
    const std::vector<Polynomial> g = in_states(model, *d.g);
    out += state_function(model, names, "diffusion", "g", g);
    std::vector<Polynomial> dg;  // [(i*q + j)*n + l]: g is row-major, so entry k = i*q + j
    for (const auto& entry : g)
      for (std::size_t l = 0; l < code.n; ++l) dg.push_back(entry.derivative(static_cast<std::uint32_t>(l)));
    out += state_function(model, names, "diffusion_jacobian", "dg", dg);
  }
  if (code.diffusion_is_covariance)
    out += state_function(model, names, "diffusion_covariance", "G", in_states(model, d.G));
  observation_code(model.observation.kind()).truth_observation(model, names, code);
  if (code.has_initial_state) {
    out += "inline void initial_state(double* x0) {\n";
    for (std::size_t i = 0; i < code.n; ++i)
      out += "  x0[" + std::to_string(i) + "] = " + emitter.literal(model.initial->x0[i]) + ";\n";
    out += "}\n\n";
  }
  return code;
}

}  // namespace pfgen::codegen
