#include "pfgen/codegen/truth_codegen.hpp"

#include <vector>

#include "pfgen/algebra/polynomial.hpp"
#include "pfgen/codegen/cpp_emitter.hpp"
#include "pfgen/codegen/graph_builder.hpp"

namespace pfgen::codegen {
namespace {

// One graph for all outputs of a function, so subexpressions shared between entries (the
// powers of x in f and in g, sin(t)) are computed once; outputs are written target[k].
std::string shared_body(const Model& model, const std::vector<Polynomial>& outputs, const std::string& target) {
  ExpressionGraph graph;
  GraphBuilder builder(graph, model, model.n(), "x");
  std::vector<std::size_t> roots;
  for (const auto& p : outputs) roots.push_back(builder.polynomial(p));
  return CppEmitter(ScalarMode::Double).shared_body(graph, roots, target);
}

std::vector<Polynomial> in_states(const Model& model, const ExMatrix& rows) {
  std::vector<Polynomial> out;
  for (const auto& row : rows)
    for (const auto& e : row) out.push_back(Polynomial::from_ex(e, model.states));
  return out;
}

// A function of (t, x) at the default parameters. Unused arguments are cast to void so that
// the plugin compiles without warnings whatever the model leaves out.
std::string function(const std::string& signature, const std::string& body) {
  return "inline void " + signature + " {\n  const Params params{};\n  (void)params;\n  (void)t;\n  (void)x;\n" +
         body + "}\n\n";
}

// Each matrix of the observation in its own block: the three are separate outputs, and blocks
// keep their temporaries apart.
std::string observation_function(const Model& model) {
  const ContinuousObservation& o = model.observation.continuous();
  std::string body;
  const std::pair<const char*, std::vector<Polynomial>> parts[] = {
      {"A0", in_states(model, ExMatrix{o.A0})}, {"A", in_states(model, o.A)}, {"B", in_states(model, o.B)}};
  for (const auto& [target, outputs] : parts) {
    std::string block = shared_body(model, outputs, target);
    body += "  {\n";
    for (std::size_t start = 0; start < block.size();) {
      std::size_t end = block.find('\n', start);
      body += "  " + block.substr(start, end - start + 1);
      start = end + 1;
    }
    body += "  }\n";
  }
  return "inline void observation(double t, double* A0, double* A, double* B) {\n"
         "  const Params params{};\n  (void)params;\n  (void)t;\n" +
         body + "}\n\n";
}

bool all_zero(const ExMatrix& m) {
  for (const auto& row : m)
    for (const auto& e : row)
      if (!e.expand().is_zero()) return false;
  return true;
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
  const ContinuousObservation& observation = model.observation.continuous();
  code.r = observation.B.empty() ? 0 : observation.B.front().size();
  code.diffusion_is_zero = d.g ? all_zero(*d.g) : all_zero(d.G);
  code.diffusion_is_covariance = !code.diffusion_is_zero && !d.g;
  code.q = code.diffusion_is_zero ? 0 : d.g ? d.g->front().size() : code.n;
  code.observation_is_constant = !depends_on_time(model, ExMatrix{observation.A0}) &&
                                 !depends_on_time(model, observation.A) && !depends_on_time(model, observation.B);
  code.has_initial_state = model.initial && !model.initial->x0.empty();

  CppEmitter emitter(ScalarMode::Double);
  std::string& out = code.definitions;
  out += "using Scalar = double;\n\n// The model's parameters at their defaults.\nstruct Params {\n";
  for (const auto& p : model.parameters) out += "  Scalar " + p.name + " = " + emitter.literal(p.default_value) + ";\n";
  out += "};\n\n";

  out += function("drift(double t, const double* x, double* f)", shared_body(model, in_states(model, {model.drift}), "f"));
  if (!code.diffusion_is_zero && d.g) {
    const std::vector<Polynomial> g = in_states(model, *d.g);
    out += function("diffusion(double t, const double* x, double* g)", shared_body(model, g, "g"));
    std::vector<Polynomial> dg;  // [(i*q + j)*n + l]: g is row-major, so entry k = i*q + j
    for (const auto& entry : g)
      for (std::size_t l = 0; l < code.n; ++l) dg.push_back(entry.derivative(static_cast<std::uint32_t>(l)));
    out += function("diffusion_jacobian(double t, const double* x, double* dg)", shared_body(model, dg, "dg"));
  }
  if (code.diffusion_is_covariance)
    out += function("diffusion_covariance(double t, const double* x, double* G)",
                    shared_body(model, in_states(model, d.G), "G"));
  out += observation_function(model);
  if (code.has_initial_state) {
    out += "inline void initial_state(double* x0) {\n";
    for (std::size_t i = 0; i < code.n; ++i)
      out += "  x0[" + std::to_string(i) + "] = " + emitter.literal(model.initial->x0[i]) + ";\n";
    out += "}\n\n";
  }
  return code;
}

}  // namespace pfgen::codegen
