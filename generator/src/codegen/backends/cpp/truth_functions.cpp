#include "pfgen/codegen/backends/cpp/truth_functions.hpp"

#include "pfgen/codegen/backends/cpp/cpp_emitter.hpp"
#include "pfgen/codegen/graph_builder.hpp"

namespace pfgen::codegen {

TruthNames::TruthNames(const Model& model)
    : local(truth_input_names(model)),
      time(model.time.get_name()),
      x(local.take("x")),
      params(local.take("params")),
      temporary_prefix(local.temporary_prefix()) {}

std::vector<Polynomial> in_states(const Model& model, const ExMatrix& rows) {
  std::vector<Polynomial> out;
  for (const auto& row : rows)
    for (const auto& e : row) out.push_back(Polynomial::from_ex(e, model.states));
  return out;
}

namespace {

// The body of a truth function; `values`: the argument holding the parameters' values, or empty
// for the model's defaults.
std::string truth_function_with(const Model& model, TruthNames& names, const std::string& signature, bool reads_x,
                                const std::vector<Polynomial>& outputs, const std::vector<std::string>& destinations,
                                const std::string& values) {
  ExpressionGraph graph;
  GraphBuilder builder(graph, model, model.state_names, names.x, names.params);
  std::vector<std::size_t> roots;
  for (const auto& p : outputs) roots.push_back(builder.polynomial(p));
  const CppEmitter emitter(ScalarMode::Double, names.temporary_prefix);
  const InputUse use = builder.uses(roots);
  std::string body;
  if (use.parameters)
    body += values.empty() ? "  const Params " + names.params + "{};\n"
                           : "  const Params " + names.params + "(" + values + ");\n";
  else if (!values.empty())
    body += "  (void)" + values + ";\n";
  if (!use.time) body += "  (void)" + names.time + ";\n";
  if (reads_x && !use.variables) body += "  (void)" + names.x + ";\n";
  body += emitter.input_declarations(graph, roots, builder.declaration_order());
  body += emitter.shared_body(graph, roots, destinations);
  return "inline void " + signature + " {\n" + body + "}\n\n";
}

// `function_name`(VALUES, t, M1, M2, ...) when `parameterised` (VALUES the parameters' values), else
// `function_name`(t, M1, M2, ...) at the defaults.
std::string matrices_function_with(const Model& model, TruthNames& names, const std::string& function_name,
                                   const std::vector<std::pair<std::string, ExMatrix>>& parts, bool parameterised) {
  std::vector<Polynomial> outputs;
  std::vector<std::string> destinations;
  const std::string values = parameterised ? names.take("values") : "";
  std::string signature = function_name + "(" + (parameterised ? "const double* " + values + ", " : "") + "double " +
                          names.time;
  for (const auto& [preferred, part] : parts) {
    const std::string target = names.take(preferred);
    signature += ", double* " + target;
    const std::vector<Polynomial> entries = in_states(model, part);
    for (std::size_t k = 0; k < entries.size(); ++k) {
      outputs.push_back(entries[k]);
      destinations.push_back(target + "[" + std::to_string(k) + "]");
    }
  }
  return truth_function_with(model, names, signature + ")", false, outputs, destinations, values);
}

}  // namespace

std::string truth_function(const Model& model, TruthNames& names, const std::string& signature, bool reads_x,
                           const std::vector<Polynomial>& outputs, const std::vector<std::string>& destinations) {
  return truth_function_with(model, names, signature, reads_x, outputs, destinations, "");
}

std::string state_function(const Model& model, TruthNames& names, const std::string& function_name,
                           const std::string& preferred_target, const std::vector<Polynomial>& outputs) {
  const std::string target = names.take(preferred_target);
  std::vector<std::string> destinations;
  for (std::size_t k = 0; k < outputs.size(); ++k) destinations.push_back(target + "[" + std::to_string(k) + "]");
  const std::string signature =
      function_name + "(double " + names.time + ", const double* " + names.x + ", double* " + target + ")";
  return truth_function(model, names, signature, true, outputs, destinations);
}

std::string matrices_function(const Model& model, TruthNames& names, const std::string& function_name,
                              const std::vector<std::pair<std::string, ExMatrix>>& parts) {
  return matrices_function_with(model, names, function_name, parts, false);
}

std::string parameterised_matrices_function(const Model& model, TruthNames& names, const std::string& function_name,
                                            const std::vector<std::pair<std::string, ExMatrix>>& parts) {
  return matrices_function_with(model, names, function_name, parts, true);
}

bool depends_on_time(const Model& model, const ExMatrix& m) {
  for (const auto& row : m)
    for (const auto& e : row)
      if (e.has(model.time)) return true;
  return false;
}

}  // namespace pfgen::codegen
