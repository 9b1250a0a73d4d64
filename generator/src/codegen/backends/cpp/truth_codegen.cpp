#include "pfgen/codegen/backends/cpp/truth_codegen.hpp"

#include <vector>

#include "pfgen/codegen/backends/cpp/cpp_emitter.hpp"
#include "pfgen/codegen/backends/cpp/truth_functions.hpp"
#include "pfgen/model/simulation_rules.hpp"

namespace pfgen::codegen {
namespace {

// The truth's observation, composed from the axes: the rate gives the matrices' offset and linear
// part (A0 + A x as they are; for rows that are not affine, zeros and the rows' own function
// observation_rate(t, x, out)), the timing names them and the noise. Increments:
// observation(t, A0, A, B), then observation_rate's h, then observation_noise(values, t, B) at given
// parameter values (the likelihood of recorded data); observation_is_constant when A0, A and B do
// not read t. Samples: sampled_observation(t, C0, C, Uv), then observation_rate's c; the runtime
// reads their matrices where it asks (TruthCode's default).
void truth_observation(const Model& model, TruthNames& names, TruthCode& code) {
  const ObservationRate& rate = model.observation.rate();
  const ExMatrix& noise = rate.noise();
  const std::size_t p = rate.p();
  ExMatrix offset{ExVector(p, GiNaC::ex(0))}, linear(p, ExVector(model.n(), GiNaC::ex(0)));
  if (rate.affine()) {
    offset = ExMatrix{rate.affine()->A0};
    linear = rate.affine()->A;
  }
  code.r = noise.empty() ? 0 : noise.front().size();
  code.has_observation_rate = !rate.affine();
  code.observation_is_sampled = model.observation.samples().has_value();
  const char* const rate_target = code.observation_is_sampled ? "c" : "h";
  if (code.observation_is_sampled) {
    code.definitions +=
        matrices_function(model, names, "sampled_observation", {{"C0", offset}, {"C", linear}, {"Uv", noise}});
  } else {
    code.observation_is_constant =
        !depends_on_time(model, offset) && !depends_on_time(model, linear) && !depends_on_time(model, noise);
    code.definitions += matrices_function(model, names, "observation", {{"A0", offset}, {"A", linear}, {"B", noise}});
  }
  if (code.has_observation_rate)
    code.definitions += state_function(model, names, "observation_rate", rate_target, rate.polynomials(model.states));
  if (!code.observation_is_sampled)
    code.definitions += parameterised_matrices_function(model, names, "observation_noise", {{"B", noise}});
}

}  // namespace

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
  truth_observation(model, names, code);
  if (code.has_initial_state) {
    out += "inline void initial_state(double* x0) {\n";
    for (std::size_t i = 0; i < code.n; ++i)
      out += "  x0[" + std::to_string(i) + "] = " + emitter.literal(model.initial->x0[i]) + ";\n";
    out += "}\n\n";
  }
  return code;
}

}  // namespace pfgen::codegen
