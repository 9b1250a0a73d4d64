#include "pfgen/printing/coefficient_report.hpp"

#include "pfgen/notation/latex_line_breaker.hpp"
#include "pfgen/notation/latex_printer.hpp"
#include "pfgen/notation/text_printer.hpp"
#include "pfgen/printing/latex_matrix.hpp"
#include "pfgen/printing/observation_report.hpp"

namespace pfgen {
namespace {

// ---- text ----

std::string text_vector(const TextPrinter& printer, const ExVector& v) {
  std::string out = "[";
  for (std::size_t k = 0; k < v.size(); ++k) out += (k ? ", " : "") + printer.print(v[k]);
  return out + "]";
}

std::string text_matrix(const TextPrinter& printer, const ExMatrix& m) {
  std::string out = "[";
  for (std::size_t k = 0; k < m.size(); ++k) out += (k ? ", " : "") + text_vector(printer, m[k]);
  return out + "]";
}

std::string text_index(const std::vector<std::uint32_t>& index) {
  std::string out;
  for (std::uint32_t k : index) out += "[" + std::to_string(k + 1) + "]";
  return out;
}

std::string text_tensor(const TextPrinter& printer, const std::string& name, const TensorEntries& tensor) {
  if (tensor.empty()) return name + ": every entry 0\n";
  std::string out;
  for (const auto& [index, value] : tensor) out += name + text_index(index) + " = " + printer.print(value) + "\n";
  return out;
}

// ---- LaTeX ----

std::string latex_index(const std::vector<std::uint32_t>& index) {
  std::string out;
  for (std::size_t k = 0; k < index.size(); ++k) out += (k ? "," : "") + std::to_string(index[k] + 1);
  return out;
}

void latex_tensor(const LatexPrinter& printer, const std::string& name, const TensorEntries& tensor,
                  std::vector<std::string>& lines) {
  if (tensor.empty()) {
    lines.push_back(name + " &= 0");
    return;
  }
  for (const auto& [index, value] : tensor)
    lines.push_back(latex_align_lines("(" + name + ")_{" + latex_index(index) + "}", printer.print(value)));
}

// ---- JSON ----

Json json_vector(const TextPrinter& printer, const ExVector& v) {
  Json out = Json::array();
  for (const auto& e : v) out.push(Json::string(printer.print(e)));
  return out;
}

Json json_matrix(const TextPrinter& printer, const ExMatrix& m) {
  Json out = Json::array();
  for (const auto& row : m) out.push(json_vector(printer, row));
  return out;
}

Json json_tensor(const TextPrinter& printer, const TensorEntries& tensor) {
  Json out = Json::array();
  for (const auto& [index, value] : tensor) {
    Json indices = Json::array();
    for (std::uint32_t k : index) indices.push(Json::integer(k + 1));
    Json entry = Json::object();
    entry.add("index", indices);
    entry.add("value", Json::string(printer.print(value)));
    out.push(entry);
  }
  return out;
}

const char* kConvention =
    "f_i(x,t) = A_i + sum_j A1_ij x_j + sum_jk A2_ijk x_j x_k + sum_jkl A3_ijkl x_j x_k x_l; A2 and A3 symmetric "
    "in their lower indices: A2_ijk = 1/2 d2f_i/dx_j dx_k, A3_ijkl = 1/6 d3f_i/dx_j dx_k dx_l, at x = 0";

}  // namespace

std::string coefficients_text(const Model& model, const DriftCoefficients& drift,
                              const ObservationCoefficients& observation) {
  TextPrinter printer;
  const ObservationStatement& report = observation_statement(model.observation);
  const CoefficientNames names = report.coefficient_names();
  std::string out = "model: " + model.name + "\n";
  out += std::string("coefficient form: ") + kConvention + "\n";
  out += "indices from 1, x = (";
  for (std::size_t i = 0; i < model.n(); ++i) out += (i ? ", " : "") + model.state_names[i];
  out += "); A2 and A3 list every nonzero entry, each order of the lower indices\n";
  out += report.coefficients_text(model) + "\n";
  out += "A = " + text_vector(printer, drift.A) + "\n";
  out += "A1 = " + text_matrix(printer, drift.A1) + "\n";
  out += text_tensor(printer, "A2", drift.A2);
  out += text_tensor(printer, "A3", drift.A3);
  out += names.offset + " = " + text_vector(printer, observation.E) + "\n";
  out += names.matrix + " = " + text_matrix(printer, observation.E1) + "\n";
  return out;
}

std::string coefficients_latex(const Model& model, const DriftCoefficients& drift,
                               const ObservationCoefficients& observation) {
  LatexPrinter printer;
  const ObservationStatement& report = observation_statement(model.observation);
  const CoefficientNames names = report.coefficient_names();
  std::string out =
      "\\paragraph{Coefficient form.} $f_{i}(x,t) = A_{i} + \\sum_{j} (A_{1})_{ij} x_{j} + \\sum_{j,k} (A_{2})_{ijk} "
      "x_{j} x_{k} + \\sum_{j,k,l} (A_{3})_{ijkl} x_{j} x_{k} x_{l}$ with $x = (";
  for (std::size_t i = 0; i < model.n(); ++i) out += (i ? ", " : "") + printer.name(model.state_names[i]);
  out += ")$; $A_{2}$ and $A_{3}$ are symmetric in their lower indices, $(A_{2})_{ijk} = \\frac{1}{2}\\,"
         "\\partial^{2} f_{i}/\\partial x_{j} \\partial x_{k}$ and $(A_{3})_{ijkl} = \\frac{1}{6}\\,\\partial^{3} "
         "f_{i}/\\partial x_{j} \\partial x_{k} \\partial x_{l}$ at $x = 0$, and every nonzero entry is listed, "
         "each order of the lower indices. " +
         report.coefficients_latex(model) + "\n";
  std::vector<std::string> lines;
  lines.push_back(matrix_lines(printer, "A", "A", column(drift.A)));
  lines.push_back(matrix_lines(printer, "A_{1}", "(A_{1})", drift.A1));
  latex_tensor(printer, "A_{2}", drift.A2, lines);
  latex_tensor(printer, "A_{3}", drift.A3, lines);
  lines.push_back(matrix_lines(printer, names.offset_latex, names.offset_latex, column(observation.E)));
  lines.push_back(matrix_lines(printer, names.matrix_latex, names.entries_latex, observation.E1));
  out += "\\begin{align*}\n";
  for (std::size_t k = 0; k < lines.size(); ++k) out += lines[k] + (k + 1 < lines.size() ? " \\\\\n" : "\n");
  out += "\\end{align*}\n";
  return out;
}

Json coefficients_json(const Model& model, const DriftCoefficients& drift, const ObservationCoefficients& observation) {
  TextPrinter printer;
  const ObservationStatement& report = observation_statement(model.observation);
  const CoefficientNames names = report.coefficient_names();
  Json states = Json::array();
  for (const auto& name : model.state_names) states.push(Json::string(name));
  Json obs = Json::object();
  obs.add("kind", Json::string(observation_kind_info(observation.kind).name));
  report.add_coefficients_json(model, obs);
  obs.add(names.offset, json_vector(printer, observation.E));
  obs.add(names.matrix, json_matrix(printer, observation.E1));

  Json out = Json::object();
  out.add("model", Json::string(model.name));
  out.add("convention", Json::string(kConvention));
  out.add("index_base", Json::integer(1));
  out.add("states", states);
  out.add("A", json_vector(printer, drift.A));
  out.add("A1", json_matrix(printer, drift.A1));
  out.add("A2", json_tensor(printer, drift.A2));
  out.add("A3", json_tensor(printer, drift.A3));
  out.add("observation", obs);
  return out;
}

}  // namespace pfgen
