#include "pfgen/codegen/backends/cpp/truth_codegen.hpp"

#include <vector>

#include "pfgen/algebra/polynomial.hpp"
#include "pfgen/codegen/backends/cpp/cpp_emitter.hpp"
#include "pfgen/codegen/local_names.hpp"
#include "pfgen/codegen/graph_builder.hpp"
#include "pfgen/model/simulation_rules.hpp"

namespace pfgen::codegen {
namespace {

// The truth functions' arguments, their local `params` and their temporaries, named clear of the
// model's states, parameters and time (local_names.hpp); the time argument has the model's name.
struct TruthNames {
  explicit TruthNames(const Model& model)
      : local(truth_input_names(model)),
        time(model.time.get_name()),
        x(local.take("x")),
        params(local.take("params")),
        temporary_prefix(local.temporary_prefix()) {}
  // An output argument: `preferred` unless the model or an earlier argument took it.
  std::string take(const std::string& preferred) { return local.take(preferred); }

  LocalNames local;  // first: the names below are taken from it
  const std::string time, x, params, temporary_prefix;
};

std::vector<Polynomial> in_states(const Model& model, const ExMatrix& rows) {
  std::vector<Polynomial> out;
  for (const auto& row : rows)
    for (const auto& e : row) out.push_back(Polynomial::from_ex(e, model.states));
  return out;
}

// One function of (t, x) at the default parameters, all outputs in one graph so that
// subexpressions shared between entries (the powers of x in f and in g, sin(t)) are computed
// once; output k is written to destinations[k]. The body first names each input it reads
// (states, then parameters, as in the model), and casts the arguments it does not read to void
// so that the plugin compiles without warnings whatever the model leaves out.
std::string function(const Model& model, TruthNames& names, const std::string& signature, bool reads_x,
                     const std::vector<Polynomial>& outputs, const std::vector<std::string>& destinations) {
  ExpressionGraph graph;
  GraphBuilder builder(graph, model, model.state_names, names.x, names.params);
  std::vector<std::size_t> roots;
  for (const auto& p : outputs) roots.push_back(builder.polynomial(p));
  const CppEmitter emitter(ScalarMode::Double, names.temporary_prefix);
  const InputUse use = builder.uses(roots);
  std::string body;
  if (use.parameters) body += "  const Params " + names.params + "{};\n";
  if (!use.time) body += "  (void)" + names.time + ";\n";
  if (reads_x && !use.variables) body += "  (void)" + names.x + ";\n";
  body += emitter.input_declarations(graph, roots, builder.declaration_order());
  body += emitter.shared_body(graph, roots, destinations);
  return "inline void " + signature + " {\n" + body + "}\n\n";
}

// A function of (t, x) writing output k to target[k].
std::string state_function(const Model& model, TruthNames& names, const std::string& function_name,
                           const std::string& preferred_target, const std::vector<Polynomial>& outputs) {
  const std::string target = names.take(preferred_target);
  std::vector<std::string> destinations;
  for (std::size_t k = 0; k < outputs.size(); ++k) destinations.push_back(target + "[" + std::to_string(k) + "]");
  const std::string signature =
      function_name + "(double " + names.time + ", const double* " + names.x + ", double* " + target + ")";
  return function(model, names, signature, true, outputs, destinations);
}

// A0, A and B in one function of t: entry k of A0, then of A, then of B. A delayed observation
// has the same coefficients; the runtime applies them to x(t - h).
std::string observation_function(const Model& model, TruthNames& names) {
  const ContinuousObservation& o = model.observation.rate();
  std::vector<Polynomial> outputs;
  std::vector<std::string> destinations;
  std::string signature = "observation(double " + names.time;
  const std::pair<const char*, std::vector<Polynomial>> parts[] = {
      {"A0", in_states(model, ExMatrix{o.A0})}, {"A", in_states(model, o.A)}, {"B", in_states(model, o.B)}};
  for (const auto& [preferred, part] : parts) {
    const std::string target = names.take(preferred);
    signature += ", double* " + target;
    for (std::size_t k = 0; k < part.size(); ++k) {
      outputs.push_back(part[k]);
      destinations.push_back(target + "[" + std::to_string(k) + "]");
    }
  }
  return function(model, names, signature + ")", false, outputs, destinations);
}

// C0, C and Uv of a sampled observation in one function of t: entry k of C0, then of C, then of Uv.
std::string sampled_observation_function(const Model& model, TruthNames& names) {
  const SampledObservation& o = model.observation.sampled();
  std::vector<Polynomial> outputs;
  std::vector<std::string> destinations;
  std::string signature = "sampled_observation(double " + names.time;
  const std::pair<const char*, std::vector<Polynomial>> parts[] = {
      {"C0", in_states(model, ExMatrix{o.C0})}, {"C", in_states(model, o.C)}, {"Uv", in_states(model, o.Uv)}};
  for (const auto& [preferred, part] : parts) {
    const std::string target = names.take(preferred);
    signature += ", double* " + target;
    for (std::size_t k = 0; k < part.size(); ++k) {
      outputs.push_back(part[k]);
      destinations.push_back(target + "[" + std::to_string(k) + "]");
    }
  }
  return function(model, names, signature + ")", false, outputs, destinations);
}

bool depends_on_time(const Model& model, const ExMatrix& m) {
  for (const auto& row : m)
    for (const auto& e : row)
      if (e.has(model.time)) return true;
  return false;
}

}  // namespace

TruthCode generate_truth_code(const Model& model) {
  const Diffusion& d = model.diffusion;
  TruthCode code;
  code.n = model.n();
  code.p = model.p();
  code.sampled = model.observation.is_sampled();
  if (code.sampled) {
    const SampledObservation& sampled = model.observation.sampled();
    code.r = sampled.Uv.empty() ? 0 : sampled.Uv.front().size();
    code.period = sampled.period.to_double();
  } else {
    const ContinuousObservation& observation = model.observation.rate();
    code.delay = model.observation.delay().to_double();
    code.r = observation.B.empty() ? 0 : observation.B.front().size();
    code.observation_is_constant = !depends_on_time(model, ExMatrix{observation.A0}) &&
                                   !depends_on_time(model, observation.A) && !depends_on_time(model, observation.B);
  }
  code.diffusion_is_zero = diffusion_is_zero(model);
  code.diffusion_is_covariance = !code.diffusion_is_zero && !d.g;
  code.q = code.diffusion_is_zero ? 0 : d.g ? d.g->front().size() : code.n;
  code.has_initial_state = model.initial && !model.initial->x0.empty();

  CppEmitter emitter(ScalarMode::Double);
  std::string& out = code.definitions;
  out += "using Scalar = double;\n\n// The model's parameters at their defaults.\nstruct Params {\n";
  for (const auto& p : model.parameters) out += "  Scalar " + p.name + " = " + emitter.literal(p.default_value) + ";\n";
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
  out += code.sampled ? sampled_observation_function(model, names) : observation_function(model, names);
  if (code.has_initial_state) {
    out += "inline void initial_state(double* x0) {\n";
    for (std::size_t i = 0; i < code.n; ++i)
      out += "  x0[" + std::to_string(i) + "] = " + emitter.literal(model.initial->x0[i]) + ";\n";
    out += "}\n\n";
  }
  return code;
}

}  // namespace pfgen::codegen
